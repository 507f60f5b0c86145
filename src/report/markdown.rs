//! The derivation table in Markdown, with statements as inline LaTeX (`$…$`), ready to
//! paste into a README, a review or an erratum.

use super::row::{full_evidence, verdict_label};
use super::summary::Summary;
use crate::check::Decided;
use std::fmt::Write as _;

/// Makes text from a file safe inside a Markdown table cell, as plain text: one line,
/// `|` escaped, no `<` directly before a letter, `/`, `!` or `?` (where HTML would start
/// a tag or comment, a space is put after it), and outside code spans nothing that
/// renders as markup: `[`, `]` (links, images), `*`, `_`, `~` (emphasis) and `$`
/// (mathematics) are escaped, every backslash of the file's own is doubled (it cannot
/// undo an escape, hide a backtick, or pass to a converter such as pandoc as a TeX
/// command, `\input{…}`), and a bare address that
/// GitHub would link (`https://…`, `www.…`, `a@b.example`) is broken.
pub fn cell(s: &str) -> String {
    escaped(s.trim(), Reading::Text)
}

/// How the characters outside code spans are read.
#[derive(Clone, Copy, PartialEq)]
enum Reading {
    /// Markdown text: everything that would be markup is escaped.
    Text,
    /// The content of [`math`]: LaTeX, kept as written except where it could be
    /// Markdown in a renderer without mathematics (brackets, dollars, addresses).
    Math,
}

/// `s` on one line, each run of white space one space (leading and trailing ones
/// kept as one).
fn one_line(s: &str) -> Vec<char> {
    let mut out: Vec<char> = Vec::with_capacity(s.len());
    for c in s.chars() {
        if c.is_whitespace() {
            if out.last() != Some(&' ') {
                out.push(' ');
            }
        } else {
            out.push(c);
        }
    }
    out
}

