//! The exact strategy: expand both sides of every equality to canonical polynomials,
//! for every value of the free indices, and compare them structurally (after the
//! unit-normal reduction when the file declares a normal). Equal everywhere: `holds`.
//! Otherwise `fails`, with the index values, the nonzero difference and its value at
//! a rational point that satisfies the assumptions (a point on the unit sphere for
//! the normal).

use super::finding::{Expansion, Finding, Record, Unexpanded};
use super::indices::{self, Symbolic};
use super::outcome::{Counterexample, Method, Outcome};
use super::points::{point_where_differ, shown_point};
use super::proportional::{self, Reference};
use super::reverify;
use crate::algebra::certificate::{scaled_by, Difference, Identities};
use crate::algebra::sign::Interval;
use crate::algebra::{assignments, Quotient, RatFunc};
use crate::derivation::parametrisation::product_value;
use crate::derivation::{statement, Check, Strategy, Verdict};
use crate::eval::exact::env::{component_name, ExactEnv, Labeled};
use crate::kernel::check::{check as kernel_check, Checked, Evaluation, Fact, Factor};
use crate::kernel::{Poly, PolyError, Rational, Var, VarTable};
use crate::lang::check::letters;
use crate::lang::{Decls, Diagnostic};
use std::collections::BTreeMap;

/// How many terms of a difference polynomial a report shows.
const SHOWN_TERMS: usize = 12;

/// Terms shown per canonical polynomial, components kept per side, in a record.
const RECORDED_TERMS: usize = 24;
const RECORDED_COMPONENTS: usize = 27;

/// Decides a check exactly; with `keep`, the outcome records every side's expansion
/// as the decision computed it. An error means the check cannot be decided by this
/// strategy (e.g. a square root of a non-square) and is reported as bad input.
pub fn decide(decls: &Decls, check: &Check, keep: bool) -> Result<Outcome, Diagnostic> {
    let mut expansions = Vec::new();
    let record = if keep { Some(&mut expansions) } else { None };
    let mut outcome = decide_recording(decls, check, record, true)?;
    if keep {
        outcome.record = Some(Record {
            expansions,
            states: Vec::new(),
        });
    }
    Ok(outcome)
}

/// One side's expansion, as the record keeps it.
fn expansion(
    env: &ExactEnv<'_>,
    decls: &Decls,
    (chain, side): (usize, usize),
    text: &str,
    value: Result<&Labeled<Quotient>, Unexpanded>,
) -> Expansion {
    let (components, more) = match value {
        Err(why) => (Err(why), false),
        Ok(v) => {
            let all: Vec<Vec<usize>> = assignments(decls.dim, v.labels.len()).collect();
            let shown = all
                .iter()
                .take(RECORDED_COMPONENTS)
                .map(|idx| {
                    let at = v
                        .labels
                        .iter()
                        .zip(idx)
                        .map(|(&c, &i)| (c, i + 1))
                        .collect();
                    (
                        at,
                        v.tensor
                            .get(idx)
                            .display_truncated(&env.vars, RECORDED_TERMS),
                    )
                })
                .collect();
            (Ok(shown), all.len() > RECORDED_COMPONENTS)
        }
    };
    Expansion {
        chain: chain + 1,
        side: side + 1,
        text: text.trim().to_owned(),
        components,
        more,
    }
}

/// Every side of the chains from `from` on, expanded for the record after the
/// decision is made (so that the record never changes the decision).
fn expand_rest(
    env: &mut ExactEnv<'_>,
    decls: &Decls,
    check: &Check,
    from: usize,
    record: &mut Vec<Expansion>,
) {
    for (ci, chain) in check.chains.iter().enumerate().skip(from) {
        for (si, side) in chain.iter().enumerate() {
            let value = match &side.node {
                Err(e) => Err(Unexpanded::IllFormed(e.message.clone())),
                Ok(node) => env
                    .eval(node, &side.origin)
                    .map_err(|r| Unexpanded::Refused(r.diagnostic().message.clone())),
            };
            let e = expansion(
                env,
                decls,
                (ci, si),
                &side.text,
                value.as_ref().map_err(Clone::clone),
            );
            record.push(e);
        }
    }
}

/// The component route alone, without trying symbolic indices first: the oracle the
/// symbolic route is cross-checked against.
#[cfg(test)]
pub(crate) fn decide_by_components(decls: &Decls, check: &Check) -> Result<Outcome, Diagnostic> {
    decide_recording(decls, check, None, false)
}

