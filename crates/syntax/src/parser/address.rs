//! Decoding `%` tokens: direct addresses (`%IX1.2.3`, `%QW*`) and the
//! size-and-index of a partial access (`w.%X3`).

use crate::ast::{AddrSize, Area, DirectAddress};
use automat_base::Span;

fn size_of(c: u8) -> Option<AddrSize> {
    Some(match c.to_ascii_uppercase() {
        b'X' => AddrSize::Bit,
        b'B' => AddrSize::Byte,
        b'W' => AddrSize::Word,
        b'D' => AddrSize::DWord,
        b'L' => AddrSize::LWord,
        _ => return None,
    })
}

/// Splits `%` + letters + rest.
fn split(text: &str) -> (&str, &str) {
    let body = text.strip_prefix('%').unwrap_or(text);
    let n = body.bytes().take_while(|b| b.is_ascii_alphabetic()).count();
    body.split_at(n)
}

fn number(text: &str, part: &str) -> Result<u32, String> {
    if part.is_empty() || !part.bytes().all(|b| b.is_ascii_digit()) {
        return Err(format!(
            "invalid direct address `{text}`: expected numbers separated by dots"
        ));
    }
    part.parse::<u32>()
        .map_err(|_| format!("invalid direct address `{text}`: `{part}` is too large"))
}

/// `%` I|Q|M, an optional size X|B|W|D|L, then `*` or dotted numbers.
pub fn decode_address(text: &str, span: Span) -> Result<DirectAddress, String> {
    let (letters, rest) = split(text);
    let l = letters.as_bytes();
    let area = match l.first().map(u8::to_ascii_uppercase) {
        Some(b'I') => Area::Input,
        Some(b'Q') => Area::Output,
        Some(b'M') => Area::Memory,
        _ => {
            return Err(format!(
                "invalid direct address `{text}`: expected I, Q or M after `%`"
            ))
        }
    };
    let size = match l.get(1) {
        None => AddrSize::None,
        Some(&c) => size_of(c).ok_or_else(|| {
            format!(
                "invalid direct address `{text}`: `{}` is not a size (X, B, W, D or L)",
                c as char
            )
        })?,
    };
    if l.len() > 2 {
        return Err(format!(
            "invalid direct address `{text}`: expected numbers after `%{}`",
            &letters[..2]
        ));
    }
    if rest == "*" {
        return Ok(DirectAddress {
            area,
            size,
            path: Vec::new(),
            partial: true,
            span,
        });
    }
    if rest.is_empty() {
        return Err(format!(
            "invalid direct address `{text}`: expected numbers or `*` after `%{letters}`"
        ));
    }
    let path = rest
        .split('.')
        .map(|p| number(text, p))
        .collect::<Result<Vec<u32>, String>>()?;
    Ok(DirectAddress {
        area,
        size,
        path,
        partial: false,
        span,
    })
}

/// `%X3`, `%B1`, `%W0`, `%D0`, `%L0` after a dot.
pub fn decode_partial(text: &str) -> Result<(AddrSize, u32), String> {
    let (letters, rest) = split(text);
    let bad = || {
        format!(
            "invalid partial access `{text}`: expected `%X`, `%B`, `%W`, `%D` or `%L` and a number"
        )
    };
    let size = match letters.as_bytes() {
        [c] => size_of(*c).ok_or_else(bad)?,
        _ => return Err(bad()),
    };
    if rest.is_empty() || !rest.bytes().all(|b| b.is_ascii_digit()) {
        return Err(bad());
    }
    let index = rest
        .parse::<u32>()
        .map_err(|_| format!("invalid partial access `{text}`: `{rest}` is too large"))?;
    Ok((size, index))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn addr(text: &str) -> Result<(Area, AddrSize, Vec<u32>, bool), String> {
        decode_address(text, Span::default()).map(|a| (a.area, a.size, a.path, a.partial))
    }

    #[test]
    fn addresses() {
        assert_eq!(
            addr("%IX0.1"),
            Ok((Area::Input, AddrSize::Bit, vec![0, 1], false))
        );
        assert_eq!(
            addr("%QW4"),
            Ok((Area::Output, AddrSize::Word, vec![4], false))
        );
        assert_eq!(
            addr("%md48"),
            Ok((Area::Memory, AddrSize::DWord, vec![48], false))
        );
        assert_eq!(
            addr("%IX1.2.3"),
            Ok((Area::Input, AddrSize::Bit, vec![1, 2, 3], false))
        );
        assert_eq!(
            addr("%I0.1"),
            Ok((Area::Input, AddrSize::None, vec![0, 1], false))
        );
        assert_eq!(
            addr("%QL7"),
            Ok((Area::Output, AddrSize::LWord, vec![7], false))
        );
        assert_eq!(addr("%I*"), Ok((Area::Input, AddrSize::None, vec![], true)));
        assert_eq!(
            addr("%QW*"),
            Ok((Area::Output, AddrSize::Word, vec![], true))
        );
    }

    #[test]
    fn bad_addresses() {
        for t in ["%", "%A0", "%IY0", "%IXX0", "%IX", "%I99999999999", "%X3"] {
            assert!(addr(t).is_err(), "{t}");
        }
    }

    #[test]
    fn partials() {
        assert_eq!(decode_partial("%X3"), Ok((AddrSize::Bit, 3)));
        assert_eq!(decode_partial("%b1"), Ok((AddrSize::Byte, 1)));
        assert_eq!(decode_partial("%W0"), Ok((AddrSize::Word, 0)));
        assert_eq!(decode_partial("%D0"), Ok((AddrSize::DWord, 0)));
        assert!(decode_partial("%IX3").is_err());
        assert!(decode_partial("%X").is_err());
        assert!(decode_partial("%Q3").is_err());
        assert!(decode_partial("%X1.2").is_err());
    }
}
