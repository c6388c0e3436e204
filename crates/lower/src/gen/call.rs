//! Calls of functions and function blocks: the caller stores the inputs
//! into the callee's frame (functions) or instance (function blocks),
//! emits `Call`, then reads the outputs and the result. Arguments are
//! evaluated before any is stored, so a nested call of the same function
//! cannot overwrite a parameter already stored.

use super::{Failed, Gen, Lv, Res, Shape, Val, V};
use crate::layout::Slot;
use automat_ir::code::{Addr, Base, Inst, MemTy};
use automat_sema::model::Section;
use automat_sema::types::{TypeId, TypeKind};
use automat_sema::PouId;
use automat_syntax::ast::{Arg, ArgDir, Expr, ExprKind, PouKind};

/// What is bound to one parameter.
enum Bound {
    /// An input value, evaluated.
    In(Val),
    /// The address of a VAR_IN_OUT argument, its type and (for an
    /// `ARRAY[*]` argument) its bounds descriptor.
    Ref(u32, TypeId, Option<Addr>),
}

impl Gen<'_, '_> {
    pub fn call(
        &mut self,
        callee: &Expr,
        args: &[Arg],
        e: &Expr,
        want: Option<TypeId>,
    ) -> Res<Val> {
        let (c, rest) = self.split_en(args);
        let args = rest.as_slice();
        // An FB instance (a variable or a member).
        if let Ok(lv) = self.fb_place(callee) {
            if let TypeKind::Fb { pou, .. } = self.kind(lv.ty) {
                let pou = *pou;
                let hidden = self
                    .cx
                    .layout
                    .pou(pou)
                    .eno
                    .map(|off| super::expr::add(lv.addr, off));
                return self.with_en(&c, hidden, |g| {
                    g.pou_call(pou, lv.addr, args, e, false)?;
                    let eno = g.declared_eno(pou, lv.addr);
                    Ok((
                        Val {
                            v: V::I(g.iconst(0)),
                            ty: TypeId::BOOL,
                        },
                        eno,
                    ))
                });
            }
        }
        let ExprKind::Name(id) = &callee.kind else {
            return Err(self.error(callee.span, "this call is not supported".into()));
        };
        if let Some((pid, p)) = self.cx.model.pou_named(id.sym) {
            if p.kind == PouKind::Function {
                let frame = self
                    .cx
                    .frames
                    .get(pid.0 as usize)
                    .copied()
                    .flatten()
                    .ok_or(Failed)?;
                return self.with_en(&c, None, |g| {
                    g.pou_call(pid, Addr::abs(frame), args, e, true)?;
                    let eno = g.declared_eno(pid, Addr::abs(frame));
                    Ok((g.result(pid, frame, e)?, eno))
                });
            }
        }
        let name = self.cx.interner.name(id.sym).to_string();
        match automat_sema::stdlib::lookup(&name) {
            Some(sig) => self.with_en(&c, None, |g| Ok((g.std_call(&sig, args, e, want)?, None))),
            None => Err(self.error(callee.span, format!("cannot call {name}"))),
        }
    }

    /// The callee's own ENO output after a call, when it declares one.
    fn declared_eno(&mut self, pou: PouId, base: Addr) -> Option<u32> {
        let p = self.cx.model.pou(pou)?;
        let idx = p.vars.index(self.cx.model.syms.eno)?;
        let var = p.vars.vars.get(idx as usize)?;
        let Some(Slot::Rel(off)) = self.cx.layout.pou(pou).slots.get(idx as usize).copied() else {
            return None;
        };
        let v = self.load(Lv {
            addr: super::expr::add(base, off),
            bit: None,
            ty: var.ty,
        });
        match v.v {
            V::I(r) => Some(r),
            _ => None,
        }
    }

    /// The place of a callee that is a variable (without reporting errors).
    fn fb_place(&mut self, callee: &Expr) -> Res<Lv> {
        let model = self.cx.model;
        match &callee.kind {
            ExprKind::Name(id) => {
                let is_var = model
                    .pou(self.pou)
                    .is_some_and(|p| p.vars.index(id.sym).is_some())
                    || self.cx.globals.contains_key(&id.sym);
                if !is_var {
                    return Err(Failed);
                }
                self.place(callee)
            }
            ExprKind::Member { .. } | ExprKind::Index { .. } | ExprKind::Deref(_) => {
                self.place(callee)
            }
            _ => Err(Failed),
        }
    }

