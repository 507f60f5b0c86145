//! `strategy = "sign"`: `left − right` has the stated sign at every point of the box
//! where both sides are defined.

use super::context::{Context, Exact, Stop};
use super::sample::{self, Sampled};
use crate::algebra::certificate::Certificate;
use crate::algebra::sign::{Sign, Violation};
use crate::decide::finding::{Finding, RationalEvidence};
use crate::decide::outcome::{Counterexample, Method, Outcome};
use crate::decide::reverify;
use crate::derivation::Expression;
use crate::kernel::check::Fact;
use crate::kernel::{Poly, Rational, Var};
use std::collections::BTreeMap;

pub(super) fn decide(cx: &mut Context<'_>, want: Sign) -> Result<Outcome, Stop> {
    let [left, right] = sides(cx)?;
    let (l, r) = (cx.exact(&left)?, cx.exact(&right)?);
    let h = l.minus(&r);
    let mut evidence = cx.evidence(&h.f);
    evidence.decided = format!("left − right = {}", evidence.decided);
    let decided = decide_function(cx, (&h, None), want, evidence)?;
    Ok(match decided {
        Decided::Holds(o) => *o,
        Decided::At(point) => counterexample(cx, (&left, &right), (&l, &r), &point),
        Decided::AtRoot {
            var,
            lo,
            hi,
            evidence,
        } => at_root(cx, (&left, &right), var, (&lo, &hi), *evidence),
    })
}

/// The claim's one pair of sides as expressions.
fn sides(cx: &Context<'_>) -> Result<[Expression; 2], Stop> {
    let chain = &cx.check.chains[0];
    let one = |k: usize| -> Result<Expression, Stop> {
        let side = &chain[k];
        let node = side
            .node
            .clone()
            .map_err(|e| Stop::Input(side.origin.diagnostic(e.span, e.message.clone())))?;
        Ok(Expression {
            text: side.text.clone(),
            origin: side.origin.clone(),
            node,
        })
    };
    Ok([one(0)?, one(1)?])
}

/// How the sign of a function was decided.
pub(super) enum Decided {
    /// Proved, or sampled without a violation: the outcome, complete.
    Holds(Box<Outcome>),
    /// Broken at an exact rational point.
    At(BTreeMap<Var, Rational>),
    /// A strict sign broken at an irrational zero of the function of `var`, isolated in
    /// (lo, hi).
    AtRoot {
        var: Var,
        lo: Rational,
        hi: Rational,
        evidence: Box<RationalEvidence>,
    },
}

