//! Stopping a run from outside: the [`Interrupt`] flag every backend polls.
//!
//! A backend owns one flag and hands out clones of it; another thread (the
//! runtime's watchdog timer, a stop request) raises it, and the run in
//! progress faults at its next poll with [`crate::FaultKind::Watchdog`]
//! naming the statement it was executing. The backends poll at least every
//! [`POLL_INSTRUCTIONS`] instructions (so inside every loop, on both
//! engines) and after every copy of [`POLL_COPY_BYTES`] bytes or more (one
//! instruction that can take milliseconds). Who raised the flag and why is
//! the raiser's business: the runtime rewrites the fault's message.
//!
//! Polling is a relaxed load; the flag is cleared by whoever arms it next,
//! never by the backend, so a raise between two runs is not lost.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// Instructions a backend may execute between two polls of the flag.
/// Small enough that a poll comes within about a millisecond on the
/// interpreter, large enough that the poll itself costs nothing measurable.
pub const POLL_INSTRUCTIONS: u64 = 1 << 16;

/// A block copy at least this long polls the flag when it is done.
pub const POLL_COPY_BYTES: u32 = 1 << 16;

/// The message of the fault a raised flag produces; the runtime replaces
/// it with the reason (a task's watchdog time, a stop request).
pub const INTERRUPTED: &str = "watchdog: the run was interrupted";

/// A shared "stop this run" flag (cheap to clone, `Send + Sync`).
#[derive(Clone, Debug, Default)]
pub struct Interrupt(Arc<AtomicBool>);

impl Interrupt {
    pub fn new() -> Interrupt {
        Interrupt::default()
    }

    /// Asks the run in progress (or the next one) to stop.
    pub fn raise(&self) {
        self.0.store(true, Ordering::Release);
    }

    pub fn clear(&self) {
        self.0.store(false, Ordering::Release);
    }

    #[inline]
    pub fn is_raised(&self) -> bool {
        self.0.load(Ordering::Relaxed)
    }

    /// The flag itself, for generated code that polls it through a pointer
    /// (valid as long as a clone of this handle lives).
    pub fn as_ptr(&self) -> *const AtomicBool {
        Arc::as_ptr(&self.0)
    }

    /// Whether two handles are the same flag.
    pub fn same(&self, other: &Interrupt) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

#[cfg(test)]
mod tests {
    use super::Interrupt;

    #[test]
    fn clones_share_the_flag() {
        let a = Interrupt::new();
        let b = a.clone();
        assert!(!b.is_raised());
        a.raise();
        assert!(b.is_raised());
        b.clear();
        assert!(!a.is_raised());
        assert!(a.same(&b));
        assert!(!a.same(&Interrupt::new()));
    }
}
