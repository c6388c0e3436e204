//! Compile cost against body size (issue 15 point 3): one PROGRAM whose
//! body is N statements of one shape (`SHAPES`: assignments and IFs
//! alternating, FB calls, loops over an array, a CASE, an ELSIF chain), compiled
//! through lower + JIT (Cranelift) and through lower + interpreter, best
//! wall time of `--runs N` (default 3) and the peak heap the compile
//! allocated (a counting allocator), then one scan whose result must agree.
//! Bar: 20,000 statements under 1 s and 300 MB on the JIT; time and memory
//! should grow linearly.
//!
//! `cargo bench -p automat --bench compile_size [-- --shape NAME]`. Prints a
//! Markdown table.

// Shared with the engine bench, which uses all of it.
#[allow(dead_code)]
#[path = "engine/plc.rs"]
mod plc;

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

/// The system allocator, counting the bytes live and their peak.
struct Counting;

static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

// SAFETY: every call is forwarded unchanged to the system allocator; the
// counters are only statistics.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            let now = LIVE.fetch_add(layout.size(), Ordering::Relaxed) + layout.size();
            PEAK.fetch_max(now, Ordering::Relaxed);
        }
        p
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) };
        LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
    }
}

#[global_allocator]
static ALLOC: Counting = Counting;

/// The shapes of body measured: each a PROGRAM `Main` of `n` statements
/// that leaves a DINT `c` to compare between the engines. `mixed` is the
/// original shape; the others stress what a long body can hold besides
/// straight-line code (issue 15 pt 3 asks for any body).
type Shape = (&'static str, fn(usize) -> String);

const SHAPES: [Shape; 5] = [
    ("mixed", mixed),
    ("fb-calls", fb_calls),
    ("loops", loops),
    ("case", case),
    ("elsif", elsif),
];

fn program(vars: &str, body: &str) -> String {
    format!("PROGRAM Main\nVAR\n{vars}END_VAR\n{body}END_PROGRAM\n")
}

/// Assignments and IFs alternating.
fn mixed(n: usize) -> String {
    let mut s = String::new();
    for i in 0..n {
        if i % 2 == 1 {
            s.push_str(&format!(
                "a := a + {}; IF a > 1000 THEN b := b + 1; a := 0; END_IF;\n",
                i % 13
            ));
        } else {
            s.push_str(&format!("c := c + a * {};\n", i % 7));
        }
    }
    program("a, b, c : DINT;\n", &s)
}

/// A TON call and a test of its output per statement, over n/4
/// instances (the standard FB the JIT inlines).
fn fb_calls(n: usize) -> String {
    let k = (n / 4).max(1);
    let vars: String = (0..k).map(|i| format!("t{i} : TON;\n")).collect();
    let body: String = (0..n)
        .map(|i| {
            let t = i % k;
            format!(
                "t{t}(IN := TRUE, PT := T#0s); IF t{t}.Q THEN c := c + {}; END_IF;\n",
                i % 5
            )
        })
        .collect();
    program(&format!("{vars}c : DINT;\n"), &body)
}

/// One FOR loop over an array in every ten statements, array reads
/// between them (loop analysis and range checks).
fn loops(n: usize) -> String {
    let body: String = (0..n)
        .map(|k| {
            if k % 10 == 0 {
                format!(
                    "FOR i := 0 TO 99 DO arr[i] := arr[i] + {}; END_FOR;\n",
                    k % 9
                )
            } else {
                format!("c := c + arr[{}];\n", k % 100)
            }
        })
        .collect();
    program("arr : ARRAY[0..99] OF DINT; i, c : DINT;\n", &body)
}

/// One CASE of n arms.
fn case(n: usize) -> String {
    let arms: String = (0..n)
        .map(|i| format!("{i}: c := c + {};\n", i % 11))
        .collect();
    program(
        "a, c : DINT;\n",
        &format!("a := {};\nCASE a OF\n{arms}END_CASE;\n", n / 2),
    )
}

/// One IF with n - 1 ELSIF branches.
fn elsif(n: usize) -> String {
    let arms: String = (1..n)
        .map(|i| format!("ELSIF a = {i} THEN c := {i};\n"))
        .collect();
    program(
        "a, c : DINT;\n",
        &format!(
            "a := a + {};\nIF a = 0 THEN c := 0;\n{arms}END_IF;\n",
            n / 3
        ),
    )
}

/// Best compile time over `runs`, the peak heap of one compile, and the
/// value of `c` after one scan.
fn measure(src: &str, kind: plc::Kind, runs: usize) -> Result<(Duration, usize, String), String> {
    let mut best = Duration::MAX;
    let mut peak = 0;
    let mut c = String::new();
    for _ in 0..runs.max(1) {
        let base = LIVE.load(Ordering::Relaxed);
        PEAK.store(base, Ordering::Relaxed);
        let t = Instant::now();
        let mut p = plc::build("body", src, kind)?;
        best = best.min(t.elapsed());
        peak = peak.max(PEAK.load(Ordering::Relaxed).saturating_sub(base));
        p.scan(0)?;
        let at = p.offset("Main.c")?;
        c = i32::from_le_bytes(
            p.engine
                .image()
                .get(at as usize..at as usize + 4)
                .and_then(|b| b.try_into().ok())
                .ok_or("c outside the image")?,
        )
        .to_string();
    }
    Ok((best, peak, c))
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let runs = args
        .iter()
        .position(|a| a == "--runs")
        .and_then(|i| args.get(i + 1))
        .and_then(|v| v.parse().ok())
        .unwrap_or(3);
    // `--shape NAME` (repeatable) measures only those shapes.
    let only: Vec<&str> = args
        .iter()
        .enumerate()
        .filter(|(i, _)| *i > 0 && args[i - 1] == "--shape")
        .map(|(_, a)| a.as_str())
        .collect();
    println!("compile cost against body size: lower + backend, best of {runs}, peak heap of one compile\n");
    println!("| shape | statements | JIT time | JIT peak heap | interpreter time | interpreter peak heap | verdict (JIT) |");
    println!("|---|---|---|---|---|---|---|");
    let mut failed = false;
    for (shape, body) in SHAPES {
        if !only.is_empty() && !only.contains(&shape) {
            continue;
        }
        for n in [1_000, 2_000, 5_000, 10_000, 20_000] {
            let src = body(n);
            let jit = measure(&src, plc::Kind::Jit, runs);
            let interp = measure(&src, plc::Kind::Interp, runs);
            match (jit, interp) {
                (Ok((jt, jm, jc)), Ok((it, im, ic))) => {
                    let verdict = if jc != ic {
                        failed = true;
                        format!("**results differ: {jc} vs {ic}**")
                    } else if n < 20_000 {
                        String::new()
                    } else if jt < Duration::from_secs(1) && jm < 300 << 20 {
                        "meets bar (< 1 s, < 300 MB)".into()
                    } else {
                        "**misses bar (< 1 s, < 300 MB)**".into()
                    };
                    println!(
                        "| {shape} | {n} | {:.1} ms | {:.1} MB | {:.1} ms | {:.1} MB | {verdict} |",
                        jt.as_secs_f64() * 1e3,
                        jm as f64 / 1048576.0,
                        it.as_secs_f64() * 1e3,
                        im as f64 / 1048576.0
                    );
                }
                (j, i) => {
                    failed = true;
                    println!(
                        "| {shape} | {n} | error | {:?} | {:?} | | |",
                        j.err(),
                        i.err()
                    );
                }
            }
        }
    }
    if failed {
        std::process::exit(1);
    }
}