/// `symbolic`: try symbolic indices first on a large tensor.
fn decide_recording(
    decls: &Decls,
    check: &Check,
    mut record: Option<&mut Vec<Expansion>>,
    symbolic: bool,
) -> Result<Outcome, Diagnostic> {
    // A verbatim transcription whose indices are ill-formed fails as printed.
    for (ci, chain) in check.chains.iter().enumerate() {
        for (si, side) in chain.iter().enumerate() {
            if let Err(e) = &side.node {
                let mut d = side.origin.diagnostic(e.span, e.message.clone());
                if let Some(h) = &e.help {
                    d = d.with_help(h.clone());
                }
                if let Some(record) = record.as_deref_mut() {
                    if let Ok(mut env) = ExactEnv::new(decls, &check.defs, &check.assumptions) {
                        expand_rest(&mut env, decls, check, 0, record);
                    }
                }
                let cx = Counterexample {
                    chain: ci + 1,
                    equality: si.max(1),
                    lhs: side.text.clone(),
                    rhs: String::new(),
                    ill_formed: Some(format!("{}: {}", d.location(), e.message)),
                    ..Counterexample::default()
                };
                let fact = Fact::IllFormed {
                    chain: ci,
                    side: si,
                };
                return by_kernel(decls, check, fact, (Method::IndexCheck, 1), |o| {
                    o.with_counterexample(cx)
                });
            }
        }
    }
    // A tensor statement is first tried in symbolic indices (`indices.rs`): equal
    // canonical forms find it without expanding a component, and the kernel then
    // checks it component by component. A scalar statement has one component; below
    // the threshold ε pairs are faster contracted by components, and `explain` (which
    // records) shows every component; the component route also decides whatever the
    // symbolic route leaves open.
    let size = largest_tensor(decls, check);
    let large = size > COMPONENT_ROUTE_UP_TO;
    if symbolic
        && matches!(check.strategy, Strategy::Exact { .. })
        && (large || (size > 1 && record.is_none()))
    {
        // The kernel checks what the symbolic route found, component by component: the
        // route does not prove it. What the kernel refuses, the component route decides.
        match indices::decide(decls, check, large) {
            Symbolic::Proved(_) => {
                if let Ok(outcome) = identity_by_kernel(decls, check) {
                    if !refused(&outcome) {
                        return Ok(outcome);
                    }
                }
            }
            Symbolic::Differs(d) => {
                if let Some(outcome) = constant_counterexample(decls, check, &d)? {
                    if !refused(&outcome) {
                        return Ok(outcome);
                    }
                }
            }
            Symbolic::Open => {}
        }
    }
    // A plain identity (no hypothesis, polynomial constraint or differential hypothesis)
    // is then offered to the kernel as it stands: where it holds, the component route's
    // own evaluation would only repeat the kernel's. The kernel's proof is taken only
    // when it compared polynomials alone (no square root taken, no constraint); else,
    // and where it refuses or the trial's work runs out, the component route decides,
    // finds the counterexample, and has the kernel check that. The trial is bounded so
    // that a statement past a resource limit does not spend the budget twice.
    let plain = matches!(check.strategy, Strategy::Exact { .. }) && !check.constrained();
    if symbolic && plain && record.is_none() {
        let trial =
            crate::kernel::interrupt::within(KERNEL_TRIAL, || identity_by_kernel(decls, check));
        // A statement the kernel cannot take, or a trial stopped: the component route
        // decides, and reports why.
        if let Ok(Ok(outcome)) = trial {
            let polynomial = |o: &Outcome| {
                let summary: Vec<&Checked> = o.proofs().iter().flat_map(|p| p.summary()).collect();
                matches!(&summary[..], [Checked::PolynomialIdentity { components, .. }] if *components > 0)
            };
            if outcome.verdict() == Verdict::Holds && polynomial(&outcome) {
                return Ok(outcome);
            }
        }
    }
    let mut env = match ExactEnv::on(
        decls,
        &check.defs,
        &check.assumptions,
        check.strategy.exact_domain(),
    ) {
        Ok(env) => env,
        // A substitution's value too large, or its root not certified on the box.
        Err(r) => match Finding::of_refusal(&r) {
            Some(f) => return Ok(Outcome::undecided(Method::Exact, 0).with_finding(f)),
            None => return Err(r.into()),
        },
    };
    // A counterexample's fields must take the values the differential hypotheses give
    // every derivative the statement reads.
    let differential = check.assumptions.iter().any(|a| {
        matches!(
            a.kind,
            crate::derivation::AssumptionKind::Differential { .. }
        )
    });
    if differential && env.complete_derivatives(check.derivative_order()).is_err() {
        return Ok(
            Outcome::undecided(Method::Exact, 0).with_finding(Finding::ResourceLimit {
                what: "the derivatives the differential hypotheses determine".to_owned(),
                at: String::new(),
                help: "split the statement, or lower the order of its derivatives".to_owned(),
            }),
        );
    }
    let normal = env.normal_vars().to_vec();
    // An identity (not a proportionality) takes the square root of a polynomial that
    // is no square as a variable of its own, compared modulo its square.
    if matches!(check.strategy, Strategy::Exact { .. }) {
        env.allow_algebraic_roots();
    }
    // The hypotheses on derived quantities, each as one quotient with its sign (a
    // square root they take is a variable of its own, as in the sides).
    let mut hypotheses = Vec::new();
    if let Strategy::Exact {
        hypotheses: stated, ..
    } = &check.strategy
    {
        for h in stated {
            let (l, r) = match (env.eval(&h.left, &h.origin), env.eval(&h.right, &h.origin)) {
                (Ok(l), Ok(r)) => (l, r),
                (Err(e), _) | (_, Err(e)) => match Finding::of_refusal(&e) {
                    Some(f) => return Ok(Outcome::undecided(Method::Exact, 0).with_finding(f)),
                    None => return Err(e.into()),
                },
            };
            let (Some(l), Some(r)) = (l.tensor.into_scalar(), r.tensor.into_scalar()) else {
                return Err(h
                    .origin
                    .diagnostic(Default::default(), "a hypothesis compares scalars"));
            };
            let mut work = crate::eval::exact::env::MAX_WORK;
            let mut ring = crate::algebra::quotient::Quotients {
                work_left: &mut work,
            };
            let difference =
                crate::algebra::einsum::Arithmetic::add(&mut ring, l, -r).map_err(|_| {
                    h.origin.diagnostic(
                        Default::default(),
                        "this hypothesis is too large to evaluate",
                    )
                })?;
            hypotheses.push((difference, h.sign));
        }
    }
    let mut identities = Identities::new(&normal).with_rules(env.rules());
    // A proportionality's factor (1 when the right side is zero everywhere: the left
    // must then be zero, and any nonzero factor states it).
    let mut factor: Option<RatFunc> =
        matches!(check.strategy, Strategy::Proportional { .. }).then(|| RatFunc::int(1));
    for (ci, chain) in check.chains.iter().enumerate() {
        let mut values = Vec::with_capacity(chain.len());
        for (si, side) in chain.iter().enumerate() {
            let node = side.node.as_ref().expect("ill-formed sides handled above");
            let value = match env.eval(node, &side.origin) {
                Ok(v) => v,
                // The statement is fine, but expanding it exactly costs more than the
                // checker allows, or needs a fact the kernel cannot certify. That
                // decides nothing about it.
                Err(r) => match Finding::of_refusal(&r) {
                    Some(f) => return Ok(Outcome::undecided(Method::Exact, 0).with_finding(f)),
                    None => return Err(r.into()),
                },
            };
            if let Some(record) = record.as_deref_mut() {
                record.push(expansion(&env, decls, (ci, si), &side.text, Ok(&value)));
            }
            values.push(value);
        }
        identities.set_rules(env.rules());
        for k in 0..chain.len() - 1 {
            let (l, r) = (&values[k], &values[k + 1]);
            let labels = union(&l.labels, &r.labels);
            // A proportionality fixes its factor first; its sides are one pair
            // (`load.rs`), so the comparison becomes `left = factor · right`.
            let mut reference = None;
            if matches!(check.strategy, Strategy::Proportional { .. }) {
                match proportional::reference(&env, decls.dim, (l, r), &labels) {
                    Err(why) => {
                        return Ok(Outcome::undecided(Method::Exact, 0).with_finding(
                            Finding::ResourceLimit {
                                what: why.to_string(),
                                at: chain[k]
                                    .origin
                                    .diagnostic(Default::default(), "")
                                    .location(),
                                help: "decide the claim as an identity with the factor written out"
                                    .to_owned(),
                            },
                        ))
                    }
                    // The right side is zero everywhere: proportional exactly when the
                    // left side is zero too, a plain identity.
                    Ok(None) => {}
                    Ok(Some(found)) => {
                        // λ = 0: no nonzero factor works. With a constant factor the
                        // reference shows it; with one of the parameters it does so
                        // only where the left side is zero everywhere, else the
                        // comparison with 0 finds where the left side is not zero.
                        if found.function.is_zero()
                            && (!proportional::reads_parameters(&env, (l, r))
                                || zero_everywhere(&normal, l, &labels, decls.dim))
                        {
                            return zero_factor(&env, decls, check, &found, (l, r));
                        }
                        factor = Some(found.function.clone());
                        identities = Identities::proportional(&normal, &found.function);
                        reference = Some(found);
                    }
                }
            }
            for a in assignments(decls.dim, labels.len()) {
                let assignment: Vec<(char, usize)> = labels.iter().copied().zip(a).collect();
                let (lp, rp) = (l.at(&assignment), r.at(&assignment));
                let compared = match identities.compare(lp, rp) {
                    Ok(c) => c,
                    // A size, not a property of the statement: undecided.
                    Err(e @ (PolyError::TooLarge | PolyError::TooManyProducts)) => {
                        let d = chain[k]
                            .origin
                            .diagnostic(Default::default(), e.to_string());
                        return Ok(Outcome::undecided(Method::Exact, identities.components())
                            .with_finding(Finding::ResourceLimit {
                                what: d.message.clone(),
                                at: d.location(),
                                help:
                                    "split the statement with definitions, or decide it numerically"
                                        .to_owned(),
                            }));
                    }
                    Err(e) => {
                        return Err(chain[k]
                            .origin
                            .diagnostic(Default::default(), e.to_string()))
                    }
                };
                let Some(diff) = compared else {
                    continue;
                };
                let scaled = reference.as_ref().map(|f| scaled_by(rp, &f.function));
                // Under constraints or square roots a side may be undefined on a whole
                // region: the point must make every side of every chain defined.
                let everywhere = if env.rules().is_empty() {
                    Vec::new()
                } else {
                    every_component(&mut env, check)
                };
                let (mut cx, point, mut values) = counterexample(
                    &env.vars,
                    (env.normal_vars(), env.rules(), &everywhere),
                    (env.domain(), &hypotheses),
                    lp,
                    scaled.as_ref().unwrap_or(rp),
                    &diff,
                );
                // Under polynomial constraints a difference modulo them is no
                // refutation without a point of the constraint set.
                if values.is_none() && !env.rules().is_empty() {
                    return Ok(Outcome::undecided(Method::Exact, identities.components())
                        .with_finding(Finding::NoConstrainedPoint {
                            difference: cx.difference.clone(),
                            tries: super::points::CONSTRAINED_TRIES,
                        }));
                }
                if values.is_none() && !hypotheses.is_empty() {
                    let stated = match &check.strategy {
                        Strategy::Exact { hypotheses, .. } => hypotheses
                            .iter()
                            .map(|h| h.text.as_str())
                            .collect::<Vec<_>>()
                            .join(", "),
                        _ => String::new(),
                    };
                    return Ok(Outcome::undecided(Method::Exact, identities.components())
                        .with_finding(Finding::NoPointUnderHypotheses {
                            difference: cx.difference.clone(),
                            hypotheses: stated,
                        }));
                }
                satisfies_assumptions(&env, &point, &chain[k].origin)?;
                // A factor of the parameters is fixed again at the parameter values of
                // the difference's point: both evaluations must share them.
                let reference = match reference.as_ref().map(|f| f.at_parameters_of(&env, &point, (l, r))) {
                    Some(None) => {
                        return Ok(Outcome::undecided(Method::Exact, identities.components())
                            .with_finding(Finding::ResourceLimit {
                                what: "the right side is zero where the factor would be fixed at the parameter values of the difference".to_owned(),
                                at: chain[k].origin.diagnostic(Default::default(), "").location(),
                                help: "decide the claim as an identity with the factor written out".to_owned(),
                            }))
                    }
                    Some(Some(moved)) => Some(moved),
                    None => None,
                };
                cx.chain = ci + 1;
                cx.reduced_on_sphere = diff
                    .numerator
                    .terms()
                    .any(|(m, _)| normal.iter().any(|&v| m.exponent(v) != 0));
                cx.reduced_by_constraints = !env.rules().is_empty();
                cx.equality = k + 1;
                cx.lhs = chain[k].text.trim().to_owned();
                cx.rhs = chain[k + 1].text.trim().to_owned();
                if let Some(found) = &reference {
                    // The factor's point is a second witness: confirm it too, and
                    // compare the interpreter's right side unscaled.
                    satisfies_assumptions(&env, &found.point, &chain[k].origin)?;
                    let shown = Counterexample {
                        chain: ci + 1,
                        equality: k + 1,
                        indices: index_values(&found.assignment),
                        ..Counterexample::default()
                    };
                    if let Err(why) = reverify::exact_counterexample(
                        decls,
                        check,
                        &env,
                        &found.point,
                        (&found.lhs, &found.rhs),
                        &shown,
                    ) {
                        return Ok(Outcome::undecided(Method::Exact, identities.components())
                            .with_finding(Finding::Unconfirmed {
                                difference: cx.difference.clone(),
                                why,
                            }));
                    }
                    let factor = found.factor();
                    cx.rhs = format!("{factor} · ({})", cx.rhs);
                    let (lq, rq) = (l.at(&found.assignment), r.at(&found.assignment));
                    let of_parameters = proportional::reads_parameters(&env, (l, r));
                    cx.factor = Some(Box::new(found.witness(&env, lq, rq, of_parameters)));
                    // The right side unscaled: its own value at the point (λ may be 0
                    // at the point's parameters).
                    let at = |v: Var| point.get(&v).cloned().unwrap_or_else(|| Rational::int(0));
                    values = values.and_then(|(lv, _)| rp.eval(&at).map(|rv| (lv, rv)));
                }
                cx.indices = index_values(&assignment);
                let (ln, rn) = (&chain[k].node, &chain[k + 1].node);
                let matching = matches!((ln, rn), (Ok(a), Ok(b)) if a.matches_free_indices(b));
                if !matching {
                    cx.ill_formed = Some(mismatch(l, r));
                }
                // A second evaluation of both sides at the point, by the interpreter.
                if let Some((lv, rv)) = &values {
                    match reverify::exact_counterexample(decls, check, &env, &point, (lv, rv), &cx)
                    {
                        Ok(how) => cx.reverified = Some(how),
                        Err(why) => {
                            if let Some(record) = record.as_deref_mut() {
                                expand_rest(&mut env, decls, check, ci + 1, record);
                            }
                            return Ok(Outcome::undecided(Method::Exact, identities.components())
                                .with_finding(Finding::Unconfirmed {
                                    difference: cx.difference.clone(),
                                    why,
                                }));
                        }
                    }
                }
                if let Some(record) = record.as_deref_mut() {
                    expand_rest(&mut env, decls, check, ci + 1, record);
                }
                let here = Evaluation {
                    chain: ci,
                    equality: k,
                    at: assignment.iter().map(|&(_, v)| v).collect(),
                    point: full_point(&env, &point),
                };
                let proportional = matches!(check.strategy, Strategy::Proportional { .. });
                let fact = match &reference {
                    // A right side zero everywhere: the left is not, here, so no
                    // nonzero factor works.
                    None if proportional => Fact::NotProportional {
                        first: here,
                        second: None,
                        roots: env.root_data(),
                    },
                    // No value could be computed (a power too large to evaluate):
                    // the kernel checks that the sides differ as functions.
                    None if values.is_none() => Fact::Differs {
                        at: Evaluation {
                            point: Vec::new(),
                            ..here
                        },
                        roots: env.root_data(),
                    },
                    None => Fact::Refutation {
                        at: here,
                        roots: env.root_data(),
                    },
                    Some(found) => Fact::NotProportional {
                        first: Evaluation {
                            chain: ci,
                            equality: k,
                            at: found.assignment.iter().map(|&(_, v)| v).collect(),
                            point: full_point(&env, &found.point),
                        },
                        second: Some(here),
                        roots: env.root_data(),
                    },
                };
                let (checks, unit) = (identities.components(), identities.used_unit_normal());
                return by_kernel(decls, check, fact, (Method::Exact, checks), |o| {
                    o.using_unit_normal(unit).with_counterexample(cx)
                });
            }
        }
    }
    let (checks, used_unit) = (identities.components(), identities.used_unit_normal());
    if let Some(radicands) = nowhere_defined(&env) {
        return Ok(Outcome::undecided(Method::Exact, checks).with_finding(
            Finding::NowhereDefined {
                radicands,
                tries: DEFINED_TRIES,
            },
        ));
    }
    if checks == 0 {
        return Ok(Outcome::undecided(Method::Exact, checks).with_finding(Finding::NothingCompared));
    }
    // The search compared every component and found no difference: the kernel checks
    // the identity again from the statement, with the square roots the search took.
    let roots = env.root_data();
    let fact = match factor {
        Some(f) => Fact::Proportional {
            factors: vec![match f.as_constant() {
                Some(q) => Factor::Constant(q),
                None => Factor::Function {
                    num: crate::kernel::statement::poly_data(f.numerator(), &env.vars),
                    den: crate::kernel::statement::poly_data(f.denominator(), &env.vars),
                },
            }],
            roots,
        },
        None => Fact::Identity { roots },
    };
    by_kernel(decls, check, fact, (Method::Exact, checks), |o| {
        o.using_unit_normal(used_unit)
    })
}

