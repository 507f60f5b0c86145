//! Numeric strategies: seeded random states evaluated in f64 (equalities and
//! inequalities, with a domain search for conditional claims), num-dual gradients
//! against closed forms and central differences, and num-dual Hessians for convexity.
//!
//! The tolerances (defined in [`crate::tolerance`]) are applied as follows:
//! - equality: |l − r| ≤ [`TOL`]·(1 + |l| + |r|); inequality l ≤ r: l − r ≤ TOL·(1 + |l| + |r|);
//! - num-dual gradient vs closed form: [`TOL`] relative, per component; vs a central
//!   difference along a direction v with v_k = ±(½ to 1)·(1 + |x_k|) and step
//!   [`FD_STEP`]: [`FD_TOL`] relative to 1 + Σ|∂_k F v_k| + |the difference| (truncation
//!   O(h²) plus rounding O(ε/h), both far below it for the smooth functions checked
//!   here); where that or a closed form disagrees, per-component differences with step
//!   h = [`FD_STEP`]·(1 + |x_k|) decide, as before;
//! - Hessian: the smallest eigenvalue must be ≥ −TOL·(1 + max |λ|).
//!
//! NaN or infinity never passes: a non-finite value is a violation unless the sample
//! lies on the declared singular set, which is excluded and counted in the evidence.

use super::enclosures::Enclosures;
use super::finding::{Finding, Point, Unresolved};
use super::outcome::{
    Counterexample, Measure, Method, NumericEvidence, Outcome, Reverified, SearchEvidence,
};
use super::reverify::ExactCache;
use super::sampler::{relation_holds, Sampler, Sink};
use super::{reverify, search};
use crate::algebra::{assignments, Tensor};
use crate::derivation::parametrisation::Component;
use crate::derivation::{Check, Expression, GradientConvention, Relation, Sampling, Strategy};
use crate::digits::{self, significant};
use crate::eval::exact::env::component_name;
use crate::eval::quadrature::{self, Level};
use crate::eval::real::{component_pairs, Labeled};
use crate::eval::state::State;
use crate::lang::{Decls, Diagnostic};
pub use crate::tolerance::SINGULAR_EPS;
use crate::tolerance::{
    FD_STEP, FD_TOL, QUADRATURE_CLEAR, QUADRATURE_MAX, SECOND_DIFFERENCE_STEP,
    SECOND_DIFFERENCE_TOL,
};
use nalgebra::{DVector, SymmetricEigen};
use num_dual::{hessian, Dual2DVec64, DualNum, DualSVec64};
use rustc_hash::FxHashMap as HashMap;
use std::collections::BTreeMap;

pub use crate::tolerance::TOL;

/// What one state says about a statement.
enum Judged {
    /// No relation is violated (beyond the tolerance and the quadrature's error).
    Satisfied,
    Violated(Counterexample),
    /// The sides differ by more than the tolerance but not clearly more than the
    /// adaptive averages' error, or that error is above [`QUADRATURE_MAX`]: the reason
    /// and the state.
    Unresolved(Unresolved, Point),
    /// A side is undefined at the state (a divisor is zero, a function is outside its
    /// domain): where and why.
    Undefined(Diagnostic),
}

/// Why a side has no value at a state where it is defined but overflows `f64`.
const OVERFLOW: &str = "the value is not finite in floating point here (an overflow)";

