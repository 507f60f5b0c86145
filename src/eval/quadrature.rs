//! Averages over the unit circle and sphere of integrands that are not polynomials in
//! the normal (`avg(abs(n_1))`, `avg(sqrt(tt_k tt_k))`), by adaptive Gauss–Kronrod
//! quadrature with an error estimate.
//!
//! A fixed rule exact for polynomials of degree 15 is off by about 1e-3 on
//! ⟨|n_1|⟩: reported as a counterexample, that error accused a correct statement. Here
//! every average carries an error bound, and [`Quadrature`] records, for the
//! evaluations that asked for it, whether any such average was taken, the largest
//! bound and whether every average met its tolerance within its budget. The decision
//! (`numeric::check_state`) evaluates a statement on two partitions ([`Level::Fine`],
//! [`Level::Coarse`]) and on a third ([`Level::Arbiter`]) when they disagree, keeps the
//! pair that agrees best, and gives `fails` only when the difference of the sides
//! exceeds the error by a clear margin; otherwise the claim is undecided, with the
//! reason.
//!
//! Rules, with the ⟨·⟩ normalisation (weights of a uniform average):
//! - circle: ⟨f⟩ = (1/2π) ∫₀^{2π} f(cos φ, sin φ) dφ;
//! - sphere: ⟨f⟩ = (1/4π) ∫_{−π/2}^{π/2} cos ψ ∫₀^{2π} f(cos ψ cos φ, cos ψ sin φ, sin ψ)
//!   dφ dψ, the inner integral adaptive for every outer node, its error added to the
//!   outer estimate. The latitude ψ (not z = sin ψ) keeps a smooth integrand smooth at
//!   the poles.
//!
//! The estimate of a piece is |K15 − G7| (QUADPACK's Kronrod pair, without its
//! empirical rescaling). It is not a bound: at a kink both rules err alike, and a kink
//! between a piece's outermost node and its end is invisible to both. Hence the bound
//! a decision uses is [`QUADRATURE_SAFETY`] times the larger of the estimate and the tolerance,
//! plus the disagreement of two partitions whose blind spots differ. Like every
//! adaptive rule it can still be fooled by a feature narrower than the initial pieces
//! that no node of either partition sees; the integrands here are absolute values,
//! square roots and maxima of polynomials in n with O(1) coefficients, whose kinks
//! are curves the bisection finds.

use num_dual::DualNum;
use std::cell::Cell;

/// Integrand evaluations left (shared by the nested integrals of one average).
type Budget = Cell<usize>;

/// The integrand: its components at a point of the circle or sphere.
pub type Integrand<'f, T, E> = dyn FnMut(&[f64]) -> Result<Vec<T>, E> + 'f;
use crate::tolerance::QUADRATURE_SAFETY;
use std::f64::consts::PI;

/// The evaluations a statement with such averages gets: the decision's error estimate
/// is the difference between two of them (see `numeric::check_state`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Level {
    Fine,
    Coarse,
    /// The fine tolerance on a third partition: the arbiter when fine and coarse
    /// disagree (one of them missed a kink in a blind spot).
    Arbiter,
}

impl Level {
    /// Relative tolerance (against ∫|f|) on the circle (`free = 2`) or the sphere. On
    /// the circle a kink costs a few hundred evaluations at 1e-11; on the sphere the
    /// latitudes where a kink curve turns are square-root singularities of the outer
    /// integrand, and ⟨|a·n|⟩ to 1e-7 already takes about 80,000 evaluations (the
    /// |K − G| estimate is pessimistic: the error is then about 3e-8).
    pub fn tolerance(self, free: usize) -> f64 {
        match (self, free) {
            (Level::Fine | Level::Arbiter, 2) => 1e-11,
            (Level::Coarse, 2) => 1e-10,
            (Level::Fine | Level::Arbiter, _) => 1e-7,
            (Level::Coarse, _) => 1e-6,
        }
    }

