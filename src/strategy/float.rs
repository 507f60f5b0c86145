//! An independent floating-point route for cross-checking exact verdicts.
//!
//! It shares only the parser and validator with the exact strategy (evaluation is
//! [`super::real`]): no polynomial, no moment formula. Symbols get seeded random values in [−1, 1], the normal is a random
//! unit vector, and `avg(…)` re-evaluates its argument at the nodes of a quadrature
//! rule on the circle (trapezoid, 32 points) or the sphere (8-point Gauss–Legendre in
//! cos θ by Newton iteration × 16 equally spaced φ), exact for polynomials of degree
//! ≤ 15 in n. A disagreement between this route and the exact one is a bug in one of
//! them, and the test suite fails on it.

use super::assume::Parametrisation;
use super::real::{component_pairs, RealEnv};
use super::taylor::{self, TaylorFields};
use crate::algebra::sign::{End, Interval};
use crate::algebra::Tensor;
use crate::derivation::{Check, Strategy, Verdict};
use crate::lang::Decls;
use rustc_hash::FxHashMap as HashMap;

/// Relative tolerance of a float comparison: |l − r| ≤ TOL · (1 + |l| + |r|). Inputs
/// are O(1), expressions have a few hundred operations at most, so rounding stays
/// near 1e-14; a wrong statement differs by O(1e-2) or more at a random point.
pub const TOL: f64 = 1e-9;

/// Degree of the random polynomial fields: derivatives up to this order are random,
/// higher ones zero (a statement with fifth derivatives is not distinguished from one
/// without them).
pub const FIELD_DEGREE: u32 = 4;

/// Quadrature nodes and weights (weights sum to 1) for the uniform average over the
/// unit circle or sphere, exact for polynomials in n of degree ≤ 15.
pub fn sphere_rule(dim: usize) -> Vec<(Vec<f64>, f64)> {
    sphere_rule_exact_to(dim, 15)
}

/// A rule exact for polynomials in n of degree ≤ `degree`: on the circle, M = degree + 1
/// equally spaced points (exact for trigonometric degree < M); on the sphere, an
/// N-point Gauss–Legendre rule in z = cos θ with 2N − 1 ≥ degree times M = degree + 1
/// equally spaced φ. (A monomial n_1^a n_2^b n_3^c with a + b odd integrates to 0 over
/// φ exactly; with a + b even it is a polynomial of degree ≤ degree in z.)
pub fn sphere_rule_exact_to(dim: usize, degree: usize) -> Vec<(Vec<f64>, f64)> {
    use std::f64::consts::PI;
    let m = degree + 1;
    if dim == 2 {
        return (0..m)
            .map(|k| {
                let phi = 2.0 * PI * k as f64 / m as f64;
                (vec![phi.cos(), phi.sin()], 1.0 / m as f64)
            })
            .collect();
    }
    let (zs, ws) = gauss_legendre(degree / 2 + 1);
    let mut out = Vec::with_capacity(zs.len() * m);
    for (z, w) in zs.iter().zip(&ws) {
        let r = (1.0 - z * z).max(0.0).sqrt();
        for k in 0..m {
            let phi = 2.0 * PI * k as f64 / m as f64;
            out.push((vec![r * phi.cos(), r * phi.sin(), *z], w / 2.0 / m as f64));
        }
    }
    out
}

/// Gauss–Legendre nodes and weights on [−1, 1] by Newton iteration on P_n.
fn gauss_legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
    let mut xs = Vec::with_capacity(n);
    let mut ws = Vec::with_capacity(n);
    for i in 0..n {
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
            let dx = p1 / dp;
            x -= dx;
            if dx.abs() < 1e-16 {
                break;
            }
        }
        xs.push(x);
        ws.push(2.0 / ((1.0 - x * x) * dp * dp));
    }
    (xs, ws)
}

/// A small deterministic generator (xorshift64*), independent of the exact route's.
pub struct Rng(u64);

impl Rng {
    /// A generator for `seed` (0 is mapped to 1: xorshift needs a nonzero state).
    pub fn new(seed: u64) -> Self {
        Rng(seed.max(1))
    }

    /// Uniform in [−1, 1).
    pub fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let x = self.0.wrapping_mul(0x2545_F491_4F6C_DD1D);
        (x >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }

    /// Uniform in 0..n (n > 0).
    pub fn below(&mut self, n: usize) -> usize {
        let k = ((self.uniform() + 1.0) / 2.0 * n as f64) as usize;
        k.min(n - 1)
    }

    /// A random unit normal (in the 1-2 plane for plane problems), padded to the
    /// dimension with zeros.
    pub fn unit_normal(&mut self, decls: &Decls) -> Vec<f64> {
        let free = if decls.normal_in_plane { 2 } else { decls.dim };
        let mut v: Vec<f64> = (0..free).map(|_| self.uniform()).collect();
        let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt().max(1e-3);
        v.iter_mut().for_each(|x| *x /= norm);
        v.resize(decls.dim, 0.0);
        v
    }
}

