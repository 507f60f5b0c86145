//! The sign of a univariate rational function on an interval, decided exactly.
//!
//! `f = num / den` is continuous and nonzero between consecutive real roots
//! of `num · den`, so its sign on each such piece is its sign at any one rational point
//! of the piece. The roots are isolated by Sturm bisection ([`isolate_roots`]); every
//! piece gets the simplest rational point that is known to lie inside it. The result,
//! a [`SignChart`], is the whole sign pattern of `f` on the interval: the roots of
//! `num` (zeros), the roots of `den` (poles, where `f` is undefined), and the sign on
//! every piece between them. Sign, monotonicity and root claims are read off it.

use super::ratfunc::RatFunc;
use super::sturm::{count_roots, isolate_roots, Bound, UniPoly};
use crate::kernel::poly::{Poly, Var, VarTable};
use crate::kernel::rational::Rational;
use num_traits::Zero;

pub use crate::kernel::statement::{End, Interval, Sign};

/// A real number known exactly: a rational, or the only root of a known polynomial
/// in the open interval (lo, hi) with rational ends.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Real {
    Exact(Rational),
    Isolated { lo: Rational, hi: Rational },
}

impl Real {
    pub fn approx(&self) -> f64 {
        match self {
            Real::Exact(x) => x.to_f64(),
            Real::Isolated { lo, hi } => 0.5 * (lo.to_f64() + hi.to_f64()),
        }
    }
}

/// A root of `num · den` inside the interval.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Cut {
    pub at: Real,
    /// A root of `den`: `f` is undefined there. Otherwise a root of `num`: `f = 0`.
    pub pole: bool,
}

/// The open piece between two consecutive cuts (or an end of the interval).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Piece {
    /// A rational point inside the piece, and the exact value of `f` there.
    pub sample: Rational,
    pub value: Rational,
}

impl Piece {
    pub fn sign(&self) -> i32 {
        sign_of(&self.value)
    }
}

/// A closed finite end of the interval and the value of `f` there (`None`: a pole).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct EndValue {
    pub at: Rational,
    pub value: Option<Rational>,
}

/// The sign pattern of `num / den` on an interval: `pieces[k]` lies between `cuts[k-1]`
/// and `cuts[k]` (so there is one more piece than cuts, and none on a one-point
/// interval), with the closed ends apart.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SignChart {
    pub cuts: Vec<Cut>,
    pub pieces: Vec<Piece>,
    pub ends: Vec<EndValue>,
}

pub fn sign_of(x: &Rational) -> i32 {
    if x.is_zero() {
        0
    } else if x.is_negative() {
        -1
    } else {
        1
    }
}

/// How tightly an irrational cut is isolated: 2⁻⁴⁰ (about 1e-12), enough for ten
/// significant digits in a report.
fn isolation_width() -> Rational {
    Rational::ratio(1, 1 << 40).expect("nonzero")
}

