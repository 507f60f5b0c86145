//! The elastic matrices (57), the gradients of the rolling yield surface F₂ (50) at the
//! state of incipient failure, and the elastoplastic tangent (55)–(56) in the form the
//! consistency condition gives.
//!
//! The state of incipient failure is partly implicit in the paper. We take (and every
//! claim that uses it says so):
//! - σ_11 = σ_22 = σ < 0: simple shear from an isotropic compressed state, with
//!   Γ_11 = Γ_22 = 0 so the elastic response keeps the normal stresses equal;
//! - σ_12 = σ_21 = τ: the homogeneous state has no couple-stress gradient, so the
//!   moment balance (60) gives σ_12 = σ_21;
//! - μ_13 = μ_23 = 0: no curvature before the band forms;
//! - F₂ = 0: the rolling surface is reached first (Section 6), so |τ| = −f_r σ;
//! - τ > 0 unless [`ShearSign::Negative`] is asked for (the relaxation of that sign).

use super::{Params, Point};
use crate::kernel::{Poly, RatFunc, Rational};
use nalgebra::SVector;
use num_dual::{gradient, DualNum, DualSVec64};
use num_traits::{One, Zero};

/// A 4-vector on the components (11, 22, 12, 21).
pub type Vec4 = [RatFunc; 4];
/// A 4×4 matrix acting on 4-vectors ordered (11, 22, 12, 21).
pub type Mat4 = [[RatFunc; 4]; 4];
/// A 2×2 matrix on the couple-stress components (13, 23).
pub type Mat2 = [[RatFunc; 2]; 2];

/// The tensor indices (1-based) of each 4-vector position.
pub const POSITIONS: [(usize, usize); 4] = [(1, 1), (2, 2), (1, 2), (2, 1)];

/// The sign of the shear stress τ = σ_12 = σ_21 at the state.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ShearSign {
    Positive,
    Negative,
}

impl ShearSign {
    pub fn factor(self) -> i64 {
        match self {
            ShearSign::Positive => 1,
            ShearSign::Negative => -1,
        }
    }
}

fn c(n: i64) -> RatFunc {
    RatFunc::int(n)
}

/// D^(el) of eq. (57), on the vector (11, 22, 12, 21):
/// G [[K+1, K−1, 0, 0], [K−1, K+1, 0, 0], [0, 0, 1+h^C, 1−h^C], [0, 0, 1−h^C, 1+h^C]].
pub fn elastic_stiffness(p: &Params) -> Mat4 {
    let g = p.var(p.g);
    let k = p.var(p.k);
    let h = p.var(p.h_c);
    let one = RatFunc::one();
    let entries = [
        [&k + &one, &k - &one, RatFunc::zero(), RatFunc::zero()],
        [&k - &one, &k + &one, RatFunc::zero(), RatFunc::zero()],
        [RatFunc::zero(), RatFunc::zero(), &one + &h, &one - &h],
        [RatFunc::zero(), RatFunc::zero(), &one - &h, &one + &h],
    ];
    entries.map(|row| row.map(|e| &g * &e))
}

/// M^(el)_ij = 4 G R_g² δ_ij (Appendix A, after eq. 56), on (13, 23).
pub fn couple_stiffness(p: &Params) -> Mat2 {
    let m = &(&c(4) * &p.var(p.g)) * &p.var(p.r_g).pow(2);
    [[m.clone(), RatFunc::zero()], [RatFunc::zero(), m]]
}

/// The gradients of F₂ at the state: Q_ij = ∂F₂/∂σ_ij on (11, 22, 12, 21) and
/// F_i = ∂F₂/∂μ_i3 on (13, 23).
#[derive(Clone, Debug, PartialEq)]
pub struct YieldGradient {
    pub q: Vec4,
    pub f: [RatFunc; 2],
}

