//! Evaluation of checked expressions over the reals, generic over the scalar: `f64`
//! for sampling, and num-dual numbers (`DualDVec64`, `Dual2DVec64`, …) for gradients
//! and Hessians. It shares only the parser and validator with the exact route, and
//! has its own contraction code: a shared bug would make both routes agree on a wrong
//! answer.
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

pub(crate) use elementary::golden_max;
pub(crate) use elementary::{elementary, elementary2};
pub use env::{
    component_pairs, ComponentPair, Labeled, RealEnv, MAXN_GRID, MAX_NESTED_DIFFERENCES,
};
pub(crate) use error::undefined;
pub use error::RealError;