/// Decides that `g` has the sign `want` on the box: the algebra searches for a
/// certificate (coefficient signs, a Sturm sign chart), and the kernel checks what
/// it found against the claim's statement.
pub(super) fn decide_function(
    cx: &Context<'_>,
    (g, function): (&Exact, Option<&Exact>),
    want: Sign,
    mut evidence: RationalEvidence,
) -> Result<Decided, Stop> {
    let names = &cx.env.vars;
    let vars = g.variables();
    let proved = |fact: Fact, e: RationalEvidence| {
        Decided::Holds(Box::new(with_evidence(cx.by_kernel(fact, None), e)))
    };
    let function_vars = function.map(|f| f.variables());
    let (reduced, function) = (Some(cx.reduced(g)), function.map(|f| cx.reduced(f)));
    let by_coefficients = || Fact::SignByCoefficients {
        reduced: reduced.clone(),
        function: function.clone(),
        roots: cx.roots(),
    };
    // Identically zero: a non-strict sign holds everywhere, a strict one nowhere.
    if g.f.is_zero() {
        return Ok(if want.admits(0) {
            proved(by_coefficients(), evidence)
        } else {
            Decided::At(first_defined(cx, g, &vars))
        });
    }
    // The sign chart of num/den in `v` (the other parameters, if any, only in a factor
    // of one strict sign, divided out), certified on v's interval by the kernel.
    let charted = |v: Var, (num, den): (Poly, Poly), mut evidence: RationalEvidence| {
        let i = cx.interval(v);
        let chart = crate::algebra::sign::chart_of((&num, &den), v, &i);
        if let Some(chart) = &chart {
            evidence.points = chart
                .cuts
                .iter()
                .map(|c| {
                    let what = if c.pole { "pole" } else { "zero" };
                    format!(
                        "{what} at {}",
                        super::context::equated(&c.at, names.name(v))
                    )
                })
                .collect();
        }
        Ok(
            match Certificate::sign_on_interval((&num, &den), v, &i, want, names) {
                Ok(_) => {
                    let fact = Fact::SignOnInterval {
                        variable: names.name(v).to_owned(),
                        cuts: chart.as_ref().map(|c| cuts(c, &i)).unwrap_or_default(),
                        reduced: reduced.clone(),
                        function: function.clone(),
                        roots: cx.roots(),
                    };
                    proved(fact, evidence)
                }
                // The other parameters anywhere in the box.
                Err(Some(violation)) => match *violation {
                    Violation::At { x, .. } => Decided::At(cx.complete(&BTreeMap::from([(v, x)]))),
                    Violation::Zero { lo, hi } => Decided::AtRoot {
                        var: v,
                        lo,
                        hi,
                        evidence: Box::new(evidence),
                    },
                },
                Err(None) => {
                    return Err(Stop::Outcome(Box::new(
                        Outcome::undecided(Method::RationalFunction, 0)
                            .with_finding(Finding::RationalFunction(evidence)),
                    )))
                }
            },
        )
    };
    match vars.as_slice() {
        [] => {
            let box_ = cx.box_on(&vars);
            Ok(
                match Certificate::sign_by_coefficients(&g.f, &box_, want, names) {
                    Some(_) => proved(by_coefficients(), evidence),
                    None => Decided::At(BTreeMap::new()),
                },
            )
        }
        // One variable, the function's own (a monotone claim's slope may have one
        // variable that is not the function's: the coefficients decide it below).
        [v] if function_vars.as_ref().is_none_or(|f| f == &[*v]) => {
            charted(*v, g.cleared(), evidence)
        }
        _ => {
            if Certificate::sign_by_coefficients(&g.f, &cx.box_on(&vars), want, names).is_some() {
                return Ok(proved(by_coefficients(), evidence));
            }
            // Of one parameter once a factor of one strict sign on the box is divided
            // out (μ (x − 1)² ≥ 0 with μ > 0): its sign chart in that parameter.
            if function_vars.is_none() {
                if let Some((v, nd)) = vars
                    .iter()
                    .find_map(|&v| Some((v, cx.cleared_in(g.cleared(), v)?)))
                {
                    return charted(v, nd, evidence);
                }
            }
            // Stopped by the time limit: undecided, with the limit as the finding
            // (`check::decide` gives it to every decision that outlived it).
            let stopped =
                |_| Stop::Outcome(Box::new(Outcome::undecided(Method::RationalFunction, 0)));
            Ok(match sample::search(cx, g, &vars, want).map_err(stopped)? {
                Sampled::Violation { point } => Decided::At(point),
                Sampled::Holds(s) => {
                    let checks = s.samples;
                    evidence.sampled = Some(s);
                    Decided::Holds(Box::new(
                        Outcome::holds_sampled(Method::RationalFunction, checks)
                            .with_finding(Finding::RationalFunction(evidence)),
                    ))
                }
            })
        }
    }
}

/// An outcome of the kernel with the search's evidence, unless the kernel refused it
/// (its reason is then the finding).
pub(super) fn with_evidence(o: Outcome, e: RationalEvidence) -> Outcome {
    if matches!(o.finding, Some(Finding::KernelRefused { .. })) {
        return o;
    }
    o.with_finding(Finding::RationalFunction(e))
}

/// Rational points that separate the roots of a sign chart, strictly inside `i`: every
/// rational root and a point inside every piece, so that each gap between two of them
/// holds at most one (irrational) root, between two points that are not roots.
pub(super) fn cuts(
    chart: &crate::algebra::sign::SignChart,
    i: &crate::algebra::sign::Interval,
) -> Vec<Rational> {
    let mut out: Vec<Rational> = chart
        .cuts
        .iter()
        .filter_map(|c| match &c.at {
            crate::algebra::sign::Real::Exact(x) => Some(x.clone()),
            _ => None,
        })
        .chain(chart.pieces.iter().map(|p| p.sample.clone()))
        .filter(|x| i.contains(x) && Some(x) != i.lo.value() && Some(x) != i.hi.value())
        .collect();
    out.sort();
    out.dedup();
    out
}

