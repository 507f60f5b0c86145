//! Evaluation: one tree walk ([`walk`]) over the expression language, generic over a
//! [`walk::Ring`], and the rings it runs on, each in its own module:
//!
//! - [`exact`]: polynomials and quotients over ℚ, for the exact routes (identities,
//!   scalar claims, the statement the kernel re-checks), with [`exact::jets`] for `grad`;
//! - [`real`]: `f64` and num-dual numbers for sampling, gradients and searches, with
//!   [`taylor`] expansions of fields and adaptive [`quadrature`] for averages;
//! - [`tape`]: a compiled form of the real walk for expressions evaluated at many states;
//! - [`interval`]: enclosures at a sampled state, to tell a real difference from rounding.
//!
//! [`assume`] solves a claim's assumptions once, with the exact ring, into the
//! [`crate::derivation::parametrisation`] every ring reads. Nothing here decides a verdict.

pub mod assume;
pub mod exact;
pub mod interval;
pub mod labeled;
pub mod quadrature;
pub mod real;
pub mod state;
pub mod tape;
pub mod taylor;
pub mod walk;
