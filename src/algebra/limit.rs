//! Limits of rational functions as one variable tends to a point or to ±∞, exactly,
//! with the other variables kept as symbols.
//!
//! The variable is moved so that it tends to 0 (`x = c + s`, or `x = ±1/s`); then
//! `num = s^a (N_a + O(s))` and `den = s^b (D_b + O(s))` with `N_a`, `D_b` polynomials
//! in the other variables, and the limit is read off the orders: 0 when `a > b`,
//! `N_a / D_b` when `a = b`, infinite with the sign of `N_a / D_b` (times the side's
//! sign to the power `b − a`) when `a < b`. Where `D_b` (or, for an infinite limit,
//! `N_a`) vanishes the orders change: these are the conditions of the result.

use super::ratfunc::RatFunc;
use crate::kernel::poly::{Poly, Var};

pub use crate::kernel::statement::{Approach, Side};

/// The limit of a rational function.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Limit {
    /// A finite value (a rational function of the other variables).
    Finite(RatFunc),
    /// |f| → ∞ with the sign of `sign_of` (a rational function of the other
    /// variables, nonzero where the conditions hold).
    Infinite { sign_of: RatFunc },
    /// |f| → ∞ with opposite signs on the two sides.
    InfiniteBothSigns,
}

/// A limit with the polynomials that must not vanish for it to hold.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Expansion {
    pub limit: Limit,
    pub nonzero: Vec<Poly>,
}

/// The lowest power of `v` in `p` (nonzero) and its coefficient, a polynomial free of `v`.
fn lowest(p: &Poly, v: Var) -> (crate::kernel::poly::Exp, Poly) {
    let a = p.terms().map(|(m, _)| m.exponent(v)).min().unwrap_or(0);
    let out = Poly::from_terms(
        p.terms()
            .filter(|(m, _)| m.exponent(v) == a)
            .map(|(m, c)| (m.without(v), c.clone())),
    );
    (a, out)
}

/// The limit of `f` as `v` tends to `to`; `None` only when the shifted function has
/// no denominator left (cannot happen for a valid `RatFunc`).
pub fn expand(f: &RatFunc, v: Var, to: &Approach) -> Option<Expansion> {
    let s = RatFunc::var(v);
    let (moved, side) = match to {
        Approach::At(c, side) => (
            f.substitute(v, &(&RatFunc::constant(c.clone()) + &s))?,
            *side,
        ),
        Approach::PlusInfinity => (f.substitute(v, &s.recip()?)?, Side::Above),
        Approach::MinusInfinity => (f.substitute(v, &(-&s.recip()?))?, Side::Above),
    };
    if moved.is_zero() {
        return Some(Expansion {
            limit: Limit::Finite(RatFunc::int(0)),
            nonzero: Vec::new(),
        });
    }
    let (a, na) = lowest(moved.numerator(), v);
    let (b, db) = lowest(moved.denominator(), v);
    let mut nonzero = Vec::new();
    if db.as_constant().is_none() {
        nonzero.push(db.clone());
    }
    let ratio = RatFunc::new(&na, &db)?;
    let limit = match a.cmp(&b) {
        std::cmp::Ordering::Greater => Limit::Finite(RatFunc::int(0)),
        std::cmp::Ordering::Equal => Limit::Finite(ratio),
        std::cmp::Ordering::Less => {
            if na.as_constant().is_none() {
                nonzero.push(na.clone());
            }
            let odd = (b - a) % 2 == 1;
            match side {
                Side::Above => Limit::Infinite { sign_of: ratio },
                Side::Below if odd => Limit::Infinite { sign_of: -&ratio },
                Side::Below => Limit::Infinite { sign_of: ratio },
                Side::Both if odd => Limit::InfiniteBothSigns,
                Side::Both => Limit::Infinite { sign_of: ratio },
            }
        }
    };
    Some(Expansion { limit, nonzero })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::Rational;
    use crate::kernel::VarTable;

    fn setup() -> (VarTable, Var, Var) {
        let mut names = VarTable::new();
        let x = names.intern("x");
        let k = names.intern("k");
        (names, x, k)
    }

    #[test]
    fn finite_limits_at_zero_and_infinity() {
        let (names, x, k) = setup();
        let (xs, ks) = (RatFunc::var(x), RatFunc::var(k));
        // (k x + x²) / (x + 2 x²) → k as x → 0; → 1/2 as x → ∞.
        let f = &(&(&ks * &xs) + &(&xs * &xs)) / &(&xs + &(&RatFunc::int(2) * &(&xs * &xs)));
        let f = f.unwrap();
        let e = expand(&f, x, &Approach::At(Rational::int(0), Side::Both)).unwrap();
        assert_eq!(e.limit, Limit::Finite(ks.clone()));
        let e = expand(&f, x, &Approach::PlusInfinity).unwrap();
        assert_eq!(
            e.limit,
            Limit::Finite(RatFunc::constant(Rational::ratio(1, 2).unwrap()))
        );
        assert!(
            e.nonzero.is_empty(),
            "{:?}",
            e.nonzero
                .iter()
                .map(|p| p.display(&names))
                .collect::<Vec<_>>()
        );
    }

    #[test]
    fn infinite_limits_carry_their_sign() {
        let (_, x, k) = setup();
        let (xs, ks) = (RatFunc::var(x), RatFunc::var(k));
        // k / x: +∞·sign(k) from above, opposite from below, no signed limit two-sided.
        let f = (&ks / &xs).unwrap();
        let at = |side| expand(&f, x, &Approach::At(Rational::int(0), side)).unwrap();
        assert_eq!(
            at(Side::Above).limit,
            Limit::Infinite {
                sign_of: ks.clone()
            }
        );
        assert_eq!(at(Side::Below).limit, Limit::Infinite { sign_of: -&ks });
        assert_eq!(at(Side::Both).limit, Limit::InfiniteBothSigns);
        assert_eq!(at(Side::Above).nonzero.len(), 1, "k ≠ 0 is a condition");
        // 1/(x − 1)² → +∞ at 1 from both sides.
        let one = RatFunc::int(1);
        let g = (&one / &(&(&xs - &one) * &(&xs - &one))).unwrap();
        let e = expand(&g, x, &Approach::At(Rational::int(1), Side::Both)).unwrap();
        assert_eq!(
            e.limit,
            Limit::Infinite {
                sign_of: one.clone()
            }
        );
        // x³ → −∞ as x → −∞.
        let c = &xs * &(&xs * &xs);
        let e = expand(&c, x, &Approach::MinusInfinity).unwrap();
        assert_eq!(
            e.limit,
            Limit::Infinite {
                sign_of: RatFunc::int(-1)
            }
        );
    }
}
