//! `--trace`: one CSV row per scan in which a task ran.
//!
//! The header row is `time` then the variable paths as the user wrote them;
//! each row is the scan's PLC time then each variable's value, every cell in
//! the printed form of `--print` (`T#20ms`, `TRUE`, `3.5`, `'abc'`). Cells
//! holding a comma, a double quote or a line break are quoted as RFC 4180
//! says (`"a,b"`, `""` for a quote).

use crate::path::Place;
use crate::scan::ScanObserver;
use crate::value;
use std::io::Write;

/// What one column shows.
#[derive(Clone, Debug, PartialEq)]
pub enum Column {
    /// A variable, in the `--print` form.
    Value(Place),
    /// The names of the BOOL places that are TRUE, separated by spaces, `-`
    /// when none is (the active steps of a chart: `steps(Main)`).
    Flags(Vec<(String, Place)>),
    /// An SLC indexed or indirect address, found in each scan's image (`?`
    /// in a scan where it lies outside its data file).
    Located(crate::slc_place::Locator),
}

impl From<Place> for Column {
    fn from(p: Place) -> Column {
        Column::Value(p)
    }
}

impl Column {
    /// The cell of this column for `image`.
    pub fn cell(&self, image: &[u8]) -> String {
        match self {
            Column::Value(p) => value::format(image, p),
            Column::Located(l) => l.format(image),
            Column::Flags(flags) => {
                let on: Vec<&str> = flags
                    .iter()
                    .filter(|(_, p)| {
                        matches!(value::read(image, p), Some(automat_iec::Value::Bool(true)))
                    })
                    .map(|(n, _)| n.as_str())
                    .collect();
                if on.is_empty() {
                    "-".to_string()
                } else {
                    on.join(" ")
                }
            }
        }
    }
}

/// Writes the trace of the given columns to `out`.
pub struct Trace<W: Write> {
    columns: Vec<Column>,
    out: W,
    line: String,
}

/// One CSV cell.
pub fn csv_cell(text: &str) -> String {
    if text.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_string()
    }
}

impl<W: Write> Trace<W> {
    /// Writes the header row at once.
    pub fn new<C: Into<Column>>(columns: Vec<(String, C)>, mut out: W) -> Result<Trace<W>, String> {
        let mut header = vec!["time".to_string()];
        header.extend(columns.iter().map(|(name, _)| csv_cell(name)));
        writeln!(out, "{}", header.join(",")).map_err(|e| e.to_string())?;
        Ok(Trace {
            columns: columns.into_iter().map(|(_, c)| c.into()).collect(),
            out,
            line: String::new(),
        })
    }

    /// Flushes and gives the writer back.
    pub fn finish(mut self) -> Result<W, String> {
        self.out.flush().map_err(|e| e.to_string())?;
        Ok(self.out)
    }
}

impl<W: Write> ScanObserver for Trace<W> {
    fn after_scan(&mut self, plc_time_ns: i64, image: &[u8]) -> Result<(), String> {
        self.line.clear();
        self.line
            .push_str(&automat_iec::format::format_duration(plc_time_ns, false));
        for c in &self.columns {
            self.line.push(',');
            self.line.push_str(&csv_cell(&c.cell(image)));
        }
        self.line.push('\n');
        self.out
            .write_all(self.line.as_bytes())
            .map_err(|e| e.to_string())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::path::PlaceType;
    use automat_iec::Elementary as E;

    #[test]
    fn a_flags_column_names_the_true_flags() {
        let flag = |offset| Place {
            offset,
            bit: None,
            ty: PlaceType::Elementary(E::Bool),
            slc_bit: false,
        };
        let col = Column::Flags(vec![("S1".into(), flag(0)), ("S2".into(), flag(1))]);
        assert_eq!(col.cell(&[0, 0]), "-");
        assert_eq!(col.cell(&[1, 0]), "S1");
        assert_eq!(col.cell(&[1, 1]), "S1 S2");
        let mut t = Trace::new(vec![("steps(Main)".to_string(), col)], Vec::new())
            .unwrap_or_else(|e| panic!("{e}"));
        t.after_scan(0, &[0, 1]).unwrap_or_else(|e| panic!("{e}"));
        let out =
            String::from_utf8(t.finish().unwrap_or_else(|e| panic!("{e}"))).unwrap_or_default();
        assert_eq!(out, "time,steps(Main)\nT#0s,S2\n");
    }

    #[test]
    fn header_and_rows() {
        let cols = vec![
            (
                "x".to_string(),
                Place {
                    offset: 0,
                    bit: None,
                    ty: PlaceType::Elementary(E::Int),
                    slc_bit: false,
                },
            ),
            (
                "main.s".to_string(),
                Place {
                    offset: 2,
                    bit: None,
                    ty: PlaceType::String { cap: 4 },
                    slc_bit: false,
                },
            ),
            (
                "%QX0.1".to_string(),
                Place {
                    offset: 8,
                    bit: Some(1),
                    ty: PlaceType::Elementary(E::Bool),
                    slc_bit: false,
                },
            ),
        ];
        let mut t = Trace::new(cols, Vec::new()).unwrap();
        let mut img = [0u8; 9];
        img[0] = 5;
        img[2] = 3;
        img[4..7].copy_from_slice(b"a,\"");
        t.after_scan(0, &img).unwrap();
        img[0] = 6;
        img[8] = 2;
        t.after_scan(10_000_000, &img).unwrap();
        let text = String::from_utf8(t.finish().unwrap()).unwrap();
        assert_eq!(
            text,
            "time,x,main.s,%QX0.1\n\
             T#0s,5,\"'a,\"\"'\",FALSE\n\
             T#10ms,6,\"'a,\"\"'\",TRUE\n"
        );
    }

    #[test]
    fn cells() {
        assert_eq!(csv_cell("T#1s"), "T#1s");
        assert_eq!(csv_cell("a,b"), "\"a,b\"");
        assert_eq!(csv_cell("arr[1, 2]"), "\"arr[1, 2]\"");
        assert_eq!(csv_cell("x\ny"), "\"x\ny\"");
    }
}
