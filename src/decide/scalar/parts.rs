//! Claims decided as several sign claims, each a statement of its own for the kernel
//! (a sign on exactly a set, a stationary point): the whole holds when every part
//! does, with a proof when every part has one, and is refuted, or left undecided, by
//! the first part that is, named in its evidence.

use super::super::finding::{Finding, RationalEvidence};
use super::super::outcome::{Method, Outcome, Strength};
use crate::derivation::{Check, Strategy};

/// A part's outcome that decides the claim, with `said` (the part in words) first
/// among its evidence's points; `what` and the part's `relation` and `box_` make the
/// evidence of an outcome that has none.
pub(super) fn labelled(
    mut o: Outcome,
    said: String,
    what: &str,
    relation: &str,
    box_: String,
) -> Outcome {
    match &mut o.finding {
        Some(Finding::RationalFunction(e)) => e.points.insert(0, said),
        None => {
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
    o
}

/// The outcome of `check` when every part (in words, with its outcome) holds: a proof
/// made of the parts' proofs when each has one, else `holds (sampled)`; the evidence
/// lists the parts.
pub(super) fn all_hold(check: &Check, decided: &[(String, Outcome)]) -> Outcome {
    let checks = decided.iter().map(|(_, o)| o.checks).sum();
    let mut evidence = None;
    let mut points = Vec::new();
    let mut sampled = None;
    for (at, o) in decided {
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
    match evidence {
        Some(mut e) => {
            e.points = points;
            e.sampled = sampled;
            if let Strategy::Scalar { domain, .. } = &check.strategy {
                e.domain = domain.describe();
            }
            o.with_finding(Finding::RationalFunction(e))
        }
        None => o,
    }
}
