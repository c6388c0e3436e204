//! The safe state: what every output is set to when the PLC stops on a
//! fault or a stop request.
//!
//! Covered: the whole %Q area, every VAR_OUTPUT of every program instance
//! (whole arrays and structures included), and any other place the caller
//! adds (the variables a plant's actuators are bound to). Each goes to 0 /
//! FALSE / an empty string — or, for a subrange or an enumeration without
//! 0, its lowest value — unless a safe value is configured for it (a
//! normally-closed valve whose safe state is TRUE); configured values are
//! applied last, so they win over the zeroing.

use crate::path::{Place, PlaceType};
use crate::value::{put_string_len, STRING_LEN_BYTES};
use automat_iec::format::parse_literal;
use automat_iec::{Elementary as E, Value};
use automat_ir::{Program, SymbolType};
use std::ops::Range;

#[derive(Clone, Debug, PartialEq, Eq)]
enum Write {
    Zero(Range<usize>),
    Bytes { at: usize, bytes: Vec<u8> },
    Bit { at: usize, bit: u8, on: bool },
}

/// The writes of the safe state, and what they cover for the message.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct SafeState {
    writes: Vec<Write>,
    /// Bytes of the %Q area.
    q_bytes: usize,
    /// Program outputs and other places set to their zero.
    zeroed: Vec<String>,
    /// Places with a configured safe value, and the value as given.
    configured: Vec<(String, String)>,
}

impl SafeState {
    /// The default safe state of `program`: the %Q area and every program
    /// VAR_OUTPUT to 0/FALSE.
    pub fn of_program(program: &Program) -> SafeState {
        let mut s = SafeState::default();
        let q = &program.areas.output;
        if let (Ok(a), Ok(b)) = (usize::try_from(q.start), usize::try_from(q.end)) {
            if a < b {
                s.q_bytes = b - a;
                s.writes.push(Write::Zero(a..b));
            }
        }
        for e in program.symbols.entries().iter().filter(|e| e.output) {
            zero(&mut s.writes, e.offset, e.bit, &e.ty);
            s.zeroed.push(e.spelling.clone());
        }
        s
    }

    /// Also sets `place` (named `name` in the message) to its zero, unless
    /// it is already covered.
    pub fn add_zero(&mut self, name: &str, place: &Place) {
        if self.zeroed.iter().any(|z| z.eq_ignore_ascii_case(name)) {
            return;
        }
        let ty = match &place.ty {
            PlaceType::Elementary(e) => SymbolType::Elementary(*e),
            PlaceType::String { cap } => SymbolType::String { cap: *cap },
            PlaceType::WString { cap } => SymbolType::WString { cap: *cap },
            PlaceType::Enum { name, base, values } => SymbolType::Enum {
                name: name.clone(),
                base: *base,
                values: values.clone(),
            },
        };
        zero(&mut self.writes, place.offset, place.bit, &ty);
        self.zeroed.push(name.to_string());
    }

    /// Configures the safe value of `place` (named `name`) from an IEC
    /// literal (`TRUE`, `5`, `2.5`, `T#1s`, `'text'`, an enumeration value
    /// `Name` or `Type#Name`).
    pub fn set_literal(&mut self, name: &str, place: &Place, text: &str) -> Result<(), String> {
        let write = encode(place, text)?;
        self.writes.push(write);
        self.configured
            .push((name.to_string(), text.trim().to_string()));
        Ok(())
    }

    /// Applies the safe state to `image` (writes outside it are skipped:
    /// places were resolved against this program's image).
    pub fn apply(&self, image: &mut [u8]) {
        for w in &self.writes {
            match w {
                Write::Zero(r) => {
                    if let Some(dst) = image.get_mut(r.clone()) {
                        dst.fill(0);
                    }
                }
                Write::Bytes { at, bytes } => {
                    if let Some(dst) = at
                        .checked_add(bytes.len())
                        .and_then(|end| image.get_mut(*at..end))
                    {
                        dst.copy_from_slice(bytes);
                    }
                }
                Write::Bit { at, bit, on } => {
                    if let (Some(b), true) = (image.get_mut(*at), *bit < 8) {
                        if *on {
                            *b |= 1 << bit;
                        } else {
                            *b &= !(1 << bit);
                        }
                    }
                }
            }
        }
    }

