//! Macro-steps run on the interpreter (rules: the module comment of
//! `automat_syntax`'s `desugar::sfc`, § Macro-steps). There is no textual
//! syntax for them, so each test writes the chart and every macro body as
//! textual charts of their own POUs, then moves each body chart into its
//! macro-step (`Step::macro_body`, as an importer builds it), drops the
//! body POU and desugars the chart again through the importers' entry
//! `automat_syntax::desugar_chart`. Scan k runs at PLC time (k - 1) × 10 ms.

mod common;
use common::*;

use automat_base::{FileId, Interner, SourceMap, Span};
use automat_engine::Engine;
use automat_lower::{lower, LowerOptions};
use automat_syntax::ast::sfc::MacroBody;
use automat_syntax::ast::{Ident, Item, Lang, Pou, SourceUnit, TypeSpec, VarBlock};

const MS: i64 = 1_000_000;

fn pou_mut<'u>(unit: &'u mut SourceUnit, name: &str, i: &Interner) -> &'u mut Pou {
    unit.items
        .iter_mut()
        .find_map(|it| match it {
            Item::Pou(p) if i.name(p.name.sym).eq_ignore_ascii_case(name) => Some(p),
            _ => None,
        })
        .unwrap_or_else(|| panic!("no POU {name}"))
}

/// Whether a block is the hidden declarations of a desugared chart.
fn is_hidden(b: &VarBlock, i: &Interner) -> bool {
    b.decls.iter().all(|d| {
        let hidden_ty = matches!(&d.ty, TypeSpec::Named(t) if i.name(t.sym).starts_with("__SFC"));
        hidden_ty || d.names.iter().all(|n| i.name(n.sym).starts_with("__"))
    })
}

/// Parses `src` and applies `macros` in order: `(pou, step, body, exit)`
/// moves the chart of POU `body` into step `step` of POU `pou` (exit step
/// `exit`) and removes POU `body`; then desugars every chart that got a
/// body again. Parse diagnostics of the re-desugared and removed POUs are
/// dropped (they were about the charts before the move).
fn with_macros(
    src: &str,
    macros: &[(&str, &str, &str, &str)],
    i: &mut Interner,
) -> (SourceUnit, Vec<automat_base::Diagnostic>) {
    let parsed = automat_syntax::parse(FileId(0), src, i);
    let mut unit = parsed.unit;
    let mut stale: Vec<Span> = Vec::new();
    let mut targets: Vec<String> = Vec::new();
    for &(pou, step, body, exit) in macros {
        let at = unit
            .items
            .iter()
            .position(
                |it| matches!(it, Item::Pou(p) if i.name(p.name.sym).eq_ignore_ascii_case(body)),
            )
            .unwrap_or_else(|| panic!("no POU {body}"));
        let Item::Pou(b) = unit.items.remove(at) else {
            unreachable!()
        };
        stale.push(b.span);
        let Lang::Sfc(chart) = b.lang else {
            panic!("{body} is not a chart")
        };
        let exit = Ident {
            sym: i.intern(exit),
            span: b.span,
        };
        let p = pou_mut(&mut unit, pou, i);
        let Lang::Sfc(c) = &mut p.lang else {
            panic!("{pou} is not a chart")
        };
        let s = c
            .steps
            .iter_mut()
            .find(|s| i.name(s.name.sym).eq_ignore_ascii_case(step))
            .unwrap_or_else(|| panic!("no step {step}"));
        s.macro_body = Some(Box::new(MacroBody {
            chart: *chart,
            exit,
        }));
        if !targets.iter().any(|t| t.eq_ignore_ascii_case(pou)) {
            targets.push(pou.to_string());
        }
    }
    let mut diags = Vec::new();
    for t in &targets {
        let Some(Item::Pou(p)) = unit
            .items
            .iter_mut()
            .find(|it| matches!(it, Item::Pou(p) if i.name(p.name.sym).eq_ignore_ascii_case(t)))
        else {
            continue; // itself moved into another chart
        };
        stale.push(p.span);
        let before = p.var_blocks.len();
        p.var_blocks.retain(|b| !is_hidden(b, i));
        assert_eq!(p.var_blocks.len() + 1, before, "one hidden block in {t}");
        diags.extend(automat_syntax::desugar_chart(p, i));
    }
    diags.extend(parsed.diagnostics.into_iter().filter(|d| {
        !stale
            .iter()
            .any(|s| s.start <= d.span.start && d.span.end <= s.end)
    }));
    (unit, diags)
}

