//! A claim and its correction decided together, each with its transcription check.

use super::decided::Decided;
use super::dispatch::{decide_keeping, decide_unisolated, method_of};
use super::{isolate, transcription};
use crate::derivation::Claim;
use crate::lang::Diagnostic;

/// Decides a claim and its correction, keeping what each decision evaluated (for
/// `explain`).
pub fn decide_claim_recorded(claim: &Claim) -> Result<Decided<'_>, Diagnostic> {
    decide_claim_keeping(claim, true)
}

/// Decides a claim and its correction.
pub fn decide_claim(claim: &Claim) -> Result<Decided<'_>, Diagnostic> {
    decide_claim_keeping(claim, false)
}

fn decide_claim_keeping(claim: &Claim, keep: bool) -> Result<Decided<'_>, Diagnostic> {
    // Where a limit is reported: the statement's first side, or the claim itself (a
    // claim about a function has no sides).
    let at = match claim.check.location() {
        at if at.is_empty() => claim.origin.diagnostic(Default::default(), "").location(),
        at => at,
    };
    let outcome = isolate::isolated(method_of(&claim.check), &at, || {
        isolate::test_hook(&claim.id);
        decide_unisolated(&claim.decls, &claim.check, keep)
    })?;
    let correction = match &claim.correction {
        Some(c) => Some(decide_keeping(&claim.decls, &c.check, keep)?),
        None => None,
    };
    let transcription = transcription::transcribe_isolated(
        &claim.id,
        &claim.decls,
        &claim.check,
        &claim.transcript,
    );
    let correction_transcription = claim.correction.as_ref().map(|c| {
        transcription::transcribe_isolated(&claim.id, &claim.decls, &c.check, &c.transcript)
    });
    Ok(Decided {
        claim,
        outcome,
        correction,
        transcription,
        correction_transcription,
        attribution: None,
    })
}
