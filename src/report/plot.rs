//! Figures as CSV and as SVG fit for a single-column figure (8.5 cm wide): every value
//! inside the axes (the y range, or a log axis, comes from the data, so nothing is
//! clipped), a colour-blind-safe palette (Okabe–Ito) with a distinct dash pattern per
//! curve, labels set as mathematics, coordinates to 1/100 of a unit. Written by hand,
//! so the same figure gives the same bytes.

use crate::derivation::Figure;
use std::fmt::Write;

/// One curve's values on the figure's grid (`None`: undefined there).
pub type Column = Vec<Option<f64>>;

/// Okabe & Ito's palette, black first.
const COLOURS: [&str; 7] = [
    "#000000", "#E69F00", "#0072B2", "#009E73", "#D55E00", "#56B4E9", "#CC79A7",
];
/// Dash patterns in user units, solid first.
const DASHES: [&str; 7] = ["", "6 3", "2 2", "8 3 2 3", "1 3", "10 4", "4 2 1 2"];

/// A number as the CSV and the tick labels show it: 12 significant digits, no trailing
/// zeros (a grid value 0.05 prints as written).
fn decimal(x: f64) -> String {
    crate::digits::significant(x, 12)
}

/// A text cell: neutralised against formulas, quoted when it holds a separator, a
/// quote or a line end.
fn csv_cell(s: &str) -> String {
    let s = super::csv::neutralised(s);
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.into_owned()
    }
}

/// A label as plain text: `$…$` marks and TeX commands dropped, Greek letters kept.
pub fn plain(label: &str) -> String {
    let mut out = String::new();
    let mut rest = label;
    while let Some(k) = rest.find(['$', '\\']) {
        out.push_str(&rest[..k]);
        let (c, tail) = rest[k..].split_at(1);
        rest = tail;
        if c == "\\" {
            let end = rest
                .find(|c: char| !c.is_ascii_alphabetic())
                .unwrap_or(rest.len());
            match greek(&rest[..end]) {
                Some(g) => out.push(g),
                None => out.push_str(&rest[..end]),
            }
            rest = &rest[end..];
        }
    }
    out.push_str(rest);
    out
}

