//! MathML that cannot carry markup. The LaTeX-to-MathML converter (`pulldown-latex`)
//! copies the text of `\operatorname{…}`, `\mathop{…}`, `\text{…}` and their kin into
//! its output unescaped, so a statement from a stranger's file could put `<script>`,
//! `<img onerror=…>` or `<style>` into the page. Its output is therefore parsed here
//! and emitted again through an allowlist: MathML elements only, a few presentation
//! attributes with short plain values (no colour, no style, no link, no id), text
//! escaped, and every element closed in order. Anything else becomes visible text.
//! The converter itself runs only on formulas within [`MAX_LATEX`] bytes and
//! [`MAX_GROUP_DEPTH`] nested groups, so that rendering stays bounded.

/// The longest LaTeX formula converted (longer ones are shown as source).
pub const MAX_LATEX: usize = 8_000;

/// The deepest nesting of `{…}` groups and `\left…\right` pairs converted.
pub const MAX_GROUP_DEPTH: usize = 40;

/// The most elements one formula's MathML may open inside each other.
const MAX_DEPTH: usize = 200;

/// MathML elements kept (MathML Core's presentation elements, without `maction`).
const ELEMENTS: &[&str] = &[
    "math",
    "semantics",
    "annotation",
    "mrow",
    "mi",
    "mn",
    "mo",
    "ms",
    "mtext",
    "mspace",
    "msub",
    "msup",
    "msubsup",
    "munder",
    "mover",
    "munderover",
    "mmultiscripts",
    "mprescripts",
    "none",
    "mfrac",
    "msqrt",
    "mroot",
    "mstyle",
    "merror",
    "mpadded",
    "mphantom",
    "menclose",
    "mtable",
    "mtr",
    "mtd",
];

/// Attributes kept, with values of at most [`MAX_VALUE`] plain characters. Lengths
/// (`width`, `lspace`, …) are kept only when small, so that no formula can push text
/// out of view or over another claim.
const ATTRIBUTES: &[&str] = &[
    "display",
    "displaystyle",
    "scriptlevel",
    "mathvariant",
    "stretchy",
    "fence",
    "separator",
    "form",
    "largeop",
    "movablelimits",
    "symmetric",
    "accent",
    "accentunder",
    "linethickness",
    "columnalign",
    "rowalign",
    "columnspacing",
    "rowspacing",
    "columnlines",
    "rowlines",
    "frame",
    "notation",
    "encoding",
    "minsize",
    "maxsize",
    "lspace",
    "rspace",
    "width",
    "height",
    "depth",
    "voffset",
];

const MAX_VALUE: usize = 48;

/// Why a formula is not converted: past a bound of its size.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum Unrendered {
    #[error("longer than {MAX_LATEX} bytes")]
    TooLong,
    #[error("nested more than {MAX_GROUP_DEPTH} groups deep")]
    TooDeep,
    /// What the converter said about LaTeX it cannot read.
    #[error("{0}")]
    Converter(String),
}

/// Whether `latex` is small enough to convert: within [`MAX_LATEX`] bytes and
/// [`MAX_GROUP_DEPTH`] nested groups. `Err` says why not.
pub fn within_bounds(latex: &str) -> Result<(), Unrendered> {
    if latex.len() > MAX_LATEX {
        return Err(Unrendered::TooLong);
    }
    let (mut depth, mut deepest) = (0usize, 0usize);
    let mut rest = latex;
    while let Some(c) = rest.chars().next() {
        if let Some(tail) = rest.strip_prefix("\\left") {
            depth += 1;
            rest = tail;
        } else if let Some(tail) = rest.strip_prefix("\\right") {
            depth = depth.saturating_sub(1);
            rest = tail;
        } else if rest.starts_with("\\{") || rest.starts_with("\\}") {
            rest = &rest[2..];
        } else {
            match c {
                '{' => depth += 1,
                '}' => depth = depth.saturating_sub(1),
                _ => {}
            }
            rest = &rest[c.len_utf8()..];
        }
        deepest = deepest.max(depth);
    }
    if deepest > MAX_GROUP_DEPTH {
        return Err(Unrendered::TooDeep);
    }
    Ok(())
}

