//! Matrices (issue 13, item 4): literals, products, transposes, det, trace, inv, adj,
//! solve, entries, and the views between index notation and matrices in declared
//! position orders. Every claim that holds has a wrong twin that must come out `fails`
//! with a counterexample confirmed by the interpreter; singular systems and shape
//! errors are located input errors, never a division by zero or a guess.

use cosserat_check::decide::Strength;
use cosserat_check::derivation::Verdict;

use crate::common;

#[test]
fn matrix_claims_and_their_twins_are_decided_as_declared() {
    common::assert_as_declared("tests/soundness/matrices.toml", 34, |rows| {
        for r in rows {
            let o = &r.outcome;
            let id = r.claim.id.as_str();
            match o.verdict() {
                Verdict::Holds if id == "rotation-is-orthogonal" => {
                    assert_eq!(o.strength(), Strength::Sampled, "cos and sin are sampled");
                }
                Verdict::Holds => assert_eq!(o.strength(), Strength::Proof, "{id}"),
                Verdict::Fails => {
                    let cx = o.counterexample.as_ref().expect(id);
                    assert!(cx.reverified.is_some(), "{id}: confirmed by a second route");
                }
                v => panic!("{id}: {v:?}"),
            }
        }
        let evidence = |id: &str| common::evidence_of(rows, id);
        // An inverse holds where the determinant does not vanish, and says so.
        assert!(evidence("inverse-left").contains("holds where a*d - b*c ≠ 0"));
        // A matrix identity is checked in every entry; the failing entry is named.
        assert!(evidence("plane-cosserat-elasticity").contains("16 component checks"));
        assert!(evidence("plane-cosserat-elasticity-wrong").contains("[3,3]"));
        // The tensor view names the failing component by its indices.
        assert!(evidence("voigt-round-trip-wrong").contains("at k=1, l=2"));
    });
}

#[test]
fn the_worked_example_is_decided_as_declared() {
    common::assert_as_declared("derivations/examples/matrices.toml", 8, |_| {});
}

const HEADER: &str = "dimension = 2\nscalars = [\"x\", \"a\"]\ntensors = [\"s_ij\"]\norders = { voigt = [\"11\", \"22\", \"12\", \"21\"] }\ndefine = [\"A = [[1, a], [a, x]]\", \"v = [1, x]\"]";

fn claim(rest: &str) -> String {
    common::one_claim(HEADER, rest)
}

#[test]
fn malformed_matrix_statements_are_located_errors() {
    let cases = [
        (
            claim("sides = [\"A + v\", \"A\"]"),
            "this term is a column vector of 2, the others a 2×2 matrix",
        ),
        (
            claim("sides = [\"v A\", \"A\"]"),
            "the columns of the first (1) must match the rows of the second (2)",
        ),
        (
            claim("sides = [\"inv(v)\", \"v\"]"),
            "inv(…) needs a square matrix, but this is a column vector of 2",
        ),
        (
            claim("sides = [\"A\", \"x\"]"),
            "this side is a scalar or tensor, and the first matrix side a 2×2 matrix",
        ),
        (
            claim("sides = [\"s_ij A\", \"A\"]"),
            "a tensor with free index i multiplies a matrix",
        ),
        (
            claim("sides = [\"x / A\", \"x\"]"),
            "a divisor takes a scalar or a tensor, but this is a 2×2 matrix",
        ),
        (
            claim("sides = [\"sqrt(A)\", \"x\"]"),
            "sqrt takes a scalar or a tensor, but this is a 2×2 matrix",
        ),
        (
            claim("sides = [\"A[3,1]\", \"x\"]"),
            "entry (3, 1) is outside a 2×2 matrix",
        ),
        (
            claim("sides = [\"vector(s_ij, mandel_ij)\", \"v\"]"),
            "`mandel` is not a declared order",
        ),
        (
            claim("sides = [\"vector(s_ij, voigt_i)\", \"v\"]"),
            "the positions of `voigt` have 2 components, so it binds 2 indices",
        ),
        (
            claim("sides = [\"vector(s_ik, voigt_ij)\", \"v\"]"),
            "the orders bind the indices i, j, and the tensor has free indices i, k",
        ),
        (
            claim("sides = [\"tensor(A, voigt_ij)\", \"s_ij\"]"),
            "the orders give a column vector of 4, and this is a 2×2 matrix",
        ),
        (
            claim("sides = [\"det(s_ij)\", \"x\"]"),
            "det(…) takes a matrix, but this is a tensor",
        ),
        (
            claim("sides = [\"inv([[1, 2], [2, 4]])\", \"A\"]"),
            "this system is singular: the determinant of its matrix is identically zero",
        ),
        (
            claim("sides = [\"solve([[x, x], [1, 1]], v)\", \"v\"]"),
            "this system is singular",
        ),
        (
            claim("sides = [\"A\", \"A\"]\nassume = [\"x = [[1, 2], [3, 4]]\"]"),
            "an assumption takes a scalar or a tensor, but this is a 2×2 matrix",
        ),
        (
            claim("strategy = \"sign\"\nsides = [\"A\", \"A\"]\nrelation = \">\""),
            "compares two sides that are not matrices",
        ),
        (
            claim(
                "strategy = \"monotone\"\nfunction = \"A\"\nin = \"x\"\ndirection = \"increasing\"",
            ),
            "this field takes a scalar or a tensor, but this is a 2×2 matrix",
        ),
        (
            claim("sides = [\"x\", \"x\"]").replace("\"12\", \"21\"", "\"12\", \"3\""),
            "`3` is not a position of 2 components in 1..=2",
        ),
        (
            claim("sides = [\"x\", \"x\"]").replace("\"12\", \"21\"", "\"12\", \"12\""),
            "position `12` occurs twice in the order `voigt`",
        ),
        (
            claim("sides = [\"x\", \"x\"]\ndefine = [\"B = identity(13)\"]"),
            "a matrix side of 13 is more than the 12 the checker accepts",
        ),
    ];
    common::assert_located_errors(&cases);
}