fn build_macros(src: &str, macros: &[(&str, &str, &str, &str)]) -> Plc {
    let mut sources = SourceMap::new();
    let file = sources.add("test.st", src);
    assert_eq!(file, FileId(0));
    let mut i = Interner::new();
    let (unit, mut diags) = with_macros(src, macros, &mut i);
    let units = vec![unit];
    let analysis = automat_sema::check(&units, &mut i);
    diags.extend(analysis.diagnostics.iter().cloned());
    let msgs: Vec<String> = diags
        .iter()
        .map(|d| format!("{} {}", d.code.as_str(), d.message))
        .collect();
    assert!(msgs.is_empty(), "diagnostics: {msgs:#?}");
    let program = lower(&units, &analysis, &i, &sources, &LowerOptions::default())
        .unwrap_or_else(|d| panic!("lowering failed: {d:?}"));
    let inst = program
        .tasks
        .first()
        .and_then(|t| t.programs.first())
        .cloned()
        .expect("a program instance");
    Plc {
        engine: Engine::new(program),
        inst,
        now: 0,
    }
}

/// Runs scan `k` (1-based) at (k - 1) × 10 ms.
fn scan(p: &mut Plc, k: i64) {
    p.now = (k - 1) * 10 * MS;
    p.run(1);
}

/// The X flags of `steps`, as a string of 0/1.
fn flags(p: &Plc, steps: &[&str]) -> String {
    steps
        .iter()
        .map(|s| p.int(&format!("Main.{s}.X")).to_string())
        .collect()
}

const BASIC: &str = "
PROGRAM Main
VAR go : BOOL; cnt, m_runs, entries, exits : INT; END_VAR
    INITIAL_STEP S0: END_STEP
    TRANSITION FROM S0 TO M := go; END_TRANSITION
    STEP M: Mark(N); Enter(P1); Leave(P0); END_STEP
    TRANSITION FROM M TO S0 := TRUE; END_TRANSITION
    ACTION Mark: m_runs := m_runs + 1; END_ACTION
    ACTION Enter: entries := entries + 1; END_ACTION
    ACTION Leave: exits := exits + 1; END_ACTION
END_PROGRAM

FUNCTION_BLOCK Body
VAR go : BOOL; cnt, m_runs, entries, exits : INT; END_VAR
    INITIAL_STEP B1: Count(N); END_STEP
    TRANSITION FROM B1 TO B2 := B1.T >= T#20ms; END_TRANSITION
    STEP B2: END_STEP
    ACTION Count: cnt := cnt + 1; END_ACTION
END_FUNCTION_BLOCK
";

