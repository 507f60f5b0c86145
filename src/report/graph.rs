//! The derivation graph in words: where each failure comes from (a root error, or
//! inherited from the claims it uses), and the errata grouped by root error.

use super::evidence::evidence;
use crate::check::decided::Attribution;
use crate::check::Decided;

/// The attribution of a failing claim, in one sentence.
pub fn attribution(a: &Attribution) -> String {
    match a {
        Attribution::Root {
            corrected,
            outcome: None,
        } if corrected.is_empty() => {
            "root error: no failing claim it uses enters its check".to_owned()
        }
        // The re-decision's evidence is in `explain` and JSON; a failure's is long.
        Attribution::Root { corrected, outcome } => format!(
            "root error: still {} with {} corrected{}",
            outcome
                .as_ref()
                .map_or("failing".to_owned(), |o| o.verdict_text()),
            list(corrected),
            outcome
                .as_ref()
                .map(|o| format!(" ({})", o.method.as_str()))
                .unwrap_or_default()
        ),
        // "holds (sampled)" when the re-decision rests on sampled evidence.
        Attribution::Inherited { from, outcome } => format!(
            "inherited: {} once {} {} corrected ({}; {})",
            outcome.verdict_text(),
            list(from),
            if from.len() == 1 { "is" } else { "are" },
            outcome.method.as_str(),
            evidence(outcome)
        ),
        Attribution::Undetermined {
            corrected,
            uncorrectable,
            outcome,
        } => {
            let mut why = Vec::new();
            if !uncorrectable.is_empty() {
                let one = uncorrectable.len() == 1;
                why.push(format!(
                    "it uses {}, which {} its check and {} no corrected form that holds",
                    list(uncorrectable),
                    if one { "fails, enters" } else { "fail, enter" },
                    if one { "has" } else { "have" },
                ));
            }
            if let Some(o) = outcome {
                why.push(format!(
                    "with {} corrected it is {} ({})",
                    list(corrected),
                    o.verdict_text(),
                    if o.verdict() == crate::derivation::Verdict::Undecided {
                        evidence(o)
                    } else {
                        o.method.as_str().to_owned()
                    }
                ));
            }
            format!(
                "root error or inherited failure: cannot tell, because {}",
                why.join("; and ")
            )
        }
    }
}

/// `a`, `a and b`, `a, b and c`.
fn list(ids: &[String]) -> String {
    match ids {
        [] => String::new(),
        [one] => one.clone(),
        [init @ .., last] => format!("{} and {last}", init.join(", ")),
    }
}

/// The short form for a verdict cell: "inherited from eq21", or nothing.
pub fn inherited_label(r: &Decided<'_>) -> Option<String> {
    let from = r.attribution.as_ref()?.inherited_from();
    (!from.is_empty()).then(|| format!("inherited from {}", from.join(", ")))
}

/// The errata in reading order: each root error followed by the failures inherited
/// from it (an inherited failure goes under the first root error among the claims it
/// inherits from, directly or through other inherited failures), then the failures
/// whose origin cannot be told, each on its own.
pub fn grouped<'a, 'c>(rows: &[&'a Decided<'c>]) -> Vec<(&'a Decided<'c>, Vec<&'a Decided<'c>>)> {
    let by_id = |id: &str| rows.iter().copied().find(|r| r.claim.id == id);
    // The root error an inherited failure traces back to, following `from` through
    // other inherited rows (bounded by the number of rows: `uses` has no cycle).
    let root_of = |r: &'a Decided<'c>| {
        let mut frontier = vec![r];
        for _ in 0..rows.len() {
            let mut next = Vec::new();
            for f in &frontier {
                for id in f
                    .attribution
                    .as_ref()
                    .map_or(&[][..], |a| a.inherited_from())
                {
                    match by_id(id) {
                        Some(d) if d.attribution.as_ref().is_some_and(Attribution::is_root) => {
                            return Some(d.claim.id.as_str())
                        }
                        Some(d) => next.push(d),
                        None => {}
                    }
                }
            }
            if next.is_empty() {
                break;
            }
            frontier = next;
        }
        None
    };
    let mut groups: Vec<(&Decided<'c>, Vec<&Decided<'c>>)> = rows
        .iter()
        .filter(|r| r.attribution.as_ref().is_none_or(Attribution::is_root))
        .map(|r| (*r, Vec::new()))
        .collect();
    let mut rest = Vec::new();
    for r in rows {
        match &r.attribution {
            Some(Attribution::Inherited { .. }) => {
                match root_of(r).and_then(|id| groups.iter_mut().find(|(g, _)| g.claim.id == id)) {
                    Some((_, under)) => under.push(*r),
                    None => rest.push((*r, Vec::new())),
                }
            }
            Some(Attribution::Undetermined { .. }) => rest.push((*r, Vec::new())),
            _ => {}
        }
    }
    groups.extend(rest);
    groups
}
