//! Located variables (`AT %IX0.1`): the address size must fit the type
//! (bit → BOOL, byte → 8-bit types, word → 16-bit, double word → 32-bit,
//! long word → 64-bit; arrays by their element type; structures and
//! strings only at byte addresses), and a partly specified address (`%I*`)
//! is only allowed in a PROGRAM, a FUNCTION_BLOCK or a configuration.

use super::{Builder, Owner};
use crate::names::address_text;
use crate::types::{Elem, TypeId, TypeKind};
use automat_base::{Code, Diagnostic};
use automat_syntax::ast::{AddrSize, Ident, Location, PouKind};

/// The width in bits an address size selects (`None`: a bit).
pub(crate) fn size_bits(size: AddrSize) -> u32 {
    match size {
        AddrSize::None | AddrSize::Bit => 1,
        AddrSize::Byte => 8,
        AddrSize::Word => 16,
        AddrSize::DWord => 32,
        AddrSize::LWord => 64,
    }
}

/// The bit string an address of this size holds when read directly.
pub(crate) fn size_elem(size: AddrSize) -> Elem {
    match size {
        AddrSize::None | AddrSize::Bit => Elem::Bool,
        AddrSize::Byte => Elem::Byte,
        AddrSize::Word => Elem::Word,
        AddrSize::DWord => Elem::Dword,
        AddrSize::LWord => Elem::Lword,
    }
}

impl<'a> Builder<'a> {
    pub(super) fn check_location(&mut self, loc: &Location, ty: TypeId, owner: Owner, name: Ident) {
        let a = &loc.addr;
        if a.partial {
            let allowed = match owner {
                Owner::Pou(p) => self
                    .pous
                    .get(p.0 as usize)
                    .is_some_and(|e| e.ast.kind != PouKind::Function),
                Owner::Config(_) | Owner::Resource(..) => true,
                Owner::Project => false,
            };
            if !allowed {
                self.emit(Diagnostic::error(
                    Code::E084,
                    a.span,
                    format!(
                        "the partly specified address {} is only allowed in a PROGRAM, FUNCTION_BLOCK or configuration",
                        address_text(a)
                    ),
                ));
                return;
            }
            if a.size == AddrSize::None {
                return;
            }
        }
        if ty == TypeId::ERROR || self.location_fits(a.size, ty) {
            return;
        }
        let (n, tn) = (self.name(name.sym), self.type_name(ty));
        let need = match a.size {
            AddrSize::None | AddrSize::Bit => "a bit address needs BOOL",
            AddrSize::Byte => "a byte address needs an 8-bit type",
            AddrSize::Word => "a word address needs a 16-bit type",
            AddrSize::DWord => "a double word address needs a 32-bit type",
            AddrSize::LWord => "a long word address needs a 64-bit type",
        };
        self.emit(Diagnostic::error(
            Code::E084,
            a.span,
            format!(
                "`{n}` of type {tn} cannot be located at {}: {need}",
                address_text(a)
            ),
        ));
    }

    fn location_fits(&self, size: AddrSize, ty: TypeId) -> bool {
        match self.types.get(ty) {
            TypeKind::Array { elem, .. } => self.location_fits(size, *elem),
            TypeKind::Struct { .. } | TypeKind::String { .. } => size == AddrSize::Byte,
            TypeKind::Enum { base, .. } => elem_fits(size, *base),
            _ => match self.types.elem(ty) {
                Some(e) => elem_fits(size, e),
                None => false,
            },
        }
    }
}

fn elem_fits(size: AddrSize, e: Elem) -> bool {
    let bits = size_bits(size);
    if bits == 1 {
        return e == Elem::Bool;
    }
    e != Elem::Bool && e.bits() == bits
}
