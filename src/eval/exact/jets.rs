//! Exact partial derivatives at a state: `grad(F, sigma_ij)` by forward-mode
//! differentiation over exact quotients.
//!
//! Substituting the state first and differentiating afterwards is wrong (∂/∂σ_22 of
//! a function after σ_22 = σ_11 was put in is not ∂F/∂σ_22), so the derivative is
//! carried along with the value: every value is a [`Jet`], the value at the state
//! (the assumptions applied, as everywhere in the exact route) and its partial
//! derivatives by each component of the symbol, every component an independent
//! variable and every other symbol held fixed. The chain rule acts node by node:
//! products, quotients, powers, contractions, averages over the normal, derivatives
//! along fields, matrices; `sqrt` where the state makes its radicand the square of a
//! rational function (the exact route's `ExactRing` certifies the root's sign).
//! The walk is the one every route uses (`walk.rs`); this is only a ring.
//!
//! The sampled route takes the same derivatives with num-dual numbers
//! (`RealEnv::gradients`), a different method, so the two cross-check each other.

use super::env::{conditions_of, ExactRing, Failure, Jet};
use crate::algebra::einsum::Arithmetic;
use crate::algebra::{Quotient, Tensor};
use crate::eval::walk::{self, Calculus, Derivative, DynCalculus, Normals, Ring};
use crate::kernel::{Poly, Rational};
use crate::lang::parser::{Func, Func2};
use crate::lang::Node;
use num_traits::One;

/// `grad(body, symbol)` at the state: a tensor with `body`'s slots followed by the
/// symbol's (see [`crate::lang::NodeKind::Wrt`]).
pub(crate) fn gradients(
    ring: &mut ExactRing<'_, '_>,
    body: &Node,
    symbol: &str,
) -> Result<Tensor<Quotient>, Failure> {
    let dim = ring.env_dim();
    let rank = ring.rank_of(symbol);
    let size = dim.pow(rank as u32);
    let mut jets = Jets {
        base: ExactRing {
            env: &mut *ring.env,
            origin: ring.origin,
        },
        symbol,
        size,
    };
    let t = walk::walk(&mut jets, body, &())?;
    let mut values = Vec::with_capacity(t.components().len() * size);
    for jet in t.components() {
        // A derivative is defined where the value is (as the kernel reads it).
        for k in 0..size {
            let partial = jet.partials.get(k).cloned().unwrap_or_default();
            values.push(partial.with_conditions(jet.value.conditions()));
        }
    }
    let mut it = values.into_iter();
    Ok(Tensor::from_fn(dim, t.rank() + rank, |_| {
        it.next().expect("one partial per component and seed")
    }))
}

/// The exact ring carrying derivatives by the components of one symbol.
struct Jets<'s, 'e, 'a> {
    base: ExactRing<'e, 'a>,
    symbol: &'s str,
    /// The number of the symbol's components.
    size: usize,
}

impl Jets<'_, '_, '_> {
    /// Σ over the partials of `f(k)`, k in 0..size, where either operand has one.
    fn partials(
        &mut self,
        a: &[Quotient],
        b: &[Quotient],
        mut f: impl FnMut(
            &mut ExactRing,
            Option<&Quotient>,
            Option<&Quotient>,
        ) -> Result<Quotient, Failure>,
    ) -> Result<Vec<Quotient>, Failure> {
        if a.is_empty() && b.is_empty() {
            return Ok(Vec::new());
        }
        fn nonzero(x: Option<&Quotient>) -> Option<&Quotient> {
            x.filter(|q| !q.is_exact_zero())
        }
        (0..self.size)
            .map(|k| f(&mut self.base, nonzero(a.get(k)), nonzero(b.get(k))))
            .collect()
    }

    /// Each partial of `x` mapped by `f`.
    fn each(
        &mut self,
        x: &Jet,
        mut f: impl FnMut(&mut ExactRing, &Quotient) -> Result<Quotient, Failure>,
    ) -> Result<Vec<Quotient>, Failure> {
        x.partials.iter().map(|p| f(&mut self.base, p)).collect()
    }

    fn refuse(&self, node: &Node, what: &str) -> Failure {
        self.base.error(
            node,
            format!("{what} inside grad(…) is not supported"),
            "take one derivative with respect to a symbol at a time, in separate claims",
        )
    }
}

/// `a + b` with either absent meaning 0.
fn plus(
    ring: &mut ExactRing,
    a: Option<Quotient>,
    b: Option<Quotient>,
) -> Result<Quotient, Failure> {
    match (a, b) {
        (Some(a), Some(b)) => ring.add(a, b),
        (Some(x), None) | (None, Some(x)) => Ok(x),
        (None, None) => Ok(Quotient::default()),
    }
}