/// Every component of every side of every chain (those that can be evaluated): a
/// point under constraints or square roots must make all of them defined.
fn every_component(env: &mut ExactEnv<'_>, check: &Check) -> Vec<Quotient> {
    let mut out = Vec::new();
    for side in check.chains.iter().flatten() {
        if let Ok(node) = &side.node {
            if let Ok(v) = env.eval(node, &side.origin) {
                out.extend(v.tensor.components().iter().cloned());
            }
        }
    }
    out
}

/// Points tried for one where every square root taken as a variable is defined.
const DEFINED_TRIES: usize = 256;

/// The radicands of the square roots taken as variables when no point tried (small
/// rationals, from the one seeded generator) makes all of them positive at once: an
/// identity modulo their squares would then hold only vacuously. `None` when there is
/// no such root, or a point is found.
fn nowhere_defined(env: &ExactEnv<'_>) -> Option<Vec<String>> {
    let roots: Vec<&crate::kernel::rules::Rule> =
        env.rules().iter().filter(|r| r.nonnegative).collect();
    if roots.is_empty() {
        return None;
    }
    let mut vars: Vec<Var> = roots.iter().flat_map(|r| r.value.variables()).collect();
    vars.sort_unstable();
    vars.dedup();
    let mut rng = super::random::Rng::new(0x0DEF_14ED);
    for _ in 0..DEFINED_TRIES {
        let point: BTreeMap<Var, Rational> = vars
            .iter()
            .map(|&v| {
                let q = Rational::ratio(rng.small(), 1 + (rng.next_u64() % 4) as i64)
                    .expect("nonzero denominator");
                (v, q)
            })
            .collect();
        let at = |v: Var| point.get(&v).cloned().unwrap_or_else(|| Rational::int(0));
        if roots.iter().all(|r| {
            r.value
                .eval(&at)
                .is_some_and(|x| !x.is_negative() && !x.is_zero())
        }) {
            return None;
        }
    }
    Some(roots.iter().map(|r| r.value.display(&env.vars)).collect())
}

