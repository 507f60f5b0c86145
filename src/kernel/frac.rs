//! Fractions as the kernel's evaluator builds them: a Laurent polynomial over a product
//! of divisor polynomials kept apart, never reduced by a gcd.
//!
//! A sum brings both terms over the least common multiple of the two factor lists,
//! matched structurally; a product concatenates them. Two fractions are compared by
//! clearing the denominators (`a/A = b/B` wherever A, B ≠ 0 exactly when
//! `a·(L/A) − b·(L/B)` is the zero polynomial, L the common multiple), so no
//! cancellation is ever needed for a sound comparison. Every divisor met on the way,
//! cancelled or not, is kept in `conds`: the statement is claimed only where each is
//! nonzero. A single-term divisor (3, V, 2·R_g) divides the numerator exactly (its
//! variables are read as nonzero, as everywhere in the checker).

use super::poly::{Monomial, Poly, PolyError, Var};
use super::rational::Rational;
use num_traits::{One, Zero};

/// `num / Π den_k^m_k`, defined where every polynomial of `conds` is nonzero. Each
/// divisor is normalised (leading coefficient 1, no monomial content, at least two
/// terms), so that equal divisors are recognised structurally.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Frac {
    pub(super) num: Poly,
    pub(super) den: Vec<(Poly, u32)>,
    pub(super) conds: Vec<Poly>,
}

/// Why a fraction operation has no result.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum FracError {
    #[error("division by zero")]
    DivisionByZero,
    /// An exponent or a multiplicity beyond the kernel's bounds.
    #[error("an exponent or a multiplicity beyond the kernel's bounds")]
    TooLarge,
}

impl From<PolyError> for FracError {
    fn from(e: PolyError) -> Self {
        match e {
            PolyError::DivisionByZero => FracError::DivisionByZero,
            _ => FracError::TooLarge,
        }
    }
}

/// The most steps one trial division of a divisor by a known one takes.
const DIVISION_STEPS: usize = 2_000;

/// The largest multiplicity of a divisor (the strategy's largest exponent).
const MAX_MULTIPLICITY: u32 = 10_000;

/// The most term products one clearing of denominators takes.
const CLEARING_WORK: usize = 5_000_000;

/// `f = c · m · g` with `g` in canonical associate form (coprime integer
/// coefficients, positive leading term) and no monomial content: `None` for a single
/// term (g would be 1).
fn normalise(f: &Poly) -> Option<(Rational, Monomial, Poly)> {
    if f.num_terms() < 2 {
        return None;
    }
    let mut lowest: Vec<(Var, super::poly::Exp)> = Vec::new();
    let vars = f.variables();
    for v in vars {
        let low = f.terms().map(|(m, _)| m.exponent(v)).min().unwrap_or(0);
        if low != 0 {
            lowest.push((v, low));
        }
    }
    let m = Monomial::checked_from_factors(lowest)?;
    let scale = super::poly::canonical_scale(f)?;
    let inverse = Poly::term(m.pow(-1)?, scale.clone());
    let g = f.checked_mul(&inverse).ok()?;
    Some((scale.recip()?, m, g))
}

fn add_factor(list: &mut Vec<(Poly, u32)>, f: &Poly, k: u32) -> Result<(), FracError> {
    let m = match list.iter_mut().find(|(g, _)| g == f) {
        Some((_, m)) => {
            *m = m.checked_add(k).ok_or(FracError::TooLarge)?;
            *m
        }
        None => {
            list.push((f.clone(), k));
            k
        }
    };
    if m > MAX_MULTIPLICITY {
        return Err(FracError::TooLarge);
    }
    Ok(())
}

/// Records each variable of a monomial divided by as a condition (`v ≠ 0`): the
/// value is undefined where it vanishes, though the division cancels it.
fn divided_by_monomial(conds: &mut Vec<Poly>, m: &Monomial) {
    for &(v, e) in m.factors() {
        let var = Poly::var(v);
        if e > 0 && !conds.contains(&var) {
            conds.push(var);
        }
    }
}

