//! Dense tensors over the index range 1..=d (d = 2 or 3), of any rank, generic over
//! the scalar: `f64`, num-dual numbers, [`Rational`](crate::kernel::Rational) and
//! [`Poly`](crate::kernel::Poly) all work. Each operation asks only for the arithmetic it
//! needs (nalgebra's style): storage needs nothing, δ needs `Zero + One`, ε also `Neg`.
//!
//! Indices are 0-based in code and 1-based in everything shown to a user.

use num_traits::{One, Zero};
use std::ops::{Add, Mul, Neg};

/// Every assignment of `rank` indices in `0..dim`, in row-major order. Rank 0 yields
/// exactly one (empty) assignment.
pub fn assignments(dim: usize, rank: usize) -> impl Iterator<Item = Vec<usize>> {
    (0..assignment_count(dim, rank)).map(move |mut flat| {
        // Least significant first, then reversed: no zero-filled allocation.
        let mut idx = Vec::with_capacity(rank);
        for _ in 0..rank {
            idx.push(flat % dim);
            flat /= dim;
        }
        idx.reverse();
        idx
    })
}

/// The most components a declared tensor or any intermediate value may have (3^10):
/// every rank is checked against it before anything is allocated.
pub const MAX_COMPONENTS: usize = 59_049;

/// The most index values one product's contraction may visit, free and summed letters
/// together (3^12).
pub const MAX_ASSIGNMENTS: usize = 531_441;

/// dim^rank, saturating: a count to compare with [`MAX_COMPONENTS`].
pub fn assignment_count_saturating(dim: usize, rank: usize) -> usize {
    u32::try_from(rank)
        .ok()
        .and_then(|r| dim.checked_pow(r))
        .unwrap_or(usize::MAX)
}

/// dim^rank, the number of assignments; 0 when there are too many to count (none are
/// then listed).
fn assignment_count(dim: usize, rank: usize) -> usize {
    u32::try_from(rank)
        .ok()
        .and_then(|r| dim.checked_pow(r))
        .unwrap_or(0)
}

/// Calls `f` with every assignment of `rank` indices in `0..dim`, in row-major order
/// (as [`assignments`] lists them), through one buffer advanced in place.
pub fn for_each_assignment(dim: usize, rank: usize, mut f: impl FnMut(&[usize])) {
    if assignment_count(dim, rank) == 0 {
        return;
    }
    let mut idx = vec![0; rank];
    loop {
        f(&idx);
        // The odometer: the last index turns fastest.
        let mut slot = rank;
        loop {
            if slot == 0 {
                return;
            }
            slot -= 1;
            idx[slot] += 1;
            if idx[slot] < dim {
                break;
            }
            idx[slot] = 0;
        }
    }
}

/// A dense tensor of the given rank over `0..dim` in every slot, stored row-major.
///
/// ```
/// use cosserat_algebra::Tensor;
/// // ε_ijk ε_ijk = 6 in 3D.
/// let e = Tensor::<i64>::levi_civita(3);
/// assert_eq!(e.components().iter().map(|x| x * x).sum::<i64>(), 6);
/// assert_eq!(*e.get(&[2, 1, 0]), -1);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Tensor<T> {
    dim: usize,
    rank: usize,
    data: Vec<T>,
}

impl<T> Tensor<T> {
    /// Builds a tensor from its components.
    pub fn from_fn(dim: usize, rank: usize, mut f: impl FnMut(&[usize]) -> T) -> Self {
        let mut data = Vec::with_capacity(assignment_count(dim, rank));
        for_each_assignment(dim, rank, |idx| data.push(f(idx)));
        Tensor { dim, rank, data }
    }

    /// A tensor from its components in row-major order (as [`Tensor::components`]
    /// lists them).
    pub fn from_components(dim: usize, rank: usize, data: Vec<T>) -> Self {
        assert_eq!(
            data.len(),
            assignment_count(dim, rank),
            "one component per assignment"
        );
        Tensor { dim, rank, data }
    }

    /// A rank-0 tensor.
    pub fn scalar(dim: usize, x: T) -> Self {
        Tensor {
            dim,
            rank: 0,
            data: vec![x],
        }
    }

    pub fn dim(&self) -> usize {
        self.dim
    }

    pub fn rank(&self) -> usize {
        self.rank
    }

    fn offset(&self, idx: &[usize]) -> usize {
        assert_eq!(idx.len(), self.rank, "index count must equal the rank");
        idx.iter().fold(0, |acc, &i| {
            assert!(i < self.dim, "index {i} out of range 0..{}", self.dim);
            acc * self.dim + i
        })
    }

    /// The component at 0-based indices `idx`.
    pub fn get(&self, idx: &[usize]) -> &T {
        &self.data[self.offset(idx)]
    }

    pub fn get_mut(&mut self, idx: &[usize]) -> &mut T {
        let k = self.offset(idx);
        &mut self.data[k]
    }

    /// Components in row-major order.
    pub fn components(&self) -> &[T] {
        &self.data
    }

    /// Consumes the tensor into its components in row-major order.
    pub fn into_components(self) -> Vec<T> {
        self.data
    }

