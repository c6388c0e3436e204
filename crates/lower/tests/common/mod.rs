//! Test helpers: compile ST text, run the program for N scans, read
//! variables through the symbol table by path (`MAIN.fb.q`, `MAIN.a[2, 1].x`).

#![allow(dead_code)]

use automat_base::{Diagnostic, Interner, SourceMap};
use automat_engine::Engine;
use automat_iec::Elementary as E;
use automat_ir::{Fault, ProgramInstance, SymbolType};
use automat_lower::{lower, LowerOptions};

pub struct Plc {
    pub engine: Engine,
    pub inst: ProgramInstance,
    pub now: i64,
}

pub fn try_build(src: &str, opts: &LowerOptions) -> Result<Plc, Vec<Diagnostic>> {
    let mut sources = SourceMap::new();
    sources.add("test.st", src);
    let mut interner = Interner::new();
    let (units, analysis) = automat_sema::check_sources(&sources, &mut interner);
    if analysis.has_errors() {
        return Err(analysis.diagnostics);
    }
    let program = lower(&units, &analysis, &interner, &sources, opts)?;
    let inst = program
        .tasks
        .first()
        .and_then(|t| t.programs.first())
        .cloned()
        .expect("a program instance");
    Ok(Plc {
        engine: Engine::new(program),
        inst,
        now: 0,
    })
}

pub fn build(src: &str) -> Plc {
    match try_build(src, &LowerOptions::default()) {
        Ok(p) => p,
        Err(d) => panic!(
            "build failed: {:#?}",
            d.iter()
                .map(|d| format!("{} {}", d.code.as_str(), d.message))
                .collect::<Vec<_>>()
        ),
    }
}

/// Codes and messages of a failed build.
pub fn build_err(src: &str) -> Vec<(String, String)> {
    match try_build(src, &LowerOptions::default()) {
        Ok(_) => panic!("build succeeded"),
        Err(d) => d
            .iter()
            .map(|d| (d.code.as_str().to_string(), d.message.clone()))
            .collect(),
    }
}

impl Plc {
    pub fn scan(&mut self) -> Result<(), Fault> {
        let inst = self.inst.clone();
        self.engine.run_program(&inst, self.now)
    }

    pub fn run(&mut self, n: usize) {
        for _ in 0..n {
            self.scan().unwrap_or_else(|f| panic!("fault: {f}"));
        }
    }

    /// Offset, bit and type of a path.
    pub fn locate(&self, path: &str) -> (u32, Option<u8>, SymbolType) {
        let syms = &self.engine.program().symbols;
        // The longest prefix of dotted names that is an entry.
        let parts: Vec<&str> = path.split('.').collect();
        for n in (1..=parts.len()).rev() {
            let head = parts[..n].join(".");
            let (name, rest_idx) = match head.find('[') {
                Some(i) => (&head[..i], &head[i..]),
                None => (head.as_str(), ""),
            };
            if let Some(e) = syms.get(name) {
                let mut rest = rest_idx.to_string();
                for p in &parts[n..] {
                    rest.push('.');
                    rest.push_str(p);
                }
                return walk(e.offset, e.bit, e.ty.clone(), &rest);
            }
        }
        panic!("no symbol {path}");
    }

    pub fn int(&self, path: &str) -> i128 {
        let (off, bit, ty) = self.locate(path);
        let img = self.engine.image();
        let e = match ty {
            SymbolType::Elementary(e)
            | SymbolType::Subrange { base: e, .. }
            | SymbolType::Enum { base: e, .. } => e,
            t => panic!("{path} is not a scalar: {t:?}"),
        };
        let o = off as usize;
        let b = |n: usize| {
            let mut a = [0u8; 8];
            a[..n].copy_from_slice(&img[o..o + n]);
            u64::from_le_bytes(a)
        };
        match (e, bit) {
            (_, Some(bit)) => ((img[o] >> bit) & 1) as i128,
            (E::Bool | E::Usint | E::Byte | E::Char, _) => b(1) as i128,
            (E::Sint, _) => b(1) as u8 as i8 as i128,
            (E::Int, _) => b(2) as u16 as i16 as i128,
            (E::Uint | E::Word | E::Wchar, _) => b(2) as i128,
            (E::Dint, _) => b(4) as u32 as i32 as i128,
            (E::Udint | E::Dword, _) => b(4) as i128,
            (E::Ulint | E::Lword, _) => b(8) as i128,
            _ => b(8) as i64 as i128,
        }
    }

