//! Sparse multivariate (Laurent) polynomials with exact rational coefficients, in a
//! canonical form: two equal polynomials have identical representations.
//!
//! This is where an exact proof happens: both sides of a claim are expanded into a
//! `Poly` and compared structurally. Canonical form is kept by construction:
//! monomials are sorted `(variable, exponent)` lists without zero exponents, and the
//! terms are a vector sorted by monomial (each once) that never holds a zero
//! coefficient. Sums are linear merges; a product sorts its term products once and
//! merges equal monomials (see [`Poly::from_terms`]). Exponents may be negative so that division
//! by a single term (`S/V`, `1/R_g`) stays exact and canonical; division by a sum is
//! not a polynomial operation and is refused.

use super::moments::monomial_moment;
use super::rational::Rational;
use num_traits::{One, Zero};
use rustc_hash::FxHashMap as HashMap;
use smallvec::SmallVec;
use std::fmt::Write as _;
use std::ops::{Add, AddAssign, Mul, Neg, Sub};

/// From this many terms on, [`Poly::eval`] works over one common denominator.
const COMMON_DENOMINATOR_TERMS: usize = 8;

/// The highest exponent [`Poly::eval`] evaluates over a common denominator.
const LADDER_TOP: u32 = 64;

/// A polynomial variable: an index into a [`VarTable`].
pub type Var = u32;

/// The largest absolute value of an exponent in any monomial. Every operation that
/// builds a monomial checks it, so that the sum of two exponents never leaves `i64`
/// and no exponent wraps: a wrapped exponent once made x^(2^32) equal to 1.
pub const MAX_EXPONENT: Exp = 1 << 40;

/// An exponent of a monomial.
pub type Exp = i64;

/// `e` as an exponent within [`MAX_EXPONENT`].
fn bounded(e: i128) -> Option<Exp> {
    Exp::try_from(e)
        .ok()
        .filter(|e| e.unsigned_abs() <= MAX_EXPONENT.unsigned_abs())
}

/// How many factors a monomial holds without a heap allocation; longer monomials spill
/// to the heap. Measured on the bench's exact tasks: eight inline made the Appendix's
/// A² 8% slower (larger terms to move) and eq. (38) 6% faster.
const INLINE_FACTORS: usize = 4;

type Factors = SmallVec<[(Var, Exp); INLINE_FACTORS]>;

/// A product of powers of variables: sorted by variable, no zero exponent. Ordered as
/// its list of `(variable, exponent)` pairs, lexicographically: the order in which a
/// [`Poly`] keeps its terms.
#[derive(Clone, PartialEq, Eq, Hash, PartialOrd, Ord, Debug, Default)]
pub struct Monomial(Factors);

impl Monomial {
    /// The empty product, 1.
    pub fn one() -> Self {
        Monomial(Factors::new())
    }

    /// `v^e`; `e` must be within [`MAX_EXPONENT`] (a constant of the caller's).
    pub fn var(v: Var, e: Exp) -> Self {
        assert!(
            bounded(i128::from(e)).is_some(),
            "exponent {e} beyond the bound"
        );
        let mut factors = Factors::new();
        if e != 0 {
            factors.push((v, e));
        }
        Monomial(factors)
    }

    /// Builds the canonical monomial from factors in any order, merging repeats.
    /// Panics (never wraps) when a merged exponent leaves [`MAX_EXPONENT`].
    pub fn from_factors(factors: Vec<(Var, Exp)>) -> Self {
        Self::checked_from_factors(factors).expect("exponent within MAX_EXPONENT")
    }

    /// [`Monomial::from_factors`], or `None` when a merged exponent leaves
    /// [`MAX_EXPONENT`].
    pub fn checked_from_factors(mut factors: Vec<(Var, Exp)>) -> Option<Self> {
        factors.sort_unstable_by_key(|&(v, _)| v);
        let mut out = Factors::with_capacity(factors.len());
        for (v, e) in factors {
            let e = bounded(i128::from(e))?;
            match out.last_mut() {
                Some((lv, le)) if *lv == v => *le = bounded(i128::from(*le) + i128::from(e))?,
                _ => out.push((v, e)),
            }
        }
        out.retain(|&mut (_, e)| e != 0);
        Some(Monomial(out))
    }

    pub fn factors(&self) -> &[(Var, Exp)] {
        &self.0
    }

    pub fn is_one(&self) -> bool {
        self.0.is_empty()
    }

    /// Exponent of `v` (0 when absent).
    pub fn exponent(&self, v: Var) -> Exp {
        self.0
            .binary_search_by_key(&v, |&(w, _)| w)
            .map_or(0, |k| self.0[k].1)
    }

    pub fn total_degree(&self) -> i128 {
        self.0.iter().map(|&(_, e)| i128::from(e)).sum()
    }

    /// The product of two monomials. Panics (never wraps) when an exponent leaves
    /// [`MAX_EXPONENT`]; [`Monomial::checked_mul`] says `None` instead.
    pub fn mul(&self, other: &Monomial) -> Monomial {
        self.checked_mul(other)
            .unwrap_or_else(|| beyond(PolyError::ExponentTooLarge))
    }

    /// The product of two monomials (a linear merge of sorted lists), or `None` when an
    /// exponent leaves [`MAX_EXPONENT`].
    pub fn checked_mul(&self, other: &Monomial) -> Option<Monomial> {
        let (a, b) = (&self.0, &other.0);
        let mut out = Factors::with_capacity(a.len() + b.len());
        let (mut i, mut j) = (0, 0);
        while i < a.len() && j < b.len() {
            match a[i].0.cmp(&b[j].0) {
                std::cmp::Ordering::Less => {
                    out.push(a[i]);
                    i += 1;
                }
                std::cmp::Ordering::Greater => {
                    out.push(b[j]);
                    j += 1;
                }
                std::cmp::Ordering::Equal => {
                    let e = bounded(i128::from(a[i].1) + i128::from(b[j].1))?;
                    if e != 0 {
                        out.push((a[i].0, e));
                    }
                    i += 1;
                    j += 1;
                }
            }
        }
        out.extend_from_slice(&a[i..]);
        out.extend_from_slice(&b[j..]);
        Some(Monomial(out))
    }

