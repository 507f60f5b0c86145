//! What a decision found beyond its verdict and its counterexample, as data: why a
//! claim is undecided, the witness of an existential claim, how a derivative was
//! compared. Strategies record a [`Finding`]; only `report` turns it into words
//! (`report::words`), and JSON carries it as it is. On request (`explain`), a decision
//! also keeps a [`Record`] of what it evaluated, so that the explanation shows the
//! decision's own expansions and states instead of recomputing them.

use crate::derivation::GradientConvention;
use crate::eval::exact::env::Refusal;
use crate::lang::Diagnostic;
use serde::Serialize;
use std::collections::BTreeMap;

/// A point as the reports show it: name → value.
pub type Point = BTreeMap<String, String>;

/// What a decision found.
/// A symbol of a drafted file: its name there, and the symbol the paper prints (the
/// key of the notation entry that names it, as written), when an entry names it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DraftedSymbol {
    pub name: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub printed: Option<String>,
    /// Where and why the paper may tie it (the file's `tied`), if it may.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tied: Option<String>,
}

#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Finding {
    /// The exact strategy compared no component, so nothing was proved.
    NothingCompared,
    /// The decision did not finish within the per-claim time limit (`--time-limit`).
    TimeLimit { seconds: f64 },
    /// The search found a proof or a counterexample, but the kernel's check of it
    /// refused it: a defect of the search, which decides nothing.
    KernelRefused { why: String },
    /// A test that decides the claim where it applies says nothing at some values of
    /// the parameters (a second derivative that vanishes): `why`.
    Inconclusive { why: String },
    /// The checker itself failed while deciding (a panic): a defect of the checker,
    /// not of the input, and never a verdict. `at` is where in the checker's source.
    InternalError { message: String, at: String },
    /// Expanding the statement exactly passes a resource limit (work, terms, the size
    /// of a power) at `at` (file:line:col).
    ResourceLimit {
        what: String,
        at: String,
        help: String,
    },
    /// An exact value the kernel could not certify, such as the sign of a square root
    /// on the claim's box, at `at` (file:line:col).
    Uncertified {
        what: String,
        at: String,
        help: String,
    },
    /// The sides are undefined on a set of positive measure: at a random state and at
    /// every state tried near it (`what` at `at`, file:line:col).
    Undefined {
        what: String,
        at: String,
        point: Point,
        /// The value exists but overflows `f64` (no gap in the domain).
        #[serde(skip_serializing_if = "std::ops::Not::not")]
        overflow: bool,
    },
    /// An identity modulo the squares of its roots, but no point tried makes every
    /// radicand positive at once: the sides may be defined nowhere, and the identity
    /// would hold only vacuously, so nothing is decided.
    NowhereDefined {
        radicands: Vec<String>,
        tries: usize,
    },
    /// The sides differ modulo the polynomial constraints and the squares of the roots
    /// taken as variables (the remainder `difference`), but no exact point where they
    /// hold and the sides differ was found in `tries` tries: there may be no real one,
    /// so nothing is decided.
    NoConstrainedPoint { difference: String, tries: usize },
    /// The sides differ (by `difference`), but no exact point where the identity's
    /// hypotheses hold (`hypotheses`, as written) and the sides differ was found: the
    /// hypotheses may hold nowhere, so nothing is decided.
    NoPointUnderHypotheses {
        difference: String,
        hypotheses: String,
    },
    /// A drafted reading (`drafted = true`) fails at equality `equality` of chain
    /// `chain` (both 1-based), but its sides read different symbols: those of `left`
    /// and `right` that the other side does not read. The draft took them as
    /// independent; the paper may tie them, so nothing is decided.
    OneSided {
        chain: usize,
        equality: usize,
        left: Vec<DraftedSymbol>,
        right: Vec<DraftedSymbol>,
    },
    /// A drafted reading fails at equality `equality` of chain `chain`, but a tie of a
    /// common kind between the draft's independent symbols (`tie`: a relation giving one
    /// component in the others, a symmetric tensor, a unit vector) removes the
    /// difference; the paper may state it in words, so nothing is decided.
    Tie {
        chain: usize,
        equality: usize,
        tie: String,
    },
    /// The sides differ as polynomials, but the counterexample was not confirmed by a
    /// second evaluation.
    Unconfirmed { difference: String, why: Rejection },
    /// An existential statement's exact witness: the state (other variables 0), the
    /// four points of the locus, and the nonzero determinant.
    Witness {
        state: Vec<(String, String)>,
        points: Vec<(String, String)>,
        determinant: String,
    },
    /// What a claim about a rational function of parameters decided
    /// (`decide::scalar`).
    RationalFunction(RationalEvidence),
    /// No witness among `attempts` rational states (not a counterexample).
    NoWitness { attempts: usize },
    /// The locus is a circle (the refutation of a not-circle claim): its centre and
    /// radius² as functions of the state.
    OnCircle {
        center: String,
        radius_squared: String,
    },
    /// A sampled state the checker could not judge.
    Unresolved { why: Unresolved, at: Point },
    /// The statement fails outside the declared domain; inside, a state could not be
    /// judged.
    UnresolvedInsideDomain {
        domain: String,
        why: Unresolved,
        at: Point,
    },
    /// The counterexample lies inside the declared domain.
    InsideDomain { domain: String },
    /// The statement also fails inside the declared domain.
    AlsoInsideDomain { domain: String },
    /// The statement holds on `samples` samples inside the domain.
    HoldsOnDomain { samples: usize, domain: String },
    /// A derivative through an average by adaptive quadrature is not checked.
    ThroughAdaptiveAverage,
    /// The statement differentiates fields, which only the exact strategy does: a
    /// sample is a point, not a field.
    DerivativesNotSampled,
    /// A closed-form gradient undefined at a sample where the derivative exists.
    ClosedFormUndefined { message: String },
    /// The closed form is undefined at a sample where the derivative does not exist.
    DerivativeDoesNotExist {
        message: String,
        component: String,
        num_dual: f64,
        central: f64,
    },
    /// num-dual and central differences disagree at a sample.
    DerivativeRoutesDisagree {
        component: String,
        num_dual: f64,
        central: f64,
        closed: f64,
        at: Point,
    },
    /// num-dual and central differences agree; the closed form does not.
    ClosedFormDisagrees,
    /// Every compared component agrees by the three routes.
    GradientAgrees {
        variables: Vec<String>,
        tied: Vec<String>,
        convention: Option<GradientConvention>,
    },
    /// The Hessian is not finite at a sample.
    HessianNotFinite { at: Point },
    /// num-dual's negative eigenvalue is not confirmed by the second difference.
    SecondDifferenceDisagrees {
        eigenvalue: f64,
        curvature: f64,
        at: Point,
    },
    /// A negative Hessian eigenvalue, confirmed by the second difference.
    NegativeEigenvalue { curvature: f64 },
    /// The Hessian is positive semidefinite at every sample.
    ConvexAgrees { variables: usize },
}

