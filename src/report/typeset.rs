//! The other direction of the transcription check: a side or a definition, written in
//! the index-notation language, typeset as LaTeX, so that `explain` and the reports can
//! show the checked statement next to the printed one for a reader to compare by eye,
//! including where the machine cannot read the printed one.

use crate::lang::parser::{ExprKind, Func, Wrt};
use crate::lang::{parse_expr, Expr};

/// Names the language spells out that LaTeX writes as letters.
const GREEK: &[(&str, &str)] = &[
    ("alpha", "\\alpha"),
    ("beta", "\\beta"),
    ("gamma", "\\gamma"),
    ("Gamma", "\\Gamma"),
    ("delta", "\\delta"),
    ("Delta", "\\Delta"),
    ("eps", "\\varepsilon"),
    ("epsilon", "\\epsilon"),
    ("zeta", "\\zeta"),
    ("eta", "\\eta"),
    ("theta", "\\theta"),
    ("kappa", "\\kappa"),
    ("lambda", "\\lambda"),
    ("mu", "\\mu"),
    ("nu", "\\nu"),
    ("xi", "\\xi"),
    ("pi", "\\pi"),
    ("rho", "\\rho"),
    ("sigma", "\\sigma"),
    ("tau", "\\tau"),
    ("phi", "\\phi"),
    ("varphi", "\\varphi"),
    ("chi", "\\chi"),
    ("psi", "\\psi"),
    ("omega", "\\omega"),
    ("Omega", "\\Omega"),
    ("Phi", "\\Phi"),
    ("Psi", "\\Psi"),
    ("ell", "\\ell"),
];

/// A language expression as LaTeX, or the text itself in `\texttt` when it does not
/// parse (a side that is ill-formed is still shown).
pub fn latex(text: &str) -> String {
    match parse_expr(text) {
        Ok(e) => expr(&e, 0),
        Err(_) => format!("\\texttt{{{}}}", text.replace('_', "\\_")),
    }
}

/// A chain of sides, `a = b = c`.
pub fn chain(sides: &[String]) -> String {
    sides
        .iter()
        .map(|s| latex(s))
        .collect::<Vec<_>>()
        .join(" = ")
}

/// What a check states, typeset: its chains as written, or for a gradient claim each
/// closed form, ∂F/∂x = G.
pub fn checked(
    check: &crate::derivation::Check,
    transcript: &crate::derivation::Transcript,
) -> Vec<String> {
    let mut out: Vec<String> = transcript.written.iter().map(|c| chain(c)).collect();
    if let crate::derivation::Strategy::Gradient {
        function,
        closed_forms,
        ..
    } = &check.strategy
    {
        let f = latex(&function.text);
        for (symbol, closed) in closed_forms {
            let free: String = closed.node.free_letters().into_iter().collect();
            let by = if free.is_empty() {
                name(symbol)
            } else {
                format!("{}_{{{free}}}", name(symbol))
            };
            out.push(format!(
                "\\frac{{\\partial \\left( {f} \\right)}}{{\\partial {by}}} = {}",
                latex(&closed.text)
            ));
        }
    }
    out
}

/// A name: Greek letters by their commands, one letter as is, longer names upright.
fn name(base: &str) -> String {
    if let Some((_, g)) = GREEK.iter().find(|(n, _)| *n == base) {
        return (*g).to_owned();
    }
    if base.chars().count() == 1 {
        return base.to_owned();
    }
    format!("\\mathrm{{{}}}", base.replace('_', "\\_"))
}

/// Precedence: 0 sum, 1 product, 2 power, 3 atom.
fn expr(e: &Expr, outer: u8) -> String {
    let (text, prec) = match &e.kind {
        ExprKind::Number(q) => {
            let t = q.to_string();
            match t.split_once('/') {
                Some((a, b)) => (format!("\\frac{{{a}}}{{{b}}}"), 3),
                None => (t, 3),
            }
        }
        ExprKind::Name {
            full,
            base,
            indices,
        } => {
            if indices.is_empty() {
                (name(full), 3)
            } else {
                let sub: String = indices.iter().map(|t| t.ch).collect();
                (format!("{}_{{{sub}}}", name(base)), 3)
            }
        }
        ExprKind::Neg(a) => (format!("-{}", expr(a, 1)), 0),
        ExprKind::Add(a, b) => (format!("{} + {}", expr(a, 0), expr(b, 0)), 0),
        ExprKind::Sub(a, b) => (format!("{} - {}", expr(a, 0), expr(b, 1)), 0),
        ExprKind::Mul(a, b) => (format!("{} \\, {}", expr(a, 1), expr(b, 1)), 1),
        ExprKind::Div(a, b) => (format!("\\frac{{{}}}{{{}}}", expr(a, 0), expr(b, 0)), 3),
        ExprKind::Pow(a, n) => (format!("{{{}}}^{{{n}}}", expr(a, 3)), 2),
        ExprKind::Call(f, a) => {
            let inner = expr(a, 0);
            let t = match f {
                Func::Sqrt => format!("\\sqrt{{{inner}}}"),
                Func::Avg => format!("\\langle {inner} \\rangle"),
                Func::Abs => format!("\\left| {inner} \\right|"),
                Func::MaxN => format!("\\max_{{n}} \\left( {inner} \\right)"),
                Func::Log => format!("\\ln \\left( {inner} \\right)"),
                Func::Atan => format!("\\arctan \\left( {inner} \\right)"),
                Func::Asin => format!("\\arcsin \\left( {inner} \\right)"),
                Func::Acos => format!("\\arccos \\left( {inner} \\right)"),
                other => format!("\\{} \\left( {inner} \\right)", other.name()),
            };
            (t, 3)
        }
        ExprKind::Call2(f, a, b) => {
            let t = match f.name() {
                "^" => format!("{{{}}}^{{{}}}", expr(a, 3), expr(b, 0)),
                n => format!("\\{n}\\left({}, {}\\right)", expr(a, 0), expr(b, 0)),
            };
            (t, 3)
        }
        ExprKind::Deriv { inner, indices, .. } => {
            let sub: String = indices.iter().map(|t| t.ch).collect();
            (format!("{{{}}}_{{,{sub}}}", expr(inner, 3)), 3)
        }
        ExprKind::Wrt { op, body, symbol } => {
            let d = match op {
                Wrt::Grad => "\\partial",
                Wrt::Variation => "\\delta",
            };
            (
                format!("\\frac{{{d} {}}}{{{d} {}}}", expr(body, 1), expr(symbol, 3)),
                3,
            )
        }
        ExprKind::Matrix(rows) => {
            let rows: Vec<String> = rows
                .iter()
                .map(|r| r.iter().map(|c| expr(c, 0)).collect::<Vec<_>>().join(" & "))
                .collect();
            (
                format!(
                    "\\begin{{pmatrix}} {} \\end{{pmatrix}}",
                    rows.join(" \\\\ ")
                ),
                3,
            )
        }
        ExprKind::Entry(a, at) => {
            let at: Vec<String> = at.iter().map(|(k, _)| k.to_string()).collect();
            (format!("{{{}}}_{{[{}]}}", expr(a, 3), at.join(",")), 3)
        }
        ExprKind::MatCall(f, args) => {
            let args: Vec<String> = args.iter().map(|a| expr(a, 0)).collect();
            (
                format!(
                    "\\operatorname{{{}}}\\left({}\\right)",
                    f.name(),
                    args.join(", ")
                ),
                3,
            )
        }
    };
    if prec < outer {
        format!("\\left( {text} \\right)")
    } else {
        text
    }
}
