//! Robustness of the `[modbus]` reader: a project file with every kind of
//! Modbus table, mutated in many deterministic ways
//! (`crates/scenario/tests/support/mutate.rs`), is read with
//! `config::load` against a compiled program. It must give a config or
//! E340–E345 diagnostics whose spans lie inside the text; nothing may
//! panic or hang.

#[path = "../../scenario/tests/support/mutate.rs"]
mod mutate;

use automat_base::{Code, SourceMap};
use automat_fieldbus::config;
use automat_project::build;
use mutate::{brief, guarded, mutate, Rng};
use std::time::Duration;

const MUTANTS: usize = 2000;
const CASE_LIMIT: Duration = Duration::from_secs(3);

const PROGRAM: &str = "
PROGRAM Main
VAR
    inA AT %IW0 : INT;
    bits AT %IX2.3 : BOOL;
    out AT %QW0 : INT;
    lamp AT %QX4.2 : BOOL;
    m AT %MD1 : DINT;
    speed : REAL := 1.5;
    small : SINT;
    levels : ARRAY[1..3] OF DINT;
    big : ARRAY[0..4000] OF BOOL;
    text : STRING[10];
    ok : BOOL;
    errors : UDINT;
END_VAR
VAR CONSTANT
    LIMIT : INT := 99;
END_VAR
    out := inA;
END_PROGRAM
";

const TOML: &str = r#"[project]
name = "robust"

[modbus.server]
listen = "127.0.0.1:5020"
max_connections = 8
allow = ["127.0.0.1", "10.0.0.0/8"]
read_only = false
default_map = true
idle_timeout = "30s"

[[modbus.server.map]]
var = "Main.speed"
table = "holding_registers"
address = 9000
word_order = "low_first"

[[modbus.server.map]]
var = "Main.levels"
table = "input_registers"
address = 100

[[modbus.server.map]]
var = "Main.lamp"
table = "coils"
address = 700

[[modbus.client]]
name = "rio"
address = "127.0.0.1:5021"
unit = 3
period = "20ms"
timeout = "100ms"
retries = 2
on_loss = "hold"
connected = "Main.ok"
errors = "Main.errors"
last_error = "Main.small"

[[modbus.client.read]]
table = "discrete_inputs"
address = 0
count = 5
to = "%IX2.3"

[[modbus.client.read]]
table = "holding_registers"
address = 10
to = ["Main.speed", "Main.levels"]
word_order = "high_first"

[[modbus.client.write]]
table = "coils"
address = 0
count = 1
from = ["Main.lamp"]

[[modbus.client.write]]
table = "holding_registers"
address = 4
count = 1
from = "%QW0"

[modbus.rtu_server]
device = "/dev/ttyS1"
baud = 9600
parity = "even"
stop_bits = 1
unit = 7

[[modbus.rtu_server.map]]
var = "Main.speed"
table = "input_registers"
address = 200

[[modbus.rtu_device]]
name = "drive"
device = "/dev/ttyUSB0"
baud = 38400
parity = "none"
stop_bits = 2
unit = 4
connected = "Main.ok"

[[modbus.rtu_device.read]]
table = "input_registers"
address = 0
count = 1
to = "%IW0"
"#;

const WORDS: &[&str] = &[
    "[modbus.server]",
    "[[modbus.server.map]]",
    "[[modbus.client]]",
    "[[modbus.client.read]]",
    "[[modbus.client.write]]",
    "[modbus.rtu_server]",
    "[[modbus.rtu_device]]",
    "[[modbus.rtu_device.read]]",
    "device =",
    "baud =",
    "parity =",
    "stop_bits =",
    "unit =",
    "\"odd\"",
    "\"/dev/ttyS1\"",
    "248",
    "listen =",
    "var =",
    "table =",
    "address =",
    "count =",
    "to =",
    "from =",
    "word_order =",
    "\"coils\"",
    "\"discrete_inputs\"",
    "\"input_registers\"",
    "\"holding_registers\"",
    "\"Main.big\"",
    "\"Main.text\"",
    "\"Main.LIMIT\"",
    "\"%QX4.7\"",
    "\"%IW9999\"",
    "\"%MW0\"",
    "65535",
    "65536",
    "-1",
    "2000",
    "\"[::1]:0\"",
    "\"localhost:99999\"",
    "\"0s\"",
];

const NESTS: &[(&str, &str)] = &[("[", "]"), ("{", "}")];

#[test]
fn mutated_modbus_tables_never_crash() {
    let dir = std::env::temp_dir().join(format!("automat-modbus-robust-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let file = dir.join("main.st");
    std::fs::write(&file, PROGRAM).expect("source");
    let (program, _) = build::compile(&[file], None, &[]).unwrap_or_else(|e| panic!("{}", e.text));
    // The sample itself is valid.
    let mut map = SourceMap::new();
    let id = map.add("automat.toml", TOML.to_string());
    let cfg = config::load(TOML, id, &program)
        .unwrap_or_else(|d| panic!("{}", automat_base::render::render_report(&map, &d)));
    assert_eq!(cfg.clients.len(), 2);
    assert!(cfg.rtu_server.is_some());
    assert_eq!(cfg.clients[0].reads[1].count, 8);
    let (mut valid, mut failures) = (0, Vec::new());
    for seed in 0..MUTANTS as u64 {
        let mut rng = Rng::new(seed);
        let text =
            String::from_utf8_lossy(&mutate(&mut rng, TOML.as_bytes(), WORDS, NESTS)).into_owned();
        let r = guarded(&format!("seed {seed}"), CASE_LIMIT, || {
            let mut map = SourceMap::new();
            let id = map.add("automat.toml", text.clone());
            match config::load(&text, id, &program) {
                Ok(_) => valid += 1,
                Err(diags) => {
                    assert!(!diags.is_empty());
                    for d in &diags {
                        assert!(
                            matches!(
                                d.code,
                                Code::E340
                                    | Code::E341
                                    | Code::E342
                                    | Code::E343
                                    | Code::E344
                                    | Code::E345
                            ),
                            "{:?}",
                            d.code
                        );
                        assert!(d.span.end as usize <= text.len(), "span past the text");
                    }
                    let _ = automat_base::render::render_report(&map, &diags);
                }
            }
        });
        if let Err(e) = r {
            failures.push(format!("{e}\n  input: {:?}", brief(&text, 600)));
        }
    }
    eprintln!("modbus tables: {MUTANTS} mutants, {valid} valid");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert!(valid >= 30, "only {valid} mutants read as valid");
}
