//! Interval arithmetic: the sides of a sampled statement enclosed, at one state, in
//! intervals that contain their exact values. It tells a violation from rounding.
//!
//! Floating point loses digits where a side cancels: `(1 − cos x)/x²` at x = 10⁻⁶ is
//! 0.49999… in `f64` with five digits wrong, and `(x − sin x)/x³` is worse. Two such
//! sides differ far beyond any relative tolerance although they are equal. Every value
//! here is an interval [lo, hi] that contains the exact value of the expression at the
//! state. Where the sides' intervals admit the relation, floating point cannot tell
//! whether it holds at that state: the state is no violation, and no evidence that the
//! claim holds either (a sampled claim with such states is undecided unless a violation
//! is confirmed elsewhere). A violation is confirmed where the intervals exclude it.
//!
//! Each operation rounds outward: `+ − × ÷` and `sqrt` are correctly rounded in IEEE
//! arithmetic, so one step to the next `f64` on each side encloses the exact result; the
//! other elementary functions come from the platform's libm, accurate to within one unit
//! in the last place on the platforms we build for, and are widened by [`LIBM_ULPS`].
//! Where an interval cannot decide a question of the domain (a divisor whose interval
//! contains 0, a square root of an interval reaching below 0), the enclosure is taken
//! on the domain (every real, or the root of the part at or above 0) and the evaluation
//! records that it **assumed** the state to lie in the domain: its enclosures then hold
//! only if the sides have a value at the exact state. That is enough to dismiss a
//! violation (at a state outside the domain there is no violation either), never to
//! confirm one. A construct that has no enclosure here (averages of a non-polynomial in
//! n, derivatives, variations, gradients) stops the evaluation with
//! an [`Enclosure`] error, and the caller keeps its floating-point judgement. An average
//! of a polynomial in n (by its rule at rounded nodes) and `maxn` (by the grid and golden
//! sections of the interpreter) are evaluated loosely: they may dismiss a violation as
//! rounding, never confirm one.

use super::labeled::Labeled;
use super::state::State;
use super::walk::{self, Derivative, DynCalculus, Normals, Ring};
use crate::algebra::einsum::Arithmetic;
use crate::algebra::Tensor;
use crate::derivation::parametrisation::{product_value, Parametrisation};
use crate::derivation::{Assumption, Definition, Relation};
use crate::kernel::Rational;
use crate::lang::parser::{Func, Func2};
use crate::lang::{Decls, Node};
use crate::tolerance::TRIG_REDUCTION;
use rustc_hash::FxHashMap as HashMap;
use std::cell::{Cell, RefCell};
use std::f64::consts::PI;

/// Units in the last place by which a libm result is widened on each side.
pub const LIBM_ULPS: u32 = 2;

/// How far from π/2 + kπ computed in `f64` the exact point may lie, at `p` with
/// |k| ≤ 10⁶: a few units in the last place of p, and k rounding errors of π.
fn slack(p: f64) -> f64 {
    1e-15 * (1.0 + p.abs())
}

/// A closed interval [lo, hi] of reals; infinite ends allowed, never NaN.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interval {
    pub lo: f64,
    pub hi: f64,
}

/// Why an enclosure was not computed: a construct this evaluation does not enclose.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("no enclosure: {0}")]
pub struct Enclosure(pub String);

pub(crate) type R<T> = Result<T, Enclosure>;

/// An enclosure valid on the function's domain, and whether it needed the assumption
/// that the exact argument lies there (rounding alone could not decide it).
type OnDomain = (Interval, bool);

fn sure(x: Interval) -> OnDomain {
    (x, false)
}

fn down(x: f64, ulps: u32) -> f64 {
    (0..ulps).fold(x, |x, _| x.next_down())
}

fn up(x: f64, ulps: u32) -> f64 {
    (0..ulps).fold(x, |x, _| x.next_up())
}

impl Interval {
    /// The number `x` itself (every `f64` is exact).
    pub fn point(x: f64) -> Self {
        Interval::new(x, x, 0)
    }

    /// Every real.
    pub fn entire() -> Self {
        Interval {
            lo: f64::NEG_INFINITY,
            hi: f64::INFINITY,
        }
    }

