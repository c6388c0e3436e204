//! Indexed and indirect addresses: the ones whose word (or bit) is found
//! at run time.
//!
//! - indexed `#N7:5`: the word `5 + S:24` of N7 (the index register S:24
//!   holds an offset in elements of the file: words of B and N, floats of F);
//! - indirect `N7:[N7:0]` (the element is the value of N7:0), `N[N7:0]:1`
//!   (the file number is the value of N7:0), `B3:[N7:0]/5`, `B3:0/[N7:2]`
//!   (the bit of the word) and the flat bit `B3/[N7:1]` (bit N7:1 of the
//!   file), as RSLogix 500 writes them.
//!
//! The emitter computes the word index before the instruction runs
//! (`__ix[k]`, the bit in `__ib[k]`, the file in `__if[k]`) and checks it
//! against the data file: outside it, the PLC stops with an SLC major fault
//! naming the rung and the instruction (never an engine's bounds check).

use automat_base::slc::{self, Address, FileType, Part};
use automat_base::slc_indirect::{self, Indirect};
use std::fmt::Write;

/// An operand whose address is resolved at run time: the address as
/// `automat_base::slc_indirect` parses it, with its slot in the generated
/// code.
#[derive(Clone, Debug, PartialEq)]
pub struct Dynamic {
    pub at: Indirect,
    /// This operand's slot in `__ix`, `__ib`, `__if`, `__iv`.
    pub slot: usize,
    /// As written (upper case), for messages and drawings.
    pub text: String,
}

/// A `Dynamic` reads as its address (`d.addr`, `d.elem_from`, ...).
impl std::ops::Deref for Dynamic {
    type Target = Indirect;
    fn deref(&self) -> &Indirect {
        &self.at
    }
}

/// Does the operand text name an indexed or indirect address?
pub fn is_dynamic(up: &str) -> bool {
    slc_indirect::is_dynamic(up)
}

/// Parses an indexed or indirect address (`up` in upper case).
pub fn parse(up: &str, slot: usize) -> Result<Dynamic, String> {
    Ok(Dynamic {
        at: slc_indirect::parse(up)?,
        slot,
        text: up.to_string(),
    })
}

impl Dynamic {
    /// The direct addresses it reads the pointers from.
    pub fn pointers(&self) -> impl Iterator<Item = Address> + '_ {
        self.file_from
            .iter()
            .chain(&self.elem_from)
            .chain(&self.bit_from)
            .copied()
    }

    /// A bit (BOOL)?
    pub fn is_bit(&self) -> bool {
        self.addr.is_bit()
    }

    /// A float?
    pub fn is_real(&self) -> bool {
        self.addr.ty == FileType::F
    }

    /// The word (INT, REAL) it names once resolved, as an ST place.
    pub fn word(&self) -> String {
        if self.file_from.is_some() {
            format!("__iv[{}]", self.slot)
        } else {
            format!("{}[__ix[{}]]", self.addr.array(), self.slot)
        }
    }

    /// The bit number in its word, as ST.
    fn bit_number(&self) -> String {
        match (self.bit_from, self.addr.part) {
            (Some(_), _) => format!("__ib[{}]", self.slot),
            (None, Part::Bit(_, b)) => b.to_string(),
            _ => "0".into(),
        }
    }

    /// The bit's value, as ST.
    pub fn read_bit(&self) -> String {
        format!("__SLC_GETBIT({}, {})", self.word(), self.bit_number())
    }

    /// Writes `v` (BOOL ST) to the bit.
    pub fn write_bit(&self, v: &str) -> String {
        let w = self.word();
        format!("{w} := __SLC_SETBIT({w}, {}, {v});", self.bit_number())
    }
}

/// The marker ending a run-time check line of the generated ST: the
/// fault raised on that line means `Emitter::faults[k]`.
pub fn fault_marker(k: usize) -> String {
    format!("(* slc check {k} *)")
}

/// The array name standing for the file of an indirect file operand
/// (`#N[N7:0]:0`, slot `k`) in an instruction's ST until the `CASE` over
/// the files of its type replaces it.
pub fn file_placeholder(k: usize) -> String {
    format!("__SLC_FILE_{k}__")
}

