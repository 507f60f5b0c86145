//! Figures as CSV and as SVG fit for a single-column figure (8.5 cm wide): every value
//! inside the axes (the y range, or a log axis, comes from the data, so nothing is
//! clipped), round ends and minor ticks on both axes, a colour-blind-safe palette
//! (Okabe–Ito) with a distinct dash pattern per curve, each curve's interior minimum
//! marked, the legend in a free corner, labels set as mathematics, coordinates to 1/100
//! of a unit.
//!
//! Written by hand rather than through a plotting crate: the labels are mathematics
//! (italic letters, sub- and superscripts as `tspan`s, `d_B/R_g`), which the text of
//! plotters' SVG backend cannot set, and every byte of the file is ours to escape. The
//! same figure gives the same bytes.

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
            match crate::lang::latex::greek_letter(&rest[..end]) {
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

/// TeX-like mathematics as SVG text: single letters italic, `_x`/`_{…}` and `^x`/`^{…}`
/// as sub- and superscripts, `\nu` and the other Greek letters, everything else upright.
pub fn math(tex: &str) -> String {
    math_at(tex, 0)
}

/// Scripts nested deeper than this are set as plain text (each level of `tspan` would
/// repeat the text inside it).
const SCRIPT_DEPTH: usize = 4;

fn math_at(tex: &str, depth: usize) -> String {
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
                if depth >= SCRIPT_DEPTH {
                    out.push_str(&escape(&body));
                    continue;
                }
                let _ = write!(
                    out,
                    "<tspan baseline-shift=\"{shift}\" font-size=\"75%\">{}</tspan>",
                    math_at(&body, depth + 1)
                );
            }
            '\\' => {
                let start = i + 1;
                i += 1;
                while chars.get(i).is_some_and(char::is_ascii_alphabetic) {
                    i += 1;
                }
                let name: String = chars[start..i].iter().collect();
                match crate::lang::latex::greek_letter(&name) {
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

/// About five round ticks (1, 2 or 5 × 10^k apart) covering [lo, hi], and their step;
/// just the two ends where no round step exists in f64 (a subnormal or an overflowing
/// range).
fn ticks(lo: f64, hi: f64) -> (Vec<f64>, Option<f64>) {
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
        return (if lo < hi { vec![lo, hi] } else { vec![lo] }, None);
    }
    let t = (first as i64..=last as i64)
        .map(|k| k as f64 * step)
        .collect();
    (t, Some(step))
}

/// Unlabelled ticks between the labelled ones: fifths of a step of 1 or 5 × 10^k,
/// quarters of a step of 2 × 10^k.
fn minor_ticks(lo: f64, hi: f64, step: f64) -> Vec<f64> {
    let mantissa = step / 10f64.powf(step.log10().floor());
    let parts = if (mantissa - 2.0).abs() < 1e-9 {
        4.0
    } else {
        5.0
    };
    let minor = step / parts;
    let (first, last) = ((lo / minor).ceil(), (hi / minor).floor());
    if !(minor.is_normal() && first.is_finite() && last.is_finite()) || last - first > 200.0 {
        return Vec::new();
    }
    (first as i64..=last as i64)
        .map(|k| k as f64 * minor)
        .filter(|t| ((t / step).round() * step - t).abs() > 1e-9 * step)
        .collect()
}

/// How the y axis is scaled: chosen from the data, or as asked.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Scale {
    /// Logarithmic when the data span more than a factor of 30 and are all positive.
    #[default]
    Auto,
    Linear,
}

/// An axis: linear with round ends, or logarithmic with ends at 1, 2 or 5 × 10^k.
struct Axis {
    lo: f64,
    hi: f64,
    log: bool,
}

/// The largest of 1, 2, 5 × 10^k at most `v` (`up`: the smallest at least `v`).
fn one_two_five(v: f64, up: bool) -> f64 {
    let decade = 10f64.powf(v.log10().floor());
    let steps = [1.0, 2.0, 5.0, 10.0].map(|m| m * decade);
    if up {
        steps
            .into_iter()
            .find(|s| *s >= v * (1.0 - 1e-12))
            .unwrap_or(v)
    } else {
        steps
            .into_iter()
            .rev()
            .find(|s| *s <= v * (1.0 + 1e-12))
            .unwrap_or(v)
    }
}

impl Axis {
    /// The axis of the finite `values` (a non-finite value is not drawn).
    fn of(values: &[f64], scale: Scale) -> Axis {
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
        if scale == Scale::Auto && min.is_normal() && min > 0.0 && max / min > 30.0 {
            let (lo, hi) = (one_two_five(min, false), one_two_five(max, true));
            if lo.is_normal() && hi.is_normal() && lo < hi {
                return Axis { lo, hi, log: true };
            }
        }
        Axis::linear(min, max)
    }

    fn linear(min: f64, max: f64) -> Axis {
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
        let Some(step) = ticks(lo, hi).1 else {
            return Axis { lo, hi, log: false };
        };
        if !(hi / step).is_finite() {
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

    /// The labelled ticks with their labels (SVG text), and the unlabelled ones.
    fn ticks(&self) -> (Vec<(f64, String)>, Vec<f64>) {
        if !self.log {
            let (major, step) = ticks(self.lo, self.hi);
            let minor = step.map_or_else(Vec::new, |s| minor_ticks(self.lo, self.hi, s));
            return (major.into_iter().map(|t| (t, decimal(t))).collect(), minor);
        }
        let (a, b) = (
            self.lo.log10().floor() as i32,
            self.hi.log10().ceil() as i32,
        );
        let inside = |t: &f64| *t >= self.lo * (1.0 - 1e-12) && *t <= self.hi * (1.0 + 1e-12);
        if b - a <= 3 {
            // A few decades: 1, 2 and 5 × 10^k labelled as numbers, the rest unlabelled.
            let mut major = Vec::new();
            let mut minor = Vec::new();
            for e in a..=b {
                for m in 1..10 {
                    let t = f64::from(m) * 10f64.powi(e);
                    if !inside(&t) {
                        continue;
                    }
                    if [1, 2, 5].contains(&m) {
                        major.push((t, decimal(t)));
                    } else {
                        minor.push(t);
                    }
                }
            }
            return (major, minor);
        }
        // At most about a dozen labelled decades, 2…9 × 10^k unlabelled between them.
        let every = usize::try_from((b - a) / 12 + 1).unwrap_or(1);
        let major = (a..=b)
            .step_by(every)
            .map(|e| 10f64.powi(e))
            .filter(inside)
            .map(|t| {
                let label = format!(
                    "10<tspan baseline-shift=\"super\" font-size=\"75%\">{}</tspan>",
                    t.log10().round()
                );
                (t, label)
            })
            .collect();
        let minor = if every == 1 {
            (a..b)
                .flat_map(|e| (2..10).map(move |m| f64::from(m) * 10f64.powi(e)))
                .filter(inside)
                .collect()
        } else {
            Vec::new()
        };
        (major, minor)
    }
}

/// The lowest value of a curve and where, when it lies strictly inside the range (a
/// minimum the figure is about, such as that of (54)), not at an end.
fn interior_minimum(xs: &[f64], col: &Column) -> Option<(f64, f64)> {
    let (k, v) = col
        .iter()
        .enumerate()
        .filter_map(|(k, v)| v.filter(|v| v.is_finite()).map(|v| (k, v)))
        .min_by(|a, b| a.1.total_cmp(&b.1))?;
    let defined = |j: usize| col.get(j).copied().flatten().is_some();
    (k > 0 && k + 1 < col.len() && defined(k - 1) && defined(k + 1)).then(|| (xs[k], v))
}

/// A length of SVG text in user units, roughly (a serif font at `size`).
fn text_width(label: &str, size: f64) -> f64 {
    plain(label).chars().count() as f64 * size * 0.5
}

/// The figure as SVG, 85 mm wide (user units: 4 per mm): both axes with round ends
/// and minor ticks, each curve's interior minimum marked and given in the legend, the
/// legend inside the axes in a corner no curve crosses, or below them.
pub fn svg(figure: &Figure, columns: &[Column], scale: Scale) -> String {
    let xs: Vec<f64> = figure.x.values.iter().map(|x| x.to_f64()).collect();
    let ys: Vec<f64> = columns.iter().flatten().flatten().copied().collect();
    let x = Axis::linear(xs[0], xs[xs.len() - 1]);
    let y = Axis::of(&ys, scale);
    let (width, left, right, top, plot_h) = (340.0, 46.0, 10.0, 8.0, 170.0);
    let plot_w = width - left - right;
    let px = |v: f64| left + plot_w * x.fraction(v);
    let py = |v: f64| top + plot_h * (1.0 - y.fraction(v));
    // Each curve's runs of points (split where undefined or off the axis), its minimum.
    let runs: Vec<Vec<Vec<(f64, f64)>>> = columns
        .iter()
        .map(|col| {
            let mut runs: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
            for (xv, v) in xs.iter().zip(col) {
                let point = v
                    .map(|v| (px(*xv), py(v)))
                    .filter(|(a, b)| a.is_finite() && b.is_finite());
                match point {
                    Some(p) => runs.last_mut().expect("one run").push(p),
                    None if !runs.last().expect("one run").is_empty() => runs.push(Vec::new()),
                    None => {}
                }
            }
            runs.retain(|r| !r.is_empty());
            runs
        })
        .collect();
    let minima: Vec<Option<(f64, f64)>> =
        columns.iter().map(|c| interior_minimum(&xs, c)).collect();
    let entries: Vec<String> = figure
        .curves
        .iter()
        .zip(columns)
        .zip(&minima)
        .map(|((curve, col), min)| {
            let missing = col.iter().filter(|v| v.is_none()).count();
            let mut words = String::new();
            if let Some((at, v)) = min {
                let _ = write!(
                    words,
                    "; min. ≈ {} at ${}$ ≈ {}",
                    crate::digits::significant(*v, 4),
                    figure.x_label.replace('$', ""),
                    crate::digits::significant(*at, 4)
                );
            }
            if missing > 0 {
                let _ = write!(words, " (undefined at {missing} of {} points)", col.len());
            }
            format!("{}{words}", curve.label)
        })
        .collect();
    // The legend: a corner of the axes that no curve enters, else below the axes.
    let (line, size, gap) = (11.0, 9.0, 4.0);
    let legend_w = 30.0
        + entries
            .iter()
            .map(|e| text_width(e, size))
            .fold(0.0, f64::max);
    let legend_h = line * entries.len() as f64 + gap;
    let free = |x0: f64, y0: f64| {
        let (x1, y1) = (x0 + legend_w, y0 + legend_h);
        runs.iter().flatten().all(|run| {
            run.windows(2).all(|w| {
                // Sampled along each segment, so that a steep one is seen.
                (0..=8).all(|k| {
                    let t = f64::from(k) / 8.0;
                    let (a, b) = (
                        w[0].0 + t * (w[1].0 - w[0].0),
                        w[0].1 + t * (w[1].1 - w[0].1),
                    );
                    !(a >= x0 && a <= x1 && b >= y0 && b <= y1)
                })
            }) && run
                .iter()
                .all(|&(a, b)| !(a >= x0 && a <= x1 && b >= y0 && b <= y1))
        })
    };
    let corners = [
        (left + plot_w - legend_w - 4.0, top + 4.0),
        (left + 4.0, top + 4.0),
        (
            left + plot_w - legend_w - 4.0,
            top + plot_h - legend_h - 4.0,
        ),
        (left + 4.0, top + plot_h - legend_h - 4.0),
    ];
    let inside = corners
        .into_iter()
        .find(|&(a, b)| legend_w + 8.0 <= plot_w && legend_h + 8.0 <= plot_h && free(a, b));
    let below = top + plot_h + 34.0;
    let (legend_x, legend_y) = inside.unwrap_or((left, below));
    let height = if inside.is_some() {
        below
    } else {
        below + legend_h
    };
    let mut s = String::new();
    let _ = writeln!(
        s,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"85mm\" height=\"{:.2}mm\" viewBox=\"0 0 {width} {height:.2}\" font-family=\"serif\" font-size=\"10\">",
        height / 4.0
    );
    let _ = writeln!(s, "<title>{}</title>", escape(&figure.title));
    let _ = writeln!(s, "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>");
    let _ = writeln!(
        s,
        "<rect x=\"{left}\" y=\"{top}\" width=\"{plot_w}\" height=\"{plot_h}\" fill=\"none\" stroke=\"black\" stroke-width=\"0.6\"/>"
    );
    let (x_major, x_minor) = x.ticks();
    let bottom = top + plot_h;
    for t in x_minor {
        let v = px(t);
        let _ = writeln!(
            s,
            "<line x1=\"{v:.2}\" y1=\"{bottom:.2}\" x2=\"{v:.2}\" y2=\"{:.2}\" stroke=\"black\" stroke-width=\"0.4\"/>",
            bottom - 1.5
        );
    }
    for (t, label) in x_major {
        let v = px(t);
        let _ = writeln!(
            s,
            "<line x1=\"{v:.2}\" y1=\"{bottom:.2}\" x2=\"{v:.2}\" y2=\"{:.2}\" stroke=\"black\" stroke-width=\"0.6\"/><text x=\"{v:.2}\" y=\"{:.2}\" text-anchor=\"middle\">{label}</text>",
            bottom - 3.0,
            bottom + 11.0,
        );
    }
    let (y_major, y_minor) = y.ticks();
    for t in y_minor {
        let v = py(t);
        let _ = writeln!(
            s,
            "<line x1=\"{left}\" y1=\"{v:.2}\" x2=\"{:.2}\" y2=\"{v:.2}\" stroke=\"black\" stroke-width=\"0.4\"/>",
            left + 1.5
        );
    }
    for (t, label) in y_major {
        let v = py(t);
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
        bottom + 25.0,
        math(&figure.x_label)
    );
    let _ = writeln!(
        s,
        "<text transform=\"translate(11 {:.2}) rotate(-90)\" text-anchor=\"middle\">{}</text>",
        top + plot_h / 2.0,
        math(&figure.y_label)
    );
    if inside.is_some() {
        let _ = writeln!(
            s,
            "<rect x=\"{:.2}\" y=\"{:.2}\" width=\"{legend_w:.2}\" height=\"{legend_h:.2}\" fill=\"white\" stroke=\"#999\" stroke-width=\"0.4\"/>",
            legend_x,
            legend_y
        );
    }
    for (k, ((run, min), entry)) in runs.iter().zip(&minima).zip(&entries).enumerate() {
        let (colour, dash) = (COLOURS[k % COLOURS.len()], DASHES[k % DASHES.len()]);
        let dash_attr = if dash.is_empty() {
            String::new()
        } else {
            format!(" stroke-dasharray=\"{dash}\"")
        };
        for r in run {
            let points: Vec<String> = r.iter().map(|(a, b)| format!("{a:.2},{b:.2}")).collect();
            let _ = writeln!(
                s,
                "<polyline points=\"{}\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"1.2\"{dash_attr}/>",
                points.join(" ")
            );
        }
        let marker = |s: &mut String, a: f64, b: f64| {
            let _ = writeln!(
                s,
                "<circle cx=\"{a:.2}\" cy=\"{b:.2}\" r=\"2.2\" fill=\"{colour}\" stroke=\"white\" stroke-width=\"0.6\"/>"
            );
        };
        if let Some((at, v)) = min {
            let (a, b) = (px(*at), py(*v));
            if a.is_finite() && b.is_finite() {
                marker(&mut s, a, b);
            }
        }
        let ly = legend_y + gap / 2.0 + line * (k as f64 + 0.5);
        let _ = writeln!(
            s,
            "<line x1=\"{:.2}\" y1=\"{ly:.2}\" x2=\"{:.2}\" y2=\"{ly:.2}\" stroke=\"{colour}\" stroke-width=\"1.2\"{dash_attr}/>",
            legend_x + 4.0,
            legend_x + 24.0
        );
        if min.is_some() {
            marker(&mut s, legend_x + 14.0, ly);
        }
        let _ = writeln!(
            s,
            "<text x=\"{:.2}\" y=\"{:.2}\" font-size=\"{size}\">{}</text>",
            legend_x + 28.0,
            ly + 2.8,
            rich(entry)
        );
    }
    s.push_str("</svg>\n");
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Deeply nested scripts in a label are set as text past a few levels: the SVG stays
    /// about as long as the label, and open groups are read once.
    #[test]
    fn nested_scripts_in_a_label_stay_linear() {
        for label in [
            "a^{".repeat(20_000),
            format!("x{}{}", "^{a".repeat(5_000), "}".repeat(5_000)),
        ] {
            let svg = math(&label);
            assert!(
                svg.len() < 40 * label.len() / 10 + 1_000,
                "{} from {}",
                svg.len(),
                label.len()
            );
            assert!(svg.matches("<tspan").count() <= 2 * SCRIPT_DEPTH + 2);
        }
    }

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
            let axis = Axis::of(values, Scale::Auto);
            let t: Vec<f64> = axis.ticks().0.into_iter().map(|(t, _)| t).collect();
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
