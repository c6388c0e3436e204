//! The FOR loop: the limit and step are evaluated once; the increment is
//! computed in 64 bits and checked against the variable's range before it
//! is stored, so a loop up to the type's maximum ends instead of wrapping.

use super::{Gen, LoopCx, Res, Val, V};
use automat_ir::code::{Cmp, Inst, IntOp, RegClass};
use automat_sema::value::Value;
use automat_syntax::ast::{Expr, Stmt};

impl Gen<'_, '_> {
    pub(super) fn for_loop(
        &mut self,
        var: &automat_syntax::ast::Ident,
        from: &Expr,
        to: &Expr,
        by: Option<&Expr>,
        body: &[Stmt],
        s: &Stmt,
    ) -> Res<()> {
        let name = Expr {
            kind: automat_syntax::ast::ExprKind::Name(*var),
            span: var.span,
        };
        let lv = self.place(&name)?;
        let el = self
            .elem(lv.ty)
            .filter(|e| e.is_int())
            .ok_or_else(|| self.error(s.span, "the FOR variable must be an integer".into()))?;
        let start = self.expr(from, Some(lv.ty))?;
        self.store(lv, start, s.span)?;
        let limit = self.expr(to, Some(lv.ty))?;
        let (step, step_const) = match by {
            Some(b) => {
                let k = self.typed(b).value.as_ref().and_then(Value::as_int);
                (self.expr(b, Some(lv.ty))?, k)
            }
            None => {
                let r = self.iconst(1);
                (
                    Val {
                        v: V::I(r),
                        ty: lv.ty,
                    },
                    Some(1),
                )
            }
        };
        let (V::I(lim), V::I(st)) = (limit.v, step.v) else {
            return Err(self.error(s.span, "FOR bounds must be integers".into()));
        };
        // Freeze the limit and step (evaluated once).
        let (lim2, st2) = (self.reg(RegClass::I64), self.reg(RegClass::I64));
        self.emit(Inst::Mov {
            dst: lim2,
            src: lim,
        });
        self.emit(Inst::Mov { dst: st2, src: st });
        // The constants of the test and the increment's range check are
        // loaded once, before the loop.
        let zero = if step_const.is_none() {
            self.iconst(0)
        } else {
            lim2
        };
        let (lo, hi) = el
            .int_range()
            .unwrap_or((i64::MIN as i128, i64::MAX as i128));
        let (lo, hi) = (
            lo.max(i64::MIN as i128) as i64,
            hi.min(i64::MAX as i128) as i64,
        );
        // With a constant step only one side of the range can be crossed.
        let bounds = match step_const {
            _ if lo == i64::MIN && hi == i64::MAX => None,
            Some(k) if k >= 0 => Some((None, Some(self.iconst(hi)))),
            Some(_) => Some((Some(self.iconst(lo)), None)),
            None => Some((Some(self.iconst(lo)), Some(self.iconst(hi)))),
        };
        // test: (step >= 0 AND v <= lim) OR (step < 0 AND v >= lim)
        let top = self.here();
        let cur = match self.load(lv).v {
            V::I(r) => r,
            _ => return Err(crate::gen::Failed),
        };
        let ok = self.reg(RegClass::I64);
        match step_const {
            Some(k) => {
                let cmp = if k >= 0 { Cmp::Le } else { Cmp::Ge };
                self.emit(Inst::ICmp {
                    cmp,
                    signed: true,
                    dst: ok,
                    a: cur,
                    b: lim2,
                });
            }
            None => {
                let (up, le, ge, a, b) = (
                    self.reg(RegClass::I64),
                    self.reg(RegClass::I64),
                    self.reg(RegClass::I64),
                    self.reg(RegClass::I64),
                    self.reg(RegClass::I64),
                );
                self.emit(Inst::ICmp {
                    cmp: Cmp::Ge,
                    signed: true,
                    dst: up,
                    a: st2,
                    b: zero,
                });
                self.emit(Inst::ICmp {
                    cmp: Cmp::Le,
                    signed: true,
                    dst: le,
                    a: cur,
                    b: lim2,
                });
                self.emit(Inst::ICmp {
                    cmp: Cmp::Ge,
                    signed: true,
                    dst: ge,
                    a: cur,
                    b: lim2,
                });
                self.emit(Inst::Int {
                    op: IntOp::And,
                    dst: a,
                    a: up,
                    b: le,
                });
                let one = self.iconst(1);
                let down = self.reg(RegClass::I64);
                self.emit(Inst::Int {
                    op: IntOp::Xor,
                    dst: down,
                    a: up,
                    b: one,
                });
                self.emit(Inst::Int {
                    op: IntOp::And,
                    dst: b,
                    a: down,
                    b: ge,
                });
                self.emit(Inst::Int {
                    op: IntOp::Or,
                    dst: ok,
                    a,
                    b,
                });
            }
        }
        let br = self.emit(Inst::Branch {
            cond: ok,
            then: u32::MAX,
            els: u32::MAX,
        });
        let t = self.here();
        self.set_then(br, t);
        self.loops.push(LoopCx {
            continues: Vec::new(),
            exits: Vec::new(),
        });
        self.block(body);
        // Increment: computed in 64 bits and compared before wrapping, so a
        // loop up to the type's maximum ends instead of wrapping around.
        let inc = self.here();
        let cur = match self.load(lv).v {
            V::I(r) => r,
            _ => return Err(crate::gen::Failed),
        };
        let next = self.reg(RegClass::I64);
        self.emit(Inst::Int {
            op: IntOp::Add,
            dst: next,
            a: cur,
            b: st2,
        });
        if let Some((l, h)) = bounds {
            let c = match (l, h) {
                (Some(l), Some(h)) => {
                    let c1 = self.cmp_reg(Cmp::Ge, next, l);
                    let c2 = self.cmp_reg(Cmp::Le, next, h);
                    let c = self.reg(RegClass::I64);
                    self.emit(Inst::Int {
                        op: IntOp::And,
                        dst: c,
                        a: c1,
                        b: c2,
                    });
                    c
                }
                (Some(l), None) => self.cmp_reg(Cmp::Ge, next, l),
                (None, Some(h)) => self.cmp_reg(Cmp::Le, next, h),
                (None, None) => return Err(crate::gen::Failed),
            };
            let br2 = self.emit(Inst::Branch {
                cond: c,
                then: u32::MAX,
                els: u32::MAX,
            });
            let store_at = self.here();
            self.set_then(br2, store_at);
            self.store(
                lv,
                Val {
                    v: V::I(next),
                    ty: lv.ty,
                },
                s.span,
            )?;
            self.emit(Inst::Jump { target: top });
            let end = self.here();
            self.patch(br2, end);
            self.patch(br, end);
            self.close_loop(inc, end);
        } else {
            self.store(
                lv,
                Val {
                    v: V::I(next),
                    ty: lv.ty,
                },
                s.span,
            )?;
            self.emit(Inst::Jump { target: top });
            let end = self.here();
            self.patch(br, end);
            self.close_loop(inc, end);
        }
        Ok(())
    }
}

impl Gen<'_, '_> {
    /// `a cmp b`, signed, into a new register.
    fn cmp_reg(&mut self, cmp: Cmp, a: u32, b: u32) -> u32 {
        let d = self.reg(RegClass::I64);
        self.emit(Inst::ICmp {
            cmp,
            signed: true,
            dst: d,
            a,
            b,
        });
        d
    }
}
