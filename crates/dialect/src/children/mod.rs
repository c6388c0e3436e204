//! ISaGRAF child SFC programs: GSTART / GKILL / GFREEZE / GRST / GSTATUS
//! and the `child(N | S | R)` associations of a parent's steps.
//!
//! A PROGRAM is a *child* when another POU controls it (one of the calls
//! above with its name, or a step association naming it). Its state lives
//! in two hidden globals, `__gcmd_c : INT` (the pending command: 1 start,
//! 2 kill, 3 freeze, 4 restart) and `__gstat_c : INT` (0 inactive, 1
//! active, 2 frozen — what `GSTATUS(c)` returns). The rewrite makes:
//! - in the parent: `GSTART(c);` → `__gcmd_c := 1;` (GKILL 2, GFREEZE 3,
//!   GRST 4); `GSTATUS(c)` → `__gstat_c`; an association `c(N)` of step s →
//!   at the end of the parent's body, on the rising edge of `s.X` a start,
//!   on its falling edge a kill (`c(S)`: start only, `c(R)`: kill at
//!   activation);
//! - in the child: before its chart, on its first call, every step is made
//!   inactive (a child does not run until started); the chart code runs
//!   only while the child is active and in the one call after a kill or a
//!   freeze (the final scan), since ISaGRAF does not execute an inactive
//!   child (its boolean actions would otherwise write FALSE over what
//!   another chart drives); after its chart (where
//!   a firing takes effect too) the pending command is carried out through
//!   the steps' own inputs (`__E` activates, `__L` deactivates, as a firing
//!   would) and cleared:
//!   - start (when inactive): the initial step is activated (its P/P1
//!     actions run in the next call), status 1;
//!   - kill (when active or frozen): every active step is left (its N
//!     actions get their final scan, P0 actions run), status 0, and the
//!     child's own children get a kill;
//!   - freeze (when active): the active steps are remembered and
//!     deactivated without P0, status 2, the child's children get a freeze;
//!   - restart (when frozen): the remembered steps are active again (step
//!     time from T#0s, no pulse actions), status 1; its children stay as
//!     they are.
//!
//! A command takes effect when the child next runs: in the same cycle when
//! the child comes after its parent in the Sequential section (the usual
//! order: write children after parents), else in the next one. The last
//! command given before the child runs wins. Children run in the
//! Sequential section like any program (the section configuration is
//! generated when a project has children).
//!
//! Errors: E155 the argument is not a PROGRAM of the project, E156 a child
//! with two parents or a program controlling itself, E157 a child
//! association with a qualifier other than N, S or R, E158 a child that is
//! not an SFC chart.

mod child;

use crate::build;
use crate::walk::{self, Visitor};
use automat_base::{Code, Diagnostic, Interner, Span, Symbol};
use automat_syntax::ast::sfc::Qualifier;
use automat_syntax::ast::{
    Body, Expr, ExprKind, Ident, Item, Lang, Pou, PouKind, Retain, SourceUnit, Stmt, StmtKind,
    VarBlock, VarDecl, VarKind,
};

const START: i128 = 1;
const KILL: i128 = 2;
const FREEZE: i128 = 3;
const RESTART: i128 = 4;

/// One control of a child by a parent.
struct Link {
    parent: Symbol,
    child: Symbol,
    span: Span,
}

/// A `child(q)` association of a parent step.
struct ChildAssoc {
    step: Ident,
    child: Symbol,
    qualifier: Qualifier,
}

/// What the rewrite found.
pub struct Found {
    /// The project has children: the section configuration is needed.
    pub any: bool,
    /// The associations taken over as child controls (their E125 is void).
    pub taken: Vec<Span>,
    /// The child programs (their whole text).
    pub children: Vec<Span>,
}

