//! The derivation table and the errata in LaTeX: a `longtable` fragment (packages
//! `longtable`, `array`, `amsmath`, `amssymb`), or with `--standalone` a complete
//! document. Statements are typeset as printed (they are LaTeX already); every other
//! text is escaped and transliterated to ASCII, so the output compiles with plain
//! pdflatex.

use super::evidence::evidence;
use super::row::full_evidence;
use super::summary::Summary;
use crate::check::Decided;
use std::fmt::Write as _;

/// Marks math that must pass through unescaped (inserted by [`math`], consumed by
/// [`escape`]).
const OPEN: char = '\u{1}';
const CLOSE: char = '\u{2}';
/// Around mathematics (between [`OPEN`] and [`CLOSE`]) that [`escape`] scales to the
/// column with `\ccfit`.
const FIT: char = '\u{3}';
const FIT_END: char = '\u{4}';
/// Around an author's superscript or subscript (inserted by [`authored`]), which
/// [`escape`] sets with `\textsuperscript` or `\textsubscript`.
const SUP: char = '\u{5}';
const SUB: char = '\u{6}';
const SCRIPT_END: char = '\u{7}';
/// Every mark [`escape`] gives a meaning; text from a file never carries one.
const MARKERS: [char; 7] = [OPEN, CLOSE, FIT, FIT_END, SUP, SUB, SCRIPT_END];

/// An author's prose (a reason) with its TeX-style scripts (`f^{(1,2)c}`) marked for
/// [`escape`] to set in text mode ([`super::scripts`]); the rest stays text.
fn authored(s: &str) -> String {
    let (sup, sub, end) = (SUP.to_string(), SUB.to_string(), SCRIPT_END.to_string());
    // Only outside `code` spans, which `escape` typesets as expressions; a backtick
    // that opens no closed span is a quotation mark, so that the span cannot run on
    // into the words that follow the reason.
    let mut text: String = s.chars().filter(|c| !MARKERS.contains(c)).collect();
    if text.matches('`').count() % 2 == 1 {
        if let Some(k) = text.rfind('`') {
            text.replace_range(k..k + 1, "‘");
        }
    }
    text.split('`')
        .enumerate()
        .map(|(k, part)| match k % 2 {
            0 => super::scripts::render(part, &|t| t.to_owned(), (&sup, &end), (&sub, &end)),
            _ => part.to_owned(),
        })
        .collect::<Vec<_>>()
        .join("`")
}

/// A printed formula as mathematics when [`super::tex::check`] lets it into a `.tex`
/// file; otherwise its text, for [`escape`] to show literally (with no backtick to
/// start a quotation).
fn math(s: &str) -> String {
    if super::tex::check(s).is_ok() {
        format!(
            "{OPEN}{}{CLOSE}",
            s.split_whitespace().collect::<Vec<_>>().join(" ")
        )
    } else {
        literal(s)
    }
}

/// Text with the characters [`escape`] gives a meaning (markers, backticks) made plain.
fn literal(s: &str) -> String {
    s.chars()
        .filter(|c| !MARKERS.contains(c))
        .map(|c| if c == '`' { '‘' } else { c })
        .collect()
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
        '‖' => "$\\|$",
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
/// backticked spans (expressions of the language) are typeset as mathematics
/// ([`expression`]). Outside mathematics a line may break after `*`, `(`, `,`, `=` and
/// `/`, so that no long token overfills a narrow column. Unknown non-ASCII characters
/// become a bold question mark (the tests assert none occur in the paper's table).
pub fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 16);
    let mut in_math = false;
    let mut code: Option<String> = None;
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
        if let Some(text) = &mut code {
            if c == '`' {
                // A quotation of printed LaTeX (a backslash or a brace: the language has
                // neither) is typeset as it was printed.
                let command = text
                    .strip_prefix('\\')
                    .is_some_and(|w| w.chars().all(|c| c.is_ascii_alphabetic()));
                if command {
                    // A command named alone (`\overline`) is quoted, not typeset.
                    let _ = write!(out, "\\texttt{{\\textbackslash {}}}", &text[1..]);
                } else if text.contains(['\\', '{']) && super::tex::check(text).is_ok() {
                    let _ = write!(out, "${text}$");
                } else if text.contains(['\\', '{']) {
                    let _ = write!(out, "\\texttt{{{}}}", escape(&literal(text)));
                } else {
                    out.push_str(&quoted_expression(text));
                }
                code = None;
            } else {
                text.push(c);
            }
            continue;
        }
        match c {
            OPEN => {
                out.push('$');
                in_math = true;
            }
            // On a line of its own, so that scaled to the column it fits beside nothing.
            FIT => out.push_str("\\newline\\ccfit{"),
            FIT_END => out.push_str("}\\newline "),
            SUP => out.push_str("\\textsuperscript{"),
            SUB => out.push_str("\\textsubscript{"),
            SCRIPT_END => out.push('}'),
            // Straight double quotes as TeX's opening and closing quotes.
            '"' => {
                // After a space, an opening bracket or a break point (`(\allowbreak{}`).
                let opening = out.is_empty()
                    || out.ends_with([' ', '(', '[', '{', '~'])
                    || out.ends_with("\\allowbreak{}");
                out.push_str(if opening { "``" } else { "''" });
            }
            '`' => code = Some(String::new()),
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
            '*' | '(' | ',' | '=' | '/' => {
                out.push(c);
                out.push_str("\\allowbreak{}");
            }
            c if c.is_ascii() => out.push(c),
            c => out.push_str(transliterate(c).unwrap_or("\\textbf{?}")),
        }
    }
    if let Some(text) = code {
        out.push_str(&quoted_expression(&text));
    }
    out
}

