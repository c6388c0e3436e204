//! CODESYS V3 `__NEW` and `__DELETE` (`--lib codesys`) on the heap of the
//! dialect's library (`lib/codesys.st`: a hidden global array and its
//! allocator in ST), so that no engine knows of them.
//!
//! The parser wrote the type of `__NEW(T [, n])` as a hidden global `t` of
//! type T (`automat_syntax` `parser/heap.rs`); here the call becomes
//! `__HEAP_NEW(SIZEOF(t), n, ADR(t))` (n = 1 without a count): the address
//! of n copies of `t`, so a function block or structure starts with its
//! initial values as in CODESYS, or 0 when the heap is full. Its DWORD is
//! assigned to the `POINTER TO T` as any address is in the dialect.
//! `__DELETE(p);` becomes `p := __HEAP_DELETE(p);`: the block is freed and
//! `p` set to 0. A program that calls neither keeps no heap: the library's
//! items are dropped.

use crate::walk::{self, Visitor};
use automat_base::{Code, Diagnostic, FileId, Interner, Span, Symbol};
use automat_syntax::ast::{
    Arg, ArgDir, Body, Expr, ExprKind, Ident, Item, LitKind, Literal, SourceUnit, Stmt, StmtKind,
};

/// Rewrites the calls in the user's units; drops the library's items
/// (`library`: its unit) when there is none.
pub fn rewrite(
    units: &mut [SourceUnit],
    is_user: &dyn Fn(&SourceUnit) -> bool,
    library: Option<FileId>,
    interner: &mut Interner,
    diags: &mut Vec<Diagnostic>,
) {
    let mut h = Heap {
        new: interner.intern("__NEW"),
        delete: interner.intern("__DELETE"),
        heap_new: interner.intern("__HEAP_NEW"),
        heap_delete: interner.intern("__HEAP_DELETE"),
        sizeof: interner.intern("SIZEOF"),
        adr: interner.intern("ADR"),
        interner,
        used: false,
        diags,
    };
    for unit in units.iter_mut().filter(|u| is_user(u)) {
        for item in &mut unit.items {
            match item {
                Item::Pou(p) => {
                    let Body::St(stmts) = &mut p.body;
                    walk::stmts(stmts, &mut h);
                }
                Item::Class(c) => {
                    walk::stmts(&mut c.body, &mut h);
                    for m in &mut c.methods {
                        walk::stmts(&mut m.body, &mut h);
                    }
                    for prop in &mut c.properties {
                        for acc in [&mut prop.get, &mut prop.set].into_iter().flatten() {
                            walk::stmts(&mut acc.body, &mut h);
                        }
                    }
                }
                _ => {}
            }
        }
    }
    if !h.used {
        for unit in units.iter_mut().filter(|u| Some(u.file) == library) {
            unit.items.clear();
        }
    }
}

struct Heap<'a> {
    new: Symbol,
    delete: Symbol,
    heap_new: Symbol,
    heap_delete: Symbol,
    sizeof: Symbol,
    adr: Symbol,
    interner: &'a Interner,
    used: bool,
    diags: &'a mut Vec<Diagnostic>,
}

fn callee_is(e: &Expr, sym: Symbol) -> bool {
    matches!(&e.kind, ExprKind::Call { callee, .. }
        if matches!(&callee.kind, ExprKind::Name(id) if id.sym == sym))
}

fn name(sym: Symbol, span: Span) -> Expr {
    Expr {
        kind: ExprKind::Name(Ident { sym, span }),
        span,
    }
}

fn arg(value: Expr) -> Arg {
    Arg {
        name: None,
        dir: ArgDir::In,
        span: value.span,
        value: Some(value),
    }
}

fn call(sym: Symbol, span: Span, args: Vec<Expr>) -> Expr {
    Expr {
        kind: ExprKind::Call {
            callee: Box::new(name(sym, span)),
            args: args.into_iter().map(arg).collect(),
        },
        span,
    }
}

impl Heap<'_> {
    fn error(&mut self, span: Span, msg: &str) {
        self.diags
            .push(Diagnostic::error(Code::E162, span, msg.to_string()));
    }

    /// `__NEW(t [, n])` → `__HEAP_NEW(SIZEOF(t), n, ADR(t))`.
    fn new_call(&mut self, e: &mut Expr) {
        let span = e.span;
        let ExprKind::Call { args, .. } = &mut e.kind else {
            return;
        };
        let positional = args.iter().all(|a| a.name.is_none() && a.value.is_some());
        let template = match args.first().and_then(|a| a.value.as_ref()) {
            Some(Expr {
                kind: ExprKind::Name(id),
                ..
            }) if self.interner.name(id.sym).starts_with("__NEW_") => Some(*id),
            _ => None,
        };
        let (Some(t), true, 1..=2) = (template, positional, args.len()) else {
            self.error(
                span,
                "`__NEW` takes a type and an optional count: `__NEW(T)` or `__NEW(T, n)`",
            );
            e.kind = ExprKind::Error;
            return;
        };
        let count = args
            .get_mut(1)
            .and_then(|a| a.value.take())
            .unwrap_or(Expr {
                kind: ExprKind::Literal(Box::new(Literal {
                    kind: LitKind::Int(1),
                    ty: None,
                })),
                span,
            });
        let size = call(self.sizeof, t.span, vec![name(t.sym, t.span)]);
        let init = call(self.adr, t.span, vec![name(t.sym, t.span)]);
        *e = call(self.heap_new, span, vec![size, count, init]);
        self.used = true;
    }
}

impl Visitor for Heap<'_> {
    fn stmt(&mut self, s: &mut Stmt) {
        let StmtKind::Expr(e) = &mut s.kind else {
            return;
        };
        if !callee_is(e, self.delete) {
            return;
        }
        let span = e.span;
        let ExprKind::Call { args, .. } = &mut e.kind else {
            return;
        };
        let p = match args.as_mut_slice() {
            [a] if a.name.is_none() => a.value.take(),
            _ => None,
        };
        let Some(p) = p else {
            self.error(
                span,
                "`__DELETE` takes the one pointer to free: `__DELETE(p);`",
            );
            e.kind = ExprKind::Error;
            return;
        };
        self.used = true;
        let value = call(self.heap_delete, span, vec![p.clone()]);
        s.kind = StmtKind::Assign { target: p, value };
    }

    fn expr(&mut self, e: &mut Expr) {
        if callee_is(e, self.new) {
            self.new_call(e);
        } else if callee_is(e, self.delete) {
            self.error(
                e.span,
                "`__DELETE(p)` is a statement of its own: it frees the memory and sets `p` to 0",
            );
            e.kind = ExprKind::Error;
        }
    }
}
