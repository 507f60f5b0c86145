//! The checker of facts: the only way to a [`Proof`].
//!
//! A strategy hands the kernel a [`Statement`] (what the claim says, in its context)
//! and a [`Fact`] (what it found: that the sides are identical, a point where they
//! differ, a sign certificate, …). [`check`] re-runs the fact against the statement
//! with the kernel's own evaluator and arithmetic and returns a `Proof` only when it
//! holds. A fact carries hints the search produced (a square root, a proportionality
//! factor, a point, the cuts between roots); a hint is never believed, only verified.
//! A `Proof` cannot be built, cloned or edited outside this module; a report keeps its
//! statement and fact, and `recheck` runs `check` on them again.
//!
//! ```compile_fail
//! use cosserat_check::kernel::check::{Proof, Conclusion};
//! let forged = Proof { conclusion: Conclusion::Holds };
//! ```

use super::eval::{Env, EvalError, Value};
use super::frac::Frac;
use super::poly::{Poly, Var};
use super::rational::Rational;
use super::statement::{Claim, FracData, PolyData, Statement};
use super::term::Term;
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

/// What a strategy found, to be checked against the statement.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Fact {
    /// Every equality holds for every value of the free indices, wherever its
    /// divisors are nonzero (modulo n·n = 1 when a normal is declared).
    Identity { roots: Vec<FracData> },
    /// Each equality's left side is its factor (nonzero) times the right.
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
    fn roots(&self) -> &[FracData] {
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
    },
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
        /// Whether the zeros are exactly the roots stated.
        exactly: bool,
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

/// A fact the kernel checked against its statement.
#[derive(Debug, PartialEq, Serialize)]
pub struct Proof {
    conclusion: Conclusion,
    statement: Statement,
    fact: Fact,
    summary: Summary,
}

impl Proof {
    pub fn conclusion(&self) -> Conclusion {
        self.conclusion
    }
    pub fn statement(&self) -> &Statement {
        &self.statement
    }
    pub fn fact(&self) -> &Fact {
        &self.fact
    }
    pub fn summary(&self) -> &[Checked] {
        &self.summary
    }
}

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

type R<T> = Result<T, Rejection>;

/// Checks `fact` against `statement`; the proof on success.
pub fn check(statement: Statement, fact: Fact) -> R<Proof> {
    let (conclusion, summary) = run(&statement, &fact)?;
    Ok(Proof {
        conclusion,
        statement,
        fact,
        summary,
    })
}

