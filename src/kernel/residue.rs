//! Values modulo a large prime: a cheap screen for "are these two rationals
//! different?". The map ℚ → 𝔽_p (defined where p divides no denominator) is a ring
//! homomorphism, so two values with different residues are different; equal residues
//! decide nothing. The counterexample search uses it to skip candidate points whose
//! exact evaluation (bigint powers of high degree) would be wasted.
//!
//! Univariate polynomials over 𝔽_P live here too (images of multivariate ones, their
//! gcds by Euclid's algorithm): the gcd proves coprimality with them, and the modular
//! gcd (`super::modular`) builds its candidates from them.

use super::poly::{Poly, Var};
use super::quotient::Quotient;
use super::rational::Rational;
use num_bigint::BigInt;
use num_traits::{Signed, ToPrimitive};

/// The Mersenne prime 2⁶¹ − 1.
pub const P: u64 = (1 << 61) - 1;

/// a·b mod P for a, b < P, by the Mersenne reduction 2⁶¹ ≡ 1 (no division).
pub(super) fn mul(a: u64, b: u64) -> u64 {
    let x = u128::from(a) * u128::from(b);
    let r = (x as u64 & P) + (x >> 61) as u64;
    // r < 2P: x < 2¹²², so x >> 61 < 2⁶¹.
    if r >= P {
        r - P
    } else {
        r
    }
}

fn pow(mut a: u64, mut e: u64) -> u64 {
    let mut r = 1;
    while e > 0 {
        if e & 1 == 1 {
            r = mul(r, a);
        }
        a = mul(a, a);
        e >>= 1;
    }
    r
}

/// a⁻¹ mod P, `None` for 0.
pub(super) fn inverse(a: u64) -> Option<u64> {
    (a != 0).then(|| pow(a, P - 2))
}

fn of_int(n: &BigInt) -> u64 {
    let m = (n.abs() % BigInt::from(P)).to_u64().expect("below P");
    if n.is_negative() && m != 0 {
        P - m
    } else {
        m
    }
}

/// The residue of a small integer.
fn of_i64(n: i64) -> u64 {
    let m = n.unsigned_abs() % P;
    if n < 0 && m != 0 {
        P - m
    } else {
        m
    }
}

/// The residue of a rational, `None` when P divides its denominator.
pub fn of_rational(q: &Rational) -> Option<u64> {
    match q.small_parts() {
        Some((_, 1)) => Some(of_i64(q.small_parts()?.0)),
        Some((n, d)) => Some(mul(of_i64(n), inverse(of_i64(d))?)),
        None => Some(mul(of_int(&q.numer()), inverse(of_int(&q.denom()))?)),
    }
}

/// A polynomial's residue at a point given by residues (`None` where a negative power
/// meets a zero residue or a coefficient's denominator vanishes mod P).
pub fn of_poly(p: &Poly, value: &dyn Fn(Var) -> u64) -> Option<u64> {
    let mut total = 0u64;
    for (m, c) in p.terms() {
        let mut t = of_rational(c)?;
        for &(v, e) in m.factors() {
            let x = value(v);
            let x = if e < 0 { inverse(x)? } else { x };
            t = mul(t, pow(x, u64::from(e.unsigned_abs())));
        }
        total = (total + t) % P;
    }
    Some(total)
}

/// A quotient's residue (its conditions are not checked: an exact evaluation does that).
pub fn of_quotient(q: &Quotient, value: &dyn Fn(Var) -> u64) -> Option<u64> {
    let mut den = 1;
    for (f, k) in q.factors() {
        den = mul(den, pow(of_poly(f, value)?, u64::from(*k)));
    }
    Some(mul(of_poly(q.numerator(), value)?, inverse(den)?))
}

/// Whether `a` and `b` certainly differ at the point (`false`: maybe equal).
pub fn differ(a: &Quotient, b: &Quotient, value: &dyn Fn(Var) -> u64) -> bool {
    match (of_quotient(a, value), of_quotient(b, value)) {
        (Some(x), Some(y)) => x != y,
        // A denominator vanishes mod P: no screen; let the exact evaluation decide.
        _ => true,
    }
}

/// `p` as a polynomial in `w` over 𝔽_P, every other variable at its residue
/// `value(v)`: the coefficients by ascending power of `w`, without trailing zeros
/// (empty for the image 0). `None` for a negative power, a denominator that P
/// divides, or a degree in `w` above [`IMAGE_DEGREE`]: no image.
pub fn univariate_image(p: &Poly, w: Var, value: &dyn Fn(Var) -> u64) -> Option<Vec<u64>> {
    let mut image: Vec<u64> = Vec::new();
    for (m, c) in p.terms() {
        let mut t = of_rational(c)?;
        let mut power = 0;
        for &(v, e) in m.factors() {
            let e = u64::try_from(e).ok()?;
            if v == w {
                power = usize::try_from(e).ok().filter(|&k| k <= IMAGE_DEGREE)?;
            } else {
                t = mul(t, pow(value(v), e));
            }
        }
        if image.len() <= power {
            image.resize(power + 1, 0);
        }
        image[power] = (image[power] + t) % P;
    }
    trim(&mut image);
    Some(image)
}

