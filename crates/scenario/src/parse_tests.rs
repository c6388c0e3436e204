use super::*;

fn ok(text: &str) -> Scenario {
    parse(text, FileId(0), "default").unwrap_or_else(|e| panic!("{e:?}"))
}

fn err(text: &str) -> (Code, u32, String) {
    let e = parse(text, FileId(0), "x").expect_err("should fail");
    (e[0].code, e[0].span.start, e[0].message.clone())
}

#[test]
fn the_contract_example() {
    let s = ok(r#"name "normal cycle"   # comment
duration 60s
seed 7
at 1s press Pornire for 200ms
at 2s set Selector = 2
at 5s release Pornire
at 10s stuck l2 = TRUE
at 30s unstick l2
at 0s noise Temp 20
at 3s plant bottle capped=0
expect at 2s M2S
expect M1D within 30s after 1s
expect always NOT (M1S AND M1D)
expect always M2S during 2s..5s
expect never M1S AND M1D
expect at 40s Ctrl.step = CraneStep#Rest1 AND plant.x < 0.05
"#);
    assert_eq!(s.name, "normal cycle");
    assert_eq!((s.duration_ns, s.seed), (60_000_000_000, Some(7)));
    assert_eq!(s.actions.len(), 7);
    assert_eq!(s.actions[0].at_ns, 1_000_000_000);
    assert!(
        matches!(&s.actions[0].kind, ActionKind::Press(n, Some(200_000_000)) if n.text == "Pornire")
    );
    assert!(
        matches!(&s.actions[1].kind, ActionKind::Set(n, Lit::Int(2), _) if n.text == "Selector")
    );
    assert!(matches!(&s.actions[4].kind, ActionKind::Unstick(_)));
    assert!(matches!(&s.actions[5].kind, ActionKind::Noise(_, a) if *a == 20.0));
    assert!(
        matches!(&s.actions[6].kind, ActionKind::Plant(n, a) if n.text == "bottle" && a == &[("capped".to_string(), 0.0)])
    );
    assert_eq!(s.expects.len(), 6);
    assert_eq!(s.expects[0].when, When::At(2_000_000_000));
    assert_eq!(s.expects[0].text, "at 2s M2S");
    assert_eq!(s.expects[0].line, 11);
    assert_eq!(
        s.expects[1].when,
        When::Within {
            after: Anchor::Time(1_000_000_000),
            within: 30_000_000_000
        }
    );
    assert_eq!(s.expects[2].when, When::Always { from: 0, to: None });
    assert_eq!(
        s.expects[3].when,
        When::Always {
            from: 2_000_000_000,
            to: Some(5_000_000_000)
        }
    );
    assert!(
        matches!(&s.expects[4].cond, Expr::Not(inner) if matches!(**inner, Expr::Logic(LogicOp::And, _, _)))
    );
    let Expr::Logic(LogicOp::And, a, b) = &s.expects[5].cond else {
        panic!()
    };
    assert!(
        matches!(&**a, Expr::Cmp(CmpOp::Eq, _, r) if matches!(&**r, Expr::Lit(Lit::Enum(t, v), _) if t == "CraneStep" && v == "Rest1"))
    );
    assert!(
        matches!(&**b, Expr::Cmp(CmpOp::Lt, _, r) if matches!(&**r, Expr::Lit(Lit::Real(x), _) if *x == 0.05))
    );
}

#[test]
fn not_binds_tighter_than_and_and_names_default() {
    let s = ok("duration 1s\nexpect always NOT a AND b\n");
    assert_eq!(s.name, "default");
    assert!(
        matches!(&s.expects[0].cond, Expr::Logic(LogicOp::And, a, _) if matches!(**a, Expr::Not(_)))
    );
}

#[test]
fn errors_point_at_the_token() {
    // line 2 starts at byte 12
    assert_eq!(
        err("duration 1s\nat 1x press a\n"),
        (Code::E320, 15, "`1x` is not a valid TIME literal: `x` is not a unit (d, h, m, s, ms, us, ns) (write a duration like `10ms` or `T#1s500ms`)".to_string())
    );
    assert_eq!(err("duration 1s\nat 1s jump a\n").0, Code::E320);
    assert_eq!(
        err("duration 1s\nexpect a within 1s\n").2,
        "expected `after`"
    );
    assert_eq!(
        err("duration 1s\nexpect always a during 5s..1s\n").2,
        "the range `5s..1s` ends before it starts"
    );
    assert_eq!(
        err("duration 1s\nfoo\n").2,
        "unknown statement `foo` (want `name`, `duration`, `seed`, `at`, `when` or `expect`)"
    );
    assert_eq!(err("duration 1s\nexpect at 1s (a\n").2, "expected `)`");
    assert_eq!(
        err("duration 1s extra\n").2,
        "unexpected text at the end of the line"
    );
    assert_eq!(err("expect at 1s a\n").0, Code::E323);
}

/// Found by `tests/robust.rs`: 100 000 `NOT`s or `(`s, or a very long
/// `AND` chain, overflowed the stack of the recursive parser (and of the
/// checker). They are E320 at the operand past the limit now.
#[test]
fn deep_or_long_conditions_are_errors_not_stack_overflows() {
    let deep_not = format!("duration 1s\nexpect at 1s {}x\n", "NOT ".repeat(100_000));
    let (code, at, msg) = err(&deep_not);
    assert_eq!(code, Code::E320);
    assert!(msg.contains("nest too deeply"), "{msg}");
    // At the operand after the NOT that opens one level too many.
    assert_eq!(
        at as usize,
        "duration 1s\nexpect at 1s ".len() + 4 * (MAX_NESTING + 1)
    );
    let deep_paren = format!("duration 1s\nexpect at 1s {}x\n", "(".repeat(100_000));
    assert!(err(&deep_paren).2.contains("nest too deeply"));
    let long = format!("duration 1s\nexpect always x{}\n", " AND x".repeat(100_000));
    let (code, _, msg) = err(&long);
    assert_eq!(code, Code::E320);
    assert!(msg.contains("too long"), "{msg}");
    // The limits leave room for every real condition.
    let nested = format!(
        "duration 1s\nexpect at 1s {}x{}\n",
        "NOT (".repeat(MAX_NESTING / 2),
        ")".repeat(MAX_NESTING / 2)
    );
    assert_eq!(ok(&nested).expects.len(), 1);
    let chain = format!(
        "duration 1s\nexpect always x{}\n",
        " AND x".repeat(MAX_TERMS - 1)
    );
    assert_eq!(ok(&chain).expects.len(), 1);
    assert!(parse_action(&format!("press {}", "(".repeat(100_000)), FileId(0)).is_err());
}

/// The language of issue 17 point 3: arithmetic, functions, event anchors,
/// `stable`, `during` with `count`, reactions.
#[test]
fn arithmetic_events_counts_and_reactions() {
    let s = ok("duration 60s
expect always plant.T - Reg.T_sp < 1.0 * 2 + -0.5
expect NOT M2S within 20ms after rise(l2)
expect count(rise(valva_1)) <= 10 during 0s..60s
expect M1 stable for 500ms after rise(Start)
expect x stable during 1s..2s
expect always abs(a - b) < max(c, 2) MOD 3
expect at 1s prev(x) = -3 AND change(y)
when rise(Alarm) then press Pc for 200ms
when fall(l1) after 1.5s then set n = -2
");
    // Precedence: `*` before `+`/`-` before `<`.
    let Expr::Cmp(CmpOp::Lt, l, r) = &s.expects[0].cond else {
        panic!("{:?}", s.expects[0].cond)
    };
    assert!(matches!(&**l, Expr::Arith(ArithOp::Sub, a, b)
        if matches!(&**a, Expr::Ref(n) if n.text == "plant.T") && matches!(&**b, Expr::Ref(n) if n.text == "Reg.T_sp")));
    assert!(matches!(&**r, Expr::Arith(ArithOp::Add, m, n)
        if matches!(&**m, Expr::Arith(ArithOp::Mul, ..)) && matches!(&**n, Expr::Lit(Lit::Real(x), _) if *x == -0.5)));
    assert!(matches!(&s.expects[1].when,
        When::Within { after: Anchor::Event(Expr::Call(Func::Rise, a, _)), within: 20_000_000 }
            if matches!(&a[..], [Expr::Ref(n)] if n.text == "l2")));
    assert_eq!(
        s.expects[2].when,
        When::During {
            from: 0,
            to: 60_000_000_000
        }
    );
    assert!(
        matches!(&s.expects[2].cond, Expr::Cmp(CmpOp::Le, c, _) if matches!(&**c, Expr::Call(Func::Count, ..)))
    );
    assert!(matches!(
        &s.expects[3].when,
        When::Stable {
            after: Anchor::Event(_),
            for_ns: 500_000_000
        }
    ));
    assert_eq!(
        s.expects[4].when,
        When::Stable {
            after: Anchor::Time(1_000_000_000),
            for_ns: 1_000_000_000
        }
    );
    assert!(matches!(&s.expects[5].cond, Expr::Cmp(CmpOp::Lt, a, m)
        if matches!(&**a, Expr::Call(Func::Abs, ..)) && matches!(&**m, Expr::Arith(ArithOp::Mod, ..))));
    assert_eq!(s.reactions.len(), 2);
    assert!(
        matches!(&s.reactions[0].kind, ActionKind::Press(n, Some(200_000_000)) if n.text == "Pc")
    );
    assert_eq!(s.reactions[1].delay_ns, 1_500_000_000);
    assert!(matches!(
        &s.reactions[1].kind,
        ActionKind::Set(_, Lit::Int(-2), _)
    ));
    assert_eq!(s.reactions[1].line, 10);
}

#[test]
fn errors_of_the_new_constructs() {
    assert_eq!(
        err("duration 1s\nexpect x during 0s..1s\n").2,
        "`expect C during A..B` judges C once at B, for conditions with count(...); write `expect always C during A..B` for C at every scan"
    );
    assert_eq!(
        err("duration 1s\nexpect min(a) < 1 within 1s after 0s\n").2,
        "expected `,`: min(...) takes 2 arguments"
    );
    assert_eq!(
        err("duration 1s\nwhen rise(a) press b\n").2,
        "expected `then`"
    );
    assert_eq!(
        err("duration 1s\nexpect x stable after 1s\n").2,
        "expected `for`"
    );
    assert_eq!(
        err("duration 1s\nexpect x\n").2,
        "expected `within`, `stable` or `during` (or write `expect at T C`, `expect always C`)"
    );
    // A name that happens to be a function's name is a name without `(`.
    let s = ok("duration 1s\nexpect at 1s count > 2\n");
    assert!(
        matches!(&s.expects[0].cond, Expr::Cmp(_, c, _) if matches!(&**c, Expr::Ref(n) if n.text == "count"))
    );
}

/// Every nesting construct is bounded, and hostile lines are refused at
/// once (parse, and the action reader of the live console).
#[test]
fn every_nesting_construct_is_bounded() {
    for open in [
        "(", "NOT ", "- ", "rise(", "abs(", "min(1, ", "prev(", "count(",
    ] {
        let line = format!("duration 1s\nexpect at 1s {}x\n", open.repeat(50_000));
        let t0 = std::time::Instant::now();
        let (code, _, msg) = err(&line);
        assert_eq!(code, Code::E320, "{open}");
        assert!(msg.contains("nest too deeply"), "{open}: {msg}");
        assert!(
            t0.elapsed() < std::time::Duration::from_millis(500),
            "{open}"
        );
    }
    for line in [
        format!("duration 1s\nat 0s press {}\n", "(".repeat(100_000)),
        format!("duration 1s\nwhen {}x then press a\n", "(".repeat(100_000)),
        format!(
            "duration 1s\nexpect x within 1s after {}x\n",
            "(".repeat(100_000)
        ),
        format!("duration 1s\nexpect always x{}\n", " + x".repeat(100_000)),
    ] {
        let t0 = std::time::Instant::now();
        assert_eq!(err(&line).0, Code::E320);
        assert!(t0.elapsed() < std::time::Duration::from_millis(500));
    }
}
