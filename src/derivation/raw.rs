//! The derivation-file format as TOML sees it: plain serde structs whose strings keep
//! their byte spans, so every later error can point into the file.

use serde::Deserialize;
use std::collections::BTreeMap;
use toml::Spanned;

/// A string value with its span in the file.
pub type S = Spanned<String>;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawFile {
    /// The work the claims come from; without it, "untitled derivations: FILE".
    pub paper: Option<S>,
    pub section: S,
    pub title: S,
    pub dimension: Spanned<i64>,
    pub normal: Option<S>,
    #[serde(default)]
    pub normal_in_plane: bool,
    /// Written by `draft`: the declarations are the draft's guesses (see
    /// [`super::model::Check::drafted`]).
    #[serde(default)]
    pub drafted: bool,
    /// Written by `draft`: the equations it could not read (`verify` lists them).
    #[serde(default)]
    pub to_complete: Vec<RawToComplete>,
    /// Written by `draft`: the declared symbols the paper's text may tie to others (a
    /// sentence, an equation left to complete, a labelled variant), each with where
    /// and why. Only a tie of these makes a drafted failure undecided.
    #[serde(default)]
    pub tied: Vec<RawTied>,
    #[serde(default)]
    pub assume: Vec<S>,
    #[serde(default)]
    pub tensors: Vec<S>,
    #[serde(default)]
    pub scalars: Vec<S>,
    /// Tensors that vary with the position: `u_i`, `theta`, `v_i(x_2)`.
    #[serde(default)]
    pub fields: Vec<S>,
    /// The name of the position vector, e.g. "x".
    pub position: Option<S>,
    /// The position orders of the matrix views: `voigt = ["11", "22", "12", "21"]`.
    #[serde(default)]
    pub orders: BTreeMap<String, Vec<S>>,
    #[serde(default)]
    pub define: Vec<S>,
    /// Printed symbols → the language (`'\sigma_{ij}^{(1)}' = "sig1_ij"`), for reading
    /// the printed statements.
    #[serde(default)]
    pub notation: BTreeMap<String, Spanned<NotationValue>>,
    /// Definitions that transcribe a claim's printed statement: `mut = { by = "eq21",
    /// corrected = "mut_ij = …" }`. A claim that reads one uses that claim; `corrected`
    /// is what the definition becomes when that claim is replaced by its correction.
    #[serde(default)]
    pub stated: BTreeMap<String, Spanned<RawStated>>,
    #[serde(default)]
    pub claim: Vec<RawClaim>,
    #[serde(default)]
    pub figure: Vec<RawFigure>,
}

/// An equation `draft` could not read: its claim id, its line in the source, why, and
/// the edit that would let it be read.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawToComplete {
    pub id: S,
    pub line: Spanned<i64>,
    pub reason: S,
    pub edit: Option<S>,
}

/// A symbol the paper may tie to others, as `draft` found it.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawTied {
    pub symbol: S,
    pub line: Option<Spanned<i64>>,
    pub why: S,
    /// `"trace"`: the reason speaks of a trace only (a deviator); `"divergence"`: of an
    /// incompressible body; `"law"`: an equation the paper may posit (see `TieKind`).
    pub tie: Option<S>,
}

/// `[[figure]]`: curves of scalar expressions against one parameter (`plot`).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawFigure {
    pub id: S,
    pub title: S,
    /// `"f_r = 0.05 .. 3 : 0.05"`: the parameter, its range and step.
    pub x: S,
    /// Axis labels as mathematics (`d_B/R_g`); the parameter's name and "value" without.
    pub x_label: Option<S>,
    pub y_label: Option<S>,
    /// Assumptions for every curve (`"u = 1"`), after the file's own.
    #[serde(default)]
    pub set: Vec<S>,
    /// The box on which square roots take their sign, as a claim's `given`.
    #[serde(default)]
    pub given: Vec<S>,
    pub curves: Vec<RawCurve>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawCurve {
    pub y: S,
    pub label: S,
    /// Assumptions for this curve alone (`"K = 2"`).
    #[serde(default)]
    pub set: Vec<S>,
}

/// `[stated]`: the claim a definition transcribes, and its corrected form.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawStated {
    pub by: S,
    pub corrected: Option<S>,
}

/// One reading of a printed symbol, or several (routes).
#[derive(Deserialize, Clone)]
#[serde(untagged)]
pub enum NotationValue {
    One(String),
    Many(Vec<String>),
}

