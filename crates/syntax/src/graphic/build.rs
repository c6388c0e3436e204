//! Building a network in code, for a front end that has no drawing (the
//! Allen-Bradley ladder): elements are numbered in the order they are
//! added, the left rail is made on first use, and positions come from the
//! rung (`y`) and the order within it (`x`), so the lowering's order is the
//! order of the source.

use super::model::*;
use super::text::Text;
use automat_base::Span;

/// A wire from an output of element `from`: its only output (`formal`
/// `None`), or a block's output pin such as `Q` or `ENO`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Wire {
    pub from: u32,
    pub formal: Option<String>,
}

impl Wire {
    /// The power flow (or value) out of element `id`.
    pub fn of(id: u32) -> Wire {
        Wire {
            from: id,
            formal: None,
        }
    }

    /// Output pin `formal` of block `id`.
    pub fn pin(id: u32, formal: &str) -> Wire {
        Wire {
            from: id,
            formal: Some(formal.to_string()),
        }
    }
}

/// What feeds one input pin of a block.
#[derive(Clone, Debug)]
pub enum PinSource {
    /// Wires from other elements (several: a wired OR), e.g. the rung's
    /// power flow into `EN`.
    Wires(Vec<Wire>),
    /// An expression read into the pin (an input variable element is made).
    Expr(Text),
    /// A VAR_IN_OUT pin bound to a variable (read and written by the block).
    InOut(Text),
}

/// One input pin of a block.
#[derive(Clone, Debug)]
pub struct BlockPin {
    pub formal: String,
    pub source: PinSource,
    pub negated: bool,
}

impl BlockPin {
    pub fn wired(formal: &str, wires: Vec<Wire>) -> BlockPin {
        BlockPin {
            formal: formal.to_string(),
            source: PinSource::Wires(wires),
            negated: false,
        }
    }

    pub fn expr(formal: &str, expr: Text) -> BlockPin {
        BlockPin {
            formal: formal.to_string(),
            source: PinSource::Expr(expr),
            negated: false,
        }
    }

    pub fn in_out(formal: &str, var: Text) -> BlockPin {
        BlockPin {
            formal: formal.to_string(),
            source: PinSource::InOut(var),
            negated: false,
        }
    }
}

/// Makes a [`Network`] element by element.
pub struct Builder {
    net: Network,
    next_id: u32,
    rail: Option<u32>,
    rung: u32,
    column: u32,
    span: Span,
}

impl Builder {
    /// An empty network; `span` is where its elements are until [`Builder::at`].
    pub fn new(lang: GraphLang, span: Span) -> Builder {
        Builder {
            net: Network {
                lang,
                elements: Vec::new(),
            },
            next_id: 1,
            rail: None,
            rung: 0,
            column: 0,
            span,
        }
    }

    /// Numbers the elements from `id` on (instead of 1): a front end that
    /// lowers several networks into one POU keeps their hidden
    /// `__ld_n<id>` names apart.
    pub fn first_id(mut self, id: u32) -> Builder {
        self.next_id = id.max(1);
        self
    }

    /// The source range the next elements stand for (their diagnostics and
    /// generated words point there).
    pub fn at(&mut self, span: Span) {
        self.span = span;
    }

    /// Starts the next rung (or FBD network): what follows is placed, and
    /// so executed, after everything added before.
    pub fn rung(&mut self) {
        self.rung += 1;
        self.column = 0;
    }

    /// The left power rail (one per network, made on first use).
    pub fn left_rail(&mut self) -> u32 {
        if let Some(r) = self.rail {
            return r;
        }
        let (x, y) = (-1.0, -1.0);
        let id = self.push_at(Kind::LeftRail, Vec::new(), true, x, y);
        self.rail = Some(id);
        id
    }

    /// The power flow of the left rail, as a wire.
    pub fn power(&mut self) -> Wire {
        Wire::of(self.left_rail())
    }

    pub fn contact(&mut self, var: Text, negated: bool, edge: EdgeKind, left: &[Wire]) -> u32 {
        let inputs = vec![self.pin(None, left)];
        self.push(Kind::Contact { negated, edge, var }, inputs, true)
    }

