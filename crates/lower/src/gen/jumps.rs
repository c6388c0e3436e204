//! Labels and jumps (`StmtKind::Label` / `StmtKind::Goto`, produced by the
//! IL desugaring): a label is an instruction index, a jump is an IR `Jump`.
//! Forward jumps are patched when their label is placed; the checker has
//! made sure every jump names a label of its body in the same or an
//! enclosing statement list, so the jump never enters a loop's body from
//! outside (loop state would be missing) — it may leave one.

use super::{Gen, Res};
use automat_base::Span;
use automat_ir::code::Inst;
use automat_syntax::ast::Ident;

impl Gen<'_, '_> {
    /// Places `label` here and resolves the jumps waiting for it.
    pub(super) fn place_label(&mut self, label: Ident) {
        // `here()` marks the position as a jump target, so no value kept
        // from the statement before is reused after it.
        let at = self.here();
        self.labels.insert(label.sym, at);
        let mut i = 0;
        while i < self.gotos.len() {
            match self.gotos.get(i) {
                Some(&(sym, j, _)) if sym == label.sym => {
                    self.patch(j, at);
                    self.gotos.swap_remove(i);
                }
                _ => i += 1,
            }
        }
    }

    /// A jump to `label`: backward at once, forward when it is placed.
    pub(super) fn goto(&mut self, label: Ident) {
        match self.labels.get(&label.sym) {
            Some(&at) => {
                self.emit(Inst::Jump { target: at });
            }
            None => {
                let j = self.jump_fwd();
                self.gotos.push((label.sym, j, label.span));
            }
        }
    }

    /// After the body: a jump whose label never came is an error (the
    /// checker reports it first; this keeps lowering from emitting a jump
    /// to nowhere if it did not).
    pub(super) fn unresolved_gotos(&mut self) -> Res<()> {
        let left: Vec<(automat_base::Symbol, Span)> =
            self.gotos.drain(..).map(|(s, _, sp)| (s, sp)).collect();
        let mut res = Ok(());
        for (sym, span) in left {
            let name = self.cx.interner.name(sym).to_string();
            res = Err(self.error(span, format!("jump to the unknown label `{name}`")));
        }
        res
    }
}