fn run(st: &Statement, fact: &Fact) -> R<(Conclusion, Summary)> {
    let chains = match &st.claim {
        Claim::Equal { chains } | Claim::Proportional { chains } => Some(chains),
        _ => None,
    };
    let proportional = matches!(st.claim, Claim::Proportional { .. });
    let mismatch = || Rejection::Mismatch("this fact is about another kind of claim".into());
    match fact {
        Fact::Identity { roots } if !proportional => Ok((
            Conclusion::Holds,
            identities(st, chains.ok_or_else(mismatch)?, roots, None)?,
        )),
        Fact::Proportional { factors, roots } if proportional => Ok((
            Conclusion::Holds,
            identities(st, chains.ok_or_else(mismatch)?, roots, Some(factors))?,
        )),
        Fact::Refutation { at, roots } if !proportional => {
            let mut env = Env::new(&st.context, roots)?;
            let (l, r) = values_at(&mut env, chains.ok_or_else(mismatch)?, at)?;
            if l == r {
                return Err(Rejection::False("the sides are equal there".into()));
            }
            Ok((Conclusion::Fails, refuted(&[(l, r)], &env)))
        }
        Fact::Differs { at, roots } if !proportional => {
            let mut env = Env::new(&st.context, roots)?;
            if !at.point.is_empty() {
                return Err(Rejection::Mismatch(
                    "a difference as functions names no point".into(),
                ));
            }
            open_box(&mut env, &st.context)?;
            let (x, y) = component(&mut env, chains.ok_or_else(mismatch)?, at)?;
            let normal = env.normal_vars().to_vec();
            let reduced = |p: Poly| {
                p.reduce_on_sphere(&normal)
                    .map_err(|e| Rejection::Eval(EvalError::Unsupported(e.to_string())))
            };
            let difference = reduced(x.cleared_difference(&y).map_err(EvalError::from)?)?;
            if difference.is_zero() {
                return Err(Rejection::False("the sides agree as functions".into()));
            }
            defined_on_sphere(&x, &normal)?;
            defined_on_sphere(&y, &normal)?;
            let mut out = roots_taken(&env);
            out.push(Checked::DifferentFunctions {
                terms: difference.num_terms(),
            });
            Ok((Conclusion::Fails, out))
        }
        Fact::NotProportional {
            first,
            second,
            roots,
        } if proportional => {
            let chains = chains.ok_or_else(mismatch)?;
            let mut env = Env::new(&st.context, roots)?;
            let (l1, r1) = values_at(&mut env, chains, first)?;
            let one_zero = l1.is_zero() != r1.is_zero();
            // A factor that depends on parameters may vanish, or have a pole, at the
            // point's parameter values: there one evaluation proves nothing, unless the
            // side that is zero there is zero as a function (then λ · right is zero
            // wherever λ is defined, while the left is not; or the left is zero while
            // λ · right is not, on an open set).
            let pairs = equality_pairs(&mut env, chains, first)?;
            let params = parameters(&st.context);
            let reads = |f: &Frac| {
                let mut vars = f.numerator().variables();
                vars.extend(f.denominator().iter().flat_map(|(p, _)| p.variables()));
                vars.into_iter().any(|v| params.contains(&env.vars.name(v)))
            };
            let constant = !pairs.iter().any(|(x, y)| reads(x) || reads(y));
            let normal = env.normal_vars().to_vec();
            let zero = |f: &Frac| {
                f.numerator()
                    .reduce_on_sphere(&normal)
                    .is_ok_and(|p| p.is_zero())
            };
            let side_is_zero = pairs
                .iter()
                .all(|(x, y)| zero(if r1.is_zero() { y } else { x }));
            let shown = match second {
                _ if one_zero && (constant || side_is_zero) => vec![(l1, r1)],
                // A factor λ would be l1/r1 (r1 ≠ 0); then l2 = λ r2 means l2 r1 = l1 r2.
                // With parameters, both evaluations must be at the same parameter
                // values: l r' − l' r is then a nonzero function of the parameters
                // (nonzero at theirs), so no factor works on a dense open set of them.
                Some(s) if (s.chain, s.equality) == (first.chain, first.equality) => {
                    if !same_parameters(&st.context, first, s) {
                        return Err(Rejection::False(
                            "the two evaluations are at different parameter values".into(),
                        ));
                    }
                    let (l2, r2) = values_at(&mut env, chains, s)?;
                    if r1.is_zero() || &l1 * &r2 == &l2 * &r1 {
                        return Err(Rejection::False("the first evaluation does not fix a factor, or the second agrees with it".into()));
                    }
                    vec![(l1, r1), (l2, r2)]
                }
                _ => {
                    return Err(Rejection::False(
                        "one evaluation with both sides zero or nonzero proves nothing".into(),
                    ))
                }
            };
            Ok((Conclusion::Fails, refuted(&shown, &env)))
        }
        Fact::IllFormed { chain, side } => {
            let t = chains
                .and_then(|c| c.get(*chain))
                .and_then(|c| c.get(*side))
                .ok_or_else(|| Rejection::Mismatch("no such side".into()))?;
            let env = Env::new(&st.context, &[])?;
            match t.letters(&env) {
                Err(why) if why == super::term::TOO_MANY_LETTERS => {
                    Err(Rejection::Eval(EvalError::Limit))
                }
                Err(why) => Ok((Conclusion::Fails, vec![Checked::IllFormed { why }])),
                Ok(_) => Err(Rejection::False("the side is well-formed".into())),
            }
        }
        Fact::SignByCoefficients { .. }
        | Fact::SignOnInterval { .. }
        | Fact::SignAt { .. }
        | Fact::ZeroBetween { .. }
        | Fact::TwoPoints { .. }
        | Fact::Constant { .. }
        | Fact::Pole { .. }
        | Fact::Limit { .. }
        | Fact::Roots { .. }
        | Fact::NotConcyclic { .. }
        | Fact::OnCircle { .. }
            if chains.is_none() =>
        {
            let mut env = Env::new(&st.context, fact.roots())?;
            let (conclusion, mut out) = super::scalar::run(&mut env, &st.claim, fact)?;
            out.extend(roots_taken(&env));
            Ok((conclusion, out))
        }
        _ => Err(mismatch()),
    }
}

