//! `.slc` files on the command line (docs/allen-bradley.md): checked and
//! run without `--lib`, SLC addresses as `--print` and `--trace` paths, the
//! diagnostics at file:line:col naming the instruction, the overflow trap
//! as a runtime fault (exit 3).

use std::path::PathBuf;
use std::process::{Command, Output};

fn automat(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_automat"))
        .args(args)
        .output()
        .expect("run automat")
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).to_string()
}

fn tmp(name: &str, content: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("automat-slc-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let p = dir.join(name);
    std::fs::write(&p, content).expect("write");
    p
}

#[test]
fn addresses_and_symbols_print_by_name() {
    let crane = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/crane-slc/crane.slc"
    );
    let out = automat(&[
        "run", crane, "--cycles", "2", "--print", "B3/1", "--print", "X1", "--print", "T4:0.PRE",
        "--print", "S:1/15", "--print", "B3:0/1", "--print", "I:1/1",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert_eq!(
        text(&out.stdout),
        "B3/1 = 1\nX1 = 1\nT4:0.PRE = 300\nS:1/15 = 0\nB3:0/1 = 1\nI:1/1 = 0\n"
    );
    // An address no file of the program holds, and one that is no address.
    let out = automat(&["run", crane, "--cycles", "1", "--print", "N7:0"]);
    assert_eq!(out.status.code(), Some(2), "{}", text(&out.stderr));
    assert!(
        text(&out.stderr).contains("is the SLC address of `N7[0]`"),
        "{}",
        text(&out.stderr)
    );
    let out = automat(&["run", crane, "--cycles", "1", "--print", "B3:0/16"]);
    assert!(
        text(&out.stderr).contains("the bit is 0 to 15"),
        "{}",
        text(&out.stderr)
    );
}

#[test]
fn diagnostics_name_rung_instruction_and_place() {
    let p = tmp(
        "bad.slc",
        "XIC B3/0 OTE T4:0\nXIC B3/0 BST XIC B3/1 OTE B3/2\n",
    );
    let out = automat(&["check", p.to_str().unwrap_or(".")]);
    assert_eq!(out.status.code(), Some(1));
    // `automat check` reports on stdout.
    let err = text(&out.stdout);
    assert!(
        err.contains(
            "bad.slc:1:14: error[E232]: LAD 2 rung 0, `OTE T4:0`: `T4:0` is no bit address"
        ),
        "{err}"
    );
    assert!(
        err.contains("bad.slc:2:1: error[E235]: LAD 2 rung 1: a branch is not closed"),
        "{err}"
    );
    assert!(err.ends_with("2 errors, 0 warnings\n"), "{err}");
}

#[test]
fn an_unhandled_overflow_is_a_major_fault() {
    let p = tmp("ov.slc", "DATA N7 2 = 32767\nADD N7:0 1 N7:1\n");
    let out = automat(&["run", p.to_str().unwrap_or("."), "--cycles", "3"]);
    assert_eq!(out.status.code(), Some(3), "{}", text(&out.stderr));
    let err = text(&out.stderr);
    assert!(err.contains("runtime fault: <slc>/ladder.st:"), "{err}");
    assert!(
        err.contains("fault in SLC: SLC major fault: math overflow trap S:5/0 set at the end of the scan (LAD 2 rung 0, `ADD N7:0 1 N7:1`)"),
        "{err}"
    );
    assert!(err.contains("PLC time T#0s"), "{err}");
}

/// SLC bits (by address or symbol) print as 1/0 in a trace too; a
/// scenario compares and sets them with 1 and 0 (TRUE/FALSE still work),
/// and its failure shows them as 1/0.
#[test]
fn slc_bits_print_as_one_and_zero() {
    let crane = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/crane-slc/crane.slc"
    );
    let csv = std::env::temp_dir().join(format!("automat-slc-trace-{}.csv", std::process::id()));
    let shown = csv.display().to_string();
    let out = automat(&[
        "run",
        crane,
        "--cycles",
        "2",
        "--trace",
        "B3:0/1,X1,T4:0.ACC",
        "--trace-file",
        &shown,
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let got = std::fs::read_to_string(&csv).unwrap_or_default();
    let _ = std::fs::remove_file(&csv);
    assert_eq!(got, "time,B3:0/1,X1,T4:0.ACC\nT#0s,1,1,0\nT#10ms,1,1,0\n");
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/crane-slc");
    let scn = tmp(
        "ones.scn",
        "duration 2s\nat 500ms set B3:0/12 = 1\nat 600ms set B3:0/12 = FALSE\nexpect at 100ms B3:0/1 = 1 AND X1 = 1 AND I:1/1 = 0\nexpect at 550ms B3:0/12 = 1\nexpect at 650ms B3:0/12 = 0\nexpect at 1s B3:0/1 = 0\n",
    );
    let shown = scn.display().to_string();
    let out = automat(&["run", dir, "--scenario", &shown]);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out.stderr));
    let err = text(&out.stderr);
    assert!(err.contains("B3:0/1 = 1"), "{err}");
    assert!(!err.contains("TRUE"), "{err}");
}

/// A scenario names the SLC addresses (`B3:0/2`, `T4:0/DN`, `T4:0.ACC`,
/// `O:3/3`) as the ladder does.
#[test]
fn scenarios_take_slc_addresses() {
    let crane = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/crane-slc");
    let scn = tmp(
        "addr.scn",
        "duration 20s\nat 500ms press Pornire for 200ms\nexpect at 1s B3:0/2 AND O:3/3 AND NOT B3:0/1\nexpect at 16s B3:0/5 AND T4:0.ACC > 0 AND NOT T4:0/DN\nexpect always O:3/3 = M2S AND I:1/1 = Pornire\n",
    );
    let shown = scn.display().to_string();
    let out = automat(&["run", crane, "--scenario", &shown]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert!(
        text(&out.stderr).ends_with(&format!("scenario {shown}: every expectation held\n")),
        "{}",
        text(&out.stderr)
    );
}

/// Indexed and indirect addresses in `--print` and `--trace`: found in
/// the image they are printed from; one outside its data file prints `?`
/// and says why, the run goes on (exit 0).
#[test]
fn indexed_and_indirect_addresses_print_by_name() {
    let src = tmp(
        "indirect.slc",
        "; S:24 = 2, N7:0 = 1, N7:1 = 18, N7:2 = 7, N7:3 = 10\n\
         DATA N7 10 = 1 18 7 10 0 0 0 55 0 0\n\
         DATA N10 3 = 0 44 0\n\
         DATA B3 2 = 0 4\n\
         MOV 2 S:24\n\
         MOV 123 N7:5\n\
         XIC B3/0 TON T4:1 0.01 500 0\n",
    );
    let csv = src.with_extension("csv");
    let (src_s, csv_s) = (src.display().to_string(), csv.display().to_string());
    let out = automat(&[
        "run",
        &src_s,
        "--cycles",
        "2",
        "--print",
        "#N7:5",
        "--print",
        "#N7:3",
        "--print",
        "N7:[N7:0]",
        "--print",
        "T4:[N7:0].PRE",
        "--print",
        "N[N7:3]:1",
        "--print",
        "B3/[N7:1]",
        "--print",
        "B3:[N7:0]/2",
        "--print",
        "B3:0/[N7:2]",
        "--print",
        "N7:[N7:1]",
        "--trace",
        "#N7:3,N7:[N7:0],B3/[N7:1]",
        "--trace-file",
        &csv_s,
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert_eq!(
        text(&out.stdout),
        "#N7:5 = 55\n#N7:3 = 123\nN7:[N7:0] = 18\nT4:[N7:0].PRE = 500\nN[N7:3]:1 = 44\n\
         B3/[N7:1] = 1\nB3:[N7:0]/2 = 1\nB3:0/[N7:2] = 0\nN7:[N7:1] = ?\n"
    );
    assert_eq!(
        text(&out.stderr),
        "error: --print N7:[N7:1]: indirect address `N7:[N7:1]`: the element 18 is not one of data file N7 (0 to 9)\n"
    );
    assert_eq!(
        std::fs::read_to_string(&csv).expect("trace"),
        "time,#N7:3,N7:[N7:0],B3/[N7:1]\nT#0s,123,18,1\nT#10ms,123,18,1\n"
    );
    // Not a place a binding or a plain path can take.
    let out = automat(&["run", &src_s, "--cycles", "1", "--print", "#N7:0/1"]);
    assert_eq!(out.status.code(), Some(2), "{}", text(&out.stderr));
    assert!(
        text(&out.stderr).contains("an indexed address names a word"),
        "{}",
        text(&out.stderr)
    );
}

/// Scenarios read, expect and set indexed and indirect addresses
/// (crates/cli/tests/projects/slc_indirect); a set or read outside the
/// data file fails that line.
#[test]
fn scenarios_set_and_expect_indexed_and_indirect_addresses() {
    let from = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/projects/slc_indirect");
    let dir = std::env::temp_dir().join(format!("automat-slc-ind-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("scenarios")).expect("dir");
    for f in [
        "automat.toml",
        "indirect.slc",
        "scenarios/indirect.scn",
        "scenarios/outside.scn",
    ] {
        std::fs::copy(format!("{from}/{f}"), dir.join(f)).expect("copy");
    }
    let d = dir.display().to_string();
    let out = automat(&["test", &format!("{d}/scenarios/indirect.scn")]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stdout));
    let out = automat(&["test", &format!("{d}/scenarios/outside.scn")]);
    assert_eq!(out.status.code(), Some(1));
    let shown = text(&out.stdout).replace(&d, "P");
    let want = "FAILED P/scenarios/outside.scn (outside)\n    \
        P/scenarios/outside.scn:4: set N7:[N7:4]\n      \
        failed at T#50ms: indirect address `N7:[N7:4]`: the element 12 is not one of data file N7 (0 to 9)\n    \
        P/scenarios/outside.scn:5: expect at 60ms N7:[N7:4] = 0\n      \
        failed at T#60ms: it is FALSE\n      \
        values: N7:[N7:4] = ? (indirect address `N7:[N7:4]`: the element 12 is not one of data file N7 (0 to 9))\n";
    assert!(shown.starts_with(want), "{shown}");
    assert!(shown.ends_with("0 passed, 1 failed\n"), "{shown}");
}
