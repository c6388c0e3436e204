//! Robustness of the RETAIN loader: seeded mutations of a valid file of a
//! program with every checked kind of type (`support/retained.rs`) go
//! through `automat_runtime::retain::decode`, most with the checksum (and
//! often the length field) re-stamped so the mutation reaches the value
//! checks. Whatever the bytes: no panic; a rejected file leaves the image
//! untouched; an accepted one restores values that all pass the type
//! checks and re-encode to exactly the file's bytes. The cargo-fuzz target
//! `fuzz/fuzz_targets/retain.rs` does the same with arbitrary bytes.

#[path = "support/retained.rs"]
mod retained;

use automat_runtime::retain::{decode, encode, validate};

/// xorshift64*.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

const CASES: u64 = 20_000;
const HEADER: usize = 24;

/// A CRC-32 (IEEE) of its own, so the test does not trust the loader's.
fn crc32(data: &[u8]) -> u32 {
    let mut c = !0u32;
    for &b in data {
        c ^= u32::from(b);
        for _ in 0..8 {
            c = if c & 1 != 0 {
                (c >> 1) ^ 0xEDB8_8320
            } else {
                c >> 1
            };
        }
    }
    !c
}

fn mutate(rng: &mut Rng, good: &[u8]) -> Vec<u8> {
    let mut data = good.to_vec();
    for _ in 0..1 + rng.below(4) {
        let at = rng.below(data.len());
        match rng.below(8) {
            // Mostly inside the payload, where the values are.
            0..=3 => {
                let p = HEADER + rng.below(good.len() - HEADER - 4);
                if let Some(b) = data.get_mut(p) {
                    *b = match rng.below(4) {
                        0 => rng.next() as u8,
                        1 => *b ^ (1 << rng.below(8)),
                        2 => 0xFF,
                        _ => 0x37,
                    };
                }
            }
            4 => data.truncate(at),
            5 => data.insert(at, rng.next() as u8),
            6 => {
                if at < data.len() {
                    data.remove(at);
                }
            }
            _ => {
                if let Some(b) = data.get_mut(at) {
                    *b = rng.next() as u8;
                }
            }
        }
    }
    if data.len() >= HEADER + 4 && rng.below(2) == 0 {
        let len = (data.len() - HEADER - 4) as u32;
        data[20..24].copy_from_slice(&len.to_le_bytes());
    }
    if data.len() >= HEADER + 4 && rng.below(4) != 0 {
        let n = data.len() - 4;
        let crc = crc32(&data[..n]);
        data[n..].copy_from_slice(&crc.to_le_bytes());
    }
    data
}

#[test]
fn mutated_retain_files_never_crash_nor_load_bad_values() {
    let program = retained::program();
    assert!(program.retain.len() >= 2, "{:?}", program.retain);
    // The start image, then a few scans' worth of changes.
    let mut image = program.initial_image.clone();
    let good = encode(&program, &image).expect("encode");
    let n = good.len() - 4;
    assert_eq!(good[n..], crc32(&good[..n]).to_le_bytes(), "the CRCs agree");
    let mut fresh = vec![0u8; image.len()];
    assert_eq!(decode(&program, &good, &mut fresh), Ok(()));
    image.clone_from(&fresh);

    let mut rng = Rng(0x05EE_D0F2_E7A1);
    let (mut accepted, mut value_errors) = (0u64, 0u64);
    let mut seen = std::collections::BTreeSet::new();
    for case in 0..CASES {
        let data = mutate(&mut rng, &good);
        let mut img = vec![0x5Au8; image.len()];
        match decode(&program, &data, &mut img) {
            Ok(()) => {
                accepted += 1;
                assert_eq!(validate::first_invalid(&program, &img), None, "case {case}");
                assert_eq!(
                    encode(&program, &img).as_deref(),
                    Some(data.as_slice()),
                    "case {case}"
                );
            }
            Err(why) => {
                assert!(img.iter().all(|&b| b == 0x5A), "case {case}: {why}");
                if let Some(rest) = why.strip_prefix("the RETAIN variable ") {
                    value_errors += 1;
                    // The variable named, without the value.
                    let name = rest.split(' ').next().unwrap_or("");
                    seen.insert(without_indexes(name).to_ascii_lowercase());
                }
            }
        }
    }
    eprintln!(
        "retain loader: {CASES} mutants, {accepted} accepted, {value_errors} refused by a value check, \
         variables named: {seen:?}"
    );
    // The value checks are reached, for every kind of checked type.
    assert!(value_errors > CASES / 20, "{value_errors}");
    for v in [
        "g",
        "main.flag",
        "main.name",
        "main.lvl",
        "main.mode",
        "main.cells.on",
        "main.cells.name",
        "main.cells.lvl",
        "main.grid",
        "main.k.q",
        "main.k.m",
        "main.k.w",
    ] {
        assert!(seen.contains(v), "{v} never named: {seen:?}");
    }
}

/// `main.cells[2].on` → `main.cells.on`.
fn without_indexes(name: &str) -> String {
    let mut out = String::new();
    let mut depth = 0;
    for c in name.chars() {
        match c {
            '[' => depth += 1,
            ']' => depth -= 1,
            _ if depth == 0 => out.push(c),
            _ => {}
        }
    }
    out
}
