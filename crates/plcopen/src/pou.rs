//! POUs: the interface as variable sections, the body in its language.

use crate::decl::SECTIONS;
use crate::xml;
use crate::Imp;
use automat_base::Code;
use roxmltree::Node;

impl Imp<'_> {
    /// `<pou name pouType>` → `PROGRAM name … END_PROGRAM` (or FB, FUNCTION).
    pub fn pou(&mut self, p: Node) {
        let Some(name) = self.name_attr(p, "name", "a POU's name") else {
            return;
        };
        let kw = match xml::attr_str(p, "pouType") {
            Some("program") => "PROGRAM",
            Some("functionBlock") => "FUNCTION_BLOCK",
            Some("function") => "FUNCTION",
            other => {
                let sp = self.span(p);
                self.error(
                    Code::E171,
                    sp,
                    format!(
                        "POU `{}`: `pouType` is {}, not program, functionBlock or function",
                        name.text,
                        other.map_or("missing".to_string(), |o| format!("`{o}`"))
                    ),
                );
                return;
            }
        };
        self.gen("\n", p);
        self.gen(kw, p);
        self.gen(" ", p);
        self.out.copy(&name);
        let iface = xml::child(p, "interface");
        if kw == "FUNCTION" {
            match iface.and_then(|i| xml::child(i, "returnType")) {
                Some(rt) => {
                    self.gen(" : ", rt);
                    self.type_of(rt, false);
                }
                None => {
                    let sp = self.span(p);
                    self.error(
                        Code::E171,
                        sp,
                        format!("function `{}` has no `returnType`", name.text),
                    );
                }
            }
        }
        self.gen("\n", p);
        if let Some(iface) = iface {
            for sec in xml::elements(iface) {
                let tag = sec.tag_name().name();
                if let Some((_, kw)) = SECTIONS.iter().find(|(t, _)| *t == tag) {
                    self.var_section(sec, kw);
                } else if !matches!(tag, "returnType" | "documentation" | "addData") {
                    let sp = self.span(sec);
                    self.error(
                        Code::E171,
                        sp,
                        format!(
                            "POU `{}`: the interface section `{tag}` is not supported",
                            name.text
                        ),
                    );
                }
            }
        }
        let pou_name = name.text.clone();
        let mut ctx = automat_syntax::graphic::PouCtx::new(&pou_name, kw == "FUNCTION");
        let sfc = xml::child(p, "body")
            .and_then(|b| xml::child(b, "SFC"))
            .is_some();
        let mut macros = Vec::new();
        match xml::child(p, "body") {
            Some(body) if sfc => {
                if let Some(chart) = xml::child(body, "SFC") {
                    macros = self.sfc(chart, p, &pou_name);
                }
            }
            Some(body) => self.body(body, &mut ctx),
            None => {
                let sp = self.span(p);
                self.error(Code::E171, sp, format!("POU `{pou_name}` has no `body`"));
            }
        }
        let extra = ["actions", "transitions"]
            .iter()
            .filter_map(|t| xml::child(p, t))
            .find(|a| xml::elements(*a).next().is_some());
        if let Some(acts) = extra.filter(|_| !sfc) {
            let sp = self.span(acts);
            self.error(
                Code::E171,
                sp,
                format!("POU `{pou_name}`: actions and transitions are only read for an SFC body"),
            );
        }
        self.gen("\nEND_", p);
        self.gen(kw, p);
        self.gen("\n", p);
        self.macro_bodies(macros, p, &pou_name);
    }

    /// A `<body>`: ST and IL copied as written, LD and FBD lowered.
    fn body(&mut self, body: Node, ctx: &mut automat_syntax::graphic::PouCtx) {
        let Some(lang) = xml::elements(body)
            .find(|e| e.tag_name().name() != "documentation" && e.tag_name().name() != "addData")
        else {
            return;
        };
        match lang.tag_name().name() {
            "ST" | "IL" => {
                let t = xml::formatted(self.src, lang);
                self.gen("\n", lang);
                self.out.copy(&t);
                self.gen("\n", lang);
            }
            "LD" | "FBD" => {
                let net = crate::graph::network(self, lang, ctx.pou());
                let lowered = automat_syntax::graphic::lower(&net, ctx);
                self.diags.extend(lowered.diagnostics.iter().cloned());
                lowered.write(&mut self.out);
            }
            other => {
                let sp = self.span(lang);
                self.error(
                    Code::E171,
                    sp,
                    format!(
                        "POU `{}`: `{other}` bodies are not supported yet",
                        ctx.pou()
                    ),
                );
            }
        }
    }
}
