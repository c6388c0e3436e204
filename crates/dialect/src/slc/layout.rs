//! The data files in memory: each file's size (declared by `DATA`, else
//! the highest element used), its direct address, its initial values, and
//! the globals declaring them and the symbols.
//!
//! `I1` starts at `%IW0` and `O0` at `%QW0` (slot s, word w is word
//! `s * 8 + w`: `I:1/1` is `%IX16.1`); S2, then the B, T, C, R, N files in
//! file-number order, lie in `%MW` from word 0, and the F files in `%MD` at
//! even words. S2 has at least 16 words.

use super::parse::{Operand, Project};
use automat_base::slc::{Address, FileType, Part, IO_SLOT_WORDS};
use automat_base::{Code, Diagnostic};
use std::collections::BTreeMap;
use std::fmt::Write;

pub struct File {
    pub ty: FileType,
    /// Elements (I/O: slots).
    pub elements: u32,
    /// The first word (F: the first double word) in its area.
    pub base: u32,
    /// Initial values by word (F: by element).
    pub init: BTreeMap<u32, Operand>,
}

impl File {
    fn words(&self) -> u32 {
        match self.ty {
            FileType::I | FileType::O => self.elements * IO_SLOT_WORDS,
            t => self.elements * t.words(),
        }
    }
}

pub struct Layout {
    /// By (file number).
    pub files: BTreeMap<u32, File>,
}

impl Layout {
    pub fn new(p: &mut Project) -> Layout {
        let mut sizes: BTreeMap<u32, (FileType, u32)> = BTreeMap::new();
        sizes.insert(2, (FileType::S, 16));
        let mut declared: BTreeMap<u32, u32> = BTreeMap::new();
        for d in &p.data {
            declared.insert(d.file, d.elements);
            let e = sizes.entry(d.file).or_insert((d.ty, 0));
            e.1 = e.1.max(d.elements);
        }
        for (a, span) in &p.used {
            let need = a.elem + 1;
            if let Some(&n) = declared.get(&a.file) {
                if need > n {
                    p.diags.push(Diagnostic::error(
                        Code::E234,
                        *span,
                        format!(
                            "`{}{}:{}` lies beyond data file {}{} (declared with {n} element{})",
                            if a.file <= 2 {
                                String::new()
                            } else {
                                a.ty.letter().to_string()
                            },
                            if a.file <= 2 {
                                a.ty.letter().to_string()
                            } else {
                                a.file.to_string()
                            },
                            a.elem,
                            a.ty.letter(),
                            a.file,
                            if n == 1 { "" } else { "s" }
                        ),
                    ));
                    continue;
                }
            }
            let e = sizes.entry(a.file).or_insert((a.ty, 0));
            e.1 = e.1.max(need);
        }
        let mut files = BTreeMap::new();
        let mut m_word = 0u32;
        for (&n, &(ty, elements)) in &sizes {
            let mut f = File {
                ty,
                elements,
                base: 0,
                init: BTreeMap::new(),
            };
            match ty {
                FileType::I | FileType::O => {}
                FileType::F => {
                    m_word += m_word % 2;
                    f.base = m_word / 2;
                    m_word += elements * 2;
                }
                _ => {
                    f.base = m_word;
                    m_word += f.words();
                }
            }
            if let Some(d) = p.data.iter().find(|d| d.file == n) {
                for (k, v) in d.init.iter().enumerate() {
                    f.init.insert(k as u32, v.clone());
                }
            }
            files.insert(n, f);
        }
        Layout { files }
    }

    /// Sets a word's initial value (a timer's or counter's PRE and ACC as
    /// the instruction gives them) unless the data-file table gave one.
    pub fn preset(&mut self, a: Address, word: u32, v: i64) {
        if let Some(f) = self.files.get_mut(&a.file) {
            f.init.entry(a.index() + word).or_insert(Operand::Int(v));
        }
    }

