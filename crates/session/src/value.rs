//! Text → the bytes a write or a force stores at a place.
//!
//! Values are written as the `--print` literals read them back (`TRUE`,
//! `42`, `T#3s`, `'abc'`, `Color#Red`); a BOOL also takes `1`/`0`, an
//! enumeration its value name alone or its number, and a typed prefix
//! (`INT#5`) must name the target's type. Every error names the type that
//! was expected. A STRING longer than the variable's capacity is refused
//! rather than truncated: a value a user typed is stored as typed or not
//! at all.

use automat_iec::{parse_literal, Elementary as E, Value};
use automat_runtime::{Place, PlaceType};

/// What a write or force stores: one bit of a byte, or a byte range.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Stored {
    Bit { offset: usize, bit: u8, value: bool },
    Bytes { offset: usize, bytes: Vec<u8> },
}

impl Stored {
    /// Stores the value in `image`; a place outside the image is left
    /// alone (places are checked against the image size when resolved).
    pub fn apply(&self, image: &mut [u8]) {
        match self {
            Stored::Bit { offset, bit, value } => {
                if let Some(b) = image.get_mut(*offset) {
                    if *value {
                        *b |= 1 << (bit & 7);
                    } else {
                        *b &= !(1 << (bit & 7));
                    }
                }
            }
            Stored::Bytes { offset, bytes } => {
                if let Some(dst) = offset
                    .checked_add(bytes.len())
                    .and_then(|end| image.get_mut(*offset..end))
                {
                    dst.copy_from_slice(bytes);
                }
            }
        }
    }

    /// The first byte and the bit (if any) it occupies: two forces of the
    /// same location (by two names) are one force.
    pub fn key(&self) -> (usize, Option<u8>) {
        match self {
            Stored::Bit { offset, bit, .. } => (*offset, Some(*bit)),
            Stored::Bytes { offset, .. } => (*offset, None),
        }
    }
}

/// The IEC type name of a place, as error messages and the symbol tree
/// show it (`BOOL`, `STRING[20]`, `COLOR`).
pub fn type_name(ty: &PlaceType) -> String {
    match ty {
        PlaceType::Elementary(e) => e.name().to_string(),
        PlaceType::String { cap } => format!("STRING[{cap}]"),
        PlaceType::WString { cap } => format!("WSTRING[{cap}]"),
        PlaceType::Enum { name, .. } => name.clone(),
    }
}

/// Integer bounds a value must keep (a subrange's), when narrower than
/// its base type's.
pub type Bounds = Option<(i64, i64)>;