    /// The initial pieces (count, and the offset of the first boundary) of the circle
    /// and of the latitude. The two levels partition differently: a kink between a
    /// piece's outermost Kronrod node and its end (within 0.0085 of its half-width)
    /// is invisible to the rule, both estimates miss it, and only a partition whose
    /// boundaries lie elsewhere shows the difference. The fine circle starts on the
    /// axes, where the kinks of |n_1| and |n_2| lie.
    fn pieces(self) -> ((usize, f64), (usize, f64)) {
        match self {
            Level::Fine => ((8, 0.0), (4, 0.0)),
            Level::Coarse => ((7, 0.1), (5, 0.05)),
            Level::Arbiter => ((9, 0.23), (3, 0.17)),
        }
    }
}

/// Integrand evaluations allowed for one average (the sphere's inner integrals
/// included); when they run out the average is marked as not converged.
pub const MAX_EVALUATIONS: usize = 300_000;

/// Kronrod abscissae on [−1, 1] (the positive half; the last is 0).
const XGK: [f64; 8] = [
    0.991_455_371_120_812_6,
    0.949_107_912_342_758_5,
    0.864_864_423_359_769_1,
    0.741_531_185_599_394_4,
    0.586_087_235_467_691_1,
    0.405_845_151_377_397_2,
    0.207_784_955_007_898_5,
    0.0,
];
/// Kronrod weights of [`XGK`].
const WGK: [f64; 8] = [
    0.022_935_322_010_529_22,
    0.063_092_092_629_978_55,
    0.104_790_010_322_250_2,
    0.140_653_259_715_525_9,
    0.169_004_726_639_267_9,
    0.190_350_578_064_785_4,
    0.204_432_940_075_298_9,
    0.209_482_141_084_727_8,
];
/// Gauss weights of the 7-point rule, at XGK[1], XGK[3], XGK[5], XGK[7].
const WG: [f64; 4] = [
    0.129_484_966_168_869_7,
    0.279_705_391_489_276_7,
    0.381_830_050_505_118_9,
    0.417_959_183_673_469_4,
];

/// The tolerance an evaluation asks of its averages, and what they reported.
#[derive(Debug)]
pub struct Quadrature {
    pub level: Level,
    used: Cell<bool>,
    converged: Cell<bool>,
    worst_error: Cell<f64>,
}

impl Quadrature {
    pub fn new(level: Level) -> Self {
        Quadrature {
            level,
            used: Cell::new(false),
            converged: Cell::new(true),
            worst_error: Cell::new(0.0),
        }
    }

    /// Whether an adaptive average was taken since the last [`Quadrature::reset`].
    pub fn used(&self) -> bool {
        self.used.get()
    }

    /// Whether every average met its tolerance within [`MAX_EVALUATIONS`].
    pub fn converged(&self) -> bool {
        self.converged.get()
    }

    /// The largest absolute error bound of an average: [`QUADRATURE_SAFETY`] times the larger of
    /// its |K − G| estimate and its tolerance times ∫|f|.
    pub fn worst_error(&self) -> f64 {
        self.worst_error.get()
    }

    pub fn reset(&self) {
        self.used.set(false);
        self.converged.set(true);
        self.worst_error.set(0.0);
    }

    /// Adds what another record saw to this one.
    pub fn absorb(&self, other: &Quadrature) {
        self.used.set(self.used.get() || other.used());
        self.converged
            .set(self.converged.get() && other.converged());
        self.worst_error
            .set(self.worst_error.get().max(other.worst_error()));
    }

    fn record<T>(&self, a: &Integral<T>, tolerance: f64) {
        self.used.set(true);
        self.converged.set(self.converged.get() && a.converged);
        let bound = QUADRATURE_SAFETY * a.error.max(tolerance * a.l1);
        self.worst_error.set(self.worst_error.get().max(bound));
    }

    /// ⟨f⟩ over the unit circle (`free = 2`) or sphere (`free = 3`), the normal padded
    /// with zeros to `dim`; `f` returns the integrand's components.
    pub fn average<T, E>(
        &self,
        free: usize,
        dim: usize,
        f: &mut Integrand<'_, T, E>,
    ) -> Result<Vec<T>, E>
    where
        T: DualNum<Primitive = f64>,
    {
        let budget = Cell::new(MAX_EVALUATIONS);
        let tolerance = self.level.tolerance(free);
        let pieces = self.level.pieces();
        let integral = if free == 2 {
            circle(tolerance, pieces.0, dim, &budget, 0.0, 1.0, f)?
        } else {
            sphere(tolerance, pieces, dim, &budget, f)?
        };
        self.record(&integral, tolerance);
        Ok(integral.value)
    }
}