/// The quadrature rule of `avg(…)` for these declarations, exact to `degree`: the
/// sphere, or the circle (embedded with n_3 = 0) for plane problems.
pub fn rule_for(decls: &Decls, degree: usize) -> Vec<(Vec<f64>, f64)> {
    let free = if decls.normal_in_plane { 2 } else { decls.dim };
    sphere_rule_exact_to(free, degree)
        .into_iter()
        .map(|(mut p, w)| {
            p.resize(decls.dim, 0.0);
            (p, w)
        })
        .collect()
}

/// The float route's verdict on a check: `holds` when every equality agrees within
/// [`TOL`] (with field derivatives, [`taylor::AGREEMENT`]) at `samples` seeded random
/// points, else `fails`. `Ok(None)` when the check
/// has an ill-formed (verbatim) side or averages an argument that is not a polynomial
/// in n, which this route does not judge.
pub fn decide(
    decls: &Decls,
    check: &Check,
    samples: usize,
    seed: u64,
) -> Result<Option<Verdict>, String> {
    if check.chains.iter().flatten().any(|s| s.node.is_err()) {
        return Ok(None);
    }
    let d = decls.dim;
    let parametrisation = Parametrisation::new(decls, &check.assumptions).map_err(|e| e.message)?;
    let mut rng = Rng::new(seed);
    // Derivatives of fields: random polynomial fields, differentiated by central
    // differences, to the stencil's accuracy.
    let differentiates = check.reads().differentiates;
    let tol = if differentiates {
        taylor::AGREEMENT
    } else {
        TOL
    };
    let proportional = matches!(check.strategy, Strategy::Proportional { .. });
    let domain = check.strategy.exact_domain();
    let mut factor: Option<f64> = None;
    for _ in 0..samples {
        let mut symbols: HashMap<String, Tensor<f64>> = HashMap::default();
        for (name, &rank) in &decls.symbols {
            let mut t = Tensor::from_fn(d, rank, |_| rng.uniform());
            // A scalar the claim bounds (`given`) is drawn inside its interval.
            if let Some(i) = domain.map(|b| b.interval(name)) {
                if rank == 0 {
                    *t.get_mut(&[]) = inside(&i, *t.get(&[]));
                }
            }
            symbols.insert(name.clone(), t);
        }
        let mut env = RealEnv::new(decls, &check.defs, symbols);
        if differentiates {
            let fields = TaylorFields::random(decls, FIELD_DEGREE, &mut || rng.uniform());
            env = env.with_fields(fields);
        }
        let n = rng.unit_normal(decls);
        env.assume(&parametrisation, &check.assumptions, &n)
            .map_err(|e| e.message)?;
        for chain in &check.chains {
            let values = chain
                .iter()
                .map(|s| env.eval(s.node.as_ref().expect("checked above"), &n))
                .collect::<Result<Vec<_>, _>>()
                .map_err(|e| e.message)?;
            if env.quadrature.used() {
                // Adaptive averages carry an error this route does not account for.
                return Ok(None);
            }
            for w in values.windows(2) {
                let (_, pairs) = component_pairs(d, &w[0], &w[1]);
                // A proportionality takes its factor from the pair with the largest
                // right side of the first sample where one is clearly nonzero (above
                // 100 tolerances, so that rounding noise never sets it), and holds it
                // fixed after that; until then the sides are compared as equal.
                if proportional && factor.is_none() {
                    let largest = pairs
                        .iter()
                        .max_by(|a, b| a.2.abs().total_cmp(&b.2.abs()))
                        .filter(|p| p.2.abs() > 100.0 * tol);
                    if let Some((_, l, r)) = largest {
                        let f = l / r;
                        if !f.is_finite() || f.abs() <= tol {
                            return Ok(Some(Verdict::Fails));
                        }
                        factor = Some(f);
                    }
                }
                let scale = factor.unwrap_or(1.0);
                for (_, l, r) in pairs {
                    if !l.is_finite() || !r.is_finite() {
                        return Ok(Some(Verdict::Fails));
                    }
                    let r = scale * r;
                    if (l - r).abs() > tol * (1.0 + l.abs() + r.abs()) {
                        return Ok(Some(Verdict::Fails));
                    }
                }
            }
        }
    }
    Ok(Some(Verdict::Holds))
}

/// A value of the interval for a uniform draw `u` in [−1, 1], off its ends.
fn inside(i: &Interval, u: f64) -> f64 {
    let unit = 0.05 + 0.9 * (u + 1.0) / 2.0;
    let end = |e: &End| match e {
        End::Unbounded => None,
        End::Open(x) | End::Closed(x) => Some(x.to_f64()),
    };
    match (end(&i.lo), end(&i.hi)) {
        (None, None) => u,
        (Some(a), None) => a + 2.0 * unit,
        (None, Some(b)) => b - 2.0 * unit,
        (Some(a), Some(b)) => a + (b - a) * unit,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rules_integrate_known_moments() {
        for dim in [2usize, 3] {
            let rule = sphere_rule(dim);
            let total: f64 = rule.iter().map(|(_, w)| w).sum();
            assert!((total - 1.0).abs() < 1e-14);
            let m4: f64 = rule.iter().map(|(p, w)| w * p[0].powi(4)).sum();
            let want = if dim == 2 { 3.0 / 8.0 } else { 1.0 / 5.0 };
            assert!((m4 - want).abs() < 1e-14, "dim {dim}: {m4}");
        }
    }
}
