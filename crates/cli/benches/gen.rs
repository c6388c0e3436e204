//! Deterministic generator of a large, valid Structured Text project, shaped
//! like real machine code: one module = a type block, a function, a function
//! block with timers/edges/counters/CASE/FOR/arrays/strings, and a program
//! using it; a configuration runs every program in one of a few tasks.
//!
//! Shared by the front-end benchmark and by a test that keeps the generated
//! project free of errors (so the benchmark measures the real path).

/// One file per module plus `config.st`; returns (file name, text) pairs.
pub fn project(modules: usize) -> Vec<(String, String)> {
    let mut files: Vec<(String, String)> = (0..modules)
        .map(|k| (format!("module_{k:04}.st"), module(k)))
        .collect();
    files.push(("config.st".to_string(), config(modules)));
    files
}

pub fn line_count(files: &[(String, String)]) -> usize {
    files.iter().map(|(_, t)| t.lines().count()).sum()
}

fn module(k: usize) -> String {
    let size = 8 + k % 5;
    let gain = 1.0 + (k % 7) as f64 * 0.25;
    format!(
        r#"(* Module {k}: a supervised processing unit, generated for the front-end benchmark. *)
TYPE
    Mode_{k} : (Idle_{k}, Starting_{k}, Running_{k}, Stopping_{k}, Fault_{k}) := Idle_{k};
    Level_{k} : INT (0..1000);
    Sample_{k} : STRUCT
        value : REAL := 0.0;
        valid : BOOL := FALSE;
        stamp : TIME;
    END_STRUCT;
    Buffer_{k} : ARRAY [0..{last}] OF Sample_{k};
END_TYPE

VAR_GLOBAL CONSTANT
    SIZE_{k} : INT := {size};
END_VAR

FUNCTION Scale_{k} : REAL
VAR_INPUT
    raw : INT;      (* 819..4095 for 4..20 mA *)
    lo : REAL;
    hi : REAL;
END_VAR
VAR
    span : REAL;
END_VAR
    span := hi - lo;
    IF raw <= 819 THEN
        Scale_{k} := lo;
    ELSIF raw >= 4095 THEN
        Scale_{k} := hi;
    ELSE
        Scale_{k} := lo + INT_TO_REAL(raw - 819) * span / 3276.0;
    END_IF;
END_FUNCTION

FUNCTION_BLOCK Unit_{k}
VAR_INPUT
    Start : BOOL;
    Stop : BOOL;
    Raw : INT;
    Setpoint : REAL := 50.0;
END_VAR
VAR_OUTPUT
    Running : BOOL;
    Output : REAL;
    Alarm : BOOL;
    Cycles : INT;
    Text : STRING[40];
END_VAR
VAR
    mode : Mode_{k};
    startEdge : R_TRIG;
    stopEdge : F_TRIG;
    rampTimer : TON;
    faultTimer : TON;
    counter : CTU;
    samples : Buffer_{k};
    head : INT;
    i : INT;
    sum : REAL;
    avg : REAL;
    level : Level_{k};
    flags : WORD := 16#0000;
END_VAR
VAR_TEMP
    pv : REAL;
    err : REAL;
END_VAR
    startEdge(CLK := Start);
    stopEdge(CLK := NOT Stop);
    pv := Scale_{k}(raw := Raw, lo := 0.0, hi := 100.0);

    (* keep a ring of the last samples *)
    samples[head].value := pv;
    samples[head].valid := TRUE;
    head := (head + 1) MOD SIZE_{k};
    sum := 0.0;
    FOR i := 0 TO SIZE_{k} - 1 DO
        IF samples[i].valid THEN
            sum := sum + samples[i].value;
        END_IF;
    END_FOR;
    avg := sum / INT_TO_REAL(SIZE_{k});

    CASE mode OF
        Idle_{k}:
            Running := FALSE;
            IF startEdge.Q AND NOT Alarm THEN
                mode := Starting_{k};
            END_IF;
        Starting_{k}:
            rampTimer(IN := TRUE, PT := T#2s500ms);
            Output := Setpoint * DINT_TO_REAL(TIME_TO_DINT(rampTimer.ET)) / 2500.0;
            IF rampTimer.Q THEN
                rampTimer(IN := FALSE);
                mode := Running_{k};
            END_IF;
        Running_{k}:
            Running := TRUE;
            err := Setpoint - avg;
            Output := LIMIT(0.0, Output + {gain:.2} * err * 0.01, 100.0);
            counter(CU := startEdge.Q, R := FALSE, PV := 1000);
            Cycles := counter.CV;
            IF stopEdge.Q THEN
                mode := Stopping_{k};
            END_IF;
        Stopping_{k}:
            Output := MAX(Output - 5.0, 0.0);
            IF Output <= 0.0 THEN
                mode := Idle_{k};
            END_IF;
    ELSE
        Alarm := TRUE;
    END_CASE;

    faultTimer(IN := Running AND ABS(Setpoint - avg) > 25.0, PT := T#10s);
    IF faultTimer.Q THEN
        Alarm := TRUE;
        mode := Fault_{k};
        flags.3 := TRUE;
    END_IF;
    level := REAL_TO_INT(LIMIT(0.0, avg * 10.0, 1000.0));
    IF Alarm THEN
        Text := CONCAT('unit {k}: ', 'fault');
    ELSE
        Text := 'unit {k}: ok';
    END_IF;
END_FUNCTION_BLOCK

PROGRAM Prog_{k}
VAR
    unit : Unit_{k};
    startButton : BOOL;
    stopButton : BOOL := TRUE;
    sensor : INT := 2048;
    out : REAL;
    runs : INT;
END_VAR
    unit(Start := startButton, Stop := stopButton, Raw := sensor, Setpoint := 60.0);
    out := unit.Output;
    runs := unit.Cycles;
    IF unit.Alarm THEN
        startButton := FALSE;
    END_IF;
END_PROGRAM
"#,
        last = size - 1,
    )
}

fn config(modules: usize) -> String {
    let mut s = String::from(
        "CONFIGURATION Plant\n    RESOURCE Cpu ON PLC\n        TASK Fast (INTERVAL := T#5ms, PRIORITY := 1);\n        TASK Slow (INTERVAL := T#50ms, PRIORITY := 5);\n",
    );
    for k in 0..modules {
        let task = if k % 4 == 0 { "Fast" } else { "Slow" };
        s.push_str(&format!(
            "        PROGRAM Inst_{k} WITH {task} : Prog_{k};\n"
        ));
    }
    s.push_str("    END_RESOURCE\nEND_CONFIGURATION\n");
    s
}
