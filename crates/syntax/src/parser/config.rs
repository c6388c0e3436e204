//! CONFIGURATION, RESOURCE, TASK, program instances, VAR_ACCESS and
//! VAR_CONFIG.

use super::Parser;
use crate::ast::{
    AccessDecl, AccessDirection, ConfigInit, Configuration, Ident, ProgramConfig, Resource, Retain,
    TaskDecl, TaskProp,
};
use crate::lexer::{Kw, Tok};

/// What a resource (explicit or implicit) holds.
#[derive(Default)]
struct ResourceParts {
    globals: Vec<crate::ast::VarBlock>,
    tasks: Vec<TaskDecl>,
    programs: Vec<ProgramConfig>,
}

impl Parser<'_> {
    /// Skips to after the next `;`, stopping early at anything that can
    /// begin or end an element of a configuration.
    fn recover_config(&mut self) {
        loop {
            match self.peek() {
                Tok::Kw(Kw::Task | Kw::Resource | Kw::Program) => return,
                _ if self.at_decl_sync() => return,
                _ => {
                    if self.bump().tok == Tok::Semi {
                        return;
                    }
                }
            }
        }
    }

    /// TASK, PROGRAM or VAR_GLOBAL inside a configuration or resource.
    /// Returns false when the current token is none of them.
    fn resource_element(&mut self, parts: &mut ResourceParts) -> bool {
        match self.peek() {
            Tok::Kw(Kw::VarGlobal) => parts.globals.push(self.var_block()),
            Tok::Kw(Kw::Task) => {
                if let Some(t) = self.task() {
                    parts.tasks.push(t);
                }
            }
            Tok::Kw(Kw::Program) => {
                if let Some(p) = self.program_config() {
                    parts.programs.push(p);
                }
            }
            _ => return false,
        }
        true
    }

    /// `CONFIGURATION name ... END_CONFIGURATION`, at `CONFIGURATION`.
    pub(super) fn configuration(&mut self) -> Option<Configuration> {
        let opener = self.bump();
        let name = self.expect_ident("the name of the configuration");
        let mut globals = Vec::new();
        let mut resources = Vec::new();
        let mut access = Vec::new();
        let mut var_config = Vec::new();
        let mut implicit = ResourceParts::default();
        loop {
            let before = self.pos;
            match self.peek() {
                Tok::Kw(Kw::EndConfiguration) => {
                    self.bump();
                    break;
                }
                Tok::Kw(Kw::VarGlobal) => globals.push(self.var_block()),
                Tok::Kw(Kw::Task | Kw::Program) => {
                    self.resource_element(&mut implicit);
                }
                Tok::Kw(Kw::Resource) => {
                    if let Some(r) = self.resource() {
                        resources.push(r);
                    }
                }
                Tok::Kw(Kw::VarAccess) => {
                    let opener = self.bump();
                    self.decl_list(opener, false, |p| p.access_decl(), &mut access);
                }
                Tok::Kw(Kw::VarConfig) => {
                    let opener = self.bump();
                    self.decl_list(opener, true, |p| p.config_init(), &mut var_config);
                }
                Tok::Eof => {
                    self.report_unclosed(Kw::EndConfiguration, opener);
                    break;
                }
                Tok::Kw(k) if k.is_item_start() => {
                    self.report_unclosed(Kw::EndConfiguration, opener);
                    break;
                }
                _ => {
                    self.expected("`RESOURCE`, `TASK`, `PROGRAM`, `VAR_GLOBAL`, `VAR_ACCESS`, `VAR_CONFIG` or `END_CONFIGURATION`");
                    self.bump();
                    self.recover_config();
                }
            }
            if self.pos == before {
                self.bump();
            }
        }
        let name = name?;
        let span = self.span_from(opener.start);
        // Tasks and programs outside any RESOURCE form the implicit one.
        let has_implicit = !implicit.tasks.is_empty() || !implicit.programs.is_empty();
        if has_implicit || resources.is_empty() {
            resources.push(Resource {
                name,
                on: None,
                implicit: true,
                globals: implicit.globals,
                tasks: implicit.tasks,
                programs: implicit.programs,
                span,
            });
        }
        Some(Configuration {
            name,
            globals,
            resources,
            access,
            var_config,
            span,
        })
    }

    /// `RESOURCE name ON processor ... END_RESOURCE`, at `RESOURCE`.
    fn resource(&mut self) -> Option<Resource> {
        let opener = self.bump();
        let name = self.expect_ident("the name of the resource");
        let on = if self.eat_kw(Kw::On) {
            self.expect_ident("the processor type after `ON`")
        } else {
            None
        };
        let mut parts = ResourceParts::default();
        loop {
            let before = self.pos;
            if self.resource_element(&mut parts) {
                continue;
            }
            match self.peek() {
                Tok::Kw(Kw::EndResource) => {
                    self.bump();
                    // Some tools write `END_RESOURCE;`.
                    self.eat(Tok::Semi);
                    break;
                }
                Tok::Eof | Tok::Kw(Kw::Resource | Kw::EndConfiguration) => {
                    self.report_unclosed(Kw::EndResource, opener);
                    break;
                }
                Tok::Kw(k) if k.is_item_start() => {
                    self.report_unclosed(Kw::EndResource, opener);
                    break;
                }
                _ => {
                    self.expected("`TASK`, `PROGRAM`, `VAR_GLOBAL` or `END_RESOURCE`");
                    self.bump();
                    self.recover_config();
                }
            }
            if self.pos == before {
                self.bump();
            }
        }
        Some(Resource {
            name: name?,
            on,
            implicit: false,
            globals: parts.globals,
            tasks: parts.tasks,
            programs: parts.programs,
            span: self.span_from(opener.start),
        })
    }

    /// `TASK name (INTERVAL := T#10ms, PRIORITY := 1, SINGLE := trig);`
    fn task(&mut self) -> Option<TaskDecl> {
        let opener = self.bump();
        let name = self.expect_ident("the name of the task");
        let mut props = Vec::new();
        if self.expect(Tok::LParen, "after the task name") && !self.eat(Tok::RParen) {
            while let Some(prop) =
                self.expect_ident("a task property (INTERVAL, PRIORITY or SINGLE)")
            {
                self.expect(Tok::ColonEq, "after the task property");
                let value = self.expr();
                props.push(TaskProp {
                    span: prop.span.to(value.span),
                    name: prop,
                    value,
                });
                if !self.eat(Tok::Comma) {
                    break;
                }
            }
            self.expect(Tok::RParen, "to close the task properties");
        }
        let span = self.span_from(opener.start);
        self.end_decl("after the task declaration");
        Some(TaskDecl {
            name: name?,
            props,
            span,
        })
    }

    /// `PROGRAM [RETAIN|NON_RETAIN] inst [WITH task] : Type [(in := x, out => y)];`
    fn program_config(&mut self) -> Option<ProgramConfig> {
        let opener = self.bump();
        let retain = if self.eat_kw(Kw::Retain) {
            Retain::Retain
        } else if self.eat_kw(Kw::NonRetain) {
            Retain::NonRetain
        } else {
            Retain::Unspecified
        };
        let name = self.expect_ident("the name of the program instance");
        let task = if self.eat_kw(Kw::With) {
            self.expect_ident("a task name after `WITH`")
        } else {
            None
        };
        self.expect(Tok::Colon, "after the program instance name");
        let ty: Option<Ident> = self.qualified_ident_here();
        if ty.is_none() {
            self.expected("the program type");
        }
        let conns = if self.eat(Tok::LParen) {
            self.call_args()
        } else {
            Vec::new()
        };
        let span = self.span_from(opener.start);
        self.end_decl("after the program declaration");
        Some(ProgramConfig {
            retain,
            name: name?,
            task,
            ty: ty?,
            conns,
            span,
        })
    }

    /// `name : Res.Prog.var : INT [READ_WRITE|READ_ONLY];`
    fn access_decl(&mut self) -> Option<AccessDecl> {
        let start = self.cur().start;
        let Some(name) = self.expect_ident("the name of the access variable") else {
            self.recover_decl();
            return None;
        };
        self.expect(Tok::Colon, "after the access variable name");
        let path = self.expr();
        if !self.expect(Tok::Colon, "after the access path") && !self.can_start_type() {
            self.recover_decl();
            return None;
        }
        let Some(ty) = self.type_spec() else {
            self.recover_decl();
            return None;
        };
        let direction = if self.eat_kw(Kw::ReadWrite) {
            Some(AccessDirection::ReadWrite)
        } else if self.eat_kw(Kw::ReadOnly) {
            Some(AccessDirection::ReadOnly)
        } else {
            None
        };
        let span = self.span_from(start);
        self.end_decl("after the access declaration");
        Some(AccessDecl {
            name,
            path,
            ty,
            direction,
            span,
        })
    }

    /// `Res.Prog.fb.x [AT %QX1.0] : BOOL [:= TRUE];`
    fn config_init(&mut self) -> Option<ConfigInit> {
        let start = self.cur().start;
        let path = self.expr();
        let location = if self.at_kw(Kw::At) {
            self.location()
        } else {
            None
        };
        if !self.expect(Tok::Colon, "after the variable path") && !self.can_start_type() {
            self.recover_decl();
            return None;
        }
        let Some(ty) = self.type_spec() else {
            self.recover_decl();
            return None;
        };
        let init = if self.eat(Tok::ColonEq) {
            Some(self.initializer())
        } else {
            None
        };
        let span = self.span_from(start);
        self.end_decl("after the configuration variable");
        Some(ConfigInit {
            path,
            location,
            ty,
            init,
            span,
        })
    }
}
