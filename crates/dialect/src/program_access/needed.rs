//! Which variables of a program other POUs reach: only those move to
//! hidden globals, so the rest (the inputs a configuration connects, the
//! program's working variables) stay the instance's own.
//!
//! A variable is reached when another POU names it (`Main.count`,
//! `Main.ctr.CV`) or when an action another POU calls (`Main.Reset();`,
//! the hidden function with the program's other actions inlined) uses it.
//! A configuration connecting an input or output that is reached
//! (`PROGRAM Main WITH T : Main(count := g);`) is E164: one global serves
//! every POU that names it, which no instance's connection can write.

use super::{names, Program, PREFIX};
use crate::walk::{self, Visitor};
use automat_base::{Code, Diagnostic, Interner, Span, Symbol};
use automat_syntax::ast::{Body, Expr, ExprKind, Item, PouKind, SourceUnit, Stmt};
use std::collections::{HashMap, HashSet};

/// Program → variable → where it is first reached (`true`: by a call of
/// an action that uses it).
type Reached = HashMap<Symbol, HashMap<Symbol, (Span, bool)>>;

/// Keeps in each program's `globals` and `externals` only the variables
/// other POUs reach, and notes where (`reached_at`).
pub(super) fn keep_reached(
    units: &mut [SourceUnit],
    is_user: &dyn Fn(&SourceUnit) -> bool,
    interner: &Interner,
    programs: &mut HashMap<Symbol, Program>,
) {
    let mut reached = Reached::new();
    // Hidden action function → (its program, the first outside call).
    let mut called: HashMap<Symbol, (Symbol, Span)> = HashMap::new();
    for unit in units.iter_mut().filter(|u| is_user(u)) {
        let mut owner = None;
        for item in &mut unit.items {
            match item {
                Item::Pou(p) => {
                    if p.kind == PouKind::Program {
                        owner = Some(p.name.sym);
                    } else if !interner.name(p.name.sym).starts_with(PREFIX) {
                        owner = None;
                    }
                    let declared = names(&p.var_blocks, &[]);
                    let Body::St(stmts) = &mut p.body;
                    let mut n = Names::new(&declared, owner, programs, &mut reached, &mut called);
                    walk::stmts(stmts, &mut n);
                }
                Item::Class(c) => {
                    owner = None;
                    let outer = &c.var_blocks;
                    let mut bodies: Vec<(HashSet<Symbol>, &mut Vec<Stmt>)> =
                        vec![(names(outer, &[]), &mut c.body)];
                    for m in &mut c.methods {
                        bodies.push((names(outer, &m.var_blocks), &mut m.body));
                    }
                    for prop in &mut c.properties {
                        for acc in [&mut prop.get, &mut prop.set].into_iter().flatten() {
                            bodies.push((names(outer, &acc.var_blocks), &mut acc.body));
                        }
                    }
                    for (declared, body) in bodies {
                        let mut n =
                            Names::new(&declared, None, programs, &mut reached, &mut called);
                        walk::stmts(body, &mut n);
                    }
                }
                _ => owner = None,
            }
        }
    }
    // The variables the actions called from outside use.
    for unit in units.iter_mut().filter(|u| is_user(u)) {
        for item in &mut unit.items {
            let Item::Pou(p) = item else { continue };
            let Some(&(prog, call)) = called.get(&p.name.sym) else {
                continue;
            };
            let Some(program) = programs.get(&prog) else {
                continue;
            };
            let declared = names(&p.var_blocks, &[]);
            let Body::St(stmts) = &mut p.body;
            let mut used = Used {
                declared: &declared,
                candidates: &program.globals,
                found: HashSet::new(),
            };
            walk::stmts(stmts, &mut used);
            let entry = reached.entry(prog).or_default();
            for v in used.found {
                entry.entry(v).or_insert((call, true));
            }
        }
    }
    for (sym, prog) in programs.iter_mut() {
        let here = reached.remove(sym).unwrap_or_default();
        prog.globals.retain(|v, _| here.contains_key(v));
        let kept: HashSet<Symbol> = prog.globals.values().copied().collect();
        prog.externals.retain(|g, _| kept.contains(g));
        prog.reached_at = here;
    }
}

