//! Interface values in expressions: `=`/`<>` of two interface values, the class number an
//! interface holds, property reads, and CODESYS's `__QUERYINTERFACE`/`__QUERYPOINTER`.

use super::body::is_place;
use super::*;

impl<'a> Oop<'a> {
    /// `l = r` of two interface values (`NOT (...)` for `<>`): the same
    /// class number and the same reference of each of `classes`, the
    /// classes implementing both interfaces (an assignment sets one
    /// reference and leaves the others NULL; a class implementing only one
    /// of them has a number the other side never holds).
    pub(super) fn itf_equal(
        &mut self,
        classes: &[Symbol],
        l: &Expr,
        r: &Expr,
        negate: bool,
        span: Span,
    ) -> Expr {
        let member = |b: &Expr, m: Symbol| Expr {
            kind: ExprKind::Member {
                base: Box::new(b.clone()),
                member: Ident { sym: m, span },
            },
            span,
        };
        let bin = |op: BinaryOp, a: Expr, b: Expr| Expr {
            kind: ExprKind::Binary {
                op,
                lhs: Box::new(a),
                rhs: Box::new(b),
            },
            span,
        };
        let mut fields = vec![self.sym("__id")];
        for c in classes {
            let f = format!("__r{}", self.ids.get(c).copied().unwrap_or(0));
            fields.push(self.sym(&f));
        }
        let mut all: Option<Expr> = None;
        for f in fields {
            let eq = bin(BinaryOp::Eq, member(l, f), member(r, f));
            all = Some(match all {
                None => eq,
                Some(acc) => bin(BinaryOp::And, acc, eq),
            });
        }
        let all = all.unwrap_or(Expr {
            kind: ExprKind::Error,
            span,
        });
        let all = Expr {
            kind: ExprKind::Paren(Box::new(all)),
            span,
        };
        if negate {
            Expr {
                kind: ExprKind::Unary {
                    op: crate::ast::UnaryOp::Not,
                    operand: Box::new(all),
                },
                span,
            }
        } else {
            all
        }
    }

    /// `__IE_<A>__<B>(l, r)` (under NOT for `<>`), the function made for
    /// the pair once all bodies are rewritten (`itf_equal_fn`).
    pub(super) fn itf_equal_call(
        &mut self,
        a: Symbol,
        b: Symbol,
        l: &Expr,
        r: &Expr,
        negate: bool,
        span: Span,
    ) -> Expr {
        if !self.itf_equals.contains(&(a, b)) {
            self.itf_equals.push((a, b));
        }
        let f = format!("__IE_{}__{}", self.name(a), self.name(b));
        let f = self.sym(&f);
        negated_call(f, &[l, r], negate, span)
    }

    /// `NULL` or the literal 0 (CODESYS writes `itf <> 0`).
    pub(super) fn is_nothing(&self, e: &Expr) -> bool {
        match &e.kind {
            ExprKind::Paren(i) => self.is_nothing(i),
            ExprKind::Literal(l) => matches!(l.kind, LitKind::Int(0)) && l.ty.is_none(),
            ExprKind::Name(_) => self.is_word(e, "NULL"),
            _ => false,
        }
    }

    /// `itf` becomes `itf.__id`, `nothing` the literal 0.
    pub(super) fn itf_id(&mut self, itf: &mut Expr, nothing: &mut Expr) {
        let t = std::mem::replace(
            itf,
            Expr {
                kind: ExprKind::Error,
                span: itf.span,
            },
        );
        self.itf_id_expr(t, nothing, itf);
    }

    pub(super) fn itf_id_expr(&mut self, t: Expr, nothing: &mut Expr, into: &mut Expr) {
        let span = t.span;
        let id = self.sym("__id");
        *into = Expr {
            kind: ExprKind::Member {
                base: Box::new(t),
                member: Ident { sym: id, span },
            },
            span,
        };
        *nothing = Expr {
            kind: ExprKind::Literal(Box::new(Literal {
                kind: LitKind::Int(0),
                ty: None,
            })),
            span: nothing.span,
        };
    }

    /// Replaces `e` by a call of the GET of property `p` of class `c` on `this`.
    pub(super) fn read_property(
        &mut self,
        e: &mut Expr,
        c: Symbol,
        this: Expr,
        p: Ident,
        cx: &Ctx,
    ) {
        let Some((_, prop)) = self.property_of(c, p.sym) else {
            return;
        };
        self.check_access(c, prop.visibility, p, cx);
        if prop.get.is_none() {
            let n = self.name(p.sym);
            self.err(Code::E210, p.span, format!("the property `{n}` has no GET"));
            return;
        }
        let f = self.prop_fn(c, p.sym, true);
        let span = e.span;
        e.kind = ExprKind::Call {
            callee: Box::new(Expr {
                kind: ExprKind::Name(Ident {
                    sym: f,
                    span: p.span,
                }),
                span: p.span,
            }),
            args: vec![Arg {
                name: Some(Ident {
                    sym: self.this,
                    span,
                }),
                dir: ArgDir::In,
                value: Some(this),
                span,
            }],
        };
    }

