//! Fields as explicit functions of the position, for the second route of a claim about
//! derivatives. The exact route treats a field's derivatives at a point as independent
//! jet variables and differentiates symbolically (`eval.rs`); this route builds, from
//! the same jet values, the Taylor polynomial of each field component about the point,
//! and differentiates the *expression* numerically by central differences of its
//! values at nearby positions. The two share no differentiation code.

use super::eval::Varying;
use crate::kernel::{Rational, Var, VarTable};
use num_dual::DualNum;
use std::collections::{BTreeMap, HashMap};

/// Step of the central differences. The five-point stencil is exact for polynomials of
/// degree ≤ 4 in the step and has truncation error h⁴/30 · |f⁽⁵⁾| otherwise; rounding
/// adds about ε/h per level of nesting.
pub const STEP: f64 = 1e-3;

/// Relative agreement required between an exact value involving derivatives and the
/// difference quotients' value: the stencil's error at [`STEP`], nested up to three
/// derivatives deep (ε/h³ ≈ 2e-7), with a margin.
pub const AGREEMENT: f64 = 1e-5;

/// The fields of a claim as Taylor polynomials about `centre`.
#[derive(Clone, Debug, Default)]
pub struct TaylorFields {
    pub centre: Vec<f64>,
    /// (field, component) → (exponent of each coordinate, coefficient / α!).
    terms: HashMap<(String, Vec<usize>), Vec<(Vec<u32>, f64)>>,
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
        point: &dyn Fn(Var) -> Option<Rational>,
        absent: f64,
    ) -> Self {
        let mut centre = vec![absent; dim];
        let mut jets: BTreeMap<(String, Vec<usize>), Vec<(Vec<u32>, f64)>> = BTreeMap::new();
        let mut ordered: Vec<(&Var, &Varying)> = varying.iter().collect();
        ordered.sort_by_key(|(v, _)| vars.name(**v).to_owned());
        for (&v, what) in ordered {
            let value = point(v).map(|q| q.to_f64());
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

    /// Sets a component that the point does not determine through its own jets (a
    /// component an assumption ties to others) to a combination of other components:
    /// `Σ q · other + constant`, term by term of the Taylor polynomials.
    pub fn tie(
        &mut self,
        (field, idx): (&str, &[usize]),
        terms: &[((String, Vec<usize>), f64)],
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

/// The derivative by the five-point central stencil from values at −2h, −h, h, 2h.
pub fn stencil<T: DualNum<Primitive = f64>>([m2, m1, p1, p2]: [T; 4]) -> T {
    (m2 - m1 * 8.0 + p1 * 8.0 - p2) * (1.0 / (12.0 * STEP))
}
