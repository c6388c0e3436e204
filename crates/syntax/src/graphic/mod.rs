//! The graphical model of LD and FBD bodies, beside the ST, IL and SFC
//! trees, and its lowering into them.
//!
//! One model for every graphical front end (PLCopen TC6 XML, the
//! Allen-Bradley ladder): a [`model::Network`] is a list of elements
//! (rails, contacts, coils, blocks, variables, labels, jumps, returns,
//! connectors) whose input pins name the output pins they are wired to.
//! [`lower::lower`] writes it as Structured Text statements in execution
//! order (`lower.rs` states the rules) with hidden BOOLs for power flow and
//! edge memories; the front end puts them in the POU it generates
//! ([`generated::Generated`], text with the source bytes of each piece), and
//! [`parse_generated`] parses that text into the usual tree, every span and
//! diagnostic moved back into the source file and the jump markers turned
//! into `Goto`/`Label` statements. Everything after (checker, IR, both
//! engines) sees ordinary POUs: there is no graphical special case there.
//!
//! [`build::Builder`] makes a network in code, for a front end without a
//! drawing: it numbers the elements, adds the left rail, places each rung
//! below the previous one and binds block pins to variables.

pub mod build;
pub mod generated;
mod jumps;
pub mod lower;
pub mod model;
mod remap;
pub mod text;

pub use generated::Generated;
pub use jumps::{GOTO_MARK, LABEL_MARK};
pub use lower::{lower, Lowered, Piece, PouCtx};
pub use model::*;
pub use text::Text;

use crate::ast::{Body, Item, SourceUnit};
use crate::{Options, Parsed};
use automat_base::{Diagnostic, FileId, Interner};

/// An IEC 61131-3 identifier: a letter or `_`, then letters, digits, `_`.
pub fn is_identifier(s: &str) -> bool {
    let mut chars = s.chars();
    chars
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// Parses text a front end generated for source file `file`: the tree and
/// the parser's diagnostics are moved into the source through
/// [`Generated::map`], the jump and label markers become statements, and
/// `front` (the front end's own diagnostics, already in source spans) is
/// merged in; all sorted by position.
pub fn parse_generated(
    file: FileId,
    out: &Generated,
    front: Vec<Diagnostic>,
    interner: &mut Interner,
    opts: Options,
) -> Parsed {
    let parsed = crate::parse_with(file, &out.text, interner, opts);
    let remap = remap::Remap { out };
    let mut unit = parsed.unit;
    for item in &mut unit.items {
        remap.item(item);
    }
    for item in &mut unit.items {
        if let Item::Pou(p) = item {
            let Body::St(stmts) = &mut p.body;
            jumps::rewrite(stmts, interner);
        }
    }
    let mut diagnostics = front;
    for mut d in parsed.diagnostics {
        remap.diag(&mut d);
        diagnostics.push(d);
    }
    diagnostics.sort_by_key(|d| d.span.start);
    Parsed {
        unit: SourceUnit {
            file,
            items: unit.items,
        },
        diagnostics,
    }
}