    /// `self^e` for any integer `e`, or `None` when an exponent leaves
    /// [`MAX_EXPONENT`].
    pub fn pow(&self, e: Exp) -> Option<Monomial> {
        if e == 0 {
            return Some(Monomial::one());
        }
        // Sorted stays sorted, and no exponent becomes zero.
        let factors = self
            .0
            .iter()
            .map(|&(v, k)| Some((v, bounded(i128::from(k) * i128::from(e))?)));
        Some(Monomial(factors.collect::<Option<_>>()?))
    }

    /// The first two factors packed into a word whose order is the monomials' order on
    /// those factors: 16 bits of variable + 1 and 16 bits of offset exponent per
    /// factor, 0 for a missing one. `None` when a variable or exponent does not fit.
    fn sort_key(&self) -> Option<u64> {
        let mut key = 0u64;
        for slot in 0..2 {
            key <<= 32;
            if let Some(&(v, e)) = self.0.get(slot) {
                let v = u16::try_from(v).ok()?.checked_add(1)?;
                let e = i16::try_from(e).ok()?;
                key |= (u64::from(v) << 16) | u64::from((e as u16) ^ 0x8000);
            }
        }
        Some(key)
    }

    /// The monomial with the factor of `v` left out (still sorted).
    pub fn without(&self, v: Var) -> Monomial {
        Monomial(self.0.iter().copied().filter(|&(w, _)| w != v).collect())
    }

    /// Splits off the exponents of `vars` (in that order), returning them and the rest.
    fn split(&self, vars: &[Var]) -> (Vec<Exp>, Monomial) {
        let exps = vars.iter().map(|&v| self.exponent(v)).collect();
        let rest = self
            .0
            .iter()
            .copied()
            .filter(|(v, _)| !vars.contains(v))
            .collect();
        (exps, Monomial(rest))
    }
}

/// Names of polynomial variables, interned in order of first use.
#[derive(Clone, Debug, Default)]
pub struct VarTable {
    names: Vec<String>,
    index: HashMap<String, Var>,
}

impl VarTable {
    pub fn new() -> Self {
        Self::default()
    }

    /// The variable called `name`, created on first use.
    pub fn intern(&mut self, name: &str) -> Var {
        if let Some(&v) = self.index.get(name) {
            return v;
        }
        let v = Var::try_from(self.names.len()).expect("fewer than 2^32 variables");
        self.names.push(name.to_owned());
        self.index.insert(name.to_owned(), v);
        v
    }

    pub fn name(&self, v: Var) -> &str {
        self.names.get(v as usize).map_or("?", String::as_str)
    }

    pub fn lookup(&self, name: &str) -> Option<Var> {
        self.index.get(name).copied()
    }

    pub fn len(&self) -> usize {
        self.names.len()
    }

    pub fn is_empty(&self) -> bool {
        self.names.is_empty()
    }
}

/// Why a polynomial operation could not be carried out exactly.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum PolyError {
    #[error("division by zero")]
    DivisionByZero,
    #[error("division by a sum of several terms is not a polynomial operation; multiply it out or use a numeric strategy")]
    DivisionBySum,
    #[error("a negative power of a component of the normal cannot be averaged or reduced on the unit sphere")]
    NegativeNormalPower,
    #[error("clearing the denominators takes more than 1000000 term products")]
    TooLarge,
    #[error("an exponent would exceed 2^40")]
    ExponentTooLarge,
    #[error("a product of polynomials would take more than 4194304 term products")]
    TooManyProducts,
}

/// Where an operator without a `Result` (`*`, [`Poly::pow`], [`Monomial::mul`]) passes
/// a limit: it unwinds with the [`PolyError`] itself as the payload (the panic hook
/// does not run), and the checker's isolation of each claim reads it as a resource
/// limit, `undecided`. It never wraps and never returns a value.
pub fn beyond(e: PolyError) -> ! {
    std::panic::resume_unwind(Box::new(e))
}

/// The most term products one multiplication of polynomials may form (each is kept
/// until the terms are merged): past it, a product is a resource limit, not a process
/// that runs out of memory.
pub const MAX_PRODUCTS: usize = 1 << 22;

/// A sparse Laurent polynomial with exact rational coefficients, in canonical form.
///
/// ```
/// use cosserat_kernel::{Poly, VarTable};
/// let mut names = VarTable::new();
/// let x = Poly::var(names.intern("x"));
/// let y = Poly::var(names.intern("y"));
/// // (x + y)(x − y) and x² − y² are the same polynomial, so they compare equal.
/// assert_eq!(&(&x + &y) * &(&x - &y), &(&x * &x) - &(&y * &y));
/// assert_eq!((&x + &y).pow(2).display(&names), "x^2 + 2*x*y + y^2");
/// ```
#[derive(Clone, PartialEq, Eq, Hash, Debug, Default)]
pub struct Poly {
    /// Strictly increasing monomials, no zero coefficient: the canonical form, so
    /// structural equality is equality of polynomials.
    terms: Vec<(Monomial, Rational)>,
}

impl Poly {
    pub fn constant(q: Rational) -> Self {
        let mut p = Poly::default();
        p.add_term(Monomial::one(), q);
        p
    }

    pub fn var(v: Var) -> Self {
        Poly::term(Monomial::var(v, 1), Rational::one())
    }

    pub fn term(m: Monomial, c: Rational) -> Self {
        let mut p = Poly::default();
        p.add_term(m, c);
        p
    }

