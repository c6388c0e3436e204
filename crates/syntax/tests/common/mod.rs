//! Helpers shared by the parser tests: parse a snippet, and print trees as
//! compact S-expressions so tests can assert exact shapes in one line.
#![allow(dead_code)]

use automat_base::{Diagnostic, FileId, Interner, SourceFile};
use automat_syntax::ast::*;

pub struct Out {
    pub unit: SourceUnit,
    pub diags: Vec<Diagnostic>,
    pub interner: Interner,
    pub src: String,
}

pub fn parse(src: &str) -> Out {
    let mut interner = Interner::new();
    let parsed = automat_syntax::parse(FileId(0), src, &mut interner);
    Out {
        unit: parsed.unit,
        diags: parsed.diagnostics,
        interner,
        src: src.to_string(),
    }
}

/// Parses and asserts there is no diagnostic.
pub fn ok(src: &str) -> Out {
    let out = parse(src);
    assert!(
        out.diags.is_empty(),
        "unexpected diagnostics: {:#?}",
        out.diags
    );
    out
}

/// `(code, line)` of every diagnostic, in order.
pub fn errors(src: &str) -> Vec<(&'static str, u32)> {
    let out = parse(src);
    let file = SourceFile::new("t.st", src);
    out.diags
        .iter()
        .map(|d| (d.code.as_str(), file.line_col(d.span.start).0))
        .collect()
}

/// The messages of every diagnostic.
pub fn messages(src: &str) -> Vec<String> {
    parse(src).diags.into_iter().map(|d| d.message).collect()
}

impl Out {
    pub fn name(&self, id: Ident) -> String {
        self.interner.name(id.sym).to_string()
    }

    pub fn pou(&self, i: usize) -> &Pou {
        match self.unit.items.get(i) {
            Some(Item::Pou(p)) => p,
            other => panic!("item {i} is not a POU: {other:?}"),
        }
    }

    pub fn body(&self, i: usize) -> &[Stmt] {
        let Body::St(b) = &self.pou(i).body;
        b
    }

    /// The text a span covers.
    pub fn text(&self, span: automat_base::Span) -> &str {
        &self.src[span.start as usize..span.end as usize]
    }

    pub fn expr(&self, e: &Expr) -> String {
        match &e.kind {
            ExprKind::Literal(l) => self.lit(l),
            ExprKind::Name(i) => self.name(*i),
            ExprKind::Address(a) => addr(a),
            ExprKind::Member { base, member } => {
                format!("(. {} {})", self.expr(base), self.name(*member))
            }
            ExprKind::Partial {
                base, size, index, ..
            } => format!("(.% {} {size:?} {index})", self.expr(base)),
            ExprKind::Index { base, indices } => {
                let ix: Vec<String> = indices.iter().map(|i| self.expr(i)).collect();
                format!("(index {} {})", self.expr(base), ix.join(" "))
            }
            ExprKind::Deref(b) => format!("(^ {})", self.expr(b)),
            ExprKind::Unary { op, operand } => {
                let o = match op {
                    UnaryOp::Neg => "neg",
                    UnaryOp::Plus => "plus",
                    UnaryOp::Not => "not",
                };
                format!("({o} {})", self.expr(operand))
            }
            ExprKind::Binary { op, lhs, rhs } => {
                format!("({} {} {})", op.symbol(), self.expr(lhs), self.expr(rhs))
            }
            ExprKind::Call { callee, args } => {
                let mut s = format!("(call {}", self.expr(callee));
                for a in args {
                    s.push(' ');
                    s.push_str(&self.arg(a));
                }
                s.push(')');
                s
            }
            ExprKind::Paren(e) => format!("(paren {})", self.expr(e)),
            ExprKind::Error => "<error>".to_string(),
        }
    }

    pub fn arg(&self, a: &Arg) -> String {
        let v = a.value.as_ref().map(|v| self.expr(v)).unwrap_or_default();
        match (a.name, a.dir) {
            (None, _) => v,
            (Some(n), ArgDir::In) => format!("({} := {v})", self.name(n)),
            (Some(n), ArgDir::Out) => format!("({} => {v})", self.name(n)),
            (Some(n), ArgDir::OutNot) => format!("(NOT {} => {v})", self.name(n)),
        }
    }

