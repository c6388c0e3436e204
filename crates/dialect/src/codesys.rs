//! CODESYS V2.3/V3 and TwinCAT (`--lib codesys`): the rewrites of the tree.
//! The other CODESYS rules are options of the parser
//! (`automat_syntax::Options::codesys`: non-nesting `(* *)`, `END_IF`
//! without `;`, W160 for pragmas) and of the checker
//! (`automat_sema::Options::codesys`: VAR_INPUT assignment, arithmetic on
//! bit strings, W161 for implicit narrowing).
//!
//! Here: a global variable of a global variable list (`VAR_GLOBAL` outside
//! any configuration) is visible in every POU without VAR_EXTERNAL. Each
//! POU whose body names such a global, and declares no variable of that
//! name, gets the VAR_EXTERNAL declaration CODESYS implies: the global's
//! name and type, no initial value, CONSTANT when the global is.
//! The generated block carries the span of the first use, so an error in
//! it points at code the user wrote.

use crate::walk::{self, Visitor};
use automat_base::{Span, Symbol};
use automat_syntax::ast::{
    Body, Expr, ExprKind, Item, Retain, SourceUnit, VarBlock, VarDecl, VarKind,
};
use std::collections::HashMap;

/// Whether a file's `(* *)` comments nest: CODESYS V2.3 writes the
/// project's setting into each object of a text export as the marker
/// `(* @NESTEDCOMMENTS := 'Yes' *)` (or `'No'`); the file's first marker
/// decides. Without a marker they do not nest (the CODESYS default).
pub fn nested_comments(text: &str) -> bool {
    const MARK: &str = "(* @NESTEDCOMMENTS := '";
    text.find(MARK)
        .and_then(|i| text.get(i + MARK.len()..i + MARK.len() + 3))
        .is_some_and(|v| v.eq_ignore_ascii_case("yes"))
}

/// Adds the implied VAR_EXTERNAL blocks to the user POUs of `units`.
pub fn implicit_externals(units: &mut [SourceUnit], is_user: &dyn Fn(&SourceUnit) -> bool) {
    // name → (declaration to copy, constant)
    let mut globals: HashMap<Symbol, (VarDecl, bool)> = HashMap::new();
    for unit in units.iter() {
        for item in &unit.items {
            if let Item::Globals(b) = item {
                for d in &b.decls {
                    for n in &d.names {
                        globals.entry(n.sym).or_insert_with(|| {
                            let mut one = d.clone();
                            one.names = vec![*n];
                            one.init = None;
                            one.location = None;
                            (one, b.constant)
                        });
                    }
                }
            }
        }
    }
    if globals.is_empty() {
        return;
    }
    for unit in units.iter_mut().filter(|u| is_user(u)) {
        for item in &mut unit.items {
            let Item::Pou(pou) = item else { continue };
            let declared: Vec<Symbol> = pou
                .var_blocks
                .iter()
                .flat_map(|b| b.decls.iter())
                .flat_map(|d| d.names.iter().map(|n| n.sym))
                .chain(std::iter::once(pou.name.sym))
                .collect();
            let mut uses = Uses {
                globals: &globals,
                declared: &declared,
                found: Vec::new(),
            };
            let Body::St(stmts) = &mut pou.body;
            walk::stmts(stmts, &mut uses);
            let found = uses.found;
            for constant in [false, true] {
                let decls: Vec<VarDecl> = found
                    .iter()
                    .filter_map(|(sym, span)| {
                        let (d, c) = globals.get(sym)?;
                        (*c == constant).then(|| {
                            let mut d = d.clone();
                            d.span = *span;
                            if let Some(n) = d.names.first_mut() {
                                n.span = *span;
                            }
                            d
                        })
                    })
                    .collect();
                if let Some(first) = decls.first() {
                    let span = first.span;
                    pou.var_blocks.push(VarBlock {
                        kind: VarKind::External,
                        constant,
                        retain: Retain::Unspecified,
                        decls,
                        span,
                    });
                }
            }
        }
    }
}

