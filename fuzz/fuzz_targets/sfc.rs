//! Arbitrary bytes (as lossy UTF-8) as the body of a program that holds a
//! textual SFC chart, through the whole check pipeline (SFC parser, chart
//! checks, desugaring, lowering); the first byte chooses the dialect
//! (ISaGRAF and PL7 rewrite charts).
#![no_main]

use libfuzzer_sys::fuzz_target;

#[path = "common/pipeline.rs"]
mod pipeline;

const HEAD: &str = "PROGRAM Main\nVAR x, y, go : BOOL; n : INT; t : TIME; END_VAR\n";
const TAIL: &str = "\nEND_PROGRAM\n";

fuzz_target!(|data: &[u8]| {
    let Some((&dialect, rest)) = data.split_first() else {
        return;
    };
    let body = String::from_utf8_lossy(rest);
    pipeline::check(&format!("{HEAD}{body}{TAIL}"), dialect);
});