    /// The sum of terms given in any order, repeats included: sorted once and merged,
    /// which is how every operation that produces many terms builds its result.
    pub fn from_terms(terms: impl IntoIterator<Item = (Monomial, Rational)>) -> Self {
        let mut terms: Vec<(Monomial, Rational)> = terms.into_iter().collect();
        sort_by_monomial(&mut terms);
        let mut out: Vec<(Monomial, Rational)> = Vec::with_capacity(terms.len());
        for (m, c) in terms {
            match out.last_mut() {
                Some((last, sum)) if *last == m => *sum += &c,
                _ => {
                    if out.last().is_some_and(|(_, sum)| sum.is_zero()) {
                        out.pop();
                    }
                    out.push((m, c));
                }
            }
        }
        if out.last().is_some_and(|(_, sum)| sum.is_zero()) {
            out.pop();
        }
        Poly { terms: out }
    }

    /// Adds `c * m`, keeping the canonical form (no zero coefficient stored). One term
    /// at a time: many terms go through [`Poly::from_terms`].
    pub fn add_term(&mut self, m: Monomial, c: Rational) {
        if c.is_zero() {
            return;
        }
        if self.terms.last().is_none_or(|(last, _)| *last < m) {
            self.terms.push((m, c));
            return;
        }
        match self.terms.binary_search_by(|(k, _)| k.cmp(&m)) {
            Ok(k) => {
                self.terms[k].1 += &c;
                if self.terms[k].1.is_zero() {
                    self.terms.remove(k);
                }
            }
            Err(k) => self.terms.insert(k, (m, c)),
        }
    }

    pub fn terms(&self) -> impl Iterator<Item = (&Monomial, &Rational)> {
        self.terms.iter().map(|(m, c)| (m, c))
    }

    /// Whether this is the zero polynomial (canonical form: no terms at all).
    pub fn is_zero(&self) -> bool {
        self.terms.is_empty()
    }

    pub fn num_terms(&self) -> usize {
        self.terms.len()
    }

    /// The value when the polynomial is a constant.
    pub fn as_constant(&self) -> Option<Rational> {
        match self.terms.len() {
            0 => Some(Rational::zero()),
            1 => self
                .terms
                .first()
                .filter(|(m, _)| m.is_one())
                .map(|(_, c)| c.clone()),
            _ => None,
        }
    }

    /// `self / d` when `d` is a single nonzero term (exact in Laurent polynomials).
    pub fn checked_div(&self, d: &Poly) -> Result<Poly, PolyError> {
        let (m, c) = match d.terms.as_slice() {
            [] => return Err(PolyError::DivisionByZero),
            [(m, c)] => (m, c),
            _ => return Err(PolyError::DivisionBySum),
        };
        let inv = Poly::term(
            m.pow(-1).expect("a bounded exponent negated is bounded"),
            c.recip().expect("stored coefficients are nonzero"),
        );
        Ok(self * &inv)
    }

    /// `c · self` for a nonzero `c`: the same monomials in the same order.
    fn scaled(&self, c: &Rational) -> Poly {
        if c.is_one() {
            return self.clone();
        }
        Poly {
            terms: self.terms.iter().map(|(m, a)| (m.clone(), a * c)).collect(),
        }
    }

    /// The variables that occur, sorted.
    pub fn variables(&self) -> Vec<Var> {
        let mut vars: Vec<Var> = self
            .terms
            .iter()
            .flat_map(|(m, _)| m.factors().iter().map(|&(v, _)| v))
            .collect();
        vars.sort_unstable();
        vars.dedup();
        vars
    }

    /// ∂/∂v, exactly (Laurent exponents included).
    pub fn derivative(&self, v: Var) -> Poly {
        let down = Monomial::var(v, -1);
        Poly::from_terms(self.terms.iter().filter_map(|(m, c)| {
            let e = m.exponent(v);
            (e != 0).then(|| (m.mul(&down), c * &Rational::int(e)))
        }))
    }

    /// `self^e`; past a limit it unwinds like the product ([`beyond`]).
    pub fn pow(&self, e: u32) -> Poly {
        self.checked_pow(e).unwrap_or_else(|e| beyond(e))
    }

    /// `self^e` by repeated squaring, or an error when an exponent would leave
    /// [`MAX_EXPONENT`].
    pub fn checked_pow(&self, e: u32) -> Result<Poly, PolyError> {
        self.checked_pow_wide(u64::from(e))
    }

    /// [`Poly::checked_pow`] for any exponent that fits in 64 bits.
    pub fn checked_pow_wide(&self, mut e: u64) -> Result<Poly, PolyError> {
        let (mut base, mut acc) = (self.clone(), Poly::one());
        while e > 0 {
            if e & 1 == 1 {
                acc = acc.checked_mul(&base)?;
            }
            e >>= 1;
            if e > 0 {
                base = base.checked_mul(&base)?;
            }
        }
        Ok(acc)
    }

    /// The product, or an error when an exponent would leave [`MAX_EXPONENT`] or the
    /// product would form more than [`MAX_PRODUCTS`] term products.
    pub fn checked_mul(&self, rhs: &Poly) -> Result<Poly, PolyError> {
        // A constant factor (δ and ε components, the 1 a product starts from) scales
        // every coefficient and keeps the order: no sort.
        match (self.terms.as_slice(), rhs.terms.as_slice()) {
            ([], _) | (_, []) => return Ok(Poly::zero()),
            ([(m, c)], _) if m.is_one() => return Ok(rhs.scaled(c)),
            (_, [(m, c)]) if m.is_one() => return Ok(self.scaled(c)),
            _ => {}
        }
        let count = self.terms.len().saturating_mul(rhs.terms.len());
        if count > MAX_PRODUCTS {
            return Err(PolyError::TooManyProducts);
        }
        let mut products = Vec::with_capacity(count);
        for (m1, c1) in &self.terms {
            // A row can be long (thousands of terms with coefficients of thousands of
            // digits): the claim's time limit may stop it here.
            super::interrupt::tick_by(rhs.terms.len());
            for (m2, c2) in &rhs.terms {
                let m = m1.checked_mul(m2).ok_or(PolyError::ExponentTooLarge)?;
                products.push((m, c1 * c2));
            }
        }
        Ok(Poly::from_terms(products))
    }

