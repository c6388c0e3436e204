//! The instruction set: typed three-address code over virtual registers.
//!
//! # Rules (every backend implements exactly these)
//! - A [`Func`] is a flat list of [`Inst`]; control moves by [`Inst::Jump`]
//!   and [`Inst::Branch`] to instruction indexes, and ends at [`Inst::Ret`].
//! - Every register has one [`RegClass`] for the whole function: `I64`
//!   (integers, bit strings, BOOL, times, dates, enums, chars, addresses),
//!   `F32` (REAL: every operation rounds to f32) or `F64` (LREAL).
//! - Loads sign- or zero-extend per [`MemTy`]; stores truncate. Arithmetic on
//!   `I64` is 64-bit wrapping; after an operation on a narrower IEC type the
//!   lowering emits [`Inst::Wrap`] to restore wrap-around at that width.
//! - Memory is one little-endian byte image; an [`Addr`] is relative to the
//!   image (`Abs`), the current instance (`This`) or a register holding an
//!   absolute offset (`Reg`).
//! - Instructions that can fault carry a site index into `Program::sites`.
//! - Registers of a function are private to it; since IEC forbids recursion
//!   a backend may give every function one static register window.

pub use crate::verify::{verify, Limits, VerifyError};

/// A virtual register of the current function.
pub type Reg = u32;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RegClass {
    I64,
    F32,
    F64,
}

/// The width and signedness of a memory access or a wrap.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MemTy {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    I64,
    F32,
    F64,
}

impl MemTy {
    pub fn size(self) -> u32 {
        match self {
            MemTy::I8 | MemTy::U8 => 1,
            MemTy::I16 | MemTy::U16 => 2,
            MemTy::I32 | MemTy::U32 | MemTy::F32 => 4,
            MemTy::I64 | MemTy::F64 => 8,
        }
    }

    /// The register class a value of this memory type lives in.
    pub fn class(self) -> RegClass {
        match self {
            MemTy::F32 => RegClass::F32,
            MemTy::F64 => RegClass::F64,
            _ => RegClass::I64,
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Base {
    Abs,
    This,
    Reg(Reg),
}

/// A memory operand: `base + offset`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Addr {
    pub base: Base,
    pub offset: u32,
}

impl Addr {
    pub fn abs(offset: u32) -> Addr {
        Addr {
            base: Base::Abs,
            offset,
        }
    }
    pub fn this(offset: u32) -> Addr {
        Addr {
            base: Base::This,
            offset,
        }
    }
    pub fn reg(r: Reg, offset: u32) -> Addr {
        Addr {
            base: Base::Reg(r),
            offset,
        }
    }
}

/// Integer binary operations (64-bit, wrapping).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum IntOp {
    Add,
    Sub,
    Mul,
    And,
    Or,
    Xor,
}

/// Shifts and rotations at a bit width (8, 16, 32, 64; 1 for BOOL).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ShiftOp {
    Shl,
    Shr,
    Rol,
    Ror,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FloatOp {
    Add,
    Sub,
    Mul,
    Div,
}

/// Comparisons; integer ones say whether they are signed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Cmp {
    Eq,
    Ne,
    Lt,
    Le,
    Gt,
    Ge,
}

/// Which fault a range check raises.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CheckKind {
    Index,
    Subrange,
    /// Dereferencing a reference: 0 is NULL (`FaultKind::Function`).
    Ref,
}