/// The sign chart of `num / den` on `interval`. A common root of `num` and `den` is a
/// pole: a point where the expression is undefined. `None` for a zero denominator, an
/// empty interval, or roots that the bisection could not isolate (see
/// [`isolate_roots`]).
pub fn chart(num: &UniPoly, den: &UniPoly, interval: &Interval) -> Option<SignChart> {
    if den.is_zero() || interval.is_empty() {
        return None;
    }
    let value = |x: &Rational| {
        let d = den.eval(x);
        (!d.is_zero()).then(|| num.eval(x).checked_div(&d).expect("nonzero"))
    };
    let product = num.mul(den);
    let mut ends: Vec<EndValue> = [&interval.lo, &interval.hi]
        .into_iter()
        .filter_map(|e| match e {
            End::Closed(x) => Some(EndValue {
                at: x.clone(),
                value: value(x),
            }),
            _ => None,
        })
        .collect();
    // A one-point interval has one end.
    ends.dedup_by(|a, b| a.at == b.at);
    if product.is_zero() {
        // f = 0 everywhere: one piece, sampled anywhere inside.
        let sample = inner_point(interval);
        return Some(SignChart {
            cuts: Vec::new(),
            pieces: vec![Piece {
                value: Rational::zero(),
                sample,
            }],
            ends,
        });
    }
    // Finite ends for the bisection: the interval's own, or the root bound, beyond
    // which `num · den` has no root. Roots at a finite end are the ends' business.
    let bound = product.root_bound();
    let a = interval
        .lo
        .value()
        .cloned()
        .unwrap_or_else(|| -bound.clone());
    let b = interval.hi.value().cloned().unwrap_or(bound);
    if a == b {
        // One point: no open piece; the point is a closed end (`ends`).
        return Some(SignChart {
            cuts: Vec::new(),
            pieces: Vec::new(),
            ends,
        });
    }
    let inner = product.without_root_at(&a).without_root_at(&b);
    // A rational root is usually the simplest rational of its isolating interval:
    // kept exactly when it is.
    let isolated = isolate_roots(&inner, &a, &b, &isolation_width())?
        .into_iter()
        .map(|(lo, hi)| {
            if lo == hi {
                return (lo, hi);
            }
            let s = crate::rational::simplest_between(&lo, &hi);
            if inner.eval(&s).is_zero() {
                (s.clone(), s)
            } else {
                (lo, hi)
            }
        });
    let cuts: Vec<Cut> = isolated
        .map(|(lo, hi)| {
            if lo == hi {
                Cut {
                    pole: den.eval(&lo).is_zero(),
                    at: Real::Exact(lo),
                }
            } else {
                // `lo` is no root of `num · den`, so not of `den`: the count is sound.
                let poles = count_roots(den, &Bound::At(lo.clone()), &Bound::At(hi.clone()));
                Cut {
                    at: Real::Isolated { lo, hi },
                    pole: poles > 0,
                }
            }
        })
        .collect();
    // Piece k lies between cut k−1 and cut k. Its known inside: from the upper end of
    // cut k−1's isolating interval (no root, and above the root) or from the exact
    // root (excluded), up to the lower end of cut k's (or the exact root).
    let mut pieces = Vec::with_capacity(cuts.len() + 1);
    for k in 0..=cuts.len() {
        let (left, left_in) = match k.checked_sub(1).map(|j| &cuts[j].at) {
            None => (a.clone(), false),
            Some(Real::Exact(r)) => (r.clone(), false),
            Some(Real::Isolated { hi, .. }) => (hi.clone(), true),
        };
        let (right, right_in) = match cuts.get(k).map(|c| &c.at) {
            None => (b.clone(), false),
            Some(Real::Exact(r)) => (r.clone(), false),
            Some(Real::Isolated { lo, .. }) => (lo.clone(), true),
        };
        let sample = if left < right {
            crate::rational::simplest_between(&left, &right)
        } else {
            // Two isolating intervals that share an end: that end is inside.
            debug_assert!(left == right && left_in && right_in);
            left
        };
        let value = value(&sample).expect("a piece holds no root of den");
        pieces.push(Piece { sample, value });
    }
    Some(SignChart { cuts, pieces, ends })
}

/// The sign chart of `num / den`, polynomials in `v` alone; `None` when another
/// variable occurs, the interval is empty, or the roots could not be isolated.
pub fn chart_of((num, den): (&Poly, &Poly), v: Var, interval: &Interval) -> Option<SignChart> {
    let num = UniPoly::from_poly(num, v)?;
    let den = UniPoly::from_poly(den, v)?;
    chart(&num, &den, interval)
}

/// One case of [`orthant_cases`]: the moved function and the variables whose t = 0 lies
/// in the domain.
pub type OrthantCase = (RatFunc, Vec<Var>);

/// The most cases [`orthant_cases`] enumerates: two per unbounded variable.
const MAX_CASES: usize = 64;

