//! The exact environment as the walk's ring: every node of a checked expression
//! evaluated to tensors of canonical quotients ([`super::env`] holds the environment).

use super::env::{
    conditions_of, poly_error, too_much, ExactRing, Failure, Varying, MAX_COEFFICIENT_BITS,
    MAX_EXPONENT, MAX_TERMS,
};
use crate::algebra::einsum::Arithmetic;
use crate::algebra::quotient::DivideError;
use crate::algebra::{assignments, Quotient, Tensor};
use crate::eval::walk::{self, Calculus, Derivative, DynCalculus, Normals, Ring};
use crate::kernel::{Poly, PolyError, Rational, Var};
use crate::lang::parser::{Func, Func2};
use crate::lang::{Node, NodeKind};
use num_traits::Zero;

impl Ring for ExactRing<'_, '_> {
    /// The normal is a polynomial variable: nothing to pass.
    type Normal = ();

    fn dim(&self) -> usize {
        self.env.decls.dim
    }

    fn constant(&mut self, q: &Rational) -> Quotient {
        Quotient::from(Poly::constant(q.clone()))
    }

    fn neg(&mut self, x: Quotient) -> Quotient {
        -x
    }

    fn symbol(&mut self, name: &str, _node: &Node) -> Result<Tensor<Quotient>, Failure> {
        Ok(self.env.symbol(name))
    }

    fn definition(
        &mut self,
        name: &str,
        node: &Node,
        _n: &(),
    ) -> Result<Tensor<Quotient>, Failure> {
        if let Some(t) = self.env.cache.get(name) {
            return Ok(t.clone());
        }
        let Some(def) = self.env.definition(name) else {
            return Err(Failure::Located(self.origin.diagnostic(
                node.span,
                format!("internal: definition `{name}` is not in scope"),
            )));
        };
        let mut inner = ExactRing {
            env: &mut *self.env,
            origin: &def.origin,
        };
        let t = walk::in_formal_order(&mut inner, &def.body, &def.sig.formal, &())?;
        // A definition is defined where every component is: reading one entry of a
        // matrix whose other entries divide by G is undefined at G = 0 (and the
        // interpreter that confirms a counterexample evaluates the whole definition).
        let all = conditions_of(t.components());
        let t = if all.is_empty() {
            t
        } else {
            t.into_map(|q| q.with_conditions(&all))
        };
        self.env.cache.insert(name.to_owned(), t.clone());
        Ok(t)
    }

    /// A single-term divisor (3, V, 2*R_g) divides the numerator as before; a sum must
    /// be a polynomial in scalar parameters and components of tensors that do not vary
    /// with position, and joins the denominator. A divisor
    /// written as a product of scalars or a power, `(1 + nu) (1 - 2 nu)`, is divided
    /// by one factor at a time, so that the factors stay apart in the denominator and
    /// in the conditions where the statement holds.
    fn divide(&mut self, x: Quotient, den: &Quotient, divisor: &Node) -> Result<Quotient, Failure> {
        if den.factors().is_empty() && den.numerator().num_terms() > 1 {
            let parts: Vec<(&Node, u32)> = match &divisor.kind {
                NodeKind::Product(fs) if fs.iter().all(|f| f.free_letters().is_empty()) => {
                    fs.iter().map(|f| (f, 1)).collect()
                }
                NodeKind::Pow(a, k) => vec![(&**a, *k)],
                _ => Vec::new(),
            };
            if !parts.is_empty() {
                let mut out = x;
                for (part, k) in parts {
                    // x / a^k = x · (1/a)^k: one division, then a power under its limits.
                    let value = walk::scalar(self, part, &())?;
                    let one = Arithmetic::one(self);
                    let inverse = self.divide(one, &value, part)?;
                    let inverse = self.power(inverse, k, divisor)?;
                    out = self.mul(out, &inverse)?;
                }
                return Ok(out);
            }
        }
        let env = &*self.env;
        let single_term = den.factors().is_empty() && den.numerator().num_terms() == 1;
        let offending = den
            .variables()
            .into_iter()
            .filter(|_| !single_term)
            .find(|v| env.normal.contains(v) || env.varying.contains_key(v));
        if let Some(v) = offending {
            let name = env.vars.name(v);
            let what = if env.normal.contains(&v) {
                format!("`{name}` is a component of the normal")
            } else {
                format!("`{name}` varies with position")
            };
            return Err(self.error(
                divisor,
                format!("exact mode divides by a sum only when it is free of the normal and of fields; {what}"),
                "decide this claim with strategy = \"numeric\", or multiply the statement out",
            ));
        }
        x.divide(den).map_err(|DivideError::ByZero| {
            Failure::Located(poly_error(self.origin, divisor, PolyError::DivisionByZero))
        })
    }

