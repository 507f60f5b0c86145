//! Dense matrices of any ring's values, and the division-free linear algebra that the
//! matrix language needs: products, transposes, determinants and adjugates.
//!
//! Everything here only adds, multiplies and negates, so it runs unchanged in every
//! arithmetic the walk knows: canonical polynomials and quotients (exact), `f64` and
//! num-dual numbers (sampled), and op ids of the tape compiler. An inverse or a linear
//! solve is `adj(A) / det(A)`; the one division is the caller's, after it has decided
//! that det(A) is not zero, so a singular system is reported and never divided by.
//!
//! The determinant is Laplace's expansion along the rows with every minor of the
//! lower rows memoised by its column set: n·2ⁿ⁻¹ products instead of n!, with no pivot
//! and therefore no zero test that would depend on the arithmetic.

use super::einsum::Arithmetic;

/// Largest side of a matrix the language accepts: a determinant costs n·2ⁿ⁻¹ products
/// and an adjugate n² determinants of side n − 1.
pub const MAX_SIDE: usize = 12;

/// Negation, the one operation a determinant needs beyond [`Arithmetic`].
pub trait Signed: Arithmetic {
    fn negate(&mut self, x: Self::Value) -> Self::Value;
}

/// A dense `rows × cols` matrix, stored row by row. Indices are 0-based in code and
/// 1-based in everything shown to a user.
#[derive(Clone, Debug, PartialEq)]
pub struct Matrix<T> {
    rows: usize,
    cols: usize,
    data: Vec<T>,
}

impl<T> Matrix<T> {
    /// Builds a matrix from its entries, `f(row, col)`.
    pub fn from_fn(rows: usize, cols: usize, mut f: impl FnMut(usize, usize) -> T) -> Self {
        let data = (0..rows * cols).map(|k| f(k / cols, k % cols)).collect();
        Matrix { rows, cols, data }
    }

    /// A matrix from its entries row by row; `None` if their number is not rows·cols.
    pub fn from_rows(rows: usize, cols: usize, data: Vec<T>) -> Option<Self> {
        (data.len() == rows * cols).then_some(Matrix { rows, cols, data })
    }

    pub fn rows(&self) -> usize {
        self.rows
    }

    pub fn cols(&self) -> usize {
        self.cols
    }

    pub fn get(&self, row: usize, col: usize) -> &T {
        assert!(
            row < self.rows && col < self.cols,
            "entry outside the matrix"
        );
        &self.data[row * self.cols + col]
    }

    /// The entries row by row.
    pub fn entries(&self) -> &[T] {
        &self.data
    }

    pub fn into_entries(self) -> Vec<T> {
        self.data
    }

    pub fn is_square(&self) -> bool {
        self.rows == self.cols
    }
}

impl<T: Clone> Matrix<T> {
    pub fn transpose(&self) -> Matrix<T> {
        Matrix::from_fn(self.cols, self.rows, |i, j| self.get(j, i).clone())
    }
}

/// `a · b`; the caller has checked that `a.cols() == b.rows()`.
pub fn product<A: Arithmetic>(
    ar: &mut A,
    a: &Matrix<A::Value>,
    b: &Matrix<A::Value>,
) -> Result<Matrix<A::Value>, A::Error> {
    assert_eq!(a.cols, b.rows, "a product of non-conforming matrices");
    let mut data = Vec::with_capacity(a.rows * b.cols);
    for i in 0..a.rows {
        for j in 0..b.cols {
            let mut acc = ar.zero();
            for k in 0..a.cols {
                let (x, y) = (a.get(i, k), b.get(k, j));
                if ar.is_exact_zero(x) || ar.is_exact_zero(y) {
                    continue;
                }
                let p = ar.mul(x.clone(), y)?;
                acc = ar.add(acc, p)?;
            }
            data.push(acc);
        }
    }
    Ok(Matrix {
        rows: a.rows,
        cols: b.cols,
        data,
    })
}

/// det(a) of a square matrix by Laplace expansion with memoised minors (see the module
/// documentation). The determinant of the 0×0 matrix is 1.
pub fn determinant<A: Signed>(ar: &mut A, a: &Matrix<A::Value>) -> Result<A::Value, A::Error> {
    assert!(a.is_square(), "the determinant of a non-square matrix");
    let rows: Vec<usize> = (0..a.rows).collect();
    let cols: Vec<usize> = (0..a.cols).collect();
    minor(ar, a, &rows, &cols)
}

/// The determinant of the submatrix of `a` on the given rows and columns (as many of
/// each). Row `rows[k]` is expanded with the minors of the rows after it, keyed by the
/// bit set of the columns they use.
fn minor<A: Signed>(
    ar: &mut A,
    a: &Matrix<A::Value>,
    rows: &[usize],
    cols: &[usize],
) -> Result<A::Value, A::Error> {
    let n = rows.len();
    assert_eq!(n, cols.len(), "a minor of unequal sides");
    assert!(n <= 31, "minors are keyed by 32-bit column sets");
    // memo[set] = det of rows[n − |set| ..] on the columns cols[b] for the bits b of set.
    let mut memo: Vec<Option<A::Value>> = vec![None; 1 << n];
    memo[0] = Some(ar.one());
    for size in 1..=n {
        let row = rows[n - size];
        for set in 0usize..1 << n {
            if set.count_ones() as usize != size {
                continue;
            }
            let mut acc = ar.zero();
            // Expansion along `row`: the sign alternates over the columns of the set
            // in increasing order.
            for (position, bit) in (0..n).filter(|b| set & (1 << b) != 0).enumerate() {
                let entry = a.get(row, cols[bit]);
                if ar.is_exact_zero(entry) {
                    continue;
                }
                let rest = memo[set & !(1 << bit)]
                    .as_ref()
                    .expect("smaller minors come first");
                if ar.is_exact_zero(rest) {
                    continue;
                }
                let term = ar.mul(entry.clone(), rest)?;
                let term = if position % 2 == 1 {
                    ar.negate(term)
                } else {
                    term
                };
                acc = ar.add(acc, term)?;
            }
            memo[set] = Some(acc);
        }
    }
    Ok(memo[(1 << n) - 1].take().expect("the full set is computed"))
}