/// An integral's components, the absolute error estimate (largest over components, on
/// real parts), ∫|f| (largest over components) and whether it met its tolerance.
#[derive(Clone, Debug)]
struct Integral<T> {
    value: Vec<T>,
    error: f64,
    l1: f64,
    converged: bool,
}

/// One piece [a, b] with its Kronrod value.
struct Piece<T> {
    a: f64,
    b: f64,
    integral: Integral<T>,
}

fn scaled<T: DualNum<Primitive = f64>>(v: &[T], w: f64) -> Vec<T> {
    v.iter().map(|x| x.clone() * T::from(w)).collect()
}

fn add_into<T: DualNum<Primitive = f64>>(acc: &mut Vec<T>, v: &[T]) {
    if acc.is_empty() {
        *acc = v.to_vec();
    } else {
        for (a, x) in acc.iter_mut().zip(v) {
            *a = a.clone() + x.clone();
        }
    }
}

/// The 15-point Kronrod value of ∫_a^b g, its |K − G| estimate and ∫|g|.
fn kronrod<T, E>(
    a: f64,
    b: f64,
    g: &mut dyn FnMut(f64) -> Result<Integral<T>, E>,
) -> Result<Integral<T>, E>
where
    T: DualNum<Primitive = f64>,
{
    let (c, h) = ((a + b) / 2.0, (b - a) / 2.0);
    let mut kron: Vec<T> = Vec::new();
    let mut gauss: Vec<f64> = Vec::new();
    let mut l1 = 0.0;
    let mut inner_error = 0.0;
    let mut converged = true;
    for (k, (&x, &wk)) in XGK.iter().zip(&WGK).enumerate() {
        let points: &[f64] = if x == 0.0 {
            &[c]
        } else {
            &[c - h * x, c + h * x]
        };
        for &t in points {
            let v = g(t)?;
            converged &= v.converged;
            inner_error += wk * h * v.error;
            l1 += wk * h * v.l1;
            add_into(&mut kron, &scaled(&v.value, wk * h));
            if k % 2 == 1 {
                let wg = WG[k / 2] * h;
                if gauss.is_empty() {
                    gauss = vec![0.0; v.value.len()];
                }
                for (s, x) in gauss.iter_mut().zip(&v.value) {
                    *s += wg * x.re();
                }
            }
        }
    }
    let error = kron
        .iter()
        .zip(&gauss)
        .map(|(k, g)| (k.re() - g).abs())
        .fold(0.0, f64::max)
        + inner_error;
    Ok(Integral {
        value: kron,
        error: if error.is_nan() { f64::INFINITY } else { error },
        l1,
        converged,
    })
}

/// Globally adaptive integration of g over [a, b], starting from `pieces` equal pieces
/// shifted by `offset` (a periodic integrand: the last piece wraps round to a + offset;
/// 0 for a non-periodic one) and bisecting the piece of largest error until the total is within `tol`·∫|g| or
/// the budget cannot pay for another bisection (30 evaluations of g, each of which
/// costs `node_cost()` evaluations of the integrand).
#[allow(clippy::too_many_arguments)]
fn adaptive<T, E>(
    a: f64,
    b: f64,
    (pieces, offset): (usize, f64),
    tol: f64,
    budget: &Budget,
    node_cost: &dyn Fn() -> usize,
    g: &mut dyn FnMut(f64) -> Result<Integral<T>, E>,
) -> Result<Integral<T>, E>
where
    T: DualNum<Primitive = f64>,
{
    let mut parts: Vec<Piece<T>> = Vec::with_capacity(pieces);
    let step = (b - a) / pieces as f64;
    for k in 0..pieces {
        let (lo, hi) = (
            a + offset + step * k as f64,
            a + offset + step * (k + 1) as f64,
        );
        parts.push(Piece {
            a: lo,
            b: hi,
            integral: kronrod(lo, hi, g)?,
        });
    }
    let total = |parts: &[Piece<T>]| -> (f64, f64) {
        parts.iter().fold((0.0, 0.0), |(e, l), p| {
            (e + p.integral.error, l + p.integral.l1)
        })
    };
    loop {
        let (error, l1) = total(&parts);
        if !error.is_finite() || error <= tol * l1 || budget.get() < 30 * node_cost() {
            break;
        }
        let worst = (0..parts.len())
            .max_by(|&i, &j| parts[i].integral.error.total_cmp(&parts[j].integral.error))
            .expect("at least one piece");
        let (lo, hi) = (parts[worst].a, parts[worst].b);
        let mid = (lo + hi) / 2.0;
        if mid <= lo || mid >= hi {
            // The piece cannot be split further in f64 (it stays, with its error).
            break;
        }
        parts.swap_remove(worst);
        for (x, y) in [(lo, mid), (mid, hi)] {
            parts.push(Piece {
                a: x,
                b: y,
                integral: kronrod(x, y, g)?,
            });
        }
    }
    parts.sort_by(|p, q| p.a.total_cmp(&q.a));
    let (error, l1) = total(&parts);
    let mut value = Vec::new();
    let mut converged = error <= tol * l1;
    for p in &parts {
        add_into(&mut value, &p.integral.value);
        converged &= p.integral.converged;
    }
    Ok(Integral {
        value,
        error,
        l1,
        converged,
    })
}

