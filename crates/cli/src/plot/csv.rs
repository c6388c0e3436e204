//! Reading a trace CSV (the `--trace` and scenario format: a header row
//! `time,name,...`, then one row per scan with the PLC time as `T#…` and
//! each value in the `--print` form), and classifying each column.

/// How a column is drawn.
#[derive(Clone, Debug, PartialEq)]
pub enum Series {
    /// TRUE/FALSE: a step line.
    Bool(Vec<bool>),
    /// Numbers: a line with its range.
    Analog(Vec<f64>),
    /// Anything else (enumeration values such as active steps, strings):
    /// bands of constant value, each with its label.
    Bands(Vec<String>),
}

#[derive(Clone, Debug, PartialEq)]
pub struct Column {
    pub name: String,
    pub series: Series,
}

/// A whole trace: the time of each row (ns) and the columns.
#[derive(Clone, Debug, PartialEq)]
pub struct Trace {
    pub times: Vec<i64>,
    pub columns: Vec<Column>,
}

/// The most columns a trace may have (`time` included). `--trace` names
/// its columns one by one and a scenario trace has one per signal, quantity
/// and chart, so real traces have dozens; without a bound a header of a
/// million empty cells became a million columns (tens of bytes each, and
/// a diagram some 36 million pixels high).
pub const MAX_COLUMNS: usize = 10_000;

/// The cells of one CSV line (RFC 4180 quoting; no line breaks in cells).
/// Stops after `max` + 1 cells: the caller refuses the line then, and a
/// line of a million commas costs no million strings.
fn cells(line: &str, max: usize) -> Vec<String> {
    let mut out = Vec::new();
    let mut cur = String::new();
    let mut quoted = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', true) if chars.peek() == Some(&'"') => {
                chars.next();
                cur.push('"');
            }
            ('"', _) => quoted = !quoted,
            (',', false) => {
                out.push(std::mem::take(&mut cur));
                if out.len() > max {
                    return out;
                }
            }
            _ => cur.push(c),
        }
    }
    out.push(cur);
    out
}

fn number(cell: &str) -> Option<f64> {
    cell.parse::<f64>().ok().filter(|x| x.is_finite())
}

/// Parses a trace; errors name the line (counting blank lines, which are
/// skipped).
pub fn parse(text: &str) -> Result<Trace, String> {
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l))
        .filter(|(_, l)| !l.trim().is_empty());
    let (first, head) = lines.next().ok_or("the trace is empty")?;
    let header = cells(head, MAX_COLUMNS);
    if header.first().map(String::as_str) != Some("time") {
        return Err(format!("line {first}: the first column must be `time`"));
    }
    if header.len() > MAX_COLUMNS {
        return Err(format!(
            "line {first}: more than {MAX_COLUMNS} columns; a trace has at most {MAX_COLUMNS}"
        ));
    }
    let mut times: Vec<i64> = Vec::new();
    let mut raw: Vec<Vec<String>> = vec![Vec::new(); header.len().saturating_sub(1)];
    for (n, line) in lines {
        let row = cells(line, header.len());
        if row.len() != header.len() {
            let more = if row.len() > header.len() {
                "more than "
            } else {
                ""
            };
            return Err(format!(
                "line {n}: {more}{} cells, the header has {}",
                row.len().min(header.len()),
                header.len()
            ));
        }
        let mut it = row.into_iter();
        let t = it.next().unwrap_or_default();
        let t = automat_runtime::timearg::parse_duration(&t)
            .map_err(|e| format!("line {n}: time: {e}"))?;
        // The diagram's time axis runs from the first row to the last; a
        // trace whose time goes back was not written by automat.
        if times.last().is_some_and(|&last| t < last) {
            return Err(format!(
                "line {n}: time {} is before the previous row's",
                automat_iec::format::format_duration(t, false)
            ));
        }
        times.push(t);
        for (col, cell) in raw.iter_mut().zip(it) {
            col.push(cell);
        }
    }
    let columns = header
        .into_iter()
        .skip(1)
        .zip(raw)
        .map(|(name, vals)| {
            let series = if vals.iter().all(|v| v == "TRUE" || v == "FALSE") {
                Series::Bool(vals.iter().map(|v| v == "TRUE").collect())
            } else if vals.iter().all(|v| number(v).is_some()) {
                Series::Analog(vals.iter().filter_map(|v| number(v)).collect())
            } else {
                Series::Bands(vals)
            };
            Column { name, series }
        })
        .collect();
    Ok(Trace { times, columns })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_are_classified() {
        let t = parse("time,b,x,\"s,t\"\nT#0s,FALSE,1,A#One\nT#10ms,TRUE,2.5,\"A#Two\"\n").unwrap();
        assert_eq!(t.times, [0, 10_000_000]);
        assert_eq!(t.columns[0].series, Series::Bool(vec![false, true]));
        assert_eq!(t.columns[1].series, Series::Analog(vec![1.0, 2.5]));
        assert_eq!(t.columns[2].name, "s,t");
        assert_eq!(
            t.columns[2].series,
            Series::Bands(vec!["A#One".into(), "A#Two".into()])
        );
        assert!(parse("").is_err());
        assert!(parse("x,y\n").is_err());
        assert_eq!(
            parse("time,a\nT#0s\n").unwrap_err(),
            "line 2: 1 cells, the header has 2"
        );
        // Blank lines count for the line number.
        assert_eq!(
            parse("\ntime,a\n\nT#0s,1,2\n").unwrap_err(),
            "line 4: more than 2 cells, the header has 2"
        );
        assert_eq!(
            parse("time,a\nT#1s,1\nT#0s,1\n").unwrap_err(),
            "line 3: time T#0s is before the previous row's"
        );
    }
}
