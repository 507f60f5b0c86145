//! The gcd of two polynomials over ℚ from their images modulo primes (Brown's dense
//! modular algorithm; Geddes, Czapor & Labahn, ch. 7), for [`super::gcd::gcd`].
//!
//! The primitive remainder sequence over ℚ swells: the gcd of two products `g·a`,
//! `g·b` of five-term polynomials in three variables took minutes. Over 𝔽_p the
//! coefficients stay one word, and the variables are removed one at a time by
//! evaluation and interpolation. The images for several primes are combined by the
//! Chinese remainder theorem until rational reconstruction gives the coefficients:
//! one prime suffices for small ones, and a material constant such as
//! E = 210 000 000 000 needs a few.
//!
//! Nothing here is trusted. Each reconstruction is only a *candidate*, and the
//! caller's check decides whether it is the gcd (it divides both inputs exactly over ℚ
//! and the cofactors are proved coprime), whatever happened here. An unlucky prime or
//! evaluation point, coefficients too large for every prime together, or an input out
//! of range gives `None`, and the caller falls back to the remainder sequence.

use super::residue::{self, Field, Uni};
use crate::kernel::poly::{Monomial, Poly, Var};
use crate::kernel::rational::Rational;
use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, Signed, ToPrimitive, Zero};
use std::collections::BTreeMap;

/// A polynomial over 𝔽_p in `n` variables: exponent vectors (variable 0 most
/// significant, so the map's order is lexicographic) to nonzero residues.
type Image = BTreeMap<Vec<u32>, u64>;

/// The most variables, and the highest degree in any one, tried: the work grows as
/// the product of the degrees, and beyond these the caller's exact route decides.
const MAX_VARS: usize = 16;
const MAX_DEGREE: u32 = 64;

/// The evaluation points one gcd may use, over every prime and every level of the
/// recursion (their number per prime is the product of the degrees).
const POINT_BUDGET: u64 = 100_000;

/// Evaluation points tried beyond those needed, per level, before giving up: those
/// where a leading coefficient vanishes, and unlucky ones, where the image gcd has a
/// larger leading monomial than the gcd's image.
const SPARE_POINTS: u64 = 16;

/// gcd(a, b) of two nonzero ordinary polynomials, as accepted by `check`: each
/// candidate (leading coefficient 1) goes to `check`, which returns the gcd when the
/// candidate is one. `None` when the modular route finds none that `check` accepts
/// (see the module doc).
///
/// A constant image gcd ends the search: the candidate 1 goes to `check` once, since
/// more primes would only repeat it.
pub(super) fn gcd(a: &Poly, b: &Poly, check: &dyn Fn(&Poly) -> Option<Poly>) -> Option<Poly> {
    let mut vars = a.variables();
    for v in b.variables() {
        if !vars.contains(&v) {
            vars.push(v);
        }
    }
    vars.sort_unstable();
    if vars.is_empty() || vars.len() > MAX_VARS {
        return None;
    }
    let mut budget = POINT_BUDGET;
    let mut combined: Option<Combined> = None;
    let mut refused: Option<Poly> = None;
    for f in residue::fields() {
        // A prime that divides a coefficient (or a denominator) changes the images'
        // shape: skip it.
        let (Some(ia), Some(ib)) = (image(f, a, &vars), image(f, b, &vars)) else {
            continue;
        };
        let Some(g) = brown(f, &ia, &ib, vars.len(), &mut budget) else {
            if budget == 0 {
                return None;
            }
            continue;
        };
        let lm = leading_monomial(&g);
        if lm.iter().all(|&k| k == 0) {
            return check(&Poly::one());
        }
        let c = match combined.as_mut() {
            Some(c) if lm > c.leading => continue, // an unlucky prime
            Some(c) if lm == c.leading => {
                c.add(f, &g);
                c
            }
            // The first prime, or every earlier one was unlucky.
            _ => combined.insert(Combined::new(f, lm, &g)),
        };
        let Some(candidate) = c.lift(&vars) else {
            continue; // the coefficients need more primes
        };
        if refused.as_ref() != Some(&candidate) {
            if let Some(g) = check(&candidate) {
                return Some(g);
            }
            refused = Some(candidate);
        }
    }
    None
}

/// The image gcds of the primes so far, combined by the Chinese remainder theorem:
/// every coefficient as a residue mod the product of the primes.
struct Combined {
    leading: Vec<u32>,
    modulus: BigInt,
    coefficients: BTreeMap<Vec<u32>, BigInt>,
}

impl Combined {
    fn new(f: Field, leading: Vec<u32>, g: &Image) -> Self {
        Combined {
            leading,
            modulus: BigInt::from(f.p()),
            coefficients: g
                .iter()
                .map(|(k, &c)| (k.clone(), BigInt::from(c)))
                .collect(),
        }
    }

