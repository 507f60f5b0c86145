//! `strategy = "monotone"`: a function increases (decreases) in one parameter on the
//! box: its derivative is ≥ 0 (≤ 0) wherever defined, not identically 0, and the
//! function has no pole in the domain. Of one parameter, the derivative's sign chart
//! gives the exact turning points; a claim that holds between them and fails beyond is
//! `conditional`, with the interval where it holds.

use super::context::{Context, Exact, Stop};
use super::sign::{cuts, decide_function, with_evidence, Decided};
use crate::algebra::certificate::Certificate;
use crate::algebra::sign::{chart_of, End, Interval, Real, Sign, SignChart};
use crate::decide::finding::{Finding, RationalEvidence};
use crate::decide::outcome::{Counterexample, Method, Outcome, Reverified};
use crate::derivation::Expression;
use crate::kernel::check::Fact;
use crate::kernel::{Rational, Var};
use std::collections::BTreeMap;

pub(super) fn decide(
    cx: &mut Context<'_>,
    function: &Expression,
    variable: &str,
    increasing: bool,
) -> Result<Outcome, Stop> {
    let f = cx.exact(function)?;
    let v = match cx.var(variable) {
        Some(v) if f.variables().contains(&v) => v,
        // Constant in the variable: it neither increases nor decreases.
        _ => {
            let v = cx.env.vars.intern(variable);
            let evidence = cx.evidence(&f.f);
            return Ok(constant(cx, function, &f, v, evidence));
        }
    };
    let slope = Exact {
        f: f.f.derivative(v),
        conditions: f.conditions.clone(),
    };
    let want = if increasing {
        Sign::NonNegative
    } else {
        Sign::NonPositive
    };
    let mut evidence = cx.evidence(&slope.f);
    evidence.decided = format!("d/d{variable} ({}) = {}", function.text, evidence.decided);
    if slope.f.is_zero() {
        return Ok(constant(cx, function, &f, v, evidence));
    }
    let names = &cx.env.vars;
    // The slope and the function in v alone, once a factor of one strict sign on the
    // box is divided out (μ in μ g(ν), μ > 0): decided by their sign charts in v.
    // The function's own numerator and denominator: a cancelled divisor is a removable
    // point, not a pole that breaks monotonicity.
    let reduced = (f.f.numerator().clone(), f.f.denominator().clone());
    let charted = cx
        .cleared_in(slope.cleared(), v)
        .zip(cx.cleared_in(reduced, v));
    let Some(((num, den), (f_num, f_den))) = charted else {
        // Several parameters: the sign of the derivative on the box, and a
        // denominator of one strict sign (no pole), each by the kernel if it can.
        let den = Exact {
            f: crate::algebra::RatFunc::from_poly(f.f.denominator()),
            conditions: Vec::new(),
        };
        let bx = cx.box_on(&den.variables());
        let pole_free = [Sign::Positive, Sign::Negative]
            .into_iter()
            .find_map(|s| Certificate::sign_by_coefficients(&den.f, &bx, s, names));
        return Ok(
            match decide_function(cx, (&slope, Some(&f)), want, evidence.clone())? {
                // Without a denominator certified free of zeros, a pole may break the
                // monotonicity whatever the derivative's sign: nothing is decided.
                Decided::Holds(_) if pole_free.is_none() => {
                    evidence.points.push(
                        "the denominator was not certified free of zeros on the box".to_owned(),
                    );
                    Outcome::undecided(Method::RationalFunction, 0)
                        .with_finding(Finding::RationalFunction(evidence))
                }
                // The kernel checked the derivative's sign and the denominator's.
                Decided::Holds(o) => *o,
                Decided::At(point) => two_points(cx, function, &f, v, &point, increasing, evidence),
                Decided::AtRoot { evidence, .. } => Outcome::undecided(Method::RationalFunction, 0)
                    .with_finding(Finding::RationalFunction(*evidence)),
            },
        );
    };
    let i = cx.interval(v);
    // Poles of the reduced function (a cancelled divisor is a removable point, not a
    // pole that breaks monotonicity).
    let (Some(chart), Some(of_f)) = (
        chart_of((&num, &den), v, &i),
        chart_of((&f_num, &f_den), v, &i),
    ) else {
        return Ok(Outcome::undecided(Method::RationalFunction, 0)
            .with_finding(Finding::RationalFunction(evidence)));
    };
    let name = names.name(v).to_owned();
    evidence.points = chart
        .cuts
        .iter()
        .filter(|c| !c.pole)
        .map(|c| format!("d/d{name} = 0 at {}", super::context::equated(&c.at, &name)))
        .chain(
            of_f.cuts
                .iter()
                .filter(|c| c.pole)
                .map(|c| format!("pole at {}", super::context::equated(&c.at, &name))),
        )
        .collect();
    let runs = runs(&chart, &of_f, want);
    let whole = runs.len() == 1 && runs[0].first == 0 && runs[0].last == chart.pieces.len() - 1;
    if whole && of_f.poles() == 0 {
        return Ok(
            match Certificate::sign_on_interval((&num, &den), v, &i, want, names) {
                Ok(_) => {
                    let fact = Fact::SignOnInterval {
                        variable: name.clone(),
                        cuts: cuts(&chart, &i),
                        reduced: Some(cx.reduced(&slope)),
                        function: Some(cx.reduced(&f)),
                        roots: cx.roots(),
                    };
                    with_evidence(cx.by_kernel(fact, None), evidence)
                }
                Err(_) => Outcome::undecided(Method::RationalFunction, 0)
                    .with_finding(Finding::RationalFunction(evidence)),
            },
        );
    }
    // A piece where the derivative has the wrong sign, or a pole: a counterexample.
    let bad = chart.pieces.iter().position(|p| !want.admits(p.sign()));
    let witness = match bad {
        Some(k) => {
            // The other parameters (in a factor of one sign) anywhere in the box.
            let s = chart.pieces[k].sample.clone();
            two_points(
                cx,
                function,
                &f,
                v,
                &cx.complete(&BTreeMap::from([(v, s)])),
                increasing,
                evidence.clone(),
            )
        }
        None => across_pole(cx, function, &f, v, &of_f, increasing, evidence.clone()),
    };
    if witness.verdict() != crate::derivation::Verdict::Fails || runs.is_empty() {
        return Ok(witness);
    }
    // Where it holds: the runs of admitted pieces, the first one certified on its
    // rational inner interval.
    let described: Vec<String> = runs.iter().map(|r| r.describe(&chart, &i, &name)).collect();
    evidence.holds_on = Some(described.join(" and "));
    let inner = runs[0].inner(&chart, &i);
    // Both parts go to the kernel: the sign on the run, with the run as the box, and
    // the counterexample outside it.
    let on_run = Certificate::sign_on_interval((&num, &den), v, &inner, want, names)
        .ok()
        .and_then(|_| {
            let mut domain = cx.domain.clone();
            domain.bounds.retain(|(n, _)| *n != name);
            domain.bounds.push((name.clone(), inner.clone()));
            let fact = Fact::SignOnInterval {
                variable: name.clone(),
                cuts: cuts(&chart, &inner),
                reduced: Some(cx.reduced(&slope)),
                function: Some(cx.reduced(&f)),
                roots: cx.roots(),
            };
            cx.by_kernel(fact, Some(&domain)).proofs().first().cloned()
        });
    let proofs = on_run.zip(witness.proofs().first().cloned());
    let mut out = Outcome::conditional(Method::RationalFunction, 1, proofs)
        .with_finding(Finding::RationalFunction(evidence));
    out.counterexample = witness.counterexample;
    Ok(out)
}

