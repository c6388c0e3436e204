//! CODESYS (`--lib codesys`): a PROGRAM's variables and V2.3 actions used
//! from other POUs, `Main.count := 0;`, `x := PLC_PRG.state;`,
//! `Main.Reset();`. CODESYS has one instance of each program, so its
//! variables are reachable by the program's name.
//!
//! A program that another POU reaches this way keeps its variables (VAR,
//! VAR_INPUT, VAR_OUTPUT, VAR_STAT; not VAR_TEMP) as hidden globals named
//! `<Program>.<name>`: the symbol of each is then the path `Main.count`
//! tools and scenarios already use, and one copy serves every instance of
//! the program a configuration might declare (CODESYS has just one). The
//! program's body, its actions and the POUs that use them get the
//! VAR_EXTERNAL declarations of the globals they name, and `Main.count`
//! is renamed to the global. An action called as `Main.Reset();` is the
//! hidden function `__ACTION_Main_Reset` the parser wrote after the
//! program (its statements, the program's other actions inlined): the
//! call is renamed to it. The hidden functions no other POU calls are
//! dropped (the program's own calls are inlined by the parser).

use crate::codesys::Rename;
use crate::walk::{self, Visitor};
use automat_base::{Diagnostic, Interner, Span, Symbol};
use automat_syntax::ast::{
    Body, Expr, ExprKind, Ident, Item, PouKind, SourceUnit, Stmt, StmtKind, VarBlock, VarDecl,
    VarKind,
};
use std::collections::{HashMap, HashSet};

mod needed;

/// What other POUs may reach of one program.
struct Program {
    /// Variable → its hidden global: only those other POUs name and those
    /// the actions they call use.
    globals: HashMap<Symbol, Symbol>,
    /// Every variable of the program (`Main.n` in Main itself is its `n`).
    vars: HashSet<Symbol>,
    /// Its inputs, outputs and in-outs, which a configuration connects.
    params: HashSet<Symbol>,
    /// A moved variable → where another POU first reaches it, and whether
    /// through an action (for the configuration's connection, E164).
    reached_at: HashMap<Symbol, (Span, bool)>,
    /// Hidden global → (its VAR_EXTERNAL declaration, CONSTANT).
    externals: HashMap<Symbol, (VarDecl, bool)>,
    /// Action → its hidden function.
    actions: HashMap<Symbol, Symbol>,
    /// The FOR control variables, which stay in the program (a FOR variable
    /// is local, E062): an action's hidden function gets its own copy.
    for_locals: Vec<VarDecl>,
}

const PREFIX: &str = "__ACTION_";

