//! Places named by an SLC-500 indexed or indirect address (`#N7:5`,
//! `N7:[N7:0]`, `T4:[N7:0].ACC`, `N[N7:0]:1`, `B3/[N7:1]`, `B3:[N7:0]/5`,
//! `B3:0/[N7:2]`), found in the image at each read or write.
//!
//! Where such an address lies depends on the data (the index register S:24,
//! the words inside `[ ]`), so it is not resolved once like a direct path:
//! [`locate`] resolves what is fixed (the data-file arrays, the pointer
//! words) and [`Locator::place`] works out the word or bit against the
//! image it is given, checking it against the data file as the program
//! sizes it. Outside the file, that one read or write fails with a message
//! naming the address and the file's range; the PLC is not affected.

use crate::path::{self, Place, PlaceType};
use automat_base::slc::{Address, FileType, Part, IO_SLOT_WORDS};
use automat_base::slc_indirect::{self, Indirect};
use automat_iec::Elementary;
use automat_ir::{Program, SymbolType};

/// A variable named by a user: a fixed place, or an SLC indexed or
/// indirect address found in the image at each access.
#[derive(Clone, Debug, PartialEq)]
pub enum Locator {
    Fixed(Place),
    Slc(Box<SlcPlace>),
}

/// An indexed or indirect SLC address with its fixed parts resolved.
#[derive(Clone, Debug, PartialEq)]
pub struct SlcPlace {
    /// As the user wrote it (trimmed), for messages.
    text: String,
    ind: Indirect,
    /// S:24, for an indexed address.
    index_register: Option<Place>,
    file_word: Option<Place>,
    elem_word: Option<Place>,
    bit_word: Option<Place>,
    /// The data files it may lie in: its own, or (indirect file number)
    /// every file of its type.
    files: Vec<DataFile>,
}

/// A data-file array of the image.
#[derive(Clone, Debug, PartialEq)]
struct DataFile {
    number: u32,
    offset: u32,
    /// Words (F: floats) in the array.
    len: u32,
    /// Bytes per word or float.
    stride: u32,
}

/// Does `text` look like an indexed or indirect SLC address (so it is
/// located here rather than resolved as a path)?
pub fn looks_dynamic(text: &str) -> bool {
    let t = text.trim();
    if !slc_indirect::is_dynamic(t) {
        return false;
    }
    // A file letter, its number or `[word]`, then `:` or `/`: `N7:`,
    // `N[N7:0]:`, `B3/`, `I:` (so an IEC path `inst.arr[3]` is none).
    let b = t.trim_start_matches('#').as_bytes();
    if b.first()
        .is_none_or(|&c| FileType::from_letter(char::from(c)).is_none())
    {
        return false;
    }
    let mut i = 1 + b[1..].iter().take_while(|c| c.is_ascii_digit()).count();
    if i == 1 && b.get(1) == Some(&b'[') {
        match b[1..].iter().position(|&c| c == b']') {
            Some(close) => i = close + 2,
            None => return false,
        }
    }
    matches!(b.get(i), Some(b':' | b'/'))
}

