//! IEC values and OPC UA values: the data type of a place, the variant
//! of its value in a snapshot image, and the IEC literal a client's
//! variant is written as (through the session, so its rules hold).
//!
//! BOOL Boolean; SINT SByte, INT Int16, DINT Int32, LINT Int64; USINT and
//! BYTE Byte, UINT and WORD UInt16, UDINT and DWORD UInt32, ULINT and LWORD
//! UInt64; REAL Float, LREAL Double; STRING and WSTRING String; TIME and
//! LTIME Duration (milliseconds, a Double, as OPC UA defines it); dates,
//! times of day, CHARs and enumerations String holding the IEC literal
//! (`D#2024-01-31`, `Color#Red`), which a client writes back the same way.

use automat_iec::{Elementary as E, Value};
use automat_runtime::{value, Place, PlaceType};
use opcua::types::{DataTypeId, Variant};

/// The OPC UA data type of a place.
pub fn data_type(ty: &PlaceType) -> DataTypeId {
    match ty {
        PlaceType::Elementary(e) => match e {
            E::Bool => DataTypeId::Boolean,
            E::Sint => DataTypeId::SByte,
            E::Int => DataTypeId::Int16,
            E::Dint => DataTypeId::Int32,
            E::Lint => DataTypeId::Int64,
            E::Usint | E::Byte => DataTypeId::Byte,
            E::Uint | E::Word => DataTypeId::UInt16,
            E::Udint | E::Dword => DataTypeId::UInt32,
            E::Ulint | E::Lword => DataTypeId::UInt64,
            E::Real => DataTypeId::Float,
            E::Lreal => DataTypeId::Double,
            E::Time | E::Ltime => DataTypeId::Duration,
            _ => DataTypeId::String,
        },
        PlaceType::String { .. } | PlaceType::WString { .. } | PlaceType::Enum { .. } => {
            DataTypeId::String
        }
    }
}

/// The value at `place` in `image`; `Variant::Empty` outside the image.
pub fn read(image: &[u8], place: &Place) -> Variant {
    let Some(v) = value::read(image, place) else {
        return Variant::Empty;
    };
    if matches!(place.ty, PlaceType::Enum { .. }) {
        return Variant::String(value::format(image, place).into());
    }
    match v {
        Value::Bool(b) => Variant::Boolean(b),
        Value::Int(n, e) => match e {
            E::Sint => Variant::SByte(n as i8),
            E::Int => Variant::Int16(n as i16),
            E::Dint => Variant::Int32(n as i32),
            E::Lint => Variant::Int64(n as i64),
            E::Usint | E::Byte => Variant::Byte(n as u8),
            E::Uint | E::Word => Variant::UInt16(n as u16),
            E::Udint | E::Dword => Variant::UInt32(n as u32),
            _ => Variant::UInt64(n as u64),
        },
        Value::Real(x, E::Real) => Variant::Float(x as f32),
        Value::Real(x, _) => Variant::Double(x),
        Value::Duration(ns, _) => Variant::Double(ns as f64 / 1e6),
        Value::Str(bytes) => Variant::String(String::from_utf8_lossy(&bytes).into_owned().into()),
        Value::WStr(units) => Variant::String(String::from_utf16_lossy(&units).into()),
        other => Variant::String(automat_iec::format_value(&other).into()),
    }
}

/// An IEC string literal of `s` (`'it$'s'`).
fn quoted(s: &str, quote: char) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push(quote);
    for c in s.chars() {
        match c {
            '$' => out.push_str("$$"),
            c if c == quote => {
                out.push('$');
                out.push(c);
            }
            '\n' => out.push_str("$N"),
            '\r' => out.push_str("$R"),
            '\t' => out.push_str("$T"),
            c => out.push(c),
        }
    }
    out.push(quote);
    out
}

