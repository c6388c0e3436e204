//! Arbitrary bytes (as lossy UTF-8) as an `automat.toml`: the reader must
//! never panic, and every diagnostic is E300–E308 with its span inside the
//! text. The project's folder does not exist, so no source is read.
#![no_main]

use automat_base::{Code, FileId};
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let path = Path::new("/nonexistent/automat-fuzz/automat.toml");
    if let Err(diags) = automat_project::file::parse(path, FileId(0), &text) {
        assert!(!diags.is_empty());
        for d in &diags {
            assert!(
                matches!(
                    d.code,
                    Code::E300
                        | Code::E301
                        | Code::E302
                        | Code::E303
                        | Code::E304
                        | Code::E305
                        | Code::E306
                        | Code::E307
                        | Code::E308
                ),
                "{:?}",
                d.code
            );
            assert!(d.span.start <= d.span.end && d.span.end as usize <= text.len());
        }
    }
});