/// Checks every chain at one state; the first violation as a counterexample.
///
/// When the statement takes averages of arguments that are not polynomials in n
/// (adaptive quadrature), the sides are evaluated again at a coarser tolerance on a
/// different partition, and, when the two disagree beyond [`TOL`]/10, a third time at
/// the fine tolerance on a third partition. Each comparison keeps the two residuals
/// that agree best: the error estimate is their difference plus the fine averages' own
/// estimate, and a residual above the tolerance counts as a violation only beyond
/// [`QUADRATURE_CLEAR`] times it.
fn check_state(
    sampler: &Sampler<'_>,
    exact: &ExactCache<'_>,
    state: &State,
    relation: Relation,
    largest: &mut f64,
    quadrature_error: &mut f64,
) -> Result<Judged, Diagnostic> {
    let d = sampler.decls.dim;
    // Every comparison's (labels, index values, left, right) at one level.
    type Pairs = Vec<(Vec<char>, Vec<usize>, f64, f64)>;
    // The outer error is malformed input; the inner one, a side undefined at the state.
    type Compared = Result<Vec<Vec<Pairs>>, Diagnostic>;
    let compare = |level: Level| -> Result<Compared, Diagnostic> {
        let mut chains = Vec::new();
        for chain in &sampler.check.chains {
            let mut values = Vec::new();
            for s in chain {
                let node = s
                    .node
                    .as_ref()
                    .map_err(|e| s.origin.diagnostic(e.span, e.message.clone()))?;
                match sampler.eval_at(&state.symbols, node, &state.n, level) {
                    // A value that is not finite (an overflow, inf − inf) is no value
                    // of the expression in floating point: the state is stepped off like
                    // one where the side is undefined, never a counterexample.
                    Ok(v) if v.tensor.components().iter().any(|x: &f64| !x.is_finite()) => {
                        return Ok(Err(s.origin.diagnostic(node.span, OVERFLOW)))
                    }
                    Ok(v) => values.push(v),
                    Err(r) if r.pointwise => {
                        return Ok(Err(s.origin.diagnostic(r.span, r.message)))
                    }
                    Err(r) => return Err(s.origin.diagnostic(r.span, r.message)),
                }
            }
            let links = values
                .windows(2)
                .map(|w| {
                    let (labels, pairs) = component_pairs(d, &w[0], &w[1]);
                    pairs
                        .into_iter()
                        .map(|(a, l, r)| (labels.clone(), a, l, r))
                        .collect()
                })
                .collect();
            chains.push(links);
        }
        Ok(Ok(chains))
    };
    let residual = |p: &(Vec<char>, Vec<usize>, f64, f64)| relation_holds(relation, p.2, p.3).1;
    sampler.fine.reset();
    let fine = match compare(Level::Fine)? {
        Ok(v) => v,
        Err(undefined) => return Ok(Judged::Undefined(undefined)),
    };
    let mut others: Vec<Vec<Vec<Pairs>>> = Vec::new();
    if sampler.fine.used() {
        sampler.coarse.reset();
        let coarse = match compare(Level::Coarse)? {
            Ok(v) => v,
            Err(undefined) => return Ok(Judged::Undefined(undefined)),
        };
        let disagree = fine
            .iter()
            .flatten()
            .zip(coarse.iter().flatten())
            .any(|(f, c)| {
                // NaN residuals never agree.
                let agree = |x, y| (residual(x) - residual(y)).abs() < TOL / 10.0;
                f.iter().zip(c).any(|(x, y)| !agree(x, y))
            });
        others.push(coarse);
        if disagree {
            sampler.arbiter.reset();
            match compare(Level::Arbiter)? {
                Ok(v) => others.push(v),
                Err(undefined) => return Ok(Judged::Undefined(undefined)),
            }
        }
    }
    let own_error = sampler
        .fine
        .worst_error()
        .max(sampler.arbiter.worst_error());
    let mut enclosures = Enclosures::new(sampler, state);
    let mut rounding = false;
    for (ci, chain) in sampler.check.chains.iter().enumerate() {
        for k in 0..chain.len().saturating_sub(1) {
            for (p, fp) in fine[ci][k].iter().enumerate() {
                let (labels, a, mut l, mut r) = fp.clone();
                let (mut ok, mut res) = relation_holds(relation, l, r);
                if !others.is_empty() {
                    // The best-agreeing pair among (fine, coarse), (fine, arbiter) and
                    // (arbiter, coarse); the reported values are a fine-tolerance pair's.
                    let coarse = &others[0][ci][k][p];
                    let mut best = ((res - residual(coarse)).abs(), fp.clone());
                    if let Some(arbiter) = others.get(1).map(|o| &o[ci][k][p]) {
                        for (gap, kept) in [
                            ((res - residual(arbiter)).abs(), fp),
                            ((residual(arbiter) - residual(coarse)).abs(), arbiter),
                        ] {
                            if gap < best.0 {
                                best = (gap, kept.clone());
                            }
                        }
                    }
                    let (gap, kept) = best;
                    (l, r) = (kept.2, kept.3);
                    (ok, res) = relation_holds(relation, l, r);
                    let error = gap + own_error / (1.0 + l.abs() + r.abs());
                    *quadrature_error = quadrature_error.max(error);
                    if error.is_nan() || error > QUADRATURE_MAX {
                        let converged = sampler.fine.converged() && sampler.coarse.converged();
                        return Ok(Judged::Unresolved(
                            Unresolved::QuadratureError {
                                error,
                                limit: QUADRATURE_MAX,
                                budget: (!converged).then_some(quadrature::MAX_EVALUATIONS),
                            },
                            sampler.describe(state),
                        ));
                    }
                    if res.is_finite() && res > TOL {
                        if res <= TOL + error {
                            ok = true;
                        } else if res <= TOL + QUADRATURE_CLEAR * error {
                            return Ok(Judged::Unresolved(
                                Unresolved::WithinError {
                                    chain: ci + 1,
                                    residual: res,
                                    clear: QUADRATURE_CLEAR,
                                    error,
                                },
                                sampler.describe(state),
                            ));
                        }
                    }
                }
                if !ok && others.is_empty() {
                    // A difference that cancellation can explain is no violation: where
                    // the sides' interval enclosures admit the relation, floating point
                    // cannot tell at this state (`interval`), which is no evidence either
                    // way (the claim is then undecided unless a violation is confirmed
                    // elsewhere); where no enclosure is computed, the floating-point
                    // judgement stands and the second evaluation decides.
                    let at: Vec<(char, usize)> =
                        labels.iter().copied().zip(a.iter().copied()).collect();
                    // Polynomial sides are judged exactly at the rational point the
                    // state denotes: satisfied there, the state is evidence like any.
                    let exact = exact.holds_at(state, relation, (ci, k), &at);
                    match exact {
                        Some(true) => continue,
                        // Violated exactly: a violation (confirmed again below).
                        Some(false) => {}
                        None => {
                            if let Ok((li, ri, _)) = enclosures.pair(ci, k, &at) {
                                if li.may_satisfy(relation, &ri) {
                                    rounding = true;
                                    continue;
                                }
                            }
                        }
                    }
                }
                *largest = largest.max(res);
                if !ok {
                    sampler.verify_state(state)?;
                    return Ok(Judged::Violated(Counterexample {
                        chain: ci + 1,
                        equality: k + 1,
                        lhs: chain[k].text.trim().to_owned(),
                        rhs: chain[k + 1].text.trim().to_owned(),
                        indices: labels
                            .iter()
                            .zip(&a)
                            .map(|(c, v)| (c.to_string(), v + 1))
                            .collect(),
                        point: sampler.describe(state),
                        lhs_value: Some(significant(l, digits::VALUE)),
                        rhs_value: Some(significant(r, digits::VALUE)),
                        ..Counterexample::default()
                    }));
                }
            }
        }
    }
    if rounding {
        sampler
            .within_rounding
            .set(sampler.within_rounding.get() + 1);
    }
    Ok(Judged::Satisfied)
}

/// The first side of a check as an expression (the anchor of sampling errors).
fn first_side(check: &Check) -> Result<Expression, Diagnostic> {
    let side = check
        .chains
        .first()
        .and_then(|c| c.first())
        .expect("numeric checks have sides");
    side.expression()
        .map_err(|e| side.origin.diagnostic(e.span, e.message.clone()))
}

/// The evidence of a sampled verdict; `derivatives` says the singular set is where the
/// function is not differentiable.
fn sampled_evidence(
    sampling: &Sampling,
    largest: f64,
    residual: Measure,
    excluded: usize,
    tolerance: String,
    derivatives: bool,
) -> NumericEvidence {
    let why = if derivatives {
        " (not differentiable there)"
    } else {
        ""
    };
    NumericEvidence {
        samples: sampling.samples,
        seed: sampling.seed,
        largest_residual: largest,
        residual,
        excluded,
        exclusion: sampling
            .singular
            .as_ref()
            .map(|s| format!("|{}| < {SINGULAR_EPS:e}{why}", s.text)),
        undefined: 0,
        rounding: 0,
        domain: None,
        tolerance,
        search: None,
    }
}

