//! Strategies: how a claim is decided. Each returns an [`Outcome`] carrying the
//! evidence its verdict requires (component checks, counterexample, the kernel's
//! certificate). `Outcome` lives in its own module so that no strategy can reach its
//! private fields: a proved `holds` is made only from a certificate.

pub mod assume;
mod claim;
pub mod decided;
mod dispatch;
pub mod eval;
pub mod exact;
mod exact_ring;
pub mod finding;

mod indices;
#[cfg(test)]
mod indices_tests;
pub mod inherit;
mod interval;
pub mod isolate;
mod jets;
pub mod numeric;
mod outcome;
pub mod parametrisation;
pub mod points;
pub mod probe;
mod proportional;
pub mod quadrature;
pub mod random;
pub mod real;
mod reverify;
pub mod sampler;
mod scalar;
pub mod search;
pub mod statement;
pub mod tape;
pub mod taylor;
pub mod tolerance;
pub mod transcription;
pub mod walk;
pub mod watch;
pub mod witness;

pub use claim::{decide_claim, decide_claim_recorded};
pub use decided::{Attribution, Decided};
pub use dispatch::decide;
pub use outcome::{
    Counterexample, FactorWitness, Measure, Method, NumericEvidence, Outcome, Reverified,
    SearchEvidence, Strength,
};
