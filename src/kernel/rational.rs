//! Exact rational numbers: the scalar that every exact verdict rests on.
//!
//! Two representations behind one type: a fast path for numerator and denominator that
//! fit in `i64` (arithmetic in `i128`, which cannot overflow for a product or a sum of
//! two such fractions) and `num_rational::BigRational` for everything else. Every
//! result is normalised — lowest terms, positive denominator, and the small form
//! whenever the value fits — so equal values have identical representations and `==`
//! and `Hash` stay structural. Arbitrary precision keeps the kernel free of overflow:
//! no coefficient can wrap silently (tested at the boundary of the fast path below).

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};
use std::cmp::Ordering;
use std::fmt;
use std::ops::{Add, AddAssign, Mul, Neg, Sub};

/// The most bits an exact power may have ([`Rational::pow`]).
const MAX_POWER_BITS: u64 = 1 << 24;

/// The representation: `Small(n, d)` with d > 0, gcd(n, d) = 1 and n ≠ i64::MIN (so
/// that negation stays small), used exactly when the value fits; `Big` otherwise.
#[derive(Clone, PartialEq, Eq, Hash, Debug)]
enum Repr {
    Small(i64, i64),
    /// Boxed, so that the common small case keeps a term of a polynomial compact.
    Big(Box<BigRational>),
}

/// An exact rational number, always in lowest terms with a positive denominator, so
/// that equal values have equal representations (`==` and `Hash` are structural).
#[derive(Clone, PartialEq, Eq, Hash, Debug)]
pub struct Rational(Repr);

fn gcd_u128(mut a: u128, mut b: u128) -> u128 {
    // 128-bit division is a library call; most operands fit in 64 bits.
    if let (Ok(x), Ok(y)) = (u64::try_from(a), u64::try_from(b)) {
        return u128::from(gcd_u64(x, y));
    }
    while b != 0 {
        (a, b) = (b, a % b);
        if let (Ok(x), Ok(y)) = (u64::try_from(a), u64::try_from(b)) {
            return u128::from(gcd_u64(x, y));
        }
    }
    a
}

/// Binary gcd (Stein): shifts and subtractions, no division.
fn gcd_u64(mut a: u64, mut b: u64) -> u64 {
    if a == 0 {
        return b;
    }
    if b == 0 {
        return a;
    }
    let shift = (a | b).trailing_zeros();
    a >>= a.trailing_zeros();
    loop {
        b >>= b.trailing_zeros();
        if a > b {
            std::mem::swap(&mut a, &mut b);
        }
        b -= a;
        if b == 0 {
            return a << shift;
        }
    }
}

/// n/d in normal form from 128-bit parts (d ≠ 0, |n|, |d| < 2^127).
fn from_i128(n: i128, d: i128) -> Rational {
    debug_assert!(d != 0);
    if d == 1 {
        if let Ok(small) = i64::try_from(n) {
            if small != i64::MIN {
                return Rational(Repr::Small(small, 1));
            }
        }
    }
    if let (Ok(n), Ok(d)) = (i64::try_from(n), i64::try_from(d)) {
        // Both fit in 64 bits: divide in 64 bits (128-bit division is a library call).
        let g = gcd_u64(n.unsigned_abs(), d.unsigned_abs()).max(1);
        let (un, ud) = (n.unsigned_abs() / g, d.unsigned_abs() / g);
        let negative = (n < 0) != (d < 0);
        if let (Ok(un), Ok(ud)) = (i64::try_from(un), i64::try_from(ud)) {
            return Rational(Repr::Small(if negative { -un } else { un }, ud));
        }
    }
    let g = gcd_u128(n.unsigned_abs(), d.unsigned_abs()).max(1) as i128;
    let (mut n, mut d) = (n / g, d / g);
    if d < 0 {
        n = -n;
        d = -d;
    }
    if n > i128::from(i64::MIN) && n <= i128::from(i64::MAX) && d <= i128::from(i64::MAX) {
        Rational(Repr::Small(n as i64, d as i64))
    } else {
        Rational(Repr::Big(Box::new(BigRational::new_raw(
            BigInt::from(n),
            BigInt::from(d),
        ))))
    }
}