    /// [lo, hi] widened by `ulps` on each side; a NaN end makes it the whole line.
    fn new(lo: f64, hi: f64, ulps: u32) -> Self {
        if lo.is_nan() || hi.is_nan() {
            return Interval::entire();
        }
        Interval {
            lo: down(lo, ulps),
            hi: up(hi, ulps),
        }
    }

    /// The hull of finitely many rounded values, widened by `ulps`.
    fn hull(values: &[f64], ulps: u32) -> Self {
        let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        if values.iter().any(|x| x.is_nan()) {
            return Interval::entire();
        }
        Interval::new(lo, hi, ulps)
    }

    pub fn contains_zero(&self) -> bool {
        self.lo <= 0.0 && 0.0 <= self.hi
    }

    fn neg(self) -> Self {
        Interval {
            lo: -self.hi,
            hi: -self.lo,
        }
    }

    /// Whether this is the number 0 exactly (a component an assumption sets to 0).
    fn is_zero(&self) -> bool {
        self.lo == 0.0 && self.hi == 0.0
    }

    fn add(self, b: Self) -> Self {
        // Adding an exact 0 is exact: no widening, so a component set to 0 stays 0.
        if b.is_zero() {
            return self;
        }
        if self.is_zero() {
            return b;
        }
        Interval::new(self.lo + b.lo, self.hi + b.hi, 1)
    }

    fn mul(self, b: Self) -> Self {
        // 0 times any real is 0 exactly (the ends of an unbounded interval are no values).
        if self.is_zero() || b.is_zero() {
            return Interval::point(0.0);
        }
        if b == Interval::point(1.0) {
            return self;
        }
        if self == Interval::point(1.0) {
            return b;
        }
        Interval::hull(
            &[
                self.lo * b.lo,
                self.lo * b.hi,
                self.hi * b.lo,
                self.hi * b.hi,
            ],
            1,
        )
    }

    /// On the domain (a divisor that is not 0) a quotient by an interval containing 0
    /// can be any real.
    fn div(self, b: Self) -> OnDomain {
        if b.contains_zero() {
            return (Interval::entire(), true);
        }
        sure(Interval::hull(
            &[
                self.lo / b.lo,
                self.lo / b.hi,
                self.hi / b.lo,
                self.hi / b.hi,
            ],
            1,
        ))
    }

    /// |x| as an interval.
    fn abs(self) -> Self {
        if self.lo >= 0.0 {
            self
        } else if self.hi <= 0.0 {
            self.neg()
        } else {
            Interval {
                lo: 0.0,
                hi: self.hi.max(-self.lo),
            }
        }
    }

    /// x^k by squaring, each product rounded outward; an even power is taken of |x|,
    /// so that it is never negative.
    fn powi(self, k: u32) -> Self {
        let base = if k.is_multiple_of(2) {
            self.abs()
        } else {
            self
        };
        let (mut acc, mut b, mut e) = (Interval::point(1.0), base, k);
        while e > 0 {
            if e & 1 == 1 {
                acc = acc.mul(b);
            }
            e >>= 1;
            if e > 0 {
                b = b.mul(b);
                if b.lo < 0.0 && base.lo >= 0.0 {
                    b.lo = 0.0;
                }
            }
        }
        if k.is_multiple_of(2) && acc.lo < 0.0 {
            acc.lo = 0.0;
        }
        acc
    }

    /// A function increasing on the interval, from libm.
    fn increasing(self, f: fn(f64) -> f64) -> Self {
        Interval::new(f(self.lo), f(self.hi), LIBM_ULPS)
    }

    fn sqrt(self) -> OnDomain {
        let assumed = self.lo < 0.0;
        // IEEE square roots are correctly rounded; on the domain the argument is ≥ 0.
        let mut root = Interval::new(self.lo.max(0.0).sqrt(), self.hi.max(0.0).sqrt(), 1);
        root.lo = root.lo.max(0.0);
        (root, assumed)
    }

    fn exp(self) -> Self {
        let mut e = self.increasing(f64::exp);
        e.lo = e.lo.max(0.0);
        e
    }

    fn log(self) -> OnDomain {
        if self.lo <= 0.0 {
            let hi = if self.hi > 0.0 {
                up(self.hi.ln(), LIBM_ULPS)
            } else {
                f64::INFINITY
            };
            return (
                Interval {
                    lo: f64::NEG_INFINITY,
                    hi,
                },
                true,
            );
        }
        sure(self.increasing(f64::ln))
    }