/// Whether the kernel refused the fact it was given.
fn refused(o: &Outcome) -> bool {
    matches!(o.finding, Some(Finding::KernelRefused { .. }))
}

/// The kernel's check of `check` as an identity, with no square root offered: the
/// components it compared, and whether one needed n·n = 1, are the evidence.
fn identity_by_kernel(decls: &Decls, check: &Check) -> Result<Outcome, Diagnostic> {
    let fact = Fact::Identity { roots: Vec::new() };
    by_kernel(decls, check, fact, (Method::Exact, 0), |mut o| {
        let compared = o
            .proofs()
            .iter()
            .flat_map(|p| p.summary())
            .find_map(|c| match c {
                Checked::PolynomialIdentity {
                    components,
                    modulo_unit_normal,
                    ..
                } => Some((*components, *modulo_unit_normal > 0)),
                _ => None,
            });
        (o.checks, o.used_unit_normal) = compared.unwrap_or((0, false));
        o
    })
}

/// The outcome of the kernel's check of `fact` against the statement of `check`: the
/// proof's verdict (`finish` adds its evidence), or `undecided` with the kernel's
/// reason for refusing it.
fn by_kernel(
    decls: &Decls,
    check: &Check,
    fact: Fact,
    (method, checks): (Method, usize),
    finish: impl FnOnce(Outcome) -> Outcome,
) -> Result<Outcome, Diagnostic> {
    let statement = statement::equalities(decls, check)?;
    Ok(match kernel_check(statement, fact) {
        Ok(proof) => finish(Outcome::proved(method, checks, proof)),
        Err(why) => Outcome::undecided(method, checks).with_finding(Finding::KernelRefused {
            why: why.to_string(),
        }),
    })
}

