//! A program file's rungs as an LD drawing sheet (`automat draw`): the
//! left rail, then each rung's instructions wired left to right, a branch's
//! legs in parallel from the element before `BST` and wired together into
//! the element after `BND`. XIC and XIO are contacts, OTE/OTL/OTU coils
//! (plain, S, R), every other instruction a box with its operands. Placed
//! on a grid: one column per instruction of a series, one row per branch
//! leg, rungs one under the other with their comment above. Each operand's text is its symbol from the
//! table and its address; above it, a note with the symbol table's
//! description (a box: each described operand's symbol and description),
//! shortened to fit the column.

use super::parse::{Elem, Ins, Operand, Project};
use automat_plcopen::sheet::{NodeKind, Pin, Sheet, SheetLang, SheetNode, Wire};

/// Where power comes from: elements and, for a box, its output pin.
type From = Vec<(u32, Option<String>)>;

struct Build<'a> {
    p: &'a Project,
    nodes: Vec<SheetNode>,
    /// The instruction each node draws (for the HMI's live values).
    drawn: Vec<(u32, Ins)>,
    /// The top of the rung being placed.
    top: f64,
}

/// Column width and row height of the ladder grid.
const COL: f64 = 170.0;
/// A row: the element (a box up to 40 high), its operand text and the
/// description note above it.
const ROW: f64 = 110.0;
const LEFT: f64 = 60.0;
/// The note's place above its element, and the room above a rung for the
/// rung comment and the first row's notes.
const NOTE_UP: f64 = 52.0;
const RUNG_UP: f64 = 90.0;
/// The longest note (characters) a column holds.
const NOTE_CHARS: usize = 26;

fn pin(name: &str, from: &From) -> Pin {
    Pin {
        name: name.to_string(),
        negated: false,
        edge: "",
        rel: None,
        wires: from
            .iter()
            .map(|(id, p)| Wire {
                from: *id,
                from_pin: p.clone(),
                points: Vec::new(),
            })
            .collect(),
    }
}

