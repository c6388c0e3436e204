//! Memory layout: sizes and alignments of types, the field offsets of
//! structures and POU instances, and where located variables live.
//!
//! Rules (the image format, shared with every backend and tool):
//! - BOOL 1 byte; integers and bit strings their width; REAL f32, LREAL
//!   f64; every time and date type i64; CHAR 1, WCHAR 2; enums as their base.
//! - STRING[n] = u16 length + n bytes; WSTRING[n] = u16 length + n u16
//!   (`automat_ir::strbuf`; n ≤ 32,767).
//! - Arrays row-major; structures and instances as their fields in order,
//!   each naturally aligned; the size rounded up to the alignment.
//! - VAR_IN_OUT and REF_TO: a u32 image offset, 0 being NULL. A
//!   VAR_IN_OUT `ARRAY[*]` is the offset followed by `lo, hi` (i32) per
//!   dimension, which the caller fills from the argument's type.
//! - Located variables follow the CODESYS / OpenPLC convention: the number
//!   of a sized address is an index in units of the access size, so
//!   `%IB3` is input byte 3, `%QW2` output bytes 4..=5, `%MD1` memory bytes
//!   4..=7, `%IL1` input bytes 8..=15; a bit address `%IX1.2` (or `%I1.2`)
//!   is bit 2 of byte 1. Hence `%QX4.0` is bit 0 of `%QW2` (little-endian:
//!   the low byte of the word comes first).
//! - The image starts with [`RESERVED`] bytes nothing lives in, so that
//!   offset 0 can be the NULL reference; then %I, %Q, %M.

use automat_ir::code::MemTy;
use automat_sema::model::Section;
use automat_sema::types::{Dim, Elem, PouId, TypeId, TypeKind};
use automat_sema::Model;
use automat_syntax::ast::{AddrSize, Area, DirectAddress};
use rustc_hash::FxHashMap;

/// Types nest at most this deep (arrays, structures, FB instances within
/// each other); a cycle is reported by the checker before lowering.
pub const MAX_DEPTH: u32 = 64;

/// Where a variable of a POU lives.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Slot {
    /// At this offset in the instance (or the function's static frame).
    Rel(u32),
    /// A located variable: absolute image offset and bit.
    Located(u32, Option<u8>),
    /// VAR_EXTERNAL: the global of the same name.
    External,
}

#[derive(Clone, Debug, Default)]
pub struct PouLayout {
    pub slots: Vec<Slot>,
    /// Edge-qualified inputs (`R_EDGE`, `F_EDGE`): the variable's index and
    /// the offset of the hidden byte holding its previous raw value.
    pub edges: Vec<(u32, u32)>,
    /// A function block without a declared ENO: the hidden byte holding
    /// the ENO of its last call (`fb.ENO`), followed by the EN byte.
    pub eno: Option<u32>,
    /// The size in bytes, saturated at `u32::MAX` (see `bytes`).
    pub size: u32,
    /// The exact size, for the image-size limit and its message: sizes are
    /// computed in 64 bits so that a type larger than 4 GiB is reported with
    /// what it needs, not a wrapped or saturated number.
    pub bytes: u64,
    pub align: u32,
}

/// The byte ranges of %I, %Q, %M at the start of the image.
#[derive(Clone, Copy, Debug, Default)]
pub struct AreaBases {
    pub input: (u32, u32),
    pub output: (u32, u32),
    pub memory: (u32, u32),
}

pub struct Layout<'m> {
    pub model: &'m Model,
    pub areas: AreaBases,
    /// Exact size and alignment of each type sized so far.
    sizes: FxHashMap<TypeId, (u64, u32)>,
    fields: FxHashMap<TypeId, Vec<u32>>,
    pous: FxHashMap<PouId, PouLayout>,
    /// Some type nests more than `MAX_DEPTH` levels deep.
    pub too_deep: bool,
    /// Declared spellings of enumeration types and values, for the symbol
    /// table (see `symbols::spellings`).
    pub spellings: FxHashMap<automat_base::Symbol, String>,
}

pub fn align_up(x: u32, a: u32) -> u32 {
    let a = a.max(1);
    x.div_ceil(a).saturating_mul(a)
}

/// [`align_up`] on exact (64-bit) sizes.
pub fn align_up64(x: u64, a: u32) -> u64 {
    let a = u64::from(a.max(1));
    x.div_ceil(a).saturating_mul(a)
}

/// An exact size or offset as the u32 the image uses (saturated: anything
/// that large is refused by the image-size limit before it is used).
pub fn narrow(x: u64) -> u32 {
    u32::try_from(x).unwrap_or(u32::MAX)
}