/// The radicand X of F₂ = √X + f_r p (eq. 50, with q², r² of (45), M² of (43) and p of
/// (40)) as a polynomial in the six plane components `comps` =
/// (σ_11, σ_22, σ_12, σ_21, μ_13, μ_23): X = 2M²/R_g² + q² + 2r².
pub fn rolling_radicand(p: &Params, comps: &[Poly; 6]) -> (Poly, Poly) {
    let half = Poly::constant(Rational::ratio(1, 2).expect("2 ≠ 0"));
    let quarter = Poly::constant(Rational::ratio(1, 4).expect("4 ≠ 0"));
    let [s11, s22, s12, s21, m13, m23] = comps;
    let mean = &half * &(s11 + s22); // p, eq. (40)
    let d11 = s11 - &mean;
    let d22 = s22 - &mean;
    let q2 = &(&quarter * &(&d11 - &d22).pow(2)) + &(&quarter * &(s12 + s21).pow(2));
    let r2 = &quarter * &(s12 - s21).pow(2);
    let m2 = &half * &(&m13.pow(2) + &m23.pow(2)); // eq. (43)
    let inv_r2 = Poly::term(crate::kernel::Monomial::var(p.r_g, -2), Rational::int(2));
    let x = &(&(&inv_r2 * &m2) + &q2) + &(&r2 * &Poly::constant(Rational::int(2)));
    (x, mean)
}

/// Q and F exactly, at the state of the module documentation (eq. 50 differentiated).
/// Fails with a message if the state does not make X a perfect square τ², i.e. if the
/// assumptions are inconsistent.
pub fn yield_gradient_exact(p: &Params, shear: ShearSign) -> Result<YieldGradient, String> {
    // τ = s ρ with s the sign of τ and ρ = √X = |τ|.
    let s = c(shear.factor());
    let sigma = RatFunc::var(p.sigma);
    gradient_on_surface(p, &|rho| {
        let tau = &s * rho;
        [
            sigma.clone(),
            sigma.clone(),
            tau.clone(),
            tau,
            RatFunc::zero(),
            RatFunc::zero(),
        ]
    })
}

/// Q and F with the assumption σ_11 = σ_22 relaxed: σ_11 − σ_22 = 2ρ cos α and
/// τ = σ_12 = σ_21 = ρ sin α, written rationally with t = tan(α/2) (`p.t`):
/// cos α = (1 − t²)/(1 + t²), sin α = 2t/(1 + t²). t = 1 (α = 90°) is the state of
/// [`yield_gradient_exact`]; every other t rotates the principal axes of σ.
pub fn yield_gradient_rotated(p: &Params) -> Result<YieldGradient, String> {
    let sigma = RatFunc::var(p.sigma);
    let t = p.var(p.t);
    let one = RatFunc::one();
    let t2 = t.pow(2);
    let den = &one + &t2;
    let cos = (&(&one - &t2) / &den).expect("1 + t² ≠ 0");
    let sin = (&(&c(2) * &t) / &den).expect("1 + t² ≠ 0");
    gradient_on_surface(p, &|rho| {
        let d = rho * &cos;
        let tau = rho * &sin;
        [
            &sigma + &d,
            &sigma - &d,
            tau.clone(),
            tau,
            RatFunc::zero(),
            RatFunc::zero(),
        ]
    })
}

