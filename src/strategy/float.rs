//! An independent floating-point route for cross-checking exact verdicts.
//!
//! It shares only the parser and validator with the exact strategy: no polynomial, no
//! moment formula. Symbols get seeded random values in [−1, 1], the normal is a random
//! unit vector, and `avg(…)` re-evaluates its argument at the nodes of a quadrature
//! rule on the circle (trapezoid, 32 points) or the sphere (8-point Gauss–Legendre in
//! cos θ by Newton iteration × 16 equally spaced φ), exact for polynomials of degree
//! ≤ 15 in n. A disagreement between this route and the exact one is a bug in one of
//! them, and the test suite fails on it.

use crate::derivation::{Assumption, Check, Definition, Verdict};
use crate::kernel::{assignments, Tensor};
use crate::lang::{Decls, Node, NodeKind, Slot, Target};
use std::collections::HashMap;

/// Relative tolerance of a float comparison: |l − r| ≤ TOL · (1 + |l| + |r|). Inputs
/// are O(1), expressions have a few hundred operations at most, so rounding stays
/// near 1e-14; a wrong statement differs by O(1e-2) or more at a random point.
pub const TOL: f64 = 1e-9;

/// Quadrature nodes and weights (weights sum to 1) for the uniform average over the
/// unit circle or sphere.
pub fn sphere_rule(dim: usize) -> Vec<(Vec<f64>, f64)> {
    use std::f64::consts::PI;
    if dim == 2 {
        let m = 32;
        return (0..m)
            .map(|k| {
                let phi = 2.0 * PI * k as f64 / m as f64;
                (vec![phi.cos(), phi.sin()], 1.0 / m as f64)
            })
            .collect();
    }
    let (zs, ws) = gauss_legendre(8);
    let m = 16;
    let mut out = Vec::with_capacity(zs.len() * m);
    for (z, w) in zs.iter().zip(&ws) {
        let r = (1.0 - z * z).max(0.0).sqrt();
        for k in 0..m {
            let phi = 2.0 * PI * k as f64 / m as f64;
            out.push((vec![r * phi.cos(), r * phi.sin(), *z], w / 2.0 / m as f64));
        }
    }
    out
}

/// Gauss–Legendre nodes and weights on [−1, 1] by Newton iteration on P_n.
fn gauss_legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
    let mut xs = Vec::with_capacity(n);
    let mut ws = Vec::with_capacity(n);
    for i in 0..n {
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
            let dx = p1 / dp;
            x -= dx;
            if dx.abs() < 1e-16 {
                break;
            }
        }
        xs.push(x);
        ws.push(2.0 / ((1.0 - x * x) * dp * dp));
    }
    (xs, ws)
}

/// A small deterministic generator (xorshift64*), independent of the exact route's.
struct Rng(u64);

impl Rng {
    fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let x = self.0.wrapping_mul(0x2545_F491_4F6C_DD1D);
        (x >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
}

type Labeled = (Vec<char>, Tensor<f64>);

struct Env<'a> {
    decls: &'a Decls,
    defs: &'a [Definition],
    symbols: HashMap<String, Tensor<f64>>,
    rule: Vec<(Vec<f64>, f64)>,
}

