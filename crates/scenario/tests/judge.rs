//! The verdicts of the scenario language, exactly: each case is a scenario
//! run against one small program without a plant (10 ms scans), with the
//! failures it must give (`line: time: reason`), none for a pass.

use automat_base::FileId;
use automat_ir::Program;
use automat_project::{Project, RetainSpec};

const PROGRAM: &str = "PROGRAM P
VAR
    In AT %IX0.0 : BOOL;
    Out AT %QX0.0 : BOOL;
    n : INT;
    t : TON;
    x : REAL;
END_VAR
t(IN := In, PT := T#50ms);
Out := t.Q;
IF In THEN n := n + 1; END_IF;
x := INT_TO_REAL(n) * 0.5;
END_PROGRAM
";

fn build() -> (Program, Project) {
    // One folder per call: the tests run in parallel.
    static NEXT: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!("automat-judge-{}-{n}", std::process::id()));
    let _ = std::fs::create_dir_all(&dir);
    let st = dir.join("p.st");
    std::fs::write(&st, PROGRAM).expect("write the program");
    let (program, _) = automat_project::build::compile(std::slice::from_ref(&st), None, &[])
        .expect("the program compiles");
    let project = Project {
        dir,
        file: FileId(0),
        name: "judge".into(),
        description: String::new(),
        sources: vec![st],
        program: None,
        cycle_time_ns: 10_000_000,
        libraries: Vec::new(),
        plant: None,
        retain: RetainSpec::default(),
        safe_state: Vec::new(),
        users: Vec::new(),
        tasks: Vec::new(),
        runtime: automat_project::RuntimeSpec::default(),
        warnings: Vec::new(),
    };
    (program, project)
}

