//! The compact table for a terminal: one line per claim with its id, section,
//! verdict, strength, method, transcription status and one short line of evidence,
//! failures highlighted.
//! The full evidence stays in `explain`, `--format markdown`, JSON and HTML; this view
//! only shortens it.

use super::summary::Summary;
use super::words::{self, inert};
use crate::check::Decided;
use crate::decide::{Counterexample, Outcome, Strength};
use crate::derivation::Verdict;
use std::fmt::Write as _;

/// The widest the evidence column gets, in characters, when the width of the terminal
/// is not known; longer evidence ends in `…`.
pub const EVIDENCE_WIDTH: usize = 80;

/// The narrowest the evidence column gets on a narrow terminal.
const EVIDENCE_MIN: usize = 24;

/// How the table marks failures: `color` adds ANSI colours (bold red for `fails`,
/// yellow for `conditional` and `undecided`) to the words, which say it without them.
/// `columns`, the terminal's width when known: the evidence then fills what the other
/// columns leave (never less than a short phrase). For the `errata`, each root error
/// comes with the failures inherited from it beneath it (`↳`), then those whose origin
/// cannot be told.
pub fn render(
    rows: &[&Decided<'_>],
    paper: &str,
    (color, columns): (bool, Option<usize>),
    explain: &str,
    errata: bool,
) -> String {
    let marked: Vec<(&Decided<'_>, bool)> = if errata {
        super::graph::grouped(rows)
            .into_iter()
            .flat_map(|(root, inherited)| {
                std::iter::once((root, false)).chain(inherited.into_iter().map(|r| (r, true)))
            })
            .collect()
    } else {
        rows.iter().map(|&r| (r, false)).collect()
    };
    table(&marked, paper, color, explain, columns)
}

/// The table of `rows`, each marked when it sits beneath the root error it inherits
/// from.
fn table(
    marked: &[(&Decided<'_>, bool)],
    paper: &str,
    color: bool,
    explain: &str,
    columns: Option<usize>,
) -> String {
    let rows: Vec<&Decided<'_>> = marked.iter().map(|(r, _)| *r).collect();
    let header = [
        "claim", "§", "verdict", "strength", "method", "read", "evidence",
    ];
    let lines: Vec<[String; 7]> = marked
        .iter()
        .map(|&(r, beneath)| {
            [
                if beneath {
                    format!("  ↳ {}", inert(&r.claim.id))
                } else {
                    inert(&r.claim.id)
                },
                inert(&r.claim.section),
                verdict(r),
                match r.outcome.strength() {
                    Strength::Proof => "proof",
                    Strength::Sampled => "sampled",
                }
                .to_owned(),
                r.outcome.method.as_str().to_owned(),
                super::row::read_label(r),
                inert(&short_evidence(r)),
            ]
        })
        .collect();
    let width = |k: usize| {
        lines
            .iter()
            .map(|l| l[k].chars().count())
            .chain([header[k].chars().count()])
            .max()
            .unwrap_or(0)
    };
    let widths: Vec<usize> = (0..6).map(width).collect();
    let evidence = columns.map_or(EVIDENCE_WIDTH, |c| {
        c.saturating_sub(widths.iter().map(|w| w + 2).sum::<usize>())
            .max(EVIDENCE_MIN)
    });
    let lines: Vec<[String; 7]> = lines
        .into_iter()
        .map(|mut l| {
            l[6] = shorten(&l[6], evidence);
            l
        })
        .collect();
    let mut out = String::new();
    let _ = writeln!(out, "{}\n", inert(paper));
    let row = |cells: [&str; 7], paint: Option<&str>| {
        let mut line = String::new();
        for (k, cell) in cells.iter().enumerate().take(6) {
            let pad = widths[k] - cell.chars().count();
            match (k, paint) {
                (2, Some(code)) => {
                    let _ = write!(line, "\x1b[{code}m{cell}\x1b[0m{}  ", " ".repeat(pad));
                }
                _ => {
                    let _ = write!(line, "{cell}{}  ", " ".repeat(pad));
                }
            }
        }
        line.push_str(cells[6]);
        line.trim_end().to_owned()
    };
    let _ = writeln!(out, "{}", row(header, None));
    for (r, l) in rows.iter().zip(&lines) {
        let paint = match (color, r.outcome.verdict(), r.as_expected()) {
            (false, _, _) => None,
            (true, _, false) | (true, Verdict::Fails, _) => Some("1;31"),
            (true, Verdict::Conditional | Verdict::Undecided, _) => Some("33"),
            (true, Verdict::Holds, _) => None,
        };
        let cells = [&l[0], &l[1], &l[2], &l[3], &l[4], &l[5], &l[6]].map(String::as_str);
        let _ = writeln!(out, "{}", row(cells, paint));
    }
    let summary = Summary::of(&rows);
    let _ = writeln!(out, "\n{}", summary.sentence(rows.len()));
    let origin = summary.origin_sentence();
    if !origin.is_empty() {
        let _ = writeln!(out, "{origin}");
    }
    let _ = writeln!(
        out,
        "{}\nFull evidence: `{}`, or `--format markdown|json|html` (this compact view is \
         printed only to a terminal).",
        summary.transcription_sentence(),
        super::words::inert(explain)
    );
    out
}

/// The verdict in capitals when it accuses the paper (`FAILS`), so that a failure
/// stands out without colour; marked `✗` when it is not the declared one.
fn verdict(r: &Decided<'_>) -> String {
    let v = r.outcome.verdict();
    let mut text = match v {
        Verdict::Fails => "FAILS".to_owned(),
        _ => v.as_str().to_owned(),
    };
    if !r.verdict_as_expected() {
        let _ = write!(text, " ✗ (declared {})", r.claim.expect);
    }
    text
}

/// One short line: what decided the claim, and for a failure what its correction
/// gives.
fn short_evidence(r: &Decided<'_>) -> String {
    let mut line = super::graph::inherited_label(r)
        .map(|from| format!("{from}; "))
        .unwrap_or_default();
    line.push_str(&outcome_line(&r.outcome));
    if let Some(c) = &r.correction {
        let _ = write!(line, "; correction {}", c.verdict_text());
    }
    line
}

fn outcome_line(o: &Outcome) -> String {
    if let Some(cx) = &o.counterexample {
        return match (
            o.verdict(),
            o.numeric.as_ref().and_then(|n| n.domain.as_ref()),
        ) {
            (Verdict::Conditional, Some(domain)) => {
                format!("holds with {domain}; outside, {}", counterexample_line(cx))
            }
            _ => counterexample_line(cx),
        };
    }
    if let (Verdict::Undecided, Some(f)) = (o.verdict(), &o.finding) {
        return words::finding(f);
    }
    if let Some(w) = super::evidence::proof_words(o) {
        return w;
    }
    if let Some(n) = &o.numeric {
        return format!(
            "{} samples (seed {}): {}",
            n.samples,
            n.seed,
            words::measure(n.residual, n.largest_residual, false)
        );
    }
    o.finding.as_ref().map(words::finding).unwrap_or_default()
}

fn counterexample_line(cx: &Counterexample) -> String {
    if let Some(m) = &cx.ill_formed {
        return format!("ill-formed: {m}");
    }
    let at: Vec<String> = cx.indices.iter().map(|(c, v)| format!("{c}={v}")).collect();
    let at = if at.is_empty() {
        String::new()
    } else {
        format!("at {}: ", at.join(", "))
    };
    match (&cx.lhs_value, &cx.rhs_value) {
        (Some(l), Some(r)) => format!("{at}left {l}, right {r}"),
        _ if !cx.difference.is_empty() => format!("{at}left − right = {}", cx.difference),
        _ => {
            let aux: Vec<String> = cx.aux.iter().map(|(k, v)| format!("{k} {v}")).collect();
            format!("{at}{} is not {}; {}", cx.lhs, cx.rhs, aux.join(", "))
        }
    }
}

/// `text` cut to `width` characters, the last one `…` when anything was cut, at the
/// end of a word when one ends in the second half.
fn shorten(text: &str, width: usize) -> String {
    let text = text.split_whitespace().collect::<Vec<_>>().join(" ");
    if text.chars().count() <= width {
        return text;
    }
    let mut cut: String = text.chars().take(width.saturating_sub(1)).collect();
    let next_is_space = text.chars().nth(width.saturating_sub(1)) == Some(' ');
    if !next_is_space {
        if let Some(k) = cut
            .rfind(' ')
            .filter(|&k| cut[..k].chars().count() >= width / 2)
        {
            cut.truncate(k);
        }
    }
    let mut cut = cut.trim_end().to_owned();
    cut.push('…');
    cut
}

#[cfg(test)]
mod tests {
    use super::shorten;

    #[test]
    fn long_evidence_is_cut_with_an_ellipsis() {
        assert_eq!(shorten("a  b", 10), "a b");
        assert_eq!(shorten("abcdef", 4), "abc…");
        assert_eq!(shorten("αβγδ", 4), "αβγδ");
        // A word is not cut in the middle when an earlier one ends late enough.
        assert_eq!(
            shorten("correction holds at every point", 20),
            "correction holds at…"
        );
        assert_eq!(shorten("a correctionholdsatevery", 10), "a correct…");
    }
}
