//! The initial image: every variable at its folded initial value, computed
//! at compile time (cold start copies it).

use crate::layout::{mem_ty, Layout};
use automat_ir::code::MemTy;
use automat_ir::strbuf;
use automat_sema::model::Section;
use automat_sema::types::{Elem, TypeId, TypeKind};
use automat_sema::value::{Init, Value};

/// Writes raw little-endian bytes, ignoring writes outside the image (a
/// layout bug, never user input).
fn put(img: &mut [u8], at: u32, ty: MemTy, v: u64) {
    let n = ty.size() as usize;
    let a = at as usize;
    if let Some(dst) = img.get_mut(a..a + n) {
        dst.copy_from_slice(&v.to_le_bytes()[..n]);
    }
}

fn put_bit(img: &mut [u8], at: u32, bit: u8, on: bool) {
    if let Some(b) = img.get_mut(at as usize) {
        if on {
            *b |= 1 << bit;
        } else {
            *b &= !(1 << bit);
        }
    }
}

/// The register bits of a folded scalar value stored as `e`.
pub fn scalar_bits(v: &Value, e: Elem) -> u64 {
    match v {
        Value::Bool(b) => *b as u64,
        Value::Int(i) | Value::Enum(i) | Value::Duration(i) | Value::DateTime(i) => match e {
            Elem::Real => (*i as f32).to_bits() as u64,
            Elem::Lreal => (*i as f64).to_bits(),
            _ => *i as i64 as u64,
        },
        Value::Real(r) => match e {
            Elem::Real => (*r as f32).to_bits() as u64,
            _ => r.to_bits(),
        },
        Value::Date(d) | Value::Tod(d) => *d as u64,
        Value::Str(s) => s.chars().next().map_or(0, |c| c as u64),
    }
}

pub struct ImageWriter<'l, 'm> {
    pub layout: &'l mut Layout<'m>,
    pub img: Vec<u8>,
    /// Where each global lives (for `REF(global)` initial values).
    pub globals: &'l rustc_hash::FxHashMap<automat_base::Symbol, (u32, Option<u8>, TypeId)>,
    /// The instance whose variables are being written: `REF(x)` of one of
    /// its own variables points into it.
    pub here: Option<(u32, automat_sema::PouId)>,
}

impl ImageWriter<'_, '_> {
    /// Writes the initial value of a variable of type `ty` at `at`.
    pub fn init(&mut self, at: u32, bit: Option<u8>, ty: TypeId, init: Option<&Init>, depth: u32) {
        if depth > 64 {
            return;
        }
        let model = self.layout.model;
        match (model.types.get(ty), init) {
            (
                TypeKind::Elem(e)
                | TypeKind::Subrange { base: e, .. }
                | TypeKind::Enum { base: e, .. },
                _,
            ) => {
                let e = *e;
                let v = match init.and_then(Init::as_value) {
                    Some(v) => scalar_bits(v, e),
                    None => match model.types.get(ty) {
                        TypeKind::Subrange { lo, .. } => *lo as i64 as u64,
                        TypeKind::Enum { values, .. } => {
                            values.first().map_or(0, |v| v.value as i64 as u64)
                        }
                        _ => 0,
                    },
                };
                match bit {
                    Some(b) => put_bit(&mut self.img, at, b, v & 1 != 0),
                    None => put(&mut self.img, at, mem_ty(e), v),
                }
            }
            (TypeKind::Ref(_), Some(Init::Ref(target))) => {
                let addr = target.map_or(0, |sym| self.ref_target(sym));
                put(&mut self.img, at, MemTy::U32, u64::from(addr));
            }
            (TypeKind::String { wide, len }, Some(Init::Value(Value::Str(s)))) => {
                let (wide, cap) = (*wide, *len as usize);
                if wide {
                    let units: Vec<u16> = s.encode_utf16().take(cap).collect();
                    strbuf::set_len(&mut self.img, at, units.len() as u32);
                    for (i, u) in units.iter().enumerate() {
                        let a = at + strbuf::LEN_BYTES + 2 * i as u32;
                        put(&mut self.img, a, MemTy::U16, *u as u64);
                    }
                } else {
                    let bytes: Vec<u8> = s
                        .chars()
                        .take(cap)
                        .map(|c| if (c as u32) < 256 { c as u8 } else { b'?' })
                        .collect();
                    strbuf::set_len(&mut self.img, at, bytes.len() as u32);
                    for (i, b) in bytes.iter().enumerate() {
                        let a = at + strbuf::LEN_BYTES + i as u32;
                        put(&mut self.img, a, MemTy::U8, *b as u64);
                    }
                }
            }
            (TypeKind::Array { elem, dims }, init) => {
                let (elem, n) = (*elem, dims.iter().map(|d| d.len()).product::<u64>());
                let stride = self.layout.stride(elem);
                let mut i = 0u64;
                if let Some(Init::Array(items)) = init {
                    for item in items {
                        for _ in 0..item.repeat {
                            if i >= n {
                                break;
                            }
                            self.init(
                                at + (i * stride as u64) as u32,
                                None,
                                elem,
                                item.value.as_ref(),
                                depth + 1,
                            );
                            i += 1;
                        }
                    }
                }
                if !self.zero_default(elem) {
                    while i < n {
                        self.init(at + (i * stride as u64) as u32, None, elem, None, depth + 1);
                        i += 1;
                    }
                }
            }
            (TypeKind::Struct { members, .. }, init) => {
                let members = members.clone();
                let offs = self.layout.fields(ty);
                for (m, off) in members.iter().zip(offs) {
                    let given = match init {
                        Some(Init::Struct(fs)) => {
                            fs.iter().find(|f| f.name == m.name).map(|f| &f.value)
                        }
                        _ => None,
                    };
                    self.init(at + off, None, m.ty, given.or(m.init.as_ref()), depth + 1);
                }
            }
            (TypeKind::Fb { pou, .. } | TypeKind::Program { pou, .. }, init) => {
                let pou = *pou;
                // `t : TON := (PT := T#2s)`: the given members win over the
                // declared initial values of the function block.
                let given = match init {
                    Some(Init::Struct(fs)) => fs.as_slice(),
                    _ => &[],
                };
                self.instance_with(at, pou, depth + 1, given);
            }
            _ => {}
        }
    }