    /// Adds the image gcd `g` mod `f`'s prime (its leading monomial is `leading`): x
    /// mod M and r mod p give x + M·((r − x)·M⁻¹ mod p) mod M·p.
    fn add(&mut self, f: Field, g: &Image) {
        let p = BigInt::from(f.p());
        let residue_of = |n: &BigInt| (n % &p).to_u64().expect("a residue below p");
        let inverse = f
            .inverse(residue_of(&self.modulus))
            .expect("distinct primes are coprime");
        let mut keys: Vec<Vec<u32>> = g.keys().cloned().collect();
        keys.extend(
            self.coefficients
                .keys()
                .filter(|k| !g.contains_key(*k))
                .cloned(),
        );
        for k in keys {
            let r = g.get(&k).copied().unwrap_or(0);
            let x = self.coefficients.entry(k).or_default();
            let t = f.mul(f.sub(r, residue_of(x)), inverse);
            *x += &self.modulus * BigInt::from(t);
        }
        self.coefficients.retain(|_, x| !x.is_zero());
        self.modulus *= p;
    }

    /// The polynomial over ℚ whose coefficients reconstruct the combined ones, when
    /// every one of them reconstructs.
    fn lift(&self, vars: &[Var]) -> Option<Poly> {
        let mut terms = Vec::with_capacity(self.coefficients.len());
        for (e, c) in &self.coefficients {
            let factors = vars
                .iter()
                .zip(e)
                .filter(|&(_, &k)| k > 0)
                .map(|(&v, &k)| Some((v, crate::kernel::poly::Exp::from(k))))
                .collect::<Option<Vec<_>>>()?;
            terms.push((
                Monomial::from_factors(factors),
                reconstruct(c, &self.modulus)?,
            ));
        }
        Some(Poly::from_terms(terms))
    }
}

/// The image of `p` mod `f`'s prime over `vars`; `None` for a negative or too high
/// exponent, or a coefficient whose numerator or denominator the prime divides.
fn image(f: Field, p: &Poly, vars: &[Var]) -> Option<Image> {
    let mut out = Image::new();
    for (m, c) in p.terms() {
        let mut e = vec![0u32; vars.len()];
        for &(v, k) in m.factors() {
            let k = u32::try_from(k).ok().filter(|&k| k <= MAX_DEGREE)?;
            e[vars.binary_search(&v).ok()?] = k;
        }
        let r = f.of_rational(c).filter(|&r| r != 0)?;
        out.insert(e, r);
    }
    (!out.is_empty()).then_some(out)
}

/// The rational `r/s` with |r|, s ≤ √(m/2), gcd(r, s) = 1 and `r ≡ c·s` mod m, when
/// there is one (Wang's rational reconstruction by the extended Euclidean
/// algorithm); it is then unique.
fn reconstruct(c: &BigInt, m: &BigInt) -> Option<Rational> {
    let bound = (m / 2u32).sqrt();
    let (mut r0, mut r1) = (m.clone(), c.clone());
    let (mut s0, mut s1) = (BigInt::zero(), BigInt::one());
    while r1 > bound {
        let (q, r) = r0.div_rem(&r1);
        (r0, r1) = (r1, r);
        let s = &s0 - &q * &s1;
        (s0, s1) = (s1, s);
    }
    if s1.is_zero() || s1.abs() > bound || !r1.gcd(&s1).is_one() {
        return None;
    }
    let (n, d) = if s1.is_negative() {
        (-r1, -s1)
    } else {
        (r1, s1)
    };
    Rational::from_big(n, d)
}