/// The circle average of f at latitude `z` (`r` = √(1 − z²)): ⟨f⟩ over φ.
fn circle<T, E>(
    tol: f64,
    pieces: (usize, f64),
    dim: usize,
    budget: &Budget,
    z: f64,
    r: f64,
    f: &mut Integrand<'_, T, E>,
) -> Result<Integral<T>, E>
where
    T: DualNum<Primitive = f64>,
{
    let mut point = vec![0.0; dim];
    let mut g = |phi: f64| -> Result<Integral<T>, E> {
        point[0] = r * phi.cos();
        point[1] = r * phi.sin();
        if dim > 2 {
            point[2] = z;
        }
        budget.set(budget.get().saturating_sub(1));
        let value = f(&point)?;
        let l1 = value.iter().map(|x| x.re().abs()).fold(0.0, f64::max);
        Ok(Integral {
            value,
            error: 0.0,
            l1,
            converged: true,
        })
    };
    let i = adaptive(0.0, 2.0 * PI, pieces, tol, budget, &|| 1, &mut g)?;
    Ok(normalised(i, 2.0 * PI))
}

/// The sphere average: the circle average at every latitude, integrated over ψ.
fn sphere<T, E>(
    tol: f64,
    (around, latitude): ((usize, f64), (usize, f64)),
    dim: usize,
    budget: &Budget,
    f: &mut Integrand<'_, T, E>,
) -> Result<Integral<T>, E>
where
    T: DualNum<Primitive = f64>,
{
    // Integrand evaluations and circles so far: a bisection of the latitude costs 30
    // circles of the average cost.
    let start = budget.get();
    let circles = Cell::new(0usize);
    let node_cost = || (start - budget.get()) / circles.get().max(1) + 1;
    let mut g = |psi: f64| -> Result<Integral<T>, E> {
        circles.set(circles.get() + 1);
        let w = psi.cos();
        // Once the budget is spent, each further circle takes its 8 initial pieces
        // only (and reports whether they met the tolerance).
        let inner = circle(tol, around, dim, budget, psi.sin(), w.max(0.0), f)?;
        Ok(Integral {
            value: scaled(&inner.value, w),
            error: inner.error * w,
            l1: inner.l1 * w,
            converged: inner.converged,
        })
    };
    // Not periodic: the offset shrinks the first piece instead of wrapping.
    let (count, offset) = latitude;
    let i = if offset == 0.0 {
        adaptive(
            -PI / 2.0,
            PI / 2.0,
            (count, 0.0),
            tol,
            budget,
            &node_cost,
            &mut g,
        )?
    } else {
        let split = -PI / 2.0 + offset;
        let head = adaptive(-PI / 2.0, split, (1, 0.0), tol, budget, &node_cost, &mut g)?;
        let tail = adaptive(
            split,
            PI / 2.0,
            (count, 0.0),
            tol,
            budget,
            &node_cost,
            &mut g,
        )?;
        joined(head, tail)
    };
    Ok(normalised(i, 2.0))
}

