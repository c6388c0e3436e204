//! Standard functions beyond arithmetic and strings: BCD conversions,
//! ATAN2, date composition and decomposition, DAY_OF_WEEK, array bounds,
//! references and SIZEOF.

use super::{Failed, Gen, Res, Val, V};
use crate::symbols::elementary;
use automat_ir::code::{Builtin, Cmp, DateFn, DatePart, DateSrc, Inst, MemTy, Reg, RegClass};
use automat_sema::ops::Ty;
use automat_sema::stdlib::{PTy, Sig, StdOp};
use automat_sema::types::{Elem, TypeId, TypeKind};
use automat_syntax::ast::Expr;

impl Gen<'_, '_> {
    /// The standard functions `std_call` does not handle itself; `pos` are
    /// the arguments by parameter position.
    pub(super) fn std_more(
        &mut self,
        sig: &Sig,
        pos: &[Option<&Expr>],
        e: &Expr,
        want: Option<TypeId>,
        rty: Option<TypeId>,
    ) -> Res<Val> {
        let arg = |i: usize| pos.get(i).copied().flatten().ok_or(Failed);
        match sig.op {
            StdOp::BcdToInt(to) => {
                let x = arg(0)?;
                let from = match sig.params.first().map(|p| p.ty) {
                    Some(PTy::Elem(f)) => f,
                    _ => self.bcd_source(x),
                };
                let v = self.expr(x, Some(TypeId::elem(from)))?;
                let V::I(r) = v.v else { return Err(Failed) };
                let d = self.reg(RegClass::I64);
                self.builtin(
                    Builtin::FromBcd(elementary(from), elementary(to)),
                    Some(d),
                    &[r],
                    e.span,
                );
                Ok(Val {
                    v: V::I(d),
                    ty: TypeId::elem(to),
                })
            }
            StdOp::IntToBcd(to) => {
                let x = arg(0)?;
                let from = match sig.params.first().map(|p| p.ty) {
                    Some(PTy::Elem(f)) => f,
                    _ => Elem::Lint,
                };
                let v = self.expr(x, Some(TypeId::elem(from)))?;
                let V::I(r) = v.v else { return Err(Failed) };
                let d = self.reg(RegClass::I64);
                self.builtin(
                    Builtin::ToBcd(elementary(from), elementary(to)),
                    Some(d),
                    &[r],
                    e.span,
                );
                Ok(Val {
                    v: V::I(d),
                    ty: TypeId::elem(to),
                })
            }
            StdOp::Atan2 => {
                let ty = rty.ok_or(Failed)?;
                let y = self.expr(arg(0)?, Some(ty))?;
                let x = self.expr(arg(1)?, Some(ty))?;
                let (wide, a, b) = match (y.v, x.v) {
                    (V::D(a), V::D(b)) => (true, a, b),
                    (V::F(a), V::F(b)) => (false, a, b),
                    _ => return Err(Failed),
                };
                let d = self.reg(if wide { RegClass::F64 } else { RegClass::F32 });
                self.builtin(Builtin::Atan2(wide), Some(d), &[a, b], e.span);
                Ok(Val {
                    v: if wide { V::D(d) } else { V::F(d) },
                    ty,
                })
            }
            StdOp::ConcatDate | StdOp::ConcatTod | StdOp::ConcatDt => {
                let (f, n, ty) = match sig.op {
                    StdOp::ConcatDate => (DateFn::ConcatDate, 3, Elem::Date),
                    StdOp::ConcatTod => (DateFn::ConcatTod, 4, Elem::Tod),
                    _ => (DateFn::ConcatDt, 7, Elem::Dt),
                };
                let mut regs = Vec::with_capacity(n);
                for i in 0..n {
                    regs.push(self.int_expr(arg(i)?)?);
                }
                let d = self.reg(RegClass::I64);
                self.builtin(Builtin::Date(f), Some(d), &regs, e.span);
                Ok(Val {
                    v: V::I(d),
                    ty: TypeId::elem(ty),
                })
            }
            StdOp::DayOfWeek => {
                let v = self.expr(arg(0)?, Some(TypeId::elem(Elem::Date)))?;
                let V::I(r) = v.v else { return Err(Failed) };
                let d = self.reg(RegClass::I64);
                self.builtin(Builtin::Date(DateFn::DayOfWeek), Some(d), &[r], e.span);
                let v = Val {
                    v: V::I(d),
                    ty: TypeId::elem(Elem::Lint),
                };
                self.coerce(v, TypeId::elem(Elem::Int), e.span)
            }
            StdOp::SplitDate | StdOp::SplitTod | StdOp::SplitDt => {
                use DatePart::*;
                let (src, input, parts): (DateSrc, Elem, &[DatePart]) = match sig.op {
                    StdOp::SplitDate => (DateSrc::Date, Elem::Date, &[Year, Month, Day]),
                    StdOp::SplitTod => (
                        DateSrc::Tod,
                        Elem::Tod,
                        &[Hour, Minute, Second, Millisecond],
                    ),
                    _ => (
                        DateSrc::Dt,
                        Elem::Dt,
                        &[Year, Month, Day, Hour, Minute, Second, Millisecond],
                    ),
                };
                let v = self.expr(arg(0)?, Some(TypeId::elem(input)))?;
                let V::I(r) = v.v else { return Err(Failed) };
                for (k, part) in parts.iter().enumerate() {
                    let Some(target) = pos.get(k + 1).copied().flatten() else {
                        continue;
                    };
                    let lv = self.place(target)?;
                    let d = self.reg(RegClass::I64);
                    self.builtin(
                        Builtin::Date(DateFn::Part(*part, src)),
                        Some(d),
                        &[r],
                        e.span,
                    );
                    let pv = Val {
                        v: V::I(d),
                        ty: TypeId::elem(Elem::Lint),
                    };
                    let pv = self.coerce(pv, lv.ty, target.span)?;
                    self.store(lv, pv, target.span)?;
                }
                Ok(Val {
                    v: V::I(self.iconst(0)),
                    ty: TypeId::BOOL,
                })
            }
            StdOp::LowerBound | StdOp::UpperBound => {
                let upper = sig.op == StdOp::UpperBound;
                self.array_bound(arg(0)?, arg(1)?, upper)
            }
            StdOp::Ref | StdOp::Adr => self.ref_of(arg(0)?, want, e),
            StdOp::Sizeof => self.size_of(arg(0)?),
            _ => Err(self.error(
                e.span,
                format!("standard function {} is not supported", sig.name),
            )),
        }
    }