/// `f` with every variable moved onto t ≥ 0 (the same name standing for t): one
/// function per case, with the variables whose t = 0 lies in the domain, and the
/// substitution in words. `None` when a variable's interval is closed at both finite
/// ends (no single map from t ≥ 0 covers it) or there are too many cases.
pub fn orthant_cases(
    f: &RatFunc,
    domain: &[(Var, Interval)],
    names: &VarTable,
) -> Option<(Vec<OrthantCase>, String)> {
    let mut vars: Vec<Var> = f.numerator().variables();
    vars.extend(f.denominator().variables());
    vars.sort_unstable();
    vars.dedup();
    let whole = Interval::real_line();
    let t = |v: Var| RatFunc::var(v);
    let c = |x: &Rational| RatFunc::constant(x.clone());
    let one = RatFunc::int(1);
    // Per variable: its alternatives (value in t, t = 0 inside the domain).
    let mut per_var: Vec<(Var, Vec<(RatFunc, bool)>)> = Vec::new();
    let mut words = Vec::new();
    for &v in &vars {
        let i = domain
            .iter()
            .find(|(w, _)| *w == v)
            .map_or(&whole, |(_, i)| i);
        let name = names.name(v);
        let closed_lo = matches!(i.lo, End::Closed(_));
        let closed_hi = matches!(i.hi, End::Closed(_));
        let alternatives = match (i.lo.value(), i.hi.value()) {
            (None, None) => {
                words.push(format!("{name} = ±t"));
                vec![(t(v), true), (-&t(v), true)]
            }
            (Some(a), None) => {
                words.push(if a.is_zero() {
                    format!("{name} = t")
                } else {
                    format!("{name} = {a} + t")
                });
                vec![(&c(a) + &t(v), closed_lo)]
            }
            (None, Some(b)) => {
                words.push(if b.is_zero() {
                    format!("{name} = −t")
                } else {
                    format!("{name} = {b} − t")
                });
                vec![(&c(b) - &t(v), closed_hi)]
            }
            (Some(a), Some(b)) if !closed_hi => {
                words.push(format!("{name} = ({a} + {b} t)/(1 + t)"));
                let value = (&(&c(a) + &(&c(b) * &t(v))) / &(&one + &t(v)))?;
                vec![(value, closed_lo)]
            }
            (Some(a), Some(b)) if !closed_lo => {
                words.push(format!("{name} = ({b} + {a} t)/(1 + t)"));
                let value = (&(&c(b) + &(&c(a) * &t(v))) / &(&one + &t(v)))?;
                vec![(value, true)]
            }
            _ => return None,
        };
        per_var.push((v, alternatives));
    }
    let count = per_var
        .iter()
        .try_fold(1usize, |acc, (_, a)| acc.checked_mul(a.len()))?;
    if count > MAX_CASES {
        return None;
    }
    let mut cases = vec![(f.clone(), Vec::new())];
    for (v, alternatives) in &per_var {
        let mut next = Vec::new();
        for (g, closed) in &cases {
            for (value, at_zero) in alternatives {
                let mut closed = closed.clone();
                if *at_zero {
                    closed.push(*v);
                }
                next.push((g.substitute(*v, value)?, closed));
            }
        }
        cases = next;
    }
    // No variable: the text is empty and the report says "constants of one sign".
    let words = if words.is_empty() {
        String::new()
    } else {
        format!("{}, t ≥ 0", words.join(", "))
    };
    Some((cases, words))
}

/// A polynomial whose coefficients all have one sign.
pub struct CoefficientSign {
    /// 1 or −1.
    pub sign: i32,
    /// Some term has none of the variables that may be 0: the polynomial is nonzero
    /// on the whole closed orthant part of the domain, not only inside it.
    pub nonzero_on_closed: bool,
}

/// The common sign of `p`'s coefficients, or `None` when they differ or `p = 0`.
pub fn coefficient_sign(p: &Poly, closed: &[Var]) -> Option<CoefficientSign> {
    let mut sign = 0;
    let mut nonzero_on_closed = false;
    for (m, c) in p.terms() {
        let s = sign_of(c);
        if sign != 0 && s != sign {
            return None;
        }
        sign = s;
        nonzero_on_closed |= m.factors().iter().all(|(v, _)| !closed.contains(v));
    }
    (sign != 0).then_some(CoefficientSign {
        sign,
        nonzero_on_closed,
    })
}

/// A point strictly inside a nonempty interval (the closed point when it is one).
pub fn inner_point(i: &Interval) -> Rational {
    match (i.lo.value(), i.hi.value()) {
        (Some(a), Some(b)) if a == b => a.clone(),
        (Some(a), Some(b)) => crate::rational::simplest_between(a, b),
        (Some(a), None) => crate::rational::simplest_between(a, &(a + &Rational::int(2))),
        (None, Some(b)) => crate::rational::simplest_between(&(b - &Rational::int(2)), b),
        (None, None) => Rational::zero(),
    }
}