/// Resolves `text` for reading and writing at run time.
pub fn locate(program: &Program, text: &str) -> Result<Locator, String> {
    let t = text.trim();
    if !looks_dynamic(t) {
        return path::resolve(program, t).map(Locator::Fixed);
    }
    let ind = slc_indirect::parse(&t.to_ascii_uppercase()).map_err(|e| format!("{e} ({t})"))?;
    let pointer = |a: Option<Address>| -> Result<Option<Place>, String> {
        a.map(|a| path::resolve_slc_address(program, a)).transpose()
    };
    let index_register =
        if ind.indexed {
            Some(path::resolve(program, "S:24").map_err(|e| {
                format!("`{t}` is indexed by S:24, which this program has not: {e}")
            })?)
        } else {
            None
        };
    let letter = ind.addr.ty.letter();
    let mut files: Vec<DataFile> = if ind.file_from.is_some() {
        program
            .symbols
            .entries()
            .iter()
            .filter_map(|e| {
                let n = e.path.strip_prefix(letter)?.parse::<u32>().ok()?;
                data_file(n, &e.ty, e.offset)
            })
            .filter(|f| FileType::of_number(f.number).is_none_or(|ty| ty == ind.addr.ty))
            .collect()
    } else {
        let n = ind.addr.file;
        program
            .symbols
            .get(&format!("{letter}{n}"))
            .and_then(|e| data_file(n, &e.ty, e.offset))
            .into_iter()
            .collect()
    };
    files.sort_by_key(|f| f.number);
    if files.is_empty() {
        return Err(format!(
            "`{t}`: the program has no {} data file{} (is this an SLC-500 program?)",
            if ind.file_from.is_some() {
                letter.to_string()
            } else {
                format!("{letter}{}", ind.addr.file)
            },
            if ind.file_from.is_some() { "s" } else { "" }
        ));
    }
    Ok(Locator::Slc(Box::new(SlcPlace {
        text: t.to_string(),
        index_register,
        file_word: pointer(ind.file_from)?,
        elem_word: pointer(ind.elem_from)?,
        bit_word: pointer(ind.bit_from)?,
        files,
        ind,
    })))
}

fn data_file(number: u32, ty: &SymbolType, offset: u32) -> Option<DataFile> {
    let SymbolType::Array { dims, stride, .. } = ty else {
        return None;
    };
    let [(lo, hi)] = dims.as_slice() else {
        return None;
    };
    Some(DataFile {
        number,
        offset,
        len: u32::try_from(hi.saturating_sub(*lo).saturating_add(1)).ok()?,
        stride: *stride,
    })
}

/// The INT word at `p` (a pointer word or S:24).
fn word(image: &[u8], p: &Place) -> Result<i64, String> {
    let at = usize::try_from(p.offset).map_err(|e| e.to_string())?;
    image
        .get(at..at.saturating_add(2))
        .and_then(|b| <[u8; 2]>::try_from(b).ok())
        .map(|b| i64::from(i16::from_le_bytes(b)))
        .ok_or_else(|| "a pointer word lies outside the image".to_string())
}

impl Locator {
    /// The place it names in `image`.
    pub fn place(&self, image: &[u8]) -> Result<Place, String> {
        match self {
            Locator::Fixed(p) => Ok(p.clone()),
            Locator::Slc(s) => s.place(image),
        }
    }

    /// The value in `image` in the `--print` form; `?` when the address
    /// lies outside its data file in this image.
    pub fn format(&self, image: &[u8]) -> String {
        match self.place(image) {
            Ok(p) => crate::value::format(image, &p),
            Err(_) => "?".to_string(),
        }
    }

    /// What is stored there (the same for every image): an SLC bit, an
    /// INT word or a REAL.
    pub fn ty(&self) -> PlaceType {
        match self {
            Locator::Fixed(p) => p.ty.clone(),
            Locator::Slc(s) => s.ty(),
        }
    }

    /// A bit of an SLC data file (printed and written as 1/0)?
    pub fn slc_bit(&self) -> bool {
        match self {
            Locator::Fixed(p) => p.slc_bit,
            Locator::Slc(s) => s.ind.addr.is_bit(),
        }
    }

    /// The direct address an indexed or indirect one names in `image`
    /// (`N7:3` for `N7:[N7:0]` while N7:0 = 3); `None` for a fixed place.
    pub fn direct(&self, image: &[u8]) -> Option<Result<String, String>> {
        match self {
            Locator::Fixed(_) => None,
            Locator::Slc(s) => Some(s.address(image).map(|(a, _)| a.to_string())),
        }
    }

    /// The fixed place, `None` for an indexed or indirect address.
    pub fn fixed(&self) -> Option<&Place> {
        match self {
            Locator::Fixed(p) => Some(p),
            Locator::Slc(_) => None,
        }
    }
}

impl SlcPlace {
    fn ty(&self) -> PlaceType {
        PlaceType::Elementary(if self.ind.addr.is_bit() {
            Elementary::Bool
        } else if self.ind.addr.ty == FileType::F {
            Elementary::Real
        } else {
            Elementary::Int
        })
    }

