//! Expressions: constants, variables and their parts (members, elements,
//! bits), and the dispatch to operators and calls.

use super::{Failed, Gen, Lv, Res, Shape, Val, V};
use crate::image::scalar_bits;
use crate::layout::{mem_ty, Slot};
use automat_ir::code::{Addr, CheckKind, Inst, IntOp, RegClass};
use automat_ir::strbuf;
use automat_sema::ops::Ty;
use automat_sema::types::{Elem, TypeId, TypeKind};
use automat_sema::value::Value;
use automat_syntax::ast::{AddrSize, Expr, ExprKind};

impl Gen<'_, '_> {
    pub fn typed(&self, e: &Expr) -> automat_sema::Typed {
        automat_sema::type_of(self.cx.model, self.cx.interner, self.pou, e)
    }

    /// The concrete type of an expression type, an untyped constant taking
    /// the wanted type when it can.
    pub fn concrete(&self, t: Ty, want: Option<TypeId>, value: Option<&Value>) -> Option<TypeId> {
        let want_elem = want.and_then(|w| self.elem(w));
        match t {
            Ty::Of(id) if id != TypeId::ERROR => Some(id),
            Ty::AnyInt => match want_elem {
                Some(e) if e.is_num() || e.is_bit() => want,
                _ => {
                    let v = value.and_then(Value::as_int).unwrap_or(0);
                    Some(TypeId::elem(if i32::try_from(v).is_ok() {
                        Elem::Dint
                    } else {
                        Elem::Lint
                    }))
                }
            },
            Ty::AnyReal => match want_elem {
                Some(Elem::Real) => want,
                _ => Some(TypeId::elem(Elem::Lreal)),
            },
            Ty::AnyStr { wide } => match want {
                Some(w) if matches!(self.shape(w), Shape::Str { wide: ww, .. } if ww == wide) => {
                    want
                }
                Some(w) if matches!(self.elem(w), Some(Elem::Char | Elem::Wchar)) => want,
                _ => Some(if wide {
                    TypeId::WSTRING
                } else {
                    TypeId::STRING
                }),
            },
            _ => None,
        }
    }

    /// Lowers an expression, converted to `want` when given.
    pub fn expr(&mut self, e: &Expr, want: Option<TypeId>) -> Res<Val> {
        if let Some(v) = self.null_ref(e, want) {
            return Ok(v);
        }
        let typed = self.typed(e);
        let is_call = matches!(e.kind, ExprKind::Call { .. });
        if let (Some(v), false) = (&typed.value, is_call) {
            let ty = self
                .concrete(typed.ty, want, Some(v))
                .ok_or_else(|| self.cx_err(e))?;
            let val = self.constant(v, ty, e)?;
            return self.coerce_opt(val, want, e);
        }
        let val = match &e.kind {
            ExprKind::Paren(inner) => return self.expr(inner, want),
            ExprKind::Unary { op, operand } => self.unary(*op, operand, &typed, want, e)?,
            ExprKind::Binary { op, lhs, rhs } => self.binary(*op, lhs, rhs, &typed, want, e)?,
            ExprKind::Call { callee, args } => self.call(callee, args, e, want)?,
            _ => {
                let lv = self.place(e)?;
                self.load(lv)
            }
        };
        self.coerce_opt(val, want, e)
    }

    fn cx_err(&mut self, e: &Expr) -> Failed {
        self.error(
            e.span,
            "cannot determine the type of this expression".into(),
        )
    }

    fn coerce_opt(&mut self, v: Val, want: Option<TypeId>, e: &Expr) -> Res<Val> {
        match want {
            Some(w) => self.coerce(v, w, e.span),
            None => Ok(v),
        }
    }

    /// A register holding an I64 value of the expression (indexes, counts).
    pub fn int_expr(&mut self, e: &Expr) -> Res<u32> {
        let v = self.expr(e, Some(TypeId::elem(Elem::Lint)))?;
        match v.v {
            V::I(r) => Ok(r),
            _ => Err(self.error(e.span, "an integer is needed here".into())),
        }
    }

