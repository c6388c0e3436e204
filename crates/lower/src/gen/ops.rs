//! Operators and implicit conversions: integer arithmetic wraps at the
//! type's width (an explicit `Wrap` after each operation), REAL rounds to
//! f32, times use the time builtins, strings compare through a builtin.

use super::{Failed, Gen, Res, Shape, Val, V};
use crate::layout::mem_ty;
use crate::symbols::elementary;
use automat_base::Span;
use automat_ir::code::{Builtin, Cmp, FloatOp, Inst, IntOp, MemTy, Reg, RegClass, StrFn, TimeFn};
use automat_sema::ops::Ty;
use automat_sema::types::{Elem, TypeId, TypeKind};
use automat_sema::Typed;
use automat_syntax::ast::{BinaryOp, Expr, UnaryOp};

/// The values a canonical register of an integer memory type holds.
fn mem_range(t: MemTy) -> Option<(i128, i128)> {
    Some(match t {
        MemTy::I8 => (i8::MIN as i128, i8::MAX as i128),
        MemTy::U8 => (0, u8::MAX as i128),
        MemTy::I16 => (i16::MIN as i128, i16::MAX as i128),
        MemTy::U16 => (0, u16::MAX as i128),
        MemTy::I32 => (i32::MIN as i128, i32::MAX as i128),
        MemTy::U32 => (0, u32::MAX as i128),
        MemTy::I64 => (i64::MIN as i128, i64::MAX as i128),
        MemTy::F32 | MemTy::F64 => return None,
    })
}

/// Integer-like: lives in I64 and wraps by its memory type.
fn intlike(e: Elem) -> bool {
    e.is_int() || e.is_bit() || e.is_char()
}

impl Gen<'_, '_> {
    /// Converts a value to type `to` (implicit conversions and the
    /// elementary conversion functions).
    pub fn coerce(&mut self, v: Val, to: TypeId, span: Span) -> Res<Val> {
        if v.ty == to {
            return Ok(v);
        }
        match (self.shape(v.ty), self.shape(to), v.v) {
            (Shape::Int(a), Shape::Int(b), V::I(r) | V::F(r) | V::D(r)) => {
                if a == b {
                    return Ok(Val { v: v.v, ty: to });
                }
                let (ma, mb) = (mem_ty(a), mem_ty(b));
                if intlike(a) && intlike(b) {
                    // A canonical value of a narrower range is already
                    // canonical at the wider one: the wrap would do nothing.
                    if mem_range(ma).is_some_and(|(lo, hi)| {
                        mem_range(mb).is_some_and(|(l2, h2)| l2 <= lo && hi <= h2)
                    }) {
                        return Ok(Val { v: v.v, ty: to });
                    }
                    let d = self.reg(RegClass::I64);
                    self.emit(Inst::Wrap {
                        dst: d,
                        src: r,
                        ty: mb,
                    });
                    return Ok(Val { v: V::I(d), ty: to });
                }
                if ma.class() == RegClass::I64
                    && mb.class() == RegClass::I64
                    && !(intlike(a) || intlike(b))
                    && same_family(a, b)
                {
                    return Ok(Val { v: v.v, ty: to });
                }
                if let (RegClass::F32, RegClass::F64) | (RegClass::F64, RegClass::F32) =
                    (ma.class(), mb.class())
                {
                    let d = self.reg(mb.class());
                    self.emit(Inst::FResize {
                        to_wide: mb.class() == RegClass::F64,
                        dst: d,
                        src: r,
                    });
                    return Ok(Val {
                        v: wrap_v(d, mb),
                        ty: to,
                    });
                }
                let d = self.reg(mb.class());
                self.builtin(
                    Builtin::Convert(elementary(a), elementary(b)),
                    Some(d),
                    &[r],
                    span,
                );
                Ok(Val {
                    v: wrap_v(d, mb),
                    ty: to,
                })
            }
            (Shape::Str { wide: a, .. }, Shape::Str { wide: b, .. }, V::M(_)) if a == b => {
                Ok(Val { v: v.v, ty: to })
            }
            (Shape::Agg, Shape::Agg, V::M(_)) => Ok(Val { v: v.v, ty: to }),
            (Shape::Str { wide, .. }, Shape::Int(e), V::M(a)) if e.is_char() => {
                // A one-character string literal assigned to a CHAR.
                let s = self.addr_reg(a);
                let d = self.reg(RegClass::I64);
                self.builtin(
                    Builtin::FromString(elementary(e), wide),
                    Some(d),
                    &[s],
                    span,
                );
                Ok(Val { v: V::I(d), ty: to })
            }
            _ => Err(self.error(
                span,
                "conversion between these types is not supported".into(),
            )),
        }
    }