/// Entering M enters B1; the transition out of M (condition TRUE) waits for
/// the exit step B2 and leaves it; M.X is TRUE exactly while B1 or B2 is;
/// M.T counts from M's entry and is kept after M is left; M's own
/// associations (N, P1, P0) act as on a step active while M.X.
#[test]
fn macro_step_enters_its_initial_step_and_leaves_from_its_exit() {
    let mut p = build_macros(BASIC, &[("Main", "M", "Body", "B2")]);
    let steps = ["S0", "M", "B1", "B2"];
    scan(&mut p, 1);
    assert_eq!(flags(&p, &steps), "1000");
    p.set_int("Main.go", 1);
    // S0 -> M fires: M and its initial step B1 are entered together.
    scan(&mut p, 2);
    assert_eq!(flags(&p, &steps), "0110");
    assert_eq!((p.int("Main.M.T"), p.int("Main.B1.T")), (0, 0));
    p.set_int("Main.go", 0);
    // B1 active, the exit B2 not: M -> S0 (TRUE) is not enabled.
    scan(&mut p, 3);
    assert_eq!(flags(&p, &steps), "0110");
    assert_eq!(
        (
            p.int("Main.cnt"),
            p.int("Main.m_runs"),
            p.int("Main.entries")
        ),
        (1, 1, 1)
    );
    assert_eq!(p.int("Main.M.T"), 10 * MS as i128);
    // B1.T reaches 20 ms: B1 -> B2 inside the body; M stays active.
    scan(&mut p, 4);
    assert_eq!(flags(&p, &steps), "0101");
    assert_eq!((p.int("Main.cnt"), p.int("Main.m_runs")), (2, 2));
    // B2 is active: M -> S0 fires, leaving B2 and M.
    scan(&mut p, 5);
    assert_eq!(flags(&p, &steps), "1000");
    assert_eq!((p.int("Main.cnt"), p.int("Main.m_runs")), (3, 3));
    assert_eq!(p.int("Main.M.T"), 30 * MS as i128);
    assert_eq!(p.int("Main.exits"), 0);
    // The final scan of Mark, the P0 of Leave; M.T is kept.
    scan(&mut p, 6);
    assert_eq!(flags(&p, &steps), "1000");
    assert_eq!(
        (
            p.int("Main.cnt"),
            p.int("Main.m_runs"),
            p.int("Main.entries"),
            p.int("Main.exits")
        ),
        (3, 4, 1, 1)
    );
    assert_eq!(p.int("Main.M.T"), 30 * MS as i128);
    // Entered again: B1 is entered again and both times restart.
    p.set_int("Main.go", 1);
    scan(&mut p, 7);
    assert_eq!(flags(&p, &steps), "0110");
    assert_eq!((p.int("Main.M.T"), p.int("Main.B1.T")), (0, 0));
    scan(&mut p, 8);
    assert_eq!(p.int("Main.entries"), 2);
}

const NESTED: &str = "
PROGRAM Main
VAR go : BOOL; END_VAR
    INITIAL_STEP M: END_STEP
    TRANSITION FROM M TO Done := TRUE; END_TRANSITION
    STEP Done: END_STEP
    TRANSITION FROM Done TO M := go; END_TRANSITION
END_PROGRAM

FUNCTION_BLOCK Outer
VAR go : BOOL; END_VAR
    INITIAL_STEP N: END_STEP
    TRANSITION FROM N TO E2 := TRUE; END_TRANSITION
    STEP E2: END_STEP
END_FUNCTION_BLOCK

FUNCTION_BLOCK Inner
VAR go : BOOL; END_VAR
    INITIAL_STEP I1: END_STEP
    TRANSITION FROM I1 TO I2 := go; END_TRANSITION
    STEP I2: END_STEP
END_FUNCTION_BLOCK
";

/// Nested macro-steps: M (initial) holds N (its body's initial step), N
/// holds I1 -> I2. The chart starts with M, N and I1 active; leaving N
/// waits for I2, leaving M for E2; entering M again enters N and I1 in one
/// firing.
#[test]
fn nested_macro_steps_chain_entry_and_exit() {
    let mut p = build_macros(
        NESTED,
        &[("Outer", "N", "Inner", "I2"), ("Main", "M", "Outer", "E2")],
    );
    let steps = ["M", "N", "I1", "I2", "E2", "Done"];
    scan(&mut p, 1);
    assert_eq!(flags(&p, &steps), "111000");
    p.set_int("Main.go", 1);
    scan(&mut p, 2);
    assert_eq!(flags(&p, &steps), "110100");
    p.set_int("Main.go", 0);
    // N -> E2 leaves I2 and with it N; M stays active through E2.
    scan(&mut p, 3);
    assert_eq!(flags(&p, &steps), "100010");
    assert_eq!(
        (p.int("Main.M.T"), p.int("Main.N.T")),
        (20 * MS as i128, 20 * MS as i128)
    );
    scan(&mut p, 4);
    assert_eq!(flags(&p, &steps), "000001");
    assert_eq!(p.int("Main.M.T"), 30 * MS as i128);
    scan(&mut p, 5);
    assert_eq!(flags(&p, &steps), "000001");
    // Done -> M enters M, N and I1 together.
    p.set_int("Main.go", 1);
    scan(&mut p, 6);
    assert_eq!(flags(&p, &steps), "111000");
    assert_eq!((p.int("Main.M.T"), p.int("Main.N.T")), (0, 0));
}

