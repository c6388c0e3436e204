//! Code generation for one POU body: the [`Gen`] state, registers, jumps,
//! sites, loads and stores, implicit conversions.
//!
//! Expressions ([`expr`]) produce a [`Val`]: a scalar in a register, or the
//! address of a string or aggregate in the image. Statements ([`stmt`])
//! and calls ([`call`], [`stdfn`]) build on that.

mod call;
pub mod connect;
mod en;
mod expr;
mod forloop;
mod jumps;
pub mod lean;
mod ops;
mod peep;
mod refs;
mod stdfn;
mod stdmore;
mod stmt;

pub use stmt::pou;

use crate::cx::Cx;
use crate::layout::{mem_ty, Slot};
use automat_base::{Code, Diagnostic, Span};
use automat_ir::code::{Addr, Base, Builtin, Func, Inst, MemTy, Reg, RegClass, StrFn};
use automat_ir::Site;
use automat_sema::model::Section;
use automat_sema::types::{Elem, PouId, TypeId, TypeKind};

/// A lowering failure already recorded as a diagnostic.
#[derive(Debug)]
pub struct Failed;

pub type Res<T> = Result<T, Failed>;

/// Where a value is.
#[derive(Clone, Copy, Debug)]
pub enum V {
    /// I64 register.
    I(Reg),
    /// F32 register.
    F(Reg),
    /// F64 register.
    D(Reg),
    /// A string or aggregate in the image.
    M(Addr),
}

#[derive(Clone, Copy, Debug)]
pub struct Val {
    pub v: V,
    pub ty: TypeId,
}

/// A memory location of a given type.
#[derive(Clone, Copy, Debug)]
pub struct Lv {
    pub addr: Addr,
    pub bit: Option<u8>,
    pub ty: TypeId,
}

/// The scalar shape of a type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shape {
    Int(Elem),
    Str { wide: bool, cap: u32 },
    Agg,
}

pub struct Gen<'c, 'a> {
    pub cx: &'c mut Cx<'a>,
    pub pou: PouId,
    pub f: Func,
    /// The frame of a function (absolute); `None` for instances (This).
    pub frame: Option<u32>,
    /// Per loop: where CONTINUE goes (patched later when `None`) and the EXIT jumps.
    loops: Vec<LoopCx>,
    /// Jumps to the epilogue (RETURN).
    returns: Vec<u32>,
    /// Registers holding the address of a VAR_IN_OUT `ARRAY[*]`, with the
    /// address of its descriptor (bounds at +4).
    pub star: rustc_hash::FxHashMap<Reg, Addr>,
    /// Scratch buffers for string results and copied aggregates: (offset,
    /// size). Handed out in turn within a statement and reused by the next
    /// one, so a POU needs only as many as its busiest statement.
    temps: Vec<(u32, u32)>,
    temps_used: usize,
    /// The capacity (characters) each string temporary was last handed out
    /// with, by image offset: the most a string function result in it can
    /// hold, which sizes the result of a function taking it.
    pub str_caps: rustc_hash::FxHashMap<u32, u32>,
    /// The last instruction index handed out by [`Gen::here`]: a possible
    /// jump target, where a value from the previous instruction cannot be
    /// reused.
    label: std::cell::Cell<u32>,
    /// IL labels (`StmtKind::Label`) placed so far: name → instruction.
    labels: rustc_hash::FxHashMap<automat_base::Symbol, u32>,
    /// Jumps to labels not placed yet (`StmtKind::Goto` forward), patched
    /// when the label is reached.
    gotos: Vec<(automat_base::Symbol, u32, Span)>,
    /// Names are read in the configuration's scope (a connection's value):
    /// globals only, not the POU's variables (`connect.rs`).
    outside: bool,
}

struct LoopCx {
    continues: Vec<u32>,
    exits: Vec<u32>,
}

impl<'c, 'a> Gen<'c, 'a> {
    pub fn new(cx: &'c mut Cx<'a>, pou: PouId, name: &str, frame: Option<u32>) -> Gen<'c, 'a> {
        Gen {
            cx,
            pou,
            f: Func::new(name),
            frame,
            loops: Vec::new(),
            returns: Vec::new(),
            star: rustc_hash::FxHashMap::default(),
            temps: Vec::new(),
            temps_used: 0,
            str_caps: rustc_hash::FxHashMap::default(),
            label: std::cell::Cell::new(u32::MAX),
            labels: rustc_hash::FxHashMap::default(),
            gotos: Vec::new(),
            outside: false,
        }
    }

    pub fn error(&mut self, span: Span, msg: String) -> Failed {
        self.cx.diags.push(Diagnostic::error(Code::E091, span, msg));
        Failed
    }

    pub fn site(&mut self, span: Span) -> u32 {
        let pou = self
            .cx
            .model
            .pou(self.pou)
            .map(|p| automat_sema::names::display_name(self.cx.interner.name(p.name)).into_owned())
            .unwrap_or_default();
        self.cx.sites.push(Site {
            pou,
            location: self.cx.sources.location(span),
            meaning: self.cx.sources.fault_meaning(span).map(str::to_string),
        });
        self.cx.sites.len() as u32 - 1
    }