fn union(into: &mut Vec<Poly>, from: &[Poly]) {
    for c in from {
        if !into.contains(c) {
            into.push(c.clone());
        }
    }
}

/// `p · Π f^k`, within [`CLEARING_WORK`] term products.
fn times(mut p: Poly, factors: &[(Poly, u32)]) -> Result<Poly, FracError> {
    let mut work = 0usize;
    for (f, k) in factors {
        for _ in 0..*k {
            work = work.saturating_add(p.num_terms().saturating_mul(f.num_terms()));
            if work > CLEARING_WORK {
                return Err(FracError::TooLarge);
            }
            p = p.checked_mul(f)?;
        }
    }
    Ok(p)
}

impl From<Poly> for Frac {
    fn from(num: Poly) -> Self {
        Frac {
            num,
            ..Frac::default()
        }
    }
}

impl Frac {
    pub fn one() -> Self {
        Frac::from(Poly::one())
    }

    pub fn constant(q: Rational) -> Self {
        Frac::from(Poly::constant(q))
    }

    pub fn numerator(&self) -> &Poly {
        &self.num
    }

    /// The divisors with their multiplicities.
    pub fn denominator(&self) -> &[(Poly, u32)] {
        &self.den
    }

    /// Every divisor met on the way: where one vanishes, the value is undefined.
    pub fn conditions(&self) -> &[Poly] {
        &self.conds
    }

    /// Whether the value is 0 wherever it is defined.
    pub fn is_zero(&self) -> bool {
        self.num.is_zero()
    }

    /// Whether `v` occurs in some divisor.
    pub fn divides_by(&self, v: Var) -> bool {
        self.conds
            .iter()
            .any(|c| c.terms().any(|(m, _)| m.exponent(v) != 0))
    }

    /// The same value with every divisor that divides the numerator cancelled (the
    /// conditions stay).
    pub fn tidied(&self) -> Frac {
        let mut out = self.clone();
        for (f, k) in &mut out.den {
            while *k > 0 {
                match out.num.divide_exact(f, DIVISION_STEPS) {
                    Some(q) => {
                        out.num = q;
                        *k -= 1;
                    }
                    None => break,
                }
            }
        }
        out.den.retain(|(_, k)| *k > 0);
        out
    }

    /// The same value, also undefined where `other` is.
    pub fn with_conditions_of(mut self, other: &Frac) -> Frac {
        union(&mut self.conds, &other.conds);
        self
    }

    pub fn neg(&self) -> Frac {
        Frac {
            num: -&self.num,
            ..self.clone()
        }
    }

    pub fn mul(&self, other: &Frac) -> Result<Frac, FracError> {
        let mut den = self.den.clone();
        for (f, k) in &other.den {
            add_factor(&mut den, f, *k)?;
        }
        let mut conds = self.conds.clone();
        union(&mut conds, &other.conds);
        Ok(Frac {
            num: self.num.checked_mul(&other.num)?,
            den,
            conds,
        })
    }

    pub fn add(&self, other: &Frac) -> Result<Frac, FracError> {
        let mut conds = self.conds.clone();
        union(&mut conds, &other.conds);
        if self.den == other.den {
            return Ok(Frac {
                num: &self.num + &other.num,
                den: self.den.clone(),
                conds,
            });
        }
        let (lcm, a, b) = over_common(&self.den, &other.den);
        Ok(Frac {
            num: &times(self.num.clone(), &a)? + &times(other.num.clone(), &b)?,
            den: lcm,
            conds,
        })
    }

    pub fn sub(&self, other: &Frac) -> Result<Frac, FracError> {
        self.add(&other.neg())
    }