    pub fn coil(
        &mut self,
        var: Text,
        negated: bool,
        storage: Storage,
        edge: EdgeKind,
        left: &[Wire],
    ) -> u32 {
        let inputs = vec![self.pin(None, left)];
        let kind = Kind::Coil {
            negated,
            storage,
            edge,
            var,
        };
        self.push(kind, inputs, true)
    }

    /// A function (`instance` `None`) or function block call with its input
    /// pins and the names of its output pins (read with [`Wire::pin`]).
    pub fn block(
        &mut self,
        type_name: Text,
        instance: Option<Text>,
        pins: Vec<BlockPin>,
        outputs: &[&str],
    ) -> u32 {
        let mut inputs = Vec::with_capacity(pins.len());
        for p in pins {
            let (wires, in_out) = match p.source {
                PinSource::Wires(w) => (w, false),
                PinSource::Expr(e) => (vec![Wire::of(self.in_var(e))], false),
                PinSource::InOut(v) => (vec![Wire::of(self.in_var(v))], true),
            };
            let mut pin = self.pin(Some(p.formal), &wires);
            pin.negated = p.negated;
            pin.in_out = in_out;
            inputs.push(pin);
        }
        let mut el = self.element(
            Kind::Block {
                type_name,
                instance,
            },
            inputs,
            false,
        );
        el.outputs = outputs
            .iter()
            .map(|f| PinOut {
                formal: Some(f.to_string()),
                negated: false,
            })
            .collect();
        self.add(el)
    }

    /// Reads an expression (wire it with [`Wire::of`]).
    pub fn in_var(&mut self, expr: Text) -> u32 {
        self.push(
            Kind::InVar {
                negated: false,
                expr,
            },
            Vec::new(),
            true,
        )
    }

    /// Writes what `from` carries into the variable `expr`.
    pub fn out_var(&mut self, expr: Text, from: Wire) -> u32 {
        let inputs = vec![self.pin(None, &[from])];
        let kind = Kind::OutVar {
            negated: false,
            expr,
        };
        self.push(kind, inputs, false)
    }

    pub fn label(&mut self, name: Text) -> u32 {
        self.push(Kind::Label { name }, Vec::new(), false)
    }

    /// Jumps to `label` when powered.
    pub fn jump(&mut self, label: Text, left: &[Wire]) -> u32 {
        let inputs = vec![self.pin(None, left)];
        self.push(Kind::Jump { label }, inputs, false)
    }

    /// Returns from the POU when powered.
    pub fn ret(&mut self, left: &[Wire]) -> u32 {
        let inputs = vec![self.pin(None, left)];
        self.push(Kind::Return, inputs, false)
    }

    pub fn finish(self) -> Network {
        self.net
    }

    fn pin(&self, formal: Option<String>, wires: &[Wire]) -> PinIn {
        PinIn {
            formal,
            negated: false,
            edge: EdgeKind::None,
            in_out: false,
            conns: wires
                .iter()
                .map(|w| Conn {
                    from: w.from,
                    formal: w.formal.clone(),
                    span: self.span,
                })
                .collect(),
            span: self.span,
        }
    }

    fn element(&mut self, kind: Kind, inputs: Vec<PinIn>, output: bool) -> Element {
        self.column += 1;
        let (x, y) = (f64::from(self.column), f64::from(self.rung));
        self.element_at(kind, inputs, output, x, y)
    }

    fn element_at(
        &mut self,
        kind: Kind,
        inputs: Vec<PinIn>,
        output: bool,
        x: f64,
        y: f64,
    ) -> Element {
        let id = self.next_id;
        self.next_id = self.next_id.saturating_add(1);
        Element {
            id,
            kind,
            x,
            y,
            order: None,
            span: self.span,
            inputs,
            outputs: if output {
                vec![PinOut {
                    formal: None,
                    negated: false,
                }]
            } else {
                Vec::new()
            },
        }
    }

    fn add(&mut self, el: Element) -> u32 {
        let id = el.id;
        self.net.elements.push(el);
        id
    }

    fn push(&mut self, kind: Kind, inputs: Vec<PinIn>, output: bool) -> u32 {
        let el = self.element(kind, inputs, output);
        self.add(el)
    }

    fn push_at(&mut self, kind: Kind, inputs: Vec<PinIn>, output: bool, x: f64, y: f64) -> u32 {
        let el = self.element_at(kind, inputs, output, x, y);
        self.add(el)
    }
}
