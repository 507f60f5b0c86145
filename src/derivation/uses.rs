//! The derivation graph: the claims each claim is derived from (`uses`), checked across
//! the files read together; the edges the definitions imply (a claim whose check reads a
//! definition that `[stated]` attributes to another claim uses that claim); and warnings
//! where the written edges and the implied ones disagree.

use super::model::{Claim, DerivationFile};
use crate::lang::{Diagnostic, Origin, Span};
use std::collections::{BTreeMap, BTreeSet};

/// A diagnostic pointing at the whole of `text`, which `origin` locates.
fn at(origin: &Origin, text: &str, message: String) -> Diagnostic {
    origin.diagnostic(Span::new(0, text.len()), message)
}

/// Every claim of `files` by id.
pub fn by_id(files: &[DerivationFile]) -> BTreeMap<&str, &Claim> {
    files
        .iter()
        .flat_map(|f| &f.claims)
        .map(|c| (c.id.as_str(), c))
        .collect()
}

/// Checks the graph of the files read together: no claim uses itself, `uses` has no
/// cycle, and a `corrected` form belongs to a claim that has a correction. An id that
/// names no claim of these files is only a warning ([`warnings`]): one file of a set
/// may be read alone (`plot`, `explain`, `verify` of one file).
pub(super) fn link(files: &[DerivationFile]) -> Result<(), Diagnostic> {
    let claims = by_id(files);
    for c in claims.values() {
        if let Some(u) = c.uses.iter().find(|u| u.id == c.id) {
            return Err(at(&u.origin, &u.id, format!("`{}` uses itself", c.id))
                .with_help("a claim lists the claims it is derived from, not itself"));
        }
    }
    for s in files.iter().flat_map(|f| f.stated.iter()) {
        if let Some(by) = claims.get(s.by.as_str()) {
            if s.corrected.is_some() && by.correction.is_none() {
                return Err(at(
                    &s.origin,
                    &s.by,
                    format!(
                        "`{}` has no correction, so `{}` has no corrected form",
                        s.by, s.name
                    ),
                )
                .with_help("give the claim a [claim.correction], or drop `corrected`"));
            }
        }
    }
    // A cycle in `uses` (depth-first, in file order, so the cycle reported is the same
    // on every run).
    let mut state: BTreeMap<&str, bool> = BTreeMap::new(); // false: on the path; true: done
    for c in files.iter().flat_map(|f| &f.claims) {
        if state.contains_key(c.id.as_str()) {
            continue;
        }
        let mut path: Vec<(&Claim, usize)> = vec![(c, 0)];
        state.insert(&c.id, false);
        while let Some((claim, next)) = path.last_mut() {
            let Some(u) = claim.uses.get(*next) else {
                state.insert(&claim.id, true);
                path.pop();
                continue;
            };
            *next += 1;
            match state.get(u.id.as_str()) {
                Some(true) => {}
                None if !claims.contains_key(u.id.as_str()) => {}
                Some(false) => {
                    let from = path.iter().position(|(p, _)| p.id == u.id).unwrap_or(0);
                    let mut ids: Vec<&str> =
                        path[from..].iter().map(|(p, _)| p.id.as_str()).collect();
                    ids.push(&u.id);
                    return Err(at(&u.origin, &u.id, format!("`uses` makes a cycle: {}", ids.join(" → ")))
                        .with_help("a claim cannot be derived, even indirectly, from itself; remove one of these entries"));
                }
                None => {
                    let next = claims[u.id.as_str()];
                    state.insert(&next.id, false);
                    path.push((next, 0));
                }
            }
        }
    }
    Ok(())
}

/// An edge the definitions imply: the claim's check reads `definition`, which
/// transcribes the statement of claim `by`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Implied<'c> {
    pub by: &'c str,
    pub definition: &'c str,
}

/// The claims this claim's check implies it uses, each once, with the first definition
/// (in definition order) that implies it.
pub fn implied(claim: &Claim) -> Vec<Implied<'_>> {
    let reads = claim.check.definitions_read();
    let mut out: Vec<Implied<'_>> = Vec::new();
    for s in claim.stated.iter() {
        if s.by != claim.id && reads.contains(s.name.as_str()) && out.iter().all(|e| e.by != s.by) {
            out.push(Implied {
                by: &s.by,
                definition: &s.name,
            });
        }
    }
    out
}

/// Where `uses` and the definitions disagree: an edge the definitions imply that `uses`
/// does not list (missing), and a listed claim whose stated definitions in this file the
/// check does not read at all, while it reads those of other claims (stale). An edge to
/// a claim that states no definition of the file, or from a check that reads no stated
/// definition (a step checked on its own symbols), cannot be inferred either way and is
/// taken as written.
///
/// `unread_ids` are the claims of files left unread (reading for one claim,
/// [`super::only`]): an edge to one of them is no warning, as in a whole run.
pub fn warnings(files: &[DerivationFile], unread_ids: &BTreeSet<String>) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    let mut known: BTreeSet<&str> = by_id(files).into_keys().collect();
    known.extend(unread_ids.iter().map(String::as_str));
    let unknown =
        |id: &str| format!("`{id}` is no claim of the files read, so this edge is not followed");
    let help = "check the id, or read the file that has it together with this one";
    for c in files.iter().flat_map(|f| &f.claims) {
        for u in c.uses.iter().filter(|u| !known.contains(u.id.as_str())) {
            out.push(at(&u.origin, &u.id, unknown(&u.id)).with_help(help));
        }
    }
    for s in files.iter().flat_map(|f| f.stated.iter()) {
        if !known.contains(s.by.as_str()) {
            out.push(at(&s.origin, &s.by, unknown(&s.by)).with_help(help));
        }
    }
    for c in files.iter().flat_map(|f| &f.claims) {
        let implied = implied(c);
        for e in &implied {
            if c.uses.iter().all(|u| u.id != e.by) {
                out.push(
                    at(
                        &c.origin,
                        &c.id,
                        format!(
                        "`{}` reads `{}`, which transcribes {}, but its `uses` does not list {}",
                        c.id, e.definition, e.by, e.by
                    ),
                    )
                    .with_help(format!(
                        "add \"{}\" to uses (or correct the [stated] entry of `{}`)",
                        e.by, e.definition
                    )),
                );
            }
        }
        for u in &c.uses {
            let states: Vec<&str> = c
                .stated
                .iter()
                .filter(|s| s.by == u.id)
                .map(|s| s.name.as_str())
                .collect();
            if !states.is_empty() && !implied.is_empty() && implied.iter().all(|e| e.by != u.id) {
                out.push(
                    at(
                        &u.origin,
                        &u.id,
                        format!(
                        "`{}` uses {}, but reads none of the definitions that transcribe it ({})",
                        c.id,
                        u.id,
                        states.join(", ")
                    ),
                    )
                    .with_help("remove the entry if the claim no longer depends on it"),
                );
            }
        }
    }
    out
}
