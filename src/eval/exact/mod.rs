//! The exact ring: every component a polynomial or a quotient of polynomials over ℚ in
//! the free components of the state ([`env`](mod@env)), the walk's operations on it ([`ring`]),
//! and `grad(…)` (nested once, for second derivatives) by forward-mode jets ([`jet`]
//! the values, [`jets`] the ring); derivatives of fields are total
//! derivatives over jet variables ([`env`](mod@env)).

pub mod differential;
pub mod env;
pub mod jet;
pub mod jets;
pub mod ring;
