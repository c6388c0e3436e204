//! Top-level items: POUs, TYPE blocks, global variable lists, and the
//! recovery between them.

use super::expr::is_identish;
use super::Parser;
use crate::ast::{
    Body, Expr, ExprKind, Item, Lang, Pou, PouKind, Stmt, StmtKind, TypeBlock, TypeDecl, TypeSpec,
};
use crate::lexer::{Kw, Tok};

const END_PROGRAM: &[Kw] = &[Kw::EndProgram];
const END_FUNCTION: &[Kw] = &[Kw::EndFunction];
const END_FUNCTION_BLOCK: &[Kw] = &[Kw::EndFunctionBlock];

fn is_pou_end(k: Kw) -> bool {
    matches!(k, Kw::EndProgram | Kw::EndFunction | Kw::EndFunctionBlock)
}

impl Parser<'_> {
    fn at_item_start(&self) -> bool {
        matches!(self.peek(), Tok::Kw(k) if k.is_item_start() || k == Kw::VarGlobal)
    }

    pub(super) fn items(&mut self) -> Vec<Item> {
        let mut items = self.items_in(false);
        let heap = std::mem::take(&mut self.heap_templates);
        items.extend(heap.into_iter().map(Item::Globals));
        items
    }

    /// The items of a file, or (`nested`) of a namespace, up to its
    /// `END_NAMESPACE` (not consumed).
    pub(super) fn items_in(&mut self, nested: bool) -> Vec<Item> {
        let mut items = Vec::new();
        loop {
            let before = self.pos;
            if !matches!(self.peek(), Tok::Kw(Kw::Action)) {
                self.program_actions(&mut items);
            }
            match self.peek() {
                Tok::Eof => break,
                Tok::Ident(_) if nested && self.is_word("END_NAMESPACE") => break,
                Tok::Ident(_)
                    if self.is_word("NAMESPACE") && matches!(self.nth(1), Tok::Ident(_)) =>
                {
                    if let Some(n) = self.namespace() {
                        items.push(n);
                    }
                }
                Tok::Kw(Kw::Program | Kw::Function | Kw::FunctionBlock) => {
                    if let Some(item) = self.pou() {
                        items.push(self.with_pou_usings(item));
                    }
                }
                Tok::Kw(Kw::Action) => self.pou_action(&mut items),
                Tok::Kw(Kw::Type) => items.push(Item::Types(self.type_block())),
                Tok::Kw(Kw::VarGlobal) => items.push(Item::Globals(self.var_block())),
                Tok::Kw(Kw::Configuration) => {
                    if let Some(c) = self.configuration() {
                        items.push(Item::Config(c));
                    }
                }
                Tok::Ident(_) if self.is_word("CLASS") && matches!(self.nth(1), Tok::Ident(_)) => {
                    if let Some(c) = self.class() {
                        items.push(self.with_pou_usings(Item::Class(Box::new(c))));
                    }
                }
                Tok::Ident(_)
                    if self.is_word("INTERFACE") && matches!(self.nth(1), Tok::Ident(_)) =>
                {
                    if let Some(i) = self.interface() {
                        items.push(Item::Interface(Box::new(i)));
                    }
                }
                _ => {
                    self.expected("`PROGRAM`, `FUNCTION`, `FUNCTION_BLOCK`, `TYPE`, `VAR_GLOBAL` or `CONFIGURATION`");
                    self.bump();
                    while !(self.at_item_start() || self.at_eof() || self.at_namespace_word()) {
                        self.bump();
                    }
                }
            }
            if self.pos == before {
                self.bump();
            }
        }
        self.program_actions(&mut items);
        items
    }

    /// After the last action of a PROGRAM: each action also as a hidden
    /// function `__ACTION_<program>_<action>` (its statements, the other
    /// actions inlined), for the calls `Program.Action();` from other POUs.
    /// The `codesys` dialect makes the program's variables visible to it,
    /// or drops it when no other POU calls it (`automat_dialect::codesys`).
    fn program_actions(&mut self, items: &mut Vec<Item>) {
        let actions = std::mem::take(&mut self.pou_actions);
        let Some(Item::Pou(program)) = items.last() else {
            return;
        };
        if program.kind != PouKind::Program {
            return;
        }
        let owner = self.interner.name(program.name.sym).to_string();
        for (name, body, span) in actions {
            let hidden = format!("__ACTION_{owner}_{}", self.interner.name(name));
            let sym = self.interner.intern(&hidden);
            items.push(Item::Pou(Pou {
                kind: PouKind::Function,
                name: crate::ast::Ident { sym, span },
                return_type: None,
                var_blocks: Vec::new(),
                body: Body::St(body),
                lang: Lang::St,
                span,
            }));
        }
    }

    /// CODESYS V2.3 `ACTION name: statements END_ACTION` after a POU (as
    /// its text exports write a POU's actions). After a function block: a
    /// method of it without parameters or result, called `name();` in its
    /// body and `inst.name();` outside, running on the instance's
    /// variables. After a program or a function: its statements replace
    /// the calls `name();` of the body (the same variables; an action with
    /// RETURN is E161). At the start of a file it is E161.
    fn pou_action(&mut self, items: &mut Vec<Item>) {
        let opener = self.bump();
        let name = self.expect_ident("the name of the action");
        self.eat(Tok::Colon);
        self.frames.push(super::sfc::END_ACTION);
        self.oop_depth += 1;
        let body = self.stmt_list(false);
        self.oop_depth -= 1;
        self.frames.pop();
        if !self.eat_kw(Kw::EndAction) {
            self.report_unclosed(Kw::EndAction, opener);
        }
        self.eat(Tok::Semi);
        let span = self.span_from(opener.start);
        if !self.opts.codesys {
            self.report(
                automat_base::Diagnostic::error(
                    automat_base::Code::E161,
                    self.tok_span(opener),
                    "an ACTION outside a chart is a CODESYS V2.3 action of the POU before it",
                )
                .with_note("check with `--lib codesys` (or `libraries = [\"codesys\"]` in automat.toml) to read CODESYS code"),
            );
            return;
        }
        let Some(name) = name else { return };
        let method = crate::ast::oop::Method {
            name,
            visibility: crate::ast::oop::Visibility::Public,
            visibility_span: None,
            is_abstract: false,
            is_final: false,
            is_override: false,
            return_type: None,
            var_blocks: Vec::new(),
            body,
            usings: Vec::new(),
            span,
        };
        let fb = matches!(items.last(), Some(Item::Pou(p)) if p.kind == PouKind::FunctionBlock);
        match items.last_mut() {
            Some(Item::Class(c)) if c.kind == crate::ast::oop::ClassKind::FunctionBlock => {
                c.methods.push(method);
            }
            Some(Item::Pou(_)) if fb => {
                let Some(Item::Pou(p)) = items.pop() else {
                    return;
                };
                let crate::ast::Body::St(body) = p.body;
                items.push(Item::Class(Box::new(crate::ast::oop::Class {
                    kind: crate::ast::oop::ClassKind::FunctionBlock,
                    name: p.name,
                    is_abstract: false,
                    is_final: false,
                    extends: None,
                    implements: Vec::new(),
                    var_blocks: p.var_blocks,
                    var_access: Vec::new(),
                    methods: vec![method],
                    properties: Vec::new(),
                    body,
                    span: p.span,
                    desugared: false,
                })));
            }
            // A program's or function's action runs on the same variables
            // wherever it is called from its own body: the calls
            // (`Name();`) are replaced by its statements.
            Some(Item::Pou(p)) => {
                if has_return(&method.body) {
                    self.diags.push(automat_base::Diagnostic::error(
                        automat_base::Code::E161,
                        self.tok_span(opener),
                        "an action of a PROGRAM or FUNCTION is run in place of its calls, so it cannot RETURN: leave it with IF instead",
                    ));
                }
                // The actions read before, in this one; this one, in them
                // and in the body.
                let mut body = method.body;
                for (other, its, _) in &self.pou_actions {
                    inline_calls(&mut body, *other, its);
                }
                for (_, its, _) in &mut self.pou_actions {
                    inline_calls(its, method.name.sym, &body);
                }
                let crate::ast::Body::St(stmts) = &mut p.body;
                inline_calls(stmts, method.name.sym, &body);
                self.pou_actions.push((method.name.sym, body, span));
            }
            _ => self.report(automat_base::Diagnostic::error(
                automat_base::Code::E161,
                self.tok_span(opener),
                "a CODESYS ACTION is read after the POU it belongs to",
            )),
        }
    }

    /// FUNCTION, FUNCTION_BLOCK or PROGRAM, at its keyword. `None` when it
    /// has no name (the error was reported and its text consumed).
    fn pou(&mut self) -> Option<Item> {
        self.pou_actions.clear();
        let opener = self.bump();
        let (kind, end, frame, what) = match opener.tok {
            Tok::Kw(Kw::Function) => (PouKind::Function, Kw::EndFunction, END_FUNCTION, "function"),
            Tok::Kw(Kw::FunctionBlock) => (
                PouKind::FunctionBlock,
                Kw::EndFunctionBlock,
                END_FUNCTION_BLOCK,
                "function block",
            ),
            _ => (PouKind::Program, Kw::EndProgram, END_PROGRAM, "program"),
        };
        let mut head = super::oop::FbHead::default();
        if kind == PouKind::FunctionBlock {
            self.fb_modifiers_before_name(&mut head);
        }
        let name = self.expect_ident(&format!("the name of the {what}"));
        if kind == PouKind::FunctionBlock {
            self.fb_head_after_name(&mut head);
        }
        let return_type = if kind == PouKind::Function && self.eat(Tok::Colon) {
            self.type_spec()
        } else {
            None
        };
        self.pou_usings = self.usings();
        let mut var_blocks = Vec::new();
        self.var_access_ok = kind == PouKind::FunctionBlock;
        while let Tok::Kw(k) = self.peek() {
            match k {
                Kw::VarAccess | Kw::VarConfig => {
                    let msg = format!(
                        "`{}` is only allowed in a CONFIGURATION, not in a {what}",
                        k.name()
                    );
                    self.error_here(msg);
                    self.var_block();
                }
                k if k.is_var_block() => var_blocks.push(self.var_block()),
                _ => break,
            }
        }
        self.var_access_ok = false;
        let var_access = std::mem::take(&mut self.var_access);
        let (mut methods, mut properties) = (Vec::new(), Vec::new());
        if kind == PouKind::FunctionBlock {
            self.oop_depth += 1;
            self.members(&mut methods, &mut properties);
        }
        self.frames.push(frame);
        let (body, lang) = if self.at_sfc_start() {
            self.sfc_body(kind, &mut var_blocks)
        } else if self.at_il_start() {
            self.il_pou_body(end, &mut var_blocks)
        } else {
            let stmts = self.stmt_list(false);
            if self.at_sfc_start() {
                // Statements, then a chart: one error, and the chart is
                // still parsed and checked (the statements are dropped).
                self.statements_before_chart(&stmts);
                self.sfc_body(kind, &mut var_blocks)
            } else {
                (stmts, Lang::St)
            }
        };
        self.frames.pop();
        if kind == PouKind::FunctionBlock {
            // Methods may also follow the body (as some tools write them).
            self.members(&mut methods, &mut properties);
            self.oop_depth -= 1;
        }
        if !self.eat_kw(end) {
            self.report_unclosed(end, opener);
            match self.peek() {
                // A misspelt end (`END_FUNCTION` closing a PROGRAM) closes it.
                Tok::Kw(k) if is_pou_end(k) => {
                    self.bump();
                }
                // Skip what the body could not parse, up to this POU's end.
                _ => {
                    while !(self.at_item_start() || self.at_eof()) {
                        if self.bump().tok == Tok::Kw(end) {
                            break;
                        }
                    }
                }
            }
        }
        let name = name?;
        let span = self.span_from(opener.start);
        if head.any || !var_access.is_empty() || !methods.is_empty() || !properties.is_empty() {
            return Some(Item::Class(Box::new(crate::ast::oop::Class {
                kind: crate::ast::oop::ClassKind::FunctionBlock,
                name,
                is_abstract: head.is_abstract,
                is_final: head.is_final,
                extends: head.extends,
                implements: head.implements,
                var_blocks,
                var_access,
                methods,
                properties,
                body,
                span,
                desugared: false,
            })));
        }
        Some(Item::Pou(Pou {
            kind,
            name,
            return_type,
            var_blocks,
            body: Body::St(body),
            lang,
            span,
        }))
    }

    /// `TYPE decl; ... END_TYPE`, at `TYPE`.
    fn type_block(&mut self) -> TypeBlock {
        let opener = self.bump();
        let mut decls = Vec::new();
        loop {
            let before = self.pos;
            match self.peek() {
                Tok::Kw(Kw::EndType) => {
                    self.bump();
                    break;
                }
                t if is_identish(t) => {
                    if let Some(d) = self.type_decl() {
                        decls.push(d);
                    }
                }
                _ if self.at_decl_sync() => {
                    self.report_unclosed(Kw::EndType, opener);
                    break;
                }
                _ => {
                    self.expected("a type declaration or `END_TYPE`");
                    self.recover_decl();
                }
            }
            if self.pos == before {
                self.bump();
            }
        }
        TypeBlock {
            decls,
            span: self.span_from(opener.start),
        }
    }

    /// `Name : spec [:= init];` (the `;` after `END_STRUCT` is optional).
    fn type_decl(&mut self) -> Option<TypeDecl> {
        let start = self.cur().start;
        let name = self.ident_here()?;
        if !self.eat(Tok::Colon) {
            self.expected("`:` after the type name");
            if !self.can_start_type() {
                self.recover_decl();
                return None;
            }
        }
        let Some(spec) = self.type_spec() else {
            self.recover_decl();
            return None;
        };
        let init = if self.eat(Tok::ColonEq) {
            Some(self.initializer())
        } else {
            None
        };
        let span = self.span_from(start);
        let is_struct = matches!(spec, TypeSpec::Struct { .. });
        if !(is_struct && init.is_none() && !self.at(Tok::Semi)) {
            self.end_decl("after the type declaration");
        }
        Some(TypeDecl {
            name,
            spec,
            init,
            span,
        })
    }
}

