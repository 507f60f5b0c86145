//! The counts a table is summarised by, and the work it is credited to.

use crate::check::Decided;
use serde::Serialize;

/// The work a table is credited to: the papers of its rows' files, in order; with no
/// rows, the papers of the files read (`files_papers`). A file without `paper = …` is
/// "untitled derivations: FILE", never another work.
pub fn paper_of(rows: &[&Decided<'_>], files_papers: &[&str]) -> String {
    let mut papers: Vec<&str> = Vec::new();
    let all = rows.iter().map(|r| r.claim.paper.as_str());
    let all: Vec<&str> = if rows.is_empty() {
        files_papers.to_vec()
    } else {
        all.collect()
    };
    for p in all {
        if !papers.contains(&p) {
            papers.push(p);
        }
    }
    papers.join("; ")
}

/// Verdict counts over a table.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Summary {
    pub holds: usize,
    pub fails: usize,
    pub conditional: usize,
    /// Claims the checker could not decide (each says why).
    pub undecided: usize,
    /// Claims whose verdict (or whose correction's verdict) differs from the one the
    /// derivation file declares, or whose sides differ from the printed statement
    /// where the claim does not declare why.
    pub unexpected: usize,
    /// Claims whose file declares no verdict (`expect`): reported as found.
    pub undeclared: usize,
    /// Formula claims whose sides were decided to say what the printed LaTeX says.
    pub machine_read: usize,
    /// Formula claims whose sides differ from the printed LaTeX (declared or not).
    pub differs: usize,
    /// Formula claims whose printed LaTeX is read by hand (outside the subset, or a
    /// claim kind that is not an equation chain).
    pub hand: usize,
    /// Claims that are sentences of prose.
    pub prose: usize,
    /// Failing claims whose own step is wrong.
    pub root_errors: usize,
    /// Failing claims that hold once the failing claims they use are corrected.
    pub inherited: usize,
    /// Failing claims whose origin the checker cannot tell (it says why).
    pub undetermined_origin: usize,
}

impl Summary {
    /// "N claims: … hold, … fail, … conditional[, … undecided]; … unexpected."
    pub fn sentence(&self, n: usize) -> String {
        let undecided = if self.undecided > 0 {
            format!(", {} undecided", self.undecided)
        } else {
            String::new()
        };
        let undeclared = match self.undeclared {
            0 => String::new(),
            k => format!(" ({k} without a declared verdict, reported as found)"),
        };
        format!(
            "{n} claim{}: {} hold, {} fail, {} conditional{undecided}; {} unexpected{undeclared}.",
            if n == 1 { "" } else { "s" },
            self.holds,
            self.fails,
            self.conditional,
            self.unexpected
        )
    }

    pub fn of(rows: &[&Decided<'_>]) -> Self {
        let mut s = Summary::default();
        for r in rows {
            match r.outcome.verdict() {
                crate::derivation::Verdict::Holds => s.holds += 1,
                crate::derivation::Verdict::Fails => s.fails += 1,
                crate::derivation::Verdict::Conditional => s.conditional += 1,
                crate::derivation::Verdict::Undecided => s.undecided += 1,
            }
            if !r.as_expected() {
                s.unexpected += 1;
            }
            if !r.claim.declared {
                s.undeclared += 1;
            }
            match r.attribution.as_ref().map(|a| a.label()) {
                Some("root") => s.root_errors += 1,
                Some("inherited") => s.inherited += 1,
                Some(_) => s.undetermined_origin += 1,
                None => {}
            }
            if r.claim.prose {
                s.prose += 1;
            } else {
                match r.transcription.label() {
                    "machine-read" => s.machine_read += 1,
                    "differs" => s.differs += 1,
                    _ => s.hand += 1,
                }
            }
        }
        s
    }

    /// "Origin of the N failing or conditional claims: … root errors, … inherited[, … of
    /// undetermined origin]." (empty when nothing fails).
    pub fn origin_sentence(&self) -> String {
        let failing = self.root_errors + self.inherited + self.undetermined_origin;
        if failing == 0 {
            return String::new();
        }
        let undetermined = if self.undetermined_origin > 0 {
            format!(", {} of undetermined origin", self.undetermined_origin)
        } else {
            String::new()
        };
        // Conditional claims fail outside their domain: they are counted here too, so
        // that the numbers add up to the fails and conditionals above.
        format!(
            "Origin of the {failing} failing or conditional claim{}: {} root error{}, {} inherited from a failing claim they use{undetermined}.",
            if failing == 1 { "" } else { "s" },
            self.root_errors,
            if self.root_errors == 1 { "" } else { "s" },
            self.inherited
        )
    }

    /// "Printed statements: … of … formula claims machine-read, … differ (declared), …
    /// read by hand; … prose."
    pub fn transcription_sentence(&self) -> String {
        let formulas = self.machine_read + self.differs + self.hand;
        format!(
            "Printed statements: {} of {formulas} formula claims machine-read, {} differ from their sides, {} read by hand; {} prose.",
            self.machine_read, self.differs, self.hand, self.prose
        )
    }
}

/// References to every row (the renderers take slices of references so that
/// `errata` can pass a filtered view).
pub fn refs<'a, 'c>(rows: &'a [Decided<'c>]) -> Vec<&'a Decided<'c>> {
    rows.iter().collect()
}
