//! Exact real-root counting and isolation for univariate polynomials over ℚ (Sturm's
//! theorem). Used to decide sign claims exactly: "A² increases with f_r" is the sign
//! of a polynomial on an interval, which is constant between consecutive real roots.

use crate::kernel::poly::{Poly, Var};
use crate::kernel::rational::Rational;
use num_traits::Zero;

/// A dense univariate polynomial, coefficients from the constant term up, no
/// trailing zeros.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UniPoly(Vec<Rational>);

impl UniPoly {
    pub fn new(mut c: Vec<Rational>) -> Self {
        while c.last().is_some_and(Rational::is_zero) {
            c.pop();
        }
        UniPoly(c)
    }

    /// `p` as a polynomial in `v`; `None` if another variable or a negative power occurs.
    pub fn from_poly(p: &Poly, v: Var) -> Option<Self> {
        let mut c: Vec<Rational> = Vec::new();
        for (m, coef) in p.terms() {
            let e = match m.factors() {
                [] => 0,
                [(w, e)] if *w == v && *e > 0 => *e as usize,
                _ => return None,
            };
            if c.len() <= e {
                c.resize(e + 1, Rational::zero());
            }
            c[e] = coef.clone();
        }
        Some(UniPoly::new(c))
    }

    /// `p / (x − a)^k` for the largest k with (x − a)^k dividing `p` (synthetic
    /// division): the same roots as `p`, except `a`.
    pub fn without_root_at(&self, a: &Rational) -> UniPoly {
        let mut p = self.clone();
        while !p.is_zero() && p.eval(a).is_zero() {
            // Coefficients of the quotient, from the top: q_{n−1} = p_n, q_{k−1} = p_k + a q_k.
            let n = p.0.len() - 1;
            let mut q = vec![Rational::zero(); n];
            let mut carry = Rational::zero();
            for k in (1..=n).rev() {
                carry = &p.0[k] + &(a * &carry);
                q[k - 1] = carry.clone();
            }
            p = UniPoly::new(q);
        }
        p
    }

    pub fn degree(&self) -> Option<usize> {
        self.0.len().checked_sub(1)
    }

    pub fn is_zero(&self) -> bool {
        self.0.is_empty()
    }

    pub fn eval(&self, x: &Rational) -> Rational {
        self.0
            .iter()
            .rev()
            .fold(Rational::zero(), |acc, c| &(&acc * x) + c)
    }

    fn derivative(&self) -> UniPoly {
        UniPoly::new(
            self.0
                .iter()
                .enumerate()
                .skip(1)
                .map(|(k, c)| c * &Rational::int(k as i64))
                .collect(),
        )
    }

    /// The sign of the value at `x` for integer coefficients, by homogeneous Horner in
    /// big integers: b^deg p(a/b) = Σ c_i a^i b^(deg − i) has the sign of p(a/b)
    /// (b > 0), and no fraction is ever reduced.
    fn sign_at(&self, x: &Rational) -> i32 {
        use num_traits::Signed;
        let (a, b) = (x.numer(), x.denom());
        let mut acc = num_bigint::BigInt::zero();
        let mut pow_b = num_bigint::BigInt::from(1);
        for (k, c) in self.0.iter().rev().enumerate() {
            debug_assert!(c.is_integer(), "scaled to integers first");
            if k == 0 {
                acc = c.numer();
            } else {
                pow_b *= &b;
                acc = acc * &a + c.numer() * &pow_b;
            }
        }
        if acc.is_zero() {
            0
        } else if acc.is_negative() {
            -1
        } else {
            1
        }
    }

    /// The remainder of `self` divided by `d` (exact over ℚ); `d` nonzero.
    fn rem(&self, d: &UniPoly) -> UniPoly {
        let mut r = self.0.clone();
        let dd = d.0.len() - 1;
        let lead = d.0[dd].recip().expect("nonzero leading coefficient");
        while r.len() > dd && !r.is_empty() {
            crate::kernel::interrupt::tick();
            let k = r.len() - 1;
            let f = &r[k] * &lead;
            for (j, dc) in d.0.iter().enumerate() {
                let idx = k - dd + j;
                r[idx] = &r[idx] - &(&f * dc);
            }
            r.pop();
            while r.last().is_some_and(Rational::is_zero) {
                r.pop();
            }
        }
        UniPoly::new(r)
    }

