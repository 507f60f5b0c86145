//! `exactly_when`: a sign claim that holds on a set of parameter values and nowhere
//! else in the domain ("K > 0 exactly when −1 < ν < 1/2"). It is decided as one sign
//! claim per part ([`crate::derivation::exact_parts`]): the sign on the set, its
//! negation on each box of the rest. Each part is a statement of its own for the
//! kernel, so the whole is proved when every part is, and refuted by the first part
//! that fails: a point of the set where the sign does not hold, or one outside it where
//! it holds too.

use super::super::outcome::{Method, Outcome};
use super::parts;
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
        let (at, o) = decided.swap_remove(k);
        let what = if is_inside(check, &parts[k]) {
            "the part inside the set it is claimed on"
        } else {
            "a part outside the set it is claimed on, where its negation is claimed"
        };
        let (relation, box_) = where_(&parts[k]).1;
        return Ok(parts::labelled(
            o,
            format!("{what}: {at}"),
            what,
            relation,
            box_,
        ));
    }
    Ok(parts::all_hold(check, &decided))
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