    /// The direct address of an address's word or bit.
    pub fn direct(&self, a: Address) -> Option<String> {
        let f = self.files.get(&a.file)?;
        let area = match a.ty {
            FileType::I => 'I',
            FileType::O => 'Q',
            _ => 'M',
        };
        if a.ty == FileType::F {
            return Some(format!("%MD{}", f.base + a.index()));
        }
        let word = f.base + a.index();
        Some(match a.part {
            Part::Bit(_, b) => format!("%{area}X{}.{}", word * 2 + b / 8, b % 8),
            _ => format!("%{area}W{word}"),
        })
    }

    /// The VAR_GLOBAL block: the files and the symbols.
    pub fn globals(&self, p: &Project) -> String {
        let mut s = String::from("VAR_GLOBAL\n");
        for (n, f) in &self.files {
            let name = format!("{}{n}", f.ty.letter());
            let (area, ty) = match f.ty {
                FileType::I => ("%IW", "INT"),
                FileType::O => ("%QW", "INT"),
                FileType::F => ("%MD", "REAL"),
                _ => ("%MW", "INT"),
            };
            let len = if f.ty == FileType::F {
                f.elements
            } else {
                f.words()
            };
            let _ = write!(
                s,
                "    {name} AT {area}{} : ARRAY[0..{}] OF {ty}",
                f.base,
                len - 1
            );
            if !f.init.is_empty() {
                let vals: Vec<String> = (0..=f.init.keys().max().copied().unwrap_or(0))
                    .map(|k| match f.init.get(&k) {
                        Some(Operand::Int(v)) if f.ty == FileType::F => format!("{v}.0"),
                        Some(Operand::Int(v)) if *v > 32767 => format!("{}", v - 65536),
                        Some(Operand::Int(v)) => v.to_string(),
                        Some(Operand::Real(v)) => real(*v),
                        _ if f.ty == FileType::F => "0.0".into(),
                        _ => "0".into(),
                    })
                    .collect();
                let _ = write!(s, " := [{}]", vals.join(", "));
            }
            s.push_str(";\n");
        }
        for sym in &p.symbols {
            if sym.addr.is_structure() {
                continue;
            }
            let Some(at) = self.direct(sym.addr) else {
                continue;
            };
            let ty = if sym.addr.is_bit() {
                "BOOL"
            } else if sym.addr.ty == FileType::F {
                "REAL"
            } else {
                "INT"
            };
            // The alias is declared after its file, so it must carry the
            // word's initial value or its own default would overwrite it.
            let init = self
                .files
                .get(&sym.addr.file)
                .and_then(|f| f.init.get(&sym.addr.index()))
                .map(|v| match (v, sym.addr.part) {
                    (Operand::Int(v), Part::Bit(_, b)) => {
                        let set = (v >> b) & 1 == 1;
                        format!(" := {}", if set { "TRUE" } else { "FALSE" })
                    }
                    (Operand::Int(v), _) if sym.addr.ty == FileType::F => format!(" := {v}.0"),
                    (Operand::Int(v), _) if *v > 32767 => format!(" := {}", v - 65536),
                    (Operand::Int(v), _) => format!(" := {v}"),
                    (Operand::Real(v), _) if sym.addr.ty == FileType::F => {
                        format!(" := {}", real(*v))
                    }
                    _ => String::new(),
                })
                .unwrap_or_default();
            let _ = writeln!(s, "    {} AT {at} : {ty}{init};", sym.name);
        }
        s.push_str("    __slc_started : BOOL;\n    __slc_last : LINT;\n    __slc_fault : __SLC_MAJOR_FAULT;\nEND_VAR\n\n");
        s
    }
}

/// A REAL literal (`1.5E0`, `2.0E3`).
pub fn real(v: f64) -> String {
    let s = format!("{v:E}");
    match s.split_once('E') {
        Some((m, e)) if !m.contains('.') => format!("{m}.0E{e}"),
        _ => s,
    }
}
