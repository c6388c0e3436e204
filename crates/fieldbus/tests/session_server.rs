//! The Modbus server over a real PLC session, through its socket: the
//! OpenPLC default map, explicit entries, exceptions, the session's write
//! rules (a forced location stays forced), read-only servers.

use automat_base::SourceMap;
use automat_engine::Engine;
use automat_fieldbus::client::Conn;
use automat_fieldbus::config;
use automat_fieldbus::map::Map;
use automat_fieldbus::pdu::{Request, Response, Table};
use automat_fieldbus::server::{self, Options, SessionDevice};
use automat_project::build;
use automat_runtime::{ClockMode, SystemClock};
use automat_session::{Config, Control, Parts, Session};
use std::net::SocketAddr;
use std::sync::atomic::AtomicBool;
use std::sync::Arc;
use std::time::Duration;

const PROGRAM: &str = "
PROGRAM Main
VAR
    inA AT %IW0 : INT;
    inB AT %IX2.3 : BOOL;
    out AT %QW0 : INT;
    out2 AT %QW1 : WORD;
    coil AT %QX4.2 : BOOL;
    m AT %MD1 : DINT;
    speed : REAL := 1.5;
    small : SINT := -3;
    levels : ARRAY[1..3] OF DINT := [10, -20, 30];
    n : INT;
END_VAR
VAR CONSTANT
    LIMIT : INT := 99;
END_VAR
    n := n + 1;
    out := inA * 2;
END_PROGRAM
";

