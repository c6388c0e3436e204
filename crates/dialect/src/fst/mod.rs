//! Festo FST statement list (STL), `libraries = ["fst"]`: programs
//! `P<n>.stl` (n = 0–63), CMP modules `B<n>.stl` (n = 0–99) and the
//! allocation list `allocation.txt`, turned into one generated ST file
//! (`<fst>/programs.st`) over hidden globals for the operands, so both
//! engines run it unchanged. The STL files are checked here, with their
//! own diagnostics at file:line:col (E180–E189); the generated ST should
//! never fail to check (a failure there is ours).
//!
//! One PROGRAM `FST` runs per scan: it counts the running timers down by
//! the 0.01 s ticks of PLC time elapsed since the last scan, then runs
//! every active program once in number order. A STEP program is a CASE
//! over its step (`Pn.step`, an enumeration of its step names, `S20` for a
//! numbered step), a parallel program its sentences, an executive program
//! its list. The semantics are in `docs/festo-stl.md`.

mod lex;
mod operand;
mod parse;

use automat_base::{Code, Diagnostic, FileId, SourceMap, Span};
use operand::Operand;
use parse::{Body, Instr, Parser, Sentence};
use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write;

/// The generated file's name in diagnostics.
pub const GENERATED: &str = "<fst>/programs.st";

/// What a project file is to FST.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Role {
    Program(u32),
    Module(u32),
    Allocation,
}

/// Is this source file an FST file (read by this module, not parsed as ST)?
pub fn is_fst_file(name: &str) -> bool {
    let base = base_name(name).to_ascii_lowercase();
    base.ends_with(".stl") || base == "allocation.txt"
}

fn base_name(name: &str) -> &str {
    name.rsplit(['/', '\\']).next().unwrap_or(name)
}

fn role(name: &str) -> Option<Result<Role, String>> {
    let base = base_name(name);
    if base.eq_ignore_ascii_case("allocation.txt") {
        return Some(Ok(Role::Allocation));
    }
    let stem = base
        .strip_suffix(".stl")
        .or_else(|| base.strip_suffix(".STL"))?;
    let num = |s: &str| {
        s.parse::<u32>()
            .ok()
            .filter(|_| s.bytes().all(|b| b.is_ascii_digit()))
    };
    let up = stem.to_ascii_uppercase();
    Some(match (up.strip_prefix('P').and_then(num), up.strip_prefix('B').and_then(num)) {
        (Some(n), _) if n <= operand::MAX_PROGRAM => Ok(Role::Program(n)),
        (_, Some(n)) if n <= 99 => Ok(Role::Module(n)),
        _ => Err(format!(
            "`{base}`: an STL file is named P<n>.stl (program, n = 0 to 63) or B<n>.stl (CMP module, n = 0 to 99)"
        )),
    })
}

/// A symbol of the allocation list: its operand and where it was defined.
struct Symbols {
    map: BTreeMap<String, Operand>,
    /// (symbol as written, operand) in file order.
    list: Vec<(String, Operand)>,
}

fn allocation(file: FileId, text: &str, diags: &mut Vec<Diagnostic>) -> Symbols {
    let mut s = Symbols {
        map: BTreeMap::new(),
        list: Vec::new(),
    };
    let mut offset = 0u32;
    for line in text.split_inclusive('\n') {
        let start = offset;
        offset += line.len() as u32;
        let content = line.split([';', '"']).next().unwrap_or("");
        let mut words = content.split_whitespace();
        let (Some(op), sym) = (words.next(), words.next()) else {
            continue;
        };
        let at = |w: &str| {
            let col = content.find(w).unwrap_or(0) as u32;
            Span::new(file, start + col, start + col + w.len() as u32)
        };
        let Some(sym) = sym else {
            diags.push(Diagnostic::error(
                Code::E184,
                at(op),
                format!("`{op}`: an allocation line is `OPERAND SYMBOL [comment]`"),
            ));
            continue;
        };
        let o = match operand::parse(&op.to_ascii_uppercase()) {
            Some(Ok(o)) if o.kind != operand::Kind::P => o,
            Some(Err(why)) => {
                diags.push(Diagnostic::error(Code::E183, at(op), why));
                continue;
            }
            _ => {
                diags.push(Diagnostic::error(Code::E184, at(op), format!("`{op}` is not an operand that takes a symbol (I, O, F, T, C, IW, OW, FW, TP, TW, CP, CW, FU, R)")));
                continue;
            }
        };
        let up = sym.to_ascii_uppercase();
        let valid = sym.len() <= 9
            && sym.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_')
            && !sym.starts_with(|c: char| c.is_ascii_digit());
        let why = if !valid {
            Some("a symbol has at most 9 letters, digits or `_` and does not start with a digit")
        } else if parse::is_keyword(&up) || matches!(up.as_str(), "SBA" | "MBA" | "FST") {
            Some("a symbol cannot be a keyword or an accumulator")
        } else if operand::parse(&up).is_some()
            || operand::parse(&format!("{up}.0")).is_some()
            || up.starts_with("__")
            || up.starts_with('V')
                && up[1..].starts_with(|c: char| c.is_ascii_digit() || c == '$' || c == '%')
        {
            Some("a symbol cannot be spelled like an operand or a constant")
        } else if s.map.contains_key(&up) {
            Some("the symbol is defined twice")
        } else {
            None
        };
        if let Some(why) = why {
            diags.push(Diagnostic::error(
                Code::E184,
                at(sym),
                format!("symbol `{sym}`: {why}"),
            ));
            continue;
        }
        s.map.insert(up, o);
        s.list.push((sym.to_string(), o));
    }
    s
}

