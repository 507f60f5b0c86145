//! The one contraction of every route (`algebra::einsum`) against a reference built another
//! way: the outer product of all factors, a basis vector traced against every fixed
//! slot, then pairwise traces of repeated letters and a permutation into the output
//! order, all with `Tensor`'s own `outer`, `contract` and `permuted`. Random tensors
//! of total rank up to 6, in 2D and 3D, in exact rationals and in polynomials under
//! the work budget.

use crate::support::products::Products;
use approx::assert_relative_eq;
use cosserat_check::algebra::einsum::{einsum, Plain, Polynomials, Slot};
use cosserat_check::algebra::Tensor;
use cosserat_check::decide::random::Rng;
use cosserat_check::kernel::{Poly, Rational, VarTable};
use num_dual::Dual64;
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

#[test]
fn epsilon_delta_identity_in_3d() {
    // ε_ijk ε_imn = δ_jm δ_kn − δ_jn δ_km, checked over all 81 components.
    let e = Tensor::<i64>::levi_civita(3);
    let d = Tensor::<i64>::delta(3);
    let lhs = e.outer(&e).contract(0, 3);
    let rhs = Tensor::from_fn(3, 4, |x| {
        d.get(&[x[0], x[2]]) * d.get(&[x[1], x[3]]) - d.get(&[x[0], x[3]]) * d.get(&[x[1], x[2]])
    });
    assert_eq!(lhs, rhs);
    // Contracting once more: ε_ijk ε_ijn = 2 δ_kn.
    assert_eq!(lhs.contract(0, 2), d.map(|x| 2 * x));
}

#[test]
fn rank_six_outer_products_and_contractions() {
    // δ_ij δ_kl δ_mn contracted as (i,j), (k,l), (m,n): 3·3·3 = 27 in 3D, 8 in 2D.
    for (dim, want) in [(3usize, 27i64), (2, 8)] {
        let d = Tensor::<i64>::delta(dim);
        let t = d.outer(&d).outer(&d);
        assert_eq!(t.rank(), 6);
        assert_eq!(t.components().len(), dim.pow(6));
        let s = t.contract(4, 5).contract(2, 3).contract(0, 1);
        assert_eq!(s.into_scalar(), Some(want));
    }
}

#[test]
fn generic_over_rationals_polynomials_and_floats() {
    let d = Tensor::<Rational>::delta(3);
    assert_eq!(d.contract(0, 1).into_scalar(), Some(Rational::int(3)));
    let dp = Tensor::<Poly>::delta(2);
    assert_eq!(
        dp.contract(0, 1).into_scalar(),
        Some(Poly::constant(Rational::int(2)))
    );
    let v = Tensor::from_fn(3, 1, |i| (i[0] + 1) as f64);
    let norm2 = v.outer(&v).contract(0, 1).into_scalar().unwrap();
    assert_relative_eq!(norm2, 14.0, epsilon = 1e-15);
}

#[test]
fn generic_over_dual_numbers_carries_derivatives() {
    // |v|² with v = (x, 2x, 3x): d/dx at x = 1 is 2·14·x = 28.
    let x = Dual64::from(1.0).derivative();
    let v = Tensor::from_fn(3, 1, |i| x * ((i[0] + 1) as f64));
    let norm2 = v.outer(&v).contract(0, 1).into_scalar().unwrap();
    assert_relative_eq!(norm2.re, 14.0, epsilon = 1e-15);
    assert_relative_eq!(norm2.eps, 28.0, epsilon = 1e-12);
}
