//! Modbus RTU in `automat.toml`: the serial line settings of
//! `[modbus.rtu_server]` and `[[modbus.rtu_device]]`, the slave's unit and
//! map, and the rules of a bus (E345): one port is either the slave's or
//! the master's, the devices sharing a port agree on its settings and
//! have distinct units.

use super::server::{build_map, RawEntry};
use super::Ctx;
use crate::map::Map;
use crate::serial::{Line, Parity};
use automat_base::Code;
use serde::Deserialize;
use toml::Spanned;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawRtuServer {
    device: Spanned<String>,
    baud: Option<Spanned<i64>>,
    parity: Option<Spanned<String>>,
    stop_bits: Option<Spanned<i64>>,
    unit: Option<Spanned<i64>>,
    #[serde(default)]
    read_only: bool,
    default_map: Option<bool>,
    #[serde(default)]
    map: Vec<RawEntry>,
}

/// The RTU slave as configured.
#[derive(Clone, Debug)]
pub struct RtuServerConfig {
    pub line: Line,
    pub unit: u8,
    pub map: Map,
}

/// The line of `device` with its settings (19200 baud, even parity, one
/// stop bit unless given).
pub(super) fn line(
    cx: &mut Ctx,
    device: &Spanned<String>,
    baud: &Option<Spanned<i64>>,
    parity: &Option<Spanned<String>>,
    stop_bits: &Option<Spanned<i64>>,
) -> Option<Line> {
    let before = cx.errors.len();
    let path = device.get_ref().trim();
    if path.is_empty() {
        cx.err(
            Code::E345,
            device.span(),
            "`device` is empty: name the serial port, e.g. \"/dev/ttyUSB0\"",
        );
    }
    let mut line = Line::new(path);
    if let Some(b) = baud {
        match u32::try_from(*b.get_ref())
            .ok()
            .filter(|b| (50..=4_000_000).contains(b))
        {
            Some(b) => line.baud = b,
            None => cx.err(
                Code::E345,
                b.span(),
                format!("baud {} is outside 50..=4000000", b.get_ref()),
            ),
        }
    }
    if let Some(p) = parity {
        match Parity::parse(p.get_ref().trim()) {
            Some(p) => line.parity = p,
            None => cx.err(
                Code::E345,
                p.span(),
                format!("parity `{}` is not none, even or odd", p.get_ref()),
            ),
        }
    }
    if let Some(s) = stop_bits {
        match *s.get_ref() {
            1 | 2 => line.stop_bits = *s.get_ref() as u8,
            n => cx.err(Code::E345, s.span(), format!("stop_bits {n} is not 1 or 2")),
        }
    }
    (cx.errors.len() == before).then_some(line)
}

/// A unit on a serial line: 1..=247 (0 is the broadcast, 248–255 are
/// reserved); 1 unless given.
pub(super) fn unit(cx: &mut Ctx, u: &Option<Spanned<i64>>, what: &str) -> u8 {
    let Some(u) = u else { return 1 };
    match u8::try_from(*u.get_ref())
        .ok()
        .filter(|u| (1..=247).contains(u))
    {
        Some(u) => u,
        None => {
            cx.err(
                Code::E345,
                u.span(),
                format!(
                    "{what}: unit {} is outside 1..=247 (0 is the broadcast address)",
                    u.get_ref()
                ),
            );
            1
        }
    }
}

pub(super) fn rtu_server_config(cx: &mut Ctx, s: RawRtuServer) -> Option<RtuServerConfig> {
    let line = line(cx, &s.device, &s.baud, &s.parity, &s.stop_bits);
    let unit = unit(cx, &s.unit, "[modbus.rtu_server]");
    let map = build_map(cx, s.default_map, s.read_only, &s.map);
    line.map(|line| RtuServerConfig { line, unit, map })
}

/// The rules of a bus over the RTU devices (line, unit, span of the name)
/// and the slave.
pub(super) fn one_bus_each(
    cx: &mut Ctx,
    devices: &[(Line, u8, std::ops::Range<usize>)],
    slave: Option<&RtuServerConfig>,
) {
    for (i, (line, unit, span)) in devices.iter().enumerate() {
        if slave.is_some_and(|s| s.line.device == line.device) {
            cx.err(
                Code::E345,
                span.clone(),
                format!(
                    "{} is the port of [modbus.rtu_server]: one port is either the slave's or the master's",
                    line.device
                ),
            );
        }
        let Some((first, first_unit, _)) = devices[..i]
            .iter()
            .find(|(l, _, _)| l.device == line.device)
        else {
            continue;
        };
        if first != line {
            cx.err(
                Code::E345,
                span.clone(),
                format!(
                    "devices on one port share its settings: {} here, {} before",
                    line.describe(),
                    first.describe()
                ),
            );
        } else if let Some(u) = devices[..i]
            .iter()
            .find(|(l, u, _)| l.device == line.device && u == unit)
            .map(|d| d.1)
        {
            cx.err(
                Code::E345,
                span.clone(),
                format!("unit {u} is already a device on {}", line.device),
            );
        }
        let _ = first_unit;
    }
}