/// Products whose rows and columns collapse to scalars midway, and sums that mix
/// scalars with matrices, are typed without a panic (found by the mutation sweep).
#[test]
fn collapsing_products_and_mixed_sums_are_typed() {
    let ok = claim("sides = [\"v^T v A\", \"(1 + x^2) A\"]\n[[claim]]\nid = \"d\"\nprinted = 'x'\nexpect = \"holds\"\nsides = [\"v^T v v^T v\", \"(1 + x^2)^2\"]");
    let f = cosserat_check::derivation::load_str("f.toml", &ok).expect("loads");
    let rows = cosserat_check::cli::decide_all(std::slice::from_ref(&f), None).unwrap();
    assert!(rows.iter().all(|r| r.as_expected()));
    for (sides, want) in [
        (
            "\"A - x\", \"A\"",
            "this term is a scalar or tensor, the others a 2×2 matrix",
        ),
        (
            "\"x - A\", \"A\"",
            "this term is a scalar or tensor, the others a 2×2 matrix",
        ),
    ] {
        let e = common::error_of(&claim(&format!("sides = [{sides}]")));
        assert!(e.contains(want), "{sides}\n→ {e}");
    }
}

/// A sampled matrix that is singular at every state (a set of positive measure) leaves
/// that claim undecided, with where and why; it is not a counterexample.
#[test]
fn a_matrix_singular_everywhere_leaves_a_sampled_claim_undecided() {
    let o = &common::outcomes_of(&claim(
        "strategy = \"numeric\"\nsamples = 50\nsides = [\"inv([[1, 2], [2, 4]]) cos(x)\", \"A\"]",
    ))[0];
    let ev = cosserat_check::report::evidence(o);
    assert_eq!(o.verdict(), Verdict::Undecided, "{ev}");
    assert!(
        ev.contains("singular matrix: its determinant is 0 here") && ev.contains("f.toml:"),
        "{ev}"
    );
}

/// A definition is defined where all its entries are: a counterexample to one entry of
/// a matrix whose other entries divide by G is taken where G ≠ 0, so that the
/// interpreter, which evaluates the whole matrix, confirms it (found by the mutation
/// sweep of eq. (57)).
#[test]
fn a_counterexample_avoids_the_poles_of_the_other_entries() {
    let text = claim("expect = \"fails\"\nreason = \"wrong\"\nsides = [\"B[2,2]\", \"2\"]\ndefine = [\"B = [[1 + a / x, 1], [1, a + x]]\"]")
        .replacen("expect = \"holds\"\n", "", 1);
    let outcomes = common::outcomes_of(&text);
    let o = &outcomes[0];
    assert_eq!(
        o.verdict(),
        Verdict::Fails,
        "{}",
        cosserat_check::report::evidence(o)
    );
    let cx = o.counterexample.as_ref().unwrap();
    assert!(cx.reverified.is_some(), "confirmed by the interpreter");
    assert_ne!(cx.point.get("x").map(String::as_str), Some("0"));
}

