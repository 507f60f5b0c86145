//! Fields as explicit functions of the position, for the second route of a claim about
//! derivatives. The exact route treats a field's derivatives at a point as independent
//! jet variables and differentiates symbolically (`exact/env.rs`); this route builds, from
//! the same jet values, the Taylor polynomial of each field component about the point,
//! and differentiates the *expression* numerically by central differences of its
//! values at nearby positions. The two share no differentiation code.

use super::exact::env::Varying;
use crate::algebra::{assignments, Tensor};
use crate::kernel::{Var, VarTable};
use crate::lang::Decls;
use num_dual::DualNum;
use rustc_hash::FxHashMap as HashMap;
use std::collections::BTreeMap;

/// A field component: the field's name and the component's indices (0-based).
type Component = (String, Vec<usize>);

/// A polynomial in the displacement from the centre: (exponent of each coordinate,
/// coefficient).
type Polynomial = Vec<(Vec<u32>, f64)>;

/// The fields of a claim as Taylor polynomials about `centre`.
#[derive(Clone, Debug, Default)]
pub struct TaylorFields {
    pub centre: Vec<f64>,
    /// (field, component) → (exponent of each coordinate, coefficient / α!).
    terms: HashMap<Component, Polynomial>,
}

impl TaylorFields {
    /// The Taylor polynomials whose derivatives at the centre are the values `point`
    /// gives the jet variables (`absent` for a component's own value when the point
    /// leaves it out; 0 for its derivatives), centred where the point puts the
    /// position's coordinates.
    pub fn new(
        dim: usize,
        varying: &HashMap<Var, Varying>,
        vars: &VarTable,
        point: &dyn Fn(Var) -> Option<f64>,
        absent: f64,
    ) -> Self {
        let mut centre = vec![absent; dim];
        let mut jets: BTreeMap<Component, Polynomial> = BTreeMap::new();
        let mut ordered: Vec<(&Var, &Varying)> = varying.iter().collect();
        ordered.sort_by_key(|(v, _)| vars.name(**v).to_owned());
        for (&v, what) in ordered {
            let value = point(v);
            match what {
                Varying::Coordinate(k) => {
                    if let Some(x) = value {
                        centre[*k] = x;
                    }
                }
                Varying::Jet { field, idx, orders } => {
                    let value = value.unwrap_or(if orders.is_empty() { absent } else { 0.0 });
                    let mut exponents = vec![0u32; dim];
                    for &k in orders {
                        exponents[k] += 1;
                    }
                    let factorial: f64 = exponents
                        .iter()
                        .map(|&e| (1..=e).map(f64::from).product::<f64>())
                        .product();
                    jets.entry((field.clone(), idx.clone()))
                        .or_default()
                        .push((exponents, value / factorial));
                }
            }
        }
        TaylorFields {
            centre,
            terms: jets.into_iter().collect(),
        }
    }

    /// Random fields for sampling: every component of every field a polynomial of
    /// degree ≤ `order` in the coordinates it depends on, coefficients from `uniform`,
    /// about a random centre.
    pub fn random(decls: &Decls, order: u32, uniform: &mut dyn FnMut() -> f64) -> Self {
        let dim = decls.dim;
        let centre: Vec<f64> = (0..dim).map(|_| uniform()).collect();
        let mut terms = HashMap::default();
        for (field, deps) in &decls.fields {
            let rank = decls.symbols.get(field).copied().unwrap_or(0);
            let exponents: Vec<Vec<u32>> = (0..(order + 1).pow(dim as u32))
                .map(|mut flat| {
                    (0..dim)
                        .map(|k| {
                            let e = flat % (order + 1);
                            flat /= order + 1;
                            if deps[k] {
                                e
                            } else {
                                0
                            }
                        })
                        .collect::<Vec<u32>>()
                })
                .filter(|e| e.iter().sum::<u32>() <= order)
                .collect::<std::collections::BTreeSet<_>>()
                .into_iter()
                .collect();
            for idx in assignments(dim, rank) {
                let poly = exponents.iter().map(|e| (e.clone(), uniform())).collect();
                terms.insert((field.clone(), idx), poly);
            }
        }
        TaylorFields { centre, terms }
    }

    /// Sets a component that the point does not determine through its own jets (a
    /// component an assumption ties to others) to a combination of other components:
    /// `Σ q · other + constant`, term by term of the Taylor polynomials.
    pub fn tie(
        &mut self,
        (field, idx): (&str, &[usize]),
        terms: &[(Component, f64)],
        constant: f64,
    ) {
        let mut combined: BTreeMap<Vec<u32>, f64> = BTreeMap::new();
        combined.insert(vec![0; self.centre.len()], constant);
        for (other, q) in terms {
            for (e, c) in self.terms.get(other).into_iter().flatten() {
                *combined.entry(e.clone()).or_default() += q * c;
            }
        }
        self.terms.insert(
            (field.to_owned(), idx.to_vec()),
            combined.into_iter().collect(),
        );
    }