/// Rewrites the child controls of the user units.
pub fn rewrite(
    units: &mut [SourceUnit],
    is_user: &dyn Fn(&SourceUnit) -> bool,
    interner: &mut Interner,
    diags: &mut Vec<Diagnostic>,
) -> Found {
    let programs: Vec<Symbol> = units
        .iter()
        .filter(|u| is_user(u))
        .flat_map(|u| u.items.iter())
        .filter_map(|i| match i {
            Item::Pou(p) if p.kind == PouKind::Program => Some(p.name.sym),
            _ => None,
        })
        .collect();
    let names = Names::new(interner);
    let mut links: Vec<Link> = Vec::new();
    let mut taken = Vec::new();
    // Pass 1: rewrite the calls and collect the associations, per POU.
    let mut assocs: Vec<(Symbol, Vec<ChildAssoc>)> = Vec::new();
    for unit in units.iter_mut().filter(|u| is_user(u)) {
        for item in &mut unit.items {
            let Item::Pou(p) = item else { continue };
            if p.kind == PouKind::Function {
                continue;
            }
            let mut calls = Calls {
                names: &names,
                programs: &programs,
                parent: p.name.sym,
                interner: &mut *interner,
                links: &mut links,
                diags: &mut *diags,
            };
            let Body::St(stmts) = &mut p.body;
            walk::stmts(stmts, &mut calls);
            let found = chart_assocs(p, &programs, &mut taken, diags);
            for a in &found {
                links.push(Link {
                    parent: p.name.sym,
                    child: a.child,
                    span: a.step.span,
                });
            }
            if !found.is_empty() {
                assocs.push((p.name.sym, found));
            }
        }
    }
    if links.is_empty() {
        return Found {
            any: false,
            taken,
            children: Vec::new(),
        };
    }
    check_hierarchy(&links, interner, diags);
    let mut children: Vec<Symbol> = links.iter().map(|l| l.child).collect();
    children.sort_by_key(|s| s.0);
    children.dedup();
    // Pass 2: declarations, parent association code, child command handling.
    let mut globals = Vec::new();
    let mut child_spans = Vec::new();
    for c in &children {
        let (cmd, stat) = hidden(interner, *c, Span::default());
        let int = build::ident(interner, "INT", Span::default());
        globals.push(build::var(cmd, int));
        globals.push(build::var(stat, int));
    }
    for unit in units.iter_mut().filter(|u| is_user(u)) {
        for item in &mut unit.items {
            let Item::Pou(p) = item else { continue };
            let sym = p.name.sym;
            if children.contains(&sym) {
                child_spans.push(p.span);
            }
            let mut used: Vec<Symbol> = links
                .iter()
                .filter(|l| l.parent == sym)
                .map(|l| l.child)
                .collect();
            if children.contains(&sym) {
                used.push(sym);
            }
            used.sort_by_key(|s| s.0);
            used.dedup();
            if used.is_empty() {
                continue;
            }
            externals(p, &used, interner);
            let edges = match assocs.iter().find(|(s, _)| *s == sym) {
                Some((_, list)) => parent_code(p, list, interner),
                None => Vec::new(),
            };
            if children.contains(&sym) {
                let own: Vec<Symbol> = links
                    .iter()
                    .filter(|l| l.parent == sym)
                    .map(|l| l.child)
                    .collect();
                // The body is still the chart code alone: the child code
                // gates it and puts the edge detection after it.
                child::child_code(p, &own, edges, interner, diags);
            } else {
                let Body::St(stmts) = &mut p.body;
                stmts.extend(edges);
            }
        }
    }
    if let Some(first) = units.iter_mut().find(|u| is_user(u)) {
        first.items.push(Item::Globals(VarBlock {
            kind: VarKind::Global,
            constant: false,
            retain: Retain::Unspecified,
            decls: globals,
            span: Span::default(),
        }));
    }
    Found {
        any: true,
        taken,
        children: child_spans,
    }
}

/// The call names, interned once.
struct Names {
    gstart: Symbol,
    gkill: Symbol,
    gfreeze: Symbol,
    grst: Symbol,
    gstatus: Symbol,
}

impl Names {
    fn new(interner: &mut Interner) -> Names {
        Names {
            gstart: interner.intern("GSTART"),
            gkill: interner.intern("GKILL"),
            gfreeze: interner.intern("GFREEZE"),
            grst: interner.intern("GRST"),
            gstatus: interner.intern("GSTATUS"),
        }
    }

