//! The trusted kernel: the few things every verdict depends on.
//!
//! Exact rationals, canonical sparse polynomials, dense tensors generic over the
//! scalar with δ and ε, and the exact isotropic moments of a unit vector. Everything
//! else in the crate reaches a verdict only through these types, so they are kept
//! small and are tested hardest (unit tests here, cross-checks in `tests/`).

pub mod certificate;
pub mod einsum;
pub mod gcd;
pub mod indexed;
pub mod interrupt;
pub mod limit;
pub mod linear;
pub mod matrix;
pub mod modular;
pub mod moments;
pub mod poly;
pub mod quotient;
pub mod ratfunc;
pub mod rational;
pub mod residue;
pub mod sign;
pub mod sturm;
pub mod tensor;

pub use moments::{monomial_moment, tensor_moment};
pub use poly::{Monomial, Poly, PolyError, Var, VarTable};
pub use quotient::Quotient;
pub use ratfunc::RatFunc;
pub use rational::Rational;
pub use tensor::{assignments, permutation_sign, Tensor};
