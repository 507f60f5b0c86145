//! Deciding the claims of Appendix A and Section 6 (`strategy = "appendix"`): each
//! step compares what `crate::model` derives exactly with the printed statement, and
//! cross-checks the derivation by an independent floating-point route (num-dual
//! gradients, nalgebra linear algebra) before a verdict is given.

use super::eval::ExactEnv;
use super::{Counterexample, Method, Outcome};
use crate::derivation::{AppendixStep, Check, Verdict};
use crate::kernel::sturm::{count_roots, isolate_roots, Bound, UniPoly};
use crate::kernel::{Poly, RatFunc, Rational, VarTable};
use crate::lang::{Decls, Diagnostic, Origin, Span};
use crate::model::acoustic::{self, Contraction};
use crate::model::balance::{self, Velocity};
use crate::model::shear_band::{self, Derivation};
use crate::model::tangent::{self, ShearSign};
use crate::model::{ExactPoint, Params, Point};
use std::collections::BTreeMap;
use std::sync::OnceLock;

/// Largest relative disagreement allowed between the exact derivation evaluated in
/// `f64` and the independent floating-point route.
pub const ROUTE_TOL: f64 = 1e-9;
/// Central-difference step and tolerance for the gradient check.
pub const FD_STEP: f64 = 1e-6;
pub const FD_TOL: f64 = 1e-6;

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

pub fn decide(
    step: AppendixStep,
    origin: &Origin,
    decls: &Decls,
    check: &Check,
) -> Result<Outcome, Diagnostic> {
    let fail = |m: String| origin.diagnostic(Span::new(0, 0), m);
    let (p, d) = derivations().as_ref().map_err(|e| fail(e.clone()))?;
    match step {
        AppendixStep::YieldGradients => yield_gradients(p).map_err(fail),
        AppendixStep::BandDirection => band_direction(p, d).map_err(fail),
        AppendixStep::CriticalHardening => critical_hardening(p, d).map_err(fail),
        AppendixStep::BPositive => Ok(b_positive(p, d)),
        AppendixStep::BalanceV1 => balance_law(Velocity::V1, origin, decls, check),
        AppendixStep::BalanceV2 => balance_law(Velocity::V2, origin, decls, check),
        AppendixStep::BalanceW3 => balance_law(Velocity::W3, origin, decls, check),
        AppendixStep::Eq61 => derivation_negative_shear(p)
            .and_then(|d_neg| eq61(p, d, d_neg))
            .map_err(fail),
        AppendixStep::BoundaryModes => Ok(boundary_modes()),
        AppendixStep::Eq54 => eq54(p, d).map_err(fail),
        AppendixStep::NoBandWithoutRolling => no_band_without_rolling(p, d).map_err(fail),
        AppendixStep::ThicknessDecreases => thickness_decreases(p, d).map_err(fail),
    }
}

/// The exact gradient evaluated at `f_r`, as (Q_11, Q_22, Q_12, Q_21, F_13, F_23).
fn exact_gradient_at(p: &Params, g: &tangent::YieldGradient, f_r: f64) -> [f64; 6] {
    let at = |x: &RatFunc| x.eval_f64(&|v| if v == p.f_r { f_r } else { f64::NAN });
    [
        at(&g.q[0]),
        at(&g.q[1]),
        at(&g.q[2]),
        at(&g.q[3]),
        at(&g.f[0]),
        at(&g.f[1]),
    ]
}

