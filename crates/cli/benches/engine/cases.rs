//! The compute cases: each is an ST program and the same algorithm in Rust.
//! Results are rendered to text so that the ST result (read through the
//! symbol table) and the native one compare exactly; floats compare by bits
//! because both sides do the same IEEE operations in the same order.

use crate::plc::Plc;
use std::hint::black_box;

pub struct Case {
    pub name: &'static str,
    pub src: String,
    /// Scans per run; each scan is 1 ms of PLC time after the previous.
    pub scans: u32,
    /// The ST result, read after a run.
    pub read: fn(&Plc) -> Result<String, String>,
    /// The same algorithm in Rust; returns the same text.
    pub native: fn() -> String,
    /// The same algorithm in C: its name in `kernels.c`.
    pub c_name: &'static str,
    /// The variables `automat run --print` shows for the whole-process
    /// comparison with the C executable.
    pub print: &'static [&'static str],
}

pub const SIEVE_N: i64 = 200_000;
pub const FILTER_N: i64 = 1_000_000;
pub const PRNG_N: i64 = 1_000_000;
pub const CRC_N: i64 = 100_000;
pub const FB_COUNT: usize = 1_000;
pub const FB_SCANS: u32 = 10_000;
pub const STR_N: i64 = 20_000;

pub fn all() -> Vec<Case> {
    vec![
        Case {
            name: "sieve of Eratosthenes, ARRAY OF BOOL, n = 200,000",
            src: format!(
                "PROGRAM Sieve
VAR flags : ARRAY[0..{n}] OF BOOL; i, j, count : DINT; END_VAR
FOR i := 0 TO {n} DO flags[i] := TRUE; END_FOR;
flags[0] := FALSE; flags[1] := FALSE;
i := 2;
WHILE i * i <= {n} DO
    IF flags[i] THEN
        j := i * i;
        WHILE j <= {n} DO flags[j] := FALSE; j := j + i; END_WHILE;
    END_IF;
    i := i + 1;
END_WHILE;
count := 0;
FOR i := 0 TO {n} DO IF flags[i] THEN count := count + 1; END_IF; END_FOR;
END_PROGRAM
",
                n = SIEVE_N
            ),
            scans: 1,
            read: |p| Ok(p.i32("SIEVE.COUNT")?.to_string()),
            native: || sieve(black_box(SIEVE_N)).to_string(),
            c_name: "sieve",
            print: &["SIEVE.COUNT"],
        },
        Case {
            name: "LREAL low-pass filter loop, 1,000,000 steps",
            src: format!(
                "PROGRAM Filter
VAR i : DINT; x, y, sum : LREAL; END_VAR
x := 0.0; y := 0.0; sum := 0.0;
FOR i := 1 TO {n} DO
    x := x + 0.5;
    IF x > 100.0 THEN x := x - 200.0; END_IF;
    y := y + 0.01 * (x - y);
    sum := sum + y * y;
END_FOR;
END_PROGRAM
",
                n = FILTER_N
            ),
            scans: 1,
            read: |p| Ok(format!("{:016x}", p.f64("FILTER.SUM")?.to_bits())),
            native: || format!("{:016x}", filter(black_box(FILTER_N)).to_bits()),
            c_name: "filter",
            print: &["FILTER.SUM"],
        },
        Case {
            name: "DWORD xorshift PRNG, 1,000,000 steps",
            src: format!(
                "PROGRAM Prng
VAR i : DINT; x, acc : DWORD; END_VAR
x := 16#2545F491; acc := 0;
FOR i := 1 TO {n} DO
    x := x XOR SHL(x, 13);
    x := x XOR SHR(x, 17);
    x := x XOR SHL(x, 5);
    acc := ROL(acc, 1) XOR x;
END_FOR;
END_PROGRAM
",
                n = PRNG_N
            ),
            scans: 1,
            read: |p| Ok(format!("{:08x}", p.u32("PRNG.ACC")?)),
            native: || format!("{:08x}", xorshift(black_box(PRNG_N))),
            c_name: "xorshift",
            print: &["PRNG.ACC"],
        },
        Case {
            name: "DWORD bitwise CRC-32, 100,000 bytes",
            src: format!(
                "PROGRAM Crc
VAR i, k : DINT; b, crc : DWORD; END_VAR
crc := 16#FFFFFFFF; b := 0;
FOR i := 1 TO {n} DO
    b := ROL(b XOR 16#3B, 1) AND 16#FF;
    crc := crc XOR b;
    FOR k := 1 TO 8 DO
        IF (crc AND 16#1) = 16#1 THEN
            crc := SHR(crc, 1) XOR 16#EDB88320;
        ELSE
            crc := SHR(crc, 1);
        END_IF;
    END_FOR;
END_FOR;
crc := crc XOR 16#FFFFFFFF;
END_PROGRAM
",
                n = CRC_N
            ),
            scans: 1,
            read: |p| Ok(format!("{:08x}", p.u32("CRC.CRC")?)),
            native: || format!("{:08x}", crc32(black_box(CRC_N))),
            c_name: "crc32",
            // `CRC.CRC` would name the variable crc first, then its member CRC.
            print: &["CRC"],
        },
        Case {
            name: "1,000 TON + R_TRIG + CTU per scan, 10,000 scans",
            src: format!(
                "PROGRAM Fbs
VAR
    t : ARRAY[1..{n}] OF TON;
    e : ARRAY[1..{n}] OF R_TRIG;
    c : ARRAY[1..{n}] OF CTU;
    i : INT;
END_VAR
FOR i := 1 TO {n} DO
    t[i](IN := NOT t[i].Q, PT := T#5MS);
    e[i](CLK := t[i].Q);
    c[i](CU := e[i].Q, R := FALSE, PV := 30000);
END_FOR;
END_PROGRAM
",
                n = FB_COUNT
            ),
            scans: FB_SCANS,
            read: |p| {
                Ok(format!(
                    "{} {} {}",
                    p.i16("FBS.C[1].CV")?,
                    p.i16(&format!("FBS.C[{FB_COUNT}].CV"))?,
                    p.i64("FBS.T[500].ET")?
                ))
            },
            native: || fbs(black_box(FB_COUNT), black_box(FB_SCANS)),
            c_name: "fbs",
            print: &["FBS.C[1].CV", "FBS.C[1000].CV", "FBS.T[500].ET"],
        },
        Case {
            name: "string building: CONCAT/LEFT/INT_TO_STRING, 20,000 steps",
            src: format!(
                "PROGRAM Strs
VAR i : INT; s : STRING; total : DINT; END_VAR
s := ''; total := 0;
FOR i := 1 TO {n} DO
    s := CONCAT(LEFT(s, 20), INT_TO_STRING(i));
    total := total + INT_TO_DINT(LEN(s));
END_FOR;
END_PROGRAM
",
                n = STR_N
            ),
            scans: 1,
            read: |p| Ok(format!("{} {}", p.i32("STRS.TOTAL")?, p.string("STRS.S")?)),
            native: || strings(black_box(STR_N)),
            c_name: "strings",
            print: &["STRS.TOTAL", "STRS.S"],
        },
    ]
}

fn sieve(n: i64) -> i64 {
    let n = n as usize;
    let mut flags = vec![true; n + 1];
    flags[0] = false;
    flags[1] = false;
    let mut i = 2;
    while i * i <= n {
        if flags[i] {
            let mut j = i * i;
            while j <= n {
                flags[j] = false;
                j += i;
            }
        }
        i += 1;
    }
    black_box(&flags);
    flags.iter().filter(|&&f| f).count() as i64
}

fn filter(n: i64) -> f64 {
    let (mut x, mut y, mut sum) = (0.0f64, 0.0f64, 0.0f64);
    for _ in 1..=n {
        x += 0.5;
        if x > 100.0 {
            x -= 200.0;
        }
        y += 0.01 * (x - y);
        sum += y * y;
    }
    sum
}

fn xorshift(n: i64) -> u32 {
    let (mut x, mut acc) = (0x2545_F491u32, 0u32);
    for _ in 1..=n {
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        acc = acc.rotate_left(1) ^ x;
    }
    acc
}

fn crc32(n: i64) -> u32 {
    let (mut crc, mut b) = (0xFFFF_FFFFu32, 0u32);
    for _ in 1..=n {
        b = (b ^ 0x3B).rotate_left(1) & 0xFF;
        crc ^= b;
        for _ in 1..=8 {
            crc = if crc & 1 == 1 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    crc ^ 0xFFFF_FFFF
}

/// The standard bodies of TON, R_TRIG and CTU (`sema/src/stdlib/fbs.st`).
#[derive(Clone, Copy, Default)]
struct Ton {
    q: bool,
    et: i64,
    m: bool,
    start: i64,
}

impl Ton {
    fn call(&mut self, inp: bool, pt: i64, now: i64) {
        if inp {
            if !self.m {
                self.start = now;
            }
            if !self.q {
                self.et = now - self.start;
                if self.et >= pt {
                    self.et = pt;
                    self.q = true;
                }
            }
        } else {
            self.q = false;
            self.et = 0;
        }
        self.m = inp;
    }
}

#[derive(Clone, Copy, Default)]
struct RTrig {
    q: bool,
    m: bool,
}

impl RTrig {
    fn call(&mut self, clk: bool) {
        self.q = clk && !self.m;
        self.m = clk;
    }
}

#[derive(Clone, Copy, Default)]
struct Ctu {
    cu_m: bool,
    q: bool,
    cv: i16,
}

impl Ctu {
    fn call(&mut self, cu: bool, r: bool, pv: i16) {
        let edge = cu && !self.cu_m;
        self.cu_m = cu;
        if r {
            self.cv = 0;
        } else if edge && self.cv < 32767 {
            self.cv += 1;
        }
        self.q = self.cv >= pv;
    }
}

fn fbs(count: usize, scans: u32) -> String {
    let mut t = vec![Ton::default(); count];
    let mut e = vec![RTrig::default(); count];
    let mut c = vec![Ctu::default(); count];
    for scan in 0..scans {
        let now = scan as i64 * 1_000_000;
        for ((t, e), c) in t.iter_mut().zip(&mut e).zip(&mut c) {
            let inp = !t.q;
            t.call(inp, 5_000_000, now);
            e.call(t.q);
            c.call(e.q, false, 30000);
        }
        black_box((&t, &e, &c));
    }
    let cv = |i: usize| c.get(i).map(|c| c.cv).unwrap_or(-1);
    let et = t.get(499).map(|t| t.et).unwrap_or(-1);
    format!("{} {} {}", cv(0), cv(count - 1), et)
}

fn strings(n: i64) -> String {
    let mut s = String::new();
    let mut total = 0i64;
    for i in 1..=n {
        let left: String = s.chars().take(20).collect();
        s = left + &(i as i16).to_string();
        total += s.len() as i64;
    }
    format!("{total} {s}")
}