    /// sin on the interval: the values at the ends, and ±1 wherever an extremum
    /// π/2 + kπ may lie inside (decided generously: including one too many only widens).
    fn sin(self) -> Self {
        self.periodic(f64::sin, PI / 2.0)
    }

    /// cos: its maxima lie at 2kπ, its minima at π + 2kπ.
    fn cos(self) -> Self {
        self.periodic(f64::cos, 0.0)
    }

    /// `f` of period 2π with its maximum 1 at `peak` + 2kπ and minimum −1 half a period
    /// later.
    fn periodic(self, f: fn(f64) -> f64, peak: f64) -> Self {
        let whole = Interval { lo: -1.0, hi: 1.0 };
        if !(self.lo.is_finite() && self.hi.is_finite()) {
            return whole;
        }
        // At one number libm's value is accurate whatever its size (its argument
        // reduction is exact).
        if self.lo == self.hi {
            let e = Interval::new(f(self.lo), f(self.lo), LIBM_ULPS);
            return Interval {
                lo: e.lo.max(-1.0),
                hi: e.hi.min(1.0),
            };
        }
        if self.lo.abs().max(self.hi.abs()) > TRIG_REDUCTION || self.hi - self.lo >= 2.0 * PI {
            return whole;
        }
        let mut e = Interval::hull(&[f(self.lo), f(self.hi)], LIBM_ULPS);
        let inside = |at: f64| {
            let k0 = ((self.lo - at) / (2.0 * PI)).floor() - 1.0;
            (0..4).any(|j| {
                let p = at + (k0 + j as f64) * 2.0 * PI;
                p >= self.lo - slack(p) && p <= self.hi + slack(p)
            })
        };
        if inside(peak) {
            e.hi = 1.0;
        }
        if inside(peak + PI) {
            e.lo = -1.0;
        }
        Interval {
            lo: e.lo.max(-1.0),
            hi: e.hi.min(1.0),
        }
    }

    fn tan(self) -> OnDomain {
        if !(self.lo.is_finite() && self.hi.is_finite())
            || self.lo.abs().max(self.hi.abs()) > TRIG_REDUCTION
        {
            return (Interval::entire(), true);
        }
        // A pole π/2 + kπ inside (generously) leaves no enclosure.
        let k0 = ((self.lo - PI / 2.0) / PI).floor() - 1.0;
        let pole = (0..4).any(|j| {
            let p = PI / 2.0 + (k0 + j as f64) * PI;
            p >= self.lo - slack(p) && p <= self.hi + slack(p)
        });
        if pole {
            return (Interval::entire(), true);
        }
        sure(self.increasing(f64::tan))
    }

    /// The part of the interval inside [−1, 1] (the domain of asin and acos), and
    /// whether anything was cut off.
    fn in_unit(self) -> OnDomain {
        let cut = Interval {
            lo: self.lo.max(-1.0),
            hi: self.hi.min(1.0),
        };
        if cut.lo > cut.hi {
            // Nothing of the domain is left: any value (the state is outside it).
            return (Interval::entire(), true);
        }
        (cut, cut != self)
    }

    fn min(self, b: Self) -> Self {
        Interval {
            lo: self.lo.min(b.lo),
            hi: self.hi.min(b.hi),
        }
    }

    fn max(self, b: Self) -> Self {
        Interval {
            lo: self.lo.max(b.lo),
            hi: self.hi.max(b.hi),
        }
    }

    /// atan2(y = self, x): its range over a box that contains neither the origin nor a
    /// point of the branch cut (x < 0, y = 0) is attained at the box's corners; a box
    /// that meets them gets the whole range [−π, π].
    fn atan2(self, x: Self) -> Self {
        // On the cut itself the value is the branch's: atan2(0, x) is 0 for x > 0 and π
        // for x < 0 (as libm gives it for +0).
        if self == Interval::point(0.0) && x.lo > 0.0 {
            return self;
        }
        if self == Interval::point(0.0) && x.hi < 0.0 {
            return Interval::new(PI, PI, 1);
        }
        if self.contains_zero() && x.lo <= 0.0 {
            return Interval::new(-PI, PI, 1);
        }
        Interval::hull(
            &[
                self.lo.atan2(x.lo),
                self.lo.atan2(x.hi),
                self.hi.atan2(x.lo),
                self.hi.atan2(x.hi),
            ],
            LIBM_ULPS,
        )
    }