    /// Consumes the tensor into another of the same shape, component by component.
    pub fn into_map<U>(self, f: impl FnMut(T) -> U) -> Tensor<U> {
        Tensor {
            dim: self.dim,
            rank: self.rank,
            data: self.data.into_iter().map(f).collect(),
        }
    }

    /// Consumes a rank-0 tensor into its value.
    pub fn into_scalar(mut self) -> Option<T> {
        (self.rank == 0).then(|| self.data.remove(0))
    }

    pub fn map<U>(&self, f: impl FnMut(&T) -> U) -> Tensor<U> {
        Tensor {
            dim: self.dim,
            rank: self.rank,
            data: self.data.iter().map(f).collect(),
        }
    }

    /// Fallible map: the first error stops it.
    pub fn try_map<U, E>(&self, f: impl FnMut(&T) -> Result<U, E>) -> Result<Tensor<U>, E> {
        Ok(Tensor {
            dim: self.dim,
            rank: self.rank,
            data: self.data.iter().map(f).collect::<Result<_, _>>()?,
        })
    }

    /// The tensor with slots reordered: `result[j_0..] = self[i]` where
    /// `i[perm[k]] = j[k]`, i.e. slot k of the result is slot `perm[k]` of `self`.
    pub fn permuted(&self, perm: &[usize]) -> Self
    where
        T: Clone,
    {
        assert_eq!(perm.len(), self.rank);
        Tensor::from_fn(self.dim, self.rank, |j| {
            let mut i = vec![0; self.rank];
            for (k, &p) in perm.iter().enumerate() {
                i[p] = j[k];
            }
            self.get(&i).clone()
        })
    }
}

impl<T: Zero + One> Tensor<T> {
    /// The Kronecker delta δ_ij.
    pub fn delta(dim: usize) -> Self {
        Tensor::from_fn(dim, 2, |i| if i[0] == i[1] { T::one() } else { T::zero() })
    }
}

/// The sign of a permutation of `0..n` (0 when an entry repeats).
pub fn permutation_sign(p: &[usize]) -> i8 {
    let mut sign = 1;
    for a in 0..p.len() {
        for b in a + 1..p.len() {
            if p[a] == p[b] {
                return 0;
            }
            if p[a] > p[b] {
                sign = -sign;
            }
        }
    }
    sign
}

impl<T: Zero + One + Neg<Output = T>> Tensor<T> {
    /// The Levi-Civita (permutation) symbol of rank `dim`, with ε_12 = 1 in 2D and
    /// ε_123 = 1 in 3D (the paper's e_ijk).
    pub fn levi_civita(dim: usize) -> Self {
        Tensor::from_fn(dim, dim, |i| match permutation_sign(i) {
            1 => T::one(),
            -1 => -T::one(),
            _ => T::zero(),
        })
    }
}

impl<T: Clone + Zero + Add<Output = T> + Mul<Output = T>> Tensor<T> {
    /// Component-wise sum.
    pub fn add(&self, other: &Self) -> Self {
        assert_eq!((self.dim, self.rank), (other.dim, other.rank));
        Tensor {
            dim: self.dim,
            rank: self.rank,
            data: self
                .data
                .iter()
                .zip(&other.data)
                .map(|(a, b)| a.clone() + b.clone())
                .collect(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn assignments_cover_every_index_once() {
        assert_eq!(
            assignments(3, 0).collect::<Vec<_>>(),
            vec![Vec::<usize>::new()]
        );
        assert_eq!(assignments(2, 2).count(), 4);
        let all: Vec<_> = assignments(3, 6).collect();
        assert_eq!(all.len(), 729);
        assert_eq!(all[1], vec![0, 0, 0, 0, 0, 1]);
        assert_eq!(all[728], vec![2; 6]);
        // The in-place odometer visits the same assignments in the same order.
        for (dim, rank) in [(3, 0), (2, 3), (3, 4), (1, 5), (0, 2), (0, 0)] {
            let mut visited = Vec::new();
            for_each_assignment(dim, rank, |idx| visited.push(idx.to_vec()));
            assert_eq!(
                visited,
                assignments(dim, rank).collect::<Vec<_>>(),
                "{dim} {rank}"
            );
        }
    }

    #[test]
    fn epsilon_in_2d_and_signs() {
        let e = Tensor::<i64>::levi_civita(2);
        assert_eq!(e.components(), &[0, 1, -1, 0]);
        assert_eq!(*Tensor::<i64>::levi_civita(3).get(&[2, 1, 0]), -1);
        assert_eq!(permutation_sign(&[1, 2, 0]), 1);
        assert_eq!(permutation_sign(&[0, 0, 1]), 0);
    }

    #[test]
    fn permutation_moves_slots() {
        let t = Tensor::from_fn(3, 3, |i| (100 * i[0] + 10 * i[1] + i[2]) as i64);
        let p = t.permuted(&[2, 0, 1]);
        // slot 0 of p is slot 2 of t: p[a,b,c] = t[b,c,a].
        assert_eq!(*p.get(&[1, 2, 0]), *t.get(&[2, 0, 1]));
        assert_eq!(p.permuted(&[1, 2, 0]), t);
    }
}