    /// A constant of type `ty`.
    pub fn constant(&mut self, v: &Value, ty: TypeId, e: &Expr) -> Res<Val> {
        let shape = self.shape(ty);
        let v = match (shape, v) {
            (Shape::Int(el), v) => {
                let bits = scalar_bits(v, el);
                let mt = mem_ty(el);
                let r = self.reg(mt.class());
                match mt.class() {
                    RegClass::I64 => {
                        self.emit(Inst::IConst {
                            dst: r,
                            value: bits as i64,
                        });
                        V::I(r)
                    }
                    RegClass::F32 => {
                        self.emit(Inst::F32Const {
                            dst: r,
                            value: f32::from_bits(bits as u32),
                        });
                        V::F(r)
                    }
                    RegClass::F64 => {
                        self.emit(Inst::F64Const {
                            dst: r,
                            value: f64::from_bits(bits),
                        });
                        V::D(r)
                    }
                }
            }
            (Shape::Str { wide, .. }, Value::Str(s)) => V::M(Addr::abs(self.const_str(s, wide))),
            _ => {
                return Err(self.error(
                    e.span,
                    format!("constant {} of this type is not supported", v.show()),
                ))
            }
        };
        Ok(Val { v, ty })
    }

    /// A string constant placed in the image. A literal longer than the
    /// longest string keeps its first `strbuf::MAX_LEN` characters: no
    /// variable could hold more (an assignment truncates to the declared
    /// length anyway).
    pub fn const_str(&mut self, s: &str, wide: bool) -> u32 {
        let max = strbuf::MAX_LEN as usize;
        let mut bytes = Vec::new();
        if wide {
            let units: Vec<u16> = s.encode_utf16().take(max).collect();
            bytes.extend_from_slice(&strbuf::header(units.len() as u32));
            for u in units {
                bytes.extend_from_slice(&u.to_le_bytes());
            }
        } else {
            let b: Vec<u8> = s
                .chars()
                .take(max)
                .map(|c| if (c as u32) < 256 { c as u8 } else { b'?' })
                .collect();
            bytes.extend_from_slice(&strbuf::header(b.len() as u32));
            bytes.extend_from_slice(&b);
        }
        let at = self.cx.alloc(bytes.len() as u32, 2);
        self.cx.consts.push((at, bytes));
        at
    }

    /// The memory location an expression designates.
    pub fn place(&mut self, e: &Expr) -> Res<Lv> {
        match &e.kind {
            ExprKind::Paren(inner) => self.place(inner),
            ExprKind::Name(id) => {
                let model = self.cx.model;
                let pou = model.pou(self.pou).ok_or(Failed)?;
                if let Some(idx) = pou.vars.index(id.sym).filter(|_| !self.outside) {
                    return self.var_lv(idx, e.span);
                }
                // `__SELF`: the current function block instance (the
                // object-orientation desugaring passes it to methods).
                if id.sym == model.syms.self_
                    && pou.kind == automat_syntax::ast::PouKind::FunctionBlock
                {
                    if let Some(ty) = pou.instance_type {
                        return Ok(Lv {
                            addr: Addr::this(0),
                            bit: None,
                            ty,
                        });
                    }
                }
                if let Some(&(off, bit, ty)) = self.cx.globals.get(&id.sym) {
                    return Ok(Lv {
                        addr: Addr::abs(off),
                        bit,
                        ty,
                    });
                }
                let n = self.cx.interner.name(id.sym).to_string();
                Err(self.error(e.span, format!("{n} is not a variable here")))
            }
            ExprKind::Address(a) => {
                let (off, bit) = self.cx.layout.located(a);
                let el = match a.size {
                    AddrSize::None | AddrSize::Bit => Elem::Bool,
                    AddrSize::Byte => Elem::Byte,
                    AddrSize::Word => Elem::Word,
                    AddrSize::DWord => Elem::Dword,
                    AddrSize::LWord => Elem::Lword,
                };
                Ok(Lv {
                    addr: Addr::abs(off),
                    bit,
                    ty: TypeId::elem(el),
                })
            }
            ExprKind::Member { base, member } => {
                let b = self.place(base)?;
                self.member(b, member.sym, e)
            }
            ExprKind::Index { base, indices } => {
                let b = self.place(base)?;
                self.index(b, indices, e)
            }
            ExprKind::Partial {
                base, size, index, ..
            } => {
                let b = self.place(base)?;
                let (bytes, el) = match size {
                    AddrSize::None | AddrSize::Bit => {
                        return Ok(Lv {
                            addr: add(b.addr, index / 8),
                            bit: Some((index % 8) as u8),
                            ty: TypeId::BOOL,
                        })
                    }
                    AddrSize::Byte => (1, Elem::Byte),
                    AddrSize::Word => (2, Elem::Word),
                    AddrSize::DWord => (4, Elem::Dword),
                    AddrSize::LWord => (8, Elem::Lword),
                };
                Ok(Lv {
                    addr: add(b.addr, index * bytes),
                    bit: None,
                    ty: TypeId::elem(el),
                })
            }
            ExprKind::Deref(base) => self.deref_place(base, e),
            _ => Err(self.error(e.span, "this expression is not a variable".into())),
        }
    }