    /// x^y for x > 0, as exp(y log x); 0^y for y > 0 is 0.
    fn pow(self, y: Self) -> OnDomain {
        if self == Interval::point(0.0) && y.lo > 0.0 {
            return sure(self);
        }
        // exp(…) ≥ 0, so the enclosure also contains 0^y = 0 for y > 0.
        let (log, assumed) = self.log();
        (log.mul(y).exp(), assumed)
    }

    /// Whether the exact values enclosed in `self` (left) and `right` may satisfy
    /// `relation`.
    pub fn may_satisfy(&self, relation: Relation, right: &Interval) -> bool {
        let below = Relation::Le.holds(&self.lo, &right.hi);
        let above = Relation::Ge.holds(&self.hi, &right.lo);
        match relation {
            Relation::Eq => below && above,
            Relation::Le => below,
            Relation::Ge => above,
        }
    }
}

/// The statement's values at one state, in intervals.
pub struct IntervalEnv<'a> {
    decls: &'a Decls,
    defs: &'a [Definition],
    symbols: HashMap<String, Tensor<Interval>>,
    memo: RefCell<HashMap<String, Tensor<Interval>>>,
    /// The state's normal (nothing here changes it: averages and `maxn` are not
    /// enclosed).
    n: Vec<f64>,
    /// Whether some value is loose: an enclosure that holds only on the domain (see the
    /// module doc), or an average by a rule with rounded nodes. A loose evaluation can
    /// dismiss a violation, never confirm one.
    loose: Cell<bool>,
}

impl<'a> IntervalEnv<'a> {
    /// The state's components as exact points, then every component the assumptions
    /// tie to others computed again in intervals (the state's `f64` values of those are
    /// rounded), then the whole-symbol substitutions.
    pub fn at_state(
        decls: &'a Decls,
        defs: &'a [Definition],
        parametrisation: &Parametrisation,
        assumptions: &[Assumption],
        state: &State,
    ) -> R<Self> {
        let symbols = state
            .symbols
            .iter()
            .map(|(k, t)| (k.clone(), t.map(|&x| Interval::point(x))))
            .collect();
        let mut env = IntervalEnv {
            decls,
            defs,
            symbols,
            memo: RefCell::new(HashMap::default()),
            n: state.n.clone(),
            loose: Cell::new(false),
        };
        // A component solved for by a polynomial constraint: the enclosure of its root
        // on the branch of the state's value (the whole line for a power above 2).
        for s in parametrisation.solved() {
            let at = |(s, i): &(String, Vec<usize>)| {
                env.symbols
                    .get(s)
                    .map_or_else(Interval::entire, |t| *t.get(i))
            };
            let value = s.value.iter().fold(Interval::point(0.0), |acc, (p, q)| {
                acc.add(product_value(p, Interval::point(1.0), at).mul(rational(q)))
            });
            let (symbol, idx) = &s.component;
            if let Some(t) = env.symbols.get_mut(symbol) {
                let x = t.get_mut(idx);
                *x = match s.power {
                    1 => value,
                    2 => {
                        let (root, assumed) = value.sqrt();
                        env.loose.set(env.loose.get() || assumed);
                        if x.hi < 0.0 {
                            root.neg()
                        } else {
                            root
                        }
                    }
                    _ => Interval::entire(),
                };
            }
        }
        for d in parametrisation.dependents() {
            let at = |(s, i): &(String, Vec<usize>)| {
                env.symbols
                    .get(s)
                    .map_or_else(Interval::entire, |t| *t.get(i))
            };
            let mut value = rational(d.constant);
            for (c, q) in &d.terms {
                value = value.add(at(c).mul(rational(q)));
            }
            for (p, q) in &d.products {
                let product = product_value(p, Interval::point(1.0), at);
                value = value.add(product.mul(rational(q)));
            }
            let (symbol, idx) = d.component;
            if let Some(t) = env.symbols.get_mut(symbol) {
                *t.get_mut(idx) = value;
            }
        }
        for sub in parametrisation.substituted(assumptions) {
            let n = env.n.clone();
            let t = walk::in_formal_order(&mut &env, sub.body, sub.formal, &n)?;
            env.symbols.insert(sub.symbol.to_owned(), t);
            env.memo.borrow_mut().clear();
        }
        Ok(env)
    }

