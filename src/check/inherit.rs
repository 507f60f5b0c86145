//! Root errors and inherited failures. A claim that fails (or holds only on a domain)
//! is re-decided with every failing claim it uses, directly or through others, replaced
//! by its correction: each definition that transcribes such a claim (`[stated]`) takes
//! its corrected form. If the claim then holds, its failure is inherited from them; if
//! it still fails, or no failing claim it uses enters its check, it is a root error.
//!
//! Only corrections that themselves hold are applied, and only through the definitions
//! the claim's check reads: a failing claim whose statement does not enter the check
//! cannot be what makes it fail.

use super::decided::{Attribution, Decided};
use super::dispatch::decide;
use crate::decide::watch;
use crate::derivation::{Claim, Verdict};
use crate::lang::Diagnostic;
use std::collections::{BTreeMap, BTreeSet};
use std::time::Duration;

/// Whether a verdict accuses the printed statement.
pub fn failing(v: Verdict) -> bool {
    matches!(v, Verdict::Fails | Verdict::Conditional)
}

/// Every claim `id` uses, directly or through others, in first-visit order.
pub fn ancestors<'c>(id: &str, claims: &BTreeMap<&str, &'c Claim>) -> Vec<&'c Claim> {
    let mut out: Vec<&Claim> = Vec::new();
    let mut seen = BTreeSet::new();
    let mut stack: Vec<&str> = claims
        .get(id)
        .map(|c| c.uses.iter().rev().map(|u| u.id.as_str()).collect())
        .unwrap_or_default();
    while let Some(next) = stack.pop() {
        let Some(c) = claims.get(next) else { continue };
        if seen.insert(next) {
            out.push(c);
            stack.extend(c.uses.iter().rev().map(|u| u.id.as_str()));
        }
    }
    out
}

/// Attributes the failure of every failing row whose failing ancestors are among the
/// rows; each re-decision runs under the time limit `limit`.
pub fn attribute(rows: &mut [Decided<'_>], limit: Duration) -> Result<(), Diagnostic> {
    let claims: BTreeMap<&str, &Claim> = rows
        .iter()
        .map(|r| (r.claim.id.as_str(), r.claim))
        .collect();
    // A dependency counts as corrected only when its correction holds.
    let verdicts: BTreeMap<&str, (Verdict, bool)> = rows
        .iter()
        .map(|r| {
            let corrected = r
                .correction
                .as_ref()
                .is_some_and(|o| o.verdict() == Verdict::Holds);
            (r.claim.id.as_str(), (r.outcome.verdict(), corrected))
        })
        .collect();
    // Each failing row is re-decided on its own; the first error in row order is the
    // one reported.
    let found = crate::parallel::in_index_order(rows.len(), |k| {
        let r = &rows[k];
        failing(r.outcome.verdict())
            .then(|| attribution(r.claim, &claims, &verdicts, limit))
            .transpose()
    });
    for (r, a) in rows.iter_mut().zip(found) {
        r.attribution = a?;
    }
    Ok(())
}

fn attribution(
    claim: &Claim,
    claims: &BTreeMap<&str, &Claim>,
    verdicts: &BTreeMap<&str, (Verdict, bool)>,
    limit: Duration,
) -> Result<Attribution, Diagnostic> {
    let failing_ancestors: BTreeSet<&str> = ancestors(&claim.id, claims)
        .into_iter()
        .filter(|c| {
            verdicts
                .get(c.id.as_str())
                .is_some_and(|(v, _)| failing(*v))
        })
        .map(|c| c.id.as_str())
        .collect();
    let reads = claim.check.definitions_read();
    let mut check = claim.check.clone();
    let (mut corrected, mut uncorrectable) = (Vec::new(), Vec::new());
    for s in claim.stated.iter() {
        if !failing_ancestors.contains(s.by.as_str()) || !reads.contains(s.name.as_str()) {
            continue;
        }
        let holds = verdicts.get(s.by.as_str()).is_some_and(|(_, c)| *c);
        match (&s.corrected, holds) {
            (Some(def), true) => {
                for d in check.defs.iter_mut().filter(|d| d.sig.name == s.name) {
                    *d = def.clone();
                }
                if !corrected.contains(&s.by) {
                    corrected.push(s.by.clone());
                }
            }
            _ => {
                if !uncorrectable.contains(&s.by) {
                    uncorrectable.push(s.by.clone());
                }
            }
        }
    }
    uncorrectable.retain(|id| !corrected.contains(id));
    let outcome = if corrected.is_empty() {
        None
    } else {
        let w = watch::Watch::new(&claim.id, limit);
        Some(watch::under(&w, || decide(&claim.decls, &check))?)
    };
    Ok(match outcome {
        Some(o) if o.verdict() == Verdict::Holds => Attribution::Inherited {
            from: corrected,
            outcome: o,
        },
        o if uncorrectable.is_empty() && o.as_ref().is_none_or(|o| failing(o.verdict())) => {
            Attribution::Root {
                corrected,
                outcome: o,
            }
        }
        o => Attribution::Undetermined {
            corrected,
            uncorrectable,
            outcome: o,
        },
    })
}
