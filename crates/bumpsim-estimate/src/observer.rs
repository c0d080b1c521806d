//! What a long estimation reports while it runs (argmin's observers): the
//! search calls the observer instead of requiring a progress closure, so a
//! progress bar, a log or nothing at all can watch.
//!
//! ```
//! use bumpsim_estimate::observer::{Observer, Silent};
//! use std::sync::atomic::{AtomicUsize, Ordering};
//! let finished = AtomicUsize::new(0);
//! let count = || { finished.fetch_add(1, Ordering::Relaxed); };
//! let observers: [&dyn Observer; 2] = [&count, &Silent];
//! observers.iter().for_each(|o| o.start_finished());
//! assert_eq!(finished.into_inner(), 1);
//! ```

/// Watches a search; called from any thread.
pub trait Observer: Sync {
    /// One start has finished (run to its end, abandoned or merged).
    fn start_finished(&self) {}
}

/// An observer that watches nothing.
#[derive(Debug, Clone, Copy, Default)]
pub struct Silent;

impl Observer for Silent {}

/// Any `Fn() + Sync` closure counts finished starts (a progress bar's `inc`).
impl<F: Fn() + Sync> Observer for F {
    fn start_finished(&self) {
        self()
    }
}