    /// Evaluates at a point; `None` when a negative power meets a zero value.
    pub fn eval(&self, value: &dyn Fn(Var) -> Rational) -> Option<Rational> {
        if self.terms.len() >= COMMON_DENOMINATOR_TERMS {
            if let Some(total) = self.eval_over_common_denominator(value) {
                return Some(total);
            }
        }
        self.eval_term_by_term(value)
    }

    /// [`Poly::eval`] one term at a time, each reduced: the cheapest way for a few
    /// terms, and the only one for negative exponents.
    fn eval_term_by_term(&self, value: &dyn Fn(Var) -> Rational) -> Option<Rational> {
        let mut total = Rational::zero();
        for (m, c) in &self.terms {
            let mut t = c.clone();
            for &(v, e) in m.factors() {
                t = &t * &value(v).pow(e)?;
            }
            total += &t;
        }
        Some(total)
    }

    /// [`Poly::eval`] over one denominator, `None` for a negative exponent or one
    /// above [`LADDER_TOP`] (every power up to it is kept): with
    /// xᵥ = nᵥ/dᵥ, Eᵥ the highest power of xᵥ and L the lcm of the coefficients'
    /// denominators, the value is Σ (L·c)·Π nᵥ^e·dᵥ^(Eᵥ−e) / (L·Π dᵥ^Eᵥ), every term an
    /// integer. One gcd at the end instead of several per term: a polynomial of a few
    /// hundred terms at 20-bit rationals evaluates several times faster.
    fn eval_over_common_denominator(&self, value: &dyn Fn(Var) -> Rational) -> Option<Rational> {
        use num_bigint::BigInt;
        use num_integer::Integer;
        // The variables (sorted) and their highest exponents.
        let mut highest: Vec<(Var, u32)> = Vec::new();
        for (m, _) in &self.terms {
            for &(v, e) in m.factors() {
                let e = u32::try_from(e).ok().filter(|&e| e <= LADDER_TOP)?;
                match highest.binary_search_by_key(&v, |&(w, _)| w) {
                    Ok(k) => highest[k].1 = highest[k].1.max(e),
                    Err(k) => highest.insert(k, (v, e)),
                }
            }
        }
        // nᵥ^k and dᵥ^k for k = 0 … Eᵥ.
        let powers: Vec<(Vec<BigInt>, Vec<BigInt>)> = highest
            .iter()
            .map(|&(v, top)| {
                let x = value(v);
                let ladder = |base: BigInt| {
                    let mut out = vec![BigInt::one()];
                    for k in 1..=top as usize {
                        let next = &out[k - 1] * &base;
                        out.push(next);
                    }
                    out
                };
                (ladder(x.numer()), ladder(x.denom()))
            })
            .collect();
        let lcm = self
            .terms
            .iter()
            .fold(BigInt::one(), |l, (_, c)| l.lcm(&c.denom()));
        let mut total = BigInt::zero();
        for (m, c) in &self.terms {
            let mut t = c.numer() * (&lcm / c.denom());
            let mut factors = m.factors().iter().peekable();
            for (&(v, top), (nums, dens)) in highest.iter().zip(&powers) {
                let e = match factors.peek() {
                    Some(&&(w, e)) if w == v => {
                        factors.next();
                        e as usize
                    }
                    _ => 0,
                };
                t *= &nums[e];
                t *= &dens[top as usize - e];
            }
            total += t;
        }
        let denominator = highest
            .iter()
            .zip(&powers)
            .fold(lcm, |d, (&(_, top), (_, dens))| d * &dens[top as usize]);
        Rational::from_big(total, denominator)
    }

    /// The exact average over a unit vector `n = (vars[0], …, vars[d-1])` uniformly
    /// distributed on the unit circle (d = 2) or sphere (d = 3): every monomial
    /// `n^α · rest` becomes `⟨n^α⟩ · rest`, with the moments of
    /// [`monomial_moment`]. Eqs. (25)–(26) are the first two instances.
    pub fn average_over_normal(&self, vars: &[Var]) -> Result<Poly, PolyError> {
        let mut out = Vec::with_capacity(self.terms.len());
        for (m, c) in &self.terms {
            let (exps, rest) = m.split(vars);
            if exps.iter().any(|&e| e < 0) {
                return Err(PolyError::NegativeNormalPower);
            }
            let exps: Vec<u32> = exps.iter().map(|&e| e as u32).collect();
            let moment = monomial_moment(vars.len(), &exps);
            if !moment.is_zero() {
                out.push((rest, c * &moment));
            }
        }
        Ok(Poly::from_terms(out))
    }

    /// The canonical normal form modulo `n·n − 1` (the normal is a unit vector).
    ///
    /// `{n·n − 1}` is a Gröbner basis of its ideal for any order in which the last
    /// component's square leads, so rewriting `n_d² → 1 − n_1² − … − n_{d−1}²` until no
    /// monomial contains `n_d²` yields the unique remainder. Two polynomials agree on
    /// the unit sphere (for all values of the other variables) iff their normal forms
    /// are identical: the sphere is Zariski-dense in the complex variety of the
    /// irreducible `n·n − 1` for d ≥ 2.
    pub fn reduce_on_sphere(&self, vars: &[Var]) -> Result<Poly, PolyError> {
        let Some((&last, others)) = vars.split_last() else {
            return Ok(self.clone());
        };
        let mut out = Vec::with_capacity(self.terms.len());
        let mut stack: Vec<(Monomial, Rational)> = self.terms.clone();
        while let Some((m, c)) = stack.pop() {
            if vars.iter().any(|&v| m.exponent(v) < 0) {
                return Err(PolyError::NegativeNormalPower);
            }
            if m.exponent(last) < 2 {
                out.push((m, c));
                continue;
            }
            let lowered = m.mul(&Monomial::var(last, -2));
            for &v in others {
                stack.push((lowered.mul(&Monomial::var(v, 2)), -&c));
            }
            stack.push((lowered, c));
        }
        Ok(Poly::from_terms(out))
    }

