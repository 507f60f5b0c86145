//! Mapping characters of TOML string values back to byte offsets in their file, so a
//! diagnostic inside an expression points at the right line and column.

use crate::lang::Origin;
use std::ops::Range;

/// The origin of a slice `range` of an expression's text.
pub fn sub_origin(origin: &Origin, range: Range<usize>) -> Origin {
    let end = range.end.min(origin.map.len().saturating_sub(1));
    let start = range.start.min(end);
    Origin {
        file: origin.file.clone(),
        map: origin.map[start..=end].to_vec(),
    }
}

/// Maps each byte of a TOML string's value to its byte offset in the file. Literal
/// strings map one to one; escapes in basic strings map to their backslash. When the
/// raw text cannot be matched to the value, every byte maps to the string's start.
pub fn content_map(text: &str, span: Range<usize>, value: &str) -> Vec<usize> {
    let fallback = || vec![span.start; value.len() + 1];
    let Some(raw) = text.get(span.clone()) else {
        return fallback();
    };
    let (open, literal) = if raw.starts_with("'''") {
        (3, true)
    } else if raw.starts_with("\"\"\"") {
        (3, false)
    } else if raw.starts_with('\'') {
        (1, true)
    } else if raw.starts_with('"') {
        (1, false)
    } else {
        return fallback();
    };
    let mut pos = span.start + open;
    if open == 3 {
        if text[pos..].starts_with("\r\n") {
            pos += 2;
        } else if text[pos..].starts_with('\n') {
            pos += 1;
        }
    }
    if literal {
        if text.get(pos..pos + value.len()) != Some(value) {
            return fallback();
        }
        return (0..=value.len()).map(|k| pos + k).collect();
    }
    let mut map = Vec::with_capacity(value.len() + 1);
    let mut decoded = String::with_capacity(value.len());
    let body = &text[pos..span.end];
    let mut it = body.char_indices().peekable();
    while decoded.len() < value.len() {
        let Some((k, c)) = it.next() else { break };
        let at = pos + k;
        let ch = if c == '\\' {
            match it.next() {
                Some((_, 'n')) => '\n',
                Some((_, 't')) => '\t',
                Some((_, 'r')) => '\r',
                Some((_, 'b')) => '\u{8}',
                Some((_, 'f')) => '\u{c}',
                Some((_, 'e')) => '\u{1b}',
                Some((_, '"')) => '"',
                Some((_, '\\')) => '\\',
                Some((_, u @ ('u' | 'U'))) => {
                    let n = if u == 'u' { 4 } else { 8 };
                    let hex: String = (0..n).filter_map(|_| it.next().map(|(_, h)| h)).collect();
                    match u32::from_str_radix(&hex, 16).ok().and_then(char::from_u32) {
                        Some(ch) => ch,
                        None => return fallback(),
                    }
                }
                Some((_, w)) if w.is_whitespace() => {
                    // Line-ending backslash: skip all following whitespace.
                    while it.peek().is_some_and(|(_, w)| w.is_whitespace()) {
                        it.next();
                    }
                    continue;
                }
                _ => return fallback(),
            }
        } else {
            c
        };
        for _ in 0..ch.len_utf8() {
            map.push(at);
        }
        decoded.push(ch);
    }
    if decoded != value {
        return fallback();
    }
    map.push(map.last().map_or(pos, |&m| m + 1));
    map
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn content_maps_follow_quotes_and_escapes() {
        let text = r#"a = 'x_i y'
b = "p\tq_i"
c = '''
m_k'''"#;
        let span = |v: &str| {
            let k = text.find(v).unwrap();
            k..k + v.len()
        };
        assert_eq!(
            content_map(text, span("'x_i y'"), "x_i y")[2],
            text.find("i y").unwrap()
        );
        let m = content_map(text, span(r#""p\tq_i""#), "p\tq_i");
        assert_eq!(m[2], text.find("q_i").unwrap());
        let m = content_map(text, span("'''\nm_k'''"), "m_k");
        assert_eq!(m[0], text.find("m_k").unwrap());
        // A value that does not match its raw text falls back to the string's start.
        assert_eq!(content_map(text, span("'x_i y'"), "zzz"), vec![4; 4]);
    }
}
