//! Variable paths → places in the image.
//!
//! Grammar (names case-insensitive, spaces allowed around brackets and
//! commas): `name ('.' name | '.' digits | '[' int (',' int)* ']')*`, or a
//! direct address `%IX1.2`, `%QB0`, `%MW4`, `%ID8`, `%QL0`.
//!
//! Resolution: the longest dotted prefix of names that is a declared
//! variable of the symbol table (entries may be qualified: `MAIN.X`,
//! `CELL.RES.PF.N`), then each member (struct field, FB or program
//! variable), index (checked against the declared bounds) or bit (`.3` of
//! an integer or bit string) is walked through the [`SymbolType`]. When the
//! program has exactly one program instance, a path is first tried inside
//! it (`x` is `MAIN.x`, as the program itself sees it), then as given.
//!
//! An Allen-Bradley SLC-500 address (`N7:15`, `T4:0.ACC`, `B3/18`,
//! `I:1/1`: `automat_base::slc::looks_like`) is read as the word or bit of
//! the data-file array it names (`N7[15]`, `T4[2]`, `B3[1].2`, `I1[8].1`),
//! the globals the SLC front end generates.
//!
//! Direct addresses follow the CODESYS/OpenPLC convention that lowering uses
//! (`automat_lower::layout::address_offset`): the number of a sized address
//! counts units of its size, so `%QW2` is output bytes 4 and 5
//! (little-endian), `%QD1` bytes 4..7, `%QB3` byte 3; `%QX1.2` is bit 2 of
//! output byte 1.

use automat_iec::Elementary;
use automat_ir::{Program, SymbolType};

/// What is stored at a place, as far as reading a value needs.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PlaceType {
    Elementary(Elementary),
    String {
        cap: u32,
    },
    WString {
        cap: u32,
    },
    Enum {
        name: String,
        base: Elementary,
        values: Vec<(String, i64)>,
    },
}

/// A readable variable: where it is in the image and its type.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Place {
    pub offset: u32,
    /// A BOOL packed in one bit of the byte at `offset`.
    pub bit: Option<u8>,
    pub ty: PlaceType,
    /// A bit of an SLC-500 data file (named by its address or a symbol of
    /// the ladder's table): printed as 1/0, as RSLogix shows bits.
    pub slc_bit: bool,
}

impl PlaceType {
    /// Bytes occupied in the image.
    pub fn size(&self) -> u32 {
        match self {
            PlaceType::Elementary(e) | PlaceType::Enum { base: e, .. } => {
                e.bit_width().map_or(0, |w| w.div_ceil(8))
            }
            PlaceType::String { cap } => cap.saturating_add(crate::value::STRING_LEN_BYTES),
            PlaceType::WString { cap } => cap
                .saturating_mul(2)
                .saturating_add(crate::value::STRING_LEN_BYTES),
        }
    }
}

#[derive(Clone, Debug, PartialEq, Eq)]
enum Sel {
    Name(String),
    Index(Vec<i64>),
}

/// A resolved path with what decides whether a user may change it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Access {
    pub place: Place,
    /// The declared variable is a CONSTANT.
    pub constant: bool,
    /// The path goes through compiler-generated state: a name starting
    /// with `__`, or an instance of a hidden block (`__SFC_STEP`, the SFC
    /// step flags and times; `__SFC_ACTION`); the hidden type's name.
    pub generated: Option<String>,
    /// The bounds of a subrange type.
    pub bounds: Option<(i64, i64)>,
}

/// Resolves `text` in `program` (see the module rules).
pub fn resolve(program: &Program, text: &str) -> Result<Place, String> {
    resolve_access(program, text).map(|a| a.place)
}

