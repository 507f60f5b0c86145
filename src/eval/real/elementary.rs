//! The scalar functions of a number (`f64` or num-dual) and the maximum over the
//! normal's angle: the one definition the interpreter and the compiled tapes share.

use super::error::RealError;
use crate::lang::parser::{Func, Func2};
use num_dual::DualNum;

/// Golden-section search for the maximum of `f` on [c − h, c + h]: the maximiser and
/// the value (never below f(c)).
pub(crate) fn golden_max(
    f: &dyn Fn(f64) -> Result<f64, RealError>,
    c: f64,
    h: f64,
) -> Result<(f64, f64), RealError> {
    let g = (5f64.sqrt() - 1.0) / 2.0;
    let (mut lo, mut hi) = (c - h, c + h);
    let (mut x1, mut x2) = (hi - g * (hi - lo), lo + g * (hi - lo));
    let (mut f1, mut f2) = (f(x1)?, f(x2)?);
    while hi - lo > 1e-12 {
        if f1 < f2 {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + g * (hi - lo);
            f2 = f(x2)?;
        } else {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - g * (hi - lo);
            f1 = f(x1)?;
        }
    }
    let mid = (lo + hi) / 2.0;
    let fm = f(mid)?;
    let fc = f(c)?;
    Ok(if fm >= fc { (mid, fm) } else { (c, fc) })
}

/// Why a function has no real value at its argument.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub(crate) enum Undefined {
    #[error("{function}(…) of {what} ({at})")]
    Outside {
        function: &'static str,
        what: &'static str,
        at: f64,
    },
    #[error("{base}^({exponent}): a real power needs a positive base")]
    Power { base: f64, exponent: f64 },
}

/// A scalar function of a number (`f64` or num-dual), or why it is undefined there: the
/// one definition the interpreter and the compiled tapes share.
pub(crate) fn elementary<T: DualNum<Primitive = f64>>(f: Func, x: T) -> Result<T, Undefined> {
    let outside = |what: &'static str| {
        Err(Undefined::Outside {
            function: f.name(),
            what,
            at: x.re(),
        })
    };
    Ok(match f {
        Func::Sqrt if x.re() < 0.0 => return outside("a negative number"),
        Func::Sqrt => x.sqrt(),
        Func::Abs => x.abs(),
        Func::Cos => x.cos(),
        Func::Sin => x.sin(),
        Func::Tan => x.tan(),
        Func::Exp => x.exp(),
        Func::Log if x.re() <= 0.0 => return outside("a number that is not positive"),
        Func::Log => x.ln(),
        Func::Atan => x.atan(),
        Func::Asin | Func::Acos if !(-1.0..=1.0).contains(&x.re()) => {
            return outside("a number outside [−1, 1]")
        }
        Func::Asin => x.asin(),
        Func::Acos => x.acos(),
        Func::Avg | Func::MaxN => unreachable!("checked as their own node kinds"),
    })
}

/// A function of two numbers, or why it is undefined there (shared with the tapes).
/// `min` and `max` pick an argument by value, so their derivative is the picked one's.
pub(crate) fn elementary2<T: DualNum<Primitive = f64>>(
    f: Func2,
    x: T,
    y: T,
) -> Result<T, Undefined> {
    Ok(match f {
        Func2::Atan2 => x.atan2(y),
        Func2::Min => {
            if y.re() < x.re() {
                y
            } else {
                x
            }
        }
        Func2::Max => {
            if y.re() > x.re() {
                y
            } else {
                x
            }
        }
        Func2::Pow if x.re() > 0.0 => x.powd(y),
        Func2::Pow if x.re() == 0.0 && y.re() > 0.0 => x * T::zero(),
        Func2::Pow => {
            return Err(Undefined::Power {
                base: x.re(),
                exponent: y.re(),
            })
        }
    })
}
