//! Robustness: mutate every sample program and every `.st` file of the
//! repository's `tests/corpus/` in many deterministic ways and parse each
//! result. Nothing may panic, hang or overflow the stack, and diagnostics
//! must stay well-formed (codes E001–E007 and the IL codes, spans inside the text, sorted).

use automat_base::{Code, FileId, Interner};
use automat_syntax::lexer;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

const SAMPLES: &[(&str, &str)] = &[
    ("traffic.st", include_str!("samples/traffic.st")),
    ("math.st", include_str!("samples/math.st")),
    ("plant.st", include_str!("samples/plant.st")),
];

/// Bytes of corpus mutants parsed in total (keeps the test within a few
/// seconds in a debug build however large the corpus grows).
const BUDGET: usize = 16 << 20;

/// xorshift64*: small, seeded, good enough to pick positions.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    fn below(&mut self, n: usize) -> usize {
        if n == 0 {
            0
        } else {
            (self.next() % n as u64) as usize
        }
    }
}

/// The codes the IL parser and its desugaring report (E105–E107 are the
/// checker's).
fn is_il_code(c: Code) -> bool {
    matches!(
        c,
        Code::E100
            | Code::E101
            | Code::E102
            | Code::E103
            | Code::E104
            | Code::E108
            | Code::E109
            | Code::E110
    )
}

/// The chart checks `parse` runs on each textual SFC (`desugar::sfc::check`).
fn is_chart_code(c: Code) -> bool {
    matches!(
        c,
        Code::E120
            | Code::E121
            | Code::E122
            | Code::E123
            | Code::E124
            | Code::E125
            | Code::E126
            | Code::E128
            | Code::E129
            | Code::E130
            | Code::E131
            | Code::W120
            | Code::W121
            | Code::W122
    )
}

fn corpus_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let mut paths: Vec<PathBuf> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
    paths.sort();
    for p in paths {
        if p.is_dir() {
            corpus_files(&p, out);
        } else if p.extension().is_some_and(|e| e.eq_ignore_ascii_case("st")) {
            out.push(p);
        }
    }
}

fn inputs() -> Vec<(String, String)> {
    let mut v: Vec<(String, String)> = SAMPLES
        .iter()
        .map(|(n, t)| (n.to_string(), t.to_string()))
        .collect();
    let corpus = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/corpus");
    let mut files = Vec::new();
    corpus_files(&corpus, &mut files);
    for f in files {
        if let Ok(bytes) = std::fs::read(&f) {
            let name = f.display().to_string();
            v.push((name, String::from_utf8_lossy(&bytes).into_owned()));
        }
    }
    v
}

/// Parses and checks the invariants; returns how long it took.
fn check(name: &str, what: &str, text: &str) -> Duration {
    let start = Instant::now();
    let mut interner = Interner::new();
    let parsed = automat_syntax::parse(FileId(0), text, &mut interner);
    let took = start.elapsed();
    let mut last = 0;
    for d in &parsed.diagnostics {
        assert!(
            matches!(
                d.code,
                Code::E001
                    | Code::E002
                    | Code::E003
                    | Code::E004
                    | Code::E005
                    | Code::E006
                    | Code::E007
                    // VAR_STAT outside the CODESYS dialect, a CODESYS
                    // ACTION after something else than a function block.
                    | Code::E160
                    | Code::E161
                    // MatIEC's embedded C code `{{ ... }}`.
                    | Code::E191
            ) || is_il_code(d.code)
                || is_chart_code(d.code),
            "{name} ({what}): unexpected code {:?}",
            d.code
        );
        assert!(
            d.span.start <= d.span.end && d.span.end as usize <= text.len(),
            "{name} ({what}): span {:?} outside the text of {} bytes",
            d.span,
            text.len()
        );
        assert!(
            d.span.start >= last,
            "{name} ({what}): diagnostics not sorted"
        );
        last = d.span.start;
        assert!(!d.message.is_empty());
    }
    took
}

/// Token boundaries `(start, end)` of a text, from the real lexer.
fn token_ranges(text: &str) -> Vec<(usize, usize)> {
    let mut interner = Interner::new();
    let mut diags = Vec::new();
    let lexed = lexer::lex(FileId(0), text, &mut interner, &mut diags);
    lexed
        .toks
        .iter()
        .filter(|t| t.start < t.end)
        .map(|t| (t.start as usize, t.end as usize))
        .collect()
}

fn floor_char(s: &str, mut i: usize) -> usize {
    i = i.min(s.len());
    while !s.is_char_boundary(i) {
        i -= 1;
    }
    i
}

fn splice(s: &str, at: usize, del: usize, insert: &str) -> String {
    let a = floor_char(s, at);
    let b = floor_char(s, at + del).max(a);
    format!("{}{}{}", &s[..a], insert, &s[b..])
}

