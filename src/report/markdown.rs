//! The derivation table in Markdown, with statements as inline LaTeX (`$…$`), ready to
//! paste into a README, a review or an erratum.

use super::row::{full_evidence, verdict_label};
use super::summary::Summary;
use crate::check::Decided;
use std::fmt::Write as _;

/// Makes text safe inside a Markdown table cell: one line, `|` escaped, no `<`
/// directly before a letter, `/`, `!` or `?` (where HTML would start a tag or comment,
/// a space is put after it), and outside code spans nothing that renders as markup:
/// no `[` or `]` that could make a link or an image (`[text](javascript:…)`,
/// `![](https://…)`), escaped in `$…$` too (a file decides where its dollars are); no
/// bare address that GitHub would link (`https://…`, `www.…`, `a@b.example`); and
/// outside `$…$` no emphasis (`*`, `_`, `~`).
pub fn cell(s: &str) -> String {
    escaped(s, Dollars::Paired)
}

/// Where a text's mathematics is.
#[derive(Clone, Copy, PartialEq)]
enum Dollars {
    /// Between the text's own pairs of dollars: a table cell.
    Paired,
    /// All of it, inside dollars [`math`] adds; its own dollars are escaped.
    Inside,
}

/// How a character is read.
#[derive(Clone, Copy, PartialEq)]
enum Reading {
    Code,
    Math,
    Text,
}

/// [`cell`], or the content of [`math`] (where LaTeX's brackets are kept unless the
/// file wrote a dollar of its own, and every character is mathematics).
fn escaped(s: &str, dollars: Dollars) -> String {
    let line: Vec<char> = s
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
        .chars()
        .collect();
    let readings = readings(&line, dollars);
    let brackets = dollars == Dollars::Paired || line.contains(&'$');
    let mut out = String::with_capacity(line.len());
    for (k, &c) in line.iter().enumerate() {
        let reading = readings[k];
        let rest = &line[k + 1..];
        // A bare address would be linked: its `://`, `www.` or `@` is broken, by a
        // Markdown escape in text and by a LaTeX group in mathematics.
        let address = match c {
            ':' => rest.starts_with(&['/', '/']),
            '.' => k >= 3 && line[k - 3..k].iter().all(|w| w.eq_ignore_ascii_case(&'w')),
            '@' => true,
            _ => false,
        };
        match (c, reading) {
            ('|', _) => out.push_str("\\|"),
            ('<', _)
                if rest
                    .first()
                    .is_some_and(|n| n.is_ascii_alphabetic() || "/!?".contains(*n)) =>
            {
                out.push_str("< ");
            }
            (_, Reading::Code) => out.push(c),
            ('$', Reading::Math) if dollars == Dollars::Inside => {
                let backslashes = out.chars().rev().take_while(|&b| b == '\\').count();
                if backslashes % 2 == 0 {
                    out.push('\\');
                }
                out.push('$');
            }
            ('[' | ']', _) if brackets => {
                out.push('\\');
                out.push(c);
            }
            (_, Reading::Math) if address => {
                out.push('{');
                out.push(c);
                out.push('}');
            }
            ('*' | '_' | '~', Reading::Text) => {
                out.push('\\');
                out.push(c);
            }
            (_, Reading::Text) if address => {
                out.push('\\');
                out.push(c);
            }
            _ => out.push(c),
        }
    }
    out
}

/// How each character of a line is read: in a code span, in mathematics (between a
/// dollar and the next, outside code; a last dollar without its closer is text), or
/// as text.
fn readings(line: &[char], dollars: Dollars) -> Vec<Reading> {
    let code = code_spans(line);
    let mut out: Vec<Reading> = code
        .iter()
        .map(|&c| match (c, dollars) {
            (true, _) => Reading::Code,
            (false, Dollars::Inside) => Reading::Math,
            (false, Dollars::Paired) => Reading::Text,
        })
        .collect();
    if dollars == Dollars::Paired {
        let signs: Vec<usize> = (0..line.len())
            .filter(|&k| line[k] == '$' && !code[k] && (k == 0 || line[k - 1] != '\\'))
            .collect();
        for pair in signs.chunks_exact(2) {
            for k in pair[0]..=pair[1] {
                if !code[k] {
                    out[k] = Reading::Math;
                }
            }
        }
    }
    out
}

/// Which characters lie inside a code span, as CommonMark reads them: a run of n
/// backticks opens a span that the next run of exactly n backticks closes; a run
/// without its closer is literal text.
fn code_spans(line: &[char]) -> Vec<bool> {
    let run_at = |k: usize| line[k..].iter().take_while(|&&c| c == '`').count();
    let mut inside = vec![false; line.len()];
    let mut k = 0;
    while k < line.len() {
        if line[k] != '`' {
            k += 1;
            continue;
        }
        let n = run_at(k);
        let mut j = k + n;
        let close = loop {
            match line[j..].iter().position(|&c| c == '`') {
                None => break None,
                Some(p) => {
                    let m = run_at(j + p);
                    if m == n {
                        break Some(j + p);
                    }
                    j += p + m;
                }
            }
        };
        match close {
            Some(c) => {
                inside[k + n..c].iter_mut().for_each(|x| *x = true);
                k = c + n;
            }
            None => k += n,
        }
    }
    inside
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
    format!("${}$", escaped(s, Dollars::Inside))
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
            "see \\[click\\](javascript:alert(1)) and !\\[x\\](http\\://e.example/p.png)"
        );
        // Code spans keep their brackets: there they are not Markdown.
        assert_eq!(cell("`[[a, b]]` and ``[`x`]``"), "`[[a, b]]` and ``[`x`]``");
        // A backtick run without its closer, or a dollar, opens nothing: links stay text.
        assert_eq!(cell("` [a](javascript:1) ``"), "` \\[a\\](javascript:1) ``");
        assert_eq!(cell("$ [a](x) $"), "$ \\[a\\](x) $");
        assert_eq!(math("\\left[ x \\right]"), "$\\left[ x \\right]$");
        assert_eq!(math("x$ [a](b) $y"), "$x\\$ \\[a\\](b) \\$y$");
        assert_eq!(math("x\\$ y"), "$x\\$ y$");
        assert_eq!(cell("a | b <script>"), "a \\| b < script>");
    }

    #[test]
    fn emphasis_and_bare_addresses_from_a_file_are_text() {
        assert_eq!(cell("*a* _b_ ~~c~~"), "\\*a\\* \\_b\\_ \\~\\~c\\~\\~");
        // Inside mathematics a subscript stays a subscript.
        assert_eq!(cell("at $h_{cr} = 1$, h_cr"), "at $h_{cr} = 1$, h\\_cr");
        // A dollar without its closer opens nothing.
        assert_eq!(cell("$ *a*"), "$ \\*a\\*");
        assert_eq!(
            cell("see https://e.example and WWW.e.example or me@e.example"),
            "see https\\://e.example and WWW\\.e.example or me\\@e.example"
        );
        assert_eq!(math("http://e.example"), "$http{:}//e.example$");
        assert_eq!(cell("`https://e.example`"), "`https://e.example`");
    }
}
