//! Standard functions (IEC 61131-3 tables 22–43): conversions, numeric,
//! bit-shift, bitwise, selection, comparison, string and time functions,
//! lowered to instructions or [`Builtin`]s.

use super::{Failed, Gen, Res, Shape, Val, V};
use crate::symbols::elementary;
use automat_ir::code::{
    Addr, Base, Builtin, CheckKind, Cmp, Inst, IntOp, MathFn, Reg, RegClass, ShiftOp, StrFn, TimeFn,
};
use automat_sema::ops::Ty;
use automat_sema::stdlib::{ConvTy, Sig, StdOp};
use automat_sema::types::{Elem, TypeId};
use automat_syntax::ast::{Arg, BinaryOp, Expr};

/// Capacity of the temporary that holds a conversion's result (a number,
/// time or date as text): longer than any such text, so never a cut.
const TEMP_CAP: u32 = 1024;

impl Gen<'_, '_> {
    pub fn std_call(
        &mut self,
        sig: &Sig,
        args: &[Arg],
        e: &Expr,
        want: Option<TypeId>,
    ) -> Res<Val> {
        let mut pos: Vec<Option<&Expr>> = Vec::new();
        for (k, a) in args.iter().enumerate() {
            let i = match a.name {
                Some(n) => sig
                    .position_of(self.cx.interner.name(n.sym))
                    .unwrap_or(usize::MAX),
                None => k,
            };
            if i == usize::MAX || i > 4096 {
                return Err(self.error(a.span, format!("{}: unknown parameter", sig.name)));
            }
            if pos.len() <= i {
                pos.resize(i + 1, None);
            }
            pos[i] = a.value.as_ref();
        }
        let xs: Vec<&Expr> = pos.iter().flatten().copied().collect();
        let typed = self.typed(e);
        let rty = self.concrete(typed.ty, want, None);
        let arg = |i: usize| xs.get(i).copied().ok_or(Failed);
        let conv_ty = |c: ConvTy| match c {
            ConvTy::Elem(e) => TypeId::elem(e),
            ConvTy::Str(w) => {
                if w {
                    TypeId::WSTRING
                } else {
                    TypeId::STRING
                }
            }
        };
        use StdOp::*;
        match sig.op {
            Convert { from, to } => {
                let x = arg(0)?;
                let v = self.expr(x, Some(conv_ty(from)))?;
                self.convert(v, x, conv_ty(to), e)
            }
            ToType(to) => {
                let x = arg(0)?;
                let t = self.typed(x);
                let from = self.concrete(t.ty, None, t.value.as_ref()).ok_or(Failed)?;
                let v = self.expr(x, Some(from))?;
                self.convert(v, x, conv_ty(to), e)
            }
            Trunc(to) => {
                // The generic TRUNC: the integer type the checker chose.
                let to = match want.or(rty).and_then(|t| self.elem(t)) {
                    Some(r) if sig.name == "TRUNC" && r.is_int() => r,
                    _ => to,
                };
                let x = arg(0)?;
                let t = self.typed(x);
                let from = self.concrete(t.ty, None, t.value.as_ref()).ok_or(Failed)?;
                let v = self.expr(x, Some(from))?;
                let (Some(fe), V::F(r) | V::D(r)) = (self.elem(from), v.v) else {
                    return Err(Failed);
                };
                let d = self.reg(RegClass::I64);
                self.builtin(
                    Builtin::Trunc(elementary(fe), elementary(to)),
                    Some(d),
                    &[r],
                    e.span,
                );
                Ok(Val {
                    v: V::I(d),
                    ty: TypeId::elem(to),
                })
            }
            Abs | Sqrt | Ln | Log | Exp | Sin | Cos | Tan | Asin | Acos | Atan => {
                let ty = rty.ok_or(Failed)?;
                let v = self.expr(arg(0)?, Some(ty))?;
                let m = match sig.op {
                    Abs => MathFn::Abs,
                    Sqrt => MathFn::Sqrt,
                    Ln => MathFn::Ln,
                    Log => MathFn::Log,
                    Exp => MathFn::Exp,
                    Sin => MathFn::Sin,
                    Cos => MathFn::Cos,
                    Tan => MathFn::Tan,
                    Asin => MathFn::Asin,
                    Acos => MathFn::Acos,
                    _ => MathFn::Atan,
                };
                match v.v {
                    V::F(r) | V::D(r) => {
                        let wide = matches!(v.v, V::D(_));
                        let d = self.reg(if wide { RegClass::F64 } else { RegClass::F32 });
                        self.builtin(Builtin::Math(m, wide), Some(d), &[r], e.span);
                        Ok(Val {
                            v: if wide { V::D(d) } else { V::F(d) },
                            ty,
                        })
                    }
                    V::I(r) if m == MathFn::Abs => {
                        let el = self.elem(ty).ok_or(Failed)?;
                        let n = self.reg(RegClass::I64);
                        self.emit(Inst::Neg { dst: n, src: r });
                        let n = match self.wrap(n, el) {
                            V::I(x) => x,
                            _ => n,
                        };
                        let z = self.iconst(0);
                        let c = self.reg(RegClass::I64);
                        self.emit(Inst::ICmp {
                            cmp: Cmp::Lt,
                            signed: true,
                            dst: c,
                            a: r,
                            b: z,
                        });
                        let d = self.select(c, n, r, RegClass::I64);
                        Ok(Val { v: V::I(d), ty })
                    }
                    _ => Err(self.error(
                        e.span,
                        format!("{} of this type is not supported", sig.name),
                    )),
                }
            }
            Expt => {
                let ty = rty.ok_or(Failed)?;
                let (b, x) = (arg(0)?, arg(1)?);
                let bin = Expr {
                    kind: automat_syntax::ast::ExprKind::Binary {
                        op: BinaryOp::Pow,
                        lhs: Box::new(b.clone()),
                        rhs: Box::new(x.clone()),
                    },
                    span: e.span,
                };
                self.expr(&bin, Some(ty))
            }
            Add | Sub | Mul | Div | Mod | And | Or | Xor => {
                let ty = rty.ok_or(Failed)?;
                let el = self.elem(ty).ok_or(Failed)?;
                let op = match sig.op {
                    Add => BinaryOp::Add,
                    Sub => BinaryOp::Sub,
                    Mul => BinaryOp::Mul,
                    Div => BinaryOp::Div,
                    Mod => BinaryOp::Mod,
                    And => BinaryOp::And,
                    Or => BinaryOp::Or,
                    _ => BinaryOp::Xor,
                };
                if el.is_duration() || el.is_date() {
                    // Time arithmetic (ADD_TIME, SUB_DT_DT, ...) is the operator's.
                    let mut acc = arg(0)?.clone();
                    for x in xs.iter().skip(1) {
                        acc = Expr {
                            kind: automat_syntax::ast::ExprKind::Binary {
                                op,
                                lhs: Box::new(acc),
                                rhs: Box::new((*x).clone()),
                            },
                            span: e.span,
                        };
                    }
                    return self.expr(&acc, Some(ty));
                }
                let mut acc = self.expr(arg(0)?, Some(ty))?;
                for x in xs.iter().skip(1) {
                    let b = self.expr(x, Some(ty))?;
                    acc = Val {
                        v: self.arith(op, acc, b, el, e.span)?,
                        ty,
                    };
                }
                Ok(acc)
            }
            Move => self.expr(arg(0)?, want),
            Not => {
                let ty = rty.ok_or(Failed)?;
                let n = Expr {
                    kind: automat_syntax::ast::ExprKind::Unary {
                        op: automat_syntax::ast::UnaryOp::Not,
                        operand: Box::new(arg(0)?.clone()),
                    },
                    span: e.span,
                };
                self.expr(&n, Some(ty))
            }
            Shl | Shr | Rol | Ror => {
                let ty = rty.ok_or(Failed)?;
                let el = self.elem(ty).ok_or(Failed)?;
                let v = self.expr(arg(0)?, Some(ty))?;
                let n = self.int_expr(arg(1)?)?;
                let V::I(r) = v.v else { return Err(Failed) };
                let op = match sig.op {
                    Shl => ShiftOp::Shl,
                    Shr => ShiftOp::Shr,
                    Rol => ShiftOp::Rol,
                    _ => ShiftOp::Ror,
                };
                let width = match crate::layout::mem_ty(el).size() {
                    _ if el == Elem::Bool => 1,
                    n => (n * 8) as u8,
                };
                let d = self.reg(RegClass::I64);
                self.emit(Inst::Shift {
                    op,
                    width,
                    dst: d,
                    a: r,
                    n,
                });
                // The result is masked to `width` bits: already canonical
                // for an unsigned type of that width.
                let v = if el.is_signed() {
                    self.wrap(d, el)
                } else {
                    V::I(d)
                };
                Ok(Val { v, ty })
            }
            Sel => {
                let ty = rty.ok_or(Failed)?;
                let g = self.cond_reg(arg(0)?)?;
                let a = self.expr(arg(1)?, Some(ty))?;
                let b = self.expr(arg(2)?, Some(ty))?;
                self.select_val(g, b, a, ty)
            }
            Max | Min => {
                let ty = rty.ok_or(Failed)?;
                let mut acc = self.expr(arg(0)?, Some(ty))?;
                for x in xs.iter().skip(1) {
                    let b = self.expr(x, Some(ty))?;
                    let cmp = if sig.op == Max { Cmp::Gt } else { Cmp::Lt };
                    let c = self.compare(cmp, b, acc, e.span)?;
                    acc = self.select_val(c, b, acc, ty)?;
                }
                Ok(acc)
            }
            Limit => {
                let ty = rty.ok_or(Failed)?;
                let mn = self.expr(arg(0)?, Some(ty))?;
                let x = self.expr(arg(1)?, Some(ty))?;
                let mx = self.expr(arg(2)?, Some(ty))?;
                let c = self.compare(Cmp::Lt, x, mn, e.span)?;
                let lo = self.select_val(c, mn, x, ty)?;
                let c2 = self.compare(Cmp::Gt, lo, mx, e.span)?;
                self.select_val(c2, mx, lo, ty)
            }
            Mux => {
                let ty = rty.ok_or(Failed)?;
                let k = self.int_expr(arg(0)?)?;
                let n = xs.len().saturating_sub(1);
                if n == 0 {
                    return Err(Failed);
                }
                let site = self.site(e.span);
                self.emit(Inst::Check {
                    kind: CheckKind::Index,
                    val: k,
                    lo: 0,
                    hi: n as i64 - 1,
                    site,
                });
                let mut acc = self.expr(arg(1)?, Some(ty))?;
                for (i, x) in xs.iter().enumerate().skip(2) {
                    let b = self.expr(x, Some(ty))?;
                    let ki = self.iconst(i as i64 - 1);
                    let c = self.reg(RegClass::I64);
                    self.emit(Inst::ICmp {
                        cmp: Cmp::Eq,
                        signed: true,
                        dst: c,
                        a: k,
                        b: ki,
                    });
                    acc = self.select_val(c, b, acc, ty)?;
                }
                Ok(acc)
            }
            Gt | Ge | Eq | Le | Lt | Ne => {
                let cmp = match sig.op {
                    Gt => Cmp::Gt,
                    Ge => Cmp::Ge,
                    Eq => Cmp::Eq,
                    Le => Cmp::Le,
                    Lt => Cmp::Lt,
                    _ => Cmp::Ne,
                };
                let mut ct: Option<TypeId> = None;
                for x in &xs {
                    let t = self.typed(x);
                    let c = self.concrete(t.ty, ct, t.value.as_ref());
                    ct = match (ct, c) {
                        (Some(a), Some(b)) => match (self.elem(a), self.elem(b)) {
                            (Some(p), Some(q)) => automat_sema::lattice::lub(p, q)
                                .map(TypeId::elem)
                                .or(Some(a)),
                            _ => Some(a),
                        },
                        (None, c) => c,
                        (a, None) => a,
                    };
                }
                let ct = ct.ok_or(Failed)?;
                let vals = xs
                    .iter()
                    .map(|x| self.expr(x, Some(ct)))
                    .collect::<Res<Vec<_>>>()?;
                let mut acc: Option<Reg> = None;
                for w in vals.windows(2) {
                    let c = self.compare(cmp, w[0], w[1], e.span)?;
                    acc = Some(match acc {
                        None => c,
                        Some(a) => {
                            let d = self.reg(RegClass::I64);
                            self.emit(Inst::Int {
                                op: IntOp::And,
                                dst: d,
                                a,
                                b: c,
                            });
                            d
                        }
                    });
                }
                let r = match acc {
                    Some(r) => r,
                    None => self.iconst(1),
                };
                Ok(Val {
                    v: V::I(r),
                    ty: TypeId::BOOL,
                })
            }
            Len | Find => {
                let wide = self.str_arg_wide(&xs)?;
                let (regs, _) = self.str_regs(&xs, wide, &[])?;
                let d = self.reg(RegClass::I64);
                let f = if sig.op == Len {
                    StrFn::Len
                } else {
                    StrFn::Find
                };
                self.builtin(Builtin::Str(f, wide), Some(d), &regs, e.span);
                let ty = rty.unwrap_or(TypeId::elem(Elem::Int));
                let v = Val {
                    v: V::I(d),
                    ty: TypeId::elem(Elem::Lint),
                };
                self.coerce(v, ty, e.span)
            }
            Left | Right | Mid | Concat | Insert | Delete | Replace => {
                let wide = self.str_arg_wide(&xs)?;
                // Which arguments are integers (positions and lengths).
                let ints: &[usize] = match sig.op {
                    Left | Right => &[1],
                    Mid | Delete => &[1, 2],
                    Insert => &[2],
                    Replace => &[2, 3],
                    _ => &[],
                };
                let f = match sig.op {
                    Left => StrFn::Left,
                    Right => StrFn::Right,
                    Mid => StrFn::Mid,
                    Concat => StrFn::Concat,
                    Insert => StrFn::Insert,
                    Delete => StrFn::Delete,
                    _ => StrFn::Replace,
                };
                let (regs, bounds) = self.str_regs(&xs, wide, ints)?;
                // The result holds all it can be (LEFT, RIGHT, MID, DELETE
                // at most their input; CONCAT, INSERT, REPLACE the inputs
                // together), up to the longest string: only the assignment
                // of the result truncates, to the destination's length.
                let first = bounds.first().copied().unwrap_or(0);
                let result = match f {
                    StrFn::Concat => bounds.iter().fold(0u32, |a, b| a.saturating_add(*b)),
                    StrFn::Insert | StrFn::Replace => {
                        first.saturating_add(bounds.get(1).copied().unwrap_or(0))
                    }
                    _ => first,
                };
                let result = result.min(automat_ir::strbuf::MAX_LEN);
                let out = self.temp_str(wide, result);
                let d = self.addr_reg(out);
                let cap = self.iconst(i64::from(result));
                let mut all = vec![d, cap];
                all.extend(regs);
                self.builtin(Builtin::Str(f, wide), None, &all, e.span);
                let ty = rty.unwrap_or(if wide {
                    TypeId::WSTRING
                } else {
                    TypeId::STRING
                });
                Ok(Val { v: V::M(out), ty })
            }
            ConcatDateTod => {
                let a = self.expr(arg(0)?, Some(TypeId::elem(Elem::Date)))?;
                let b = self.expr(arg(1)?, Some(TypeId::elem(Elem::Tod)))?;
                let (V::I(x), V::I(y)) = (a.v, b.v) else {
                    return Err(Failed);
                };
                let d = self.reg(RegClass::I64);
                self.builtin(
                    Builtin::Time(TimeFn::ConcatDateTod),
                    Some(d),
                    &[x, y],
                    e.span,
                );
                Ok(Val {
                    v: V::I(d),
                    ty: rty.unwrap_or(TypeId::elem(Elem::Dt)),
                })
            }
            ScanTime => {
                let d = self.reg(RegClass::I64);
                self.emit(Inst::Now { dst: d });
                Ok(Val {
                    v: V::I(d),
                    ty: TypeId::elem(Elem::Time),
                })
            }
            _ => self.std_more(sig, &pos, e, want, rty),
        }
    }