    /// Component `idx` of `field` at `x`, if the field has jets.
    pub fn value(&self, field: &str, idx: &[usize], x: &[f64]) -> Option<f64> {
        let terms = self.terms.get(&(field.to_owned(), idx.to_vec()))?;
        Some(
            terms
                .iter()
                .map(|(e, c)| {
                    e.iter()
                        .zip(x.iter().zip(&self.centre))
                        .fold(*c, |acc, (&p, (xi, ci))| acc * (xi - ci).powi(p as i32))
                })
                .sum(),
        )
    }

    /// Whether a field has any jets here.
    pub fn has(&self, field: &str) -> bool {
        self.terms.keys().any(|(f, _)| f == field)
    }
}

/// The positions of the stencil, in steps: −2h, −h, h, 2h.
pub const STEPS: [f64; 4] = [-2.0, -1.0, 1.0, 2.0];

/// The five-point stencil with step `h`, component by component, from the values at
/// the four [`STEPS`].
pub fn stencil_tensor<T: DualNum<Primitive = f64>>(values: &[Tensor<T>], h: f64) -> Tensor<T> {
    let t = &values[0];
    Tensor::from_fn(t.dim(), t.rank(), |i| {
        stencil_with([0, 1, 2, 3].map(|j| values[j].get(i).clone()), h)
    })
}

/// The derivative by the five-point central stencil with step `h`, from the values at
/// the four [`STEPS`].
pub fn stencil_with<T: DualNum<Primitive = f64>>([m2, m1, p1, p2]: [T; 4], h: f64) -> T {
    (m2 - m1 * 8.0 + p1 * 8.0 - p2) * (1.0 / (12.0 * h))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::Rational;
    use crate::tolerance::TAYLOR_STEP;

    /// u(x) with u = 2, u_,1 = 3, u_,12 = 5, u_,11 = 4 at the centre (1, 0, -1).
    fn field() -> TaylorFields {
        let mut vars = VarTable::new();
        let mut varying = HashMap::default();
        let mut values = HashMap::default();
        for (orders, value) in [(vec![], 2), (vec![0], 3), (vec![0, 1], 5), (vec![0, 0], 4)] {
            let v = vars.intern(&format!("u{orders:?}"));
            varying.insert(
                v,
                Varying::Jet {
                    field: "u".into(),
                    idx: vec![],
                    orders,
                },
            );
            values.insert(v, Rational::int(value));
        }
        for k in 0..3 {
            let v = vars.intern(&format!("x{k}"));
            varying.insert(v, Varying::Coordinate(k));
            values.insert(v, Rational::int(1 - k as i64));
        }
        TaylorFields::new(
            3,
            &varying,
            &vars,
            &|v| values.get(&v).map(Rational::to_f64),
            0.0,
        )
    }

    #[test]
    fn the_polynomial_has_the_jets_as_derivatives() {
        let f = field();
        assert_eq!(f.centre, vec![1.0, 0.0, -1.0]);
        let u = |x: [f64; 3]| f.value("u", &[], &x).unwrap();
        assert_eq!(u([1.0, 0.0, -1.0]), 2.0);
        let h = TAYLOR_STEP;
        let d1 = |x: [f64; 3]| stencil_with(STEPS.map(|s| u([x[0] + s * h, x[1], x[2]])), h);
        let d2 = |x: [f64; 3]| stencil_with(STEPS.map(|s| u([x[0], x[1] + s * h, x[2]])), h);
        let c = [1.0, 0.0, -1.0];
        assert!((d1(c) - 3.0).abs() < 1e-9);
        assert!(d2(c).abs() < 1e-9);
        let d11 = stencil_with(STEPS.map(|s| d1([1.0 + s * h, 0.0, -1.0])), h);
        let d12 = stencil_with(STEPS.map(|s| d1([1.0, s * h, -1.0])), h);
        assert!((d11 - 4.0).abs() < 1e-6, "{d11}");
        assert!((d12 - 5.0).abs() < 1e-6, "{d12}");
        assert!(f.value("v", &[], &c).is_none());
    }

    #[test]
    fn a_tied_component_combines_the_others_term_by_term() {
        let mut f = field();
        f.tie(("w", &[]), &[(("u".into(), vec![]), -2.0)], 1.0);
        let x = [1.5, 0.25, 0.0];
        let (u, w) = (
            f.value("u", &[], &x).unwrap(),
            f.value("w", &[], &x).unwrap(),
        );
        assert!((w - (1.0 - 2.0 * u)).abs() < 1e-12);
    }
}
