//! Appendix A: the derived expressions (snapshot-tested), agreement of the exact and
//! floating-point routes, and evidence that each step refutes wrong inputs.

use cosserat_check::kernel::{gcd, Poly, RatFunc, Rational, VarTable};
use cosserat_check::model::acoustic::{self, Contraction};
use cosserat_check::model::shear_band::{self, MomentLaw};
use cosserat_check::model::tangent::{self, ShearSign, YieldGradient};
use cosserat_check::model::{fig6, ExactPoint, Params, Point};
use cosserat_check::strategy::appendix::ROUTE_TOL;

/// Central-difference step and tolerance of the yield-gradient route.
const FD_STEP: f64 = 1e-6;
const FD_TOL: f64 = 1e-6;

/// The second route of the Rust model's yield gradients, which the elastoplastic steps
/// still use (`appA-yield-gradients` itself is decided from the derivation file): the
/// exact Q and F against num-dual gradients and central differences of an
/// independently written F₂, at states of both signs of τ.
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
fn gradient_residuals(
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

fn snapshot(name: &str, value: String) {
    insta::with_settings!({
        snapshot_path => concat!(env!("CARGO_MANIFEST_DIR"), "/snapshots"),
        prepend_module_to_snapshot => false,
    }, {
        insta::assert_snapshot!(name, value);
    });
}

fn derivation() -> (Params, shear_band::Derivation) {
    let p = Params::new();
    let d = shear_band::derive(&p, ShearSign::Positive).expect("the Appendix derives");
    (p, d)
}

#[test]
fn derived_expressions_are_snapshotted() {
    let (p, d) = derivation();
    let mut dep = String::new();
    for (a, row) in d.tangent.d_ep.iter().enumerate() {
        for (b, x) in row.iter().enumerate() {
            let (i, j) = tangent::POSITIONS[a];
            let (k, l) = tangent::POSITIONS[b];
            dep.push_str(&format!("D^(ep)_{i}{j}{k}{l} = {}\n", p.display(x)));
        }
    }
    dep.push_str(&format!(
        "H = Q D Q + F M F + h_2 = {}\nM^(ep) = diag({}, {})\n",
        p.display(&d.tangent.hardening_denominator),
        p.display(&d.tangent.m_ep[0][0]),
        p.display(&d.tangent.m_ep[1][1])
    ));
    snapshot("appendix__elastoplastic_tangent", dep);
    let paper_values = |f: &RatFunc| {
        f.substitute(p.h_c, &RatFunc::constant(Rational::ratio(1, 2).unwrap()))
            .and_then(|x| x.substitute(p.h_2, &RatFunc::int(0)))
            .unwrap()
    };
    let mut a2 = String::new();
    for (name, f) in [
        (
            "following the Appendix as printed, (60) included",
            &d.a2_printed_balance,
        ),
        (
            "with the balance law derived from (2)-(3)",
            &d.a2_derived_balance,
        ),
        ("by the printed (61) with the derived D^(ep)", &d.a2_eq61),
        ("eq. (54)", &d.a2_eq54),
    ] {
        a2.push_str(&format!(
            "A² {name}:\n  {}\n  at h^C = 1/2, h_2 = 0: {}\n  LaTeX: {}\n",
            p.display(f),
            p.display(&paper_values(f)),
            p.latex(f)
        ));
    }
    // Relaxing σ_11 = σ_22 (t = tan(α/2), σ_11 − σ_22 = 2ρ cos α, τ = ρ sin α), for the
    // material ν = 1/4 (K = 2), h^C = 1/2, h_2 = 0, G = R_g = 1.
    let material = ExactPoint {
        f_r: Rational::int(0),
        k: Rational::int(2),
        g: Rational::int(1),
        h_c: Rational::ratio(1, 2).unwrap(),
        h_2: Rational::int(0),
        r_g: Rational::int(1),
    };
    let rotated = shear_band::a_squared_rotated(&p, &material).unwrap();
    let at_t1 = rotated.substitute(p.t, &RatFunc::int(1)).unwrap();
    let fixed = d
        .a2_printed_balance
        .fix(&|v| (v != p.f_r).then(|| material.value(&p, v)))
        .unwrap();
    assert_eq!(at_t1, fixed, "t = 1 is the Appendix's state");
    // The nalgebra route at rotated states: num-dual gradient at σ_11 − σ_22 = 2ρ cos α,
    // τ = ρ sin α, ρ = −f_r σ.
    for (f_r, t) in [(0.3, 0.0), (1.0, 0.5), (2.0, 3.0)] {
        let (alpha, sigma) = (2.0 * f64::atan(t), -1.5);
        let rho = -f_r * sigma;
        let state = [
            sigma + rho * alpha.cos(),
            sigma - rho * alpha.cos(),
            rho * alpha.sin(),
            rho * alpha.sin(),
            0.0,
            0.0,
        ];
        let pt = Point {
            f_r,
            k: 2.0,
            g: 1.0,
            h_c: 0.5,
            h_2: 0.0,
            r_g: 1.0,
        };
        let grad = tangent::yield_gradient_dual(state, f_r, 1.0);
        let d_ep = tangent::elastoplastic_f64_with(&pt, &grad);
        let float = shear_band::a_squared_f64_from(&d_ep, &pt, 1.0, -1.0).unwrap();
        let exact = rotated.eval_f64(&|v| if v == p.t { t } else { f_r });
        assert!(
            (exact - float).abs() <= 1e-9 * exact.abs().max(1.0),
            "t = {t}: {exact} vs {float}"
        );
    }
    a2.push_str(&format!(
        "A² following the Appendix as printed, with σ_11 ≠ σ_22 (t = tan(α/2); K = 2, h^C = 1/2, h_2 = 0):\n  {}\n  at t = 1: {}\n",
        p.display(&rotated),
        p.display(&at_t1)
    ));
    snapshot("appendix__a_squared", a2);
    let h2cr =
        acoustic::critical_hardening(&p, &d.tangent.d_ep, Contraction::GradientIndices).unwrap();
    snapshot(
        "appendix__acoustic",
        format!(
            "h_2^cr(n) = {}\nB = {}\n",
            p.display(&h2cr),
            p.display(&acoustic::b_scalar(&p, &d.tangent.m_ep))
        ),
    );
}

#[test]
fn printed_contraction_gives_the_same_critical_hardening() {
    let (p, d) = derivation();
    let a =
        acoustic::critical_hardening(&p, &d.tangent.d_ep, Contraction::GradientIndices).unwrap();
    let b = acoustic::critical_hardening(&p, &d.tangent.d_ep, Contraction::AsPrinted).unwrap();
    assert_eq!(a, b);
}

#[test]
fn exact_and_float_routes_agree_on_a_squared_and_critical_hardening() {
    let p = Params::new();
    for shear in [ShearSign::Positive, ShearSign::Negative] {
        let d = shear_band::derive(&p, shear).unwrap();
        let h2cr = acoustic::critical_hardening(&p, &d.tangent.d_ep, Contraction::GradientIndices)
            .unwrap();
        for (k, f_r) in [0.05, 0.4, 1.0, 2.7].into_iter().enumerate() {
            let pt = Point {
                f_r,
                k: [1.0, 1.7, 3.0, 10.0][k],
                g: [1.0, 0.3, 2.0, 5.0][k],
                h_c: [0.5, 0.2, 0.9, 0.5][k],
                h_2: [0.0, 0.1, 0.5, 2.0][k],
                r_g: [1.0, 0.5, 2.0, 1.0][k],
            };
            for (law, a, b) in [
                (&d.a2_printed_balance, 1.0, -1.0),
                (&d.a2_derived_balance, 1.0, 1.0),
            ] {
                let exact = law.eval_f64(&|v| pt.value(&p, v));
                let float = shear_band::a_squared_f64(&pt, shear, a, b).unwrap();
                assert!(
                    (exact - float).abs() <= ROUTE_TOL * exact.abs().max(1.0),
                    "{exact} vs {float}"
                );
            }
            for theta in [0.0, 0.3, 1.2, 2.5] {
                let exact = h2cr.eval_f64(&|v| {
                    if v == p.n_1 {
                        -f64::sin(theta)
                    } else if v == p.n_2 {
                        f64::cos(theta)
                    } else {
                        pt.value(&p, v)
                    }
                });
                let float =
                    acoustic::critical_hardening_f64(&Point { h_2: 0.0, ..pt }, shear, theta);
                assert!(
                    (exact - float).abs() <= 1e-9 * exact.abs().max(1.0),
                    "θ = {theta}: {exact} vs {float}"
                );
            }
        }
    }
}

/// The exact gradient with component `k` (0..3: Q, 4..5: F) replaced by `value`, or
/// Q_11 and Q_12 swapped.
fn mutated_gradient(
    p: &Params,
    s: ShearSign,
    k: usize,
    value: &dyn Fn(&YieldGradient) -> RatFunc,
    swap: bool,
) -> Result<YieldGradient, String> {
    let mut g = tangent::yield_gradient_exact(p, s)?;
    let v = value(&g);
    if swap {
        g.q.swap(0, 2);
    } else if k < 4 {
        g.q[k] = v;
    } else {
        g.f[k - 4] = v;
    }
    Ok(g)
}

#[test]
fn a_wrong_yield_gradient_is_refuted() {
    let p = Params::new();
    let (exact, fd, n) = gradient_residuals(&p, &|s| tangent::yield_gradient_exact(&p, s)).unwrap();
    assert!(exact <= ROUTE_TOL && fd <= FD_TOL && n > 100);
    // Mutants: a changed coefficient (Q_12 = 1), a flipped sign (Q_11 = −f_r/2), a
    // dropped term (Q_22 = 0), swapped components (Q_11 ↔ Q_12), a nonzero F.
    type Replacement = Box<dyn Fn(&YieldGradient) -> RatFunc>;
    let cases: Vec<(usize, Replacement, bool)> = vec![
        (2, Box::new(|_| RatFunc::int(1)), false),
        (0, Box::new(|g| -&g.q[0]), false),
        (1, Box::new(|_| RatFunc::int(0)), false),
        (0, Box::new(|_| RatFunc::int(0)), true),
        (
            4,
            Box::new(|_| RatFunc::constant(Rational::ratio(1, 10).unwrap())),
            false,
        ),
    ];
    for (k, value, swap) in cases {
        let (worst, _, _) =
            gradient_residuals(&p, &|s| mutated_gradient(&p, s, k, value.as_ref(), swap)).unwrap();
        assert!(worst > ROUTE_TOL, "mutant {k} (swap {swap}) survived");
    }
}

#[test]
fn a_squared_depends_on_every_input_of_the_elimination() {
    let (p, d) = derivation();
    // The sign of the moment balance flips A²; a changed factor changes it.
    let t = &d.tangent;
    let flipped = shear_band::a_squared(
        &p,
        t,
        &MomentLaw {
            a: Rational::int(1),
            b: Rational::int(1),
        },
    )
    .unwrap();
    assert_eq!(flipped, -&d.a2_printed_balance);
    let doubled = shear_band::a_squared(
        &p,
        t,
        &MomentLaw {
            a: Rational::int(1),
            b: Rational::int(-2),
        },
    )
    .unwrap();
    assert_ne!(doubled, d.a2_printed_balance);
    // A mutated D^(ep) entry (D_(12)(22) sign flipped) changes A².
    let mut t2 = t.clone();
    t2.d_ep[2][1] = -&t2.d_ep[2][1];
    let mutated = shear_band::a_squared(&p, &t2, &shear_band::printed_moment_law()).unwrap();
    assert_ne!(mutated, d.a2_printed_balance);
    // A mutant of (54) with one coefficient changed is a different function.
    let mut names = VarTable::new();
    let _ = names.intern("unused");
    let f2 = p.var(p.f_r).pow(2);
    let mutant54 =
        (&(&RatFunc::int(15) * &f2) / &(&RatFunc::int(1) + &(&RatFunc::int(8) * &f2))).unwrap();
    assert_ne!(mutant54, d.a2_eq54);
}

#[test]
fn gcd_of_random_products_recovers_the_common_factor() {
    // Deterministic pseudo-random polynomials in three variables.
    let mut names = VarTable::new();
    let vars: Vec<Poly> = ["x", "y", "z"]
        .iter()
        .map(|n| Poly::var(names.intern(n)))
        .collect();
    let mut state = 12345u64;
    let mut next = || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((state >> 33) % 7) as i64 - 3
    };
    let mut random_poly = |terms: usize| {
        let mut p = Poly::constant(Rational::int(next().max(1)));
        for _ in 0..terms {
            let mut t = Poly::constant(Rational::int(next()));
            for v in &vars {
                t = &t * &v.pow((next() + 3) as u32 % 3);
            }
            p = &p + &t;
        }
        p
    };
    for _ in 0..25 {
        let g = random_poly(3);
        let a = random_poly(3);
        let b = random_poly(3);
        let h = gcd::gcd(&(&g * &a), &(&g * &b));
        // The gcd is a multiple of g and divides both products exactly.
        assert!(gcd::divide_exact(&h, &g).is_some() || g.as_constant().is_some());
        assert!(gcd::divide_exact(&(&g * &a), &h).is_some());
        assert!(gcd::divide_exact(&(&g * &b), &h).is_some());
        // After dividing out the gcd nothing common is left.
        let (ra, rb) = (
            gcd::divide_exact(&(&g * &a), &h).unwrap(),
            gcd::divide_exact(&(&g * &b), &h).unwrap(),
        );
        assert_eq!(gcd::gcd(&ra, &rb), Poly::constant(Rational::int(1)));
    }
}

