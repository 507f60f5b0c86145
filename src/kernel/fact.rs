//! What a strategy hands the kernel and what the kernel answers: a [`Fact`] (a claim
//! about a statement, with the hints the search found), the items of a proof's
//! evidence ([`Checked`]), and why a fact was refused ([`Rejection`]). The checker
//! itself is [`super::check`]; the scalar facts are checked in [`super::scalar`].

use super::eval::{Env, EvalError};
use super::frac::Frac;
use super::poly::Var;
use super::rational::Rational;
use super::statement::{FracData, PolyData};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// One component of one equality of a chain, at a state.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Evaluation {
    /// 0-based chain and equality (between sides `equality` and `equality + 1`).
    pub chain: usize,
    pub equality: usize,
    /// The values (0-based) of the sides' free letters, in sorted letter order.
    pub at: Vec<usize>,
    /// Every variable the sides read, by name, with its value.
    pub point: Vec<(String, Rational)>,
}

/// A rational function in lowest terms, numerator and denominator by names.
pub type Reduced = (PolyData, PolyData);

/// The factor of a proportionality: a nonzero constant, or a rational function of the
/// claim's parameters (the declared scalars that are not fields), nonzero as a
/// function; the proportionality then holds where it is defined and nonzero, and the
/// proof says so.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Factor {
    Constant(Rational),
    Function { num: PolyData, den: PolyData },
}

/// The components an identity's compared components stand for, and the blocks of
/// free letters (`"ijklmpqrst"`) no permutation of which changes a side.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct OrbitsCompared {
    pub of: usize,
    pub blocks: Vec<String>,
}

/// What a strategy found, to be checked against the statement.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Fact {
    /// Every equality holds for every value of the free indices, wherever its
    /// divisors are nonzero (modulo n·n = 1 when a normal is declared).
    Identity { roots: Vec<FracData> },
    /// Each equality's left side is the factor (nonzero) times the right: one factor,
    /// written as a list of one, the same in every equality and component.
    Proportional {
        factors: Vec<Factor>,
        roots: Vec<FracData>,
    },
    /// The sides of one equality differ at a state that satisfies the assumptions,
    /// lies in the box and, for the normal, on the unit sphere.
    Refutation {
        at: Evaluation,
        roots: Vec<FracData>,
    },
    /// The sides of one component differ as functions (`at.point` is empty): their
    /// cleared difference is a nonzero polynomial modulo n·n = 1, and so are the
    /// divisors. Such a polynomial vanishes on no open piece of the unit sphere times
    /// the box, when every interval of the box has interior and bounds a free
    /// variable. For sides whose values at a point are too large to compute.
    Differs {
        at: Evaluation,
        roots: Vec<FracData>,
    },
    /// No nonzero factor relates one equality's sides: at `first` exactly one side is
    /// zero, or `first` and `second` give different ratios.
    NotProportional {
        first: Evaluation,
        second: Option<Evaluation>,
        roots: Vec<FracData>,
    },
    /// A side of a chain is ill-formed in its indices.
    IllFormed { chain: usize, side: usize },
    /// A sign claim's `left − right` (or a monotonicity's derivative, with its
    /// denominator of one strict sign) has the sign on the box, by coefficients.
    SignByCoefficients {
        /// The function (and a monotonicity's function itself) in lowest terms, as
        /// the search reduced it: accepted when its denominator divides the kernel's
        /// and the numerators agree.
        reduced: Option<Reduced>,
        function: Option<Reduced>,
        roots: Vec<FracData>,
    },
    /// The same for a function of one variable, with cuts between its roots.
    SignOnInterval {
        variable: String,
        cuts: Vec<Rational>,
        reduced: Option<Reduced>,
        function: Option<Reduced>,
        roots: Vec<FracData>,
    },
    /// A sign claim broken at a point of the box.
    SignAt {
        point: Vec<(String, Rational)>,
        roots: Vec<FracData>,
    },
    /// A strict sign broken at a zero of `left − right` in (lo, hi) of one variable.
    ZeroBetween {
        variable: String,
        lo: Rational,
        hi: Rational,
        roots: Vec<FracData>,
    },
    /// A monotonicity broken between two values of the variable (the other
    /// parameters at `point`).
    TwoPoints {
        a: Rational,
        b: Rational,
        point: Vec<(String, Rational)>,
        roots: Vec<FracData>,
    },
    /// A monotonicity of a function constant in the variable.
    Constant { roots: Vec<FracData> },
    /// A monotonicity broken by a pole in (lo, hi).
    Pole {
        lo: Rational,
        hi: Rational,
        roots: Vec<FracData>,
    },
    /// A limit, read off the lowest orders by the kernel; a refutation names a point
    /// where the limit found and the one stated differ.
    Limit {
        point: Option<Vec<(String, Rational)>>,
        roots: Vec<FracData>,
    },
    /// The zeros of a function of one variable, counted by the kernel.
    Roots { roots: Vec<FracData> },
    /// The zeros of a function of parameters are the roots stated, rational functions
    /// of them, each of this multiplicity in the numerator.
    RootsOfParameters {
        multiplicities: Vec<u32>,
        roots: Vec<FracData>,
    },
    /// Its refutation: at `point` (every parameter but the variable) the zeros are not
    /// the roots stated there.
    RootsAt {
        point: Vec<(String, Rational)>,
        roots: Vec<FracData>,
    },
    /// The not-a-circle witness: a state and four parameters u of rational normals.
    NotConcyclic {
        point: Vec<(String, Rational)>,
        us: Vec<Rational>,
        roots: Vec<FracData>,
    },
    /// Its refutation: the coefficients D, E, F (rational functions of the state) of the
    /// circle x² + y² + D x + E y + F = 0 on which the whole locus lies.
    OnCircle {
        circle: [Reduced; 3],
        roots: Vec<FracData>,
    },
}

