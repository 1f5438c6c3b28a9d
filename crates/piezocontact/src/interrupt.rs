//! A request to stop the runs of this process at their next safe point — a signal (SIGINT,
//! SIGTERM) caught by the command, or Ctrl-C in Python. The contact algorithms look at it
//! before every outer step, Uzawa iteration and Newton step, and stop with
//! [`crate::Error::Interrupted`], keeping the last iterate as they do at an iteration cap.
//! A factorisation in progress finishes first.

use std::sync::atomic::{AtomicI32, Ordering};

/// The signal that asked for the stop (0: none).
static SIGNAL: AtomicI32 = AtomicI32::new(0);

/// Asks the runs to stop, for `signal` (its number; any non-zero value). Returns whether
/// this was the first request. Async-signal-safe: one atomic operation.
pub fn request(signal: i32) -> bool {
    SIGNAL.compare_exchange(0, signal, Ordering::SeqCst, Ordering::SeqCst).is_ok()
}

/// The signal of the pending request, if any.
pub fn requested() -> Option<i32> {
    match SIGNAL.load(Ordering::SeqCst) {
        0 => None,
        signal => Some(signal),
    }
}

/// Withdraws a request (before a new run in a process that goes on, such as Python's).
pub fn clear() {
    SIGNAL.store(0, Ordering::SeqCst);
}
