//! The second route of `variation(P, v_j)`: the Euler operator by perturbing the
//! field, not by differentiating with respect to jet variables.
//!
//! At a point y, ∂P/∂v_j,α is the rate of change of P(y) when v_j is perturbed by
//! ε (x − y)^α / α!: that perturbation has, at y, the α-th derivative 1 and every other
//! derivative 0. The route evaluates P with the perturbed field for four values of ε
//! (the five-point stencil in ε), then applies the total derivatives D_α by central
//! differences of that whole procedure at positions moved from y, the perturbation
//! moving with them. It shares the expression walk with the exact route and nothing
//! else: no jet variables, no symbolic ∂P/∂v_j,α.

use super::env::{Perturbation, RealEnv};
use super::error::RealError;
use crate::algebra::{assignments, Tensor};
use crate::derivation::Definition;
use crate::eval::{taylor, walk};
use crate::lang::{Node, NodeKind, Target};
use crate::tolerance::VARIATION_STEP;
use num_dual::DualNum;
use rustc_hash::FxHashMap as HashMap;

/// The deepest nesting of derivatives above a leaf that `counts` accepts, through
/// definitions (`None`: no such leaf). With the varied field's leaves, it bounds the
/// order of its derivatives that the density reads: the multi-indices α the route
/// visits (a bound is enough, since a term with ∂P/∂v_j,α = 0 contributes only
/// rounding). With every leaf, it is the depth of the central differences inside the
/// density: each level amplifies the rounding of the next and multiplies the cost.
fn deepest(
    node: &Node,
    defs: &[Definition],
    counts: &dyn Fn(&Node) -> bool,
    memo: &mut HashMap<String, Option<usize>>,
) -> Option<usize> {
    if let Some(name) = node.definition() {
        if let Some(o) = memo.get(name) {
            return *o;
        }
        memo.insert(name.to_owned(), None);
        let o = defs
            .iter()
            .rev()
            .find(|d| d.sig.name == name)
            .and_then(|d| deepest(&d.body, defs, counts, memo));
        memo.insert(name.to_owned(), o);
        return o;
    }
    match &node.kind {
        NodeKind::Deriv(a, _) => deepest(a, defs, counts, memo).map(|o| o + 1),
        _ => {
            let children = node.children();
            if children.is_empty() {
                return counts(node).then_some(0);
            }
            children
                .into_iter()
                .filter_map(|c| deepest(c, defs, counts, memo))
                .max()
        }
    }
}

/// Largest number of nested central differences the route takes (the derivatives
/// inside the density plus those of α): a second-gradient density (u_i,jj, moved off
/// twice) needs 4. Deeper nesting would be slow and, in `f64`, not accurate enough.
pub const MAX_NESTING: usize = 4;

/// Multisets of `coords` of sizes 0..=`order`, each sorted.
fn multi_indices(coords: &[usize], order: usize) -> Vec<Vec<usize>> {
    let mut out = vec![Vec::new()];
    let mut last = vec![Vec::new()];
    for _ in 0..order {
        let mut next = Vec::new();
        for a in &last {
            for &k in coords.iter().filter(|&&k| a.last().is_none_or(|&l| k >= l)) {
                let mut b: Vec<usize> = a.clone();
                b.push(k);
                next.push(b);
            }
        }
        out.extend(next.iter().cloned());
        last = next;
    }
    out
}