/// Keeps the `WORST_STARTS` states of largest margin.
fn keep_worst(worst: &mut Vec<(f64, State)>, margin: f64, state: State) {
    worst.push((margin, state));
    worst.sort_by(|a, b| b.0.total_cmp(&a.0));
    worst.truncate(search::WORST_STARTS);
}

/// What sampling found: nothing, a violation, a state it could not judge, or sides
/// undefined on a set of positive measure (why, and the state).
enum Found {
    Nothing,
    Violation(Box<State>, Counterexample),
    Unresolved(Unresolved, Point),
    Undefined(Diagnostic, Point),
}

/// Random samples, then the adversarial search, inside `extra` (a conditional
/// claim's domain); the largest residual, the worst states and the quadrature's
/// largest error estimate are accumulated in `tally`.
fn sample_and_search(
    sampler: &mut Sampler<'_>,
    relation: Relation,
    extra: &[crate::derivation::Constraint],
    tally: &mut Tally,
) -> Result<(Found, Option<SearchEvidence>), Diagnostic> {
    let mut worst = Vec::new();
    // Random samples where floating point could not tell whether the relation holds
    // (see `check_state`). Sampling cannot see a set much smaller than one sample in a
    // hundred, and such states are no different: past that share they mark a region
    // floating point cannot judge, and the claim is not decided unless a violation is
    // confirmed. Fewer, and those met by the search or next to a point where a side is
    // undefined (where it pushes towards cancellation on purpose), are excluded and
    // counted.
    let mut random_rounding: (usize, Option<Point>) = (0, None);
    // The exact route at sampled states (polynomial sides), built when first needed.
    let exact = ExactCache::new(sampler.decls, sampler.check);
    // The first state where a side is undefined on a set of positive measure: the
    // claim is not decided there, but a violation at a later sample, where both sides
    // are defined, is a counterexample all the same (whichever the draws meet first).
    let mut undefined_at = None;
    for _ in 0..sampler.sampling.samples {
        let mut state = sampler.next(extra, &mut tally.excluded)?;
        let mut margin = f64::NEG_INFINITY;
        let before = sampler.within_rounding.get();
        let mut judged = check_state(
            sampler,
            &exact,
            &state,
            relation,
            &mut margin,
            &mut tally.quadrature,
        )?;
        if sampler.within_rounding.get() > before {
            random_rounding.0 += 1;
            random_rounding
                .1
                .get_or_insert_with(|| sampler.describe(&state));
        }
        // Undefined at a random state: on a set of measure zero (a zero of a divisor)
        // when a state next to it is defined, which then takes its place; else on a
        // set of positive measure, and the claim is not decided.
        if let Judged::Undefined(why) = judged {
            let mut moved = None;
            for near in search::nearby(sampler, &state, extra)? {
                let mut m = f64::NEG_INFINITY;
                let j = check_state(
                    sampler,
                    &exact,
                    &near,
                    relation,
                    &mut m,
                    &mut tally.quadrature,
                )?;
                if !matches!(j, Judged::Undefined(_)) {
                    moved = Some((near, j, m));
                    break;
                }
            }
            let Some((near, j, m)) = moved else {
                undefined_at.get_or_insert_with(|| (why, sampler.describe(&state)));
                continue;
            };
            tally.undefined += 1;
            (state, judged, margin) = (near, j, m);
        }
        tally.largest = tally.largest.max(margin);
        match judged {
            Judged::Satisfied => keep_worst(&mut worst, margin, state),
            Judged::Violated(cx) => return Ok((confirmed(sampler, state, relation, cx), None)),
            Judged::Unresolved(why, at) => return Ok((Found::Unresolved(why, at), None)),
            Judged::Undefined(_) => unreachable!("stepped off above"),
        }
    }
    if let Some((why, at)) = undefined_at {
        return Ok((Found::Undefined(why, at), None));
    }
    let check = sampler.check;
    let nodes = check
        .chains
        .iter()
        .flatten()
        .filter_map(|s| s.node.as_ref().ok())
        .chain(check.strategy.expressions().into_iter().map(|e| &e.node))
        .chain(extra.iter().flat_map(|c| [&c.lhs.node, &c.rhs.node]));
    let relevant = search::components_read(sampler, nodes);
    let starts: Vec<State> = worst.iter().map(|(_, s)| s.clone()).collect();
    let budget = search::EVALUATIONS_PER_SAMPLE * sampler.sampling.samples;
    let mut unresolved = None;
    let mut quadrature = tally.quadrature;
    let mut undefined = 0;
    let result = search::worst_case(
        sampler,
        &starts,
        extra,
        relevant,
        budget,
        &mut |s, state| {
            let mut m = f64::NEG_INFINITY;
            let stop = match check_state(s, &exact, state, relation, &mut m, &mut quadrature)? {
                Judged::Satisfied => false,
                Judged::Violated(_) => !m.is_finite() || m > crate::tolerance::SEARCH_CONFIRM,
                Judged::Unresolved(why, at) => {
                    unresolved = Some((why, at));
                    true
                }
                // Undefined here: the search does not move here (it steps off).
                Judged::Undefined(_) => {
                    undefined += 1;
                    m = f64::NEG_INFINITY;
                    false
                }
            };
            Ok((!stop).then_some(m))
        },
    )?;
    tally.quadrature = quadrature;
    tally.undefined += undefined;
    let evidence = SearchEvidence {
        starts: result.starts,
        evaluations: result.evaluations,
        worst_margin: result.worst,
        at: result
            .worst_state
            .as_ref()
            .map(|s| sampler.describe(s))
            .unwrap_or_default(),
    };
    if let Some(why) = unresolved {
        return Ok((Found::Unresolved(why.0, why.1), Some(evidence)));
    }
    let found = match result.violation {
        Some(state) => {
            let mut m = f64::NEG_INFINITY;
            match check_state(
                sampler,
                &exact,
                &state,
                relation,
                &mut m,
                &mut tally.quadrature,
            )? {
                Judged::Violated(cx) => {
                    tally.largest = tally.largest.max(m);
                    confirmed(sampler, state, relation, cx)
                }
                Judged::Unresolved(why, at) => Found::Unresolved(why, at),
                Judged::Undefined(why) => Found::Undefined(why, sampler.describe(&state)),
                Judged::Satisfied => Found::Nothing,
            }
        }
        None => Found::Nothing,
    };
    if let (Found::Nothing, (n, Some(at))) = (&found, random_rounding) {
        if 100 * n > sampler.sampling.samples {
            let why = Unresolved::WithinRounding {
                random: n,
                samples: sampler.sampling.samples,
            };
            return Ok((Found::Unresolved(why, at), Some(evidence)));
        }
    }
    Ok((found, Some(evidence)))
}