impl Arithmetic for Jets<'_, '_, '_> {
    type Value = Jet;
    type Error = Failure;
    fn zero(&mut self) -> Jet {
        Jet::default()
    }

    fn one(&mut self) -> Jet {
        Jet::constant(Quotient::from(Poly::one()))
    }

    fn is_exact_zero(&self, x: &Jet) -> bool {
        x.value.is_exact_zero() && x.is_constant()
    }

    /// (ab)' = a'b + ab'.
    fn mul(&mut self, a: Jet, b: &Jet) -> Result<Jet, Failure> {
        let partials = self.partials(&a.partials, &b.partials, |r, da, db| {
            let left = da.map(|d| r.mul(d.clone(), &b.value)).transpose()?;
            let right = db.map(|d| r.mul(a.value.clone(), d)).transpose()?;
            plus(r, left, right)
        })?;
        Ok(Jet {
            value: self.base.mul(a.value, &b.value)?,
            partials,
        })
    }

    fn add(&mut self, a: Jet, b: Jet) -> Result<Jet, Failure> {
        let partials = self.partials(&a.partials, &b.partials, |r, da, db| {
            plus(r, da.cloned(), db.cloned())
        })?;
        Ok(Jet {
            value: self.base.add(a.value, b.value)?,
            partials,
        })
    }
}

impl Ring for Jets<'_, '_, '_> {
    type Normal = ();

    fn dim(&self) -> usize {
        self.base.dim()
    }

    fn constant(&mut self, q: &Rational) -> Jet {
        Jet::constant(self.base.constant(q))
    }

    fn neg(&mut self, x: Jet) -> Jet {
        Jet {
            value: -x.value,
            partials: x.partials.into_iter().map(|p| -p).collect(),
        }
    }

    /// The symbol's components seed one partial each; every other symbol is fixed.
    fn symbol(&mut self, name: &str, node: &Node) -> Result<Tensor<Jet>, Failure> {
        let t = self.base.symbol(name, node)?;
        if name != self.symbol {
            return Ok(t.map(|q| Jet::constant(q.clone())));
        }
        let size = self.size;
        let mut k = 0;
        Ok(t.map(|q| {
            let mut partials = vec![Quotient::default(); size];
            partials[k] = Quotient::from(Poly::one());
            k += 1;
            Jet {
                value: q.clone(),
                partials,
            }
        }))
    }

    fn definition(&mut self, name: &str, node: &Node, _n: &()) -> Result<Tensor<Jet>, Failure> {
        let key = (self.symbol.to_owned(), name.to_owned());
        if let Some(t) = self.base.env.jet_cache.get(&key) {
            return Ok(t.clone());
        }
        let Some(def) = self.base.env.definition(name) else {
            return Err(self.base.error(
                node,
                format!("internal: definition `{name}` is not in scope"),
                "",
            ));
        };
        let mut inner = Jets {
            base: ExactRing {
                env: &mut *self.base.env,
                origin: &def.origin,
            },
            symbol: self.symbol,
            size: self.size,
        };
        let t = walk::in_formal_order(&mut inner, &def.body, &def.sig.formal, &())?;
        // Defined where the whole definition is, as in the exact route.
        let all = conditions_of(
            t.components()
                .iter()
                .flat_map(|j| std::iter::once(&j.value).chain(&j.partials)),
        );
        let t = if all.is_empty() {
            t
        } else {
            t.into_map(|j| Jet {
                value: j.value.with_conditions(&all),
                partials: j
                    .partials
                    .into_iter()
                    .map(|p| p.with_conditions(&all))
                    .collect(),
            })
        };
        self.base.env.jet_cache.insert(key, t.clone());
        Ok(t)
    }

    /// (x/d)' = (x' − (x/d) d')/d, with 1/d taken once (the exact route's division
    /// checks the divisor and records where it vanishes).
    fn divide(&mut self, x: Jet, den: &Jet, divisor: &Node) -> Result<Jet, Failure> {
        let inverse = self
            .base
            .divide(Quotient::from(Poly::one()), &den.value, divisor)?;
        let q = self.base.mul(x.value, &inverse)?;
        let partials = self.partials(&x.partials, &den.partials, |r, dx, dd| {
            let shifted = dd.map(|d| r.mul(q.clone(), d).map(|t| -t)).transpose()?;
            let top = plus(r, dx.cloned(), shifted)?;
            r.mul(top, &inverse)
        })?;
        Ok(Jet { value: q, partials })
    }

    /// (x^k)' = k x^(k−1) x'.
    fn power(&mut self, x: Jet, k: u32, node: &Node) -> Result<Jet, Failure> {
        if x.is_constant() || k == 0 {
            return Ok(Jet::constant(self.base.power(x.value, k, node)?));
        }
        let lower = self.base.power(x.value.clone(), k - 1, node)?;
        let factor = self.base.mul(
            lower.clone(),
            &Quotient::from(Poly::constant(Rational::int(i64::from(k)))),
        )?;
        let partials = self.each(&x, |r, p| r.mul(factor.clone(), p))?;
        Ok(Jet {
            value: self.base.mul(lower, &x.value)?,
            partials,
        })
    }

    /// (√x)' = x'/(2√x), where the exact route takes √x (a certified root). A radicand
    /// that is 0 at the state is refused even when its first partials vanish there:
    /// √((σ_12 − σ_21)²) = |σ_12 − σ_21| has no derivative at σ_12 = σ_21, and a jet
    /// cannot tell that from √(σ_12⁴) (nor a zero skipped as exact from one that is
    /// not), so no value is better than a wrong one.
    fn apply(&mut self, f: Func, x: Jet, node: &Node) -> Result<Jet, Failure> {
        let value = self.base.apply(f, x.value.clone(), node)?;
        if value.is_zero() {
            return Err(self.base.error(
                node,
                "sqrt(…) is not differentiable here: its radicand is 0 at the state",
                "differentiate where the radicand is positive",
            ));
        }
        if x.is_constant() {
            return Ok(Jet::constant(value));
        }
        let twice = self.base.add(value.clone(), value.clone())?;
        let half_inverse = self
            .base
            .divide(Quotient::from(Poly::one()), &twice, node)?;
        let partials = self.each(&x, |r, p| r.mul(p.clone(), &half_inverse))?;
        Ok(Jet { value, partials })
    }

    fn apply2(&mut self, f: Func2, x: Jet, y: Jet, node: &Node) -> Result<Jet, Failure> {
        self.base
            .apply2(f, x.value, y.value, node)
            .map(Jet::constant)
    }

    fn pi(&mut self, node: &Node) -> Result<Jet, Failure> {
        self.base.pi(node).map(Jet::constant)
    }

    fn leave(&mut self, node: &Node, value: Tensor<Jet>) -> Result<Tensor<Jet>, Failure> {
        let all = value
            .components()
            .iter()
            .flat_map(|j| std::iter::once(&j.value).chain(&j.partials));
        self.base.within_limits(node, all)?;
        Ok(value)
    }

    fn at(&mut self, e: Failure, node: &Node) -> Failure {
        self.base.at(e, node)
    }

    fn not_scalar(&mut self, node: &Node) -> Failure {
        self.base.not_scalar(node)
    }

    /// A matrix is singular where its determinant's value is, whatever its partials.
    fn vanishes(&self, det: &Jet) -> bool {
        det.value.is_zero()
    }

    fn singular(&mut self, node: &Node) -> Failure {
        self.base.singular(node)
    }

    fn calculus(
        &mut self,
        _what: Derivative,
        _node: &Node,
    ) -> Result<&mut DynCalculus<'_, Self>, Failure> {
        Ok(self)
    }
}