    fn command(&self, f: Symbol) -> Option<(i128, &'static str)> {
        Some(match f {
            f if f == self.gstart => (START, "GSTART"),
            f if f == self.gkill => (KILL, "GKILL"),
            f if f == self.gfreeze => (FREEZE, "GFREEZE"),
            f if f == self.grst => (RESTART, "GRST"),
            _ => return None,
        })
    }
}

/// The hidden (command, status) globals of a child.
fn hidden(interner: &mut Interner, child: Symbol, span: Span) -> (Ident, Ident) {
    let n = interner.name(child).to_ascii_lowercase();
    (
        build::ident(interner, &format!("__gcmd_{n}"), span),
        build::ident(interner, &format!("__gstat_{n}"), span),
    )
}

/// The callee and single program argument of `F(p)`.
fn call_parts(e: &Expr) -> Option<(Symbol, Option<Ident>)> {
    let ExprKind::Call { callee, args } = &e.kind else {
        return None;
    };
    let ExprKind::Name(f) = callee.kind else {
        return None;
    };
    let arg = match args.as_slice() {
        [a] if a.name.is_none() => a.value.as_ref().and_then(|v| match v.kind {
            ExprKind::Name(id) => Some(id),
            _ => None,
        }),
        _ => None,
    };
    Some((f.sym, arg))
}

struct Calls<'a> {
    names: &'a Names,
    programs: &'a [Symbol],
    parent: Symbol,
    interner: &'a mut Interner,
    links: &'a mut Vec<Link>,
    diags: &'a mut Vec<Diagnostic>,
}

impl Calls<'_> {
    /// The child a call names, or E155.
    fn child(&mut self, what: &str, arg: Option<Ident>, span: Span) -> Option<Ident> {
        match arg {
            Some(id) if id.sym == self.parent => {
                self.diags.push(Diagnostic::error(
                    Code::E156,
                    span,
                    format!(
                        "program `{}` cannot control itself",
                        self.interner.name(id.sym)
                    ),
                ));
                None
            }
            Some(id) if self.programs.contains(&id.sym) => {
                self.links.push(Link {
                    parent: self.parent,
                    child: id.sym,
                    span,
                });
                Some(id)
            }
            _ => {
                self.diags.push(Diagnostic::error(
                    Code::E155,
                    span,
                    format!("{what} needs the name of a PROGRAM of the project (the child chart)"),
                ));
                None
            }
        }
    }
}

impl Visitor for Calls<'_> {
    fn stmt(&mut self, s: &mut Stmt) {
        let StmtKind::Expr(e) = &s.kind else { return };
        let Some((f, arg)) = call_parts(e) else {
            return;
        };
        let Some((code, what)) = self.names.command(f) else {
            return;
        };
        let span = s.span;
        s.kind = match self.child(what, arg, span) {
            Some(c) => {
                let (cmd, _) = hidden(self.interner, c.sym, span);
                build::assign(build::name(cmd), build::int_lit(code, span), span).kind
            }
            None => StmtKind::Empty,
        };
    }

    fn expr(&mut self, e: &mut Expr) {
        let Some((f, arg)) = call_parts(e) else {
            return;
        };
        if f != self.names.gstatus {
            return;
        }
        let span = e.span;
        *e = match self.child("GSTATUS", arg, span) {
            Some(c) => build::name(hidden(self.interner, c.sym, span).1),
            None => build::int_lit(0, span),
        };
    }
}

