//! Direct addresses follow the CODESYS / OpenPLC convention: a sized
//! address counts units of its size (`%QW2` = bytes 4..=5), a bit address
//! is byte.bit; the views overlap accordingly.

mod common;
use common::*;

#[test]
fn sized_addresses_count_units_of_their_size() {
    let mut p = build(
        "PROGRAM Main
         VAR w AT %QW2 : WORD; x AT %QX4.0 : BOOL; x9 AT %QX5.1 : BOOL; d AT %QD1 : DWORD;
             b AT %QB3 : BYTE; l AT %ML1 : LWORD; mb AT %MB8 : BYTE; iw AT %IW1 : WORD;
             copy : WORD; END_VAR
         w := 16#0201;
         b := 16#7F;
         l := 16#1122334455667788;
         copy := iw;
         END_PROGRAM",
    );
    let a = p.engine.program().areas.clone();
    assert_eq!(a.input.len(), 4);
    assert_eq!(a.output.len(), 8);
    assert_eq!(a.memory.len(), 16);
    let iw = p.engine.program().symbols.get("Main.iw").unwrap().offset;
    assert_eq!(iw, a.input.start + 2);
    p.engine.image_mut()[a.input.start as usize + 2] = 0x34;
    p.engine.image_mut()[a.input.start as usize + 3] = 0x12;
    p.run(1);
    // %QX4.0 is bit 0 of %QW2's low byte, %QX5.1 bit 1 of its high byte.
    assert_eq!(p.int("Main.x"), 1);
    assert_eq!(p.int("Main.x9"), 1);
    // %QD1 is bytes 4..=7: the word at 4..=5 is its low half.
    assert_eq!(p.int("Main.d"), 0x0201);
    assert_eq!(p.engine.image()[a.output.start as usize + 3], 0x7F);
    // %ML1 is memory bytes 8..=15; %MB8 its lowest byte.
    assert_eq!(p.int("Main.mb"), 0x88);
    assert_eq!(p.int("Main.copy"), 0x1234);
}

#[test]
fn direct_addresses_in_expressions() {
    let mut p = build(
        "PROGRAM Main
         VAR w AT %QW1 : WORD; v : WORD; bit : BOOL; END_VAR
         %QW1 := 16#8001;
         v := %QW1;
         bit := %QX3.7;
         %QB0 := 5;
         END_PROGRAM",
    );
    p.run(1);
    let q = p.engine.program().areas.output.start as usize;
    assert_eq!(p.int("Main.w"), 0x8001);
    assert_eq!(p.int("Main.v"), 0x8001);
    assert_eq!(p.int("Main.bit"), 1);
    assert_eq!(p.engine.image()[q], 5);
    assert_eq!(p.engine.image()[q + 2], 1);
}

#[test]
fn addresses_used_only_in_code_are_inside_their_area() {
    let mut p = build(
        "PROGRAM Main
         VAR g : DINT := -1; END_VAR
         %QD3 := 16#11223344;
         %MX2.7 := TRUE;
         END_PROGRAM",
    );
    let a = p.engine.program().areas.clone();
    assert_eq!(a.output.len(), 16);
    assert_eq!(a.memory.len(), 3);
    p.run(1);
    let q = a.output.start as usize;
    assert_eq!(&p.engine.image()[q + 12..q + 16], &[0x44, 0x33, 0x22, 0x11]);
    assert_eq!(p.engine.image()[a.memory.start as usize + 2], 0x80);
    assert_eq!(p.int("Main.g"), -1);
}
