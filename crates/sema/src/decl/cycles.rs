//! A function block may not contain an instance of itself, directly or
//! through other function blocks, structures or arrays (its memory would be
//! infinite). Structures containing themselves are caught while resolving
//! types; instances are types by id, so their cycles are found here, on the
//! finished model (E027). References and VAR_IN_OUT break containment.

use crate::model::{Model, Section};
use crate::types::{PouId, TypeId, TypeKind};
use automat_base::{Code, Diagnostic, Interner, Span};
use rustc_hash::FxHashMap;

/// The instances (by POU) a type holds by value.
fn instances_in(
    model: &Model,
    t: TypeId,
    memo: &mut FxHashMap<TypeId, Vec<PouId>>,
    depth: u32,
) -> Vec<PouId> {
    if let Some(v) = memo.get(&t) {
        return v.clone();
    }
    if depth > 64 {
        return Vec::new();
    }
    let out = match model.types.get(t) {
        TypeKind::Fb { pou, .. } | TypeKind::Program { pou, .. } => vec![*pou],
        TypeKind::Array { elem, .. } => instances_in(model, *elem, memo, depth + 1),
        TypeKind::Struct { members, .. } => {
            let mut v = Vec::new();
            for m in members {
                for p in instances_in(model, m.ty, memo, depth + 1) {
                    if !v.contains(&p) {
                        v.push(p);
                    }
                }
            }
            v
        }
        _ => Vec::new(),
    };
    memo.insert(t, out.clone());
    out
}

pub(crate) fn instance_cycles(model: &Model, interner: &Interner) -> Vec<Diagnostic> {
    let mut memo = FxHashMap::default();
    // Edges: POU → (contained POU, the variable holding it).
    let mut edges: Vec<Vec<(usize, Span)>> = Vec::with_capacity(model.pous.len());
    for p in &model.pous {
        let mut e = Vec::new();
        for v in &p.vars.vars {
            if matches!(
                v.section,
                Section::InOut | Section::External | Section::Global
            ) {
                continue;
            }
            for q in instances_in(model, v.ty, &mut memo, 0) {
                e.push((q.0 as usize, v.span));
            }
        }
        edges.push(e);
    }
    // Iterative depth-first search with colours: 0 new, 1 on the stack, 2 done.
    let mut colour = vec![0u8; edges.len()];
    let mut diags = Vec::new();
    for start in 0..edges.len() {
        if colour.get(start) != Some(&0) {
            continue;
        }
        let mut stack: Vec<(usize, usize)> = vec![(start, 0)];
        if let Some(c) = colour.get_mut(start) {
            *c = 1;
        }
        while let Some(&mut (node, ref mut next)) = stack.last_mut() {
            let Some(&(to, span)) = edges.get(node).and_then(|e| e.get(*next)) else {
                if let Some(c) = colour.get_mut(node) {
                    *c = 2;
                }
                stack.pop();
                continue;
            };
            *next += 1;
            match colour.get(to) {
                Some(0) => {
                    if let Some(c) = colour.get_mut(to) {
                        *c = 1;
                    }
                    stack.push((to, 0));
                }
                Some(1) => {
                    let name = model.pous.get(to).map_or("?", |p| interner.name(p.name));
                    diags.push(Diagnostic::error(
                        Code::E027,
                        span,
                        format!("function block `{name}` contains an instance of itself through this variable"),
                    ));
                }
                _ => {}
            }
        }
    }
    diags
}
