//! ISaGRAF program sections: Begin, Sequential, End.
//!
//! An ISaGRAF cycle runs the Begin programs (input conditioning), then the
//! Sequential ones (the charts), then the End programs (output protection).
//! Here a PROGRAM is put in a section by a pragma right before it:
//!
//! ```text
//! {section begin}
//! PROGRAM Inputs ... END_PROGRAM
//! ```
//!
//! When a project marks any program and has no CONFIGURATION, the rewrite
//! adds one (named `__ISAGRAF`) whose implicit resource instantiates every
//! PROGRAM under its own name, without a task, in the order: Begin programs,
//! Sequential programs (marked or not marked), End programs, each group in
//! file and text order. Programs without a task all run, in declaration
//! order, in the one cyclic task of `--cycle-time`, so this is exactly one
//! ISaGRAF cycle per scan; paths stay `Inputs.x`. A project that has its
//! own CONFIGURATION keeps it: the pragmas are then ignored (W150).
//!
//! Diagnostics: E152 unknown section name, E153 a section pragma that does
//! not come right before a PROGRAM, E154 an SFC program in Begin or End
//! (ISaGRAF runs charts only in the Sequential section).

use crate::pragma::SectionMark;
use automat_base::{Code, Diagnostic, FileId, Interner, Span};
use automat_syntax::ast::{
    Configuration, Ident, Item, Lang, PouKind, ProgramConfig, Resource, Retain, SourceUnit,
};

#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Section {
    Begin,
    Sequential,
    End,
}

impl Section {
    fn from_word(w: &str) -> Option<Section> {
        Some(match w.to_ascii_lowercase().as_str() {
            "begin" | "prl" => Section::Begin,
            "sequential" | "chart" => Section::Sequential,
            "end" | "post" => Section::End,
            _ => return None,
        })
    }
}

/// Reads the marks of every file, and adds the configuration when the
/// project marked a program (or has child charts, which run as programs
/// beside their parents) and has none.
pub fn synthesize(
    units: &mut [SourceUnit],
    marks: &[(FileId, Vec<SectionMark>)],
    has_children: bool,
    interner: &mut Interner,
    diags: &mut Vec<Diagnostic>,
) {
    // (section, program name) in file and text order.
    let mut placed: Vec<(Section, Ident, Span)> = Vec::new();
    for unit in units.iter() {
        let Some((_, file_marks)) = marks.iter().find(|(f, _)| *f == unit.file) else {
            continue;
        };
        for m in file_marks {
            let Some(section) = Section::from_word(&m.word) else {
                diags.push(
                    Diagnostic::error(Code::E152, m.span, format!("unknown section `{}`", m.word))
                        .with_note("the ISaGRAF sections are begin, sequential and end"),
                );
                continue;
            };
            match program_after(unit, m.span) {
                Some((name, lang_is_sfc)) => {
                    if lang_is_sfc && section != Section::Sequential {
                        diags.push(Diagnostic::error(
                            Code::E154,
                            m.span,
                            "an SFC program can only be in the sequential section",
                        ));
                        continue;
                    }
                    placed.push((section, name, m.span));
                }
                None => diags.push(Diagnostic::error(
                    Code::E153,
                    m.span,
                    "a section pragma must come right before a PROGRAM",
                )),
            }
        }
    }
    if placed.is_empty() && !has_children {
        return;
    }
    if units
        .iter()
        .any(|u| u.items.iter().any(|i| matches!(i, Item::Config(_))))
    {
        for (_, _, span) in &placed {
            diags.push(Diagnostic::warning(
                Code::W150,
                *span,
                "section ignored: the project has a CONFIGURATION, whose tasks decide the order",
            ));
        }
        return;
    }
    // Every PROGRAM in file and text order, in its section (Sequential when
    // no pragma placed it).
    let mut ordered: Vec<(Section, Ident, Span)> = Vec::new();
    for unit in units.iter() {
        for item in &unit.items {
            if let Item::Pou(p) = item {
                if p.kind == PouKind::Program {
                    let section = placed
                        .iter()
                        .find(|(_, n, _)| n.sym == p.name.sym)
                        .map_or(Section::Sequential, |(s, _, _)| *s);
                    ordered.push((section, p.name, p.name.span));
                }
            }
        }
    }
    // Stable: the text order inside each section is kept.
    ordered.sort_by_key(|(s, _, _)| *s);
    let placed = ordered;
    let Some(first) = units.first_mut() else {
        return;
    };
    // The generated configuration points at the first program it runs.
    let span = placed.first().map_or_else(Span::default, |p| p.2);
    let programs = placed
        .iter()
        .map(|(_, name, _)| ProgramConfig {
            retain: Retain::Unspecified,
            name: *name,
            task: None,
            ty: *name,
            conns: Vec::new(),
            span: name.span,
        })
        .collect();
    let config = Configuration {
        name: Ident {
            sym: interner.intern("__ISAGRAF"),
            span,
        },
        globals: Vec::new(),
        resources: vec![Resource {
            name: Ident {
                sym: interner.intern("__SECTIONS"),
                span,
            },
            on: None,
            implicit: true,
            globals: Vec::new(),
            tasks: Vec::new(),
            programs,
            span,
        }],
        access: Vec::new(),
        var_config: Vec::new(),
        span,
    };
    first.items.push(Item::Config(config));
}

/// The PROGRAM that is the first item after the pragma (its name, and
/// whether it is written in SFC).
fn program_after(unit: &SourceUnit, mark: Span) -> Option<(Ident, bool)> {
    let next = unit
        .items
        .iter()
        .filter(|i| item_start(i) >= mark.end)
        .min_by_key(|i| item_start(i))?;
    match next {
        Item::Pou(p) if p.kind == PouKind::Program => {
            Some((p.name, matches!(p.lang, Lang::Sfc(_))))
        }
        _ => None,
    }
}

fn item_start(i: &Item) -> u32 {
    match i {
        Item::Pou(p) => p.span.start,
        Item::Types(t) => t.span.start,
        Item::Globals(g) => g.span.start,
        Item::Config(c) => c.span.start,
        Item::Class(c) => c.span.start,
        Item::Interface(i) => i.span.start,
        Item::Namespace(n) => n.span.start,
    }
}
