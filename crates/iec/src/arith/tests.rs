use super::*;
use crate::error::ErrorKind;

#[test]
fn division_truncates_toward_zero_on_every_width() {
    assert_eq!(div(7i8, 2), Ok(3));
    assert_eq!(div(-7i16, 2), Ok(-3));
    assert_eq!(div(7i32, -2), Ok(-3));
    assert_eq!(div(-7i64, -2), Ok(3));
    assert_eq!(div(7u8, 2), Ok(3));
    assert_eq!(div(65535u16, 256), Ok(255));
    assert_eq!(div(u32::MAX, 3), Ok(1431655765));
    assert_eq!(div(u64::MAX, u64::MAX), Ok(1));
    assert_eq!(div(i8::MIN, -1), Ok(i8::MIN));
    assert_eq!(div(i64::MIN, -1), Ok(i64::MIN));
    assert_eq!(div(i32::MIN, 1), Ok(i32::MIN));
}

#[test]
fn modulo_has_the_dividends_sign() {
    assert_eq!(modulo(7i16, 2), Ok(1));
    assert_eq!(modulo(-7i16, 2), Ok(-1));
    assert_eq!(modulo(7i32, -2), Ok(1));
    assert_eq!(modulo(-7i64, -2), Ok(-1));
    assert_eq!(modulo(10u8, 3), Ok(1));
    assert_eq!(modulo(i8::MIN, -1), Ok(0));
    assert_eq!(modulo(i64::MIN, -1), Ok(0));
    assert_eq!(modulo(-6i32, 3), Ok(0));
}

#[test]
fn division_by_zero_is_an_error() {
    let e = div(5i32, 0).map_err(|e| (e.kind, e.message));
    assert_eq!(
        e,
        Err((
            ErrorKind::DivisionByZero,
            "DIV: division by zero".to_string()
        ))
    );
    let e = modulo(5u8, 0).map_err(|e| (e.kind, e.message));
    assert_eq!(
        e,
        Err((
            ErrorKind::DivisionByZero,
            "MOD: division by zero".to_string()
        ))
    );
    assert!(div(i64::MIN, 0).is_err());
    assert!(modulo(0u64, 0).is_err());
}

#[test]
fn overflow_wraps() {
    assert_eq!(add(i16::MAX, 1), i16::MIN);
    assert_eq!(add(255u8, 1), 0);
    assert_eq!(sub(0u32, 1), u32::MAX);
    assert_eq!(sub(i8::MIN, 1), i8::MAX);
    assert_eq!(mul(i32::MAX, 2), -2);
    assert_eq!(mul(300u16, 300), 24464);
    assert_eq!(neg(i8::MIN), i8::MIN);
    assert_eq!(neg(5i64), -5);
    assert_eq!(abs(i16::MIN), i16::MIN);
    assert_eq!(abs(-5i32), 5);
    assert_eq!(abs(i64::MIN + 1), i64::MAX);
}

#[test]
fn expt_on_reals() {
    assert_eq!(expt_lreal(2.0, 10.0), 1024.0);
    assert_eq!(expt_lreal(2.0, -1.0), 0.5);
    assert_eq!(expt_lreal(9.0, 0.5), 3.0);
    assert_eq!(expt_lreal(0.0, -1.0), f64::INFINITY);
    assert!(expt_lreal(-8.0, 1.0 / 3.0).is_nan());
    assert_eq!(expt_lreal(f64::NAN, 0.0), 1.0);
    assert_eq!(expt_real(2.0, 0.5), std::f32::consts::SQRT_2);
    assert_eq!(expt_real(10.0, 38.0), 1e38);
    assert_eq!(expt_real(10.0, 39.0), f32::INFINITY);
    assert_eq!(expt_lreal_int(-2.0, 3), -8.0);
    assert_eq!(expt_lreal_int(2.0, -2), 0.25);
    assert_eq!(expt_lreal_int(2.0, 1 << 40), f64::INFINITY);
    assert_eq!(expt_lreal_int(-1.0, (1 << 40) + 1), -1.0);
    assert_eq!(expt_real_int(3.0, 4), 81.0);
    assert_eq!(expt_real_int(0.5, i64::MAX), 0.0);
}

#[test]
fn expt_on_integers() {
    assert_eq!(expt_int(2i32, 10), Ok(1024));
    assert_eq!(expt_int(-3i16, 3), Ok(-27));
    assert_eq!(expt_int(7u8, 0), Ok(1));
    assert_eq!(expt_int(0i32, 0), Ok(1));
    assert_eq!(expt_int(2i8, 7), Ok(-128));
    assert_eq!(expt_int(2u8, 8), Ok(0));
    assert_eq!(expt_int(3i64, 40), Ok(12157665459056928801i128 as i64));
    assert_eq!(expt_int(1i32, -5), Ok(1));
    assert_eq!(expt_int(-1i32, -5), Ok(-1));
    assert_eq!(expt_int(-1i32, -4), Ok(1));
    assert_eq!(expt_int(2i32, -1), Ok(0));
    assert_eq!(expt_int(-1i64, i64::MAX), Ok(-1));
    assert_eq!(
        expt_int(0i32, -1).map_err(|e| e.message),
        Err("EXPT: 0 raised to a negative power".to_string())
    );
}

