//! STRING functions worked in place in the image: LEN, assignment, LEFT,
//! CONCAT of two and integer to STRING, when every byte they read or write is inside the
//! image. Why: the general path (`builtins.rs`) reads every operand into a
//! `Vec`, builds the result in another and copies it in, several heap
//! allocations per call; a string loop spent most of its time there.
//! Anything else (a range leaving the image, a negative length, WSTRING,
//! overlapping operands of CONCAT) returns `None` and takes the general
//! path, which also produces every fault, so results are the same bytes.
//!
//! [`run`] works on the operands' register bits directly, so the JIT calls
//! it from generated code with the operands in machine registers
//! (`automat_jit::rt::jit_str`), without the slot array and the dispatch
//! of the general builtin entry; the interpreter calls it through
//! [`narrow`] and [`int_text`].

use crate::interp::Ctx;
use automat_iec::Elementary as E;
use automat_ir::code::{Builtin, Reg, StrFn};
use automat_ir::strbuf::{self, LEN_BYTES, MAX_LEN};

/// The units of the string at `at` as (start, length), when its header and
/// all of them are inside the image.
fn units(image: &[u8], at: u32) -> Option<(usize, usize)> {
    let n = strbuf::len(image, at)? as usize;
    let start = (at as usize).checked_add(LEN_BYTES as usize)?;
    (start.checked_add(n)? <= image.len()).then_some((start, n))
}

/// Where `n` units stored at `at` (room `cap`) go, as (start, stored
/// length), when the header and those units are inside the image.
fn room(image: &[u8], at: u32, cap: u32, n: usize) -> Option<(usize, usize)> {
    let m = n.min(cap.min(MAX_LEN) as usize);
    let start = (at as usize).checked_add(LEN_BYTES as usize)?;
    (start.checked_add(m)? <= image.len()).then_some((start, m))
}

/// Whether `a .. a + n` and `b .. b + m` share a byte.
fn overlap(a: usize, n: usize, b: usize, m: usize) -> bool {
    a < b + m && b < a + n
}

/// Whether [`run`] may handle `op` with `count` arguments (it may still
/// decline a call at run time).
pub fn handles(op: Builtin, count: usize) -> bool {
    // The operands each reads (CONCAT of more than two: the general path).
    match op {
        Builtin::Str(StrFn::Len, false) => (1..=4).contains(&count),
        Builtin::Str(StrFn::Assign, false) => (3..=4).contains(&count),
        Builtin::Str(StrFn::Left, false) | Builtin::Str(StrFn::Concat, false) => count == 4,
        Builtin::ToString(from, false) => from.is_int() && (3..=4).contains(&count),
        _ => false,
    }
}

/// Runs `op` in place over the argument register bits `a` (as the general
/// path reads them; missing ones are 0): `Some(result)` (LEN's length, else
/// 0) or `None`, not handled here (nothing was written).
pub fn run(image: &mut [u8], op: Builtin, a: [u64; 4]) -> Option<u64> {
    match op {
        Builtin::Str(StrFn::Len, false) => Some(units(image, a[0] as u32)?.1 as u64),
        Builtin::Str(s @ (StrFn::Assign | StrFn::Left), false) => {
            let (d, cap) = (a[0] as u32, a[1] as u32);
            let (from, mut n) = units(image, a[2] as u32)?;
            if s == StrFn::Left {
                // LEFT(IN, L) with L < 0 faults on the general path.
                n = n.min(usize::try_from(a[3] as i64).ok()?);
            }
            let (to, m) = room(image, d, cap, n)?;
            // A memmove: the source is read as a whole before the header
            // is written, as the general path's copy is.
            image.copy_within(from..from + m, to);
            strbuf::set_len(image, d, m as u32)?;
            Some(0)
        }
        Builtin::Str(StrFn::Concat, false) => {
            let (d, cap) = (a[0] as u32, a[1] as u32);
            let (x, nx) = units(image, a[2] as u32)?;
            let (y, ny) = units(image, a[3] as u32)?;
            let (to, m) = room(image, d, cap, nx + ny)?;
            let head = to - LEN_BYTES as usize;
            let written = m + LEN_BYTES as usize;
            if overlap(head, written, x, nx) || overlap(head, written, y, ny) {
                return None;
            }
            let first = nx.min(m);
            image.copy_within(x..x + first, to);
            image.copy_within(y..y + (m - first), to + first);
            strbuf::set_len(image, d, m as u32)?;
            Some(0)
        }
        Builtin::ToString(from, false) => {
            let (d, cap, bits) = (a[0] as u32, a[1] as u32, a[2]);
            let mut buf = [0u8; 20];
            // The register holds the value as `builtins::to_value` reads it.
            let digits = match from {
                E::Sint | E::Int | E::Dint | E::Lint => {
                    let v = bits as i64;
                    decimal(&mut buf, v < 0, v.unsigned_abs())
                }
                E::Usint | E::Uint | E::Udint | E::Ulint => decimal(&mut buf, false, bits),
                _ => return None,
            };
            let (to, m) = room(image, d, cap, digits.len())?;
            image.get_mut(to..to + m)?.copy_from_slice(digits.get(..m)?);
            strbuf::set_len(image, d, m as u32)?;
            Some(0)
        }
        _ => None,
    }
}

