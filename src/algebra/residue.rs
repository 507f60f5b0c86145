//! Values modulo a large prime: a cheap screen for "are these two rationals
//! different?". The map ℚ → 𝔽_p (defined where p divides no denominator) is a ring
//! homomorphism, so two values with different residues are different; equal residues
//! decide nothing. The counterexample search uses it to skip candidate points whose
//! exact evaluation (bigint powers of high degree) would be wasted.
//!
//! Prime fields 𝔽_p with p = 2⁶¹ − c and univariate polynomials over them live here
//! too (images of multivariate ones, their gcds by Euclid's algorithm): the gcd proves
//! coprimality with them mod P, and the modular gcd (`super::modular`) builds its
//! candidates from them mod several primes.

use crate::kernel::poly::{Poly, Var};
use crate::kernel::rational::Rational;
use num_bigint::BigInt;
use num_traits::{Signed, ToPrimitive};

/// A prime field 𝔽_p with p = 2⁶¹ − c for a small c, so that a product reduces by
/// folding 2⁶¹ ≡ c twice, with no division. The modular gcd (`super::modular`) uses
/// several; everything else works in [`MERSENNE`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Field {
    c: u64,
}

/// 𝔽_P for the Mersenne prime P = 2⁶¹ − 1.
pub(super) const MERSENNE: Field = Field { c: 1 };

/// The Mersenne prime 2⁶¹ − 1.
pub const P: u64 = MERSENNE.p();

/// The c with 2⁶¹ − c prime, descending from the Mersenne prime: the moduli of the
/// multi-prime gcd. Nothing depends on their primality for soundness (every modular
/// result is checked over ℚ); a test checks it anyway.
const OFFSETS: [u64; 48] = [
    1, 31, 45, 229, 259, 283, 339, 391, 403, 465, 531, 579, 675, 759, 799, 819, 829, 843, 859, 939,
    985, 1015, 1153, 1195, 1215, 1281, 1299, 1351, 1371, 1425, 1489, 1525, 1533, 1543, 1609, 1621,
    1669, 1741, 1753, 1813, 1845, 1849, 1855, 1863, 1869, 1909, 1921, 1923,
];

/// The prime fields of [`OFFSETS`], the Mersenne one first.
pub(super) fn fields() -> impl Iterator<Item = Field> {
    OFFSETS.iter().map(|&c| Field { c })
}

impl Field {
    /// The prime.
    pub(super) const fn p(self) -> u64 {
        (1 << 61) - self.c
    }

    /// a·b mod p for a, b < p.
    #[inline]
    pub(super) fn mul(self, a: u64, b: u64) -> u64 {
        const LOW: u64 = (1 << 61) - 1;
        let x = u128::from(a) * u128::from(b); // < 2¹²²
        let (lo, hi) = (x as u64 & LOW, (x >> 61) as u64); // hi < 2⁶¹
        let z = if self.c == 1 {
            lo + hi // < 2⁶², and below 2P since x ≤ (P − 1)²
        } else {
            let y = u128::from(hi) * u128::from(self.c) + u128::from(lo); // < 2⁷³
            (y as u64 & LOW) + (y >> 61) as u64 * self.c // < 2⁶¹ + 2²⁴ < 2p
        };
        if z >= self.p() {
            z - self.p()
        } else {
            z
        }
    }

    fn add(self, a: u64, b: u64) -> u64 {
        let s = a + b; // < 2p < 2⁶²
        if s >= self.p() {
            s - self.p()
        } else {
            s
        }
    }

    pub(super) fn sub(self, a: u64, b: u64) -> u64 {
        if a >= b {
            a - b
        } else {
            a + self.p() - b
        }
    }

    fn pow(self, mut a: u64, mut e: u64) -> u64 {
        let mut r = 1;
        while e > 0 {
            if e & 1 == 1 {
                r = self.mul(r, a);
            }
            a = self.mul(a, a);
            e >>= 1;
        }
        r
    }

