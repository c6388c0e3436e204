//! PL7 step objects `%Xi` / `%Xi.T` are global: PRL and POST read them.
//!
//! In the chart, step i is the step instance `_Xi` (its `.X`, `.T`); a bare
//! `%Xi` there means its activity, `_Xi.X`. Every chart keeps global
//! mirrors `__pl7_x_i : BOOL` / `__pl7_t_i : TIME`, written at the end of
//! its call; other POUs read `%Xi` and `%Xi.T` through them (so PRL sees the
//! state the previous cycle left, POST the state of this one, as in PL7).
//! One step number belongs to one chart (E159).

use crate::build;
use crate::walk::{self, Visitor};
use automat_base::{Code, Diagnostic, Interner, Span, Symbol};
use automat_syntax::ast::{
    Body, Expr, ExprKind, Ident, Item, Lang, Pou, PouKind, Retain, SourceUnit, VarBlock, VarKind,
};

/// The step number of a name `_X<digits>` (any case).
fn step_number(name: &str) -> Option<u32> {
    let digits = name
        .strip_prefix("_X")
        .or_else(|| name.strip_prefix("_x"))?;
    if digits.is_empty() || digits.len() > 5 || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    digits.parse().ok()
}

fn mirrors(interner: &mut Interner, i: u32, span: Span) -> (Ident, Ident) {
    (
        build::ident(interner, &format!("__pl7_x_{i}"), span),
        build::ident(interner, &format!("__pl7_t_{i}"), span),
    )
}

/// Declares the mirrors, writes them in the charts, reads them elsewhere.
pub fn rewrite(
    units: &mut [SourceUnit],
    is_user: &dyn Fn(&SourceUnit) -> bool,
    interner: &mut Interner,
    diags: &mut Vec<Diagnostic>,
) {
    // (step number, chart, step name) of every chart.
    let mut steps: Vec<(u32, Symbol, Ident)> = Vec::new();
    for unit in units.iter().filter(|u| is_user(u)) {
        for item in &unit.items {
            let Item::Pou(p) = item else { continue };
            let Lang::Sfc(chart) = &p.lang else { continue };
            for s in &chart.steps {
                let Some(i) = step_number(interner.name(s.name.sym)) else {
                    continue;
                };
                if let Some((_, other, _)) = steps.iter().find(|(j, _, _)| *j == i) {
                    diags.push(Diagnostic::error(
                        Code::E159,
                        s.name.span,
                        format!(
                            "step %X{i} is already a step of `{}`: a PL7 step number names one step",
                            interner.name(*other)
                        ),
                    ));
                    continue;
                }
                steps.push((i, p.name.sym, s.name));
            }
        }
    }
    if steps.is_empty() {
        return;
    }
    let boolean = build::ident(interner, "BOOL", Span::default());
    let time = build::ident(interner, "TIME", Span::default());
    let all: Vec<(u32, Ident, Ident)> = steps
        .iter()
        .map(|(i, _, _)| {
            let (x, t) = mirrors(interner, *i, Span::default());
            (*i, x, t)
        })
        .collect();
    for unit in units.iter_mut().filter(|u| is_user(u)) {
        for item in &mut unit.items {
            let Item::Pou(p) = item else { continue };
            if p.kind == PouKind::Function {
                continue;
            }
            let own: Vec<(u32, Ident)> = steps
                .iter()
                .filter(|(_, c, _)| *c == p.name.sym)
                .map(|(i, _, s)| (*i, *s))
                .collect();
            let mut v = Names {
                interner: &mut *interner,
                own: &own,
                all: &all,
                used: false,
            };
            let Body::St(stmts) = &mut p.body;
            walk::stmts(stmts, &mut v);
            if !v.used && own.is_empty() {
                continue;
            }
            externals(p, &all, boolean, time);
            write_mirrors(p, &own, interner);
        }
    }
    let decls = all
        .iter()
        .flat_map(|(_, x, t)| [build::var(*x, boolean), build::var(*t, time)])
        .collect();
    if let Some(first) = units.iter_mut().find(|u| is_user(u)) {
        first.items.push(Item::Globals(VarBlock {
            kind: VarKind::Global,
            constant: false,
            retain: Retain::Unspecified,
            decls,
            span: Span::default(),
        }));
    }
}

fn externals(p: &mut Pou, all: &[(u32, Ident, Ident)], boolean: Ident, time: Ident) {
    let span = p.name.span;
    let decls = all
        .iter()
        .flat_map(|(_, x, t)| {
            [
                build::var(Ident { span, ..*x }, Ident { span, ..boolean }),
                build::var(Ident { span, ..*t }, Ident { span, ..time }),
            ]
        })
        .collect();
    p.var_blocks.push(VarBlock {
        kind: VarKind::External,
        constant: false,
        retain: Retain::Unspecified,
        decls,
        span,
    });
}

/// At the end of a chart's body: its steps' mirrors.
fn write_mirrors(p: &mut Pou, own: &[(u32, Ident)], interner: &mut Interner) {
    let sp = p.name.span;
    let mut code = Vec::new();
    for (i, s) in own {
        let (x, t) = mirrors(interner, *i, sp);
        code.push(build::assign(
            build::name(x),
            build::member(interner, *s, "X", sp),
            sp,
        ));
        code.push(build::assign(
            build::name(t),
            build::member(interner, *s, "T", sp),
            sp,
        ));
    }
    let Body::St(stmts) = &mut p.body;
    stmts.extend(code);
}

/// `%Xi` / `%Xi.T` / `%Xi.X` in expressions.
struct Names<'a> {
    interner: &'a mut Interner,
    /// The steps of this POU's own chart.
    own: &'a [(u32, Ident)],
    all: &'a [(u32, Ident, Ident)],
    used: bool,
}

impl Names<'_> {
    fn step_of(&self, id: Ident) -> Option<u32> {
        step_number(self.interner.name(id.sym))
    }
}

impl Visitor for Names<'_> {
    fn expr_pre(&mut self, e: &mut Expr) -> bool {
        let span = e.span;
        match &e.kind {
            ExprKind::Member { base, member } => {
                let ExprKind::Name(id) = base.kind else {
                    return true;
                };
                let Some(i) = self.step_of(id) else {
                    return true;
                };
                if self.own.iter().any(|(j, _)| *j == i) {
                    return false; // the chart's own step instance
                }
                let Some((_, x, t)) = self.all.iter().find(|(j, _, _)| *j == i) else {
                    return true;
                };
                let m = self.interner.name(member.sym).to_ascii_uppercase();
                let mirror = match m.as_str() {
                    "X" => *x,
                    "T" => *t,
                    _ => return true,
                };
                self.used = true;
                *e = build::name(Ident { span, ..mirror });
                false
            }
            ExprKind::Name(id) => {
                let id = *id;
                let Some(i) = self.step_of(id) else {
                    return true;
                };
                if self.own.iter().any(|(j, _)| *j == i) {
                    *e = build::member(self.interner, id, "X", span);
                } else if let Some((_, x, _)) = self.all.iter().find(|(j, _, _)| *j == i) {
                    self.used = true;
                    *e = build::name(Ident { span, ..*x });
                }
                false
            }
            _ => true,
        }
    }
}
