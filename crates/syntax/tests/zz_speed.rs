use automat_base::{FileId, Interner};
#[test]
fn speed() {
    let files: Vec<String> = (0..300).map(|i| match i % 3 { 0 => include_str!("samples/math.st"), 1 => include_str!("samples/traffic.st"), _ => include_str!("samples/plant.st") }.repeat(4)).collect();
    let lines: usize = files.iter().map(|f| f.lines().count()).sum();
    let bytes: usize = files.iter().map(|f| f.len()).sum();
    let mut i = Interner::new();
    for round in 0..8 {
        let t = std::time::Instant::now();
        let mut toks = 0;
        for f in &files {
            let mut d = Vec::new();
            let lx = automat_syntax::lexer::lex(FileId(0), f, &mut i, &mut d);
            toks += lx.toks.len();
        }
        let tl = t.elapsed();
        let t = std::time::Instant::now();
        let mut n = 0;
        for f in &files {
            let p = automat_syntax::parse(FileId(0), f, &mut i);
            n += p.unit.items.len();
        }
        let el = t.elapsed();
        if round > 2 {
        println!("{} lines {} KB: lex {:?} ({} toks) = {:.0} lines/s, lex+parse {:?} = {:.0} lines/s, {} items", lines, bytes >> 10, tl, toks, lines as f64 / tl.as_secs_f64(), el, lines as f64 / el.as_secs_f64(), n);
        }
    }
}
