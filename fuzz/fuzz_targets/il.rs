//! Arbitrary bytes (as lossy UTF-8) as the Instruction List body of a
//! function block that a program calls, through the whole check pipeline
//! (IL parser, desugaring into ST, checks, lowering).
#![no_main]

use libfuzzer_sys::fuzz_target;

#[path = "common/pipeline.rs"]
mod pipeline;

const HEAD: &str = "FUNCTION_BLOCK Fb\nVAR_INPUT a, b : INT; s : BOOL; END_VAR\n\
VAR_OUTPUT q : INT; done : BOOL; END_VAR\nVAR x : INT; y : BOOL; t : TON; c : CTU; END_VAR\n";
const TAIL: &str = "\nEND_FUNCTION_BLOCK\nPROGRAM Main\nVAR f : Fb; END_VAR\n\
f(a := 1, b := 2, s := TRUE);\nEND_PROGRAM\n";

fuzz_target!(|data: &[u8]| {
    let body = String::from_utf8_lossy(data);
    pipeline::check(&format!("{HEAD}{body}{TAIL}"), 0);
});
