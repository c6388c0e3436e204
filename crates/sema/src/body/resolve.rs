//! What names and callees denote, for lowering: the same lookup the checker
//! uses, answered without diagnostics.
//!
//! Invariant: these functions agree with the checker; a name the checker
//! accepted resolves here to the same variable, value or POU.

use super::{Checker, Scope};
use crate::model::Model;
use crate::ops::Ty;
use crate::stdlib::Sig;
use crate::types::{PouId, TypeId, TypeKind};
use crate::value::Value;
use automat_base::{Interner, Symbol};
use automat_syntax::ast::{Expr, ExprKind, PouKind};
use std::rc::Rc;

/// What a bare name in a POU body denotes.
#[derive(Clone, Debug, PartialEq)]
pub enum NameRef {
    /// `pou.vars.vars[i]` (including VAR_EXTERNAL entries and the return value).
    Local(u32),
    /// `model.globals.vars[i]` (a project-level global constant).
    Global(u32),
    /// An enumeration value.
    Enum(TypeId, i128),
}

/// What a call expression calls.
#[derive(Clone, Debug, PartialEq)]
pub enum CallTarget {
    /// A user (or library) FUNCTION.
    Function(PouId),
    /// A function block instance (the callee expression), of this function block.
    Instance(PouId),
    /// A standard function.
    Std(Rc<Sig>),
}

/// The meaning of `name` read in the body of `pou` (`expect` picks among
/// enumerations sharing a value name, as in the checker).
pub fn resolve_name(
    model: &Model,
    interner: &Interner,
    pou: PouId,
    name: Symbol,
    expect: Option<TypeId>,
) -> Option<NameRef> {
    let ck = Checker::new(model, interner, Scope::Pou(pou), true);
    if let Some(p) = model.pou(pou) {
        if let Some(i) = p.vars.index(name) {
            return Some(NameRef::Local(i));
        }
    }
    if ck.var(name).is_some() {
        return model.globals.index(name).map(NameRef::Global);
    }
    match ck.enum_value(name, expect)? {
        crate::ops::Typed {
            ty: Ty::Of(t),
            value: Some(Value::Enum(v)),
        } => Some(NameRef::Enum(t, v)),
        _ => None,
    }
}

/// What the callee of a call in the body of `pou` denotes.
pub fn resolve_callee(
    model: &Model,
    interner: &Interner,
    pou: PouId,
    callee: &Expr,
) -> Option<CallTarget> {
    let mut ck = Checker::new(model, interner, Scope::Pou(pou), true);
    if let ExprKind::Name(id) = &callee.kind {
        if ck.name_calls_a_function(id.sym) {
            if let Some((pid, p)) = model.pou_named(id.sym) {
                return (p.kind == PouKind::Function).then_some(CallTarget::Function(pid));
            }
            return ck.std_fn(id.sym).map(CallTarget::Std);
        }
    }
    match ck.expr(callee, None).ty {
        Ty::Of(t) => match model.types.get(t) {
            TypeKind::Fb { pou, .. } => Some(CallTarget::Instance(*pou)),
            _ => None,
        },
        _ => None,
    }
}
