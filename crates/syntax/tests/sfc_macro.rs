//! Macro-steps and jumps through the importers' entry
//! `automat_syntax::desugar_chart`: the chart checks of macro bodies and the
//! hidden declarations. There is no textual syntax for a macro-step, so a
//! test writes each body as the chart of its own POU, moves it into the
//! macro-step (`Step::macro_body`, as an importer builds it), drops that POU
//! and desugars the chart again. Execution is pinned in
//! `crates/lower/tests/sfc_macro.rs`.

use automat_base::{Code, Diagnostic, FileId, Interner, Span};
use automat_syntax::ast::sfc::MacroBody;
use automat_syntax::ast::{Ident, Item, Lang, Pou, SourceUnit, TypeSpec, VarBlock};

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

/// Parses `src`, moves the chart of POU `Body` into step `M` of `Main`
/// with exit step `exit`, and desugars `Main` again. The diagnostics of
/// that desugaring (parse diagnostics of `Main` and `Body` are about the
/// charts before the move and are dropped).
fn macro_main(src: &str, exit: &str, i: &mut Interner) -> (SourceUnit, Vec<Diagnostic>) {
    let parsed = automat_syntax::parse(FileId(0), src, i);
    let mut unit = parsed.unit;
    let at = unit
        .items
        .iter()
        .position(|it| matches!(it, Item::Pou(p) if i.name(p.name.sym) == "Body"))
        .expect("a POU Body");
    let Item::Pou(body) = unit.items.remove(at) else {
        unreachable!()
    };
    let Lang::Sfc(chart) = body.lang else {
        panic!("Body is not a chart")
    };
    let exit = Ident {
        sym: i.intern(exit),
        span: Span::new(FileId(0), 0, 0),
    };
    let p = pou_mut(&mut unit, "Main", i);
    let Lang::Sfc(c) = &mut p.lang else {
        panic!("Main is not a chart")
    };
    let m = c
        .steps
        .iter_mut()
        .find(|s| i.name(s.name.sym) == "M")
        .expect("a step M");
    m.macro_body = Some(Box::new(MacroBody {
        chart: *chart,
        exit,
    }));
    p.var_blocks.retain(|b| !is_hidden(b, i));
    let diags = automat_syntax::desugar_chart(p, i);
    (unit, diags)
}

fn codes(d: &[Diagnostic]) -> Vec<(Code, String)> {
    d.iter().map(|d| (d.code, d.message.clone())).collect()
}

/// The hidden declarations of `Main`: `name: type` per line.
fn hidden_decls(unit: &mut SourceUnit, i: &Interner) -> Vec<String> {
    let p = pou_mut(unit, "Main", i);
    p.var_blocks
        .iter()
        .filter(|b| is_hidden(b, i))
        .flat_map(|b| b.decls.iter())
        .map(|d| {
            let ty = match &d.ty {
                TypeSpec::Named(t) => i.name(t.sym).to_string(),
                _ => "?".to_string(),
            };
            format!("{}: {ty}", i.name(d.names[0].sym))
        })
        .collect()
}

const MAIN: &str = "
PROGRAM Main
    INITIAL_STEP S0: END_STEP
    TRANSITION FROM S0 TO M := TRUE; END_TRANSITION
    STEP M: END_STEP
    TRANSITION FROM M TO S0 := TRUE; END_TRANSITION
END_PROGRAM
";

fn with_body(body: &str) -> String {
    format!("{MAIN}\nFUNCTION_BLOCK Body\n{body}\nEND_FUNCTION_BLOCK\n")
}

const BODY: &str = "
    INITIAL_STEP B1: END_STEP
    TRANSITION FROM B1 TO B2 := TRUE; END_TRANSITION
    STEP B2: END_STEP
";

