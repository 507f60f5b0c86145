//! The checked, in-memory form of derivation files: claims whose expressions have
//! already passed name resolution and index validation.

use super::notation::{Reading, Unread};
use crate::algebra::limit::Approach;
use crate::algebra::sign::{Interval, Sign};
use crate::lang::{Decls, DefSig, LangError, Node, Origin};
use serde::Serialize;
use std::fmt;
use std::sync::Arc;

/// A verdict, as in the guide's table.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Verdict {
    /// Proved (method `exact`) or verified on seeded samples (method `numeric`).
    Holds,
    /// A counterexample exists.
    Fails,
    /// Holds on a stated domain and fails outside it.
    Conditional,
    /// The checker could not decide; the outcome says why (never a guess).
    Undecided,
}

impl Verdict {
    pub fn parse(s: &str) -> Option<Self> {
        match s {
            "holds" => Some(Verdict::Holds),
            "fails" => Some(Verdict::Fails),
            "conditional" => Some(Verdict::Conditional),
            "undecided" => Some(Verdict::Undecided),
            _ => None,
        }
    }

    pub fn as_str(self) -> &'static str {
        match self {
            Verdict::Holds => "holds",
            Verdict::Fails => "fails",
            Verdict::Conditional => "conditional",
            Verdict::Undecided => "undecided",
        }
    }
}

impl fmt::Display for Verdict {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// A named definition such as `t_i = sigma_ki n_k`.
///
/// Every check carries the definitions in its scope, so a definition is shared rather
/// than copied: cloning one is a reference count (the fields are read through
/// [`Deref`](std::ops::Deref)).
#[derive(Clone, Debug)]
pub struct Definition(Arc<DefinitionData>);

/// What a [`Definition`] holds.
#[derive(Debug)]
pub struct DefinitionData {
    pub sig: DefSig,
    pub body: Node,
    pub origin: Origin,
    /// The definition as written.
    pub text: String,
    /// How deeply its body nests, the bodies of the definitions it reads included.
    pub depth: usize,
}

/// The deepest nesting of a definition (its body within the bodies of those it reads,
/// one level per operation): every evaluator recurses that deep, so a chain of
/// thousands of definitions would overflow a stack. The paper's deepest is about 30.
pub const MAX_NESTING: usize = 10_000;

impl Definition {
    /// A definition whose body may read the `visible` ones (the last of a name).
    pub fn new(
        sig: DefSig,
        body: Node,
        origin: Origin,
        text: String,
        visible: &[Definition],
    ) -> Self {
        let depth = nesting(&body, visible);
        Definition(Arc::new(DefinitionData {
            sig,
            body,
            origin,
            text,
            depth,
        }))
    }
}

/// How deeply `node` nests, counting the bodies of the `visible` definitions it reads.
pub fn nesting(node: &Node, visible: &[Definition]) -> usize {
    let read = node
        .definition()
        .and_then(|name| visible.iter().rev().find(|d| d.sig.name == name))
        .map_or(0, |d| d.depth);
    let inner = node
        .children()
        .into_iter()
        .map(|c| nesting(c, visible))
        .max()
        .unwrap_or(0);
    1 + read.max(inner)
}

impl std::ops::Deref for Definition {
    type Target = DefinitionData;
    fn deref(&self) -> &DefinitionData {
        &self.0
    }
}

/// An assumption of a claim or a file, as written, with what it says.
///
/// Component-level assumptions are affine equations on components and are solved
/// together, once, whatever their order (`eval::assume`); a substitution whose
/// right side is not affine replaces the whole symbol.
#[derive(Clone, Debug)]
pub struct Assumption {
    pub kind: AssumptionKind,
    /// The assumption as written.
    pub text: String,
    pub origin: Origin,
    /// The symbols its right side reads, directly or through the definitions it reads
    /// (an assumption may read definitions: `sigma_12 = tau_y` with `tau_y = c + mu p`
    /// reads `c`, `mu` and `p`).
    pub reads: std::collections::BTreeSet<String>,
}

impl Assumption {
    /// Every symbol the assumption mentions: the one it is about and those in its
    /// right side.
    pub fn symbols(&self) -> Vec<String> {
        let mut out: Vec<String> = self.kind.symbol().map(str::to_owned).into_iter().collect();
        out.extend(self.reads.iter().cloned());
        out
    }

