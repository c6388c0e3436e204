use super::*;
use crate::testutil::{program, task};
use automat_iec::Elementary as E;
use automat_ir::{SymbolEntry, SymbolTable};

fn retained() -> Program {
    let mut p = program(vec![task("MAIN", None, 0, vec![])]);
    p.retain = vec![4..8, 16..18];
    p.symbols = SymbolTable::new(vec![
        SymbolEntry {
            path: "MAIN.COUNT".into(),
            offset: 4,
            bit: None,
            ty: SymbolType::Elementary(E::Dint),
            retain: true,
            constant: false,
            spelling: String::new(),
        },
        SymbolEntry {
            path: "MAIN.W".into(),
            offset: 16,
            bit: None,
            ty: SymbolType::Elementary(E::Word),
            retain: true,
            constant: false,
            spelling: String::new(),
        },
        SymbolEntry {
            path: "MAIN.TMP".into(),
            offset: 20,
            bit: None,
            ty: SymbolType::Elementary(E::Int),
            retain: false,
            constant: false,
            spelling: String::new(),
        },
    ]);
    p
}

fn image() -> Vec<u8> {
    (0..64u8).collect()
}

#[test]
fn exact_file_layout() {
    let p = retained();
    let data = encode(&p, &image()).unwrap();
    assert_eq!(data.len(), 24 + 6 + 4);
    assert_eq!(&data[..8], b"AUTOMATR");
    assert_eq!(data[8..12], [1, 0, 0, 0]);
    assert_eq!(data[12..20], layout_hash(&p).to_le_bytes());
    assert_eq!(data[20..24], [6, 0, 0, 0]);
    assert_eq!(data[24..30], [4, 5, 6, 7, 16, 17]);
    assert_eq!(data[30..34], crc32(&data[..30]).to_le_bytes());
}

#[test]
fn round_trip_restores_only_retain_ranges() {
    let p = retained();
    let data = encode(&p, &image()).unwrap();
    let mut img = vec![0u8; 64];
    assert_eq!(decode(&p, &data, &mut img), Ok(()));
    let mut want = vec![0u8; 64];
    want[4..8].copy_from_slice(&[4, 5, 6, 7]);
    want[16..18].copy_from_slice(&[16, 17]);
    assert_eq!(img, want);
}

#[test]
fn save_and_load_through_a_file() {
    let dir = std::env::temp_dir().join(format!("automat-retain-{}", std::process::id()));
    fs::create_dir_all(&dir).unwrap();
    let path = dir.join("plc.retain");
    let p = retained();
    let mut img = vec![0u8; 64];
    assert_eq!(load(&p, &path, &mut img), Loaded::NoFile);
    save(&p, &path, &image()).unwrap();
    assert!(!dir.join("plc.retain.tmp").exists());
    assert_eq!(load(&p, &path, &mut img), Loaded::Warm);
    assert_eq!(img[4..8], [4, 5, 6, 7]);
    // Saving again replaces the file.
    let mut other = image();
    other[4] = 99;
    save(&p, &path, &other).unwrap();
    assert_eq!(load(&p, &path, &mut img), Loaded::Warm);
    assert_eq!(img[4], 99);
    // A directory where the file should be: a clear error, no panic.
    let err = save(&p, &dir, &image()).unwrap_err();
    assert!(err.contains("cannot save the RETAIN variables"), "{err}");
    fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn corrupt_truncated_and_foreign_files_fall_back_to_cold() {
    let p = retained();
    let good = encode(&p, &image()).unwrap();
    let mut img = vec![0u8; 64];
    let check = |data: &[u8], img: &mut Vec<u8>| decode(&p, data, img).unwrap_err();

    let mut flipped = good.clone();
    flipped[25] ^= 1;
    assert_eq!(
        check(&flipped, &mut img),
        "the checksum does not match: the file is corrupt"
    );
    for cut in [0, 5, 8, 12, 23, 24, 29, 33] {
        let e = check(&good[..cut], &mut img);
        assert!(
            e == "not an automat retain file" || e == "the file is truncated",
            "cut at {cut}: {e}"
        );
    }
    let mut longer = good.clone();
    longer.push(0);
    assert_eq!(
        check(&longer, &mut img),
        "the file has 35 bytes; its header announces 34"
    );
    assert_eq!(
        check(b"hello world, not retain", &mut img),
        "not an automat retain file"
    );
    let mut v2 = good.clone();
    v2[8] = 2;
    assert_eq!(
        check(&v2, &mut img),
        "format version 2 is not supported (this automat reads version 1)"
    );
    // A huge announced length must not allocate or overflow.
    let mut huge = good.clone();
    huge[20..24].copy_from_slice(&u32::MAX.to_le_bytes());
    assert_eq!(check(&huge, &mut img), "the file is truncated");
    // Nothing was written into the image by any failed load.
    assert_eq!(img, vec![0u8; 64]);
}

#[test]
fn a_changed_program_is_detected() {
    let p = retained();
    let data = encode(&p, &image()).unwrap();
    let mut img = vec![0u8; 64];
    let msg = "the program's RETAIN variables changed since the file was written";

    let mut moved = retained();
    moved.retain = vec![8..12, 16..18];
    assert_eq!(decode(&moved, &data, &mut img).unwrap_err(), msg);

    let mut retyped = retained();
    let mut entries = retyped.symbols.entries().to_vec();
    for e in entries.iter_mut().filter(|e| e.path == "MAIN.COUNT") {
        e.ty = SymbolType::Elementary(E::Udint);
    }
    retyped.symbols = SymbolTable::new(entries);
    assert_eq!(decode(&retyped, &data, &mut img).unwrap_err(), msg);

    // A non-retained variable does not matter.
    let mut other = retained();
    let mut entries = other.symbols.entries().to_vec();
    for e in entries.iter_mut().filter(|e| e.path == "MAIN.TMP") {
        e.ty = SymbolType::Elementary(E::Lint);
    }
    other.symbols = SymbolTable::new(entries);
    assert_eq!(decode(&other, &data, &mut img), Ok(()));
    assert_eq!(layout_hash(&other), layout_hash(&p));
}

#[test]
fn ranges_outside_the_image_are_errors_not_panics() {
    let mut p = retained();
    p.retain = vec![Range { start: 60, end: 70 }];
    assert_eq!(encode(&p, &image()), None);
    let data = {
        let mut ok = p.clone();
        ok.retain = vec![Range { start: 0, end: 10 }];
        let mut d = encode(&ok, &image()).unwrap();
        // Re-stamp the hash and CRC for `p` so only the range is wrong.
        d[12..20].copy_from_slice(&layout_hash(&p).to_le_bytes());
        let n = d.len() - 4;
        let crc = crc32(&d[..n]);
        d[n..].copy_from_slice(&crc.to_le_bytes());
        d
    };
    let mut img = vec![0u8; 64];
    assert_eq!(
        decode(&p, &data, &mut img).unwrap_err(),
        "a RETAIN range lies outside the memory image"
    );
}