/// A well-formed macro-step gives no diagnostic (no E091 any more, no W120
/// for M, no W121 for M's exit step B2, which only M's transition leaves);
/// body steps are ordinary step instances named as written, the body's
/// initial step is not an initial step of the chart.
#[test]
fn macro_step_is_accepted_and_declares_its_body_steps() {
    let mut i = Interner::new();
    let (mut unit, d) = macro_main(&with_body(BODY), "B2", &mut i);
    assert_eq!(codes(&d), vec![]);
    let decls = hidden_decls(&mut unit, &i);
    assert_eq!(
        decls[..4],
        [
            "S0: __SFC_INITIAL_STEP",
            "M: __SFC_STEP",
            "B1: __SFC_STEP",
            "B2: __SFC_STEP"
        ]
    );
}

/// An INITIAL_STEP macro-step starts with its body's initial step active.
#[test]
fn initial_macro_step_makes_its_entry_initial() {
    let src = "
PROGRAM Main
    INITIAL_STEP M: END_STEP
    TRANSITION FROM M TO S1 := TRUE; END_TRANSITION
    STEP S1: END_STEP
    TRANSITION FROM S1 TO M := TRUE; END_TRANSITION
END_PROGRAM
FUNCTION_BLOCK Body
    INITIAL_STEP B1: END_STEP
    TRANSITION FROM B1 TO B2 := TRUE; END_TRANSITION
    STEP B2: END_STEP
END_FUNCTION_BLOCK
";
    let mut i = Interner::new();
    let (mut unit, d) = macro_main(src, "B2", &mut i);
    assert_eq!(codes(&d), vec![]);
    let decls = hidden_decls(&mut unit, &i);
    assert_eq!(
        decls[..4],
        [
            "M: __SFC_INITIAL_STEP",
            "S1: __SFC_STEP",
            "B1: __SFC_INITIAL_STEP",
            "B2: __SFC_STEP"
        ]
    );
}

#[test]
fn unknown_exit_step_is_e121() {
    let mut i = Interner::new();
    let (_, d) = macro_main(&with_body(BODY), "Nope", &mut i);
    assert_eq!(
        codes(&d),
        vec![
            (
                Code::E121,
                "unknown exit step `Nope` of macro-step `M`".to_string()
            ),
            (
                Code::W121,
                "no transition leaves step `B2`: once active, it stays active".to_string()
            )
        ]
    );
}

#[test]
fn exit_step_outside_the_body_is_e121() {
    let mut i = Interner::new();
    let (_, d) = macro_main(&with_body(BODY), "S0", &mut i);
    assert_eq!(
        codes(&d),
        vec![
            (
                Code::E121,
                "the exit step `S0` of macro-step `M` is not a step of its body".to_string()
            ),
            (
                Code::W121,
                "no transition leaves step `B2`: once active, it stays active".to_string()
            )
        ]
    );
}

#[test]
fn body_without_initial_step_is_e123() {
    let body = "
    STEP B1: END_STEP
    TRANSITION FROM B1 TO B2 := TRUE; END_TRANSITION
    STEP B2: END_STEP
";
    let mut i = Interner::new();
    let (_, d) = macro_main(&with_body(body), "B2", &mut i);
    // One error: no W120 for the body steps that are never entered.
    assert_eq!(
        codes(&d),
        vec![(
            Code::E123,
            "the body of macro-step `M` has no INITIAL_STEP: it is the step entered with the macro-step"
                .to_string()
        )]
    );
}

#[test]
fn body_with_two_initial_steps_is_e124() {
    let body = "
    INITIAL_STEP B1: END_STEP
    TRANSITION FROM B1 TO B2 := TRUE; END_TRANSITION
    INITIAL_STEP B2: END_STEP
";
    let mut i = Interner::new();
    let (_, d) = macro_main(&with_body(body), "B2", &mut i);
    assert_eq!(
        codes(&d),
        vec![(
            Code::E124,
            "a macro-step's body has exactly one INITIAL_STEP".to_string()
        )]
    );
}