/// Moves the variables of the programs other POUs use into hidden globals,
/// renames the uses, and drops the hidden action functions nobody calls.
pub fn rewrite(
    units: &mut [SourceUnit],
    is_user: &dyn Fn(&SourceUnit) -> bool,
    interner: &mut Interner,
    diags: &mut Vec<Diagnostic>,
) {
    let mut programs = collect(units, is_user, interner);
    if programs.is_empty() {
        return;
    }
    needed::keep_reached(units, is_user, interner, &mut programs);
    needed::check_connections(units, is_user, &programs, interner, diags);
    let mut exported: HashSet<Symbol> = HashSet::new();
    let mut called: HashSet<Symbol> = HashSet::new();
    for unit in units.iter_mut().filter(|u| is_user(u)) {
        let mut owner = None;
        for item in &mut unit.items {
            match item {
                Item::Pou(p) => {
                    // A program's own body and actions name its variables
                    // directly.
                    if p.kind == PouKind::Program {
                        owner = Some(p.name.sym);
                    } else if !interner.name(p.name.sym).starts_with(PREFIX) {
                        owner = None;
                    }
                    let mine = owner;
                    let Body::St(stmts) = &mut p.body;
                    let declared = names(&p.var_blocks, &[]);
                    let used = reach(stmts, &declared, mine, &programs, &mut called);
                    add_externals(&mut p.var_blocks, &used, &programs, &mut exported);
                }
                Item::Class(c) => {
                    owner = None;
                    let declared = names(&c.var_blocks, &[]);
                    let used = reach(&mut c.body, &declared, None, &programs, &mut called);
                    add_externals(&mut c.var_blocks, &used, &programs, &mut exported);
                    for m in &mut c.methods {
                        let declared = names(&c.var_blocks, &m.var_blocks);
                        let used = reach(&mut m.body, &declared, None, &programs, &mut called);
                        add_externals(&mut m.var_blocks, &used, &programs, &mut exported);
                    }
                    for prop in &mut c.properties {
                        for acc in [&mut prop.get, &mut prop.set].into_iter().flatten() {
                            let declared = names(&c.var_blocks, &acc.var_blocks);
                            let used =
                                reach(&mut acc.body, &declared, None, &programs, &mut called);
                            add_externals(&mut acc.var_blocks, &used, &programs, &mut exported);
                        }
                    }
                }
                _ => owner = None,
            }
        }
    }
    for unit in units.iter_mut().filter(|u| is_user(u)) {
        let mut globals = Vec::new();
        let mut owner: Option<Symbol> = None;
        let mut keep = Vec::with_capacity(unit.items.len());
        for mut item in std::mem::take(&mut unit.items) {
            if let Item::Pou(p) = &mut item {
                if p.kind == PouKind::Program {
                    owner = Some(p.name.sym);
                    if let Some(prog) = programs.get(&p.name.sym) {
                        if exported.contains(&p.name.sym) {
                            globals.extend(hide_vars(&mut p.var_blocks, prog));
                            own_externals(p, prog, false);
                        }
                    }
                } else if interner.name(p.name.sym).starts_with(PREFIX) {
                    if !called.contains(&p.name.sym) {
                        continue;
                    }
                    if let Some(prog) = owner.and_then(|o| programs.get(&o)) {
                        own_externals(p, prog, true);
                    }
                } else {
                    owner = None;
                }
            }
            keep.push(item);
        }
        keep.extend(globals.into_iter().map(Item::Globals));
        unit.items = keep;
    }
}

/// The programs of the user's units, their variables and actions.
fn collect(
    units: &[SourceUnit],
    is_user: &dyn Fn(&SourceUnit) -> bool,
    interner: &mut Interner,
) -> HashMap<Symbol, Program> {
    // The FOR control variables of each program and its actions: they
    // stay local (a FOR variable must be, E062).
    let mut for_vars: HashMap<Symbol, HashSet<Symbol>> = HashMap::new();
    each_program_item(units, is_user, interner, |prog, p| {
        let Body::St(stmts) = &p.body;
        for_names(stmts, for_vars.entry(prog).or_default());
    });
    let mut out = HashMap::new();
    for unit in units.iter().filter(|u| is_user(u)) {
        for item in &unit.items {
            let Item::Pou(p) = item else { continue };
            if p.kind != PouKind::Program {
                continue;
            }
            let prog_name = interner.name(p.name.sym).to_string();
            let local = for_vars.get(&p.name.sym);
            let mut prog = Program {
                globals: HashMap::new(),
                vars: names(&p.var_blocks, &[]),
                params: p
                    .var_blocks
                    .iter()
                    .filter(|b| matches!(b.kind, VarKind::Input | VarKind::Output | VarKind::InOut))
                    .flat_map(|b| b.decls.iter())
                    .flat_map(|d| d.names.iter().map(|n| n.sym))
                    .collect(),
                reached_at: HashMap::new(),
                externals: HashMap::new(),
                actions: HashMap::new(),
                for_locals: Vec::new(),
            };
            for b in p.var_blocks.iter().filter(|b| moves(b.kind)) {
                for d in &b.decls {
                    for n in &d.names {
                        let mut one = d.clone();
                        if local.is_some_and(|l| l.contains(&n.sym)) {
                            one.names = vec![*n];
                            one.init = None;
                            prog.for_locals.push(one);
                            continue;
                        }
                        let hidden = format!("{prog_name}.{}", interner.name(n.sym));
                        let sym = interner.intern(&hidden);
                        prog.globals.insert(n.sym, sym);
                        one.names = vec![Ident { sym, span: n.span }];
                        one.init = None;
                        one.location = None;
                        prog.externals.insert(sym, (one, b.constant));
                    }
                }
            }
            out.insert(p.name.sym, prog);
        }
    }
    let mut actions = Vec::new();
    each_program_item(units, is_user, interner, |prog, p| {
        if p.kind != PouKind::Program {
            actions.push((prog, p.name.sym));
        }
    });
    for (prog, hidden) in actions {
        let prefix = format!("{PREFIX}{}_", interner.name(prog));
        let name = interner.name(hidden).to_string();
        if let (Some(action), Some(p)) = (name.get(prefix.len()..), out.get_mut(&prog)) {
            let action = interner.intern(action);
            p.actions.insert(action, hidden);
        }
    }
    out
}

