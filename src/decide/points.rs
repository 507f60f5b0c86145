//! Exact rational points: where two sides of an equality differ (sparse points first,
//! the normal on the unit sphere by stereographic projection), from the one seeded
//! generator ([`crate::decide::random`]) so that the same sides always get the same point.

use crate::algebra::sign::{inner_point, End, Interval};
use crate::algebra::{residue, Quotient};
use crate::decide::random::Rng;
use crate::kernel::rules::Rule;
use crate::kernel::{Poly, Rational, Var, VarTable};
use std::collections::BTreeMap;

/// The point of the unit circle (one parameter u) or sphere (two, u and v) by the
/// stereographic projection: ((1 − u²), 2u)/(1 + u²), or
/// (2u, 2v, 1 − u² − v²)/(1 + u² + v²), every rational point of either but a pole;
/// `flip` negates the coordinate along the pole (the first on the circle, the last on
/// the sphere).
pub(crate) fn stereographic(params: &[Rational], flip: bool) -> Vec<Rational> {
    let (one, two) = (Rational::int(1), Rational::int(2));
    let r2 = params
        .iter()
        .fold(Rational::int(0), |acc, p| &acc + &(p * p));
    let den = &one + &r2;
    let over = |x: Rational| x.checked_div(&den).expect("1 + r² > 0");
    let along = over(&one - &r2);
    let along = if flip { -along } else { along };
    let mut point: Vec<Rational> = params.iter().map(|p| over(&two * p)).collect();
    if params.len() == 1 {
        point.insert(0, along);
    } else {
        point.push(along);
    }
    point
}

/// A rational point of the unit circle or sphere, its parameters drawn from `rng`.
pub(crate) fn sphere_point(rng: &mut Rng, dim: usize) -> Vec<Rational> {
    let u =
        Rational::ratio(rng.small(), 1 + (rng.next_u64() % 3) as i64).expect("nonzero denominator");
    let v =
        Rational::ratio(rng.small(), 1 + (rng.next_u64() % 3) as i64).expect("nonzero denominator");
    if dim == 2 {
        return stereographic(&[u], false);
    }
    let mut p = stereographic(&[u, v], true);
    p.truncate(dim);
    p
}

/// The coordinates of `point` that the two sides use, by name, for the report.
pub fn shown_point(
    names: &VarTable,
    lhs: &Quotient,
    rhs: &Quotient,
    point: &BTreeMap<Var, Rational>,
) -> BTreeMap<String, String> {
    let used = used_variables(lhs, rhs);
    point
        .iter()
        .filter(|(v, _)| used.contains(v))
        .map(|(&v, q)| (names.name(v).to_owned(), q.to_string()))
        .collect()
}

fn used_variables(lhs: &Quotient, rhs: &Quotient) -> Vec<Var> {
    let mut used: Vec<Var> = lhs.variables();
    used.extend(rhs.variables());
    used.sort_unstable();
    used.dedup();
    used
}

/// `x` when the interval holds it; otherwise a point inside that still moves with
/// `x`, so that different draws give different points.
fn into_interval(i: &Interval, x: Rational) -> Rational {
    if i.contains(&x) {
        return x;
    }
    let size = if x.is_negative() {
        -x.clone()
    } else {
        x.clone()
    };
    let step = &size + &Rational::int(1);
    let inside = match (&i.lo, &i.hi) {
        (End::Unbounded, End::Unbounded) => x,
        (End::Open(a) | End::Closed(a), End::Unbounded) => a + &step,
        (End::Unbounded, End::Open(b) | End::Closed(b)) => b - &step,
        // a + (b − a)·s/(s + 1), strictly inside for s ≥ 1.
        (End::Open(a) | End::Closed(a), End::Open(b) | End::Closed(b)) => {
            let fraction = step
                .checked_div(&(&step + &Rational::int(1)))
                .expect("s + 1 > 0");
            a + &(&(b - a) * &fraction)
        }
    };
    if i.contains(&inside) {
        inside
    } else {
        inner_point(i)
    }
}

