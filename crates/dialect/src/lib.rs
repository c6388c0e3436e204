//! Vendor dialects: the ISaGRAF and PL7 ways of writing IEC 61131-3
//! programs, and their libraries, on top of the standard front end.
//!
//! A project opts in per dialect (`automat check --lib isagraf`,
//! `libraries = ["isagraf"]` in `automat.toml`); without it nothing here
//! changes a program. A dialect is two things:
//! - a *library*: POUs written in Structured Text (`lib/*.st`), added to the
//!   project as one more source file ([`add_libraries`]). A user POU of the
//!   same name replaces the library's, so a project never collides with it;
//! - *rewrites* of the parsed tree before checking ([`check_sources`]): the
//!   dialect's constructs become plain ST plus hidden `__` variables, so the
//!   checker, lowering and every backend see nothing vendor-specific (the
//!   same rule the SFC desugaring follows).
//!
//! ISaGRAF (`timer`, `sections`, `children`, `empty`): TIMER variables with
//! TSTART/TSTOP, the program sections Begin / Sequential / End, child SFC
//! programs (GSTART, GKILL, GFREEZE, GRST, GSTATUS, `child(N|S|R)`), and
//! transitions without a condition (TRUE). PL7 (`pl7`): `%Xi` steps,
//! `%S`/`%SW` system objects, P1/N1/P0 sections in PL7 order, PRL/CHART/POST
//! sections, transitions without a condition (FALSE). The exact semantics
//! are in `docs/vendor-dialects.md`.
//!
//! Coupling to the SFC desugaring (`automat_syntax::desugar::sfc`), which
//! the children, PL7 and empty-transition rewrites build on: step instances
//! named as their steps with inputs `__TICK`/`__E`/`__L` and outputs
//! `X`/`T`; one fire flag `__sfc_t<i>` per transition, cleared then set in
//! precedence order; action bodies as consecutive `IF a.A THEN ...`. The
//! conformance cases `isagraf_*`/`pl7_*` fail if that representation
//! changes.
//!
//! Invariants: never panics on any tree; every rewrite keeps the spans of
//! the text it came from, so diagnostics point at what the user wrote;
//! diagnostics use the codes E150–E169 / W150–W159.

mod boolact;
mod build;
mod children;
mod clock;
mod codesys;
mod empty;
mod fst;
mod heap;
mod heap_size;
mod pl7;
mod pragma;
mod program_access;
mod sections;
pub mod slc;
mod timer;
mod walk;

use automat_base::{Code, Diagnostic, FileId, Interner, SourceMap, Span};
use automat_sema::Analysis;
use automat_syntax::ast::{Item, SourceUnit};

/// A vendor dialect a project can opt into.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Dialect {
    /// ISaGRAF: helper library, TIMER variables, program sections, child
    /// charts.
    Isagraf,
    /// PL7: `%Xi` steps, `%S`/`%SW` system objects, P1/N1/P0 sections.
    Pl7,
    /// Festo FST statement list: `P<n>.stl` programs, `B<n>.stl` modules,
    /// `allocation.txt` (module `fst`).
    Fst,
    /// CODESYS V2.3/V3 and TwinCAT: VAR_INPUT assignment, bit-string
    /// arithmetic, globals without VAR_EXTERNAL, `END_IF` without `;`,
    /// non-nesting comments, pragmas ignored, implicit narrowing (module
    /// `codesys`).
    Codesys,
}

impl Dialect {
    pub const ALL: &'static [Dialect] = &[
        Dialect::Isagraf,
        Dialect::Pl7,
        Dialect::Fst,
        Dialect::Codesys,
    ];

    /// The dialect a `--lib` / `libraries` name selects (any case).
    pub fn from_name(name: &str) -> Option<Dialect> {
        Dialect::ALL
            .iter()
            .copied()
            .find(|d| d.name().eq_ignore_ascii_case(name.trim()))
    }

    /// The name used on the command line and in `automat.toml`.
    pub fn name(self) -> &'static str {
        match self {
            Dialect::Isagraf => "isagraf",
            Dialect::Pl7 => "pl7",
            Dialect::Fst => "fst",
            Dialect::Codesys => "codesys",
        }
    }

    /// The name the library's source file has in diagnostics (`None`: the
    /// dialect has no library).
    pub fn library_file(self) -> Option<&'static str> {
        match self {
            Dialect::Isagraf => Some("<library isagraf>/isagraf.st"),
            Dialect::Codesys => Some("<library codesys>/codesys.st"),
            Dialect::Pl7 | Dialect::Fst => None,
        }
    }

    /// The ST source of the dialect's library.
    pub fn library_source(self) -> Option<&'static str> {
        match self {
            Dialect::Isagraf => Some(include_str!("../lib/isagraf.st")),
            Dialect::Codesys => Some(include_str!("../lib/codesys.st")),
            Dialect::Pl7 | Dialect::Fst => None,
        }
    }
}

