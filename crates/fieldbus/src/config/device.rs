//! `[[modbus.client]]` and `[[modbus.rtu_device]]`: a remote device, its
//! timing and its status variables; its blocks are checked in `block.rs`,
//! its serial line in `serial.rs`.

use super::block::{block, RawBlock};
use super::{serial, Ctx};
use crate::client::{DeviceSpec, Link, OnLoss, StatusPlaces};
use automat_base::Code;
use automat_iec::Elementary;
use automat_runtime::{resolve_access, PlaceType};
use serde::Deserialize;
use std::net::SocketAddr;
use std::time::Duration;
use toml::Spanned;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawDevice {
    pub(super) name: Spanned<String>,
    address: Option<Spanned<String>>,
    device: Option<Spanned<String>>,
    baud: Option<Spanned<i64>>,
    parity: Option<Spanned<String>>,
    stop_bits: Option<Spanned<i64>>,
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

/// How a `[[modbus.client]]` (TCP) or `[[modbus.rtu_device]]` is reached.
fn link(cx: &mut Ctx, d: &RawDevice, rtu: bool) -> Link {
    let name = d.name.get_ref();
    let nowhere = Link::Tcp(SocketAddr::from(([127, 0, 0, 1], 0)));
    if rtu {
        if let Some(a) = &d.address {
            cx.err(
                Code::E345,
                a.span(),
                format!("RTU device `{name}` is on a serial line: `device = \"/dev/ttyS0\"`, not `address`"),
            );
        }
        let Some(dev) = &d.device else {
            cx.err(
                Code::E345,
                d.name.span(),
                format!(
                    "RTU device `{name}` has no `device` (its serial port, e.g. \"/dev/ttyUSB0\")"
                ),
            );
            return nowhere;
        };
        return serial::line(cx, dev, &d.baud, &d.parity, &d.stop_bits).map_or(nowhere, Link::Rtu);
    }
    let serial_keys = [
        d.device.as_ref().map(|x| x.span()),
        d.baud.as_ref().map(|x| x.span()),
        d.parity.as_ref().map(|x| x.span()),
        d.stop_bits.as_ref().map(|x| x.span()),
    ];
    if let Some(span) = serial_keys.into_iter().flatten().next() {
        cx.err(
            Code::E345,
            span,
            format!("device `{name}` is a Modbus TCP device: serial settings belong to a `[[modbus.rtu_device]]`"),
        );
    }
    let Some(address) = &d.address else {
        cx.err(
            Code::E340,
            d.name.span(),
            format!("device `{name}` has no `address` (IP:PORT)"),
        );
        return nowhere;
    };
    match device_addr(address.get_ref()) {
        Some(a) => Link::Tcp(a),
        None => {
            cx.err(
                Code::E340,
                address.span(),
                format!(
                    "device `{name}`: address `{}` is not IP:PORT (e.g. 192.168.0.20:502, [fe80::1]:502, localhost:502)",
                    address.get_ref()
                ),
            );
            nowhere
        }
    }
}

/// A client device; `rtu` for `[[modbus.rtu_device]]`.
pub(super) fn device(cx: &mut Ctx, d: RawDevice, rtu: bool) -> Option<DeviceSpec> {
    let name = d.name.get_ref().clone();
    let before = cx.errors.len();
    let link = link(cx, &d, rtu);
    let unit = if rtu {
        serial::unit(cx, &d.unit, &name)
    } else {
        match &d.unit {
            None => 1,
            Some(u) => u8::try_from(*u.get_ref()).unwrap_or_else(|_| {
                cx.err(
                    Code::E340,
                    u.span(),
                    format!("device `{name}`: unit {} is outside 0..=255", u.get_ref()),
                );
                1
            }),
        }
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
        link,
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
