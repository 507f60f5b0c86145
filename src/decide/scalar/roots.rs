//! `strategy = "roots"`: the real roots of a function of one parameter on its interval
//! are exactly the stated rationals, or as many as `count`. The search isolates every
//! real root of the numerator (Sturm, `algebra::sturm`) and the kernel checks the count
//! between rational cuts, so a root left out is found as surely as a stated one that is
//! not a root. Roots that are functions of the other parameters (h = h_cr(G, k, …))
//! are proved by the kernel's exact division of the numerator, or refuted at a point
//! of the parameters.

use super::context::{Context, Stop};
use crate::algebra::certificate::Certificate;
use crate::algebra::sign::Real;
use crate::decide::finding::{Finding, RationalEvidence};
use crate::decide::outcome::{Counterexample, Method, Outcome, Reverified};
use crate::derivation::Expression;
use crate::kernel::check::Fact;
use crate::kernel::Rational;
use std::collections::BTreeMap;

pub(super) fn decide(
    cx: &mut Context<'_>,
    function: &Expression,
    variable: &str,
    roots: &[Expression],
) -> Result<Outcome, Stop> {
    let (f, v, mut evidence) = function_of(cx, function, variable)?;
    let mut exact_roots = Vec::with_capacity(roots.len());
    for r in roots {
        exact_roots.push(cx.exact(r)?);
    }
    let stated: Option<Vec<Rational>> = exact_roots.iter().map(|r| r.f.as_constant()).collect();
    let others = f.variables().iter().any(|w| *w != v);
    let one = match &stated {
        Some(_) if !others => Some(f.cleared()),
        Some(_) => cx.cleared_in(f.cleared(), v),
        None => None,
    };
    let (Some(stated), Some((num, den))) = (stated, one) else {
        // Roots that are functions of the other parameters (h = h_cr(a, b)), or a
        // function of several parameters not only through a factor of one sign.
        return parametric(cx, (function, &f), v, &exact_roots, evidence);
    };
    let i = cx.interval(v);
    let names = &cx.env.vars;
    let zeros = match Certificate::roots_exactly((&num, &den), v, &i, &stated, names) {
        Ok(_) => {
            evidence.points = stated.iter().map(|r| format!("root {r}")).collect();
            let o = cx.by_kernel(Fact::Roots { roots: cx.roots() }, None);
            return Ok(super::sign::with_evidence(o, evidence));
        }
        Err(Some(zeros)) => zeros,
        Err(None) => {
            evidence.points.push(format!(
                "no sign chart on {}: the interval is empty or the roots could not be isolated within {} bisections",
                i.describe(&cx.name(v)),
                crate::algebra::sturm::MAX_BISECTIONS
            ));
            return Ok(Outcome::undecided(Method::RationalFunction, 0)
                .with_finding(Finding::RationalFunction(evidence)));
        }
    };
    let name = cx.name(v);
    evidence.points = found(&zeros, &i, &name);
    // A stated value that is no root, with its exact value.
    for r in &stated {
        if zeros.contains(&Real::Exact(r.clone())) {
            continue;
        }
        // Other parameters (a factor of one sign) inside the box.
        let point = cx.complete(&BTreeMap::from([(v, r.clone())]));
        let value = f.eval(&point);
        let confirmed = match (&value, cx.interpret(function, &point)) {
            (Some(q), Ok(y)) => super::context::agrees(y, q),
            (None, _) => true,
            _ => false,
        };
        if !confirmed {
            return Ok(Outcome::undecided(Method::RationalFunction, 0)
                .with_finding(Finding::RationalFunction(evidence)));
        }
        let lhs_value = value.map_or_else(|| "undefined".to_owned(), |q| q.to_string());
        let outside = if i.contains(r) {
            ""
        } else {
            " (outside the domain)"
        };
        let others: Vec<String> = point
            .iter()
            .filter(|(w, _)| **w != v && f.variables().contains(w))
            .map(|(w, x)| format!("{} = {x}", cx.name(*w)))
            .collect();
        let outside = if others.is_empty() {
            outside.to_owned()
        } else {
            format!("{outside}, {}", others.join(", "))
        };
        let how = Reverified::FloatingPoint;
        return Ok(super::sign::with_evidence(
            fails(cx, function, &name, format!("{r}{outside}"), lhs_value, how),
            evidence,
        ));
    }
    // A root that is not stated.
    let missing = zeros
        .iter()
        .find(|z| !matches!(z, Real::Exact(x) if stated.contains(x)));
    Ok(match missing {
        // Found by Sturm isolation in the kernel: exact, whatever its value's digits.
        Some(z) => super::sign::with_evidence(
            fails(
                cx,
                function,
                &name,
                format!("{} (a root not stated)", super::context::shown_real(z)),
                "0".to_owned(),
                Reverified::Exact,
            ),
            evidence,
        ),
        None => Outcome::undecided(Method::RationalFunction, 0)
            .with_finding(Finding::RationalFunction(evidence)),
    })
}

