//! `__ISVALIDREF` the reference desugaring left alone (E163).
//!
//! `automat_syntax`'s `desugar/reference.rs` turns `__ISVALIDREF(r)` of one
//! `REFERENCE TO` variable into `r <> NULL`; any call of it that reaches
//! the checker is therefore a misuse, and the message says which one
//! instead of "unknown function".

use super::Checker;
use crate::names::expr_text;
use crate::ops::Ty;
use crate::types::TypeKind;
use automat_base::{Code, Diagnostic, Span};
use automat_syntax::ast::Arg;

impl Checker<'_> {
    pub(crate) fn isvalidref_misuse(&mut self, span: Span, args: &[Arg]) {
        if !self.model.codesys {
            self.args_unchecked(args);
            self.diag(|_| {
                Diagnostic::error(
                    Code::E163,
                    span,
                    "`__ISVALIDREF` tests a CODESYS reference (`REFERENCE TO`), which exists only in the CODESYS dialect",
                )
                .with_note("check with `--lib codesys` (or `libraries = [\"codesys\"]` in automat.toml); in IEC 61131-3 a `REF_TO` is tested with `r <> NULL`")
            });
            return;
        }
        let one = match args {
            [a] if a.name.is_none() => a.value.as_ref(),
            _ => None,
        };
        let Some(v) = one else {
            self.args_unchecked(args);
            let msg = match args.len() {
                1 => "`__ISVALIDREF` takes its reference without a name: `__ISVALIDREF(r)`"
                    .to_string(),
                n => format!(
                    "`__ISVALIDREF` takes one reference, `__ISVALIDREF(r)`, not {n} arguments"
                ),
            };
            self.err(Code::E163, span, |_| msg);
            return;
        };
        let t = self.expr(v, None);
        let Ty::Of(ty) = t.ty else {
            return;
        };
        let pointer = matches!(self.model.types.get(ty), TypeKind::Ref(_));
        self.diag(|c| {
            let text = expr_text(c.interner, v);
            let d = Diagnostic::error(
                Code::E163,
                v.span,
                format!(
                    "`{text}` is of type {}, not a reference: `__ISVALIDREF` takes a variable declared `REFERENCE TO T`",
                    c.type_name(ty)
                ),
            );
            if pointer {
                d.with_note(format!("a pointer or `REF_TO` is tested with `{text} <> 0` or `{text} <> NULL`"))
            } else {
                d
            }
        });
    }
}
