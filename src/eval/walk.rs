//! The one tree walk every route evaluates expressions with, generic over the ring it
//! computes in: canonical polynomials under a work budget (`exact/`), `f64` and num-dual
//! numbers (the interpreter, `real/`), op ids of the tape compiler (`tape.rs`) and
//! enclosures (`interval.rs`), as SymEngine's single visitor does it.
//!
//! The walk owns what the routes have in common — free-index labels, contraction by
//! [`einsum`], sums, scalar arguments, matrices — and asks the ring for what is its own,
//! by capability: [`Ring`] (constants, symbols and definitions, division, powers,
//! functions), [`Normals`] (the normal and the two operations over it: `avg`, by exact
//! moments, by quadrature or as a sub-tape; `maxn`) and [`Calculus`] (derivatives along
//! the position, variations, gradients). Independence between routes therefore comes
//! from their methods (canonical forms against sampling, moments against quadrature),
//! not from copies of this code.
//!
//! Every value is a tensor whose slots are the node's free letters in sorted order
//! ([`Node::free_letters`]).

use crate::algebra::einsum::{einsum, Arithmetic, Slot};
use crate::algebra::matrix::{self as linear, Matrix, Signed};
use crate::algebra::Tensor;
use crate::derivation::Definition;
use crate::eval::labeled::Labeled;
use crate::kernel::Rational;
use crate::lang::matrix::{MatrixOp, MatrixRead, Order};
use crate::lang::parser::{Func, Func2, Wrt};
use crate::lang::{Node, NodeKind, Target};
use rustc_hash::FxHashMap as HashMap;

/// What a route computes in: constants, symbols, definitions, quotients, powers and
/// functions, and what the walk needs to locate an error. `Normal` is how the walk hands
/// it the normal vector n: numbers, op ids, or nothing at all when n is a polynomial
/// variable. The operations over n and the derivatives are capabilities of their own
/// ([`Normals`], [`Calculus`]).
pub trait Ring: Arithmetic {
    type Normal: ?Sized;

    /// The index range 1..=d.
    fn dim(&self) -> usize;
    fn constant(&mut self, q: &Rational) -> Self::Value;
    fn neg(&mut self, x: Self::Value) -> Self::Value;
    /// δ_ij and ε_ijk.
    fn delta(&mut self) -> Tensor<Self::Value> {
        let (zero, one) = (self.zero(), self.one());
        Tensor::from_fn(self.dim(), 2, |i| {
            if i[0] == i[1] {
                one.clone()
            } else {
                zero.clone()
            }
        })
    }

    fn epsilon(&mut self) -> Tensor<Self::Value> {
        let e = Tensor::<i64>::levi_civita(self.dim());
        let values = [-1, 0, 1].map(|k| self.constant(&Rational::int(k)));
        e.map(|&v| values[(v + 1) as usize].clone())
    }

    /// A declared symbol's components.
    fn symbol(&mut self, name: &str, node: &Node) -> Result<Tensor<Self::Value>, Self::Error>;
    /// A definition's value, slots in its formal order (memoised as the ring sees fit).
    fn definition(
        &mut self,
        name: &str,
        node: &Node,
        n: &Self::Normal,
    ) -> Result<Tensor<Self::Value>, Self::Error>;
    /// `x / den`; `divisor` is the denominator's node, for errors.
    fn divide(
        &mut self,
        x: Self::Value,
        den: &Self::Value,
        divisor: &Node,
    ) -> Result<Self::Value, Self::Error>;
    fn power(&mut self, x: Self::Value, k: u32, node: &Node) -> Result<Self::Value, Self::Error>;
    fn apply(&mut self, f: Func, x: Self::Value, node: &Node) -> Result<Self::Value, Self::Error>;
    /// A function of two scalars.
    fn apply2(
        &mut self,
        f: Func2,
        x: Self::Value,
        y: Self::Value,
        node: &Node,
    ) -> Result<Self::Value, Self::Error>;
    /// π (`node` locates a refusal: it is not rational).
    fn pi(&mut self, node: &Node) -> Result<Self::Value, Self::Error>;
    /// Called before a node is evaluated (a budget on the walk).
    fn enter(&mut self, _node: &Node) -> Result<(), Self::Error> {
        Ok(())
    }

