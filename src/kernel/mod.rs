//! The trusted kernel: the few things every proof depends on.
//!
//! Exact rationals, canonical sparse polynomials with checked exponents, and the exact
//! isotropic moments of a unit vector. Everything else in the crate reaches a proved
//! verdict only through these types, so they are kept small and are tested hardest
//! (unit tests here, cross-checks in `tests/`).

pub mod check;
pub mod differentiate;
pub mod eval;
pub mod fact;
pub mod frac;
pub mod interrupt;
pub mod moments;
pub mod poly;
pub mod rational;
pub mod scalar;
pub mod sign;
pub mod statement;
pub mod term;
pub mod univariate;

pub use moments::monomial_moment;
pub use poly::{Monomial, Poly, PolyError, Var, VarTable};
pub use rational::Rational;