/// Why a sampled state could not be judged.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Unresolved {
    /// The averages' error estimate (relative) is above the largest usable one.
    QuadratureError {
        error: f64,
        limit: f64,
        /// The evaluation budget of an average that stopped short, if one did.
        budget: Option<usize>,
    },
    /// The sides of a chain differ by no more than a few times the error estimate.
    WithinError {
        chain: usize,
        residual: f64,
        clear: f64,
        error: f64,
    },
    /// A floating-point violation the second evaluation did not confirm.
    NotConfirmed(Rejection),
    /// No violation was confirmed, but at `random` of the `samples` random samples
    /// (more than one in a hundred) the floating-point values violate the relation while
    /// the sides' interval enclosures admit it (see `eval::interval`): floating
    /// point cannot tell there.
    WithinRounding { random: usize, samples: usize },
}

/// Why a second evaluation did not confirm a counterexample (`reverify`).
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Rejection {
    /// Exactly, the relation holds at the point: the violation was rounding.
    Rounding { lhs: String, rhs: String },
    /// At the exact point a hypothesis does not hold.
    HypothesisFails { hypothesis: String },
    /// The exact point lies on the singular set.
    OnSingularSet,
    /// A side or hypothesis has a pole at the exact point.
    Pole { what: String },
    /// The interpreter's values differ from the exact ones.
    InterpreterDisagrees {
        lhs: f64,
        rhs: f64,
        exact_lhs: String,
        exact_rhs: String,
    },
    /// The interpreter finds the relation satisfied.
    InterpreterSatisfied { lhs: f64, rhs: f64, residual: f64 },
    /// The interpreter cannot evaluate the sides there.
    CannotEvaluate { message: String },
    /// The sides' interval enclosures at the point admit the relation: the violation is
    /// within rounding.
    WithinRounding { lhs: (f64, f64), rhs: (f64, f64) },
}

