//! `strategy = "roots"`: the real roots of a function of one parameter on its interval
//! are exactly the stated rationals. The search isolates every real root of the
//! numerator (Sturm, `algebra::sturm`) and the kernel checks the count between rational
//! cuts, so a root left out is found as surely as a stated one that is not a root.

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
    let f = cx.exact(function)?;
    let v = cx
        .var(variable)
        .unwrap_or_else(|| cx.env.vars.intern(variable));
    let mut evidence = cx.evidence(&f.f);
    evidence.decided = format!("{} = {}", function.text, evidence.decided);
    let mut stated = Vec::with_capacity(roots.len());
    for r in roots {
        match cx.exact(r)?.f.as_constant() {
            Some(q) => stated.push(q),
            None => {
                return Err(Stop::Input(
                    r.origin
                        .diagnostic(r.node.span, "a stated root must be a rational number")
                        .with_help("roots are decided for functions of one parameter; fix the others with assumptions"),
                ))
            }
        }
    }
    let (num, den) = match of_one(cx, &f, v, &mut evidence) {
        Some(nd) => nd,
        None => {
            return Ok(Outcome::undecided(Method::RationalFunction, 0)
                .with_finding(Finding::RationalFunction(evidence)))
        }
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
    evidence.points = zeros
        .iter()
        .map(|z| format!("root at {}", super::context::equated(z, &name)))
        .collect();
    if zeros.is_empty() {
        evidence.points.push(format!(
            "no real root (Sturm isolation on {})",
            i.describe(&name)
        ));
    }
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
    let f = cx.exact(function)?;
    let v = cx
        .var(variable)
        .unwrap_or_else(|| cx.env.vars.intern(variable));
    let mut evidence = cx.evidence(&f.f);
    evidence.decided = format!("{} = {}", function.text, evidence.decided);
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
    evidence.points = zeros
        .iter()
        .map(|z| format!("root at {}", super::context::equated(z, &name)))
        .collect();
    if zeros.is_empty() {
        evidence.points.push(format!(
            "no real root (Sturm isolation on {})",
            i.describe(&name)
        ));
    }
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