/// [`cell`], or the content of [`math`].
fn escaped(s: &str, reading: Reading) -> String {
    let line = one_line(s);
    let code = code_spans(&line);
    let mut out = String::with_capacity(line.len());
    for (k, &c) in line.iter().enumerate() {
        let rest = &line[k + 1..];
        if c == '|' {
            out.push_str("\\|");
            continue;
        }
        if c == '<'
            && rest
                .first()
                .is_some_and(|n| n.is_ascii_alphabetic() || "/!?".contains(*n))
        {
            out.push_str("< ");
            continue;
        }
        if code[k] {
            out.push(c);
            continue;
        }
        // A bare address would be linked: its `://`, `www.` or `@` is broken, by a
        // Markdown escape in text and by a LaTeX group in mathematics.
        let address = match c {
            ':' => rest.starts_with(&['/', '/']),
            '.' => k >= 3 && line[k - 3..k].iter().all(|w| w.eq_ignore_ascii_case(&'w')),
            '@' => true,
            _ => false,
        };
        match reading {
            Reading::Text => {
                if "\\[]*_~$".contains(c) || address {
                    out.push('\\');
                }
                out.push(c);
            }
            Reading::Math => match c {
                // LaTeX's own names for the brackets: no `[` for a link to start from.
                '[' => out.push_str("\\lbrack "),
                ']' => out.push_str("\\rbrack "),
                // A backslash of the file's would escape what follows to Markdown: a
                // dollar (which then closes the mathematics), a backtick (which then
                // opens no code span where one is read), a pipe. Doubled, it is text.
                '\\' if matches!(rest.first(), Some('$' | '`' | '|')) => out.push_str("\\\\"),
                '$' => out.push_str("\\$"),
                _ if address => {
                    out.push('{');
                    out.push(c);
                    out.push('}');
                }
                _ => out.push(c),
            },
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

/// Inline LaTeX, `$…$`, safe in a table cell as [`cell`] makes text: its brackets
/// become `\lbrack`, `\rbrack` (the same brackets to LaTeX, no link to Markdown), its
/// dollars are escaped. Only a formula the LaTeX report would take (the allowlist of
/// [`super::tex::check`]) becomes mathematics, since a converter such as pandoc hands
/// it to TeX as it stands; any other is shown as text, escaped as [`cell`] escapes it.
pub fn math(s: &str) -> String {
    let s = s.trim();
    match super::tex::check(s) {
        Ok(()) => format!("${}$", escaped(s, Reading::Math)),
        Err(_) => escaped(s, Reading::Text),
    }
}

/// Marks where [`evidence_cell`] puts a statement back, around its number.
const MARK: char = '\u{E000}';

/// The full evidence of a row as a cell: its words escaped as [`cell`] escapes text,
/// each statement it quotes as [`math`]. The statements are taken out (marked by
/// number) while the words are escaped, then put back. A file that writes the mark
/// itself can at most repeat one of the row's statements, which are safe.
fn evidence_cell(r: &Decided<'_>) -> String {
    let maths = std::cell::RefCell::new(Vec::new());
    let mark = |s: &str| {
        let mut m = maths.borrow_mut();
        m.push(math(s));
        format!("{MARK}{}{MARK}", m.len() - 1)
    };
    let words = full_evidence(r, (&mark, &mark), &|s| s.to_owned());
    let maths = maths.into_inner();
    let escaped = cell(&words);
    let parts: Vec<&str> = escaped.split(MARK).collect();
    let mut out = String::with_capacity(escaped.len());
    out.push_str(parts[0]);
    let mut k = 1;
    while k < parts.len() {
        let statement = (k + 1 < parts.len())
            .then(|| parts[k].parse::<usize>().ok())
            .flatten()
            .and_then(|i| maths.get(i));
        match statement {
            Some(m) => {
                out.push_str(m);
                out.push_str(parts[k + 1]);
                k += 2;
            }
            None => {
                out.push(MARK);
                out.push_str(parts[k]);
                k += 1;
            }
        }
    }
    out
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
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} | {} | {} | {} |",
            cell(&c.id),
            cell(&c.section),
            statement(c),
            verdict,
            super::row::read_label(r),
            r.outcome.method.as_str(),
            evidence_cell(r)
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
        format!("“{}”", prose(&c.statement))
    } else {
        math(&c.statement)
    }
}

/// A sentence of the paper with its inline mathematics: each pair of dollars as
/// pandoc and GitHub pair them (an opening `$` not followed by a space, a closing one
/// not after a space nor before a digit) is [`math`], the rest is [`cell`] text.
fn prose(s: &str) -> String {
    let line = one_line(s.trim());
    let dollar = |k: usize| line[k] == '$' && (k == 0 || line[k - 1] != '\\');
    // Where a dollar may close, found once: an opening dollar takes the first of them
    // past it (a search from each opening dollar takes quadratic time on a line of them).
    let closers: Vec<usize> = (1..line.len())
        .filter(|&j| {
            dollar(j)
                && !line[j - 1].is_whitespace()
                && !line.get(j + 1).is_some_and(char::is_ascii_digit)
        })
        .collect();
    let mut out = String::new();
    let (mut text, mut k) = (0, 0);
    while k < line.len() {
        let opens = dollar(k)
            && line
                .get(k + 1)
                .is_some_and(|c| !c.is_whitespace() && *c != '$');
        let close = opens
            .then(|| {
                closers
                    .get(closers.partition_point(|&j| j < k + 2))
                    .copied()
            })
            .flatten();
        match close {
            Some(j) => {
                let piece = |a: usize, b: usize| line[a..b].iter().collect::<String>();
                out.push_str(&escaped(&piece(text, k), Reading::Text));
                let formula = piece(k + 1, j);
                match super::tex::check(&formula) {
                    Ok(()) => out.push_str(&format!("${}$", escaped(&formula, Reading::Math))),
                    Err(_) => out.push_str(&escaped(&piece(k, j + 1), Reading::Text)),
                }
                text = j + 1;
                k = j + 1;
            }
            None => k += 1,
        }
    }
    out.push_str(&escaped(
        &line[text..].iter().collect::<String>(),
        Reading::Text,
    ));
    out
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
        assert_eq!(cell("$ [a](x) $"), "\\$ \\[a\\](x) \\$");
        assert_eq!(cell("a | b <script>"), "a \\| b < script>");
    }

    #[test]
    fn a_backslash_of_the_files_cannot_undo_an_escape_or_hide_a_backtick() {
        // `\*` of the file would make `\\*`: a backslash, then a live `*`.
        assert_eq!(cell(r"\*a\* \[x\](y)"), r"\\\*a\\\* \\\[x\\\](y)");
        // `\`` is a literal backtick to CommonMark: doubled, the backslash is text and
        // the backtick opens the span it is read as.
        assert_eq!(cell(r"\`*a*`"), r"\\`*a*`");
        // Before a letter too: pandoc would pass `\input{…}` on to TeX.
        assert_eq!(cell(r"\alpha \input{x}"), r"\\alpha \\input{x}");
    }

    #[test]
    fn emphasis_dollars_and_bare_addresses_from_a_file_are_text() {
        assert_eq!(cell("*a* _b_ ~~c~~"), "\\*a\\* \\_b\\_ \\~\\~c\\~\\~");
        // A file's dollars are text: what they enclose is escaped like the rest.
        assert_eq!(
            cell("price $5 *bold* and $6"),
            "price \\$5 \\*bold\\* and \\$6"
        );
        assert_eq!(
            cell("see https://e.example and WWW.e.example or me@e.example"),
            "see https\\://e.example and WWW\\.e.example or me\\@e.example"
        );
        assert_eq!(cell("`https://e.example`"), "`https://e.example`");
    }

    #[test]
    fn a_sentence_keeps_its_mathematics_and_nothing_else_renders() {
        assert_eq!(
            prose("if $f_r \\leq f_s$ then *F_2* [a](b)"),
            "if $f_r \\leq f_s$ then \\*F\\_2\\* \\[a\\](b)"
        );
        // Dollars that pandoc and GitHub do not pair are text.
        assert_eq!(
            prose("price $5 *bold* and $6"),
            "price \\$5 \\*bold\\* and \\$6"
        );
        assert_eq!(prose("$ a $"), "\\$ a \\$");
        assert_eq!(prose("$[x](y)$"), "$\\lbrack x\\rbrack (y)$");
    }

    #[test]
    fn mathematics_keeps_its_latex_without_links_or_early_dollars() {
        assert_eq!(math("h_{cr} = 1"), "$h_{cr} = 1$");
        assert_eq!(
            math("\\left[ x \\right]"),
            "$\\left\\lbrack  x \\right\\rbrack $"
        );
        assert_eq!(
            math("[a](javascript:b)"),
            "$\\lbrack a\\rbrack (javascript:b)$"
        );
        assert_eq!(math("http://e.example"), "$http{:}//e.example$");
        assert_eq!(math("\\|x\\|"), "$\\\\\\|x\\\\\\|$");
    }

    #[test]
    fn a_formula_the_latex_report_would_refuse_is_text() {
        // A dollar would close the mathematics early; an escaped backtick would open
        // no code span; `\input` would read a file when a converter hands it to TeX.
        assert_eq!(math("x$ y"), "x\\$ y");
        assert_eq!(math("\\`[a](b)`"), "\\\\`[a](b)`");
        assert_eq!(
            math("x = \\input{/etc/passwd}"),
            "x = \\\\input{/etc/passwd}"
        );
        assert_eq!(
            prose("see $\\openout5$ and $a_1$"),
            "see \\$\\\\openout5\\$ and $a_1$"
        );
    }
}
