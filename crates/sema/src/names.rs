//! Well-known names, and how types and expressions are written in messages.
//!
//! Invariant: the functions here only format; they are called when a
//! diagnostic is about to be emitted, never on the clean path.

use crate::ops::Ty;
use crate::types::{Dim, Elem, TypeId, TypeKind, TypeTable, DEFAULT_STRING_LEN};
use automat_base::{Interner, Symbol};
use automat_syntax::ast::{AddrSize, Area, DirectAddress, Expr, ExprKind, LitKind, UnaryOp};
use rustc_hash::FxHashMap;
use std::fmt::Write;

/// Symbols the checker compares against, interned once per run.
#[derive(Clone, Debug, PartialEq)]
pub struct Syms {
    pub elems: FxHashMap<Symbol, Elem>,
    pub string: Symbol,
    pub wstring: Symbol,
    pub en: Symbol,
    pub eno: Symbol,
    pub r: Symbol,
    pub reset: Symbol,
    pub interval: Symbol,
    pub priority: Symbol,
    pub single: Symbol,
}

impl Syms {
    pub fn new(interner: &mut Interner) -> Syms {
        let mut elems = FxHashMap::default();
        for e in Elem::ALL {
            for n in e.spellings() {
                elems.insert(interner.intern(n), e);
            }
        }
        Syms {
            elems,
            string: interner.intern("STRING"),
            wstring: interner.intern("WSTRING"),
            en: interner.intern("EN"),
            eno: interner.intern("ENO"),
            r: interner.intern("R"),
            reset: interner.intern("RESET"),
            interval: interner.intern("INTERVAL"),
            priority: interner.intern("PRIORITY"),
            single: interner.intern("SINGLE"),
        }
    }

    /// Whether a name is reserved for an elementary type (STRING included).
    pub fn is_elementary(&self, s: Symbol) -> bool {
        self.elems.contains_key(&s) || s == self.string || s == self.wstring
    }
}

/// A type as written in messages: `INT`, `STRING[20]`, `ARRAY[1..10] OF INT`, `Color`.
pub fn type_name(types: &TypeTable, interner: &Interner, id: TypeId) -> String {
    let mut out = String::new();
    write_type(&mut out, types, interner, id, 0);
    out
}

fn write_type(out: &mut String, types: &TypeTable, interner: &Interner, id: TypeId, depth: u32) {
    if depth > 8 {
        out.push_str("...");
        return;
    }
    match types.get(id) {
        TypeKind::Error => out.push_str("<error>"),
        TypeKind::Elem(e) => out.push_str(e.name()),
        TypeKind::String { wide, len } => {
            out.push_str(if *wide { "WSTRING" } else { "STRING" });
            if *len != DEFAULT_STRING_LEN {
                let _ = write!(out, "[{len}]");
            }
        }
        TypeKind::Array { elem, dims } => {
            out.push_str("ARRAY[");
            for (i, d) in dims.iter().enumerate() {
                if i > 0 {
                    out.push_str(", ");
                }
                match d {
                    Dim::Range(lo, hi) => {
                        let _ = write!(out, "{lo}..{hi}");
                    }
                    Dim::Star => out.push('*'),
                }
            }
            out.push_str("] OF ");
            write_type(out, types, interner, *elem, depth + 1);
        }
        TypeKind::Struct { name, .. } => match name {
            Some(n) => out.push_str(interner.name(*n)),
            None => out.push_str("STRUCT"),
        },
        TypeKind::Enum { name, values, .. } => match name {
            Some(n) => out.push_str(interner.name(*n)),
            None => {
                out.push('(');
                for (i, v) in values.iter().enumerate() {
                    if i > 0 {
                        out.push_str(", ");
                    }
                    out.push_str(interner.name(v.name));
                }
                out.push(')');
            }
        },
        TypeKind::Subrange { base, lo, hi } => {
            let _ = write!(out, "{}({lo}..{hi})", base.name());
        }
        TypeKind::Fb { name, .. } | TypeKind::Program { name, .. } => {
            out.push_str(interner.name(*name))
        }
        TypeKind::Ref(t) => {
            out.push_str("REF_TO ");
            write_type(out, types, interner, *t, depth + 1);
        }
    }
}

/// An expression type as written in messages.
pub fn ty_name(types: &TypeTable, interner: &Interner, ty: Ty) -> String {
    match ty {
        Ty::Error => "<error>".into(),
        Ty::Of(id) => type_name(types, interner, id),
        Ty::AnyInt => "an integer literal".into(),
        Ty::AnyReal => "a real literal".into(),
        Ty::AnyStr { wide: false } => "a STRING literal".into(),
        Ty::AnyStr { wide: true } => "a WSTRING literal".into(),
        Ty::RefOf(t) => format!("REF_TO {}", type_name(types, interner, t)),
    }
}

