//! The integration tests: one crate, a module per concern, so that the library is linked
//! once. Slow sweeps run here too; `cargo test --release` runs them all.

mod common;
/// Test-only helpers shared with the library's unit tests: written against `crate::lang`,
/// which here is the library's.
mod support {
    pub mod float;
    pub mod mutate;
    pub mod pairings;
    pub mod products;
}
use cosserat_check::{derivation, lang};

mod adversarial;
mod appendix;
mod assumptions;
mod averages;
mod bad_inputs;
mod balance;
mod claims;
mod cli;
mod compact;
mod corpus;
mod counterexamples;
mod draft;
mod einsum;
mod explain;
mod fields;
mod gradients;
mod graph;
mod hostile;
mod html;
mod kernel;
mod latex;
mod layers;
mod literal_zero;
mod markdown_safety;
mod matrices;
mod moments;
mod mutants;
mod notation;
mod numeric;
mod rational;
mod readme;
mod recheck;
mod resource_limits;
mod reverify;
mod scalar;
mod states;
mod tape;
mod transcription;
mod unseen;
