//! Parser tests of textual SFC: exact chart trees (printed compactly with
//! names and values, spans left out), the rewriting's declarations, the
//! chart diagnostics, and ST bodies that use the contextual keywords.

use crate::ast::sfc::{ActionBody, Chart, Condition};
use crate::ast::{Body, ExprKind, Item, Lang, LitKind, Pou, TypeSpec};
use automat_base::{Code, FileId, Interner};

fn parse(src: &str) -> (Vec<Pou>, Vec<(Code, String)>, Interner) {
    let mut i = Interner::new();
    let p = crate::parse(FileId(0), src, &mut i);
    let pous = p
        .unit
        .items
        .into_iter()
        .filter_map(|it| match it {
            Item::Pou(p) => Some(p),
            _ => None,
        })
        .collect();
    let diags = p
        .diagnostics
        .iter()
        .map(|d| (d.code, d.message.clone()))
        .collect();
    (pous, diags, i)
}

fn expr_text(e: &crate::ast::Expr, i: &Interner) -> String {
    match &e.kind {
        ExprKind::Name(id) => i.name(id.sym).to_string(),
        ExprKind::Member { base, member } => {
            format!("{}.{}", expr_text(base, i), i.name(member.sym))
        }
        ExprKind::Literal(l) => match l.kind {
            LitKind::Duration { nanos, .. } => format!("{}ms", nanos / 1_000_000),
            LitKind::Bool(b) => b.to_string(),
            LitKind::Int(v) => v.to_string(),
            _ => "lit".to_string(),
        },
        ExprKind::Binary { op, lhs, rhs } => {
            format!(
                "({} {} {})",
                expr_text(lhs, i),
                op.symbol(),
                expr_text(rhs, i)
            )
        }
        _ => "?".to_string(),
    }
}

/// One line per element: what the tree holds, in source order.
fn dump(c: &Chart, i: &Interner) -> String {
    let mut out = Vec::new();
    for s in &c.steps {
        let assocs: Vec<String> = s
            .assocs
            .iter()
            .map(|a| {
                let mut parts = vec![a.qualifier.name().to_string()];
                parts.extend(a.time.iter().map(|t| expr_text(t, i)));
                parts.extend(a.indicators.iter().map(|n| i.name(n.sym).to_string()));
                format!("{}({})", i.name(a.name.sym), parts.join(", "))
            })
            .collect();
        let kw = if s.initial { "INITIAL_STEP" } else { "STEP" };
        out.push(format!("{kw} {}: {}", i.name(s.name.sym), assocs.join(" ")));
    }
    for t in &c.transitions {
        let names = |l: &[crate::ast::Ident]| {
            l.iter()
                .map(|n| i.name(n.sym))
                .collect::<Vec<_>>()
                .join(",")
        };
        let cond = match &t.cond {
            Condition::St(e) => expr_text(e, i),
            Condition::Il { il, .. } => format!("IL[{}]", il.instrs.len()),
            Condition::Missing => "-".to_string(),
        };
        out.push(format!(
            "TRANSITION {} {:?} {} -> {} := {cond}",
            t.name.map_or("_", |n| i.name(n.sym)),
            t.priority,
            names(&t.from),
            names(&t.to)
        ));
    }
    for a in &c.actions {
        let body = match &a.body {
            ActionBody::St(s) => format!("ST[{}]", s.len()),
            ActionBody::Il { il, .. } => format!("IL[{}]", il.instrs.len()),
        };
        out.push(format!("ACTION {}: {body}", i.name(a.name.sym)));
    }
    out.join("\n")
}

const CHART: &str = "
FUNCTION_BLOCK Fb
VAR
    lamp, ind : BOOL;
    t : TIME;
    n : INT;
