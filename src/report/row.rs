//! What a row of a table says beside its statement: the verdict and transcription
//! labels, and the evidence, reason, origin and correction in one paragraph.

use super::evidence::evidence;
use super::{graph, transcription};
use crate::check::Decided;

/// Whether a prose claim's statement is a formula rather than a sentence: it has no
/// `$…$` but LaTeX commands or scripts (a formula the paper does not print, stated by
/// the checker's own claims). Sentences are rendered as text with inline mathematics.
pub fn prose_is_formula(statement: &str) -> bool {
    !statement.contains('$') && statement.contains(['\\', '_', '^'])
}

/// Whether a row belongs in the errata: its printed statement fails, or holds only on
/// a domain (an undecided claim accuses nobody).
pub fn is_erratum(r: &Decided<'_>) -> bool {
    crate::check::inherit::failing(r.outcome.verdict())
}

/// The transcription status for a table: "machine", "differs", "hand" or "prose",
/// marked when a difference is not declared.
pub fn read_label(r: &Decided<'_>) -> String {
    if r.claim.prose {
        return "prose".to_owned();
    }
    let label = match r.transcription.label() {
        "machine-read" => "machine",
        other => other,
    };
    if r.transcription.as_expected() {
        label.to_owned()
    } else {
        format!("{label} ✗")
    }
}

/// The verdict, marked when it differs from the declared one.
pub fn verdict_label(r: &Decided<'_>) -> String {
    let mut text = r.outcome.verdict_text();
    if let Some(from) = graph::inherited_label(r) {
        text = format!("{text} ({from})");
    }
    if r.verdict_as_expected() {
        text
    } else {
        format!("{text} ✗ (declared: {})", r.claim.expect)
    }
}

/// A counterexample's point in the paper's notation: `symbol = value` for each nonzero
/// coordinate whose variable the claim's notation table names (read backwards), each
/// rendered by `math` (which lets only safe LaTeX through). None when no coordinate has
/// a printed name.
pub fn printed_point(r: &Decided<'_>, math: &dyn Fn(&str) -> String) -> Option<String> {
    let cx = r.outcome.counterexample.as_ref()?;
    let table = &r.claim.transcript.notation;
    let shown: Vec<String> = cx
        .point
        .iter()
        .filter(|(_, v)| v.as_str() != "0" && !v.starts_with('≈'))
        .filter_map(|(k, v)| {
            let symbol = table.printed(k)?;
            (symbol != *k).then(|| math(&format!("{symbol} = {v}")))
        })
        .collect();
    (!shown.is_empty()).then(|| format!("in the paper's notation, {}", shown.join(", ")))
}

/// A renderer of a formula or of words for one format.
pub type Render<'a> = &'a dyn Fn(&str) -> String;

/// The evidence, the reason and the correction of a row in one paragraph;
/// `statement` renders the correction's statement (math in Markdown or LaTeX),
/// `inline` a formula within the text (a counterexample in the paper's notation) and
/// `authored` the author's reason (its scripts, in LaTeX).
pub fn full_evidence(
    r: &Decided<'_>,
    (statement, inline): (Render<'_>, Render<'_>),
    authored: &dyn Fn(&str) -> String,
) -> String {
    let c = r.claim;
    let mut ev = evidence(&r.outcome);
    if let Some(p) = printed_point(r, inline) {
        ev.push_str(&format!(" ({p})"));
    }
    if !c.prose && r.transcription.label() != "machine-read" {
        ev.push_str(&format!(
            ". Read: {}",
            transcription::describe(&r.transcription, &c.statement).trim_end_matches('.')
        ));
    }
    if let Some(reason) = &c.reason {
        ev.push_str(&format!(
            ". Why: {}",
            authored(reason.trim_end_matches('.'))
        ));
    }
    if let Some(a) = &r.attribution {
        ev.push_str(&format!(". Origin: {}", graph::attribution(a)));
    }
    if let (Some(corr), Some(o)) = (&c.correction, &r.correction) {
        ev.push_str(&format!(
            ". Correction {}: {} ({}; {})",
            statement(&corr.statement),
            o.verdict_text(),
            o.method.as_str(),
            evidence(o)
        ));
        if o.verdict() != corr.expect {
            ev.push_str(&format!(" ✗ (declared: {})", corr.expect));
        }
    }
    ev
}
