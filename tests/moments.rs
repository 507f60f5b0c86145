//! The exact isotropic moments against an independent numeric quadrature.
//!
//! The quadrature is built here from scratch with nalgebra: Gauss–Legendre nodes by
//! the Golub–Welsch method (eigenvalues of the Jacobi matrix), a different algorithm
//! from the Newton iteration used by `eval::quadrature`. On the sphere, an N-point rule
//! in z = cos θ (exact to degree 2N − 1) times M equally spaced φ (exact for
//! trigonometric degree < M) integrates every monomial of degree < min(2N, M)
//! exactly; on the circle, M equally spaced points do.

use approx::assert_relative_eq;
use cosserat_check::kernel::{monomial_moment, Rational};
use nalgebra::{DMatrix, SymmetricEigen};

/// Gauss–Legendre nodes and weights on [−1, 1] (Golub–Welsch).
fn golub_welsch(n: usize) -> Vec<(f64, f64)> {
    let mut j = DMatrix::<f64>::zeros(n, n);
    for k in 1..n {
        let b = k as f64 / ((4 * k * k - 1) as f64).sqrt();
        j[(k - 1, k)] = b;
        j[(k, k - 1)] = b;
    }
    let eig = SymmetricEigen::new(j);
    (0..n)
        .map(|k| (eig.eigenvalues[k], 2.0 * eig.eigenvectors[(0, k)].powi(2)))
        .collect()
}

fn sphere_average(exps: &[u32; 3]) -> f64 {
    let gl = golub_welsch(10);
    let m = 24;
    let mut total = 0.0;
    for (z, w) in gl {
        let r = (1.0 - z * z).sqrt();
        for k in 0..m {
            let phi = 2.0 * std::f64::consts::PI * k as f64 / m as f64;
            let n = [r * phi.cos(), r * phi.sin(), z];
            let v: f64 = n.iter().zip(exps).map(|(x, &e)| x.powi(e as i32)).product();
            total += w / 2.0 / m as f64 * v;
        }
    }
    total
}

fn circle_average(exps: &[u32; 2]) -> f64 {
    let m = 32;
    (0..m)
        .map(|k| {
            let phi = 2.0 * std::f64::consts::PI * k as f64 / m as f64;
            phi.cos().powi(exps[0] as i32) * phi.sin().powi(exps[1] as i32) / m as f64
        })
        .sum()
}

#[test]
fn sphere_moments_match_quadrature_up_to_order_12() {
    let mut compared = 0;
    for a in 0..=12u32 {
        for b in 0..=12 - a {
            for c in 0..=12 - a - b {
                let exact = monomial_moment(3, &[a, b, c]).to_f64();
                assert_relative_eq!(exact, sphere_average(&[a, b, c]), epsilon = 1e-13);
                compared += 1;
            }
        }
    }
    assert_eq!(compared, 455);
}

#[test]
fn circle_moments_match_quadrature_up_to_order_12() {
    for a in 0..=12u32 {
        for b in 0..=12 - a {
            let exact = monomial_moment(2, &[a, b]).to_f64();
            assert_relative_eq!(exact, circle_average(&[a, b]), epsilon = 1e-13);
        }
    }
}

#[test]
fn the_quadrature_is_not_trivially_agreeing() {
    // Guard against a rule that returns 0 for everything: the printed eq. (26) factor
    // 1/3 would give ⟨n_1^4⟩ = 1, the true value is 1/5.
    assert_relative_eq!(sphere_average(&[4, 0, 0]), 0.2, epsilon = 1e-13);
    assert!((sphere_average(&[4, 0, 0]) - 1.0).abs() > 0.5);
    assert_relative_eq!(circle_average(&[2, 2]), 0.125, epsilon = 1e-13);
}

/// ⟨n_{i1} … n_{ik}⟩ for the (0-based) component indices `indices`: eqs. (25), (26)
/// component by component.
fn tensor_moment(dim: usize, indices: &[usize]) -> Rational {
    let mut exps = vec![0u32; dim];
    for &i in indices {
        exps[i] += 1;
    }
    monomial_moment(dim, &exps)
}

#[test]
fn tensor_moments_are_isotropic_forms() {
    // ⟨n_i n_j n_k n_l⟩ = (δδ + δδ + δδ)/15 in 3D and /8 in 2D, every component.
    let d = |a: usize, b: usize| i64::from(a == b);
    for (dim, denom) in [(3usize, 15i64), (2, 8)] {
        for i in 0..dim {
            for j in 0..dim {
                for k in 0..dim {
                    for l in 0..dim {
                        let want = d(i, j) * d(k, l) + d(i, k) * d(j, l) + d(i, l) * d(j, k);
                        assert_eq!(
                            tensor_moment(dim, &[i, j, k, l]),
                            Rational::ratio(want, denom).unwrap()
                        );
                    }
                }
            }
        }
    }
}

/// The isotropic moment of rank 10 in 3D, ⟨n_i n_j … n_t⟩ = (1/10395) Σ over its 945
/// pairings of δ products, as a file whose right side is split into definitions (a
/// side holds at most 1000 tokens), with the constant's denominator `den`.
fn rank_ten_moment(den: u32) -> String {
    use crate::support::pairings::delta_products;
    let letters: Vec<char> = "ijklmpqrst".chars().collect();
    let free: String = letters.iter().collect();
    let terms: Vec<String> = delta_products(&letters);
    assert_eq!(terms.len(), 945);
    let defs: Vec<String> = terms
        .chunks(35)
        .enumerate()
        .map(|(k, c)| format!("\"P{k}_{free} = {}\"", c.join(" + ")))
        .collect();
    let total: Vec<String> = (0..defs.len()).map(|k| format!("P{k}_{free}")).collect();
    let ns: Vec<String> = letters.iter().map(|c| format!("n_{c}")).collect();
    format!(
        "section = \"m\"\ntitle = \"m\"\ndimension = 3\nnormal = \"n\"\ndefine = [{}]\n\
         [[claim]]\nid = \"rank-10\"\nprinted = 'x'\nexpect = \"holds\"\n\
         sides = [\"avg({})\", \"1/{den} ({})\"]\n",
        defs.join(", "),
        ns.join(" "),
        total.join(" + ")
    )
}

#[test]
fn a_wrong_constant_at_rank_ten_is_refuted_at_its_first_component() {
    use cosserat_check::check::decide_claim;
    use cosserat_check::decide::Strength;
    use cosserat_check::derivation::{load_str, Verdict};
    // The symbolic route finds the difference at i = j = … = t = 1 (1/11 against
    // 945/10396) without visiting the other 59,048 index values; the kernel checks the
    // refutation there alone. The identity itself the kernel compares at its 66 orbits
    // (both sides are unchanged by every permutation of the ten letters).
    for (den, verdict) in [(10396, Verdict::Fails), (10395, Verdict::Holds)] {
        let file = load_str("rank-ten.toml", &rank_ten_moment(den)).unwrap();
        let d = decide_claim(&file.claims[0]).unwrap();
        assert_eq!(
            d.outcome.verdict(),
            verdict,
            "1/{den}: {:?}",
            d.outcome.finding
        );
        assert_eq!(d.outcome.strength(), Strength::Proof);
        if verdict == Verdict::Holds {
            assert_eq!(d.outcome.checks, 66);
        }
    }
}
