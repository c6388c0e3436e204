use super::*;
use crate::ast::LitKind;

fn lex_str(src: &str) -> (Lexed, Vec<Diagnostic>, Interner) {
    let mut interner = Interner::new();
    let mut diags = Vec::new();
    let lexed = lex(FileId(0), src, &mut interner, &mut diags);
    (lexed, diags, interner)
}

fn kinds(src: &str) -> Vec<Tok> {
    lex_str(src).0.toks.iter().map(|t| t.tok).collect()
}

fn codes(src: &str) -> Vec<(Code, u32, u32)> {
    lex_str(src)
        .1
        .iter()
        .map(|d| (d.code, d.span.start, d.span.end))
        .collect()
}

#[test]
fn keywords_are_case_insensitive_and_identifiers_interned() {
    let (lexed, diags, interner) = lex_str("if Motor tHeN motor END_if");
    assert!(diags.is_empty());
    let t: Vec<Tok> = lexed.toks.iter().map(|t| t.tok).collect();
    let m = interner.lookup("MOTOR").unwrap();
    assert_eq!(
        t,
        vec![
            Tok::Kw(Kw::If),
            Tok::Ident(m),
            Tok::Kw(Kw::Then),
            Tok::Ident(m),
            Tok::Kw(Kw::EndIf),
            Tok::Eof
        ]
    );
    assert_eq!((lexed.toks[1].start, lexed.toks[1].end), (3, 8));
}

#[test]
fn punctuation() {
    assert_eq!(
        kinds(":= => : ; , . .. ( ) [ ] + - * ** / = <> < <= > >= & ^"),
        vec![
            Tok::ColonEq,
            Tok::Arrow,
            Tok::Colon,
            Tok::Semi,
            Tok::Comma,
            Tok::Dot,
            Tok::DotDot,
            Tok::LParen,
            Tok::RParen,
            Tok::LBracket,
            Tok::RBracket,
            Tok::Plus,
            Tok::Minus,
            Tok::Star,
            Tok::StarStar,
            Tok::Slash,
            Tok::Eq,
            Tok::Ne,
            Tok::Lt,
            Tok::Le,
            Tok::Gt,
            Tok::Ge,
            Tok::Amp,
            Tok::Caret,
            Tok::Eof
        ]
    );
}

#[test]
fn comments_and_pragmas_are_skipped() {
    let src = "a (* x (* nested *) y *) b /* c (* */ c // d\n e {attribute 'x'} f";
    assert_eq!(kinds(src).len(), 6);
    assert!(codes(src).is_empty());
}

#[test]
fn unterminated_comments() {
    assert_eq!(codes("a (* (* *) b"), vec![(Code::E002, 2, 4)]);
    assert_eq!(codes("a /* b"), vec![(Code::E002, 2, 4)]);
    assert_eq!(codes("a { b"), vec![(Code::E002, 2, 3)]);
}

#[test]
fn ranges_and_bit_access_are_not_reals() {
    let (lexed, _, _) = lex_str("1..5 w.3 1.5");
    let t: Vec<Tok> = lexed.toks.iter().map(|t| t.tok).collect();
    assert!(matches!(
        t.as_slice(),
        [
            Tok::Lit(_),
            Tok::DotDot,
            Tok::Lit(_),
            Tok::Ident(_),
            Tok::Dot,
            Tok::Lit(_),
            Tok::Lit(_),
            Tok::Eof
        ]
    ));
    assert_eq!(lexed.lits[0].kind, LitKind::Int(1));
    assert_eq!(lexed.lits[2].kind, LitKind::Int(3));
    assert_eq!(lexed.lits[3].kind, LitKind::Real(1.5));
}

#[test]
fn typed_literals_are_one_token() {
    let (lexed, diags, interner) = lex_str("INT#-5 WORD#16#00FF T#1h2m TOD#12:30:00.5 Color#Red");
    assert!(diags.is_empty(), "{diags:?}");
    assert_eq!(lexed.toks.len(), 6);
    assert_eq!(lexed.lits[0].kind, LitKind::Int(-5));
    assert_eq!(lexed.lits[0].ty.map(|i| i.sym), interner.lookup("int"));
    assert_eq!(lexed.lits[1].kind, LitKind::Int(255));
    assert_eq!(lexed.lits[2].ty, None);
    let red = interner.lookup("red").unwrap();
    assert!(matches!(lexed.lits[4].kind, LitKind::Enum(i) if i.sym == red && i.span.start == 48));
}

#[test]
fn malformed_literals_are_reported_with_their_span() {
    assert_eq!(codes("x := 16#G0;"), vec![(Code::E004, 5, 10)]);
    assert_eq!(codes("T#5x"), vec![(Code::E004, 0, 4)]);
    assert_eq!(codes("D#2024-13-01"), vec![(Code::E004, 0, 12)]);
    assert_eq!(codes("99999999999999999999"), vec![(Code::E006, 0, 20)]);
    assert_eq!(codes("INT#"), vec![(Code::E004, 0, 4)]);
    assert_eq!(kinds("16#G0"), vec![Tok::BadLit, Tok::Eof]);
}

#[test]
fn strings() {
    let (lexed, diags, _) = lex_str("'it$'s' \"w$\"\"");
    assert!(diags.is_empty());
    assert_eq!(
        lexed.lits[0].kind,
        LitKind::String {
            value: "it's".into(),
            wide: false
        }
    );
    assert_eq!(
        lexed.lits[1].kind,
        LitKind::String {
            value: "w\"".into(),
            wide: true
        }
    );
    assert_eq!(codes("x := 'abc\ny"), vec![(Code::E003, 5, 9)]);
    assert_eq!(codes("'a$q'"), vec![(Code::E003, 0, 5)]);
    assert_eq!(codes("'abc"), vec![(Code::E003, 0, 4)]);
}

#[test]
fn invalid_characters_are_one_error_per_run() {
    assert_eq!(
        codes("a @@ b ? c"),
        vec![(Code::E001, 2, 4), (Code::E001, 7, 8)]
    );
    assert_eq!(codes("a \u{e9}\u{e8} b"), vec![(Code::E001, 2, 6)]);
    assert_eq!(kinds("a # b").len(), 3);
}

#[test]
fn addresses() {
    let (lexed, _, _) = lex_str("%IX1.2.3 %QW* %I0.1 %X3");
    let spans: Vec<(u32, u32)> = lexed.toks.iter().map(|t| (t.start, t.end)).collect();
    assert_eq!(spans, vec![(0, 8), (9, 13), (14, 19), (20, 23), (23, 23)]);
}

#[test]
fn byte_order_mark_is_skipped() {
    assert_eq!(kinds("\u{feff}x"), kinds("x"));
    assert!(codes("\u{feff}x").is_empty());
}

#[test]
fn many_identifiers_map_to_their_own_symbols() {
    // More names than the lexer's cache of recent identifiers has slots,
    // each twice in different case: every token must carry its own symbol.
    let names: Vec<String> = (0..2000).map(|i| format!("name_{i}")).collect();
    let src = names
        .iter()
        .map(|n| format!("{n} {}", n.to_uppercase()))
        .collect::<Vec<_>>()
        .join(" ");
    let (lexed, diags, interner) = lex_str(&src);
    assert!(diags.is_empty());
    for (i, n) in names.iter().enumerate() {
        let want = interner.lookup(n).unwrap();
        assert_eq!(lexed.toks[2 * i].tok, Tok::Ident(want), "{n}");
        assert_eq!(lexed.toks[2 * i + 1].tok, Tok::Ident(want), "{n}");
        assert_eq!(interner.name(want), n.as_str());
    }
}
