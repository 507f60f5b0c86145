//! The paper's Fig. 6: shear-band thickness d_B/R_g against the rolling resistance
//! f_r, from (54) as printed and from the A² derived by following the Appendix's
//! steps as printed ((60) included) with h^C = 1/2, h_2 = 0 and three Poisson ratios.

use super::shear_band::Derivation;
use super::{Params, Point};
use plotters::prelude::*;

/// The Poisson ratios of the derived curves and their CSV column names.
pub const POISSON: [(f64, &str); 3] = [(0.0, "nu=0"), (0.25, "nu=0.25"), (0.45, "nu=0.45")];

/// One row of the figure's table.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    pub f_r: f64,
    /// d_B/R_g = π/A with A from (54).
    pub paper: Option<f64>,
    /// d_B/R_g from the derived A², per Poisson ratio; `None` where A is not real.
    pub derived: [Option<f64>; 3],
}

/// π/A for a given A², or `None` when A is not real and positive.
pub fn thickness(a2: f64) -> Option<f64> {
    (a2.is_finite() && a2 > 0.0).then(|| std::f64::consts::PI / a2.sqrt())
}

/// The grid f_r = 0.05, 0.10, …, 3.00 (k/20 exactly as f64 allows).
pub fn grid() -> impl Iterator<Item = f64> {
    (1..=60).map(|k| k as f64 / 20.0)
}

pub fn rows(p: &Params, d: &Derivation) -> Vec<Row> {
    grid()
        .map(|f_r| {
            let paper_pt = Point::figure(f_r, 0.0);
            Row {
                f_r,
                paper: thickness(d.a2_eq54.eval_f64(&|v| paper_pt.value(p, v))),
                derived: POISSON.map(|(nu, _)| {
                    let pt = Point::figure(f_r, nu);
                    thickness(d.a2_printed_balance.eval_f64(&|v| pt.value(p, v)))
                }),
            }
        })
        .collect()
}

/// A CSV cell: 12 significant digits without trailing zeros, so that a grid value such
/// as 0.05 is printed as it is written.
pub fn decimal(x: f64) -> String {
    crate::digits::significant(x, 12)
}

/// The CSV: `f_r,paper,nu=0,nu=0.25,nu=0.45`, empty cells where A is not real.
pub fn csv(rows: &[Row]) -> String {
    let mut out = String::from("f_r,paper");
    for (_, name) in POISSON {
        out.push(',');
        out.push_str(name);
    }
    out.push('\n');
    let cell = |v: Option<f64>| v.map(decimal).unwrap_or_default();
    for r in rows {
        out.push_str(&decimal(r.f_r));
        out.push(',');
        out.push_str(&cell(r.paper));
        for v in r.derived {
            out.push(',');
            out.push_str(&cell(v));
        }
        out.push('\n');
    }
    out
}

/// The figure as SVG: all four curves, axis labels and a legend. The y axis is cut at
/// 50 (lines leaving the plot are clipped) so that the curves' shapes stay visible (the derived curves rise like 1/f_r).
pub fn svg(rows: &[Row]) -> Result<String, String> {
    let mut buf = String::new();
    {
        let root = SVGBackend::with_string(&mut buf, (860, 600)).into_drawing_area();
        let err = |e: &dyn std::fmt::Display| format!("drawing the figure: {e}");
        root.fill(&WHITE).map_err(|e| err(&e))?;
        let ymax = 50.0;
        let mut chart = ChartBuilder::on(&root)
            .caption(
                "Fig. 6: shear band thickness versus rolling resistance",
                ("sans-serif", 22),
            )
            .margin(16)
            .x_label_area_size(48)
            .y_label_area_size(64)
            .build_cartesian_2d(0.0f64..3.0f64, 0.0f64..ymax)
            .map_err(|e| err(&e))?;
        chart
            .configure_mesh()
            .x_desc("rolling resistance f_r")
            .y_desc("shear band thickness d_B / R_g (axis cut at 50)")
            .draw()
            .map_err(|e| err(&e))?;
        let styles = [
            (BLACK, "paper, eq. (54)".to_string()),
            (BLUE, "derived, nu = 0 (h^C = 1/2, h_2 = 0)".to_string()),
            (GREEN, "derived, nu = 0.25".to_string()),
            (RED, "derived, nu = 0.45".to_string()),
        ];
        for (k, (color, label)) in styles.iter().enumerate() {
            let points: Vec<(f64, f64)> = rows
                .iter()
                .filter_map(|r| {
                    let v = if k == 0 { r.paper } else { r.derived[k - 1] };
                    v.map(|y| (r.f_r, y))
                })
                .collect();
            let color = *color;
            chart
                .draw_series(LineSeries::new(points, color.stroke_width(2)))
                .map_err(|e| err(&e))?
                .label(label.as_str())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 24, y)], color.stroke_width(2))
                });
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK)
            .draw()
            .map_err(|e| err(&e))?;
        root.present().map_err(|e| err(&e))?;
    }
    Ok(buf)
}