/// A rational point where both sides are defined and differ, with their values there:
/// sparse points first (one variable 1, the rest 0) because they read best, then dense
/// ones; the normal always lies on the unit sphere, and the point carries the whole
/// normal (for the second evaluation). The same sides always get the same point.
pub fn point_where_differ(
    normal: &[Var],
    lhs: &Quotient,
    rhs: &Quotient,
    (domain, hypotheses): (&[(Var, Interval)], &[Hypothesis]),
) -> Option<(BTreeMap<Var, Rational>, Rational, Rational)> {
    // A bounded variable gets a value in its interval even where the sides do not
    // read it: the interpreter that confirms the point evaluates the statement before
    // the state is substituted (a square root of τ² at τ = 0 has no derivative).
    let mut used = used_variables(lhs, rhs);
    used.extend(domain.iter().map(|(v, _)| *v));
    used.extend(hypotheses.iter().flat_map(|(q, _)| q.variables()));
    used.sort_unstable();
    used.dedup();
    let mut rng = Rng::new(0x05EE_DC05_E4A7);
    let others: Vec<Var> = used
        .iter()
        .copied()
        .filter(|v| !normal.contains(v))
        .collect();
    // Points with one variable at 1 read best; then dense ones. Under hypotheses, also
    // points with two variables at 1 and dense points of small fractions (0 < J2 < 1
    // excludes both the origin and most integer points).
    let more = if hypotheses.is_empty() {
        0
    } else {
        HYPOTHESIS_TRIES
    };
    let sparse = others.iter().map(|&v| Try::Sparse(Some(v)));
    let pairs = others
        .iter()
        .enumerate()
        .flat_map(|(k, &a)| others[k + 1..].iter().map(move |&b| Try::Pair(a, b)))
        .take(more);
    let candidates = sparse
        .chain(std::iter::once(Try::Sparse(None)))
        .flat_map(|one| (0..4).map(move |_| one))
        .chain((0..64).map(|_| Try::Dense))
        .chain(pairs)
        .chain((0..more).map(|_| Try::Fractions));
    for candidate in candidates {
        let n = sphere_point(&mut rng, normal.len().max(2));
        let mut point: BTreeMap<Var, Rational> = BTreeMap::new();
        for &v in &used {
            let value = match (normal.iter().position(|&w| w == v), candidate) {
                (Some(k), _) => n[k].clone(),
                (None, Try::Sparse(Some(one))) => Rational::int(i64::from(v == one)),
                (None, Try::Sparse(None)) => Rational::int(0),
                (None, Try::Dense) => Rational::int(rng.small()),
                (None, Try::Pair(a, b)) => Rational::int(i64::from(v == a || v == b)),
                (None, Try::Fractions) => {
                    Rational::ratio(rng.small(), 1 + (rng.next_u64() % 8) as i64)
                        .expect("nonzero denominator")
                }
            };
            let value = match domain.iter().find(|(w, _)| *w == v) {
                Some((_, i)) => into_interval(i, value),
                None => value,
            };
            point.insert(v, value);
        }
        // Screen modulo a prime first: equal residues mean (almost surely) equal
        // values, and the exact evaluation of a high power at a dense point costs
        // bigint arithmetic that is wasted on a candidate that will be skipped.
        if let Some(residues) = residues_of(&point) {
            let value = |v: Var| residues.get(v as usize).copied().unwrap_or(0);
            if !lhs.differs_mod_p(rhs, &value) {
                continue;
            }
        }
        let at = |v: Var| point.get(&v).cloned().unwrap_or_else(|| Rational::int(0));
        let (Some(l), Some(r)) = (lhs.eval(&at), rhs.eval(&at)) else {
            continue;
        };
        if l != r && hold(hypotheses, &at) {
            let (mut point, l, r) = if matches!(candidate, Try::Sparse(_)) {
                (point, l, r)
            } else {
                sparser(point, (l, r), &others, lhs, rhs, (domain, hypotheses))
            };
            for (k, &v) in normal.iter().enumerate() {
                point.entry(v).or_insert_with(|| n[k].clone());
            }
            return Some((point, l, r));
        }
    }
    None
}

/// At most this many variables are tried one by one by [`sparser`], on sides whose
/// values at the point found take at most this many bits.
const SPARSER_VARIABLES: usize = 64;
const SPARSER_BITS: u64 = 4096;