/// Every variable the search's environment knows, with its value at `point` (0 where
/// the point leaves it out, as in the search's evaluation), each component the
/// assumptions determine at its value in the free ones; the normal only where the
/// point gives it.
pub(crate) fn full_point(
    env: &ExactEnv<'_>,
    point: &BTreeMap<Var, Rational>,
) -> Vec<(String, Rational)> {
    let normal = env.normal_vars();
    let mut values: BTreeMap<String, Rational> = (0..env.vars.len() as Var)
        .filter(|v| point.contains_key(v) || !normal.contains(v))
        .map(|v| {
            let x = point.get(&v).cloned().unwrap_or_else(|| Rational::int(0));
            (env.vars.name(v).to_owned(), x)
        })
        .collect();
    if let Some(p) = env.parametrisation() {
        for d in p.dependents() {
            let at = |(s, i): &(String, Vec<usize>)| {
                values
                    .get(&component_name(s, i))
                    .cloned()
                    .unwrap_or_else(|| Rational::int(0))
            };
            let linear = d.terms.iter().map(|(c, q)| *q * &at(c));
            let products = d
                .products
                .iter()
                .map(|(p, q)| *q * &product_value(p, Rational::int(1), at));
            let value = linear
                .chain(products)
                .fold(d.constant.clone(), |acc, x| &acc + &x);
            let (symbol, idx) = d.component;
            values.insert(component_name(symbol, idx), value);
        }
    }
    values.into_iter().collect()
}

