//! The ST code and hidden declarations of a resolved chart (the scheme is
//! in the parent module's comment).

use super::build::{and_all, assign, binary, bool_lit, if_then, not, or_all, var, Builder};
use super::check::Resolved;
use crate::ast::sfc::{Assoc, Chart, Condition, Qualifier};
use crate::ast::{BinaryOp, Stmt, VarBlock, VarDecl, VarKind};
use automat_base::{Interner, Span, Symbol};
use std::collections::{HashMap, HashSet};

/// Who an action control drives: an ACTION's body or a BOOL variable.
enum Driven {
    Action(usize),
    Var(Symbol, Span),
}

/// One action control instance and the associations feeding it.
struct Control<'c> {
    inst: Symbol,
    driven: Driven,
    /// (step index, association), in source order.
    assocs: Vec<(usize, &'c Assoc)>,
}

struct Gen<'c, 'i> {
    b: Builder<'i>,
    chart: &'c Chart,
    r: &'c Resolved,
    span: Span,
    /// Instance name of each step.
    step_inst: Vec<Symbol>,
    decls: Vec<VarDecl>,
    dt: Symbol,
}

pub(super) fn generate(
    chart: &Chart,
    r: &Resolved,
    vars: &HashSet<Symbol>,
    span: Span,
    interner: &mut Interner,
) -> (Vec<Stmt>, VarBlock) {
    let mut b = Builder { interner };
    let dt = b.sym("__sfc_dt");
    let mut g = Gen {
        b,
        chart,
        r,
        span,
        step_inst: Vec::new(),
        decls: Vec::new(),
        dt,
    };
    let mut out = Vec::new();
    g.declare_steps();
    let controls = g.controls(vars);
    g.clock(&mut out);
    g.tick_steps(&mut out);
    g.actions(&controls, &mut out);
    g.transitions(&mut out);
    let block = VarBlock {
        kind: VarKind::Local,
        constant: false,
        retain: crate::ast::Retain::Unspecified,
        decls: std::mem::take(&mut g.decls),
        span,
    };
    (out, block)
}

