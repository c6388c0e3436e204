//! The object-oriented parts of IEC 61131-3 3rd edition as parsed:
//! classes, interfaces, methods, properties, and their contextual words.

mod common;

use automat_syntax::ast::oop::{ClassKind, Visibility};
use automat_syntax::ast::{Item, VarKind};
use common::{errors, ok};

#[test]
fn function_block_with_methods_is_a_class() {
    let out = ok("FUNCTION_BLOCK ABSTRACT A EXTENDS B IMPLEMENTS I, J
VAR_INPUT x : INT; END_VAR
METHOD PRIVATE FINAL M : INT
VAR_INPUT n : INT; END_VAR
VAR t : INT; END_VAR
    M := n + x;
END_METHOD
METHOD ABSTRACT OVERRIDE N
END_METHOD
PROPERTY PROTECTED P : INT
GET
    P := x;
END_GET
SET
    x := P;
END_SET
END_PROPERTY
    x := M(1);
END_FUNCTION_BLOCK");
    let [Item::Class(c)] = out.unit.items.as_slice() else {
        panic!("{:?}", out.unit.items)
    };
    assert_eq!(c.kind, ClassKind::FunctionBlock);
    assert_eq!(out.name(c.name), "A");
    assert!(c.is_abstract && !c.is_final);
    assert_eq!(c.extends.map(|b| out.name(b)).as_deref(), Some("B"));
    let imps: Vec<String> = c.implements.iter().map(|i| out.name(*i)).collect();
    assert_eq!(imps, ["I", "J"]);
    assert_eq!(c.var_blocks.len(), 1);
    assert_eq!(c.methods.len(), 2);
    let m = &c.methods[0];
    assert_eq!(out.name(m.name), "M");
    assert_eq!(m.visibility, Visibility::Private);
    assert!(m.is_final && !m.is_abstract && m.return_type.is_some());
    let kinds: Vec<VarKind> = m.var_blocks.iter().map(|b| b.kind).collect();
    assert_eq!(kinds, [VarKind::Input, VarKind::Local]);
    assert_eq!(m.body.len(), 1);
    let n = &c.methods[1];
    assert!(n.is_abstract && n.is_override && n.body.is_empty() && n.return_type.is_none());
    let p = &c.properties[0];
    assert_eq!(p.visibility, Visibility::Protected);
    assert!(p.get.is_some() && p.set.is_some());
    assert_eq!(c.body.len(), 1);
}

#[test]
fn plain_function_block_stays_a_pou_and_words_are_names() {
    let out = ok("FUNCTION_BLOCK F
VAR get, set, method, final : INT; END_VAR
    get := set;
    method := final;
END_FUNCTION_BLOCK");
    assert!(matches!(out.unit.items.as_slice(), [Item::Pou(_)]));
}

#[test]
fn class_interface_and_methods_after_the_body() {
    let out = ok("CLASS FINAL K
VAR v : INT; END_VAR
METHOD Get : INT
    Get := v;
END_METHOD
END_CLASS
INTERFACE I EXTENDS J, L
METHOD Start : BOOL
VAR_INPUT fast : BOOL; END_VAR
END_METHOD
PROPERTY Speed : INT
GET END_GET
END_PROPERTY
END_INTERFACE
FUNCTION_BLOCK F
VAR_OUTPUT q : INT; END_VAR
    q := q + 1;
METHOD Late : INT
    Late := q;
END_METHOD
END_FUNCTION_BLOCK");
    let [Item::Class(k), Item::Interface(i), Item::Class(f)] = out.unit.items.as_slice() else {
        panic!("{:?}", out.unit.items)
    };
    assert_eq!(k.kind, ClassKind::Class);
    assert!(k.is_final && k.body.is_empty() && k.methods.len() == 1);
    assert_eq!(i.extends.len(), 2);
    assert_eq!(i.methods.len(), 1);
    assert_eq!(i.properties.len(), 1);
    assert_eq!(f.body.len(), 1);
    assert_eq!(f.methods.len(), 1);
}

#[test]
fn unclosed_method_is_one_error() {
    assert_eq!(
        errors("FUNCTION_BLOCK F\nMETHOD M : INT\n    M := 1;\nEND_FUNCTION_BLOCK"),
        [("E005", 4)]
    );
}
