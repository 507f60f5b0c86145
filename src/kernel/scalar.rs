//! Facts about scalar functions of parameters on a box: signs, monotonicity, limits,
//! roots, and the not-a-circle witness. The function is the kernel's own value of the
//! claim's terms; a fact's cuts and points are hints, checked exactly: Sturm counts of
//! roots between rational points (`univariate`), signs by coefficients (`sign`), exact
//! values.

use super::eval::{Env, EvalError};
use super::fact::{Checked, Conclusion, Reduced, Rejection};
use super::frac::Frac;
use super::poly::{Poly, Var};
use super::rational::Rational;
use super::sign::by_coefficients;
use super::statement::{Approach, Claim, End, Interval, LimitValue, Side, Sign};
use super::univariate::Uni;
use num_traits::Zero;
use std::collections::BTreeMap;

type R<T> = Result<T, Rejection>;

/// `f`'s numerator and `den`, both times the power v^m that clears their negative powers
/// of `v` (their quotient is unchanged), and that power.
fn lifted(f: &Frac, den: &Poly, v: Var) -> R<(Poly, Poly, Poly)> {
    let low = f
        .numerator()
        .terms()
        .chain(den.terms())
        .map(|(m, _)| m.exponent(v))
        .min()
        .unwrap_or(0);
    let lift = Poly::term(
        super::poly::Monomial::var(v, (-low).max(0)),
        Rational::int(1),
    );
    let num = f
        .numerator()
        .checked_mul(&lift)
        .map_err(|_| EvalError::Limit)?;
    let den = den.checked_mul(&lift).map_err(|_| EvalError::Limit)?;
    Ok((num, den, lift))
}

/// The product of `f`'s denominator factors that `keep` selects, each to its power.
fn denominator(f: &Frac, keep: impl Fn(&Poly) -> bool) -> R<Poly> {
    let mut den = <Poly as num_traits::One>::one();
    for (g, k) in f.denominator().iter().filter(|(g, _)| keep(g)) {
        den = den
            .checked_mul(&g.checked_pow(*k).map_err(|_| EvalError::Limit)?)
            .map_err(|_| EvalError::Limit)?;
    }
    Ok(den)
}

fn no(why: &str) -> Rejection {
    Rejection::False(why.to_owned())
}

fn frac(r: Result<Frac, super::frac::FracError>) -> R<Frac> {
    r.map_err(|e| Rejection::Eval(EvalError::from(e)))
}

/// The scalar value of a term.
fn scalar(env: &mut Env<'_>, t: &super::term::Term) -> R<Frac> {
    match env.eval(t)? {
        super::eval::Value { letters, mut comps } if letters.is_empty() => Ok(comps.remove(0)),
        _ => Err(Rejection::Mismatch(
            "a scalar claim about something that is not a scalar".into(),
        )),
    }
}

/// The sign `f` must have, and what to say of it: a sign claim's `left − right`, a
/// monotonicity's derivative.
struct Target {
    f: Frac,
    want: Sign,
    /// For a monotonicity: the function itself, whose poles break it.
    function: Option<Frac>,
    v: Option<Var>,
}

/// `f` in the lowest terms a fact offers: `num_r / den_r` with `den_r` dividing the
/// kernel's denominator D (D = den_r·q) and its numerator N = num_r·q (both times
/// the same power of each variable, to clear negative ones). Where f is defined,
/// D ≠ 0, so den_r ≠ 0 and the two agree; f's conditions stay.
fn reduce(env: &mut Env<'_>, f: Frac, hint: Option<&Reduced>) -> R<Frac> {
    let Some((n, d)) = hint else { return Ok(f) };
    let (nr, dr) = (env.poly_of(n)?, env.poly_of(d)?);
    let den = denominator(&f, |_| true)?;
    let mut vars = f.numerator().variables();
    vars.extend(den.variables());
    let lowest: Vec<(Var, super::poly::Exp)> = vars
        .iter()
        .map(|&v| {
            let low = f
                .numerator()
                .terms()
                .chain(den.terms())
                .map(|(m, _)| m.exponent(v))
                .min()
                .unwrap_or(0);
            (v, (-low).max(0))
        })
        .collect();
    let lift = Poly::term(
        super::poly::Monomial::checked_from_factors(lowest).ok_or(EvalError::Limit)?,
        Rational::int(1),
    );
    let (num, den) = (
        f.numerator()
            .checked_mul(&lift)
            .map_err(|_| EvalError::Limit)?,
        den.checked_mul(&lift).map_err(|_| EvalError::Limit)?,
    );
    let q = den
        .divide_exact(&dr, 100_000)
        .ok_or_else(|| no("the reduced denominator does not divide the function's"))?;
    if num != nr.checked_mul(&q).map_err(|_| EvalError::Limit)? {
        return Err(no("the reduced form is not the function"));
    }
    let mut conds = f.conditions().to_vec();
    if dr.num_terms() > 1 && !conds.contains(&dr) {
        conds.push(dr.clone());
    }
    // A constant denominator (of either sign) divides into the numerator.
    let (num, den) = match dr.as_constant() {
        Some(c) => {
            let inverse = c.recip().ok_or_else(|| no("a zero denominator"))?;
            (
                nr.checked_mul(&Poly::constant(inverse))
                    .map_err(|_| EvalError::Limit)?,
                Vec::new(),
            )
        }
        None => (nr, vec![(dr, 1)]),
    };
    Ok(Frac { num, den, conds })
}

fn target(env: &mut Env<'_>, claim: &Claim) -> R<Target> {
    Ok(match claim {
        Claim::Sign { left, right, sign } => {
            let (l, r) = (scalar(env, left)?, scalar(env, right)?);
            Target {
                f: frac(l.sub(&r))?,
                want: *sign,
                function: None,
                v: None,
            }
        }
        Claim::Monotone {
            function,
            variable,
            increasing,
        } => {
            let f = scalar(env, function)?;
            let v = env.free_variable(variable)?;
            Target {
                f: frac(f.derivative(v))?,
                want: if *increasing {
                    Sign::NonNegative
                } else {
                    Sign::NonPositive
                },
                function: Some(f),
                v: Some(v),
            }
        }
        _ => return Err(Rejection::Mismatch("not a sign or a monotonicity".into())),
    })
}