/// A point of the box where `g` is defined (for a function that is zero everywhere).
fn first_defined(cx: &Context<'_>, g: &Exact, vars: &[Var]) -> BTreeMap<Var, Rational> {
    let candidates = [1, 2, 3, -1].map(Rational::int);
    for c in &candidates {
        let p: BTreeMap<Var, Rational> = vars
            .iter()
            .map(|&v| {
                let i = cx.interval(v);
                let x = if i.contains(c) {
                    c.clone()
                } else {
                    crate::algebra::sign::inner_point(&i)
                };
                (v, x)
            })
            .collect();
        if g.eval(&p).is_some() {
            return p;
        }
    }
    BTreeMap::new()
}

/// The exact counterexample at `point`, confirmed by the interpreter.
fn counterexample(
    cx: &Context<'_>,
    (left, right): (&Expression, &Expression),
    (l, r): (&Exact, &Exact),
    point: &BTreeMap<Var, Rational>,
) -> Outcome {
    let (Some(lv), Some(rv)) = (l.eval(point), r.eval(point)) else {
        return Outcome::undecided(Method::RationalFunction, 0);
    };
    let mut shown = cx.shown(point);
    if shown.is_empty() {
        shown.insert("(no parameter)".to_owned(), "—".to_owned());
    }
    let mut found = Counterexample {
        chain: 1,
        equality: 1,
        lhs: left.text.clone(),
        rhs: right.text.clone(),
        point: shown,
        lhs_value: Some(lv.to_string()),
        rhs_value: Some(rv.to_string()),
        difference: (&lv - &rv).to_string(),
        ..Counterexample::default()
    };
    let completed = cx.complete(point);
    match reverify::exact_counterexample(
        cx.decls,
        cx.check,
        &cx.env,
        &completed,
        (&lv, &rv),
        &found,
    ) {
        Ok(how) => {
            found.reverified = Some(how);
            let fact = Fact::SignAt {
                point: cx.full_point(point),
                roots: cx.roots(),
            };
            let o = cx.by_kernel(fact, None);
            if o.verdict() == crate::derivation::Verdict::Fails {
                o.with_counterexample(found)
            } else {
                o
            }
        }
        Err(why) => {
            Outcome::undecided(Method::RationalFunction, 0).with_finding(Finding::Unconfirmed {
                difference: found.difference,
                why,
            })
        }
    }
}

/// A strict sign broken at an irrational zero of `left − right`: both sides are equal
/// there. The interpreter must find them equal to 1e-6 at the isolating interval's
/// midpoint (at most 2⁻⁴⁰ from the zero).
fn at_root(
    cx: &Context<'_>,
    (left, right): (&Expression, &Expression),
    var: Var,
    (lo, hi): (&Rational, &Rational),
    evidence: RationalEvidence,
) -> Outcome {
    let mid = &(lo + hi) * &Rational::ratio(1, 2).expect("nonzero");
    // The other parameters (in a factor of one sign) anywhere in the box.
    let point = cx.complete(&BTreeMap::from([(var, mid.clone())]));
    let values = cx
        .interpret(left, &point)
        .and_then(|a| cx.interpret(right, &point).map(|b| (a, b)));
    let (a, b) = match values {
        Ok((a, b)) if (a - b).abs() <= 1e-6 * (1.0 + a.abs() + b.abs()) => (a, b),
        _ => {
            return Outcome::undecided(Method::RationalFunction, 0)
                .with_finding(Finding::RationalFunction(evidence))
        }
    };
    let root = crate::algebra::sign::Real::Isolated {
        lo: lo.clone(),
        hi: hi.clone(),
    };
    let found = Counterexample {
        chain: 1,
        equality: 1,
        lhs: left.text.clone(),
        rhs: right.text.clone(),
        point: BTreeMap::from([(
            cx.name(var),
            format!(
                "{} (the zero of left − right in ({lo}, {hi}))",
                super::context::shown_real(&root)
            ),
        )]),
        lhs_value: Some(crate::digits::significant(a, crate::digits::VALUE)),
        rhs_value: Some(crate::digits::significant(b, crate::digits::VALUE)),
        difference: "0".to_owned(),
        reverified: Some(crate::decide::outcome::Reverified::FloatingPoint),
        ..Counterexample::default()
    };
    let fact = Fact::ZeroBetween {
        variable: cx.name(var),
        lo: lo.clone(),
        hi: hi.clone(),
        roots: cx.roots(),
    };
    let o = cx.by_kernel(fact, None);
    if o.verdict() != crate::derivation::Verdict::Fails {
        return o;
    }
    o.with_counterexample(found)
        .with_finding(Finding::RationalFunction(evidence))
}
