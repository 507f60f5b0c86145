//! cosserat-check: a derivation checker for continuum mechanics.
//!
//! Its first corpus is Papanicolopoulos & Veveakis, *Sliding and rolling dissipation
//! in Cosserat plasticity*. Every checkable statement of the paper is a claim in a
//! file under `derivations/`; the checker decides each claim and reports a verdict
//! with its evidence. Data flows one way: file → parse/validate → decide → report.

pub use cosserat_algebra as algebra;
pub mod check;
pub mod cli;
pub mod corpus;
pub mod decide;
pub mod derivation;
pub mod digits;
pub mod eval;
pub use cosserat_kernel as kernel;
pub use cosserat_lang as lang;
/// Mutants of a statement, for the unit tests of the index canonicaliser (the sweep
/// over the paper is `tests/mutants.rs`); test-only, so it lives with the tests.
#[cfg(test)]
#[path = "../tests/support/mutate.rs"]
mod mutate;
pub mod parallel;
pub mod recheck;
pub mod report;
pub mod tolerance;