fn refuted(values: &[(Rational, Rational)], env: &Env<'_>) -> Summary {
    let mut out = roots_taken(env);
    out.extend(values.iter().map(|(l, r)| Checked::Values {
        left: l.to_string(),
        right: r.to_string(),
    }));
    out
}

/// The square roots the evaluation accepted.
fn roots_taken(env: &Env<'_>) -> Summary {
    env.roots_taken
        .iter()
        .map(|r| Checked::SquareRoot {
            radicand: r.radicand.clone(),
            root: r.root.clone(),
            on: r.on.clone(),
            substitution: r.sign.substitution.clone(),
            cases: r.sign.cases,
        })
        .collect()
}

/// Every equality of the chains, component by component: identical fractions (after
/// the unit-normal reduction), or `factor ·` the right side.
fn identities(
    st: &Statement,
    chains: &[Vec<Term>],
    roots: &[FracData],
    factors: Option<&[Factor]>,
) -> R<Summary> {
    let mut env = Env::new(&st.context, roots)?;
    let normal = env.normal_vars().to_vec();
    let (mut components, mut modulo_unit_normal) = (0, 0);
    let mut nonzero: Vec<Poly> = Vec::new();
    let mut factor_nonzero: Vec<Poly> = Vec::new();
    let mut k = 0;
    for chain in chains {
        if chain.len() < 2 {
            return Err(Rejection::Mismatch("a chain of one side".into()));
        }
        for pair in chain.windows(2) {
            let factor = match factors {
                None => None,
                Some(f) => {
                    let f = f
                        .get(k)
                        .ok_or_else(|| Rejection::Mismatch("a factor per equality".into()))?;
                    let (f, zeros) = factor_of(&mut env, &st.context, f)?;
                    factor_nonzero.extend(zeros);
                    Some(f)
                }
            };
            k += 1;
            let (a, b) = (env.eval(&pair[0])?, env.eval(&pair[1])?);
            for (x, y) in pairs_of(&a, &b, env.ctx_dim())? {
                let y = match &factor {
                    Some(f) => y.mul(f).map_err(EvalError::from)?,
                    None => y.clone(),
                };
                let raw = x.cleared_difference(&y).map_err(EvalError::from)?;
                let reduced = raw
                    .reduce_on_sphere(&normal)
                    .map_err(|e| Rejection::Eval(EvalError::Unsupported(e.to_string())))?;
                if !reduced.is_zero() {
                    return Err(Rejection::False(format!(
                        "the sides differ in component {}",
                        components + 1
                    )));
                }
                components += 1;
                modulo_unit_normal += usize::from(!raw.is_zero());
                defined_on_sphere(&x, &normal)?;
                defined_on_sphere(&y, &normal)?;
                for c in x.conditions().iter().chain(y.conditions()) {
                    if c.num_terms() > 1 && !nonzero.contains(c) {
                        nonzero.push(c.clone());
                    }
                }
            }
        }
    }
    if components == 0 {
        return Err(Rejection::False("no component was compared".into()));
    }
    let mut nonzero: Vec<String> = nonzero.iter().map(|p| p.display(&env.vars)).collect();
    nonzero.sort();
    let mut out = vec![Checked::PolynomialIdentity {
        components,
        modulo_unit_normal,
        nonzero,
    }];
    if let Some([f]) = factors {
        let factor = match f {
            Factor::Constant(q) => q.to_string(),
            Factor::Function { num, den } => {
                let (n, d) = (env.poly_of(num)?, env.poly_of(den)?);
                match d.as_constant() {
                    Some(c) if c.is_one() && n.num_terms() == 1 => n.display(&env.vars),
                    Some(c) if c.is_one() => format!("({})", n.display(&env.vars)),
                    _ => format!("({}) / ({})", n.display(&env.vars), d.display(&env.vars)),
                }
            }
        };
        let mut nonzero: Vec<String> = factor_nonzero
            .iter()
            .map(|p| p.display(&env.vars))
            .collect();
        nonzero.sort();
        nonzero.dedup();
        out.push(Checked::Proportional { factor, nonzero });
    }
    out.extend(roots_taken(&env));
    Ok(out)
}

