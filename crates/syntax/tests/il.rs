//! Instruction List: body detection, the IL tree as written, and the exact
//! ST it is desugared into (printed as S-expressions by `common`).

mod common;
use automat_syntax::ast::il::{IlBody, Instr, InstrKind, Op, When};
use automat_syntax::ast::*;
use common::{errors, ok, Out};

fn il(src: &str) -> Out {
    ok(&format!(
        "PROGRAM p\nVAR x, y, z : BOOL; i : INT; t : TON; END_VAR\n{src}\nEND_PROGRAM\n"
    ))
}

fn st(src: &str) -> String {
    let out = il(src);
    out.stmts(out.body(0))
}

fn tree(out: &Out) -> &IlBody {
    match &out.pou(0).lang {
        Lang::Il(b) => b,
        other => panic!("not an IL body: {other:?}"),
    }
}

/// One instruction as `label: OP operand` text, groups with their lines.
fn show(out: &Out, i: &Instr) -> String {
    let mut s = i
        .label
        .map(|l| format!("{}: ", out.name(l)))
        .unwrap_or_default();
    let when = |w: &When| match w {
        When::Always => "",
        When::IfTrue => "C",
        When::IfFalse => "CN",
    };
    s.push_str(&match &i.kind {
        InstrKind::Nothing => "-".into(),
        InstrKind::Simple { op, operand, .. } => match operand {
            Some(e) => format!("{} {}", op.name(), out.expr(e)),
            None => op.name().into(),
        },
        InstrKind::Group {
            op, first, body, ..
        } => {
            let inner: Vec<String> = body.iter().map(|i| show(out, i)).collect();
            let first = first.as_ref().map(|e| out.expr(e)).unwrap_or_default();
            format!("{}({first} [{}])", op.name(), inner.join(", "))
        }
        InstrKind::Call { name, args, formal } => {
            let a: Vec<String> = args.iter().map(|a| out.arg(a)).collect();
            format!(
                "{}{} {}",
                if *formal { "formal " } else { "" },
                out.name(*name),
                a.join(", ")
            )
        }
        InstrKind::Cal {
            when: w, fb, args, ..
        } => {
            let a: Vec<String> = args.iter().map(|a| out.arg(a)).collect();
            format!("CAL{} {}({})", when(w), out.expr(fb), a.join(", "))
        }
        InstrKind::FbInput { input, fb } => format!("{} {}", out.name(*input), out.expr(fb)),
        InstrKind::Jump { when: w, label, .. } => format!("JMP{} {}", when(w), out.name(*label)),
        InstrKind::Ret { when: w, .. } => format!("RET{}", when(w)),
        InstrKind::Error => "<error>".into(),
    });
    s
}

fn lines(out: &Out) -> Vec<String> {
    tree(out).instrs.iter().map(|i| show(out, i)).collect()
}

#[test]
fn an_arithmetic_chain_is_one_expression() {
    let out = il("LD i\nADD 2\nMUL( i\nSUB 1\n)\nST i");
    assert_eq!(lines(&out), ["LD i", "ADD 2", "MUL(i [SUB 1])", "ST i"]);
    assert_eq!(out.stmts(out.body(0)), "[i := (* (+ i 2) (paren (- i 1)))]");
}

#[test]
fn st_twice_reads_the_first_target_back() {
    assert_eq!(
        st("LD x\nAND y\nST z\nSTN x"),
        "[z := (AND x y); x := (not z)]"
    );
    // A plain variable stays the CR (with its own type).
    assert_eq!(st("LD i\nST i\nST i"), "[i := i; i := i]");
    assert_eq!(st("LD x\nST y\nSTN z"), "[y := x; z := (not x)]");
    // A literal is reloaded as it is.
    assert_eq!(st("LD 5\nST i\nST i"), "[i := 5; i := 5]");
}

