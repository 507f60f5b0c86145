//! How numbers are written in every output: rounded to a number of **significant**
//! digits (never to a fixed number of decimals, which prints 0.000002 as 0.000000 and
//! 123456.789 with nine digits of noise), without trailing zeros, so that a grid value
//! such as 0.05 reads as it was written. Very large and very small magnitudes switch to
//! scientific notation, as `%g` does.

/// Digits of a coordinate of a sampled state (a counterexample's point).
pub const POINT: usize = 6;
/// Digits of a value compared in a verdict (both sides of a relation, a derivative, an
/// eigenvalue): enough to show a relative difference of 1e-9.
pub const VALUE: usize = 10;

/// `x` rounded to `digits` significant digits (at least 1), without trailing zeros;
/// plain decimals for magnitudes from 1e-4 up to 10^digits, scientific notation
/// (`1.5e-7`) outside. `NaN`, `inf` and `-inf` are written as such.
///
/// ```
/// use cosserat_check::digits::significant;
/// assert_eq!(significant(0.05, 12), "0.05");
/// assert_eq!(significant(-0.0023431234, 6), "-0.00234312");
/// assert_eq!(significant(2.0, 6), "2");
/// assert_eq!(significant(9.9999996, 6), "10");
/// assert_eq!(significant(1.5e-7, 6), "1.5e-7");
/// assert_eq!(significant(-3.875353978e12, 4), "-3.875e12");
/// ```
pub fn significant(x: f64, digits: usize) -> String {
    if !x.is_finite() {
        return if x.is_nan() {
            "NaN".into()
        } else if x > 0.0 {
            "inf".into()
        } else {
            "-inf".into()
        };
    }
    if x == 0.0 {
        return "0".into();
    }
    let digits = digits.max(1);
    // The exponent after rounding (9.9999996 to 6 digits is 1.00000e1).
    let sci = format!("{:.*e}", digits - 1, x);
    let (mantissa, exponent) = sci.split_once('e').expect("`e` formatting has an exponent");
    let exponent: i32 = exponent
        .parse()
        .expect("`e` formatting has an integer exponent");
    if (-4..digits as i32).contains(&exponent) {
        let decimals = (digits as i32 - 1 - exponent).max(0) as usize;
        trim(&format!("{x:.decimals$}")).to_owned()
    } else {
        format!("{}e{exponent}", trim(mantissa))
    }
}

/// Drops trailing zeros after a decimal point, and the point itself when nothing is
/// left after it.
fn trim(s: &str) -> &str {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.')
    } else {
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rounds_to_significant_digits_not_decimals() {
        assert_eq!(significant(0.000002345678, 3), "2.35e-6");
        assert_eq!(significant(0.0002345678, 3), "0.000235");
        assert_eq!(significant(123456.789, 6), "123457");
        assert_eq!(significant(1234567.0, 6), "1.23457e6");
        assert_eq!(significant(-0.64589658012, 10), "-0.6458965801");
        assert_eq!(significant(0.1 + 0.2, 12), "0.3");
        assert_eq!(significant(3.0, 12), "3");
        assert_eq!(significant(-1e-300, 2), "-1e-300");
        assert_eq!(significant(f64::NAN, 6), "NaN");
        assert_eq!(significant(f64::NEG_INFINITY, 6), "-inf");
        assert_eq!(significant(0.0, 6), "0");
        assert_eq!(significant(-0.0, 6), "0");
        assert_eq!(significant(7.0, 0), "7");
    }

    #[test]
    fn rounding_up_a_power_of_ten_changes_the_exponent() {
        assert_eq!(significant(0.000099999999, 3), "0.0001");
        assert_eq!(significant(999999.7, 6), "1e6");
    }
}
