//! Evaluation of checked expressions over the reals, generic over the scalar: `f64`
//! for sampling, and num-dual numbers (`DualDVec64`, `Dual2DVec64`, …) for gradients
//! and Hessians. It shares only the parser and validator with the exact route, and
//! has its own contraction code: a shared bug would make both routes agree on a wrong
//! answer.
//!
//! `avg(…)` re-evaluates its argument at the nodes of a quadrature rule exact for its
//! degree in n (see [`super::quadrature::sphere_rule_exact_to`]), or, when the argument is
//! not a polynomial in n, by adaptive quadrature with an error estimate (see
//! [`super::quadrature`]); `maxn(…)` maximises over the normal's angle in the
//! plane by a dense grid refined by golden-section search (see [`MAXN_GRID`]).

use super::assume::{product_value, Component, Parametrisation};
use super::quadrature::{Level, Quadrature};
use super::taylor::{self, TaylorFields};
use super::variation::{self, Perturbation};
use super::walk::{self, Ring};
use crate::algebra::einsum::Arithmetic;
use crate::algebra::{assignments, Tensor};
use crate::derivation::{Assumption, Definition};
use crate::kernel::Rational;
use crate::lang::parser::{Func, Func2};
use crate::lang::{Decls, Node, Span};
use nalgebra::{Dyn, U1};
use num_dual::{Derivative, DualDVec64, DualNum};
use rustc_hash::FxHashMap as HashMap;
use std::cell::{Cell, RefCell};
use std::rc::Rc;

/// Grid points of `maxn` over [0, 2π) before golden-section refinement of every local
/// maximum of the grid. For a function whose peaks are wider than two grid steps (a
/// trigonometric polynomial of degree ≤ 4 in the angle, or its absolute value, as
/// here: peaks at least 2π/8 wide), each peak contains a grid local maximum, and the
/// refinement converges to 1e-12 in angle, so the maximum is found to rounding.
pub const MAXN_GRID: usize = 360;

/// The most derivatives along the position nested inside each other that central
/// differences take: each level evaluates its argument 4d times, and each loses
/// digits, so a fifth order would be both slow and meaningless (the exact route
/// differentiates any order symbolically).
pub const MAX_NESTED_DIFFERENCES: usize = 4;

/// An evaluation error located in the expression's text.
#[derive(Clone, Debug, PartialEq)]
pub struct RealError {
    pub span: Span,
    pub message: String,
    /// The expression has no value at this state only (a divisor zero, a function
    /// outside its domain, a derivative that does not exist): a sampled claim steps off
    /// such a state. Otherwise the expression cannot be evaluated at all.
    pub pointwise: bool,
}

fn err(node: &Node, message: impl Into<String>) -> RealError {
    RealError {
        span: node.span,
        message: message.into(),
        pointwise: false,
    }
}

/// The expression at `node` has no value at this state (see [`RealError::pointwise`]).
pub(super) fn undefined(span: Span, message: impl Into<String>) -> RealError {
    RealError {
        span,
        message: message.into(),
        pointwise: true,
    }
}

/// Free-index labels (sorted) and the tensor.
pub type Labeled<T> = (Vec<char>, Tensor<T>);

/// Quadrature nodes and weights.
type Rule = Vec<(Vec<f64>, f64)>;

/// Memoised definition values, keyed by name and (for definitions that depend on the
/// normal) the normal's bits.
type Memo<T> = HashMap<(String, Vec<u64>), Tensor<T>>;

/// Entries kept before the memo is cleared (a `maxn` visits hundreds of normals).
const MEMO_LIMIT: usize = 4096;

