//! The SFC charts of a project as the compiler reads them, for tools that
//! draw them live (the web HMI through `GET /api/v1/charts`).
//!
//! The model comes from the parser's own chart tree (`ast::sfc::Chart`, kept
//! in `Pou::lang`) after the dialect front ends ran, so textual SFC, the
//! ISaGRAF and PL7 dialects and PLCopen graphical SFC give the same model.
//! Condition and time texts are the source text as written (whitespace
//! folded), so PL7 `%X1` stays `%X1`. Nothing here runs the program: the
//! activity of a step is read by the client as `INSTANCE.STEP.X`/`.T`.

use automat_base::{Interner, SourceMap, Span};
use automat_syntax::ast::sfc::{Chart as AstChart, Condition, Step as AstStep};
use automat_syntax::ast::{Item, Lang, PouKind};
use serde::Serialize;

/// The chart of one POU.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PouChart {
    /// The POU as written (`Crane`).
    pub pou: String,
    /// `PROGRAM`, `FUNCTION_BLOCK`.
    pub kind: &'static str,
    /// The file and line of the POU.
    pub file: String,
    pub line: u32,
    pub chart: Chart,
}

#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Chart {
    pub steps: Vec<Step>,
    pub transitions: Vec<Transition>,
    /// The ACTIONs declared in the chart, in declaration order.
    pub actions: Vec<String>,
}

#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Step {
    pub name: String,
    pub initial: bool,
    pub line: u32,
    /// Action associations in the order written.
    pub actions: Vec<Assoc>,
    /// A macro-step's body (graphical charts).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub body: Option<Box<MacroBody>>,
}

#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MacroBody {
    /// The body step whose activity lets a transition leave the macro-step.
    pub exit: String,
    pub chart: Chart,
}

#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Assoc {
    /// An ACTION of the chart or a BOOL variable.
    pub name: String,
    /// `N`, `S`, `R`, `P`, `P0`, `P1`, `L`, `D`, `SD`, `DS`, `SL`.
    pub qualifier: &'static str,
    /// The duration of a timed qualifier as written (`T#3s`).
    pub time: Option<String>,
    /// Whether `name` is a BOOL variable rather than an ACTION.
    pub variable: bool,
    pub indicators: Vec<String>,
}

#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Transition {
    pub name: Option<String>,
    pub priority: Option<u32>,
    pub from: Vec<String>,
    pub to: Vec<String>,
    /// Drawn as a jump to a named step (graphical charts).
    pub jump: bool,
    /// The condition as written (ST expression or IL instructions).
    pub condition: String,
    pub line: u32,
}

/// Whitespace folded to single spaces.
fn fold(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

struct Reader<'a> {
    map: &'a SourceMap,
    interner: &'a Interner,
}

impl Reader<'_> {
    fn name(&self, sym: automat_base::Symbol) -> String {
        self.interner.name(sym).to_string()
    }
    fn text(&self, span: Span) -> String {
        fold(self.map.text(span))
    }
    fn line(&self, span: Span) -> u32 {
        if span.file.0 as usize >= self.map.len() {
            return 0;
        }
        self.map.get(span.file).line_col(span.start).0
    }

    fn condition(&self, c: &Condition) -> String {
        match c {
            Condition::St(e) => self.text(e.span),
            Condition::Il { il, .. } => il
                .instrs
                .iter()
                .map(|i| self.text(i.span))
                .collect::<Vec<_>>()
                .join("; "),
            Condition::Missing => String::new(),
        }
    }

    fn step(&self, s: &AstStep, actions: &[String]) -> Step {
        let assocs = s
            .assocs
            .iter()
            .map(|a| {
                let name = self.name(a.name.sym);
                Assoc {
                    variable: !actions.iter().any(|x| x.eq_ignore_ascii_case(&name)),
                    name,
                    qualifier: a.qualifier.name(),
                    time: a.time.as_ref().map(|t| self.text(t.span)),
                    indicators: a.indicators.iter().map(|i| self.name(i.sym)).collect(),
                }
            })
            .collect();
        Step {
            name: self.name(s.name.sym),
            initial: s.initial,
            line: self.line(s.span),
            actions: assocs,
            body: s.macro_body.as_ref().map(|b| {
                Box::new(MacroBody {
                    exit: self.name(b.exit.sym),
                    chart: self.chart(&b.chart, actions),
                })
            }),
        }
    }

    /// `outer` are the actions of the enclosing charts: a macro body's
    /// associations may name them (one namespace per chart).
    fn chart(&self, c: &AstChart, outer: &[String]) -> Chart {
        let mut actions: Vec<String> = outer.to_vec();
        actions.extend(c.actions.iter().map(|a| self.name(a.name.sym)));
        Chart {
            steps: c.steps.iter().map(|s| self.step(s, &actions)).collect(),
            transitions: c
                .transitions
                .iter()
                .map(|t| Transition {
                    name: t.name.map(|n| self.name(n.sym)),
                    priority: t.priority,
                    from: t.from.iter().map(|f| self.name(f.sym)).collect(),
                    to: t.to.iter().map(|f| self.name(f.sym)).collect(),
                    jump: t.jump,
                    condition: self.condition(&t.cond),
                    line: self.line(t.span),
                })
                .collect(),
            actions: c.actions.iter().map(|a| self.name(a.name.sym)).collect(),
        }
    }
}

