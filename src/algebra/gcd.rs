//! Exact division and greatest common divisors of multivariate polynomials over ℚ.
//!
//! An elastoplastic tangent, an acoustic determinant or a shear band's A² are rational
//! functions of the material parameters; keeping them reduced (so that two equal functions print and
//! compare identically) needs the gcd of numerator and denominator. The method is the
//! textbook recursive one (Knuth, TAOCP vol. 2, §4.6.1; Geddes, Czapor & Labahn,
//! ch. 7): view a polynomial as univariate in its largest variable with coefficients
//! in the others, split off the content, run the primitive pseudo-remainder sequence,
//! and recurse on the contents. Every step is exact and small enough to audit, but the
//! coefficients of the remainders swell, so it is the last resort: monomial contents
//! are split off first, coprime pairs are proved coprime by images mod a prime, and a
//! common factor of positive degree is first sought by the modular algorithm of
//! [`super::modular`], whose candidates are accepted only when they divide both inputs
//! and the cofactors are proved coprime (`confirmed`). The remainder sequence is left
//! for what the modular route cannot take (more than 16 variables, a degree above 64,
//! its budget of points or primes spent); it is the one computation of a decision
//! without a work bound, so it stops when the claim's time limit asks it to
//! ([`crate::kernel::interrupt`]).
//!
//! Only ordinary polynomials (no negative exponents) are accepted: a Laurent
//! polynomial is first cleared by [`clear_denominator_monomial`].

use super::modular;
use super::residue;
use crate::kernel::interrupt;
use crate::kernel::poly::{Exp, Monomial, Poly, Var};
use crate::kernel::rational::Rational;
use num_traits::{One, Zero};
use std::collections::BTreeMap;

/// Splits a Laurent polynomial `p` into `(q, m)` with `p = q / m`, `q` an ordinary
/// polynomial and `m` the smallest monomial that clears every negative exponent.
pub fn clear_denominator_monomial(p: &Poly) -> (Poly, Monomial) {
    let mut lowest: BTreeMap<Var, Exp> = BTreeMap::new();
    for (m, _) in p.terms() {
        for &(v, e) in m.factors() {
            if e < 0 {
                let slot = lowest.entry(v).or_insert(0);
                *slot = (*slot).min(e);
            }
        }
    }
    if lowest.is_empty() {
        // Already ordinary: multiplying by the monomial 1 would only copy it, sorted.
        return (p.clone(), Monomial::one());
    }
    let m = Monomial::from_factors(lowest.into_iter().map(|(v, e)| (v, -e)).collect());
    (p * &Poly::term(m.clone(), Rational::one()), m)
}

/// The largest monomial dividing every term of an ordinary polynomial.
pub(super) fn monomial_content(p: &Poly) -> Monomial {
    let mut terms = p.terms();
    let Some((first, _)) = terms.next() else {
        return Monomial::one();
    };
    let mut common: Vec<(Var, Exp)> = first.factors().to_vec();
    for (m, _) in terms {
        common = common
            .into_iter()
            .filter_map(|(v, e)| {
                let e = e.min(m.exponent(v));
                (e > 0).then_some((v, e))
            })
            .collect();
    }
    Monomial::from_factors(common)
}

/// The largest variable occurring in `p`, if any.
fn main_var(p: &Poly) -> Option<Var> {
    p.terms()
        .filter_map(|(m, _)| m.factors().last().map(|&(v, _)| v))
        .max()
}

/// Degree of `p` in `v` (0 for the zero polynomial).
pub fn degree_in(p: &Poly, v: Var) -> Exp {
    p.terms().map(|(m, _)| m.exponent(v)).max().unwrap_or(0)
}

/// `p` as a polynomial in `v`: exponent of `v` ↦ coefficient (free of `v`).
fn coefficients_in(p: &Poly, v: Var) -> BTreeMap<Exp, Poly> {
    let mut terms: BTreeMap<Exp, Vec<(Monomial, Rational)>> = BTreeMap::new();
    for (m, c) in p.terms() {
        terms
            .entry(m.exponent(v))
            .or_default()
            .push((m.without(v), c.clone()));
    }
    terms
        .into_iter()
        .map(|(e, terms)| (e, Poly::from_terms(terms)))
        .collect()
}