struct Unit {
    file: FileId,
    body: Body,
}

/// Reads the FST files of `map`: the generated ST text (`None` when there
/// are none, or when they have errors) and the STL diagnostics.
pub fn translate(map: &SourceMap) -> (Option<String>, Vec<Diagnostic>) {
    let mut diags = Vec::new();
    let mut alloc = Symbols {
        map: BTreeMap::new(),
        list: Vec::new(),
    };
    let mut files = Vec::new();
    let mut any = false;
    for (id, f) in map.files() {
        if !is_fst_file(&f.name) {
            continue;
        }
        any = true;
        match role(&f.name) {
            Some(Ok(Role::Allocation)) => alloc = allocation(id, &f.text, &mut diags),
            Some(Ok(r)) => files.push((id, r)),
            Some(Err(why)) => diags.push(Diagnostic::error(Code::E188, Span::new(id, 0, 0), why)),
            None => {}
        }
    }
    if !any {
        return (None, diags);
    }
    let mut programs: BTreeMap<u32, Unit> = BTreeMap::new();
    let mut modules: BTreeMap<u32, Unit> = BTreeMap::new();
    let mut used: BTreeSet<Operand> = alloc.list.iter().map(|(_, o)| *o).collect();
    for (id, r) in files {
        let toks = lex::lex(&map.get(id).text);
        let mut p = Parser::new(&toks, id, &alloc.map);
        let body = p.program();
        diags.append(&mut p.diags);
        used.extend(p.used);
        let unit = Unit { file: id, body };
        let clash = match r {
            Role::Program(n) => programs.insert(n, unit).is_some(),
            Role::Module(n) => {
                if matches!(unit.body, Body::Steps(_)) {
                    diags.push(Diagnostic::error(Code::E188, Span::new(id, 0, 0), format!("module B{n}: a CMP module here is a parallel or executive list (no steps)")));
                }
                modules.insert(n, unit).is_some()
            }
            Role::Allocation => false,
        };
        if clash {
            diags.push(Diagnostic::error(
                Code::E188,
                Span::new(id, 0, 0),
                "a program or module number is used by two files",
            ));
        }
    }
    if !programs.contains_key(&0) {
        let at = map
            .files()
            .find(|(_, f)| is_fst_file(&f.name))
            .map(|(id, _)| id)
            .unwrap_or(FileId(0));
        diags.push(Diagnostic::error(
            Code::E188,
            Span::new(at, 0, 0),
            "the project has no P0.stl: P0 must exist and starts first",
        ));
    }
    let mut e = Emitter {
        programs: &programs,
        modules: &modules,
        diags: Vec::new(),
        calls: Vec::new(),
    };
    let text = e.project(&alloc, &used);
    diags.append(&mut e.diags);
    if diags.iter().any(|d| d.is_error()) {
        return (None, diags);
    }
    (Some(text), diags)
}

/// The enumeration value of a step label.
fn step_value(label: &str) -> String {
    if label.starts_with(|c: char| c.is_ascii_digit()) {
        format!("S{label}")
    } else {
        label.to_string()
    }
}

