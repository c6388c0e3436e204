//! Allen-Bradley SLC-500 ladder (`*.slc` files, docs/allen-bradley.md):
//! program files of rungs, the symbol table and the data-file table, turned
//! into one generated ST file (`<slc>/ladder.st`) that both engines run.
//!
//! The data files are globals at fixed direct addresses, one array of
//! 16-bit words per file as `automat_base::slc` maps the addresses (`I1`
//! at `%IW0`, `O0` at `%QW0`, the others in `%MW`/`%MD` in file order), so
//! the runtime's path resolver reads `N7:15` or `T4:0/DN` as the word or
//! bit it names; each symbol is a global at its address's place. The rungs
//! are checked here with their own diagnostics (E230–E239) at
//! file:line:col naming the rung and the instruction; the generated ST
//! should never fail to check (a failure there is ours).
//!
//! One PROGRAM `SLC` runs per scan (the runtime does the input and output
//! scans around it): first pass S:1/15, the PLC time elapsed since the last
//! scan for the timers, program file 2 (subroutines inlined at each JSR),
//! then the overflow trap S:5/0 as a major fault.
//!
//! A rung's contacts, coils and branches go through the graphical model of
//! PLCopen LD (`network.rs`: a `graphic::Network` lowered by
//! `graphic::lower`, with the same hidden `__ld_n<id>` power-flow BOOLs);
//! the other instructions are the ST of `emit.rs` between the network's
//! segments. `ladder_to_st` is the one place the ladder becomes ST.

mod dynamic;
mod emit;
mod instr;
mod layout;
mod network;
mod parse;
mod pid;
mod sheet;

use automat_base::{Code, Diagnostic, SourceMap, Span};

/// The generated file's name in diagnostics.
pub const GENERATED: &str = "<slc>/ladder.st";

/// Is this source file an SLC-500 ladder file (read by this module, not
/// parsed as ST)?
pub fn is_slc_file(name: &str) -> bool {
    std::path::Path::new(name)
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("slc"))
}

/// The generated ST and what a fault means at byte ranges of it.
pub type Generated = (String, Vec<(std::ops::Range<u32>, String)>);

/// Reads the `.slc` files of `map`: the generated ST (`None` when there are
/// none, or when they have errors) and their diagnostics.
pub fn translate(map: &SourceMap) -> (Option<Generated>, Vec<Diagnostic>) {
    let mut project = parse::Project::default();
    let slc: Vec<_> = map.files().filter(|(_, f)| is_slc_file(&f.name)).collect();
    if slc.is_empty() {
        return (None, Vec::new());
    }
    for (id, f) in &slc {
        parse::Reader::new(&mut project, *id).tables(&f.text);
    }
    for (id, f) in &slc {
        parse::Reader::new(&mut project, *id).rungs(&f.text);
    }
    if !project.files.contains_key(&2) {
        let at = slc.first().map(|(id, _)| *id);
        if let Some(id) = at {
            project.diags.push(Diagnostic::error(
                Code::E237,
                Span::new(id, 0, 0),
                "the project has no program file 2 (`LAD 2`, or rungs before any `LAD` line)",
            ));
        }
    }
    let text = ladder_to_st(&mut project);
    let mut diags = std::mem::take(&mut project.diags);
    diags.sort_by_key(|d| (d.span.file, d.span.start));
    if diags.iter().any(|d| d.is_error()) {
        return (None, diags);
    }
    (Some(text), diags)
}

/// The drawing sheet of the program file `pou` names (`LAD2`, `LAD 2`,
/// `2`, or the name its `LAD` line gives) in the `.slc` files of `map`.
pub fn sheet(map: &SourceMap, pou: &str) -> Option<automat_plcopen::sheet::Sheet> {
    let mut project = parse::Project::default();
    let slc: Vec<_> = map.files().filter(|(_, f)| is_slc_file(&f.name)).collect();
    for (id, f) in &slc {
        parse::Reader::new(&mut project, *id).tables(&f.text);
    }
    for (id, f) in &slc {
        parse::Reader::new(&mut project, *id).rungs(&f.text);
    }
    let want = pou.trim().to_ascii_uppercase();
    let digits = want.trim_start_matches("LAD").trim();
    let n = digits.parse::<u32>().ok().or_else(|| {
        project
            .files
            .values()
            .find(|f| !f.name.is_empty() && f.name.eq_ignore_ascii_case(pou.trim()))
            .map(|f| f.number)
    })?;
    sheet::sheet(&project, n)
}