/// The table: the parameter, then one column per curve (its label as plain text),
/// empty cells where a curve is undefined.
pub fn csv(figure: &Figure, columns: &[Column]) -> String {
    let mut out = csv_cell(&figure.x.name);
    for c in &figure.curves {
        out.push(',');
        out.push_str(&csv_cell(&plain(&c.label)));
    }
    out.push('\n');
    for (k, x) in figure.x.values.iter().enumerate() {
        out.push_str(&decimal(x.to_f64()));
        for col in columns {
            out.push(',');
            out.push_str(&col[k].map(decimal).unwrap_or_default());
        }
        out.push('\n');
    }
    out
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// A Greek letter named by its LaTeX command.
fn greek(name: &str) -> Option<char> {
    let table = [
        ("alpha", 'α'),
        ("beta", 'β'),
        ("gamma", 'γ'),
        ("delta", 'δ'),
        ("epsilon", 'ε'),
        ("varepsilon", 'ε'),
        ("theta", 'θ'),
        ("kappa", 'κ'),
        ("lambda", 'λ'),
        ("mu", 'μ'),
        ("nu", 'ν'),
        ("xi", 'ξ'),
        ("pi", 'π'),
        ("rho", 'ρ'),
        ("sigma", 'σ'),
        ("tau", 'τ'),
        ("phi", 'φ'),
        ("psi", 'ψ'),
        ("omega", 'ω'),
        ("Gamma", 'Γ'),
        ("Delta", 'Δ'),
        ("Sigma", 'Σ'),
    ];
    table.iter().find(|(n, _)| *n == name).map(|(_, c)| *c)
}

/// TeX-like mathematics as SVG text: single letters italic, `_x`/`_{…}` and `^x`/`^{…}`
/// as sub- and superscripts, `\nu` and the other Greek letters, everything else upright.
pub fn math(tex: &str) -> String {
    let mut out = String::new();
    let chars: Vec<char> = tex.chars().collect();
    let mut i = 0;
    // The text of a script: one character or a braced group.
    let script = |i: &mut usize| -> String {
        if chars.get(*i) == Some(&'{') {
            let start = *i + 1;
            let mut depth = 0;
            while *i < chars.len() {
                match chars[*i] {
                    '{' => depth += 1,
                    '}' => {
                        depth -= 1;
                        if depth == 0 {
                            break;
                        }
                    }
                    _ => {}
                }
                *i += 1;
            }
            let body: String = chars[start..(*i).min(chars.len())].iter().collect();
            *i += 1;
            body
        } else if chars.get(*i) == Some(&'\\') {
            let start = *i;
            *i += 1;
            while chars.get(*i).is_some_and(char::is_ascii_alphabetic) {
                *i += 1;
            }
            chars[start..*i].iter().collect()
        } else {
            let c = chars.get(*i).map(char::to_string).unwrap_or_default();
            *i += 1;
            c
        }
    };
    while i < chars.len() {
        let c = chars[i];
        match c {
            '_' | '^' => {
                i += 1;
                let body = script(&mut i);
                let shift = if c == '_' { "sub" } else { "super" };
                let _ = write!(
                    out,
                    "<tspan baseline-shift=\"{shift}\" font-size=\"75%\">{}</tspan>",
                    math(&body)
                );
            }
            '\\' => {
                let start = i + 1;
                i += 1;
                while chars.get(i).is_some_and(char::is_ascii_alphabetic) {
                    i += 1;
                }
                let name: String = chars[start..i].iter().collect();
                match greek(&name) {
                    Some(g) => {
                        let _ = write!(out, "<tspan font-style=\"italic\">{g}</tspan>");
                    }
                    None => out.push_str(&escape(&name)),
                }
            }
            c if c.is_alphabetic() => {
                let start = i;
                while chars.get(i).is_some_and(|c| c.is_alphabetic()) {
                    i += 1;
                }
                let word: String = chars[start..i].iter().collect();
                if word.chars().count() == 1 {
                    let _ = write!(
                        out,
                        "<tspan font-style=\"italic\">{}</tspan>",
                        escape(&word)
                    );
                } else {
                    out.push_str(&escape(&word));
                }
            }
            '-' => {
                out.push('−');
                i += 1;
            }
            c => {
                out.push_str(&escape(&c.to_string()));
                i += 1;
            }
        }
    }
    out
}

/// Text with `$…$` segments set as mathematics.
fn rich(text: &str) -> String {
    text.split('$')
        .enumerate()
        .map(|(k, part)| if k % 2 == 1 { math(part) } else { escape(part) })
        .collect()
}

/// About five round ticks (1, 2 or 5 × 10^k apart) covering [lo, hi]; just the two
/// ends where no round step exists in f64 (a subnormal or an overflowing range).
fn ticks(lo: f64, hi: f64) -> Vec<f64> {
    // Halves first, so that a range near ±f64::MAX does not overflow.
    let raw = (hi / 2.0 - lo / 2.0) / 2.5;
    let magnitude = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * magnitude)
        .find(|s| *s >= raw)
        .unwrap_or(10.0 * magnitude);
    let (first, last) = ((lo / step).ceil(), (hi / step).floor());
    if !(step.is_normal() && first.is_finite() && last.is_finite()) || last - first > 20.0 {
        return if lo < hi { vec![lo, hi] } else { vec![lo] };
    }
    (first as i64..=last as i64)
        .map(|k| k as f64 * step)
        .collect()
}

/// The y axis: linear with round ends, or logarithmic when the data span more than a
/// factor of 30 and are all positive.
struct Axis {
    lo: f64,
    hi: f64,
    log: bool,
}

