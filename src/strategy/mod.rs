//! Strategies: how a claim is decided. Each returns an [`Outcome`] carrying the
//! evidence its verdict requires (component checks, counterexample).

pub mod appendix;
pub mod assume;
pub mod eval;
pub mod exact;
pub mod float;
pub mod numeric;
pub mod quadrature;
pub mod real;
pub mod sampler;
pub mod search;
pub mod tape;
pub mod witness;

use crate::derivation::{Claim, Verdict};
use crate::lang::Diagnostic;
use serde::Serialize;
use std::collections::BTreeMap;

/// How a verdict was reached.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Method {
    /// Canonical polynomial expansion for every value of the free indices.
    Exact,
    /// The printed statement is ill-formed in its indices.
    IndexCheck,
    /// Seeded random states in f64.
    Numeric,
    /// num-dual gradients against closed forms and central differences.
    Gradient,
    /// num-dual Hessians, positive semidefinite.
    Convex,
    /// An exact witness of an existential statement.
    Witness,
    /// Exact rational functions (Appendix A), with a floating-point second route.
    Symbolic,
}

/// How strong a verdict's evidence is: a proof by exact computation, or no violation
/// found by seeded sampling and a search for the worst case.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Strength {
    Proof,
    Sampled,
}

impl Method {
    /// The strength of a verdict reached by this method (a strategy that samples
    /// inside an otherwise exact method marks its outcome [`Outcome::sampled`]).
    pub fn strength(self) -> Strength {
        match self {
            Method::Exact | Method::IndexCheck | Method::Witness | Method::Symbolic => {
                Strength::Proof
            }
            Method::Numeric | Method::Gradient | Method::Convex => Strength::Sampled,
        }
    }

    pub fn as_str(self) -> &'static str {
        match self {
            Method::Exact => "exact",
            Method::IndexCheck => "index-check",
            Method::Numeric => "numeric",
            Method::Gradient => "gradient",
            Method::Convex => "convex",
            Method::Witness => "witness",
            Method::Symbolic => "symbolic",
        }
    }
}

/// Evidence that a statement is false.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Counterexample {
    /// Which chain (1-based) and which equality in it (1-based: sides k and k+1).
    pub chain: usize,
    pub equality: usize,
    pub lhs: String,
    pub rhs: String,
    /// Values (1-based) of the free indices where the sides differ.
    pub indices: BTreeMap<String, usize>,
    /// lhs − rhs in canonical form, reduced modulo n·n = 1 when the file declares a
    /// normal (see `reduced_on_sphere`).
    pub difference: String,
    pub reduced_on_sphere: bool,
    /// A rational point where the sides differ, and their values there.
    pub point: BTreeMap<String, String>,
    pub lhs_value: Option<String>,
    pub rhs_value: Option<String>,
    /// Set when the statement is ill-formed in its indices as printed.
    pub ill_formed: Option<String>,
}

/// The result of deciding one statement.
#[derive(Clone, Debug, PartialEq)]
pub struct Outcome {
    pub verdict: Verdict,
    pub method: Method,
    pub strength: Strength,
    /// Number of component comparisons made.
    pub checks: usize,
    /// Whether some comparison needed n·n = 1.
    pub used_unit_normal: bool,
    pub counterexample: Option<Counterexample>,
    /// Sample count, seed and residuals of the numeric strategies.
    pub numeric: Option<NumericEvidence>,
    /// A strategy-specific line of evidence (the domain of a conditional claim, the
    /// witness of an existential one, …).
    pub detail: Option<String>,
}

impl Outcome {
    /// A verdict with its method and number of checks; the evidence is added with the
    /// `with_*` methods.
    pub fn new(verdict: Verdict, method: Method, checks: usize) -> Self {
        Outcome {
            verdict,
            method,
            strength: method.strength(),
            checks,
            used_unit_normal: false,
            counterexample: None,
            numeric: None,
            detail: None,
        }
    }

