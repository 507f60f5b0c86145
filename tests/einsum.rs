//! The one contraction of every route (`algebra::einsum`) against a reference built another
//! way: the outer product of all factors, a basis vector traced against every fixed
//! slot, then pairwise traces of repeated letters and a permutation into the output
//! order, all with `Tensor`'s own `outer`, `contract` and `permuted`. Random tensors
//! of total rank up to 6, in 2D and 3D, in exact rationals and in polynomials under
//! the work budget.

use cosserat_check::algebra::einsum::{einsum, Plain, Polynomials, Slot};
use cosserat_check::algebra::Tensor;
use cosserat_check::decide::random::Rng;
use cosserat_check::kernel::{Poly, Rational, VarTable};
use num_traits::Zero;

/// One random contraction: factor ranks, their slots and the output letters. Every
/// letter occurs once (free, in `out`) or twice (summed), as the language allows.
struct Case {
    dim: usize,
    ranks: Vec<usize>,
    slots: Vec<Vec<Slot>>,
    out: Vec<char>,
}

fn random_case(rng: &mut Rng) -> Case {
    let dim = 2 + rng.below(2);
    let total = 1 + rng.below(6);
    let factors = 1 + rng.below(total.min(3));
    // Split `total` slots among the factors (each at least... zero is allowed: scalars).
    let mut ranks = vec![0; factors];
    for _ in 0..total {
        let k = rng.below(factors);
        ranks[k] += 1;
    }
    let mut flat: Vec<Slot> = Vec::with_capacity(total);
    let mut out = Vec::new();
    let letters = ['i', 'j', 'k', 'l', 'm', 'p'];
    let mut next_letter = 0;
    let mut positions: Vec<usize> = (0..total).collect();
    // Shuffle slot positions, then pair some of them up.
    for a in (1..positions.len()).rev() {
        let b = rng.below(a + 1);
        positions.swap(a, b);
    }
    let mut assigned: Vec<Option<Slot>> = vec![None; total];
    let mut it = positions.into_iter().peekable();
    while let Some(p) = it.next() {
        match rng.below(3) {
            0 => assigned[p] = Some(Slot::Fixed(rng.below(dim))),
            1 if it.peek().is_some() => {
                let q = it.next().expect("peeked");
                let c = letters[next_letter];
                next_letter += 1;
                assigned[p] = Some(Slot::Letter(c));
                assigned[q] = Some(Slot::Letter(c));
            }
            _ => {
                let c = letters[next_letter];
                next_letter += 1;
                assigned[p] = Some(Slot::Letter(c));
                out.push(c);
            }
        }
    }
    flat.extend(
        assigned
            .into_iter()
            .map(|s| s.expect("every slot assigned")),
    );
    for a in (1..out.len()).rev() {
        let b = rng.below(a + 1);
        out.swap(a, b);
    }
    let mut slots = Vec::new();
    let mut start = 0;
    for &r in &ranks {
        slots.push(flat[start..start + r].to_vec());
        start += r;
    }
    Case {
        dim,
        ranks,
        slots,
        out,
    }
}

/// The reference: outer products, traces, a permutation.
fn reference<T>(dim: usize, tensors: &[Tensor<T>], slots: &[Vec<Slot>], out: &[char]) -> Tensor<T>
where
    T: Clone + Zero + num_traits::One + std::ops::Mul<Output = T>,
{
    let mut acc = Tensor::scalar(dim, T::one());
    let mut labels: Vec<Slot> = Vec::new();
    for (t, s) in tensors.iter().zip(slots) {
        acc = acc.outer(t);
        labels.extend(s.iter().copied());
    }
    // A fixed slot v: trace against the basis vector e_v.
    while let Some(pos) = labels.iter().position(|s| matches!(s, Slot::Fixed(_))) {
        let Slot::Fixed(v) = labels[pos] else {
            unreachable!()
        };
        let e = Tensor::from_fn(dim, 1, |i| if i[0] == v { T::one() } else { T::zero() });
        acc = acc.outer(&e);
        let last = labels.len();
        acc = acc.contract(pos, last);
        labels.remove(pos);
    }
    // A letter twice: trace the pair.
    loop {
        let pair = (0..labels.len()).find_map(|a| {
            (a + 1..labels.len())
                .find(|&b| labels[a] == labels[b])
                .map(|b| (a, b))
        });
        let Some((a, b)) = pair else { break };
        acc = acc.contract(a, b);
        labels.remove(b);
        labels.remove(a);
    }
    let perm: Vec<usize> = out
        .iter()
        .map(|c| {
            labels
                .iter()
                .position(|s| *s == Slot::Letter(*c))
                .expect("free letter")
        })
        .collect();
    acc.permuted(&perm)
}