/// The values of one sample: every symbol's components, with caches for definition
/// values, their degree in the normal, and quadrature rules.
pub struct RealEnv<'a, T> {
    pub decls: &'a Decls,
    pub defs: &'a [Definition],
    pub symbols: HashMap<String, Tensor<T>>,
    memo: RefCell<Memo<T>>,
    degrees: RefCell<HashMap<String, Option<usize>>>,
    rules: RefCell<HashMap<usize, Rc<Rule>>>,
    /// The accuracy of averages of arguments that are not polynomials in n, and what
    /// they reported.
    pub quadrature: Quadrature,
    /// The fields as functions of the position, where a claim differentiates them
    /// (the second route of a derivative claim); `None`: derivatives are refused.
    pub fields: Option<TaylorFields>,
    /// Where the fields are evaluated (the centre of `fields` until a derivative
    /// moves it).
    pub(super) position: RefCell<Vec<f64>>,
    /// A perturbation added to one field component while a variation is taken
    /// (see [`super::variation`]).
    pub(super) perturbation: RefCell<Option<Perturbation>>,
    /// Counts changes of `perturbation`: definition values are memoised per epoch.
    epoch: Cell<u64>,
    /// How many central differences are nested now ([`MAX_NESTED_DIFFERENCES`]).
    differences: Cell<usize>,
    /// Fields that an assumption defines by an expression (`u_i = A_ij x_j`), with
    /// fields in use: evaluated from that expression wherever the position is.
    defined_fields: HashMap<String, (Vec<char>, Node, Vec<f64>)>,
    /// This environment evaluates the body of a `grad(…)`: its values are dual
    /// numbers seeded from real ones, so a gradient inside is refused.
    in_gradient: bool,
}

impl<'a, T: DualNum<Primitive = f64>> RealEnv<'a, T> {
    /// An environment with the given symbol values (any map or list of them).
    pub fn new(
        decls: &'a Decls,
        defs: &'a [Definition],
        symbols: impl IntoIterator<Item = (String, Tensor<T>)>,
    ) -> Self {
        RealEnv {
            decls,
            defs,
            symbols: symbols.into_iter().collect(),
            memo: RefCell::new(HashMap::default()),
            degrees: RefCell::new(HashMap::default()),
            rules: RefCell::new(HashMap::default()),
            quadrature: Quadrature::new(Level::Fine),
            fields: None,
            position: RefCell::new(Vec::new()),
            perturbation: RefCell::new(None),
            epoch: Cell::new(0),
            differences: Cell::new(0),
            defined_fields: HashMap::default(),
            in_gradient: false,
        }
    }

    /// Sets (or, with `None`, removes) the perturbation of a field component.
    pub(super) fn perturb(&self, p: Option<Perturbation>) {
        *self.perturbation.borrow_mut() = p;
        self.epoch.set(self.epoch.get() + 1);
    }

    /// `t`, the value of `name` at `x`, plus the perturbation when it is of `name`.
    fn perturbed(&self, name: &str, mut t: Tensor<T>, x: &[f64]) -> Tensor<T> {
        if let Some(p) = self
            .perturbation
            .borrow()
            .as_ref()
            .filter(|p| p.field == name)
        {
            let c = t.get_mut(&p.idx);
            *c = c.clone() + T::from(p.at(x));
        }
        t
    }

    /// The central difference along coordinate `k` with step `h` of `f`, a value
    /// computed wherever the position is: `f` at the position moved by each of
    /// [`taylor::STEPS`], the position restored after each.
    pub(super) fn difference_along(
        &self,
        k: usize,
        h: f64,
        f: &mut dyn FnMut(&Self) -> Result<Tensor<T>, RealError>,
    ) -> Result<Tensor<T>, RealError> {
        let centre = self.position.borrow().clone();
        let mut values = Vec::with_capacity(4);
        for step in taylor::STEPS {
            let mut x = centre.clone();
            x[k] += step * h;
            *self.position.borrow_mut() = x;
            let value = f(self);
            *self.position.borrow_mut() = centre.clone();
            values.push(value?);
        }
        Ok(taylor::stencil_tensor(&values, h))
    }

    /// Whether an assumption defines the field by an expression of the position.
    pub(super) fn defines(&self, field: &str) -> bool {
        self.defined_fields.contains_key(field)
    }

    /// Evaluates fields as the given Taylor polynomials, at their centre.
    pub fn with_fields(mut self, fields: TaylorFields) -> Self {
        *self.position.borrow_mut() = fields.centre.clone();
        self.fields = Some(fields);
        self
    }