/// The largest differences (exact vs num-dual, num-dual vs central differences) over
/// the states of the check; `exact` gives the closed form for a shear sign.
pub fn gradient_residuals(
    p: &Params,
    exact: &dyn Fn(ShearSign) -> Result<tangent::YieldGradient, String>,
) -> Result<(f64, f64, usize), String> {
    let (mut worst_exact, mut worst_fd, mut n) = (0.0f64, 0.0f64, 0);
    for shear in [ShearSign::Positive, ShearSign::Negative] {
        let g = exact(shear)?;
        for f_r in [0.05, 0.3, 0.5, 1.0, 2.0, 3.0] {
            for sigma in [-1.0, -2.5] {
                for r_g in [1.0, 0.4] {
                    let x = tangent::state_components(sigma, f_r, shear);
                    let dual = tangent::yield_gradient_dual(x, f_r, r_g);
                    let closed = exact_gradient_at(p, &g, f_r);
                    for k in 0..6 {
                        worst_exact = worst_exact.max((dual[k] - closed[k]).abs());
                        let (mut xp, mut xm) = (x, x);
                        xp[k] += FD_STEP;
                        xm[k] -= FD_STEP;
                        let fd = (tangent::rolling_yield(&xp, f_r, r_g)
                            - tangent::rolling_yield(&xm, f_r, r_g))
                            / (2.0 * FD_STEP);
                        // μ-derivatives: F₂ is not differentiable across μ = 0 only when
                        // q = r = 0, which the state avoids (τ ≠ 0).
                        worst_fd = worst_fd.max((fd - dual[k]).abs());
                        n += 1;
                    }
                }
            }
        }
    }
    Ok((worst_exact, worst_fd, n))
}

fn yield_gradients(p: &Params) -> Result<Outcome, String> {
    let (worst_exact, worst_fd, n) =
        gradient_residuals(p, &|s| tangent::yield_gradient_exact(p, s))?;
    let g = tangent::yield_gradient_exact(p, ShearSign::Positive)?;
    let shown: Vec<String> = g.q.iter().chain(&g.f).map(|x| p.display(x)).collect();
    let holds = worst_exact <= ROUTE_TOL && worst_fd <= FD_TOL;
    let detail = format!(
        "exact at the state (τ > 0): (Q_11, Q_22, Q_12, Q_21) = ({}), (F_1, F_2) = ({}); τ < 0 flips Q_12, Q_21; \
         num-dual at {n} component checks (f_r 0.05–3, σ = −1, −2.5, R_g = 1, 0.4, both signs of τ): \
         largest |exact − num-dual| {worst_exact:.1e} (tolerance {ROUTE_TOL:.0e}), largest |num-dual − central difference| \
         {worst_fd:.1e} (step {FD_STEP:.0e}, tolerance {FD_TOL:.0e})",
        shown[..4].join(", "),
        shown[4..].join(", ")
    );
    let verdict = if holds {
        Verdict::Holds
    } else {
        Verdict::Fails
    };
    Ok(Outcome::new(verdict, Method::Symbolic, n).with_detail(detail))
}

/// h_2^cr(θ) by the exact route, evaluated in `f64`.
fn h2cr_exact_f64(p: &Params, h2cr: &RatFunc, pt: &Point, theta: f64) -> f64 {
    let (n1, n2) = (-theta.sin(), theta.cos());
    h2cr.eval_f64(&|v| {
        if v == p.n_1 {
            n1
        } else if v == p.n_2 {
            n2
        } else {
            pt.value(p, v)
        }
    })
}

/// Both routes' maximum of h_2^cr over θ at `pt`: (θ*, h*) exact-in-f64 and nalgebra.
/// (θ*, h_2^cr(θ*)): the maximum over orientations found by one route.
type Maximum = (f64, f64);

fn maxima(p: &Params, h2cr: &RatFunc, pt: &Point) -> Result<(Maximum, Maximum), String> {
    let exact = acoustic::maximise_over_orientation(|t| h2cr_exact_f64(p, h2cr, pt, t));
    let float = acoustic::maximise_over_orientation(|t| {
        acoustic::critical_hardening_f64(pt, ShearSign::Positive, t)
    });
    if rel(exact.1, float.1) > 1e-6 || (exact.0 - float.0).abs() > 1e-4 {
        return Err(format!(
            "the two routes disagree on max h_2^cr: exact {exact:?}, nalgebra {float:?}"
        ));
    }
    Ok((exact, float))
}

/// h_2^cr(n) of the state with τ > 0, computed once.
fn critical_hardening_function(p: &Params, d: &Derivation) -> Result<&'static RatFunc, String> {
    static CELL: OnceLock<Result<RatFunc, String>> = OnceLock::new();
    CELL.get_or_init(|| {
        acoustic::critical_hardening(p, &d.tangent.d_ep, Contraction::GradientIndices)
    })
    .as_ref()
    .map_err(Clone::clone)
}

