//! Engine speed benchmark (issue 3, point 7): compute-heavy ST programs run
//! through lower + engine against the same algorithms in optimised Rust,
//! measured in the same run; plus compile+load time of a program with 1,000
//! FB instances (in process, and as a whole `automat run` process) and the
//! scan overhead of an empty program.
//!
//! `cargo bench -p automat --bench engine` (add `-- --runs N` to change the
//! number of timed runs; the best is reported). Prints a Markdown table.
//! Bar: ST/native ≤ 10× must, ≤ 5× aim; issue 15 wants the JIT within
//! 1.5× of the same algorithm in C (`cc -O2`, built in the same run, in
//! process and as whole processes).

#[path = "engine/c.rs"]
mod c;
#[path = "engine/cases.rs"]
mod cases;
#[path = "engine/plc.rs"]
mod plc;

use std::hint::black_box;
use std::time::{Duration, Instant};

fn best_of<F: FnMut() -> Result<(), String>>(runs: usize, mut f: F) -> Result<Duration, String> {
    let mut best = Duration::MAX;
    for _ in 0..runs.max(1) {
        let t = Instant::now();
        f()?;
        best = best.min(t.elapsed());
    }
    Ok(best)
}

fn fmt_time(d: Duration) -> String {
    let s = d.as_secs_f64();
    if s >= 1.0 {
        format!("{s:.2} s")
    } else if s >= 1e-3 {
        format!("{:.2} ms", s * 1e3)
    } else if s >= 1e-6 {
        format!("{:.2} µs", s * 1e6)
    } else {
        format!("{:.1} ns", s * 1e9)
    }
}

fn verdict(ratio: f64) -> &'static str {
    if ratio <= 1.5 {
        "meets issue 15 (≤ 1.5× C)"
    } else if ratio <= 5.0 {
        "meets aim (≤ 5×)"
    } else if ratio <= 10.0 {
        "meets bar (≤ 10×)"
    } else {
        "**misses bar (> 10×)**"
    }
}

/// Runs the ST program of a case (cold start, `scans` scans) on `kind`,
/// best of `runs`; returns the time and the result it read back.
fn run_st(case: &cases::Case, runs: usize, kind: plc::Kind) -> Result<(Duration, String), String> {
    let mut plc = plc::build(case.name, &case.src, kind)?;
    let st = best_of(runs, || {
        plc.engine.cold_start();
        for scan in 0..case.scans {
            plc.scan(scan as i64 * 1_000_000)?;
        }
        Ok(())
    })?;
    Ok((st, (case.read)(&plc)?))
}

/// Runs one case on the interpreter, the JIT, natively in Rust and in C,
/// best of `runs` each; checks that all four results agree.
fn run_case(
    case: &cases::Case,
    runs: usize,
    kernels: &c::Kernels,
) -> Result<[Duration; 4], String> {
    let (interp, got_i) = run_st(case, runs, plc::Kind::Interp)?;
    let (jit, got_j) = run_st(case, runs, plc::Kind::Jit)?;
    let mut want = String::new();
    let native = best_of(runs, || {
        want = black_box((case.native)());
        Ok(())
    })?;
    // The ST cases run their scans 1 ms of PLC time apart.
    let c = kernels.run(case.c_name, runs, 1_000_000)?;
    for (engine, got) in [("interpreter", &got_i), ("JIT", &got_j), ("C", &c.native)] {
        if *got != want {
            return Err(format!(
                "{}: result on the {engine} {got:?} differs from native {want:?}",
                case.name
            ));
        }
    }
    Ok([interp, jit, native, c.best])
}

/// How many times the whole-process comparison runs a one-scan kernel in
/// each process (`--cycles` for `automat run`, the run count for C): one
/// run of 1-2 ms would compare process start and compile (about 8 ms for
/// `automat run`, 1 ms for C), not the kernel. Every scan of those
/// programs starts the kernel from its own initial values, so the printed
/// result is the same as after one.
const WHOLE_REPEAT: u32 = 50;