/// The variational derivatives of `body` with respect to `field` (slots: the body's,
/// then the field's), by perturbation and central differences.
pub fn variations<T: DualNum<Primitive = f64>>(
    env: &RealEnv<'_, T>,
    body: &Node,
    field: &str,
    node: &Node,
    n: &[f64],
) -> Result<Tensor<T>, RealError> {
    let fail = |m: &str| RealError {
        span: node.span,
        message: m.to_owned(),
        pointwise: false,
    };
    if env.fields.is_none() {
        return Err(fail(
            "a variation is decided exactly: sampling has no fields to perturb",
        ));
    }
    if env.defines(field) {
        return Err(fail(
            "the varied field is defined by an assumption, so it cannot be varied",
        ));
    }
    if env.perturbation.borrow().is_some() {
        return Err(fail("a variation inside a variation is not supported"));
    }
    let d = env.decls.dim;
    let deps = &env.decls.fields[field];
    let coords: Vec<usize> = (0..d).filter(|&k| deps[k]).collect();
    let is_field = |x: &Node| matches!(&x.kind, NodeKind::Leaf { target: Target::Symbol(s), .. } if s == field);
    let order = deepest(body, env.defs, &is_field, &mut HashMap::default()).unwrap_or(0);
    let inside = deepest(body, env.defs, &|_| true, &mut HashMap::default()).unwrap_or(0);
    let depth = inside + order;
    if depth > MAX_NESTING {
        return Err(fail(&format!(
            "the variation needs {depth} nested central differences, more than the {MAX_NESTING} this route resolves"
        )));
    }
    let alphas = multi_indices(&coords, order);
    let rank = env.decls.symbols.get(field).copied().unwrap_or(0);
    let body_rank = body.free_letters().len();
    let mut per_component = Vec::new();
    for idx in assignments(d, rank) {
        let mut acc = Tensor::from_fn(d, body_rank, |_| T::zero());
        for alpha in &alphas {
            let mut exponents = vec![0u32; d];
            for &k in alpha {
                exponents[k] += 1;
            }
            let rate = |env: &RealEnv<'_, T>| -> Result<Tensor<T>, RealError> {
                let centre = env.position.borrow().clone();
                let mut values = Vec::with_capacity(4);
                for step in taylor::STEPS {
                    env.perturb(Some(Perturbation {
                        field: field.to_owned(),
                        idx: idx.clone(),
                        exponents: exponents.clone(),
                        centre: centre.clone(),
                        amount: step * VARIATION_STEP,
                    }));
                    let v = walk::walk(&mut { env }, body, n);
                    env.perturb(None);
                    values.push(v?);
                }
                Ok(taylor::stencil_tensor(&values, VARIATION_STEP))
            };
            let term = along(env, alpha, &rate)?;
            let sign = if alpha.len() % 2 == 1 { -1.0 } else { 1.0 };
            acc = Tensor::from_fn(d, body_rank, |i| {
                acc.get(i).clone() + term.get(i).clone() * sign
            });
        }
        per_component.push(acc);
    }
    // Body slots first, the field's last (fastest).
    let mut values = Vec::with_capacity(per_component.len() * per_component[0].components().len());
    for b in 0..per_component[0].components().len() {
        values.extend(per_component.iter().map(|t| t.components()[b].clone()));
    }
    let mut it = values.into_iter();
    Ok(Tensor::from_fn(d, body_rank + rank, |_| {
        it.next()
            .expect("one value per component of the density and of the field")
    }))
}

/// A value computed wherever the environment's position is.
type AtPosition<'f, T> = dyn Fn(&RealEnv<'_, T>) -> Result<Tensor<T>, RealError> + 'f;

/// The total derivative D_α of `f` (a function of where the position is), by nested
/// central differences, one coordinate of α per level.
fn along<T: DualNum<Primitive = f64>>(
    env: &RealEnv<'_, T>,
    alpha: &[usize],
    f: &AtPosition<'_, T>,
) -> Result<Tensor<T>, RealError> {
    let Some((&k, rest)) = alpha.split_first() else {
        return f(env);
    };
    env.difference_along(k, VARIATION_STEP, &mut |env| along(env, rest, f))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn multi_indices_are_the_sorted_multisets() {
        assert_eq!(multi_indices(&[0, 1, 2], 0), vec![Vec::<usize>::new()]);
        let two = multi_indices(&[0, 2], 2);
        assert_eq!(
            two,
            vec![vec![], vec![0], vec![2], vec![0, 0], vec![0, 2], vec![2, 2]]
        );
        // 1 + 3 + 6 in three coordinates up to order 2.
        assert_eq!(multi_indices(&[0, 1, 2], 2).len(), 10);
    }

    #[test]
    fn a_perturbation_has_one_unit_derivative_at_its_centre() {
        let p = Perturbation {
            field: "v".into(),
            idx: vec![0],
            exponents: vec![2, 1],
            centre: vec![0.5, -1.0],
            amount: 3.0,
        };
        // 3 (x−0.5)² (y+1) / 2 at (1.5, 1): 3 · 1 · 2 / 2.
        assert!((p.at(&[1.5, 1.0]) - 3.0).abs() < 1e-15);
        assert_eq!(p.at(&[0.5, 7.0]), 0.0);
    }
}
