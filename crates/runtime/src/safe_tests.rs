use super::*;
use crate::testutil::{program, task};
use automat_ir::{Field, SymbolEntry, SymbolTable};

fn entry(path: &str, offset: u32, bit: Option<u8>, ty: SymbolType, output: bool) -> SymbolEntry {
    SymbolEntry {
        path: path.into(),
        offset,
        bit,
        ty,
        retain: false,
        constant: false,
        output,
        spelling: path.into(),
    }
}

/// %Q at 44..48; outputs of every kind of type in 0..40; `MAIN.KEEP` is
/// not an output.
fn outputs() -> Program {
    let mut p = program(vec![task("MAIN", None, 0, vec![])]);
    p.symbols = SymbolTable::new(vec![
        entry("MAIN.RUN", 0, None, SymbolType::Elementary(E::Bool), true),
        entry("MAIN.SPEED", 2, None, SymbolType::Elementary(E::Int), true),
        entry(
            "MAIN.GEAR",
            4,
            None,
            SymbolType::Subrange {
                base: E::Int,
                lo: 5,
                hi: 10,
            },
            true,
        ),
        entry(
            "MAIN.MODE",
            6,
            None,
            SymbolType::Enum {
                name: "Mode".into(),
                base: E::Int,
                values: vec![("Auto".into(), 3), ("Hand".into(), 7)],
            },
            true,
        ),
        entry(
            "MAIN.LEVELS",
            8,
            None,
            SymbolType::Array {
                elem: Box::new(SymbolType::Elementary(E::Word)),
                dims: vec![(1, 3)],
                stride: 2,
            },
            true,
        ),
        entry("MAIN.MSG", 14, None, SymbolType::String { cap: 4 }, true),
        entry(
            "MAIN.MOTOR",
            20,
            None,
            SymbolType::Struct {
                name: "DRIVE".into(),
                fields: vec![
                    Field {
                        name: "on".into(),
                        offset: 0,
                        bit: None,
                        ty: SymbolType::Elementary(E::Bool),
                    },
                    Field {
                        name: "rpm".into(),
                        offset: 4,
                        bit: None,
                        ty: SymbolType::Elementary(E::Real),
                    },
                ],
            },
            true,
        ),
        entry(
            "MAIN.KEEP",
            30,
            None,
            SymbolType::Elementary(E::Dint),
            false,
        ),
        entry(
            "MAIN.LAMP",
            36,
            Some(2),
            SymbolType::Elementary(E::Bool),
            true,
        ),
    ]);
    p
}

#[test]
fn every_output_goes_to_its_zero_and_nothing_else_moves() {
    let p = outputs();
    let safe = SafeState::of_program(&p);
    let mut img = vec![0xFFu8; 64];
    safe.apply(&mut img);
    let mut want = vec![0xFFu8; 64];
    want[0] = 0; // RUN
    want[2..4].copy_from_slice(&[0, 0]); // SPEED
    want[4..6].copy_from_slice(&5i16.to_le_bytes()); // GEAR: 0 is not in 5..10
    want[6..8].copy_from_slice(&3i16.to_le_bytes()); // MODE: the lowest value
    want[8..14].fill(0); // LEVELS[1..3]
    want[14..16].fill(0); // MSG: empty (characters untouched)
    want[20] = 0; // MOTOR.on
    want[24..28].fill(0); // MOTOR.rpm
    want[36] = 0xFB; // LAMP: bit 2 only
    want[44..48].fill(0); // %Q
    assert_eq!(img, want);
    assert_eq!(
        safe.describe(),
        "the %Q area (4 bytes) and 8 outputs (MAIN.GEAR, MAIN.LAMP, MAIN.LEVELS, MAIN.MODE, \
         MAIN.MOTOR, MAIN.MSG, MAIN.RUN, MAIN.SPEED) set to 0/FALSE"
    );
}

#[test]
fn configured_values_win_over_the_zeroing() {
    let p = outputs();
    let mut safe = SafeState::of_program(&p);
    let place = |path: &str| crate::resolve(&p, path).unwrap();
    safe.set_literal("MAIN.RUN", &place("MAIN.RUN"), "TRUE")
        .unwrap();
    safe.set_literal("MAIN.SPEED", &place("MAIN.SPEED"), "-300")
        .unwrap();
    safe.set_literal("MAIN.MODE", &place("MAIN.MODE"), "Mode#Hand")
        .unwrap();
    safe.set_literal("MAIN.MSG", &place("MAIN.MSG"), "'off'")
        .unwrap();
    safe.set_literal("MAIN.MOTOR.rpm", &place("MAIN.MOTOR.rpm"), "2.5")
        .unwrap();
    safe.set_literal("MAIN.LAMP", &place("MAIN.LAMP"), "1")
        .unwrap();
    safe.set_literal("%QX0.1", &place("%QX0.1"), "TRUE")
        .unwrap();
    let mut img = vec![0u8; 64];
    img[2] = 9;
    safe.apply(&mut img);
    assert_eq!(img[0], 1);
    assert_eq!(img[2..4], (-300i16).to_le_bytes());
    assert_eq!(img[6..8], 7i16.to_le_bytes());
    assert_eq!(img[14..19], [3, 0, b'o', b'f', b'f']);
    assert_eq!(img[24..28], 2.5f32.to_le_bytes());
    assert_eq!(img[36], 0b100);
    assert_eq!(img[44..48], [0b10, 0, 0, 0]);
    assert!(safe.describe().starts_with(
        "the %Q area (4 bytes) and 3 outputs (MAIN.GEAR, MAIN.LEVELS, MAIN.MOTOR) set"
    ));
    assert!(safe.describe().ends_with(
        "set to 0/FALSE; MAIN.RUN set to TRUE; MAIN.SPEED set to -300; MAIN.MODE set to \
         Mode#Hand; MAIN.MSG set to 'off'; MAIN.MOTOR.rpm set to 2.5; MAIN.LAMP set to 1; \
         %QX0.1 set to TRUE"
    ));
}

