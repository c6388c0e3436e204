//! Code for every non-control instruction, with the interpreter's exact
//! semantics (see the rules in `automat_ir::code`).
//!
//! # Bounds checks
//! `Abs` addresses are inside the image by the verifier, so they are used
//! unchecked. `This` and `Reg` addresses depend on run-time values: every
//! access through them is checked against the image length and faults like
//! the interpreter (`FaultKind::Function`, "load of .. outside the image").
//! `AddrOf` and `Call` compute offsets without access, as the interpreter
//! does. `Check`/`CheckDyn` are emitted exactly where the IR has them.

use crate::rt::{self, BuiltinCall};
use crate::translate::{mem, Tx};
use crate::JitError;
use automat_ir::code::{
    Addr, Base, Builtin, Cmp, FloatOp, Inst, IntOp, MemTy, RegClass, ShiftOp, StrFn, TimeFn,
};
use cranelift_codegen::ir::{
    condcodes::{FloatCC, IntCC},
    types, AbiParam, InstBuilder, MemFlagsData, Signature, Value,
};

fn int_cc(c: Cmp, signed: bool) -> IntCC {
    match (c, signed) {
        (Cmp::Eq, _) => IntCC::Equal,
        (Cmp::Ne, _) => IntCC::NotEqual,
        (Cmp::Lt, true) => IntCC::SignedLessThan,
        (Cmp::Le, true) => IntCC::SignedLessThanOrEqual,
        (Cmp::Gt, true) => IntCC::SignedGreaterThan,
        (Cmp::Ge, true) => IntCC::SignedGreaterThanOrEqual,
        (Cmp::Lt, false) => IntCC::UnsignedLessThan,
        (Cmp::Le, false) => IntCC::UnsignedLessThanOrEqual,
        (Cmp::Gt, false) => IntCC::UnsignedGreaterThan,
        (Cmp::Ge, false) => IntCC::UnsignedGreaterThanOrEqual,
    }
}

fn float_cc(c: Cmp) -> FloatCC {
    match c {
        Cmp::Eq => FloatCC::Equal,
        Cmp::Ne => FloatCC::NotEqual,
        Cmp::Lt => FloatCC::LessThan,
        Cmp::Le => FloatCC::LessThanOrEqual,
        Cmp::Gt => FloatCC::GreaterThan,
        Cmp::Ge => FloatCC::GreaterThanOrEqual,
    }
}

impl Tx<'_, '_> {
    /// The absolute image offset of `a` as the interpreter computes it
    /// (u32 wrapping), zero-extended to 64 bits.
    pub fn offset(&mut self, a: Addr) -> Value {
        match a.base {
            Base::Abs => self.iconst(a.offset as i64),
            // Inside the proved extent `this + offset` is below the image
            // length, a u32: the wrapping sum is the plain one.
            Base::This if self.this_safe && a.offset as u64 <= self.extent => {
                self.b.ins().iadd_imm_s(self.this, a.offset as i64)
            }
            Base::This => self.wrap32(self.this, a.offset),
            Base::Reg(r) => match self.get(r) {
                Ok(v) => self.wrap32(v, a.offset),
                Err(_) => self.iconst(0),
            },
        }
    }

    /// `(v as u32).wrapping_add(off)`, zero-extended: 32-bit arithmetic.
    fn wrap32(&mut self, v: Value, off: u32) -> Value {
        let n = self.b.ins().ireduce(types::I32, v);
        let s = self.b.ins().iadd_imm_s(n, off as i32 as i64);
        self.b.ins().uextend(types::I64, s)
    }

    /// A native pointer to `size` bytes at `a`, bounds-checked unless the
    /// address is absolute (verified).
    fn pointer(&mut self, a: Addr, size: u32, what: i64, ty: MemTy) -> Value {
        if a.base == Base::Abs {
            return self.b.ins().iadd_imm_s(self.image, a.offset as i64);
        }
        if let Some(p) = self.proved_pointer(a, size) {
            return p;
        }
        if a.base == Base::This && self.this_safe {
            // The entry check proved this + offset + size <= image length
            // (`translate.rs`), so the u32 sum does not wrap either.
            let at = self.b.ins().iadd_imm_s(self.this, a.offset as i64);
            return self.b.ins().iadd(self.image, at);
        }
        let at = self.offset(a);
        let end = self.b.ins().iadd_imm_s(at, size as i64);
        let out = self.b.ins().icmp(IntCC::UnsignedGreaterThan, end, self.len);
        let code = self.iconst(rt::mem_ty_code(ty));
        let zero = self.iconst(0);
        self.fault_if(out, rt::F_MEMORY, what, [at, code, zero]);
        self.b.ins().iadd(self.image, at)
    }