    fn power(&mut self, q: Quotient, k: u32, node: &Node) -> Result<Quotient, Failure> {
        let p = q.numerator();
        let max_exp = p
            .terms()
            .flat_map(|(m, _)| m.factors().iter().map(|&(_, e)| e.abs()))
            .max()
            .unwrap_or(0);
        // Terms of p^k: at most the number of multisets of k of p's t terms,
        // C(t + k − 1, k) (each term of the expansion is one such product), and at most
        // the number of monomials of degree ≤ k·(max exponent) in p's variables. The
        // first is exact for a sum of distinct monomials such as (a_i n_i)^16: 153 terms,
        // where the second says 74,613 (issue 18).
        let mut vars: Vec<_> = p
            .terms()
            .flat_map(|(m, _)| m.factors().iter().map(|&(v, _)| v))
            .collect();
        vars.sort_unstable();
        vars.dedup();
        let degree = max_exp as f64 * f64::from(k);
        let monomials = (1..=vars.len()).fold(1.0, |acc, j| acc * (degree + j as f64) / j as f64);
        let t = p.num_terms() as f64;
        let multisets = (1..=k).fold(1.0, |acc, j| acc * (t - 1.0 + f64::from(j)) / f64::from(j));
        let terms = multisets.min(monomials);
        // Coefficients grow too: (q)^k has about k times the bits of q.
        let max_bits = p.terms().map(|(_, c)| c.bits()).max().unwrap_or(0);
        let too_big = max_exp
            .checked_mul(i64::from(k))
            .is_none_or(|e| e > MAX_EXPONENT)
            || terms > MAX_TERMS as f64
            || max_bits.saturating_mul(u64::from(k)) > MAX_COEFFICIENT_BITS;
        if too_big {
            return Err(self.limit(
                node,
                "this power is too large to expand exactly",
                &format!(
                    "exponents up to {MAX_EXPONENT}, expansions up to {MAX_TERMS} terms and coefficients up to {MAX_COEFFICIENT_BITS} bits are supported"
                ),
            ));
        }
        // A denominator's factors are not expanded, but their multiplicities are
        // exponents too.
        let multiplicity = q.factors().iter().map(|&(_, m)| m).max().unwrap_or(0);
        if u64::from(multiplicity) * u64::from(k) > MAX_EXPONENT.unsigned_abs() {
            return Err(self.limit(
                node,
                "this power of a quotient is too large to expand exactly",
                &format!("exponents up to {MAX_EXPONENT} are supported"),
            ));
        }
        Ok(q.pow(k))
    }

    fn apply2(
        &mut self,
        f: Func2,
        _x: Quotient,
        _y: Quotient,
        node: &Node,
    ) -> Result<Quotient, Failure> {
        let what = match f {
            Func2::Pow => "a power with an exponent that is not a whole number".to_owned(),
            f => format!("{}(…, …)", f.name()),
        };
        Err(self.error(
            node,
            format!("{what} has no exact polynomial value"),
            "decide this claim with strategy = \"numeric\"",
        ))
    }

    fn pi(&mut self, node: &Node) -> Result<Quotient, Failure> {
        Err(self.error(
            node,
            "π is not a rational number, so it has no exact polynomial value",
            "decide this claim with strategy = \"numeric\"",
        ))
    }

    fn apply(&mut self, f: Func, p: Quotient, node: &Node) -> Result<Quotient, Failure> {
        match f {
            Func::Sqrt => self.square_root(&p, node),
            _ => Err(self.error(
                node,
                format!("{}(…) has no exact polynomial value", f.name()),
                "decide this claim with strategy = \"numeric\"",
            )),
        }
    }

    fn leave(&mut self, node: &Node, value: Tensor<Quotient>) -> Result<Tensor<Quotient>, Failure> {
        self.within_limits(node, value.components())?;
        Ok(value)
    }

    fn at(&mut self, e: Failure, node: &Node) -> Failure {
        match e {
            Failure::OverBudget => Failure::Limit(too_much(self.origin, node)),
            located => located,
        }
    }

    fn not_scalar(&mut self, node: &Node) -> Failure {
        Failure::Located(self.origin.diagnostic(node.span, "expected a scalar"))
    }

    fn singular(&mut self, node: &Node) -> Failure {
        self.error(
            node,
            "this system is singular: the determinant of its matrix is identically zero",
            "a singular matrix has no inverse and the system no unique solution; check the matrix, or solve a reduced system",
        )
    }

    fn calculus(
        &mut self,
        _what: Derivative,
        _node: &Node,
    ) -> Result<&mut DynCalculus<'_, Self>, Failure> {
        Ok(self)
    }
}

