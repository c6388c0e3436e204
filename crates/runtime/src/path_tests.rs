use super::*;
use crate::testutil::{inst, program, task};
use automat_ir::{Field, SymbolEntry, SymbolTable};
use Elementary as E;

fn entry(path: &str, offset: u32, ty: SymbolType) -> SymbolEntry {
    SymbolEntry {
        path: path.into(),
        offset,
        bit: None,
        ty,
        retain: false,
        constant: false,
        output: false,
        spelling: String::new(),
    }
}

fn field(name: &str, offset: u32, ty: SymbolType) -> Field {
    Field {
        name: name.into(),
        offset,
        bit: None,
        ty,
    }
}

fn el(e: E) -> SymbolType {
    SymbolType::Elementary(e)
}

fn ton() -> SymbolType {
    SymbolType::Struct {
        name: "TON".into(),
        fields: vec![
            field("IN", 0, el(E::Bool)),
            field("PT", 8, el(E::Time)),
            field("Q", 16, el(E::Bool)),
            field("ET", 24, el(E::Time)),
        ],
    }
}

/// One program MAIN (entries per variable), globals X and GCOUNT.
fn sample() -> Program {
    let point = SymbolType::Struct {
        name: "POINT".into(),
        fields: vec![field("X", 0, el(E::Int)), field("Y", 2, el(E::Int))],
    };
    let mut p = program(vec![task("MAIN", None, 0, vec![inst("MAIN", 0, 0)])]);
    p.image_size = 160;
    p.areas.input = 100..104;
    p.areas.output = 104..108;
    p.areas.memory = 108..112;
    p.symbols = SymbolTable::new(vec![
        entry("Main.x", 0, el(E::Int)),
        entry("MAIN.FB", 8, ton()),
        entry(
            "MAIN.ARR",
            40,
            SymbolType::Array {
                elem: Box::new(point),
                dims: vec![(1, 3), (0, 1)],
                stride: 4,
            },
        ),
        entry("MAIN.W", 64, el(E::Word)),
        entry("MAIN.S", 66, SymbolType::String { cap: 10 }),
        entry("MAIN.R", 80, SymbolType::Ref(Box::new(el(E::Int)))),
        entry("GCOUNT", 84, el(E::Dint)),
        entry("X", 88, el(E::Dint)),
        entry(
            "MAIN.C",
            92,
            SymbolType::Enum {
                name: "COLOR".into(),
                base: E::Int,
                values: vec![("RED".into(), 0)],
            },
        ),
        entry(
            "MAIN.SUB",
            94,
            SymbolType::Subrange {
                base: E::Int,
                lo: 0,
                hi: 9,
            },
        ),
        entry("MAIN.BIG", 155, el(E::Lint)),
    ]);
    p
}

fn at(offset: u32, bit: Option<u8>, e: E) -> Place {
    Place {
        offset,
        bit,
        ty: PlaceType::Elementary(e),
        slc_bit: false,
    }
}

#[test]
fn names_members_indexes_and_bits() {
    let p = sample();
    assert_eq!(resolve(&p, "x"), Ok(at(0, None, E::Int)));
    assert_eq!(resolve(&p, "main.X"), Ok(at(0, None, E::Int)));
    assert_eq!(resolve(&p, "gcount"), Ok(at(84, None, E::Dint)));
    assert_eq!(resolve(&p, "fb.q"), Ok(at(24, None, E::Bool)));
    assert_eq!(resolve(&p, "Main.fb.ET"), Ok(at(32, None, E::Time)));
    assert_eq!(resolve(&p, "arr[1, 0].x"), Ok(at(40, None, E::Int)));
    assert_eq!(
        resolve(&p, "arr[2,1].y"),
        Ok(at(40 + 3 * 4 + 2, None, E::Int))
    );
    assert_eq!(
        resolve(&p, " arr[ 3 , 1 ].Y "),
        Ok(at(40 + 5 * 4 + 2, None, E::Int))
    );
    assert_eq!(resolve(&p, "w.9"), Ok(at(65, Some(1), E::Bool)));
    assert_eq!(resolve(&p, "w.0"), Ok(at(64, Some(0), E::Bool)));
    assert_eq!(resolve(&p, "sub"), Ok(at(94, None, E::Int)));
    assert_eq!(
        resolve(&p, "s"),
        Ok(Place {
            offset: 66,
            bit: None,
            ty: PlaceType::String { cap: 10 },
            slc_bit: false
        })
    );
    assert!(matches!(
        resolve(&p, "c"),
        Ok(Place {
            offset: 92,
            ty: PlaceType::Enum { .. },
            ..
        })
    ));
}

