//! A candidate gcd of two polynomials over ℚ from their images mod P (Brown's dense
//! modular algorithm with one prime; Geddes, Czapor & Labahn, ch. 7), for
//! [`super::gcd::gcd`].
//!
//! The primitive remainder sequence over ℚ swells: the gcd of two products `g·a`,
//! `g·b` of five-term polynomials in three variables took minutes. Over 𝔽_P the
//! coefficients stay one word, and the variables are removed one at a time by
//! evaluation and interpolation.
//!
//! Nothing here is trusted. The image is lifted to ℚ by rational reconstruction and
//! returned as a *candidate*; the caller accepts it only when it divides both inputs
//! exactly over ℚ and the cofactors are proved coprime, which makes it the gcd
//! whatever happened here. An unlucky prime or evaluation point, a coefficient too
//! large to reconstruct, or an input out of range gives `None` or a candidate that
//! fails the check, and the caller falls back to the remainder sequence.

use super::poly::{Monomial, Poly, Var};
use super::rational::Rational;
use super::residue::{
    self, eval, scramble, sub, uni_add, uni_divrem, uni_gcd, uni_mul, uni_scale, Uni, P,
};
use std::collections::BTreeMap;

/// A polynomial over 𝔽_P in `n` variables: exponent vectors (variable 0 most
/// significant, so the map's order is lexicographic) to nonzero residues.
type Image = BTreeMap<Vec<u32>, u64>;

/// The most variables, and the highest degree in any one, tried: the work grows as
/// the product of the degrees, and beyond these the caller's exact route decides.
const MAX_VARS: usize = 8;
const MAX_DEGREE: u32 = 64;

/// The evaluation points one candidate may use, over every level of the recursion
/// (their number is the product of the degrees).
const POINT_BUDGET: u64 = 100_000;

/// Evaluation points tried beyond those needed, per level, before giving up: those
/// where a leading coefficient vanishes, and unlucky ones, where the image gcd has a
/// larger leading monomial than the gcd's image.
const SPARE_POINTS: u64 = 16;

/// A candidate for gcd(a, b) of two nonzero ordinary polynomials, with leading
/// coefficient 1; `None` when the modular route cannot produce one (see the module
/// doc). The caller must check it.
pub(super) fn candidate(a: &Poly, b: &Poly) -> Option<Poly> {
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
    let (ia, ib) = (image(a, &vars)?, image(b, &vars)?);
    let mut budget = POINT_BUDGET;
    let g = brown(&ia, &ib, vars.len(), &mut budget)?;
    lift(&g, &vars)
}

/// The image of `p` mod P over `vars`; `None` for a negative or too high exponent or
/// a denominator that P divides.
fn image(p: &Poly, vars: &[Var]) -> Option<Image> {
    let mut out = Image::new();
    for (m, c) in p.terms() {
        let mut e = vec![0u32; vars.len()];
        for &(v, k) in m.factors() {
            let k = u32::try_from(k).ok().filter(|&k| k <= MAX_DEGREE)?;
            e[vars.binary_search(&v).ok()?] = k;
        }
        let r = residue::of_rational(c)?;
        if r != 0 {
            out.insert(e, r);
        }
    }
    (!out.is_empty()).then_some(out)
}

/// The polynomial over ℚ whose coefficients reconstruct those of `g`.
fn lift(g: &Image, vars: &[Var]) -> Option<Poly> {
    let mut terms = Vec::with_capacity(g.len());
    for (e, &c) in g {
        let factors = vars
            .iter()
            .zip(e)
            .filter(|&(_, &k)| k > 0)
            .map(|(&v, &k)| Some((v, i32::try_from(k).ok()?)))
            .collect::<Option<Vec<_>>>()?;
        terms.push((Monomial::from_factors(factors), reconstruct(c)?));
    }
    Some(Poly::from_terms(terms))
}

/// The rational `r/s` with |r|, s ≤ √(P/2) and `r ≡ c·s` mod P, when there is one
/// (Wang's rational reconstruction by the extended Euclidean algorithm); it is then
/// unique.
fn reconstruct(c: u64) -> Option<Rational> {
    let bound = i128::from((P / 2).isqrt());
    let (mut r0, mut r1) = (i128::from(P), i128::from(c));
    let (mut s0, mut s1) = (0i128, 1i128);
    while r1 > bound {
        let q = r0 / r1;
        (r0, r1) = (r1, r0 - q * r1);
        (s0, s1) = (s1, s0 - q * s1);
    }
    if s1 == 0 || s1.abs() > bound {
        return None;
    }
    let (n, d) = if s1 < 0 { (-r1, -s1) } else { (r1, s1) };
    Rational::ratio(i64::try_from(n).ok()?, i64::try_from(d).ok()?)
}

