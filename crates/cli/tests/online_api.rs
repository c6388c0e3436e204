//! `automat run --listen` end to end: the real binary on a free loopback
//! port, driven by a real client (Python `requests` and `websockets`,
//! installed by `.ci/run`): `tests/online/api_client.py` holds the checks.

#[path = "support/common.rs"]
mod common;

use common::{bin, hash, root};
use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::time::Duration;

fn python_ready() {
    let ok = Command::new("python3")
        .args(["-c", "import requests, websockets.sync.client"])
        .status()
        .is_ok_and(|s| s.success());
    assert!(
        ok,
        "python3 with `requests` and `websockets` is needed: \
         python3 -m pip install requests websockets (as .ci/run does)"
    );
}

/// The crane example in a temporary folder, with two users.
fn project(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("automat-online-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
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

struct Plc {
    child: Child,
    url: String,
    token: String,
}

/// Starts `automat run DIR --token-file … EXTRA` (EXTRA has `--listen`)
/// and waits for its address.
fn start(dir: &Path, extra: &[&str]) -> Plc {
    let token_file = dir.join("token");
    let mut child = Command::new(bin())
        .arg("run")
        .arg(dir)
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

fn client(mode: &str, plc: &Plc) {
    client_with(mode, plc, &[]);
}

fn client_with(mode: &str, plc: &Plc, extra: &[&str]) {
    let out = Command::new("python3")
        .arg(root().join("crates/cli/tests/online/api_client.py"))
        .args([mode, &plc.url, &plc.token])
        .args(extra)
        .output()
        .expect("python3");
    let text = String::from_utf8_lossy(&out.stdout);
    println!("{text}{}", String::from_utf8_lossy(&out.stderr));
    assert!(out.status.success(), "the API client failed:\n{text}");
    assert!(text.contains(" passed, 0 failed"), "{text}");
}

/// Ctrl-C (SIGINT) ends the run cleanly: exit 0.
fn interrupt(mut plc: Plc) {
    let pid = plc.child.id().to_string();
    let sent = Command::new("kill").args(["-INT", &pid]).status();
    assert!(sent.is_ok_and(|s| s.success()), "kill -INT");
    let deadline = std::time::Instant::now() + Duration::from_secs(30);
    loop {
        if let Some(status) = plc.child.try_wait().expect("wait") {
            assert!(status.success(), "automat exited with {status}");
            return;
        }
        if std::time::Instant::now() > deadline {
            let _ = plc.child.kill();
            panic!("automat did not stop on SIGINT");
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

#[test]
fn the_api_contract_from_a_python_client_on_the_virtual_clock() {
    python_ready();
    let dir = project("exact");
    let plc = start(&dir, &["--listen", "0", "--virtual-clock"]);
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        let mode = std::fs::metadata(dir.join("token"))
            .expect("token")
            .permissions()
            .mode();
        assert_eq!(mode & 0o777, 0o600);
    }
    client("exact", &plc);
    interrupt(plc);
}

/// FST online status: each STL program's run state and step, the operands
/// by FST name and symbol, through the same API (the MPS station in STL).
#[test]
fn festo_stl_programs_online_status() {
    python_ready();
    let dir = std::env::temp_dir().join(format!("automat-online-fst-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    let src = root().join("examples/festo-distribution-stl");
    for f in ["automat.toml", "allocation.txt", "P0.stl", "P1.stl"] {
        std::fs::copy(src.join(f), dir.join(f)).expect("copy");
    }
    let plc = start(&dir, &["--listen", "0", "--virtual-clock"]);
    client("fst", &plc);
    interrupt(plc);
}

/// The LD/FBD drawings of the HMI through the API: the PID loop in FBD
/// (`GET /api/v1/drawings` resolved against its instances, pins of a
/// function block instance, variable elements).
#[test]
fn fbd_drawings_through_the_api() {
    python_ready();
    let dir = std::env::temp_dir().join(format!("automat-online-fbd-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    let src = root().join("examples/pid-temperature-fbd");
    for f in ["automat.toml", "pid.xml"] {
        std::fs::copy(src.join(f), dir.join(f)).expect("copy");
    }
    let plc = start(&dir, &["--listen", "0", "--virtual-clock"]);
    client("fbd", &plc);
    interrupt(plc);
}

/// The SLC-500 ladder's drawing through the API: LAD 2 of the crane run by
/// the program `SLC`, power flows, bits and the timer's ACC resolved.
#[test]
fn slc_drawings_through_the_api() {
    python_ready();
    let dir = std::env::temp_dir().join(format!("automat-online-slc-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    let src = root().join("examples/crane-slc");
    for f in ["automat.toml", "crane.slc"] {
        std::fs::copy(src.join(f), dir.join(f)).expect("copy");
    }
    let plc = start(&dir, &["--listen", "0", "--virtual-clock"]);
    client("slc", &plc);
    interrupt(plc);
}

#[test]
fn the_plant_is_read_and_operated_through_the_api() {
    python_ready();
    let dir = project("plant");
    let plc = start(&dir, &["--listen", "0", "--virtual-clock"]);
    client("plant", &plc);
    interrupt(plc);
}

#[test]
fn hostile_clients_do_not_stop_the_scan_in_real_time() {
    python_ready();
    let dir = project("robust");
    let plc = start(&dir, &["--listen", "0"]);
    client("robust", &plc);
    interrupt(plc);
}

#[test]
fn listen_refuses_what_does_not_apply_and_plain_http_off_loopback() {
    let crane = root().join("examples/crane");
    let run = |args: &[&str]| {
        Command::new(bin())
            .arg("run")
            .arg(&crane)
            .args(args)
            .output()
            .expect("automat")
    };
    let out = run(&["--listen", "0", "--duration", "1s"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr)
        .contains("error: --duration does not apply with --listen"));
    let out = run(&["--listen", "0.0.0.0:0"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(
        err.contains(
            "a non-loopback address needs TLS (--tls-cert FILE --tls-key FILE), or --insecure"
        ),
        "{err}"
    );
    // No credentials at all: refused (the crane has no [users]).
    let out = run(&["--listen", "0"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--listen needs credentials"));
}

#[test]
fn the_live_view_forces_and_watches_through_the_session() {
    let mut child = Command::new(bin())
        .arg("run")
        .arg(root().join("examples/crane"))
        .args(["--speed", "10"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("automat run");
    let mut stdin = child.stdin.take().expect("stdin");
    for line in [
        "force Ctrl.l1 FALSE",
        "watch Ctrl.startEdge.Q",
        "force Ctrl.GS1.x TRUE",
        "write Ctrl.M1S 2",
        "help",
    ] {
        writeln!(stdin, "{line}").expect("command");
        // One redraw a second shows each answer.
        std::thread::sleep(Duration::from_millis(1100));
    }
    writeln!(stdin, "quit").expect("quit");
    let out = child.wait_with_output().expect("wait");
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("ok: force Ctrl.l1 FALSE"), "{text}");
    assert!(text.contains("FORCED: Ctrl.l1=FALSE"), "{text}");
    // The plant's own sensor stays on; the program sees the forced value.
    assert!(text.contains("in:    Pornire=0 l1=1 "), "{text}");
    assert!(text.contains("Ctrl.l1=FALSE"), "{text}");
    assert!(text.contains("Ctrl.startEdge.Q=FALSE"), "{text}");
    assert!(
        text.contains("`force Ctrl.GS1.x TRUE`: `Ctrl.GS1.x` is a step flag"),
        "{text}"
    );
    assert!(
        text.contains("`write Ctrl.M1S 2`: `Ctrl.M1S`: expected a value of type BOOL"),
        "{text}"
    );
    assert!(text.contains("program: watch PATH"), "{text}");
}

#[test]
fn speed_is_refused_where_it_does_not_apply() {
    let out = Command::new(bin())
        .arg("run")
        .arg(root().join("examples/crane"))
        .args(["--speed", "2", "--duration", "1s"])
        .output()
        .expect("automat");
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr)
        .contains("error: --speed applies to real-time runs; this one is on the virtual clock"));
}

#[test]
fn https_and_wss_with_a_certificate() {
    python_ready();
    let dir = project("tls");
    let (cert, key) = (dir.join("cert.pem"), dir.join("key.pem"));
    let made = Command::new("openssl")
        .args([
            "req",
            "-x509",
            "-newkey",
            "ec",
            "-pkeyopt",
            "ec_paramgen_curve:prime256v1",
        ])
        .args(["-nodes", "-days", "2", "-subj", "/CN=localhost"])
        .args([
            "-addext",
            "subjectAltName=IP:127.0.0.1,DNS:localhost",
            "-keyout",
        ])
        .arg(&key)
        .arg("-out")
        .arg(&cert)
        .output()
        .expect("openssl (installed by .ci/run) makes the test certificate");
    assert!(
        made.status.success(),
        "{}",
        String::from_utf8_lossy(&made.stderr)
    );
    let cert_s = cert.display().to_string();
    let key_s = key.display().to_string();
    let plc = start(
        &dir,
        &[
            "--virtual-clock",
            "--listen",
            "127.0.0.1:0",
            "--tls-cert",
            &cert_s,
            "--tls-key",
            &key_s,
        ],
    );
    assert!(plc.url.starts_with("https://127.0.0.1:"), "{}", plc.url);
    client_with("tls", &plc, &[&cert_s]);
    interrupt(plc);
}

/// A project served online keeps its `[retain]` file (periodic saves from
/// the session's keeper) and stops on SIGTERM in its safe state, with the
/// note every run gives: exit 0.
#[test]
fn a_served_project_saves_retain_and_stops_in_its_safe_state_on_sigterm() {
    let dir = project("retain-safe");
    let file = dir.join("plc.retain");
    let mut toml = std::fs::read_to_string(dir.join("automat.toml")).expect("toml");
    toml.push_str("\n[retain]\nfile = \"plc.retain\"\nsave_every = \"20ms\"\n");
    std::fs::write(dir.join("automat.toml"), toml).expect("toml");
    let child = Command::new(bin())
        .arg("run")
        .arg(&dir)
        .args(["--listen", "0", "--token-file"])
        .arg(dir.join("token"))
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("automat run --listen");
    // The first periodic save shows the PLC runs, however loaded the machine.
    let deadline = std::time::Instant::now() + Duration::from_secs(60);
    while !file.exists() {
        assert!(
            std::time::Instant::now() < deadline,
            "no RETAIN save in 60 s"
        );
        std::thread::sleep(Duration::from_millis(10));
    }
    let sent = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status();
    assert!(sent.is_ok_and(|s| s.success()), "kill -TERM");
    let out = child.wait_with_output().expect("wait");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    // The project's safe state: the %Q area and the actuator-bound outputs.
    assert_eq!(
        stderr.lines().last(),
        Some(
            "note: stopped at the end of a scan, in the safe state: the %Q area (4 bytes) and \
             4 outputs (%QX3.1, M1D, M2S, M2J) set to 0/FALSE"
        ),
        "{stderr}"
    );
    assert!(std::fs::metadata(&file).is_ok_and(|m| m.len() > 0));
}