/// A value for messages: `the value 5`, `the string 'abc'`, `a value of type DINT`.
pub fn value_desc(types: &TypeTable, interner: &Interner, t: &crate::ops::Typed) -> String {
    let shown = || t.value.as_ref().map_or_else(String::new, |v| v.show());
    match t.ty {
        Ty::AnyInt | Ty::AnyReal => format!("the value {}", shown()),
        Ty::AnyStr { .. } => format!("the string {}", shown()),
        ty => format!("a value of type {}", ty_name(types, interner, ty)),
    }
}

/// A direct address as written: `%IX0.1`, `%QW4`, `%I*`.
pub fn address_text(a: &DirectAddress) -> String {
    let mut s = String::from("%");
    s.push(match a.area {
        Area::Input => 'I',
        Area::Output => 'Q',
        Area::Memory => 'M',
    });
    s.push_str(match a.size {
        AddrSize::None => "",
        AddrSize::Bit => "X",
        AddrSize::Byte => "B",
        AddrSize::Word => "W",
        AddrSize::DWord => "D",
        AddrSize::LWord => "L",
    });
    if a.partial {
        s.push('*');
    }
    for (i, n) in a.path.iter().enumerate() {
        if i > 0 {
            s.push('.');
        }
        let _ = write!(s, "{n}");
    }
    s
}

/// An expression written back as source text, for messages (`a.b[i]`).
pub fn expr_text(interner: &Interner, e: &Expr) -> String {
    let mut out = String::new();
    write_expr(&mut out, interner, e, 0);
    out
}

fn write_expr(out: &mut String, interner: &Interner, e: &Expr, depth: u32) {
    if depth > 6 || out.len() > 60 {
        out.push_str("...");
        return;
    }
    let d = depth + 1;
    match &e.kind {
        ExprKind::Name(i) => out.push_str(interner.name(i.sym)),
        ExprKind::Member { base, member } => {
            write_expr(out, interner, base, d);
            out.push('.');
            out.push_str(interner.name(member.sym));
        }
        ExprKind::Index { base, indices } => {
            write_expr(out, interner, base, d);
            out.push('[');
            for (i, x) in indices.iter().enumerate() {
                if i > 0 {
                    out.push_str(", ");
                }
                write_expr(out, interner, x, d);
            }
            out.push(']');
        }
        ExprKind::Partial {
            base, size, index, ..
        } => {
            write_expr(out, interner, base, d);
            out.push('.');
            out.push_str(match size {
                AddrSize::None => "",
                AddrSize::Bit => "%X",
                AddrSize::Byte => "%B",
                AddrSize::Word => "%W",
                AddrSize::DWord => "%D",
                AddrSize::LWord => "%L",
            });
            let _ = write!(out, "{index}");
        }
        ExprKind::Deref(b) => {
            write_expr(out, interner, b, d);
            out.push('^');
        }
        ExprKind::Paren(b) => {
            out.push('(');
            write_expr(out, interner, b, d);
            out.push(')');
        }
        ExprKind::Unary { op, operand } => {
            out.push_str(match op {
                UnaryOp::Neg => "-",
                UnaryOp::Plus => "+",
                UnaryOp::Not => "NOT ",
            });
            write_expr(out, interner, operand, d);
        }
        ExprKind::Binary { op, lhs, rhs } => {
            write_expr(out, interner, lhs, d);
            let _ = write!(out, " {} ", op.symbol());
            write_expr(out, interner, rhs, d);
        }
        ExprKind::Call { callee, .. } => {
            write_expr(out, interner, callee, d);
            out.push_str("(...)");
        }
        ExprKind::Address(a) => out.push_str(&address_text(a)),
        ExprKind::Literal(l) => match &l.kind {
            LitKind::Int(v) => {
                let _ = write!(out, "{v}");
            }
            LitKind::Real(r) => {
                let _ = write!(out, "{r:?}");
            }
            LitKind::Bool(b) => out.push_str(if *b { "TRUE" } else { "FALSE" }),
            LitKind::String { value, wide } => {
                let q = if *wide { '"' } else { '\'' };
                let _ = write!(out, "{q}{value}{q}");
            }
            LitKind::Enum(i) => out.push_str(interner.name(i.sym)),
            _ => out.push_str("literal"),
        },
        ExprKind::Error => out.push('?'),
    }
}