    fn def(&self, name: &str) -> Option<&'a Definition> {
        self.defs.iter().rev().find(|x| x.sig.name == name)
    }

    /// The degree in n of `node` (see [`walk::normal_degree`]).
    pub fn normal_degree(&self, node: &Node) -> Option<usize> {
        walk::normal_degree(node, self.defs, &mut self.degrees.borrow_mut())
    }

    /// The averaging rule for an argument of this degree in n.
    fn rule(&self, degree: usize) -> Rc<Rule> {
        let degree = degree.clamp(1, 40);
        self.rules
            .borrow_mut()
            .entry(degree)
            .or_insert_with(|| Rc::new(super::quadrature::rule_for(self.decls, degree)))
            .clone()
    }

    /// Evaluates `node` with the normal `n` (used outside `avg`/`maxn`).
    pub fn eval(&self, node: &Node, n: &[f64]) -> Result<Labeled<T>, RealError> {
        Ok((node.free_letters(), walk::walk(&mut &*self, node, n)?))
    }

    /// max over θ of `a` at n = (cos θ, sin θ[, 0]): grid, then golden section around
    /// the best grid point; the value (with its derivatives, by the envelope theorem)
    /// is `a` evaluated at the maximiser.
    fn max_over_angle(&self, node: &Node, a: &Node) -> Result<T, RealError> {
        let d = self.decls.dim;
        if d == 3 && !self.decls.normal_in_plane {
            return Err(err(node, "maxn(…) maximises over the normal in a plane: use dimension = 2 or normal_in_plane = true"));
        }
        let at = |theta: f64| -> Vec<f64> {
            let mut n = vec![theta.cos(), theta.sin()];
            n.resize(d, 0.0);
            n
        };
        let value = |theta: f64| walk::scalar(&mut &*self, a, &at(theta));
        let f = |theta: f64| -> Result<f64, RealError> { Ok(value(theta)?.re()) };
        let h = 2.0 * std::f64::consts::PI / MAXN_GRID as f64;
        let mut grid = Vec::with_capacity(MAXN_GRID);
        for k in 0..MAXN_GRID {
            let v = f(k as f64 * h)?;
            if !v.is_finite() {
                return Err(undefined(node.span, "maxn(…): the argument is not finite"));
            }
            grid.push(v);
        }
        // Refine every local maximum of the grid (not only the best one), so that a
        // second peak whose grid value is slightly lower is not missed.
        let mut best = (0.0, f64::NEG_INFINITY);
        for k in 0..MAXN_GRID {
            let (prev, next) = (
                grid[(k + MAXN_GRID - 1) % MAXN_GRID],
                grid[(k + 1) % MAXN_GRID],
            );
            if grid[k] < prev || grid[k] < next {
                continue;
            }
            let (theta, v) = golden_max(&f, k as f64 * h, h)?;
            if v > best.1 {
                best = (theta, v);
            }
        }
        value(best.0)
    }

    /// Applies the solved assumptions to the symbol values: every constrained
    /// component set from the free ones, then the substitutions in dependency order.
    pub fn assume(
        &mut self,
        parametrisation: &Parametrisation,
        assumptions: &[Assumption],
        n: &[f64],
    ) -> Result<(), RealError> {
        self.memo.borrow_mut().clear();
        let symbols = &self.symbols;
        if let Some(fields) = &mut self.fields {
            // A component tied to others is tied as a function of the position.
            // A product of parameters (never fields) is a constant in space.
            for d in parametrisation.dependents() {
                let (symbol, idx) = d.component;
                if self.decls.fields.contains_key(symbol) {
                    let terms: Vec<_> = d
                        .terms
                        .iter()
                        .map(|((s, i), q)| ((s.clone(), i.clone()), q.to_f64()))
                        .collect();
                    let products = d.products.iter().fold(0.0, |acc, (p, q)| {
                        let at =
                            |(s, i): &Component| symbols.get(s).map_or(f64::NAN, |t| t.get(i).re());
                        acc + q.to_f64() * product_value(p, 1.0, at)
                    });
                    fields.tie((symbol, idx), &terms, d.constant.to_f64() + products);
                }
            }
        }
        for d in parametrisation.dependents() {
            let at = |(s, i): &Component| {
                self.symbols
                    .get(s)
                    .map_or_else(|| T::from(f64::NAN), |t| t.get(i).clone())
            };
            let linear = d.terms.iter().map(|(c, q)| at(c) * q.to_f64());
            let products = d
                .products
                .iter()
                .map(|(p, q)| product_value(p, T::from(1.0), at) * q.to_f64());
            let value = linear
                .chain(products)
                .fold(T::from(d.constant.to_f64()), |acc, x| acc + x);
            let (symbol, idx) = d.component;
            if let Some(t) = self.symbols.get_mut(symbol) {
                *t.get_mut(idx) = value;
            }
        }
        for sub in parametrisation.substituted(assumptions) {
            let (symbol, formal, body) = (sub.symbol, sub.formal, sub.body);
            if self.fields.is_some() && self.decls.varies(symbol) {
                self.defined_fields.insert(
                    symbol.to_owned(),
                    (formal.to_vec(), body.clone(), n.to_vec()),
                );
                continue;
            }
            let t = walk::in_formal_order(&mut &*self, body, formal, n)?;
            self.symbols.insert(symbol.to_owned(), t);
            self.memo.borrow_mut().clear();
        }
        Ok(())
    }
}

