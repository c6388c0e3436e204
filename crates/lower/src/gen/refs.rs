//! References: `REF(x)` / `ADR(x)` (the image offset of a variable),
//! dereferencing `r^` (faults on NULL), and `SIZEOF(x)`.

use super::{Failed, Gen, Lv, Res, Val, V};
use automat_ir::code::{Addr, CheckKind, Inst};
use automat_sema::ops::Ty;
use automat_sema::types::{Elem, TypeId, TypeKind};
use automat_syntax::ast::{Expr, ExprKind};

impl Gen<'_, '_> {
    /// The variable `r^` designates.
    pub fn deref_place(&mut self, base: &Expr, e: &Expr) -> Res<Lv> {
        // `REF(x)^` is `x` itself.
        if let Some(inner) = self.ref_call_arg(base) {
            return self.place(inner);
        }
        let v = self.expr(base, None)?;
        let target = match self.kind(v.ty) {
            TypeKind::Ref(t) => *t,
            _ => {
                return Err(self.error(
                    e.span,
                    "only a REF_TO variable can be dereferenced here".into(),
                ))
            }
        };
        let V::I(r) = v.v else { return Err(Failed) };
        let site = self.site(e.span);
        // The whole target must lie in the image (0 is NULL): a CODESYS
        // pointer moved by arithmetic can point anywhere. The image's size
        // is known only after code generation, which patches the bound
        // (`-size` stands for `image size - size`, see `patch_ref_checks`).
        let (size, _) = self.cx.layout.size(target);
        self.emit(Inst::Check {
            kind: CheckKind::Ref,
            val: r,
            lo: 1,
            hi: -i64::from(size.max(1)),
            site,
        });
        Ok(Lv {
            addr: Addr::reg(r, 0),
            bit: None,
            ty: target,
        })
    }

    /// `NULL` (when no variable hides the name): offset 0, which no
    /// variable has (the image starts with reserved bytes), typed as the
    /// reference the context wants. The checker already rejected NULL
    /// where no reference type is wanted.
    pub fn null_ref(&mut self, e: &Expr, want: Option<TypeId>) -> Option<Val> {
        let ExprKind::Name(id) = &e.kind else {
            return None;
        };
        if !self.cx.interner.name(id.sym).eq_ignore_ascii_case("NULL") {
            return None;
        }
        let model = self.cx.model;
        let pou = model.pou(self.pou)?;
        if pou.vars.index(id.sym).is_some() || self.cx.globals.contains_key(&id.sym) {
            return None;
        }
        let ty = want.filter(|&w| matches!(self.kind(w), TypeKind::Ref(_)))?;
        let r = self.reg(automat_ir::code::RegClass::I64);
        self.emit(Inst::IConst { dst: r, value: 0 });
        Some(Val { v: V::I(r), ty })
    }

    /// The argument of a `REF(x)` / `ADR(x)` call.
    fn ref_call_arg<'e>(&self, e: &'e Expr) -> Option<&'e Expr> {
        let ExprKind::Call { callee, args } = &e.kind else {
            return None;
        };
        let ExprKind::Name(id) = &callee.kind else {
            return None;
        };
        if self.cx.model.pou_named(id.sym).is_some() {
            return None;
        }
        let name = self.cx.interner.name(id.sym);
        let is_ref = name.eq_ignore_ascii_case("REF") || name.eq_ignore_ascii_case("ADR");
        match (is_ref, args.as_slice()) {
            (true, [a]) => a.value.as_ref(),
            _ => None,
        }
    }

    /// `REF(x)` / `ADR(x)`: the offset of `x`, typed `REF_TO <type of x>`
    /// when that type exists (else the wanted reference type, else UDINT).
    pub fn ref_of(&mut self, x: &Expr, want: Option<TypeId>, e: &Expr) -> Res<Val> {
        let lv = self.place(x)?;
        if lv.bit.is_some() {
            return Err(self.error(
                e.span,
                "a reference to a single bit (a BOOL at a bit address) is not possible".into(),
            ));
        }
        let r = self.addr_reg(lv.addr);
        let ty = match want.map(|w| self.kind(w)) {
            Some(TypeKind::Ref(t)) if *t == lv.ty => want,
            _ => None,
        }
        .or_else(|| self.cx.model.types.find_ref(lv.ty))
        .unwrap_or(TypeId::elem(Elem::Udint));
        Ok(Val { v: V::I(r), ty })
    }

    /// `SIZEOF(x)`: the bytes `x` occupies (a VAR_IN_OUT: its target's).
    pub fn size_of(&mut self, x: &Expr) -> Res<Val> {
        let named = automat_sema::type_named(self.cx.model, self.cx.interner, self.pou, x);
        let ty = match named.map_or(self.typed(x).ty, Ty::Of) {
            Ty::Of(t) => t,
            t => self.concrete(t, None, None).ok_or(Failed)?,
        };
        let (n, _) = self.cx.layout.size(ty);
        Ok(Val {
            v: V::I(self.iconst(i64::from(n))),
            ty: TypeId::elem(Elem::Udint),
        })
    }
}