struct Emitter<'a> {
    programs: &'a BTreeMap<u32, Unit>,
    modules: &'a BTreeMap<u32, Unit>,
    diags: Vec<Diagnostic>,
    /// The modules being inlined (a module calling itself is refused).
    calls: Vec<u32>,
}

/// The context a part runs in: the program number and, in a STEP
/// program, its step labels (upper case).
struct Ctx<'b> {
    n: u32,
    steps: Option<&'b [String]>,
    file: FileId,
}

impl Emitter<'_> {
    fn project(&mut self, alloc: &Symbols, used: &BTreeSet<Operand>) -> String {
        let mut s = String::from(
            "(* Generated from the FST STL files of the project (docs/festo-stl.md). *)\n",
        );
        let mut types = String::new();
        for (n, u) in self.programs {
            if let Body::Steps(steps) = &u.body {
                let vals: Vec<String> = steps.iter().map(|st| step_value(&st.label)).collect();
                let _ = writeln!(types, "    __FST_P{n}_STEPS : ({});", vals.join(", "));
                let _ = writeln!(
                    types,
                    "    __FST_P{n} : STRUCT RUN : BOOL; STEP : __FST_P{n}_STEPS; END_STRUCT;"
                );
            } else {
                let _ = writeln!(types, "    __FST_P{n} : STRUCT RUN : BOOL; END_STRUCT;");
            }
        }
        let _ = writeln!(s, "TYPE\n{types}END_TYPE\n");
        let mut globals = String::new();
        let mut declared = BTreeSet::new();
        for o in used {
            for (name, addr, ty) in o.globals() {
                if declared.insert(name.clone()) {
                    let _ = writeln!(globals, "    {name} AT {addr} : {ty};");
                }
            }
        }
        for (sym, o) in &alloc.list {
            let ty = if o.is_bit() { "BOOL" } else { "WORD" };
            let _ = writeln!(
                globals,
                "    {sym} AT {} : {ty};",
                o.address().unwrap_or_default()
            );
        }
        for n in self.programs.keys() {
            let run = if *n == 0 { " := (RUN := TRUE)" } else { "" };
            let _ = writeln!(globals, "    P{n} : __FST_P{n}{run};");
        }
        let _ = writeln!(
            globals,
            "    SBA : BOOL;\n    MBA : WORD;\n    __fst_last : LINT;"
        );
        let _ = writeln!(s, "VAR_GLOBAL\n{globals}END_VAR\n");
        s.push_str(HELPERS);
        let externs: String = globals
            .lines()
            .filter_map(|l| {
                let (name, rest) = l.split_once(" : ").or_else(|| l.split_once(" AT "))?;
                let name = name.split(" AT ").next().unwrap_or(name);
                let ty = rest.rsplit(" : ").next().unwrap_or(rest);
                let ty = ty.split(" :=").next().unwrap_or(ty).trim_end_matches(';');
                Some(format!("{name} : {ty};\n"))
            })
            .collect();
        let _ = writeln!(s, "PROGRAM FST\nVAR_EXTERNAL\n{externs}END_VAR\nVAR\n    __now : LINT;\n    __d : LINT;\n    __adv : BOOL;\n    __jmp : BOOL;\n    __fst_bit : BOOL;\nEND_VAR");
        let _ = writeln!(s, "    __now := TIME_TO_LINT(__SCAN_TIME()) / 10;\n    __d := __now - __fst_last;\n    __fst_last := __now;");
        for o in used.iter().filter(|o| {
            o.kind == operand::Kind::T || o.kind == operand::Kind::Tp || o.kind == operand::Kind::Tw
        }) {
            let n = o.n;
            let line = format!("    IF T{n} THEN IF WORD_TO_LINT(TW{n}) <= __d THEN TW{n} := 0; T{n} := FALSE; ELSE TW{n} := LINT_TO_WORD(WORD_TO_LINT(TW{n}) - __d); END_IF; END_IF;\n");
            if !s.contains(&line) {
                s.push_str(&line);
            }
        }
        for (n, u) in self.programs {
            let _ = writeln!(s, "    (* P{n} *)\n    IF P{n}.RUN THEN");
            let body = self.program(*n, u);
            s.push_str(&body);
            let _ = writeln!(s, "    END_IF;");
        }
        s.push_str("END_PROGRAM\n");
        s
    }

    fn program(&mut self, n: u32, u: &Unit) -> String {
        let mut s = String::new();
        match &u.body {
            Body::Steps(steps) => {
                let labels: Vec<String> = steps
                    .iter()
                    .map(|st| st.label.to_ascii_uppercase())
                    .collect();
                let ctx = Ctx {
                    n,
                    steps: Some(&labels),
                    file: u.file,
                };
                let _ = writeln!(s, "        __jmp := FALSE;\n        CASE P{n}.STEP OF");
                for (k, st) in steps.iter().enumerate() {
                    let next = steps
                        .get(k + 1)
                        .or(steps.first())
                        .map(|x| step_value(&x.label))
                        .unwrap_or_default();
                    let _ = writeln!(
                        s,
                        "        __FST_P{n}_STEPS#{}:\n            __adv := FALSE;",
                        step_value(&st.label)
                    );
                    s.push_str(&self.sentences(&st.sentences, &ctx, true));
                    let _ = writeln!(s, "            IF __adv AND NOT __jmp THEN P{n}.STEP := __FST_P{n}_STEPS#{next}; END_IF;");
                }
                let _ = writeln!(s, "        END_CASE;");
            }
            Body::Parallel(list) => {
                let ctx = Ctx {
                    n,
                    steps: None,
                    file: u.file,
                };
                s.push_str(&self.sentences(list, &ctx, false));
            }
            Body::Executive(list) => {
                let ctx = Ctx {
                    n,
                    steps: None,
                    file: u.file,
                };
                s.push_str(&self.instrs(list, &ctx));
            }
        }
        s
    }

    fn sentences(&mut self, list: &[Sentence], ctx: &Ctx, step: bool) -> String {
        let mut s = String::new();
        for (k, se) in list.iter().enumerate() {
            let last = step && k + 1 == list.len();
            let mut then = self.instrs(&se.then, ctx);
            if last {
                then.push_str("__adv := TRUE;\n");
            }
            let othrw = se.othrw.as_ref().map(|o| {
                let mut t = self.instrs(o, ctx);
                if last {
                    t.push_str("__adv := TRUE;\n");
                }
                t
            });
            let guard = if step { "NOT __jmp AND " } else { "" };
            let cond = se.cond.as_deref().unwrap_or("TRUE");
            let _ = write!(s, "            IF {guard}{cond} THEN\n{then}");
            if let Some(o) = othrw {
                if step {
                    let _ = write!(s, "            ELSIF NOT __jmp THEN\n{o}");
                } else {
                    let _ = write!(s, "            ELSE\n{o}");
                }
            }
            s.push_str("            END_IF;\n");
        }
        s
    }

    fn instrs(&mut self, list: &[Instr], ctx: &Ctx) -> String {
        let mut s = String::new();
        for i in list {
            match i {
                Instr::Code(c) => {
                    let _ = writeln!(s, "                {c}");
                }
                Instr::Program(p, on) => {
                    let Some(u) = self.programs.get(p) else {
                        self.diags.push(Diagnostic::error(
                            Code::E188,
                            Span::new(ctx.file, 0, 0),
                            format!("P{p} is set or reset but the project has no P{p}.stl"),
                        ));
                        continue;
                    };
                    if *on {
                        let _ = write!(s, "                P{p}.RUN := TRUE;");
                        if let Body::Steps(steps) = &u.body {
                            if let Some(f) = steps.first() {
                                let _ = write!(
                                    s,
                                    " P{p}.STEP := __FST_P{p}_STEPS#{};",
                                    step_value(&f.label)
                                );
                            }
                        }
                        s.push('\n');
                    } else {
                        let _ = writeln!(s, "                P{p}.RUN := FALSE;");
                    }
                }
                Instr::Jmp(label, span) => {
                    match ctx.steps {
                        Some(steps) if steps.contains(label) => {
                            let n = ctx.n;
                            let v = step_value(label);
                            let real = self
                                .programs
                                .get(&n)
                                .and_then(|u| match &u.body {
                                    Body::Steps(st) => st
                                        .iter()
                                        .find(|x| x.label.eq_ignore_ascii_case(label))
                                        .map(|x| step_value(&x.label)),
                                    _ => None,
                                })
                                .unwrap_or(v);
                            let _ = writeln!(s, "                P{n}.STEP := __FST_P{n}_STEPS#{real}; __jmp := TRUE;");
                        }
                        Some(_) => self.diags.push(Diagnostic::error(
                            Code::E186,
                            *span,
                            format!("JMP TO {label}: the program has no such step"),
                        )),
                        None => self.diags.push(Diagnostic::error(
                            Code::E186,
                            *span,
                            "JMP TO outside a STEP program",
                        )),
                    }
                }
                Instr::Call(m, params, span) => {
                    let Some(u) = self.modules.get(m) else {
                        self.diags.push(Diagnostic::error(
                            Code::E188,
                            *span,
                            format!("CMP {m}: the project has no B{m}.stl"),
                        ));
                        continue;
                    };
                    if self.calls.contains(m) {
                        self.diags.push(Diagnostic::error(
                            Code::E188,
                            *span,
                            format!("CMP {m} calls itself"),
                        ));
                        continue;
                    }
                    for (k, p) in params.iter().enumerate() {
                        let _ = writeln!(s, "                FU{} := {p};", 32 + k);
                    }
                    self.calls.push(*m);
                    let mctx = Ctx {
                        n: ctx.n,
                        steps: None,
                        file: u.file,
                    };
                    let body = match &u.body {
                        Body::Parallel(l) => self.sentences(l, &mctx, false),
                        Body::Executive(l) => self.instrs(l, &mctx),
                        Body::Steps(_) => String::new(),
                    };
                    self.calls.pop();
                    let _ = write!(s, "                (* CMP {m} *)\n{body}");
                }
            }
        }
        s
    }
}

