//! Imports arbitrary bytes (as lossy UTF-8) as a PLCopen TC6 XML file and
//! checks the result: the importer and the checker must never panic, hang
//! or overflow the stack, and every diagnostic lies inside the text.
#![no_main]

use automat_base::{Interner, SourceMap};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let mut map = SourceMap::new();
    map.add("fuzz.xml", text.as_ref());
    let mut interner = Interner::new();
    let (_, analysis) = automat_dialect::check_sources(&map, &mut interner, &[]);
    for d in &analysis.diagnostics {
        assert!(d.span.start <= d.span.end && d.span.end as usize <= text.len());
    }
});