    /// a⁻¹ mod p, `None` for 0 (by Fermat: a^(p−2); monic divisors make 1 common).
    pub(super) fn inverse(self, a: u64) -> Option<u64> {
        match a {
            0 => None,
            1 => Some(1),
            _ => Some(self.pow(a, self.p() - 2)),
        }
    }

    fn of_int(self, n: &BigInt) -> u64 {
        let m = (n.abs() % BigInt::from(self.p()))
            .to_u64()
            .expect("below p");
        if n.is_negative() && m != 0 {
            self.p() - m
        } else {
            m
        }
    }

    /// The residue of a small integer.
    fn of_i64(self, n: i64) -> u64 {
        let m = n.unsigned_abs() % self.p();
        if n < 0 && m != 0 {
            self.p() - m
        } else {
            m
        }
    }

    /// The residue of a rational, `None` when p divides its denominator.
    pub(super) fn of_rational(self, q: &Rational) -> Option<u64> {
        match q.small_parts() {
            Some((n, 1)) => Some(self.of_i64(n)),
            Some((n, d)) => Some(self.mul(self.of_i64(n), self.inverse(self.of_i64(d))?)),
            None => Some(self.mul(
                self.of_int(&q.numer()),
                self.inverse(self.of_int(&q.denom()))?,
            )),
        }
    }

    /// A residue that looks random, from `seed` (splitmix64's finaliser, reduced mod
    /// p): evaluation points far from 0 and 1, the same in every run.
    pub(super) fn scramble(self, seed: u64) -> u64 {
        let mut z = seed.wrapping_add(0x9e37_79b9_7f4a_7c15);
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        (z ^ (z >> 31)) % self.p()
    }
}

pub(super) fn mul(a: u64, b: u64) -> u64 {
    MERSENNE.mul(a, b)
}

pub(super) fn pow(a: u64, e: u64) -> u64 {
    MERSENNE.pow(a, e)
}

pub(super) fn inverse(a: u64) -> Option<u64> {
    MERSENNE.inverse(a)
}

/// The residue mod P of a rational, `None` when P divides its denominator.
pub fn of_rational(q: &Rational) -> Option<u64> {
    MERSENNE.of_rational(q)
}

