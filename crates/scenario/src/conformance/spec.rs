//! The expectation header of a conformance case: its syntax (documented in
//! `mod.rs`) and its parser.

use automat_ir::FaultKind;

/// One `expect:` / `expect-at N:` line.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Expect {
    /// `None`: after the last scan; `Some(k)`: after scan k (1-based).
    pub at: Option<u64>,
    pub path: String,
    /// The exact printed form (`format_value` text).
    pub value: String,
    /// Line in the `.st` file, for messages.
    pub line: usize,
}

/// An `expect-fault:` line.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ExpectFault {
    pub kind: FaultKind,
    /// Source line of the fault site.
    pub line: u32,
    /// The scan the fault happens in, when given.
    pub cycle: Option<u64>,
}

/// A whole header.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Spec {
    pub cycles: u64,
    pub cycle_time_ns: i64,
    pub program: Option<String>,
    pub budget: Option<u64>,
    /// `watchdog: TIME|off`: the watchdog of every task of the case.
    pub watchdog: Option<automat_ir::TaskWatchdog>,
    pub expects: Vec<Expect>,
    pub fault: Option<ExpectFault>,
    /// `skip-until:` reason: the case is reported as pending.
    pub pending: Option<String>,
    /// `known-bug:` reason: a failure is reported but does not fail the run.
    pub known_bug: Option<String>,
    /// `libraries: isagraf, ...`: vendor dialects (`automat run --lib`).
    pub libraries: Vec<String>,
}

fn fault_kind(name: &str) -> Option<FaultKind> {
    Some(match name {
        "division-by-zero" => FaultKind::DivisionByZero,
        "index-out-of-bounds" => FaultKind::IndexOutOfBounds,
        "subrange" => FaultKind::SubrangeViolation,
        "string-index" => FaultKind::StringIndex,
        "watchdog" => FaultKind::Watchdog,
        "function" => FaultKind::Function,
        _ => return None,
    })
}

/// `KIND at LINE [in cycle K]`
fn parse_fault(text: &str) -> Result<ExpectFault, String> {
    let words: Vec<&str> = text.split_whitespace().collect();
    let bad = || format!("expect-fault: `{text}`: want `KIND at LINE [in cycle K]`");
    let (kind, line, cycle) = match words.as_slice() {
        [k, "at", l] => (k, l, None),
        [k, "at", l, "in", "cycle", c] => (k, l, Some(c)),
        _ => return Err(bad()),
    };
    let kind =
        fault_kind(kind).ok_or_else(|| format!("expect-fault: unknown fault kind `{kind}`"))?;
    let line = line.parse().map_err(|_| bad())?;
    let cycle = match cycle {
        Some(c) => Some(c.parse().map_err(|_| bad())?),
        None => None,
    };
    Ok(ExpectFault { kind, line, cycle })
}

/// `PATH = VALUE` (the value is everything after the first ` = `, trimmed).
fn parse_expect(text: &str, at: Option<u64>, line: usize) -> Result<Expect, String> {
    let (path, value) = text
        .split_once(" = ")
        .ok_or_else(|| format!("line {line}: `{text}`: want `PATH = VALUE`"))?;
    Ok(Expect {
        at,
        path: path.trim().to_string(),
        value: value.trim().to_string(),
        line,
    })
}

/// The text of the header: the first comment, which must open the file.
pub(crate) fn header(source: &str) -> Result<(&str, usize), String> {
    let start = source.trim_start();
    // A PLCopen XML case carries the header in its first XML comment, after
    // the XML declaration when it has one (files saved by Beremiz, CODESYS).
    let start = match start.strip_prefix("<?xml") {
        Some(rest) => rest
            .find("?>")
            .map_or(start, |e| rest[e + 2..].trim_start()),
        None => start,
    };
    let start = start.strip_prefix("<!--").map_or(start, str::trim_start);
    let skipped = source.len() - start.len();
    let body = start
        .strip_prefix("(*")
        .ok_or("the file must start with a `(* ... *)` expectation header")?;
    let end = body
        .find("*)")
        .ok_or("the expectation header is not closed")?;
    let first_line = source.get(..skipped).unwrap_or("").matches('\n').count() + 1;
    Ok((body.get(..end).unwrap_or(""), first_line))
}