/// The IEC literal that writes `v` to a place of type `ty`; `None` when
/// the variant's type is not the node's (BadTypeMismatch).
pub fn literal(v: &Variant, ty: &PlaceType) -> Option<String> {
    let want = data_type(ty);
    Some(match (v, want) {
        (Variant::Boolean(b), DataTypeId::Boolean) => if *b { "TRUE" } else { "FALSE" }.into(),
        (Variant::SByte(n), DataTypeId::SByte) => n.to_string(),
        (Variant::Int16(n), DataTypeId::Int16) => n.to_string(),
        (Variant::Int32(n), DataTypeId::Int32) => n.to_string(),
        (Variant::Int64(n), DataTypeId::Int64) => n.to_string(),
        (Variant::Byte(n), DataTypeId::Byte) => n.to_string(),
        (Variant::UInt16(n), DataTypeId::UInt16) => n.to_string(),
        (Variant::UInt32(n), DataTypeId::UInt32) => n.to_string(),
        (Variant::UInt64(n), DataTypeId::UInt64) => n.to_string(),
        (Variant::Float(x), DataTypeId::Float) if x.is_finite() => format!("{x:?}"),
        (Variant::Double(x), DataTypeId::Double) if x.is_finite() => format!("{x:?}"),
        (Variant::Double(ms), DataTypeId::Duration) if ms.is_finite() => {
            // Whole nanoseconds: T#...ms takes a fraction.
            let ns = (ms * 1e6).round();
            if ns.abs() > 9.2e18 {
                return None;
            }
            let ns = ns as i64;
            let prefix = if matches!(ty, PlaceType::Elementary(E::Ltime)) {
                "LTIME#"
            } else {
                "T#"
            };
            if ns < 0 {
                format!("{prefix}-{}ns", ns.unsigned_abs())
            } else {
                format!("{prefix}{ns}ns")
            }
        }
        (Variant::String(s), DataTypeId::String) => {
            let s = s.as_ref();
            match ty {
                PlaceType::String { .. } => quoted(s, '\''),
                PlaceType::WString { .. } => quoted(s, '"'),
                // Dates, times of day, CHARs, enumerations: the literal.
                _ => s.to_string(),
            }
        }
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn el(e: E) -> PlaceType {
        PlaceType::Elementary(e)
    }

    #[test]
    fn values_read_as_their_opc_ua_types() {
        let mut img = vec![0u8; 32];
        img[0] = 0b100;
        img[1..3].copy_from_slice(&(-2i16).to_le_bytes());
        img[4..8].copy_from_slice(&1.5f32.to_le_bytes());
        img[8..16].copy_from_slice(&1_500_000_000i64.to_le_bytes());
        img[16..18].copy_from_slice(&2u16.to_le_bytes());
        img[18..20].copy_from_slice(b"ok");
        let p = |offset, bit, ty| Place {
            offset,
            bit,
            ty,
            slc_bit: false,
        };
        assert_eq!(
            read(&img, &p(0, Some(2), el(E::Bool))),
            Variant::Boolean(true)
        );
        assert_eq!(read(&img, &p(1, None, el(E::Int))), Variant::Int16(-2));
        assert_eq!(read(&img, &p(1, None, el(E::Word))), Variant::UInt16(65534));
        assert_eq!(read(&img, &p(4, None, el(E::Real))), Variant::Float(1.5));
        assert_eq!(
            read(&img, &p(8, None, el(E::Time))),
            Variant::Double(1500.0)
        );
        assert_eq!(
            read(&img, &p(16, None, PlaceType::String { cap: 4 })),
            Variant::String("ok".into())
        );
        assert_eq!(read(&img, &p(60, None, el(E::Lint))), Variant::Empty);
        assert_eq!(data_type(&el(E::Udint)), DataTypeId::UInt32);
        assert_eq!(data_type(&el(E::Time)), DataTypeId::Duration);
    }

    #[test]
    fn writes_become_iec_literals_of_the_nodes_type_only() {
        assert_eq!(
            literal(&Variant::Int16(-7), &el(E::Int)).as_deref(),
            Some("-7")
        );
        assert_eq!(literal(&Variant::Int32(7), &el(E::Int)), None);
        assert_eq!(
            literal(&Variant::Boolean(true), &el(E::Bool)).as_deref(),
            Some("TRUE")
        );
        assert_eq!(
            literal(&Variant::Float(2.5), &el(E::Real)).as_deref(),
            Some("2.5")
        );
        assert_eq!(literal(&Variant::Float(f32::NAN), &el(E::Real)), None);
        assert_eq!(
            literal(&Variant::Double(1.5), &el(E::Time)).as_deref(),
            Some("T#1500000ns")
        );
        assert_eq!(
            literal(
                &Variant::String("it's $5".into()),
                &PlaceType::String { cap: 20 }
            )
            .as_deref(),
            Some("'it$'s $$5'")
        );
    }
}
