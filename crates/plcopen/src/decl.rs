//! Data types, variable sections, types and initial values as ST.

use crate::names::is_identifier;
use crate::xml::{self, Text};
use crate::Imp;
use automat_base::Code;
use roxmltree::Node;

/// Elementary type elements of TC6, and the ST name each stands for (the
/// importer also takes the long names and LTIME/CHAR/WCHAR, which the 2.01
/// schema lacks; see [`tc6_element`] for the other direction).
const ELEMENTARY: &[(&str, &str)] = &[
    ("BOOL", "BOOL"),
    ("BYTE", "BYTE"),
    ("WORD", "WORD"),
    ("DWORD", "DWORD"),
    ("LWORD", "LWORD"),
    ("SINT", "SINT"),
    ("INT", "INT"),
    ("DINT", "DINT"),
    ("LINT", "LINT"),
    ("USINT", "USINT"),
    ("UINT", "UINT"),
    ("UDINT", "UDINT"),
    ("ULINT", "ULINT"),
    ("REAL", "REAL"),
    ("LREAL", "LREAL"),
    ("TIME", "TIME"),
    ("LTIME", "LTIME"),
    ("DATE", "DATE"),
    ("DT", "DT"),
    ("TOD", "TOD"),
    ("DATE_AND_TIME", "DT"),
    ("TIME_OF_DAY", "TOD"),
    ("CHAR", "CHAR"),
    ("WCHAR", "WCHAR"),
];

/// The names of [`ELEMENTARY`] that are no element of the TC6 2.01 schema.
const NOT_IN_TC6_2_01: &[&str] = &["LTIME", "DATE_AND_TIME", "TIME_OF_DAY", "CHAR", "WCHAR"];

/// The TC6 2.01 element for the elementary ST type `st_name` (any case;
/// `DATE_AND_TIME` is `DT`), or `None` for a type the schema has no element
/// for (written as `derived`, which [`ELEMENTARY`] reads back as the same name).
pub(crate) fn tc6_element(st_name: &str) -> Option<&'static str> {
    let (_, st) = ELEMENTARY
        .iter()
        .find(|(tag, _)| tag.eq_ignore_ascii_case(st_name))?;
    (!NOT_IN_TC6_2_01.contains(st)).then_some(*st)
}

/// Variable sections of an interface and their ST keyword.
pub const SECTIONS: &[(&str, &str)] = &[
    ("inputVars", "VAR_INPUT"),
    ("outputVars", "VAR_OUTPUT"),
    ("inOutVars", "VAR_IN_OUT"),
    ("externalVars", "VAR_EXTERNAL"),
    ("globalVars", "VAR_GLOBAL"),
    ("localVars", "VAR"),
    ("tempVars", "VAR_TEMP"),
];