/// The decimal text of `v` (with a leading `-` when `negative`), as
/// `automat_iec::convert` prints an integer, built from the end of `buf`
/// without the formatting machinery (a string loop spent more time in
/// `write!` than in the copy).
fn decimal(buf: &mut [u8; 20], negative: bool, mut v: u64) -> &[u8] {
    let mut i = buf.len();
    loop {
        i -= 1;
        buf[i] = b'0' + (v % 10) as u8;
        v /= 10;
        if v == 0 {
            break;
        }
    }
    if negative {
        i -= 1;
        buf[i] = b'-';
    }
    &buf[i..]
}

/// The register bits of `args` as [`run`] takes them.
fn bits(ctx: &Ctx, args: &[Reg]) -> Option<[u64; 4]> {
    if args.len() > 4 {
        return None;
    }
    let mut a = [0u64; 4];
    for (slot, &r) in a.iter_mut().zip(args) {
        *slot = ctx.get(r);
    }
    Some(a)
}

/// Runs `s` in place; `None`: not handled here (nothing was written).
pub fn narrow(ctx: &mut Ctx, s: StrFn, dst: Option<Reg>, args: &[Reg]) -> Option<()> {
    let op = Builtin::Str(s, false);
    if !handles(op, args.len()) {
        return None;
    }
    let r = run(ctx.image, op, bits(ctx, args)?)?;
    if let (StrFn::Len, Some(d)) = (s, dst) {
        ctx.set(d, r);
    }
    Some(())
}

