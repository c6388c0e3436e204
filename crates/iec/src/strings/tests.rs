use super::*;
use crate::error::ErrorKind;

fn s(text: &str) -> Vec<u8> {
    text.as_bytes().to_vec()
}

fn msg<T: std::fmt::Debug>(r: Result<T, IecError>) -> String {
    match r {
        Ok(v) => panic!("expected an error, got {v:?}"),
        Err(e) => {
            assert_eq!(e.kind, ErrorKind::StringIndex);
            e.message
        }
    }
}

#[test]
fn assignment_truncates_at_the_declared_length() {
    assert_eq!(assign(b"abcdef", 4), s("abcd"));
    assert_eq!(assign(b"abc", 4), s("abc"));
    assert_eq!(assign(b"abcd", 4), s("abcd"));
    assert_eq!(assign(b"abc", 0), s(""));
    assert_eq!(assign(&[1u16, 2, 3], 2), vec![1u16, 2]);
    let mut v = s("hello");
    truncate(&mut v, 2);
    assert_eq!(v, s("he"));
    assert_eq!(to_buffer(b"abcdef", 3), s("abc\0"));
    assert_eq!(to_buffer(b"a", 3), s("a\0\0\0"));
    assert_eq!(until_nul(b"ab\0cd"), b"ab");
    assert_eq!(until_nul(b"abc"), b"abc");
    assert_eq!(until_nul(&[0u16, 5]), &[] as &[u16]);
}

#[test]
fn len_left_right() {
    assert_eq!(len(b"hello"), 5);
    assert_eq!(len::<u16>(&[]), 0);
    assert_eq!(left(b"hello", 2), Ok(s("he")));
    assert_eq!(left(b"hello", 0), Ok(s("")));
    assert_eq!(left(b"hello", 9), Ok(s("hello")));
    assert_eq!(right(b"hello", 3), Ok(s("llo")));
    assert_eq!(right(b"hello", 5), Ok(s("hello")));
    assert_eq!(right(b"hello", 6), Ok(s("hello")));
    assert_eq!(right(b"", 0), Ok(s("")));
    assert_eq!(
        msg(left(b"abc", -1)),
        "LEFT: L = -1 is negative (IN has 3 characters)"
    );
    assert_eq!(
        msg(right(b"a", -5)),
        "RIGHT: L = -5 is negative (IN has 1 character)"
    );
}

#[test]
fn mid_takes_l_characters_from_p() {
    assert_eq!(mid(b"hello", 3, 2), Ok(s("ell")));
    assert_eq!(mid(b"hello", 10, 4), Ok(s("lo")));
    assert_eq!(mid(b"hello", 0, 1), Ok(s("")));
    assert_eq!(mid(b"hello", 2, 6), Ok(s("")));
    assert_eq!(mid(b"", 1, 1), Ok(s("")));
    assert_eq!(mid(b"hello", i64::MAX, 1), Ok(s("hello")));
    assert_eq!(
        msg(mid(b"abc", 1, 0)),
        "MID: P = 0 is out of range 1..=4 (IN has 3 characters)"
    );
    assert_eq!(
        msg(mid(b"abc", 1, 5)),
        "MID: P = 5 is out of range 1..=4 (IN has 3 characters)"
    );
    assert_eq!(
        msg(mid(b"abc", -1, 1)),
        "MID: L = -1 is negative (IN has 3 characters)"
    );
    assert_eq!(
        msg(mid(b"", 0, i64::MIN)),
        "MID: P = -9223372036854775808 is out of range 1..=1 (IN has 0 characters)"
    );
}

#[test]
fn concat_insert_delete_replace() {
    assert_eq!(concat(&[b"ab".as_slice(), b"", b"cd", b"e"]), s("abcde"));
    assert_eq!(concat::<u8>(&[]), s(""));
    assert_eq!(insert(b"ABC", b"XY", 2), Ok(s("ABXYC")));
    assert_eq!(insert(b"ABC", b"XY", 0), Ok(s("XYABC")));
    assert_eq!(insert(b"ABC", b"XY", 3), Ok(s("ABCXY")));
    assert_eq!(
        msg(insert(b"ABC", b"XY", 4)),
        "INSERT: P = 4 is out of range 0..=3 (IN1 has 3 characters)"
    );
    assert_eq!(
        msg(insert(b"ABC", b"XY", -1)),
        "INSERT: P = -1 is out of range 0..=3 (IN1 has 3 characters)"
    );
    assert_eq!(delete(b"ABCDE", 2, 2), Ok(s("ADE")));
    assert_eq!(delete(b"ABCDE", 10, 4), Ok(s("ABC")));
    assert_eq!(delete(b"ABCDE", 0, 1), Ok(s("ABCDE")));
    assert_eq!(delete(b"ABCDE", 3, 6), Ok(s("ABCDE")));
    assert_eq!(
        msg(delete(b"ABCDE", 1, 7)),
        "DELETE: P = 7 is out of range 1..=6 (IN has 5 characters)"
    );
    assert_eq!(
        msg(delete(b"ABCDE", -2, 1)),
        "DELETE: L = -2 is negative (IN has 5 characters)"
    );
    assert_eq!(replace(b"ABCDE", b"X", 2, 3), Ok(s("ABXE")));
    assert_eq!(replace(b"ABCDE", b"XYZ", 0, 1), Ok(s("XYZABCDE")));
    assert_eq!(replace(b"ABCDE", b"XY", 99, 4), Ok(s("ABCXY")));
    assert_eq!(replace(b"ABC", b"!", 1, 4), Ok(s("ABC!")));
    assert_eq!(
        msg(replace(b"ABC", b"!", 1, 0)),
        "REPLACE: P = 0 is out of range 1..=4 (IN1 has 3 characters)"
    );
    assert_eq!(
        msg(replace(b"ABC", b"!", -1, 1)),
        "REPLACE: L = -1 is negative (IN1 has 3 characters)"
    );
}