    /// `self / d` when `d` divides `self` exactly, both ordinary polynomials (no
    /// negative exponent); `None` when it does not, or after `steps` steps. Division
    /// by the leading term in the graded order: with one divisor, a leading term it
    /// does not divide stays in the remainder, so the first such term decides.
    pub fn divide_exact(&self, d: &Poly, steps: usize) -> Option<Poly> {
        let ordinary = |p: &Poly| {
            p.terms
                .iter()
                .all(|(m, _)| m.0.iter().all(|&(_, e)| e >= 0))
        };
        if !ordinary(self) || !ordinary(d) {
            return None;
        }
        let (dm, dc) = d.leading()?;
        let (inverse, dc) = (dm.pow(-1)?, dc.clone());
        let mut rem = self.clone();
        let mut quot = Poly::zero();
        for _ in 0..steps {
            let Some((rm, rc)) = rem.leading() else {
                return Some(quot);
            };
            let m = rm.checked_mul(&inverse)?;
            if m.0.iter().any(|&(_, e)| e < 0) {
                return None;
            }
            let t = Poly::term(m, rc.checked_div(&dc)?);
            rem = &rem - &t.checked_mul(d).ok()?;
            quot += &t;
        }
        None
    }

    /// The leading term in graded lexicographic order (the first term displayed).
    pub fn leading(&self) -> Option<(&Monomial, &Rational)> {
        self.terms().min_by(|a, b| graded_lex_desc(a.0, b.0))
    }

    /// The terms in graded lexicographic order, largest first: the order of display.
    pub fn graded_terms(&self) -> Vec<(&Monomial, &Rational)> {
        let mut terms: Vec<_> = self.terms().collect();
        terms.sort_by(|a, b| graded_lex_desc(a.0, b.0));
        terms
    }

    /// Plain-text form with variable names, highest total degree first.
    pub fn display(&self, names: &VarTable) -> String {
        self.display_truncated(names, usize::MAX)
    }

    /// Like [`Poly::display`], showing at most `max_terms` leading terms and saying how
    /// many there are in all when some are left out.
    pub fn display_truncated(&self, names: &VarTable, max_terms: usize) -> String {
        let power = |name: &str, e: Exp| format!("{name}^{e}");
        let mut s = self.written(names, max_terms, &|c| c.to_string(), &power, "*");
        if self.terms.len() > max_terms {
            let _ = write!(s, " + … ({} terms in all)", self.terms.len());
        }
        s
    }

    /// The first `max_terms` terms, highest total degree first, each coefficient (when
    /// not 1) and power written by the given forms and joined by `times`.
    pub fn written(
        &self,
        names: &VarTable,
        max_terms: usize,
        coefficient: &dyn Fn(&Rational) -> String,
        power: &dyn Fn(&str, Exp) -> String,
        times: &str,
    ) -> String {
        if self.terms.is_empty() {
            return "0".into();
        }
        let mut s = String::new();
        for (k, (m, c)) in self.graded_terms().into_iter().take(max_terms).enumerate() {
            s.push_str(match (k, c.is_negative()) {
                (0, true) => "-",
                (0, false) => "",
                (_, true) => " - ",
                (_, false) => " + ",
            });
            let abs = if c.is_negative() { -c } else { c.clone() };
            let mut parts: Vec<String> = Vec::new();
            if !abs.is_one() || m.is_one() {
                parts.push(coefficient(&abs));
            }
            for &(v, e) in m.factors() {
                let name = names.name(v);
                parts.push(if e == 1 {
                    name.to_owned()
                } else {
                    power(name, e)
                });
            }
            s.push_str(&parts.join(times));
        }
        s
    }
}

/// The rational `s` with `s·p` in canonical associate form: coprime integer
/// coefficients, the leading term (graded lexicographic) positive; `None` for the
/// zero polynomial.
pub fn canonical_scale(p: &Poly) -> Option<Rational> {
    use num_bigint::BigInt;
    use num_integer::Integer;
    use num_traits::Signed;
    let (_, lead) = p.leading()?;
    let mut den_lcm = BigInt::one();
    let mut num_gcd = BigInt::zero();
    for (_, c) in p.terms() {
        den_lcm = den_lcm.lcm(&c.denom());
        num_gcd = num_gcd.gcd(&c.numer());
    }
    let mut scale = Rational::from_big(den_lcm, num_gcd.abs())?;
    if lead.is_negative() {
        scale = -scale;
    }
    Some(scale)
}

/// Graded lexicographic order, largest first: higher total degree first, then the
/// larger exponent of the earliest variable (`x^3 + 3*x^2*y + …`).
fn graded_lex_desc(a: &Monomial, b: &Monomial) -> std::cmp::Ordering {
    b.total_degree().cmp(&a.total_degree()).then_with(|| {
        let mut vars: Vec<Var> = a.0.iter().chain(&b.0).map(|&(v, _)| v).collect();
        vars.sort_unstable();
        vars.dedup();
        vars.iter()
            .map(|&v| b.exponent(v).cmp(&a.exponent(v)))
            .find(|o| o.is_ne())
            .unwrap_or(std::cmp::Ordering::Equal)
    })
}

impl Zero for Poly {
    fn zero() -> Self {
        Poly::default()
    }
    fn is_zero(&self) -> bool {
        self.terms.is_empty()
    }
}

impl One for Poly {
    fn one() -> Self {
        Poly::constant(Rational::one())
    }
}

/// Terms beyond which [`sort_by_monomial`] sorts keys instead of the terms themselves.
const SORT_BY_KEY_FROM: usize = 32;

