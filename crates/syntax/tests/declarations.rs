mod common;
use automat_syntax::ast::*;
use common::{decls, ok, types};

#[test]
fn pous_of_every_kind() {
    let out = ok(
        "FUNCTION f : INT\nVAR_INPUT a : INT; END_VAR\nf := a;\nEND_FUNCTION\n\
                  FUNCTION g\nEND_FUNCTION\n\
                  FUNCTION_BLOCK fb\nVAR_OUTPUT q : BOOL; END_VAR\nEND_FUNCTION_BLOCK\n\
                  PROGRAM main\nEND_PROGRAM\n",
    );
    let f = out.pou(0);
    assert_eq!((f.kind, out.name(f.name)), (PouKind::Function, "f".into()));
    assert_eq!(
        f.return_type.as_ref().map(|t| out.ty(t)),
        Some("INT".into())
    );
    assert_eq!(out.stmts(out.body(0)), "[f := a]");
    assert_eq!(out.pou(1).return_type, None);
    assert_eq!(out.pou(2).kind, PouKind::FunctionBlock);
    assert_eq!(out.pou(2).var_blocks[0].kind, VarKind::Output);
    assert_eq!(out.pou(3).kind, PouKind::Program);
    assert_eq!(out.text(out.pou(3).span), "PROGRAM main\nEND_PROGRAM");
}

#[test]
fn var_sections_and_qualifiers() {
    let out = ok("PROGRAM p\n\
        VAR a : INT; END_VAR\n\
        VAR_INPUT b : BOOL; END_VAR\n\
        VAR_OUTPUT c : BOOL; END_VAR\n\
        VAR_IN_OUT d : INT; END_VAR\n\
        VAR_EXTERNAL e : INT; END_VAR\n\
        VAR_GLOBAL f : INT; END_VAR\n\
        VAR_TEMP g : INT; END_VAR\n\
        VAR CONSTANT h : INT := 1; END_VAR\n\
        VAR RETAIN i : INT; END_VAR\n\
        VAR NON_RETAIN CONSTANT j : INT := 2; END_VAR\n\
        VAR_GLOBAL CONSTANT RETAIN k : INT := 3; END_VAR\n\
        END_PROGRAM");
    let blocks = &out.pou(0).var_blocks;
    let kinds: Vec<VarKind> = blocks.iter().map(|b| b.kind).collect();
    use VarKind::*;
    assert_eq!(
        kinds,
        vec![Local, Input, Output, InOut, External, Global, Temp, Local, Local, Local, Global]
    );
    let q: Vec<(bool, Retain)> = blocks[7..].iter().map(|b| (b.constant, b.retain)).collect();
    assert_eq!(
        q,
        vec![
            (true, Retain::Unspecified),
            (false, Retain::Retain),
            (true, Retain::NonRetain),
            (true, Retain::Retain)
        ]
    );
}

#[test]
fn variable_declarations() {
    assert_eq!(
        decls(
            "a, b : INT := 5;\n\
             s : STRING[20] := 'x';\n\
             s2 : STRING(20);\n\
             w : WSTRING[n + 1];\n\
             x AT %IX0.1 : BOOL;\n\
             AT %QW4 : WORD;\n\
             y AT %I* : BOOL;\n\
             z AT %QW* : WORD;\n\
             e : BOOL R_EDGE;\n\
             f : BOOL F_EDGE;\n\
             t : TON := (PT := T#1s);\n\
             r : REF_TO INT;\n\
             ptr : POINTER TO BYTE;\n\
             k : INT (0..100) := 50;\n\
             c : (Red, Green) := Green;"
        ),
        vec![
            "a,b : INT := 5;",
            "s : STRING[20] := \"x\";",
            "s2 : STRING[20];",
            "w : WSTRING[(+ n 1)];",
            "x AT %IX0.1 : BOOL;",
            " AT %QW4 : WORD;",
            "y AT %I* : BOOL;",
            "z AT %QW* : WORD;",
            "e : BOOL R_EDGE;",
            "f : BOOL F_EDGE;",
            "t : TON := (PT:=T#1000000000ns);",
            "r : REF_TO INT;",
            "ptr : REF_TO BYTE;",
            "k : INT(0..100) := 50;",
            "c : (Red,Green) := Green;",
        ]
    );
}

