//! The program's variables as a tree for browsing: program instances and
//! globals at the top, then FB instances, struct members and array
//! elements, each with its IEC type and whether a client may write or
//! force it. Compiler-generated names (`__…`) are left out; SFC step
//! instances are shown with their `X` and `T`, read-only.

use automat_ir::{Program, SymbolType};
use automat_runtime::resolve_access;

/// Elements of one array listed at most (the rest is counted in `more`).
pub const MAX_ELEMENTS: usize = 256;
/// Nodes of one answer at most, whatever the program's size.
pub const MAX_NODES: usize = 20_000;

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Node {
    /// The last part of the path (`Q`, `[3]`).
    pub name: String,
    /// The whole path, readable with `read`.
    pub path: String,
    /// `BOOL`, `TON`, `ARRAY[1..10] OF INT`, `STRING[20]`.
    pub ty: String,
    /// Whether `write`/`force` accept it (only elementary values).
    pub writable: bool,
    pub children: Vec<Node>,
    /// Array elements not listed (beyond [`MAX_ELEMENTS`] or [`MAX_NODES`]).
    pub more: usize,
}

pub fn type_name(ty: &SymbolType) -> String {
    match ty {
        SymbolType::Elementary(e) => e.name().to_string(),
        SymbolType::String { cap } => format!("STRING[{cap}]"),
        SymbolType::WString { cap } => format!("WSTRING[{cap}]"),
        SymbolType::Array { elem, dims, .. } => {
            let d: Vec<String> = dims.iter().map(|(lo, hi)| format!("{lo}..{hi}")).collect();
            format!("ARRAY[{}] OF {}", d.join(", "), type_name(elem))
        }
        // The hidden blocks of the SFC desugaring, as the user wrote them.
        SymbolType::Struct { name, .. } if name.starts_with("__SFC_ACTION") => "ACTION".into(),
        SymbolType::Struct { name, .. } if name.starts_with("__SFC_") => "STEP".into(),
        SymbolType::Struct { name, .. } | SymbolType::Enum { name, .. } => name.clone(),
        SymbolType::Subrange { base, lo, hi } => format!("{base}({lo}..{hi})"),
        SymbolType::Ref(t) => format!("REF_TO {}", type_name(t)),
    }
}

struct Builder<'a> {
    program: &'a Program,
    nodes: usize,
}

impl Builder<'_> {
    fn node(&mut self, name: String, path: String, ty: &SymbolType) -> Node {
        self.nodes += 1;
        let mut node = Node {
            writable: false,
            ty: type_name(ty),
            name,
            children: Vec::new(),
            more: 0,
            path,
        };
        match ty {
            SymbolType::Struct { fields, .. } => {
                for f in fields {
                    if f.name.starts_with("__") {
                        continue;
                    }
                    if self.nodes >= MAX_NODES {
                        node.more += 1;
                        continue;
                    }
                    let path = format!("{}.{}", node.path, f.name);
                    let child = self.node(f.name.clone(), path, &f.ty);
                    node.children.push(child);
                }
            }
            SymbolType::Array { elem, dims, .. } => {
                let total = dims.iter().fold(1usize, |n, (lo, hi)| {
                    n.saturating_mul(usize::try_from(hi.saturating_sub(*lo) + 1).unwrap_or(0))
                });
                for ix in indexes(dims).take(MAX_ELEMENTS) {
                    if self.nodes >= MAX_NODES {
                        break;
                    }
                    let list: Vec<String> = ix.iter().map(i64::to_string).collect();
                    let name = format!("[{}]", list.join(", "));
                    let path = format!("{}{name}", node.path);
                    let child = self.node(name, path, elem);
                    node.children.push(child);
                }
                node.more = total.saturating_sub(node.children.len());
            }
            SymbolType::Ref(_) => {}
            _ => {
                node.writable = resolve_access(self.program, &node.path)
                    .is_ok_and(|a| !a.constant && a.generated.is_none());
            }
        }
        node
    }
}

