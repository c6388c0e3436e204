//! `[modbus.server]`: the listening address, its limits and the map
//! entries that add variables to the default map (E341–E344 per entry).

use super::{expand, Ctx};
use crate::map::{register_shape, Map, WordOrder};
use crate::pdu::Table;
use crate::server::{self, Allow};
use automat_base::Code;
use automat_iec::Elementary;
use automat_runtime::{resolve_access, PlaceType};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::net::SocketAddr;
use toml::Spanned;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawServer {
    listen: Spanned<String>,
    max_connections: Option<Spanned<i64>>,
    allow: Option<Vec<Spanned<String>>>,
    #[serde(default)]
    read_only: bool,
    default_map: Option<bool>,
    idle_timeout: Option<Spanned<String>>,
    #[serde(default)]
    map: Vec<RawEntry>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawEntry {
    var: Spanned<String>,
    table: Spanned<String>,
    address: Spanned<i64>,
    word_order: Option<Spanned<String>>,
}

/// The server as configured.
#[derive(Clone, Debug)]
pub struct ServerConfig {
    pub options: server::Options,
    pub map: Map,
}

pub(super) fn server_config(cx: &mut Ctx, s: RawServer) -> Option<ServerConfig> {
    let addr = match server::parse_addr(s.listen.get_ref()) {
        Ok(a) => Some(a),
        Err(e) => {
            cx.err(Code::E340, s.listen.span(), format!("listen: {e}"));
            None
        }
    };
    let mut options = server::Options::new(addr.unwrap_or(SocketAddr::from(([127, 0, 0, 1], 0))));
    if let Some(m) = &s.max_connections {
        match usize::try_from(*m.get_ref())
            .ok()
            .filter(|n| (1..=1024).contains(n))
        {
            Some(n) => options.max_connections = n,
            None => cx.err(
                Code::E340,
                m.span(),
                format!("max_connections must be 1..=1024, not {}", m.get_ref()),
            ),
        }
    }
    for a in s.allow.iter().flatten() {
        match Allow::parse(a.get_ref()) {
            Ok(x) => options.allow.push(x),
            Err(e) => cx.err(Code::E340, a.span(), format!("allow: {e}")),
        }
    }
    options.idle_timeout = cx.duration(&s.idle_timeout, "idle_timeout", options.idle_timeout);
    let map = build_map(cx, s.default_map, s.read_only, &s.map);
    if let Some(why) = options.open_to_writes(map.read_only) {
        cx.err(
            Code::E340,
            s.listen.span(),
            format!("{why}: list the clients in `allow = [...]` or set `read_only = true`"),
        );
    }
    addr.map(|_| ServerConfig { options, map })
}

/// A server's map (TCP or RTU): the default map unless turned off, then
/// the entries.
pub(super) fn build_map(
    cx: &mut Ctx,
    default_map: Option<bool>,
    read_only: bool,
    entries: &[RawEntry],
) -> Map {
    let mut map = if default_map.unwrap_or(true) {
        Map::default_of(cx.program)
    } else {
        Map::default()
    };
    map.read_only = read_only;
    let mut taken: BTreeMap<(Table, u32), String> = BTreeMap::new();
    for e in entries {
        entry(cx, e, &mut map, &mut taken);
    }
    map
}

fn entry(cx: &mut Ctx, e: &RawEntry, map: &mut Map, taken: &mut BTreeMap<(Table, u32), String>) {
    let (Some(table), Some(address)) = (cx.table(&e.table), cx.address(&e.address)) else {
        return;
    };
    let order = cx.order(&e.word_order, WordOrder::HighFirst);
    let mut at = u32::from(address);
    for path in expand(cx.program, e.var.get_ref().trim()) {
        let Ok(a16) = u16::try_from(at) else {
            return cx.err(
                Code::E340,
                e.address.span(),
                format!(
                    "`{}` runs past Modbus address 65535",
                    e.var.get_ref().trim()
                ),
            );
        };
        match entry_one(cx, e, table, a16, order, &path, map, taken) {
            Some(width) => at += width,
            None => return,
        }
    }
}

/// One variable of an entry at `address`; its number of addresses.
#[allow(clippy::too_many_arguments)]
fn entry_one(
    cx: &mut Ctx,
    e: &RawEntry,
    table: Table,
    address: u16,
    order: WordOrder,
    path: &str,
    map: &mut Map,
    taken: &mut BTreeMap<(Table, u32), String>,
) -> Option<u32> {
    let a = match resolve_access(cx.program, path) {
        Ok(a) => a,
        Err(m) => {
            cx.err(Code::E341, e.var.span(), m);
            return None;
        }
    };
    if table.writable() && (a.constant || a.generated.is_some()) {
        let what = if a.constant {
            "a CONSTANT"
        } else {
            "compiler-generated state"
        };
        cx.err(
            Code::E344,
            e.var.span(),
            format!(
                "`{path}` is {what}: clients would write it as {}; map it as {} instead",
                table.name(),
                if table.is_bits() {
                    "discrete_inputs"
                } else {
                    "input_registers"
                }
            ),
        );
        return None;
    }
    let is_bool = a.place.ty == PlaceType::Elementary(Elementary::Bool);
    let width = if table.is_bits() {
        if !is_bool {
            cx.err(
                Code::E342,
                e.var.span(),
                format!(
                    "`{path}` is {}: {} take a BOOL",
                    automat_session::value::type_name(&a.place.ty),
                    table.name()
                ),
            );
            return None;
        }
        map.add_bit(table, address, &a.place);
        1
    } else {
        let Some((width, _, _)) = register_shape(&a.place.ty).filter(|_| !is_bool) else {
            cx.err(
                Code::E342,
                e.var.span(),
                format!(
                    "`{path}` is {}: registers take one elementary value of 8 to 64 bits",
                    automat_session::value::type_name(&a.place.ty)
                ),
            );
            return None;
        };
        if u32::from(address) + width > 65_536 {
            cx.err(
                Code::E340,
                e.address.span(),
                format!("`{path}` needs {width} registers from {address}: past 65535"),
            );
            return None;
        }
        map.add_registers(table, address, &a.place, order);
        width
    };
    for r in u32::from(address)..u32::from(address) + width {
        if let Some(other) = taken.insert((table, r), path.to_string()) {
            cx.err(
                Code::E343,
                e.address.span(),
                format!(
                    "{} address {r} is mapped twice: to `{other}` and to `{path}`",
                    table.name()
                ),
            );
            return None;
        }
    }
    Some(width)
}