impl Build<'_> {
    fn node_at(
        &mut self,
        kind: NodeKind,
        text: String,
        mark: &'static str,
        ins: Vec<Pin>,
        outs: Vec<Pin>,
        pos: Option<(f64, f64)>,
    ) -> u32 {
        let id = self.nodes.len() as u32 + 1;
        self.nodes.push(SheetNode {
            id,
            kind,
            pos,
            size: None,
            text,
            instance: String::new(),
            mark,
            ins,
            outs,
            actions: Vec::new(),
        });
        id
    }

    /// An operand as written in the drawing: its symbol and address.
    fn operand(&self, o: &Operand) -> String {
        match o {
            Operand::Addr(a) => {
                let text = address_text(*a);
                match self.p.symbols.iter().find(|s| s.addr == *a) {
                    Some(s) => format!("{} {text}", s.name),
                    None => text,
                }
            }
            Operand::Int(v) => v.to_string(),
            Operand::Real(v) => v.to_string(),
            Operand::Base(ms) => format!("{}", *ms as f64 / 1000.0),
            Operand::Number(n) => n.to_string(),
            Operand::Dyn(d) => d.text.clone(),
        }
    }

    /// The description of an operand named by a symbol of the table.
    fn description(&self, o: &Operand) -> Option<(&str, &str)> {
        let Operand::Addr(a) = o else { return None };
        self.p
            .symbols
            .iter()
            .find(|s| s.addr == *a && !s.desc.is_empty())
            .map(|s| (s.name.as_str(), s.desc.as_str()))
    }

    /// The note above an instruction: its operands' descriptions.
    fn note(&mut self, i: &Ins, (x, y): (f64, f64)) {
        let descs: Vec<(&str, &str)> = i.ops.iter().filter_map(|o| self.description(o)).collect();
        let box_like = !matches!(i.mn, "XIC" | "XIO" | "OTE" | "OTL" | "OTU");
        let text = descs
            .iter()
            .map(|(name, desc)| {
                if box_like {
                    format!("{name}: {desc}")
                } else {
                    desc.to_string()
                }
            })
            .collect::<Vec<_>>()
            .join("; ");
        if text.is_empty() {
            return;
        }
        let text = if text.chars().count() > NOTE_CHARS {
            let mut t: String = text.chars().take(NOTE_CHARS - 3).collect();
            t.push_str("...");
            t
        } else {
            text
        };
        self.node_at(
            NodeKind::Comment,
            text,
            "",
            Vec::new(),
            Vec::new(),
            Some((x, y - NOTE_UP)),
        );
    }

    fn ins(&mut self, i: &Ins, from: &From, col: usize, row: usize) -> From {
        let at = (LEFT + col as f64 * COL, self.top + row as f64 * ROW);
        self.note(i, at);
        let pos = Some(at);
        let ops: Vec<String> = i.ops.iter().map(|o| self.operand(o)).collect();
        let (kind, mark) = match i.mn {
            "XIC" => (NodeKind::Contact, ""),
            "XIO" => (NodeKind::Contact, "/"),
            "OTE" => (NodeKind::Coil, ""),
            "OTL" => (NodeKind::Coil, "S"),
            "OTU" => (NodeKind::Coil, "R"),
            _ => (NodeKind::Block, ""),
        };
        let id = if kind == NodeKind::Block {
            let text = std::iter::once(i.mn.to_string())
                .chain(ops)
                .collect::<Vec<_>>()
                .join(" ");
            let id = self.node_at(
                kind,
                text,
                mark,
                vec![pin("EN", from)],
                vec![pin("ENO", &Vec::new())],
                pos,
            );
            self.drawn.push((id, i.clone()));
            return vec![(id, Some("ENO".to_string()))];
        } else {
            self.node_at(
                kind,
                ops.join(" "),
                mark,
                vec![pin("", from)],
                vec![pin("", &Vec::new())],
                pos,
            )
        };
        self.drawn.push((id, i.clone()));
        vec![(id, None)]
    }

    /// Places `elems` (a series, branches nested) from `from` at grid
    /// column `col`, row `row`; returns what the series ends on, the next
    /// free column and the rows it took.
    fn series(
        &mut self,
        elems: &[Elem],
        from: From,
        mut col: usize,
        row: usize,
    ) -> (From, usize, usize) {
        let mut at = from;
        let mut rows = 1;
        let mut k = 0;
        while k < elems.len() {
            match &elems[k] {
                Elem::Ins(i) => {
                    at = self.ins(i, &at, col, row);
                    col += 1;
                    k += 1;
                }
                Elem::Bst(_) => {
                    // The legs up to the matching BND.
                    let mut depth = 0;
                    let mut legs: Vec<&[Elem]> = Vec::new();
                    let mut start = k + 1;
                    let mut end = elems.len();
                    for (j, e) in elems.iter().enumerate().skip(k) {
                        match e {
                            Elem::Bst(_) => depth += 1,
                            Elem::Nxb(_) if depth == 1 => {
                                legs.push(&elems[start..j]);
                                start = j + 1;
                            }
                            Elem::Bnd(_) => {
                                depth -= 1;
                                if depth == 0 {
                                    legs.push(&elems[start..j]);
                                    end = j;
                                    break;
                                }
                            }
                            _ => {}
                        }
                    }
                    let mut joined = From::new();
                    let (mut used, mut end_col) = (0, col);
                    for leg in legs {
                        let (ends, c, h) = self.series(leg, at.clone(), col, row + used);
                        used += h;
                        end_col = end_col.max(c);
                        for f in ends {
                            if !joined.contains(&f) {
                                joined.push(f);
                            }
                        }
                    }
                    rows = rows.max(used);
                    col = end_col;
                    at = joined;
                    k = end + 1;
                }
                Elem::Nxb(_) | Elem::Bnd(_) => k += 1,
            }
        }
        (at, col, rows)
    }
}

