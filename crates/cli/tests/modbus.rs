//! Modbus TCP end to end with real processes: the pymodbus client
//! (`tests/modbus/client_check.py`) against `automat run` serving a
//! project, automat's client against a pymodbus device
//! (`tests/modbus/device.py`), and the crane's controller in one automat
//! process against `automat plant crane --modbus-server` in another
//! (`examples/crane-modbus`). pymodbus comes from PyPI (`.ci/run`).

#[path = "support/common.rs"]
mod common;

use automat_fieldbus::client::Conn;
use automat_fieldbus::pdu::{Request, Table};
use common::{bin, pymodbus_ready, root, scripts, temp, Proc};
use std::net::{SocketAddr, TcpListener};
use std::process::Command;
use std::time::{Duration, Instant};

/// A free loopback port (bound and released: the OS does not hand it out
/// again at once).
fn free_port() -> u16 {
    TcpListener::bind("127.0.0.1:0")
        .and_then(|l| l.local_addr())
        .map(|a| a.port())
        .expect("a free port")
}

const SERVED: &str = "
PROGRAM Main
VAR
    sensor AT %IW0 : INT;
    level AT %QW0 : INT;
    cmd AT %QW1 : INT;
    lamp AT %QX4.0 : BOOL;
    flags AT %QX4.7 : BOOL;
    total AT %MD0 : DINT;
    speed : REAL := 1.5;
END_VAR
    level := sensor + 7;
    lamp := cmd > 10;
END_PROGRAM
";

#[test]
fn a_pymodbus_client_reads_and_writes_the_plc_and_cannot_break_the_server() {
    pymodbus_ready();
    let dir = temp("served");
    std::fs::write(dir.join("main.st"), SERVED).expect("source");
    std::fs::write(
        dir.join("automat.toml"),
        "[project]\nname = \"served\"\n\n[modbus.server]\nlisten = \"127.0.0.1:0\"\nmax_connections = 4\n\n\
         [[modbus.server.map]]\nvar = \"Main.speed\"\ntable = \"holding_registers\"\naddress = 9000\n",
    )
    .expect("toml");
    let mut plc = Proc::start(Command::new(bin()).arg("run").arg(&dir), "automat");
    let line = plc.wait_for("Modbus TCP server on ", Duration::from_secs(120));
    let addr: SocketAddr = line
        .split("Modbus TCP server on ")
        .nth(1)
        .and_then(|r| r.split(' ').next())
        .and_then(|a| a.parse().ok())
        .expect("the server's address");
    assert!(addr.ip().is_loopback());
    let out = Command::new("python3")
        .arg(scripts().join("client_check.py"))
        .arg(addr.ip().to_string())
        .arg(addr.port().to_string())
        .output()
        .expect("python3");
    let text = String::from_utf8_lossy(&out.stdout);
    eprintln!("{text}{}", String::from_utf8_lossy(&out.stderr));
    assert!(out.status.success(), "client_check.py failed:\n{text}");
    assert_eq!(text.lines().last(), Some("24 passed, 0 failed"));
    assert_eq!(plc.stop(), Some(0));
}

#[test]
fn automats_client_drives_a_pymodbus_device() {
    pymodbus_ready();
    let port = free_port();
    let dev = Proc::start(
        Command::new("python3")
            .arg(scripts().join("device.py"))
            .arg(port.to_string()),
        "device",
    );
    dev.wait_for("listening", Duration::from_secs(30));
    let dir = temp("client");
    std::fs::write(
        dir.join("main.st"),
        "PROGRAM Main
VAR
    a AT %IX0.0 : BOOL;
    b AT %IX0.1 : BOOL;
    c AT %IX0.2 : BOOL;
    w AT %IW1 : INT;
    x AT %IW2 : WORD;
    qa AT %QX0.0 : BOOL;
    qb AT %QX0.1 : BOOL;
    q AT %QW1 : INT;
    qx AT %QW2 : WORD;
    ok : BOOL;
    errors : UDINT;
    code : INT;
END_VAR
    qa := a AND c;
    qb := b;
    q := w * 3;
    qx := x;
END_PROGRAM
",
    )
    .expect("source");
    std::fs::write(
        dir.join("automat.toml"),
        format!(
            "[project]\nname = \"client\"\n\n[[modbus.client]]\nname = \"dev\"\naddress = \"127.0.0.1:{port}\"\n\
             period = \"20ms\"\ntimeout = \"500ms\"\nconnected = \"Main.ok\"\nerrors = \"Main.errors\"\nlast_error = \"Main.code\"\n\n\
             [[modbus.client.read]]\ntable = \"discrete_inputs\"\naddress = 0\ncount = 3\nto = \"%IX0.0\"\n\n\
             [[modbus.client.read]]\ntable = \"holding_registers\"\naddress = 0\ncount = 2\nto = \"%IW1\"\n\n\
             [[modbus.client.write]]\ntable = \"coils\"\naddress = 0\ncount = 2\nfrom = [\"Main.qa\", \"Main.qb\"]\n\n\
             [[modbus.client.write]]\ntable = \"holding_registers\"\naddress = 10\ncount = 2\nfrom = \"%QW1\"\n"
        ),
    )
    .expect("toml");
    let mut plc = Proc::start(
        Command::new(bin()).arg("run").arg(&dir).args([
            "--print",
            "Main.ok",
            "--print",
            "Main.code",
        ]),
        "automat",
    );
    dev.wait_for("ok", Duration::from_secs(60));
    // The device is done and gone: the PLC sees the loss and goes on.
    drop(dev);
    std::thread::sleep(Duration::from_millis(500));
    assert_eq!(plc.stop(), Some(0));
    let lines = plc.drain();
    assert!(lines.iter().any(|l| l == "Main.ok = FALSE"), "{lines:?}");
    assert!(lines.iter().any(|l| l == "Main.code = -2"), "{lines:?}");
}

