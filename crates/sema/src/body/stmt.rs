//! Checking statements: assignments, calls as statements, conditions,
//! CASE selectors and labels, FOR loops, EXIT/CONTINUE placement.

use super::{Access, Checker, MAX_EXPR_DEPTH};
use crate::convert::{fits, Fit};
use crate::names::expr_text;
use crate::ops::{Ty, Typed};
use crate::types::{TypeId, TypeKind};
use crate::value::Value;
use automat_base::{Code, Span};
use automat_syntax::ast::{CaseArm, CaseLabel, Expr, ExprKind, Ident, Stmt, StmtKind};

impl<'m> Checker<'m> {
    pub(crate) fn stmts(&mut self, body: &[Stmt]) {
        let mut after_jump = false;
        for s in body {
            // A label can be jumped to: what follows it is reachable again.
            if matches!(s.kind, StmtKind::Label(_)) {
                after_jump = false;
            }
            if after_jump && !matches!(s.kind, StmtKind::Empty) {
                self.warn(Code::W002, s.span, |_| {
                    "unreachable statement: it follows RETURN, EXIT, CONTINUE or an unconditional jump".into()
                });
                after_jump = false;
            }
            self.stmt(s);
            // (EXIT and CONTINUE outside a loop are errors, not jumps.)
            let jumps = match s.kind {
                StmtKind::Return | StmtKind::Goto(_) => true,
                StmtKind::Exit | StmtKind::Continue => self.loop_depth > 0,
                _ => false,
            };
            after_jump |= jumps;
        }
    }

    fn stmt(&mut self, s: &Stmt) {
        if self.stmt_depth >= MAX_EXPR_DEPTH {
            self.too_deep(s.span, "statements");
            return;
        }
        self.stmt_depth += 1;
        self.stmt_inner(s);
        self.stmt_depth -= 1;
    }

    fn stmt_inner(&mut self, s: &Stmt) {
        match &s.kind {
            StmtKind::Assign { target, value } => {
                let t = self.expr_access(target, None, Access::Assign);
                let expect = match t.ty {
                    Ty::Of(id) => Some(id),
                    _ => None,
                };
                let v = self.expr(value, expect);
                if let Some(to) = expect {
                    self.assign_fits(&v, to, value.span, target);
                    self.integer_division_to_real(value, &v, to, target);
                }
            }
            StmtKind::Expr(e) => match &e.kind {
                ExprKind::Call { callee, args } => {
                    self.call(e, callee, args, None, true);
                }
                _ => {
                    let t = self.expr(e, None);
                    if t.ty != Ty::Error {
                        self.err(Code::E063, e.span, |c| {
                            let fix = match &e.kind {
                                ExprKind::Binary {
                                    op: automat_syntax::ast::BinaryOp::Eq,
                                    lhs,
                                    rhs,
                                } => format!(
                                    "; to assign, write `{} := {}`",
                                    expr_text(c.interner, lhs),
                                    expr_text(c.interner, rhs)
                                ),
                                _ => String::new(),
                            };
                            format!(
                                "the expression `{}` has no effect; only calls can be statements{fix}",
                                expr_text(c.interner, e)
                            )
                        });
                    }
                }
            },
            // Labels and jumps are checked once per body (`labels.rs`).
            StmtKind::Return | StmtKind::Empty | StmtKind::Label(_) | StmtKind::Goto(_) => {}
            StmtKind::If {
                branches,
                else_body,
            } => {
                for (i, b) in branches.iter().enumerate() {
                    self.condition(&b.cond, if i == 0 { "IF" } else { "ELSIF" });
                    self.stmts(&b.body);
                }
                if let Some(body) = else_body {
                    self.stmts(body);
                }
            }
            StmtKind::Case {
                selector,
                arms,
                else_body,
            } => self.case(selector, arms, else_body.as_deref()),
            StmtKind::For {
                var,
                from,
                to,
                by,
                body,
            } => self.for_loop(*var, from, to, by.as_deref(), body),
            StmtKind::While { cond, body } => {
                self.condition(cond, "WHILE");
                self.loop_body(body);
            }
            StmtKind::Repeat { body, until } => {
                self.loop_body(body);
                self.condition(until, "UNTIL");
            }
            StmtKind::Exit => {
                if self.loop_depth == 0 {
                    self.err(Code::E060, s.span, |_| {
                        "EXIT outside a FOR, WHILE or REPEAT loop".into()
                    });
                }
            }
            StmtKind::Continue => {
                if self.loop_depth == 0 {
                    self.err(Code::E061, s.span, |_| {
                        "CONTINUE outside a FOR, WHILE or REPEAT loop".into()
                    });
                }
            }
        }
    }

    fn loop_body(&mut self, body: &[Stmt]) {
        self.loop_depth += 1;
        self.stmts(body);
        self.loop_depth -= 1;
    }

