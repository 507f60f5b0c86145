//! The real environment as the walk's ring: numbers, contractions, averages by
//! quadrature, derivatives along fields and the variations.

use super::elementary::{elementary, elementary2};
use super::env::{RealEnv, MAX_NESTED_DIFFERENCES, MEMO_LIMIT};
use super::error::{err, undefined, RealError};
use super::variation;
use crate::algebra::einsum::Arithmetic;
use crate::algebra::Tensor;
use crate::eval::quadrature::Quadrature;
use crate::eval::walk::{self, Calculus, DynCalculus, Normals, Ring};
use crate::kernel::Rational;
use crate::lang::parser::{Func, Func2};
use crate::lang::Node;
use nalgebra::{Dyn, U1};
use num_dual::{Derivative, DualNum, HyperDualDVec64};
use rustc_hash::FxHashMap as HashMap;

/// Numbers: plain arithmetic in `T`.
impl<T: DualNum<Primitive = f64>> Arithmetic for &RealEnv<'_, T> {
    type Value = T;
    type Error = RealError;
    fn zero(&mut self) -> T {
        T::zero()
    }

    fn one(&mut self) -> T {
        T::one()
    }

    fn mul(&mut self, a: T, b: &T) -> Result<T, RealError> {
        Ok(a * b.clone())
    }

    fn add(&mut self, a: T, b: T) -> Result<T, RealError> {
        Ok(a + b)
    }
}

/// The interpreter as the walk's ring: values in `f64` or num-dual numbers, `avg` by a
/// rule exact for the argument's degree in n (adaptive quadrature when it is not a
/// polynomial in n), `maxn` by a grid and golden sections.
impl<T: DualNum<Primitive = f64>> Ring for &RealEnv<'_, T> {
    type Normal = [f64];

    fn dim(&self) -> usize {
        self.decls.dim
    }

    fn constant(&mut self, q: &Rational) -> T {
        T::from(q.to_f64())
    }

    fn neg(&mut self, x: T) -> T {
        -x
    }

    fn symbol(&mut self, name: &str, node: &Node) -> Result<Tensor<T>, RealError> {
        if let Some((formal, body, n)) = self.defined_fields.get(name) {
            // A field given by an expression of the position: its value where the
            // position now is.
            return walk::in_formal_order(&mut &**self, body, formal, n);
        }
        if let Some(fields) = &self.fields {
            let x = self.position.borrow();
            let d = self.decls.dim;
            if self.decls.position.as_deref() == Some(name) {
                return Ok(Tensor::from_fn(d, 1, |i| T::from(x[i[0]])));
            }
            if fields.has(name) {
                let rank = self.decls.symbols.get(name).copied().unwrap_or(0);
                let mut missing = false;
                let t = Tensor::from_fn(d, rank, |idx| {
                    T::from(fields.value(name, idx, &x).unwrap_or_else(|| {
                        missing = true;
                        f64::NAN
                    }))
                });
                if missing {
                    return Err(err(
                        node,
                        format!("no Taylor polynomial for a component of {name}"),
                    ));
                }
                return Ok(self.perturbed(name, t, &x));
            }
        }
        let t = self
            .symbols
            .get(name)
            .cloned()
            .ok_or_else(|| err(node, format!("no value for symbol {name}")))?;
        match &self.fields {
            // A field the point gives no jets: constant, plus any perturbation.
            Some(_) => Ok(self.perturbed(name, t, &self.position.borrow())),
            None => Ok(t),
        }
    }

    fn definition(&mut self, name: &str, node: &Node, n: &[f64]) -> Result<Tensor<T>, RealError> {
        let env: &RealEnv<'_, T> = self;
        let def = env
            .def(name)
            .ok_or_else(|| err(node, format!("definition {name} not in scope")))?;
        // Definitions that do not involve the normal are the same for every n.
        let mut key_n: Vec<u64> = if env.normal_degree(&def.body) == Some(0) {
            Vec::new()
        } else {
            n.iter().map(|x| x.to_bits()).collect()
        };
        // With fields, a definition's value also depends on where it is evaluated.
        if env.fields.is_some() {
            key_n.extend(env.position.borrow().iter().map(|x| x.to_bits()));
            key_n.push(env.epoch.get());
        }
        let key = (name.to_owned(), key_n);
        let cached = env.memo.borrow().get(&key).cloned();
        if let Some(t) = cached {
            return Ok(t);
        }
        let t = walk::in_formal_order(&mut { env }, &def.body, &def.sig.formal, n)?;
        let mut memo = env.memo.borrow_mut();
        if memo.len() > MEMO_LIMIT {
            memo.clear();
        }
        memo.insert(key, t.clone());
        Ok(t)
    }

    fn divide(&mut self, x: T, den: &T, divisor: &Node) -> Result<T, RealError> {
        if den.re() == 0.0 {
            return Err(undefined(divisor.span, "division by zero"));
        }
        Ok(x / den.clone())
    }

    fn power(&mut self, x: T, k: u32, _node: &Node) -> Result<T, RealError> {
        Ok(x.powi(k as i32))
    }

    fn apply(&mut self, f: Func, x: T, node: &Node) -> Result<T, RealError> {
        elementary(f, x).map_err(|e| undefined(node.span, e.to_string()))
    }

    fn apply2(&mut self, f: Func2, x: T, y: T, node: &Node) -> Result<T, RealError> {
        elementary2(f, x, y).map_err(|e| undefined(node.span, e.to_string()))
    }

    fn pi(&mut self, _node: &Node) -> Result<T, RealError> {
        Ok(T::from(std::f64::consts::PI))
    }

    fn not_scalar(&mut self, node: &Node) -> RealError {
        err(node, "expected a scalar")
    }

    fn vanishes(&self, det: &T) -> bool {
        det.re() == 0.0
    }

    fn singular(&mut self, node: &Node) -> RealError {
        undefined(node.span, "singular matrix: its determinant is 0 here")
    }

    fn calculus(
        &mut self,
        _what: walk::Derivative,
        _node: &Node,
    ) -> Result<&mut DynCalculus<'_, Self>, RealError> {
        Ok(self)
    }
}

