//! A class's own code reaching the internal variables (VAR, VAR_TEMP…, not
//! the inputs and outputs) of *another* instance of the class: `p^.val` in
//! a method of `Node` for `p : REF_TO Node` (a linked list), `other.val`.
//! Those variables are PROTECTED (the standard's default for a VAR
//! section): the methods, accessors and body of the declaring class and of
//! the classes derived from it reach them, through any instance; a
//! `VAR PRIVATE` one only the declaring class's code. A `VAR PUBLIC` one
//! stays a plain member that the checker lets any code see
//! (`Model::public_vars`), as a `VAR INTERNAL` one once this stage has
//! refused its uses outside the class's namespace (E207).
//!
//! The checker only lets `__THIS.v` reach such a variable, so the access
//! becomes `__PF_<C>__<v>(__THIS := instance)^`, a function returning the
//! reference to the variable of the instance given as `VAR_IN_OUT __THIS`.

use super::*;

impl<'a> Oop<'a> {
    /// The class of `c`'s chain that declares the variable `v`.
    fn var_owner(&self, c: Symbol, v: Symbol) -> Option<Symbol> {
        self.chain(c).into_iter().find(|k| {
            self.class(*k).is_some_and(|cl| {
                cl.var_blocks
                    .iter()
                    .any(|b| b.decls.iter().any(|d| d.names.iter().any(|x| x.sym == v)))
            })
        })
    }

    /// The class declaring the internal variable `v` of class `c` (not an
    /// input, output or in-out) and its access: as its `VAR PUBLIC`,
    /// `VAR PRIVATE`... section says, PROTECTED for a plain `VAR`.
    pub(super) fn var_access(&self, c: Symbol, v: Symbol) -> Option<(Symbol, Visibility)> {
        let (_, kind) = self.class_var_kind(c, v)?;
        if matches!(kind, VarKind::Input | VarKind::Output | VarKind::InOut) {
            return None;
        }
        let owner = self.var_owner(c, v)?;
        let vis = self
            .class(owner)?
            .var_access
            .iter()
            .find(|(n, _)| *n == v)
            .map_or(Visibility::Protected, |(_, a)| *a);
        Some((owner, vis))
    }

    /// `v` is an internal variable of class `c` that the code compiled
    /// under `cx` may reach through an instance of `c`.
    pub(super) fn internal_reachable(&self, c: Symbol, v: Symbol, cx: &Ctx) -> bool {
        self.var_access(c, v)
            .is_some_and(|(owner, vis)| self.visible(owner, vis, cx))
    }

    /// `x.v` must go through `__PF_` (`internal_member`): a reachable
    /// PROTECTED or PRIVATE variable. A PUBLIC or INTERNAL one stays a
    /// member, which the checker lets any code see (`Model::public_vars`).
    pub(super) fn field_fn_needed(&self, c: Symbol, v: Symbol, cx: &Ctx) -> bool {
        self.var_access(c, v).is_some_and(|(owner, vis)| {
            matches!(vis, Visibility::Protected | Visibility::Private)
                && self.visible(owner, vis, cx)
        })
    }

    /// A use of the internal variable `v` of class `c` declared PRIVATE or
    /// INTERNAL where its access does not reach: E207 (`true`). Other
    /// variables that are out of reach are the checker's E024.
    pub(super) fn var_refused(&mut self, c: Symbol, v: Ident, cx: &Ctx) -> bool {
        let Some((owner, vis)) = self.var_access(c, v.sym) else {
            return false;
        };
        if !matches!(vis, Visibility::Private | Visibility::Internal)
            || self.visible(owner, vis, cx)
        {
            return false;
        }
        let (n, o) = (self.name(v.sym), self.name(owner));
        let w = access_word(vis);
        self.err(
            Code::E207,
            v.span,
            format!("the variable `{n}` is {w} in `{o}`"),
        );
        true
    }

    /// `e` (`base.member`, `base` an instance of class `c`) as
    /// `__PF_<c>__<member>(__THIS := base)^`; `base` already rewritten.
    pub(super) fn internal_member(&mut self, e: &mut Expr, c: Symbol, base: Expr, member: Ident) {
        let span = e.span;
        if !self.private_fields.contains(&(c, member.sym)) {
            self.private_fields.push((c, member.sym));
        }
        let f = self.private_fn_name(c, member.sym);
        e.kind = ExprKind::Deref(Box::new(self.private_call(f, base, span)));
    }

    /// `f(__THIS := instance)`.
    pub(super) fn private_call(&self, f: Symbol, instance: Expr, span: Span) -> Expr {
        Expr {
            kind: ExprKind::Call {
                callee: Box::new(Expr {
                    kind: ExprKind::Name(Ident { sym: f, span }),
                    span,
                }),
                args: vec![Arg {
                    name: Some(Ident {
                        sym: self.this,
                        span,
                    }),
                    dir: ArgDir::In,
                    value: Some(instance),
                    span,
                }],
            },
            span,
        }
    }

    pub(super) fn private_fn_name(&mut self, c: Symbol, v: Symbol) -> Symbol {
        let n = format!("__PF_{}__{}", self.name(c), self.name(v));
        self.sym(&n)
    }

    /// `FUNCTION __PF_<c>__<v> : REF_TO <type of v>` with
    /// `VAR_IN_OUT __THIS : <c>`: `REF(__THIS.v)`.
    pub(super) fn private_field_fn(&mut self, c: Symbol, v: Symbol) -> Option<Item> {
        let (mut ty, _) = self.class_var_kind(c, v)?;
        self.retype_spec(&mut ty, VarKind::Local);
        let span = self.class(c).map_or(Span::default(), |x| x.name.span);
        let fsym = self.private_fn_name(c, v);
        let this = self.this;
        let rsym = self.sym("REF");
        let id = |s: Symbol| Ident { sym: s, span };
        let place = Expr {
            kind: ExprKind::Member {
                base: Box::new(Expr {
                    kind: ExprKind::Name(id(this)),
                    span,
                }),
                member: id(v),
            },
            span,
        };
        let body = vec![Stmt {
            kind: StmtKind::Assign {
                target: Expr {
                    kind: ExprKind::Name(id(fsym)),
                    span,
                },
                value: poly::call_expr(rsym, vec![place], span),
            },
            span,
        }];
        Some(Item::Pou(Pou {
            kind: PouKind::Function,
            name: id(fsym),
            return_type: Some(TypeSpec::Ref {
                target: Box::new(ty),
                span,
                reference: false,
            }),
            var_blocks: vec![VarBlock {
                kind: VarKind::InOut,
                constant: false,
                retain: Default::default(),
                decls: vec![VarDecl {
                    names: vec![id(this)],
                    location: None,
                    ty: TypeSpec::Named(id(c)),
                    edge: None,
                    init: None,
                    span,
                }],
                span,
            }],
            body: Body::St(body),
            lang: Lang::St,
            span,
        }))
    }
}
