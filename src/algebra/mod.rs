//! Untrusted algebra: the searches and fast computations that find proofs and
//! counterexamples. Gcds and their modular machinery, rational functions and quotients,
//! the canonicaliser of index expressions, root isolation and sign charts, limit
//! expansions, linear algebra, dense tensors and their contraction. A bug here may make
//! a claim `undecided`; it cannot make one wrong, because every proof is re-checked by
//! the kernel.

// The kernel under its name in the checker, so that paths read the same on both sides.
use cosserat_kernel as kernel;

pub mod certificate;
pub mod einsum;
pub mod gcd;
pub mod indexed;
pub mod limit;
pub mod linear;
pub mod matrix;
pub mod modular;
pub mod polynomial;
pub mod quotient;
pub mod ratfunc;
pub mod rational;
pub mod residue;
pub mod sign;
pub mod sturm;
pub mod tensor;
#[cfg(test)]
mod testing;

pub use quotient::Quotient;
pub use ratfunc::RatFunc;
pub use tensor::{assignments, permutation_sign, Tensor};