/// The gradient of F₂ = √X + f_r p at a state given as a function of ρ = √X > 0 (the
/// state must make X = ρ² identically, which is checked), on the surface F₂ = 0, i.e.
/// with ρ = −f_r σ. The result must not depend on σ (checked).
fn gradient_on_surface(
    p: &Params,
    state: &dyn Fn(&RatFunc) -> [RatFunc; 6],
) -> Result<YieldGradient, String> {
    let mut names = p.names.clone();
    let comp_vars: Vec<_> = ["s11", "s22", "s12", "s21", "m13", "m23"]
        .iter()
        .map(|n| names.intern(&format!("__{n}")))
        .collect();
    let rho_var = names.intern("__rho");
    let comps: [Poly; 6] = std::array::from_fn(|k| Poly::var(comp_vars[k]));
    let (x, mean) = rolling_radicand(p, &comps);
    let rho = RatFunc::var(rho_var);
    let values = state(&rho);
    let at_state = |poly: &Poly| -> RatFunc {
        comp_vars
            .iter()
            .zip(&values)
            .fold(RatFunc::from_poly(poly), |acc, (&v, value)| {
                acc.substitute(v, value).expect("polynomial substitution")
            })
    };
    if at_state(&x) != rho.pow(2) {
        return Err(format!(
            "at the state, X = {} is not ρ²",
            at_state(&x).display(&names)
        ));
    }
    let f_r = p.var(p.f_r);
    let on_surface = &c(-1) * &(&f_r * &RatFunc::var(p.sigma));
    let grads: Vec<RatFunc> = comp_vars
        .iter()
        .map(|&v| {
            let dx = at_state(&x.derivative(v));
            let dp = at_state(&mean.derivative(v));
            let g = &(&dx / &(&c(2) * &rho)).expect("ρ ≠ 0") + &(&f_r * &dp);
            g.substitute(rho_var, &on_surface).expect("σ ≠ 0")
        })
        .collect();
    for g in &grads {
        if g.depends_on(p.sigma) || g.depends_on(rho_var) {
            return Err(format!(
                "the gradient {} still depends on σ",
                g.display(&names)
            ));
        }
    }
    Ok(YieldGradient {
        q: std::array::from_fn(|k| grads[k].clone()),
        f: [grads[4].clone(), grads[5].clone()],
    })
}

/// F₂ of eq. (50) in floating point, generic over dual numbers: written out again from
/// (40), (43), (45) so that the num-dual route shares no code with the exact one.
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

/// The state's components for given σ < 0 and shear sign: (σ, σ, τ, τ, 0, 0) with
/// |τ| = −f_r σ (F₂ = 0).
pub fn state_components(sigma: f64, f_r: f64, shear: ShearSign) -> [f64; 6] {
    let tau = -f_r * sigma * shear.factor() as f64;
    [sigma, sigma, tau, tau, 0.0, 0.0]
}

/// The elastoplastic tangent from the consistency condition (associated flow, eqs.
/// 55–56 as the Appendix intends them). With H = Q·D·Q + F·M·F + h_2:
/// D^(ep) = D − (D Q)(Q D)/H and M^(ep) = M − (M F)(F M)/H, and the coupling blocks
/// −(D Q)(F M)/H, −(M F)(Q D)/H, which vanish when F = 0.
#[derive(Clone, Debug, PartialEq)]
pub struct Tangent {
    pub d_ep: Mat4,
    pub m_ep: Mat2,
    /// σ̇ ← K coupling block (4×2).
    pub d_k: [[RatFunc; 2]; 4],
    /// H, the denominator.
    pub hardening_denominator: RatFunc,
}

pub fn elastoplastic_tangent(p: &Params, grad: &YieldGradient) -> Tangent {
    elastoplastic_tangent_with(
        grad,
        &elastic_stiffness(p),
        &couple_stiffness(p),
        &p.var(p.h_2),
    )
}

/// [`elastoplastic_tangent`] for given stiffnesses and hardening modulus (symbolic, or
/// with the material fixed to numbers, which keeps the rational functions small).
pub fn elastoplastic_tangent_with(
    grad: &YieldGradient,
    d: &Mat4,
    m: &Mat2,
    h_2: &RatFunc,
) -> Tangent {
    let dq: Vec4 = std::array::from_fn(|a| dot4(&d[a], &grad.q));
    let qd: Vec4 = std::array::from_fn(|b| {
        (0..4).fold(RatFunc::zero(), |acc, a| &acc + &(&grad.q[a] * &d[a][b]))
    });
    let mf: [RatFunc; 2] =
        std::array::from_fn(|a| &(&m[a][0] * &grad.f[0]) + &(&m[a][1] * &grad.f[1]));
    let fm: [RatFunc; 2] =
        std::array::from_fn(|b| &(&grad.f[0] * &m[0][b]) + &(&grad.f[1] * &m[1][b]));
    let h = &(&dot4(&grad.q, &dq) + &(&(&grad.f[0] * &mf[0]) + &(&grad.f[1] * &mf[1]))) + h_2;
    let over_h = |x: RatFunc| (&x / &h).expect("H is not identically zero");
    Tangent {
        d_ep: std::array::from_fn(|a| std::array::from_fn(|b| &d[a][b] - &over_h(&dq[a] * &qd[b]))),
        m_ep: std::array::from_fn(|a| std::array::from_fn(|b| &m[a][b] - &over_h(&mf[a] * &fm[b]))),
        d_k: std::array::from_fn(|a| std::array::from_fn(|b| -&over_h(&dq[a] * &fm[b]))),
        hardening_denominator: h,
    }
}