/// The whole `automat run FILE --cycles N --print ...` process on the JIT
/// against the whole C process running the same case, best of `runs`
/// each, the printed values compared exactly; `automat run` scans every
/// 10 ms of PLC time, so the C process does too.
fn whole_case(
    case: &cases::Case,
    runs: usize,
    kernels: &c::Kernels,
) -> Result<[Duration; 2], String> {
    let path = std::env::temp_dir().join(format!(
        "automat-bench-{}-{}.st",
        case.c_name,
        std::process::id()
    ));
    std::fs::write(&path, &case.src).map_err(|e| e.to_string())?;
    let repeat = if case.scans == 1 { WHOLE_REPEAT } else { 1 };
    let mut printed = Vec::new();
    let automat = best_of(runs, || {
        let mut cmd = std::process::Command::new(env!("CARGO_BIN_EXE_automat"));
        cmd.arg("run")
            .arg(&path)
            .args(["--cycles", &(case.scans * repeat).to_string()]);
        for p in case.print {
            cmd.args(["--print", p]);
        }
        let out = cmd.output().map_err(|e| e.to_string())?;
        if !out.status.success() {
            return Err(String::from_utf8_lossy(&out.stderr).into_owned());
        }
        printed = String::from_utf8_lossy(&out.stdout)
            .lines()
            .map(str::to_string)
            .collect();
        Ok(())
    });
    let _ = std::fs::remove_file(&path);
    let automat = automat?;
    let (c, by_c) = kernels.whole(case.c_name, runs, repeat, 10_000_000)?;
    if !c::same_values(&printed, &by_c.values) {
        return Err(format!(
            "{}: `automat run` printed {printed:?}, C {:?}",
            case.name, by_c.values
        ));
    }
    Ok([automat, c])
}

