//! Exact affine systems over ℚ, solved once into a parametrisation.
//!
//! Assumptions on components (`symmetric`, `traceless`, `sigma_13 = 0`, `C_ijkl =
//! C_klij`, …) are affine equations. Applying them one after another, as rewrites,
//! depends on their order: a later `eta_12 = 0` does not reach the mirror component a
//! earlier `symmetric(eta)` already copied. Solved together, they have one solution set
//! whatever the order, and a contradiction is found instead of silently ignored.
//!
//! The solver brings the system to reduced row echelon form, whose pivot columns are
//! the unique leftmost ones; so the caller chooses which unknowns are eliminated by
//! ordering the columns, and the result does not depend on the order of the equations.
//! Every row remembers which equations it was combined from, so an inconsistency names
//! the equations that clash.

use crate::kernel::Rational;
use num_traits::Zero;
use std::collections::{BTreeMap, BTreeSet};

/// `Σ coeffs[c]·x_c + constant = 0`, from the caller's equation number `source`.
#[derive(Clone, Debug, PartialEq)]
pub struct AffineEquation {
    pub coeffs: BTreeMap<usize, Rational>,
    pub constant: Rational,
    pub source: usize,
}

/// `Σ terms·x + constant`: the value of an eliminated unknown in the free ones.
#[derive(Clone, Debug, PartialEq)]
pub struct Affine {
    pub terms: Vec<(usize, Rational)>,
    pub constant: Rational,
}

impl Affine {
    /// Evaluates at the free unknowns' values.
    pub fn eval(&self, free: impl Fn(usize) -> Rational) -> Rational {
        self.terms
            .iter()
            .fold(self.constant.clone(), |acc, (c, q)| &acc + &(q * &free(*c)))
    }
}

/// The equations (by `source`) whose combination reads `0 = nonzero`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Inconsistent {
    pub sources: Vec<usize>,
}

/// The solution set of a consistent system: each unknown is free or an affine
/// function of the free ones.
#[derive(Clone, Debug, PartialEq)]
pub struct Solution {
    /// `None` for a free unknown.
    values: Vec<Option<Affine>>,
}

impl Solution {
    /// The value of unknown `c` in the free unknowns (`None`: `c` is free).
    pub fn dependent(&self, c: usize) -> Option<&Affine> {
        self.values.get(c).and_then(Option::as_ref)
    }

    pub fn is_free(&self, c: usize) -> bool {
        self.dependent(c).is_none()
    }

    /// The value of every unknown, given the free ones' values.
    pub fn complete(&self, free: impl Fn(usize) -> Rational) -> Vec<Rational> {
        (0..self.values.len())
            .map(|c| match &self.values[c] {
                None => free(c),
                Some(a) => a.eval(&free),
            })
            .collect()
    }
}

struct Row {
    coeffs: BTreeMap<usize, Rational>,
    constant: Rational,
    sources: BTreeSet<usize>,
}

impl Row {
    /// self −= factor·other, removing the entries that cancel.
    fn subtract(&mut self, factor: &Rational, other: &Row) {
        for (c, q) in &other.coeffs {
            let entry = self.coeffs.entry(*c).or_insert_with(Rational::zero);
            *entry = &*entry - &(factor * q);
            if entry.is_zero() {
                self.coeffs.remove(c);
            }
        }
        self.constant = &self.constant - &(factor * &other.constant);
        self.sources.extend(other.sources.iter().copied());
    }
}

/// Solves `equations` in `columns` unknowns. Lower column numbers are eliminated
/// first: the pivot of each row is its leftmost unknown.
pub fn solve(columns: usize, equations: &[AffineEquation]) -> Result<Solution, Inconsistent> {
    // Reduced rows, each with its pivot: the pivot column occurs in no other row, and it
    // is the row's leftmost column. Inserting a row keeps both, so the end result is the
    // reduced row echelon form, which is unique: independent of the equations' order.
    let mut rows: Vec<(usize, Row)> = Vec::new();
    for eq in equations {
        let mut row = Row {
            coeffs: eq
                .coeffs
                .iter()
                .filter(|(_, q)| !q.is_zero())
                .map(|(c, q)| (*c, q.clone()))
                .collect(),
            constant: eq.constant.clone(),
            sources: BTreeSet::from([eq.source]),
        };
        for (pivot, pivot_row) in &rows {
            if let Some(q) = row.coeffs.get(pivot).cloned() {
                row.subtract(&q, pivot_row);
            }
        }
        let Some((&pivot, lead)) = row.coeffs.iter().next() else {
            if row.constant.is_zero() {
                continue;
            }
            return Err(Inconsistent {
                sources: row.sources.into_iter().collect(),
            });
        };
        let scale = lead.recip().expect("nonzero entries only");
        for q in row.coeffs.values_mut() {
            *q = &*q * &scale;
        }
        row.constant = &row.constant * &scale;
        for (_, other) in rows.iter_mut() {
            if let Some(q) = other.coeffs.get(&pivot).cloned() {
                other.subtract(&q, &row);
            }
        }
        rows.push((pivot, row));
    }
    let mut values = vec![None; columns];
    for (pivot, row) in rows {
        let terms = row
            .coeffs
            .iter()
            .filter(|(c, _)| **c != pivot)
            .map(|(c, q)| (*c, -q.clone()))
            .collect();
        values[pivot] = Some(Affine {
            terms,
            constant: -row.constant,
        });
    }
    Ok(Solution { values })
}

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

