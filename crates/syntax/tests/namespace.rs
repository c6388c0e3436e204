//! NAMESPACE and USING as parsed, and as `desugar_namespaces` flattens
//! them: the items' qualified names, the rewritten references, bad input.

mod common;

use automat_base::{FileId, Interner};
use automat_syntax::ast::{Body, ExprKind, Item, StmtKind, TypeSpec};
use common::{errors, ok};

#[test]
fn namespaces_nest_and_hold_items_and_usings() {
    let out = ok("NAMESPACE A.B
USING C, D.E;
TYPE T : INT; END_TYPE
NAMESPACE INTERNAL Inner
FUNCTION F : INT F := 1; END_FUNCTION
END_NAMESPACE
END_NAMESPACE
PROGRAM P USING A.B;
VAR x : A.B.T; END_VAR
END_PROGRAM");
    let [Item::Namespace(n), Item::Namespace(p)] = out.unit.items.as_slice() else {
        panic!("{:?}", out.unit.items)
    };
    let name: Vec<String> = n.name.iter().map(|i| out.name(*i)).collect();
    assert_eq!(name, ["A", "B"]);
    assert_eq!(n.usings.len(), 2);
    assert_eq!(n.usings[1].path.len(), 2);
    let [Item::Types(_), Item::Namespace(inner)] = n.items.as_slice() else {
        panic!("{:?}", n.items)
    };
    assert!(inner.internal && matches!(inner.items.as_slice(), [Item::Pou(_)]));
    // A POU's USING: a namespace without a name around it.
    assert!(p.name.is_empty() && p.usings.len() == 1);
    let [Item::Pou(prog)] = p.items.as_slice() else {
        panic!("{:?}", p.items)
    };
    let TypeSpec::Named(t) = &prog.var_blocks[0].decls[0].ty else {
        panic!("{:?}", prog.var_blocks)
    };
    assert_eq!(out.name(*t), "A.B.T");
}

#[test]
fn a_missing_end_namespace_is_one_error() {
    assert_eq!(
        errors("NAMESPACE N\nFUNCTION F : INT F := 1; END_FUNCTION\n"),
        [("E005", 3)]
    );
    assert_eq!(
        errors("NAMESPACE N\nUSING ;\nEND_NAMESPACE\n"),
        [("E005", 2)]
    );
}

#[test]
fn flattening_renames_items_and_references() {
    let src = "NAMESPACE Motion
FUNCTION Clamp : INT
VAR_INPUT x : INT; END_VAR
    Clamp := x;
END_FUNCTION
FUNCTION Twice : INT
VAR_INPUT x : INT; END_VAR
VAR Clamp2 : INT; END_VAR
    Twice := Clamp(x) * 2;
END_FUNCTION
END_NAMESPACE
PROGRAM Main
VAR v : INT; END_VAR
    v := Motion.Twice(3);
END_PROGRAM";
    let mut interner = Interner::new();
    let parsed = automat_syntax::parse(FileId(0), src, &mut interner);
    assert!(parsed.diagnostics.is_empty(), "{:?}", parsed.diagnostics);
    let mut units = vec![parsed.unit];
    let diags = automat_syntax::desugar_namespaces(&mut units, &mut interner);
    assert!(diags.is_empty(), "{diags:?}");
    let names: Vec<&str> = units[0]
        .items
        .iter()
        .map(|i| match i {
            Item::Pou(p) => interner.name(p.name.sym),
            Item::Namespace(n) if n.items.is_empty() => "(namespace)",
            _ => "?",
        })
        .collect();
    assert_eq!(
        names,
        ["Motion.Clamp", "Motion.Twice", "(namespace)", "Main"]
    );
    // The function's result keeps matching its (new) name.
    let callee_of = |pou: usize| {
        let Item::Pou(p) = &units[0].items[if pou == 2 { 3 } else { pou }] else {
            panic!()
        };
        let Body::St(body) = &p.body;
        let StmtKind::Assign { target, value } = &body[0].kind else {
            panic!("{body:?}")
        };
        let target = match &target.kind {
            ExprKind::Name(n) => interner.name(n.sym).to_string(),
            k => format!("{k:?}"),
        };
        let mut e = value;
        if let ExprKind::Binary { lhs, .. } = &e.kind {
            e = lhs;
        }
        let ExprKind::Call { callee, .. } = &e.kind else {
            return (target, String::new());
        };
        let ExprKind::Name(n) = &callee.kind else {
            panic!("{callee:?}")
        };
        (target, interner.name(n.sym).to_string())
    };
    assert_eq!(callee_of(0), ("Motion.Clamp".into(), String::new()));
    assert_eq!(callee_of(1), ("Motion.Twice".into(), "Motion.Clamp".into()));
    assert_eq!(callee_of(2), ("v".into(), "Motion.Twice".into()));
}

#[test]
fn deep_namespaces_do_not_overflow() {
    let n = 100_000;
    let src = "NAMESPACE N ".repeat(n) + &"END_NAMESPACE ".repeat(n);
    let mut interner = Interner::new();
    let parsed = automat_syntax::parse(FileId(0), &src, &mut interner);
    assert!(parsed
        .diagnostics
        .iter()
        .any(|d| d.message.contains("too deep")));
    let mut units = vec![parsed.unit];
    automat_syntax::desugar_namespaces(&mut units, &mut interner);
}
