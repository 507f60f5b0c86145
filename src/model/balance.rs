//! The balance laws of the simple-shear problem, derived from the virtual power (3)
//! with the kinematics (2), for fields that depend on x_2 only.
//!
//! With P = σ_ij Γ_ij + μ_ij K_ij, Γ_ij = v_j,i − e_ijk w_k and K_ij = w_j,i, and the
//! generalised velocities v_1, v_2, w_3 of the plane problem, the principle of virtual
//! power (no body forces or couples) gives one Euler–Lagrange equation per velocity q:
//!
//!   d/dx_2 (∂P/∂q') − ∂P/∂q = 0.
//!
//! The computation is symbolic in the stress components: the variable `sigma_ij`
//! stands for σ_ij (a rate σ̇_ij in the Appendix's use) and `dsigma_ij` for its
//! derivative ∂σ_ij/∂x_2, likewise `mu_ij` and `dmu_ij`. The result is compared with
//! the printed (58)–(60) in `strategy::appendix`.

use crate::kernel::{Poly, Rational, Tensor, Var, VarTable};
use num_traits::Zero;

/// The generalised velocities of the plane problem.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Velocity {
    V1,
    V2,
    W3,
}

impl Velocity {
    pub const ALL: [Velocity; 3] = [Velocity::V1, Velocity::V2, Velocity::W3];

    pub fn name(self) -> &'static str {
        match self {
            Velocity::V1 => "v_1",
            Velocity::V2 => "v_2",
            Velocity::W3 => "w_3",
        }
    }

    pub fn parse(s: &str) -> Option<Self> {
        Velocity::ALL.into_iter().find(|v| v.name() == s)
    }
}

/// The kinematic variables of the fields of x_2 alone: v_1', v_2', w_3 and w_3'.
pub struct Kinematics {
    pub names: VarTable,
    pub dv1: Var,
    pub dv2: Var,
    pub w3: Var,
    pub dw3: Var,
    /// Γ_ij of eq. (2), 3D indices, as polynomials linear in v_1', v_2', w_3.
    pub gamma: Tensor<Poly>,
    /// K_ij of eq. (2).
    pub kappa: Tensor<Poly>,
}

/// Γ_ij = v_j,i − e_ijk w_k and K_ij = w_j,i (eq. 2) for v = (v_1(x_2), v_2(x_2), 0)
/// and w = (0, 0, w_3(x_2)): a derivative ∂/∂x_i is δ_i2 d/dx_2.
pub fn kinematics() -> Kinematics {
    let mut names = VarTable::new();
    let dv1 = names.intern("v_1'");
    let dv2 = names.intern("v_2'");
    let w3 = names.intern("w_3");
    let dw3 = names.intern("w_3'");
    let dv = [Poly::var(dv1), Poly::var(dv2), Poly::zero()];
    let w = [Poly::zero(), Poly::zero(), Poly::var(w3)];
    let dw = [Poly::zero(), Poly::zero(), Poly::var(dw3)];
    let eps = Tensor::<Poly>::levi_civita(3);
    let gamma = Tensor::from_fn(3, 2, |ij| {
        let (i, j) = (ij[0], ij[1]);
        let grad = if i == 1 { dv[j].clone() } else { Poly::zero() };
        let rot = (0..3).fold(Poly::zero(), |acc, k| &acc + &(eps.get(&[i, j, k]) * &w[k]));
        &grad - &rot
    });
    let kappa = Tensor::from_fn(3, 2, |ij| {
        if ij[0] == 1 {
            dw[ij[1]].clone()
        } else {
            Poly::zero()
        }
    });
    Kinematics {
        names,
        dv1,
        dv2,
        w3,
        dw3,
        gamma,
        kappa,
    }
}

