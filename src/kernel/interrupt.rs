//! A request to stop: for the remainder sequence of `algebra::gcd` (asked between
//! steps), and for every long evaluation, polynomial product or root isolation, which
//! [`tick`]s and is unwound to [`stoppable`] once the claim's time is up. It lives in
//! the kernel because the kernel's products tick too; a stop never makes a verdict:
//! whatever was being computed is abandoned, and the claim is `undecided`.
//!
//! Every other computation a decision runs is bounded by the size of its input or by a
//! budget of terms, points or bisections. The algebra's pseudo-remainder sequence over ℚ
//! is not: its
//! coefficients can swell for minutes on inputs of a few dozen terms. So a decision
//! runs the kernel [`under`] a stop condition (the claim's time limit, from
//! `decide::watch`), and the remainder sequence asks [`requested`] between steps.
//!
//! A stopped computation returns a value that means nothing. That is sound only
//! because whoever set the condition discards everything computed after it became
//! true: the time-limit watch makes such a decision `undecided (time limit)`, and a
//! trial bounded by [`within`] is abandoned for another route.
//! Outside [`under`] nothing ever stops.

use std::cell::RefCell;
use std::sync::Arc;

/// Whether the computation should stop now.
pub type Stop = Arc<dyn Fn() -> bool + Send + Sync>;

thread_local! {
    static CONDITION: RefCell<Option<Stop>> = const { RefCell::new(None) };
}

/// Runs `f` on this thread with `stop` as the stop condition (the previous one is
/// restored afterwards).
pub fn under<T>(stop: Stop, f: impl FnOnce() -> T) -> T {
    let previous = CONDITION.with(|c| c.replace(Some(stop)));
    let out = f();
    CONDITION.with(|c| *c.borrow_mut() = previous);
    out
}

/// Whether the current stop condition holds (never outside [`under`]). Once it has
/// held, the caller's results are meaningless; see the module doc.
pub fn requested() -> bool {
    CONDITION.with(|c| c.borrow().as_ref().is_some_and(|stop| stop()))
}

/// What a computation stopped by [`tick`] unwinds with.
#[derive(Debug)]
pub struct Stopped;

thread_local! {
    static TICKS: std::cell::Cell<u64> = const { std::cell::Cell::new(0) };
}

/// A point in a long computation (a node of an evaluation, a step of a Sturm sequence)
/// where it may be stopped: every 1,024th call checks the stop condition, and once it
/// holds, unwinds with [`Stopped`] to the nearest [`stoppable`] (the panic hook does
/// not run; nothing is printed). Outside [`under`] it never stops.
pub fn tick() {
    tick_by(1);
}

/// [`tick`] for a step worth `work` simple ones (a row of a polynomial product): the
/// condition is checked once per 1,024 units of work.
pub fn tick_by(work: usize) {
    let (before, after) = TICKS.with(|t| {
        let before = t.get();
        let after = before.wrapping_add(work as u64);
        t.set(after);
        (before, after)
    });
    if before / 1024 != after / 1024 && requested() {
        std::panic::resume_unwind(Box::new(Stopped));
    }
}

/// Runs `f` as a trial of at most `work` units of ticked work, under the current stop
/// condition too: `Err(Stopped)` when either stopped it. The units are the ticks of the
/// computation itself, not time: the same input stops within the same 1,024 ticks on
/// any machine, however loaded.
pub fn within<T>(work: u64, f: impl FnOnce() -> T) -> Result<T, Stopped> {
    let start = TICKS.with(std::cell::Cell::get);
    let outer = CONDITION.with(|c| c.borrow().clone());
    let stop: Stop = Arc::new(move || {
        TICKS.with(std::cell::Cell::get).wrapping_sub(start) > work
            || outer.as_ref().is_some_and(|s| s())
    });
    // `stoppable` inside `under`: the unwinding stops before `under` restores the
    // condition.
    under(stop, || stoppable(f))
}

/// Runs `f`; `Err(Stopped)` when a [`tick`] inside it stopped it. Any other panic goes
/// on unwinding.
pub fn stoppable<T>(f: impl FnOnce() -> T) -> Result<T, Stopped> {
    match std::panic::catch_unwind(std::panic::AssertUnwindSafe(f)) {
        Ok(v) => Ok(v),
        Err(p) if p.is::<Stopped>() => Err(Stopped),
        Err(p) => std::panic::resume_unwind(p),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicBool, Ordering};

    #[test]
    fn a_tick_stops_a_computation_only_under_a_condition_that_holds() {
        let endless = || loop {
            tick();
        };
        let stopped = under(Arc::new(|| true), || stoppable(endless));
        assert!(stopped.is_err());
        let counted = under(Arc::new(|| false), || {
            stoppable(|| (0..5_000).for_each(|_| tick()))
        });
        assert!(counted.is_ok());
        // Another panic is not a stop.
        let other = std::panic::catch_unwind(|| stoppable(|| panic!("a defect")));
        assert!(other.is_err());
    }

    #[test]
    fn a_stop_is_requested_only_under_a_condition_that_holds() {
        assert!(!requested());
        let flag = Arc::new(AtomicBool::new(false));
        let seen = flag.clone();
        under(Arc::new(move || seen.load(Ordering::Relaxed)), || {
            assert!(!requested());
            flag.store(true, Ordering::Relaxed);
            assert!(requested());
            // A nested condition replaces the outer one and gives it back.
            under(Arc::new(|| false), || assert!(!requested()));
            assert!(requested());
        });
        assert!(!requested());
    }

    #[test]
    fn a_trial_stops_at_its_work_and_under_the_outer_condition() {
        // Within its work: the value. Past it: stopped, and nothing is requested after.
        assert_eq!(
            within(10_000, || (0..5_000).map(|_| tick()).count()).ok(),
            Some(5_000)
        );
        assert!(within(10_000, || loop {
            tick();
        })
        .is_err());
        assert!(!requested());
        // The same work stops at the same tick each time (the condition is asked once
        // per 1,024 ticks).
        let count = || {
            let n = std::cell::Cell::new(0u64);
            let _ = within(50_000, || loop {
                tick();
                n.set(n.get() + 1);
            });
            n.get()
        };
        let first = count();
        assert!((50_000..=51_024).contains(&first), "{first}");
        assert_eq!(count(), first);
        // An outer condition that holds stops the trial, and is in force after it.
        under(Arc::new(|| true), || {
            assert!(within(u64::MAX, || loop {
                tick();
            })
            .is_err());
            assert!(requested());
        });
    }
}