    /// A diagnostic that points at the whole assumption.
    pub fn diagnostic(&self, message: impl Into<String>) -> crate::lang::Diagnostic {
        self.origin
            .diagnostic(crate::lang::Span::new(0, self.text.len()), message)
    }
}

/// What an assumption says.
#[derive(Clone, Debug)]
pub enum AssumptionKind {
    /// The rank-2 symbol's trace vanishes.
    Traceless { symbol: String },
    /// `X_ji = X_ij` for a rank-2 symbol.
    Symmetric { symbol: String },
    /// `X_ji = −X_ij` (and `X_ii = 0`) for a rank-2 symbol.
    Antisymmetric { symbol: String },
    /// One component of a symbol equals a scalar expression, e.g. `sigma_13 = 0` for
    /// plane problems.
    Component {
        symbol: String,
        /// 0-based component indices.
        index: Vec<usize>,
        body: Node,
    },
    /// `X_ij… = expression` for every value of the indices: an affine relation between
    /// components (`C_ijkl = C_klij`, `f_g = f_r`) or, when the right side is not
    /// affine, a substitution of the whole symbol (`S = 3 V / (2 R_g)`).
    Equals {
        symbol: String,
        formal: Vec<char>,
        body: Node,
    },
    /// `left = right` between expressions, for every value of their free indices: a
    /// relation that is no single symbol's value (`s_kk = 0`, `s_ij s_ij = 2 tau^2`,
    /// `N_ij N_ij = 1`). Affine ones join the linear system; a polynomial one is solved
    /// for a variable that occurs in it only as a power of its own (`eval::assume`).
    Constraint { left: Node, right: Node },
    /// `left = right` at every point, where a side reads a derivative of a field
    /// (`phi_,kk = 0`: harmonic; `u_k,k = 0`: solenoidal): a linear differential
    /// hypothesis, so every derivative of it holds too. Solved for its highest
    /// derivative (`kernel::eval` says which), exact claims only.
    Differential { left: Node, right: Node },
}

impl AssumptionKind {
    /// The symbol the assumption is about (its left side); `None` for a constraint
    /// between expressions or a differential hypothesis.
    pub fn symbol(&self) -> Option<&str> {
        match self {
            AssumptionKind::Traceless { symbol }
            | AssumptionKind::Symmetric { symbol }
            | AssumptionKind::Antisymmetric { symbol }
            | AssumptionKind::Component { symbol, .. }
            | AssumptionKind::Equals { symbol, .. } => Some(symbol),
            AssumptionKind::Constraint { .. } | AssumptionKind::Differential { .. } => None,
        }
    }