/// A `jump` transition runs as the same transition drawn as a line.
#[test]
fn jump_transitions_run_like_ordinary_ones() {
    let src = "
PROGRAM Main
VAR n : INT; END_VAR
    INITIAL_STEP A: Inc(N); END_STEP
    TRANSITION FROM A TO B := A.T >= T#10ms; END_TRANSITION
    STEP B: END_STEP
    TRANSITION FROM B TO A := TRUE; END_TRANSITION
    ACTION Inc: n := n + 1; END_ACTION
END_PROGRAM
";
    let mut sources = SourceMap::new();
    sources.add("test.st", src);
    let mut i = Interner::new();
    let mut unit = automat_syntax::parse(FileId(0), src, &mut i).unit;
    let p = pou_mut(&mut unit, "Main", &i);
    p.var_blocks.retain(|b| !is_hidden(b, &i));
    if let Lang::Sfc(c) = &mut p.lang {
        for t in &mut c.transitions {
            t.jump = true;
        }
    }
    assert!(automat_syntax::desugar_chart(p, &mut i).is_empty());
    let units = vec![unit];
    let analysis = automat_sema::check(&units, &mut i);
    assert!(!analysis.has_errors(), "{:?}", analysis.diagnostics);
    let program = lower(&units, &analysis, &i, &sources, &LowerOptions::default())
        .unwrap_or_else(|d| panic!("{d:?}"));
    let inst = program.tasks[0].programs[0].clone();
    let mut jumped = Plc {
        engine: Engine::new(program),
        inst,
        now: 0,
    };
    let mut plain = build(src);
    for k in 1..=8 {
        scan(&mut jumped, k);
        scan(&mut plain, k);
        let got = (flags(&jumped, &["A", "B"]), jumped.int("Main.n"));
        assert_eq!(got, (flags(&plain, &["A", "B"]), plain.int("Main.n")));
    }
    // A -> B at scan 2 (A.T = 10 ms), then every scan (A.T is 10 ms again
    // one scan after A is entered); Inc runs every scan (final scans).
    assert_eq!(flags(&jumped, &["A", "B"]), "01");
    assert_eq!(jumped.int("Main.n"), 8);
}

/// A side effect in a transition condition inside a macro body is refused
/// like one in the chart itself (E127).
#[test]
fn a_side_effect_in_a_macro_body_condition_is_e127() {
    const SRC: &str = "
FUNCTION Bump : BOOL
VAR_IN_OUT x : INT; END_VAR
    x := x + 1;
    Bump := x > 3;
END_FUNCTION

PROGRAM Main
VAR go : BOOL; n : INT; END_VAR
    INITIAL_STEP S0: END_STEP
    TRANSITION FROM S0 TO M := go; END_TRANSITION
    STEP M: END_STEP
    TRANSITION FROM M TO S0 := TRUE; END_TRANSITION
END_PROGRAM

FUNCTION_BLOCK Body
VAR go : BOOL; n : INT; END_VAR
    INITIAL_STEP B1: END_STEP
    TRANSITION FROM B1 TO B2 := Bump(n); END_TRANSITION
    STEP B2: END_STEP
END_FUNCTION_BLOCK
";
    let mut i = Interner::new();
    let (unit, mut diags) = with_macros(SRC, &[("Main", "M", "Body", "B2")], &mut i);
    let analysis = automat_sema::check(&[unit], &mut i);
    diags.extend(analysis.diagnostics.iter().cloned());
    let codes: Vec<&str> = diags.iter().map(|d| d.code.as_str()).collect();
    assert_eq!(codes, ["E127"], "{diags:#?}");
}