/// The kernel has no matrices: the reader writes each one out in definitions of its
/// entries (Laplace minors, cofactors, 1/det). That reading is checked here against an
/// independent route, Gauss–Jordan elimination over ℚ written in this test: for seeded
/// chains of products, sums, transposes, scalings, inverses, adjugates and solves of
/// integer matrices of sides 2 to 4, the chain's last matrix equals the eliminated
/// value (proved) and its determinant too, and a twin with one entry off by one fails.
#[test]
fn the_reading_of_matrices_agrees_with_gauss_jordan_elimination() {
    use num_rational::BigRational as Q;
    use num_traits::{One, Zero};
    type M = Vec<Vec<Q>>;
    fn q(n: i64) -> Q {
        Q::from_integer(n.into())
    }
    // det and inverse by elimination with row swaps; None when singular.
    fn eliminate(a: &M) -> (Q, Option<M>) {
        let n = a.len();
        let mut m: Vec<Vec<Q>> = a
            .iter()
            .enumerate()
            .map(|(i, r)| {
                let mut row = r.clone();
                row.extend((0..n).map(|j| if i == j { Q::one() } else { Q::zero() }));
                row
            })
            .collect();
        let mut det = Q::one();
        for c in 0..n {
            let Some(p) = (c..n).find(|&r| !m[r][c].is_zero()) else {
                return (Q::zero(), None);
            };
            if p != c {
                m.swap(p, c);
                det = -det;
            }
            let pivot = m[c][c].clone();
            det *= &pivot;
            for x in m[c].iter_mut() {
                *x /= &pivot;
            }
            for r in 0..n {
                if r != c && !m[r][c].is_zero() {
                    let f = m[r][c].clone();
                    let pivot_row = m[c].clone();
                    for (x, y) in m[r].iter_mut().zip(&pivot_row) {
                        *x -= &f * y;
                    }
                }
            }
        }
        (det, Some(m.into_iter().map(|r| r[n..].to_vec()).collect()))
    }
    fn mul(a: &M, b: &M) -> M {
        (0..a.len())
            .map(|i| {
                (0..b[0].len())
                    .map(|j| (0..b.len()).map(|k| &a[i][k] * &b[k][j]).sum())
                    .collect()
            })
            .collect()
    }
    fn text(m: &M) -> String {
        let rows: Vec<String> = m
            .iter()
            .map(|r| {
                let es: Vec<String> = r.iter().map(|x| format!("({x})")).collect();
                format!("[{}]", es.join(", "))
            })
            .collect();
        format!("[{}]", rows.join(", "))
    }
    let mut state: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut next = move |k: u64| {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 33) % k
    };
    let mut claims = String::new();
    let mut count = 0;
    for case in 0..24 {
        let n = 2 + (case % 3);
        let mut defs: Vec<(String, M)> = Vec::new();
        let mut lines = Vec::new();
        for k in 0..3 {
            // An invertible leaf: a random integer matrix, drawn again while singular.
            let leaf = loop {
                let m: M = (0..n)
                    .map(|_| (0..n).map(|_| q(next(7) as i64 - 3)).collect())
                    .collect();
                if eliminate(&m).1.is_some() {
                    break m;
                }
            };
            lines.push(format!("\"L{case}x{k} = {}\"", text(&leaf)));
            defs.push((format!("L{case}x{k}"), leaf));
        }
        for k in 0..4 {
            let pick = |r: u64| defs[r as usize % defs.len()].clone();
            let (x, y) = (pick(next(64)), pick(next(64)));
            let (body, value) = match next(7) {
                0 => (format!("{} {}", x.0, y.0), mul(&x.1, &y.1)),
                1 => (
                    format!("{} + {}", x.0, y.0),
                    x.1.iter()
                        .zip(&y.1)
                        .map(|(a, b)| a.iter().zip(b).map(|(u, v)| u + v).collect())
                        .collect(),
                ),
                2 => (
                    format!("{}^T", x.0),
                    (0..n)
                        .map(|i| (0..n).map(|j| x.1[j][i].clone()).collect())
                        .collect(),
                ),
                3 => (
                    format!("-2 {}", x.0),
                    x.1.iter()
                        .map(|r| r.iter().map(|u| u * q(-2)).collect())
                        .collect(),
                ),
                op => match eliminate(&x.1) {
                    (_, Some(inv)) if op == 4 => (format!("inv({})", x.0), inv),
                    (det, Some(inv)) if op == 5 => (
                        format!("adj({})", x.0),
                        inv.iter()
                            .map(|r| r.iter().map(|u| u * &det).collect())
                            .collect(),
                    ),
                    (_, Some(inv)) => (format!("solve({}, {})", x.0, y.0), mul(&inv, &y.1)),
                    // Singular: its product with the other instead.
                    (_, None) => (format!("{} {}", x.0, y.0), mul(&x.1, &y.1)),
                },
            };
            lines.push(format!("\"C{case}x{k} = {body}\""));
            defs.push((format!("C{case}x{k}"), value));
        }
        let (last, value) = defs.last().cloned().unwrap();
        let det = eliminate(&value).0;
        let mut off = value.clone();
        off[next(n as u64) as usize][next(n as u64) as usize] += q(1);
        claims.push_str(&format!(
            "[[claim]]\nid = \"c{case}\"\nprinted = 'x'\nexpect = \"holds\"\ndefine = [{}]\nsides = [\"{last}\", \"{}\"]\n\n\
             [[claim]]\nid = \"c{case}-det\"\nprinted = 'x'\nexpect = \"holds\"\ndefine = [{}]\nsides = [\"det({last})\", \"{det}\"]\n\n\
             [[claim]]\nid = \"c{case}-off\"\nprinted = 'x'\nexpect = \"fails\"\nreason = \"one entry is off by one\"\ndefine = [{}]\nsides = [\"{last}\", \"{}\"]\n\n",
            lines.join(", "),
            text(&value),
            lines.join(", "),
            lines.join(", "),
            text(&off),
        ));
        count += 3;
    }
    let file = format!("section = \"t\"\ntitle = \"t\"\ndimension = 2\n\n{claims}");
    let f = cosserat_check::derivation::load_str("f.toml", &file).expect("loads");
    let rows = cosserat_check::cli::decide_all(std::slice::from_ref(&f), None).unwrap();
    assert_eq!(rows.len(), count);
    for r in &rows {
        assert!(
            r.as_expected(),
            "{}: {}: {}",
            r.claim.id,
            r.outcome.verdict_text(),
            cosserat_check::report::evidence(&r.outcome)
        );
        if r.outcome.verdict() == Verdict::Holds {
            assert_eq!(r.outcome.strength(), Strength::Proof, "{}", r.claim.id);
        }
    }
}

