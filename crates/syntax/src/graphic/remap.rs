//! Moves every span of a parsed tree (and of its diagnostics) from the
//! generated text into the source file (see `generated.rs`). One function per node
//! type; every `Span` field is visited.

use super::generated::Generated;
use crate::ast::il::{IlBody, Instr, InstrKind};
use crate::ast::sfc::{ActionBody, Chart, Condition};
use crate::ast::*;
use automat_base::{Diagnostic, Span};

pub struct Remap<'a> {
    pub out: &'a Generated,
}

impl Remap<'_> {
    fn s(&self, s: &mut Span) {
        *s = self.out.map(*s);
    }

    fn id(&self, i: &mut Ident) {
        self.s(&mut i.span);
    }

    pub fn diag(&self, d: &mut Diagnostic) {
        self.s(&mut d.span);
        for l in &mut d.labels {
            self.s(&mut l.span);
        }
    }

    pub fn item(&self, item: &mut Item) {
        match item {
            Item::Pou(p) => self.pou(p),
            Item::Types(t) => {
                self.s(&mut t.span);
                for d in &mut t.decls {
                    self.id(&mut d.name);
                    self.ty(&mut d.spec);
                    if let Some(i) = &mut d.init {
                        self.init(i);
                    }
                    self.s(&mut d.span);
                }
            }
            Item::Globals(b) => self.block(b),
            Item::Config(c) => self.config(c),
            // The graphical front ends generate no object-oriented items.
            Item::Class(_) | Item::Interface(_) | Item::Namespace(_) => {}
        }
    }

    fn pou(&self, p: &mut Pou) {
        self.id(&mut p.name);
        if let Some(t) = &mut p.return_type {
            self.ty(t);
        }
        for b in &mut p.var_blocks {
            self.block(b);
        }
        let Body::St(stmts) = &mut p.body;
        self.stmts(stmts);
        match &mut p.lang {
            Lang::St => {}
            Lang::Il(il) => self.il(il),
            Lang::Sfc(c) => self.chart(c),
        }
        self.s(&mut p.span);
    }

    fn block(&self, b: &mut VarBlock) {
        for d in &mut b.decls {
            self.var(d);
        }
        self.s(&mut b.span);
    }

    fn var(&self, d: &mut VarDecl) {
        for n in &mut d.names {
            self.id(n);
        }
        if let Some(l) = &mut d.location {
            self.loc(l);
        }
        self.ty(&mut d.ty);
        if let Some(i) = &mut d.init {
            self.init(i);
        }
        self.s(&mut d.span);
    }

    fn loc(&self, l: &mut Location) {
        self.s(&mut l.addr.span);
        self.s(&mut l.span);
    }

    fn ty(&self, t: &mut TypeSpec) {
        match t {
            TypeSpec::Named(i) => self.id(i),
            TypeSpec::String { len, span, .. } => {
                if let Some(e) = len {
                    self.expr(e);
                }
                self.s(span);
            }
            TypeSpec::Array { dims, elem, span } => {
                for d in dims {
                    match d {
                        ArrayDim::Range { lo, hi, span } => {
                            self.expr(lo);
                            self.expr(hi);
                            self.s(span);
                        }
                        ArrayDim::Star(s) => self.s(s),
                    }
                }
                self.ty(elem);
                self.s(span);
            }
            TypeSpec::Subrange { base, lo, hi, span } => {
                self.id(base);
                self.expr(lo);
                self.expr(hi);
                self.s(span);
            }
            TypeSpec::Enum { base, values, span } => {
                if let Some(b) = base {
                    self.id(b);
                }
                for v in values {
                    self.id(&mut v.name);
                    if let Some(e) = &mut v.value {
                        self.expr(e);
                    }
                }
                self.s(span);
            }
            TypeSpec::Struct { members, span } => {
                for m in members {
                    self.var(m);
                }
                self.s(span);
            }
            TypeSpec::Ref { target, span, .. } => {
                self.ty(target);
                self.s(span);
            }
        }
    }

    fn init(&self, i: &mut Initializer) {
        match i {
            Initializer::Expr(e) => self.expr(e),
            Initializer::Array { elems, span } => {
                for e in elems {
                    if let Some(r) = &mut e.repeat {
                        self.expr(r);
                    }
                    if let Some(v) = &mut e.value {
                        self.init(v);
                    }
                    self.s(&mut e.span);
                }
                self.s(span);
            }
            Initializer::Struct { fields, span } => {
                for f in fields {
                    self.id(&mut f.name);
                    self.init(&mut f.value);
                    self.s(&mut f.span);
                }
                self.s(span);
            }
        }
    }

    fn config(&self, c: &mut Configuration) {
        self.id(&mut c.name);
        for b in &mut c.globals {
            self.block(b);
        }
        for r in &mut c.resources {
            self.id(&mut r.name);
            if let Some(o) = &mut r.on {
                self.id(o);
            }
            for b in &mut r.globals {
                self.block(b);
            }
            for t in &mut r.tasks {
                self.id(&mut t.name);
                for p in &mut t.props {
                    self.id(&mut p.name);
                    self.expr(&mut p.value);
                    self.s(&mut p.span);
                }
                self.s(&mut t.span);
            }
            for p in &mut r.programs {
                self.id(&mut p.name);
                if let Some(t) = &mut p.task {
                    self.id(t);
                }
                self.id(&mut p.ty);
                self.args(&mut p.conns);
                self.s(&mut p.span);
            }
            self.s(&mut r.span);
        }
        for a in &mut c.access {
            self.id(&mut a.name);
            self.expr(&mut a.path);
            self.ty(&mut a.ty);
            self.s(&mut a.span);
        }
        for v in &mut c.var_config {
            self.expr(&mut v.path);
            if let Some(l) = &mut v.location {
                self.loc(l);
            }
            self.ty(&mut v.ty);
            if let Some(i) = &mut v.init {
                self.init(i);
            }
            self.s(&mut v.span);
        }
        self.s(&mut c.span);
    }

    pub fn stmts(&self, stmts: &mut [Stmt]) {
        for s in stmts {
            self.stmt(s);
        }
    }

    fn stmt(&self, s: &mut Stmt) {
        match &mut s.kind {
            StmtKind::Assign { target, value } => {
                self.expr(target);
                self.expr(value);
            }
            StmtKind::Expr(e) => self.expr(e),
            StmtKind::If {
                branches,
                else_body,
            } => {
                for b in branches {
                    self.expr(&mut b.cond);
                    self.stmts(&mut b.body);
                    self.s(&mut b.span);
                }
                if let Some(e) = else_body {
                    self.stmts(e);
                }
            }
            StmtKind::Case {
                selector,
                arms,
                else_body,
            } => {
                self.expr(selector);
                for a in arms {
                    for l in &mut a.labels {
                        match l {
                            CaseLabel::Value(e) => self.expr(e),
                            CaseLabel::Range(a, b) => {
                                self.expr(a);
                                self.expr(b);
                            }
                        }
                    }
                    self.stmts(&mut a.body);
                    self.s(&mut a.span);
                }
                if let Some(e) = else_body {
                    self.stmts(e);
                }
            }
            StmtKind::For {
                var,
                from,
                to,
                by,
                body,
            } => {
                self.id(var);
                self.expr(from);
                self.expr(to);
                if let Some(b) = by {
                    self.expr(b);
                }
                self.stmts(body);
            }
            StmtKind::While { cond, body } => {
                self.expr(cond);
                self.stmts(body);
            }
            StmtKind::Repeat { body, until } => {
                self.stmts(body);
                self.expr(until);
            }
            StmtKind::Label(i) | StmtKind::Goto(i) => self.id(i),
            StmtKind::Return | StmtKind::Exit | StmtKind::Continue | StmtKind::Empty => {}
        }
        self.s(&mut s.span);
    }

    fn args(&self, args: &mut [Arg]) {
        for a in args {
            if let Some(n) = &mut a.name {
                self.id(n);
            }
            if let Some(v) = &mut a.value {
                self.expr(v);
            }
            self.s(&mut a.span);
        }
    }

    pub fn expr(&self, e: &mut Expr) {
        // An explicit stack: generated chains (`a OR b OR ...`) can be long.
        let mut stack: Vec<&mut Expr> = vec![e];
        while let Some(e) = stack.pop() {
            self.s(&mut e.span);
            match &mut e.kind {
                ExprKind::Literal(l) => {
                    if let Some(t) = &mut l.ty {
                        self.id(t);
                    }
                    if let LitKind::Enum(i) = &mut l.kind {
                        self.id(i);
                    }
                }
                ExprKind::Name(i) => self.id(i),
                ExprKind::Address(a) => self.s(&mut a.span),
                ExprKind::Member { base, member } => {
                    self.id(member);
                    stack.push(base);
                }
                ExprKind::Partial {
                    base, index_span, ..
                } => {
                    self.s(index_span);
                    stack.push(base);
                }
                ExprKind::Index { base, indices } => {
                    stack.push(base);
                    stack.extend(indices.iter_mut());
                }
                ExprKind::Deref(b) | ExprKind::Paren(b) => stack.push(b),
                ExprKind::Unary { operand, .. } => stack.push(operand),
                ExprKind::Binary { lhs, rhs, .. } => {
                    stack.push(lhs);
                    stack.push(rhs);
                }
                ExprKind::Call { callee, args } => {
                    stack.push(callee);
                    for a in args {
                        if let Some(n) = &mut a.name {
                            self.id(n);
                        }
                        self.s(&mut a.span);
                        if let Some(v) = &mut a.value {
                            stack.push(v);
                        }
                    }
                }
                ExprKind::Error => {}
            }
        }
    }

    fn il(&self, il: &mut IlBody) {
        self.instrs(&mut il.instrs);
    }

    fn instrs(&self, instrs: &mut [Instr]) {
        for i in instrs {
            if let Some(l) = &mut i.label {
                self.id(l);
            }
            match &mut i.kind {
                InstrKind::Nothing | InstrKind::Error => {}
                InstrKind::Simple {
                    op_span, operand, ..
                } => {
                    self.s(op_span);
                    if let Some(e) = operand {
                        self.expr(e);
                    }
                }
                InstrKind::Group {
                    op_span,
                    first,
                    body,
                    ..
                } => {
                    self.s(op_span);
                    if let Some(e) = first {
                        self.expr(e);
                    }
                    self.instrs(body);
                }
                InstrKind::Call { name, args, .. } => {
                    self.id(name);
                    self.args(args);
                }
                InstrKind::Cal {
                    op_span, fb, args, ..
                } => {
                    self.s(op_span);
                    self.expr(fb);
                    self.args(args);
                }
                InstrKind::FbInput { input, fb } => {
                    self.id(input);
                    self.expr(fb);
                }
                InstrKind::Jump { op_span, label, .. } => {
                    self.s(op_span);
                    self.id(label);
                }
                InstrKind::Ret { op_span, .. } => self.s(op_span),
            }
            self.s(&mut i.span);
        }
    }

    fn chart(&self, c: &mut Chart) {
        let mut stack: Vec<&mut Chart> = vec![c];
        while let Some(c) = stack.pop() {
            for a in &mut c.actions {
                self.id(&mut a.name);
                match &mut a.body {
                    ActionBody::St(s) => self.stmts(s),
                    ActionBody::Il { il, stmts } => {
                        self.il(il);
                        self.stmts(stmts);
                    }
                }
                self.s(&mut a.span);
            }
            for t in &mut c.transitions {
                if let Some(n) = &mut t.name {
                    self.id(n);
                }
                for i in t.from.iter_mut().chain(t.to.iter_mut()) {
                    self.id(i);
                }
                match &mut t.cond {
                    Condition::St(e) => self.expr(e),
                    Condition::Il { il, stmts, result } => {
                        self.il(il);
                        self.stmts(stmts);
                        self.expr(result);
                    }
                    Condition::Missing => {}
                }
                self.s(&mut t.span);
            }
            for s in &mut c.steps {
                self.id(&mut s.name);
                for a in &mut s.assocs {
                    self.id(&mut a.name);
                    if let Some(t) = &mut a.time {
                        self.expr(t);
                    }
                    for i in &mut a.indicators {
                        self.id(i);
                    }
                    self.s(&mut a.span);
                }
                self.s(&mut s.span);
                if let Some(m) = &mut s.macro_body {
                    self.id(&mut m.exit);
                    stack.push(&mut m.chart);
                }
            }
        }
    }
}
