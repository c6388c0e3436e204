//! Phase 3: configurations. Tasks (INTERVAL a TIME, PRIORITY an integer,
//! SINGLE a BOOL variable, each once: E081), program instances (the type
//! must be a PROGRAM: E082; the task known in the resource: E080; the
//! connections formal, naming the program's inputs and outputs), and the
//! paths of VAR_ACCESS and VAR_CONFIG (resource → program instance →
//! variables / instance members: E083).
//!
//! Invariant: expressions of a configuration are typed by the same
//! [`Checker`] as bodies, in a configuration scope (resource globals, then
//! configuration globals, then the project's).

use crate::body::{Checker, Scope};
use crate::convert::{fits, Fit};
use crate::decl::ConfigDecls;
use crate::model::{AccessPath, Model, ProgramInstance, Section, Task};
use crate::names::expr_text;
use crate::ops::Ty;
use crate::types::{TypeId, TypeKind};
use crate::value::Value;
use automat_base::{Code, Diagnostic, Interner, Span, Symbol};
use automat_syntax::ast::{self, AccessDirection, ArgDir, Expr, ExprKind, Ident, PouKind};

/// Checks every configuration and records tasks, instances and paths in the model.
pub(crate) fn check_configs(
    model: &mut Model,
    configs: &[ConfigDecls],
    interner: &Interner,
    diags: &mut Vec<Diagnostic>,
) {
    for (ci, decls) in configs.iter().enumerate() {
        let mut per_resource = Vec::new();
        for (ri, res) in decls.ast.resources.iter().enumerate() {
            let mut ck = Checker::new(model, interner, Scope::Config(ci, Some(ri)), false);
            let tasks = tasks(&mut ck, res);
            let programs = programs(&mut ck, res, &tasks);
            diags.append(&mut ck.diags);
            per_resource.push((tasks, programs));
        }
        if let Some(cf) = model.configs.get_mut(ci) {
            for (r, (t, p)) in cf.resources.iter_mut().zip(per_resource) {
                r.tasks = t;
                r.programs = p;
            }
        }
        let mut ck = Checker::new(model, interner, Scope::Config(ci, None), false);
        let mut access = Vec::new();
        for (a, &ty) in decls.ast.access.iter().zip(&decls.access_types) {
            if let Some(mut p) = resolve_path(&mut ck, ci, &a.path) {
                check_path_type(&mut ck, &a.path, p.ty, ty);
                p.name = Some(a.name.sym);
                p.ty = ty;
                p.read_only = a.direction == Some(AccessDirection::ReadOnly);
                p.span = a.span;
                access.push(p);
            }
        }
        let mut var_config = Vec::new();
        for (vc, (ty, init)) in decls.ast.var_config.iter().zip(&decls.var_config) {
            if let Some(mut p) = resolve_path(&mut ck, ci, &vc.path) {
                check_path_type(&mut ck, &vc.path, p.ty, *ty);
                if let (Some(loc), Some(target)) = (&vc.location, &p.location) {
                    if !target.partial {
                        let a = crate::names::address_text(target);
                        ck.err(Code::E084, loc.addr.span, |c| {
                            format!(
                                "`{}` is located at {a} already; VAR_CONFIG can only complete a partly specified address (`%I*`)",
                                expr_text(c.interner, &vc.path)
                            )
                        });
                    }
                }
                p.ty = *ty;
                p.location = vc.location.as_ref().map(|l| l.addr.clone());
                p.init = init.clone();
                p.span = vc.span;
                var_config.push(p);
            }
        }
        diags.append(&mut ck.diags);
        if let Some(cf) = model.configs.get_mut(ci) {
            cf.access = access;
            cf.var_config = var_config;
        }
    }
}

