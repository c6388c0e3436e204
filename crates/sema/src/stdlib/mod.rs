//! The standard library as the checker sees it.
//!
//! - Standard *functions* are signatures in Rust ([`lookup`]): generic
//!   parameter kinds (ANY_NUM, ...) with the standard's formal names, and a
//!   [`StdOp`] saying which operation a call performs, so the execution stage
//!   can hang its implementation off the same table.
//! - Standard *function blocks* are declared in Structured Text
//!   (`fbs.st`, parsed with the real parser) and become ordinary POUs of the
//!   model marked `builtin`.
//!
//! Invariants: lookup is by name, case-insensitive, and pure; a name that is
//! not a standard function gives `None` (user POUs shadow standard ones).

pub mod conv;
mod table;

use crate::types::Elem;

pub use conv::ConvTy;

/// The ST source of the standard function blocks (and of the hidden blocks
/// SFC charts are rewritten into, `sfc.st`).
pub const FB_SOURCE: &str = concat!(include_str!("fbs.st"), include_str!("sfc.st"));

/// The file id given to the standard library's spans (no file of a project has it).
pub const STD_FILE: automat_base::FileId = automat_base::FileId(u32::MAX);

/// A generic parameter kind of the standard (`ANY_NUM`, ...).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Kind {
    Any,
    AnyElementary,
    AnyMagnitude,
    AnyNum,
    AnyReal,
    AnyInt,
    /// ANY_BIT, BOOL included.
    AnyBit,
    /// ANY_BIT or ANY_INT: the bitwise functions as CODESYS and TwinCAT accept them.
    AnyLogic,
    AnyString,
    AnyDate,
    AnyDuration,
}

impl Kind {
    pub fn name(self) -> &'static str {
        match self {
            Kind::Any => "ANY",
            Kind::AnyElementary => "ANY_ELEMENTARY",
            Kind::AnyMagnitude => "ANY_MAGNITUDE",
            Kind::AnyNum => "ANY_NUM",
            Kind::AnyReal => "ANY_REAL",
            Kind::AnyInt => "ANY_INT",
            Kind::AnyBit => "ANY_BIT",
            Kind::AnyLogic => "ANY_BIT or ANY_INT",
            Kind::AnyString => "ANY_STRING",
            Kind::AnyDate => "ANY_DATE",
            Kind::AnyDuration => "ANY_DURATION",
        }
    }

    /// Whether an elementary type belongs to the kind.
    pub fn has_elem(self, e: Elem) -> bool {
        match self {
            Kind::Any | Kind::AnyElementary => true,
            Kind::AnyMagnitude => e.is_num() || e.is_duration(),
            Kind::AnyNum => e.is_num(),
            Kind::AnyReal => e.is_real(),
            Kind::AnyInt => e.is_int(),
            Kind::AnyBit => e.is_bit(),
            Kind::AnyLogic => e.is_bit() || e.is_int(),
            Kind::AnyString => false,
            Kind::AnyDate => e.is_date(),
            Kind::AnyDuration => e.is_duration(),
        }
    }

    /// Whether strings belong to the kind.
    pub fn has_string(self) -> bool {
        matches!(self, Kind::Any | Kind::AnyElementary | Kind::AnyString)
    }

    /// The narrowest members of the kind, in the order a generic type
    /// widens to them (an INT argument of ANY_REAL becomes REAL).
    pub fn widen_targets(self) -> &'static [Elem] {
        match self {
            Kind::AnyReal => &[Elem::Real, Elem::Lreal],
            _ => &[],
        }
    }
}

/// The type of one parameter of a standard function.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PTy {
    /// The call's generic type `T`, shared by every `Gen` parameter (and the
    /// result when it is [`RTy::Gen`]), of the given kind.
    Gen(Kind),
    /// A generic parameter of its own, not tied to `T`.
    Free(Kind),
    Elem(Elem),
    /// STRING (false) or WSTRING (true) of any length.
    Str(bool),
    /// An array of any type (LOWER_BOUND, UPPER_BOUND).
    Array,
}

/// Parameter direction.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PDir {
    In,
    Out,
    InOut,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Param {
    pub name: &'static str,
    pub ty: PTy,
    pub dir: PDir,
}

/// The result type of a standard function.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RTy {
    /// The generic type `T`.
    Gen,
    Elem(Elem),
    Str(bool),
    /// A reference to the first argument's type (REF, ADR).
    RefToArg,
    /// No return value (SPLIT_DATE, ...): the call is a statement.
    Void,
}

/// Extensible functions (ADD, MAX, MUX, ...): after the fixed parameters
/// come `{prefix}{first}`, `{prefix}{first+1}`, ... (`IN1, IN2, ...`), at
/// least `min` of them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Ext {
    pub prefix: &'static str,
    pub first: u32,
    pub min: u32,
    pub ty: PTy,
}