    pub fn unary(
        &mut self,
        op: UnaryOp,
        x: &Expr,
        typed: &Typed,
        want: Option<TypeId>,
        e: &Expr,
    ) -> Res<Val> {
        let ty = self.concrete(typed.ty, want, None).ok_or(Failed)?;
        let v = self.expr(x, Some(ty))?;
        let el = self.elem(ty).ok_or(Failed)?;
        let out = match (op, v.v) {
            (UnaryOp::Plus, _) => return Ok(v),
            (UnaryOp::Neg, V::I(r)) => {
                let d = self.reg(RegClass::I64);
                self.emit(Inst::Neg { dst: d, src: r });
                self.wrap(d, el)
            }
            (UnaryOp::Neg, V::F(r) | V::D(r)) => {
                let wide = matches!(v.v, V::D(_));
                let m = self.fconst(-1.0, wide);
                let d = self.reg(if wide { RegClass::F64 } else { RegClass::F32 });
                self.emit(Inst::Float {
                    op: FloatOp::Mul,
                    wide,
                    dst: d,
                    a: r,
                    b: m,
                });
                if wide {
                    V::D(d)
                } else {
                    V::F(d)
                }
            }
            (UnaryOp::Not, V::I(r)) if el == Elem::Bool => {
                let one = self.iconst(1);
                let d = self.reg(RegClass::I64);
                self.emit(Inst::Int {
                    op: IntOp::Xor,
                    dst: d,
                    a: r,
                    b: one,
                });
                V::I(d)
            }
            (UnaryOp::Not, V::I(r)) => {
                let d = self.reg(RegClass::I64);
                self.emit(Inst::Not { dst: d, src: r });
                self.wrap(d, el)
            }
            _ => return Err(self.error(e.span, "operator not supported on this type".into())),
        };
        Ok(Val { v: out, ty })
    }

    pub fn fconst(&mut self, x: f64, wide: bool) -> Reg {
        if wide {
            let r = self.reg(RegClass::F64);
            self.emit(Inst::F64Const { dst: r, value: x });
            r
        } else {
            let r = self.reg(RegClass::F32);
            self.emit(Inst::F32Const {
                dst: r,
                value: x as f32,
            });
            r
        }
    }

    /// Wraps an I64 register to the width of `e` (nothing to do at 64 bits).
    pub fn wrap(&mut self, r: Reg, e: Elem) -> V {
        let mt = mem_ty(e);
        if mt == MemTy::I64 || !intlike(e) {
            return V::I(r);
        }
        let d = self.reg(RegClass::I64);
        self.emit(Inst::Wrap {
            dst: d,
            src: r,
            ty: mt,
        });
        V::I(d)
    }

    /// The type two operands of a comparison meet in.
    fn common(&self, a: &Typed, b: &Typed) -> Option<TypeId> {
        let is_ref = |t: &Typed| match t.ty {
            Ty::RefOf(_) => true,
            Ty::Of(x) => matches!(self.kind(x), TypeKind::Ref(_)),
            _ => false,
        };
        // References and pointers compare as the image offsets they hold
        // (REF(x) = r; CODESYS also p <> 0, pointers of other types).
        if is_ref(a) || is_ref(b) {
            return match (a.ty, b.ty) {
                (Ty::Of(x), Ty::Of(y)) if x == y => Some(x),
                (Ty::Of(x), Ty::Error) | (Ty::Error, Ty::Of(x)) => Some(x),
                _ => Some(TypeId::elem(Elem::Udint)),
            };
        }
        match (a.ty, b.ty) {
            (Ty::Of(x), Ty::Of(y)) if x == y => Some(x),
            (Ty::Of(x), Ty::Of(y)) => match (self.elem(x), self.elem(y)) {
                (Some(p), Some(q)) => automat_sema::lattice::lub(p, q).map(TypeId::elem),
                _ => Some(x),
            },
            // In a checked program only NULL has no type of its own: it
            // takes the other operand's reference type.
            (Ty::Of(x), Ty::Error) => Some(x),
            (Ty::Error, Ty::Of(y)) => Some(y),
            (Ty::Of(x), _) => self.concrete(b.ty, Some(x), b.value.as_ref()),
            (_, Ty::Of(y)) => self.concrete(a.ty, Some(y), a.value.as_ref()),
            (Ty::AnyReal, _) | (_, Ty::AnyReal) => Some(TypeId::elem(Elem::Lreal)),
            (Ty::AnyStr { wide }, _) => Some(if wide {
                TypeId::WSTRING
            } else {
                TypeId::STRING
            }),
            _ => Some(TypeId::elem(Elem::Lint)),
        }
    }