/// `<integer>_TO_STRING` in place: the decimal digits, as
/// `automat_iec::convert` prints an integer, written without allocation.
pub fn int_text(ctx: &mut Ctx, from: E, args: &[Reg]) -> Option<()> {
    let op = Builtin::ToString(from, false);
    if !handles(op, args.len()) {
        return None;
    }
    run(ctx.image, op, bits(ctx, args)?).map(|_| ())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An image with `text` stored as a string at each offset of `at`.
    fn image(size: usize, at: &[(u32, &str)]) -> Vec<u8> {
        let mut img = vec![0xEE; size];
        for &(a, text) in at {
            strbuf::set_len(&mut img, a, text.len() as u32).unwrap();
            let s = a as usize + 2;
            img[s..s + text.len()].copy_from_slice(text.as_bytes());
        }
        img
    }

    fn text(img: &[u8], at: u32) -> String {
        let (s, n) = units(img, at).unwrap();
        String::from_utf8(img[s..s + n].to_vec()).unwrap()
    }

    /// Runs `s` through the engine's builtin entry with registers `regs`
    /// (arguments r0.., result in the last): (handled in place, result).
    fn run(img: &mut [u8], s: StrFn, regs: &[u64], has_dst: bool) -> (bool, Result<u64, String>) {
        let mut r: Vec<u64> = regs.to_vec();
        r.push(0);
        let args: Vec<Reg> = (0..regs.len() as Reg).collect();
        let dst = has_dst.then_some(regs.len() as Reg);
        let mut probe = img.to_vec();
        let mut rp = r.clone();
        let mut c = Ctx {
            image: &mut probe,
            regs: &mut rp,
            base: 0,
        };
        let inplace = narrow(&mut c, s, dst, &args).is_some();
        let mut c = Ctx {
            image: img,
            regs: &mut r,
            base: 0,
        };
        let res = crate::builtins::call(&mut c, Builtin::Str(s, false), dst, &args)
            .map(|()| c.get(regs.len() as Reg))
            .map_err(|e| e.1);
        (inplace, res)
    }

    #[test]
    fn assign_left_len_concat_in_place() {
        let mut img = image(64, &[(0, "hello"), (10, "world!")]);
        // LEFT(s0, 3) into 20 (room 80).
        assert!(run(&mut img, StrFn::Left, &[20, 80, 0, 3], false).0);
        assert_eq!(text(&img, 20), "hel");
        // LEFT with L beyond the length: the whole string.
        assert!(run(&mut img, StrFn::Left, &[20, 80, 0, 99], false).0);
        assert_eq!(text(&img, 20), "hello");
        // CONCAT into room 8: truncated to 8.
        assert!(run(&mut img, StrFn::Concat, &[30, 8, 0, 10], false).0);
        assert_eq!(text(&img, 30), "hellowor");
        assert_eq!(run(&mut img, StrFn::Len, &[30], true), (true, Ok(8)));
        // Assign onto itself shifted by one byte (overlapping memmove).
        assert!(run(&mut img, StrFn::Assign, &[1, 80, 0], false).0);
        assert_eq!(text(&img, 1), "hello");
    }

    #[test]
    fn integer_text_is_the_conversions() {
        let cases: [(E, u64); 8] = [
            (E::Int, 0),
            (E::Int, 20000),
            (E::Int, -32768i64 as u64),
            (E::Dint, -7i64 as u64),
            (E::Lint, i64::MIN as u64),
            (E::Udint, 4_294_967_295),
            (E::Ulint, u64::MAX),
            (E::Usint, 255),
        ];
        for (ty, bits) in cases {
            let mut img = vec![0u8; 40];
            let mut regs = [0, 80, bits];
            let mut c = Ctx {
                image: &mut img,
                regs: &mut regs,
                base: 0,
            };
            assert!(int_text(&mut c, ty, &[0, 1, 2]).is_some());
            let v = crate::builtins::to_value(bits, ty);
            let want = match automat_iec::convert(&v, E::String) {
                Ok(automat_iec::Value::Str(s)) => s,
                other => panic!("{other:?}"),
            };
            assert_eq!(text(&img, 0).into_bytes(), want, "{ty:?} {bits}");
        }
        // Room 3: truncated as an assignment truncates.
        let mut img = vec![0u8; 40];
        let mut regs = [0, 3, 12345];
        let mut c = Ctx {
            image: &mut img,
            regs: &mut regs,
            base: 0,
        };
        assert!(int_text(&mut c, E::Int, &[0, 1, 2]).is_some());
        // Not an integer: the general path.
        assert!(int_text(&mut c, E::Real, &[0, 1, 2]).is_none());
        assert_eq!(text(&img, 0), "123");
    }

    #[test]
    fn the_general_path_keeps_what_it_alone_does() {
        let mut img = image(40, &[(0, "abc"), (10, "de")]);
        // CONCAT(s, s2) into s itself: operands overlap the result.
        assert!(!run(&mut img, StrFn::Concat, &[0, 80, 0, 10], false).0);
        assert_eq!(text(&img, 0), "abcde");
        // A negative L: not here, and the general path faults.
        let (inplace, res) = run(&mut img, StrFn::Left, &[20, 80, 0, -1i64 as u64], false);
        assert!(!inplace);
        assert!(res.unwrap_err().contains("negative"));
        // A result that would leave the image: not here, and a fault.
        let (inplace, res) = run(&mut img, StrFn::Assign, &[36, 80, 0], false);
        assert!(!inplace);
        assert!(res.is_err());
    }
}
