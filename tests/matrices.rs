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