/// [`resolve`], with what online writing and forcing check.
pub fn resolve_access(program: &Program, text: &str) -> Result<Access, String> {
    let t = text.trim();
    let access = if let Some(addr) = t.strip_prefix('%') {
        Access {
            place: direct(program, t, addr)?,
            constant: false,
            generated: None,
            bounds: None,
        }
    } else if crate::slc_place::looks_dynamic(t) {
        return Err(format!(
            "`{t}` is an indexed or indirect SLC-500 address: its place depends on the data (S:24, the words in `[ ]`), so it names no fixed place here (it is read and written by name where the value is taken at run time: --print, --trace, scenarios, the online API)"
        ));
    } else if automat_base::slc::looks_like(t) {
        // An SLC-500 address (`N7:15`, `T4:0/DN`, `I:1/1`) names a word or
        // bit of the data-file arrays the SLC front end generates.
        let path = automat_base::slc::st_path(t)?;
        let sels = parse(&path)?;
        walk_path(program, t, &sels).map_err(|e| {
            format!("{e} (`{t}` is the SLC address of `{path}`: is this an SLC-500 program?)")
        })?
    } else {
        let sels = parse(t)?;
        walk_path(program, t, &sels)?
    };
    let mut access = access;
    access.place.slc_bit = is_slc_bit(program, t, &access.place);
    let place = &access.place;
    let end = u64::from(place.offset) + u64::from(place.ty.size());
    if end > u64::from(program.image_size) {
        return Err(format!(
            "`{t}` lies outside the memory image ({end} > {} bytes)",
            program.image_size
        ));
    }
    Ok(access)
}

/// The place of a direct SLC address (a pointer word of an indirect one).
pub(crate) fn resolve_slc_address(
    program: &Program,
    a: automat_base::slc::Address,
) -> Result<Place, String> {
    let path = a
        .st_path()
        .ok_or_else(|| format!("`{}` is a whole element", a.array()))?;
    let sels = parse(&path)?;
    let mut access = walk_path(program, &path, &sels)?;
    access.place.slc_bit = a.is_bit();
    Ok(access.place)
}

/// Is `place` a bit of an SLC-500 data file: named by its SLC address
/// (`B3:0/1`), or a BOOL (a symbol of the ladder's table, `%IX16.1`) lying
/// in one of the data-file arrays of a program the SLC front end generated
/// (its global `__slc_started`)? IEC BOOLs elsewhere are not.
fn is_slc_bit(program: &Program, text: &str, place: &Place) -> bool {
    if place.bit.is_none() || place.ty != PlaceType::Elementary(Elementary::Bool) {
        return false;
    }
    if automat_base::slc::looks_like(text) {
        return true;
    }
    if program.symbols.get("__SLC_STARTED").is_none() {
        return false;
    }
    program.symbols.entries().iter().any(|e| {
        let file = e.path.len() > 1
            && e.path.starts_with(['O', 'I', 'S', 'B', 'T', 'C', 'R', 'N'])
            && e.path[1..].bytes().all(|b| b.is_ascii_digit());
        match &e.ty {
            SymbolType::Array { dims, stride, .. } if file => {
                let count = dims
                    .iter()
                    .map(|(lo, hi)| hi.saturating_sub(*lo).saturating_add(1).max(0))
                    .product::<i64>();
                let size = u64::try_from(count).unwrap_or(0) * u64::from(*stride);
                let at = u64::from(place.offset);
                at >= u64::from(e.offset) && at < u64::from(e.offset) + size
            }
            _ => false,
        }
    })
}

fn parse(text: &str) -> Result<Vec<Sel>, String> {
    let bad = |why: &str| format!("`{text}` is not a variable path: {why}");
    let mut sels = Vec::new();
    let mut rest = text;
    let mut want_name = true;
    while !rest.is_empty() {
        if want_name {
            let len = rest
                .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                .unwrap_or(rest.len());
            let (name, tail) = rest.split_at(len);
            if name.is_empty() {
                return Err(bad("a name is missing"));
            }
            sels.push(Sel::Name(name.to_ascii_uppercase()));
            rest = tail;
            want_name = false;
        } else if let Some(tail) = rest.strip_prefix('.') {
            rest = tail;
            want_name = true;
        } else if let Some(tail) = rest.strip_prefix('[') {
            let close = tail.find(']').ok_or_else(|| bad("`[` without `]`"))?;
            let (inside, after) = tail.split_at(close);
            let idx = inside
                .split(',')
                .map(|s| {
                    s.trim()
                        .parse::<i64>()
                        .map_err(|_| bad(&format!("`{}` is not an integer index", s.trim())))
                })
                .collect::<Result<Vec<i64>, String>>()?;
            sels.push(Sel::Index(idx));
            rest = after.get(1..).unwrap_or("").trim_start();
        } else {
            return Err(bad(&format!("unexpected `{rest}`")));
        }
    }
    if want_name {
        return Err(bad("it ends where a name is expected"));
    }
    match sels.first() {
        Some(Sel::Name(n)) if !n.starts_with(|c: char| c.is_ascii_digit()) => Ok(sels),
        _ => Err(bad("it must start with a name")),
    }
}

