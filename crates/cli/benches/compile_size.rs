//! Compile cost against body size (issue 15 point 3): one PROGRAM whose
//! body is N statements (assignments and IFs alternating), compiled
//! through lower + JIT (Cranelift) and through lower + interpreter, best
//! wall time of `--runs N` (default 3) and the peak heap the compile
//! allocated (a counting allocator), then one scan whose result must agree.
//! Bar: 20,000 statements under 1 s and 300 MB on the JIT; time and memory
//! should grow linearly.
//!
//! `cargo bench -p automat --bench compile_size`. Prints a Markdown table.

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

fn body(n: usize) -> String {
    let mut s = String::from("PROGRAM Main\nVAR a, b, c : DINT; END_VAR\n");
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
    s.push_str("END_PROGRAM\n");
    s
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
    println!("compile cost against body size: lower + backend, best of {runs}, peak heap of one compile\n");
    println!("| statements | JIT time | JIT peak heap | interpreter time | interpreter peak heap | verdict (JIT) |");
    println!("|---|---|---|---|---|---|");
    let mut failed = false;
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
                    "| {n} | {:.1} ms | {:.1} MB | {:.1} ms | {:.1} MB | {verdict} |",
                    jt.as_secs_f64() * 1e3,
                    jm as f64 / 1048576.0,
                    it.as_secs_f64() * 1e3,
                    im as f64 / 1048576.0
                );
            }
            (j, i) => {
                failed = true;
                println!("| {n} | error | {:?} | {:?} | | |", j.err(), i.err());
            }
        }
    }
    if failed {
        std::process::exit(1);
    }
}