impl NotationValue {
    pub fn values(&self) -> Vec<String> {
        match self {
            NotationValue::One(v) => vec![v.clone()],
            NotationValue::Many(v) => v.clone(),
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawClaim {
    pub id: S,
    pub section: Option<S>,
    pub printed: S,
    /// The claims this one is derived from (ids of any file checked with it).
    #[serde(default)]
    pub uses: Vec<S>,
    /// This claim's own notation entries, before the file's.
    #[serde(default)]
    pub notation: BTreeMap<String, Spanned<NotationValue>>,
    /// Printed symbols that the statement defines: a chain's first member that is one
    /// of them is a definition, not a checked equality.
    #[serde(default)]
    pub defines: Vec<S>,
    /// Why the sides intentionally read the printed statement differently.
    pub differs_from_printed: Option<S>,
    #[serde(default)]
    pub prose: bool,
    /// The verdict declared; without one the claim is reported as found.
    pub expect: Option<S>,
    pub reason: Option<S>,
    pub note: Option<S>,
    #[serde(default)]
    pub verbatim: bool,
    /// In a drafted file, the declared symbols this equation is the first to write: it
    /// may be what defines them, so a failure they could explain is undecided, as for
    /// the file's `tied`, in this claim only.
    #[serde(default)]
    pub introduces: Vec<S>,
    #[serde(default)]
    pub define: Vec<S>,
    #[serde(default)]
    pub assume: Vec<S>,
    pub sides: Option<Vec<S>>,
    pub chains: Option<Vec<Vec<S>>>,
    pub correction: Option<RawCorrection>,
    /// exact (default) | proportional | numeric | gradient | convex | not-circle |
    /// sign | monotone | limit | roots | stationary
    pub strategy: Option<S>,
    /// == (default) | <= | >=, between consecutive sides (numeric); > | >= | < | <=
    /// between the two sides (sign).
    pub relation: Option<S>,
    pub samples: Option<Spanned<i64>>,
    pub seed: Option<Spanned<i64>>,
    /// symbol → [low, high]
    #[serde(default)]
    pub ranges: BTreeMap<String, Vec<f64>>,
    #[serde(default)]
    pub given: Vec<S>,
    #[serde(default)]
    pub domain: Vec<S>,
    pub singular: Option<S>,
    pub function: Option<S>,
    /// symbol → closed-form gradient
    #[serde(default)]
    pub gradient: BTreeMap<String, S>,
    /// independent | symmetrised: what a gradient means for tied components.
    pub convention: Option<S>,
    #[serde(default)]
    pub wrt: Vec<S>,
    pub x: Option<S>,
    pub y: Option<S>,
    /// The parameter a monotone, limit, roots or stationary claim is about.
    #[serde(rename = "in")]
    pub variable: Option<S>,
    /// increasing | decreasing (strategy = "monotone").
    pub direction: Option<S>,
    /// Where the parameter goes: "0", "0+", "1-", "infinity", "-infinity" (strategy = "limit").
    pub tends_to: Option<S>,
    /// The limit: an expression, or "infinity", "+infinity", "-infinity".
    pub limit: Option<S>,
    /// Every real root in the domain, exactly (strategy = "roots").
    pub roots: Option<Vec<S>>,
    /// How many distinct real roots the domain holds, instead of `roots`.
    pub count: Option<Spanned<i64>>,
    /// The set on which a sign claim holds exactly: bounds on scalars, as `given`.
    pub exactly_when: Option<Spanned<Vec<S>>>,
    /// The point a stationary claim names: an expression in the other parameters.
    pub at: Option<S>,
    /// stationary | local-maximum | local-minimum (strategy = "stationary").
    pub kind: Option<S>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawCorrection {
    pub printed: S,
    /// This claim's own notation entries, before the file's.
    #[serde(default)]
    pub notation: BTreeMap<String, Spanned<NotationValue>>,
    /// Printed symbols that the statement defines: a chain's first member that is one
    /// of them is a definition, not a checked equality.
    #[serde(default)]
    pub defines: Vec<S>,
    /// Why the sides intentionally read the printed statement differently.
    pub differs_from_printed: Option<S>,
    pub reason: S,
    pub expect: S,
    #[serde(default)]
    pub verbatim: bool,
    #[serde(default)]
    pub define: Vec<S>,
    #[serde(default)]
    pub assume: Vec<S>,
    pub sides: Option<Vec<S>>,
    pub chains: Option<Vec<Vec<S>>>,
    /// The corrected function of a monotone, limit or roots claim.
    pub function: Option<S>,
}
