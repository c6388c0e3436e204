//! PLCopen TC6 XML (schema 2.01 and 2.0) into automat's trees.
//!
//! [`import`] reads one XML file with `roxmltree` and returns the same
//! [`Parsed`] the ST parser returns: data types, POUs with every variable
//! section, ST and IL bodies, LD and FBD networks, configurations with
//! their resources, tasks, program instances and globals. Everything after
//! it (checker, lowering, both engines) is unchanged.
//!
//! How: each element is written as the Structured Text it means into one
//! generated text (`out.rs`), which the ST parser parses (so IL bodies are
//! desugared as in `.il` files, and a malformed expression gets the ST
//! parser's message); every span of the tree and of the diagnostics is then
//! moved back to the XML bytes it came from. LD and FBD bodies are read
//! (`graph.rs`) into the syntax layer's graphical network model
//! (`automat_syntax::graphic`), which lowers them to ST statements in their
//! execution order; the generated text, its span map and the parsing back
//! are the syntax layer's too (`graphic::Generated`,
//! `graphic::parse_generated`), shared with the other graphical front ends.
//!
//! Invariants: never panics on any input; every diagnostic has a code
//! (E170–E177 for the importer's own) and a span in the XML file; names
//! from attributes are checked to be identifiers before they are written
//! into the generated text, so an attribute can never change the structure
//! of the program around it.

mod config;
mod decl;
mod export;
mod graph;
mod macros;
mod names;
mod pou;
mod sfc;
pub mod sheet;
pub mod xml;

use automat_base::{Code, Diagnostic, FileId, Interner, Span};
use automat_syntax::graphic::Generated as Out;
use automat_syntax::Parsed;
pub use export::export;
use roxmltree::{Document, Node, ParsingOptions};

/// Whether a source file is read by this importer (by its name).
pub fn is_plcopen_file(name: &str) -> bool {
    name.rsplit('.')
        .next()
        .is_some_and(|e| e.eq_ignore_ascii_case("xml"))
        && name.contains('.')
}

/// Caps the tree a file may build (a fuzzed file cannot exhaust memory).
pub(crate) const NODES_LIMIT: u32 = 4_000_000;

/// The Structured Text an XML file is read as (for tests and for looking at
/// what an LD or FBD body means), with the importer's own diagnostics.
pub fn generated_st(file: FileId, src: &str) -> (String, Vec<Diagnostic>) {
    let imp = generate(file, src);
    (imp.out.text, imp.diags)
}

/// Reads one PLCopen XML file. Never panics, never fails: errors are
/// diagnostics next to the tree of what could be read.
pub fn import(file: FileId, src: &str, interner: &mut Interner) -> Parsed {
    let imp = generate(file, src);
    let Imp {
        out, diags, macros, ..
    } = imp;
    let opts = automat_syntax::Options::default();
    let mut parsed = automat_syntax::graphic::parse_generated(file, &out, diags, interner, opts);
    macros::attach(&mut parsed, &macros, interner);
    parsed
}

fn generate<'s>(file: FileId, src: &'s str) -> Imp<'s> {
    let mut imp = Imp {
        file,
        src,
        out: Out::default(),
        diags: Vec::new(),
        macros: Vec::new(),
    };
    let opts = ParsingOptions {
        allow_dtd: false,
        nodes_limit: NODES_LIMIT,
        ..ParsingOptions::default()
    };
    match Document::parse_with_options(src, opts) {
        Ok(doc) => imp.project(doc.root_element()),
        Err(e) => {
            let pos = e.pos();
            let at = offset_of(src, pos.row, pos.col);
            imp.error(
                Code::E170,
                Span::new(file, at, at),
                format!("not well-formed XML: {e}"),
            );
        }
    }
    imp
}

/// The byte offset of a 1-based row and column (as `roxmltree` reports).
fn offset_of(src: &str, row: u32, col: u32) -> u32 {
    let mut off = 0usize;
    for (i, line) in src.split_inclusive('\n').enumerate() {
        if i + 1 == row as usize {
            let col = (col as usize).saturating_sub(1);
            let mut k = line.char_indices().nth(col).map_or(line.len(), |(k, _)| k);
            k = k.min(line.len());
            return (off + k) as u32;
        }
        off += line.len();
    }
    src.len() as u32
}

