//! FST operands (`I0.1`, `TP3`, `FU32`, `P1`) and where they live.
//!
//! Every operand is a hidden global of the generated ST at a fixed direct
//! address, so a symbol of the allocation list is one more global at the
//! same address (reading and writing either is the same memory), and the
//! operand names resolve in `--print`, `--trace` and scenarios: a bit
//! `I0.1` is bit 1 of the word global `I0` (= `IW0`). Layout: inputs
//! `%IWn`, outputs `%QWn`, flag words `%MWn` (n < 256); in the memory area
//! after them timer status bits (bytes 512–543), counter status bits
//! (544–575), then the words TP, TW, CP, CW, R, FU, 256 of each from
//! `%MW288` on. Programs are not in memory: `Pn` is a structure
//! `Pn.run` / `Pn.step`.

/// What kind of operand.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Kind {
    I,
    O,
    F,
    T,
    C,
    P,
    Iw,
    Ow,
    Fw,
    Tp,
    Tw,
    Cp,
    Cw,
    Fu,
    R,
}

/// An operand: kind, number and (for In.m, On.m, Fn.m) bit.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Operand {
    pub kind: Kind,
    pub n: u32,
    pub bit: u32,
}

/// The greatest word number of inputs and outputs, flags, others.
pub const MAX_IO: u32 = 31;
pub const MAX_N: u32 = 255;
pub const MAX_PROGRAM: u32 = 63;

/// Prefixes, longest first.
const PREFIXES: &[(&str, Kind)] = &[
    ("IW", Kind::Iw),
    ("OW", Kind::Ow),
    ("FW", Kind::Fw),
    ("TP", Kind::Tp),
    ("TW", Kind::Tw),
    ("CP", Kind::Cp),
    ("CW", Kind::Cw),
    ("FU", Kind::Fu),
    ("I", Kind::I),
    ("O", Kind::O),
    ("F", Kind::F),
    ("T", Kind::T),
    ("C", Kind::C),
    ("P", Kind::P),
    ("R", Kind::R),
];

/// Parses an upper-case word: `None` when it is not spelled as an operand,
/// `Some(Err(why))` when it is one out of range.
pub fn parse(up: &str) -> Option<Result<Operand, String>> {
    let (prefix, kind) = PREFIXES.iter().find(|(p, _)| {
        up.strip_prefix(p)
            .is_some_and(|r| r.starts_with(|c: char| c.is_ascii_digit()))
    })?;
    let rest = up.get(prefix.len()..)?;
    let bits = matches!(kind, Kind::I | Kind::O | Kind::F);
    let (n, bit) = match rest.split_once('.') {
        Some((n, b)) if bits => (n, Some(b)),
        Some(_) => return None,
        None if bits => return None,
        None => (rest, None),
    };
    let num = |s: &str| -> Option<u32> {
        if !s.is_empty() && s.bytes().all(|c| c.is_ascii_digit()) {
            Some(s.parse::<u32>().unwrap_or(u32::MAX))
        } else {
            None
        }
    };
    let n = num(n)?;
    let bit = match bit {
        Some(b) => num(b)?,
        None => 0,
    };
    let max = match kind {
        Kind::I | Kind::O | Kind::Iw | Kind::Ow => MAX_IO,
        Kind::P => MAX_PROGRAM,
        _ => MAX_N,
    };
    if n > max {
        return Some(Err(format!(
            "operand out of range, {up}: the number is 0 to {max}"
        )));
    }
    if bit > 15 {
        return Some(Err(format!(
            "operand out of range, {up}: the bit is 0 to 15"
        )));
    }
    Some(Ok(Operand {
        kind: *kind,
        n,
        bit,
    }))
}

impl Operand {
    /// A single-bit operand (SBO)?
    pub fn is_bit(self) -> bool {
        matches!(
            self.kind,
            Kind::I | Kind::O | Kind::F | Kind::T | Kind::C | Kind::P
        )
    }

    /// Inputs are read-only.
    pub fn is_input(self) -> bool {
        matches!(self.kind, Kind::I | Kind::Iw)
    }

    /// The name FST writes (`I0.1`, `TP3`).
    pub fn name(self) -> String {
        let n = self.n;
        match self.kind {
            Kind::I => format!("I{n}.{}", self.bit),
            Kind::O => format!("O{n}.{}", self.bit),
            Kind::F => format!("F{n}.{}", self.bit),
            Kind::T => format!("T{n}"),
            Kind::C => format!("C{n}"),
            Kind::P => format!("P{n}"),
            Kind::Iw => format!("IW{n}"),
            Kind::Ow => format!("OW{n}"),
            Kind::Fw => format!("FW{n}"),
            Kind::Tp => format!("TP{n}"),
            Kind::Tw => format!("TW{n}"),
            Kind::Cp => format!("CP{n}"),
            Kind::Cw => format!("CW{n}"),
            Kind::Fu => format!("FU{n}"),
            Kind::R => format!("R{n}"),
        }
    }