/// Parses `text` for `place` into what to store.
pub fn encode(place: &Place, text: &str, bounds: Bounds) -> Result<Stored, String> {
    let offset = usize::try_from(place.offset).map_err(|_| "offset out of range".to_string())?;
    let expected = type_name(&place.ty);
    let err = |why: String| format!("expected a value of type {expected}: {why}");
    let value = match &place.ty {
        PlaceType::Enum { name, base, values } => {
            let t = text.trim();
            let bare = match t.split_once('#') {
                Some((p, v)) if p.eq_ignore_ascii_case(name) => v,
                Some((p, _)) if !p.chars().all(|c| c.is_ascii_digit()) => {
                    return Err(err(format!("`{p}#` does not name the enumeration {name}")));
                }
                _ => t,
            };
            let n = match values.iter().find(|(v, _)| v.eq_ignore_ascii_case(bare)) {
                Some((_, n)) => *n,
                None => {
                    let names: Vec<&str> = values.iter().map(|(v, _)| v.as_str()).collect();
                    return Err(err(format!("`{t}` is not one of {}", names.join(", "))));
                }
            };
            Value::Int(i128::from(n), *base)
        }
        PlaceType::Elementary(e) => parse_literal(text, *e).map_err(|e| err(e.to_string()))?,
        PlaceType::String { .. } => {
            parse_literal(text, E::String).map_err(|e| err(e.to_string()))?
        }
        PlaceType::WString { .. } => {
            parse_literal(text, E::Wstring).map_err(|e| err(e.to_string()))?
        }
    };
    if let (Some((lo, hi)), Value::Int(n, _)) = (bounds, &value) {
        if *n < i128::from(lo) || *n > i128::from(hi) {
            return Err(err(format!("{n} is outside the subrange {lo}..{hi}")));
        }
    }
    let bytes = match (&place.ty, value) {
        (_, Value::Bool(b)) => {
            return Ok(match place.bit {
                Some(bit) => Stored::Bit {
                    offset,
                    bit,
                    value: b,
                },
                None => Stored::Bytes {
                    offset,
                    bytes: vec![u8::from(b)],
                },
            })
        }
        (PlaceType::String { cap }, Value::Str(s)) => {
            let cap = usize::try_from(*cap).unwrap_or(0);
            if s.len() > cap {
                return Err(err(format!(
                    "the text has {} characters, more than {cap}",
                    s.len()
                )));
            }
            let mut out = u16::try_from(s.len()).unwrap_or(0).to_le_bytes().to_vec();
            out.extend_from_slice(&s);
            out
        }
        (PlaceType::WString { cap }, Value::WStr(s)) => {
            let cap = usize::try_from(*cap).unwrap_or(0);
            if s.len() > cap {
                return Err(err(format!(
                    "the text has {} characters, more than {cap}",
                    s.len()
                )));
            }
            let mut out = u16::try_from(s.len()).unwrap_or(0).to_le_bytes().to_vec();
            for u in s {
                out.extend_from_slice(&u.to_le_bytes());
            }
            out
        }
        (_, Value::Int(n, t)) => {
            let width = t.bit_width().map_or(8, |w| w.div_ceil(8)) as usize;
            n.to_le_bytes().get(..width).unwrap_or(&[]).to_vec()
        }
        (_, Value::Real(r, t)) => match t {
            E::Real => (r as f32).to_le_bytes().to_vec(),
            _ => r.to_le_bytes().to_vec(),
        },
        (_, Value::Duration(n, _) | Value::Date(n, _) | Value::Tod(n, _) | Value::Dt(n, _)) => {
            n.to_le_bytes().to_vec()
        }
        (_, Value::Char(c)) => vec![c],
        (_, Value::WChar(c)) => c.to_le_bytes().to_vec(),
        (_, Value::Str(_) | Value::WStr(_)) => {
            return Err(err("a string does not fit this variable".into()))
        }
    };
    Ok(Stored::Bytes { offset, bytes })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn el(e: E, bit: Option<u8>) -> Place {
        Place {
            offset: 2,
            bit,
            ty: PlaceType::Elementary(e),
            slc_bit: false,
        }
    }

    #[test]
    fn booleans_take_true_false_one_and_zero() {
        for (text, v) in [("TRUE", true), ("false", false), ("1", true), ("0", false)] {
            assert_eq!(
                encode(&el(E::Bool, Some(3)), text, None),
                Ok(Stored::Bit {
                    offset: 2,
                    bit: 3,
                    value: v
                })
            );
        }
        assert_eq!(
            encode(&el(E::Bool, None), "1", None),
            Ok(Stored::Bytes {
                offset: 2,
                bytes: vec![1]
            })
        );
        let e = encode(&el(E::Bool, None), "2", None).unwrap_err();
        assert!(e.starts_with("expected a value of type BOOL: "), "{e}");
    }

    #[test]
    fn numbers_times_and_strings_are_stored_little_endian() {
        let bytes = |p: &Place, t: &str| match encode(p, t, None) {
            Ok(Stored::Bytes { bytes, .. }) => bytes,
            other => panic!("{other:?}"),
        };
        assert_eq!(bytes(&el(E::Int, None), "-2"), vec![0xFE, 0xFF]);
        assert_eq!(bytes(&el(E::Real, None), "1.5"), 1.5f32.to_le_bytes());
        assert_eq!(
            bytes(&el(E::Time, None), "T#3s"),
            3_000_000_000i64.to_le_bytes()
        );
        let s = Place {
            offset: 0,
            bit: None,
            ty: PlaceType::String { cap: 4 },
            slc_bit: false,
        };
        assert_eq!(bytes(&s, "'ab'"), vec![2, 0, b'a', b'b']);
        let e = encode(&s, "'abcde'", None).unwrap_err();
        assert_eq!(
            e,
            "expected a value of type STRING[4]: the text has 5 characters, more than 4"
        );
        let e = encode(&el(E::Int, None), "70000", None).unwrap_err();
        assert!(e.starts_with("expected a value of type INT: "), "{e}");
        let e = encode(&el(E::Int, None), "7", Some((0, 5))).unwrap_err();
        assert_eq!(
            e,
            "expected a value of type INT: 7 is outside the subrange 0..5"
        );
    }

    #[test]
    fn enumerations_take_names_with_or_without_their_type() {
        let p = Place {
            offset: 0,
            bit: None,
            ty: PlaceType::Enum {
                name: "COLOR".into(),
                base: E::Int,
                values: vec![("RED".into(), 0), ("GREEN".into(), 1)],
            },
            slc_bit: false,
        };
        let want = Ok(Stored::Bytes {
            offset: 0,
            bytes: vec![1, 0],
        });
        assert_eq!(encode(&p, "Color#Green", None), want);
        assert_eq!(encode(&p, "green", None), want);
        assert_eq!(
            encode(&p, "BLUE", None).unwrap_err(),
            "expected a value of type COLOR: `BLUE` is not one of RED, GREEN"
        );
    }
}
