//! The rules of classes and interfaces: inheritance, FINAL/ABSTRACT, interface methods, access (E200–E213).

use super::*;

impl<'a> Oop<'a> {
    pub(super) fn check_classes(&mut self) {
        for &c in self.order {
            let Some(cl) = self.class(c) else { continue };
            // Bases.
            let mut seen = vec![c];
            let mut cur = cl;
            while let Some(b) = cur.extends {
                if seen.len() > MAX_INHERITANCE {
                    break;
                }
                match self.class(b.sym) {
                    None => {
                        // Reported once, at the class that names it.
                        if cur.name.sym == c {
                            let n = self.name(b.sym);
                            self.err(Code::E200, b.span, format!("`{n}` is not a function block or class with which `EXTENDS` can be used here"));
                        }
                        self.broken.insert(c);
                        break;
                    }
                    Some(base) => {
                        if seen.contains(&b.sym) {
                            if cur.name.sym == c || b.sym == c {
                                let n = self.name(c);
                                self.err(
                                    Code::E202,
                                    cl.name.span,
                                    format!("`{n}` extends itself through its bases"),
                                );
                            }
                            self.broken.insert(c);
                            break;
                        }
                        if cur.name.sym == c {
                            if base.is_final {
                                let (n, bn) = (self.name(c), self.name(b.sym));
                                self.err(
                                    Code::E201,
                                    b.span,
                                    format!("`{n}` cannot extend `{bn}`: it is FINAL"),
                                );
                            }
                            if base.kind != cl.kind {
                                let n = self.name(b.sym);
                                self.err(
                                    Code::E200,
                                    b.span,
                                    format!(
                                        "`{n}` is a {} and cannot be the base of a {}",
                                        kind_name(base.kind),
                                        kind_name(cl.kind)
                                    ),
                                );
                            }
                        }
                        seen.push(b.sym);
                        cur = base;
                    }
                }
            }
            if !self.broken.contains(&c) && self.chain(c).len() > MAX_INHERITANCE + 1 {
                let n = self.name(c);
                self.err(
                    Code::E213,
                    cl.name.span,
                    format!("`{n}` has more than {MAX_INHERITANCE} levels of bases"),
                );
                self.broken.insert(c);
            }
            // Methods and properties of the class itself.
            let mut names: HashSet<Symbol> = HashSet::new();
            for b in &cl.var_blocks {
                for decl in &b.decls {
                    names.extend(decl.names.iter().map(|n| n.sym));
                }
            }
            for m in &cl.methods {
                if !names.insert(m.name.sym) {
                    let n = self.name(m.name.sym);
                    self.err(
                        Code::E209,
                        m.name.span,
                        format!("`{n}` is declared twice in `{}`", self.name(c)),
                    );
                }
                if m.is_abstract && !m.body.is_empty() {
                    let n = self.name(m.name.sym);
                    self.err(
                        Code::E203,
                        m.name.span,
                        format!("the ABSTRACT method `{n}` cannot have a body"),
                    );
                }
                if m.is_abstract && !cl.is_abstract {
                    let n = self.name(m.name.sym);
                    self.err(
                        Code::E203,
                        m.name.span,
                        format!(
                            "`{}` declares the ABSTRACT method `{n}` but is not ABSTRACT itself",
                            self.name(c)
                        ),
                    );
                }
                let base = cl
                    .extends
                    .map(|b| b.sym)
                    .filter(|_| !self.broken.contains(&c));
                let inherited = base.and_then(|b| self.method_of(b, m.name.sym));
                match inherited {
                    Some((k, bm)) if bm.is_final => {
                        let n = self.name(m.name.sym);
                        self.err(
                            Code::E201,
                            m.name.span,
                            format!(
                                "`{n}` cannot be overridden: it is FINAL in `{}`",
                                self.name(k)
                            ),
                        );
                    }
                    Some(_) => {}
                    None if m.is_override => {
                        let n = self.name(m.name.sym);
                        self.err(
                            Code::E211,
                            m.name.span,
                            format!(
                                "`{n}` is marked OVERRIDE but no base of `{}` declares it",
                                self.name(c)
                            ),
                        );
                    }
                    None => {}
                }
            }
            for p in &cl.properties {
                if !names.insert(p.name.sym) {
                    let n = self.name(p.name.sym);
                    self.err(
                        Code::E209,
                        p.name.span,
                        format!("`{n}` is declared twice in `{}`", self.name(c)),
                    );
                }
            }
            if self.broken.contains(&c) {
                continue;
            }
            // Inherited abstract methods must be implemented.
            if !cl.is_abstract {
                for (m, k, meth) in self.all_methods(c) {
                    if meth.is_abstract && k != c {
                        let n = self.name(m);
                        self.err(
                            Code::E203,
                            cl.name.span,
                            format!(
                                "`{}` does not implement the ABSTRACT method `{n}` of `{}`",
                                self.name(c),
                                self.name(k)
                            ),
                        );
                    }
                }
            }
            // Interfaces.
            for i in &cl.implements {
                if self.itf(i.sym).is_none() {
                    let n = self.name(i.sym);
                    self.err(Code::E200, i.span, format!("`{n}` is not an interface"));
                    continue;
                }
                for k in self.itf_chain(i.sym) {
                    let Some(it) = self.itf(k) else { continue };
                    for im in &it.methods {
                        match self.method_of(c, im.name.sym) {
                            None => {
                                let n = self.name(im.name.sym);
                                self.bad_impl.insert(c);
                                self.err(Code::E205, i.span, format!("`{}` does not implement the method `{n}` of interface `{}`", self.name(c), self.name(k)));
                            }
                            Some((_, m)) if !same_type(&m.return_type, &im.return_type) => {
                                let n = self.name(im.name.sym);
                                self.bad_impl.insert(c);
                                self.err(
                                    Code::E205,
                                    m.name.span,
                                    format!(
                                        "`{n}` must return what interface `{}` declares",
                                        self.name(k)
                                    ),
                                );
                            }
                            _ => {}
                        }
                    }
                    for ip in &it.properties {
                        if self.property_of(c, ip.name.sym).is_none() {
                            let n = self.name(ip.name.sym);
                            self.bad_impl.insert(c);
                            self.err(
                                Code::E205,
                                i.span,
                                format!(
                                    "`{}` does not implement the property `{n}` of interface `{}`",
                                    self.name(c),
                                    self.name(k)
                                ),
                            );
                        }
                    }
                }
            }
        }
    }

    pub(super) fn check_interfaces(&mut self) {
        let mut list: Vec<&Interface> = self.itfs.values().map(|(_, i)| i).collect();
        list.sort_by_key(|i| i.span.start);
        for it in list {
            // The hidden `<B>^` of a base class: checked as the class.
            if self.poly_class.contains_key(&it.name.sym) {
                continue;
            }
            for e in &it.extends {
                if self.itf(e.sym).is_none() {
                    let n = self.name(e.sym);
                    self.err(Code::E200, e.span, format!("`{n}` is not an interface"));
                } else if e.sym == it.name.sym || self.itf_chain(e.sym).contains(&it.name.sym) {
                    let n = self.name(it.name.sym);
                    self.err(
                        Code::E202,
                        e.span,
                        format!("interface `{n}` extends itself"),
                    );
                }
            }
            let mut names = HashSet::new();
            for m in &it.methods {
                if !names.insert(m.name.sym) {
                    let n = self.name(m.name.sym);
                    self.err(
                        Code::E209,
                        m.name.span,
                        format!(
                            "`{n}` is declared twice in interface `{}`",
                            self.name(it.name.sym)
                        ),
                    );
                }
            }
        }
    }
}
