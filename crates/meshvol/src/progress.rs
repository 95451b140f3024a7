//! Progress from inside long kernels, for a progress display: which stage a kernel is
//! in, and how far through it.
//!
//! A kernel takes `&dyn Progress` and calls [`Progress::stage`] as each stage starts
//! and [`Progress::advance`] as work is done, with `done` of `total` units of the
//! current stage (points inserted, rows of columns, pairs of triangles: the stage's
//! own units). Both do nothing unless the caller implements them: `&()` asks for no
//! progress, and a closure taking a stage name (what the check always took,
//! [`StageReport`]) gets the stages only.
//!
//! The same hook lets the caller give up: [`Progress::cancelled`] says the result is no
//! longer wanted (a server's request past its deadline), and a kernel that asks stops
//! at its next stage with an error instead of finishing (the check does). A hook is the
//! caller's own state, so two calls never cancel each other.
//!
//! Kernels report per chunk of work, never per item: a [`Counter`] adds a chunk's
//! units from any thread and passes on a count that only grows and ends at `total`,
//! so the hook costs an atomic add and a short lock per chunk, and nothing per point.
//! Progress never changes what a kernel computes.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;

/// What a long kernel tells its caller as it goes. Called from any of the kernel's
/// threads; both methods default to doing nothing.
pub trait Progress: Sync {
    /// A stage starts (`"welding"`, `"inserting points"`, ...).
    fn stage(&self, _name: &'static str) {}
    /// `done` of `total` units of the current stage are done: within a stage `done`
    /// only grows, and the last call of a stage that finishes has `done == total`.
    fn advance(&self, _done: u64, _total: u64) {}
    /// Whether the caller no longer wants the result: a kernel that asks stops at its
    /// next stage with an error. Never, unless the caller implements it.
    fn cancelled(&self) -> bool {
        false
    }
}

/// No progress wanted.
impl Progress for () {}

/// A closure given each stage's name as it starts (the stages only).
impl<F: Fn(&'static str) + Sync> Progress for F {
    fn stage(&self, name: &'static str) {
        self(name)
    }
}

/// A progress hook as kernels take it.
pub type StageReport<'a> = &'a dyn Progress;

/// Counts one stage's units done, from any thread, for [`Progress::advance`].
pub struct Counter<'a> {
    progress: &'a dyn Progress,
    total: u64,
    done: AtomicU64,
    /// The largest count passed on so far: a thread that finished an earlier chunk but
    /// reports later passes nothing on, so the counts seen only grow.
    reported: Mutex<u64>,
}

impl<'a> Counter<'a> {
    /// Starts a count of `total` units at 0 (and says so).
    pub fn new(progress: &'a dyn Progress, total: usize) -> Counter<'a> {
        let total = total as u64;
        progress.advance(0, total);
        Counter { progress, total, done: AtomicU64::new(0), reported: Mutex::new(0) }
    }

    /// Adds `units` done (a chunk's) and reports the count.
    pub fn add(&self, units: usize) {
        let done =
            (self.done.fetch_add(units as u64, Ordering::Relaxed) + units as u64).min(self.total);
        // A poisoned lock (a hook that panicked) only stops the reports.
        if let Ok(mut reported) = self.reported.lock() {
            if done > *reported {
                *reported = done;
                self.progress.advance(done, self.total);
            }
        }
    }
}

/// A hook that records every call, and checks them.
#[cfg(test)]
pub(crate) mod testing {
    use super::Progress;
    use std::sync::Mutex;

    /// Records every call: (stage, 0, 0) for a stage, ("", done, total) for an advance.
    #[derive(Default)]
    pub(crate) struct Record {
        calls: Mutex<Vec<(&'static str, u64, u64)>>,
    }

    impl Progress for Record {
        fn stage(&self, name: &'static str) {
            self.calls.lock().unwrap().push((name, 0, 0));
        }
        fn advance(&self, done: u64, total: u64) {
            self.calls.lock().unwrap().push(("", done, total));
        }
    }

    impl Record {
        /// The stages that counted their work, in order, having checked that in each
        /// the count never falls, keeps one total, and ends at it.
        pub fn counted_stages(self) -> Vec<&'static str> {
            let calls = self.calls.into_inner().unwrap();
            let mut counted = Vec::new();
            let mut i = 0;
            while i < calls.len() {
                let name = calls[i].0;
                let end =
                    (i + 1..calls.len()).find(|&j| !calls[j].0.is_empty()).unwrap_or(calls.len());
                let advances = &calls[i + 1..end];
                if let Some(last) = advances.last() {
                    assert!(
                        advances.windows(2).all(|w| w[0].1 <= w[1].1 && w[0].2 == w[1].2),
                        "{name}: {advances:?}"
                    );
                    assert_eq!(last.1, last.2, "{name} ends short: {advances:?}");
                    counted.push(name);
                }
                i = end;
            }
            counted
        }
    }
}

#[cfg(test)]
mod tests {
    use super::testing::Record;
    use super::*;
    use rayon::prelude::*;

    #[test]
    fn counts_from_many_threads_only_grow_and_end_at_the_total() {
        let record = Record::default();
        record.stage("adding");
        let counter = Counter::new(&record, 10_000);
        (0..100).into_par_iter().for_each(|_| counter.add(100));
        assert_eq!(record.counted_stages(), ["adding"]);
        // The stages of a closure, nothing else.
        let names = Mutex::new(Vec::new());
        let hook = |name: &'static str| names.lock().unwrap().push(name);
        let p: &dyn Progress = &hook;
        p.stage("one");
        p.advance(1, 2);
        assert_eq!(names.into_inner().unwrap(), ["one"]);
    }

    /// Cancels once `after` stages have started.
    struct CancelAfter {
        after: usize,
        started: Mutex<Vec<&'static str>>,
    }

    impl Progress for CancelAfter {
        fn stage(&self, name: &'static str) {
            self.started.lock().unwrap().push(name);
        }
        fn cancelled(&self) -> bool {
            self.started.lock().unwrap().len() >= self.after
        }
    }

    #[test]
    fn a_cancelled_check_stops_at_its_next_stage() {
        use crate::shapes::cuboid;
        use crate::topology::{check, check_in_stages, CheckError, CheckOptions};
        let cube = cuboid([0.0; 3], [2.0; 3]);
        let options = CheckOptions::default();
        let whole = check(&cube, &options).unwrap();
        // Never cancelled: the plain check's facts.
        let never = CancelAfter { after: usize::MAX, started: Mutex::new(Vec::new()) };
        let c = check_in_stages(&cube, &[], &options, &never).unwrap();
        assert_eq!((c.volume, c.closed, c.faces), (whole.volume, whole.closed, whole.faces));
        let stages = never.started.into_inner().unwrap();
        // Cancelled after each number of stages: the error, and no stage after it.
        for after in 0..stages.len() {
            let hook = CancelAfter { after, started: Mutex::new(Vec::new()) };
            let e = check_in_stages(&cube, &[], &options, &hook).map(|_| ());
            assert_eq!(e, Err(CheckError::Cancelled));
            assert_eq!(hook.started.into_inner().unwrap(), stages[..after]);
        }
    }
}