/// The derived balance law of one velocity, as a polynomial in the variables
/// `sigma_ij`, `mu_ij`, `dsigma_ij`, `dmu_ij` (interned into `names`), set equal to 0.
/// `sign` = +1 is the paper's eq. (2); −1 flips the sign of the rotation term,
/// Γ_ij = v_j,i + e_ijk w_k, the other convention found in the literature.
pub fn balance_law(v: Velocity, rotation_sign: i64, names: &mut VarTable) -> Poly {
    let kin = kinematics();
    let sign = Poly::constant(Rational::int(rotation_sign));
    let stress = |names: &mut VarTable, prefix: &str, i: usize, j: usize| {
        Poly::var(names.intern(&format!("{prefix}_{}{}", i + 1, j + 1)))
    };
    // P = σ_ij Γ_ij + μ_ij K_ij, with the rotation term of Γ scaled by `rotation_sign`.
    let (q_var, dq_var) = match v {
        Velocity::V1 => (None, kin.dv1),
        Velocity::V2 => (None, kin.dv2),
        Velocity::W3 => (Some(kin.w3), kin.dw3),
    };
    let mut flux = Poly::zero(); // ∂P/∂q', with d/dx_2 applied below
    let mut source = Poly::zero(); // ∂P/∂q
    for i in 0..3 {
        for j in 0..3 {
            let g = kin.gamma.get(&[i, j]);
            // Split Γ_ij into its gradient part (in v') and rotation part (in w_3).
            let rot = g.derivative(kin.w3);
            let grad = g - &(&rot * &Poly::var(kin.w3));
            let g = &grad + &(&(&rot * &Poly::var(kin.w3)) * &sign);
            let k = kin.kappa.get(&[i, j]);
            let s = stress(names, "sigma", i, j);
            let ds = stress(names, "dsigma", i, j);
            let m = stress(names, "mu", i, j);
            let dm = stress(names, "dmu", i, j);
            flux += &(&ds * &g.derivative(dq_var));
            flux += &(&dm * &k.derivative(dq_var));
            if let Some(qv) = q_var {
                source += &(&s * &g.derivative(qv));
                source += &(&m * &k.derivative(qv));
            }
        }
    }
    &flux - &source
}

/// `Some(λ)` with `a = λ b`, λ ≠ 0, when the two polynomials are proportional.
pub fn proportional(a: &Poly, b: &Poly) -> Option<Rational> {
    let (m, cb) = b.terms().next()?;
    let ca = a.terms().find(|(ma, _)| *ma == m).map(|(_, c)| c.clone())?;
    let lambda = ca.checked_div(cb)?;
    (a == &(b * &Poly::constant(lambda.clone()))).then_some(lambda)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kinematics_of_the_shear_layer() {
        let k = kinematics();
        let show = |i: usize, j: usize| k.gamma.get(&[i - 1, j - 1]).display(&k.names);
        assert_eq!(show(2, 1), "v_1' + w_3");
        assert_eq!(show(1, 2), "-w_3");
        assert_eq!(show(2, 2), "v_2'");
        assert_eq!(show(1, 1), "0");
        assert_eq!(k.kappa.get(&[1, 2]).display(&k.names), "w_3'");
    }

    #[test]
    fn derived_balance_laws() {
        let mut names = VarTable::new();
        let law = |v, s, names: &mut VarTable| {
            let p = balance_law(v, s, names);
            p.display(names)
        };
        assert_eq!(law(Velocity::V1, 1, &mut names), "dsigma_21");
        assert_eq!(law(Velocity::V2, 1, &mut names), "dsigma_22");
        assert_eq!(
            law(Velocity::W3, 1, &mut names),
            "sigma_12 - sigma_21 + dmu_23"
        );
        assert_eq!(
            law(Velocity::W3, -1, &mut names),
            "-sigma_12 + sigma_21 + dmu_23"
        );
    }

    #[test]
    fn proportionality_is_exact() {
        let mut names = VarTable::new();
        let a = Poly::var(names.intern("a"));
        let b = Poly::var(names.intern("b"));
        let two = Poly::constant(Rational::int(2));
        assert_eq!(
            proportional(&(&(&a + &b) * &two), &(&a + &b)),
            Some(Rational::int(2))
        );
        assert_eq!(proportional(&(&a - &b), &(&a + &b)), None);
        assert_eq!(proportional(&a, &Poly::zero()), None);
    }
}