/// A reduced big rational in normal form (small when it fits).
fn from_big_reduced(r: BigRational) -> Rational {
    match (r.numer().to_i64(), r.denom().to_i64()) {
        (Some(n), Some(d)) if n != i64::MIN => Rational(Repr::Small(n, d)),
        _ => Rational(Repr::Big(Box::new(r))),
    }
}

impl Rational {
    /// The integer `n`.
    pub fn int(n: i64) -> Self {
        from_i128(i128::from(n), 1)
    }

    /// `n / d`, or `None` when `d == 0`.
    pub fn ratio(n: i64, d: i64) -> Option<Self> {
        (d != 0).then(|| from_i128(i128::from(n), i128::from(d)))
    }

    fn big(&self) -> BigRational {
        match &self.0 {
            Repr::Small(n, d) => BigRational::new_raw(BigInt::from(*n), BigInt::from(*d)),
            Repr::Big(r) => (**r).clone(),
        }
    }

    pub fn is_zero(&self) -> bool {
        matches!(self.0, Repr::Small(0, _))
    }

    pub fn is_one(&self) -> bool {
        matches!(self.0, Repr::Small(1, 1))
    }

    pub fn is_negative(&self) -> bool {
        match &self.0 {
            Repr::Small(n, _) => *n < 0,
            Repr::Big(r) => r.is_negative(),
        }
    }

    /// −1, 0 or 1.
    pub fn signum(&self) -> i32 {
        if self.is_zero() {
            0
        } else if self.is_negative() {
            -1
        } else {
            1
        }
    }

    pub fn is_integer(&self) -> bool {
        match &self.0 {
            Repr::Small(_, d) => *d == 1,
            Repr::Big(r) => r.is_integer(),
        }
    }

    /// `1 / self`, or `None` for zero.
    pub fn recip(&self) -> Option<Self> {
        match &self.0 {
            Repr::Small(0, _) => None,
            Repr::Small(n, d) if *n > 0 => Some(Rational(Repr::Small(*d, *n))),
            Repr::Small(n, d) => Some(Rational(Repr::Small(-*d, -*n))),
            Repr::Big(r) => Some(from_big_reduced(r.recip())),
        }
    }

    /// `self / other`, or `None` when `other` is zero.
    pub fn checked_div(&self, other: &Self) -> Option<Self> {
        other.recip().map(|r| self * &r)
    }

    /// `self^e` for any integer exponent; `None` for a negative power of zero, or a
    /// power of more than 2^24 bits (past that, an exact value is no use to a check).
    pub fn pow(&self, e: i64) -> Option<Self> {
        if e < 0 {
            return self.recip()?.pow(e.checked_neg()?);
        }
        let trivial = self.is_zero() || self.is_one() || *self == Rational::int(-1);
        if !trivial && self.bits().saturating_mul(e.unsigned_abs()) > MAX_POWER_BITS {
            return None;
        }
        let (mut base, mut e, mut acc) = (self.clone(), e.unsigned_abs(), Rational::one());
        while e > 0 {
            if e & 1 == 1 {
                acc = &acc * &base;
            }
            e >>= 1;
            if e > 0 {
                base = &base * &base;
            }
        }
        Some(acc)
    }

    /// The exact square root when `self` is the square of a rational, else `None`.
    pub fn sqrt_exact(&self) -> Option<Self> {
        if self.is_negative() {
            return None;
        }
        let r = self.big();
        let n = r.numer().sqrt();
        let d = r.denom().sqrt();
        let root = BigRational::new(n, d);
        (&root * &root == r).then(|| from_big_reduced(root))
    }

    /// The numerator (the sign is carried here; the denominator is positive).
    pub fn numer(&self) -> BigInt {
        match &self.0 {
            Repr::Small(n, _) => BigInt::from(*n),
            Repr::Big(r) => r.numer().clone(),
        }
    }

    /// Numerator and denominator when both fit in `i64` (the denominator positive).
    pub fn small_parts(&self) -> Option<(i64, i64)> {
        match self.0 {
            Repr::Small(n, d) => Some((n, d)),
            Repr::Big(_) => None,
        }
    }

    /// The denominator, always positive.
    pub fn denom(&self) -> BigInt {
        match &self.0 {
            Repr::Small(_, d) => BigInt::from(*d),
            Repr::Big(r) => r.denom().clone(),
        }
    }