/// A violation found in floating point, evaluated a second time (`reverify`): exactly
/// where the statement is polynomial, else by the interpreter. Unconfirmed, it is no
/// counterexample and the claim is undecided.
fn confirmed(
    sampler: &Sampler<'_>,
    state: State,
    relation: Relation,
    mut cx: Counterexample,
) -> Found {
    match reverify::numeric_counterexample(sampler, &state, relation, &mut cx) {
        Ok(how) => {
            cx.reverified = Some(how);
            Found::Violation(Box::new(state), cx)
        }
        Err(why) => Found::Unresolved(Unresolved::NotConfirmed(why), sampler.describe(&state)),
    }
}

/// Running totals of a sampled decision.
struct Tally {
    largest: f64,
    excluded: usize,
    /// States where the sides are undefined on a set of measure zero, stepped off.
    undefined: usize,
    /// The largest relative error estimate of a comparison through adaptive averages
    /// (0 when there were none).
    quadrature: f64,
}

impl Tally {
    fn new() -> Self {
        Tally {
            largest: f64::NEG_INFINITY,
            excluded: 0,
            undefined: 0,
            quadrature: 0.0,
        }
    }
}

/// Decides a `strategy = "numeric"` check.
pub fn decide_numeric(
    decls: &Decls,
    check: &Check,
    sink: Option<&Sink>,
) -> Result<Outcome, Diagnostic> {
    let Strategy::Numeric {
        sampling,
        relation,
        domain,
    } = &check.strategy
    else {
        unreachable!("dispatched on the strategy")
    };
    let anchor = first_side(check)?;
    let mut sampler = Sampler::new(decls, check, sampling, &anchor)?;
    sampler.record(sink, sides(check));
    let mut tally = Tally::new();
    let (found, search) = sample_and_search(&mut sampler, *relation, &[], &mut tally)?;
    let residual = match relation {
        Relation::Eq => Measure::RelativeDifference,
        Relation::Le | Relation::Ge => Measure::RelativeViolation,
    };
    let evidence = |tally: &Tally, search: Option<SearchEvidence>, domain: Option<String>| {
        let tolerance = if tally.quadrature > 0.0 {
            format!(
                "{TOL:e} relative plus the error of the adaptive averages (largest estimate {:.1e})",
                tally.quadrature
            )
        } else {
            format!("{TOL:e} relative")
        };
        NumericEvidence {
            domain,
            search,
            undefined: tally.undefined,
            rounding: sampler.within_rounding.get(),
            ..sampled_evidence(
                sampling,
                tally.largest,
                residual,
                tally.excluded,
                tolerance,
                false,
            )
        }
    };
    let undecided = |finding: Finding, tally: &Tally, search: Option<SearchEvidence>| {
        Outcome::undecided(Method::Numeric, sampling.samples)
            .with_numeric(evidence(tally, search, None))
            .with_finding(finding)
    };
    let (state, cx) = match found {
        Found::Nothing => {
            return Ok(Outcome::holds_sampled(Method::Numeric, sampling.samples)
                .with_numeric(evidence(&tally, search, None)))
        }
        Found::Unresolved(why, at) => {
            return Ok(undecided(Finding::Unresolved { why, at }, &tally, search))
        }
        // Nothing was measured: no sampled evidence to show.
        Found::Undefined(why, point) => {
            return Ok(
                Outcome::undecided(Method::Numeric, 0).with_finding(Finding::Undefined {
                    what: why.message.clone(),
                    at: format!("{}:{}:{}", why.path, why.line, why.col),
                    point,
                    overflow: why.message == OVERFLOW,
                }),
            );
        }
        Found::Violation(state, cx) => (state, cx),
    };
    let fails = |cx: Counterexample, finding: Option<Finding>| {
        // Sampled, even when the point was confirmed in exact arithmetic: a proof of
        // strength `proof` comes only from the kernel, which does not evaluate the
        // functions the sampled strategies allow.
        let mut o = Outcome::fails_sampled(Method::Numeric, sampling.samples)
            .with_counterexample(cx)
            .with_numeric(evidence(&tally, search.clone(), None));
        o.finding = finding;
        o
    };
    if domain.is_empty() {
        return Ok(fails(cx, None));
    }
    // The statement fails; does it hold on the declared domain?
    let domain_text = domain
        .iter()
        .map(|c| c.text.clone())
        .collect::<Vec<_>>()
        .join(" and ");
    if sampler.satisfies(&state, domain)? {
        let inside = Finding::InsideDomain {
            domain: domain_text,
        };
        return Ok(fails(cx, Some(inside)));
    }
    let mut inner = Sampler::new(decls, check, sampling, &anchor)?;
    let mut inside = Tally::new();
    let (found_inside, inside_search) =
        sample_and_search(&mut inner, *relation, domain, &mut inside)?;
    match found_inside {
        Found::Violation(_, cx_in) => Ok(fails(
            cx_in,
            Some(Finding::AlsoInsideDomain {
                domain: domain_text,
            }),
        )),
        Found::Unresolved(why, at) => Ok(undecided(
            Finding::UnresolvedInsideDomain {
                domain: domain_text,
                why,
                at,
            },
            &inside,
            inside_search,
        )
        .with_counterexample(cx)),
        Found::Undefined(why, point) => Ok(Outcome::undecided(Method::Numeric, 0)
            .with_finding(Finding::Undefined {
                what: why.message.clone(),
                at: format!("{}:{}:{}", why.path, why.line, why.col),
                point,
                overflow: why.message == OVERFLOW,
            })
            .with_counterexample(cx)),
        Found::Nothing => Ok(
            Outcome::conditional(Method::Numeric, 2 * sampling.samples, None)
                .with_counterexample(cx)
                .with_numeric(evidence(&inside, inside_search, Some(domain_text.clone())))
                .with_finding(Finding::HoldsOnDomain {
                    samples: sampling.samples,
                    domain: domain_text,
                }),
        ),
    }
}