    /// Called on every node's value (a size limit).
    fn leave(
        &mut self,
        _node: &Node,
        value: Tensor<Self::Value>,
    ) -> Result<Tensor<Self::Value>, Self::Error> {
        Ok(value)
    }

    /// Locates an error of the contraction at `node`.
    fn at(&mut self, e: Self::Error, _node: &Node) -> Self::Error {
        e
    }

    /// An argument that should be a scalar is not.
    fn not_scalar(&mut self, node: &Node) -> Self::Error;
    /// Whether a determinant is zero, so that `inv(A)` or `solve(A, b)` is refused as
    /// singular ([`Ring::singular`]) rather than divided by: identically zero in exact
    /// arithmetic, zero at the point in floating point.
    fn vanishes(&self, det: &Self::Value) -> bool {
        self.is_exact_zero(det)
    }

    /// `inv(A)` or `solve(A, b)` of a matrix whose determinant [`Ring::vanishes`].
    fn singular(&mut self, node: &Node) -> Self::Error;

    /// The ring's derivatives ([`Calculus`]), or why it takes none (`what` is the
    /// derivative asked for, `node` where): the exact, jet and real rings have them, the
    /// tape and the enclosures do not.
    fn calculus(
        &mut self,
        what: Derivative,
        node: &Node,
    ) -> Result<&mut DynCalculus<'_, Self>, Self::Error>;
}

/// The derivative a node asks for, to say which one a ring does not take.
#[derive(Clone, Copy, Debug)]
pub enum Derivative {
    /// `u_i,k`: along the position.
    Position,
    /// `variation(…)`.
    Variation,
    /// `grad(…)`.
    Gradient,
}

impl std::fmt::Display for Derivative {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Derivative::Position => "a derivative along the position",
            Derivative::Variation => "a variational derivative",
            Derivative::Gradient => "grad(…)",
        })
    }
}

/// A ring's [`Calculus`], seen through its values, errors and normal.
pub type DynCalculus<'r, R> = dyn Calculus<
        Normal = <R as Ring>::Normal,
        Value = <R as Arithmetic>::Value,
        Error = <R as Arithmetic>::Error,
    > + 'r;

/// The unit normal and the operations over it: `avg` (by exact moments, by quadrature
/// or as a sub-tape) and `maxn`.
pub trait Normals: Ring {
    fn normal(&mut self, n: &Self::Normal) -> Tensor<Self::Value>;
    /// `avg(arg)` over the unit normal.
    fn average(
        &mut self,
        arg: &Node,
        node: &Node,
        n: &Self::Normal,
    ) -> Result<Tensor<Self::Value>, Self::Error>;
    /// `maxn(arg)` over the in-plane orientation of the normal.
    fn maximum(&mut self, arg: &Node, node: &Node) -> Result<Self::Value, Self::Error>;
}

/// Derivatives: along the position (of fields), variational, and with respect to a
/// declared symbol. A ring hands them to the walk through [`Ring::calculus`]; the exact
/// and real rings take all three, the jet ring of `grad` only derivatives along the
/// position (a variation or a gradient inside `grad(…)` it refuses, with where).
pub trait Calculus: Ring {
    /// The derivatives of `arg` with respect to every coordinate of the position: a
    /// tensor with `arg`'s slots (its free letters, sorted) and one more, last, for the
    /// coordinate.
    fn derivatives(
        &mut self,
        arg: &Node,
        node: &Node,
        n: &Self::Normal,
    ) -> Result<Tensor<Self::Value>, Self::Error>;
    /// The variational derivatives of the density `body` with respect to every
    /// component of `field` (see `variation(…)` in the guide): a tensor with `body`'s
    /// slots (its free letters, sorted) followed by the field's slots.
    fn variations(
        &mut self,
        body: &Node,
        field: &str,
        node: &Node,
        n: &Self::Normal,
    ) -> Result<Tensor<Self::Value>, Self::Error>;
    /// The partial derivatives of `body` with respect to every component of the
    /// declared `symbol` at the state (see [`NodeKind::Wrt`]): a tensor with `body`'s
    /// slots (its free letters, sorted) followed by the symbol's slots.
    fn gradients(
        &mut self,
        body: &Node,
        symbol: &str,
        node: &Node,
        n: &Self::Normal,
    ) -> Result<Tensor<Self::Value>, Self::Error>;
}

