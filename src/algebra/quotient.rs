//! Quotients of polynomials as exact evaluation builds them: a Laurent polynomial
//! numerator over a product of polynomial factors, each factor a divisor the statement
//! divided by (`3*lambda + 2*G`), kept apart and never multiplied out.
//!
//! Unlike [`RatFunc`], a quotient is not reduced after every operation
//! (no gcd): a product concatenates the factor lists, a sum brings both terms over the
//! least common multiple of the two lists, matched structurally. Equality is therefore
//! not structural; it is decided by [`Identities::compare`](super::certificate::Identities::compare),
//! which clears the denominators and compares canonical polynomials. Because the
//! factors stay apart, the set where a statement is defined is read off directly: every
//! factor ≠ 0.
//!
//! A polynomial is a quotient with no factors, and costs nothing more: the statements
//! that never divide by a sum compute exactly as with [`Poly`].

use super::einsum::{Arithmetic, OverBudget};
use super::gcd::{canonical_scale, clear_denominator_monomial, divide_exact, monomial_content};
use super::ratfunc::RatFunc;
use super::residue;
use crate::kernel::poly::{beyond, Monomial, Poly, PolyError, Var, VarTable};
use crate::kernel::rational::Rational;
use num_traits::One;
use std::sync::Arc;

/// `num / Π factor^multiplicity`. Every factor is an ordinary polynomial of at least
/// two terms, with no monomial content, in canonical associate form (coprime integer
/// coefficients, positive leading term), so that equal divisors are recognised
/// structurally.
///
/// ```
/// use cosserat_algebra::quotient::Quotients;
/// use cosserat_kernel::{Poly, Rational, VarTable};
/// use cosserat_algebra::Quotient;
/// use cosserat_algebra::einsum::Arithmetic;
/// let mut names = VarTable::new();
/// let (l, g) = (Poly::var(names.intern("lambda")), Poly::var(names.intern("G")));
/// let three = Poly::constant(Rational::int(3));
/// let two = Poly::constant(Rational::int(2));
/// let sum = Quotient::from(&(&three * &l) + &(&two * &g));
/// // 6 G / (6 lambda + 4 G): the divisor's scale and content leave the factor.
/// let q = Quotient::from(&(&three * &g) * &two).divide(&Quotient::from(&sum.numerator().clone() * &two)).unwrap();
/// assert_eq!(q.display(&names), "3*G / (3*lambda + 2*G)");
/// let mut work = 1_000;
/// let s = Quotients { work_left: &mut work }.add(q.clone(), q).unwrap();
/// assert_eq!(s.display(&names), "6*G / (3*lambda + 2*G)");
/// ```
#[derive(Clone, Debug, Default)]
pub struct Quotient {
    num: Poly,
    /// `None` for a polynomial that never divided by anything: the common case stays
    /// one pointer wider than a [`Poly`]. Shared between clones (a definition's
    /// value is cloned at every use), copied only when an operation changes it.
    rest: Option<Arc<Rest>>,
}

#[derive(Clone, Debug, Default, PartialEq)]
struct Rest {
    den: Vec<(Poly, u32)>,
    /// Every factor this value was ever divided by, cancelled or not, and every
    /// variable of a single-term divisor: where one of them vanishes, the expression
    /// that built the value is undefined.
    conditions: Vec<Poly>,
}

/// A quotient with its parts laid open, for the operations that change them.
#[derive(Clone, Debug, Default)]
struct Open {
    num: Poly,
    den: Vec<(Poly, u32)>,
    conditions: Vec<Poly>,
}

impl Open {
    fn close(self) -> Quotient {
        let rest = (!(self.den.is_empty() && self.conditions.is_empty())).then(|| {
            Arc::new(Rest {
                den: self.den,
                conditions: self.conditions,
            })
        });
        Quotient {
            num: self.num,
            rest,
        }
    }
}

/// Why a division could not be carried out.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum DivideError {
    /// The divisor is identically zero.
    #[error("division by an identically zero divisor")]
    ByZero,
}

impl From<Poly> for Quotient {
    fn from(num: Poly) -> Self {
        Quotient { num, rest: None }
    }
}

/// Adds the factors of `from` missing in `to`.
fn union(to: &mut Vec<Poly>, from: &[Poly]) {
    for f in from {
        if !to.contains(f) {
            to.push(f.clone());
        }
    }
}

