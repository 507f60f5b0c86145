//! Exact division and greatest common divisors of multivariate polynomials over ℚ.
//!
//! An elastoplastic tangent, an acoustic determinant or a shear band's A² are rational
//! functions of the material parameters; keeping them reduced (so that two equal functions print and
//! compare identically) needs the gcd of numerator and denominator. The method is the
//! textbook recursive one (Knuth, TAOCP vol. 2, §4.6.1; Geddes, Czapor & Labahn,
//! ch. 7): view a polynomial as univariate in its largest variable with coefficients
//! in the others, split off the content, run the primitive pseudo-remainder sequence,
//! and recurse on the contents. It is not the fastest gcd (no modular or sparse
//! interpolation), but every step is exact and small enough to audit, and the
//! polynomials of such derivations have a handful of variables and low degree.
//!
//! Only ordinary polynomials (no negative exponents) are accepted: a Laurent
//! polynomial is first cleared by [`clear_denominator_monomial`].

use super::poly::{Monomial, Poly, Var};
use super::rational::Rational;
use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, Signed, Zero};
use std::collections::BTreeMap;

/// Splits a Laurent polynomial `p` into `(q, m)` with `p = q / m`, `q` an ordinary
/// polynomial and `m` the smallest monomial that clears every negative exponent.
pub fn clear_denominator_monomial(p: &Poly) -> (Poly, Monomial) {
    let mut lowest: BTreeMap<Var, i32> = BTreeMap::new();
    for (m, _) in p.terms() {
        for &(v, e) in m.factors() {
            if e < 0 {
                let slot = lowest.entry(v).or_insert(0);
                *slot = (*slot).min(e);
            }
        }
    }
    let m = Monomial::from_factors(lowest.into_iter().map(|(v, e)| (v, -e)).collect());
    (p * &Poly::term(m.clone(), Rational::one()), m)
}

/// The largest variable occurring in `p`, if any.
fn main_var(p: &Poly) -> Option<Var> {
    p.terms()
        .filter_map(|(m, _)| m.factors().last().map(|&(v, _)| v))
        .max()
}

/// Degree of `p` in `v` (0 for the zero polynomial).
pub fn degree_in(p: &Poly, v: Var) -> i32 {
    p.terms().map(|(m, _)| m.exponent(v)).max().unwrap_or(0)
}

/// `p` as a polynomial in `v`: exponent of `v` ↦ coefficient (free of `v`).
fn coefficients_in(p: &Poly, v: Var) -> BTreeMap<i32, Poly> {
    let mut terms: BTreeMap<i32, Vec<(Monomial, Rational)>> = BTreeMap::new();
    for (m, c) in p.terms() {
        terms
            .entry(m.exponent(v))
            .or_default()
            .push((m.without(v), c.clone()));
    }
    terms
        .into_iter()
        .map(|(e, terms)| (e, Poly::from_terms(terms)))
        .collect()
}

fn leading_coefficient_in(p: &Poly, v: Var) -> Poly {
    let top = degree_in(p, v);
    Poly::from_terms(
        p.terms()
            .filter(|(m, _)| m.exponent(v) == top)
            .map(|(m, c)| (m.without(v), c.clone())),
    )
}

fn var_power(v: Var, e: i32) -> Poly {
    Poly::term(Monomial::var(v, e), Rational::one())
}

/// `a / b` when `b` divides `a` exactly in ℚ[x…]; `None` when it does not (or `b = 0`).
/// Both must be ordinary polynomials.
pub fn divide_exact(a: &Poly, b: &Poly) -> Option<Poly> {
    if b.is_zero() {
        return None;
    }
    if a.is_zero() {
        return Some(Poly::zero());
    }
    let Some(v) = main_var(b) else {
        let c = b.as_constant()?;
        return Some(a * &Poly::constant(c.recip()?));
    };
    let db = degree_in(b, v);
    let lb = leading_coefficient_in(b, v);
    let mut rem = a.clone();
    let mut quot = Poly::zero();
    while !rem.is_zero() {
        let dr = degree_in(&rem, v);
        if dr < db {
            return None;
        }
        let q = divide_exact(&leading_coefficient_in(&rem, v), &lb)?;
        let t = &q * &var_power(v, dr - db);
        rem = &rem - &(&t * b);
        quot += &t;
    }
    Some(quot)
}

