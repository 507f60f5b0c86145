//! `exactly_when`: a sign claim that holds on a set of parameter values and nowhere
//! else in the domain ("K > 0 exactly when −1 < ν < 1/2"). It is decided as one sign
//! claim per part ([`crate::derivation::exact_parts`]): the sign on the set, its
//! negation on each box of the rest. Each part is a statement of its own for the
//! kernel, so the whole is proved when every part is, and refuted by the first part
//! that fails: a point of the set where the sign does not hold, or one outside it where
//! it holds too.

use super::super::finding::{Finding, RationalEvidence};
use super::super::outcome::{Method, Outcome, Strength};
use crate::derivation::{exact_part_checks, Check, ScalarClaim, Strategy, Verdict};
use crate::lang::Diagnostic;

/// Decides a sign claim with `exactly_when`, part by part, each by `sign` (the scalar
/// decision of a sign claim).
pub(super) fn decide(
    check: &Check,
    sign: impl Fn(&Check) -> Result<Outcome, Diagnostic>,
) -> Result<Outcome, Diagnostic> {
    let parts = exact_part_checks(check).unwrap_or_default();
    if parts.is_empty() {
        // The parts cover a domain with a point in it: none means nothing was decided.
        return Ok(Outcome::undecided(Method::RationalFunction, 0));
    }
    let mut decided = Vec::with_capacity(parts.len());
    for part in &parts {
        decided.push((where_(part).0, sign(part)?));
    }
    let first = |v: Verdict| decided.iter().position(|(_, o)| o.verdict() == v);
    if let Some(k) = first(Verdict::Fails).or_else(|| first(Verdict::Undecided)) {
        let (at, mut o) = decided.swap_remove(k);
        let what = if is_inside(check, &parts[k]) {
            "the part inside the set it is claimed on"
        } else {
            "a part outside the set it is claimed on, where its negation is claimed"
        };
        let said = format!("{what}: {at}");
        match &mut o.finding {
            Some(Finding::RationalFunction(e)) => e.points.insert(0, said),
            None => {
                let (relation, box_) = where_(&parts[k]).1;
                o.finding = Some(Finding::RationalFunction(RationalEvidence {
                    decided: format!("left − right {relation} ({what})"),
                    domain: box_,
                    points: Vec::new(),
                    holds_on: None,
                    limit: None,
                    sampled: None,
                }))
            }
            Some(_) => {}
        }
        return Ok(o);
    }
    let checks = decided.iter().map(|(_, o)| o.checks).sum();
    let mut evidence = None;
    let mut points = Vec::new();
    let mut sampled = None;
    for (at, o) in &decided {
        if let Some(Finding::RationalFunction(e)) = &o.finding {
            let detail = if e.points.is_empty() {
                String::new()
            } else {
                format!(" ({})", e.points.join(", "))
            };
            points.push(format!("{at}{detail}"));
            sampled = sampled.or_else(|| e.sampled.clone());
            evidence.get_or_insert_with(|| e.clone());
        }
    }
    let all_proved = decided.iter().all(|(_, o)| o.strength() == Strength::Proof);
    let proofs = decided
        .iter()
        .flat_map(|(_, o)| o.proofs().iter().cloned())
        .collect();
    let o = match Outcome::proved_parts(Method::RationalFunction, checks, proofs) {
        Some(o) if all_proved => o,
        _ => Outcome::holds_sampled(Method::RationalFunction, checks),
    };
    Ok(match evidence {
        Some(mut e) => {
            e.points = points;
            e.sampled = sampled;
            if let Strategy::Scalar { domain, .. } = &check.strategy {
                e.domain = domain.describe();
            }
            o.with_finding(Finding::RationalFunction(e))
        }
        None => o,
    })
}

/// A part in words (`left − right ≤ 0 where nu ≤ −1`), and its relation and box.
fn where_(part: &Check) -> (String, (&'static str, String)) {
    match &part.strategy {
        Strategy::Scalar { claim, domain, .. } => {
            let relation = match &**claim {
                ScalarClaim::Sign(s) => s.relation(),
                _ => "",
            };
            let box_ = domain.describe();
            (
                format!("left − right {relation} where {box_}"),
                (relation, box_),
            )
        }
        _ => (String::new(), ("", String::new())),
    }
}

/// Whether `part` is the set itself: the one part with the claim's own sign (the
/// others have its negation).
fn is_inside(check: &Check, part: &Check) -> bool {
    let sign = |c: &Check| match &c.strategy {
        Strategy::Scalar { claim, .. } => match &**claim {
            ScalarClaim::Sign(s) | ScalarClaim::SignExactly(s, _) => Some(*s),
            _ => None,
        },
        _ => None,
    };
    sign(check).is_some() && sign(check) == sign(part)
}