/// `markup` (a converter's MathML) re-emitted through the allowlist.
pub fn sanitized(markup: &str) -> String {
    let mut out = String::with_capacity(markup.len());
    let mut open: Vec<&str> = Vec::new();
    let mut rest = markup;
    while !rest.is_empty() {
        if let Some(after) = rest.strip_prefix("<!--") {
            rest = after.find("-->").map_or("", |k| &after[k + 3..]);
            continue;
        }
        if rest.starts_with('<') {
            if let Some((tag, after)) = Tag::parse(rest) {
                if tag.emit(&mut out, &mut open) {
                    rest = after;
                    continue;
                }
            }
            out.push_str("&lt;");
            rest = &rest[1..];
            continue;
        }
        let end = rest.find('<').unwrap_or(rest.len());
        text(&rest[..end], &mut out);
        rest = &rest[end..];
    }
    while let Some(name) = open.pop() {
        out.push_str("</");
        out.push_str(name);
        out.push('>');
    }
    out
}

/// Text with `<`, `>` and quotes escaped, and `&` kept only where it starts a
/// character reference.
fn text(s: &str, out: &mut String) {
    let mut rest = s;
    while let Some(c) = rest.chars().next() {
        match c {
            '&' => match reference(rest) {
                Some(len) => {
                    out.push_str(&rest[..len]);
                    rest = &rest[len..];
                    continue;
                }
                None => out.push_str("&amp;"),
            },
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c if c.is_control() && c != '\n' && c != '\t' => {}
            c => out.push(c),
        }
        rest = &rest[c.len_utf8()..];
    }
}

/// The length of the character reference `s` starts with (`&lt;`, `&#8722;`,
/// `&#x2212;`), if it starts with one.
fn reference(s: &str) -> Option<usize> {
    let body = s.strip_prefix('&')?;
    let end = body.find(';')?;
    let name = &body[..end];
    let ok = if let Some(hex) = name.strip_prefix("#x").or_else(|| name.strip_prefix("#X")) {
        (1..=6).contains(&hex.len()) && hex.chars().all(|c| c.is_ascii_hexdigit())
    } else if let Some(dec) = name.strip_prefix('#') {
        (1..=7).contains(&dec.len()) && dec.chars().all(|c| c.is_ascii_digit())
    } else {
        (1..=32).contains(&name.len()) && name.chars().all(|c| c.is_ascii_alphanumeric())
    };
    ok.then_some(end + 2)
}

/// One tag of the converter's output.
struct Tag<'a> {
    name: &'a str,
    closing: bool,
    empty: bool,
    attributes: Vec<(&'a str, &'a str)>,
}

impl<'a> Tag<'a> {
    /// The tag `s` starts with and what follows it, or `None` when `s` does not start
    /// with a well-formed tag.
    fn parse(s: &'a str) -> Option<(Tag<'a>, &'a str)> {
        let body = s.strip_prefix('<')?;
        let (closing, body) = match body.strip_prefix('/') {
            Some(b) => (true, b),
            None => (false, body),
        };
        let name_len = body
            .find(|c: char| !c.is_ascii_alphanumeric())
            .unwrap_or(body.len());
        let name = &body[..name_len];
        if name.is_empty() {
            return None;
        }
        let mut rest = &body[name_len..];
        let mut attributes = Vec::new();
        loop {
            rest = rest.trim_start();
            if let Some(after) = rest.strip_prefix("/>") {
                return (!closing).then_some((
                    Tag {
                        name,
                        closing,
                        empty: true,
                        attributes,
                    },
                    after,
                ));
            }
            if let Some(after) = rest.strip_prefix('>') {
                return Some((
                    Tag {
                        name,
                        closing,
                        empty: false,
                        attributes,
                    },
                    after,
                ));
            }
            if closing {
                return None;
            }
            let key_len = rest
                .find(|c: char| !(c.is_ascii_alphanumeric() || c == '-' || c == ':'))
                .unwrap_or(rest.len());
            if key_len == 0 {
                return None;
            }
            let key = &rest[..key_len];
            rest = rest[key_len..].trim_start();
            let value;
            if let Some(after) = rest.strip_prefix('=') {
                let after = after.trim_start();
                let quote = after.chars().next()?;
                if quote != '"' && quote != '\'' {
                    return None;
                }
                let inner = &after[1..];
                let end = inner.find(quote)?;
                value = &inner[..end];
                rest = &inner[end + 1..];
            } else {
                value = "";
            }
            attributes.push((key, value));
        }
    }

