//! `.slc` text → program files of rungs, the symbol table and the
//! data-file table (the format is in docs/allen-bradley.md).
//!
//! Line-oriented: `LAD n [name]` starts a program file, `SYM`, `DATA` and
//! `RC` lines are table entries and rung comments, `;` starts a comment
//! line, and anything else is rung text: one rung per line, or `SOR … EOR`
//! over as many lines as it takes. Operands are resolved here (symbols to
//! addresses, kinds checked against the instruction's table row); an error
//! is reported once, at the instruction, and the rung is dropped.

// Spans and names of rungs, files, symbols and declarations not read by the
// ST generation are kept for the ladder drawing (issue 12 point 6).
#![allow(dead_code)]

use super::dynamic::{self, Dynamic};
use super::instr::{self, Kind};
use automat_base::slc::{self, Address, FileType, Part};
use automat_base::{Code, Diagnostic, FileId, Span};
use std::collections::BTreeMap;

/// One operand as the emitter needs it.
#[derive(Clone, Debug, PartialEq)]
pub enum Operand {
    Addr(Address),
    Int(i64),
    Real(f64),
    /// A timer's time base in milliseconds (0.01 s → 10).
    Base(i64),
    /// A program file (JSR) or label (JMP, LBL) number.
    Number(u32),
    /// An indexed (`#N7:0`) or indirect (`N7:[N7:0]`) word or bit.
    Dyn(Box<Dynamic>),
}

#[derive(Clone, Debug)]
pub struct Ins {
    pub mn: &'static str,
    pub ops: Vec<Operand>,
    pub span: Span,
    /// The instruction as written, for messages.
    pub text: String,
}

#[derive(Clone, Debug)]
pub enum Elem {
    Bst(Span),
    Nxb(Span),
    Bnd(Span),
    Ins(Ins),
}

#[derive(Clone, Debug)]
pub struct Rung {
    pub elems: Vec<Elem>,
    pub span: Span,
    pub comment: Option<String>,
    /// Its number in its program file (from 0).
    pub number: usize,
}

#[derive(Clone, Debug)]
pub struct LadFile {
    pub number: u32,
    pub name: String,
    pub span: Span,
    pub rungs: Vec<Rung>,
    /// Rungs read, those dropped for an error included.
    pub seen: usize,
}

#[derive(Clone, Debug)]
pub struct Symbol {
    pub name: String,
    pub addr: Address,
    pub desc: String,
}

#[derive(Clone, Debug)]
pub struct DataDecl {
    pub ty: FileType,
    pub file: u32,
    pub elements: u32,
    pub init: Vec<Operand>,
    pub span: Span,
}

/// Everything read from the `.slc` files of a project.
#[derive(Default)]
pub struct Project {
    pub files: BTreeMap<u32, LadFile>,
    pub symbols: Vec<Symbol>,
    pub data: Vec<DataDecl>,
    /// Every address an instruction names, with where (for sizing and the
    /// "beyond a declared file" check).
    pub used: Vec<(Address, Span)>,
    pub diags: Vec<Diagnostic>,
    /// Indexed and indirect operands read so far (each has its slot).
    pub dynamic: usize,
}

/// A word of a line with its byte range in the file.
#[derive(Clone, Debug)]
struct Tok {
    text: String,
    up: String,
    start: u32,
    end: u32,
}

fn words(line: &str, at: u32) -> Vec<Tok> {
    let mut out = Vec::new();
    let b = line.as_bytes();
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        if c.is_ascii_whitespace() || c == b',' {
            i += 1;
            continue;
        }
        let start = i;
        if c == b'"' {
            i += 1;
            while i < b.len() && b[i] != b'"' {
                i += 1;
            }
            i = (i + 1).min(b.len());
        } else {
            while i < b.len() && !b[i].is_ascii_whitespace() && b[i] != b',' {
                i += 1;
            }
        }
        while i < b.len() && !line.is_char_boundary(i) {
            i += 1;
        }
        let text = &line[start..i];
        out.push(Tok {
            text: text.to_string(),
            up: text.to_ascii_uppercase(),
            start: at + start as u32,
            end: at + i as u32,
        });
    }
    out
}