    /// The ST expression naming it in the generated code.
    pub fn st(self) -> String {
        let n = self.n;
        match self.kind {
            Kind::I => format!("IW{n}.{}", self.bit),
            Kind::O => format!("OW{n}.{}", self.bit),
            Kind::F => format!("FW{n}.{}", self.bit),
            Kind::P => format!("P{n}.RUN"),
            _ => self.name(),
        }
    }

    /// The direct address of the operand (`None`: a program).
    pub fn address(self) -> Option<String> {
        let (n, m) = (self.n, self.bit);
        let word = |area: char, w: u32| format!("%{area}W{w}");
        let bit = |area: char, byte: u32, b: u32| format!("%{area}X{byte}.{b}");
        Some(match self.kind {
            Kind::I => bit('I', 2 * n + m / 8, m % 8),
            Kind::O => bit('Q', 2 * n + m / 8, m % 8),
            Kind::F => bit('M', 2 * n + m / 8, m % 8),
            Kind::T => bit('M', 512 + n / 8, n % 8),
            Kind::C => bit('M', 544 + n / 8, n % 8),
            Kind::P => return None,
            Kind::Iw => word('I', n),
            Kind::Ow => word('Q', n),
            Kind::Fw => word('M', n),
            Kind::Tp => word('M', 288 + n),
            Kind::Tw => word('M', 544 + n),
            Kind::Cp => word('M', 800 + n),
            Kind::Cw => word('M', 1056 + n),
            Kind::R => word('M', 1312 + n),
            Kind::Fu => word('M', 1568 + n),
        })
    }

    /// The word global(s) to declare for it: (name, address).
    pub fn globals(self) -> Vec<(String, String, &'static str)> {
        let n = self.n;
        let w = |k: Kind| Operand { kind: k, n, bit: 0 };
        let word = |k: Kind| {
            let o = w(k);
            (o.name(), o.address().unwrap_or_default(), "WORD")
        };
        let alias = |name: String, k: Kind| (name, w(k).address().unwrap_or_default(), "WORD");
        match self.kind {
            Kind::I | Kind::Iw => vec![word(Kind::Iw), alias(format!("I{n}"), Kind::Iw)],
            Kind::O | Kind::Ow => vec![word(Kind::Ow), alias(format!("O{n}"), Kind::Ow)],
            Kind::F | Kind::Fw => vec![word(Kind::Fw), alias(format!("F{n}"), Kind::Fw)],
            Kind::T | Kind::Tp | Kind::Tw => vec![
                (
                    format!("T{n}"),
                    w(Kind::T).address().unwrap_or_default(),
                    "BOOL",
                ),
                word(Kind::Tp),
                word(Kind::Tw),
            ],
            Kind::C | Kind::Cp | Kind::Cw => vec![
                (
                    format!("C{n}"),
                    w(Kind::C).address().unwrap_or_default(),
                    "BOOL",
                ),
                word(Kind::Cp),
                word(Kind::Cw),
            ],
            Kind::R => vec![word(Kind::R)],
            Kind::Fu => vec![word(Kind::Fu)],
            Kind::P => vec![],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn operands_parse_with_ranges() {
        let p = |s: &str| parse(s).map(|r| r.map(|o| (o.kind, o.n, o.bit)));
        assert_eq!(p("I0.1"), Some(Ok((Kind::I, 0, 1))));
        assert_eq!(p("TP12"), Some(Ok((Kind::Tp, 12, 0))));
        assert_eq!(p("FU32"), Some(Ok((Kind::Fu, 32, 0))));
        assert_eq!(p("P1"), Some(Ok((Kind::P, 1, 0))));
        assert_eq!(p("START"), None);
        assert_eq!(p("I0"), None);
        assert!(matches!(p("T256"), Some(Err(_))));
        assert!(matches!(p("O0.16"), Some(Err(_))));
        assert!(matches!(p("P64"), Some(Err(_))));
    }

    #[test]
    fn addresses() {
        let a = |s: &str| parse(s).and_then(|r| r.ok()).and_then(|o| o.address());
        assert_eq!(a("I1.0").as_deref(), Some("%IX2.0"));
        assert_eq!(a("O0.9").as_deref(), Some("%QX1.1"));
        assert_eq!(a("T9").as_deref(), Some("%MX513.1"));
        assert_eq!(a("TP0").as_deref(), Some("%MW288"));
    }
}
