//! What a counterexample shows: only the symbols the
//! statement reads, auxiliary numbers (a central difference, an eigenvalue) apart from
//! the point, and numbers rounded to significant digits rather than fixed decimals.

use cosserat_check::check::Decided;
use cosserat_check::cli::decide_all;
use cosserat_check::decide::Counterexample;
use cosserat_check::derivation::load_files;
use cosserat_check::report;

const FILE: &str = "tests/user/irrelevant-symbols.toml";

fn decided<T>(f: impl FnOnce(&[Decided<'_>]) -> T) -> T {
    let files = load_files(&[FILE]).unwrap();
    let rows = decide_all(&files, None).unwrap();
    f(&rows)
}

fn counterexample<'a>(rows: &'a [Decided<'_>], id: &str) -> &'a Counterexample {
    let row = rows.iter().find(|r| r.claim.id == id).unwrap();
    assert_eq!(row.outcome.verdict().as_str(), "fails", "{id}");
    row.outcome.counterexample.as_ref().unwrap()
}

fn names(cx: &Counterexample) -> Vec<String> {
    cx.point
        .keys()
        .map(|k| k.split('_').next().unwrap().to_owned())
        .collect()
}

#[test]
fn the_point_holds_only_the_symbols_the_statement_reads() {
    decided(|rows| {
        for (id, allowed) in [
            ("exact-slip", &["lambda", "G"][..]),
            ("numeric-slip", &["lambda", "G"][..]),
            ("gradient-slip", &["lambda", "sigma"][..]),
            ("convex-slip", &["lambda", "G"][..]),
        ] {
            let cx = counterexample(rows, id);
            let shown = names(cx);
            assert!(!shown.is_empty(), "{id}: an empty point");
            for name in &shown {
                assert!(
                    allowed.contains(&name.as_str()),
                    "{id} shows {name}: {cx:?}"
                );
            }
            assert!(!shown.iter().any(|n| n == "D" || n == "E"), "{id}");
        }
    })
}

#[test]
fn auxiliary_numbers_are_kept_apart_from_the_point() {
    decided(|rows| {
        let gradient = counterexample(rows, "gradient-slip");
        assert!(gradient.aux.contains_key("central difference"));
        assert!(!gradient.point.contains_key("central difference"));
        let convex = counterexample(rows, "convex-slip");
        let eigenvalue: f64 = convex.aux["smallest eigenvalue"].parse().unwrap();
        assert!(eigenvalue < 0.0);
        assert!(!convex.point.contains_key("smallest eigenvalue"));
    })
}

#[test]
fn a_convexity_failure_row_carries_its_eigenvalue_and_point() {
    decided(|rows| {
        let row = rows.iter().find(|r| r.claim.id == "convex-slip").unwrap();
        let evidence = report::evidence(&row.outcome);
        assert!(
            !evidence.contains("; ;") && !evidence.ends_with("; "),
            "{evidence}"
        );
        assert!(evidence.contains("smallest eigenvalue -"), "{evidence}");
        assert!(evidence.contains("lambda="), "{evidence}");
    })
}

#[test]
fn numbers_have_significant_digits_not_fixed_decimals() {
    decided(|rows| {
        for id in ["numeric-slip", "gradient-slip", "convex-slip"] {
            let cx = counterexample(rows, id);
            let numbers = cx
                .point
                .values()
                .chain(cx.aux.values())
                .chain(cx.lhs_value.iter())
                .chain(cx.rhs_value.iter());
            for v in numbers {
                let Ok(x) = v.parse::<f64>() else { continue };
                let digits = v.trim_start_matches('-').replace('.', "");
                let significant = digits.trim_start_matches('0');
                assert!(significant.len() <= 10, "{id}: {v}");
                assert!(
                    !v.contains('.') || !v.ends_with('0'),
                    "{id}: trailing zero in {v}"
                );
                assert!(x != 0.0, "{id}: a zero coordinate is shown: {v}");
            }
        }
    })
}

#[test]
fn small_values_keep_their_significant_digits() {
    use cosserat_check::digits::{significant, POINT, VALUE};
    let files = load_files(&["tests/user/small-values.toml"]).unwrap();
    let rows = decide_all(&files, None).unwrap();
    let cx = counterexample(&rows, "small-slip");
    let shown = &cx.point["lambda"];
    let x: f64 = shown.parse().unwrap();
    assert!((1e-5..=2e-5).contains(&x), "{shown}");
    // Six significant digits (a fixed six decimals would print 0.000015).
    assert_eq!(shown, &significant(x, POINT));
    let mantissa = shown.split('e').next().unwrap().replace(['.', '-'], "");
    assert!(mantissa.trim_start_matches('0').len() >= 5, "{shown}");
    for v in [&cx.lhs_value, &cx.rhs_value] {
        let v = v.as_deref().unwrap();
        let y: f64 = v.parse().unwrap();
        assert_eq!(v, significant(y, VALUE), "{v}");
        assert!(
            v.contains('e'),
            "{v}: a value of 1e-5 is written in scientific notation"
        );
    }
}

/// A counterexample names its variables as the paper prints them, through the notation
/// table read backwards, and its point is sparse: the one product that the difference
/// needs, each factor 1, every other variable 0.
#[test]
fn the_point_is_sparse_and_shown_in_the_papers_notation() {
    let text = r#"
section = "1"
title = "t"
dimension = 3
scalars = ["tb", "k"]
tensors = ["s1_ij", "a_i"]

[notation]
'\bar\tau' = "tb"
'\sigma_{ij}^{(1)}' = "s1_ij"

[[claim]]
id = "slip"
printed = '\bar\tau \sigma_{ij}^{(1)} a_i a_j = 0'
expect = "fails"
reason = "planted"
"#;
    let files = vec![cosserat_check::derivation::load_str("notation.toml", text).unwrap()];
    let rows = decide_all(&files, None).unwrap();
    let refs: Vec<&Decided<'_>> = rows.iter().collect();
    let cx = counterexample(&rows, "slip");
    let nonzero: Vec<&String> = cx
        .point
        .iter()
        .filter(|(_, v)| *v != "0")
        .map(|(k, _)| k)
        .collect();
    assert_eq!(
        nonzero,
        ["a_3", "s1_33", "tb"],
        "not sparse: {:?}",
        cx.point
    );
    let table = report::markdown::render(&refs, &report::paper_of(&refs, &[]));
    assert!(
        table.contains(r"(in the paper's notation, $\sigma_{33}^{(1)} = 1$, $\bar\tau = 1$)"),
        "{table}"
    );
    let html = report::html::render(&refs, "p");
    assert!(html.contains("in the paper's notation, <math"), "{html}");
}
