//! Rational functions in named parameters with exact rational coefficients, always
//! reduced: the numerator and denominator share no factor, and the denominator is the
//! canonical associate of [`gcd::normalize_sign_and_scale`] (coprime integer
//! coefficients, positive leading term). Two equal rational functions therefore have
//! identical representations, so equality is structural, exactly as for [`Poly`].
//!
//! Claims about parameters are decided in this type: signs, monotonicity, limits and
//! roots of a rational function (`decide::scalar`), and the exact values of
//! definitions such as an elastoplastic tangent or a shear band's A².

use super::gcd::{self, clear_denominator_monomial};
use crate::kernel::poly::{Poly, Var, VarTable};
use crate::kernel::rational::Rational;
use num_traits::{One, Zero};
use std::ops::{Add, Div, Mul, Neg, Sub};

/// A reduced rational function `num / den`.
///
/// ```
/// use cosserat_kernel::VarTable;
/// use cosserat_algebra::RatFunc;
/// use num_traits::One;
/// let mut names = VarTable::new();
/// let x = RatFunc::var(names.intern("x"));
/// let one = RatFunc::one();
/// // 1/(x − 1) − 1/(x + 1) = 2/(x² − 1), reduced automatically.
/// let lhs = &(&one / &(&x - &one)).unwrap() - &(&one / &(&x + &one)).unwrap();
/// assert_eq!(lhs.display(&names), "2 / (x^2 - 1)");
/// ```
#[derive(Clone, PartialEq, Eq, Hash, Debug)]
pub struct RatFunc {
    num: Poly,
    den: Poly,
}

impl RatFunc {
    /// `num / den`, reduced; `None` when `den` is zero. Laurent inputs are cleared.
    pub fn new(num: &Poly, den: &Poly) -> Option<Self> {
        if den.is_zero() {
            return None;
        }
        let (n, mn) = clear_denominator_monomial(num);
        let (d, md) = clear_denominator_monomial(den);
        let unit = |m| Poly::term(m, Rational::one());
        let n = &n * &unit(md);
        let d = &d * &unit(mn);
        if let Some(c) = d.as_constant() {
            // A constant denominator: scale it to 1, no gcd needed.
            let inv = Poly::constant(c.recip().expect("the denominator is nonzero"));
            return Some(RatFunc {
                num: &n * &inv,
                den: Poly::one(),
            });
        }
        let g = gcd::gcd(&n, &d);
        let n = gcd::divide_exact(&n, &g).expect("the gcd divides the numerator");
        let d = gcd::divide_exact(&d, &g).expect("the gcd divides the denominator");
        let scale = gcd::canonical_scale(&d).expect("the denominator is nonzero");
        let s = Poly::constant(scale);
        Some(RatFunc {
            num: &n * &s,
            den: &d * &s,
        })
    }

    pub fn from_poly(p: &Poly) -> Self {
        RatFunc::new(p, &Poly::one()).expect("1 is nonzero")
    }

    pub fn constant(q: Rational) -> Self {
        RatFunc::from_poly(&Poly::constant(q))
    }

    pub fn int(n: i64) -> Self {
        RatFunc::constant(Rational::int(n))
    }

    pub fn var(v: Var) -> Self {
        RatFunc::from_poly(&Poly::var(v))
    }

    pub fn numerator(&self) -> &Poly {
        &self.num
    }

    pub fn denominator(&self) -> &Poly {
        &self.den
    }

    pub fn is_zero(&self) -> bool {
        self.num.is_zero()
    }

    /// Whether the variable `v` occurs (in the reduced form).
    pub fn depends_on(&self, v: Var) -> bool {
        gcd::degree_in(&self.num, v) != 0 || gcd::degree_in(&self.den, v) != 0
    }

    /// The value when this is a constant.
    pub fn as_constant(&self) -> Option<Rational> {
        let d = self.den.as_constant()?;
        self.num.as_constant()?.checked_div(&d)
    }

    pub fn recip(&self) -> Option<Self> {
        RatFunc::new(&self.den, &self.num)
    }

    pub fn pow(&self, e: u32) -> Self {
        (0..e).fold(RatFunc::one(), |acc, _| &acc * self)
    }

    /// ∂/∂v by the quotient rule (exact).
    pub fn derivative(&self, v: Var) -> Self {
        let num = &(&self.num.derivative(v) * &self.den) - &(&self.num * &self.den.derivative(v));
        RatFunc::new(&num, &(&self.den * &self.den)).expect("a nonzero square")
    }

    /// The function with `v` replaced by `value`; `None` if the denominator vanishes.
    pub fn substitute(&self, v: Var, value: &RatFunc) -> Option<Self> {
        let n = substitute_poly(&self.num, v, value)?;
        let d = substitute_poly(&self.den, v, value)?;
        &n / &d
    }