/// Pseudo-remainder of `a` by `b` in `v`: `lc(b)^k a = q b + r` with `deg_v r < deg_v b`.
fn pseudo_remainder(a: &Poly, b: &Poly, v: Var) -> Poly {
    let db = degree_in(b, v);
    let lb = leading_coefficient_in(b, v);
    let mut r = a.clone();
    while !r.is_zero() && degree_in(&r, v) >= db {
        let dr = degree_in(&r, v);
        let lr = leading_coefficient_in(&r, v);
        r = &(&lb * &r) - &(&(&lr * &var_power(v, dr - db)) * b);
    }
    r
}

/// The content of `p` in `v` (gcd of its coefficients, a polynomial free of `v`) and
/// the primitive part `p / content`.
fn content_and_primitive(p: &Poly, v: Var) -> (Poly, Poly) {
    let content = coefficients_in(p, v)
        .values()
        .fold(Poly::zero(), |g, c| gcd(&g, c));
    let primitive = divide_exact(p, &content).expect("the content divides every coefficient");
    (content, primitive)
}

/// The greatest common divisor of two ordinary polynomials, normalised by
/// [`normalize_sign_and_scale`] (integer coefficients without common factor, positive
/// leading coefficient); `gcd(0, 0) = 0`.
///
/// ```
/// use cosserat_check::kernel::{gcd, Poly, VarTable};
/// let mut names = VarTable::new();
/// let x = Poly::var(names.intern("x"));
/// let y = Poly::var(names.intern("y"));
/// let a = &(&x + &y) * &(&x - &y); // x² − y²
/// let b = &(&x + &y) * &(&x + &y); // (x + y)²
/// assert_eq!(gcd::gcd(&a, &b).display(&names), "x + y");
/// ```
pub fn gcd(a: &Poly, b: &Poly) -> Poly {
    if a.is_zero() {
        return normalize_sign_and_scale(b);
    }
    if b.is_zero() {
        return normalize_sign_and_scale(a);
    }
    // Short cuts: a nonzero constant is a unit; gcd(a, a) = a.
    if a.as_constant().is_some() || b.as_constant().is_some() {
        return Poly::one();
    }
    if a == b {
        return normalize_sign_and_scale(a);
    }
    let v = match (main_var(a), main_var(b)) {
        (None, None) => return Poly::one(),
        (x, y) => x.max(y).expect("one of them has a variable"),
    };
    let (ca, pa) = content_and_primitive(a, v);
    let (cb, pb) = content_and_primitive(b, v);
    let content = gcd(&ca, &cb);
    let (mut r0, mut r1) = if degree_in(&pa, v) >= degree_in(&pb, v) {
        (pa, pb)
    } else {
        (pb, pa)
    };
    while !r1.is_zero() {
        let r = pseudo_remainder(&r0, &r1, v);
        r0 = r1;
        // The primitive part, scaled to coprime integer coefficients: over ℚ the
        // content of constant coefficients is a unit, and without this scaling the
        // coefficients of the pseudo-remainders grow exponentially.
        r1 = if r.is_zero() {
            r
        } else {
            normalize_sign_and_scale(&content_and_primitive(&r, v).1)
        };
    }
    let primitive = if degree_in(&r0, v) == 0 {
        Poly::one()
    } else {
        content_and_primitive(&r0, v).1
    };
    normalize_sign_and_scale(&(&content * &primitive))
}

/// `p` scaled by a nonzero rational so that its coefficients are coprime integers and
/// its leading term (graded lexicographic) is positive: the canonical associate.
pub fn normalize_sign_and_scale(p: &Poly) -> Poly {
    match canonical_scale(p) {
        Some(s) => p * &Poly::constant(s),
        None => Poly::zero(),
    }
}

