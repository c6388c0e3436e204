//! Declarations: class and interface types in variable declarations, and the POU rewrite entry.

use super::*;

impl<'a> Oop<'a> {
    pub(super) fn retype_block(&mut self, b: &mut VarBlock) {
        let kind = b.kind;
        for decl in &mut b.decls {
            self.retype_decl(decl, kind);
        }
    }

    /// Interface types become their structures; an instance of an abstract
    /// class is refused.
    pub(super) fn retype_decl(&mut self, decl: &mut VarDecl, kind: VarKind) {
        self.retype_spec(&mut decl.ty, kind);
    }

    pub(super) fn retype_spec(&mut self, ty: &mut TypeSpec, kind: VarKind) {
        match ty {
            TypeSpec::Named(id) => {
                if self.itfs.contains_key(&id.sym) {
                    let n = format!("__ITF_{}", self.name(id.sym));
                    id.sym = self.sym(&n);
                } else if let Some(c) = self.class(id.sym) {
                    if c.is_abstract && kind != VarKind::InOut {
                        let n = self.name(id.sym);
                        self.err(
                            Code::E204,
                            id.span,
                            format!("`{n}` is ABSTRACT and cannot be instantiated"),
                        );
                    }
                }
            }
            TypeSpec::Array { elem, .. } => self.retype_spec(elem, kind),
            TypeSpec::Struct { members, .. } => {
                for m in members {
                    self.retype_spec(&mut m.ty, kind);
                }
            }
            // A reference may designate an instance of a derived class.
            TypeSpec::Ref { .. } => {}
            _ => {}
        }
    }

    pub(super) fn locals_of(blocks: &[VarBlock]) -> HashMap<Symbol, TypeSpec> {
        let mut m = HashMap::new();
        for b in blocks {
            for decl in &b.decls {
                for n in &decl.names {
                    m.insert(n.sym, decl.ty.clone());
                }
            }
        }
        m
    }

    pub(super) fn rewrite_pou(&mut self, p: &mut Pou) {
        let mut locals = Self::locals_of(&p.var_blocks);
        // A function's result is assigned to its name.
        if let (PouKind::Function, Some(r)) = (p.kind, &p.return_type) {
            locals.insert(p.name.sym, r.clone());
        }
        let cx = Ctx {
            class: None,
            defined_in: None,
            in_method: false,
            locals,
            result: None,
            pou: Some(p.name.sym),
        };
        for b in &mut p.var_blocks {
            self.retype_block(b);
        }
        if let Some(r) = &mut p.return_type {
            self.retype_spec(r, VarKind::Output);
        }
        let Body::St(stmts) = &mut p.body;
        self.stmts(stmts, &cx);
    }
}