/// The counterexample of a constant difference the symbolic route found, as the
/// component route reports it (the same component, values and count), re-verified by
/// the interpreter. `None` when the interpreter does not confirm it: the component
/// route then decides.
pub(crate) fn constant_counterexample(
    decls: &Decls,
    check: &Check,
    d: &indices::Difference,
) -> Result<Option<Outcome>, Diagnostic> {
    let env = ExactEnv::new(decls, &check.defs, &check.assumptions)?;
    let chain = &check.chains[d.chain];
    let point = BTreeMap::new();
    satisfies_assumptions(&env, &point, &chain[d.equality].origin)?;
    let difference = Difference {
        numerator: Poly::constant(&d.lhs - &d.rhs),
        denominator: Vec::new(),
    };
    let mut cx = Counterexample {
        chain: d.chain + 1,
        equality: d.equality + 1,
        lhs: chain[d.equality].text.trim().to_owned(),
        rhs: chain[d.equality + 1].text.trim().to_owned(),
        indices: index_values(&d.at),
        difference: difference.display(&env.vars, SHOWN_TERMS),
        lhs_value: Some(d.lhs.to_string()),
        rhs_value: Some(d.rhs.to_string()),
        ..Counterexample::default()
    };
    match reverify::exact_counterexample(decls, check, &env, &point, (&d.lhs, &d.rhs), &cx) {
        Ok(how) => cx.reverified = Some(how),
        Err(_) => return Ok(None),
    }
    let fact = Fact::Refutation {
        at: Evaluation {
            chain: d.chain,
            equality: d.equality,
            at: {
                let mut at = d.at.clone();
                at.sort_unstable();
                at.iter().map(|&(_, v)| v).collect()
            },
            point: Vec::new(),
        },
        roots: Vec::new(),
    };
    by_kernel(decls, check, fact, (Method::Exact, d.components), |o| {
        o.with_counterexample(cx)
    })
    .map(Some)
}