fn leading_coefficient_in(p: &Poly, v: Var) -> Poly {
    let top = degree_in(p, v);
    Poly::from_terms(
        p.terms()
            .filter(|(m, _)| m.exponent(v) == top)
            .map(|(m, c)| (m.without(v), c.clone())),
    )
}

fn var_power(v: Var, e: Exp) -> Poly {
    Poly::term(Monomial::var(v, e), Rational::one())
}

/// `a / b` when `b` divides `a` exactly in ℚ[x…]; `None` when it does not (or `b = 0`).
/// Both must be ordinary polynomials.
pub fn divide_exact(a: &Poly, b: &Poly) -> Option<Poly> {
    if b.is_zero() {
        return None;
    }
    if a.is_zero() {
        return Some(Poly::zero());
    }
    let Some(v) = main_var(b) else {
        let c = b.as_constant()?;
        return Some(a * &Poly::constant(c.recip()?));
    };
    if !degrees_admit(a, b) {
        return None;
    }
    let db = degree_in(b, v);
    let lb = leading_coefficient_in(b, v);
    let mut rem = a.clone();
    let mut quot = Poly::zero();
    while !rem.is_zero() {
        let dr = degree_in(&rem, v);
        if dr < db {
            return None;
        }
        let q = divide_exact(&leading_coefficient_in(&rem, v), &lb)?;
        let t = &q * &var_power(v, dr - db);
        rem = &rem - &(&t * b);
        quot += &t;
    }
    Some(quot)
}

/// Whether the degrees of two nonzero ordinary polynomials allow `a = q·b` with `q`
/// ordinary: a necessary condition, read off without dividing. In every variable `v`
/// of `b`, and in the total degree (a grading too), the highest and the lowest degree
/// of a product are the sums of its factors' (the extreme homogeneous parts of `q` and
/// `b` multiply to a nonzero part over a domain), so `q`'s would be `a`'s minus `b`'s,
/// and its lowest must be at least 0 and at most its highest. A false answer is a
/// proof that `b` does not divide `a`; most trial divisions in a derivation fail this
/// way, on their first scan.
fn degrees_admit(a: &Poly, b: &Poly) -> bool {
    let admits = |degree: &dyn Fn(&Monomial) -> i128| {
        let range = |p: &Poly| {
            p.terms().fold((i128::MAX, i128::MIN), |(lo, hi), (m, _)| {
                let d = degree(m);
                (lo.min(d), hi.max(d))
            })
        };
        let ((lo_a, hi_a), (lo_b, hi_b)) = (range(a), range(b));
        let lo_q = lo_a - lo_b;
        lo_q >= 0 && hi_a - hi_b >= lo_q
    };
    admits(&Monomial::total_degree)
        && b.variables()
            .into_iter()
            .all(|v| admits(&|m| i128::from(m.exponent(v))))
}

/// Pseudo-remainder of `a` by `b` in `v`: `lc(b)^k a = q b + r` with `deg_v r < deg_v b`.
fn pseudo_remainder(a: &Poly, b: &Poly, v: Var) -> Poly {
    let db = degree_in(b, v);
    let lb = leading_coefficient_in(b, v);
    let mut r = a.clone();
    while !r.is_zero() && degree_in(&r, v) >= db {
        let dr = degree_in(&r, v);
        let lr = leading_coefficient_in(&r, v);
        r = &(&lb * &r) - &(&(&lr * &var_power(v, dr - db)) * b);
    }
    r
}

/// The content of `p` in `v` (gcd of its coefficients, a polynomial free of `v`) and
/// the primitive part `p / content`.
fn content_and_primitive(p: &Poly, v: Var) -> (Poly, Poly) {
    let content = coefficients_in(p, v)
        .values()
        .fold(Poly::zero(), |g, c| gcd(&g, c));
    let primitive = divide_exact(p, &content).expect("the content divides every coefficient");
    (content, primitive)
}

