//! Appendix A from its derivation files (`derivations/A-3-shear-band.toml`): the
//! derived expressions (snapshot-tested), and the independent floating-point route —
//! num-dual gradients of a separately written F₂, nalgebra matrices, an LU solve, a
//! bisection for the critical hardening — against the file's exact derivation.

mod route;

use cosserat_check::algebra::{gcd, RatFunc};
use cosserat_check::check::probe::{curve_values, Probe};
use cosserat_check::derivation::load_files;
use cosserat_check::kernel::{Poly, Rational, VarTable};
use route::{Point, ShearSign};

/// Largest relative disagreement allowed between the file's exact derivation evaluated
/// in `f64` and the independent floating-point route.
const ROUTE_TOL: f64 = 1e-9;

/// Central-difference step and tolerance of the yield-gradient route.
const FD_STEP: f64 = 1e-6;
const FD_TOL: f64 = 1e-6;

const FILE: &str = "derivations/A-3-shear-band.toml";

fn text() -> String {
    std::fs::read_to_string(FILE).expect("the Appendix file")
}

fn strings(items: &[&str]) -> Vec<String> {
    items.iter().map(|s| (*s).to_owned()).collect()
}

/// The box every probe of the file needs: the square root of F₂ takes its sign there.
const GIVEN: [&str; 2] = ["f_r > 0", "sig < 0"];

/// `expression` of the Appendix file, exactly, under `assume`.
fn exact(expression: &str, assume: &[&str]) -> (RatFunc, VarTable) {
    Probe::new(
        FILE,
        &text(),
        expression,
        &strings(assume),
        &strings(&GIVEN),
    )
    .unwrap_or_else(|e| panic!("{expression}: {e}"))
    .exact()
    .unwrap_or_else(|e| panic!("{expression}: {e}"))
}

/// Evaluates `f` at the named values (every variable of `f` must be named).
fn at(f: &(RatFunc, VarTable), values: &[(&str, f64)]) -> f64 {
    let (f, names) = f;
    f.eval_f64(&|v| {
        let name = names.name(v);
        values
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, x)| *x)
            .unwrap_or_else(|| panic!("no value for {name}"))
    })
}

fn material(pt: &Point) -> Vec<(&'static str, f64)> {
    vec![
        ("f_r", pt.f_r),
        ("K", pt.k),
        ("G", pt.g),
        ("hC", pt.h_c),
        ("h2", pt.h_2),
        ("R_g", pt.r_g),
    ]
}

/// The shear sense of the state u = ±1 (τ = σ_12 = σ_21 of sign ±1).
fn state(shear: ShearSign) -> &'static str {
    match shear {
        ShearSign::Positive => "u = 1",
        ShearSign::Negative => "u = -1",
    }
}

fn snapshot(name: &str, value: String) {
    insta::with_settings!({
        snapshot_path => concat!(env!("CARGO_MANIFEST_DIR"), "/snapshots"),
        prepend_module_to_snapshot => false,
    }, {
        insta::assert_snapshot!(name, value);
    });
}

fn shown((f, names): &(RatFunc, VarTable)) -> String {
    f.display(names)
}

#[test]
fn derived_expressions_are_snapshotted() {
    let positions = ["11", "22", "12", "21"];
    let mut dep = String::new();
    for (a, pa) in positions.iter().enumerate() {
        for (b, pb) in positions.iter().enumerate() {
            let x = exact(&format!("Dep[{},{}]", a + 1, b + 1), &["u = 1"]);
            dep.push_str(&format!("D^(ep)_{pa}{pb} = {}\n", shown(&x)));
        }
    }
    dep.push_str(&format!(
        "H = Q D Q + F M F + h_2 = {}\nM^(ep) = diag({}, {})\n",
        shown(&exact("H0 + h2", &["u = 1"])),
        shown(&exact("Mep[1,1]", &["u = 1"])),
        shown(&exact("Mep[2,2]", &["u = 1"]))
    ));
    snapshot("appendix__elastoplastic_tangent", dep);
    let mut a2 = String::new();
    for (name, e) in [
        ("following the Appendix as printed, (60) included", "A2"),
        ("with the balance law derived from (2)-(3)", "A2c"),
        ("by the printed (61) with the derived D^(ep)", "A2eq61"),
        ("eq. (54)", "A2eq54"),
    ] {
        let (f, names) = exact(e, &["u = 1"]);
        let paper = exact(e, &["u = 1", "hC = 1/2", "h2 = 0"]);
        a2.push_str(&format!(
            "A² {name}:\n  {}\n  at h^C = 1/2, h_2 = 0: {}\n  LaTeX: {}\n",
            f.display(&names),
            shown(&paper),
            f.latex(&names)
        ));
    }
    let relaxed = exact("A2", &["K = 2", "hC = 1/2", "h2 = 0", "G = 1"]);
    a2.push_str(&format!(
        "A² following the Appendix as printed, with σ_11 ≠ σ_22 (u = tan(α/2); K = 2, h^C = 1/2, h_2 = 0):\n  {}\n",
        shown(&relaxed)
    ));
    snapshot("appendix__a_squared", a2);
    snapshot(
        "appendix__acoustic",
        format!(
            "h_2^cr(n), n = (-2v, 1 - v^2) = {}\nB = {}\n",
            shown(&exact("h2cr", &["u = 1"])),
            shown(&exact(
                "vector(n_i, plane_i)^T Mep vector(n_i, plane_i)",
                &["u = 1"]
            ))
        ),
    );
}