fn random_rational(rng: &mut Rng) -> Rational {
    Rational::ratio(rng.below(11) as i64 - 5, 1 + rng.below(4) as i64).expect("nonzero")
}

#[test]
fn einsum_agrees_with_outer_products_and_traces_in_rationals() {
    let mut rng = Rng::new(0xE175_0001);
    let mut nontrivial = 0;
    for _ in 0..400 {
        let case = random_case(&mut rng);
        let tensors: Vec<Tensor<Rational>> = case
            .ranks
            .iter()
            .map(|&r| Tensor::from_fn(case.dim, r, |_| random_rational(&mut rng)))
            .collect();
        let factors: Vec<_> = tensors
            .iter()
            .zip(&case.slots)
            .map(|(t, s)| (t, s.clone()))
            .collect();
        let got = Plain::einsum(case.dim, &factors, &case.out);
        let want = reference(case.dim, &tensors, &case.slots, &case.out);
        assert_eq!(
            got, want,
            "ranks {:?} slots {:?} out {:?}",
            case.ranks, case.slots, case.out
        );
        nontrivial += usize::from(got.components().iter().any(|q| !q.is_zero()));
    }
    assert!(
        nontrivial > 300,
        "the cases must exercise nonzero results: {nontrivial}"
    );
}

#[test]
fn einsum_agrees_in_polynomials_under_the_budget() {
    let mut rng = Rng::new(0xE175_0002);
    let mut names = VarTable::new();
    let vars: Vec<Poly> = ["a", "b", "c"]
        .iter()
        .map(|n| Poly::var(names.intern(n)))
        .collect();
    for _ in 0..150 {
        let case = random_case(&mut rng);
        let tensors: Vec<Tensor<Poly>> = case
            .ranks
            .iter()
            .map(|&r| {
                Tensor::from_fn(case.dim, r, |_| {
                    // Sparse on purpose: zeros exercise the skipped products.
                    match rng.below(4) {
                        0 => Poly::zero(),
                        k => &vars[k - 1] + &Poly::constant(random_rational(&mut rng)),
                    }
                })
            })
            .collect();
        let factors: Vec<_> = tensors
            .iter()
            .zip(&case.slots)
            .map(|(t, s)| (t, s.clone()))
            .collect();
        let mut work = usize::MAX;
        let got = einsum(
            &mut Polynomials {
                work_left: &mut work,
            },
            case.dim,
            &factors,
            &case.out,
        )
        .expect("unbounded budget");
        let want = reference(case.dim, &tensors, &case.slots, &case.out);
        assert_eq!(
            got, want,
            "ranks {:?} slots {:?} out {:?}",
            case.ranks, case.slots, case.out
        );
    }
}

#[test]
fn a_wrong_contraction_is_detected_by_the_reference() {
    // The reference is not blind: summing the wrong pair of slots differs.
    let a = Tensor::from_fn(3, 2, |i| Rational::int((3 * i[0] + i[1]) as i64));
    let (i, j) = (Slot::Letter('i'), Slot::Letter('j'));
    let right = reference(3, std::slice::from_ref(&a), &[vec![i, j]], &['j', 'i']);
    let wrong = Plain::einsum(3, &[(&a, vec![i, j])], &['i', 'j']);
    assert_ne!(right, wrong, "the transpose must differ from the tensor");
    assert_eq!(right, Plain::einsum(3, &[(&a, vec![i, j])], &['j', 'i']));
}
