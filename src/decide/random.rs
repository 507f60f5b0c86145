//! The random generator of the sampled routes: seeded, so that the same seed draws
//! the same states on every machine.

use crate::lang::Decls;

/// A small deterministic generator (xorshift64*), independent of the exact route's.
pub struct Rng(u64);

impl Rng {
    /// A generator for `seed` (0 is mapped to 1: xorshift needs a nonzero state).
    pub fn new(seed: u64) -> Self {
        Rng(seed.max(1))
    }

    /// Uniform in [−1, 1).
    pub fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let x = self.0.wrapping_mul(0x2545_F491_4F6C_DD1D);
        (x >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }

    /// Uniform in 0..n (n > 0).
    pub fn below(&mut self, n: usize) -> usize {
        let k = ((self.uniform() + 1.0) / 2.0 * n as f64) as usize;
        k.min(n - 1)
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
}
