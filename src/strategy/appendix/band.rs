//! `eq61`, `boundary-modes` (eq. 62) and `eq54`: A² and the band thickness.

use super::*;

pub(super) fn eq61(p: &Params, d: &Derivation, d_neg: &Derivation) -> Result<Outcome, String> {
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
    let certificate = Certificate::rational_functions_equal(&d.a2_eq61, &d.a2_printed_balance);
    let equal = certificate.is_some();
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
    let mut out = proved_or_fails(certificate, 1).with_finding(Finding::Appendix { text: detail });
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

pub(super) fn boundary_modes() -> Outcome {
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
    // The kernel verifies the two modes: with s = sin(A d_B), c = cos(A d_B) the
    // conditions −C s + S c = 0 and C s + S c = 0 read [[−s, c], [s, c]] (C, S) = 0;
    // at A d_B = π/2 (s = 1, c = 0) (C, S) = (0, 1) solves them (antisymmetric), at
    // A d_B = π (s = 0, c = −1) (C, S) = (1, 0) does (symmetric).
    let q = Rational::int;
    let certificate = (first_symmetric == Some(2))
        .then(|| {
            let quarter =
                Certificate::null_vector(&[vec![q(-1), q(0)], vec![q(1), q(0)]], &[q(0), q(1)])?;
            let half =
                Certificate::null_vector(&[vec![q(0), q(-1)], vec![q(0), q(-1)]], &[q(1), q(0)])?;
            Some(quarter.and(half))
        })
        .flatten();
    proved_or_fails(certificate, modes.len()).with_finding(Finding::Appendix { text: format!(
        "w_3 = C cos(A x_2) + S sin(A x_2) + const; μ_23 = M_22 w_3' = 0 at x_2 = ±d_B has a nonzero (C, S) exactly when \
         sin(2 A d_B) = 0: {}; d_B/R_g = π/A is the first symmetric mode (w_3 even about the band's centre, C ≠ 0); \
         the first antisymmetric mode would give d_B/R_g = π/(2A)",
        listed.join(", ")
    ) })
}

pub(super) fn eq54(p: &Params, d: &Derivation) -> Result<Outcome, String> {
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
    let certificate = Certificate::rational_functions_equal(&d.a2_printed_balance, &d.a2_eq54);
    let same = certificate.is_some();
    // With the derived balance law A² is minus the printed-route A²; that one is positive
    // for positive parameters when every coefficient of its numerator and denominator is.
    let positive_coefficients = |q: &Poly| !q.is_zero() && q.terms().all(|(_, c)| !c.is_negative());
    let derived_sign = if d.a2_derived_balance == -&d.a2_printed_balance
        && positive_coefficients(d.a2_printed_balance.numerator())
        && positive_coefficients(d.a2_printed_balance.denominator())
    {
        "< 0 for all positive parameters (minus a ratio of polynomials with positive \
         coefficients), so A is not real and w_3 is exponential (no periodic band profile)"
    } else {
        "(its sign is not established here)"
    };
    // The assumption σ_11 = σ_22 relaxed, at the counterexample material.
    let rotated = shear_band::a_squared_rotated(p, &at)?;
    let at_zero = |t: i64| {
        rotated
            .fix(&|v| {
                if v == p.f_r {
                    Some(Rational::int(0))
                } else if v == p.t {
                    Some(Rational::int(t))
                } else {
                    None
                }
            })
            .and_then(|x| x.as_constant())
            .ok_or("a pole at f_r = 0")
    };
    let relaxed = format!(
        "relaxing σ_11 = σ_22 (σ_11 − σ_22 = 2ρ cos α, τ = ρ sin α, t = tan(α/2), at K = 2, h^C = 1/2, h_2 = 0): \
         A² = {}, which at f_r = 0 is {} for t = 1 (the state above) but {} for t = 0, so the limit f_r → 0 of Section 6 \
         rests on σ_11 = σ_22",
        p.display(&rotated),
        at_zero(1)?,
        at_zero(0)?
    );
    let parting = if d.a2_printed_balance != d.a2_eq61 {
        "the routes part at (61): eliminating through (58)–(60) as printed and the printed formula (61) already disagree, \
         and (54) equals neither"
    } else {
        "the routes part at (54): (61) agrees with the elimination but not with (54)"
    };
    let detail = format!(
        "derived by following the Appendix as printed ((55) with its indices fixed, (58)–(60) as printed, y in units of R_g): \
         A² = {}, which with h^C = 1/2, h_2 = 0 is {}; it depends on K (ν) and h^C, (54) does not; {parting}; with the \
         balance law derived from (2)–(3) instead of (60), A² = {} {derived_sign}; nalgebra route at the point: \
         {float:.12}; {relaxed}",
        p.display(&d.a2_printed_balance),
        p.display(&paper_values),
        p.display(&d.a2_derived_balance)
    );
    let mut out = proved_or_fails(certificate, 1).with_finding(Finding::Appendix { text: detail });
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
