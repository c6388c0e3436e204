//! A checked project as PLCopen TC6 2.01 XML (`automat export`).
//!
//! What was read from a PLCopen file (a POU, a data type, a configuration)
//! is written back as the file had it, graphics included: its span is the
//! element. What was read from Structured Text is written from the tree,
//! with names, expressions and bodies as their source text: declarations
//! as TC6 elements, ST, IL and textual SFC bodies as text (`<ST>` / `<IL>`:
//! a textual chart stays textual, inside an ST body). Output is
//! deterministic (a fixed creation date). What TC6 has no place for is
//! E178.

use automat_base::{Code, Diagnostic, SourceMap, Span};
use automat_syntax::ast::*;
use std::fmt::Write;

struct Ex<'a> {
    sources: &'a SourceMap,
    diags: Vec<Diagnostic>,
}

/// `&`, `<`, `>`, `"` as entities (attribute values and text).
fn esc(s: &str) -> String {
    let mut o = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => o.push_str("&amp;"),
            '<' => o.push_str("&lt;"),
            '>' => o.push_str("&gt;"),
            '"' => o.push_str("&quot;"),
            c => o.push(c),
        }
    }
    o
}

/// A CDATA section holding `s` (a `]]>` inside is split across two).
fn cdata(s: &str) -> String {
    format!("<![CDATA[{}]]>", s.replace("]]>", "]]]]><![CDATA[>"))
}