    pub fn binary(
        &mut self,
        op: BinaryOp,
        l: &Expr,
        r: &Expr,
        typed: &Typed,
        want: Option<TypeId>,
        e: &Expr,
    ) -> Res<Val> {
        use BinaryOp::*;
        if matches!(op, Lt | Gt | Le | Ge | Eq | Ne) {
            let (tl, tr) = (self.typed(l), self.typed(r));
            let ct = self.common(&tl, &tr).ok_or(Failed)?;
            let a = self.expr(l, Some(ct))?;
            let b = self.expr(r, Some(ct))?;
            let cmp = match op {
                Lt => Cmp::Lt,
                Gt => Cmp::Gt,
                Le => Cmp::Le,
                Ge => Cmp::Ge,
                Eq => Cmp::Eq,
                _ => Cmp::Ne,
            };
            let d = self.compare(cmp, a, b, e.span)?;
            return Ok(Val {
                v: V::I(d),
                ty: TypeId::BOOL,
            });
        }
        if let Ty::RefOf(t) = typed.ty {
            // `ADR(x) + n`: typed as the wanted pointer, else as one to x's type.
            let ty = want
                .filter(|&w| matches!(self.kind(w), TypeKind::Ref(_)))
                .or_else(|| self.cx.model.types.find_ref(t))
                .unwrap_or(TypeId::elem(Elem::Udint));
            return self.pointer_offset(op, l, r, ty, e);
        }
        let ty = self.concrete(typed.ty, want, None).ok_or(Failed)?;
        if matches!(self.kind(ty), TypeKind::Ref(_)) {
            return self.pointer_offset(op, l, r, ty, e);
        }
        let el = self
            .elem(ty)
            .ok_or_else(|| self.error(e.span, "operator not supported on this type".into()))?;
        if el.is_duration() || el.is_date() {
            return self.time_op(op, l, r, ty, e);
        }
        if op == Pow {
            return self.pow(l, r, ty, e);
        }
        let a = self.expr(l, Some(ty))?;
        let b = self.expr(r, Some(ty))?;
        let v = self.arith(op, a, b, el, e.span)?;
        Ok(Val { v, ty })
    }

    /// CODESYS pointer arithmetic, `p + n`, `n + p`, `p - n`: the image
    /// offset moved by `n` bytes, wrapping at 32 bits (a pointer that
    /// leaves the image faults when it is dereferenced).
    fn pointer_offset(
        &mut self,
        op: BinaryOp,
        l: &Expr,
        r: &Expr,
        ty: TypeId,
        e: &Expr,
    ) -> Res<Val> {
        let l_is_ptr =
            matches!(self.typed(l).ty, Ty::Of(t) if matches!(self.kind(t), TypeKind::Ref(_)));
        let (p, n) = if l_is_ptr { (l, r) } else { (r, l) };
        let pv = self.expr(p, None)?;
        let nv = self.expr(n, None)?;
        let as_udint = |v: Val| Val {
            v: v.v,
            ty: TypeId::elem(Elem::Udint),
        };
        let v = self.arith(op, as_udint(pv), as_udint(nv), Elem::Udint, e.span)?;
        Ok(Val { v, ty })
    }