#[cfg(test)]
mod tests {
    use super::*;

    fn qi(a: i64) -> Rational {
        Rational::int(a)
    }

    fn eq(source: usize, coeffs: &[(usize, i64)], constant: i64) -> AffineEquation {
        AffineEquation {
            coeffs: coeffs.iter().map(|&(c, q)| (c, Rational::int(q))).collect(),
            constant: Rational::int(constant),
            source,
        }
    }

    #[test]
    fn mirror_of_a_fixed_component_is_fixed_in_either_order() {
        // x0 = eta_21, x1 = eta_12: symmetric (x0 − x1 = 0) and eta_12 = 0 (x1 = 0).
        let a = [eq(0, &[(0, 1), (1, -1)], 0), eq(1, &[(1, 1)], 0)];
        let b = [a[1].clone(), a[0].clone()];
        let (sa, sb) = (solve(2, &a).unwrap(), solve(2, &b).unwrap());
        assert_eq!(sa, sb);
        assert_eq!(sa.complete(|_| Rational::int(7)), vec![Rational::int(0); 2]);
    }

    #[test]
    fn leftmost_columns_are_eliminated() {
        // x0 + x1 + x2 = 0 (traceless, x0 the last diagonal component): x0 = −x1 − x2.
        let s = solve(3, &[eq(0, &[(0, 1), (1, 1), (2, 1)], 0)]).unwrap();
        assert!(s.is_free(1) && s.is_free(2));
        let a = s.dependent(0).unwrap();
        assert_eq!(
            a.terms,
            vec![(1, Rational::int(-1)), (2, Rational::int(-1))]
        );
    }

    #[test]
    fn contradiction_names_exactly_the_clashing_equations() {
        // x0 = 5 (source 3), x0 + x1 = 0 (source 4, unrelated), x0 = 0 (source 7).
        let e = solve(
            2,
            &[
                eq(3, &[(0, 1)], -5),
                eq(4, &[(1, 1), (0, 1)], 0),
                eq(7, &[(0, 2)], 0),
            ],
        )
        .unwrap_err();
        assert_eq!(e.sources, vec![3, 7]);
    }

    #[test]
    fn redundant_equations_are_accepted() {
        let s = solve(
            2,
            &[eq(0, &[(0, 1), (1, -1)], 0), eq(1, &[(0, 2), (1, -2)], 0)],
        );
        assert!(s.unwrap().is_free(1));
    }

    #[test]
    fn every_order_gives_the_same_solution() {
        // A 4-unknown system with a one-dimensional solution set, in all 24 orders.
        let eqs = [
            eq(0, &[(0, 1), (2, -1)], 0),
            eq(1, &[(1, 2), (3, 1)], -1),
            eq(2, &[(0, 1), (1, 1), (2, 1)], 0),
            eq(3, &[(0, 3), (1, 1), (2, -1), (3, 1)], -1),
        ];
        let reference = solve(4, &eqs).unwrap();
        for perm in itertools::Itertools::permutations(0..4, 4) {
            let permuted: Vec<_> = perm.iter().map(|&k| eqs[k].clone()).collect();
            assert_eq!(solve(4, &permuted).unwrap(), reference, "{perm:?}");
        }
        // And the solution satisfies every equation at arbitrary free values.
        let x = reference.complete(|c| Rational::int(c as i64 * 3 - 2));
        for e in &eqs {
            let lhs = e
                .coeffs
                .iter()
                .fold(e.constant.clone(), |acc, (c, q)| &acc + &(q * &x[*c]));
            assert!(lhs.is_zero());
        }
    }

    #[test]
    fn determinant_is_exact() {
        assert_eq!(
            determinant(vec![vec![qi(2), qi(1)], vec![qi(1), qi(3)]]),
            qi(5)
        );
        assert_eq!(
            determinant(vec![vec![qi(0), qi(1)], vec![qi(1), qi(0)]]),
            qi(-1)
        );
        assert_eq!(
            determinant(vec![vec![qi(1), qi(2)], vec![qi(2), qi(4)]]),
            qi(0)
        );
    }
}