/// A backticked span of text: an expression of the language typeset by [`expression`],
/// anything else (an author's `é`, `^^`) in typewriter type as the characters it is.
fn quoted_expression(text: &str) -> String {
    // What the typesetter reads: the language's characters (with the ellipsis of a
    // truncated polynomial and √), each script followed by what it raises or lowers.
    let chars: Vec<char> = text.chars().collect();
    let known = chars.iter().all(|c| {
        c.is_ascii_alphanumeric() || " _^*/+-(),.=<>|!'[];:".contains(*c) || "…√·−".contains(*c)
    });
    let scripts = chars.iter().enumerate().all(|(k, c)| {
        !matches!(c, '^' | '_')
            || chars
                .get(k + 1)
                .is_some_and(|n| n.is_ascii_alphanumeric() || matches!(n, '(' | '-'))
    });
    if known && scripts && !text.trim().is_empty() {
        expression(text)
    } else {
        format!("\\texttt{{{}}}", escape(&literal(text)))
    }
}

/// An expression of the language (`-n_2*R_g*Dw_31 + sigma_ki n_k`) as inline
/// mathematics: Greek names as letters, index digits and letters as subscripts,
/// products as thin spaces, powers as superscripts; a name of several letters upright.
/// A sum may break at its top-level `+` and `−`.
pub fn expression(s: &str) -> String {
    let chars: Vec<char> = s.chars().collect();
    let mut out = String::from("$");
    let mut k = 0;
    while k < chars.len() {
        let c = chars[k];
        if c.is_ascii_alphabetic() {
            let start = k;
            while k < chars.len() && (chars[k].is_ascii_alphanumeric() || chars[k] == '_') {
                k += 1;
            }
            let word: String = chars[start..k].iter().collect();
            let (base, sub) = match word.rsplit_once('_') {
                Some((b, i)) if !b.is_empty() && !i.is_empty() => {
                    (b.to_owned(), Some(i.to_owned()))
                }
                _ => (word.clone(), None),
            };
            out.push_str(&name(&base));
            if let Some(i) = sub {
                let _ = write!(out, "_{{{}}}", i.replace('_', "\\_"));
            }
            continue;
        }
        // The truncation note of a long polynomial, "(82 terms in all)", is words.
        if c == '(' {
            let rest: String = chars[k..].iter().collect();
            if let Some(n) = rest
                .strip_prefix('(')
                .and_then(|r| r.split_once(" terms in all)"))
                .map(|(n, _)| n)
                .filter(|n| !n.is_empty() && n.chars().all(|d| d.is_ascii_digit()))
            {
                let _ = write!(out, "\\text{{({n} terms in all)}}");
                k += n.len() + " terms in all)".len() + 1;
                continue;
            }
        }
        match c {
            '*' => out.push_str("\\,"),
            // A product written with a space.
            ' ' if k > 0
                && chars[k - 1].is_ascii_alphanumeric()
                && chars.get(k + 1).is_some_and(|n| n.is_ascii_alphanumeric()) =>
            {
                out.push_str("\\,")
            }
            '^' => {
                // The exponent: a signed integer or one character.
                let mut e = String::new();
                k += 1;
                if k < chars.len() && chars[k] == '-' {
                    e.push('-');
                    k += 1;
                }
                while k < chars.len() && chars[k].is_ascii_digit() {
                    e.push(chars[k]);
                    k += 1;
                }
                if e.is_empty() || e == "-" {
                    if let Some(&x) = chars.get(k) {
                        e.push(x);
                        k += 1;
                    }
                }
                let _ = write!(out, "^{{{e}}}");
                continue;
            }
            '{' | '}' | '$' | '&' | '#' | '%' | '_' => {
                out.push('\\');
                out.push(c);
            }
            '\\' => out.push_str("\\backslash "),
            '~' | '|' => out.push_str("\\mid "),
            '…' => out.push_str("\\dots"),
            c if c.is_ascii() => out.push(c),
            c => {
                let t = transliterate(c).unwrap_or("\\textbf{?}");
                out.push_str(t.trim_matches('$'));
            }
        }
        k += 1;
    }
    out.push('$');
    out
}

