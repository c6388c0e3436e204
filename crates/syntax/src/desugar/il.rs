//! IL → ST. The current result (CR) is carried as an ST expression tree
//! that grows with each operator (`LD a` / `ADD b` / `MUL c` is
//! `(a + b) * c`) and is emitted where an instruction consumes it:
//!
//! | IL | ST |
//! |---|---|
//! | `ST x` / `STN x` | `x := cr;` / `x := NOT cr;` — the CR is then read back from `x` |
//! | `S x` / `R x` | `IF cr THEN x := TRUE; END_IF` / `... FALSE ...` |
//! | `AND( LD b` / `OR c` / `)` | `cr AND (b OR c)`; short form `AND( b` |
//! | `F a, b` / `F(P := a)` | `F(cr, a, b)` / `F(P := a)` (formal: CR not passed) |
//! | `CAL fb(..)` / `CALC` / `CALCN` | `fb(..);` / `IF cr THEN fb(..); END_IF` / `IF NOT cr ...` |
//! | `PT t1` (FB input operators) | `t1(PT := cr);` |
//! | `JMP L` / `JMPC L` / `JMPCN L` | `GOTO L` / `IF cr THEN GOTO L; END_IF` / `IF NOT cr ...` |
//! | `RET` / `RETC` / `RETCN` | `RETURN` / `IF cr THEN RETURN; END_IF` / ... |
//! | `L:` | `Label(L)`; a CR used right after it comes from `__CRL` (below) |
//!
//! Every generated node's span is the IL text it came from (an operator's
//! node spans its line), so type errors of the CR come out of the checker
//! at the IL line that caused them (`LD 5` / `AND TRUE`: at the `AND`).
//!
//! Evaluate once: a tree is emitted only once. After `ST x` a CR that is a
//! computed tree is read back from `x` (same value; its type is `x`'s,
//! which differs from the CR's only by an implicit widening: after
//! `ADD 1` / `ST dint_var` the CR is DINT); a literal or plain variable
//! stays the CR as it is. A conditional instruction (S, R,
//! JMPC, CALC, RETC, ...) whose CR is still needed afterwards first stores
//! it in the hidden BOOL variable `__CR` (declared in VAR_TEMP), since the
//! instruction may change what the tree reads (`LD b` / `R b` / `S c`).
//!
//! The CR across a label: when the instruction after `L:` uses the CR, every
//! way into `L` leaves it in the hidden BOOL `__CRL`: the line above falls
//! through with `__CRL := cr`, `JMPC L` jumps with `__CRL := TRUE` (its
//! condition held), `JMPCN L` with FALSE, `JMP L` with its CR. So a Boolean
//! CR continues across a label as in ladder-like IL; a way in without a CR
//! is E101, and a non-BOOL CR a type error at the line that brings it.
//!
//! Limits: `R x` / `S x` on a variable of a named non-elementary type are
//! the function block input operators (`x(R := cr)`), so an alias of BOOL
//! declared as a TYPE cannot be set with S/R (use `ST`); `LD` is never the
//! CTD input operator. A function's result is what `ST <function name>` stored.
//!
//! Diagnostics: E100 (no current result), E101 (undefined after a label),
//! E108 (statement-like instruction inside parentheses), E005 (a CR built
//! from more than `MAX_DEPTH` instructions in a row: the tree depth every
//! later stage may assume is bounded).

use crate::ast::il::{IlBody, Instr, InstrKind, Op, When};
use crate::ast::{
    Arg, ArgDir, BinaryOp, CondBlock, Expr, ExprKind, Ident, LitKind, Literal, Stmt, StmtKind,
    TypeSpec, UnaryOp, VarDecl,
};
use crate::parser::MAX_DEPTH;
use automat_base::{Code, Diagnostic, Interner, Span, Symbol};

/// The name of the hidden BOOL variable that keeps a condition for the
/// instructions after a conditional one.
pub const CR_VAR: &str = "__CR";

/// The hidden BOOL variable that carries the CR into a label whose next
/// instruction uses it.
pub const LABEL_CR_VAR: &str = "__CRL";

/// What desugaring an instruction list gives.
pub struct IlOut {
    /// The ST statements (with `Label`/`Goto`) that execute the list.
    pub stmts: Vec<Stmt>,
    /// The current result at the end of the list, when it is defined (an
    /// SFC transition condition written in IL is this value).
    pub result: Option<Expr>,
}