    /// `n / d` for big integers, or `None` when `d == 0`.
    pub fn from_big(n: BigInt, d: BigInt) -> Option<Self> {
        (!d.is_zero()).then(|| from_big_reduced(BigRational::new(n, d)))
    }

    /// Bits in the numerator and the denominator together: the size of the number.
    pub fn bits(&self) -> u64 {
        match &self.0 {
            Repr::Small(n, d) => {
                u64::from(64 - n.unsigned_abs().leading_zeros())
                    + u64::from(64 - d.unsigned_abs().leading_zeros())
            }
            Repr::Big(r) => r.numer().bits() + r.denom().bits(),
        }
    }

    /// The nearest `f64` (used only by numeric cross-checks, never by exact verdicts).
    pub fn to_f64(&self) -> f64 {
        match &self.0 {
            Repr::Small(n, d) if n.unsigned_abs() < 1 << 53 && *d < 1 << 53 => {
                *n as f64 / *d as f64
            }
            _ => self.big().to_f64().unwrap_or(f64::NAN),
        }
    }
}

impl PartialOrd for Rational {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// Ordered by value.
impl Ord for Rational {
    fn cmp(&self, other: &Self) -> Ordering {
        match (&self.0, &other.0) {
            (Repr::Small(a, b), Repr::Small(c, d)) => {
                (i128::from(*a) * i128::from(*d)).cmp(&(i128::from(*c) * i128::from(*b)))
            }
            _ => self.big().cmp(&other.big()),
        }
    }
}

impl fmt::Display for Rational {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.0 {
            Repr::Small(n, 1) => write!(f, "{n}"),
            Repr::Small(n, d) => write!(f, "{n}/{d}"),
            Repr::Big(r) if r.is_integer() => write!(f, "{}", r.numer()),
            Repr::Big(r) => write!(f, "{}/{}", r.numer(), r.denom()),
        }
    }
}

/// Written as its text, `-3/4`: the form a report keeps and `recheck` reads back.
impl serde::Serialize for Rational {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

impl<'de> serde::Deserialize<'de> for Rational {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let text = <std::borrow::Cow<'de, str>>::deserialize(d)?;
        Rational::parse_fraction(&text)
            .ok_or_else(|| serde::de::Error::custom(format!("not a rational number: {text:.40}")))
    }
}

/// The most digits [`Rational::parse_fraction`] reads in a numerator or denominator.
const MAX_FRACTION_DIGITS: usize = 100_000;

impl Rational {
    /// `n` or `n/d` in decimal integers, as [`Display`](fmt::Display) writes them;
    /// `None` for anything else, a zero denominator, or more than 100,000 digits.
    pub fn parse_fraction(text: &str) -> Option<Self> {
        let integer = |t: &str| -> Option<BigInt> {
            let digits = t.strip_prefix('-').unwrap_or(t);
            let plain = !digits.is_empty()
                && digits.len() <= MAX_FRACTION_DIGITS
                && digits.bytes().all(|b| b.is_ascii_digit());
            plain.then(|| t.parse().ok()).flatten()
        };
        let (n, d) = match text.split_once('/') {
            Some((n, d)) => (integer(n)?, integer(d)?),
            None => (integer(text)?, BigInt::one()),
        };
        Rational::from_big(n, d)
    }
}

impl From<i64> for Rational {
    fn from(n: i64) -> Self {
        Rational::int(n)
    }
}

impl Zero for Rational {
    fn zero() -> Self {
        Rational(Repr::Small(0, 1))
    }
    fn is_zero(&self) -> bool {
        Rational::is_zero(self)
    }
}

impl One for Rational {
    fn one() -> Self {
        Rational(Repr::Small(1, 1))
    }
}

impl Add<&Rational> for &Rational {
    type Output = Rational;
    fn add(self, rhs: &Rational) -> Rational {
        match (&self.0, &rhs.0) {
            (Repr::Small(a, b), Repr::Small(c, d)) if b == d => {
                from_i128(i128::from(*a) + i128::from(*c), i128::from(*b))
            }
            (Repr::Small(a, b), Repr::Small(c, d)) => from_i128(
                i128::from(*a) * i128::from(*d) + i128::from(*c) * i128::from(*b),
                i128::from(*b) * i128::from(*d),
            ),
            // Integers add without a gcd, as they multiply below.
            _ => match (self.big(), rhs.big()) {
                (a, b) if a.is_integer() && b.is_integer() => {
                    from_big_reduced(BigRational::from_integer(a.numer() + b.numer()))
                }
                (a, b) => from_big_reduced(a + b),
            },
        }
    }
}