/// `roots = [...]` where the roots are functions of the other parameters, or the
/// function depends on them: for every value of them in the box, the zeros in `v` are
/// exactly the roots there. The search finds each root's multiplicity at a parameter
/// point, for the kernel to check the factorisation over the whole box; failing that,
/// it looks for a point of the parameters where the zeros differ (simple points, then
/// seeded draws), which the kernel checks by Sturm counts.
fn parametric(
    cx: &mut Context<'_>,
    (function, f): (&Expression, &super::context::Exact),
    v: crate::kernel::Var,
    roots: &[super::context::Exact],
    mut evidence: RationalEvidence,
) -> Result<Outcome, Stop> {
    use crate::kernel::{Poly, Var};
    let name = cx.name(v);
    let (num, den) = f.cleared();
    let params: Vec<Var> = {
        let mut all = f.variables();
        for r in roots {
            all.extend(r.variables());
        }
        all.sort();
        all.dedup();
        all.retain(|w| *w != v);
        all
    };
    let bx = cx.box_on(&params);
    let i = cx.interval(v);
    // Simple points first (the box's inner point, small integers and halves), then draws.
    let mut points: Vec<BTreeMap<Var, Rational>> = Vec::new();
    let simple: Vec<Vec<Rational>> = bx
        .iter()
        .map(|(_, iv)| {
            let fractions = [
                (1, 1),
                (2, 1),
                (-1, 1),
                (1, 2),
                (-1, 2),
                (3, 1),
                (-2, 1),
                (1, 3),
                (-3, 1),
            ];
            super::sample::simple_values(iv, &fractions)
        })
        .collect();
    // The box's inner point (0 where unbounded), then each parameter moved alone
    // through its simple values, then every combination while there are at most 256.
    let base: BTreeMap<Var, Rational> = bx
        .iter()
        .zip(&simple)
        .map(|((w, _), c)| (*w, c[0].clone()))
        .collect();
    points.push(base.clone());
    for ((w, _), c) in bx.iter().zip(&simple) {
        for x in &c[1..] {
            let mut point = base.clone();
            point.insert(*w, x.clone());
            points.push(point);
        }
    }
    let few: Vec<Vec<Rational>> = simple
        .iter()
        .map(|c| c[..c.len().min(4)].to_vec())
        .collect();
    points.extend(super::sample::combinations(&bx, &few, 256));
    let mut rng = crate::decide::random::Rng::salted(cx.seed, 0x2007_5EED);
    for _ in 0..cx.samples.min(64) {
        points.push(bx.iter().map(|(w, iv)| (*w, rng.draw(iv))).collect());
    }
    let at = |p: &Poly, point: &BTreeMap<Var, Rational>| -> Option<Poly> {
        let values = point
            .iter()
            .map(|(w, x)| (*w, Poly::constant(x.clone())))
            .collect();
        crate::kernel::eval::substitute(p, &values).ok()
    };
    let mut multiplicities: Option<Vec<u32>> = None;
    let mut refuted: Option<Differs> = None;
    for point in &points {
        super::super::watch::check().map_err(|_| {
            Stop::Outcome(Box::new(
                Outcome::undecided(Method::RationalFunction, 0)
                    .with_finding(Finding::RationalFunction(evidence.clone())),
            ))
        })?;
        let (Some(n0), Some(d0)) = (at(&num, point), at(&den, point)) else {
            continue;
        };
        let Some(stated) = roots
            .iter()
            .map(|r| r.eval(point))
            .collect::<Option<Vec<_>>>()
        else {
            continue;
        };
        if d0.is_zero() {
            // Undefined for every value of the variable: no zero, so a stated root is
            // none.
            if !stated.is_empty() {
                refuted = Some((point.clone(), Vec::new(), stated));
                break;
            }
            continue;
        }
        if n0.is_zero() {
            continue;
        }
        let Some(chart) = crate::algebra::sign::chart_of((&n0, &d0), v, &i) else {
            continue;
        };
        let zeros = chart.zeros();
        // A stated value is a zero when N vanishes there and D does not (exactly, so
        // that a rational root the chart isolated rather than found still counts).
        let value =
            |p: &Poly, r: &Rational| p.eval(&|w| if w == v { r.clone() } else { Rational::int(0) });
        let is_zero = |r: &Rational| {
            i.contains(r)
                && value(&n0, r).is_some_and(|x| x.is_zero())
                && value(&d0, r).is_some_and(|x| !x.is_zero())
        };
        let mut distinct = stated.clone();
        distinct.sort();
        distinct.dedup();
        if distinct.iter().all(is_zero) && distinct.len() == zeros.len() {
            if multiplicities.is_none() && distinct.len() == stated.len() {
                multiplicities = Some(stated.iter().map(|r| multiplicity(&n0, v, r)).collect());
            }
        } else {
            refuted = Some((point.clone(), zeros, stated));
            break;
        }
    }
    evidence.points = roots
        .iter()
        .map(|r| format!("root {name} = {}", cx.evidence(&r.f).decided))
        .collect();
    if let Some((point, zeros, stated)) = refuted {
        let mut full = cx.full_point(&point);
        full.retain(|(n, _)| *n != name);
        let o = cx.by_kernel(
            Fact::RootsAt {
                point: full,
                roots: cx.roots(),
            },
            None,
        );
        if o.verdict() == crate::derivation::Verdict::Fails {
            let shown = |z: &crate::algebra::sign::Real| super::context::shown_real(z);
            let found = zeros.iter().map(shown).collect::<Vec<_>>().join(", ");
            // The parameters only: the variable's own bound is no coordinate of it.
            let mut at = cx.shown(&point);
            at.remove(&name);
            let stated: Vec<String> = stated.iter().map(ToString::to_string).collect();
            let o = o.with_counterexample(Counterexample {
                chain: 1,
                equality: 1,
                lhs: format!("the real roots of {} in {name}", function.text),
                rhs: format!("[{}]", stated.join(", ")),
                point: at,
                lhs_value: Some(format!("[{found}]")),
                rhs_value: Some(format!("[{}]", stated.join(", "))),
                reverified: Some(Reverified::Exact),
                ..Counterexample::default()
            });
            return Ok(super::sign::with_evidence(o, evidence));
        }
    }
    let Some(multiplicities) = multiplicities else {
        evidence
            .points
            .push("no parameter point where the roots are distinct and are the zeros".to_owned());
        return Ok(Outcome::undecided(Method::RationalFunction, 0)
            .with_finding(Finding::RationalFunction(evidence)));
    };
    let o = cx.by_kernel(
        Fact::RootsOfParameters {
            multiplicities,
            roots: cx.roots(),
        },
        None,
    );
    Ok(super::sign::with_evidence(o, evidence))
}

