//! A body longer than `promote::MAX_CODE` / `compile::QUICK_CODE` IR
//! instructions is compiled without promoted slots and with Cranelift's
//! `opt_level = "none"` (for compile time linear in its length). Such a
//! body must still give exactly the interpreter's images after every
//! scan, and a fault in it must name the same site.

mod common;

use automat_jit::{MAX_PROMOTED_CODE, QUICK_CODE};

/// One program holding every shape of `benches/compile_size.rs`: FOR
/// loops over an array, TON calls, an ELSIF chain and a CASE, over
/// `n` statements of each, changing from scan to scan.
fn long_program(n: usize) -> String {
    let mut s =
        String::from("PROGRAM Main\nVAR\n    arr : ARRAY[0..99] OF DINT; i, a, c, d : DINT;\n");
    for k in 0..n / 4 {
        s.push_str(&format!("    t{k} : TON;\n"));
    }
    s.push_str("END_VAR\na := a + 1;\n");
    for k in 0..n {
        if k % 10 == 0 {
            s.push_str(&format!(
                "FOR i := 0 TO 99 DO arr[i] := arr[i] + {}; END_FOR;\n",
                k % 9
            ));
        } else {
            s.push_str(&format!("c := c + arr[{}] * a;\n", k % 100));
        }
    }
    for k in 0..n / 4 {
        s.push_str(&format!(
            "t{k}(IN := a > {}, PT := T#{}ms); IF t{k}.Q THEN d := d + {}; END_IF;\n",
            k % 3,
            10 * (k % 4),
            k % 5 + 1
        ));
    }
    s.push_str("IF a = 0 THEN c := c - 1;\n");
    for k in 1..n {
        s.push_str(&format!("ELSIF a = {} THEN c := c + {};\n", k % 7, k));
    }
    s.push_str("END_IF;\nCASE a OF\n");
    for k in 0..n {
        s.push_str(&format!("{k}: d := d - {};\n", k % 11));
    }
    s.push_str("END_CASE;\nEND_PROGRAM\n");
    s
}

#[test]
fn a_long_body_runs_as_on_the_interpreter() {
    let program = common::compile_one(&long_program(2_000));
    let main = program
        .funcs
        .iter()
        .map(|f| f.code.len())
        .max()
        .unwrap_or(0);
    assert!(
        main > QUICK_CODE.max(MAX_PROMOTED_CODE),
        "the body is only {main} instructions: it does not take the long-body path"
    );
    common::differential(program, 5, 10_000_000, None).unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn a_fault_in_a_long_body_names_the_same_site() {
    // The index reaches 100 in the fifth scan: both engines fault there.
    let mut text = long_program(2_000);
    text = text.replace(
        "END_CASE;\nEND_PROGRAM\n",
        "END_CASE;\nd := arr[a + 95];\nEND_PROGRAM\n",
    );
    let program = common::compile_one(&text);
    let mut interp = automat_engine::Engine::new(program.clone());
    let end = common::run_on(&mut interp, 6, 10_000_000).end;
    let automat_runtime::RunEnd::Fault(f) = &end else {
        panic!("the run did not fault: {end:?}")
    };
    assert_eq!(f.plc_time_ns, 40_000_000, "{f}");
    common::differential(program, 6, 10_000_000, None).unwrap_or_else(|e| panic!("{e}"));
}
