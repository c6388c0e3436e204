//! `[modbus]` in `automat.toml`: the server and the client devices,
//! checked against the compiled program (every error a diagnostic in the
//! project file, E340–E344). The format is documented in `docs/modbus.md`.
//!
//! The tables are read from the same text as the rest of the project file
//! (`automat-project` only lets `[modbus]` through), so spans point at
//! the key in the file.

use crate::client::{Block, DeviceSpec, OnLoss, StatusPlaces, Target};
use crate::map::{register_shape, Map, WordOrder};
use crate::pdu::{self, Table};
use crate::server::{self, Allow};
use automat_base::{Code, Diagnostic, FileId, Span};
use automat_iec::Elementary;
use automat_ir::{Program, SymbolType};
use automat_runtime::{resolve_access, PlaceType};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::net::SocketAddr;
use std::time::Duration;
use toml::Spanned;

#[derive(Deserialize)]
struct RawRoot {
    modbus: Option<RawModbus>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawModbus {
    server: Option<RawServer>,
    #[serde(default)]
    client: Vec<RawDevice>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawServer {
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
struct RawEntry {
    var: Spanned<String>,
    table: Spanned<String>,
    address: Spanned<i64>,
    word_order: Option<Spanned<String>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawDevice {
    name: Spanned<String>,
    address: Spanned<String>,
    unit: Option<Spanned<i64>>,
    period: Option<Spanned<String>>,
    timeout: Option<Spanned<String>>,
    retries: Option<Spanned<i64>>,
    on_loss: Option<Spanned<String>>,
    connected: Option<Spanned<String>>,
    errors: Option<Spanned<String>>,
    last_error: Option<Spanned<String>>,
    #[serde(default)]
    read: Vec<RawBlock>,
    #[serde(default)]
    write: Vec<RawBlock>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawBlock {
    table: Spanned<String>,
    address: Spanned<i64>,
    count: Option<Spanned<i64>>,
    to: Option<Spanned<toml::Value>>,
    from: Option<Spanned<toml::Value>>,
    word_order: Option<Spanned<String>>,
}

/// The server as configured.
#[derive(Clone, Debug)]
pub struct ServerConfig {
    pub options: server::Options,
    pub map: Map,
}

/// `[modbus]` checked.
#[derive(Clone, Debug, Default)]
pub struct Config {
    pub server: Option<ServerConfig>,
    pub clients: Vec<DeviceSpec>,
}

struct Ctx<'a> {
    file: FileId,
    program: &'a Program,
    errors: Vec<Diagnostic>,
}

impl Ctx<'_> {
    fn span(&self, r: std::ops::Range<usize>) -> Span {
        let c = |x: usize| u32::try_from(x).unwrap_or(u32::MAX);
        Span::new(self.file, c(r.start), c(r.end))
    }
    fn err(&mut self, code: Code, r: std::ops::Range<usize>, msg: impl Into<String>) {
        let span = self.span(r);
        self.errors.push(Diagnostic::error(code, span, msg.into()));
    }
    fn duration(&mut self, d: &Option<Spanned<String>>, what: &str, default: Duration) -> Duration {
        let Some(d) = d else { return default };
        match automat_runtime::timearg::parse_duration(d.get_ref()) {
            Ok(ns) if ns > 0 => Duration::from_nanos(ns as u64),
            Ok(_) => {
                self.err(
                    Code::E340,
                    d.span(),
                    format!("{what} must be longer than 0"),
                );
                default
            }
            Err(e) => {
                self.err(Code::E340, d.span(), format!("{what}: {e}"));
                default
            }
        }
    }
    fn table(&mut self, t: &Spanned<String>) -> Option<Table> {
        let got = Table::parse(t.get_ref().trim());
        if got.is_none() {
            self.err(
                Code::E340,
                t.span(),
                format!(
                    "`{}` is not a Modbus table: coils, discrete_inputs, input_registers or holding_registers",
                    t.get_ref()
                ),
            );
        }
        got
    }
    fn address(&mut self, a: &Spanned<i64>) -> Option<u16> {
        let got = u16::try_from(*a.get_ref()).ok();
        if got.is_none() {
            self.err(
                Code::E340,
                a.span(),
                format!("Modbus address {} is outside 0..=65535", a.get_ref()),
            );
        }
        got
    }
    fn order(&mut self, o: &Option<Spanned<String>>, default: WordOrder) -> WordOrder {
        match o {
            None => default,
            Some(o) => match o.get_ref().as_str() {
                "high_first" => WordOrder::HighFirst,
                "low_first" => WordOrder::LowFirst,
                other => {
                    self.err(
                        Code::E340,
                        o.span(),
                        format!("word_order `{other}` is not high_first or low_first"),
                    );
                    default
                }
            },
        }
    }
}

/// Reads `[modbus]` from the text of `automat.toml` (`file` in the
/// caller's source map) and checks it against `program`.
pub fn load(text: &str, file: FileId, program: &Program) -> Result<Config, Vec<Diagnostic>> {
    let raw: RawRoot = toml::from_str(text).map_err(|e| {
        let r = e.span().unwrap_or(0..0);
        let c = |x: usize| u32::try_from(x).unwrap_or(u32::MAX);
        vec![Diagnostic::error(
            Code::E340,
            Span::new(file, c(r.start), c(r.end)),
            format!("invalid [modbus] table: {}", e.message().trim_end()),
        )]
    })?;
    let Some(raw) = raw.modbus else {
        return Ok(Config::default());
    };
    let mut cx = Ctx {
        file,
        program,
        errors: Vec::new(),
    };
    let server = raw.server.map(|s| server_config(&mut cx, s));
    let mut names: BTreeMap<String, ()> = BTreeMap::new();
    let mut clients = Vec::new();
    for d in raw.client {
        if names.insert(d.name.get_ref().clone(), ()).is_some() {
            cx.err(
                Code::E340,
                d.name.span(),
                format!("two Modbus client devices are named `{}`", d.name.get_ref()),
            );
        }
        if let Some(spec) = device(&mut cx, d) {
            clients.push(spec);
        }
    }
    if cx.errors.is_empty() {
        Ok(Config {
            server: server.flatten(),
            clients,
        })
    } else {
        Err(cx.errors)
    }
}

fn server_config(cx: &mut Ctx, s: RawServer) -> Option<ServerConfig> {
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
    let mut map = if s.default_map.unwrap_or(true) {
        Map::default_of(cx.program)
    } else {
        Map::default()
    };
    map.read_only = s.read_only;
    if let Some(why) = options.open_to_writes(map.read_only) {
        cx.err(
            Code::E340,
            s.listen.span(),
            format!("{why}: list the clients in `allow = [...]` or set `read_only = true`"),
        );
    }
    let mut taken: BTreeMap<(Table, u32), String> = BTreeMap::new();
    for e in &s.map {
        entry(cx, e, &mut map, &mut taken);
    }
    addr.map(|_| ServerConfig { options, map })
}

/// The paths a map entry or block names: a one-dimensional array declared
/// as a whole variable (`Main.levels`) stands for its elements in order.
pub(crate) fn expand(program: &Program, path: &str) -> Vec<String> {
    if let Some(e) = program.symbols.get(path) {
        if let SymbolType::Array { dims, .. } = &e.ty {
            if let [(lo, hi)] = dims.as_slice() {
                if hi >= lo && hi - lo < 2000 {
                    return (*lo..=*hi).map(|i| format!("{path}[{i}]")).collect();
                }
            }
        }
    }
    vec![path.to_string()]
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

/// `IP:PORT`, or `localhost:PORT` (127.0.0.1). No name is looked up:
/// loading a project never waits for a resolver, and a PLC's remote I/O is
/// configured by address.
fn device_addr(s: &str) -> Option<SocketAddr> {
    let s = s.trim();
    if let Some(port) = s.strip_prefix("localhost:") {
        return port
            .parse::<u16>()
            .ok()
            .map(|p| SocketAddr::from(([127, 0, 0, 1], p)));
    }
    s.parse().ok()
}

fn device(cx: &mut Ctx, d: RawDevice) -> Option<DeviceSpec> {
    let name = d.name.get_ref().clone();
    let before = cx.errors.len();
    let addr = match device_addr(d.address.get_ref()) {
        Some(a) => a,
        None => {
            cx.err(
                Code::E340,
                d.address.span(),
                format!(
                    "device `{name}`: address `{}` is not IP:PORT (e.g. 192.168.0.20:502, [fe80::1]:502, localhost:502)",
                    d.address.get_ref()
                ),
            );
            SocketAddr::from(([127, 0, 0, 1], 0))
        }
    };
    let unit = match &d.unit {
        None => 1,
        Some(u) => u8::try_from(*u.get_ref()).unwrap_or_else(|_| {
            cx.err(
                Code::E340,
                u.span(),
                format!("device `{name}`: unit {} is outside 0..=255", u.get_ref()),
            );
            1
        }),
    };
    let period = cx.duration(&d.period, "period", Duration::from_millis(100));
    let timeout = cx.duration(&d.timeout, "timeout", Duration::from_millis(500));
    let retries = match &d.retries {
        None => 1,
        Some(r) => u32::try_from(*r.get_ref())
            .ok()
            .filter(|n| *n <= 10)
            .unwrap_or_else(|| {
                cx.err(
                    Code::E340,
                    r.span(),
                    format!(
                        "device `{name}`: retries must be 0..=10, not {}",
                        r.get_ref()
                    ),
                );
                1
            }),
    };
    let on_loss = match &d.on_loss {
        None => OnLoss::Zero,
        Some(o) => match o.get_ref().as_str() {
            "zero" => OnLoss::Zero,
            "hold" => OnLoss::Hold,
            other => {
                cx.err(
                    Code::E340,
                    o.span(),
                    format!("on_loss `{other}` is not zero or hold"),
                );
                OnLoss::Zero
            }
        },
    };
    let mut reads = Vec::new();
    for b in &d.read {
        if let Some(b) = block(cx, &name, b, true) {
            reads.push(b);
        }
    }
    let mut writes = Vec::new();
    for b in &d.write {
        if let Some(b) = block(cx, &name, b, false) {
            writes.push(b);
        }
    }
    let status = StatusPlaces {
        connected: d
            .connected
            .as_ref()
            .and_then(|p| status_place(cx, p, true).map(|(o, bit, _)| (o, bit))),
        errors: d
            .errors
            .as_ref()
            .and_then(|p| status_place(cx, p, false).map(|(o, _, n)| (o, n))),
        last_error: d
            .last_error
            .as_ref()
            .and_then(|p| status_place(cx, p, false).map(|(o, _, n)| (o, n))),
    };
    (cx.errors.len() == before).then_some(DeviceSpec {
        name,
        addr,
        unit,
        period,
        timeout,
        retries,
        on_loss,
        reads,
        writes,
        status,
    })
}

/// A status variable: BOOL for `connected`, an integer otherwise.
fn status_place(
    cx: &mut Ctx,
    p: &Spanned<String>,
    boolean: bool,
) -> Option<(usize, Option<u8>, usize)> {
    let path = p.get_ref().trim();
    let a = match resolve_access(cx.program, path) {
        Ok(a) => a,
        Err(m) => {
            cx.err(Code::E341, p.span(), m);
            return None;
        }
    };
    if a.constant || a.generated.is_some() {
        cx.err(
            Code::E344,
            p.span(),
            format!("`{path}` is read-only: the client cannot write its status there"),
        );
        return None;
    }
    let ok = match &a.place.ty {
        PlaceType::Elementary(Elementary::Bool) => boolean,
        PlaceType::Elementary(e) => !boolean && (e.is_int() || e.is_bit_string()),
        _ => false,
    };
    if !ok {
        cx.err(
            Code::E342,
            p.span(),
            format!(
                "`{path}` is {}: a status variable is {}",
                automat_session::value::type_name(&a.place.ty),
                if boolean { "a BOOL" } else { "an integer" }
            ),
        );
        return None;
    }
    Some((
        a.place.offset as usize,
        a.place.bit,
        a.place.ty.size() as usize,
    ))
}

/// The area (`%I`, `%Q`, `%M`) holding `offset`, as a byte range.
fn area_of(program: &Program, offset: u32) -> Option<std::ops::Range<u32>> {
    let a = &program.areas;
    [&a.input, &a.output, &a.memory]
        .into_iter()
        .find(|r| r.contains(&offset))
        .cloned()
}

fn block(cx: &mut Ctx, dev: &str, b: &RawBlock, read: bool) -> Option<Block> {
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