    /// `a op b` at elementary type `el` (both operands already of it).
    pub fn arith(&mut self, op: BinaryOp, a: Val, b: Val, el: Elem, span: Span) -> Res<V> {
        use BinaryOp::*;
        Ok(match (a.v, b.v) {
            (V::I(x), V::I(y)) => {
                let d = self.reg(RegClass::I64);
                let signed = el.is_signed();
                match op {
                    Add | Sub | Mul | And | Or | Xor => {
                        let iop = match op {
                            Add => IntOp::Add,
                            Sub => IntOp::Sub,
                            Mul => IntOp::Mul,
                            And => IntOp::And,
                            Or => IntOp::Or,
                            _ => IntOp::Xor,
                        };
                        self.emit(Inst::Int {
                            op: iop,
                            dst: d,
                            a: x,
                            b: y,
                        });
                    }
                    Div => {
                        let site = self.site(span);
                        self.emit(Inst::Div {
                            signed,
                            dst: d,
                            a: x,
                            b: y,
                            site,
                        });
                    }
                    Mod => {
                        let site = self.site(span);
                        self.emit(Inst::Rem {
                            signed,
                            dst: d,
                            a: x,
                            b: y,
                            site,
                        });
                    }
                    _ => {
                        return Err(self.error(
                            span,
                            format!("operator {} not supported on integers", op.symbol()),
                        ))
                    }
                }
                // Bitwise results of canonical operands are canonical
                // (zero- or sign-extension survives AND/OR/XOR), and a
                // remainder is smaller than its divisor: no wrap needed.
                // Only a signed division can overflow (MIN / -1).
                match op {
                    And | Or | Xor | Mod => V::I(d),
                    Div if !signed => V::I(d),
                    _ => self.wrap(d, el),
                }
            }
            (V::F(x), V::F(y)) | (V::D(x), V::D(y)) => {
                let wide = matches!(a.v, V::D(_));
                let fop = match op {
                    Add => FloatOp::Add,
                    Sub => FloatOp::Sub,
                    Mul => FloatOp::Mul,
                    Div => FloatOp::Div,
                    _ => {
                        return Err(self.error(
                            span,
                            format!("operator {} not supported on reals", op.symbol()),
                        ))
                    }
                };
                let d = self.reg(if wide { RegClass::F64 } else { RegClass::F32 });
                self.emit(Inst::Float {
                    op: fop,
                    wide,
                    dst: d,
                    a: x,
                    b: y,
                });
                if wide {
                    V::D(d)
                } else {
                    V::F(d)
                }
            }
            _ => {
                return Err(self.error(
                    span,
                    format!("operator {} not supported on this type", op.symbol()),
                ))
            }
        })
    }

    /// Compares two values of one type into a BOOL register.
    pub fn compare(&mut self, cmp: Cmp, a: Val, b: Val, span: Span) -> Res<Reg> {
        let d = self.reg(RegClass::I64);
        match (a.v, b.v) {
            (V::I(x), V::I(y)) => {
                let signed = self
                    .elem(a.ty)
                    .is_none_or(|e| !matches!(e, Elem::Ulint | Elem::Lword));
                self.emit(Inst::ICmp {
                    cmp,
                    signed,
                    dst: d,
                    a: x,
                    b: y,
                });
            }
            (V::F(x), V::F(y)) | (V::D(x), V::D(y)) => {
                let wide = matches!(a.v, V::D(_));
                self.emit(Inst::FCmp {
                    cmp,
                    wide,
                    dst: d,
                    a: x,
                    b: y,
                });
            }
            (V::M(x), V::M(y)) => {
                let Shape::Str { wide, .. } = self.shape(a.ty) else {
                    return Err(self.error(
                        span,
                        "comparison of structured values is not supported".into(),
                    ));
                };
                let (rx, ry) = (self.addr_reg(x), self.addr_reg(y));
                let o = self.reg(RegClass::I64);
                self.builtin(Builtin::Str(StrFn::Compare, wide), Some(o), &[rx, ry], span);
                let z = self.iconst(0);
                self.emit(Inst::ICmp {
                    cmp,
                    signed: true,
                    dst: d,
                    a: o,
                    b: z,
                });
            }
            _ => return Err(self.error(span, "comparison of these values is not supported".into())),
        }
        Ok(d)
    }

    fn pow(&mut self, l: &Expr, r: &Expr, ty: TypeId, e: &Expr) -> Res<Val> {
        let Some(el @ (Elem::Real | Elem::Lreal)) = self.elem(ty) else {
            return Err(self.error(e.span, "** of integers is not supported".into()));
        };
        let wide = el == Elem::Lreal;
        let a = self.expr(l, Some(ty))?;
        let rt = self.typed(r);
        let int_exp = matches!(rt.ty, Ty::AnyInt)
            || matches!(rt.ty, Ty::Of(t) if self.elem(t).is_some_and(|x| x.is_int()));
        let (op, b) = if int_exp {
            (
                Builtin::PowInt(wide),
                self.expr(r, Some(TypeId::elem(Elem::Lint)))?,
            )
        } else {
            (Builtin::Pow(wide), self.expr(r, Some(ty))?)
        };
        let (V::F(x) | V::D(x), V::I(y) | V::F(y) | V::D(y)) = (a.v, b.v) else {
            return Err(Failed);
        };
        let d = self.reg(if wide { RegClass::F64 } else { RegClass::F32 });
        self.builtin(op, Some(d), &[x, y], e.span);
        Ok(Val {
            v: if wide { V::D(d) } else { V::F(d) },
            ty,
        })
    }

