mod common;
#[test]
fn stack() {
    let n = 250;
    let wrap = |stmts: String| format!("PROGRAM p\n{stmts}\nEND_PROGRAM");
    let cases = [
        wrap(format!("x := {}1{};", "(".repeat(n), ")".repeat(n))),
        wrap(format!("x := {}1{};", "f(".repeat(n), ")".repeat(n))),
        wrap(format!("x := {}1{};", "a[".repeat(n), "]".repeat(n))),
        wrap(format!("x := {}1;", "NOT -".repeat(n / 2))),
        wrap(format!("{}x := 1;{}", "IF a THEN ".repeat(n), " END_IF;".repeat(n))),
        wrap(format!("{}x := 1;{}", "CASE a OF 1: ".repeat(n), " END_CASE;".repeat(n))),
        wrap(format!("{}x := 1;{}", "WHILE a DO ".repeat(n), " END_WHILE;".repeat(n))),
        format!("TYPE T : {}INT; END_TYPE", "ARRAY [1..2] OF ".repeat(n)),
        format!("TYPE T : {} a : INT; {} END_TYPE", "STRUCT s : ".repeat(n - 1) + "STRUCT", "END_STRUCT; ".repeat(n)),
        format!("PROGRAM p VAR x : T := {}1{}; END_VAR END_PROGRAM", "[".repeat(n), "]".repeat(n)),
        format!("PROGRAM p VAR x : T := {}1{}; END_VAR END_PROGRAM", "(a := ".repeat(n), ")".repeat(n)),
    ];
    for (i, src) in cases.iter().enumerate() {
        let mut lo = 16_000usize; let mut hi = 8_000_000usize;
        while hi - lo > 8000 {
            let mid = (lo + hi) / 2;
            let s = src.clone();
            let ok = std::process::Command::new(std::env::current_exe().unwrap()).arg("--exact").arg("child").arg("--nocapture").env("CHILD_SRC", &s).env("CHILD_STACK", mid.to_string()).output().unwrap().status.success();
            if ok { hi = mid } else { lo = mid }
        }
        println!("case {i}: {} KB ({} B/level)", hi / 1024, hi / n);
    }
}
#[test]
fn child() {
    let Ok(src) = std::env::var("CHILD_SRC") else { return };
    let st: usize = std::env::var("CHILD_STACK").unwrap().parse().unwrap();
    std::thread::Builder::new().stack_size(st).spawn(move || { common::parse(&src); }).unwrap().join().unwrap();
}
