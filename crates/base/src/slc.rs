//! Allen-Bradley SLC-500 data addresses (`N7:15`, `T4:0.ACC`, `B3:1/5`,
//! `B3/18`, `T4:0/DN`, `I:1/1`, `O:0.1/3`, `S:1/15`, `F8:2`) and the path
//! of the memory that holds them.
//!
//! Shared by the SLC front end (`automat-dialect`, which generates the data
//! files as globals) and the runtime's path resolver (which reads and writes
//! them by their SLC name in `--print`, `--trace`, scenarios, bindings and
//! the online API). The memory is the SLC's: every data file but the float
//! files is one array of 16-bit words (`ARRAY OF INT` named `N7`, `B3`,
//! `T4`, `S2`, `I1`, `O0`, ...), a timer, counter or control element three
//! consecutive words (control bits, PRE or LEN, ACC or POS), a float file an
//! `ARRAY OF REAL`. I/O files give each slot [`IO_SLOT_WORDS`] words, so
//! `I:s.w` is word `s * 8 + w` of `I1`.

/// Words of each I/O slot in the `I1` and `O0` arrays.
pub const IO_SLOT_WORDS: u32 = 8;
/// The highest I/O slot.
pub const MAX_SLOT: u32 = 30;
/// The highest element number of a data file.
pub const MAX_ELEMENT: u32 = 255;

/// A data file's type.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum FileType {
    O,
    I,
    S,
    B,
    T,
    C,
    R,
    N,
    F,
}

impl FileType {
    pub fn from_letter(c: char) -> Option<FileType> {
        Some(match c.to_ascii_uppercase() {
            'O' => FileType::O,
            'I' => FileType::I,
            'S' => FileType::S,
            'B' => FileType::B,
            'T' => FileType::T,
            'C' => FileType::C,
            'R' => FileType::R,
            'N' => FileType::N,
            'F' => FileType::F,
            _ => return None,
        })
    }

    pub fn letter(self) -> char {
        match self {
            FileType::O => 'O',
            FileType::I => 'I',
            FileType::S => 'S',
            FileType::B => 'B',
            FileType::T => 'T',
            FileType::C => 'C',
            FileType::R => 'R',
            FileType::N => 'N',
            FileType::F => 'F',
        }
    }

    /// Words per element (a float element is one REAL).
    pub fn words(self) -> u32 {
        match self {
            FileType::T | FileType::C | FileType::R => 3,
            _ => 1,
        }
    }

    /// The file number a type has by default (O0 … F8), `None` for B, T,
    /// C, R, N, F files of other numbers.
    pub fn fixed_number(self) -> Option<u32> {
        match self {
            FileType::O => Some(0),
            FileType::I => Some(1),
            FileType::S => Some(2),
            _ => None,
        }
    }

    /// The type file `n` must have (0–8), `None` for user files 9–255.
    pub fn of_number(n: u32) -> Option<FileType> {
        Some(match n {
            0 => FileType::O,
            1 => FileType::I,
            2 => FileType::S,
            3 => FileType::B,
            4 => FileType::T,
            5 => FileType::C,
            6 => FileType::R,
            7 => FileType::N,
            8 => FileType::F,
            _ => return None,
        })
    }
}

/// What part of an element an address names.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Part {
    /// The element: a word of N, B, S, I, O; a float of F; a whole timer,
    /// counter or control of T, C, R.
    Element,
    /// A word of the element (T/C/R: 1 = PRE/LEN, 2 = ACC/POS; I/O: the
    /// slot's word).
    Word(u32),
    /// A bit of a word of the element.
    Bit(u32, u32),
}

/// A parsed direct address.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Address {
    pub ty: FileType,
    pub file: u32,
    /// Element number (I/O: the slot).
    pub elem: u32,
    pub part: Part,
}

