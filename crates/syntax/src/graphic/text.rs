//! Text of a graphical element (a variable, an expression, a block's type or
//! instance name) with the source offset of each of its bytes.
//!
//! Per-byte offsets let a front end whose text is decoded on the way (XML
//! entities and CDATA sections) keep exact positions: a diagnostic on the
//! third byte of `a &lt; b` points at the third character of the entity in
//! the file. A front end reading plain text uses [`Text::at`] (byte `i` is
//! at `start + i`), one whose text has no place of its own (a name it made
//! up) uses [`Text::generated`] (every byte stands for one span).

use automat_base::{FileId, Span};

/// Text and, for each byte of it (plus one for its end), the offset in the
/// source file it came from (the file is the one of the element's span).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Text {
    pub text: String,
    /// `text.len() + 1` offsets, non-decreasing.
    pub raw: Vec<u32>,
}

impl Text {
    /// `text` written in the source at byte `start`, byte for byte.
    pub fn at(text: &str, start: u32) -> Text {
        let raw = (0..=text.len() as u32)
            .map(|i| start.saturating_add(i))
            .collect();
        Text {
            text: text.to_string(),
            raw,
        }
    }

    /// `text` standing as a whole for the source range `span` (every byte
    /// maps to its start, the end to its end).
    pub fn generated(text: &str, span: Span) -> Text {
        let mut raw = vec![span.start; text.len()];
        raw.push(span.end.max(span.start));
        Text {
            text: text.to_string(),
            raw,
        }
    }

    /// Without leading and trailing white space (offsets kept).
    pub fn trimmed(&self) -> Text {
        let start = self.text.len() - self.text.trim_start().len();
        let end = self.text.trim_end().len().max(start);
        Text {
            text: self.text.get(start..end).unwrap_or("").to_string(),
            raw: self
                .raw
                .get(start..=end)
                .map(<[u32]>::to_vec)
                .unwrap_or_default(),
        }
    }

    /// The source range of the whole text.
    pub fn span(&self, file: FileId) -> Span {
        let s = self.raw.first().copied().unwrap_or(0);
        let e = self.raw.last().copied().unwrap_or(s);
        Span::new(file, s, e.max(s))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn at_and_generated_offsets() {
        let t = Text::at("ab", 10);
        assert_eq!(t.raw, vec![10, 11, 12]);
        assert_eq!(t.span(FileId(0)), Span::new(FileId(0), 10, 12));
        let g = Text::generated("xyz", Span::new(FileId(0), 4, 9));
        assert_eq!(g.raw, vec![4, 4, 4, 9]);
        let s = Text::at("  a ", 0).trimmed();
        assert_eq!((s.text.as_str(), s.raw), ("a", vec![2, 3]));
    }
}
