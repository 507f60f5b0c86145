//! Exact witnesses of existential statements: "the locus of (x, y) over all
//! orientations of the normal is not a circle" is proved by one rational state and four
//! rational normals whose points lie on no common circle or line.
//!
//! Four points lie on a common circle or line iff
//! det [x_k² + y_k², x_k, y_k, 1]_{k=1..4} = 0; a nonzero determinant, computed in exact
//! rationals, is the proof.

use super::finding::Finding;
use super::outcome::{Method, Outcome};
use crate::algebra::certificate::{Certificate, Fact};
use crate::algebra::{Quotient, RatFunc};
use crate::derivation::{Check, Strategy};
use crate::eval::exact::env::ExactEnv;
use crate::kernel::{Rational, Var};
use crate::lang::{Decls, Diagnostic};
use std::collections::BTreeMap;

/// States tried before giving up.
const ATTEMPTS: usize = 64;

/// A rational point of the unit circle: ((1 − u²), 2u)/(1 + u²).
fn circle_point(u: &Rational) -> (Rational, Rational) {
    let p = super::points::stereographic(std::slice::from_ref(u), false);
    (p[0].clone(), p[1].clone())
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
        .variables()
        .into_iter()
        .chain(py.variables())
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
            let value = |p: &Quotient| p.eval(&at);
            match (value(&px), value(&py)) {
                (Some(a), Some(b)) => points.push((a, b)),
                _ => break,
            }
        }
        if points.len() < 4 {
            continue;
        }
        let points: [(Rational, Rational); 4] = points.try_into().expect("four points");
        if let Some(certificate) = Certificate::not_concyclic(&points) {
            let det = match certificate.facts() {
                [Fact::NotConcyclic { determinant }] => determinant.clone(),
                _ => unreachable!("one fact"),
            };
            // The kernel evaluates the locus at the state and the four normals itself.
            let statement =
                crate::derivation::statement::not_circle(decls, check, &x.node, &y.node)?;
            let fact = crate::kernel::check::Fact::NotConcyclic {
                point: super::identity::full_point(&env, &state),
                us: us.clone(),
                roots: env.root_data(),
            };
            let proof = match crate::kernel::check::check(statement, fact) {
                Ok(p) => p,
                Err(why) => {
                    return Ok(Outcome::undecided(Method::Witness, 1).with_finding(
                        Finding::KernelRefused {
                            why: why.to_string(),
                        },
                    ))
                }
            };
            let state = state
                .iter()
                .filter(|(_, q)| !q.is_zero())
                .map(|(&v, q)| (env.vars.name(v).to_owned(), q.to_string()))
                .collect();
            let points = points
                .iter()
                .map(|(a, b)| (a.to_string(), b.to_string()))
                .collect();
            return Ok(
                Outcome::proved(Method::Witness, 1, proof).with_finding(Finding::Witness {
                    state,
                    points,
                    determinant: det,
                }),
            );
        }
    }
    // No witness: perhaps the locus is a circle. The circle through three of its points,
    // as rational functions of the state, goes to the kernel, which checks it on the
    // whole locus; refused, it proves nothing either way.
    if let Some(circle) = circle_through(&px, &py, &normal) {
        let statement = crate::derivation::statement::not_circle(decls, check, &x.node, &y.node)?;
        let names = &env.vars;
        let data = |f: &RatFunc| {
            (
                crate::kernel::statement::poly_data(f.numerator(), names),
                crate::kernel::statement::poly_data(f.denominator(), names),
            )
        };
        let fact = crate::kernel::check::Fact::OnCircle {
            circle: [data(&circle[0]), data(&circle[1]), data(&circle[2])],
            roots: env.root_data(),
        };
        if let Ok(proof) = crate::kernel::check::check(statement, fact) {
            let finding = match proof.summary().iter().find_map(|c| match c {
                crate::kernel::check::Checked::OnCircle {
                    center,
                    radius_squared,
                } => Some((center.clone(), radius_squared.clone())),
                _ => None,
            }) {
                Some((center, radius_squared)) => Finding::OnCircle {
                    center,
                    radius_squared,
                },
                None => Finding::NoWitness { attempts: ATTEMPTS },
            };
            return Ok(Outcome::proved(Method::Witness, 1, proof).with_finding(finding));
        }
    }
    // Not finding a witness proves nothing about the statement.
    Ok(Outcome::undecided(Method::Witness, ATTEMPTS)
        .with_finding(Finding::NoWitness { attempts: ATTEMPTS }))
}

