//! Exact partial derivatives at a state: `grad(F, sigma_ij)`, and a `grad` inside a
//! `grad` (second derivatives: Hessians, fourth-order tangents), by forward-mode
//! differentiation over exact quotients.
//!
//! Substituting the state first and differentiating afterwards is wrong (∂/∂σ_22 of
//! a function after σ_22 = σ_11 was put in is not ∂F/∂σ_22), so the derivative is
//! carried along with the value: every value is a [`Jet`], the value at the state
//! (the assumptions applied, as everywhere in the exact route) and its partial
//! derivatives by each component of the symbol, every component an independent
//! variable and every other symbol held fixed. A `grad` inside a `grad` adds a level:
//! a jet's value and partials are then jets of the level below (nested dual numbers,
//! each level tagged with its own symbol, so that two levels by the same symbol give
//! its Hessian and never mix). The chain rule acts node by node: products, quotients,
//! powers, contractions, averages over the normal, derivatives along fields,
//! matrices; `sqrt` where the state makes its radicand the square of a rational
//! function (the exact route's `ExactRing` certifies the root's sign). The walk is the
//! one every route uses (`walk.rs`); this is only a ring.
//!
//! The sampled route takes the same derivatives with num-dual numbers
//! (`RealEnv::gradients`), a different method, so the two cross-check each other.

use super::env::{conditions_of, ExactRing, Failure};
pub use super::jet::Jet;
use crate::algebra::einsum::Arithmetic;
use crate::algebra::{Quotient, Tensor};
use crate::eval::walk::{self, Calculus, Derivative, DynCalculus, Normals, Ring};
use crate::kernel::{Poly, Rational};
use crate::lang::parser::{Func, Func2};
use crate::lang::Node;
use num_traits::One;

/// How many `grad`s may nest: second derivatives.
pub const MAX_ORDER: usize = 2;

/// `grad(body, symbol)` at the state: a tensor with `body`'s slots followed by the
/// symbol's (see [`crate::lang::NodeKind::Wrt`]).
pub(crate) fn gradients(
    ring: &mut ExactRing<'_, '_>,
    body: &Node,
    symbol: &str,
) -> Result<Tensor<Quotient>, Failure> {
    let mut jets = Jets {
        base: ExactRing {
            env: &mut *ring.env,
            origin: ring.origin,
        },
        seeds: Vec::new(),
    };
    let t = jets.gradients(body, symbol, body, &())?;
    Ok(t.into_map(|j| match j {
        Jet::Const(q) => q,
        // Every level was read off: none is left.
        Jet::Var { .. } => unreachable!("a gradient at the state has no partials left"),
    }))
}

/// The exact ring carrying derivatives by the components of the symbols of `seeds`
/// (level k by `seeds[k]`: its name and number of components).
struct Jets<'e, 'a> {
    base: ExactRing<'e, 'a>,
    seeds: Vec<(String, usize)>,
}

impl Jets<'_, '_> {
    fn refuse(&self, node: &Node, what: &str) -> Failure {
        self.base.error(
            node,
            format!("{what} inside grad(…) is not supported"),
            "take at most two derivatives with respect to symbols, nested as grad(grad(F, a_ij), b_kl)",
        )
    }

    /// Partials of one level combined by `f` (absent partials are 0, and so is the
    /// result where `f` gives `None`).
    fn zip(
        &mut self,
        a: &[Jet],
        b: &[Jet],
        mut f: impl FnMut(&mut Self, Option<&Jet>, Option<&Jet>) -> Result<Option<Jet>, Failure>,
    ) -> Result<Vec<Jet>, Failure> {
        fn nonzero(x: Option<&Jet>) -> Option<&Jet> {
            x.filter(|j| !j.is_zero())
        }
        (0..a.len().max(b.len()))
            .map(|k| Ok(f(self, nonzero(a.get(k)), nonzero(b.get(k)))?.unwrap_or_default()))
            .collect()
    }

    fn var(level: usize, value: Jet, partials: Vec<Jet>) -> Jet {
        if partials.iter().all(Jet::is_zero) {
            return value;
        }
        Jet::Var {
            level,
            value: Box::new(value),
            partials,
        }
    }