    pub(crate) fn load(&mut self, ty: MemTy, p: Value) -> Value {
        let fl = mem();
        let ins = self.b.ins();
        match ty {
            MemTy::I8 => ins.sload8(types::I64, fl, p, 0),
            MemTy::U8 => ins.uload8(types::I64, fl, p, 0),
            MemTy::I16 => ins.sload16(types::I64, fl, p, 0),
            MemTy::U16 => ins.uload16(types::I64, fl, p, 0),
            MemTy::I32 => ins.sload32(fl, p, 0),
            MemTy::U32 => ins.uload32(fl, p, 0),
            MemTy::I64 => ins.load(types::I64, fl, p, 0),
            MemTy::F32 => ins.load(types::F32, fl, p, 0),
            MemTy::F64 => ins.load(types::F64, fl, p, 0),
        }
    }

    fn store(&mut self, ty: MemTy, v: Value, p: Value) {
        let fl = mem();
        let ins = self.b.ins();
        match ty.size() {
            1 => ins.istore8(fl, v, p, 0),
            2 => ins.istore16(fl, v, p, 0),
            4 if ty != MemTy::F32 => ins.istore32(fl, v, p, 0),
            _ => ins.store(fl, v, p, 0),
        };
    }

    pub(crate) fn wrap(&mut self, v: Value, ty: MemTy) -> Value {
        let (narrow, signed) = match ty {
            MemTy::I8 => (types::I8, true),
            MemTy::U8 => (types::I8, false),
            MemTy::I16 => (types::I16, true),
            MemTy::U16 => (types::I16, false),
            MemTy::I32 => (types::I32, true),
            MemTy::U32 => (types::I32, false),
            _ => return v,
        };
        let n = self.b.ins().ireduce(narrow, v);
        if signed {
            self.b.ins().sextend(types::I64, n)
        } else {
            self.b.ins().uextend(types::I64, n)
        }
    }

    fn shift(&mut self, op: ShiftOp, width: u8, a: Value, n: Value) -> Value {
        let w = width as i64;
        let mask = if w >= 64 { -1 } else { (1i64 << w) - 1 };
        let x = if w >= 64 {
            a
        } else {
            self.b.ins().band_imm_s(a, mask)
        };
        let zero = self.iconst(0);
        let neg = self.b.ins().icmp_imm_s(IntCC::SignedLessThan, n, 0);
        let n = self.b.ins().select(neg, zero, n);
        match op {
            ShiftOp::Shl | ShiftOp::Shr if matches!(width, 8 | 16 | 32) => {
                // In the type's own width: the masks before and after the
                // shift are the reduce and the zero-extension, which the
                // machine does for free (no `and` with a 64-bit constant
                // around every DWORD shift). `n >= w` still gives 0.
                let narrow = match width {
                    8 => types::I8,
                    16 => types::I16,
                    _ => types::I32,
                };
                let xn = self.b.ins().ireduce(narrow, a);
                let r = if op == ShiftOp::Shl {
                    self.b.ins().ishl(xn, n)
                } else {
                    self.b.ins().ushr(xn, n)
                };
                let r = self.b.ins().uextend(types::I64, r);
                let big = self
                    .b
                    .ins()
                    .icmp_imm_s(IntCC::UnsignedGreaterThanOrEqual, n, w);
                self.b.ins().select(big, zero, r)
            }
            ShiftOp::Shl | ShiftOp::Shr => {
                let r = if op == ShiftOp::Shl {
                    self.b.ins().ishl(x, n)
                } else {
                    self.b.ins().ushr(x, n)
                };
                let big = self
                    .b
                    .ins()
                    .icmp_imm_s(IntCC::UnsignedGreaterThanOrEqual, n, w);
                let r = self.b.ins().select(big, zero, r);
                if w >= 64 {
                    r
                } else {
                    self.b.ins().band_imm_s(r, mask)
                }
            }
            ShiftOp::Rol | ShiftOp::Ror => {
                let narrow = match width {
                    1 => return x,
                    8 => types::I8,
                    16 => types::I16,
                    32 => types::I32,
                    _ => types::I64,
                };
                // The widths are powers of two: n mod w is a mask.
                let k = self.b.ins().band_imm_s(n, w - 1);
                let xn = if narrow == types::I64 {
                    x
                } else {
                    self.b.ins().ireduce(narrow, x)
                };
                let r = if op == ShiftOp::Rol {
                    self.b.ins().rotl(xn, k)
                } else {
                    self.b.ins().rotr(xn, k)
                };
                if narrow == types::I64 {
                    r
                } else {
                    self.b.ins().uextend(types::I64, r)
                }
            }
        }
    }