/// adj(a), the transposed cofactor matrix: adj(a)_ij = (−1)^(i+j) M_ji, so that
/// a · adj(a) = adj(a) · a = det(a) I for every square matrix, singular or not.
pub fn adjugate<A: Signed>(ar: &mut A, a: &Matrix<A::Value>) -> Result<Matrix<A::Value>, A::Error> {
    assert!(a.is_square(), "the adjugate of a non-square matrix");
    let n = a.rows;
    let mut data = Vec::with_capacity(n * n);
    for i in 0..n {
        for j in 0..n {
            let rows: Vec<usize> = (0..n).filter(|&r| r != j).collect();
            let cols: Vec<usize> = (0..n).filter(|&c| c != i).collect();
            let m = minor(ar, a, &rows, &cols)?;
            data.push(if (i + j) % 2 == 1 { ar.negate(m) } else { m });
        }
    }
    Ok(Matrix {
        rows: n,
        cols: n,
        data,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::Rational;
    use crate::permutation_sign;
    use itertools::Itertools;
    use std::convert::Infallible;

    struct Exact;

    impl Arithmetic for Exact {
        type Value = Rational;
        type Error = Infallible;
        fn zero(&mut self) -> Rational {
            Rational::int(0)
        }
        fn one(&mut self) -> Rational {
            Rational::int(1)
        }
        fn is_exact_zero(&self, x: &Rational) -> bool {
            x.is_zero()
        }
        fn mul(&mut self, a: Rational, b: &Rational) -> Result<Rational, Infallible> {
            Ok(&a * b)
        }
        fn add(&mut self, a: Rational, b: Rational) -> Result<Rational, Infallible> {
            Ok(&a + &b)
        }
    }

    impl Signed for Exact {
        fn negate(&mut self, x: Rational) -> Rational {
            -x
        }
    }

    /// Leibniz's formula: Σ over permutations of sign · Π a_i,σ(i).
    fn leibniz(a: &Matrix<Rational>) -> Rational {
        let n = a.rows();
        (0..n).permutations(n).fold(Rational::int(0), |acc, p| {
            let term = (0..n).fold(Rational::int(permutation_sign(&p).into()), |t, i| {
                &t * a.get(i, p[i])
            });
            &acc + &term
        })
    }

    fn pseudo_random(n: usize, seed: u64, zeros: bool) -> Matrix<Rational> {
        let mut s = seed;
        Matrix::from_fn(n, n, |_, _| {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let v = (s >> 33) as i64 % 7 - 3;
            if zeros && (s >> 20).is_multiple_of(3) {
                Rational::int(0)
            } else {
                Rational::ratio(v, 1 + (s >> 40) as i64 % 3).expect("nonzero")
            }
        })
    }

    #[test]
    fn determinant_agrees_with_leibniz() {
        for n in 0..=6 {
            for seed in 0..12 {
                let a = pseudo_random(n, seed * 31 + n as u64, seed % 2 == 0);
                let det = determinant(&mut Exact, &a).unwrap();
                assert_eq!(det, leibniz(&a), "n = {n}, seed = {seed}");
            }
        }
    }

    #[test]
    fn adjugate_times_matrix_is_det_identity() {
        for n in 1..=5 {
            for seed in 0..8 {
                let a = pseudo_random(n, seed + 100 * n as u64, seed % 3 == 0);
                let det = determinant(&mut Exact, &a).unwrap();
                let adj = adjugate(&mut Exact, &a).unwrap();
                for p in [product(&mut Exact, &a, &adj), product(&mut Exact, &adj, &a)] {
                    let p = p.unwrap();
                    for i in 0..n {
                        for j in 0..n {
                            let want = if i == j {
                                det.clone()
                            } else {
                                Rational::int(0)
                            };
                            assert_eq!(p.get(i, j), &want, "n = {n}, seed = {seed}");
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn a_singular_matrix_has_zero_determinant_and_a_nonzero_adjugate() {
        // Rows 1 and 3 equal: det = 0, yet adj ≠ 0 (rank 2 of 3).
        let q = |v: i64| Rational::int(v);
        let a = Matrix::from_rows(3, 3, [1, 2, 3, 0, 1, 4, 1, 2, 3].map(q).to_vec()).unwrap();
        assert!(determinant(&mut Exact, &a).unwrap().is_zero());
        let adj = adjugate(&mut Exact, &a).unwrap();
        assert!(adj.entries().iter().any(|x| !x.is_zero()));
    }

    #[test]
    fn transpose_and_product_shapes() {
        let q = |v: i64| Rational::int(v);
        let a = Matrix::from_rows(2, 3, [1, 2, 3, 4, 5, 6].map(q).to_vec()).unwrap();
        let at = a.transpose();
        assert_eq!((at.rows(), at.cols()), (3, 2));
        assert_eq!(at.get(2, 1), &q(6));
        let p = product(&mut Exact, &a, &at).unwrap();
        assert_eq!(p.entries(), &[14, 32, 32, 77].map(q));
        assert!(Matrix::from_rows(2, 2, vec![q(1)]).is_none());
    }
}