    fn member(&mut self, b: Lv, name: automat_base::Symbol, e: &Expr) -> Res<Lv> {
        match self.kind(b.ty) {
            TypeKind::Struct { members, .. } => {
                let i = members.iter().position(|m| m.name == name).ok_or(Failed)?;
                let ty = members.get(i).ok_or(Failed)?.ty;
                let offs = self.cx.layout.fields(b.ty);
                let off = offs.get(i).copied().ok_or(Failed)?;
                Ok(Lv {
                    addr: add(b.addr, off),
                    bit: None,
                    ty,
                })
            }
            TypeKind::Fb { pou, .. } | TypeKind::Program { pou, .. } => {
                let pou = *pou;
                let p = self.cx.model.pou(pou).ok_or(Failed)?;
                let syms = &self.cx.model.syms;
                let hidden = self.cx.layout.pou(pou).eno;
                match (p.vars.index(name), hidden) {
                    (None, Some(at)) if name == syms.eno || name == syms.en => {
                        let at = if name == syms.eno { at } else { at + 1 };
                        self.cx.hidden.read = true;
                        return Ok(Lv {
                            addr: add(b.addr, at),
                            bit: None,
                            ty: TypeId::BOOL,
                        });
                    }
                    (None, _) => {
                        let n = self.cx.interner.name(name).to_string();
                        return Err(self.error(e.span, format!("{n} is not a member here")));
                    }
                    _ => {}
                }
                let idx = p.vars.index(name).ok_or(Failed)?;
                let var = p.vars.vars.get(idx as usize).ok_or(Failed)?;
                let slot = self.cx.layout.pou(pou).slots.get(idx as usize).copied();
                match slot {
                    Some(Slot::Rel(off)) if var.section == automat_sema::model::Section::InOut => {
                        let r = self.reg(RegClass::I64);
                        self.emit(Inst::Load {
                            dst: r,
                            ty: automat_ir::code::MemTy::U32,
                            addr: add(b.addr, off),
                        });
                        Ok(Lv {
                            addr: Addr::reg(r, 0),
                            bit: None,
                            ty: var.ty,
                        })
                    }
                    Some(Slot::Rel(off)) => Ok(Lv {
                        addr: add(b.addr, off),
                        bit: None,
                        ty: var.ty,
                    }),
                    Some(Slot::Located(off, bit)) => Ok(Lv {
                        addr: Addr::abs(off),
                        bit,
                        ty: var.ty,
                    }),
                    _ => Err(self.error(e.span, "this member cannot be accessed".into())),
                }
            }
            _ => Err(self.error(e.span, "member access on a value without members".into())),
        }
    }