impl<T: DualNum<Primitive = f64>> Normals for &RealEnv<'_, T> {
    fn normal(&mut self, n: &[f64]) -> Tensor<T> {
        Tensor::from_fn(self.decls.dim, 1, |i| T::from(n[i[0]]))
    }

    fn average(&mut self, a: &Node, node: &Node, _n: &[f64]) -> Result<Tensor<T>, RealError> {
        let env: &RealEnv<'_, T> = self;
        let d = env.decls.dim;
        let Some(degree) = env.normal_degree(a) else {
            // Not a polynomial in n: adaptive quadrature with an error estimate.
            let free = if env.decls.normal_in_plane { 2 } else { d };
            let value = env.quadrature.average(free, d, &mut |point| {
                Ok(walk::walk(&mut { env }, a, point)?.into_components())
            })?;
            let mut it = value.into_iter();
            let rank = a.free_letters().len();
            return Ok(Tensor::from_fn(d, rank, |_| it.next().expect("one each")));
        };
        let mut acc: Option<Tensor<T>> = None;
        for (point, w) in env.rule(degree).iter() {
            let t = walk::walk(&mut { env }, a, point)?;
            let t = t.map(|x| x.clone() * *w);
            acc = Some(match acc {
                None => t,
                Some(s) => s.add(&t),
            });
        }
        acc.ok_or_else(|| err(node, "empty quadrature rule"))
    }

    fn maximum(&mut self, a: &Node, node: &Node) -> Result<T, RealError> {
        self.max_over_angle(node, a)
    }
}

