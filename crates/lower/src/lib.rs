//! Lowering: a checked project (syntax trees + semantic model) becomes an
//! executable [`automat_ir::Program`]: memory layout, symbol table, initial
//! image, tasks and the code of every POU.
//!
//! # Steps
//! 1. [`layout`]: the located areas (%I, %Q, %M) first, sized from the
//!    highest address used; then globals, program instances, one static
//!    frame per FUNCTION and one pristine template per POU.
//! 2. [`image`]: the cold-start image from the folded initial values.
//! 3. [`symbols`]: one entry per declared variable of globals and program
//!    instances.
//! 4. [`gen`]: the code of every POU (function index = POU index), then the
//!    verifier in debug builds.
//!
//! # Invariants
//! - Never panics on any model; a construct it cannot execute is an E091
//!   diagnostic, recursion E092, no program to run E090.
//! - Calls are explicit: the caller stores inputs into the callee's instance
//!   or frame, calls, then reads outputs.

mod addrs;
mod cx;
mod gen;
pub mod image;
pub mod layout;
mod recursion;
pub mod symbols;
mod tasks;

use automat_base::{Code, Diagnostic, Interner, SourceMap, Span};
use automat_ir::code::{Func, Inst};
use automat_ir::{Areas, Program, SymbolEntry, SymbolTable};
use automat_sema::model::{Section, VarTable};
use automat_sema::{Analysis, PouId};
use automat_syntax::ast::{PouKind, Retain, SourceUnit};
use cx::Cx;
use layout::{Layout, Slot};
use rustc_hash::FxHashMap;

/// The largest memory image lowering produces (256 MiB).
pub const MAX_IMAGE: u32 = 256 << 20;

#[derive(Clone, Debug, Default)]
pub struct LowerOptions {
    /// The PROGRAM to run when there is no CONFIGURATION (`--program`).
    pub program: Option<String>,
}

/// Lowers a checked project (no errors) to a Program.
pub fn lower(
    units: &[SourceUnit],
    analysis: &Analysis,
    interner: &Interner,
    sources: &SourceMap,
    opts: &LowerOptions,
) -> Result<Program, Vec<Diagnostic>> {
    lower_as(units, analysis, interner, sources, opts, false)
}

/// What [`lower`] would refuse in a checked project (no errors), for
/// `automat check`: E091 (with the exact image size needed), E092, ...
/// Without a CONFIGURATION every PROGRAM is lowered, as the one a run may
/// choose, so no E090 (which program to run is the run's question); the
/// programs share one place in the image, so the size checked is the
/// largest a run needs.
pub fn check(
    units: &[SourceUnit],
    analysis: &Analysis,
    interner: &Interner,
    sources: &SourceMap,
) -> Vec<Diagnostic> {
    match lower_as(
        units,
        analysis,
        interner,
        sources,
        &LowerOptions::default(),
        true,
    ) {
        Ok(_) => Vec::new(),
        Err(diags) => diags,
    }
}

