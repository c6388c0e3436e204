//! Typing expressions: names, members, bit access, indexing, operators.
//! Writes (`Access` other than `Read`) are checked at the variable they
//! reach: CONSTANT (E040), the POU's own VAR_INPUT (E041), an instance's
//! output or something that is no variable (E042).

use super::{Access, Checker, Named, Scope, MAX_EXPR_DEPTH};
use crate::decl::location::{size_bits, size_elem};
use crate::lattice::int_fits;
use crate::model::Section;
use crate::names::expr_text;
use crate::ops::{self, Ty, Typed};
use crate::types::{Dim, Elem, TypeId, TypeKind};
use crate::value::{self, FoldError, Value};
use automat_base::{Code, Span};
use automat_syntax::ast::{AddrSize, Expr, ExprKind, Ident, UnaryOp};

impl<'m> Checker<'m> {
    /// The type (and constant value) of an expression that is read.
    pub fn expr(&mut self, e: &Expr, expect: Option<TypeId>) -> Typed {
        self.expr_access(e, expect, Access::Read)
    }

    pub(crate) fn expr_access(
        &mut self,
        e: &Expr,
        expect: Option<TypeId>,
        access: Access,
    ) -> Typed {
        if self.depth >= MAX_EXPR_DEPTH {
            self.too_deep(e.span, "expression");
            return Typed::ERROR;
        }
        self.depth += 1;
        let r = self.expr_inner(e, expect, access);
        self.depth -= 1;
        r
    }

    fn expr_inner(&mut self, e: &Expr, expect: Option<TypeId>, access: Access) -> Typed {
        let place = matches!(
            e.kind,
            ExprKind::Name(_)
                | ExprKind::Member { .. }
                | ExprKind::Index { .. }
                | ExprKind::Partial { .. }
                | ExprKind::Deref(_)
                | ExprKind::Address(_)
                | ExprKind::Error
        );
        if access.writes() && !place {
            let t = self.expr_inner(e, expect, Access::Read);
            if t.ty != Ty::Error {
                self.not_assignable(e, access);
            }
            return t;
        }
        match &e.kind {
            ExprKind::Literal(lit) => {
                let ty = match lit.ty {
                    Some(t) => match self.type_by_name(t) {
                        Some(id) => Some(id),
                        None => {
                            self.err(Code::E021, t.span, |c| {
                                format!("unknown type `{}`", c.name(t.sym))
                            });
                            return Typed::ERROR;
                        }
                    },
                    None => None,
                };
                match crate::literal::literal(
                    &self.model.types,
                    self.interner,
                    &lit.kind,
                    ty,
                    e.span,
                ) {
                    Ok(t) => t,
                    Err(d) => {
                        if !self.silent {
                            self.diags.push(d);
                        }
                        Typed::ERROR
                    }
                }
            }
            ExprKind::Name(id) => self.name_expr(*id, expect, access),
            ExprKind::Address(a) => {
                if a.partial {
                    self.err(Code::E084, a.span, |_| {
                        "a partly specified address (`%I*`) cannot be used in code".into()
                    });
                    return Typed::ERROR;
                }
                Typed::elem(size_elem(a.size))
            }
            ExprKind::Member { base, member } => self.member_expr(base, *member, access),
            ExprKind::Partial {
                base,
                size,
                index,
                index_span,
            } => self.partial_expr(base, *size, *index, *index_span, access),
            ExprKind::Index { base, indices } => self.index_expr(base, indices, access),
            ExprKind::Deref(base) => {
                let b = self.expr(base, None);
                match b.ty {
                    Ty::Error => Typed::ERROR,
                    Ty::RefOf(t) => Typed::of(t),
                    Ty::Of(id) => match self.model.types.get(id) {
                        TypeKind::Ref(t) => Typed::of(*t),
                        _ => self.not_a_reference(e.span, b.ty),
                    },
                    _ => self.not_a_reference(e.span, b.ty),
                }
            }
            ExprKind::Unary { op, operand } => {
                let v = self.expr(operand, expect);
                let Some(ty) = ops::unary(&self.model.types, *op, &v) else {
                    let sym = match op {
                        UnaryOp::Neg => "-",
                        UnaryOp::Plus => "+",
                        UnaryOp::Not => "NOT",
                    };
                    self.err(Code::E031, e.span, |c| {
                        format!("operator `{sym}` is not defined for {}", c.tyname(v.ty))
                    });
                    return Typed::ERROR;
                };
                let elem = match (ty, expect) {
                    (Ty::Of(t), _) => self.model.types.elem(t),
                    (Ty::AnyInt, Some(x)) => self.model.types.elem(x),
                    _ => None,
                };
                let folded = v.value.as_ref().map(|x| value::unary(*op, x, elem));
                self.folded(folded, ty, e.span)
            }
            ExprKind::Binary { op, lhs, rhs } => {
                // `NULL = r`: NULL takes its reference type from the other side.
                let (l, r) = if self.is_null_name(lhs) {
                    let r = self.expr(rhs, None);
                    let hint = match r.ty {
                        Ty::Of(t) => Some(t),
                        _ => expect,
                    };
                    (self.expr(lhs, hint), r)
                } else {
                    let l = self.expr(lhs, None);
                    let hint = match l.ty {
                        Ty::Of(t) => Some(t),
                        _ => expect,
                    };
                    let r = self.expr(rhs, hint);
                    (l, r)
                };
                let Some(ty) = ops::binary_in(&self.model.types, *op, &l, &r, self.model.codesys)
                else {
                    self.err(Code::E031, e.span, |c| {
                        format!(
                            "operator `{}` is not defined for {} and {}",
                            op.symbol(),
                            c.tyname(l.ty),
                            c.tyname(r.ty)
                        )
                    });
                    if ops::binary_in(&self.model.types, *op, &l, &r, true).is_some() {
                        let pointer = |t: &Typed| match t.ty {
                            Ty::RefOf(_) => true,
                            Ty::Of(id) => {
                                matches!(self.model.types.get(id), crate::types::TypeKind::Ref(_))
                            }
                            _ => false,
                        };
                        self.note_codesys(if pointer(&l) || pointer(&r) {
                            "CODESYS allows arithmetic on pointers (in bytes) and compares them as addresses"
                        } else {
                            "CODESYS allows arithmetic on BYTE, WORD, DWORD and LWORD"
                        });
                    }
                    return Typed::ERROR;
                };
                let folded = match (&l.value, &r.value) {
                    (Some(a), Some(b)) => Some(value::binary(*op, a, b)),
                    _ => None,
                };
                self.folded(folded, ty, e.span)
            }
            ExprKind::Call { callee, args } => self.call(e, callee, args, expect, false),
            ExprKind::Paren(inner) => self.expr_access(inner, expect, access),
            ExprKind::Error => Typed::ERROR,
        }
    }

