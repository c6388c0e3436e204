//! `automat plot`: a trace CSV to a timing diagram.

pub mod csv;
mod font;
pub mod layout;
pub mod png;
pub mod svg;

use crate::Outcome;
use clap::Args;
use std::path::PathBuf;

/// Draw a timing diagram of a trace CSV (from `automat run --trace` or a
/// failed scenario): booleans as steps, numbers as lines with their range,
/// other values (active steps, states) as bands, a time axis with ticks.
/// Written as SVG, or as PNG when the output is `*.png` (the same drawing,
/// text in a built-in bitmap font).
///
/// Exit codes: 0 ok, 2 unreadable trace, unknown signal or bad output.
#[derive(Args)]
pub struct PlotArgs {
    /// The trace CSV.
    #[arg(value_name = "TRACE.csv")]
    trace: PathBuf,
    /// The diagram to write: `.svg`, or `.png` (the same drawing as pixels).
    #[arg(short = 'o', long = "output", value_name = "FILE")]
    output: PathBuf,
    /// Only these columns, in this order (comma-separated, case-insensitive).
    #[arg(long, value_name = "A,B,...", value_delimiter = ',')]
    signals: Vec<String>,
}

/// Keeps the named columns in the given order.
pub fn select(trace: &mut csv::Trace, names: &[String]) -> Result<(), String> {
    if names.is_empty() {
        return Ok(());
    }
    let mut cols = Vec::new();
    for n in names {
        let n = n.trim();
        let c = trace
            .columns
            .iter()
            .find(|c| c.name.eq_ignore_ascii_case(n))
            .ok_or_else(|| {
                format!(
                    "no column `{n}` in the trace (it has: {})",
                    trace
                        .columns
                        .iter()
                        .map(|c| c.name.as_str())
                        .collect::<Vec<_>>()
                        .join(", ")
                )
            })?;
        cols.push(c.clone());
    }
    trace.columns = cols;
    Ok(())
}

/// Writes the diagram of the CSV text `text` to `output` (SVG or PNG, by
/// its extension).
pub fn write_diagram(text: &str, names: &[String], output: &std::path::Path) -> Result<(), String> {
    let mut trace = csv::parse(text)?;
    select(&mut trace, names)?;
    let ext = output
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("svg") => std::fs::write(output, svg::render(&trace))
            .map_err(|e| format!("{}: {e}", output.display())),
        Some("png") => std::fs::write(output, png::render(&trace)?)
            .map_err(|e| format!("{}: {e}", output.display())),
        _ => Err(format!(
            "{}: the diagram is written as SVG or PNG; name the output `*.svg` or `*.png`",
            output.display()
        )),
    }
}

pub fn run(args: &PlotArgs) -> Outcome {
    let text = match std::fs::read_to_string(&args.trace) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("error: {}: {e}", args.trace.display());
            return Outcome::BadInput;
        }
    };
    match write_diagram(&text, &args.signals, &args.output) {
        Ok(()) => Outcome::Ok,
        Err(e) => {
            eprintln!("error: {e}");
            Outcome::BadInput
        }
    }
}

#[cfg(test)]
#[path = "robust_tests.rs"]
mod robust_tests;
