use super::*;

const SRC: &str = "FUNCTION_BLOCK Fill
VAR_INPUT go : BOOL; END_VAR
    INITIAL_STEP Idle: END_STEP
    TRANSITION FROM Idle TO Run := go; END_TRANSITION
    STEP Run: END_STEP
    TRANSITION FROM Run TO Idle := NOT go; END_TRANSITION
END_FUNCTION_BLOCK
PROGRAM Main
VAR fill : Fill; n : INT; END_VAR
    INITIAL_STEP Start: END_STEP
    TRANSITION FROM Start TO (B1, A1) := TRUE; END_TRANSITION
    STEP B1: Work(N); END_STEP
    STEP A1: END_STEP
    TRANSITION FROM (B1, A1) TO Start := n >= 2; END_TRANSITION
    ACTION Work:
        n := n + 1;
        fill(go := TRUE);
    END_ACTION
END_PROGRAM
";

/// Compiles `SRC` from a file of its own per test (tests run in parallel).
fn program(test: &str) -> Program {
    let dir = std::env::temp_dir().join(format!("automat-steps-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    let f = dir.join(format!("{test}.st"));
    std::fs::write(&f, SRC).unwrap_or_else(|e| panic!("{e}"));
    let (p, _) = crate::build::compile(&[f], None, &[]).unwrap_or_else(|e| panic!("{}", e.text));
    p
}

fn active(charts: &[Chart], image: &[u8]) -> Vec<String> {
    charts
        .iter()
        .map(|c| format!("{}: {}", c.owner, c.active(image).join(" ")))
        .collect()
}

#[test]
fn charts_of_programs_and_fb_instances_in_declaration_order() {
    let p = program("decl");
    let charts = charts(&p);
    let names: Vec<(String, Vec<String>)> = charts
        .iter()
        .map(|c| {
            (
                c.owner.clone(),
                c.steps.iter().map(|s| s.name.clone()).collect(),
            )
        })
        .collect();
    assert_eq!(
        names,
        [
            (
                "Main".to_string(),
                vec!["Start".into(), "B1".into(), "A1".into()]
            ),
            // The interner keeps the first spelling of a name: `Fill` (the
            // FB's) for the instance `fill`.
            ("Main.Fill".to_string(), vec!["Idle".into(), "Run".into()]),
        ]
    );
    // Cold start: the initial steps.
    assert_eq!(
        active(&charts, &p.initial_image),
        ["Main: Start", "Main.Fill: Idle"]
    );
}

#[test]
fn active_steps_follow_the_scans() {
    let p = program("scans");
    let charts = charts(&p);
    let mut e = automat_engine::Engine::new(p.clone());
    let inst = p
        .tasks
        .first()
        .and_then(|t| t.programs.first())
        .cloned()
        .unwrap_or_else(|| panic!("no program"));
    // Scan 1: Start → (B1, A1). 2: B1's action: n 1, fill Idle → Run.
    // 3: n 2, so (B1, A1) → Start. 4: Start → (B1, A1) again.
    let mut seen = Vec::new();
    for k in 0..4 {
        e.run_program(&inst, k * 10_000_000)
            .unwrap_or_else(|f| panic!("{f:?}"));
        seen.push(active(&charts, e.image()).join(" | "));
    }
    assert_eq!(
        seen,
        [
            "Main: B1 A1 | Main.Fill: Idle",
            "Main: B1 A1 | Main.Fill: Run",
            "Main: Start | Main.Fill: Run",
            "Main: B1 A1 | Main.Fill: Run",
        ]
    );
}

#[test]
fn the_steps_column_names_a_chart_by_its_owner() {
    let p = program("column");
    let Some(Ok(c)) = column(&p, "steps(main.fill)") else {
        panic!("no chart for main.fill")
    };
    assert_eq!(c.owner, "Main.Fill");
    assert_eq!(c.column(), "steps(Main.Fill)");
    assert_eq!(c.active_text(&p.initial_image), "Idle");
    assert!(column(&p, "Main.Start.X").is_none(), "an ordinary path");
    let Some(Err(e)) = column(&p, "steps(Nope)") else {
        panic!("steps(Nope) accepted")
    };
    assert_eq!(e, "`Nope` has no SFC chart (charts: Main, Main.Fill)");
}
