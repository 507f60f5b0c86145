//! Deciding one claim: each claim kind returns an [`Outcome`] carrying the evidence its
//! verdict requires (component checks, counterexample, the kernel's certificate).
//! `Outcome` lives in its own module so that no decision can reach its private fields:
//! a proved `holds` is made only from a fact the kernel checked.
//!
//! The claim kinds: [`identity`] (exact, component by component, with the
//! symbolic-index route of `indices` and `proportional` claims), [`numeric`] (sampled
//! relations, gradients and convexity, with the [`sampler`], the adversarial [`search`]
//! and one random generator, [`random`]), `scalar` (sign, monotonicity, limits,
//! roots) and [`witness`]; `reverify` confirms a counterexample by a second method
//! before it is printed; [`drafted`] keeps a drafted file's guesses from becoming
//! errors of the paper. [`finding`] holds what a decision found, as data; [`watch`]
//! is the per-claim time limit the decisions poll.

pub mod drafted;
pub(crate) mod enclosures;
pub mod finding;
pub mod identity;
pub(crate) mod indices;
#[cfg(test)]
mod indices_tests;
pub mod numeric;
mod outcome;
pub mod points;
pub(crate) mod proportional;
pub mod random;
pub(crate) mod reverify;
pub mod sampler;
pub(crate) mod scalar;
pub mod search;
pub mod watch;
pub mod witness;

pub use outcome::{
    Counterexample, FactorWitness, Measure, Method, NumericEvidence, Outcome, Reverified,
    SearchEvidence, Strength,
};