/// A ring the walk evaluates every construct in (derivatives where it takes them).
pub trait Evaluator: Normals {}

impl<R: Normals> Evaluator for R {}

/// A ring seen by the determinants and adjugates of `algebra::matrix`, which need its
/// arithmetic and its negation only.
struct Signing<'r, R>(&'r mut R);

impl<R: Ring> Arithmetic for Signing<'_, R> {
    type Value = R::Value;
    type Error = R::Error;
    fn zero(&mut self) -> R::Value {
        self.0.zero()
    }
    fn one(&mut self) -> R::Value {
        self.0.one()
    }
    fn is_exact_zero(&self, x: &R::Value) -> bool {
        self.0.is_exact_zero(x)
    }
    fn mul(&mut self, a: R::Value, b: &R::Value) -> Result<R::Value, R::Error> {
        self.0.mul(a, b)
    }
    fn add(&mut self, a: R::Value, b: R::Value) -> Result<R::Value, R::Error> {
        self.0.add(a, b)
    }
    fn first(&mut self, x: &R::Value) -> Result<R::Value, R::Error> {
        self.0.first(x)
    }
}

impl<R: Ring> Signed for Signing<'_, R> {
    fn negate(&mut self, x: R::Value) -> R::Value {
        self.0.neg(x)
    }
}

