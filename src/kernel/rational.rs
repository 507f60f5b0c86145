//! Exact rational numbers: the scalar that every exact verdict rests on.
//!
//! A thin newtype over `num_rational::BigRational`, so the representation can change
//! (an `i128` fast path, say) without touching any caller. Arbitrary precision keeps
//! the kernel free of overflow: no coefficient can wrap silently.

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};
use std::fmt;
use std::ops::{Add, AddAssign, Mul, Neg, Sub};

/// An exact rational number, always in lowest terms with a positive denominator, so
/// that equal values have equal representations (`==` and `Hash` are structural).
#[derive(Clone, PartialEq, Eq, Hash, PartialOrd, Ord, Debug)]
pub struct Rational(BigRational);

impl Rational {
    /// The integer `n`.
    pub fn int(n: i64) -> Self {
        Rational(BigRational::from_integer(BigInt::from(n)))
    }

    /// `n / d`, or `None` when `d == 0`.
    pub fn ratio(n: i64, d: i64) -> Option<Self> {
        (d != 0).then(|| Rational(BigRational::new(BigInt::from(n), BigInt::from(d))))
    }

    /// Parses a plain decimal literal such as `12`, `0.25` or `3.` exactly.
    pub fn parse_decimal(text: &str) -> Option<Self> {
        let (int_part, frac_part) = match text.split_once('.') {
            Some((a, b)) => (a, b),
            None => (text, ""),
        };
        let all_digits = |s: &str| s.bytes().all(|b| b.is_ascii_digit());
        if int_part.is_empty() && frac_part.is_empty()
            || !all_digits(int_part)
            || !all_digits(frac_part)
        {
            return None;
        }
        let digits = format!("{int_part}{frac_part}");
        let numer: BigInt = digits.parse().ok()?;
        let denom = num_traits::pow(BigInt::from(10), frac_part.len());
        Some(Rational(BigRational::new(numer, denom)))
    }

    pub fn is_zero(&self) -> bool {
        self.0.is_zero()
    }

    pub fn is_one(&self) -> bool {
        self.0.is_one()
    }

    pub fn is_negative(&self) -> bool {
        self.0.is_negative()
    }

    pub fn is_integer(&self) -> bool {
        self.0.is_integer()
    }

    /// `1 / self`, or `None` for zero.
    pub fn recip(&self) -> Option<Self> {
        (!self.is_zero()).then(|| Rational(self.0.recip()))
    }

    /// `self / other`, or `None` when `other` is zero.
    pub fn checked_div(&self, other: &Self) -> Option<Self> {
        other.recip().map(|r| self * &r)
    }

    /// `self^e` for any integer exponent; `None` for a negative power of zero.
    pub fn pow(&self, e: i32) -> Option<Self> {
        if e < 0 {
            return self.recip().map(|r| r.pow(-e).expect("nonzero base"));
        }
        Some(Rational(num_traits::pow(self.0.clone(), e as usize)))
    }

    /// The exact square root when `self` is the square of a rational, else `None`.
    pub fn sqrt_exact(&self) -> Option<Self> {
        if self.is_negative() {
            return None;
        }
        let n = self.0.numer().sqrt();
        let d = self.0.denom().sqrt();
        let root = BigRational::new(n, d);
        (&root * &root == self.0).then_some(Rational(root))
    }

    /// The numerator (the sign is carried here; the denominator is positive).
    pub fn numer(&self) -> &BigInt {
        self.0.numer()
    }

    /// The denominator, always positive.
    pub fn denom(&self) -> &BigInt {
        self.0.denom()
    }

    /// `n / d` for big integers, or `None` when `d == 0`.
    pub fn from_big(n: BigInt, d: BigInt) -> Option<Self> {
        (!d.is_zero()).then(|| Rational(BigRational::new(n, d)))
    }

    /// Bits in the numerator and the denominator together: the size of the number.
    pub fn bits(&self) -> u64 {
        self.0.numer().bits() + self.0.denom().bits()
    }

    /// The nearest `f64` (used only by numeric cross-checks, never by exact verdicts).
    pub fn to_f64(&self) -> f64 {
        self.0.to_f64().unwrap_or(f64::NAN)
    }

    /// LaTeX form: `\frac{p}{q}` or `p`, with a leading minus sign.
    pub fn latex(&self) -> String {
        if self.is_integer() {
            return self.0.numer().to_string();
        }
        let sign = if self.is_negative() { "-" } else { "" };
        format!(
            "{sign}\\frac{{{}}}{{{}}}",
            self.0.numer().abs(),
            self.0.denom()
        )
    }
}

impl fmt::Display for Rational {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.is_integer() {
            write!(f, "{}", self.0.numer())
        } else {
            write!(f, "{}/{}", self.0.numer(), self.0.denom())
        }
    }
}

impl From<i64> for Rational {
    fn from(n: i64) -> Self {
        Rational::int(n)
    }
}

impl Zero for Rational {
    fn zero() -> Self {
        Rational(BigRational::zero())
    }
    fn is_zero(&self) -> bool {
        self.0.is_zero()
    }
}

impl One for Rational {
    fn one() -> Self {
        Rational(BigRational::one())
    }
}

macro_rules! forward_binop {
    ($tr:ident, $method:ident) => {
        impl $tr<&Rational> for &Rational {
            type Output = Rational;
            fn $method(self, rhs: &Rational) -> Rational {
                Rational((&self.0).$method(&rhs.0))
            }
        }
        impl $tr for Rational {
            type Output = Rational;
            fn $method(self, rhs: Rational) -> Rational {
                Rational(self.0.$method(rhs.0))
            }
        }
    };
}
forward_binop!(Add, add);
forward_binop!(Sub, sub);
forward_binop!(Mul, mul);

impl AddAssign<&Rational> for Rational {
    fn add_assign(&mut self, rhs: &Rational) {
        self.0 += &rhs.0;
    }
}

impl Neg for Rational {
    type Output = Rational;
    fn neg(self) -> Rational {
        Rational(-self.0)
    }
}

impl Neg for &Rational {
    type Output = Rational;
    fn neg(self) -> Rational {
        Rational(-&self.0)
    }
}

#[cfg(test)]
mod tests {
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
    fn decimal_literals_parse_exactly() {
        assert_eq!(Rational::parse_decimal("0.25"), Some(q(1, 4)));
        assert_eq!(Rational::parse_decimal("12"), Some(Rational::int(12)));
        assert_eq!(Rational::parse_decimal("3."), Some(Rational::int(3)));
        assert_eq!(Rational::parse_decimal("."), None);
        assert_eq!(Rational::parse_decimal("1.2.3"), None);
    }

    #[test]
    fn square_roots_only_of_squares() {
        assert_eq!(q(9, 4).sqrt_exact(), Some(q(3, 2)));
        assert_eq!(q(2, 1).sqrt_exact(), None);
        assert_eq!(q(-4, 1).sqrt_exact(), None);
    }

    #[test]
    fn latex_form() {
        assert_eq!(q(-1, 15).latex(), "-\\frac{1}{15}");
        assert_eq!(q(4, 1).latex(), "4");
    }
}