/// Whether a statement list contains a RETURN (at any depth).
fn has_return(stmts: &[Stmt]) -> bool {
    stmts.iter().any(|s| match &s.kind {
        StmtKind::Return => true,
        StmtKind::If {
            branches,
            else_body,
        } => {
            branches.iter().any(|b| has_return(&b.body))
                || else_body.as_deref().is_some_and(has_return)
        }
        StmtKind::Case {
            arms, else_body, ..
        } => {
            arms.iter().any(|a| has_return(&a.body)) || else_body.as_deref().is_some_and(has_return)
        }
        StmtKind::For { body, .. }
        | StmtKind::While { body, .. }
        | StmtKind::Repeat { body, .. } => has_return(body),
        _ => false,
    })
}

/// Replaces each statement `name();` (at any depth) by `body`.
fn inline_calls(stmts: &mut Vec<Stmt>, name: automat_base::Symbol, body: &[Stmt]) {
    let mut i = 0;
    while i < stmts.len() {
        let is_call = matches!(&stmts[i].kind, StmtKind::Expr(Expr { kind: ExprKind::Call { callee, args }, .. })
            if args.is_empty() && matches!(&callee.kind, ExprKind::Name(id) if id.sym == name));
        if is_call {
            stmts.splice(i..=i, body.iter().cloned());
            i += body.len();
            continue;
        }
        match &mut stmts[i].kind {
            StmtKind::If {
                branches,
                else_body,
            } => {
                for b in branches {
                    inline_calls(&mut b.body, name, body);
                }
                if let Some(e) = else_body {
                    inline_calls(e, name, body);
                }
            }
            StmtKind::Case {
                arms, else_body, ..
            } => {
                for a in arms {
                    inline_calls(&mut a.body, name, body);
                }
                if let Some(e) = else_body {
                    inline_calls(e, name, body);
                }
            }
            StmtKind::For { body: b, .. }
            | StmtKind::While { body: b, .. }
            | StmtKind::Repeat { body: b, .. } => inline_calls(b, name, body),
            _ => {}
        }
        i += 1;
    }
}
