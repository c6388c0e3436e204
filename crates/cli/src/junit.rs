//! JUnit XML for `automat test --junit FILE`: the format GitLab, Jenkins
//! and GitHub test reporters read (`testsuites` > `testsuite` per project or
//! folder, in the order first met > `testcase` per scenario or program,
//! with `failure`, `error` or `skipped`).

/// What became of one test case.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Passed,
    Failed,
    Error,
    Skipped,
}

/// One test case.
pub struct Case<'a> {
    pub suite: &'a str,
    pub name: &'a str,
    pub file: &'a str,
    pub kind: Kind,
    /// The failure, error or skip details (several lines).
    pub details: &'a str,
    pub secs: f64,
}

/// `text` as XML character data or attribute value: the five special
/// characters escaped, characters XML 1.0 cannot hold replaced by U+FFFD.
pub fn escape(text: &str) -> String {
    let mut s = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => s.push_str("&amp;"),
            '<' => s.push_str("&lt;"),
            '>' => s.push_str("&gt;"),
            '"' => s.push_str("&quot;"),
            '\'' => s.push_str("&apos;"),
            '\t' | '\n' | '\r' => s.push(c),
            c if (c as u32) < 0x20 || c == '\u{FFFE}' || c == '\u{FFFF}' => s.push('\u{FFFD}'),
            c => s.push(c),
        }
    }
    s
}

struct Counts {
    tests: usize,
    failures: usize,
    errors: usize,
    skipped: usize,
    secs: f64,
}

fn counts<'a>(cases: impl Iterator<Item = &'a Case<'a>>) -> Counts {
    let mut n = Counts {
        tests: 0,
        failures: 0,
        errors: 0,
        skipped: 0,
        secs: 0.0,
    };
    for c in cases {
        n.tests += 1;
        n.secs += c.secs;
        match c.kind {
            Kind::Passed => {}
            Kind::Failed => n.failures += 1,
            Kind::Error => n.errors += 1,
            Kind::Skipped => n.skipped += 1,
        }
    }
    n
}

fn attrs(n: &Counts, secs: f64) -> String {
    format!(
        "tests=\"{}\" failures=\"{}\" errors=\"{}\" skipped=\"{}\" time=\"{secs:.3}\"",
        n.tests, n.failures, n.errors, n.skipped
    )
}

/// The whole report; `wall_secs` is the run's wall time.
pub fn write(cases: &[Case], wall_secs: f64) -> String {
    let mut suites: Vec<&str> = Vec::new();
    for c in cases {
        if !suites.contains(&c.suite) {
            suites.push(c.suite);
        }
    }
    let all = counts(cases.iter());
    let mut x = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    x.push_str(&format!(
        "<testsuites name=\"automat test\" {}>\n",
        attrs(&all, wall_secs)
    ));
    for suite in suites {
        let n = counts(cases.iter().filter(|c| c.suite == suite));
        x.push_str(&format!(
            "  <testsuite name=\"{}\" {}>\n",
            escape(suite),
            attrs(&n, n.secs)
        ));
        for c in cases.iter().filter(|c| c.suite == suite) {
            x.push_str(&format!(
                "    <testcase name=\"{}\" classname=\"{}\" file=\"{}\" time=\"{:.3}\"",
                escape(c.name),
                escape(suite),
                escape(c.file),
                c.secs
            ));
            let first = c.details.lines().next().unwrap_or("").trim();
            let (tag, kind) = match c.kind {
                Kind::Passed => {
                    x.push_str("/>\n");
                    continue;
                }
                Kind::Failed => ("failure", "failure"),
                Kind::Error => ("error", "error"),
                Kind::Skipped => {
                    x.push_str(&format!(
                        ">\n      <skipped message=\"{}\"/>\n    </testcase>\n",
                        escape(first)
                    ));
                    continue;
                }
            };
            x.push_str(&format!(
                ">\n      <{tag} message=\"{}\" type=\"{kind}\">{}</{tag}>\n    </testcase>\n",
                escape(first),
                escape(c.details)
            ));
        }
        x.push_str("  </testsuite>\n");
    }
    x.push_str("</testsuites>\n");
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suites_cases_and_escapes() {
        let cases = [
            Case {
                suite: "examples/crane",
                name: "a.scn (normal)",
                file: "examples/crane/scenarios/a.scn",
                kind: Kind::Passed,
                details: "",
                secs: 0.25,
            },
            Case {
                suite: "tests/conformance",
                name: "x.st",
                file: "tests/conformance/x.st",
                kind: Kind::Failed,
                details: "x.st:3: expect a < 1 & \"b\"\n  failed at 2s: it is FALSE\u{1}",
                secs: 0.5,
            },
            Case {
                suite: "examples/crane",
                name: "b.scn",
                file: "examples/crane/scenarios/b.scn",
                kind: Kind::Error,
                details: "b.scn:2:7: error[E320]: unknown action `jump`",
                secs: 0.0,
            },
            Case {
                suite: "tests/conformance",
                name: "y.st",
                file: "tests/conformance/y.st",
                kind: Kind::Skipped,
                details: "pending y.st: later",
                secs: 0.0,
            },
        ];
        assert_eq!(
            write(&cases, 1.0),
            r#"<?xml version="1.0" encoding="UTF-8"?>
<testsuites name="automat test" tests="4" failures="1" errors="1" skipped="1" time="1.000">
  <testsuite name="examples/crane" tests="2" failures="0" errors="1" skipped="0" time="0.250">
    <testcase name="a.scn (normal)" classname="examples/crane" file="examples/crane/scenarios/a.scn" time="0.250"/>
    <testcase name="b.scn" classname="examples/crane" file="examples/crane/scenarios/b.scn" time="0.000">
      <error message="b.scn:2:7: error[E320]: unknown action `jump`" type="error">b.scn:2:7: error[E320]: unknown action `jump`</error>
    </testcase>
  </testsuite>
  <testsuite name="tests/conformance" tests="2" failures="1" errors="0" skipped="1" time="0.500">
    <testcase name="x.st" classname="tests/conformance" file="tests/conformance/x.st" time="0.500">
      <failure message="x.st:3: expect a &lt; 1 &amp; &quot;b&quot;" type="failure">x.st:3: expect a &lt; 1 &amp; &quot;b&quot;
  failed at 2s: it is FALSE�</failure>
    </testcase>
    <testcase name="y.st" classname="tests/conformance" file="tests/conformance/y.st" time="0.000">
      <skipped message="pending y.st: later"/>
    </testcase>
  </testsuite>
</testsuites>
"#
        );
    }
}
