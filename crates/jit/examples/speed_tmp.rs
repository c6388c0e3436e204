#[path = "../../cli/benches/engine/cases.rs"]
mod cases;
#[path = "../../cli/benches/engine/plc.rs"]
#[allow(dead_code)]
mod plc;
use std::time::Instant;
fn main() {
    let only: Option<String> = std::env::args().nth(1);
    let dump = std::env::args().nth(2).is_some();
    for case in cases::all() {
        if only.as_ref().is_some_and(|o| !case.name.starts_with(o.as_str())) { continue; }
        if dump {
            let p = plc::build(case.name, &case.src, plc::Kind::Interp).unwrap();
            for f in &p.engine.program().funcs { println!("{}:", f.name); for (pc, i) in f.code.iter().enumerate() { println!("  {pc:4} {i:?}"); } }
        }
        let t = Instant::now();
        let n0 = Instant::now();
        let nat = (case.native)();
        let nt = n0.elapsed();
        let mut line = format!("{}: native {:?}", case.name, nt);
        for k in [plc::Kind::Interp, plc::Kind::Jit] { if std::env::var("JITONLY").is_ok() && k == plc::Kind::Interp { continue; }
            let c0 = Instant::now();
            let mut p = plc::build(case.name, &case.src, k).unwrap();
            let ct = c0.elapsed();
            let mut best = std::time::Duration::MAX;
            for _ in 0..3 {
                p.engine.cold_start();
                let s = Instant::now();
                for scan in 0..case.scans { p.scan(scan as i64 * 1_000_000).unwrap(); }
                best = best.min(s.elapsed());
            }
            let got = (case.read)(&p).unwrap();
            line += &format!(" | {k:?} {:?} ({:.1}x, compile {:?}) {}", best, best.as_secs_f64()/nt.as_secs_f64(), ct, if got == nat {"ok"} else {"MISMATCH"});
        }
        let _ = t;
        println!("{line}");
    }
}