    /// The expressions the assumption reads: a right side, or both sides of a
    /// constraint.
    pub fn bodies(&self) -> Vec<&Node> {
        match self {
            AssumptionKind::Component { body, .. } | AssumptionKind::Equals { body, .. } => {
                vec![body]
            }
            AssumptionKind::Constraint { left, right }
            | AssumptionKind::Differential { left, right } => vec![left, right],
            _ => Vec::new(),
        }
    }
}

/// One side of an equation chain.
#[derive(Clone, Debug)]
pub struct Side {
    /// The side as written in the derivation file.
    pub text: String,
    pub origin: Origin,
    /// The checked expression; an index error is kept (not raised) only for a
    /// printed statement transcribed verbatim, where it is a finding about the paper.
    pub node: Result<Node, LangError>,
    /// For a chain of matrices, decided entry by entry: the entry (row, column,
    /// 0-based) this side reads off the matrix side as written.
    pub entry: Option<(usize, usize)>,
}

impl Side {
    /// The side as an expression to evaluate, or its index error.
    pub fn expression(&self) -> Result<Expression, &LangError> {
        let node = self.node.as_ref()?;
        Ok(Expression {
            text: self.text.clone(),
            origin: self.origin.clone(),
            node: node.clone(),
        })
    }
}

/// Everything needed to decide one statement: definitions, assumptions and one or
/// more chains `a = b = c` whose consecutive members must be equal.
#[derive(Clone, Debug)]
pub struct Check {
    pub defs: Vec<Definition>,
    pub assumptions: Vec<Assumption>,
    pub chains: Vec<Vec<Side>>,
    /// The sides transcribe a printed statement index for index, so ill-formed
    /// indices are a verdict rather than an input error.
    pub verbatim: bool,
    /// The file was written by `draft` (`drafted = true`): its declarations are guesses,
    /// so a symbol it takes as independent may be tied to others by the paper, in its
    /// text or in an equation the draft could not read. A failure then counts only when
    /// both sides of the failing equality read the same symbols (`decide::drafted`).
    pub drafted: Option<Drafted>,
    /// How the statement is decided.
    pub strategy: Strategy,
}

/// What a drafted file says of its symbols, for the failures of its claims.
#[derive(Clone, Debug)]
pub struct Drafted {
    /// The claim's notation table, then the file's: it names symbols as printed.
    pub notation: std::sync::Arc<super::notation::Notation>,
    /// The symbols the paper's text may tie to others (`tied`), each with where and
    /// why: only a tie of one of them makes a failure undecided.
    pub tied: std::sync::Arc<std::collections::BTreeMap<String, TiedSymbol>>,
}

/// Why a drafted file's text may tie a symbol, and to what.
#[derive(Clone, Debug)]
pub struct TiedSymbol {
    /// Where and why, in words.
    pub why: String,
    /// The ties the reason allows.
    pub kind: TieKind,
}

/// The ties a drafted file's reason allows, from the narrowest: a later kind allows
/// every tie of an earlier one, and prevails when a symbol has two reasons.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum TieKind {
    /// `tie = "trace"` (a deviator, an equation of the text that sets a trace): a zero
    /// trace of a tensor, or a zero divergence of a vector field, explains a difference
    /// linear in it. A wrong coefficient of a trace squared stays an error: the words
    /// may speak of a part of the tensor (`s` deviatoric, `σ` not).
    Trace,
    /// `tie = "divergence"` (the text says the body is incompressible, or its motion
    /// isochoric): a vector field's divergence is zero outright, and explains a
    /// difference that vanishes with it at any power (`(u_k,k)²`); a tensor's trace is
    /// as for [`TieKind::Trace`].
    Divergence,
    /// `tie = "law"` (an equation that may be a law the paper posits, such as
    /// equilibrium `\sigma_{ij,j} + b_i = 0`): explains sides that read different
    /// symbols (Navier's equations, on the solutions of the law) and nothing else: no
    /// relation between components, no zero trace (a wrong coefficient of a derivative
    /// stays an error).
    Law,
    /// No `tie`: any tie (a relation, a symmetry, a unit length, a zero trace).
    Any,
}

impl Check {
    /// Whether the check is constrained beyond its symbols' assumptions: a polynomial
    /// constraint, a differential hypothesis, or (for the exact strategy) a hypothesis
    /// on derived quantities. Neither symbolic indices nor the kernel's plain identity
    /// decide such a check.
    pub fn constrained(&self) -> bool {
        self.assumptions.iter().any(|a| {
            matches!(
                a.kind,
                AssumptionKind::Constraint { .. } | AssumptionKind::Differential { .. }
            )
        }) || matches!(&self.strategy, Strategy::Exact { hypotheses, .. } if !hypotheses.is_empty())
    }

    /// Where the statement is written (file:line:col of its first side).
    pub fn location(&self) -> String {
        self.chains
            .iter()
            .flatten()
            .next()
            .map_or_else(String::new, |s| {
                s.origin.diagnostic(Default::default(), "").location()
            })
    }
}

/// The relation between consecutive sides of a chain.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Relation {
    Eq,
    Le,
    Ge,
}

impl Relation {
    pub fn parse(s: &str) -> Option<Self> {
        match s {
            "==" | "=" => Some(Relation::Eq),
            "<=" => Some(Relation::Le),
            ">=" => Some(Relation::Ge),
            _ => None,
        }
    }

    pub fn symbol(self) -> &'static str {
        match self {
            Relation::Eq => "=",
            Relation::Le => "≤",
            Relation::Ge => "≥",
        }
    }

    /// Whether `l rel r` holds, in any ordered numbers: exact rationals, or the ends of
    /// two enclosures (see `eval::interval`).
    pub fn holds<T: PartialOrd>(self, l: &T, r: &T) -> bool {
        match self {
            Relation::Eq => l == r,
            Relation::Le => l <= r,
            Relation::Ge => l >= r,
        }
    }

    /// How far `l rel r` is from holding (≤ 0 where an inequality holds; for `=`, the
    /// size of the difference).
    pub fn violation(self, l: f64, r: f64) -> f64 {
        match self {
            Relation::Eq => (l - r).abs(),
            Relation::Le => l - r,
            Relation::Ge => r - l,
        }
    }
}

