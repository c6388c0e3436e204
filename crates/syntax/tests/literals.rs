mod common;
use common::{errors, expr};

const S: i128 = 1_000_000_000;

#[test]
fn integers() {
    assert_eq!(expr("123_456"), "123456");
    assert_eq!(expr("2#1010"), "10");
    assert_eq!(expr("8#17"), "15");
    assert_eq!(expr("16#FF"), "255");
    assert_eq!(expr("-5"), "(neg 5)");
    assert_eq!(expr("18446744073709551615"), "18446744073709551615");
}

#[test]
fn typed_numbers() {
    assert_eq!(expr("INT#-5"), "INT#-5");
    assert_eq!(expr("WORD#16#00FF"), "WORD#255");
    assert_eq!(expr("REAL#1"), "REAL#1");
    assert_eq!(expr("LREAL#-1.5"), "LREAL#-1.5");
    assert_eq!(expr("BOOL#1"), "BOOL#1");
    assert_eq!(expr("BOOL#TRUE"), "BOOL#TRUE");
    assert_eq!(expr("dint#+7"), "dint#7");
    assert_eq!(expr("UDINT#2#1111"), "UDINT#15");
}

#[test]
fn reals() {
    assert_eq!(expr("1.5E-3"), "0.0015");
    assert_eq!(expr("1.0e6"), "1000000.0");
    assert_eq!(expr("0.5"), "0.5");
    assert_eq!(expr("3.141_592"), "3.141592");
}

#[test]
fn booleans() {
    assert_eq!(expr("TRUE"), "TRUE");
    assert_eq!(expr("false"), "FALSE");
}

#[test]
fn durations() {
    let ms = S / 1000;
    assert_eq!(
        expr("T#1h2m3s4ms"),
        format!("T#{}ns", (3600 + 120 + 3) * S + 4 * ms)
    );
    assert_eq!(expr("TIME#-5s"), format!("T#{}ns", -5 * S));
    assert_eq!(expr("T#1.5s"), format!("T#{}ns", 3 * S / 2));
    assert_eq!(expr("t#1d_2h"), format!("T#{}ns", 26 * 3600 * S));
    assert_eq!(expr("T#100ms"), format!("T#{}ns", 100 * ms));
    assert_eq!(expr("T#5us"), "T#5000ns");
    assert_eq!(expr("T#3ns"), "T#3ns");
    assert_eq!(expr("LTIME#1s"), format!("LT#{}ns", S));
    assert_eq!(expr("LT#2m"), format!("LT#{}ns", 120 * S));
}

#[test]
fn dates_and_times_of_day() {
    assert_eq!(expr("D#2024-01-31"), "D#19753d");
    assert_eq!(expr("DATE#1970-01-01"), "D#0d");
    assert_eq!(expr("LDATE#2024-02-29"), "LD#19782d");
    let tod = (12 * 3600 + 30 * 60) * S + S / 2;
    assert_eq!(expr("TOD#12:30:00.5"), format!("TOD#{tod}ns"));
    assert_eq!(expr("TIME_OF_DAY#12:30:00.5"), format!("TOD#{tod}ns"));
    assert_eq!(expr("LTOD#00:00:01"), format!("LTOD#{S}ns"));
    let dt = 19753 * 86400 * S + (12 * 3600 + 30 * 60) * S;
    assert_eq!(expr("DT#2024-01-31-12:30:00"), format!("DT#{dt}ns"));
    assert_eq!(
        expr("DATE_AND_TIME#2024-01-31-12:30:00"),
        format!("DT#{dt}ns")
    );
    assert_eq!(expr("LDT#1970-01-01-00:00:00"), "LDT#0ns");
}

#[test]
fn strings_with_escapes() {
    assert_eq!(expr("'text $'q$' $N $24'"), "\"text 'q' \\n $\"");
    assert_eq!(expr("\"wide $\"x$\" $0041\""), "w\"wide \\\"x\\\" A\"");
    assert_eq!(expr("'$L$P$R$T$$'"), "\"\\n\\u{c}\\r\\t$\"");
    assert_eq!(expr("''"), "\"\"");
    assert_eq!(expr("STRING#'abc'"), "STRING#\"abc\"");
}

#[test]
fn typed_enum_literals() {
    assert_eq!(expr("Color#Red"), "Color#Red");
    assert_eq!(expr("a = E_State#Idle"), "(= a E_State#Idle)");
}

#[test]
fn malformed_literals_are_e004_and_overflow_e006() {
    let prog = |lit: &str| format!("PROGRAM p\nx := {lit};\nEND_PROGRAM\n");
    for bad in [
        "16#G0",
        "T#5x",
        "D#2024-13-01",
        "D#2023-02-29",
        "TOD#24:00:00",
        "TOD#12:60:00",
        "DT#2024-01-01-12:00:60",
        "3#12",
        "1.5e",
        "T#1s2h",
        "INT#",
        "12abc",
        "1__000",
        "T#",
        "16#",
    ] {
        assert_eq!(errors(&prog(bad)), vec![("E004", 2)], "{bad}");
    }
    for big in [
        "18446744073709551616",
        "16#1_0000_0000_0000_0000",
        "INT#-9223372036854775809",
        "SINT#300",
        "SINT#-129",
        "USINT#-1",
        "INT#40000",
        "INT#16#10000",
        "BYTE#256",
        "BOOL#2",
        "REAL#1.0E39",
    ] {
        assert_eq!(errors(&prog(big)), vec![("E006", 2)], "{big}");
    }
    assert_eq!(errors(&prog("'a$qb'")), vec![("E003", 2)]);
}

#[test]
fn a_malformed_literal_is_an_error_expression() {
    let out = common::parse("PROGRAM p\nx := 16#G0 + 1;\nEND_PROGRAM\n");
    assert_eq!(out.diags.len(), 1);
    let automat_syntax::ast::StmtKind::Assign { value, .. } = &out.body(0)[0].kind else {
        panic!()
    };
    assert_eq!(out.expr(value), "(+ <error> 1)");
}

#[test]
fn typed_literals_at_the_edges_of_their_types() {
    assert_eq!(expr("SINT#-128"), "SINT#-128");
    assert_eq!(expr("SINT#127"), "SINT#127");
    assert_eq!(expr("BYTE#16#FF"), "BYTE#255");
    assert_eq!(
        expr("ULINT#18446744073709551615"),
        "ULINT#18446744073709551615"
    );
    assert_eq!(
        expr("LINT#-9223372036854775808"),
        "LINT#-9223372036854775808"
    );
    assert_eq!(expr("BOOL#0"), "BOOL#0");
    // Unknown to the parser: the checker types these.
    assert_eq!(expr("MyInt#100000"), "MyInt#100000");
    assert_eq!(expr("LREAL#1.0E300"), "LREAL#1e300");
}
