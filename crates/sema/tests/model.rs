//! The semantic model handed to lowering: types with folded bounds,
//! ordered variables with folded initial values, the standard library,
//! expression typing on demand.

mod common;
use automat_sema::model::{Section, UnitRef};
use automat_sema::types::{Dim, Elem, TypeId, TypeKind};
use automat_sema::value::{ArrayInit, Init, Value};
use automat_sema::{PouId, Ty};
use automat_syntax::ast::{Item, PouKind, StmtKind};
use common::analyze;

const SRC: &str = "VAR_GLOBAL CONSTANT N : INT := 4; END_VAR
TYPE
    Buf : ARRAY[0..N - 1] OF REAL;
    Mode : (Idle, Run := 5, Stop);
    Pt : STRUCT x : INT := 1; y : INT; END_STRUCT;
    MyInt : INT := 7;
END_TYPE
FUNCTION Twice : DINT
VAR_INPUT x : INT; END_VAR
    Twice := x * 2;
END_FUNCTION
PROGRAM Main
VAR
    b : Buf;
    m : Mode := Run;
    p : Pt;
    k : MyInt;
    s : STRING[N * 5] := 'hi';
    arr : ARRAY[1..3] OF INT := [2(9)];
    t : TON;
END_VAR
VAR RETAIN counter : UDINT; END_VAR
    b[0] := DINT_TO_REAL(Twice(k));
END_PROGRAM";

#[test]
fn types_are_folded() {
    let (_, interner, a) = analyze(SRC);
    assert!(a.diagnostics.is_empty(), "{:?}", a.diagnostics);
    let m = &a.model;
    let sym = |s: &str| interner.lookup(s).unwrap();
    let buf = m.type_names[&sym("Buf")];
    assert_eq!(
        m.types.get(buf),
        &TypeKind::Array {
            elem: TypeId::elem(Elem::Real),
            dims: vec![Dim::Range(0, 3)]
        }
    );
    let mode = m.type_names[&sym("Mode")];
    match m.types.get(mode) {
        TypeKind::Enum { values, base, .. } => {
            let v: Vec<i128> = values.iter().map(|v| v.value).collect();
            assert_eq!(v, [0, 5, 6]);
            assert_eq!(*base, Elem::Int);
        }
        k => panic!("{k:?}"),
    }
    match m.types.get(m.type_names[&sym("Pt")]) {
        TypeKind::Struct { members, .. } => {
            assert_eq!(members.len(), 2);
            assert_eq!(members[0].init, Some(Init::Value(Value::Int(1))));
            assert_eq!(members[1].init, None);
        }
        k => panic!("{k:?}"),
    }
    assert_eq!(m.type_names[&sym("MyInt")], TypeId::elem(Elem::Int));
}

#[test]
fn variables_are_ordered_with_folded_initial_values() {
    let (_, interner, a) = analyze(SRC);
    let m = &a.model;
    let sym = |s: &str| interner.lookup(s).unwrap();
    let (_, main) = m.pou_named(sym("Main")).unwrap();
    let names: Vec<&str> = main
        .vars
        .vars
        .iter()
        .map(|v| interner.name(v.name))
        .collect();
    assert_eq!(names, ["b", "m", "p", "k", "s", "arr", "t", "counter"]);
    let var = |n: &str| main.vars.get(sym(n)).unwrap();
    assert_eq!(var("m").init, Some(Init::Value(Value::Enum(5))));
    assert_eq!(var("k").init, Some(Init::Value(Value::Int(7))));
    assert_eq!(
        m.types.get(var("s").ty),
        &TypeKind::String {
            wide: false,
            len: 20
        }
    );
    assert_eq!(
        var("arr").init,
        Some(Init::Array(vec![ArrayInit {
            repeat: 2,
            value: Some(Init::Value(Value::Int(9)))
        }]))
    );
    assert_eq!(var("counter").retain, automat_syntax::ast::Retain::Retain);
    assert_eq!(var("counter").section, Section::Local);
    let ton = m.pou_named(sym("TON")).unwrap().1;
    assert!(ton.builtin);
    assert_eq!(ton.ast.unit, UnitRef::Std);
    assert_eq!(
        m.types.get(var("t").ty),
        &TypeKind::Fb {
            pou: m.pou_names[&sym("TON")],
            name: sym("TON")
        }
    );
    let (_, twice) = m.pou_named(sym("Twice")).unwrap();
    assert_eq!(twice.vars.vars[0].section, Section::Return);
    assert_eq!(twice.vars.vars[0].ty, TypeId::elem(Elem::Dint));
    assert_eq!(twice.vars.index(sym("x")), Some(1));
    assert_eq!(twice.return_type, Some(TypeId::elem(Elem::Dint)));
    let g = m.globals.get(sym("N")).unwrap();
    assert!(g.constant);
    assert_eq!(g.init, Some(Init::Value(Value::Int(4))));
}

