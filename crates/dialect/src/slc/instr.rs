//! The instruction table: each implemented SLC-500 instruction with its
//! operands in RSLogix order, and the SLC instructions automat knows but
//! does not run (an error naming them, never a silent no-op).

/// What an operand must be.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A bit address (`B3/1`, `I:1/1`, `T4:0/DN`).
    Bit,
    /// An element of a T file.
    Timer,
    /// An element of a C file.
    Counter,
    /// A timer, counter or control element (RES).
    Structure,
    /// A word address or a constant.
    Source,
    /// A word address written.
    Dest,
    /// A time base 0.01 or 1.0.
    Base,
    /// An integer constant (preset, accumulator).
    Preset,
    /// A subroutine file number.
    File,
    /// A label number.
    Label,
    /// The start of a run of words (`#N7:10`).
    FileRef,
    /// A control element (`R6:0`).
    Control,
    /// A PID control block: an element of an N file with 23 words.
    Block,
    /// A length: 1 to 128 words (COP, FLL, FFL, FFU) or 1 to 2048 bits
    /// (BSL, BSR), checked by the instruction.
    Length,
}

pub struct Def {
    pub name: &'static str,
    pub operands: &'static [Kind],
}

use Kind::*;

const fn d(name: &'static str, operands: &'static [Kind], _output: bool) -> Def {
    Def { name, operands }
}

pub const TABLE: &[Def] = &[
    d("XIC", &[Bit], false),
    d("XIO", &[Bit], false),
    d("OTE", &[Bit], true),
    d("OTL", &[Bit], true),
    d("OTU", &[Bit], true),
    d("OSR", &[Bit], false),
    d("TON", &[Timer, Base, Preset, Preset], true),
    d("TOF", &[Timer, Base, Preset, Preset], true),
    d("RTO", &[Timer, Base, Preset, Preset], true),
    d("CTU", &[Counter, Preset, Preset], true),
    d("CTD", &[Counter, Preset, Preset], true),
    d("RES", &[Structure], true),
    d("EQU", &[Source, Source], false),
    d("NEQ", &[Source, Source], false),
    d("LES", &[Source, Source], false),
    d("LEQ", &[Source, Source], false),
    d("GRT", &[Source, Source], false),
    d("GEQ", &[Source, Source], false),
    d("LIM", &[Source, Source, Source], false),
    d("MEQ", &[Source, Source, Source], false),
    d("ADD", &[Source, Source, Dest], true),
    d("SUB", &[Source, Source, Dest], true),
    d("MUL", &[Source, Source, Dest], true),
    d("DIV", &[Source, Source, Dest], true),
    d("NEG", &[Source, Dest], true),
    d("ABS", &[Source, Dest], true),
    d("SQR", &[Source, Dest], true),
    d("SCL", &[Source, Source, Source, Dest], true),
    d("SCP", &[Source, Source, Source, Source, Source, Dest], true),
    d("CLR", &[Dest], true),
    d("MOV", &[Source, Dest], true),
    d("MVM", &[Source, Source, Dest], true),
    d("AND", &[Source, Source, Dest], true),
    d("OR", &[Source, Source, Dest], true),
    d("XOR", &[Source, Source, Dest], true),
    d("NOT", &[Source, Dest], true),
    d("JSR", &[File], true),
    d("SBR", &[], false),
    d("RET", &[], true),
    d("JMP", &[Label], true),
    d("LBL", &[Label], false),
    d("MCR", &[], true),
    d("TND", &[], true),
    d("COP", &[FileRef, FileRef, Length], true),
    d("FLL", &[Source, FileRef, Length], true),
    d("FFL", &[Source, FileRef, Control, Length, Preset], true),
    d("FFU", &[FileRef, Dest, Control, Length, Preset], true),
    d("BSL", &[FileRef, Control, Bit, Length], true),
    d("BSR", &[FileRef, Control, Bit, Length], true),
    d(
        "SQO",
        &[FileRef, Source, Dest, Control, Length, Preset],
        true,
    ),
    d(
        "SQC",
        &[FileRef, Source, Source, Control, Length, Preset],
        true,
    ),
    d("PID", &[Block, Source, Dest], true),
    d("AFI", &[], false),
    d("NOP", &[], false),
];

/// SLC-500 instructions that exist but automat does not run yet.
const UNIMPLEMENTED: &[&str] = &[
    "LFL", "LFU", "SQL", "CPT", "TOD", "FRD", "DCD", "ENC", "SWP", "ONS", "OSF", "HSC", "IIM",
    "IOM", "REF", "SUS", "INT", "STD", "STE", "STS", "UID", "UIE", "DDV", "SVC", "MSG", "ABL",
    "ACB", "ACI", "ACN", "AEX", "AHL", "ARD", "ARL", "AWA", "AWT", "ASC", "ASR", "DEG", "RAD",
    "SIN", "COS", "TAN", "ASN", "ACS", "ATN", "LN", "LOG", "XPY", "SRT", "STD", "FBC", "DDT",
    "BTR", "BTW", "RPC", "RHC", "TDF", "PTO", "PWM", "RTA", "HSL", "RAC", "REAL",
];

pub fn find(up: &str) -> Option<&'static Def> {
    TABLE.iter().find(|d| d.name == up)
}

pub fn is_unimplemented(up: &str) -> bool {
    UNIMPLEMENTED.contains(&up)
}

/// The operand list of a row, for messages.
pub fn describe(kinds: &[Kind]) -> String {
    if kinds.is_empty() {
        return "none".into();
    }
    kinds
        .iter()
        .map(|k| match k {
            Bit => "bit",
            Timer => "timer",
            Counter => "counter",
            Structure => "timer/counter/control",
            Source => "source",
            Dest => "destination",
            Base => "time base",
            Preset => "constant",
            File => "file",
            Label => "label",
            FileRef => "#file",
            Control => "control",
            Length => "length",
            Block => "control block",
        })
        .collect::<Vec<_>>()
        .join(", ")
}