    /// Stores the arguments, calls, copies the outputs back.
    fn pou_call(
        &mut self,
        pou: PouId,
        base: Addr,
        args: &[Arg],
        e: &Expr,
        function: bool,
    ) -> Res<()> {
        let model = self.cx.model;
        let p = model.pou(pou).ok_or(Failed)?;
        let slots = self.cx.layout.pou(pou).slots;
        let params: Vec<u32> = p.params().map(|(i, _)| i).collect();
        let en = model.syms.en;
        let eno = model.syms.eno;
        // Resolve each argument to a parameter index.
        let mut inputs: Vec<(u32, Bound)> = Vec::new();
        let mut outputs: Vec<(u32, &Arg)> = Vec::new();
        for (k, a) in args.iter().enumerate() {
            if a.name.is_some_and(|n| n.sym == en || n.sym == eno) {
                // Handled by `with_en`; only a declared ENO output gets here.
                continue;
            }
            let idx = match a.name {
                // CODESYS spells the counters' R as RESET.
                Some(n)
                    if n.sym == model.syms.reset && p.builtin && p.vars.index(n.sym).is_none() =>
                {
                    p.vars.index(model.syms.r)
                }
                Some(n) => p.vars.index(n.sym),
                None => params.get(k).copied(),
            };
            let Some(idx) = idx else {
                return Err(self.error(a.span, "argument does not match a parameter".into()));
            };
            let var = p.vars.vars.get(idx as usize).ok_or(Failed)?;
            match (a.dir, var.section) {
                (ArgDir::In, Section::Input) => {
                    let Some(v) = &a.value else { continue };
                    let val = self.expr(v, Some(var.ty))?;
                    inputs.push((idx, Bound::In(val)));
                }
                (ArgDir::In, Section::InOut) => {
                    let Some(v) = &a.value else { continue };
                    let lv = self.place(v)?;
                    let r = self.addr_reg(lv.addr);
                    let desc = match lv.addr.base {
                        Base::Reg(x) if lv.addr.offset == 0 => self.star.get(&x).copied(),
                        _ => None,
                    };
                    inputs.push((idx, Bound::Ref(r, lv.ty, desc)));
                }
                (ArgDir::Out | ArgDir::OutNot, Section::Output) | (ArgDir::In, Section::Output) => {
                    outputs.push((idx, a));
                }
                _ => {
                    return Err(self.error(
                        a.span,
                        "argument direction does not match the parameter".into(),
                    ))
                }
            }
        }
        // Inputs of a function not given take their initial value.
        if function {
            let tpl = self
                .cx
                .templates
                .get(pou.0 as usize)
                .copied()
                .flatten()
                .ok_or(Failed)?;
            for &i in &params {
                let var = p.vars.vars.get(i as usize).ok_or(Failed)?;
                if var.section == Section::Input && !inputs.iter().any(|(j, _)| *j == i) {
                    if let Some(Slot::Rel(off)) = slots.get(i as usize) {
                        let (len, _) = self.cx.layout.size(var.ty);
                        self.emit(Inst::Copy {
                            dst: super::expr::add(base, *off),
                            src: Addr::abs(tpl + off),
                            len,
                        });
                    }
                }
            }
        }
        for (idx, b) in inputs {
            let var = p.vars.vars.get(idx as usize).ok_or(Failed)?;
            let Some(Slot::Rel(off)) = slots.get(idx as usize).copied() else {
                return Err(self.error(e.span, "located parameters are not supported".into()));
            };
            let at = super::expr::add(base, off);
            match b {
                Bound::In(v) => self.store(
                    Lv {
                        addr: at,
                        bit: None,
                        ty: var.ty,
                    },
                    v,
                    e.span,
                )?,
                Bound::Ref(r, arg_ty, desc) => {
                    self.emit(Inst::Store {
                        src: r,
                        ty: MemTy::U32,
                        addr: at,
                    });
                    if let Some(n) = self.cx.layout.star_rank(var.ty) {
                        self.pass_bounds(super::expr::add(at, 4), n, arg_ty, desc);
                    }
                }
            }
        }
        self.emit(Inst::Call {
            func: pou.0,
            this: base,
        });
        for (idx, a) in outputs {
            let var = p.vars.vars.get(idx as usize).ok_or(Failed)?;
            let Some(target) = &a.value else { continue };
            let src = match slots.get(idx as usize).copied() {
                Some(Slot::Rel(off)) => Lv {
                    addr: super::expr::add(base, off),
                    bit: None,
                    ty: var.ty,
                },
                Some(Slot::Located(off, bit)) => Lv {
                    addr: Addr::abs(off),
                    bit,
                    ty: var.ty,
                },
                _ => return Err(Failed),
            };
            let mut v = self.load(src);
            if a.dir == ArgDir::OutNot {
                if let V::I(r) = v.v {
                    let one = self.iconst(1);
                    let d = self.reg(automat_ir::code::RegClass::I64);
                    self.emit(Inst::Int {
                        op: automat_ir::code::IntOp::Xor,
                        dst: d,
                        a: r,
                        b: one,
                    });
                    v.v = V::I(d);
                }
            }
            let lv = self.place(target)?;
            let v = self.coerce(v, lv.ty, a.span)?;
            self.store(lv, v, a.span)?;
        }
        Ok(())
    }

