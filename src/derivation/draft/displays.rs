//! The numbered displayed equations of a paper's source, in the order LaTeX numbers
//! them: `equation`, `align`, `gather`, `multline` and `eqnarray` (each numbered row;
//! starred forms, `\nonumber` and `\notag` unnumbered), and `$$…$$` or `\[…\]` with a
//! trailing `(N)` or a `\tag{N}` (as in a Markdown rendering of a paper). A `\tag{N}`
//! numbers its row N without advancing the counter, as LaTeX does.
//!
//! A statement is flattened for the reader: alignment marks (`&`, `\\`, `aligned`,
//! `split`) are removed, and a row that starts with a relation (`&= …`) continues the
//! row before it: the chain carries the number of the last row, and a numbered row
//! before it is a statement of its own as well.

/// One numbered statement.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Display {
    /// The number LaTeX would print (`26`, `A.3`).
    pub number: String,
    /// The statement, flattened, without its number.
    pub latex: String,
    /// The line (1-based) where it starts in the source.
    pub line: usize,
    /// The line where its display ends (an environment's `\end`, the closing `$$`).
    pub end: usize,
}

/// The environments that number their rows, with whether each row is a statement of
/// its own (`multline` is one statement over several rows).
const ENVIRONMENTS: &[(&str, bool)] = &[
    ("equation", false),
    ("align", true),
    ("flalign", true),
    ("alignat", true),
    ("gather", true),
    ("multline", false),
    ("eqnarray", true),
];

/// Regions of a LaTeX source that are not the paper's text: their displays are neither
/// drafted nor counted (TeX comments are removed line by line as well; `\iffalse` is
/// matched to its `\fi` by nesting, and nothing after `\end{document}` counts).
const DEAD_TEX: &[(&str, &str)] = &[
    ("\\begin{comment}", "\\end{comment}"),
    ("\\begin{verbatim}", "\\end{verbatim}"),
    ("\\begin{verbatim*}", "\\end{verbatim*}"),
    ("\\begin{lstlisting}", "\\end{lstlisting}"),
    ("\\begin{minted}", "\\end{minted}"),
];

/// Regions of a Markdown source that are not shown as mathematics.
const DEAD_MARKDOWN: &[(&str, &str)] = &[("<!--", "-->"), ("```", "```"), ("~~~", "~~~")];