/// Sorts terms by monomial. A long list is sorted as (key, position) pairs: the key
/// packs a monomial's first two factors so that a smaller key is a smaller monomial
/// (a missing factor packs as 0, below any factor, as a list that ends sorts before
/// one that goes on), and only equal keys compare the monomials. Moving 16-byte pairs
/// and comparing integers is what makes a product's sort cheap.
fn sort_by_monomial(terms: &mut Vec<(Monomial, Rational)>) {
    let keys: Option<Vec<(u64, u32)>> = (terms.len() > SORT_BY_KEY_FROM)
        .then(|| {
            terms
                .iter()
                .enumerate()
                .map(|(k, (m, _))| Some((m.sort_key()?, u32::try_from(k).ok()?)))
                .collect()
        })
        .flatten();
    let Some(mut keys) = keys else {
        terms.sort_unstable_by(|a, b| a.0.cmp(&b.0));
        return;
    };
    keys.sort_unstable_by(|a, b| {
        a.0.cmp(&b.0)
            .then_with(|| terms[a.1 as usize].0.cmp(&terms[b.1 as usize].0))
    });
    let mut sorted = Vec::with_capacity(terms.len());
    for (_, k) in keys {
        sorted.push(std::mem::replace(
            &mut terms[k as usize],
            (Monomial::one(), Rational::zero()),
        ));
    }
    *terms = sorted;
}

/// `a + sign·b` for sorted term lists: one linear merge, the result sorted.
/// `a` is owned or cloned term by term, so a borrowed sum copies each term once.
fn merge(
    a: impl ExactSizeIterator<Item = (Monomial, Rational)>,
    b: &[(Monomial, Rational)],
    negate_b: bool,
) -> Poly {
    let signed = |c: &Rational| if negate_b { -c } else { c.clone() };
    let mut out = Vec::with_capacity(a.len() + b.len());
    let mut b = b.iter().peekable();
    for (m, c) in a {
        while let Some((mb, cb)) = b.next_if(|(mb, _)| *mb < m) {
            out.push((mb.clone(), signed(cb)));
        }
        match b.next_if(|(mb, _)| *mb == m) {
            Some((_, cb)) => {
                let sum = if negate_b { &c - cb } else { &c + cb };
                if !sum.is_zero() {
                    out.push((m, sum));
                }
            }
            None => out.push((m, c)),
        }
    }
    out.extend(b.map(|(mb, cb)| (mb.clone(), signed(cb))));
    Poly { terms: out }
}

impl Add<&Poly> for &Poly {
    type Output = Poly;
    fn add(self, rhs: &Poly) -> Poly {
        merge(self.terms.iter().cloned(), &rhs.terms, false)
    }
}

impl AddAssign<&Poly> for Poly {
    fn add_assign(&mut self, rhs: &Poly) {
        if let [(m, c)] = rhs.terms.as_slice() {
            self.add_term(m.clone(), c.clone());
        } else if !rhs.terms.is_empty() {
            *self = merge(
                std::mem::take(&mut self.terms).into_iter(),
                &rhs.terms,
                false,
            );
        }
    }
}

impl Sub<&Poly> for &Poly {
    type Output = Poly;
    fn sub(self, rhs: &Poly) -> Poly {
        merge(self.terms.iter().cloned(), &rhs.terms, true)
    }
}

/// Panics (never wraps) when an exponent leaves [`MAX_EXPONENT`]: evaluation of input
/// multiplies with [`Poly::checked_mul`].
impl Mul<&Poly> for &Poly {
    type Output = Poly;
    fn mul(self, rhs: &Poly) -> Poly {
        self.checked_mul(rhs).unwrap_or_else(|e| beyond(e))
    }
}

impl Neg for &Poly {
    type Output = Poly;
    fn neg(self) -> Poly {
        Poly {
            terms: self.terms.iter().map(|(m, c)| (m.clone(), -c)).collect(),
        }
    }
}

impl Add for Poly {
    type Output = Poly;
    fn add(self, rhs: Poly) -> Poly {
        merge(self.terms.into_iter(), &rhs.terms, false)
    }
}

impl Sub for Poly {
    type Output = Poly;
    fn sub(self, rhs: Poly) -> Poly {
        merge(self.terms.into_iter(), &rhs.terms, true)
    }
}

impl Mul for Poly {
    type Output = Poly;
    fn mul(self, rhs: Poly) -> Poly {
        &self * &rhs
    }
}

impl Neg for Poly {
    type Output = Poly;
    fn neg(mut self) -> Poly {
        for (_, c) in &mut self.terms {
            *c = -&*c;
        }
        self
    }
}

/// Helpers of the unit tests of polynomials.
#[cfg(test)]
pub(crate) mod testing {
    use super::{Poly, Rational, VarTable};

    pub(crate) fn q(n: i64, d: i64) -> Rational {
        Rational::ratio(n, d).unwrap()
    }

    /// A deterministic stream (xorshift from `seed`) of numbers below the argument.
    pub(crate) fn below(mut seed: u64) -> impl FnMut(u64) -> u64 {
        move |m: u64| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed % m
        }
    }

    /// Variables of these names, as polynomials, and their table.
    pub(crate) fn vars(names: &[&str]) -> (VarTable, Vec<Poly>) {
        let mut t = VarTable::new();
        let ps = names.iter().map(|n| Poly::var(t.intern(n))).collect();
        (t, ps)
    }
}

#[cfg(test)]
mod tests {
    use super::testing::{below, q, vars};
    use super::*;

