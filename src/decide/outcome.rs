//! What deciding a statement produces: the verdict, its strength, and the evidence.
//!
//! The verdict and strength of an [`Outcome`] are private to this module, which no
//! strategy is inside of: the only way to strength `proof` (`holds`, `fails` or
//! `conditional`) is a kernel [`Proof`], which only the kernel's checker makes
//! ([`crate::kernel::check`]), and whose conclusion gives the verdict.
//!
//! ```compile_fail
//! use cosserat_check::decide::Outcome;
//! use cosserat_check::derivation::Verdict;
//! // A verdict cannot be set by hand.
//! let mut o = Outcome::holds_sampled(cosserat_check::decide::Method::Numeric, 1);
//! o.verdict = Verdict::Holds;
//! ```

use super::finding::{Finding, Record};
use crate::derivation::Verdict;
use crate::kernel::check::{Conclusion, Proof};
use serde::Serialize;
use std::collections::BTreeMap;
use std::sync::Arc;

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
    /// A claim about a rational function of parameters: Sturm sign charts, coefficient
    /// signs, lowest orders, or exact seeded samples.
    RationalFunction,
    /// An exact witness of an existential statement.
    Witness,
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
    pub fn as_str(self) -> &'static str {
        match self {
            Method::Exact => "exact",
            Method::IndexCheck => "index-check",
            Method::Numeric => "numeric",
            Method::Gradient => "gradient",
            Method::Convex => "convex",
            Method::Witness => "witness",
            Method::RationalFunction => "rational-function",
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
    /// The difference is reduced by the polynomial constraints too (`assume`).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub reduced_by_constraints: bool,
    /// A rational point where the sides differ, and their values there.
    pub point: BTreeMap<String, String>,
    pub lhs_value: Option<String>,
    pub rhs_value: Option<String>,
    /// Numbers that belong to the counterexample but are not coordinates of its point
    /// (a central difference, the negative eigenvalue of a Hessian).
    pub aux: BTreeMap<String, String>,
    /// Set when the statement is ill-formed in its indices as printed.
    pub ill_formed: Option<String>,
    /// How the counterexample was confirmed by a second evaluation (`reverify`).
    pub reverified: Option<Reverified>,
    /// For a proportionality: where the factor was fixed (the comparison that fails
    /// is then `left = factor · right`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub factor: Option<Box<FactorWitness>>,
}

/// Where a proportionality's factor was fixed: left/right at one component and point.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct FactorWitness {
    pub factor: String,
    /// The claim has parameters, so the factor may be a function of them (fixed here at
    /// the parameter values of the difference's point).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub of_parameters: bool,
    pub indices: BTreeMap<String, usize>,
    pub point: BTreeMap<String, String>,
    pub lhs_value: String,
    pub rhs_value: String,
}

/// The second evaluation that confirmed a counterexample.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Reverified {
    /// Exact rational arithmetic at the rational point the sample denotes.
    Exact,
    /// The `f64` interpreter on the expression tree agrees with the exact values.
    FloatingPoint,
    /// The `f64` interpreter, with each field an explicit Taylor polynomial and every
    /// derivative a central difference, agrees with the exact values.
    TaylorDifferences,
    /// The `f64` interpreter (not the compiled tape) confirms the violation.
    Interpreter,
    /// The interpreter confirms it, and interval enclosures of the sides exclude the
    /// relation: the violation is not rounding.
    Intervals,
    /// Central differences of the function agree with the num-dual derivative.
    CentralDifferences,
    /// The second derivative along the eigenvector, by central differences of the
    /// function, is negative too.
    SecondDifferences,
}

/// The result of deciding one statement.
///
/// Its verdict and strength are private: strength `proof` is made only from kernel
/// proofs ([`Outcome::proved`], [`Outcome::conditional`]); the sampled verdicts have
/// their own constructors.
#[derive(Clone, Debug, PartialEq)]
pub struct Outcome {
    verdict: Verdict,
    strength: Strength,
    /// The kernel's proofs behind a verdict of strength `proof`: one, or for a
    /// conditional its domain's and its counterexample's.
    proofs: Vec<Arc<Proof>>,
    pub method: Method,
    /// Number of component comparisons made.
    pub checks: usize,
    /// Whether some comparison needed n·n = 1.
    pub used_unit_normal: bool,
    pub counterexample: Option<Counterexample>,
    /// Sample count, seed and residuals of the numeric strategies.
    pub numeric: Option<NumericEvidence>,
    /// What the decision found beyond the verdict (why it is undecided, a witness, how
    /// a derivative was compared), as data.
    pub finding: Option<Finding>,
    /// What the decision evaluated, when it was asked to keep it.
    pub record: Option<Record>,
}

impl Outcome {
    fn new(verdict: Verdict, strength: Strength, method: Method, checks: usize) -> Self {
        Outcome {
            verdict,
            strength,
            proofs: Vec::new(),
            method,
            checks,
            used_unit_normal: false,
            counterexample: None,
            numeric: None,
            finding: None,
            record: None,
        }
    }

