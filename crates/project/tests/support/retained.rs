//! A program whose RETAIN variables have every kind of type the retain
//! loader checks (BOOL, STRING, WSTRING, subrange, enumeration, arrays,
//! structures, FB instances, REAL, TIME), for the retain loader's
//! robustness test and its fuzz target (`fuzz/fuzz_targets/retain.rs`).

use automat_base::SourceMap;
use automat_ir::Program;

pub const SOURCE: &str = "TYPE Mode : (Auto, Hand, Off); END_TYPE
TYPE Level : INT (0..10); END_TYPE
TYPE Cell :
    STRUCT
        on : BOOL;
        name : STRING[4];
        lvl : Level;
    END_STRUCT;
END_TYPE
FUNCTION_BLOCK Keep
VAR_OUTPUT q : BOOL; END_VAR
VAR m : Mode := Off; w : WSTRING[3]; END_VAR
    q := NOT q;
END_FUNCTION_BLOCK
VAR_GLOBAL RETAIN
    g : Level := 3;
END_VAR
PROGRAM main
VAR RETAIN
    flag : BOOL;
    name : STRING[5] := 'ab';
    lvl : Level := 4;
    mode : Mode := Hand;
    cells : ARRAY[1..3] OF Cell;
    grid : ARRAY[0..1, 1..2] OF BOOL;
    k : Keep;
    t : TON;
    x : REAL := 1.5;
    d : TIME := T#2s;
END_VAR
VAR
    scratch : INT;
END_VAR
    flag := NOT flag;
    k();
    cells[2].name := 'xy';
    cells[3].lvl := 9;
    grid[1, 2] := TRUE;
END_PROGRAM
";

/// The compiled program.
pub fn program() -> Program {
    let mut map = SourceMap::new();
    map.add("retained.st".to_string(), SOURCE.to_string());
    match automat_project::build::compile_map(map, None, &[]) {
        Ok((p, _)) => p,
        Err(e) => panic!("{}", e.text),
    }
}
