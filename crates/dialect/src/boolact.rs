//! ISaGRAF boolean actions: a BOOL variable named in a step's associations
//! is written at the step's activation and deactivation only, not in every
//! call of the chart (the IEC rule the SFC desugaring generates):
//! - `v(S);` — v := TRUE at the activation; `v(R);` — v := FALSE there;
//! - `v(N);` / `v;` — v := TRUE at the activation, v := FALSE at the
//!   deactivation unless another N step of v in the chart is still active
//!   (v follows "any of its N steps is active");
//! - `/v;` — the negation: FALSE at the activation, TRUE at the
//!   deactivation unless another `/v` step is still active.
//!
//! Between those edges the variable is not written, so code or another
//! chart may change it. In one call, deactivations are written first, then
//! the activations that set TRUE, then those that set FALSE (an R wins, as
//! in IEC). A variable with any other qualifier in the chart (L, D, P, SD,
//! ...) keeps the IEC action control for all its associations there.
//!
//! The desugared chart (`automat_syntax::desugar::sfc`) drives a variable
//! `v` by a call of a hidden action control `__sfc_v<k>(__N := s.X OR ...,
//! __S := ..., __R := ..., __DT := ...)` right followed by
//! `v := __sfc_v<k>.Q;`. Both statements are replaced by `IF`s on the
//! steps' `__E` (entered by the last firing) and `__L` (left by it) inputs,
//! which stay TRUE for exactly the call after the firing — the call whose
//! actions see the new step states. Each generated statement has the span
//! of its association.
//!
//! The forms `v;` and `/v;`, which the IEC parser does not accept, are
//! rewritten in the text first ([`text`]), keeping every byte offset.

use crate::build;
use automat_base::{Code, Diagnostic, Interner, Span};
use automat_syntax::ast::{
    BinaryOp, Body, Expr, ExprKind, Ident, Item, SourceUnit, Stmt, StmtKind,
};

/// One association of the variable: the step instance and its span.
#[derive(Clone, Copy)]
struct Term {
    step: Ident,
    span: Span,
}

/// The associations of one variable, by what they write.
#[derive(Default)]
struct Drives {
    n: Vec<Term>,
    neg: Vec<Term>,
    s: Vec<Term>,
    r: Vec<Term>,
}

/// Rewrites the boolean actions of every chart of the user's units.
/// `negated` are the `/v;` associations: the offset of the name in the
/// rewritten text (where the parser's span starts) and the span of what
/// the user wrote; one that does not name a suitable variable is reported.
pub fn rewrite(
    units: &mut [SourceUnit],
    is_user: &dyn Fn(&SourceUnit) -> bool,
    negated: &[(u32, Span)],
    interner: &mut Interner,
    diags: &mut Vec<Diagnostic>,
) {
    let mut used = vec![false; negated.len()];
    for unit in units.iter_mut().filter(|u| is_user(u)) {
        for item in &mut unit.items {
            let Item::Pou(p) = item else { continue };
            let Body::St(stmts) = &mut p.body;
            fix(stmts, negated, &mut used, interner);
        }
    }
    for (i, &(_, written)) in negated.iter().enumerate() {
        if used.get(i).copied().unwrap_or(true) {
            continue;
        }
        diags.push(Diagnostic::error(
            Code::E126,
            written,
            "`/` (NOT the step activity) needs a BOOL variable whose associations in this chart \
             are N, S, R or `/` only"
                .to_string(),
        ));
    }
}

/// Replaces the generated pairs in `list`, and in the statements nested in
/// its `IF`s (the children rewrite may have gated the chart code).
fn fix(list: &mut Vec<Stmt>, negated: &[(u32, Span)], used: &mut [bool], interner: &mut Interner) {
    let mut i = 0;
    while i < list.len() {
        let found = match (list.get(i), list.get(i + 1)) {
            (Some(call), Some(set)) => pair(call, set, negated, used, interner),
            _ => None,
        };
        if let Some((target, drives)) = found {
            let new = generate(target, &drives, interner);
            let n = new.len();
            list.splice(i..i + 2, new);
            i += n;
            continue;
        }
        if let Some(s) = list.get_mut(i) {
            if let StmtKind::If {
                branches,
                else_body,
            } = &mut s.kind
            {
                for b in branches {
                    fix(&mut b.body, negated, used, interner);
                }
                if let Some(e) = else_body {
                    fix(e, negated, used, interner);
                }
            }
        }
        i += 1;
    }
}

