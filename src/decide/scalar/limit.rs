//! `strategy = "limit"`: a function tends to a stated value (or to ±∞) as one
//! parameter tends to a point or to ±∞, the other parameters kept as symbols.
//!
//! The search reads the limit off the lowest orders (`algebra::limit`) and the kernel
//! checks it (`kernel::scalar`); the sign of an
//! infinite limit is a sign claim on the box. A refuted limit is confirmed by the
//! interpreter: near the point, the function must be closer to the limit found than
//! to the one stated.

use super::context::{Context, Exact, Stop};
use super::sign::{decide_function, with_evidence, Decided};
use crate::algebra::certificate::Certificate;
use crate::algebra::limit::{self as klimit, Approach, Limit, Side};
use crate::algebra::sign::{inner_point, Sign};
use crate::decide::finding::Finding;
use crate::decide::outcome::{Counterexample, Method, Outcome, Reverified};
use crate::derivation::{Expression, LimitValue};
use crate::kernel::check::Fact;
use crate::kernel::{Rational, Var};
use std::collections::BTreeMap;

pub(super) fn decide(
    cx: &mut Context<'_>,
    function: &Expression,
    variable: &str,
    to: &Approach,
    value: &LimitValue,
) -> Result<Outcome, Stop> {
    let f = cx.exact(function)?;
    let v = cx
        .var(variable)
        .unwrap_or_else(|| cx.env.vars.intern(variable));
    let names = &cx.env.vars;
    let found = klimit::expand(&f.f, v, to);
    let mut evidence = cx.evidence(&f.f);
    evidence.decided = format!("{} = {}", function.text, evidence.decided);
    evidence.limit = found.as_ref().map(|e| describe(&e.limit, cx));
    let plus = match value {
        LimitValue::Signed(p) => Some(*p),
        _ => None,
    };
    let refuted = |cx: &Context<'_>, claimed: Option<&Exact>| {
        let found = found.as_ref().map(|e| &e.limit);
        refutation(cx, (function, &f), v, to, found, (claimed, plus))
    };
    match value {
        LimitValue::Finite(e) => {
            let claimed = cx.exact(e)?;
            if claimed.variables().contains(&v) {
                return Err(Stop::Input(
                    e.origin
                        .diagnostic(e.node.span, format!("the stated limit depends on `{variable}`, the parameter that tends"))
                        .with_help("a limit is a function of the other parameters only"),
                ));
            }
            let names = &cx.env.vars;
            Ok(match Certificate::limit(&f.f, v, to, &claimed.f, names) {
                Ok(_) => with_evidence(cx.by_kernel(kernel_limit(cx, None), None), evidence),
                Err(_) => with_evidence(refuted(cx, Some(&claimed)), evidence),
            })
        }
        LimitValue::Unsigned | LimitValue::Signed(_) => {
            let Ok((_, sign_of)) = Certificate::diverges(&f.f, v, to, names) else {
                return Ok(with_evidence(refuted(cx, None), evidence));
            };
            let Some(plus) = plus else {
                return Ok(with_evidence(
                    cx.by_kernel(kernel_limit(cx, None), None),
                    evidence,
                ));
            };
            let Some(sign_of) = sign_of else {
                // Opposite infinities on the two sides: no signed limit.
                return Ok(with_evidence(refuted(cx, None), evidence));
            };
            // The kernel reads the limit and certifies its sign; when it cannot, the
            // search looks for a point where the sign is wrong.
            let o = cx.by_kernel(kernel_limit(cx, None), None);
            if o.verdict() == crate::derivation::Verdict::Holds {
                return Ok(with_evidence(o, evidence));
            }
            let want = if plus { Sign::Positive } else { Sign::Negative };
            let g = Exact {
                f: sign_of,
                conditions: Vec::new(),
            };
            Ok(
                match decide_function(cx, (&g, None), want, evidence.clone())? {
                    // The search found the sign, the kernel did not accept the limit: its
                    // reason stands.
                    Decided::Holds(_) => o,
                    Decided::At(point) => {
                        let mut out =
                            refuted_at(cx, function, v, to, &point, (None, None, Some(plus)));
                        out.finding = Some(Finding::RationalFunction(evidence));
                        out
                    }
                    Decided::AtRoot { .. } => Outcome::undecided(Method::RationalFunction, 0)
                        .with_finding(Finding::RationalFunction(evidence)),
                },
            )
        }
    }
}

/// The limit fact for the kernel: without a point for a limit that holds, with the
/// other parameters' point for one refuted there.
fn kernel_limit(cx: &Context<'_>, point: Option<&BTreeMap<Var, Rational>>) -> Fact {
    Fact::Limit {
        point: point.map(|p| cx.full_point(p)),
        roots: cx.roots(),
    }
}

fn describe(l: &Limit, cx: &Context<'_>) -> String {
    match l {
        Limit::Finite(v) => v.display(&cx.env.vars),
        Limit::Infinite { sign_of } => {
            format!("∞ with the sign of {}", sign_of.display(&cx.env.vars))
        }
        Limit::InfiniteBothSigns => "+∞ on one side and −∞ on the other".to_owned(),
    }
}

/// Points of the other parameters tried for a refutation: small integers, then
/// seeded random rationals of the box.
const SIMPLE_POINTS: usize = 8;
const RANDOM_POINTS: usize = 16;