impl Imp<'_> {
    /// `<dataType name="T"><baseType>…</baseType><initialValue>…` →
    /// `TYPE T : spec := init; END_TYPE`.
    pub fn data_type(&mut self, dt: Node) {
        let Some(name) = self.name_attr(dt, "name", "a data type's name") else {
            return;
        };
        let Some(base) = xml::child(dt, "baseType") else {
            let sp = self.span(dt);
            self.error(
                Code::E171,
                sp,
                format!("data type `{}` has no `baseType`", name.text),
            );
            return;
        };
        self.gen("\nTYPE ", dt);
        self.out.copy(&name);
        self.gen(" : ", dt);
        self.type_of(base, true);
        if let Some(init) = xml::child(dt, "initialValue") {
            self.gen(" := ", init);
            self.initial(init);
        }
        self.gen(";\nEND_TYPE\n", dt);
    }

    /// A variable section: `VAR_INPUT [CONSTANT] [RETAIN] decls END_VAR`.
    pub fn var_section(&mut self, sec: Node, keyword: &str) {
        self.gen("\n", sec);
        self.gen(keyword, sec);
        if xml::flag(sec, "constant") {
            self.gen(" CONSTANT", sec);
        }
        if xml::flag(sec, "retain") {
            self.gen(" RETAIN", sec);
        } else if xml::flag(sec, "nonretain") {
            self.gen(" NON_RETAIN", sec);
        }
        self.gen("\n", sec);
        for v in xml::children(sec, "variable") {
            self.variable(v);
        }
        self.gen("END_VAR\n", sec);
    }

    /// `<variable name address><type/><initialValue/></variable>`.
    pub fn variable(&mut self, v: Node) {
        let Some(name) = self.name_attr(v, "name", "a variable's name") else {
            return;
        };
        let Some(ty) = xml::child(v, "type") else {
            let sp = self.span(v);
            self.error(
                Code::E171,
                sp,
                format!("variable `{}` has no `type`", name.text),
            );
            return;
        };
        self.out.copy(&name);
        if let Some(addr) = xml::attr(self.src, v, "address") {
            let addr = addr.trimmed();
            if addr.text.starts_with('%')
                && addr
                    .text
                    .chars()
                    .skip(1)
                    .all(|c| c.is_ascii_alphanumeric() || c == '.' || c == '*')
            {
                self.gen(" AT ", v);
                self.out.copy(&addr);
            } else {
                let sp = addr.span(self.file);
                self.error(
                    Code::E171,
                    sp,
                    format!("`{}` is not a direct address (`%IX0.1`, `%QW2`)", addr.text),
                );
            }
        }
        self.gen(" : ", v);
        self.type_of(ty, false);
        if let Some(init) = xml::child(v, "initialValue") {
            self.gen(" := ", init);
            self.initial(init);
        }
        self.gen(";\n", v);
    }

    /// The type held by a `<type>` / `<baseType>` element.
    pub fn type_of(&mut self, holder: Node, in_type_decl: bool) {
        let Some(t) = xml::elements(holder).next() else {
            let sp = self.span(holder);
            self.error(Code::E171, sp, "a type element is empty");
            self.gen("INT", holder);
            return;
        };
        let tag = t.tag_name().name();
        if let Some((_, st)) = ELEMENTARY.iter().find(|(x, _)| *x == tag) {
            self.gen(st, t);
            return;
        }
        match tag {
            "string" | "wstring" => {
                self.gen(if tag == "string" { "STRING" } else { "WSTRING" }, t);
                if let Some(len) = xml::attr_str(t, "length") {
                    if let Ok(n) = len.trim().parse::<u32>() {
                        self.gen(&format!("[{n}]"), t);
                    } else {
                        let sp = self.span(t);
                        self.error(
                            Code::E171,
                            sp,
                            format!("string length `{len}` is not a number"),
                        );
                    }
                }
            }
            "derived" => match self.name_attr(t, "name", "a derived type's name") {
                Some(n) => self.out.copy(&n),
                None => self.gen("INT", t),
            },
            "array" => {
                self.gen("ARRAY [", t);
                let mut first = true;
                for d in xml::children(t, "dimension") {
                    if !first {
                        self.gen(", ", d);
                    }
                    first = false;
                    self.bound(d, "lower");
                    self.gen("..", d);
                    self.bound(d, "upper");
                }
                if first {
                    let sp = self.span(t);
                    self.error(Code::E171, sp, "an array without a `dimension`");
                    self.gen("0..0", t);
                }
                self.gen("] OF ", t);
                match xml::child(t, "baseType") {
                    Some(b) => self.type_of(b, false),
                    None => {
                        let sp = self.span(t);
                        self.error(Code::E171, sp, "an array without a `baseType`");
                        self.gen("INT", t);
                    }
                }
            }
            "enum" => {
                let base = xml::child(t, "baseType");
                if let Some(b) = base.filter(|b| xml::elements(*b).next().is_some()) {
                    self.type_of(b, false);
                    self.gen(" ", t);
                }
                self.gen("(", t);
                let mut first = true;
                if let Some(vals) = xml::child(t, "values") {
                    for v in xml::children(vals, "value") {
                        let Some(n) = self.name_attr(v, "name", "an enumeration value") else {
                            continue;
                        };
                        if !first {
                            self.gen(", ", v);
                        }
                        first = false;
                        self.out.copy(&n);
                        if let Some(x) = xml::attr(self.src, v, "value") {
                            self.gen(" := ", v);
                            self.out.copy(&x.trimmed());
                        }
                    }
                }
                if first {
                    let sp = self.span(t);
                    self.error(Code::E171, sp, "an enumeration without values");
                    self.gen("__EMPTY", t);
                }
                self.gen(")", t);
            }
            "subrangeSigned" | "subrangeUnsigned" => {
                match xml::child(t, "baseType") {
                    Some(b) => self.type_of(b, false),
                    None => self.gen(
                        if tag == "subrangeSigned" {
                            "DINT"
                        } else {
                            "UDINT"
                        },
                        t,
                    ),
                }
                self.gen(" (", t);
                match xml::child(t, "range") {
                    Some(r) => {
                        self.bound(r, "lower");
                        self.gen("..", r);
                        self.bound(r, "upper");
                    }
                    None => {
                        let sp = self.span(t);
                        self.error(Code::E171, sp, "a subrange without a `range`");
                        self.gen("0..0", t);
                    }
                }
                self.gen(")", t);
            }
            "struct" => {
                if !in_type_decl {
                    let sp = self.span(t);
                    self.error(
                        Code::E171,
                        sp,
                        "an anonymous structure type: declare it as a data type and name it",
                    );
                }
                self.gen("STRUCT\n", t);
                for v in xml::children(t, "variable") {
                    self.variable(v);
                }
                self.gen("END_STRUCT", t);
            }
            "pointer" => {
                self.gen("REF_TO ", t);
                match xml::child(t, "baseType") {
                    Some(b) => self.type_of(b, false),
                    None => self.gen("BYTE", t),
                }
            }
            other => {
                let sp = self.span(t);
                self.error(Code::E171, sp, format!("unknown type element `{other}`"));
                self.gen("INT", t);
            }
        }
    }

    /// An array or subrange bound: a (possibly signed) integer, or a
    /// constant's name.
    fn bound(&mut self, n: Node, attr: &str) {
        let Some(t) = xml::attr(self.src, n, attr) else {
            let sp = self.span(n);
            self.error(
                Code::E171,
                sp,
                format!("`{}` without `{attr}`", n.tag_name().name()),
            );
            self.gen("0", n);
            return;
        };
        let t = t.trimmed();
        let s = t.text.strip_prefix('-').unwrap_or(&t.text);
        if !s.is_empty() && (s.chars().all(|c| c.is_ascii_digit() || c == '_') || is_identifier(s))
        {
            self.out.copy(&t);
        } else {
            let sp = t.span(self.file);
            self.error(
                Code::E171,
                sp,
                format!("bound `{}` is not an integer", t.text),
            );
            self.gen("0", n);
        }
    }

    /// `<initialValue>` (or a `<value>` inside one): simple, array and
    /// structure values.
    pub fn initial(&mut self, holder: Node) {
        let Some(v) = xml::elements(holder).next() else {
            let sp = self.span(holder);
            self.error(Code::E171, sp, "an empty initial value");
            self.gen("0", holder);
            return;
        };
        match v.tag_name().name() {
            "simpleValue" => match xml::attr(self.src, v, "value") {
                Some(t) => self.expr_text(&t.trimmed(), v, false),
                None => {
                    let sp = self.span(v);
                    self.error(Code::E171, sp, "a `simpleValue` without `value`");
                    self.gen("0", v);
                }
            },
            "arrayValue" => {
                self.gen("[", v);
                let mut first = true;
                for e in xml::children(v, "value") {
                    if !first {
                        self.gen(", ", e);
                    }
                    first = false;
                    let rep = xml::attr_str(e, "repetitionValue").map(str::trim);
                    match rep {
                        Some(r) if r.chars().all(|c| c.is_ascii_digit()) && !r.is_empty() => {
                            self.gen(&format!("{r}("), e);
                            self.initial(e);
                            self.gen(")", e);
                        }
                        _ => self.initial(e),
                    }
                }
                self.gen("]", v);
            }
            "structValue" => {
                self.gen("(", v);
                let mut first = true;
                for e in xml::children(v, "value") {
                    let Some(m) = self.name_attr(e, "member", "a structure member") else {
                        continue;
                    };
                    if !first {
                        self.gen(", ", e);
                    }
                    first = false;
                    self.out.copy(&m);
                    self.gen(" := ", e);
                    self.initial(e);
                }
                self.gen(")", v);
            }
            other => {
                let sp = self.span(v);
                self.error(
                    Code::E171,
                    sp,
                    format!("unknown initial value element `{other}`"),
                );
                self.gen("0", v);
            }
        }
    }

    /// An expression written in the file (a value, a variable's expression):
    /// copied (in parentheses with `paren`, so it stays one operand wherever
    /// it is used; an initial value must not be, `(` would open a structure). A `;` or a keyword ending a
    /// declaration would change what surrounds it, so such text is refused.
    pub fn expr_text(&mut self, t: &Text, n: Node, paren: bool) {
        if t.text.is_empty() || !safe_expr(&t.text) {
            let sp = if t.text.is_empty() {
                self.span(n)
            } else {
                t.span(self.file)
            };
            self.error(Code::E171, sp, format!("`{}` is not an expression", t.text));
            self.gen("0", n);
            return;
        }
        if paren {
            self.gen("(", n);
        }
        self.out.copy(t);
        if paren {
            self.gen(")", n);
        }
    }
}

/// Text that can stand as one expression in the generated program: no `;`
/// or comment opener outside string literals, balanced brackets.
pub fn safe_expr(s: &str) -> bool {
    let mut depth = 0i32;
    let mut quote: Option<char> = None;
    let mut prev = ' ';
    for c in s.chars() {
        match quote {
            Some(q) => {
                if c == q {
                    quote = None;
                }
            }
            None => match c {
                '\'' | '"' => quote = Some(c),
                '(' | '[' => depth += 1,
                ')' | ']' => {
                    depth -= 1;
                    if depth < 0 {
                        return false;
                    }
                }
                ';' => return false,
                '*' if prev == '(' => return false,
                '/' if prev == '/' => return false,
                '*' if prev == '/' => return false,
                _ => {}
            },
        }
        prev = c;
    }
    depth == 0 && quote.is_none()
}
