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

/// The cells of one CSV line (RFC 4180 quoting; no line breaks in cells).
fn cells(line: &str) -> Vec<String> {
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
            (',', false) => out.push(std::mem::take(&mut cur)),
            _ => cur.push(c),
        }
    }
    out.push(cur);
    out
}

fn number(cell: &str) -> Option<f64> {
    cell.parse::<f64>().ok().filter(|x| x.is_finite())
}

/// Parses a trace; errors name the line.
pub fn parse(text: &str) -> Result<Trace, String> {
    let mut lines = text.lines().filter(|l| !l.trim().is_empty());
    let header = cells(lines.next().ok_or("the trace is empty")?);
    if header.first().map(String::as_str) != Some("time") {
        return Err("line 1: the first column must be `time`".into());
    }
    let mut times = Vec::new();
    let mut raw: Vec<Vec<String>> = vec![Vec::new(); header.len().saturating_sub(1)];
    for (i, line) in lines.enumerate() {
        let row = cells(line);
        if row.len() != header.len() {
            return Err(format!(
                "line {}: {} cells, the header has {}",
                i + 2,
                row.len(),
                header.len()
            ));
        }
        let mut it = row.into_iter();
        let t = it.next().unwrap_or_default();
        times.push(
            automat_runtime::timearg::parse_duration(&t)
                .map_err(|e| format!("line {}: time: {e}", i + 2))?,
        );
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
    }
}