#[test]
fn direct_addresses_count_units_of_their_size() {
    let p = sample();
    assert_eq!(resolve(&p, "%QX0.1"), Ok(at(104, Some(1), E::Bool)));
    assert_eq!(resolve(&p, "%ix3.7"), Ok(at(103, Some(7), E::Bool)));
    assert_eq!(resolve(&p, "%I3.2"), Ok(at(103, Some(2), E::Bool)));
    assert_eq!(resolve(&p, "%QB2"), Ok(at(106, None, E::Byte)));
    assert_eq!(resolve(&p, "%MW1"), Ok(at(110, None, E::Word)));
    assert_eq!(resolve(&p, "%QW1"), Ok(at(106, None, E::Word)));
    assert_eq!(
        resolve(&p, "%MW2").unwrap_err(),
        "`%MW2` is outside the area the program uses (4 bytes)"
    );
    assert_eq!(resolve(&p, "%ID0"), Ok(at(100, None, E::Dword)));
    assert_eq!(
        resolve(&p, "%QD1").unwrap_err(),
        "`%QD1` is outside the area the program uses (4 bytes)"
    );
    assert_eq!(
        resolve(&p, "%QX0.8").unwrap_err(),
        "`%QX0.8` is not a direct address: bit 8 is out of range 0..7"
    );
    assert_eq!(
        resolve(&p, "%Z1").unwrap_err(),
        "`%Z1` is not a direct address: the area must be I, Q or M"
    );
    assert_eq!(
        resolve(&p, "%QB1.2").unwrap_err(),
        "`%QB1.2` is not a direct address: a byte, word or double word address is one number"
    );
    assert_eq!(
        resolve(&p, "%QXa.1").unwrap_err(),
        "`%QXa.1` is not a direct address: `a` is not a number"
    );
}

#[test]
fn clear_errors() {
    let p = sample();
    let err = |t: &str| match resolve(&p, t) {
        Ok(pl) => panic!("{t} resolved to {pl:?}"),
        Err(e) => e,
    };
    assert_eq!(
        err("nope"),
        "unknown variable `nope`: no program variable or global named `NOPE`"
    );
    assert_eq!(err("fb.qq"), "`FB` (TON) has no member `QQ`");
    assert_eq!(err("arr[4, 0].x"), "index 4 of `ARR` is out of range 1..3");
    assert_eq!(
        err("arr[1, -1].x"),
        "index -1 of `ARR` is out of range 0..1"
    );
    assert_eq!(
        err("arr[1].x"),
        "`ARR` has 2 dimension(s); 1 index(es) given"
    );
    assert_eq!(
        err("arr[1, 1]"),
        "`ARR[1, 1]` is a POINT; name one of its members: X, Y"
    );
    assert_eq!(err("arr"), "`ARR` is an ARRAY[1..3, 0..1]; give an index");
    assert_eq!(
        err("fb"),
        "`FB` is a TON; name one of its members: IN, PT, Q, ET"
    );
    assert_eq!(err("x[1]"), "`X` is INT, not an array");
    assert_eq!(err("x.y"), "`X` is INT; it has no member `Y`");
    assert_eq!(err("w.16"), "bit `16` of `W` (WORD) is out of range 0..15");
    assert_eq!(
        err("r.x"),
        "`R` is a reference (VAR_IN_OUT or REF_TO); a path cannot follow it to `X`"
    );
    assert_eq!(
        err("r"),
        "`R` is a reference (VAR_IN_OUT or REF_TO) and cannot be read by path"
    );
    assert_eq!(
        err("big"),
        "`big` lies outside the memory image (163 > 160 bytes)"
    );
    assert_eq!(
        err("a..b"),
        "`a..b` is not a variable path: a name is missing"
    );
    assert_eq!(
        err("a."),
        "`a.` is not a variable path: it ends where a name is expected"
    );
    assert_eq!(
        err("arr[1"),
        "`arr[1` is not a variable path: `[` without `]`"
    );
    assert_eq!(
        err("arr[x]"),
        "`arr[x]` is not a variable path: `x` is not an integer index"
    );
    assert_eq!(
        err("1abc"),
        "`1abc` is not a variable path: it must start with a name"
    );
    assert_eq!(err("a b"), "`a b` is not a variable path: unexpected ` b`");
    assert_eq!(
        err(""),
        "`` is not a variable path: it ends where a name is expected"
    );
}

