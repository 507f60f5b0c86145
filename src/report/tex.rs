//! Printed LaTeX from a stranger's file, checked before it enters a `.tex` report.
//! TeX is a programming language: `\input{/etc/passwd}` reads a file when the report
//! is compiled, `\openout` and `\write` write one, `$}` and `\end{document}` close the
//! table early, `%` hides the rest of a line, and `^^5c` spells a backslash. A formula
//! passes only when every token is on an allowlist of mathematical notation
//! (`COMMANDS`, `ENVIRONMENTS`), its braces balance, and `&` and `\\` appear only
//! inside a matrix-like environment; anything else is shown as text, escaped.

/// Control words a formula may use besides those the LaTeX reader knows (its Greek
/// letters, functions, accents and delimiter sizes): operators, relations, symbols,
/// delimiters, fonts, spacing.
const COMMANDS: &[&str] = &[
    // Greek variants the reader does not take
    "epsilon",
    "varpi",
    "varrho",
    "varsigma",
    // operators and functions
    "frac",
    "tfrac",
    "dfrac",
    "sqrt",
    "sum",
    "prod",
    "int",
    "oint",
    "lim",
    "limits",
    "nolimits",
    "max",
    "min",
    "sup",
    "inf",
    "cot",
    "sec",
    "csc",
    "sinh",
    "cosh",
    "tanh",
    "sgn",
    "tr",
    "operatorname",
    "mathop",
    "partial",
    "nabla",
    "cdot",
    "cdots",
    "ldots",
    "dots",
    "vdots",
    "ddots",
    "times",
    "otimes",
    "oplus",
    "pm",
    "mp",
    "circ",
    "bullet",
    "ast",
    "star",
    // relations and arrows
    "le",
    "leq",
    "ge",
    "geq",
    "ne",
    "neq",
    "approx",
    "sim",
    "simeq",
    "cong",
    "equiv",
    "propto",
    "ll",
    "gg",
    "in",
    "notin",
    "ni",
    "subset",
    "subseteq",
    "supset",
    "cup",
    "cap",
    "to",
    "rightarrow",
    "Rightarrow",
    "leftarrow",
    "Leftarrow",
    "leftrightarrow",
    "Leftrightarrow",
    "longrightarrow",
    "Longrightarrow",
    "iff",
    "implies",
    "mapsto",
    "forall",
    "exists",
    "not",
    "mid",
    "parallel",
    "perp",
    "wedge",
    "vee",
    "neg",
    "land",
    "lor",
    // symbols
    "infty",
    "hbar",
    "prime",
    "emptyset",
    "angle",
    "deg",
    "S",
    // delimiters
    "bigg",
    "Bigg",
    "langle",
    "rangle",
    "lvert",
    "rvert",
    "lVert",
    "rVert",
    "vert",
    "Vert",
    "lbrace",
    "rbrace",
    "lfloor",
    "rfloor",
    "lceil",
    "rceil",
    // accents and fonts
    "check",
    "breve",
    "acute",
    "grave",
    "overline",
    "underline",
    "widehat",
    "widetilde",
    "overbrace",
    "underbrace",
    "mathrm",
    "mathit",
    "mathsf",
    "mathtt",
    "mathcal",
    "mathbb",
    "text",
    "textrm",
    "textit",
    "textbf",
    "mbox",
    // spacing and styles
    "quad",
    "qquad",
    "displaystyle",
    "textstyle",
    "scriptstyle",
    "begin",
    "end",
];

/// Whether `\word` may appear in a formula.
fn allowed(word: &str) -> bool {
    use crate::lang::latex::{ACCENTS, FUNCTIONS, GREEK, SIZES};
    [COMMANDS, GREEK, FUNCTIONS, ACCENTS, SIZES]
        .iter()
        .any(|list| list.contains(&word))
}

/// Environments a formula may open; inside them `&` and `\\` separate cells and rows.
const ENVIRONMENTS: &[&str] = &[
    "matrix",
    "pmatrix",
    "bmatrix",
    "Bmatrix",
    "vmatrix",
    "Vmatrix",
    "smallmatrix",
    "cases",
    "aligned",
    "gathered",
    "split",
];

/// Control symbols (a backslash and one other character) a formula may use.
const SYMBOLS: &str = ",;:! {}|_&#%$";