/// A checked scalar expression with its text, e.g. a function to differentiate.
#[derive(Clone, Debug)]
pub struct Expression {
    pub text: String,
    pub origin: Origin,
    pub node: Node,
}

/// An inequality or equation between two scalars: `f_r <= f_s`, `p <= 0`.
#[derive(Clone, Debug)]
pub struct Constraint {
    pub text: String,
    pub lhs: Expression,
    pub relation: Relation,
    pub rhs: Expression,
}

/// The meaning of a gradient with respect to a tensor whose components the assumptions
/// tie together (σ_12 = σ_21, a zero trace, …).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum GradientConvention {
    /// `convention = "independent"`: F as a function of the free components only;
    /// ∂F/∂σ_12 is the derivative along σ_12 and everything tied to it (for a symmetric
    /// σ: ∂F/∂σ_12 + ∂F/∂σ_21 as independent variables). Tied components are not compared.
    Independent,
    /// `convention = "symmetrised"`: the gradient within the constrained set, i.e. the
    /// orthogonal (Frobenius) projection of ∂F/∂σ onto it; for a symmetric σ,
    /// ½ (∂F/∂σ_ij + ∂F/∂σ_ji), for a traceless one the deviatoric part. Every
    /// component is compared.
    Symmetrised,
}

impl GradientConvention {
    pub fn parse(s: &str) -> Option<Self> {
        match s {
            "independent" => Some(GradientConvention::Independent),
            "symmetrised" | "symmetrized" => Some(GradientConvention::Symmetrised),
            _ => None,
        }
    }

    /// The convention in words, for the evidence.
    pub fn describe(self) -> &'static str {
        match self {
            GradientConvention::Independent => {
                "independent components: a free component's derivative moves every component tied to it; tied components are not compared"
            }
            GradientConvention::Symmetrised => {
                "symmetrised: the gradient projected onto the constrained set (for a symmetric tensor ½(∂F/∂σ_ij + ∂F/∂σ_ji))"
            }
        }
    }
}

/// How random states are drawn for the numeric strategies.
#[derive(Clone, Debug)]
pub struct Sampling {
    /// Number of accepted samples.
    pub samples: usize,
    pub seed: u64,
    /// Range of every component of a symbol; symbols not listed use [−1, 1], which
    /// includes compression and tension.
    pub ranges: std::collections::BTreeMap<String, (f64, f64)>,
    /// Hypotheses: samples that violate one are redrawn.
    pub given: Vec<Constraint>,
    /// Where the statement is not defined (e.g. the apex of a cone): samples with this
    /// scalar below 1e-8 in magnitude are excluded and counted.
    pub singular: Option<Expression>,
}

impl Strategy {
    /// The parameter box of an exact or proportional claim (`given`).
    pub fn exact_domain(&self) -> Option<&ParamBox> {
        match self {
            Strategy::Exact { domain, .. } | Strategy::Proportional { domain } => Some(domain),
            _ => None,
        }
    }

    /// Every expression of the strategy itself (functions, closed forms, constraints,
    /// singular sets), for dependency analysis.
    pub fn expressions(&self) -> Vec<&Expression> {
        let mut out = Vec::new();
        match self {
            Strategy::Exact { .. } | Strategy::Proportional { .. } => {}
            Strategy::Numeric {
                sampling, domain, ..
            } => {
                out.extend(sampling.given.iter().flat_map(|c| [&c.lhs, &c.rhs]));
                out.extend(sampling.singular.iter());
                out.extend(domain.iter().flat_map(|c| [&c.lhs, &c.rhs]));
            }
            Strategy::Gradient {
                sampling,
                function,
                closed_forms,
                ..
            } => {
                out.extend(sampling.given.iter().flat_map(|c| [&c.lhs, &c.rhs]));
                out.extend(sampling.singular.iter());
                out.push(function);
                out.extend(closed_forms.iter().map(|(_, e)| e));
            }
            Strategy::Convex {
                sampling, function, ..
            } => {
                out.extend(sampling.given.iter().flat_map(|c| [&c.lhs, &c.rhs]));
                out.extend(sampling.singular.iter());
                out.push(function);
            }
            Strategy::NotCircle { x, y } => {
                out.push(x);
                out.push(y);
            }
            Strategy::Scalar { claim, .. } => match &**claim {
                ScalarClaim::Sign(_) | ScalarClaim::SignExactly(..) => {}
                ScalarClaim::Monotone { function, .. } => out.push(function),
                ScalarClaim::Limit {
                    function, value, ..
                } => {
                    out.push(function);
                    if let LimitValue::Finite(v) = value {
                        out.push(v);
                    }
                }
                ScalarClaim::Roots {
                    function, roots, ..
                } => {
                    out.push(function);
                    out.extend(roots);
                }
                ScalarClaim::Stationary(s) => out.extend([&s.function, &s.at]),
            },
        }
        out
    }
}