fn tasks(ck: &mut Checker, res: &ast::Resource) -> Vec<Task> {
    let syms = &ck.model.syms;
    let (interval, priority, single) = (syms.interval, syms.priority, syms.single);
    let mut out: Vec<Task> = Vec::new();
    for t in &res.tasks {
        if let Some(first) = out.iter().find(|x| x.name == t.name.sym) {
            let first = first.span;
            ck.diag(|c| {
                Diagnostic::error(
                    Code::E023,
                    t.name.span,
                    format!("task `{}` is declared twice", c.name(t.name.sym)),
                )
                .with_label(first, "first declared here")
            });
            continue;
        }
        let mut task = Task {
            name: t.name.sym,
            span: t.name.span,
            interval: None,
            priority: None,
            single: None,
        };
        let mut seen: Vec<Symbol> = Vec::new();
        for p in &t.props {
            if seen.contains(&p.name.sym) {
                ck.err(Code::E081, p.name.span, |c| {
                    format!("task property `{}` is given twice", c.name(p.name.sym))
                });
                continue;
            }
            seen.push(p.name.sym);
            let v = ck.expr(&p.value, None);
            if v.ty == Ty::Error {
                continue;
            }
            let elem = match v.ty {
                Ty::Of(id) => ck.model.types.elem(id),
                _ => None,
            };
            if p.name.sym == interval {
                if elem.is_some_and(|e| e.is_duration()) {
                    if let Some(Value::Duration(ns)) = v.value {
                        task.interval = Some(ns);
                    }
                } else {
                    ck.err(Code::E081, p.value.span, |c| {
                        format!("INTERVAL must be a TIME, found {}", c.tyname(v.ty))
                    });
                }
            } else if p.name.sym == priority {
                let is_int = v.ty == Ty::AnyInt || elem.is_some_and(|e| e.is_int());
                match (&v.value, is_int) {
                    (Some(val), true) => task.priority = val.as_int(),
                    (None, true) => {}
                    _ => ck.err(Code::E081, p.value.span, |c| {
                        format!("PRIORITY must be an integer, found {}", c.tyname(v.ty))
                    }),
                }
            } else if p.name.sym == single {
                match &p.value.kind {
                    ExprKind::Name(id) if v.ty == Ty::Of(TypeId::BOOL) => {
                        task.single = Some(id.sym)
                    }
                    _ => ck.err(Code::E081, p.value.span, |c| {
                        format!("SINGLE must be a BOOL variable, found {}", c.tyname(v.ty))
                    }),
                }
            } else {
                ck.err(Code::E081, p.name.span, |c| {
                    format!(
                        "unknown task property `{}`: a TASK accepts INTERVAL, PRIORITY and SINGLE",
                        c.name(p.name.sym)
                    )
                });
            }
        }
        out.push(task);
    }
    out
}

fn programs(ck: &mut Checker, res: &ast::Resource, tasks: &[Task]) -> Vec<ProgramInstance> {
    let mut out: Vec<ProgramInstance> = Vec::new();
    for pc in &res.programs {
        if let Some(first) = out.iter().find(|x| x.name == pc.name.sym) {
            let first = first.span;
            ck.diag(|c| {
                Diagnostic::error(
                    Code::E023,
                    pc.name.span,
                    format!(
                        "program instance `{}` is declared twice",
                        c.name(pc.name.sym)
                    ),
                )
                .with_label(first, "first declared here")
            });
            continue;
        }
        let task = match pc.task {
            None => None,
            Some(t) => match tasks.iter().position(|x| x.name == t.sym) {
                Some(i) => Some(i as u32),
                None => {
                    ck.err(Code::E080, t.span, |c| {
                        format!(
                            "unknown task `{}` in resource `{}`",
                            c.name(t.sym),
                            c.name(res.name.sym)
                        )
                    });
                    None
                }
            },
        };
        let Some((pou_id, pou)) = ck.model.pou_named(pc.ty.sym) else {
            if ck.type_by_name(pc.ty).is_some() {
                ck.err(Code::E082, pc.ty.span, |c| {
                    format!("`{}` is a data type, not a PROGRAM; only programs can be instantiated in a resource", c.name(pc.ty.sym))
                });
            } else {
                ck.err(Code::E022, pc.ty.span, |c| {
                    format!("unknown program `{}`", c.name(pc.ty.sym))
                });
            }
            ck.args_unchecked(&pc.conns);
            continue;
        };
        if pou.kind != PouKind::Program {
            let what = if pou.kind == PouKind::Function {
                "a function"
            } else {
                "a function block"
            };
            ck.err(Code::E082, pc.ty.span, |c| {
                format!("`{}` is {what}, not a PROGRAM; only programs can be instantiated in a resource", c.name(pc.ty.sym))
            });
            ck.args_unchecked(&pc.conns);
            continue;
        }
        connections(ck, pou, pc);
        out.push(ProgramInstance {
            name: pc.name.sym,
            span: pc.name.span,
            pou: pou_id,
            task,
            retain: pc.retain,
            conns: pc.conns.clone(),
        });
    }
    out
}