impl Env<'_> {
    fn eval(&self, node: &Node, n: &[f64]) -> Result<Labeled, String> {
        let d = self.decls.dim;
        let labels = node.free_letters();
        let scalar = |x: f64| (vec![], Tensor::scalar(d, x));
        Ok(match &node.kind {
            NodeKind::Const(q) => scalar(q.to_f64()),
            NodeKind::Leaf { target, slots } => {
                let base = match target {
                    Target::Delta => Tensor::delta(d),
                    Target::Eps => Tensor::levi_civita(d),
                    Target::Normal => Tensor::from_fn(d, 1, |i| n[i[0]]),
                    Target::Symbol(s) => self.symbols[s].clone(),
                    Target::Def(name) => {
                        let def = self
                            .defs
                            .iter()
                            .rev()
                            .find(|x| &x.sig.name == name)
                            .ok_or_else(|| format!("definition {name} not in scope"))?;
                        let (ls, t) = self.eval(&def.body, n)?;
                        let perm: Vec<usize> = def
                            .sig
                            .formal
                            .iter()
                            .map(|c| ls.iter().position(|x| x == c).unwrap_or(0))
                            .collect();
                        t.permuted(&perm)
                    }
                };
                let t = product(d, &[(&base, slots.clone())], &labels);
                (labels, t)
            }
            NodeKind::Neg(a) => {
                let (ls, t) = self.eval(a, n)?;
                (ls, t.map(|x| -x))
            }
            NodeKind::Sum(terms) => {
                let mut acc: Option<Labeled> = None;
                for t in terms {
                    let (ls, v) = self.eval(t, n)?;
                    acc = Some(match acc {
                        None => (ls, v),
                        Some((ls, a)) => (ls, a.add(&v)),
                    });
                }
                acc.ok_or("empty sum")?
            }
            NodeKind::Product(fs) => {
                let vals = fs
                    .iter()
                    .map(|f| self.eval(f, n))
                    .collect::<Result<Vec<_>, _>>()?;
                let slots: Vec<(&Tensor<f64>, Vec<Slot>)> = vals
                    .iter()
                    .map(|(ls, t)| (t, ls.iter().map(|&c| Slot::Letter(c)).collect()))
                    .collect();
                let t = product(d, &slots, &labels);
                (labels, t)
            }
            NodeKind::Div(a, b) => {
                let (ls, t) = self.eval(a, n)?;
                let den = self
                    .eval(b, n)?
                    .1
                    .into_scalar()
                    .ok_or("divisor is not a scalar")?;
                if den == 0.0 {
                    return Err("division by zero".into());
                }
                (ls, t.map(|x| x / den))
            }
            NodeKind::Pow(a, k) => {
                let x = self
                    .eval(a, n)?
                    .1
                    .into_scalar()
                    .ok_or("power of a non-scalar")?;
                scalar(x.powi(*k as i32))
            }
            NodeKind::Sqrt(a) => {
                let x = self
                    .eval(a, n)?
                    .1
                    .into_scalar()
                    .ok_or("sqrt of a non-scalar")?;
                if x < 0.0 {
                    return Err("sqrt of a negative number".into());
                }
                scalar(x.sqrt())
            }
            NodeKind::Avg(a) => {
                let mut acc: Option<Labeled> = None;
                for (point, w) in &self.rule {
                    let (ls, t) = self.eval(a, point)?;
                    let t = t.map(|x| x * w);
                    acc = Some(match acc {
                        None => (ls, t),
                        Some((ls, s)) => (ls, s.add(&t)),
                    });
                }
                acc.ok_or("empty quadrature rule")?
            }
        })
    }
}

/// The contraction of this route, written separately from the exact route's `einsum`
/// on purpose: a shared bug would make the two routes agree on a wrong answer.
fn product(dim: usize, factors: &[(&Tensor<f64>, Vec<Slot>)], out: &[char]) -> Tensor<f64> {
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
    let summed = all.len() - out.len();
    Tensor::from_fn(dim, out.len(), |o| {
        assignments(dim, summed)
            .map(|s| {
                factors
                    .iter()
                    .map(|(t, slots)| {
                        let idx: Vec<usize> = slots
                            .iter()
                            .map(|sl| match sl {
                                Slot::Fixed(v) => *v,
                                Slot::Letter(c) => {
                                    let k = all.iter().position(|x| x == c).expect("collected");
                                    if k < out.len() {
                                        o[k]
                                    } else {
                                        s[k - out.len()]
                                    }
                                }
                            })
                            .collect();
                        *t.get(&idx)
                    })
                    .product::<f64>()
            })
            .sum()
    })
}