/// E164 for a configuration's connection of a program input or output
/// that other POUs reach (then a hidden global); the connection is
/// dropped, so the checker does not report it again as unknown.
pub(super) fn check_connections(
    units: &mut [SourceUnit],
    is_user: &dyn Fn(&SourceUnit) -> bool,
    programs: &HashMap<Symbol, Program>,
    interner: &Interner,
    diags: &mut Vec<Diagnostic>,
) {
    for unit in units.iter_mut().filter(|u| is_user(u)) {
        for item in &mut unit.items {
            let Item::Config(c) = item else { continue };
            for pc in c.resources.iter_mut().flat_map(|r| r.programs.iter_mut()) {
                let Some(prog) = programs.get(&pc.ty.sym) else {
                    continue;
                };
                pc.conns.retain(|a| {
                    let Some(name) = a.name else { return true };
                    let Some(&(at, by_action)) = prog.reached_at.get(&name.sym) else {
                        return true;
                    };
                    if !prog.globals.contains_key(&name.sym) || !prog.params.contains(&name.sym) {
                        return true;
                    }
                    let p = interner.name(pc.ty.sym);
                    let v = interner.name(name.sym);
                    diags.push(
                        Diagnostic::error(
                            Code::E164,
                            name.span,
                            format!(
                                "`{v}` of program `{p}` cannot be connected here: another POU reaches it (`{p}.{v}`), so it is the program's one global copy, not a parameter of this instance"
                            ),
                        )
                        .with_label(
                            at,
                            if by_action {
                                format!("this action of `{p}` uses `{v}`")
                            } else {
                                format!("`{p}.{v}` named here")
                            },
                        )
                        .with_note(format!(
                            "give it its value in a POU (`{p}.{v} := ...;`), or connect a parameter no other POU names"
                        )),
                    );
                    false
                });
            }
        }
    }
}

/// Notes the `Program.var` and `Program.Action()` of one body.
struct Names<'a> {
    declared: &'a HashSet<Symbol>,
    own: Option<Symbol>,
    programs: &'a HashMap<Symbol, Program>,
    reached: &'a mut Reached,
    called: &'a mut HashMap<Symbol, (Symbol, Span)>,
}

impl<'a> Names<'a> {
    fn new(
        declared: &'a HashSet<Symbol>,
        own: Option<Symbol>,
        programs: &'a HashMap<Symbol, Program>,
        reached: &'a mut Reached,
        called: &'a mut HashMap<Symbol, (Symbol, Span)>,
    ) -> Self {
        Names {
            declared,
            own,
            programs,
            reached,
            called,
        }
    }

    /// The program `base` names, other than the body's own.
    fn program(&self, base: &Expr) -> Option<(Symbol, &'a Program)> {
        let ExprKind::Name(id) = &base.kind else {
            return None;
        };
        if self.declared.contains(&id.sym) || self.own == Some(id.sym) {
            return None;
        }
        self.programs.get(&id.sym).map(|p| (id.sym, p))
    }
}

impl Visitor for Names<'_> {
    fn expr_pre(&mut self, e: &mut Expr) -> bool {
        match &e.kind {
            ExprKind::Call { callee, args } if args.is_empty() => {
                let ExprKind::Member { base, member } = &callee.kind else {
                    return true;
                };
                if let Some((sym, prog)) = self.program(base) {
                    if let Some(&hidden) = prog.actions.get(&member.sym) {
                        self.called.entry(hidden).or_insert((sym, e.span));
                    }
                }
            }
            ExprKind::Member { base, member } => {
                if let Some((sym, prog)) = self.program(base) {
                    if prog.globals.contains_key(&member.sym) {
                        let at = self.reached.entry(sym).or_default();
                        at.entry(member.sym).or_insert((e.span, false));
                    }
                }
            }
            _ => {}
        }
        true
    }
}

/// The program variables (`candidates`) an action's body names.
struct Used<'a> {
    declared: &'a HashSet<Symbol>,
    candidates: &'a HashMap<Symbol, Symbol>,
    found: HashSet<Symbol>,
}

impl Visitor for Used<'_> {
    fn expr(&mut self, e: &mut Expr) {
        let id = match &e.kind {
            ExprKind::Name(id) => id,
            // A call of the program's FB instance: `ctr(CU := TRUE);`.
            ExprKind::Call { callee, .. } => match &callee.kind {
                ExprKind::Name(id) => id,
                _ => return,
            },
            _ => return,
        };
        if !self.declared.contains(&id.sym) && self.candidates.contains_key(&id.sym) {
            self.found.insert(id.sym);
        }
    }
}