    /// The bit string type a BCD argument is read as: its own type when it
    /// is one, else the bit string of the integer's width.
    fn bcd_source(&self, x: &Expr) -> Elem {
        let t = self.typed(x);
        let el = match t.ty {
            Ty::Of(id) => self.elem(id),
            _ => None,
        };
        match el {
            Some(e) if e.is_bit() && e != Elem::Bool => e,
            Some(e) if e.bits() == 8 => Elem::Byte,
            Some(e) if e.bits() == 16 => Elem::Word,
            Some(e) if e.bits() == 32 => Elem::Dword,
            Some(_) => Elem::Lword,
            None => {
                let v = t.value.as_ref().and_then(|v| v.as_int()).unwrap_or(0);
                if u32::try_from(v).is_ok() {
                    Elem::Dword
                } else {
                    Elem::Lword
                }
            }
        }
    }

    /// LOWER_BOUND / UPPER_BOUND of dimension `dim` (1-based) of an array,
    /// from its type or, for a VAR_IN_OUT `ARRAY[*]`, from the bounds the
    /// caller passed.
    fn array_bound(&mut self, arr: &Expr, dim: &Expr, upper: bool) -> Res<Val> {
        let lv = self.place(arr)?;
        let TypeKind::Array { dims, .. } = self.kind(lv.ty) else {
            return Err(self.error(arr.span, "LOWER_BOUND/UPPER_BOUND need an array".into()));
        };
        let bounds = self.cx.layout.dims(dims);
        let n = bounds.len() as i64;
        let desc = match lv.addr.base {
            automat_ir::code::Base::Reg(r) if lv.addr.offset == 0 => self.star.get(&r).copied(),
            _ => None,
        };
        let known = self.typed(dim).value.as_ref().and_then(|v| v.as_int());
        let one = |g: &mut Self, k: i64| -> Reg {
            match (desc, bounds.get(k as usize)) {
                (Some(d), _) => {
                    let r = g.reg(RegClass::I64);
                    g.emit(Inst::Load {
                        dst: r,
                        ty: MemTy::I32,
                        addr: super::expr::add(d, 4 + 8 * k as u32 + if upper { 4 } else { 0 }),
                    });
                    r
                }
                (None, Some(&(lo, hi))) => g.iconst(if upper { hi } else { lo }),
                (None, None) => g.iconst(0),
            }
        };
        let r = match known {
            Some(k) if (1..=n as i128).contains(&k) => one(self, k as i64 - 1),
            Some(k) => {
                return Err(self.error(
                    dim.span,
                    format!("the array has {n} dimension(s); dimension {k} does not exist"),
                ))
            }
            None => {
                // A dimension chosen at run time: checked, then selected.
                let k = self.int_expr(dim)?;
                let site = self.site(dim.span);
                self.emit(Inst::Check {
                    kind: automat_ir::code::CheckKind::Index,
                    val: k,
                    lo: 1,
                    hi: n.max(1),
                    site,
                });
                let mut acc = one(self, 0);
                for i in 1..n {
                    let b = one(self, i);
                    let ki = self.iconst(i + 1);
                    let c = self.reg(RegClass::I64);
                    self.emit(Inst::ICmp {
                        cmp: Cmp::Eq,
                        signed: true,
                        dst: c,
                        a: k,
                        b: ki,
                    });
                    acc = self.select(c, b, acc, RegClass::I64);
                }
                acc
            }
        };
        Ok(Val {
            v: V::I(r),
            ty: TypeId::elem(Elem::Dint),
        })
    }
}