/// `__sfc_v<k>(...); v := __sfc_v<k>.Q;` with only N, S and R inputs: the
/// variable and its associations.
fn pair(
    call: &Stmt,
    set: &Stmt,
    negated: &[(u32, Span)],
    used: &mut [bool],
    interner: &Interner,
) -> Option<(Ident, Drives)> {
    let StmtKind::Expr(e) = &call.kind else {
        return None;
    };
    let ExprKind::Call { callee, args } = &e.kind else {
        return None;
    };
    let ExprKind::Name(inst) = callee.kind else {
        return None;
    };
    if !interner.name(inst.sym).starts_with("__sfc_v") {
        return None;
    }
    let StmtKind::Assign { target, value } = &set.kind else {
        return None;
    };
    let (ExprKind::Name(v), ExprKind::Member { base, member }) = (&target.kind, &value.kind) else {
        return None;
    };
    let same = matches!(base.kind, ExprKind::Name(b) if b.sym == inst.sym);
    if !same || !interner.name(member.sym).eq_ignore_ascii_case("Q") {
        return None;
    }
    let mut d = Drives::default();
    let mut marks = Vec::new();
    for a in args {
        let name = interner.name(a.name?.sym);
        if name == "__DT" {
            continue;
        }
        let mut terms = Vec::new();
        steps_of(a.value.as_ref()?, interner, &mut terms)?;
        match name {
            "__N" => {
                for t in terms {
                    let at = negated
                        .iter()
                        .position(|&(o, w)| w.file == t.span.file && o == t.span.start);
                    match at {
                        Some(k) => {
                            marks.push(k);
                            d.neg.push(t);
                        }
                        None => d.n.push(t),
                    }
                }
            }
            "__S" => d.s.extend(terms),
            "__R" => d.r.extend(terms),
            // Another qualifier: the variable keeps the IEC action control.
            _ => return None,
        }
    }
    for k in marks {
        if let Some(u) = used.get_mut(k) {
            *u = true;
        }
    }
    Some((*v, d))
}

/// The step instances of `s1.X OR s2.X OR ...`; `None` for anything else.
fn steps_of(e: &Expr, interner: &Interner, out: &mut Vec<Term>) -> Option<()> {
    match &e.kind {
        ExprKind::Binary {
            op: BinaryOp::Or,
            lhs,
            rhs,
        } => {
            steps_of(lhs, interner, out)?;
            steps_of(rhs, interner, out)
        }
        ExprKind::Member { base, member } if interner.name(member.sym) == "X" => {
            let ExprKind::Name(step) = base.kind else {
                return None;
            };
            out.push(Term { step, span: e.span });
            Some(())
        }
        _ => None,
    }
}

/// The edge assignments of one variable (the order is the module's).
fn generate(v: Ident, d: &Drives, interner: &mut Interner) -> Vec<Stmt> {
    let mut out = Vec::new();
    let write = |value: bool, sp: Span| {
        build::assign(
            build::name(Ident {
                sym: v.sym,
                span: sp,
            }),
            build::bool_lit(value, sp),
            sp,
        )
    };
    // Deactivation: unless another step of the same kind is active (or the
    // step itself was re-entered by the same firing).
    for (group, value) in [(&d.n, false), (&d.neg, true)] {
        for t in group {
            let sp = t.span;
            let left = build::member(interner, t.step, "__L", sp);
            let any = group
                .iter()
                .map(|o| build::member(interner, o.step, "X", sp))
                .reduce(|a, b| build::binary(BinaryOp::Or, a, b, sp));
            let cond = match any {
                Some(any) => build::binary(BinaryOp::And, left, build::not(any, sp), sp),
                None => left,
            };
            out.push(build::if_then(cond, vec![write(value, sp)], sp));
        }
    }
    // Activation: TRUE first, then FALSE (reset wins).
    let on = d.n.iter().chain(&d.s).map(|t| (t, true));
    let off = d.neg.iter().chain(&d.r).map(|t| (t, false));
    for (t, value) in on.chain(off) {
        let sp = t.span;
        let entered = build::member(interner, t.step, "__E", sp);
        out.push(build::if_then(entered, vec![write(value, sp)], sp));
    }
    out
}