    /// The polynomial times a positive rational that makes its coefficients coprime
    /// integers: the same signs everywhere, much smaller numbers to evaluate.
    fn positive_scaled(self) -> UniPoly {
        use num_integer::Integer;
        use num_traits::{One, Signed};
        if self.0.is_empty() {
            return self;
        }
        let mut den_lcm = num_bigint::BigInt::one();
        let mut num_gcd = num_bigint::BigInt::zero();
        for c in &self.0 {
            den_lcm = den_lcm.lcm(&c.denom());
            num_gcd = num_gcd.gcd(&c.numer());
        }
        match Rational::from_big(den_lcm, num_gcd.abs()) {
            Some(scale) => UniPoly(self.0.iter().map(|c| c * &scale).collect()),
            None => self,
        }
    }

    /// The sign at +∞ (`at_plus`) or −∞ of a nonzero polynomial.
    fn sign_at_infinity(&self, at_plus: bool) -> i32 {
        let lead = self.0.last().expect("nonzero");
        let s = if lead.is_negative() { -1 } else { 1 };
        if !at_plus && self.0.len().is_multiple_of(2) {
            -s
        } else {
            s
        }
    }
}

/// A bound of an interval: a rational or ±∞.
#[derive(Clone, Debug, PartialEq)]
pub enum Bound {
    MinusInfinity,
    At(Rational),
    PlusInfinity,
}

/// Sturm's sequence p₀ = p, p₁ = p', p_{k+1} = −rem(p_{k−1}, p_k), each entry a
/// positive multiple with coprime integer coefficients (so the first is never empty
/// for a nonzero `p`, and vanishes exactly where `p` does).
pub fn sturm_sequence(p: &UniPoly) -> Vec<UniPoly> {
    // Positive multiples keep every sign, so each entry is scaled to coprime integers.
    let mut seq = vec![
        p.clone().positive_scaled(),
        p.derivative().positive_scaled(),
    ];
    while !seq.last().expect("two entries").is_zero() {
        crate::kernel::interrupt::tick();
        let n = seq.len();
        let r = seq[n - 2].rem(&seq[n - 1]);
        seq.push(UniPoly::new(r.0.iter().map(|c| -c.clone()).collect()).positive_scaled());
    }
    seq.pop();
    seq
}

fn sign_changes(seq: &[UniPoly], at: &Bound) -> usize {
    let signs: Vec<i32> = seq
        .iter()
        .map(|q| match at {
            Bound::MinusInfinity => q.sign_at_infinity(false),
            Bound::PlusInfinity => q.sign_at_infinity(true),
            Bound::At(x) => q.sign_at(x),
        })
        .filter(|&s| s != 0)
        .collect();
    signs.windows(2).filter(|w| w[0] != w[1]).count()
}

/// The number of distinct real roots of a nonzero `p` in the half-open interval
/// (a, b] (Sturm's theorem; `a` must not be a root when finite).
pub fn count_roots(p: &UniPoly, a: &Bound, b: &Bound) -> usize {
    let seq = sturm_sequence(p);
    sign_changes(&seq, a).saturating_sub(sign_changes(&seq, b))
}

/// The distinct real roots of `p` in (a, b), in increasing order, each either exact,
/// `(r, r)`, or isolated in `(lo, hi)` with `lo < hi`, `hi − lo ≤ width`, exactly one
/// root inside and neither end a root of `p` (bisection with Sturm counts). `a < b`
/// must not be roots.
///
/// A midpoint that is a root is kept exactly and divided out of the polynomial that
/// the halves go on with, so that no root next to it is lost.
///
/// `None` after [`MAX_BISECTIONS`] bisections: with correct Sturm counts a root needs
/// about log₂((b − a)/width) of them plus the bits of its distance to the next root,
/// so the bound is met only by a wrong count or by extreme input (roots within about
/// 2⁻⁹⁰⁰⁰⁰ of each other, or thousands of roots); either way the caller cannot
/// decide, and says so.
pub fn isolate_roots(
    p: &UniPoly,
    a: &Rational,
    b: &Rational,
    width: &Rational,
) -> Option<Vec<(Rational, Rational)>> {
    isolate_roots_within(p, a, b, width, MAX_BISECTIONS)
}

