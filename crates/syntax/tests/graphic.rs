//! The graphical model without XML: an LD network built in code, lowered to
//! Structured Text, put in a generated POU and parsed back, with the spans
//! of the tree and of the diagnostics in the network's own source.

use automat_base::{Code, FileId, Interner, Span};
use automat_syntax::ast::{Body, Item, StmtKind};
use automat_syntax::graphic::build::{BlockPin, Builder, Wire};
use automat_syntax::graphic::{
    lower, parse_generated, EdgeKind, Generated, GraphLang, PouCtx, Storage, Text,
};
use automat_syntax::Options;

const FILE: FileId = FileId(3);

fn sp(start: u32, end: u32) -> Span {
    Span::new(FILE, start, end)
}

/// Rung 1: `Start` and not `Stop`, or the seal-in `Motor`, drives `Motor`.
/// Rung 2: a TON on `Motor` whose `Q` sets `Lamp`, and a rising edge of
/// `Start` into `Count`. Rung 3: jump over rung 4 when `Skip`.
fn network() -> automat_syntax::graphic::Network {
    let mut b = Builder::new(GraphLang::Ld, sp(0, 100));
    b.at(sp(10, 15));
    let p = b.left_rail();
    let start = b.contact(Text::at("Start", 10), false, EdgeKind::None, &[Wire::of(p)]);
    let stop = b.contact(
        Text::at("Stop", 20),
        true,
        EdgeKind::None,
        &[Wire::of(start)],
    );
    let seal = b.contact(Text::at("Motor", 30), false, EdgeKind::None, &[Wire::of(p)]);
    b.coil(
        Text::at("Motor", 40),
        false,
        Storage::None,
        EdgeKind::None,
        &[Wire::of(stop), Wire::of(seal)],
    );
    b.rung();
    b.at(sp(50, 60));
    let m = b.contact(Text::at("Motor", 50), false, EdgeKind::None, &[Wire::of(p)]);
    let ton = b.block(
        Text::at("TON", 60),
        Some(Text::at("T1", 64)),
        vec![
            BlockPin::wired("IN", vec![Wire::of(m)]),
            BlockPin::expr("PT", Text::at("T#2s", 70)),
        ],
        &["Q", "ET"],
    );
    b.coil(
        Text::at("Lamp", 80),
        false,
        Storage::Set,
        EdgeKind::None,
        &[Wire::pin(ton, "Q")],
    );
    b.rung();
    let edge = b.contact(
        Text::at("Start", 90),
        false,
        EdgeKind::Rising,
        &[Wire::of(p)],
    );
    b.coil(
        Text::at("Pulse", 95),
        false,
        Storage::None,
        EdgeKind::None,
        &[Wire::of(edge)],
    );
    b.rung();
    let skip = b.contact(Text::at("Skip", 100), false, EdgeKind::None, &[Wire::of(p)]);
    b.jump(Text::at("L4", 105), &[Wire::of(skip)]);
    b.rung();
    b.label(Text::at("L4", 110));
    b.finish()
}

#[test]
fn an_ld_network_built_in_code_lowers_to_st_in_rung_order() {
    let l = lower(&network(), &PouCtx::new("MAIN", false));
    assert!(l.diagnostics.is_empty(), "{:?}", l.diagnostics);
    assert_eq!(
        l.hidden,
        [
            "__ld_m10", "__ld_n10", "__ld_n11", "__ld_n12", "__ld_n2", "__ld_n3", "__ld_n4",
            "__ld_n5", "__ld_n6", "__ld_n9",
        ]
    );
    // The seal-in contact reads `Motor` before the coil writes it (rung
    // order); the rising edge keeps its memory `__ld_m10` for the next scan.
    assert_eq!(
        l.statements_text(),
        "__ld_n2 := TRUE AND (Start);\n\
         __ld_n3 := __ld_n2 AND NOT (Stop);\n\
         __ld_n4 := TRUE AND (Motor);\n\
         __ld_n5 := (__ld_n3 OR __ld_n4);\n\
         Motor := __ld_n5;\n\
         __ld_n6 := TRUE AND (Motor);\n\
         T1(IN := __ld_n6, PT := (T#2s));\n\
         __ld_n9 := T1.Q;\n\
         IF __ld_n9 THEN Lamp := TRUE; END_IF;\n\
         __ld_n10 := TRUE AND (Start) AND NOT __ld_m10;\n\
         __ld_m10 := Start;\n\
         __ld_n11 := __ld_n10;\n\
         Pulse := __ld_n11;\n\
         __ld_n12 := TRUE AND (Skip);\n\
         IF __ld_n12 THEN __PLCOPEN_GOTO := L4; END_IF;\n\
         __PLCOPEN_LABEL := L4;\n"
    );
}

#[test]
fn a_generated_pou_parses_with_spans_in_the_source_and_real_jumps() {
    let net = network();
    let l = lower(&net, &PouCtx::new("MAIN", false));
    let mut g = Generated::default();
    let whole = sp(0, 120);
    g.gen(
        "PROGRAM MAIN\nVAR\nStart, Stop, Motor, Lamp, Pulse, Skip : BOOL;\nT1 : TON;\nEND_VAR\n",
        whole,
    );
    l.write(&mut g);
    g.gen("\nEND_PROGRAM\n", whole);
    let mut interner = Interner::new();
    let parsed = parse_generated(
        FILE,
        &g,
        l.diagnostics.clone(),
        &mut interner,
        Options::default(),
    );
    assert!(parsed.diagnostics.is_empty(), "{:?}", parsed.diagnostics);
    let Some(Item::Pou(pou)) = parsed.unit.items.first() else {
        panic!("no POU: {:?}", parsed.unit.items);
    };
    let Body::St(stmts) = &pou.body;
    assert_eq!(stmts.len(), 16);
    // The coil `Motor := __ld_n5;`: its target is the coil's own text.
    let StmtKind::Assign { target, .. } = &stmts[4].kind else {
        panic!("{:?}", stmts[4].kind);
    };
    assert_eq!((target.span.start, target.span.end), (40, 45));
    // The jump marker became a real jump, the label a real label.
    let StmtKind::If { branches, .. } = &stmts[14].kind else {
        panic!("{:?}", stmts[14].kind);
    };
    assert!(matches!(branches[0].body[0].kind, StmtKind::Goto(_)));
    assert!(matches!(stmts[15].kind, StmtKind::Label(_)));
}

#[test]
fn wrong_networks_are_diagnostics_at_the_element() {
    let mut b = Builder::new(GraphLang::Ld, sp(0, 10));
    b.at(sp(200, 210));
    b.coil(
        Text::at("Q", 200),
        false,
        Storage::None,
        EdgeKind::None,
        &[],
    );
    b.at(sp(220, 230));
    b.contact(Text::at("X", 220), false, EdgeKind::None, &[Wire::of(99)]);
    let l = lower(
        &b.finish(),
        &PouCtx::new("P", false).with_id_word("instruction"),
    );
    let got: Vec<(Code, u32, String)> = l
        .diagnostics
        .iter()
        .map(|d| (d.code, d.span.start, d.message.clone()))
        .collect();
    assert_eq!(
        got,
        [
            (
                Code::E175,
                200,
                "POU `P`, instruction 1: nothing is connected on the left".to_string()
            ),
            (
                Code::E172,
                220,
                "POU `P`, instruction 2: a connection names localId 99, which is not in this body"
                    .to_string()
            ),
        ]
    );
}
