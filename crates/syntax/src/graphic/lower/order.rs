//! Execution order of a network's statement elements and the wire-loop check (E174);
//! the rules are in the module comment of `lower.rs`.

use super::*;

/// Where a statement sorts: its rung's top (y, x), the rung, its own
/// (y, x) and `localId`.
type OrderKey = (f64, f64, usize, f64, f64, u32);

/// Execution order of the statement elements (see the module comment).
pub(super) fn order(l: &mut L, own: &[bool]) -> Vec<usize> {
    let net = l.net;
    let n = net.elements.len();
    let stmts: Vec<usize> = (0..n).filter(|&i| own[i]).collect();
    let pos = |i: usize| {
        let e = &net.elements[i];
        (e.y, e.x, e.id)
    };
    let by_pos = |a: &usize, b: &usize| {
        let (pa, pb) = (pos(*a), pos(*b));
        pa.partial_cmp(&pb).unwrap_or(std::cmp::Ordering::Equal)
    };
    // Dependencies (also needed for the loop check with an explicit order).
    let mut deps: Vec<Vec<usize>> = vec![Vec::new(); n];
    for &i in &stmts {
        let mut acc = Vec::new();
        let mut seen = Vec::new();
        l.deps(i, i, &mut acc, &mut seen);
        acc.retain(|&j| j != i || matches!(net.elements[i].kind, Kind::Block { .. }));
        deps[i] = acc;
    }
    if net.lang == GraphLang::Fbd && stmts.iter().any(|&i| net.elements[i].order.is_some()) {
        let mut s = stmts.clone();
        s.sort_by(|a, b| {
            let ka = net.elements[*a].order.unwrap_or(u32::MAX);
            let kb = net.elements[*b].order.unwrap_or(u32::MAX);
            ka.cmp(&kb).then_with(|| by_pos(a, b))
        });
        check_loops(l, &stmts, &deps);
        return s;
    }
    check_loops(l, &stmts, &deps);
    // Rungs: groups of elements joined by wires, the rails left out.
    let mut group: Vec<usize> = (0..n).collect();
    fn find(g: &mut [usize], mut i: usize) -> usize {
        while g[i] != i {
            g[i] = g[g[i]];
            i = g[i];
        }
        i
    }
    for (i, e) in net.elements.iter().enumerate() {
        if matches!(e.kind, Kind::LeftRail | Kind::RightRail) {
            continue;
        }
        let link = |j: usize, g: &mut Vec<usize>| {
            if matches!(net.elements[j].kind, Kind::LeftRail | Kind::RightRail) {
                return;
            }
            let (a, b) = (find(g, i), find(g, j));
            g[a] = b;
        };
        for p in &e.inputs {
            for c in &p.conns {
                if let Some(&j) = l.by_id.get(&c.from) {
                    link(j, &mut group);
                }
            }
        }
        if let Kind::Continuation { name } = &e.kind {
            if let Some(&j) = l.connectors.get(name) {
                link(j, &mut group);
            }
        }
    }
    let mut top: HashMap<usize, (f64, f64)> = HashMap::new();
    for i in 0..n {
        let r = find(&mut group, i);
        let e = &net.elements[i];
        let t = top.entry(r).or_insert((e.y, e.x));
        if (e.y, e.x) < *t {
            *t = (e.y, e.x);
        }
    }
    let key = |i: usize, group: &mut Vec<usize>| {
        let r = find(group, i);
        let t = top.get(&r).copied().unwrap_or((0.0, 0.0));
        let (y, x, id) = pos(i);
        (t.0, t.1, r, y, x, id)
    };
    // Kahn's algorithm, always taking the first ready element by key.
    let mut done = vec![false; n];
    let mut out = Vec::with_capacity(stmts.len());
    let mut keys: Vec<(usize, OrderKey)> = stmts.iter().map(|&i| (i, key(i, &mut group))).collect();
    keys.sort_by(|a, b| a.1.partial_cmp(&b.1).unwrap_or(std::cmp::Ordering::Equal));
    while out.len() < stmts.len() {
        let ready = keys
            .iter()
            .find(|(i, _)| !done[*i] && deps[*i].iter().all(|&d| done[d] || d == *i));
        match ready {
            Some(&(i, _)) => {
                done[i] = true;
                out.push(i);
            }
            None => {
                // A loop (E174, reported above): break it the loop at the first remaining element to go on.
                if let Some(&(i, _)) = keys.iter().find(|(i, _)| !done[*i]) {
                    done[i] = true;
                    out.push(i);
                }
            }
        }
    }
    out
}

/// E174 for each element on a loop of wires (reported once per loop).
fn check_loops(l: &mut L, stmts: &[usize], deps: &[Vec<usize>]) {
    let net = l.net;
    let n = net.elements.len();
    // 0 unvisited, 1 on the stack, 2 done: iterative depth-first search.
    let mut state = vec![0u8; n];
    for &s in stmts {
        if state[s] != 0 {
            continue;
        }
        let mut stack = vec![(s, 0usize)];
        state[s] = 1;
        while let Some(&mut (v, ref mut k)) = stack.last_mut() {
            match deps[v].get(*k) {
                Some(&w) => {
                    *k += 1;
                    if w == v {
                        if matches!(net.elements[v].kind, Kind::Block { .. }) {
                            let e = &net.elements[v];
                            l.err(Code::E174, e.span, e, "this block's output comes back to its own input without a variable");
                        }
                    } else if state[w] == 1 {
                        let e = &net.elements[w];
                        l.err(Code::E174, e.span, e, "a loop of connections without a feedback variable passes through this element");
                    } else if state[w] == 0 {
                        state[w] = 1;
                        stack.push((w, 0));
                    }
                }
                None => {
                    state[v] = 2;
                    stack.pop();
                }
            }
        }
    }
    l.diags.dedup_by(|a, b| a.2 == b.2);
}
