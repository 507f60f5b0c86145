//! The derivation table and the errata in LaTeX: a `longtable` fragment (packages
//! `longtable`, `array`, `amsmath`, `amssymb`), or with `--standalone` a complete
//! document. Statements are typeset as printed (they are LaTeX already); every other
//! text is escaped and transliterated to ASCII, so the output compiles with plain
//! pdflatex.

use super::{evidence, full_evidence, verdict_label, Summary};
use crate::strategy::Decided;
use std::fmt::Write as _;

/// Marks math that must pass through unescaped (inserted by [`math`], consumed by
/// [`escape`]).
const OPEN: char = '\u{1}';
const CLOSE: char = '\u{2}';

fn math(s: &str) -> String {
    format!(
        "{OPEN}{}{CLOSE}",
        s.split_whitespace().collect::<Vec<_>>().join(" ")
    )
}

/// A non-ASCII character in text mode, as LaTeX.
fn transliterate(c: char) -> Option<&'static str> {
    Some(match c {
        '≤' => "$\\le$",
        '≥' => "$\\ge$",
        '≠' => "$\\ne$",
        '≈' => "$\\approx$",
        '\u{0307}' => "$^{\\cdot}$", // combining dot above (a rate: μ̇)
        '−' => "-",
        '–' => "--",
        '—' => "---",
        '·' => "$\\cdot$",
        '×' | '✗' => "$\\times$",
        '⊗' => "$\\otimes$",
        '±' => "$\\pm$",
        '∂' => "$\\partial$",
        '∝' => "$\\propto$",
        '∞' => "$\\infty$",
        '∈' => "$\\in$",
        '√' => "$\\surd$",
        '→' => "$\\to$",
        '⟨' => "$\\langle$",
        '⟩' => "$\\rangle$",
        '…' => "\\dots{}",
        '“' => "``",
        '”' => "''",
        '‘' => "`",
        '’' => "'",
        '°' => "$^\\circ$",
        '¹' => "$^1$",
        '²' => "$^2$",
        '³' => "$^3$",
        '⁴' => "$^4$",
        '§' => "\\S{}",
        'ℓ' => "$\\ell$",
        'α' => "$\\alpha$",
        'β' => "$\\beta$",
        'γ' => "$\\gamma$",
        'Γ' => "$\\Gamma$",
        'δ' => "$\\delta$",
        'Δ' => "$\\Delta$",
        'ε' => "$\\varepsilon$",
        'θ' => "$\\theta$",
        'κ' => "$\\kappa$",
        'λ' => "$\\lambda$",
        'μ' => "$\\mu$",
        'ν' => "$\\nu$",
        'ξ' => "$\\xi$",
        'π' => "$\\pi$",
        'Π' => "$\\Pi$",
        'ρ' => "$\\rho$",
        'σ' => "$\\sigma$",
        'Σ' => "$\\Sigma$",
        'τ' => "$\\tau$",
        'φ' => "$\\phi$",
        'ψ' => "$\\psi$",
        'ω' => "$\\omega$",
        'é' => "\\'e",
        'ü' => "\\\"u",
        _ => return None,
    })
}

/// Escapes text for LaTeX text mode; `OPEN…CLOSE` spans become `$…$` unchanged and
/// backticked spans become `\texttt{…}`. Unknown non-ASCII characters become a bold
/// question mark (the tests assert none occur in the paper's table).
pub fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 16);
    let mut in_math = false;
    let mut in_code = false;
    for c in s.chars() {
        if in_math {
            if c == CLOSE {
                out.push('$');
                in_math = false;
            } else {
                out.push(c);
            }
            continue;
        }
        match c {
            OPEN => {
                out.push('$');
                in_math = true;
            }
            '`' => {
                out.push_str(if in_code { "}" } else { "\\texttt{" });
                in_code = !in_code;
            }
            '\\' => out.push_str("\\textbackslash{}"),
            '{' | '}' | '$' | '&' | '#' | '_' | '%' => {
                out.push('\\');
                out.push(c);
            }
            '^' => out.push_str("\\textasciicircum{}"),
            '~' => out.push_str("\\textasciitilde{}"),
            '|' => out.push_str("\\textbar{}"),
            '<' => out.push_str("\\textless{}"),
            '>' => out.push_str("\\textgreater{}"),
            '\n' => out.push(' '),
            c if c.is_ascii() => out.push(c),
            c => out.push_str(transliterate(c).unwrap_or("\\textbf{?}")),
        }
    }
    if in_code {
        out.push('}');
    }
    out
}