    /// CODESYS `__QUERYINTERFACE(source, dest)`: `__IQ_<A>__<B>(source,
    /// dest)`, made once all bodies are rewritten (`itf_query_fn`). False
    /// when `e` is another call.
    pub(super) fn query_interface(&mut self, e: &mut Expr, cx: &Ctx) -> bool {
        let span = e.span;
        let ExprKind::Call { callee, args } = &mut e.kind else {
            return false;
        };
        let pointer = self.is_word(callee, "__QUERYPOINTER");
        if !pointer && !self.is_word(callee, "__QUERYINTERFACE") {
            return false;
        }
        let op = if pointer {
            "__QUERYPOINTER"
        } else {
            "__QUERYINTERFACE"
        };
        let positional = args.len() == 2
            && args
                .iter()
                .all(|a| a.name.is_none() && a.dir == ArgDir::In && a.value.is_some());
        let (src, dst) = match args.as_mut_slice() {
            [Arg { value: Some(s), .. }, Arg { value: Some(d), .. }] if positional => (s, d),
            _ => {
                let what = if pointer { "a pointer" } else { "an interface" };
                self.diags.push(Diagnostic::error(
                    Code::E214,
                    span,
                    format!("`{op}` takes two arguments: an interface value and {what} variable"),
                ));
                e.kind = ExprKind::Error;
                return true;
            }
        };
        let (st, dt) = (self.type_of(src, cx), self.type_of(dst, cx));
        if pointer {
            return self.query_pointer(e, st, dt, cx);
        }
        let (a, b) = if let (T::Itf(a), T::Itf(b)) = (&st, &dt) {
            (*a, *b)
        } else {
            let (what, at) = match (&st, &dt) {
                (T::Itf(_), _) => ("its second argument is not an interface", dst.span),
                (T::Class(_), _) => (
                    "its first argument is an instance: assign it to an interface variable first",
                    src.span,
                ),
                _ => ("its first argument is not an interface", src.span),
            };
            self.diags.push(Diagnostic::error(
                Code::E214,
                at,
                format!("`__QUERYINTERFACE`: {what}"),
            ));
            e.kind = ExprKind::Error;
            return true;
        };
        if !is_place(dst) {
            self.diags.push(Diagnostic::error(
                Code::E214,
                dst.span,
                "`__QUERYINTERFACE`: its second argument must be a variable, member or element it can set",
            ));
            e.kind = ExprKind::Error;
            return true;
        }
        self.expr(src, cx);
        self.expr(dst, cx);
        if !self.itf_queries.contains(&(a, b)) {
            self.itf_queries.push((a, b));
        }
        let f = format!("__IQ_{}__{}", self.name(a), self.name(b));
        let f = self.sym(&f);
        let (sa, sb) = (self.sym("__a"), self.sym("__b"));
        *e = named_call(f, [(sa, src.clone()), (sb, dst.clone())], span);
        true
    }

    /// CODESYS `__QUERYPOINTER(source, dest)`: `__QP_<A>__<k>(source,
    /// dest)`, one function per call (the pointer's type is the call's).
    pub(super) fn query_pointer(&mut self, e: &mut Expr, st: T, dt: T, cx: &Ctx) -> bool {
        let span = e.span;
        let ExprKind::Call { args, .. } = &mut e.kind else {
            return true;
        };
        let [Arg {
            value: Some(src), ..
        }, Arg {
            value: Some(dst), ..
        }] = args.as_mut_slice()
        else {
            return true;
        };
        let problem = match (&st, &dt) {
            (T::Itf(_), T::Ref(_)) if is_place(dst) => None,
            (T::Itf(_), T::Ref(_)) => Some((
                "its second argument must be a variable, member or element it can set",
                dst.span,
            )),
            (T::Itf(_), _) => Some(("its second argument is not a pointer", dst.span)),
            (T::Class(_), _) => Some((
                "its first argument is an instance: take `ADR(instance)` instead",
                src.span,
            )),
            _ => Some(("its first argument is not an interface", src.span)),
        };
        if let Some((what, at)) = problem {
            self.diags.push(Diagnostic::error(
                Code::E214,
                at,
                format!("`__QUERYPOINTER`: {what}"),
            ));
            e.kind = ExprKind::Error;
            return true;
        }
        let (T::Itf(a), T::Ref(target)) = (st, dt) else {
            return true;
        };
        self.expr(src, cx);
        self.expr(dst, cx);
        let f = format!("__QP_{}__{}", self.name(a), self.itf_pointers.len() + 1);
        let f = self.sym(&f);
        self.itf_pointers.push((a, target, f));
        let (sa, sp) = (self.sym("__a"), self.sym("__p"));
        *e = named_call(f, [(sa, src.clone()), (sp, dst.clone())], span);
        true
    }
}

/// `f(a := x, b := y)`: the call `__QUERYINTERFACE` and `__QUERYPOINTER` become.
fn named_call(f: Symbol, args: [(Symbol, Expr); 2], span: Span) -> Expr {
    let args = args
        .into_iter()
        .map(|(n, v)| Arg {
            name: Some(Ident { sym: n, span }),
            dir: ArgDir::In,
            value: Some(v),
            span,
        })
        .collect();
    Expr {
        kind: ExprKind::Call {
            callee: Box::new(Expr {
                kind: ExprKind::Name(Ident { sym: f, span }),
                span,
            }),
            args,
        },
        span,
    }
}

/// `f(a, b, …)` with positional inputs, under NOT when `negate` (a hidden
/// comparison function called for `=` or `<>`).
pub(super) fn negated_call(f: Symbol, args: &[&Expr], negate: bool, span: Span) -> Expr {
    let call = Expr {
        kind: ExprKind::Call {
            callee: Box::new(Expr {
                kind: ExprKind::Name(Ident { sym: f, span }),
                span,
            }),
            args: args
                .iter()
                .map(|v| Arg {
                    name: None,
                    dir: ArgDir::In,
                    value: Some((*v).clone()),
                    span,
                })
                .collect(),
        },
        span,
    };
    if negate {
        Expr {
            kind: ExprKind::Unary {
                op: crate::ast::UnaryOp::Not,
                operand: Box::new(call),
            },
            span,
        }
    } else {
        call
    }
}