/// Standard functions implemented by the backend (with `automat-iec`).
/// Arguments are registers listed in [`Func::args`]; string operands are
/// absolute image offsets of a `u16 length + capacity units` buffer, and a
/// string result is written to the buffer given as first argument, whose
/// capacity (in characters) is the second argument.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Builtin {
    /// Unary math on F64 (`wide`) or F32 registers.
    Math(MathFn, bool),
    /// `EXPT` of reals: base, exponent (same class).
    Pow(bool),
    /// `EXPT` of a real by an integer.
    PowInt(bool),
    /// Elementary conversion between scalar register values.
    Convert(automat_iec::Elementary, automat_iec::Elementary),
    /// `TRUNC`: a real to an integer, rounding toward zero.
    Trunc(automat_iec::Elementary, automat_iec::Elementary),
    /// Conversion of a scalar to a string buffer: (dst, cap, value).
    ToString(automat_iec::Elementary, bool),
    /// Conversion of a string buffer to a scalar: (src).
    FromString(automat_iec::Elementary, bool),
    /// String builtins; `bool` = wide.
    Str(StrFn, bool),
    /// Time and date arithmetic.
    Time(TimeFn),
    /// `BCD_TO_*`: a bit string of type `.0` read as BCD into integer type `.1`;
    /// a nibble above 9 faults (`FaultKind::Function`).
    FromBcd(automat_iec::Elementary, automat_iec::Elementary),
    /// `*_TO_BCD`: an integer of type `.0` written as BCD in bit string type `.1`.
    ToBcd(automat_iec::Elementary, automat_iec::Elementary),
    /// `ATAN2(Y, X)` of reals (`wide`: LREAL).
    Atan2(bool),
    /// Date and time composition and decomposition.
    Date(DateFn),
    /// STRING <-> WSTRING: (dst, cap, src); `true`: to WSTRING.
    StrConv(bool),
}

/// CONCAT_DATE and friends: integer arguments in the standard's order,
/// results in the IEC representation (DATE days, TOD and DT nanoseconds).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DateFn {
    /// (year, month, day) -> DATE
    ConcatDate,
    /// (hour, minute, second, millisecond) -> TOD
    ConcatTod,
    /// (year, month, day, hour, minute, second, millisecond) -> DT
    ConcatDt,
    /// (DATE) -> 0 = Sunday .. 6 = Saturday
    DayOfWeek,
    /// One part of a DATE (days), TOD or DT (ns): (value) -> I64.
    Part(DatePart, DateSrc),
}

/// Which part SPLIT_* extracts.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DatePart {
    Year,
    Month,
    Day,
    Hour,
    Minute,
    Second,
    Millisecond,
}

