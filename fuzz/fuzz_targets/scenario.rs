//! Parses arbitrary bytes (as lossy UTF-8) as a scenario file, and each of
//! its lines as a live-console action: the parser must never panic, hang
//! or overflow the stack, and its diagnostics must be E320/E323, in order,
//! with spans within the text.
#![no_main]

use automat_base::{Code, FileId};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    if let Err(diags) = automat_scenario::parse(&text, FileId(0), "fuzz") {
        assert!(!diags.is_empty());
        let mut last = 0;
        for d in &diags {
            assert!(matches!(d.code, Code::E320 | Code::E323));
            // A tokenizer error may point one past the end of its line.
            assert!(d.span.start <= d.span.end && d.span.end as usize <= text.len() + 1);
            assert!(d.span.start >= last);
            last = d.span.start;
        }
    }
    for line in text.lines() {
        if let Err(d) = automat_scenario::parse::parse_action(line, FileId(0)) {
            assert!(d.span.start <= d.span.end && d.span.end as usize <= line.len() + 1);
        }
    }
});