/// The most bisections [`isolate_roots`] makes.
pub const MAX_BISECTIONS: usize = 100_000;

fn isolate_roots_within(
    p: &UniPoly,
    a: &Rational,
    b: &Rational,
    width: &Rational,
    max_bisections: usize,
) -> Option<Vec<(Rational, Rational)>> {
    if p.is_zero() {
        return Some(Vec::new());
    }
    let mut bisections = 0usize;
    let half = Rational::ratio(1, 2).expect("2 ≠ 0");
    // Polynomials by index, each with its Sturm sequence: `p`, and `p` with exact
    // roots divided out.
    let mut polys = vec![(p.clone(), sturm_sequence(p))];
    let changes = |k: usize, polys: &[(UniPoly, Vec<UniPoly>)], x: &Rational| {
        sign_changes(&polys[k].1, &Bound::At(x.clone()))
    };
    // Each interval carries the sign changes of its polynomial's sequence at both
    // ends, so that a midpoint's are computed once for both halves.
    let mut out = Vec::new();
    let mut stack = vec![(
        0,
        a.clone(),
        b.clone(),
        changes(0, &polys, a),
        changes(0, &polys, b),
    )];
    while let Some((k, lo, hi, at_lo, at_hi)) = stack.pop() {
        crate::kernel::interrupt::tick();
        let n = at_lo.saturating_sub(at_hi);
        if n == 0 {
            continue;
        }
        // One root, narrow enough, and no end that is an exact root found earlier. The
        // zero tests read the head of a Sturm sequence: a positive multiple of the
        // polynomial with integer coefficients, evaluated without reducing fractions.
        let clean = |x: &Rational| polys[0].1[0].sign_at(x) != 0;
        if n == 1 && &hi - &lo <= *width && clean(&lo) && clean(&hi) {
            out.push((lo, hi));
            continue;
        }
        bisections += 1;
        if bisections > max_bisections {
            return None;
        }
        let mid = &(&lo + &hi) * &half;
        if polys[k].1[0].sign_at(&mid) == 0 {
            out.push((mid.clone(), mid.clone()));
            let q = polys[k].0.without_root_at(&mid);
            let seq = sturm_sequence(&q);
            polys.push((q, seq));
            let j = polys.len() - 1;
            let (at_lo, at_mid, at_hi) = (
                changes(j, &polys, &lo),
                changes(j, &polys, &mid),
                changes(j, &polys, &hi),
            );
            stack.push((j, mid.clone(), hi, at_mid, at_hi));
            stack.push((j, lo, mid, at_lo, at_mid));
        } else {
            let at_mid = changes(k, &polys, &mid);
            stack.push((k, mid.clone(), hi, at_mid, at_hi));
            stack.push((k, lo, mid, at_lo, at_mid));
        }
    }
    out.sort();
    Some(out)
}

/// `p = content · rest`: `content` free of `v`, `rest` a polynomial in `v` alone with
/// rational coefficients (the coefficient of every power of `v` is a rational multiple
/// of one polynomial); `None` otherwise. (The kernel checks its own split.)
pub fn content_in(p: &Poly, v: Var) -> Option<(Poly, Poly)> {
    use std::collections::BTreeMap;
    let mut by_power: BTreeMap<i64, Poly> = BTreeMap::new();
    for (m, c) in p.terms() {
        let k = m.exponent(v);
        if k < 0 {
            return None;
        }
        by_power
            .entry(k)
            .or_default()
            .add_term(m.without(v), c.clone());
    }
    let content = by_power.values().next()?.clone();
    let (lead_m, lead_c) = content.leading()?;
    let mut rest = Poly::zero();
    for (k, a) in &by_power {
        let (m, c) = a.leading()?;
        let ratio = c.checked_div(lead_c)?;
        if m != lead_m || a != &(&content * &Poly::constant(ratio.clone())) {
            return None;
        }
        rest.add_term(crate::kernel::Monomial::var(v, *k), ratio);
    }
    Some((content, rest))
}

