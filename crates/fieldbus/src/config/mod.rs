//! `[modbus]` in `automat.toml`: the server and the client devices,
//! checked against the compiled program (every error a diagnostic in the
//! project file, E340–E344). The format is documented in `docs/modbus.md`.
//!
//! The tables are read from the same text as the rest of the project file
//! (`automat-project` only lets `[modbus]` through), so spans point at
//! the key in the file.

mod block;
mod device;
mod serial;
mod server;

use crate::client::DeviceSpec;
use crate::map::WordOrder;
use crate::pdu::Table;
use automat_base::{Code, Diagnostic, FileId, Span};
use automat_ir::{Program, SymbolType};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::time::Duration;
use toml::Spanned;

pub use serial::RtuServerConfig;
pub use server::ServerConfig;

#[derive(Deserialize)]
struct RawRoot {
    modbus: Option<RawModbus>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawModbus {
    server: Option<server::RawServer>,
    #[serde(default)]
    client: Vec<device::RawDevice>,
    rtu_server: Option<serial::RawRtuServer>,
    #[serde(default)]
    rtu_device: Vec<device::RawDevice>,
}

/// `[modbus]` checked.
#[derive(Clone, Debug, Default)]
pub struct Config {
    pub server: Option<ServerConfig>,
    /// TCP and RTU devices.
    pub clients: Vec<DeviceSpec>,
    pub rtu_server: Option<RtuServerConfig>,
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
    let server = raw.server.map(|s| server::server_config(&mut cx, s));
    let mut names: BTreeMap<String, ()> = BTreeMap::new();
    let rtu_server = raw
        .rtu_server
        .map(|s| serial::rtu_server_config(&mut cx, s));
    let mut clients = Vec::new();
    let tcp = raw.client.into_iter().map(|d| (d, false));
    let rtu = raw.rtu_device.into_iter().map(|d| (d, true));
    let mut lines = Vec::new();
    for (d, is_rtu) in tcp.chain(rtu) {
        if names.insert(d.name.get_ref().clone(), ()).is_some() {
            cx.err(
                Code::E340,
                d.name.span(),
                format!("two Modbus client devices are named `{}`", d.name.get_ref()),
            );
        }
        let span = d.name.span();
        if let Some(spec) = device::device(&mut cx, d, is_rtu) {
            if let crate::client::Link::Rtu(line) = &spec.link {
                lines.push((line.clone(), spec.unit, span));
            }
            clients.push(spec);
        }
    }
    serial::one_bus_each(
        &mut cx,
        &lines,
        rtu_server.as_ref().and_then(|s| s.as_ref()),
    );
    if cx.errors.is_empty() {
        Ok(Config {
            server: server.flatten(),
            clients,
            rtu_server: rtu_server.flatten(),
        })
    } else {
        Err(cx.errors)
    }
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