    fn time_op(&mut self, op: BinaryOp, l: &Expr, r: &Expr, ty: TypeId, e: &Expr) -> Res<Val> {
        let (tl, tr) = (self.typed(l), self.typed(r));
        let el_of = |g: &Self, t: &Typed| match t.ty {
            Ty::Of(id) => g.elem(id),
            Ty::AnyInt => Some(Elem::Lint),
            Ty::AnyReal => Some(Elem::Lreal),
            _ => None,
        };
        let (a, b) = (el_of(self, &tl), el_of(self, &tr));
        let (Some(a), Some(b)) = (a, b) else {
            return Err(Failed);
        };
        use BinaryOp::*;
        let lint = TypeId::elem(Elem::Lint);
        let lreal = TypeId::elem(Elem::Lreal);
        // (function, type of lhs, type of rhs, swap operands)
        let (f, lt, rt, swap) = match (op, a, b) {
            (Add, x, y) if x.is_duration() && y.is_duration() => (TimeFn::AddTime, ty, ty, false),
            (Sub, x, y) if x.is_duration() && y.is_duration() => (TimeFn::SubTime, ty, ty, false),
            (Add, Elem::Tod | Elem::Ltod, _) => {
                (TimeFn::AddTodTime, ty, TypeId::elem(Elem::Ltime), false)
            }
            (Sub, Elem::Tod | Elem::Ltod, y) if y.is_duration() => {
                (TimeFn::SubTodTime, ty, TypeId::elem(Elem::Ltime), false)
            }
            (Sub, Elem::Tod | Elem::Ltod, _) => (
                TimeFn::SubTodTod,
                TypeId::elem(Elem::Ltod),
                TypeId::elem(Elem::Ltod),
                false,
            ),
            (Add, Elem::Dt | Elem::Ldt, _) => {
                (TimeFn::AddDtTime, ty, TypeId::elem(Elem::Ltime), false)
            }
            (Sub, Elem::Dt | Elem::Ldt, y) if y.is_duration() => {
                (TimeFn::SubDtTime, ty, TypeId::elem(Elem::Ltime), false)
            }
            (Sub, Elem::Dt | Elem::Ldt, _) => (
                TimeFn::SubDtDt,
                TypeId::elem(Elem::Ldt),
                TypeId::elem(Elem::Ldt),
                false,
            ),
            (Sub, Elem::Date | Elem::Ldate, _) => (
                TimeFn::SubDateDate,
                TypeId::elem(Elem::Ldate),
                TypeId::elem(Elem::Ldate),
                false,
            ),
            (Mul, x, y) if x.is_duration() && y.is_real() => {
                (TimeFn::MulTimeReal, ty, lreal, false)
            }
            (Mul, x, y) if x.is_duration() && y.is_int() => (TimeFn::MulTime, ty, lint, false),
            (Mul, x, y) if y.is_duration() && x.is_real() => (TimeFn::MulTimeReal, lreal, ty, true),
            (Mul, x, y) if y.is_duration() && x.is_int() => (TimeFn::MulTime, lint, ty, true),
            (Div, x, y) if x.is_duration() && y.is_real() => {
                (TimeFn::DivTimeReal, ty, lreal, false)
            }
            (Div, x, y) if x.is_duration() && y.is_int() => (TimeFn::DivTime, ty, lint, false),
            _ => {
                return Err(self.error(
                    e.span,
                    format!("operator {} not supported on these time types", op.symbol()),
                ))
            }
        };
        let x = self.expr(l, Some(lt))?;
        let y = self.expr(r, Some(rt))?;
        let (V::I(rx) | V::D(rx), V::I(ry) | V::D(ry)) = (x.v, y.v) else {
            return Err(Failed);
        };
        let (p, q) = if swap { (ry, rx) } else { (rx, ry) };
        let d = self.reg(RegClass::I64);
        self.builtin(Builtin::Time(f), Some(d), &[p, q], e.span);
        Ok(Val { v: V::I(d), ty })
    }
}

fn wrap_v(r: Reg, mt: MemTy) -> V {
    match mt.class() {
        RegClass::I64 => V::I(r),
        RegClass::F32 => V::F(r),
        RegClass::F64 => V::D(r),
    }
}

/// TIME/LTIME, DATE/LDATE, TOD/LTOD, DT/LDT: the same representation.
fn same_family(a: Elem, b: Elem) -> bool {
    (a.is_duration() && b.is_duration())
        || matches!((a, b), (Elem::Date | Elem::Ldate, Elem::Date | Elem::Ldate))
        || matches!((a, b), (Elem::Tod | Elem::Ltod, Elem::Tod | Elem::Ltod))
        || matches!((a, b), (Elem::Dt | Elem::Ldt, Elem::Dt | Elem::Ldt))
}