/// The first token of a formula that may not enter a `.tex` file.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum Refused {
    #[error("a backslash at the end")]
    TrailingBackslash,
    /// A control word or symbol outside the allowlist.
    #[error("`\\{0}`")]
    Macro(String),
    #[error("`\\{0}` of an environment not allowed")]
    Environment(String),
    #[error("`\\end{{{0}}}` without its `\\begin`")]
    UnopenedEnd(String),
    #[error("`\\begin{{{0}}}` never ended")]
    UnendedBegin(String),
    #[error("a `}}` closing no group")]
    ClosingBrace,
    #[error("a `{{` never closed")]
    OpenBrace,
    #[error("`&` outside a matrix")]
    Ampersand,
    /// `$`, `%` or `#`.
    #[error("`{0}`")]
    Special(char),
    #[error("`^^`")]
    Caret,
    #[error("a control character")]
    Control,
}

/// Whether `latex` is a formula that may enter a `.tex` file as it is: `Err` names
/// the first token that may not.
pub fn check(latex: &str) -> Result<(), Refused> {
    let mut depth = 0usize;
    let mut envs: Vec<&str> = Vec::new();
    let mut rest = latex;
    while let Some(c) = rest.chars().next() {
        let after = &rest[c.len_utf8()..];
        match c {
            '\\' => {
                let word_len = after
                    .find(|c: char| !c.is_ascii_alphabetic())
                    .unwrap_or(after.len());
                if word_len == 0 {
                    let Some(symbol) = after.chars().next() else {
                        return Err(Refused::TrailingBackslash);
                    };
                    let in_env = !envs.is_empty();
                    if !(SYMBOLS.contains(symbol) || (symbol == '\\' && in_env)) {
                        return Err(Refused::Macro(symbol.to_string()));
                    }
                    rest = &after[symbol.len_utf8()..];
                    continue;
                }
                let word = &after[..word_len];
                if !allowed(word) {
                    return Err(Refused::Macro(word.to_owned()));
                }
                rest = &after[word_len..];
                if word == "begin" || word == "end" {
                    let name = rest
                        .strip_prefix('{')
                        .and_then(|r| r.find('}').map(|k| &r[..k]))
                        .filter(|name| ENVIRONMENTS.contains(name))
                        .ok_or_else(|| Refused::Environment(word.to_owned()))?;
                    if word == "begin" {
                        envs.push(name);
                    } else if envs.pop() != Some(name) {
                        return Err(Refused::UnopenedEnd(name.to_owned()));
                    }
                    rest = &rest[name.len() + 2..];
                }
                continue;
            }
            '{' => depth += 1,
            '}' => {
                depth = depth.checked_sub(1).ok_or(Refused::ClosingBrace)?;
            }
            '&' if envs.is_empty() => return Err(Refused::Ampersand),
            '$' | '%' | '#' => return Err(Refused::Special(c)),
            '^' if after.starts_with('^') => return Err(Refused::Caret),
            c if c.is_control() => return Err(Refused::Control),
            _ => {}
        }
        rest = after;
    }
    if depth != 0 {
        return Err(Refused::OpenBrace);
    }
    if let Some(env) = envs.last() {
        return Err(Refused::UnendedBegin((*env).to_owned()));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::check;

    #[test]
    fn mathematics_passes() {
        for ok in [
            r"\frac{\partial F_2}{\partial \sigma_{ij}} = \tfrac13 \quad (\tau = 0,\ h^C = 1/2)",
            r"\mathbf{D}^{(el)} = G \begin{pmatrix} K+1 & 0 \\ 0 & 1 \end{pmatrix}",
            r"\left\langle n_i n_j \right\rangle = \tfrac{1}{3}\delta_{ij}, \text{ for } x \ge 0",
            r"\{ x \} \; \dot{\Gamma}",
        ] {
            assert_eq!(check(ok), Ok(()), "{ok}");
        }
    }

    #[test]
    fn tex_that_reads_writes_or_escapes_the_table_is_refused() {
        for bad in [
            r"\input{/etc/passwd}",
            r"x \text{\openout5=pwned.txt}",
            r"\immediate\write18{rm -rf ~}",
            r"x $} \end{longtable}\end{document}",
            r"x } \end{longtable}",
            r"x % the rest of the line",
            r"^^5cinput{/etc/passwd}",
            r"\catcode`\@=11",
            r"a & b",
            r"a \\ b",
            r"\begin{verbatim}",
            r"\begin{pmatrix} a \end{bmatrix}",
            r"\def\x{y}",
            r"{",
            "x \u{1}",
        ] {
            assert!(check(bad).is_err(), "{bad}");
        }
    }
}