/// A project with one FB type and a program holding `n` instances, each
/// called once per scan.
fn many_instances(n: usize) -> String {
    let mut s = String::from(
        "FUNCTION_BLOCK Stage
VAR_INPUT enable : BOOL; step : DINT; END_VAR
VAR_OUTPUT busy : BOOL; count : DINT; END_VAR
VAR edge : R_TRIG; delay : TON; END_VAR
edge(CLK := enable);
delay(IN := enable, PT := T#10MS);
IF edge.Q OR delay.Q THEN count := count + step; END_IF;
busy := enable AND NOT delay.Q;
END_FUNCTION_BLOCK

PROGRAM Plant
VAR
",
    );
    for i in 0..n {
        s.push_str(&format!("    st{i} : Stage;\n"));
    }
    s.push_str("    run : BOOL;\nEND_VAR\nrun := NOT run;\n");
    for i in 0..n {
        s.push_str(&format!("st{i}(enable := run, step := {});\n", i % 7 + 1));
    }
    s.push_str("END_PROGRAM\n");
    s
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let runs = args
        .iter()
        .position(|a| a == "--runs")
        .and_then(|i| args.get(i + 1))
        .and_then(|v| v.parse().ok())
        .unwrap_or(5usize);
    let mut failed = false;
    // `--dump NAME`: print the lowered code of the case whose name starts
    // with NAME instead of measuring (for profiling the interpreter).
    if let Some(name) = args
        .iter()
        .position(|a| a == "--dump")
        .and_then(|i| args.get(i + 1))
    {
        for case in cases::all()
            .iter()
            .filter(|c| c.name.starts_with(name.as_str()))
        {
            match plc::build(case.name, &case.src, plc::Kind::Interp) {
                Ok(p) => {
                    for f in &p.engine.program().funcs {
                        println!("{}:", f.name);
                        for (pc, inst) in f.code.iter().enumerate() {
                            println!("  {pc:4} {inst:?}");
                        }
                    }
                }
                Err(e) => println!("{e}"),
            }
        }
        return;
    }

    let kernels = match c::Kernels::build(&std::env::temp_dir()) {
        Ok(k) => k,
        Err(e) => {
            println!("the C side cannot be built: {e}");
            std::process::exit(1);
        }
    };
    println!("engine: ST through lower + interpreter and lower + JIT (Cranelift) vs the same algorithm in optimised Rust and in C (`cc -O2`), in process (best of {runs} runs, one core)\n");
    println!(
        "| case | Rust | C | interpreter | interp / C | JIT | JIT / Rust | JIT / C | verdict (JIT / C) |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    // `--only NAME`: measure just the cases whose name starts with NAME.
    let only = args
        .iter()
        .position(|a| a == "--only")
        .and_then(|i| args.get(i + 1));
    for case in cases::all() {
        if only.is_some_and(|o| !case.name.starts_with(o.as_str())) {
            continue;
        }
        match run_case(&case, runs, &kernels) {
            Ok([interp, jit, native, c]) => {
                let n = native.as_secs_f64().max(1e-9);
                let cn = c.as_secs_f64().max(1e-9);
                let rj = jit.as_secs_f64() / cn;
                println!(
                    "| {} | {} | {} | {} | {:.1}× | {} | {:.1}× | {:.1}× | {} |",
                    case.name,
                    fmt_time(native),
                    fmt_time(c),
                    fmt_time(interp),
                    interp.as_secs_f64() / cn,
                    fmt_time(jit),
                    jit.as_secs_f64() / n,
                    rj,
                    verdict(rj)
                );
            }
            Err(e) => {
                failed = true;
                println!("| {} | error | | | | | | | {e} |", case.name);
            }
        }
    }
    println!("\nwhole process: `automat run FILE --cycles N` (JIT, 10 ms scans) vs the C executable, printed values compared (best of {runs}; the one-scan kernels run {WHOLE_REPEAT} times in each process)\n");
    println!("| case | `automat run` | C process | automat / C | verdict |");
    println!("|---|---|---|---|---|");
    for case in cases::all() {
        if only.is_some_and(|o| !case.name.starts_with(o.as_str())) {
            continue;
        }
        match whole_case(&case, runs, &kernels) {
            Ok([automat, c]) => {
                let r = automat.as_secs_f64() / c.as_secs_f64().max(1e-9);
                println!(
                    "| {} | {} | {} | {r:.1}× | {} |",
                    case.name,
                    fmt_time(automat),
                    fmt_time(c),
                    verdict(r)
                );
            }
            Err(e) => {
                failed = true;
                println!("| {} | error | | | {e} |", case.name);
            }
        }
    }
    if only.is_some() {
        return;
    }

    println!("\n| measure | time | bar | verdict |");
    println!("|---|---|---|---|");
    let src = many_instances(1000);
    for (kind, label) in [(plc::Kind::Interp, "interpreter"), (plc::Kind::Jit, "JIT")] {
        let mut load = || -> Result<(), String> {
            black_box(plc::build("plant", &src, kind)?);
            Ok(())
        };
        match best_of(runs, &mut load) {
            Ok(d) => println!(
                "| compile + load, 1,000 FB instances ({} lines), {label} | {} | well under 1 s | {} |",
                src.lines().count(),
                fmt_time(d),
                if d.as_secs_f64() < 0.5 {
                    "meets bar"
                } else {
                    "**misses bar**"
                }
            ),
            Err(e) => {
                failed = true;
                println!("| compile + load, 1,000 FB instances, {label} | error | | {e} |");
            }
        }
        let scans = 1_000_000u32;
        let empty = plc::build(
            "empty",
            "PROGRAM Empty\nVAR x : INT; END_VAR\nEND_PROGRAM\n",
            kind,
        )
        .and_then(|mut p| {
            best_of(runs, || {
                for scan in 0..scans {
                    p.scan(black_box(scan as i64))?;
                }
                Ok(())
            })
        });
        match empty {
            Ok(d) => {
                let per = d / scans;
                println!(
                    "| empty-program scan overhead, {label} | {} per scan | < 1 µs | {} |",
                    fmt_time(per),
                    if per < Duration::from_micros(1) {
                        "meets bar"
                    } else {
                        "**misses bar**"
                    }
                );
            }
            Err(e) => {
                failed = true;
                println!("| empty-program scan overhead, {label} | error | | {e} |");
            }
        }
    }
    if let Err(e) = whole_process(runs, &src) {
        failed = true;
        println!("| `automat run` process, 1,000 FB instances | error | | {e} |");
    }
    if failed {
        std::process::exit(1);
    }
}

/// Issue 15 point 4: the whole `automat run FILE --cycles 1` process on
/// the 1,000-instance program (start, read, compile, load, one scan,
/// print), best of `runs`, on each engine.
fn whole_process(runs: usize, src: &str) -> Result<(), String> {
    let path = std::env::temp_dir().join(format!("automat-bench-{}.st", std::process::id()));
    std::fs::write(&path, src).map_err(|e| e.to_string())?;
    for (engine, bar) in [("jit", 0.1), ("interp", 0.01)] {
        let d = best_of(runs, || {
            let out = std::process::Command::new(env!("CARGO_BIN_EXE_automat"))
                .arg("run")
                .arg(&path)
                .args([
                    "--cycles",
                    "1",
                    "--engine",
                    engine,
                    "--print",
                    "st999.count",
                ])
                .output()
                .map_err(|e| e.to_string())?;
            if out.stdout != b"st999.count = 6\n" {
                return Err(String::from_utf8_lossy(&out.stderr).into_owned());
            }
            Ok(())
        })?;
        println!(
            "| `automat run` process, 1,000 FB instances, one cycle, {engine} | {} | < {} ms | {} |",
            fmt_time(d),
            bar * 1e3,
            if d.as_secs_f64() < bar {
                "meets bar"
            } else {
                "**misses bar**"
            }
        );
    }
    let _ = std::fs::remove_file(&path);
    Ok(())
}