/// `PROGRAM p : Main (in1 := g1, out1 => g2)`: formal, naming inputs and outputs.
fn connections(ck: &mut Checker, pou: &crate::model::Pou, pc: &ast::ProgramConfig) {
    for a in &pc.conns {
        let Some(name) = a.name else {
            ck.err(Code::E055, a.span, |c| {
                format!(
                    "connections of program `{}` must be formal (`name := value`)",
                    c.name(pou.name)
                )
            });
            ck.args_unchecked(std::slice::from_ref(a));
            continue;
        };
        let Some(param) = pou.vars.get(name.sym).filter(|v| v.section.is_param()) else {
            ck.err(Code::E051, name.span, |c| {
                format!(
                    "program `{}` has no input or output `{}`",
                    c.name(pou.name),
                    c.name(name.sym)
                )
            });
            ck.args_unchecked(std::slice::from_ref(a));
            continue;
        };
        let Some(v) = &a.value else { continue };
        let out = matches!(a.dir, ArgDir::Out | ArgDir::OutNot);
        if out != (param.section == Section::Output) {
            ck.err(Code::E051, a.span, |c| {
                if out {
                    format!(
                        "`{}` is an input of `{}`: connect it with `:=`",
                        c.name(name.sym),
                        c.name(pou.name)
                    )
                } else {
                    format!(
                        "`{}` is an output of `{}`: connect it with `=>`",
                        c.name(name.sym),
                        c.name(pou.name)
                    )
                }
            });
            continue;
        }
        if out {
            let t = ck.expr_access(v, None, crate::body::Access::Output);
            if let Ty::Of(tt) = t.ty {
                if fits(&ck.model.types, &crate::ops::Typed::of(param.ty), tt) != Fit::Ok {
                    ck.err(Code::E052, v.span, |c| {
                        format!(
                            "the output `{}` of `{}` has type {}, which cannot be stored in `{}` of type {}",
                            c.name(name.sym),
                            c.name(pou.name),
                            c.type_name(param.ty),
                            expr_text(c.interner, v),
                            c.type_name(tt)
                        )
                    });
                }
            }
        } else {
            let t = ck.expr(v, Some(param.ty));
            let what =
                |c: &Checker| format!("input `{}` of `{}`", c.name(name.sym), c.name(pou.name));
            ck.arg_fits(&t, param.ty, v.span, &what);
        }
    }
}

/// The names of a path written `a.b.c` (indexes kept as `None` markers are
/// not supported in paths and make the path unknown).
fn segments(e: &Expr, out: &mut Vec<Ident>) -> bool {
    match &e.kind {
        ExprKind::Name(i) => {
            out.push(*i);
            true
        }
        ExprKind::Member { base, member } => {
            let ok = segments(base, out);
            out.push(*member);
            ok
        }
        _ => false,
    }
}