    /// Writes the tag if the allowlist keeps it; `false` (nothing written) when it
    /// must be shown as text instead.
    fn emit(&self, out: &mut String, open: &mut Vec<&'a str>) -> bool {
        let Some(&name) = ELEMENTS.iter().find(|e| **e == self.name) else {
            return false;
        };
        if self.closing {
            if open.last() != Some(&name) {
                return false;
            }
            open.pop();
            out.push_str("</");
            out.push_str(name);
            out.push('>');
            return true;
        }
        if open.len() >= MAX_DEPTH || (name == "math") != open.is_empty() {
            return false;
        }
        out.push('<');
        out.push_str(name);
        for &(key, value) in &self.attributes {
            if ATTRIBUTES.contains(&key) && plain(key, value) {
                out.push(' ');
                out.push_str(key);
                out.push_str("=\"");
                out.push_str(value);
                out.push('"');
            }
        }
        if self.empty {
            out.push_str(" />");
        } else {
            out.push('>');
            open.push(name);
        }
        true
    }
}

/// Whether an attribute's value is plain (letters, digits, spaces, `.`, `-`, `+`,
/// `%`, `#`), short, and, for a length, at most 4 units in size.
fn plain(key: &str, value: &str) -> bool {
    let chars_ok = value.len() <= MAX_VALUE
        && value
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || " .-+%#".contains(c));
    if !chars_ok {
        return false;
    }
    let length = matches!(
        key,
        "lspace" | "rspace" | "width" | "height" | "depth" | "voffset" | "minsize" | "maxsize"
    );
    if !length {
        return true;
    }
    let number: String = value
        .trim_start_matches(['+', '-'])
        .chars()
        .take_while(|c| c.is_ascii_digit() || *c == '.')
        .collect();
    number.is_empty() || number.parse::<f64>().is_ok_and(|x| x <= 4.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn markup_in_token_text_becomes_text() {
        let hostile = "<math display=\"inline\"><mi><img src=x onerror=alert(1)></mi>\
                       <mo><script>alert(2)</script></mo><mtext><style>*{display:none}</style></mtext></math>";
        let out = sanitized(hostile);
        assert!(!out.contains("<img") && !out.contains("<script") && !out.contains("<style"));
        assert!(out.contains("&lt;img src=x onerror=alert(1)&gt;"), "{out}");
        assert!(out.starts_with("<math display=\"inline\">"));
        assert!(out.ends_with("</math>"));
    }

    #[test]
    fn attributes_outside_the_allowlist_or_not_plain_are_dropped() {
        let out = sanitized(
            "<math><mi onclick=\"alert(1)\" style=\"color:red\" mathcolor=\"white\" mathvariant=\"bold\">x</mi>\
             <mspace width=\"10000em\"/><mspace width=\"1em\"/><mi href=\"javascript:alert(1)\">y</mi></math>",
        );
        assert!(!out.contains("onclick") && !out.contains("style") && !out.contains("mathcolor"));
        assert!(!out.contains("href") && !out.contains("10000em"), "{out}");
        assert!(out.contains("mathvariant=\"bold\"") && out.contains("width=\"1em\""));
    }

    #[test]
    fn unbalanced_and_nested_math_tags_cannot_break_out() {
        // A stray closing tag is text; an element left open is closed at the end; a
        // second <math> inside the first is text.
        let out = sanitized("<math><mi>x</mi></mrow></mi></math><mrow><math><mi>y");
        assert_eq!(
            out,
            "<math><mi>x</mi>&lt;/mrow&gt;&lt;/mi&gt;</math>&lt;mrow&gt;<math><mi>y</mi></math>"
        );
    }

    #[test]
    fn entities_are_kept_and_bare_ampersands_escaped() {
        let out = sanitized("<math><mo>&lt;</mo><mo>&#x2212;</mo><mi>a&b</mi><mi>&amp</mi></math>");
        assert!(out.contains("<mo>&lt;</mo><mo>&#x2212;</mo><mi>a&amp;b</mi><mi>&amp;amp</mi>"));
    }

    #[test]
    fn formulas_past_the_bounds_are_not_converted() {
        assert!(within_bounds("\\frac{a}{b} + \\left( x \\right)").is_ok());
        let deep = "{".repeat(41) + &"}".repeat(41);
        assert!(within_bounds(&deep).is_err());
        let lefts = "\\left(".repeat(41) + &"\\right)".repeat(41);
        assert!(within_bounds(&lefts).is_err());
        assert!(within_bounds(&"x".repeat(MAX_LATEX + 1)).is_err());
        // Escaped braces are not groups.
        assert!(within_bounds(&"\\{".repeat(100)).is_ok());
    }
}