    /// The function with some variables fixed to rational values (`value` returns
    /// `None` for the variables that stay), reduced once at the end; `None` if the
    /// denominator vanishes there.
    pub fn fix(&self, value: &dyn Fn(Var) -> Option<Rational>) -> Option<Self> {
        let fix_poly = |p: &Poly| -> Option<Poly> {
            let mut out = Vec::with_capacity(p.num_terms());
            for (m, c) in p.terms() {
                let mut coef = c.clone();
                let mut rest = Vec::new();
                for &(v, e) in m.factors() {
                    match value(v) {
                        Some(x) => coef = &coef * &x.pow(e)?,
                        None => rest.push((v, e)),
                    }
                }
                out.push((crate::kernel::Monomial::from_factors(rest), coef));
            }
            Some(Poly::from_terms(out))
        };
        RatFunc::new(&fix_poly(&self.num)?, &fix_poly(&self.den)?)
    }

    /// Exact value at a point; `None` where the denominator vanishes.
    pub fn eval(&self, value: &dyn Fn(Var) -> Rational) -> Option<Rational> {
        let d = self.den.eval(value)?;
        self.num.eval(value)?.checked_div(&d)
    }

    /// `f64` value at a point (used by the plots and numeric cross-checks only).
    pub fn eval_f64(&self, value: &dyn Fn(Var) -> f64) -> f64 {
        let ev = |p: &Poly| -> f64 {
            p.terms()
                .map(|(m, c)| {
                    m.factors()
                        .iter()
                        .fold(c.to_f64(), |t, &(v, e)| t * value(v).powf(e as f64))
                })
                .sum()
        };
        ev(&self.num) / ev(&self.den)
    }

    /// Plain text: `num` or `num / den`, sums parenthesised.
    pub fn display(&self, names: &VarTable) -> String {
        if self.den.is_one() {
            return self.num.display(names);
        }
        let wrap = |p: &Poly| {
            let s = p.display(names);
            if p.num_terms() > 1 {
                format!("({s})")
            } else {
                s
            }
        };
        format!("{} / {}", wrap(&self.num), wrap(&self.den))
    }

    /// LaTeX: `\frac{num}{den}`.
    pub fn latex(&self, names: &VarTable) -> String {
        if self.den.is_one() {
            return super::polynomial::latex(&self.num, names);
        }
        format!(
            "\\frac{{{}}}{{{}}}",
            super::polynomial::latex(&self.num, names),
            super::polynomial::latex(&self.den, names)
        )
    }
}

/// `p` with `v ↦ value` (Horner over the powers of `v`).
fn substitute_poly(p: &Poly, v: Var, value: &RatFunc) -> Option<RatFunc> {
    let mut out = RatFunc::zero();
    for (m, c) in p.terms() {
        let e = m.exponent(v);
        let rest = Poly::term(
            crate::kernel::Monomial::from_factors(
                m.factors()
                    .iter()
                    .copied()
                    .filter(|&(w, _)| w != v)
                    .collect(),
            ),
            c.clone(),
        );
        let k = u32::try_from(e.unsigned_abs()).ok()?;
        let power = if e >= 0 {
            value.pow(k)
        } else {
            value.recip()?.pow(k)
        };
        out = &out + &(&RatFunc::from_poly(&rest) * &power);
    }
    Some(out)
}

impl Zero for RatFunc {
    fn zero() -> Self {
        RatFunc {
            num: Poly::zero(),
            den: Poly::one(),
        }
    }
    fn is_zero(&self) -> bool {
        self.num.is_zero()
    }
}

impl One for RatFunc {
    fn one() -> Self {
        RatFunc {
            num: Poly::one(),
            den: Poly::one(),
        }
    }
}

impl Add<&RatFunc> for &RatFunc {
    type Output = RatFunc;
    fn add(self, rhs: &RatFunc) -> RatFunc {
        if self.is_zero() {
            return rhs.clone();
        }
        if rhs.is_zero() {
            return self.clone();
        }
        if self.den == rhs.den {
            return RatFunc::new(&(&self.num + &rhs.num), &self.den).expect("nonzero");
        }
        let num = &(&self.num * &rhs.den) + &(&rhs.num * &self.den);
        RatFunc::new(&num, &(&self.den * &rhs.den)).expect("a product of nonzero polynomials")
    }
}

impl Sub<&RatFunc> for &RatFunc {
    type Output = RatFunc;
    fn sub(self, rhs: &RatFunc) -> RatFunc {
        self + &(-rhs)
    }
}

