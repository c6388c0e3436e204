//! Rungs → Structured Text. Each rung evaluates its rung condition `__rc`
//! from left to right: an input instruction ANDs its test into it, an
//! output instruction acts on it and leaves it; a branch saves the
//! condition at `BST` (`__bs[d]`), starts each leg from it and ORs the legs
//! at `BND` (`__bo[d]`). A rung starts from `__mcr` (TRUE outside a false
//! MCR zone). A subroutine is inlined at its JSR (its branch slots 16
//! higher, so a JSR inside a branch keeps the caller's). A file with JMP,
//! LBL, RET or TND runs as segments, one per LBL, in a loop over the
//! segment number: a jump sets the next segment and skips the rest of the
//! segment after its rung.

use super::layout::{real, Layout};
use super::parse::{Elem, Ins, Operand, Project, Rung};
use automat_base::slc::{Address, FileType};
use automat_base::{Code, Diagnostic, Span};
use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write;

/// Branches nested in one rung.
const MAX_BRANCH: usize = 16;
/// Subroutine calls nested (the SLC 5/03 and later allow 8).
const MAX_CALLS: usize = 8;

pub struct Emitter<'a> {
    p: &'a Project,
    pub(super) layout: &'a mut Layout,
    pub diags: Vec<Diagnostic>,
    /// The files being inlined (a file calling itself is refused).
    stack: Vec<u32>,
    /// Segment loops generated so far (each has its `__pcN`, `__jN`).
    loops: u32,
    /// A remainder slot per timer element: (file, word index) → slot.
    rems: BTreeMap<(u32, u32), usize>,
    /// A slot per PID block for its integral, last PV, last error and
    /// last valid setpoint.
    pids: BTreeMap<(u32, u32), usize>,
    /// The instruction being emitted, as diagnostics name it
    /// (`LAD 2 rung 4, `ADD N7:0 1 N7:1``).
    pub(super) here: String,
    /// The math instructions that can set the overflow trap S:5/0, as
    /// [`Emitter::here`] named them; the one that set it last is
    /// `__slc_trap` = its index + 1 at the end of the scan.
    pub traps: Vec<String>,
    /// The next element id of the rung networks (`network.rs`): ids are
    /// unique in the POU, so each `__ld_n<id>` names one element.
    pub(super) next_id: u32,
    /// The hidden BOOLs of the lowered networks.
    pub(super) hidden: Vec<String>,
    /// The model element of each contact or coil, by the instruction's
    /// place in its file: its power flow is `__ld_n<id>`.
    pub(super) elements: BTreeMap<(automat_base::FileId, u32), u32>,
    /// The run-time checks of indexed and indirect addresses: what each
    /// fault means (the check line carries its number, `fault_marker`).
    pub faults: Vec<String>,
}

/// Where the rungs of one inlined file run.
pub(super) struct Level {
    /// The segment loop's number, when the file has one.
    seg: Option<u32>,
    /// The first branch slot.
    base: usize,
    /// Label number → segment.
    labels: BTreeMap<u32, usize>,
}

fn place(a: Address) -> String {
    a.st_path().unwrap_or_default()
}

fn is_real(o: &Operand) -> bool {
    match o {
        Operand::Real(_) => true,
        Operand::Addr(a) => a.ty == FileType::F,
        Operand::Dyn(d) => d.is_real(),
        _ => false,
    }
}

/// A word operand (direct, indexed or indirect) as an ST place.
fn word(o: &Operand) -> String {
    match o {
        Operand::Addr(a) => place(*a),
        Operand::Dyn(d) => d.word(),
        _ => String::new(),
    }
}

/// A bit operand's value as ST.
fn read_bit(o: &Operand) -> String {
    match o {
        Operand::Dyn(d) => d.read_bit(),
        _ => word(o),
    }
}

/// Writes `v` (BOOL ST) to a bit operand.
fn write_bit(o: &Operand, v: &str) -> String {
    match o {
        Operand::Dyn(d) => d.write_bit(v),
        _ => format!("{} := {v};", word(o)),
    }
}

/// An integer operand as INT text.
fn int(o: &Operand) -> String {
    match o {
        Operand::Addr(_) | Operand::Dyn(_) => word(o),
        Operand::Int(v) => v.to_string(),
        _ => "0".into(),
    }
}

fn dint(o: &Operand) -> String {
    match o {
        Operand::Addr(_) | Operand::Dyn(_) => format!("INT_TO_DINT({})", int(o)),
        _ => int(o),
    }
}

fn lreal(o: &Operand) -> String {
    match o {
        Operand::Addr(_) | Operand::Dyn(_) if is_real(o) => {
            format!("REAL_TO_LREAL({})", word(o))
        }
        Operand::Addr(_) | Operand::Dyn(_) => format!("INT_TO_LREAL({})", word(o)),
        Operand::Int(v) => format!("{v}.0"),
        Operand::Real(v) => real(*v),
        _ => "0.0".into(),
    }
}