/// Word arithmetic wraps at 16 bits; SHL/SHR shift one place, ROL/ROR
/// rotate one place, BID/DEB convert 4 BCD digits.
const HELPERS: &str = r#"FUNCTION __FST_ADD : WORD VAR_INPUT A, B : WORD; END_VAR
    __FST_ADD := DINT_TO_WORD((WORD_TO_DINT(A) + WORD_TO_DINT(B)) MOD 65536);
END_FUNCTION
FUNCTION __FST_SUB : WORD VAR_INPUT A, B : WORD; END_VAR
    __FST_SUB := DINT_TO_WORD((WORD_TO_DINT(A) - WORD_TO_DINT(B) + 65536) MOD 65536);
END_FUNCTION
FUNCTION __FST_MUL : WORD VAR_INPUT A, B : WORD; END_VAR
    __FST_MUL := LINT_TO_WORD((WORD_TO_LINT(A) * WORD_TO_LINT(B)) MOD 65536);
END_FUNCTION
FUNCTION __FST_DIV : WORD VAR_INPUT A, B : WORD; END_VAR
    IF B = 0 THEN __FST_DIV := 0; ELSE __FST_DIV := DINT_TO_WORD(WORD_TO_DINT(A) / WORD_TO_DINT(B)); END_IF;