/// The highest degree a dense univariate image is built for (its vector has one entry
/// per power; a higher degree is left to the exact route).
pub const IMAGE_DEGREE: usize = 4_096;

fn trim(p: &mut Vec<u64>) {
    while p.last() == Some(&0) {
        p.pop();
    }
}

/// A residue that looks random, from `seed` (splitmix64's finaliser, reduced mod P):
/// evaluation points far from 0 and 1, the same in every run.
pub(super) fn scramble(seed: u64) -> u64 {
    let mut z = seed.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    (z ^ (z >> 31)) % P
}

/// The degree of the greatest common divisor of two nonzero univariate polynomials
/// over 𝔽_P (coefficients ascending, no trailing zeros).
pub fn gcd_degree(a: Vec<u64>, b: Vec<u64>) -> usize {
    assert!(
        !a.is_empty() && !b.is_empty(),
        "gcd_degree of a zero polynomial"
    );
    uni_gcd(a, b).len() - 1
}

/// A univariate polynomial over 𝔽_P, coefficients ascending, no trailing zeros (empty
/// for 0).
pub(super) type Uni = Vec<u64>;

/// The value at `x` (Horner).
pub(super) fn eval(u: &[u64], x: u64) -> u64 {
    u.iter().rev().fold(0, |acc, &c| add(mul(acc, x), c))
}

fn add(a: u64, b: u64) -> u64 {
    let s = a + b; // < 2P < 2⁶⁴
    if s >= P {
        s - P
    } else {
        s
    }
}

pub(super) fn sub(a: u64, b: u64) -> u64 {
    if a >= b {
        a - b
    } else {
        a + P - b
    }
}

fn trimmed(mut u: Uni) -> Uni {
    trim(&mut u);
    u
}

pub(super) fn uni_add(a: &[u64], b: &[u64]) -> Uni {
    let mut out = vec![0; a.len().max(b.len())];
    for (k, o) in out.iter_mut().enumerate() {
        *o = add(
            a.get(k).copied().unwrap_or(0),
            b.get(k).copied().unwrap_or(0),
        );
    }
    trimmed(out)
}

pub(super) fn uni_scale(a: &[u64], s: u64) -> Uni {
    trimmed(a.iter().map(|&c| mul(c, s)).collect())
}

pub(super) fn uni_mul(a: &[u64], b: &[u64]) -> Uni {
    if a.is_empty() || b.is_empty() {
        return Vec::new();
    }
    let mut out = vec![0; a.len() + b.len() - 1];
    for (i, &x) in a.iter().enumerate() {
        for (j, &y) in b.iter().enumerate() {
            out[i + j] = add(out[i + j], mul(x, y));
        }
    }
    trimmed(out)
}

/// Quotient and remainder; `None` for division by 0.
pub(super) fn uni_divrem(a: &[u64], b: &[u64]) -> Option<(Uni, Uni)> {
    let lead = inverse(*b.last()?)?;
    let mut r = a.to_vec();
    if r.len() < b.len() {
        return Some((Vec::new(), r));
    }
    let mut q = vec![0; r.len() - b.len() + 1];
    while r.len() >= b.len() {
        let shift = r.len() - b.len();
        let f = mul(*r.last().expect("nonempty"), lead);
        q[shift] = f;
        for (k, &bk) in b.iter().enumerate() {
            r[shift + k] = sub(r[shift + k], mul(f, bk));
        }
        trim(&mut r);
    }
    Some((trimmed(q), r))
}

