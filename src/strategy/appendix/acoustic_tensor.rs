//! `band-direction`, `critical-hardening`, `b-positive`: the acoustic tensor and B,
//! exact with a nalgebra second route.

use super::*;

/// h_2^cr(θ) by the exact route, evaluated in `f64`.
pub(super) fn h2cr_exact_f64(p: &Params, h2cr: &RatFunc, pt: &Point, theta: f64) -> f64 {
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

/// (θ*, h_2^cr(θ*)): the maximum over orientations found by one route.
pub(super) type Maximum = (f64, f64);

/// Both routes' maximum of h_2^cr over θ at `pt`: (θ*, h*) exact-in-f64 and nalgebra.
pub(super) fn maxima(p: &Params, h2cr: &RatFunc, pt: &Point) -> Result<(Maximum, Maximum), String> {
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
pub(super) fn critical_hardening_function(
    p: &Params,
    d: &Derivation,
) -> Result<&'static RatFunc, String> {
    static CELL: OnceLock<Result<RatFunc, String>> = OnceLock::new();
    CELL.get_or_init(|| {
        acoustic::critical_hardening(p, &d.tangent.d_ep, Contraction::GradientIndices)
    })
    .as_ref()
    .map_err(Clone::clone)
}

pub(super) fn band_direction(p: &Params, d: &Derivation) -> Result<Outcome, String> {
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
    let certificate = Certificate::rational_functions_equal(&slope, &RatFunc::int(0));
    let stationary = certificate.is_some();
    let detail = format!(
        "h_2^cr(n), the h_2 at which det(n_i D^(ep)_ijkl n_k) = 0, is exact (the printed contraction n_j D_ijkl n_l gives \
         the same function); at θ = 0, dh_2^cr/dθ = {} exactly, so θ = 0 is not even stationary for f_r ≠ 0; at {} the slope is \
         {slope_at} and the band forms first at θ_B = {:.2}° (h_2^cr = {h:.6} G; nalgebra route: {:.2}°)",
        p.display(&slope),
        at.describe(),
        theta.to_degrees(),
        theta_f.to_degrees()
    );
    let mut out = proved_or_fails(certificate, 1).with_finding(Finding::Appendix { text: detail });
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

/// Substitutes the exact point into everything but n and returns h_2^cr(t, 1) as
/// (numerator, denominator) polynomials in t = n_1 (n_2 = 1).
pub(super) fn h2cr_on_line(
    p: &Params,
    h2cr: &RatFunc,
    at: &ExactPoint,
) -> Result<(UniPoly, UniPoly), String> {
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

pub(super) fn critical_hardening(p: &Params, d: &Derivation) -> Result<Outcome, String> {
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
    if !everywhere_negative {
        return Err(format!(
            "the exact sign argument did not apply ({roots} real roots); a different check is needed: {detail}"
        ));
    }
    Ok(Outcome::fails(Method::Symbolic, Strength::Proof, 3)
        .with_finding(Finding::Appendix { text: detail })
        .with_counterexample(Counterexample {
            lhs: "max over θ of h_2^cr".into(),
            rhs: "0".into(),
            lhs_value: Some(crate::digits::significant(h, crate::digits::POINT)),
            rhs_value: Some("0".into()),
            point: describe_point(&at),
            ..Counterexample::default()
        }))
}

pub(super) fn b_positive(p: &Params, d: &Derivation) -> Outcome {
    let b = acoustic::b_scalar(p, &d.tangent.m_ep);
    let n2 = &p.var(p.n_1).pow(2) + &p.var(p.n_2).pow(2);
    let expected = &(&(&RatFunc::int(4) * &p.var(p.g)) * &p.var(p.r_g).pow(2)) * &n2;
    if let Some(certificate) = Certificate::rational_functions_equal(&b, &expected) {
        Outcome::proved(Method::Symbolic, 1, certificate).with_finding(Finding::Appendix { text: format!(
            "B = {} exactly (F_i = 0 at the state, so M^(ep) = M^(el) = 4 G R_g² δ_ij); on n·n = 1, B = 4 G R_g² > 0 for \
             G, R_g > 0: a jump in the curvature rate cannot satisfy B [K] = 0",
            p.display(&b)
        ) })
    } else {
        Outcome::undecided(Method::Symbolic, 1).with_finding(Finding::Appendix {
            text: format!(
                "undecided: B = {} is not 4 G R_g² n·n; its sign is not established",
                p.display(&b)
            ),
        })
    }
}
