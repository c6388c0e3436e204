//! ISaGRAF TIMER variables.
//!
//! A TIMER is a TIME that counts PLC time while it is started: `TSTART(t)`
//! lets it count (from its current value), `TSTOP(t)` freezes it, and an
//! assignment (`t := T#0s`) sets it. It compares with TIME values like any
//! TIME, because it *is* a TIME in memory: the rewrite makes
//! - the declaration `t : TIMER` a `t : TIME` plus two hidden variables
//!   beside it, `__timer_run_t : BOOL` (started) and `__timer_last_t : TIME`
//!   (PLC time of the last update), in the same kind of block (so a
//!   VAR_GLOBAL timer has hidden globals, and each VAR_EXTERNAL of it the
//!   matching externals);
//! - at the start of every body that declares timers, for each of them:
//!   `IF run THEN t := t + (__SCAN_TIME() - last); END_IF; last :=
//!   __SCAN_TIME();` — the update is idempotent within one scan (the second
//!   POU to see a global timer adds nothing), so it is right however many
//!   POUs share a timer;
//! - `TSTART(t);` / `TSTOP(t);` the statements `run := TRUE/FALSE;`.
//!
//! So a timer started in a scan at time s reads `now - s` in every later
//! scan (plus what it held), and the IR and the engine see only ST.
//!
//! Where a TIMER may be declared: VAR, VAR_OUTPUT, VAR_GLOBAL and
//! VAR_EXTERNAL of a PROGRAM or FUNCTION_BLOCK, and global variable lists.
//! Anywhere else (a FUNCTION, VAR_INPUT, VAR_IN_OUT, VAR_TEMP, a structure
//! member or an array element) its state would not survive a call: E150.

use crate::build;
use automat_base::{Code, Diagnostic, Interner, Span, Symbol};
use automat_syntax::ast::{
    Body, Configuration, ExprKind, Ident, Item, Pou, PouKind, SourceUnit, Stmt, StmtKind, TypeSpec,
    VarBlock, VarKind,
};

/// Rewrites the TIMER declarations and TSTART/TSTOP calls of one file.
pub fn rewrite(unit: &mut SourceUnit, interner: &mut Interner, diags: &mut Vec<Diagnostic>) {
    // A symbol no file uses: no declaration matches it, TSTART/TSTOP are
    // still checked.
    let timer = interner.intern("TIMER");
    for item in &mut unit.items {
        match item {
            Item::Pou(p) => rewrite_pou(p, timer, interner, diags),
            Item::Globals(b) => {
                declare(b, timer, interner);
            }
            Item::Config(c) => rewrite_config(c, timer, interner),
            // Dialect rewrites run before the object-orientation desugaring
            // and leave classes alone.
            Item::Class(_) | Item::Interface(_) | Item::Namespace(_) => {}
            Item::Types(t) => {
                for d in &mut t.decls {
                    reject_nested(&mut d.spec, timer, interner, diags);
                }
            }
        }
    }
}

fn rewrite_config(c: &mut Configuration, timer: Symbol, interner: &mut Interner) {
    for b in &mut c.globals {
        declare(b, timer, interner);
    }
    for r in &mut c.resources {
        for b in &mut r.globals {
            declare(b, timer, interner);
        }
    }
}

fn rewrite_pou(p: &mut Pou, timer: Symbol, interner: &mut Interner, diags: &mut Vec<Diagnostic>) {
    let stateful = matches!(p.kind, PouKind::Program | PouKind::FunctionBlock);
    let mut timers: Vec<Ident> = Vec::new();
    for b in &mut p.var_blocks {
        let allowed = stateful
            && matches!(
                b.kind,
                VarKind::Local | VarKind::Output | VarKind::Global | VarKind::External
            );
        if allowed {
            timers.extend(declare(b, timer, interner));
        } else {
            for d in &mut b.decls {
                if is_timer(&d.ty, timer) {
                    diags.push(misplaced(d.ty.span(), p.kind, b.kind));
                    as_time(&mut d.ty, interner);
                }
            }
        }
        for d in &mut b.decls {
            reject_nested(&mut d.ty, timer, interner, diags);
        }
    }
    let Body::St(stmts) = &mut p.body;
    calls(stmts, &timers, interner, diags);
    if timers.is_empty() {
        return;
    }
    let scan = build::ident(interner, "__SCAN_TIME", p.name.span);
    let mut prologue = Vec::with_capacity(timers.len() * 2);
    for t in &timers {
        let (run, last) = hidden(interner, *t);
        let span = t.span;
        let elapsed = build::binary(
            automat_syntax::ast::BinaryOp::Sub,
            build::call0(Ident { span, ..scan }),
            build::name(last),
            span,
        );
        let sum = build::binary(
            automat_syntax::ast::BinaryOp::Add,
            build::name(*t),
            elapsed,
            span,
        );
        prologue.push(build::if_then(
            build::name(run),
            vec![build::assign(build::name(*t), sum, span)],
            span,
        ));
        prologue.push(build::assign(
            build::name(last),
            build::call0(Ident { span, ..scan }),
            span,
        ));
    }
    prologue.append(stmts);
    *stmts = prologue;
}

/// Turns the TIMER declarations of a block into TIME plus the hidden pair;
/// returns the timers declared.
fn declare(b: &mut VarBlock, timer: Symbol, interner: &mut Interner) -> Vec<Ident> {
    let mut found = Vec::new();
    for d in &mut b.decls {
        if let TypeSpec::Named(id) = &mut d.ty {
            if id.sym == timer {
                id.sym = interner.intern("TIME");
                found.extend(d.names.iter().copied());
            }
        }
    }
    let bool_ty = interner.intern("BOOL");
    let time_ty = interner.intern("TIME");
    for t in &found {
        let (run, last) = hidden(interner, *t);
        b.decls.push(build::var(
            run,
            Ident {
                sym: bool_ty,
                span: t.span,
            },
        ));
        b.decls.push(build::var(
            last,
            Ident {
                sym: time_ty,
                span: t.span,
            },
        ));
    }
    found
}