/// A fraction's numerator, denominator and conditions in one variable, its divisors
/// that divide the numerator cancelled. A condition without `v` only leaves points
/// out, and one of strict sign on the box none: both are dropped (the sign is then
/// shown on more points, never fewer).
fn univariate(f: &Frac, v: Var, box_: &[(Var, Interval)], env: &Env<'_>) -> R<(Uni, Uni, Uni)> {
    let one = |p: &Poly| {
        Uni::of(p, v).ok_or_else(|| {
            Rejection::False(format!(
                "the function is not of `{}` alone: {}",
                env.vars.name(v),
                p.display_truncated(&env.vars, 4)
            ))
        })
    };
    let f = f.tidied();
    let den = denominator(&f, |_| true)?;
    let mut conds = <Poly as num_traits::One>::one();
    for c in f.conditions() {
        let of_v = c.variables().contains(&v);
        let strict = [Sign::Positive, Sign::Negative]
            .into_iter()
            .any(|s| by_coefficients(&Frac::from(c.clone()), box_, s, &env.vars).is_some());
        if of_v && !strict {
            conds = conds.checked_mul(c).map_err(|_| EvalError::Limit)?;
        }
    }
    // Both times v^m, so that no negative power of v is left (v = 0 is then a root of
    // the denominator: the function is undefined there, as it was).
    let (num, den, _) = lifted(&f, &den, v)?;
    // A factor free of v that keeps one strict sign on the box (μ in μ (x² − 1), with
    // μ > 0) changes neither the roots in v nor, up to that sign, the sign of f: it is
    // divided out, and its sign moves to the numerator.
    let mut negative = false;
    let mut part = |p: &Poly| -> R<Uni> {
        if let Some(u) = Uni::of(p, v) {
            return Ok(u);
        }
        let strict = |content: &Poly| {
            [Sign::Positive, Sign::Negative].into_iter().find(|&s| {
                by_coefficients(&Frac::from(content.clone()), box_, s, &env.vars).is_some()
            })
        };
        match content_in(p, v) {
            Some((content, u)) => match strict(&content) {
                Some(s) => {
                    negative ^= s == Sign::Negative;
                    Ok(u)
                }
                None => one(p),
            },
            None => one(p),
        }
    };
    let (n, d) = (part(&num)?, part(&den)?);
    let n = if negative { n.negated() } else { n };
    Ok((n, d, one(&conds)?))
}

/// `p = content · q(v)`: `content` free of `v`, and `q` a polynomial in `v` alone with
/// rational coefficients (every power of `v` has a rational multiple of one polynomial
/// as its coefficient); `None` otherwise.
fn content_in(p: &Poly, v: Var) -> Option<(Poly, Uni)> {
    let mut by_power: BTreeMap<super::poly::Exp, Poly> = BTreeMap::new();
    for (m, c) in p.terms() {
        let k = m.exponent(v);
        if k < 0 {
            return None;
        }
        by_power
            .entry(k)
            .or_default()
            .add_term(m.without(v), c.clone());
    }
    let content = by_power.values().next()?.clone();
    let (lead_m, lead_c) = content.leading()?;
    let mut q = Poly::zero();
    for (k, a) in &by_power {
        let (m, c) = a.leading()?;
        if m != lead_m {
            return None;
        }
        let ratio = c.checked_div(lead_c)?;
        if a != &(&content * &Poly::constant(ratio.clone())) {
            return None;
        }
        q.add_term(super::poly::Monomial::var(v, *k), ratio);
    }
    Some((content, Uni::of(&q, v)?))
}