    /// `node`'s enclosure, labelled by its free letters.
    pub fn eval(&self, node: &Node) -> R<Labeled<Interval>> {
        Ok(Labeled::new(
            node.free_letters(),
            walk::walk(&mut &*self, node, &self.n)?,
        ))
    }

    /// Whether some value so far is loose (see [`IntervalEnv::loose`]).
    pub fn loose(&self) -> bool {
        self.loose.get()
    }

    fn on_domain(&self, (x, assumed): OnDomain) -> Interval {
        if assumed {
            self.loose.set(true);
        }
        x
    }
}

impl std::ops::Mul for Interval {
    type Output = Interval;
    fn mul(self, b: Interval) -> Interval {
        Interval::mul(self, b)
    }
}

/// A rational's enclosure: its nearest `f64`, widened (the conversion need not round
/// to nearest).
fn rational(q: &Rational) -> Interval {
    let x = q.to_f64();
    if q.is_zero() {
        return Interval::point(0.0);
    }
    Interval::new(x, x, 2)
}

fn unsupported<T>(what: &str) -> R<T> {
    Err(Enclosure(format!("{what} has no interval enclosure")))
}

impl Arithmetic for &IntervalEnv<'_> {
    type Value = Interval;
    type Error = Enclosure;
    fn zero(&mut self) -> Interval {
        Interval::point(0.0)
    }

    fn one(&mut self) -> Interval {
        Interval::point(1.0)
    }

    fn mul(&mut self, a: Interval, b: &Interval) -> R<Interval> {
        Ok(a.mul(*b))
    }

    fn add(&mut self, a: Interval, b: Interval) -> R<Interval> {
        Ok(a.add(b))
    }
}

impl Ring for &IntervalEnv<'_> {
    type Normal = [f64];

    fn dim(&self) -> usize {
        self.decls.dim
    }

    fn constant(&mut self, q: &Rational) -> Interval {
        rational(q)
    }

    fn neg(&mut self, x: Interval) -> Interval {
        x.neg()
    }

    fn symbol(&mut self, name: &str, _node: &Node) -> R<Tensor<Interval>> {
        self.symbols
            .get(name)
            .cloned()
            .ok_or_else(|| Enclosure(format!("no value for symbol {name}")))
    }

    fn definition(&mut self, name: &str, _node: &Node, n: &[f64]) -> R<Tensor<Interval>> {
        let env: &IntervalEnv<'_> = self;
        let def = env
            .defs
            .iter()
            .rev()
            .find(|d| d.sig.name == name)
            .ok_or_else(|| Enclosure(format!("definition {name} not in scope")))?;
        let same_normal = n == env.n.as_slice();
        if same_normal {
            if let Some(t) = env.memo.borrow().get(name) {
                return Ok(t.clone());
            }
        }
        let t = walk::in_formal_order(&mut { env }, &def.body, &def.sig.formal, n)?;
        if same_normal {
            env.memo.borrow_mut().insert(name.to_owned(), t.clone());
        }
        Ok(t)
    }

    fn divide(&mut self, x: Interval, den: &Interval, _divisor: &Node) -> R<Interval> {
        Ok(self.on_domain(x.div(*den)))
    }

    fn power(&mut self, x: Interval, k: u32, _node: &Node) -> R<Interval> {
        Ok(x.powi(k))
    }

    fn apply(&mut self, f: Func, x: Interval, _node: &Node) -> R<Interval> {
        Ok(match f {
            Func::Sqrt => self.on_domain(x.sqrt()),
            Func::Abs => x.abs(),
            Func::Cos => x.cos(),
            Func::Sin => x.sin(),
            Func::Tan => self.on_domain(x.tan()),
            Func::Exp => x.exp(),
            Func::Log => self.on_domain(x.log()),
            Func::Atan => x.increasing(f64::atan),
            Func::Asin | Func::Acos => {
                let x = self.on_domain(x.in_unit());
                if !x.lo.is_finite() || !x.hi.is_finite() {
                    Interval::new(-PI, PI, 1)
                } else if f == Func::Asin {
                    x.increasing(f64::asin)
                } else {
                    // Decreasing.
                    Interval::new(x.hi.acos(), x.lo.acos(), LIBM_ULPS)
                }
            }
            Func::Avg | Func::MaxN => unreachable!("checked as their own node kinds"),
        })
    }

    fn apply2(&mut self, f: Func2, x: Interval, y: Interval, _node: &Node) -> R<Interval> {
        Ok(match f {
            Func2::Atan2 => x.atan2(y),
            Func2::Min => x.min(y),
            Func2::Max => x.max(y),
            Func2::Pow => self.on_domain(x.pow(y)),
        })
    }

    fn pi(&mut self, _node: &Node) -> R<Interval> {
        Ok(Interval::new(PI, PI, 1))
    }

    fn not_scalar(&mut self, _node: &Node) -> Enclosure {
        Enclosure("expected a scalar".into())
    }

    /// Only a determinant that is exactly 0 is singular; one whose enclosure merely
    /// contains 0 is divided by, on the domain.
    fn vanishes(&self, det: &Interval) -> bool {
        *det == Interval::point(0.0)
    }

    fn singular(&mut self, _node: &Node) -> Enclosure {
        Enclosure("a singular matrix".into())
    }

    /// Derivatives have no enclosure here.
    fn calculus(&mut self, what: Derivative, _node: &Node) -> R<&mut DynCalculus<'_, Self>> {
        unsupported(&what.to_string())
    }
}