/// A language name in mathematics: a Greek name as its letter, one letter as itself,
/// several letters upright.
fn name(base: &str) -> String {
    const GREEK: [&str; 20] = [
        "alpha", "beta", "gamma", "delta", "epsilon", "theta", "kappa", "lambda", "mu", "nu", "xi",
        "pi", "rho", "sigma", "tau", "phi", "psi", "omega", "Gamma", "Delta",
    ];
    if GREEK.contains(&base) {
        format!("\\{base}")
    } else if base == "eps" {
        "\\varepsilon".to_owned()
    } else if base.chars().count() == 1 {
        base.to_owned()
    } else {
        format!("\\mathrm{{{base}}}")
    }
}

/// A statement: math scaled down to the column when wider, or quoted prose with its own
/// inline math.
fn statement(c: &crate::derivation::Claim) -> String {
    let formulas_safe = c
        .statement
        .split('$')
        .skip(1)
        .step_by(2)
        .all(|m| super::tex::check(m).is_ok());
    if c.prose && !super::row::prose_is_formula(&c.statement) && !formulas_safe {
        format!("``{}''", escape(&literal(&c.statement)))
    } else if c.prose && !super::row::prose_is_formula(&c.statement) {
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
        format!("\\ccfit{{{}}}", escape(&math(&stacked(&c.statement))))
    }
}

/// A printed formula stacked to be narrow: one line per part (parts separated by
/// `\quad` outside any group), each chain broken before its `=` signs and aligned on
/// them. Only where the split is at brace depth 0 and outside `\left … \right`.
fn stacked(latex: &str) -> String {
    let mut lines: Vec<Vec<String>> = vec![vec![String::new()]];
    let (mut depth, mut delims) = (0i32, 0i32);
    let bytes = latex.as_bytes();
    let mut k = 0;
    while k < latex.len() {
        let rest = &latex[k..];
        let top = depth == 0 && delims == 0;
        if rest.starts_with("\\left") || rest.starts_with("\\begin") {
            delims += 1;
        } else if rest.starts_with("\\right") || rest.starts_with("\\end") {
            delims -= 1;
        }
        if top
            && rest.starts_with("\\quad")
            && !rest[5..].starts_with(|c: char| c.is_ascii_alphabetic())
        {
            lines.push(vec![String::new()]);
            k += 5;
            continue;
        }
        // An implication starts a new line, the arrow first.
        let arrow = ["\\Rightarrow", "\\implies", "\\Leftrightarrow", "\\iff"]
            .into_iter()
            .find(|a| {
                rest.starts_with(a)
                    && !rest[a.len()..].starts_with(|c: char| c.is_ascii_alphabetic())
            });
        if let (true, Some(a)) = (top, arrow) {
            lines.push(vec![a.to_owned()]);
            k += a.len();
            continue;
        }
        let c = rest.chars().next().unwrap_or(' ');
        match c {
            // Brackets group as braces do: an `=` inside a condition (τ = 0, …) is no
            // step of the chain.
            '{' | '(' | '[' => depth += 1,
            '}' | ')' | ']' => depth -= 1,
            '\\' if bytes.get(k + 1).is_some_and(|b| !b.is_ascii_alphabetic()) => {
                // An escaped character (`\{`, `\,`) is copied whole.
                let line = lines.last_mut().expect("one line");
                let end = k + 1 + rest[1..].chars().next().map_or(0, char::len_utf8);
                line.last_mut()
                    .expect("one member")
                    .push_str(&latex[k..end]);
                k = end;
                continue;
            }
            '=' if top => {
                lines.last_mut().expect("one line").push(String::new());
                k += 1;
                continue;
            }
            _ => {}
        }
        lines
            .last_mut()
            .expect("one line")
            .last_mut()
            .expect("one member")
            .push(c);
        k += c.len_utf8();
    }
    let rows: Vec<String> = lines
        .iter()
        .filter(|l| l.iter().any(|m| !m.trim().is_empty()))
        .flat_map(|l| {
            let mut l = l.iter().map(|m| m.trim().trim_end_matches(',').trim());
            let first = l.next().unwrap_or_default().to_owned();
            let rest: Vec<String> = l.map(|m| format!("&= {m}")).collect();
            match rest.split_first() {
                None => vec![format!("&{first}")],
                Some((r1, more)) => std::iter::once(format!("{first} {r1}"))
                    .chain(more.iter().cloned())
                    .collect(),
            }
        })
        .collect();
    if rows.len() <= 1 || depth != 0 || delims != 0 {
        return latex.to_owned();
    }
    // Top-aligned, so that its first line sits on the row's first line.
    format!(
        "\\begin{{aligned}}[t]{}\\end{{aligned}}",
        rows.join(" \\\\ ")
    )
}

