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
            output: false,
            spelling: String::new(),
        },
        SymbolEntry {
            path: "MAIN.W".into(),
            offset: 16,
            bit: None,
            ty: SymbolType::Elementary(E::Word),
            retain: true,
            constant: false,
            output: false,
            spelling: String::new(),
        },
        SymbolEntry {
            path: "MAIN.TMP".into(),
            offset: 20,
            bit: None,
            ty: SymbolType::Elementary(E::Int),
            retain: false,
            constant: false,
            output: false,
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

fn typed_entry(path: &str, offset: u32, ty: SymbolType) -> SymbolEntry {
    SymbolEntry {
        path: path.into(),
        offset,
        bit: None,
        ty,
        retain: true,
        constant: false,
        output: false,
        spelling: path.into(),
    }
}

/// RETAIN variables of every checked kind: BOOL at 0, STRING[4] at 2..8,
/// subrange 0..10 at 8, enum at 10, ARRAY[1..2] OF a struct {x: BOOL; s:
/// WSTRING[1]} at 12..24 (stride 6).
fn typed() -> Program {
    let mut p = program(vec![task("MAIN", None, 0, vec![])]);
    p.retain = vec![Range { start: 0, end: 24 }];
    p.symbols = SymbolTable::new(vec![
        typed_entry("Main.flag", 0, SymbolType::Elementary(E::Bool)),
        typed_entry("Main.name", 2, SymbolType::String { cap: 4 }),
        typed_entry(
            "Main.level",
            8,
            SymbolType::Subrange {
                base: E::Int,
                lo: 0,
                hi: 10,
            },
        ),
        typed_entry(
            "Main.mode",
            10,
            SymbolType::Enum {
                name: "Mode".into(),
                base: E::Int,
                values: vec![("Auto".into(), 0), ("Hand".into(), 1)],
            },
        ),
        typed_entry(
            "Main.cells",
            12,
            SymbolType::Array {
                elem: Box::new(SymbolType::Struct {
                    name: "CELL".into(),
                    fields: vec![
                        automat_ir::Field {
                            name: "x".into(),
                            offset: 0,
                            bit: None,
                            ty: SymbolType::Elementary(E::Bool),
                        },
                        automat_ir::Field {
                            name: "s".into(),
                            offset: 2,
                            bit: None,
                            ty: SymbolType::WString { cap: 1 },
                        },
                    ],
                }),
                dims: vec![(1, 2)],
                stride: 6,
            },
        ),
    ]);
    p
}

/// A valid image of [`typed`]: flag TRUE, name 'ab', level 10, mode Hand,
/// cells[2].x TRUE with s "z".
fn typed_image() -> Vec<u8> {
    let mut img = vec![0u8; 64];
    img[0] = 1;
    img[2..6].copy_from_slice(&[2, 0, b'a', b'b']);
    img[8..10].copy_from_slice(&10i16.to_le_bytes());
    img[10..12].copy_from_slice(&1i16.to_le_bytes());
    img[18] = 1;
    img[20..24].copy_from_slice(&[1, 0, b'z', 0]);
    img
}

#[test]
fn every_value_is_checked_against_its_type() {
    let p = typed();
    let good = typed_image();
    let mut img = vec![0u8; 64];
    assert_eq!(decode(&p, &encode(&p, &good).unwrap(), &mut img), Ok(()));
    assert_eq!(img, good);
    let cases: &[(usize, &[u8], &str)] = &[
        (0, &[0x37], "Main.flag holds 55, not a BOOL (0 or 1)"),
        (
            2,
            &[5, 0],
            "Main.name has a length of 5, longer than its STRING[4]",
        ),
        (
            2,
            &[0xFF, 0xFF],
            "Main.name has a length of 65535, longer than its STRING[4]",
        ),
        (
            8,
            &[0x30, 0x75],
            "Main.level holds 30000, outside its subrange 0..10",
        ),
        (
            8,
            &[0xFF, 0xFF],
            "Main.level holds -1, outside its subrange 0..10",
        ),
        (10, &[2, 0], "Main.mode holds 2, not a value of Mode"),
        (12, &[2], "Main.cells[1].x holds 2, not a BOOL (0 or 1)"),
        (
            20,
            &[2, 0],
            "Main.cells[2].s has a length of 2, longer than its WSTRING[1]",
        ),
    ];
    for (at, bytes, why) in cases {
        let mut bad = good.clone();
        bad[*at..*at + bytes.len()].copy_from_slice(bytes);
        let data = encode(&p, &bad).unwrap();
        let mut img = vec![7u8; 64];
        assert_eq!(
            decode(&p, &data, &mut img),
            Err(format!("the RETAIN variable {why}")),
            "byte {at}"
        );
        assert_eq!(img, vec![7u8; 64], "a rejected file leaves the image alone");
    }
}

fn temp_dir(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("automat-retain-{name}-{}", std::process::id()));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn an_invalid_file_is_moved_aside_not_overwritten() {
    let dir = temp_dir("bad");
    let path = dir.join("plc.retain");
    let p = typed();
    let mut bad = typed_image();
    bad[0] = 0x37;
    let data = encode(&p, &bad).unwrap();
    fs::write(&path, &data).unwrap();
    let mut img = vec![0u8; 64];
    let Loaded::Cold(why) = load(&p, &path, &mut img) else {
        panic!("loaded an invalid file")
    };
    let moved = dir.join("plc.retain.bad");
    assert_eq!(
        why,
        format!(
            "the RETAIN variable Main.flag holds 55, not a BOOL (0 or 1); the file was moved to {}",
            moved.display()
        )
    );
    assert!(!path.exists());
    assert_eq!(fs::read(&moved).unwrap(), data);
    // The next save writes a new file and leaves the bad one alone.
    save(&p, &path, &typed_image()).unwrap();
    assert_eq!(load(&p, &path, &mut img), Loaded::Warm);
    assert_eq!(fs::read(&moved).unwrap(), data);
    // A corrupt file likewise.
    let mut corrupt = fs::read(&path).unwrap();
    corrupt[25] ^= 0x40;
    fs::write(&path, &corrupt).unwrap();
    assert!(matches!(load(&p, &path, &mut img), Loaded::Cold(w) if w.starts_with("the checksum")));
    assert_eq!(fs::read(&moved).unwrap(), corrupt);
    fs::remove_dir_all(&dir).unwrap();
}

#[cfg(unix)]
#[test]
fn a_planted_temp_symlink_is_never_followed() {
    use std::os::unix::fs::{symlink, PermissionsExt};
    let dir = temp_dir("symlink");
    let path = dir.join("plc.retain");
    let victim = dir.join("victim");
    fs::write(&victim, b"precious").unwrap();
    symlink(&victim, dir.join("plc.retain.tmp")).unwrap();
    let p = retained();
    save(&p, &path, &image()).unwrap();
    assert_eq!(fs::read(&victim).unwrap(), b"precious");
    assert!(fs::symlink_metadata(dir.join("plc.retain.tmp")).is_err());
    let meta = fs::symlink_metadata(&path).unwrap();
    assert!(meta.file_type().is_file());
    assert_eq!(meta.permissions().mode() & 0o777, 0o600);
    let mut img = vec![0u8; 64];
    assert_eq!(load(&p, &path, &mut img), Loaded::Warm);
    // A dangling symlink and a stale regular temporary go the same way.
    symlink(dir.join("nowhere"), dir.join("plc.retain.tmp")).unwrap();
    save(&p, &path, &image()).unwrap();
    assert!(!dir.join("nowhere").exists());
    fs::write(dir.join("plc.retain.tmp"), b"half a file").unwrap();
    save(&p, &path, &image()).unwrap();
    assert!(fs::symlink_metadata(dir.join("plc.retain.tmp")).is_err());
    // A directory of that name is an error, not removed.
    fs::create_dir(dir.join("plc.retain.tmp")).unwrap();
    let err = save(&p, &path, &image()).unwrap_err();
    assert!(err.contains("cannot save the RETAIN variables"), "{err}");
    assert!(dir.join("plc.retain.tmp").is_dir());
    fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_path_is_checked_before_the_first_scan() {
    let dir = temp_dir("check");
    let p = retained();
    assert_eq!(check_path(&p, &dir.join("plc.retain")), Ok(()));
    assert!(
        fs::read_dir(&dir).unwrap().next().is_none(),
        "the test save leaves nothing"
    );
    let missing = dir.join("no/such/plc.retain");
    let err = check_path(&p, &missing).unwrap_err();
    assert!(
        err.starts_with(&format!("{}: the directory ", missing.display())),
        "{err}"
    );
    fs::write(dir.join("file"), b"x").unwrap();
    let under_file = dir.join("file/plc.retain");
    let err = check_path(&p, &under_file).unwrap_err();
    assert!(err.contains("is not a directory"), "{err}");
    let err = check_path(&p, &dir).unwrap_err();
    assert!(err.ends_with("is a directory"), "{err}");
    fs::remove_dir_all(&dir).unwrap();
}