impl UniPoly {
    /// `p` on the line through `point` along `v`: every other variable replaced by its
    /// value there (a variable `point` leaves out is 0). `None` when a negative power
    /// of a variable that is 0 there, or of `v`, occurs, or a value is too large.
    pub fn restricted(p: &Poly, v: Var, point: &dyn Fn(Var) -> Rational) -> Option<UniPoly> {
        let mut c: Vec<Rational> = Vec::new();
        for (m, coef) in p.terms() {
            let mut k = 0usize;
            let mut value = coef.clone();
            for &(w, e) in m.factors() {
                if w == v {
                    k = usize::try_from(e).ok()?;
                } else {
                    value = &value * &point(w).pow(e)?;
                }
            }
            if c.len() <= k {
                c.resize(k + 1, Rational::zero());
            }
            c[k] = &c[k] + &value;
        }
        Some(UniPoly::new(c))
    }

    /// The greatest common divisor of two polynomials, monic (zero when both are).
    pub fn gcd(&self, other: &UniPoly) -> UniPoly {
        let (mut a, mut b) = (self.clone(), other.clone());
        while !b.is_zero() {
            let r = a.rem(&b);
            a = b;
            b = r;
        }
        match a.0.last().and_then(Rational::recip) {
            Some(lead) => UniPoly(a.0.iter().map(|c| c * &lead).collect()),
            None => a,
        }
    }

    /// The rational root of a multiple factor of degree one: for p = q² r with q
    /// linear (a zero where p touches 0 without changing sign, as a square of a
    /// linear form does on a line that crosses it), the root of q.
    pub fn touching_root(&self) -> Option<Rational> {
        let h = self.gcd(&self.derivative());
        match h.0.as_slice() {
            [c0, c1] => (-c0).checked_div(c1),
            _ => None,
        }
    }

    /// The coefficients from the constant term up.
    pub fn coefficients(&self) -> &[Rational] {
        &self.0
    }

    /// The product of two polynomials.
    pub fn mul(&self, other: &UniPoly) -> UniPoly {
        if self.is_zero() || other.is_zero() {
            return UniPoly(Vec::new());
        }
        let mut c = vec![Rational::zero(); self.0.len() + other.0.len() - 1];
        for (i, a) in self.0.iter().enumerate() {
            for (j, b) in other.0.iter().enumerate() {
                c[i + j] += &(a * b);
            }
        }
        UniPoly::new(c)
    }