    fn bool64(&mut self, c: Value) -> Value {
        self.b.ins().uextend(types::I64, c)
    }

    /// Register bits as the interpreter keeps them (`u64` patterns).
    fn bits(&mut self, v: Value, class: RegClass) -> Value {
        let fl = MemFlagsData::new();
        match class {
            RegClass::I64 => v,
            RegClass::F32 => {
                let b = self.b.ins().bitcast(types::I32, fl, v);
                self.b.ins().uextend(types::I64, b)
            }
            RegClass::F64 => self.b.ins().bitcast(types::I64, fl, v),
        }
    }

    fn class(&self, r: u32) -> Result<RegClass, JitError> {
        self.f
            .regs
            .get(r as usize)
            .copied()
            .ok_or_else(|| JitError::Backend(format!("{}: no register r{r}", self.f.name)))
    }

    pub(crate) fn emit_plain(&mut self, inst: &Inst) -> Result<(), JitError> {
        match *inst {
            Inst::IConst { dst, value } => {
                let v = self.iconst(value);
                self.set(dst, v)?;
            }
            Inst::F32Const { dst, value } => {
                let v = self.b.ins().f32const(value);
                self.set(dst, v)?;
            }
            Inst::F64Const { dst, value } => {
                let v = self.b.ins().f64const(value);
                self.set(dst, v)?;
            }
            Inst::Mov { dst, src } => {
                let v = self.get(src)?;
                self.set(dst, v)?;
            }
            Inst::Load { dst, ty, addr } => {
                let p = self.pointer(addr, ty.size(), rt::M_LOAD, ty);
                let v = self.load(ty, p);
                self.set(dst, v)?;
            }
            Inst::Store { src, ty, addr } => {
                let p = self.pointer(addr, ty.size(), rt::M_STORE, ty);
                let v = self.get(src)?;
                self.store(ty, v, p);
            }
            Inst::LoadBit { dst, addr, bit } => {
                let p = self.pointer(addr, 1, rt::M_BIT_LOAD, MemTy::U8);
                let byte = self.load(MemTy::U8, p);
                let s = self.b.ins().ushr_imm_s(byte, bit as i64);
                let v = self.b.ins().band_imm_s(s, 1);
                self.set(dst, v)?;
            }
            Inst::StoreBit { src, addr, bit } => {
                let p = self.pointer(addr, 1, rt::M_BIT_STORE, MemTy::U8);
                let byte = self.load(MemTy::U8, p);
                let cleared = self.b.ins().band_imm_s(byte, !(1i64 << bit));
                let v = self.get(src)?;
                let one = self.b.ins().band_imm_s(v, 1);
                let on = self.b.ins().ishl_imm_s(one, bit as i64);
                let r = self.b.ins().bor(cleared, on);
                self.store(MemTy::U8, r, p);
            }
            Inst::AddrOf { dst, addr } => {
                let v = self.offset(addr);
                self.set(dst, v)?;
            }
            Inst::Copy { dst, src, len } => {
                let d = self.offset(dst);
                let s = self.offset(src);
                let n = self.iconst(len as i64);
                let func = self.iconst(self.index as i64 | (self.pc as i64) << 32);
                let call = self.b.ins().call(self.h.copy, &[self.ctx, func, d, s, n]);
                let st = self.result(call)?;
                self.propagate(st);
            }
            Inst::Int { op, dst, a, b } => {
                let (x, y) = (self.get(a)?, self.get(b)?);
                let ins = self.b.ins();
                let v = match op {
                    IntOp::Add => ins.iadd(x, y),
                    IntOp::Sub => ins.isub(x, y),
                    IntOp::Mul => ins.imul(x, y),
                    IntOp::And => ins.band(x, y),
                    IntOp::Or => ins.bor(x, y),
                    IntOp::Xor => ins.bxor(x, y),
                };
                self.set(dst, v)?;
            }
            Inst::Div {
                signed,
                dst,
                a,
                b,
                site,
            } => self.divide(true, signed, dst, a, b, site)?,
            Inst::Rem {
                signed,
                dst,
                a,
                b,
                site,
            } => self.divide(false, signed, dst, a, b, site)?,
            Inst::Neg { dst, src } => {
                let v = self.get(src)?;
                let r = self.b.ins().ineg(v);
                self.set(dst, r)?;
            }
            Inst::Not { dst, src } => {
                let v = self.get(src)?;
                let r = self.b.ins().bnot(v);
                self.set(dst, r)?;
            }
            Inst::Wrap { dst, src, ty } => {
                let v = self.get(src)?;
                let r = self.wrap(v, ty);
                self.set(dst, r)?;
            }
            Inst::Shift {
                op,
                width,
                dst,
                a,
                n,
            } => {
                let (x, k) = (self.get(a)?, self.get(n)?);
                let r = self.shift(op, width, x, k);
                self.set(dst, r)?;
            }
            Inst::ICmp {
                cmp,
                signed,
                dst,
                a,
                b,
            } => {
                let (x, y) = (self.get(a)?, self.get(b)?);
                let c = self.b.ins().icmp(int_cc(cmp, signed), x, y);
                let r = self.bool64(c);
                self.set(dst, r)?;
            }
            Inst::Float { op, dst, a, b, .. } => {
                let (x, y) = (self.get(a)?, self.get(b)?);
                let ins = self.b.ins();
                let r = match op {
                    FloatOp::Add => ins.fadd(x, y),
                    FloatOp::Sub => ins.fsub(x, y),
                    FloatOp::Mul => ins.fmul(x, y),
                    FloatOp::Div => ins.fdiv(x, y),
                };
                self.set(dst, r)?;
            }
            Inst::FCmp { cmp, dst, a, b, .. } => {
                let (x, y) = (self.get(a)?, self.get(b)?);
                let c = self.b.ins().fcmp(float_cc(cmp), x, y);
                let r = self.bool64(c);
                self.set(dst, r)?;
            }
            Inst::FResize { to_wide, dst, src } => {
                let v = self.get(src)?;
                let r = if to_wide {
                    self.b.ins().fpromote(types::F64, v)
                } else {
                    self.b.ins().fdemote(types::F32, v)
                };
                self.set(dst, r)?;
            }
            Inst::Check {
                kind,
                val,
                lo,
                hi,
                site,
            } => {
                let v = self.get(val)?;
                // One unsigned compare: lo <= v <= hi  <=>  v - lo <= hi - lo.
                let span = (hi as i128 - lo as i128) as u64 as i64;
                let d = self.b.ins().iadd_imm_s(v, lo.wrapping_neg());
                let out = self.b.ins().icmp_imm_s(IntCC::UnsignedGreaterThan, d, span);
                let (l, h) = (self.iconst(lo), self.iconst(hi));
                self.fault_if(out, rt::check_code(kind), site as i64, [v, l, h]);
            }
            Inst::CheckDyn {
                kind,
                val,
                lo,
                hi,
                site,
            } => {
                let (v, l, h) = (self.get(val)?, self.get(lo)?, self.get(hi)?);
                let below = self.b.ins().icmp(IntCC::SignedLessThan, v, l);
                let above = self.b.ins().icmp(IntCC::SignedGreaterThan, v, h);
                let out = self.b.ins().bor(below, above);
                self.fault_if(out, rt::check_code(kind), site as i64, [v, l, h]);
            }
            Inst::Now { dst } => {
                let v = self.b.ins().load(types::I64, mem(), self.ctx, rt::OFF_NOW);
                self.set(dst, v)?;
            }
            Inst::Builtin {
                op,
                dst,
                first,
                count,
                site,
            } => self.builtin(op, dst, first, count, site)?,
            Inst::Jump { .. } | Inst::Branch { .. } | Inst::Call { .. } | Inst::Ret => {
                return Err(JitError::Backend("control instruction in emit".into()))
            }
        }
        Ok(())
    }