    /// The direct address it names in `image`, and the file holding it.
    fn address(&self, image: &[u8]) -> Result<(Address, &DataFile), String> {
        let t = &self.text;
        let a = self.ind.addr;
        let letter = a.ty.letter();
        let file = match &self.file_word {
            Some(p) => {
                let n = word(image, p)?;
                self.files
                    .iter()
                    .find(|f| i64::from(f.number) == n)
                    .ok_or_else(|| {
                        let list: Vec<String> =
                            self.files.iter().map(|f| f.number.to_string()).collect();
                        format!(
                            "indirect address `{t}`: the file number {n} is not one of the {letter} files of the program ({})",
                            list.join(", ")
                        )
                    })?
            }
            None => self
                .files
                .first()
                .ok_or_else(|| format!("`{t}`: no data file"))?,
        };
        // Only for the messages: no allocation on a read that succeeds.
        let name = || format!("{letter}{}", file.number);
        let io = matches!(a.ty, FileType::I | FileType::O);
        let per_elem = if io { IO_SLOT_WORDS } else { a.ty.words() };
        let len = i64::from(file.len);
        let number = |v: i64| u32::try_from(v).unwrap_or(0);
        let at = |elem: i64, part: Part| Address {
            ty: a.ty,
            file: file.number,
            elem: number(elem),
            part,
        };
        if self.ind.indexed {
            // B, N and F files only: one word (float) per element.
            let s24 = self
                .index_register
                .as_ref()
                .map_or(Ok(0), |p| word(image, p))?;
            let i = i64::from(a.index()) + s24;
            if !(0..len).contains(&i) {
                return Err(format!(
                    "indexed address `{t}` + S:24 ({s24}) lies outside data file {} ({} 0 to {})",
                    name(),
                    if a.ty == FileType::F {
                        "elements"
                    } else {
                        "words"
                    },
                    len - 1
                ));
            }
            return Ok((at(i, Part::Element), file));
        }
        if let (true, Some(p)) = (self.ind.flat, &self.bit_word) {
            let b = word(image, p)?;
            if !(0..len * 16).contains(&b) {
                return Err(format!(
                    "indirect address `{t}`: the bit {b} lies outside data file {} (bits 0 to {})",
                    name(),
                    len * 16 - 1
                ));
            }
            return Ok((at(b / 16, Part::Bit(0, number(b % 16))), file));
        }
        let elements = len / i64::from(per_elem);
        let elem = match &self.elem_word {
            Some(p) => word(image, p)?,
            None => i64::from(a.elem),
        };
        if !(0..elements).contains(&elem) {
            return Err(format!(
                "indirect address `{t}`: the element {elem} is not one of data file {} (0 to {})",
                name(),
                elements - 1
            ));
        }
        let part = match (a.part, &self.bit_word) {
            (Part::Bit(w, _), Some(p)) => {
                let b = word(image, p)?;
                if !(0..16).contains(&b) {
                    return Err(format!(
                        "indirect address `{t}`: the bit {b} is not 0 to 15"
                    ));
                }
                Part::Bit(w, number(b))
            }
            (part, _) => part,
        };
        Ok((at(elem, part), file))
    }

    fn place(&self, image: &[u8]) -> Result<Place, String> {
        let (a, file) = self.address(image)?;
        let offset = a
            .index()
            .checked_mul(file.stride)
            .and_then(|d| file.offset.checked_add(d))
            .ok_or_else(|| format!("`{}` lies outside the memory image", self.text))?;
        Ok(match a.part {
            Part::Bit(_, b) => Place {
                offset: offset.saturating_add(b / 8),
                bit: u8::try_from(b % 8).ok(),
                ty: PlaceType::Elementary(Elementary::Bool),
                slc_bit: true,
            },
            _ => Place {
                offset,
                bit: None,
                ty: self.ty(),
                slc_bit: false,
            },
        })
    }
}

#[cfg(test)]
#[path = "slc_place_tests.rs"]
mod tests;
