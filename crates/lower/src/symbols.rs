//! The symbol table entries: declared variables by qualified name, with
//! their layout-level types.

use crate::layout::Layout;
use automat_base::{Interner, SourceMap, Symbol};
use automat_iec::Elementary;
use automat_ir::{Field, SymbolType};
use automat_sema::model::Section;
use automat_sema::types::{Elem, TypeId, TypeKind};
use automat_syntax::ast::{Item, SourceUnit, TypeSpec};
use rustc_hash::FxHashMap;

/// The IEC value type of a checker elementary type. An exhaustive match, so
/// a type added to either enum is a compile error here rather than a silent
/// mismatch. (The checker's `Elem` and `automat_iec::Elementary` should
/// become one type; until then this is the only bridge.)
pub fn elementary(e: Elem) -> Elementary {
    use Elementary as E;
    match e {
        Elem::Bool => E::Bool,
        Elem::Sint => E::Sint,
        Elem::Int => E::Int,
        Elem::Dint => E::Dint,
        Elem::Lint => E::Lint,
        Elem::Usint => E::Usint,
        Elem::Uint => E::Uint,
        Elem::Udint => E::Udint,
        Elem::Ulint => E::Ulint,
        Elem::Real => E::Real,
        Elem::Lreal => E::Lreal,
        Elem::Byte => E::Byte,
        Elem::Word => E::Word,
        Elem::Dword => E::Dword,
        Elem::Lword => E::Lword,
        Elem::Time => E::Time,
        Elem::Ltime => E::Ltime,
        Elem::Date => E::Date,
        Elem::Ldate => E::Ldate,
        Elem::Tod => E::Tod,
        Elem::Ltod => E::Ltod,
        Elem::Dt => E::Dt,
        Elem::Ldt => E::Ldt,
        Elem::Char => E::Char,
        Elem::Wchar => E::Wchar,
    }
}

/// How enumeration types and values were declared (`CraneStep`, `Rest1`),
/// so that values print as the user wrote them (`CraneStep#Rest1`) whatever
/// spelling the interner saw first; the first declaration wins.
pub fn spellings(units: &[SourceUnit], sources: &SourceMap) -> FxHashMap<Symbol, String> {
    let mut out = FxHashMap::default();
    for u in units {
        for item in &u.items {
            let Item::Types(block) = item else { continue };
            for d in &block.decls {
                let TypeSpec::Enum { values, .. } = &d.spec else {
                    continue;
                };
                out.entry(d.name.sym)
                    .or_insert_with(|| sources.text(d.name.span).to_string());
                for v in values {
                    out.entry(v.name.sym)
                        .or_insert_with(|| sources.text(v.name.span).to_string());
                }
            }
        }
    }
    out.retain(|_, s: &mut String| !s.is_empty());
    out
}

fn spelled(layout: &Layout, interner: &Interner, sym: Symbol) -> String {
    layout
        .spellings
        .get(&sym)
        .cloned()
        .unwrap_or_else(|| interner.name(sym).to_string())
}

/// The layout-level type of a sema type.
pub fn symbol_type(layout: &mut Layout, interner: &Interner, ty: TypeId, depth: u32) -> SymbolType {
    symbol_type_in(layout, interner, ty, depth, 0)
}

/// How many references deep the tree goes: a linked list (`next : REF_TO
/// Node`) is shown this many links deep. Types that refer to each other
/// through several references (a base class's hidden interface holds one
/// per class that extends it) would otherwise grow a tree exponential in
/// the depth. Only names (`--print`, the online API) stop at this depth;
/// the program's code follows references however deep.
const REF_DEPTH: usize = 4;

fn symbol_type_in(
    layout: &mut Layout,
    interner: &Interner,
    ty: TypeId,
    depth: u32,
    refs: usize,
) -> SymbolType {
    let model = layout.model;
    if depth > 64 {
        return SymbolType::Struct {
            name: "?".into(),
            fields: Vec::new(),
        };
    }
    match model.types.get(ty).clone() {
        TypeKind::Error => SymbolType::Struct {
            name: "?".into(),
            fields: Vec::new(),
        },
        TypeKind::Elem(e) => SymbolType::Elementary(elementary(e)),
        TypeKind::String { wide: false, len } => SymbolType::String { cap: len },
        TypeKind::String { wide: true, len } => SymbolType::WString { cap: len },
        TypeKind::Array { elem, dims } => SymbolType::Array {
            stride: layout.stride(elem),
            elem: Box::new(symbol_type_in(layout, interner, elem, depth + 1, refs)),
            dims: layout.dims(&dims),
        },
        TypeKind::Struct { name, members } => {
            let offs = layout.fields(ty);
            let fields = members
                .iter()
                .zip(offs)
                .map(|(m, offset)| Field {
                    name: interner.name(m.name).to_string(),
                    offset,
                    bit: None,
                    ty: symbol_type_in(layout, interner, m.ty, depth + 1, refs),
                })
                .collect();
            SymbolType::Struct {
                name: name.map_or_else(String::new, |n| interner.name(n).to_ascii_uppercase()),
                fields,
            }
        }
        TypeKind::Enum { name, base, values } => SymbolType::Enum {
            name: name.map_or_else(String::new, |n| spelled(layout, interner, n)),
            base: elementary(base),
            values: values
                .iter()
                .map(|v| (spelled(layout, interner, v.name), v.value as i64))
                .collect(),
        },
        TypeKind::Subrange { base, lo, hi } => SymbolType::Subrange {
            base: elementary(base),
            lo: lo as i64,
            hi: hi as i64,
        },
        TypeKind::Fb { pou, name } | TypeKind::Program { pou, name } => {
            let l = layout.pou(pou);
            let mut fields = Vec::new();
            if let Some(p) = model.pou(pou) {
                for (v, slot) in p.vars.vars.iter().zip(l.slots.iter()) {
                    // The standard blocks (TON, CTU, ...) show their interface
                    // only: their private state is an implementation detail.
                    if p.builtin
                        && !matches!(v.section, Section::Input | Section::Output | Section::InOut)
                    {
                        continue;
                    }
                    if let crate::layout::Slot::Rel(offset) = slot {
                        let t = symbol_type_in(layout, interner, v.ty, depth + 1, refs);
                        fields.push(Field {
                            name: interner.name(v.name).to_string(),
                            offset: *offset,
                            bit: None,
                            ty: if v.section == Section::InOut {
                                SymbolType::Ref(Box::new(t))
                            } else {
                                t
                            },
                        });
                    }
                }
            }
            SymbolType::Struct {
                name: interner.name(name).to_ascii_uppercase(),
                fields,
            }
        }
        TypeKind::Ref(t) => {
            if refs >= REF_DEPTH {
                return SymbolType::Ref(Box::new(SymbolType::Struct {
                    name: "?".into(),
                    fields: Vec::new(),
                }));
            }
            let target = symbol_type_in(layout, interner, t, depth + 1, refs + 1);
            SymbolType::Ref(Box::new(target))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_checker_type_maps_to_the_iec_type_of_the_same_name_and_width() {
        for e in Elem::ALL {
            let iec = elementary(e);
            assert_eq!(iec.name(), e.name(), "{e:?}");
            assert_eq!(iec.bit_width(), Some(e.bits()), "{e:?}");
            assert_eq!(iec.is_int(), e.is_int(), "{e:?}");
            assert_eq!(iec.is_real(), e.is_real(), "{e:?}");
        }
    }
}
