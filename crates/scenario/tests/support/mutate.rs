//! Deterministic input mutations for the robustness tests of the
//! user-facing readers (scenarios, `automat.toml`, conformance headers,
//! trace CSVs). Shared by file inclusion (`#[path]`), so it needs nothing
//! but std: a seeded xorshift PRNG and byte/line/token mutations.
//!
//! Every mutant is a pure function of (seed, input), so a failure names
//! the seed that reproduces it.

#![allow(dead_code)]

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::time::{Duration, Instant};

/// xorshift64*: small, seeded, good enough to pick positions.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        // Never 0 (a fixed point of xorshift); mix the seed so neighbouring
        // seeds do not start alike.
        Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }

    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    /// 0..n (0 when n is 0).
    pub fn below(&mut self, n: usize) -> usize {
        if n == 0 {
            0
        } else {
            (self.next() % n as u64) as usize
        }
    }

    pub fn pick<'a, T>(&mut self, xs: &'a [T]) -> Option<&'a T> {
        let i = self.below(xs.len());
        xs.get(i)
    }
}

/// Tokens that break parsers: huge and odd numbers, odd times, quoting,
/// separators, control characters and multi-byte text.
pub const SPECIAL: &[&str] = &[
    "99999999999999999999999999999999",
    "9223372036854775807",
    "9223372036854775808",
    "-9223372036854775808",
    "18446744073709551615",
    "18446744073709551616",
    "1e308",
    "1e309",
    "-1e309",
    "NaN",
    "inf",
    "-inf",
    "-0",
    "0",
    "-1",
    "0.000000000000000000000000001",
    "T#106751d23h47m16s854ms775us807ns",
    "T#106751d23h47m16s854ms775us808ns",
    "T#9999999999999d",
    "T#-1s",
    "T#0s",
    "1000000000000000000",
    "1.5s",
    "0s",
    "1e18ns",
    "TRUE",
    "FALSE",
    "#",
    "\"",
    "'",
    "\\",
    "[",
    "]",
    "{",
    "}",
    "(",
    ")",
    "(*",
    "*)",
    "=",
    " = ",
    "<>",
    "<=",
    "..",
    ",",
    ":",
    ".",
    "\n",
    "\r\n",
    "\r",
    "\t",
    "\0",
    "\u{feff}",
    "\u{7f}",
    "é",
    "日本",
    "\u{1F600}",
    "",
];

/// Applies one to four random mutations to `src`. `words` are tokens of
/// the format (keywords) to insert or substitute; `nests` are (open,
/// close) pairs repeated to nest deeply.
pub fn mutate(rng: &mut Rng, src: &[u8], words: &[&str], nests: &[(&str, &str)]) -> Vec<u8> {
    let mut v = src.to_vec();
    let n = 1 + rng.below(4);
    for _ in 0..n {
        v = mutate_once(rng, &v, words, nests);
    }
    v
}

fn line_starts(v: &[u8]) -> Vec<usize> {
    let mut s = vec![0];
    s.extend(
        v.iter()
            .enumerate()
            .filter(|(_, &b)| b == b'\n')
            .map(|(i, _)| i + 1),
    );
    s
}

/// The byte range of line `k` (with its `\n`).
fn line_range(v: &[u8], starts: &[usize], k: usize) -> (usize, usize) {
    let a = starts.get(k).copied().unwrap_or(v.len()).min(v.len());
    let b = starts.get(k + 1).copied().unwrap_or(v.len()).min(v.len());
    (a, b)
}

/// Byte ranges of the white-space separated words.
fn word_ranges(v: &[u8]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut start = None;
    for (i, &b) in v.iter().enumerate() {
        let ws = b.is_ascii_whitespace();
        match (start, ws) {
            (None, false) => start = Some(i),
            (Some(s), true) => {
                out.push((s, i));
                start = None;
            }
            _ => {}
        }
    }
    if let Some(s) = start {
        out.push((s, v.len()));
    }
    out
}

fn splice(v: &[u8], a: usize, b: usize, with: &[u8]) -> Vec<u8> {
    let (a, b) = (a.min(v.len()), b.min(v.len()));
    let (a, b) = (a.min(b), b.max(a));
    let mut out = Vec::with_capacity(v.len() + with.len());
    out.extend_from_slice(&v[..a]);
    out.extend_from_slice(with);
    out.extend_from_slice(&v[b..]);
    out
}

fn token<'a>(rng: &mut Rng, words: &[&'a str]) -> &'a str {
    if rng.below(2) == 0 {
        rng.pick(words).copied().unwrap_or("x")
    } else {
        rng.pick(SPECIAL).copied().unwrap_or("x")
    }
}