/// The value of `node` in `ring`, with the normal `n` (outside `avg` and `maxn`).
pub fn walk<R: Evaluator>(
    ring: &mut R,
    node: &Node,
    n: &R::Normal,
) -> Result<Tensor<R::Value>, R::Error> {
    // Every ring's evaluation can be long (nested differences, exact expansions): the
    // claim's time limit stops it here.
    crate::kernel::interrupt::tick();
    ring.enter(node)?;
    let d = ring.dim();
    let labels = node.free_letters();
    let value = match &node.kind {
        // A constant is a scalar, except the literal 0 where a context gave it free
        // indices (`Node::zero_with_free`): zero in every component.
        NodeKind::Const(q) => {
            let c = ring.constant(q);
            Tensor::from_fn(d, labels.len(), |_| c.clone())
        }
        NodeKind::Leaf { target, slots } => {
            let base = match target {
                Target::Delta => ring.delta(),
                Target::Eps => ring.epsilon(),
                Target::Pi => Tensor::scalar(d, ring.pi(node)?),
                Target::Normal => ring.normal(n),
                Target::Symbol(s) => ring.symbol(s, node)?,
                Target::Def(name) => ring.definition(name, node, n)?,
            };
            contract(ring, &[(&base, slots.clone())], &labels, node)?
        }
        NodeKind::Neg(a) => {
            let t = walk(ring, a, n)?;
            let mut out = Vec::with_capacity(t.components().len());
            for x in t.components() {
                out.push(ring.neg(x.clone()));
            }
            Tensor::from_components(d, t.rank(), out)
        }
        NodeKind::Sum(terms) => {
            let mut acc: Option<Tensor<R::Value>> = None;
            for term in terms {
                let v = walk(ring, term, n)?;
                acc = Some(match acc {
                    None => v,
                    Some(a) => {
                        let mut out = Vec::with_capacity(a.components().len());
                        for (x, y) in a.components().iter().zip(v.components()) {
                            out.push(ring.add(x.clone(), y.clone())?);
                        }
                        Tensor::from_components(d, a.rank(), out)
                    }
                });
            }
            acc.expect("the parser gives a sum at least one term")
        }
        NodeKind::Product(fs) => {
            let values = factor_values(ring, fs, n)?;
            contract(ring, &as_factors(&values), &labels, node)?
        }
        NodeKind::Div(a, b) => {
            let t = walk(ring, a, n)?;
            let den = scalar(ring, b, n)?;
            let mut out = Vec::with_capacity(t.components().len());
            for x in t.components() {
                out.push(ring.divide(x.clone(), &den, b)?);
            }
            Tensor::from_components(d, t.rank(), out)
        }
        NodeKind::Pow(a, k) => {
            let x = scalar(ring, a, n)?;
            Tensor::scalar(d, ring.power(x, *k, node)?)
        }
        NodeKind::Apply(f, a) => {
            let x = scalar(ring, a, n)?;
            Tensor::scalar(d, ring.apply(*f, x, node)?)
        }
        NodeKind::Apply2(f, a, b) => {
            let (x, y) = (scalar(ring, a, n)?, scalar(ring, b, n)?);
            Tensor::scalar(d, ring.apply2(*f, x, y, node)?)
        }
        NodeKind::Avg(a) => ring.average(a, node, n)?,
        NodeKind::MaxN(a) => Tensor::scalar(d, ring.maximum(a, node)?),
        NodeKind::Deriv(a, slot) => {
            let t = ring
                .calculus(Derivative::Position, node)?
                .derivatives(a, node, n)?;
            let mut slots: Vec<Slot> = a.free_letters().into_iter().map(Slot::Letter).collect();
            slots.push(*slot);
            contract(ring, &[(&t, slots)], &labels, node)?
        }
        NodeKind::Wrt {
            op,
            body,
            symbol,
            slots: field_slots,
        } => {
            let t = match op {
                Wrt::Variation => ring
                    .calculus(Derivative::Variation, node)?
                    .variations(body, symbol, node, n)?,
                Wrt::Grad => ring
                    .calculus(Derivative::Gradient, node)?
                    .gradients(body, symbol, node, n)?,
            };
            let mut slots: Vec<Slot> = body.free_letters().into_iter().map(Slot::Letter).collect();
            slots.extend(field_slots.iter().copied());
            contract(ring, &[(&t, slots)], &labels, node)?
        }
        // A matrix travels as the rank-1 list of its entries, row by row (how a
        // definition's value is cached); its shape is the node's.
        NodeKind::Matrix { .. } => {
            let m = matrix(ring, node, n)?;
            let len = m.entries().len();
            let mut entries = m.into_entries().into_iter();
            Tensor::from_fn(len, 1, |_| entries.next().expect("one value per entry"))
        }
        NodeKind::Read(read, a) => {
            let m = matrix(ring, a, n)?;
            match read {
                MatrixRead::Det => Tensor::scalar(d, linear::determinant(&mut Signing(ring), &m)?),
                MatrixRead::Trace => {
                    let mut acc = ring.zero();
                    for k in 0..m.rows() {
                        acc = ring.add(acc, m.get(k, k).clone())?;
                    }
                    Tensor::scalar(d, acc)
                }
                MatrixRead::Entry(i, j) => Tensor::scalar(d, m.get(*i, *j).clone()),
                MatrixRead::Tensor { rows, cols } => {
                    let zero = ring.zero();
                    Tensor::from_fn(d, labels.len(), |idx| {
                        let at = |o: &Order| {
                            let values: Vec<usize> = o
                                .slots
                                .iter()
                                .map(|s| match s {
                                    Slot::Letter(c) => {
                                        idx[labels
                                            .iter()
                                            .position(|l| l == c)
                                            .expect("an order's letter is free")]
                                    }
                                    Slot::Fixed(k) => *k,
                                })
                                .collect();
                            o.position_of(&values)
                        };
                        let col = cols.as_deref().map_or(Some(0), at);
                        match (at(rows), col) {
                            (Some(a), Some(b)) => m.get(a, b).clone(),
                            _ => zero.clone(),
                        }
                    })
                }
            }
        }
    };
    ring.leave(node, value)
}

