//! The JSON contract of `check --format json`. Later versions may add fields but never
//! remove or rename these: `paper`, `claims[]` (`id`, `section`, `statement`,
//! `verdict`, `method`, `strength` (`proof` or `sampled`), `expected`, `checks`,
//! `certificate` (what the kernel checked behind a proof: `{"facts": [{"kind": …}]}`,
//! or null), `proofs` (each kernel proof whole: its `conclusion`, the `statement` it
//! is about, the `fact` checked and its `summary`, which `recheck` checks again),
//! `counterexample`, `correction`, `transcription` (`status`: `machine-read`,
//! `differs` or `hand`, `detail`, `declared`, `checked_latex`), `uses`, `root`,
//! `inherited_from`, `origin` (`status`: `root`, `inherited` or `undetermined`, `detail`;
//! null unless the claim fails)), and `summary` (`holds`, `fails`, `conditional`,
//! `undecided`, `unexpected`, `machine_read`, `differs`, `hand`, `prose`, `root_errors`,
//! `inherited`, `undetermined_origin`).

use super::summary::Summary;
use crate::check::Decided;
use crate::decide::finding::Finding;
use crate::decide::{Counterexample, Method, NumericEvidence, Outcome, Strength};
use crate::kernel::check::Proof;
use serde::Serialize;
use serde_json::value::RawValue;

#[derive(Serialize)]
struct Report<'a> {
    paper: &'a str,
    claims: Vec<ClaimRow<'a>>,
    summary: Summary,
}

#[derive(Serialize)]
struct ClaimRow<'a> {
    id: &'a str,
    section: &'a str,
    statement: &'a str,
    verdict: &'static str,
    method: Method,
    strength: Strength,
    /// The declared verdict; null when the file declares none.
    expected: Option<&'static str>,
    checks: usize,
    certificate: Option<serde_json::Value>,
    proofs: Vec<Box<RawValue>>,
    counterexample: Option<&'a Counterexample>,
    correction: Option<CorrectionRow<'a>>,
    as_expected: bool,
    used_unit_normal: bool,
    numeric: Option<&'a NumericEvidence>,
    /// The finding in words.
    detail: Option<String>,
    /// The finding as data (`decide::Finding`).
    finding: Option<&'a Finding>,
    reason: Option<&'a str>,
    note: Option<&'a str>,
    transcription: TranscriptionRow,
    /// The claims this one is derived from.
    uses: Vec<&'a str>,
    /// A failing claim whose own step is wrong (false for every other claim).
    root: bool,
    /// The failing claims whose correction makes this failing claim hold.
    inherited_from: Vec<&'a str>,
    /// For a failing claim: `root`, `inherited` or `undetermined`, in words.
    origin: Option<OriginRow>,
}

#[derive(Serialize)]
struct OriginRow {
    status: &'static str,
    detail: String,
}

/// Whether the sides say what the printed statement says (`machine-read`, `differs`,
/// `hand`), in words, and the checked chains typeset as LaTeX.
#[derive(Serialize)]
struct TranscriptionRow {
    status: &'static str,
    detail: String,
    declared: bool,
    checked_latex: Vec<String>,
}

fn transcription_row(
    t: &crate::check::transcription::Transcription,
    check: &crate::derivation::Check,
    transcript: &crate::derivation::Transcript,
    printed: &str,
) -> TranscriptionRow {
    use crate::check::transcription::Status;
    TranscriptionRow {
        status: t.label(),
        detail: super::transcription::describe(t, printed),
        declared: matches!(
            &t.status,
            Status::Differs {
                declared: Some(_),
                ..
            }
        ),
        checked_latex: super::typeset::checked(check, transcript),
    }
}

#[derive(Serialize)]
struct CorrectionRow<'a> {
    statement: &'a str,
    verdict: &'static str,
    method: Method,
    strength: Strength,
    expected: &'static str,
    checks: usize,
    certificate: Option<serde_json::Value>,
    proofs: Vec<Box<RawValue>>,
    counterexample: Option<&'a Counterexample>,
    reason: &'a str,
    transcription: Option<TranscriptionRow>,
}

/// What the kernel checked, as `{"facts": [...]}`: the items of its proofs.
fn certificate(o: &Outcome) -> Option<serde_json::Value> {
    if o.proofs().is_empty() {
        return None;
    }
    let facts: Vec<_> = o.proofs().iter().flat_map(|p| p.summary()).collect();
    Some(serde_json::json!({ "facts": facts }))
}

/// Each proof whole, on one line (a statement is a deep tree: written out one token
/// per line, it would be most of the report).
fn proofs(o: &Outcome) -> Vec<Box<RawValue>> {
    o.proofs()
        .iter()
        .map(|p| {
            let p: &Proof = p;
            serde_json::value::to_raw_value(p).expect("plain data serialises")
        })
        .collect()
}

/// Renders the table as pretty-printed JSON (deterministic: fixed field order).
pub fn render(rows: &[&Decided<'_>], paper: &str) -> String {
    let claims =
        rows.iter()
            .map(|r| {
                let c = r.claim;
                ClaimRow {
                    id: &c.id,
                    section: &c.section,
                    statement: &c.statement,
                    verdict: r.outcome.verdict().as_str(),
                    method: r.outcome.method,
                    strength: r.outcome.strength(),
                    expected: c.declared.then(|| c.expect.as_str()),
                    checks: r.outcome.checks,
                    certificate: certificate(&r.outcome),
                    proofs: proofs(&r.outcome),
                    counterexample: r.outcome.counterexample.as_ref(),
                    correction: c
                        .correction
                        .as_ref()
                        .zip(r.correction.as_ref())
                        .map(|(k, o)| CorrectionRow {
                            statement: &k.statement,
                            verdict: o.verdict().as_str(),
                            method: o.method,
                            strength: o.strength(),
                            expected: k.expect.as_str(),
                            checks: o.checks,
                            certificate: certificate(o),
                            proofs: proofs(o),
                            counterexample: o.counterexample.as_ref(),
                            reason: &k.reason,
                            transcription: r.correction_transcription.as_ref().map(|t| {
                                transcription_row(t, &k.check, &k.transcript, &k.statement)
                            }),
                        }),
                    as_expected: r.as_expected(),
                    used_unit_normal: r.outcome.used_unit_normal,
                    numeric: r.outcome.numeric.as_ref(),
                    detail: r.outcome.finding.as_ref().map(super::words::finding),
                    finding: r.outcome.finding.as_ref(),
                    reason: c.reason.as_deref(),
                    note: c.note.as_deref(),
                    transcription: transcription_row(
                        &r.transcription,
                        &c.check,
                        &c.transcript,
                        &c.statement,
                    ),
                    uses: c.uses.iter().map(|u| u.id.as_str()).collect(),
                    root: r.attribution.as_ref().is_some_and(|a| a.is_root()),
                    inherited_from: r
                        .attribution
                        .iter()
                        .flat_map(|a| a.inherited_from())
                        .map(String::as_str)
                        .collect(),
                    origin: r.attribution.as_ref().map(|a| OriginRow {
                        status: a.label(),
                        detail: super::graph::attribution(a),
                    }),
                }
            })
            .collect();
    let report = Report {
        paper,
        claims,
        summary: Summary::of(rows),
    };
    let mut s = serde_json::to_string_pretty(&report).expect("plain data serialises");
    s.push('\n');
    s
}
