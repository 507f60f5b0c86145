//! Polynomials in one variable over ℚ and the counts of their real roots (Sturm's
//! theorem): what the kernel needs to check a sign, a root count or a pole on an
//! interval. The search isolates roots (`algebra::sturm`); the kernel only counts
//! roots between the rational points a fact names, and evaluates exactly.

use super::poly::{Poly, Var};
use super::rational::Rational;
use num_traits::Zero;

/// Coefficients, constant first, without trailing zeros (empty: the zero polynomial).
#[derive(Clone, Debug, PartialEq)]
pub struct Uni(Vec<Rational>);

/// The highest degree the kernel works with in one variable.
const MAX_DEGREE: super::poly::Exp = 2_000;

impl Uni {
    fn trimmed(mut c: Vec<Rational>) -> Uni {
        while c.last().is_some_and(Rational::is_zero) {
            c.pop();
        }
        Uni(c)
    }

    /// `p` as a polynomial in `v` alone; `None` when it has another variable, a
    /// negative power or a degree beyond the bound.
    pub fn of(p: &Poly, v: Var) -> Option<Uni> {
        let mut c: Vec<Rational> = Vec::new();
        for (m, q) in p.terms() {
            let e = match m.factors() {
                [] => 0,
                [(w, e)] if *w == v && (0..=MAX_DEGREE).contains(e) => *e as usize,
                _ => return None,
            };
            if c.len() <= e {
                c.resize(e + 1, Rational::zero());
            }
            c[e] += q;
        }
        Some(Uni::trimmed(c))
    }

    pub fn is_zero(&self) -> bool {
        self.0.is_empty()
    }

    /// `−self`: the same roots, every sign flipped.
    pub fn negated(&self) -> Uni {
        Uni(self.0.iter().map(|c| -c.clone()).collect())
    }

    fn degree(&self) -> usize {
        self.0.len().saturating_sub(1)
    }

    pub fn eval(&self, x: &Rational) -> Rational {
        self.0
            .iter()
            .rev()
            .fold(Rational::zero(), |acc, c| &(&acc * x) + c)
    }

    pub fn mul(&self, other: &Uni) -> Uni {
        if self.is_zero() || other.is_zero() {
            return Uni(Vec::new());
        }
        let mut c = vec![Rational::zero(); self.0.len() + other.0.len() - 1];
        for (i, a) in self.0.iter().enumerate() {
            for (j, b) in other.0.iter().enumerate() {
                c[i + j] += &(a * b);
            }
        }
        Uni::trimmed(c)
    }

    fn derivative(&self) -> Uni {
        Uni::trimmed(
            self.0
                .iter()
                .enumerate()
                .skip(1)
                .map(|(k, c)| c * &Rational::int(k as i64))
                .collect(),
        )
    }

    /// The remainder of `self` by a nonzero `d`.
    fn rem(&self, d: &Uni) -> Uni {
        let mut r = self.0.clone();
        let lead =
            d.0.last()
                .expect("a nonzero divisor")
                .recip()
                .expect("nonzero");
        while r.len() >= d.0.len() {
            // Sturm chains of high degree are long: the claim's time limit may stop one.
            super::interrupt::tick_by(d.0.len());
            let q = &r[r.len() - 1] * &lead;
            let shift = r.len() - d.0.len();
            for (k, c) in d.0.iter().enumerate() {
                r[shift + k] = &r[shift + k] - &(&q * c);
            }
            r.pop();
            while r.last().is_some_and(Rational::is_zero) {
                r.pop();
            }
        }
        Uni(r)
    }

    /// `a / b` for a nonzero `b` that divides `a` (the remainder is dropped).
    pub fn quotient(a: &Uni, b: &Uni) -> Uni {
        let mut r = a.0.clone();
        let lead =
            b.0.last()
                .expect("a nonzero divisor")
                .recip()
                .expect("nonzero");
        let mut q = vec![Rational::zero(); a.0.len().saturating_sub(b.0.len()) + 1];
        while r.len() >= b.0.len() && !r.is_empty() {
            super::interrupt::tick_by(b.0.len());
            let c = &r[r.len() - 1] * &lead;
            let shift = r.len() - b.0.len();
            for (k, x) in b.0.iter().enumerate() {
                r[shift + k] = &r[shift + k] - &(&c * x);
            }
            q[shift] = c;
            r.pop();
        }
        Uni::trimmed(q)
    }