/// The greatest common divisor of two ordinary polynomials, normalised by
/// [`normalize_sign_and_scale`] (integer coefficients without common factor, positive
/// leading coefficient); `gcd(0, 0) = 0`.
///
/// ```
/// use cosserat_kernel::{Poly, VarTable};
/// use cosserat_algebra::gcd;
/// let mut names = VarTable::new();
/// let x = Poly::var(names.intern("x"));
/// let y = Poly::var(names.intern("y"));
/// let a = &(&x + &y) * &(&x - &y); // x² − y²
/// let b = &(&x + &y) * &(&x + &y); // (x + y)²
/// assert_eq!(gcd::gcd(&a, &b).display(&names), "x + y");
/// ```
pub fn gcd(a: &Poly, b: &Poly) -> Poly {
    if a.is_zero() {
        return normalize_sign_and_scale(b);
    }
    if b.is_zero() {
        return normalize_sign_and_scale(a);
    }
    // Short cuts: a nonzero constant is a unit; gcd(a, a) = a.
    if a.as_constant().is_some() || b.as_constant().is_some() {
        return Poly::one();
    }
    if a == b {
        return normalize_sign_and_scale(a);
    }
    // The monomial contents apart: a variable divides the gcd exactly as often as it
    // divides both, and the rest is the gcd of what remains (which no variable
    // divides). The remainder sequence of the whole would drag the contents through
    // every step.
    let (ma, mb) = (monomial_content(a), monomial_content(b));
    if !ma.is_one() || !mb.is_one() {
        let strip = |p: &Poly, m: Monomial| {
            p.checked_div(&Poly::term(m, Rational::one()))
                .expect("a monomial divides")
        };
        let common = Monomial::from_factors(
            ma.factors()
                .iter()
                .filter_map(|&(v, e)| {
                    let e = e.min(mb.exponent(v));
                    (e > 0).then_some((v, e))
                })
                .collect(),
        );
        let rest = gcd(&strip(a, ma), &strip(b, mb));
        return normalize_sign_and_scale(&(&rest * &Poly::term(common, Rational::one())));
    }
    if coprime_by_images(a, b) {
        return Poly::one();
    }
    if let Some(g) = modular::gcd(a, b, &|g| confirmed(a, b, g)) {
        return g;
    }
    gcd_by_remainders(a, b)
}

/// `g`, normalised, when it is gcd(a, b): it divides both exactly and the cofactors
/// are proved coprime, so gcd(a, b) = g·gcd(a/g, b/g) = g. `None` proves nothing.
/// This is what makes the untrusted [`modular::gcd`] safe to use.
///
/// A constant `g` is the gcd when `a` and `b` are proved coprime; the images at the
/// usual point have just failed to prove it, so other points are tried.
fn confirmed(a: &Poly, b: &Poly, g: &Poly) -> Option<Poly> {
    if g.as_constant().is_some() {
        let proved = (1..=SPARE_IMAGE_POINTS).any(|k| coprime_at(a, b, &image_point(k)));
        return proved.then(Poly::one);
    }
    let (ca, cb) = (divide_exact(a, g)?, divide_exact(b, g)?);
    let coprime =
        ca.as_constant().is_some() || cb.as_constant().is_some() || coprime_by_images(&ca, &cb);
    coprime.then(|| normalize_sign_and_scale(g))
}

/// Further points at which [`confirmed`] tries to prove coprimality when the modular
/// gcd is 1.
const SPARE_IMAGE_POINTS: u64 = 4;

/// The gcd of two nonzero, nonconstant, different ordinary polynomials by the
/// primitive pseudo-remainder sequence in their largest variable.
///
/// Its coefficients can swell without a bound known in advance, so it asks
/// [`interrupt::requested`] before each step; once a stop is requested it returns 1,
/// which means nothing, and whoever requested the stop discards the result.
fn gcd_by_remainders(a: &Poly, b: &Poly) -> Poly {
    if interrupt::requested() {
        return Poly::one();
    }
    let v = match (main_var(a), main_var(b)) {
        (None, None) => return Poly::one(),
        (x, y) => x.max(y).expect("one of them has a variable"),
    };
    let (ca, pa) = content_and_primitive(a, v);
    let (cb, pb) = content_and_primitive(b, v);
    let content = gcd(&ca, &cb);
    let (mut r0, mut r1) = if degree_in(&pa, v) >= degree_in(&pb, v) {
        (pa, pb)
    } else {
        (pb, pa)
    };
    while !r1.is_zero() {
        if interrupt::requested() {
            return Poly::one();
        }
        let r = pseudo_remainder(&r0, &r1, v);
        r0 = r1;
        // The primitive part, scaled to coprime integer coefficients: over ℚ the
        // content of constant coefficients is a unit, and without this scaling the
        // coefficients of the pseudo-remainders grow exponentially.
        r1 = if r.is_zero() {
            r
        } else {
            normalize_sign_and_scale(&content_and_primitive(&r, v).1)
        };
    }
    let primitive = if degree_in(&r0, v) == 0 {
        Poly::one()
    } else {
        content_and_primitive(&r0, v).1
    };
    normalize_sign_and_scale(&(&content * &primitive))
}

