//! Resolving written types ([`TypeSpec`]) to [`TypeId`]s: named types on
//! demand with cycle detection, array bounds / string lengths / subrange
//! limits / enumeration values folded to numbers.

use super::{Builder, TypeState, MAX_DEPTH};
use crate::lattice::int_fits;
use crate::types::{Dim, Elem, EnumVal, Member, TypeId, TypeKind, MAX_STRING_LEN};
use crate::value::{ArrayInit, Init};
use automat_base::{Code, Diagnostic, Span, Symbol};
use automat_syntax::ast::{ArrayDim, Expr, Ident, PouKind, TypeSpec};
use rustc_hash::FxHashMap;

/// The longest string type accepted.
/// The most elements an array type may have.
const MAX_ARRAY_ELEMS: u64 = 1 << 31;

/// How a type is being resolved.
#[derive(Clone, Copy, Default)]
pub(super) struct SpecCtx {
    /// The name of the TYPE declaration (structures and enumerations keep it).
    pub name: Option<Symbol>,
    /// The id already reserved for this structure or enumeration.
    pub reserved: Option<TypeId>,
    /// Inside `REF_TO`: a type being declared may be named (a link to itself).
    pub in_ref: bool,
}

impl<'a> Builder<'a> {
    /// Resolves a named user type; `None` if no TYPE declares the name.
    pub(super) fn resolve_named(
        &mut self,
        name: Symbol,
        use_span: Option<Span>,
        in_ref: bool,
    ) -> Option<(TypeId, Option<Init>)> {
        let slot = self.type_slots.get(&name)?;
        let decl = slot.decl;
        match slot.state.clone() {
            TypeState::Done(t, init) => return Some((t, init)),
            TypeState::InProgress(Some(id)) if in_ref => return Some((id, None)),
            TypeState::InProgress(_) => {
                let n = self.name(name);
                self.emit(
                    Diagnostic::error(
                        Code::E027,
                        use_span.unwrap_or(decl.name.span),
                        format!("type `{n}` is defined in terms of itself"),
                    )
                    .with_label(decl.name.span, "declared here"),
                );
                return Some((TypeId::ERROR, None));
            }
            TypeState::Pending => {}
        }
        if self.depth >= MAX_DEPTH {
            let n = self.name(name);
            self.emit(Diagnostic::error(
                Code::E027,
                use_span.unwrap_or(decl.name.span),
                format!("type `{n}` is nested too deeply in other declarations"),
            ));
            return Some((TypeId::ERROR, None));
        }
        let reserved = match decl.spec {
            TypeSpec::Struct { .. } | TypeSpec::Enum { .. } => {
                Some(self.types.add(TypeKind::Error))
            }
            _ => None,
        };
        self.set_type_state(name, TypeState::InProgress(reserved));
        self.depth += 1;
        let ctx = SpecCtx {
            name: Some(name),
            reserved,
            in_ref: false,
        };
        let (t, alias_init) = self.resolve_spec(&decl.spec, 0, ctx);
        // Done before the initial value, which may name the type's own values.
        self.set_type_state(name, TypeState::Done(t, None));
        let init = match &decl.init {
            Some(i) => self.check_init(i, t, 0, decl.name),
            None => alias_init,
        };
        self.depth -= 1;
        self.set_type_state(name, TypeState::Done(t, init.clone()));
        Some((t, init))
    }

    fn set_type_state(&mut self, name: Symbol, state: TypeState) {
        if let Some(s) = self.type_slots.get_mut(&name) {
            s.state = state;
        }
    }

    pub(super) fn resolve_return_type(&mut self, p: usize) {
        let Some(entry) = self.pous.get(p) else {
            return;
        };
        let (scope, spec) = (entry.scope, entry.ast.return_type.as_ref());
        if entry.ast.kind != PouKind::Function {
            return;
        }
        if let Some(spec) = spec {
            let (t, _) = self.resolve_spec(spec, scope, SpecCtx::default());
            if let Some(e) = self.pous.get_mut(p) {
                e.return_type = Some(t);
            }
        }
    }