/// Every chart of the sources in `map` (read with the `dialects` of the
/// project), in file and source order. Sources with errors give the charts
/// the parser could read; nothing here fails.
pub fn of_sources(mut map: SourceMap, libraries: &[String]) -> Vec<PouChart> {
    let dialects = automat_dialect::parse_names(libraries).unwrap_or_default();
    let user_files = map.len();
    automat_dialect::add_libraries(&mut map, &dialects);
    let mut interner = Interner::new();
    let units = automat_dialect::parse_as_written(&map, &mut interner, &dialects);
    let r = Reader {
        map: &map,
        interner: &interner,
    };
    let mut out = Vec::new();
    for unit in units.iter().filter(|u| (u.file.0 as usize) < user_files) {
        for item in &unit.items {
            let Item::Pou(p) = item else { continue };
            let Lang::Sfc(chart) = &p.lang else { continue };
            out.push(PouChart {
                pou: r.name(p.name.sym),
                kind: match p.kind {
                    PouKind::Program => "PROGRAM",
                    PouKind::FunctionBlock => "FUNCTION_BLOCK",
                    PouKind::Function => "FUNCTION",
                },
                file: map.get(unit.file).name.clone(),
                line: r.line(p.span),
                chart: r.chart(chart, &[]),
            });
        }
    }
    out
}

/// [`of_sources`] on files.
pub fn of_files(files: &[std::path::PathBuf], libraries: &[String]) -> Vec<PouChart> {
    match crate::build::read_sources(files) {
        Ok(map) => of_sources(map, libraries),
        Err(_) => Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_textual_chart_reads_as_written() {
        let mut map = SourceMap::new();
        map.add(
            "t.st",
            "PROGRAM P\nVAR a, b : BOOL; END_VAR\n\
             INITIAL_STEP S1: A1(N); END_STEP\n\
             STEP S2: b(S); A1(L, T#2s); END_STEP\n\
             STEP S3: END_STEP\n\
             TRANSITION FROM S1 TO (S2, S3) := a   AND\n NOT b; END_TRANSITION\n\
             TRANSITION (PRIORITY := 2) FROM (S2, S3) TO S1 := S2.T >= T#1s; END_TRANSITION\n\
             ACTION A1: a := NOT a; END_ACTION\nEND_PROGRAM\n",
        );
        let charts = of_sources(map, &[]);
        assert_eq!(charts.len(), 1);
        let c = &charts[0];
        assert_eq!((c.pou.as_str(), c.kind, c.line), ("P", "PROGRAM", 1));
        let steps: Vec<(&str, bool, u32)> = c
            .chart
            .steps
            .iter()
            .map(|s| (s.name.as_str(), s.initial, s.line))
            .collect();
        assert_eq!(steps, [("S1", true, 3), ("S2", false, 4), ("S3", false, 5)]);
        let s2 = &c.chart.steps[1].actions;
        assert_eq!(
            (s2[0].name.as_str(), s2[0].qualifier, s2[0].variable),
            ("b", "S", true)
        );
        assert_eq!(
            (s2[1].qualifier, s2[1].time.as_deref(), s2[1].variable),
            ("L", Some("T#2s"), false)
        );
        let t = &c.chart.transitions;
        assert_eq!(t[0].from, ["S1"]);
        assert_eq!(t[0].to, ["S2", "S3"]);
        assert_eq!(t[0].condition, "a AND NOT b");
        assert_eq!((t[0].line, t[1].line), (6, 8));
        assert_eq!(t[1].priority, Some(2));
        assert_eq!(t[1].condition, "S2.T >= T#1s");
        assert_eq!(c.chart.actions, ["A1"]);
    }

    #[test]
    fn an_isagraf_chart_reads_through_its_dialect() {
        let mut map = SourceMap::new();
        map.add(
            "c.st",
            "PROGRAM P\nVAR m, l : BOOL; END_VAR\n\
             INITIAL_STEP GS1:\n    m;\nEND_STEP\nSTEP GS2: END_STEP\n\
             TRANSITION FROM GS1 TO GS2 := l; END_TRANSITION\n\
             TRANSITION FROM GS2 TO GS1 := GS2.t > t#1s; END_TRANSITION\nEND_PROGRAM\n",
        );
        let charts = of_sources(map, &["isagraf".to_string()]);
        assert_eq!(charts.len(), 1, "the library's POUs are not charts here");
        let a = &charts[0].chart.steps[0].actions[0];
        assert_eq!((a.name.as_str(), a.qualifier, a.variable), ("m", "N", true));
        assert_eq!(charts[0].chart.transitions[1].condition, "GS2.t > t#1s");
    }
}
