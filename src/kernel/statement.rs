//! What a claim says, as the kernel reads it: the context that gives its symbols
//! meaning (dimension, normal, declarations, definitions, assumptions, the box of
//! parameter values) and the claim itself (equal sides, a sign, a monotonicity, a
//! limit, roots, a witness). A report records it whole, so that `recheck` can check
//! a proof from the statement alone.

use super::rational::Rational;
use super::term::Term;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// One end of an interval.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum End {
    Unbounded,
    Open(Rational),
    Closed(Rational),
}

impl End {
    pub fn value(&self) -> Option<&Rational> {
        match self {
            End::Unbounded => None,
            End::Open(x) | End::Closed(x) => Some(x),
        }
    }
}

/// An interval of the real line, open, closed or half-open, possibly unbounded.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Interval {
    pub lo: End,
    pub hi: End,
}

impl Interval {
    /// Whether the interval holds an open interval (a nonzero polynomial cannot vanish
    /// on all of it).
    pub fn has_interior(&self) -> bool {
        match (self.lo.value(), self.hi.value()) {
            (Some(a), Some(b)) => a < b,
            _ => true,
        }
    }

    pub fn real_line() -> Self {
        Interval {
            lo: End::Unbounded,
            hi: End::Unbounded,
        }
    }

    /// Whether the interval has no point (`lo > hi`, or `lo = hi` with an open end).
    pub fn is_empty(&self) -> bool {
        match (&self.lo, &self.hi) {
            (End::Closed(a), End::Closed(b)) => a > b,
            (a, b) => match (a.value(), b.value()) {
                (Some(a), Some(b)) => a >= b,
                _ => false,
            },
        }
    }

    pub fn contains(&self, x: &Rational) -> bool {
        let above = match &self.lo {
            End::Unbounded => true,
            End::Open(a) => x > a,
            End::Closed(a) => x >= a,
        };
        let below = match &self.hi {
            End::Unbounded => true,
            End::Open(b) => x < b,
            End::Closed(b) => x <= b,
        };
        above && below
    }

    /// The interval as constraints on `name`: `0 < f_r`, `1 ≤ x ≤ 2`, `x real`.
    pub fn describe(&self, name: &str) -> String {
        let lo = match &self.lo {
            End::Unbounded => String::new(),
            End::Open(a) => format!("{a} < "),
            End::Closed(a) => format!("{a} ≤ "),
        };
        let hi = match &self.hi {
            End::Unbounded => String::new(),
            End::Open(b) => format!(" < {b}"),
            End::Closed(b) => format!(" ≤ {b}"),
        };
        if lo.is_empty() && hi.is_empty() {
            format!("{name} real")
        } else {
            format!("{lo}{name}{hi}")
        }
    }
}

/// What a sign claim says of `f`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Sign {
    Positive,
    NonNegative,
    Negative,
    NonPositive,
}

impl Sign {
    /// Whether a value of sign `s` (−1, 0, 1) satisfies the claim.
    pub fn admits(self, s: i32) -> bool {
        match self {
            Sign::Positive => s > 0,
            Sign::NonNegative => s >= 0,
            Sign::Negative => s < 0,
            Sign::NonPositive => s <= 0,
        }
    }

    /// `> 0`, `≥ 0`, `< 0` or `≤ 0`.
    pub fn relation(self) -> &'static str {
        match self {
            Sign::Positive => "> 0",
            Sign::NonNegative => "≥ 0",
            Sign::Negative => "< 0",
            Sign::NonPositive => "≤ 0",
        }
    }
}

/// A definition: `name_formal = body`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Definition {
    pub name: String,
    pub formal: Vec<char>,
    pub body: Term,
}

/// An assumption that relates components linearly: solved as one system.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Equation {
    Symmetric(String),
    Antisymmetric(String),
    Traceless(String),
    /// `symbol_index = value` (index 0-based), affine in the components.
    Component {
        symbol: String,
        index: Vec<usize>,
        value: Term,
    },
    /// `symbol_formal = value`, affine in the components.
    Equals {
        symbol: String,
        formal: Vec<char>,
        value: Term,
    },
    /// `left = right` for every value of their free letters: a polynomial constraint
    /// between expressions, solved for a power of one variable ([`super::rules`]).
    Constraint {
        left: Term,
        right: Term,
    },
    /// `left = right` at every point, for every value of their free letters, and
    /// therefore every derivative of it: a linear differential hypothesis on fields,
    /// solved for its highest derivative (see `Env::differential`).
    Differential {
        left: Term,
        right: Term,
    },
}

