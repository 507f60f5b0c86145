//! The derivation table in Markdown, with statements as inline LaTeX (`$…$`), ready to
//! paste into a README, a review or an erratum.

use super::{evidence, Summary, PAPER};
use crate::strategy::Decided;
use std::fmt::Write as _;

/// Makes text safe inside a Markdown table cell.
fn cell(s: &str) -> String {
    s.split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
        .replace('|', "\\|")
}

fn math(s: &str) -> String {
    format!("${}$", cell(s))
}

/// Renders the whole table with its summary line.
pub fn render(rows: &[Decided<'_>]) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "# Derivation table\n");
    let _ = writeln!(out, "{PAPER}.\n");
    let _ = writeln!(
        out,
        "| claim | § | statement (as printed) | verdict | method | evidence |"
    );
    let _ = writeln!(out, "|---|---|---|---|---|---|");
    for r in rows {
        let c = r.claim;
        let mut verdict = match r.outcome.verdict {
            crate::derivation::Verdict::Holds => "holds".to_owned(),
            v => format!("**{v}**"),
        };
        if !r.as_expected() {
            let _ = write!(verdict, " ✗ (declared: {})", c.expect);
        }
        let mut ev = evidence(&r.outcome);
        if let Some(reason) = &c.reason {
            let _ = write!(ev, ". Why: {}", reason.trim_end_matches('.'));
        }
        if let (Some(corr), Some(o)) = (&c.correction, &r.correction) {
            let _ = write!(
                ev,
                ". Correction {}: {} ({}; {})",
                math(&corr.statement),
                o.verdict,
                o.method.as_str(),
                evidence(o)
            );
            if o.verdict != corr.expect {
                let _ = write!(ev, " ✗ (declared: {})", corr.expect);
            }
        }
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} | {} | {} |",
            cell(&c.id),
            cell(&c.section),
            if c.prose {
                format!("“{}”", cell(&c.statement))
            } else {
                math(&c.statement)
            },
            verdict,
            r.outcome.method.as_str(),
            cell(&ev)
        );
    }
    let s = Summary::of(rows);
    let _ = writeln!(
        out,
        "\n{} claims: {} hold, {} fail, {} conditional; {} unexpected.",
        rows.len(),
        s.holds,
        s.fails,
        s.conditional,
        s.unexpected
    );
    out
}
