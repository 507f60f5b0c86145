//! The independent floating-point route of Appendix A, written once more by hand: F₂ of
//! (50) in num-dual numbers, D^(el) of (57) and D^(ep) of the corrected (55) as nalgebra
//! matrices, the elimination of v_1', v_2' by an LU solve, and the critical hardening
//! modulus by bisection in h_2. It shares no code with the exact route, which reads
//! `derivations/A-3-shear-band.toml`; the tests compare the two.

use nalgebra::{Matrix2, Matrix4, Matrix4x3, SVector, Vector2, Vector4};
use num_dual::{gradient, DualNum, DualSVec64};

/// A material point: f_r, K = 1/(1 − 2ν), G, h^C, h_2, R_g.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point {
    pub f_r: f64,
    pub k: f64,
    pub g: f64,
    pub h_c: f64,
    pub h_2: f64,
    pub r_g: f64,
}

/// The sign of the shear stress τ = σ_12 = σ_21 at the state.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ShearSign {
    Positive,
    Negative,
}

/// The tensor indices (1-based) of each 4-vector position of (57).
const POSITIONS: [(usize, usize); 4] = [(1, 1), (2, 2), (1, 2), (2, 1)];

fn position(i: usize, j: usize) -> usize {
    POSITIONS
        .iter()
        .position(|&p| p == (i, j))
        .expect("in-plane indices")
}

/// F₂ of eq. (50) from (40), (43), (45), generic over dual numbers.
pub fn rolling_yield<D: DualNum<Primitive = f64> + Copy>(x: &[D; 6], f_r: f64, r_g: f64) -> D {
    let [s11, s22, s12, s21, m13, m23] = *x;
    let p = (s11 + s22) * 0.5;
    let q2 = ((s11 - s22) * (s11 - s22) + (s12 + s21) * (s12 + s21)) * 0.25;
    let r2 = (s12 - s21) * (s12 - s21) * 0.25;
    let m2 = (m13 * m13 + m23 * m23) * 0.5;
    (m2 * (2.0 / (r_g * r_g)) + q2 + r2 * 2.0).sqrt() + p * f_r
}

/// ∂F₂/∂(σ_11, σ_22, σ_12, σ_21, μ_13, μ_23) by num-dual at the given components.
pub fn yield_gradient_dual(components: [f64; 6], f_r: f64, r_g: f64) -> [f64; 6] {
    let x0 = SVector::<f64, 6>::from(components);
    let (_, g) = gradient(
        |x: SVector<DualSVec64<6>, 6>| {
            let arr: [DualSVec64<6>; 6] = std::array::from_fn(|k| x[k]);
            rolling_yield(&arr, f_r, r_g)
        },
        &x0,
    );
    std::array::from_fn(|k| g[k])
}

/// The state (σ, σ, τ, τ, 0, 0) with |τ| = −f_r σ (F₂ = 0) and the given sign of τ.
pub fn state_components(sigma: f64, f_r: f64, shear: ShearSign) -> [f64; 6] {
    let sign = match shear {
        ShearSign::Positive => 1.0,
        ShearSign::Negative => -1.0,
    };
    let tau = -f_r * sigma * sign;
    [sigma, sigma, tau, tau, 0.0, 0.0]
}

/// D^(el) of (57).
pub fn elastic(pt: &Point) -> Matrix4<f64> {
    let (k, h) = (pt.k, pt.h_c);
    #[rustfmt::skip]
    let d = Matrix4::new(
        k + 1.0, k - 1.0, 0.0, 0.0,
        k - 1.0, k + 1.0, 0.0, 0.0,
        0.0, 0.0, 1.0 + h, 1.0 - h,
        0.0, 0.0, 1.0 - h, 1.0 + h,
    );
    d * pt.g
}

/// D^(ep) = D − (D Q)(D Q)ᵀ/(Q D Q + F M F + h_2) for a gradient (Q, F).
pub fn elastoplastic_with(pt: &Point, grad: &[f64; 6]) -> Matrix4<f64> {
    let d = elastic(pt);
    let q = Vector4::new(grad[0], grad[1], grad[2], grad[3]);
    let f = Vector2::new(grad[4], grad[5]);
    let m = Matrix2::identity() * (4.0 * pt.g * pt.r_g * pt.r_g);
    let dq = d * q;
    let h = q.dot(&dq) + f.dot(&(m * f)) + pt.h_2;
    d - dq * dq.transpose() / h
}