/// The rational `s` with `s·p` in canonical associate form (see
/// [`normalize_sign_and_scale`]); `None` for the zero polynomial.
pub fn canonical_scale(p: &Poly) -> Option<Rational> {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::VarTable;

    fn setup() -> (VarTable, Poly, Poly, Poly) {
        let mut names = VarTable::new();
        let x = Poly::var(names.intern("x"));
        let y = Poly::var(names.intern("y"));
        let z = Poly::var(names.intern("z"));
        (names, x, y, z)
    }

    fn c(n: i64) -> Poly {
        Poly::constant(Rational::int(n))
    }

    #[test]
    fn exact_division_recovers_the_factor_and_refuses_a_remainder() {
        let (_, x, y, z) = setup();
        let f = &(&(&x * &y) + &c(3)) - &z; // xy + 3 − z
        let g = &(&x.pow(2) - &(&y * &z)) + &c(1);
        let fg = &f * &g;
        assert_eq!(divide_exact(&fg, &f), Some(g.clone()));
        assert_eq!(divide_exact(&fg, &g), Some(f.clone()));
        assert_eq!(divide_exact(&(&fg + &c(1)), &f), None);
        assert_eq!(divide_exact(&fg, &Poly::zero()), None);
        assert_eq!(
            divide_exact(&(&x * &c(6)), &c(4)),
            Some(&x * &Poly::constant(Rational::ratio(3, 2).unwrap()))
        );
    }

    #[test]
    fn gcd_finds_the_common_factor_of_multivariate_products() {
        let (names, x, y, z) = setup();
        let g = &(&(&x * &z) - &y.pow(2)) + &c(2); // xz − y² + 2
        let p = &(&x + &y) + &z;
        let q = &(&x.pow(2) + &z) - &c(5);
        let a = &(&g * &p) * &c(3);
        let b = &(&g * &q) * &Poly::constant(Rational::ratio(-1, 7).unwrap());
        assert_eq!(gcd(&a, &b), normalize_sign_and_scale(&g));
        assert_eq!(gcd(&a, &b).display(&names), "x*z - y^2 + 2");
        // Coprime inputs give 1; a repeated factor is found with its multiplicity.
        assert_eq!(gcd(&p, &q), Poly::one());
        let g2 = &g * &g;
        assert_eq!(gcd(&(&g2 * &p), &(&g2 * &q)), normalize_sign_and_scale(&g2));
        // Contents in the other variables are found too: gcd(y·x, y·z) = y.
        assert_eq!(gcd(&(&y * &x), &(&y * &z)), y);
        assert_eq!(gcd(&Poly::zero(), &(&x * &c(-4))), x);
        assert_eq!(gcd(&c(6), &c(4)), Poly::one());
    }

    #[test]
    fn gcd_is_refuted_by_a_wrong_factor() {
        // Mutant: the second input carries g with one coefficient changed, so the
        // common factor disappears and the gcd must be 1.
        let (_, x, y, z) = setup();
        let g = &(&(&x * &z) - &y.pow(2)) + &c(2);
        let g_mutant = &(&(&x * &z) - &y.pow(2)) + &c(3);
        let p = &(&x + &y) + &z;
        assert_eq!(
            gcd(&(&g * &p), &(&g_mutant * &p)),
            normalize_sign_and_scale(&p)
        );
        assert_eq!(gcd(&(&g * &x), &(&g_mutant * &y)), Poly::one());
    }

    #[test]
    fn laurent_polynomials_are_cleared_by_the_smallest_monomial() {
        let (_, x, y, _) = setup();
        let p = &(&x * &Poly::term(Monomial::var(1, -2), Rational::one())) + &y; // x/y² + y
        let (q, m) = clear_denominator_monomial(&p);
        assert_eq!(m, Monomial::var(1, 2));
        assert_eq!(q, &x + &y.pow(3));
    }
}