    /// The greatest common divisor (up to a constant).
    pub fn gcd(&self, other: &Uni) -> Uni {
        let (mut a, mut b) = (self.clone(), other.clone());
        while !b.is_zero() {
            let r = a.rem(&b);
            a = b;
            b = r;
        }
        a
    }

    /// The sign at +∞ (`above`) or −∞ of a nonzero polynomial.
    fn sign_at_infinity(&self, above: bool) -> i32 {
        let s = if self.0.last().is_some_and(Rational::is_negative) {
            -1
        } else {
            1
        };
        if above || self.degree().is_multiple_of(2) {
            s
        } else {
            -s
        }
    }

    /// The number of distinct real roots in (lo, hi) (`None`: unbounded end), the ends
    /// excluded; `None` for the zero polynomial.
    pub fn roots_between(&self, lo: Option<&Rational>, hi: Option<&Rational>) -> Option<usize> {
        if self.is_zero() {
            return None;
        }
        let mut chain = vec![self.clone(), self.derivative()];
        while !chain[chain.len() - 1].is_zero() {
            let (a, b) = (&chain[chain.len() - 2], &chain[chain.len() - 1]);
            let r = a.rem(b);
            chain.push(Uni(r.0.iter().map(|c| -c).collect()));
        }
        chain.pop();
        // Sign changes of the chain at x (zeros skipped); at a root of `self`, the
        // count is taken just beyond it, which Sturm's theorem also allows.
        let changes = |at: Option<&Rational>, above: bool| -> usize {
            let signs: Vec<i32> = chain
                .iter()
                .map(|p| match at {
                    None => p.sign_at_infinity(above),
                    Some(x) => {
                        let v = p.eval(x);
                        if v.is_zero() {
                            0
                        } else if v.is_negative() {
                            -1
                        } else {
                            1
                        }
                    }
                })
                .filter(|&s| s != 0)
                .collect();
            signs.windows(2).filter(|w| w[0] != w[1]).count()
        };
        // Sturm counts the roots in (a, b] with a, b not roots; a root at an end is
        // handled by dividing it out first.
        let at_end = |x: Option<&Rational>| x.is_some_and(|x| self.eval(x).is_zero());
        if at_end(lo) || at_end(hi) {
            let mut p = self.clone();
            for x in [lo, hi].into_iter().flatten() {
                while p.eval(x).is_zero() {
                    p = p.divided_by_root(x);
                }
            }
            return p.roots_between(lo, hi);
        }
        changes(lo, false).checked_sub(changes(hi, true))
    }

    /// `self / (x − r)` for a root `r` (synthetic division).
    fn divided_by_root(&self, r: &Rational) -> Uni {
        let mut out = vec![Rational::zero(); self.0.len().saturating_sub(1)];
        let mut carry = Rational::zero();
        for k in (1..self.0.len()).rev() {
            carry = &(&carry * r) + &self.0[k];
            out[k - 1] = carry.clone();
        }
        Uni::trimmed(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn u(c: &[i64]) -> Uni {
        Uni::trimmed(c.iter().map(|&k| Rational::int(k)).collect())
    }

    #[test]
    fn sturm_counts_distinct_roots_between_ends() {
        let q = |n, d| Rational::ratio(n, d).unwrap();
        // (x − 1)(x − 2)(x + 3) = x³ − 7x + 6
        let p = u(&[6, -7, 0, 1]);
        assert_eq!(p.roots_between(None, None), Some(3));
        assert_eq!(p.roots_between(Some(&q(0, 1)), None), Some(2));
        assert_eq!(
            p.roots_between(Some(&q(1, 1)), Some(&q(2, 1))),
            Some(0),
            "ends excluded"
        );
        assert_eq!(p.roots_between(Some(&q(1, 2)), Some(&q(3, 2))), Some(1));
        assert_eq!(p.roots_between(None, Some(&q(-3, 1))), Some(0));
        // x² + 1 has none; (x − 1)² one, counted once.
        assert_eq!(u(&[1, 0, 1]).roots_between(None, None), Some(0));
        assert_eq!(u(&[1, -2, 1]).roots_between(None, None), Some(1));
        assert_eq!(u(&[]).roots_between(None, None), None);
        assert_eq!(u(&[6, -7, 0, 1]).gcd(&u(&[-1, 1])).0.len(), 2);
    }
}