/// Fragments that tend to break lexers and parsers.
const NASTY: &[&str] = &[
    "(*",
    "*)",
    "/*",
    "*/",
    "//",
    "{",
    "}",
    "'",
    "\"",
    "$",
    "$'",
    "#",
    "%",
    "%I",
    "%IX",
    "%QW*",
    "16#",
    "T#",
    "TOD#25:",
    "D#2024-",
    "1..",
    "..",
    ".",
    "..5",
    ":=",
    "=>",
    ";",
    ",",
    "(",
    ")",
    "[",
    "]",
    "^",
    "**",
    "END_IF",
    "END_VAR",
    "ELSE",
    "UNTIL",
    "VAR",
    "STRUCT",
    "ARRAY",
    "OF",
    "CASE x OF",
    "1:",
    "\u{0}",
    "\u{7f}",
    "\u{feff}",
    "\u{e9}",
    "\u{2028}",
    "\u{1F600}",
    "\r",
    "\t",
    "\u{fffd}",
    "9999999999999999999999",
    "1e999",
    "INT#",
    "Color#",
    "AT",
    "%X99999999999",
];

const KEYWORDS: &[&str] = &[
    "IF",
    "THEN",
    "ELSIF",
    "END_IF",
    "CASE",
    "OF",
    "END_CASE",
    "FOR",
    "TO",
    "BY",
    "DO",
    "END_FOR",
    "WHILE",
    "END_WHILE",
    "REPEAT",
    "UNTIL",
    "END_REPEAT",
    "PROGRAM",
    "END_PROGRAM",
    "FUNCTION",
    "FUNCTION_BLOCK",
    "VAR",
    "VAR_INPUT",
    "END_VAR",
    "TYPE",
    "END_TYPE",
    "STRUCT",
    "END_STRUCT",
    "CONFIGURATION",
    "RESOURCE",
    "TASK",
    "WITH",
    "ON",
    "AT",
    "NOT",
    "MOD",
    "RETURN",
    "EXIT",
];

fn mutants(text: &str, rng: &mut Rng, rounds: usize) -> Vec<(String, String)> {
    let toks = token_ranges(text);
    let lines: Vec<&str> = text.split_inclusive('\n').collect();
    let mut out = Vec::new();
    // Truncation at every k-th byte.
    let k = (text.len() / rounds.max(1)).max(1);
    for at in (0..text.len()).step_by(k) {
        out.push((
            format!("truncate at {at}"),
            text[..floor_char(text, at)].to_string(),
        ));
    }
    for round in 0..rounds {
        let tok = |rng: &mut Rng| toks.get(rng.below(toks.len())).copied().unwrap_or((0, 0));
        let m = match round % 8 {
            0 => {
                let (a, _) = tok(rng);
                let (_, b) = toks
                    .get((rng.below(toks.len()) + 1).min(toks.len().saturating_sub(1)))
                    .copied()
                    .unwrap_or((0, 0));
                let (a, b) = (a.min(b), a.max(b).min(a.min(b) + 400));
                ("delete tokens".to_string(), splice(text, a, b - a, ""))
            }
            1 => {
                let i = rng.below(lines.len());
                let mut s: Vec<&str> = lines.clone();
                if let Some(l) = lines.get(i) {
                    s.insert(i, l);
                }
                (format!("duplicate line {i}"), s.concat())
            }
            2 => {
                let (a1, b1) = tok(rng);
                let (a2, b2) = tok(rng);
                let ((a1, b1), (a2, b2)) = if a1 <= a2 {
                    ((a1, b1), (a2, b2))
                } else {
                    ((a2, b2), (a1, b1))
                };
                if b1 > a2 {
                    ("swap (same token)".to_string(), text.to_string())
                } else {
                    let s = format!(
                        "{}{}{}{}{}",
                        &text[..a1],
                        &text[a2..b2],
                        &text[b1..a2],
                        &text[a1..b1],
                        &text[b2..]
                    );
                    ("swap tokens".to_string(), s)
                }
            }
            3 => {
                let n = 1 + rng.below(8);
                let bytes: Vec<u8> = (0..n).map(|_| rng.next() as u8).collect();
                let junk = String::from_utf8_lossy(&bytes).into_owned();
                (
                    "insert random bytes".to_string(),
                    splice(text, rng.below(text.len() + 1), 0, &junk),
                )
            }
            4 => {
                let frag = NASTY[rng.below(NASTY.len())];
                (
                    format!("insert {frag:?}"),
                    splice(text, rng.below(text.len() + 1), 0, frag),
                )
            }
            5 => {
                let (a, b) = tok(rng);
                let kw = KEYWORDS[rng.below(KEYWORDS.len())];
                (
                    format!("replace a token with {kw}"),
                    splice(text, a, b - a, kw),
                )
            }
            6 => {
                let (a, b) = tok(rng);
                ("delete one token".to_string(), splice(text, a, b - a, ""))
            }
            _ => {
                let frag = NASTY[rng.below(NASTY.len())];
                let (a, b) = tok(rng);
                (
                    format!("replace a token with {frag:?}"),
                    splice(text, a, b - a, frag),
                )
            }
        };
        out.push(m);
    }
    out
}