    /// `self / d`. A zero divisor is an error; a single-term one divides the numerator;
    /// any other joins the denominator, normalised, and `d`'s own divisors move to the
    /// numerator (staying in the conditions).
    pub fn div(&self, d: &Frac) -> Result<Frac, FracError> {
        if d.num.is_zero() {
            return Err(FracError::DivisionByZero);
        }
        let mut out = self.clone();
        union(&mut out.conds, &d.conds);
        out.num = times(out.num, &d.den)?;
        // Divisors met before are split off first, so that a product of them joins
        // the denominator (and the conditions) as its factors, not as one polynomial.
        let mut rest = d.num.clone();
        let known: Vec<Poly> = out.conds.clone();
        for f in &known {
            while let Some(q) = rest.divide_exact(f, DIVISION_STEPS) {
                add_factor(&mut out.den, f, 1)?;
                rest = q;
            }
        }
        match normalise(&rest) {
            None => {
                if let Some((m, _)) = rest.leading() {
                    divided_by_monomial(&mut out.conds, m);
                }
                out.num = out.num.checked_div(&rest)?
            }
            Some((c, m, g)) => {
                divided_by_monomial(&mut out.conds, &m);
                let scale = Poly::term(
                    m.pow(-1).ok_or(FracError::TooLarge)?,
                    c.recip().ok_or(FracError::DivisionByZero)?,
                );
                out.num = out.num.checked_mul(&scale)?;
                add_factor(&mut out.den, &g, 1)?;
                union(&mut out.conds, std::slice::from_ref(&g));
            }
        }
        Ok(out)
    }

    pub fn pow(&self, k: u32) -> Result<Frac, FracError> {
        let mut den = Vec::with_capacity(self.den.len());
        for (f, m) in &self.den {
            let m = m.checked_mul(k).filter(|&m| m <= MAX_MULTIPLICITY);
            den.push((f.clone(), m.ok_or(FracError::TooLarge)?));
        }
        Ok(Frac {
            num: self.num.checked_pow(k)?,
            den,
            conds: self.conds.clone(),
        })
    }

    /// The numerator of `self − other` over their common denominator: zero exactly
    /// when the two are equal wherever both are defined.
    pub fn cleared_difference(&self, other: &Frac) -> Result<Poly, FracError> {
        let (_, a, b) = over_common(&self.den, &other.den);
        Ok(&times(self.num.clone(), &a)? - &times(other.num.clone(), &b)?)
    }

    /// ∂/∂v by the quotient rule: (N' Π f − N Σ k_i f_i' Π_{j≠i} f_j) / Π f^(k+1).
    pub fn derivative(&self, v: Var) -> Result<Frac, FracError> {
        let once: Vec<(Poly, u32)> = self.den.iter().map(|(f, _)| (f.clone(), 1)).collect();
        let mut num = times(self.num.derivative(v), &once)?;
        for (i, (f, k)) in self.den.iter().enumerate() {
            let others: Vec<(Poly, u32)> = once
                .iter()
                .enumerate()
                .filter(|(j, _)| *j != i)
                .map(|(_, x)| x.clone())
                .collect();
            let term = times(self.num.checked_mul(&f.derivative(v))?, &others)?;
            num = &num - &term.checked_mul(&Poly::constant(Rational::int(i64::from(*k))))?;
        }
        let den = self
            .den
            .iter()
            .map(|(f, k)| Ok((f.clone(), k.checked_add(1).ok_or(FracError::TooLarge)?)))
            .collect::<Result<_, FracError>>()?;
        Ok(Frac {
            num,
            den,
            conds: self.conds.clone(),
        })
    }

    /// The value at a point, or `None` where a condition vanishes (undefined) or a
    /// variable is missing.
    pub fn eval(&self, at: &dyn Fn(Var) -> Option<Rational>) -> Option<Rational> {
        let value = |p: &Poly| -> Option<Rational> {
            let mut total = Rational::zero();
            for (m, c) in p.terms() {
                let mut t = c.clone();
                for &(v, e) in m.factors() {
                    t = &t * &at(v)?.pow(e)?;
                }
                total += &t;
            }
            Some(total)
        };
        for c in &self.conds {
            if value(c)?.is_zero() {
                return None;
            }
        }
        let mut den = Rational::one();
        for (f, k) in &self.den {
            den = &den * &value(f)?.pow(i64::from(*k))?;
        }
        value(&self.num)?.checked_div(&den)
    }

