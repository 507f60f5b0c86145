//! A request to stop, for the one kernel computation without a work bound of its own:
//! the remainder sequence of [`super::gcd`], the gcd's last resort.
//!
//! Every other kernel computation is bounded by the size of its input or by a budget
//! of terms, points or bisections. The pseudo-remainder sequence over ℚ is not: its
//! coefficients can swell for minutes on inputs of a few dozen terms. So a decision
//! runs the kernel [`under`] a stop condition (the claim's time limit, from
//! `strategy::watch`), and the remainder sequence asks [`requested`] between steps.
//!
//! A stopped computation returns a value that means nothing. That is sound only
//! because whoever set the condition discards everything computed after it became
//! true: the time-limit watch makes such a decision `undecided (time limit)`.
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
pub(super) fn requested() -> bool {
    CONDITION.with(|c| c.borrow().as_ref().is_some_and(|stop| stop()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicBool, Ordering};

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
}