    /// `NULL` when no variable or enumeration value of that name hides it.
    fn is_null(&self, sym: automat_base::Symbol) -> bool {
        self.interner.name(sym).eq_ignore_ascii_case("NULL")
    }

    fn is_null_name(&self, e: &Expr) -> bool {
        match &e.kind {
            ExprKind::Name(id) => {
                self.is_null(id.sym)
                    && self.var(id.sym).is_none()
                    && !self.model.enum_values.contains_key(&id.sym)
            }
            ExprKind::Paren(inner) => self.is_null_name(inner),
            _ => false,
        }
    }

    /// NULL (3rd edition): the reference that designates nothing. It has
    /// the reference type its context wants (an assignment target, a
    /// parameter, the other operand of a comparison); the image holds
    /// references as offsets, and offset 0 is never a variable's.
    fn null_value(&mut self, span: Span, expect: Option<TypeId>, access: Access) -> Typed {
        if access.writes() {
            self.err(Code::E042, span, |_| "cannot assign to NULL".to_string());
            return Typed::ERROR;
        }
        match expect {
            Some(t) if matches!(self.model.types.get(t), TypeKind::Ref(_)) => {
                Typed::with(Ty::Of(t), Value::Int(0))
            }
            _ => {
                self.err(Code::E031, span, |c| {
                    let ctx = expect.map_or("no type".to_string(), |t| c.tyname(Ty::Of(t)));
                    format!("NULL is a reference, but here {ctx} is expected")
                });
                Typed::ERROR
            }
        }
    }