    /// A rational `B` with every real root strictly inside (−B, B) (Cauchy's bound,
    /// 1 + max |c_i / c_n|); `p` nonzero.
    pub fn root_bound(&self) -> Rational {
        let n = self.0.len() - 1;
        let lead = &self.0[n];
        let largest = self.0[..n]
            .iter()
            .map(|c| {
                let r = c.checked_div(lead).expect("nonzero leading coefficient");
                if r.is_negative() {
                    -r
                } else {
                    r
                }
            })
            .max()
            .unwrap_or_else(Rational::zero);
        &largest + &Rational::int(1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn up(c: &[i64]) -> UniPoly {
        UniPoly::new(c.iter().map(|&k| Rational::int(k)).collect())
    }

    #[test]
    fn counts_real_roots() {
        // (x − 1)(x − 2)(x + 3) = x³ − 7x + 6
        let p = up(&[6, -7, 0, 1]);
        assert_eq!(
            count_roots(&p, &Bound::MinusInfinity, &Bound::PlusInfinity),
            3
        );
        assert_eq!(
            count_roots(&p, &Bound::At(Rational::int(0)), &Bound::PlusInfinity),
            2
        );
        // x² + 1 has none; x² − 2 has two, x⁴ − 4x² + 4 = (x² − 2)² has two distinct.
        assert_eq!(
            count_roots(&up(&[1, 0, 1]), &Bound::MinusInfinity, &Bound::PlusInfinity),
            0
        );
        assert_eq!(
            count_roots(
                &up(&[-2, 0, 1]),
                &Bound::MinusInfinity,
                &Bound::PlusInfinity
            ),
            2
        );
        assert_eq!(
            count_roots(
                &up(&[4, 0, -4, 0, 1]),
                &Bound::MinusInfinity,
                &Bound::PlusInfinity
            ),
            2
        );
    }

    #[test]
    fn isolates_irrational_roots() {
        let p = up(&[-2, 0, 1]); // ±√2
        let w = Rational::ratio(1, 1_000_000).unwrap();
        let roots = isolate_roots(&p, &Rational::int(0), &Rational::int(10), &w).unwrap();
        assert_eq!(roots.len(), 1);
        let (lo, hi) = &roots[0];
        assert!(lo.to_f64() <= 2f64.sqrt() && 2f64.sqrt() <= hi.to_f64());
        // An exact rational root is found exactly.
        let q = up(&[-1, 2]); // 2x − 1
        let r = isolate_roots(&q, &Rational::int(0), &Rational::int(1), &w).unwrap();
        assert_eq!(
            r,
            vec![(
                Rational::ratio(1, 2).unwrap(),
                Rational::ratio(1, 2).unwrap()
            )]
        );
    }

    /// Two roots 2⁻⁶⁰ apart need more than 60 bisections to separate: under a budget of
    /// 50 the isolation gives up (`None`, never a partial list), and with the full
    /// budget it separates them.
    #[test]
    fn isolation_gives_up_beyond_its_bisection_budget() {
        let gap = Rational::ratio(1, 1 << 60).unwrap();
        let (r1, r2) = (
            Rational::ratio(1, 3).unwrap(),
            &Rational::ratio(1, 3).unwrap() + &gap,
        );
        // (x − r1)(x − r2) = x² − (r1 + r2) x + r1 r2.
        let p = UniPoly::new(vec![&r1 * &r2, -(&r1 + &r2), Rational::int(1)]);
        let w = Rational::ratio(1, 1 << 20).unwrap();
        let (a, b) = (Rational::int(0), Rational::int(1));
        assert_eq!(isolate_roots_within(&p, &a, &b, &w, 50), None);
        let roots = isolate_roots(&p, &a, &b, &w).expect("within the budget");
        assert_eq!(roots.len(), 2);
        assert!(roots[0].1 <= roots[1].0);
        assert!(roots[0].0 <= r1 && r1 <= roots[0].1 && roots[1].0 <= r2 && r2 <= roots[1].1);
    }

    #[test]
    fn roots_at_midpoints_are_kept_exactly_and_their_neighbours_isolated() {
        // x (2x − 1)² (4x + 1)(x² − 2) on (−2, 2): the bisection meets 0, 1/2 (a double
        // root, divided out twice) and −1/4 as midpoints; ±√2 lie between midpoints.
        let mut p = up(&[0, 1]);
        for factor in [&[-1, 2][..], &[-1, 2], &[1, 4], &[-2, 0, 1]] {
            p = p.mul(&up(factor));
        }
        let w = Rational::ratio(1, 1 << 20).unwrap();
        let roots = isolate_roots(&p, &Rational::int(-2), &Rational::int(2), &w).unwrap();
        let exact = |n, d| {
            let r = Rational::ratio(n, d).unwrap();
            (r.clone(), r)
        };
        assert_eq!(roots.len(), 5, "{roots:?}");
        assert!(roots.contains(&exact(0, 1)));
        assert!(roots.contains(&exact(1, 2)));
        assert!(roots.contains(&exact(-1, 4)));
        let s = 2f64.sqrt();
        for (lo, hi) in roots.iter().filter(|(lo, hi)| lo != hi) {
            let (lo, hi) = (lo.to_f64(), hi.to_f64());
            assert!(hi - lo <= 1.0 / f64::from(1 << 20));
            assert!((lo < -s && -s < hi) || (lo < s && s < hi), "({lo}, {hi})");
        }
        // In increasing order, and every isolating interval holds exactly one root.
        assert!(roots.windows(2).all(|w| w[0].1 < w[1].0));
        for (lo, hi) in roots.iter().filter(|(lo, hi)| lo != hi) {
            assert_eq!(
                count_roots(&p, &Bound::At(lo.clone()), &Bound::At(hi.clone())),
                1
            );
        }
    }
}
