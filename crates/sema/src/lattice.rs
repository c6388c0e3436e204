//! The implicit-conversion lattice of the elementary types, and the typing
//! rules of automat built on it (this comment is their reference; tests pin
//! every rule).
//!
//! # Implicit conversions (IEC 61131-3 3rd edition, widening only)
//! - `SINT → INT → DINT → LINT` and `USINT → UINT → UDINT → ULINT`;
//! - an unsigned type to every strictly wider signed type (`USINT → INT`,
//!   `UINT → DINT`, `UDINT → LINT`, and transitively `USINT → DINT`, ...);
//! - integers of at most 16 bits → `REAL` and `LREAL`; 32-bit integers →
//!   `LREAL` (exact); 64-bit integers convert to no real;
//! - `REAL → LREAL`;
//! - `BYTE → WORD → DWORD → LWORD` (BOOL converts to nothing);
//! - `TIME → LTIME`, `DATE → LDATE`, `TOD → LTOD`, `DT → LDT`;
//! - `STRING[n] → STRING[m]` and `WSTRING[n] → WSTRING[m]` for any n, m
//!   (assignment truncates, which is defined behaviour); no char ↔ string;
//! - a subrange converts to its base type (and on to what the base converts
//!   to); the base converts to the subrange, and a constant is checked
//!   against the limits (E038);
//! - an enumeration converts only to itself; arrays, structures, function
//!   block types and references only to the identical type.
//!
//! Everything else needs an explicit conversion function (`DINT_TO_INT`).
//!
//! # Untyped literals
//! An integer literal (or a constant expression made only of untyped
//! literals, folded: `2 * 100`) fits every integer, bit-string or real type
//! whose range holds its value; 0 and 1 also fit BOOL. A real literal fits
//! REAL (when in range) and LREAL. A string literal fits STRING or WSTRING by
//! its quotes, and a one-character one fits CHAR / WCHAR. Typed literals
//! (`INT#5`, `T#1s`) have their type.
//!
//! # Operators ([`crate::ops`])
//! - Operands are widened to their least upper bound in this lattice ([`lub`]);
//!   an untyped literal operand first adapts to the other operand's type, or
//!   to the narrowest wider type of the same family that holds it
//!   (`int_var + 100000` is DINT), else to its natural type (the narrowest
//!   signed integer, LREAL for reals) before the upper bound is taken; a real
//!   literal with an integer operand gives REAL if the integer converts to
//!   REAL, else LREAL. No upper bound → E031 naming the operator and both types.
//! - `+ - * /` on ANY_NUM; `MOD` on ANY_INT; `**`: ANY_NUM exponent, result
//!   the base's type when the base is real, else REAL for integers of ≤ 16
//!   bits and LREAL for wider ones (two untyped integers give an untyped real).
//! - `AND OR XOR NOT` on BOOL and ANY_BIT, and on integers (as CODESYS and
//!   TwinCAT accept, bitwise).
//! - Comparisons on numbers, bit strings, durations, dates, strings, chars and
//!   values of one enumeration → BOOL.
//! - Time arithmetic (the standard's ADD_TIME family, long variants alike):
//!   `TIME ± TIME → TIME`, `TIME * ANY_NUM → TIME` (either order),
//!   `TIME / ANY_NUM → TIME`, `DT ± TIME → DT`, `DT − DT → TIME`,
//!   `TOD ± TIME → TOD`, `TOD − TOD → TIME`, `DATE − DATE → TIME`. Mixing a
//!   short and a long operand widens to the long variant.
//! - Unary minus on signed integers, reals and durations; unary plus on
//!   numbers and durations.
//!
//! # Statements ([`crate::body`])
//! - `a := e` needs `e` implicitly convertible to `a`'s type (E030, naming
//!   both types, or the value and the type for a literal that does not fit).
//! - IF/ELSIF/WHILE/REPEAT conditions are BOOL (E032).
//! - FOR: the control variable is an integer variable of the POU; start,
//!   end and step convert to its type; a constant step is not zero (E062).
//! - CASE: the selector is an integer, enumeration or bit string; labels are
//!   constants of that type (E033), ranges `lo..hi` with `lo ≤ hi`.
//! - Bit access `v.n` / `v.%Xn` on ANY_BIT and integers with `n` below the
//!   width (E037), giving BOOL; `%B`, `%W`, `%D` partial access gives BYTE,
//!   WORD, DWORD.

use crate::types::Elem;
use std::sync::OnceLock;