/// The scopes a path is tried in: inside the only program instance (when
/// there is exactly one), then as given.
fn scopes(program: &Program) -> Vec<Option<String>> {
    let mut names: Vec<&str> = program
        .tasks
        .iter()
        .flat_map(|t| t.programs.iter().map(|p| p.name.as_str()))
        .collect();
    names.sort_unstable();
    names.dedup();
    match names.as_slice() {
        [only] => vec![Some(only.to_ascii_uppercase()), None],
        _ => vec![None],
    }
}

fn walk_path(program: &Program, text: &str, sels: &[Sel]) -> Result<Access, String> {
    // A path that fails inside the only program may still be right as
    // given: `Crc.crc` in `PROGRAM Crc` with a variable `crc` is first read
    // as `Crc.crc.crc` (no such member), then as the program's `crc`. When
    // every scope fails, the first scope's error is the one shown.
    let mut first_error = None;
    for scope in scopes(program) {
        let mut all: Vec<Sel> = scope.iter().map(|s| Sel::Name(s.clone())).collect();
        let scoped = all.len();
        all.extend_from_slice(sels);
        if let Some((k, w)) = root(program, &all, scoped) {
            let mut w = w;
            let walked = all
                .iter()
                .skip(k)
                .try_for_each(|s| w.step(s))
                .and_then(|()| w.finish());
            match walked {
                Ok(access) => return Ok(access),
                Err(e) => {
                    first_error.get_or_insert(e);
                }
            }
        }
    }
    if let Some(e) = first_error {
        return Err(e);
    }
    let first = match sels.first() {
        Some(Sel::Name(n)) => n.as_str(),
        _ => text,
    };
    // A program instance is no entry of its own: its variables are.
    let inside = format!("{first}.");
    let instance = program
        .symbols
        .entries()
        .iter()
        .any(|e| e.path.starts_with(&inside));
    if let (true, Some(Sel::Name(member))) = (instance, sels.get(1)) {
        return Err(format!(
            "unknown variable `{text}`: `{first}` has no variable `{member}`"
        ));
    }
    Err(format!(
        "unknown variable `{text}`: no program variable or global named `{first}`"
    ))
}

/// The longest dotted prefix of `sels` that is a declared variable, and a
/// walker standing on it. The first `scoped` names are the scope: a match
/// covering only them counts when the scope has a member named like the
/// path's first name (so an unknown `x` falls through to the globals).
fn root(program: &Program, sels: &[Sel], scoped: usize) -> Option<(usize, Walker)> {
    let names: Vec<&str> = sels
        .iter()
        .map_while(|s| match s {
            Sel::Name(n) => Some(n.as_str()),
            Sel::Index(_) => None,
        })
        .collect();
    // No declared path has more names than the deepest symbol: longer
    // prefixes are not tried (a hostile `a.a.a...` of 20,000 names would
    // otherwise join 20,000 prefixes, quadratic in its length).
    let deepest = program
        .symbols
        .entries()
        .iter()
        .map(|e| e.path.bytes().filter(|&b| b == b'.').count() + 1)
        .max()
        .unwrap_or(0);
    for k in (1..=names.len().min(deepest)).rev() {
        let joined = names.get(..k)?.join(".");
        let Some(e) = program.symbols.get(&joined) else {
            continue;
        };
        if k <= scoped {
            let member = names.get(scoped)?;
            let has = matches!(&e.ty, SymbolType::Struct { fields, .. }
                if fields.iter().any(|f| f.name.eq_ignore_ascii_case(member)));
            if !has {
                return None;
            }
        }
        let shown = names
            .get(scoped.min(k)..k)
            .map(|n| n.join("."))
            .unwrap_or_default();
        return Some((
            k,
            Walker {
                generated: names
                    .get(..k)
                    .and_then(|n| n.iter().find(|n| n.starts_with("__")))
                    .map(|n| n.to_string()),
                shown: if shown.is_empty() { joined } else { shown },
                offset: e.offset,
                bit: e.bit,
                ty: e.ty.clone(),
                constant: e.constant,
            },
        ));
    }
    None
}

