//! Checked expressions equal up to the letters of their summed indices.
//!
//! `⟨t_b t_b⟩` and `⟨t_k t_k⟩` are the same expression: a summed index is a bound
//! variable, and renaming it consistently changes nothing. A printed statement and its
//! transcription often differ only so, and proving that they agree needs no evaluation.

use super::check::{Node, NodeKind, Slot};
use std::collections::BTreeMap;

/// Whether `b` is `a` with its index letters renamed by one bijection that leaves the
/// free letters of the whole as they are: the same tree, targets, constants, functions
/// and fixed slots, and at each slot of `a` with letter `x`, the letter `σ(x)` in `b`.
///
/// Why that is the same value in any context: a bijection keeps which slots share a
/// letter, so every contraction sums the same components together, and it fixes the
/// free slots of the whole, so the result's slots are the same. Only the order in
/// which an inner node lists its own free letters may change, and every node that reads
/// an inner value aligns it by letter. Derivatives with respect to a symbol and matrix
/// constructs (whose orders name letters of their own) are not compared: `false`.
pub fn same_up_to_summed_letters(a: &Node, b: &Node) -> bool {
    let mut renaming = Renaming::default();
    a.free.len() == b.free.len()
        && a.free
            .iter()
            .zip(&b.free)
            .all(|((x, _), (y, _))| x == y && renaming.pair(*x, *y))
        && same(a, b, &mut renaming)
}

/// A bijection between letters, built as pairs are met.
#[derive(Default)]
struct Renaming {
    forward: BTreeMap<char, char>,
    backward: BTreeMap<char, char>,
}

impl Renaming {
    /// Adds `x ↦ y`; false when it contradicts a pair already met.
    fn pair(&mut self, x: char, y: char) -> bool {
        match (self.forward.get(&x), self.backward.get(&y)) {
            (None, None) => {
                self.forward.insert(x, y);
                self.backward.insert(y, x);
                true
            }
            (Some(&y2), Some(&x2)) => y2 == y && x2 == x,
            _ => false,
        }
    }

    fn slot(&mut self, s: &Slot, t: &Slot) -> bool {
        match (s, t) {
            (Slot::Letter(x), Slot::Letter(y)) => self.pair(*x, *y),
            (Slot::Fixed(i), Slot::Fixed(j)) => i == j,
            _ => false,
        }
    }
}

fn same(a: &Node, b: &Node, r: &mut Renaming) -> bool {
    use NodeKind as K;
    match (&a.kind, &b.kind) {
        (K::Const(p), K::Const(q)) => p == q,
        (
            K::Leaf {
                target: t,
                slots: s,
            },
            K::Leaf {
                target: u,
                slots: v,
            },
        ) => t == u && s.len() == v.len() && s.iter().zip(v).all(|(x, y)| r.slot(x, y)),
        (K::Sum(xs), K::Sum(ys)) | (K::Product(xs), K::Product(ys)) => {
            xs.len() == ys.len() && xs.iter().zip(ys).all(|(x, y)| same(x, y, r))
        }
        (K::Div(x1, x2), K::Div(y1, y2)) => same(x1, y1, r) && same(x2, y2, r),
        (K::Neg(x), K::Neg(y)) | (K::Avg(x), K::Avg(y)) | (K::MaxN(x), K::MaxN(y)) => same(x, y, r),
        (K::Pow(x, k), K::Pow(y, m)) => k == m && same(x, y, r),
        (K::Apply(f, x), K::Apply(g, y)) => f == g && same(x, y, r),
        (K::Apply2(f, x1, x2), K::Apply2(g, y1, y2)) => {
            f == g && same(x1, y1, r) && same(x2, y2, r)
        }
        (K::Deriv(x, s), K::Deriv(y, t)) => r.slot(s, t) && same(x, y, r),
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check::{Decls, DefSig, Scope};
    use crate::parser::parse_expr;

    fn node(src: &str) -> Node {
        let decls = Decls {
            dim: 3,
            normal: Some("n".into()),
            symbols: [("t", 1), ("s", 2), ("c", 2), ("R_g", 0), ("u", 1)]
                .into_iter()
                .map(|(k, v)| (k.to_string(), v))
                .collect(),
            fields: [("u".to_string(), vec![true; 3])].into_iter().collect(),
            position: Some("x".into()),
            ..Decls::default()
        };
        let defs = vec![DefSig {
            name: "tt".into(),
            formal: vec!['k'],
            shape: None,
        }];
        Scope {
            decls: &decls,
            defs: &defs,
        }
        .check(&parse_expr(src).unwrap())
        .unwrap()
    }

    fn same(a: &str, b: &str) -> bool {
        same_up_to_summed_letters(&node(a), &node(b))
    }

    #[test]
    fn summed_letters_may_be_renamed() {
        for (a, b) in [
            ("avg(tt_b tt_b)", "avg(tt_k tt_k)"),
            ("s_ij s_ij - s_ij s_ji", "s_ab s_ab - s_ab s_ba"),
            ("R_g n_a n_b s_ac c_bc", "R_g n_k n_m s_ki c_mi"),
            ("t_i s_ij", "t_k s_kj"),
            ("u_j,i s_ij", "u_b,a s_ab"),
            ("s_11 + t_a t_a", "s_11 + t_b t_b"),
        ] {
            assert!(same(a, b), "{a} | {b}");
            assert!(same(b, a), "{b} | {a}");
        }
    }

    #[test]
    fn free_letters_order_and_structure_are_kept() {
        for (a, b) in [
            // A free letter renamed, or free letters exchanged.
            ("t_i", "t_j"),
            ("s_ij", "s_ji"),
            ("t_i s_jk t_k", "t_j s_ik t_k"),
            // Two summed letters merged into one, or the pairing changed.
            ("s_ab s_ab", "s_ab s_ba"),
            ("t_a t_a t_b t_b", "t_a t_b t_a t_b"),
            ("s_ij s_ij - s_ij s_ji", "s_ab s_ab - s_ab s_ab"),
            // A renaming that is not one bijection over the whole.
            ("t_a t_a + t_b t_b", "t_a t_a + t_a t_a"),
            // A fixed slot, a number, a target, a function, a derivative's slot.
            ("s_12", "s_21"),
            ("1/3 t_a t_a", "1/15 t_a t_a"),
            ("s_aa", "c_aa"),
            ("sqrt(t_a t_a)", "abs(t_a t_a)"),
            ("u_j,i s_ij", "u_i,j s_ij"),
            ("avg(n_a n_a)", "n_a n_a"),
        ] {
            assert!(!same(a, b), "{a} | {b}");
            assert!(!same(b, a), "{b} | {a}");
        }
    }
}
