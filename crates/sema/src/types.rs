//! The type table: every type of a checked project, addressed by [`TypeId`].
//!
//! Invariants:
//! - `TypeId(0)` is the poison [`TypeKind::Error`]; ids `1..=25` are the
//!   elementary types in [`Elem::ALL`] order ([`TypeId::elem`]); 26 and 27 are
//!   `STRING` and `WSTRING` of the default length 80.
//! - Structural types (strings of a length, arrays, subranges, references,
//!   function block and program types) are interned: two equal spellings give
//!   one id, so type equality is id equality. Structures and enumerations are
//!   nominal: each declaration gets its own id.
//! - Aliases (`TYPE MyInt : INT; END_TYPE`) have no id of their own: the name
//!   maps to its target's id (the alias's initial value is carried to the
//!   variables declared with it).
//! - Array bounds, string lengths, subrange limits and enumeration values are
//!   folded numbers here, never expressions.

use crate::value::Init;
use automat_base::{Span, Symbol};
use rustc_hash::FxHashMap;

/// The elementary types of IEC 61131-3 except the strings (see [`TypeKind::String`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Elem {
    Bool,
    Sint,
    Int,
    Dint,
    Lint,
    Usint,
    Uint,
    Udint,
    Ulint,
    Real,
    Lreal,
    Byte,
    Word,
    Dword,
    Lword,
    Time,
    Ltime,
    Date,
    Ldate,
    Tod,
    Ltod,
    Dt,
    Ldt,
    Char,
    Wchar,
}

impl Elem {
    pub const ALL: [Elem; 25] = [
        Elem::Bool,
        Elem::Sint,
        Elem::Int,
        Elem::Dint,
        Elem::Lint,
        Elem::Usint,
        Elem::Uint,
        Elem::Udint,
        Elem::Ulint,
        Elem::Real,
        Elem::Lreal,
        Elem::Byte,
        Elem::Word,
        Elem::Dword,
        Elem::Lword,
        Elem::Time,
        Elem::Ltime,
        Elem::Date,
        Elem::Ldate,
        Elem::Tod,
        Elem::Ltod,
        Elem::Dt,
        Elem::Ldt,
        Elem::Char,
        Elem::Wchar,
    ];

    /// The canonical (standard) spelling.
    pub fn name(self) -> &'static str {
        match self {
            Elem::Bool => "BOOL",
            Elem::Sint => "SINT",
            Elem::Int => "INT",
            Elem::Dint => "DINT",
            Elem::Lint => "LINT",
            Elem::Usint => "USINT",
            Elem::Uint => "UINT",
            Elem::Udint => "UDINT",
            Elem::Ulint => "ULINT",
            Elem::Real => "REAL",
            Elem::Lreal => "LREAL",
            Elem::Byte => "BYTE",
            Elem::Word => "WORD",
            Elem::Dword => "DWORD",
            Elem::Lword => "LWORD",
            Elem::Time => "TIME",
            Elem::Ltime => "LTIME",
            Elem::Date => "DATE",
            Elem::Ldate => "LDATE",
            Elem::Tod => "TOD",
            Elem::Ltod => "LTOD",
            Elem::Dt => "DT",
            Elem::Ldt => "LDT",
            Elem::Char => "CHAR",
            Elem::Wchar => "WCHAR",
        }
    }

    /// Every spelling that names this type (the long date/time names too).
    pub fn spellings(self) -> &'static [&'static str] {
        match self {
            Elem::Tod => &["TOD", "TIME_OF_DAY"],
            Elem::Ltod => &["LTOD", "LTIME_OF_DAY"],
            Elem::Dt => &["DT", "DATE_AND_TIME"],
            Elem::Ldt => &["LDT", "LDATE_AND_TIME"],
            _ => std::slice::from_ref(&ELEM_NAMES_STATIC[self as usize]),
        }
    }

    /// The elementary type named `s` (any case, any spelling).
    pub fn from_name(s: &str) -> Option<Elem> {
        Elem::ALL
            .iter()
            .copied()
            .find(|e| e.spellings().iter().any(|n| n.eq_ignore_ascii_case(s)))
    }

    /// Storage width in bits (time and date types are 64-bit nanosecond counts).
    pub fn bits(self) -> u32 {
        use Elem::*;
        match self {
            Bool => 1,
            Sint | Usint | Byte | Char => 8,
            Int | Uint | Word | Wchar => 16,
            Dint | Udint | Dword | Real => 32,
            Lint | Ulint | Lword | Lreal => 64,
            Time | Ltime | Date | Ldate | Tod | Ltod | Dt | Ldt => 64,
        }
    }

    pub fn is_signed(self) -> bool {
        matches!(self, Elem::Sint | Elem::Int | Elem::Dint | Elem::Lint)
    }

    pub fn is_unsigned(self) -> bool {
        matches!(self, Elem::Usint | Elem::Uint | Elem::Udint | Elem::Ulint)
    }

    /// ANY_INT.
    pub fn is_int(self) -> bool {
        self.is_signed() || self.is_unsigned()
    }

    /// ANY_REAL.
    pub fn is_real(self) -> bool {
        matches!(self, Elem::Real | Elem::Lreal)
    }

    /// ANY_NUM.
    pub fn is_num(self) -> bool {
        self.is_int() || self.is_real()
    }

    /// ANY_BIT (BOOL included).
    pub fn is_bit(self) -> bool {
        matches!(
            self,
            Elem::Bool | Elem::Byte | Elem::Word | Elem::Dword | Elem::Lword
        )
    }

    /// ANY_DURATION.
    pub fn is_duration(self) -> bool {
        matches!(self, Elem::Time | Elem::Ltime)
    }

    /// ANY_DATE (dates, times of day, dates and times).
    pub fn is_date(self) -> bool {
        matches!(
            self,
            Elem::Date | Elem::Ldate | Elem::Tod | Elem::Ltod | Elem::Dt | Elem::Ldt
        )
    }

    pub fn is_char(self) -> bool {
        matches!(self, Elem::Char | Elem::Wchar)
    }

    /// The value range of integer-like types (integers, bit strings, BOOL).
    pub fn int_range(self) -> Option<(i128, i128)> {
        use Elem::*;
        Some(match self {
            Bool => (0, 1),
            Sint => (i8::MIN as i128, i8::MAX as i128),
            Int => (i16::MIN as i128, i16::MAX as i128),
            Dint => (i32::MIN as i128, i32::MAX as i128),
            Lint => (i64::MIN as i128, i64::MAX as i128),
            Usint | Byte => (0, u8::MAX as i128),
            Uint | Word => (0, u16::MAX as i128),
            Udint | Dword => (0, u32::MAX as i128),
            Ulint | Lword => (0, u64::MAX as i128),
            _ => return None,
        })
    }
}

