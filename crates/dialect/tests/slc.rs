//! The Allen-Bradley SLC-500 cases of `tests/slc/*.slc`
//! (docs/allen-bradley.md). Each case is a ladder file whose `;` comment
//! lines at the top say what must hold:
//! - `; period: MS` the scan period (10 ms by default; scan N runs at PLC
//!   time (N - 1) x period from 0);
//! - `; set N: ADDRESS = VALUE` written before scan N (1/0 or TRUE/FALSE
//!   for a bit, an integer for a word), kept until set again;
//! - `; expect N: ADDRESS = VALUE` read after scan N, exact (bits print
//!   1/0, as `--print` shows them);
//! - `; fault N: TEXT` scan N stops with a runtime fault whose message
//!   contains TEXT (the expects of scan N are read in the image the fault
//!   left, e.g. the PID's sub-error code);
//! - `; error LINE: CODE` the file must give exactly these diagnostics.
//!
//! Every case runs on the interpreter and on the JIT.

mod support;

use automat_base::SourceMap;
use std::path::Path;
use support::Run;

/// A case's `;` header lines: what it runs and the diagnostics it must give.
struct Case {
    run: Run,
    errors: Vec<String>,
}

fn header(text: &str) -> Case {
    let mut c = Case {
        run: Run::default(),
        errors: Vec::new(),
    };
    for line in text.lines() {
        let Some(l) = line.trim().strip_prefix(';') else {
            continue;
        };
        let l = l.trim();
        let Some((head, rest)) = l.split_once(':') else {
            continue;
        };
        let rest = rest.trim();
        if head == "period" {
            c.run.period_ms = rest.parse().unwrap_or_else(|_| panic!("bad period `{l}`"));
            continue;
        }
        let Some((what, at)) = head.split_once(' ') else {
            continue;
        };
        let Ok(at) = at.trim().parse::<u64>() else {
            continue;
        };
        match what {
            "set" | "expect" => {
                let (p, v) = rest
                    .rsplit_once('=')
                    .unwrap_or_else(|| panic!("bad line `{l}`"));
                let e = (at, p.trim().to_string(), v.trim().to_string());
                if what == "set" {
                    c.run.sets.push(e);
                } else {
                    c.run.expects.push(e);
                }
            }
            "fault" => c.run.fault = Some((at, rest.to_string())),
            "error" => c.errors.push(format!("{at}: {rest}")),
            _ => {}
        }
    }
    c
}

fn run_case(path: &Path, jit: bool) -> Result<(), String> {
    let text = std::fs::read_to_string(path).map_err(|e| e.to_string())?;
    let case = header(&text);
    let mut map = SourceMap::new();
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().to_string())
        .unwrap_or_default();
    map.add(name, text);
    let checked = support::check(map, &[]);
    let got = support::diagnostic_lines(&checked.map, &checked.analysis.diagnostics, false);
    let mut want = case.errors.clone();
    want.sort();
    if got != want {
        return Err(format!(
            "diagnostics {got:?}, wanted {want:?}\n{}",
            checked.report()
        ));
    }
    if !want.is_empty() {
        return Ok(());
    }
    checked.run(&case.run, jit)
}

#[test]
fn slc_cases() {
    let cases = support::case_files("slc", "slc");
    assert!(cases.len() >= 10, "{}", cases.len());
    support::run_all(&cases, "E23", run_case);
}

/// Bad input never panics: every case with one word deleted, or cut
/// short, at many places, gives diagnostics or a program that lowers, and
/// the generated ST never fails to check.
#[test]
fn mutated_cases_never_panic() {
    let mut tried = 0;
    for c in support::case_files("slc", "slc") {
        let t = std::fs::read_to_string(&c).unwrap_or_default();
        for mutated in support::mutations(&t, 7) {
            let mut map = SourceMap::new();
            map.add("m.slc", mutated.clone());
            support::check_mutated(map, &[], "<slc>", &format!("{}: {mutated:?}", c.display()));
            tried += 1;
        }
    }
    assert!(tried > 500, "{tried}");
}
