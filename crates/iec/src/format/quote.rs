//! Quoted STRING, WSTRING, CHAR and WCHAR text with `$` escapes.

/// The escape of a control character both string kinds share.
fn named_escape(code: u32) -> Option<&'static str> {
    match code {
        0x0A => Some("$N"),
        0x0D => Some("$R"),
        0x09 => Some("$T"),
        0x0C => Some("$P"),
        0x24 => Some("$$"),
        _ => None,
    }
}

/// One STRING byte: printable ASCII as is, `'` as `$'`, `$` as `$$`, LF, CR,
/// tab and form feed as `$N`, `$R`, `$T`, `$P`, any other byte (controls,
/// DEL, 16#80..16#FF) as `$hh`.
fn push_byte(out: &mut String, b: u8) {
    if let Some(e) = named_escape(u32::from(b)) {
        out.push_str(e);
    } else if b == b'\'' {
        out.push_str("$'");
    } else if (0x20..0x7F).contains(&b) {
        out.push(char::from(b));
    } else {
        out.push_str(&format!("${b:02X}"));
    }
}

/// Whether a non-ASCII character prints as itself in a WSTRING: letters and
/// digits of any script and the visible Latin-1 signs; everything else
/// (controls, spaces, invisible format characters) is escaped.
fn shows_as_itself(c: char) -> bool {
    c.is_alphanumeric() || matches!(u32::from(c), 0xA1..=0xAC | 0xAE..=0xBF | 0xD7 | 0xF7 | 0x20AC)
}

/// One WSTRING code unit: like STRING, but `"` is `$"` (and `'` is plain),
/// other units as themselves when they show, else as `$hhhh`.
fn push_unit(out: &mut String, u: u16) {
    if let Some(e) = named_escape(u32::from(u)) {
        out.push_str(e);
        return;
    }
    if u == u16::from(b'"') {
        out.push_str("$\"");
        return;
    }
    match char::from_u32(u32::from(u)) {
        Some(c) if (0x20..0x7F).contains(&u) || (u >= 0x80 && shows_as_itself(c)) => out.push(c),
        _ => out.push_str(&format!("${u:04X}")),
    }
}

/// `'abc'`, `'it$'s'`, `'a$Nb'`, `'$00'`.
pub fn quote_string(s: &[u8]) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('\'');
    for &b in s {
        push_byte(&mut out, b);
    }
    out.push('\'');
    out
}

/// `"abc"`, `"say $"hi$""`, `"caf\u{e9}"`, `"$2028"`.
pub fn quote_wstring(s: &[u16]) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for &u in s {
        push_unit(&mut out, u);
    }
    out.push('"');
    out
}

/// A CHAR: `'a'`.
pub fn quote_char(c: u8) -> String {
    quote_string(&[c])
}

/// A WCHAR: `"a"`.
pub fn quote_wchar(c: u16) -> String {
    quote_wstring(&[c])
}
