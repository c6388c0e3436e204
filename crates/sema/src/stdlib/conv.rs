//! Type conversion functions, recognised by their names rather than listed:
//! `<T1>_TO_<T2>`, `TO_<T>`, `TRUNC_<INT>`, `<REAL>_TRUNC_<INT>`,
//! `BCD_TO_<INT>`, `<BIT>_BCD_TO_<INT>`, `<INT>_TO_BCD`, `<INT>_TO_BCD_<BIT>`.
//!
//! Allowed pairs (the standard's table, with the vendor extensions that
//! CODESYS and TwinCAT code relies on): numeric ↔ numeric, numeric ↔ bit
//! string, BOOL ↔ numeric and bit strings, durations ↔ numeric and bit
//! strings, date types among themselves and ↔ integers and bit strings,
//! CHAR/WCHAR ↔ integers, bit strings and each other, every elementary type
//! ↔ STRING/WSTRING, STRING ↔ WSTRING. Not: real ↔ date or char, duration ↔
//! date or char, date ↔ char.

use super::{Kind, PDir, PTy, Param, RTy, Sig, StdOp};
use crate::types::Elem;

/// A type that conversion functions name.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ConvTy {
    Elem(Elem),
    /// STRING (false) or WSTRING (true).
    Str(bool),
}

impl ConvTy {
    fn parse(s: &str) -> Option<ConvTy> {
        if s == "STRING" {
            return Some(ConvTy::Str(false));
        }
        if s == "WSTRING" {
            return Some(ConvTy::Str(true));
        }
        Elem::from_name(s).map(ConvTy::Elem)
    }

    fn pty(self) -> PTy {
        match self {
            ConvTy::Elem(e) => PTy::Elem(e),
            ConvTy::Str(w) => PTy::Str(w),
        }
    }

    fn rty(self) -> RTy {
        match self {
            ConvTy::Elem(e) => RTy::Elem(e),
            ConvTy::Str(w) => RTy::Str(w),
        }
    }
}

/// Whether `<from>_TO_<to>` exists.
pub fn allowed(from: ConvTy, to: ConvTy) -> bool {
    match (from, to) {
        (ConvTy::Str(_), _) | (_, ConvTy::Str(_)) => true,
        (ConvTy::Elem(a), ConvTy::Elem(b)) => elem_allowed(a, b) && elem_allowed(b, a),
    }
}

/// One direction of the (symmetric) relation.
fn elem_allowed(a: Elem, b: Elem) -> bool {
    let numeric_like = |e: Elem| e.is_num() || e.is_bit();
    let integral = |e: Elem| e.is_int() || e.is_bit();
    if numeric_like(a) {
        return numeric_like(b)
            || b.is_duration()
            || (b.is_date() && integral(a))
            || (b.is_char() && integral(a));
    }
    if a.is_duration() {
        return b.is_duration() || numeric_like(b);
    }
    if a.is_date() {
        return b.is_date() || integral(b);
    }
    if a.is_char() {
        return b.is_char() || integral(b);
    }
    false
}

fn one(name: &str, op: StdOp, input: PTy, ret: RTy) -> Sig {
    Sig {
        name: name.to_string(),
        op,
        params: vec![Param {
            name: "IN",
            ty: input,
            dir: PDir::In,
        }],
        ext: None,
        ret,
    }
}

/// The bit string of an integer's width (the result of `<INT>_TO_BCD`).
fn bits_of(e: Elem) -> Option<Elem> {
    Some(match e.bits() {
        8 => Elem::Byte,
        16 => Elem::Word,
        32 => Elem::Dword,
        64 => Elem::Lword,
        _ => return None,
    })
}

fn int_elem(s: &str) -> Option<Elem> {
    Elem::from_name(s).filter(|e| e.is_int())
}

/// A conversion function by its upper-case name.
pub(super) fn conversion(n: &str) -> Option<Sig> {
    if let Some(t) = n.strip_prefix("TO_") {
        if let Some(to) = ConvTy::parse(t) {
            return Some(one(
                n,
                StdOp::ToType(to),
                PTy::Free(Kind::AnyElementary),
                to.rty(),
            ));
        }
    }
    if let Some(t) = n.strip_prefix("TRUNC_") {
        let to = int_elem(t)?;
        return Some(one(
            n,
            StdOp::Trunc(to),
            PTy::Free(Kind::AnyReal),
            RTy::Elem(to),
        ));
    }
    if let Some((from, to)) = n.split_once("_TRUNC_") {
        let from = Elem::from_name(from).filter(|e| e.is_real())?;
        let to = int_elem(to)?;
        return Some(one(n, StdOp::Trunc(to), PTy::Elem(from), RTy::Elem(to)));
    }
    if let Some(t) = n.strip_prefix("BCD_TO_") {
        let to = int_elem(t)?;
        return Some(one(
            n,
            StdOp::BcdToInt(to),
            PTy::Free(Kind::AnyBit),
            RTy::Elem(to),
        ));
    }
    if let Some((from, to)) = n.split_once("_BCD_TO_") {
        let from = Elem::from_name(from).filter(|e| e.is_bit() && *e != Elem::Bool)?;
        let to = int_elem(to)?;
        return Some(one(n, StdOp::BcdToInt(to), PTy::Elem(from), RTy::Elem(to)));
    }
    if let Some(f) = n.strip_suffix("_TO_BCD") {
        let from = int_elem(f)?;
        let to = bits_of(from)?;
        return Some(one(n, StdOp::IntToBcd(to), PTy::Elem(from), RTy::Elem(to)));
    }
    if let Some((from, to)) = n.split_once("_TO_BCD_") {
        let from = int_elem(from)?;
        let to = Elem::from_name(to).filter(|e| e.is_bit() && *e != Elem::Bool)?;
        return Some(one(n, StdOp::IntToBcd(to), PTy::Elem(from), RTy::Elem(to)));
    }
    // `<T1>_TO_<T2>`: type names contain underscores (TIME_OF_DAY), so try every split.
    let mut start = 0;
    while let Some(i) = n.get(start..).and_then(|s| s.find("_TO_")) {
        let at = start + i;
        let (l, r) = (n.get(..at)?, n.get(at + 4..)?);
        if let (Some(from), Some(to)) = (ConvTy::parse(l), ConvTy::parse(r)) {
            if !allowed(from, to) {
                return None;
            }
            return Some(one(n, StdOp::Convert { from, to }, from.pty(), to.rty()));
        }
        start = at + 1;
    }
    None
}
