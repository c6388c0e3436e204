//! Transitions written without a condition. The textual SFC has no such
//! form (the parser reports a missing condition and the transition never
//! fires); the vendors give it a meaning:
//! - ISaGRAF: "no expression = TRUE" — the transition fires as soon as it
//!   is enabled (and no transition of higher precedence sharing a preceding
//!   step fires);
//! - PL7: "a transition without a program is always FALSE" — it stays as
//!   the parser left it.
//!
//! In both the parser's error is void. For ISaGRAF the fire flag
//! `__sfc_t<i>` of the desugared chart (the representation `desugar::sfc`
//! documents: one flag per transition, cleared then set in precedence order)
//! is set right after it is cleared.

use crate::build;
use automat_base::{Interner, Span};
use automat_syntax::ast::sfc::{Chart, Condition};
use automat_syntax::ast::{
    BinaryOp, Body, ExprKind, Item, Lang, LitKind, SourceUnit, Stmt, StmtKind,
};
use automat_syntax::lexer::{Kw, Tok};

/// The transitions of a chart written with no condition: (index, span of
/// the text from the end of the `TO` list to the end of the transition).
pub fn missing_conditions(chart: &Chart, text: &str) -> Vec<(usize, Span)> {
    let mut out = Vec::new();
    for (i, t) in chart.transitions.iter().enumerate() {
        if !matches!(t.cond, Condition::Missing) {
            continue;
        }
        let Some(last) = t.to.last() else { continue };
        // No text (spans outside the file): treat as written, so no error
        // is voided.
        let Some(rest) = text.get(last.span.end as usize..t.span.end as usize) else {
            continue;
        };
        if is_blank(rest, t.span.file) {
            out.push((i, Span::new(t.span.file, last.span.end, t.span.end)));
        }
    }
    out
}

/// Whether the text between a transition's `TO` list and its end holds
/// nothing but the `)` closing the list and `END_TRANSITION`: no condition
/// was written. Anything else (a `:=` or `:`, even with a wrong condition)
/// keeps the parser's error. Lexed, so comments do not count, whatever
/// they contain (`(* T1: no condition *)`).
fn is_blank(rest: &str, file: automat_base::FileId) -> bool {
    // A scratch interner: the identifiers of this slice are not the
    // project's business, and the lexer's diagnostics were reported when
    // the whole file was lexed.
    let mut scratch = Interner::new();
    let mut diags = Vec::new();
    let lexed = automat_syntax::lexer::lex(file, rest, &mut scratch, &mut diags);
    let mut ends = 0;
    for t in &lexed.toks {
        match t.tok {
            Tok::Kw(Kw::EndTransition) => ends += 1,
            Tok::RParen | Tok::Eof => {}
            _ => return false,
        }
    }
    ends == 1 && diags.is_empty()
}

/// ISaGRAF: makes every transition without a condition TRUE; returns the
/// spans whose "missing condition" error is void.
pub fn isagraf_true(
    units: &mut [SourceUnit],
    is_user: &dyn Fn(&SourceUnit) -> bool,
    texts: &dyn Fn(&SourceUnit) -> String,
    interner: &mut Interner,
) -> Vec<Span> {
    let mut void = Vec::new();
    for unit in units.iter_mut().filter(|u| is_user(u)) {
        let text = texts(unit);
        for item in &mut unit.items {
            let Item::Pou(p) = item else { continue };
            let Lang::Sfc(chart) = &p.lang else { continue };
            let chart = (**chart).clone();
            let missing = missing_conditions(&chart, &text);
            if missing.is_empty() {
                continue;
            }
            let Body::St(stmts) = &mut p.body;
            for (i, span) in missing {
                void.push(span);
                let set = fire(&chart, i, interner);
                let flag = format!("__sfc_t{i}");
                let at = stmts.iter().position(|s| clears(s, &flag, interner));
                if let (Some(at), Some(set)) = (at, set) {
                    stmts.insert(at + 1, set);
                }
            }
        }
    }
    void
}

/// `__sfc_t<i> := FALSE;` at the top level of the chart code.
fn clears(s: &Stmt, flag: &str, interner: &Interner) -> bool {
    let StmtKind::Assign { target, value } = &s.kind else {
        return false;
    };
    let is_flag = matches!(target.kind, ExprKind::Name(id) if interner.name(id.sym).eq_ignore_ascii_case(flag));
    let is_false = matches!(&value.kind, ExprKind::Literal(l) if l.kind == LitKind::Bool(false));
    is_flag && is_false
}

/// `IF <preceding steps active> AND NOT <flags of higher precedence
/// sharing one> THEN __sfc_t<i> := TRUE; END_IF`
fn fire(chart: &Chart, i: usize, interner: &mut Interner) -> Option<Stmt> {
    let t = chart.transitions.get(i)?;
    let sp = t.span;
    let key = |k: usize| {
        let p = chart.transitions.get(k).and_then(|t| t.priority);
        (p.is_none(), p.unwrap_or(0), k)
    };
    let mut terms: Vec<_> = t
        .from
        .iter()
        .map(|s| build::member(interner, *s, "X", sp))
        .collect();
    for (j, other) in chart.transitions.iter().enumerate() {
        let shares = other
            .from
            .iter()
            .any(|a| t.from.iter().any(|b| a.sym == b.sym));
        if j != i && shares && key(j) < key(i) {
            let f = build::ident(interner, &format!("__sfc_t{j}"), sp);
            terms.push(build::not(build::name(f), sp));
        }
    }
    let mut it = terms.into_iter();
    let first = it.next()?;
    let enabled = it.fold(first, |a, b| build::binary(BinaryOp::And, a, b, sp));
    let flag = build::ident(interner, &format!("__sfc_t{i}"), sp);
    Some(build::if_then(
        enabled,
        vec![build::assign(
            build::name(flag),
            build::bool_lit(true, sp),
            sp,
        )],
        sp,
    ))
}
