//! Interval arithmetic: the sides of a sampled statement enclosed, at one state, in
//! intervals that contain their exact values. It tells a violation from rounding.
//!
//! Floating point loses digits where a side cancels: `(1 − cos x)/x²` at x = 10⁻⁶ is
//! 0.49999… in `f64` with five digits wrong, and `(x − sin x)/x³` is worse. Two such
//! sides differ far beyond any relative tolerance although they are equal. Every value
//! here is an interval [lo, hi] that contains the exact value of the expression at the
//! state, so two sides whose intervals overlap may be equal, and a violation counts only
//! where the intervals exclude the relation.
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
//! confirm one. A construct that has no enclosure here (averages over the normal,
//! `maxn`, derivatives, variations, gradients) stops the evaluation with
//! [`Enclosure::Unsupported`], and the caller keeps its floating-point judgement.

use super::assume::{product_value, Parametrisation};
use super::sampler::{Sampler, State};
use super::walk::{self, Ring};
use crate::algebra::einsum::Arithmetic;
use crate::algebra::Tensor;
use crate::derivation::{Assumption, AssumptionKind, Definition, Relation};
use crate::kernel::Rational;
use crate::lang::parser::{Func, Func2};
use crate::lang::{Decls, Node};
use rustc_hash::FxHashMap as HashMap;
use std::cell::{Cell, RefCell};
use std::f64::consts::PI;

/// Units in the last place by which a libm result is widened on each side.
pub const LIBM_ULPS: u32 = 2;

/// Beyond this magnitude of the argument, `sin`, `cos` and `tan` are enclosed by their
/// whole range (the position of the extrema is not computed there).
const TRIG_REDUCTION: f64 = 1e6;

/// A closed interval [lo, hi] of reals; infinite ends allowed, never NaN.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interval {
    pub lo: f64,
    pub hi: f64,
}

/// Why an enclosure was not computed: a construct this evaluation does not enclose.
#[derive(Clone, Debug, PartialEq)]
pub struct Enclosure(pub String);

type R<T> = Result<T, Enclosure>;

/// A value's free letters (sorted) and its enclosure.
type Lettered = (Vec<char>, Tensor<Interval>);

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

    fn add(self, b: Self) -> Self {
        Interval::new(self.lo + b.lo, self.hi + b.hi, 1)
    }

    fn mul(self, b: Self) -> Self {
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
        if !(self.lo.is_finite() && self.hi.is_finite())
            || self.lo.abs().max(self.hi.abs()) > TRIG_REDUCTION
            || self.hi - self.lo >= 2.0 * PI
        {
            return whole;
        }
        let mut e = Interval::hull(&[f(self.lo), f(self.hi)], LIBM_ULPS);
        let slack = 1e-9;
        let inside = |at: f64| {
            let k0 = ((self.lo - at) / (2.0 * PI)).floor() - 1.0;
            (0..4).any(|j| {
                let p = at + (k0 + j as f64) * 2.0 * PI;
                p >= self.lo - slack && p <= self.hi + slack
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
        let slack = 1e-9;
        let pole = (0..4).any(|j| {
            let p = PI / 2.0 + (k0 + j as f64) * PI;
            p >= self.lo - slack && p <= self.hi + slack
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
        match relation {
            Relation::Eq => self.lo <= right.hi && right.lo <= self.hi,
            Relation::Le => self.lo <= right.hi,
            Relation::Ge => right.lo <= self.hi,
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
    /// Whether some enclosure holds only on the domain (see the module doc).
    assumed: Cell<bool>,
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
            assumed: Cell::new(false),
        };
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
        for &k in parametrisation.substitutions() {
            let AssumptionKind::Equals {
                symbol,
                formal,
                body,
            } = &assumptions[k].kind
            else {
                unreachable!("substitutions are equations")
            };
            let n = env.n.clone();
            let t = walk::in_formal_order(&mut &env, body, formal, &n)?;
            env.symbols.insert(symbol.clone(), t);
            env.memo.borrow_mut().clear();
        }
        Ok(env)
    }

    /// `node`'s enclosure: its free letters (sorted) and the tensor.
    pub fn eval(&self, node: &Node) -> R<Lettered> {
        Ok((node.free_letters(), walk::walk(&mut &*self, node, &self.n)?))
    }

    /// Whether an enclosure so far holds only if the state lies in the domain.
    pub fn assumed(&self) -> bool {
        self.assumed.get()
    }

    fn on_domain(&self, (x, assumed): OnDomain) -> Interval {
        if assumed {
            self.assumed.set(true);
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

    fn average(&mut self, _a: &Node, _node: &Node, _n: &[f64]) -> R<Tensor<Interval>> {
        unsupported("an average over the normal")
    }

    fn maximum(&mut self, _a: &Node, _node: &Node) -> R<Interval> {
        unsupported("maxn(…)")
    }

    fn derivatives(&mut self, _a: &Node, _node: &Node, _n: &[f64]) -> R<Tensor<Interval>> {
        unsupported("a derivative along the position")
    }

    fn variations(
        &mut self,
        _body: &Node,
        _field: &str,
        _node: &Node,
        _n: &[f64],
    ) -> R<Tensor<Interval>> {
        unsupported("a variational derivative")
    }

    fn gradients(
        &mut self,
        _body: &Node,
        _symbol: &str,
        _node: &Node,
        _n: &[f64],
    ) -> R<Tensor<Interval>> {
        unsupported("grad(…)")
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
}

/// The enclosures of a sampled statement's comparisons at one state, each side walked
/// once.
pub(super) struct Enclosures<'s, 'a> {
    sampler: &'s Sampler<'a>,
    state: &'s State,
    env: Option<R<IntervalEnv<'a>>>,
    sides: HashMap<(usize, usize), R<Lettered>>,
}

impl<'s, 'a> Enclosures<'s, 'a> {
    pub(super) fn new(sampler: &'s Sampler<'a>, state: &'s State) -> Self {
        Enclosures {
            sampler,
            state,
            env: None,
            sides: HashMap::default(),
        }
    }

    /// The enclosures of sides `k` and `k + 1` of chain `chain` (both 0-based) at the
    /// index values `at` (0-based, by letter), and whether they hold only on the
    /// domain ([`IntervalEnv::assumed`]).
    pub(super) fn pair(
        &mut self,
        chain: usize,
        k: usize,
        at: &[(char, usize)],
    ) -> R<(Interval, Interval, bool)> {
        let (sampler, state) = (self.sampler, self.state);
        let env = self.env.get_or_insert_with(|| {
            IntervalEnv::at_state(
                sampler.decls,
                &sampler.check.defs,
                &sampler.parametrisation,
                &sampler.check.assumptions,
                state,
            )
        });
        let env = match env {
            Ok(env) => env,
            Err(e) => return Err(e.clone()),
        };
        let mut side = |j: usize| -> R<Interval> {
            let value = self.sides.entry((chain, j)).or_insert_with(|| {
                let s = &sampler.check.chains[chain][j];
                match &s.node {
                    Ok(node) => env.eval(node),
                    Err(e) => Err(Enclosure(e.message.clone())),
                }
            });
            let (letters, t) = value.as_ref().map_err(Clone::clone)?;
            let idx: Vec<usize> = letters
                .iter()
                .map(|c| at.iter().find(|(l, _)| l == c).map_or(0, |&(_, v)| v))
                .collect();
            Ok(*t.get(&idx))
        };
        let (l, r) = (side(k)?, side(k + 1)?);
        Ok((l, r, env.assumed()))
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