impl Normals for &IntervalEnv<'_> {
    /// The state's normal is a unit vector to rounding: its exact direction n/|n| is
    /// enclosed.
    fn normal(&mut self, n: &[f64]) -> Tensor<Interval> {
        let d = self.decls.dim;
        let norm2 = n
            .iter()
            .map(|&x| Interval::point(x).powi(2))
            .fold(Interval::point(0.0), Interval::add);
        // |n| is about 1: neither the root nor the quotient leaves the domain.
        let enclosed = |x: f64| Interval::point(x).div(norm2.sqrt().0).0;
        Tensor::from_fn(d, 1, |i| enclosed(n.get(i[0]).copied().unwrap_or(0.0)))
    }

    /// A polynomial in n of degree ≤ 40 by the rule exact for its degree, at nodes and
    /// weights rounded to `f64`: close to an enclosure but not one, so the evaluation
    /// becomes loose ([`IntervalEnv::loose`]).
    fn average(&mut self, a: &Node, _node: &Node, _n: &[f64]) -> R<Tensor<Interval>> {
        let env: &IntervalEnv<'_> = self;
        let degree = walk::normal_degree(a, env.defs, &mut HashMap::default())
            .filter(|&d| d <= 40)
            .ok_or_else(|| Enclosure("an average of a non-polynomial in n".into()))?;
        env.loose.set(true);
        let mut acc: Option<Tensor<Interval>> = None;
        for (point, w) in super::quadrature::rule_for(env.decls, degree.max(1)) {
            let w = Interval::new(w, w, 2);
            let t = walk::walk(&mut { env }, a, &point)?.map(|x| x.mul(w));
            acc = Some(match acc {
                None => t,
                Some(s) => {
                    let sum: Vec<Interval> = s
                        .components()
                        .iter()
                        .zip(t.components())
                        .map(|(x, y)| x.add(*y))
                        .collect();
                    Tensor::from_components(s.dim(), s.rank(), sum)
                }
            });
        }
        acc.ok_or_else(|| Enclosure("an empty averaging rule".into()))
    }

    /// The maximum over the in-plane angle: at least the value at every point of the
    /// interpreter's grid (a true lower bound), and about the value at the maximiser
    /// that golden sections find from the best grid point (not a bound: loose).
    fn maximum(&mut self, a: &Node, _node: &Node) -> R<Interval> {
        let env: &IntervalEnv<'_> = self;
        let d = env.decls.dim;
        if d == 3 && !env.decls.normal_in_plane {
            return unsupported("maxn(…) with the normal out of the plane");
        }
        env.loose.set(true);
        let at = |theta: f64| -> R<Interval> {
            let mut n = vec![theta.cos(), theta.sin()];
            n.resize(d, 0.0);
            walk::scalar(&mut { env }, a, &n)
        };
        let mid = |i: Interval| (i.lo + i.hi) / 2.0;
        let step = 2.0 * PI / super::real::MAXN_GRID as f64;
        let (mut low, mut high, mut best) = (
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
            (0.0, f64::NEG_INFINITY),
        );
        for k in 0..super::real::MAXN_GRID {
            let theta = k as f64 * step;
            let v = at(theta)?;
            (low, high) = (low.max(v.lo), high.max(v.hi));
            if mid(v) > best.1 {
                best = (theta, mid(v));
            }
        }
        let g = (5f64.sqrt() - 1.0) / 2.0;
        let (mut lo, mut hi) = (best.0 - step, best.0 + step);
        for _ in 0..60 {
            let (x1, x2) = (hi - g * (hi - lo), lo + g * (hi - lo));
            if mid(at(x1)?) < mid(at(x2)?) {
                lo = x1;
            } else {
                hi = x2;
            }
        }
        let v = at((lo + hi) / 2.0)?;
        Ok(Interval {
            lo: low.max(v.lo),
            hi: high.max(v.hi),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn iv(lo: f64, hi: f64) -> Interval {
        Interval { lo, hi }
    }

    #[test]
    fn arithmetic_encloses_the_exact_result() {
        // 0.1 + 0.2 is not 0.3 in f64; the enclosure contains both roundings.
        let s = Interval::point(0.1).add(Interval::point(0.2));
        assert!(s.lo < 0.1 + 0.2 && 0.1 + 0.2 < s.hi);
        assert!(s.lo <= 0.3 && 0.3 <= s.hi);
        let p = iv(-2.0, 3.0).mul(iv(-1.0, 4.0));
        assert!(p.lo <= -8.0 && p.hi >= 12.0 && p.lo > -8.1 && p.hi < 12.1);
        assert_eq!(iv(1.0, 2.0).div(iv(-1.0, 1.0)), (Interval::entire(), true));
    }

    #[test]
    fn even_powers_are_never_negative() {
        let sq = iv(-1.0, 2.0).powi(2);
        assert_eq!(sq.lo, 0.0);
        assert!(sq.hi >= 4.0 && sq.hi < 4.001);
        let cube = iv(-2.0, 1.0).powi(3);
        assert!(cube.lo <= -8.0 && cube.hi >= 1.0);
        assert_eq!(iv(5.0, 7.0).powi(0), Interval::point(1.0));
    }

    #[test]
    fn sine_and_cosine_reach_their_extrema_inside() {
        let s = iv(1.0, 2.0).sin(); // π/2 inside
        assert_eq!(s.hi, 1.0);
        assert!(s.lo <= 1f64.sin().min(2f64.sin()));
        let c = iv(3.0, 3.5).cos(); // π inside
        assert_eq!(c.lo, -1.0);
        let narrow = iv(0.1, 0.2).cos();
        assert!(narrow.lo <= 0.2f64.cos() && narrow.hi >= 0.1f64.cos() && narrow.hi < 1.0);
    }

    #[test]
    fn cancellation_is_visible_as_width() {
        // 1 − cos x at x = 1e-6 is 5e-13 exactly to 13 digits; in f64 only the first
        // few digits are right, and the enclosure is as wide as that error.
        let x = Interval::point(1e-6);
        let one_minus_cos = Interval::point(1.0).add(x.cos().neg());
        let (q, assumed) = one_minus_cos.div(x.powi(2));
        assert!(!assumed);
        assert!(q.lo <= 0.5 && 0.5 <= q.hi, "{q:?}");
        assert!(q.hi - q.lo > 1e-6);
        assert!(q.may_satisfy(Relation::Eq, &Interval::point(0.5)));
        // A real difference at a point where nothing cancels is excluded.
        let far = Interval::point(1.0).add(Interval::point(0.5).cos().neg());
        assert!(!far.may_satisfy(Relation::Eq, &Interval::point(0.12)));
    }

    #[test]
    fn domains_that_rounding_cannot_decide_are_assumed() {
        let (root, assumed) = iv(-1e-300, 4.0).sqrt();
        assert!(assumed && root.lo == 0.0 && root.hi >= 2.0);
        assert!(iv(0.0, 1.0).log().1);
        assert!(iv(1.5, 1.6).tan().1); // π/2 inside
        let angle = iv(-1.0, 1.0).atan2(iv(-2.0, -1.0));
        assert!(angle.lo <= -PI && angle.hi >= PI);
        assert_eq!(iv(0.5, 1.0 + 1e-15).in_unit(), (iv(0.5, 1.0), true));
        assert_eq!(iv(0.5, 0.75).in_unit(), (iv(0.5, 0.75), false));
        // Inside the domain nothing is assumed.
        assert!(!iv(1.0, 4.0).sqrt().1 && !iv(0.5, 2.0).log().1);
    }
}
