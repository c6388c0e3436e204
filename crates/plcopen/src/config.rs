//! Configurations, resources, tasks, program instances and their globals.

use crate::xml;
use crate::Imp;
use automat_base::Code;
use roxmltree::Node;

impl Imp<'_> {
    /// `<configuration>` → `CONFIGURATION … END_CONFIGURATION`.
    pub fn configuration(&mut self, c: Node) {
        let Some(name) = self.name_attr(c, "name", "a configuration's name") else {
            return;
        };
        self.gen("\nCONFIGURATION ", c);
        self.out.copy(&name);
        self.gen("\n", c);
        for g in xml::children(c, "globalVars") {
            self.var_section(g, "VAR_GLOBAL");
        }
        for r in xml::children(c, "resource") {
            self.resource(r);
        }
        self.gen("\nEND_CONFIGURATION\n", c);
    }

    fn resource(&mut self, r: Node) {
        let Some(name) = self.name_attr(r, "name", "a resource's name") else {
            return;
        };
        self.gen("\nRESOURCE ", r);
        self.out.copy(&name);
        self.gen(" ON PLC\n", r);
        for g in xml::children(r, "globalVars") {
            self.var_section(g, "VAR_GLOBAL");
        }
        for t in xml::children(r, "task") {
            self.task(t);
        }
        for t in xml::children(r, "task") {
            let task = xml::attr(self.src, t, "name").map(|n| n.trimmed());
            for i in xml::children(t, "pouInstance") {
                self.instance(i, task.as_ref());
            }
        }
        for i in xml::children(r, "pouInstance") {
            self.instance(i, None);
        }
        self.gen("\nEND_RESOURCE\n", r);
    }

    /// `TASK name (INTERVAL := …, PRIORITY := …, SINGLE := …);`
    fn task(&mut self, t: Node) {
        let Some(name) = self.name_attr(t, "name", "a task's name") else {
            return;
        };
        self.gen("TASK ", t);
        self.out.copy(&name);
        self.gen(" (", t);
        let mut first = true;
        for (attr, prop) in [
            ("single", "SINGLE"),
            ("interval", "INTERVAL"),
            ("priority", "PRIORITY"),
        ] {
            let Some(v) = xml::attr(self.src, t, attr) else {
                continue;
            };
            if !first {
                self.gen(", ", t);
            }
            first = false;
            self.gen(prop, t);
            self.gen(" := ", t);
            self.expr_text(&v.trimmed(), t, false);
        }
        if first {
            self.gen("PRIORITY := 0", t);
        }
        self.gen(");\n", t);
    }

    /// `PROGRAM inst [WITH task] : Type;`
    fn instance(&mut self, i: Node, task: Option<&xml::Text>) {
        let Some(name) = self.name_attr(i, "name", "a program instance's name") else {
            return;
        };
        let Some(ty) = self.name_attr(i, "typeName", "a program instance's type") else {
            return;
        };
        self.gen("PROGRAM ", i);
        self.out.copy(&name);
        if let Some(task) = task {
            if crate::names::is_identifier(&task.text) {
                self.gen(" WITH ", i);
                self.out.copy(task);
            }
        }
        self.gen(" : ", i);
        self.out.copy(&ty);
        self.gen(";\n", i);
        if xml::elements(i).any(|e| !matches!(e.tag_name().name(), "documentation" | "addData")) {
            let sp = self.span(i);
            self.error(
                Code::E171,
                sp,
                "connections of a program instance are not supported",
            );
        }
    }
}