/// Where a sign claim fails on a chart.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Violation {
    /// `f` has the wrong sign (or is zero where a strict sign is claimed) at a
    /// rational point of the interval.
    At { x: Rational, value: Rational },
    /// `f = 0` at an irrational root of `num` in (lo, hi), where a strict sign is claimed.
    Zero { lo: Rational, hi: Rational },
}

impl SignChart {
    /// The first place where `f` breaks `want`, or `None` when `f` satisfies it on the
    /// whole interval wherever it is defined.
    pub fn violation(&self, want: Sign) -> Option<Violation> {
        for e in &self.ends {
            if let Some(v) = &e.value {
                if !want.admits(sign_of(v)) {
                    return Some(Violation::At {
                        x: e.at.clone(),
                        value: v.clone(),
                    });
                }
            }
        }
        for p in &self.pieces {
            if !want.admits(p.sign()) {
                return Some(Violation::At {
                    x: p.sample.clone(),
                    value: p.value.clone(),
                });
            }
        }
        // A zero of `num` inside breaks a strict sign.
        if !want.admits(0) {
            if let Some(c) = self.cuts.iter().find(|c| !c.pole) {
                return Some(match &c.at {
                    Real::Exact(x) => Violation::At {
                        x: x.clone(),
                        value: Rational::zero(),
                    },
                    Real::Isolated { lo, hi } => Violation::Zero {
                        lo: lo.clone(),
                        hi: hi.clone(),
                    },
                });
            }
        }
        None
    }

    /// The zeros of `f` in the interval, in increasing order: closed ends where it is
    /// 0 and roots of the numerator inside that are not poles.
    pub fn zeros(&self) -> Vec<Real> {
        let mut out: Vec<Real> = self
            .cuts
            .iter()
            .filter(|c| !c.pole)
            .map(|c| c.at.clone())
            .collect();
        for e in &self.ends {
            if e.value.as_ref().is_some_and(Rational::is_zero) {
                out.push(Real::Exact(e.at.clone()));
            }
        }
        out.sort_by(|a, b| a.approx().total_cmp(&b.approx()));
        out
    }