/// The value of a matrix-valued node (see [`crate::lang::matrix`]).
pub fn matrix<R: Evaluator>(
    ring: &mut R,
    node: &Node,
    n: &R::Normal,
) -> Result<Matrix<R::Value>, R::Error> {
    let NodeKind::Matrix { rows, cols, op } = &node.kind else {
        // A scalar standing for a 1×1 matrix.
        let x = scalar(ring, node, n)?;
        return Ok(Matrix::from_fn(1, 1, |_, _| x.clone()));
    };
    let (rows, cols) = (*rows, *cols);
    let elementwise = |ring: &mut R, a: &Node| -> Result<Vec<R::Value>, R::Error> {
        Ok(matrix(ring, a, n)?.into_entries())
    };
    let out = match op {
        MatrixOp::Literal(entries) => {
            let mut values = Vec::with_capacity(entries.len());
            for e in entries {
                values.push(scalar(ring, e, n)?);
            }
            values
        }
        MatrixOp::Def(name) => ring.definition(name, node, n)?.into_components(),
        MatrixOp::Identity => {
            let (zero, one) = (ring.zero(), ring.one());
            (0..rows * cols)
                .map(|k| {
                    if k / cols == k % cols {
                        one.clone()
                    } else {
                        zero.clone()
                    }
                })
                .collect()
        }
        MatrixOp::Sum(terms) => {
            let mut acc = elementwise(ring, &terms[0])?;
            for t in &terms[1..] {
                let v = elementwise(ring, t)?;
                let mut out = Vec::with_capacity(acc.len());
                for (x, y) in acc.into_iter().zip(v) {
                    out.push(ring.add(x, y)?);
                }
                acc = out;
            }
            acc
        }
        MatrixOp::Scale(s, m) => {
            let s = scalar(ring, s, n)?;
            let mut out = Vec::with_capacity(rows * cols);
            for x in elementwise(ring, m)? {
                out.push(ring.mul(x, &s)?);
            }
            out
        }
        MatrixOp::Product(a, b) => {
            let (a, b) = (matrix(ring, a, n)?, matrix(ring, b, n)?);
            linear::product(ring, &a, &b)?.into_entries()
        }
        MatrixOp::Transpose(a) => matrix(ring, a, n)?.transpose().into_entries(),
        MatrixOp::Adjugate(a) => {
            let a = matrix(ring, a, n)?;
            linear::adjugate(&mut Signing(ring), &a)?.into_entries()
        }
        MatrixOp::Inverse(a) | MatrixOp::Solve(a, _) => {
            let am = matrix(ring, a, n)?;
            let det = linear::determinant(&mut Signing(ring), &am)?;
            if ring.vanishes(&det) {
                return Err(ring.singular(node));
            }
            let mut adj = linear::adjugate(&mut Signing(ring), &am)?;
            if let MatrixOp::Solve(_, b) = op {
                let b = matrix(ring, b, n)?;
                adj = linear::product(ring, &adj, &b)?;
            }
            let mut out = Vec::with_capacity(rows * cols);
            for x in adj.into_entries() {
                out.push(ring.divide(x, &det, a)?);
            }
            out
        }
        MatrixOp::View {
            tensor,
            rows: ro,
            cols: co,
        } => {
            let t = walk(ring, tensor, n)?;
            let letters = tensor.free_letters();
            let mut out = Vec::with_capacity(rows * cols);
            for a in 0..rows {
                for b in 0..cols {
                    let mut values: Vec<(char, usize)> = Vec::with_capacity(letters.len());
                    let mut bind = |o: &Order, p: usize| {
                        for (s, &v) in o.slots.iter().zip(&o.positions[p]) {
                            if let Slot::Letter(c) = s {
                                values.push((*c, v));
                            }
                        }
                    };
                    bind(ro, a);
                    if let Some(co) = co {
                        bind(co, b);
                    }
                    let idx: Vec<usize> = letters
                        .iter()
                        .map(|c| values.iter().find(|(l, _)| l == c).map_or(0, |&(_, v)| v))
                        .collect();
                    out.push(t.get(&idx).clone());
                }
            }
            out
        }
    };
    Ok(Matrix::from_rows(rows, cols, out).expect("every operation keeps the node's shape"))
}

/// The value of a node that must be a scalar.
pub fn scalar<R: Evaluator>(
    ring: &mut R,
    node: &Node,
    n: &R::Normal,
) -> Result<R::Value, R::Error> {
    let t = walk(ring, node, n)?;
    match t.into_scalar() {
        Some(x) => Ok(x),
        None => Err(ring.not_scalar(node)),
    }
}