/// The float route's verdict on a check: `holds` when every equality agrees within
/// [`TOL`] at `samples` seeded random points, else `fails`. `Ok(None)` when the check
/// has an ill-formed (verbatim) side, which this route does not judge.
pub fn decide(
    decls: &Decls,
    check: &Check,
    samples: usize,
    seed: u64,
) -> Result<Option<Verdict>, String> {
    if check.chains.iter().flatten().any(|s| s.node.is_err()) {
        return Ok(None);
    }
    let d = decls.dim;
    let mut rng = Rng(seed.max(1));
    for _ in 0..samples {
        let mut symbols: HashMap<String, Tensor<f64>> = HashMap::new();
        for (name, &rank) in &decls.symbols {
            symbols.insert(name.clone(), Tensor::from_fn(d, rank, |_| rng.uniform()));
        }
        // An in-plane normal uses the circle rule, embedded with n_3 = 0.
        let free = if decls.normal_in_plane { 2 } else { d };
        let rule = sphere_rule(free)
            .into_iter()
            .map(|(mut p, w)| {
                p.resize(d, 0.0);
                (p, w)
            })
            .collect();
        let mut env = Env {
            decls,
            defs: &check.defs,
            symbols,
            rule,
        };
        let n: Vec<f64> = {
            let mut v: Vec<f64> = (0..free).map(|_| rng.uniform()).collect();
            let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt().max(1e-3);
            v.iter_mut().for_each(|x| *x /= norm);
            v.resize(d, 0.0);
            v
        };
        for a in &check.assumptions {
            apply(&mut env, a, &n)?;
        }
        for chain in &check.chains {
            let values = chain
                .iter()
                .map(|s| env.eval(s.node.as_ref().expect("checked above"), &n))
                .collect::<Result<Vec<_>, _>>()?;
            for w in values.windows(2) {
                let ((la, ta), (lb, tb)) = (&w[0], &w[1]);
                let mut labels: Vec<char> = la.iter().chain(lb).copied().collect();
                labels.sort_unstable();
                labels.dedup();
                for a in assignments(d, labels.len()) {
                    let pick = |ls: &[char], t: &Tensor<f64>| {
                        let idx: Vec<usize> = ls
                            .iter()
                            .map(|c| a[labels.iter().position(|x| x == c).unwrap_or(0)])
                            .collect();
                        *t.get(&idx)
                    };
                    let (l, r) = (pick(la, ta), pick(lb, tb));
                    if !l.is_finite()
                        || !r.is_finite()
                        || (l - r).abs() > TOL * (1.0 + l.abs() + r.abs())
                    {
                        return Ok(Some(Verdict::Fails));
                    }
                }
            }
        }
    }
    Ok(Some(Verdict::Holds))
}

fn apply(env: &mut Env<'_>, a: &Assumption, n: &[f64]) -> Result<(), String> {
    let d = env.decls.dim;
    match a {
        Assumption::Traceless { symbol } => {
            let t = env.symbols.get_mut(symbol).ok_or("unknown symbol")?;
            let rest: f64 = (0..d - 1).map(|k| *t.get(&[k, k])).sum();
            *t.get_mut(&[d - 1, d - 1]) = -rest;
        }
        Assumption::Symmetric { symbol } | Assumption::Antisymmetric { symbol } => {
            let anti = matches!(a, Assumption::Antisymmetric { .. });
            let t = env.symbols.get_mut(symbol).ok_or("unknown symbol")?;
            for i in 0..d {
                for j in 0..i {
                    let u = *t.get(&[j, i]);
                    *t.get_mut(&[i, j]) = if anti { -u } else { u };
                }
                if anti {
                    *t.get_mut(&[i, i]) = 0.0;
                }
            }
        }
        Assumption::Component {
            symbol,
            index,
            body,
            ..
        } => {
            let x = env
                .eval(body, n)?
                .1
                .into_scalar()
                .ok_or("component set to a non-scalar")?;
            let t = env.symbols.get_mut(symbol).ok_or("unknown symbol")?;
            *t.get_mut(index) = x;
        }
        Assumption::Equals {
            symbol,
            formal,
            body,
            ..
        } => {
            let (ls, t) = env.eval(body, n)?;
            let perm: Vec<usize> = formal
                .iter()
                .map(|c| ls.iter().position(|x| x == c).unwrap_or(0))
                .collect();
            env.symbols.insert(symbol.clone(), t.permuted(&perm));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rules_integrate_known_moments() {
        for dim in [2usize, 3] {
            let rule = sphere_rule(dim);
            let total: f64 = rule.iter().map(|(_, w)| w).sum();
            assert!((total - 1.0).abs() < 1e-14);
            let m4: f64 = rule.iter().map(|(p, w)| w * p[0].powi(4)).sum();
            let want = if dim == 2 { 3.0 / 8.0 } else { 1.0 / 5.0 };
            assert!((m4 - want).abs() < 1e-14, "dim {dim}: {m4}");
        }
    }
}
