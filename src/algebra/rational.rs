//! Rationals the search picks: the exact value of a float, and the simplest rational
//! between two (so that sample points and cuts read as `1` or `3/2`). Neither is
//! trusted: a point chosen here is checked by the kernel like any other.

use crate::kernel::Rational;
use num_bigint::BigInt;
use num_integer::Integer;

/// The rational a finite `f64` denotes, exactly (every finite float is a dyadic
/// rational); `None` for NaN and infinities.
pub fn from_f64_exact(x: f64) -> Option<Rational> {
    let r = num_rational::BigRational::from_float(x)?;
    Rational::from_big(r.numer().clone(), r.denom().clone())
}

/// The largest integer not above `x`.
pub fn floor(x: &Rational) -> Rational {
    Rational::from_big(x.numer().div_floor(&x.denom()), BigInt::from(1)).expect("1 is nonzero")
}

/// The simplest rational strictly between `a` and `b` (`a < b`): the one with the
/// smallest denominator, and among those the smallest absolute numerator (the
/// Stern–Brocot descent by continued fractions).
pub fn simplest_between(a: &Rational, b: &Rational) -> Rational {
    debug_assert!(a < b);
    let zero = Rational::int(0);
    if a.is_negative() && !b.is_negative() && !b.is_zero() {
        return zero;
    }
    if !b.is_negative() && !b.is_zero() {
        // 0 ≤ a < b.
        let one = Rational::int(1);
        let fl = floor(a);
        let next = &fl + &one;
        if next < *b {
            return next;
        }
        // fl ≤ a < b ≤ fl + 1: descend into the fractional parts.
        let (fa, fb) = (a - &fl, b - &fl);
        let inner = if fa.is_zero() {
            &floor(&fb.recip().expect("b > fl")) + &one
        } else {
            simplest_between(&fb.recip().expect("b > fl"), &fa.recip().expect("fa ≠ 0"))
        };
        return &fl + &inner.recip().expect("inner ≥ 1");
    }
    -simplest_between(&-b, &-a)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::q;
    use num_traits::ToPrimitive;

    #[test]
    fn floor_rounds_towards_minus_infinity() {
        assert_eq!(floor(&q(7, 2)), Rational::int(3));
        assert_eq!(floor(&q(-7, 2)), Rational::int(-4));
        assert_eq!(floor(&Rational::int(-3)), Rational::int(-3));
    }

    #[test]
    fn simplest_rational_between_two() {
        let s = |a: Rational, b: Rational| simplest_between(&a, &b);
        assert_eq!(s(q(-1, 3), q(1, 2)), Rational::int(0));
        assert_eq!(s(q(1, 3), q(1, 2)), q(2, 5));
        assert_eq!(s(Rational::int(0), Rational::int(1)), q(1, 2));
        assert_eq!(s(Rational::int(2), q(7, 3)), q(9, 4));
        assert_eq!(s(q(-1, 2), q(-1, 3)), q(-2, 5));
        assert_eq!(s(q(-1, 2), Rational::int(0)), q(-1, 3));
        assert_eq!(s(q(3, 2), q(7, 2)), Rational::int(2));
        // Brute force: no rational with a smaller denominator lies strictly between.
        for (a, b) in [
            (q(31, 100), q(32, 100)),
            (q(-7, 11), q(-5, 8)),
            (q(1, 1000), q(1, 999)),
        ] {
            let x = s(a.clone(), b.clone());
            assert!(a < x && x < b);
            let d = x.denom().to_i64().unwrap();
            for den in 1..d {
                let lo = floor(&(&a * &Rational::int(den)));
                let cand = (&lo + &Rational::int(1))
                    .checked_div(&Rational::int(den))
                    .unwrap();
                assert!(!(a < cand && cand < b), "{cand} is simpler than {x}");
            }
        }
    }

    #[test]
    fn floats_convert_exactly() {
        assert_eq!(from_f64_exact(0.75), Rational::ratio(3, 4));
        assert_eq!(from_f64_exact(-2.0), Some(Rational::int(-2)));
        // 0.1 is not 1/10 in binary: the conversion keeps what the float is.
        let tenth = from_f64_exact(0.1).unwrap();
        assert_ne!(Some(tenth.clone()), Rational::ratio(1, 10));
        assert_eq!(tenth.to_f64(), 0.1);
        assert_eq!(from_f64_exact(f64::NAN), None);
        assert_eq!(from_f64_exact(f64::INFINITY), None);
    }
}
