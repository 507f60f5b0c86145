//! Checking a derivation: `dispatch` sends each claim to its decision under a time
//! limit and with panic isolation ([`isolate`]); [`transcription`] compares the printed
//! LaTeX with the claim's sides; [`inherit`] re-decides a failure with the claims it
//! uses taken as given, to tell a root error from an inherited one; [`probe`] evaluates
//! one expression in a file's context (plots and cross-checks).

pub(crate) mod claim;
pub mod decided;
pub(crate) mod dispatch;
pub mod inherit;
pub mod isolate;
pub mod probe;
pub mod transcription;

pub use claim::{decide_claim, decide_claim_recorded};
pub use decided::{Attribution, Decided};
pub use dispatch::{decide, proof_statements, ProofStatements};