/// The associations of a chart that name a PROGRAM (not an action or a
/// variable of the POU).
fn chart_assocs(
    p: &Pou,
    programs: &[Symbol],
    taken: &mut Vec<Span>,
    diags: &mut Vec<Diagnostic>,
) -> Vec<ChildAssoc> {
    let Lang::Sfc(chart) = &p.lang else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for step in &chart.steps {
        for a in &step.assocs {
            let sym = a.name.sym;
            let local = chart.actions.iter().any(|x| x.name.sym == sym)
                || p.var_blocks
                    .iter()
                    .flat_map(|b| b.decls.iter())
                    .any(|d| d.names.iter().any(|n| n.sym == sym));
            if local || !programs.contains(&sym) {
                continue;
            }
            taken.push(a.name.span);
            if sym == p.name.sym {
                diags.push(Diagnostic::error(
                    Code::E156,
                    a.name.span,
                    "a program cannot control itself",
                ));
                continue;
            }
            if !matches!(a.qualifier, Qualifier::N | Qualifier::S | Qualifier::R) {
                diags.push(Diagnostic::error(
                    Code::E157,
                    a.span,
                    format!(
                        "a child program is started or killed with N, S or R, not {}",
                        a.qualifier.name()
                    ),
                ));
                continue;
            }
            out.push(ChildAssoc {
                step: step.name,
                child: sym,
                qualifier: a.qualifier,
            });
        }
    }
    out
}

/// Each child has one parent (self-control was refused where it was written).
fn check_hierarchy(links: &[Link], interner: &Interner, diags: &mut Vec<Diagnostic>) {
    for (i, l) in links.iter().enumerate() {
        let name = interner.name(l.child);
        if let Some(first) = links
            .iter()
            .take(i)
            .find(|k| k.child == l.child && k.parent != l.parent)
        {
            diags.push(
                Diagnostic::error(
                    Code::E156,
                    l.span,
                    format!(
                        "`{name}` is already the child of `{}`: a child has one parent",
                        interner.name(first.parent)
                    ),
                )
                .with_label(first.span, "first controlled here"),
            );
        }
    }
}

/// VAR_EXTERNAL for the hidden globals of `children`.
fn externals(p: &mut Pou, children: &[Symbol], interner: &mut Interner) {
    let span = p.name.span;
    let int = build::ident(interner, "INT", span);
    let mut decls = Vec::new();
    for c in children {
        let (cmd, stat) = hidden(interner, *c, span);
        decls.push(build::var(cmd, int));
        decls.push(build::var(stat, int));
    }
    p.var_blocks.push(VarBlock {
        kind: VarKind::External,
        constant: false,
        retain: Retain::Unspecified,
        decls,
        span,
    });
}

fn locals(p: &mut Pou, decls: Vec<VarDecl>) {
    let span = p.name.span;
    p.var_blocks.push(VarBlock {
        kind: VarKind::Local,
        constant: false,
        retain: Retain::Unspecified,
        decls,
        span,
    });
}

/// The edge detection that turns `child(q)` associations into commands
/// (its variables are declared in `p`; the code goes after the chart).
fn parent_code(p: &mut Pou, list: &[ChildAssoc], interner: &mut Interner) -> Vec<Stmt> {
    let boolean = build::ident(interner, "BOOL", p.name.span);
    let mut decls = Vec::new();
    let mut code = Vec::new();
    for (k, a) in list.iter().enumerate() {
        let sp = a.step.span;
        let prev = build::ident(interner, &format!("__gprev_{k}"), sp);
        decls.push(build::var(prev, boolean));
        let x = build::member(interner, a.step, "X", sp);
        let (cmd, _) = hidden(interner, a.child, sp);
        let on = match a.qualifier {
            Qualifier::R => KILL,
            _ => START,
        };
        let rising = build::binary(
            automat_syntax::ast::BinaryOp::And,
            x.clone(),
            build::not(build::name(prev), sp),
            sp,
        );
        let mut branches = vec![(
            rising,
            vec![build::assign(build::name(cmd), build::int_lit(on, sp), sp)],
        )];
        if a.qualifier == Qualifier::N {
            let falling = build::binary(
                automat_syntax::ast::BinaryOp::And,
                build::not(x.clone(), sp),
                build::name(prev),
                sp,
            );
            branches.push((
                falling,
                vec![build::assign(
                    build::name(cmd),
                    build::int_lit(KILL, sp),
                    sp,
                )],
            ));
        }
        code.push(build::if_chain(branches, sp));
        code.push(build::assign(build::name(prev), x, sp));
    }
    locals(p, decls);
    code
}