    fn result(&mut self, call: cranelift_codegen::ir::Inst) -> Result<Value, JitError> {
        self.b
            .inst_results(call)
            .first()
            .copied()
            .ok_or_else(|| JitError::Backend("call result".into()))
    }

    fn divide(
        &mut self,
        div: bool,
        signed: bool,
        dst: u32,
        a: u32,
        b: u32,
        site: u32,
    ) -> Result<(), JitError> {
        let (x, y) = (self.get(a)?, self.get(b)?);
        let zero = self.b.ins().icmp_imm_s(IntCC::Equal, y, 0);
        let flag = self.iconst(div as i64);
        let z = self.iconst(0);
        self.fault_if(zero, rt::F_DIV, site as i64, [x, flag, z]);
        let r = if signed {
            // MIN / -1 wraps (and MIN MOD -1 is 0) where the machine traps:
            // divide by 1 instead and negate.
            let m1 = self.b.ins().icmp_imm_s(IntCC::Equal, y, -1);
            let one = self.iconst(1);
            let safe = self.b.ins().select(m1, one, y);
            if div {
                let q = self.b.ins().sdiv(x, safe);
                let n = self.b.ins().ineg(x);
                self.b.ins().select(m1, n, q)
            } else {
                self.b.ins().srem(x, safe)
            }
        } else if div {
            self.b.ins().udiv(x, y)
        } else {
            self.b.ins().urem(x, y)
        };
        self.set(dst, r)
    }

