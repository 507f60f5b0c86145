//! Signs of rational functions on a box of parameter values, decided from
//! coefficients: after every variable is moved onto t ≥ 0 (v = a + t, v = b − t,
//! v = ±t, or v = (a + b t)/(1 + t) for a bounded end), a polynomial whose
//! coefficients all have one sign has that sign at every point of the open orthant,
//! and is nonzero on its closed part when one of its monomials avoids every variable
//! whose t = 0 lies in the box.

use super::frac::Frac;
use super::poly::{Monomial, Poly, Var, VarTable};
use super::rational::Rational;
use super::statement::{End, Interval, Sign};
use num_traits::{One, Zero};

/// The most cases (two per variable unbounded on both sides) a certificate takes.
const MAX_CASES: usize = 64;

/// The highest degree in one variable that is moved (a bound on the work).
const MAX_DEGREE: super::poly::Exp = 1_000;

/// One variable's ways onto t ≥ 0: its value as `(a + b t) / (1 + c t)` with c = 0
/// or 1, and whether t = 0 lies in the box.
struct Move {
    v: Var,
    a: Rational,
    b: Rational,
    bounded: bool,
    at_zero: bool,
}

/// The moves of `v` on interval `i`; two for an interval closed at both finite ends,
/// which no single map from t ≥ 0 covers; `None` for an empty one.
fn moves(v: Var, i: &Interval) -> Option<Vec<Move>> {
    let closed = |e: &End| matches!(e, End::Closed(_));
    let one = Rational::one;
    let mv = |a: Rational, b: Rational, bounded, at_zero| Move {
        v,
        a,
        b,
        bounded,
        at_zero,
    };
    if i.is_empty() {
        return None;
    }
    Some(match (i.lo.value(), i.hi.value()) {
        (None, None) => vec![
            mv(Rational::zero(), one(), false, true),
            mv(Rational::zero(), -&one(), false, true),
        ],
        (Some(a), None) => vec![mv(a.clone(), one(), false, closed(&i.lo))],
        (None, Some(b)) => vec![mv(b.clone(), -&one(), false, closed(&i.hi))],
        (Some(a), Some(b)) if !closed(&i.hi) => vec![mv(a.clone(), b.clone(), true, closed(&i.lo))],
        (Some(a), Some(b)) if !closed(&i.lo) => vec![mv(b.clone(), a.clone(), true, true)],
        // [a, b] is [a, b) and the point b (the move (b + b t)/(1 + t) = b).
        (Some(a), Some(b)) => vec![
            mv(a.clone(), b.clone(), true, true),
            mv(b.clone(), b.clone(), true, true),
        ],
    })
}

/// `p` with `v` replaced by its move, times (1 + t)^deg for a bounded one (positive
/// for t ≥ 0, so no sign changes). `p` has no negative power of `v`.
fn apply(p: &Poly, m: &Move) -> Poly {
    let deg = p
        .terms()
        .map(|(mono, _)| mono.exponent(m.v))
        .max()
        .unwrap_or(0)
        .max(0) as u32;
    let t = Poly::var(m.v);
    let num = &Poly::constant(m.a.clone()) + &(&Poly::constant(m.b.clone()) * &t);
    let den = &Poly::one() + &t;
    let mut out = Poly::zero();
    for (mono, c) in p.terms() {
        let e = mono.exponent(m.v).max(0) as u32;
        let rest = Poly::term(mono.without(m.v), c.clone());
        let mut term = &rest * &num.pow(e);
        if m.bounded {
            term = &term * &den.pow(deg - e);
        }
        out += &term;
    }
    out
}

/// The common sign of `p`'s coefficients (±1), and whether `p` is nonzero wherever
/// every variable outside `closed` is positive; `None` when the signs differ or p = 0.
fn coefficient_sign(p: &Poly, closed: &[Var]) -> Option<(i32, bool)> {
    let mut sign = 0;
    let mut nonzero = false;
    for (m, c) in p.terms() {
        let s = if c.is_negative() { -1 } else { 1 };
        if sign != 0 && s != sign {
            return None;
        }
        sign = s;
        nonzero |= m.factors().iter().all(|(v, _)| !closed.contains(v));
    }
    (sign != 0).then_some((sign, nonzero))
}

