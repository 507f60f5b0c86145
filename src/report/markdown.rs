//! The derivation table in Markdown, with statements as inline LaTeX (`$…$`), ready to
//! paste into a README, a review or an erratum.

use super::row::{full_evidence, verdict_label};
use super::summary::Summary;
use crate::check::Decided;
use std::fmt::Write as _;

/// Makes text safe inside a Markdown table cell: one line, `|` escaped, no `<`
/// directly before a letter, `/`, `!` or `?` (where HTML would start a tag or comment,
/// a space is put after it), and outside code spans and `$…$` no `[` or `]` that could
/// make a link or an image (`[text](javascript:…)`, `![](https://…)`): they are escaped.
pub fn cell(s: &str) -> String {
    escaped(s, true)
}

/// [`cell`], with the brackets of links escaped only where `prose` (not inside `$…$`,
/// where they are LaTeX's).
fn escaped(s: &str, prose: bool) -> String {
    let line = s.split_whitespace().collect::<Vec<_>>().join(" ");
    let mut out = String::with_capacity(line.len());
    let mut chars = line.chars().peekable();
    let (mut in_code, mut in_math) = (false, false);
    while let Some(c) = chars.next() {
        match c {
            '`' => {
                in_code = !in_code;
                out.push(c);
            }
            '$' if !in_code => {
                in_math = !in_math;
                out.push(c);
            }
            '[' | ']' if prose && !in_code && !in_math => {
                out.push('\\');
                out.push(c);
            }
            '|' => out.push_str("\\|"),
            '<' if chars
                .peek()
                .is_some_and(|n| n.is_ascii_alphabetic() || "/!?".contains(*n)) =>
            {
                out.push_str("< ");
            }
            c => out.push(c),
        }
    }
    out
}

/// A line of text outside the table (the paper's name): a [`cell`] that cannot start
/// a heading, a quotation, a list or a table row.
pub fn line(s: &str) -> String {
    let s = cell(s);
    if s.starts_with(['#', '>', '-', '*', '+', '=', '|', '`', '~'])
        || s.starts_with(|c: char| c.is_ascii_digit())
    {
        format!("\\{s}")
    } else {
        s
    }
}

/// Inline LaTeX, `$…$`, safe in a table cell as [`cell`] makes text, its brackets kept.
pub fn math(s: &str) -> String {
    format!("${}$", escaped(s, false))
}

/// Renders the whole table with its summary line.
pub fn render(rows: &[&Decided<'_>], paper: &str) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "# Derivation table\n");
    let _ = writeln!(out, "{}.\n", line(paper));
    let _ = writeln!(
        out,
        "| claim | § | statement (as printed) | verdict | read | method | evidence |"
    );
    let _ = writeln!(out, "|---|---|---|---|---|---|---|");
    for r in rows {
        let c = r.claim;
        let verdict = match r.outcome.verdict() {
            crate::derivation::Verdict::Holds => verdict_label(r),
            _ => format!("**{}**", verdict_label(r)),
        };
        let ev = full_evidence(r, &|s| math(s));
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} | {} | {} | {} |",
            cell(&c.id),
            cell(&c.section),
            statement(c),
            verdict,
            super::row::read_label(r),
            r.outcome.method.as_str(),
            cell(&ev)
        );
    }
    let summary = Summary::of(rows);
    let _ = writeln!(out, "\n{}", summary.sentence(rows.len()));
    let origin = summary.origin_sentence();
    if !origin.is_empty() {
        let _ = writeln!(out, "\n{origin}");
    }
    let _ = writeln!(out, "\n{}", summary.transcription_sentence());
    out
}

/// A statement as it appears in a table cell: inline math, or quoted prose.
pub fn statement(c: &crate::derivation::Claim) -> String {
    if c.prose {
        format!("“{}”", cell(&c.statement))
    } else {
        math(&c.statement)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn links_and_images_from_a_file_are_text_in_a_cell() {
        assert_eq!(
            cell("see [click](javascript:alert(1)) and ![x](http://e.example/p.png)"),
            "see \\[click\\](javascript:alert(1)) and !\\[x\\](http://e.example/p.png)"
        );
        // Code spans and LaTeX keep their brackets: there they are not Markdown.
        assert_eq!(
            cell("`[[a, b]]` and $\\left[ x \\right]$"),
            "`[[a, b]]` and $\\left[ x \\right]$"
        );
        assert_eq!(math("\\left[ x \\right]"), "$\\left[ x \\right]$");
        assert_eq!(cell("a | b <script>"), "a \\| b < script>");
    }
}
