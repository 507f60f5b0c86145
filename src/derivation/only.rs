//! Reading for one claim (`--only`, `explain`): only the files that deciding it reads.
//!
//! Deciding a claim reads its own file, and a failure is attributed through the claims
//! it `uses`, so those files are read too (transitively); files are otherwise
//! self-contained (one file of a set may be read alone). Which files those are is told
//! from an outline of every file — its claims' ids and `uses`, read as TOML without
//! reading any expression — so the expressions of the other files are neither parsed
//! nor validated. Where the outline cannot tell (a file that is not TOML, an id held by
//! no file or by two), every file is read, so that the run reports exactly what a whole
//! run would.

use super::load::{load_files, load_texts, read_bounded, LoadError};
use super::model::DerivationFile;
use serde::Deserialize;
use std::collections::{BTreeMap, BTreeSet};
use std::path::PathBuf;

/// The part of a derivation file the outline reads; every other key is skipped.
#[derive(Deserialize)]
struct Outline {
    #[serde(default)]
    claim: Vec<OutlineClaim>,
}

#[derive(Deserialize)]
struct OutlineClaim {
    id: String,
    #[serde(default)]
    uses: Vec<String>,
}

/// The indices (ascending) of the texts that deciding claim `id` reads: the one that
/// holds it and those holding the claims it uses, transitively; and the claim ids of
/// the other texts. `None` when the outlines cannot tell: a text that does not
/// outline, or an id held by no text or by two (a `uses` id held by none is skipped,
/// as it is only a warning in a whole run).
fn needed(texts: &[&str], id: &str) -> Option<(Vec<usize>, BTreeSet<String>)> {
    let outlines: Vec<Outline> =
        crate::parallel::in_index_order(texts.len(), |k| toml::from_str::<Outline>(texts[k]).ok())
            .into_iter()
            .collect::<Option<_>>()?;
    let mut holder: BTreeMap<&str, (usize, &[String])> = BTreeMap::new();
    for (k, o) in outlines.iter().enumerate() {
        for c in &o.claim {
            if holder.insert(&c.id, (k, &c.uses)).is_some() {
                return None;
            }
        }
    }
    holder.get(id)?;
    let mut files = BTreeSet::new();
    let mut seen = BTreeSet::from([id]);
    let mut next = vec![id];
    while let Some(c) = next.pop() {
        let Some(&(k, uses)) = holder.get(c) else {
            continue;
        };
        files.insert(k);
        for u in uses {
            if seen.insert(u.as_str()) {
                next.push(u);
            }
        }
    }
    let unread = outlines
        .iter()
        .enumerate()
        .filter(|(k, _)| !files.contains(k))
        .flat_map(|(_, o)| o.claim.iter().map(|c| c.id.clone()))
        .collect();
    Some((files.into_iter().collect(), unread))
}

/// The files read for one claim, and the claim ids of the files left unread: a `uses`
/// edge to one of those is followed in a whole run, so reading fewer files must not
/// warn about it ([`crate::derivation::uses::warnings`]).
pub struct Reading {
    pub files: Vec<DerivationFile>,
    pub unread_ids: BTreeSet<String>,
}

impl Reading {
    /// Every file was read.
    pub fn whole(files: Vec<DerivationFile>) -> Reading {
        Reading {
            files,
            unread_ids: BTreeSet::new(),
        }
    }
}

/// [`load_files`] of the files claim `id` needs (every file when that cannot be told).
pub fn load_files_for(paths: &[PathBuf], id: &str) -> Result<Reading, LoadError> {
    let texts: Option<Vec<String>> = crate::parallel::in_index_order(paths.len(), |k| {
        read_bounded(&paths[k])
            .ok()
            .and_then(|b| String::from_utf8(b).ok())
    })
    .into_iter()
    .collect();
    let subset = texts.and_then(|t| needed(&t.iter().map(String::as_str).collect::<Vec<_>>(), id));
    Ok(match subset {
        Some((ks, unread_ids)) => Reading {
            files: load_files(&ks.iter().map(|&k| &paths[k]).collect::<Vec<_>>())?,
            unread_ids,
        },
        None => Reading::whole(load_files(paths)?),
    })
}

/// [`load_texts`] of the texts claim `id` needs (every text when that cannot be told).
pub fn load_texts_for(sources: &[(&str, &str)], id: &str) -> Result<Reading, LoadError> {
    let texts: Vec<&str> = sources.iter().map(|&(_, t)| t).collect();
    Ok(match needed(&texts, id) {
        Some((ks, unread_ids)) => Reading {
            files: load_texts(&ks.iter().map(|&k| sources[k]).collect::<Vec<_>>())?,
            unread_ids,
        },
        None => Reading::whole(load_texts(sources)?),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const A: &str = "x = 1\n[[claim]]\nid = \"a\"\nuses = [\"b\"]\n[[claim]]\nid = \"a2\"\n";
    const B: &str = "[[claim]]\nid = \"b\"\nuses = [\"c\", \"gone\"]\n";
    const C: &str = "[[claim]]\nid = \"c\"\nuses = [\"b\"]\n";
    const D: &str = "[[claim]]\nid = \"d\"\n";

    #[test]
    fn a_claim_needs_its_file_and_those_of_what_it_uses() {
        let texts = [A, B, C, D];
        let files = |id| needed(&texts, id).map(|(ks, _)| ks);
        assert_eq!(files("a"), Some(vec![0, 1, 2]));
        assert_eq!(files("a2"), Some(vec![0]));
        // A cycle (b → c → b) is read once; the whole run reports it.
        assert_eq!(files("c"), Some(vec![1, 2]));
        assert_eq!(files("d"), Some(vec![3]));
        // The ids of the files left unread are known, not missing.
        let unread = |id| needed(&texts, id).map(|(_, ids)| ids.into_iter().collect::<Vec<_>>());
        assert_eq!(unread("a2"), Some(vec!["b".into(), "c".into(), "d".into()]));
        assert_eq!(unread("a"), Some(vec!["d".into()]));
    }

    #[test]
    fn what_the_outline_cannot_tell_reads_every_file() {
        assert_eq!(needed(&[A, B], "nowhere"), None);
        assert_eq!(needed(&[A, B, "[[claim]]\nid = \"b\"\n"], "a2"), None);
        assert_eq!(needed(&[A, "[[claim]\n"], "a2"), None);
        assert_eq!(needed(&[A, "[[claim]]\nid = 3\n"], "a2"), None);
    }
}
