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
            let v = v.trimmed();
            // CODESYS writes the schema's xsd:duration (`PT0.01S`).
            if attr == "interval" && v.text.starts_with('P') {
                match iso_duration(&v.text) {
                    Some(lit) => self.gen(&lit, t),
                    None => {
                        let sp = v.span(self.file);
                        self.error(
                            Code::E171,
                            sp,
                            format!("a task interval `{}` that is neither a TIME literal nor an xsd:duration of hours, minutes and seconds", v.text),
                        );
                        self.gen("T#0s", t);
                    }
                }
                continue;
            }
            self.expr_text(&v, t, false);
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

/// An xsd:duration `PT[nH][nM][n[.f]S]` (the form CODESYS writes for a
/// task's interval) as a TIME literal; None for any other form (years,
/// months and days are no task interval).
pub(crate) fn iso_duration(s: &str) -> Option<String> {
    let rest = s.strip_prefix("PT")?;
    if rest.is_empty() {
        return None;
    }
    let mut ns: u128 = 0;
    let mut num = String::new();
    for c in rest.chars() {
        match c {
            '0'..='9' | '.' => num.push(c),
            'H' | 'M' | 'S' if !num.is_empty() => {
                let (int, frac) = num.split_once('.').unwrap_or((num.as_str(), ""));
                if int.is_empty() && frac.is_empty() || frac.contains('.') || frac.len() > 9 {
                    return None;
                }
                let unit: u128 = match c {
                    'H' => 3_600_000_000_000,
                    'M' => 60_000_000_000,
                    _ => 1_000_000_000,
                };
                let whole: u128 = if int.is_empty() { 0 } else { int.parse().ok()? };
                let f: u128 = if frac.is_empty() {
                    0
                } else {
                    let digits: u128 = frac.parse().ok()?;
                    digits * 10u128.pow(9 - frac.len() as u32)
                };
                if c != 'S' && f != 0 {
                    return None;
                }
                ns = ns.checked_add(whole.checked_mul(unit)?)?.checked_add(f)?;
                num.clear();
            }
            _ => return None,
        }
    }
    if !num.is_empty() || ns > i64::MAX as u128 {
        return None;
    }
    Some(if ns.is_multiple_of(1_000_000) {
        format!("T#{}ms", ns / 1_000_000)
    } else if ns.is_multiple_of(1_000) {
        format!("T#{}us", ns / 1_000)
    } else {
        format!("T#{ns}ns")
    })
}

#[cfg(test)]
mod tests {
    use super::iso_duration;

    #[test]
    fn xsd_durations_of_task_intervals() {
        let cases = [
            ("PT0.01S", Some("T#10ms")),
            ("PT1S", Some("T#1000ms")),
            ("PT1M30S", Some("T#90000ms")),
            ("PT1H", Some("T#3600000ms")),
            ("PT0.000001S", Some("T#1us")),
            ("PT0.000000001S", Some("T#1ns")),
            ("PT.5S", Some("T#500ms")),
            ("P1D", None),
            ("PT", None),
            ("PT1.5M", None),
            ("PT1", None),
            ("PT1..2S", None),
            ("PT0.0000000001S", None),
            ("PT99999999999999999999999999H", None),
        ];
        for (s, want) in cases {
            assert_eq!(iso_duration(s).as_deref(), want, "{s}");
        }
    }
}
