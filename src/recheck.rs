//! `recheck REPORT.json`: every proof of a JSON report checked again by the kernel
//! alone, from the statement the report records. No search runs: each proof's
//! statement and fact go to [`crate::kernel::check::check`] as they are written, and
//! the result must conclude what the report says (the verdict, and the same items
//! checked). An edited statement or fact that no longer holds, a verdict of strength
//! `proof` without its proof, or a proof whose conclusion is not the verdict, is refused.
//! What this cannot see is a statement edited into another true one: that is why each
//! line names what was proved, for the reader to compare with the paper.

use crate::check::ProofStatements;
use crate::kernel::check::{check, Checked, Conclusion, Fact, Rejection};
use crate::kernel::statement::Statement;
use serde::Deserialize;

/// The most bytes of a report `recheck` reads.
pub const MAX_REPORT_BYTES: usize = 256 << 20;

/// One proof as a report writes it.
#[derive(Deserialize)]
struct Written {
    conclusion: String,
    statement: Statement,
    fact: Fact,
    summary: serde_json::Value,
}

/// What `recheck` found.
/// Why a file is not a report that can be re-checked.
#[derive(Debug, thiserror::Error)]
pub enum NotAReport {
    #[error("the report is larger than {} MiB", MAX_REPORT_BYTES >> 20)]
    TooLarge,
    #[error("not a JSON report: {0}")]
    Json(#[from] serde_json::Error),
    #[error("not a cosserat-check report: no `claims` array")]
    NoClaims,
}

/// Why the proofs of one claim are refused.
#[derive(Debug, thiserror::Error)]
enum Refused {
    #[error("proofs recorded for a verdict of strength `{0}`")]
    NotOfStrengthProof(String),
    #[error("a `{0}` of strength proof without a kernel proof")]
    NoProof(String),
    #[error("a proof that is not well written: {0}")]
    IllWritten(serde_json::Error),
    #[error("{0}")]
    Kernel(#[from] Rejection),
    #[error("the proof concludes `{said}`, the report says `{written}`")]
    Conclusion { said: &'static str, written: String },
    #[error("the recorded summary is not what the kernel checked")]
    Summary,
    #[error("the recorded certificate is not what the kernel checked")]
    Certificate,
    #[error("the files given have no claim of this id")]
    NotInTheFiles,
    #[error("the proof is about another statement than the one its claim's file gives")]
    NotItsStatement,
    #[error("the proofs do not conclude the verdict `{0}`")]
    Verdict(String),
}

#[derive(Debug)]
pub struct Rechecked {
    /// One line per claim (and correction) with a verdict of strength `proof`.
    pub lines: Vec<String>,
    /// Proofs checked again and accepted.
    pub accepted: usize,
    /// Proofs, or verdicts, refused.
    pub refused: usize,
    /// Counts of the report's summary that are not the counts of its rows' verdicts.
    pub summary_refused: usize,
    /// Verdicts (of claims and corrections) that are not proofs: sampled or undecided,
    /// which the kernel has nothing to check for; `verify` decides them again.
    pub not_proofs: usize,
}

/// Text from the report, safe to print: control characters (terminal escapes) shown
/// as `\u{…}`, at most 200 characters.
fn shown(s: &str) -> String {
    let head: String = s.chars().take(200).collect();
    let mut out = crate::report::words::inert(&head.replace('\n', " "));
    if s.chars().count() > 200 {
        out.push('…');
    }
    out
}

/// The statements a claim's proofs may be about, by claim id (and whether it is the
/// correction), rebuilt from the derivation files: `None` when the files have no such
/// claim.
pub type Statements<'a> = dyn Fn(&str, bool) -> Option<ProofStatements> + Sync + 'a;

/// Re-checks every proof of the report `text`; `Err` when it is not a report. With
/// `files`, each proof must also be about the statement its claim's file gives (so that
/// a true proof moved onto another claim, or an edited statement, is refused).
pub fn recheck(text: &str, files: Option<&Statements<'_>>) -> Result<Rechecked, NotAReport> {
    // On a thread of its own: a statement may nest definitions as deep as the kernel's
    // bound, deeper than the caller's stack allows.
    std::thread::scope(|scope| {
        crate::parallel::spawn_scoped(scope, || recheck_here(text, files))
            .join()
            .unwrap_or_else(|e| std::panic::resume_unwind(e))
    })
}

/// The statements of every claim of `files` that a proof may be about, for [`recheck`].
pub fn statements_of(
    files: &[crate::derivation::DerivationFile],
) -> Result<std::collections::BTreeMap<(String, bool), ProofStatements>, crate::lang::Diagnostic> {
    let mut out = std::collections::BTreeMap::new();
    for claim in files.iter().flat_map(|f| &f.claims) {
        let own = crate::check::proof_statements(&claim.decls, &claim.check)?;
        out.insert((claim.id.clone(), false), own);
        if let Some(c) = &claim.correction {
            let corrected = crate::check::proof_statements(&claim.decls, &c.check)?;
            out.insert((claim.id.clone(), true), corrected);
        }
    }
    Ok(out)
}

fn recheck_here(text: &str, files: Option<&Statements<'_>>) -> Result<Rechecked, NotAReport> {
    if text.len() > MAX_REPORT_BYTES {
        return Err(NotAReport::TooLarge);
    }
    let report: serde_json::Value = serde_json::from_str(text)?;
    let claims = report
        .get("claims")
        .and_then(|c| c.as_array())
        .ok_or(NotAReport::NoClaims)?;
    let mut out = Rechecked {
        lines: Vec::new(),
        accepted: 0,
        refused: 0,
        summary_refused: 0,
        not_proofs: 0,
    };
    // The summary a reader sees first counts the claims' verdicts as the rows give them.
    if let Some(summary) = report.get("summary") {
        let count = |v: &str| {
            claims
                .iter()
                .filter(|c| c.get("verdict").and_then(|x| x.as_str()) == Some(v))
                .count()
        };
        for verdict in ["holds", "fails", "conditional", "undecided"] {
            if summary.get(verdict).and_then(|x| x.as_u64()) != Some(count(verdict) as u64) {
                out.summary_refused += 1;
                out.lines.push(format!(
                    "summary: REFUSED: `{verdict}` is not the number of claims whose verdict is `{verdict}`"
                ));
            }
        }
    }
    for claim in claims {
        let id = claim.get("id").and_then(|v| v.as_str()).unwrap_or("?");
        let mut rows = vec![(shown(id), claim, false)];
        if let Some(c) = claim.get("correction").filter(|c| !c.is_null()) {
            rows.push((format!("{} (correction)", shown(id)), c, true));
        }
        for (name, row, correction) in rows {
            let expected = files.map(|f| f(id, correction));
            match one(row, expected) {
                Ok(None) => out.not_proofs += 1,
                Ok(Some(line)) => {
                    out.accepted += 1;
                    out.lines.push(format!("{name}: {line}"));
                }
                Err(why) => {
                    out.refused += 1;
                    out.lines.push(format!("{name}: REFUSED: {why}"));
                }
            }
        }
    }
    Ok(out)
}

/// Whether a proof's statement is the one its file gives: equal, except that the part
/// of a `conditional` claim about a function that holds is proved on the domain the
/// decision found, a sub-box of the file's (its box is then not compared).
fn about(proved: &Statement, file: &Statement, conditional: bool) -> bool {
    use crate::kernel::statement::Claim;
    let scalar = !matches!(file.claim, Claim::Equal { .. } | Claim::Proportional { .. });
    let mut proved = proved.clone();
    if scalar && conditional {
        proved.context.given.clone_from(&file.context.given);
    }
    &proved == file
}

/// One claim's (or correction's) proofs: `None` when its verdict is not of strength
/// `proof`. `expected`, when the files were given: the statements its file gives
/// (`None` inside when the files have no such claim).
fn one(
    row: &serde_json::Value,
    expected: Option<Option<ProofStatements>>,
) -> Result<Option<String>, Refused> {
    let text = |k: &str| row.get(k).and_then(|v| v.as_str()).unwrap_or("");
    let (verdict, strength) = (text("verdict"), text("strength"));
    let written = row
        .get("proofs")
        .and_then(|p| p.as_array())
        .cloned()
        .unwrap_or_default();
    let certificate = row.get("certificate").filter(|c| !c.is_null());
    if strength != "proof" {
        if certificate.is_some() {
            return Err(Refused::NotOfStrengthProof(shown(strength)));
        }
        return if written.is_empty() {
            Ok(None)
        } else {
            Err(Refused::NotOfStrengthProof(shown(strength)))
        };
    }
    if written.is_empty() {
        return Err(Refused::NoProof(shown(verdict)));
    }
    let mut conclusions = Vec::new();
    let mut items = 0;
    let mut facts = Vec::new();
    // Which of the file's statements a proof is about: a `holds` proved in parts
    // (a sign on exactly a set) needs every part proved.
    let mut covered = Vec::new();
    for w in written {
        let w: Written = serde_json::from_value(w).map_err(Refused::IllWritten)?;
        match &expected {
            None => {}
            Some(None) => return Err(Refused::NotInTheFiles),
            Some(Some(statements)) => {
                let k = statements
                    .whole
                    .iter()
                    .chain(&statements.weaker)
                    .position(|s| about(&w.statement, s, verdict == "conditional"))
                    .ok_or(Refused::NotItsStatement)?;
                covered.push(k);
            }
        }
        let proof = check(w.statement, w.fact)?;
        let said = match proof.conclusion() {
            Conclusion::Holds => "holds",
            Conclusion::Fails => "fails",
        };
        if w.conclusion != said {
            return Err(Refused::Conclusion {
                said,
                written: shown(&w.conclusion),
            });
        }
        let summary: Vec<Checked> = proof.summary().to_vec();
        if serde_json::to_value(&summary).ok().as_ref() != Some(&w.summary) {
            return Err(Refused::Summary);
        }
        items += summary.len();
        facts.extend(summary);
        conclusions.push(proof.conclusion());
    }
    // The certificate a reader sees first is the proofs' summaries, and nothing else.
    if certificate != Some(&serde_json::json!({ "facts": facts })) {
        return Err(Refused::Certificate);
    }
    covered.sort_unstable();
    covered.dedup();
    // With the files, a `holds` has one proof for each statement of the whole claim
    // they give (and none of a weaker part).
    let every_part = match &expected {
        Some(Some(statements)) => {
            covered == (0..statements.whole.len()).collect::<Vec<_>>()
                && conclusions.len() == covered.len()
        }
        _ => true,
    };
    let agrees = match verdict {
        "holds" => {
            every_part
                && !conclusions.is_empty()
                && conclusions.iter().all(|c| *c == Conclusion::Holds)
        }
        "fails" => conclusions == [Conclusion::Fails],
        "conditional" => conclusions == [Conclusion::Holds, Conclusion::Fails],
        _ => false,
    };
    if !agrees {
        return Err(Refused::Verdict(shown(verdict)));
    }
    let s = if conclusions.len() == 1 { "" } else { "s" };
    Ok(Some(format!(
        "{verdict}: {} proof{s} checked again, {items} item{} verified",
        conclusions.len(),
        if items == 1 { "" } else { "s" }
    )))
}