/// The circle x² + y² + D x + E y + F = 0 through the locus at three normals, its
/// coefficients [D, E, F] as rational functions of the state (Cramer's rule). The
/// normals are at angles whose doubles differ too (a locus quadratic in n takes the
/// same point at n and −n); `None` when every triple tried is collinear or undefined.
fn circle_through(px: &Quotient, py: &Quotient, normal: &[Var]) -> Option<[RatFunc; 3]> {
    [[0, 1, 2], [0, 2, 3], [1, 2, 3]].into_iter().find_map(|t| {
        circle_at(
            px,
            py,
            normal,
            t.map(|k| [(0, 1), (1, 1), (1, 2), (1, 3)][k]),
        )
    })
}

/// [`circle_through`] at the normals ((1 − u²), 2u)/(1 + u²) for u = a/b of each pair.
fn circle_at(
    px: &Quotient,
    py: &Quotient,
    normal: &[Var],
    us: [(i64, i64); 3],
) -> Option<[RatFunc; 3]> {
    let (x, y) = (px.to_ratfunc(), py.to_ratfunc());
    let point = |(a, b): (i64, i64)| -> Option<[RatFunc; 2]> {
        let (n1, n2) = circle_point(&Rational::ratio(a, b)?);
        let at = |v: Var| {
            if v == normal[0] {
                Some(n1.clone())
            } else if v == normal[1] {
                Some(n2.clone())
            } else {
                None
            }
        };
        Some([x.fix(&at)?, y.fix(&at)?])
    };
    let points = [point(us[0])?, point(us[1])?, point(us[2])?];
    let one = RatFunc::int(1);
    // Rows [x, y, 1 | −(x² + y²)].
    let rows: Vec<[RatFunc; 4]> = points
        .iter()
        .map(|[a, b]| {
            let rhs = -(&(&(a * a) + &(b * b)));
            [a.clone(), b.clone(), one.clone(), rhs]
        })
        .collect();
    let det3 = |c: [usize; 3]| -> RatFunc {
        let m = |r: usize, k: usize| &rows[r][c[k]];
        let minor = |r1: usize, r2: usize, k1: usize, k2: usize| {
            &(m(r1, k1) * m(r2, k2)) - &(m(r1, k2) * m(r2, k1))
        };
        &(&(m(0, 0) * &minor(1, 2, 1, 2)) - &(m(0, 1) * &minor(1, 2, 0, 2)))
            + &(m(0, 2) * &minor(1, 2, 0, 1))
    };
    let det = det3([0, 1, 2]);
    if det.is_zero() {
        return None;
    }
    let solve = |c: [usize; 3]| &det3(c) / &det;
    Some([solve([3, 1, 2])?, solve([0, 3, 2])?, solve([0, 1, 3])?])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn circle_points_lie_on_the_unit_circle() {
        // Four of them are concyclic (no witness); moving one off the circle gives one.
        let mut pts: [(Rational, Rational); 4] = [(0, 1), (1, 2), (2, 1), (-1, 3)]
            .map(|(a, b)| circle_point(&Rational::ratio(a, b).unwrap()));
        for (x, y) in &pts {
            assert_eq!(&(x * x) + &(y * y), Rational::int(1));
        }
        assert!(Certificate::not_concyclic(&pts).is_none());
        pts[3] = (Rational::int(2), Rational::int(0));
        assert!(Certificate::not_concyclic(&pts).is_some());
    }
}