/// Parses the header of a conformance case.
pub fn parse(source: &str) -> Result<Spec, String> {
    let (text, first_line) = header(source)?;
    let mut spec = Spec {
        cycles: 1,
        cycle_time_ns: 10_000_000,
        program: None,
        budget: None,
        watchdog: None,
        expects: Vec::new(),
        fault: None,
        pending: None,
        known_bug: None,
        libraries: Vec::new(),
    };
    for (i, raw) in text.lines().enumerate() {
        let line = first_line + i;
        let l = raw.trim();
        // `--` starts a note that the harness ignores.
        let l = l.split_once(" -- ").map_or(l, |(a, _)| a).trim();
        if l.is_empty() || l.starts_with("--") {
            continue;
        }
        let Some((key, rest)) = l.split_once(':') else {
            // Free text (a title) is allowed.
            continue;
        };
        let rest = rest.trim();
        match key.trim() {
            "cycles" => {
                spec.cycles = rest
                    .parse()
                    .map_err(|_| format!("line {line}: cycles: `{rest}` is not a count"))?
            }
            "cycle-time" => {
                spec.cycle_time_ns = automat_runtime::timearg::parse_duration(rest)
                    .map_err(|e| format!("line {line}: cycle-time: {e}"))?
            }
            "program" => spec.program = Some(rest.to_string()),
            "budget" => {
                spec.budget = Some(
                    rest.parse()
                        .map_err(|_| format!("line {line}: budget: `{rest}` is not a count"))?,
                )
            }
            "watchdog" => {
                spec.watchdog = Some(
                    automat_runtime::watchdog::parse_watchdog(rest)
                        .map_err(|e| format!("line {line}: watchdog: {e}"))?,
                )
            }
            "expect" => spec.expects.push(parse_expect(rest, None, line)?),
            "expect-fault" => {
                spec.fault = Some(parse_fault(rest).map_err(|e| format!("line {line}: {e}"))?)
            }
            "skip-until" => spec.pending = Some(rest.to_string()),
            "known-bug" => spec.known_bug = Some(rest.to_string()),
            "libraries" => spec
                .libraries
                .extend(rest.split(',').map(|l| l.trim().to_string())),
            k if k.starts_with("expect-at ") => {
                let n = k.get("expect-at ".len()..).unwrap_or("").trim();
                let at = n
                    .parse()
                    .map_err(|_| format!("line {line}: expect-at: `{n}` is not a scan number"))?;
                spec.expects.push(parse_expect(rest, Some(at), line)?);
            }
            _ => {}
        }
    }
    Ok(spec)
}

#[cfg(test)]
#[test]
fn header_after_an_xml_declaration() {
    let src = "<?xml version='1.0' encoding='utf-8'?>\n<!--(* cycles: 2\n   expect: p.x = 1\n*)-->\n<project/>";
    let s = parse(src).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(s.cycles, 2);
    assert_eq!(s.expects[0].line, 3);
}

#[test]
fn header_syntax() {
    let src = "\n(* title: whatever\n   cycles: 3\n   cycle-time: T#20ms\n   expect: Main.q = TRUE\n   expect-at 2: a[1].x = 'a = b'  -- note\n   expect-fault: division-by-zero at 12 in cycle 3\n   known-bug: E1\n*)\nPROGRAM Main END_PROGRAM";
    let s = parse(src).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!((s.cycles, s.cycle_time_ns), (3, 20_000_000));
    assert_eq!(
        s.expects,
        vec![
            Expect {
                at: None,
                path: "Main.q".into(),
                value: "TRUE".into(),
                line: 5
            },
            Expect {
                at: Some(2),
                path: "a[1].x".into(),
                value: "'a = b'".into(),
                line: 6
            },
        ]
    );
    assert_eq!(
        s.fault,
        Some(ExpectFault {
            kind: FaultKind::DivisionByZero,
            line: 12,
            cycle: Some(3)
        })
    );
    assert_eq!(s.known_bug.as_deref(), Some("E1"));
    assert!(parse("PROGRAM p END_PROGRAM").is_err());
    assert!(parse("(* expect-fault: oops at 1 *)").is_err());
    assert!(parse("(* expect: nothing *)").is_err());
}
