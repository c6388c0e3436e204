//! A rung through the graphical model of PLCopen LD
//! (`automat_syntax::graphic`): its contacts (XIC, XIO), coils (OTE, OTL,
//! OTU) and branches (`BST … NXB … BND` as wired ORs) become a
//! `graphic::Network` lowered by `graphic::lower`, so the rung's power flow
//! lives in the same hidden `__ld_n<id>` BOOLs as a PLCopen LD body.
//!
//! Every other instruction stays the ST of `emit.rs`, which reads and
//! writes the rung condition `__rc`: the instruction is a coil on a hidden
//! `__bin<k>` (the power into it, the instruction's frame in the HMI), its
//! ST inserted after the line the lowering gives that coil (`__rc :=
//! __bin<k>`, the ST, `__bout<k> := __rc`), and a contact on `__bout<k>`
//! (the condition after it), so a wired OR around it stays whole. So is an
//! XIC/XIO/OTE/OTL/OTU whose bit is indexed or indirect (its place is found
//! at run time: no variable of the model). Why not blocks: timers,
//! counters, OSR, the math and file instructions work on the SLC's own
//! words (T4:n's EN/TT/DN bits and ACC, the OSR storage bit, the math
//! status S:0 and S:5/0) in place, as RSLogix shows them; IEC blocks with
//! instances would keep a second copy of that state. JSR, JMP, RET, TND,
//! MCR, LBL and SBR steer the scan: on the rung itself the network is cut
//! there (the power so far into `__rc`, their ST, the next segment from a
//! contact on `__rc`); a rung with one inside a branch stays all ST
//! (`emit.rs`'s `__bs`/`__bo` branch slots).

use super::emit::Emitter;
use super::parse::{Elem, Ins, Rung};
use automat_syntax::graphic::build::{Builder, Wire};
use automat_syntax::graphic::{lower, EdgeKind, GraphLang, PouCtx, Storage, Text};

/// The instructions drawn as model elements.
fn in_model(mn: &str) -> bool {
    matches!(mn, "XIC" | "XIO" | "OTE" | "OTL" | "OTU")
}

/// Instructions that change where scanning goes: inside a branch they keep
/// the rung ST.
fn steers(mn: &str) -> bool {
    matches!(mn, "JSR" | "JMP" | "LBL" | "RET" | "TND" | "MCR" | "SBR")
}

/// An XIC, XIO, OTE, OTL or OTU whose bit is indexed or indirect: its
/// place is found at run time, so it is no variable of the model; it runs
/// as the ST of `emit.rs` on the power into it, as a box does.
fn dynamic_bit(i: &Ins) -> bool {
    i.ops
        .iter()
        .any(|o| matches!(o, super::parse::Operand::Dyn(_)))
}

/// Can the rung go through the model (no JSR, JMP, RET, TND or MCR inside
/// a branch)?
pub fn fits(rung: &Rung) -> bool {
    let mut depth = 0usize;
    for e in &rung.elems {
        match e {
            Elem::Bst(_) => depth += 1,
            Elem::Bnd(_) => depth = depth.saturating_sub(1),
            Elem::Nxb(_) => {}
            Elem::Ins(i) if depth > 0 && steers(i.mn) => return false,
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
    /// The ST instructions inside its branches: the hidden BOOL their
    /// power goes into and their ST, run where the lowered network sets it.
    inner: Vec<(String, String)>,
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
            inner: Vec::new(),
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
            let line = line.trim_start();
            s.push_str("    ");
            s.push_str(line);
            s.push('\n');
            if let Some((_, code)) = seg
                .inner
                .iter()
                .find(|(var, _)| line.starts_with(&format!("{var} :=")))
            {
                s.push_str(code);
            }
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
                Elem::Ins(i) if in_model(i.mn) && !dynamic_bit(i) => {
                    seg.used = true;
                    let id = self.element(&mut seg, i);
                    seg.power = vec![Wire::of(id)];
                }
                Elem::Ins(i) if !seg.open.is_empty() || !steers(i.mn) => {
                    // A coil takes the power into the instruction (its
                    // frame in the HMI), the instruction's ST runs on it, a
                    // contact gives the condition after it. Inside a branch
                    // this keeps the wired OR whole; on the rung itself it
                    // gives a box its own frame too.
                    seg.used = true;
                    let k = self
                        .hidden
                        .iter()
                        .filter(|h| h.starts_with("__bin"))
                        .count();
                    let (into, out) = (format!("__bin{k}"), format!("__bout{k}"));
                    self.hidden.push(into.clone());
                    self.hidden.push(out.clone());
                    seg.b.at(i.span);
                    let coil = seg.b.coil(
                        Text::generated(&into, i.span),
                        false,
                        Storage::None,
                        EdgeKind::None,
                        &seg.power,
                    );
                    let after = seg.b.contact(
                        Text::generated(&out, i.span),
                        false,
                        EdgeKind::None,
                        &[Wire::of(coil)],
                    );
                    self.elements
                        .entry((i.span.file, i.span.start))
                        .or_insert(coil);
                    let code = self.ins(n, r, i, level);
                    seg.inner.push((
                        into.clone(),
                        format!("    __rc := {into};\n{code}    {out} := __rc;\n"),
                    ));
                    seg.power = vec![Wire::of(after)];
                }
                // JSR, JMP, RET, TND, MCR, LBL, SBR on the rung itself:
                // the network is cut there (their ST steers the scan).
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