    fn builtin(
        &mut self,
        op: Builtin,
        dst: Option<u32>,
        first: u32,
        count: u16,
        site: u32,
    ) -> Result<(), JitError> {
        let args = self.f.builtin_args(first, count).to_vec();
        if let (Builtin::Time(t @ (TimeFn::AddTime | TimeFn::SubTime)), Some(d), [a, b]) =
            (op, dst, args.as_slice())
        {
            return self.time_add_sub(t == TimeFn::AddTime, d, *a, *b, op, first, count, site);
        }
        if let (Builtin::Convert(from, to), Some(d), [a]) = (op, dst, args.as_slice()) {
            if self.convert_inline(from, to, d, *a)? {
                return Ok(());
            }
        }
        if automat_engine::shared::str_in_place(op, args.len()) {
            return self.str_in_place(op, dst, first, count, site);
        }
        self.builtin_call(op, dst, first, count, site)
    }

    /// A string builtin worked in place: the operand bits go to
    /// `rt::jit_str` in machine registers; only when it declines (-1: a
    /// range outside the image, a negative length, overlapping operands)
    /// does a cold block take the general path, which makes the same
    /// bytes or the fault.
    fn str_in_place(
        &mut self,
        op: Builtin,
        dst: Option<u32>,
        first: u32,
        count: u16,
        site: u32,
    ) -> Result<(), JitError> {
        if let (Builtin::Str(StrFn::Len, _), Some(d)) = (op, dst) {
            if self.class(d)? != RegClass::I64 {
                return self.builtin_call(op, dst, first, count, site);
            }
        }
        let args = self.f.builtin_args(first, count).to_vec();
        // The general path below registers this call under this number.
        let index = self.builtins.len() as i64;
        let mut vals = vec![self.ctx, self.iconst(index)];
        for i in 0..4 {
            let v = match args.get(i) {
                Some(&r) => {
                    let class = self.class(r)?;
                    let v = self.get(r)?;
                    self.bits(v, class)
                }
                None => self.iconst(0),
            };
            vals.push(v);
        }
        let mut sig = Signature::new(self.h.target.default_call_conv);
        sig.params.push(AbiParam::new(self.h.ptr));
        sig.params.extend([AbiParam::new(types::I64); 5]);
        sig.returns.push(AbiParam::new(types::I64));
        let sig = self.b.import_signature(sig);
        let helper = self
            .b
            .ins()
            .iconst(self.h.ptr, rt::jit_str as *const u8 as usize as i64);
        let call = self.b.ins().call_indirect(sig, helper, &vals);
        let r = self.result(call)?;
        // LEN's length (as the interpreter sets it); the other functions
        // write the image only.
        if let (Builtin::Str(StrFn::Len, _), Some(d)) = (op, dst) {
            self.set(d, r)?;
        }
        let slow = self.b.create_block();
        let cont = self.b.create_block();
        self.b.set_cold_block(slow);
        let declined = self.b.ins().icmp_imm_s(IntCC::SignedLessThan, r, 0);
        self.b.ins().brif(declined, slow, &[], cont, &[]);
        self.b.switch_to_block(slow);
        self.builtin_call(op, dst, first, count, site)?;
        self.b.ins().jump(cont, &[]);
        self.b.switch_to_block(cont);
        if self.builtins.get(index as usize).map(|c| c.op) != Some(op) {
            return Err(JitError::Backend("string builtin numbering".into()));
        }
        Ok(())
    }