#[test]
fn standard_function_blocks_have_the_standard_interfaces() {
    let (_, interner, a) = analyze("");
    let m = &a.model;
    let iface = |n: &str| -> Vec<(String, Section, String)> {
        let (_, p) = m.pou_named(interner.lookup(n).unwrap()).unwrap();
        assert_eq!(p.kind, PouKind::FunctionBlock);
        p.params()
            .map(|(_, v)| {
                (
                    interner.name(v.name).to_string(),
                    v.section,
                    automat_sema::names::type_name(&m.types, &interner, v.ty),
                )
            })
            .collect()
    };
    let s = |n: &str, sec: Section, t: &str| (n.to_string(), sec, t.to_string());
    use Section::{Input as I, Output as O};
    assert_eq!(
        iface("SR"),
        [s("S1", I, "BOOL"), s("R", I, "BOOL"), s("Q1", O, "BOOL")]
    );
    assert_eq!(
        iface("RS"),
        [s("S", I, "BOOL"), s("R1", I, "BOOL"), s("Q1", O, "BOOL")]
    );
    assert_eq!(iface("R_TRIG"), [s("CLK", I, "BOOL"), s("Q", O, "BOOL")]);
    assert_eq!(iface("F_TRIG"), [s("CLK", I, "BOOL"), s("Q", O, "BOOL")]);
    for (n, t) in [
        ("TON", "TIME"),
        ("TOF", "TIME"),
        ("TP", "TIME"),
        ("LTON", "LTIME"),
        ("LTOF", "LTIME"),
        ("LTP", "LTIME"),
    ] {
        assert_eq!(
            iface(n),
            [
                s("IN", I, "BOOL"),
                s("PT", I, t),
                s("Q", O, "BOOL"),
                s("ET", O, t)
            ],
            "{n}"
        );
    }
    for (suffix, t) in [
        ("", "INT"),
        ("_INT", "INT"),
        ("_DINT", "DINT"),
        ("_LINT", "LINT"),
        ("_UDINT", "UDINT"),
        ("_ULINT", "ULINT"),
    ] {
        assert_eq!(
            iface(&format!("CTU{suffix}")),
            [
                s("CU", I, "BOOL"),
                s("R", I, "BOOL"),
                s("PV", I, t),
                s("Q", O, "BOOL"),
                s("CV", O, t)
            ]
        );
        assert_eq!(
            iface(&format!("CTD{suffix}")),
            [
                s("CD", I, "BOOL"),
                s("LD", I, "BOOL"),
                s("PV", I, t),
                s("Q", O, "BOOL"),
                s("CV", O, t)
            ]
        );
        assert_eq!(
            iface(&format!("CTUD{suffix}")),
            [
                s("CU", I, "BOOL"),
                s("CD", I, "BOOL"),
                s("R", I, "BOOL"),
                s("LD", I, "BOOL"),
                s("PV", I, t),
                s("QU", O, "BOOL"),
                s("QD", O, "BOOL"),
                s("CV", O, t)
            ]
        );
    }
}

#[test]
fn standard_library_source_checks_clean() {
    let (_, mut interner, _) = analyze("");
    let unit = automat_syntax::parse(
        automat_base::FileId(0),
        automat_sema::stdlib::FB_SOURCE,
        &mut interner,
    );
    assert!(unit.diagnostics.is_empty(), "{:?}", unit.diagnostics);
    let a = automat_sema::check(&[unit.unit], &mut interner);
    assert!(a.diagnostics.is_empty(), "{:?}", a.diagnostics);
}