    /// The verdict a kernel proof concludes (`holds` or `fails`), strength `proof`.
    pub fn proved(method: Method, checks: usize, proof: Proof) -> Self {
        let verdict = match proof.conclusion() {
            Conclusion::Holds => Verdict::Holds,
            Conclusion::Fails => Verdict::Fails,
        };
        let mut o = Outcome::new(verdict, Strength::Proof, method, checks);
        o.proofs = vec![Arc::new(proof)];
        o
    }

    /// `holds`, strength `proof`, from kernel proofs of the parts a statement is
    /// decided in (a sign on a set and its negation on each box of the rest); `None`
    /// unless there is one and every one concludes `holds`.
    pub fn proved_parts(method: Method, checks: usize, proofs: Vec<Arc<Proof>>) -> Option<Self> {
        if proofs.is_empty() || proofs.iter().any(|p| p.conclusion() != Conclusion::Holds) {
            return None;
        }
        let mut o = Outcome::new(Verdict::Holds, Strength::Proof, method, checks);
        o.proofs = proofs;
        Some(o)
    }

    /// `fails` on sampled evidence: a counterexample found and confirmed in floating
    /// point.
    pub fn fails_sampled(method: Method, checks: usize) -> Self {
        Outcome::new(Verdict::Fails, Strength::Sampled, method, checks)
    }

    /// `holds` on sampled evidence: no violation among the samples and the search.
    pub fn holds_sampled(method: Method, checks: usize) -> Self {
        Outcome::new(Verdict::Holds, Strength::Sampled, method, checks)
    }

    /// `conditional`: proved on its domain when a certificate covers the domain,
    /// otherwise sampled there.
    /// `conditional`: proved when the kernel proved both parts, that it holds on its
    /// domain and fails outside it (`proofs`: the two, concluding `holds` and `fails`
    /// in that order); otherwise sampled.
    pub fn conditional(
        method: Method,
        checks: usize,
        proofs: Option<(Arc<Proof>, Arc<Proof>)>,
    ) -> Self {
        let proofs = proofs.filter(|(holds, fails)| {
            holds.conclusion() == Conclusion::Holds && fails.conclusion() == Conclusion::Fails
        });
        let strength = if proofs.is_some() {
            Strength::Proof
        } else {
            Strength::Sampled
        };
        let mut o = Outcome::new(Verdict::Conditional, strength, method, checks);
        o.proofs = proofs.map(|(h, f)| vec![h, f]).unwrap_or_default();
        o
    }

    /// `undecided`: the reason goes in the evidence.
    pub fn undecided(method: Method, checks: usize) -> Self {
        Outcome::new(Verdict::Undecided, Strength::Sampled, method, checks)
    }

    pub fn verdict(&self) -> Verdict {
        self.verdict
    }

    pub fn strength(&self) -> Strength {
        self.strength
    }

    /// The kernel's proofs behind a verdict of strength `proof`.
    pub fn proofs(&self) -> &[Arc<Proof>] {
        &self.proofs
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

    pub fn with_finding(mut self, finding: Finding) -> Self {
        self.finding = Some(finding);
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
    /// The extreme of `residual` over the samples: the largest, or for convexity the
    /// smallest.
    pub largest_residual: f64,
    /// What `largest_residual` measures.
    pub residual: Measure,
    /// Samples excluded because they lie on the singular set.
    pub excluded: usize,
    pub exclusion: Option<String>,
    /// States (random or of the search) where a side was undefined only on a set of
    /// measure zero (a zero of a divisor), stepped off.
    #[serde(skip_serializing_if = "is_zero")]
    pub undefined: usize,
    /// States where the sides differ in floating point, but their interval enclosures
    /// admit the relation: the difference is within rounding (cancellation), no
    /// violation.
    #[serde(skip_serializing_if = "is_zero")]
    pub rounding: usize,
    /// The domain on which a conditional statement holds.
    pub domain: Option<String>,
    pub tolerance: String,
    /// The adversarial search that followed the random samples.
    pub search: Option<SearchEvidence>,
}

/// What a sampled decision measured at every sample (`report::words::measure` says it
/// in words).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Measure {
    /// Equalities: |l − r| / (1 + |l| + |r|); the largest is reported.
    RelativeDifference,
    /// Inequalities: (l − r) / (1 + |l| + |r|) for `<=` ((r − l) / … for `>=`); negative
    /// where the inequality holds, its magnitude the relative margin to spare.
    RelativeViolation,
    /// Gradients: the relative difference between num-dual and the closed form.
    DifferenceFromClosedForm,
    /// Convexity: the smallest Hessian eigenvalue divided by 1 + max |λ|; the smallest
    /// is reported.
    RelativeEigenvalue,
}

/// What the search for the worst violation did (`decide::search`).
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

fn is_zero(n: &usize) -> bool {
    *n == 0
}