/// What the HMI shows live on one node of an SLC drawing: the power flow
/// of a contact or coil (`__ld_n<id>` of the program `SLC`), the bit it
/// names (`B3:0/1`), a timer's or counter's `ACC` as a pin (name, path).
#[derive(Clone, Debug, PartialEq)]
pub struct Live {
    pub node: u32,
    pub power: Option<String>,
    pub value: Option<String>,
    pub pins: Vec<(String, String)>,
}

/// A program file drawn (`sheet`) with its live values, and the `.slc`
/// file holding it.
pub struct LiveSheet {
    pub file: String,
    pub sheet: automat_plcopen::sheet::Sheet,
    pub live: Vec<Live>,
}

/// Every program file of the `.slc` files of `map` as the HMI draws it
/// (none when the ladder has errors: it does not run then).
pub fn live_sheets(map: &SourceMap) -> Vec<LiveSheet> {
    let mut project = parse::Project::default();
    let slc: Vec<_> = map.files().filter(|(_, f)| is_slc_file(&f.name)).collect();
    for (id, f) in &slc {
        parse::Reader::new(&mut project, *id).tables(&f.text);
    }
    for (id, f) in &slc {
        parse::Reader::new(&mut project, *id).rungs(&f.text);
    }
    if slc.is_empty() || project.diags.iter().any(|d| d.is_error()) {
        return Vec::new();
    }
    // The element ids exactly as `ladder_to_st` numbers them.
    let mut layout = layout::Layout::new(&mut project);
    let elements = {
        let mut e = emit::Emitter::new(&project, &mut layout);
        e.program();
        std::mem::take(&mut e.elements)
    };
    let mut out = Vec::new();
    for (&n, f) in &project.files {
        let Some((sheet, drawn)) = sheet::sheet_drawn(&project, n) else {
            continue;
        };
        let file = f
            .rungs
            .first()
            .map(|r| map.get(r.span.file).name.clone())
            .unwrap_or_default();
        let live = drawn
            .iter()
            .map(|(node, i)| {
                let a = match i.ops.first() {
                    Some(parse::Operand::Addr(a)) => Some(*a),
                    _ => None,
                };
                let text = a.map(sheet::address_text);
                let bit = matches!(i.mn, "XIC" | "XIO" | "OTE" | "OTL" | "OTU");
                let acc = matches!(i.mn, "TON" | "TOF" | "RTO" | "CTU" | "CTD");
                Live {
                    node: *node,
                    power: elements
                        .get(&(i.span.file, i.span.start))
                        .map(|id| format!("__ld_n{id}")),
                    value: text.clone().filter(|_| bit),
                    pins: text
                        .filter(|_| acc)
                        .map(|t| vec![("ACC".to_string(), format!("{t}.ACC"))])
                        .unwrap_or_default(),
                }
            })
            .collect();
        out.push(LiveSheet { file, sheet, live });
    }
    out
}

/// The data files and rungs as Structured Text (its diagnostics go to the
/// project's list), with what a fault means at the byte ranges of the
/// text that raise the SLC's major faults.
fn ladder_to_st(project: &mut parse::Project) -> Generated {
    let mut layout = layout::Layout::new(project);
    let (body, traps, faults, mut diags) = {
        let mut e = emit::Emitter::new(project, &mut layout);
        let body = e.program();
        (
            body,
            std::mem::take(&mut e.traps),
            std::mem::take(&mut e.faults),
            std::mem::take(&mut e.diags),
        )
    };
    project.diags.append(&mut diags);
    let mut s = String::from(
        "(* Generated from the SLC-500 ladder of the project (docs/allen-bradley.md). *)\n",
    );
    s.push_str("TYPE __SLC_MAJOR_FAULT : INT (0..0); END_TYPE\n\n");
    s.push_str(&layout.globals(project));
    s.push_str(include_str!("../../lib/slc.st"));
    let at = s.len();
    s.push_str(&body);
    let mut meanings = check_meanings(&s, at, &faults);
    meanings.extend(trap_check(&mut s, &traps));
    s.push_str("END_PROGRAM\n");
    (s, meanings)
}