#[test]
fn figure_columns_follow_the_two_routes() {
    let (p, d) = derivation();
    let rows = fig6::rows(&p, &d);
    assert_eq!(rows.len(), 60);
    for r in &rows {
        let paper_a2 = 16.0 * r.f_r.powi(2) * (1.0 + 2.0 * r.f_r.powi(2))
            / (1.0 + 8.0 * r.f_r.powi(2) * (1.0 + 3.0 * r.f_r.powi(2)));
        let expected = std::f64::consts::PI / paper_a2.sqrt();
        assert!((r.paper.unwrap() - expected).abs() <= 1e-12 * expected);
        for (k, (nu, _)) in fig6::POISSON.iter().enumerate() {
            let a2 = shear_band::a_squared_f64(
                &Point::figure(r.f_r, *nu),
                ShearSign::Positive,
                1.0,
                -1.0,
            )
            .unwrap();
            let expected = std::f64::consts::PI / a2.sqrt();
            assert!((r.derived[k].unwrap() - expected).abs() <= 1e-9 * expected);
        }
    }
    // Grid values as written; other values to 12 significant digits, no trailing zeros.
    assert_eq!(fig6::decimal(0.05), "0.05");
    assert_eq!(fig6::decimal(3.0), "3");
    assert_eq!(fig6::decimal(1.25), "1.25");
    assert_eq!(fig6::decimal(15.825916248913), "15.8259162489");
    assert_eq!(fig6::decimal(66.12287614497), "66.122876145");
    assert_eq!(fig6::decimal(0.0), "0");
    let csv = fig6::csv(&rows);
    let grid: Vec<&str> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').next().unwrap())
        .collect();
    assert_eq!(&grid[..4], ["0.05", "0.1", "0.15", "0.2"]);
    assert_eq!(grid[59], "3");
}