/// Openers (and closers) that nest: statements, expressions, types,
/// initial values, comments.
const NESTS: &[(&str, &str)] = &[
    ("(", ")"),
    ("[", "]"),
    ("f(", ")"),
    ("a[", "]"),
    ("-", ""),
    ("NOT ", ""),
    ("IF x THEN ", " END_IF;"),
    ("CASE x OF 1: ", " END_CASE;"),
    ("WHILE x DO ", " END_WHILE;"),
    ("REPEAT ", " UNTIL x END_REPEAT;"),
    ("ARRAY [1..2] OF ", ""),
    ("STRUCT a : ", " END_STRUCT;"),
    ("(a := ", ")"),
    ("(*", ""),
    ("{", ""),
    ("a + ", ""),
    ("a ** ", ""),
    ("s.", ""),
];

/// One kind of deep nesting (far past the parser's limit) inserted at a
/// random place; half of the closers are missing.
fn deep(text: &str, rng: &mut Rng, kind: usize) -> (String, String) {
    let (open, close) = NESTS[kind % NESTS.len()];
    let at = rng.below(text.len() + 1);
    let n = 2_000;
    let ins = format!("{}x{}", open.repeat(n), close.repeat(n / 2));
    (format!("{n} × {open:?} at {at}"), splice(text, at, 0, &ins))
}

#[test]
fn mangled_inputs_never_panic_or_hang() {
    let inputs = inputs();
    let corpus: usize = inputs[SAMPLES.len()..]
        .iter()
        .map(|(_, t)| t.len().max(1))
        .sum();
    let mut rng = Rng(0x5EED_1EC6_1131_0003);
    let mut parses = 0usize;
    let mut slowest = (Duration::ZERO, String::new());
    for (i, (name, text)) in inputs.iter().enumerate() {
        // The samples get many rounds; the corpus shares the budget by size,
        // with at least a few rounds per file.
        let rounds = if i < SAMPLES.len() {
            300
        } else {
            (BUDGET / corpus.max(1) / 2).clamp(4, 300)
        };
        assert!(check(name, "original", text) < Duration::from_secs(5));
        let mut all = mutants(text, &mut rng, rounds);
        for _ in 0..2 {
            let kind = rng.below(NESTS.len());
            all.push(deep(text, &mut rng, kind));
        }
        for (what, m) in &all {
            let took = check(name, what, m);
            if std::env::var("MANGLED_TRACE").is_ok() && took > Duration::from_millis(20) {
                eprintln!("{took:?} {name}: {what} ({} bytes)", m.len());
            }
            parses += 1;
            if took > slowest.0 {
                slowest = (took, format!("{name}: {what}"));
            }
        }
    }
    // Linear-time parsing: no single input may take long even in debug.
    assert!(
        slowest.0 < Duration::from_secs(2),
        "slowest parse took {:?} ({})",
        slowest.0,
        slowest.1
    );
    assert!(parses >= 3 * 8);
}

#[test]
fn every_kind_of_deep_nesting_alone_and_in_every_sample() {
    let mut rng = Rng(7);
    for (open, _) in NESTS {
        check("nesting", open, &open.repeat(10_000));
    }
    for (name, text) in SAMPLES {
        for kind in 0..NESTS.len() {
            let (what, m) = deep(text, &mut rng, kind);
            check(name, &what, &m);
        }
    }
}

#[test]
fn samples_parse_cleanly() {
    for (name, text) in SAMPLES {
        let mut interner = Interner::new();
        let parsed = automat_syntax::parse(FileId(0), text, &mut interner);
        assert!(
            parsed.diagnostics.is_empty(),
            "{name}: {:#?}",
            parsed.diagnostics
        );
        assert!(!parsed.unit.items.is_empty());
    }
}

#[test]
fn arbitrary_bytes_never_panic() {
    let mut rng = Rng(42);
    for len in [0usize, 1, 2, 3, 5, 8, 13, 64, 512, 4096] {
        for _ in 0..40 {
            // Bias towards bytes that mean something to the lexer.
            let alphabet =
                b"(*)/{}'\"$#%:=;,.[]^+-<>&ABCDEFIXQWMTtdhms0123456789_ \n\x00\xc3\xa9\xff";
            let bytes: Vec<u8> = (0..len)
                .map(|_| {
                    if rng.below(4) == 0 {
                        rng.next() as u8
                    } else {
                        alphabet[rng.below(alphabet.len())]
                    }
                })
                .collect();
            let text = String::from_utf8_lossy(&bytes);
            check("random", "bytes", &text);
        }
    }
}
