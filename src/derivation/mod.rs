//! Derivation files: the claims of the paper, one file per section, in TOML with
//! expressions in index notation. [`load`] reads and validates them into the
//! [`model`] types; [`notation`] reads the printed LaTeX of each claim through the
//! file's notation table, for the transcription check.

pub(crate) mod control;
pub mod draft;
pub mod edit;
mod fields;
pub mod load;
mod lowering;
pub mod model;
pub mod notation;
pub mod only;
pub mod parametrisation;
mod raw;
mod reads;
mod scalar;
mod spans;
mod spec;
pub mod statement;
pub mod uses;

pub use load::{load_dir, load_files, load_str, load_texts, parse_grid, LoadError};
pub use model::{
    Assumption, AssumptionKind, Check, Claim, Constraint, Correction, Curve, Definition,
    DerivationFile, Drafted, Expression, Extremum, Figure, GradientConvention, Grid, Hypothesis,
    LimitValue, ParamBox, Relation, Sampling, ScalarClaim, Side, Stated, Stationary, Strategy,
    TieKind, TiedSymbol, ToComplete, Transcript, Use, Verdict,
};
pub use reads::{reachable, Reads};
pub use scalar::{exact_part_checks, exact_parts, stationary_parts, Part};
pub use spec::DEFAULT_SAMPLES;