    pub fn reg(&mut self, c: RegClass) -> Reg {
        self.f.reg(c)
    }

    pub fn emit(&mut self, i: Inst) -> u32 {
        self.f.push(i)
    }

    pub fn here(&self) -> u32 {
        let at = self.f.code.len() as u32;
        self.label.set(at);
        at
    }

    /// The register just stored to `addr` as `ty`, when the previous
    /// instruction is that store and nothing can jump in between: reading
    /// the variable back would load the same (canonical) value.
    fn just_stored(&self, addr: Addr, ty: MemTy) -> Option<Reg> {
        let at = self.f.code.len() as u32;
        if self.label.get() == at {
            return None;
        }
        match self.f.code.last() {
            Some(Inst::Store {
                src,
                ty: t,
                addr: a,
            }) if *t == ty && *a == addr => Some(*src),
            // Reading the same location twice in a row (`i * i`).
            Some(Inst::Load {
                dst,
                ty: t,
                addr: a,
            }) if *t == ty && *a == addr => Some(*dst),
            _ => None,
        }
    }

    /// A forward jump whose target is patched later.
    pub fn jump_fwd(&mut self) -> u32 {
        self.emit(Inst::Jump { target: u32::MAX })
    }

    pub fn patch(&mut self, at: u32, target: u32) {
        match self.f.code.get_mut(at as usize) {
            Some(Inst::Jump { target: t }) => *t = target,
            Some(Inst::Branch { then, els, .. }) => {
                if *then == u32::MAX {
                    *then = target;
                }
                if *els == u32::MAX {
                    *els = target;
                }
            }
            _ => {}
        }
    }

    pub fn iconst(&mut self, v: i64) -> Reg {
        let r = self.reg(RegClass::I64);
        self.emit(Inst::IConst { dst: r, value: v });
        r
    }

    pub fn builtin(&mut self, op: Builtin, dst: Option<Reg>, args: &[Reg], span: Span) {
        let first = self.f.args.len() as u32;
        self.f.args.extend_from_slice(args);
        let site = self.site(span);
        self.emit(Inst::Builtin {
            op,
            dst,
            first,
            count: args.len() as u16,
            site,
        });
    }