    fn constant_int(&mut self, k: i64) -> Jet {
        Jet::Const(Quotient::from(Poly::constant(Rational::int(k))))
    }

    /// 1/den, by (1/d)' = −d'/d² at each level; the state's division is the exact
    /// route's (which checks the divisor and records where it vanishes).
    fn inverse(&mut self, den: Jet, divisor: &Node) -> Result<Jet, Failure> {
        match den {
            Jet::Const(q) => Ok(Jet::Const(self.base.divide(
                Quotient::from(Poly::one()),
                &q,
                divisor,
            )?)),
            Jet::Var {
                level,
                value,
                partials,
            } => {
                let inv = self.inverse(*value, divisor)?;
                let square = self.mul(inv.clone(), &inv)?;
                let partials = partials
                    .into_iter()
                    .map(|p| {
                        let product = self.mul(square.clone(), &p)?;
                        Ok(self.neg(product))
                    })
                    .collect::<Result<_, Failure>>()?;
                Ok(Self::var(level, inv, partials))
            }
        }
    }

    /// √x, by (√x)' = x'/(2√x) at each level.
    fn root(&mut self, x: Jet, node: &Node) -> Result<Jet, Failure> {
        match x {
            Jet::Const(q) => Ok(Jet::Const(self.base.apply(Func::Sqrt, q, node)?)),
            Jet::Var {
                level,
                value,
                partials,
            } => {
                let r = self.root(*value, node)?;
                let two = self.constant_int(2);
                let twice = self.mul(two, &r)?;
                let half_inverse = self.inverse(twice, node)?;
                let partials = partials
                    .into_iter()
                    .map(|p| self.mul(p, &half_inverse))
                    .collect::<Result<_, _>>()?;
                Ok(Self::var(level, r, partials))
            }
        }
    }

    /// `t` with every quotient defined where all of them are.
    fn defined_together(t: Tensor<Jet>) -> Tensor<Jet> {
        let mut all = Vec::new();
        t.components().iter().for_each(|j| j.quotients(&mut all));
        let all = conditions_of(all);
        if all.is_empty() {
            return t;
        }
        t.into_map(|j| j.map(|q| q.clone().with_conditions(&all)))
    }
}

impl Arithmetic for Jets<'_, '_> {
    type Value = Jet;
    type Error = Failure;
    fn zero(&mut self) -> Jet {
        Jet::default()
    }

    fn one(&mut self) -> Jet {
        Jet::Const(Quotient::from(Poly::one()))
    }

    fn is_exact_zero(&self, x: &Jet) -> bool {
        x.is_zero()
    }

    /// (ab)' = a'b + ab', at the higher of the two levels (the other operand is a
    /// constant there).
    fn mul(&mut self, a: Jet, b: &Jet) -> Result<Jet, Failure> {
        let Some(level) = a.level().max(b.level()) else {
            let (Jet::Const(x), Jet::Const(y)) = (a, b) else {
                unreachable!("no level: both constant")
            };
            return Ok(Jet::Const(self.base.mul(x, y)?));
        };
        let (av, ap) = a.split(level);
        let (bv, bp) = b.clone().split(level);
        let partials = self.zip(&ap, &bp, |r, da, db| {
            let left = da.map(|d| r.mul(d.clone(), &bv)).transpose()?;
            let right = db.map(|d| r.mul(av.clone(), d)).transpose()?;
            Ok(match (left, right) {
                (Some(x), Some(y)) => Some(r.add(x, y)?),
                (x, y) => x.or(y),
            })
        })?;
        let value = self.mul(av, &bv)?;
        Ok(Self::var(level, value, partials))
    }

    fn add(&mut self, a: Jet, b: Jet) -> Result<Jet, Failure> {
        let Some(level) = a.level().max(b.level()) else {
            let (Jet::Const(x), Jet::Const(y)) = (a, b) else {
                unreachable!("no level: both constant")
            };
            return Ok(Jet::Const(self.base.add(x, y)?));
        };
        let (av, ap) = a.split(level);
        let (bv, bp) = b.split(level);
        let partials = self.zip(&ap, &bp, |r, da, db| {
            Ok(match (da, db) {
                (Some(x), Some(y)) => Some(r.add(x.clone(), y.clone())?),
                (x, y) => x.or(y).cloned(),
            })
        })?;
        let value = self.add(av, bv)?;
        Ok(Self::var(level, value, partials))
    }
}