    /// W004: `r := i / 2` with an integer quotient and a REAL target.
    fn integer_division_to_real(&mut self, value: &Expr, v: &Typed, to: TypeId, target: &Expr) {
        use crate::types::Elem;
        let mut e = value;
        while let ExprKind::Paren(inner) = &e.kind {
            e = inner;
        }
        let ExprKind::Binary {
            op: automat_syntax::ast::BinaryOp::Div,
            ..
        } = &e.kind
        else {
            return;
        };
        let types = &self.model.types;
        let real_target = matches!(types.elem(to), Some(Elem::Real | Elem::Lreal));
        let int_quotient = match v.ty {
            Ty::AnyInt => true,
            Ty::Of(id) => types.elem(id).is_some_and(|e| e.is_int()),
            _ => false,
        };
        if real_target && int_quotient {
            let shown = v.value.as_ref().map(|x| x.show());
            self.warn(Code::W004, value.span, |c| {
                let mut m = format!(
                    "the integer division `{}` truncates before it is converted to {} for `{}`",
                    expr_text(c.interner, e),
                    c.type_name(to),
                    expr_text(c.interner, target)
                );
                if let Some(s) = shown {
                    m.push_str(&format!(" (it gives {s})"));
                }
                m.push_str("; convert an operand to a real first");
                m
            });
        }
    }

    /// `target := v`: E030 (types or a literal out of range), E038 (subrange), W003.
    pub(crate) fn assign_fits(&mut self, v: &Typed, to: TypeId, span: Span, target: &Expr) {
        let shown = || v.value.as_ref().map_or_else(String::new, |x| x.show());
        match fits(&self.model.types, v, to) {
            Fit::Ok => {}
            Fit::NarrowedConstant => {
                let val = shown();
                self.warn(Code::W003, span, |c| {
                    format!(
                        "the constant {val} is narrowed to {} for `{}`",
                        c.type_name(to),
                        expr_text(c.interner, target)
                    )
                });
            }
            Fit::OutOfRange => {
                let val = shown();
                self.err(Code::E030, span, |c| {
                    format!(
                        "the value {val} does not fit `{}` of type {}",
                        expr_text(c.interner, target),
                        c.type_name(to)
                    )
                });
            }
            Fit::OutOfSubrange { lo, hi } => {
                let val = shown();
                self.err(Code::E038, span, |c| {
                    format!(
                        "the value {val} is outside the subrange {lo}..{hi} of `{}`",
                        expr_text(c.interner, target)
                    )
                });
            }
            Fit::Mismatch
                if self.model.codesys && crate::convert::pointer_cast(&self.model.types, v, to) => {
            }
            Fit::Mismatch if self.model.codesys && narrowing(&self.model.types, v, to) => {
                self.warn(Code::W161, span, |c| {
                    let from = crate::names::value_desc(&c.model.types, c.interner, v);
                    format!(
                        "{from} is converted implicitly to {} for `{}`: the value may not fit",
                        c.type_name(to),
                        expr_text(c.interner, target)
                    )
                });
            }
            Fit::Mismatch => {
                let narrow = narrowing(&self.model.types, v, to);
                self.err(Code::E030, span, |c| {
                    let from = crate::names::value_desc(&c.model.types, c.interner, v);
                    // The IL current result carried into a label (the hidden
                    // BOOL of the IL lowering) is not a name the user wrote.
                    if expr_text(c.interner, target).eq_ignore_ascii_case(automat_syntax::LABEL_CR_VAR) {
                        return format!(
                            "the current result ({from}) continues across a label, which only a BOOL current result can: store it with ST and load it again after the label"
                        );
                    }
                    format!(
                        "cannot assign {from} to `{}` of type {}{}",
                        expr_text(c.interner, target),
                        c.type_name(to),
                        c.conversion_hint(v.ty, to)
                    )
                });
                if narrow {
                    self.note_codesys("CODESYS converts such a value implicitly (warning W161)");
                } else if crate::convert::pointer_cast(&self.model.types, v, to) {
                    self.note_codesys(
                        "CODESYS converts pointers to each other and to and from DWORD/UDINT/LWORD/ULINT",
                    );
                }
            }
        }
    }

    /// IF / ELSIF / WHILE / UNTIL conditions are BOOL (E032).
    fn condition(&mut self, cond: &Expr, what: &'static str) {
        let t = self.expr(cond, Some(TypeId::BOOL));
        if t.ty == Ty::Error {
            return;
        }
        // Strict: an integer literal is no condition, even 0 or 1.
        if t.ty == Ty::AnyInt || fits(&self.model.types, &t, TypeId::BOOL) != Fit::Ok {
            self.err(Code::E032, cond.span, |c| {
                format!(
                    "the {what} condition must be BOOL, found {}",
                    c.tyname(t.ty)
                )
            });
        }
    }