/// The importer's state for one file.
pub(crate) struct Imp<'s> {
    pub file: FileId,
    pub src: &'s str,
    pub out: Out,
    pub diags: Vec<Diagnostic>,
    /// Macro-steps whose bodies were written as hidden blocks (`macros.rs`).
    pub macros: Vec<macros::Link>,
}

impl<'s> Imp<'s> {
    pub fn error(&mut self, code: Code, span: Span, msg: impl Into<String>) {
        self.diags.push(Diagnostic::error(code, span, msg));
    }

    pub fn span(&self, n: Node) -> Span {
        xml::span(self.file, n)
    }

    /// Generated words standing for element `n`.
    pub fn gen(&mut self, s: &str, n: Node) {
        let sp = self.span(n);
        self.out.gen(s, sp);
    }

    fn project(&mut self, root: Node) {
        if !xml::is(root, "project") {
            let sp = self.span(root);
            self.error(
                Code::E170,
                sp,
                format!(
                    "the root element is `{}`, not a PLCopen TC6 `project`",
                    root.tag_name().name()
                ),
            );
            return;
        }
        if let Some(types) = xml::child(root, "types") {
            if let Some(dts) = xml::child(types, "dataTypes") {
                for dt in xml::children(dts, "dataType") {
                    self.data_type(dt);
                }
            }
            if let Some(pous) = xml::child(types, "pous") {
                for p in xml::children(pous, "pou") {
                    self.pou(p);
                }
            }
        }
        if let Some(inst) = xml::child(root, "instances") {
            if let Some(cfgs) = xml::child(inst, "configurations") {
                for c in xml::children(cfgs, "configuration") {
                    self.configuration(c);
                }
            }
        }
    }
}

/// Names the LD, FBD or SFC element each diagnostic of `file` points into:
/// a diagnostic of the checker (an unknown name, a type mismatch at a pin)
/// whose span lies inside an element with a `localId` gets the prefix
/// "POU `P`, localId N: " the importer's own diagnostics have. Diagnostics
/// of other files, outside graphical elements, or already naming a POU are
/// left as they are.
pub fn name_elements(file: FileId, src: &str, diags: &mut [Diagnostic]) {
    if !diags.iter().any(|d| d.span.file == file) {
        return;
    }
    let opts = ParsingOptions {
        allow_dtd: false,
        nodes_limit: NODES_LIMIT,
        ..ParsingOptions::default()
    };
    let Ok(doc) = Document::parse_with_options(src, opts) else {
        return;
    };
    // (start, end, pou, localId) of every element with a localId in a body.
    let mut elems: Vec<(usize, usize, String, String)> = Vec::new();
    for n in doc.descendants().filter(|n| n.is_element()) {
        let Some(id) = xml::attr_str(n, "localId") else {
            continue;
        };
        let Some(pou) = n
            .ancestors()
            .find(|a| xml::is(*a, "pou"))
            .and_then(|p| xml::attr_str(p, "name"))
        else {
            continue;
        };
        let r = n.range();
        elems.push((
            r.start,
            r.end,
            pou.trim().to_string(),
            id.trim().to_string(),
        ));
    }
    // Document order is start order. Elements of a body are siblings; only
    // an action block holds elements with a localId (its actions), so the
    // innermost element holding an offset is among the last few that start
    // before it: a bounded look back keeps this linear in the diagnostics.
    const LOOK_BACK: usize = 8;
    for d in diags.iter_mut().filter(|d| d.span.file == file) {
        if d.message.starts_with("POU `") {
            continue;
        }
        let at = d.span.start as usize;
        let upto = elems.partition_point(|(s, _, _, _)| *s <= at);
        let inner = elems[upto.saturating_sub(LOOK_BACK)..upto]
            .iter()
            .filter(|(_, e, _, _)| at < *e)
            .min_by_key(|(s, e, _, _)| e - s);
        if let Some((_, _, pou, id)) = inner {
            d.message = format!("POU `{pou}`, localId {id}: {}", d.message);
        }
    }
}