    /// The numeric `*_TO_*` conversions that cannot fault, inline, with
    /// the shared implementation's exact results (`automat_iec::convert`
    /// on the register as `automat_engine::builtins::to_value` reads it):
    /// integers and BOOL to REAL/LREAL, REAL <-> LREAL, integer to integer
    /// (wrap), to and from BOOL, and REAL/LREAL to an integer (halves to
    /// even, saturating, NaN 0). Returns `false` for every other pair,
    /// which calls the helper. The register classes are checked so a pair
    /// this does not expect also takes the helper.
    fn convert_inline(
        &mut self,
        from: automat_iec::Elementary,
        to: automat_iec::Elementary,
        dst: u32,
        src: u32,
    ) -> Result<bool, JitError> {
        use automat_iec::Elementary as E;
        let class_of = |e: E| match e {
            E::Real => RegClass::F32,
            E::Lreal => RegClass::F64,
            _ => RegClass::I64,
        };
        let numeric = |e: E| e == E::Bool || e.is_integral() || e.is_real();
        if !numeric(from)
            || !(to == E::Bool || to.is_int() || to.is_bit_string() || to.is_real())
            || self.class(src)? != class_of(from)
            || self.class(dst)? != class_of(to)
        {
            return Ok(false);
        }
        let x = self.get(src)?;
        let real_ty = |e: E| if e == E::Real { types::F32 } else { types::F64 };
        let v = match (from, to) {
            (f, t) if f == t => x,
            // `Bool`: the register's low bit (`to_value`).
            (E::Bool, t) => {
                let one = self.b.ins().band_imm_u(x, 1);
                if t.is_real() {
                    self.b.ins().fcvt_from_uint(real_ty(t), one)
                } else {
                    one
                }
            }
            (f, E::Bool) => {
                let c = if f.is_real() {
                    let z = if f == E::Real {
                        self.b.ins().f32const(0.0)
                    } else {
                        self.b.ins().f64const(0.0)
                    };
                    // NaN is not 0: TRUE.
                    self.b.ins().fcmp(FloatCC::NotEqual, x, z)
                } else {
                    self.b.ins().icmp_imm_s(IntCC::NotEqual, x, 0)
                };
                self.bool64(c)
            }
            (E::Real, E::Lreal) => self.b.ins().fpromote(types::F64, x),
            (E::Lreal, E::Real) => self.b.ins().fdemote(types::F32, x),
            // One rounding straight from the 64-bit integer (the value
            // `to_value` reads: sign-extended for signed types, the bits
            // as they are for unsigned ones and bit strings).
            (f, t) if t.is_real() && f.is_signed_int() => {
                self.b.ins().fcvt_from_sint(real_ty(t), x)
            }
            (f, t) if t.is_real() && (f.is_unsigned_int() || f.is_bit_string()) => {
                self.b.ins().fcvt_from_uint(real_ty(t), x)
            }
            (f, t) if f.is_integral() && (t.is_int() || t.is_bit_string()) => self.wrap_to(x, t),
            (f, t) if f.is_real() && t.is_int() => {
                let w = if f == E::Real {
                    self.b.ins().fpromote(types::F64, x)
                } else {
                    x
                };
                let r = self.b.ins().nearest(w);
                let Some(bits) = t.bit_width() else {
                    return Ok(false);
                };
                if t.is_signed_int() {
                    // Saturating, NaN 0; then clamped to the type.
                    let v = self.b.ins().fcvt_to_sint_sat(types::I64, r);
                    if bits == 64 {
                        v
                    } else {
                        let hi = self.iconst((1i64 << (bits - 1)) - 1);
                        let lo = self.iconst(-(1i64 << (bits - 1)));
                        let v = self.b.ins().smin(v, hi);
                        self.b.ins().smax(v, lo)
                    }
                } else {
                    let v = self.b.ins().fcvt_to_uint_sat(types::I64, r);
                    if bits == 64 {
                        v
                    } else {
                        let hi = self.iconst((1i64 << bits) - 1);
                        self.b.ins().umin(v, hi)
                    }
                }
            }
            _ => return Ok(false),
        };
        self.set(dst, v)?;
        Ok(true)
    }

