//! Rendering diagnostics for people (rustc-like, with a source excerpt and a
//! caret) and for programs (JSON).
//!
//! The human format's first line is the contract scripts grep for:
//! `file:line:col: error[E030]: message`.

use crate::diag::{Diagnostic, Severity};
use crate::source::SourceMap;
use crate::span::Span;
use std::fmt::Write;

fn severity_word(s: Severity) -> &'static str {
    match s {
        Severity::Error => "error",
        Severity::Warning => "warning",
    }
}

/// One diagnostic as text, ending with a blank line.
pub fn render_human(map: &SourceMap, d: &Diagnostic) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "{}: {}[{}]: {}",
        map.location(d.span),
        severity_word(d.severity),
        d.code.as_str(),
        d.message
    );
    let mut excerpts: Vec<(Span, &str)> = vec![(d.span, "")];
    excerpts.extend(d.labels.iter().map(|l| (l.span, l.message.as_str())));
    let width = excerpts
        .iter()
        .filter_map(|(s, _)| line_of(map, *s))
        .map(|(l, _, _)| l.to_string().len())
        .max()
        .unwrap_or(1);
    let pad = " ".repeat(width);
    for (i, (span, msg)) in excerpts.iter().enumerate() {
        let Some((line_no, line, col)) = line_of(map, *span) else {
            continue;
        };
        if i > 0 && span.file != d.span.file {
            let _ = writeln!(out, "{pad}--> {}", map.location(*span));
        }
        let _ = writeln!(out, "{pad} |");
        let shown = line.trim_end_matches(['\r', '\n']).replace('\t', " ");
        let _ = writeln!(out, "{:>width$} | {}", line_no, shown);
        let caret_len = span_chars_on_line(map, *span, line).max(1);
        let marker = if i == 0 { '^' } else { '-' };
        let _ = writeln!(
            out,
            "{pad} | {}{} {}",
            " ".repeat(col as usize - 1),
            marker.to_string().repeat(caret_len),
            msg
        )
        .map(|_| ());
        // Trim the trailing space when there is no label text.
        if msg.is_empty() && out.ends_with(" \n") {
            out.truncate(out.len() - 2);
            out.push('\n');
        }
    }
    for note in &d.notes {
        let _ = writeln!(out, "{pad} = note: {note}");
    }
    out.push('\n');
    out
}

/// How many diagnostics a report shows. Past a few hundred nobody reads
/// them, and a hostile or binary file would otherwise give more text than
/// it is long (50 MB of random bytes gave 104 MB): the rest are counted.
pub const MAX_SHOWN: usize = 200;

fn plural(n: usize, word: &str) -> String {
    format!("{n} {word}{}", if n == 1 { "" } else { "s" })
}

/// What the report says for the diagnostics past [`MAX_SHOWN`]:
/// `and 5 more (4 errors, 1 warning)`; `None` when all are shown.
pub fn omitted(diags: &[Diagnostic]) -> Option<String> {
    let rest = diags.get(MAX_SHOWN..).filter(|r| !r.is_empty())?;
    let errors = rest.iter().filter(|d| d.is_error()).count();
    Some(format!(
        "and {} more ({}, {})",
        rest.len(),
        plural(errors, "error"),
        plural(rest.len() - errors, "warning")
    ))
}

/// The whole report for a run: the first [`MAX_SHOWN`] diagnostics, a line
/// counting the others, then a summary line over all of them.
pub fn render_report(map: &SourceMap, diags: &[Diagnostic]) -> String {
    let mut out = String::new();
    for d in diags.iter().take(MAX_SHOWN) {
        out.push_str(&render_human(map, d));
    }
    if let Some(more) = omitted(diags) {
        let _ = writeln!(out, "{more} not shown\n");
    }
    let errors = diags.iter().filter(|d| d.is_error()).count();
    let warnings = diags.len() - errors;
    if errors > 0 || warnings > 0 {
        let _ = writeln!(
            out,
            "{} error{}, {} warning{}",
            errors,
            if errors == 1 { "" } else { "s" },
            warnings,
            if warnings == 1 { "" } else { "s" }
        );
    }
    out
}

/// Diagnostics as a JSON array of objects with `code`, `severity`, `file`,
/// `line`, `column`, `end_line`, `end_column`, `message`, `labels`, `notes`:
/// the first [`MAX_SHOWN`], then, when there are more, one object of the
/// same shape with severity `note`, an empty code, no file and the message
/// `and N more (E errors, W warnings) not shown`.
pub fn render_json(map: &SourceMap, diags: &[Diagnostic]) -> String {
    let mut items: Vec<serde_json::Value> = diags
        .iter()
        .take(MAX_SHOWN)
        .map(|d| json_of(map, d))
        .collect();
    if let Some(more) = omitted(diags) {
        items.push(serde_json::json!({
            "file": null, "line": 0, "column": 0, "end_line": 0, "end_column": 0,
            "code": "", "severity": "note", "message": format!("{more} not shown"),
            "labels": [], "notes": [],
        }));
    }
    serde_json::to_string_pretty(&items).unwrap_or_else(|_| "[]".to_string())
}

fn position(map: &SourceMap, span: Span) -> serde_json::Value {
    if (span.file.0 as usize) >= map.len() {
        return serde_json::json!({"file": null, "line": 0, "column": 0, "end_line": 0, "end_column": 0});
    }
    let f = map.get(span.file);
    let (line, column) = f.line_col(span.start);
    let (end_line, end_column) = f.line_col(span.end);
    serde_json::json!({
        "file": f.name, "line": line, "column": column,
        "end_line": end_line, "end_column": end_column,
    })
}