END_VAR
    INITIAL_STEP Idle:
        lamp(N, ind);
    END_STEP
    TRANSITION Go (PRIORITY := 3) FROM Idle TO (A, B) := n > 0; END_TRANSITION
    STEP A:
        Work(L, T#250ms);
        Work(R);
        lamp();
    END_STEP
    step B:
        Work(SD, t, ind);
    END_STEP
    TRANSITION FROM (A, B) TO Idle :
        LD A.T
        GT T#1s
    END_TRANSITION
    ACTION Work:
        n := n + 1;
        n := n * 2;
    END_ACTION
    ACTION Other:
        LD n
        ST n
    END_ACTION
END_FUNCTION_BLOCK
";

#[test]
fn chart_tree_is_exact() {
    let (pous, _, i) = parse(CHART);
    let Some(Lang::Sfc(chart)) = pous.first().map(|p| &p.lang) else {
        panic!("not a chart");
    };
    assert_eq!(
        dump(chart, &i),
        "INITIAL_STEP Idle: lamp(N, ind)
STEP A: Work(L, 250ms) Work(R) lamp(N)
STEP B: Work(SD, t, ind)
TRANSITION Go Some(3) Idle -> A,B := (n > 0)
TRANSITION _ None A,B -> Idle := IL[2]
ACTION Work: ST[2]
ACTION Other: IL[2]"
    );
}

#[test]
fn chart_declares_hidden_state_and_warns() {
    let (pous, diags, i) = parse(CHART);
    let pou = pous.first().expect("one POU");
    let decls: Vec<String> = pou
        .var_blocks
        .iter()
        .flat_map(|b| b.decls.iter())
        .flat_map(|d| {
            let ty = match &d.ty {
                TypeSpec::Named(n) => i.name(n.sym).to_string(),
                _ => "?".to_string(),
            };
            d.names
                .iter()
                .map(|n| format!("{}:{ty}", i.name(n.sym)))
                .collect::<Vec<_>>()
        })
        .collect();
    assert_eq!(
        decls.join(" "),
        "lamp:BOOL ind:BOOL t:TIME n:INT Idle:__SFC_INITIAL_STEP A:__SFC_STEP B:__SFC_STEP \
         Work:__SFC_ACTION Other:__SFC_ACTION __sfc_v2:__SFC_ACTION __sfc_run:BOOL \
         __sfc_last:TIME __sfc_dt:TIME __sfc_t0:BOOL __sfc_t1:BOOL"
    );
    let Body::St(stmts) = &pou.body;
    // clock (3) + 3 step ticks + Work: 2 timed settings (L, SD) + 1 call;
    // Other: 1 call; lamp: call + assignment; 2 bodies; 2 x (flag reset +
    // IF); 3 step updates.
    assert_eq!(stmts.len(), 3 + 3 + 3 + 1 + 2 + 2 + 4 + 3);
    // A and B are parallel branches: Work's L and SD can be active together.
    assert_eq!(
        diags,
        vec![
            (
                Code::E128,
                "`Work` has two timed associations that can be active together".to_string()
            ),
            (
                Code::W122,
                "action `Other` is associated with no step and never runs".to_string()
            )
        ]
    );
}

#[test]
fn structural_warnings() {
    let src = "PROGRAM P
    INITIAL_STEP S0: END_STEP
    TRANSITION FROM S0 TO S1 := TRUE; END_TRANSITION
    STEP S1: END_STEP
    STEP Lost: END_STEP
    TRANSITION FROM (S1, Lost) TO S2 := TRUE; END_TRANSITION
    STEP S2: END_STEP
END_PROGRAM";
    let (_, diags, _) = parse(src);
    let codes: Vec<Code> = diags.iter().map(|d| d.0).collect();
    // Lost is never active, so the convergence never fires: S2 is
    // unreachable too (the exploration of markings sees it).
    assert_eq!(codes, vec![Code::W120, Code::W120, Code::W121]);
    assert_eq!(diags[0].1, "step `Lost` can never become active");
    assert_eq!(diags[1].1, "step `S2` can never become active");
    assert_eq!(
        diags[2].1,
        "no transition leaves step `S2`: once active, it stays active"
    );
}

#[test]
fn st_bodies_keep_step_action_transition_as_names() {
    let src = "PROGRAM P
VAR step, action, transition : INT; END_VAR
    step := 1;
    action := step + 1;
    transition := action;
END_PROGRAM";
    let (pous, diags, _) = parse(src);
    assert!(diags.is_empty(), "{diags:?}");
    let pou = pous.first().expect("one POU");
    assert_eq!(pou.lang, Lang::St);
    let Body::St(stmts) = &pou.body;
    assert_eq!(stmts.len(), 3);
}

#[test]
fn chart_errors_are_reported_once() {
    let src = "PROGRAM P
VAR x : INT; END_VAR
    INITIAL_STEP S0: A(Q); END_STEP
    TRANSITION (PRIORITY := x) FROM S0 TO Nope := TRUE; END_TRANSITION
    ACTION A: x := 1; END_ACTION
END_PROGRAM";
    let (_, diags, _) = parse(src);
    let codes: Vec<Code> = diags.iter().map(|d| d.0).collect();
    assert_eq!(codes, vec![Code::E126, Code::E130, Code::E121]);
}

#[test]
fn truncated_charts_never_panic() {
    for end in 0..=CHART.len() {
        if CHART.is_char_boundary(end) {
            let _ = parse(&CHART[..end]);
        }
    }
}