    pub fn kind(&self, ty: TypeId) -> &'a TypeKind {
        self.cx.model.types.get(ty)
    }

    /// The elementary type a scalar type is stored as (enums as their base).
    pub fn elem(&self, ty: TypeId) -> Option<Elem> {
        match self.kind(ty) {
            TypeKind::Elem(e)
            | TypeKind::Subrange { base: e, .. }
            | TypeKind::Enum { base: e, .. } => Some(*e),
            // A reference is a u32 image offset.
            TypeKind::Ref(_) => Some(Elem::Udint),
            _ => None,
        }
    }

    pub fn shape(&self, ty: TypeId) -> Shape {
        match self.kind(ty) {
            TypeKind::String { wide, len } => Shape::Str {
                wide: *wide,
                cap: *len,
            },
            _ => match self.elem(ty) {
                Some(e) => Shape::Int(e),
                None => Shape::Agg,
            },
        }
    }

    /// Absolute offset of an address in a register.
    pub fn addr_reg(&mut self, a: Addr) -> Reg {
        if let Base::Reg(r) = a.base {
            if a.offset == 0 {
                return r;
            }
        }
        let r = self.reg(RegClass::I64);
        self.emit(Inst::AddrOf { dst: r, addr: a });
        r
    }

    /// Where variable `idx` of the current POU lives (VAR_IN_OUT dereferenced).
    /// A variable of this POU as its body sees it: an R_EDGE/F_EDGE input
    /// is the edge the prologue computed (a hidden byte), not the raw
    /// input the caller wrote.
    pub fn var_lv(&mut self, idx: u32, span: Span) -> Res<Lv> {
        let edge = self
            .cx
            .layout
            .pou(self.pou)
            .edges
            .iter()
            .find(|(i, _)| *i == idx)
            .map(|&(_, mem)| mem);
        if let Some(mem) = edge {
            let at = match self.frame {
                Some(f) => Addr::abs(f + mem + 1),
                None => Addr::this(mem + 1),
            };
            return Ok(Lv {
                addr: at,
                bit: None,
                ty: automat_sema::types::TypeId::BOOL,
            });
        }
        self.raw_var_lv(idx, span)
    }

    /// A variable of this POU where it is stored.
    pub fn raw_var_lv(&mut self, idx: u32, span: Span) -> Res<Lv> {
        let model = self.cx.model;
        let pou = model.pou(self.pou).ok_or(Failed)?;
        let var = pou.vars.vars.get(idx as usize).ok_or(Failed)?;
        let slot = self
            .cx
            .layout
            .pou(self.pou)
            .slots
            .get(idx as usize)
            .copied()
            .ok_or(Failed)?;
        let base = |off: u32, frame: Option<u32>| match frame {
            Some(f) => Addr::abs(f + off),
            None => Addr::this(off),
        };
        Ok(match slot {
            Slot::Rel(off) if var.section == Section::InOut => {
                let r = self.reg(RegClass::I64);
                let at = base(off, self.frame);
                self.emit(Inst::Load {
                    dst: r,
                    ty: MemTy::U32,
                    addr: at,
                });
                if self.cx.layout.star_rank(var.ty).is_some() {
                    self.star.insert(r, at);
                }
                Lv {
                    addr: Addr::reg(r, 0),
                    bit: None,
                    ty: var.ty,
                }
            }
            Slot::Rel(off) => Lv {
                addr: base(off, self.frame),
                bit: None,
                ty: var.ty,
            },
            Slot::Located(off, bit) => Lv {
                addr: Addr::abs(off),
                bit: if self.elem(var.ty) == Some(Elem::Bool) {
                    bit
                } else {
                    None
                },
                ty: var.ty,
            },
            Slot::External => match self.cx.globals.get(&var.name) {
                Some(g) => Lv {
                    addr: Addr::abs(g.0),
                    bit: g.1,
                    ty: g.2,
                },
                None => {
                    let n = self.cx.interner.name(var.name).to_string();
                    return Err(
                        self.error(span, format!("VAR_EXTERNAL {n} has no global of that name"))
                    );
                }
            },
        })
    }

    /// Reads a location into a value.
    pub fn load(&mut self, lv: Lv) -> Val {
        let v = match self.shape(lv.ty) {
            Shape::Int(e) => {
                let mt = mem_ty(e);
                let known = match lv.bit {
                    None => self.just_stored(lv.addr, mt),
                    Some(_) => None,
                };
                let r = match known {
                    Some(r) => r,
                    None => self.reg(mt.class()),
                };
                match (known, lv.bit) {
                    (Some(_), _) => 0,
                    (None, bit) => match bit {
                        Some(bit) => self.emit(Inst::LoadBit {
                            dst: r,
                            addr: lv.addr,
                            bit,
                        }),
                        None => self.emit(Inst::Load {
                            dst: r,
                            ty: mt,
                            addr: lv.addr,
                        }),
                    },
                };
                match mt.class() {
                    RegClass::I64 => V::I(r),
                    RegClass::F32 => V::F(r),
                    RegClass::F64 => V::D(r),
                }
            }
            _ => V::M(lv.addr),
        };
        Val { v, ty: lv.ty }
    }

    /// Writes a value (already of the location's type) to a location.
    pub fn store(&mut self, lv: Lv, val: Val, span: Span) -> Res<()> {
        match (self.shape(lv.ty), val.v) {
            (Shape::Int(e), V::I(r) | V::F(r) | V::D(r)) => {
                if let TypeKind::Subrange { lo, hi, .. } = self.kind(lv.ty) {
                    let (lo, hi) = (*lo as i64, *hi as i64);
                    let site = self.site(span);
                    self.emit(Inst::Check {
                        kind: automat_ir::code::CheckKind::Subrange,
                        val: r,
                        lo,
                        hi,
                        site,
                    });
                }
                match lv.bit {
                    Some(bit) => self.emit(Inst::StoreBit {
                        src: r,
                        addr: lv.addr,
                        bit,
                    }),
                    None => self.emit(Inst::Store {
                        src: r,
                        ty: mem_ty(e),
                        addr: lv.addr,
                    }),
                };
                Ok(())
            }
            (Shape::Str { wide, cap }, V::M(src)) => {
                let d = self.addr_reg(lv.addr);
                let c = self.iconst(cap as i64);
                let s = self.addr_reg(src);
                self.builtin(Builtin::Str(StrFn::Assign, wide), None, &[d, c, s], span);
                Ok(())
            }
            (Shape::Agg, V::M(src)) => {
                let (len, _) = self.cx.layout.size(lv.ty);
                self.emit(Inst::Copy {
                    dst: lv.addr,
                    src,
                    len,
                });
                Ok(())
            }
            _ => Err(self.error(
                span,
                "value and target of an assignment do not match".into(),
            )),
        }
    }

    /// A temporary string buffer of `cap` characters in the image.
    pub fn temp_str(&mut self, wide: bool, cap: u32) -> Addr {
        let cap = cap.min(automat_ir::strbuf::MAX_LEN);
        let size = automat_ir::strbuf::LEN_BYTES + cap * if wide { 2 } else { 1 };
        let at = self.temp(size);
        self.str_caps.insert(at.offset, cap);
        at
    }

    /// A scratch buffer of `size` bytes (8-aligned) for the current statement.
    pub fn temp(&mut self, size: u32) -> Addr {
        let k = self.temps_used;
        self.temps_used += 1;
        match self.temps.get(k).copied() {
            Some((at, have)) if have >= size => Addr::abs(at),
            _ => {
                let at = self.cx.alloc(size, 8);
                if let Some(slot) = self.temps.get_mut(k) {
                    *slot = (at, size);
                } else {
                    self.temps.push((at, size));
                }
                Addr::abs(at)
            }
        }
    }

    /// A new statement: the scratch buffers of the previous one are dead.
    pub fn free_temps(&mut self) {
        self.temps_used = 0;
    }
}