#[test]
fn shifts_on_every_width() {
    assert_eq!(shl(0x81u8, 1), 0x02);
    assert_eq!(shl(0x8001u16, 4), 0x0010);
    assert_eq!(shl(1u32, 31), 0x8000_0000);
    assert_eq!(shl(1u64, 63), 1 << 63);
    assert_eq!(shl(0xFFu8, 8), 0);
    assert_eq!(shl(0xFFFFu16, 100), 0);
    assert_eq!(shr(0x80u8, 7), 1);
    assert_eq!(shr(0xF000u16, 12), 0xF);
    assert_eq!(shr(u32::MAX, 32), 0);
    assert_eq!(shr(u64::MAX, 63), 1);
    assert_eq!(shr(-1i16, 4), 0x0FFF);
    assert_eq!(shl(1u8, -1), 0);
    assert_eq!(shr(0xFFu8, i64::MIN), 0);
    assert_eq!(shl(0x12u8, 0), 0x12);
}

#[test]
fn rotations_on_every_width() {
    assert_eq!(rol(0x81u8, 1), 0x03);
    assert_eq!(ror(0x81u8, 1), 0xC0);
    assert_eq!(rol(0x1234u16, 4), 0x2341);
    assert_eq!(ror(0x1234u16, 4), 0x4123);
    assert_eq!(rol(0x8000_0001u32, 1), 0x0000_0003);
    assert_eq!(ror(1u64, 1), 1 << 63);
    assert_eq!(rol(0x81u8, 8), 0x81);
    assert_eq!(rol(0x81u8, 9), 0x03);
    assert_eq!(ror(0x1234u16, 20), 0x4123);
    assert_eq!(rol(0x81u8, -1), 0xC0);
    assert_eq!(ror(0x81u8, -1), 0x03);
    assert_eq!(rol(0xDEAD_BEEF_0000_0001u64, 64), 0xDEAD_BEEF_0000_0001);
    assert_eq!(not(0x0Fu8), 0xF0);
    assert_eq!(not(0u64), u64::MAX);
}

#[test]
fn selection() {
    assert_eq!(max(3, 5), 5);
    assert_eq!(min(3, 5), 3);
    assert_eq!(max_of(&[3, 9, -2]), Some(9));
    assert_eq!(min_of(&[3, 9, -2]), Some(-2));
    assert_eq!(max_of::<i32>(&[]), None);
    assert!(max(f64::NAN, 1.0).is_nan());
    assert_eq!(max(1.0, f64::NAN), 1.0);
    assert_eq!(limit(0, 5, 10), 5);
    assert_eq!(limit(0, -5, 10), 0);
    assert_eq!(limit(0, 15, 10), 10);
    assert_eq!(limit(10, 5, 0), 0);
    assert_eq!(limit(0.0, 2.5, 1.0), 1.0);
    assert_eq!(sel(false, 'a', 'b'), 'a');
    assert_eq!(sel(true, 'a', 'b'), 'b');
    assert_eq!(mux(1, &[10, 20, 30]), Ok(20));
    assert_eq!(mux(0, &["x"]), Ok("x"));
    assert_eq!(
        mux(3, &[10, 20, 30]).map_err(|e| (e.kind, e.message)),
        Err((
            ErrorKind::SelectorRange,
            "MUX: K = 3 selects no input (there are 3 inputs, K must be in 0..=2)".to_string()
        ))
    );
    assert!(mux(-1, &[1]).is_err());
    assert!(mux::<i32>(0, &[]).is_err());
}

#[test]
fn division_at_the_limits_of_unsigned_and_signed_widths() {
    assert_eq!(div(u8::MAX, 1), Ok(255));
    assert_eq!(div(i16::MIN, 2), Ok(-16384));
    assert_eq!(div(i16::MIN, i16::MAX), Ok(-1));
    assert_eq!(modulo(i16::MIN, i16::MAX), Ok(-1));
    assert_eq!(modulo(u16::MAX, 256), Ok(255));
    assert_eq!(div(1i32, i32::MIN), Ok(0));
    assert_eq!(modulo(1i32, i32::MIN), Ok(1));
    assert_eq!(div(-1i64, i64::MAX), Ok(0));
}

#[test]
fn shifts_by_width_minus_one() {
    assert_eq!(shl(1u8, 7), 0x80);
    assert_eq!(shl(3u8, 7), 0x80);
    assert_eq!(shr(0xFFFFu16, 15), 1);
    assert_eq!(rol(1u32, 31), 0x8000_0000);
    assert_eq!(ror(1u32, 31), 2);
    assert_eq!(rol(0x8000_0000_0000_0000u64, 63), 0x4000_0000_0000_0000);
    assert_eq!(shl(-1i8, 4), -16);
    assert_eq!(rol(-128i8, 1), 1);
}

#[test]
fn typed_arithmetic_on_each_signed_width() {
    assert_eq!(add(100i8, 100), -56);
    assert_eq!(sub(-30000i16, 10000), 25536);
    assert_eq!(mul(65536i32, 65536), 0);
    assert_eq!(add(i64::MAX, i64::MAX), -2);
    assert_eq!(mul(16u8, 16), 0);
    assert_eq!(sub(0u64, 2), u64::MAX - 1);
}