fn dot4(a: &Vec4, b: &Vec4) -> RatFunc {
    (0..4).fold(RatFunc::zero(), |acc, k| &acc + &(&a[k] * &b[k]))
}

/// D^(el) of (57) in `f64`, as a nalgebra matrix.
pub fn elastic_f64(pt: &Point) -> nalgebra::Matrix4<f64> {
    let (k, h) = (pt.k, pt.h_c);
    #[rustfmt::skip]
    let d = nalgebra::Matrix4::new(
        k + 1.0, k - 1.0, 0.0, 0.0,
        k - 1.0, k + 1.0, 0.0, 0.0,
        0.0, 0.0, 1.0 + h, 1.0 - h,
        0.0, 0.0, 1.0 - h, 1.0 + h,
    );
    d * pt.g
}

/// D^(ep) in `f64` by an independent route: nalgebra matrices, the gradient from
/// num-dual at the state (σ = −1), the same consistency formula.
pub fn elastoplastic_f64(pt: &Point, shear: ShearSign) -> nalgebra::Matrix4<f64> {
    let grad = yield_gradient_dual(state_components(-1.0, pt.f_r, shear), pt.f_r, pt.r_g);
    elastoplastic_f64_with(pt, &grad)
}

/// [`elastoplastic_f64`] for a gradient (Q_11, Q_22, Q_12, Q_21, F_1, F_2) already
/// computed (the bisections of the acoustic analysis reuse one).
pub fn elastoplastic_f64_with(pt: &Point, grad: &[f64; 6]) -> nalgebra::Matrix4<f64> {
    let d = elastic_f64(pt);
    let qv = nalgebra::Vector4::new(grad[0], grad[1], grad[2], grad[3]);
    let fv = nalgebra::Vector2::new(grad[4], grad[5]);
    let m = nalgebra::Matrix2::identity() * (4.0 * pt.g * pt.r_g * pt.r_g);
    let dq = d * qv;
    let h_den = qv.dot(&dq) + fv.dot(&(m * fv)) + pt.h_2;
    d - dq * dq.transpose() / h_den
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gradient_at_the_state_is_half_f_r_and_half() {
        let p = Params::new();
        let g = yield_gradient_exact(&p, ShearSign::Positive).unwrap();
        let shown: Vec<String> = g.q.iter().map(|x| p.display(x)).collect();
        assert_eq!(shown, ["1/2*f_r", "1/2*f_r", "1/2", "1/2"]);
        assert!(g.f.iter().all(RatFunc::is_zero));
        let neg = yield_gradient_exact(&p, ShearSign::Negative).unwrap();
        assert_eq!(p.display(&neg.q[2]), "-1/2");
        // Relaxing σ_11 = σ_22: the rotated state at t = 1 is the same state.
        let rot = yield_gradient_rotated(&p).unwrap();
        for (a, b) in rot.q.iter().zip(&g.q) {
            assert_eq!(&a.substitute(p.t, &RatFunc::int(1)).unwrap(), b);
        }
        assert_eq!(p.display(&rot.q[2]), "t / (t^2 + 1)");
    }

    #[test]
    fn elastic_matrix_is_eq_57() {
        let p = Params::new();
        let d = elastic_stiffness(&p);
        assert_eq!(p.display(&d[0][1]), "K*G - G");
        assert_eq!(p.display(&d[3][2]), "-G*h_C + G");
        assert!(d[0][2].is_zero());
    }
}