impl<'c> Gen<'c, '_> {
    /// The name of the instance of a step or action: its own, or a hidden
    /// one when a variable has it (E122 was reported).
    fn inst_name(&mut self, sym: Symbol, hidden: String) -> Symbol {
        if self.r.clash.contains(&sym) {
            self.b.sym(&hidden)
        } else {
            sym
        }
    }

    fn declare_steps(&mut self) {
        for (i, s) in self.chart.steps.iter().enumerate() {
            let inst = self.inst_name(s.name.sym, format!("__sfc_s{i}"));
            self.step_inst.push(inst);
            if self.r.step_ok.get(i).copied().unwrap_or(false) {
                let ty = if s.initial {
                    "__SFC_INITIAL_STEP"
                } else {
                    "__SFC_STEP"
                };
                let d = self.b.decl(inst, ty, None, s.name.span);
                self.decls.push(d);
            }
        }
    }

    /// The action controls: code actions in declaration order, then BOOL
    /// variables in order of first association.
    fn controls(&mut self, vars: &HashSet<Symbol>) -> Vec<Control<'c>> {
        let chart = self.chart;
        let mut out: Vec<Control<'c>> = Vec::new();
        let mut by_name: HashMap<Symbol, usize> = HashMap::new();
        for (i, a) in chart.actions.iter().enumerate() {
            if !self.r.action_ok.get(i).copied().unwrap_or(false) {
                continue;
            }
            let inst = self.inst_name(a.name.sym, format!("__sfc_a{i}"));
            let d = self.b.decl(inst, "__SFC_ACTION", None, a.name.span);
            self.decls.push(d);
            by_name.insert(a.name.sym, out.len());
            out.push(Control {
                inst,
                driven: Driven::Action(i),
                assocs: Vec::new(),
            });
        }
        for (si, s) in chart.steps.iter().enumerate() {
            if !self.r.step_ok.get(si).copied().unwrap_or(false) {
                continue;
            }
            for a in &s.assocs {
                let k = match by_name.get(&a.name.sym) {
                    Some(&k) => k,
                    None if vars.contains(&a.name.sym) => {
                        let inst = self.b.sym(&format!("__sfc_v{}", out.len()));
                        let d = self.b.decl(inst, "__SFC_ACTION", None, a.name.span);
                        self.decls.push(d);
                        by_name.insert(a.name.sym, out.len());
                        out.push(Control {
                            inst,
                            driven: Driven::Var(a.name.sym, a.name.span),
                            assocs: Vec::new(),
                        });
                        out.len() - 1
                    }
                    None => continue, // E125 was reported
                };
                if let Some(c) = out.get_mut(k) {
                    c.assocs.push((si, a));
                }
            }
        }
        out
    }

    /// Phase 0: the time since the chart's previous call.
    fn clock(&mut self, out: &mut Vec<Stmt>) {
        let sp = self.span;
        let run = self.b.sym("__sfc_run");
        let last = self.b.sym("__sfc_last");
        for (sym, ty) in [(run, "BOOL"), (last, "TIME"), (self.dt, "TIME")] {
            let d = self.b.decl(sym, ty, None, sp);
            self.decls.push(d);
        }
        let now = self.b.call0("__SCAN_TIME", sp);
        let diff = binary(BinaryOp::Sub, now.clone(), var(last, sp), sp);
        let set_dt = assign(var(self.dt, sp), diff, sp);
        out.push(if_then(var(run, sp), vec![set_dt], sp));
        out.push(assign(var(run, sp), bool_lit(true, sp), sp));
        out.push(assign(var(last, sp), now, sp));
    }

    /// Phase 1: active steps count their time.
    fn tick_steps(&mut self, out: &mut Vec<Stmt>) {
        for (i, s) in self.chart.steps.iter().enumerate() {
            if !self.r.step_ok.get(i).copied().unwrap_or(false) {
                continue;
            }
            let Some(&inst) = self.step_inst.get(i) else {
                continue;
            };
            let sp = s.name.span;
            let args = vec![("__TICK", bool_lit(true, sp)), ("__DT", var(self.dt, sp))];
            out.push(self.b.call_stmt(inst, args, sp));
        }
    }

    /// A step's member (`X`, `T`, `__E`, `__L`) as an expression.
    fn step_member(&mut self, step: usize, member: &str, span: Span) -> Option<crate::ast::Expr> {
        let inst = *self.step_inst.get(step)?;
        Some(self.b.member(inst, member, span))
    }

    /// Phase 2: action controls, BOOL variables, then action bodies.
    fn actions(&mut self, controls: &[Control<'c>], out: &mut Vec<Stmt>) {
        const INPUTS: [(Qualifier, &str, &str); 11] = [
            (Qualifier::N, "__N", "X"),
            (Qualifier::R, "__R", "X"),
            (Qualifier::S, "__S", "X"),
            (Qualifier::L, "__L", "X"),
            (Qualifier::D, "__D", "X"),
            (Qualifier::P, "__P", "__E"),
            (Qualifier::SD, "__SD", "X"),
            (Qualifier::DS, "__DS", "X"),
            (Qualifier::SL, "__SL", "X"),
            (Qualifier::P1, "__P1", "__E"),
            (Qualifier::P0, "__P0", "__L"),
        ];
        for c in controls {
            let sp = match c.driven {
                Driven::Action(i) => self.chart.actions.get(i).map_or(self.span, |a| a.name.span),
                Driven::Var(_, sp) => sp,
            };
            // The duration and elapsed time of the active timed association.
            for &(si, a) in &c.assocs {
                let (Some(t), true) = (&a.time, a.qualifier.is_timed()) else {
                    continue;
                };
                let (Some(x), Some(et)) = (
                    self.step_member(si, "X", a.span),
                    self.step_member(si, "T", a.span),
                ) else {
                    continue;
                };
                let set_t = assign(self.b.member(c.inst, "__T", a.span), t.clone(), a.span);
                let set_et = assign(self.b.member(c.inst, "__ET", a.span), et, a.span);
                out.push(if_then(x, vec![set_t, set_et], a.span));
            }
            let mut args = Vec::new();
            for (q, input, member) in INPUTS {
                let terms: Vec<_> = c
                    .assocs
                    .iter()
                    .filter(|(_, a)| a.qualifier == q)
                    .filter_map(|&(si, a)| self.step_member(si, member, a.span))
                    .collect();
                if !terms.is_empty() {
                    args.push((input, or_all(terms, sp)));
                }
            }
            args.push(("__DT", var(self.dt, sp)));
            out.push(self.b.call_stmt(c.inst, args, sp));
            if let Driven::Var(v, vsp) = c.driven {
                let q = self.b.member(c.inst, "Q", vsp);
                out.push(assign(var(v, vsp), q, vsp));
            }
        }
        for c in controls {
            if let Driven::Action(i) = c.driven {
                let Some(a) = self.chart.actions.get(i) else {
                    continue;
                };
                let cond = self.b.member(c.inst, "A", a.name.span);
                out.push(if_then(cond, a.body.stmts().to_vec(), a.span));
            }
        }
    }

    /// Phase 3: fire flags in precedence order, then the steps' updates.
    fn transitions(&mut self, out: &mut Vec<Stmt>) {
        let chart = self.chart;
        let n = chart.transitions.len();
        let flags: Vec<Symbol> = (0..n).map(|i| self.b.sym(&format!("__sfc_t{i}"))).collect();
        for (i, t) in chart.transitions.iter().enumerate() {
            if let Some(&f) = flags.get(i) {
                let d = self.b.decl(f, "BOOL", None, t.span);
                self.decls.push(d);
            }
        }
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by_key(|&i| {
            let p = chart.transitions.get(i).and_then(|t| t.priority);
            (p.is_none(), p.unwrap_or(0), i)
        });
        let empty = Vec::new();
        let from = |i: usize| self.r.from.get(i).unwrap_or(&empty);
        for (k, &i) in order.iter().enumerate() {
            let (Some(t), Some(&flag)) = (chart.transitions.get(i), flags.get(i)) else {
                continue;
            };
            let sp = t.span;
            out.push(assign(var(flag, sp), bool_lit(false, sp), sp));
            let fi = from(i);
            if fi.is_empty() {
                continue; // no known preceding step (reported): never fires
            }
            let mut terms = Vec::new();
            // A macro-step is active when its exit step is: its flag is
            // left out of the test.
            let plain: Vec<usize> = fi.iter().copied().filter(|&s| !self.is_macro(s)).collect();
            for s in plain {
                if let Some(x) = self.step_member(s, "X", sp) {
                    terms.push(x);
                }
            }
            // Transitions of higher precedence sharing a preceding step.
            for &j in order.iter().take(k) {
                if from(j).iter().any(|s| fi.contains(s)) {
                    if let Some(&fj) = flags.get(j) {
                        terms.push(not(var(fj, sp), sp));
                    }
                }
            }
            let set = assign(var(flag, sp), bool_lit(true, sp), sp);
            let body = match &t.cond {
                Condition::St(e) => vec![if_then(e.clone(), vec![set], e.span)],
                Condition::Il { stmts, result, .. } => {
                    let mut v = stmts.clone();
                    v.push(if_then(result.clone(), vec![set], result.span));
                    v
                }
                Condition::Missing => continue,
            };
            if let Some(enabled) = and_all(terms, sp) {
                out.push(if_then(enabled, body, sp));
            }
        }
        // Ordinary steps first: a macro-step's update reads its body's new
        // flags.
        let steps = (0..chart.steps.len()).filter(|&i| !self.is_macro(i));
        let macros = (0..chart.steps.len()).filter(|&i| self.is_macro(i));
        for si in steps.chain(macros).collect::<Vec<_>>() {
            let Some(s) = chart.steps.get(si) else {
                continue;
            };
            if !self.r.step_ok.get(si).copied().unwrap_or(false) {
                continue;
            }
            let Some(&inst) = self.step_inst.get(si) else {
                continue;
            };
            let sp = s.name.span;
            let pick = |list: &Vec<Vec<usize>>| -> Vec<Symbol> {
                list.iter()
                    .zip(&flags)
                    .filter(|(steps, _)| steps.contains(&si))
                    .map(|(_, &f)| f)
                    .collect()
            };
            let (entered, left) = (pick(&self.r.to), pick(&self.r.from));
            let e = entered.into_iter().map(|f| var(f, sp)).collect();
            let l = match self.macro_body(si) {
                // Left when it was active and no step of its body is now.
                Some(body) => {
                    let mut any = Vec::new();
                    for b in body {
                        any.extend(self.step_member(b, "X", sp));
                    }
                    let was = self.b.member(inst, "X", sp);
                    binary(BinaryOp::And, was, not(or_all(any, sp), sp), sp)
                }
                None => or_all(left.into_iter().map(|f| var(f, sp)).collect(), sp),
            };
            let args = vec![
                ("__TICK", bool_lit(false, sp)),
                ("__E", or_all(e, sp)),
                ("__L", l),
            ];
            out.push(self.b.call_stmt(inst, args, sp));
        }
    }

    fn is_macro(&self, step: usize) -> bool {
        self.r.macro_of.get(step).copied().flatten().is_some()
    }

    /// The body steps of a macro-step (see `MacroR::body`).
    fn macro_body(&self, step: usize) -> Option<Vec<usize>> {
        let k = self.r.macro_of.get(step).copied().flatten()?;
        Some(self.r.macros.get(k)?.body.clone())
    }
}