/// Desugars one IL list. Hidden variables it needs are added to `hidden`
/// (once, even when several lists of one POU share it); the caller puts
/// them in a VAR_TEMP block of the POU. `want_result`: the final CR is
/// used by the caller (SFC transitions), so it must survive the last
/// instruction.
pub fn desugar(
    body: &IlBody,
    want_result: bool,
    hidden: &mut Vec<VarDecl>,
    interner: &mut Interner,
    diags: &mut Vec<Diagnostic>,
) -> IlOut {
    // Labels whose instruction reads the CR (the ways into them carry it).
    // (A label alone on its line labels an empty instruction: look past it.)
    let instrs = &body.instrs;
    let carried = (0..instrs.len())
        .filter_map(|k| {
            let l = instrs[k].label?;
            let next = instrs[k..].iter().enumerate().find(|(j, i)| {
                !matches!(i.kind, InstrKind::Nothing) || (*j > 0 && i.label.is_some())
            });
            match next {
                Some((j, i)) if (j == 0 || i.label.is_none()) && reads_cr(i) => Some(l.sym),
                _ => None,
            }
        })
        .collect();
    let mut d = Ds {
        interner,
        diags,
        hidden,
        carried,
    };
    let mut stmts = Vec::new();
    let cr = d.list(
        &body.instrs,
        Cr::None(Why::Start),
        false,
        want_result,
        &mut stmts,
    );
    let result = match cr {
        Cr::Val(e, _) => Some(e),
        _ => None,
    };
    IlOut { stmts, result }
}

/// Why there is no current result.
#[derive(Clone, Copy)]
enum Why {
    Start,
    GroupStart,
    Jump,
    Ret,
    Call,
}

/// The current result.
enum Cr {
    /// An expression and the depth of its tree.
    Val(Expr, u32),
    None(Why),
    /// Undefined after the label (its span) on the way in from above.
    AfterLabel(Ident, Why),
    /// Unknown after an error (reported): uses stay silent.
    Poison,
}

struct Ds<'a> {
    interner: &'a mut Interner,
    diags: &'a mut Vec<Diagnostic>,
    hidden: &'a mut Vec<VarDecl>,
    /// Labels whose next instruction reads the CR.
    carried: Vec<Symbol>,
}

fn mk(kind: ExprKind, span: Span) -> Expr {
    Expr { kind, span }
}

fn stmt(kind: StmtKind, span: Span) -> Stmt {
    Stmt { kind, span }
}

fn not(e: Expr, span: Span) -> Expr {
    mk(
        ExprKind::Unary {
            op: UnaryOp::Not,
            operand: Box::new(e),
        },
        span,
    )
}

fn bool_lit(v: bool, span: Span) -> Expr {
    mk(
        ExprKind::Literal(Box::new(Literal {
            kind: LitKind::Bool(v),
            ty: None,
        })),
        span,
    )
}

fn binop(op: Op) -> BinaryOp {
    match op {
        Op::And | Op::Andn => BinaryOp::And,
        Op::Or | Op::Orn => BinaryOp::Or,
        Op::Xor | Op::Xorn => BinaryOp::Xor,
        Op::Add => BinaryOp::Add,
        Op::Sub => BinaryOp::Sub,
        Op::Mul => BinaryOp::Mul,
        Op::Div => BinaryOp::Div,
        Op::Mod => BinaryOp::Mod,
        Op::Gt => BinaryOp::Gt,
        Op::Ge => BinaryOp::Ge,
        Op::Eq => BinaryOp::Eq,
        Op::Ne => BinaryOp::Ne,
        Op::Le => BinaryOp::Le,
        // (Only binary operators reach here.)
        _ => BinaryOp::Lt,
    }
}

/// Whether `instr` (the one after a conditional instruction) reads the CR.
fn uses_cr(instr: Option<&Instr>, want_result: bool) -> bool {
    let Some(i) = instr else {
        return want_result;
    };
    if i.label.is_some() {
        return false;
    }
    reads_cr(i)
}

