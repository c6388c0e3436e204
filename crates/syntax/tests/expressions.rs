mod common;
use common::{expr, ok};

#[test]
fn precedence_levels_from_or_down_to_multiplication() {
    assert_eq!(expr("a OR b XOR c"), "(OR a (XOR b c))");
    assert_eq!(expr("a XOR b AND c"), "(XOR a (AND b c))");
    assert_eq!(expr("a AND b = c"), "(AND a (= b c))");
    assert_eq!(expr("a & b OR c"), "(OR (AND a b) c)");
    assert_eq!(expr("a = b < c"), "(= a (< b c))");
    assert_eq!(expr("a <> b >= c"), "(<> a (>= b c))");
    assert_eq!(expr("a < b + c"), "(< a (+ b c))");
    assert_eq!(expr("a + b * c"), "(+ a (* b c))");
    assert_eq!(expr("a - b MOD c"), "(- a (MOD b c))");
    assert_eq!(expr("a * b ** c"), "(* a (** b c))");
    assert_eq!(
        expr("a OR b AND c = d + e * f"),
        "(OR a (AND b (= c (+ d (* e f)))))"
    );
}

#[test]
fn binary_operators_are_left_associative() {
    assert_eq!(expr("a - b - c"), "(- (- a b) c)");
    assert_eq!(expr("a / b * c"), "(* (/ a b) c)");
    assert_eq!(expr("a ** b ** c"), "(** (** a b) c)");
    assert_eq!(expr("a AND b AND c"), "(AND (AND a b) c)");
    assert_eq!(expr("a <= b <= c"), "(<= (<= a b) c)");
}

#[test]
fn unary_operators_and_power() {
    assert_eq!(expr("-2**2"), "(neg (** 2 2))");
    assert_eq!(expr("2 ** -1"), "(** 2 (neg 1))");
    assert_eq!(expr("-a * b"), "(* (neg a) b)");
    assert_eq!(expr("NOT a AND b"), "(AND (not a) b)");
    assert_eq!(expr("NOT a = b"), "(= (not a) b)");
    assert_eq!(expr("- -a"), "(neg (neg a))");
    assert_eq!(expr("+a"), "(plus a)");
    assert_eq!(expr("a - -b"), "(- a (neg b))");
}

#[test]
fn parentheses_are_kept() {
    assert_eq!(expr("(a + b) * c"), "(* (paren (+ a b)) c)");
    assert_eq!(expr("((a))"), "(paren (paren a))");
}

#[test]
fn postfix_member_index_call_deref() {
    assert_eq!(expr("a.b.c"), "(. (. a b) c)");
    assert_eq!(expr("a[1, j + 1]"), "(index a 1 (+ j 1))");
    assert_eq!(expr("a[i][j]"), "(index (index a i) j)");
    assert_eq!(expr("p^"), "(^ p)");
    assert_eq!(expr("p^.x"), "(. (^ p) x)");
    assert_eq!(expr("s.arr[2].v"), "(. (index (. s arr) 2) v)");
    assert_eq!(expr("fb.out[3]^"), "(^ (index (. fb out) 3))");
    assert_eq!(expr("inst.fb(1)"), "(call (. inst fb) 1)");
}

#[test]
fn calls_formal_and_non_formal() {
    assert_eq!(expr("f()"), "(call f)");
    assert_eq!(expr("f(a, b + 1)"), "(call f a (+ b 1))");
    assert_eq!(
        expr("fb(IN := x, Q => y, NOT Q2 => z)"),
        "(call fb (IN := x) (Q => y) (NOT Q2 => z))"
    );
    assert_eq!(
        expr("f(EN := c, IN := x, ENO => ok)"),
        "(call f (EN := c) (IN := x) (ENO => ok))"
    );
    assert_eq!(expr("fb(Q => )"), "(call fb (Q => ))");
    assert_eq!(expr("f(NOT a)"), "(call f (not a))");
    assert_eq!(expr("MAX(a, MIN(b, c))"), "(call MAX a (call MIN b c))");
}

#[test]
fn partial_access_and_bits() {
    assert_eq!(expr("w.3"), "(.% w None 3)");
    assert_eq!(expr("w.%X3"), "(.% w Bit 3)");
    assert_eq!(expr("w.%B1"), "(.% w Byte 1)");
    assert_eq!(expr("w.%W0"), "(.% w Word 0)");
    assert_eq!(expr("w.%D0"), "(.% w DWord 0)");
    assert_eq!(expr("s.w.15 AND TRUE"), "(AND (.% (. s w) None 15) TRUE)");
    assert_eq!(expr("arr[1].2"), "(.% (index arr 1) None 2)");
}

#[test]
fn direct_addresses_as_values() {
    assert_eq!(expr("%IX0.1"), "%IX0.1");
    assert_eq!(expr("%QW4 + %MD48"), "(+ %QW4 %MD48)");
    assert_eq!(expr("%IX1.2.3"), "%IX1.2.3");
    assert_eq!(expr("%I0.1"), "%I0.1");
    assert_eq!(expr("%iw2"), "%IW2");
}

#[test]
fn contextual_keywords_are_names() {
    assert_eq!(expr("on + task + with"), "(+ (+ on task) with)");
    assert_eq!(expr("pointer.read_only"), "(. pointer read_only)");
}

#[test]
fn spans_cover_the_expression_text() {
    let out = ok("PROGRAM p\nx := a + f(b, c)[1];\nEND_PROGRAM\n");
    let automat_syntax::ast::StmtKind::Assign { target, value } = &out.body(0)[0].kind else {
        panic!()
    };
    assert_eq!(out.text(target.span), "x");
    assert_eq!(out.text(value.span), "a + f(b, c)[1]");
    assert_eq!(out.text(out.body(0)[0].span), "x := a + f(b, c)[1]");
}

#[test]
fn standard_functions_named_like_operators() {
    assert_eq!(expr("AND(a, b)"), "(call AND a b)");
    assert_eq!(expr("OR(a, AND(b, c))"), "(call OR a (call AND b c))");
    assert_eq!(
        expr("XOR(IN1 := a, IN2 := b)"),
        "(call XOR (IN1 := a) (IN2 := b))"
    );
    assert_eq!(expr("MOD(x, 3) + 1"), "(+ (call MOD x 3) 1)");
    assert_eq!(expr("NOT(IN := a)"), "(call NOT (IN := a))");
    // Still operators where an operator is expected.
    assert_eq!(expr("NOT(a)"), "(not (paren a))");
    assert_eq!(expr("a AND (b)"), "(AND a (paren b))");
    assert_eq!(expr("a MOD (3)"), "(MOD a (paren 3))");
}