#[test]
fn arrays_and_initialisers() {
    assert_eq!(
        decls(
            "a : ARRAY [1..3] OF INT := [1, 2, 3(7)];\n\
             b : ARRAY [0..1, 1..2] OF INT := [2([1, 2])];\n\
             c : ARRAY [1..5] OF INT := [5()];\n\
             d : ARRAY [1..2] OF ARRAY [0..N-1] OF STRING[10];\n\
             e : ARRAY [*] OF REAL;\n\
             f : ARRAY [1..2] OF Point := [(x := 1, y := 2), (x := 3)];\n\
             g : ARRAY [1..2] OF TON;\n\
             h : Pt := (x := 1, sub := (a := [1, 2], b := TRUE));\n\
             i : INT := (1 + 2) * 3;"
        ),
        vec![
            "a : ARRAY[1..3] OF INT := [1,2,3(7)];",
            "b : ARRAY[0..1,1..2] OF INT := [2([1,2])];",
            "c : ARRAY[1..5] OF INT := [5()];",
            "d : ARRAY[1..2] OF ARRAY[0..(- N 1)] OF STRING[10];",
            "e : ARRAY[*] OF REAL;",
            "f : ARRAY[1..2] OF Point := [(x:=1,y:=2),(x:=3)];",
            "g : ARRAY[1..2] OF TON;",
            "h : Pt := (x:=1,sub:=(a:=[1,2],b:=TRUE));",
            "i : INT := (* (paren (+ 1 2)) 3);",
        ]
    );
}

#[test]
fn type_blocks() {
    assert_eq!(
        types(
            "MyInt : INT := 5;\n\
             Color : (Red, Green, Blue) := Red;\n\
             Level : INT (Low := 1, High := 2);\n\
             Mode : (Auto := 1, Manual := 2) DINT;\n\
             Percent : INT (0..100);\n\
             Vec : ARRAY [1..3] OF REAL;\n\
             Name : STRING[20];\n\
             Pt : STRUCT x : INT := 1; y : INT; END_STRUCT;\n\
             Nested : STRUCT p : Pt := (x := 2); a : ARRAY [1..2] OF STRUCT q : BOOL; END_STRUCT; END_STRUCT\n\
             IntRef : REF_TO INT;"
        ),
        vec![
            "MyInt : INT := 5",
            "Color : (Red,Green,Blue) := Red",
            "Level : INT (Low:=1,High:=2)",
            "Mode : DINT (Auto:=1,Manual:=2)",
            "Percent : INT(0..100)",
            "Vec : ARRAY[1..3] OF REAL",
            "Name : STRING[20]",
            "Pt : STRUCT x : INT := 1; y : INT; END_STRUCT",
            "Nested : STRUCT p : Pt := (x:=2); a : ARRAY[1..2] OF STRUCT q : BOOL; END_STRUCT; END_STRUCT",
            "IntRef : REF_TO INT",
        ]
    );
}

#[test]
fn top_level_globals() {
    let out =
        ok("VAR_GLOBAL\n  g : INT;\nEND_VAR\nVAR_GLOBAL CONSTANT\n  N : INT := 10;\nEND_VAR\n");
    let [Item::Globals(a), Item::Globals(b)] = out.unit.items.as_slice() else {
        panic!("{:?}", out.unit.items)
    };
    assert_eq!(
        (a.kind, a.constant, a.decls.len()),
        (VarKind::Global, false, 1)
    );
    assert_eq!((b.kind, b.constant), (VarKind::Global, true));
    assert_eq!(out.decl(&b.decls[0]), "N : INT := 10;");
}

#[test]
fn declaration_spans() {
    let out = ok("PROGRAM p\nVAR\n  a, b : INT := 5; (* c *)\nEND_VAR\nEND_PROGRAM");
    let blk = &out.pou(0).var_blocks[0];
    assert_eq!(
        out.text(blk.span),
        "VAR\n  a, b : INT := 5; (* c *)\nEND_VAR"
    );
    assert_eq!(out.text(blk.decls[0].span), "a, b : INT := 5");
    let loc = ok("PROGRAM p VAR x AT %IX1.2 : BOOL; END_VAR END_PROGRAM");
    let d = &loc.pou(0).var_blocks[0].decls[0];
    assert_eq!(loc.text(d.location.as_ref().unwrap().span), "AT %IX1.2");
    assert_eq!(loc.text(d.location.as_ref().unwrap().addr.span), "%IX1.2");
}