#[test]
fn bad_configured_values_are_errors() {
    let p = outputs();
    let mut safe = SafeState::of_program(&p);
    let place = |path: &str| crate::resolve(&p, path).unwrap();
    let err = |safe: &mut SafeState, path: &str, text: &str| {
        safe.set_literal(path, &place(path), text).unwrap_err()
    };
    assert!(err(&mut safe, "MAIN.SPEED", "70000").contains("70000"));
    assert!(err(&mut safe, "MAIN.RUN", "maybe").contains("maybe"));
    assert_eq!(
        err(&mut safe, "MAIN.MODE", "Off"),
        "`Off` is not a value of Mode"
    );
    assert_eq!(
        err(&mut safe, "MAIN.MODE", "5"),
        "`5` is not a value of Mode"
    );
    assert_eq!(
        err(&mut safe, "MAIN.MSG", "'too long'"),
        "the string has 8 characters; the variable holds 4"
    );
    // Nothing was configured by the failures.
    let mut img = vec![0u8; 64];
    safe.apply(&mut img);
    assert_eq!(img[0], 0);
}

#[test]
fn extra_places_are_zeroed_once_and_named() {
    let p = outputs();
    let mut safe = SafeState::of_program(&p);
    let keep = crate::resolve(&p, "MAIN.KEEP").unwrap();
    safe.add_zero("Main.keep", &keep);
    safe.add_zero("MAIN.RUN", &crate::resolve(&p, "MAIN.RUN").unwrap());
    let mut img = vec![0xFFu8; 64];
    safe.apply(&mut img);
    assert_eq!(img[30..34], [0, 0, 0, 0]);
    assert!(
        safe.describe().contains("9 outputs ("),
        "{}",
        safe.describe()
    );
    assert!(
        safe.describe().contains(" and 1 more)"),
        "{}",
        safe.describe()
    );

    let mut none = program(vec![]);
    none.areas.output = 0..0;
    assert_eq!(
        SafeState::of_program(&none).describe(),
        "the program has no outputs"
    );
}

#[test]
fn arrays_of_structures_zero_each_field_by_its_type() {
    let cell = |lo: i64| SymbolType::Struct {
        name: "CELL".into(),
        fields: vec![
            Field {
                name: "on".into(),
                offset: 0,
                bit: None,
                ty: SymbolType::Elementary(E::Bool),
            },
            Field {
                name: "gear".into(),
                offset: 2,
                bit: None,
                ty: SymbolType::Subrange {
                    base: E::Int,
                    lo,
                    hi: 10,
                },
            },
        ],
    };
    let array = |lo: i64| SymbolType::Array {
        elem: Box::new(cell(lo)),
        dims: vec![(0, 2)],
        stride: 4,
    };
    let mut p = program(vec![task("MAIN", None, 0, vec![])]);
    p.symbols = SymbolTable::new(vec![
        entry("MAIN.A", 0, None, array(5), true),
        entry("MAIN.B", 12, None, array(0), true),
    ]);
    let safe = SafeState::of_program(&p);
    // B is one write of its 12 bytes; A one write per field.
    assert_eq!(safe.writes.len(), 1 + 6 + 1);
    let mut img = vec![0xFFu8; 64];
    safe.apply(&mut img);
    let mut want = vec![0xFFu8; 64];
    for k in 0..3 {
        want[4 * k] = 0;
        want[4 * k + 2..4 * k + 4].copy_from_slice(&5i16.to_le_bytes());
    }
    want[12..24].fill(0);
    want[44..48].fill(0);
    assert_eq!(img, want);
}

#[test]
fn held_puts_back_every_value_the_safe_state_replaced() {
    let p = outputs();
    let mut safe = SafeState::of_program(&p);
    let place = |path: &str| crate::resolve(&p, path).unwrap();
    // A configured value over a zeroed one: two writes on the same bytes.
    safe.set_literal("MAIN.SPEED", &place("MAIN.SPEED"), "7")
        .unwrap();
    let before: Vec<u8> = (0..64u8).map(|i| i.wrapping_mul(37) | 1).collect();
    let mut img = before.clone();
    let held = safe.held(&img);
    safe.apply(&mut img);
    assert_ne!(img, before);
    held.apply(&mut img);
    assert_eq!(img, before);
    // LAMP is one bit: its neighbours are the program's, never the held copy's.
    let mut img = before.clone();
    let held = safe.held(&img);
    safe.apply(&mut img);
    img[36] ^= 0x01;
    held.apply(&mut img);
    assert_eq!(img[36], before[36] ^ 0x01);
}
