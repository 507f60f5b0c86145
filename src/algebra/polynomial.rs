//! Operations on the kernel's polynomials that the search needs and the checker does
//! not: square roots of perfect squares (a candidate root, which the kernel then checks
//! by squaring), the average of a product without forming the terms whose average
//! vanishes (the fast route of exact averages), and LaTeX. None of them is trusted: a
//! root or an average found here reaches a proof only through the kernel's own
//! evaluation.

use crate::kernel::moments::monomial_moment;
use crate::kernel::poly::{Exp, Monomial, Poly, PolyError, Var, VarTable};
use crate::kernel::Rational;
use rustc_hash::FxHashMap as HashMap;

/// The square root of a perfect square: `r` with `r·r = self` and a positive
/// leading coefficient, or `None` when `p` is not the square of a (Laurent)
/// polynomial with rational coefficients, or its root would pass `max_terms`.
///
/// Long division from the top in graded lexicographic order (compatible with
/// products, so leading terms multiply): the root's leading term is the square
/// root of `p`'s; each next term is the remainder's leading term over twice
/// the root's, and the remainder's leading monomial strictly decreases. A root's
/// exponents in each variable lie within half of `p`'s range in it (the top
/// and bottom parts of a square are squares), so a term outside that box proves
/// that `p` is not a square, and the division stops.
///
/// ```
/// use cosserat_algebra::polynomial::sqrt;
/// use cosserat_kernel::{Poly, Rational, VarTable};
/// let mut names = VarTable::new();
/// let (x, y) = (Poly::var(names.intern("x")), Poly::var(names.intern("y")));
/// let r = &(&x * &Poly::constant(Rational::int(2))) - &y;
/// assert_eq!(sqrt(&(&r * &r), 100), Some(r));
/// assert_eq!(sqrt(&(&(&x * &x) + &y), 100), None);
/// ```
pub fn sqrt(p: &Poly, max_terms: usize) -> Option<Poly> {
    let Some((m0, c0)) = p.leading() else {
        return Some(Poly::default());
    };
    let halved: Vec<(Var, Exp)> = m0
        .factors()
        .iter()
        .map(|&(v, e)| (e % 2 == 0).then_some((v, e / 2)))
        .collect::<Option<_>>()?;
    let lead_m = Monomial::from_factors(halved);
    let lead_c = c0.sqrt_exact()?;
    let bounds: Vec<(Var, Exp, Exp)> = p
        .variables()
        .into_iter()
        .map(|v| {
            let exps = p.terms().map(|(m, _)| m.exponent(v));
            let (lo, hi) = exps.fold((Exp::MAX, Exp::MIN), |(lo, hi), e| (lo.min(e), hi.max(e)));
            (v, lo, hi)
        })
        .collect();
    let in_box = |m: &Monomial| {
        m.factors()
            .iter()
            .all(|(v, _)| bounds.iter().any(|(w, _, _)| w == v))
            && bounds.iter().all(|&(v, lo, hi)| {
                let e = 2 * m.exponent(v);
                lo <= e && e <= hi
            })
    };
    let over_twice_lead = (&lead_c + &lead_c)
        .recip()
        .expect("a leading coefficient is nonzero");
    let lead_inverse = lead_m.pow(-1)?;
    let lead = Poly::term(lead_m, lead_c);
    let mut root = lead.clone();
    let mut rem = p - &(&lead * &lead);
    let two = Poly::constant(Rational::int(2));
    loop {
        let Some((m, c)) = rem.leading() else {
            return Some(root);
        };
        let tm = m.mul(&lead_inverse);
        if !in_box(&tm) || root.num_terms() >= max_terms {
            return None;
        }
        let t = Poly::term(tm, c * &over_twice_lead);
        rem = &rem - &(&(&(&root * &t) * &two) + &(&t * &t));
        root = &root + &t;
    }
}

