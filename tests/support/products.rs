//! Outer products and traces of dense tensors: a reference built another way than the
//! checker's one contraction (`algebra::einsum`), to state identities component by
//! component in tests.

use cosserat_check::algebra::Tensor;
use num_traits::Zero;
use std::ops::{Add, Mul};

/// Outer products and traces.
pub trait Products: Sized {
    /// The outer product `self ⊗ other` (slots of `self` first).
    fn outer(&self, other: &Self) -> Self;
    /// Sums over slots `a` and `b` set equal (a trace), lowering the rank by two.
    fn contract(&self, a: usize, b: usize) -> Self;
}

impl<T: Clone + Zero + Add<Output = T> + Mul<Output = T>> Products for Tensor<T> {
    fn outer(&self, other: &Self) -> Self {
        assert_eq!(self.dim(), other.dim(), "dimensions must agree");
        let split = self.rank();
        Tensor::from_fn(self.dim(), split + other.rank(), |idx| {
            self.get(&idx[..split]).clone() * other.get(&idx[split..]).clone()
        })
    }

    fn contract(&self, a: usize, b: usize) -> Self {
        let rank = self.rank();
        assert!(a != b && a < rank && b < rank, "two distinct slots");
        Tensor::from_fn(self.dim(), rank - 2, |rest| {
            let mut it = rest.iter();
            let mut full: Vec<usize> = (0..rank)
                .map(|s| {
                    if s == a || s == b {
                        0
                    } else {
                        *it.next().unwrap()
                    }
                })
                .collect();
            (0..self.dim()).fold(T::zero(), |acc, k| {
                full[a] = k;
                full[b] = k;
                acc + self.get(&full).clone()
            })
        })
    }
}
