//! Arbitrary bytes through the RETAIN loader (`automat_runtime::retain::
//! decode`) of a program with every kind of checked type (the fixture of
//! `crates/project/tests/retain_robust.rs`): it must never panic; a
//! rejected file leaves the image untouched; an accepted one restores only
//! values that pass the type checks and re-encodes to the same bytes.
//!
//! When the first byte is odd, the rest of the input gets a correct
//! checksum stamped on its last four bytes, so the fuzzer reaches the
//! layout and value checks instead of stopping at the CRC. The value
//! checker also runs on the input laid over a whole image.
#![no_main]

#[path = "../../crates/project/tests/support/retained.rs"]
mod retained;

use automat_runtime::retain::{decode, encode, validate};
use libfuzzer_sys::fuzz_target;
use std::sync::OnceLock;

fn program() -> &'static automat_ir::Program {
    static PROGRAM: OnceLock<automat_ir::Program> = OnceLock::new();
    PROGRAM.get_or_init(retained::program)
}

fn crc32(data: &[u8]) -> u32 {
    let mut c = !0u32;
    for &b in data {
        c ^= u32::from(b);
        for _ in 0..8 {
            c = if c & 1 != 0 { (c >> 1) ^ 0xEDB8_8320 } else { c >> 1 };
        }
    }
    !c
}

fuzz_target!(|data: &[u8]| {
    let program = program();
    let Some((&mode, rest)) = data.split_first() else {
        return;
    };
    let mut file = rest.to_vec();
    if mode & 1 == 1 && file.len() >= 4 {
        let n = file.len() - 4;
        let crc = crc32(&file[..n]);
        file[n..].copy_from_slice(&crc.to_le_bytes());
    }
    let mut image = vec![0x5Au8; program.initial_image.len()];
    match decode(program, &file, &mut image) {
        Ok(()) => {
            assert_eq!(validate::first_invalid(program, &image), None);
            assert_eq!(encode(program, &image).as_deref(), Some(file.as_slice()));
        }
        Err(why) => {
            assert!(!why.is_empty());
            assert!(image.iter().all(|&b| b == 0x5A), "{why}");
        }
    }
    // The checker alone, on arbitrary image contents.
    let mut raw = program.initial_image.clone();
    for (dst, src) in raw.iter_mut().zip(rest) {
        *dst = *src;
    }
    let _ = validate::first_invalid(program, &raw);
});
