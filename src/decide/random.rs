//! The one random generator of the decisions (SplitMix64): seeded, so that the same
//! seed draws the same states and points on every machine. The sampled routes draw
//! `f64` states from it, the exact routes rational points (counterexample candidates,
//! samples of a scalar function on its box).

use crate::algebra::sign::{End, Interval};
use crate::kernel::Rational;
use crate::lang::Decls;

/// A deterministic generator (SplitMix64).
pub struct Rng(u64);

impl Rng {
    /// A generator for `seed`.
    pub fn new(seed: u64) -> Self {
        Rng(seed)
    }

    /// A generator for `seed` and the purpose `salt`: two routes of one claim draw
    /// different streams from the claim's one seed.
    pub fn salted(seed: u64, salt: u64) -> Self {
        Rng(seed ^ salt)
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [−1, 1).
    pub fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }

    /// Uniform in 0..n (n > 0).
    pub fn below(&mut self, n: usize) -> usize {
        ((u128::from(self.next_u64()) * n as u128) >> 64) as usize
    }

    /// A random unit normal (in the 1-2 plane for plane problems), padded to the
    /// dimension with zeros.
    pub fn unit_normal(&mut self, decls: &Decls) -> Vec<f64> {
        let free = if decls.normal_in_plane { 2 } else { decls.dim };
        let mut v: Vec<f64> = (0..free).map(|_| self.uniform()).collect();
        let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt().max(1e-3);
        v.iter_mut().for_each(|x| *x /= norm);
        v.resize(decls.dim, 0.0);
        v
    }

    /// A nonzero integer in −4..=4.
    pub fn small(&mut self) -> i64 {
        let k = (self.next_u64() % 8) as i64;
        if k < 4 {
            k - 4
        } else {
            k - 3
        }
    }

    /// A dyadic rational strictly inside (0, 1).
    fn unit(&mut self) -> Rational {
        let k = (self.next_u64() >> 44) as i64; // 20 bits
        Rational::ratio(2 * k + 1, 1 << 21).expect("nonzero")
    }

    /// A positive dyadic spread over scales 2⁻⁶ … 2⁶.
    fn spread(&mut self) -> Rational {
        let scale = (self.next_u64() % 13) as i32 - 6;
        &self.unit() * &Rational::int(2).pow(i64::from(scale)).expect("nonzero")
    }

    /// A rational point of `i`; one time in sixteen a closed end itself.
    pub fn draw(&mut self, i: &Interval) -> Rational {
        if self.next_u64().is_multiple_of(16) {
            let ends: Vec<&Rational> = [&i.lo, &i.hi]
                .into_iter()
                .filter_map(|e| match e {
                    End::Closed(x) => Some(x),
                    _ => None,
                })
                .collect();
            if let Some(x) = ends.get((self.next_u64() % 2) as usize).or(ends.first()) {
                return (*x).clone();
            }
        }
        let value = |e: &End| match e {
            End::Unbounded => None,
            End::Open(x) | End::Closed(x) => Some(x.clone()),
        };
        match (value(&i.lo), value(&i.hi)) {
            (Some(a), Some(b)) => &a + &(&(&b - &a) * &self.unit()),
            (Some(a), None) => &a + &self.spread(),
            (None, Some(b)) => &b - &self.spread(),
            (None, None) if self.next_u64().is_multiple_of(2) => self.spread(),
            (None, None) => -self.spread(),
        }
    }
}