/// The variables of a derivative: the free components of the `wrt` symbols, and the
/// components the assumptions tie to them, each an affine function of them (so that
/// a derivative along a free component moves what is tied to it).
struct Variables {
    free: Vec<Component>,
    tied: Vec<Tie>,
}

/// A component tied to free ones: (component, [(index into `free`, coefficient)],
/// constant).
type Tie = (Component, Vec<(usize, f64)>, f64);

impl Variables {
    fn len(&self) -> usize {
        self.free.len()
    }
}

/// Why a derivative with respect to some components is ambiguous under the assumptions.
#[derive(Debug, thiserror::Error)]
enum Ambiguous {
    #[error("`{symbol}` is tied to the substitution `{assumption}`; derivatives with respect to it are ambiguous")]
    Substitution { symbol: String, assumption: String },
    #[error("the assumptions fix every component of {wrt}: there is nothing to differentiate")]
    AllFixed { wrt: String },
    #[error("`{dependent}` depends on a power or product of `{on}` through the assumptions; derivatives with respect to `{symbol}` are ambiguous")]
    Nonlinear {
        dependent: String,
        on: String,
        symbol: String,
    },
    #[error("`{dependent}` depends on `{on}` through the assumptions but is not a variable of the derivative; derivatives with respect to `{symbol}` are ambiguous")]
    DependentOutside {
        dependent: String,
        on: String,
        symbol: String,
    },
    #[error("`{dependent}` is tied to `{on}`, which is not a variable of the derivative; derivatives with respect to `{symbol}` are ambiguous")]
    TiedOutside {
        dependent: String,
        on: String,
        symbol: String,
    },
}

/// The free and tied components of `wrt`; an error when a derivative would be
/// ambiguous (a component tied to one outside `wrt`, or to a whole-symbol substitution).
fn variables(sampler: &Sampler<'_>, wrt: &[String]) -> Result<Variables, Ambiguous> {
    use crate::derivation::parametrisation::Constrained;
    let (decls, check, p) = (sampler.decls, sampler.check, &sampler.parametrisation);
    let mut free: Vec<Component> = Vec::new();
    for symbol in wrt {
        for sub in p.substituted(&check.assumptions) {
            if sub.symbol == symbol || sub.assumption.reads.contains(symbol) {
                return Err(Ambiguous::Substitution {
                    symbol: symbol.clone(),
                    assumption: sub.assumption.text.clone(),
                });
            }
        }
        let rank = decls.symbols.get(symbol).copied().unwrap_or(0);
        for idx in assignments(decls.dim, rank) {
            if p.constrained(symbol, &idx) == Constrained::Free {
                free.push((symbol.clone(), idx));
            }
        }
    }
    if free.is_empty() {
        return Err(Ambiguous::AllFixed {
            wrt: wrt.join(", "),
        });
    }
    let in_wrt = |c: &Component| wrt.contains(&c.0);
    let mut tied = Vec::new();
    for dependent in p.dependents() {
        let (d, terms, constant) = (dependent.component, &dependent.terms, dependent.constant);
        // A product of parameters moves with no free component of the derivative, or
        // would make the tie nonlinear.
        if let Some((f, _)) = dependent
            .products
            .iter()
            .flat_map(|(p, _)| p.iter())
            .find(|(f, _)| free.contains(f))
        {
            return Err(Ambiguous::Nonlinear {
                dependent: component_name(&d.0, &d.1),
                on: component_name(&f.0, &f.1),
                symbol: f.0.clone(),
            });
        }
        let touches = terms.iter().any(|(f, _)| free.contains(f));
        if !in_wrt(d) && !touches {
            continue;
        }
        if !in_wrt(d) {
            let (f, _) = terms
                .iter()
                .find(|(f, _)| free.contains(f))
                .expect("touches");
            return Err(Ambiguous::DependentOutside {
                dependent: component_name(&d.0, &d.1),
                on: component_name(&f.0, &f.1),
                symbol: f.0.clone(),
            });
        }
        let mut linear = Vec::new();
        for (f, q) in terms.iter().copied() {
            let Some(k) = free.iter().position(|c| c == f) else {
                return Err(Ambiguous::TiedOutside {
                    dependent: component_name(&d.0, &d.1),
                    on: component_name(&f.0, &f.1),
                    symbol: d.0.clone(),
                });
            };
            linear.push((k, q.to_f64()));
        }
        if !linear.is_empty() {
            tied.push((d.clone(), linear, constant.to_f64()));
        }
    }
    Ok(Variables { free, tied })
}

/// The symmetrised convention: the derivative along the free components `t` mapped
/// to the gradient within the constrained set, `B (BᵀB)⁻¹ t`, where B's columns are
/// the directions each free component moves every component in (its own unit vector
/// plus what is tied to it). For σ_12 = σ_21 this is ½(∂F/∂σ_12 + ∂F/∂σ_21) on both.
struct Projection<'v> {
    components: Vec<&'v Component>,
    b: nalgebra::DMatrix<f64>,
    gram_inverse: nalgebra::DMatrix<f64>,
}

impl<'v> Projection<'v> {
    fn new(vars: &'v Variables) -> Self {
        let n = vars.free.len();
        let components: Vec<&Component> = vars
            .free
            .iter()
            .chain(vars.tied.iter().map(|(c, _, _)| c))
            .collect();
        let mut b = nalgebra::DMatrix::zeros(components.len(), n);
        for k in 0..n {
            b[(k, k)] = 1.0;
        }
        for (r, (_, terms, _)) in vars.tied.iter().enumerate() {
            for &(k, q) in terms {
                b[(n + r, k)] = q;
            }
        }
        // BᵀB = I + (tied coefficients)ᵀ(…) is positive definite: always invertible.
        let gram_inverse = (b.transpose() * &b)
            .try_inverse()
            .expect("BᵀB is positive definite");
        Projection {
            components,
            b,
            gram_inverse,
        }
    }