#[test]
fn program_instance_as_one_struct_entry() {
    // A symbol table whose program instance is one entry with fields.
    let mut p = program(vec![task("T", None, 0, vec![inst("PRG", 0, 16)])]);
    p.symbols = SymbolTable::new(vec![
        entry(
            "PRG",
            16,
            SymbolType::Struct {
                name: "PRG".into(),
                fields: vec![field("N", 4, el(E::Dint)), field("T1", 8, ton())],
            },
        ),
        entry("G", 0, el(E::Bool)),
    ]);
    assert_eq!(resolve(&p, "n"), Ok(at(20, None, E::Dint)));
    assert_eq!(resolve(&p, "prg.n"), Ok(at(20, None, E::Dint)));
    assert_eq!(resolve(&p, "t1.q"), Ok(at(40, None, E::Bool)));
    assert_eq!(resolve(&p, "g"), Ok(at(0, None, E::Bool)));
    assert_eq!(
        resolve(&p, "m").unwrap_err(),
        "unknown variable `m`: no program variable or global named `M`"
    );
    assert_eq!(
        resolve(&p, "prg.m").unwrap_err(),
        "`PRG` (PRG) has no member `M`"
    );
}

#[test]
fn several_instances_need_qualified_names() {
    let mut p = program(vec![
        task("A", Some(10), 0, vec![inst("P1", 0, 0)]),
        task("B", Some(20), 0, vec![inst("P2", 0, 8)]),
    ]);
    p.symbols = SymbolTable::new(vec![
        entry("P1.N", 0, el(E::Int)),
        entry("P2.N", 8, el(E::Int)),
    ]);
    assert_eq!(resolve(&p, "p2.n"), Ok(at(8, None, E::Int)));
    assert!(resolve(&p, "n").is_err());
}

/// A variable named like its program (`crc` in `PROGRAM Crc`, the only
/// program): `Crc.crc` is first read inside the program as `Crc.crc.crc`,
/// which has no such member, then as given; a path wrong both ways keeps
/// the error of the first reading.
#[test]
fn a_variable_named_like_its_program() {
    let mut p = program(vec![task("CRC", None, 0, vec![inst("CRC", 0, 0)])]);
    p.image_size = 16;
    p.symbols = SymbolTable::new(vec![
        entry("Crc.crc", 0, el(E::Dword)),
        entry("CRC.X", 4, el(E::Int)),
    ]);
    assert_eq!(resolve(&p, "Crc.crc"), Ok(at(0, None, E::Dword)));
    assert_eq!(resolve(&p, "crc"), Ok(at(0, None, E::Dword)));
    assert_eq!(resolve(&p, "crc.x"), Ok(at(4, None, E::Int)));
    assert_eq!(resolve(&p, "x"), Ok(at(4, None, E::Int)));
    let e = resolve(&p, "crc.crc.y").unwrap_err();
    assert!(e.contains("no member"), "{e}");
}