/// The refutation of a stated limit at a rational point of the other parameters where
/// the found limit differs from it.
fn refutation(
    cx: &Context<'_>,
    (function, f): (&Expression, &Exact),
    v: Var,
    to: &Approach,
    found: Option<&Limit>,
    (claimed, plus): (Option<&Exact>, Option<bool>),
) -> Outcome {
    let Some(found) = found else {
        return Outcome::undecided(Method::RationalFunction, 0);
    };
    // The other parameters of the function and of the stated limit.
    let mut others: Vec<Var> = f.variables();
    others.extend(claimed.map(Exact::variables).unwrap_or_default());
    others.sort_unstable();
    others.dedup();
    others.retain(|w| *w != v);
    // Try a few points of the box; keep the first where both limits are defined and
    // differ. Small integers first (they read best; distinct for distinct parameters),
    // then seeded random rationals: a nonzero polynomial difference vanishes at almost
    // none of those.
    let mut rng = crate::decide::random::Rng::salted(cx.seed, 0x11_3175);
    for k in 0..SIMPLE_POINTS + RANDOM_POINTS {
        let point: BTreeMap<Var, Rational> = others
            .iter()
            .enumerate()
            .map(|(j, &w)| {
                let i = cx.interval(w);
                if k >= SIMPLE_POINTS {
                    return (w, rng.draw(&i));
                }
                // Distinct values for distinct parameters.
                let base = Rational::int(1 + (k + j) as i64);
                let x = if i.contains(&base) {
                    base
                } else {
                    inner_point(&i)
                };
                (w, x)
            })
            .collect();
        let at = |w: Var| point.get(&w).cloned().unwrap_or_else(|| Rational::int(0));
        let finite = match found {
            Limit::Finite(m) => match m.eval(&at) {
                Some(x) => Some(x),
                None => continue,
            },
            _ => None,
        };
        let stated = match claimed {
            Some(c) => match c.f.eval(&at) {
                Some(x) => Some(x),
                None => continue,
            },
            None => None,
        };
        if finite.is_some() && finite == stated {
            continue;
        }
        return refuted_at(cx, function, v, to, &point, (finite, stated, plus));
    }
    Outcome::undecided(Method::RationalFunction, 0)
}

/// `fails` at `point` (the other parameters): the stated limit against the found one
/// (`None`: infinite), confirmed by the interpreter near the point.
fn refuted_at(
    cx: &Context<'_>,
    function: &Expression,
    v: Var,
    to: &Approach,
    point: &BTreeMap<Var, Rational>,
    (found, stated, plus): (Option<Rational>, Option<Rational>, Option<bool>),
) -> Outcome {
    // Near the point: 2⁻²⁴ from it, or 2²⁴ out (both sides of a two-sided approach).
    let near: Vec<Rational> = match to {
        Approach::At(c, side) => {
            let d = Rational::ratio(1, 1 << 24).expect("nonzero");
            match side {
                Side::Above => vec![c + &d],
                Side::Below => vec![c - &d],
                Side::Both => vec![c + &d, c - &d],
            }
        }
        Approach::PlusInfinity => vec![Rational::int(1 << 24)],
        Approach::MinusInfinity => vec![Rational::int(-(1 << 24))],
    };
    let values: Vec<Option<f64>> = near
        .iter()
        .map(|x| {
            let mut p = point.clone();
            p.insert(v, x.clone());
            cx.interpret(function, &p).ok().filter(|y| y.is_finite())
        })
        .collect();
    let confirmed = match (&found, &stated) {
        // Both infinite: the stated sign is wrong on some side.
        (None, None) => values
            .iter()
            .any(|y| y.is_some_and(|y| y.abs() > 1e3 && plus.is_some_and(|p| (y > 0.0) != p))),
        _ => values.iter().all(|y| {
            let Some(y) = *y else { return false };
            let dist = |q: &Option<Rational>| match q {
                Some(q) => (y - q.to_f64()).abs(),
                None => 1.0 / (1.0 + y.abs()),
            };
            dist(&found) < dist(&stated)
        }),
    };
    if !confirmed {
        return Outcome::undecided(Method::RationalFunction, 0);
    }
    let name = cx.name(v);
    let shown = cx.shown(point);
    let infinite = match plus {
        Some(true) if found.is_none() && stated.is_none() => "−∞ on some side",
        Some(false) if found.is_none() && stated.is_none() => "+∞ on some side",
        _ => "∞",
    };
    let stated_text = match plus {
        Some(true) => "+∞",
        Some(false) => "−∞",
        None => "∞",
    };
    let text = |q: &Option<Rational>, inf: &str| {
        q.as_ref()
            .map_or_else(|| inf.to_owned(), Rational::to_string)
    };
    let o = cx.by_kernel(kernel_limit(cx, Some(point)), None);
    if o.verdict() != crate::derivation::Verdict::Fails {
        return o;
    }
    o.with_counterexample(Counterexample {
        chain: 1,
        equality: 1,
        lhs: format!("lim {} as {name} → {to}", function.text),
        rhs: "the stated limit".to_owned(),
        point: shown,
        lhs_value: Some(text(&found, infinite)),
        rhs_value: Some(text(&stated, stated_text)),
        reverified: Some(Reverified::FloatingPoint),
        ..Counterexample::default()
    })
}