/// A maximal run of consecutive pieces where the derivative has the claimed sign,
/// joined at zeros of the derivative (not at poles of the function).
struct Run {
    first: usize,
    last: usize,
}

fn runs(chart: &SignChart, of_f: &SignChart, want: Sign) -> Vec<Run> {
    let poles: Vec<f64> = of_f
        .cuts
        .iter()
        .filter(|c| c.pole)
        .map(|c| c.at.approx())
        .collect();
    let mut out: Vec<Run> = Vec::new();
    for (k, p) in chart.pieces.iter().enumerate() {
        if !want.admits(p.sign()) {
            continue;
        }
        // Joined to the previous run when the cut between is a zero of the slope and
        // no pole of the function lies there.
        let joined = out.last().is_some_and(|r| {
            r.last + 1 == k && {
                let cut = &chart.cuts[k - 1];
                !cut.pole && !poles.iter().any(|x| (x - cut.at.approx()).abs() < 1e-12)
            }
        });
        if joined {
            out.last_mut().expect("joined").last = k;
        } else {
            out.push(Run { first: k, last: k });
        }
    }
    out
}

/// Where a run ends at `cut` (the domain's own end `outer` when there is none): open
/// at a pole, closed at an exact turning point, and at an isolated one the end of its
/// isolating interval inside the run: its low end when the run ends there
/// (`run_is_below`), its high end when the run starts there.
fn run_end(cut: Option<&crate::algebra::sign::Cut>, outer: &End, run_is_below: bool) -> End {
    match cut {
        None => outer.clone(),
        Some(c) => match &c.at {
            Real::Exact(r) if c.pole => End::Open(r.clone()),
            Real::Exact(r) => End::Closed(r.clone()),
            Real::Isolated { lo, hi } => End::Closed(if run_is_below { lo } else { hi }.clone()),
        },
    }
}