/// The integral over two adjacent intervals.
fn joined<T: DualNum<Primitive = f64>>(a: Integral<T>, b: Integral<T>) -> Integral<T> {
    let mut value = a.value;
    add_into(&mut value, &b.value);
    Integral {
        value,
        error: a.error + b.error,
        l1: a.l1 + b.l1,
        converged: a.converged && b.converged,
    }
}

fn normalised<T: DualNum<Primitive = f64>>(i: Integral<T>, measure: f64) -> Integral<T> {
    Integral {
        value: scaled(&i.value, 1.0 / measure),
        error: i.error / measure,
        l1: i.l1 / measure,
        converged: i.converged,
    }
}

/// The quadrature rule of `avg(…)` for these declarations, exact to `degree`: the
/// sphere, or the circle (embedded with n_3 = 0) for plane problems.
pub fn rule_for(decls: &crate::lang::Decls, degree: usize) -> Vec<(Vec<f64>, f64)> {
    let free = if decls.normal_in_plane { 2 } else { decls.dim };
    sphere_rule_exact_to(free, degree)
        .into_iter()
        .map(|(mut p, w)| {
            p.resize(decls.dim, 0.0);
            (p, w)
        })
        .collect()
}

/// Quadrature nodes and weights (weights sum to 1) for the uniform average over the
/// unit circle or sphere, exact for polynomials in n of degree ≤ 15.
pub fn sphere_rule(dim: usize) -> Vec<(Vec<f64>, f64)> {
    sphere_rule_exact_to(dim, 15)
}

/// A rule exact for polynomials in n of degree ≤ `degree`: on the circle, M = degree + 1
/// equally spaced points (exact for trigonometric degree < M); on the sphere, an
/// N-point Gauss–Legendre rule in z = cos θ with 2N − 1 ≥ degree times M = degree + 1
/// equally spaced φ. (A monomial n_1^a n_2^b n_3^c with a + b odd integrates to 0 over
/// φ exactly; with a + b even it is a polynomial of degree ≤ degree in z.)
pub fn sphere_rule_exact_to(dim: usize, degree: usize) -> Vec<(Vec<f64>, f64)> {
    use std::f64::consts::PI;
    let m = degree + 1;
    if dim == 2 {
        return (0..m)
            .map(|k| {
                let phi = 2.0 * PI * k as f64 / m as f64;
                (vec![phi.cos(), phi.sin()], 1.0 / m as f64)
            })
            .collect();
    }
    let (zs, ws) = gauss_legendre(degree / 2 + 1);
    let mut out = Vec::with_capacity(zs.len() * m);
    for (z, w) in zs.iter().zip(&ws) {
        let r = (1.0 - z * z).max(0.0).sqrt();
        for k in 0..m {
            let phi = 2.0 * PI * k as f64 / m as f64;
            out.push((vec![r * phi.cos(), r * phi.sin(), *z], w / 2.0 / m as f64));
        }
    }
    out
}

