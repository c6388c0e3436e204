//! `f() = NULL` for a value of an interface that is not a place (a
//! function's or method's result): the checker reads no member of a call's
//! result, so the test becomes `__IZ_<A>(f())`, a function made once per
//! interface that says whether its input designates nothing. A place
//! (`itf = NULL`, `arr[i] <> 0`) compares its `__id` inline (`itf_id`).

use super::*;

impl<'a> Oop<'a> {
    /// `__IZ_<A>(v)` (under NOT for `<>`); the function is made once all
    /// bodies are rewritten (`itf_null_fn`).
    pub(super) fn itf_null_call(&mut self, a: Symbol, v: &Expr, negate: bool, span: Span) -> Expr {
        if !self.itf_nulls.contains(&a) {
            self.itf_nulls.push(a);
        }
        let f = format!("__IZ_{}", self.name(a));
        let f = self.sym(&f);
        super::interfaces::negated_call(f, &[v], negate, span)
    }

    /// `FUNCTION __IZ_<A> : BOOL` over `__a : __ITF_A`: `__a.__id = 0`.
    pub(super) fn itf_null_fn(&mut self, a: Symbol) -> Item {
        let span = self.itf(a).map_or(Span::default(), |i| i.name.span);
        let id = |s: Symbol| Ident { sym: s, span };
        let asym = self.sym("__a");
        let idsym = self.sym("__id");
        let fname = format!("__IZ_{}", self.name(a));
        let fsym = self.sym(&fname);
        let sa = format!("__ITF_{}", self.name(a));
        let sa = self.sym(&sa);
        let bool_sym = self.sym("BOOL");
        let value = Expr {
            kind: ExprKind::Binary {
                op: BinaryOp::Eq,
                lhs: Box::new(Expr {
                    kind: ExprKind::Member {
                        base: Box::new(Expr {
                            kind: ExprKind::Name(id(asym)),
                            span,
                        }),
                        member: id(idsym),
                    },
                    span,
                }),
                rhs: Box::new(Expr {
                    kind: ExprKind::Literal(Box::new(Literal {
                        kind: LitKind::Int(0),
                        ty: None,
                    })),
                    span,
                }),
            },
            span,
        };
        Item::Pou(Pou {
            kind: PouKind::Function,
            name: id(fsym),
            return_type: Some(TypeSpec::Named(id(bool_sym))),
            var_blocks: vec![VarBlock {
                kind: VarKind::Input,
                constant: false,
                retain: Default::default(),
                decls: vec![VarDecl {
                    names: vec![id(asym)],
                    location: None,
                    ty: TypeSpec::Named(id(sa)),
                    edge: None,
                    init: None,
                    span,
                }],
                span,
            }],
            body: Body::St(vec![Stmt {
                kind: StmtKind::Assign {
                    target: Expr {
                        kind: ExprKind::Name(id(fsym)),
                        span,
                    },
                    value,
                },
                span,
            }]),
            lang: Lang::St,
            span,
        })
    }
}