END_FUNCTION
FUNCTION __FST_SHL : WORD VAR_INPUT A : WORD; END_VAR
    __FST_SHL := SHL(A, 1);
END_FUNCTION
FUNCTION __FST_SHR : WORD VAR_INPUT A : WORD; END_VAR
    __FST_SHR := SHR(A, 1);
END_FUNCTION
FUNCTION __FST_ROL : WORD VAR_INPUT A : WORD; END_VAR
    __FST_ROL := ROL(A, 1);
END_FUNCTION
FUNCTION __FST_ROR : WORD VAR_INPUT A : WORD; END_VAR
    __FST_ROR := ROR(A, 1);
END_FUNCTION
FUNCTION __FST_INV : WORD VAR_INPUT A : WORD; END_VAR
    __FST_INV := NOT A;
END_FUNCTION
FUNCTION __FST_CPL : WORD VAR_INPUT A : WORD; END_VAR
    __FST_CPL := __FST_SUB(0, A);
END_FUNCTION
FUNCTION __FST_SWAP : WORD VAR_INPUT A : WORD; END_VAR
    __FST_SWAP := ROL(A, 8);
END_FUNCTION
FUNCTION __FST_BID : WORD VAR_INPUT A : WORD; END_VAR
VAR v : DINT; END_VAR
    v := WORD_TO_DINT(A) MOD 10000;
    __FST_BID := DINT_TO_WORD(v / 1000 * 4096 + v / 100 MOD 10 * 256 + v / 10 MOD 10 * 16 + v MOD 10);
END_FUNCTION
FUNCTION __FST_DEB : WORD VAR_INPUT A : WORD; END_VAR
VAR v : DINT; END_VAR
    v := WORD_TO_DINT(A);
    __FST_DEB := DINT_TO_WORD(v / 4096 * 1000 + v / 256 MOD 16 * 100 + v / 16 MOD 16 * 10 + v MOD 16);
END_FUNCTION

"#;