    /// The low bits of `x` for integer or bit-string type `t`, sign-extended
    /// for signed integers, zero-extended otherwise (`wrap_int`).
    fn wrap_to(&mut self, x: Value, t: automat_iec::Elementary) -> Value {
        let narrow = match t.bit_width() {
            Some(8) => types::I8,
            Some(16) => types::I16,
            Some(32) => types::I32,
            _ => return x,
        };
        let n = self.b.ins().ireduce(narrow, x);
        if t.is_signed_int() {
            self.b.ins().sextend(types::I64, n)
        } else {
            self.b.ins().uextend(types::I64, n)
        }
    }

    /// ADD_TIME / SUB_TIME (TIME `+`/`-`, the timers' elapsed time): the
    /// sum inline; only when it overflows does the shared implementation
    /// run, which then raises its fault.
    #[allow(clippy::too_many_arguments)]
    fn time_add_sub(
        &mut self,
        add: bool,
        dst: u32,
        a: u32,
        b: u32,
        op: Builtin,
        first: u32,
        count: u16,
        site: u32,
    ) -> Result<(), JitError> {
        let (x, y) = (self.get(a)?, self.get(b)?);
        let (r, over) = if add {
            self.b.ins().sadd_overflow(x, y)
        } else {
            self.b.ins().ssub_overflow(x, y)
        };
        self.set(dst, r)?;
        let slow = self.b.create_block();
        let cont = self.b.create_block();
        self.b.set_cold_block(slow);
        self.b.ins().brif(over, slow, &[], cont, &[]);
        self.b.switch_to_block(slow);
        self.builtin_call(op, Some(dst), first, count, site)?;
        self.b.ins().jump(cont, &[]);
        self.b.switch_to_block(cont);
        Ok(())
    }

    fn builtin_call(
        &mut self,
        op: Builtin,
        dst: Option<u32>,
        first: u32,
        count: u16,
        site: u32,
    ) -> Result<(), JitError> {
        let slots = self
            .slots
            .ok_or_else(|| JitError::Backend("builtin slots".into()))?;
        let args = self.f.builtin_args(first, count).to_vec();
        if args.len() != count as usize {
            return Err(JitError::Backend("builtin arguments".into()));
        }
        for (i, r) in args.iter().enumerate() {
            let class = self.class(*r)?;
            let v = self.get(*r)?;
            let bits = self.bits(v, class);
            self.b
                .ins()
                .stack_store(self.h.ptr, bits, slots, i as i32 * 8);
        }
        let index = self.builtins.len() as i64;
        self.builtins.push(BuiltinCall {
            op,
            func: self.index,
            site,
            has_dst: dst.is_some(),
            args: (0..count as u32).collect(),
        });
        let idx = self.iconst(index);
        let p = self.b.ins().stack_addr(self.h.ptr, slots, 0);
        let call = self.b.ins().call(self.h.builtin, &[self.ctx, idx, p]);
        let st = self.result(call)?;
        self.propagate(st);
        if let Some(d) = dst {
            let ty = crate::translate::class_type(self.class(d)?);
            let v = self
                .b
                .ins()
                .stack_load(self.h.ptr, ty, slots, count as i32 * 8);
            self.set(d, v)?;
        }
        Ok(())
    }
}