    fn case(&mut self, selector: &Expr, arms: &[CaseArm], else_body: Option<&[Stmt]>) {
        let sel = self.expr(selector, None);
        let sel_ty = match sel.ty {
            Ty::Error => None,
            Ty::Of(id) if self.is_selector(id) => Some(id),
            t => {
                self.err(Code::E030, selector.span, |c| {
                    format!(
                        "the CASE selector must be an integer, bit string or enumeration, found {}",
                        c.tyname(t)
                    )
                });
                None
            }
        };
        for arm in arms {
            for label in &arm.labels {
                match label {
                    CaseLabel::Value(e) => {
                        self.case_label(e, sel_ty);
                    }
                    CaseLabel::Range(lo, hi) => {
                        let l = self.case_label(lo, sel_ty);
                        let h = self.case_label(hi, sel_ty);
                        if let (Some(l), Some(h)) = (l, h) {
                            if l > h {
                                self.err(Code::E033, lo.span.to(hi.span), |_| {
                                    format!("the CASE range {l}..{h} is empty: its lower bound is greater than its upper bound")
                                });
                            }
                        }
                    }
                }
            }
            self.stmts(&arm.body);
        }
        if let Some(body) = else_body {
            self.stmts(body);
        }
    }

    fn is_selector(&self, id: TypeId) -> bool {
        let types = &self.model.types;
        if let Some(e) = types.elem(id) {
            return e.is_int() || e.is_bit();
        }
        matches!(types.get(id), TypeKind::Enum { .. })
    }

    /// A CASE label: a constant of the selector's type (E033). Its integer value.
    fn case_label(&mut self, e: &Expr, sel: Option<TypeId>) -> Option<i128> {
        let t = self.expr(e, sel);
        if t.ty == Ty::Error {
            return None;
        }
        let Some(v) = t.value.as_ref() else {
            self.err(Code::E070, e.span, |c| {
                format!(
                    "the CASE label `{}` is not a constant",
                    expr_text(c.interner, e)
                )
            });
            return None;
        };
        let sel = sel?;
        match fits(&self.model.types, &t, sel) {
            Fit::Ok | Fit::NarrowedConstant => v.as_int(),
            Fit::OutOfRange | Fit::OutOfSubrange { .. } => {
                let shown = v.show();
                self.err(Code::E033, e.span, |c| {
                    format!(
                        "the CASE label {shown} does not fit the selector of type {}",
                        c.type_name(sel)
                    )
                });
                None
            }
            Fit::Mismatch => {
                let shown = v.show();
                self.err(Code::E033, e.span, |c| {
                    let label = match t.ty {
                        Ty::Of(lt) => format!("a CASE label of type {}", c.type_name(lt)),
                        _ => format!("the CASE label {shown}"),
                    };
                    format!(
                        "{label} does not match the selector of type {}",
                        c.type_name(sel)
                    )
                });
                None
            }
        }
    }

    fn for_loop(&mut self, var: Ident, from: &Expr, to: &Expr, by: Option<&Expr>, body: &[Stmt]) {
        let ty = match self.var(var.sym) {
            Some((v, own)) => {
                self.check_write(v, own, var.span, Access::ForVar);
                let is_int = self.model.types.elem(v.ty).is_some_and(|e| e.is_int());
                if v.ty == TypeId::ERROR {
                    None
                } else if !is_int {
                    self.err(Code::E062, var.span, |c| {
                        format!(
                            "the FOR variable `{}` must be an integer, found {}",
                            c.name(var.sym),
                            c.type_name(v.ty)
                        )
                    });
                    None
                } else {
                    Some(v.ty)
                }
            }
            None => {
                self.err(Code::E020, var.span, |c| {
                    format!(
                        "unknown variable `{}` {}{}",
                        c.name(var.sym),
                        c.where_(),
                        c.var_hint(var.sym)
                    )
                });
                None
            }
        };
        for (e, what) in [
            (Some(from), "start value"),
            (Some(to), "end value"),
            (by, "step"),
        ] {
            let Some(e) = e else { continue };
            let t = self.expr(e, ty);
            if let Some(ty) = ty {
                if !matches!(
                    fits(&self.model.types, &t, ty),
                    Fit::Ok | Fit::NarrowedConstant
                ) {
                    self.err(Code::E062, e.span, |c| {
                        format!(
                            "the FOR {what} ({}) does not fit the variable `{}` of type {}",
                            c.tyname(t.ty),
                            c.name(var.sym),
                            c.type_name(ty)
                        )
                    });
                    continue;
                }
            }
            if what == "step" && matches!(t.value, Some(Value::Int(0))) {
                self.err(Code::E062, e.span, |_| {
                    "the FOR step must not be zero".into()
                });
            }
        }
        self.loop_body(body);
    }
}

/// Whether `v` → `to` is a conversion CODESYS makes implicitly although the
/// standard does not: between two integer, bit-string (not BOOL) or real
/// types (the narrowing ones; widening ones are implicit everywhere), of a
/// typed value (literals keep their range checks).
pub(crate) fn narrowing(types: &crate::types::TypeTable, v: &Typed, to: TypeId) -> bool {
    let numeric =
        |e: crate::types::Elem| e.is_num() || (e.is_bit() && e != crate::types::Elem::Bool);
    let from = match v.ty {
        Ty::Of(id) => types.elem(id),
        _ => None,
    };
    matches!((from, types.elem(to)), (Some(f), Some(t)) if numeric(f) && numeric(t))
}