impl Quotient {
    /// The square root of a perfect square of a rational function, up to sign: `r`
    /// with `r·r = self` (see [`super::polynomial::sqrt`]), defined where `self` is. A
    /// factor of odd multiplicity is first multiplied into the numerator and the
    /// denominator, so that every multiplicity is even; the value is then a square
    /// exactly when the numerator is. `None`: not a square (or its root's numerator
    /// would pass `max_terms`).
    pub fn sqrt_exact(&self, max_terms: usize) -> Option<Quotient> {
        let mut num = self.num.clone();
        let mut den = Vec::with_capacity(self.factors().len());
        for (f, m) in self.factors() {
            if m % 2 == 1 {
                num = &num * f;
            }
            den.push((f.clone(), m.div_ceil(2)));
        }
        Some(
            Open {
                num: super::polynomial::sqrt(&num, max_terms)?,
                den,
                conditions: self.conditions().to_vec(),
            }
            .close(),
        )
    }

    /// The same value, defined only where `extra` are nonzero too: a component of a
    /// definition is defined where the whole definition is.
    ///
    /// Consumes the value, and leaves it as it is when it already has every condition
    /// (each component of a definition has its own, usually most of them): the
    /// numerator is moved, never copied.
    pub fn with_conditions(self, extra: &[Poly]) -> Quotient {
        if extra.iter().all(|f| self.conditions().contains(f)) {
            return self;
        }
        let mut open = self.into_open();
        union(&mut open.conditions, extra);
        open.close()
    }

    /// The quotient as a reduced rational function.
    pub fn to_ratfunc(&self) -> RatFunc {
        let den = self
            .factors()
            .iter()
            .fold(Poly::one(), |acc, (f, k)| &acc * &f.pow(*k));
        RatFunc::new(&self.num, &den).expect("a product of nonzero factors")
    }

    /// The numerator (a Laurent polynomial).
    pub fn numerator(&self) -> &Poly {
        &self.num
    }

    /// The denominator's factors with their multiplicities (empty for a polynomial).
    pub fn factors(&self) -> &[(Poly, u32)] {
        self.rest.as_ref().map_or(&[], |r| &r.den)
    }

    /// Every factor the value was divided by on its way, including those that
    /// cancelled, and the variables of single-term divisors: the value is defined
    /// where each of them is nonzero.
    pub fn conditions(&self) -> &[Poly] {
        self.rest.as_ref().map_or(&[], |r| &r.conditions)
    }

    /// The polynomial, when there is no denominator.
    pub fn as_poly(&self) -> Option<&Poly> {
        self.factors().is_empty().then_some(&self.num)
    }

    fn open(&self) -> Open {
        self.clone().into_open()
    }

    fn into_open(self) -> Open {
        let rest = self.rest.map(Arc::unwrap_or_clone).unwrap_or_default();
        Open {
            num: self.num,
            den: rest.den,
            conditions: rest.conditions,
        }
    }

    /// Whether the quotient is exactly zero (its numerator is the zero polynomial; the
    /// denominator is a product of nonzero polynomials).
    pub fn is_zero(&self) -> bool {
        self.num.is_zero()
    }

    /// Whether the quotient is zero wherever anything is defined: zero with no
    /// condition. A zero with conditions (0/R_g² at M = 0) is undefined where they
    /// vanish, so a sum or product must not drop it.
    pub fn is_exact_zero(&self) -> bool {
        self.num.is_zero() && self.conditions().is_empty()
    }

    /// The value when it is a constant polynomial.
    pub fn as_constant(&self) -> Option<Rational> {
        self.as_poly()?.as_constant()
    }

    /// Every variable of the numerator, the factors and the conditions, sorted.
    pub fn variables(&self) -> Vec<Var> {
        let mut vars: Vec<Var> = std::iter::once(&self.num)
            .chain(self.factors().iter().map(|(f, _)| f))
            .chain(self.conditions())
            .flat_map(Poly::variables)
            .collect();
        vars.sort_unstable();
        vars.dedup();
        vars
    }

