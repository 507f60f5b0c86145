//! Exact witnesses of existential statements: "the locus of (x, y) over all
//! orientations of the normal is not a circle" is proved by one rational state and four
//! rational normals whose points lie on no common circle or line.
//!
//! Four points lie on a common circle or line iff
//! det [x_k² + y_k², x_k, y_k, 1]_{k=1..4} = 0; a nonzero determinant, computed in exact
//! rationals, is the proof.

use super::eval::ExactEnv;
use super::{Method, Outcome};
use crate::derivation::{Check, Strategy, Verdict};
use crate::kernel::{Poly, Rational, Var};
use crate::lang::{Decls, Diagnostic};
use std::collections::BTreeMap;

/// States tried before giving up.
const ATTEMPTS: usize = 64;

/// The determinant of a square matrix of rationals (Gaussian elimination, exact).
pub fn determinant(mut m: Vec<Vec<Rational>>) -> Rational {
    let n = m.len();
    let mut det = Rational::int(1);
    for col in 0..n {
        let Some(pivot) = (col..n).find(|&r| !m[r][col].is_zero()) else {
            return Rational::int(0);
        };
        if pivot != col {
            m.swap(pivot, col);
            det = -det;
        }
        det = &det * &m[col][col];
        let inv = m[col][col].recip().expect("pivot is nonzero");
        for r in col + 1..n {
            let factor = &m[r][col] * &inv;
            if factor.is_zero() {
                continue;
            }
            let pivot_row = m[col].clone();
            for (target, p) in m[r].iter_mut().zip(&pivot_row).skip(col) {
                *target = &*target - &(&factor * p);
            }
        }
    }
    det
}

/// A rational point of the unit circle: ((1 − u²), 2u)/(1 + u²).
fn circle_point(u: &Rational) -> (Rational, Rational) {
    let one = Rational::int(1);
    let s = &(u * u) + &one;
    let x = (&one - &(u * u)).checked_div(&s).expect("1 + u² > 0");
    let y = (&Rational::int(2) * u).checked_div(&s).expect("1 + u² > 0");
    (x, y)
}

/// Decides a `strategy = "not-circle"` check.
pub fn decide_not_circle(decls: &Decls, check: &Check) -> Result<Outcome, Diagnostic> {
    let Strategy::NotCircle { x, y } = &check.strategy else {
        unreachable!("dispatched on the strategy")
    };
    let mut env = ExactEnv::new(decls, &check.defs, &check.assumptions)?;
    let px = env
        .eval(&x.node, &x.origin)?
        .tensor
        .into_scalar()
        .expect("validated: scalar");
    let py = env
        .eval(&y.node, &y.origin)?
        .tensor
        .into_scalar()
        .expect("validated: scalar");
    let normal: Vec<Var> = env.normal_vars().to_vec();
    if normal.len() != 2 {
        return Err(x
            .origin
            .diagnostic(x.node.span, "not-circle needs the normal in a plane")
            .with_help("use dimension = 2, or normal_in_plane = true"));
    }
    let mut used: Vec<Var> = px
        .terms()
        .chain(py.terms())
        .flat_map(|(m, _)| m.factors().iter().map(|&(v, _)| v))
        .filter(|v| !normal.contains(v))
        .collect();
    used.sort_unstable();
    used.dedup();
    let us: Vec<Rational> = [(0, 1), (1, 2), (2, 1), (-1, 3)]
        .iter()
        .map(|&(a, b)| Rational::ratio(a, b).expect("nonzero"))
        .collect();
    let mut seed: u64 = 0x9E37_79B9;
    let mut small = || {
        seed = seed
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        ((seed >> 33) % 7) as i64 - 3
    };
    for _ in 0..ATTEMPTS {
        let state: BTreeMap<Var, Rational> =
            used.iter().map(|&v| (v, Rational::int(small()))).collect();
        let mut points = Vec::new();
        for u in &us {
            let (n1, n2) = circle_point(u);
            let at = |v: Var| {
                if v == normal[0] {
                    n1.clone()
                } else if v == normal[1] {
                    n2.clone()
                } else {
                    state.get(&v).cloned().unwrap_or_else(|| Rational::int(0))
                }
            };
            let value = |p: &Poly| p.eval(&at);
            match (value(&px), value(&py)) {
                (Some(a), Some(b)) => points.push((a, b)),
                _ => break,
            }
        }
        if points.len() < 4 {
            continue;
        }
        let rows = points
            .iter()
            .map(|(a, b)| vec![&(a * a) + &(b * b), a.clone(), b.clone(), Rational::int(1)])
            .collect();
        let det = determinant(rows);
        if !det.is_zero() {
            let names: Vec<String> = state
                .iter()
                .filter(|(_, q)| !q.is_zero())
                .map(|(&v, q)| format!("{}={q}", env.vars.name(v)))
                .collect();
            let pts: Vec<String> = points.iter().map(|(a, b)| format!("({a}, {b})")).collect();
            return Ok(Outcome::new(Verdict::Holds, Method::Witness, 1).with_detail(format!(
                    "witness: at {} (other variables 0) and n = ((1−u²), 2u)/(1+u²) for u = 0, 1/2, 2, −1/3, the points (x, y) = {} lie on no common circle or line: det[x²+y², x, y, 1] = {det}",
                    names.join(", "),
                    pts.join(", ")
                )));
        }
    }
    Ok(
        Outcome::new(Verdict::Fails, Method::Witness, ATTEMPTS).with_detail(format!(
            "no witness among {ATTEMPTS} rational states: every four points tried were concyclic"
        )),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(a: i64) -> Rational {
        Rational::int(a)
    }

    #[test]
    fn determinant_is_exact() {
        assert_eq!(determinant(vec![vec![q(2), q(1)], vec![q(1), q(3)]]), q(5));
        assert_eq!(determinant(vec![vec![q(0), q(1)], vec![q(1), q(0)]]), q(-1));
        assert_eq!(determinant(vec![vec![q(1), q(2)], vec![q(2), q(4)]]), q(0));
    }

    #[test]
    fn concyclic_points_give_zero() {
        // Four points of the unit circle, and three of them with one off it.
        let pts: Vec<(Rational, Rational)> = [(0, 1), (1, 2), (2, 1), (-1, 3)]
            .iter()
            .map(|&(a, b)| circle_point(&Rational::ratio(a, b).unwrap()))
            .collect();
        let row =
            |(a, b): &(Rational, Rational)| vec![&(a * a) + &(b * b), a.clone(), b.clone(), q(1)];
        assert!(determinant(pts.iter().map(row).collect()).is_zero());
        let mut off = pts.clone();
        off[3] = (q(2), q(0));
        assert!(!determinant(off.iter().map(row).collect()).is_zero());
    }
}
