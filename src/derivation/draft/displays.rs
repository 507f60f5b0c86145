//! The numbered displayed equations of a paper's source, in the order LaTeX numbers
//! them: `equation`, `align`, `gather`, `multline` and `eqnarray` (each numbered row;
//! starred forms, `\nonumber` and `\notag` unnumbered), and `$$…$$` or `\[…\]` with a
//! trailing `(N)` or a `\tag{N}` (as in a Markdown rendering of a paper). A `\tag{N}`
//! numbers its row N without advancing the counter, as LaTeX does.
//!
//! A statement is flattened for the reader: alignment marks (`&`, `\\`, `aligned`,
//! `split`) are removed, and a row that starts with a relation (`&= …`) continues the
//! row before it, which then carries the number of the last.

/// One numbered statement.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Display {
    /// The number LaTeX would print (`26`, `A.3`).
    pub number: String,
    /// The statement, flattened, without its number.
    pub latex: String,
    /// The line (1-based) where it starts in the source.
    pub line: usize,
}

/// The environments that number their rows, with whether each row is a statement of
/// its own (`multline` is one statement over several rows).
const ENVIRONMENTS: &[(&str, bool)] = &[
    ("equation", false),
    ("align", true),
    ("gather", true),
    ("multline", false),
    ("eqnarray", true),
];

/// Every numbered display of `text`, and how many displays carry no number.
pub fn numbered(text: &str) -> (Vec<Display>, usize) {
    let text = without_comments(text);
    let mut out = Vec::new();
    let mut unnumbered = 0;
    let mut counter = 0usize;
    let mut at = 0;
    while let Some((start, kind)) = next_display(&text, at) {
        let line = 1 + text[..start].matches('\n').count();
        match kind {
            Kind::Dollars | Kind::Brackets => {
                let (open, close) = if kind == Kind::Dollars {
                    ("$$", "$$")
                } else {
                    ("\\[", "\\]")
                };
                let body_start = start + open.len();
                let Some(len) = text[body_start..].find(close) else {
                    break;
                };
                let body = &text[body_start..body_start + len];
                at = body_start + len + close.len();
                let (body, tag) = take_tag(body);
                let (body, trailing) = match tag {
                    Some(t) => (body, Some(t)),
                    None => take_trailing_number(&body),
                };
                match trailing {
                    Some(number) => out.push(Display {
                        number,
                        latex: flatten(&body),
                        line,
                    }),
                    None => unnumbered += 1,
                }
            }
            Kind::Environment(name, starred) => {
                let full = if starred {
                    format!("{name}*")
                } else {
                    name.to_owned()
                };
                let open = format!("\\begin{{{full}}}");
                let close = format!("\\end{{{full}}}");
                let body_start = start + open.len();
                let Some(len) = text[body_start..].find(&close) else {
                    break;
                };
                let body = &text[body_start..body_start + len];
                at = body_start + len + close.len();
                let by_rows = ENVIRONMENTS.iter().any(|&(n, rows)| n == name && rows);
                let rows: Vec<(usize, String)> = if by_rows {
                    rows_of(body)
                        .into_iter()
                        .map(|(offset, row)| (offset, row.to_owned()))
                        .collect()
                } else {
                    vec![(0, body.to_owned())]
                };
                let mut pending: Option<Display> = None;
                for (offset, row) in rows {
                    // The row's line is where its first character is.
                    let lead = row.len() - row.trim_start().len();
                    let row_line = line
                        + text[start..body_start + offset + lead]
                            .matches('\n')
                            .count();
                    let (row, tag) = take_tag(&row);
                    let unnumbered_row =
                        starred || row.contains("\\nonumber") || row.contains("\\notag");
                    let row = row.replace("\\nonumber", " ").replace("\\notag", " ");
                    let number = match tag {
                        Some(t) => Some(t),
                        None if unnumbered_row => None,
                        None => {
                            counter += 1;
                            Some(counter.to_string())
                        }
                    };
                    let flat = flatten(&row);
                    if flat.trim().is_empty() {
                        continue;
                    }
                    match pending.as_mut() {
                        Some(p) if starts_with_relation(&flat) => {
                            p.latex = format!("{} {}", p.latex, flat.trim());
                            if number.is_some() {
                                p.number = number.unwrap_or_default();
                            }
                        }
                        _ => {
                            if let Some(p) = pending.take() {
                                push_numbered(&mut out, &mut unnumbered, p);
                            }
                            pending = Some(Display {
                                number: number.unwrap_or_default(),
                                latex: flat.trim().to_owned(),
                                line: row_line,
                            });
                        }
                    }
                }
                if let Some(p) = pending.take() {
                    push_numbered(&mut out, &mut unnumbered, p);
                }
            }
        }
    }
    (out, unnumbered)
}

