//! The value of an expression with free indices in every ring: a tensor whose slots are
//! labelled by the index letters, sorted.

use crate::algebra::Tensor;

/// A tensor whose slots are labelled by index letters, sorted.
#[derive(Clone, Debug, PartialEq)]
pub struct Labeled<T> {
    pub labels: Vec<char>,
    pub tensor: Tensor<T>,
}

impl<T> Labeled<T> {
    pub fn new(labels: Vec<char>, tensor: Tensor<T>) -> Self {
        Labeled { labels, tensor }
    }

    /// The component for the given values (0-based) of (a superset of) its labels; a
    /// label the assignment leaves out takes 0.
    pub fn at(&self, assignment: &[(char, usize)]) -> &T {
        let idx: Vec<usize> = self
            .labels
            .iter()
            .map(|c| {
                assignment
                    .iter()
                    .find(|(d, _)| d == c)
                    .map_or(0, |&(_, v)| v)
            })
            .collect();
        self.tensor.get(&idx)
    }
}
