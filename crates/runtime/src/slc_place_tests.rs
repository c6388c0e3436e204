use super::*;
use crate::testutil::{inst, program, task};
use automat_ir::{SymbolEntry, SymbolTable};

fn array(path: &str, offset: u32, len: i64, elem: Elementary) -> SymbolEntry {
    SymbolEntry {
        path: path.into(),
        offset,
        bit: None,
        ty: SymbolType::Array {
            elem: Box::new(SymbolType::Elementary(elem)),
            dims: vec![(0, len - 1)],
            stride: if elem == Elementary::Real { 4 } else { 2 },
        },
        retain: false,
        constant: false,
        output: false,
        spelling: String::new(),
    }
}

/// S2 (32 words) at 0, N7 (10 words) at 64, T4 (2 timers) at 84, B3 (2
/// words) at 96, F8 (4 floats) at 100, N10 (5 words) at 116.
fn slc() -> Program {
    let mut p = program(vec![task("MAIN", None, 0, vec![inst("SLC", 0, 0)])]);
    p.image_size = 126;
    p.initial_image = vec![0; 126];
    p.symbols = SymbolTable::new(vec![
        array("B3", 96, 2, Elementary::Int),
        array("F8", 100, 4, Elementary::Real),
        array("N10", 116, 5, Elementary::Int),
        array("N7", 64, 10, Elementary::Int),
        array("S2", 0, 32, Elementary::Int),
        array("T4", 84, 6, Elementary::Int),
    ]);
    p
}

fn set(image: &mut [u8], offset: usize, v: i16) {
    image[offset..offset + 2].copy_from_slice(&v.to_le_bytes());
}

fn word_at(offset: u32) -> Place {
    Place {
        offset,
        bit: None,
        ty: PlaceType::Elementary(Elementary::Int),
        slc_bit: false,
    }
}

fn bit_at(offset: u32, bit: u8) -> Place {
    Place {
        offset,
        bit: Some(bit),
        ty: PlaceType::Elementary(Elementary::Bool),
        slc_bit: true,
    }
}

#[test]
fn each_form_is_found_in_the_image_it_is_given() {
    let p = slc();
    let mut image = vec![0u8; 126];
    let at = |text: &str, image: &[u8]| {
        locate(&p, text)
            .and_then(|l| l.place(image))
            .unwrap_or_else(|e| panic!("{text}: {e}"))
    };
    // S:24 = 3, N7:0 = 1, N7:1 = 18, N7:2 = 7, N7:3 = 10.
    set(&mut image, 48, 3);
    set(&mut image, 64, 1);
    set(&mut image, 66, 18);
    set(&mut image, 68, 7);
    set(&mut image, 70, 10);
    assert_eq!(at("#N7:5", &image), word_at(64 + 16));
    assert_eq!(at("n7:[N7:0]", &image), word_at(66));
    assert_eq!(at("T4:[N7:0].ACC", &image), word_at(84 + 10));
    assert_eq!(at("T4:[N7:0]/DN", &image), bit_at(84 + 7, 5));
    assert_eq!(at("N[N7:3]:1", &image), word_at(118));
    assert_eq!(at("N[N7:2]:[N7:0]", &image), word_at(66));
    assert_eq!(at("B3/[N7:1]", &image), bit_at(98, 2));
    assert_eq!(at("B3:[N7:0]/5", &image), bit_at(98, 5));
    assert_eq!(at("B3:0/[N7:2]", &image), bit_at(96, 7));
    assert_eq!(
        at("#F8:0", &image),
        Place {
            offset: 112,
            bit: None,
            ty: PlaceType::Elementary(Elementary::Real),
            slc_bit: false,
        }
    );
    let direct = |text: &str| locate(&p, text).ok().and_then(|l| l.direct(&image));
    assert_eq!(direct("#N7:5"), Some(Ok("N7:8".into())));
    assert_eq!(direct("T4:[N7:0]/DN"), Some(Ok("T4:1/DN".into())));
    assert_eq!(direct("N[N7:3]:1"), Some(Ok("N10:1".into())));
    assert_eq!(direct("B3/[N7:1]"), Some(Ok("B3:1/2".into())));
    assert_eq!(direct("N7:2"), None);
    // The same locator, another image: another place.
    set(&mut image, 48, 0);
    assert_eq!(at("#N7:5", &image), word_at(74));
}

#[test]
fn outside_its_file_a_read_fails_with_the_range() {
    let p = slc();
    let mut image = vec![0u8; 126];
    let err = |text: &str, image: &[u8]| {
        locate(&p, text)
            .and_then(|l| l.place(image))
            .expect_err(text)
    };
    set(&mut image, 48, 5);
    assert_eq!(
        err("#N7:5", &image),
        "indexed address `#N7:5` + S:24 (5) lies outside data file N7 (words 0 to 9)"
    );
    set(&mut image, 64, 2);
    assert_eq!(
        err("T4:[N7:0].ACC", &image),
        "indirect address `T4:[N7:0].ACC`: the element 2 is not one of data file T4 (0 to 1)"
    );
    set(&mut image, 64, -1);
    assert_eq!(
        err("N7:[N7:0]", &image),
        "indirect address `N7:[N7:0]`: the element -1 is not one of data file N7 (0 to 9)"
    );
    set(&mut image, 64, 32);
    assert_eq!(
        err("B3/[N7:0]", &image),
        "indirect address `B3/[N7:0]`: the bit 32 lies outside data file B3 (bits 0 to 31)"
    );
    set(&mut image, 64, 16);
    assert_eq!(
        err("B3:0/[N7:0]", &image),
        "indirect address `B3:0/[N7:0]`: the bit 16 is not 0 to 15"
    );
    set(&mut image, 64, 9);
    assert_eq!(
        err("N[N7:0]:0", &image),
        "indirect address `N[N7:0]:0`: the file number 9 is not one of the N files of the program (7, 10)"
    );
}

#[test]
fn a_path_takes_no_dynamic_address_and_bad_ones_say_why() {
    let p = slc();
    assert!(crate::path::resolve(&p, "#N7:5")
        .unwrap_err()
        .contains("indexed or indirect SLC-500 address"));
    assert!(locate(&p, "N7:[N7:0/1]")
        .unwrap_err()
        .contains("the word inside `[ ]` is an integer word"));
    assert!(locate(&p, "#R6:0")
        .unwrap_err()
        .contains("an indexed address names a word"));
    assert_eq!(
        locate(&p, "C5:[N7:0].ACC").unwrap_err(),
        "`C5:[N7:0].ACC`: the program has no C5 data file (is this an SLC-500 program?)"
    );
    for t in [
        "#N7:5",
        "N7:[N7:0]",
        "n[N7:0]:1",
        "B3/[N7:1]",
        "I:[N7:0]/1",
        "#B3:0",
    ] {
        assert!(looks_dynamic(t), "{t}");
    }
    for t in [
        "inst.arr[3]",
        "n7[2]",
        "N7:1",
        "B3/4",
        "main.b[1].x",
        "#",
        "N[N7:0",
    ] {
        assert!(!looks_dynamic(t), "{t}");
    }
    let l = locate(&p, "B3/[N7:1]").expect("locates");
    assert!(l.slc_bit());
    assert_eq!(l.ty(), PlaceType::Elementary(Elementary::Bool));
    assert_eq!(l.format(&[0u8; 126]), "0");
    assert!(locate(&p, "N7:1").is_ok_and(|l| l.fixed().is_some()));
}