struct Walker {
    /// The path walked so far, for messages.
    shown: String,
    offset: u32,
    bit: Option<u8>,
    ty: SymbolType,
    constant: bool,
    /// The first compiler-generated name or hidden type on the path.
    generated: Option<String>,
}

fn type_name(ty: &SymbolType) -> String {
    match ty {
        SymbolType::Elementary(e) => e.name().to_string(),
        SymbolType::String { cap } => format!("STRING[{cap}]"),
        SymbolType::WString { cap } => format!("WSTRING[{cap}]"),
        SymbolType::Array { .. } => "an ARRAY".to_string(),
        SymbolType::Struct { name, .. } | SymbolType::Enum { name, .. } => name.clone(),
        SymbolType::Subrange { base, .. } => format!("a subrange of {base}"),
        SymbolType::Ref(_) => "a reference".to_string(),
    }
}

impl Walker {
    fn step(&mut self, sel: &Sel) -> Result<(), String> {
        let shown = self.shown.clone();
        match (sel, &self.ty) {
            (Sel::Name(n), SymbolType::Struct { name, fields }) => {
                let f = fields
                    .iter()
                    .find(|f| f.name.eq_ignore_ascii_case(n))
                    .ok_or_else(|| format!("`{shown}` ({name}) has no member `{n}`"))?;
                if self.generated.is_none() && (name.starts_with("__") || n.starts_with("__")) {
                    self.generated = Some(name.clone());
                }
                self.offset = self
                    .offset
                    .checked_add(f.offset)
                    .ok_or_else(|| format!("`{shown}.{n}` lies outside the memory image"))?;
                self.bit = f.bit;
                self.ty = f.ty.clone();
                self.shown = format!("{shown}.{n}");
            }
            (Sel::Name(n), SymbolType::Elementary(e))
                if e.is_integral() && n.bytes().all(|b| b.is_ascii_digit()) =>
            {
                let width = e.bit_width().unwrap_or(0);
                let bit = n
                    .parse::<u32>()
                    .ok()
                    .filter(|&b| b < width)
                    .ok_or_else(|| {
                        format!(
                            "bit `{n}` of `{shown}` ({e}) is out of range 0..{}",
                            width.saturating_sub(1)
                        )
                    })?;
                self.offset = self.offset.saturating_add(bit / 8);
                self.bit = u8::try_from(bit % 8).ok();
                self.ty = SymbolType::Elementary(Elementary::Bool);
                self.shown = format!("{shown}.{n}");
            }
            (Sel::Name(n), SymbolType::Ref(_)) => {
                return Err(format!(
                "`{shown}` is a reference (VAR_IN_OUT or REF_TO); a path cannot follow it to `{n}`"
            ))
            }
            (Sel::Name(n), ty) => {
                return Err(format!(
                    "`{shown}` is {}; it has no member `{n}`",
                    type_name(ty)
                ))
            }
            (Sel::Index(ix), SymbolType::Array { elem, dims, stride }) => {
                let linear = linear_index(&shown, ix, dims)?;
                let delta = u64::from(*stride).saturating_mul(linear);
                self.offset = u32::try_from(u64::from(self.offset).saturating_add(delta))
                    .map_err(|_| format!("`{shown}` element lies outside the memory image"))?;
                self.bit = None;
                self.ty = (**elem).clone();
                let list: Vec<String> = ix.iter().map(i64::to_string).collect();
                self.shown = format!("{shown}[{}]", list.join(", "));
            }
            (Sel::Index(_), ty) => {
                return Err(format!("`{shown}` is {}, not an array", type_name(ty)))
            }
        }
        Ok(())
    }

