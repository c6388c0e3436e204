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
//! The rungs are generated as ST directly (`emit.rs`), not through the
//! graphical model of PLCopen LD: `ladder_to_st` is the one function to
//! replace when the ladder lands in that model.

mod emit;
mod instr;
mod layout;
mod parse;
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

/// Reads the `.slc` files of `map`: the generated ST (`None` when there are
/// none, or when they have errors) and their diagnostics.
pub fn translate(map: &SourceMap) -> (Option<String>, Vec<Diagnostic>) {
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

/// The data files and rungs as Structured Text (its diagnostics go to the
/// project's list).
fn ladder_to_st(project: &mut parse::Project) -> String {
    let mut layout = layout::Layout::new(project);
    let (body, mut diags) = {
        let mut e = emit::Emitter::new(project, &mut layout);
        let body = e.program();
        (body, std::mem::take(&mut e.diags))
    };
    project.diags.append(&mut diags);
    let mut s = String::from(
        "(* Generated from the SLC-500 ladder of the project (docs/allen-bradley.md). *)\n",
    );
    s.push_str("TYPE __SLC_MAJOR_FAULT : INT (0..0); END_TYPE\n\n");
    s.push_str(&layout.globals(project));
    s.push_str(include_str!("../../lib/slc.st"));
    s.push_str(&body);
    s
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
        if std::env::var("SLC_DUMP").is_ok() {
            println!("{}", st.as_deref().unwrap_or(""));
        }
        assert!(st.is_some_and(|s| s.contains("__SLC_TON(RUNG := __rc")));
    }
}