impl Normals for Jets<'_, '_, '_> {
    fn normal(&mut self, n: &()) -> Tensor<Jet> {
        self.base.normal(n).map(|q| Jet::constant(q.clone()))
    }

    /// Averaging is linear: the value and every partial are averaged.
    fn average(&mut self, a: &Node, node: &Node, _n: &()) -> Result<Tensor<Jet>, Failure> {
        let v = walk::walk(self, a, &())?;
        v.try_map(|jet| {
            Ok(Jet {
                value: self.base.averaged(&jet.value, node)?,
                partials: self.each(jet, |r, p| r.averaged(p, node))?,
            })
        })
    }

    fn maximum(&mut self, a: &Node, node: &Node) -> Result<Jet, Failure> {
        self.base.maximum(a, node).map(Jet::constant)
    }
}

impl Calculus for Jets<'_, '_, '_> {
    /// D_k commutes with ∂/∂σ (the symbol does not vary with position): both the
    /// value and every partial get the total derivative.
    fn derivatives(&mut self, a: &Node, _node: &Node, _n: &()) -> Result<Tensor<Jet>, Failure> {
        let v = walk::walk(self, a, &())?;
        let d = self.dim();
        let mut values = Vec::with_capacity(v.components().len() * d);
        for jet in v.components() {
            for k in 0..d {
                let value = self.base.total_derivative(jet.value.numerator(), k)?;
                let partials = self.each(jet, |r, p| {
                    Ok(p.with_numerator(r.total_derivative(p.numerator(), k)?))
                })?;
                values.push(Jet {
                    value: jet.value.with_numerator(value),
                    partials,
                });
            }
        }
        let mut it = values.into_iter();
        Ok(Tensor::from_fn(d, v.rank() + 1, |_| {
            it.next().expect("one value per component and coordinate")
        }))
    }

    fn variations(
        &mut self,
        _b: &Node,
        _f: &str,
        node: &Node,
        _n: &(),
    ) -> Result<Tensor<Jet>, Failure> {
        Err(self.refuse(node, "a variation"))
    }

    fn gradients(
        &mut self,
        _b: &Node,
        _s: &str,
        node: &Node,
        _n: &(),
    ) -> Result<Tensor<Jet>, Failure> {
        Err(self.refuse(node, "a gradient"))
    }
}