    fn apply(&self, t: &[f64]) -> Vec<f64> {
        let t = DVector::from_column_slice(t);
        (&self.b * (&self.gram_inverse * t))
            .iter()
            .copied()
            .collect()
    }
}

/// Variables per pass of [`chunked_gradient`]: derivative vectors of this fixed size
/// live on the stack, where num-dual's dynamic ones allocate at every operation.
const CHUNK: usize = 8;

/// ∇F at `x0` by forward-mode num-dual numbers, [`CHUNK`] variables per evaluation of
/// `f` (each derivative component is computed by the same operations as with one
/// dynamic derivative vector for all variables, so the values are the same).
fn chunked_gradient(
    x0: &DVector<f64>,
    f: impl Fn(&DVector<DualSVec64<CHUNK>>) -> DualSVec64<CHUNK>,
) -> DVector<f64> {
    let n = x0.len();
    let mut grad = DVector::zeros(n);
    // One pass even without variables, so that F is evaluated (and its averages seen).
    for start in (0..n.max(1)).step_by(CHUNK) {
        let x = DVector::from_iterator(
            n,
            x0.iter().enumerate().map(|(k, &v)| {
                let d = DualSVec64::<CHUNK>::from_re(v);
                if (start..start + CHUNK).contains(&k) {
                    d.derivative(k - start)
                } else {
                    d
                }
            }),
        );
        let eps = f(&x)
            .eps
            .unwrap_generic(nalgebra::Const::<CHUNK>, nalgebra::U1);
        for k in start..n.min(start + CHUNK) {
            grad[k] = eps[k - start];
        }
    }
    grad
}

/// The direction of the central difference that cross-checks a num-dual gradient at
/// the sample numbered `seq`: every variable moves, by ±(½ to 1)·(1 + |x_k|) (the
/// per-component step's scale), with signs and sizes from a low-discrepancy sequence
/// (no draw from the sampler's random stream, which would move every later sample).
fn difference_direction(x0: &DVector<f64>, seq: usize) -> DVector<f64> {
    let golden = 0.618_033_988_749_894_9;
    DVector::from_iterator(
        x0.len(),
        x0.iter().enumerate().map(|(k, &x)| {
            let u = ((k as f64 + 1.0) * golden + seq as f64 * 0.754_877_666_246_692_7).fract();
            let sign = if (k + seq).is_multiple_of(2) {
                1.0
            } else {
                -1.0
            };
            sign * (0.5 + 0.5 * u) * (1.0 + x.abs())
        }),
    )
}

/// `function` evaluated with the variables set to `x` (any num-dual scalar).
fn eval_at<T: DualNum<Primitive = f64>>(
    sampler: &Sampler<'_>,
    state: &State,
    vars: &Variables,
    function: &Expression,
    x: &DVector<T>,
) -> T {
    // Every variable's value: the free ones from `x`, the tied ones following them.
    let values: Vec<(&Component, T)> = vars
        .free
        .iter()
        .zip(x.iter().cloned())
        .chain(vars.tied.iter().map(|(c, terms, constant)| {
            let v = terms
                .iter()
                .fold(T::from(*constant), |acc, &(k, q)| acc + x[k].clone() * q);
            (c, v)
        }))
        .collect();
    if let Some(tape) = sampler.tape(&function.node) {
        // The tape's inputs straight from the state, the variables overridden.
        let mut inputs: Vec<T> = tape.gather(
            |s| state.symbols.get(s),
            |x: Option<&f64>| T::from(x.map_or(f64::NAN, |x| *x)),
        );
        for (var, v) in &values {
            if let Some(pos) = tape.inputs.iter().position(|input| input == *var) {
                inputs[pos] = v.clone();
            }
        }
        return match tape.eval(&inputs, &state.n, &sampler.fine) {
            Ok(v) => v.tensor.into_scalar().unwrap_or_else(|| T::from(f64::NAN)),
            Err(_) => T::from(f64::NAN),
        };
    }
    let mut symbols: HashMap<String, Tensor<T>> = state
        .symbols
        .iter()
        .map(|(k, t)| (k.clone(), t.map(|&v| T::from(v))))
        .collect();
    for ((symbol, idx), v) in values {
        if let Some(t) = symbols.get_mut(symbol) {
            *t.get_mut(idx) = v;
        }
    }
    match sampler.eval(&symbols, &function.node, &state.n) {
        Ok(v) => v.tensor.into_scalar().unwrap_or_else(|| T::from(f64::NAN)),
        Err(_) => T::from(f64::NAN),
    }
}

/// The refusal of a derivative through an average whose argument is not a polynomial
/// in n: the adaptive quadrature chooses its nodes from the values, so its result is
/// not a differentiable function of the variables to the accuracy the comparisons need
/// (central differences would measure the quadrature's noise, not the derivative).
fn through_adaptive_average(method: Method) -> Outcome {
    Outcome::undecided(method, 0).with_finding(Finding::ThroughAdaptiveAverage)
}

