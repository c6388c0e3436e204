//! CODESYS's clock: `TIME()`, the function of the CODESYS standard library
//! that reads the time since the PLC started. OSCAT's `T_PLC_MS` and
//! `T_PLC_US` are written on it, and through them the library's ramps,
//! profiles, ontime counters and pulse generators.
//!
//! The rewrite makes each call `TIME()` without arguments a call of
//! `__SCAN_TIME()`, the clock the standard timers read: the PLC time of the
//! current scan (virtual in tests, so the value is exact: scan k reads
//! (k − 1) × cycle time). Two readings within one scan are therefore equal,
//! where CODESYS's millisecond clock may advance during a long scan; no
//! OSCAT block depends on that. `TIME` with arguments, or as a type, is
//! left alone (the checker reports a misuse as before).

use crate::walk;
use automat_base::{Interner, Symbol};
use automat_syntax::ast::{Body, Expr, ExprKind, Item, SourceUnit};

/// Rewrites the `TIME()` calls of the user's units.
pub fn rewrite(
    units: &mut [SourceUnit],
    is_user: &dyn Fn(&SourceUnit) -> bool,
    interner: &mut Interner,
) {
    let mut c = Clock {
        time: interner.intern("TIME"),
        scan_time: interner.intern("__SCAN_TIME"),
    };
    for unit in units.iter_mut().filter(|u| is_user(u)) {
        items(&mut unit.items, &mut c);
    }
}

fn items(list: &mut [Item], c: &mut Clock) {
    for item in list {
        match item {
            Item::Pou(p) => {
                let Body::St(stmts) = &mut p.body;
                walk::stmts(stmts, c);
            }
            Item::Class(cl) => {
                walk::stmts(&mut cl.body, c);
                for m in &mut cl.methods {
                    walk::stmts(&mut m.body, c);
                }
                for prop in &mut cl.properties {
                    for acc in [&mut prop.get, &mut prop.set].into_iter().flatten() {
                        walk::stmts(&mut acc.body, c);
                    }
                }
            }
            Item::Namespace(ns) => items(&mut ns.items, c),
            _ => {}
        }
    }
}

struct Clock {
    time: Symbol,
    scan_time: Symbol,
}

impl walk::Visitor for Clock {
    fn expr(&mut self, e: &mut Expr) {
        if let ExprKind::Call { callee, args } = &mut e.kind {
            if args.is_empty() {
                if let ExprKind::Name(id) = &mut callee.kind {
                    if id.sym == self.time {
                        id.sym = self.scan_time;
                    }
                }
            }
        }
    }
}