/// The names of a statement's parameters: its declared scalars that are not fields (or
/// the normal, or the position). A proportionality's factor may depend on them alone.
fn parameters(ctx: &super::statement::Context) -> Vec<&str> {
    ctx.symbols
        .iter()
        .filter(|(name, rank)| {
            **rank == 0
                && !ctx.fields.contains_key(*name)
                && ctx.normal.as_deref() != Some(name.as_str())
                && ctx.position.as_deref() != Some(name.as_str())
        })
        .map(|(name, _)| name.as_str())
        .collect()
}

/// A proportionality's factor as a fraction, and the polynomials it must not vanish
/// on (its numerator and denominator, when not constant). A function factor reads
/// only parameters that no assumption fixes, and is not the zero function.
fn factor_of(
    env: &mut Env<'_>,
    ctx: &super::statement::Context,
    f: &Factor,
) -> R<(Frac, Vec<Poly>)> {
    match f {
        Factor::Constant(q) if q.is_zero() => Err(Rejection::False("a zero factor".into())),
        Factor::Constant(q) => Ok((Frac::constant(q.clone()), Vec::new())),
        Factor::Function { num, den } => {
            // Each parameter it reads ranges over an open interval of the box, so that
            // the factor (a nonzero function) is nonzero on a dense part of the box: a
            // box that fixes one could make "where the factor ≠ 0" empty.
            let params = parameters(ctx);
            for (name, _) in num.iter().chain(den).flat_map(|(m, _)| m) {
                if !params.contains(&name.as_str()) || env.substituted_or_eliminated(name) {
                    return Err(Rejection::Mismatch(format!(
                        "the factor reads `{name}`, which is not a free parameter"
                    )));
                }
                if ctx
                    .given
                    .iter()
                    .any(|(n, i)| n == name && !i.has_interior())
                {
                    return Err(Rejection::Mismatch(format!(
                        "the factor reads `{name}`, which the box fixes: write it as an assumption"
                    )));
                }
            }
            let (n, d) = (env.poly_of(num)?, env.poly_of(den)?);
            if n.is_zero() || d.is_zero() {
                return Err(Rejection::False("a zero factor, or a zero divisor".into()));
            }
            let f = Frac::from(n.clone())
                .div(&Frac::from(d.clone()))
                .map_err(EvalError::from)?;
            // Listed as they read best: coprime integer coefficients, leading one positive.
            let zeros = [n, d]
                .into_iter()
                .filter(|p| p.as_constant().is_none())
                .map(|p| match super::poly::canonical_scale(&p) {
                    Some(c) => &p * &Poly::constant(c),
                    None => p,
                })
                .collect();
            Ok((f, zeros))
        }
    }
}

/// The pairs of components an equality compares: for tensors, at every value of the
/// free letters of either side (a side without a letter does not depend on it), for
/// matrices of one shape, entry by entry.
fn pairs_of(a: &Value, b: &Value, dim: usize) -> R<Vec<(Frac, Frac)>> {
    match (a, b) {
        (
            Value::Matrix {
                rows,
                cols,
                entries: x,
            },
            Value::Matrix {
                rows: r2,
                cols: c2,
                entries: y,
            },
        ) if (rows, cols) == (r2, c2) => Ok(x.iter().cloned().zip(y.iter().cloned()).collect()),
        (
            Value::Tensor {
                letters: la,
                comps: x,
            },
            Value::Tensor {
                letters: lb,
                comps: y,
            },
        ) => {
            let mut all: Vec<char> = la.iter().chain(lb).copied().collect();
            all.sort_unstable();
            all.dedup();
            let at = |letters: &[char], idx: &[usize]| {
                letters.iter().fold(0, |acc, c| {
                    acc * dim + idx[all.iter().position(|x| x == c).unwrap_or(0)]
                })
            };
            Ok(super::eval::assignments(dim, all.len())
                .iter()
                .map(|idx| (x[at(la, idx)].clone(), y[at(lb, idx)].clone()))
                .collect())
        }
        _ => Err(Rejection::False(
            "a matrix is compared with something of another shape".into(),
        )),
    }
}

/// Whether two evaluations agree on every parameter both name (a parameter one of them
/// leaves out does not enter its sides there).
fn same_parameters(ctx: &super::statement::Context, a: &Evaluation, b: &Evaluation) -> bool {
    let value = |e: &Evaluation, name: &str| {
        e.point
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, x)| x.clone())
    };
    parameters(ctx)
        .into_iter()
        .all(|p| match (value(a, p), value(b, p)) {
            (Some(x), Some(y)) => x == y,
            _ => true,
        })
}

