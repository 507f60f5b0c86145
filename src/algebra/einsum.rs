//! The one contraction every verdict relies on: Σ over the summed letters of a
//! product of tensor components, for every value of the free letters.
//!
//! It is written once, generic over the arithmetic it computes in ([`Arithmetic`]):
//! canonical polynomials under a work budget (the exact strategy), `f64` and num-dual
//! numbers (the sampled strategies' interpreter), and op ids of the tape compiler.
//! The exact route and the sampled routes thus contract with the same code; what makes
//! them independent is the *method* (canonical forms against sampling), not a second
//! copy of these lines. `tests/einsum.rs` checks this function against outer products
//! followed by pairwise traces, built another way (`tests/support/products.rs`).

use super::tensor::{assignments, for_each_assignment, Tensor};
use num_traits::{One, Zero};

pub use crate::kernel::term::Slot;

/// The ring operations a contraction needs, with a context: a work budget, or the
/// tape under construction. Products are formed left to right and summed in the
/// order of the summed letters' assignments, so two arithmetics that round alike give
/// bit-identical results.
pub trait Arithmetic {
    type Value: Clone;
    /// Why an operation was refused (a work budget ran out).
    type Error;
    fn zero(&mut self) -> Self::Value;
    fn one(&mut self) -> Self::Value;
    /// Whether `x` is exactly 0, so that a product through it may be skipped. Only an
    /// arithmetic where 0·x = 0 for every x (not IEEE floats: 0·∞ is NaN) says yes.
    fn is_exact_zero(&self, _x: &Self::Value) -> bool {
        false
    }
    fn mul(&mut self, a: Self::Value, b: &Self::Value) -> Result<Self::Value, Self::Error>;
    fn add(&mut self, a: Self::Value, b: Self::Value) -> Result<Self::Value, Self::Error>;
    /// The product of one factor, `1 · x`: an arithmetic where that is `x` itself may
    /// return a copy, charged as the product would be.
    fn first(&mut self, x: &Self::Value) -> Result<Self::Value, Self::Error> {
        let one = self.one();
        self.mul(one, x)
    }
}

/// One factor of a contraction: a tensor and the slots it is indexed with.
pub type Factor<'t, T> = (&'t Tensor<T>, Vec<Slot>);