/// A point with as few nonzero variables (and as many at 1) as one pass finds: each
/// variable in turn is set to 0, then each left nonzero to 1, where the sides still
/// differ there and the hypotheses still hold. A point that reads best, for the same
/// refutation; the kernel checks whichever point it is given.
///
/// Residues modulo a prime decide each step where they can: equal residues mean
/// (almost surely) equal sides, and the step is not taken; different residues, with
/// every divisor and condition nonzero modulo the prime, mean different sides, both
/// defined, and the step is taken without evaluating (the sides are evaluated once,
/// at the end). Elsewhere, and under hypotheses, the sides are evaluated exactly.
fn sparser(
    point: BTreeMap<Var, Rational>,
    (l, r): (Rational, Rational),
    others: &[Var],
    lhs: &Quotient,
    rhs: &Quotient,
    (domain, hypotheses): (&[(Var, Interval)], &[Hypothesis]),
) -> (BTreeMap<Var, Rational>, Rational, Rational) {
    // Values of many digits mean costly evaluations: such a point is left as found.
    if others.len() > SPARSER_VARIABLES || l.bits() + r.bits() > SPARSER_BITS {
        return (point, l, r);
    }
    let found = (point.clone(), l.clone(), r.clone());
    let (mut point, mut values) = (point, Some((l, r)));
    for target in [0, 1] {
        for &v in others {
            let value = match domain.iter().find(|(w, _)| *w == v) {
                Some((_, i)) => into_interval(i, Rational::int(target)),
                None => Rational::int(target),
            };
            if point.get(&v).is_none_or(|x| x.is_zero()) || point.get(&v) == Some(&value) {
                continue;
            }
            let old = point.insert(v, value);
            let screened = residues_of(&point).and_then(|residues| {
                let value = |w: Var| residues.get(w as usize).copied().unwrap_or(0);
                differ_mod_p(lhs, rhs, &value).filter(|&d| !d || hypotheses.is_empty())
            });
            let keep = match screened {
                Some(differ) => {
                    if differ {
                        values = None;
                    }
                    differ
                }
                None => {
                    let at = |w: Var| point.get(&w).cloned().unwrap_or_else(|| Rational::int(0));
                    match (lhs.eval(&at), rhs.eval(&at)) {
                        (Some(a), Some(b)) if a != b && hold(hypotheses, &at) => {
                            values = Some((a, b));
                            true
                        }
                        _ => false,
                    }
                }
            };
            if !keep {
                point.insert(v, old.expect("a nonzero value was there"));
            }
        }
    }
    let at = |w: Var| point.get(&w).cloned().unwrap_or_else(|| Rational::int(0));
    match values.or_else(|| Some((lhs.eval(&at)?, rhs.eval(&at)?))) {
        Some((a, b)) if a != b => (point, a, b),
        _ => found,
    }
}

/// The residues of a point's values modulo the prime, by variable (0 for a variable
/// it leaves out); `None` when a denominator is a multiple of the prime.
fn residues_of(point: &BTreeMap<Var, Rational>) -> Option<Vec<u64>> {
    let size = point.keys().last().map_or(0, |&v| v as usize + 1);
    let mut out = vec![0; size];
    for (&v, q) in point {
        out[v as usize] = residue::of_rational(q)?;
    }
    Some(out)
}

/// Whether the sides differ at a point, by residues modulo a prime: `Some(false)` when
/// their residues agree (almost surely equal), `Some(true)` when they disagree and
/// every divisor and condition is nonzero modulo the prime (so nonzero: both sides
/// are defined and differ), `None` when the residues say neither.
fn differ_mod_p(lhs: &Quotient, rhs: &Quotient, value: &dyn Fn(Var) -> u64) -> Option<bool> {
    let (x, y) = (lhs.residue(value)?, rhs.residue(value)?);
    if x == y {
        return Some(false);
    }
    let nonzero = |p: &Poly| residue::of_poly(p, value).is_some_and(|x| x != 0);
    [lhs, rhs]
        .iter()
        .all(|q| {
            q.conditions()
                .iter()
                .chain(q.factors().iter().map(|(f, _)| f))
                .all(nonzero)
        })
        .then_some(true)
}

/// One kind of candidate point of [`point_where_differ`].
#[derive(Clone, Copy)]
enum Try {
    /// One variable at 1 (or none), the others 0.
    Sparse(Option<Var>),
    /// Small integers.
    Dense,
    /// Two variables at 1, the others 0.
    Pair(Var, Var),
    /// Small fractions.
    Fractions,
}

/// Further candidates of each kind [`point_where_differ`] tries under hypotheses.
const HYPOTHESIS_TRIES: usize = 256;

/// A hypothesis of an identity (`given = ["J2 > 0"]`): `q` has the sign.
pub type Hypothesis = (Quotient, crate::kernel::statement::Sign);