#[test]
fn expression_types_on_demand() {
    let mut map = automat_base::SourceMap::new();
    map.add("t.st", SRC);
    let mut interner = automat_base::Interner::new();
    let (units, a) = automat_sema::check_sources(&map, &mut interner);
    let main = a.model.pou_names[&interner.lookup("Main").unwrap()];
    let pou = units[0]
        .items
        .iter()
        .find_map(|i| match i {
            Item::Pou(p) if p.kind == PouKind::Program => Some(p),
            _ => None,
        })
        .unwrap();
    let automat_syntax::ast::Body::St(body) = &pou.body;
    let StmtKind::Assign { target, value } = &body[0].kind else {
        panic!()
    };
    let t = automat_sema::type_of(&a.model, &interner, main, target);
    assert_eq!(t.ty, Ty::Of(TypeId::elem(Elem::Real)));
    let v = automat_sema::type_of(&a.model, &interner, main, value);
    assert_eq!(v.ty, Ty::Of(TypeId::elem(Elem::Real)));
    assert_eq!(
        a.model.pou_ast(&units, main).map(|p| p.name.sym),
        Some(pou.name.sym)
    );
    assert!(a.model.pou(PouId(u32::MAX)).is_none());
}

#[test]
fn names_and_callees_resolve_for_lowering() {
    use automat_sema::{resolve_callee, resolve_name, CallTarget, NameRef};
    let src = "VAR_GLOBAL CONSTANT K : INT := 3; END_VAR
VAR_GLOBAL g : INT; END_VAR
TYPE Color : (Red, Green); END_TYPE
FUNCTION F : INT
VAR_INPUT x : INT; END_VAR
    F := x;
END_FUNCTION
PROGRAM Main
VAR_EXTERNAL g : INT; END_VAR
VAR t : TON; c : Color; END_VAR
    t(IN := TRUE);
    g := F(K) + LIMIT(0, g, 9);
    c := Green;
END_PROGRAM";
    let mut map = automat_base::SourceMap::new();
    map.add("t.st", src);
    let mut interner = automat_base::Interner::new();
    let (_, a) = automat_sema::check_sources(&map, &mut interner);
    assert!(a.diagnostics.is_empty(), "{:?}", a.diagnostics);
    let m = &a.model;
    let sym = |s: &str| interner.lookup(s).unwrap();
    let main = m.pou_names[&sym("Main")];
    assert_eq!(
        resolve_name(m, &interner, main, sym("g"), None),
        Some(NameRef::Local(0))
    );
    assert_eq!(
        resolve_name(m, &interner, main, sym("t"), None),
        Some(NameRef::Local(1))
    );
    assert_eq!(
        resolve_name(m, &interner, main, sym("K"), None),
        Some(NameRef::Global(0))
    );
    let color = m.type_names[&sym("Color")];
    assert_eq!(
        resolve_name(m, &interner, main, sym("Green"), None),
        Some(NameRef::Enum(color, 1))
    );
    let name = |s: &str| automat_syntax::ast::Expr {
        kind: automat_syntax::ast::ExprKind::Name(automat_syntax::ast::Ident {
            sym: sym(s),
            span: automat_base::Span::default(),
        }),
        span: automat_base::Span::default(),
    };
    assert_eq!(
        resolve_callee(m, &interner, main, &name("F")),
        Some(CallTarget::Function(m.pou_names[&sym("F")]))
    );
    assert_eq!(
        resolve_callee(m, &interner, main, &name("t")),
        Some(CallTarget::Instance(m.pou_names[&sym("TON")]))
    );
    match resolve_callee(m, &interner, main, &name("LIMIT")) {
        Some(CallTarget::Std(sig)) => assert_eq!(sig.op, automat_sema::stdlib::StdOp::Limit),
        other => panic!("{other:?}"),
    }
    assert_eq!(resolve_callee(m, &interner, main, &name("c")), None);
}