/// Is this token a symbol name (letters, digits, `_`, not starting with a
/// digit) rather than an address or a constant?
fn is_name(s: &str) -> bool {
    s.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_')
        && s.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_')
}

pub struct Reader<'a> {
    pub p: &'a mut Project,
    file: FileId,
    /// The program file rungs go to.
    lad: u32,
    comment: Option<String>,
    /// An open `SOR`: its tokens so far and where it started.
    open: Option<(Vec<Tok>, u32)>,
}

impl<'a> Reader<'a> {
    pub fn new(p: &'a mut Project, file: FileId) -> Reader<'a> {
        Reader {
            p,
            file,
            lad: 2,
            comment: None,
            open: None,
        }
    }

    fn span(&self, t: &Tok) -> Span {
        Span::new(self.file, t.start, t.end)
    }

    fn err(&mut self, code: Code, span: Span, msg: String) {
        self.p.diags.push(Diagnostic::error(code, span, msg));
    }

    /// First pass over a file: the symbol and data tables (so rungs above
    /// a `SYM` line may use the symbol).
    pub fn tables(&mut self, text: &str) {
        let mut offset = 0u32;
        for line in text.split_inclusive('\n') {
            let at = offset;
            offset += line.len() as u32;
            let toks = words(line, at);
            match toks.first().map(|t| t.up.as_str()) {
                Some("SYM") => self.symbol(&toks),
                Some("DATA") => self.data(&toks),
                _ => {}
            }
        }
    }

    /// Second pass: program files and rungs.
    pub fn rungs(&mut self, text: &str) {
        let mut offset = 0u32;
        for line in text.split_inclusive('\n') {
            let at = offset;
            offset += line.len() as u32;
            if line.trim_start().starts_with(';') {
                continue;
            }
            let toks = words(line, at);
            let Some(first) = toks.first() else { continue };
            if self.open.is_none() {
                match first.up.as_str() {
                    "SYM" | "DATA" => continue,
                    "RC" => {
                        let rest = line.trim_start()[2..].trim();
                        self.comment = Some(rest.trim_matches('"').to_string());
                        continue;
                    }
                    "LAD" => {
                        self.lad_header(&toks);
                        continue;
                    }
                    _ => {}
                }
            }
            for t in toks {
                match (t.up.as_str(), self.open.is_some()) {
                    ("SOR", false) => self.open = Some((Vec::new(), t.start)),
                    ("SOR", true) => {
                        let s = self.span(&t);
                        self.err(
                            Code::E235,
                            s,
                            "`SOR` inside a rung: the rung before has no `EOR`".into(),
                        );
                    }
                    ("EOR", true) => {
                        if let Some((body, start)) = self.open.take() {
                            self.rung(&body, Span::new(self.file, start, t.end));
                        }
                    }
                    ("EOR", false) => {
                        let s = self.span(&t);
                        self.err(Code::E235, s, "`EOR` without `SOR`".into());
                    }
                    (_, true) => {
                        if let Some((body, _)) = self.open.as_mut() {
                            body.push(t);
                        }
                    }
                    (_, false) => {
                        // One rung per line.
                        let rest: Vec<Tok> = words(line, at);
                        let span = Span::new(
                            self.file,
                            rest.first().map_or(at, |t| t.start),
                            rest.last().map_or(at, |t| t.end),
                        );
                        self.rung(&rest, span);
                        break;
                    }
                }
            }
        }
        if let Some((_, start)) = self.open.take() {
            self.err(
                Code::E235,
                Span::new(self.file, start, start + 3),
                "the rung started by `SOR` has no `EOR`".into(),
            );
        }
    }

    fn lad_header(&mut self, toks: &[Tok]) {
        let span = Span::new(self.file, toks[0].start, toks.last().map_or(0, |t| t.end));
        let n = toks.get(1).and_then(|t| t.up.parse::<u32>().ok());
        match n {
            Some(n) if (2..=255).contains(&n) => {
                let name = toks[2..]
                    .iter()
                    .map(|t| t.text.as_str())
                    .collect::<Vec<_>>()
                    .join(" ");
                match self.p.files.entry(n) {
                    std::collections::btree_map::Entry::Occupied(_) => self.err(
                        Code::E237,
                        span,
                        format!("program file LAD {n} is defined twice"),
                    ),
                    std::collections::btree_map::Entry::Vacant(v) => {
                        v.insert(LadFile {
                            number: n,
                            name,
                            span,
                            rungs: Vec::new(),
                            seen: 0,
                        });
                    }
                }
                self.lad = n;
            }
            _ => self.err(
                Code::E237,
                span,
                "`LAD n`: a program file number is 2 (the main file) to 255".into(),
            ),
        }
    }

    fn symbol(&mut self, toks: &[Tok]) {
        let span = Span::new(self.file, toks[0].start, toks.last().map_or(0, |t| t.end));
        let (Some(a), Some(name)) = (toks.get(1), toks.get(2)) else {
            self.err(
                Code::E238,
                span,
                "a symbol line is `SYM ADDRESS NAME [\"description\"]`".into(),
            );
            return;
        };
        let addr = match slc::parse(&a.text) {
            Ok(addr) => addr,
            Err(why) => {
                let s = self.span(a);
                self.err(Code::E236, s, why);
                return;
            }
        };
        // `N7`, `B3`: the data files' own arrays.
        let file_like = name.up.len() > 1
            && name
                .up
                .chars()
                .next()
                .and_then(FileType::from_letter)
                .is_some()
            && name.up[1..].bytes().all(|b| b.is_ascii_digit());
        if !is_name(&name.text)
            || file_like
            || name.up == "SLC"
            || slc::looks_like(&name.text)
            || instr::find(&name.up).is_some()
            || name.up.starts_with("__")
        {
            let s = self.span(name);
            self.err(Code::E238, s, format!("symbol `{}`: a symbol is letters, digits and `_`, not an instruction or an address, and does not start with a digit or `__`", name.text));
            return;
        }
        if self
            .p
            .symbols
            .iter()
            .any(|s| s.name.eq_ignore_ascii_case(&name.text))
        {
            let s = self.span(name);
            self.err(
                Code::E238,
                s,
                format!("symbol `{}` is defined twice", name.text),
            );
            return;
        }
        let desc = toks[3..]
            .iter()
            .map(|t| t.text.trim_matches('"'))
            .collect::<Vec<_>>()
            .join(" ");
        self.p.symbols.push(Symbol {
            name: name.text.clone(),
            addr,
            desc,
        });
        self.p.used.push((addr, self.span(a)));
    }

    fn data(&mut self, toks: &[Tok]) {
        let span = Span::new(self.file, toks[0].start, toks.last().map_or(0, |t| t.end));
        let bad = "a data-file line is `DATA <type><number> <elements> [= values...]` (DATA N7 10 = 1 2 3)";
        let (Some(f), Some(n)) = (toks.get(1), toks.get(2)) else {
            self.err(Code::E238, span, bad.into());
            return;
        };
        let Some(ty) = f.up.chars().next().and_then(FileType::from_letter) else {
            self.err(Code::E238, span, bad.into());
            return;
        };
        let num = if f.up.len() == 1 {
            ty.fixed_number()
        } else {
            f.up[1..].parse::<u32>().ok()
        };
        let Some(num) = num.filter(|&k| k <= 255) else {
            self.err(Code::E238, span, bad.into());
            return;
        };
        match FileType::of_number(num) {
            Some(t) if t != ty => {
                self.err(
                    Code::E238,
                    span,
                    format!("file {num} is a {} file", t.letter()),
                );
                return;
            }
            None if matches!(ty, FileType::O | FileType::I | FileType::S) => {
                self.err(Code::E238, span, "O, I and S are files 0, 1 and 2".into());
                return;
            }
            _ => {}
        }
        let max = if matches!(ty, FileType::I | FileType::O) {
            slc::MAX_SLOT + 1
        } else {
            slc::MAX_ELEMENT + 1
        };
        let Some(elements) = n.up.parse::<u32>().ok().filter(|&e| (1..=max).contains(&e)) else {
            let s = self.span(n);
            self.err(
                Code::E238,
                s,
                format!("a data file has 1 to {max} elements"),
            );
            return;
        };
        let mut init = Vec::new();
        let words = if matches!(ty, FileType::I | FileType::O) {
            elements * slc::IO_SLOT_WORDS
        } else {
            elements * ty.words()
        };
        match toks.get(3).map(|t| t.up.as_str()) {
            None => {}
            Some("=") => {
                for t in &toks[4..] {
                    let v = constant(&t.up).filter(|v| {
                        ty == FileType::F
                            || matches!(v, Operand::Int(i) if (-32768..=65535).contains(i))
                    });
                    match v {
                        Some(v) => init.push(v),
                        None => {
                            let s = self.span(t);
                            self.err(
                                Code::E238,
                                s,
                                format!(
                                    "`{}`: an initial value of a {} file is {}",
                                    t.text,
                                    ty.letter(),
                                    if ty == FileType::F {
                                        "a number"
                                    } else {
                                        "an integer -32768 to 65535"
                                    }
                                ),
                            );
                            return;
                        }
                    }
                }
                if init.len() as u32 > words {
                    self.err(
                        Code::E238,
                        span,
                        format!("{} initial values for {words} words", init.len()),
                    );
                    return;
                }
            }
            Some(_) => {
                self.err(Code::E238, span, bad.into());
                return;
            }
        }
        if self.p.data.iter().any(|d| d.ty == ty && d.file == num) {
            self.err(
                Code::E238,
                span,
                format!("data file {}{num} is declared twice", ty.letter()),
            );
            return;
        }
        self.p.data.push(DataDecl {
            ty,
            file: num,
            elements,
            init,
            span,
        });
    }

    /// Reads one rung's tokens into instructions; drops the rung on an
    /// error (reported once).
    fn rung(&mut self, toks: &[Tok], span: Span) {
        let comment = self.comment.take();
        // The program file exists once it has a rung, even one with an
        // error; rungs are numbered from 0 in each file, those dropped for
        // an error included.
        let (lad, file) = (self.lad, self.file);
        let number = {
            let f = self.p.files.entry(lad).or_insert_with(|| LadFile {
                number: lad,
                name: String::new(),
                span: Span::new(file, 0, 0),
                rungs: Vec::new(),
                seen: 0,
            });
            f.seen += 1;
            f.seen - 1
        };
        let at = format!("LAD {lad} rung {number}");
        let mut elems = Vec::new();
        let mut depth = 0u32;
        let mut i = 0;
        let mut ok = true;
        while i < toks.len() {
            let t = &toks[i];
            let s = self.span(t);
            match t.up.as_str() {
                "BST" => {
                    depth += 1;
                    elems.push(Elem::Bst(s));
                    i += 1;
                    continue;
                }
                "NXB" | "BND" if depth == 0 => {
                    self.err(
                        Code::E235,
                        s,
                        format!("{at}: `{}` outside a branch: no `BST` opened it", t.up),
                    );
                    ok = false;
                    break;
                }
                "NXB" => {
                    elems.push(Elem::Nxb(s));
                    i += 1;
                    continue;
                }
                "BND" => {
                    depth -= 1;
                    elems.push(Elem::Bnd(s));
                    i += 1;
                    continue;
                }
                _ => {}
            }
            let Some(def) = instr::find(&t.up) else {
                let why = if instr::is_unimplemented(&t.up) {
                    (
                        Code::E231,
                        format!(
                            "{at}: `{}`: this SLC-500 instruction is not implemented by automat",
                            t.text
                        ),
                    )
                } else {
                    (
                        Code::E230,
                        format!("{at}: `{}` is not an SLC-500 instruction", t.text),
                    )
                };
                self.err(why.0, s, why.1);
                ok = false;
                break;
            };
            let kinds = def.operands;
            let ops_toks = &toks[i + 1..(i + 1 + kinds.len()).min(toks.len())];
            let end = ops_toks.last().map_or(t.end, |o| o.end);
            let text = std::iter::once(t.text.as_str())
                .chain(ops_toks.iter().map(|o| o.text.as_str()))
                .collect::<Vec<_>>()
                .join(" ");
            let ispan = Span::new(self.file, t.start, end);
            // An operand missing: the next word is an instruction or the end.
            let short = ops_toks.len() < kinds.len()
                || ops_toks.iter().any(|o| {
                    instr::find(&o.up).is_some() || matches!(o.up.as_str(), "BST" | "NXB" | "BND")
                });
            if short {
                self.err(
                    Code::E233,
                    ispan,
                    format!(
                        "{at}, `{text}`: {} takes {} operand(s): {}",
                        def.name,
                        kinds.len(),
                        instr::describe(kinds)
                    ),
                );
                ok = false;
                break;
            }
            let mut ops = Vec::new();
            for (k, o) in kinds.iter().zip(ops_toks) {
                match self.operand(*k, o) {
                    Ok(v) => ops.push(v),
                    Err((code, why)) => {
                        let os = self.span(o);
                        self.err(code, os, format!("{at}, `{text}`: {why}"));
                        ok = false;
                        break;
                    }
                }
            }
            if !ok {
                break;
            }
            if def.name == "PID" && ops.iter().any(|o| matches!(o, Operand::Dyn(_))) {
                self.err(
                    Code::E236,
                    ispan,
                    format!("{at}, `{text}`: PID takes direct addresses only"),
                );
                ok = false;
                break;
            }
            for (o, ot) in ops.iter_mut().zip(ops_toks) {
                match o {
                    Operand::Addr(a) => self.p.used.push((*a, self.span(ot))),
                    Operand::Dyn(d) => {
                        d.slot = self.p.dynamic;
                        self.p.dynamic += 1;
                        let s = self.span(ot);
                        // The file must exist (an indirect file is any of its type).
                        if d.file_from.is_none() {
                            self.p.used.push((d.addr, s));
                        }
                        for a in d.pointers() {
                            self.p.used.push((a, s));
                        }
                        if d.indexed {
                            // The index register S:24.
                            let s24 = Address {
                                ty: FileType::S,
                                file: 2,
                                elem: 24,
                                part: Part::Element,
                            };
                            self.p.used.push((s24, s));
                        }
                    }
                    _ => {}
                }
            }
            // A run of words: its last element is used too.
            let too_long = run_words(def.name, &ops).is_some_and(|words| {
                !matches!(def.name, "BSL" | "BSR")
                    && words > 128 + u32::from(matches!(def.name, "SQO" | "SQC"))
            });
            if too_long {
                self.err(
                    Code::E232,
                    ispan,
                    format!("{at}, `{text}`: the length is 1 to 128 words (BSL, BSR: 2048 bits)"),
                );
                ok = false;
                break;
            }
            for (start, words) in runs(def.name, &ops) {
                let last = Address {
                    elem: start.elem + words - 1,
                    ..start
                };
                if last.elem > slc::MAX_ELEMENT {
                    self.err(
                        Code::E234,
                        ispan,
                        format!(
                            "{at}, `{text}`: the run of {words} words from element {} passes element 255",
                            start.elem
                        ),
                    );
                    ok = false;
                    break;
                }
                self.p.used.push((last, ispan));
            }
            if !ok {
                break;
            }
            elems.push(Elem::Ins(Ins {
                mn: def.name,
                ops,
                span: ispan,
                text,
            }));
            i += 1 + kinds.len();
        }
        if ok && depth > 0 {
            self.err(
                Code::E235,
                span,
                format!("{at}: a branch is not closed: `BST` without its `BND`"),
            );
            ok = false;
        }
        if !ok {
            return;
        }
        if elems.is_empty() {
            return;
        }
        if let Some(f) = self.p.files.get_mut(&lad) {
            f.rungs.push(Rung {
                elems,
                span,
                comment,
                number,
            });
        }
    }

    fn address(&self, t: &Tok) -> Result<Address, String> {
        if let Some(s) = self
            .p
            .symbols
            .iter()
            .find(|s| s.name.eq_ignore_ascii_case(&t.text))
        {
            return Ok(s.addr);
        }
        if dynamic::is_dynamic(&t.up) {
            return Err(format!(
                "`{}`: an indexed (`#`) or indirect (`[ ]`) address is a word or bit operand (a source, a destination, a bit), not a timer, counter, control or block",
                t.text
            ));
        }
        if is_name(&t.text) && !slc::looks_like(&t.text) {
            return Err(format!(
                "`{}` is no address and no symbol of the table",
                t.text
            ));
        }
        slc::parse(&t.text)
    }

    fn operand(&self, kind: Kind, t: &Tok) -> Result<Operand, (Code, String)> {
        let wrong = |what: &str| (Code::E232, format!("`{}` is {what}", t.text));
        match kind {
            Kind::Base => match t.up.as_str() {
                "0.01" | ".01" => Ok(Operand::Base(10)),
                "1.0" | "1" | "1.00" => Ok(Operand::Base(1000)),
                _ => Err(wrong("no time base: 0.01 or 1.0 (seconds)")),
            },
            Kind::Preset => match constant(&t.up) {
                Some(Operand::Int(v)) if (-32768..=32767).contains(&v) => Ok(Operand::Int(v)),
                _ => Err(wrong("no integer constant -32768 to 32767")),
            },
            Kind::File | Kind::Label => {
                let digits = t.up.rsplit(':').next().unwrap_or("");
                let max = if kind == Kind::File { 255 } else { 999 };
                match digits.parse::<u32>() {
                    Ok(n) if n <= max && (kind == Kind::Label || n >= 3) => Ok(Operand::Number(n)),
                    _ if kind == Kind::File => {
                        Err(wrong("no subroutine file number (3 to 255, `U:3` or `3`)"))
                    }
                    _ => Err(wrong("no label number (0 to 999, `Q2:5` or `5`)")),
                }
            }
            Kind::Length => match constant(&t.up) {
                Some(Operand::Int(v)) if (1..=2048).contains(&v) => Ok(Operand::Int(v)),
                _ => Err(wrong("no length (a constant 1 to 128 words, 2048 bits)")),
            },
            Kind::FileRef => {
                let Some(rest) = t.text.strip_prefix('#') else {
                    return Err(wrong(
                        "no file operand: a run of words starts with `#` (`#N7:10`)",
                    ));
                };
                let rest_up = rest.to_ascii_uppercase();
                if dynamic::is_dynamic(&rest_up) {
                    // `#N7:[N7:0]`, `#N[N7:0]:[N7:1]`: a run whose start
                    // (and file) is found at run time, as RSLogix allows.
                    let mut d = dynamic::parse(&rest_up, 0).map_err(|why| (Code::E236, why))?;
                    if d.indexed
                        || d.is_bit()
                        || d.addr.part != Part::Element
                        || d.addr.ty.words() != 1
                        || matches!(d.addr.ty, FileType::I | FileType::O | FileType::S)
                    {
                        return Err((
                            Code::E236,
                            format!(
                                "`{}`: an indirect file operand starts a run of B, N or F elements (`#N7:[N7:0]`, `#N[N7:0]:[N7:1]`)",
                                t.text
                            ),
                        ));
                    }
                    d.text = t.up.clone();
                    return Ok(Operand::Dyn(Box::new(d)));
                }
                let a = slc::parse(rest).map_err(|why| (Code::E236, why))?;
                if a.part != Part::Element
                    || a.ty.words() != 1
                    || matches!(a.ty, FileType::I | FileType::O)
                {
                    return Err(wrong(
                        "no file operand: `#` starts a run of B, N, S or F elements (`#N7:10`)",
                    ));
                }
                Ok(Operand::Addr(a))
            }
            Kind::Source if constant(&t.up).is_some() => match constant(&t.up) {
                Some(Operand::Int(v)) if !(-32768..=32767).contains(&v) => {
                    Err(wrong("an integer constant outside -32768 to 32767"))
                }
                Some(c) => Ok(c),
                None => Err(wrong("no constant")),
            },
            Kind::Source | Kind::Dest | Kind::Bit if dynamic::is_dynamic(&t.up) => {
                let d = dynamic::parse(&t.up, 0).map_err(|why| (Code::E236, why))?;
                let ok = match kind {
                    Kind::Bit => d.is_bit(),
                    _ => !d.is_bit(),
                };
                if !ok {
                    return Err(wrong(if kind == Kind::Bit {
                        "no bit address: an indirect bit is `B3/[N7:1]`, `B3:[N7:0]/5`, `B3:0/[N7:2]`"
                    } else {
                        "no word address: an indexed or indirect word is `#N7:0`, `N7:[N7:0]`, `N[N7:0]:1`"
                    }));
                }
                Ok(Operand::Dyn(Box::new(d)))
            }
            _ => {
                let a = self.address(t).map_err(|why| (Code::E236, why))?;
                let ok = match kind {
                    Kind::Bit => a.is_bit(),
                    Kind::Timer => a.ty == FileType::T && a.part == Part::Element,
                    Kind::Counter => a.ty == FileType::C && a.part == Part::Element,
                    Kind::Structure => a.is_structure(),
                    Kind::Control => a.ty == FileType::R && a.part == Part::Element,
                    Kind::Block => a.ty == FileType::N && a.part == Part::Element,
                    Kind::Source | Kind::Dest => !a.is_bit() && !a.is_structure(),
                    _ => false,
                };
                if ok {
                    Ok(Operand::Addr(a))
                } else {
                    Err(wrong(match kind {
                        Kind::Bit => {
                            "no bit address: a bit is `B3/1`, `I:1/1`, `T4:0/DN`, `N7:0/3`"
                        }
                        Kind::Timer => "no timer: a timer is an element of a T file (`T4:0`)",
                        Kind::Counter => "no counter: a counter is an element of a C file (`C5:0`)",
                        Kind::Structure => {
                            "no timer, counter or control element (`T4:0`, `C5:0`, `R6:0`)"
                        }
                        Kind::Block => {
                            "no PID control block: an element of an N file (`N10:0`, 23 words)"
                        }
                        Kind::Control => "no control element: an element of an R file (`R6:0`)",
                        Kind::Dest => "no word address to write (`N7:0`, `T4:0.PRE`, `F8:1`)",
                        _ => "no word address or constant (`N7:0`, `T4:0.ACC`, `F8:1`, `25`)",
                    }))
                }
            }
        }
    }
}

/// The number of words each file operand of `mn` covers (BSL/BSR: the
/// words holding its bits; SQO/SQC: LEN + 1 steps), `None` for other
/// instructions or a length that is no constant.
pub fn run_words(mn: &str, ops: &[Operand]) -> Option<u32> {
    let n = |k: usize| match ops.get(k) {
        Some(Operand::Int(n)) => u32::try_from(*n).ok(),
        _ => None,
    };
    Some(match mn {
        "COP" | "FLL" => n(2)?.max(1),
        "FFL" | "FFU" => n(3)?.max(1),
        "BSL" | "BSR" => n(3)?.max(1).div_ceil(16),
        "SQO" | "SQC" => n(4)? + 1,
        _ => return None,
    })
}

/// The runs of words a file instruction works on: each one's first
/// element and number of words.
pub fn runs(mn: &str, ops: &[Operand]) -> Vec<(Address, u32)> {
    let (files, len): (&[usize], _) = match mn {
        "COP" => (&[0, 1], ops.get(2)),
        "FLL" => (&[1], ops.get(2)),
        "FFL" => (&[1], ops.get(3)),
        "FFU" | "BSL" | "BSR" => (&[0], ops.get(3)),
        "PID" => {
            return match ops.first() {
                Some(Operand::Addr(a)) => vec![(*a, 23)],
                _ => Vec::new(),
            }
        }
        // Steps 0..=LEN: LEN + 1 words.
        "SQO" | "SQC" => {
            return match (ops.first(), ops.get(4)) {
                (Some(Operand::Addr(a)), Some(Operand::Int(n))) => {
                    vec![(*a, u32::try_from(*n).unwrap_or(0) + 1)]
                }
                _ => Vec::new(),
            }
        }
        _ => return Vec::new(),
    };
    let Some(Operand::Int(n)) = len else {
        return Vec::new();
    };
    let n = u32::try_from(*n).unwrap_or(1).max(1);
    let words = if mn == "BSL" || mn == "BSR" {
        n.div_ceil(16)
    } else {
        n
    };
    files
        .iter()
        .filter_map(|&k| match ops.get(k) {
            Some(Operand::Addr(a)) => Some((*a, words)),
            _ => None,
        })
        .collect()
}

/// A numeric constant: an integer or a real (`1.5`, `-2.0E3`).
pub fn constant(s: &str) -> Option<Operand> {
    let body = s.strip_prefix(['-', '+']).unwrap_or(s);
    if body.is_empty() || !body.starts_with(|c: char| c.is_ascii_digit() || c == '.') {
        return None;
    }
    if body.bytes().all(|b| b.is_ascii_digit()) {
        return s.parse::<i64>().ok().map(Operand::Int);
    }
    s.parse::<f64>()
        .ok()
        .filter(|v| v.is_finite())
        .map(Operand::Real)
}