/// Whether a value of `from` converts implicitly to `to` (reflexive).
pub fn implicit(from: Elem, to: Elem) -> bool {
    use Elem::*;
    if from == to {
        return true;
    }
    let (fb, tb) = (from.bits(), to.bits());
    match (from, to) {
        _ if from.is_signed() && to.is_signed() => tb > fb,
        _ if from.is_unsigned() && to.is_unsigned() => tb > fb,
        _ if from.is_unsigned() && to.is_signed() => tb > fb,
        _ if from.is_int() && to == Real => fb <= 16,
        _ if from.is_int() && to == Lreal => fb <= 32,
        (Real, Lreal) => true,
        _ if from.is_bit() && from != Bool && to.is_bit() && to != Bool => tb > fb,
        (Time, Ltime) | (Date, Ldate) | (Tod, Ltod) | (Dt, Ldt) => true,
        _ => false,
    }
}

/// The least upper bound of two elementary types: the narrowest type both
/// convert to implicitly, if any (for two integers, the narrowest integer).
pub fn lub(a: Elem, b: Elem) -> Option<Elem> {
    let table = LUB.get_or_init(build_lub);
    table[a as usize][b as usize]
}

static LUB: OnceLock<[[Option<Elem>; 25]; 25]> = OnceLock::new();

fn build_lub() -> [[Option<Elem>; 25]; 25] {
    let mut t = [[None; 25]; 25];
    for a in Elem::ALL {
        for b in Elem::ALL {
            let mut uppers: Vec<Elem> = Elem::ALL
                .iter()
                .copied()
                .filter(|&c| implicit(a, c) && implicit(b, c))
                .collect();
            // Two integers meet in an integer when one exists (INT ⊔ UINT is
            // DINT, although REAL also bounds both and DINT ⋢ REAL).
            if a.is_int() && b.is_int() && uppers.iter().any(|c| c.is_int()) {
                uppers.retain(|c| c.is_int());
            }
            // The least one converts to every other upper bound.
            t[a as usize][b as usize] = uppers
                .iter()
                .copied()
                .find(|&u| uppers.iter().all(|&v| implicit(u, v)));
        }
    }
    t
}

/// The types an untyped literal may take when it meets an operand of type
/// `e`, narrowest first: `e` and its wider types of the same family.
pub fn literal_chain(e: Elem) -> &'static [Elem] {
    use Elem::*;
    const S: [Elem; 4] = [Sint, Int, Dint, Lint];
    const U: [Elem; 4] = [Usint, Uint, Udint, Ulint];
    const B: [Elem; 4] = [Byte, Word, Dword, Lword];
    const R: [Elem; 2] = [Real, Lreal];
    match e {
        Sint => &S,
        Int => &S[1..],
        Dint => &S[2..],
        Lint => &S[3..],
        Usint => &U,
        Uint => &U[1..],
        Udint => &U[2..],
        Ulint => &U[3..],
        Byte => &B,
        Word => &B[1..],
        Dword => &B[2..],
        Lword => &B[3..],
        Real => &R,
        Lreal => &R[1..],
        Bool => &[Bool],
        _ => &[],
    }
}

/// Whether an integer value fits a type (integers, bit strings, BOOL: by
/// range; reals: always, as the nearest real).
pub fn int_fits(v: i128, e: Elem) -> bool {
    if e.is_real() {
        return true;
    }
    match e.int_range() {
        Some((lo, hi)) => v >= lo && v <= hi,
        None => false,
    }
}

/// Whether a real value fits a real type (REAL is bounded by `f32::MAX`).
pub fn real_fits(v: f64, e: Elem) -> bool {
    match e {
        Elem::Lreal => true,
        Elem::Real => !v.is_finite() || v.abs() <= f32::MAX as f64,
        _ => false,
    }
}

/// The natural type of an untyped integer: the narrowest signed integer
/// holding it, else ULINT.
pub fn natural_int(v: i128) -> Option<Elem> {
    [Elem::Sint, Elem::Int, Elem::Dint, Elem::Lint, Elem::Ulint]
        .into_iter()
        .find(|&e| int_fits(v, e))
}

/// The long variant of a time or date type (itself if already long).
pub fn long_of(e: Elem) -> Elem {
    match e {
        Elem::Time => Elem::Ltime,
        Elem::Date => Elem::Ldate,
        Elem::Tod => Elem::Ltod,
        Elem::Dt => Elem::Ldt,
        other => other,
    }
}

#[cfg(test)]
mod tests;