impl Mul<&RatFunc> for &RatFunc {
    type Output = RatFunc;
    fn mul(self, rhs: &RatFunc) -> RatFunc {
        // A constant factor keeps the function reduced: scale the numerator only.
        for (c, f) in [(self, rhs), (rhs, self)] {
            if let Some(k) = c.as_constant() {
                if k.is_zero() {
                    return RatFunc::zero();
                }
                return RatFunc {
                    num: &f.num * &Poly::constant(k),
                    den: f.den.clone(),
                };
            }
        }
        RatFunc::new(&(&self.num * &rhs.num), &(&self.den * &rhs.den))
            .expect("a product of nonzero polynomials")
    }
}

/// Division; `None` when dividing by the zero function.
impl Div<&RatFunc> for &RatFunc {
    type Output = Option<RatFunc>;
    fn div(self, rhs: &RatFunc) -> Option<RatFunc> {
        RatFunc::new(&(&self.num * &rhs.den), &(&self.den * &rhs.num))
    }
}

impl Neg for &RatFunc {
    type Output = RatFunc;
    fn neg(self) -> RatFunc {
        RatFunc {
            num: -&self.num,
            den: self.den.clone(),
        }
    }
}

macro_rules! owned_ops {
    ($($tr:ident $method:ident),*) => {$(
        impl $tr for RatFunc {
            type Output = RatFunc;
            fn $method(self, rhs: RatFunc) -> RatFunc {
                (&self).$method(&rhs)
            }
        }
    )*};
}
owned_ops!(Add add, Sub sub, Mul mul);

impl Neg for RatFunc {
    type Output = RatFunc;
    fn neg(self) -> RatFunc {
        -&self
    }
}

impl From<Poly> for RatFunc {
    fn from(p: Poly) -> Self {
        RatFunc::from_poly(&p)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn setup() -> (VarTable, RatFunc, RatFunc) {
        let mut names = VarTable::new();
        let x = RatFunc::var(names.intern("x"));
        let y = RatFunc::var(names.intern("y"));
        (names, x, y)
    }

    #[test]
    fn equal_functions_have_identical_representations() {
        let (names, x, y) = setup();
        let one = RatFunc::one();
        // (x² − y²)/(2x − 2y) = (x + y)/2
        let a = &(&(&x * &x) - &(&y * &y)) / &(&(&x * &RatFunc::int(2)) - &(&y * &RatFunc::int(2)));
        let a = a.unwrap();
        let b = &(&x + &y) * &RatFunc::constant(Rational::ratio(1, 2).unwrap());
        assert_eq!(a, b);
        assert_eq!(a.display(&names), "1/2*x + 1/2*y");
        // The sign is carried by the numerator: 1/(−x) = −1/x.
        let c = (&one / &(-&x)).unwrap();
        assert_eq!(c.display(&names), "-1 / x");
        assert_eq!(c.latex(&names), "\\frac{-1}{x}");
        assert!((&one / &RatFunc::zero()).is_none());
    }

    #[test]
    fn a_changed_coefficient_is_a_different_function() {
        let (_, x, y) = setup();
        let one = RatFunc::one();
        let lhs = (&one / &(&x + &y)).unwrap();
        let mutant = (&one / &(&x + &(&y * &RatFunc::int(2)))).unwrap();
        assert_ne!(lhs, mutant);
        assert_ne!(lhs, -&lhs);
    }

    #[test]
    fn derivative_substitution_and_evaluation() {
        let (names, x, y) = setup();
        let xv = names.lookup("x").unwrap();
        let yv = names.lookup("y").unwrap();
        // d/dx [x/(x + y)] = y/(x + y)²
        let f = (&x / &(&x + &y)).unwrap();
        let expected = (&y / &(&x + &y).pow(2)).unwrap();
        assert_eq!(f.derivative(xv), expected);
        // x ↦ 1/y gives 1/(1 + y²)
        let g = f.substitute(xv, &y.recip().unwrap()).unwrap();
        assert_eq!(g.display(&names), "1 / (y^2 + 1)");
        let at = |v: Var| {
            if v == yv {
                Rational::int(2)
            } else {
                Rational::int(0)
            }
        };
        assert_eq!(g.eval(&at), Rational::ratio(1, 5));
        assert!((g.eval_f64(&|_| 2.0) - 0.2).abs() < 1e-15);
        // Fixing some variables at once equals substituting them one by one.
        let fixed = f.fix(&|v| (v == yv).then(|| Rational::int(3))).unwrap();
        assert_eq!(fixed, f.substitute(yv, &RatFunc::int(3)).unwrap());
        assert_eq!(fixed.display(&names), "x / (x + 3)");
        assert_eq!(f.fix(&|_| Some(Rational::int(0))), None);
        // A pole is reported, not divided through.
        assert_eq!(f.eval(&|_| Rational::int(0)), None);
    }
}
