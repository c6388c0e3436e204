//! The web HMI in a real browser: headless Chromium (Debian's `chromium`
//! and `chromium-driver`) driven by Selenium (PyPI), installed by
//! `.ci/run`; `tests/hmi/hmi_browser.py` holds the checks. Nothing is
//! skipped: without the browser or the driver the test fails and says
//! what to install.
//!
//! Screenshots of every view are written to a temporary folder, and to
//! `docs/hmi/` with `UPDATE_DOCS=1` (as `tests/docs.rs` regenerates the
//! diagnostics page).

#[path = "support/common.rs"]
mod common;

use common::{bin, hash, root};
use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::time::Duration;

fn browser_ready() {
    let chromium = std::env::var("CHROMIUM").unwrap_or_else(|_| "/usr/bin/chromium".into());
    let driver = std::env::var("CHROMEDRIVER").unwrap_or_else(|_| "/usr/bin/chromedriver".into());
    for (path, what) in [(&chromium, "chromium"), (&driver, "chromium-driver")] {
        assert!(
            Path::new(path).exists(),
            "{path} is missing: the HMI test needs headless Chromium and its driver \
             (apt-get install -y chromium chromium-driver, as .ci/run does; or set CHROMIUM / \
             CHROMEDRIVER to their paths) [{what}]"
        );
    }
    let ok = Command::new("python3")
        .args(["-c", "import selenium, requests"])
        .status()
        .is_ok_and(|s| s.success());
    assert!(
        ok,
        "python3 with `selenium` and `requests` is needed: \
         python3 -m pip install selenium requests (as .ci/run does)"
    );
}

fn temp(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("automat-hmi-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

/// The crane example with a viewer and an operator.
fn crane() -> PathBuf {
    let dir = temp("crane");
    for f in ["automat.toml", "config.st", "crane.st"] {
        std::fs::copy(root().join("examples/crane").join(f), dir.join(f)).expect("copy");
    }
    let mut toml = std::fs::read_to_string(dir.join("automat.toml")).expect("toml");
    toml.push('\n');
    toml.push_str(&hash("ada", "viewer", "viewer-pass"));
    toml.push_str(&hash("otto", "operator", "operator-pass"));
    std::fs::write(dir.join("automat.toml"), toml).expect("toml");
    dir
}

/// 200 counters that all change every scan, for the update-rate figure,
/// and a division by zero when `trip` is written, for the fault's display.
fn counters() -> PathBuf {
    let dir = temp("load");
    std::fs::write(
        dir.join("load.st"),
        "PROGRAM Load\nVAR\n    v : ARRAY[1..200] OF DINT;\n    i : INT;\n    trip : BOOL;\n    \
         zero : DINT;\n    q : DINT;\nEND_VAR\n\
         FOR i := 1 TO 200 DO\n    v[i] := v[i] + i;\nEND_FOR;\n\
         IF trip THEN\n    q := v[1] / zero;\nEND_IF;\nEND_PROGRAM\n",
    )
    .expect("load.st");
    dir
}

struct Plc {
    child: Child,
    url: String,
    token: String,
}

impl Drop for Plc {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn start(target: &Path, token_dir: &Path, extra: &[&str]) -> Plc {
    let token_file = token_dir.join("token");
    let mut child = Command::new(bin())
        .arg("run")
        .arg(target)
        .arg("--listen")
        .arg("0")
        .arg("--token-file")
        .arg(&token_file)
        .args(extra)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("automat run --listen");
    let stderr = child.stderr.take().expect("stderr");
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        for line in BufReader::new(stderr).lines().map_while(Result::ok) {
            eprintln!("automat: {line}");
            let _ = tx.send(line);
        }
    });
    let url = loop {
        let line = rx
            .recv_timeout(Duration::from_secs(120))
            .expect("automat run --listen did not announce its address");
        if let Some(rest) = line.split("PLC API on ").nth(1) {
            let addr = rest.split("/api/v1/ ").next().expect("address");
            break addr.to_string();
        }
    };
    let token = std::fs::read_to_string(&token_file)
        .expect("the token file is created")
        .trim()
        .to_string();
    Plc { child, url, token }
}

#[test]
fn the_hmi_in_headless_chromium() {
    browser_ready();
    let crane_dir = crane();
    let plc = start(&crane_dir, &crane_dir, &["--virtual-clock"]);
    let load_dir = counters();
    let load = start(&load_dir.join("load.st"), &load_dir, &[]);
    let ld_dir = temp("crane-ld");
    for f in ["automat.toml", "crane.xml"] {
        std::fs::copy(root().join("examples/crane-ld").join(f), ld_dir.join(f)).expect("copy");
    }
    let ld = start(&ld_dir, &ld_dir, &["--virtual-clock"]);
    let slc_dir = temp("crane-slc");
    for f in ["automat.toml", "crane.slc"] {
        std::fs::copy(root().join("examples/crane-slc").join(f), slc_dir.join(f)).expect("copy");
    }
    let slc = start(&slc_dir, &slc_dir, &["--virtual-clock"]);
    let shots = temp("shots");
    let out = Command::new("python3")
        .arg(root().join("crates/cli/tests/hmi/hmi_browser.py"))
        .args([&plc.url, &plc.token, &load.url, &load.token])
        .arg(&shots)
        .args([&ld.url, &ld.token])
        .args([&slc.url, &slc.token])
        .output()
        .expect("python3");
    let text = String::from_utf8_lossy(&out.stdout);
    println!("{text}{}", String::from_utf8_lossy(&out.stderr));
    assert!(out.status.success(), "the browser test failed:\n{text}");
    assert!(text.contains(" passed, 0 failed"), "{text}");
    assert!(text.contains("updates/s rendered"), "{text}");
    if std::env::var_os("UPDATE_DOCS").is_some() {
        let docs = root().join("docs/hmi");
        std::fs::create_dir_all(&docs).expect("docs/hmi");
        for view in [
            "overview", "watch", "charts", "drawings", "trends", "plant", "fault",
        ] {
            let name = format!("{view}.png");
            std::fs::copy(shots.join(&name), docs.join(&name)).expect("screenshot");
        }
    }
}

/// The chart view's condition evaluator (which marks the transitions that
/// can fire), run by Node.js on the page's own `charts.js`: crane and PL7
/// (`%Xi.T`) conditions with exact verdicts.
#[test]
fn chart_conditions_are_evaluated_as_the_page_does() {
    let out = Command::new("node")
        .arg(root().join("crates/cli/tests/hmi/charts_eval.js"))
        .arg(root().join("crates/online/hmi/charts.js"))
        .output()
        .expect("Node.js (`node`) is needed for this test: apt-get install nodejs");
    let text = String::from_utf8_lossy(&out.stdout);
    println!("{text}{}", String::from_utf8_lossy(&out.stderr));
    assert!(out.status.success(), "{text}");
    assert!(text.contains(" passed, 0 failed"), "{text}");
}