/// What a fragment needs: its packages, and `\ccfit`, which scales a formula down to
/// the column when it is wider (never up).
const NEEDS: &str = "% Needs \\usepackage{longtable,array,amsmath,amssymb,graphicx}.\n\\providecommand{\\ccfit}[1]{\\resizebox{\\ifdim\\width>\\linewidth\\linewidth\\else\\width\\fi}{!}{#1}}\n";

const PREAMBLE: &str = "\\documentclass[10pt]{article}\n\\usepackage{longtable,array,amsmath,amssymb,graphicx}\n\\begin{document}\n";

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

/// The verdict cell: `fails` framed and bold, so that it stands out in print without
/// colour; the strength; a failure's origin.
fn verdict_cell(r: &Decided<'_>) -> String {
    let v = r.outcome.verdict();
    let mut cell = match v {
        crate::derivation::Verdict::Fails => "\\fbox{\\textbf{fails}}".to_owned(),
        crate::derivation::Verdict::Conditional => "\\textbf{conditional}".to_owned(),
        _ => escape(v.as_str()),
    };
    let _ = write!(
        cell,
        " ({})",
        match r.outcome.strength() {
            crate::decide::Strength::Proof => "proof",
            crate::decide::Strength::Sampled => "sampled",
        }
    );
    match &r.attribution {
        Some(a) if a.is_root() => cell.push_str("; root error"),
        Some(a) if !a.inherited_from().is_empty() => {
            let _ = write!(
                cell,
                "; inherited from {}",
                escape(&a.inherited_from().join(", "))
            );
        }
        Some(_) => cell.push_str("; origin undetermined"),
        None => {}
    }
    if !r.verdict_as_expected() {
        let _ = write!(cell, " \\textbf{{(declared {})}}", r.claim.expect);
    }
    cell
}

/// The table's short evidence: how the claim was decided, in a few words; the full
/// evidence is in the table keyed by claim that follows.
fn short_evidence(r: &Decided<'_>) -> String {
    use crate::derivation::Verdict;
    let o = &r.outcome;
    let mut s = match (o.verdict(), &o.numeric) {
        (Verdict::Holds, Some(n)) => format!("{} samples, seed {}", n.samples, n.seed),
        (Verdict::Holds, None) => format!(
            "{} ({} check{})",
            o.method.as_str(),
            o.checks,
            if o.checks == 1 { "" } else { "s" }
        ),
        (Verdict::Fails, _) => "a counterexample".to_owned(),
        (Verdict::Conditional, Some(n)) => format!(
            "holds with {}; a counterexample outside",
            n.domain.as_deref().unwrap_or("the stated domain")
        ),
        (Verdict::Conditional, None) => {
            "holds on the stated domain; a counterexample outside".to_owned()
        }
        (Verdict::Undecided, _) => "undecided: see the reason".to_owned(),
    };
    if let Some(c) = &r.correction {
        let _ = write!(s, "; correction {}", c.verdict_text());
    }
    escape(&s)
}