/// Collects the globals a body names (each once, at its first use).
struct Uses<'a> {
    globals: &'a HashMap<Symbol, (VarDecl, bool)>,
    declared: &'a [Symbol],
    found: Vec<(Symbol, Span)>,
}

impl Visitor for Uses<'_> {
    // Member names (`inst.member`) are not expressions: only the base's
    // name is seen.
    fn expr(&mut self, e: &mut Expr) {
        match &e.kind {
            ExprKind::Name(id) => self.note(id.sym, id.span),
            // A call of a global FB instance: `gTimer(IN := x);`.
            ExprKind::Call { callee, .. } => {
                if let ExprKind::Name(id) = &callee.kind {
                    self.note(id.sym, id.span);
                }
            }
            _ => {}
        }
    }
}

impl Uses<'_> {
    fn note(&mut self, sym: Symbol, span: Span) {
        if self.globals.contains_key(&sym)
            && !self.declared.contains(&sym)
            && !self.found.iter().any(|(s, _)| *s == sym)
        {
            self.found.push((sym, span));
        }
    }
}

/// `VAR_STAT` (CODESYS): a variable of a POU that keeps its value from one
/// call to the next, one copy for every call and every instance. Each
/// becomes a hidden global `__STAT_<POU>_<name>` (its initial value set
/// once, at a cold start, like any global) and the body's uses of the name
/// are renamed to it; [`implicit_externals`], run after this, gives the
/// POU the VAR_EXTERNAL that makes the global visible (a METHOD gets its
/// VAR_EXTERNAL here: methods are not POUs until `desugar_oop`).
/// `VAR_INST` of a METHOD: its variables move into the function block as
/// hidden variables `__INST_<FB>_<method>_<name>`, kept with the instance.
/// A function block with methods shares its VAR_STAT globals with its
/// methods and properties (each gets the VAR_EXTERNAL). VAR_INST outside a
/// method is E160.
pub fn static_vars(
    units: &mut [SourceUnit],
    is_user: &dyn Fn(&SourceUnit) -> bool,
    interner: &mut automat_base::Interner,
    diags: &mut Vec<automat_base::Diagnostic>,
) {
    for unit in units.iter_mut().filter(|u| is_user(u)) {
        let mut globals = Vec::new();
        for item in &mut unit.items {
            match item {
                Item::Pou(pou) => {
                    misplaced_inst(
                        &pou.var_blocks,
                        "`VAR_INST` belongs in a METHOD of a function block",
                        diags,
                    );
                    let owner = interner.name(pou.name.sym).to_string();
                    let mut renames = HashMap::new();
                    let stat = take_static(&mut pou.var_blocks, &owner, interner, &mut renames);
                    if stat.is_empty() {
                        continue;
                    }
                    globals.extend(stat);
                    let Body::St(stmts) = &mut pou.body;
                    walk::stmts(stmts, &mut Rename { renames: &renames });
                }
                Item::Class(class) => {
                    let owner = interner.name(class.name.sym).to_string();
                    misplaced_inst(
                        &class.var_blocks,
                        "`VAR_INST` belongs in a METHOD: a function block's own variables are kept in its instance already",
                        diags,
                    );
                    // The function block's own VAR_STAT: hidden globals, seen
                    // by its body, its methods and its properties.
                    let mut renames = HashMap::new();
                    let stat = take_static(&mut class.var_blocks, &owner, interner, &mut renames);
                    if !stat.is_empty() {
                        let externals: Vec<VarBlock> = stat.iter().map(external_of).collect();
                        globals.extend(stat);
                        let rename = &mut Rename { renames: &renames };
                        walk::stmts(&mut class.body, rename);
                        class.var_blocks.extend(externals.iter().cloned());
                        for m in &mut class.methods {
                            walk::stmts(&mut m.body, rename);
                            m.var_blocks.extend(externals.iter().cloned());
                        }
                        for p in &mut class.properties {
                            for acc in [&mut p.get, &mut p.set].into_iter().flatten() {
                                walk::stmts(&mut acc.body, rename);
                                acc.var_blocks.extend(externals.iter().cloned());
                            }
                        }
                    }
                    let mut moved = Vec::new();
                    for m in &mut class.methods {
                        let method = interner.name(m.name.sym).to_string();
                        let (mine, rest): (Vec<VarBlock>, Vec<VarBlock>) =
                            std::mem::take(&mut m.var_blocks)
                                .into_iter()
                                .partition(|b| matches!(b.kind, VarKind::Static | VarKind::Inst));
                        m.var_blocks = rest;
                        if mine.is_empty() {
                            continue;
                        }
                        let mut renames: HashMap<Symbol, Symbol> = HashMap::new();
                        for mut block in mine {
                            let prefix = if block.kind == VarKind::Static {
                                "__STAT"
                            } else {
                                "__INST"
                            };
                            hide(
                                &mut block,
                                &format!("{prefix}_{owner}_{method}"),
                                interner,
                                &mut renames,
                            );
                            if block.kind == VarKind::Static {
                                // A hidden global, and the method's VAR_EXTERNAL of it.
                                m.var_blocks.push(external_of(&block));
                                block.kind = VarKind::Global;
                                globals.push(block);
                            } else {
                                // A variable of the function block's instance.
                                block.kind = VarKind::Local;
                                moved.push(block);
                            }
                        }
                        walk::stmts(&mut m.body, &mut Rename { renames: &renames });
                    }
                    class.var_blocks.extend(moved);
                }
                _ => {}
            }
        }
        unit.items.extend(globals.into_iter().map(Item::Globals));
    }
}

