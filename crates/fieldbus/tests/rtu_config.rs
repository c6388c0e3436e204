//! `[modbus.rtu_server]` and `[[modbus.rtu_device]]` through
//! `config::load`: the settings as read (defaults of the specification:
//! 19200 baud, even parity, one stop bit, unit 1) and each E345 with its
//! message and the key it points at.

use automat_base::{Code, SourceMap};
use automat_fieldbus::client::Link;
use automat_fieldbus::config;
use automat_fieldbus::serial::{Line, Parity};
use automat_ir::Program;
use automat_project::build;

fn program() -> Program {
    // A folder per call: the tests run in parallel.
    static N: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = N.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!("automat-rtu-config-{}-{n}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let file = dir.join("main.st");
    std::fs::write(
        &file,
        "PROGRAM Main\nVAR\n  w AT %IW0 : INT;\n  q AT %QW0 : INT;\n  ok : BOOL;\nEND_VAR\n  q := w;\nEND_PROGRAM\n",
    )
    .expect("source");
    build::compile(&[file], None, &[])
        .unwrap_or_else(|e| panic!("{}", e.text))
        .0
}

/// The E345 messages with the text each points at.
fn errors(toml: &str) -> Vec<(String, String)> {
    let mut map = SourceMap::new();
    let id = map.add("automat.toml", toml.to_string());
    let diags = config::load(toml, id, &program()).expect_err("errors");
    diags
        .iter()
        .map(|d| {
            assert_eq!(d.code, Code::E345, "{}", d.message);
            let at = &toml[d.span.start as usize..d.span.end as usize];
            (d.message.clone(), at.to_string())
        })
        .collect()
}

const READ: &str =
    "[[modbus.rtu_device.read]]\ntable = \"input_registers\"\naddress = 0\nto = \"%IW0\"\n";

#[test]
fn settings_are_read_with_the_specifications_defaults() {
    let toml = format!(
        "[modbus.rtu_server]\ndevice = \"/dev/ttyS1\"\n\n[[modbus.rtu_device]]\nname = \"a\"\ndevice = \"/dev/ttyUSB0\"\nbaud = 38400\nparity = \"odd\"\nstop_bits = 2\nunit = 9\n{READ}"
    );
    let mut map = SourceMap::new();
    let id = map.add("automat.toml", toml.clone());
    let cfg = config::load(&toml, id, &program()).expect("valid");
    let s = cfg.rtu_server.expect("rtu server");
    assert_eq!(s.line, Line::new("/dev/ttyS1"));
    assert_eq!(
        (s.line.baud, s.line.parity, s.line.stop_bits, s.unit),
        (19_200, Parity::Even, 1, 1)
    );
    assert_eq!(s.line.describe(), "/dev/ttyS1 19200 8E1");
    assert_eq!(
        cfg.clients[0].link,
        Link::Rtu(Line {
            device: "/dev/ttyUSB0".into(),
            baud: 38_400,
            parity: Parity::Odd,
            stop_bits: 2
        })
    );
    assert_eq!(cfg.clients[0].unit, 9);
}

#[test]
fn bad_and_conflicting_lines_are_e345() {
    assert_eq!(
        errors("[modbus.rtu_server]\ndevice = \"/dev/x\"\nbaud = 10\nparity = \"mark\"\nstop_bits = 3\nunit = 0\n"),
        [
            ("baud 10 is outside 50..=4000000".to_string(), "10".to_string()),
            ("parity `mark` is not none, even or odd".into(), "\"mark\"".into()),
            ("stop_bits 3 is not 1 or 2".into(), "3".into()),
            (
                "[modbus.rtu_server]: unit 0 is outside 1..=247 (0 is the broadcast address)".into(),
                "0".into()
            ),
        ]
    );
    let dev = |name: &str, unit: u32, baud: u32| {
        format!("[[modbus.rtu_device]]\nname = \"{name}\"\ndevice = \"/dev/ttyS0\"\nbaud = {baud}\nunit = {unit}\n{READ}\n")
    };
    let two = format!(
        "{}{}{}",
        dev("a", 1, 9600),
        dev("b", 1, 9600),
        dev("c", 2, 19200)
    );
    assert_eq!(
        errors(&two),
        [
            ("unit 1 is already a device on /dev/ttyS0".to_string(), "\"b\"".to_string()),
            (
                "devices on one port share its settings: /dev/ttyS0 19200 8E1 here, /dev/ttyS0 9600 8E1 before".into(),
                "\"c\"".into()
            ),
        ]
    );
    let shared = format!(
        "[modbus.rtu_server]\ndevice = \"/dev/ttyS0\"\n\n{}",
        dev("a", 1, 19200)
    );
    assert_eq!(
        errors(&shared),
        [(
            "/dev/ttyS0 is the port of [modbus.rtu_server]: one port is either the slave's or the master's".to_string(),
            "\"a\"".to_string()
        )]
    );
    assert_eq!(
        errors("[[modbus.rtu_device]]\nname = \"x\"\naddress = \"127.0.0.1:502\"\n"),
        [
            (
                "RTU device `x` is on a serial line: `device = \"/dev/ttyS0\"`, not `address`"
                    .to_string(),
                "\"127.0.0.1:502\"".to_string()
            ),
            (
                "RTU device `x` has no `device` (its serial port, e.g. \"/dev/ttyUSB0\")".into(),
                "\"x\"".into()
            ),
        ]
    );
    assert_eq!(
        errors("[[modbus.client]]\nname = \"t\"\naddress = \"127.0.0.1:502\"\nbaud = 9600\n"),
        [(
            "device `t` is a Modbus TCP device: serial settings belong to a `[[modbus.rtu_device]]`".to_string(),
            "9600".to_string()
        )]
    );
}
