//! `r^(IN := a, Q => b);` through a reference to a base class (or `x(...)`
//! for a `VAR_IN_OUT x : B`): the body of the instance's actual class runs.
//!
//! Every class family that such a call may reach gets a hidden method
//! `__BODY` on its root (inherited, so each class compiles its own copy,
//! whose `__THIS();` runs that class's body); the call becomes
//! `r^.IN := a; r^.__BODY(); b := r^.Q;`, i.e. the inputs written and the
//! outputs read through the reference as fields are, and the body
//! dispatched as any method is.

use super::*;

/// The hidden method's name.
pub(super) const BODY_METHOD: &str = "__BODY";

/// Adds `__BODY` to the root of every family of function blocks (a
/// FUNCTION_BLOCK that others EXTEND and that extends nothing), when some
/// statement calls an instance through a reference or a VAR_IN_OUT.
pub(super) fn add_body_methods(
    units: &[SourceUnit],
    classes: &mut HashMap<Symbol, (usize, Class)>,
    interner: &mut Interner,
) {
    if !units.iter().any(unit_calls_through) {
        return;
    }
    let extended: HashSet<Symbol> = classes
        .values()
        .filter_map(|(_, c)| c.extends.map(|e| e.sym))
        .collect();
    let name = interner.intern(BODY_METHOD);
    let this = interner.intern("__THIS");
    for (_, c) in classes.values_mut() {
        if c.kind != ClassKind::FunctionBlock
            || c.extends.is_some()
            || !extended.contains(&c.name.sym)
            || c.methods.iter().any(|m| m.name.sym == name)
        {
            continue;
        }
        // An empty span: the E213 size bound counts the methods' text.
        let span = Span {
            end: c.name.span.start,
            ..c.name.span
        };
        let callee = Expr {
            kind: ExprKind::Name(Ident { sym: this, span }),
            span,
        };
        c.methods.push(Method {
            name: Ident { sym: name, span },
            visibility: Visibility::Public,
            visibility_span: None,
            is_abstract: false,
            is_final: false,
            is_override: false,
            return_type: None,
            var_blocks: Vec::new(),
            body: vec![Stmt {
                kind: StmtKind::Expr(Expr {
                    kind: ExprKind::Call {
                        callee: Box::new(callee),
                        args: Vec::new(),
                    },
                    span,
                }),
                span,
            }],
            usings: Vec::new(),
            span,
        });
    }
}

fn unit_calls_through(unit: &SourceUnit) -> bool {
    unit.items.iter().any(|item| match item {
        Item::Pou(p) => {
            let Body::St(b) = &p.body;
            calls_through(b, &in_outs(&p.var_blocks))
        }
        Item::Class(c) => {
            calls_through(&c.body, &HashSet::new())
                || c.methods
                    .iter()
                    .any(|m| calls_through(&m.body, &in_outs(&m.var_blocks)))
        }
        _ => false,
    })
}

fn in_outs(blocks: &[VarBlock]) -> HashSet<Symbol> {
    blocks
        .iter()
        .filter(|b| b.kind == VarKind::InOut)
        .flat_map(|b| b.decls.iter().flat_map(|d| d.names.iter().map(|n| n.sym)))
        .collect()
}

/// A statement calling `x^(...)` or an in-out `x(...)` (`SUPER^()` aside:
/// its callee is a name, SUPER, dereferenced too, but harmless to count).
fn calls_through(list: &[Stmt], in_outs: &HashSet<Symbol>) -> bool {
    list.iter().any(|s| match &s.kind {
        StmtKind::Expr(Expr {
            kind: ExprKind::Call { callee, .. },
            ..
        }) => match &callee.kind {
            ExprKind::Deref(_) => true,
            ExprKind::Name(n) => in_outs.contains(&n.sym),
            _ => false,
        },
        StmtKind::If {
            branches,
            else_body,
        } => {
            branches.iter().any(|b| calls_through(&b.body, in_outs))
                || else_body
                    .as_ref()
                    .is_some_and(|b| calls_through(b, in_outs))
        }
        StmtKind::Case {
            arms, else_body, ..
        } => {
            arms.iter().any(|a| calls_through(&a.body, in_outs))
                || else_body
                    .as_ref()
                    .is_some_and(|b| calls_through(b, in_outs))
        }
        StmtKind::For { body, .. }
        | StmtKind::While { body, .. }
        | StmtKind::Repeat { body, .. } => calls_through(body, in_outs),
        _ => false,
    })
}

impl Oop<'_> {
    /// The statements replacing `s` when it calls an instance's body
    /// through a reference to a base class; `None` otherwise.
    pub(super) fn body_call(&mut self, s: &Stmt, cx: &Ctx) -> Option<Vec<Stmt>> {
        let StmtKind::Expr(Expr {
            kind: ExprKind::Call { callee, args },
            ..
        }) = &s.kind
        else {
            return None;
        };
        let (i, _) = self.poly_view(callee, cx)?;
        let base = self.poly_class.get(&i).copied()?;
        let span = s.span;
        let body = self.sym(BODY_METHOD);
        if self.method_of(base, body).is_none() {
            // A CLASS has no body to run.
            let n = self.name(base);
            self.err(
                Code::E054,
                callee.span,
                format!("`{n}` has no body to call through a reference (a CLASS)"),
            );
            return Some(Vec::new());
        }
        let field = |m: Ident| Expr {
            kind: ExprKind::Member {
                base: callee.clone(),
                member: m,
            },
            span: m.span,
        };
        let mut before = Vec::new();
        let mut after = Vec::new();
        for a in args {
            let (Some(n), Some(v)) = (a.name, &a.value) else {
                if a.name.is_none() {
                    self.err(
                        Code::E055,
                        a.span,
                        "a function block called through a reference takes formal arguments (`IN := x`)".into(),
                    );
                }
                continue;
            };
            match a.dir {
                ArgDir::In => before.push(Stmt {
                    kind: StmtKind::Assign {
                        target: field(n),
                        value: v.clone(),
                    },
                    span: a.span,
                }),
                ArgDir::Out | ArgDir::OutNot => {
                    let mut value = field(n);
                    if a.dir == ArgDir::OutNot {
                        value = Expr {
                            kind: ExprKind::Unary {
                                op: crate::ast::UnaryOp::Not,
                                operand: Box::new(value),
                            },
                            span: a.span,
                        };
                    }
                    after.push(Stmt {
                        kind: StmtKind::Assign {
                            target: v.clone(),
                            value,
                        },
                        span: a.span,
                    });
                }
            }
        }
        let call = Expr {
            kind: ExprKind::Call {
                callee: Box::new(field(Ident {
                    sym: body,
                    span: callee.span,
                })),
                args: Vec::new(),
            },
            span,
        };
        before.push(Stmt {
            kind: StmtKind::Expr(call),
            span,
        });
        before.extend(after);
        Some(before)
    }
}