#[test]
fn modifiers_negate_the_operand() {
    assert_eq!(
        st("LDN x\nANDN y\nORN z\nXORN x\n&N y\n& z\nNOT\nST x"),
        "[x := (not (AND (AND (XOR (OR (AND (not x) (not y)) (not z)) (not x)) (not y)) z))]"
    );
}

#[test]
fn comparisons_and_every_arithmetic_operator() {
    assert_eq!(
        st("LD i\nADD 1\nSUB 2\nMUL 3\nDIV 4\nMOD 5\nGT 0\nST x\nLD i\nGE 1\nEQ y\nNE z\nST x\nLD i\nLE 2\nST x\nLD i\nLT 3\nST x"),
        "[x := (> (MOD (/ (* (- (+ i 1) 2) 3) 4) 5) 0); x := (<> (= (>= i 1) y) z); x := (<= i 2); x := (< i 3)]"
    );
}

#[test]
fn set_and_reset_keep_a_condition_still_needed_in_a_hidden_bool() {
    // Only S reads the CR: no hidden variable.
    assert_eq!(st("LD x\nS y"), "[IF x [y := TRUE]]");
    let out = il("LD x\nAND y\nR x\nS z");
    assert_eq!(
        out.stmts(out.body(0)),
        "[__CR := (AND x y); IF __CR [x := FALSE]; IF __CR [z := TRUE]]"
    );
    let hidden = out.pou(0).var_blocks.last().expect("hidden block");
    assert_eq!(hidden.kind, VarKind::Temp);
    assert_eq!(out.decl(&hidden.decls[0]), "__CR : BOOL;");
}

#[test]
fn labels_jumps_and_returns() {
    let out = il("top: LD i\nADD 1\nST i\nLT 10\nJMPC top\nJMPCN out\nRETC\nRETCN\nout:\nRET");
    assert_eq!(
        lines(&out),
        [
            "top: LD i",
            "ADD 1",
            "ST i",
            "LT 10",
            "JMPC top",
            "JMPCN out",
            "RETC",
            "RETCN",
            "out: -",
            "RET"
        ]
    );
    assert_eq!(
        out.stmts(out.body(0)),
        "[top:; i := (+ i 1); __CR := (< i 10); IF __CR [GOTO top]; IF (not __CR) [GOTO out]; IF __CR [RETURN]; IF (not __CR) [RETURN]; out:; RETURN]"
    );
}

#[test]
fn function_calls_take_the_current_result_first() {
    assert_eq!(
        st("LD i\nLIMIT 0, 10\nABS\nST i\nLIMIT(MN := 0, IN := i, MX := 5)\nST i"),
        "[i := (call ABS (call LIMIT i 0 10)); i := (call LIMIT (MN := 0) (IN := i) (MX := 5))]"
    );
}

#[test]
fn fb_calls_and_input_operators() {
    let out = il("CAL t(IN := x, PT := T#1s)\nLD x\nCALC t\nCALCN t()\nLD T#2s\nPT t\nLD y\nIN t");
    assert_eq!(
        lines(&out),
        [
            "CAL t((IN := x), (PT := T#1000000000ns))",
            "LD x",
            "CALC t()",
            "CALCN t()",
            "LD T#2000000000ns",
            "PT t",
            "LD y",
            "IN t"
        ]
    );
    assert_eq!(
        out.stmts(out.body(0)),
        "[(call t (IN := x) (PT := T#1000000000ns)); __CR := x; IF __CR [(call t)]; IF (not __CR) [(call t)]; (call t (PT := T#2000000000ns)); (call t (IN := y))]"
    );
}

#[test]
fn groups_nest_in_long_and_short_form() {
    let out = il("LD x\nAND( LD y\nOR( z\nANDN x\n)\n)\nORN( y\n)\nST z");
    assert_eq!(
        lines(&out),
        ["LD x", "AND( [LD y, OR(z [ANDN x])])", "ORN(y [])", "ST z"]
    );
    assert_eq!(
        out.stmts(out.body(0)),
        "[z := (OR (AND x (paren (OR y (paren (AND z (not x)))))) (not (paren y)))]"
    );
}