/// Decides a `strategy = "gradient"` check.
pub fn decide_gradient(
    decls: &Decls,
    check: &Check,
    sink: Option<&Sink>,
) -> Result<Outcome, Diagnostic> {
    let Strategy::Gradient {
        sampling,
        function,
        closed_forms,
        convention,
    } = &check.strategy
    else {
        unreachable!("dispatched on the strategy")
    };
    let wrt: Vec<String> = closed_forms.iter().map(|(s, _)| s.clone()).collect();
    let mut sampler = Sampler::new(decls, check, sampling, function)?;
    sampler.record(sink, vec![function.clone()]);
    let vars = variables(&sampler, &wrt).map_err(|m| {
        function
            .origin
            .diagnostic(function.node.span, m.to_string())
    })?;
    let convention = match (vars.tied.first(), convention) {
        (None, _) => None,
        (Some(_), Some(c)) => Some(*c),
        (Some((d, terms, _)), None) => {
            let f = &vars.free[terms[0].0];
            return Err(function
                .origin
                .diagnostic(
                    function.node.span,
                    format!(
                        "`{}` is tied to `{}` by the assumptions, so ∂F/∂{} has two meanings",
                        component_name(&d.0, &d.1),
                        component_name(&f.0, &f.1),
                        d.0
                    ),
                )
                .with_help(
                    "state it: convention = \"independent\" (F of the free components) or \
                     \"symmetrised\" (the gradient projected onto the constrained set)",
                ));
        }
    };
    let projection = match convention {
        Some(GradientConvention::Symmetrised) => Some(Projection::new(&vars)),
        _ => None,
    };
    let mut excluded = 0;
    let mut largest: f64 = 0.0;
    let mut checks = 0;
    for sample in 0..sampling.samples {
        let state = sampler.next(&[], &mut excluded)?;
        let x0 = DVector::from_iterator(
            vars.len(),
            vars.free.iter().map(|(s, idx)| *state.symbols[s].get(idx)),
        );
        let grad = chunked_gradient(&x0, |x| eval_at(&sampler, &state, &vars, function, x));
        if sampler.fine.used() {
            return Ok(through_adaptive_average(Method::Gradient));
        }
        let closed: Result<HashMap<&str, Tensor<f64>>, _> = closed_forms
            .iter()
            .map(|(s, e)| {
                sampler
                    .eval(&state.symbols, &e.node, &state.n)
                    .map(
                        |Labeled {
                             labels: ls,
                             tensor: t,
                         }| {
                            // Closed forms are written with the indices i, j, … in order.
                            let perm: Vec<usize> = "ijklmn"
                                .chars()
                                .take(ls.len())
                                .map(|c| ls.iter().position(|x| *x == c).unwrap_or(0))
                                .collect();
                            (s.as_str(), t.permuted(&perm))
                        },
                    )
                    .map_err(|r| (e, r))
            })
            .collect::<Result<_, _>>();
        // Central differences of F itself: the second route for every component.
        let central = |k: usize| {
            let h = FD_STEP * (1.0 + x0[k].abs());
            let shifted = |delta: f64| {
                let mut x = x0.clone();
                x[k] += delta;
                eval_at::<f64>(&sampler, &state, &vars, function, &x)
            };
            (shifted(h) - shifted(-h)) / (2.0 * h)
        };
        let near = |a: f64, b: f64| {
            a.is_finite() && b.is_finite() && (a - b).abs() <= FD_TOL * (1.0 + a.abs() + b.abs())
        };
        let closed = match closed {
            Ok(c) => c,
            Err((e, r)) => {
                sampler.verify_state(&state)?;
                // A closed form undefined at a sample where the derivative exists (num-dual
                // and central differences agree on a finite value) is wrong there; where
                // they do not, F is not differentiable at the sample and nothing is shown.
                let k = (0..vars.len()).find(|&k| !near(grad[k], central(k)));
                if let Some(k) = k {
                    return Ok(Outcome::undecided(Method::Gradient, checks).with_finding(
                        Finding::DerivativeDoesNotExist {
                            message: r.message,
                            component: component_name(&vars.free[k].0, &vars.free[k].1),
                            num_dual: grad[k],
                            central: central(k),
                        },
                    ));
                }
                return Ok(Outcome::fails_sampled(Method::Gradient, checks)
                    .with_counterexample(Counterexample {
                        chain: 1,
                        equality: 1,
                        lhs: format!("∂({})", function.text.trim()),
                        rhs: e.text.clone(),
                        point: sampler.describe(&state),
                        lhs_value: Some("(num-dual = central differences)".into()),
                        rhs_value: Some(format!("undefined: {}", r.message)),
                        reverified: Some(Reverified::CentralDifferences),
                        ..Counterexample::default()
                    })
                    .with_finding(Finding::ClosedFormUndefined { message: r.message }));
            }
        };
        // num-dual against one central difference along a direction that mixes every
        // variable: a wrong derivative in any component shows in it. Per-component
        // differences are taken only where this or a closed form disagrees.
        let ad: Vec<f64> = grad.iter().copied().collect();
        let direction = difference_direction(&x0, sample);
        let along = |t: f64| {
            let x = &x0 + &direction * t;
            eval_at::<f64>(&sampler, &state, &vars, function, &x)
        };
        let fd_along = (along(FD_STEP) - along(-FD_STEP)) / (2.0 * FD_STEP);
        let ad_along: f64 = ad.iter().zip(direction.iter()).map(|(a, v)| a * v).sum();
        let scale: f64 = ad
            .iter()
            .zip(direction.iter())
            .map(|(a, v)| (a * v).abs())
            .sum();
        let routes_agree = ad_along.is_finite()
            && fd_along.is_finite()
            && (ad_along - fd_along).abs() <= FD_TOL * (1.0 + scale + fd_along.abs());
        // The compared components, with num-dual's values and (when needed) central
        // differences': the free components' total derivatives, or their projection onto
        // every component (symmetrised convention).
        let (components, ad): (Vec<&Component>, Vec<f64>) = match &projection {
            None => (vars.free.iter().collect(), ad),
            Some(p) => (p.components.clone(), p.apply(&ad)),
        };
        let per_component = || -> Vec<f64> {
            let fd: Vec<f64> = (0..vars.len()).map(central).collect();
            match &projection {
                None => fd,
                Some(p) => p.apply(&fd),
            }
        };
        let mut fd: Option<Vec<f64>> = (!routes_agree).then(per_component);
        for (k, ((symbol, idx), ad)) in components.into_iter().zip(ad).enumerate() {
            checks += 1;
            let cf = *closed[symbol.as_str()].get(idx);
            let (ok_cf, r_cf) = relation_holds(Relation::Eq, ad, cf);
            largest = largest.max(r_cf);
            if ok_cf && routes_agree {
                continue;
            }
            let fd = fd.get_or_insert_with(per_component)[k];
            if ok_cf && near(ad, fd) {
                continue;
            }
            sampler.verify_state(&state)?;
            let name = component_name(symbol, idx);
            if ok_cf || !near(ad, fd) {
                // The closed form agrees with num-dual but not with the difference
                // quotient, or the two derivative routes disagree: a numerical artefact
                // (a kink, a step too large) is not a counterexample.
                return Ok(Outcome::undecided(Method::Gradient, checks).with_finding(
                    Finding::DerivativeRoutesDisagree {
                        component: name,
                        num_dual: ad,
                        central: fd,
                        closed: cf,
                        at: sampler.describe(&state),
                    },
                ));
            }
            // num-dual and central differences agree, and the closed form differs.
            let point = sampler.describe(&state);
            return Ok(Outcome::fails_sampled(Method::Gradient, checks)
                .with_counterexample(Counterexample {
                    chain: 1,
                    equality: 1,
                    lhs: format!("∂({})/∂{name}", function.text.trim()),
                    rhs: closed_forms
                        .iter()
                        .find(|(s, _)| s == symbol)
                        .map(|(_, e)| e.text.clone())
                        .unwrap_or_default(),
                    point,
                    lhs_value: Some(significant(ad, digits::VALUE)),
                    rhs_value: Some(significant(cf, digits::VALUE)),
                    aux: BTreeMap::from([(
                        "central difference".to_owned(),
                        significant(fd, digits::VALUE),
                    )]),
                    reverified: Some(Reverified::CentralDifferences),
                    ..Counterexample::default()
                })
                .with_finding(Finding::ClosedFormDisagrees));
        }
    }
    let names: Vec<String> = vars
        .free
        .iter()
        .map(|(s, idx)| component_name(s, idx))
        .collect();
    Ok(Outcome::holds_sampled(Method::Gradient, checks)
        .with_numeric(sampled_evidence(
            sampling,
            largest,
            Measure::DifferenceFromClosedForm,
            excluded,
            format!(
                "{TOL:e} relative vs closed form, {FD_TOL:e} vs a central difference along a mixed direction"
            ),
            true,
        ))
        .with_finding(Finding::GradientAgrees {
            variables: names,
            tied: vars
                .tied
                .iter()
                .map(|((s, i), _, _)| component_name(s, i))
                .collect(),
            convention,
        }))
}