    pub fn real(&self, path: &str) -> f64 {
        let (off, _, ty) = self.locate(path);
        let o = off as usize;
        let img = self.engine.image();
        match ty {
            SymbolType::Elementary(E::Real) => {
                f32::from_le_bytes(img[o..o + 4].try_into().unwrap()) as f64
            }
            SymbolType::Elementary(E::Lreal) => {
                f64::from_le_bytes(img[o..o + 8].try_into().unwrap())
            }
            t => panic!("{path} is not a real: {t:?}"),
        }
    }

    pub fn string(&self, path: &str) -> String {
        let (off, _, ty) = self.locate(path);
        let o = off as usize;
        let img = self.engine.image();
        let len = u16::from_le_bytes([img[o], img[o + 1]]) as usize;
        match ty {
            SymbolType::String { .. } => {
                img[o + 2..o + 2 + len].iter().map(|&b| b as char).collect()
            }
            SymbolType::WString { .. } => (0..len)
                .map(|i| u16::from_le_bytes([img[o + 2 + 2 * i], img[o + 3 + 2 * i]]))
                .map(|u| char::from_u32(u as u32).unwrap_or('?'))
                .collect(),
            t => panic!("{path} is not a string: {t:?}"),
        }
    }

    pub fn set_int(&mut self, path: &str, v: i64) {
        let (off, bit, ty) = self.locate(path);
        let n = match ty {
            SymbolType::Elementary(e) => match e {
                E::Bool | E::Sint | E::Usint | E::Byte | E::Char => 1,
                E::Int | E::Uint | E::Word | E::Wchar => 2,
                E::Dint | E::Udint | E::Dword | E::Real => 4,
                _ => 8,
            },
            _ => panic!("not scalar"),
        };
        let img = self.engine.image_mut();
        let o = off as usize;
        match bit {
            Some(b) => {
                if v != 0 {
                    img[o] |= 1 << b
                } else {
                    img[o] &= !(1 << b)
                }
            }
            None => img[o..o + n].copy_from_slice(&v.to_le_bytes()[..n]),
        }
    }
}

fn walk(off: u32, bit: Option<u8>, ty: SymbolType, rest: &str) -> (u32, Option<u8>, SymbolType) {
    let rest = rest.trim();
    if rest.is_empty() {
        return (off, bit, ty);
    }
    if let Some(r) = rest.strip_prefix('.') {
        let end = r.find(['.', '[']).unwrap_or(r.len());
        let name = r[..end].to_ascii_uppercase();
        let SymbolType::Struct { fields, .. } = ty else {
            panic!("no members")
        };
        let f = fields
            .iter()
            .find(|f| f.name.eq_ignore_ascii_case(&name))
            .unwrap_or_else(|| panic!("no field {name}"));
        return walk(off + f.offset, f.bit, f.ty.clone(), &r[end..]);
    }
    if let Some(r) = rest.strip_prefix('[') {
        let end = r.find(']').unwrap();
        let idx: Vec<i64> = r[..end]
            .split(',')
            .map(|s| s.trim().parse().unwrap())
            .collect();
        let SymbolType::Array { elem, dims, stride } = ty else {
            panic!("not an array")
        };
        let mut lin = 0i64;
        for (i, (lo, hi)) in idx.iter().zip(&dims) {
            lin = lin * (hi - lo + 1) + (i - lo);
        }
        return walk(off + (lin as u32) * stride, None, *elem, &r[end + 1..]);
    }
    panic!("bad path rest {rest}");
}
