//! Helpers of the unit tests of the search's polynomials and rationals.

use crate::kernel::{Poly, Rational, VarTable};

pub(crate) fn q(n: i64, d: i64) -> Rational {
    Rational::ratio(n, d).unwrap()
}

/// A deterministic stream (a linear congruential generator from `seed`) of numbers
/// below the argument.
pub(crate) fn below(mut seed: u64) -> impl FnMut(u64) -> u64 {
    move |m: u64| {
        seed = seed
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (seed >> 33) % m
    }
}

/// Variables of these names, as polynomials, and their table.
pub(crate) fn vars(names: &[&str]) -> (VarTable, Vec<Poly>) {
    let mut t = VarTable::new();
    let ps = names.iter().map(|n| Poly::var(t.intern(n))).collect();
    (t, ps)
}