impl Run {
    fn start(&self, chart: &SignChart, i: &Interval) -> End {
        let cut = self.first.checked_sub(1).map(|j| &chart.cuts[j]);
        run_end(cut, &i.lo, false)
    }

    fn end(&self, chart: &SignChart, i: &Interval) -> End {
        run_end(chart.cuts.get(self.last), &i.hi, true)
    }

    /// The run with rational ends inside it (an isolated turning point replaced by the
    /// near end of its isolating interval).
    fn inner(&self, chart: &SignChart, i: &Interval) -> Interval {
        Interval {
            lo: self.start(chart, i),
            hi: self.end(chart, i),
        }
    }

    /// The run in words, turning points exact or to ten digits; strict at a pole.
    fn describe(&self, chart: &SignChart, i: &Interval, name: &str) -> String {
        let relation = |c: &crate::algebra::sign::Cut| if c.pole { "<" } else { "≤" };
        let lo = match self.first.checked_sub(1).map(|j| &chart.cuts[j]) {
            None => match &i.lo {
                End::Unbounded => String::new(),
                End::Open(a) => format!("{a} < "),
                End::Closed(a) => format!("{a} ≤ "),
            },
            Some(c) => format!("{} {} ", super::context::shown_real(&c.at), relation(c)),
        };
        let hi = match chart.cuts.get(self.last) {
            None => match &i.hi {
                End::Unbounded => String::new(),
                End::Open(b) => format!(" < {b}"),
                End::Closed(b) => format!(" ≤ {b}"),
            },
            Some(c) => format!(" {} {}", relation(c), super::context::shown_real(&c.at)),
        };
        format!("{lo}{name}{hi}")
    }
}

/// A function that does not change with the variable: two points with equal values.
fn constant(
    cx: &Context<'_>,
    function: &Expression,
    f: &Exact,
    v: Var,
    evidence: RationalEvidence,
) -> Outcome {
    let i = cx.interval(v);
    if i.is_empty() {
        return Outcome::undecided(Method::RationalFunction, 0);
    }
    let s = crate::algebra::sign::inner_point(&i);
    let mut point = BTreeMap::from([(v, s)]);
    for w in f.variables() {
        point.entry(w).or_insert_with(|| Rational::int(1));
    }
    let b = &point[&v] + &Rational::ratio(1, 1024).expect("nonzero");
    if !i.contains(&b) {
        return Outcome::undecided(Method::RationalFunction, 0)
            .with_finding(Finding::RationalFunction(evidence));
    }
    // The two equal values illustrate it; the kernel checks that the derivative is 0.
    let shown = pair(cx, function, f, v, &point, &b, None);
    let o = cx.by_kernel(Fact::Constant { roots: cx.roots() }, None);
    let o = match shown.counterexample {
        Some(c) if o.verdict() == crate::derivation::Verdict::Fails => o.with_counterexample(c),
        _ => o,
    };
    with_evidence(o, evidence)
}

