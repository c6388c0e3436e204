//! A rung through the graphical model of PLCopen LD
//! (`automat_syntax::graphic`): its contacts (XIC, XIO), coils (OTE, OTL,
//! OTU) and branches (`BST … NXB … BND` as wired ORs) become a
//! `graphic::Network` lowered by `graphic::lower`, so the rung's power flow
//! lives in the same hidden `__ld_n<id>` BOOLs as a PLCopen LD body.
//!
//! Every other instruction stays the ST of `emit.rs`, which reads and
//! writes the rung condition `__rc`: the network is cut there into
//! segments, the power flow into the instruction written to `__rc` (a coil
//! on `__rc`), its ST, and the next segment starting from a contact on
//! `__rc`. Why not blocks: timers, counters, OSR, the math and file
//! instructions work on the SLC's own words (T4:n's EN/TT/DN bits and ACC,
//! the OSR storage bit, the math status S:0 and S:5/0) in place, as
//! RSLogix shows them; IEC blocks with instances would keep a second copy
//! of that state. A rung with such an instruction inside a branch stays
//! all ST (`emit.rs`'s `__bs`/`__bo` branch slots): cutting there would cut
//! the wired OR.

use super::emit::Emitter;
use super::parse::{Elem, Ins, Rung};
use automat_syntax::graphic::build::{Builder, Wire};
use automat_syntax::graphic::{lower, EdgeKind, GraphLang, PouCtx, Storage, Text};

/// The instructions drawn as model elements.
fn in_model(mn: &str) -> bool {
    matches!(mn, "XIC" | "XIO" | "OTE" | "OTL" | "OTU")
}

/// Can the rung go through the model (no ST instruction inside a branch)?
pub fn fits(rung: &Rung) -> bool {
    let mut depth = 0usize;
    for e in &rung.elems {
        match e {
            Elem::Bst(_) => depth += 1,
            Elem::Bnd(_) => depth = depth.saturating_sub(1),
            Elem::Nxb(_) => {}
            Elem::Ins(i) if depth > 0 && !in_model(i.mn) => return false,
            // An indexed or indirect bit is no variable of the model.
            Elem::Ins(i)
                if in_model(i.mn)
                    && i.ops
                        .iter()
                        .any(|o| matches!(o, super::parse::Operand::Dyn(_))) =>
            {
                return false
            }
            Elem::Ins(_) => {}
        }
    }
    depth == 0
}

/// A segment being built: the builder and the wires of the power flow so
/// far (several: a wired OR), with the open branches.
struct Segment {
    b: Builder,
    power: Vec<Wire>,
    /// Per open branch: the power at its BST, the ends of its legs so far.
    open: Vec<(Vec<Wire>, Vec<Wire>)>,
    /// Elements added besides the rail and the `__rc` contact.
    used: bool,
}

impl<'a> Emitter<'a> {
    fn segment(&mut self, rung: &Rung) -> Segment {
        let mut b = Builder::new(GraphLang::Ld, rung.span).first_id(self.next_id);
        let rail = b.power();
        let rc = b.contact(
            Text::generated("__rc", rung.span),
            false,
            EdgeKind::None,
            &[rail],
        );
        Segment {
            b,
            power: vec![Wire::of(rc)],
            open: Vec::new(),
            used: false,
        }
    }

    /// Lowers a segment, its power flow left in `__rc`, into `s`.
    fn flush(&mut self, mut seg: Segment, rung: &Rung, s: &mut String) {
        if !seg.used {
            return;
        }
        seg.b.at(rung.span);
        seg.b.coil(
            Text::generated("__rc", rung.span),
            false,
            Storage::None,
            EdgeKind::None,
            &seg.power,
        );
        let net = seg.b.finish();
        self.next_id += net.elements.len() as u32;
        let l = lower(
            &net,
            &PouCtx::new("SLC", false).with_id_word("rung element"),
        );
        self.hidden.extend(l.hidden.iter().cloned());
        self.diags.extend(l.diagnostics.iter().cloned());
        for line in l.statements_text().lines() {
            s.push_str("    ");
            s.push_str(line.trim_start());
            s.push('\n');
        }
    }

    /// The rung's elements (after its `__rc := …` start) through the model.
    pub(super) fn rung_network(
        &mut self,
        n: u32,
        r: usize,
        rung: &Rung,
        level: &super::emit::Level,
        s: &mut String,
    ) {
        let mut seg = self.segment(rung);
        for e in &rung.elems {
            match e {
                Elem::Bst(_) => {
                    let at = seg.power.clone();
                    seg.open.push((at, Vec::new()));
                }
                Elem::Nxb(_) => {
                    if let Some((at, ends)) = seg.open.last_mut() {
                        ends.append(&mut seg.power);
                        seg.power = at.clone();
                    }
                }
                Elem::Bnd(_) => {
                    if let Some((_, mut ends)) = seg.open.pop() {
                        ends.append(&mut seg.power);
                        seg.power = ends;
                    }
                }
                Elem::Ins(i) if in_model(i.mn) => {
                    seg.used = true;
                    let id = self.element(&mut seg, i);
                    seg.power = vec![Wire::of(id)];
                }
                Elem::Ins(i) => {
                    self.flush(seg, rung, s);
                    let code = self.ins(n, r, i, level);
                    s.push_str(&code);
                    seg = self.segment(rung);
                }
            }
        }
        self.flush(seg, rung, s);
    }

    fn element(&mut self, seg: &mut Segment, i: &Ins) -> u32 {
        let var = Text::generated(&self.bit(i), i.span);
        seg.b.at(i.span);
        let p = &seg.power;
        let id = match i.mn {
            "XIC" => seg.b.contact(var, false, EdgeKind::None, p),
            "XIO" => seg.b.contact(var, true, EdgeKind::None, p),
            "OTL" => seg.b.coil(var, false, Storage::Set, EdgeKind::None, p),
            "OTU" => seg.b.coil(var, false, Storage::Reset, EdgeKind::None, p),
            _ => seg.b.coil(var, false, Storage::None, EdgeKind::None, p),
        };
        // The first emission (a subroutine JSR calls twice is inlined
        // twice): the one the HMI animates.
        self.elements
            .entry((i.span.file, i.span.start))
            .or_insert(id);
        id
    }
}