impl Ex<'_> {
    fn text(&self, sp: Span) -> &str {
        if (sp.file.0 as usize) >= self.sources.len() {
            return "";
        }
        self.sources.get(sp.file).text.get(sp.range()).unwrap_or("")
    }

    fn is_xml(&self, sp: Span) -> bool {
        (sp.file.0 as usize) < self.sources.len()
            && crate::is_plcopen_file(&self.sources.get(sp.file).name)
    }

    fn err(&mut self, sp: Span, msg: impl Into<String>) {
        self.diags.push(Diagnostic::error(Code::E178, sp, msg));
    }

    fn name(&self, i: &Ident) -> String {
        esc(self.text(i.span))
    }

    fn ty(&mut self, o: &mut String, t: &TypeSpec) {
        match t {
            TypeSpec::Named(i) => {
                let n = self.text(i.span).to_string();
                match crate::decl::tc6_element(&n) {
                    Some(tag) => {
                        let _ = write!(o, "<{tag}/>");
                    }
                    None => {
                        let _ = write!(o, "<derived name=\"{}\"/>", esc(&n));
                    }
                }
            }
            TypeSpec::String { wide, len, .. } => {
                let tag = if *wide { "wstring" } else { "string" };
                match len {
                    Some(l) => {
                        let _ = write!(o, "<{tag} length=\"{}\"/>", esc(self.text(l.span)));
                    }
                    None => {
                        let _ = write!(o, "<{tag}/>");
                    }
                }
            }
            TypeSpec::Array { dims, elem, span } => {
                o.push_str("<array>");
                for d in dims {
                    match d {
                        ArrayDim::Range { lo, hi, .. } => {
                            let _ = write!(
                                o,
                                "<dimension lower=\"{}\" upper=\"{}\"/>",
                                esc(self.text(lo.span)),
                                esc(self.text(hi.span))
                            );
                        }
                        ArrayDim::Star(_) => self.err(*span, "`ARRAY [*]` has no TC6 form"),
                    }
                }
                o.push_str("<baseType>");
                self.ty(o, elem);
                o.push_str("</baseType></array>");
            }
            TypeSpec::Subrange { base, lo, hi, .. } => {
                let b = self.text(base.span).to_ascii_uppercase();
                let tag = if b.starts_with('U') {
                    "subrangeUnsigned"
                } else {
                    "subrangeSigned"
                };
                let _ = write!(
                    o,
                    "<{tag}><range lower=\"{}\" upper=\"{}\"/><baseType>",
                    esc(self.text(lo.span)),
                    esc(self.text(hi.span))
                );
                self.ty(o, &TypeSpec::Named(*base));
                let _ = write!(o, "</baseType></{tag}>");
            }
            TypeSpec::Enum { base, values, .. } => {
                o.push_str("<enum><values>");
                for v in values {
                    match &v.value {
                        Some(e) => {
                            let _ = write!(
                                o,
                                "<value name=\"{}\" value=\"{}\"/>",
                                self.name(&v.name),
                                esc(self.text(e.span))
                            );
                        }
                        None => {
                            let _ = write!(o, "<value name=\"{}\"/>", self.name(&v.name));
                        }
                    }
                }
                o.push_str("</values>");
                if let Some(b) = base {
                    o.push_str("<baseType>");
                    self.ty(o, &TypeSpec::Named(*b));
                    o.push_str("</baseType>");
                }
                o.push_str("</enum>");
            }
            TypeSpec::Struct { members, .. } => {
                o.push_str("<struct>");
                for m in members {
                    self.var(o, m);
                }
                o.push_str("</struct>");
            }
            TypeSpec::Ref { target, .. } => {
                o.push_str("<pointer><baseType>");
                self.ty(o, target);
                o.push_str("</baseType></pointer>");
            }
        }
    }

    fn init(&mut self, o: &mut String, i: &Initializer) {
        match i {
            Initializer::Expr(e) => {
                let _ = write!(o, "<simpleValue value=\"{}\"/>", esc(self.text(e.span)));
            }
            Initializer::Array { elems, .. } => {
                o.push_str("<arrayValue>");
                for e in elems {
                    match &e.repeat {
                        Some(r) => {
                            let _ =
                                write!(o, "<value repetitionValue=\"{}\">", esc(self.text(r.span)));
                        }
                        None => o.push_str("<value>"),
                    }
                    match &e.value {
                        Some(v) => self.init(o, v),
                        None => self.err(e.span, "an empty repeated array element has no TC6 form"),
                    }
                    o.push_str("</value>");
                }
                o.push_str("</arrayValue>");
            }
            Initializer::Struct { fields, .. } => {
                o.push_str("<structValue>");
                for f in fields {
                    let _ = write!(o, "<value member=\"{}\">", self.name(&f.name));
                    self.init(o, &f.value);
                    o.push_str("</value>");
                }
                o.push_str("</structValue>");
            }
        }
    }

    fn var(&mut self, o: &mut String, d: &VarDecl) {
        if d.edge.is_some() {
            self.err(d.span, "an R_EDGE/F_EDGE input has no TC6 form");
        }
        for n in &d.names {
            let _ = write!(o, "<variable name=\"{}\"", self.name(n));
            if let Some(l) = &d.location {
                let _ = write!(o, " address=\"{}\"", esc(self.text(l.addr.span)));
            }
            o.push_str("><type>");
            self.ty(o, &d.ty);
            o.push_str("</type>");
            if let Some(i) = &d.init {
                o.push_str("<initialValue>");
                self.init(o, i);
                o.push_str("</initialValue>");
            }
            o.push_str("</variable>\n");
        }
    }

    /// A declared section (generated ones, such as IL's `__CR` or a
    /// chart's step instances, are not: they come back on import).
    fn declared(&self, b: &VarBlock) -> bool {
        self.text(b.span)
            .get(..3)
            .is_some_and(|k| k.eq_ignore_ascii_case("VAR"))
    }

    fn section(&mut self, o: &mut String, b: &VarBlock) {
        let tag = match b.kind {
            // VAR_STAT has no TC6 section; the dialect turns it into globals first.
            VarKind::Local | VarKind::Static | VarKind::Inst => "localVars",
            VarKind::Input => "inputVars",
            VarKind::Output => "outputVars",
            VarKind::InOut => "inOutVars",
            VarKind::External => "externalVars",
            VarKind::Global => "globalVars",
            VarKind::Temp => "tempVars",
        };
        let _ = write!(o, "<{tag}");
        if b.constant {
            o.push_str(" constant=\"true\"");
        }
        match b.retain {
            Retain::Retain => o.push_str(" retain=\"true\""),
            Retain::NonRetain => o.push_str(" nonretain=\"true\""),
            Retain::Unspecified => {}
        }
        o.push_str(">\n");
        for d in &b.decls {
            self.var(o, d);
        }
        let _ = writeln!(o, "</{tag}>");
    }

    fn pou(&mut self, o: &mut String, p: &Pou) {
        if self.is_xml(p.span) {
            o.push_str(self.text(p.span));
            o.push('\n');
            return;
        }
        let (kind, end_kw) = match p.kind {
            PouKind::Program => ("program", "END_PROGRAM"),
            PouKind::FunctionBlock => ("functionBlock", "END_FUNCTION_BLOCK"),
            PouKind::Function => ("function", "END_FUNCTION"),
        };
        let _ = writeln!(
            o,
            "<pou name=\"{}\" pouType=\"{kind}\">\n<interface>",
            self.name(&p.name)
        );
        if let Some(rt) = &p.return_type {
            o.push_str("<returnType>");
            self.ty(o, rt);
            o.push_str("</returnType>\n");
        }
        let mut body_start = p
            .return_type
            .as_ref()
            .map_or(p.name.span.end, |t| t.span().end);
        let declared: Vec<&VarBlock> = p.var_blocks.iter().filter(|b| self.declared(b)).collect();
        for b in declared {
            self.section(o, b);
            body_start = body_start.max(b.span.end);
        }
        o.push_str("</interface>\n");
        // The body is the text between the declarations and END_<kind>.
        let src = self.text(Span::new(p.span.file, body_start, p.span.end));
        let body = match src.len().checked_sub(end_kw.len()) {
            Some(cut)
                if src
                    .get(cut..)
                    .is_some_and(|k| k.eq_ignore_ascii_case(end_kw)) =>
            {
                src.get(..cut).unwrap_or("")
            }
            _ => src,
        };
        let lang = if matches!(p.lang, Lang::Il(_)) {
            "IL"
        } else {
            "ST"
        };
        let _ = writeln!(
            o,
            "<body><{lang}><xhtml:p>{}</xhtml:p></{lang}></body>\n</pou>",
            cdata(body)
        );
    }

    fn data_types(&mut self, o: &mut String, t: &TypeBlock) {
        if self.is_xml(t.span) {
            o.push_str(self.text(t.span));
            o.push('\n');
            return;
        }
        for d in &t.decls {
            let _ = write!(o, "<dataType name=\"{}\"><baseType>", self.name(&d.name));
            self.ty(o, &d.spec);
            o.push_str("</baseType>");
            if let Some(i) = &d.init {
                o.push_str("<initialValue>");
                self.init(o, i);
                o.push_str("</initialValue>");
            }
            o.push_str("</dataType>\n");
        }
    }

    fn config(&mut self, o: &mut String, c: &Configuration) {
        if self.is_xml(c.span) {
            o.push_str(self.text(c.span));
            o.push('\n');
            return;
        }
        if !c.access.is_empty() || !c.var_config.is_empty() {
            self.err(c.span, "VAR_ACCESS and VAR_CONFIG are not exported");
        }
        let _ = writeln!(o, "<configuration name=\"{}\">", self.name(&c.name));
        for r in &c.resources {
            let name = if r.implicit {
                "Resource".to_string()
            } else {
                self.name(&r.name)
            };
            let _ = writeln!(o, "<resource name=\"{name}\">");
            for t in &r.tasks {
                let _ = write!(o, "<task name=\"{}\"", self.name(&t.name));
                let mut priority = false;
                for p in &t.props {
                    let key = self.text(p.name.span).to_ascii_lowercase();
                    priority |= key == "priority";
                    let _ = write!(o, " {key}=\"{}\"", esc(self.text(p.value.span)));
                }
                if !priority {
                    o.push_str(" priority=\"0\"");
                }
                o.push_str(">\n");
                let tname = self.text(t.name.span).to_ascii_uppercase();
                let mine: Vec<&ProgramConfig> = r
                    .programs
                    .iter()
                    .filter(|p| {
                        p.task
                            .is_some_and(|tk| self.text(tk.span).to_ascii_uppercase() == tname)
                    })
                    .collect();
                for p in mine {
                    self.instance(o, p);
                }
                o.push_str("</task>\n");
            }
            for b in &r.globals {
                self.section(o, b);
            }
            for p in r.programs.iter().filter(|p| p.task.is_none()) {
                self.instance(o, p);
            }
            o.push_str("</resource>\n");
        }
        for b in &c.globals {
            self.section(o, b);
        }
        o.push_str("</configuration>\n");
    }

    fn instance(&mut self, o: &mut String, p: &ProgramConfig) {
        if !p.conns.is_empty() {
            self.err(p.span, "connections of a program instance are not exported");
        }
        let _ = writeln!(
            o,
            "<pouInstance name=\"{}\" typeName=\"{}\"/>",
            self.name(&p.name),
            self.name(&p.ty)
        );
    }
}