impl Fact {
    /// The square roots a fact offers.
    pub(super) fn roots(&self) -> &[FracData] {
        match self {
            Fact::IllFormed { .. } => &[],
            Fact::Identity { roots }
            | Fact::Proportional { roots, .. }
            | Fact::Refutation { roots, .. }
            | Fact::Differs { roots, .. }
            | Fact::NotProportional { roots, .. }
            | Fact::SignByCoefficients { roots, .. }
            | Fact::SignOnInterval { roots, .. }
            | Fact::SignAt { roots, .. }
            | Fact::ZeroBetween { roots, .. }
            | Fact::TwoPoints { roots, .. }
            | Fact::Constant { roots }
            | Fact::Pole { roots, .. }
            | Fact::Limit { roots, .. }
            | Fact::Roots { roots }
            | Fact::RootsOfParameters { roots, .. }
            | Fact::RootsAt { roots, .. }
            | Fact::NotConcyclic { roots, .. }
            | Fact::OnCircle { roots, .. } => roots,
        }
    }
}

/// What a proof establishes about its statement.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Conclusion {
    Holds,
    Fails,
}

/// What the kernel verified, item by item: the evidence a proof states.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Checked {
    /// Both sides identical, component by component, `modulo_unit_normal` of them
    /// only after reduction by n·n = 1; where each polynomial of `nonzero` is nonzero.
    PolynomialIdentity {
        components: usize,
        modulo_unit_normal: usize,
        #[serde(skip_serializing_if = "Vec::is_empty")]
        nonzero: Vec<String>,
        /// Where an equality was compared at one component per orbit
        /// ([`super::symmetry`]): how many components those compared stand for.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        orbits: Option<OrbitsCompared>,
    },
    /// The polynomial constraints, each solved for a power of a variable of its own,
    /// and the square roots taken as variables (`rules`, as `v^d = value`), and how many
    /// components were identical only after the reduction by them: the sides agree
    /// wherever the constraints hold, on every branch of the roots.
    Constraints { rules: Vec<String>, reduced: usize },
    /// The left side is `factor` (nonzero) times the right, where each polynomial of
    /// `nonzero` (the factor's numerator and denominator) is nonzero.
    Proportional {
        factor: String,
        #[serde(skip_serializing_if = "Vec::is_empty")]
        nonzero: Vec<String>,
    },
    /// √radicand = root: its square exactly, its sign on the box `on` by coefficients
    /// after `substitution` (empty: a nonnegative constant).
    SquareRoot {
        radicand: String,
        root: String,
        on: String,
        substitution: String,
        cases: usize,
    },
    /// The sides differ as functions of the free variables: their difference, with
    /// denominators cleared and reduced by n·n = 1, has `terms` terms.
    DifferentFunctions { terms: usize },
    /// The sides take these exact values at the state of a refutation.
    Values { left: String, right: String },
    /// A side is ill-formed in its indices.
    IllFormed { why: String },
    /// A rational function of several variables has its sign on the box: after every
    /// variable is moved onto t ≥ 0, numerator and denominator have coefficients of
    /// one sign (`cases`: one per sign of each unbounded variable).
    CoefficientSigns { substitution: String, cases: usize },
    /// A function of one variable has the sign on the interval wherever defined:
    /// its roots counted between cuts (Sturm), the sign exact on each piece.
    SignOnInterval {
        interval: String,
        relation: String,
        pieces: usize,
        /// Poles inside the interval, where the function is undefined.
        poles: usize,
    },
    /// A zero (or a pole) of a function of one variable lies in (lo, hi).
    ZeroBetween {
        variable: String,
        lo: String,
        hi: String,
    },
    /// The function does not change with the variable.
    Constant,
    /// A limit read off the lowest orders, where each of `nonzero` is nonzero.
    Limit {
        variable: String,
        to: String,
        value: String,
        #[serde(skip_serializing_if = "Vec::is_empty")]
        nonzero: Vec<String>,
    },
    /// The zeros of a function of one variable on an interval (Sturm counts), against
    /// the roots stated.
    Roots {
        interval: String,
        roots: Vec<String>,
        zeros: usize,
        /// The number of zeros stated, for a claim that counts them.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        count: Option<usize>,
        /// Whether the zeros are exactly the roots stated (or as many as `count`).
        exactly: bool,
    },
    /// The roots of a function of parameters, each of its multiplicity in the
    /// numerator, and how many polynomials were certified nonzero on the box (the
    /// numerator's quotient by the roots, the roots' divisors, the function's divisors
    /// at the roots).
    RootsOfParameters {
        variable: String,
        roots: Vec<String>,
        multiplicities: Vec<u32>,
        nonzero: usize,
    },
    /// The zeros at a point of the parameters, not the roots stated there.
    RootsAt {
        point: Vec<String>,
        roots: Vec<String>,
        zeros: usize,
    },
    /// Four points on no common circle or line.
    NotConcyclic { determinant: String },
    /// The locus lies on one circle of nonzero radius at every state off a thin set,
    /// and covers it (a polynomial in the normal of constant distance from the centre).
    OnCircle {
        center: String,
        radius_squared: String,
    },
}