/// The hidden (started, last update) variables of a timer.
fn hidden(interner: &mut Interner, t: Ident) -> (Ident, Ident) {
    let n = interner.name(t.sym).to_ascii_lowercase();
    (
        build::ident(interner, &format!("__timer_run_{n}"), t.span),
        build::ident(interner, &format!("__timer_last_{n}"), t.span),
    )
}

fn is_timer(ty: &TypeSpec, timer: Symbol) -> bool {
    matches!(ty, TypeSpec::Named(id) if id.sym == timer)
}

/// TIMER inside an array or a structure has nowhere to keep its state (it
/// becomes a TIME after the error, so the checker adds nothing).
fn reject_nested(
    ty: &mut TypeSpec,
    timer: Symbol,
    interner: &mut Interner,
    diags: &mut Vec<Diagnostic>,
) {
    match ty {
        TypeSpec::Array { elem, .. } => {
            if is_timer(elem, timer) {
                diags.push(Diagnostic::error(
                    Code::E150,
                    elem.span(),
                    "an array of TIMER is not supported: declare each timer as a variable",
                ));
                as_time(elem, interner);
            } else {
                reject_nested(elem, timer, interner, diags);
            }
        }
        TypeSpec::Struct { members, .. } => {
            for m in members {
                if is_timer(&m.ty, timer) {
                    diags.push(Diagnostic::error(
                        Code::E150,
                        m.ty.span(),
                        "a TIMER cannot be a structure member: declare it as a variable",
                    ));
                    as_time(&mut m.ty, interner);
                } else {
                    reject_nested(&mut m.ty, timer, interner, diags);
                }
            }
        }
        _ => {}
    }
}

fn as_time(ty: &mut TypeSpec, interner: &mut Interner) {
    if let TypeSpec::Named(id) = ty {
        id.sym = interner.intern("TIME");
    }
}

fn misplaced(span: Span, pou: PouKind, kind: VarKind) -> Diagnostic {
    let place = match (pou, kind) {
        (PouKind::Function, _) => "a FUNCTION (its variables do not survive the call)",
        (_, VarKind::Input) => "VAR_INPUT",
        (_, VarKind::InOut) => "VAR_IN_OUT",
        (_, VarKind::Temp) => "VAR_TEMP",
        _ => "this block",
    };
    Diagnostic::error(
        Code::E150,
        span,
        format!("a TIMER variable cannot be declared in {place}"),
    )
    .with_note("declare timers in VAR, VAR_OUTPUT, VAR_GLOBAL or VAR_EXTERNAL of a PROGRAM or FUNCTION_BLOCK")
}

/// Rewrites `TSTART(t);` and `TSTOP(t);` in a statement list, recursively.
fn calls(
    stmts: &mut [Stmt],
    timers: &[Ident],
    interner: &mut Interner,
    diags: &mut Vec<Diagnostic>,
) {
    if interner.lookup("TSTART").is_some() || interner.lookup("TSTOP").is_some() {
        calls_one(stmts, timers, interner, diags);
    }
}

fn calls_one(
    stmts: &mut [Stmt],
    timers: &[Ident],
    interner: &mut Interner,
    diags: &mut Vec<Diagnostic>,
) {
    for s in stmts {
        match &mut s.kind {
            StmtKind::Expr(e) => {
                let ExprKind::Call { callee, args } = &e.kind else {
                    continue;
                };
                let ExprKind::Name(f) = callee.kind else {
                    continue;
                };
                let start = match interner.name(f.sym).to_ascii_uppercase().as_str() {
                    "TSTART" => true,
                    "TSTOP" => false,
                    _ => continue,
                };
                let target = match args.as_slice() {
                    [a] if a.name.is_none() => a.value.as_ref().and_then(|v| match v.kind {
                        ExprKind::Name(id) => timers.iter().find(|t| t.sym == id.sym).copied(),
                        _ => None,
                    }),
                    _ => None,
                };
                let Some(t) = target else {
                    diags.push(Diagnostic::error(
                        Code::E151,
                        e.span,
                        format!(
                            "{} needs one TIMER variable of this POU as its argument",
                            if start { "TSTART" } else { "TSTOP" }
                        ),
                    ));
                    s.kind = StmtKind::Empty;
                    continue;
                };
                let (run, _) = hidden(interner, t);
                let span = s.span;
                *s = build::assign(
                    build::name(Ident {
                        span: e.span,
                        ..run
                    }),
                    build::bool_lit(start, span),
                    span,
                );
            }
            StmtKind::If {
                branches,
                else_body,
            } => {
                for b in branches {
                    calls_one(&mut b.body, timers, interner, diags);
                }
                if let Some(e) = else_body {
                    calls_one(e, timers, interner, diags);
                }
            }
            StmtKind::Case {
                arms, else_body, ..
            } => {
                for a in arms {
                    calls_one(&mut a.body, timers, interner, diags);
                }
                if let Some(e) = else_body {
                    calls_one(e, timers, interner, diags);
                }
            }
            StmtKind::For { body, .. }
            | StmtKind::While { body, .. }
            | StmtKind::Repeat { body, .. } => calls_one(body, timers, interner, diags),
            _ => {}
        }
    }
}