/// Is `name` a file the FST dialect reads itself (`*.stl`,
/// `allocation.txt`) rather than a Structured Text source?
pub fn is_fst_file(name: &str) -> bool {
    fst::is_fst_file(name)
}

/// Is `name` an Allen-Bradley SLC-500 ladder file (`*.slc`), read by the
/// SLC front end whatever the project's libraries?
pub fn is_slc_file(name: &str) -> bool {
    slc::is_slc_file(name)
}

/// The drawing sheet of an SLC-500 program file (`LAD2`, `2`, or its
/// name) in the `.slc` files of `map`, for `automat draw`.
pub fn slc_sheet(map: &SourceMap, pou: &str) -> Option<automat_plcopen::sheet::Sheet> {
    slc::sheet(map, pou)
}

/// The SLC-500 program files of `map` drawn for the HMI's live view, with
/// what to show on each node.
pub fn slc_live_sheets(map: &SourceMap) -> Vec<slc::LiveSheet> {
    slc::live_sheets(map)
}

/// Is `name` a CODESYS V2.3 text export (`*.exp`), read as Structured
/// Text when a folder is given (the `(* @... *)` markers are comments)?
pub fn is_export_file(name: &str) -> bool {
    std::path::Path::new(name)
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("exp"))
}

pub use heap_size::{parse_heap_size, DEFAULT_HEAP_BYTES};

/// The dialects a project uses, with their settings.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Libraries {
    pub dialects: Vec<Dialect>,
    /// The CODESYS heap's size in bytes (`codesys:heap=256KiB`).
    pub heap_bytes: u32,
}

/// Parses a list of dialect names (`--lib a --lib b`, `libraries = [...]`),
/// each with its settings after a `:` (`codesys:heap=256KiB`, the only
/// one so far).
pub fn parse_libraries<S: AsRef<str>>(names: &[S]) -> Result<Libraries, String> {
    let mut heap_bytes = DEFAULT_HEAP_BYTES;
    let mut plain = Vec::with_capacity(names.len());
    for n in names {
        let n = n.as_ref();
        let Some((name, settings)) = n.split_once(':') else {
            plain.push(n);
            continue;
        };
        if Dialect::from_name(name) != Some(Dialect::Codesys) {
            match Dialect::from_name(name) {
                Some(d) => return Err(format!("library `{}` has no settings (`{n}`)", d.name())),
                None => {
                    plain.push(name);
                    continue;
                }
            }
        }
        for setting in settings.split(',') {
            match setting.split_once('=') {
                Some((key, value)) if key.trim().eq_ignore_ascii_case("heap") => {
                    heap_bytes = parse_heap_size(value)?;
                }
                _ => {
                    return Err(format!(
                        "unknown setting `{setting}` of library `codesys` (known: `heap=SIZE`, as `codesys:heap=256KiB`)"
                    ))
                }
            }
        }
        plain.push(name);
    }
    Ok(Libraries {
        dialects: parse_plain_names(&plain)?,
        heap_bytes,
    })
}

/// Parses a list of dialect names (`--lib a --lib b`, `libraries = [...]`);
/// settings (`codesys:heap=256KiB`) are checked and left to
/// [`parse_libraries`].
pub fn parse_names<S: AsRef<str>>(names: &[S]) -> Result<Vec<Dialect>, String> {
    parse_libraries(names).map(|l| l.dialects)
}