/// gcd(a, b) in 𝔽_p[x_0 … x_{n−1}] with leading coefficient 1 (lexicographic order),
/// assuming no evaluation point is unlucky in a way the leading monomials cannot
/// show; `None` when too many points are unlucky or the points `budget` runs out.
fn brown(f: Field, a: &Image, b: &Image, n: usize, budget: &mut u64) -> Option<Image> {
    if n == 1 {
        let g = f.uni_gcd(to_uni(a), to_uni(b));
        return Some(from_uni(&g));
    }
    // As polynomials in x_0 … x_{n−2} over 𝔽_p[y], y = x_{n−1}.
    let (ca, cb) = (by_last(a), by_last(b));
    let (conta, contb) = (content(f, &ca), content(f, &cb));
    let c = f.uni_gcd(conta.clone(), contb.clone());
    let pa = divide_coefficients(f, &ca, &conta)?;
    let pb = divide_coefficients(f, &cb, &contb)?;
    let (la, lb) = (lead(&pa), lead(&pb));
    let gamma = f.uni_gcd(la.clone(), lb.clone());
    let deg_y = |p: &BTreeMap<Vec<u32>, Uni>| p.values().map(|u| u.len() - 1).max().unwrap_or(0);
    let needed = deg_y(&pa).min(deg_y(&pb)) + gamma.len();
    let mut g: BTreeMap<Vec<u32>, Uni> = BTreeMap::new();
    let mut nodes: Uni = vec![1];
    let mut leading: Option<Vec<u32>> = None;
    let mut count = 0;
    for k in 0..(needed as u64 + SPARE_POINTS) {
        if count == needed {
            break;
        }
        let alpha = point(f, n, k);
        if f.eval(&la, alpha) == 0 || f.eval(&lb, alpha) == 0 {
            continue;
        }
        *budget = budget.checked_sub(1)?;
        let image = brown(f, &at(f, &pa, alpha), &at(f, &pb, alpha), n - 1, budget)?;
        let lm = leading_monomial(&image);
        if lm.iter().all(|&k| k == 0) {
            // The images of the primitive parts are coprime, and degrees never drop
            // at a point that keeps both leading coefficients: the gcd is the content's.
            return Some(monic(f, &from_coefficients(&BTreeMap::from([(lm, c)]))));
        }
        match leading.as_ref().map(|l| lm.cmp(l)) {
            Some(std::cmp::Ordering::Greater) => continue,
            Some(std::cmp::Ordering::Equal) => {}
            None | Some(std::cmp::Ordering::Less) => {
                // The first point, or every earlier one was unlucky.
                g.clear();
                nodes = vec![1];
                count = 0;
                leading = Some(lm);
            }
        }
        // Newton's step: g += (γ(α)·image − g(α)) · nodes / nodes(α).
        let scale = f.eval(&gamma, alpha);
        let inv = f.inverse(f.eval(&nodes, alpha))?;
        let mut keys: Vec<Vec<u32>> = image.keys().cloned().collect();
        keys.extend(g.keys().filter(|k| !image.contains_key(*k)).cloned());
        for k in keys {
            let want = f.mul(scale, image.get(&k).copied().unwrap_or(0));
            let have = g.get(&k).map_or(0, |u| f.eval(u, alpha));
            let step = f.mul(f.sub(want, have), inv);
            if step != 0 {
                let entry = g.entry(k).or_default();
                *entry = f.uni_add(entry, &f.uni_scale(&nodes, step));
            }
        }
        g.retain(|_, u| !u.is_empty());
        nodes = f.uni_mul(&nodes, &[f.sub(0, alpha), 1]);
        count += 1;
    }
    if count < needed || g.is_empty() {
        return None;
    }
    let primitive = divide_coefficients(f, &g, &content(f, &g))?;
    let with_content = primitive
        .into_iter()
        .map(|(k, u)| (k, f.uni_mul(&u, &c)))
        .collect();
    Some(monic(f, &from_coefficients(&with_content)))
}

/// The `k`-th evaluation point of level `n`: pseudo-random residues (splitmix64), so
/// that an unlucky point (a root of a resultant of degree about the inputs' degrees)
/// is as unlikely as degree/p, and the run is deterministic. Small points such as
/// 1, 2, 3 are unlucky for inputs like `x + y` and `x + 1` at `y = 1`.
fn point(f: Field, n: usize, k: u64) -> u64 {
    f.scramble((n as u64).wrapping_mul(0x1000_0000_0000_0001) ^ k)
}

/// The exponents of the lexicographically largest monomial of an image gcd (an
/// unlucky prime or point shows as a larger one than the gcd's).
fn leading_monomial(g: &Image) -> Vec<u32> {
    g.keys()
        .next_back()
        .expect("a gcd of nonzero images")
        .clone()
}

/// `p` as a polynomial in all variables but the last, over 𝔽_P[last].
fn by_last(p: &Image) -> BTreeMap<Vec<u32>, Uni> {
    let mut out: BTreeMap<Vec<u32>, Uni> = BTreeMap::new();
    for (e, &c) in p {
        let (&k, rest) = e.split_last().expect("at least two variables");
        let u = out.entry(rest.to_vec()).or_default();
        let k = k as usize;
        if u.len() <= k {
            u.resize(k + 1, 0);
        }
        u[k] = c;
    }
    out
}

/// The inverse of [`by_last`].
fn from_coefficients(p: &BTreeMap<Vec<u32>, Uni>) -> Image {
    let mut out = Image::new();
    for (rest, u) in p {
        for (k, &c) in u.iter().enumerate() {
            if c != 0 {
                let mut e = rest.clone();
                e.push(k as u32);
                out.insert(e, c);
            }
        }
    }
    out
}

/// The coefficients' gcd in 𝔽_p[y] (monic).
fn content(f: Field, p: &BTreeMap<Vec<u32>, Uni>) -> Uni {
    let mut acc = Vec::new();
    for u in p.values() {
        acc = f.uni_gcd(acc, u.clone());
        if acc.len() == 1 {
            break; // a unit: the usual case
        }
    }
    acc
}