/// Whether `i` reads the CR when it executes.
fn reads_cr(i: &Instr) -> bool {
    match &i.kind {
        InstrKind::Simple { op, .. } => !matches!(op, Op::Ld | Op::Ldn),
        InstrKind::Group { .. } | InstrKind::FbInput { .. } => true,
        InstrKind::Call { formal, .. } => !formal,
        InstrKind::Cal { when, .. }
        | InstrKind::Jump { when, .. }
        | InstrKind::Ret { when, .. } => *when != When::Always,
        InstrKind::Nothing | InstrKind::Error => false,
    }
}

/// The span of an instruction's operator, for messages about it.
fn op_span(i: &Instr) -> Span {
    match &i.kind {
        InstrKind::Simple { op_span, .. }
        | InstrKind::Group { op_span, .. }
        | InstrKind::Cal { op_span, .. }
        | InstrKind::Jump { op_span, .. }
        | InstrKind::Ret { op_span, .. } => *op_span,
        InstrKind::Call { name, .. } => name.span,
        InstrKind::FbInput { input, .. } => input.span,
        InstrKind::Nothing | InstrKind::Error => i.span,
    }
}

/// The operator's name, for messages.
fn op_name(i: &Instr, interner: &Interner) -> String {
    let cond = |w: &When, base: &str| match w {
        When::Always => base.to_string(),
        When::IfTrue => format!("{base}C"),
        When::IfFalse => format!("{base}CN"),
    };
    match &i.kind {
        InstrKind::Simple { op, .. } | InstrKind::Group { op, .. } => op.name().to_string(),
        InstrKind::Cal { when, .. } => cond(when, "CAL"),
        InstrKind::Jump { when, .. } => cond(when, "JMP"),
        InstrKind::Ret { when, .. } => cond(when, "RET"),
        InstrKind::Call { name, .. } => interner.name(name.sym).to_string(),
        InstrKind::FbInput { input, .. } => interner.name(input.sym).to_string(),
        InstrKind::Nothing | InstrKind::Error => "the instruction".into(),
    }
}