    /// The value at a point; `None` where the expression that built it is undefined:
    /// a condition (a divisor, cancelled or not) or a negative power is zero there.
    pub fn eval(&self, value: &dyn Fn(Var) -> Rational) -> Option<Rational> {
        for f in self.conditions() {
            if f.eval(value)?.is_zero() {
                return None;
            }
        }
        let mut den = Rational::one();
        for (f, k) in self.factors() {
            den = &den * &f.eval(value)?.pow(i64::from(*k))?;
        }
        self.num.eval(value)?.checked_div(&den)
    }

    /// The same denominator and conditions over another numerator: the result of a
    /// map that commutes with division by the factors (a derivative or an average by
    /// variables the factors do not contain).
    pub fn with_numerator(&self, num: Poly) -> Quotient {
        Quotient {
            num,
            rest: self.rest.clone(),
        }
    }

    /// `self^k`.
    pub fn pow(&self, k: u32) -> Quotient {
        // The zeroth power keeps no divisor (a factor of multiplicity 0 would be
        // cancelled below zero later), only the conditions where the base is defined.
        Open {
            num: self.num.pow(k),
            den: (self.factors().iter())
                .filter(|_| k > 0)
                .map(|(f, m)| {
                    let m = m
                        .checked_mul(k)
                        .unwrap_or_else(|| beyond(PolyError::ExponentTooLarge));
                    (f.clone(), m)
                })
                .collect(),
            conditions: self.conditions().to_vec(),
        }
        .tidy()
        .close()
    }

    /// `self / d`. A single-term divisor divides the numerator (a Laurent polynomial);
    /// any other is split into a scale, a monomial and a canonical factor, which joins
    /// the denominator (its own factors move to the numerator, cancelling where they
    /// can).
    pub fn divide(&self, d: &Quotient) -> Result<Quotient, DivideError> {
        if d.num.is_zero() {
            return Err(DivideError::ByZero);
        }
        Ok(self.open().divide(d).close())
    }

    /// Plain text: the numerator, then ` / ` and the factors when there are any.
    pub fn display(&self, names: &VarTable) -> String {
        self.display_truncated(names, usize::MAX)
    }

    /// Like [`Poly::display_truncated`], with the factors in full.
    pub fn display_truncated(&self, names: &VarTable, max_terms: usize) -> String {
        over(&self.num, self.factors(), names, max_terms)
    }
}

impl Open {
    /// See [`Quotient::divide`]; `d` is not zero.
    fn divide(self, d: &Quotient) -> Open {
        let mut out = self;
        union(&mut out.conditions, d.conditions());
        for (f, k) in d.factors() {
            for _ in 0..*k {
                out.multiply_by_factor(f);
            }
        }
        if d.num.num_terms() == 1 {
            out.num = out
                .num
                .checked_div(&d.num)
                .expect("a nonzero single term divides");
            // Its variables must not vanish either, though they stay in the
            // numerator as negative powers.
            let (m, _) = d.num.terms().next().expect("one term");
            union(&mut out.conditions, &monomial_vars(m));
            return out.tidy();
        }
        // d = q / m with q ordinary; q = c · factor / s with c its monomial content.
        let (q, m) = clear_denominator_monomial(&d.num);
        let content = monomial_content(&q);
        let q = q
            .checked_div(&Poly::term(content.clone(), Rational::one()))
            .expect("a monomial divides");
        union(&mut out.conditions, &monomial_vars(&content));
        let s = canonical_scale(&q).expect("a divisor with two terms is nonzero");
        let factor = &q * &Poly::constant(s.clone());
        // x / d = x · s · m / (c · factor).
        let unit = Poly::term(m, s);
        out.num = (&out.num * &unit)
            .checked_div(&Poly::term(content, Rational::one()))
            .expect("a monomial divides");
        union(&mut out.conditions, std::slice::from_ref(&factor));
        match out.den.iter_mut().find(|(f, _)| *f == factor) {
            Some((_, k)) => *k += 1,
            None => out.den.push((factor, 1)),
        }
        out.tidy()
    }

    /// Multiplies by one factor: cancels it from the denominator when it is there.
    fn multiply_by_factor(&mut self, f: &Poly) {
        match self.den.iter().position(|(g, _)| g == f) {
            Some(i) => {
                self.den[i].1 -= 1;
                if self.den[i].1 == 0 {
                    self.den.remove(i);
                }
            }
            None => self.num = &self.num * f,
        }
    }

