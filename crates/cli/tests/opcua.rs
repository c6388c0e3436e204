//! The OPC UA server end to end with a real client: asyncua (PyPI, as
//! `.ci/run` installs it) against `automat run` with `[opcua]`
//! (`tests/opcua/opcua_check.py`): browse, typed reads, anonymous
//! read-only, an untrusted client certificate refused and then trusted
//! the documented way (moved from `rejected/` to `trusted/`), wrong
//! passwords refused, roles, writes, a subscription, Basic256Sha256 Sign
//! and SignAndEncrypt. The client certificate is made with openssl.
#![cfg(feature = "opcua")]

#[path = "support/common.rs"]
mod common;

use common::{bin, hash, temp, Proc};
use std::path::Path;
use std::process::Command;
use std::time::Duration;

const PROGRAM: &str = "
PROGRAM Main
VAR
    sensor : INT;
    level : INT;
    cmd : INT;
    lamp : BOOL;
    speed : REAL := 1.5;
    levels : ARRAY[1..3] OF DINT := [10, 20, 30];
    name : STRING[20] := 'tank';
    t : TON;
    wait : TIME := T#1500ms;
END_VAR
VAR CONSTANT
    LIMIT : INT := 99;
END_VAR
    level := sensor + 7;
    lamp := cmd > 10;
    t(IN := lamp, PT := wait);
END_PROGRAM
";

fn ready() {
    let asyncua = Command::new("python3")
        .args(["-c", "import asyncua"])
        .status()
        .is_ok_and(|s| s.success());
    assert!(
        asyncua,
        "python3 with asyncua is needed: python3 -m pip install asyncua (as .ci/run does)"
    );
}

fn run_check(url: &str, dir: &Path, phase: &str) -> String {
    let out = Command::new("python3")
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/opcua/opcua_check.py"))
        .arg(url)
        .arg(dir.join("cert.der"))
        .arg(dir.join("key.pem"))
        .arg(phase)
        .output()
        .expect("python3");
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    eprintln!("{text}{}", String::from_utf8_lossy(&out.stderr));
    assert!(
        out.status.success(),
        "opcua_check.py {phase} failed:\n{text}"
    );
    text
}

#[test]
fn an_asyncua_client_browses_reads_writes_and_subscribes_with_roles_and_encryption() {
    ready();
    let dir = temp("opcua");
    std::fs::write(dir.join("main.st"), PROGRAM).expect("source");
    std::fs::write(
        dir.join("globals.st"),
        "VAR_GLOBAL\n    total : UDINT;\nEND_VAR\n",
    )
    .expect("globals");
    let port = std::net::TcpListener::bind("127.0.0.1:0")
        .and_then(|l| l.local_addr())
        .map(|a| a.port())
        .expect("a free port");
    std::fs::write(
        dir.join("automat.toml"),
        format!(
            "[project]\nname = \"ua\"\n\n[opcua]\nlisten = \"127.0.0.1:{port}\"\n\n{}\n{}",
            hash("op", "operator", "secret-op1"),
            hash("view", "viewer", "secret-view2")
        ),
    )
    .expect("toml");
    // The client's certificate: self-signed, its application URI in the
    // subject alternative name, as OPC UA wants.
    let openssl = Command::new("openssl")
        .current_dir(&dir)
        .args([
            "req",
            "-x509",
            "-newkey",
            "rsa:2048",
            "-nodes",
            "-keyout",
            "key.pem",
            "-out",
            "cert.pem",
            "-days",
            "2",
            "-subj",
            "/CN=automat-test",
            "-addext",
            "subjectAltName=URI:urn:automat:test,DNS:localhost",
            "-addext",
            "keyUsage=digitalSignature,nonRepudiation,keyEncipherment,dataEncipherment",
            "-addext",
            "extendedKeyUsage=clientAuth",
        ])
        .output()
        .expect("openssl");
    assert!(
        openssl.status.success(),
        "{}",
        String::from_utf8_lossy(&openssl.stderr)
    );
    let der = Command::new("openssl")
        .current_dir(&dir)
        .args([
            "x509", "-in", "cert.pem", "-outform", "der", "-out", "cert.der",
        ])
        .status()
        .expect("openssl");
    assert!(der.success());

    let mut plc = Proc::start(Command::new(bin()).arg("run").arg(&dir), "automat");
    let line = plc.wait_for("OPC UA server on opc.tcp://", Duration::from_secs(120));
    assert!(
        line.contains(&format!(
            "opc.tcp://127.0.0.1:{port} (14 variables; anonymous read-only"
        )),
        "{line}"
    );
    let url = format!("opc.tcp://127.0.0.1:{port}/");
    let first = run_check(&url, &dir, "untrusted");
    assert_eq!(first.lines().last(), Some("17 passed, 0 failed"));
    // The refused certificate is in `rejected/`: trusting it is moving it.
    let pki = dir.join(".automat/opcua-pki");
    let rejected: Vec<_> = std::fs::read_dir(pki.join("rejected"))
        .expect("rejected/")
        .flatten()
        .collect();
    assert_eq!(rejected.len(), 1, "{rejected:?}");
    let name = rejected[0].file_name();
    assert!(
        name.to_string_lossy().starts_with("CN=automat-test ["),
        "{name:?}"
    );
    std::fs::create_dir_all(pki.join("trusted")).expect("trusted/");
    std::fs::rename(rejected[0].path(), pki.join("trusted").join(&name)).expect("trust");
    let second = run_check(&url, &dir, "trusted");
    assert_eq!(second.lines().last(), Some("13 passed, 0 failed"));
    assert_eq!(plc.stop(), Some(0));
}
