//! Section 6: `no-band-without-rolling` and `thickness-decreases`, decided exactly with
//! Sturm sequences.

use super::*;

/// (54)'s A² as numerator and denominator polynomials in f_r.
pub(super) fn eq54_in_f(p: &Params, d: &Derivation) -> Result<(UniPoly, UniPoly), String> {
    let num = UniPoly::from_poly(d.a2_eq54.numerator(), p.f_r)
        .ok_or("(54) is not a function of f_r alone")?;
    let den = UniPoly::from_poly(d.a2_eq54.denominator(), p.f_r)
        .ok_or("(54) is not a function of f_r alone")?;
    Ok((num, den))
}

pub(super) fn no_band_without_rolling(p: &Params, d: &Derivation) -> Result<Outcome, String> {
    let (num, den) = eq54_in_f(p, d)?;
    let zero = Rational::int(0);
    let a2_at_0 = num
        .eval(&zero)
        .checked_div(&den.eval(&zero))
        .ok_or("(54) has a pole at f_r = 0")?;
    let pos = (Bound::At(zero.clone()), Bound::PlusInfinity);
    let f_is_zero = |v| {
        debug_assert_eq!(v, p.f_r);
        Rational::int(0)
    };
    let certificate = (|| {
        let at_0 = Certificate::value(&d.a2_eq54, &f_is_zero, &zero)?;
        let num_free = Certificate::no_root(&num, &pos.0, &pos.1, "f_r > 0")?;
        let den_free = Certificate::no_root(&den, &pos.0, &pos.1, "f_r > 0")?;
        Some(at_0.and(num_free).and(den_free))
    })();
    let derived_at_0 = d
        .a2_printed_balance
        .substitute(p.f_r, &RatFunc::int(0))
        .and_then(|x| x.substitute(p.h_2, &RatFunc::int(0)))
        .ok_or("pole")?;
    Ok(proved_or_fails(certificate, 2).with_finding(Finding::Appendix { text: format!(
        "(54): A² = {} is 0 at f_r = 0 ({a2_at_0}) with a nonzero denominator, and its numerator and denominator have no \
         root for f_r > 0 (Sturm), so A² > 0 there, A → 0 and d_B/R_g = π/A → ∞ as f_r → 0; the A² derived from the \
         Appendix as printed is {} at f_r = 0, h_2 = 0, so it agrees",
        p.display(&d.a2_eq54),
        p.display(&derived_at_0)
    ) }))
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
    /// The kernel's facts behind "increasing" on (0, ∞) (`Holds`) or on (0, lo] with
    /// lo the isolating interval's lower end (`Conditional`).
    pub certificate: Option<Certificate>,
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
    // Increasing on (0, upto]: the slope's denominator has no root on (0, ∞), its
    // numerator none on (0, upto] and is positive at `tiny` inside it.
    let increasing_up_to = |upto: Bound, interval: &str| {
        let den_free = Certificate::no_root(&den, &pos.0, &pos.1, "f_r > 0")?;
        let num_free = Certificate::no_root(&num, &pos.0, &upto, interval)?;
        let start = Certificate::positive_at(&num, &tiny)?;
        Some(den_free.and(num_free).and(start))
    };
    let certificate = match roots.first() {
        _ if !positive(&tiny) => None,
        None => increasing_up_to(Bound::PlusInfinity, "f_r > 0"),
        Some((lo, _)) => increasing_up_to(Bound::At(lo.clone()), &format!("0 < f_r ≤ {lo}")),
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
        certificate,
    })
}

pub(super) fn thickness_decreases(p: &Params, d: &Derivation) -> Result<Outcome, String> {
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
    let out = match (verdict, m.certificate.clone()) {
        (Verdict::Holds, Some(c)) => Outcome::proved(Method::Symbolic, 2, c),
        (Verdict::Conditional, domain) => Outcome::conditional(Method::Symbolic, 2, domain),
        (Verdict::Fails, _) => Outcome::fails(Method::Symbolic, Strength::Proof, 2),
        _ => Outcome::undecided(Method::Symbolic, 2),
    };
    let mut out = out.with_finding(Finding::Appendix { text: format!(
        "d_B = π/A decreases where A² of (54) increases; d(A²)/df_r = {}; {domain}; beyond f*, A² decreases and d_B grows \
         again; for the A² derived from the Appendix, {} = {}, \"d_B decreases as f_r grows\" {} for every f_r > 0 (K = 2, \
         h^C = 1/2, h_2 = 0)",
        p.display(slope),
        "A²",
        p.display(&derived),
        if derived_verdict == Verdict::Holds { "holds" } else { "does not hold" }
    ) });
    if verdict == Verdict::Conditional {
        out = out.with_counterexample(Counterexample {
            lhs: "d_B/R_g at f_r = 1".into(),
            rhs: "d_B/R_g at f_r = 2".into(),
            lhs_value: Some(crate::digits::significant(db(&a1), crate::digits::VALUE)),
            rhs_value: Some(crate::digits::significant(db(&a2v), crate::digits::VALUE)),
            point: BTreeMap::from([("f_r".to_owned(), "1 → 2".to_owned())]),
            ..Counterexample::default()
        });
    }
    Ok(out)
}
