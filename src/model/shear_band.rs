//! The shear-band parameter A² of the Appendix: the rate equations in the balance laws
//! (58)–(60) give w_3'' + A² w_3 = const, whose oscillatory solutions set the band
//! thickness d_B/R_g = π/A (62).
//!
//! The elimination follows the Appendix step by step. With the kinematics of
//! [`balance::kinematics`], Γ = (Γ_11, Γ_22, Γ_12, Γ_21) = (0, v_2', −w_3, v_1' + w_3)
//! and σ̇ = D^(ep) Γ:
//! 1. (58), (59) integrated: σ̇_21 = C_1 and σ̇_22 = C_2 (constants) are two linear
//!    equations for v_1', v_2' in terms of w_3; they are solved by Cramer's rule;
//! 2. the moment balance a μ̇_23' + b (σ̇_12 − σ̇_21) = 0 (a, b read off the law: the
//!    derived one or the printed (60)) with μ̇_23 = M^(ep)_22 w_3' gives
//!    w_3'' + (b α / (a M^(ep)_22)) w_3 = const, α the coefficient of w_3 in
//!    σ̇_12 − σ̇_21;
//! 3. lengths in units of R_g: A² = b α R_g² / (a M^(ep)_22), dimensionless.

use super::balance::{self, Velocity};
use super::tangent::{self, Mat4, ShearSign, Tangent};
use super::{ExactPoint, Params, Point};
use crate::kernel::{Poly, RatFunc, Rational, VarTable};
use num_traits::{One, Zero};

/// The moment balance read as `a dmu_23 + b sigma_12 − b sigma_21 = 0`.
#[derive(Clone, Debug, PartialEq)]
pub struct MomentLaw {
    pub a: Rational,
    pub b: Rational,
}

/// Reads the coefficients of a moment-balance law given as a polynomial in
/// `dmu_23`, `sigma_12`, `sigma_21` (names in `names`); `Err` if it has any other
/// term or the stress terms are not antisymmetric.
pub fn moment_law(law: &Poly, names: &VarTable) -> Result<MomentLaw, String> {
    let mut a = Rational::zero();
    let mut b12 = Rational::zero();
    let mut b21 = Rational::zero();
    for (m, c) in law.terms() {
        let name = match m.factors() {
            [(v, 1)] => names.name(*v),
            _ => {
                return Err(format!(
                    "the term {} is not linear in one variable",
                    law.display(names)
                ))
            }
        };
        match name {
            "dmu_23" => a = c.clone(),
            "sigma_12" => b12 = c.clone(),
            "sigma_21" => b21 = c.clone(),
            other => {
                return Err(format!(
                    "unexpected variable `{other}` in the moment balance"
                ))
            }
        }
    }
    if a.is_zero() || b12 != -b21.clone() {
        return Err(format!(
            "{} is not of the form a μ̇_23' + b (σ̇_12 − σ̇_21)",
            law.display(names)
        ));
    }
    Ok(MomentLaw { a, b: b12 })
}

/// The derived moment balance (from (2) and (3)) in the form of [`MomentLaw`].
pub fn derived_moment_law() -> MomentLaw {
    let mut names = VarTable::new();
    let law = balance::balance_law(Velocity::W3, 1, &mut names);
    moment_law(&law, &names).expect("the derived law has the form")
}

/// The law as printed in (60): ∂μ̇_23/∂y + σ̇_21 − σ̇_12 = 0.
pub fn printed_moment_law() -> MomentLaw {
    MomentLaw {
        a: Rational::int(1),
        b: Rational::int(-1),
    }
}