static ELEM_NAMES_STATIC: [&str; 25] = [
    "BOOL", "SINT", "INT", "DINT", "LINT", "USINT", "UINT", "UDINT", "ULINT", "REAL", "LREAL",
    "BYTE", "WORD", "DWORD", "LWORD", "TIME", "LTIME", "DATE", "LDATE", "TOD", "LTOD", "DT", "LDT",
    "CHAR", "WCHAR",
];

/// Index of a type in the [`TypeTable`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct TypeId(pub u32);

impl TypeId {
    /// The poison type: an expression whose error was already reported.
    pub const ERROR: TypeId = TypeId(0);
    pub const STRING: TypeId = TypeId(26);
    pub const WSTRING: TypeId = TypeId(27);
    pub const BOOL: TypeId = TypeId::elem(Elem::Bool);

    pub const fn elem(e: Elem) -> TypeId {
        TypeId(1 + e as u32)
    }
}

/// Index of a POU in [`crate::Model::pous`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct PouId(pub u32);

/// The default length of `STRING` and `WSTRING`.
pub const DEFAULT_STRING_LEN: u32 = 80;

/// The longest declarable STRING/WSTRING (E072 beyond): `LEN` returns an
/// INT and positions are INTs, so 32,767 characters keep every length and
/// position exact (the image's 16-bit length field holds it;
/// `automat_ir::strbuf::MAX_LEN` is equal, by a test in `crates/lower`).
pub const MAX_STRING_LEN: u32 = 32_767;

/// One dimension of an array: `lo..hi`, or `*` (a VAR_IN_OUT of any length).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Dim {
    Range(i64, i64),
    Star,
}

impl Dim {
    /// Number of elements (0 for `*`).
    pub fn len(self) -> u64 {
        match self {
            Dim::Range(lo, hi) if hi >= lo => (hi as i128 - lo as i128 + 1) as u64,
            _ => 0,
        }
    }

