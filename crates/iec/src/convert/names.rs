//! Recognising conversion function names: `INT_TO_REAL`, `TO_REAL`,
//! `DATE_AND_TIME_TO_TIME_OF_DAY`, `TRUNC`, `REAL_TRUNC_DINT`, `BCD_TO_INT`,
//! `WORD_BCD_TO_UINT`, `INT_TO_BCD`, `UINT_TO_BCD_WORD`. Case-insensitive.

use crate::elementary::Elementary as E;

/// A conversion function, as named in source. `None` types come from the
/// argument (overloaded forms).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Conversion {
    /// `<from>_TO_<to>` or `TO_<to>`: [`super::convert`].
    Plain { from: Option<E>, to: E },
    /// `TRUNC`, `TRUNC_<to>`, `<from>_TRUNC_<to>`: [`super::trunc`].
    Trunc { from: Option<E>, to: Option<E> },
    /// `BCD_TO_<to>`, `<from>_BCD_TO_<to>`: [`super::from_bcd`].
    FromBcd { from: Option<E>, to: E },
    /// `<from>_TO_BCD`, `<from>_TO_BCD_<to>`: [`super::to_bcd`].
    ToBcd { from: E, to: Option<E> },
}

/// The conversion `name` calls, if it names one of a defined pair.
pub fn conversion_by_name(name: &str) -> Option<Conversion> {
    let up = name.to_ascii_uppercase();
    let ty = E::from_name;
    if up == "TRUNC" {
        return Some(Conversion::Trunc {
            from: None,
            to: None,
        });
    }
    if let Some(to) = up.strip_prefix("TRUNC_").and_then(ty) {
        return to.is_int().then_some(Conversion::Trunc {
            from: None,
            to: Some(to),
        });
    }
    if let Some(to) = up.strip_prefix("BCD_TO_").and_then(ty) {
        return to
            .is_int()
            .then_some(Conversion::FromBcd { from: None, to });
    }
    if let Some(from) = up.strip_suffix("_TO_BCD").and_then(ty) {
        return from
            .is_int()
            .then_some(Conversion::ToBcd { from, to: None });
    }
    if let Some(to) = up.strip_prefix("TO_").and_then(ty) {
        return Some(Conversion::Plain { from: None, to });
    }
    if let Some((from, to)) = split_types(&up, "_BCD_TO_") {
        return (from.is_bit_string() && to.is_int()).then_some(Conversion::FromBcd {
            from: Some(from),
            to,
        });
    }
    if let Some((from, to)) = split_types(&up, "_TO_BCD_") {
        return (from.is_int() && to.is_bit_string())
            .then_some(Conversion::ToBcd { from, to: Some(to) });
    }
    if let Some((from, to)) = split_types(&up, "_TRUNC_") {
        return (from.is_real() && to.is_int()).then_some(Conversion::Trunc {
            from: Some(from),
            to: Some(to),
        });
    }
    let (from, to) = split_types(&up, "_TO_")?;
    super::is_convertible(from, to).then_some(Conversion::Plain {
        from: Some(from),
        to,
    })
}

/// `A<sep>B` where A and B both name types; every occurrence of `sep` is
/// tried, since a type name may itself contain `_` (`DATE_AND_TIME`).
fn split_types(up: &str, sep: &str) -> Option<(E, E)> {
    up.match_indices(sep).find_map(|(i, _)| {
        let from = E::from_name(up.get(..i)?)?;
        let to = E::from_name(up.get(i + sep.len()..)?)?;
        Some((from, to))
    })
}
