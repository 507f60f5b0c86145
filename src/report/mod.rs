//! Reports: the derivation table (compact, Markdown, JSON, HTML, CSV, LaTeX), errata,
//! the graph, `explain` and plots. Rendering only; every verdict
//! has been decided before anything here runs.

pub mod compact;
pub mod csv;
pub mod errata;
pub mod evidence;
pub mod explain;
pub mod graph;
pub mod html;
pub mod json;
pub mod latex;
pub mod layout;
pub mod markdown;
pub mod mathml;
pub mod plot;
pub mod row;
pub mod scripts;
pub mod summary;
pub mod tex;
pub mod transcription;
pub mod typeset;
pub mod words;

pub use evidence::{evidence, proof_words};
pub use row::{full_evidence, is_erratum, prose_is_formula, read_label, verdict_label};
pub use summary::{paper_of, refs, Summary};