/// A hypothesis of an exact identity on a derived quantity (`given = ["J2 > 0"]`,
/// `["a > b"]`): the identity is claimed where `left − right` has the sign.
#[derive(Clone, Debug)]
pub struct Hypothesis {
    pub text: String,
    pub origin: Origin,
    pub left: Node,
    pub right: Node,
    pub sign: crate::kernel::statement::Sign,
}

/// The decision procedure of a claim.
#[derive(Clone, Debug)]
pub enum Strategy {
    /// Canonical polynomial expansion (the default). `domain` (`given`) bounds the
    /// parameters: square roots take their sign on it, and a counterexample lies in it;
    /// `hypotheses` (the other entries of `given`, on derived quantities) must hold at
    /// a counterexample too.
    Exact {
        domain: ParamBox,
        hypotheses: Vec<Hypothesis>,
    },
    /// Canonical expansion of `left = λ · right` for one nonzero λ (a constant, or a
    /// rational function of the parameters), the same in every component: two sides
    /// that agree up to a sign or scale convention, or a modulus.
    Proportional { domain: ParamBox },
    /// Seeded random states in f64; `domain`, when given, is where a statement that
    /// fails is claimed to hold (verdict `conditional`).
    Numeric {
        sampling: Sampling,
        relation: Relation,
        domain: Vec<Constraint>,
    },
    /// num-dual gradient of `function` against closed forms and central differences.
    Gradient {
        sampling: Sampling,
        function: Expression,
        /// (symbol, closed-form ∂F/∂symbol with the symbol's free indices).
        closed_forms: Vec<(String, Expression)>,
        /// What ∂F/∂σ means when the assumptions tie components of σ together
        /// (`convention = …`); required then, and stated in the evidence.
        convention: Option<GradientConvention>,
    },
    /// num-dual Hessian of `function` in the components of `wrt` is positive
    /// semidefinite at every sample.
    Convex {
        sampling: Sampling,
        function: Expression,
        wrt: Vec<String>,
    },
    /// The locus of (x, y) over the orientations of the normal is not a circle: an
    /// exact witness state with four points on no common circle or line.
    NotCircle { x: Expression, y: Expression },
    /// A claim about a scalar rational function of the parameters (its sign, its
    /// monotonicity in one of them, a limit, its real roots) on a box of parameter
    /// values, decided by `decide::scalar`: exactly (Sturm sequences, coefficient
    /// signs, lowest orders) where the kernel can, by exact evaluation at seeded
    /// sample points otherwise.
    Scalar {
        claim: Box<ScalarClaim>,
        domain: ParamBox,
        /// Sample count and seed of the sampled route (several parameters, no
        /// certificate).
        samples: usize,
        seed: u64,
    },
}

