//! Evaluation of checked expressions over the reals, generic over the scalar: `f64`
//! for sampling, and num-dual numbers (`DualDVec64`, `Dual2DVec64`, …) for gradients
//! and Hessians. It shares only the parser and validator with the exact route, and
//! has its own contraction code: a shared bug would make both routes agree on a wrong
//! answer.
//!
//! `avg(…)` re-evaluates its argument at the nodes of a quadrature rule exact for its
//! degree in n (see [`super::float::sphere_rule_exact_to`]), or, when the argument is
//! not a polynomial in n, by adaptive quadrature with an error estimate (see
//! [`super::quadrature`]); `maxn(…)` maximises over the normal's angle in the
//! plane by a dense grid refined by golden-section search (see [`MAXN_GRID`]).

use super::assume::Parametrisation;
use super::quadrature::{Level, Quadrature};
use crate::derivation::{Assumption, AssumptionKind, Definition};
use crate::kernel::einsum::{Plain, Slot};
use crate::kernel::{assignments, Tensor};
use crate::lang::parser::Func;
use crate::lang::{Decls, Node, NodeKind, Span, Target};
use num_dual::DualNum;
use std::cell::RefCell;
use std::collections::HashMap;
use std::rc::Rc;

/// Grid points of `maxn` over [0, 2π) before golden-section refinement of every local
/// maximum of the grid. For a function whose peaks are wider than two grid steps (a
/// trigonometric polynomial of degree ≤ 4 in the angle, or its absolute value, as
/// here: peaks at least 2π/8 wide), each peak contains a grid local maximum, and the
/// refinement converges to 1e-12 in angle, so the maximum is found to rounding.
pub const MAXN_GRID: usize = 360;

/// An evaluation error located in the expression's text.
#[derive(Clone, Debug, PartialEq)]
pub struct RealError {
    pub span: Span,
    pub message: String,
}

fn err(node: &Node, message: impl Into<String>) -> RealError {
    RealError {
        span: node.span,
        message: message.into(),
    }
}

/// Free-index labels (sorted) and the tensor.
pub type Labeled<T> = (Vec<char>, Tensor<T>);

/// Quadrature nodes and weights.
type Rule = Vec<(Vec<f64>, f64)>;

/// Memoised definition values, keyed by name and (for definitions that depend on the
/// normal) the normal's bits.
type Memo<T> = HashMap<(String, Vec<u64>), Labeled<T>>;

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
}

impl<'a, T: DualNum<Primitive = f64>> RealEnv<'a, T> {
    pub fn new(
        decls: &'a Decls,
        defs: &'a [Definition],
        symbols: HashMap<String, Tensor<T>>,
    ) -> Self {
        RealEnv {
            decls,
            defs,
            symbols,
            memo: RefCell::new(HashMap::new()),
            degrees: RefCell::new(HashMap::new()),
            rules: RefCell::new(HashMap::new()),
            quadrature: Quadrature::new(Level::Fine),
        }
    }