/// The degree of `node` as a polynomial in the normal n outside `avg` and `maxn`
/// (`None`: not a polynomial in n, e.g. n under a square root or in a divisor), with
/// the definitions' degrees memoised in `memo`.
pub fn normal_degree(
    node: &Node,
    defs: &[Definition],
    memo: &mut HashMap<String, Option<usize>>,
) -> Option<usize> {
    if let Some(name) = node.definition() {
        if let Some(d) = memo.get(name) {
            return *d;
        }
        let d = defs
            .iter()
            .rev()
            .find(|x| x.sig.name == name)
            .and_then(|def| normal_degree(&def.body, defs, memo));
        memo.insert(name.to_owned(), d);
        return d;
    }
    match &node.kind {
        NodeKind::Const(_) | NodeKind::Avg(_) | NodeKind::MaxN(_) => Some(0),
        NodeKind::Leaf { target, .. } => match target {
            Target::Normal => Some(1),
            _ => Some(0),
        },
        // ∂/∂σ of a polynomial in n is one of no higher degree.
        NodeKind::Neg(a) | NodeKind::Deriv(a, _) | NodeKind::Wrt { body: a, .. } => {
            normal_degree(a, defs, memo)
        }
        NodeKind::Sum(xs) => xs
            .iter()
            .try_fold(0, |m, x| Some(m.max(normal_degree(x, defs, memo)?))),
        NodeKind::Product(xs) => xs
            .iter()
            .try_fold(0, |m, x| Some(m + normal_degree(x, defs, memo)?)),
        NodeKind::Div(a, b) => match normal_degree(b, defs, memo)? {
            0 => normal_degree(a, defs, memo),
            _ => None,
        },
        NodeKind::Pow(a, k) => Some(normal_degree(a, defs, memo)? * *k as usize),
        // Determinants, inverses and solves multiply and divide entries: only
        // entries free of n keep a known degree (0).
        NodeKind::Matrix {
            op: MatrixOp::Inverse(_) | MatrixOp::Adjugate(_) | MatrixOp::Solve(..),
            ..
        }
        | NodeKind::Read(MatrixRead::Det, _) => {
            match node
                .children()
                .into_iter()
                .try_fold(0, |m, x| Some(m.max(normal_degree(x, defs, memo)?)))?
            {
                0 => Some(0),
                _ => None,
            }
        }
        NodeKind::Matrix {
            op: MatrixOp::Scale(..) | MatrixOp::Product(..),
            ..
        } => node
            .children()
            .into_iter()
            .try_fold(0, |m, x| Some(m + normal_degree(x, defs, memo)?)),
        NodeKind::Matrix { .. } | NodeKind::Read(..) => node
            .children()
            .into_iter()
            .try_fold(0, |m, x| Some(m.max(normal_degree(x, defs, memo)?))),
        NodeKind::Apply(_, a) => match normal_degree(a, defs, memo)? {
            0 => Some(0),
            _ => None,
        },
        NodeKind::Apply2(_, a, b) => {
            match (normal_degree(a, defs, memo)?, normal_degree(b, defs, memo)?) {
                (0, 0) => Some(0),
                _ => None,
            }
        }
    }
}

/// A definition's body walked and reordered into the definition's formal slots.
pub fn in_formal_order<R: Evaluator>(
    ring: &mut R,
    body: &Node,
    formal: &[char],
    n: &R::Normal,
) -> Result<Tensor<R::Value>, R::Error> {
    let t = walk(ring, body, n)?;
    if body.shape().is_some() {
        // A matrix's entries, row by row: no slots to reorder.
        return Ok(t);
    }
    let letters = body.free_letters();
    let perm: Vec<usize> = formal
        .iter()
        .map(|c| letters.iter().position(|x| x == c).unwrap_or(0))
        .collect();
    Ok(t.permuted(&perm))
}

/// The values of a product's factors, each with its free letters.
pub fn factor_values<R: Evaluator>(
    ring: &mut R,
    fs: &[Node],
    n: &R::Normal,
) -> Result<Vec<Labeled<R::Value>>, R::Error> {
    let mut values = Vec::with_capacity(fs.len());
    for f in fs {
        values.push(Labeled::new(f.free_letters(), walk(ring, f, n)?));
    }
    Ok(values)
}

/// A product's factors for [`einsum`]: each value indexed by its free letters.
pub fn as_factors<T>(values: &[Labeled<T>]) -> Vec<(&Tensor<T>, Vec<Slot>)> {
    values
        .iter()
        .map(|v| {
            let slots = v.labels.iter().map(|&c| Slot::Letter(c)).collect();
            (&v.tensor, slots)
        })
        .collect()
}

/// The contraction of `factors` onto `labels`, its errors located at `node`.
pub fn contract<R: Ring>(
    ring: &mut R,
    factors: &[(&Tensor<R::Value>, Vec<Slot>)],
    labels: &[char],
    node: &Node,
) -> Result<Tensor<R::Value>, R::Error> {
    let d = ring.dim();
    match einsum(ring, d, factors, labels) {
        Ok(t) => Ok(t),
        Err(e) => Err(ring.at(e, node)),
    }
}