    /// Evaluation over one denominator agrees with term-by-term evaluation: random
    /// polynomials of 8–40 terms (small and 30-digit coefficients, in some rounds a
    /// negative exponent, exponents up to 70 so that the ladder's limit
    /// is crossed) at random rational points, zero included. A wrong power or a lost
    /// lcm factor changes values, so this refutes them.
    #[test]
    fn evaluation_over_one_denominator_agrees_term_by_term() {
        let mut next = below(0x2545_F491_4F6C_DD1D);
        let big = Rational::from_big(
            "123456789012345678901234567890".parse().unwrap(),
            "7".parse().unwrap(),
        )
        .unwrap();
        let mut over_one = 0;
        for round in 0..300 {
            let mut p = Poly::zero();
            for _ in 0..(8 + next(33)) {
                let top = if round % 10 == 0 { 71 } else { 7 };
                let m = Monomial::from_factors(
                    (0..4)
                        .map(|k| {
                            let e = next(top) as Exp;
                            let negative = round % 5 == 1 && next(40) == 0;
                            (k as Var, if negative { -e } else { e })
                        })
                        .collect(),
                );
                let c = match next(6) {
                    0 => &big * &q(next(5) as i64 + 1, 1),
                    _ => q(next(19) as i64 - 9, 1 + next(12) as i64),
                };
                p.add_term(m, c);
            }
            let point: Vec<Rational> = (0..4)
                .map(|_| match next(8) {
                    0 => Rational::zero(),
                    _ => q(next(2001) as i64 - 1000, 1 + next(1 << 20) as i64),
                })
                .collect();
            let value = |v: Var| point[v as usize].clone();
            over_one += usize::from(p.eval_over_common_denominator(&value).is_some());
            assert_eq!(p.eval(&value), p.eval_term_by_term(&value), "{round}");
        }
        assert!(over_one > 150, "{over_one}");
    }

    #[test]
    fn equal_polynomials_have_identical_representations() {
        let (_, v) = vars(&["x", "y"]);
        let (x, y) = (&v[0], &v[1]);
        let lhs = &(x + y) * &(x - y);
        let rhs = &(x * x) - &(y * y);
        assert_eq!(lhs, rhs);
        assert_eq!(format!("{lhs:?}"), format!("{rhs:?}"));
        // Built in a different order, still identical.
        let rhs2 = &(&(y * y) * &Poly::constant(q(-1, 1))) + &(x * x);
        assert_eq!(lhs, rhs2);
    }

    /// The sorted-vector representation against a reference model: a `BTreeMap` from
    /// factor lists to coefficients, which is what the kernel kept before. Sums,
    /// differences and products of random Laurent polynomials (monomials of up to 7
    /// factors, beyond the inline capacity; many cancellations) agree term by term and
    /// in the same order, so everything that iterates terms (printing, pivots, leading
    /// terms) sees what it saw before. Each operation is also built a second way, one
    /// term at a time in reverse order, and compared structurally.
    #[test]
    fn operations_agree_with_a_tree_map_model() {
        use std::collections::BTreeMap;
        type Model = BTreeMap<Vec<(Var, Exp)>, Rational>;
        let mut next = below(0x2545_F491_4F6C_DD1D);
        let random = |next: &mut dyn FnMut(u64) -> u64| -> Vec<(Vec<(Var, Exp)>, Rational)> {
            let mut terms = Vec::new();
            for _ in 0..next(9) {
                let mut factors = Vec::new();
                for v in 0..7 {
                    if next(3) == 0 {
                        factors.push((v as Var, next(5) as Exp - 1));
                    }
                }
                terms.push((factors, q(next(7) as i64 - 3, 1 + next(3) as i64)));
            }
            terms
        };
        let model_add = |model: &mut Model, f: &[(Var, Exp)], c: &Rational, sign: i64| {
            let m = Monomial::from_factors(f.to_vec()).factors().to_vec();
            let sum =
                model.get(&m).cloned().unwrap_or_else(Rational::zero) + c * &Rational::int(sign);
            if sum.is_zero() {
                model.remove(&m);
            } else {
                model.insert(m, sum);
            }
        };
        let same = |p: &Poly, model: &Model| {
            let ours: Vec<(Vec<(Var, Exp)>, Rational)> = p
                .terms()
                .map(|(m, c)| (m.factors().to_vec(), c.clone()))
                .collect();
            let want: Vec<(Vec<(Var, Exp)>, Rational)> = model.clone().into_iter().collect();
            assert_eq!(ours, want);
        };
        for _ in 0..300 {
            let (ta, tb) = (random(&mut next), random(&mut next));
            let build = |t: &[(Vec<(Var, Exp)>, Rational)]| {
                Poly::from_terms(
                    t.iter()
                        .map(|(f, c)| (Monomial::from_factors(f.clone()), c.clone())),
                )
            };
            let (a, b) = (build(&ta), build(&tb));
            let mut model_a = Model::new();
            for (f, c) in &ta {
                model_add(&mut model_a, f, c, 1);
            }
            same(&a, &model_a);
            // Sum and difference.
            for sign in [1, -1] {
                let mut model = model_a.clone();
                for (f, c) in &tb {
                    model_add(&mut model, f, c, sign);
                }
                let op = if sign == 1 { &a + &b } else { &a - &b };
                same(&op, &model);
                let mut by_terms = a.clone();
                for (f, c) in tb.iter().rev() {
                    by_terms.add_term(Monomial::from_factors(f.clone()), c * &Rational::int(sign));
                }
                assert_eq!(by_terms, op);
                if sign == 1 {
                    let mut assigned = a.clone();
                    assigned += &b;
                    assert_eq!(assigned, op);
                }
            }
            // Product, and the constant fast path against the general one.
            let mut model = Model::new();
            for (fa, ca) in &ta {
                for (fb, cb) in &tb {
                    let mut f = fa.clone();
                    f.extend_from_slice(fb);
                    model_add(&mut model, &f, &(ca * cb), 1);
                }
            }
            same(&(&a * &b), &model);
            let k = Poly::constant(q(-5, 3));
            let general = Poly::from_terms(a.terms().map(|(m, c)| (m.clone(), c * &q(-5, 3))));
            assert_eq!(&a * &k, general);
            assert_eq!(&k * &a, general);
            assert_eq!(&a * &Poly::one(), a);
        }
    }