fn push_numbered(out: &mut Vec<Display>, unnumbered: &mut usize, d: Display) {
    if d.number.is_empty() {
        *unnumbered += 1;
    } else {
        out.push(d);
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    Dollars,
    Brackets,
    Environment(&'static str, bool),
}

/// The next display at or after `at`: where it starts, and what opens it.
fn next_display(text: &str, at: usize) -> Option<(usize, Kind)> {
    let mut best: Option<(usize, Kind)> = None;
    let mut consider = |pos: Option<usize>, kind: Kind| {
        if let Some(p) = pos {
            if best.is_none_or(|(b, _)| p < b) {
                best = Some((p, kind));
            }
        }
    };
    let rest = &text[at..];
    consider(rest.find("$$").map(|p| p + at), Kind::Dollars);
    consider(rest.find("\\[").map(|p| p + at), Kind::Brackets);
    for &(name, _) in ENVIRONMENTS {
        for starred in [false, true] {
            let open = if starred {
                format!("\\begin{{{name}*}}")
            } else {
                format!("\\begin{{{name}}}")
            };
            consider(
                rest.find(&open).map(|p| p + at),
                Kind::Environment(name, starred),
            );
        }
    }
    best
}

/// `text` without its TeX comments (`%` to the end of the line, `\%` kept).
fn without_comments(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for line in text.split_inclusive('\n') {
        let mut escaped = false;
        let mut cut = None;
        for (i, c) in line.char_indices() {
            if c == '%' && !escaped {
                cut = Some(i);
                break;
            }
            escaped = c == '\\' && !escaped;
        }
        match cut {
            Some(i) => {
                out.push_str(&line[..i]);
                if line.ends_with('\n') {
                    out.push('\n');
                }
            }
            None => out.push_str(line),
        }
    }
    out
}

/// The rows of an environment's body, split at `\\` outside braces and nested
/// environments, with their offsets in `body`.
fn rows_of(body: &str) -> Vec<(usize, &str)> {
    let bytes = body.as_bytes();
    let (mut depth, mut env_depth) = (0i64, 0i64);
    let mut rows = Vec::new();
    let mut from = 0;
    let mut i = 0;
    while i < bytes.len() {
        match bytes[i] {
            b'{' => depth += 1,
            b'}' => depth -= 1,
            b'\\' if body[i..].starts_with("\\begin{") => env_depth += 1,
            b'\\' if body[i..].starts_with("\\end{") => env_depth -= 1,
            b'\\' if depth == 0 && env_depth == 0 && body[i..].starts_with("\\\\") => {
                rows.push((from, &body[from..i]));
                from = i + 2;
                i += 2;
                continue;
            }
            b'\\' => {
                // A control symbol such as `\{` or `\\` inside a group: skip it whole.
                i += 2;
                continue;
            }
            _ => {}
        }
        i += 1;
    }
    rows.push((from, &body[from..]));
    rows
}

/// A statement with its `\tag{N}` removed, and N.
fn take_tag(body: &str) -> (String, Option<String>) {
    let Some(start) = body.find("\\tag{") else {
        return (body.to_owned(), None);
    };
    let after = &body[start + 5..];
    let Some(end) = after.find('}') else {
        return (body.to_owned(), None);
    };
    let number = after[..end].trim().to_owned();
    let rest = format!("{}{}", &body[..start], &after[end + 1..]);
    (rest, (!number.is_empty()).then_some(number))
}

/// A statement whose last thing is `(N)` (after spacing such as `\quad`): the statement
/// without it, and N. N is a number, possibly with letters and dots (`A.3`, `12a`).
fn take_trailing_number(body: &str) -> (String, Option<String>) {
    let trimmed = body.trim_end();
    let Some(inner) = trimmed.strip_suffix(')') else {
        return (body.to_owned(), None);
    };
    let Some(open) = inner.rfind('(') else {
        return (body.to_owned(), None);
    };
    let number = &inner[open + 1..];
    let plausible = !number.is_empty()
        && number.len() <= 12
        && number.chars().any(|c| c.is_ascii_digit())
        && number
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '.');
    if !plausible {
        return (body.to_owned(), None);
    }
    let mut before = inner[..open].trim_end();
    // The spacing that separates the number from the statement.
    loop {
        let shorter = ["\\qquad", "\\quad", "\\;", "\\,", "~", "\\hfill"]
            .iter()
            .find_map(|s| before.strip_suffix(s));
        match shorter {
            Some(s) => before = s.trim_end(),
            None => break,
        }
    }
    (before.to_owned(), Some(number.to_owned()))
}

/// The statement without alignment marks, on one line.
fn flatten(body: &str) -> String {
    let mut s = body.to_owned();
    for env in ["aligned", "split", "gathered"] {
        s = s
            .replace(&format!("\\begin{{{env}}}"), " ")
            .replace(&format!("\\end{{{env}}}"), " ");
    }
    let s = s.replace("\\\\", " ").replace('&', " ");
    let s = s.split_whitespace().collect::<Vec<_>>().join(" ");
    // The punctuation of the sentence the display ends (`s_{kk} = 0 ,`).
    let mut s = s.as_str();
    loop {
        let t = s
            .trim_end()
            .trim_end_matches([',', '.', ';'])
            .trim_end_matches(r"\,")
            .trim_end();
        if t.len() == s.len() {
            break;
        }
        s = t;
    }
    s.to_owned()
}

fn starts_with_relation(s: &str) -> bool {
    let s = s.trim_start();
    [
        "=", "<", ">", "\\le", "\\ge", "\\leq", "\\geq", "\\approx", "\\equiv",
    ]
    .iter()
    .any(|r| s.starts_with(r))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn numbers(text: &str) -> Vec<(String, String)> {
        numbered(text)
            .0
            .into_iter()
            .map(|d| (d.number, d.latex))
            .collect()
    }

    #[test]
    fn markdown_displays_carry_their_numbers() {
        let text = "intro\n$$P = a + b \\quad (3)$$\n$$x = y$$\ntext\n$$\\begin{aligned} Q &= a \\\\ &= b \\end{aligned} \\quad (4)$$";
        let (found, unnumbered) = numbered(text);
        assert_eq!(unnumbered, 1);
        assert_eq!(found[0].line, 2);
        assert_eq!(
            numbers(text),
            vec![
                ("3".to_owned(), "P = a + b".to_owned()),
                ("4".to_owned(), "Q = a = b".to_owned())
            ]
        );
    }

    #[test]
    fn environments_number_as_latex_does() {
        let text = "\\begin{equation} a = b, \\end{equation}\n% \\begin{equation} c = d \\end{equation}\n\\begin{align} x &= y \\\\ z &= w \\nonumber \\\\ &= v \\tag{A.1} \\end{align}\n\\begin{equation*} u = u \\end{equation*}\n\\begin{gather} p = q \\end{gather}";
        assert_eq!(
            numbers(text),
            vec![
                ("1".to_owned(), "a = b".to_owned()),
                ("2".to_owned(), "x = y".to_owned()),
                ("A.1".to_owned(), "z = w = v".to_owned()),
                ("3".to_owned(), "p = q".to_owned()),
            ]
        );
    }

    #[test]
    fn unclosed_displays_end_the_scan_without_a_panic() {
        for text in [
            "$$ a = b (1)",
            "\\[ a",
            "\\begin{align} a &= b \\\\",
            "$$$",
            "\\begin{equation}",
        ] {
            let _ = numbered(text);
        }
        assert!(numbered("$$ (1) $$").0.iter().all(|d| d.latex.is_empty()));
    }
}