    /// The writes that undo [`apply`](Self::apply) on `image` as it is now:
    /// every byte and bit the safe state covers, with its current value.
    /// A PLC in STOP shows the outside world its safe state, but the
    /// program's memory is not the outside world: on the next start the
    /// program continues from the values it had (an output set by a stored
    /// action at a step's activation is driven again, as on a real PLC,
    /// where STOP replaces only what reaches the output hardware).
    pub fn held(&self, image: &[u8]) -> SafeState {
        let mut writes = Vec::with_capacity(self.writes.len());
        for w in &self.writes {
            let r = match w {
                Write::Zero(r) => r.clone(),
                Write::Bytes { at, bytes } => *at..at.saturating_add(bytes.len()),
                Write::Bit { at, bit, .. } => {
                    if let Some(b) = image.get(*at) {
                        writes.push(Write::Bit {
                            at: *at,
                            bit: *bit,
                            on: *bit < 8 && b & (1 << bit) != 0,
                        });
                    }
                    continue;
                }
            };
            if let Some(src) = image.get(r.clone()) {
                writes.push(Write::Bytes {
                    at: r.start,
                    bytes: src.to_vec(),
                });
            }
        }
        // Applied in reverse: where two writes overlap, the oldest value
        // (the one before the safe state) is the one left.
        writes.reverse();
        SafeState {
            writes,
            ..SafeState::default()
        }
    }

    /// What the safe state does, for the message after a stop:
    /// `the %Q area (1 byte) and 2 program outputs (main.y, main.z) set to 0/FALSE; main.valve set to TRUE`.
    pub fn describe(&self) -> String {
        let mut parts = Vec::new();
        if self.q_bytes > 0 {
            let s = if self.q_bytes == 1 { "" } else { "s" };
            parts.push(format!("the %Q area ({} byte{s})", self.q_bytes));
        }
        // A configured place is named once, with its value.
        let zeroed: Vec<String> = self
            .zeroed
            .iter()
            .filter(|z| {
                !self
                    .configured
                    .iter()
                    .any(|(c, _)| c.eq_ignore_ascii_case(z))
            })
            .cloned()
            .collect();
        if !zeroed.is_empty() {
            let n = zeroed.len();
            let s = if n == 1 { "" } else { "s" };
            parts.push(format!("{n} output{s} ({})", names(&zeroed)));
        }
        let mut text = match parts.len() {
            0 => String::new(),
            _ => format!("{} set to 0/FALSE", parts.join(" and ")),
        };
        for (name, value) in &self.configured {
            if !text.is_empty() {
                text.push_str("; ");
            }
            text.push_str(&format!("{name} set to {value}"));
        }
        if text.is_empty() {
            text.push_str("the program has no outputs");
        }
        text
    }
}

/// Up to eight names, then how many more.
fn names(all: &[String]) -> String {
    const SHOWN: usize = 8;
    let mut text = all
        .iter()
        .take(SHOWN)
        .cloned()
        .collect::<Vec<_>>()
        .join(", ");
    if all.len() > SHOWN {
        text.push_str(&format!(" and {} more", all.len() - SHOWN));
    }
    text
}

fn width(e: E) -> usize {
    e.bit_width().map_or(0, |w| (w as usize).div_ceil(8))
}

/// The little-endian bytes of `v` in `width` bytes (two's complement).
fn int_bytes(v: i128, width: usize) -> Vec<u8> {
    v.to_le_bytes()
        .get(..width)
        .map(<[u8]>::to_vec)
        .unwrap_or_default()
}

/// Whether the zero of `ty` is all zero bytes (so a whole array of it is
/// one write): not for a subrange or enumeration without 0.
fn zero_is_all_zero_bytes(ty: &SymbolType) -> bool {
    match ty {
        SymbolType::Elementary(_)
        | SymbolType::String { .. }
        | SymbolType::WString { .. }
        | SymbolType::Ref(_) => true,
        SymbolType::Subrange { lo, hi, .. } => (*lo..=*hi).contains(&0),
        SymbolType::Enum { values, .. } => values.is_empty() || values.iter().any(|(_, v)| *v == 0),
        SymbolType::Array { elem, .. } => zero_is_all_zero_bytes(elem),
        SymbolType::Struct { fields, .. } => fields.iter().all(|f| zero_is_all_zero_bytes(&f.ty)),
    }
}