/// Whether every hypothesis holds at `at` (defined there, of its sign).
fn hold(hypotheses: &[Hypothesis], at: &dyn Fn(Var) -> Rational) -> bool {
    hypotheses
        .iter()
        .all(|(q, sign)| q.eval(at).is_some_and(|x| sign.admits(x.signum())))
}

/// Tries at a point that satisfies the polynomial constraints.
pub const CONSTRAINED_TRIES: usize = 128;

/// Tries at a seed of a quadric, and at a line through it.
const LINE_TRIES: usize = 64;

/// [`point_where_differ`] under polynomial constraints, each solved for a power of a
/// variable of its own (`v^d = value`, [`crate::kernel::rules`]): the other variables
/// drawn, then each solved variable the exact root of its value there. A square whose
/// value is no rational square takes a rational point of its quadric instead: the
/// second intersection with a line of rational slope through a seed point found among
/// small integers (the way [`sphere_point`] puts the normal on the sphere). `None` when
/// no try gives a point where the sides differ.
pub fn point_where_differ_constrained(
    rules: &[Rule],
    normal: &[Var],
    (lhs, rhs, everywhere): (&Quotient, &Quotient, &[Quotient]),
    (domain, hypotheses): (&[(Var, Interval)], &[Hypothesis]),
) -> Option<(BTreeMap<Var, Rational>, Rational, Rational)> {
    let mut used = used_variables(lhs, rhs);
    used.extend(domain.iter().map(|(v, _)| *v));
    used.extend(hypotheses.iter().flat_map(|(q, _)| q.variables()));
    used.extend(everywhere.iter().flat_map(Quotient::variables));
    for r in rules {
        used.push(r.var);
        used.extend(r.value.variables());
    }
    used.sort_unstable();
    used.dedup();
    let mut rng = Rng::new(0xC0_57_4A_17);
    let interval = |v: Var| domain.iter().find(|(w, _)| *w == v).map(|(_, i)| i);
    // Variables some side divides by (a negative power, a divisor's variable).
    let mut divisors: Vec<Var> = Vec::new();
    for q in everywhere.iter().chain([lhs, rhs]) {
        for (m, _) in q.numerator().terms() {
            divisors.extend(m.factors().iter().filter(|&&(_, e)| e < 0).map(|&(v, _)| v));
        }
        for (f, _) in q.factors() {
            divisors.extend(f.variables());
        }
    }
    for attempt in 0..CONSTRAINED_TRIES {
        let n = sphere_point(&mut rng, normal.len().max(2));
        let mut point: BTreeMap<Var, Rational> = BTreeMap::new();
        for &v in &used {
            if rules.iter().any(|r| r.var == v) {
                continue;
            }
            // The point of ones first, then the origin of the variables that no side
            // divides by (a radicand is often a square there: 1 + x^2 at 0).
            let value = match (normal.iter().position(|&w| w == v), attempt) {
                (Some(k), _) => n[k].clone(),
                (None, 0) => Rational::int(1),
                (None, 1) if !divisors.contains(&v) => Rational::int(0),
                (None, 1) => Rational::int(1),
                (None, _) => Rational::ratio(rng.small(), 1 + (rng.next_u64() % 3) as i64)
                    .expect("nonzero denominator"),
            };
            let value = match interval(v) {
                Some(i) => into_interval(i, value),
                None => value,
            };
            point.insert(v, value);
        }
        if !rules
            .iter()
            .all(|r| solve_rule(&mut rng, r, rules, &mut point, &interval))
        {
            continue;
        }
        // A first power is a value, not a root: set again after a later square moved
        // the variables it reads.
        for r in rules.iter().filter(|r| r.power == 1) {
            let at = |v: Var| point.get(&v).cloned().unwrap_or_else(|| Rational::int(0));
            match r.value.eval(&at) {
                Some(x) => {
                    point.insert(r.var, x);
                }
                None => continue,
            }
        }
        let at = |v: Var| point.get(&v).cloned().unwrap_or_else(|| Rational::int(0));
        let (Some(l), Some(r)) = (lhs.eval(&at), rhs.eval(&at)) else {
            continue;
        };
        if l != r && everywhere.iter().all(|q| q.eval(&at).is_some()) && hold(hypotheses, &at) {
            return Some((point, l, r));
        }
    }
    None
}

