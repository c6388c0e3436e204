//! The active steps of the program's Sequential Function Charts, for the
//! live view. The SFC desugaring (`crates/syntax/src/desugar/sfc`) makes
//! each step an instance, named as the step, of the hidden function block
//! `__SFC_STEP` (`__SFC_INITIAL_STEP` for the initial one) whose output `X`
//! is the step flag; so a chart is found in the symbol table as the step
//! instances of one POU instance (`Main`, `Main.fill`), and `Main.S1.X` is
//! an ordinary path for `--print` and `--trace`.

use crate::image;
use automat_iec::Elementary;
use automat_ir::{Program, SymbolType};
use automat_plant::Value;
use automat_runtime::{Place, PlaceType};

/// The type names of step instances (the hidden blocks of `sfc.st`).
const STEP_TYPES: [&str; 2] = ["__SFC_STEP", "__SFC_INITIAL_STEP"];

/// Instances nested deeper than this are not searched (a bound on any
/// symbol table, however it nests).
const MAX_DEPTH: usize = 16;

/// One step: its name and where its `X` flag is.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Step {
    pub name: String,
    pub x: Place,
}

/// The steps of the chart of one POU instance, in declaration order.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Chart {
    /// The instance's path as the symbol table spells it (`MAIN`, `MAIN.FILL`).
    pub owner: String,
    pub steps: Vec<Step>,
}

/// The trace column of a chart's active steps: `steps(OWNER)`.
pub const COLUMN_PREFIX: &str = "steps(";

impl Chart {
    /// The active steps as one text cell, `GS2 GS10`, or `-` when none
    /// is active (a timing diagram draws it as a band).
    pub fn active_text(&self, image: &[u8]) -> String {
        let active = self.active(image);
        if active.is_empty() {
            "-".to_string()
        } else {
            active.join(" ")
        }
    }

    /// The column name of this chart's active steps.
    pub fn column(&self) -> String {
        format!("{COLUMN_PREFIX}{})", self.owner)
    }

    /// The trace column of this chart's active steps.
    pub fn trace_column(&self) -> automat_runtime::trace::Column {
        automat_runtime::trace::Column::Flags(
            self.steps
                .iter()
                .map(|s| (s.name.clone(), s.x.clone()))
                .collect(),
        )
    }

    /// The names of the steps active in `image`.
    pub fn active<'a>(&'a self, image: &[u8]) -> Vec<&'a str> {
        self.steps
            .iter()
            .filter(|s| image::read(image, &s.x) == Some(Value::Bool(true)))
            .map(|s| s.name.as_str())
            .collect()
    }
}

fn is_step(ty: &SymbolType) -> bool {
    matches!(ty, SymbolType::Struct { name, .. }
        if STEP_TYPES.iter().any(|t| t.eq_ignore_ascii_case(name)))
}

/// The place of a step instance's `X` at `base`.
fn flag(ty: &SymbolType, base: u32) -> Option<Place> {
    let SymbolType::Struct { fields, .. } = ty else {
        return None;
    };
    let x = fields.iter().find(|f| f.name.eq_ignore_ascii_case("X"))?;
    Some(Place {
        offset: base.checked_add(x.offset)?,
        bit: x.bit,
        ty: PlaceType::Elementary(Elementary::Bool),
        slc_bit: false,
    })
}

fn walk(owner: &str, ty: &SymbolType, base: u32, depth: usize, out: &mut Vec<Chart>) {
    let SymbolType::Struct { fields, .. } = ty else {
        return;
    };
    if depth > MAX_DEPTH {
        return;
    }
    let mut steps = Vec::new();
    for f in fields {
        let Some(at) = base.checked_add(f.offset) else {
            continue;
        };
        if is_step(&f.ty) {
            if let Some(x) = flag(&f.ty, at) {
                steps.push(Step {
                    name: f.name.clone(),
                    x,
                });
            }
        } else if matches!(f.ty, SymbolType::Struct { .. }) {
            walk(&format!("{owner}.{}", f.name), &f.ty, at, depth + 1, out);
        }
    }
    if !steps.is_empty() {
        out.push(Chart {
            owner: owner.to_string(),
            steps,
        });
    }
}

/// Every chart of `program`, by owner path: one per POU instance with
/// steps (program instances and the function-block instances inside them;
/// arrays of instances are not searched), each with its steps in
/// declaration (memory) order. Names are spelled as declared (the symbol
/// table's `spelling`); look owners up case-insensitively.
pub fn charts(program: &Program) -> Vec<Chart> {
    let mut out: Vec<Chart> = Vec::new();
    for e in program.symbols.entries() {
        // The table has one entry per variable of a program instance
        // (`MAIN.S1`) or global; members of FB instances are its fields.
        match e.spelling.rsplit_once('.') {
            Some((owner, name)) if is_step(&e.ty) => {
                if let Some(x) = flag(&e.ty, e.offset) {
                    let step = Step {
                        name: name.to_string(),
                        x,
                    };
                    match out.iter_mut().find(|c| c.owner.eq_ignore_ascii_case(owner)) {
                        Some(c) => c.steps.push(step),
                        None => out.push(Chart {
                            owner: owner.to_string(),
                            steps: vec![step],
                        }),
                    }
                }
            }
            _ => walk(&e.spelling, &e.ty, e.offset, 0, &mut out),
        }
    }
    for c in &mut out {
        c.steps.sort_by_key(|s| s.x.offset);
    }
    out.sort_by(|a, b| a.owner.cmp(&b.owner));
    out
}

#[cfg(test)]
#[path = "steps_tests.rs"]
mod tests;

/// `steps(OWNER)`, the pseudo-variable of `--trace` (and of scenario
/// traces) that holds the active steps of the chart of instance `OWNER`:
/// `None` when `text` is not of that form, the chart or an error naming
/// the instances that have one.
pub fn column(program: &Program, text: &str) -> Option<Result<Chart, String>> {
    let t = text.trim();
    let inner = t
        .get(..COLUMN_PREFIX.len())
        .filter(|p| p.eq_ignore_ascii_case(COLUMN_PREFIX))
        .and_then(|_| t.get(COLUMN_PREFIX.len()..))
        .and_then(|r| r.strip_suffix(')'))?;
    let all = charts(program);
    let found = all
        .iter()
        .find(|c| c.owner.eq_ignore_ascii_case(inner.trim()))
        .cloned();
    Some(found.ok_or_else(|| {
        let owners: Vec<&str> = all.iter().map(|c| c.owner.as_str()).collect();
        if owners.is_empty() {
            format!("`{}` has no SFC chart: the program has none", inner.trim())
        } else {
            format!(
                "`{}` has no SFC chart (charts: {})",
                inner.trim(),
                owners.join(", ")
            )
        }
    }))
}