/// Row-major index tuples of `dims`.
fn indexes(dims: &[(i64, i64)]) -> impl Iterator<Item = Vec<i64>> + '_ {
    let mut cur: Option<Vec<i64>> = if dims.iter().all(|(lo, hi)| lo <= hi) {
        Some(dims.iter().map(|(lo, _)| *lo).collect())
    } else {
        None
    };
    std::iter::from_fn(move || {
        let out = cur.clone()?;
        let mut next = out.clone();
        let mut k = dims.len();
        loop {
            if k == 0 {
                cur = None;
                break;
            }
            k -= 1;
            let (lo, hi) = dims.get(k).copied().unwrap_or((0, 0));
            let Some(v) = next.get_mut(k) else {
                cur = None;
                break;
            };
            if *v < hi {
                *v += 1;
                cur = Some(next);
                break;
            }
            *v = lo;
        }
        Some(out)
    })
}

/// The tree of every declared variable (empty `prefix`), or the subtree
/// of the node at `prefix` (case-insensitive, `Ctrl`, `Ctrl.startEdge`);
/// `None` when nothing is there.
pub fn tree(program: &Program, prefix: &str) -> Option<Vec<Node>> {
    let mut b = Builder { program, nodes: 0 };
    // Entries are qualified (`CTRL.M1S`) or not (globals); a program
    // instance is found as the common first name of its variables.
    let mut roots: Vec<Node> = Vec::new();
    for e in program.symbols.entries() {
        let parts: Vec<&str> = e.spelling.split('.').collect();
        if parts.iter().any(|p| p.starts_with("__")) {
            continue;
        }
        let Some((last, init)) = parts.split_last() else {
            continue;
        };
        if b.nodes >= MAX_NODES {
            break;
        }
        insert(&mut b, &mut roots, "", init, last, &e.ty);
    }
    let prefix = prefix.trim();
    if prefix.is_empty() {
        return Some(roots);
    }
    find(&roots, prefix).map(|n| vec![n.clone()])
}

/// Puts the entry `init.last` under the nodes named by `init` (made as
/// program instance nodes when missing).
fn insert(
    b: &mut Builder,
    level: &mut Vec<Node>,
    path: &str,
    init: &[&str],
    last: &str,
    ty: &SymbolType,
) {
    let join = |name: &str| {
        if path.is_empty() {
            name.to_string()
        } else {
            format!("{path}.{name}")
        }
    };
    match init.split_first() {
        None => {
            if !level.iter().any(|n| n.name.eq_ignore_ascii_case(last)) {
                let node = b.node(last.to_string(), join(last), ty);
                level.push(node);
            }
        }
        Some((first, rest)) => {
            let pos = match level
                .iter()
                .position(|n| n.name.eq_ignore_ascii_case(first))
            {
                Some(i) => i,
                None => {
                    level.push(Node {
                        name: first.to_string(),
                        path: join(first),
                        ty: "PROGRAM".to_string(),
                        writable: false,
                        children: Vec::new(),
                        more: 0,
                    });
                    level.len() - 1
                }
            };
            if let Some(n) = level.get_mut(pos) {
                let here = n.path.clone();
                insert(b, &mut n.children, &here, rest, last, ty);
            }
        }
    }
}

fn find<'a>(nodes: &'a [Node], path: &str) -> Option<&'a Node> {
    for n in nodes {
        if n.path.eq_ignore_ascii_case(path) {
            return Some(n);
        }
        let below = n.path.len() < path.len()
            && path
                .get(..n.path.len())
                .is_some_and(|p| p.eq_ignore_ascii_case(&n.path))
            && matches!(path.as_bytes().get(n.path.len()), Some(b'.' | b'['));
        if below {
            return find(&n.children, path);
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::indexes;

    #[test]
    fn indexes_are_row_major() {
        let all: Vec<Vec<i64>> = indexes(&[(1, 2), (0, 1)]).collect();
        assert_eq!(all, vec![vec![1, 0], vec![1, 1], vec![2, 0], vec![2, 1]]);
        assert_eq!(indexes(&[(3, 2)]).count(), 0);
    }
}
