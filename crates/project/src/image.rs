//! Plant values in and out of the memory image, at a resolved [`Place`]
//! (the IR layout: little-endian, BOOL a byte or one bit).
//!
//! Writing converts to the variable's type the way a field device would
//! deliver the value: integers saturate at the type's range, reals are
//! rounded half away from zero into integers; anything written to a place
//! of another kind (a string, a date) is ignored: the binding check refuses
//! such bindings before a run.

use automat_iec::{Elementary as E, Value as IecValue};
use automat_plant::Value;
use automat_runtime::{value, Place, PlaceType};

/// The element type of a place (an enumeration stores its base integer).
fn elementary(place: &Place) -> Option<E> {
    match &place.ty {
        PlaceType::Elementary(e) => Some(*e),
        PlaceType::Enum { base, .. } => Some(*base),
        _ => None,
    }
}

/// The value at `place` as the plant sees it; `None` for strings and
/// places outside the image.
pub fn read(image: &[u8], place: &Place) -> Option<Value> {
    // Every actuator is read every scan: BOOL, integers and reals straight
    // from the bytes, without building an `automat_iec::Value` (the same
    // values as the general path below).
    read_direct(image, place).unwrap_or_else(|| read_general(image, place))
}

/// [`read`] through `automat_iec::Value`, for every type.
fn read_general(image: &[u8], place: &Place) -> Option<Value> {
    Some(match value::read(image, place)? {
        IecValue::Bool(b) => Value::Bool(b),
        IecValue::Int(i, _) => {
            Value::Int(i64::try_from(i).unwrap_or(if i < 0 { i64::MIN } else { i64::MAX }))
        }
        IecValue::Real(r, _) => Value::Real(r),
        IecValue::Duration(ns, _) => Value::Int(ns),
        _ => return None,
    })
}

/// [`read`] for the elementary types actuators have (`None`: take the
/// general path; `Some(None)`: the place is outside the image).
fn read_direct(image: &[u8], place: &Place) -> Option<Option<Value>> {
    fn at<const N: usize>(image: &[u8], offset: u32) -> Option<[u8; N]> {
        let start = usize::try_from(offset).ok()?;
        image.get(start..start.checked_add(N)?)?.try_into().ok()
    }
    let (ty, bit) = match &place.ty {
        PlaceType::Elementary(e) => (*e, place.bit),
        PlaceType::Enum { base, .. } => (*base, None),
        _ => return None,
    };
    let o = place.offset;
    let int = |i: Option<i64>| i.map(Value::Int);
    Some(match ty {
        E::Bool => at::<1>(image, o).map(|[b]| {
            Value::Bool(match bit {
                Some(k) => k < 8 && b >> k & 1 != 0,
                None => b != 0,
            })
        }),
        E::Real => at(image, o).map(|b| Value::Real(f32::from_le_bytes(b).into())),
        E::Lreal => at(image, o).map(|b| Value::Real(f64::from_le_bytes(b))),
        E::Sint => int(at(image, o).map(|b| i8::from_le_bytes(b).into())),
        E::Int => int(at(image, o).map(|b| i16::from_le_bytes(b).into())),
        E::Dint => int(at(image, o).map(|b| i32::from_le_bytes(b).into())),
        E::Lint | E::Time | E::Ltime => int(at(image, o).map(i64::from_le_bytes)),
        E::Usint | E::Byte => int(at(image, o).map(|b| u8::from_le_bytes(b).into())),
        E::Uint | E::Word => int(at(image, o).map(|b| u16::from_le_bytes(b).into())),
        E::Udint | E::Dword => int(at(image, o).map(|b| u32::from_le_bytes(b).into())),
        // Beyond i64 the general path saturates.
        E::Ulint | E::Lword => {
            int(at(image, o).map(|b| i64::try_from(u64::from_le_bytes(b)).unwrap_or(i64::MAX)))
        }
        _ => return None,
    })
}

fn put<const N: usize>(image: &mut [u8], offset: u32, bytes: [u8; N]) {
    let Ok(start) = usize::try_from(offset) else {
        return;
    };
    if let Some(dst) = start
        .checked_add(N)
        .and_then(|end| image.get_mut(start..end))
    {
        dst.copy_from_slice(&bytes);
    }
}

/// Writes `v` at `place`, converted to its type (see the module rules).
pub fn write(image: &mut [u8], place: &Place, v: Value) {
    let Some(ty) = elementary(place) else {
        return;
    };
    if ty == E::Bool {
        let on = v.as_bool();
        let Some(byte) = usize::try_from(place.offset)
            .ok()
            .and_then(|o| image.get_mut(o))
        else {
            return;
        };
        match place.bit {
            Some(k) if k < 8 => {
                if on {
                    *byte |= 1 << k;
                } else {
                    *byte &= !(1 << k);
                }
            }
            Some(_) => {}
            None => *byte = u8::from(on),
        }
        return;
    }
    if ty.is_real() {
        let r = v.as_f64();
        match ty {
            E::Real => put(image, place.offset, (r as f32).to_le_bytes()),
            _ => put(image, place.offset, r.to_le_bytes()),
        }
        return;
    }
    let Some((lo, hi)) = ty.int_range() else {
        if ty.is_duration() {
            put(image, place.offset, int_of(v).to_le_bytes());
        }
        return;
    };
    let i = i128::from(int_of(v)).clamp(lo, hi);
    let o = place.offset;
    // In range by the clamp above, so the casts keep the value.
    match ty.bit_width() {
        Some(8) => put(image, o, [i as u8]),
        Some(16) => put(image, o, (i as u16).to_le_bytes()),
        Some(32) => put(image, o, (i as u32).to_le_bytes()),
        Some(64) => put(image, o, (i as u64).to_le_bytes()),
        _ => {}
    }
}