/// The kernel's work (in its ticks: product rows and charged limb products) that a
/// plain identity is offered before the component route decides it: twice the largest
/// identity the examples and tests prove (243,613 ticks for a Hessian in
/// `tests/soundness/second-derivatives.toml`; at most 5,580 for a claim of the paper),
/// and a third or less of what a statement past the work budget spends (1.5 to 34
/// million in `tests/soundness/resource-limits.toml`).
const KERNEL_TRIAL: u64 = 500_000;

/// Components beyond which an identity with ε is first tried in symbolic indices: 243
/// is rank 5 in 3D (the largest tensor of the paper, the odd averages), rank 7 in 2D.
/// Up to there the component route contracts ε pairs faster than the algebra.
const COMPONENT_ROUTE_UP_TO: usize = 243;

/// The most components a side of `check` has: d to the number of its free indices.
fn largest_tensor(decls: &Decls, check: &Check) -> usize {
    check
        .chains
        .iter()
        .flatten()
        .filter_map(|side| side.node.as_ref().ok())
        .map(|node| decls.dim.saturating_pow(node.free.len() as u32))
        .max()
        .unwrap_or(1)
}

/// A counterexample point must satisfy every assumption; a point that does not is a
/// bug in the checker, reported as such and never as a verdict.
fn satisfies_assumptions(
    env: &ExactEnv<'_>,
    point: &BTreeMap<Var, Rational>,
    origin: &crate::lang::Origin,
) -> Result<(), Diagnostic> {
    let Some(p) = env.parametrisation() else {
        return Ok(());
    };
    // Variables the point leaves out are 0, as in the evaluation of the sides.
    let value = |(s, idx): &(String, Vec<usize>)| {
        env.vars
            .lookup(&component_name(s, idx))
            .and_then(|v| point.get(&v).cloned())
            .unwrap_or_else(|| Rational::int(0))
    };
    if p.holds_exactly(value) {
        Ok(())
    } else {
        Err(origin.diagnostic(
            Default::default(),
            "internal error: a counterexample violates the assumptions; no verdict is given",
        ))
    }
}

/// Index values for a report, 1-based.
fn index_values(assignment: &[(char, usize)]) -> BTreeMap<String, usize> {
    assignment
        .iter()
        .map(|&(c, v)| (c.to_string(), v + 1))
        .collect()
}

/// `factor · q`.
/// Whether every component of `side` is zero (modulo n·n = 1).
fn zero_everywhere(normal: &[Var], side: &Labeled<Quotient>, labels: &[char], dim: usize) -> bool {
    let zero = Quotient::default();
    let mut ids = Identities::new(normal);
    for a in assignments(dim, labels.len()) {
        let assignment: Vec<(char, usize)> = labels.iter().copied().zip(a).collect();
        if !matches!(ids.compare(side.at(&assignment), &zero), Ok(None)) {
            return false;
        }
    }
    true
}