    pub fn is_empty(self) -> bool {
        self.len() == 0
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct Member {
    pub name: Symbol,
    pub ty: TypeId,
    /// The folded initial value written on the member (or inherited from its type's alias).
    pub init: Option<Init>,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub struct EnumVal {
    pub name: Symbol,
    pub value: i128,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub enum TypeKind {
    Error,
    Elem(Elem),
    String {
        wide: bool,
        len: u32,
    },
    Array {
        elem: TypeId,
        dims: Vec<Dim>,
    },
    /// Members in declaration order.
    Struct {
        name: Option<Symbol>,
        members: Vec<Member>,
    },
    /// Values in declaration order; `base` is the integer type holding them (INT by default).
    Enum {
        name: Option<Symbol>,
        base: Elem,
        values: Vec<EnumVal>,
    },
    Subrange {
        base: Elem,
        lo: i128,
        hi: i128,
    },
    /// An instance of a function block.
    Fb {
        pou: PouId,
        name: Symbol,
    },
    /// An instance of a program (only in resources).
    Program {
        pou: PouId,
        name: Symbol,
    },
    /// `REF_TO T` / `POINTER TO T`.
    Ref(TypeId),
}

/// The interning key of structural types.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
enum Key {
    Str(bool, u32),
    Array(TypeId, Vec<Dim>),
    Subrange(Elem, i128, i128),
    Fb(PouId),
    Program(PouId),
    Ref(TypeId),
}

pub struct TypeTable {
    kinds: Vec<TypeKind>,
    interned: FxHashMap<Key, TypeId>,
}

impl Default for TypeTable {
    fn default() -> Self {
        TypeTable::new()
    }
}

impl TypeTable {
    pub fn new() -> TypeTable {
        let mut t = TypeTable {
            kinds: vec![TypeKind::Error],
            interned: FxHashMap::default(),
        };
        for e in Elem::ALL {
            t.kinds.push(TypeKind::Elem(e));
        }
        t.string(false, DEFAULT_STRING_LEN);
        t.string(true, DEFAULT_STRING_LEN);
        t
    }

    pub fn len(&self) -> usize {
        self.kinds.len()
    }

    pub fn is_empty(&self) -> bool {
        self.kinds.is_empty()
    }

    /// The kind of a type; [`TypeKind::Error`] for an id not in the table.
    pub fn get(&self, id: TypeId) -> &TypeKind {
        self.kinds.get(id.0 as usize).unwrap_or(&TypeKind::Error)
    }

    /// The elementary type an id denotes, subranges stripped to their base.
    pub fn elem(&self, id: TypeId) -> Option<Elem> {
        match self.get(id) {
            TypeKind::Elem(e) => Some(*e),
            TypeKind::Subrange { base, .. } => Some(*base),
            _ => None,
        }
    }

    /// Adds a nominal type (structure, enumeration) or a placeholder to fill later.
    pub fn add(&mut self, kind: TypeKind) -> TypeId {
        self.kinds.push(kind);
        TypeId(self.kinds.len() as u32 - 1)
    }

    /// Replaces a placeholder made by [`TypeTable::add`].
    pub fn set(&mut self, id: TypeId, kind: TypeKind) {
        if let Some(slot) = self.kinds.get_mut(id.0 as usize) {
            *slot = kind;
        }
    }

    fn intern(&mut self, key: Key, kind: TypeKind) -> TypeId {
        if let Some(&id) = self.interned.get(&key) {
            return id;
        }
        let id = self.add(kind);
        self.interned.insert(key, id);
        id
    }

    pub fn string(&mut self, wide: bool, len: u32) -> TypeId {
        self.intern(Key::Str(wide, len), TypeKind::String { wide, len })
    }

    pub fn array(&mut self, elem: TypeId, dims: Vec<Dim>) -> TypeId {
        self.intern(
            Key::Array(elem, dims.clone()),
            TypeKind::Array { elem, dims },
        )
    }

    pub fn subrange(&mut self, base: Elem, lo: i128, hi: i128) -> TypeId {
        self.intern(
            Key::Subrange(base, lo, hi),
            TypeKind::Subrange { base, lo, hi },
        )
    }

    pub fn fb(&mut self, pou: PouId, name: Symbol) -> TypeId {
        self.intern(Key::Fb(pou), TypeKind::Fb { pou, name })
    }

    pub fn program(&mut self, pou: PouId, name: Symbol) -> TypeId {
        self.intern(Key::Program(pou), TypeKind::Program { pou, name })
    }

    pub fn reference(&mut self, target: TypeId) -> TypeId {
        self.intern(Key::Ref(target), TypeKind::Ref(target))
    }

    /// The existing interned array type, without adding one.
    pub fn find_array(&self, elem: TypeId, dims: &[Dim]) -> Option<TypeId> {
        self.interned.get(&Key::Array(elem, dims.to_vec())).copied()
    }

    /// The existing interned reference type, without adding one.
    pub fn find_ref(&self, target: TypeId) -> Option<TypeId> {
        self.interned.get(&Key::Ref(target)).copied()
    }

    /// The existing interned string type, without adding one.
    pub fn find_string(&self, wide: bool, len: u32) -> Option<TypeId> {
        self.interned.get(&Key::Str(wide, len)).copied()
    }
}