    /// The initial values of a POU instance (or function frame) at `at`.
    pub fn instance(&mut self, at: u32, pou: automat_sema::PouId, depth: u32) {
        self.instance_with(at, pou, depth, &[]);
    }

    /// [`instance`](Self::instance) with some members' initial values given
    /// by the instance's declaration.
    fn instance_with(
        &mut self,
        at: u32,
        pou: automat_sema::PouId,
        depth: u32,
        given: &[automat_sema::value::FieldInit],
    ) {
        let model = self.layout.model;
        let l = self.layout.pou(pou);
        let Some(p) = model.pou(pou) else { return };
        let outer = self.here.replace((at, pou));
        for (v, slot) in p.vars.vars.iter().zip(l.slots.iter()) {
            if v.section == Section::InOut {
                continue;
            }
            let init = given
                .iter()
                .find(|f| f.name == v.name)
                .map(|f| &f.value)
                .or(v.init.as_ref());
            match *slot {
                crate::layout::Slot::Rel(off) => self.init(at + off, None, v.ty, init, depth),
                crate::layout::Slot::Located(off, bit) => self.init(off, bit, v.ty, init, depth),
                crate::layout::Slot::External => {}
            }
        }
        self.here = outer;
    }

    /// The address `REF(sym)` denotes here: a variable of the current
    /// instance, else a global (the checker allowed nothing else).
    fn ref_target(&mut self, sym: automat_base::Symbol) -> u32 {
        if let Some((base, pou)) = self.here {
            let model = self.layout.model;
            if let Some(i) = model.pou(pou).and_then(|p| p.vars.index(sym)) {
                let slot = self.layout.pou(pou).slots.get(i as usize).copied();
                match slot {
                    Some(crate::layout::Slot::Rel(off)) => return base + off,
                    Some(crate::layout::Slot::Located(off, _)) => return off,
                    _ => {}
                }
            }
        }
        self.globals.get(&sym).map_or(0, |g| g.0)
    }

    /// True when every byte of the type's default is zero (nothing to write).
    fn zero_default(&self, ty: TypeId) -> bool {
        match self.layout.model.types.get(ty) {
            TypeKind::Elem(_) | TypeKind::String { .. } | TypeKind::Ref(_) => true,
            TypeKind::Subrange { lo, .. } => *lo == 0,
            TypeKind::Enum { values, .. } => values.first().is_none_or(|v| v.value == 0),
            _ => false,
        }
    }
}