/// The rows in the order of their sections (3.1 before 3.10, numbered sections before
/// appendices), file order kept within a section.
fn in_section_order<'r, 'd>(rows: &[&'r Decided<'d>]) -> Vec<&'r Decided<'d>> {
    let key = |section: &str| -> Vec<(u8, u64, String)> {
        section
            .split('.')
            .map(|part| match part.parse::<u64>() {
                Ok(n) => (0, n, String::new()),
                Err(_) => (1, 0, part.to_owned()),
            })
            .collect()
    };
    let mut out = rows.to_vec();
    out.sort_by_key(|r| key(&r.claim.section));
    out
}

/// The derivation table as a longtable that fits a portrait page (statements scaled to
/// their column when wider), followed by the full evidence in a second table keyed by
/// claim.
pub fn render(rows: &[&Decided<'_>], standalone: bool, paper: &str) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "% Derivation table generated by cosserat-check.");
    out.push_str(NEEDS);
    out.push_str("{\\footnotesize\n");
    let _ = writeln!(
        out,
        "\\begin{{longtable}}{{@{{}}>{{\\raggedright}}p{{0.15\\linewidth}}>{{\\raggedright}}p{{0.40\\linewidth}}>{{\\raggedright}}p{{0.15\\linewidth}}>{{\\raggedright\\arraybackslash}}p{{0.18\\linewidth}}@{{}}}}"
    );
    let _ = writeln!(
        out,
        "\\caption{{Derivation table: each claim as printed, its verdict and how it was \
         decided.}}\\label{{tab:derivation}}\\\\"
    );
    // The caption on the first page only; the column heads on every page.
    let head = "\\hline\nclaim (\\S) & statement (as printed) & verdict & decided by \\\\\n\\hline";
    let _ = writeln!(out, "{head}\n\\endfirsthead\n{head}\n\\endhead");
    let rows = &in_section_order(rows);
    for r in rows {
        let c = r.claim;
        let _ = writeln!(
            out,
            "{} (\\S{{}}{}) & {} & {} & {} \\\\[3pt]",
            escape(&c.id),
            escape(&c.section),
            statement(c),
            verdict_cell(r),
            short_evidence(r)
        );
    }
    let _ = writeln!(out, "\\hline\n\\end{{longtable}}");
    let summary = Summary::of(rows);
    let _ = writeln!(out, "{}", escape(&summary.sentence(rows.len())));
    let origin = summary.origin_sentence();
    if !origin.is_empty() {
        let _ = writeln!(out, "{}", escape(&origin));
    }
    let _ = writeln!(
        out,
        "\n\\medskip\\noindent The evidence in full, by claim:\n"
    );
    let _ = writeln!(
        out,
        "\\begin{{longtable}}{{@{{}}>{{\\raggedright}}p{{0.17\\linewidth}}>{{\\raggedright\\arraybackslash}}p{{0.78\\linewidth}}@{{}}}}"
    );
    let _ = writeln!(
        out,
        "\\caption{{The evidence for each claim.}}\\label{{tab:evidence}}\\\\"
    );
    let head = "\\hline\nclaim & evidence \\\\\n\\hline";
    let _ = writeln!(out, "{head}\n\\endfirsthead\n{head}\n\\endhead");
    for r in rows {
        let _ = writeln!(
            out,
            "{} & {} \\\\",
            escape(&r.claim.id),
            escape(&full_evidence(
                r,
                (&|s| format!("{FIT}{}{FIT_END}", math(s)), &math),
                &authored
            ))
        );
    }
    let _ = writeln!(out, "\\hline\n\\end{{longtable}}\n}}");
    wrap(out, standalone, "Derivation table", paper)
}

/// The errata as a list: each root error, then the failures inherited from it.
pub fn errata(rows: &[&Decided<'_>], standalone: bool, paper: &str) -> String {
    let mut out = String::from("% Errata generated by cosserat-check.\n");
    out.push_str(NEEDS);
    if rows.is_empty() {
        out.push_str("Every printed statement checked holds.\n");
        return wrap(out, standalone, "Errata", paper);
    }
    let origin = Summary::of(rows).origin_sentence();
    if !origin.is_empty() {
        let _ = writeln!(out, "{}\n", escape(&origin));
    }
    // Long sums in the evidence break only at their top-level signs: let lines stretch.
    out.push_str("{\\sloppy\n\\begin{itemize}\n");
    for (root, inherited) in super::graph::grouped(rows) {
        erratum(&mut out, root);
        if !inherited.is_empty() {
            out.push_str("\\begin{itemize}\n");
            for r in inherited {
                erratum(&mut out, r);
            }
            out.push_str("\\end{itemize}\n");
        }
    }
    out.push_str("\\end{itemize}\n}\n");
    wrap(out, standalone, "Errata", paper)
}

fn erratum(out: &mut String, r: &Decided<'_>) {
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
        "\\item Verdict: {} ({})",
        verdict_cell(r),
        escape(r.outcome.method.as_str())
    );
    if let Some(reason) = &c.reason {
        let _ = writeln!(out, "\\item Why: {}", escape(&authored(reason)));
    }
    if let Some(a) = &r.attribution {
        let _ = writeln!(
            out,
            "\\item Origin: {}",
            escape(&super::graph::attribution(a))
        );
    }
    let printed = super::row::printed_point(r, &math)
        .map(|p| format!(" ({p})"))
        .unwrap_or_default();
    let _ = writeln!(
        out,
        "\\item Evidence: {}",
        escape(&format!("{}{printed}", evidence(&r.outcome)))
    );
    if let (Some(k), Some(o)) = (&c.correction, &r.correction) {
        let _ = writeln!(
            out,
            "\\item Correction:\\par\\ccfit{{{}}}\\par {} ({}). {}",
            escape(&math(&k.statement)),
            escape(&o.verdict_text()),
            escape(o.method.as_str()),
            escape(&authored(&k.reason))
        );
    }
    let _ = writeln!(out, "\\end{{itemize}}");
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escaping_is_ascii_and_keeps_math() {
        let s = escape(&format!("a_b 50% & {}x^2{} ≤ `n_k` σ", OPEN, CLOSE));
        assert_eq!(s, "a\\_b 50\\% \\& $x^2$ $\\le$ $n_{k}$ $\\sigma$");
        assert!(s.is_ascii());
        assert_eq!(escape("☃"), "\\textbf{?}");
    }

    #[test]
    fn a_chain_is_stacked_on_its_equals_signs_and_parts_on_lines() {
        assert_eq!(
            stacked("a = \\frac{b}{c=d} = e, \\quad f = g"),
            "\\begin{aligned}[t]a &= \\frac{b}{c=d} \\\\ &= e \\\\ f &= g\\end{aligned}"
        );
        assert_eq!(
            stacked("\\left(a = b\\right) = c"),
            "\\left(a = b\\right) = c"
        );
        assert_eq!(stacked("a \\le b"), "a \\le b");
        // An `=` inside a condition is no step; an implication starts a line.
        assert_eq!(
            stacked("h = 1 \\quad (\\tau = 0, h^C = 1/2)"),
            "\\begin{aligned}[t]h &= 1 \\\\ &(\\tau = 0, h^C = 1/2)\\end{aligned}"
        );
        assert_eq!(
            stacked("a = b \\Rightarrow c = d"),
            "\\begin{aligned}[t]a &= b \\\\ \\Rightarrow c &= d\\end{aligned}"
        );
    }

    #[test]
    fn words_quotes_and_scaled_formulas_read_as_text() {
        assert!(expression("x + ... (82 terms in all)").contains("\\text{(82 terms in all)}"));
        assert_eq!(escape("the \"static\" model"), "the ``static'' model");
        assert_eq!(escape("(\"static\")"), "(\\allowbreak{}``static'')");
        let fitted = escape(&format!(
            "Correction {FIT}{OPEN}x = 1{CLOSE}{FIT_END}: holds"
        ));
        assert_eq!(
            fitted,
            "Correction \\newline\\ccfit{$x = 1$}\\newline : holds"
        );
        // A file's text cannot smuggle the markers in.
        assert_eq!(literal(&format!("{FIT}x{FIT_END}")), "x");
    }

    #[test]
    fn expressions_are_typeset_as_mathematics() {
        assert_eq!(
            expression("-n_2*R_g*Dw_31 + sigma_ki n_k^2*V^-1"),
            "$-n_{2}\\,R_{g}\\,\\mathrm{Dw}_{31} + \\sigma_{ki}\\,n_{k}^{2}\\,V^{-1}$"
        );
        assert_eq!(
            expression("eps_ijk … mut_ij"),
            "$\\varepsilon_{ijk} \\dots \\mathrm{mut}_{ij}$"
        );
    }
}