#[test]
fn find_and_compare() {
    assert_eq!(find(b"ABCBC", b"BC"), 2);
    assert_eq!(find(b"ABCBC", b"A"), 1);
    assert_eq!(find(b"ABCBC", b"CBC"), 3);
    assert_eq!(find(b"ABC", b"X"), 0);
    assert_eq!(find(b"ABC", b"ABCD"), 0);
    assert_eq!(find(b"ABC", b""), 0);
    assert_eq!(find(b"", b"A"), 0);
    assert_eq!(find(&[0x20ACu16, 0x41], &[0x41]), 2);
    use std::cmp::Ordering::*;
    assert_eq!(compare(b"AB", b"ABC"), Less);
    assert_eq!(compare(b"ABC", b"B"), Less);
    assert_eq!(compare(b"b", b"B"), Greater);
    assert_eq!(compare(b"", b""), Equal);
    assert_eq!(compare(&[0xE9u8], b"z"), Greater);
    assert_eq!(compare(&[0x100u16], &[0xFFu16, 0xFF]), Greater);
}

#[test]
fn wide_strings_share_the_rules() {
    let w: Vec<u16> = "h\u{e9}llo".encode_utf16().collect();
    assert_eq!(mid(&w, 2, 2), Ok(vec![0xE9, 0x6C]));
    assert_eq!(left(&w, 1), Ok(vec![0x68]));
    assert_eq!(
        msg(right(&w, -1)),
        "RIGHT: L = -1 is negative (IN has 5 characters)"
    );
}

#[test]
fn results_truncate_when_stored() {
    // CONCAT of two STRING(4) into a STRING(5): the engine stores assign(.., 5).
    let joined = concat(&[b"abcd".as_slice(), b"efgh"]);
    assert_eq!(assign(&joined, 5), s("abcde"));
    let inserted = insert(b"abcd", b"XYZ", 4).unwrap_or_default();
    assert_eq!(assign(&inserted, 4), s("abcd"));
    assert_eq!(to_buffer(&inserted, 0), s("\0"));
    assert_eq!(assign(&[0xE9u16; 300], 254).len(), 254);
}

#[test]
fn positions_at_the_exact_ends() {
    assert_eq!(mid(b"abc", 1, 3), Ok(s("c")));
    assert_eq!(mid(b"abc", 1, 4), Ok(s("")));
    assert_eq!(delete(b"abc", 1, 3), Ok(s("ab")));
    assert_eq!(delete(b"abc", 1, 4), Ok(s("abc")));
    assert_eq!(replace(b"abc", b"Z", 1, 3), Ok(s("abZ")));
    assert_eq!(insert(b"", b"Z", 0), Ok(s("Z")));
    assert_eq!(replace(b"", b"Z", 5, 1), Ok(s("Z")));
    assert_eq!(delete(b"", 5, 1), Ok(s("")));
    assert_eq!(
        msg(mid(b"", 0, 2)),
        "MID: P = 2 is out of range 1..=1 (IN has 0 characters)"
    );
}

#[test]
fn wide_comparison_and_find() {
    let a: Vec<u16> = "\u{65e5}\u{672c}".encode_utf16().collect();
    let b: Vec<u16> = "\u{65e5}".encode_utf16().collect();
    assert_eq!(compare(&b, &a), std::cmp::Ordering::Less);
    assert_eq!(find(&a, &[0x672C]), 2);
    assert_eq!(
        concat(&[a.as_slice(), b.as_slice()]),
        vec![0x65E5, 0x672C, 0x65E5]
    );
    assert_eq!(replace(&a, &[0x41], 1, 1), Ok(vec![0x41, 0x672C]));
}
