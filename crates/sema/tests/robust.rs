//! The checker never panics and never hangs: deep nesting, hostile
//! hand-built trees, cycles, and mutated real sources.

mod common;
use automat_base::{FileId, Interner, SourceMap, Span};
use automat_sema::check;
use automat_syntax::ast::*;
use std::path::Path;

fn sp() -> Span {
    Span::new(FileId(0), 0, 1)
}

fn ident(i: &mut Interner, s: &str) -> Ident {
    Ident {
        sym: i.intern(s),
        span: sp(),
    }
}

fn e(kind: ExprKind) -> Expr {
    Expr { kind, span: sp() }
}

fn program(i: &mut Interner, body: Vec<Stmt>, decls: Vec<VarDecl>) -> SourceUnit {
    SourceUnit {
        file: FileId(0),
        items: vec![Item::Pou(Pou {
            kind: PouKind::Program,
            name: ident(i, "P"),
            return_type: None,
            var_blocks: vec![VarBlock {
                kind: VarKind::Local,
                constant: false,
                retain: Retain::Unspecified,
                decls,
                span: sp(),
            }],
            body: Body::St(body),
            lang: Lang::St,
            span: sp(),
        })],
    }
}

#[test]
fn expressions_deeper_than_any_parser_allows() {
    let mut i = Interner::new();
    let x = ident(&mut i, "x");
    let mut deep = e(ExprKind::Name(x));
    for k in 0..20_000 {
        deep = if k % 2 == 0 {
            e(ExprKind::Paren(Box::new(deep)))
        } else {
            e(ExprKind::Binary {
                op: BinaryOp::Add,
                lhs: Box::new(deep),
                rhs: Box::new(e(ExprKind::Name(x))),
            })
        };
    }
    let decl = VarDecl {
        names: vec![x],
        location: None,
        ty: TypeSpec::Named(ident(&mut i, "INT")),
        edge: None,
        init: None,
        span: sp(),
    };
    let unit = program(
        &mut i,
        vec![Stmt {
            kind: StmtKind::Assign {
                target: e(ExprKind::Name(x)),
                value: deep,
            },
            span: sp(),
        }],
        vec![decl],
    );
    let a = check(std::slice::from_ref(&unit), &mut i);
    std::mem::forget(unit);
    assert!(a.diagnostics.iter().any(|d| d.code.as_str() == "E070"));
}

#[test]
fn statements_nested_deeper_than_any_parser_allows() {
    let mut i = Interner::new();
    let b = ident(&mut i, "b");
    let mut body = vec![Stmt {
        kind: StmtKind::Exit,
        span: sp(),
    }];
    for _ in 0..20_000 {
        body = vec![Stmt {
            kind: StmtKind::While {
                cond: e(ExprKind::Name(b)),
                body,
            },
            span: sp(),
        }];
    }
    let decl = VarDecl {
        names: vec![b],
        location: None,
        ty: TypeSpec::Named(ident(&mut i, "BOOL")),
        edge: None,
        init: None,
        span: sp(),
    };
    let unit = program(&mut i, body, vec![decl]);
    let a = check(std::slice::from_ref(&unit), &mut i);
    // Dropping a 20,000-deep tree recursively is the tree's business, not the checker's.
    std::mem::forget(unit);
    assert_eq!(a.diagnostics.len(), 1, "{:?}", a.diagnostics);
}

#[test]
fn long_chains_of_declarations_do_not_overflow() {
    // 5,000 aliases each naming the next, and constants each using the next.
    let mut src = String::from("TYPE\n");
    for k in 0..5000 {
        src.push_str(&format!("    T{k} : T{};\n", k + 1));
    }
    src.push_str("    T5000 : INT;\nEND_TYPE\nVAR_GLOBAL CONSTANT\n");
    for k in 0..5000 {
        src.push_str(&format!("    C{k} : INT := C{} + 0;\n", k + 1));
    }
    src.push_str("    C5000 : INT := 1;\nEND_VAR\nPROGRAM P\nVAR a : T0; b : ARRAY[1..C0] OF INT; END_VAR\nEND_PROGRAM\n");
    let (_, _, a) = common::analyze(&src);
    // The chains are too deep to follow; that is reported, not a crash.
    assert!(!a.diagnostics.is_empty());
    assert!(a.diagnostics.len() < 500, "{}", a.diagnostics.len());
}

#[test]
fn empty_and_error_nodes() {
    let mut i = Interner::new();
    let x = ident(&mut i, "x");
    let unit = program(
        &mut i,
        vec![
            Stmt {
                kind: StmtKind::Assign {
                    target: e(ExprKind::Error),
                    value: e(ExprKind::Error),
                },
                span: sp(),
            },
            Stmt {
                kind: StmtKind::Expr(e(ExprKind::Call {
                    callee: Box::new(e(ExprKind::Error)),
                    args: vec![Arg {
                        name: None,
                        dir: ArgDir::Out,
                        value: None,
                        span: sp(),
                    }],
                })),
                span: sp(),
            },
            Stmt {
                kind: StmtKind::Case {
                    selector: e(ExprKind::Name(x)),
                    arms: vec![],
                    else_body: None,
                },
                span: sp(),
            },
        ],
        vec![VarDecl {
            names: vec![],
            location: None,
            ty: TypeSpec::Array {
                dims: vec![],
                elem: Box::new(TypeSpec::Named(x)),
                span: sp(),
            },
            edge: None,
            init: Some(Initializer::Array {
                elems: vec![ArrayInitElem {
                    repeat: None,
                    value: None,
                    span: sp(),
                }],
                span: sp(),
            }),
            span: sp(),
        }],
    );
    let _ = check(&[unit.clone(), unit], &mut i);
    let _ = check(&[], &mut i);
}