/// What a standard function call does (the execution stage dispatches on it).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum StdOp {
    /// `<T1>_TO_<T2>`.
    Convert {
        from: ConvTy,
        to: ConvTy,
    },
    /// `TO_<T>` (from any elementary type).
    ToType(ConvTy),
    /// `TRUNC`, `TRUNC_<INT>`, `<REAL>_TRUNC_<INT>`: towards zero.
    Trunc(Elem),
    /// `BCD_TO_<INT>`, `<BIT>_BCD_TO_<INT>`.
    BcdToInt(Elem),
    /// `<INT>_TO_BCD`, `<INT>_TO_BCD_<BIT>`: the result bit string.
    IntToBcd(Elem),
    Abs,
    Sqrt,
    Ln,
    Log,
    Exp,
    Expt,
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan,
    Atan2,
    Add,
    Sub,
    Mul,
    Div,
    Mod,
    Move,
    Shl,
    Shr,
    Rol,
    Ror,
    And,
    Or,
    Xor,
    Not,
    Sel,
    Max,
    Min,
    Limit,
    Mux,
    Gt,
    Ge,
    Eq,
    Le,
    Lt,
    Ne,
    Len,
    Left,
    Right,
    Mid,
    Concat,
    Insert,
    Delete,
    Replace,
    Find,
    ConcatDateTod,
    ConcatDate,
    ConcatTod,
    ConcatDt,
    SplitDate,
    SplitTod,
    SplitDt,
    DayOfWeek,
    LowerBound,
    UpperBound,
    /// `REF(x)`: a reference to a variable.
    Ref,
    /// `ADR(x)`: CODESYS's address-of, typed here as a reference.
    Adr,
    /// `SIZEOF(x)`: the storage size in bytes (UDINT).
    Sizeof,
    /// `__SCAN_TIME()`: the PLC time of the current scan (TIME, ns since
    /// start), for the timer blocks of the standard library.
    ScanTime,
}

/// The signature of one standard function.
#[derive(Clone, Debug, PartialEq)]
pub struct Sig {
    /// The canonical name (upper case).
    pub name: String,
    pub op: StdOp,
    pub params: Vec<Param>,
    pub ext: Option<Ext>,
    pub ret: RTy,
}

impl Sig {
    /// The smallest number of positional arguments.
    pub fn min_args(&self) -> usize {
        self.params.len() + self.ext.map_or(0, |e| e.min as usize)
    }

    /// The largest number of positional arguments (`None`: unbounded).
    pub fn max_args(&self) -> Option<usize> {
        match self.ext {
            Some(_) => None,
            None => Some(self.params.len()),
        }
    }

    /// The parameter at a position.
    pub fn param_at(&self, pos: usize) -> Option<Param> {
        if let Some(p) = self.params.get(pos) {
            return Some(*p);
        }
        let ext = self.ext?;
        Some(Param {
            name: ext.prefix,
            ty: ext.ty,
            dir: PDir::In,
        })
    }

    /// The position of a formal parameter name (`IN`, `IN3`, case-insensitive).
    pub fn position_of(&self, name: &str) -> Option<usize> {
        if let Some(i) = self
            .params
            .iter()
            .position(|p| p.name.eq_ignore_ascii_case(name))
        {
            return Some(i);
        }
        let ext = self.ext?;
        let rest = name
            .get(..ext.prefix.len())
            .filter(|p| p.eq_ignore_ascii_case(ext.prefix))
            .map(|_| &name[ext.prefix.len()..])?;
        if rest.is_empty() || !rest.bytes().all(|b| b.is_ascii_digit()) || rest.len() > 4 {
            return None;
        }
        let n: u32 = rest.parse().ok()?;
        let k = n.checked_sub(ext.first)?;
        Some(self.params.len() + k as usize)
    }

    /// The formal name of the parameter at a position (`IN2` for extensible ones).
    pub fn name_at(&self, pos: usize) -> String {
        match (self.params.get(pos), self.ext) {
            (Some(p), _) => p.name.to_string(),
            (None, Some(e)) => format!(
                "{}{}",
                e.prefix,
                e.first as usize + pos.saturating_sub(self.params.len())
            ),
            (None, None) => String::new(),
        }
    }
}

/// The standard function named `name` (any case).
pub fn lookup(name: &str) -> Option<Sig> {
    if name.len() > 64 || !name.is_ascii() {
        return None;
    }
    let upper = name.to_ascii_uppercase();
    table::fixed(&upper).or_else(|| conv::conversion(&upper))
}

#[cfg(test)]
mod tests;