/// D^(ep) at the Appendix's state (σ = −1), the gradient by num-dual.
pub fn elastoplastic(pt: &Point, shear: ShearSign) -> Matrix4<f64> {
    let grad = yield_gradient_dual(state_components(-1.0, pt.f_r, shear), pt.f_r, pt.r_g);
    elastoplastic_with(pt, &grad)
}

/// A² for a D^(ep): σ̇_22, σ̇_21 constant solved for v_1', v_2' (LU), then the moment
/// balance a μ̇_23' + b (σ̇_12 − σ̇_21) = 0 with μ̇_23 = 4 G R_g² w_3', lengths in R_g.
pub fn a_squared_from(d: &Matrix4<f64>, pt: &Point, a: f64, b: f64) -> Option<f64> {
    // Γ = G_u (v_1', v_2', w_3), written out from (2) by hand.
    #[rustfmt::skip]
    let gu = Matrix4x3::new(
        0.0, 0.0, 0.0, // Γ_11
        0.0, 1.0, 0.0, // Γ_22 = v_2'
        0.0, 0.0, -1.0, // Γ_12 = −w_3
        1.0, 0.0, 1.0, // Γ_21 = v_1' + w_3
    );
    let l = d * gu;
    let sys = Matrix2::new(l[(1, 0)], l[(1, 1)], l[(3, 0)], l[(3, 1)]);
    let rhs = Vector2::new(-l[(1, 2)], -l[(3, 2)]);
    let x = sys.lu().solve(&rhs)?;
    let coef = |r: usize| l[(r, 0)] * x[0] + l[(r, 1)] * x[1] + l[(r, 2)];
    let alpha = coef(2) - coef(3);
    let m22 = 4.0 * pt.g * pt.r_g * pt.r_g;
    Some(b * alpha * pt.r_g * pt.r_g / (a * m22))
}

/// [`a_squared_from`] at the Appendix's state.
pub fn a_squared(pt: &Point, shear: ShearSign, a: f64, b: f64) -> Option<f64> {
    a_squared_from(&elastoplastic(pt, shear), pt, a, b)
}

/// h_2^cr(θ), n = (−sin θ, cos θ): det(n_i D^(ep)_ijkl n_k) = 0, by bisection in h_2 on
/// (−H, 100 G], where det A goes from −∞ to det A^(el) > 0.
pub fn critical_hardening(pt: &Point, shear: ShearSign, theta: f64) -> f64 {
    let n = [-theta.sin(), theta.cos()];
    let grad = yield_gradient_dual(state_components(-1.0, pt.f_r, shear), pt.f_r, pt.r_g);
    let det_at = |h2: f64| {
        let d = elastoplastic_with(&Point { h_2: h2, ..*pt }, &grad);
        Matrix2::from_fn(|r, s| {
            let mut acc = 0.0;
            for i in 0..2 {
                for k in 0..2 {
                    acc += n[i] * d[(position(i + 1, r + 1), position(k + 1, s + 1))] * n[k];
                }
            }
            acc
        })
        .determinant()
    };
    let q = Vector4::new(grad[0], grad[1], grad[2], grad[3]);
    let h = q.dot(&(elastic(pt) * q));
    let (mut lo, mut hi) = (-h * (1.0 - 1e-12), 100.0 * pt.g);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if det_at(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// The maximum of `f` over θ ∈ [0, π): a 720-point grid, then golden-section search
/// around the best grid point. Returns (θ*, f(θ*)).
pub fn maximise_over_orientation(f: impl Fn(f64) -> f64) -> (f64, f64) {
    let n = 720;
    let step = std::f64::consts::PI / n as f64;
    let (mut best, mut best_v) = (0.0, f(0.0));
    for k in 1..n {
        let t = k as f64 * step;
        let v = f(t);
        if v > best_v {
            (best, best_v) = (t, v);
        }
    }
    let (mut a, mut b) = (best - step, best + step);
    let g = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..80 {
        let c = b - g * (b - a);
        let d = a + g * (b - a);
        if f(c) > f(d) {
            b = d;
        } else {
            a = c;
        }
    }
    let t = 0.5 * (a + b);
    let v = f(t);
    if v > best_v {
        (t.rem_euclid(std::f64::consts::PI), v)
    } else {
        (best, best_v)
    }
}