/// (scenario after `duration 1s` and one press of In from 100 ms to 300 ms
/// on lines 1-2, failures as `line: time: reason`).
const CASES: &[(&str, &[&str])] = &[
    // Event anchors: the window [event, event + W] includes the event's scan.
    ("expect Out within 50ms after rise(In)", &[]),
    (
        "expect Out within 40ms after rise(In)",
        &["3: T#140ms: after the event at T#100ms it did not become TRUE in [T#100ms, T#140ms]"],
    ),
    // A window ending between two scans: the scan after its end is too late.
    (
        "expect Out within 45ms after rise(In)",
        &["3: T#150ms: after the event at T#100ms it did not become TRUE in [T#100ms, T#145ms]"],
    ),
    ("expect NOT Out within 0s after fall(In)", &[]),
    ("expect NOT Out within 0s after fall(%IX0.0)", &[]),
    // A plain condition as anchor is its rising edge.
    ("expect Out within 50ms after In", &[]),
    (
        "expect Out within 1s after n > 1000",
        &["3: T#990ms: its event never happened"],
    ),
    // Time anchors keep their (A, A + W] window.
    ("expect Out within 60ms after 100ms", &[]),
    (
        "expect Out within 40ms after 100ms",
        &["3: T#140ms: it did not become TRUE in (T#100ms, T#140ms]"],
    ),
    // Counting over a window, judged at its end.
    ("expect count(rise(Out)) = 1 during 0s..1s", &[]),
    ("expect count(change(n)) = 20 during 0s..1s", &[]),
    (
        "expect count(In) = 20 AND count(Out) = 15 during 0s..1s",
        &[],
    ),
    ("expect count(rise(In)) = 0 during 400ms..1s", &[]),
    (
        "expect count(rise(Out)) = 2 during 0s..1s",
        &["3: T#990ms: it is FALSE at the end of the run"],
    ),
    (
        "expect count(In) < 5 during 0s..500ms",
        &["3: T#500ms: it is FALSE at the end of the window"],
    ),
    ("expect at 200ms count(In) = 11", &[]),
    ("expect always count(rise(Out)) <= 1", &[]),
    (
        "expect count(In) = 1 during 0s..2s",
        &["3: T#990ms: the run ends at T#1s before the window ends at T#2s"],
    ),
    // Holding a value.
    ("expect Out stable for 140ms after rise(Out)", &[]),
    (
        "expect Out stable for 150ms after rise(Out)",
        &["3: T#300ms: it changed from TRUE to FALSE, T#150ms after the event at T#150ms"],
    ),
    ("expect n stable during 0s..90ms", &[]),
    ("expect n stable during 0s..95ms", &[]),
    (
        "expect n stable during 0s..100ms",
        &["3: T#100ms: it changed from 0 to 1 (stable since T#0s)"],
    ),
    ("expect n stable for 1s after fall(In)", &[]),
    (
        "expect x stable for 10ms after rise(In)",
        &["3: T#110ms: it changed from 0.5 to 1, T#10ms after the event at T#100ms"],
    ),
    // Arithmetic, on numbers and TIMEs.
    ("expect always abs(x - n * 0.5) < 0.001 AND x * 2 = n", &[]),
    // (ET stops at PT: 50 ms.)
    (
        "expect at 200ms P.t.ET = 50ms AND P.t.ET - 20ms = T#30ms",
        &[],
    ),
    (
        "expect at 200ms P.t.ET / 2 = 25ms AND P.t.ET / 10ms = 5 AND P.t.ET * 2 = 2 * P.t.ET",
        &[],
    ),
    (
        "expect at 200ms n MOD 4 = 3 AND -n = 0 - 11 AND min(n, 5) + max(n, 5) = 16",
        &[],
    ),
    ("expect at 200ms x / 0 > 1000000", &[]),
    // The previous scan's values; before the first scan: the initial ones.
    (
        "expect always n - prev(n) <= 1 AND (n = prev(n) OR In)",
        &[],
    ),
    ("expect never rise(Out) AND prev(Out)", &[]),
    ("expect always change(n) = (n <> prev(n))", &[]),
    // A name is read only at the scans that evaluate it: an expectation
    // waiting for its time sees the scan it is judged at, one using `prev`
    // the scan before too, and one judged on the final state (no scan at
    // 1 s) what the last scan left, though no scan read its name.
    ("expect at 50ms n = 0\nexpect at 990ms n = 20", &[]),
    ("expect at 200ms prev(n) = 10 AND n = 11 AND change(n)", &[]),
    ("expect at 200ms NOT rise(Out) AND prev(Out)", &[]),
    ("expect at 1s n = 20 AND x = 10", &[]),
    (
        "expect at 1s n = 19",
        &["3: T#990ms: it is FALSE at the end of the run"],
    ),
    ("expect count(In) = 20 AND n = 20 during 0s..1s", &[]),
    // Reactions: at the event's scan, applied by the next scan.
    ("when rise(Out) then release In\nexpect at 500ms n = 6", &[]),
    (
        "when rise(Out) after 100ms then release In\nexpect at 500ms n = 15",
        &[],
    ),
    // Each fall presses again: two more scans with In every 30 ms.
    (
        "when fall(In) then press In for 30ms\nexpect at 500ms n = 34",
        &[],
    ),
    ("when In then set n = 100\nexpect at 110ms n = 101", &[]),
];

fn verdicts(program: &Program, project: &Project, body: &str) -> Vec<String> {
    let text = format!("duration 1s\nat 100ms press In for 200ms\n{body}\n");
    let scn = automat_scenario::parse(&text, FileId(1), "case")
        .unwrap_or_else(|d| panic!("{body}: {d:?}"));
    let out = automat_scenario::run::<std::io::Sink>(program, project, &scn, None)
        .unwrap_or_else(|d| panic!("{body}: {d:?}"));
    out.failures
        .iter()
        .map(|f| {
            format!(
                "{}: {}: {}",
                f.line,
                automat_iec::format::format_duration(f.at_ns, false),
                f.reason
            )
        })
        .collect()
}

