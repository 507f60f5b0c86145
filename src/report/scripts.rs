//! Superscripts and subscripts in an author's prose (notes, reasons): `f^{(1,2)c}`,
//! `K^c_mi`, `n_1^4`, `(M^c)^2`. Authors write them TeX-style in plain text; the HTML
//! and LaTeX reports set them as scripts instead of showing the braces and carets.
//!
//! The reading is deliberately narrow, so that ordinary text is left alone: a script
//! follows a one-letter word (`T^2`, `ℓ_m`, not `my_file` or `sigma_11`), a closing
//! parenthesis or brace, or another script; its argument is a braced group or a run of
//! letters and digits. Anything else, an unbalanced brace included, stays as written.

/// A piece of prose: text, or a script whose content is itself prose.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Piece {
    Text(String),
    Sup(Vec<Piece>),
    Sub(Vec<Piece>),
}

/// Braced groups deeper than this stay as written (the reading recurses into them).
const DEPTH: usize = 4;

/// `s` as text and scripts.
pub fn pieces(s: &str) -> Vec<Piece> {
    read(s, 0)
}

fn read(s: &str, depth: usize) -> Vec<Piece> {
    let chars: Vec<char> = s.chars().collect();
    // The brace each `{` closes at, found once (a scan per script would be quadratic
    // on a long run of unbalanced groups).
    let mut closing: Vec<Option<usize>> = vec![None; chars.len()];
    let mut open = Vec::new();
    for (k, &c) in chars.iter().enumerate() {
        match c {
            '{' => open.push(k),
            '}' => {
                if let Some(o) = open.pop() {
                    closing[o] = Some(k);
                }
            }
            _ => {}
        }
    }
    let mut out = Vec::new();
    let mut text = String::new();
    // Letters in the current word, and whether the last thing read was a script.
    let (mut word, mut after_script) = (0usize, false);
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        let base = word == 1 || after_script || matches!(text.chars().last(), Some(')' | '}'));
        if (c == '^' || c == '_') && base && i + 1 < chars.len() {
            if let Some((inner, next)) = argument(&chars, &closing, i + 1, depth) {
                if !text.is_empty() {
                    out.push(Piece::Text(std::mem::take(&mut text)));
                }
                out.push(if c == '^' {
                    Piece::Sup(inner)
                } else {
                    Piece::Sub(inner)
                });
                i = next;
                word = 0;
                after_script = true;
                continue;
            }
        }
        after_script = false;
        word = if c.is_alphabetic() { word + 1 } else { 0 };
        text.push(c);
        i += 1;
    }
    if !text.is_empty() {
        out.push(Piece::Text(text));
    }
    out
}

/// The argument of a script starting at `chars[at]`, and the index after it.
fn argument(
    chars: &[char],
    closing: &[Option<usize>],
    at: usize,
    depth: usize,
) -> Option<(Vec<Piece>, usize)> {
    if chars[at] == '{' {
        let end = closing[at]?;
        if depth >= DEPTH || end == at + 1 {
            return None;
        }
        let inner: String = chars[at + 1..end].iter().collect();
        return Some((read(&inner, depth + 1), end + 1));
    }
    let end = chars[at..]
        .iter()
        .position(|c| !c.is_alphanumeric())
        .map_or(chars.len(), |k| at + k);
    (end > at).then(|| (vec![Piece::Text(chars[at..end].iter().collect())], end))
}

/// Renders prose with each format's escaping of text and its markup for scripts.
pub fn render(
    s: &str,
    text: &dyn Fn(&str) -> String,
    sup: (&str, &str),
    sub: (&str, &str),
) -> String {
    fn go(
        ps: &[Piece],
        text: &dyn Fn(&str) -> String,
        sup: (&str, &str),
        sub: (&str, &str),
        out: &mut String,
    ) {
        for p in ps {
            match p {
                Piece::Text(t) => out.push_str(&text(t)),
                Piece::Sup(inner) | Piece::Sub(inner) => {
                    let (open, close) = if matches!(p, Piece::Sup(_)) { sup } else { sub };
                    out.push_str(open);
                    go(inner, text, sup, sub, out);
                    out.push_str(close);
                }
            }
        }
    }
    let mut out = String::new();
    go(&pieces(s), text, sup, sub, &mut out);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn html(s: &str) -> String {
        render(
            s,
            &|t| t.replace('<', "&lt;"),
            ("<sup>", "</sup>"),
            ("<sub>", "</sub>"),
        )
    }

    #[test]
    fn an_authors_scripts_are_set_and_ordinary_text_is_left_alone() {
        assert_eq!(
            html("The reaction f^{(1,2)c} = −f^{(2,1)c}"),
            "The reaction f<sup>(1,2)c</sup> = −f<sup>(2,1)c</sup>"
        );
        assert_eq!(
            html("K^c_mi and n_1^4"),
            "K<sup>c</sup><sub>mi</sub> and n<sub>1</sub><sup>4</sup>"
        );
        assert_eq!(
            html("(M^c)^2 = T^2"),
            "(M<sup>c</sup>)<sup>2</sup> = T<sup>2</sup>"
        );
        assert_eq!(html("t^{(t)}_k"), "t<sup>(t)</sup><sub>k</sub>");
        // Words longer than a letter, empty or unbalanced groups, a caret at the end.
        for plain in [
            "my_file.toml",
            "sigma_11",
            "x^{}",
            "f^{(1,2",
            "a^",
            "2^3",
            "_k",
        ] {
            assert_eq!(html(plain), plain);
        }
        // Markup inside a script is still the format's text.
        assert_eq!(html("x^{<b>}"), "x<sup>&lt;b></sup>");
        // Nesting past the bound stays as written.
        let deep = "x^{a^{b^{c^{d^{e}}}}}";
        assert!(html(deep).contains("d^{e}"), "{}", html(deep));
        // A long run of unbalanced groups is read in linear time, as written.
        let long = "a^{".repeat(200_000);
        assert_eq!(html(&long), long.replace('<', "&lt;"));
    }
}