fn band_direction(p: &Params, d: &Derivation) -> Result<Outcome, String> {
    let h2cr = critical_hardening_function(p, d)?;
    // n = (−sin θ, cos θ): d/dθ at θ = 0 is −∂/∂n_1 at n = (0, 1). The quotient rule
    // is applied to numerator and denominator separately and evaluated at n = (0, 1)
    // before anything is reduced (reducing the full derivative first is slow).
    let at_axis = |q: &Poly| -> Option<RatFunc> {
        RatFunc::from_poly(q)
            .substitute(p.n_1, &RatFunc::int(0))?
            .substitute(p.n_2, &RatFunc::int(1))
    };
    let (nu, de) = (h2cr.numerator(), h2cr.denominator());
    let pieces = (|| {
        Some((
            at_axis(nu)?,
            at_axis(&nu.derivative(p.n_1))?,
            at_axis(de)?,
            at_axis(&de.derivative(p.n_1))?,
        ))
    })()
    .ok_or("h_2^cr has a pole at θ = 0")?;
    let (n0, n1, d0, d1) = pieces;
    let slope =
        -&(&(&(&n1 * &d0) - &(&n0 * &d1)) / &d0.pow(2)).ok_or("h_2^cr has a pole at θ = 0")?;
    let at = point(half());
    let slope_at = slope
        .eval(&|v| at.value(p, v))
        .ok_or("the slope has a pole at the point")?;
    let pt = at.to_f64();
    let ((theta, h), (theta_f, _)) = maxima(p, h2cr, &pt)?;
    let stationary = slope.is_zero();
    let detail = format!(
        "h_2^cr(n), the h_2 at which det(n_i D^(ep)_ijkl n_k) = 0, is exact (the printed contraction n_j D_ijkl n_l gives \
         the same function); at θ = 0, dh_2^cr/dθ = {} exactly, so θ = 0 is not even stationary for f_r ≠ 0; at {} the slope is \
         {slope_at} and the band forms first at θ_B = {:.2}° (h_2^cr = {h:.6} G; nalgebra route: {:.2}°)",
        p.display(&slope),
        at.describe(),
        theta.to_degrees(),
        theta_f.to_degrees()
    );
    let verdict = if stationary {
        Verdict::Holds
    } else {
        Verdict::Fails
    };
    let mut out = Outcome::new(verdict, Method::Symbolic, 1).with_detail(detail);
    if !stationary {
        out = out.with_counterexample(Counterexample {
            lhs: "θ_B".into(),
            rhs: "0".into(),
            lhs_value: Some(format!("{:.2}°", theta.to_degrees())),
            rhs_value: Some("0°".into()),
            point: describe_point(&at),
            ..Counterexample::default()
        });
    }
    Ok(out)
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

/// Substitutes the exact point into everything but n and returns h_2^cr(t, 1) as
/// (numerator, denominator) polynomials in t = n_1 (n_2 = 1).
fn h2cr_on_line(p: &Params, h2cr: &RatFunc, at: &ExactPoint) -> Result<(UniPoly, UniPoly), String> {
    let mut f = h2cr
        .substitute(p.n_2, &RatFunc::int(1))
        .ok_or("pole at n_2 = 1")?;
    for v in [p.f_r, p.k, p.g, p.h_c, p.h_2, p.r_g] {
        f = f
            .substitute(v, &RatFunc::constant(at.value(p, v)))
            .ok_or("pole at the point")?;
    }
    let num = UniPoly::from_poly(f.numerator(), p.n_1).ok_or("not univariate in n_1")?;
    let den = UniPoly::from_poly(f.denominator(), p.n_1).ok_or("not univariate in n_1")?;
    Ok((num, den))
}

fn critical_hardening(p: &Params, d: &Derivation) -> Result<Outcome, String> {
    let h2cr = critical_hardening_function(p, d)?;
    let at_zero = h2cr
        .substitute(p.n_1, &RatFunc::int(0))
        .and_then(|x| x.substitute(p.n_2, &RatFunc::int(1)))
        .ok_or("pole at θ = 0")?;
    let at = point(half());
    // Exact: on the line n = (t, 1) (every θ but θ = 90°) numerator and denominator
    // of h_2^cr have no real root, so h_2^cr keeps the sign of its value at t = 0;
    // θ = 90° (n = (1, 0)) is evaluated separately.
    let (num, den) = h2cr_on_line(p, h2cr, &at)?;
    let all = (Bound::MinusInfinity, Bound::PlusInfinity);
    let roots = count_roots(&num, &all.0, &all.1) + count_roots(&den, &all.0, &all.1);
    let zero = Rational::int(0);
    let value_0 = num
        .eval(&zero)
        .checked_div(&den.eval(&zero))
        .ok_or("pole")?;
    let f90 = h2cr
        .fix(&|v| {
            if v == p.n_1 {
                Some(Rational::int(1))
            } else if v == p.n_2 {
                Some(Rational::int(0))
            } else {
                Some(at.value(p, v))
            }
        })
        .ok_or("pole at θ = 90°")?;
    let value_90 = f90.as_constant().ok_or("not a number")?;
    let pt = at.to_f64();
    let ((theta, h), (_, h_f)) = maxima(p, h2cr, &pt)?;
    let everywhere_negative = roots == 0 && value_0.is_negative() && value_90.is_negative();
    let detail = format!(
        "at θ = 0, h_2^cr = {} exactly; at {} the numerator and denominator of h_2^cr(n_1 = t, n_2 = 1) have no real \
         root (Sturm), h_2^cr(θ = 0) = {value_0} and h_2^cr(θ = 90°) = {value_90}, so h_2^cr < 0 for every orientation \
         and det A ≠ 0 at h_2 = 0; the largest is h_2^cr = {h:.6} G at θ = {:.2}° (nalgebra bisection route: {h_f:.6} G)",
        p.display(&at_zero),
        at.describe(),
        theta.to_degrees()
    );
    let verdict = if everywhere_negative {
        Verdict::Fails
    } else {
        return Err(format!(
            "the exact sign argument did not apply ({roots} real roots); a different check is needed: {detail}"
        ));
    };
    Ok(Outcome::new(verdict, Method::Symbolic, 3)
        .with_detail(detail)
        .with_counterexample(Counterexample {
            lhs: "max over θ of h_2^cr".into(),
            rhs: "0".into(),
            lhs_value: Some(format!("{h:.6}")),
            rhs_value: Some("0".into()),
            point: describe_point(&at),
            ..Counterexample::default()
        }))
}

fn b_positive(p: &Params, d: &Derivation) -> Outcome {
    let b = acoustic::b_scalar(p, &d.tangent.m_ep);
    let n2 = &p.var(p.n_1).pow(2) + &p.var(p.n_2).pow(2);
    let expected = &(&(&RatFunc::int(4) * &p.var(p.g)) * &p.var(p.r_g).pow(2)) * &n2;
    if b == expected {
        Outcome::new(Verdict::Holds, Method::Symbolic, 1).with_detail(format!(
            "B = {} exactly (F_i = 0 at the state, so M^(ep) = M^(el) = 4 G R_g² δ_ij); on n·n = 1, B = 4 G R_g² > 0 for \
             G, R_g > 0: a jump in the curvature rate cannot satisfy B [K] = 0",
            p.display(&b)
        ))
    } else {
        Outcome::new(Verdict::Fails, Method::Symbolic, 1).with_detail(format!(
            "B = {} is not 4 G R_g² n·n; its sign is not established",
            p.display(&b)
        ))
    }
}

/// The printed law (`sides[0] − sides[1]` of the first chain) as a polynomial whose
/// variables are named like the derived law's (`sigma_12`, `dmu_23`, …).
fn printed_law(
    origin: &Origin,
    decls: &Decls,
    check: &Check,
) -> Result<(Poly, VarTable, String), Diagnostic> {
    let chain =
        check
            .chains
            .first()
            .filter(|c| c.len() == 2)
            .ok_or_else(|| {
                origin
            .diagnostic(Span::new(0, 0), "a balance step needs sides = [\"printed law\", \"0\"]")
            .with_help("the left side is the printed equation's left-hand side, e.g. \"dsigma_21\"")
            })?;
    let mut env = ExactEnv::new(decls, &check.defs, &check.assumptions)?;
    let mut value = |k: usize| -> Result<Poly, Diagnostic> {
        let side = &chain[k];
        let node = side
            .node
            .as_ref()
            .map_err(|e| side.origin.diagnostic(e.span, e.message.clone()))?;
        let l = env.eval(node, &side.origin)?;
        l.tensor.into_scalar().ok_or_else(|| {
            side.origin.diagnostic(
                Span::new(0, side.text.len()),
                "a balance law is a scalar equation",
            )
        })
    };
    let law = &value(0)? - &value(1)?;
    let text = format!("{} = {}", chain[0].text, chain[1].text);
    Ok((law, env.vars.clone(), text))
}

fn translate(p: &Poly, from: &VarTable, to: &mut VarTable) -> Poly {
    let mut out = Poly::default();
    for (m, c) in p.terms() {
        let factors = m
            .factors()
            .iter()
            .map(|&(v, e)| (to.intern(from.name(v)), e))
            .collect();
        out.add_term(crate::kernel::Monomial::from_factors(factors), c.clone());
    }
    out
}

fn balance_law(
    v: Velocity,
    origin: &Origin,
    decls: &Decls,
    check: &Check,
) -> Result<Outcome, Diagnostic> {
    let (printed, mut names, text) = printed_law(origin, decls, check)?;
    let mut own = VarTable::new();
    let derived = balance::balance_law(v, 1, &mut own);
    let derived = translate(&derived, &own, &mut names);
    let mut own_flipped = VarTable::new();
    let flipped = balance::balance_law(v, -1, &mut own_flipped);
    let flipped = translate(&flipped, &own_flipped, &mut names);
    let derived_text = derived.display(&names);
    let base = format!(
        "Euler–Lagrange equation of the virtual power (3) for {} with Γ_ij = v_j,i − e_ijk w_k, K_ij = w_j,i (2), fields of x_2 \
         only: {derived_text} = 0 (d-prefixed variables are ∂/∂x_2; rates implied)",
        v.name()
    );
    // A point where the two laws differ: the first variable of the difference set to
    // 1, every other one 0.
    let diff = &printed - &derived;
    let first = diff
        .terms()
        .next()
        .and_then(|(m, _)| m.factors().first().map(|&(v, _)| v));
    let at_point: BTreeMap<String, Rational> = first
        .map(|v| (names.name(v).to_owned(), Rational::int(1)))
        .into_iter()
        .collect();
    let value = |v| {
        if Some(v) == first {
            Rational::int(1)
        } else {
            Rational::int(0)
        }
    };
    match balance::proportional(&printed, &derived) {
        Some(lambda) => Ok(Outcome::new(Verdict::Holds, Method::Symbolic, 1)
            .with_detail(format!("{base}; the printed law is {lambda} times it"))),
        None => {
            let flip = if balance::proportional(&printed, &flipped).is_some() {
                format!(
                    "; the printed law follows from the opposite rotation sign Γ_ij = v_j,i + e_ijk w_k ({} = 0)",
                    flipped.display(&names)
                )
            } else {
                String::new()
            };
            Ok(Outcome::new(Verdict::Fails, Method::Symbolic, 1)
                .with_detail(format!("{base}{flip}"))
                .with_counterexample(Counterexample {
                    chain: 1,
                    equality: 1,
                    lhs: text,
                    rhs: format!("{derived_text} = 0"),
                    difference: (&printed - &derived).display(&names),
                    point: at_point
                        .iter()
                        .map(|(k, v)| (k.clone(), v.to_string()))
                        .collect(),
                    lhs_value: printed.eval(&value).map(|v| v.to_string()),
                    rhs_value: derived.eval(&value).map(|v| v.to_string()),
                    ..Counterexample::default()
                }))
        }
    }
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

fn eq61(p: &Params, d: &Derivation, d_neg: &Derivation) -> Result<Outcome, String> {
    let at = point(Rational::int(1));
    let derived = eval_at(p, &d.a2_printed_balance, &at)?;
    let printed = eval_at(p, &d.a2_eq61, &at)?;
    let float = a2_float(&at, ShearSign::Positive)?;
    if rel(derived.to_f64(), float) > ROUTE_TOL {
        return Err(format!(
            "routes disagree on A²: exact {derived}, nalgebra {float}"
        ));
    }
    let odd = d.a2_eq61 != d_neg.a2_eq61 && d.a2_printed_balance == d_neg.a2_printed_balance;
    let equal = d.a2_eq61 == d.a2_printed_balance;
    let detail = format!(
        "reading: D_IJkl = D^(ep)_IJ / G with I, J the positions 1..4 = 11, 22, 12, 21 of (57) (so D_3222 = D^(ep)_(12)(22), \
         D_4421 = D^(ep)_(21)(21)), divided by G so that A² is dimensionless; (61) then gives A² = {}; eliminating v_1', v_2' \
         from (58)–(59) and substituting in (60) as printed gives A² = {}{}; nalgebra route at the point: {float:.12}",
        p.display(&d.a2_eq61),
        p.display(&d.a2_printed_balance),
        if odd {
            "; (61) changes with the sign of τ, the elimination does not"
        } else {
            ""
        }
    );
    let mut out = Outcome::new(
        if equal {
            Verdict::Holds
        } else {
            Verdict::Fails
        },
        Method::Symbolic,
        1,
    )
    .with_detail(detail);
    if !equal {
        out = out.with_counterexample(Counterexample {
            lhs: "A² by (61)".into(),
            rhs: "A² from (58)–(60)".into(),
            lhs_value: Some(printed.to_string()),
            rhs_value: Some(derived.to_string()),
            point: describe_point(&at),
            ..Counterexample::default()
        });
    }
    Ok(out)
}

fn boundary_modes() -> Outcome {
    let modes = shear_band::boundary_modes(4);
    let listed: Vec<String> = modes
        .iter()
        .map(|(k, m)| {
            let multiple = match k {
                1 => "π/2".to_string(),
                2 => "π".to_string(),
                k if k % 2 == 0 => format!("{}π", k / 2),
                k => format!("{k}π/2"),
            };
            format!("A d_B = {multiple} ({m})")
        })
        .collect();
    let first_symmetric = modes
        .iter()
        .find(|(_, m)| *m == "symmetric")
        .map(|(k, _)| *k);
    let holds = first_symmetric == Some(2);
    Outcome::new(if holds { Verdict::Holds } else { Verdict::Fails }, Method::Symbolic, modes.len()).with_detail(format!(
        "w_3 = C cos(A x_2) + S sin(A x_2) + const; μ_23 = M_22 w_3' = 0 at x_2 = ±d_B has a nonzero (C, S) exactly when \
         sin(2 A d_B) = 0: {}; d_B/R_g = π/A is the first symmetric mode (w_3 even about the band's centre, C ≠ 0); \
         the first antisymmetric mode would give d_B/R_g = π/(2A)",
        listed.join(", ")
    ))
}

fn eq54(p: &Params, d: &Derivation) -> Result<Outcome, String> {
    let at = point(Rational::int(1));
    let derived = eval_at(p, &d.a2_printed_balance, &at)?;
    let paper = eval_at(p, &d.a2_eq54, &at)?;
    let by61 = eval_at(p, &d.a2_eq61, &at)?;
    let float = a2_float(&at, ShearSign::Positive)?;
    if rel(derived.to_f64(), float) > ROUTE_TOL {
        return Err(format!(
            "routes disagree on A²: exact {derived}, nalgebra {float}"
        ));
    }
    // The paper's own values h^C = 1/2 and h_2 = 0.
    let paper_values = d
        .a2_printed_balance
        .substitute(p.h_c, &RatFunc::constant(half()))
        .and_then(|x| x.substitute(p.h_2, &RatFunc::int(0)))
        .ok_or("pole")?;
    let same = d.a2_printed_balance == d.a2_eq54;
    let parting = if d.a2_printed_balance != d.a2_eq61 {
        "the routes part at (61): eliminating through (58)–(60) as printed and the printed formula (61) already disagree, \
         and (54) equals neither"
    } else {
        "the routes part at (54): (61) agrees with the elimination but not with (54)"
    };
    let detail = format!(
        "derived by following the Appendix as printed ((55) with its indices fixed, (58)–(60) as printed, y in units of R_g): \
         A² = {}, which with h^C = 1/2, h_2 = 0 is {}; it depends on K (ν) and h^C, (54) does not; {parting}; with the \
         balance law derived from (2)–(3) instead of (60), A² = {} < 0, so A is not real and w_3 is exponential (no \
         periodic band profile); nalgebra route at the point: {float:.12}",
        p.display(&d.a2_printed_balance),
        p.display(&paper_values),
        p.display(&d.a2_derived_balance)
    );
    let mut out = Outcome::new(
        if same { Verdict::Holds } else { Verdict::Fails },
        Method::Symbolic,
        1,
    )
    .with_detail(detail);
    if !same {
        out = out.with_counterexample(Counterexample {
            lhs: "A² of (54)".into(),
            rhs: "A² derived".into(),
            lhs_value: Some(paper.to_string()),
            rhs_value: Some(format!("{derived} (and {by61} by (61))")),
            point: describe_point(&at),
            ..Counterexample::default()
        });
    }
    Ok(out)
}

/// (54)'s A² as numerator and denominator polynomials in f_r.
fn eq54_in_f(p: &Params, d: &Derivation) -> Result<(UniPoly, UniPoly), String> {
    let num = UniPoly::from_poly(d.a2_eq54.numerator(), p.f_r)
        .ok_or("(54) is not a function of f_r alone")?;
    let den = UniPoly::from_poly(d.a2_eq54.denominator(), p.f_r)
        .ok_or("(54) is not a function of f_r alone")?;
    Ok((num, den))
}

fn no_band_without_rolling(p: &Params, d: &Derivation) -> Result<Outcome, String> {
    let (num, den) = eq54_in_f(p, d)?;
    let zero = Rational::int(0);
    let a2_at_0 = num
        .eval(&zero)
        .checked_div(&den.eval(&zero))
        .ok_or("(54) has a pole at f_r = 0")?;
    let pos = (Bound::At(zero.clone()), Bound::PlusInfinity);
    let positive_roots = count_roots(&num, &pos.0, &pos.1) + count_roots(&den, &pos.0, &pos.1);
    let holds = a2_at_0.is_zero() && positive_roots == 0;
    let derived_at_0 = d
        .a2_printed_balance
        .substitute(p.f_r, &RatFunc::int(0))
        .and_then(|x| x.substitute(p.h_2, &RatFunc::int(0)))
        .ok_or("pole")?;
    Ok(Outcome::new(if holds { Verdict::Holds } else { Verdict::Fails }, Method::Symbolic, 2).with_detail(format!(
        "(54): A² = {} is 0 at f_r = 0 ({a2_at_0}) with a nonzero denominator, and its numerator and denominator have no \
         root for f_r > 0 (Sturm), so A² > 0 there, A → 0 and d_B/R_g = π/A → ∞ as f_r → 0; the A² derived from the \
         Appendix as printed is {} at f_r = 0, h_2 = 0, so it agrees",
        p.display(&d.a2_eq54),
        p.display(&derived_at_0)
    )))
}

/// Where a function of f_r alone increases for f_r > 0, decided exactly.
#[derive(Clone, Debug, PartialEq)]
pub struct Monotonicity {
    /// `Holds`: increasing on all of f_r > 0; `Conditional`: increasing on (0, f*)
    /// and decreasing just after f*; `Fails`: decreasing just after 0.
    pub verdict: Verdict,
    /// The first positive root f* of d/df_r, isolated in [lo, hi].
    pub first_root: Option<(Rational, Rational)>,
    pub slope: RatFunc,
}

/// The sign of d/df_r of `f` (a rational function of f_r alone) on f_r > 0, from
/// Sturm counts of the slope's numerator (its denominator is a square, so ≥ 0; it
/// must have no positive root). Roots are isolated to width 1e-9 below 10 (`Err` if
/// any lies beyond).
pub fn increasing_for_positive(p: &Params, f: &RatFunc) -> Result<Monotonicity, String> {
    let slope = f.derivative(p.f_r);
    let num = UniPoly::from_poly(slope.numerator(), p.f_r).ok_or("not a function of f_r alone")?;
    let den =
        UniPoly::from_poly(slope.denominator(), p.f_r).ok_or("not a function of f_r alone")?;
    let pos = (Bound::At(Rational::int(0)), Bound::PlusInfinity);
    if count_roots(&den, &pos.0, &pos.1) != 0 {
        return Err("the denominator of the slope vanishes for some f_r > 0".into());
    }
    let width = Rational::ratio(1, 1_000_000_000).expect("nonzero");
    let tiny = Rational::ratio(1, 1_000_000_000_000).expect("nonzero");
    let total = count_roots(&num, &pos.0, &pos.1);
    let roots = isolate_roots(&num, &tiny, &Rational::int(10), &width);
    if roots.len() != total {
        return Err(format!(
            "{total} positive roots of the slope, {} isolated in (1e-12, 10)",
            roots.len()
        ));
    }
    let positive = |x: &Rational| {
        let v = num.eval(x);
        !v.is_negative() && !v.is_zero()
    };
    let verdict = match roots.first() {
        _ if !positive(&tiny) => Verdict::Fails,
        None => Verdict::Holds,
        Some((_, hi)) => {
            let next = roots
                .get(1)
                .map_or(hi + &Rational::int(1), |(lo, _)| lo.clone());
            let after = &(hi + &next) * &half();
            if positive(&after) {
                return Err("the slope touches 0 without changing sign; not handled".into());
            }
            Verdict::Conditional
        }
    };
    Ok(Monotonicity {
        verdict,
        first_root: roots.first().cloned(),
        slope,
    })
}

fn thickness_decreases(p: &Params, d: &Derivation) -> Result<Outcome, String> {
    // d_B = π/A decreases exactly where A² increases: the sign of d(A²)/df_r.
    let m = increasing_for_positive(p, &d.a2_eq54)?;
    let (slope, verdict) = (&m.slope, m.verdict);
    let roots: Vec<(Rational, Rational)> = m.first_root.iter().cloned().collect();
    let a2 = |f: i64| {
        d.a2_eq54.eval(&|v| {
            if v == p.f_r {
                Rational::int(f)
            } else {
                Rational::int(0)
            }
        })
    };
    let db = |x: &Rational| std::f64::consts::PI / x.to_f64().sqrt();
    let (a1, a2v) = (a2(1).ok_or("pole")?, a2(2).ok_or("pole")?);
    // The derived A² at the counterexample material (ν = 1/4, h^C = 1/2, h_2 = 0, G = 1),
    // decided by the same exact procedure.
    let at = point(half());
    let derived = d
        .a2_printed_balance
        .fix(&|v| (v != p.f_r).then(|| at.value(p, v)))
        .ok_or("pole")?;
    let derived_verdict = increasing_for_positive(p, &derived)?.verdict;
    let domain = roots
        .first()
        .map(|(lo, hi)| {
            format!(
                "holds for 0 < f_r < f* ≈ {:.9}, the positive root of {} (isolated by Sturm bisection in a rational \
                 interval of width ≤ 1e-9 around it)",
                0.5 * (lo.to_f64() + hi.to_f64()),
                p.display(&RatFunc::from_poly(slope.numerator())),
            )
        })
        .unwrap_or_else(|| "d(A²)/df_r > 0 for every f_r > 0".into());
    let mut out = Outcome::new(verdict, Method::Symbolic, 2).with_detail(format!(
        "d_B = π/A decreases where A² of (54) increases; d(A²)/df_r = {}; {domain}; beyond f*, A² decreases and d_B grows \
         again; for the A² derived from the Appendix, {} = {}, \"d_B decreases as f_r grows\" {} for every f_r > 0 (K = 2, \
         h^C = 1/2, h_2 = 0)",
        p.display(slope),
        "A²",
        p.display(&derived),
        if derived_verdict == Verdict::Holds { "holds" } else { "does not hold" }
    ));
    if verdict == Verdict::Conditional {
        out = out.with_counterexample(Counterexample {
            lhs: "d_B/R_g at f_r = 1".into(),
            rhs: "d_B/R_g at f_r = 2".into(),
            lhs_value: Some(format!("{:.9}", db(&a1))),
            rhs_value: Some(format!("{:.9}", db(&a2v))),
            point: BTreeMap::from([("f_r".to_owned(), "1 → 2".to_owned())]),
            ..Counterexample::default()
        });
    }
    Ok(out)
}
