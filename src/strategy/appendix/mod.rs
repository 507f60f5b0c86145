//! Deciding the claims of Appendix A and Section 6 (`strategy = "appendix"`): each
//! step compares what `crate::model` derives exactly with the printed statement, and
//! cross-checks the derivation by an independent floating-point route (num-dual
//! gradients, nalgebra linear algebra) before a verdict is given.

use super::finding::Finding;
use super::{Counterexample, Method, Outcome, Strength};
use crate::derivation::AppendixStep;
use crate::kernel::certificate::Certificate;
use crate::kernel::sturm::{count_roots, Bound, UniPoly};
use crate::kernel::{Poly, RatFunc, Rational};
use crate::lang::{Diagnostic, Origin, Span};
use crate::model::acoustic::{self, Contraction};
use crate::model::shear_band::{self, Derivation};
use crate::model::tangent::ShearSign;
use crate::model::{ExactPoint, Params, Point};
use std::collections::BTreeMap;
use std::sync::OnceLock;

mod acoustic_tensor;
mod band;

/// Largest relative disagreement allowed between the exact derivation evaluated in
/// `f64` and the independent floating-point route.
pub const ROUTE_TOL: f64 = 1e-9;

/// The derivation for τ > 0, computed once.
fn derivations() -> &'static Result<(Params, Derivation), String> {
    static CELL: OnceLock<Result<(Params, Derivation), String>> = OnceLock::new();
    CELL.get_or_init(|| {
        let p = Params::new();
        let pos = shear_band::derive(&p, ShearSign::Positive)?;
        Ok((p, pos))
    })
}

/// The derivation for τ < 0 (the relaxation of the shear sign), computed once when a
/// step needs it.
fn derivation_negative_shear(p: &Params) -> Result<&'static Derivation, String> {
    static CELL: OnceLock<Result<Derivation, String>> = OnceLock::new();
    CELL.get_or_init(|| shear_band::derive(p, ShearSign::Negative))
        .as_ref()
        .map_err(Clone::clone)
}

/// The exact parameter point used for counterexamples: f_r = 1/2 (or as given),
/// ν = 1/4 (K = 2), h^C = 1/2, h_2 = 0, G = R_g = 1.
fn point(f_r: Rational) -> ExactPoint {
    ExactPoint {
        f_r,
        k: Rational::int(2),
        g: Rational::int(1),
        h_c: Rational::ratio(1, 2).expect("2 ≠ 0"),
        h_2: Rational::int(0),
        r_g: Rational::int(1),
    }
}

fn half() -> Rational {
    Rational::ratio(1, 2).expect("2 ≠ 0")
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / a.abs().max(b.abs()).max(1e-300)
}

pub fn decide(step: AppendixStep, origin: &Origin) -> Result<Outcome, Diagnostic> {
    let fail = |m: String| origin.diagnostic(Span::new(0, 0), m);
    let (p, d) = derivations().as_ref().map_err(|e| fail(e.clone()))?;
    match step {
        AppendixStep::BandDirection => acoustic_tensor::band_direction(p, d).map_err(fail),
        AppendixStep::CriticalHardening => acoustic_tensor::critical_hardening(p, d).map_err(fail),
        AppendixStep::BPositive => Ok(acoustic_tensor::b_positive(p, d)),
        AppendixStep::Eq61 => derivation_negative_shear(p)
            .and_then(|d_neg| band::eq61(p, d, d_neg))
            .map_err(fail),
        AppendixStep::BoundaryModes => Ok(band::boundary_modes()),
        AppendixStep::Eq54 => band::eq54(p, d).map_err(fail),
    }
}

fn describe_point(at: &ExactPoint) -> BTreeMap<String, String> {
    [
        ("f_r", &at.f_r),
        ("K", &at.k),
        ("G", &at.g),
        ("h_C", &at.h_c),
        ("h_2", &at.h_2),
        ("R_g", &at.r_g),
    ]
    .into_iter()
    .map(|(k, v)| (k.to_owned(), v.to_string()))
    .collect()
}

fn eval_at(p: &Params, f: &RatFunc, at: &ExactPoint) -> Result<Rational, String> {
    f.eval(&|v| at.value(p, v))
        .ok_or_else(|| format!("{} has a pole at {}", p.display(f), at.describe()))
}

/// The second route's A² (nalgebra) at `at`, for the printed moment law.
fn a2_float(at: &ExactPoint, shear: ShearSign) -> Result<f64, String> {
    shear_band::a_squared_f64(&at.to_f64(), shear, 1.0, -1.0)
        .ok_or_else(|| "singular system".to_string())
}

/// A proved `holds` from the kernel's certificate, or a `fails` (exact) without one.
fn proved_or_fails(certificate: Option<Certificate>, checks: usize) -> Outcome {
    match certificate {
        Some(c) => Outcome::proved(Method::Symbolic, checks, c),
        None => Outcome::fails(Method::Symbolic, Strength::Proof, checks),
    }
}