/// Every coefficient divided by `d`; `None` if one does not divide (it always does
/// for a content, but nothing here is trusted to panic).
fn divide_coefficients(
    f: Field,
    p: &BTreeMap<Vec<u32>, Uni>,
    d: &Uni,
) -> Option<BTreeMap<Vec<u32>, Uni>> {
    if d.as_slice() == [1] {
        return Some(p.clone()); // a unit content, the usual case
    }
    p.iter()
        .map(|(k, u)| {
            let (q, r) = f.uni_divrem(u, d)?;
            r.is_empty().then(|| (k.clone(), q))
        })
        .collect()
}

/// The coefficient in 𝔽_p[y] of the lexicographically largest monomial.
fn lead(p: &BTreeMap<Vec<u32>, Uni>) -> Uni {
    p.values().next_back().cloned().unwrap_or_default()
}

/// Every coefficient at y = α: a polynomial in one variable fewer.
fn at(f: Field, p: &BTreeMap<Vec<u32>, Uni>, alpha: u64) -> Image {
    p.iter()
        .filter_map(|(k, u)| {
            let v = f.eval(u, alpha);
            (v != 0).then(|| (k.clone(), v))
        })
        .collect()
}

/// Scaled so that the leading coefficient is 1.
fn monic(f: Field, p: &Image) -> Image {
    let lc = *p.values().next_back().expect("nonzero");
    let inv = f.inverse(lc).expect("a nonzero residue");
    p.iter().map(|(k, &c)| (k.clone(), f.mul(c, inv))).collect()
}

fn to_uni(p: &Image) -> Uni {
    let mut u = Vec::new();
    for (e, &c) in p {
        let k = e[0] as usize;
        if u.len() <= k {
            u.resize(k + 1, 0);
        }
        u[k] = c;
    }
    u
}

fn from_uni(u: &Uni) -> Image {
    u.iter()
        .enumerate()
        .filter(|&(_, &c)| c != 0)
        .map(|(k, &c)| (vec![k as u32], c))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `q`'s residues for the first `primes` primes, combined.
    fn combined(q: &Rational, primes: usize) -> Combined {
        let mut fields = residue::fields();
        let residue = |f: Field| Image::from([(vec![0], f.of_rational(q).unwrap())]);
        let first = fields.next().unwrap();
        let mut c = Combined::new(first, vec![0], &residue(first));
        for f in fields.take(primes - 1) {
            c.add(f, &residue(f));
        }
        c
    }

    #[test]
    fn reconstruction_recovers_fractions_within_the_bound_and_refuses_larger_ones() {
        for (n, d) in [(0, 1), (1, 1), (-3, 7), (22, 15), (-1_000_000, 999_999)] {
            let q = Rational::ratio(n, d).unwrap();
            let c = residue::of_rational(&q).unwrap();
            let m = BigInt::from(residue::P);
            assert_eq!(reconstruct(&BigInt::from(c), &m), Some(q), "{n}/{d}");
        }
        // Beyond one prime's bound (about 1.07·10⁹) a fraction does not come back as
        // itself; two primes recover it.
        let big = Rational::ratio(3_000_000_007, 5).unwrap();
        let one = combined(&big, 1);
        let c = &one.coefficients[&vec![0]];
        assert_ne!(reconstruct(c, &one.modulus), Some(big.clone()));
        let two = combined(&big, 2);
        assert_eq!(
            reconstruct(&two.coefficients[&vec![0]], &two.modulus),
            Some(big)
        );
    }

    /// The Chinese remainder step gives the integer itself once the product of the
    /// primes exceeds it, for either sign; a wrong inverse would not.
    #[test]
    fn residues_combine_to_the_integer() {
        let n: BigInt = "1000000000000000000000000000012345".parse().unwrap();
        for value in [n.clone(), -n.clone()] {
            let q = Rational::from_big(value.clone(), BigInt::one()).unwrap();
            let c = combined(&q, 2);
            let x = &c.coefficients[&vec![0]];
            let symmetric = if x > &(&c.modulus / 2u32) {
                x - &c.modulus
            } else {
                x.clone()
            };
            assert_eq!(symmetric, value);
            // Reconstruction needs a modulus above 2·n² (about 2²²¹): three primes
            // (2¹⁸³) are not enough, four (2²⁴⁴) are.
            let three = combined(&q, 3);
            let four = combined(&q, 4);
            let back = |c: &Combined| reconstruct(&c.coefficients[&vec![0]], &c.modulus);
            assert_ne!(back(&three), Some(q.clone()));
            assert_eq!(back(&four), Some(q.clone()));
        }
    }
}
