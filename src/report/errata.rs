//! The errata: every printed statement that fails (or holds only on a domain), with
//! the counterexample, the correction and its verdict, and the reason — ready to paste
//! into an erratum.

use super::evidence::evidence;
use super::graph;
use super::markdown::{cell, math, statement};
use crate::check::Decided;
use std::fmt::Write as _;

/// The errata in Markdown: each root error, then the failures inherited from it, then
/// the failures whose origin cannot be told; one section per statement.
pub fn markdown(rows: &[&Decided<'_>], paper: &str) -> String {
    let mut out = format!("# Errata\n\n{}.\n\n", super::markdown::line(paper));
    if rows.is_empty() {
        out.push_str("Every printed statement checked holds.\n");
        return out;
    }
    let summary = super::Summary::of(rows);
    let _ = writeln!(
        out,
        "{} statements do not hold as printed. {}\n",
        rows.len(),
        summary.origin_sentence()
    );
    for (root, inherited) in graph::grouped(rows) {
        section(&mut out, root, "##");
        for r in inherited {
            section(&mut out, r, "###");
        }
    }
    out
}

fn section(out: &mut String, r: &Decided<'_>, level: &str) {
    let c = r.claim;
    let origin = match &r.attribution {
        Some(a) if a.is_root() => " — root error".to_owned(),
        Some(a) if !a.inherited_from().is_empty() => {
            format!(" — inherited from {}", a.inherited_from().join(", "))
        }
        Some(_) => " — origin undetermined".to_owned(),
        None => String::new(),
    };
    let _ = writeln!(
        out,
        "{level} {} (Section {}){origin}\n",
        cell(&c.id),
        cell(&c.section)
    );
    let _ = writeln!(out, "- As printed: {}", statement(c));
    let _ = writeln!(
        out,
        "- Verdict: **{}** (method {})",
        r.outcome.verdict_text(),
        r.outcome.method.as_str()
    );
    if let Some(reason) = &c.reason {
        let _ = writeln!(out, "- Why: {}", cell(reason));
    }
    if let Some(a) = &r.attribution {
        let _ = writeln!(out, "- Origin: {}", cell(&graph::attribution(a)));
    }
    // The printed point's words are plain and its formulas pass `math`'s check.
    let printed = super::row::printed_point(r, &math)
        .map(|p| format!(" ({p})"))
        .unwrap_or_default();
    let _ = writeln!(out, "- Evidence: {}{printed}", cell(&evidence(&r.outcome)));
    if let (Some(k), Some(o)) = (&c.correction, &r.correction) {
        let _ = writeln!(out, "- Correction: {}", math(&k.statement));
        let _ = writeln!(out, "  - {}", cell(&k.reason));
        let _ = writeln!(
            out,
            "  - Verdict: **{}** (method {}; {})",
            o.verdict_text(),
            o.method.as_str(),
            cell(&evidence(o))
        );
    }
    if let Some(note) = &c.note {
        let _ = writeln!(out, "- Note: {}", cell(note));
    }
    out.push('\n');
}