    fn not_a_reference(&mut self, span: Span, t: Ty) -> Typed {
        self.err(Code::E031, span, |c| {
            format!("operator `^` needs a reference, found {}", c.tyname(t))
        });
        Typed::ERROR
    }

    /// Attaches a folded value to a type; reports division by zero and
    /// overflow of constants.
    fn folded(
        &mut self,
        folded: Option<Result<Option<Value>, FoldError>>,
        ty: Ty,
        span: Span,
    ) -> Typed {
        if ty == Ty::Error {
            return Typed::ERROR;
        }
        match folded {
            None | Some(Ok(None)) => match ty {
                // An untyped result needs its value; without one it is not untyped.
                Ty::AnyInt | Ty::AnyReal | Ty::AnyStr { .. } => Typed::ERROR,
                _ => Typed { ty, value: None },
            },
            Some(Err(FoldError::DivByZero)) => {
                self.err(Code::E071, span, |_| {
                    "division by zero in a constant expression".into()
                });
                Typed::ERROR
            }
            Some(Err(FoldError::Overflow)) => {
                self.err(Code::E073, span, |_| "constant expression overflows".into());
                Typed::ERROR
            }
            Some(Ok(Some(v))) => {
                if let (Ty::Of(t), Value::Int(i)) = (ty, &v) {
                    if let Some(el) = self.model.types.elem(t) {
                        if !int_fits(*i, el) {
                            let i = *i;
                            self.err(Code::E073, span, |_| {
                                format!(
                                    "constant expression overflows {}: its value is {i}",
                                    el.name()
                                )
                            });
                            return Typed::ERROR;
                        }
                    }
                }
                Typed::with(ty, v)
            }
        }
    }

    /// Reports a write to something that is not a variable.
    pub(crate) fn not_assignable(&mut self, e: &Expr, access: Access) {
        self.err(Code::E042, e.span, |c| {
            let text = expr_text(c.interner, e);
            match access {
                Access::Output => {
                    format!("an output can only be bound to a variable, not to `{text}`")
                }
                Access::InOut => format!("a VAR_IN_OUT needs a variable, not `{text}`"),
                _ => format!("cannot assign to `{text}`: it is not a variable"),
            }
        });
    }

    fn name_expr(&mut self, id: Ident, expect: Option<TypeId>, access: Access) -> Typed {
        if id.sym == self.model.syms.self_ {
            if let Some(t) = self.self_type() {
                return Typed::of(t);
            }
        }
        if let Some((v, own)) = self.var(id.sym) {
            if access.writes() {
                self.check_write(v, own, id.span, access);
            }
            if v.ty == TypeId::ERROR {
                return Typed::ERROR;
            }
            // A VAR_INPUT CONSTANT is an input the body may not assign: its
            // value is the caller's, never folded from its default.
            let value = if v.constant && v.section != crate::model::Section::Input {
                v.init
                    .as_ref()
                    .and_then(|i| i.as_value())
                    .cloned()
                    .or_else(|| value::default_value(&self.model.types, v.ty))
            } else {
                None
            };
            return Typed {
                ty: Ty::Of(v.ty),
                value,
            };
        }
        if let Some(t) = self.enum_value(id.sym, expect) {
            if access.writes() {
                self.err(Code::E042, id.span, |c| {
                    format!(
                        "cannot assign to `{}`: it is an enumeration value",
                        c.name(id.sym)
                    )
                });
            }
            return t;
        }
        let named = self.lookup(id.sym);
        if matches!(named, Named::Unknown) && self.is_null(id.sym) {
            return self.null_value(id.span, expect, access);
        }
        if matches!(named, Named::Unknown) {
            self.err(Code::E020, id.span, |c| {
                format!(
                    "unknown variable `{}` {}{}",
                    c.name(id.sym),
                    c.where_(),
                    c.var_hint(id.sym)
                )
            });
            if matches!(self.scope, Scope::Pou(_))
                && self.model.globals.get(id.sym).is_some_and(|g| !g.constant)
            {
                self.note_codesys("CODESYS makes the global variables of a global variable list visible in every POU");
            }
        } else {
            self.err(Code::E026, id.span, |c| c.what_is(id.sym, &named));
        }
        Typed::ERROR
    }

