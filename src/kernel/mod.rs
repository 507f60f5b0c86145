//! The trusted kernel of cosserat-check: everything a proof depends on, and nothing
//! that searches.
//!
//! - numbers and polynomials: exact rationals ([`rational`]), canonical sparse
//!   polynomials with checked exponents ([`poly`]), fractions kept over their divisors
//!   ([`frac`]), polynomials in one variable with Sturm counts ([`univariate`]), the
//!   exact isotropic moments of a unit vector ([`moments`]), polynomial constraints as
//!   rewrite rules ([`rules`]);
//! - statements: the terms of index notation and their free letters ([`term`]), the
//!   context that gives them meaning ([`statement`]), and their evaluator ([`eval`],
//!   with [`differentiate`] for `grad`), written to be read rather than to be fast,
//!   and the orbits of free letters that no permutation changes ([`symmetry`]);
//! - facts: what a search hands in ([`fact`]), the checker that alone turns a fact into
//!   a [`check::Proof`] ([`check`]), the scalar facts ([`scalar`]) and signs by
//!   coefficients ([`sign`]); [`interrupt`] lets a claim's time limit stop a long
//!   computation, which then proves nothing.
//!
//! The kernel is a crate of its own (`cosserat-kernel`, re-exported by the checker as
//! `kernel`): it cannot import the search, and a bug outside can make a claim
//! `undecided`, never a proof. Its size and what it checks are stated in the guide
//! (`docs/src/trust.md`); unit tests here, cross-checks in `tests/`.

pub mod check;
pub mod differentiate;
pub mod eval;
pub mod fact;
pub mod frac;
pub mod interrupt;
pub mod moments;
pub mod poly;
pub mod rational;
pub mod rules;
pub mod scalar;
pub mod sign;
pub mod statement;
pub mod symmetry;
pub mod term;
pub mod univariate;

pub use moments::monomial_moment;
pub use poly::{Monomial, Poly, PolyError, Var, VarTable};
pub use rational::Rational;