/// Everything a proof verified.
pub type Summary = Vec<Checked>;

/// Why the kernel did not accept a fact.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum Rejection {
    #[error("the kernel could not evaluate the statement: {0}")]
    Eval(#[from] EvalError),
    #[error("the fact does not hold: {0}")]
    False(String),
    #[error("the fact does not fit the statement: {0}")]
    Mismatch(String),
}

pub(super) type R<T> = Result<T, Rejection>;

impl Env<'_> {
    /// A point by variable names, checked: it satisfies the solved assumptions (every
    /// eliminated component equals its value in the free ones), lies in the box, and
    /// puts the normal on the unit sphere.
    pub fn point(&mut self, named: &[(String, Rational)]) -> R<BTreeMap<Var, Rational>> {
        let mut point = BTreeMap::new();
        for (name, value) in named {
            if point
                .insert(self.vars.intern(name), value.clone())
                .is_some()
            {
                return Err(Rejection::Mismatch(format!("`{name}` is given twice")));
            }
        }
        let at = |v: Var| point.get(&v).cloned();
        let zero = |v: Var| point.get(&v).cloned().unwrap_or_else(|| Rational::int(0));
        if !self.rules.iter().all(|r| r.holds_at(&zero)) {
            return Err(Rejection::False(
                "the point does not satisfy the polynomial constraints".into(),
            ));
        }
        for (v, value) in self.eliminated() {
            if let Some(x) = point.get(&v) {
                let should = Frac::from(value).eval(&at);
                if should.as_ref() != Some(x) {
                    return Err(Rejection::False(
                        "the point does not satisfy the assumptions".into(),
                    ));
                }
            }
        }
        // Every interval of the box holds at the point: a variable the point names, or
        // an eliminated one by its value there; one the sides do not read still needs
        // an interval with a point in it (else there is no state at all).
        let eliminated = self.eliminated();
        for (v, i) in self.given_box() {
            let value = match (point.get(&v), eliminated.iter().find(|(w, _)| *w == v)) {
                (Some(x), _) => Some(x.clone()),
                (None, Some((_, p))) => Some(Frac::from(p.clone()).eval(&at).ok_or_else(|| {
                    Rejection::False("the point leaves out a variable of the box".into())
                })?),
                (None, None) => None,
            };
            let inside = match &value {
                Some(x) => i.contains(x),
                None => !i.is_empty(),
            };
            if !inside {
                return Err(Rejection::False("the point lies outside the box".into()));
            }
        }
        let normal = self.normal_vars().to_vec();
        if !normal.is_empty() && normal.iter().any(|v| point.contains_key(v)) {
            let mut norm = Rational::int(0);
            for v in &normal {
                let x = point.get(v).cloned().unwrap_or_else(|| Rational::int(0));
                norm += &(&x * &x);
            }
            if !norm.is_one() {
                return Err(Rejection::False(
                    "the normal is not a unit vector at the point".into(),
                ));
            }
        }
        Ok(point)
    }
}
