//! Checks of Sequential Function Charts that need the semantic model: a
//! transition condition must have no side effect (E127). It is evaluated
//! every call while its transition is enabled, so a call that changes
//! state there would run an unpredictable number of times: output
//! bindings (`=>`) and calls of functions with VAR_IN_OUT or VAR_OUTPUT
//! parameters are refused (a function block instance has no value in an
//! expression at all: E054). (Assignments
//! cannot be written in an expression.) The rest of a chart is checked as
//! the ST it is rewritten into (`automat_syntax`'s desugaring).

use crate::body::resolve::{resolve_callee, CallTarget};
use crate::model::Section;
use crate::{Model, PouId};
use automat_base::{Code, Diagnostic, Interner};
use automat_syntax::ast::sfc::{Chart, Condition};
use automat_syntax::ast::{ArgDir, Expr, ExprKind};

/// E127 for every side effect in the transition conditions of `chart`,
/// its macro-step bodies included.
pub(crate) fn check_chart(
    model: &Model,
    interner: &Interner,
    pou: PouId,
    chart: &Chart,
    diags: &mut Vec<Diagnostic>,
) {
    for t in chart
        .charts()
        .into_iter()
        .flat_map(|c| c.transitions.iter())
    {
        if let Condition::St(e) = &t.cond {
            walk(model, interner, pou, e, diags);
        }
    }
}

/// Visits every call in `e` (recursion bounded by the parser's nesting cap).
fn walk(model: &Model, interner: &Interner, pou: PouId, e: &Expr, diags: &mut Vec<Diagnostic>) {
    match &e.kind {
        ExprKind::Call { callee, args } => {
            if let Some(msg) = side_effect(model, interner, pou, callee, args) {
                diags.push(Diagnostic::error(Code::E127, e.span, msg));
            }
            for a in args {
                if let Some(v) = &a.value {
                    walk(model, interner, pou, v, diags);
                }
            }
        }
        ExprKind::Member { base, .. }
        | ExprKind::Partial { base, .. }
        | ExprKind::Deref(base)
        | ExprKind::Paren(base)
        | ExprKind::Unary { operand: base, .. } => walk(model, interner, pou, base, diags),
        ExprKind::Index { base, indices } => {
            walk(model, interner, pou, base, diags);
            for i in indices {
                walk(model, interner, pou, i, diags);
            }
        }
        ExprKind::Binary { lhs, rhs, .. } => {
            walk(model, interner, pou, lhs, diags);
            walk(model, interner, pou, rhs, diags);
        }
        ExprKind::Literal(_) | ExprKind::Name(_) | ExprKind::Address(_) | ExprKind::Error => {}
    }
}

/// Why a call has a side effect, if it has one.
fn side_effect(
    model: &Model,
    interner: &Interner,
    pou: PouId,
    callee: &Expr,
    args: &[automat_syntax::ast::Arg],
) -> Option<String> {
    if args.iter().any(|a| a.dir != ArgDir::In) {
        return Some("a transition condition cannot bind outputs with `=>`".to_string());
    }
    match resolve_callee(model, interner, pou, callee)? {
        // Already refused as a value (E054): one mistake, one diagnostic.
        CallTarget::Instance(_) => None,
        CallTarget::Function(f) => {
            let p = model.pou(f)?;
            p.params()
                .any(|(_, v)| matches!(v.section, Section::InOut | Section::Output))
                .then(|| {
                    format!(
                        "a transition condition cannot call `{}`: it has VAR_IN_OUT or VAR_OUTPUT parameters",
                        interner.name(p.name)
                    )
                })
        }
        CallTarget::Std(_) => None,
    }
}