/// Index values with the left and right components there.
pub type ComponentPair = (Vec<usize>, f64, f64);

/// The component pairs of two labelled tensors compared under the reading "for every
/// value of every free index of either side": (letters, their values, left, right).
pub fn component_pairs(
    dim: usize,
    left: &Labeled<f64>,
    right: &Labeled<f64>,
) -> (Vec<char>, Vec<ComponentPair>) {
    let ((la, ta), (lb, tb)) = (left, right);
    let mut labels: Vec<char> = la.iter().chain(lb).copied().collect();
    labels.sort_unstable();
    labels.dedup();
    let pairs = assignments(dim, labels.len())
        .map(|a| {
            let pick = |ls: &[char], t: &Tensor<f64>| {
                let idx: Vec<usize> = ls
                    .iter()
                    .map(|c| a[labels.iter().position(|x| x == c).unwrap_or(0)])
                    .collect();
                *t.get(&idx)
            };
            let (l, r) = (pick(la, ta), pick(lb, tb));
            (a, l, r)
        })
        .collect();
    (labels, pairs)
}

/// Golden-section search for the maximum of `f` on [c − h, c + h]: the maximiser and
/// the value (never below f(c)).
pub(crate) fn golden_max(
    f: &dyn Fn(f64) -> Result<f64, RealError>,
    c: f64,
    h: f64,
) -> Result<(f64, f64), RealError> {
    let g = (5f64.sqrt() - 1.0) / 2.0;
    let (mut lo, mut hi) = (c - h, c + h);
    let (mut x1, mut x2) = (hi - g * (hi - lo), lo + g * (hi - lo));
    let (mut f1, mut f2) = (f(x1)?, f(x2)?);
    while hi - lo > 1e-12 {
        if f1 < f2 {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + g * (hi - lo);
            f2 = f(x2)?;
        } else {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - g * (hi - lo);
            f1 = f(x1)?;
        }
    }
    let mid = (lo + hi) / 2.0;
    let fm = f(mid)?;
    let fc = f(c)?;
    Ok(if fm >= fc { (mid, fm) } else { (c, fc) })
}

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

    fn normal(&mut self, n: &[f64]) -> Tensor<T> {
        Tensor::from_fn(self.decls.dim, 1, |i| T::from(n[i[0]]))
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
        elementary(f, x).map_err(|m| undefined(node.span, m))
    }

    fn apply2(&mut self, f: Func2, x: T, y: T, node: &Node) -> Result<T, RealError> {
        elementary2(f, x, y).map_err(|m| undefined(node.span, m))
    }

    fn pi(&mut self, _node: &Node) -> Result<T, RealError> {
        Ok(T::from(std::f64::consts::PI))
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

    /// Central differences of `a`'s values at positions moved along each coordinate
    /// (see [`super::taylor`]): only where the fields are explicit functions.
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
            let along =
                env.difference_along(k, crate::strategy::tolerance::TAYLOR_STEP, &mut |env| {
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
    /// derivative at the state (see [`crate::lang::NodeKind::Wrt`]). The values
    /// enter as real parts, so this is a first derivative only: the reader refuses a
    /// gradient inside a function that a `gradient` or `convex` claim differentiates
    /// again, and a gradient inside a gradient.
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
            return Err(err(node, "a gradient inside grad(…) is not supported"));
        }
        let Some(wrt) = self.symbols.get(symbol) else {
            return Err(err(node, format!("`{symbol}` has no value here")));
        };
        let size = wrt.components().len();
        let lift = |x: &T| DualDVec64::from_re(x.re());
        let mut symbols: HashMap<String, Tensor<DualDVec64>> = self
            .symbols
            .iter()
            .map(|(k, t)| (k.clone(), t.map(lift)))
            .collect();
        let mut k = 0;
        let seeded = wrt.map(|x| {
            let mut v = lift(x);
            v.eps = Derivative::derivative_generic(Dyn(size), U1, k);
            k += 1;
            v
        });
        symbols.insert(symbol.to_owned(), seeded);
        let mut inner = RealEnv::new(self.decls, self.defs, symbols);
        inner.quadrature = Quadrature::new(self.quadrature.level);
        inner.in_gradient = true;
        let (_, value) = inner.eval(body, n)?;
        self.quadrature.absorb(&inner.quadrature);
        let mut values = Vec::with_capacity(value.components().len() * size);
        for c in value.components() {
            let g = c.eps.clone().unwrap_generic(Dyn(size), U1);
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

    fn not_scalar(&mut self, node: &Node) -> RealError {
        err(node, "expected a scalar")
    }

    fn vanishes(&self, det: &T) -> bool {
        det.re() == 0.0
    }

    fn singular(&mut self, node: &Node) -> RealError {
        undefined(node.span, "singular matrix: its determinant is 0 here")
    }
}

/// A scalar function of a number (`f64` or num-dual), or why it is undefined there: the
/// one definition the interpreter and the compiled tapes share.
pub(super) fn elementary<T: DualNum<Primitive = f64>>(f: Func, x: T) -> Result<T, String> {
    let outside = |what: &str| Err(format!("{}(…) of {} ({})", f.name(), what, x.re()));
    Ok(match f {
        Func::Sqrt if x.re() < 0.0 => return outside("a negative number"),
        Func::Sqrt => x.sqrt(),
        Func::Abs => x.abs(),
        Func::Cos => x.cos(),
        Func::Sin => x.sin(),
        Func::Tan => x.tan(),
        Func::Exp => x.exp(),
        Func::Log if x.re() <= 0.0 => return outside("a number that is not positive"),
        Func::Log => x.ln(),
        Func::Atan => x.atan(),
        Func::Asin | Func::Acos if !(-1.0..=1.0).contains(&x.re()) => {
            return outside("a number outside [−1, 1]")
        }
        Func::Asin => x.asin(),
        Func::Acos => x.acos(),
        Func::Avg | Func::MaxN => unreachable!("checked as their own node kinds"),
    })
}

/// A function of two numbers, or why it is undefined there (shared with the tapes).
/// `min` and `max` pick an argument by value, so their derivative is the picked one's.
pub(super) fn elementary2<T: DualNum<Primitive = f64>>(f: Func2, x: T, y: T) -> Result<T, String> {
    Ok(match f {
        Func2::Atan2 => x.atan2(y),
        Func2::Min => {
            if y.re() < x.re() {
                y
            } else {
                x
            }
        }
        Func2::Max => {
            if y.re() > x.re() {
                y
            } else {
                x
            }
        }
        Func2::Pow if x.re() > 0.0 => x.powd(y),
        Func2::Pow if x.re() == 0.0 && y.re() > 0.0 => x * T::zero(),
        Func2::Pow => {
            return Err(format!(
                "{}^({}): a real power needs a positive base",
                x.re(),
                y.re()
            ))
        }
    })
}
