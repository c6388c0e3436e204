//! Scenarios without a plant (issue 17 point 1), `automat run --scenario`
//! judging expectations and honouring `seed`, the JUnit report and exit
//! codes of `automat test` (point 4), and `--jobs` giving the output of
//! `--jobs 1` (issue 15 point 5).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn automat(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_automat"))
        .current_dir(root())
        .args(args)
        .output()
        .expect("run automat")
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("automat-scnlang-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

const LIGHT: &str = "examples/traffic-light";

/// A project without [plant] runs, driven and judged by its scenario.
#[test]
fn a_project_without_plant_runs_its_scenario() {
    let out = automat(&[
        "run",
        LIGHT,
        "--scenario",
        "examples/traffic-light/scenarios/one_request.scn",
        "--print",
        "Crossing.state",
        "--print",
        "%QX0.0",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert_eq!(
        text(&out.stdout),
        "Crossing.state = Phase#Go\n%QX0.0 = TRUE\n"
    );
    assert_eq!(
        text(&out.stderr),
        "scenario examples/traffic-light/scenarios/one_request.scn: every expectation held\n"
    );
    // Without a scenario it just runs.
    let out = automat(&["run", LIGHT, "--duration", "1s", "--print", "CarGreen"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert_eq!(text(&out.stdout), "CarGreen = TRUE\n");
}

/// A plain source file with --scenario: actions, reactions and
/// expectations on the program's variables, failures on stderr, exit 1.
#[test]
fn a_plain_source_file_runs_a_scenario() {
    let dir = tmp("plain");
    let st = dir.join("light.st");
    std::fs::write(
        &st,
        "PROGRAM Light
VAR
    Button AT %IX0.0 : BOOL;
    Lamp AT %QX0.0 : BOOL;
    n : INT;
    t : TON;
END_VAR
t(IN := Button, PT := T#100ms);
Lamp := t.Q;
IF t.Q THEN n := n + 1; END_IF;
END_PROGRAM
",
    )
    .expect("write");
    let scn = dir.join("s.scn");
    std::fs::write(
        &scn,
        "duration 1s
at 100ms press %IX0.0 for 300ms
expect Lamp within 100ms after rise(Button)
expect NOT Lamp within 10ms after fall(Button)
expect count(rise(Lamp)) = 1 during 0s..1s
expect Lamp stable for 190ms after rise(Lamp)
expect at 450ms n = 20
expect always n >= prev(n) OR n = -5
when rise(Lamp) after 500ms then set n = -5
expect at 950ms n = -5
",
    )
    .expect("write");
    let (st, scn) = (st.display().to_string(), scn.display().to_string());
    let out = automat(&["run", &st, "--scenario", &scn, "--print", "n"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert_eq!(text(&out.stdout), "n = -5\n");
    // A wrong expectation: exit 1, the failure as `automat test` shows it.
    std::fs::write(
        &scn,
        "duration 1s\nat 100ms press Button for 300ms\nexpect at 450ms n = 21\n",
    )
    .expect("write");
    let out = automat(&["run", &st, "--scenario", &scn]);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out.stderr));
    assert_eq!(
        text(&out.stderr),
        format!(
            "scenario {scn}: 1 expectation failed\n{scn}:3: expect at 450ms n = 21\n  failed at T#450ms: it is FALSE\n  values: n = 20\n"
        )
    );
    // What needs a plant is refused with its code.
    std::fs::write(&scn, "duration 1s\nat 0s stuck Button = TRUE\n").expect("write");
    let out = automat(&["run", &st, "--scenario", &scn]);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        text(&out.stderr).starts_with(&format!(
            "{scn}:2:13: error[E325]: `stuck` needs a plant model, and the project has no [plant]"
        )),
        "{}",
        text(&out.stderr)
    );
}

/// `automat run --scenario` uses the scenario's seed, as `automat test`
/// does (the project's seed is 7; seed-3.scn draws other spacings).
#[test]
fn run_scenario_honours_the_seed() {
    let good = |scn: &str| {
        let out = automat(&[
            "run",
            "examples/bottling-random",
            "--scenario",
            &format!("examples/bottling-random/scenarios/{scn}"),
            "--print",
            "plant.good",
        ]);
        assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
        text(&out.stdout)
    };
    assert_eq!(good("random.scn"), "plant.good = 15\n");
    assert_eq!(good("seed-3.scn"), "plant.good = 16\n");
}

/// The attributes of a JUnit report with the times taken out.
fn without_times(xml: &str) -> String {
    let mut out = String::new();
    let mut rest = xml;
    while let Some(i) = rest.find(" time=\"") {
        out.push_str(&rest[..i]);
        let after = &rest[i + 7..];
        rest = after.find('"').map_or("", |j| &after[j + 1..]);
    }
    out.push_str(rest);
    out
}

/// Passed, failed and error cases in one run: the summary line, exit 2 (an
/// error outranks a failure), the JUnit file; and every --jobs gives the
/// same output and report.
#[test]
fn junit_report_exit_codes_and_jobs() {
    let dir = tmp("junit");
    let run = |jobs: &str, name: &str| {
        let xml = dir.join(name);
        let o = dir.join(format!("out-{jobs}"));
        let out = automat(&[
            "test",
            LIGHT,
            "crates/cli/tests/fixtures/failing_crane",
            "crates/cli/tests/projects/no_plant_e325_e326",
            "tests/conformance/tp.st",
            "--jobs",
            jobs,
            "--out",
            o.to_str().unwrap_or("."),
            "--junit",
            xml.to_str().unwrap_or("x"),
        ]);
        let report = std::fs::read_to_string(&xml).expect("junit file");
        (out, report)
    };
    let (one, xml1) = run("1", "one.xml");
    let (four, xml4) = run("4", "four.xml");
    assert_eq!(one.status.code(), Some(2));
    assert_eq!(four.status.code(), Some(2));
    // The failure's trace paths name the --out folder of each run.
    let norm = |o: &Output, jobs: &str| {
        text(&o.stdout).replace(
            &dir.join(format!("out-{jobs}")).display().to_string(),
            "OUT",
        )
    };
    let stdout = norm(&one, "1");
    assert_eq!(stdout, norm(&four, "4"));
    let out1 = dir.join("out-1").display().to_string();
    let out4 = dir.join("out-4").display().to_string();
    assert_eq!(
        without_times(&xml1).replace(&out1, "OUT"),
        without_times(&xml4).replace(&out4, "OUT")
    );
    let last: Vec<&str> = stdout.lines().rev().take(1).collect();
    assert_eq!(last, ["5 passed, 1 failed, 3 errors"]);
    assert!(stdout.contains(
        "FAILED crates/cli/tests/fixtures/failing_crane/scenarios/wrong.scn (wrong expectations)\n"
    ));
    assert!(stdout.contains("ERROR crates/cli/tests/projects/no_plant_e325_e326/scenarios/e325_needs_plant.scn (e325_needs_plant)\n"));
    // Well-formed XML (xmllint is installed by .ci/run).
    let lint = Command::new("xmllint")
        .args(["--noout", &dir.join("one.xml").display().to_string()])
        .output();
    match lint {
        Ok(o) => assert!(o.status.success(), "{}", text(&o.stderr)),
        Err(e) => assert!(std::env::var_os("CI").is_none(), "xmllint: {e}"),
    }
    let xml = without_times(&xml1);
    assert!(xml.starts_with(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"automat test\" tests=\"9\" failures=\"1\" errors=\"3\" skipped=\"0\">\n  <testsuite name=\"examples/traffic-light\" tests=\"4\" failures=\"0\" errors=\"0\" skipped=\"0\">\n    <testcase name=\"scenarios/busy.scn (a pedestrian presses again 1 s after every walk phase)\" classname=\"examples/traffic-light\" file=\"examples/traffic-light/scenarios/busy.scn\"/>\n"
    ), "{xml}");
    assert!(xml.contains("<testsuite name=\"crates/cli/tests/fixtures/failing_crane\" tests=\"1\" failures=\"1\" errors=\"0\" skipped=\"0\">"), "{xml}");
    assert!(xml.contains("<failure message=\"crates/cli/tests/fixtures/failing_crane/scenarios/wrong.scn:4: expect at 2s M1D\" type=\"failure\">"), "{xml}");
    assert!(xml.contains("<error message=\"crates/cli/tests/projects/no_plant_e325_e326/scenarios/e325_needs_plant.scn:2:13: error[E325]: `stuck` needs a plant model, and the project has no [plant]\" type=\"error\">"), "{xml}");
    assert!(xml.contains("<testsuite name=\"tests/conformance\" tests=\"1\" failures=\"0\" errors=\"0\" skipped=\"0\">"), "{xml}");
    assert!(xml.ends_with("  </testsuite>\n</testsuites>\n"));
    // Only passing items: exit 0; an unwritable --junit path: exit 2.
    let ok = automat(&[
        "test",
        LIGHT,
        "--junit",
        &dir.join("ok.xml").display().to_string(),
    ]);
    assert_eq!(ok.status.code(), Some(0));
    assert!(text(&ok.stdout).ends_with("4 passed, 0 failed\n"));
    let bad = automat(&[
        "test",
        LIGHT,
        "--junit",
        &dir.join("no/such/dir.xml").display().to_string(),
    ]);
    assert_eq!(bad.status.code(), Some(2));
    assert!(
        text(&bad.stderr).starts_with("error: --junit "),
        "{}",
        text(&bad.stderr)
    );
    // A bad --jobs is a command-line error.
    assert_eq!(
        automat(&["test", LIGHT, "--jobs", "0"]).status.code(),
        Some(2)
    );
}

/// The dialects' own addresses name variables in scenarios: PL7 steps
/// (`%X0`, `%X0.T`) and I/O (`%I1.0`), Festo FST operands (`I0.1`, a bit of
/// the input word at `%IX0.1`).
#[test]
fn scenarios_take_the_dialects_addresses() {
    let dir = tmp("dialects");
    let cases = [
        (
            "examples/trains",
            "duration 1s\nexpect at 0s %X0 AND %X10 AND %X20 AND NOT %X1\nexpect at 500ms %X0.T >= 490ms AND %X0.T <= 500ms\nexpect always %IX1.0 = %I1.0\n",
        ),
        (
            "examples/festo-distribution-stl",
            "duration 1s\nexpect always I0.1 = %IX0.1 AND O0.0 = %QX0.0 AND IW0 = %IW0\n",
        ),
    ];
    for (k, (project, scn)) in cases.iter().enumerate() {
        let path = dir.join(format!("{k}.scn"));
        std::fs::write(&path, scn).expect("write");
        let shown = path.display().to_string();
        let out = automat(&["run", project, "--scenario", &shown]);
        assert_eq!(
            out.status.code(),
            Some(0),
            "{project}: {}",
            text(&out.stderr)
        );
        assert!(
            text(&out.stderr).ends_with(&format!("scenario {shown}: every expectation held\n")),
            "{}",
            text(&out.stderr)
        );
    }
}
