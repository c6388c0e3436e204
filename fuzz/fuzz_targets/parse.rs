//! Parses arbitrary bytes (as lossy UTF-8): the parser must never panic,
//! hang or overflow the stack, and its diagnostics must stay within the text.
#![no_main]

use automat_base::{FileId, Interner};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let mut interner = Interner::new();
    let parsed = automat_syntax::parse(FileId(0), &text, &mut interner);
    for d in &parsed.diagnostics {
        assert!(d.span.start <= d.span.end && d.span.end as usize <= text.len());
    }
});
