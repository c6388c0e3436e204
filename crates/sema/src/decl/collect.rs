//! Collecting the names a project declares: POUs and types share one
//! namespace (a function block is a type), elementary type names are
//! reserved, and standard function blocks are added unless a user POU or
//! type of the same name replaces them.

use super::{
    Builder, ConfigEntry, Owner, PouEntry, Scope, SlotState, TypeSlot, TypeState, VarSlot,
};
use crate::model::{AstRef, UnitRef};
use crate::types::PouId;
use automat_base::{Code, Diagnostic, Span};
use automat_syntax::ast::{self, Ident, Item, PouKind, SourceUnit, TypeSpec};
use rustc_hash::FxHashMap;

impl<'a> Builder<'a> {
    pub(super) fn collect(&mut self, units: &'a [SourceUnit], stdlib: &'a SourceUnit) {
        let mut bases = Vec::new();
        for (u, unit) in units.iter().enumerate() {
            for (i, item) in unit.items.iter().enumerate() {
                let aref = AstRef {
                    unit: UnitRef::User(u as u32),
                    item: i as u32,
                };
                match item {
                    Item::Pou(p) => self.add_pou(p, aref, false),
                    Item::Types(block) => {
                        for d in &block.decls {
                            self.add_type(d);
                        }
                    }
                    Item::Globals(block) => self.add_block(0, block),
                    Item::Config(c) => self.add_config(c),
                    // Replaced by plain items (`automat_syntax::desugar_oop`).
                    Item::Class(c) => {
                        if c.kind == ast::oop::ClassKind::Class {
                            self.classes.insert(c.name.sym);
                        }
                        self.collect_public_vars(c);
                        if let Some(b) = c.extends {
                            bases.push((c.name.sym, b.sym));
                        }
                    }
                    Item::Interface(_) => {}
                    // Replaced by its items (`automat_syntax::desugar_namespaces`).
                    Item::Namespace(_) => {}
                }
            }
        }
        self.inherit_public_vars(&bases);
        for (i, item) in stdlib.items.iter().enumerate() {
            if let Item::Pou(p) = item {
                let taken = self.pou_names.contains_key(&p.name.sym)
                    || self.type_slots.contains_key(&p.name.sym);
                if !taken {
                    let aref = AstRef {
                        unit: UnitRef::Std,
                        item: i as u32,
                    };
                    self.add_pou(p, aref, true);
                }
            }
        }
    }

    /// The class's own `VAR PUBLIC` / `VAR INTERNAL` variables.
    fn collect_public_vars(&mut self, c: &ast::oop::Class) {
        use ast::oop::Visibility;
        for (v, vis) in &c.var_access {
            if matches!(vis, Visibility::Public | Visibility::Internal) {
                self.public_vars.insert((c.name.sym, *v));
            }
        }
    }

    /// A derived class has its bases' public variables (`bases`: class,
    /// base). One pass per level of inheritance, bounded: a cycle was
    /// reported by the desugaring (E202).
    fn inherit_public_vars(&mut self, bases: &[(automat_base::Symbol, automat_base::Symbol)]) {
        // The desugaring refuses more than 64 levels of bases (E213).
        for _ in 0..=64 {
            let mut added = Vec::new();
            for &(c, b) in bases {
                for &(k, v) in &self.public_vars {
                    if k == b && !self.public_vars.contains(&(c, v)) {
                        added.push((c, v));
                    }
                }
            }
            if added.is_empty() {
                break;
            }
            self.public_vars.extend(added);
        }
    }

    /// Reports a POU or type name that is reserved or already taken.
    fn name_taken(&mut self, name: Ident) -> bool {
        if self.syms.is_elementary(name.sym) {
            let n = self.name(name.sym);
            self.emit(Diagnostic::error(
                Code::E023,
                name.span,
                format!("`{n}` is the name of an elementary type and cannot be declared again"),
            ));
            return true;
        }
        let first: Option<Span> = if let Some(&id) = self.pou_names.get(&name.sym) {
            self.pous.get(id.0 as usize).map(|p| p.ast.name.span)
        } else {
            self.type_slots.get(&name.sym).map(|t| t.decl.name.span)
        };
        if let Some(first) = first {
            let n = self.name(name.sym);
            self.emit(
                Diagnostic::error(Code::E023, name.span, format!("`{n}` is declared twice"))
                    .with_label(first, "first declared here"),
            );
            return true;
        }
        false
    }

