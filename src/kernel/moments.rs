//! Exact isotropic moments of a unit vector uniformly distributed on the unit circle
//! (d = 2) or the unit sphere (d = 3), for any order: the fabric averages of
//! Section 3.3, eqs. (25)–(26).
//!
//! Derivation (first principles, no table): let g be a standard Gaussian vector in
//! R^d. Then g = ρ n with ρ = |g| independent of n = g/|g|, and n is uniform on the
//! unit sphere S^{d−1}. For a multi-index α with |α| = k,
//!
//!   E[g^α] = E[ρ^k] ⟨n^α⟩.
//!
//! The components of g are independent N(0,1), so E[g^α] = Π_i E[g_i^{α_i}], and
//! E[x^a] = (a−1)!! for even a, 0 for odd a. ρ² is χ²-distributed with d degrees of
//! freedom, whose m-th moment is d(d+2)…(d+2m−2). Hence, for all α_i even,
//!
//!   ⟨n^α⟩ = Π_i (α_i − 1)!! / (d (d+2) … (d+k−2)),
//!
//! and ⟨n^α⟩ = 0 as soon as one α_i is odd (the odd-averages claim). Checks:
//! ⟨n_1²⟩ = 1/d, ⟨n_1⁴⟩ = 3/(d(d+2)) (1/5 in 3D), ⟨n_1² n_2²⟩ = 1/(d(d+2)).

use super::rational::Rational;
use num_traits::{One, Zero};

/// (a − 1)!! for even a ≥ 0, i.e. 1·3·5·…·(a−1); 1 for a = 0.
fn odd_double_factorial_below(a: u32) -> Rational {
    (1..a).step_by(2).fold(Rational::one(), |acc, k| {
        &acc * &Rational::int(i64::from(k))
    })
}

/// ⟨n_1^{α_1} … n_d^{α_d}⟩ for n uniform on the unit sphere S^{d−1}, exactly.
///
/// ```
/// use cosserat_kernel::{monomial_moment, Rational};
/// assert_eq!(monomial_moment(3, &[4, 0, 0]), Rational::ratio(1, 5).unwrap()); // ⟨n_1⁴⟩
/// assert_eq!(monomial_moment(3, &[2, 2, 0]), Rational::ratio(1, 15).unwrap()); // eq. (26)
/// ```
/// `exponents.len()` is the dimension d (2 or 3 in this paper; any d ≥ 1 works).
pub fn monomial_moment(dim: usize, exponents: &[u32]) -> Rational {
    debug_assert_eq!(dim, exponents.len());
    if exponents.iter().any(|a| a % 2 == 1) {
        return Rational::zero();
    }
    let k: u32 = exponents.iter().sum();
    let numer = exponents.iter().fold(Rational::one(), |acc, &a| {
        &acc * &odd_double_factorial_below(a)
    });
    let denom = (0..k / 2).fold(Rational::one(), |acc, m| {
        &acc * &Rational::int(dim as i64 + 2 * i64::from(m))
    });
    numer
        .checked_div(&denom)
        .expect("a product of positive integers is nonzero")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(n: i64, d: i64) -> Rational {
        Rational::ratio(n, d).unwrap()
    }

    #[test]
    fn known_values_in_3d() {
        assert_eq!(monomial_moment(3, &[2, 0, 0]), q(1, 3));
        assert_eq!(monomial_moment(3, &[4, 0, 0]), q(1, 5));
        assert_eq!(monomial_moment(3, &[2, 2, 0]), q(1, 15));
        assert_eq!(monomial_moment(3, &[2, 2, 2]), q(1, 105));
        assert_eq!(monomial_moment(3, &[6, 0, 0]), q(1, 7));
        assert_eq!(monomial_moment(3, &[1, 1, 0]), q(0, 1));
        assert_eq!(monomial_moment(3, &[0, 0, 0]), q(1, 1));
    }

    #[test]
    fn known_values_in_2d() {
        // ∫ cos²θ dθ / 2π = 1/2, ∫ cos⁴θ = 3/8, ∫ cos²θ sin²θ = 1/8.
        assert_eq!(monomial_moment(2, &[2, 0]), q(1, 2));
        assert_eq!(monomial_moment(2, &[4, 0]), q(3, 8));
        assert_eq!(monomial_moment(2, &[2, 2]), q(1, 8));
        assert_eq!(monomial_moment(2, &[3, 1]), q(0, 1));
    }

    #[test]
    fn moments_respect_the_unit_constraint() {
        // ⟨(n·n) n^α⟩ = ⟨n^α⟩ for every α up to order 10, in 2D and 3D.
        for dim in [2usize, 3] {
            for total in 0..=10u32 {
                for alpha in exponent_vectors(dim, total) {
                    let lhs = (0..dim).fold(Rational::zero(), |acc, i| {
                        let mut e = alpha.clone();
                        e[i] += 2;
                        &acc + &monomial_moment(dim, &e)
                    });
                    assert_eq!(lhs, monomial_moment(dim, &alpha), "dim {dim} α {alpha:?}");
                }
            }
        }
    }

    pub(crate) fn exponent_vectors(dim: usize, total: u32) -> Vec<Vec<u32>> {
        if dim == 1 {
            return vec![vec![total]];
        }
        (0..=total)
            .flat_map(|a| {
                exponent_vectors(dim - 1, total - a)
                    .into_iter()
                    .map(move |mut rest| {
                        rest.insert(0, a);
                        rest
                    })
            })
            .collect()
    }
}