    /// An explicit conversion (`*_TO_*`, `TO_*`) of `v`, the value of `x`.
    fn convert(&mut self, v: Val, x: &Expr, to: TypeId, e: &Expr) -> Res<Val> {
        match (self.shape(v.ty), self.shape(to)) {
            (Shape::Int(_), Shape::Int(_)) => self.coerce(v, to, e.span),
            (Shape::Int(a), Shape::Str { wide, .. }) => {
                let (V::I(r) | V::F(r) | V::D(r)) = v.v else {
                    return Err(Failed);
                };
                let out = self.temp_str(wide, TEMP_CAP);
                let d = self.addr_reg(out);
                let cap = self.iconst(TEMP_CAP as i64);
                self.builtin(
                    Builtin::ToString(elementary(a), wide),
                    None,
                    &[d, cap, r],
                    e.span,
                );
                Ok(Val {
                    v: V::M(out),
                    ty: to,
                })
            }
            (Shape::Str { wide, .. }, Shape::Int(b)) => {
                let V::M(a) = v.v else { return Err(Failed) };
                let s = self.addr_reg(a);
                let mt = crate::layout::mem_ty(b);
                let d = self.reg(mt.class());
                self.builtin(
                    Builtin::FromString(elementary(b), wide),
                    Some(d),
                    &[s],
                    e.span,
                );
                let vv = match mt.class() {
                    RegClass::I64 => V::I(d),
                    RegClass::F32 => V::F(d),
                    RegClass::F64 => V::D(d),
                };
                Ok(Val { v: vv, ty: to })
            }
            (Shape::Str { wide: a, .. }, Shape::Str { wide: b, .. }) if a == b => {
                Ok(Val { v: v.v, ty: to })
            }
            (Shape::Str { .. }, Shape::Str { wide, .. }) => {
                let V::M(src) = v.v else { return Err(Failed) };
                // As long as the source can be (a WCHAR per CHAR or back).
                let n = self.str_bound(Some(x), &v, src);
                let out = self.temp_str(wide, n);
                let d = self.addr_reg(out);
                let cap = self.iconst(i64::from(n));
                let s = self.addr_reg(src);
                self.builtin(Builtin::StrConv(wide), None, &[d, cap, s], e.span);
                Ok(Val {
                    v: V::M(out),
                    ty: to,
                })
            }
            _ => Err(self.error(e.span, "this conversion is not supported yet".into())),
        }
    }

