//! A configuration's connections of a program instance,
//! `PROGRAM inst WITH T : Main(step := g_step, total => g_total);`: the
//! code the task runs in place of the program for that instance. Each
//! scan it stores the connected inputs (their values read in the
//! configuration's scope: globals, directly represented variables,
//! constants), runs the program on the instance, then stores the connected
//! outputs into their places, as a function block call passes its
//! arguments (IEC 61131-3 2.7.1; CODESYS and TwinCAT copy them the same
//! way around every cycle of the program).

use super::{Gen, Res, V};
use crate::cx::Cx;
use automat_ir::code::{Addr, Func, Inst, IntOp, RegClass};
use automat_sema::PouId;
use automat_syntax::ast::{Arg, ArgDir, Expr, ExprKind};

/// The code running program `pou` on its instance (`This`) between the
/// stores of `conns` (checked by the configuration's checker).
/// The function is named like the program: it is that program's code as
/// this instance runs it (views find a task's program by that name; the
/// program's own function comes first among the functions so named).
pub fn program(cx: &mut Cx, pou: PouId, conns: &[Arg]) -> Func {
    let name = match cx.model.pou(pou) {
        Some(p) => cx.interner.name(p.name).to_string(),
        None => "?".to_string(),
    };
    let mut g = Gen::new(cx, pou, &name, None);
    // A failed connection has its error in `cx.diags` already.
    let _ = g.connections(pou, conns);
    super::peep::tidy(&mut g.f);
    g.f
}

impl Gen<'_, '_> {
    fn connections(&mut self, pou: PouId, conns: &[Arg]) -> Res<()> {
        let model = self.cx.model;
        let p = model.pou(pou).ok_or(super::Failed)?;
        fn param<'e>(
            p: &automat_sema::model::Pou,
            a: &'e Arg,
        ) -> Option<(u32, automat_syntax::ast::Ident, &'e Expr)> {
            let name = a.name?;
            Some((p.vars.index(name.sym)?, name, a.value.as_ref()?))
        }
        for a in conns.iter().filter(|a| a.dir == ArgDir::In) {
            let Some((idx, _, value)) = param(p, a) else {
                continue;
            };
            // The raw input, as a caller writes it (an R_EDGE input's edge
            // is the program's prologue's to compute).
            let lv = self.raw_var_lv(idx, a.span)?;
            let v = self.outside(|g| g.expr(value, Some(lv.ty)))?;
            self.store(lv, v, a.span)?;
        }
        self.emit(Inst::Call {
            func: pou.0,
            this: Addr::this(0),
        });
        for a in conns.iter().filter(|a| a.dir != ArgDir::In) {
            let Some((_, name, target)) = param(p, a) else {
                continue;
            };
            let output = Expr {
                kind: ExprKind::Name(name),
                span: name.span,
            };
            let src = self.place(&output)?;
            let mut v = self.load(src);
            if a.dir == ArgDir::OutNot {
                if let V::I(r) = v.v {
                    let one = self.iconst(1);
                    let d = self.reg(RegClass::I64);
                    self.emit(Inst::Int {
                        op: IntOp::Xor,
                        dst: d,
                        a: r,
                        b: one,
                    });
                    v.v = V::I(d);
                }
            }
            let lv = self.outside(|g| g.place(target))?;
            let v = self.coerce(v, lv.ty, a.span)?;
            self.store(lv, v, a.span)?;
        }
        self.emit(Inst::Ret);
        Ok(())
    }

    /// Runs `f` with names read in the configuration's scope: a global,
    /// never a variable of the program named alike.
    fn outside<T>(&mut self, f: impl FnOnce(&mut Self) -> Res<T>) -> Res<T> {
        self.outside = true;
        let r = f(self);
        self.outside = false;
        r
    }
}