/// The address as RSLogix writes it (`B3:0/1`, `T4:0/DN`, `I:1/1`).
pub(super) fn address_text(a: automat_base::slc::Address) -> String {
    use automat_base::slc::{FileType, Part};
    let file = match a.ty {
        FileType::I | FileType::O | FileType::S => a.ty.letter().to_string(),
        t => format!("{}{}", t.letter(), a.file),
    };
    let named = |w: u32, b: Option<u32>| -> Option<&'static str> {
        let names: &[(&str, u32, Option<u32>)] = match a.ty {
            FileType::T => &[
                ("EN", 0, Some(15)),
                ("TT", 0, Some(14)),
                ("DN", 0, Some(13)),
                ("PRE", 1, None),
                ("ACC", 2, None),
            ],
            FileType::C => &[
                ("CU", 0, Some(15)),
                ("CD", 0, Some(14)),
                ("DN", 0, Some(13)),
                ("OV", 0, Some(12)),
                ("UN", 0, Some(11)),
                ("UA", 0, Some(10)),
                ("PRE", 1, None),
                ("ACC", 2, None),
            ],
            FileType::R => &[
                ("EN", 0, Some(15)),
                ("EU", 0, Some(14)),
                ("DN", 0, Some(13)),
                ("EM", 0, Some(12)),
                ("ER", 0, Some(11)),
                ("UL", 0, Some(10)),
                ("IN", 0, Some(9)),
                ("FD", 0, Some(8)),
                ("LEN", 1, None),
                ("POS", 2, None),
            ],
            _ => &[],
        };
        names.iter().find(|n| n.1 == w && n.2 == b).map(|n| n.0)
    };
    let io = matches!(a.ty, FileType::I | FileType::O);
    match a.part {
        Part::Element => format!("{file}:{}", a.elem),
        Part::Word(w) if io => format!("{file}:{}.{w}", a.elem),
        Part::Word(w) => match named(w, None) {
            Some(n) => format!("{file}:{}.{n}", a.elem),
            None => format!("{file}:{}.{w}", a.elem),
        },
        Part::Bit(w, b) if io && w > 0 => format!("{file}:{}.{w}/{b}", a.elem),
        Part::Bit(w, b) => match named(w, Some(b)) {
            Some(n) => format!("{file}:{}/{n}", a.elem),
            None => format!("{file}:{}/{b}", a.elem),
        },
    }
}

/// The sheet of program file `lad` (`None` when the project has none).
pub fn sheet(p: &Project, lad: u32) -> Option<Sheet> {
    sheet_drawn(p, lad).map(|(s, _)| s)
}

/// The sheet of program file `lad` and the instruction each of its
/// nodes draws (by node id).
pub fn sheet_drawn(p: &Project, lad: u32) -> Option<(Sheet, Vec<(u32, Ins)>)> {
    let f = p.files.get(&lad)?;
    let mut b = Build {
        p,
        nodes: Vec::new(),
        drawn: Vec::new(),
        top: RUNG_UP + 10.0,
    };
    // One left rail per rung, the rung's comment above it.
    for (r, rung) in f.rungs.iter().enumerate() {
        let text = match &rung.comment {
            Some(c) => format!("rung {r}: {c}"),
            None => format!("rung {r}"),
        };
        b.node_at(
            NodeKind::Comment,
            text,
            "",
            Vec::new(),
            Vec::new(),
            Some((LEFT - 40.0, b.top - RUNG_UP)),
        );
        let rail = b.node_at(
            NodeKind::LeftRail,
            String::new(),
            "",
            Vec::new(),
            vec![pin("", &Vec::new())],
            Some((LEFT - 40.0, b.top)),
        );
        let (_, _, rows) = b.series(&rung.elems, vec![(rail, None)], 0, 0);
        b.top += rows as f64 * ROW - ROW + 40.0 + RUNG_UP + 10.0;
    }
    let name = if f.name.is_empty() {
        format!("LAD {lad}")
    } else {
        format!("LAD {lad} {}", f.name)
    };
    let sheet = Sheet {
        pou: name,
        lang: SheetLang::Ld,
        nodes: b.nodes,
    };
    Some((sheet, b.drawn))
}