/// A sign certified by coefficients: the substitution in words (empty for
/// constants) and the number of cases.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ByCoefficients {
    pub substitution: String,
    pub cases: usize,
}

/// The move of a variable in words: `x = t`, `x = 1/2 + t`, `x = ±t`, …
fn words(name: &str, i: &Interval) -> String {
    match (i.lo.value(), i.hi.value()) {
        (None, None) => format!("{name} = ±t"),
        (Some(a), None) if a.is_zero() => format!("{name} = t"),
        (Some(a), None) => format!("{name} = {a} + t"),
        (None, Some(b)) if b.is_zero() => format!("{name} = −t"),
        (None, Some(b)) => format!("{name} = {b} − t"),
        (Some(a), Some(b)) if !matches!(i.hi, End::Closed(_)) => {
            format!("{name} = ({a} + {b} t)/(1 + t)")
        }
        (Some(a), Some(b)) if !matches!(i.lo, End::Closed(_)) => {
            format!("{name} = ({b} + {a} t)/(1 + t)")
        }
        (Some(a), Some(b)) => format!("{name} = ({a} + {b} t)/(1 + t) or {name} = {b}"),
    }
}

/// Whether `f` has the sign `want` at every point of the box where it is defined
/// (variables not in the box range over the real line), by coefficients: how, or
/// `None`, which says nothing about `f`.
pub fn by_coefficients(
    f: &Frac,
    box_: &[(Var, Interval)],
    want: Sign,
    names: &VarTable,
) -> Option<ByCoefficients> {
    let holds = |substitution: String, cases: usize| {
        Some(ByCoefficients {
            substitution,
            cases,
        })
    };
    let mut num = f.numerator().clone();
    if num.is_zero() {
        return if want.admits(0) {
            holds(String::new(), 1)
        } else {
            None
        };
    }
    let mut den = Poly::one();
    for (g, k) in f.denominator() {
        // Bounded before it is expanded: a power past the degree limit is refused.
        let degree = g
            .terms()
            .flat_map(|(m, _)| m.factors().iter().map(|&(_, e)| e.unsigned_abs()))
            .max()
            .unwrap_or(0);
        if degree.saturating_mul(u64::from(*k)) > MAX_DEGREE.unsigned_abs() {
            return None;
        }
        den = den.checked_mul(&g.checked_pow(*k).ok()?).ok()?;
    }
    // Both times one monomial, so that no negative power is left: the quotient and the
    // product of their signs are unchanged.
    let mut vars = num.variables();
    vars.extend(den.variables());
    vars.sort_unstable();
    vars.dedup();
    let lowest: Vec<(Var, super::poly::Exp)> = vars
        .iter()
        .map(|&v| {
            let low = num
                .terms()
                .chain(den.terms())
                .map(|(m, _)| m.exponent(v))
                .min()
                .unwrap_or(0);
            (v, (-low).max(0))
        })
        .collect();
    let lift = Monomial::checked_from_factors(lowest)?;
    let lift = Poly::term(lift, Rational::one());
    let (Ok(n), Ok(d)) = (num.checked_mul(&lift), den.checked_mul(&lift)) else {
        return None;
    };
    num = n;
    den = d;
    let too_high = num
        .terms()
        .chain(den.terms())
        .any(|(m, _)| m.factors().iter().any(|&(_, e)| e > MAX_DEGREE));
    if too_high {
        return None;
    }
    let whole = Interval::real_line();
    let mut per_var = Vec::new();
    let mut said = Vec::new();
    for &v in &vars {
        let i = box_
            .iter()
            .find(|(w, _)| *w == v)
            .map_or(&whole, |(_, i)| i);
        per_var.push(moves(v, i)?);
        said.push(words(names.name(v), i));
    }
    let count = per_var
        .iter()
        .try_fold(1usize, |acc, m| acc.checked_mul(m.len()))?;
    if count > MAX_CASES {
        return None;
    }
    let mut cases: Vec<(Poly, Poly, Vec<Var>)> = vec![(num, den, Vec::new())];
    for alternatives in &per_var {
        let mut next = Vec::new();
        for (n, d, closed) in &cases {
            for m in alternatives {
                let mut closed = closed.clone();
                if m.at_zero {
                    closed.push(m.v);
                }
                next.push((apply(n, m), apply(d, m), closed));
            }
        }
        cases = next;
    }
    let all = cases.iter().all(|(n, d, closed)| {
        // A case that is one point (a closed end) may give 0, or leave f undefined.
        if d.is_zero() {
            return true;
        }
        if n.is_zero() {
            return want.admits(0);
        }
        match (coefficient_sign(n, closed), coefficient_sign(d, closed)) {
            (Some((sn, nonzero)), Some((sd, _))) => {
                want.admits(sn * sd) && (want.admits(0) || nonzero)
            }
            _ => false,
        }
    });
    let substitution = if said.is_empty() {
        String::new()
    } else {
        format!("{}, t ≥ 0", said.join(", "))
    };
    if all {
        holds(substitution, count)
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::VarTable;

    fn q(n: i64, d: i64) -> Rational {
        Rational::ratio(n, d).unwrap()
    }

    fn by_c(f: &Frac, b: &[(Var, Interval)], want: Sign) -> bool {
        let mut names = VarTable::new();
        for n in ["x", "y"] {
            names.intern(n);
        }
        by_coefficients(f, b, want, &names).is_some()
    }

    #[test]
    fn signs_on_boxes() {
        let mut names = VarTable::new();
        let (x, y) = (names.intern("x"), names.intern("y"));
        let (px, py) = (Poly::var(x), Poly::var(y));
        let positive = Interval {
            lo: End::Open(q(0, 1)),
            hi: End::Unbounded,
        };
        let unit = Interval {
            lo: End::Open(q(0, 1)),
            hi: End::Open(q(1, 1)),
        };
        // x² + y² ≥ 0 everywhere, not > 0 (it is 0 at the origin).
        let sq = Frac::from(&(&px * &px) + &(&py * &py));
        assert!(by_c(&sq, &[], Sign::NonNegative));
        assert!(!by_c(&sq, &[], Sign::Positive));
        // x y > 0 on x, y > 0, and not on x > 0 alone.
        let xy = Frac::from(&px * &py);
        assert!(by_c(
            &xy,
            &[(x, positive.clone()), (y, positive.clone())],
            Sign::Positive
        ));
        assert!(!by_c(&xy, &[(x, positive.clone())], Sign::NonNegative));
        // 1 − x > 0 on (0, 1): (1 + t)(1 − t/(1+t))... = 1 after the move.
        let one_minus = Frac::from(&Poly::one() - &px);
        assert!(by_c(&one_minus, &[(x, unit.clone())], Sign::Positive));
        // x − 1/2 changes sign on (0, 1).
        let half = Frac::from(&px - &Poly::constant(q(1, 2)));
        assert!(!by_c(&half, &[(x, unit.clone())], Sign::NonNegative));
        assert!(!by_c(&half, &[(x, unit)], Sign::NonPositive));
        // y / x with x⁻¹ a negative power: positive on the positive quadrant.
        let over = Frac::from(Poly::term(
            Monomial::from_factors(vec![(x, -1), (y, 1)]),
            q(1, 1),
        ));
        assert!(by_c(
            &over,
            &[(x, positive.clone()), (y, positive)],
            Sign::Positive
        ));
        // On the closed [1, 2], both ends included: x > 0 and 2 − x ≥ 0, but not
        // 2 − x > 0 (0 at x = 2) nor x − 1 > 0 (0 at x = 1).
        let closed = Interval {
            lo: End::Closed(q(1, 1)),
            hi: End::Closed(q(2, 1)),
        };
        let on = |f: &Poly, want| by_c(&Frac::from(f.clone()), &[(x, closed.clone())], want);
        assert!(on(&px, Sign::Positive));
        let two_minus = &Poly::constant(q(2, 1)) - &px;
        assert!(on(&two_minus, Sign::NonNegative));
        assert!(!on(&two_minus, Sign::Positive));
        assert!(!on(&(&px - &Poly::one()), Sign::Positive));
        assert!(on(&(&px - &Poly::one()), Sign::NonNegative));
        // The zero function is ≥ 0, not > 0.
        assert!(by_c(&Frac::default(), &[], Sign::NonNegative));
        assert!(!by_c(&Frac::default(), &[], Sign::Positive));
    }
}