/// Calls `f` with each program of the user's units and each hidden action
/// function after it (which the parser writes right after its program).
fn each_program_item(
    units: &[SourceUnit],
    is_user: &dyn Fn(&SourceUnit) -> bool,
    interner: &Interner,
    mut f: impl FnMut(Symbol, &automat_syntax::ast::Pou),
) {
    for unit in units.iter().filter(|u| is_user(u)) {
        let mut owner: Option<Symbol> = None;
        for item in &unit.items {
            let Item::Pou(p) = item else {
                owner = None;
                continue;
            };
            if p.kind == PouKind::Program {
                owner = Some(p.name.sym);
            } else if !interner.name(p.name.sym).starts_with(PREFIX) {
                owner = None;
            }
            if let Some(o) = owner {
                f(o, p);
            }
        }
    }
}

/// The FOR control variables of `stmts`, at any depth.
fn for_names(stmts: &[Stmt], out: &mut HashSet<Symbol>) {
    for s in stmts {
        match &s.kind {
            StmtKind::For { var, body, .. } => {
                out.insert(var.sym);
                for_names(body, out);
            }
            StmtKind::If {
                branches,
                else_body,
            } => {
                for b in branches {
                    for_names(&b.body, out);
                }
                if let Some(e) = else_body {
                    for_names(e, out);
                }
            }
            StmtKind::Case {
                arms, else_body, ..
            } => {
                for a in arms {
                    for_names(&a.body, out);
                }
                if let Some(e) = else_body {
                    for_names(e, out);
                }
            }
            StmtKind::While { body, .. } | StmtKind::Repeat { body, .. } => for_names(body, out),
            _ => {}
        }
    }
}

/// The blocks whose variables a used program keeps as hidden globals.
fn moves(kind: VarKind) -> bool {
    matches!(
        kind,
        VarKind::Local | VarKind::Input | VarKind::Output | VarKind::Static
    )
}

/// The names declared by `outer` and `inner`.
fn names(outer: &[VarBlock], inner: &[VarBlock]) -> HashSet<Symbol> {
    outer
        .iter()
        .chain(inner)
        .flat_map(|b| b.decls.iter())
        .flat_map(|d| d.names.iter().map(|n| n.sym))
        .collect()
}

/// Renames `Program.var` and `Program.Action()` in `stmts` (programs
/// other than `own`, not hidden by a variable of that name); the hidden
/// globals named, with their program.
fn reach(
    stmts: &mut [Stmt],
    declared: &HashSet<Symbol>,
    own: Option<Symbol>,
    programs: &HashMap<Symbol, Program>,
    called: &mut HashSet<Symbol>,
) -> Vec<(Symbol, Symbol)> {
    let mut r = Reach {
        declared,
        own,
        programs,
        called,
        used: Vec::new(),
    };
    walk::stmts(stmts, &mut r);
    r.used
}

struct Reach<'a> {
    declared: &'a HashSet<Symbol>,
    own: Option<Symbol>,
    programs: &'a HashMap<Symbol, Program>,
    called: &'a mut HashSet<Symbol>,
    used: Vec<(Symbol, Symbol)>,
}

