//! The figures of `automat corpus` as text (one block per source, then the
//! totals) and as JSON (the same figures, for dashboards and the test that
//! pins them).

use super::{Source, Verdict};
use automat_base::Code;
use std::collections::BTreeMap;

/// The counts of one source, or of all of them.
#[derive(Default, Clone, Copy, PartialEq, Eq, Debug)]
pub struct Figures {
    pub files: usize,
    pub files_clean: usize,
    pub pous: usize,
    pub pous_clean: usize,
    pub passed: usize,
    pub failed: usize,
    pub pending: usize,
    pub known_bug: usize,
}

impl Figures {
    pub fn of(s: &Source) -> Figures {
        let mut f = Figures {
            files: s.files.len(),
            files_clean: s.files.iter().filter(|f| f.errors == 0).count(),
            pous: s.files.iter().map(|f| f.pous.len()).sum(),
            pous_clean: s
                .files
                .iter()
                .flat_map(|f| &f.pous)
                .filter(|p| p.errors.is_empty())
                .count(),
            ..Figures::default()
        };
        for e in &s.examples {
            match e.verdict {
                Verdict::Passed => f.passed += 1,
                Verdict::Failed(_) => f.failed += 1,
                Verdict::Pending(_) => f.pending += 1,
                Verdict::KnownBug(_) => f.known_bug += 1,
            }
        }
        f
    }

    fn add(&mut self, o: Figures) {
        self.files += o.files;
        self.files_clean += o.files_clean;
        self.pous += o.pous;
        self.pous_clean += o.pous_clean;
        self.passed += o.passed;
        self.failed += o.failed;
        self.pending += o.pending;
        self.known_bug += o.known_bug;
    }

    fn line(&self) -> String {
        let mut s = format!(
            "{}, {} clean; {}, {} clean; examples: {} passed, {} failed",
            plural(self.files, "file"),
            self.files_clean,
            plural(self.pous, "POU"),
            self.pous_clean,
            self.passed,
            self.failed
        );
        if self.pending > 0 {
            s.push_str(&format!(", {} pending", self.pending));
        }
        if self.known_bug > 0 {
            s.push_str(&format!(", {} known bugs", self.known_bug));
        }
        s
    }
}

fn plural(n: usize, word: &str) -> String {
    if n == 1 {
        format!("1 {word}")
    } else {
        format!("{n} {word}s")
    }
}

/// The totals over every source.
pub fn total(sources: &[Source]) -> Figures {
    let mut t = Figures::default();
    for s in sources {
        t.add(Figures::of(s));
    }
    t
}

/// Codes by count, most frequent first (then in code order), at most `top`.
fn top_codes(codes: &BTreeMap<Code, usize>, top: usize) -> Vec<(Code, usize)> {
    let mut v: Vec<(Code, usize)> = codes.iter().map(|(c, n)| (*c, *n)).collect();
    v.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
    v.truncate(top);
    v
}

/// `E030 ×2, E041` for the error codes of one POU.
fn code_list(codes: &[Code]) -> String {
    let mut counts: BTreeMap<Code, usize> = BTreeMap::new();
    for c in codes {
        *counts.entry(*c).or_default() += 1;
    }
    let parts: Vec<String> = counts
        .iter()
        .map(|(c, n)| match n {
            1 => c.as_str().to_string(),
            n => format!("{} ×{n}", c.as_str()),
        })
        .collect();
    parts.join(", ")
}

/// The text report: per source its figures, top codes, the POUs and files
/// that are not clean and the examples that did not pass; then the totals.
pub fn text(sources: &[Source], top: usize) -> String {
    let mut out = String::new();
    for s in sources {
        out.push_str(&format!("{}: {}\n", s.path, Figures::of(s).line()));
        let codes = top_codes(&s.codes, top);
        if !codes.is_empty() {
            let parts: Vec<String> = codes
                .iter()
                .map(|(c, n)| format!("{} ×{n}", c.as_str()))
                .collect();
            out.push_str(&format!("  top codes: {}\n", parts.join(", ")));
        }
        for f in &s.files {
            let dirty: Vec<_> = f.pous.iter().filter(|p| !p.errors.is_empty()).collect();
            for p in &dirty {
                out.push_str(&format!(
                    "  not clean: {}:{}: {} ({})\n",
                    f.path,
                    p.line,
                    p.name,
                    code_list(&p.errors)
                ));
            }
            let in_pous: usize = dirty.iter().map(|p| p.errors.len()).sum();
            if f.errors > in_pous {
                out.push_str(&format!(
                    "  not clean: {}: {} errors outside its POUs\n",
                    f.path,
                    f.errors - in_pous
                ));
            }
        }
        for e in &s.examples {
            let why = match &e.verdict {
                Verdict::Passed => continue,
                Verdict::Failed(w) => format!("FAILED {w}"),
                Verdict::Pending(w) => format!("pending {w}"),
                Verdict::KnownBug(w) => format!("known-bug {w}"),
            };
            for l in why.lines() {
                out.push_str(&format!("  {l}\n"));
            }
        }
    }
    if sources.len() > 1 {
        out.push_str(&format!("total: {}\n", total(sources).line()));
    }
    out
}

fn figures_json(f: Figures) -> serde_json::Value {
    serde_json::json!({
        "files": f.files, "files_clean": f.files_clean,
        "pous": f.pous, "pous_clean": f.pous_clean,
        "examples": {
            "passed": f.passed, "failed": f.failed,
            "pending": f.pending, "known_bug": f.known_bug,
        },
    })
}

/// The JSON report: `{"sources": [...], "total": {...}}`; each source has
/// its figures, `codes` (every code with its count), `not_clean` (file,
/// line, POU, error codes) and `examples` (file and verdict).
pub fn json(sources: &[Source]) -> String {
    let list: Vec<serde_json::Value> = sources
        .iter()
        .map(|s| {
            let mut v = figures_json(Figures::of(s));
            let codes: serde_json::Map<String, serde_json::Value> = s
                .codes
                .iter()
                .map(|(c, n)| (c.as_str().to_string(), (*n).into()))
                .collect();
            let not_clean: Vec<serde_json::Value> = s
                .files
                .iter()
                .flat_map(|f| {
                    f.pous.iter().filter(|p| !p.errors.is_empty()).map(|p| {
                        let codes: Vec<&str> = p.errors.iter().map(|c| c.as_str()).collect();
                        serde_json::json!({"file": f.path, "line": p.line, "pou": p.name, "codes": codes})
                    })
                })
                .collect();
            let examples: Vec<serde_json::Value> = s
                .examples
                .iter()
                .map(|e| {
                    let (verdict, details) = match &e.verdict {
                        Verdict::Passed => ("passed", String::new()),
                        Verdict::Failed(w) => ("failed", w.clone()),
                        Verdict::Pending(w) => ("pending", w.clone()),
                        Verdict::KnownBug(w) => ("known-bug", w.clone()),
                    };
                    serde_json::json!({"file": e.path, "verdict": verdict, "details": details})
                })
                .collect();
            if let Some(o) = v.as_object_mut() {
                o.insert("source".into(), s.path.clone().into());
                o.insert("codes".into(), codes.into());
                o.insert("not_clean".into(), not_clean.into());
                o.insert("example_results".into(), examples.into());
            }
            v
        })
        .collect();
    let doc = serde_json::json!({"sources": list, "total": figures_json(total(sources))});
    serde_json::to_string_pretty(&doc).unwrap_or_else(|_| "{}".to_string())
}
