//! A read or write block of a client device: the Modbus range and the PLC
//! places it is exchanged with (a direct `%I`/`%Q`/`%M` range, BOOLs, or
//! register-shaped variables).

use super::{expand, Ctx};
use crate::client::{Block, Target};
use crate::map::{register_shape, WordOrder};
use crate::pdu;
use automat_base::Code;
use automat_iec::Elementary;
use automat_ir::Program;
use automat_runtime::{resolve_access, PlaceType};
use serde::Deserialize;
use toml::Spanned;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawBlock {
    table: Spanned<String>,
    address: Spanned<i64>,
    count: Option<Spanned<i64>>,
    to: Option<Spanned<toml::Value>>,
    from: Option<Spanned<toml::Value>>,
    word_order: Option<Spanned<String>>,
}

/// The area (`%I`, `%Q`, `%M`) holding `offset`, as a byte range.
fn area_of(program: &Program, offset: u32) -> Option<std::ops::Range<u32>> {
    let a = &program.areas;
    [&a.input, &a.output, &a.memory]
        .into_iter()
        .find(|r| r.contains(&offset))
        .cloned()
}

pub(super) fn block(cx: &mut Ctx, dev: &str, b: &RawBlock, read: bool) -> Option<Block> {
    let table = cx.table(&b.table)?;
    let addr = cx.address(&b.address)?;
    let key = if read { "to" } else { "from" };
    let (place, wrong) = if read {
        (&b.to, &b.from)
    } else {
        (&b.from, &b.to)
    };
    if let Some(w) = wrong {
        cx.err(
            Code::E340,
            w.span(),
            format!(
                "device `{dev}`: a {} block names its PLC places with `{key}`",
                if read { "read" } else { "write" }
            ),
        );
        return None;
    }
    let Some(place) = place else {
        cx.err(
            Code::E340,
            b.table.span(),
            format!("device `{dev}`: the block has no `{key}` (the PLC places it exchanges)"),
        );
        return None;
    };
    if !read && !table.writable() {
        cx.err(
            Code::E340,
            b.table.span(),
            format!(
                "device `{dev}`: {} cannot be written; a write block goes to coils or holding_registers",
                table.name()
            ),
        );
        return None;
    }
    let paths: Vec<String> = match place.get_ref() {
        toml::Value::String(s) => expand(cx.program, s.trim()),
        toml::Value::Array(items) => items
            .iter()
            .filter_map(|v| v.as_str())
            .flat_map(|p| expand(cx.program, p.trim()))
            .collect(),
        _ => Vec::new(),
    };
    if paths.is_empty() {
        cx.err(
            Code::E340,
            place.span(),
            format!("device `{dev}`: `{key}` is a path or a list of paths"),
        );
        return None;
    }
    let max = match (table.is_bits(), read) {
        (true, true) => pdu::MAX_READ_BITS,
        (false, true) => pdu::MAX_READ_REGS,
        (true, false) => pdu::MAX_WRITE_BITS,
        (false, false) => pdu::MAX_WRITE_REGS,
    };
    let count = match &b.count {
        None => None,
        Some(c) => match u16::try_from(*c.get_ref())
            .ok()
            .filter(|n| (1..=max).contains(n))
        {
            Some(n) => Some(n),
            None => {
                cx.err(
                    Code::E340,
                    c.span(),
                    format!(
                        "count {} is outside 1..={max} for {}",
                        c.get_ref(),
                        table.name()
                    ),
                );
                return None;
            }
        },
    };
    let mut accesses = Vec::new();
    for p in &paths {
        match resolve_access(cx.program, p.trim()) {
            Ok(a) => {
                if read && (a.constant || a.generated.is_some()) {
                    cx.err(
                        Code::E344,
                        place.span(),
                        format!(
                            "`{}` is read-only: device `{dev}` cannot write it",
                            p.trim()
                        ),
                    );
                    return None;
                }
                accesses.push(a)
            }
            Err(m) => {
                cx.err(Code::E341, place.span(), m);
                return None;
            }
        }
    }
    let direct = paths.len() == 1 && paths[0].trim_start().starts_with('%');
    let mismatch = |cx: &mut Ctx, why: String| {
        cx.err(Code::E342, place.span(), format!("device `{dev}`: {why}"));
        None
    };
    let first = &accesses[0].place;
    let (target, n_values) = if direct {
        let Some(area) = area_of(cx.program, first.offset) else {
            return mismatch(cx, format!("`{}` is in no %I/%Q/%M area", paths[0]));
        };
        let n = u32::from(count.unwrap_or(1));
        if table.is_bits() {
            let Some(bit) = first.bit else {
                return mismatch(
                    cx,
                    format!("`{}` is no bit address (%IX/%QX/%MX n.b)", paths[0]),
                );
            };
            let last = first.offset + (u32::from(bit) + n - 1) / 8;
            if last >= area.end {
                return mismatch(
                    cx,
                    format!(
                        "{n} bits from `{}` reach past the end of its area ({} bytes: the program's highest address there)",
                        paths[0],
                        area.len()
                    ),
                );
            }
            (
                Target::Bits {
                    byte: first.offset as usize,
                    bit,
                },
                n as u16,
            )
        } else {
            if first.ty.size() != 2 || first.bit.is_some() {
                return mismatch(
                    cx,
                    format!("`{}` is no word address (%IW/%QW/%MW n)", paths[0]),
                );
            }
            if first.offset + 2 * n > area.end {
                return mismatch(
                    cx,
                    format!(
                        "{n} registers from `{}` reach past the end of its area ({} bytes: the program's highest address there)",
                        paths[0],
                        area.len()
                    ),
                );
            }
            (
                Target::Words {
                    base: first.offset as usize,
                },
                n as u16,
            )
        }
    } else if table.is_bits() {
        let mut places = Vec::new();
        for (p, a) in paths.iter().zip(&accesses) {
            if a.place.ty != PlaceType::Elementary(Elementary::Bool) {
                return mismatch(
                    cx,
                    format!(
                        "`{}` is {}: {} take BOOLs",
                        p.trim(),
                        automat_session::value::type_name(&a.place.ty),
                        table.name()
                    ),
                );
            }
            places.push((a.place.offset as usize, a.place.bit));
        }
        if places.len() > usize::from(max) {
            return mismatch(
                cx,
                format!("{} bits in one block: at most {max}", places.len()),
            );
        }
        let n = places.len() as u16;
        (Target::Bools(places), n)
    } else {
        let order = cx.order(&b.word_order, WordOrder::HighFirst);
        let mut items = Vec::new();
        let mut total = 0u32;
        for (p, a) in paths.iter().zip(&accesses) {
            let is_bool = a.place.ty == PlaceType::Elementary(Elementary::Bool);
            let Some((w, bytes, signed)) = register_shape(&a.place.ty).filter(|_| !is_bool) else {
                return mismatch(
                    cx,
                    format!(
                        "`{}` is {}: registers take elementary values of 8 to 64 bits",
                        p.trim(),
                        automat_session::value::type_name(&a.place.ty)
                    ),
                );
            };
            items.push((a.place.offset as usize, w, bytes, signed));
            total += w;
        }
        if total > u32::from(max) {
            return mismatch(cx, format!("{total} registers in one block: at most {max}"));
        }
        (Target::Values { items, order }, total as u16)
    };
    if !direct {
        if let Some(c) = count {
            if c != count_of(&target) {
                return mismatch(
                    cx,
                    format!(
                        "count {c} differs from the {} value(s) the variables hold",
                        count_of(&target)
                    ),
                );
            }
        }
    }
    let count = n_values;
    if u32::from(addr) + u32::from(count) > 65_536 {
        cx.err(
            Code::E340,
            b.address.span(),
            format!("{count} values from address {addr} run past 65535"),
        );
        return None;
    }
    Some(Block {
        table,
        addr,
        count,
        target,
    })
}

fn count_of(t: &Target) -> u16 {
    match t {
        Target::Bools(p) => p.len() as u16,
        Target::Values { items, .. } => items.iter().map(|i| i.1 as u16).sum(),
        _ => 0,
    }
}
