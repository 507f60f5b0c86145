//! Evaluation of checked expressions over the reals, generic over the scalar: `f64`
//! for sampling, and num-dual numbers (`DualDVec64`, `Dual2DVec64`, …) for gradients
//! and Hessians. It shares the parser, the validator, the one walk of every route
//! (`walk.rs`) and the contraction (`algebra::einsum`) with the exact route, and
//! nothing of its arithmetic: floating point or dual numbers instead of polynomials,
//! quadrature instead of exact moments. Every proof is re-checked by the kernel's own
//! evaluator, which shares nothing with either route.
//!
//! `avg(…)` re-evaluates its argument at the nodes of a quadrature rule exact for its
//! degree in n (see [`super::quadrature::sphere_rule_exact_to`]), or, when the argument is
//! not a polynomial in n, by adaptive quadrature with an error estimate (see
//! [`super::quadrature`]); `maxn(…)` maximises over the normal's angle in the
//! plane by a dense grid refined by golden-section search (see [`MAXN_GRID`]).

mod elementary;
mod env;
mod error;
mod ring;
mod variation;

pub(crate) use elementary::{elementary, elementary2, golden_max};
pub use env::{
    component_pairs, ComponentPair, Labeled, RealEnv, MAXN_GRID, MAX_NESTED_DIFFERENCES,
};
pub use error::RealError;
pub(crate) use error::{maxn_not_differentiated, undefined};