impl Axis {
    /// The axis of the finite `values` (a non-finite value is not drawn).
    fn of(values: &[f64]) -> Axis {
        let finite = values.iter().copied().filter(|v| v.is_finite());
        let min = finite.clone().fold(f64::INFINITY, f64::min);
        let max = finite.fold(f64::NEG_INFINITY, f64::max);
        if !min.is_finite() {
            return Axis {
                lo: 0.0,
                hi: 1.0,
                log: false,
            };
        }
        if min.is_normal() && min > 0.0 && max / min > 30.0 {
            return Axis {
                lo: 10f64.powf(min.log10().floor()),
                hi: 10f64.powf(max.log10().ceil()),
                log: true,
            };
        }
        let (mut lo, mut hi) = (min, max);
        if lo >= 0.0 && lo < 0.3 * hi {
            lo = 0.0;
        }
        if hi - lo < 1e-12 * hi.abs().max(1.0) {
            // A constant: a band around it, wide enough to be a band in f64.
            let pad = 0.5f64.max(hi.abs() / 20.0);
            lo = (lo - pad).max(f64::MIN);
            hi = (hi + pad).min(f64::MAX);
        }
        let t = ticks(lo, hi);
        let step = if t.len() > 1 { t[1] - t[0] } else { hi - lo };
        if !step.is_normal() || !(hi / step).is_finite() {
            return Axis { lo, hi, log: false };
        }
        // Round ends, unless rounding would leave f64.
        let (round_lo, round_hi) = ((lo / step).floor() * step, (hi / step).ceil() * step);
        Axis {
            lo: if round_lo.is_finite() { round_lo } else { lo },
            hi: if round_hi.is_finite() { round_hi } else { hi },
            log: false,
        }
    }

    /// Where `v` lies between the ends, 0..1.
    fn fraction(&self, v: f64) -> f64 {
        if self.log {
            (v.log10() - self.lo.log10()) / (self.hi.log10() - self.lo.log10())
        } else {
            (v / 2.0 - self.lo / 2.0) / (self.hi / 2.0 - self.lo / 2.0)
        }
    }

    fn ticks(&self) -> Vec<f64> {
        if self.log {
            let (a, b) = (
                self.lo.log10().round() as i32,
                self.hi.log10().round() as i32,
            );
            // At most about a dozen labelled decades.
            let every = usize::try_from((b - a) / 12 + 1).unwrap_or(1);
            (a..=b).step_by(every).map(|e| 10f64.powi(e)).collect()
        } else {
            ticks(self.lo, self.hi)
        }
    }
}

