//! The sampled route of a claim about a function of several parameters: exact values
//! at seeded rational points of the box, then an adversarial pattern search in `f64`
//! from the points closest to breaking the claim, whose end points are evaluated
//! exactly again. A violation found either way is an exact counterexample; none found
//! is sampled evidence, never a proof.

use super::context::{Context, Exact};
use crate::algebra::sign::{chart, sign_of, Interval, Sign, Violation};
use crate::algebra::sturm::UniPoly;
use crate::decide::finding::SampledSign;
use crate::decide::random::Rng;
use crate::decide::watch::{self, TimeUp};
use crate::kernel::{Rational, Var};
use std::collections::BTreeMap;

/// Pattern-search starts (the samples with the smallest margins) and steps per start.
const STARTS: usize = 4;
const STEPS: usize = 60;

pub(super) enum Sampled {
    /// The function breaks the claim here (exactly).
    Violation {
        point: BTreeMap<Var, Rational>,
    },
    Holds(SampledSign),
}

/// How far `value` is from breaking `want` (negative: broken).
fn margin(value: &Rational, want: Sign) -> Rational {
    match want {
        Sign::Positive | Sign::NonNegative => value.clone(),
        Sign::Negative | Sign::NonPositive => -value.clone(),
    }
}

/// The interval's inner point, then those of the fractions `n/d` it holds, in order:
/// the simple values a counterexample reads best at.
pub(super) fn simple_values(i: &Interval, fractions: &[(i64, i64)]) -> Vec<Rational> {
    let mut c: Vec<Rational> = fractions
        .iter()
        .map(|&(n, d)| Rational::ratio(n, d).expect("nonzero"))
        .filter(|x| i.contains(x))
        .collect();
    c.insert(0, crate::algebra::sign::inner_point(i));
    c.dedup();
    c
}

/// Every point whose coordinates take one of `values` each (the box's variables in
/// order, the first varying fastest), or none when there are more than `limit`.
pub(super) fn combinations(
    bx: &[(Var, Interval)],
    values: &[Vec<Rational>],
    limit: usize,
) -> Vec<BTreeMap<Var, Rational>> {
    let count = values
        .iter()
        .try_fold(1usize, |acc, c| acc.checked_mul(c.len()))
        .filter(|&n| n <= limit)
        .unwrap_or(0);
    (0..count)
        .map(|k| {
            let mut rest = k;
            bx.iter()
                .zip(values)
                .map(|((v, _), c)| {
                    let x = c[rest % c.len()].clone();
                    rest /= c.len();
                    (*v, x)
                })
                .collect()
        })
        .collect()
}

/// Samples `g` on the box of `vars` for the sign `want`; `Err` when the claim's time
/// limit passes between two exact evaluations (`check::decide` then makes the
/// claim undecided).
pub(super) fn search(
    cx: &Context<'_>,
    g: &Exact,
    vars: &[Var],
    want: Sign,
) -> Result<Sampled, TimeUp> {
    let bx = cx.box_on(vars);
    let mut rng = Rng::salted(cx.seed, 0x5CA1_AB1E);
    let mut excluded = 0;
    let mut kept: Vec<(Rational, BTreeMap<Var, Rational>, Rational)> = Vec::new();
    // Simple points first (small integers and halves inside the box, every
    // combination up to 64): a counterexample there reads best.
    let simple: Vec<Vec<Rational>> = bx
        .iter()
        .map(|(_, i)| simple_values(i, &[(1, 1), (-1, 1), (1, 2), (-1, 2), (2, 1), (-2, 1)]))
        .collect();
    for point in combinations(&bx, &simple, 64) {
        watch::check()?;
        if let Some(value) = g.eval(&point) {
            if !want.admits(sign_of(&value)) {
                return Ok(Sampled::Violation { point });
            }
        }
    }
    let mut drawn = 0;
    // Undefined samples are redrawn, up to four times the sample count in all.
    while kept.len() < cx.samples && drawn < 4 * cx.samples {
        drawn += 1;
        watch::check()?;
        watch::progress("samples", kept.len(), cx.samples);
        let point: BTreeMap<Var, Rational> = bx.iter().map(|(v, i)| (*v, rng.draw(i))).collect();
        let Some(value) = g.eval(&point) else {
            excluded += 1;
            continue;
        };
        if !want.admits(sign_of(&value)) {
            return Ok(Sampled::Violation { point });
        }
        kept.push((margin(&value, want), point, value));
    }
    kept.sort_by(|a, b| a.0.cmp(&b.0));
    let mut evaluations = 0;
    for (_, start, _) in kept.iter().take(STARTS).cloned().collect::<Vec<_>>() {
        watch::check()?;
        let (point, evals) = descend(g, &bx, start, want);
        evaluations += evals;
        if let Some(value) = g.eval(&point) {
            if !want.admits(sign_of(&value)) {
                return Ok(Sampled::Violation { point });
            }
            kept.push((margin(&value, want), point, value));
        }
    }
    kept.sort_by(|a, b| a.0.cmp(&b.0));
    // A strict sign can break on a set that no sample lands on: a square of a linear
    // form is zero on a plane. On the coordinate lines through the points closest to
    // breaking the claim (and through the first simple point, whose zeros read
    // best), the exact zeros of the restriction are tried too.
    if !want.admits(0) {
        let cleared = g.cleared();
        let simplest: BTreeMap<Var, Rational> = bx
            .iter()
            .zip(&simple)
            .map(|((v, _), c)| (*v, c[0].clone()))
            .collect();
        // The closest points rounded to the simplest rationals near them: a search that
        // converged to an isolated rational zero (1/3, 2/7) lands next to it, not on it.
        let rounded: Vec<BTreeMap<Var, Rational>> = kept
            .iter()
            .take(STARTS)
            .map(|(_, p, _)| {
                p.iter()
                    .map(|(v, x)| {
                        let eps = &Rational::ratio(1, 1 << 20).expect("nonzero")
                            * &(&Rational::int(1) + &abs(x));
                        let r =
                            crate::algebra::rational::simplest_between(&(x - &eps), &(x + &eps));
                        let inside = bx.iter().any(|(w, i)| w == v && i.contains(&r));
                        (*v, if inside { r } else { x.clone() })
                    })
                    .collect()
            })
            .collect();
        let bases = std::iter::once(&simplest)
            .chain(rounded.iter())
            .chain(kept.iter().take(STARTS).map(|k| &k.1));
        for start in bases {
            watch::check()?;
            if let Some(point) = zero_on_lines(g, &cleared, &bx, start, want) {
                return Ok(Sampled::Violation { point });
            }
        }
    }
    let (smallest, at) = kept
        .first()
        .map(|(_, p, v)| (super::context::readable(v), cx.shown(p)))
        .unwrap_or_else(|| ("none (every sample undefined)".to_owned(), BTreeMap::new()));
    Ok(Sampled::Holds(SampledSign {
        samples: kept.len(),
        seed: cx.seed,
        excluded,
        search_evaluations: evaluations,
        smallest_margin: smallest,
        at,
    }))
}

