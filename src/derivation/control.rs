//! Control characters are refused in a derivation file, written raw or as a TOML
//! escape (`"\u001b[2J"`, `"\b"`): they would reach a terminal as escape sequences, a
//! report as invisible text, or the LaTeX writer, and no statement needs one. So are the
//! bidirectional controls and the line separators, which reorder or break what a reader
//! sees. A tab and the line ends are allowed.

/// The byte offset of the first control character in `text` (raw, or escaped inside
/// a basic string), with a description of it; `None` when there is none.
pub fn first_control(text: &str) -> Option<(usize, String)> {
    let bytes = text.as_bytes();
    let mut k = 0;
    let mut string: Option<&'static str> = None; // the closing quote(s) of the string we are in
    let mut comment = false;
    while k < bytes.len() {
        let c = text[k..].chars().next()?;
        if forbidden(c) {
            return Some((k, describe(c)));
        }
        let rest = &text[k..];
        match string {
            None if comment => {
                if c == '\n' {
                    comment = false;
                }
            }
            None => {
                if c == '#' {
                    comment = true;
                } else if matches!(c, '"' | '\'') {
                    for quote in ["\"\"\"", "'''", "\"", "'"] {
                        if rest.starts_with(quote) {
                            string = Some(quote);
                            k += quote.len();
                            break;
                        }
                    }
                    if string.is_some() {
                        continue;
                    }
                }
            }
            Some(quote) => {
                if matches!(c, '"' | '\'') && rest.starts_with(quote) {
                    string = None;
                    k += quote.len();
                    continue;
                }
                if c == '\\' && quote.starts_with('"') {
                    if let Some(found) = escaped(&rest[1..]) {
                        return Some((k, found));
                    }
                    // Skip the escaped character, so that `\"` does not end the string.
                    k += 1 + rest[1..].chars().next().map_or(0, char::len_utf8);
                    continue;
                }
            }
        }
        k += c.len_utf8();
    }
    None
}

pub(crate) fn forbidden(c: char) -> bool {
    (c.is_control() && !matches!(c, '\t' | '\n' | '\r')) || invisible(c) || noncharacter(c)
}

/// The noncharacters (U+FDD0–U+FDEF and the last two code points of every plane),
/// which XML, and so the SVG and HTML reports, may not contain.
fn noncharacter(c: char) -> bool {
    let u = u32::from(c);
    (0xFDD0..=0xFDEF).contains(&u) || u & 0xFFFE == 0xFFFE
}

/// Formatting characters that reorder or break what a reader sees: the bidirectional
/// controls (which make `=1 X` display as `X 1=`) and the line and paragraph separators
/// (a line break to some terminals and viewers, none to a report's line count).
fn invisible(c: char) -> bool {
    matches!(c, '\u{61C}' | '\u{200E}' | '\u{200F}' | '\u{202A}'..='\u{202E}' | '\u{2066}'..='\u{2069}' | '\u{2028}' | '\u{2029}')
}

pub(crate) fn describe(c: char) -> String {
    if invisible(c) {
        format!(
            "the invisible formatting character U+{:04X} (a bidirectional control or a line separator)",
            u32::from(c)
        )
    } else if noncharacter(c) {
        format!("the noncharacter U+{:04X}", u32::from(c))
    } else {
        format!("the control character U+{:04X}", u32::from(c))
    }
}

/// The control character an escape (after its backslash) stands for, described.
fn escaped(after: &str) -> Option<String> {
    let hex = |n: usize| {
        after
            .get(1..=n)
            .and_then(|h| u32::from_str_radix(h, 16).ok())
            .and_then(char::from_u32)
    };
    let c = match after.chars().next()? {
        'b' => '\u{8}',
        'f' => '\u{c}',
        'e' => '\u{1b}',
        'u' => hex(4)?,
        'U' => hex(8)?,
        _ => return None,
    };
    forbidden(c).then(|| format!("{} (written as a TOML escape)", describe(c)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn raw_and_escaped_control_characters_are_found_where_they_are() {
        assert_eq!(first_control("a = \"x\"\nb = 'y'\n"), None);
        assert_eq!(first_control("a = \"x\u{1b}\"").map(|f| f.0), Some(6));
        let (at, what) = first_control("a = \"ok\"\nb = \"\\u001b[2J\"").unwrap();
        assert_eq!(at, 14);
        assert!(what.contains("U+001B") && what.contains("escape"), "{what}");
        // \b in a basic string is a backspace (a LaTeX \beta written in "…").
        assert!(first_control("p = \"\\beta\"").is_some());
        // In a literal string, or a comment, a backslash is only a backslash.
        assert_eq!(first_control("p = '\\beta \\u0001'  # \\u0007"), None);
        // An escaped quote does not end the string; a tab is fine.
        assert_eq!(first_control("p = \"\\\"\\u0041\t\""), None);
        assert!(first_control("p = \"\\\"\\u0002\"").is_some());
        assert!(first_control("p = \"\"\"\n\\U0000009b\"\"\"").is_some());
        // Bidirectional controls and line separators, raw or escaped.
        assert!(first_control("p = 'a\u{202e}b'").is_some());
        assert!(first_control("p = \"\\u2066\"").is_some());
        assert!(first_control("p = \"a\u{2028}b\"").is_some());
        assert!(first_control("# \u{200f}\np = 1").is_some());
        // Noncharacters, which no XML may hold, raw or escaped.
        assert!(first_control("p = 'A\u{fffe}'").is_some());
        assert!(first_control("p = \"\\uFFFF\"").is_some());
        assert!(first_control("p = \"\\U0010FFFF\"").is_some());
        assert_eq!(first_control("p = 'ﬀ \u{fdcf}'"), None);
    }
}