/// Two points a < b near `point` in the variable where the function moves the wrong
/// way, found by halving the step until the exact values show it.
fn two_points(
    cx: &Context<'_>,
    function: &Expression,
    f: &Exact,
    v: Var,
    point: &BTreeMap<Var, Rational>,
    increasing: bool,
    evidence: RationalEvidence,
) -> Outcome {
    let i = cx.interval(v);
    // A point from the derivative's sign may leave the variable out (a slope free of
    // it, such as (μ − 1) in (μ − 1) x): any value of the variable will do there.
    let mut point = cx.complete(point);
    let a = point
        .entry(v)
        .or_insert_with(|| crate::algebra::sign::inner_point(&i))
        .clone();
    let point = &point;
    let mut step = Rational::ratio(1, 16).expect("nonzero");
    for _ in 0..60 {
        let b = &a + &step;
        if i.contains(&b) && wrong_way(f, point, v, &b, increasing) {
            return with_evidence(
                pair(cx, function, f, v, point, &b, Some(increasing)),
                evidence,
            );
        }
        step = &step * &Rational::ratio(1, 2).expect("nonzero");
    }
    Outcome::undecided(Method::RationalFunction, 0)
        .with_finding(Finding::RationalFunction(evidence))
}

/// Two points on either side of a pole of the function where it moves the wrong way.
fn across_pole(
    cx: &Context<'_>,
    function: &Expression,
    f: &Exact,
    v: Var,
    of_f: &SignChart,
    increasing: bool,
    evidence: RationalEvidence,
) -> Outcome {
    for (k, _) in of_f.cuts.iter().enumerate().filter(|(_, c)| c.pole) {
        let (a, b) = (&of_f.pieces[k].sample, &of_f.pieces[k + 1].sample);
        let at_a = cx.complete(&BTreeMap::from([(v, a.clone())]));
        if wrong_way(f, &at_a, v, b, increasing) {
            return with_evidence(
                pair(cx, function, f, v, &at_a, b, Some(increasing)),
                evidence,
            );
        }
    }
    Outcome::undecided(Method::RationalFunction, 0)
        .with_finding(Finding::RationalFunction(evidence))
}

/// Whether the function, exactly, moves against the claimed direction from `point` to
/// `point` with the variable moved up to `b`.
fn wrong_way(
    f: &Exact,
    point: &BTreeMap<Var, Rational>,
    v: Var,
    b: &Rational,
    increasing: bool,
) -> bool {
    let mut at_b = point.clone();
    at_b.insert(v, b.clone());
    match (f.eval(point), f.eval(&at_b)) {
        (Some(fa), Some(fb)) => (fb < fa && increasing) || (fb > fa && !increasing),
        _ => false,
    }
}

/// `fails`: the function at `point` and at `point` with the variable moved to `b`,
/// both values exact and confirmed by the interpreter, checked by the kernel as two
/// points where it moves against the claim (`None`: only the counterexample to show).
fn pair(
    cx: &Context<'_>,
    function: &Expression,
    f: &Exact,
    v: Var,
    point: &BTreeMap<Var, Rational>,
    b: &Rational,
    checked: Option<bool>,
) -> Outcome {
    let mut at_b = point.clone();
    at_b.insert(v, b.clone());
    let (Some(fa), Some(fb)) = (f.eval(point), f.eval(&at_b)) else {
        return Outcome::undecided(Method::RationalFunction, 0);
    };
    let confirmed = matches!(
        (cx.interpret(function, point), cx.interpret(function, &at_b)),
        (Ok(x), Ok(y)) if super::context::agrees(x, &fa) && super::context::agrees(y, &fb)
    );
    if !confirmed {
        return Outcome::undecided(Method::RationalFunction, 0);
    }
    let name = cx.name(v);
    let mut shown = cx.shown(point);
    shown.insert(name.clone(), format!("{} → {b}", point[&v]));
    let o = match checked {
        None => Outcome::fails_sampled(Method::RationalFunction, 1),
        Some(_) => {
            let fact = Fact::TwoPoints {
                a: point[&v].clone(),
                b: b.clone(),
                point: cx.full_point(point),
                roots: cx.roots(),
            };
            let o = cx.by_kernel(fact, None);
            if o.verdict() != crate::derivation::Verdict::Fails {
                return o;
            }
            o
        }
    };
    o.with_counterexample(Counterexample {
        chain: 1,
        equality: 1,
        lhs: format!("{} at {name} = {}", function.text, point[&v]),
        rhs: format!("{} at {name} = {b}", function.text),
        point: shown,
        lhs_value: Some(fa.to_string()),
        rhs_value: Some(fb.to_string()),
        reverified: Some(Reverified::FloatingPoint),
        ..Counterexample::default()
    })
}