    /// Cancels every factor that divides the numerator exactly, and drops the
    /// denominator of zero.
    fn tidy(self) -> Open {
        self.tidy_from(0)
    }

    /// [`Open::tidy`] for a value whose factors before `start` are known not to
    /// divide the numerator.
    fn tidy_from(mut self, start: usize) -> Open {
        if self.num.is_zero() {
            self.den.clear();
            return self;
        }
        if self.num.num_terms() > TIDY_TERMS {
            return self;
        }
        let mut k = start;
        while k < self.den.len() {
            match divide_laurent(&self.num, &self.den[k].0) {
                Some(q) => {
                    self.num = q;
                    self.den[k].1 -= 1;
                    if self.den[k].1 == 0 {
                        self.den.remove(k);
                    }
                }
                None => k += 1,
            }
        }
        self
    }

    /// The least common multiple of two factor lists, and what each list lacks of it.
    fn common(a: &[(Poly, u32)], b: &[(Poly, u32)]) -> CommonDenominator {
        let mut lcm: Vec<(Poly, u32)> = a.to_vec();
        let mut a_lacks = Vec::new();
        let mut b_lacks = Vec::new();
        for (f, kb) in b {
            match lcm.iter_mut().find(|(g, _)| g == f) {
                Some((_, ka)) => {
                    if *kb > *ka {
                        a_lacks.push((f.clone(), *kb - *ka));
                        *ka = *kb;
                    }
                }
                None => {
                    a_lacks.push((f.clone(), *kb));
                    lcm.push((f.clone(), *kb));
                }
            }
        }
        for (f, ka) in &lcm {
            let kb = b.iter().find(|(g, _)| g == f).map_or(0, |(_, k)| *k);
            if *ka > kb {
                b_lacks.push((f.clone(), ka - kb));
            }
        }
        CommonDenominator {
            lcm,
            a_lacks,
            b_lacks,
        }
    }
}

/// `num / (factors)` in plain text; just `num` when there are no factors.
pub fn over(num: &Poly, factors: &[(Poly, u32)], names: &VarTable, max_terms: usize) -> String {
    let shown = num.display_truncated(names, max_terms);
    if factors.is_empty() {
        return shown;
    }
    let num = if num.num_terms() > 1 {
        format!("({shown})")
    } else {
        shown
    };
    let parts: Vec<String> = factors
        .iter()
        .map(|(f, k)| match k {
            1 => format!("({})", f.display(names)),
            _ => format!("({})^{k}", f.display(names)),
        })
        .collect();
    match parts.as_slice() {
        [one] => format!("{num} / {one}"),
        _ => format!("{num} / ({})", parts.join(" ")),
    }
}

struct CommonDenominator {
    lcm: Vec<(Poly, u32)>,
    a_lacks: Vec<(Poly, u32)>,
    b_lacks: Vec<(Poly, u32)>,
}

/// `p / f` for a Laurent `p` and an ordinary `f`, when `f` divides exactly.
fn divide_laurent(p: &Poly, f: &Poly) -> Option<Poly> {
    if p.terms()
        .all(|(m, _)| m.factors().iter().all(|&(_, e)| e >= 0))
    {
        return divide_exact(p, f);
    }
    let (q, m) = clear_denominator_monomial(p);
    let r = divide_exact(&q, f)?;
    Some(
        r.checked_div(&Poly::term(m, Rational::one()))
            .expect("a monomial divides"),
    )
}

/// The variables of a monomial, each as a polynomial.
fn monomial_vars(m: &Monomial) -> Vec<Poly> {
    m.factors().iter().map(|&(v, _)| Poly::var(v)).collect()
}

/// Quotients under a work budget: every product of polynomials is charged its term
/// count, as in [`Polynomials`](super::einsum::Polynomials).
pub struct Quotients<'b> {
    pub work_left: &'b mut usize,
}

impl Quotients<'_> {
    fn product(&mut self, a: &Poly, b: &Poly) -> Result<Poly, OverBudget> {
        let cost = a.num_terms().saturating_mul(b.num_terms());
        *self.work_left = self.work_left.checked_sub(cost).ok_or(OverBudget)?;
        // An exponent beyond the kernel's bound is a resource limit like the budget.
        a.checked_mul(b).map_err(|_| OverBudget)
    }

    /// `p · Π factors`, charged.
    fn times(&mut self, mut p: Poly, factors: &[(Poly, u32)]) -> Result<Poly, OverBudget> {
        for (f, k) in factors {
            for _ in 0..*k {
                p = self.product(&p, f)?;
            }
        }
        Ok(p)
    }
}

