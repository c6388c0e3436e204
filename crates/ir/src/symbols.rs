//! The symbol table: qualified name → offset and type, for everything
//! outside the backend (printing, monitoring, forcing, tracing, retain,
//! protocols).
//!
//! Only declared variables are entries (`Main.fb1`, `Main.arr`, globals,
//! `%QX0.1`-located ones); elements and members (`Main.arr[2, 1].x`,
//! `Main.fb1.Q`) are reached by walking [`SymbolType`], so the table stays
//! small whatever the array sizes. Names are stored upper-case: IEC names are
//! case-insensitive.

use automat_iec::Elementary;

/// The layout-level type of a symbol.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SymbolType {
    /// A scalar; BOOL occupies one byte (0/1) unless the entry has a bit.
    Elementary(Elementary),
    /// `STRING[cap]` stored as u16 length then `cap` bytes.
    String { cap: u32 },
    /// `WSTRING[cap]` stored as u16 length then `cap` u16 units.
    WString { cap: u32 },
    /// Dimensions `(lo, hi)` outermost first; elements row-major, each
    /// `stride` bytes apart.
    Array {
        elem: Box<SymbolType>,
        dims: Vec<(i64, i64)>,
        stride: u32,
    },
    /// A structure, function-block instance or program instance: named
    /// fields at offsets relative to its start.
    Struct { name: String, fields: Vec<Field> },
    /// An enumeration stored as its base integer type.
    Enum {
        name: String,
        base: Elementary,
        values: Vec<(String, i64)>,
    },
    /// A subrange of an integer type.
    Subrange { base: Elementary, lo: i64, hi: i64 },
    /// A reference (VAR_IN_OUT, REF_TO): a u32 image offset.
    Ref(Box<SymbolType>),
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Field {
    pub name: String,
    pub offset: u32,
    /// For BOOLs packed in a bit (not used by the default layout).
    pub bit: Option<u8>,
    pub ty: SymbolType,
}

/// One declared variable.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SymbolEntry {
    /// Upper-case qualified name: `MAIN.FB1`, `GLOBALCOUNT`, `INST.X`.
    pub path: String,
    pub offset: u32,
    /// Located BOOLs (`%IX1.2`) live in one bit of a byte.
    pub bit: Option<u8>,
    pub ty: SymbolType,
    pub retain: bool,
    pub constant: bool,
    /// A VAR_OUTPUT of a program instance: set to its safe value when the
    /// PLC stops in its safe state.
    pub output: bool,
    /// The qualified name as written (`Main.fb1.Q`), for display; filled
    /// from `path` by [`SymbolTable::new`] when left empty.
    pub spelling: String,
}

/// All declared variables, sorted by path for lookup.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct SymbolTable {
    entries: Vec<SymbolEntry>,
}

impl SymbolTable {
    pub fn new(mut entries: Vec<SymbolEntry>) -> SymbolTable {
        for e in &mut entries {
            if e.spelling.is_empty() {
                e.spelling = e.path.clone();
            }
            e.path.make_ascii_uppercase();
        }
        entries.sort_by(|a, b| a.path.cmp(&b.path));
        SymbolTable { entries }
    }

    /// The entry of a declared variable (case-insensitive).
    pub fn get(&self, path: &str) -> Option<&SymbolEntry> {
        let key = path.to_ascii_uppercase();
        self.entries
            .binary_search_by(|e| e.path.as_str().cmp(&key))
            .ok()
            .and_then(|i| self.entries.get(i))
    }

    pub fn entries(&self) -> &[SymbolEntry] {
        &self.entries
    }
}