/// gcd(a, b) in 𝔽_P[x_0 … x_{n−1}] with leading coefficient 1 (lexicographic order),
/// assuming no evaluation point is unlucky in a way the leading monomials cannot
/// show; `None` when too many points are unlucky or the points `budget` runs out.
fn brown(a: &Image, b: &Image, n: usize, budget: &mut u64) -> Option<Image> {
    if n == 1 {
        let g = uni_gcd(to_uni(a), to_uni(b));
        return Some(from_uni(&g));
    }
    // As polynomials in x_0 … x_{n−2} over 𝔽_P[y], y = x_{n−1}.
    let (ca, cb) = (by_last(a), by_last(b));
    let (conta, contb) = (content(&ca), content(&cb));
    let c = uni_gcd(conta.clone(), contb.clone());
    let pa = divide_coefficients(&ca, &conta)?;
    let pb = divide_coefficients(&cb, &contb)?;
    let (la, lb) = (lead(&pa), lead(&pb));
    let gamma = uni_gcd(la.clone(), lb.clone());
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
        let alpha = point(n, k);
        if eval(&la, alpha) == 0 || eval(&lb, alpha) == 0 {
            continue;
        }
        *budget = budget.checked_sub(1)?;
        let image = brown(&at(&pa, alpha), &at(&pb, alpha), n - 1, budget)?;
        let lm = image
            .keys()
            .next_back()
            .expect("a gcd of nonzero images")
            .clone();
        if lm.iter().all(|&k| k == 0) {
            // The images of the primitive parts are coprime, and degrees never drop
            // at a point that keeps both leading coefficients: the gcd is the content's.
            return Some(monic(&from_coefficients(&BTreeMap::from([(lm, c)]))));
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
        let scale = eval(&gamma, alpha);
        let inv = residue::inverse(eval(&nodes, alpha))?;
        let mut keys: Vec<Vec<u32>> = image.keys().cloned().collect();
        keys.extend(g.keys().filter(|k| !image.contains_key(*k)).cloned());
        for k in keys {
            let want = residue::mul(scale, image.get(&k).copied().unwrap_or(0));
            let have = g.get(&k).map_or(0, |u| eval(u, alpha));
            let step = residue::mul(sub(want, have), inv);
            if step != 0 {
                let entry = g.entry(k).or_default();
                *entry = uni_add(entry, &uni_scale(&nodes, step));
            }
        }
        g.retain(|_, u| !u.is_empty());
        nodes = uni_mul(&nodes, &[(P - alpha) % P, 1]);
        count += 1;
    }
    if count < needed || g.is_empty() {
        return None;
    }
    let primitive = divide_coefficients(&g, &content(&g))?;
    let with_content = primitive
        .into_iter()
        .map(|(k, u)| (k, uni_mul(&u, &c)))
        .collect();
    Some(monic(&from_coefficients(&with_content)))
}

/// The `k`-th evaluation point of level `n`: pseudo-random residues (splitmix64), so
/// that an unlucky point (a root of a resultant of degree about the inputs' degrees)
/// is as unlikely as degree/P, and the run is deterministic. Small points such as
/// 1, 2, 3 are unlucky for inputs like `x + y` and `x + 1` at `y = 1`.
fn point(n: usize, k: u64) -> u64 {
    scramble((n as u64).wrapping_mul(0x1000_0000_0000_0001) ^ k)
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

/// The coefficients' gcd in 𝔽_P[y] (monic).
fn content(p: &BTreeMap<Vec<u32>, Uni>) -> Uni {
    let mut acc = Vec::new();
    for u in p.values() {
        acc = uni_gcd(acc, u.clone());
        if acc.len() == 1 {
            break; // a unit: the usual case
        }
    }
    acc
}

/// Every coefficient divided by `d`; `None` if one does not divide (it always does
/// for a content, but nothing here is trusted to panic).
fn divide_coefficients(p: &BTreeMap<Vec<u32>, Uni>, d: &Uni) -> Option<BTreeMap<Vec<u32>, Uni>> {
    p.iter()
        .map(|(k, u)| {
            let (q, r) = uni_divrem(u, d)?;
            r.is_empty().then(|| (k.clone(), q))
        })
        .collect()
}

/// The coefficient in 𝔽_P[y] of the lexicographically largest monomial.
fn lead(p: &BTreeMap<Vec<u32>, Uni>) -> Uni {
    p.values().next_back().cloned().unwrap_or_default()
}

/// Every coefficient at y = α: a polynomial in one variable fewer.
fn at(p: &BTreeMap<Vec<u32>, Uni>, alpha: u64) -> Image {
    p.iter()
        .filter_map(|(k, u)| {
            let v = eval(u, alpha);
            (v != 0).then(|| (k.clone(), v))
        })
        .collect()
}

/// Scaled so that the leading coefficient is 1.
fn monic(p: &Image) -> Image {
    let lc = *p.values().next_back().expect("nonzero");
    let inv = residue::inverse(lc).expect("a nonzero residue");
    p.iter()
        .map(|(k, &c)| (k.clone(), residue::mul(c, inv)))
        .collect()
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

    #[test]
    fn reconstruction_recovers_small_fractions_and_refuses_large_ones() {
        for (n, d) in [(0, 1), (1, 1), (-3, 7), (22, 15), (-1_000_000, 999_999)] {
            let q = Rational::ratio(n, d).unwrap();
            let c = residue::of_rational(&q).unwrap();
            assert_eq!(reconstruct(c), Some(q), "{n}/{d}");
        }
        // A residue of a fraction beyond the bound does not come back as itself.
        let big = Rational::ratio(3_000_000_007, 5).unwrap();
        let c = residue::of_rational(&big).unwrap();
        assert_ne!(reconstruct(c), Some(big));
    }
}