    fn index(&mut self, b: Lv, indices: &[Expr], e: &Expr) -> Res<Lv> {
        // CODESYS `s[i]`: the i-th character code of a STRING (BYTE) or
        // WSTRING (WORD), from 0, as an array of its capacity after the
        // 2-byte length.
        let (elem, bounds, stride, header) = match self.kind(b.ty) {
            TypeKind::Array { elem, dims } => {
                let elem = *elem;
                let bounds = self.cx.layout.dims(dims);
                let desc = match b.addr.base {
                    automat_ir::code::Base::Reg(r) if b.addr.offset == 0 => {
                        self.star.get(&r).copied()
                    }
                    _ => None,
                };
                if let (Some(d), true) = (desc, bounds.len() == indices.len()) {
                    return self.index_star(b, d, elem, indices);
                }
                (elem, bounds, self.cx.layout.stride(elem) as i64, 0)
            }
            TypeKind::String { wide, len } => {
                let (el, unit) = if *wide {
                    (Elem::Word, 2)
                } else {
                    (Elem::Byte, 1)
                };
                let last = i64::from(*len) - 1;
                (TypeId::elem(el), vec![(0, last)], unit, 2)
            }
            _ => return Err(self.error(e.span, "indexing a value that is not an array".into())),
        };
        if bounds.len() != indices.len() || bounds.iter().any(|(lo, hi)| lo > hi) {
            return Err(self.error(
                e.span,
                "arrays of unknown size ([*]) are not supported".into(),
            ));
        }
        // Multiplier of each dimension: row-major.
        let mut mults = vec![stride; bounds.len()];
        for k in (0..bounds.len().saturating_sub(1)).rev() {
            let (lo, hi) = bounds[k + 1];
            mults[k] = mults[k + 1].saturating_mul(hi - lo + 1);
        }
        let mut const_off: i64 = header;
        let mut acc: Option<u32> = None;
        for ((ix, (lo, hi)), m) in indices.iter().zip(bounds).zip(mults) {
            let known = self.typed(ix).value.as_ref().and_then(Value::as_int);
            match known {
                Some(v) if (lo as i128..=hi as i128).contains(&v) => {
                    const_off += (v as i64 - lo) * m;
                }
                _ => {
                    let r = self.int_expr(ix)?;
                    let site = self.site(ix.span);
                    self.emit(Inst::Check {
                        kind: CheckKind::Index,
                        val: r,
                        lo,
                        hi,
                        site,
                    });
                    // (r - lo) * m: the -lo*m part is folded into the constant.
                    const_off -= lo * m;
                    let t = if m == 1 {
                        r
                    } else {
                        let mr = self.iconst(m);
                        let t = self.reg(RegClass::I64);
                        self.emit(Inst::Int {
                            op: IntOp::Mul,
                            dst: t,
                            a: r,
                            b: mr,
                        });
                        t
                    };
                    acc = Some(match acc {
                        None => t,
                        Some(a) => {
                            let s = self.reg(RegClass::I64);
                            self.emit(Inst::Int {
                                op: IntOp::Add,
                                dst: s,
                                a,
                                b: t,
                            });
                            s
                        }
                    });
                }
            }
        }
        let addr = match acc {
            None => add(b.addr, const_off as u32),
            // The constant part goes into the operand's offset: the engine
            // adds it modulo 2^32, so a negative part works too.
            Some(a) => {
                let (base, off0) = match b.addr.base {
                    automat_ir::code::Base::Reg(r) => (r, b.addr.offset),
                    _ => (self.addr_reg(b.addr), 0),
                };
                let t = self.int_op(IntOp::Add, base, a);
                Addr::reg(t, off0.wrapping_add(const_off as u32))
            }
        };
        Ok(Lv {
            addr,
            bit: None,
            ty: elem,
        })
    }
}

/// `a + k` bytes.
pub fn add(a: Addr, k: u32) -> Addr {
    Addr {
        base: a.base,
        offset: a.offset.wrapping_add(k),
    }
}

impl Gen<'_, '_> {
    /// An element of a VAR_IN_OUT `ARRAY[*]`: bounds come from the
    /// descriptor the caller filled (`lo, hi` i32 per dimension at +4).
    fn index_star(&mut self, b: Lv, desc: Addr, elem: TypeId, indices: &[Expr]) -> Res<Lv> {
        let stride = self.cx.layout.stride(elem) as i64;
        let mut los = Vec::with_capacity(indices.len());
        let mut his = Vec::with_capacity(indices.len());
        for k in 0..indices.len() as u32 {
            for (j, out) in [&mut los, &mut his].into_iter().enumerate() {
                let r = self.reg(RegClass::I64);
                self.emit(Inst::Load {
                    dst: r,
                    ty: automat_ir::code::MemTy::I32,
                    addr: add(desc, 4 + 8 * k + 4 * j as u32),
                });
                out.push(r);
            }
        }
        // Row-major: offset = ((i0 - lo0) * n1 + (i1 - lo1)) * n2 + ... , times the stride.
        let one = self.iconst(1);
        let mut acc: Option<u32> = None;
        for (k, ix) in indices.iter().enumerate() {
            let (lo, hi) = (los[k], his[k]);
            let r = self.int_expr(ix)?;
            let site = self.site(ix.span);
            self.emit(Inst::CheckDyn {
                kind: CheckKind::Index,
                val: r,
                lo,
                hi,
                site,
            });
            let rel = self.int_op(IntOp::Sub, r, lo);
            acc = Some(match acc {
                None => rel,
                Some(a) => {
                    let span = self.int_op(IntOp::Sub, hi, lo);
                    let n = self.int_op(IntOp::Add, span, one);
                    let m = self.int_op(IntOp::Mul, a, n);
                    self.int_op(IntOp::Add, m, rel)
                }
            });
        }
        let Some(acc) = acc else {
            return Err(Failed);
        };
        let s = self.iconst(stride);
        let off = self.int_op(IntOp::Mul, acc, s);
        let base = self.addr_reg(b.addr);
        let at = self.int_op(IntOp::Add, base, off);
        Ok(Lv {
            addr: Addr::reg(at, 0),
            bit: None,
            ty: elem,
        })
    }

    fn int_op(&mut self, op: IntOp, a: u32, b: u32) -> u32 {
        let d = self.reg(RegClass::I64);
        self.emit(Inst::Int { op, dst: d, a, b });
        d
    }
}