/// Gives each variable of `block` the hidden name `<prefix>_<name>`,
/// noting the rename.
fn hide(
    block: &mut VarBlock,
    prefix: &str,
    interner: &mut automat_base::Interner,
    renames: &mut HashMap<Symbol, Symbol>,
) {
    for d in &mut block.decls {
        for n in &mut d.names {
            let hidden = format!("{prefix}_{}", interner.name(n.sym));
            let sym = interner.intern(&hidden);
            renames.insert(n.sym, sym);
            n.sym = sym;
        }
    }
}

/// E160 for each VAR_INST block of `blocks` (`why` says where it belongs).
fn misplaced_inst(blocks: &[VarBlock], why: &str, diags: &mut Vec<automat_base::Diagnostic>) {
    for b in blocks.iter().filter(|b| b.kind == VarKind::Inst) {
        diags.push(automat_base::Diagnostic::error(
            automat_base::Code::E160,
            b.span,
            why,
        ));
    }
}

/// Takes the VAR_STAT blocks out of `blocks`, their variables renamed
/// `__STAT_<owner>_<name>`: the hidden globals (VAR_GLOBAL blocks) to add.
fn take_static(
    blocks: &mut Vec<VarBlock>,
    owner: &str,
    interner: &mut automat_base::Interner,
    renames: &mut HashMap<Symbol, Symbol>,
) -> Vec<VarBlock> {
    let (mut stat, rest): (Vec<VarBlock>, Vec<VarBlock>) = std::mem::take(blocks)
        .into_iter()
        .partition(|b| b.kind == VarKind::Static);
    *blocks = rest;
    for block in &mut stat {
        hide(block, &format!("__STAT_{owner}"), interner, renames);
        block.kind = VarKind::Global;
    }
    stat
}

/// The VAR_EXTERNAL that makes the globals of `block` visible in a POU.
fn external_of(block: &VarBlock) -> VarBlock {
    let mut ext = block.clone();
    ext.kind = VarKind::External;
    for d in &mut ext.decls {
        d.init = None;
        d.location = None;
    }
    ext
}

/// Renames the uses of VAR_STAT variables to their hidden globals.
pub(crate) struct Rename<'a> {
    pub(crate) renames: &'a HashMap<Symbol, Symbol>,
}

impl Visitor for Rename<'_> {
    fn expr(&mut self, e: &mut Expr) {
        let id = match &mut e.kind {
            ExprKind::Name(id) => id,
            // A call of a static FB instance: `counter(IN := x);`.
            ExprKind::Call { callee, .. } => match &mut callee.kind {
                ExprKind::Name(id) => id,
                _ => return,
            },
            _ => return,
        };
        if let Some(&to) = self.renames.get(&id.sym) {
            id.sym = to;
        }
    }
}
