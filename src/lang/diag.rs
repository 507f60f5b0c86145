//! Diagnostics that point at a file, line and column, with the line shown and a caret
//! under the offending token (rustc's layout, which users already read fluently).

use std::fmt;
use std::sync::Arc;

/// A byte range in some text (an expression's own text, or a whole file).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Span {
    pub start: usize,
    pub end: usize,
}

impl Span {
    pub fn new(start: usize, end: usize) -> Self {
        Span { start, end }
    }

    /// The smallest span covering both.
    pub fn to(self, other: Span) -> Span {
        Span::new(self.start.min(other.start), self.end.max(other.end))
    }
}

/// A file that diagnostics can point into.
#[derive(Debug)]
pub struct SourceFile {
    pub path: String,
    pub text: String,
    /// Found once, since a file locates every claim and a scan from the start for each
    /// would be quadratic in its length: the byte offset where each line starts, and
    /// the number of characters before every 4 KiB of the text (a line may be long).
    index: std::sync::OnceLock<Positions>,
}

/// Where each line starts (bytes), and (byte, characters before it) every 4 KiB.
type Positions = (Vec<usize>, Vec<(usize, usize)>);

/// The span of text whose characters [`SourceFile::line_col`] counts one by one.
const BLOCK: usize = 4096;

impl SourceFile {
    pub fn new(path: impl Into<String>, text: impl Into<String>) -> Arc<Self> {
        Arc::new(SourceFile {
            path: path.into(),
            text: text.into(),
            index: std::sync::OnceLock::new(),
        })
    }

    /// 1-based line and column (in characters) of a byte offset.
    pub fn line_col(&self, offset: usize) -> (usize, usize) {
        let offset = floor_char_boundary(&self.text, offset.min(self.text.len()));
        let (starts, blocks) = self.index.get_or_init(|| {
            let starts = std::iter::once(0)
                .chain(self.text.match_indices('\n').map(|(k, _)| k + 1))
                .collect();
            let mut blocks = Vec::new();
            let (mut byte, mut chars) = (0, 0);
            while byte < self.text.len() {
                blocks.push((byte, chars));
                // A character is at most 4 bytes, so the block always moves on.
                let next = floor_char_boundary(&self.text, (byte + BLOCK).min(self.text.len()));
                chars += self.text[byte..next].chars().count();
                byte = next;
            }
            blocks.push((byte, chars));
            (starts, blocks)
        });
        let chars_before = |at: usize| {
            let k = blocks.partition_point(|&(b, _)| b <= at) - 1;
            let (b, c) = blocks[k];
            c + self.text[b..at].chars().count()
        };
        // The last line start at or before the offset.
        let line = starts.partition_point(|&s| s <= offset);
        let line_start = starts[line - 1];
        (line, chars_before(offset) - chars_before(line_start) + 1)
    }

    /// A diagnostic at a byte span of this file.
    pub fn diagnostic(&self, span: Span, message: impl Into<String>) -> Diagnostic {
        let start = floor_char_boundary(&self.text, span.start.min(self.text.len()));
        let (line, col) = self.line_col(start);
        let line_start = self.text[..start].rfind('\n').map_or(0, |k| k + 1);
        let line_end = self.text[start..]
            .find('\n')
            .map_or(self.text.len(), |k| start + k);
        // Control characters (a binary file's NULs, say) would garble the terminal.
        let line_text: String = self.text[line_start..line_end]
            .trim_end_matches('\r')
            .chars()
            .map(|c| {
                if c.is_control() && c != '\t' {
                    '\u{fffd}'
                } else {
                    c
                }
            })
            .collect();
        let end = floor_char_boundary(&self.text, span.end.clamp(start, line_end));
        let width = self.text[start..end].chars().count().max(1);
        Diagnostic {
            path: self.path.clone(),
            line,
            col,
            width,
            line_text,
            message: message.into(),
            help: None,
        }
    }
}

fn floor_char_boundary(s: &str, mut k: usize) -> usize {
    while k > 0 && !s.is_char_boundary(k) {
        k -= 1;
    }
    k
}

/// Where an expression's text lives in its file: byte `k` of the expression is byte
/// `map[k]` of the file (a TOML string may contain escapes, so the map is explicit).
#[derive(Clone, Debug)]
pub struct Origin {
    pub file: Arc<SourceFile>,
    pub map: Vec<usize>,
}

impl Origin {
    /// An origin for text that is itself the whole file (tests, command-line input).
    pub fn whole(file: Arc<SourceFile>) -> Self {
        let map = (0..=file.text.len()).collect();
        Origin { file, map }
    }

    /// The file span of an expression span.
    pub fn file_span(&self, span: Span) -> Span {
        let at = |k: usize| self.map.get(k).or(self.map.last()).copied().unwrap_or(0);
        let start = at(span.start);
        let end = if span.end > span.start {
            at(span.end - 1) + 1
        } else {
            start
        };
        Span::new(start, end.max(start))
    }

    pub fn diagnostic(&self, span: Span, message: impl Into<String>) -> Diagnostic {
        self.file.diagnostic(self.file_span(span), message)
    }
}

/// The most characters of a source line a diagnostic shows.
const SHOWN_CHARS: usize = 120;