/// A polynomial's residue at a point given by residues (`None` where a negative power
/// meets a zero residue or a coefficient's denominator vanishes mod P).
pub fn of_poly(p: &Poly, value: &dyn Fn(Var) -> u64) -> Option<u64> {
    let mut total = 0u64;
    for (m, c) in p.terms() {
        let mut t = of_rational(c)?;
        for &(v, e) in m.factors() {
            let x = value(v);
            t = match e.cmp(&0) {
                std::cmp::Ordering::Less => mul(t, pow(inverse(x)?, e.unsigned_abs())),
                // A term with a factor 0 is 0 (unless a negative power of 0 follows:
                // no value), and need not be multiplied out.
                std::cmp::Ordering::Greater if x == 0 || t == 0 => 0,
                std::cmp::Ordering::Greater => mul(t, pow(x, e.unsigned_abs())),
                std::cmp::Ordering::Equal => t,
            };
        }
        total = (total + t) % P;
    }
    Some(total)
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

/// A residue mod P that looks random, from `seed` (see [`Field::scramble`]).
pub(super) fn scramble(seed: u64) -> u64 {
    MERSENNE.scramble(seed)
}

/// The degree of the greatest common divisor of two nonzero univariate polynomials
/// over 𝔽_P (coefficients ascending, no trailing zeros).
pub fn gcd_degree(a: Vec<u64>, b: Vec<u64>) -> usize {
    assert!(
        !a.is_empty() && !b.is_empty(),
        "gcd_degree of a zero polynomial"
    );
    MERSENNE.uni_gcd(a, b).len() - 1
}

/// A univariate polynomial over 𝔽_p, coefficients ascending, no trailing zeros (empty
/// for 0).
pub(super) type Uni = Vec<u64>;

fn trimmed(mut u: Uni) -> Uni {
    trim(&mut u);
    u
}

/// Univariate arithmetic over 𝔽_p: the images of the modular gcd and the coprimality
/// proofs.
impl Field {
    /// The value at `x` (Horner).
    pub(super) fn eval(self, u: &[u64], x: u64) -> u64 {
        u.iter()
            .rev()
            .fold(0, |acc, &c| self.add(self.mul(acc, x), c))
    }

    pub(super) fn uni_add(self, a: &[u64], b: &[u64]) -> Uni {
        let mut out = vec![0; a.len().max(b.len())];
        for (k, o) in out.iter_mut().enumerate() {
            *o = self.add(
                a.get(k).copied().unwrap_or(0),
                b.get(k).copied().unwrap_or(0),
            );
        }
        trimmed(out)
    }

    pub(super) fn uni_scale(self, a: &[u64], s: u64) -> Uni {
        trimmed(a.iter().map(|&c| self.mul(c, s)).collect())
    }

    pub(super) fn uni_mul(self, a: &[u64], b: &[u64]) -> Uni {
        if a.is_empty() || b.is_empty() {
            return Vec::new();
        }
        let mut out = vec![0; a.len() + b.len() - 1];
        for (i, &x) in a.iter().enumerate() {
            for (j, &y) in b.iter().enumerate() {
                out[i + j] = self.add(out[i + j], self.mul(x, y));
            }
        }
        trimmed(out)
    }

    /// Quotient and remainder; `None` for division by 0.
    pub(super) fn uni_divrem(self, a: &[u64], b: &[u64]) -> Option<(Uni, Uni)> {
        let lead = self.inverse(*b.last()?)?;
        let mut r = a.to_vec();
        if r.len() < b.len() {
            return Some((Vec::new(), r));
        }
        let mut q = vec![0; r.len() - b.len() + 1];
        while r.len() >= b.len() {
            let shift = r.len() - b.len();
            let f = self.mul(*r.last().expect("nonempty"), lead);
            q[shift] = f;
            for (k, &bk) in b.iter().enumerate() {
                r[shift + k] = self.sub(r[shift + k], self.mul(f, bk));
            }
            trim(&mut r);
        }
        Some((trimmed(q), r))
    }

    /// A nonzero multiple of the remainder of `a` by a nonzero `b`: each step scales
    /// the partial remainder by b's leading coefficient instead of dividing by it, so
    /// Euclid's algorithm needs no inverse (one costs about 120 products).
    fn uni_rem_scaled(self, a: &[u64], b: &[u64]) -> Uni {
        let lead = *b.last().expect("a nonzero divisor");
        let mut r = a.to_vec();
        while r.len() >= b.len() {
            let shift = r.len() - b.len();
            let f = *r.last().expect("nonempty");
            for x in r.iter_mut() {
                *x = self.mul(*x, lead);
            }
            for (k, &bk) in b.iter().enumerate() {
                r[shift + k] = self.sub(r[shift + k], self.mul(f, bk));
            }
            trim(&mut r);
        }
        r
    }

    /// The monic gcd (gcd(0, 0) = 0).
    pub(super) fn uni_gcd(self, mut a: Uni, mut b: Uni) -> Uni {
        while !b.is_empty() {
            let r = self.uni_rem_scaled(&a, &b);
            a = b;
            b = r;
        }
        match a.last() {
            None => a,
            Some(&lc) => self.uni_scale(&a, self.inverse(lc).expect("nonzero")),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::VarTable;

    /// The folding reduction agrees with plain 128-bit remainders in every field, at
    /// the extremes and at pseudo-random operands; small and big rationals have the
    /// same residues.
    #[test]
    fn reduction_agrees_with_the_remainder() {
        let mut x = 0x9E37_79B9_7F4A_7C15_u64;
        let mut draws = Vec::new();
        for _ in 0..2000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            draws.push(x);
        }
        for f in fields() {
            let p = f.p();
            let reference =
                |a: u64, b: u64| ((u128::from(a) * u128::from(b)) % u128::from(p)) as u64;
            let mut operands = vec![0, 1, 2, p - 1, p - 2, 1 << 60, p / 2];
            operands.extend(draws.iter().map(|d| d % p));
            for (k, &a) in operands.iter().enumerate() {
                let b = operands[(k * 7 + 3) % operands.len()];
                assert_eq!(f.mul(a, b), reference(a, b), "{a} * {b} mod {p}");
            }
        }
        for (n, d) in [(3, 7), (-5, 11), (i64::MAX, 3), (-1, 1), (0, 1)] {
            let q = Rational::ratio(n, d).unwrap();
            let by_big = mul(
                MERSENNE.of_int(&q.numer()),
                inverse(MERSENNE.of_int(&q.denom())).unwrap(),
            );
            assert_eq!(of_rational(&q), Some(by_big));
        }
    }

    /// Every modulus is prime (Miller–Rabin with the first twelve prime bases, which
    /// is deterministic below 3.3·10²⁴), and they are distinct and descending.
    #[test]
    fn the_moduli_are_distinct_primes() {
        let ps: Vec<u64> = fields().map(Field::p).collect();
        assert!(ps.windows(2).all(|w| w[0] > w[1]));
        for &p in &ps {
            let f = Field { c: (1 << 61) - p };
            let (mut d, mut s) = (p - 1, 0);
            while d % 2 == 0 {
                d /= 2;
                s += 1;
            }
            for a in [2u64, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37] {
                let mut y = f.pow(a, d);
                let witness = y != 1
                    && (0..s).all(|_| {
                        let minus_one = y == p - 1;
                        y = f.mul(y, y);
                        !minus_one
                    });
                assert!(!witness, "{p} is composite (witness {a})");
            }
        }
        // A composite modulus fails Fermat's test: 2⁶¹ − 3 = 29 · 79511827903920481.
        let f = Field { c: 3 };
        assert_ne!(f.pow(2, f.p() - 1), 1);
    }

    /// A polynomial's residue is the residue of its exact value, at points with zeros
    /// (a term through 0 vanishes; a negative power of 0 has no residue, as it has no
    /// value).
    #[test]
    fn a_polynomial_s_residue_is_that_of_its_value() {
        let mut names = VarTable::new();
        let (x, y, z) = (names.intern("x"), names.intern("y"), names.intern("z"));
        let term = |c: i64, f: &[(Var, i32)]| {
            crate::kernel::Poly::from_terms(vec![(
                crate::kernel::Monomial::checked_from_factors(
                    f.iter().map(|&(v, e)| (v, e.into())).collect(),
                )
                .unwrap(),
                Rational::ratio(c, 3).unwrap(),
            )])
        };
        let p = &(&term(5, &[(x, 2), (y, 1)]) + &term(-7, &[(y, 3), (z, 2)]))
            + &(&term(2, &[(z, 1)]) + &term(1, &[]));
        let q = &p + &term(4, &[(x, 1), (z, -1)]);
        for point in [
            [0, 0, 0],
            [1, 0, 2],
            [0, 3, 0],
            [2, -1, 5],
            [-4, 0, 0],
            [3, 2, 1],
        ] {
            let exact = |v: Var| {
                Rational::int(
                    [x, y, z]
                        .iter()
                        .position(|&w| w == v)
                        .map_or(0, |k| point[k]),
                )
            };
            let residue = |v: Var| of_rational(&exact(v)).unwrap();
            for poly in [&p, &q] {
                let value = poly.eval(&exact);
                assert_eq!(
                    of_poly(poly, &residue),
                    value.and_then(|v| of_rational(&v)),
                    "{point:?}"
                );
            }
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
        let f = MERSENNE;
        let a = f.uni_mul(&[m(2), 1], &[m(-3), 1]);
        assert_eq!(a, vec![m(-6), m(-1), 1]);
        let (q, r) = f.uni_divrem(&a, &[m(2), 1]).unwrap();
        assert_eq!((q, r), (vec![m(-3), 1], Vec::new()));
        let b = f.uni_mul(&[m(2), 1], &[m(5), 1]);
        assert_eq!(f.uni_gcd(a.clone(), b), vec![m(2), 1]);
        assert_eq!(f.eval(&a, 3), 0);
        assert_eq!(f.uni_gcd(a.clone(), vec![m(7)]), vec![1]);
    }
}