/// `every_program`: see [`check`].
fn lower_as(
    units: &[SourceUnit],
    analysis: &Analysis,
    interner: &Interner,
    sources: &SourceMap,
    opts: &LowerOptions,
    every_program: bool,
) -> Result<Program, Vec<Diagnostic>> {
    let model = &analysis.model;
    let mut cx = Cx {
        model,
        interner,
        units,
        sources,
        layout: Layout::new(model),
        globals: FxHashMap::default(),
        frames: vec![None; model.pous.len()],
        templates: vec![None; model.pous.len()],
        consts: Vec::new(),
        top: 0,
        sites: Vec::new(),
        diags: Vec::new(),
        hidden: Default::default(),
    };
    cx.layout.spellings = symbols::spellings(units, sources);
    let areas_end = cx.layout.size_areas(&addrs::in_bodies(units));
    cx.top = areas_end.into();
    let mut entries = Vec::new();
    let mut retain = Vec::new();

    // Globals.
    let mut global_tables: Vec<&VarTable> = vec![&model.globals];
    for c in &model.configs {
        global_tables.push(&c.globals);
        global_tables.extend(c.resources.iter().map(|r| &r.globals));
    }
    // Everything is placed first and the image-size limit checked before
    // any symbol type or image byte is built: a deep tree of FB instances
    // (2^40 of them) is sized in microseconds from the per-type layouts, but
    // enumerating it would take hours and terabytes.
    let mut global_inits = Vec::new();
    let mut placed_globals = Vec::new();
    for t in &global_tables {
        for v in &t.vars {
            let (off, bit) = match v.location.as_ref().filter(|a| !a.partial) {
                Some(a) => cx.layout.located(a),
                None => {
                    let (_, a) = cx.layout.size(v.ty);
                    let s = cx.layout.bytes(v.ty);
                    (cx.alloc(s, a), None)
                }
            };
            let bit =
                bit.filter(|_| model.types.elem(v.ty) == Some(automat_sema::types::Elem::Bool));
            cx.globals.entry(v.name).or_insert((off, bit, v.ty));
            placed_globals.push((v, off, bit));
        }
    }

    // Program instances and tasks.
    let instances = match tasks::instances(&mut cx, opts, every_program) {
        Ok(i) => i,
        Err(d) => return Err(vec![d]),
    };
    let mut placed = Vec::new();
    if every_program && model.configs.is_empty() {
        // Alternatives (a run picks one): all at one place, the largest's size.
        let (size, align) = instances.iter().fold((0u64, 8u32), |(s, a), pi| {
            let l = cx.layout.pou(pi.pou);
            (s.max(l.bytes), a.max(l.align))
        });
        let at = cx.alloc(size, align);
        placed.resize(instances.len(), at);
    } else {
        for pi in &instances {
            let l = cx.layout.pou(pi.pou);
            placed.push(cx.alloc(l.bytes, l.align.max(8)));
        }
    }

    // Static frames of functions and templates of every POU.
    for (i, p) in model.pous.iter().enumerate() {
        let l = cx.layout.pou(PouId(i as u32));
        if p.kind == PouKind::Function {
            cx.frames[i] = Some(cx.alloc(l.bytes, l.align.max(8)));
        }
        cx.templates[i] = Some(cx.alloc(l.bytes, l.align.max(8)));
    }
    if let Some(d) = cx.too_large() {
        return Err(vec![d]);
    }

    for &(v, off, bit) in &placed_globals {
        let ty = symbols::symbol_type(&mut cx.layout, interner, v.ty, 0);
        if v.retain == Retain::Retain {
            let (s, _) = cx.layout.size(v.ty);
            retain.push(off..off + s);
        }
        entries.push(SymbolEntry {
            path: interner.name(v.name).to_string(),
            offset: off,
            bit,
            ty,
            retain: v.retain == Retain::Retain,
            constant: v.constant,
            output: false,
            spelling: String::new(),
        });
        global_inits.push((off, bit, v.ty, v.init.clone()));
    }
    for (pi, &off) in instances.iter().zip(&placed) {
        instance_symbols(
            &mut cx,
            &mut entries,
            &mut retain,
            &pi.name,
            pi.pou,
            off,
            pi.retain,
        );
    }

    if let Err(d) = recursion::check(&cx) {
        return Err(vec![d]);
    }

    // Code.
    let mut funcs = Vec::with_capacity(model.pous.len());
    for i in 0..model.pous.len() {
        funcs.push(gen::pou(&mut cx, PouId(i as u32)));
    }
    gen::lean::finish(&mut funcs, &cx.hidden);
    // A connected instance runs the code that stores its connections
    // around the program (after `lean`, which knows only POUs).
    let mut instances = instances;
    for pi in instances.iter_mut().filter(|pi| !pi.conns.is_empty()) {
        pi.func = funcs.len() as u32;
        funcs.push(gen::connect::program(&mut cx, pi.pou, &pi.conns));
    }
    if cx.diags.iter().any(Diagnostic::is_error) {
        return Err(cx.diags);
    }

    // The initial image (code generation allocated temporaries and
    // constants since the first check).
    if let Some(d) = cx.too_large() {
        return Err(vec![d]);
    }
    let image_size = align8(layout::narrow(cx.top));
    patch_ref_checks(&mut funcs, image_size);
    let mut w = image::ImageWriter {
        layout: &mut cx.layout,
        img: vec![0; image_size as usize],
        globals: &cx.globals,
        here: None,
    };
    for (off, bit, ty, init) in &global_inits {
        w.init(*off, *bit, *ty, init.as_ref(), 0);
    }
    for (pi, off) in instances.iter().zip(&placed) {
        w.instance(*off, pi.pou, 0);
    }
    for i in 0..model.pous.len() {
        for base in [cx.frames[i], cx.templates[i]].into_iter().flatten() {
            w.instance(base, PouId(i as u32), 0);
        }
    }
    let mut img = w.img;
    for (at, bytes) in &cx.consts {
        if let Some(dst) = img.get_mut(*at as usize..*at as usize + bytes.len()) {
            dst.copy_from_slice(bytes);
        }
    }
    let a = cx.layout.areas;
    let program = Program {
        image_size,
        initial_image: img,
        areas: Areas {
            input: a.input.0..a.input.1,
            output: a.output.0..a.output.1,
            memory: a.memory.0..a.memory.1,
        },
        retain,
        symbols: SymbolTable::new(entries),
        tasks: tasks::task_defs(&cx, &instances, &placed),
        funcs,
        sites: std::mem::take(&mut cx.sites),
    };
    if cfg!(debug_assertions) {
        if let Err(e) = program.verify() {
            return Err(vec![Diagnostic::error(
                Code::E091,
                Span::default(),
                format!("internal error: generated code failed verification: {e}"),
            )]);
        }
    }
    Ok(program)
}