/// Whether two nonzero ordinary polynomials are proved coprime by their images in
/// 𝔽_P\[w\] (the first step of a modular gcd; Geddes, Czapor & Labahn, ch. 7). `false`
/// proves nothing: the caller computes the gcd.
///
/// Why a `true` is a proof: a common factor `g` of positive degree has a variable `w`
/// of positive degree, which both `a` and `b` contain. Take `g` primitive with integer
/// coefficients; by Gauss's lemma `a = g·h` with `h` as `P`-integral as `a`, so the map
/// φ to 𝔽_P\[w\] (every other variable at a fixed residue) gives `φ(a) = φ(g)·φ(h)`.
/// When φ keeps `a`'s degree in `w`, it keeps the leading coefficient of `g` nonzero, so
/// `φ(g)` has positive degree and divides both images. Images with a gcd of degree 0,
/// for every shared variable, rule every such `g` out.
fn coprime_by_images(a: &Poly, b: &Poly) -> bool {
    coprime_at(a, b, &image_point(0))
}

/// The `k`-th fixed point of residues, far from 0 and 1 (splitmix64 of the variable
/// and `k`); the 0-th is where [`coprime_by_images`] looks.
fn image_point(k: u64) -> impl Fn(Var) -> u64 {
    move |v: Var| residue::scramble(u64::from(v) ^ k.wrapping_mul(0x5851_f42d_4c95_7f2d))
}

/// [`coprime_by_images`] with the other variables at the residues `at`.
fn coprime_at(a: &Poly, b: &Poly, at: &dyn Fn(Var) -> u64) -> bool {
    let (va, vb) = (a.variables(), b.variables());
    va.iter().filter(|w| vb.contains(w)).all(|&w| {
        let (Some(ia), Some(ib)) = (
            residue::univariate_image(a, w, at),
            residue::univariate_image(b, w, at),
        ) else {
            return false;
        };
        !ia.is_empty()
            && !ib.is_empty()
            && ia.len() - 1 == degree_in(a, w) as usize
            && residue::gcd_degree(ia, ib) == 0
    })
}

/// `p` scaled by a nonzero rational so that its coefficients are coprime integers and
/// its leading term (graded lexicographic) is positive: the canonical associate.
pub fn normalize_sign_and_scale(p: &Poly) -> Poly {
    match canonical_scale(p) {
        Some(s) => p * &Poly::constant(s),
        None => Poly::zero(),
    }
}

