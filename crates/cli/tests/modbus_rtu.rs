//! Modbus RTU end to end over a serial line: a socat pseudo-terminal pair
//! (`socat pty,raw,echo=0,link=DIR/a pty,raw,echo=0,link=DIR/b`), automat
//! on one end and pymodbus's serial side (pyserial) on the other: automat
//! as slave against pymodbus's client (`tests/modbus/rtu_check.py`), and
//! automat as master of two pymodbus slaves on one line
//! (`tests/modbus/rtu_device.py`). socat is Debian's package, pyserial and
//! pymodbus come from PyPI (`.ci/run`).

#[path = "support/common.rs"]
mod common;

use common::{bin, pymodbus_ready, scripts, temp, Proc};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

fn serial_ready() {
    pymodbus_ready();
    let socat = Command::new("socat")
        .arg("-V")
        .output()
        .is_ok_and(|o| o.status.success());
    assert!(
        socat,
        "socat is needed: apt-get install socat (as .ci/run does)"
    );
    let pyserial = Command::new("python3")
        .args(["-c", "import serial"])
        .status()
        .is_ok_and(|s| s.success());
    assert!(
        pyserial,
        "pyserial is needed: python3 -m pip install pyserial (as .ci/run does)"
    );
}

/// A pseudo-terminal pair `dir/a` <-> `dir/b`, gone when dropped.
struct Line {
    _socat: Proc,
    a: PathBuf,
    b: PathBuf,
}