    /// E040/E041 for a write to a variable.
    pub(crate) fn check_write(
        &mut self,
        v: &crate::model::Var,
        own: bool,
        span: Span,
        access: Access,
    ) {
        if v.constant {
            self.err(Code::E040, span, |c| {
                format!("`{}` is a constant and cannot be assigned", c.name(v.name))
            });
        } else if own && v.section == Section::Input {
            if self.model.codesys {
                // CODESYS: an input is a local copy the body may change.
                return;
            }
            self.err(Code::E041, span, |c| {
                let pou = c.pou().map_or("", |p| c.name(p.name));
                format!(
                    "`{}` is a VAR_INPUT of `{pou}` and cannot be assigned inside it",
                    c.name(v.name)
                )
            });
            self.note_codesys("CODESYS lets a POU assign its own VAR_INPUT");
        } else if access == Access::ForVar && (!own || v.section == Section::External) {
            self.err(Code::E062, span, |c| {
                format!(
                    "the FOR variable `{}` must be a local variable {}",
                    c.name(v.name),
                    c.where_()
                )
            });
        }
    }

    /// An enumeration value by its bare name (the expected type chooses
    /// among enumerations sharing the name).
    pub(crate) fn enum_value(
        &self,
        sym: automat_base::Symbol,
        expect: Option<TypeId>,
    ) -> Option<Typed> {
        let cands = self.model.enum_values.get(&sym)?;
        let pick = expect
            .filter(|t| cands.contains(t))
            .or_else(|| cands.first().copied())?;
        match self.model.types.get(pick) {
            TypeKind::Enum { values, .. } => values
                .iter()
                .find(|v| v.name == sym)
                .map(|v| Typed::with(Ty::Of(pick), Value::Enum(v.value))),
            _ => None,
        }
    }

    fn member_expr(&mut self, base: &Expr, member: Ident, access: Access) -> Typed {
        // `Color.Red`: CODESYS's qualified enumeration value.
        if let ExprKind::Name(t) = &base.kind {
            if self.var(t.sym).is_none() {
                if let Some(&tid) = self.model.type_names.get(&t.sym) {
                    if let TypeKind::Enum { values, .. } = self.model.types.get(tid) {
                        return match values.iter().find(|v| v.name == member.sym) {
                            Some(v) => Typed::with(Ty::Of(tid), Value::Enum(v.value)),
                            None => {
                                self.err(Code::E020, member.span, |c| {
                                    format!(
                                        "enumeration `{}` has no value `{}`",
                                        c.name(t.sym),
                                        c.name(member.sym)
                                    )
                                });
                                Typed::ERROR
                            }
                        };
                    }
                }
            }
        }
        let b = self.expr_access(base, None, access);
        self.member_of(&b, base, member, access)
    }

