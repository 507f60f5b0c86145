//! The real evaluation environment of one claim: symbols, fields and definitions
//! over a scalar `T` (`f64` or num-dual), and its errors.

use super::elementary::golden_max;
use super::error::{err, maxn_not_differentiated, undefined, RealError};
use crate::algebra::{assignments, Tensor};
use crate::derivation::parametrisation::{product_value, Component, Parametrisation};
use crate::derivation::{Assumption, Definition};
use crate::eval::quadrature::{Level, Quadrature};
use crate::eval::taylor::{self, TaylorFields};
use crate::eval::walk;
use crate::lang::{Decls, Node};
use num_dual::DualNum;
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

pub use crate::eval::labeled::Labeled;

/// Quadrature nodes and weights.
pub(super) type Rule = Vec<(Vec<f64>, f64)>;

/// Memoised definition values, keyed by name and (for definitions that depend on the
/// normal) the normal's bits.
pub(super) type Memo<T> = HashMap<(String, Vec<u64>), Tensor<T>>;

/// Entries kept before the memo is cleared (a `maxn` visits hundreds of normals).
pub(super) const MEMO_LIMIT: usize = 4096;

/// The values of one sample: every symbol's components, with caches for definition
/// values, their degree in the normal, and quadrature rules.
pub struct RealEnv<'a, T> {
    pub decls: &'a Decls,
    pub defs: &'a [Definition],
    pub symbols: HashMap<String, Tensor<T>>,
    pub(super) memo: RefCell<Memo<T>>,
    pub(super) degrees: RefCell<HashMap<String, Option<usize>>>,
    pub(super) rules: RefCell<HashMap<usize, Rc<Rule>>>,
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
    pub(super) epoch: Cell<u64>,
    /// How many central differences are nested now ([`MAX_NESTED_DIFFERENCES`]).
    pub(super) differences: Cell<usize>,
    /// Fields that an assumption defines by an expression (`u_i = A_ij x_j`), with
    /// fields in use: evaluated from that expression wherever the position is.
    pub(super) defined_fields: HashMap<String, (Vec<char>, Node, Vec<f64>)>,
    /// This environment evaluates the body of a `grad(…)`: its values are dual
    /// numbers seeded from real ones.
    pub(super) in_gradient: bool,
    /// How a `grad(…)` inside that body is taken (second derivatives, through the
    /// values' second dual part); `None`: it is refused.
    pub(super) nested: Option<NestedGradient<'a, T>>,
}

/// A `grad(…)` taken inside the body of another: see [`super::ring`].
pub(super) type NestedGradient<'a, T> =
    fn(&RealEnv<'a, T>, &Node, &str, &Node, &[f64]) -> Result<Tensor<T>, RealError>;

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
            nested: None,
        }
    }

    /// Sets (or, with `None`, removes) the perturbation of a field component.
    pub(crate) fn perturb(&self, p: Option<Perturbation>) {
        *self.perturbation.borrow_mut() = p;
        self.epoch.set(self.epoch.get() + 1);
    }

    /// `t`, the value of `name` at `x`, plus the perturbation when it is of `name`.
    pub(super) fn perturbed(&self, name: &str, mut t: Tensor<T>, x: &[f64]) -> Tensor<T> {
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
    pub(crate) fn difference_along(
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
    pub(crate) fn defines(&self, field: &str) -> bool {
        self.defined_fields.contains_key(field)
    }

    /// Evaluates fields as the given Taylor polynomials, at their centre.
    pub fn with_fields(mut self, fields: TaylorFields) -> Self {
        *self.position.borrow_mut() = fields.centre.clone();
        self.fields = Some(fields);
        self
    }

    pub(super) fn def(&self, name: &str) -> Option<&'a Definition> {
        self.defs.iter().rev().find(|x| x.sig.name == name)
    }

    /// The degree in n of `node` (see [`walk::normal_degree`]).
    pub fn normal_degree(&self, node: &Node) -> Option<usize> {
        walk::normal_degree(node, self.defs, &mut self.degrees.borrow_mut())
    }

    /// The averaging rule for an argument of this degree in n.
    pub(super) fn rule(&self, degree: usize) -> Rc<Rule> {
        let degree = degree.clamp(1, 40);
        self.rules
            .borrow_mut()
            .entry(degree)
            .or_insert_with(|| Rc::new(crate::eval::quadrature::rule_for(self.decls, degree)))
            .clone()
    }

    /// Evaluates `node` with the normal `n` (used outside `avg`/`maxn`).
    pub fn eval(&self, node: &Node, n: &[f64]) -> Result<Labeled<T>, RealError> {
        Ok(Labeled::new(
            node.free_letters(),
            walk::walk(&mut &*self, node, n)?,
        ))
    }

    /// max over θ of `a` at n = (cos θ, sin θ[, 0]): grid, then golden section around
    /// the best grid point; the value is `a` evaluated at the maximiser. Refused for
    /// dual numbers ([`maxn_not_differentiated`]): the maximiser is found to about 1e-8
    /// and moves with what is differentiated.
    pub(super) fn max_over_angle(&self, node: &Node, a: &Node) -> Result<T, RealError> {
        if T::NDERIV > 0 {
            return Err(maxn_not_differentiated(node.span));
        }
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
        // A component solved for by a polynomial constraint: the real root of its power
        // on the branch its drawn value's sign picks (NaN where there is none).
        for s in parametrisation.solved() {
            let at = |(s, i): &Component| {
                self.symbols
                    .get(s)
                    .map_or_else(|| T::from(f64::NAN), |t| t.get(i).clone())
            };
            let value = s.value.iter().fold(T::from(0.0), |acc, (p, q)| {
                acc + product_value(p, T::from(1.0), at) * q.to_f64()
            });
            let (symbol, idx) = &s.component;
            if let Some(t) = self.symbols.get_mut(symbol) {
                let x = t.get_mut(idx);
                *x = real_root(value, s.power, x.re() < 0.0);
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

/// The real x with x^power = value, negative when `negative` and the power is even; NaN
/// when an even power would need a negative value.
pub(crate) fn real_root<T: DualNum<Primitive = f64>>(value: T, power: u32, negative: bool) -> T {
    let root = match power {
        0 => return T::from(f64::NAN),
        1 => return value,
        // The root of |value| carries the derivative of the root of value.
        _ if power % 2 == 1 && value.re() < 0.0 => -(-value).powf(1.0 / f64::from(power)),
        _ if value.re() < 0.0 => return T::from(f64::NAN),
        2 => value.sqrt(),
        _ => value.powf(1.0 / f64::from(power)),
    };
    // A zero root is +0: a −0 would pick the other branch of atan2 and its kind.
    if negative && power.is_multiple_of(2) && root.re() != 0.0 {
        -root
    } else {
        root
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
    let (la, ta, lb, tb) = (&left.labels, &left.tensor, &right.labels, &right.tensor);
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

/// A perturbation of one field component: `amount · Π (x_k − centre_k)^e_k / e_k!`.
#[derive(Clone, Debug)]
pub struct Perturbation {
    pub field: String,
    pub idx: Vec<usize>,
    pub exponents: Vec<u32>,
    pub centre: Vec<f64>,
    pub amount: f64,
}

impl Perturbation {
    /// Its value at `x`.
    pub fn at(&self, x: &[f64]) -> f64 {
        self.exponents.iter().zip(x.iter().zip(&self.centre)).fold(
            self.amount,
            |acc, (&e, (xi, ci))| {
                acc * (xi - ci).powi(e as i32) / (1..=e).map(f64::from).product::<f64>()
            },
        )
    }
}