/// Named sub-elements: (type, name, word, bit or `None` for a word).
const SUBS: &[(FileType, &str, u32, Option<u32>)] = &[
    (FileType::T, "EN", 0, Some(15)),
    (FileType::T, "TT", 0, Some(14)),
    (FileType::T, "DN", 0, Some(13)),
    (FileType::T, "PRE", 1, None),
    (FileType::T, "ACC", 2, None),
    (FileType::C, "CU", 0, Some(15)),
    (FileType::C, "CD", 0, Some(14)),
    (FileType::C, "DN", 0, Some(13)),
    (FileType::C, "OV", 0, Some(12)),
    (FileType::C, "UN", 0, Some(11)),
    (FileType::C, "UA", 0, Some(10)),
    (FileType::C, "PRE", 1, None),
    (FileType::C, "ACC", 2, None),
    (FileType::R, "EN", 0, Some(15)),
    (FileType::R, "EU", 0, Some(14)),
    (FileType::R, "DN", 0, Some(13)),
    (FileType::R, "EM", 0, Some(12)),
    (FileType::R, "ER", 0, Some(11)),
    (FileType::R, "UL", 0, Some(10)),
    (FileType::R, "IN", 0, Some(9)),
    (FileType::R, "FD", 0, Some(8)),
    (FileType::R, "LEN", 1, None),
    (FileType::R, "POS", 2, None),
];

/// The bit number of a named control bit (`DN` of a timer: 13).
pub fn sub_bit(ty: FileType, name: &str) -> Option<u32> {
    SUBS.iter()
        .find(|s| s.0 == ty && s.1.eq_ignore_ascii_case(name))
        .and_then(|s| s.3)
}

fn number(s: &str) -> Option<u32> {
    if s.is_empty() || s.len() > 6 || !s.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    s.parse().ok()
}

/// Does the text look like an SLC address (so a resolver should read it as
/// one and report why it is wrong rather than fall back to other forms)?
pub fn looks_like(text: &str) -> bool {
    let t = text.trim();
    let mut c = t.chars();
    c.next().is_some_and(|c| FileType::from_letter(c).is_some())
        && t.contains([':', '/'])
        && !t.contains(['%', '[', ' '])
}

