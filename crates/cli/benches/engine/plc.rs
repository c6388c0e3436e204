//! Building an ST program through the whole tool chain (parse, check, lower,
//! engine) and reading its variables back through the symbol table, the way
//! any tool outside the engine does.

use automat_base::{Interner, SourceMap};
use automat_engine::Engine;
use automat_ir::{Fault, Program, ProgramInstance, SymbolType};
use automat_jit::Jit;
use automat_lower::{lower, LowerOptions};

/// Which backend runs the program.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Interp,
    Jit,
}

/// The interpreter or the JIT, behind the few calls the benchmark makes.
pub enum Exec {
    Interp(Box<Engine>),
    Jit(Box<Jit>),
}

impl Exec {
    pub fn program(&self) -> &Program {
        match self {
            Exec::Interp(e) => e.program(),
            Exec::Jit(j) => j.program(),
        }
    }
    pub fn image(&self) -> &[u8] {
        match self {
            Exec::Interp(e) => e.image(),
            Exec::Jit(j) => j.image(),
        }
    }
    pub fn cold_start(&mut self) {
        match self {
            Exec::Interp(e) => e.cold_start(),
            Exec::Jit(j) => j.cold_start(),
        }
    }
    pub fn run_program(&mut self, inst: &ProgramInstance, now: i64) -> Result<(), Fault> {
        match self {
            Exec::Interp(e) => e.run_program(inst, now),
            Exec::Jit(j) => j.run_program(inst, now),
        }
    }
}

pub struct Plc {
    pub engine: Exec,
    pub inst: ProgramInstance,
}

/// Compiles `src` (one file) and loads it into a fresh engine of `kind`
/// (for the JIT: compiles it to native code); the error names every
/// diagnostic so a broken case is easy to fix.
pub fn build(name: &str, src: &str, kind: Kind) -> Result<Plc, String> {
    let mut sources = SourceMap::new();
    sources.add(format!("{name}.st"), src.to_string());
    let mut interner = Interner::new();
    let (units, analysis) = automat_sema::check_sources(&sources, &mut interner);
    let describe = |d: &[automat_base::Diagnostic]| {
        d.iter()
            .map(|d| format!("{} {}", d.code.as_str(), d.message))
            .collect::<Vec<_>>()
            .join("; ")
    };
    if analysis.has_errors() {
        return Err(format!("{name}: {}", describe(&analysis.diagnostics)));
    }
    let program = lower(
        &units,
        &analysis,
        &interner,
        &sources,
        &LowerOptions::default(),
    )
    .map_err(|d| format!("{name}: {}", describe(&d)))?;
    let inst = program
        .tasks
        .first()
        .and_then(|t| t.programs.first())
        .cloned()
        .ok_or_else(|| format!("{name}: no program instance to run"))?;
    // The compute cases run millions of instructions in one scan on purpose.
    let engine = match kind {
        Kind::Interp => {
            let mut e = Engine::new(program);
            e.set_budget(u64::MAX);
            Exec::Interp(Box::new(e))
        }
        Kind::Jit => {
            let mut j = Jit::new(program).map_err(|e| format!("{name}: {e}"))?;
            j.set_budget(u64::MAX);
            Exec::Jit(Box::new(j))
        }
    };
    Ok(Plc { engine, inst })
}

impl Plc {
    /// One scan at PLC time `now_ns`.
    pub fn scan(&mut self, now_ns: i64) -> Result<(), String> {
        self.engine
            .run_program(&self.inst, now_ns)
            .map_err(|f| f.to_string())
    }

    /// The offset of `path`: a declared variable, optionally followed by
    /// `[i]` (one dimension) and `.field`, e.g. `FBS.C[500].CV`.
    pub fn offset(&self, path: &str) -> Result<u32, String> {
        let (var, rest) = match path.find('[') {
            Some(i) => path.split_at(i),
            None => (path, ""),
        };
        let entry = self
            .engine
            .program()
            .symbols
            .get(var)
            .ok_or_else(|| format!("no symbol {var}"))?;
        let (mut off, mut ty) = (entry.offset, &entry.ty);
        if let Some(inner) = rest.strip_prefix('[') {
            let (index, field) = inner
                .split_once(']')
                .ok_or_else(|| format!("unclosed index in {path}"))?;
            let index: i64 = index
                .trim()
                .parse()
                .map_err(|_| format!("bad index in {path}"))?;
            let SymbolType::Array { elem, dims, stride } = ty else {
                return Err(format!("{var} is not an array"));
            };
            let lo = dims.first().map(|d| d.0).unwrap_or(0);
            off += (index - lo) as u32 * stride;
            ty = elem;
            if let Some(name) = field.strip_prefix('.') {
                let SymbolType::Struct { fields, .. } = ty else {
                    return Err(format!("{path}: element is not a structure"));
                };
                let f = fields
                    .iter()
                    .find(|f| f.name.eq_ignore_ascii_case(name))
                    .ok_or_else(|| format!("no field {name} in {path}"))?;
                off += f.offset;
            }
        }
        Ok(off)
    }

    fn bytes<const N: usize>(&self, path: &str) -> Result<[u8; N], String> {
        let at = self.offset(path)? as usize;
        self.engine
            .image()
            .get(at..at + N)
            .and_then(|b| b.try_into().ok())
            .ok_or_else(|| format!("{path} lies outside the image"))
    }

    pub fn i16(&self, path: &str) -> Result<i64, String> {
        Ok(i16::from_le_bytes(self.bytes(path)?) as i64)
    }

    pub fn i32(&self, path: &str) -> Result<i64, String> {
        Ok(i32::from_le_bytes(self.bytes(path)?) as i64)
    }

    pub fn i64(&self, path: &str) -> Result<i64, String> {
        Ok(i64::from_le_bytes(self.bytes(path)?))
    }

    pub fn u32(&self, path: &str) -> Result<u32, String> {
        Ok(u32::from_le_bytes(self.bytes(path)?))
    }

    pub fn f64(&self, path: &str) -> Result<f64, String> {
        Ok(f64::from_le_bytes(self.bytes(path)?))
    }

    /// A `STRING` variable (u16 length, then the characters).
    pub fn string(&self, path: &str) -> Result<String, String> {
        let at = self.offset(path)? as usize;
        let len = u16::from_le_bytes(self.bytes(path)?) as usize;
        self.engine
            .image()
            .get(at + 2..at + 2 + len)
            .map(|b| b.iter().map(|&c| c as char).collect())
            .ok_or_else(|| format!("{path} lies outside the image"))
    }
}