impl Arithmetic for Quotients<'_> {
    type Value = Quotient;
    type Error = OverBudget;
    fn zero(&mut self) -> Quotient {
        Quotient::default()
    }
    fn one(&mut self) -> Quotient {
        Quotient::from(Poly::one())
    }
    fn is_exact_zero(&self, x: &Quotient) -> bool {
        x.is_exact_zero()
    }
    /// `1 · x` is `x` when `x` is a polynomial, charged as the product (`1 · |x|`).
    fn first(&mut self, x: &Quotient) -> Result<Quotient, OverBudget> {
        if x.rest.is_some() {
            let one = self.one();
            return self.mul(one, x);
        }
        *self.work_left = self
            .work_left
            .checked_sub(x.num.num_terms())
            .ok_or(OverBudget)?;
        Ok(x.clone())
    }
    fn mul(&mut self, a: Quotient, b: &Quotient) -> Result<Quotient, OverBudget> {
        let num = self.product(&a.num, &b.num)?;
        match (&a.rest, &b.rest) {
            (None, None) => return Ok(Quotient::from(num)),
            // One side a polynomial: the other's denominator and conditions, shared
            // unless a factor cancels (the factor lists hold distinct factors, so this
            // is the general case below without the copies).
            (Some(r), None) | (None, Some(r)) => return Ok(keeping(num, Arc::clone(r))),
            (Some(_), Some(_)) => {}
        }
        let a = a.into_open();
        let mut out = Open {
            num,
            den: a.den,
            conditions: a.conditions,
        };
        union(&mut out.conditions, b.conditions());
        for (f, k) in b.factors() {
            match out.den.iter_mut().find(|(g, _)| g == f) {
                Some((_, m)) => *m += k,
                None => out.den.push((f.clone(), *k)),
            }
        }
        Ok(out.tidy().close())
    }
    fn add(&mut self, a: Quotient, b: Quotient) -> Result<Quotient, OverBudget> {
        if a.rest.is_none() && b.rest.is_none() {
            let mut num = a.num;
            num += &b.num;
            return Ok(Quotient::from(num));
        }
        // One side a polynomial, or both over the same factors with the same
        // conditions: the common denominator is the other's (or theirs), shared unless
        // a factor cancels. This is the general case below without the copies.
        let shared = match (&a.rest, &b.rest) {
            (Some(r), None) | (None, Some(r)) => Some(Arc::clone(r)),
            (Some(r), Some(s)) if Arc::ptr_eq(r, s) || r == s => Some(Arc::clone(r)),
            (Some(_), Some(_)) | (None, None) => None,
        };
        if let Some(rest) = shared {
            let none: &[(Poly, u32)] = &[];
            let (a_lacks, b_lacks) = match (&a.rest, &b.rest) {
                (None, _) => (rest.den.as_slice(), none),
                (_, None) => (none, rest.den.as_slice()),
                _ => (none, none),
            };
            let mut num = self.times(a.num, a_lacks)?;
            num += &self.times(b.num, b_lacks)?;
            return Ok(keeping(num, rest));
        }
        let (a, b) = (a.into_open(), b.into_open());
        let mut conditions = a.conditions;
        union(&mut conditions, &b.conditions);
        if a.den.is_empty() && b.den.is_empty() {
            let mut num = a.num;
            num += &b.num;
            return Ok(Open {
                num,
                den: Vec::new(),
                conditions,
            }
            .close());
        }
        let common = Open::common(&a.den, &b.den);
        let mut num = self.times(a.num, &common.a_lacks)?;
        num += &self.times(b.num, &common.b_lacks)?;
        Ok(Open {
            num,
            den: common.lcm,
            conditions,
        }
        .tidy()
        .close())
    }
}

impl std::ops::Neg for Quotient {
    type Output = Quotient;
    fn neg(self) -> Quotient {
        Quotient {
            num: -self.num,
            ..self
        }
    }
}

