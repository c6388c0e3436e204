//! Arbitrary bytes (as lossy UTF-8, the first byte choosing the dialect)
//! through the whole `automat check` pipeline: parse, dialect rewrites,
//! semantic checks and lowering must never panic, hang or overflow the
//! stack, and every diagnostic lies inside its file.
#![no_main]

use libfuzzer_sys::fuzz_target;

#[path = "common/pipeline.rs"]
mod pipeline;

fuzz_target!(|data: &[u8]| {
    let Some((&dialect, rest)) = data.split_first() else {
        return;
    };
    pipeline::check(&String::from_utf8_lossy(rest), dialect);
});