/// `v;` and `/v;` in a step's associations, which the IEC parser does not
/// accept, become `v(N);` in the text, at the same byte offsets otherwise:
/// the three bytes more come from the blanks around the association (a
/// form without three of them is left to the parser's error). Returns the
/// new text (`None`: nothing rewritten) and, for the negated ones, the new
/// offset of the name and the (start, end) of the `/v` written.
pub fn text(src: &str) -> (Option<String>, Vec<(u32, u32, u32)>) {
    let b = src.as_bytes();
    let mut out = b.to_vec();
    let mut neg = Vec::new();
    let mut in_step = false;
    // The end of the last rewritten region: its blanks are spent.
    let mut floor = 0;
    let mut i = 0;
    while i < b.len() {
        match (b[i], b.get(i + 1).copied()) {
            (b'(', Some(b'*')) => i = skip_past(b, i + 2, b"*)"),
            (b'/', Some(b'*')) => i = skip_past(b, i + 2, b"*/"),
            (b'/', Some(b'/')) => i = skip_past(b, i + 2, b"\n"),
            (b'{', _) => i = skip_past(b, i + 1, b"}"),
            (q @ (b'\'' | b'"'), _) => i = skip_past(b, i + 1, &[q]),
            (b'/', _) if in_step => {
                let name = skip_blanks(b, i + 1);
                match bare(b, &mut out, floor, i, name) {
                    Some((at, end)) => {
                        let word = word_end(b, name);
                        if let (Ok(s), Ok(e)) = (u32::try_from(i), u32::try_from(word)) {
                            neg.push((at, s, e));
                        }
                        floor = end;
                        i = end;
                    }
                    None => i += 1,
                }
            }
            (c, _) if is_word_start(c) && (i == 0 || !is_word_byte(b[i - 1])) => {
                let end = word_end(b, i);
                let word = &b[i..end];
                if word.eq_ignore_ascii_case(b"STEP") || word.eq_ignore_ascii_case(b"INITIAL_STEP")
                {
                    in_step = true;
                    i = end;
                } else if word.eq_ignore_ascii_case(b"END_STEP") {
                    in_step = false;
                    i = end;
                } else if in_step {
                    i = match bare(b, &mut out, floor, i, i) {
                        Some((_, e)) => {
                            floor = e;
                            e
                        }
                        None => end,
                    };
                } else {
                    i = end;
                }
            }
            _ => i += 1,
        }
    }
    if out == b {
        return (None, neg);
    }
    // Only ASCII bytes were replaced by ASCII bytes: still UTF-8.
    match String::from_utf8(out) {
        Ok(s) => (Some(s), neg),
        Err(_) => (None, Vec::new()),
    }
}

/// At `name` (after the `/` at `start`, or `start == name`): `name ;`
/// rewritten in `out` as `name(N);` within the region it spans plus the
/// blanks around it (none before `floor`, which an earlier rewrite spent).
/// Returns the new offset of the name and the end of the region.
fn bare(b: &[u8], out: &mut [u8], floor: usize, start: usize, name: usize) -> Option<(u32, usize)> {
    if !b.get(name).copied().is_some_and(is_word_start) {
        return None;
    }
    let name_end = word_end(b, name);
    let semi = skip_blanks(b, name_end);
    if b.get(semi) != Some(&b';') {
        return None;
    }
    // Blanks before (spaces and tabs of the same line: a line break could
    // pull the text into a `//` comment) and after.
    let mut from = start;
    while from > floor && matches!(b[from - 1], b' ' | b'\t') {
        from -= 1;
    }
    let mut to = semi + 1;
    while to < b.len() && b[to].is_ascii_whitespace() {
        to += 1;
    }
    let len = name_end - name;
    let need = len + 4; // name(N);
    if to - from < need {
        return None;
    }
    let at = name.min(to - need).max(from);
    let word = b.get(name..name_end)?.to_vec();
    for x in out.get_mut(from..to)? {
        *x = b' ';
    }
    let mut put = word;
    put.extend_from_slice(b"(N);");
    out.get_mut(at..at + need)?.copy_from_slice(&put);
    // Keep the line breaks of the blanks that were not needed, so line
    // numbers of later text do not matter for the lexer.
    for k in (at + need)..to {
        if b[k] == b'\n' {
            out[k] = b'\n';
        }
    }
    Some((u32::try_from(at).ok()?, to))
}

fn skip_blanks(b: &[u8], mut i: usize) -> usize {
    while i < b.len() && matches!(b[i], b' ' | b'\t') {
        i += 1;
    }
    i
}

fn skip_past(b: &[u8], from: usize, end: &[u8]) -> usize {
    let mut i = from;
    while i < b.len() {
        if b[i..].starts_with(end) {
            return i + end.len();
        }
        i += 1;
    }
    b.len()
}

fn is_word_start(c: u8) -> bool {
    c.is_ascii_alphabetic() || c == b'_'
}

fn is_word_byte(c: u8) -> bool {
    c.is_ascii_alphanumeric() || c == b'_'
}

fn word_end(b: &[u8], mut i: usize) -> usize {
    while i < b.len() && is_word_byte(b[i]) {
        i += 1;
    }
    i
}