/// Decides a `strategy = "convex"` check.
pub fn decide_convex(
    decls: &Decls,
    check: &Check,
    sink: Option<&Sink>,
) -> Result<Outcome, Diagnostic> {
    let Strategy::Convex {
        sampling,
        function,
        wrt,
    } = &check.strategy
    else {
        unreachable!("dispatched on the strategy")
    };
    let mut sampler = Sampler::new(decls, check, sampling, function)?;
    sampler.record(sink, vec![function.clone()]);
    let vars = variables(&sampler, wrt).map_err(|m| {
        function
            .origin
            .diagnostic(function.node.span, m.to_string())
    })?;
    let mut excluded = 0;
    let mut smallest = f64::INFINITY;
    for _ in 0..sampling.samples {
        let state = sampler.next(&[], &mut excluded)?;
        let x0 = DVector::from_iterator(
            vars.len(),
            vars.free.iter().map(|(s, idx)| *state.symbols[s].get(idx)),
        );
        let (_, _, h) = hessian(
            |x: DVector<Dual2DVec64>| eval_at(&sampler, &state, &vars, function, &x),
            &x0,
        );
        if sampler.fine.used() {
            return Ok(through_adaptive_average(Method::Convex));
        }
        if !h.iter().all(|v| v.is_finite()) {
            sampler.verify_state(&state)?;
            return Ok(
                Outcome::undecided(Method::Convex, sampling.samples).with_finding(
                    Finding::HessianNotFinite {
                        at: sampler.describe(&state),
                    },
                ),
            );
        }
        let eigen = SymmetricEigen::new(h.clone());
        let (k_min, min) =
            eigen
                .eigenvalues
                .iter()
                .copied()
                .enumerate()
                .fold(
                    (0, f64::INFINITY),
                    |a, (k, v)| if v < a.1 { (k, v) } else { a },
                );
        let max_abs = eigen
            .eigenvalues
            .iter()
            .map(|v| v.abs())
            .fold(0.0, f64::max);
        let relative = min / (1.0 + max_abs);
        smallest = smallest.min(relative);
        if relative < -TOL {
            sampler.verify_state(&state)?;
            // The second route: the second difference of the function along the
            // eigenvector must be negative as well.
            let v = eigen.eigenvectors.column(k_min).into_owned();
            let step = SECOND_DIFFERENCE_STEP * (1.0 + x0.amax());
            let f = |t: f64| eval_at::<f64>(&sampler, &state, &vars, function, &(&x0 + &v * t));
            let curvature = (f(step) - 2.0 * f(0.0) + f(-step)) / (step * step);
            let confirmed = curvature.is_finite()
                && curvature < -SECOND_DIFFERENCE_TOL * (1.0 + max_abs)
                && (curvature - min).abs() <= 0.5 * min.abs();
            let point = sampler.describe(&state);
            if !confirmed {
                return Ok(
                    Outcome::undecided(Method::Convex, sampling.samples).with_finding(
                        Finding::SecondDifferenceDisagrees {
                            eigenvalue: min,
                            curvature,
                            at: point,
                        },
                    ),
                );
            }
            return Ok(Outcome::fails_sampled(Method::Convex, sampling.samples)
                .with_counterexample(Counterexample {
                    chain: 1,
                    equality: 1,
                    lhs: format!("Hessian of {}", function.text.trim()),
                    rhs: "positive semidefinite".into(),
                    point,
                    aux: BTreeMap::from([(
                        "smallest eigenvalue".to_owned(),
                        significant(min, digits::VALUE),
                    )]),
                    reverified: Some(Reverified::SecondDifferences),
                    ..Counterexample::default()
                })
                .with_finding(Finding::NegativeEigenvalue { curvature }));
        }
    }
    Ok(Outcome::holds_sampled(Method::Convex, sampling.samples)
        .with_numeric(sampled_evidence(
            sampling,
            smallest,
            Measure::RelativeEigenvalue,
            excluded,
            format!("smallest eigenvalue ≥ −{TOL:e}·(1 + max|λ|)"),
            true,
        ))
        .with_finding(Finding::ConvexAgrees {
            variables: vars.len(),
        }))
}

/// Every well-formed side of every chain, as an expression (what a recorded numeric
/// decision keeps the values of).
fn sides(check: &Check) -> Vec<Expression> {
    check
        .chains
        .iter()
        .flatten()
        .filter_map(|s| s.expression().ok())
        .collect()
}
