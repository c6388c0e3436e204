//! The semantic checker of automat: name resolution, typing, constant
//! folding and checks over the AST of a whole project, producing
//! diagnostics and the semantic [`Model`] that lowering consumes.
//!
//! # Phases
//! 1. `decl`: collect POUs, types and globals of every file; resolve types
//!    and the constants they depend on (on demand, cycles reported); check
//!    initial values, locations and VAR_EXTERNAL.
//! 2. [`body`]: type every statement and expression of every POU body.
//! 3. `config`: tasks, program instances, connections, access paths.
//!
//! # Invariants
//! - [`check`] never panics and always terminates, whatever the AST: no
//!   indexing that user input controls, recursion bounded by depth limits,
//!   cycles in declarations detected and reported.
//! - One mistake, one diagnostic: an expression whose error was reported has
//!   the poison type [`ops::Ty::Error`], which every rule accepts silently.
//! - Every diagnostic has a code from `automat_base::codes`, the span of the
//!   offending token and a one-line message naming the things involved.
//! - No string formatting on the clean path: messages are built only when a
//!   diagnostic is emitted.
//! - The model holds no AST copies: POUs refer to their items by index.
//!
//! # Decisions where the standard is silent or tools differ
//! (The typing rules themselves are in [`lattice`].)
//! - Project-level `VAR_GLOBAL CONSTANT`s are visible in every POU (they size
//!   arrays and strings of libraries); global *variables* are visible in a
//!   POU only through VAR_EXTERNAL (E020 otherwise), whose type must match
//!   (E025). A program's own VAR_GLOBAL also serves VAR_EXTERNAL.
//! - A user POU or type named like a standard function or function block
//!   replaces it (vendor libraries ship their own TON or LIMIT).
//! - A bare enumeration value shared by several enumerations takes the
//!   expected type, else the first declared; `Color#Red` and CODESYS's
//!   `Color.Red` are accepted.
//! - 0 and 1 fit BOOL in assignments, never as conditions (E032).
//! - A typed constant converted to a narrower type it fits is a warning
//!   (W003), not an error; a variable never is.
//! - Initial values are constant expressions (E070 otherwise).
//! - Positional arguments bind inputs and in-outs in declaration order, then
//!   outputs. `EN`/`ENO` are accepted on every call and every instance
//!   (`inst.ENO`). The counters accept `RESET` for `R`.
//! - `TRUNC` returns DINT (`TRUNC_<INT>` picks another type).
//! - Statements after RETURN (or EXIT/CONTINUE in a loop) are W002.
//!
//! # For lowering
//! [`type_of`] types any expression of a POU body; [`resolve_name`] and
//! [`resolve_callee`] say what a name or a callee denotes; the standard
//! function table ([`stdlib::lookup`], [`stdlib::StdOp`]) says what a
//! standard call does.

pub mod body;
mod config;
pub mod convert;
mod decl;
pub mod lattice;
pub mod literal;
pub mod model;
pub mod names;
pub mod ops;
mod sfc;
pub mod stdlib;
pub mod suggest;
pub mod types;
pub mod value;

pub use model::Model;

use automat_base::{Diagnostic, Interner, SourceMap};
use automat_syntax::ast::{Expr, SourceUnit};

pub use body::resolve::{resolve_callee, resolve_name, CallTarget, NameRef};
pub use body::{Checker, Scope};
pub use ops::{Ty, Typed};
pub use types::{PouId, TypeId};

/// The result of checking a project.
pub struct Analysis {
    /// Errors and warnings, sorted by file and position.
    pub diagnostics: Vec<Diagnostic>,
    pub model: Model,
}

impl Analysis {
    pub fn has_errors(&self) -> bool {
        self.diagnostics.iter().any(Diagnostic::is_error)
    }
}

/// What a dialect relaxes in checking (the default is strict IEC 61131-3).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Options {
    /// CODESYS / TwinCAT rules (`--lib codesys`): a POU may assign its own
    /// VAR_INPUTs; `+ - * / MOD` apply to BYTE/WORD/DWORD/LWORD (the
    /// result has the wider operand's type, wrapping); an implicit narrowing
    /// between integer, bit-string and real types is a warning (W161)
    /// instead of an error.
    pub codesys: bool,
}

/// Checks a whole project (all files of it). Never panics on any AST.
pub fn check(units: &[SourceUnit], interner: &mut Interner) -> Analysis {
    check_with(units, interner, Options::default())
}

/// [`check`] with a dialect's [`Options`].
pub fn check_with(units: &[SourceUnit], interner: &mut Interner, opts: Options) -> Analysis {
    let syms = names::Syms::new(interner);
    let std_unit = automat_syntax::parse(stdlib::STD_FILE, stdlib::FB_SOURCE, interner).unit;
    let interner: &Interner = interner;
    let declared = decl::declare(units, &std_unit, interner, syms);
    let mut diags = declared.diags;
    let mut model = declared.model;
    model.codesys = opts.codesys;
    {
        let mut ck = Checker::new(&model, interner, Scope::Pou(PouId(0)), false);
        for (i, p) in model.pous.iter().enumerate() {
            if p.builtin {
                continue;
            }
            if let Some(ast) = model.pou_ast(units, PouId(i as u32)) {
                ck.check_pou(PouId(i as u32), ast);
                if let automat_syntax::ast::Lang::Sfc(chart) = &ast.lang {
                    sfc::check_chart(&model, interner, PouId(i as u32), chart, &mut diags);
                }
            }
        }
        diags.append(&mut ck.diags);
    }
    config::check_configs(&mut model, &declared.configs, interner, &mut diags);
    model.stdlib = std_unit;
    sort(&mut diags);
    Analysis {
        diagnostics: diags,
        model,
    }
}

/// Parses every file of `sources` and checks them together; parse and check
/// diagnostics, sorted by file and position.
pub fn check_sources(sources: &SourceMap, interner: &mut Interner) -> (Vec<SourceUnit>, Analysis) {
    let mut units = Vec::with_capacity(sources.len());
    let mut diags = Vec::new();
    for (id, file) in sources.files() {
        let parsed = automat_syntax::parse(id, &file.text, interner);
        units.push(parsed.unit);
        diags.extend(parsed.diagnostics);
    }
    diags.extend(automat_syntax::desugar_namespaces(&mut units, interner));
    diags.extend(automat_syntax::desugar_oop(&mut units, interner));
    let mut analysis = check(&units, interner);
    diags.append(&mut analysis.diagnostics);
    sort(&mut diags);
    analysis.diagnostics = diags;
    (units, analysis)
}

/// The type of an expression of a POU body, as the checker computed it
/// (for lowering; no diagnostics).
pub fn type_of(model: &Model, interner: &Interner, pou: PouId, expr: &Expr) -> Typed {
    Checker::new(model, interner, Scope::Pou(pou), true).expr(expr, None)
}

/// The type an expression names when it is a type name and nothing else
/// (`SIZEOF(INT)`, `SIZEOF(MyStruct)`); `None` for anything else, a
/// variable of that name included.
pub fn type_named(model: &Model, interner: &Interner, pou: PouId, expr: &Expr) -> Option<TypeId> {
    Checker::new(model, interner, Scope::Pou(pou), true).type_named(expr)
}

fn sort(diags: &mut [Diagnostic]) {
    diags.sort_by_key(|d| (d.span.file, d.span.start, d.span.end));
}
