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
//! use cosserat_kernel::check::{Proof, Conclusion};
//! let forged = Proof { conclusion: Conclusion::Holds };
//! ```

use super::eval::{Env, EvalError, Value, RULE_STEPS};
pub use super::fact::{
    Checked, Conclusion, Evaluation, Fact, Factor, OrbitsCompared, Reduced, Rejection, Summary,
};
use super::frac::Frac;
use super::poly::{Poly, Var};
use super::rational::Rational;
use super::statement::{Claim, Context, FracData, Statement};
use super::term::Term;
use serde::Serialize;

type R<T> = Result<T, Rejection>;

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
    // Under polynomial constraints only two facts are checked: an identity modulo
    // them, and a refutation at a point that satisfies them. (A difference modulo the
    // constraints need not be a difference at any real point.)
    let constrained = st
        .context
        .equations
        .iter()
        .any(|e| matches!(e, super::statement::Equation::Constraint { .. }));
    if constrained && !matches!(fact, Fact::Identity { .. } | Fact::Refutation { .. }) {
        return Err(Rejection::Mismatch(
            "under polynomial constraints only an identity or a refutation at a point is checked"
                .into(),
        ));
    }
    // Hypotheses may hold nowhere: only a point shows that they hold somewhere.
    let checked = matches!(fact, Fact::Identity { .. } | Fact::Refutation { .. })
        && matches!(st.claim, Claim::Equal { .. });
    if !st.context.hypotheses.is_empty() && !checked {
        return Err(Rejection::Mismatch(
            "under hypotheses only an identity or a refutation at a point where they hold is checked"
                .into(),
        ));
    }
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
            env.algebraic_roots = true;
            let chains = chains.ok_or_else(mismatch)?;
            let (l, r) = values_at(&mut env, chains, at)?;
            if l == r {
                return Err(Rejection::False("the sides are equal there".into()));
            }
            hypotheses_hold(&mut env, &st.context, &at.point)?;
            // Under constraints or square roots a side may be undefined on a whole
            // region: the claim says nothing there, so every side of every chain must
            // be defined at the point (their own roots join the rules it satisfies).
            if !env.rules.is_empty() {
                let sides = chains
                    .iter()
                    .flatten()
                    .map(|t| env.eval(t))
                    .collect::<Result<Vec<_>, _>>()?;
                let point = env.point(&at.point)?;
                let value = |v: Var| point.get(&v).cloned();
                if sides
                    .iter()
                    .flat_map(Value::comps)
                    .any(|f| f.eval(&value).is_none())
                {
                    return Err(Rejection::False(
                        "a side of the claim is undefined at the point".into(),
                    ));
                }
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
                Err(EvalError::IllFormed(why)) => {
                    Ok((Conclusion::Fails, vec![Checked::IllFormed { why }]))
                }
                Err(e) => Err(Rejection::Eval(e)),
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
        | Fact::RootsOfParameters { .. }
        | Fact::RootsAt { .. }
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
    env.algebraic_roots = factors.is_none();
    let normal = env.normal_vars().to_vec();
    let (mut components, mut modulo_unit_normal, mut modulo_rules) = (0, 0, 0);
    let mut nonzero: Vec<Poly> = Vec::new();
    let mut orbits = OrbitsCompared {
        of: 0,
        blocks: Vec::new(),
    };
    let mut factor_nonzero: Vec<Poly> = Vec::new();
    // A proportionality has one factor, the same in every equality (a matrix's
    // entries are one chain each) and in every component; each chain is one equality.
    let factor = match factors {
        None => None,
        Some([f]) => {
            if chains.iter().any(|c| c.len() != 2) {
                return Err(Rejection::Mismatch(
                    "a proportionality compares two sides".into(),
                ));
            }
            let (f, zeros) = factor_of(&mut env, &st.context, f)?;
            factor_nonzero.extend(zeros);
            Some(f)
        }
        Some(_) => {
            return Err(Rejection::Mismatch(
                "a proportionality has one factor".into(),
            ))
        }
    };
    for chain in chains {
        if chain.len() < 2 {
            return Err(Rejection::Mismatch("a chain of one side".into()));
        }
        for pair in chain.windows(2) {
            // An identity of many components whose sides no permutation of some free
            // letters changes is compared at one component per orbit.
            let at_orbits = match (&factor, roots.is_empty()) {
                (None, true) => super::symmetry::orbits(&env, &pair[0], &pair[1])
                    .and_then(|o| orbit_pairs(&mut env, &o)),
                _ => None,
            };
            let pairs = match at_orbits {
                Some((pairs, these)) => {
                    orbits.of += these.of;
                    orbits.blocks.extend(these.blocks);
                    pairs
                }
                None => {
                    let (a, b) = (env.eval(&pair[0])?, env.eval(&pair[1])?);
                    let pairs = pairs_of(&a, &b, env.ctx_dim());
                    orbits.of += pairs.len();
                    pairs
                }
            };
            for (x, y) in pairs {
                let y = match &factor {
                    Some(f) => y.mul(f).map_err(EvalError::from)?,
                    None => y.clone(),
                };
                let raw = x.cleared_difference(&y).map_err(EvalError::from)?;
                let on_sphere = raw
                    .reduce_on_sphere(&normal)
                    .map_err(|e| Rejection::Eval(EvalError::Unsupported(e.to_string())))?;
                let reduced = super::rules::reduce(&on_sphere, &env.rules, RULE_STEPS)
                    .map_err(|_| EvalError::Limit)?;
                modulo_rules += usize::from(!on_sphere.is_zero());
                if !reduced.is_zero() {
                    return Err(Rejection::False(format!(
                        "the sides differ in component {}",
                        components + 1
                    )));
                }
                components += 1;
                modulo_unit_normal += usize::from(raw != on_sphere);
                defined_on_sphere(&x, &normal)?;
                defined_on_sphere(&y, &normal)?;
                for c in x.conditions().iter().chain(y.conditions()) {
                    // A divisor that the constraints make zero leaves no point where
                    // the claim is defined: a proof there would be vacuous.
                    if super::rules::reduce(c, &env.rules, RULE_STEPS)
                        .map_err(|_| EvalError::Limit)?
                        .is_zero()
                    {
                        return Err(Rejection::False(
                            "a divisor is zero wherever the constraints hold".into(),
                        ));
                    }
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
    orbits.blocks.sort();
    orbits.blocks.dedup();
    let mut out = vec![Checked::PolynomialIdentity {
        components,
        modulo_unit_normal,
        nonzero,
        orbits: (orbits.of > components).then_some(orbits),
    }];
    // The constraints are evidence only where a comparison needed them.
    if modulo_rules > 0 {
        let rules = env
            .rules
            .iter()
            .map(|r| {
                let name = env.vars.name(r.var);
                let power = if r.power == 1 {
                    name.to_owned()
                } else {
                    format!("{name}^{}", r.power)
                };
                format!("{power} = {}", r.value.display(&env.vars))
            })
            .collect();
        out.push(Checked::Constraints {
            rules,
            reduced: modulo_rules,
        });
    }
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

/// The pairs of components an equality compares, at every value of the free letters
/// of either side (a side without a letter does not depend on it).
fn pairs_of(a: &Value, b: &Value, dim: usize) -> Vec<(Frac, Frac)> {
    let (la, lb) = (&a.letters, &b.letters);
    let mut all: Vec<char> = la.iter().chain(lb).copied().collect();
    all.sort_unstable();
    all.dedup();
    let at = |letters: &[char], idx: &[usize]| {
        letters.iter().fold(0, |acc, c| {
            acc * dim + idx[all.iter().position(|x| x == c).unwrap_or(0)]
        })
    };
    super::eval::assignments(dim, all.len())
        .iter()
        .map(|idx| (a.comps[at(la, idx)].clone(), b.comps[at(lb, idx)].clone()))
        .collect()
}

/// Both sides' components at one index value per orbit ([`super::symmetry`]), with
/// how many components they stand for and the blocks; `None` where a side cannot be
/// evaluated there (every component is then compared).
fn orbit_pairs(
    env: &mut Env<'_>,
    o: &super::symmetry::Orbits,
) -> Option<(Vec<(Frac, Frac)>, OrbitsCompared)> {
    let mut pairs = Vec::with_capacity(o.representatives.len());
    for values in &o.representatives {
        let at: Vec<(char, usize)> = o
            .letters
            .iter()
            .copied()
            .zip(values.iter().copied())
            .collect();
        let mut one = |side: &Term| -> Option<Frac> {
            let v = env.eval(&super::symmetry::at_values(side, &at)).ok()?;
            match v.comps() {
                [x] => Some(x.clone()),
                _ => None,
            }
        };
        let x = one(&o.sides[0])?;
        pairs.push((x, one(&o.sides[1])?));
    }
    let of = env
        .ctx_dim()
        .checked_pow(u32::try_from(o.letters.len()).ok()?)?;
    let blocks = o.blocks.iter().map(|b| b.iter().collect()).collect();
    Some((pairs, OrbitsCompared { of, blocks }))
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
    Ok(pairs_of(&a, &b, env.ctx_dim()))
}

/// One component of one equality: the pair of fractions its sides have there, each
/// side evaluated with its free letters fixed at the evaluation's values (in sorted
/// letter order over both sides).
fn component(env: &mut Env<'_>, chains: &[Vec<Term>], e: &Evaluation) -> R<(Frac, Frac)> {
    let chain = chains
        .get(e.chain)
        .ok_or_else(|| Rejection::Mismatch("no such chain".into()))?;
    let (Some(left), Some(right)) = (chain.get(e.equality), chain.get(e.equality + 1)) else {
        return Err(Rejection::Mismatch("no such equality".into()));
    };
    let mut letters = left.letters(env)?.free;
    letters.extend(right.letters(env)?.free);
    letters.sort_unstable();
    letters.dedup();
    if e.at.iter().any(|&v| v >= env.ctx_dim()) {
        return Err(Rejection::Mismatch("index values out of range".into()));
    }
    if letters.len() != e.at.len() {
        return Err(Rejection::Mismatch(
            "index values that do not fit the sides".into(),
        ));
    }
    let at: Vec<(char, usize)> = letters.into_iter().zip(e.at.iter().copied()).collect();
    // With the definitions written out, only this component of each is formed.
    let written = super::symmetry::written_out(env, left, right).and_then(|[l, r]| {
        let l = env.eval(&super::symmetry::at_values(&l, &at)).ok()?;
        Some((l, env.eval(&super::symmetry::at_values(&r, &at)).ok()?))
    });
    let (a, b) = match written {
        Some(pair) => pair,
        None => (
            env.eval(&left.at_indices(&at, env)?)?,
            env.eval(&right.at_indices(&at, env)?)?,
        ),
    };
    match (a.comps(), b.comps()) {
        ([x], [y]) => Ok((x.clone(), y.clone())),
        _ => Err(Rejection::Mismatch(
            "a side with free letters left at the index values".into(),
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

/// Every hypothesis of `ctx` holds at `point`: both its sides defined, their
/// difference of its sign.
fn hypotheses_hold(env: &mut Env<'_>, ctx: &Context, point: &[(String, Rational)]) -> R<()> {
    // Evaluated first: a square root they take joins the rules the point must satisfy.
    let mut sides = Vec::new();
    for h in &ctx.hypotheses {
        let (l, r) = (env.eval(&h.left)?, env.eval(&h.right)?);
        let ([l], [r]) = (l.comps(), r.comps()) else {
            return Err(Rejection::False("a hypothesis is not a scalar".into()));
        };
        sides.push((l.clone(), r.clone(), h.sign));
    }
    let at = env.point(point)?;
    let value = |v: Var| at.get(&v).cloned();
    for (l, r, sign) in &sides {
        let holds = match (l.eval(&value), r.eval(&value)) {
            (Some(x), Some(y)) => sign.admits((&x - &y).signum()),
            _ => false,
        };
        if !holds {
            return Err(Rejection::False(
                "a hypothesis does not hold at the point, or is undefined there".into(),
            ));
        }
    }
    Ok(())
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