impl Normals for ExactRing<'_, '_> {
    fn normal(&mut self, _n: &()) -> Tensor<Quotient> {
        // An in-plane normal has no third component: n_3 = 0.
        let normal = &self.env.normal;
        Tensor::from_fn(self.env.decls.dim, 1, |i| {
            Quotient::from(normal.get(i[0]).map_or_else(Poly::zero, |&v| Poly::var(v)))
        })
    }

    /// The average acts on the numerator: no divisor contains the normal.
    fn average(&mut self, a: &Node, node: &Node, _n: &()) -> Result<Tensor<Quotient>, Failure> {
        if let NodeKind::Product(fs) = &a.kind {
            if fs.len() >= 2 {
                return self.average_of_product(a, fs, node);
            }
        }
        let v = walk::walk(self, a, &())?;
        v.try_map(|q| self.averaged(q, node))
    }

    fn maximum(&mut self, _a: &Node, node: &Node) -> Result<Quotient, Failure> {
        Err(self.error(
            node,
            "maxn(…) is a maximum over orientations, not a polynomial",
            "decide this claim with strategy = \"numeric\"",
        ))
    }
}

impl Calculus for ExactRing<'_, '_> {
    /// The total derivative D_k p = Σ_v ∂p/∂v · ∂v/∂x_k over the variables of p
    /// (the chain rule on jet variables), for every component and every k. No divisor
    /// varies with position, so the derivative acts on the numerator alone.
    fn derivatives(
        &mut self,
        a: &Node,
        _node: &Node,
        _n: &(),
    ) -> Result<Tensor<Quotient>, Failure> {
        let v = walk::walk(self, a, &())?;
        let d = self.env.decls.dim;
        let mut values = Vec::with_capacity(v.components().len() * d);
        for q in v.components() {
            for k in 0..d {
                let dk = self.total_derivative(q.numerator(), k)?;
                values.push(q.with_numerator(dk));
            }
        }
        // Components are stored with the last slot fastest, so the coordinate slot
        // added last comes out in this order.
        let mut it = values.into_iter();
        Ok(Tensor::from_fn(d, v.rank() + 1, |_| {
            it.next().expect("one value per component and coordinate")
        }))
    }

    /// The Euler operator on jet variables: for each component v_j of the field,
    /// Σ_α (−1)^|α| D_α (∂P/∂v_j,α) over the jet variables v_j,α that P's numerator
    /// contains. A field that an assumption mentions is refused: its components are
    /// then not independent, and varying them one by one would be wrong.
    fn variations(
        &mut self,
        body: &Node,
        field: &str,
        node: &Node,
        _n: &(),
    ) -> Result<Tensor<Quotient>, Failure> {
        if self.env.assumed.contains(field) {
            return Err(self.error(
                node,
                format!("`{field}` is varied, but an assumption constrains it"),
                "vary a field that no assumption mentions; write the constraint into the density instead",
            ));
        }
        let v = walk::walk(self, body, &())?;
        let d = self.env.decls.dim;
        let rank = self.env.decls.symbols.get(field).copied().unwrap_or(0);
        let components: Vec<Vec<usize>> = assignments(d, rank).collect();
        let mut values = Vec::with_capacity(v.components().len() * components.len());
        for q in v.components() {
            let p = q.numerator();
            let mut jets: Vec<(Var, Vec<usize>, Vec<usize>)> = p
                .variables()
                .into_iter()
                .filter_map(|x| match self.env.varying.get(&x) {
                    Some(Varying::Jet {
                        field: f,
                        idx,
                        orders,
                    }) if f == field => Some((x, idx.clone(), orders.clone())),
                    _ => None,
                })
                .collect();
            jets.sort_unstable();
            for idx in &components {
                let mut acc = Poly::zero();
                for (x, _, orders) in jets.iter().filter(|(_, i, _)| i == idx) {
                    let mut term = p.derivative(*x);
                    for &k in orders {
                        term = self.total_derivative(&term, k)?;
                    }
                    if orders.len() % 2 == 1 {
                        term = -term;
                    }
                    acc += &term;
                }
                values.push(q.with_numerator(acc));
            }
        }
        let mut it = values.into_iter();
        Ok(Tensor::from_fn(d, v.rank() + rank, |_| {
            it.next()
                .expect("one value per component of the density and of the field")
        }))
    }

    /// ∂body/∂symbol at the state, by the chain rule over exact quotients
    /// ([`super::jets`]).
    fn gradients(
        &mut self,
        body: &Node,
        symbol: &str,
        _node: &Node,
        _n: &(),
    ) -> Result<Tensor<Quotient>, Failure> {
        super::jets::gradients(self, body, symbol)
    }
}
