//! `explain` renders what the decision recorded (`check::decide_claim_recorded`): every
//! side's expansion as the exact decision computed it, also past a failing chain, and
//! the first states a sampled decision drew. An ordinary decision records nothing.

use cosserat_check::check::{decide, decide_claim_recorded};
use cosserat_check::derivation::{load_str, Verdict};

const FILE: &str = r#"
section = "t"
title = "explain"
dimension = 3
normal = "n"
tensors = ["A_ij"]
scalars = ["x", "y"]

[[claim]]
id = "two-chains"
printed = 'x'
expect = "fails"
reason = "the first chain is wrong"
chains = [["(x + y)^2", "x^2 + y^2"], ["A_ii", "A_kk"]]

[[claim]]
id = "sampled"
printed = 'x'
expect = "holds"
strategy = "numeric"
relation = "<="
sides = ["2 x y", "x^2 + y^2"]
"#;

#[test]
fn an_exact_record_holds_every_side_as_the_decision_expanded_it() {
    let file = load_str("t.toml", FILE).unwrap();
    let c = &file.claims[0];
    assert!(decide(&c.decls, &c.check).unwrap().record.is_none());
    let o = decide_claim_recorded(c).unwrap().outcome;
    assert_eq!(o.verdict(), Verdict::Fails);
    let record = o.record.expect("recorded");
    // The decision stops at the first chain; the record still has the second.
    let sides: Vec<(usize, usize)> = record
        .expansions
        .iter()
        .map(|e| (e.chain, e.side))
        .collect();
    assert_eq!(sides, vec![(1, 1), (1, 2), (2, 1), (2, 2)]);
    let first = record.expansions[0].components.as_ref().unwrap();
    assert_eq!(first[0].1, "x^2 + 2*x*y + y^2");
    let trace = record.expansions[2].components.as_ref().unwrap();
    assert_eq!(trace[0].1, "A_11 + A_22 + A_33");
    assert!(record.states.is_empty());
}

#[test]
fn a_sampled_record_holds_the_first_states_drawn() {
    let file = load_str("t.toml", FILE).unwrap();
    let c = &file.claims[1];
    assert!(decide(&c.decls, &c.check).unwrap().record.is_none());
    let o = decide_claim_recorded(c).unwrap().outcome;
    assert_eq!(o.verdict(), Verdict::Holds);
    let states = o.record.expect("recorded").states;
    assert_eq!(states.len(), 3);
    for s in &states {
        let x: f64 = s.point["x"].parse().unwrap();
        let y: f64 = s.point["y"].parse().unwrap();
        let (l, r) = (s.values[0].1.unwrap(), s.values[1].1.unwrap());
        // The values are the sides at the recorded point (shown to 9 digits).
        assert!((l - 2.0 * x * y).abs() < 1e-6 && (r - x * x - y * y).abs() < 1e-6);
    }
}

/// The definition the reader makes of each side of a matrix chain (`side 1.1`) is
/// typeset as its name in words, not as a product of `side` and the number 1.1.
#[test]
fn a_side_of_a_matrix_chain_is_typeset_by_its_name() {
    let (_, text) = crate::common::run_cli(
        &[
            "explain",
            "inverse-left",
            "--file",
            "tests/soundness/matrices.toml",
        ],
        false,
    );
    assert!(text.contains("typeset: $\\text{side 1.1} = "), "{text}");
    assert!(!text.contains("\\frac{11}{10}"), "{text}");
}

#[test]
fn the_hypotheses_of_an_identity_are_listed_once_each() {
    let (_, text) = crate::common::run_cli(
        &[
            "explain",
            "between-two-scalars-wrong",
            "--file",
            "tests/soundness/hypotheses.toml",
        ],
        false,
    );
    assert!(
        text.contains("Hypotheses (given): a > b; 0 < J2 < 1\n"),
        "{text}"
    );
    assert!(text.contains("values at a=1, s_11=1"), "{text}");
}
