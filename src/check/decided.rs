//! A decided claim: its outcome, its correction's, whether the sides say what is
//! printed, and (once every claim is decided) where a failure comes from.

use super::transcription;
use crate::decide::Outcome;
use crate::derivation::Claim;

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
    /// claims it uses ([`super::inherit::attribute`], once every claim is decided).
    pub attribution: Option<Attribution>,
}

impl Decided<'_> {
    /// Whether a claim that declares no verdict fails (or holds only on a domain): the
    /// run's exit status says so, as it does for an unexpected verdict.
    pub fn fails_undeclared(&self) -> bool {
        !self.claim.declared
            && matches!(
                self.outcome.verdict(),
                crate::derivation::Verdict::Fails | crate::derivation::Verdict::Conditional
            )
    }

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

    /// Whether every verdict equals its declared expectation (a claim that declares
    /// none is as found).
    pub fn verdict_as_expected(&self) -> bool {
        (!self.claim.declared || self.outcome.verdict() == self.claim.expect)
            && match (&self.claim.correction, &self.correction) {
                (Some(c), Some(o)) => o.verdict() == c.expect,
                _ => true,
            }
    }
}

/// Where a failing claim's failure comes from.
#[derive(Clone, Debug)]
pub enum Attribution {
    /// The claim's own step is wrong: it still fails with `corrected` (the failing
    /// claims it uses whose statements enter its check) replaced by their corrections,
    /// or no failing claim it uses enters its check at all.
    Root {
        corrected: Vec<String>,
        /// The re-decision with `corrected` replaced (none when nothing was replaced).
        outcome: Option<Outcome>,
    },
    /// The claim holds once `from` are replaced by their corrections.
    Inherited { from: Vec<String>, outcome: Outcome },
    /// The checker cannot tell: a failing claim whose statement enters the check has
    /// no corrected form to replace it with (`uncorrectable`), or the re-decision was
    /// undecided. Never counted as a root error.
    Undetermined {
        corrected: Vec<String>,
        uncorrectable: Vec<String>,
        outcome: Option<Outcome>,
    },
}

impl Attribution {
    /// Whether the claim is a root error.
    pub fn is_root(&self) -> bool {
        matches!(self, Attribution::Root { .. })
    }

    /// The claims the failure is inherited from (empty unless inherited).
    pub fn inherited_from(&self) -> &[String] {
        match self {
            Attribution::Inherited { from, .. } => from,
            _ => &[],
        }
    }

    /// `root`, `inherited` or `undetermined`.
    pub fn label(&self) -> &'static str {
        match self {
            Attribution::Root { .. } => "root",
            Attribution::Inherited { .. } => "inherited",
            Attribution::Undetermined { .. } => "undetermined",
        }
    }
}