/// Every pair of components of the equality `e` names.
fn equality_pairs(env: &mut Env<'_>, chains: &[Vec<Term>], e: &Evaluation) -> R<Vec<(Frac, Frac)>> {
    let (Some(left), Some(right)) = (
        chains.get(e.chain).and_then(|c| c.get(e.equality)),
        chains.get(e.chain).and_then(|c| c.get(e.equality + 1)),
    ) else {
        return Err(Rejection::Mismatch("no such equality".into()));
    };
    let (a, b) = (env.eval(left)?, env.eval(right)?);
    pairs_of(&a, &b, env.ctx_dim())
}

/// One component of one equality: the pair of fractions its sides have there.
fn component(env: &mut Env<'_>, chains: &[Vec<Term>], e: &Evaluation) -> R<(Frac, Frac)> {
    let chain = chains
        .get(e.chain)
        .ok_or_else(|| Rejection::Mismatch("no such chain".into()))?;
    let (Some(left), Some(right)) = (chain.get(e.equality), chain.get(e.equality + 1)) else {
        return Err(Rejection::Mismatch("no such equality".into()));
    };
    let (a, b) = (env.eval(left)?, env.eval(right)?);
    let dim = env.ctx_dim();
    let pairs = pairs_of(&a, &b, dim)?;
    let at =
        e.at.iter()
            .try_fold(0usize, |acc, &v| {
                (v < dim).then_some(())?;
                acc.checked_mul(dim)?.checked_add(v)
            })
            .ok_or_else(|| Rejection::Mismatch("index values out of range".into()))?;
    let count_ok = match (&a, &b) {
        (Value::Matrix { .. }, _) => e.at.len() == 1 && e.at[0] < pairs.len(),
        _ => dim.checked_pow(e.at.len() as u32) == Some(pairs.len()),
    };
    let at = if matches!(a, Value::Matrix { .. }) {
        e.at.first().copied().unwrap_or(0)
    } else {
        at
    };
    match pairs.get(at) {
        Some(p) if count_ok => Ok(p.clone()),
        _ => Err(Rejection::Mismatch(
            "index values that do not fit the sides".into(),
        )),
    }
}

/// Both sides' exact values at one evaluation: the point must assign every
/// variable they read, satisfy the assumptions, lie in the box and put the normal on
/// the unit sphere; both sides must be defined there.
fn values_at(env: &mut Env<'_>, chains: &[Vec<Term>], e: &Evaluation) -> R<(Rational, Rational)> {
    let (x, y) = component(env, chains, e)?;
    let point = env.point(&e.point)?;
    let value = |v: Var| point.get(&v).cloned();
    match (x.eval(&value), y.eval(&value)) {
        (Some(l), Some(r)) => Ok((l, r)),
        _ => Err(Rejection::False(
            "a side is undefined at the point, or the point leaves a variable out".into(),
        )),
    }
}

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

/// No divisor of `f` vanishes wherever the normal is a unit vector: else `f` is
/// defined nowhere, and an equality with it says nothing.
fn defined_on_sphere(f: &Frac, normal: &[Var]) -> R<()> {
    for c in f.conditions() {
        let on_sphere = c
            .reduce_on_sphere(normal)
            .map_err(|e| Rejection::Eval(EvalError::Unsupported(e.to_string())))?;
        if on_sphere.is_zero() {
            return Err(Rejection::False(
                "a divisor vanishes wherever the normal is a unit vector".into(),
            ));
        }
    }
    Ok(())
}

/// The box must be open somewhere for a difference as functions to refute: every
/// interval has interior and bounds a variable other than the normal's (the
/// environment has refused a bounded variable fixed by an assumption).
fn open_box(env: &mut Env<'_>, ctx: &super::statement::Context) -> R<()> {
    let normal = env.normal_vars().to_vec();
    for (name, i) in &ctx.given {
        let v = env.vars.intern(name);
        if !i.has_interior() || normal.contains(&v) {
            return Err(Rejection::Mismatch(format!(
                "the box bounds `{name}` to no open interval of a free variable"
            )));
        }
    }
    Ok(())
}