#[test]
fn printed_contraction_gives_the_same_acoustic_determinant() {
    // |D_ijkl n_j n_l| as printed against n_i D_ijkl n_k: the same determinant here.
    let (d, _) = exact(
        "det(matrix(n_j Dept_ijkl n_l, plane_i, plane_k)) - det(Ac)",
        &["u = 1"],
    );
    assert_eq!(d, RatFunc::int(0));
}

#[test]
fn exact_and_float_routes_agree_on_a_squared_and_critical_hardening() {
    for shear in [ShearSign::Positive, ShearSign::Negative] {
        let a2 = exact("A2", &[state(shear)]);
        let a2c = exact("A2c", &[state(shear)]);
        let h2cr = exact("h2cr", &[state(shear)]);
        for (k, f_r) in [0.05, 0.4, 1.0, 2.7].into_iter().enumerate() {
            let pt = Point {
                f_r,
                k: [1.0, 1.7, 3.0, 10.0][k],
                g: [1.0, 0.3, 2.0, 5.0][k],
                h_c: [0.5, 0.2, 0.9, 0.5][k],
                h_2: [0.0, 0.1, 0.5, 2.0][k],
                r_g: [1.0, 0.5, 2.0, 1.0][k],
            };
            for (law, a, b) in [(&a2, 1.0, -1.0), (&a2c, 1.0, 1.0)] {
                let exact = at(law, &material(&pt));
                let float = route::a_squared(&pt, shear, a, b).unwrap();
                assert!(
                    (exact - float).abs() <= ROUTE_TOL * exact.abs().max(1.0),
                    "{exact} vs {float}"
                );
            }
            for theta in [0.0f64, 0.3, 1.2, 2.5] {
                // n = (−2v, 1 − v²) is (1 + v²)(−sin θ, cos θ) at v = tan(θ/2).
                let mut values = material(&Point { h_2: 0.0, ..pt });
                values.push(("v", (theta / 2.0).tan()));
                let exact = at(&h2cr, &values);
                let float = route::critical_hardening(&Point { h_2: 0.0, ..pt }, shear, theta);
                assert!(
                    (exact - float).abs() <= ROUTE_TOL * exact.abs().max(1.0),
                    "θ = {theta}: {exact} vs {float}"
                );
            }
        }
    }
}