/// A user-facing error located in a file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Diagnostic {
    pub path: String,
    pub line: usize,
    pub col: usize,
    pub width: usize,
    pub line_text: String,
    pub message: String,
    pub help: Option<String>,
}

impl Diagnostic {
    /// Where it points, as `path:line:col`.
    pub fn location(&self) -> String {
        format!("{}:{}:{}", self.path, self.line, self.col)
    }

    pub fn with_help(mut self, help: impl Into<String>) -> Self {
        self.help = Some(help.into());
        self
    }
}

impl Diagnostic {
    /// The diagnostic as a warning: the same text, headed `warning:`.
    pub fn warning(&self) -> String {
        struct Warning<'a>(&'a Diagnostic);
        impl fmt::Display for Warning<'_> {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                self.0.write_headed(f, "warning")
            }
        }
        Warning(self).to_string()
    }

    fn write_headed(&self, f: &mut fmt::Formatter<'_>, head: &str) -> fmt::Result {
        let num = self.line.to_string();
        let pad = " ".repeat(num.len());
        writeln!(f, "{head}: {}", self.message)?;
        writeln!(f, "{pad} --> {}:{}:{}", self.path, self.line, self.col)?;
        writeln!(f, "{pad} |")?;
        // A long line is shown as a window around the caret, marked `…` where cut.
        let chars: Vec<char> = self.line_text.chars().collect();
        let at = (self.col - 1).min(chars.len());
        let from = if chars.len() > SHOWN_CHARS {
            at.saturating_sub(SHOWN_CHARS / 3)
        } else {
            0
        };
        let to = chars.len().min(from + SHOWN_CHARS);
        let (open, close) = (
            if from > 0 { "…" } else { "" },
            if to < chars.len() { "…" } else { "" },
        );
        let shown: String = chars[from..to].iter().collect();
        writeln!(f, "{num} | {open}{shown}{close}")?;
        let lead: String = std::iter::repeat_n(' ', open.chars().count())
            .chain(
                chars[from..at]
                    .iter()
                    .map(|&c| if c == '\t' { '\t' } else { ' ' }),
            )
            .collect();
        let width = self.width.min((to - at).max(1));
        write!(f, "{pad} | {lead}{}", "^".repeat(width))?;
        if let Some(help) = &self.help {
            write!(f, "\n{pad} = help: {help}")?;
        }
        Ok(())
    }
}

impl std::error::Error for Diagnostic {}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.write_headed(f, "error")
    }
}

#[cfg(test)]
mod tests {

    #[test]
    fn line_and_column_agree_with_a_scan_from_the_start() {
        let long: String = "αβ".repeat(5000);
        let text = format!("a = 1\nσ_ij = 'é'\n{long}x\n\nlast");
        let file = SourceFile::new("t.toml", text.clone());
        let naive = |offset: usize| {
            let before = &text[..offset];
            let line = before.matches('\n').count() + 1;
            let start = before.rfind('\n').map_or(0, |k| k + 1);
            (line, text[start..offset].chars().count() + 1)
        };
        for offset in (0..=text.len()).filter(|&k| text.is_char_boundary(k)) {
            assert_eq!(file.line_col(offset), naive(offset), "at {offset}");
        }
    }
    use super::*;

    #[test]
    fn caret_points_at_the_span() {
        let file = SourceFile::new("x.toml", "a = 1\nsides = [\"sigma_ki n_k n_k\"]\n");
        let at = file.text.find("n_k n_k").unwrap() + 4;
        let d = file.diagnostic(Span::new(at, at + 3), "index `k` occurs three times");
        assert_eq!((d.line, d.col), (2, 24));
        let text = d.with_help("rename one pair").to_string();
        assert_eq!(
            text,
            "error: index `k` occurs three times\n  --> x.toml:2:24\n  |\n2 | sides = [\"sigma_ki n_k n_k\"]\n  |                        ^^^\n  = help: rename one pair"
        );
    }

    #[test]
    fn a_long_line_is_shown_as_a_window_around_the_caret() {
        let text = format!("id = \"{}\"", "x".repeat(200_000));
        let file = SourceFile::new("z.toml", text.as_str());
        let d = file
            .diagnostic(Span::new(100_006, 100_007), "here")
            .to_string();
        let shown = d.lines().nth(3).unwrap();
        assert!(shown.chars().count() < 130, "{shown}");
        assert!(
            shown.starts_with("1 | …x") && shown.ends_with("x…"),
            "{shown}"
        );
        let caret = d.lines().nth(4).unwrap();
        assert_eq!(caret.find('^').unwrap() - "  | ".len(), 41, "{caret}");
        let short = file.diagnostic(Span::new(3, 4), "start").to_string();
        assert!(short.lines().nth(4).unwrap().ends_with("   ^"), "{short}");
    }

    #[test]
    fn out_of_range_spans_do_not_panic() {
        let file = SourceFile::new("y", "ab\u{e9}");
        let d = file.diagnostic(Span::new(3, 99), "m");
        assert_eq!(d.line, 1);
        let o = Origin::whole(file);
        let _ = o.diagnostic(Span::new(50, 60), "m").to_string();
    }
}
