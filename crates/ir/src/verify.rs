//! The verifier: checks that a [`Func`] obeys the rules of [`crate::code`]
//! (register classes consistent, jump targets and callees valid, absolute
//! addresses inside the image, sites known, no falling off the end). Run in
//! debug builds and tests; a failure is a compiler bug, never a user error.

use crate::code::{Addr, Base, Builtin, Func, Inst, MemTy, Reg, RegClass};

/// What is wrong, at which instruction.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct VerifyError {
    pub func: String,
    pub at: usize,
    pub message: String,
}

impl std::fmt::Display for VerifyError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} @{}: {}", self.func, self.at, self.message)
    }
}

/// The sizes a function is checked against.
#[derive(Clone, Copy, Debug)]
pub struct Limits {
    pub image_size: u32,
    pub funcs: u32,
    pub sites: u32,
}

struct V<'a> {
    f: &'a Func,
    lim: Limits,
    at: usize,
}

impl V<'_> {
    fn err(&self, message: String) -> VerifyError {
        VerifyError {
            func: self.f.name.clone(),
            at: self.at,
            message,
        }
    }

    fn reg(&self, r: Reg, want: RegClass) -> Result<(), VerifyError> {
        match self.f.regs.get(r as usize) {
            Some(c) if *c == want => Ok(()),
            Some(c) => Err(self.err(format!("r{r} is {c:?}, expected {want:?}"))),
            None => Err(self.err(format!("r{r} is not a register"))),
        }
    }

    fn float(&self, r: Reg, wide: bool) -> Result<(), VerifyError> {
        self.reg(r, if wide { RegClass::F64 } else { RegClass::F32 })
    }

    fn addr(&self, a: Addr, size: u32) -> Result<(), VerifyError> {
        match a.base {
            Base::Abs => {
                if a.offset as u64 + size as u64 > self.lim.image_size as u64 {
                    return Err(self.err(format!(
                        "address {}+{size} outside the image of {} bytes",
                        a.offset, self.lim.image_size
                    )));
                }
                Ok(())
            }
            Base::This => Ok(()),
            Base::Reg(r) => self.reg(r, RegClass::I64),
        }
    }

    fn target(&self, t: u32) -> Result<(), VerifyError> {
        if (t as usize) < self.f.code.len() {
            Ok(())
        } else {
            Err(self.err(format!("jump target {t} outside the code")))
        }
    }

    fn site(&self, s: u32) -> Result<(), VerifyError> {
        if s < self.lim.sites {
            Ok(())
        } else {
            Err(self.err(format!("site {s} unknown")))
        }
    }

    fn int_mem(&self, ty: MemTy) -> Result<(), VerifyError> {
        if ty.class() == RegClass::I64 {
            Ok(())
        } else {
            Err(self.err(format!("{ty:?} is not an integer type")))
        }
    }

    fn inst(&self, inst: &Inst) -> Result<(), VerifyError> {
        use RegClass::*;
        match *inst {
            Inst::IConst { dst, .. } | Inst::Now { dst } => self.reg(dst, I64),
            Inst::F32Const { dst, .. } => self.reg(dst, F32),
            Inst::F64Const { dst, .. } => self.reg(dst, F64),
            Inst::Mov { dst, src } => {
                let c = *self
                    .f
                    .regs
                    .get(src as usize)
                    .ok_or_else(|| self.err(format!("r{src} is not a register")))?;
                self.reg(dst, c)
            }
            Inst::Load { dst, ty, addr } => {
                self.addr(addr, ty.size())?;
                self.reg(dst, ty.class())
            }
            Inst::Store { src, ty, addr } => {
                self.addr(addr, ty.size())?;
                self.reg(src, ty.class())
            }
            Inst::LoadBit { dst: r, addr, bit } | Inst::StoreBit { src: r, addr, bit } => {
                if bit > 7 {
                    return Err(self.err(format!("bit {bit} of a byte")));
                }
                self.addr(addr, 1)?;
                self.reg(r, I64)
            }
            Inst::AddrOf { dst, addr } => {
                self.addr(addr, 0)?;
                self.reg(dst, I64)
            }
            Inst::Copy { dst, src, len } => {
                self.addr(dst, len)?;
                self.addr(src, len)
            }
            Inst::Int { dst, a, b, .. } | Inst::ICmp { dst, a, b, .. } => {
                self.reg(dst, I64)?;
                self.reg(a, I64)?;
                self.reg(b, I64)
            }
            Inst::Shift {
                width, dst, a, n, ..
            } => {
                if !matches!(width, 1 | 8 | 16 | 32 | 64) {
                    return Err(self.err(format!("shift width {width}")));
                }
                self.reg(dst, I64)?;
                self.reg(a, I64)?;
                self.reg(n, I64)
            }
            Inst::Div {
                dst, a, b, site, ..
            }
            | Inst::Rem {
                dst, a, b, site, ..
            } => {
                self.site(site)?;
                self.reg(dst, I64)?;
                self.reg(a, I64)?;
                self.reg(b, I64)
            }
            Inst::Neg { dst, src } | Inst::Not { dst, src } => {
                self.reg(dst, I64)?;
                self.reg(src, I64)
            }
            Inst::Wrap { dst, src, ty } => {
                self.int_mem(ty)?;
                self.reg(dst, I64)?;
                self.reg(src, I64)
            }
            Inst::Float {
                wide, dst, a, b, ..
            } => {
                self.float(dst, wide)?;
                self.float(a, wide)?;
                self.float(b, wide)
            }
            Inst::FCmp {
                wide, dst, a, b, ..
            } => {
                self.reg(dst, I64)?;
                self.float(a, wide)?;
                self.float(b, wide)
            }
            Inst::FResize { to_wide, dst, src } => {
                self.float(dst, to_wide)?;
                self.float(src, !to_wide)
            }
            Inst::Check {
                val, lo, hi, site, ..
            } => {
                if lo > hi {
                    return Err(self.err(format!("empty check range {lo}..{hi}")));
                }
                self.site(site)?;
                self.reg(val, I64)
            }
            Inst::CheckDyn {
                val, lo, hi, site, ..
            } => {
                self.site(site)?;
                self.reg(val, I64)?;
                self.reg(lo, I64)?;
                self.reg(hi, I64)
            }
            Inst::Builtin {
                op,
                dst,
                first,
                count,
                site,
            } => {
                self.site(site)?;
                if first as usize + count as usize > self.f.args.len() {
                    return Err(self.err("builtin arguments outside the list".into()));
                }
                for &r in self.f.builtin_args(first, count) {
                    if self.f.regs.get(r as usize).is_none() {
                        return Err(self.err(format!("r{r} is not a register")));
                    }
                }
                if let (
                    Some(d),
                    Builtin::Math(_, wide)
                    | Builtin::Pow(wide)
                    | Builtin::PowInt(wide)
                    | Builtin::Atan2(wide),
                ) = (dst, op)
                {
                    self.float(d, wide)?;
                }
                if let Some(d) = dst {
                    if self.f.regs.get(d as usize).is_none() {
                        return Err(self.err(format!("r{d} is not a register")));
                    }
                }
                Ok(())
            }
            Inst::Jump { target } => self.target(target),
            Inst::Branch { cond, then, els } => {
                self.reg(cond, I64)?;
                self.target(then)?;
                self.target(els)
            }
            Inst::Call { func, this } => {
                if func >= self.lim.funcs {
                    return Err(self.err(format!("call of unknown function {func}")));
                }
                self.addr(this, 0)
            }
            Inst::Ret => Ok(()),
        }
    }
}

/// Checks one function against the program's sizes.
pub fn verify(f: &Func, lim: Limits) -> Result<(), VerifyError> {
    let mut v = V { f, lim, at: 0 };
    for (i, inst) in f.code.iter().enumerate() {
        v.at = i;
        v.inst(inst)?;
    }
    for &(_, site) in &f.stmt_sites {
        v.site(site)?;
    }
    match f.code.last() {
        Some(Inst::Ret | Inst::Jump { .. }) => Ok(()),
        _ => Err(v.err("code does not end with Ret or Jump".into())),
    }
}