impl super::emit::Emitter<'_> {
    /// `body`, an instruction working on the run of `words` words from the
    /// file operand `d` (`#N7:[N7:0]`, `#N[N7:0]:[N7:1]`), preceded by the
    /// ST finding its first word (`__ix[k]`) and checking that the run lies
    /// in the data file: outside it, an SLC major fault naming the operand.
    /// With an indirect file number, one copy of `body` per file of the
    /// type, chosen at run time.
    pub(super) fn file_run(&mut self, d: &Dynamic, words: u32, body: &str) -> String {
        let k = d.slot;
        let run_check = |this: &mut Self, file: u32| -> String {
            let Some(f) = this.layout.files.get(&file) else {
                return String::new();
            };
            let len = f.elements;
            let name = format!("{}{file}", f.ty.letter());
            let what = format!(
                "file operand `{}`: the run of {words} {} from its first element lies outside data file {name} ({} 0 to {})",
                d.text,
                if f.ty == FileType::F { "elements" } else { "words" },
                if f.ty == FileType::F { "elements" } else { "words" },
                len.saturating_sub(1)
            );
            this.check(&format!("__ix[{k}] + {words} > {len}"), what)
        };
        let Some(f) = d.file_from else {
            let find = self.index_in(d, d.addr.file);
            let check = run_check(self, d.addr.file);
            return format!("{find}{check}{body}");
        };
        let files = self.files_of(d.addr.ty);
        let mut s = file_case(k, f);
        for &n in &files {
            let find = self.index_in(d, n);
            let check = run_check(self, n);
            let arr = format!("{}{n}", d.addr.ty.letter());
            let _ = write!(
                s,
                "    {n}:\n{find}{check}{}",
                body.replace(&file_placeholder(k), &arr)
            );
        }
        s += &self.no_such_file(d, "file operand", &files);
        s
    }

    /// The numbers of the project's data files of type `ty`.
    fn files_of(&self, ty: FileType) -> Vec<u32> {
        self.layout
            .files
            .iter()
            .filter(|(_, f)| f.ty == ty)
            .map(|(n, _)| *n)
            .collect()
    }

    /// The end of the CASE over an indirect file number: any other number
    /// is a major fault naming `d` and the files there are.
    fn no_such_file(&mut self, d: &Dynamic, what: &str, files: &[u32]) -> String {
        let k = d.slot;
        let list = files
            .iter()
            .map(|n| n.to_string())
            .collect::<Vec<_>>()
            .join(", ");
        let what = format!(
            "{what} `{}`: the file number is not one of the {} files of the project ({list})",
            d.text,
            d.addr.ty.letter()
        );
        let mut s = String::from("    ELSE\n");
        s += &self.check(&format!("__if[{k}] = __if[{k}]"), what);
        s.push_str("    END_CASE;\n");
        s
    }

    /// A check: the PLC stops (the subrange fault of `__slc_fault`) when
    /// `bad` holds, the fault saying `what` and the instruction.
    pub(super) fn check(&mut self, bad: &str, what: String) -> String {
        let k = self.faults.len();
        self.faults
            .push(format!("SLC major fault: {what} ({})", self.here));
        format!(
            "    __slc_fault := BOOL_TO_INT({bad}); {}\n",
            fault_marker(k)
        )
    }

    /// The ST resolving `d` in data file `file` into `__ix` (and `__ib`),
    /// with its checks.
    fn index_in(&mut self, d: &Dynamic, file: u32) -> String {
        let k = d.slot;
        let Some(f) = self.layout.files.get(&file) else {
            return String::new();
        };
        let (ty, elements) = (f.ty, f.elements);
        let io = matches!(ty, FileType::I | FileType::O);
        let stride = if io { slc::IO_SLOT_WORDS } else { ty.words() };
        let len = if ty == FileType::F {
            elements
        } else {
            elements * stride
        };
        let name = format!("{}{file}", ty.letter());
        let word_of = |a: Address| format!("INT_TO_DINT({})", a.st_path().unwrap_or_default());
        let text = d.text.clone();
        let mut s = String::new();
        if d.indexed {
            let _ = writeln!(
                s,
                "    __ix[{k}] := {} + INT_TO_DINT(S2[24]);",
                d.addr.index()
            );
            let what = format!(
                "indexed address `{text}` + S:24 lies outside data file {name} ({} 0 to {})",
                if ty == FileType::F {
                    "elements"
                } else {
                    "words"
                },
                len - 1
            );
            s += &self.check(&format!("__ix[{k}] < 0 OR __ix[{k}] > {}", len - 1), what);
            return s;
        }
        if let (true, Some(b)) = (d.flat, d.bit_from) {
            let _ = writeln!(s, "    __ib[{k}] := {};", word_of(b));
            let what = format!(
                "indirect address `{text}`: the bit lies outside data file {name} (bits 0 to {})",
                len * 16 - 1
            );
            s += &self.check(
                &format!("__ib[{k}] < 0 OR __ib[{k}] > {}", len * 16 - 1),
                what,
            );
            let _ = writeln!(
                s,
                "    __ix[{k}] := __ib[{k}] / 16; __ib[{k}] := __ib[{k}] MOD 16;"
            );
            return s;
        }
        let w = match d.addr.part {
            Part::Element => 0,
            Part::Word(w) | Part::Bit(w, _) => w,
        };
        match d.elem_from {
            Some(e) => {
                let _ = writeln!(s, "    __ix[{k}] := {};", word_of(e));
                let what = format!(
                    "indirect address `{text}`: the element is not one of data file {name} (0 to {})",
                    elements - 1
                );
                s += &self.check(
                    &format!("__ix[{k}] < 0 OR __ix[{k}] > {}", elements - 1),
                    what,
                );
                let _ = writeln!(s, "    __ix[{k}] := __ix[{k}] * {stride} + {w};");
            }
            None => {
                let elem = d.addr.elem;
                if elem >= elements {
                    // An indirect file smaller than the element named.
                    let what = format!(
                        "indirect address `{text}`: element {elem} is not one of data file {name} (0 to {})",
                        elements - 1
                    );
                    s += &self.check(&format!("__ix[{k}] = __ix[{k}]"), what);
                }
                let _ = writeln!(s, "    __ix[{k}] := {};", elem * stride + w);
            }
        }
        if let Some(b) = d.bit_from {
            let _ = writeln!(s, "    __ib[{k}] := {};", word_of(b));
            let what = format!("indirect address `{text}`: the bit is not 0 to 15");
            s += &self.check(&format!("__ib[{k}] < 0 OR __ib[{k}] > 15"), what);
        }
        s
    }

    /// The ST run before an instruction with the operand `d` (its word
    /// found and checked) and after it (a destination in a file found at
    /// run time written back).
    pub(super) fn resolve(&mut self, d: &Dynamic, dest: bool) -> (String, String) {
        let k = d.slot;
        let Some(f) = d.file_from else {
            return (self.index_in(d, d.addr.file), String::new());
        };
        let files = self.files_of(d.addr.ty);
        if files.is_empty() {
            let what = format!(
                "indirect address `{}`: the project has no {} file",
                d.text,
                d.addr.ty.letter()
            );
            return (
                self.check(&format!("__ix[{k}] = __ix[{k}]"), what),
                String::new(),
            );
        }
        let mut before = file_case(k, f);
        let mut after = format!("    CASE __if[{k}] OF\n");
        for &n in &files {
            let code = self.index_in(d, n);
            let arr = format!("{}{n}", d.addr.ty.letter());
            let _ = write!(
                before,
                "    {n}:\n{code}    __iv[{k}] := {arr}[__ix[{k}]];\n"
            );
            let _ = writeln!(after, "    {n}: {arr}[__ix[{k}]] := __iv[{k}];");
        }
        before += &self.no_such_file(d, "indirect address", &files);
        after.push_str("    END_CASE;\n");
        (before, if dest { after } else { String::new() })
    }
}

/// The start of the CASE over the file number read from `from` into
/// `__if[k]`.
fn file_case(k: usize, from: Address) -> String {
    format!(
        "    __if[{k}] := INT_TO_DINT({});\n    CASE __if[{k}] OF\n",
        from.st_path().unwrap_or_default()
    )
}
