//! REAL/LREAL text: the shortest digits that read back to the same value at
//! the type's precision, laid out like Python's `repr`.

/// An LREAL as text: `3.5`, `4.0`, `-0.0`, `1e-07`, `1.5e+20`, `inf`, `nan`.
pub fn format_lreal(x: f64) -> String {
    if let Some(s) = special(x.is_nan(), x.is_infinite(), x < 0.0) {
        return s;
    }
    // `{:e}` gives the shortest round-trip digits in scientific form.
    layout(&format!("{x:e}"))
}

/// A REAL as text, digits chosen at `f32` precision: 0.1f32 is `0.1`.
///
/// ```
/// use automat_iec::format::{format_lreal, format_real};
/// assert_eq!(format_real(0.1), "0.1");
/// assert_eq!(format_lreal(f64::from(0.1f32)), "0.10000000149011612");
/// assert_eq!(format_lreal(1.5e20), "1.5e+20");
/// ```
pub fn format_real(x: f32) -> String {
    if let Some(s) = special(x.is_nan(), x.is_infinite(), x < 0.0) {
        return s;
    }
    layout(&format!("{x:e}"))
}

fn special(nan: bool, inf: bool, negative: bool) -> Option<String> {
    if nan {
        Some("nan".to_string())
    } else if inf {
        Some(if negative { "-inf" } else { "inf" }.to_string())
    } else {
        None
    }
}

/// Lays out `[-]d[.ddd]e[-]x` (Rust's `{:e}`): positional when the decimal
/// exponent is in −4..16, else `d.ddde±xx` with at least two exponent digits.
fn layout(sci: &str) -> String {
    let (sign, rest) = match sci.strip_prefix('-') {
        Some(r) => ("-", r),
        None => ("", sci),
    };
    let (mantissa, exp) = rest.split_once('e').unwrap_or((rest, "0"));
    let exp: i32 = exp.parse().unwrap_or(0);
    let digits: String = mantissa.chars().filter(|c| c.is_ascii_digit()).collect();
    let (first, more) = digits.split_at(digits.len().min(1));
    if !(-4..16).contains(&exp) {
        let dot = if more.is_empty() { "" } else { "." };
        let esign = if exp < 0 { '-' } else { '+' };
        return format!("{sign}{first}{dot}{more}e{esign}{:02}", exp.unsigned_abs());
    }
    if exp < 0 {
        let zeros = "0".repeat(exp.unsigned_abs() as usize - 1);
        return format!("{sign}0.{zeros}{digits}");
    }
    let int_len = exp as usize + 1;
    if digits.len() <= int_len {
        let zeros = "0".repeat(int_len - digits.len());
        format!("{sign}{digits}{zeros}.0")
    } else {
        let (int_part, frac) = digits.split_at(int_len);
        format!("{sign}{int_part}.{frac}")
    }
}