/// Every numbered display of `text` (Markdown when `markdown`, else LaTeX), and every
/// display (or row) that carries no number.
pub fn numbered(text: &str, markdown: bool) -> (Vec<Display>, Vec<Display>) {
    let text = live(text, markdown);
    let mut out = Vec::new();
    let mut unnumbered = Vec::new();
    let mut counter = 0usize;
    let mut at = 0;
    let mut scan = Scan::new(&text);
    // Lines counted as the scan goes (from the start each time would be quadratic).
    let (mut counted_to, mut line) = (0, 1);
    while let Some((start, kind)) = scan.next(&text, at) {
        line += text[counted_to..start].matches('\n').count();
        counted_to = start;
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
                let end = line + text[start..at].matches('\n').count();
                let (body, tag) = take_tag(body);
                let (body, trailing) = match tag {
                    Some(t) => (body, Some(t)),
                    None => take_trailing_number(&body),
                };
                let d = Display {
                    number: trailing.unwrap_or_default(),
                    latex: flatten(&body),
                    line,
                    end,
                };
                push_numbered(&mut out, &mut unnumbered, d);
            }
            Kind::Environment(name, starred) => {
                let full = if starred {
                    format!("{name}*")
                } else {
                    name.to_owned()
                };
                let open = format!("\\begin{{{full}}}");
                let close = format!("\\end{{{full}}}");
                let mut body_start = start + open.len();
                // `alignat{2}`: the number of columns is no part of a row.
                if name == "alignat" && text[body_start..].starts_with('{') {
                    body_start += text[body_start..].find('}').map_or(0, |k| k + 1);
                }
                let Some(len) = text[body_start..].find(&close) else {
                    break;
                };
                let body = &text[body_start..body_start + len];
                at = body_start + len + close.len();
                let end = line + text[start..at].matches('\n').count();
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
                            // Both rows numbered (`σ &= Cε \\ &= λ…`, (2) and (3)):
                            // (2) is its row, (3) the chain up to its own row.
                            if number.is_some() && !p.number.is_empty() {
                                out.push(p.clone());
                            }
                            p.latex = format!("{} {}", p.latex, without_spacing(&flat));
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
                                end,
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

fn push_numbered(out: &mut Vec<Display>, unnumbered: &mut Vec<Display>, d: Display) {
    if d.number.is_empty() {
        unnumbered.push(d);
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

/// The openings of displays, each found once and again only when the scan passes it
/// (a search per opening and display would be quadratic in the number of displays).
struct Scan {
    openings: Vec<(String, Kind)>,
    next: Vec<Option<usize>>,
}

impl Scan {
    fn new(text: &str) -> Self {
        let mut openings = vec![
            ("$$".to_owned(), Kind::Dollars),
            ("\\[".to_owned(), Kind::Brackets),
        ];
        for &(name, _) in ENVIRONMENTS {
            openings.push((format!("\\begin{{{name}}}"), Kind::Environment(name, false)));
            openings.push((format!("\\begin{{{name}*}}"), Kind::Environment(name, true)));
        }
        let next = openings
            .iter()
            .map(|(o, _)| text.find(o.as_str()))
            .collect();
        Scan { openings, next }
    }

    /// The next display at or after `at`: where it starts, and what opens it.
    fn next(&mut self, text: &str, at: usize) -> Option<(usize, Kind)> {
        let mut best: Option<(usize, Kind)> = None;
        for (k, (open, kind)) in self.openings.iter().enumerate() {
            if self.next[k].is_some_and(|p| p < at) {
                self.next[k] = text[at..].find(open.as_str()).map(|q| q + at);
            }
            if let Some(p) = self.next[k] {
                if best.is_none_or(|(b, _)| p < b) {
                    best = Some((p, *kind));
                }
            }
        }
        best
    }
}

/// `text` without what is not the paper's text (see [`DEAD_TEX`], [`DEAD_MARKDOWN`]),
/// line breaks kept so that lines are counted as in the source.
pub fn live(text: &str, markdown: bool) -> String {
    let mut text = if markdown {
        text.to_owned()
    } else {
        let text = without_comments(text);
        let text = match text.find("\\end{document}") {
            // Line breaks after it kept, for nothing; the text after it is gone.
            Some(end) => text[..end].to_owned(),
            None => text,
        };
        without_iffalse(&text)
    };
    for (open, close) in if markdown { DEAD_MARKDOWN } else { DEAD_TEX } {
        let mut out = String::with_capacity(text.len());
        let mut rest = text.as_str();
        while let Some(a) = rest.find(open) {
            out.push_str(&rest[..a]);
            let after = &rest[a + open.len()..];
            let end = after.find(close).map_or(after.len(), |b| b + close.len());
            out.extend(rest[a..a + open.len() + end].chars().filter(|&c| c == '\n'));
            rest = &after[end..];
        }
        out.push_str(rest);
        text = out;
    }
    text
}

/// The words that lead into a display starting on line `line` (1-based) of `lines` (the
/// paper's text, [`live`], by lines): the last sentence before it, back to a blank line or the
/// end of another display, its inline formulas left in. "The Cauchy stress is symmetric,"
/// before `\sigma_{ij} = \sigma_{ji}`.
pub fn lead_in(lines: &[&str], line: usize) -> String {
    let Some(first) = line.checked_sub(1).and_then(|k| lines.get(k)) else {
        return String::new();
    };
    // The display may start in the middle of its line.
    let opening = ["\\begin{", "$$", "\\["]
        .iter()
        .filter_map(|o| first.find(o))
        .min()
        .unwrap_or(first.len());
    let mut text = vec![&first[..opening]];
    // Blank lines just above a display (a Markdown paragraph of its own) are skipped.
    let mut above = first[..opening].trim().is_empty();
    for prior in lines[..line - 1].iter().rev() {
        let display_end = ["\\end{", "$$", "\\]", "\\\\"]
            .iter()
            .any(|e| prior.contains(e));
        if prior.trim().is_empty() && above {
            continue;
        }
        above = false;
        if prior.trim().is_empty()
            || display_end
            || text.iter().map(|t| t.len()).sum::<usize>() > SENTENCE
        {
            break;
        }
        text.push(prior);
    }
    text.reverse();
    let text = text.join(" ");
    let text = &text[floor(&text, text.len().saturating_sub(SENTENCE))..];
    let start = sentence_end(text).unwrap_or(0);
    text[start..].trim().to_owned()
}

/// The words that follow a display ending on line `end` (1-based) of `lines`: the first
/// sentence after it, up to a blank line or another display. "where $n$ is the unit
/// normal" after `A_{ik} = C_{ijkl} n_j n_l`.
pub fn lead_out(lines: &[&str], end: usize) -> String {
    let Some(last) = end.checked_sub(1).and_then(|k| lines.get(k)) else {
        return String::new();
    };
    // What follows the display's closing on its last line (`\end{…}`, `$$`, `\]`).
    let closing = ["\\end{", "$$", "\\]"]
        .iter()
        .filter_map(|c| {
            let at = last.rfind(c)?;
            let after = &last[at + c.len()..];
            Some(if *c == "\\end{" {
                after.find('}').map_or("", |k| &after[k + 1..])
            } else {
                after
            })
        })
        .min_by_key(|rest| rest.len())
        .unwrap_or("");
    let mut text = vec![closing];
    // Blank lines just below a display (a Markdown paragraph of its own) are skipped.
    let mut below = closing.trim().is_empty();
    for next in lines.iter().skip(end) {
        if next.trim().is_empty() && below {
            continue;
        }
        below = false;
        let display = ["\\begin{", "$$", "\\["].iter().any(|o| next.contains(o));
        if next.trim().is_empty()
            || display
            || text.iter().map(|t| t.len()).sum::<usize>() > SENTENCE
        {
            break;
        }
        text.push(next);
    }
    let text = text.join(" ");
    let text = &text[..ceil(&text, SENTENCE)];
    let stop = sentence_end_after(text).unwrap_or(text.len());
    text[..stop].trim().to_owned()
}

/// An inline formula of the paper's text (`$…$`, `\(…\)`): its line, its body, and the
/// words of its sentence (the formulas in it left out).
#[derive(Clone, Debug)]
pub struct Inline {
    pub line: usize,
    pub body: String,
    pub words: String,
    /// Where the formula stands in `words` (a byte offset): the words before it are
    /// `words[..at]`.
    pub at: usize,
}

/// The inline formulas of the paper's text, each with its line and the words of its
/// sentence. A `$$` (a display) is not inline, and a formula does not run past a blank
/// line; an escaped dollar is text.
pub fn inline_formulas(text: &str, markdown: bool) -> Vec<Inline> {
    let mut out = Vec::new();
    for Lifted { words, found, .. } in lifted(&live(text, markdown)) {
        // Where each sentence starts, found once for the paragraph; a sentence is taken
        // at most `SENTENCE` bytes either side of its formula.
        let starts: Vec<usize> = std::iter::once(0).chain(sentence_starts(&words)).collect();
        for f in found {
            let k = starts.partition_point(|&b| b <= f.at);
            let start =
                starts[k.saturating_sub(1)].max(floor(&words, f.at.saturating_sub(SENTENCE)));
            let stop = starts
                .get(k)
                .copied()
                .unwrap_or(words.len())
                .min(ceil(&words, f.at + SENTENCE));
            out.push(Inline {
                line: f.line,
                body: f.body,
                words: words[start..stop].to_owned(),
                at: f.at - start,
            });
        }
    }
    out
}

/// A sentence of the paper's text, with or without formulas: its first line, its words
/// (each inline formula standing as ` x `, as in [`Inline`]) and its formulas, each with
/// where it stands in the words. A sentence longer than `2 × SENTENCE` bytes is cut.
#[derive(Clone, Debug)]
pub struct Sentence {
    pub line: usize,
    pub words: String,
    pub formulas: Vec<(usize, String)>,
}

/// The sentences of the paper's text ([`Sentence`]), paragraph by paragraph; a clause
/// after a semicolon is one too.
pub fn sentences(text: &str, markdown: bool) -> Vec<Sentence> {
    let mut out = Vec::new();
    for Lifted { line, words, found } in lifted(&live(text, markdown)) {
        // A sentence also ends at the structure of the source: a display's `\begin{…}`,
        // its `\end{…}`, a heading.
        // A clause after a semicolon is read as a sentence of its own.
        let mut starts: Vec<usize> = std::iter::once(0)
            .chain(sentence_starts(&words))
            .chain(structure(&words))
            .chain(words.match_indices(';').map(|(k, _)| k + 1))
            .collect();
        starts.sort_unstable();
        starts.dedup();
        // One pass: the line breaks counted up to each sentence, the formulas (in the
        // order of the words) taken as the sentences reach them.
        let (mut counted, mut breaks, mut next, mut passed) = (0, 0, 0, 0);
        for (k, &start) in starts.iter().enumerate() {
            let stop = starts
                .get(k + 1)
                .copied()
                .unwrap_or(words.len())
                .min(ceil(&words, start + 2 * SENTENCE));
            // Its first word's line: the lines the words before it run over, and those
            // of the formulas before it.
            let first = start + (words[start..stop].len() - words[start..stop].trim_start().len());
            breaks += words[counted..first].matches('\n').count();
            counted = first;
            while let Some(f) = found.get(next).filter(|f| f.at < start) {
                passed += f.breaks;
                next += 1;
            }
            let inside: Vec<&Formula> = found[next..].iter().take_while(|f| f.at < stop).collect();
            let formula_breaks = passed
                + inside
                    .iter()
                    .filter(|f| f.at < first)
                    .map(|f| f.breaks)
                    .sum::<usize>();
            out.push(Sentence {
                line: line + breaks + formula_breaks,
                words: words[start..stop].to_owned(),
                formulas: inside
                    .iter()
                    .map(|f| (f.at - start, f.body.clone()))
                    .collect(),
            });
        }
    }
    out
}

/// Where a command that structures the source starts in `words`, and where its braced
/// argument ends (`\begin{equation}`, `\end{align}`, `\section{Stress}`): neither is
/// part of a sentence.
fn structure(words: &str) -> Vec<usize> {
    const COMMANDS: &[&str] = &[
        "\\begin{",
        "\\end{",
        "\\section",
        "\\subsection",
        "\\subsubsection",
        "\\paragraph",
        "\\chapter",
        "\\title",
        "\\author",
        "\\documentclass",
        "\\usepackage",
        "\\label",
        "\\maketitle",
        "\\item",
    ];
    let mut out = Vec::new();
    for c in COMMANDS {
        for (at, _) in words.match_indices(c) {
            out.push(at);
            // The end of its first braced argument, if one follows at once.
            let rest = &words[at + c.len()..];
            let rest_at = at + c.len();
            let open = if c.ends_with('{') {
                Some(0)
            } else {
                rest.trim_start_matches('*')
                    .starts_with('{')
                    .then(|| rest.find('{').map_or(0, |k| k + 1))
            };
            if let Some(from) = open {
                if let Some(close) = rest[from..].find('}') {
                    out.push(rest_at + from + close + 1);
                }
            }
        }
    }
    out
}

/// One paragraph of the text with its inline formulas lifted out.
struct Lifted {
    /// Its first line (1-based).
    line: usize,
    /// Its words, each formula standing as ` x `.
    words: String,
    found: Vec<Formula>,
}

/// An inline formula lifted out of its paragraph's words.
struct Formula {
    /// Where it stands in the words (a byte offset).
    at: usize,
    line: usize,
    body: String,
    /// The line breaks inside it, which its ` x ` does not keep.
    breaks: usize,
}

/// The paragraphs of `live` with their inline formulas lifted out ([`Lifted`]).
fn lifted(live: &str) -> Vec<Lifted> {
    let mut out = Vec::new();
    for (first, paragraph) in paragraphs(live) {
        let mut line = first;
        let mut found = Vec::new();
        let mut words = String::new();
        let mut rest = paragraph.as_str();
        while let Some((open, close, at)) = next_inline(rest) {
            let body_start = at + open.len();
            let Some(end) = rest[body_start..].find(close) else {
                break;
            };
            let here = line + rest[..at].matches('\n').count();
            words.push_str(&rest[..at]);
            let skip = body_start + end + close.len();
            found.push(Formula {
                at: words.len(),
                line: here,
                body: rest[body_start..body_start + end].trim().to_owned(),
                breaks: rest[at..skip].matches('\n').count(),
            });
            // A formula stands for a word in its sentence.
            words.push_str(" x ");
            line += rest[..skip].matches('\n').count();
            rest = &rest[skip..];
        }
        words.push_str(rest);
        out.push(Lifted {
            line: first,
            words,
            found,
        });
    }
    out
}

/// The most of a sentence taken either side of a formula, or before and after a
/// display, in bytes: longer runs without a full stop are no prose a tie is read from.
const SENTENCE: usize = 600;

/// The largest character boundary of `s` at or below `at`.
fn floor(s: &str, at: usize) -> usize {
    (0..=at.min(s.len()))
        .rev()
        .find(|&k| s.is_char_boundary(k))
        .unwrap_or(0)
}

/// The smallest character boundary of `s` at or above `at` (at most its length).
fn ceil(s: &str, at: usize) -> usize {
    (at.min(s.len())..=s.len())
        .find(|&k| s.is_char_boundary(k))
        .unwrap_or(s.len())
}

/// Where the last sentence of `text` starts: after its last `.`, `?` or `!` followed by
/// white space.
fn sentence_end(text: &str) -> Option<usize> {
    sentence_starts(text).last()
}

/// Where each sentence after the first starts in `text`: after a `.`, `?` or `!` that
/// white space follows.
fn sentence_starts(text: &str) -> impl Iterator<Item = usize> + '_ {
    text.char_indices()
        .zip(text.chars().skip(1))
        .filter(|((_, c), next)| matches!(c, '.' | '?' | '!') && next.is_whitespace())
        .map(|((k, _), _)| k + 1)
}

/// Where the first sentence of `text` ends: at its first `.`, `?` or `!` followed by
/// white space (or the end).
fn sentence_end_after(text: &str) -> Option<usize> {
    text.char_indices()
        .zip(text.chars().skip(1).map(Some).chain([None]))
        .find(|((_, c), next)| matches!(c, '.' | '?' | '!') && next.is_none_or(char::is_whitespace))
        .map(|((k, _), _)| k + 1)
}

/// The next inline formula's opening in `s`: (opening, closing, where), skipping `$$`
/// and escaped dollars.
fn next_inline(s: &str) -> Option<(&'static str, &'static str, usize)> {
    let bytes = s.as_bytes();
    let mut k = 0;
    while k < bytes.len() {
        match bytes[k] {
            b'\\' if bytes.get(k + 1) == Some(&b'(') => return Some(("\\(", "\\)", k)),
            b'\\' => k += 2,
            b'$' if bytes.get(k + 1) == Some(&b'$') => {
                // A display: skip to its end.
                let end = s[k + 2..].find("$$")?;
                k += 2 + end + 2;
            }
            b'$' => return Some(("$", "$", k)),
            _ => k += 1,
        }
    }
    None
}

/// The paragraphs of `text` (separated by blank lines), each with its first line
/// (1-based).
fn paragraphs(text: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    let mut current = String::new();
    let mut first = 1;
    for (k, line) in text.lines().enumerate() {
        if line.trim().is_empty() {
            if !current.is_empty() {
                out.push((first, std::mem::take(&mut current)));
            }
            first = k + 2;
        } else {
            if current.is_empty() {
                first = k + 1;
            } else {
                current.push('\n');
            }
            current.push_str(line);
        }
    }
    if !current.is_empty() {
        out.push((first, current));
    }
    out
}

/// `text` without its `\iffalse … \fi` blocks, each ended by the `\fi` that matches it
/// (every `\if…` inside opens one more); line breaks kept.
fn without_iffalse(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(a) = rest.find("\\iffalse") {
        out.push_str(&rest[..a]);
        let mut depth = 0usize;
        let mut end = rest.len();
        let mut k = a;
        while let Some(b) = rest[k..].find('\\') {
            let at = k + b;
            let tail = &rest[at..];
            if tail.starts_with("\\fi") && !tail[3..].starts_with(|c: char| c.is_ascii_alphabetic())
            {
                depth = depth.saturating_sub(1);
                if depth == 0 {
                    end = at + 3;
                    break;
                }
            } else if tail.starts_with("\\if") {
                depth += 1;
            }
            k = at + 1;
        }
        out.extend(rest[a..end].chars().filter(|&c| c == '\n'));
        rest = &rest[end..];
    }
    out.push_str(rest);
    out
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
    let (start, open) = match (body.find("\\tag{"), body.find("\\tag*{")) {
        (Some(a), _) => (a, 5),
        (None, Some(b)) => (b, 6),
        (None, None) => return (body.to_owned(), None),
    };
    let after = &body[start + open..];
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
    // `a = 2 \cdot (3)`: after an operator, a bracketed number is a factor.
    if [
        "\\cdot", "\\times", "+", "-", "=", "/", "^", "_", "{", "(", "\\left", "\\frac",
    ]
    .iter()
    .any(|op| before.ends_with(op))
    {
        return (body.to_owned(), None);
    }
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

/// The statement without alignment marks and labels, on one line.
fn flatten(body: &str) -> String {
    let mut s = body.to_owned();
    while let Some(a) = s.find("\\label{") {
        let end = s[a..].find('}').map_or(s.len(), |b| a + b + 1);
        s.replace_range(a..end, " ");
    }
    for env in ["aligned", "split", "gathered"] {
        s = s
            .replace(&format!("\\begin{{{env}}}"), " ")
            .replace(&format!("\\end{{{env}}}"), " ");
    }
    // Rows of an `aligned` block: one that starts with a relation or an operator
    // continues the row above; any other is a statement of its own, after a separator.
    let mut joined = String::new();
    for (_, row) in rows_of(&s) {
        let row = row.replace('&', " ");
        if !joined.trim().is_empty() && !row.trim().is_empty() {
            if starts_with_relation(&row) {
                joined.push(' ');
                joined.push_str(without_spacing(&row));
                continue;
            }
            joined.push_str(", \\quad ");
        }
        joined.push_str(&row);
    }
    let s = joined.split_whitespace().collect::<Vec<_>>().join(" ");
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

/// `s` without the spacing it starts with (`\quad + 1` → `+ 1`).
fn without_spacing(s: &str) -> &str {
    let mut s = s.trim_start();
    while let Some(rest) = ["\\qquad", "\\quad", "\\;", "\\,", "\\!", "~"]
        .iter()
        .find_map(|sp| s.strip_prefix(sp))
    {
        s = rest.trim_start();
    }
    s
}

/// A row that continues the statement above it: it starts (after spacing) with a
/// relation or a binary operator.
fn starts_with_relation(s: &str) -> bool {
    let s = without_spacing(s);
    [
        "=", "<", ">", "+", "-", "\\le", "\\ge", "\\leq", "\\geq", "\\approx", "\\equiv", "\\cdot",
        "\\times", "\\pm", "\\mp",
    ]
    .iter()
    .any(|r| s.starts_with(r))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn numbers(text: &str) -> Vec<(String, String)> {
        numbered(text, text.contains("$$"))
            .0
            .into_iter()
            .map(|d| (d.number, d.latex))
            .collect()
    }

    #[test]
    fn markdown_displays_carry_their_numbers() {
        let text = "intro\n$$P = a + b \\quad (3)$$\n$$x = y$$\ntext\n$$\\begin{aligned} Q &= a \\\\ &= b \\end{aligned} \\quad (4)$$";
        let (found, unnumbered) = numbered(text, true);
        assert_eq!(unnumbered.len(), 1);
        assert_eq!((unnumbered[0].line, unnumbered[0].end), (3, 3));
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
    fn a_numbered_row_before_a_continuation_is_a_statement_of_its_own() {
        let text = "\\begin{align} s &= a \\\\ &= b \\\\ t &= c \\nonumber \\\\ &= d \\end{align}";
        assert_eq!(
            numbers(text),
            vec![
                ("1".to_owned(), "s = a".to_owned()),
                ("2".to_owned(), "s = a = b".to_owned()),
                ("3".to_owned(), "t = c = d".to_owned()),
            ]
        );
    }

    #[test]
    fn inline_formulas_carry_the_words_of_their_sentence_and_displays_their_lead_in() {
        let text = "First $a = 1$ here. The stress $s_{ij}$ is\nsymmetric. Last.\n\nnext $b$";
        let found = inline_formulas(text, false);
        let got: Vec<(usize, &str, &str)> = found
            .iter()
            .map(|f| (f.line, f.body.as_str(), f.words.as_str()))
            .collect();
        assert_eq!(
            got,
            vec![
                (1, "a = 1", "First  x  here."),
                (1, "s_{ij}", " The stress  x  is\nsymmetric."),
                (4, "b", "next  x "),
            ]
        );
        let live = "Intro. The stress is symmetric,\n\\begin{equation} s = t \\end{equation}\nThen\n\n$$ u = v (2)$$";
        let lines: Vec<&str> = live.lines().collect();
        assert_eq!(lead_in(&lines, 2), "The stress is symmetric,");
        assert_eq!(lead_in(&lines, 5), "Then");
        assert_eq!(lead_in(&["$$ a = b (1)$$"], 1), "");
        let live = "\\begin{equation} a = b \\end{equation} where $n$ is\na unit vector. More.\n\n$$ c = d (2)$$\n\nNext line.";
        let lines: Vec<&str> = live.lines().collect();
        assert_eq!(lead_out(&lines, 1), "where $n$ is a unit vector.");
        assert_eq!(lead_out(&lines, 4), "Next line.");
        assert_eq!(lead_out(&lines, 99), "");
        assert_eq!(lead_in(&lines, 99), "");
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
            let _ = numbered(text, false);
        }
        assert!(numbered("$$ (1) $$", true)
            .0
            .iter()
            .all(|d| d.latex.is_empty()));
    }
}
