mod common;
#[test]
fn show() {
    let src = std::fs::read_to_string("/tmp/pg/in.st").unwrap();
    for case in src.split("=====\n") {
        println!("---------------\n{case}");
        let out = common::parse(case);
        let file = automat_base::SourceFile::new("t", case);
        for d in &out.diags {
            let (l, c) = file.line_col(d.span.start);
            println!("  {}:{} {} {}{}", l, c, d.code.as_str(), d.message, d.labels.iter().map(|l| format!(" [label {}:{} {}]", file.line_col(l.span.start).0, file.line_col(l.span.start).1, l.message)).collect::<String>());
        }
    }
}