fn mutate_once(rng: &mut Rng, v: &[u8], words: &[&str], nests: &[(&str, &str)]) -> Vec<u8> {
    let len = v.len();
    let at = rng.below(len + 1);
    let span = 1 + rng.below(16);
    match rng.below(16) {
        // Delete a byte range.
        0 => splice(v, at, at + span, b""),
        // Duplicate a byte range in place.
        1 => {
            let end = (at + span).min(len);
            let piece = v[at.min(end)..end].to_vec();
            splice(v, at, at, &piece)
        }
        // Truncate.
        2 => v[..at].to_vec(),
        // Random bytes (often not UTF-8).
        3 => {
            let bytes: Vec<u8> = (0..span).map(|_| rng.next() as u8).collect();
            splice(v, at, at, &bytes)
        }
        // Overwrite one byte.
        4 => {
            let b = [rng.next() as u8];
            splice(v, at, at + 1, &b)
        }
        // Insert a token (at a word boundary half of the time).
        5 => {
            let t = token(rng, words);
            let spaced = rng.below(2) == 0;
            let text = if spaced {
                format!(" {t} ")
            } else {
                t.to_string()
            };
            splice(v, at, at, text.as_bytes())
        }
        // Delete a line.
        6 => {
            let s = line_starts(v);
            let (a, b) = line_range(v, &s, rng.below(s.len()));
            splice(v, a, b, b"")
        }
        // Duplicate a line.
        7 => {
            let s = line_starts(v);
            let (a, b) = line_range(v, &s, rng.below(s.len()));
            let mut piece = v[a..b].to_vec();
            if !piece.ends_with(b"\n") {
                piece.push(b'\n');
            }
            splice(v, a, a, &piece)
        }
        // Swap two lines.
        8 => {
            let s = line_starts(v);
            let (i, j) = (rng.below(s.len()), rng.below(s.len()));
            let (i, j) = (i.min(j), i.max(j));
            let (a0, a1) = line_range(v, &s, i);
            let (b0, b1) = line_range(v, &s, j);
            if i == j || a1 > b0 {
                return v.to_vec();
            }
            let mut out = v[..a0].to_vec();
            out.extend_from_slice(&v[b0..b1]);
            if !out.ends_with(b"\n") {
                out.push(b'\n');
            }
            out.extend_from_slice(&v[a1..b0]);
            out.extend_from_slice(&v[a0..a1]);
            out.extend_from_slice(&v[b1..]);
            out
        }
        // Swap two words.
        9 => {
            let w = word_ranges(v);
            let (i, j) = (rng.below(w.len()), rng.below(w.len()));
            let (i, j) = (i.min(j), i.max(j));
            let (Some(&(a0, a1)), Some(&(b0, b1))) = (w.get(i), w.get(j)) else {
                return v.to_vec();
            };
            if i == j {
                return v.to_vec();
            }
            let mut out = v[..a0].to_vec();
            out.extend_from_slice(&v[b0..b1]);
            out.extend_from_slice(&v[a1..b0]);
            out.extend_from_slice(&v[a0..a1]);
            out.extend_from_slice(&v[b1..]);
            out
        }
        // Replace a word by a token.
        10 => {
            let w = word_ranges(v);
            let Some(&(a, b)) = rng.pick(&w) else {
                return v.to_vec();
            };
            let t = token(rng, words);
            splice(v, a, b, t.as_bytes())
        }
        // Delete a word.
        11 => {
            let w = word_ranges(v);
            let Some(&(a, b)) = rng.pick(&w) else {
                return v.to_vec();
            };
            splice(v, a, b, b"")
        }
        // Deep nesting around a word (or at a random place).
        12 => {
            let Some(&(open, close)) = rng.pick(nests) else {
                return v.to_vec();
            };
            let depth = [10, 100, 1_000, 10_000][rng.below(4)];
            let w = word_ranges(v);
            let (a, b) = rng.pick(&w).copied().unwrap_or((at, at));
            let mut out = v[..a].to_vec();
            for _ in 0..depth {
                out.extend_from_slice(open.as_bytes());
            }
            out.extend_from_slice(&v[a..b]);
            if rng.below(4) != 0 {
                for _ in 0..depth {
                    out.extend_from_slice(close.as_bytes());
                }
            }
            out.extend_from_slice(&v[b..]);
            out
        }
        // A very long line: one word repeated many times.
        13 => {
            let w = word_ranges(v);
            let (a, b) = rng.pick(&w).copied().unwrap_or((at, at));
            let word = v[a..b].to_vec();
            let sep = token(rng, words);
            let times = [10, 100, 1_000, 10_000][rng.below(4)];
            let mut piece = Vec::new();
            for _ in 0..times {
                piece.extend_from_slice(&word);
                piece.push(b' ');
                piece.extend_from_slice(sep.as_bytes());
                piece.push(b' ');
            }
            splice(v, b, b, &piece)
        }
        // Replace a number (a run of digits) by a huge or odd one.
        14 => {
            let digits: Vec<usize> = (0..len).filter(|&i| v[i].is_ascii_digit()).collect();
            let Some(&i) = rng.pick(&digits) else {
                return v.to_vec();
            };
            let mut j = i;
            while j < len && (v[j].is_ascii_digit() || v[j] == b'.') {
                j += 1;
            }
            let mut s = i;
            while s > 0 && v[s - 1].is_ascii_digit() {
                s -= 1;
            }
            let t = rng
                .pick(&SPECIAL[..24])
                .copied()
                .unwrap_or("99999999999999999999");
            splice(v, s, j, t.as_bytes())
        }
        // Cut a multi-byte character in half (invalid UTF-8), or add a
        // lone continuation / overlong byte.
        _ => {
            let bad: &[u8] =
                [&b"\xC3"[..], b"\xE6\x97", b"\x80", b"\xFF\xFE", b"\xC0\xAF"][rng.below(5)];
            splice(v, at, at, bad)
        }
    }
}

/// The first `n` characters of `s` (for failure messages).
pub fn brief(s: &str, n: usize) -> String {
    let mut out: String = s.chars().take(n).collect();
    if s.chars().nth(n).is_some() {
        out.push('…');
    }
    out
}

/// Runs `case` and turns a panic into an error message naming `what`;
/// also reports a case slower than `limit` (a hang in the making).
pub fn guarded(what: &str, limit: Duration, case: impl FnOnce()) -> Result<Duration, String> {
    let start = Instant::now();
    let r = catch_unwind(AssertUnwindSafe(case));
    let took = start.elapsed();
    match r {
        Err(e) => {
            let msg = e
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| e.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            Err(format!("{what}: panicked: {msg}"))
        }
        Ok(()) if took > limit => Err(format!("{what}: took {took:?} (limit {limit:?})")),
        Ok(()) => Ok(took),
    }
}