    fn cond_reg(&mut self, x: &Expr) -> Res<Reg> {
        match self.expr(x, Some(TypeId::BOOL))?.v {
            V::I(r) => Ok(r),
            _ => Err(Failed),
        }
    }

    /// `c ? a : b` for registers of one class (branch-free for a backend to pick).
    pub fn select(&mut self, c: Reg, a: Reg, b: Reg, class: RegClass) -> Reg {
        let d = self.reg(class);
        let br = self.emit(Inst::Branch {
            cond: c,
            then: u32::MAX,
            els: u32::MAX,
        });
        let t = self.here();
        self.emit(Inst::Mov { dst: d, src: a });
        let j = self.jump_fwd();
        let f = self.here();
        self.emit(Inst::Mov { dst: d, src: b });
        let end = self.here();
        if let Some(Inst::Branch { then, els, .. }) = self.f.code.get_mut(br as usize) {
            *then = t;
            *els = f;
        }
        self.patch(j, end);
        d
    }

    fn select_val(&mut self, c: Reg, a: Val, b: Val, ty: TypeId) -> Res<Val> {
        let v = match (a.v, b.v) {
            (V::I(x), V::I(y)) => V::I(self.select(c, x, y, RegClass::I64)),
            (V::F(x), V::F(y)) => V::F(self.select(c, x, y, RegClass::F32)),
            (V::D(x), V::D(y)) => V::D(self.select(c, x, y, RegClass::F64)),
            (V::M(x), V::M(y)) => {
                let (rx, ry) = (self.addr_reg(x), self.addr_reg(y));
                V::M(automat_ir::code::Addr::reg(
                    self.select(c, rx, ry, RegClass::I64),
                    0,
                ))
            }
            _ => return Err(Failed),
        };
        Ok(Val { v, ty })
    }