    /// Marks an outcome whose decision rests on sampled floating-point evidence.
    pub fn sampled(mut self) -> Self {
        self.strength = Strength::Sampled;
        self
    }

    /// The verdict as the tables show it: `holds` and `conditional` say `(sampled)`
    /// when they rest on sampled evidence; a `fails` always carries its
    /// counterexample.
    pub fn verdict_text(&self) -> String {
        match (self.verdict, self.strength) {
            (Verdict::Holds | Verdict::Conditional, Strength::Sampled) => {
                format!("{} (sampled)", self.verdict)
            }
            _ => self.verdict.to_string(),
        }
    }

    pub fn with_counterexample(mut self, cx: Counterexample) -> Self {
        self.counterexample = Some(cx);
        self
    }

    pub fn with_numeric(mut self, evidence: NumericEvidence) -> Self {
        self.numeric = Some(evidence);
        self
    }

    pub fn with_detail(mut self, detail: impl Into<String>) -> Self {
        self.detail = Some(detail.into());
        self
    }

    pub fn using_unit_normal(mut self, used: bool) -> Self {
        self.used_unit_normal = used;
        self
    }
}

/// The evidence a numeric verdict must carry.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NumericEvidence {
    pub samples: usize,
    pub seed: u64,
    /// Largest relative residual (equalities) or relative violation (inequalities,
    /// ≤ 0 when satisfied) over the samples; for convexity, the smallest relative
    /// eigenvalue.
    pub largest_residual: f64,
    /// What `largest_residual` measures, in words.
    pub residual: &'static str,
    /// Samples excluded because they lie on the singular set.
    pub excluded: usize,
    pub exclusion: Option<String>,
    /// The domain on which a conditional statement holds.
    pub domain: Option<String>,
    pub tolerance: String,
    /// The adversarial search that followed the random samples.
    pub search: Option<SearchEvidence>,
}

/// What the search for the worst violation did (`strategy::search`).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SearchEvidence {
    pub starts: usize,
    pub evaluations: usize,
    /// The largest margin found, in the units of `largest_residual` (≤ tolerance:
    /// not violated).
    pub worst_margin: f64,
    /// Where it was found.
    pub at: BTreeMap<String, String>,
}

/// A decided claim: the claim's own outcome and its correction's.
#[derive(Clone, Debug)]
pub struct Decided<'c> {
    pub claim: &'c Claim,
    pub outcome: Outcome,
    pub correction: Option<Outcome>,
}

impl Decided<'_> {
    /// Whether every verdict equals its declared expectation.
    pub fn as_expected(&self) -> bool {
        self.outcome.verdict == self.claim.expect
            && match (&self.claim.correction, &self.correction) {
                (Some(c), Some(o)) => o.verdict == c.expect,
                _ => true,
            }
    }
}

/// Decides one check with its strategy.
pub fn decide(
    decls: &crate::lang::Decls,
    check: &crate::derivation::Check,
) -> Result<Outcome, Diagnostic> {
    use crate::derivation::Strategy;
    match &check.strategy {
        Strategy::Exact => exact::decide(decls, check),
        Strategy::Numeric { .. } => numeric::decide_numeric(decls, check),
        Strategy::Gradient { .. } => numeric::decide_gradient(decls, check),
        Strategy::Convex { .. } => numeric::decide_convex(decls, check),
        Strategy::NotCircle { .. } => witness::decide_not_circle(decls, check),
        Strategy::Appendix { step, origin } => appendix::decide(*step, origin, decls, check),
    }
}

/// Decides a claim and its correction.
pub fn decide_claim(claim: &Claim) -> Result<Decided<'_>, Diagnostic> {
    let outcome = decide(&claim.decls, &claim.check)?;
    let correction = match &claim.correction {
        Some(c) => Some(decide(&claim.decls, &c.check)?),
        None => None,
    };
    Ok(Decided {
        claim,
        outcome,
        correction,
    })
}