/// The figure as SVG, 85 mm wide (user units: 4 per mm); the legend below the axes.
pub fn svg(figure: &Figure, columns: &[Column]) -> String {
    let xs: Vec<f64> = figure.x.values.iter().map(|x| x.to_f64()).collect();
    let ys: Vec<f64> = columns.iter().flatten().flatten().copied().collect();
    let (x_lo, x_hi) = (xs[0], xs[xs.len() - 1]);
    let y = Axis::of(&ys);
    let (width, left, right, top, plot_h) = (340.0, 46.0, 10.0, 8.0, 170.0);
    let plot_w = width - left - right;
    let legend_top = top + plot_h + 40.0;
    let height = legend_top + 13.0 * figure.curves.len() as f64 + 4.0;
    let px = |x: f64| left + plot_w * (x - x_lo) / (x_hi - x_lo);
    let py = |v: f64| top + plot_h * (1.0 - y.fraction(v));
    let mut s = String::new();
    let _ = writeln!(
        s,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"85mm\" height=\"{:.2}mm\" viewBox=\"0 0 {width} {height:.2}\" font-family=\"serif\" font-size=\"10\">",
        height / 4.0
    );
    let _ = writeln!(s, "<title>{}</title>", escape(&figure.title));
    let _ = writeln!(s, "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>");
    // Axes, ticks and grid.
    let _ = writeln!(
        s,
        "<rect x=\"{left}\" y=\"{top}\" width=\"{plot_w}\" height=\"{plot_h}\" fill=\"none\" stroke=\"black\" stroke-width=\"0.6\"/>"
    );
    for t in ticks(x_lo, x_hi) {
        let x = px(t);
        let _ = writeln!(
            s,
            "<line x1=\"{x:.2}\" y1=\"{:.2}\" x2=\"{x:.2}\" y2=\"{:.2}\" stroke=\"black\" stroke-width=\"0.6\"/><text x=\"{x:.2}\" y=\"{:.2}\" text-anchor=\"middle\">{}</text>",
            top + plot_h,
            top + plot_h - 3.0,
            top + plot_h + 11.0,
            decimal(t)
        );
    }
    if y.log {
        // Unlabelled minor ticks at 2…9 × 10^k.
        for decade in y.ticks() {
            for m in 2..10 {
                let t = decade * f64::from(m);
                if t < y.hi {
                    let v = py(t);
                    let _ = writeln!(
                        s,
                        "<line x1=\"{left}\" y1=\"{v:.2}\" x2=\"{:.2}\" y2=\"{v:.2}\" stroke=\"black\" stroke-width=\"0.4\"/>",
                        left + 1.5
                    );
                }
            }
        }
    }
    for t in y.ticks() {
        let v = py(t);
        let label = if y.log {
            format!(
                "10<tspan baseline-shift=\"super\" font-size=\"75%\">{}</tspan>",
                t.log10().round()
            )
        } else {
            decimal(t)
        };
        let _ = writeln!(
            s,
            "<line x1=\"{left}\" y1=\"{v:.2}\" x2=\"{:.2}\" y2=\"{v:.2}\" stroke=\"black\" stroke-width=\"0.6\"/><text x=\"{:.2}\" y=\"{:.2}\" text-anchor=\"end\">{label}</text>",
            left + 3.0,
            left - 3.0,
            v + 3.5
        );
    }
    let _ = writeln!(
        s,
        "<text x=\"{:.2}\" y=\"{:.2}\" text-anchor=\"middle\">{}</text>",
        left + plot_w / 2.0,
        top + plot_h + 25.0,
        math(&figure.x_label)
    );
    let _ = writeln!(
        s,
        "<text transform=\"translate(11 {:.2}) rotate(-90)\" text-anchor=\"middle\">{}</text>",
        top + plot_h / 2.0,
        math(&figure.y_label)
    );
    // Curves, split where undefined; the legend names the points left out.
    for (k, (curve, col)) in figure.curves.iter().zip(columns).enumerate() {
        let (colour, dash) = (COLOURS[k % COLOURS.len()], DASHES[k % DASHES.len()]);
        let dash_attr = if dash.is_empty() {
            String::new()
        } else {
            format!(" stroke-dasharray=\"{dash}\"")
        };
        let mut runs: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
        for (x, v) in xs.iter().zip(col) {
            // A value off the axis (non-finite, or ≤ 0 on a log axis) breaks the curve.
            let point = v
                .map(|v| (px(*x), py(v)))
                .filter(|(a, b)| a.is_finite() && b.is_finite());
            match point {
                Some(p) => runs.last_mut().expect("one run").push(p),
                None if !runs.last().expect("one run").is_empty() => runs.push(Vec::new()),
                None => {}
            }
        }
        for run in runs.iter().filter(|r| !r.is_empty()) {
            let points: Vec<String> = run.iter().map(|(a, b)| format!("{a:.2},{b:.2}")).collect();
            let _ = writeln!(
                s,
                "<polyline points=\"{}\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"1.2\"{dash_attr}/>",
                points.join(" ")
            );
        }
        let missing = col.iter().filter(|v| v.is_none()).count();
        let note = if missing > 0 {
            format!(" (undefined at {missing} of {} points)", col.len())
        } else {
            String::new()
        };
        let ly = legend_top + 13.0 * k as f64;
        let _ = writeln!(
            s,
            "<line x1=\"{left}\" y1=\"{ly:.2}\" x2=\"{:.2}\" y2=\"{ly:.2}\" stroke=\"{colour}\" stroke-width=\"1.2\"{dash_attr}/><text x=\"{:.2}\" y=\"{:.2}\">{}{}</text>",
            left + 24.0,
            left + 30.0,
            ly + 3.5,
            rich(&curve.label),
            escape(&note)
        );
    }
    s.push_str("</svg>\n");
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Data at the edges of f64 (subnormal, near ±f64::MAX, constant, non-finite) give
    /// an axis with a few finite ticks on which every finite value has a finite place.
    #[test]
    fn axes_stay_finite_and_small_at_the_edges_of_f64() {
        let sets: [&[f64]; 7] = [
            &[1e-320, 2e-320],
            &[1e-320, 1.0],
            &[-1.7e308, 1.7e308],
            &[-1.7e256; 3],
            &[f64::MAX, f64::MAX],
            &[f64::NAN, f64::INFINITY, 1.0, 2.0],
            &[1e-300, 1e300],
        ];
        for values in sets {
            let axis = Axis::of(values);
            let t = axis.ticks();
            assert!(
                !t.is_empty() && t.len() <= 25,
                "{values:?}: {} ticks",
                t.len()
            );
            assert!(t.iter().all(|x| x.is_finite()), "{values:?}: {t:?}");
            for v in values.iter().filter(|v| v.is_finite()) {
                assert!(axis.fraction(*v).is_finite(), "{values:?}: {v}");
            }
        }
    }
}
