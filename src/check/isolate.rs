//! Panic isolation: a defect of the checker that panics while deciding one check makes
//! that check `undecided (internal error)`, never a verdict, and never ends the run.
//!
//! A panic inside [`isolated`] is caught where it unwinds to; its message and source
//! location are kept by a process-wide panic hook (installed once) for the finding, and
//! nothing is printed for it. Panics elsewhere go to the hook that was there before.
//! Everything a decision changes on its thread (the time limit's watch, the kernel's
//! interrupt flag) is restored by the guards of `watch::under` and `interrupt::under`,
//! which sit outside the isolated call.

use crate::decide::finding::Finding;
use crate::decide::{Method, Outcome};
use crate::kernel::PolyError;
use std::cell::{Cell, RefCell};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::Once;

thread_local! {
    /// How many isolated calls this thread is inside.
    static DEPTH: Cell<usize> = const { Cell::new(0) };
    /// The last panic of this thread inside an isolated call: message and location.
    static CAUGHT: RefCell<Option<(String, String)>> = const { RefCell::new(None) };
}

fn install_hook() {
    static INSTALL: Once = Once::new();
    INSTALL.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if DEPTH.with(Cell::get) == 0 {
                return previous(info);
            }
            let message = if let Some(s) = info.payload().downcast_ref::<&str>() {
                (*s).to_owned()
            } else if let Some(s) = info.payload().downcast_ref::<String>() {
                s.clone()
            } else {
                "a panic without a message".to_owned()
            };
            let at = info.location().map_or_else(
                || "an unknown place".to_owned(),
                |l| format!("{}:{}:{}", l.file(), l.line(), l.column()),
            );
            CAUGHT.with(|c| *c.borrow_mut() = Some((message, at)));
        }));
    });
}

/// What unwound out of an isolated call.
pub enum Unwound {
    /// A polynomial operator passed a limit ([`crate::kernel::poly::beyond`]).
    Limit(PolyError),
    /// A panic: its message and where in the checker it happened.
    Panic(String, String),
}

/// Runs `f`; what unwinds out of it comes back as [`Unwound`].
pub fn caught<T>(f: impl FnOnce() -> T) -> Result<T, Unwound> {
    install_hook();
    DEPTH.with(|d| d.set(d.get() + 1));
    let result = catch_unwind(AssertUnwindSafe(f));
    DEPTH.with(|d| d.set(d.get() - 1));
    result.map_err(|payload| match payload.downcast::<PolyError>() {
        Ok(e) => Unwound::Limit(*e),
        Err(_) => {
            let (message, at) = CAUGHT
                .with(|c| c.borrow_mut().take())
                .unwrap_or_else(|| ("a panic".to_owned(), "an unknown place".to_owned()));
            Unwound::Panic(message, at)
        }
    })
}

/// Runs one decision; a polynomial past its limits makes it `undecided (resource
/// limit)`, a panic `undecided (internal error)` with `method`, its message and where
/// in the checker it happened.
pub fn isolated<E>(
    method: Method,
    at: &str,
    decide: impl FnOnce() -> Result<Outcome, E>,
) -> Result<Outcome, E> {
    caught(decide).unwrap_or_else(|unwound| {
        let finding = match unwound {
            Unwound::Limit(e) => Finding::ResourceLimit {
                what: e.to_string(),
                at: at.to_owned(),
                help: "split the statement with definitions, or decide it numerically".to_owned(),
            },
            Unwound::Panic(message, at) => Finding::InternalError { message, at },
        };
        Ok(Outcome::undecided(method, 0).with_finding(finding))
    })
}

/// Whether an outcome is an internal error of the checker (exit status 3).
pub fn is_internal_error(o: &Outcome) -> bool {
    matches!(o.finding, Some(Finding::InternalError { .. }))
}

/// The test-only hook that provokes a panic inside a claim's decision: a claim with
/// this id panics (only in the library's own unit tests).
#[cfg(test)]
pub(crate) const PROVOKE_PANIC: &str = "provoke-an-internal-error";

/// The same for the transcription check of a claim with this id.
#[cfg(test)]
pub(crate) const PROVOKE_TRANSCRIPTION_PANIC: &str = "provoke-a-transcription-internal-error";

/// Panics for the claim [`PROVOKE_PANIC`] (a no-op outside the library's unit tests).
pub(crate) fn test_hook(_id: &str) {
    #[cfg(test)]
    if _id == PROVOKE_PANIC {
        panic!("provoked by the test hook");
    }
}

/// Panics for the claim [`PROVOKE_TRANSCRIPTION_PANIC`] (likewise test-only).
pub(crate) fn transcription_test_hook(_id: &str) {
    #[cfg(test)]
    if _id == PROVOKE_TRANSCRIPTION_PANIC {
        panic!("provoked by the transcription test hook");
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panic_is_the_decisions_internal_error_and_later_panics_are_reported_alike() {
        for round in 0..2 {
            let o: Result<Outcome, ()> = isolated(Method::Exact, "", || {
                let v: Vec<u8> = Vec::new();
                let _ = v[round + 3];
                unreachable!()
            });
            let o = o.unwrap();
            assert_eq!(o.verdict(), crate::derivation::Verdict::Undecided);
            let Some(Finding::InternalError { message, at }) = &o.finding else {
                panic!("{:?}", o.finding)
            };
            assert!(message.contains("index out of bounds"), "{message}");
            assert!(at.contains("isolate.rs"), "{at}");
            assert!(is_internal_error(&o));
        }
        // Outside an isolated call nothing is caught or kept.
        assert!(std::panic::catch_unwind(|| panic!("plain")).is_err());
        assert!(CAUGHT.with(|c| c.borrow().is_none()));
    }

    #[test]
    fn a_polynomial_past_its_limits_in_an_operator_is_a_resource_limit() {
        use crate::kernel::{Poly, VarTable};
        let mut names = VarTable::new();
        let x = Poly::var(names.intern("x"));
        let y = Poly::var(names.intern("y"));
        let o: Result<Outcome, ()> = isolated(Method::Exact, "f.toml:3:9", || {
            // (x + y)^4096 times itself forms more term products than allowed.
            let big = (&x + &y).pow(4096);
            let _ = &big * &big;
            unreachable!()
        });
        let o = o.unwrap();
        assert_eq!(o.verdict(), crate::derivation::Verdict::Undecided);
        let Some(Finding::ResourceLimit { what, at, .. }) = &o.finding else {
            panic!("{:?}", o.finding)
        };
        assert!(what.contains("term products"), "{what}");
        assert_eq!(at, "f.toml:3:9");
        assert!(!is_internal_error(&o));
        assert!(CAUGHT.with(|c| c.borrow().is_none()));
    }
}