fn parse_plain_names(names: &[&str]) -> Result<Vec<Dialect>, String> {
    let mut out = Vec::new();
    for &n in names {
        match Dialect::from_name(n) {
            Some(d) if !out.contains(&d) => out.push(d),
            Some(_) => {}
            None => {
                let known: Vec<&str> = Dialect::ALL.iter().map(|d| d.name()).collect();
                return Err(format!(
                    "unknown library `{n}` (known: {})",
                    known.join(", ")
                ));
            }
        }
    }
    Ok(out)
}

/// Adds the library source file of every dialect to the project (after the
/// user's files, so their diagnostics come first). With FST, the ST
/// generated from the project's STL files (when they have no error: their
/// diagnostics come from [`check_sources`]).
pub fn add_libraries(map: &mut SourceMap, dialects: &[Dialect]) {
    add_libraries_to(
        map,
        &Libraries {
            dialects: dialects.to_vec(),
            heap_bytes: DEFAULT_HEAP_BYTES,
        },
    );
}

/// [`add_libraries`] with the libraries' settings (the CODESYS heap's size).
pub fn add_libraries_to(map: &mut SourceMap, libraries: &Libraries) {
    let dialects = libraries.dialects.as_slice();
    if let (Some((text, meanings)), _) = slc::translate(map) {
        let file = map.add(slc::GENERATED, text);
        for (at, meaning) in meanings {
            map.add_fault_meaning(Span::new(file, at.start, at.end), meaning);
        }
    }
    if dialects.contains(&Dialect::Fst) {
        if let (Some(text), _) = fst::translate(map) {
            map.add(fst::GENERATED, text);
        }
    }
    for d in dialects {
        if let (Some(name), Some(text)) = (d.library_file(), d.library_source()) {
            if *d == Dialect::Codesys {
                map.add(name, heap_size::codesys_library(text, libraries.heap_bytes));
            } else {
                map.add(name, text);
            }
        }
    }
}

/// The checker's diagnostics inside an LD, FBD or SFC element of a PLCopen
/// file name the element's POU and `localId`, as the importer's do.
fn name_xml_elements(sources: &SourceMap, diags: &mut [Diagnostic]) {
    for (id, file) in sources.files() {
        if automat_plcopen::is_plcopen_file(&file.name) {
            automat_plcopen::name_elements(id, &file.text, diags);
        }
    }
}

/// Every file of `sources` parsed after the dialects' text rewrites only
/// (PL7 spellings, ISaGRAF `v;` associations), before any tree rewrite:
/// the charts as written, for tools that draw them. FST files and the
/// dialect libraries give empty units.
pub fn parse_as_written(
    sources: &SourceMap,
    interner: &mut Interner,
    dialects: &[Dialect],
) -> Vec<SourceUnit> {
    let pl7 = dialects.contains(&Dialect::Pl7);
    let isagraf = dialects.contains(&Dialect::Isagraf);
    let fst = dialects.contains(&Dialect::Fst);
    let mut units = Vec::with_capacity(sources.len());
    for (id, file) in sources.files() {
        let lib = dialects
            .iter()
            .any(|d| d.library_file() == Some(file.name.as_str()));
        if lib || (fst && fst::is_fst_file(&file.name)) || slc::is_slc_file(&file.name) {
            units.push(SourceUnit {
                file: id,
                items: Vec::new(),
            });
            continue;
        }
        if automat_plcopen::is_plcopen_file(&file.name) {
            units.push(automat_plcopen::import(id, &file.text, interner).unit);
            continue;
        }
        let pl7_text = if pl7 {
            pl7::text::rewrite(&file.text)
        } else {
            None
        };
        let text = pl7_text.as_deref().unwrap_or(&file.text);
        let isa_text = if isagraf { boolact::text(text).0 } else { None };
        let text = isa_text.as_deref().unwrap_or(text);
        units.push(automat_syntax::parse(id, text, interner).unit);
    }
    units
}