/// Resolves a VAR_ACCESS / VAR_CONFIG path to the variable it names.
fn resolve_path(ck: &mut Checker, ci: usize, path: &Expr) -> Option<AccessPath> {
    let model = ck.model;
    let mk = |path: Vec<Symbol>, ty: TypeId, location: Option<ast::DirectAddress>| AccessPath {
        name: None,
        path,
        ty,
        read_only: false,
        location,
        init: None,
        span: Span::default(),
    };
    if let ExprKind::Address(a) = &path.kind {
        let e = crate::decl::location::size_elem(a.size);
        return Some(mk(Vec::new(), TypeId::elem(e), Some((**a).clone())));
    }
    let mut segs = Vec::new();
    if !segments(path, &mut segs) {
        ck.err(Code::E083, path.span, |_| {
            "an access path is written `resource.instance.variable`, `global` or a direct address"
                .into()
        });
        return None;
    }
    let cf = model.configs.get(ci)?;
    let unknown = |ck: &mut Checker, at: Ident, msg: String| {
        ck.err(Code::E083, at.span, |c| {
            format!(
                "unknown access path `{}`: {msg}",
                expr_text(c.interner, path)
            )
        });
        None
    };
    let first = *segs.first()?;
    let name = |s: Symbol| ck.interner.name(s).to_string();
    // The variable the first names reach, and how many names that took.
    let (var, used): (&crate::model::Var, usize) = if let Some(r) = cf
        .resources
        .iter()
        .find(|r| r.name == first.sym && !r.implicit)
    {
        let Some(&second) = segs.get(1) else {
            return unknown(
                ck,
                first,
                format!("`{}` is a resource, not a variable", name(first.sym)),
            );
        };
        if let Some(g) = r.globals.get(second.sym) {
            (g, 2)
        } else if let Some(inst) = r.programs.iter().find(|p| p.name == second.sym) {
            let Some(&third) = segs.get(2) else {
                return unknown(
                    ck,
                    second,
                    format!(
                        "`{}` is a program instance, not a variable",
                        name(second.sym)
                    ),
                );
            };
            match model.pou(inst.pou).and_then(|p| p.vars.get(third.sym)) {
                Some(v) => (v, 3),
                None => {
                    return unknown(
                        ck,
                        third,
                        format!(
                            "program instance `{}` has no variable `{}`",
                            name(second.sym),
                            name(third.sym)
                        ),
                    )
                }
            }
        } else {
            return unknown(
                ck,
                second,
                format!(
                    "resource `{}` has no program instance or global `{}`",
                    name(first.sym),
                    name(second.sym)
                ),
            );
        }
    } else if let Some(g) = cf.globals.get(first.sym) {
        (g, 1)
    } else if let Some(inst) = cf
        .resources
        .iter()
        .filter(|r| r.implicit)
        .flat_map(|r| r.programs.iter())
        .find(|p| p.name == first.sym)
    {
        let Some(&second) = segs.get(1) else {
            return unknown(
                ck,
                first,
                format!(
                    "`{}` is a program instance, not a variable",
                    name(first.sym)
                ),
            );
        };
        match model.pou(inst.pou).and_then(|p| p.vars.get(second.sym)) {
            Some(v) => (v, 2),
            None => {
                return unknown(
                    ck,
                    second,
                    format!(
                        "program instance `{}` has no variable `{}`",
                        name(first.sym),
                        name(second.sym)
                    ),
                )
            }
        }
    } else {
        let cn = name(cf.name);
        return unknown(
            ck,
            first,
            format!(
                "`{}` is not a resource, program instance or global of configuration `{cn}`",
                name(first.sym)
            ),
        );
    };
    let mut ty = var.ty;
    let location = var.location.clone();
    for seg in segs.iter().skip(used) {
        let next = match model.types.get(ty) {
            TypeKind::Struct { members, .. } => {
                members.iter().find(|m| m.name == seg.sym).map(|m| m.ty)
            }
            TypeKind::Fb { pou, .. } => model
                .pou(*pou)
                .and_then(|p| p.vars.get(seg.sym))
                .map(|v| v.ty),
            _ => None,
        };
        match next {
            Some(t) => ty = t,
            None => {
                let tn = ck.type_name(ty);
                return unknown(ck, *seg, format!("{tn} has no member `{}`", name(seg.sym)));
            }
        }
    }
    Some(mk(segs.iter().map(|s| s.sym).collect(), ty, location))
}

/// The declared type of an access path must be the variable's.
fn check_path_type(ck: &mut Checker, path: &Expr, actual: TypeId, declared: TypeId) {
    if actual == declared || actual == TypeId::ERROR || declared == TypeId::ERROR {
        return;
    }
    ck.err(Code::E030, path.span, |c| {
        format!(
            "`{}` has type {}, not {}",
            expr_text(c.interner, path),
            c.type_name(actual),
            c.type_name(declared)
        )
    });
}