/// A² by the elimination of the module documentation, for a tangent with F = 0 (the
/// state of the Appendix; with F ≠ 0 the rates couple Γ and K and the elimination is a
/// different one, which is refused).
pub fn a_squared(p: &Params, t: &Tangent, law: &MomentLaw) -> Result<RatFunc, String> {
    if t.d_k.iter().flatten().any(|x| !x.is_zero()) || !t.m_ep[1][0].is_zero() {
        return Err("the tangent couples Γ and K (F ≠ 0); not the Appendix's state".into());
    }
    let kin = balance::kinematics();
    let unknowns = [kin.dv1, kin.dv2, kin.w3];
    // Coefficient of each unknown in Γ at positions (11, 22, 12, 21).
    let gamma_coef: Vec<[RatFunc; 3]> = tangent::POSITIONS
        .iter()
        .map(|&(i, j)| {
            let g = kin.gamma.get(&[i - 1, j - 1]);
            std::array::from_fn(|u| RatFunc::from_poly(&g.derivative(unknowns[u])))
        })
        .collect();
    // L[a][u]: coefficient of unknown u in σ̇_a.
    let l: Vec<[RatFunc; 3]> = (0..4)
        .map(|a| {
            std::array::from_fn(|u| {
                (0..4).fold(RatFunc::zero(), |acc, b| {
                    &acc + &(&t.d_ep[a][b] * &gamma_coef[b][u])
                })
            })
        })
        .collect();
    let (r22, r12, r21) = (1, 2, 3);
    // Step 1: σ̇_22 and σ̇_21 constant; v_1', v_2' per unit w_3 by Cramer's rule.
    let det = &(&l[r22][0] * &l[r21][1]) - &(&l[r22][1] * &l[r21][0]);
    if det.is_zero() {
        return Err("σ̇_22 = C_2, σ̇_21 = C_1 do not determine v_1', v_2'".into());
    }
    let (e, f) = (-&l[r22][2], -&l[r21][2]);
    let dv1 = (&(&(&e * &l[r21][1]) - &(&l[r22][1] * &f)) / &det).expect("det ≠ 0");
    let dv2 = (&(&(&l[r22][0] * &f) - &(&e * &l[r21][0])) / &det).expect("det ≠ 0");
    // Step 2: α, the coefficient of w_3 in σ̇_12 − σ̇_21.
    let row = |a: usize| &(&(&l[a][0] * &dv1) + &(&l[a][1] * &dv2)) + &l[a][2];
    let alpha = &row(r12) - &row(r21);
    // Step 3: A² = b α R_g² / (a M_22).
    let a = RatFunc::constant(law.a.clone());
    let b = RatFunc::constant(law.b.clone());
    let r2 = p.var(p.r_g).pow(2);
    (&(&(&b * &alpha) * &r2) / &(&a * &t.m_ep[1][1]))
        .ok_or_else(|| "M^(ep)_22 vanishes".to_string())
}

/// A² as printed in eq. (61): 4 (D_3222 D_4421 − D_3421 D_4222)/(D_4222 + D_4421),
/// read with D_IJkl = D^(ep)_IJ / G: I, J the 4-vector positions (3 = 12, 4 = 21,
/// 2 = 22), the last two digits repeating position J as tensor indices; dividing by G
/// makes the printed expression dimensionless like A².
pub fn a_squared_eq61(p: &Params, d_ep: &Mat4) -> Option<RatFunc> {
    let g = p.var(p.g);
    let d = |i: usize, j: usize| (&d_ep[i - 1][j - 1] / &g).expect("G ≠ 0");
    let num = &(&d(3, 2) * &d(4, 4)) - &(&d(3, 4) * &d(4, 2));
    &(&RatFunc::int(4) * &num) / &(&d(4, 2) + &d(4, 4))
}

/// A² of eq. (54): 16 f_r²(1 + 2f_r²) / (1 + 8f_r²(1 + 3f_r²)).
pub fn a_squared_eq54(p: &Params) -> RatFunc {
    let f2 = p.var(p.f_r).pow(2);
    let one = RatFunc::one();
    let num = &(&RatFunc::int(16) * &f2) * &(&one + &(&RatFunc::int(2) * &f2));
    let den = &one + &(&(&RatFunc::int(8) * &f2) * &(&one + &(&RatFunc::int(3) * &f2)));
    (&num / &den).expect("1 + 8f²(1 + 3f²) is not identically 0")
}

/// The derived expressions of the Appendix, all exact.
#[derive(Clone, Debug)]
pub struct Derivation {
    pub tangent: Tangent,
    /// A² following the Appendix as printed, (60) included.
    pub a2_printed_balance: RatFunc,
    /// A² with the balance law derived from (2) and (3).
    pub a2_derived_balance: RatFunc,
    /// The printed (61) evaluated with the derived D^(ep).
    pub a2_eq61: RatFunc,
    /// (54).
    pub a2_eq54: RatFunc,
}

pub fn derive(p: &Params, shear: ShearSign) -> Result<Derivation, String> {
    let grad = tangent::yield_gradient_exact(p, shear)?;
    let t = tangent::elastoplastic_tangent(p, &grad);
    Ok(Derivation {
        a2_printed_balance: a_squared(p, &t, &printed_moment_law())?,
        a2_derived_balance: a_squared(p, &t, &derived_moment_law())?,
        a2_eq61: a_squared_eq61(p, &t.d_ep).ok_or("(61) divides by D_4222 + D_4421 = 0")?,
        a2_eq54: a_squared_eq54(p),
        tangent: t,
    })
}

/// A² following the Appendix as printed at the rotated state of
/// [`tangent::yield_gradient_rotated`] (σ_11 ≠ σ_22), for a material fixed to numbers
/// (K, G, h^C, h_2, R_g of `at`): a function of f_r and t = tan(α/2). (Symbolic in every
/// parameter and t at once, the gcds take minutes.)
pub fn a_squared_rotated(p: &Params, at: &ExactPoint) -> Result<RatFunc, String> {
    let grad = tangent::yield_gradient_rotated(p)?;
    let material = |v| (v != p.f_r && v != p.t).then(|| at.value(p, v));
    let fix = |x: &RatFunc| x.fix(&material).ok_or("a pole at the material".to_string());
    let d: Vec<Vec<RatFunc>> = tangent::elastic_stiffness(p)
        .iter()
        .map(|row| row.iter().map(fix).collect())
        .collect::<Result<_, _>>()?;
    let d: tangent::Mat4 = std::array::from_fn(|a| std::array::from_fn(|b| d[a][b].clone()));
    let m = tangent::couple_stiffness(p);
    let m: tangent::Mat2 = [
        [fix(&m[0][0])?, fix(&m[0][1])?],
        [fix(&m[1][0])?, fix(&m[1][1])?],
    ];
    let t = tangent::elastoplastic_tangent_with(&grad, &d, &m, &RatFunc::constant(at.h_2.clone()));
    fix(&a_squared(p, &t, &printed_moment_law())?)
}