    /// A value that later code cannot overwrite: strings and aggregates
    /// living in a callee's frame are copied to a temporary.
    pub fn stabilise(&mut self, v: Val) -> Res<Val> {
        let V::M(src) = v.v else { return Ok(v) };
        match self.shape(v.ty) {
            Shape::Str { wide, cap } => {
                let t = self.temp_str(wide, cap);
                let lv = Lv {
                    addr: t,
                    bit: None,
                    ty: v.ty,
                };
                self.store(lv, v, automat_base::Span::default())?;
                Ok(Val {
                    v: V::M(t),
                    ty: v.ty,
                })
            }
            _ => {
                let (size, _) = self.cx.layout.size(v.ty);
                let t = self.temp(size);
                self.emit(Inst::Copy {
                    dst: t,
                    src,
                    len: size,
                });
                Ok(Val {
                    v: V::M(t),
                    ty: v.ty,
                })
            }
        }
    }

    /// The result of a function just called.
    fn result(&mut self, pou: PouId, frame: u32, e: &Expr) -> Res<Val> {
        let p = self.cx.model.pou(pou).ok_or(Failed)?;
        let Some(ret_ty) = p.return_type else {
            return Ok(Val {
                v: V::I(self.iconst(0)),
                ty: TypeId::BOOL,
            });
        };
        let idx = p
            .vars
            .vars
            .iter()
            .position(|v| v.section == Section::Return)
            .ok_or(Failed)?;
        let Some(Slot::Rel(off)) = self.cx.layout.pou(pou).slots.get(idx).copied() else {
            return Err(self.error(e.span, "function result has no slot".into()));
        };
        let v = self.load(Lv {
            addr: Addr::abs(frame + off),
            bit: None,
            ty: ret_ty,
        });
        self.stabilise(v)
    }

    /// Fills the bounds of an `ARRAY[*]` parameter from the argument: its
    /// declared bounds, or the bounds it was itself passed.
    fn pass_bounds(&mut self, at: Addr, n: u32, arg_ty: TypeId, desc: Option<Addr>) {
        if let Some(d) = desc {
            self.emit(Inst::Copy {
                dst: at,
                src: super::expr::add(d, 4),
                len: 8 * n,
            });
            return;
        }
        let TypeKind::Array { dims, .. } = self.kind(arg_ty) else {
            return;
        };
        let bounds = self.cx.layout.dims(dims);
        for (k, (lo, hi)) in bounds.into_iter().take(n as usize).enumerate() {
            for (j, v) in [lo, hi].into_iter().enumerate() {
                let r = self.iconst(v);
                self.emit(Inst::Store {
                    src: r,
                    ty: MemTy::I32,
                    addr: super::expr::add(at, 8 * k as u32 + 4 * j as u32),
                });
            }
        }
    }
}