    pub fn lit(&self, l: &Literal) -> String {
        let v = match &l.kind {
            LitKind::Int(v) => v.to_string(),
            LitKind::Real(f) => format!("{f:?}"),
            LitKind::Bool(b) => (if *b { "TRUE" } else { "FALSE" }).to_string(),
            LitKind::Duration { nanos, long } => {
                format!("{}#{nanos}ns", if *long { "LT" } else { "T" })
            }
            LitKind::Date { days, long } => format!("{}#{days}d", if *long { "LD" } else { "D" }),
            LitKind::TimeOfDay { nanos, long } => {
                format!("{}#{nanos}ns", if *long { "LTOD" } else { "TOD" })
            }
            LitKind::DateTime { nanos, long } => {
                format!("{}#{nanos}ns", if *long { "LDT" } else { "DT" })
            }
            LitKind::String { value, wide } => {
                if *wide {
                    format!("w{value:?}")
                } else {
                    format!("{value:?}")
                }
            }
            LitKind::Enum(i) => self.name(*i),
        };
        match l.ty {
            Some(t) => format!("{}#{v}", self.name(t)),
            None => v,
        }
    }

    pub fn stmts(&self, body: &[Stmt]) -> String {
        let s: Vec<String> = body.iter().map(|s| self.stmt(s)).collect();
        format!("[{}]", s.join("; "))
    }

    pub fn stmt(&self, s: &Stmt) -> String {
        match &s.kind {
            StmtKind::Assign { target, value } => {
                format!("{} := {}", self.expr(target), self.expr(value))
            }
            StmtKind::Expr(e) => self.expr(e),
            StmtKind::Return => "RETURN".into(),
            StmtKind::Exit => "EXIT".into(),
            StmtKind::Continue => "CONTINUE".into(),
            StmtKind::Empty => "EMPTY".into(),
            StmtKind::Label(l) => format!("{}:", self.name(*l)),
            StmtKind::Goto(l) => format!("GOTO {}", self.name(*l)),
            StmtKind::If {
                branches,
                else_body,
            } => {
                let mut out = String::from("IF");
                for b in branches {
                    out.push_str(&format!(" {} {}", self.expr(&b.cond), self.stmts(&b.body)));
                }
                if let Some(e) = else_body {
                    out.push_str(&format!(" ELSE {}", self.stmts(e)));
                }
                out
            }
            StmtKind::Case {
                selector,
                arms,
                else_body,
            } => {
                let mut out = format!("CASE {}", self.expr(selector));
                for a in arms {
                    let labels: Vec<String> = a
                        .labels
                        .iter()
                        .map(|l| match l {
                            CaseLabel::Value(v) => self.expr(v),
                            CaseLabel::Range(a, b) => format!("{}..{}", self.expr(a), self.expr(b)),
                        })
                        .collect();
                    out.push_str(&format!(" | {}: {}", labels.join(","), self.stmts(&a.body)));
                }
                if let Some(e) = else_body {
                    out.push_str(&format!(" | ELSE {}", self.stmts(e)));
                }
                out
            }
            StmtKind::For {
                var,
                from,
                to,
                by,
                body,
            } => format!(
                "FOR {} {} {} {} {}",
                self.name(*var),
                self.expr(from),
                self.expr(to),
                by.as_ref().map(|b| self.expr(b)).unwrap_or("-".into()),
                self.stmts(body)
            ),
            StmtKind::While { cond, body } => {
                format!("WHILE {} {}", self.expr(cond), self.stmts(body))
            }
            StmtKind::Repeat { body, until } => {
                format!("REPEAT {} UNTIL {}", self.stmts(body), self.expr(until))
            }
        }
    }

    pub fn ty(&self, t: &TypeSpec) -> String {
        match t {
            TypeSpec::Named(i) => self.name(*i),
            TypeSpec::String { wide, len, .. } => {
                let n = if *wide { "WSTRING" } else { "STRING" };
                match len {
                    Some(l) => format!("{n}[{}]", self.expr(l)),
                    None => n.to_string(),
                }
            }
            TypeSpec::Array { dims, elem, .. } => {
                let d: Vec<String> = dims
                    .iter()
                    .map(|d| match d {
                        ArrayDim::Range { lo, hi, .. } => {
                            format!("{}..{}", self.expr(lo), self.expr(hi))
                        }
                        ArrayDim::Star(_) => "*".into(),
                    })
                    .collect();
                format!("ARRAY[{}] OF {}", d.join(","), self.ty(elem))
            }
            TypeSpec::Subrange { base, lo, hi, .. } => {
                format!("{}({}..{})", self.name(*base), self.expr(lo), self.expr(hi))
            }
            TypeSpec::Enum { base, values, .. } => {
                let v: Vec<String> = values
                    .iter()
                    .map(|v| match &v.value {
                        Some(e) => format!("{}:={}", self.name(v.name), self.expr(e)),
                        None => self.name(v.name),
                    })
                    .collect();
                let b = base
                    .map(|b| format!("{} ", self.name(b)))
                    .unwrap_or_default();
                format!("{b}({})", v.join(","))
            }
            TypeSpec::Struct { members, .. } => {
                let m: Vec<String> = members.iter().map(|m| self.decl(m)).collect();
                format!("STRUCT {} END_STRUCT", m.join(" "))
            }
            TypeSpec::Ref { target, .. } => format!("REF_TO {}", self.ty(target)),
        }
    }