impl Reach<'_> {
    /// The program `base` names, if it is one this body may reach.
    fn program(&self, base: &Expr) -> Option<(Symbol, &Program)> {
        let ExprKind::Name(id) = &base.kind else {
            return None;
        };
        if self.declared.contains(&id.sym) {
            return None;
        }
        self.programs.get(&id.sym).map(|p| (id.sym, p))
    }
}

impl Visitor for Reach<'_> {
    fn expr_pre(&mut self, e: &mut Expr) -> bool {
        match &mut e.kind {
            // `Main.Reset()`: the action's hidden function.
            ExprKind::Call { callee, args } if args.is_empty() => {
                let ExprKind::Member { base, member } = &callee.kind else {
                    return true;
                };
                let Some((sym, prog)) = self.program(base) else {
                    return true;
                };
                if let Some(&hidden) = prog.actions.get(&member.sym) {
                    self.called.insert(hidden);
                    self.used.push((sym, hidden));
                    callee.kind = ExprKind::Name(Ident {
                        sym: hidden,
                        span: member.span,
                    });
                }
                true
            }
            // `Main.count`: the hidden global.
            ExprKind::Member { base, member } => {
                let Some((sym, prog)) = self.program(base) else {
                    return true;
                };
                if self.own == Some(sym) {
                    // `Main.n` in Main itself is its `n` (renamed with the
                    // rest of its body when other POUs reach it).
                    let m = *member;
                    let local = |d: &VarDecl| d.names.iter().any(|n| n.sym == m.sym);
                    if prog.vars.contains(&m.sym) || prog.for_locals.iter().any(local) {
                        e.kind = ExprKind::Name(m);
                        return false;
                    }
                    return true;
                }
                let Some(&global) = prog.globals.get(&member.sym) else {
                    return true;
                };
                self.used.push((sym, global));
                e.kind = ExprKind::Name(Ident {
                    sym: global,
                    span: e.span,
                });
                false
            }
            _ => true,
        }
    }
}

/// The VAR_EXTERNAL blocks for the hidden globals in `used` (an action's
/// hidden function needs none here: it is a function, not a variable);
/// notes the programs reached.
fn add_externals(
    blocks: &mut Vec<VarBlock>,
    used: &[(Symbol, Symbol)],
    programs: &HashMap<Symbol, Program>,
    exported: &mut HashSet<Symbol>,
) {
    let mut seen = HashSet::new();
    for constant in [false, true] {
        let mut decls = Vec::new();
        for &(prog, global) in used {
            exported.insert(prog);
            let Some((d, c)) = programs.get(&prog).and_then(|p| p.externals.get(&global)) else {
                continue;
            };
            if *c == constant && seen.insert(global) {
                decls.push(d.clone());
            }
        }
        if let Some(first) = decls.first() {
            let span = first.span;
            blocks.push(VarBlock {
                kind: VarKind::External,
                constant,
                retain: automat_syntax::ast::Retain::Unspecified,
                decls,
                span,
            });
        }
    }
}

/// Takes the variables of a used program out of its blocks: the hidden
/// global blocks (their variables renamed, initial values kept).
fn hide_vars(blocks: &mut Vec<VarBlock>, prog: &Program) -> Vec<VarBlock> {
    let (mut moved, rest): (Vec<VarBlock>, Vec<VarBlock>) = std::mem::take(blocks)
        .into_iter()
        .partition(|b| moves(b.kind));
    *blocks = rest;
    let mut kept = Vec::new();
    for b in &mut moved {
        let mut stay = b.clone();
        stay.decls.clear();
        b.kind = VarKind::Global;
        for d in std::mem::take(&mut b.decls) {
            let (global, local): (Vec<Ident>, Vec<Ident>) = d
                .names
                .iter()
                .partition(|n| prog.globals.contains_key(&n.sym));
            if !local.is_empty() {
                stay.decls.push(VarDecl {
                    names: local,
                    ..d.clone()
                });
            }
            if !global.is_empty() {
                let names = global
                    .iter()
                    .map(|n| Ident {
                        sym: prog.globals.get(&n.sym).copied().unwrap_or(n.sym),
                        span: n.span,
                    })
                    .collect();
                b.decls.push(VarDecl { names, ..d });
            }
        }
        if !stay.decls.is_empty() {
            kept.push(stay);
        }
    }
    blocks.extend(kept);
    moved.retain(|b| !b.decls.is_empty());
    moved
}