/// Parses every file of `sources`, applies the rewrites of `dialects`, and
/// checks the project; parse, rewrite and check diagnostics, sorted by file
/// and position. `*.xml` files are PLCopen TC6 XML, read by
/// `automat_plcopen::import` (the dialect rewrites see its trees like any
/// other). With no dialect and no XML file this is exactly
/// [`automat_sema::check_sources`].
pub fn check_sources(
    sources: &SourceMap,
    interner: &mut Interner,
    dialects: &[Dialect],
) -> (Vec<SourceUnit>, Analysis) {
    let xml = sources
        .files()
        .any(|(_, f)| automat_plcopen::is_plcopen_file(&f.name));
    let has_slc = sources.files().any(|(_, f)| slc::is_slc_file(&f.name));
    if dialects.is_empty() && !xml && !has_slc {
        return automat_sema::check_sources(sources, interner);
    }
    let mut units = Vec::with_capacity(sources.len());
    let mut diags = Vec::new();
    let mut libs: Vec<FileId> = Vec::new();
    let pl7 = dialects.contains(&Dialect::Pl7);
    let isagraf = dialects.contains(&Dialect::Isagraf);
    let mut negated = Vec::new();
    let fst = dialects.contains(&Dialect::Fst);
    let codesys = dialects.contains(&Dialect::Codesys);
    let parse_opts = automat_syntax::Options {
        codesys,
        nested_comments: false,
    };
    let check_opts = automat_sema::Options { codesys };
    if fst {
        diags.extend(fst::translate(sources).1);
    }
    if has_slc {
        diags.extend(slc::translate(sources).1);
    }
    for (id, file) in sources.files() {
        if (fst && fst::is_fst_file(&file.name)) || slc::is_slc_file(&file.name) {
            units.push(SourceUnit {
                file: id,
                items: Vec::new(),
            });
            continue;
        }
        let lib = dialects
            .iter()
            .any(|d| d.library_file() == Some(file.name.as_str()));
        // PL7 spellings become identifiers of the same length first.
        let pl7_text = if pl7 && !lib {
            pl7::text::rewrite(&file.text)
        } else {
            None
        };
        let text = pl7_text.as_deref().unwrap_or(&file.text);
        // ISaGRAF `v;` / `/v;` associations become `v(N);`, same offsets.
        let isa_text = if isagraf && !lib {
            let (t, neg) = boolact::text(text);
            negated.extend(
                neg.into_iter()
                    .map(|(at, s, e)| (at, automat_base::Span::new(id, s, e))),
            );
            t
        } else {
            None
        };
        let text = isa_text.as_deref().unwrap_or(text);
        // PLCopen XML files are read by their importer into the same trees.
        let parsed = if automat_plcopen::is_plcopen_file(&file.name) {
            automat_plcopen::import(id, &file.text, interner)
        } else {
            let opts = automat_syntax::Options {
                nested_comments: codesys && codesys::nested_comments(text),
                ..parse_opts
            };
            automat_syntax::parse_with(id, text, interner, opts)
        };
        if lib {
            libs.push(id);
        }
        units.push(parsed.unit);
        diags.extend(parsed.diagnostics);
    }
    if dialects.is_empty() {
        // XML files without a dialect: no rewrite applies.
        diags.extend(automat_syntax::desugar_namespaces(&mut units, interner));
        diags.extend(automat_syntax::desugar_oop(&mut units, interner));
        let mut analysis = automat_sema::check(&units, interner);
        diags.append(&mut analysis.diagnostics);
        diags.sort_by_key(|d: &Diagnostic| (d.span.file, d.span.start, d.span.end));
        name_xml_elements(sources, &mut diags);
        analysis.diagnostics = diags;
        return (units, analysis);
    }
    drop_shadowed_library_pous(&mut units, &libs);
    // The rewrites below see namespaces' items under their flat names.
    diags.extend(automat_syntax::desugar_namespaces(&mut units, interner));
    let is_user = |u: &SourceUnit| !libs.contains(&u.file);
    let mut marks = Vec::new();
    for unit in units.iter().filter(|u| is_user(u) && (isagraf || pl7)) {
        marks.push((
            unit.file,
            pragma::sections(unit.file, &sources.get(unit.file).text),
        ));
    }
    // ISaGRAF and PL7 charts may have several initial steps (IEC allows
    // one, E124): each is active at the start and after a reset.
    if isagraf || pl7 {
        diags.retain(|d| d.code != Code::E124);
    }
    let mut has_children = false;
    if isagraf {
        // Boolean actions are edge writes; on the chart code as the
        // desugaring left it (before the children rewrite gates it).
        boolact::rewrite(&mut units, &is_user, &negated, interner, &mut diags);
        // Children first: a child's chart code is then its whole body, which
        // the child rewrite gates (an inactive child does not run its
        // chart); the timer updates put before it afterwards stay ungated.
        let found = children::rewrite(&mut units, &is_user, interner, &mut diags);
        has_children = found.any;
        let taken = found.taken;
        // A child chart's final step is left when its parent kills it: "no
        // transition leaves this step" (W121) misleads there.
        diags.retain(|d| {
            !(d.code == Code::W121
                && found.children.iter().any(|s| {
                    s.file == d.span.file && s.start <= d.span.start && d.span.end <= s.end
                }))
        });
        for unit in units.iter_mut().filter(|u| is_user(u)) {
            timer::rewrite(unit, interner, &mut diags);
        }
        // The chart parser reported the associations naming a child
        // program as unknown actions (E125): they are child controls.
        diags.retain(|d| !(d.code == Code::E125 && taken.contains(&d.span)));
        // An ISaGRAF transition written without a condition is TRUE.
        let texts = |u: &SourceUnit| sources.get(u.file).text.clone();
        let open = empty::isagraf_true(&mut units, &is_user, &texts, interner);
        drop_errors_within(&mut diags, &open);
    }
    if pl7 {
        let texts = |u: &SourceUnit| sources.get(u.file).text.clone();
        let open = pl7::rewrite(&mut units, &is_user, &texts, interner, &mut diags);
        // A PL7 transition written without a condition is FALSE: the
        // parser's "missing condition" error there is void.
        drop_errors_within(&mut diags, &open);
    }
    if codesys {
        // A program's variables and actions used from other POUs: hidden
        // globals first (its VAR_STAT too), before the rewrites below.
        program_access::rewrite(&mut units, &is_user, interner, &mut diags);
        // `__NEW` / `__DELETE`: calls of the library's allocator.
        let heap_lib = sources
            .files()
            .find(|(_, f)| Some(f.name.as_str()) == Dialect::Codesys.library_file())
            .map(|(id, _)| id);
        heap::rewrite(&mut units, &is_user, heap_lib, interner, &mut diags);
        // VAR_STAT variables become hidden globals first, so the POU gets
        // their VAR_EXTERNAL below.
        codesys::static_vars(&mut units, &is_user, interner, &mut diags);
        // Globals of global variable lists need no VAR_EXTERNAL.
        codesys::implicit_externals(&mut units, &is_user);
        // `TIME()`: CODESYS's clock, the scan's PLC time.
        clock::rewrite(&mut units, &is_user, interner);
    }
    if isagraf || pl7 {
        sections::synthesize(&mut units, &marks, has_children, interner, &mut diags);
    }
    diags.extend(automat_syntax::desugar_oop(&mut units, interner));
    let mut analysis = automat_sema::check_with(&units, interner, check_opts);
    diags.append(&mut analysis.diagnostics);
    diags.sort_by_key(|d: &Diagnostic| (d.span.file, d.span.start, d.span.end));
    if codesys {
        program_access::drop_duplicates(&mut diags);
    }
    name_xml_elements(sources, &mut diags);
    analysis.diagnostics = diags;
    (units, analysis)
}

/// Drops the diagnostics that lie within one of `spans`.
fn drop_errors_within(diags: &mut Vec<Diagnostic>, spans: &[automat_base::Span]) {
    diags.retain(|d| {
        !spans
            .iter()
            .any(|s| s.file == d.span.file && s.start <= d.span.start && d.span.end <= s.end)
    });
}

/// A user POU named like a library POU replaces it (the rule the checker
/// follows for the standard library).
fn drop_shadowed_library_pous(units: &mut [SourceUnit], libs: &[FileId]) {
    let user: Vec<_> = units
        .iter()
        .filter(|u| !libs.contains(&u.file))
        .flat_map(|u| u.items.iter())
        .filter_map(|i| match i {
            Item::Pou(p) => Some(p.name.sym),
            _ => None,
        })
        .collect();
    for unit in units.iter_mut().filter(|u| libs.contains(&u.file)) {
        unit.items.retain(|i| match i {
            Item::Pou(p) => !user.contains(&p.name.sym),
            _ => true,
        });
    }
}

#[cfg(test)]
mod tests;