#[test]
fn verdicts_of_every_construct() {
    let (program, project) = build();
    let mut wrong = Vec::new();
    for (body, want) in CASES {
        let got = verdicts(&program, &project, body);
        if got != *want {
            wrong.push(format!("{body}\n  want {want:?}\n  got  {got:?}"));
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

/// The values named in a failure, as people read them.
#[test]
fn failures_show_the_values() {
    let (program, project) = build();
    let text =
        "duration 1s\nat 100ms press In for 200ms\nexpect at 200ms n * 2 = x + P.t.ET / 1ms\n";
    let scn = automat_scenario::parse(text, FileId(1), "case").expect("parses");
    let out = automat_scenario::run::<std::io::Sink>(&program, &project, &scn, None).expect("runs");
    let f = out.failures.first().expect("a failure");
    assert_eq!(f.values, "n = 11, x = 5.5, P.t.ET = T#50ms");
    // Counts show as written, with their value.
    let text = "duration 1s\nat 100ms press In for 200ms\nexpect count(rise(Out)) + count(In) < 3 AND n > 0 during 0s..500ms\n";
    let scn = automat_scenario::parse(text, FileId(1), "case").expect("parses");
    let out = automat_scenario::run::<std::io::Sink>(&program, &project, &scn, None).expect("runs");
    let f = out.failures.first().expect("a failure");
    assert_eq!(
        f.values,
        "n = 20, Out = FALSE, In = FALSE, count(rise(Out)) = 1, count(In) = 20"
    );
}

/// A scenario's checker errors for what needs a plant and misplaced
/// functions, every one at once in the file's order.
#[test]
fn checker_errors_without_a_plant() {
    let (program, project) = build();
    let text = "duration 1s
at 0s noise In 2
expect at 1s plant.level > 1
expect count(In) > 1 within 1s after 0s
when count(In) > 2 then press In
expect at 1s Nothing
";
    let scn = automat_scenario::parse(text, FileId(1), "case").expect("parses");
    let Err(d) = automat_scenario::run::<std::io::Sink>(&program, &project, &scn, None) else {
        panic!("should be refused")
    };
    let got: Vec<(String, u32)> = d
        .iter()
        .map(|d| (d.code.as_str().to_string(), d.span.start))
        .collect();
    assert_eq!(
        got,
        [
            ("E325".to_string(), 24),
            ("E325".to_string(), 42),
            ("E326".to_string(), 65),
            ("E326".to_string(), 103),
            ("E321".to_string(), 144),
        ]
    );
}

/// Hostile names and lines are refused at once, in the checker as in the
/// parser: a path of 20,000 names (the path resolver tried every prefix),
/// brackets, huge addresses, deep nesting in actions and reactions.
#[test]
fn hostile_scenarios_are_refused_fast() {
    let (program, project) = build();
    let lines = [
        format!("expect at 1s {}b", "a.".repeat(20_000)),
        format!("expect at 1s x{}{}", "[".repeat(20_000), "]".repeat(20_000)),
        format!("expect at 1s {}", "a".repeat(200_000)),
        format!("expect at 1s %IX{}.0", "9".repeat(20_000)),
        format!(
            "at 0s set {}1{} = 1",
            "a[".repeat(10_000),
            "]".repeat(10_000)
        ),
        format!("at 0s press {}", "(".repeat(100_000)),
        format!("when {}x then press In", "rise(".repeat(100_000)),
        format!("expect {}b stable for 1s after 0s", "P.".repeat(20_000)),
    ];
    for line in lines {
        let text = format!("duration 100ms\n{line}\n");
        let t0 = std::time::Instant::now();
        if let Ok(scn) = automat_scenario::parse(&text, FileId(1), "hostile") {
            let r = automat_scenario::run::<std::io::Sink>(&program, &project, &scn, None);
            assert!(r.is_err(), "{}", &line[..40]);
        }
        let took = t0.elapsed();
        assert!(
            took < std::time::Duration::from_millis(1500),
            "{took:?}: {}",
            &line[..40]
        );
    }
}