impl Ring for Jets<'_, '_> {
    type Normal = ();

    fn dim(&self) -> usize {
        self.base.dim()
    }

    fn constant(&mut self, q: &Rational) -> Jet {
        Jet::Const(self.base.constant(q))
    }

    fn neg(&mut self, x: Jet) -> Jet {
        x.map(|q| -q.clone())
    }

    /// The components of each level's symbol seed one partial each at that level;
    /// every other symbol is fixed.
    fn symbol(&mut self, name: &str, node: &Node) -> Result<Tensor<Jet>, Failure> {
        let t = self.base.symbol(name, node)?;
        let seeds = self.seeds.clone();
        let mut k = 0;
        Ok(t.map(|q| {
            let mut jet = Jet::Const(q.clone());
            for (level, (symbol, size)) in seeds.iter().enumerate() {
                if symbol == name {
                    let mut partials = vec![Jet::default(); *size];
                    partials[k] = Jet::Const(Quotient::from(Poly::one()));
                    jet = Jet::Var {
                        level,
                        value: Box::new(jet),
                        partials,
                    };
                }
            }
            k += 1;
            jet
        }))
    }

    fn definition(&mut self, name: &str, node: &Node, _n: &()) -> Result<Tensor<Jet>, Failure> {
        let levels: Vec<&str> = self.seeds.iter().map(|(s, _)| s.as_str()).collect();
        let key = (levels.join("/"), name.to_owned());
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
            seeds: self.seeds.clone(),
        };
        let t = walk::in_formal_order(&mut inner, &def.body, &def.sig.formal, &())?;
        // Defined where the whole definition is, as in the exact route.
        let t = Self::defined_together(t);
        self.base.env.jet_cache.insert(key, t.clone());
        Ok(t)
    }

    /// x/d = x · (1/d).
    fn divide(&mut self, x: Jet, den: &Jet, divisor: &Node) -> Result<Jet, Failure> {
        if let (Jet::Const(x), Jet::Const(d)) = (&x, den) {
            return Ok(Jet::Const(self.base.divide(x.clone(), d, divisor)?));
        }
        let inverse = self.inverse(den.clone(), divisor)?;
        self.mul(x, &inverse)
    }

    /// (x^k)' = k x^(k−1) x', at each level.
    fn power(&mut self, x: Jet, k: u32, node: &Node) -> Result<Jet, Failure> {
        match x {
            Jet::Const(q) => Ok(Jet::Const(self.base.power(q, k, node)?)),
            _ if k == 0 => Ok(self.one()),
            Jet::Var {
                level,
                value,
                partials,
            } => {
                let lower = self.power((*value).clone(), k - 1, node)?;
                let count = self.constant_int(i64::from(k));
                let factor = self.mul(count, &lower)?;
                let partials = partials
                    .into_iter()
                    .map(|p| self.mul(p, &factor))
                    .collect::<Result<_, _>>()?;
                let value = self.mul(lower, &value)?;
                Ok(Self::var(level, value, partials))
            }
        }
    }

    /// A radicand that is 0 at the state is refused even when its first partials
    /// vanish there: √((σ_12 − σ_21)²) = |σ_12 − σ_21| has no derivative at σ_12 =
    /// σ_21, and a jet cannot tell that from √(σ_12⁴) (nor a zero skipped as exact
    /// from one that is not), so no value is better than a wrong one.
    fn apply(&mut self, f: Func, x: Jet, node: &Node) -> Result<Jet, Failure> {
        if f != Func::Sqrt {
            // Only a constant argument may give a constant: no rule here carries the
            // derivatives of another function.
            let value = self.base.apply(f, x.state().clone(), node)?;
            return match x {
                Jet::Const(_) => Ok(Jet::Const(value)),
                Jet::Var { .. } => Err(self.refuse(node, &format!("{}(…)", f.name()))),
            };
        }
        let root = self.root(x, node)?;
        if root.state().is_zero() {
            return Err(self.base.error(
                node,
                "sqrt(…) is not differentiable here: its radicand is 0 at the state",
                "differentiate where the radicand is positive",
            ));
        }
        Ok(root)
    }

    /// Of constants only, as [`Jets::apply`] for functions other than `sqrt`.
    fn apply2(&mut self, f: Func2, x: Jet, y: Jet, node: &Node) -> Result<Jet, Failure> {
        let value = self
            .base
            .apply2(f, x.state().clone(), y.state().clone(), node)?;
        match (x, y) {
            (Jet::Const(_), Jet::Const(_)) => Ok(Jet::Const(value)),
            _ => Err(self.refuse(node, &format!("{}(…, …)", f.name()))),
        }
    }

    fn pi(&mut self, node: &Node) -> Result<Jet, Failure> {
        self.base.pi(node).map(Jet::Const)
    }

    fn leave(&mut self, node: &Node, value: Tensor<Jet>) -> Result<Tensor<Jet>, Failure> {
        let mut all = Vec::new();
        value
            .components()
            .iter()
            .for_each(|j| j.quotients(&mut all));
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
        det.state().is_zero()
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

impl Normals for Jets<'_, '_> {
    fn normal(&mut self, n: &()) -> Tensor<Jet> {
        self.base.normal(n).map(|q| Jet::Const(q.clone()))
    }

    /// Averaging is linear: the value and every partial are averaged.
    fn average(&mut self, a: &Node, node: &Node, _n: &()) -> Result<Tensor<Jet>, Failure> {
        let v = walk::walk(self, a, &())?;
        let base = &self.base;
        v.try_map(|jet| jet.try_map(&mut |q| base.averaged(q, node)))
    }

    fn maximum(&mut self, a: &Node, node: &Node) -> Result<Jet, Failure> {
        self.base.maximum(a, node).map(Jet::Const)
    }
}

impl Calculus for Jets<'_, '_> {
    /// D_k commutes with ∂/∂σ (the symbol does not vary with position): the value
    /// and every partial get the total derivative.
    fn derivatives(&mut self, a: &Node, _node: &Node, _n: &()) -> Result<Tensor<Jet>, Failure> {
        let v = walk::walk(self, a, &())?;
        let d = self.dim();
        let mut values = Vec::with_capacity(v.components().len() * d);
        for jet in v.components() {
            for k in 0..d {
                values.push(jet.try_map(&mut |q| {
                    Ok(q.with_numerator(self.base.total_derivative(q.numerator(), k)?))
                })?);
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

    /// ∂body/∂symbol one level up: `body` is evaluated with the symbol's components
    /// seeding a new level, which is then read off (its partials, one per component,
    /// each a jet of the levels below). Derivatives by symbols commute (the values are
    /// rational functions and roots, smooth where defined), so a `grad` inside a
    /// `grad` is the mixed second derivative.
    fn gradients(
        &mut self,
        body: &Node,
        symbol: &str,
        node: &Node,
        _n: &(),
    ) -> Result<Tensor<Jet>, Failure> {
        if self.seeds.len() >= MAX_ORDER {
            return Err(self.refuse(node, "a third derivative"));
        }
        let rank = self.base.rank_of(symbol);
        let size = self.dim().pow(rank as u32);
        let level = self.seeds.len();
        let mut inner = Jets {
            base: ExactRing {
                env: &mut *self.base.env,
                origin: self.base.origin,
            },
            seeds: self
                .seeds
                .iter()
                .cloned()
                .chain([(symbol.to_owned(), size)])
                .collect(),
        };
        let t = walk::walk(&mut inner, body, &())?;
        let mut values = Vec::with_capacity(t.components().len() * size);
        for jet in t.components() {
            // A derivative is defined where the value is (as the kernel reads it).
            let mut all = Vec::new();
            jet.quotients(&mut all);
            let conditions = conditions_of(all);
            let (_, partials) = jet.clone().split(level);
            for k in 0..size {
                let partial = partials.get(k).cloned().unwrap_or_default();
                values.push(partial.map(|q| q.clone().with_conditions(&conditions)));
            }
        }
        let mut it = values.into_iter();
        Ok(Tensor::from_fn(self.dim(), t.rank() + rank, |_| {
            it.next().expect("one partial per component and seed")
        }))
    }
}