/// `num` over `rest`'s factors, tidied ([`Open::tidy`]), with `rest` itself kept when
/// no factor divides `num` (the usual case). When factor `k` divides, the factors
/// before it do not divide the quotient either (they would divide `num`), so tidying
/// goes on from `k`, exactly as [`Open::tidy`] would.
fn keeping(num: Poly, rest: Arc<Rest>) -> Quotient {
    let divides = if num.is_zero() || num.num_terms() > TIDY_TERMS {
        None
    } else {
        rest.den
            .iter()
            .enumerate()
            .find_map(|(k, (f, _))| Some((k, divide_laurent(&num, f)?)))
    };
    match divides {
        None if !num.is_zero() => Quotient {
            num,
            rest: Some(rest),
        },
        None => Open {
            num,
            den: Vec::new(),
            conditions: rest.conditions.clone(),
        }
        .close(),
        Some((k, q)) => {
            let Rest {
                mut den,
                conditions,
            } = Arc::unwrap_or_clone(rest);
            den[k].1 -= 1;
            if den[k].1 == 0 {
                den.remove(k);
            }
            Open {
                num: q,
                den,
                conditions,
            }
            .tidy_from(k)
            .close()
        }
    }
}

/// Clears the denominators of `a − b`: the numerator of the difference over the least
/// common multiple of both denominators, and that multiple's factors. `a = b` wherever
/// every factor is nonzero exactly when the numerator is the zero polynomial.
/// `None` when clearing takes more than [`CLEARING_WORK`] term products.
pub fn cleared_difference(a: &Quotient, b: &Quotient) -> Option<(Poly, Vec<(Poly, u32)>)> {
    if a.factors().is_empty() && b.factors().is_empty() {
        return Some((&a.num - &b.num, Vec::new()));
    }
    let common = Open::common(a.factors(), b.factors());
    let mut work = CLEARING_WORK;
    let mut ring = Quotients {
        work_left: &mut work,
    };
    let left = ring.times(a.num.clone(), &common.a_lacks).ok()?;
    let right = ring.times(b.num.clone(), &common.b_lacks).ok()?;
    Some((&left - &right, common.lcm))
}

/// Term products one comparison may spend clearing denominators (as much as a whole
/// claim's evaluation may: `eval::exact::env::MAX_WORK`).
pub const CLEARING_WORK: usize = 1_000_000;

/// Numerators larger than this are not tried for cancellation: exact division of a
/// large polynomial costs time quadratic in its size, and cancelling only tidies the
/// display (comparisons clear denominators anyway).
const TIDY_TERMS: usize = 2_000;

impl Quotient {
    /// The residue mod [`residue::P`] at a point of residues (the conditions are not
    /// checked: an exact evaluation does that); `None` where a denominator vanishes.
    pub fn residue(&self, value: &dyn Fn(Var) -> u64) -> Option<u64> {
        let mut den = 1;
        for (f, k) in self.factors() {
            den = residue::mul(
                den,
                residue::pow(residue::of_poly(f, value)?, u64::from(*k)),
            );
        }
        Some(residue::mul(
            residue::of_poly(self.numerator(), value)?,
            residue::inverse(den)?,
        ))
    }

    /// Whether `self` and `other` certainly differ at the point (`false`: maybe
    /// equal). A denominator that vanishes mod P screens nothing: `true`, and an exact
    /// evaluation decides.
    pub fn differs_mod_p(&self, other: &Quotient, value: &dyn Fn(Var) -> u64) -> bool {
        match (self.residue(value), other.residue(value)) {
            (Some(x), Some(y)) => x != y,
            _ => true,
        }
    }
}

