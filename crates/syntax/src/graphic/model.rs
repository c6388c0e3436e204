//! Elements and connections of an LD or FBD body, whatever file it was
//! read from.
//!
//! An element is known by its `id` (PLCopen's `localId`; any number unique
//! in the network for another front end) and placed at `(x, y)`: the
//! position decides the order of what the wires leave free (rungs from the
//! top, then top to bottom, left to right; see `lower.rs`), so a front end
//! without a drawing gives each rung a growing `y` and each element of a
//! rung a growing `x` ([`super::build::Builder`] does). Texts carry their
//! own source offsets ([`Text`]), spans point at the element in its file.

use super::text::Text;
use automat_base::Span;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GraphLang {
    Ld,
    Fbd,
}

/// One body: its elements in file order.
#[derive(Clone, Debug)]
pub struct Network {
    pub lang: GraphLang,
    pub elements: Vec<Element>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EdgeKind {
    None,
    Rising,
    Falling,
}

/// What a coil does with its power flow.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Storage {
    /// `var := power` (or its negation, or an edge of it)
    None,
    /// `IF power THEN var := TRUE`
    Set,
    /// `IF power THEN var := FALSE`
    Reset,
}

#[derive(Clone, Debug)]
pub enum Kind {
    LeftRail,
    RightRail,
    /// `--| |--`, `--|/|--`, `--|P|--`, `--|N|--` on `var`.
    Contact {
        negated: bool,
        edge: EdgeKind,
        var: Text,
    },
    /// `--( )--` and its negated, set, reset, rising and falling forms.
    Coil {
        negated: bool,
        storage: Storage,
        edge: EdgeKind,
        var: Text,
    },
    /// A function (no instance) or function block instance.
    Block {
        type_name: Text,
        instance: Option<Text>,
    },
    /// Reads an expression.
    InVar {
        negated: bool,
        expr: Text,
    },
    /// Writes its input to a variable.
    OutVar {
        negated: bool,
        expr: Text,
    },
    /// Reads a variable and, when its input is connected, writes it.
    InOutVar {
        expr: Text,
    },
    Label {
        name: Text,
    },
    Jump {
        label: Text,
    },
    Return,
    /// The named end of a wire continued elsewhere by a continuation.
    Connector {
        name: String,
    },
    Continuation {
        name: String,
    },
}

/// One element: its `localId`, kind, position and pins.
#[derive(Clone, Debug)]
pub struct Element {
    pub id: u32,
    pub kind: Kind,
    pub x: f64,
    pub y: f64,
    /// `executionOrderId` when the file gives a non-zero one.
    pub order: Option<u32>,
    pub span: Span,
    pub inputs: Vec<PinIn>,
    pub outputs: Vec<PinOut>,
}

/// An input pin and the outputs wired to it (several: a wired OR).
#[derive(Clone, Debug)]
pub struct PinIn {
    /// `formalParameter` of a block pin; `None` for other elements.
    pub formal: Option<String>,
    pub negated: bool,
    pub edge: EdgeKind,
    /// A block's VAR_IN_OUT pin.
    pub in_out: bool,
    pub conns: Vec<Conn>,
    pub span: Span,
}

/// A wire from output `formal` of element `from`.
#[derive(Clone, Debug)]
pub struct Conn {
    pub from: u32,
    pub formal: Option<String>,
    pub span: Span,
}

#[derive(Clone, Debug)]
pub struct PinOut {
    pub formal: Option<String>,
    pub negated: bool,
}
