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

/// The whole report for a run: every diagnostic, then a summary line.
pub fn render_report(map: &SourceMap, diags: &[Diagnostic]) -> String {
    let mut out = String::new();
    for d in diags {
        out.push_str(&render_human(map, d));
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
/// `line`, `column`, `end_line`, `end_column`, `message`, `labels`, `notes`.
pub fn render_json(map: &SourceMap, diags: &[Diagnostic]) -> String {
    let items: Vec<serde_json::Value> = diags.iter().map(|d| json_of(map, d)).collect();
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
}