/// `(a · b).average_over_normal(vars)`, without forming the products whose
/// average vanishes: a moment is zero unless every exponent of n is even, so a pair
/// of terms counts only when their n-exponents have the same parities. The terms
/// are grouped by that parity and only pairs within a group are multiplied (about
/// one pair in 2^d). Averages of products such as eqs. (33), (36) and (38).
///
/// Where a term has a negative power of n, or n has more than four components, it
/// is the product averaged, with that route's errors.
pub fn average_of_product(x: &Poly, y: &Poly, vars: &[Var]) -> Result<Poly, PolyError> {
    /// A term split into its n-exponents (with their parities as bits) and the rest.
    struct Split<'p> {
        parity: usize,
        exps: [u32; 4],
        rest: Monomial,
        coefficient: &'p Rational,
    }
    fn split<'p>(p: &'p Poly, vars: &[Var]) -> Option<Vec<Split<'p>>> {
        p.terms()
            .map(|(m, c)| {
                let signed: Vec<Exp> = vars.iter().map(|&v| m.exponent(v)).collect();
                let rest = Monomial::from_factors(
                    (m.factors().iter().copied())
                        .filter(|(v, _)| !vars.contains(v))
                        .collect(),
                );
                let mut exps = [0u32; 4];
                let mut parity = 0;
                for (k, &e) in signed.iter().enumerate() {
                    exps[k] = u32::try_from(e).ok()?;
                    parity |= ((e & 1) as usize) << k;
                }
                Some(Split {
                    parity,
                    exps,
                    rest,
                    coefficient: c,
                })
            })
            .collect()
    }
    let (Some(a), Some(b)) = (
        (vars.len() <= 4).then(|| split(x, vars)).flatten(),
        (vars.len() <= 4).then(|| split(y, vars)).flatten(),
    ) else {
        return (x * y).average_over_normal(vars);
    };
    let mut by_parity: Vec<Vec<&Split>> = (0..16).map(|_| Vec::new()).collect();
    for t in &b {
        by_parity[t.parity].push(t);
    }
    let mut moments: HashMap<[u32; 4], Rational> = HashMap::default();
    let mut out = Vec::new();
    for s in &a {
        for t in &by_parity[s.parity] {
            let mut exps = [0u32; 4];
            for ((e, x), y) in exps.iter_mut().zip(s.exps).zip(t.exps) {
                *e = x + y;
            }
            let moment = moments
                .entry(exps)
                .or_insert_with(|| monomial_moment(vars.len(), &exps[..vars.len()]));
            out.push((
                s.rest.mul(&t.rest),
                &(s.coefficient * t.coefficient) * &*moment,
            ));
        }
    }
    Ok(Poly::from_terms(out))
}

/// LaTeX form, highest total degree first.
pub fn latex(p: &Poly, names: &VarTable) -> String {
    let power = |name: &str, e: Exp| format!("{name}^{{{e}}}");
    p.written(names, usize::MAX, &rational_latex, &power, " ")
}