/// Parses an address (any case). `Err` says why the text is not one.
pub fn parse(text: &str) -> Result<Address, String> {
    let up = text.trim().to_ascii_uppercase();
    let bad = |why: &str| Err(format!("`{}` is not an SLC address: {why}", text.trim()));
    let mut chars = up.chars();
    let Some(ty) = chars.next().and_then(FileType::from_letter) else {
        return bad("it starts with a file type letter O I S B T C R N F");
    };
    let rest = &up[1..];
    // The file number, up to `:` or `/`.
    let cut = rest.find([':', '/']).unwrap_or(rest.len());
    let (num, rest) = rest.split_at(cut);
    let file = if num.is_empty() {
        match ty.fixed_number() {
            Some(n) => n,
            None => return bad("a file number follows the type letter (N7, B3)"),
        }
    } else {
        match number(num) {
            Some(n) if n <= 255 => n,
            _ => return bad("the file number is 0 to 255"),
        }
    };
    match FileType::of_number(file) {
        Some(t) if t != ty => return bad(&format!("file {file} is a {} file", t.letter())),
        None if matches!(ty, FileType::O | FileType::I | FileType::S) => {
            return bad("O, I and S are files 0, 1 and 2")
        }
        _ => {}
    }
    let io = matches!(ty, FileType::I | FileType::O);
    // The flat bit form `B3/18`: bit 18 of the file = word 1, bit 2.
    if let Some(flat) = rest.strip_prefix('/') {
        let Some(b) = number(flat) else {
            return bad("a bit number follows `/`");
        };
        if ty == FileType::F || ty.words() != 1 || io {
            return bad("the flat bit form `/n` is for B, N and S files");
        }
        if b / 16 > MAX_ELEMENT {
            return bad("the bit lies past the largest file (4096 bits)");
        }
        return Ok(Address {
            ty,
            file,
            elem: b / 16,
            part: Part::Bit(0, b % 16),
        });
    }
    let Some(rest) = rest.strip_prefix(':') else {
        return bad("`:` and an element number follow the file");
    };
    let cut = rest.find(['.', '/']).unwrap_or(rest.len());
    let (e, mut rest) = rest.split_at(cut);
    let Some(elem) = number(e) else {
        return bad("an element number follows `:`");
    };
    if io && elem > MAX_SLOT {
        return bad("the slot is 0 to 30");
    }
    if elem > MAX_ELEMENT {
        return bad("the element is 0 to 255");
    }
    let mut word = None;
    if let Some(r) = rest.strip_prefix('.') {
        let cut = r.find('/').unwrap_or(r.len());
        let (w, r2) = r.split_at(cut);
        rest = r2;
        if io {
            match number(w) {
                Some(w) if w < IO_SLOT_WORDS => word = Some(w),
                _ => return bad("the slot's word is 0 to 7"),
            }
        } else if let Some(s) = SUBS.iter().find(|s| s.0 == ty && s.1 == w && s.3.is_none()) {
            word = Some(s.2);
        } else {
            return bad(&format!("`.{w}` is no word of a {} element", ty.letter()));
        }
    }
    let part = if let Some(b) = rest.strip_prefix('/') {
        if let Some(bit) = number(b) {
            if ty == FileType::F {
                return bad("a float has no bits");
            }
            if matches!(ty, FileType::T | FileType::C | FileType::R) && word.is_none() {
                return bad("a bit of a timer, counter or control is named: /EN, /DN, ...");
            }
            if bit > 15 {
                return bad("the bit is 0 to 15");
            }
            Part::Bit(word.unwrap_or(0), bit)
        } else if let (None, Some(s)) = (
            word,
            SUBS.iter().find(|s| s.0 == ty && s.1 == b && s.3.is_some()),
        ) {
            Part::Bit(s.2, s.3.unwrap_or(0))
        } else {
            return bad(&format!("`/{b}` is no bit of a {} element", ty.letter()));
        }
    } else if !rest.is_empty() {
        return bad("unexpected text after the element");
    } else {
        match word {
            Some(w) => Part::Word(w),
            None => Part::Element,
        }
    };
    Ok(Address {
        ty,
        file,
        elem,
        part,
    })
}

impl Address {
    /// The global array holding the file (`N7`, `I1`, `O0`, `S2`).
    pub fn array(self) -> String {
        format!("{}{}", self.ty.letter(), self.file)
    }

    /// The word index in the file's array (F: the float index).
    pub fn index(self) -> u32 {
        let w = match self.part {
            Part::Element => 0,
            Part::Word(w) | Part::Bit(w, _) => w,
        };
        match self.ty {
            FileType::I | FileType::O => self.elem * IO_SLOT_WORDS + w,
            t => self.elem * t.words() + w,
        }
    }

    /// A bit (BOOL)?
    pub fn is_bit(self) -> bool {
        matches!(self.part, Part::Bit(..))
    }

    /// A whole timer, counter or control element (no value of its own)?
    pub fn is_structure(self) -> bool {
        self.part == Part::Element && matches!(self.ty, FileType::T | FileType::C | FileType::R)
    }

    /// The variable path of the generated globals (`T4[2]`, `B3[1].5`),
    /// `None` for a whole structured element.
    pub fn st_path(self) -> Option<String> {
        if self.is_structure() {
            return None;
        }
        let base = format!("{}[{}]", self.array(), self.index());
        Some(match self.part {
            Part::Bit(_, b) => format!("{base}.{b}"),
            _ => base,
        })
    }
}