/// A² in `f64` by an independent route: the D^(ep) of [`tangent::elastoplastic_f64`]
/// (num-dual gradient, nalgebra), the same two balance equations solved by nalgebra's
/// LU decomposition, and the moment balance with coefficients (a, b).
pub fn a_squared_f64(pt: &Point, shear: ShearSign, a: f64, b: f64) -> Option<f64> {
    a_squared_f64_from(&tangent::elastoplastic_f64(pt, shear), pt, a, b)
}

/// [`a_squared_f64`] for a given f64 D^(ep) (e.g. at another state).
pub fn a_squared_f64_from(d: &nalgebra::Matrix4<f64>, pt: &Point, a: f64, b: f64) -> Option<f64> {
    // Γ = G_u · (v_1', v_2', w_3): written out from (2) by hand, not from `kinematics`.
    #[rustfmt::skip]
    let gu = nalgebra::Matrix4x3::new(
        0.0, 0.0, 0.0, // Γ_11
        0.0, 1.0, 0.0, // Γ_22 = v_2'
        0.0, 0.0, -1.0, // Γ_12 = −w_3
        1.0, 0.0, 1.0, // Γ_21 = v_1' + w_3
    );
    let l = d * gu; // σ̇ = L (v_1', v_2', w_3)
    let sys = nalgebra::Matrix2::new(l[(1, 0)], l[(1, 1)], l[(3, 0)], l[(3, 1)]);
    let rhs = nalgebra::Vector2::new(-l[(1, 2)], -l[(3, 2)]);
    let x = sys.lu().solve(&rhs)?;
    let coef = |r: usize| l[(r, 0)] * x[0] + l[(r, 1)] * x[1] + l[(r, 2)];
    let alpha = coef(2) - coef(3);
    let m22 = 4.0 * pt.g * pt.r_g * pt.r_g;
    Some(b * alpha * pt.r_g * pt.r_g / (a * m22))
}

/// The solutions of w'' + A² w = 0 that satisfy μ_23 ∝ w' = 0 at x_2 = ±d (eq. 62):
/// w = C cos(A x_2) + S sin(A x_2) needs (C, S) in the kernel of
/// [[−sin(A d), cos(A d)], [sin(A d), cos(A d)]], whose determinant −sin(2 A d)
/// vanishes at A d = kπ/2. Returns, for k = 1, 2, …, `kmax`, the mode: `"symmetric"`
/// (C ≠ 0, w even: sin(A d) = 0) or `"antisymmetric"` (S ≠ 0, w odd: cos(A d) = 0).
/// Sines and cosines of multiples of π/2 are exact integers.
pub fn boundary_modes(kmax: u32) -> Vec<(u32, &'static str)> {
    let sin_cos = |k: u32| match k % 4 {
        0 => (0, 1),
        1 => (1, 0),
        2 => (0, -1),
        _ => (-1, 0),
    };
    (1..=kmax)
        .filter_map(|k| {
            let (s, c) = sin_cos(k);
            // det = −2 sin cos; the kernel is (1, 0) when sin = 0 and (0, 1) when cos = 0.
            (-2 * s * c == 0).then_some((k, if s == 0 { "symmetric" } else { "antisymmetric" }))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn moment_laws_are_read_off() {
        assert_eq!(
            derived_moment_law(),
            MomentLaw {
                a: Rational::int(1),
                b: Rational::int(1)
            }
        );
    }

    #[test]
    fn exact_and_float_routes_agree() {
        let p = Params::new();
        let d = derive(&p, ShearSign::Positive).unwrap();
        for (f_r, nu) in [(0.3, 0.0), (1.0, 0.25), (2.5, 0.45)] {
            let pt = Point::figure(f_r, nu);
            let exact = d.a2_printed_balance.eval_f64(&|v| pt.value(&p, v));
            let float = a_squared_f64(&pt, ShearSign::Positive, 1.0, -1.0).unwrap();
            assert!(
                (exact - float).abs() <= 1e-12 * exact.abs().max(1.0),
                "{exact} {float}"
            );
        }
    }

    #[test]
    fn modes_alternate() {
        assert_eq!(
            boundary_modes(4),
            [
                (1, "antisymmetric"),
                (2, "symmetric"),
                (3, "antisymmetric"),
                (4, "symmetric")
            ]
        );
    }
}