    /// `base.member` once `base` is typed.
    pub(crate) fn member_of(
        &mut self,
        b: &Typed,
        base: &Expr,
        member: Ident,
        access: Access,
    ) -> Typed {
        let id = match b.ty {
            Ty::Error => return Typed::ERROR,
            Ty::Of(id) => id,
            _ => return self.no_members(base, b.ty),
        };
        match self.model.types.get(id) {
            TypeKind::Struct { members, .. } => match members.iter().find(|m| m.name == member.sym)
            {
                Some(m) => Typed::of(m.ty),
                None => {
                    self.err(Code::E024, member.span, |c| {
                        format!(
                            "`{}` has no member `{}`",
                            c.type_name(id),
                            c.name(member.sym)
                        )
                    });
                    Typed::ERROR
                }
            },
            TypeKind::Fb { pou, name } | TypeKind::Program { pou, name } => {
                let (pou, fb_name) = (*pou, *name);
                let var = self.model.pou(pou).and_then(|p| p.vars.get(member.sym));
                // Every instance has the execution control outputs EN and ENO.
                let syms = &self.model.syms;
                if var.is_none() && (member.sym == syms.eno || member.sym == syms.en) {
                    if access.writes() {
                        self.err(Code::E042, member.span, |c| {
                            format!("`{}` of an instance cannot be written", c.name(member.sym))
                        });
                    }
                    return Typed::of(TypeId::BOOL);
                }
                // A generated method reaches every member of its class
                // through `__THIS` (access rules were checked by the
                // desugaring, at the source's names).
                let this = matches!(&base.kind, ExprKind::Name(t) if t.sym == syms.this_)
                    || matches!(&base.kind, ExprKind::Name(t) if t.sym == syms.self_);
                match var {
                    Some(v) if this => {
                        if v.ty == TypeId::ERROR {
                            Typed::ERROR
                        } else {
                            Typed::of(v.ty)
                        }
                    }
                    Some(v)
                        if v.section.is_param()
                            || self.model.public_vars.contains(&(fb_name, member.sym)) =>
                    {
                        if access.writes() && v.constant {
                            self.err(Code::E040, member.span, |c| {
                                format!(
                                    "`{}` of `{}` is a constant",
                                    c.name(member.sym),
                                    expr_text(c.interner, base)
                                )
                            });
                        }
                        if access.writes() && v.section == Section::Output {
                            self.err(Code::E042, member.span, |c| {
                                format!(
                                    "the output `{}` of `{}` cannot be written from outside",
                                    c.name(member.sym),
                                    expr_text(c.interner, base)
                                )
                            });
                        }
                        if v.ty == TypeId::ERROR {
                            Typed::ERROR
                        } else {
                            Typed::of(v.ty)
                        }
                    }
                    Some(_) => {
                        let kind = self.fb_kind_word(fb_name);
                        self.err(Code::E024, member.span, |c| {
                            format!(
                                "`{}` is not an input or output of {kind} `{}`",
                                c.name(member.sym),
                                c.name(fb_name)
                            )
                        });
                        Typed::ERROR
                    }
                    None => {
                        let kind = self.fb_kind_word(fb_name);
                        self.err(Code::E024, member.span, |c| {
                            format!(
                                "{kind} `{}` has no member `{}`",
                                c.name(fb_name),
                                c.name(member.sym)
                            )
                        });
                        Typed::ERROR
                    }
                }
            }
            _ => self.no_members(base, b.ty),
        }
    }