/// What a scalar claim states (see [`Strategy::Scalar`]).
// Held boxed by `Strategy::Scalar`, so the variants' sizes cost nothing elsewhere.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug)]
pub enum ScalarClaim {
    /// `left − right` has this sign (`strategy = "sign"`; the claim's one pair of sides
    /// and its `relation`).
    Sign(Sign),
    /// `left − right` has this sign exactly where the parameters lie in the box
    /// (`exactly_when`), within the domain: the sign there, and the opposite relation
    /// (its negation) everywhere else, wherever both sides are defined. Decided part by
    /// part (see [`crate::derivation::exact_parts`]).
    SignExactly(Sign, ParamBox),
    /// `function` increases (or decreases) in `variable`: its derivative is ≥ 0 (≤ 0)
    /// wherever defined, and it has no pole in the domain (`strategy = "monotone"`).
    Monotone {
        function: Expression,
        variable: String,
        increasing: bool,
    },
    /// `function` tends to `value` as `variable` tends to `to` (`strategy = "limit"`).
    Limit {
        function: Expression,
        variable: String,
        to: Approach,
        value: LimitValue,
    },
    /// The real roots of `function` in `variable` on the domain are exactly `roots`, or
    /// with `count` (and no roots listed) exactly that many distinct reals, rational or
    /// not (`strategy = "roots"`).
    Roots {
        function: Expression,
        variable: String,
        roots: Vec<Expression>,
        count: Option<usize>,
    },
    /// `variable = at` (an expression in the other parameters) is a stationary point of
    /// `function` for every value of them in the domain: the derivative vanishes there;
    /// for a local maximum (minimum) by the second-derivative test, the second
    /// derivative there is < 0 (> 0) and the point lies inside the interval `given` for
    /// `variable` (`strategy = "stationary"`). Decided part by part
    /// ([`crate::derivation::stationary_parts`]).
    Stationary(Box<Stationary>),
}

/// What a stationary claim says of its point.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Extremum {
    Stationary,
    LocalMaximum,
    LocalMinimum,
}

/// A stationary claim (see [`ScalarClaim::Stationary`]), with what its parts read.
#[derive(Clone, Debug)]
pub struct Stationary {
    pub function: Expression,
    pub variable: String,
    pub at: Expression,
    pub kind: Extremum,
    /// `grad(function, variable)` and its own derivative in `variable`.
    pub first: Expression,
    pub second: Expression,
    /// `variable = at`: every part is decided under it.
    pub point: Assumption,
    /// The ends of the interval `given` for `variable`: lower or upper, closed or
    /// open, and the end as a constant expression.
    pub ends: Vec<(bool, bool, Expression)>,
}

impl ScalarClaim {
    /// The function and the variable the claim is about (none for a sign claim, whose
    /// function is the difference of its sides).
    pub fn function(&self) -> Option<(&Expression, &str)> {
        match self {
            ScalarClaim::Sign(_) | ScalarClaim::SignExactly(..) => None,
            ScalarClaim::Monotone {
                function, variable, ..
            }
            | ScalarClaim::Limit {
                function, variable, ..
            }
            | ScalarClaim::Roots {
                function, variable, ..
            } => Some((function, variable)),
            ScalarClaim::Stationary(s) => Some((&s.function, &s.variable)),
        }
    }
}

/// The value a limit claim states.
#[derive(Clone, Debug)]
pub enum LimitValue {
    Finite(Expression),
    /// `+infinity` or `-infinity`.
    Signed(bool),
    /// `infinity`: |f| → ∞, whatever the sign.
    Unsigned,
}

/// A box of parameter values: an interval per bounded parameter (`given = ["f_r > 0",
/// "0 < nu < 1/2"]`); parameters not listed range over the real line.
#[derive(Clone, Debug, Default)]
pub struct ParamBox {
    pub bounds: Vec<(String, Interval)>,
}

impl ParamBox {
    pub fn interval(&self, symbol: &str) -> Interval {
        self.bounds
            .iter()
            .find(|(s, _)| s == symbol)
            .map_or_else(Interval::real_line, |(_, i)| i.clone())
    }

    /// `0 < f_r, 0 < nu < 1/2`, or "every real value".
    pub fn describe(&self) -> String {
        if self.bounds.is_empty() {
            return "every real value of the parameters".to_owned();
        }
        let parts: Vec<String> = self.bounds.iter().map(|(s, i)| i.describe(s)).collect();
        parts.join(", ")
    }
}

/// A corrected statement that the paper evidently intended.
#[derive(Clone, Debug)]
pub struct Correction {
    pub statement: String,
    pub reason: String,
    pub expect: Verdict,
    pub check: Check,
    pub transcript: Transcript,
}

