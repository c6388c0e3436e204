//! Small helpers over `roxmltree`: elements by local name (the namespace of
//! TC6 2.0, 2.01 or none is accepted alike), and text with the XML offset
//! of each of its bytes (entities and CDATA sections decoded here, so an
//! ST body keeps exact positions).

use automat_base::{FileId, Span};
use roxmltree::Node;

/// Decoded text with the XML offset of each byte: the syntax layer's
/// graphical text, so what is read here goes into the network model as is.
pub use automat_syntax::graphic::Text;

/// Decodes the raw XML `raw` found at offset `base`: entities, CDATA
/// sections; comments and markup are dropped.
pub fn decode(raw: &str, base: usize) -> Text {
    let mut out = Text::default();
    let bytes = raw.as_bytes();
    let mut i = 0;
    let push = |out: &mut Text, s: &str, at: usize| {
        for _ in 0..s.len() {
            out.raw.push((base + at) as u32);
        }
        out.text.push_str(s);
    };
    while i < bytes.len() {
        let rest = raw.get(i..).unwrap_or("");
        if let Some(r) = rest.strip_prefix("<![CDATA[") {
            let body = r.find("]]>").map_or(r, |e| r.get(..e).unwrap_or(""));
            let start = i + 9;
            for (k, _) in body.char_indices() {
                let ch_len = body
                    .get(k..)
                    .and_then(|s| s.chars().next())
                    .map_or(1, char::len_utf8);
                for j in 0..ch_len {
                    out.raw.push((base + start + k + j) as u32);
                }
            }
            out.text.push_str(body);
            i = start + body.len() + 3;
        } else if rest.starts_with("<!--") {
            i += rest.find("-->").map_or(rest.len(), |e| e + 3);
        } else if rest.starts_with('<') {
            i += rest.find('>').map_or(rest.len(), |e| e + 1);
        } else if rest.starts_with('&') {
            let end = rest.find(';').filter(|&e| e <= 10);
            let ent = end.and_then(|e| rest.get(1..e)).unwrap_or("");
            let decoded = match ent {
                "lt" => Some('<'),
                "gt" => Some('>'),
                "amp" => Some('&'),
                "quot" => Some('"'),
                "apos" => Some('\''),
                _ => ent
                    .strip_prefix("#x")
                    .and_then(|h| u32::from_str_radix(h, 16).ok())
                    .or_else(|| ent.strip_prefix('#').and_then(|d| d.parse().ok()))
                    .and_then(char::from_u32),
            };
            match (decoded, end) {
                (Some(c), Some(e)) => {
                    push(&mut out, c.encode_utf8(&mut [0; 4]), i);
                    i += e + 1;
                }
                _ => {
                    push(&mut out, "&", i);
                    i += 1;
                }
            }
        } else {
            let c = rest.chars().next().unwrap_or(' ');
            push(&mut out, c.encode_utf8(&mut [0; 4]), i);
            i += c.len_utf8();
        }
    }
    out.raw.push((base + i.min(bytes.len())) as u32);
    out
}

/// The text content of an element (CDATA and entities decoded).
pub fn content(src: &str, n: Node) -> Text {
    let r = n.range();
    let Some(first) = n.first_child() else {
        return Text {
            text: String::new(),
            raw: vec![r.end as u32],
        };
    };
    let start = first.range().start;
    let end = src
        .get(..r.end)
        .and_then(|s| s.rfind("</"))
        .filter(|&e| e >= start)
        .unwrap_or(start);
    decode(src.get(start..end).unwrap_or(""), start)
}

/// Formatted text (`<ST>`, `<IL>`, `<documentation>`…): the text of its
/// `xhtml:p`/`xhtml` child when it has one, else its own.
pub fn formatted(src: &str, n: Node) -> Text {
    let mut n = n;
    // Descend through the xhtml wrappers (bounded by the document depth).
    while let Some(c) = n.children().find(|c| c.is_element()) {
        n = c;
    }
    content(src, n)
}

/// An attribute's value with its positions.
pub fn attr(src: &str, n: Node, name: &str) -> Option<Text> {
    let a = n.attributes().find(|a| a.name() == name)?;
    let r = a.range_value();
    Some(decode(src.get(r.clone()).unwrap_or(""), r.start))
}

pub fn attr_str<'a>(n: Node<'a, '_>, name: &str) -> Option<&'a str> {
    n.attributes().find(|a| a.name() == name).map(|a| a.value())
}

pub fn is(n: Node, name: &str) -> bool {
    n.is_element() && n.tag_name().name() == name
}

pub fn child<'a, 'i>(n: Node<'a, 'i>, name: &str) -> Option<Node<'a, 'i>> {
    n.children().find(|c| is(*c, name))
}

pub fn children<'a, 'i: 'a>(
    n: Node<'a, 'i>,
    name: &'a str,
) -> impl Iterator<Item = Node<'a, 'i>> + 'a {
    n.children().filter(move |c| is(*c, name))
}

pub fn elements<'a, 'i: 'a>(n: Node<'a, 'i>) -> impl Iterator<Item = Node<'a, 'i>> + 'a {
    n.children().filter(|c| c.is_element())
}

/// The span of an element's start tag (where its diagnostics point).
pub fn span(file: FileId, n: Node) -> Span {
    let r = n.range();
    Span::new(file, r.start as u32, r.end as u32)
}

/// A `TRUE`/`true`/`1` attribute.
pub fn flag(n: Node, name: &str) -> bool {
    matches!(attr_str(n, name), Some("true" | "TRUE" | "1"))
}