/// The monic gcd (gcd(0, 0) = 0).
pub(super) fn uni_gcd(mut a: Uni, mut b: Uni) -> Uni {
    while !b.is_empty() {
        let (_, r) = uni_divrem(&a, &b).expect("b is nonzero");
        a = b;
        b = r;
    }
    match a.last() {
        None => a,
        Some(&lc) => uni_scale(&a, inverse(lc).expect("nonzero")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::VarTable;

    /// The Mersenne reduction agrees with plain 128-bit remainders, at the extremes
    /// and at pseudo-random operands; small and big rationals have the same residues.
    #[test]
    fn reduction_agrees_with_the_remainder() {
        let reference = |a: u64, b: u64| ((u128::from(a) * u128::from(b)) % u128::from(P)) as u64;
        let mut x = 0x9E37_79B9_7F4A_7C15_u64;
        let mut operands = vec![0, 1, 2, P - 1, P - 2, 1 << 60, (1 << 61) - 3];
        for _ in 0..2000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            operands.push(x % P);
        }
        for (k, &a) in operands.iter().enumerate() {
            let b = operands[(k * 7 + 3) % operands.len()];
            assert_eq!(mul(a, b), reference(a, b), "{a} * {b}");
        }
        for (n, d) in [(3, 7), (-5, 11), (i64::MAX, 3), (-1, 1), (0, 1)] {
            let q = Rational::ratio(n, d).unwrap();
            let by_big = mul(of_int(&q.numer()), inverse(of_int(&q.denom())).unwrap());
            assert_eq!(of_rational(&q), Some(by_big));
        }
    }

    #[test]
    fn univariate_images_and_their_gcd_degree() {
        let mut names = VarTable::new();
        let (x, y) = (names.intern("x"), names.intern("y"));
        let (px, py) = (Poly::var(x), Poly::var(y));
        let int = |n: i64| Poly::constant(Rational::int(n));
        // (x − y)(x + 2) and (x − y)(x − 3) at y = 5: a common root, degree 1; with
        // x² + y instead of the second, none.
        let a = &(&px - &py) * &(&px + &int(2));
        let b = &(&px - &py) * &(&px - &int(3));
        let at = |_: Var| 5;
        let ia = univariate_image(&a, x, &at).unwrap();
        assert_eq!(ia, vec![P - 10, P - 3, 1]); // x² − 3x − 10
        assert_eq!(
            gcd_degree(ia.clone(), univariate_image(&b, x, &at).unwrap()),
            1
        );
        let c = &(&px * &px) + &py;
        assert_eq!(
            gcd_degree(ia.clone(), univariate_image(&c, x, &at).unwrap()),
            0
        );
        assert_eq!(gcd_degree(ia.clone(), ia), 2);
        // The image may lose degree (x·y at y = 0), and cancel to zero.
        assert_eq!(
            univariate_image(&(&px * &py), x, &|_| 0).unwrap(),
            Vec::<u64>::new()
        );
        let inv = Poly::term(crate::kernel::poly::Monomial::var(y, -1), Rational::int(1));
        assert_eq!(univariate_image(&inv, x, &at), None);
        let high = Poly::term(
            crate::kernel::poly::Monomial::var(x, 5_000),
            Rational::int(1),
        );
        assert_eq!(univariate_image(&high, x, &at), None);
        assert_eq!(univariate_image(&high, y, &at).map(|i| i.len()), Some(1));
    }

    #[test]
    fn residues_respect_arithmetic() {
        let half = Rational::ratio(1, 2).unwrap();
        assert_eq!(mul(of_rational(&half).unwrap(), 2), 1);
        assert_eq!(of_rational(&Rational::int(-1)), Some(P - 1));
        let mut names = VarTable::new();
        let x = names.intern("x");
        // (x + 1)^2 − x^2 − 2x − 1 = 0 at any residue.
        let px = Poly::var(x);
        let one = Poly::constant(Rational::int(1));
        let sq = &(&px + &one) * &(&px + &one);
        let expanded = &(&(&px * &px) + &(&px * &Poly::constant(Rational::int(2)))) + &one;
        let at = |_: Var| 123_456_789u64;
        assert_eq!(of_poly(&sq, &at), of_poly(&expanded, &at));
        assert_ne!(of_poly(&sq, &at), of_poly(&(&px * &px), &at));
        // x^-1 at 0 is undefined.
        let inv = Poly::term(crate::kernel::poly::Monomial::var(x, -1), Rational::int(1));
        assert_eq!(of_poly(&inv, &|_| 0), None);
    }

    #[test]
    fn univariate_arithmetic_mod_p() {
        // (y + 2)(y − 3) = y² − y − 6, divided back; gcd with (y + 2)(y + 5).
        let m = |n: i64| of_rational(&Rational::int(n)).unwrap();
        let a = uni_mul(&[m(2), 1], &[m(-3), 1]);
        assert_eq!(a, vec![m(-6), m(-1), 1]);
        let (q, r) = uni_divrem(&a, &[m(2), 1]).unwrap();
        assert_eq!((q, r), (vec![m(-3), 1], Vec::new()));
        let b = uni_mul(&[m(2), 1], &[m(5), 1]);
        assert_eq!(uni_gcd(a.clone(), b), vec![m(2), 1]);
        assert_eq!(eval(&a, 3), 0);
        assert_eq!(uni_gcd(a.clone(), vec![m(7)]), vec![1]);
    }
}