fn json_of(map: &SourceMap, d: &Diagnostic) -> serde_json::Value {
    let mut v = position(map, d.span);
    if let Some(obj) = v.as_object_mut() {
        obj.insert("code".into(), d.code.as_str().into());
        obj.insert("severity".into(), severity_word(d.severity).into());
        obj.insert("message".into(), d.message.clone().into());
        let labels: Vec<serde_json::Value> = d
            .labels
            .iter()
            .map(|l| {
                let mut p = position(map, l.span);
                if let Some(o) = p.as_object_mut() {
                    o.insert("message".into(), l.message.clone().into());
                }
                p
            })
            .collect();
        obj.insert("labels".into(), labels.into());
        obj.insert("notes".into(), d.notes.clone().into());
    }
    v
}

/// (line number, line text, column) of a span's start, if the span is valid.
fn line_of(map: &SourceMap, span: Span) -> Option<(u32, &str, u32)> {
    if (span.file.0 as usize) >= map.len() {
        return None;
    }
    let f = map.get(span.file);
    let (line, col) = f.line_col(span.start);
    let starts = f.line_starts();
    let start = starts[line as usize - 1] as usize;
    let end = starts
        .get(line as usize)
        .map(|&e| e as usize)
        .unwrap_or(f.text.len());
    Some((line, f.text.get(start..end)?, col))
}

fn span_chars_on_line(map: &SourceMap, span: Span, line: &str) -> usize {
    let text = map.text(span);
    let first_line = text.split('\n').next().unwrap_or("");
    first_line.chars().count().min(line.chars().count())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::codes::Code;

    #[test]
    fn human_format_has_location_code_and_caret() {
        let mut map = SourceMap::new();
        let f = map.add("p.st", "PROGRAM p\n  i := d;\nEND_PROGRAM\n");
        let d = Diagnostic::error(
            Code::E030,
            Span::new(f, 17, 18),
            "cannot assign DINT to INT",
        )
        .with_note("use DINT_TO_INT");
        let s = render_human(&map, &d);
        assert_eq!(
            s,
            "p.st:2:8: error[E030]: cannot assign DINT to INT\n  |\n2 |   i := d;\n  |        ^\n  = note: use DINT_TO_INT\n\n"
        );
    }

    #[test]
    fn json_has_positions() {
        let mut map = SourceMap::new();
        let f = map.add("p.st", "x\ny");
        let d = Diagnostic::warning(Code::W001, Span::new(f, 2, 3), "unused");
        let v: serde_json::Value = serde_json::from_str(&render_json(&map, &[d])).unwrap();
        assert_eq!(v[0]["line"], 2);
        assert_eq!(v[0]["column"], 1);
        assert_eq!(v[0]["code"], "W001");
        assert_eq!(v[0]["severity"], "warning");
    }

    /// 150 errors then 100 warnings on one line each of a file.
    fn many() -> (SourceMap, Vec<Diagnostic>) {
        let mut map = SourceMap::new();
        let f = map.add("p.st", "x\n".repeat(250));
        let diags = (0..250u32)
            .map(|i| {
                let span = Span::new(f, 2 * i, 2 * i + 1);
                if i < 150 {
                    Diagnostic::error(Code::E030, span, format!("e{i}"))
                } else {
                    Diagnostic::warning(Code::W001, span, format!("w{i}"))
                }
            })
            .collect();
        (map, diags)
    }

    #[test]
    fn a_report_shows_the_first_200_and_counts_the_rest() {
        let (map, diags) = many();
        let text = render_report(&map, &diags);
        assert_eq!(text.matches(": error[E030]: ").count(), 150);
        assert_eq!(text.matches(": warning[W001]: ").count(), 50);
        assert!(text.contains("p.st:200:1: warning[W001]: w199\n"), "{text}");
        assert!(!text.contains("w200"));
        let tail =
            "\n\nand 50 more (0 errors, 50 warnings) not shown\n\n150 errors, 100 warnings\n";
        assert!(text.ends_with(tail), "{}", &text[text.len() - 200..]);
        // At the cap, nothing is left out.
        let text = render_report(&map, &diags[..200]);
        assert!(!text.contains("not shown"));
        assert!(text.ends_with("150 errors, 50 warnings\n"));
        let mixed: Vec<Diagnostic> = diags[..50].iter().chain(&diags).cloned().collect();
        assert_eq!(
            omitted(&mixed).unwrap(),
            "and 100 more (0 errors, 100 warnings)"
        );
        let errors_past: Vec<Diagnostic> =
            diags[150..].iter().chain(&diags[..150]).cloned().collect();
        assert_eq!(
            omitted(&errors_past).unwrap(),
            "and 50 more (50 errors, 0 warnings)"
        );
    }

    #[test]
    fn json_shows_the_first_200_and_one_note_for_the_rest() {
        let (map, diags) = many();
        let v: serde_json::Value = serde_json::from_str(&render_json(&map, &diags)).unwrap();
        let items = v.as_array().unwrap();
        assert_eq!(items.len(), 201);
        assert_eq!(items[199]["message"], "w199");
        let note = &items[200];
        assert_eq!(note["severity"], "note");
        assert_eq!(note["code"], "");
        assert_eq!(note["file"], serde_json::Value::Null);
        assert_eq!(
            note["message"],
            "and 50 more (0 errors, 50 warnings) not shown"
        );
        let v: serde_json::Value = serde_json::from_str(&render_json(&map, &diags[..200])).unwrap();
        assert_eq!(v.as_array().unwrap().len(), 200);
    }
}