/// The writes that set a value of type `ty` at `offset` to its zero (see
/// the module comment).
fn zero(out: &mut Vec<Write>, offset: u32, bit: Option<u8>, ty: &SymbolType) {
    let Ok(at) = usize::try_from(offset) else {
        return;
    };
    let span = |n: usize| Write::Zero(at..at.saturating_add(n));
    match ty {
        SymbolType::Elementary(E::Bool) if bit.is_some() => out.push(Write::Bit {
            at,
            bit: bit.unwrap_or(0),
            on: false,
        }),
        SymbolType::Elementary(e) => out.push(span(width(*e))),
        SymbolType::String { .. } | SymbolType::WString { .. } => {
            // An empty string: its length 0 (the characters do not matter).
            out.push(span(STRING_LEN_BYTES as usize));
        }
        SymbolType::Subrange { base, lo, hi } => {
            let v = if (*lo..=*hi).contains(&0) { 0 } else { *lo };
            out.push(Write::Bytes {
                at,
                bytes: int_bytes(v.into(), width(*base)),
            });
        }
        SymbolType::Enum { base, values, .. } => {
            let v = if values.iter().any(|(_, v)| *v == 0) || values.is_empty() {
                0
            } else {
                values.iter().map(|(_, v)| *v).min().unwrap_or(0)
            };
            out.push(Write::Bytes {
                at,
                bytes: int_bytes(v.into(), width(*base)),
            });
        }
        SymbolType::Array { elem, dims, stride } => {
            let count = dims.iter().try_fold(1u64, |n, (lo, hi)| {
                let e = u64::try_from(i128::from(*hi) - i128::from(*lo) + 1).ok()?;
                n.checked_mul(e)
            });
            let Some(count) = count else { return };
            // Elements of no size all lie at one place.
            let count = if *stride == 0 { count.min(1) } else { count };
            if zero_is_all_zero_bytes(elem) {
                let bytes = count.saturating_mul(u64::from(*stride));
                out.push(span(usize::try_from(bytes).unwrap_or(usize::MAX)));
                return;
            }
            for k in 0..count {
                let Some(o) = u64::from(offset)
                    .checked_add(k.saturating_mul(u64::from(*stride)))
                    .and_then(|o| u32::try_from(o).ok())
                else {
                    return;
                };
                zero(out, o, None, elem);
            }
        }
        SymbolType::Struct { fields, .. } => {
            for f in fields {
                if let Some(o) = offset.checked_add(f.offset) {
                    zero(out, o, f.bit, &f.ty);
                }
            }
        }
        SymbolType::Ref(_) => {}
    }
}

/// The write of a configured safe value (see [`SafeState::set_literal`]).
fn encode(place: &Place, text: &str) -> Result<Write, String> {
    let at = usize::try_from(place.offset).map_err(|_| "outside the image".to_string())?;
    let ty = match &place.ty {
        PlaceType::Elementary(e) => *e,
        PlaceType::String { .. } => E::String,
        PlaceType::WString { .. } => E::Wstring,
        PlaceType::Enum { name, base, values } => {
            let t = text.trim();
            let bare = t
                .split_once('#')
                .filter(|(ty, _)| ty.eq_ignore_ascii_case(name))
                .map_or(t, |(_, v)| v);
            let v = match values.iter().find(|(n, _)| n.eq_ignore_ascii_case(bare)) {
                Some((_, v)) => i128::from(*v),
                None => match parse_literal(bare, *base) {
                    Ok(Value::Int(v, _)) if values.iter().any(|(_, x)| i128::from(*x) == v) => v,
                    _ => return Err(format!("`{t}` is not a value of {name}")),
                },
            };
            return Ok(Write::Bytes {
                at,
                bytes: int_bytes(v, width(*base)),
            });
        }
    };
    let value = parse_literal(text, ty).map_err(|e| e.to_string())?;
    let bytes = match value {
        Value::Bool(on) => match place.bit {
            Some(bit) => return Ok(Write::Bit { at, bit, on }),
            None => vec![u8::from(on)],
        },
        Value::Int(v, _) => int_bytes(v, width(ty)),
        Value::Real(r, E::Real) => (r as f32).to_le_bytes().to_vec(),
        Value::Real(r, _) => r.to_le_bytes().to_vec(),
        Value::Duration(n, _) | Value::Date(n, _) | Value::Tod(n, _) | Value::Dt(n, _) => {
            n.to_le_bytes().to_vec()
        }
        Value::Char(c) => vec![c],
        Value::WChar(c) => c.to_le_bytes().to_vec(),
        Value::Str(s) => string_bytes(place, s.len(), &s)?,
        Value::WStr(s) => {
            let units: Vec<u8> = s.iter().flat_map(|u| u.to_le_bytes()).collect();
            string_bytes(place, s.len(), &units)?
        }
    };
    Ok(Write::Bytes { at, bytes })
}

/// The length field and characters of a string value of `len` characters.
fn string_bytes(place: &Place, len: usize, chars: &[u8]) -> Result<Vec<u8>, String> {
    let cap = match place.ty {
        PlaceType::String { cap } | PlaceType::WString { cap } => cap,
        _ => 0,
    };
    let n = u32::try_from(len).unwrap_or(u32::MAX);
    if n > cap {
        return Err(format!(
            "the string has {len} characters; the variable holds {cap}"
        ));
    }
    let mut out = vec![0u8; STRING_LEN_BYTES as usize];
    put_string_len(&mut out, 0, n).ok_or_else(|| "the string is too long".to_string())?;
    out.extend_from_slice(chars);
    Ok(out)
}

#[cfg(test)]
#[path = "safe_tests.rs"]
mod tests;