/// A file operand's array and first word, as ST: `N7` and `10` for
/// `#N7:10`; for `#N7:[N7:0]` the word found before the instruction
/// (`__ix[k]`) and, for an indirect file (`#N[N7:0]:0`), a placeholder
/// the instruction's `CASE` over the files replaces
/// ([`super::dynamic::file_placeholder`]).
fn run_at(o: &Operand) -> (String, String) {
    match o {
        Operand::Dyn(d) => (
            if d.file_from.is_some() {
                super::dynamic::file_placeholder(d.slot)
            } else {
                d.addr.array()
            },
            format!("__ix[{}]", d.slot),
        ),
        _ => {
            let a = addr(o);
            (a.array(), a.index().to_string())
        }
    }
}

fn addr(o: &Operand) -> Address {
    match o {
        Operand::Addr(a) => *a,
        _ => Address {
            ty: FileType::N,
            file: 7,
            elem: 0,
            part: automat_base::slc::Part::Element,
        },
    }
}

impl<'a> Emitter<'a> {
    pub fn new(p: &'a Project, layout: &'a mut Layout) -> Emitter<'a> {
        Emitter {
            p,
            layout,
            diags: Vec::new(),
            stack: Vec::new(),
            loops: 0,
            rems: BTreeMap::new(),
            pids: BTreeMap::new(),
            here: String::new(),
            traps: Vec::new(),
            next_id: 1,
            hidden: Vec::new(),
            elements: BTreeMap::new(),
            faults: Vec::new(),
        }
    }

    fn err(&mut self, code: Code, span: Span, msg: String) {
        self.diags.push(Diagnostic::error(code, span, msg));
    }

    /// The PROGRAM `SLC`.
    pub fn program(&mut self) -> String {
        let main = if self.p.files.contains_key(&2) {
            self.file(2, 0)
        } else {
            String::new()
        };
        // Files no JSR reaches are still checked.
        for n in self
            .p
            .files
            .keys()
            .copied()
            .filter(|&n| n != 2)
            .collect::<Vec<_>>()
        {
            let _ = self.file(n, 1);
        }
        let sti = self.sti();
        // A file inlined at several JSRs reports its errors once.
        let mut seen = BTreeSet::new();
        self.diags
            .retain(|d| seen.insert((d.span.file, d.span.start, d.span.end, d.code)));
        let mut s = String::from("PROGRAM SLC\nVAR_EXTERNAL\n");
        for (n, f) in &self.layout.files {
            let ty = if f.ty == FileType::F { "REAL" } else { "INT" };
            let len = if f.ty == FileType::F {
                f.elements
            } else if matches!(f.ty, FileType::I | FileType::O) {
                f.elements * automat_base::slc::IO_SLOT_WORDS
            } else {
                f.elements * f.ty.words()
            };
            let _ = writeln!(
                s,
                "    {}{n} : ARRAY[0..{}] OF {ty};",
                f.ty.letter(),
                len - 1
            );
        }
        s.push_str("    __slc_started : BOOL;\n    __slc_last : LINT;\n    __slc_fault : __SLC_MAJOR_FAULT;\nEND_VAR\nVAR\n    __slc_trap : INT;\n");
        let _ = writeln!(
            s,
            "    __rc, __t, __x, __mcr, __tnd : BOOL;\n    __bs, __bo : ARRAY[0..{}] OF BOOL;\n    __d, __i : DINT;\n    __now : LINT;\n    __rem : ARRAY[0..{}] OF DINT;\n    __pidi, __pidp, __pide, __pids : ARRAY[0..{}] OF LREAL;\n    __pidc, __stim : INT;\n    __sti : DINT;",
            MAX_BRANCH * (MAX_CALLS + 1) - 1,
            self.rems.len().max(1) - 1,
            self.pids.len().max(1) - 1
        );
        let _ = writeln!(
            s,
            "    __ix, __ib, __if : ARRAY[0..{0}] OF DINT;\n    __iv : ARRAY[0..{0}] OF INT;",
            self.p.dynamic.max(1) - 1
        );
        for k in 0..self.loops {
            let _ = writeln!(s, "    __pc{k} : INT;\n    __j{k} : BOOL;");
        }
        for h in &self.hidden {
            let _ = writeln!(s, "    {h} : BOOL;");
        }
        s.push_str("END_VAR\n");
        s.push_str("    __now := TIME_TO_LINT(__SCAN_TIME());\n    IF __slc_started THEN __d := LINT_TO_DINT(__now - __slc_last); ELSE __d := 0; END_IF;\n    __slc_last := __now;\n    (* S:1/15 first pass *)\n    S2[1].15 := NOT __slc_started;\n    __mcr := TRUE;\n    __tnd := FALSE;\n    __slc_trap := 0;\n");
        s.push_str(&sti);
        s.push_str(&main);
        s.push_str("    __slc_started := TRUE;\n");
        // The overflow trap and END_PROGRAM follow (`super::trap_check`).
        s
    }

    /// The Selectable Timed Interrupt, run before program file 2: S:30
    /// the interval in ms of PLC time, S:31 the file. Each whole interval
    /// elapsed since the previous scan runs the file once (the remainder
    /// kept in `__sti`); S:30 <= 0 or S:31 naming no subroutine file
    /// disables it and drops the time. Generated only when the program
    /// has S:31 (S2 of at least 32 words) and subroutine files.
    fn sti(&mut self) -> String {
        let words = self.layout.files.get(&2).map_or(0, |f| f.elements);
        let files: Vec<u32> = self.p.files.keys().copied().filter(|&n| n >= 3).collect();
        if words < 32 || files.is_empty() {
            return String::new();
        }
        let mut s = format!(
            "    (* STI: S:30 interval (ms), S:31 file *)\n    IF S2[30] > 0 AND (S2[31] = {}) THEN\n    __sti := __sti + __d;\n    WHILE S2[30] > 0 AND __sti >= INT_TO_DINT(S2[30]) DO\n    __sti := __sti - INT_TO_DINT(S2[30]);\n    __stim := S2[0];\n    CASE S2[31] OF\n",
            files
                .iter()
                .map(|n| n.to_string())
                .collect::<Vec<_>>()
                .join(" OR S2[31] = ")
        );
        for n in files {
            let code = self.file(n, 1);
            let _ = write!(
                s,
                "    {n}:\n    __mcr := TRUE;\n    __tnd := FALSE;\n{code}"
            );
        }
        // As the SLC: the math flags S:0/0-3 the interrupted program saw
        // are back when the STI file returns.
        s.push_str("    END_CASE;\n    S2[0].0 := __stim.0; S2[0].1 := __stim.1; S2[0].2 := __stim.2; S2[0].3 := __stim.3;\n    END_WHILE;\n    ELSE\n    __sti := 0;\n    END_IF;\n    __mcr := TRUE;\n    __tnd := FALSE;\n");
        s
    }

    fn has(&self, n: u32, names: &[&str]) -> bool {
        self.p.files.get(&n).is_some_and(|f| {
            f.rungs
                .iter()
                .flat_map(|r| &r.elems)
                .any(|e| matches!(e, Elem::Ins(i) if names.contains(&i.mn)))
        })
    }

    /// Does running file `n` possibly end the scan (TND in it or a file it
    /// calls)?
    fn ends_scan(&self, n: u32, seen: &mut BTreeSet<u32>) -> bool {
        if !seen.insert(n) {
            return false;
        }
        if self.has(n, &["TND"]) {
            return true;
        }
        let called: Vec<u32> = self.p.files.get(&n).map_or(Vec::new(), |f| {
            f.rungs
                .iter()
                .flat_map(|r| &r.elems)
                .filter_map(|e| match e {
                    Elem::Ins(i) if i.mn == "JSR" => match i.ops.first() {
                        Some(Operand::Number(k)) => Some(*k),
                        _ => None,
                    },
                    _ => None,
                })
                .collect()
        });
        called.into_iter().any(|k| self.ends_scan(k, seen))
    }

    /// The code of program file `n` at call depth `depth`.
    fn file(&mut self, n: u32, depth: usize) -> String {
        let p: &'a Project = self.p;
        let Some(f) = p.files.get(&n) else {
            return String::new();
        };
        let rungs: &'a [Rung] = &f.rungs;
        let segmented =
            self.has(n, &["JMP", "LBL", "RET", "TND"]) || self.ends_scan(n, &mut BTreeSet::new());
        let mut level = Level {
            seg: None,
            base: depth * MAX_BRANCH,
            labels: BTreeMap::new(),
        };
        // Segments start at rungs beginning with LBL.
        let mut seg = 0usize;
        for (r, rung) in rungs.iter().enumerate() {
            let rn = rung.number;
            for (k, e) in rung.elems.iter().enumerate() {
                let Elem::Ins(i) = e else { continue };
                match i.mn {
                    "LBL" => {
                        if k != 0 {
                            self.err(Code::E237, i.span, format!("LAD {n} rung {rn}, `{}`: LBL is the first instruction of its rung", i.text));
                            continue;
                        }
                        if r > 0 {
                            seg += 1;
                        }
                        if let Some(Operand::Number(l)) = i.ops.first() {
                            if level.labels.insert(*l, seg).is_some() {
                                self.err(Code::E237, i.span, format!("LAD {n} rung {rn}, `{}`: label {l} is defined twice in this file", i.text));
                            }
                        }
                    }
                    "SBR" if n == 2 || r != 0 || k != 0 => {
                        self.err(Code::E237, i.span, format!("LAD {n} rung {rn}, `SBR`: SBR is the first instruction of a subroutine file (3 to 255)"));
                    }
                    _ => {}
                }
            }
        }
        let mut s = String::new();
        let u = if segmented {
            let u = self.loops;
            self.loops += 1;
            level.seg = Some(u);
            let _ = write!(s, "    __pc{u} := 0;\n    WHILE __pc{u} >= 0 DO\n    __j{u} := FALSE;\n    CASE __pc{u} OF\n    0:\n");
            Some(u)
        } else {
            None
        };
        let mut seg = 0usize;
        for (r, rung) in rungs.iter().enumerate() {
            let starts = matches!(rung.elems.first(), Some(Elem::Ins(i)) if i.mn == "LBL");
            let code = self.rung(n, rung.number, rung, &level);
            match u {
                Some(u) if starts && r > 0 => {
                    seg += 1;
                    let _ = write!(
                        s,
                        "    IF NOT __j{u} THEN __pc{u} := {seg}; END_IF;\n    {seg}:\n{code}"
                    );
                }
                Some(u) if r > 0 => {
                    let _ = write!(s, "    IF NOT __j{u} THEN\n{code}    END_IF;\n");
                }
                _ => s.push_str(&code),
            }
        }
        if let Some(u) = u {
            let _ = write!(
                s,
                "    IF NOT __j{u} THEN __pc{u} := -1; END_IF;\n    END_CASE;\n    END_WHILE;\n"
            );
        }
        s
    }

    fn rung(&mut self, n: u32, r: usize, rung: &Rung, level: &Level) -> String {
        let mut s = String::new();
        let comment = rung
            .comment
            .as_deref()
            .map(|c| format!(": {}", c.replace("*)", "* )").replace("(*", "( *")))
            .unwrap_or_default();
        let _ = writeln!(s, "    (* LAD {n} rung {r}{comment} *)");
        let mcr = rung
            .elems
            .iter()
            .any(|e| matches!(e, Elem::Ins(i) if i.mn == "MCR"));
        let _ = writeln!(s, "    __rc := {};", if mcr { "TRUE" } else { "__mcr" });
        if super::network::fits(rung) {
            self.rung_network(n, r, rung, level, &mut s);
            return s;
        }
        let mut depth = 0usize;
        for e in &rung.elems {
            match e {
                Elem::Bst(span) => {
                    if depth + 1 >= MAX_BRANCH {
                        self.err(
                            Code::E235,
                            *span,
                            format!(
                                "LAD {n} rung {r}: branches nested deeper than {}",
                                MAX_BRANCH - 1
                            ),
                        );
                        return String::new();
                    }
                    depth += 1;
                    let d = level.base + depth;
                    let _ = writeln!(s, "    __bs[{d}] := __rc; __bo[{d}] := FALSE;");
                }
                Elem::Nxb(_) => {
                    let d = level.base + depth;
                    let _ = writeln!(s, "    __bo[{d}] := __bo[{d}] OR __rc; __rc := __bs[{d}];");
                }
                Elem::Bnd(_) => {
                    let d = level.base + depth;
                    let _ = writeln!(s, "    __rc := __bo[{d}] OR __rc;");
                    depth = depth.saturating_sub(1);
                }
                Elem::Ins(i) => {
                    let code = self.ins(n, r, i, level);
                    s.push_str(&code);
                }
            }
        }
        s
    }

    /// The bit an XIC/XIO/OTE/OTL/OTU names, as an ST place.
    pub(super) fn bit(&self, i: &Ins) -> String {
        place(addr(&i.ops.first().cloned().unwrap_or(Operand::Int(0))))
    }

    /// An instruction's ST: its indexed and indirect operands resolved
    /// and checked first (`dynamic.rs`), written back after when one is
    /// the destination in a file found at run time.
    pub(super) fn ins(&mut self, n: u32, r: usize, i: &Ins, level: &Level) -> String {
        self.here = format!("LAD {n} rung {r}, `{}`", i.text);
        let mut before = String::new();
        let mut after = String::new();
        let kinds = super::instr::find(i.mn).map_or(&[][..], |d| d.operands);
        let mut runs = Vec::new();
        for (k, o) in i.ops.iter().enumerate() {
            if let Operand::Dyn(d) = o {
                if kinds.get(k) == Some(&super::instr::Kind::FileRef) {
                    runs.push(d);
                    continue;
                }
                let dest = kinds.get(k) == Some(&super::instr::Kind::Dest);
                let (b, a) = self.resolve(d, dest);
                before.push_str(&b);
                after.push_str(&a);
            }
        }
        let mut body = self.ins_body(n, r, i, level);
        let words = super::parse::run_words(i.mn, &i.ops).unwrap_or(1);
        for d in runs {
            body = self.file_run(d, words, &body);
        }
        format!("{before}{body}{after}")
    }

    fn ins_body(&mut self, n: u32, r: usize, i: &Ins, level: &Level) -> String {
        self.here = format!("LAD {n} rung {r}, `{}`", i.text);
        let ops = &i.ops;
        let op = |k: usize| ops.get(k).cloned().unwrap_or(Operand::Int(0));
        let a0 = addr(&op(0));
        let gate = |body: String| format!("    IF __rc THEN {body} END_IF;\n");
        match i.mn {
            "XIC" => format!("    __rc := __rc AND {};\n", read_bit(&op(0))),
            "XIO" => format!("    __rc := __rc AND NOT {};\n", read_bit(&op(0))),
            "OTE" => format!("    {}\n", write_bit(&op(0), "__rc")),
            "OTL" => gate(write_bit(&op(0), "TRUE")),
            "OTU" => gate(write_bit(&op(0), "FALSE")),
            "OSR" => format!(
                "    __t := __rc AND NOT {}; {} __rc := __t;\n",
                read_bit(&op(0)),
                write_bit(&op(0), "__rc")
            ),
            "TON" | "TOF" | "RTO" => {
                let (base, pre, acc) = match (op(1), op(2), op(3)) {
                    (Operand::Base(b), Operand::Int(p), Operand::Int(a)) => (b, p, a),
                    _ => (10, 0, 0),
                };
                self.layout.preset(a0, 1, pre);
                self.layout.preset(a0, 2, acc);
                let k = self.rem(a0);
                let (arr, ix) = (a0.array(), a0.index());
                format!(
                    "    __x := __SLC_{}(RUNG := __rc, BASE := {base}, D := __d, CTL := {arr}[{ix}], PRE := {arr}[{}], ACC := {arr}[{}], REM := __rem[{k}]);\n",
                    i.mn,
                    ix + 1,
                    ix + 2
                )
            }
            "CTU" | "CTD" => {
                if let (Operand::Int(p), Operand::Int(a)) = (op(1), op(2)) {
                    self.layout.preset(a0, 1, p);
                    self.layout.preset(a0, 2, a);
                }
                let (arr, ix) = (a0.array(), a0.index());
                format!(
                    "    __x := __SLC_{}(RUNG := __rc, CTL := {arr}[{ix}], PRE := {arr}[{}], ACC := {arr}[{}]);\n",
                    i.mn,
                    ix + 1,
                    ix + 2
                )
            }
            "RES" => {
                let (arr, ix) = (a0.array(), a0.index());
                let bits: &[u32] = match a0.ty {
                    FileType::T => &[15, 14, 13],
                    FileType::C => &[15, 14, 13, 12, 11, 10],
                    _ => &[15, 14, 13, 12, 11, 10, 9, 8],
                };
                let mut b: String = bits
                    .iter()
                    .map(|k| format!("{arr}[{ix}].{k} := FALSE; "))
                    .collect();
                let _ = write!(b, "{arr}[{}] := 0;", ix + 2);
                if a0.ty == FileType::T {
                    let k = self.rem(a0);
                    let _ = write!(b, " __rem[{k}] := 0;");
                }
                gate(b)
            }
            "EQU" | "NEQ" | "LES" | "LEQ" | "GRT" | "GEQ" => {
                let sym = match i.mn {
                    "EQU" => "=",
                    "NEQ" => "<>",
                    "LES" => "<",
                    "LEQ" => "<=",
                    "GRT" => ">",
                    _ => ">=",
                };
                let (a, b) = (op(0), op(1));
                if is_real(&a) || is_real(&b) {
                    format!(
                        "    __rc := __rc AND ({} {sym} {});\n",
                        lreal(&a),
                        lreal(&b)
                    )
                } else {
                    format!("    __rc := __rc AND ({} {sym} {});\n", dint(&a), dint(&b))
                }
            }
            "LIM" => format!(
                "    __rc := __rc AND __SLC_LIM({}, {}, {});\n",
                lreal(&op(0)),
                lreal(&op(1)),
                lreal(&op(2))
            ),
            "MEQ" => {
                if !self.ints(n, r, i, ops) {
                    return String::new();
                }
                format!(
                    "    __rc := __rc AND __SLC_MEQ({}, {}, {});\n",
                    int(&op(0)),
                    int(&op(1)),
                    int(&op(2))
                )
            }
            "ADD" | "SUB" | "MUL" | "DIV" => {
                let (a, b) = (op(0), op(1));
                let (ie, re, carry) = match i.mn {
                    "ADD" => (
                        format!("{} + {}", dint(&a), dint(&b)),
                        format!("{} + {}", lreal(&a), lreal(&b)),
                        format!("__SLC_U({}) + __SLC_U({}) > 65535", int(&a), int(&b)),
                    ),
                    "SUB" => (
                        format!("{} - {}", dint(&a), dint(&b)),
                        format!("{} - {}", lreal(&a), lreal(&b)),
                        format!("__SLC_U({}) < __SLC_U({})", int(&a), int(&b)),
                    ),
                    "MUL" => (
                        format!("{} * {}", dint(&a), dint(&b)),
                        format!("{} * {}", lreal(&a), lreal(&b)),
                        "FALSE".into(),
                    ),
                    _ => (
                        format!("__SLC_IDIV({}, {})", dint(&a), dint(&b)),
                        format!("__SLC_FDIV({}, {})", lreal(&a), lreal(&b)),
                        "FALSE".into(),
                    ),
                };
                let realm = is_real(&a) || is_real(&b);
                gate(self.store(&op(2), realm, &ie, &re, &carry))
            }
            "NEG" | "ABS" | "MOV" => {
                let a = op(0);
                let (ie, re) = match i.mn {
                    "NEG" => (format!("-{}", dint(&a)), format!("-{}", lreal(&a))),
                    "ABS" => (format!("ABS({})", dint(&a)), format!("ABS({})", lreal(&a))),
                    _ => (dint(&a), lreal(&a)),
                };
                gate(self.store(&op(1), is_real(&a), &ie, &re, "FALSE"))
            }
            "SQR" => {
                let a = op(0);
                let re = format!("SQRT(ABS({}))", lreal(&a));
                let carry = format!("{} < 0.0", lreal(&a));
                gate(self.store(&op(1), true, "", &re, &carry))
            }
            "SCL" => {
                let re = format!(
                    "{} * {} / 10000.0 + {}",
                    lreal(&op(0)),
                    lreal(&op(1)),
                    lreal(&op(2))
                );
                gate(self.store(&op(3), true, "", &re, "FALSE"))
            }
            "SCP" => {
                let (x, il, ih, sl, sh) = (
                    lreal(&op(0)),
                    lreal(&op(1)),
                    lreal(&op(2)),
                    lreal(&op(3)),
                    lreal(&op(4)),
                );
                let re = format!("__SLC_FDIV(({x} - {il}) * ({sh} - {sl}), {ih} - {il}) + {sl}");
                gate(self.store(&op(5), true, "", &re, "FALSE"))
            }
            "CLR" => gate(self.store(&op(0), false, "0", "0.0", "FALSE")),
            "AND" | "OR" | "XOR" | "NOT" | "MVM" => {
                if !self.ints(n, r, i, ops) {
                    return String::new();
                }
                let (e, dest) = match i.mn {
                    "NOT" => (format!("__SLC_NOT({})", int(&op(0))), op(1)),
                    "MVM" => (
                        format!(
                            "__SLC_MVM({}, {}, {})",
                            int(&op(0)),
                            int(&op(1)),
                            int(&op(2))
                        ),
                        op(2),
                    ),
                    m => (
                        format!("__SLC_{m}({}, {})", int(&op(0)), int(&op(1))),
                        op(2),
                    ),
                };
                let ie = format!("INT_TO_DINT({e})");
                gate(self.store(&dest, false, &ie, "", "FALSE"))
            }
            "JSR" => {
                let Some(Operand::Number(k)) = ops.first().cloned() else {
                    return String::new();
                };
                if !self.p.files.contains_key(&k) {
                    self.err(
                        Code::E237,
                        i.span,
                        format!(
                            "LAD {n} rung {r}, `{}`: the project has no program file LAD {k}",
                            i.text
                        ),
                    );
                    return String::new();
                }
                if self.stack.contains(&k) || k == n {
                    self.err(Code::E237, i.span, format!("LAD {n} rung {r}, `{}`: LAD {k} calls itself (the SLC has no recursion)", i.text));
                    return String::new();
                }
                if self.stack.len() + 1 >= MAX_CALLS {
                    self.err(
                        Code::E237,
                        i.span,
                        format!(
                            "LAD {n} rung {r}, `{}`: subroutine calls nest deeper than {MAX_CALLS}",
                            i.text
                        ),
                    );
                    return String::new();
                }
                self.stack.push(n);
                let depth = self.stack.len();
                let body = self.file(k, depth);
                self.stack.pop();
                let mut s = format!(
                    "    IF __rc THEN\n    (* JSR {k} *)\n{body}    __rc := TRUE;\n    END_IF;\n"
                );
                if let Some(u) = level.seg {
                    if self.ends_scan(k, &mut BTreeSet::new()) {
                        let _ = writeln!(
                            s,
                            "    IF __tnd THEN __pc{u} := -1; __j{u} := TRUE; END_IF;"
                        );
                    }
                }
                s
            }
            "COP" | "FLL" | "FFL" | "FFU" | "BSL" | "BSR" => self.file_ins(n, r, i),
            "SQO" | "SQC" => self.sequencer(n, r, i),
            "PID" => {
                if !self.ints(n, r, i, ops) {
                    return String::new();
                }
                let (arr, b) = (a0.array(), a0.index());
                let w = |k: u32| format!("{arr}[{}]", b + k);
                let k = self.pid_slot(a0);
                let mut s = format!(
                    "    __x := __SLC_PID(RUNG := __rc, D := __d, PVIN := {}, SP := {}, KC := {}, TI := {}, TD := {}, BIAS := {}, SMAX := {}, SMIN := {}, DB := {}, OMAX := {}, OMIN := {}, UPD := {}, CTL := {}, W1 := {}, W14 := {}, W15 := {}, W16 := {}, W17 := {}, W18 := {}, CV := {}, ERR := __pidc, REM := __rem[{k}], I := __pidi[{p}], PREV := __pidp[{p}], PREVE := __pide[{p}], LSP := __pids[{p}]);\n",
                    int(&op(1)), w(2), w(3), w(4), w(5), w(6), w(7), w(8), w(9), w(11), w(12), w(13), w(0), w(1), w(14), w(15), w(16), w(17), w(18),
                    place(addr(&op(2))), p = self.pids_index(a0)
                );
                // One check per sub-error code, so the fault message says
                // which control-block value is wrong.
                for (code, what) in super::pid::ERRORS {
                    let bad = format!("__pidc = 16#{code:X}");
                    let msg = format!("PID error 0036h, sub-error {code:X}h in word 1: {what}");
                    s.push_str(&self.check(&bad, msg));
                }
                s
            }
            "SBR" | "LBL" | "NOP" => String::new(),
            "AFI" => "    __rc := FALSE;\n".into(),
            "MCR" => "    __mcr := __rc;\n".into(),
            "JMP" => {
                let Some(Operand::Number(l)) = ops.first().cloned() else {
                    return String::new();
                };
                let (Some(u), Some(seg)) = (level.seg, level.labels.get(&l)) else {
                    self.err(
                        Code::E237,
                        i.span,
                        format!(
                            "LAD {n} rung {r}, `{}`: no `LBL {l}` in this program file",
                            i.text
                        ),
                    );
                    return String::new();
                };
                gate(format!("__pc{u} := {seg}; __j{u} := TRUE;"))
            }
            "RET" | "TND" => {
                let u = level.seg.unwrap_or(0);
                let tnd = if i.mn == "TND" { "__tnd := TRUE; " } else { "" };
                gate(format!("{tnd}__pc{u} := -1; __j{u} := TRUE;"))
            }
            other => {
                // Every row of the table has a case above.
                self.err(
                    Code::E231,
                    i.span,
                    format!("`{other}`: this SLC-500 instruction is not implemented by automat"),
                );
                String::new()
            }
        }
    }

    /// The file instructions: COP, FLL, the FIFO pair FFL/FFU and the bit
    /// shifts BSL/BSR over a run of words (`#N7:10`).
    fn file_ins(&mut self, n: u32, r: usize, i: &Ins) -> String {
        let ops = &i.ops;
        let op = |k: usize| ops.get(k).cloned().unwrap_or(Operand::Int(0));
        let len = |k: usize| match ops.get(k) {
            Some(Operand::Int(v)) => *v,
            _ => 1,
        };
        let at = run_at;
        match i.mn {
            "COP" => {
                if is_real(&op(0)) != is_real(&op(1)) {
                    self.err(Code::E232, i.span, format!("LAD {n} rung {r}, `{}`: COP copies between files of one kind (integer words or floats)", i.text));
                    return String::new();
                }
                let ((sa, si), (da, di)) = (at(&op(0)), at(&op(1)));
                format!(
                    "    IF __rc THEN FOR __i := 0 TO {} DO {da}[{di} + __i] := {sa}[{si} + __i]; END_FOR; END_IF;\n",
                    len(2) - 1
                )
            }
            "FLL" => {
                let v = if is_real(&op(1)) {
                    match op(0) {
                        o @ (Operand::Addr(_) | Operand::Dyn(_)) if is_real(&o) => word(&o),
                        o => format!("LREAL_TO_REAL({})", lreal(&o)),
                    }
                } else if is_real(&op(0)) {
                    self.err(Code::E232, i.span, format!("LAD {n} rung {r}, `{}`: FLL fills integer words from an integer source", i.text));
                    return String::new();
                } else {
                    int(&op(0))
                };
                let (da, di) = at(&op(1));
                format!(
                    "    IF __rc THEN FOR __i := 0 TO {} DO {da}[{di} + __i] := {v}; END_FOR; END_IF;\n",
                    len(2) - 1
                )
            }
            "FFL" | "FFU" => {
                if !self.ints(n, r, i, ops) {
                    return String::new();
                }
                let ctl = addr(&op(2));
                let l = len(3);
                if let Operand::Int(pos) = op(4) {
                    self.layout.preset(ctl, 1, l);
                    self.layout.preset(ctl, 2, pos);
                }
                let (ca, ci) = (ctl.array(), ctl.index());
                let (c, ln, pos) = (
                    format!("{ca}[{ci}]"),
                    format!("{ca}[{}]", ci + 1),
                    format!("{ca}[{}]", ci + 2),
                );
                let mut s = String::new();
                if i.mn == "FFL" {
                    let (fa, fi) = at(&op(1));
                    let _ = writeln!(s, "    IF __rc AND NOT {c}.15 THEN IF {pos} >= 0 AND {pos} < {ln} AND {pos} < {l} THEN {fa}[{fi} + {pos}] := {}; {pos} := {pos} + 1; END_IF; END_IF;", int(&op(0)));
                    let _ = writeln!(s, "    {c}.15 := __rc;");
                } else {
                    let (fa, fi) = at(&op(0));
                    let dest = word(&op(1));
                    let _ = writeln!(s, "    IF __rc AND NOT {c}.14 THEN IF {pos} > 0 AND {pos} <= {l} THEN {dest} := {fa}[{fi}]; FOR __i := 0 TO INT_TO_DINT({pos}) - 2 DO {fa}[{fi} + __i] := {fa}[{fi} + __i + 1]; END_FOR; {fa}[{fi} + {pos} - 1] := 0; {pos} := {pos} - 1; END_IF; END_IF;");
                    let _ = writeln!(s, "    {c}.14 := __rc;");
                }
                let _ = writeln!(s, "    {c}.13 := {pos} >= {ln}; {c}.12 := {pos} = 0;");
                s
            }
            _ => {
                // BSL / BSR
                let ctl = addr(&op(1));
                let l = len(3);
                self.layout.preset(ctl, 1, l);
                let (ca, ci) = (ctl.array(), ctl.index());
                let c = format!("{ca}[{ci}]");
                let (aa, ai) = at(&op(0));
                let bit = |k: &str| format!("__SLC_GETBIT({aa}[{ai} + ({k}) / 16], ({k}) MOD 16)");
                let set = |k: &str, v: &str| {
                    format!("{aa}[{ai} + ({k}) / 16] := __SLC_SETBIT({aa}[{ai} + ({k}) / 16], ({k}) MOD 16, {v});")
                };
                let src = read_bit(&op(2));
                let last = (l - 1).to_string();
                let body = if i.mn == "BSL" {
                    format!(
                        "{c}.10 := {}; FOR __i := {last} TO 1 BY -1 DO {} END_FOR; {}",
                        bit(&last),
                        set("__i", &bit("__i - 1")),
                        set("0", &src)
                    )
                } else {
                    format!(
                        "{c}.10 := {}; FOR __i := 0 TO {} DO {} END_FOR; {}",
                        bit("0"),
                        l - 2,
                        set("__i", &bit("__i + 1")),
                        set(&last, &src)
                    )
                };
                format!("    IF __rc AND NOT {c}.15 THEN {body} {c}.13 := TRUE; END_IF;\n    IF NOT __rc THEN {c}.13 := FALSE; END_IF;\n    {c}.15 := __rc;\n")
            }
        }
    }

    /// SQO and SQC step through a file of LEN + 1 words (step 0 the
    /// start) on each false -> true change of the rung, wrapping from LEN to
    /// 1: SQO moves the step's word through the mask into the destination,
    /// SQC compares the source with it through the mask (FD, bit 8).
    fn sequencer(&mut self, n: u32, r: usize, i: &Ins) -> String {
        if !self.ints(n, r, i, &i.ops) {
            return String::new();
        }
        let op = |k: usize| i.ops.get(k).cloned().unwrap_or(Operand::Int(0));
        let ctl = addr(&op(3));
        let l = match op(4) {
            Operand::Int(v) => v,
            _ => 1,
        };
        self.layout.preset(ctl, 1, l);
        if let Operand::Int(p) = op(5) {
            self.layout.preset(ctl, 2, p);
        }
        let (ca, ci) = (ctl.array(), ctl.index());
        let (c, ln, pos) = (
            format!("{ca}[{ci}]"),
            format!("{ca}[{}]", ci + 1),
            format!("{ca}[{}]", ci + 2),
        );
        let (fa, fi) = run_at(&op(0));
        let step = format!("{fa}[{fi} + {pos}]");
        let act = if i.mn == "SQO" {
            let d = word(&op(2));
            format!("{d} := __SLC_MVM({step}, {}, {d});", int(&op(1)))
        } else {
            format!(
                "{c}.8 := __SLC_MEQ({}, {}, {step});",
                int(&op(2)),
                int(&op(1))
            )
        };
        format!(
            "    IF __rc AND NOT {c}.15 THEN IF {pos} >= {ln} OR {pos} < 0 THEN {pos} := 1; ELSE {pos} := {pos} + 1; END_IF; IF {pos} <= {l} THEN {act} END_IF; END_IF;\n    {c}.15 := __rc;\n    {c}.13 := {pos} >= {ln};\n"
        )
    }

    /// Bitwise instructions take integer words only.
    fn ints(&mut self, n: u32, r: usize, i: &Ins, ops: &[Operand]) -> bool {
        if ops.iter().any(is_real) {
            self.err(
                Code::E232,
                i.span,
                format!(
                    "LAD {n} rung {r}, `{}`: {} works on integer words, not floats",
                    i.text, i.mn
                ),
            );
            return false;
        }
        true
    }

    /// The remainder slot of a PID block (shared with the timers' slots).
    fn pid_slot(&mut self, a: Address) -> usize {
        self.rem(a)
    }

    /// The state slot of a PID block (`__pidi`, `__pidp`, `__pide`, `__pids`).
    fn pids_index(&mut self, a: Address) -> usize {
        let next = self.pids.len();
        *self.pids.entry((a.file, a.index())).or_insert(next)
    }

    fn rem(&mut self, a: Address) -> usize {
        let next = self.rems.len();
        *self.rems.entry((a.file, a.index())).or_insert(next)
    }

    /// Stores a result in `dest` with the math status: `ie` the exact
    /// integer (DINT) result, `re` the LREAL one (used when `realm`, or
    /// when `dest` is a float).
    /// S:0/1 tells whether this store overflowed: then it is the one to
    /// name when the trap S:5/0 faults at the end of the scan.
    fn store(&mut self, dest: &Operand, realm: bool, ie: &str, re: &str, carry: &str) -> String {
        self.traps.push(self.here.clone());
        let k = self.traps.len();
        let store = self.store_status(dest, realm, ie, re, carry);
        format!("{store} IF S2[0].1 THEN __slc_trap := {k}; END_IF;")
    }

    fn store_status(&self, dest: &Operand, realm: bool, ie: &str, re: &str, carry: &str) -> String {
        let d = word(dest);
        if is_real(dest) {
            let re = if realm || ie.is_empty() {
                re.to_string()
            } else {
                format!("DINT_TO_LREAL({ie})")
            };
            format!("{d} := __SLC_REAL({re}, S2[0], S2[5]);")
        } else if realm || ie.is_empty() {
            format!("{d} := __SLC_INT(__SLC_ROUND({re}), {carry}, S2[0], S2[5]);")
        } else {
            format!("{d} := __SLC_INT({ie}, {carry}, S2[0], S2[5]);")
        }
    }
}