/// A used program's body or action: its variables renamed to the hidden
/// globals, with their VAR_EXTERNAL declarations (`action`: and its own
/// FOR control variables).
fn own_externals(p: &mut automat_syntax::ast::Pou, prog: &Program, action: bool) {
    let mut fors = HashSet::new();
    let Body::St(stmts) = &p.body;
    for_names(stmts, &mut fors);
    let decls: Vec<VarDecl> = prog
        .for_locals
        .iter()
        .filter(|d| action && d.names.iter().any(|n| fors.contains(&n.sym)))
        .cloned()
        .collect();
    if !decls.is_empty() {
        p.var_blocks.push(VarBlock {
            kind: VarKind::Local,
            constant: false,
            retain: automat_syntax::ast::Retain::Unspecified,
            decls,
            span: p.span,
        });
    }
    let Body::St(stmts) = &mut p.body;
    walk::stmts(
        stmts,
        &mut Rename {
            renames: &prog.globals,
        },
    );
    rename_for_vars(stmts, &prog.globals);
    for constant in [false, true] {
        let mut decls: Vec<VarDecl> = prog
            .externals
            .values()
            .filter(|(_, c)| *c == constant)
            .map(|(d, _)| d.clone())
            .collect();
        // A stable order (the map's is not): as declared, by each name's
        // place (`count, calls : INT;` is one declaration).
        decls.sort_by_key(|d| d.names.first().map_or(d.span.start, |n| n.span.start));
        if let Some(first) = decls.first() {
            let span = first.span;
            let block = VarBlock {
                kind: VarKind::External,
                constant,
                retain: automat_syntax::ast::Retain::Unspecified,
                decls,
                span,
            };
            p.var_blocks.push(block);
        }
    }
}

/// The control variables of FOR loops (an identifier, not an expression
/// the walk visits).
fn rename_for_vars(stmts: &mut [Stmt], renames: &HashMap<Symbol, Symbol>) {
    for s in stmts {
        match &mut s.kind {
            StmtKind::For { var, body, .. } => {
                if let Some(&to) = renames.get(&var.sym) {
                    var.sym = to;
                }
                rename_for_vars(body, renames);
            }
            StmtKind::If {
                branches,
                else_body,
            } => {
                for b in branches {
                    rename_for_vars(&mut b.body, renames);
                }
                if let Some(e) = else_body {
                    rename_for_vars(e, renames);
                }
            }
            StmtKind::Case {
                arms, else_body, ..
            } => {
                for a in arms {
                    rename_for_vars(&mut a.body, renames);
                }
                if let Some(e) = else_body {
                    rename_for_vars(e, renames);
                }
            }
            StmtKind::While { body, .. } | StmtKind::Repeat { body, .. } => {
                rename_for_vars(body, renames);
            }
            _ => {}
        }
    }
}

/// Drops a diagnostic of an action's hidden function when the same error
/// was reported at the same place already: the action's statements are
/// checked where the program's body inlines them too.
pub fn drop_duplicates(diags: &mut Vec<automat_base::Diagnostic>) {
    let mut seen: HashSet<(automat_base::Span, automat_base::Code)> = HashSet::new();
    let mut hidden = HashSet::new();
    for (i, d) in diags.iter().enumerate() {
        if d.message.contains(PREFIX) {
            hidden.insert(i);
        } else {
            seen.insert((d.span, d.code));
        }
    }
    if hidden.is_empty() {
        return;
    }
    let mut i = 0;
    diags.retain(|d| {
        let drop = hidden.contains(&i) && !seen.insert((d.span, d.code));
        i += 1;
        !drop
    });
}