/// The memory type of an elementary type.
pub fn mem_ty(e: Elem) -> MemTy {
    match e {
        Elem::Bool | Elem::Usint | Elem::Byte | Elem::Char => MemTy::U8,
        Elem::Sint => MemTy::I8,
        Elem::Int => MemTy::I16,
        Elem::Uint | Elem::Word | Elem::Wchar => MemTy::U16,
        Elem::Dint => MemTy::I32,
        Elem::Udint | Elem::Dword => MemTy::U32,
        Elem::Real => MemTy::F32,
        Elem::Lreal => MemTy::F64,
        _ => MemTy::I64,
    }
}

/// Byte offset and bit of a located address.
pub fn address_offset(a: &DirectAddress) -> (u32, Option<u8>) {
    let first = a.path.first().copied().unwrap_or(0);
    match a.size {
        AddrSize::None | AddrSize::Bit => {
            let bit = a.path.get(1).copied().unwrap_or(0).min(7) as u8;
            (first, Some(bit))
        }
        AddrSize::Byte => (first, None),
        AddrSize::Word => (first.saturating_mul(2), None),
        AddrSize::DWord => (first.saturating_mul(4), None),
        AddrSize::LWord => (first.saturating_mul(8), None),
    }
}

/// Bytes at the start of the image no variable uses (offset 0 is NULL).
pub const RESERVED: u32 = 8;