/// Sets `rule.var` so that the rule holds at `point`, moving the variables only this
/// rule reads when its value has no rational root there; `false` when no try works.
fn solve_rule<'d>(
    rng: &mut Rng,
    rule: &Rule,
    rules: &[Rule],
    point: &mut BTreeMap<Var, Rational>,
    interval: &impl Fn(Var) -> Option<&'d Interval>,
) -> bool {
    let inside = |v: Var, x: &Rational| interval(v).is_none_or(|i| i.contains(x));
    let value_at = |point: &BTreeMap<Var, Rational>| {
        rule.value
            .eval(&|v| point.get(&v).cloned().unwrap_or_else(|| Rational::int(0)))
    };
    // A root of either sign, on the box.
    let choose = |rng: &mut Rng, root: Rational| -> Option<Rational> {
        let mut roots = vec![root.clone()];
        if rule.power.is_multiple_of(2) && !root.is_zero() {
            roots.push(-root);
        }
        roots.retain(|x| inside(rule.var, x) && !(rule.nonnegative && x.is_negative()));
        (!roots.is_empty()).then(|| roots.swap_remove(rng.below(roots.len())))
    };
    if let Some(root) = value_at(point).and_then(|q| exact_root(&q, rule.power)) {
        if let Some(x) = choose(rng, root) {
            point.insert(rule.var, x);
            return true;
        }
    }
    if rule.power != 2 {
        return false;
    }
    // The variables no other root reads (a first power is set again afterwards), in
    // which the value is at most quadratic.
    let movable: Vec<Var> = rule
        .value
        .variables()
        .into_iter()
        .filter(|&v| {
            !rules
                .iter()
                .any(|r| r.var != rule.var && r.power > 1 && r.value.variables().contains(&v))
        })
        .collect();
    let quadratic = rule
        .value
        .terms()
        .all(|(m, _)| movable.iter().map(|&v| m.exponent(v)).sum::<i64>() <= 2);
    if movable.is_empty() || !quadratic {
        return false;
    }
    let small = |rng: &mut Rng| Rational::int(rng.small());
    for _ in 0..LINE_TRIES {
        // A seed: small integers (half of them 0) at which the value is a rational
        // square v0² (a seed at 0 where the quadric is singular gives itself back).
        let mut seed = point.clone();
        for &v in &movable {
            let x = if rng.below(2) == 0 {
                Rational::int(0)
            } else {
                small(rng)
            };
            seed.insert(v, x);
        }
        let Some(v0) = value_at(&seed).and_then(|q| q.sqrt_exact()) else {
            continue;
        };
        // Along x0 + t·dx, v0 + t·m: Q(t) = Q0 + B t + C t², and (v0 + t m)² = Q(t)
        // has the root t = 0 and t = (B − 2 v0 m)/(m² − C).
        let dx: Vec<Rational> = movable.iter().map(|_| small(rng)).collect();
        let m = small(rng);
        let along = |t: &Rational| {
            let mut p = seed.clone();
            for (&v, d) in movable.iter().zip(&dx) {
                let x = &seed[&v] + &(t * d);
                p.insert(v, x);
            }
            p
        };
        let (Some(q0), Some(q1), Some(qm)) = (
            value_at(&seed),
            value_at(&along(&Rational::int(1))),
            value_at(&along(&Rational::int(-1))),
        ) else {
            continue;
        };
        let half = Rational::ratio(1, 2).expect("nonzero");
        let b = &(&q1 - &qm) * &half;
        let c = &(&(&q1 + &qm) * &half) - &q0;
        let Some(t) = (&b - &(&(&Rational::int(2) * &v0) * &m)).checked_div(&(&(&m * &m) - &c))
        else {
            continue;
        };
        let mut p = along(&t);
        let v = &v0 + &(&t * &m);
        if value_at(&p) != Some(&v * &v) || !movable.iter().all(|&w| inside(w, &p[&w])) {
            continue;
        }
        let Some(v) = choose(rng, v) else { continue };
        p.insert(rule.var, v);
        *point = p;
        return true;
    }
    false
}

/// The rational x ≥ 0 with x^power = q (any sign for an odd power), when there is one:
/// square roots exactly, other odd powers only for 0 and ±1.
fn exact_root(q: &Rational, power: u32) -> Option<Rational> {
    match power {
        0 => None,
        1 => Some(q.clone()),
        _ if power.is_multiple_of(2) => exact_root(&q.sqrt_exact()?, power / 2),
        _ => [Rational::int(0), Rational::int(1), Rational::int(-1)]
            .into_iter()
            .find(|x| x == q),
    }
}
