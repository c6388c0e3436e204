//! The symbol table stays small for types that refer to each other: a
//! linked list of a base class (whose hidden interface holds one reference
//! per class) once grew a tree exponential in its depth, so `automat
//! check` of a 40-line program took 48 s and gigabytes.

mod common;
use automat_ir::SymbolType;
use common::*;

fn nodes(t: &SymbolType) -> usize {
    1 + match t {
        SymbolType::Array { elem, .. } => nodes(elem),
        SymbolType::Struct { fields, .. } => fields.iter().map(|f| nodes(&f.ty)).sum(),
        SymbolType::Ref(t) => nodes(t),
        _ => 0,
    }
}

#[test]
fn a_linked_list_of_a_base_class_has_a_small_symbol_tree() {
    let p = build(
        "CLASS Node
         VAR val : INT; next : REF_TO Node; END_VAR
         METHOD PUBLIC Peek : INT Peek := val; END_METHOD
         END_CLASS
         CLASS Tagged EXTENDS Node
         VAR tag : INT; END_VAR
         METHOD PUBLIC OVERRIDE Peek : INT Peek := tag; END_METHOD
         END_CLASS
         CLASS Mark EXTENDS Tagged
         END_CLASS
         PROGRAM Main
         VAR a : Node; b : Tagged; c : Mark; n : INT; END_VAR
         n := a.Peek() + b.Peek() + c.Peek();
         END_PROGRAM",
    );
    let total: usize = p
        .engine
        .program()
        .symbols
        .entries()
        .iter()
        .map(|e| nodes(&e.ty))
        .sum();
    assert!(total < 20_000, "{total} symbol nodes");
}