    fn add_pou(&mut self, p: &'a ast::Pou, aref: AstRef, builtin: bool) {
        if !builtin && self.name_taken(p.name) {
            return;
        }
        let id = PouId(self.pous.len() as u32);
        let instance_type = match p.kind {
            PouKind::FunctionBlock => Some(self.types.fb(id, p.name.sym)),
            PouKind::Program => Some(self.types.program(id, p.name.sym)),
            PouKind::Function => None,
        };
        let scope = self.new_scope(Some(0), Owner::Pou(id));
        self.pous.push(PouEntry {
            ast: p,
            aref,
            builtin,
            scope,
            instance_type,
            return_type: None,
        });
        self.pou_names.insert(p.name.sym, id);
        let n: usize = p
            .var_blocks
            .iter()
            .flat_map(|b| &b.decls)
            .map(|d| d.names.len())
            .sum();
        if let Some(sc) = self.scopes.get_mut(scope) {
            sc.slots.reserve_exact(n);
            sc.vars.reserve_exact(n);
            sc.by_name.reserve(n);
        }
        for block in &p.var_blocks {
            self.add_block(scope, block);
        }
    }

    fn add_type(&mut self, d: &'a ast::TypeDecl) {
        if self.name_taken(d.name) {
            return;
        }
        if let TypeSpec::Enum { values, .. } = &d.spec {
            for v in values {
                let list = self.enum_decls.entry(v.name.sym).or_default();
                if !list.contains(&d.name.sym) {
                    list.push(d.name.sym);
                }
            }
        }
        self.type_slots.insert(
            d.name.sym,
            TypeSlot {
                decl: d,
                state: TypeState::Pending,
            },
        );
        self.type_order.push(d.name.sym);
    }

    fn add_config(&mut self, c: &'a ast::Configuration) {
        let idx = self.configs.len();
        let scope = self.new_scope(Some(0), Owner::Config(idx));
        for block in &c.globals {
            self.add_block(scope, block);
        }
        let mut resources = Vec::new();
        for (r, res) in c.resources.iter().enumerate() {
            let rs = self.new_scope(Some(scope), Owner::Resource(idx, r));
            for block in &res.globals {
                self.add_block(rs, block);
            }
            resources.push(rs);
        }
        self.configs.push(ConfigEntry {
            ast: c,
            scope,
            resources,
            access_types: Vec::new(),
            var_config: Vec::new(),
        });
    }

    fn new_scope(&mut self, parent: Option<usize>, owner: Owner) -> usize {
        self.scopes.push(Scope {
            parent,
            owner,
            slots: Vec::new(),
            vars: Vec::new(),
            by_name: FxHashMap::default(),
        });
        self.scopes.len() - 1
    }

    /// Adds the variables of a block to a scope; a second declaration of a
    /// name in the scope (or of a function's own name) is reported.
    fn add_block(&mut self, scope: usize, block: &'a ast::VarBlock) {
        let fn_name = match self.scopes.get(scope).map(|s| s.owner) {
            Some(Owner::Pou(id)) => self
                .pous
                .get(id.0 as usize)
                .filter(|p| p.ast.kind == PouKind::Function)
                .map(|p| p.ast.name),
            _ => None,
        };
        // Every call of a function or function block has the implicit EN; a
        // variable of that name would be a second one, which a call never
        // sets (the body would read FALSE, silently). A declared ENO output
        // is the call's ENO (`desugar/eno.rs` declares one itself when the
        // body assigns it), so only EN is refused.
        let implicit_en = match self.scopes.get(scope).map(|s| s.owner) {
            Some(Owner::Pou(id)) => self
                .pous
                .get(id.0 as usize)
                .is_some_and(|p| matches!(p.ast.kind, PouKind::Function | PouKind::FunctionBlock)),
            _ => false,
        };
        for decl in &block.decls {
            let mut first = None;
            for &name in &decl.names {
                if implicit_en && name.sym == self.syms.en {
                    let n = self.name(name.sym);
                    self.emit(Diagnostic::error(
                        Code::E023,
                        name.span,
                        format!(
                            "`{n}` is the implicit enable input of every call and is declared already: rename this variable"
                        ),
                    ));
                    // Still declared, so its uses are not reported again.
                }
                if let Some(f) = fn_name.filter(|f| f.sym == name.sym) {
                    let n = self.name(name.sym);
                    self.emit(
                        Diagnostic::error(
                            Code::E023,
                            name.span,
                            format!("`{n}` is the name of the function's return value"),
                        )
                        .with_label(f.span, "function declared here"),
                    );
                    continue;
                }
                let Some(sc) = self.scopes.get_mut(scope) else {
                    return;
                };
                let idx = sc.slots.len() as u32;
                if let Some(&prev) = sc.by_name.get(&name.sym) {
                    let prev_span = sc.slots.get(prev as usize).map(|s| s.name.span);
                    let n = self.name(name.sym);
                    let mut d = Diagnostic::error(
                        Code::E023,
                        name.span,
                        format!("`{n}` is declared twice"),
                    );
                    if let Some(p) = prev_span {
                        d = d.with_label(p, "first declared here");
                    }
                    self.emit(d);
                    continue;
                }
                let first_idx = *first.get_or_insert(idx);
                sc.by_name.insert(name.sym, idx);
                sc.slots.push(VarSlot {
                    name,
                    block,
                    decl,
                    first: first_idx,
                    state: SlotState::Pending,
                });
                sc.vars.push(None);
            }
        }
    }
}