/// What the transcription check compares: the printed statement as read through the
/// notation table, and the claim's chains as written.
#[derive(Clone, Debug)]
pub struct Transcript {
    /// The printed statement in the language, or where and why it could not be read
    /// (a prose claim is not read).
    pub reading: Result<Reading, Unread>,
    /// The chains as written in the file, before matrix chains are split into entries.
    pub written: Vec<Vec<String>>,
    /// Why the sides intentionally read the printed statement differently
    /// (`differs_from_printed`).
    pub declared: Option<String>,
    /// The claim's hypotheses as written (`given`, `domain`), which a printed condition
    /// ("for G > 0") must be one of.
    pub conditions: Vec<String>,
    /// The claim has no `sides`: its chains are the reading itself.
    pub from_reading: bool,
    /// The statement is a sentence of prose, which is not read.
    pub prose: bool,
    /// The claim's notation table, then the file's: read backwards, it names a
    /// counterexample's variables as the paper prints them.
    pub notation: std::sync::Arc<super::notation::Notation>,
}

/// A claim this one is derived from (`uses`), as written.
#[derive(Clone, Debug)]
pub struct Use {
    pub id: String,
    pub origin: Origin,
}

/// A definition that transcribes (part of) a claim's printed statement (`[stated]`):
/// a claim whose check reads it uses that claim, and `corrected` is what it becomes
/// when that claim is replaced by its correction.
#[derive(Clone, Debug)]
pub struct Stated {
    /// The definition's name.
    pub name: String,
    /// The claim whose statement it transcribes.
    pub by: String,
    /// Where `by` is written.
    pub origin: Origin,
    pub corrected: Option<Definition>,
}

/// One checkable statement of a derivation file.
#[derive(Clone, Debug)]
pub struct Claim {
    /// The work the claim comes from.
    pub paper: String,
    pub id: String,
    /// Where the id is written.
    pub origin: Origin,
    pub section: String,
    /// The statement as printed (LaTeX, verbatim, typos included).
    pub statement: String,
    /// The statement is a sentence of the paper's prose rather than a formula.
    pub prose: bool,
    /// The verdict the file declares; `holds` when it declares none.
    pub expect: Verdict,
    /// Whether the file declares `expect`: a claim without it is reported as found
    /// (its verdict is never "unexpected"), unless the run is `--strict`.
    pub declared: bool,
    /// Why the expected verdict is not `holds` (required then).
    pub reason: Option<String>,
    /// Conventions, readings and second routes behind the verdict.
    pub note: Option<String>,
    /// The file's declarations (dimension, normal, symbols).
    pub decls: Arc<Decls>,
    pub check: Check,
    pub transcript: Transcript,
    pub correction: Option<Correction>,
    /// The claims this one is derived from.
    pub uses: Vec<Use>,
    /// The file's definitions attributed to the claims that state them.
    pub stated: Arc<Vec<Stated>>,
}

/// A whole derivation file, checked.
#[derive(Clone, Debug)]
pub struct DerivationFile {
    /// The work the claims are credited to (`paper = …`, or "untitled derivations:
    /// FILE").
    pub paper: String,
    pub path: String,
    pub section: String,
    pub title: String,
    pub claims: Vec<Claim>,
    /// The definitions attributed to the claims that state them (`[stated]`).
    pub stated: Arc<Vec<Stated>>,
    /// The `[[figure]]` tables, for `plot`.
    pub figures: Vec<Figure>,
    /// The equations `draft` could not read (`to_complete`), which `verify` lists.
    pub to_complete: Vec<ToComplete>,
}

/// An equation `draft` could not read, kept in its file as a commented claim.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ToComplete {
    pub id: String,
    /// Its line in the paper's source.
    pub line: usize,
    /// Why the draft could not read it.
    pub reason: String,
    /// The one edit that would let it be read, where the reason names one.
    pub edit: Option<String>,
}

/// A figure of a derivation file: curves of scalar expressions against one parameter.
#[derive(Clone, Debug)]
pub struct Figure {
    pub id: String,
    pub title: String,
    pub x: Grid,
    pub x_label: String,
    pub y_label: String,
    pub curves: Vec<Curve>,
}

/// The parameter of a figure and its values: `from + k·step` up to `to`, exactly.
#[derive(Clone, Debug)]
pub struct Grid {
    pub name: String,
    pub values: Vec<crate::kernel::Rational>,
}

/// One curve: its expression, read as the side of a claim with the figure's and the
/// curve's assumptions and the figure's box.
#[derive(Clone, Debug)]
pub struct Curve {
    pub label: String,
    pub text: String,
    pub decls: Arc<Decls>,
    pub check: Check,
}