/// A small deterministic generator (no dependency needed for this).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> u64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        self.0 >> 33
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

const SNIPPETS: &[&str] = &[
    " ",
    ";",
    ":=",
    "(",
    ")",
    "[",
    "]",
    ".",
    ",",
    "..",
    "#",
    "%IX0.1",
    "%I*",
    "'x'",
    "1",
    "-1",
    "300",
    "1.5",
    "T#1s",
    "TRUE",
    "END_IF",
    "END_VAR",
    "VAR",
    "IF",
    "THEN",
    "ARRAY[1..2] OF",
    "STRUCT",
    "END_STRUCT",
    "REF_TO",
    "^",
    "=>",
    "TON",
    "x",
    "INT",
    "AND",
    "**",
    "CASE",
    "OF",
    "FOR",
    "TO",
    "EXIT",
    "(*",
    "*)",
    "FUNCTION_BLOCK",
    "END_FUNCTION_BLOCK",
    "PROGRAM",
    "CONFIGURATION",
    "TASK",
    "RESOURCE",
    "AT",
    "CONSTANT",
    "NOT",
    "MOD",
    "16#FF",
    "STRING[5]",
    "Color#Red",
    "LIMIT(",
    "w.3",
];

fn mutate(text: &str, rng: &mut Lcg) -> String {
    let mut bytes: Vec<char> = text.chars().collect();
    for _ in 0..1 + rng.below(4) {
        let at = rng.below(bytes.len() + 1);
        match rng.below(3) {
            0 => {
                let len = rng.below(40).min(bytes.len().saturating_sub(at));
                bytes.drain(at..at + len);
            }
            1 => {
                let s = SNIPPETS[rng.below(SNIPPETS.len())];
                for (k, c) in s.chars().enumerate() {
                    bytes.insert(at + k, c);
                }
            }
            _ => {
                // Duplicate a slice elsewhere: declarations twice, bodies inside bodies.
                let from = rng.below(bytes.len() + 1);
                let len = rng.below(120).min(bytes.len().saturating_sub(from));
                let piece: Vec<char> = bytes[from..from + len].to_vec();
                for (k, c) in piece.into_iter().enumerate() {
                    bytes.insert(at + k, c);
                }
            }
        }
    }
    bytes.into_iter().collect()
}

fn corpus_files() -> Vec<String> {
    fn walk(p: &Path, out: &mut Vec<String>) {
        if p.is_dir() {
            let mut entries: Vec<_> = std::fs::read_dir(p)
                .map(|d| d.filter_map(|e| e.ok()).map(|e| e.path()).collect())
                .unwrap_or_default();
            entries.sort();
            for e in entries {
                walk(&e, out);
            }
        } else if p.extension().is_some_and(|e| e == "st") {
            if let Ok(b) = std::fs::read(p) {
                out.push(b.iter().map(|&c| c as char).collect());
            }
        }
    }
    let mut out = Vec::new();
    walk(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/corpus"),
        &mut out,
    );
    out.push(automat_sema::stdlib::FB_SOURCE.to_string());
    out
}

#[test]
fn mutated_sources_never_panic() {
    let files = corpus_files();
    // FUZZ_SEED / FUZZ_ROUNDS run other or longer campaigns by hand.
    let env = |k: &str| std::env::var(k).ok().and_then(|v| v.parse::<u64>().ok());
    let mut rng = Lcg(env("FUZZ_SEED").unwrap_or(0x5eed));
    let default_rounds = if cfg!(debug_assertions) { 600 } else { 5000 };
    let rounds = env("FUZZ_ROUNDS").unwrap_or(default_rounds);
    for _ in 0..rounds {
        let mut map = SourceMap::new();
        for _ in 0..1 + rng.below(3) {
            let base = &files[rng.below(files.len())];
            map.add("m.st", mutate(base, &mut rng));
        }
        let mut interner = Interner::new();
        let _ = automat_sema::check_sources(&map, &mut interner);
    }
}

#[test]
fn deep_statements_holding_deep_expressions() {
    let mut i = Interner::new();
    let x = ident(&mut i, "x");
    let b = ident(&mut i, "b");
    let mut deep = e(ExprKind::Name(x));
    for _ in 0..1000 {
        deep = e(ExprKind::Index {
            base: Box::new(e(ExprKind::Call {
                callee: Box::new(e(ExprKind::Member {
                    base: Box::new(deep),
                    member: x,
                })),
                args: vec![],
            })),
            indices: vec![e(ExprKind::Unary {
                op: UnaryOp::Neg,
                operand: Box::new(e(ExprKind::Name(x))),
            })],
        });
    }
    let mut body = vec![Stmt {
        kind: StmtKind::Assign {
            target: e(ExprKind::Name(x)),
            value: deep,
        },
        span: sp(),
    }];
    // Just under the statement limit, so the expression is reached.
    for _ in 0..250 {
        body = vec![Stmt {
            kind: StmtKind::If {
                branches: vec![CondBlock {
                    cond: e(ExprKind::Name(b)),
                    body,
                    span: sp(),
                }],
                else_body: None,
            },
            span: sp(),
        }];
    }
    let decls = vec![
        VarDecl {
            names: vec![b],
            location: None,
            ty: TypeSpec::Named(ident(&mut i, "BOOL")),
            edge: None,
            init: None,
            span: sp(),
        },
        VarDecl {
            names: vec![x],
            location: None,
            ty: TypeSpec::Named(ident(&mut i, "INT")),
            edge: None,
            init: None,
            span: sp(),
        },
    ];
    let unit = program(&mut i, body, decls);
    let a = check(std::slice::from_ref(&unit), &mut i);
    std::mem::forget(unit);
    assert_eq!(a.diagnostics.len(), 1, "{:?}", a.diagnostics);
}