    /// How messages name a function block's type: `class` for one
    /// written as `CLASS` (the desugaring made it a function block).
    fn fb_kind_word(&self, name: automat_base::Symbol) -> &'static str {
        if self.model.classes.contains(&name) {
            "class"
        } else {
            "function block"
        }
    }

    fn no_members(&mut self, base: &Expr, t: Ty) -> Typed {
        self.err(Code::E036, base.span, |c| {
            format!(
                "`{}` of type {} has no members",
                expr_text(c.interner, base),
                c.tyname(t)
            )
        });
        Typed::ERROR
    }

    fn partial_expr(
        &mut self,
        base: &Expr,
        size: AddrSize,
        index: u32,
        span: Span,
        access: Access,
    ) -> Typed {
        let b = self.expr_access(base, None, access);
        let elem = match b.ty {
            Ty::Error => return Typed::ERROR,
            Ty::Of(id) => self.model.types.elem(id),
            _ => None,
        };
        let Some(el) = elem.filter(|e| (e.is_bit() && *e != Elem::Bool) || e.is_int()) else {
            self.err(Code::E037, span, |c| {
                format!(
                    "bit access needs an integer or bit string variable, but `{}` is {}",
                    expr_text(c.interner, base),
                    c.tyname(b.ty)
                )
            });
            return Typed::ERROR;
        };
        let part = size_bits(size);
        let count = el.bits() / part;
        if part >= el.bits() || index >= count {
            self.err(Code::E037, span, |c| {
                let unit = if part == 1 { "bit" } else { "part" };
                format!(
                    "{unit} {index} is out of range for `{}` of type {} ({unit}s 0..{})",
                    expr_text(c.interner, base),
                    el.name(),
                    count.saturating_sub(1)
                )
            });
            return Typed::ERROR;
        }
        Typed::elem(size_elem(size))
    }

    fn index_expr(&mut self, base: &Expr, indices: &[Expr], access: Access) -> Typed {
        let b = self.expr_access(base, None, access);
        let array = match b.ty {
            Ty::Of(id) => match self.model.types.get(id) {
                TypeKind::Array { elem, dims } => Some((*elem, dims)),
                _ => None,
            },
            _ => None,
        };
        let string = match b.ty {
            Ty::Of(id) => match self.model.types.get(id) {
                TypeKind::String { wide, len } => Some((*wide, *len)),
                _ => None,
            },
            _ => None,
        };
        if let (Some((wide, len)), true, [ix]) = (string, self.model.codesys, indices) {
            return self.string_index(base, ix, wide, len);
        }
        let Some((elem, dims)) = array else {
            for i in indices {
                self.expr(i, None);
            }
            if b.ty == Ty::Error {
                return Typed::ERROR;
            }
            let t = self.not_indexable(base, b.ty);
            if string.is_some() && indices.len() == 1 {
                self.note_codesys(
                    "CODESYS reads and writes the character codes of a string as `s[i]`",
                );
            }
            return t;
        };
        if dims.len() != indices.len() {
            for i in indices {
                self.expr(i, None);
            }
            let (d, n) = (dims.len(), indices.len());
            let span = indices
                .first()
                .map_or(base.span, |f| f.span)
                .to(indices.last().map_or(base.span, |l| l.span));
            self.err(Code::E034, span, |c| {
                format!(
                    "`{}` has {d} dimension{} but is indexed with {n} subscript{}",
                    expr_text(c.interner, base),
                    if d == 1 { "" } else { "s" },
                    if n == 1 { "" } else { "s" }
                )
            });
            return Typed::of(elem);
        }
        for (ix, dim) in indices.iter().zip(dims) {
            let Some(t) = self.integer_index(ix, "an array") else {
                continue;
            };
            if let (Some(v), Dim::Range(lo, hi)) = (t.value.as_ref().and_then(Value::as_int), dim) {
                let (lo, hi) = (*lo, *hi);
                if v < lo as i128 || v > hi as i128 {
                    self.err(Code::E035, ix.span, |c| {
                        format!(
                            "index {v} is out of range {lo}..{hi} of `{}`",
                            expr_text(c.interner, base)
                        )
                    });
                }
            }
        }
        Typed::of(elem)
    }

    /// An index expression checked to be an integer (E030 naming `what`
    /// otherwise); `None` when it is not one (or already in error).
    fn integer_index(&mut self, ix: &Expr, what: &str) -> Option<Typed> {
        let t = self.expr(ix, None);
        let is_int = match t.ty {
            Ty::Error => return None,
            Ty::AnyInt => true,
            Ty::Of(id) => self.model.types.elem(id).is_some_and(|e| e.is_int()),
            _ => false,
        };
        // CODESYS indexes with a bit string too (OSCAT's `X[set0, 1]`, a
        // BYTE of selector bits): its unsigned value, as BYTE_TO_UDINT.
        let bits = match t.ty {
            Ty::Of(id) => self
                .model
                .types
                .elem(id)
                .is_some_and(|e| e.is_bit() && e != Elem::Bool),
            _ => false,
        };
        if bits && self.model.codesys {
            return Some(t);
        }
        if !is_int {
            self.err(Code::E030, ix.span, |c| {
                format!("{what} index must be an integer, found {}", c.tyname(t.ty))
            });
            if bits {
                self.note_codesys("CODESYS indexes with BYTE, WORD, DWORD and LWORD values");
            }
            return None;
        }
        Some(t)
    }

    /// CODESYS `s[i]`: the character code at position `i` (from 0) of a
    /// STRING (BYTE) or WSTRING (WORD) of capacity `len`.
    fn string_index(&mut self, base: &Expr, ix: &Expr, wide: bool, len: u32) -> Typed {
        let t = self.integer_index(ix, "a string");
        if let Some(v) = t.and_then(|t| t.value.as_ref().and_then(Value::as_int)) {
            if v < 0 || v >= i128::from(len) {
                self.err(Code::E035, ix.span, |c| {
                    format!(
                        "index {v} is out of range 0..{} of the string `{}`",
                        i128::from(len) - 1,
                        expr_text(c.interner, base)
                    )
                });
            }
        }
        Typed::elem(if wide { Elem::Word } else { Elem::Byte })
    }

    fn not_indexable(&mut self, base: &Expr, t: Ty) -> Typed {
        self.err(Code::E036, base.span, |c| {
            format!(
                "`{}` of type {} is not an array",
                expr_text(c.interner, base),
                c.tyname(t)
            )
        });
        Typed::ERROR
    }
}