/// A statement: math, or prose with its own inline math.
fn statement(c: &crate::derivation::Claim) -> String {
    if c.prose {
        // Prose is LaTeX text already (with $…$ for math); quote it.
        let mut inner = String::new();
        let mut in_math = false;
        for ch in c.statement.chars() {
            if ch == '$' {
                in_math = !in_math;
                inner.push(if in_math { OPEN } else { CLOSE });
            } else {
                inner.push(ch);
            }
        }
        format!("``{}''", escape(&inner))
    } else {
        escape(&math(&c.statement))
    }
}

const PREAMBLE: &str = "\\documentclass[10pt]{article}\n\\usepackage[landscape,margin=1.5cm]{geometry}\n\\usepackage{longtable,array,amsmath,amssymb}\n\\renewcommand{\\arraystretch}{1.4}\n\\begin{document}\n";

fn wrap(body: String, standalone: bool, title: &str, paper: &str) -> String {
    if !standalone {
        return body;
    }
    format!(
        "{PREAMBLE}\\section*{{{}}}\n{}\n\n{body}\\end{{document}}\n",
        escape(title),
        escape(paper)
    )
}

/// The derivation table as a longtable.
pub fn render(rows: &[&Decided<'_>], standalone: bool, paper: &str) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "% Derivation table generated by cosserat-check; needs \\usepackage{{longtable,array,amsmath,amssymb}}.");
    let _ = writeln!(
        out,
        "\\begin{{longtable}}{{@{{}}>{{\\raggedright}}p{{0.09\\linewidth}}p{{0.03\\linewidth}}>{{\\raggedright}}p{{0.30\\linewidth}}p{{0.07\\linewidth}}p{{0.06\\linewidth}}>{{\\raggedright\\arraybackslash}}p{{0.35\\linewidth}}@{{}}}}"
    );
    let _ = writeln!(out, "\\hline\nclaim & \\S & statement (as printed) & verdict & method & evidence \\\\\n\\hline\n\\endhead");
    for r in rows {
        let c = r.claim;
        let _ = writeln!(
            out,
            "{} & {} & {} & {} & {} & {} \\\\",
            escape(&c.id),
            escape(&c.section),
            statement(c),
            escape(&verdict_label(r)),
            escape(r.outcome.method.as_str()),
            escape(&full_evidence(r, &math))
        );
    }
    let _ = writeln!(out, "\\hline\n\\end{{longtable}}");
    let _ = writeln!(out, "{}", escape(&Summary::of(rows).sentence(rows.len())));
    wrap(out, standalone, "Derivation table", paper)
}

/// The errata as a list.
pub fn errata(rows: &[&Decided<'_>], standalone: bool, paper: &str) -> String {
    let mut out = String::from("% Errata generated by cosserat-check.\n");
    if rows.is_empty() {
        out.push_str("Every printed statement checked holds.\n");
        return wrap(out, standalone, "Errata", paper);
    }
    out.push_str("\\begin{itemize}\n");
    for r in rows {
        let c = r.claim;
        let _ = writeln!(
            out,
            "\\item \\textbf{{{}}} (Section {}): {}",
            escape(&c.id),
            escape(&c.section),
            statement(c)
        );
        let _ = writeln!(out, "\\begin{{itemize}}");
        let _ = writeln!(
            out,
            "\\item Verdict: \\textbf{{{}}} ({})",
            escape(&r.outcome.verdict_text()),
            escape(r.outcome.method.as_str())
        );
        if let Some(reason) = &c.reason {
            let _ = writeln!(out, "\\item Why: {}", escape(reason));
        }
        let _ = writeln!(out, "\\item Evidence: {}", escape(&evidence(&r.outcome)));
        if let (Some(k), Some(o)) = (&c.correction, &r.correction) {
            let _ = writeln!(
                out,
                "\\item Correction: {} --- {} ({}). {}",
                escape(&math(&k.statement)),
                escape(&o.verdict_text()),
                escape(o.method.as_str()),
                escape(&k.reason)
            );
        }
        let _ = writeln!(out, "\\end{{itemize}}");
    }
    out.push_str("\\end{itemize}\n");
    wrap(out, standalone, "Errata", paper)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escaping_is_ascii_and_keeps_math() {
        let s = escape(&format!("a_b 50% & {}x^2{} ≤ `n_k` σ", OPEN, CLOSE));
        assert_eq!(s, "a\\_b 50\\% \\& $x^2$ $\\le$ \\texttt{n\\_k} $\\sigma$");
        assert!(s.is_ascii());
        assert_eq!(escape("☃"), "\\textbf{?}");
    }
}
