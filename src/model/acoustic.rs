//! The acoustic tensor of the Appendix and the critical hardening modulus.
//!
//! A band with unit normal n = (n_1, n_2) = (−sin θ, cos θ) (θ_B = arctan(−n_1/n_2))
//! carries jumps [v_j,i] = n_i g_j with w_3 continuous (B > 0, below), so
//! [Γ_kl] = n_k g_l and continuity of the traction rate n_i σ̇_ij needs
//! A_jl g_l = 0 with A_jl = n_i D^(ep)_ijkl n_k (the first index of σ and Γ is the
//! gradient index, eq. 2). The paper prints |D^(ep)_ijkl n_j n_l|; both contractions
//! are computed. det A = 0 is linear in h_2, so each orientation has one critical
//! hardening modulus h_2^cr(n); the band forms first at the orientation of the largest.

use super::tangent::{self, Mat2, Mat4, ShearSign};
use super::{Params, Point};
use crate::kernel::gcd::degree_in;
use crate::kernel::{Monomial, Poly, RatFunc};
use num_traits::Zero;

fn position(i: usize, j: usize) -> usize {
    tangent::POSITIONS
        .iter()
        .position(|&p| p == (i, j))
        .expect("in-plane indices")
}

/// Which pair of indices of D^(ep)_ijkl is contracted with n.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Contraction {
    /// n_i D_ijkl n_k: the traction-rate continuity of the convention (2).
    GradientIndices,
    /// n_j D_ijkl n_l: as printed in the Appendix.
    AsPrinted,
}

/// The 2×2 acoustic tensor as rational functions of the parameters and n_1, n_2.
pub fn acoustic_tensor(p: &Params, d_ep: &Mat4, which: Contraction) -> Mat2 {
    let n = [p.var(p.n_1), p.var(p.n_2)];
    std::array::from_fn(|r| {
        std::array::from_fn(|s| {
            let mut acc = RatFunc::zero();
            for a in 0..2 {
                for b in 0..2 {
                    let (row, col) = match which {
                        Contraction::GradientIndices => {
                            (position(a + 1, r + 1), position(b + 1, s + 1))
                        }
                        Contraction::AsPrinted => (position(r + 1, a + 1), position(s + 1, b + 1)),
                    };
                    acc = &acc + &(&(&n[a] * &d_ep[row][col]) * &n[b]);
                }
            }
            acc
        })
    })
}

pub fn det2(m: &Mat2) -> RatFunc {
    &(&m[0][0] * &m[1][1]) - &(&m[0][1] * &m[1][0])
}

/// h_2^cr(n): the value of h_2 at which det A(n) = 0, from the numerator of det A,
/// which is linear in h_2 (`Err` if it is not).
pub fn critical_hardening(p: &Params, d_ep: &Mat4, which: Contraction) -> Result<RatFunc, String> {
    let det = det2(&acoustic_tensor(p, d_ep, which));
    let num = det.numerator();
    if degree_in(num, p.h_2) != 1 {
        return Err(format!(
            "the numerator of det A has degree {} in h_2, not 1",
            degree_in(num, p.h_2)
        ));
    }
    let mut c0 = Poly::zero();
    let mut c1 = Poly::zero();
    for (m, c) in num.terms() {
        let rest = Monomial::from_factors(
            m.factors()
                .iter()
                .copied()
                .filter(|&(v, _)| v != p.h_2)
                .collect(),
        );
        if m.exponent(p.h_2) == 1 {
            c1.add_term(rest, c.clone());
        } else {
            c0.add_term(rest, c.clone());
        }
    }
    RatFunc::new(&(-&c0), &c1).ok_or_else(|| "det A does not depend on h_2".to_string())
}

/// B = M^(ep)_ij n_i n_j (Appendix A).
pub fn b_scalar(p: &Params, m_ep: &Mat2) -> RatFunc {
    let n = [p.var(p.n_1), p.var(p.n_2)];
    let mut acc = RatFunc::zero();
    for a in 0..2 {
        for b in 0..2 {
            acc = &acc + &(&(&n[a] * &m_ep[a][b]) * &n[b]);
        }
    }
    acc
}

/// h_2^cr(θ) in `f64` by an independent route: nalgebra's D^(ep)(h_2) of
/// [`tangent::elastoplastic_f64`], the 2×2 determinant, and bisection in h_2 on
/// (−H, 100 G], where det A goes from −∞ to det A^(el) > 0.
pub fn critical_hardening_f64(pt: &Point, shear: ShearSign, theta: f64) -> f64 {
    let n = [-theta.sin(), theta.cos()];
    let grad = tangent::yield_gradient_dual(
        tangent::state_components(-1.0, pt.f_r, shear),
        pt.f_r,
        pt.r_g,
    );
    let det_at = |h2: f64| {
        let d = tangent::elastoplastic_f64_with(&Point { h_2: h2, ..*pt }, &grad);
        let a = nalgebra::Matrix2::from_fn(|r, s| {
            let mut acc = 0.0;
            for i in 0..2 {
                for k in 0..2 {
                    acc += n[i] * d[(position(i + 1, r + 1), position(k + 1, s + 1))] * n[k];
                }
            }
            acc
        });
        a.determinant()
    };
    // H = Q·D·Q at h_2 = 0: the pole of D^(ep) sits at h_2 = −H.
    let q = nalgebra::Vector4::new(grad[0], grad[1], grad[2], grad[3]);
    let h = q.dot(&(tangent::elastic_f64(pt) * q));
    let (mut lo, mut hi) = (-h * (1.0 - 1e-12), 100.0 * pt.g);
    // 100 halvings take the bracket below f64 resolution.
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