/// `f` (of `v` alone) has the sign `want` on `i` wherever defined: between the cuts
/// (strictly increasing, inside `i`) each piece holds no root of N·D·C (sign at one
/// point) or one, between two cuts that are not roots (signs at both cuts, and for a
/// strict sign the root a pole, not a zero); at each cut and closed end, exactly.
fn on_interval(
    f: &Frac,
    v: Var,
    i: &Interval,
    want: Sign,
    cuts: &[Rational],
    b: (&[(Var, Interval)], &Env<'_>),
) -> R<(usize, usize)> {
    let (n, d, c) = univariate(f, v, b.0, b.1)?;
    if n.is_zero() {
        return if want.admits(0) {
            Ok((1, 0))
        } else {
            Err(no("the function is 0"))
        };
    }
    let undefined = d.mul(&c);
    let all = n.mul(&undefined);
    let value = |x: &Rational| -> Option<i32> {
        (!undefined.eval(x).is_zero()).then(|| n.eval(x).signum() * d.eval(x).signum())
    };
    let inside = |x: &Rational| i.contains(x) && Some(x) != i.lo.value() && Some(x) != i.hi.value();
    if cuts.windows(2).any(|w| w[0] >= w[1]) || !cuts.iter().all(inside) {
        return Err(Rejection::Mismatch(
            "cuts not increasing inside the interval".into(),
        ));
    }
    let mut points: Vec<&Rational> = cuts.iter().collect();
    for e in [&i.lo, &i.hi] {
        if let End::Closed(x) = e {
            points.push(x);
        }
    }
    for x in points {
        if let Some(s) = value(x) {
            if !want.admits(s) {
                return Err(no("the sign is wrong at a cut"));
            }
        }
    }
    let mut ends: Vec<Option<&Rational>> = vec![i.lo.value()];
    ends.extend(cuts.iter().map(Some));
    ends.push(i.hi.value());
    let mut pieces = 0;
    for w in ends.windows(2) {
        let (a, b) = (w[0], w[1]);
        if a.is_some() && a == b {
            // A one-point interval: no open piece, its point is a closed end (above).
            continue;
        }
        pieces += 1;
        match all.roots_between(a, b) {
            Some(0) => {
                let s = match (a, b) {
                    (Some(a), Some(b)) => &(a + b) * &Rational::ratio(1, 2).expect("2 ≠ 0"),
                    (Some(a), None) => a + &Rational::int(1),
                    (None, Some(b)) => b - &Rational::int(1),
                    (None, None) => Rational::zero(),
                };
                if !value(&s).is_some_and(|s| want.admits(s)) {
                    return Err(no("the sign is wrong on a piece"));
                }
            }
            Some(1) => {
                let (Some(a), Some(b)) = (a, b) else {
                    return Err(Rejection::Mismatch(
                        "a root next to an end that is not a cut".into(),
                    ));
                };
                if !cuts.contains(a)
                    || !cuts.contains(b)
                    || all.eval(a).is_zero()
                    || all.eval(b).is_zero()
                {
                    return Err(Rejection::Mismatch("a root not between two cuts".into()));
                }
                let pole = undefined.roots_between(Some(a), Some(b)) == Some(1);
                if !want.admits(0) && !pole {
                    return Err(no("the function is 0 at a root"));
                }
            }
            _ => {
                return Err(Rejection::Mismatch(
                    "the cuts do not separate the roots".into(),
                ))
            }
        }
    }
    let poles = undefined
        .roots_between(i.lo.value(), i.hi.value())
        .unwrap_or(0);
    Ok((pieces, poles))
}

/// The reduced denominator of `f` (of `v` alone): its roots are the poles.
fn reduced_denominator(f: &Frac, v: Var, b: (&[(Var, Interval)], &Env<'_>)) -> R<Uni> {
    let (n, d, _) = univariate(f, v, b.0, b.1)?;
    let g = n.gcd(&d);
    let mut out = d;
    // d / g by Sturm-free means: roots of d that are not roots of g.
    if !g.is_zero() {
        out = Uni::quotient(&out, &g);
    }
    Ok(out)
}

/// The interval of `v` on the box (the real line when the box does not bound it).
fn interval(box_: &[(Var, Interval)], v: Var) -> Interval {
    box_.iter()
        .find(|(w, _)| *w == v)
        .map_or_else(Interval::real_line, |(_, i)| i.clone())
}

/// The value of `f` at a point (checked by the environment), `None` where undefined.
fn at(env: &mut Env<'_>, f: &Frac, point: &[(String, Rational)]) -> R<Option<Rational>> {
    let p = env.point(point)?;
    Ok(f.eval(&|v| p.get(&v).cloned()))
}

/// The scalar facts (see [`super::fact::Fact`]).
pub(super) fn run(
    env: &mut Env<'_>,
    claim: &Claim,
    fact: &super::fact::Fact,
) -> R<(Conclusion, Vec<Checked>)> {
    use super::fact::Fact as F;
    let box_ = env.given_box();
    Ok(match fact {
        F::SignByCoefficients {
            reduced, function, ..
        } => {
            let mut t = target(env, claim)?;
            // The coefficients are those of the function in lowest terms: the
            // search's reduction, checked, or the divisors that divide the numerator.
            t.f = reduce(env, t.f, reduced.as_ref())?.tidied();
            t.function = t
                .function
                .map(|f| reduce(env, f, function.as_ref()))
                .transpose()?;
            if t.function.is_some() && t.f.is_zero() {
                return Err(no("the derivative is 0: the function does not change"));
            }
            let how = by_coefficients(&t.f, &box_, t.want, &env.vars)
                .ok_or_else(|| no("coefficients of mixed signs"))?;
            let mut out = vec![Checked::CoefficientSigns {
                substitution: how.substitution,
                cases: how.cases,
            }];
            if let Some(f) = &t.function {
                // No pole: the denominator has one strict sign on the box.
                let den = Frac::from(denominator(f, |_| true)?);
                let how = [Sign::Positive, Sign::Negative]
                    .into_iter()
                    .find_map(|s| by_coefficients(&den, &box_, s, &env.vars))
                    .ok_or_else(|| no("the denominator is not certified free of zeros"))?;
                out.push(Checked::CoefficientSigns {
                    substitution: how.substitution,
                    cases: how.cases,
                });
            }
            (Conclusion::Holds, out)
        }
        F::SignOnInterval {
            variable,
            cuts,
            reduced,
            function,
            ..
        } => {
            let mut t = target(env, claim)?;
            t.f = reduce(env, t.f, reduced.as_ref())?;
            t.function = t
                .function
                .map(|f| reduce(env, f, function.as_ref()))
                .transpose()?;
            let v = env.free_variable(variable)?;
            if t.v.is_some_and(|w| w != v) {
                return Err(Rejection::Mismatch("another variable".into()));
            }
            let i = interval(&box_, v);
            if t.function.is_some() && t.f.is_zero() {
                return Err(no("the derivative is 0: the function does not change"));
            }
            let (pieces, poles) = on_interval(&t.f, v, &i, t.want, cuts, (&box_, env))?;
            if let Some(f) = &t.function {
                let p = reduced_denominator(f, v, (&box_, env))?;
                let closed_pole = [&i.lo, &i.hi]
                    .iter()
                    .any(|e| matches!(e, End::Closed(x) if p.eval(x).is_zero()));
                if p.roots_between(i.lo.value(), i.hi.value()) != Some(0) || closed_pole {
                    return Err(no("the function has a pole on the interval"));
                }
            }
            (
                Conclusion::Holds,
                vec![Checked::SignOnInterval {
                    interval: i.describe(variable),
                    relation: t.want.relation().to_owned(),
                    pieces,
                    poles,
                }],
            )
        }
        F::SignAt { point, .. } => {
            let Claim::Sign { left, right, sign } = claim else {
                return Err(Rejection::Mismatch("not a sign claim".into()));
            };
            let (l, r) = (scalar(env, left)?, scalar(env, right)?);
            let (Some(lv), Some(rv)) = (at(env, &l, point)?, at(env, &r, point)?) else {
                return Err(no("a side is undefined at the point"));
            };
            if sign.admits((&lv - &rv).signum()) {
                return Err(no("the sign holds at the point"));
            }
            (
                Conclusion::Fails,
                vec![Checked::Values {
                    left: lv.to_string(),
                    right: rv.to_string(),
                }],
            )
        }
        F::ZeroBetween {
            variable, lo, hi, ..
        } => {
            let Claim::Sign { left, right, sign } = claim else {
                return Err(Rejection::Mismatch("not a sign claim".into()));
            };
            if sign.admits(0) {
                return Err(no("a zero does not break a sign that admits 0"));
            }
            let (l, r) = (scalar(env, left)?, scalar(env, right)?);
            let v = env.free_variable(variable)?;
            let (n, d, c) = univariate(&frac(l.sub(&r))?, v, &box_, env)?;
            let i = interval(&box_, v);
            let undefined = d.mul(&c);
            let clear = lo < hi
                && i.contains(lo)
                && i.contains(hi)
                && !undefined.eval(lo).is_zero()
                && !undefined.eval(hi).is_zero();
            if !clear
                || undefined.roots_between(Some(lo), Some(hi)) != Some(0)
                || n.roots_between(Some(lo), Some(hi)).unwrap_or(0) == 0
            {
                return Err(no(
                    "no zero of the difference where it is defined in the interval",
                ));
            }
            (
                Conclusion::Fails,
                vec![Checked::ZeroBetween {
                    variable: variable.clone(),
                    lo: lo.to_string(),
                    hi: hi.to_string(),
                }],
            )
        }
        F::TwoPoints { a, b, point, .. } => {
            let Claim::Monotone {
                function,
                variable,
                increasing,
            } = claim
            else {
                return Err(Rejection::Mismatch("not a monotonicity".into()));
            };
            let f = scalar(env, function)?;
            let mut values = Vec::new();
            for x in [a, b] {
                let mut p = point.clone();
                p.retain(|(n, _)| n != variable);
                p.push((variable.clone(), x.clone()));
                values.push(
                    at(env, &f, &p)?.ok_or_else(|| no("the function is undefined at a point"))?,
                );
            }
            let wrong = if *increasing {
                values[0] > values[1]
            } else {
                values[0] < values[1]
            };
            if a >= b || !wrong {
                return Err(no("the two values agree with the claim"));
            }
            (
                Conclusion::Fails,
                vec![Checked::Values {
                    left: values[0].to_string(),
                    right: values[1].to_string(),
                }],
            )
        }
        F::Constant { .. } => {
            let t = target(env, claim)?;
            if t.function.is_none() || !t.f.is_zero() {
                return Err(no("the function is not constant in the variable"));
            }
            (Conclusion::Fails, vec![Checked::Constant])
        }
        F::Pole { lo, hi, .. } => {
            let Claim::Monotone {
                function, variable, ..
            } = claim
            else {
                return Err(Rejection::Mismatch("not a monotonicity".into()));
            };
            let f = scalar(env, function)?;
            let v = env.free_variable(variable)?;
            let i = interval(&box_, v);
            let p = reduced_denominator(&f, v, (&box_, env))?;
            if !(lo < hi && i.contains(lo) && i.contains(hi))
                || p.roots_between(Some(lo), Some(hi)).unwrap_or(0) == 0
            {
                return Err(no("no pole there"));
            }
            (
                Conclusion::Fails,
                vec![Checked::ZeroBetween {
                    variable: variable.clone(),
                    lo: lo.to_string(),
                    hi: hi.to_string(),
                }],
            )
        }
        F::Limit { point, .. } => limit(env, claim, &box_, point.as_deref())?,
        F::Roots { .. } => roots(env, claim, &box_)?,
        F::RootsOfParameters { multiplicities, .. } => {
            roots_of_parameters(env, claim, &box_, multiplicities)?
        }
        F::RootsAt { point, .. } => roots_at(env, claim, &box_, point)?,
        F::NotConcyclic { point, us, .. } => not_concyclic(env, claim, point, us)?,
        F::OnCircle { circle, .. } => on_circle(env, claim, circle)?,
        _ => {
            return Err(Rejection::Mismatch(
                "this fact is about another kind of claim".into(),
            ))
        }
    })
}

/// `p` with `v` moved so that it tends to 0 from above (`v = c ± s`, `v = ±1/s`, times
/// `s^m` to clear the negative powers), as (order, coefficient) of its lowest term.
fn lowest(p: &Poly, v: Var, to: &Approach) -> R<(i64, Poly)> {
    let limit = |_: super::poly::PolyError| Rejection::Eval(EvalError::Limit);
    let s = Poly::var(v);
    let moved = match to {
        Approach::At(c, side) => {
            let sign = if *side == Side::Below { -1 } else { 1 };
            let x = &Poly::constant(c.clone()) + &(&s * &Poly::constant(Rational::int(sign)));
            super::eval::substitute(p, &BTreeMap::from([(v, x)]))?
        }
        Approach::PlusInfinity | Approach::MinusInfinity => {
            // p(±1/s) = Σ c_k (±1)^k s^(−k): the lowest order is minus the degree.
            let minus = matches!(to, Approach::MinusInfinity);
            let mut out = Poly::zero();
            for (m, c) in p.terms() {
                let e = m.exponent(v);
                let c = if minus && e % 2 != 0 { -c } else { c.clone() };
                let rest = Poly::term(m.without(v), c);
                let power = Poly::term(
                    super::poly::Monomial::var(v, 1)
                        .pow(-e)
                        .ok_or(EvalError::Limit)?,
                    Rational::int(1),
                );
                out += &rest.checked_mul(&power).map_err(limit)?;
            }
            out
        }
    };
    let k = moved
        .terms()
        .map(|(m, _)| m.exponent(v))
        .min()
        .ok_or_else(|| no("the function is 0"))?;
    let coefficient = Poly::from_terms(
        moved
            .terms()
            .filter(|(m, _)| m.exponent(v) == k)
            .map(|(m, c)| (m.without(v), c.clone())),
    );
    Ok((k, coefficient))
}

fn limit(
    env: &mut Env<'_>,
    claim: &Claim,
    box_: &[(Var, Interval)],
    point: Option<&[(String, Rational)]>,
) -> R<(Conclusion, Vec<Checked>)> {
    let Claim::Limit {
        function,
        variable,
        to,
        value,
    } = claim
    else {
        return Err(Rejection::Mismatch("not a limit".into()));
    };
    let f = scalar(env, function)?;
    let v = env.free_variable(variable)?;
    let den = denominator(&f, |_| true)?;
    // Both times v^m, so that neither has a negative power of v: the quotient is the
    // same, and the moves of v apply to polynomials.
    let (num, den, lift) = lifted(&f, &den, v)?;
    // The zero function tends to 0 (read as the order 1 above the denominator's).
    let (kd, d) = lowest(&den, v, to)?;
    let (kn, n) = if num.is_zero() {
        (kd + 1, Poly::zero())
    } else {
        lowest(&num, v, to)?
    };
    let ratio = frac(Frac::from(n.clone()).div(&Frac::from(d.clone())))?;
    let side = match to {
        Approach::At(_, s) => *s,
        _ => Side::Above,
    };
    // The limit: finite (0 or n/d), or infinite with the sign of n/d (the moved
    // variable tends to 0 from above), or with both signs from both sides for an odd
    // order.
    let (found, sign_of): (Option<Frac>, Option<Frac>) = match kn.cmp(&kd) {
        std::cmp::Ordering::Greater => (Some(Frac::default()), None),
        std::cmp::Ordering::Equal => (Some(ratio.clone()), None),
        std::cmp::Ordering::Less if (kd - kn) % 2 != 0 && side == Side::Both => (None, None),
        std::cmp::Ordering::Less => (None, Some(ratio.clone())),
    };
    let claimed = match value {
        LimitValue::Finite(t) => Some(scalar(env, t)?),
        _ => None,
    };
    let p = match point {
        Some(pt) => Some(env.point(pt)?),
        None => None,
    };
    let names = &env.vars;
    let shown = |x: &Frac| super::eval::show(&x.tidied(), names);
    let mut nonzero: Vec<String> = [&d, &n][..if found.is_some() { 1 } else { 2 }]
        .iter()
        .filter(|p| p.num_terms() > 1)
        .map(|p| p.display(names))
        .collect();
    nonzero.sort();
    let value_words = match (&found, &sign_of) {
        (Some(l), _) => shown(l),
        (None, Some(s)) => format!("∞ with the sign of {}", shown(s)),
        (None, None) => "∞ in absolute value, with opposite signs on the two sides".to_owned(),
    };
    let mut said = vec![Checked::Limit {
        variable: variable.clone(),
        to: to.to_string(),
        value: value_words,
        nonzero,
    }];
    let holds = match (value, &found, &sign_of) {
        (LimitValue::Finite(_), Some(l), _) => claimed
            .as_ref()
            .map(|c| c.cleared_difference(l))
            .transpose()
            .map_err(EvalError::from)?
            .is_some_and(|d| d.is_zero()),
        (LimitValue::Unsigned, None, _) => true,
        (LimitValue::Signed(plus), None, Some(s)) => {
            let want = if *plus {
                Sign::Positive
            } else {
                Sign::Negative
            };
            match by_coefficients(s, box_, want, names) {
                Some(how) => {
                    said.push(Checked::CoefficientSigns {
                        substitution: how.substitution,
                        cases: how.cases,
                    });
                    true
                }
                None => false,
            }
        }
        _ => false,
    };
    if holds {
        // The expansion describes the limit only where its leading coefficients do
        // not vanish: the denominator's, and the numerator's for an infinite limit.
        // Each must keep one sign on the whole box (a nonzero constant, or one sign
        // of every coefficient after the orthant substitution).
        // Where a factor of the denominator free of the variable vanishes, the
        // function is undefined for every value of the variable: such points are not
        // the claim's, so only the other factors' leading coefficient must not vanish.
        // That needs a box with interior, on which such a factor cannot vanish
        // everywhere (else the claim would be about no point at all).
        let interior = box_.iter().all(|(_, i)| i.has_interior());
        let moving = denominator(&f, |g| !interior || g.variables().contains(&v))?;
        // Negative powers of the other variables are divisors free of the variable too.
        let laurent = f
            .numerator()
            .terms()
            .any(|(m, _)| m.factors().iter().any(|&(w, e)| w != v && e < 0));
        if !interior && laurent {
            return Err(no(
                "a divisor free of the variable may vanish on the whole box, which has no interior",
            ));
        }
        let moving = moving.checked_mul(&lift).map_err(|_| EvalError::Limit)?;
        let (_, d_moving) = lowest(&moving, v, to)?;
        let leading = [&d_moving, &n];
        for q in &leading[..if found.is_some() { 1 } else { 2 }] {
            if q.as_constant().is_some_and(|c| !c.is_zero()) {
                continue;
            }
            let q = Frac::from((*q).clone());
            let how = [Sign::Positive, Sign::Negative]
                .into_iter()
                .find_map(|want| by_coefficients(&q, box_, want, names))
                .ok_or_else(|| {
                    no(&format!(
                        "the expansion's leading coefficient {} is not shown nonzero on the box",
                        shown(&q)
                    ))
                })?;
            said.push(Checked::CoefficientSigns {
                substitution: how.substitution,
                cases: how.cases,
            });
        }
        return Ok((Conclusion::Holds, said));
    }
    // A refutation: at a point of the box where the expansion's coefficients are
    // nonzero, the limit found and the one stated differ.
    let p = p.ok_or_else(|| no("the limit is not the one stated, but no point shows it"))?;
    let at = |x: &Frac| x.eval(&|w| p.get(&w).cloned());
    let nonzero_at = |x: &Poly| at(&Frac::from(x.clone())).is_some_and(|x| !x.is_zero());
    if !nonzero_at(&d) || (found.is_none() && !nonzero_at(&n)) {
        return Err(no("an expansion's coefficient vanishes at the point"));
    }
    let differs = match (value, &found) {
        (LimitValue::Finite(_), Some(l)) => {
            matches!((claimed.as_ref().and_then(&at), at(l)), (Some(c), Some(l)) if c != l)
        }
        (LimitValue::Finite(_), None) | (_, Some(_)) => true,
        (LimitValue::Signed(plus), None) => match &sign_of {
            None => true,
            Some(s) => at(s).is_some_and(|x| (x.signum() > 0) != *plus),
        },
        (LimitValue::Unsigned, None) => false,
    };
    if !differs {
        return Err(no("the limit found and the one stated agree at the point"));
    }
    Ok((Conclusion::Fails, said))
}

/// The zeros of the function on the interval of its variable, against the list.
fn roots(
    env: &mut Env<'_>,
    claim: &Claim,
    box_: &[(Var, Interval)],
) -> R<(Conclusion, Vec<Checked>)> {
    let Claim::Roots {
        function,
        variable,
        roots,
        count: stated_count,
    } = claim
    else {
        return Err(Rejection::Mismatch("not a roots claim".into()));
    };
    let f = scalar(env, function)?;
    let v = env.free_variable(variable)?;
    let i = interval(box_, v);
    let (n, d, c) = univariate(&f, v, box_, env)?;
    let mut values = Vec::with_capacity(roots.len());
    for r in roots {
        let x = scalar(env, r)?;
        let x = x
            .numerator()
            .as_constant()
            .filter(|_| x.denominator().is_empty());
        values.push(x.ok_or_else(|| Rejection::Mismatch("a root that is not a number".into()))?);
    }
    let mut listed: Vec<&Rational> = values.iter().collect();
    listed.sort();
    listed.dedup();
    let (zeros, all_zeros) = tally(&n, &d.mul(&c), &i, &listed)?;
    if stated_count.is_some() && !listed.is_empty() {
        return Err(Rejection::Mismatch("a count with roots listed".into()));
    }
    let exactly = all_zeros && zeros == stated_count.unwrap_or(listed.len());
    let said = Checked::Roots {
        interval: i.describe(variable),
        roots: listed.iter().map(|x| x.to_string()).collect(),
        zeros,
        count: *stated_count,
        exactly,
    };
    Ok(if exactly {
        (Conclusion::Holds, vec![said])
    } else {
        (Conclusion::Fails, vec![said])
    })
}

/// The zeros on `i` of a function of one variable, N / D where `undefined` (D and the
/// conditions) is nonzero: how many (Sturm counts: roots of N in the open interval less
/// those shared with `undefined`, then the closed ends), and whether every listed value
/// is one of them.
fn tally(n: &Uni, undefined: &Uni, i: &Interval, listed: &[&Rational]) -> R<(usize, bool)> {
    let (a, b) = (i.lo.value(), i.hi.value());
    let common = n.gcd(undefined);
    let count = |p: &Uni| p.roots_between(a, b).ok_or_else(|| no("the function is 0"));
    let mut zeros = count(n)? - if common.is_zero() { 0 } else { count(&common)? };
    // The closed ends, once each (a one-point interval has one).
    let mut ends: Vec<&Rational> = [&i.lo, &i.hi]
        .into_iter()
        .filter_map(|e| match e {
            End::Closed(x) => Some(x),
            _ => None,
        })
        .collect();
    ends.dedup();
    for x in ends {
        if n.eval(x).is_zero() && !undefined.eval(x).is_zero() {
            zeros += 1;
        }
    }
    let all_zeros = listed
        .iter()
        .all(|x| i.contains(x) && n.eval(x).is_zero() && !undefined.eval(x).is_zero());
    Ok((zeros, all_zeros))
}

/// `f` as N / D with polynomials free of negative powers (both times the monomial that
/// clears them), and its conditions: f is N / D where D and every condition are
/// nonzero, undefined elsewhere.
fn cleared(f: &Frac) -> R<(Poly, Poly, Vec<Poly>)> {
    let den = denominator(f, |_| true)?;
    let mut low: BTreeMap<Var, super::poly::Exp> = BTreeMap::new();
    for (m, _) in f.numerator().terms().chain(den.terms()) {
        for &(w, e) in m.factors() {
            let l = low.entry(w).or_insert(0);
            *l = (*l).min(e);
        }
    }
    let lift = super::poly::Monomial::checked_from_factors(
        low.iter()
            .filter(|(_, e)| **e < 0)
            .map(|(w, e)| (*w, -e))
            .collect(),
    )
    .ok_or(EvalError::Limit)?;
    let lift = Poly::term(lift, Rational::int(1));
    let times = |p: &Poly| p.checked_mul(&lift).map_err(|_| EvalError::Limit);
    Ok((times(f.numerator())?, times(&den)?, f.conditions().to_vec()))
}

/// `p` with `v` replaced by `r`: Σ c_k r^k over the powers v^k of `p` (none negative).
fn composed(p: &Poly, v: Var, r: &Frac) -> R<Frac> {
    let mut by_power: BTreeMap<u32, Poly> = BTreeMap::new();
    for (m, c) in p.terms() {
        let k = u32::try_from(m.exponent(v)).map_err(|_| no("a negative power of the variable"))?;
        by_power
            .entry(k)
            .or_default()
            .add_term(m.without(v), c.clone());
    }
    let mut out = Frac::from(Poly::zero());
    for (k, c) in by_power {
        out = frac(out.add(&frac(Frac::from(c).mul(&frac(r.pow(k))?))?))?;
    }
    Ok(out)
}

/// The roots of a function of parameters, as rational functions of them: for every
/// value of the parameters in the box, the zeros in the variable (over the real line)
/// are exactly the roots stated. Checked as: the numerator N is Π (v − rᵢ)^mᵢ times a
/// quotient q / d with d free of v (exact division), so that its zeros are the rᵢ and
/// those of q; q (for every v), d, the rᵢ's divisors, and the function's divisor D and
/// conditions at each rᵢ keep one strict sign on the box (coefficient signs), so that
/// q has no zero, and every rᵢ is defined and a zero of the function.
fn roots_of_parameters(
    env: &mut Env<'_>,
    claim: &Claim,
    box_: &[(Var, Interval)],
    multiplicities: &[u32],
) -> R<(Conclusion, Vec<Checked>)> {
    let Claim::Roots {
        function,
        variable,
        roots,
        count: None,
    } = claim
    else {
        return Err(Rejection::Mismatch(
            "not a roots claim that lists them".into(),
        ));
    };
    let f = scalar(env, function)?.tidied();
    let v = env.free_variable(variable)?;
    if box_.iter().any(|(w, _)| *w == v) {
        return Err(no(
            "roots of parameters are decided on the whole real line only",
        ));
    }
    if multiplicities.len() != roots.len() || multiplicities.contains(&0) {
        return Err(Rejection::Mismatch("a multiplicity for each root".into()));
    }
    let mut rs = Vec::with_capacity(roots.len());
    for r in roots {
        let r = scalar(env, r)?;
        let reads_v = std::iter::once(r.numerator())
            .chain(r.denominator().iter().map(|(g, _)| g))
            .chain(r.conditions())
            .any(|p| p.variables().contains(&v));
        if reads_v {
            return Err(no("a root that depends on the variable"));
        }
        rs.push(r);
    }
    let (num, den, conds) = cleared(&f)?;
    // N = Π (v − rᵢ)^mᵢ · q / d: the roots divide the numerator (no divisor of the
    // quotient reads v), and q has one strict sign for every v (below), so that N's
    // zeros are the rᵢ and nothing else.
    let mut product = Frac::one();
    for (r, m) in rs.iter().zip(multiplicities) {
        let factor = frac(Frac::from(Poly::var(v)).sub(r))?;
        product = frac(product.mul(&frac(factor.pow(*m))?))?;
    }
    let quotient = frac(Frac::from(num).div(&product))?.tidied();
    if quotient
        .denominator()
        .iter()
        .any(|(g, _)| g.variables().contains(&v))
    {
        return Err(no("the roots do not divide the numerator"));
    }
    // A negative power of v would make the quotient no polynomial in v; one of a
    // parameter (a root b/a) is certified nonzero with the rest, since a sign by
    // coefficients says nothing where a divisor is 0.
    let negative = |p: &Poly, w: Var| p.terms().any(|(m, _)| m.exponent(w) < 0);
    if negative(quotient.numerator(), v) {
        return Err(no("the roots do not divide the numerator"));
    }
    let mut laurent: Vec<Var> = std::iter::once(quotient.numerator())
        .chain(rs.iter().map(Frac::numerator))
        .flat_map(|p| p.variables())
        .collect();
    laurent.sort_unstable();
    laurent.dedup();
    laurent.retain(|&w| {
        negative(quotient.numerator(), w) || rs.iter().any(|r| negative(r.numerator(), w))
    });
    let mut nonzero = vec![Frac::from(quotient.numerator().clone())];
    nonzero.extend(laurent.iter().map(|&w| Frac::from(Poly::var(w))));
    for (g, _) in quotient.denominator() {
        nonzero.push(Frac::from(g.clone()));
    }
    for r in &rs {
        for (g, _) in r.denominator() {
            nonzero.push(Frac::from(g.clone()));
        }
        nonzero.extend(r.conditions().iter().cloned().map(Frac::from));
        nonzero.push(composed(&den, v, r)?);
        for c in &conds {
            nonzero.push(composed(c, v, r)?);
        }
    }
    for g in &nonzero {
        let strict = [Sign::Positive, Sign::Negative]
            .into_iter()
            .any(|s| by_coefficients(g, box_, s, &env.vars).is_some());
        if !strict {
            return Err(no(&format!(
                "not certified nonzero on the box: {}",
                g.numerator().display_truncated(&env.vars, 4)
            )));
        }
    }
    Ok((
        Conclusion::Holds,
        vec![Checked::RootsOfParameters {
            variable: variable.clone(),
            roots: rs.iter().map(|r| super::eval::show(r, &env.vars)).collect(),
            multiplicities: multiplicities.to_vec(),
            nonzero: nonzero.len(),
        }],
    ))
}

/// A roots claim refuted at a point of the parameters (every one but the variable):
/// there the zeros of the function on the variable's interval (Sturm counts) are not
/// exactly the roots stated, evaluated at the point.
fn roots_at(
    env: &mut Env<'_>,
    claim: &Claim,
    box_: &[(Var, Interval)],
    point: &[(String, Rational)],
) -> R<(Conclusion, Vec<Checked>)> {
    let Claim::Roots {
        function,
        variable,
        roots,
        count,
    } = claim
    else {
        return Err(Rejection::Mismatch("not a roots claim".into()));
    };
    let v = env.free_variable(variable)?;
    let at = env.point(point)?;
    if at.contains_key(&v) {
        return Err(Rejection::Mismatch("the point fixes the variable".into()));
    }
    let f = scalar(env, function)?;
    let values: BTreeMap<Var, Poly> = at
        .iter()
        .map(|(w, x)| (*w, Poly::constant(x.clone())))
        .collect();
    let (num, den, conds) = cleared(&f)?;
    let one = |p: &Poly| -> R<Uni> {
        let p = super::eval::substitute(p, &values)?;
        Uni::of(&p, v).ok_or_else(|| no("the point leaves a parameter free"))
    };
    let mut undefined = one(&den)?;
    for c in &conds {
        undefined = undefined.mul(&one(c)?);
    }
    let n = one(&num)?;
    let mut values = Vec::with_capacity(roots.len());
    for r in roots {
        let x = scalar(env, r)?;
        values.push(
            x.eval(&|w| at.get(&w).cloned())
                .ok_or_else(|| no("a root is undefined at the point"))?,
        );
    }
    let mut listed: Vec<&Rational> = values.iter().collect();
    listed.sort();
    listed.dedup();
    let i = interval(box_, v);
    // Undefined for every value of the variable there: no zero at all.
    let (zeros, all_zeros) = if undefined.is_zero() {
        (0, listed.is_empty())
    } else {
        tally(&n, &undefined, &i, &listed)?
    };
    if all_zeros && zeros == count.unwrap_or(listed.len()) {
        return Err(no("the zeros are the roots stated at the point"));
    }
    Ok((
        Conclusion::Fails,
        vec![Checked::RootsAt {
            point: point
                .iter()
                .map(|(name, x)| format!("{name} = {x}"))
                .collect(),
            roots: listed.iter().map(|x| x.to_string()).collect(),
            zeros,
        }],
    ))
}

/// Four rational normals ((1 − u²), 2u)/(1 + u²) at a state: the points (x, y) lie on
/// no common circle or line, det[x² + y², x, y, 1] ≠ 0.
fn not_concyclic(
    env: &mut Env<'_>,
    claim: &Claim,
    point: &[(String, Rational)],
    us: &[Rational],
) -> R<(Conclusion, Vec<Checked>)> {
    let Claim::NotCircle { x, y } = claim else {
        return Err(Rejection::Mismatch("not a not-circle claim".into()));
    };
    let normal = env.normal_vars().to_vec();
    if normal.len() != 2 || us.len() != 4 {
        return Err(Rejection::Mismatch("four normals in a plane".into()));
    }
    let (fx, fy) = (scalar(env, x)?, scalar(env, y)?);
    let mut rows = Vec::new();
    for u in us {
        let one = Rational::int(1);
        let s = &(u * u) + &one;
        let n1 = (&one - &(u * u))
            .checked_div(&s)
            .ok_or_else(|| no("1 + u² = 0"))?;
        let n2 = (&Rational::int(2) * u)
            .checked_div(&s)
            .ok_or_else(|| no("1 + u² = 0"))?;
        let mut p: Vec<(String, Rational)> = point.to_vec();
        p.retain(|(name, _)| !normal.iter().any(|&w| env.vars.name(w) == name));
        p.push((env.vars.name(normal[0]).to_owned(), n1));
        p.push((env.vars.name(normal[1]).to_owned(), n2));
        let (Some(a), Some(b)) = (at(env, &fx, &p)?, at(env, &fy, &p)?) else {
            return Err(no("the locus is undefined at a normal"));
        };
        rows.push([&(&a * &a) + &(&b * &b), a, b, Rational::int(1)]);
    }
    // det by expansion over the first row's minors of 3×3.
    let det3 = |m: [[&Rational; 3]; 3]| {
        &(&(m[0][0] * &(&(m[1][1] * m[2][2]) - &(m[1][2] * m[2][1])))
            - &(m[0][1] * &(&(m[1][0] * m[2][2]) - &(m[1][2] * m[2][0]))))
            + &(m[0][2] * &(&(m[1][0] * m[2][1]) - &(m[1][1] * m[2][0])))
    };
    let mut det = Rational::zero();
    for col in 0..4 {
        let minor: Vec<[&Rational; 3]> = rows[1..]
            .iter()
            .map(|r| {
                let rest: Vec<&Rational> = (0..4).filter(|&c| c != col).map(|c| &r[c]).collect();
                [rest[0], rest[1], rest[2]]
            })
            .collect();
        let term = &rows[0][col] * &det3([minor[0], minor[1], minor[2]]);
        det = if col % 2 == 0 {
            &det + &term
        } else {
            &det - &term
        };
    }
    if det.is_zero() {
        return Err(no("the four points lie on a common circle or line"));
    }
    Ok((
        Conclusion::Holds,
        vec![Checked::NotConcyclic {
            determinant: det.to_string(),
        }],
    ))
}

/// The locus of (x, y) over the unit normal in a plane is a circle: at every state off
/// a thin set it lies on x² + y² + D x + E y + F = 0, whose radius² (D² + E²)/4 − F is
/// not identically 0, and covers it. Covering follows from x and y being polynomials in
/// n = (cos θ, sin θ), not constant on the circle: w = (x − a) + i (y − b) is then a
/// trigonometric polynomial Σ c_k e^{ikθ} of constant modulus r, and |w|² constant
/// leaves one frequency only (the product of the highest and lowest would remain), so
/// w = c_k e^{ikθ} with k ≠ 0, which runs over the whole circle.
fn on_circle(
    env: &mut Env<'_>,
    claim: &Claim,
    circle: &[Reduced; 3],
) -> R<(Conclusion, Vec<Checked>)> {
    let Claim::NotCircle { x, y } = claim else {
        return Err(Rejection::Mismatch("not a not-circle claim".into()));
    };
    let normal = env.normal_vars().to_vec();
    if normal.len() != 2 {
        return Err(Rejection::Mismatch("a normal in a plane".into()));
    }
    let reads_normal = |p: &Poly| p.variables().iter().any(|v| normal.contains(v));
    let (fx, fy) = (scalar(env, x)?, scalar(env, y)?);
    // Polynomials in n, not both constant on the circle (the reduction by n·n = 1 is
    // canonical in the plane: a term left that reads n makes the value move with it).
    let mut moves = false;
    for f in [&fx, &fy] {
        if f.denominator().iter().any(|(p, _)| reads_normal(p)) {
            return Err(no("the locus divides by the normal"));
        }
        let on_circle = f
            .numerator()
            .reduce_on_sphere(&normal)
            .map_err(|_| no("a negative power of the normal"))?;
        moves |= on_circle
            .terms()
            .any(|(m, _)| normal.iter().any(|&v| m.exponent(v) != 0));
    }
    if !moves {
        return Err(no("the locus does not move with the normal: a point"));
    }
    let mut coefficient = |(n, d): &Reduced| -> R<Frac> {
        let (n, d) = (env.poly_of(n)?, env.poly_of(d)?);
        if reads_normal(&n) || reads_normal(&d) {
            return Err(no("the circle moves with the normal"));
        }
        frac(Frac::from(n).div(&Frac::from(d)))
    };
    let [d, e, f] = [
        coefficient(&circle[0])?,
        coefficient(&circle[1])?,
        coefficient(&circle[2])?,
    ];
    // x² + y² + D x + E y + F, its numerator 0 on the circle of normals.
    let q = frac(fx.pow(2))?;
    let q = frac(q.add(&frac(fy.pow(2))?))?;
    let q = frac(q.add(&frac(d.mul(&fx))?))?;
    let q = frac(q.add(&frac(e.mul(&fy))?))?;
    let q = frac(q.add(&f))?;
    let rest = q
        .numerator()
        .reduce_on_sphere(&normal)
        .map_err(|_| no("a negative power of the normal"))?;
    if !rest.is_zero() {
        return Err(no("the locus is not on the circle"));
    }
    let quarter = Frac::constant(Rational::ratio(1, 4).ok_or(EvalError::Limit)?);
    let r2 = frac(frac(d.pow(2))?.add(&frac(e.pow(2))?))?;
    let r2 = frac(frac(r2.mul(&quarter))?.sub(&f))?;
    if r2.is_zero() {
        return Err(no("the circle has radius 0: a point"));
    }
    // Not identically 0, the radius is nonzero at generic states of a box open in each
    // parameter it reads; a box without interior in one of them could hold only states
    // where it is 0, where the locus is a point.
    let box_ = env.given_box();
    let mut read = r2.numerator().variables();
    for (p, _) in r2.denominator() {
        read.extend(p.variables());
    }
    if box_
        .iter()
        .any(|(v, i)| read.contains(v) && !i.has_interior())
    {
        return Err(no(
            "the box has no interior in a parameter the radius reads: the radius may be 0 on all of it",
        ));
    }
    let half = Frac::constant(Rational::ratio(-1, 2).ok_or(EvalError::Limit)?);
    let (cx, cy) = (frac(d.mul(&half))?, frac(e.mul(&half))?);
    Ok((
        Conclusion::Fails,
        vec![Checked::OnCircle {
            center: format!(
                "({}, {})",
                super::eval::show(&cx, &env.vars),
                super::eval::show(&cy, &env.vars)
            ),
            radius_squared: super::eval::show(&r2, &env.vars),
        }],
    ))
}
