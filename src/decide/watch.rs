//! What a decision reports while it runs, and the per-claim time limit that stops it.
//!
//! A worker thread decides one claim at a time under a [`Watch`]: the sampled
//! strategies say how many samples (or search evaluations) they have done out of how
//! many, which the command line shows as progress, and they ask [`check`] between
//! samples whether the claim's time is up. When it is, the decision stops and the claim
//! is `undecided (time limit)` (`check::decide`): a runaway claim never runs without
//! bound, and never becomes a verdict. A decision that finishes within its limit
//! computes what it would compute without a watch; one that does not is undecided, and
//! says so.

use std::cell::RefCell;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// The per-claim time limit when none is given: generous, so that only a runaway claim
/// reaches it (the slowest claim of the paper takes well under a second).
pub const DEFAULT_LIMIT: Duration = Duration::from_secs(600);

/// One claim's decision as the outside sees it.
#[derive(Debug)]
pub struct Watch {
    pub claim: String,
    started: Instant,
    limit: Duration,
    expired: AtomicBool,
    phase: Mutex<&'static str>,
    done: AtomicUsize,
    total: AtomicUsize,
}

impl Watch {
    pub fn new(claim: &str, limit: Duration) -> Arc<Self> {
        Arc::new(Watch {
            claim: claim.to_owned(),
            started: Instant::now(),
            limit,
            expired: AtomicBool::new(false),
            phase: Mutex::new(""),
            done: AtomicUsize::new(0),
            total: AtomicUsize::new(0),
        })
    }

    /// `claim: phase done/total, seconds` — what progress shows about it.
    pub fn status(&self) -> String {
        let phase = *self.phase.lock().unwrap_or_else(|e| e.into_inner());
        let (done, total) = (
            self.done.load(Ordering::Relaxed),
            self.total.load(Ordering::Relaxed),
        );
        let work = if total > 0 {
            format!(" {phase} {done}/{total},")
        } else {
            String::new()
        };
        format!(
            "{}:{work} {:.1} s",
            self.claim,
            self.started.elapsed().as_secs_f64()
        )
    }

    /// Whether the time limit has passed (checked against the clock).
    pub fn expired(&self) -> bool {
        if !self.expired.load(Ordering::Relaxed) && self.started.elapsed() > self.limit {
            self.expired.store(true, Ordering::Relaxed);
        }
        self.expired.load(Ordering::Relaxed)
    }

    pub fn limit(&self) -> Duration {
        self.limit
    }
}

thread_local! {
    static CURRENT: RefCell<Option<Arc<Watch>>> = const { RefCell::new(None) };
}

/// Runs `f` on this thread under `watch`. The kernel's unbounded step (a gcd's
/// remainder sequence) stops once the watch has expired (`kernel::interrupt`); the
/// decision is then undecided, so what it computed after that is never used.
pub fn under<T>(watch: &Arc<Watch>, f: impl FnOnce() -> T) -> T {
    let previous = CURRENT.with(|c| c.replace(Some(watch.clone())));
    let stop = {
        let watch = watch.clone();
        Arc::new(move || watch.expired())
    };
    let out = crate::kernel::interrupt::under(stop, f);
    CURRENT.with(|c| *c.borrow_mut() = previous);
    out
}

fn with<T>(f: impl FnOnce(&Watch) -> T) -> Option<T> {
    CURRENT.with(|c| c.borrow().as_deref().map(f))
}

/// Reports progress: `done` of `total` units of `phase` ("samples", "search").
pub fn progress(phase: &'static str, done: usize, total: usize) {
    with(|w| {
        *w.phase.lock().unwrap_or_else(|e| e.into_inner()) = phase;
        w.done.store(done, Ordering::Relaxed);
        w.total.store(total, Ordering::Relaxed);
    });
}

/// The claim's time is up.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TimeUp;

/// `Err(TimeUp)` once the current claim's time limit has passed (never without a
/// watch).
pub fn check() -> Result<(), TimeUp> {
    match with(Watch::expired) {
        Some(true) => Err(TimeUp),
        _ => Ok(()),
    }
}

/// Whether the current claim's time limit has passed, and the limit.
pub fn expired() -> Option<Duration> {
    with(|w| w.expired().then(|| w.limit())).flatten()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_watch_expires_after_its_limit_and_only_under_it() {
        let w = Watch::new("c", Duration::ZERO);
        assert_eq!(check(), Ok(()));
        std::thread::sleep(Duration::from_millis(2));
        under(&w, || {
            assert_eq!(check(), Err(TimeUp));
            assert_eq!(expired(), Some(Duration::ZERO));
        });
        assert_eq!(check(), Ok(()));
        let long = Watch::new("d", DEFAULT_LIMIT);
        under(&long, || {
            progress("samples", 3, 200);
            assert_eq!(check(), Ok(()));
        });
        assert!(
            long.status().starts_with("d: samples 3/200,"),
            "{}",
            long.status()
        );
    }
}