/// Gauss–Legendre nodes and weights on [−1, 1] by Newton iteration on P_n.
fn gauss_legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
    let mut xs = Vec::with_capacity(n);
    let mut ws = Vec::with_capacity(n);
    for i in 0..n {
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
            let dx = p1 / dp;
            x -= dx;
            if dx.abs() < 1e-16 {
                break;
            }
        }
        xs.push(x);
        ws.push(2.0 / ((1.0 - x * x) * dp * dp));
    }
    (xs, ws)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// |a| for a = (0.3, −1.1, 0.7) and for its first two components.
    const A3: f64 = 1.337_908_816_025_965_3;
    const A2: f64 = 1.140_175_425_099_138;

    fn avg(free: usize, level: Level, f: impl Fn(&[f64]) -> f64) -> (f64, Quadrature) {
        let q = Quadrature::new(level);
        let v = q
            .average::<f64, ()>(free, free, &mut |n| Ok(vec![f(n)]))
            .unwrap();
        (v[0], q)
    }

    #[test]
    fn rules_integrate_known_moments() {
        for dim in [2usize, 3] {
            let rule = sphere_rule(dim);
            let total: f64 = rule.iter().map(|(_, w)| w).sum();
            assert!((total - 1.0).abs() < 1e-14);
            let m4: f64 = rule.iter().map(|(p, w)| w * p[0].powi(4)).sum();
            let want = if dim == 2 { 3.0 / 8.0 } else { 1.0 / 5.0 };
            assert!((m4 - want).abs() < 1e-14, "dim {dim}: {m4}");
        }
    }

    #[test]
    fn exact_values_of_non_polynomial_averages() {
        type Case = (usize, fn(&[f64]) -> f64, f64);
        let cases: [Case; 5] = [
            (2, |n| n[0].abs(), 2.0 / PI),
            (3, |n| n[0].abs(), 0.5),
            // ⟨|a·n|⟩ = |a|/2 on the sphere and 2|a|/π on the circle, a = (0.3, −1.1, 0.7).
            (
                3,
                |n| (0.3 * n[0] - 1.1 * n[1] + 0.7 * n[2]).abs(),
                A3 / 2.0,
            ),
            (2, |n| (0.3 * n[0] - 1.1 * n[1]).abs(), 2.0 * A2 / PI),
            // ⟨n_1² n_2²⟩ on the sphere is 1/15 (a polynomial: exact moments agree).
            (3, |n| n[0] * n[0] * n[1] * n[1], 1.0 / 15.0),
        ];
        for (free, f, want) in cases {
            let (got, q) = avg(free, Level::Fine, f);
            let tol = Level::Fine.tolerance(free);
            assert!(q.used() && q.converged(), "{free}: not converged");
            assert!((got - want).abs() < 10.0 * tol, "{free}: {got} vs {want}");
            assert!(
                q.worst_error() <= QUADRATURE_SAFETY * tol,
                "bound {}",
                q.worst_error()
            );
        }
    }

    #[test]
    fn the_two_level_estimate_bounds_the_true_error() {
        // A kink off the axes, on the circle and the sphere. |K15 − G7| alone can
        // under-estimate at a kink (both rules err alike); the decision's estimate, the
        // fine estimate plus the fine–coarse difference, does not.
        let a3 = |n: &[f64]| (0.3 * n[0] - 1.1 * n[1] + 0.7 * n[2]).abs();
        let a2 = |n: &[f64]| (0.3 * n[0] - 1.1 * n[1]).abs();
        type Case<'a> = (usize, &'a dyn Fn(&[f64]) -> f64, f64);
        let cases: [Case; 2] = [(3, &a3, A3 / 2.0), (2, &a2, 2.0 * A2 / PI)];
        for (free, f, want) in cases {
            let (fine, q) = avg(free, Level::Fine, f);
            let (coarse, _) = avg(free, Level::Coarse, f);
            let err = (fine - want).abs();
            let bound = q.worst_error() + (fine - coarse).abs();
            assert!(err <= bound, "{free}: {err} > {bound}");
        }
    }

    #[test]
    fn a_starved_budget_is_reported_as_not_converged() {
        // sqrt of a kink: the fine tolerance is out of reach of a 15-node rule on a
        // handful of pieces, and the evaluation count is bounded.
        let q = Quadrature::new(Level::Fine);
        let mut calls = 0usize;
        q.average::<f64, ()>(3, 3, &mut |n| {
            calls += 1;
            Ok(vec![
                (n[0] - 0.3).abs().sqrt() * (n[1] + 0.2 * n[2]).abs().sqrt(),
            ])
        })
        .unwrap();
        assert!(!q.converged());
        // After the budget is spent, at most the initial circles of the latitude's 4
        // pieces (60 circles of 8 pieces) finish unrefined.
        assert!(
            calls <= MAX_EVALUATIONS + 60 * 8 * 15,
            "{calls} evaluations"
        );
    }

    #[test]
    fn derivatives_follow_the_value() {
        use num_dual::{Dual64, DualStruct};
        fn abs<T: DualNum<Primitive = f64>>(x: T) -> T {
            x.abs()
        }
        // d/da ⟨|a n_1|⟩ = ⟨|n_1|⟩ = 1/2 at a = 2 on the sphere.
        let q = Quadrature::new(Level::Fine);
        let a = Dual64::from(2.0).derivative();
        let v = q
            .average::<Dual64, ()>(3, 3, &mut |n| Ok(vec![abs(a * n[0])]))
            .unwrap();
        assert!((v[0].re() - 1.0).abs() < 1e-10);
        assert!((v[0].eps - 0.5).abs() < 1e-10);
    }
}