    /// Resolves a written type in a scope (for the constants it uses). Also
    /// returns the initial value it implies (an alias's).
    pub(super) fn resolve_spec(
        &mut self,
        spec: &TypeSpec,
        scope: usize,
        ctx: SpecCtx,
    ) -> (TypeId, Option<Init>) {
        match spec {
            TypeSpec::Named(id) => self.resolve_type_name(*id, ctx.in_ref),
            TypeSpec::String { wide, len, .. } => {
                let len = match len {
                    None => crate::types::DEFAULT_STRING_LEN,
                    Some(e) => match self.fold_int(e, scope, "a string length") {
                        Some(n) if (1..=i128::from(MAX_STRING_LEN)).contains(&n) => n as u32,
                        Some(n) => {
                            self.emit(Diagnostic::error(
                                Code::E072,
                                e.span,
                                format!(
                                    "string length must be between 1 and {MAX_STRING_LEN} \
                                     (LEN and positions are INT), found {n}"
                                ),
                            ));
                            return (TypeId::ERROR, None);
                        }
                        None => return (TypeId::ERROR, None),
                    },
                };
                (self.types.string(*wide, len), None)
            }
            TypeSpec::Array { dims, elem, span } => self.resolve_array(dims, elem, *span, scope),
            TypeSpec::Subrange { base, lo, hi, .. } => {
                let Some(b) = self.int_base(*base) else {
                    return (TypeId::ERROR, None);
                };
                let lo_v = self.fold_limit(lo, scope, b);
                let hi_v = self.fold_limit(hi, scope, b);
                let (Some(l), Some(h)) = (lo_v, hi_v) else {
                    return (TypeId::ERROR, None);
                };
                if l > h {
                    self.emit(Diagnostic::error(
                        Code::E072,
                        lo.span.to(hi.span),
                        format!(
                            "subrange {l}..{h}: the lower limit is greater than the upper limit"
                        ),
                    ));
                    return (TypeId::ERROR, None);
                }
                (self.types.subrange(b, l, h), None)
            }
            TypeSpec::Enum { base, values, .. } => {
                (self.resolve_enum(*base, values, scope, ctx), None)
            }
            TypeSpec::Struct { members, .. } => (self.resolve_struct(members, scope, ctx), None),
            TypeSpec::Ref { target, .. } => {
                let inner = SpecCtx {
                    in_ref: true,
                    ..SpecCtx::default()
                };
                let (t, _) = self.resolve_spec(target, scope, inner);
                if t == TypeId::ERROR {
                    return (t, None);
                }
                (self.types.reference(t), None)
            }
        }
    }

    fn resolve_type_name(&mut self, id: Ident, in_ref: bool) -> (TypeId, Option<Init>) {
        if let Some(&e) = self.syms.elems.get(&id.sym) {
            return (TypeId::elem(e), None);
        }
        if id.sym == self.syms.string {
            return (TypeId::STRING, None);
        }
        if id.sym == self.syms.wstring {
            return (TypeId::WSTRING, None);
        }
        if let Some(r) = self.resolve_named(id.sym, Some(id.span), in_ref) {
            return r;
        }
        if let Some(&pid) = self.pou_names.get(&id.sym) {
            if let Some(p) = self.pous.get(pid.0 as usize) {
                if let Some(t) = p.instance_type {
                    return (t, None);
                }
                let n = self.name(id.sym);
                self.emit(Diagnostic::error(
                    Code::E021,
                    id.span,
                    format!("`{n}` is a function, not a type"),
                ));
                return (TypeId::ERROR, None);
            }
        }
        let n = self.name(id.sym);
        let mut names: Vec<&str> = self
            .type_slots
            .keys()
            .chain(self.syms.elems.keys())
            .chain([&self.syms.string, &self.syms.wstring])
            .map(|&s| self.name(s))
            .chain(
                self.pous
                    .iter()
                    .filter(|p| p.instance_type.is_some())
                    .map(|p| self.name(p.ast.name.sym)),
            )
            .collect();
        names.sort_unstable();
        let hint = crate::suggest::did_you_mean(n, names);
        self.emit(Diagnostic::error(
            Code::E021,
            id.span,
            format!("unknown type `{n}`{hint}"),
        ));
        (TypeId::ERROR, None)
    }

    /// The integer type named as the base of a subrange or enumeration.
    fn int_base(&mut self, base: Ident) -> Option<Elem> {
        match self.syms.elems.get(&base.sym) {
            Some(&e) if e.is_int() => Some(e),
            _ => {
                let n = self.name(base.sym);
                self.emit(Diagnostic::error(
                    Code::E030,
                    base.span,
                    format!("`{n}` is not an integer type; a subrange or enumeration needs one as its base"),
                ));
                None
            }
        }
    }

    /// A subrange limit or enumeration value: an integer constant fitting `base`.
    fn fold_limit(&mut self, e: &Expr, scope: usize, base: Elem) -> Option<i128> {
        let v = self.fold_int(e, scope, "a subrange limit")?;
        if !int_fits(v, base) {
            self.emit(Diagnostic::error(
                Code::E030,
                e.span,
                format!("the value {v} does not fit {}", base.name()),
            ));
            return None;
        }
        Some(v)
    }