/// LaTeX form of a rational: `\frac{p}{q}` or `p`, with a leading minus sign.
pub fn rational_latex(q: &Rational) -> String {
    if q.is_integer() {
        return q.numer().to_string();
    }
    let sign = if q.is_negative() { "-" } else { "" };
    format!("{sign}\\frac{{{}}}{{{}}}", q.numer().magnitude(), q.denom())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::{below, q, vars};
    use num_traits::{One, Zero};

    #[test]
    fn latex_forms() {
        assert_eq!(rational_latex(&q(-1, 15)), "-\\frac{1}{15}");
        assert_eq!(rational_latex(&q(4, 1)), "4");
        let (names, v) = vars(&["x", "y"]);
        let p = &(&v[0] * &v[0]) - &(&v[1] * &Poly::constant(q(1, 2)));
        assert_eq!(latex(&p, &names), "x^{2} - \\frac{1}{2} y");
    }

    /// Square roots of random squares are found (up to the sign the root's leading
    /// coefficient fixes), and random squares plus a perturbation are not squares.
    #[test]
    fn square_roots_of_random_squares() {
        let (_, xs) = vars(&["x", "y", "z"]);
        let mut seed = 0x9E37_79B9_7F4A_7C15_u64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        for _ in 0..200 {
            let mut r = Poly::zero();
            for _ in 0..(1 + next() % 5) {
                let m = Monomial::from_factors(
                    (0..3)
                        .map(|k| (k as Var, (next() % 4) as Exp - 1))
                        .collect(),
                );
                let c = q((next() % 13) as i64 - 6, 1 + (next() % 4) as i64);
                r.add_term(m, c);
            }
            let square = &r * &r;
            let root = sqrt(&square, 1000).expect("a square has a root");
            assert!(root == r || root == -r.clone(), "{root:?} vs {r:?}");
            // A square plus a term below its lowest order in x is no square unless it
            // cancels to one; check the claimed root whenever one is returned.
            let bumped = &square + &(&xs[0] * &Poly::constant(q(1, 1)));
            if let Some(t) = sqrt(&bumped, 1000) {
                assert_eq!(&t * &t, bumped);
            }
        }
        let (x, y) = (&xs[0], &xs[1]);
        assert_eq!(sqrt(&(&(x * x) + &Poly::constant(q(1, 1))), 100), None);
        assert_eq!(sqrt(&(&(x * x) - &(y * y)), 100), None);
        assert_eq!(sqrt(&Poly::constant(q(2, 1)), 100), None);
        assert_eq!(
            sqrt(&Poly::constant(q(9, 4)), 100),
            Some(Poly::constant(q(3, 2)))
        );
    }

    #[test]
    fn average_of_a_product_is_the_product_averaged() {
        let (_, v) = vars(&["n1", "n2", "n3", "x", "y"]);
        let mut next = below(0x5eed_a7e5);
        let random = |dim: usize, next: &mut dyn FnMut(u64) -> u64| -> Poly {
            let terms = 1 + next(9) as usize;
            let mut p = Poly::zero();
            for _ in 0..terms {
                let mut t = Poly::constant(q(next(19) as i64 - 9, 1 + next(6) as i64));
                for n in &v[..dim] {
                    t = &t * &n.pow(next(6) as u32);
                }
                // x and y (variables 3 and 4), possibly inverted.
                for other in 3..5 {
                    let e = next(4) as Exp - 1;
                    t = &t * &Poly::from_terms([(Monomial::var(other, e), Rational::one())]);
                }
                p += &t;
            }
            p
        };
        let mut nonzero = 0;
        for round in 0..400 {
            let dim = 2 + round % 2;
            let n: Vec<Var> = (0..dim).map(|k| k as Var).collect();
            let (a, b) = (random(dim, &mut next), random(dim, &mut next));
            let fused = average_of_product(&a, &b, &n).unwrap();
            assert_eq!(fused, (&a * &b).average_over_normal(&n).unwrap(), "{round}");
            nonzero += usize::from(!fused.is_zero());
        }
        assert!(nonzero > 200, "the averages are mostly not zero: {nonzero}");
        let n: Vec<Var> = (0..3).map(|k| k as Var).collect();
        let inverse = Poly::from_terms([(Monomial::var(0, -1), Rational::one())]);
        assert_eq!(
            average_of_product(&inverse, &v[1], &n),
            (&inverse * &v[1]).average_over_normal(&n)
        );
        assert_eq!(
            average_of_product(&inverse, &v[1], &n),
            Err(PolyError::NegativeNormalPower)
        );
        // n₁⁻¹ · n₁³ = n₁²: the product has no negative power, and neither has the fused
        // route's answer.
        assert_eq!(
            average_of_product(&inverse, &v[0].pow(3), &n).unwrap(),
            Poly::constant(q(1, 3))
        );
    }
}