/// A parameter point where the zeros differ from the roots stated: the point, the
/// zeros found there, the roots' values there.
type Differs = (
    BTreeMap<crate::kernel::Var, Rational>,
    Vec<crate::algebra::sign::Real>,
    Vec<Rational>,
);

/// The multiplicity of the root `r` of `p` in `v` (the order of the first derivative
/// that is nonzero there), at least 1.
fn multiplicity(p: &crate::kernel::Poly, v: crate::kernel::Var, r: &Rational) -> u32 {
    let mut d = p.derivative(v);
    let mut m = 1;
    while m < 1000 {
        let value = d.eval(&|w| if w == v { r.clone() } else { Rational::int(0) });
        if value.is_none_or(|x| !x.is_zero()) {
            break;
        }
        d = d.derivative(v);
        m += 1;
    }
    m
}

/// Numerator and denominator of a function of `v`, its other parameters (if any) only
/// in a factor of one strict sign on the box (μ in μ (x² − 1), μ > 0), which the roots
/// are those of the rest; `None`, with the reason in the evidence, otherwise.
fn of_one(
    cx: &Context<'_>,
    f: &super::context::Exact,
    v: crate::kernel::Var,
    evidence: &mut RationalEvidence,
) -> Option<(crate::kernel::Poly, crate::kernel::Poly)> {
    let others: Vec<_> = f.variables().into_iter().filter(|w| *w != v).collect();
    if others.is_empty() {
        return Some(f.cleared());
    }
    let nd = cx.cleared_in(f.cleared(), v);
    if nd.is_none() {
        evidence.points.push(format!(
            "the function also depends on {}, not only through a factor of one sign; roots are \
             decided for functions of one parameter only",
            others
                .iter()
                .map(|w| cx.name(*w))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    nd
}

/// `count = n`: the function has exactly n distinct real roots on its interval,
/// rational or not. The kernel counts them itself (Sturm sequences); the search
/// isolates them for the evidence, each exact or between two close rationals.
pub(super) fn count(
    cx: &mut Context<'_>,
    function: &Expression,
    variable: &str,
    stated: usize,
) -> Result<Outcome, Stop> {
    let (f, v, mut evidence) = function_of(cx, function, variable)?;
    let Some((num, den)) = of_one(cx, &f, v, &mut evidence) else {
        return Ok(Outcome::undecided(Method::RationalFunction, 0)
            .with_finding(Finding::RationalFunction(evidence)));
    };
    let i = cx.interval(v);
    let name = cx.name(v);
    let zeros = match Certificate::roots_exactly((&num, &den), v, &i, &[], &cx.env.vars) {
        Ok(_) => Vec::new(),
        Err(Some(zeros)) => zeros,
        Err(None) => {
            evidence.points.push(format!(
                "the roots on {} could not be isolated within {} bisections",
                i.describe(&name),
                crate::algebra::sturm::MAX_BISECTIONS
            ));
            return Ok(Outcome::undecided(Method::RationalFunction, 0)
                .with_finding(Finding::RationalFunction(evidence)));
        }
    };
    evidence.points = found(&zeros, &i, &name);
    let o = cx.by_kernel(Fact::Roots { roots: cx.roots() }, None);
    let counted = o.proofs().first().and_then(|p| {
        p.summary().iter().find_map(|c| match c {
            crate::kernel::check::Checked::Roots { zeros, .. } => Some(*zeros),
            _ => None,
        })
    });
    let o = match (o.verdict(), counted) {
        (crate::derivation::Verdict::Fails, Some(n)) => o.with_counterexample(Counterexample {
            chain: 1,
            equality: 1,
            lhs: format!("the number of real roots of {}", function.text),
            rhs: stated.to_string(),
            // The roots found stand where a point would: none is a counterexample alone.
            point: BTreeMap::from([(
                name.clone(),
                if zeros.is_empty() {
                    "no real root".to_owned()
                } else {
                    zeros
                        .iter()
                        .map(super::context::shown_real)
                        .collect::<Vec<_>>()
                        .join(" and ")
                },
            )]),
            lhs_value: Some(n.to_string()),
            rhs_value: Some(stated.to_string()),
            reverified: Some(Reverified::Exact),
            ..Counterexample::default()
        }),
        _ => o,
    };
    Ok(super::sign::with_evidence(o, evidence))
}

/// The claim's function exactly, its variable, and the evidence saying what was
/// decided.
fn function_of(
    cx: &mut Context<'_>,
    function: &Expression,
    variable: &str,
) -> Result<(super::context::Exact, crate::kernel::Var, RationalEvidence), Stop> {
    let f = cx.exact(function)?;
    let v = cx
        .var(variable)
        .unwrap_or_else(|| cx.env.vars.intern(variable));
    let mut evidence = cx.evidence(&f.f);
    evidence.decided = format!("{} = {}", function.text, evidence.decided);
    Ok((f, v, evidence))
}

/// The zeros found, for the evidence: each exact or isolated, or that there is none.
fn found(zeros: &[Real], i: &crate::algebra::sign::Interval, name: &str) -> Vec<String> {
    if zeros.is_empty() {
        return vec![format!(
            "no real root (Sturm isolation on {})",
            i.describe(name)
        )];
    }
    zeros
        .iter()
        .map(|z| format!("root at {}", super::context::equated(z, name)))
        .collect()
}

/// `fails`, as the kernel concludes it from its own count of the zeros; the
/// counterexample shows the value the search found.
fn fails(
    cx: &Context<'_>,
    function: &Expression,
    name: &str,
    at: String,
    value: String,
    how: Reverified,
) -> Outcome {
    let o = cx.by_kernel(Fact::Roots { roots: cx.roots() }, None);
    if o.verdict() != crate::derivation::Verdict::Fails {
        return o;
    }
    o.with_counterexample(Counterexample {
        chain: 1,
        equality: 1,
        lhs: function.text.clone(),
        rhs: "0".to_owned(),
        point: BTreeMap::from([(name.to_owned(), at)]),
        lhs_value: Some(value),
        rhs_value: Some(Rational::int(0).to_string()),
        reverified: Some(how),
        ..Counterexample::default()
    })
}