impl Ds<'_> {
    /// Desugars `instrs` starting from `cr`; returns the CR at the end.
    /// `nested`: inside a parenthesised group (no statements allowed).
    fn list(
        &mut self,
        instrs: &[Instr],
        mut cr: Cr,
        nested: bool,
        want_result: bool,
        out: &mut Vec<Stmt>,
    ) -> Cr {
        for (k, i) in instrs.iter().enumerate() {
            if let Some(l) = i.label {
                cr = self.enter_label(l, cr, out);
            }
            let next_uses = uses_cr(instrs.get(k + 1), want_result || nested);
            if nested && !self.allowed_in_group(i) {
                cr = Cr::Poison;
                continue;
            }
            cr = self.instr(i, cr, next_uses, out);
        }
        cr
    }

    /// E108 for instructions that do more than compute a value.
    fn allowed_in_group(&mut self, i: &Instr) -> bool {
        let ok = match &i.kind {
            InstrKind::Simple { op, .. } => !matches!(op, Op::St | Op::Stn | Op::S | Op::R),
            InstrKind::Group { .. }
            | InstrKind::Call { .. }
            | InstrKind::Nothing
            | InstrKind::Error => true,
            _ => false,
        };
        if !ok {
            let name = op_name(i, self.interner);
            self.diags.push(Diagnostic::error(
                Code::E108,
                op_span(i),
                format!("`{name}` is not allowed inside a parenthesised group, which only computes a value"),
            ));
        }
        ok
    }

    fn instr(&mut self, i: &Instr, cr: Cr, next_uses: bool, out: &mut Vec<Stmt>) -> Cr {
        let span = i.span;
        match &i.kind {
            InstrKind::Nothing => cr,
            InstrKind::Error => Cr::Poison,
            InstrKind::Simple { op, operand, .. } => {
                let Some(x) = operand.clone() else {
                    // NOT (no operand).
                    return match self.take(cr, i) {
                        Some((e, d)) => self.grow(not(e, span), d + 1, span),
                        None => Cr::Poison,
                    };
                };
                match op {
                    Op::Ld => Cr::Val(x, 1),
                    Op::Ldn => Cr::Val(not(x, span), 2),
                    Op::St | Op::Stn => {
                        let Some((e, _)) = self.take(cr, i) else {
                            return Cr::Poison;
                        };
                        // A literal or a plain variable is still the CR
                        // after the store (storing it into the same variable
                        // changes nothing), and keeps its own type; anything
                        // else is read back so that it is evaluated once.
                        let keep = match e.kind {
                            ExprKind::Literal(_) | ExprKind::Name(_) => Some(e.clone()),
                            _ => None,
                        };
                        let value = if *op == Op::Stn { not(e, span) } else { e };
                        out.push(stmt(
                            StmtKind::Assign {
                                target: x.clone(),
                                value,
                            },
                            span,
                        ));
                        match (keep, *op) {
                            (Some(e), _) => Cr::Val(e, 1),
                            (None, Op::Stn) => Cr::Val(not(x, span), 2),
                            (None, _) => Cr::Val(x, 1),
                        }
                    }
                    Op::S | Op::R => {
                        let Some((c, d)) = self.take(cr, i) else {
                            return Cr::Poison;
                        };
                        let (c, d) = self.freeze(c, d, next_uses, out);
                        let set = stmt(
                            StmtKind::Assign {
                                target: x,
                                value: bool_lit(*op == Op::S, span),
                            },
                            span,
                        );
                        out.push(if_then(c.clone(), false, vec![set], span));
                        Cr::Val(c, d)
                    }
                    _ => {
                        let Some((a, d)) = self.take(cr, i) else {
                            return Cr::Poison;
                        };
                        let b = if op.negated() {
                            not(x.clone(), x.span)
                        } else {
                            x
                        };
                        self.combine(*op, a, d, b, span)
                    }
                }
            }
            InstrKind::Group {
                op, first, body, ..
            } => {
                // (The group is desugared even without a CR, to report
                // what is wrong inside it too.)
                let outer = self.take(cr, i);
                let start = match first {
                    Some(f) => Cr::Val(f.clone(), 1),
                    None => Cr::None(Why::GroupStart),
                };
                let inner = self.list(body, start, true, true, out);
                let b = match inner {
                    Cr::Val(e, _) => e,
                    Cr::None(_) if body.is_empty() && first.is_none() => {
                        self.diags.push(Diagnostic::error(
                            Code::E102,
                            span,
                            format!(
                                "missing operand: the group `{}( )` computes nothing",
                                op.name()
                            ),
                        ));
                        return Cr::Poison;
                    }
                    _ => return Cr::Poison,
                };
                let Some((a, d)) = outer else {
                    return Cr::Poison;
                };
                let b = mk(ExprKind::Paren(Box::new(b)), span);
                let b = if op.negated() { not(b, span) } else { b };
                self.combine(*op, a, d, b, span)
            }
            InstrKind::Call { name, args, formal } => {
                let callee = Box::new(mk(ExprKind::Name(*name), name.span));
                if *formal {
                    return Cr::Val(
                        mk(
                            ExprKind::Call {
                                callee,
                                args: args.clone(),
                            },
                            span,
                        ),
                        1,
                    );
                }
                let Some((a, d)) = self.take(cr, i) else {
                    return Cr::Poison;
                };
                let mut all = Vec::with_capacity(args.len() + 1);
                all.push(Arg {
                    name: None,
                    dir: ArgDir::In,
                    span: a.span,
                    value: Some(a),
                });
                all.extend(args.iter().cloned());
                self.grow(mk(ExprKind::Call { callee, args: all }, span), d + 1, span)
            }
            InstrKind::Cal { when, fb, args, .. } => {
                let call = stmt(
                    StmtKind::Expr(mk(
                        ExprKind::Call {
                            callee: Box::new(fb.clone()),
                            args: args.clone(),
                        },
                        span,
                    )),
                    span,
                );
                self.conditional(*when, cr, i, next_uses, call, Why::Call, out)
            }
            InstrKind::FbInput { input, fb } => {
                let Some((a, _)) = self.take(cr, i) else {
                    return Cr::Poison;
                };
                let arg = Arg {
                    name: Some(*input),
                    dir: ArgDir::In,
                    span: a.span,
                    value: Some(a),
                };
                out.push(stmt(
                    StmtKind::Expr(mk(
                        ExprKind::Call {
                            callee: Box::new(fb.clone()),
                            args: vec![arg],
                        },
                        span,
                    )),
                    span,
                ));
                Cr::None(Why::Call)
            }
            InstrKind::Jump { when, label, .. } => {
                let go = stmt(StmtKind::Goto(*label), span);
                if !self.carried.contains(&label.sym) {
                    return self.conditional(*when, cr, i, next_uses, go, Why::Jump, out);
                }
                let keep = |d: &mut Self, v: Expr| {
                    let var = d.hidden_bool(LABEL_CR_VAR, span);
                    stmt(
                        StmtKind::Assign {
                            target: mk(ExprKind::Name(Ident { sym: var, span }), span),
                            value: v,
                        },
                        span,
                    )
                };
                if *when == When::Always {
                    let Some((e, _)) = self.take(cr, i) else {
                        return Cr::Poison;
                    };
                    out.push(keep(self, e));
                    out.push(go);
                    return Cr::None(Why::Jump);
                }
                let Some((c, d)) = self.take(cr, i) else {
                    return Cr::Poison;
                };
                let (c, d) = self.freeze(c, d, next_uses, out);
                let held = keep(self, bool_lit(*when == When::IfTrue, span));
                out.push(if_then(
                    c.clone(),
                    *when == When::IfFalse,
                    vec![held, go],
                    span,
                ));
                Cr::Val(c, d)
            }
            InstrKind::Ret { when, .. } => {
                let ret = stmt(StmtKind::Return, span);
                self.conditional(*when, cr, i, next_uses, ret, Why::Ret, out)
            }
        }
    }

    /// `s` always (the CR is then gone) or under the CR (which stays).
    #[allow(clippy::too_many_arguments)]
    fn conditional(
        &mut self,
        when: When,
        cr: Cr,
        i: &Instr,
        next_uses: bool,
        s: Stmt,
        after: Why,
        out: &mut Vec<Stmt>,
    ) -> Cr {
        if when == When::Always {
            out.push(s);
            return Cr::None(after);
        }
        let Some((c, d)) = self.take(cr, i) else {
            return Cr::Poison;
        };
        let (c, d) = self.freeze(c, d, next_uses, out);
        out.push(if_then(c.clone(), when == When::IfFalse, vec![s], i.span));
        Cr::Val(c, d)
    }

    /// `a op b` as the new CR.
    fn combine(&mut self, op: Op, a: Expr, d: u32, b: Expr, span: Span) -> Cr {
        let e = mk(
            ExprKind::Binary {
                op: binop(op),
                lhs: Box::new(a),
                rhs: Box::new(b),
            },
            span,
        );
        self.grow(e, d + 1, span)
    }

    /// A new CR tree of depth `d`, refused (E005) beyond `MAX_DEPTH`.
    fn grow(&mut self, e: Expr, d: u32, span: Span) -> Cr {
        if d > MAX_DEPTH {
            self.diags.push(Diagnostic::error(
                Code::E005,
                span,
                format!("the current result is computed by more than {MAX_DEPTH} instructions in a row: store it with ST and load it again"),
            ));
            return Cr::Poison;
        }
        Cr::Val(e, d)
    }

    /// The CR for `i` to use, or `None` after reporting why there is none.
    fn take(&mut self, cr: Cr, i: &Instr) -> Option<(Expr, u32)> {
        match cr {
            Cr::Val(e, d) => Some((e, d)),
            Cr::Poison => None,
            Cr::None(why) => {
                let name = op_name(i, self.interner);
                let when = match why {
                    Why::Start => "at the start of the instruction list",
                    Why::GroupStart => "at the start of a parenthesised group",
                    Why::Jump => "after an unconditional jump",
                    Why::Ret => "after RET",
                    Why::Call => "after a function block call",
                };
                self.diags.push(Diagnostic::error(
                    Code::E100,
                    op_span(i),
                    format!("`{name}` needs a current result, but there is none {when}: load one with LD first"),
                ));
                None
            }
            Cr::AfterLabel(l, why) => {
                let name = op_name(i, self.interner);
                let label = self.interner.name(l.sym).to_string();
                let from = match why {
                    Why::Start => "the start of the list",
                    Why::Call => "a function block call",
                    _ => "an instruction that leaves none",
                };
                self.diags.push(
                    Diagnostic::error(
                        Code::E101,
                        op_span(i),
                        format!("`{name}` uses the current result after the label `{label}`, but the line above reaches the label without one (after {from}): load one with LD first"),
                    )
                    .with_label(l.span, "the way in from the line above has no current result"),
                );
                None
            }
        }
    }

    /// Keeps a condition the next instruction still needs in `__CR`, so
    /// the tree is evaluated once, before the instruction changes anything.
    fn freeze(&mut self, c: Expr, d: u32, needed: bool, out: &mut Vec<Stmt>) -> (Expr, u32) {
        let simple = matches!(c.kind, ExprKind::Literal(_))
            || matches!(c.kind, ExprKind::Name(n) if self.interner.name(n.sym) == CR_VAR);
        if !needed || simple {
            return (c, d);
        }
        let span = c.span;
        let var = Ident {
            sym: self.hidden_bool(CR_VAR, span),
            span,
        };
        let name = mk(ExprKind::Name(var), span);
        out.push(stmt(
            StmtKind::Assign {
                target: name.clone(),
                value: c,
            },
            span,
        ));
        (name, 1)
    }

    /// `L:`: the label statement, and the CR after it. When the next
    /// instruction reads the CR, the way in from above stores it in
    /// `__CRL` (jumps to `L` do the same) and the CR is that variable.
    fn enter_label(&mut self, l: Ident, cr: Cr, out: &mut Vec<Stmt>) -> Cr {
        if !self.carried.contains(&l.sym) {
            out.push(stmt(StmtKind::Label(l), l.span));
            return Cr::None(Why::Jump);
        }
        let var = self.interner.intern(LABEL_CR_VAR);
        let name = mk(
            ExprKind::Name(Ident {
                sym: var,
                span: l.span,
            }),
            l.span,
        );
        match cr {
            Cr::Val(e, _) if is_non_bool_literal(&e) => {
                self.diags.push(Diagnostic::error(
                    Code::E101,
                    e.span,
                    format!(
                        "only a BOOL current result continues across the label `{}`: store this one with ST and load it again after the label",
                        self.interner.name(l.sym)
                    ),
                ));
                out.push(stmt(StmtKind::Label(l), l.span));
                return Cr::Poison;
            }
            Cr::Val(e, _) => {
                let span = e.span;
                out.push(stmt(
                    StmtKind::Assign {
                        target: name.clone(),
                        value: e,
                    },
                    span,
                ));
            }
            // Nothing falls through after an unconditional jump or return.
            Cr::None(Why::Jump | Why::Ret) | Cr::Poison => {}
            Cr::None(why) | Cr::AfterLabel(_, why) => {
                out.push(stmt(StmtKind::Label(l), l.span));
                return Cr::AfterLabel(l, why);
            }
        }
        out.push(stmt(StmtKind::Label(l), l.span));
        self.hidden_bool(LABEL_CR_VAR, l.span);
        Cr::Val(name, 1)
    }

    /// The hidden BOOL variable `name`, declared on first use.
    fn hidden_bool(&mut self, name: &str, span: Span) -> Symbol {
        let sym = self.interner.intern(name);
        if !self
            .hidden
            .iter()
            .any(|d| d.names.iter().any(|n| n.sym == sym))
        {
            let bool_ty = Ident {
                sym: self.interner.intern("BOOL"),
                span,
            };
            self.hidden.push(VarDecl {
                names: vec![Ident { sym, span }],
                location: None,
                ty: TypeSpec::Named(bool_ty),
                edge: None,
                init: None,
                span,
            });
        }
        sym
    }
}

/// A literal that is not a Boolean (such a CR cannot live in `__CRL`).
fn is_non_bool_literal(e: &Expr) -> bool {
    // (`0` and `1` are Boolean literals too.)
    matches!(&e.kind, ExprKind::Literal(l) if !matches!(l.kind, LitKind::Bool(_) | LitKind::Int(0 | 1)))
}

/// `IF [NOT] c THEN body END_IF`
fn if_then(c: Expr, negate: bool, body: Vec<Stmt>, span: Span) -> Stmt {
    let cond = if negate { not(c, span) } else { c };
    stmt(
        StmtKind::If {
            branches: vec![CondBlock { cond, body, span }],
            else_body: None,
        },
        span,
    )
}

/// The VAR_TEMP block declaring `hidden` (none when it is empty).
pub fn hidden_block(hidden: Vec<VarDecl>) -> Option<crate::ast::VarBlock> {
    let first = hidden.first()?.span;
    let span = hidden.iter().fold(first, |s, d| s.to(d.span));
    Some(crate::ast::VarBlock {
        kind: crate::ast::VarKind::Temp,
        constant: false,
        retain: crate::ast::Retain::Unspecified,
        decls: hidden,
        span,
    })
}