    pub fn init(&self, i: &Initializer) -> String {
        match i {
            Initializer::Expr(e) => self.expr(e),
            Initializer::Array { elems, .. } => {
                let e: Vec<String> = elems
                    .iter()
                    .map(|e| {
                        let v = e.value.as_ref().map(|v| self.init(v)).unwrap_or_default();
                        match &e.repeat {
                            Some(r) => format!("{}({v})", self.expr(r)),
                            None => v,
                        }
                    })
                    .collect();
                format!("[{}]", e.join(","))
            }
            Initializer::Struct { fields, .. } => {
                let f: Vec<String> = fields
                    .iter()
                    .map(|f| format!("{}:={}", self.name(f.name), self.init(&f.value)))
                    .collect();
                format!("({})", f.join(","))
            }
        }
    }

    /// `a,b AT %IX0.1 : INT R_EDGE := 5;`
    pub fn decl(&self, d: &VarDecl) -> String {
        let names: Vec<String> = d.names.iter().map(|n| self.name(*n)).collect();
        let mut s = names.join(",");
        if let Some(l) = &d.location {
            s.push_str(&format!(" AT {}", addr(&l.addr)));
        }
        s.push_str(&format!(" : {}", self.ty(&d.ty)));
        match d.edge {
            Some(Edge::Rising) => s.push_str(" R_EDGE"),
            Some(Edge::Falling) => s.push_str(" F_EDGE"),
            None => {}
        }
        if let Some(i) = &d.init {
            s.push_str(&format!(" := {}", self.init(i)));
        }
        s.push(';');
        s
    }
}

pub fn addr(a: &DirectAddress) -> String {
    let area = match a.area {
        Area::Input => "I",
        Area::Output => "Q",
        Area::Memory => "M",
    };
    let size = match a.size {
        AddrSize::None => "",
        AddrSize::Bit => "X",
        AddrSize::Byte => "B",
        AddrSize::Word => "W",
        AddrSize::DWord => "D",
        AddrSize::LWord => "L",
    };
    if a.partial {
        return format!("%{area}{size}*");
    }
    let path: Vec<String> = a.path.iter().map(|p| p.to_string()).collect();
    format!("%{area}{size}{}", path.join("."))
}

/// Wraps statements in a program and returns the printed body.
pub fn body(stmts: &str) -> String {
    let out = ok(&format!("PROGRAM p\n{stmts}\nEND_PROGRAM\n"));
    out.stmts(out.body(0))
}

/// Parses `x := <e>;` and prints the value.
pub fn expr(e: &str) -> String {
    let out = ok(&format!("PROGRAM p\nx := {e};\nEND_PROGRAM\n"));
    match &out.body(0)[0].kind {
        StmtKind::Assign { value, .. } => out.expr(value),
        other => panic!("not an assignment: {other:?}"),
    }
}

/// Parses a VAR block and prints its declarations.
pub fn decls(vars: &str) -> Vec<String> {
    let out = ok(&format!("PROGRAM p\nVAR\n{vars}\nEND_VAR\nEND_PROGRAM\n"));
    out.pou(0).var_blocks[0]
        .decls
        .iter()
        .map(|d| out.decl(d))
        .collect()
}

/// Parses a TYPE block and prints `name : spec [:= init]` per type.
pub fn types(src: &str) -> Vec<String> {
    let out = ok(&format!("TYPE\n{src}\nEND_TYPE\n"));
    let Some(Item::Types(tb)) = out.unit.items.first() else {
        panic!("no TYPE block");
    };
    tb.decls
        .iter()
        .map(|d| {
            let mut s = format!("{} : {}", out.name(d.name), out.ty(&d.spec));
            if let Some(i) = &d.init {
                s.push_str(&format!(" := {}", out.init(i)));
            }
            s
        })
        .collect()
}
