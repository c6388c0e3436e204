//! Robustness of the PLCopen importer: every XML case of the conformance
//! corpus is mutated in many deterministic ways (`crates/scenario/tests/
//! support/mutate.rs`) and checked as `automat check` does (import, then
//! the checker). Nothing may panic, hang or overflow the stack; every
//! diagnostic lies inside the file.

#[path = "../../scenario/tests/support/mutate.rs"]
mod mutate;

use automat_base::{Interner, SourceMap};
use mutate::{brief, guarded, mutate, Rng};
use std::path::PathBuf;
use std::time::{Duration, Instant};

/// Mutants of each case (a handful of files).
const MUTANTS: usize = 150;
const CASE_LIMIT: Duration = Duration::from_secs(5);

const WORDS: &[&str] = &[
    "<pou name=\"P\" pouType=\"program\">",
    "</pou>",
    "<body><LD>",
    "</LD></body>",
    "<FBD>",
    "<SFC>",
    "<contact localId=\"2\">",
    "<coil localId=\"3\" storage=\"set\">",
    "<block localId=\"4\" typeName=\"ADD\">",
    "<block localId=\"5\" typeName=\"python_eval\" instanceName=\"p\">",
    "<connection refLocalId=\"1\"/>",
    "<connection refLocalId=\"999\"/>",
    "<connection refLocalId=\"-1\" formalParameter=\"ENO\"/>",
    "localId=\"1\"",
    "executionOrderId=\"4294967296\"",
    "<jump localId=\"70\" label=\"L\">",
    "<label localId=\"71\" label=\"L\"/>",
    "<continuation localId=\"72\" name=\"W\">",
    "<variable name=\"x\"><type><INT/></type></variable>",
    "<derived name=\"END_VAR\"/>",
    "<expression>a; END_PROGRAM</expression>",
    "<expression>(*</expression>",
    "<![CDATA[",
    "]]>",
    "&lt;",
    "&#0;",
    "&#x110000;",
    "&unknown;",
    "<!--",
    "-->",
    "<?xml version=\"1.0\"?>",
    "<!DOCTYPE x>",
    "xmlns=\"http://www.plcopen.org/xml/tc6.xsd\"",
    "<simpleValue value=\"[1,2\"/>",
    "<arrayValue><value repetitionValue=\"99999999999\">",
    "<dimension lower=\"-9223372036854775809\" upper=\"1\"/>",
];

const NESTS: &[(&str, &str)] = &[
    ("<a>", "</a>"),
    ("<value><arrayValue>", "</arrayValue></value>"),
    (
        "<baseType><array><dimension lower=\"0\" upper=\"1\"/><baseType>",
        "</baseType></array></baseType>",
    ),
    ("(", ")"),
];

fn files() -> Vec<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../tests/conformance");
    let mut v: Vec<PathBuf> = std::fs::read_dir(&dir)
        .map(|d| d.filter_map(|e| e.ok().map(|e| e.path())).collect())
        .unwrap_or_default();
    v.retain(|p| p.extension().is_some_and(|x| x == "xml"));
    v.sort();
    v
}

fn case(text: &str) {
    let mut map = SourceMap::new();
    map.add("case.xml", text);
    let mut interner = Interner::new();
    let (_, analysis) = automat_dialect::check_sources(&map, &mut interner, &[]);
    for d in &analysis.diagnostics {
        assert!(
            d.span.start <= d.span.end && d.span.end as usize <= text.len(),
            "{d:?}"
        );
    }
    let _ = automat_base::render::render_report(&map, &analysis.diagnostics);
}

#[test]
fn mutated_plcopen_files_never_crash() {
    let files = files();
    assert!(files.len() >= 4, "only {} XML cases", files.len());
    let start = Instant::now();
    let mut failures = Vec::new();
    let mut cases = 0;
    for (k, f) in files.iter().enumerate() {
        let Ok(src) = std::fs::read(f) else { continue };
        for m in 0..MUTANTS {
            let seed = (k * 1_000 + m) as u64;
            let mut rng = Rng::new(seed);
            let bytes = mutate(&mut rng, &src, WORDS, NESTS);
            let text = String::from_utf8_lossy(&bytes).into_owned();
            let r = guarded(&format!("{} seed {seed}", f.display()), CASE_LIMIT, || {
                case(&text)
            });
            cases += 1;
            if let Err(e) = r {
                failures.push(format!("{e}\n  input: {:?}", brief(&text, 400)));
            }
        }
    }
    eprintln!(
        "plcopen: {} files, {cases} mutants in {:?}",
        files.len(),
        start.elapsed()
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