    /// The number of poles inside the interval and at its closed ends.
    pub fn poles(&self) -> usize {
        self.cuts.iter().filter(|c| c.pole).count()
            + self.ends.iter().filter(|e| e.value.is_none()).count()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn up(c: &[i64]) -> UniPoly {
        UniPoly::new(c.iter().map(|&k| Rational::int(k)).collect())
    }

    fn q(n: i64, d: i64) -> Rational {
        Rational::ratio(n, d).unwrap()
    }

    fn open_from(a: i64) -> Interval {
        Interval {
            lo: End::Open(Rational::int(a)),
            hi: End::Unbounded,
        }
    }

    #[test]
    fn positive_function_holds_on_the_line() {
        // (x² + 1) / (x² + 2)
        let c = chart(&up(&[1, 0, 1]), &up(&[2, 0, 1]), &Interval::real_line()).unwrap();
        assert!(c.cuts.is_empty());
        assert_eq!(c.violation(Sign::Positive), None);
        assert!(c.violation(Sign::Negative).is_some());
    }

    #[test]
    fn sign_change_gives_a_rational_counterexample() {
        // x − 2 on x > 0: negative on (0, 2).
        let c = chart(&up(&[-2, 1]), &up(&[1]), &open_from(0)).unwrap();
        assert_eq!(c.cuts.len(), 1);
        assert_eq!(c.cuts[0].at, Real::Exact(Rational::int(2)));
        match c.violation(Sign::Positive) {
            Some(Violation::At { x, value }) => {
                assert!(x > Rational::int(0) && x < Rational::int(2));
                assert!(value.is_negative());
            }
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn double_irrational_root_breaks_only_a_strict_sign() {
        // (x² − 2)² ≥ 0 everywhere, = 0 at ±√2: no rational counterexample exists.
        let p = up(&[4, 0, -4, 0, 1]);
        let c = chart(&p, &up(&[1]), &Interval::real_line()).unwrap();
        assert_eq!(c.violation(Sign::NonNegative), None);
        match c.violation(Sign::Positive) {
            Some(Violation::Zero { lo, hi }) => {
                let r = -(2f64.sqrt());
                assert!(lo.to_f64() < r && r < hi.to_f64());
            }
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn poles_are_excluded_not_violations() {
        // 1 / (x − 1)² > 0 wherever defined; 1/(x − 1) is negative left of its pole.
        let c = chart(&up(&[1]), &up(&[1, -2, 1]), &open_from(0)).unwrap();
        assert_eq!(c.poles(), 1);
        assert_eq!(c.violation(Sign::Positive), None);
        let c = chart(&up(&[1]), &up(&[-1, 1]), &open_from(0)).unwrap();
        assert!(matches!(
            c.violation(Sign::Positive),
            Some(Violation::At { .. })
        ));
    }

    #[test]
    fn closed_ends_are_evaluated() {
        // x on [0, 1]: ≥ 0 holds, > 0 fails at 0; on (0, 1] both hold.
        let closed = Interval {
            lo: End::Closed(Rational::int(0)),
            hi: End::Closed(Rational::int(1)),
        };
        let c = chart(&up(&[0, 1]), &up(&[1]), &closed).unwrap();
        assert_eq!(c.violation(Sign::NonNegative), None);
        assert_eq!(
            c.violation(Sign::Positive),
            Some(Violation::At {
                x: Rational::int(0),
                value: Rational::int(0)
            })
        );
        let half_open = Interval {
            lo: End::Open(Rational::int(0)),
            hi: End::Closed(Rational::int(1)),
        };
        let c = chart(&up(&[0, 1]), &up(&[1]), &half_open).unwrap();
        assert_eq!(c.violation(Sign::Positive), None);
    }

    #[test]
    fn close_roots_are_all_separated() {
        // (x − 1/3)(x − 1/3 − 1e-9)(x − 1/2): three roots, two of them 1e-9 apart, the
        // middle midpoint of [0, 1] exactly a root.
        let r1 = q(1, 3);
        let r2 = &r1 + &q(1, 1_000_000_000);
        let lin = |r: &Rational| UniPoly::new(vec![-r.clone(), Rational::int(1)]);
        let p = lin(&r1).mul(&lin(&r2)).mul(&lin(&q(1, 2)));
        let unit = Interval {
            lo: End::Open(Rational::int(0)),
            hi: End::Open(Rational::int(1)),
        };
        let c = chart(&p, &up(&[1]), &unit).unwrap();
        assert_eq!(c.cuts.len(), 3);
        let signs: Vec<i32> = c.pieces.iter().map(Piece::sign).collect();
        assert_eq!(signs, vec![-1, 1, -1, 1]);
    }

    /// The chart agrees with dense floating-point sampling for many random rational
    /// functions: every piece's sign is the sign of f at points between the cuts.
    #[test]
    fn chart_agrees_with_dense_sampling() {
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = |m: i64| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state % (2 * m as u64 + 1)) as i64 - m
        };
        for _ in 0..200 {
            let num = up(&(0..4).map(|_| next(5)).collect::<Vec<_>>());
            let den = up(&[next(3).abs() + 1, next(3), next(1)]);
            if num.is_zero() || den.is_zero() {
                continue;
            }
            let Some(c) = chart(&num, &den, &Interval::real_line()) else {
                continue;
            };
            let f = |x: f64| {
                let ev = |p: &UniPoly| {
                    p.coefficients()
                        .iter()
                        .rev()
                        .fold(0.0, |acc, k| acc * x + k.to_f64())
                };
                ev(&num) / ev(&den)
            };
            // Between consecutive cuts, away from them, f has the piece's sign.
            let cuts: Vec<f64> = c.cuts.iter().map(|k| k.at.approx()).collect();
            for (k, piece) in c.pieces.iter().enumerate() {
                let lo = if k == 0 { -50.0 } else { cuts[k - 1] };
                let hi = if k == cuts.len() { 50.0 } else { cuts[k] };
                for t in 1..20 {
                    let x = lo + (hi - lo) * f64::from(t) / 20.0;
                    let v = f(x);
                    if v.abs() > 1e-6 {
                        assert_eq!(v.signum() as i32, piece.sign(), "{num:?}/{den:?} at {x}");
                    }
                }
            }
        }
    }
}
