//! Checking the values of a loaded RETAIN file against their declared
//! types: a file whose checksum is right may still hold values no program
//! could have stored (written by a tool, a bug or someone on purpose), and
//! the program must never start from them.
//!
//! Rules: a BOOL byte is 0 or 1 (a BOOL in one bit of a byte is always
//! valid), a STRING/WSTRING length is at most its capacity, a subrange
//! value lies within its bounds, an enumeration holds one of its values;
//! arrays, structures and FB instances are checked element by element and
//! field by field. Numbers, times, dates and characters take any bit
//! pattern; a reference is checked by the engine where it is used.

use crate::value::{read_elementary, string_len};
use automat_iec::{Elementary as E, Value};
use automat_ir::{Program, SymbolType};

/// The first retained variable of `program` whose value in `image` is not
/// one of its type, with the reason: `Main.flag holds 55, not a BOOL (0 or 1)`.
pub fn first_invalid(program: &Program, image: &[u8]) -> Option<String> {
    for e in program.symbols.entries().iter().filter(|e| e.retain) {
        let mut shown = e.spelling.clone();
        if let Err(why) = check(image, e.offset, e.bit, &e.ty, &mut shown) {
            return Some(format!("{shown} {why}"));
        }
    }
    None
}

fn int_at(image: &[u8], offset: u32, base: E) -> Result<i128, String> {
    match read_elementary(image, offset, None, base) {
        Some(Value::Int(v, _)) => Ok(v),
        _ => Err("lies outside the memory image".to_string()),
    }
}

/// Checks the value of type `ty` at `offset`; on an error `shown` names the
/// element or field at fault.
fn check(
    image: &[u8],
    offset: u32,
    bit: Option<u8>,
    ty: &SymbolType,
    shown: &mut String,
) -> Result<(), String> {
    let outside = || "lies outside the memory image".to_string();
    match ty {
        SymbolType::Elementary(E::Bool) if bit.is_none() => {
            let at = usize::try_from(offset).map_err(|_| outside())?;
            match image.get(at) {
                Some(0 | 1) => Ok(()),
                Some(b) => Err(format!("holds {b}, not a BOOL (0 or 1)")),
                None => Err(outside()),
            }
        }
        SymbolType::Elementary(e) => read_elementary(image, offset, bit, *e)
            .map(|_| ())
            .ok_or_else(outside),
        SymbolType::String { cap } | SymbolType::WString { cap } => {
            let len = string_len(image, offset).ok_or_else(outside)?;
            if len > *cap {
                let kind = if matches!(ty, SymbolType::String { .. }) {
                    "STRING"
                } else {
                    "WSTRING"
                };
                return Err(format!(
                    "has a length of {len}, longer than its {kind}[{cap}]"
                ));
            }
            Ok(())
        }
        SymbolType::Subrange { base, lo, hi } => {
            let v = int_at(image, offset, *base)?;
            if v < i128::from(*lo) || v > i128::from(*hi) {
                return Err(format!("holds {v}, outside its subrange {lo}..{hi}"));
            }
            Ok(())
        }
        SymbolType::Enum { name, base, values } => {
            let v = int_at(image, offset, *base)?;
            if !values.iter().any(|(_, x)| i128::from(*x) == v) {
                return Err(format!("holds {v}, not a value of {name}"));
            }
            Ok(())
        }
        SymbolType::Array { elem, dims, stride } => {
            check_array(image, offset, elem, dims, *stride, shown)
        }
        SymbolType::Struct { fields, .. } => {
            for f in fields {
                let at = offset.checked_add(f.offset).ok_or_else(outside)?;
                let len = shown.len();
                shown.push('.');
                shown.push_str(&f.name);
                check(image, at, f.bit, &f.ty, shown)?;
                shown.truncate(len);
            }
            Ok(())
        }
        SymbolType::Ref(_) => Ok(()),
    }
}

/// Every element of an array, in memory order; `shown` gets the indexes of
/// the element at fault (`[2, 1]`).
fn check_array(
    image: &[u8],
    offset: u32,
    elem: &SymbolType,
    dims: &[(i64, i64)],
    stride: u32,
    shown: &mut String,
) -> Result<(), String> {
    let extents: Vec<u64> = dims
        .iter()
        .map(|(lo, hi)| u64::try_from(i128::from(*hi) - i128::from(*lo) + 1).unwrap_or(0))
        .collect();
    let count = extents
        .iter()
        .try_fold(1u64, |n, e| n.checked_mul(*e))
        .ok_or_else(|| "has more elements than the memory image".to_string())?;
    // Elements of no size all lie at one place: one check says it all.
    let count = if stride == 0 { count.min(1) } else { count };
    for k in 0..count {
        let at = u64::from(offset)
            .checked_add(k.saturating_mul(u64::from(stride)))
            .and_then(|a| u32::try_from(a).ok())
            .ok_or_else(|| "lies outside the memory image".to_string())?;
        // The element's name is only spelled out when it is at fault.
        let mut inner = String::new();
        if let Err(why) = check(image, at, None, elem, &mut inner) {
            shown.push_str(&index_text(k, dims, &extents));
            shown.push_str(&inner);
            return Err(why);
        }
    }
    Ok(())
}

/// `[i, j]` of the k-th element in row-major order.
fn index_text(mut k: u64, dims: &[(i64, i64)], extents: &[u64]) -> String {
    let mut ix = vec![0i128; dims.len()];
    for (d, e) in extents.iter().enumerate().rev() {
        let e = (*e).max(1);
        let lo = dims.get(d).map_or(0, |(lo, _)| i128::from(*lo));
        if let Some(slot) = ix.get_mut(d) {
            *slot = lo + i128::from(k % e);
        }
        k /= e;
    }
    let parts: Vec<String> = ix.iter().map(i128::to_string).collect();
    format!("[{}]", parts.join(", "))
}
