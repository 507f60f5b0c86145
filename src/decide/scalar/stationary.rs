//! `strategy = "stationary"`: `variable = at` is a stationary point of a function for
//! every value of the other parameters in the domain, and for an extremum one by the
//! second-derivative test. It is decided as sign claims under `variable = at`
//! ([`crate::derivation::stationary_parts`]): the point inside the variable's interval,
//! the derivative ≥ 0 and ≤ 0 there, and the second derivative's strict sign. A part
//! that fails only where the test says nothing (the point at a closed end, a second
//! derivative that vanishes) leaves the claim undecided, never refuted: the point may
//! still be an extremum there.

use super::super::finding::Finding;
use super::super::outcome::{Method, Outcome};
use super::parts;
use crate::derivation::{
    stationary_parts, Check, Extremum, ScalarClaim, Stationary, Strategy, Verdict,
};
use crate::lang::Diagnostic;

/// Decides a stationary claim part by part, each by `sign` (the scalar decision of a
/// sign claim).
pub(super) fn decide(
    check: &Check,
    sign: impl Fn(&Check) -> Result<Outcome, Diagnostic>,
) -> Result<Outcome, Diagnostic> {
    let mut decided = Vec::new();
    for part in stationary_parts(check).unwrap_or_default() {
        let o = sign(&part.check)?;
        let relation = match &part.check.strategy {
            Strategy::Scalar { claim, .. } => match &**claim {
                ScalarClaim::Sign(s) => s.relation(),
                _ => "",
            },
            _ => "",
        };
        let box_ = || match &part.check.strategy {
            Strategy::Scalar { domain, .. } => domain.describe(),
            _ => String::new(),
        };
        match o.verdict() {
            Verdict::Holds => decided.push((part.what, o)),
            Verdict::Fails => {
                let Some((weaker, why)) = &part.weaker else {
                    return Ok(parts::labelled(
                        o,
                        part.what.clone(),
                        &part.what,
                        relation,
                        box_(),
                    ));
                };
                let w = sign(weaker)?;
                return Ok(match w.verdict() {
                    Verdict::Holds => {
                        Outcome::undecided(Method::RationalFunction, o.checks + w.checks)
                            .with_finding(Finding::Inconclusive {
                                why: format!("{} fails, and {why}", part.what),
                            })
                    }
                    _ => parts::labelled(w, part.what.clone(), &part.what, relation, box_()),
                });
            }
            _ => {
                return Ok(parts::labelled(
                    o,
                    part.what.clone(),
                    &part.what,
                    relation,
                    box_(),
                ))
            }
        }
    }
    if decided.is_empty() {
        return Ok(Outcome::undecided(Method::RationalFunction, 0));
    }
    let mut o = parts::all_hold(check, &decided);
    if let (Some(Finding::RationalFunction(e)), Some(s)) = (&mut o.finding, claim(check)) {
        let what = match s.kind {
            Extremum::Stationary => "a stationary point",
            Extremum::LocalMaximum => "a strict local maximum (the second-derivative test)",
            Extremum::LocalMinimum => "a strict local minimum (the second-derivative test)",
        };
        e.decided = format!("{what} at {} = {}", s.variable, s.at.text);
    }
    Ok(o)
}

fn claim(check: &Check) -> Option<&Stationary> {
    match &check.strategy {
        Strategy::Scalar { claim, .. } => match &**claim {
            ScalarClaim::Stationary(s) => Some(s),
            _ => None,
        },
        _ => None,
    }
}