    fn str_arg_wide(&mut self, xs: &[&Expr]) -> Res<bool> {
        let x = xs.first().ok_or(Failed)?;
        Ok(match self.typed(x).ty {
            Ty::AnyStr { wide } => wide,
            Ty::Of(t) => matches!(self.shape(t), Shape::Str { wide: true, .. }),
            _ => false,
        })
    }

    /// Registers for string function arguments: addresses for strings,
    /// values for the integer positions listed in `ints`; and for each
    /// string argument, in order, the most characters it can hold.
    fn str_regs(&mut self, xs: &[&Expr], wide: bool, ints: &[usize]) -> Res<(Vec<Reg>, Vec<u32>)> {
        let st = if wide {
            TypeId::WSTRING
        } else {
            TypeId::STRING
        };
        let mut out = Vec::with_capacity(xs.len());
        let mut bounds = Vec::new();
        for (i, x) in xs.iter().enumerate() {
            if ints.contains(&i) {
                out.push(self.int_expr(x)?);
            } else {
                let v = self.expr(x, Some(st))?;
                match v.v {
                    V::M(a) => {
                        bounds.push(self.str_bound(Some(x), &v, a));
                        out.push(self.addr_reg(a));
                    }
                    _ => return Err(self.error(x.span, "a string is needed here".into())),
                }
            }
        }
        Ok((out, bounds))
    }

    /// The most characters the string `v` (the value of `x`, at `a`) can
    /// hold: a function result's temporary its capacity, a constant its
    /// length, a variable its declared length.
    fn str_bound(&self, x: Option<&Expr>, v: &Val, a: Addr) -> u32 {
        if a.base == Base::Abs {
            if let Some(&cap) = self.str_caps.get(&a.offset) {
                return cap;
            }
        }
        let typed = x.map(|x| self.typed(x));
        if let Some(automat_sema::value::Value::Str(s)) =
            typed.as_ref().and_then(|t| t.value.as_ref())
        {
            let n = s.chars().count().max(s.encode_utf16().count());
            return u32::try_from(n).unwrap_or(u32::MAX);
        }
        // The declared type (the value's is the one the function wants).
        if let Some(Ty::Of(t)) = typed.map(|t| t.ty) {
            if let Shape::Str { cap, .. } = self.shape(t) {
                return cap;
            }
        }
        match self.shape(v.ty) {
            Shape::Str { cap, .. } => cap,
            _ => automat_ir::strbuf::MAX_LEN,
        }
    }
}