/// The representation SPLIT_* reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DateSrc {
    /// Days since 1970-01-01.
    Date,
    /// Nanoseconds since midnight.
    Tod,
    /// Nanoseconds since 1970-01-01-00:00.
    Dt,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MathFn {
    Abs,
    Sqrt,
    Ln,
    Log,
    Exp,
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan,
    Neg,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum StrFn {
    /// (dst, cap, src): assignment with truncation.
    Assign,
    /// (src) -> I64
    Len,
    /// (dst, cap, s, l)
    Left,
    Right,
    /// (dst, cap, s, l, p)
    Mid,
    /// (dst, cap, a, b, ...)
    Concat,
    /// (dst, cap, a, b, p)
    Insert,
    /// (dst, cap, s, l, p)
    Delete,
    /// (dst, cap, a, b, l, p)
    Replace,
    /// (a, b) -> I64
    Find,
    /// (a, b) -> I64 (-1, 0, 1)
    Compare,
    /// (dst, cap, char code): a one-character string.
    FromChar,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TimeFn {
    AddTime,
    SubTime,
    AddTodTime,
    SubTodTime,
    SubTodTod,
    AddDtTime,
    SubDtTime,
    SubDtDt,
    SubDateDate,
    MulTime,
    DivTime,
    MulTimeReal,
    DivTimeReal,
    ConcatDateTod,
}

/// One instruction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Inst {
    IConst {
        dst: Reg,
        value: i64,
    },
    F32Const {
        dst: Reg,
        value: f32,
    },
    F64Const {
        dst: Reg,
        value: f64,
    },
    Mov {
        dst: Reg,
        src: Reg,
    },
    Load {
        dst: Reg,
        ty: MemTy,
        addr: Addr,
    },
    Store {
        src: Reg,
        ty: MemTy,
        addr: Addr,
    },
    /// `dst := (byte at addr >> bit) & 1`
    LoadBit {
        dst: Reg,
        addr: Addr,
        bit: u8,
    },
    /// Sets or clears one bit of the byte at `addr` from `src & 1`.
    StoreBit {
        src: Reg,
        addr: Addr,
        bit: u8,
    },
    /// `dst := absolute offset of addr`
    AddrOf {
        dst: Reg,
        addr: Addr,
    },
    /// Copies `len` bytes (regions may not overlap partially in a way that matters: memmove).
    Copy {
        dst: Addr,
        src: Addr,
        len: u32,
    },
    Int {
        op: IntOp,
        dst: Reg,
        a: Reg,
        b: Reg,
    },
    /// Truncating division; faults on zero. `MIN / -1` wraps.
    Div {
        signed: bool,
        dst: Reg,
        a: Reg,
        b: Reg,
        site: u32,
    },
    /// Remainder with the dividend's sign; faults on zero.
    Rem {
        signed: bool,
        dst: Reg,
        a: Reg,
        b: Reg,
        site: u32,
    },
    /// Wrapping two's complement negation.
    Neg {
        dst: Reg,
        src: Reg,
    },
    /// Bitwise complement (all 64 bits; wrap afterwards).
    Not {
        dst: Reg,
        src: Reg,
    },
    /// Sign- or zero-extends the low bits of `src` per `ty` (an integer MemTy).
    Wrap {
        dst: Reg,
        src: Reg,
        ty: MemTy,
    },
    Shift {
        op: ShiftOp,
        width: u8,
        dst: Reg,
        a: Reg,
        n: Reg,
    },
    /// Integer compare: `dst := (a cmp b) as 0/1`.
    ICmp {
        cmp: Cmp,
        signed: bool,
        dst: Reg,
        a: Reg,
        b: Reg,
    },
    Float {
        op: FloatOp,
        wide: bool,
        dst: Reg,
        a: Reg,
        b: Reg,
    },
    /// Float compare into an I64 register (IEEE: NaN compares false but `Ne`).
    FCmp {
        cmp: Cmp,
        wide: bool,
        dst: Reg,
        a: Reg,
        b: Reg,
    },
    /// F32 <-> F64 (`to_wide`: F32 -> F64).
    FResize {
        to_wide: bool,
        dst: Reg,
        src: Reg,
    },
    /// Faults unless `lo <= val <= hi` (signed).
    Check {
        kind: CheckKind,
        val: Reg,
        lo: i64,
        hi: i64,
        site: u32,
    },
    /// Like `Check`, with bounds in registers (arrays of unknown size,
    /// `ARRAY[*]`, whose bounds the caller passes).
    CheckDyn {
        kind: CheckKind,
        val: Reg,
        lo: Reg,
        hi: Reg,
        site: u32,
    },
    /// The scan timestamp in ns.
    Now {
        dst: Reg,
    },
    /// Standard function: arguments `args[first..first + count]`; `dst` may be `None`.
    Builtin {
        op: Builtin,
        dst: Option<Reg>,
        first: u32,
        count: u16,
        site: u32,
    },
    Jump {
        target: u32,
    },
    /// `if cond != 0 goto then else goto els`
    Branch {
        cond: Reg,
        then: u32,
        els: u32,
    },
    /// Runs `func` with `this` (an absolute offset computed from `this`).
    Call {
        func: u32,
        this: Addr,
    },
    Ret,
}

/// The code of one POU.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Func {
    pub name: String,
    /// The class of every register.
    pub regs: Vec<RegClass>,
    pub code: Vec<Inst>,
    /// Argument lists of [`Inst::Builtin`].
    pub args: Vec<Reg>,
    /// Where statements start: (instruction index, site), ascending; names
    /// the statement a fault without a site of its own (the watchdog) hit.
    pub stmt_sites: Vec<(u32, u32)>,
}

impl Func {
    pub fn new(name: impl Into<String>) -> Func {
        Func {
            name: name.into(),
            ..Func::default()
        }
    }

    pub fn reg(&mut self, class: RegClass) -> Reg {
        self.regs.push(class);
        self.regs.len() as Reg - 1
    }

    pub fn push(&mut self, inst: Inst) -> u32 {
        self.code.push(inst);
        self.code.len() as u32 - 1
    }

    /// The site of the statement instruction `pc` belongs to.
    pub fn stmt_site(&self, pc: u32) -> Option<u32> {
        let i = self.stmt_sites.partition_point(|&(at, _)| at <= pc);
        i.checked_sub(1)
            .and_then(|i| self.stmt_sites.get(i))
            .map(|&(_, s)| s)
    }

    /// The argument registers of a builtin call.
    pub fn builtin_args(&self, first: u32, count: u16) -> &[Reg] {
        self.args
            .get(first as usize..first as usize + count as usize)
            .unwrap_or(&[])
    }
}
