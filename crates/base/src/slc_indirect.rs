//! Indexed and indirect SLC-500 addresses: the ones whose word (or bit)
//! is found at run time, parsed (the SLC front end generates the ST that
//! finds them in each scan; the runtime's path resolver finds them in the
//! image at each read or write by name).
//!
//! - indexed `#N7:5`: the word `5 + S:24` of N7 (the index register S:24
//!   holds an offset in elements of the file: words of B and N, floats of F);
//! - indirect `N7:[N7:0]` (the element is the value of N7:0), `N[N7:0]:1`
//!   (the file number is the value of N7:0), `B3:[N7:0]/5`, `B3:0/[N7:2]`
//!   (the bit of the word) and the flat bit `B3/[N7:1]` (bit N7:1 of the
//!   file), as RSLogix 500 writes them.

use crate::slc::{Address, FileType, Part};

/// An address resolved at run time.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Indirect {
    /// The address with its run-time parts at 0 (the element, the bit) or,
    /// for an indirect file, at file 9 of its type.
    pub addr: Address,
    /// `#`: offset by the index register S:24.
    pub indexed: bool,
    /// The word holding the file number (`N[N7:0]:1`).
    pub file_from: Option<Address>,
    /// The word holding the element number (`N7:[N7:0]`).
    pub elem_from: Option<Address>,
    /// The word holding the bit number (`B3:0/[N7:2]`, flat `B3/[N7:1]`).
    pub bit_from: Option<Address>,
    /// `bit_from` numbers the bits of the whole file (`B3/[N7:1]`).
    pub flat: bool,
}

/// Does the operand text name an indexed or indirect address?
pub fn is_dynamic(up: &str) -> bool {
    up.starts_with('#') || up.contains('[')
}

/// The word an indirect part is read from: a word of an integer file
/// (`N7:0`, `T4:0.ACC`), not a bit, a float or another indirect address.
fn pointer(inner: &str) -> Result<Address, String> {
    if is_dynamic(inner) {
        return Err(format!(
            "`[{inner}]`: the word inside `[ ]` is a direct address (no `#`, no nested `[ ]`)"
        ));
    }
    let a = crate::slc::parse(inner)?;
    if a.is_bit() || a.is_structure() || a.ty == FileType::F {
        return Err(format!(
            "`[{inner}]`: the word inside `[ ]` is an integer word (`N7:0`, `T4:0.ACC`), not a bit, a float or a whole element"
        ));
    }
    Ok(a)
}

/// Parses an indexed or indirect address (`up` in upper case: callers
/// upper-case the text, so messages show it as the program names it).
pub fn parse(up: &str) -> Result<Indirect, String> {
    let bad = |why: &str| Err(format!("`{up}`: {why}"));
    if let Some(rest) = up.strip_prefix('#') {
        if rest.contains('[') {
            return bad("an address is indexed (`#N7:0`) or indirect (`N7:[N7:0]`), not both");
        }
        let a = crate::slc::parse(rest)?;
        if a.part != Part::Element || !matches!(a.ty, FileType::B | FileType::N | FileType::F) {
            return bad("an indexed address names a word of a B or N file or a float of an F file (`#N7:0`, `#F8:2`)");
        }
        return Ok(Indirect {
            addr: a,
            indexed: true,
            file_from: None,
            elem_from: None,
            bit_from: None,
            flat: false,
        });
    }
    // Each `[word]` is replaced by a placeholder the direct parser accepts,
    // its place (after the type letter, `:` or `/`) saying what it gives.
    let mut template = String::new();
    let (mut file_from, mut elem_from, mut bit_from, mut flat) = (None, None, None, false);
    let mut rest = up;
    while let Some(open) = rest.find('[') {
        let (head, tail) = rest.split_at(open);
        let Some(close) = tail.find(']') else {
            return bad("`[` without `]`");
        };
        let inner = &tail[1..close];
        template.push_str(head);
        let at = pointer(inner)?;
        let before = template.chars().last();
        let first = template.len() == 1;
        match before {
            Some(c) if first && FileType::from_letter(c).is_some() => {
                if file_from.replace(at).is_some() {
                    return bad("the file is given twice");
                }
                template.push('9');
            }
            Some(':') if elem_from.is_none() => {
                elem_from = Some(at);
                template.push('0');
            }
            Some('/') if bit_from.is_none() => {
                flat = !template.contains(':');
                bit_from = Some(at);
                template.push('0');
            }
            _ => return bad("`[word]` stands for the file number (`N[N7:0]:1`), the element (`N7:[N7:0]`) or the bit (`B3/[N7:1]`, `B3:0/[N7:2]`)"),
        }
        rest = &tail[close + 1..];
    }
    if rest.contains(']') {
        return bad("`]` without `[`");
    }
    template.push_str(rest);
    let addr = crate::slc::parse(&template).map_err(|why| format!("`{up}`: {why}"))?;
    if addr.is_structure() {
        return bad("a whole timer, counter or control element is no operand here");
    }
    if file_from.is_some() {
        if addr.is_bit() || addr.ty == FileType::F {
            return bad("an indirect file number is for words of integer files (`N[N7:0]:1`)");
        }
        if matches!(addr.ty, FileType::I | FileType::O | FileType::S) {
            return bad("O, I and S are files 0, 1 and 2: their number is not indirect");
        }
    }
    Ok(Indirect {
        addr,
        indexed: false,
        file_from,
        elem_from,
        bit_from,
        flat,
    })
}

impl Indirect {
    /// The direct addresses it reads the pointers from.
    pub fn pointers(&self) -> impl Iterator<Item = Address> + '_ {
        self.file_from
            .iter()
            .chain(&self.elem_from)
            .chain(&self.bit_from)
            .copied()
    }
}
