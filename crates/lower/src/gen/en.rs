//! EN / ENO on calls (IEC 61131-3 §6.6.1.2.3): with `EN := FALSE` the call
//! is skipped and ENO is FALSE; otherwise the call runs and ENO is TRUE
//! (or the callee's own ENO when it declares one). A skipped function
//! call yields its type's zero value (an empty string).

use super::{Gen, Res, Val, V};
use automat_ir::code::{Addr, Inst, MemTy, Reg, RegClass};
use automat_sema::types::TypeId;
use automat_syntax::ast::{Arg, Expr};

/// The execution-control arguments of a call.
#[derive(Default)]
pub struct EnEno<'x> {
    pub en: Option<&'x Expr>,
    pub eno: Option<&'x Expr>,
}

impl Gen<'_, '_> {
    /// Separates `EN :=` and `ENO =>` from the other arguments.
    pub fn split_en<'x>(&self, args: &'x [Arg]) -> (EnEno<'x>, Vec<Arg>) {
        let syms = &self.cx.model.syms;
        let mut c = EnEno::default();
        let mut rest = Vec::with_capacity(args.len());
        for a in args {
            match a.name {
                Some(n) if n.sym == syms.en => c.en = a.value.as_ref(),
                Some(n) if n.sym == syms.eno => c.eno = a.value.as_ref(),
                _ => rest.push(a.clone()),
            }
        }
        (c, rest)
    }

    /// Runs `body` (which emits the call and returns its value and, when
    /// the callee has one, its ENO register) under EN, and binds ENO.
    /// `hidden_eno`: the byte of an instance that `fb.ENO` reads.
    pub fn with_en(
        &mut self,
        c: &EnEno,
        hidden_eno: Option<Addr>,
        body: impl FnOnce(&mut Self) -> Res<(Val, Option<Reg>)>,
    ) -> Res<Val> {
        let Some(en) = c.en else {
            let (v, eno) = body(self)?;
            // Nothing to bind: no ENO register is needed at all.
            if hidden_eno.is_none() && c.eno.is_none() {
                return Ok(v);
            }
            let (r, one) = match eno {
                Some(r) => (r, None),
                None => {
                    let one = self.iconst(1);
                    (one, Some(one))
                }
            };
            self.bind_eno(c, hidden_eno, r, one)?;
            return Ok(v);
        };
        let cond = self.cond_reg_of(en)?;
        let br = self.emit(Inst::Branch {
            cond,
            then: u32::MAX,
            els: u32::MAX,
        });
        let then_at = self.here();
        let (v, eno) = body(self)?;
        let eno_r = self.reg(RegClass::I64);
        match eno {
            Some(r) => self.emit(Inst::Mov { dst: eno_r, src: r }),
            None => self.emit(Inst::IConst {
                dst: eno_r,
                value: 1,
            }),
        };
        let (out, class) = match v.v {
            V::I(_) | V::M(_) => (self.reg(RegClass::I64), RegClass::I64),
            V::F(_) => (self.reg(RegClass::F32), RegClass::F32),
            V::D(_) => (self.reg(RegClass::F64), RegClass::F64),
        };
        let src = match v.v {
            V::I(r) | V::F(r) | V::D(r) => r,
            V::M(a) => self.addr_reg(a),
        };
        self.emit(Inst::Mov { dst: out, src });
        let j = self.jump_fwd();
        let else_at = self.here();
        self.emit(Inst::IConst {
            dst: eno_r,
            value: 0,
        });
        match (v.v, class) {
            (V::M(_), _) => {
                let zero = self.zero_value(v.ty);
                self.emit(Inst::AddrOf {
                    dst: out,
                    addr: zero,
                });
            }
            (_, RegClass::F32) => {
                self.emit(Inst::F32Const {
                    dst: out,
                    value: 0.0,
                });
            }
            (_, RegClass::F64) => {
                self.emit(Inst::F64Const {
                    dst: out,
                    value: 0.0,
                });
            }
            _ => {
                self.emit(Inst::IConst { dst: out, value: 0 });
            }
        }
        let end = self.here();
        if let Some(Inst::Branch { then, els, .. }) = self.f.code.get_mut(br as usize) {
            *then = then_at;
            *els = else_at;
        }
        self.patch(j, end);
        self.bind_eno(c, hidden_eno, eno_r, None)?;
        let nv = match v.v {
            V::I(_) => V::I(out),
            V::F(_) => V::F(out),
            V::D(_) => V::D(out),
            V::M(_) => V::M(Addr::reg(out, 0)),
        };
        Ok(Val { v: nv, ty: v.ty })
    }

    /// `one`: a register already holding TRUE, for the hidden EN byte.
    fn bind_eno(&mut self, c: &EnEno, hidden: Option<Addr>, r: Reg, one: Option<Reg>) -> Res<()> {
        if let Some(at) = hidden {
            let pou = self.pou.0;
            self.cx.hidden.stores.insert((pou, at));
            self.cx.hidden.stores.insert((pou, super::expr::add(at, 1)));
            self.emit(Inst::Store {
                src: r,
                ty: MemTy::U8,
                addr: at,
            });
            let en = match c.en {
                Some(_) => r,
                None => match one {
                    Some(one) => one,
                    None => self.iconst(1),
                },
            };
            self.emit(Inst::Store {
                src: en,
                ty: MemTy::U8,
                addr: super::expr::add(at, 1),
            });
        }
        if let Some(t) = c.eno {
            let lv = self.place(t)?;
            let v = Val {
                v: V::I(r),
                ty: TypeId::BOOL,
            };
            let v = self.coerce(v, lv.ty, t.span)?;
            self.store(lv, v, t.span)?;
        }
        Ok(())
    }

    fn cond_reg_of(&mut self, x: &Expr) -> Res<Reg> {
        match self.expr(x, Some(TypeId::BOOL))?.v {
            V::I(r) => Ok(r),
            _ => Err(self.error(x.span, "EN needs a BOOL".into())),
        }
    }

    /// A never-written, zero-filled value of a string or aggregate type.
    fn zero_value(&mut self, ty: TypeId) -> Addr {
        let (size, _) = self.cx.layout.size(ty);
        Addr::abs(self.cx.alloc(size.max(2), 8))
    }
}