/// The largest degree of a restriction to a line whose roots are isolated.
const MAX_LINE_DEGREE: usize = 64;

/// A point where `g` breaks the strict sign `want` on one of the coordinate lines
/// through `point` inside the box: the rational zeros of the restriction that its sign
/// chart finds, and the root of a linear multiple factor (a zero where `g` touches 0).
/// Every candidate is evaluated exactly again; `None` when none breaks the claim.
fn zero_on_lines(
    g: &Exact,
    (num, den): &(crate::kernel::Poly, crate::kernel::Poly),
    bx: &[(Var, Interval)],
    point: &BTreeMap<Var, Rational>,
    want: Sign,
) -> Option<BTreeMap<Var, Rational>> {
    let at = |w: Var| point.get(&w).cloned().unwrap_or_else(|| Rational::int(0));
    for (v, i) in bx {
        let (Some(n), Some(d)) = (
            UniPoly::restricted(num, *v, &at),
            UniPoly::restricted(den, *v, &at),
        ) else {
            continue;
        };
        if n.degree().is_none_or(|k| k > MAX_LINE_DEGREE)
            || d.degree().is_none_or(|k| k > MAX_LINE_DEGREE)
        {
            continue;
        }
        let mut candidates = Vec::new();
        if let Some(Violation::At { x, .. }) = chart(&n, &d, i).and_then(|c| c.violation(want)) {
            candidates.push(x);
        }
        candidates.extend(n.touching_root());
        for x in candidates.into_iter().filter(|x| i.contains(x)) {
            let mut p = point.clone();
            p.insert(*v, x);
            if g.eval(&p)
                .is_some_and(|value| !want.admits(sign_of(&value)))
            {
                return Some(p);
            }
        }
    }
    None
}

/// A compass search in `f64` that lowers the margin from `start`, staying in the box;
/// the end point is returned as exact rationals (every `f64` is one).
fn descend(
    g: &Exact,
    bx: &[(Var, Interval)],
    start: BTreeMap<Var, Rational>,
    want: Sign,
) -> (BTreeMap<Var, Rational>, usize) {
    let sign = match want {
        Sign::Positive | Sign::NonNegative => 1.0,
        Sign::Negative | Sign::NonPositive => -1.0,
    };
    let vars: Vec<Var> = bx.iter().map(|(v, _)| *v).collect();
    let mut x: Vec<f64> = vars.iter().map(|v| start[v].to_f64()).collect();
    let f = |x: &[f64]| {
        let at = |v: Var| vars.iter().position(|w| *w == v).map_or(0.0, |k| x[k]);
        sign * g.f.eval_f64(&at)
    };
    let inside = |x: &[f64]| {
        bx.iter().zip(x).all(|((_, i), &t)| {
            crate::algebra::rational::from_f64_exact(t).is_some_and(|q| i.contains(&q))
        })
    };
    let mut best = f(&x);
    let mut evaluations = 1;
    let mut step: Vec<f64> = x.iter().map(|t| 0.25 * (1.0 + t.abs())).collect();
    for _ in 0..STEPS {
        let mut improved = false;
        for k in 0..x.len() {
            for dir in [1.0, -1.0] {
                let mut y = x.clone();
                y[k] += dir * step[k];
                if !inside(&y) {
                    continue;
                }
                let v = f(&y);
                evaluations += 1;
                if v.is_finite() && v < best {
                    best = v;
                    x = y;
                    improved = true;
                }
            }
        }
        if !improved {
            step.iter_mut().for_each(|s| *s *= 0.5);
        }
    }
    let point = vars
        .iter()
        .zip(&x)
        .map(|(v, t)| {
            (
                *v,
                crate::algebra::rational::from_f64_exact(*t).expect("finite"),
            )
        })
        .collect();
    (point, evaluations)
}

fn abs(x: &Rational) -> Rational {
    if x.is_negative() {
        -x.clone()
    } else {
        x.clone()
    }
}