#[test]
fn spans_point_at_the_il_lines() {
    let out = il("LD i\nADD 1\nST i");
    let StmtKind::Assign { value, .. } = &out.body(0)[0].kind else {
        panic!("not an assignment")
    };
    assert_eq!(out.text(value.span), "ADD 1");
    assert_eq!(out.text(out.body(0)[0].span), "ST i");
}

#[test]
fn comments_do_not_end_or_join_lines() {
    assert_eq!(
        st("LD x (* a comment *) // and another\n(* a comment\n over lines *) ST y"),
        "[y := x]"
    );
}

#[test]
fn st_bodies_that_start_with_operator_names_stay_st() {
    let out = ok("PROGRAM p\nVAR ld, s : INT; END_VAR\nld := 1;\ns := ld;\nEND_PROGRAM\n");
    assert_eq!(out.pou(0).lang, Lang::St);
    let out = ok("FUNCTION_BLOCK f\nVAR r : RS; END_VAR\nr(S := TRUE);\nEND_FUNCTION_BLOCK\n");
    assert_eq!(out.pou(0).lang, Lang::St);
}

#[test]
fn il_in_functions_and_function_blocks() {
    let out = ok("FUNCTION f : INT\nVAR_INPUT a : INT; END_VAR\nLD a\nADD 1\nST f\nEND_FUNCTION\nFUNCTION_BLOCK g\nVAR_OUTPUT q : BOOL; END_VAR\nLD TRUE\nST q\nEND_FUNCTION_BLOCK\n");
    assert_eq!(out.stmts(out.body(0)), "[f := (+ a 1)]");
    assert_eq!(out.stmts(out.body(1)), "[q := TRUE]");
    assert!(matches!(out.pou(1).lang, Lang::Il(_)));
}

#[test]
fn errors_have_il_codes_at_their_lines() {
    let p = |body: &str| format!("PROGRAM p\nVAR x : BOOL; END_VAR\n{body}\nEND_PROGRAM\n");
    assert_eq!(errors(&p("ST x")), [("E100", 3)]);
    assert_eq!(errors(&p("L: ST x")), [("E101", 3)]);
    assert_eq!(errors(&p("LD x\nJMP L\nAND x")), [("E100", 5)]);
    assert_eq!(errors(&p("LD\nST x")), [("E102", 3)]);
    assert_eq!(errors(&p("LD x\nNOT x")), [("E103", 4)]);
    assert_eq!(errors(&p("LD x ST x")), [("E103", 3)]);
    assert_eq!(errors(&p("LD x\nSTC x")), [("E104", 4)]);
    assert_eq!(errors(&p("LD x\nAND( x\nST x\n)")), [("E108", 5)]);
    assert_eq!(errors(&p("LD x\n)")), [("E109", 4)]);
    assert_eq!(errors(&p("LD x\nAND( x")), [("E109", 4)]);
    assert_eq!(errors(&p("LD x\nST 1")), [("E110", 4)]);
    assert_eq!(errors(&p("LD x\nAND( )\nST x")), [("E102", 4)]);
}

#[test]
fn a_current_result_deeper_than_the_limit_is_refused() {
    let mut body = String::from("LD 1\n");
    for _ in 0..300 {
        body.push_str("ADD 1\n");
    }
    body.push_str("ST i\n");
    let src = format!("PROGRAM p\nVAR i : INT; END_VAR\n{body}END_PROGRAM\n");
    let errs = errors(&src);
    assert_eq!(errs.len(), 1);
    assert_eq!(errs[0].0, "E005");
}

#[test]
fn op_table_round_trips() {
    for w in [
        "LD", "LDN", "ST", "STN", "S", "R", "AND", "ANDN", "OR", "ORN", "XOR", "XORN", "NOT",
        "ADD", "SUB", "MUL", "DIV", "MOD", "GT", "GE", "EQ", "NE", "LE", "LT",
    ] {
        assert_eq!(Op::from_word(w).map(Op::name), Some(w));
    }
}