fn align8(x: u32) -> u32 {
    layout::align_up(x.max(1), 8)
}

/// Symbol entries for the variables of a program instance.
fn instance_symbols(
    cx: &mut Cx,
    entries: &mut Vec<SymbolEntry>,
    retain: &mut Vec<std::ops::Range<u32>>,
    inst: &str,
    pou: PouId,
    base: u32,
    inst_retain: Retain,
) {
    let l = cx.layout.pou(pou);
    let Some(p) = cx.model.pou(pou) else { return };
    for (v, slot) in p.vars.vars.iter().zip(l.slots.iter()) {
        let (offset, bit) = match *slot {
            Slot::Rel(o) => (base + o, None),
            Slot::Located(o, b) => (
                o,
                b.filter(|_| cx.model.types.elem(v.ty) == Some(automat_sema::types::Elem::Bool)),
            ),
            Slot::External => {
                // `Inst.g` of a VAR_EXTERNAL is the global `g` (as the
                // program's code sees it): the same place, for --print,
                // scenarios and monitoring. A CODESYS program's own
                // variable kept as the global `Main.x` has that path already.
                if cx.interner.name(v.name).contains('.') {
                    continue;
                }
                if let Some(&(offset, bit, ty)) = cx.globals.get(&v.name) {
                    let ty = symbols::symbol_type(&mut cx.layout, cx.interner, ty, 0);
                    entries.push(SymbolEntry {
                        path: format!("{inst}.{}", cx.interner.name(v.name)),
                        offset,
                        bit,
                        ty,
                        retain: false,
                        constant: v.constant,
                        output: false,
                        spelling: String::new(),
                    });
                }
                continue;
            }
        };
        let mut ty = symbols::symbol_type(&mut cx.layout, cx.interner, v.ty, 0);
        if v.section == Section::InOut {
            ty = automat_ir::SymbolType::Ref(Box::new(ty));
        }
        let is_retain = v.retain == Retain::Retain
            || (inst_retain == Retain::Retain && v.retain != Retain::NonRetain);
        if is_retain {
            let (s, _) = cx.layout.size(v.ty);
            retain.push(offset..offset + s);
        }
        entries.push(SymbolEntry {
            path: format!("{inst}.{}", cx.interner.name(v.name)),
            offset,
            bit,
            ty,
            retain: is_retain,
            constant: v.constant,
            output: v.section == Section::Output,
            spelling: String::new(),
        });
    }
}

/// Dereference checks carry `-size` as their upper bound until the image's
/// size is known: the last offset where a `size`-byte target still fits.
fn patch_ref_checks(funcs: &mut [Func], image_size: u32) {
    for f in funcs {
        for inst in &mut f.code {
            if let Inst::Check {
                kind: automat_ir::code::CheckKind::Ref,
                hi,
                ..
            } = inst
            {
                if *hi < 0 {
                    *hi = (i64::from(image_size) + *hi).max(0);
                }
            }
        }
    }
}

/// An empty function (a POU without code).
pub(crate) fn empty_func(name: &str) -> Func {
    let mut f = Func::new(name);
    f.push(Inst::Ret);
    f
}
