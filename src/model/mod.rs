//! The paper's own objects for Appendix A: the elastic matrices (57), the rolling
//! yield surface F₂ (50) at the state of incipient failure, the elastoplastic tangent
//! (55)–(56) from the consistency condition, the acoustic tensor, the balance laws of
//! the simple-shear problem (58)–(60) and the shear-band parameter A² (61), (54).
//!
//! Everything is computed exactly as reduced rational functions ([`RatFunc`]) of
//! named parameters, with an independent `f64` route (num-dual gradients, nalgebra
//! linear algebra) for the cross-checks.
//!
//! Conventions used throughout (each claim's note repeats the ones it depends on):
//! - the plane problem: in-plane stresses σ_11, σ_22, σ_12, σ_21 and couple stresses
//!   μ_13, μ_23; their rates σ̇ = D Γ and μ̇_i3 = M_ij K_j3;
//! - 4-vectors are ordered (11, 22, 12, 21), as in (57): position 1 ↔ 11, 2 ↔ 22,
//!   3 ↔ 12, 4 ↔ 21;
//! - Γ_ij = v_j,i − e_ijk w_k and K_ij = w_j,i (eq. 2: the FIRST index is the gradient
//!   index), e_123 = +1;
//! - stresses are positive in tension;
//! - lengths are measured in units of R_g, so A is dimensionless and d_B/R_g = π/A.

pub mod acoustic;
pub mod balance;
pub mod fig6;
pub mod shear_band;
pub mod tangent;

use crate::kernel::{RatFunc, Rational, Var, VarTable};

/// The named parameters of the Appendix, interned once so that every derived
/// expression prints with the same names.
#[derive(Clone, Debug)]
pub struct Params {
    pub names: VarTable,
    /// Rolling resistance f_r.
    pub f_r: Var,
    /// Normalised bulk modulus K = 1/(1 − 2ν).
    pub k: Var,
    /// Shear modulus G.
    pub g: Var,
    /// Cosserat shear modulus ratio h^C = G^C/G.
    pub h_c: Var,
    /// Hardening modulus of the rolling surface h_2.
    pub h_2: Var,
    /// Grain radius R_g.
    pub r_g: Var,
    /// The normal stress σ = σ_11 = σ_22 of the state (compression: σ < 0).
    pub sigma: Var,
    /// t = tan(α/2) of a state with σ_11 ≠ σ_22 ([`tangent::yield_gradient_rotated`]).
    pub t: Var,
    /// Components of the band normal n = (n_1, n_2).
    pub n_1: Var,
    pub n_2: Var,
}

impl Default for Params {
    fn default() -> Self {
        Params::new()
    }
}

impl Params {
    pub fn new() -> Self {
        let mut names = VarTable::new();
        let f_r = names.intern("f_r");
        let k = names.intern("K");
        let g = names.intern("G");
        let h_c = names.intern("h_C");
        let h_2 = names.intern("h_2");
        let r_g = names.intern("R_g");
        let sigma = names.intern("sigma");
        let t = names.intern("t");
        let n_1 = names.intern("n_1");
        let n_2 = names.intern("n_2");
        Params {
            names,
            f_r,
            k,
            g,
            h_c,
            h_2,
            r_g,
            sigma,
            t,
            n_1,
            n_2,
        }
    }

    pub fn var(&self, v: Var) -> RatFunc {
        RatFunc::var(v)
    }

    pub fn display(&self, f: &RatFunc) -> String {
        f.display(&self.names)
    }

    pub fn latex(&self, f: &RatFunc) -> String {
        f.latex(&self.names)
    }
}

/// A numeric point in parameter space (for the float routes and the figure).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point {
    pub f_r: f64,
    pub k: f64,
    pub g: f64,
    pub h_c: f64,
    pub h_2: f64,
    pub r_g: f64,
}

impl Point {
    /// The figure's material: h^C = 1/2 and h_2 = 0 ([44]; Appendix A), G = R_g = 1.
    pub fn figure(f_r: f64, nu: f64) -> Self {
        Point {
            f_r,
            k: 1.0 / (1.0 - 2.0 * nu),
            g: 1.0,
            h_c: 0.5,
            h_2: 0.0,
            r_g: 1.0,
        }
    }

    /// The value of each parameter variable (σ is not a parameter of the results).
    pub fn value(&self, p: &Params, v: Var) -> f64 {
        match v {
            _ if v == p.f_r => self.f_r,
            _ if v == p.k => self.k,
            _ if v == p.g => self.g,
            _ if v == p.h_c => self.h_c,
            _ if v == p.h_2 => self.h_2,
            _ if v == p.r_g => self.r_g,
            _ => f64::NAN,
        }
    }
}

/// An exact point: every parameter a rational number.
#[derive(Clone, Debug, PartialEq)]
pub struct ExactPoint {
    pub f_r: Rational,
    pub k: Rational,
    pub g: Rational,
    pub h_c: Rational,
    pub h_2: Rational,
    pub r_g: Rational,
}

impl ExactPoint {
    pub fn value(&self, p: &Params, v: Var) -> Rational {
        match v {
            _ if v == p.f_r => self.f_r.clone(),
            _ if v == p.k => self.k.clone(),
            _ if v == p.g => self.g.clone(),
            _ if v == p.h_c => self.h_c.clone(),
            _ if v == p.h_2 => self.h_2.clone(),
            _ if v == p.r_g => self.r_g.clone(),
            _ => Rational::int(0),
        }
    }

    pub fn to_f64(&self) -> Point {
        Point {
            f_r: self.f_r.to_f64(),
            k: self.k.to_f64(),
            g: self.g.to_f64(),
            h_c: self.h_c.to_f64(),
            h_2: self.h_2.to_f64(),
            r_g: self.r_g.to_f64(),
        }
    }

    /// Plain text `f_r = 1/2, K = 2, …`.
    pub fn describe(&self) -> String {
        format!(
            "f_r = {}, K = {}, G = {}, h_C = {}, h_2 = {}, R_g = {}",
            self.f_r, self.k, self.g, self.h_c, self.h_2, self.r_g
        )
    }
}
