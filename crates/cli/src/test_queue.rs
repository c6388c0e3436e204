//! The order in which `automat test`'s workers take items.
//!
//! Items come in the order they were found, so a project's scenarios sit
//! side by side: taken strictly in order, the second worker would wait for
//! the compile the first one is doing. Instead a worker takes the first
//! remaining item whose project no other worker is building, and only waits
//! for a compile when nothing else is left. Once built, a project's items
//! go first to a worker that will find one of its compiled backends idle:
//! one more worker on the same project compiles it again (9 % more CPU for
//! `automat test examples tests/conformance` on 2 workers than on 1), so
//! that is done only when nothing else is left. Reports are still printed
//! in item order (`cmd_test::run_all`), so the output does not depend on it.

use std::collections::{BTreeMap, VecDeque};
use std::path::PathBuf;
use std::sync::{Mutex, MutexGuard};

/// The items not taken yet, and which projects are built or being built.
pub struct Queue {
    state: Mutex<State>,
    /// Each item's project (an index into `tomls`), `None` for items that
    /// need none (conformance programs, scenarios outside a project).
    project_of: Vec<Option<usize>>,
    tomls: Vec<PathBuf>,
}

struct State {
    remaining: VecDeque<usize>,
    progress: Vec<Progress>,
    /// By project: its items running now, and the most that ran at once
    /// (the backends its pool has compiled).
    running: Vec<usize>,
    backends: Vec<usize>,
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Progress {
    NotStarted,
    Building,
    Built,
}

/// An item to run; `build` is the project the taker must build first
/// (then report with [`Queue::built`]).
pub struct Take {
    pub item: usize,
    pub build: Option<(usize, PathBuf)>,
}

impl Queue {
    /// `projects[i]` is item i's `automat.toml`, if it has one.
    pub fn new(projects: Vec<Option<PathBuf>>) -> Queue {
        let mut index: BTreeMap<PathBuf, usize> = BTreeMap::new();
        let mut tomls = Vec::new();
        let project_of = projects
            .into_iter()
            .map(|p| {
                p.map(|toml| {
                    *index.entry(toml.clone()).or_insert_with(|| {
                        tomls.push(toml);
                        tomls.len() - 1
                    })
                })
            })
            .collect::<Vec<_>>();
        Queue {
            state: Mutex::new(State {
                remaining: (0..project_of.len()).collect(),
                progress: vec![Progress::NotStarted; tomls.len()],
                running: vec![0; tomls.len()],
                backends: vec![0; tomls.len()],
            }),
            project_of,
            tomls,
        }
    }

    fn lock(&self) -> MutexGuard<'_, State> {
        // The queue's state is consistent between any two statements.
        self.state.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// The next item, or `None` when all are taken.
    pub fn take(&self) -> Option<Take> {
        let mut s = self.lock();
        // First an item that costs no extra compile, then one that waits
        // for none.
        let cheap = s.remaining.iter().position(|&i| match self.project_of[i] {
            None => true,
            Some(p) => match s.progress[p] {
                Progress::NotStarted => true,
                Progress::Building => false,
                Progress::Built => s.running[p] < s.backends[p],
            },
        });
        let free = cheap.or_else(|| {
            s.remaining.iter().position(|&i| match self.project_of[i] {
                None => true,
                Some(p) => s.progress[p] != Progress::Building,
            })
        });
        // Everything left waits for a compile in progress: wait for it
        // (in the project's cell) rather than spin.
        let item = s.remaining.remove(free.unwrap_or(0))?;
        if let Some(p) = self.project_of[item] {
            s.running[p] += 1;
            s.backends[p] = s.backends[p].max(s.running[p]);
        }
        let build = match self.project_of[item] {
            Some(p) if s.progress[p] == Progress::NotStarted => {
                s.progress[p] = Progress::Building;
                Some((p, self.tomls[p].clone()))
            }
            _ => None,
        };
        Some(Take { item, build })
    }

    /// The project a [`Take`] asked for is built (or failed to build: its
    /// scenarios report that without waiting).
    pub fn built(&self, project: usize) {
        if let Some(p) = self.lock().progress.get_mut(project) {
            *p = Progress::Built;
        }
    }

    /// A taken item has run (its backend is idle again).
    pub fn done(&self, item: usize) {
        if let Some(&Some(p)) = self.project_of.get(item) {
            if let Some(n) = self.lock().running.get_mut(p) {
                *n = n.saturating_sub(1);
            }
        }
    }

    /// How many items were taken.
    pub fn taken(&self) -> usize {
        self.project_of.len() - self.lock().remaining.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn order(q: &Queue, build_done: bool) -> Vec<usize> {
        let mut out = Vec::new();
        while let Some(t) = q.take() {
            if let (true, Some((p, _))) = (build_done, &t.build) {
                q.built(*p);
            }
            out.push(t.item);
        }
        out
    }

    #[test]
    fn a_second_worker_passes_a_project_being_built() {
        let a = Some(PathBuf::from("a/automat.toml"));
        let b = Some(PathBuf::from("b/automat.toml"));
        let q = Queue::new(vec![a.clone(), a.clone(), a, None, b.clone(), b]);
        // Worker 1 builds project a; worker 2 skips a's other scenarios.
        let first = q.take().map(|t| (t.item, t.build.map(|b| b.0)));
        assert_eq!(first, Some((0, Some(0))));
        let second = q.take().map(|t| (t.item, t.build.is_some()));
        assert_eq!(second, Some((3, false)));
        let third = q.take().map(|t| (t.item, t.build.map(|b| b.0)));
        assert_eq!(third, Some((4, Some(1))));
        // Both projects are being built: the next taker waits on a's.
        let fourth = q.take().map(|t| (t.item, t.build.is_some()));
        assert_eq!(fourth, Some((1, false)));
        q.built(0);
        assert_eq!(q.take().map(|t| t.item), Some(2));
        assert_eq!(q.taken(), 5);
    }

    #[test]
    fn a_built_project_waits_for_its_idle_backend() {
        let a = Some(PathBuf::from("a/automat.toml"));
        let q = Queue::new(vec![a.clone(), a.clone(), None, None, a]);
        let first = q.take().map(|t| (t.item, t.build.map(|b| b.0)));
        assert_eq!(first, Some((0, Some(0))));
        q.built(0);
        // Item 0 holds a's only backend: the other worker runs item 2
        // rather than compile a again.
        assert_eq!(q.take().map(|t| t.item), Some(2));
        q.done(0);
        assert_eq!(q.take().map(|t| t.item), Some(1));
        // Nothing else left but a's item 4 while item 1 runs: a second
        // backend is compiled (3 is free, so it goes first).
        assert_eq!(q.take().map(|t| t.item), Some(3));
        assert_eq!(q.take().map(|t| t.item), Some(4));
        q.done(1);
        q.done(4);
        assert!(q.take().is_none());
    }

    #[test]
    fn one_worker_takes_items_in_order() {
        let a = Some(PathBuf::from("a/automat.toml"));
        let q = Queue::new(vec![a.clone(), None, a]);
        assert_eq!(order(&q, true), vec![0, 1, 2]);
        assert!(q.take().is_none());
    }
}