/// Σ over the summed letters of Π factors, for every value of the `out` letters (in
/// that order). A letter is summed when it is not in `out`; a fixed slot picks one
/// component. A tensor of rank `out.len()` results.
pub fn einsum<A: Arithmetic>(
    arithmetic: &mut A,
    dim: usize,
    factors: &[Factor<'_, A::Value>],
    out: &[char],
) -> Result<Tensor<A::Value>, A::Error> {
    einsum_closing(arithmetic, dim, factors, out, A::mul)
}

/// [`einsum`] with each product's last multiplication (by the last factor, when there
/// are at least two) done by `last` instead of [`Arithmetic::mul`]: a linear map of the
/// product applied as the product is formed, such as its average over the normal
/// ([`super::polynomial::average_of_product`]), which then never forms the terms the map
/// sends to zero. The sum over the summed letters is of the mapped products.
pub fn einsum_closing<A: Arithmetic>(
    arithmetic: &mut A,
    dim: usize,
    factors: &[Factor<'_, A::Value>],
    out: &[char],
    mut last: impl FnMut(&mut A, A::Value, &A::Value) -> Result<A::Value, A::Error>,
) -> Result<Tensor<A::Value>, A::Error> {
    let mut all: Vec<char> = out.to_vec();
    for (_, slots) in factors {
        for s in slots {
            if let Slot::Letter(c) = s {
                if !all.contains(c) {
                    all.push(*c);
                }
            }
        }
    }
    let (free, summed) = (out.len(), all.len() - out.len());
    // Each factor's component offset is `base + Σ stride · value of its letter`: the
    // fixed slots make the base, each letter slot a stride (row-major, as
    // `Tensor::get`). The strides of the free letters (by position in `out`) give a
    // part formed once per output component; those of the summed letters (by position
    // among them) a part tabulated once per assignment of them.
    let mut bases = Vec::with_capacity(factors.len());
    let mut free_strides: Vec<Vec<(usize, usize)>> = Vec::with_capacity(factors.len());
    let mut summed_strides: Vec<Vec<(usize, usize)>> = Vec::with_capacity(factors.len());
    for (t, slots) in factors {
        assert_eq!(slots.len(), t.rank(), "index count must equal the rank");
        let (mut base, mut of_free, mut of_summed) = (0, Vec::new(), Vec::new());
        let mut stride = 1;
        for s in slots.iter().rev() {
            match s {
                Slot::Letter(c) => {
                    let k = all.iter().position(|d| d == c).expect("collected above");
                    if k < free {
                        of_free.push((k, stride));
                    } else {
                        of_summed.push((k - free, stride));
                    }
                }
                Slot::Fixed(v) => {
                    assert!(*v < dim, "index {v} out of range 0..{dim}");
                    base += v * stride;
                }
            }
            stride *= dim;
        }
        bases.push(base);
        free_strides.push(of_free);
        summed_strides.push(of_summed);
    }
    let offset = |strides: &[(usize, usize)], values: &[usize]| -> usize {
        strides.iter().map(|&(k, stride)| stride * values[k]).sum()
    };
    // Row `s` holds each factor's offset from the summed letters at their `s`-th
    // assignment (in the order of `assignments`).
    let mut inner = Vec::new();
    for s in assignments(dim, summed) {
        inner.extend(summed_strides.iter().map(|st| offset(st, &s)));
    }
    let mut at_free = vec![0usize; factors.len()];
    let mut data = Vec::new();
    let mut failed = None;
    for_each_assignment(dim, free, |o| {
        if failed.is_some() {
            return;
        }
        for ((a, base), st) in at_free.iter_mut().zip(&bases).zip(&free_strides) {
            *a = base + offset(st, o);
        }
        match component(arithmetic, factors, &at_free, &inner, &mut last) {
            Ok(total) => data.push(total),
            Err(e) => failed = Some(e),
        }
    });
    match failed {
        Some(e) => Err(e),
        None => Ok(Tensor::from_components(dim, free, data)),
    }
}

/// One output component: Σ over the rows of `inner` of the product of the factors'
/// components at `at_free + row`, formed left to right from the first factor (the last
/// multiplication by `last`) and summed in row order. A product through an exact zero
/// is skipped.
fn component<A: Arithmetic>(
    arithmetic: &mut A,
    factors: &[Factor<'_, A::Value>],
    at_free: &[usize],
    inner: &[usize],
    last: &mut impl FnMut(&mut A, A::Value, &A::Value) -> Result<A::Value, A::Error>,
) -> Result<A::Value, A::Error> {
    let mut total = arithmetic.zero();
    if factors.is_empty() {
        let one = arithmetic.one();
        // No factors: the empty product, once per assignment of (no) summed letters.
        return arithmetic.add(total, one);
    }
    'rows: for row in inner.chunks_exact(factors.len()) {
        let mut prod = None;
        for (f, (((t, _), &a), &s)) in factors.iter().zip(at_free).zip(row).enumerate() {
            let c = &t.components()[a + s];
            if arithmetic.is_exact_zero(c) {
                continue 'rows;
            }
            prod = Some(match prod {
                None => arithmetic.first(c)?,
                Some(p) if f + 1 == factors.len() => last(arithmetic, p, c)?,
                Some(p) => arithmetic.mul(p, c)?,
            });
        }
        total = arithmetic.add(total, prod.expect("at least one factor"))?;
    }
    Ok(total)
}

/// Plain field arithmetic for any `Clone` number type with the usual operators
/// (`f64`, num-dual numbers, [`Rational`](crate::kernel::Rational)); it never refuses.
#[derive(Clone, Copy, Debug, Default)]
pub struct Plain;

impl Plain {
    /// `einsum` in plain arithmetic.
    pub fn einsum<T>(dim: usize, factors: &[Factor<'_, T>], out: &[char]) -> Tensor<T>
    where
        T: Clone + Zero + One + std::ops::Mul<Output = T>,
    {
        match einsum(
            &mut PlainOf::<T>(std::marker::PhantomData),
            dim,
            factors,
            out,
        ) {
            Ok(t) => t,
            Err(never) => match never {},
        }
    }
}

/// [`Plain`] for one number type.
struct PlainOf<T>(std::marker::PhantomData<T>);

impl<T> Arithmetic for PlainOf<T>
where
    T: Clone + Zero + One + std::ops::Mul<Output = T>,
{
    type Value = T;
    type Error = std::convert::Infallible;
    fn zero(&mut self) -> T {
        T::zero()
    }
    fn one(&mut self) -> T {
        T::one()
    }
    fn mul(&mut self, a: T, b: &T) -> Result<T, Self::Error> {
        Ok(a * b.clone())
    }
    fn add(&mut self, a: T, b: T) -> Result<T, Self::Error> {
        Ok(a + b)
    }
}

/// The work budget of a polynomial contraction ran out.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct OverBudget;

/// Canonical polynomials, with a budget of term products: each product of an `a`-term
/// and a `b`-term polynomial costs `a·b`. Known zeros are skipped exactly.
#[derive(Debug)]
pub struct Polynomials<'b> {
    pub work_left: &'b mut usize,
}

impl Arithmetic for Polynomials<'_> {
    type Value = crate::kernel::Poly;
    type Error = OverBudget;
    fn zero(&mut self) -> crate::kernel::Poly {
        crate::kernel::Poly::zero()
    }
    fn one(&mut self) -> crate::kernel::Poly {
        crate::kernel::Poly::one()
    }
    fn is_exact_zero(&self, x: &crate::kernel::Poly) -> bool {
        x.is_zero()
    }
    fn mul(
        &mut self,
        a: crate::kernel::Poly,
        b: &crate::kernel::Poly,
    ) -> Result<crate::kernel::Poly, OverBudget> {
        let cost = a.num_terms().saturating_mul(b.num_terms());
        *self.work_left = self.work_left.checked_sub(cost).ok_or(OverBudget)?;
        // An exponent beyond the kernel's bound is a resource limit like the budget.
        a.checked_mul(b).map_err(|_| OverBudget)
    }
    fn add(
        &mut self,
        mut a: crate::kernel::Poly,
        b: crate::kernel::Poly,
    ) -> Result<crate::kernel::Poly, OverBudget> {
        a += &b;
        Ok(a)
    }
    /// `1 · x` is `x`, charged as the product (`1 · |x|`).
    fn first(&mut self, x: &crate::kernel::Poly) -> Result<crate::kernel::Poly, OverBudget> {
        *self.work_left = self
            .work_left
            .checked_sub(x.num_terms())
            .ok_or(OverBudget)?;
        Ok(x.clone())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::{Poly, Rational, VarTable};

    #[test]
    fn trace_and_matrix_product() {
        let a = Tensor::from_fn(2, 2, |i| (1 + 2 * i[0] + i[1]) as f64);
        let tr = Plain::einsum(2, &[(&a, vec![Slot::Letter('i'), Slot::Letter('i')])], &[]);
        assert_eq!(tr.into_scalar(), Some(1.0 + 4.0));
        // (AA)_ik = A_ij A_jk, [[1,2],[3,4]]² = [[7,10],[15,22]].
        let i = Slot::Letter('i');
        let j = Slot::Letter('j');
        let k = Slot::Letter('k');
        let sq = Plain::einsum(2, &[(&a, vec![i, j]), (&a, vec![j, k])], &['i', 'k']);
        assert_eq!(sq.components(), &[7.0, 10.0, 15.0, 22.0]);
        // A_2j A_j1 = 3·1 + 4·3 = 15.
        let fixed = Plain::einsum(
            2,
            &[(&a, vec![Slot::Fixed(1), j]), (&a, vec![j, Slot::Fixed(0)])],
            &[],
        );
        assert_eq!(fixed.into_scalar(), Some(15.0));
    }

    #[test]
    fn polynomial_budget_refuses_and_charges() {
        let mut names = VarTable::new();
        let x = Poly::var(names.intern("x"));
        let y = Poly::var(names.intern("y"));
        let s = &x + &y;
        let v = Tensor::from_fn(3, 1, |_| s.clone());
        let i = Slot::Letter('i');
        let mut work = 3 * 2 * 2;
        let mut ring = Polynomials {
            work_left: &mut work,
        };
        // Σ_i (x+y)(x+y): three products of a 1-term by a 2-term (the leading 1) and
        // three of 2 by 2.
        let r = einsum(&mut ring, 3, &[(&v, vec![i]), (&v, vec![i])], &[]);
        assert_eq!(r, Err(OverBudget));
        let mut work = 100;
        let mut ring = Polynomials {
            work_left: &mut work,
        };
        let r = einsum(&mut ring, 3, &[(&v, vec![i]), (&v, vec![i])], &[]).unwrap();
        let three = Poly::constant(Rational::int(3));
        assert_eq!(r.into_scalar(), Some(&three * &(&s * &s)));
        assert_eq!(work, 100 - 3 * (2 + 4));
    }
}