fn session() -> Arc<Session> {
    static NEXT: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!("automat-modbus-{}-{n}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let file = dir.join("main.st");
    std::fs::write(&file, PROGRAM).expect("write source");
    let (program, _) = build::compile(&[file], None, &[]).unwrap_or_else(|e| panic!("{}", e.text));
    let program = Arc::new(program);
    let p = (*program).clone();
    let config = Config {
        cycle_time_ns: 10_000_000,
        clock: ClockMode::Virtual,
        monotonic: Box::new(SystemClock::new()),
        running: false,
        stop: Arc::new(AtomicBool::new(false)),
        retain: None,
        safe: None,
        realtime: None,
        wait_after_fault: true,
    };
    let s = Session::start(
        program,
        config,
        Box::new(move || {
            Ok(Parts {
                exec: Box::new(Engine::new(p)),
                sim: None,
                observer: None,
                exchange: None,
            })
        }),
    )
    .expect("session");
    Arc::new(s)
}

fn serve(s: &Arc<Session>, map: Map) -> server::Server {
    let dev = SessionDevice {
        session: Arc::clone(s),
        map,
    };
    server::start(
        Arc::new(dev),
        Options::new(SocketAddr::from(([127, 0, 0, 1], 0))),
    )
    .expect("server")
}

fn conn(srv: &server::Server) -> Conn {
    Conn::connect(srv.addr, 1, Duration::from_secs(5)).expect("connect")
}

fn regs(c: &mut Conn, table: Table, addr: u16, count: u16) -> Result<Vec<u16>, String> {
    match c.call(&Request::Read { table, addr, count })? {
        Response::Registers(r) => Ok(r),
        other => Err(format!("{other:?}")),
    }
}

fn bits(c: &mut Conn, table: Table, addr: u16, count: u16) -> Result<Vec<bool>, String> {
    match c.call(&Request::Read { table, addr, count })? {
        Response::Bits(b) => Ok(b),
        other => Err(format!("{other:?}")),
    }
}

fn read(s: &Session, path: &str) -> String {
    s.read(&[path.to_string()]).expect("read")[0].1.clone()
}

#[test]
fn the_default_map_reads_and_writes_the_image_as_openplc_does() {
    let s = session();
    let srv = serve(&s, Map::default_of(s.program()));
    let mut c = conn(&srv);
    // %IW0 := 21 by the session; the scan doubles it into %QW0.
    s.write("Main.inA", "21").unwrap();
    s.write("Main.inB", "TRUE").unwrap();
    s.control(Control::Step(1)).unwrap();
    assert_eq!(regs(&mut c, Table::InputRegisters, 0, 1), Ok(vec![21]));
    assert_eq!(regs(&mut c, Table::HoldingRegisters, 0, 1), Ok(vec![42]));
    // %IX2.3 is discrete input 8*2+3 = 19.
    assert_eq!(
        bits(&mut c, Table::DiscreteInputs, 16, 8),
        Ok(vec![false, false, false, true, false, false, false, false])
    );
    // FC 6 on %QW1, FC 5 on %QX4.2 (coil 34).
    c.call(&Request::WriteRegister {
        addr: 1,
        value: 0xBEEF,
    })
    .unwrap();
    c.call(&Request::WriteCoil {
        addr: 34,
        value: true,
    })
    .unwrap();
    assert_eq!(read(&s, "Main.out2"), "48879");
    assert_eq!(read(&s, "Main.coil"), "TRUE");
    assert_eq!(
        bits(&mut c, Table::Coils, 32, 3),
        Ok(vec![false, false, true])
    );
    // FC 16 on %MD1 = holding 2050..2051, low word first; the same bytes
    // are %MW2..%MW3 = holding 1026..1027, and the first half of %ML0's upper half.
    c.call(&Request::WriteRegisters {
        addr: 2050,
        values: vec![0x5678, 0x1234],
    })
    .unwrap();
    assert_eq!(read(&s, "Main.m"), "305419896");
    assert_eq!(
        regs(&mut c, Table::HoldingRegisters, 1024, 4),
        Ok(vec![0, 0, 0x5678, 0x1234])
    );
    assert_eq!(
        regs(&mut c, Table::HoldingRegisters, 4096, 4),
        Ok(vec![0, 0, 0x5678, 0x1234])
    );
    // FC 23: the write first, then the read.
    assert_eq!(
        c.call(&Request::ReadWrite {
            read_addr: 1024,
            read_count: 3,
            write_addr: 1024,
            values: vec![7],
        }),
        Ok(Response::Registers(vec![7, 0, 0x5678]))
    );
    // Past the areas: exception 02; the connection stays usable.
    for (table, addr) in [
        (Table::HoldingRegisters, 2),
        (Table::HoldingRegisters, 1028),
        (Table::HoldingRegisters, 2052),
        (Table::HoldingRegisters, 4100),
        (Table::InputRegisters, 1),
        (Table::Coils, 40),
        (Table::DiscreteInputs, 24),
    ] {
        let r = c.call(&Request::Read {
            table,
            addr,
            count: 1,
        });
        assert_eq!(
            r,
            Err("exception 02 (illegal data address)".into()),
            "{table:?} {addr}"
        );
    }
    let w = c.call(&Request::WriteRegisters {
        addr: 1,
        values: vec![1, 2],
    });
    assert_eq!(w, Err("exception 02 (illegal data address)".into()));
    // Nothing of a refused write was stored.
    assert_eq!(read(&s, "Main.out2"), "48879");
    assert_eq!(
        regs(&mut c, Table::HoldingRegisters, 0, 2),
        Ok(vec![42, 0xBEEF])
    );
    drop(c);
    drop(srv);
    let _ = s.shutdown();
}

#[test]
fn a_forced_location_stays_forced_and_read_only_servers_refuse_writes() {
    let s = session();
    let srv = serve(&s, Map::default_of(s.program()));
    let mut c = conn(&srv);
    s.force("Main.out2", "5").unwrap();
    c.call(&Request::WriteRegister { addr: 1, value: 9 })
        .unwrap();
    assert_eq!(regs(&mut c, Table::HoldingRegisters, 1, 1), Ok(vec![5]));
    s.control(Control::Step(2)).unwrap();
    assert_eq!(read(&s, "Main.out2"), "5");
    s.unforce("Main.out2").unwrap();
    c.call(&Request::WriteRegister { addr: 1, value: 9 })
        .unwrap();
    assert_eq!(read(&s, "Main.out2"), "9");
    drop(c);
    drop(srv);

    let mut map = Map::default_of(s.program());
    map.read_only = true;
    let srv = serve(&s, map);
    let mut c = conn(&srv);
    assert_eq!(
        c.call(&Request::WriteRegister { addr: 1, value: 1 }),
        Err("exception 01 (illegal function)".into())
    );
    assert_eq!(regs(&mut c, Table::HoldingRegisters, 1, 1), Ok(vec![9]));
    drop(c);
    drop(srv);
    let _ = s.shutdown();
}

fn load(s: &Session, toml: &str) -> Result<config::Config, String> {
    let mut map = SourceMap::new();
    let file = map.add("automat.toml", toml.to_string());
    config::load(toml, file, s.program()).map_err(|d| automat_base::render::render_report(&map, &d))
}

#[test]
fn explicit_entries_map_variables_with_their_type_and_word_order() {
    let s = session();
    let cfg = load(
        &s,
        r#"
[modbus.server]
listen = "127.0.0.1:0"

[[modbus.server.map]]
var = "Main.speed"
table = "holding_registers"
address = 9000

[[modbus.server.map]]
var = "Main.speed"
table = "input_registers"
address = 100
word_order = "low_first"

[[modbus.server.map]]
var = "Main.small"
table = "input_registers"
address = 200

[[modbus.server.map]]
var = "Main.LIMIT"
table = "input_registers"
address = 201

[[modbus.server.map]]
var = "Main.coil"
table = "discrete_inputs"
address = 500

[[modbus.server.map]]
var = "Main.levels"
table = "holding_registers"
address = 300
"#,
    )
    .unwrap();
    let srv = serve(&s, cfg.server.expect("server").map);
    let mut c = conn(&srv);
    // REAL 1.5 = 16#3FC00000.
    assert_eq!(
        regs(&mut c, Table::HoldingRegisters, 9000, 2),
        Ok(vec![0x3FC0, 0])
    );
    assert_eq!(
        regs(&mut c, Table::InputRegisters, 100, 2),
        Ok(vec![0, 0x3FC0])
    );
    // SINT −3 sign-extended; a CONSTANT is readable.
    assert_eq!(
        regs(&mut c, Table::InputRegisters, 200, 2),
        Ok(vec![0xFFFD, 99])
    );
    // 2.5 = 16#40200000, both words in one write.
    c.call(&Request::WriteRegisters {
        addr: 9000,
        values: vec![0x4020, 0],
    })
    .unwrap();
    assert_eq!(read(&s, "Main.speed"), "2.5");
    c.call(&Request::WriteCoil {
        addr: 34,
        value: true,
    })
    .unwrap();
    assert_eq!(bits(&mut c, Table::DiscreteInputs, 500, 1), Ok(vec![true]));
    // An array: its elements one after another, two registers each.
    assert_eq!(
        regs(&mut c, Table::HoldingRegisters, 300, 6),
        Ok(vec![0, 10, 0xFFFF, 0xFFEC, 0, 30])
    );
    c.call(&Request::WriteRegisters {
        addr: 302,
        values: vec![0, 7],
    })
    .unwrap();
    assert_eq!(read(&s, "Main.levels[2]"), "7");
    // The default map is still there.
    assert_eq!(regs(&mut c, Table::HoldingRegisters, 0, 1), Ok(vec![0]));
    drop(c);
    drop(srv);
    let _ = s.shutdown();
}

#[test]
fn bad_modbus_tables_are_diagnostics_at_their_key() {
    let s = session();
    let cases = [
        (
            "[modbus.server]\nlisten = \"127.0.0.1:0\"\nmax_connections = 0\n",
            "automat.toml:3:19: error[E340]: max_connections must be 1..=1024, not 0",
        ),
        (
            "[modbus.server]\nlisten = \"1\"\nallow = [\"10.0.0.0/40\"]\n",
            "automat.toml:3:10: error[E340]: allow: `10.0.0.0/40`: the prefix length must be 0..=32",
        ),
        (
            "[[modbus.server.map]]\n",
            "automat.toml:1:1: error[E340]: invalid [modbus] table: missing field `var`",
        ),
        (
            "[[modbus.client]]\nname = \"a\"\naddress = \"127.0.0.1:1\"\n[[modbus.client.read]]\ntable = \"coils\"\naddress = 0\ncount = 3\nto = \"Main.coil\"\n",
            "automat.toml:8:6: error[E342]: device `a`: count 3 differs from the 1 value(s) the variables hold",
        ),
        (
            "[[modbus.client]]\nname = \"a\"\naddress = \"127.0.0.1:1\"\n[[modbus.client.read]]\ntable = \"holding\"\naddress = 0\nto = \"Main.LIMIT\"\n",
            "automat.toml:7:6: error[E344]: `Main.LIMIT` is read-only: device `a` cannot write it",
        ),
        (
            "[[modbus.client]]\nname = \"a\"\naddress = \"127.0.0.1:1\"\n[[modbus.client.read]]\ntable = \"input_registers\"\naddress = 0\ncount = 2\nto = \"%IW0\"\n",
            "automat.toml:8:6: error[E342]: device `a`: 2 registers from `%IW0` reach past the end of its area (3 bytes: the program's highest address there)",
        ),
        (
            "[[modbus.client]]\nname = \"a\"\naddress = \"127.0.0.1:1\"\nconnected = \"Main.n\"\n",
            "automat.toml:4:13: error[E342]: `Main.n` is INT: a status variable is a BOOL",
        ),
        (
            "[[modbus.client]]\nname = \"a\"\naddress = \"127.0.0.1:1\"\n[[modbus.client.write]]\ntable = \"input_registers\"\naddress = 0\nfrom = \"%QW0\"\n",
            "automat.toml:5:9: error[E340]: device `a`: input_registers cannot be written; a write block goes to coils or holding_registers",
        ),
    ];
    for (toml, want) in cases {
        let got = load(&s, toml).map(|_| ()).unwrap_err();
        assert!(
            got.lines().any(|l| l.starts_with(want)),
            "want `{want}` in\n{got}"
        );
    }
    let _ = s.shutdown();
}