impl Quotient {
    /// A quotient by variable names (a square root offered to the kernel).
    pub fn data(&self, names: &VarTable) -> crate::kernel::statement::FracData {
        use crate::kernel::statement::poly_data;
        crate::kernel::statement::FracData {
            num: poly_data(self.numerator(), names),
            den: (self.factors().iter())
                .map(|(f, k)| (poly_data(f, names), *k))
                .collect(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(n: i64) -> Poly {
        Poly::constant(Rational::int(n))
    }

    fn setup() -> (VarTable, Poly, Poly) {
        let mut names = VarTable::new();
        let x = Poly::var(names.intern("x"));
        let y = Poly::var(names.intern("y"));
        (names, x, y)
    }

    fn ring(work: &mut usize) -> Quotients<'_> {
        Quotients { work_left: work }
    }

    #[test]
    fn products_and_sums_share_or_tidy_as_the_open_route_does() {
        // x/((x + 1)²(y − 2)) times and plus a polynomial, for numerators that cancel
        // nothing, one factor, both powers of one, the other, everything, or give
        // zero: the shortcuts give what laying the parts open and tidying gives, and
        // share the denominator when nothing cancels.
        let (_, x, y) = setup();
        let (f, g) = (&x + &q(1), &y - &q(2));
        let base = Quotient::from(x.clone())
            .divide(&Quotient::from(f.clone()))
            .unwrap()
            .divide(&Quotient::from(f.clone()))
            .unwrap()
            .divide(&Quotient::from(g.clone()))
            .unwrap();
        let rest = base.rest.clone().expect("a denominator");
        let cases = [
            &x + &y,
            f.clone(),
            &f * &f,
            &g * &(&x - &q(3)),
            &(&f * &f) * &g,
            Poly::default(),
            q(5),
        ];
        for p in cases {
            let num = base.numerator() * &p;
            let open = Open {
                num: num.clone(),
                den: rest.den.clone(),
                conditions: rest.conditions.clone(),
            }
            .tidy()
            .close();
            let mut work = 1_000;
            let both = [
                ring(&mut work).mul(base.clone(), &Quotient::from(p.clone())),
                ring(&mut work).mul(Quotient::from(p.clone()), &base),
            ];
            let parts =
                |v: &Quotient| (v.num.clone(), v.factors().to_vec(), v.conditions().to_vec());
            for product in both {
                let product = product.unwrap();
                assert_eq!(parts(&product), parts(&open), "times {p:?}");
                assert_eq!(product.conditions(), base.conditions());
            }
            // Sums: with a polynomial (its numerator times every factor), and with a
            // value over the same factors and conditions (numerators added).
            let cleared = rest
                .den
                .iter()
                .fold(p.clone(), |acc, (f, k)| &acc * &f.pow(*k));
            let same_rest = Quotient {
                num: p.clone(),
                rest: Some(Arc::new((*rest).clone())),
            };
            for (other, added) in [(Quotient::from(p.clone()), cleared), (same_rest, p.clone())] {
                let open = Open {
                    num: base.numerator() + &added,
                    den: rest.den.clone(),
                    conditions: rest.conditions.clone(),
                }
                .tidy()
                .close();
                let sums = [
                    ring(&mut work).add(base.clone(), other.clone()),
                    ring(&mut work).add(other, base.clone()),
                ];
                for sum in sums {
                    assert_eq!(parts(&sum.unwrap()), parts(&open), "plus {p:?}");
                }
            }
            let kept = keeping(num, Arc::clone(&rest));
            let shared = kept.rest.as_ref().is_some_and(|r| Arc::ptr_eq(r, &rest));
            assert_eq!(
                shared,
                open.factors() == rest.den.as_slice() && !open.is_zero()
            );
        }
    }

    #[test]
    fn division_by_a_sum_keeps_a_canonical_factor() {
        let (names, x, y) = setup();
        // 1 / (2x² + 2xy) = 1/(2 x (x + y)): scale and monomial content leave the factor.
        let d = &(&q(2) * &(&x * &x)) + &(&q(2) * &(&x * &y));
        let r = Quotient::from(q(1)).divide(&Quotient::from(d)).unwrap();
        assert_eq!(r.factors().len(), 1);
        assert_eq!(r.factors()[0].0.display(&names), "x + y");
        assert_eq!(r.numerator().display(&names), "1/2*x^-1");
        // −x − y is the same factor: the sign goes to the numerator.
        let s = Quotient::from(q(1))
            .divide(&Quotient::from(-(&x + &y)))
            .unwrap();
        assert_eq!(s.factors()[0].0, r.factors()[0].0);
        assert_eq!(s.numerator(), &q(-1));
        assert_eq!(
            Quotient::from(q(1))
                .divide(&Quotient::from(Poly::default()))
                .unwrap_err(),
            DivideError::ByZero
        );
    }

    #[test]
    fn sums_use_the_least_common_multiple_and_cancel() {
        let (names, x, y) = setup();
        let mut work = 10_000;
        let one = Quotient::from(q(1));
        let a = one.divide(&Quotient::from(&x + &y)).unwrap();
        let b = one.divide(&Quotient::from(&x - &y)).unwrap();
        // 1/(x+y) + 1/(x−y) = 2x / ((x+y)(x−y)).
        let s = ring(&mut work).add(a.clone(), b.clone()).unwrap();
        assert_eq!(s.display(&names), "2*x / ((x + y) (x - y))");
        // (x+y) · 1/(x+y) = 1: the factor cancels.
        let p = ring(&mut work).mul(Quotient::from(&x + &y), &a).unwrap();
        assert_eq!(p.as_poly(), Some(&q(1)));
        // 1/(x+y) − 1/(x+y) = 0 with no denominator left.
        let z = ring(&mut work).add(a.clone(), -a.clone()).unwrap();
        assert!(z.is_zero() && z.factors().is_empty());
        // (x² − y²)/(x + y) = x − y: the numerator is divisible.
        let d = Quotient::from(&(&x * &x) - &(&y * &y))
            .divide(&Quotient::from(&x + &y))
            .unwrap();
        assert_eq!(d.as_poly(), Some(&(&x - &y)));
        // Dividing by a quotient moves its factors up: x / (1/(x+y)) = x² + xy.
        let e = Quotient::from(x.clone()).divide(&a).unwrap();
        assert_eq!(e.as_poly(), Some(&(&(&x * &x) + &(&x * &y))));
    }

    #[test]
    fn values_avoid_poles_and_differences_clear_denominators() {
        let (names, x, y) = setup();
        let vx = names.lookup("x").unwrap();
        let one = Quotient::from(q(1));
        let a = one.divide(&Quotient::from(&x + &y)).unwrap();
        let at = |v: Var| Rational::int(if v == vx { 1 } else { -1 });
        assert_eq!(a.eval(&at), None, "a pole");
        let at = |v: Var| Rational::int(if v == vx { 1 } else { 2 });
        assert_eq!(a.eval(&at), Rational::ratio(1, 3));
        // x/(x+y) + y/(x+y) − 1 clears to the zero numerator.
        let mut work = 10_000;
        let s = ring(&mut work)
            .add(
                Quotient::from(x.clone())
                    .divide(&Quotient::from(&x + &y))
                    .unwrap(),
                Quotient::from(y.clone())
                    .divide(&Quotient::from(&x + &y))
                    .unwrap(),
            )
            .unwrap();
        let (num, _) = cleared_difference(&s, &one).unwrap();
        assert!(num.is_zero());
        let (num, lcm) = cleared_difference(&a, &one).unwrap();
        assert_eq!(num.display(&names), "-x - y + 1");
        assert_eq!(lcm.len(), 1);
    }

    #[test]
    fn products_are_charged_to_the_budget() {
        let (_, x, y) = setup();
        let a = Quotient::from(q(1))
            .divide(&Quotient::from(&x + &y))
            .unwrap();
        let b = Quotient::from(q(1))
            .divide(&Quotient::from(&x - &y))
            .unwrap();
        let mut work = 1;
        assert_eq!(ring(&mut work).add(a, b).unwrap_err(), OverBudget);
    }

    #[test]
    fn a_first_factor_is_one_times_it_in_value_and_charge() {
        let (_, x, y) = setup();
        let sum = Quotient::from(&(&x * &x) + &(&y + &q(3)));
        let over = Quotient::from(x.clone())
            .divide(&Quotient::from(&x + &y))
            .unwrap();
        for v in [sum, over, Quotient::default()] {
            let (mut by_first, mut by_product) = (100, 100);
            let first = ring(&mut by_first).first(&v).unwrap();
            let one = ring(&mut by_product).one();
            let product = ring(&mut by_product).mul(one, &v).unwrap();
            assert_eq!(first.numerator(), product.numerator());
            assert_eq!(first.factors(), product.factors());
            assert_eq!(first.conditions(), product.conditions());
            assert_eq!(by_first, by_product);
            // Refused on the same budget as the product.
            let terms = v.numerator().num_terms();
            if terms > 0 {
                let mut short = terms - 1;
                assert_eq!(ring(&mut short).first(&v).unwrap_err(), OverBudget);
            }
        }
    }
}