/// Large matrices: a 12×12 inverse (the largest side) is written out in about 28,000
/// definitions and proved; a statement that would need more than the reader's bound
/// (four nested 12×12 inverses) is undecided with that reason, never a verdict.
#[test]
fn a_twelve_by_twelve_inverse_is_proved_and_a_larger_statement_undecided() {
    let n = 12;
    let rows: Vec<String> = (0..n)
        .map(|i| {
            let es: Vec<String> = (0..n)
                .map(|j| (u8::from(i == j) + u8::from(j == i + 1)).to_string())
                .collect();
            format!("[{}]", es.join(", "))
        })
        .collect();
    let file = format!(
        "section = \"t\"\ntitle = \"t\"\ndimension = 2\ndefine = [\"A = [{}]\"]\n\n\
         [[claim]]\nid = \"inverse\"\nprinted = 'x'\nexpect = \"holds\"\nsides = [\"det(inv(A))\", \"1\"]\n\n\
         [[claim]]\nid = \"too-large\"\nprinted = 'x'\nexpect = \"undecided\"\nreason = \"past the bound\"\n\
         sides = [\"det(inv(inv(inv(inv(A)))))\", \"1\"]\n",
        rows.join(", ")
    );
    let outcomes = common::outcomes_of(&file);
    assert_eq!(outcomes[0].verdict(), Verdict::Holds);
    assert_eq!(outcomes[0].strength(), Strength::Proof);
    assert_eq!(outcomes[1].verdict(), Verdict::Undecided);
    let why = cosserat_check::report::evidence(&outcomes[1]);
    assert!(why.contains("more than 100000 definitions"), "{why}");
}