    /// Long term lists are sorted by packed keys of the first two factors. Monomials
    /// that tie on the key (differing from the third factor on), that are prefixes of
    /// others, with negative exponents, and ones whose variable or exponent does not
    /// fit a key (the plain sort then) all come out strictly increasing, as the plain
    /// sort orders them, with every coefficient kept.
    #[test]
    fn key_sort_orders_long_lists_as_the_plain_sort() {
        let mut next = below(0x9E37_79B9_7F4A_7C15);
        for wide in [false, true] {
            let vars: &[Var] = if wide {
                &[0, 1, 2, 70_000]
            } else {
                &[0, 1, 2, 3]
            };
            let exps: &[Exp] = if wide {
                &[-40_000, -1, 1, 2]
            } else {
                &[-2, -1, 1, 2]
            };
            let terms: Vec<(Monomial, Rational)> = (0..300)
                .map(|k| {
                    let mut factors = Vec::new();
                    for &v in vars {
                        if next(2) == 0 {
                            factors.push((v, exps[next(4) as usize]));
                        }
                    }
                    (Monomial::from_factors(factors), Rational::int(k + 1))
                })
                .collect();
            let p = Poly::from_terms(terms.clone());
            assert!(p.terms.windows(2).all(|w| w[0].0 < w[1].0));
            let mut plain = terms;
            plain.sort_by(|a, b| a.0.cmp(&b.0));
            let mut expected: Vec<(Monomial, Rational)> = Vec::new();
            for (m, c) in plain {
                match expected.last_mut() {
                    Some((last, sum)) if *last == m => *sum += &c,
                    _ => expected.push((m, c)),
                }
            }
            assert_eq!(p.terms, expected);
        }
    }

    #[test]
    fn cancellation_leaves_no_zero_terms() {
        let (_, v) = vars(&["x"]);
        let z = &v[0] - &v[0];
        assert!(z.is_zero());
        assert_eq!(z.num_terms(), 0);
        assert_eq!(z, Poly::zero());
    }

    #[test]
    fn binomial_expansion() {
        let (names, v) = vars(&["x", "y"]);
        let p = (&v[0] + &v[1]).pow(3);
        assert_eq!(p.num_terms(), 4);
        assert_eq!(p.display(&names), "x^3 + 3*x^2*y + 3*x*y^2 + y^3");
    }

    #[test]
    fn division_by_a_term_is_exact_and_by_a_sum_refused() {
        let (names, v) = vars(&["S", "V", "R"]);
        let (s, vv, r) = (&v[0], &v[1], &v[2]);
        let two_r = &Poly::constant(q(2, 1)) * r;
        let ratio = (&two_r * s).checked_div(vv).unwrap();
        assert_eq!(ratio.display(&names), "2*S*V^-1*R");
        assert_eq!(&ratio * vv, &two_r * s);
        assert_eq!(s.checked_div(&(s + vv)), Err(PolyError::DivisionBySum));
        assert_eq!(s.checked_div(&Poly::zero()), Err(PolyError::DivisionByZero));
    }

    #[test]
    fn sphere_reduction_is_canonical() {
        let (mut names, v) = vars(&["n1", "n2", "n3"]);
        let n: Vec<Var> = (0..3).map(|k| k as Var).collect();
        let norm2 = &(&(&v[0] * &v[0]) + &(&v[1] * &v[1])) + &(&v[2] * &v[2]);
        let a = names.intern("a");
        let pa = Poly::var(a);
        // a (n·n)^2 ≡ a on the sphere.
        let lhs = (&pa * &norm2.pow(2)).reduce_on_sphere(&n).unwrap();
        assert_eq!(lhs, pa);
        // n3^4 reduces to a polynomial without n3^2.
        let r = v[2].pow(4).reduce_on_sphere(&n).unwrap();
        assert!(r.terms().all(|(m, _)| m.exponent(2) < 2));
        // … and it agrees with n3^4 on a rational point of the sphere (2/3, 2/3, 1/3).
        let pt = [q(2, 3), q(2, 3), q(1, 3)];
        let val = |w: Var| pt[w as usize].clone();
        assert_eq!(r.eval(&val), v[2].pow(4).eval(&val));
        // n·n − 1 vanishes on the sphere; n·n does not, and keeps a nonzero normal form.
        assert!((&norm2 - &Poly::one())
            .reduce_on_sphere(&n)
            .unwrap()
            .is_zero());
        assert!(!norm2.reduce_on_sphere(&n).unwrap().is_zero());
    }

    #[test]
    fn averages_use_exact_moments() {
        let (_, v) = vars(&["n1", "n2", "n3"]);
        let n: Vec<Var> = (0..3).map(|k| k as Var).collect();
        assert_eq!(
            v[0].pow(2).average_over_normal(&n).unwrap(),
            Poly::constant(q(1, 3))
        );
        assert_eq!(
            v[0].pow(4).average_over_normal(&n).unwrap(),
            Poly::constant(q(1, 5))
        );
        assert_eq!(
            (&v[0].pow(2) * &v[1].pow(2))
                .average_over_normal(&n)
                .unwrap(),
            Poly::constant(q(1, 15))
        );
        assert!(v[0].pow(3).average_over_normal(&n).unwrap().is_zero());
    }

    /// The average of a product, formed pair by pair of equal parity, is the product
    /// averaged: random polynomials in n (2 or 3 components) and two other variables,
    /// with powers of n up to 5 and of the others from −1 to 2; and a negative power of
    /// n gives the product's own error.
    #[test]
    fn derivatives_are_exact() {
        let (names, v) = vars(&["x", "y"]);
        let p = &(&v[0].pow(3) * &v[1]) - &Poly::constant(q(5, 1));
        assert_eq!(p.derivative(0).display(&names), "3*x^2*y");
        assert_eq!(p.derivative(1).display(&names), "x^3");
        let inv = Poly::one().checked_div(&v[0]).unwrap();
        assert_eq!(inv.derivative(0).display(&names), "-x^-2");
        assert!(Poly::constant(q(7, 2)).derivative(0).is_zero());
    }

    #[test]
    fn evaluation_at_a_point() {
        let (_, v) = vars(&["x", "y"]);
        let p = &(&v[0] * &v[0]) - &Poly::constant(q(1, 2));
        let val = |w: Var| if w == 0 { q(3, 1) } else { q(0, 1) };
        assert_eq!(p.eval(&val), Some(q(17, 2)));
        let inv = Poly::one().checked_div(&v[1]).unwrap();
        assert_eq!(inv.eval(&val), None);
    }
}
