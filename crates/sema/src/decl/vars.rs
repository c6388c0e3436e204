//! Resolving variable declarations into [`Var`]s (type, folded initial
//! value, location, edge) and matching VAR_EXTERNAL to VAR_GLOBAL.

use super::fold::SlotInfo;
use super::typeres::SpecCtx;
use super::{Builder, Owner, SlotState, MAX_DEPTH};
use crate::model::{Section, Var};
use crate::types::{TypeId, TypeKind};
use crate::value::Init;
use automat_base::{Code, Diagnostic};
use automat_syntax::ast::VarKind;

fn info(v: &Var, poisoned: bool) -> SlotInfo {
    SlotInfo::Var {
        ty: v.ty,
        constant: v.constant,
        section: v.section,
        poisoned,
    }
}

impl<'a> Builder<'a> {
    /// Resolves variable `i` of scope `s` (memoised).
    pub(super) fn resolve_slot(&mut self, s: usize, i: u32) -> SlotInfo {
        let Some(slot) = self.scopes.get(s).and_then(|sc| sc.slots.get(i as usize)) else {
            return SlotInfo::Cycle;
        };
        match slot.state {
            SlotState::Done { poisoned } => {
                return match self.slot_var(s, i) {
                    Some(v) => info(v, poisoned),
                    None => SlotInfo::Cycle,
                }
            }
            SlotState::InProgress => return SlotInfo::Cycle,
            SlotState::Pending => {}
        }
        let (name, block, decl, first) = (slot.name, slot.block, slot.decl, slot.first);
        self.set_slot(s, i, SlotState::InProgress);
        let shared = if first != i {
            match self.resolve_slot(s, first) {
                SlotInfo::Var { ty, poisoned, .. } => {
                    let init = self.slot_init(s, first);
                    Some((ty, init, poisoned))
                }
                SlotInfo::Cycle => None,
            }
        } else {
            None
        };
        let (ty, init, poisoned) = match shared {
            Some(x) => x,
            None if self.depth >= MAX_DEPTH => {
                let n = self.name(name.sym);
                self.emit(Diagnostic::error(
                    Code::E070,
                    name.span,
                    format!("`{n}` is nested too deeply in other declarations"),
                ));
                (TypeId::ERROR, None, true)
            }
            None => {
                self.depth += 1;
                let (ty, alias_init) = self.resolve_spec(&decl.ty, s, SpecCtx::default());
                self.init_section = Some(Section::of(block.kind));
                let init = match &decl.init {
                    Some(x) => self.check_init(x, ty, s, name),
                    None => alias_init,
                };
                self.init_section = None;
                self.depth -= 1;
                (ty, init.clone(), decl.init.is_some() && init.is_none())
            }
        };
        let owner = self.scopes.get(s).map_or(Owner::Project, |sc| sc.owner);
        if let Some(loc) = &decl.location {
            if first == i {
                self.check_location(loc, ty, owner, name);
            }
        }
        if decl.edge.is_some() && first == i {
            let is_bool = ty == TypeId::BOOL || ty == TypeId::ERROR;
            if block.kind != VarKind::Input || !is_bool {
                self.emit(Diagnostic::error(
                    Code::E030,
                    decl.ty.span(),
                    "R_EDGE and F_EDGE are only allowed on BOOL inputs (VAR_INPUT)",
                ));
            }
        }
        if block.constant && first == i && self.holds_instance(ty) {
            self.emit(Diagnostic::error(
                Code::E190,
                decl.ty.span(),
                "a function block instance cannot be declared CONSTANT: calling it changes its state",
            ));
        }
        let var = Var {
            name: name.sym,
            span: name.span,
            section: Section::of(block.kind),
            ty,
            init,
            constant: block.constant,
            retain: block.retain,
            location: decl.location.as_ref().map(|l| l.addr.clone()),
            edge: decl.edge,
        };
        let out = info(&var, poisoned);
        self.set_slot(s, i, SlotState::Done { poisoned });
        if let Some(v) = self
            .scopes
            .get_mut(s)
            .and_then(|sc| sc.vars.get_mut(i as usize))
        {
            *v = Some(var);
        }
        out
    }

    /// Whether a value of `ty` is a function block instance, or an array
    /// of them (IEC 61131-3: an instance is never CONSTANT).
    fn holds_instance(&self, ty: TypeId) -> bool {
        let mut t = ty;
        // An array's element type is never an array: one step suffices,
        // the bound only keeps the walk finite on any table.
        for _ in 0..4 {
            match self.types.get(t) {
                TypeKind::Fb { .. } => return true,
                TypeKind::Array { elem, .. } => t = *elem,
                _ => return false,
            }
        }
        false
    }

    fn set_slot(&mut self, s: usize, i: u32, state: SlotState) {
        if let Some(slot) = self
            .scopes
            .get_mut(s)
            .and_then(|sc| sc.slots.get_mut(i as usize))
        {
            slot.state = state;
        }
    }

    fn slot_init(&self, s: usize, i: u32) -> Option<Init> {
        self.slot_var(s, i)?.init.clone()
    }

    /// A resolved variable.
    pub(super) fn slot_var(&self, s: usize, i: u32) -> Option<&Var> {
        self.scopes.get(s)?.vars.get(i as usize)?.as_ref()
    }

    /// Every VAR_EXTERNAL needs a VAR_GLOBAL of the same name and type
    /// (project list, configuration or resource); it takes over the
    /// global's constness and constant value.
    pub(super) fn match_externals(&mut self) {
        for s in 0..self.scopes.len() {
            if !matches!(self.scopes.get(s).map(|sc| sc.owner), Some(Owner::Pou(_))) {
                continue;
            }
            let n = self.scopes.get(s).map_or(0, |sc| sc.slots.len());
            for i in 0..n as u32 {
                let Some(ext) = self.slot_var(s, i) else {
                    continue;
                };
                if ext.section != Section::External || ext.ty == TypeId::ERROR {
                    continue;
                }
                let (name, ty, span) = (ext.name, ext.ty, ext.span);
                let globals = self.globals_by_name.get(&name).cloned().unwrap_or_default();
                let mut matched: Option<(bool, Option<Init>)> = None;
                let mut other: Option<(TypeId, automat_base::Span)> = None;
                for (gs, gi) in globals {
                    if let Some(g) = self.slot_var(gs, gi) {
                        if g.ty == ty || g.ty == TypeId::ERROR {
                            matched = Some((g.constant, g.init.clone()));
                            break;
                        }
                        other.get_or_insert((g.ty, g.span));
                    }
                }
                match (matched, other) {
                    (Some((constant, init)), _) => {
                        if let Some(Some(v)) = self
                            .scopes
                            .get_mut(s)
                            .and_then(|sc| sc.vars.get_mut(i as usize))
                        {
                            v.constant |= constant;
                            if constant {
                                v.init = init;
                            }
                        }
                    }
                    (None, Some((gty, gspan))) => {
                        let (n, et, gt) =
                            (self.name(name), self.type_name(ty), self.type_name(gty));
                        self.emit(
                            Diagnostic::error(
                                Code::E025,
                                span,
                                format!("VAR_EXTERNAL `{n}` of type {et} does not match VAR_GLOBAL `{n}` of type {gt}"),
                            )
                            .with_label(gspan, "the global is declared here"),
                        );
                    }
                    (None, None) => {
                        let n = self.name(name);
                        self.emit(Diagnostic::error(
                            Code::E025,
                            span,
                            format!("VAR_EXTERNAL `{n}` has no matching VAR_GLOBAL"),
                        ));
                    }
                }
            }
        }
    }
}