impl std::fmt::Display for Address {
    /// As RSLogix writes it: `N7:15`, `T4:0.ACC`, `T4:0/DN`, `B3:1/2`,
    /// `I:1/1`, `I:1.2/3`, `S:24`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let l = self.ty.letter();
        match self.ty.fixed_number() {
            Some(_) => write!(f, "{l}:{}", self.elem)?,
            None => write!(f, "{l}{}:{}", self.file, self.elem)?,
        }
        let io = matches!(self.ty, FileType::I | FileType::O);
        let named = |w: u32, bit: Option<u32>| {
            SUBS.iter()
                .find(|s| s.0 == self.ty && s.2 == w && s.3 == bit)
                .map(|s| s.1)
        };
        match self.part {
            Part::Element => Ok(()),
            Part::Word(w) if io => write!(f, ".{w}"),
            Part::Word(w) => match named(w, None) {
                Some(n) => write!(f, ".{n}"),
                None => write!(f, ".{w}"),
            },
            Part::Bit(w, b) if io && w > 0 => write!(f, ".{w}/{b}"),
            Part::Bit(w, b) => match (self.ty.words(), named(w, Some(b)), named(w, None)) {
                (1, ..) => write!(f, "/{b}"),
                (_, Some(n), _) => write!(f, "/{n}"),
                (_, None, Some(n)) => write!(f, ".{n}/{b}"),
                _ => write!(f, ".{w}/{b}"),
            },
        }
    }
}

/// The variable path an SLC address stands for (see [`Address::st_path`]).
pub fn st_path(text: &str) -> Result<String, String> {
    let a = parse(text)?;
    a.st_path().ok_or_else(|| {
        format!(
            "`{}` is a whole {} element: name a part of it ({})",
            text.trim(),
            a.ty.letter(),
            match a.ty {
                FileType::T => ".PRE .ACC /EN /TT /DN",
                FileType::C => ".PRE .ACC /CU /CD /DN /OV /UN /UA",
                _ => ".LEN .POS /EN /EU /DN /EM /ER /UL /IN /FD",
            }
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_form_maps_to_its_word_and_bit() {
        let p = |s: &str| st_path(s).unwrap_or_else(|e| e);
        assert_eq!(p("N7:15"), "N7[15]");
        assert_eq!(p("t4:7.acc"), "T4[23]");
        assert_eq!(p("T4:0.PRE"), "T4[1]");
        assert_eq!(p("T4:0/DN"), "T4[0].13");
        assert_eq!(p("C5:1/OV"), "C5[3].12");
        assert_eq!(p("R6:0.POS"), "R6[2]");
        assert_eq!(p("R6:2/EM"), "R6[6].12");
        assert_eq!(p("B3:64/15"), "B3[64].15");
        assert_eq!(p("B3/18"), "B3[1].2");
        assert_eq!(p("I:1/1"), "I1[8].1");
        assert_eq!(p("I:2.1/3"), "I1[17].3");
        assert_eq!(p("O:0/5"), "O0[0].5");
        assert_eq!(p("S:1/15"), "S2[1].15");
        assert_eq!(p("S2:5/0"), "S2[5].0");
        assert_eq!(p("F8:3"), "F8[3]");
        assert_eq!(p("N10:2/4"), "N10[2].4");
        assert_eq!(
            p("B3:0/16"),
            "`B3:0/16` is not an SLC address: the bit is 0 to 15"
        );
        assert!(p("T4:0").contains("whole T element"));
        assert!(p("N4:0").contains("file 4 is a T file"));
        assert!(p("T4:0/OV").contains("no bit"));
        assert!(p("F8:0/1").contains("no bits"));
        assert!(p("N7:256").contains("0 to 255"));
    }

    #[test]
    fn addresses_print_as_rslogix_writes_them() {
        for text in [
            "N7:15",
            "T4:7.ACC",
            "T4:0/DN",
            "C5:1/OV",
            "R6:0.POS",
            "B3:1/2",
            "I:1/1",
            "I:2.1/3",
            "O:0.1",
            "S:24",
            "S:1/15",
            "F8:3",
            "N10:2/4",
            "T4:0.PRE/3",
        ] {
            assert_eq!(parse(text).map(|a| a.to_string()), Ok(text.to_string()));
        }
        assert_eq!(parse("B3/18").map(|a| a.to_string()), Ok("B3:1/2".into()));
    }

    #[test]
    fn looks_like_addresses_only() {
        assert!(looks_like("N7:1"));
        assert!(looks_like("B3/2"));
        assert!(!looks_like("Main.x"));
        assert!(!looks_like("%IX0.1"));
    }
}