impl Sub<&Rational> for &Rational {
    type Output = Rational;
    fn sub(self, rhs: &Rational) -> Rational {
        self + &(-rhs)
    }
}

impl Mul<&Rational> for &Rational {
    type Output = Rational;
    fn mul(self, rhs: &Rational) -> Rational {
        match (&self.0, &rhs.0) {
            (Repr::Small(a, b), Repr::Small(c, d)) => from_i128(
                i128::from(*a) * i128::from(*c),
                i128::from(*b) * i128::from(*d),
            ),
            // Integers multiply without a gcd (a binary gcd with 1 takes time
            // quadratic in the bits: 90% of a product of 4,000-bit coefficients).
            _ => match (self.big(), rhs.big()) {
                (a, b) if a.is_integer() && b.is_integer() => {
                    from_big_reduced(BigRational::from_integer(a.numer() * b.numer()))
                }
                (a, b) => from_big_reduced(a * b),
            },
        }
    }
}

macro_rules! owned_binop {
    ($tr:ident, $method:ident) => {
        impl $tr for Rational {
            type Output = Rational;
            fn $method(self, rhs: Rational) -> Rational {
                (&self).$method(&rhs)
            }
        }
    };
}
owned_binop!(Add, add);
owned_binop!(Sub, sub);
owned_binop!(Mul, mul);

impl AddAssign<&Rational> for Rational {
    fn add_assign(&mut self, rhs: &Rational) {
        *self = &*self + rhs;
    }
}

impl Neg for Rational {
    type Output = Rational;
    fn neg(self) -> Rational {
        -&self
    }
}

impl Neg for &Rational {
    type Output = Rational;
    fn neg(self) -> Rational {
        match &self.0 {
            // n ≠ i64::MIN by the invariant, so −n fits.
            Repr::Small(n, d) => Rational(Repr::Small(-*n, *d)),
            Repr::Big(r) => from_big_reduced(-(**r).clone()),
        }
    }
}