pub use crate::kernel::poly::canonical_scale;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::VarTable;
    use num_bigint::BigInt;

    fn setup() -> (VarTable, Poly, Poly, Poly) {
        let mut names = VarTable::new();
        let x = Poly::var(names.intern("x"));
        let y = Poly::var(names.intern("y"));
        let z = Poly::var(names.intern("z"));
        (names, x, y, z)
    }

    fn c(n: i64) -> Poly {
        Poly::constant(Rational::int(n))
    }

    #[test]
    fn exact_division_recovers_the_factor_and_refuses_a_remainder() {
        let (_, x, y, z) = setup();
        let f = &(&(&x * &y) + &c(3)) - &z; // xy + 3 − z
        let g = &(&x.pow(2) - &(&y * &z)) + &c(1);
        let fg = &f * &g;
        assert_eq!(divide_exact(&fg, &f), Some(g.clone()));
        assert_eq!(divide_exact(&fg, &g), Some(f.clone()));
        assert_eq!(divide_exact(&(&fg + &c(1)), &f), None);
        assert_eq!(divide_exact(&fg, &Poly::zero()), None);
        assert_eq!(
            divide_exact(&(&x * &c(6)), &c(4)),
            Some(&x * &Poly::constant(Rational::ratio(3, 2).unwrap()))
        );
    }

    /// Pseudo-random draws below `n` (a 64-bit LCG's high bits), seeded.
    fn draws(mut state: u64) -> impl FnMut(u64) -> u64 {
        move |n| {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 33) % n
        }
    }

    /// A random polynomial in `x, y, z` of up to `terms` terms, exponents 0..=`top`,
    /// small integer coefficients (zero-free).
    fn random_poly(next: &mut impl FnMut(u64) -> u64, terms: u64, top: u64) -> Poly {
        (0..1 + next(terms)).fold(Poly::zero(), |p, _| {
            let m = Monomial::from_factors(
                (0..3)
                    .map(|v| (v, next(top + 1) as Exp))
                    .filter(|&(_, e)| e > 0)
                    .collect(),
            );
            let c = next(7) as i64 - 3;
            &p + &Poly::term(m, Rational::int(if c == 0 { 5 } else { c }))
        })
    }

    #[test]
    fn the_degree_test_never_refuses_a_true_quotient() {
        // 600 random products q·b (monomial contents, constants and single terms
        // included): the degrees admit b and the division recovers q. The test must
        // also refuse: b·x + 1 is refused by degrees alone in many of them (a test
        // that always admitted would be sound but useless), and where it divides, it
        // truly does.
        let mut next = draws(0x9e37_79b9_7f4a_7c15_u64);
        let (mut exact, mut refused) = (0, 0);
        for _ in 0..600 {
            let q = random_poly(&mut next, 5, 3);
            let b = random_poly(&mut next, 4, 3);
            if q.is_zero() || b.is_zero() {
                continue;
            }
            let a = &q * &b;
            assert!(degrees_admit(&a, &b));
            assert_eq!(divide_exact(&a, &b), Some(q.clone()));
            exact += 1;
            let other = &(&b * &Poly::var(0)) + &c(1);
            if !degrees_admit(&a, &other) {
                refused += 1;
            }
            if let Some(r) = divide_exact(&a, &other) {
                assert_eq!(&r * &other, a);
            }
        }
        assert!(
            exact > 500 && refused > 100,
            "{exact} exact, {refused} refused"
        );
    }

    #[test]
    fn gcd_finds_the_common_factor_of_multivariate_products() {
        let (names, x, y, z) = setup();
        let g = &(&(&x * &z) - &y.pow(2)) + &c(2); // xz − y² + 2
        let p = &(&x + &y) + &z;
        let q = &(&x.pow(2) + &z) - &c(5);
        let a = &(&g * &p) * &c(3);
        let b = &(&g * &q) * &Poly::constant(Rational::ratio(-1, 7).unwrap());
        assert_eq!(gcd(&a, &b), normalize_sign_and_scale(&g));
        assert_eq!(gcd(&a, &b).display(&names), "x*z - y^2 + 2");
        // Coprime inputs give 1; a repeated factor is found with its multiplicity.
        assert_eq!(gcd(&p, &q), Poly::one());
        let g2 = &g * &g;
        assert_eq!(gcd(&(&g2 * &p), &(&g2 * &q)), normalize_sign_and_scale(&g2));
        // Contents in the other variables are found too: gcd(y·x, y·z) = y.
        assert_eq!(gcd(&(&y * &x), &(&y * &z)), y);
        assert_eq!(gcd(&Poly::zero(), &(&x * &c(-4))), x);
        assert_eq!(gcd(&c(6), &c(4)), Poly::one());
    }

    #[test]
    fn images_prove_coprimality_only_of_coprime_pairs() {
        // 150 random pairs: with a common factor of positive degree the images never
        // prove coprimality; without, whenever they do, the remainder sequence agrees,
        // and they do for nearly every coprime pair (the screen is used, not idle).
        let mut next = draws(0x2545_f491_4f6c_dd1d_u64);
        let (mut proved, mut pairs) = (0, 0);
        for _ in 0..150 {
            // A constant term keeps monomial contents out (`gcd` splits them off first).
            let p = &random_poly(&mut next, 4, 2) + &c(7);
            let q = &random_poly(&mut next, 4, 2) + &c(7);
            let g = random_poly(&mut next, 3, 2);
            if [&p, &q].iter().any(|x| x.as_constant().is_some()) || p == q {
                continue;
            }
            if g.as_constant().is_none() {
                assert!(!coprime_by_images(&(&g * &p), &(&g * &q)));
            }
            let coprime = gcd_by_remainders(&p, &q) == Poly::one();
            pairs += usize::from(coprime);
            if coprime_by_images(&p, &q) {
                proved += 1;
                assert!(coprime);
            }
        }
        assert!(
            pairs > 100 && proved * 10 >= pairs * 9,
            "{proved} of {pairs} coprime pairs proved"
        );
        // A common factor whose leading coefficients vanish at the point is not lost:
        // at x = y = 0, x·y + 1 maps to 1 in both images, and only the lost degree
        // shows that the images x + 2 and x + 5 (or y + 2 and y + 5) prove nothing.
        let (_, x, y, _) = setup();
        let g = &(&x * &y) + &c(1);
        let (a, b) = (&g * &(&(&x + &y) + &c(2)), &g * &(&(&x + &y) + &c(5)));
        assert!(!coprime_at(&a, &b, &|_| 0));
        assert!(!coprime_by_images(&a, &b));
        assert_eq!(gcd(&a, &b), g);
    }

    #[test]
    fn monomial_contents_are_split_off() {
        // x·(3 − y z³ + x y z + 5 x² y² z) and x²·(−2 y³ z² − 2 x − 3 x z³): the gcd is
        // x (the remainder sequence of the whole took 0.36 s on it), and the smaller
        // power of each shared variable is kept.
        let (_, x, y, z) = setup();
        let a = &x
            * &(&(&(&c(3) - &(&y * &z.pow(3))) + &(&(&x * &y) * &z))
                + &(&(&c(5) * &x.pow(2)) * &(&y.pow(2) * &z)));
        let b = &x.pow(2)
            * &(&(&(&c(-2) * &y.pow(3)) * &z.pow(2))
                - &(&(&c(2) * &x) + &(&(&c(3) * &x) * &z.pow(3))));
        assert_eq!(gcd(&a, &b), x);
        let f = &(&x * &y) + &c(1);
        let a = &(&x.pow(3) * &y) * &f;
        let b = &(&x.pow(2) * &y.pow(4)) * &(&f * &(&z + &c(1)));
        assert_eq!(gcd(&a, &b), &(&x.pow(2) * &y) * &f);
        assert_eq!(gcd(&a, &(&x * &z)), x);
    }

    #[test]
    fn the_modular_gcd_is_the_gcd_the_remainder_sequence_finds() {
        // 60 random pairs g·p, g·q (exponents up to 2, where the remainder sequence is
        // affordable as the oracle): the modular route gives a candidate that the
        // check accepts, and it equals the remainder sequence's gcd.
        let mut next = draws(0x51_7cc1_b727_220a_u64);
        let mut confirmed_count = 0;
        for _ in 0..60 {
            let g = &random_poly(&mut next, 3, 2) + &c(2);
            let p = &random_poly(&mut next, 3, 2) + &c(7);
            let q = &random_poly(&mut next, 3, 2) + &c(7);
            let (a, b) = (&g * &p, &g * &q);
            if a.as_constant().is_some() || b.as_constant().is_some() || a == b {
                continue;
            }
            let oracle = gcd_by_remainders(&a, &b);
            let found = modular::gcd(&a, &b, &|g| confirmed(&a, &b, g));
            assert_eq!(found, Some(oracle.clone()));
            assert_eq!(gcd(&a, &b), oracle);
            confirmed_count += 1;
        }
        assert!(confirmed_count > 50, "{confirmed_count}");
    }

    #[test]
    fn the_candidate_one_is_confirmed_only_for_coprime_pairs() {
        // A constant candidate is the gcd exactly when the pair is proved coprime (at
        // points other than the usual one); a common factor refuses it.
        let (_, x, y, z) = setup();
        let (p, q) = (&(&x * &y) + &c(1), &(&y - &z) + &c(3));
        assert_eq!(confirmed(&p, &q, &Poly::one()), Some(Poly::one()));
        assert_eq!(confirmed(&p, &q, &c(5)), Some(Poly::one()));
        let (a, b) = (&p * &q, &p * &(&x + &c(2)));
        assert_eq!(confirmed(&a, &b, &Poly::one()), None);
    }

    #[test]
    fn the_check_refuses_wrong_candidates() {
        // The check is what makes the modular route sound: a candidate that misses a
        // factor of the gcd leaves cofactors that are not coprime; one with an extra
        // factor, a changed coefficient or a flipped sign of a term does not divide.
        let (_, x, y, z) = setup();
        let f = &(&x * &y) + &c(1);
        let h = &(&y - &z) + &c(3);
        let (a, b) = (&(&f * &h) * &(&x + &c(2)), &(&f * &h) * &(&z - &c(5)));
        let gcd_ab = normalize_sign_and_scale(&(&f * &h));
        assert_eq!(confirmed(&a, &b, &(&f * &h)), Some(gcd_ab.clone()));
        assert_eq!(confirmed(&a, &b, &(&c(-3) * &(&f * &h))), Some(gcd_ab));
        assert_eq!(confirmed(&a, &b, &f), None, "a missing factor");
        assert_eq!(
            confirmed(&a, &b, &(&(&f * &h) * &(&x + &c(2)))),
            None,
            "an extra factor"
        );
        let changed = &(&(&x * &y) + &c(2)) * &h;
        assert_eq!(confirmed(&a, &b, &changed), None, "a changed coefficient");
        let flipped = &(&(&x * &y) - &c(1)) * &h;
        assert_eq!(confirmed(&a, &b, &flipped), None, "a flipped sign");
    }

    #[test]
    fn gcds_of_products_are_found_without_the_remainder_sequence() {
        // Products of three four-term factors with exponents up to 3: the remainder
        // sequence took minutes on one such pair; the modular route finds g at once.
        let mut next = draws(0x2545_f491_4f6c_dd1d_u64);
        for _ in 0..10 {
            let g = &random_poly(&mut next, 4, 3) + &c(3);
            let p = &random_poly(&mut next, 4, 3) + &c(3);
            let q = &random_poly(&mut next, 4, 3) + &c(3);
            let (a, b) = (&g * &p, &g * &q);
            if [&g, &p, &q].iter().any(|x| x.as_constant().is_some()) {
                continue;
            }
            let d = modular::gcd(&a, &b, &|d| confirmed(&a, &b, d)).expect("confirmed");
            assert!(divide_exact(&d, &g).is_some(), "g divides the gcd");
            assert_eq!(gcd(&a, &b), d);
        }
    }

    /// The candidates [`modular::gcd`] offers the check, and its answer.
    fn offered(a: &Poly, b: &Poly) -> (Vec<Poly>, Option<Poly>) {
        let seen = std::cell::RefCell::new(Vec::new());
        let found = modular::gcd(a, b, &|g| {
            seen.borrow_mut().push(g.clone());
            confirmed(a, b, g)
        });
        (seen.into_inner(), found)
    }

    #[test]
    fn coefficients_beyond_one_prime_are_reconstructed_from_several() {
        // g = 10¹²·x + y + 1: with leading coefficient 1, its coefficients are 10⁻¹²,
        // beyond what one prime reconstructs. The first prime's reconstruction is
        // another small fraction with the same residue, a wrong candidate, which the
        // check refuses; with a second prime the reconstruction is g.
        let (_, x, y, z) = setup();
        let big =
            Poly::constant(Rational::from_big(BigInt::from(10).pow(12), BigInt::one()).unwrap());
        let g = &(&(&big * &x) + &y) + &c(1);
        let (a, b) = (&g * &(&x - &z), &g * &(&y + &c(3)));
        let (seen, found) = offered(&a, &b);
        assert_eq!(seen.len(), 2, "{seen:?}");
        assert_ne!(
            normalize_sign_and_scale(&seen[0]),
            normalize_sign_and_scale(&g)
        );
        assert_eq!(confirmed(&a, &b, &seen[0]), None);
        assert_eq!(found, Some(normalize_sign_and_scale(&g)));
        assert_eq!(gcd(&a, &b), normalize_sign_and_scale(&g));
    }

    #[test]
    fn material_constants_do_not_send_the_gcd_to_the_remainder_sequence() {
        // A user's rational function (g·a)² / ((g·b)² + g²) with coefficients like
        // E = 2.1·10¹¹: the gcd g² has coefficients near 10²⁵ once scaled to leading
        // coefficient 1. The remainder sequence ran for minutes on it; the modular
        // route needs a few primes.
        let (mut names, x, y, z) = setup();
        let w = Poly::var(names.intern("w"));
        let n = |s: &str| {
            Poly::constant(Rational::from_big(s.parse().unwrap(), BigInt::one()).unwrap())
        };
        let g = &(&(&(&n("210000000000") * &(&x.pow(2) * &y))
            + &(&n("7000000000013") * &(&z.pow(3) * &w)))
            + &(&n("123456789123") * &w.pow(2)))
            + &n("99999999977");
        let a = &(&(&n("31000000007") * &(&x * &y.pow(2))) + &(&c(5) * &(&z * &w.pow(3)))) + &c(11);
        let b = &(&(&c(13) * &x.pow(3)) + &(&n("45000000001") * &(&y * &z))) + &n("600000000001");
        let (ga, gb) = (&g * &a, &g * &b);
        let num = &ga * &ga;
        let den = &(&gb * &gb) + &(&g * &g);
        let (_, found) = offered(&num, &den);
        assert_eq!(found, Some(normalize_sign_and_scale(&(&g * &g))));
    }

    #[test]
    fn the_remainder_sequence_stops_when_asked() {
        // The remainder sequence asks before every step whether to stop. A condition
        // that never holds is asked more than once and changes nothing; one that
        // holds from its second question ends the sequence there, with a
        // meaningless value that still divides both inputs (so that no caller's
        // division fails).
        use crate::kernel::interrupt;
        use std::sync::atomic::{AtomicUsize, Ordering};
        use std::sync::Arc;
        let (_, x, y, z) = setup();
        let g = &(&(&x * &z) - &y.pow(2)) + &c(2);
        let (a, b) = (&g * &(&x.pow(3) + &z), &g * &(&y.pow(2) - &x));
        let asking = |from: usize| {
            let asked = Arc::new(AtomicUsize::new(0));
            let counter = asked.clone();
            let out = interrupt::under(
                Arc::new(move || counter.fetch_add(1, Ordering::Relaxed) + 1 >= from),
                || gcd_by_remainders(&a, &b),
            );
            (out, asked.load(Ordering::Relaxed))
        };
        let (found, questions) = asking(usize::MAX);
        assert_eq!(found, normalize_sign_and_scale(&g));
        assert!(questions >= 2, "{questions}");
        let (stopped, asked) = asking(2);
        assert_eq!(asked, 2);
        assert_ne!(stopped, found);
        assert!(divide_exact(&a, &stopped).is_some() && divide_exact(&b, &stopped).is_some());
    }

    #[test]
    fn gcd_is_refuted_by_a_wrong_factor() {
        // Mutant: the second input carries g with one coefficient changed, so the
        // common factor disappears and the gcd must be 1.
        let (_, x, y, z) = setup();
        let g = &(&(&x * &z) - &y.pow(2)) + &c(2);
        let g_mutant = &(&(&x * &z) - &y.pow(2)) + &c(3);
        let p = &(&x + &y) + &z;
        assert_eq!(
            gcd(&(&g * &p), &(&g_mutant * &p)),
            normalize_sign_and_scale(&p)
        );
        assert_eq!(gcd(&(&g * &x), &(&g_mutant * &y)), Poly::one());
    }

    #[test]
    fn laurent_polynomials_are_cleared_by_the_smallest_monomial() {
        let (_, x, y, _) = setup();
        let p = &(&x * &Poly::term(Monomial::var(1, -2), Rational::one())) + &y; // x/y² + y
        let (q, m) = clear_denominator_monomial(&p);
        assert_eq!(m, Monomial::var(1, 2));
        assert_eq!(q, &x + &y.pow(3));
    }
}