/// `symbol_formal := value`: the whole symbol replaced, after the equations, in order.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Substitution {
    pub symbol: String,
    pub formal: Vec<char>,
    pub value: Term,
}

/// Everything that gives a claim's terms their meaning.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Context {
    /// The index range 1..=dim (2 or 3).
    pub dim: usize,
    /// The unit normal's name; `in_plane`: its third component is 0 (a circle in 3D).
    pub normal: Option<String>,
    pub in_plane: bool,
    /// Declared symbols and their ranks (fields and the position included).
    pub symbols: BTreeMap<String, usize>,
    /// Fields, with the coordinates each depends on.
    pub fields: BTreeMap<String, Vec<bool>>,
    pub position: Option<String>,
    /// In scope order: a name means the last definition of that name.
    pub definitions: Vec<Definition>,
    pub equations: Vec<Equation>,
    pub substitutions: Vec<Substitution>,
    /// The box of parameter values (`given`): square roots take their sign on it, and
    /// sign claims hold on it.
    pub given: Vec<(String, Interval)>,
    /// Hypotheses on derived quantities (`given = ["J2 > 0"]`) of an identity: it is
    /// claimed where they hold, so a refutation needs a point where they do.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub hypotheses: Vec<Hypothesis>,
}

/// `left − right` has the sign: a hypothesis of an identity.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Hypothesis {
    pub left: Term,
    pub right: Term,
    pub sign: Sign,
}

/// Where a limit's variable goes.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Approach {
    /// To `c`, from both sides, from above (`c+`) or from below (`c−`).
    At(Rational, Side),
    PlusInfinity,
    MinusInfinity,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Side {
    Both,
    Above,
    Below,
}

impl std::fmt::Display for Approach {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Approach::At(c, Side::Both) => write!(f, "{c}"),
            Approach::At(c, Side::Above) => write!(f, "{c}+"),
            Approach::At(c, Side::Below) => write!(f, "{c}−"),
            Approach::PlusInfinity => write!(f, "+∞"),
            Approach::MinusInfinity => write!(f, "−∞"),
        }
    }
}

/// The value a limit claim states.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum LimitValue {
    Finite(Term),
    /// +∞ (`true`) or −∞.
    Signed(bool),
    /// |f| → ∞, whatever the sign.
    Unsigned,
}

/// What is claimed.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Claim {
    /// The sides of each chain are equal, for every value of the free indices.
    Equal { chains: Vec<Vec<Term>> },
    /// The left side of each equality is a nonzero factor (a constant, or a rational
    /// function of the parameters) times the right, where the factor is defined and
    /// nonzero.
    Proportional { chains: Vec<Vec<Term>> },
    /// `left − right` has the sign on the box, wherever both are defined.
    Sign { left: Term, right: Term, sign: Sign },
    /// `function` does not decrease (`increasing`) or not increase in `variable`:
    /// its derivative has that sign wherever defined.
    Monotone {
        function: Term,
        variable: String,
        increasing: bool,
    },
    Limit {
        function: Term,
        variable: String,
        to: Approach,
        value: LimitValue,
    },
    /// The zeros of `function` in `variable` on the box are exactly `roots`, or, with
    /// `count` (and no roots listed), exactly `count` distinct real numbers.
    Roots {
        function: Term,
        variable: String,
        roots: Vec<Term>,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        count: Option<usize>,
    },
    /// The points (x, y) over the unit normal in a plane lie on no common circle or
    /// line.
    NotCircle { x: Term, y: Term },
}

/// A polynomial by variable names: terms of (variable, exponent) factors and a
/// coefficient. The form in which a fact carries a polynomial hint.
pub type PolyData = Vec<(Vec<(String, super::poly::Exp)>, Rational)>;

/// A fraction hint (a square root a fact offers): numerator over divisors with
/// multiplicities.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FracData {
    pub num: PolyData,
    pub den: Vec<(PolyData, u32)>,
}

/// A claim in its context.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Statement {
    pub context: Context,
    pub claim: Claim,
}

/// A polynomial by variable names.
pub fn poly_data(p: &super::poly::Poly, names: &super::poly::VarTable) -> PolyData {
    p.terms()
        .map(|(m, c)| {
            let factors = m
                .factors()
                .iter()
                .map(|&(v, e)| (names.name(v).to_owned(), e))
                .collect();
            (factors, c.clone())
        })
        .collect()
}