/// An integer from a plant value: reals rounded, saturating.
fn int_of(v: Value) -> i64 {
    match v {
        Value::Bool(b) => i64::from(b),
        Value::Int(i) => i,
        // `as` saturates and maps NaN to 0.
        Value::Real(r) => r.round() as i64,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn place(offset: u32, bit: Option<u8>, e: E) -> Place {
        Place {
            offset,
            bit,
            ty: PlaceType::Elementary(e),
            slc_bit: false,
        }
    }

    #[test]
    fn bools_as_bits_and_bytes() {
        let mut img = [0u8; 4];
        write(&mut img, &place(1, Some(3), E::Bool), Value::Bool(true));
        write(&mut img, &place(2, None, E::Bool), Value::Int(5));
        assert_eq!(img, [0, 8, 1, 0]);
        assert_eq!(
            read(&img, &place(1, Some(3), E::Bool)),
            Some(Value::Bool(true))
        );
        write(&mut img, &place(1, Some(3), E::Bool), Value::Bool(false));
        assert_eq!(img, [0, 0, 1, 0]);
        // out of the image: nothing happens
        write(&mut img, &place(9, None, E::Bool), Value::Bool(true));
        assert_eq!(read(&img, &place(9, None, E::Bool)), None);
    }

    #[test]
    fn numbers_convert_and_saturate() {
        let mut img = [0u8; 16];
        write(&mut img, &place(0, None, E::Int), Value::Int(70_000));
        assert_eq!(
            read(&img, &place(0, None, E::Int)),
            Some(Value::Int(32_767))
        );
        write(&mut img, &place(0, None, E::Uint), Value::Real(4095.4));
        assert_eq!(read(&img, &place(0, None, E::Uint)), Some(Value::Int(4095)));
        write(&mut img, &place(0, None, E::Int), Value::Int(-3));
        assert_eq!(read(&img, &place(0, None, E::Int)), Some(Value::Int(-3)));
        write(&mut img, &place(4, None, E::Real), Value::Real(2.5));
        assert_eq!(read(&img, &place(4, None, E::Real)), Some(Value::Real(2.5)));
        write(&mut img, &place(8, None, E::Lreal), Value::Int(7));
        assert_eq!(
            read(&img, &place(8, None, E::Lreal)),
            Some(Value::Real(7.0))
        );
        write(&mut img, &place(12, None, E::Sint), Value::Real(-300.0));
        assert_eq!(
            read(&img, &place(12, None, E::Sint)),
            Some(Value::Int(-128))
        );
    }

    #[test]
    fn the_direct_read_is_the_general_read() {
        // Bytes with the sign bits set and the high bit of a u64; some reals
        // are NaN (compared by their printed form).
        let img = [
            0x81, 0xff, 0x80, 0x7f, 0x00, 0x00, 0x20, 0xc1, 0xfe, 0xff, 0xff, 0xff, 0xff, 0xff,
            0xff, 0xff,
        ];
        let types = [
            E::Bool,
            E::Sint,
            E::Int,
            E::Dint,
            E::Lint,
            E::Usint,
            E::Uint,
            E::Udint,
            E::Ulint,
            E::Byte,
            E::Word,
            E::Dword,
            E::Lword,
            E::Real,
            E::Lreal,
            E::Time,
            E::Ltime,
        ];
        let mut compared = 0;
        for ty in types {
            for offset in [0, 3, 4, 8, 15, 16] {
                for bit in [None, Some(0), Some(7), Some(8)] {
                    let p = place(offset, bit, ty);
                    let direct = read_direct(&img, &p);
                    assert!(direct.is_some(), "{ty:?} takes the direct path");
                    assert_eq!(
                        format!("{:?}", direct.flatten()),
                        format!("{:?}", read_general(&img, &p)),
                        "{ty:?} at {offset} {bit:?}"
                    );
                    let e = Place {
                        ty: PlaceType::Enum {
                            name: "E".into(),
                            base: ty,
                            values: Vec::new(),
                        },
                        ..p
                    };
                    if ty != E::Bool {
                        assert_eq!(
                            format!("{:?}", read_direct(&img, &e).flatten()),
                            format!("{:?}", read_general(&img, &e))
                        );
                    }
                    compared += 1;
                }
            }
        }
        assert_eq!(compared, 17 * 6 * 4);
        // Ulint beyond i64 saturates on both paths.
        assert_eq!(
            read(&img, &place(8, None, E::Ulint)),
            Some(Value::Int(i64::MAX))
        );
        assert_eq!(
            read(&img, &place(4, None, E::Real)),
            Some(Value::Real(-10.0))
        );
    }
}
