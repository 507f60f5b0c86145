//! The exact ring: every component a polynomial or a quotient of polynomials over ℚ in
//! the free components of the state ([`env`](mod@env)), the walk's operations on it ([`ring`]),
//! and the derivatives of fields as jets ([`jets`]).

pub mod env;
pub mod jets;
pub mod ring;