impl<'m> Layout<'m> {
    pub fn new(model: &'m Model) -> Layout<'m> {
        Layout {
            model,
            areas: AreaBases::default(),
            sizes: FxHashMap::default(),
            fields: FxHashMap::default(),
            pous: FxHashMap::default(),
            too_deep: false,
            spellings: FxHashMap::default(),
        }
    }

    /// Sizes the areas from the highest located address used anywhere;
    /// they start after the reserved bytes: %I, then %Q, then %M.
    pub fn size_areas(&mut self, in_code: &[DirectAddress]) -> u32 {
        let mut ends = [0u32; 3];
        let mut note = |l: &Option<DirectAddress>, ty: TypeId, this: &mut Self| {
            if let Some(a) = l {
                if a.partial {
                    return;
                }
                let (off, bit) = address_offset(a);
                let n = if bit.is_some() {
                    1
                } else {
                    this.size(ty).0.max(1)
                };
                let i = match a.area {
                    Area::Input => 0,
                    Area::Output => 1,
                    Area::Memory => 2,
                };
                ends[i] = ends[i].max(off.saturating_add(n));
            }
        };
        let model = self.model;
        let all = model
            .pous
            .iter()
            .flat_map(|p| p.vars.vars.iter())
            .chain(model.globals.vars.iter())
            .chain(model.configs.iter().flat_map(|c| {
                c.globals
                    .vars
                    .iter()
                    .chain(c.resources.iter().flat_map(|r| r.globals.vars.iter()))
            }));
        for v in all {
            note(&v.location, v.ty, self);
        }
        for a in in_code {
            let ty = TypeId::elem(match a.size {
                AddrSize::None | AddrSize::Bit | AddrSize::Byte => Elem::Byte,
                AddrSize::Word => Elem::Word,
                AddrSize::DWord => Elem::Dword,
                AddrSize::LWord => Elem::Lword,
            });
            note(&Some(a.clone()), ty, self);
        }
        let i = (RESERVED, RESERVED + ends[0]);
        let q = (i.1, i.1 + ends[1]);
        let m = (q.1, q.1 + ends[2]);
        self.areas = AreaBases {
            input: i,
            output: q,
            memory: m,
        };
        m.1
    }

    pub fn located(&self, a: &DirectAddress) -> (u32, Option<u8>) {
        let (off, bit) = address_offset(a);
        let base = match a.area {
            Area::Input => self.areas.input.0,
            Area::Output => self.areas.output.0,
            Area::Memory => self.areas.memory.0,
        };
        (base.saturating_add(off), bit)
    }

    /// Size and alignment of a type.
    pub fn size(&mut self, ty: TypeId) -> (u32, u32) {
        let (s, a) = self.size_at(ty, 0);
        (narrow(s), a)
    }

    /// The exact size of a type in bytes.
    pub fn bytes(&mut self, ty: TypeId) -> u64 {
        self.size_at(ty, 0).0
    }

    fn size_at(&mut self, ty: TypeId, depth: u32) -> (u64, u32) {
        if let Some(s) = self.sizes.get(&ty) {
            return *s;
        }
        if depth > MAX_DEPTH {
            // Not a cycle (the checker reports those): a real nesting this
            // deep cannot be laid out; lowering refuses it (E091).
            self.too_deep = true;
            return (0, 1);
        }
        let kind = self.model.types.get(ty).clone();
        let s = match kind {
            TypeKind::Error => (0, 1),
            TypeKind::Elem(e)
            | TypeKind::Subrange { base: e, .. }
            | TypeKind::Enum { base: e, .. } => {
                let n = mem_ty(e).size();
                (u64::from(n), n)
            }
            TypeKind::String { wide: false, len } => (2 + u64::from(len), 2),
            TypeKind::String { wide: true, len } => (2 + 2 * u64::from(len), 2),
            TypeKind::Array { elem, dims } => {
                let (es, ea) = self.size_at(elem, depth + 1);
                let stride = align_up64(es, ea);
                let n = dims.iter().map(|d| d.len()).fold(1u64, u64::saturating_mul);
                (n.saturating_mul(stride), ea)
            }
            TypeKind::Struct { members, .. } => {
                let mut off = 0u64;
                let mut al = 1u32;
                let mut offs = Vec::with_capacity(members.len());
                for m in &members {
                    let (s, a) = self.size_at(m.ty, depth + 1);
                    off = align_up64(off, a);
                    offs.push(narrow(off));
                    off = off.saturating_add(s);
                    al = al.max(a);
                }
                self.fields.insert(ty, offs);
                (align_up64(off, al), al)
            }
            TypeKind::Fb { pou, .. } | TypeKind::Program { pou, .. } => {
                // One level per type: the POU's variables are the next.
                let l = self.pou_at(pou, depth);
                (l.bytes, l.align)
            }
            TypeKind::Ref(_) => (4, 4),
        };
        self.sizes.insert(ty, s);
        s
    }

    /// Offsets of a structure's members.
    pub fn fields(&mut self, ty: TypeId) -> Vec<u32> {
        self.size(ty);
        self.fields.get(&ty).cloned().unwrap_or_default()
    }

    /// Element stride of an array type.
    pub fn stride(&mut self, elem: TypeId) -> u32 {
        let (s, a) = self.size(elem);
        align_up(s, a)
    }

    pub fn pou(&mut self, pou: PouId) -> PouLayout {
        self.pou_at(pou, 0)
    }

    fn pou_at(&mut self, pou: PouId, depth: u32) -> PouLayout {
        if let Some(l) = self.pous.get(&pou) {
            return l.clone();
        }
        let Some(p) = self.model.pou(pou) else {
            return PouLayout::default();
        };
        let mut off = 0u64;
        let mut al = 1u32;
        let mut slots = Vec::with_capacity(p.vars.vars.len());
        for v in &p.vars.vars {
            if v.section == Section::External {
                slots.push(Slot::External);
                continue;
            }
            if let Some(a) = v.location.as_ref().filter(|a| !a.partial) {
                let (o, b) = self.located(a);
                slots.push(Slot::Located(o, b));
                continue;
            }
            let (s, a) = if v.section == Section::InOut {
                // The address, then (for ARRAY[*]) the bounds the caller passes.
                (u64::from(4 + 8 * self.star_rank(v.ty).unwrap_or(0)), 4)
            } else {
                self.size_at(v.ty, depth + 1)
            };
            off = align_up64(off, a);
            slots.push(Slot::Rel(narrow(off)));
            off = off.saturating_add(s);
            al = al.max(a);
        }
        let mut edges = Vec::new();
        for (i, v) in p.vars.vars.iter().enumerate() {
            if v.edge.is_some() && v.section == Section::Input {
                // Two hidden bytes: the last raw value (the edge memory)
                // and the edge the body reads; the input itself keeps the
                // raw value, so a call that does not give it keeps it.
                edges.push((i as u32, narrow(off)));
                off = off.saturating_add(2);
            }
        }
        let syms = &self.model.syms;
        let eno = (p.kind == automat_syntax::ast::PouKind::FunctionBlock
            && p.vars.index(syms.eno).is_none())
        .then(|| {
            let at = narrow(off);
            off = off.saturating_add(2);
            at
        });
        let bytes = align_up64(off, al);
        let l = PouLayout {
            slots,
            edges,
            eno,
            size: narrow(bytes),
            bytes,
            align: al,
        };
        self.pous.insert(pou, l.clone());
        l
    }

    /// The number of dimensions of an array of unknown size (`ARRAY[*]`),
    /// whose VAR_IN_OUT slot holds the address and then `lo, hi` (i32 each)
    /// per dimension.
    pub fn star_rank(&self, ty: TypeId) -> Option<u32> {
        match self.model.types.get(ty) {
            TypeKind::Array { dims, .. } if dims.iter().any(|d| matches!(d, Dim::Star)) => {
                Some(dims.len() as u32)
            }
            _ => None,
        }
    }

    /// Number of elements and the `(lo, hi)` bounds of an array type's dims.
    pub fn dims(&self, dims: &[Dim]) -> Vec<(i64, i64)> {
        dims.iter()
            .map(|d| match d {
                Dim::Range(lo, hi) => (*lo, *hi),
                Dim::Star => (0, -1),
            })
            .collect()
    }
}