#[test]
fn the_relaxed_state_agrees_with_the_float_route() {
    // σ_11 − σ_22 = 2ρ cos α, τ = ρ sin α, ρ = −f_r σ, u = tan(α/2), at K = 2,
    // h^C = 1/2, h_2 = 0, G = R_g = 1.
    let relaxed = exact("A2", &["K = 2", "hC = 1/2", "h2 = 0", "G = 1", "R_g = 1"]);
    for (f_r, u) in [(0.3, 0.0), (1.0, 0.5), (2.0, 3.0)] {
        let (alpha, sigma) = (2.0 * f64::atan(u), -1.5);
        let rho = -f_r * sigma;
        let components = [
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
        let grad = route::yield_gradient_dual(components, f_r, 1.0);
        let d_ep = route::elastoplastic_with(&pt, &grad);
        let float = route::a_squared_from(&d_ep, &pt, 1.0, -1.0).unwrap();
        let exact = at(&relaxed, &[("f_r", f_r), ("u", u)]);
        assert!(
            (exact - float).abs() <= ROUTE_TOL * exact.abs().max(1.0),
            "u = {u}: {exact} vs {float}"
        );
    }
}

#[test]
fn the_interpreter_agrees_with_the_exact_derivation() {
    // The same definitions by the claim's floating-point interpreter (num-dual
    // gradients, f64 matrices): the route that confirms every counterexample.
    // Every parameter fixed by assumption (exact rationals), so the exact side is a
    // number; u and v away from the special states.
    let values = [
        "f_r = 7/10",
        "K = 5/2",
        "G = 13/10",
        "hC = 2/5",
        "h2 = 1/5",
        "R_g = 4/5",
        "sig = -11/10",
        "u = 3/5",
        "v = -3/10",
    ];
    for e in ["A2", "A2eq61", "h2cr", "det(Ac)", "q[3]", "Dep[3,2]"] {
        let probe = Probe::new(FILE, &text(), e, &strings(&values), &strings(&GIVEN)).unwrap();
        let float = probe.at(&[]).unwrap();
        let (f, _) = probe.exact().unwrap();
        let exact = f.eval_f64(&|_| f64::NAN);
        assert!(
            (exact - float).abs() <= ROUTE_TOL * exact.abs().max(1.0),
            "{e}: {exact} vs {float}"
        );
    }
}

/// Expressions probed together share their definitions (D^(ep) is derived once) and
/// give, each, the rational function that probing it alone gives: equal at three
/// rational points by exact evaluation (the variables matched by name, the two
/// evaluations number them differently), and different from each other.
#[test]
fn expressions_probed_together_derive_what_each_derives_alone() {
    let each = ["A2", "A2c", "A2eq61", "A2eq54", "Dep[3,2]"];
    let together = Probe::of_each(FILE, &text(), &each, &strings(&["u = 1"]), &strings(&GIVEN))
        .unwrap()
        .exact_each()
        .unwrap();
    assert_eq!(together.0.len(), each.len());
    // Three rational points, one row each, in the order of `names`.
    let names = ["f_r", "K", "G", "hC", "h2", "R_g", "sig"];
    let points: [[(i64, i64); 7]; 3] = [
        [(7, 10), (5, 2), (13, 10), (2, 5), (1, 5), (4, 5), (-11, 10)],
        [(3, 2), (9, 4), (1, 3), (-1, 7), (5, 3), (2, 1), (-1, 4)],
        [(1, 9), (11, 3), (8, 5), (3, 11), (1, 13), (1, 6), (-7, 3)],
    ];
    let value = |f: &RatFunc, table: &VarTable, point: &[(i64, i64); 7]| {
        f.eval(&|v| {
            let name = table.name(v);
            let k = names
                .iter()
                .position(|n| *n == name)
                .unwrap_or_else(|| panic!("no value for {name}"));
            let (p, q) = point[k];
            Rational::ratio(p, q).expect("a nonzero denominator")
        })
        .expect("no pole at the point")
    };
    for (k, e) in each.iter().enumerate() {
        let alone = exact(e, &["u = 1"]);
        for point in &points {
            assert_eq!(
                value(&together.0[k], &together.1, point),
                value(&alone.0, &alone.1, point),
                "{e} probed with the others"
            );
        }
        if k > 0 {
            assert_ne!(
                value(&together.0[k], &together.1, &points[0]),
                value(&together.0[k - 1], &together.1, &points[0]),
                "{e} and {} are different expressions",
                each[k - 1]
            );
        }
    }
}

/// The largest differences (file vs num-dual, num-dual vs central differences) of the
/// yield gradient (Q_11, Q_22, Q_12, Q_21, F_13, F_23) over states of both shear senses;
/// `mutate` changes the file's values before they are compared.
fn gradient_residuals(mutate: &dyn Fn(&mut [f64; 6])) -> (f64, f64, usize) {
    let (mut worst_exact, mut worst_fd, mut n) = (0.0f64, 0.0f64, 0);
    let entries = ["q[1]", "q[2]", "q[3]", "q[4]", "f[1]", "f[2]"];
    for shear in [ShearSign::Positive, ShearSign::Negative] {
        let file: Vec<(RatFunc, VarTable)> =
            entries.iter().map(|e| exact(e, &[state(shear)])).collect();
        for f_r in [0.05, 0.3, 0.5, 1.0, 2.0, 3.0] {
            for sigma in [-1.0, -2.5] {
                for r_g in [1.0, 0.4] {
                    let x = route::state_components(sigma, f_r, shear);
                    let dual = route::yield_gradient_dual(x, f_r, r_g);
                    let mut closed: [f64; 6] = std::array::from_fn(|k| {
                        file[k].0.eval_f64(&|v| match file[k].1.name(v) {
                            "f_r" => f_r,
                            "R_g" => r_g,
                            other => panic!("Q depends on {other}"),
                        })
                    });
                    mutate(&mut closed);
                    for k in 0..6 {
                        worst_exact = worst_exact.max((dual[k] - closed[k]).abs());
                        let (mut xp, mut xm) = (x, x);
                        xp[k] += FD_STEP;
                        xm[k] -= FD_STEP;
                        let fd = (route::rolling_yield(&xp, f_r, r_g)
                            - route::rolling_yield(&xm, f_r, r_g))
                            / (2.0 * FD_STEP);
                        worst_fd = worst_fd.max((fd - dual[k]).abs());
                        n += 1;
                    }
                }
            }
        }
    }
    (worst_exact, worst_fd, n)
}

/// A change to the yield gradient (Q_11, Q_22, Q_12, Q_21, F_13, F_23).
type Mutation = dyn Fn(&mut [f64; 6]);

#[test]
fn a_wrong_yield_gradient_is_refuted() {
    let (exact, fd, n) = gradient_residuals(&|_| {});
    assert!(
        exact <= ROUTE_TOL && fd <= FD_TOL && n > 100,
        "{exact} {fd} {n}"
    );
    // Mutants: a changed coefficient (Q_12 = 1), a flipped sign (Q_11 → −Q_11), a
    // dropped term (Q_22 = 0), swapped components (Q_11 ↔ Q_12), a nonzero F.
    let mutants: [&Mutation; 5] = [
        &|g| g[2] = 1.0,
        &|g| g[0] = -g[0],
        &|g| g[1] = 0.0,
        &|g| g.swap(0, 2),
        &|g| g[4] = 0.1,
    ];
    for (k, m) in mutants.iter().enumerate() {
        let (worst, _, _) = gradient_residuals(m);
        assert!(worst > ROUTE_TOL, "mutant {k} survived");
    }
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
fn the_figure_follows_the_float_route() {
    // Fig. 6 as the file's figure table plots it: (54) exactly as printed, and the
    // derived curves against the nalgebra route at ν = 0, 0.25, 0.45.
    let file = load_files(&[FILE]).unwrap().remove(0);
    let fig = file.figures.iter().find(|f| f.id == "fig6").expect("fig6");
    assert_eq!(fig.x.values.len(), 60);
    let columns: Vec<Vec<Option<f64>>> = fig
        .curves
        .iter()
        .map(|c| curve_values(c, &fig.x).unwrap().0)
        .collect();
    for (k, x) in fig.x.values.iter().enumerate() {
        let f_r = x.to_f64();
        let paper_a2 = 16.0 * f_r.powi(2) * (1.0 + 2.0 * f_r.powi(2))
            / (1.0 + 8.0 * f_r.powi(2) * (1.0 + 3.0 * f_r.powi(2)));
        let expected = std::f64::consts::PI / paper_a2.sqrt();
        assert!((columns[0][k].unwrap() - expected).abs() <= 1e-12 * expected);
        for (c, nu) in [0.0, 0.25, 0.45].into_iter().enumerate() {
            let pt = Point {
                f_r,
                k: 1.0 / (1.0 - 2.0 * nu),
                g: 1.0,
                h_c: 0.5,
                h_2: 0.0,
                r_g: 1.0,
            };
            let a2 = route::a_squared(&pt, ShearSign::Positive, 1.0, -1.0).unwrap();
            let expected = std::f64::consts::PI / a2.sqrt();
            let got = columns[c + 1][k].unwrap();
            assert!(
                (got - expected).abs() <= 1e-9 * expected,
                "{got} vs {expected}"
            );
        }
    }
}

#[test]
fn both_routes_find_the_band_at_135_degrees() {
    // At f_r = 1/2, K = 2, h^C = 1/2, G = 1 (appA-band-direction's material) the
    // largest h_2^cr over orientations is −G/6 at θ = 135°, not at θ = 0.
    let pt = Point {
        f_r: 0.5,
        k: 2.0,
        g: 1.0,
        h_c: 0.5,
        h_2: 0.0,
        r_g: 1.0,
    };
    let h2cr = exact("h2cr", &["u = 1"]);
    let by_file = route::maximise_over_orientation(|theta| {
        let mut values = material(&pt);
        values.push(("v", (theta / 2.0).tan()));
        at(&h2cr, &values)
    });
    let by_nalgebra = route::maximise_over_orientation(|theta| {
        route::critical_hardening(&pt, ShearSign::Positive, theta)
    });
    for (theta, h) in [by_file, by_nalgebra] {
        assert!(
            (theta.to_degrees() - 135.0).abs() < 1e-2,
            "θ = {}",
            theta.to_degrees()
        );
        assert!((h + 1.0 / 6.0).abs() < 1e-9, "h = {h}");
    }
}