    fn def(&self, name: &str) -> Option<&'a Definition> {
        self.defs.iter().rev().find(|x| x.sig.name == name)
    }

    /// An upper bound on the degree of `node` as a polynomial in the normal (outside
    /// `avg` and `maxn`, which remove it); `None` when it is not a polynomial in n.
    pub fn normal_degree(&self, node: &Node) -> Option<usize> {
        match &node.kind {
            NodeKind::Const(_) | NodeKind::Avg(_) | NodeKind::MaxN(_) => Some(0),
            NodeKind::Leaf { target, .. } => match target {
                Target::Normal => Some(1),
                Target::Def(name) => {
                    let known = self.degrees.borrow().get(name).copied();
                    if let Some(d) = known {
                        return d;
                    }
                    let d = self.def(name).and_then(|def| self.normal_degree(&def.body));
                    self.degrees.borrow_mut().insert(name.clone(), d);
                    d
                }
                _ => Some(0),
            },
            NodeKind::Neg(a) => self.normal_degree(a),
            NodeKind::Sum(xs) => xs
                .iter()
                .try_fold(0, |m, x| Some(m.max(self.normal_degree(x)?))),
            NodeKind::Product(xs) => xs
                .iter()
                .try_fold(0, |m, x| Some(m + self.normal_degree(x)?)),
            NodeKind::Div(a, b) => match self.normal_degree(b)? {
                0 => self.normal_degree(a),
                _ => None,
            },
            NodeKind::Pow(a, k) => Some(self.normal_degree(a)? * *k as usize),
            NodeKind::Apply(_, a) => match self.normal_degree(a)? {
                0 => Some(0),
                _ => None,
            },
        }
    }

    /// The averaging rule for an argument of this degree in n.
    fn rule(&self, degree: usize) -> Rc<Rule> {
        let degree = degree.clamp(1, 40);
        self.rules
            .borrow_mut()
            .entry(degree)
            .or_insert_with(|| Rc::new(super::float::rule_for(self.decls, degree)))
            .clone()
    }

    /// Evaluates `node` with the normal `n` (used outside `avg`/`maxn`).
    pub fn eval(&self, node: &Node, n: &[f64]) -> Result<Labeled<T>, RealError> {
        let d = self.decls.dim;
        let labels = node.free_letters();
        let scalar = |x: T| (vec![], Tensor::scalar(d, x));
        Ok(match &node.kind {
            NodeKind::Const(q) => scalar(T::from(q.to_f64())),
            NodeKind::Leaf { target, slots } => {
                let base = match target {
                    Target::Delta => Tensor::delta(d),
                    Target::Eps => Tensor::levi_civita(d),
                    Target::Normal => Tensor::from_fn(d, 1, |i| T::from(n[i[0]])),
                    Target::Symbol(s) => self
                        .symbols
                        .get(s)
                        .cloned()
                        .ok_or_else(|| err(node, format!("no value for symbol {s}")))?,
                    Target::Def(name) => {
                        let def = self
                            .def(name)
                            .ok_or_else(|| err(node, format!("definition {name} not in scope")))?;
                        // Definitions that do not involve the normal are the same for every n.
                        let key_n = if self.normal_degree(&def.body) == Some(0) {
                            Vec::new()
                        } else {
                            n.iter().map(|x| x.to_bits()).collect()
                        };
                        let key = (name.clone(), key_n);
                        let cached = self.memo.borrow().get(&key).map(|(_, t)| t.clone());
                        if let Some(t) = cached {
                            t
                        } else {
                            let (ls, t) = self.eval(&def.body, n)?;
                            let perm: Vec<usize> = def
                                .sig
                                .formal
                                .iter()
                                .map(|c| ls.iter().position(|x| x == c).unwrap_or(0))
                                .collect();
                            let t = t.permuted(&perm);
                            let mut memo = self.memo.borrow_mut();
                            if memo.len() > MEMO_LIMIT {
                                memo.clear();
                            }
                            memo.insert(key, (def.sig.formal.clone(), t.clone()));
                            t
                        }
                    }
                };
                let t = Plain::einsum(d, &[(&base, slots.clone())], &labels);
                (labels, t)
            }
            NodeKind::Neg(a) => {
                let (ls, t) = self.eval(a, n)?;
                (ls, t.map(|x| -x.clone()))
            }
            NodeKind::Sum(terms) => {
                let mut acc: Option<Labeled<T>> = None;
                for t in terms {
                    let (ls, v) = self.eval(t, n)?;
                    acc = Some(match acc {
                        None => (ls, v),
                        Some((ls, a)) => (ls, a.add(&v)),
                    });
                }
                acc.ok_or_else(|| err(node, "empty sum"))?
            }
            NodeKind::Product(fs) => {
                let vals = fs
                    .iter()
                    .map(|f| self.eval(f, n))
                    .collect::<Result<Vec<_>, _>>()?;
                let slots: Vec<(&Tensor<T>, Vec<Slot>)> = vals
                    .iter()
                    .map(|(ls, t)| (t, ls.iter().map(|&c| Slot::Letter(c)).collect()))
                    .collect();
                let t = Plain::einsum(d, &slots, &labels);
                (labels, t)
            }
            NodeKind::Div(a, b) => {
                let (ls, t) = self.eval(a, n)?;
                let den = self.scalar(b, n)?;
                if den.re() == 0.0 {
                    return Err(err(b, "division by zero"));
                }
                (ls, t.map(|x| x.clone() / den.clone()))
            }
            NodeKind::Pow(a, k) => scalar(self.scalar(a, n)?.powi(*k as i32)),
            NodeKind::Apply(func, a) => {
                let x = self.scalar(a, n)?;
                scalar(match func {
                    Func::Sqrt => {
                        if x.re() < 0.0 {
                            return Err(err(
                                node,
                                format!("sqrt of a negative number ({})", x.re()),
                            ));
                        }
                        x.sqrt()
                    }
                    Func::Abs => x.abs(),
                    Func::Cos => x.cos(),
                    Func::Sin => x.sin(),
                    Func::Tan => x.tan(),
                    Func::Avg | Func::MaxN => unreachable!("checked as their own node kinds"),
                })
            }
            NodeKind::Avg(a) => {
                let Some(degree) = self.normal_degree(a) else {
                    // Not a polynomial in n: adaptive quadrature with an error estimate.
                    let free = if self.decls.normal_in_plane { 2 } else { d };
                    let value = self.quadrature.average(free, d, &mut |point| {
                        Ok(self.eval(a, point)?.1.components().to_vec())
                    })?;
                    let mut it = value.into_iter();
                    let t = Tensor::from_fn(d, labels.len(), |_| it.next().expect("one each"));
                    return Ok((labels, t));
                };
                let mut acc: Option<Labeled<T>> = None;
                for (point, w) in self.rule(degree).iter() {
                    let (ls, t) = self.eval(a, point)?;
                    let t = t.map(|x| x.clone() * *w);
                    acc = Some(match acc {
                        None => (ls, t),
                        Some((ls, s)) => (ls, s.add(&t)),
                    });
                }
                acc.ok_or_else(|| err(node, "empty quadrature rule"))?
            }
            NodeKind::MaxN(a) => scalar(self.max_over_angle(node, a)?),
        })
    }

    fn scalar(&self, node: &Node, n: &[f64]) -> Result<T, RealError> {
        self.eval(node, n)?
            .1
            .into_scalar()
            .ok_or_else(|| err(node, "expected a scalar"))
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
        let f = |theta: f64| -> Result<f64, RealError> { Ok(self.scalar(a, &at(theta))?.re()) };
        let h = 2.0 * std::f64::consts::PI / MAXN_GRID as f64;
        let mut grid = Vec::with_capacity(MAXN_GRID);
        for k in 0..MAXN_GRID {
            let v = f(k as f64 * h)?;
            if !v.is_finite() {
                return Err(err(node, "maxn(…): the argument is not finite"));
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
        self.scalar(a, &at(best.0))
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
        for ((symbol, idx), terms, constant) in parametrisation.dependents() {
            let value = terms
                .iter()
                .fold(T::from(constant.to_f64()), |acc, ((s, i), q)| {
                    let x = self
                        .symbols
                        .get(s)
                        .map_or_else(|| T::from(f64::NAN), |t| t.get(i).clone());
                    acc + x * q.to_f64()
                });
            if let Some(t) = self.symbols.get_mut(symbol) {
                *t.get_mut(idx) = value;
            }
        }
        for &k in parametrisation.substitutions() {
            let AssumptionKind::Equals {
                symbol,
                formal,
                body,
            } = &assumptions[k].kind
            else {
                unreachable!("substitutions are equations")
            };
            let (ls, t) = self.eval(body, n)?;
            let perm: Vec<usize> = formal
                .iter()
                .map(|c| ls.iter().position(|x| x == c).unwrap_or(0))
                .collect();
            self.symbols.insert(symbol.clone(), t.permuted(&perm));
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