/// Writes `units` (checked, from `sources`) as one TC6 2.01 project.
pub fn export(
    units: &[SourceUnit],
    sources: &SourceMap,
    name: &str,
) -> Result<String, Vec<Diagnostic>> {
    let mut ex = Ex {
        sources,
        diags: Vec::new(),
    };
    let (mut types, mut pous, mut configs) = (String::new(), String::new(), String::new());
    for u in units {
        for item in &u.items {
            match item {
                Item::Types(t) => ex.data_types(&mut types, t),
                Item::Pou(p) => ex.pou(&mut pous, p),
                Item::Config(c) => ex.config(&mut configs, c),
                Item::Class(c) => ex.err(
                    c.name.span,
                    format!(
                        "{} `{}` has methods, inheritance or interfaces, which TC6 2.01 XML cannot hold",
                        match c.kind {
                            automat_syntax::ast::oop::ClassKind::Class => "class",
                            automat_syntax::ast::oop::ClassKind::FunctionBlock => "function block",
                        },
                        ex.text(c.name.span)
                    ),
                ),
                Item::Interface(i) => ex.err(
                    i.name.span,
                    format!(
                        "interface `{}`: TC6 2.01 XML has no interfaces",
                        ex.text(i.name.span)
                    ),
                ),
                Item::Namespace(n) => ex.err(
                    n.span,
                    "a NAMESPACE (or a POU's USING) has no place in TC6 2.01 XML",
                ),
                Item::Globals(g) => ex.err(
                    g.span,
                    "a VAR_GLOBAL outside a CONFIGURATION has no place in TC6 XML: declare it in a configuration",
                ),
            }
        }
    }
    if !ex.diags.is_empty() {
        return Err(ex.diags);
    }
    Ok(format!(
        r#"<?xml version="1.0" encoding="utf-8"?>
<project xmlns="http://www.plcopen.org/xml/tc6_0201" xmlns:xhtml="http://www.w3.org/1999/xhtml">
<fileHeader companyName="automat" productName="automat" productVersion="{}" creationDateTime="1970-01-01T00:00:00"/>
<contentHeader name="{}">
<coordinateInfo><fbd><scaling x="1" y="1"/></fbd><ld><scaling x="1" y="1"/></ld><sfc><scaling x="1" y="1"/></sfc></coordinateInfo>
</contentHeader>
<types>
<dataTypes>
{types}</dataTypes>
<pous>
{pous}</pous>
</types>
<instances>
<configurations>
{configs}</configurations>
</instances>
</project>
"#,
        env!("CARGO_PKG_VERSION"),
        esc(name)
    ))
}