fn line(dir: &Path) -> Line {
    let (a, b) = (dir.join("a"), dir.join("b"));
    let socat = Proc::start(
        Command::new("socat").args([
            "-d",
            "-d",
            &format!("pty,raw,echo=0,link={}", a.display()),
            &format!("pty,raw,echo=0,link={}", b.display()),
        ]),
        "socat",
    );
    socat.wait_for("starting data transfer loop", Duration::from_secs(20));
    let end = Instant::now() + Duration::from_secs(10);
    while !(a.exists() && b.exists()) {
        assert!(Instant::now() < end, "socat made no {a:?} and {b:?}");
        std::thread::sleep(Duration::from_millis(20));
    }
    Line {
        _socat: socat,
        a,
        b,
    }
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
fn a_pymodbus_serial_master_reads_and_writes_automat_as_rtu_slave() {
    serial_ready();
    let dir = temp("rtu-slave");
    let l = line(&dir);
    std::fs::write(dir.join("main.st"), SERVED).expect("source");
    std::fs::write(
        dir.join("automat.toml"),
        format!(
            "[project]\nname = \"rtu\"\n\n[modbus.rtu_server]\ndevice = \"{}\"\nbaud = 19200\nparity = \"none\"\n\
             stop_bits = 1\nunit = 3\n\n[[modbus.rtu_server.map]]\nvar = \"Main.speed\"\ntable = \"holding_registers\"\naddress = 9000\n",
            l.a.display()
        ),
    )
    .expect("toml");
    let mut plc = Proc::start(Command::new(bin()).arg("run").arg(&dir), "automat");
    let started = plc.wait_for("Modbus RTU slave 3 on ", Duration::from_secs(120));
    assert!(
        started.ends_with("19200 8N1 (docs/modbus.md); Ctrl-C stops"),
        "{started}"
    );
    let out = Command::new("python3")
        .arg(scripts().join("rtu_check.py"))
        .arg(&l.b)
        .output()
        .expect("python3");
    let text = String::from_utf8_lossy(&out.stdout);
    eprintln!("{text}{}", String::from_utf8_lossy(&out.stderr));
    assert!(out.status.success(), "rtu_check.py failed:\n{text}");
    assert_eq!(text.lines().last(), Some("18 passed, 0 failed"));
    assert_eq!(plc.stop(), Some(0));
}

#[test]
fn automat_as_rtu_master_drives_two_pymodbus_slaves_on_one_line() {
    serial_ready();
    let dir = temp("rtu-master");
    let l = line(&dir);
    let dev = Proc::start(
        Command::new("python3")
            .arg(scripts().join("rtu_device.py"))
            .arg(&l.b),
        "device",
    );
    dev.wait_for("listening", Duration::from_secs(30));
    std::fs::write(
        dir.join("main.st"),
        "PROGRAM Main
VAR
    a AT %IX0.0 : BOOL;
    b AT %IX0.1 : BOOL;
    c AT %IX0.2 : BOOL;
    w AT %IW1 : INT;
    x AT %IW2 : WORD;
    r2 AT %IW3 : INT;
    qa AT %QX0.0 : BOOL;
    qb AT %QX0.1 : BOOL;
    q AT %QW1 : INT;
    qx AT %QW2 : WORD;
    q2 AT %QW3 : INT;
    ok : BOOL;
    ok2 : BOOL;
    errors : UDINT;
    code : INT;
END_VAR
    qa := a AND c;
    qb := b;
    q := w * 3;
    qx := x;
    q2 := r2 + 1;
END_PROGRAM
",
    )
    .expect("source");
    let serial = format!(
        "device = \"{}\"\nbaud = 38400\nparity = \"none\"\nstop_bits = 2\nperiod = \"20ms\"\ntimeout = \"300ms\"\n",
        l.a.display()
    );
    std::fs::write(
        dir.join("automat.toml"),
        format!(
            "[project]\nname = \"rtu-master\"\n\n\
             [[modbus.rtu_device]]\nname = \"one\"\nunit = 1\n{serial}connected = \"Main.ok\"\nerrors = \"Main.errors\"\nlast_error = \"Main.code\"\n\n\
             [[modbus.rtu_device.read]]\ntable = \"discrete_inputs\"\naddress = 0\ncount = 3\nto = \"%IX0.0\"\n\n\
             [[modbus.rtu_device.read]]\ntable = \"holding_registers\"\naddress = 0\ncount = 2\nto = \"%IW1\"\n\n\
             [[modbus.rtu_device.write]]\ntable = \"coils\"\naddress = 0\ncount = 2\nfrom = [\"Main.qa\", \"Main.qb\"]\n\n\
             [[modbus.rtu_device.write]]\ntable = \"holding_registers\"\naddress = 10\ncount = 2\nfrom = \"%QW1\"\n\n\
             [[modbus.rtu_device]]\nname = \"two\"\nunit = 2\n{serial}connected = \"Main.ok2\"\n\n\
             [[modbus.rtu_device.read]]\ntable = \"holding_registers\"\naddress = 0\nto = \"Main.r2\"\n\n\
             [[modbus.rtu_device.write]]\ntable = \"holding_registers\"\naddress = 5\nfrom = \"Main.q2\"\n"
        ),
    )
    .expect("toml");
    let mut plc = Proc::start(
        Command::new(bin()).arg("run").arg(&dir).args([
            "--print",
            "Main.ok",
            "--print",
            "Main.ok2",
            "--print",
            "Main.errors",
            "--print",
            "Main.code",
        ]),
        "automat",
    );
    // `ok` needs both units: unit 2's register 5 = 101 is what the PLC
    // read from unit 2 plus one, written back over the same line.
    dev.wait_for("ok", Duration::from_secs(60));
    // The slaves are gone: the master times out (last_error -1) and goes
    // on.
    drop(dev);
    std::thread::sleep(Duration::from_millis(1500));
    assert_eq!(plc.stop(), Some(0));
    let lines = plc.drain();
    assert!(lines.iter().any(|l| l == "Main.ok2 = FALSE"), "{lines:?}");
    assert!(lines.iter().any(|l| l == "Main.ok = FALSE"), "{lines:?}");
    assert!(lines.iter().any(|l| l == "Main.code = -1"), "{lines:?}");
    let errors: u32 = lines
        .iter()
        .find_map(|l| l.strip_prefix("Main.errors = "))
        .and_then(|n| n.parse().ok())
        .expect("Main.errors printed");
    // 1.5 s of a dead line at 300 ms a timeout (retry included): a few.
    assert!((1..=10).contains(&errors), "{errors} errors");
}