    fn resolve_array(
        &mut self,
        dims: &[ArrayDim],
        elem: &TypeSpec,
        span: Span,
        scope: usize,
    ) -> (TypeId, Option<Init>) {
        let mut out = Vec::with_capacity(dims.len());
        let mut ok = true;
        let mut total: u64 = 1;
        for d in dims {
            match d {
                ArrayDim::Star(_) => out.push(Dim::Star),
                ArrayDim::Range { lo, hi, span } => {
                    let l = self.fold_int(lo, scope, "an array bound");
                    let h = self.fold_int(hi, scope, "an array bound");
                    let (Some(l), Some(h)) = (l, h) else {
                        ok = false;
                        continue;
                    };
                    let (Ok(l64), Ok(h64)) = (i64::try_from(l), i64::try_from(h)) else {
                        self.emit(Diagnostic::error(
                            Code::E073,
                            *span,
                            format!("array bounds {l}..{h} do not fit 64 bits"),
                        ));
                        ok = false;
                        continue;
                    };
                    if l > h {
                        self.emit(Diagnostic::error(
                            Code::E072,
                            *span,
                            format!("array dimension {l}..{h}: the lower bound is greater than the upper bound"),
                        ));
                        ok = false;
                        continue;
                    }
                    let dim = Dim::Range(l64, h64);
                    total = total.saturating_mul(dim.len());
                    out.push(dim);
                }
            }
        }
        if ok && total > MAX_ARRAY_ELEMS {
            self.emit(Diagnostic::error(
                Code::E072,
                span,
                format!("array has {total} elements, more than the {MAX_ARRAY_ELEMS} allowed"),
            ));
            ok = false;
        }
        let (e, elem_init) = self.resolve_spec(elem, scope, SpecCtx::default());
        if !ok || e == TypeId::ERROR {
            return (TypeId::ERROR, None);
        }
        let init = elem_init.map(|i| {
            Init::Array(vec![ArrayInit {
                repeat: total,
                value: Some(i),
            }])
        });
        (self.types.array(e, out), init)
    }

    fn resolve_enum(
        &mut self,
        base: Option<Ident>,
        values: &[automat_syntax::ast::EnumValue],
        scope: usize,
        ctx: SpecCtx,
    ) -> TypeId {
        let b = match base {
            Some(b) => self.int_base(b).unwrap_or(Elem::Int),
            None => Elem::Int,
        };
        let id = ctx
            .reserved
            .unwrap_or_else(|| self.types.add(TypeKind::Error));
        let outer = std::mem::take(&mut self.enum_in_progress);
        let mut out: Vec<EnumVal> = Vec::with_capacity(values.len());
        let mut seen: FxHashMap<Symbol, Span> = FxHashMap::default();
        let mut next: i128 = 0;
        for v in values {
            let value = match &v.value {
                Some(e) => self.fold_limit(e, scope, b).unwrap_or(next),
                None => {
                    if !int_fits(next, b) {
                        self.emit(Diagnostic::error(
                            Code::E073,
                            v.name.span,
                            format!(
                                "the value {next} of `{}` does not fit {}",
                                self.name(v.name.sym),
                                b.name()
                            ),
                        ));
                    }
                    next
                }
            };
            next = value.saturating_add(1);
            if let Some(&first) = seen.get(&v.name.sym) {
                let n = self.name(v.name.sym);
                self.emit(
                    Diagnostic::error(
                        Code::E023,
                        v.name.span,
                        format!("enumeration value `{n}` is declared twice"),
                    )
                    .with_label(first, "first declared here"),
                );
                continue;
            }
            seen.insert(v.name.sym, v.name.span);
            self.enum_in_progress.push((v.name.sym, value, b));
            out.push(EnumVal {
                name: v.name.sym,
                value,
                span: v.name.span,
            });
        }
        self.enum_in_progress = outer;
        for v in &out {
            let list = self.enum_values.entry(v.name).or_default();
            if !list.contains(&id) {
                list.push(id);
            }
        }
        self.types.set(
            id,
            TypeKind::Enum {
                name: ctx.name,
                base: b,
                values: out,
            },
        );
        id
    }

    fn resolve_struct(
        &mut self,
        members: &[automat_syntax::ast::VarDecl],
        scope: usize,
        ctx: SpecCtx,
    ) -> TypeId {
        let id = ctx
            .reserved
            .unwrap_or_else(|| self.types.add(TypeKind::Error));
        let mut out: Vec<Member> = Vec::new();
        let mut seen: FxHashMap<Symbol, Span> = FxHashMap::default();
        for decl in members {
            let (t, alias_init) = self.resolve_spec(&decl.ty, scope, SpecCtx::default());
            let init = match (&decl.init, decl.names.first()) {
                (Some(i), Some(&n)) => self.check_init(i, t, scope, n),
                _ => alias_init,
            };
            for name in &decl.names {
                if let Some(&first) = seen.get(&name.sym) {
                    let n = self.name(name.sym);
                    self.emit(
                        Diagnostic::error(
                            Code::E023,
                            name.span,
                            format!("member `{n}` is declared twice"),
                        )
                        .with_label(first, "first declared here"),
                    );
                    continue;
                }
                seen.insert(name.sym, name.span);
                out.push(Member {
                    name: name.sym,
                    ty: t,
                    init: init.clone(),
                    span: name.span,
                });
            }
        }
        self.types.set(
            id,
            TypeKind::Struct {
                name: ctx.name,
                members: out,
            },
        );
        id
    }
}
