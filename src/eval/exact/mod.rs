//! The exact ring: every component a polynomial or a quotient of polynomials over ℚ in
//! the free components of the state ([`env`](mod@env)), the walk's operations on it ([`ring`]),
//! and `grad(…)` by forward-mode jets ([`jets`]); derivatives of fields are total
//! derivatives over jet variables ([`env`](mod@env)).

pub mod env;
pub mod jets;
pub mod ring;