#[cfg(test)]
mod tests {
    /// The binary gcd and the 64-bit fast path of the normal form agree with Euclid's
    /// algorithm in 128 bits, at the extremes of the range and at pseudo-random values.
    #[test]
    fn fast_gcd_agrees_with_euclid() {
        fn euclid(mut a: u128, mut b: u128) -> u128 {
            while b != 0 {
                (a, b) = (b, a % b);
            }
            a
        }
        let mut x = 0x2545_F491_4F6C_DD1D_u64;
        let mut values: Vec<u64> = vec![0, 1, 2, 3, 6, 1 << 63, u64::MAX, u64::MAX - 1, 1 << 32];
        for _ in 0..3000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            values.push(x >> (x % 64));
        }
        for (k, &a) in values.iter().enumerate() {
            let b = values[(k * 13 + 5) % values.len()];
            assert_eq!(u128::from(super::gcd_u64(a, b)), euclid(a.into(), b.into()));
            assert_eq!(
                super::gcd_u128(a.into(), b.into()),
                euclid(a.into(), b.into())
            );
        }
        // The normal form: lowest terms, positive denominator, whichever path builds it.
        for &(n, d) in &[
            (6i128, -4i128),
            (-9, 3),
            (0, -5),
            (i128::from(i64::MIN), 2),
            (i128::from(i64::MIN), 1),
            (i128::from(i64::MAX) + 1, 2),
        ] {
            let q = super::from_i128(n, d);
            let g = euclid(n.unsigned_abs(), d.unsigned_abs()) as i128;
            let (mut en, mut ed) = (n / g, d / g);
            if ed < 0 {
                (en, ed) = (-en, -ed);
            }
            assert_eq!(q.numer(), num_bigint::BigInt::from(en), "{n}/{d}");
            assert_eq!(q.denom(), num_bigint::BigInt::from(ed), "{n}/{d}");
        }
    }

    use super::*;

    fn q(n: i64, d: i64) -> Rational {
        Rational::ratio(n, d).unwrap()
    }

    #[test]
    fn canonical_form_makes_equal_values_identical() {
        assert_eq!(q(2, 4), q(-1, -2));
        assert_eq!(q(2, 4).to_string(), "1/2");
        assert_eq!(q(3, -6).to_string(), "-1/2");
        assert_eq!(q(6, 3).to_string(), "2");
        assert_ne!(q(1, 3), q(1, 2));
    }

    #[test]
    fn arithmetic_is_exact() {
        assert_eq!(&q(1, 3) + &q(1, 6), q(1, 2));
        assert_eq!(&q(1, 3) - &q(1, 2), q(-1, 6));
        assert_eq!(&q(2, 3) * &q(9, 4), q(3, 2));
        assert_eq!(q(2, 3).checked_div(&q(4, 9)), Some(q(3, 2)));
        assert_eq!(q(2, 3).checked_div(&Rational::zero()), None);
        assert_eq!(Rational::ratio(1, 0), None);
        assert_eq!(q(2, 3).pow(-2), Some(q(9, 4)));
        assert_eq!(Rational::zero().pow(-1), None);
    }

    #[test]
    fn big_values_do_not_overflow() {
        let big = Rational::int(i64::MAX);
        let sq = &big * &big;
        assert_eq!(sq.to_string(), "85070591730234615847396907784232501249");
        assert_eq!(sq.sqrt_exact(), Some(big));
    }

    #[test]
    fn square_roots_only_of_squares() {
        assert_eq!(q(9, 4).sqrt_exact(), Some(q(3, 2)));
        assert_eq!(q(2, 1).sqrt_exact(), None);
        assert_eq!(q(-4, 1).sqrt_exact(), None);
    }

    #[test]
    fn the_fast_path_promotes_at_its_boundary_and_demotes_back() {
        // i64::MIN is kept big so that negation cannot overflow.
        let min = &Rational::int(i64::MIN + 1) - &Rational::int(1);
        assert_eq!(min.to_string(), "-9223372036854775808");
        assert!(matches!(min.0, Repr::Big(_)));
        assert_eq!((-&min).to_string(), "9223372036854775808");
        // A product beyond i64 is big; dividing back gives the small form again, so
        // equal values stay identical.
        let big = &Rational::int(i64::MAX) * &Rational::int(3);
        assert!(matches!(big.0, Repr::Big(_)));
        let back = big.checked_div(&Rational::int(3)).unwrap();
        assert_eq!(back, Rational::int(i64::MAX));
        assert!(matches!(back.0, Repr::Small(_, _)));
        // Sums of fractions with large coprime denominators.
        let a = q(1, i64::MAX);
        let b = q(1, i64::MAX - 1);
        let s = &a + &b;
        assert_eq!(&s - &b, a);
        assert!(q(1, 3) < q(1, 2) && q(-1, 2) < q(1, 3) && big > Rational::int(i64::MAX));
        assert_eq!(
            Rational::from_big(BigInt::from(6), BigInt::from(-4)),
            Some(q(-3, 2))
        );
        assert_eq!(q(2, 3).bits(), 4);
    }

    #[test]
    fn small_and_big_arithmetic_agree_on_random_values() {
        // Compare against BigRational directly on values near the i64 boundary.
        let mut state = 7u64;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 1) as i64 - (1 << 62)
        };
        for _ in 0..2000 {
            let (a, b, c, d) = (
                next(),
                next().max(1),
                next() >> (next() & 63),
                next().max(1) >> 20,
            );
            let d = d.max(1);
            let x = q(a, b);
            let y = q(c, d);
            let bx = BigRational::new(BigInt::from(a), BigInt::from(b));
            let by = BigRational::new(BigInt::from(c), BigInt::from(d));
            assert_eq!((&x + &y).big(), &bx + &by);
            assert_eq!((&x - &y).big(), &bx - &by);
            assert_eq!((&x * &y).big(), &bx * &by);
            assert_eq!(x.cmp(&y), bx.cmp(&by));
            assert_eq!(from_big_reduced(&bx + &by), &x + &y);
        }
    }
}