    /// The fraction with the numerator mapped by `f` (a linear map that the
    /// denominator does not take part in: an average over the normal, a derivative
    /// along a variable no divisor contains).
    pub fn map_numerator(
        &self,
        f: impl FnOnce(&Poly) -> Result<Poly, FracError>,
    ) -> Result<Frac, FracError> {
        Ok(Frac {
            num: f(&self.num)?,
            den: self.den.clone(),
            conds: self.conds.clone(),
        })
    }
}

/// The least common multiple of two factor lists, and what each list is multiplied by
/// to reach it.
type Common = (Vec<(Poly, u32)>, Vec<(Poly, u32)>, Vec<(Poly, u32)>);

fn over_common(a: &[(Poly, u32)], b: &[(Poly, u32)]) -> Common {
    let mut lcm = a.to_vec();
    let mut to_a = Vec::new();
    let mut to_b = Vec::new();
    for (f, k) in b {
        match lcm.iter_mut().find(|(g, _)| g == f) {
            Some((_, m)) if *m >= *k => to_b.push((f.clone(), *m - *k)),
            Some((_, m)) => {
                to_a.push((f.clone(), *k - *m));
                *m = *k;
            }
            None => {
                lcm.push((f.clone(), *k));
                to_a.push((f.clone(), *k));
            }
        }
    }
    for (f, k) in a {
        if !b.iter().any(|(g, _)| g == f) {
            to_b.push((f.clone(), *k));
        }
    }
    (lcm, to_a, to_b)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::VarTable;

    fn setup() -> (Poly, Poly) {
        let mut names = VarTable::new();
        (Poly::var(names.intern("x")), Poly::var(names.intern("y")))
    }

    fn q(n: i64) -> Poly {
        Poly::constant(Rational::int(n))
    }

    #[test]
    fn sums_over_a_common_multiple_compare_by_clearing() {
        let (x, y) = setup();
        // 1/(x+y) + 1/(x−y) = 2x/(x²−y²)
        let a = Frac::constant(Rational::int(1))
            .div(&Frac::from(&x + &y))
            .unwrap();
        let b = Frac::constant(Rational::int(1))
            .div(&Frac::from(&x - &y))
            .unwrap();
        let sum = a.add(&b).unwrap();
        let rhs = Frac::from(&q(2) * &x)
            .div(&Frac::from(&(&x * &x) - &(&y * &y)))
            .unwrap();
        assert!(sum.cleared_difference(&rhs).unwrap().is_zero());
        let wrong = Frac::from(x.clone())
            .div(&Frac::from(&(&x * &x) - &(&y * &y)))
            .unwrap();
        assert!(!sum.cleared_difference(&wrong).unwrap().is_zero());
        assert_eq!(sum.conditions().len(), 2);
        // (2x + 2y) is normalised to x + y: one factor, not two.
        let c = a
            .add(
                &Frac::constant(Rational::int(1))
                    .div(&Frac::from(&q(2) * &(&x + &y)))
                    .unwrap(),
            )
            .unwrap();
        assert_eq!(c.denominator().len(), 1);
    }

    #[test]
    fn a_divisor_leaving_the_denominator_stays_a_condition() {
        let (x, y) = setup();
        let f = Frac::from(x.clone()).div(&Frac::from(&x + &y)).unwrap();
        // 1 / (x/(x+y)) = (x+y)/x: defined only where x + y ≠ 0 too, and x ≠ 0
        // (the monomial divisor, kept as a negative power).
        let g = Frac::constant(Rational::int(1)).div(&f).unwrap();
        assert!(g.denominator().is_empty());
        assert_eq!(g.conditions(), &[&x + &y, x.clone()]);
        let at = |v: Var| {
            Some(if v == 0 {
                Rational::int(1)
            } else {
                Rational::int(-1)
            })
        };
        assert_eq!(g.eval(&at), None, "undefined where x + y = 0");
        assert_eq!(
            Frac::from(x.clone()).div(&Frac::default()),
            Err(FracError::DivisionByZero)
        );
    }
}