/// A transition links steps of its own chart or body: the chart reaches a
/// body only through the macro-step, a body never leaves itself directly.
#[test]
fn transitions_across_a_macro_body_are_e121() {
    let src = "
PROGRAM Main
    INITIAL_STEP S0: END_STEP
    TRANSITION FROM S0 TO M := TRUE; END_TRANSITION
    STEP M: END_STEP
    TRANSITION FROM M TO S0 := TRUE; END_TRANSITION
    TRANSITION FROM S0 TO B2 := TRUE; END_TRANSITION
END_PROGRAM
FUNCTION_BLOCK Body
    INITIAL_STEP B1: END_STEP
    TRANSITION FROM B1 TO B2 := TRUE; END_TRANSITION
    STEP B2: END_STEP
    TRANSITION FROM B1 TO S0 := TRUE; END_TRANSITION
END_FUNCTION_BLOCK
";
    let mut i = Interner::new();
    let (_, d) = macro_main(src, "B2", &mut i);
    assert_eq!(
        codes(&d),
        vec![
            (
                Code::E121,
                "step `B2` is inside macro-step `M`: a transition enters or leaves its body through `M`"
                    .to_string()
            ),
            (
                Code::E121,
                "step `S0` is outside the body of macro-step `M`: a transition of a macro body links steps of that body"
                    .to_string()
            ),
        ]
    );
}

/// Body steps keep their names, so they share the chart's namespace.
#[test]
fn body_step_named_as_a_chart_step_is_e122() {
    let body = "
    INITIAL_STEP S0: END_STEP
    TRANSITION FROM S0 TO B2 := TRUE; END_TRANSITION
    STEP B2: END_STEP
";
    let mut i = Interner::new();
    let (_, d) = macro_main(&with_body(body), "B2", &mut i);
    // One error: the body's transitions naming its `S0` and its missing
    // initial step are not reported again.
    assert_eq!(
        codes(&d),
        vec![(
            Code::E122,
            "`S0` is declared twice in this chart".to_string()
        )]
    );
}

/// The `jump` flag changes nothing in the generated code.
#[test]
fn jump_transitions_desugar_exactly_like_ordinary_ones() {
    let src = "
PROGRAM Main
VAR n : INT; END_VAR
    INITIAL_STEP A: Inc(N); END_STEP
    TRANSITION FROM A TO B := A.T >= T#10ms; END_TRANSITION
    STEP B: END_STEP
    TRANSITION (PRIORITY := 1) FROM B TO A := TRUE; END_TRANSITION
    TRANSITION FROM B TO B := n > 3; END_TRANSITION
    ACTION Inc: n := n + 1; END_ACTION
END_PROGRAM
";
    let mut i = Interner::new();
    let mut unit = automat_syntax::parse(FileId(0), src, &mut i).unit;
    let p = pou_mut(&mut unit, "Main", &i);
    let parsed = p.clone();
    p.var_blocks.retain(|b| !is_hidden(b, &i));
    if let Lang::Sfc(c) = &mut p.lang {
        for t in &mut c.transitions {
            t.jump = true;
        }
    }
    assert_eq!(codes(&automat_syntax::desugar_chart(p, &mut i)), vec![]);
    assert_eq!(p.body, parsed.body);
    assert_eq!(p.var_blocks, parsed.var_blocks);
}

/// `Chart::charts`: the chart, then each macro body depth first in source
/// order (the flattening order).
#[test]
fn charts_lists_bodies_depth_first() {
    use automat_syntax::ast::sfc::{Chart, Step};
    let mut i = Interner::new();
    let sp = Span::new(FileId(0), 0, 0);
    let mut step = |name: &str, body: Option<Chart>| Step {
        name: Ident {
            sym: i.intern(name),
            span: sp,
        },
        initial: false,
        assocs: Vec::new(),
        macro_body: body.map(|chart| {
            Box::new(MacroBody {
                chart,
                exit: Ident {
                    sym: i.intern("exit"),
                    span: sp,
                },
            })
        }),
        span: sp,
    };
    let leaf = |s: Step| Chart {
        steps: vec![s],
        ..Chart::default()
    };
    let a1 = leaf(step("a1", None));
    let a = leaf(step("A", Some(a1)));
    let b = leaf(step("B", None));
    let top = Chart {
        steps: vec![step("top", None), step("MA", Some(a)), step("MB", Some(b))],
        ..Chart::default()
    };
    let firsts: Vec<String> = top
        .charts()
        .iter()
        .map(|c| i.name(c.steps[0].name.sym).to_string())
        .collect();
    assert_eq!(firsts, ["top", "A", "a1", "B"]);
}