impl<T: DualNum<Primitive = f64>> Calculus for &RealEnv<'_, T> {
    /// Central differences of `a`'s values at positions moved along each coordinate
    /// (see [`crate::eval::taylor`]): only where the fields are explicit functions.
    fn derivatives(&mut self, a: &Node, node: &Node, n: &[f64]) -> Result<Tensor<T>, RealError> {
        let env: &RealEnv<'_, T> = self;
        if env.fields.is_none() {
            return Err(err(
                node,
                "a derivative of a field is decided exactly: sampling has no fields to differentiate",
            ));
        }
        let depth = env.differences.get();
        if depth >= MAX_NESTED_DIFFERENCES {
            return Err(err(
                node,
                format!(
                    "more than {MAX_NESTED_DIFFERENCES} nested derivatives: central differences would \
                     take (4d)^k evaluations and lose every digit"
                ),
            ));
        }
        let d = env.decls.dim;
        let mut per_coordinate = Vec::with_capacity(d);
        env.differences.set(depth + 1);
        for k in 0..d {
            let along = env.difference_along(k, crate::tolerance::TAYLOR_STEP, &mut |env| {
                walk::walk(&mut { env }, a, n)
            });
            match along {
                Ok(t) => per_coordinate.push(t),
                Err(e) => {
                    env.differences.set(depth);
                    return Err(e);
                }
            }
        }
        env.differences.set(depth);
        let rank = a.free_letters().len();
        Ok(Tensor::from_fn(d, rank + 1, |idx| {
            per_coordinate[idx[rank]].get(&idx[..rank]).clone()
        }))
    }

    fn variations(
        &mut self,
        body: &Node,
        field: &str,
        node: &Node,
        n: &[f64],
    ) -> Result<Tensor<T>, RealError> {
        variation::variations(self, body, field, node, n)
    }

    /// ∂body/∂symbol by forward-mode dual numbers (num-dual), every component of the
    /// symbol seeded in one pass and every other value held at the sample: the
    /// derivative at the state (see [`crate::lang::NodeKind::Wrt`]). The values enter
    /// as real parts of hyper-dual numbers whose first part carries this derivative;
    /// a `grad(…)` inside the body seeds the second part ([`nested_gradients`]), which
    /// gives second derivatives. The reader refuses a gradient inside a function that
    /// a `gradient` or `convex` claim differentiates again.
    fn gradients(
        &mut self,
        body: &Node,
        symbol: &str,
        node: &Node,
        n: &[f64],
    ) -> Result<Tensor<T>, RealError> {
        if self.fields.is_some() || !self.defined_fields.is_empty() {
            return Err(err(
                node,
                "grad(…) is not sampled where fields vary with position",
            ));
        }
        if self.in_gradient {
            return match self.nested {
                Some(nested) => nested(self, body, symbol, node, n),
                None => Err(err(
                    node,
                    "a third derivative inside grad(…) is not supported",
                )),
            };
        }
        let Some(wrt) = self.symbols.get(symbol) else {
            return Err(err(node, format!("`{symbol}` has no value here")));
        };
        let size = wrt.components().len();
        let lift = |x: &T| HyperDualDVec64::from_re(x.re());
        let mut symbols: HashMap<String, Tensor<HyperDualDVec64>> = self
            .symbols
            .iter()
            .map(|(k, t)| (k.clone(), t.map(lift)))
            .collect();
        let mut k = 0;
        let seeded = wrt.map(|x| {
            let v = lift(x).derivative1(size, k);
            k += 1;
            v
        });
        symbols.insert(symbol.to_owned(), seeded);
        let mut inner = RealEnv::new(self.decls, self.defs, symbols);
        inner.quadrature = Quadrature::new(self.quadrature.level);
        inner.in_gradient = true;
        inner.nested = Some(nested_gradients);
        let value = inner.eval(body, n)?.tensor;
        self.quadrature.absorb(&inner.quadrature);
        let mut values = Vec::with_capacity(value.components().len() * size);
        for c in value.components() {
            let g = c.eps1.clone().unwrap_generic(Dyn(size), U1);
            // A derivative that is not finite does not exist here (√ at 0, a kink): an
            // error at this sample, never a value that a comparison could call false.
            if c.re.is_finite() && g.iter().any(|x| !x.is_finite()) {
                return Err(undefined(
                    node.span,
                    format!("grad(…) does not exist at this sample: a derivative by `{symbol}` is not finite (exclude the set with `singular`)"),
                ));
            }
            values.extend(g.iter().map(|&x| T::from(x)));
        }
        let mut it = values.into_iter();
        Ok(Tensor::from_fn(
            self.decls.dim,
            value.rank() + wrt.rank(),
            |_| it.next().expect("one derivative per component and seed"),
        ))
    }
}

/// A `grad(…)` inside the body of another, whose values carry the outer derivative
/// in their first dual part: the inner symbol's components seed the second part, and
/// the result's value is the inner derivative (the second part) with, as its first
/// part, the mixed second derivative (the cross part). A third level is refused.
fn nested_gradients<'a>(
    env: &RealEnv<'a, HyperDualDVec64>,
    body: &Node,
    symbol: &str,
    node: &Node,
    n: &[f64],
) -> Result<Tensor<HyperDualDVec64>, RealError> {
    let Some(wrt) = env.symbols.get(symbol) else {
        return Err(err(node, format!("`{symbol}` has no value here")));
    };
    let size = wrt.components().len();
    let mut k = 0;
    let seeded = wrt.map(|x| {
        let v = x.clone().derivative2(size, k);
        k += 1;
        v
    });
    let mut symbols = env.symbols.clone();
    symbols.insert(symbol.to_owned(), seeded);
    let mut inner = RealEnv::new(env.decls, env.defs, symbols);
    inner.quadrature = Quadrature::new(env.quadrature.level);
    inner.in_gradient = true;
    let value = inner.eval(body, n)?.tensor;
    env.quadrature.absorb(&inner.quadrature);
    let mut values = Vec::with_capacity(value.components().len() * size);
    for c in value.components() {
        let first = c.eps2.clone().unwrap_generic(U1, Dyn(size));
        for j in 0..size {
            let cross = c.eps1eps2.0.as_ref().map(|m| m.column(j).into_owned());
            values.push(HyperDualDVec64::new(
                first[j],
                Derivative::new(cross),
                Derivative::none(),
                Derivative::none(),
            ));
        }
    }
    let mut it = values.into_iter();
    Ok(Tensor::from_fn(
        env.decls.dim,
        value.rank() + wrt.rank(),
        |_| it.next().expect("one derivative per component and seed"),
    ))
}