/// What a decision evaluated, kept when asked (`check::decide_claim_recorded`).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Record {
    /// The exact strategy: every side's canonical expansion.
    pub expansions: Vec<Expansion>,
    /// The sampled strategies: the first states the decision drew, with the value of
    /// each side (or of the function) there.
    pub states: Vec<SampledState>,
}

/// One side of one chain, expanded.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Expansion {
    pub chain: usize,
    pub side: usize,
    pub text: String,
    /// Each component: the free indices' values (1-based) and the canonical
    /// polynomial, truncated; or why the side could not be expanded, as `explain`
    /// prints it.
    pub components: Result<Vec<Component>, Unexpanded>,
    /// Whether components were left out.
    pub more: bool,
}

/// Why a side was not expanded.
#[derive(Clone, Debug, PartialEq, Serialize, thiserror::Error)]
pub enum Unexpanded {
    #[error("ill-formed as printed: {0}")]
    IllFormed(String),
    #[error("(cannot expand: {0})")]
    Refused(String),
}

/// One component of an expanded side: the free indices' values (1-based) and the
/// canonical polynomial, truncated.
pub type Component = (Vec<(char, usize)>, String);

/// A state a sampled decision drew, and the value of each expression there (`None`:
/// not a scalar or not defined).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SampledState {
    pub point: Point,
    pub values: Vec<(String, Option<f64>)>,
}

/// The evidence of a sign, monotone, limit or roots claim.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RationalEvidence {
    /// The rational function decided, reduced: `left − right` (sign), the derivative
    /// (monotone), the function (limit, roots).
    pub decided: String,
    /// The parameter box.
    pub domain: String,
    /// The real points that matter: turning points, roots, poles (exact, or isolated
    /// with ten digits).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub points: Vec<String>,
    /// Where a claim that fails on the domain holds (verdict `conditional`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub holds_on: Option<String>,
    /// The limit found, for a limit claim.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub limit: Option<String>,
    /// Present when the verdict rests on seeded samples rather than a certificate.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sampled: Option<SampledSign>,
}

/// Seeded exact samples of a rational function of several parameters, with an
/// adversarial search for the smallest margin.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SampledSign {
    pub samples: usize,
    pub seed: u64,
    /// Samples where the expression is undefined (a divisor vanishes).
    pub excluded: usize,
    pub search_evaluations: usize,
    /// The value closest to breaking the claim (exact, at `at`).
    pub smallest_margin: String,
    pub at: Point,
}

impl Finding {
    /// What makes a claim undecided when its exact evaluation was refused, or `None`
    /// for malformed input.
    pub fn of_refusal(r: &Refusal) -> Option<Finding> {
        let parts = |d: &Diagnostic| {
            (
                d.message.clone(),
                d.location(),
                d.help.clone().unwrap_or_default(),
            )
        };
        match r {
            Refusal::Input(_) => None,
            Refusal::Limit(d) => {
                let (what, at, help) = parts(d);
                Some(Finding::ResourceLimit { what, at, help })
            }
            Refusal::Uncertified(d) => {
                let (what, at, help) = parts(d);
                Some(Finding::Uncertified { what, at, help })
            }
        }
    }
}
