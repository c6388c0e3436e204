//! Functions whose instances are all static (program instances and the FB
//! instances they own) are compiled once without an entry check; an FB
//! reached through an array element keeps the checked twin. Either way the
//! results are the interpreter's.

mod common;

use automat_engine::Engine;
use automat_jit::Jit;

const SRC: &str = "
FUNCTION_BLOCK Counter
VAR_INPUT step : INT; END_VAR
VAR_OUTPUT n : INT; END_VAR
n := n + step;
END_FUNCTION_BLOCK

FUNCTION_BLOCK Direct
VAR_OUTPUT n : INT; END_VAR
n := n + 1;
END_FUNCTION_BLOCK

PROGRAM Main
VAR
    single : Direct;
    both : Counter;
    cells : ARRAY[1..3] OF Counter;
    i : INT;
END_VAR
single();
both(step := 10);
FOR i := 1 TO 3 DO
    cells[i](step := i);
END_FOR;
END_PROGRAM
";

fn func(p: &automat_ir::Program, name: &str) -> u32 {
    p.funcs
        .iter()
        .position(|f| f.name.eq_ignore_ascii_case(name))
        .unwrap_or_else(|| panic!("no function {name}")) as u32
}

#[test]
fn static_instances_are_compiled_without_entry_check() {
    let program = common::compile_one(SRC);
    let (main, direct, counter) = (
        func(&program, "Main"),
        func(&program, "Direct"),
        func(&program, "Counter"),
    );
    let jit = Jit::new(program).expect("jit");
    assert!(jit.is_static(main), "a program instance of a task");
    assert!(jit.is_static(direct), "called only as a member of Main");
    // `both` is a member, but `cells[i]` reaches Counter through a register.
    assert!(!jit.is_static(counter));
}

#[test]
fn static_and_dynamic_instances_run_as_on_the_interpreter() {
    let program = common::compile_one(SRC);
    let mut e = Engine::new(program.clone());
    let mut j = Jit::new(program).expect("jit");
    let a = common::run_on(&mut e, 5, 10_000_000);
    let b = common::run_on(&mut j, 5, 10_000_000);
    assert_eq!(a, b);
    assert_eq!(a.images.len(), 5);
}

#[test]
fn a_static_function_refuses_an_instance_outside_the_image() {
    let program = common::compile_one(SRC);
    let main = func(&program, "Main");
    let size = program.image_size;
    let mut j = Jit::new(program).expect("jit");
    let err = j.run_func(main, size, 0).expect_err("outside the image");
    assert!(err.message.contains("outside the image"), "{}", err.message);
}