/// What the run-time checks of indexed and indirect addresses mean: each
/// check line (from `at`, found by its marker) and its fault message.
fn check_meanings(s: &str, at: usize, faults: &[String]) -> Vec<(std::ops::Range<u32>, String)> {
    let mut out = Vec::new();
    let mut start = at;
    for line in s[at..].split_inclusive('\n') {
        let end = start + line.len();
        if let Some(k) = line
            .trim_end()
            .strip_suffix(" *)")
            .and_then(|l| l.rsplit_once("(* slc check "))
            .and_then(|(_, k)| k.parse::<usize>().ok())
        {
            if let Some(m) = faults.get(k) {
                out.push((start as u32..end as u32, m.clone()));
            }
        }
        start = end;
    }
    out
}

/// The end of the scan: the overflow trap S:5/0 left set is a major fault
/// (the SLC stops). The runtime's fault is a subrange check on
/// `__slc_fault`, one assignment line per math instruction that can set
/// the trap, so each line's fault can say which instruction set it last
/// (`SourceMap::add_fault_meaning`).
fn trap_check(s: &mut String, traps: &[String]) -> Vec<(std::ops::Range<u32>, String)> {
    use std::fmt::Write as _;
    const WHAT: &str = "SLC major fault: math overflow trap S:5/0 set at the end of the scan";
    let mut meanings = Vec::new();
    s.push_str("    IF S2[5].0 THEN\n        CASE __slc_trap OF\n");
    let mut line = |s: &mut String, head: String, meaning: String| {
        let start = s.len() as u32;
        // Not a constant 1: the checker would refuse it (E038).
        let _ = writeln!(s, "        {head} __slc_fault := BOOL_TO_INT(S2[5].0);");
        meanings.push((start..s.len() as u32, meaning));
    };
    for (k, here) in traps.iter().enumerate() {
        line(s, format!("{}:", k + 1), format!("{WHAT} ({here})"));
    }
    // No instruction overflowed in this scan: the program set S:5/0
    // itself (`OTL S:5/0`). (One that clears S:5/0 after an overflow and
    // sets it again is named after that overflow.)
    line(s, "ELSE".into(), WHAT.to_string());
    s.push_str("        END_CASE;\n    END_IF;\n");
    meanings
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dump_generated() {
        let mut map = SourceMap::new();
        let text = std::env::var("SLC_DUMP").unwrap_or_else(|_| "TON T4:0 0.01 300 0\n".into());
        map.add("t.slc", text);
        let (st, diags) = translate(&map);
        assert!(diags.is_empty(), "{diags:?}");
        let st = st.map(|g| g.0);
        if std::env::var("SLC_DUMP").is_ok() {
            println!("{}", st.as_deref().unwrap_or(""));
        }
        assert!(st.is_some_and(|s| s.contains("__SLC_TON(RUNG := __rc")));
    }

    /// A timer inside a branch has the power frame of the coil taking its
    /// leg's power (`__ld_n4`); one on a plain rung likewise (`__ld_n11`).
    #[test]
    fn a_block_in_a_branch_has_a_power_frame() {
        let mut map = SourceMap::new();
        map.add(
            "t.slc",
            "BST XIC I:1/1 TON T4:1 0.01 5 0 NXB XIC I:1/2 BND OTU B3:0/3\nTON T4:2 0.01 5 0\n",
        );
        let sheets = live_sheets(&map);
        let power = |text: &str| -> Option<Option<String>> {
            let s = sheets.first()?;
            let node = s.sheet.nodes.iter().find(|n| n.text == text)?;
            s.live
                .iter()
                .find(|l| l.node == node.id)
                .map(|l| l.power.clone())
        };
        assert_eq!(power("TON T4:1 0.01 5 0"), Some(Some("__ld_n4".into())));
        assert_eq!(power("TON T4:2 0.01 5 0"), Some(Some("__ld_n11".into())));
    }

    /// A contact whose bit is indirect is no variable of the model: it runs
    /// as ST on the power into it, which is its frame, and the coil after
    /// it still has its own.
    #[test]
    fn an_indirect_bit_has_a_power_frame() {
        let mut map = SourceMap::new();
        map.add("t.slc", "XIC I:1/0 XIC B3:0/[N7:0] OTE O:2/0\n");
        let sheets = live_sheets(&map);
        let power = |text: &str| -> Option<Option<String>> {
            let s = sheets.first()?;
            let node = s.sheet.nodes.iter().find(|n| n.text.starts_with(text))?;
            s.live
                .iter()
                .find(|l| l.node == node.id)
                .map(|l| l.power.clone())
        };
        assert!(matches!(power("B3:0/[N7:0]"), Some(Some(_))));
        assert!(matches!(power("O:2/0"), Some(Some(_))));
    }

    /// The drawing's notes: above a contact its operand's description,
    /// above a box each described operand's symbol and description.
    #[test]
    fn descriptions_are_noted_above_their_operands() {
        let mut map = SourceMap::new();
        map.add(
            "t.slc",
            "SYM T4:0 Dwell \"the dwell\"\nSYM B3/0 Go \"go\"\nXIC Go TON Dwell 0.01 300 0\n",
        );
        let texts: Vec<(automat_plcopen::sheet::NodeKind, String)> = sheet(&map, "2")
            .map(|s| s.nodes.into_iter().map(|n| (n.kind, n.text)).collect())
            .unwrap_or_default();
        use automat_plcopen::sheet::NodeKind::*;
        assert_eq!(
            texts,
            [
                (Comment, "rung 0".to_string()),
                (LeftRail, String::new()),
                (Comment, "go".into()),
                (Contact, "Go B3:0/0".into()),
                (Comment, "Dwell: the dwell".into()),
                (Block, "TON Dwell T4:0 0.01 300 0".into()),
            ]
        );
    }

    /// Contacts, coils and branches go through the graphical model: the
    /// power flow in `__ld_n<id>` BOOLs, ids unique in the program; a timer,
    /// on the rung or inside a branch, is a coil on its power (`__ld_n7`,
    /// `__ld_n14`: its frame), its ST on that power, and a contact on the
    /// condition after it (`__bout0`, `__bout1`).
    #[test]
    fn rungs_lower_through_the_graphical_model() {
        let mut map = SourceMap::new();
        map.add(
            "t.slc",
            "XIC I:1/0 BST XIC B3:0/1 NXB XIO B3:0/2 BND OTE O:2/0 TON T4:0 0.01 30 0 OTL B3:0/3\n\
             BST XIC I:1/1 TON T4:1 0.01 5 0 NXB XIC I:1/2 BND OTU B3:0/3\n",
        );
        let (st, diags) = translate(&map);
        assert!(diags.is_empty(), "{diags:?}");
        let st = st.map(|g| g.0).unwrap_or_default();
        let rung0 = [
            "    __rc := __mcr;",
            "    __ld_n2 := TRUE AND (__rc);",
            "    __ld_n3 := __ld_n2 AND (I1[8].0);",
            "    __ld_n4 := __ld_n3 AND (B3[0].1);",
            "    __ld_n5 := __ld_n3 AND NOT (B3[0].2);",
            "    __ld_n6 := (__ld_n4 OR __ld_n5);",
            "    O0[16].0 := __ld_n6;",
            "    __ld_n7 := __ld_n6;",
            "    __bin0 := __ld_n7;",
            "    __rc := __bin0;",
            "    __x := __SLC_TON(RUNG := __rc, BASE := 10, D := __d, CTL := T4[0], PRE := T4[1], ACC := T4[2], REM := __rem[0]);",
            "    __bout0 := __rc;",
            "    __ld_n8 := __ld_n7 AND (__bout0);",
            "    __ld_n9 := __ld_n8;",
            "    IF __ld_n9 THEN B3[0].3 := TRUE; END_IF;",
            "    __ld_n10 := __ld_n9;",
            "    __rc := __ld_n10;",
            "    (* LAD 2 rung 1 *)",
            "    __rc := __mcr;",
            "    __ld_n12 := TRUE AND (__rc);",
            "    __ld_n13 := __ld_n12 AND (I1[8].1);",
            "    __ld_n14 := __ld_n13;",
            "    __bin1 := __ld_n14;",
            "    __rc := __bin1;",
            "    __x := __SLC_TON(RUNG := __rc, BASE := 10, D := __d, CTL := T4[3], PRE := T4[4], ACC := T4[5], REM := __rem[1]);",
            "    __bout1 := __rc;",
            "    __ld_n15 := __ld_n14 AND (__bout1);",
            "    __ld_n16 := __ld_n12 AND (I1[8].2);",
            "    __ld_n17 := (__ld_n15 OR __ld_n16);",
            "    IF __ld_n17 THEN B3[0].3 := FALSE; END_IF;",
        ]
        .join("\n");
        assert!(st.contains(&rung0), "{st}");
        assert!(st.contains("    __ld_n10 : BOOL;\n"), "{st}");
    }
}