/// A proportionality refuted at its reference: the left side is 0 where the right
/// side is not, so no nonzero factor works. (Its one pair of sides is already in the
/// record, if one is kept.)
fn zero_factor(
    env: &ExactEnv<'_>,
    decls: &Decls,
    check: &Check,
    found: &Reference,
    (l, r): (&Labeled<Quotient>, &Labeled<Quotient>),
) -> Result<Outcome, Diagnostic> {
    let chain = &check.chains[0];
    satisfies_assumptions(env, &found.point, &chain[0].origin)?;
    let (lq, rq) = (l.at(&found.assignment), r.at(&found.assignment));
    let mut cx = Counterexample {
        chain: 1,
        equality: 1,
        lhs: chain[0].text.trim().to_owned(),
        rhs: chain[1].text.trim().to_owned(),
        indices: index_values(&found.assignment),
        point: shown_point(&env.vars, lq, rq, &found.point),
        lhs_value: Some(found.lhs.to_string()),
        rhs_value: Some(found.rhs.to_string()),
        aux: BTreeMap::from([(
            "factor".to_owned(),
            "left/right is 0 here, and the factor must be nonzero".to_owned(),
        )]),
        ..Counterexample::default()
    };
    match reverify::exact_counterexample(
        decls,
        check,
        env,
        &found.point,
        (&found.lhs, &found.rhs),
        &cx,
    ) {
        Ok(how) => cx.reverified = Some(how),
        Err(why) => {
            return Ok(
                Outcome::undecided(Method::Exact, 0).with_finding(Finding::Unconfirmed {
                    difference: String::new(),
                    why,
                }),
            )
        }
    }
    let fact = Fact::NotProportional {
        first: Evaluation {
            chain: 0,
            equality: 0,
            at: found.assignment.iter().map(|&(_, v)| v).collect(),
            point: full_point(env, &found.point),
        },
        second: None,
        roots: env.root_data(),
    };
    by_kernel(decls, check, fact, (Method::Exact, 0), |o| {
        o.with_counterexample(cx)
    })
}

fn union(a: &[char], b: &[char]) -> Vec<char> {
    let mut u: Vec<char> = a.iter().chain(b).copied().collect();
    u.sort_unstable();
    u.dedup();
    u
}

fn mismatch(l: &Labeled<Quotient>, r: &Labeled<Quotient>) -> String {
    format!(
        "the sides have different free indices ({} on the left, {} on the right); read as an identity for all values of {}",
        letters(&l.labels),
        letters(&r.labels),
        letters(&union(&l.labels, &r.labels))
    )
}

fn counterexample(
    names: &VarTable,
    (normal, rules, everywhere): (&[Var], &[crate::kernel::rules::Rule], &[Quotient]),
    domain: (&[(Var, Interval)], &[super::points::Hypothesis]),
    lhs: &Quotient,
    rhs: &Quotient,
    diff: &Difference,
) -> (
    Counterexample,
    BTreeMap<Var, Rational>,
    Option<(Rational, Rational)>,
) {
    let mut cx = Counterexample {
        difference: diff.display(names, SHOWN_TERMS),
        ..Counterexample::default()
    };
    let found = if rules.is_empty() {
        point_where_differ(normal, lhs, rhs, domain)
    } else {
        super::points::point_where_differ_constrained(rules, normal, (lhs, rhs, everywhere), domain)
    };
    match found {
        Some((point, l, r)) => {
            cx.point = shown_point(names, lhs, rhs, &point);
            // The hypotheses are part of the statement: their variables are shown too,
            // so that the reader can see that they hold at the point.
            let read: Vec<Var> = domain.1.iter().flat_map(|(q, _)| q.variables()).collect();
            cx.point.extend(
                point
                    .iter()
                    .filter(|(v, _)| read.contains(v))
                    .map(|(&v, q)| (names.name(v).to_owned(), q.to_string())),
            );
            // Under constraints the point's other coordinates are not 0: every one is
            // shown (the normal aside), so that the point can be checked against them.
            if !rules.is_empty() {
                cx.point.extend(
                    point
                        .iter()
                        .filter(|(v, _)| !normal.contains(v))
                        .map(|(&v, q)| (names.name(v).to_owned(), q.to_string())),
                );
            }
            cx.lhs_value = Some(l.to_string());
            cx.rhs_value = Some(r.to_string());
            (cx, point, Some((l, r)))
        }
        None => (cx, BTreeMap::new(), None),
    }
}