/// The crane's controller (examples/crane-modbus) against the crane plant
/// served by another process, both at 4× speed: one press of Pornire
/// (written to the plant's coil 4 by this test, as an HMI would) runs both
/// cycles, and the crane is back at rest position 1 with one cycle counted
/// and no motor conflict (the checks of `examples/crane/scenarios/normal.scn`
/// that the plant can tell).
#[test]
fn the_crane_runs_its_cycle_against_the_plant_over_modbus() {
    let port = free_port();
    let dir = temp("crane");
    let toml = std::fs::read_to_string(root().join("examples/crane-modbus/automat.toml"))
        .expect("toml")
        .replace("127.0.0.1:5502", &format!("127.0.0.1:{port}"))
        .replace(
            "../crane/",
            &format!("{}/", root().join("examples/crane").display()),
        );
    std::fs::write(dir.join("automat.toml"), toml).expect("toml");
    std::fs::copy(
        root().join("examples/crane-modbus/io.st"),
        dir.join("io.st"),
    )
    .expect("io.st");
    let mut plant = Proc::start(
        Command::new(bin()).args([
            "plant",
            "crane",
            "--modbus-server",
            &port.to_string(),
            "--speed",
            "4",
        ]),
        "plant",
    );
    plant.wait_for("as a Modbus TCP device on", Duration::from_secs(60));
    let mut plc = Proc::start(
        Command::new(bin()).arg("run").arg(&dir).args([
            "--speed",
            "4",
            "--print",
            "crane_errors",
            "--print",
            "Ctrl.GS1.x",
        ]),
        "automat",
    );
    let addr = SocketAddr::from(([127, 0, 0, 1], port));
    let mut hmi = Conn::connect(addr, 1, Duration::from_secs(5)).expect("connect");
    let read_di = |c: &mut Conn| match c.call(&Request::Read {
        table: Table::DiscreteInputs,
        addr: 0,
        count: 5,
    }) {
        Ok(automat_fieldbus::pdu::Response::Bits(b)) => b,
        other => panic!("{other:?}"),
    };
    // At rest position 1: l1 and l3.
    assert_eq!(read_di(&mut hmi), [false, true, false, true, false]);
    // Wait until the PLC polls the plant (its motors are written every period).
    std::thread::sleep(Duration::from_secs(1));
    hmi.call(&Request::WriteCoil {
        addr: 4,
        value: true,
    })
    .expect("press");
    std::thread::sleep(Duration::from_millis(200));
    hmi.call(&Request::WriteCoil {
        addr: 4,
        value: false,
    })
    .expect("release");
    // Both cycles take 33 s of plant time: 8.3 s at 4×; the REAL `cycles`
    // quantity is input registers 4..5.
    let end = Instant::now() + Duration::from_secs(40);
    let mut cycles = 0.0f32;
    while Instant::now() < end {
        if let Ok(automat_fieldbus::pdu::Response::Registers(r)) = hmi.call(&Request::Read {
            table: Table::InputRegisters,
            addr: 0,
            count: 8,
        }) {
            let real = |i: usize| f32::from_bits((u32::from(r[i]) << 16) | u32::from(r[i + 1]));
            cycles = real(4);
            let (x, y, conflicts) = (real(0), real(2), real(6));
            assert_eq!(conflicts, 0.0, "a motor was driven both ways");
            if cycles >= 1.0 && x <= 0.1 && y <= 0.05 {
                break;
            }
        }
        std::thread::sleep(Duration::from_millis(100));
    }
    assert_eq!(cycles, 1.0, "the crane did not complete its cycle");
    assert_eq!(read_di(&mut hmi), [false, true, false, true, false]);
    // The PLC sees the rest position at its next poll of the plant, one or
    // more periods later under load (GS8 -> GS1); at rest nothing else
    // happens, so a margin cannot hide a wrong state.
    std::thread::sleep(Duration::from_secs(2));
    drop(hmi);
    assert_eq!(plc.stop(), Some(0));
    let lines = plc.drain();
    assert!(lines.iter().any(|l| l == "crane_errors = 0"), "{lines:?}");
    assert!(lines.iter().any(|l| l == "Ctrl.GS1.x = TRUE"), "{lines:?}");
    assert_eq!(plant.stop(), Some(0));
}

/// `--modbus-server` on another address than loopback is refused before
/// anything runs: nothing would restrict who writes the PLC's outputs.
#[test]
fn a_modbus_server_open_to_every_host_is_refused() {
    let crane = root().join("examples/crane");
    let out = std::process::Command::new(bin())
        .args([
            "run",
            &crane.to_string_lossy(),
            "--modbus-server",
            "0.0.0.0:0",
        ])
        .stdin(std::process::Stdio::null())
        .output()
        .expect("run");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("would take writes from any host (Modbus has no passwords)"),
        "{err}"
    );
    let out = std::process::Command::new(bin())
        .args(["plant", "crane", "--modbus-server", "0.0.0.0:0"])
        .stdin(std::process::Stdio::null())
        .output()
        .expect("plant");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("serve a plant on 127.0.0.1"), "{err}");
}
