//! Strategies: how a claim is decided. Each returns an [`Outcome`] carrying the
//! evidence its verdict requires (component checks, counterexample, the kernel's
//! certificate). `Outcome` lives in its own module so that no strategy can reach its
//! private fields: a proved `holds` is made only from a certificate.

pub mod assume;
pub mod eval;
pub mod exact;
pub mod finding;
pub mod float;
mod indices;
#[cfg(test)]
mod indices_tests;
pub mod inherit;
mod interval;
pub mod isolate;
mod jets;
pub mod numeric;
mod outcome;
pub mod probe;
mod proportional;
pub mod quadrature;
pub mod real;
mod reverify;
pub mod sampler;
mod scalar;
pub mod search;
pub mod statement;
pub mod tape;
pub mod taylor;
pub mod transcription;
mod variation;
pub mod walk;
pub mod watch;
pub mod witness;

pub use outcome::{
    Counterexample, FactorWitness, Measure, Method, NumericEvidence, Outcome, Reverified,
    SearchEvidence, Strength,
};

use crate::derivation::Claim;
use crate::lang::Diagnostic;

/// A decided claim: the claim's own outcome and its correction's.
#[derive(Clone, Debug)]
pub struct Decided<'c> {
    pub claim: &'c Claim,
    pub outcome: Outcome,
    pub correction: Option<Outcome>,
    /// Whether the sides say what the printed statement says.
    pub transcription: transcription::Transcription,
    /// The same for the correction's printed statement.
    pub correction_transcription: Option<transcription::Transcription>,
    /// For a claim that fails: whether it is a root error or inherits its failure from
    /// claims it uses ([`inherit::attribute`], once every claim is decided).
    pub attribution: Option<inherit::Attribution>,
}

impl Decided<'_> {
    /// Whether every verdict equals its declared expectation, and every transcription
    /// that differs from the printed statement is declared to.
    pub fn as_expected(&self) -> bool {
        self.transcription.as_expected()
            && self
                .correction_transcription
                .as_ref()
                .is_none_or(transcription::Transcription::as_expected)
            && self.verdict_as_expected()
    }

    /// Whether every verdict equals its declared expectation.
    pub fn verdict_as_expected(&self) -> bool {
        self.outcome.verdict() == self.claim.expect
            && match (&self.claim.correction, &self.correction) {
                (Some(c), Some(o)) => o.verdict() == c.expect,
                _ => true,
            }
    }
}

/// Decides one check with its strategy.
pub fn decide(
    decls: &crate::lang::Decls,
    check: &crate::derivation::Check,
) -> Result<Outcome, Diagnostic> {
    decide_keeping(decls, check, false)
}

/// Decides one check and keeps what the decision evaluated (`Outcome::record`): the
/// canonical expansion of every side, or the first states drawn.
pub fn decide_recorded(
    decls: &crate::lang::Decls,
    check: &crate::derivation::Check,
) -> Result<Outcome, Diagnostic> {
    decide_keeping(decls, check, true)
}

fn decide_keeping(
    decls: &crate::lang::Decls,
    check: &crate::derivation::Check,
    keep: bool,
) -> Result<Outcome, Diagnostic> {
    isolate::isolated(method_of(check), || decide_unisolated(decls, check, keep))
}

/// The method a check's strategy decides with.
fn method_of(check: &crate::derivation::Check) -> Method {
    use crate::derivation::Strategy;
    match &check.strategy {
        Strategy::Numeric { .. } => Method::Numeric,
        Strategy::Gradient { .. } => Method::Gradient,
        Strategy::Convex { .. } => Method::Convex,
        Strategy::Exact { .. } | Strategy::Proportional { .. } => Method::Exact,
        Strategy::NotCircle { .. } => Method::Witness,
        Strategy::Scalar { .. } => Method::RationalFunction,
    }
}

/// [`decide_keeping`] without the panic isolation.
fn decide_unisolated(
    decls: &crate::lang::Decls,
    check: &crate::derivation::Check,
    keep: bool,
) -> Result<Outcome, Diagnostic> {
    use crate::derivation::Strategy;
    let sink = sampler::Sink::default();
    let states = keep.then_some(&sink);
    let method = method_of(check);
    if method != Method::Exact && check.reads().differentiates {
        return Ok(
            Outcome::undecided(method, 0).with_finding(finding::Finding::DerivativesNotSampled)
        );
    }
    // A computation stopped at the time limit unwinds to here (`interrupt::tick`);
    // the watch has expired then, so the match below makes it undecided.
    let decided = crate::kernel::interrupt::stoppable(|| match &check.strategy {
        Strategy::Exact { .. } | Strategy::Proportional { .. } => exact::decide(decls, check, keep),
        Strategy::Numeric { .. } => numeric::decide_numeric(decls, check, states),
        Strategy::Gradient { .. } => numeric::decide_gradient(decls, check, states),
        Strategy::Convex { .. } => numeric::decide_convex(decls, check, states),
        Strategy::NotCircle { .. } => witness::decide_not_circle(decls, check),
        Strategy::Scalar { .. } => scalar::decide(decls, check),
    })
    .unwrap_or_else(|_| {
        Ok(
            Outcome::undecided(method, 0).with_finding(finding::Finding::TimeLimit {
                seconds: watch::expired().map_or(0.0, |l| l.as_secs_f64()),
            }),
        )
    });
    // A decision that outlived the time limit is undecided: it was stopped
    // (`watch::check`), whatever error the stop surfaced as, or the kernel gave up a
    // step and returned a meaningless value (`kernel::interrupt`). One that finished
    // in time stands.
    let mut outcome = match (decided, watch::expired()) {
        (Ok(o), None) => o,
        (_, Some(limit)) => {
            Outcome::undecided(method, 0).with_finding(finding::Finding::TimeLimit {
                seconds: limit.as_secs_f64(),
            })
        }
        (Err(e), None) => return Err(e),
    };
    if keep {
        outcome.record.get_or_insert_with(Default::default).states = sink.into_inner();
    }
    Ok(outcome)
}

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
    let outcome = isolate::isolated(method_of(&claim.check), || {
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