    fn finish(self) -> Result<Access, String> {
        let bounds = match self.ty {
            SymbolType::Subrange { lo, hi, .. } => Some((lo, hi)),
            _ => None,
        };
        let ty = match self.ty {
            SymbolType::Elementary(e) => PlaceType::Elementary(e),
            SymbolType::Subrange { base, .. } => PlaceType::Elementary(base),
            SymbolType::String { cap } => PlaceType::String { cap },
            SymbolType::WString { cap } => PlaceType::WString { cap },
            SymbolType::Enum { name, base, values } => PlaceType::Enum { name, base, values },
            SymbolType::Struct { name, fields } => {
                let members: Vec<&str> = fields.iter().map(|f| f.name.as_str()).collect();
                return Err(format!(
                    "`{}` is a {name}; name one of its members: {}",
                    self.shown,
                    members.join(", ")
                ));
            }
            SymbolType::Array { dims, .. } => {
                let b: Vec<String> = dims.iter().map(|(lo, hi)| format!("{lo}..{hi}")).collect();
                return Err(format!(
                    "`{}` is an ARRAY[{}]; give an index",
                    self.shown,
                    b.join(", ")
                ));
            }
            SymbolType::Ref(_) => {
                return Err(format!(
                    "`{}` is a reference (VAR_IN_OUT or REF_TO) and cannot be read by path",
                    self.shown
                ))
            }
        };
        Ok(Access {
            place: Place {
                offset: self.offset,
                bit: self.bit,
                ty,
                slc_bit: false,
            },
            constant: self.constant,
            generated: self.generated,
            bounds,
        })
    }
}

/// Row-major element number of `ix` in `dims`, every index checked.
fn linear_index(shown: &str, ix: &[i64], dims: &[(i64, i64)]) -> Result<u64, String> {
    if ix.len() != dims.len() {
        return Err(format!(
            "`{shown}` has {} dimension(s); {} index(es) given",
            dims.len(),
            ix.len()
        ));
    }
    let mut linear: u64 = 0;
    for (&i, &(lo, hi)) in ix.iter().zip(dims) {
        if i < lo || i > hi {
            return Err(format!("index {i} of `{shown}` is out of range {lo}..{hi}"));
        }
        let len = u64::try_from(i128::from(hi) - i128::from(lo) + 1).unwrap_or(u64::MAX);
        let pos = u64::try_from(i128::from(i) - i128::from(lo)).unwrap_or(0);
        linear = linear.saturating_mul(len).saturating_add(pos);
    }
    Ok(linear)
}

/// `%IX1.2`, `%QB0`, `%MW4` (without the `%`).
fn direct(program: &Program, text: &str, addr: &str) -> Result<Place, String> {
    let bad = |why: String| format!("`{text}` is not a direct address: {why}");
    let mut chars = addr.chars();
    let area = match chars.next().map(|c| c.to_ascii_uppercase()) {
        Some('I') => &program.areas.input,
        Some('Q') => &program.areas.output,
        Some('M') => &program.areas.memory,
        _ => return Err(bad("the area must be I, Q or M".into())),
    };
    let rest = chars.as_str();
    let (size, nums) = match rest.chars().next().map(|c| c.to_ascii_uppercase()) {
        Some(c @ ('X' | 'B' | 'W' | 'D' | 'L')) => (c, rest.get(1..).unwrap_or("")),
        _ => ('X', rest),
    };
    let parts = nums
        .split('.')
        .map(|p| {
            p.parse::<u32>()
                .map_err(|_| bad(format!("`{p}` is not a number")))
        })
        .collect::<Result<Vec<u32>, String>>()?;
    let (byte, bit, ty) = match (size, parts.as_slice()) {
        ('X', [byte, bit]) if *bit < 8 => (*byte, u8::try_from(*bit).ok(), Elementary::Bool),
        ('X', [_, bit]) => return Err(bad(format!("bit {bit} is out of range 0..7"))),
        ('X', _) => return Err(bad("a bit address is `byte.bit`".into())),
        (s, [n]) => {
            let (unit, ty) = match s {
                'B' => (1, Elementary::Byte),
                'W' => (2, Elementary::Word),
                'D' => (4, Elementary::Dword),
                _ => (8, Elementary::Lword),
            };
            (n.saturating_mul(unit), None, ty)
        }
        _ => {
            return Err(bad(
                "a byte, word or double word address is one number".into()
            ))
        }
    };
    let place = Place {
        offset: area.start.saturating_add(byte),
        bit,
        ty: PlaceType::Elementary(ty),
        slc_bit: false,
    };
    let end = u64::from(area.start) + u64::from(byte) + u64::from(place.ty.size());
    if end > u64::from(area.end) {
        return Err(format!(
            "`{text}` is outside the area the program uses ({} bytes)",
            area.end.saturating_sub(area.start)
        ));
    }
    Ok(place)
}

#[cfg(test)]
#[path = "path_tests.rs"]
mod tests;
