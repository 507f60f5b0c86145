//! The proof checker: every claim of the paper is decided, and the test fails when
//! any verdict differs from the one its derivation file declares. The derivation
//! table (Markdown and JSON) is snapshot-tested, and every exact verdict is
//! cross-checked by the independent floating-point route.

use crate::support::float;
use cosserat_check::check::Decided;
use cosserat_check::cli::decide_all;
use cosserat_check::decide::Method;
use cosserat_check::derivation::{load_dir, DerivationFile, Strategy, Verdict};
use cosserat_check::report;
use std::path::Path;
use std::sync::OnceLock;

fn corpus() -> Vec<DerivationFile> {
    load_dir(&Path::new(env!("CARGO_MANIFEST_DIR")).join("derivations"))
        .unwrap_or_else(|e| panic!("{e}"))
}

/// The whole paper decided once and shared by the tests of this file (the numeric
/// strategies make a run take seconds).
fn decided() -> &'static [Decided<'static>] {
    static ROWS: OnceLock<Vec<Decided<'static>>> = OnceLock::new();
    ROWS.get_or_init(|| {
        let files: &'static [DerivationFile] = Box::leak(corpus().into_boxed_slice());
        decide_all(files, None).unwrap_or_else(|e| panic!("{e}"))
    })
}

/// Snapshots of the table, with the checkout's location removed from the file paths
/// that diagnostics name (so the snapshot is the same in every clone).
fn snapshot(name: &str, value: &str) {
    let value = value.replace(concat!(env!("CARGO_MANIFEST_DIR"), "/"), "");
    insta::with_settings!({
        snapshot_path => concat!(env!("CARGO_MANIFEST_DIR"), "/snapshots"),
        prepend_module_to_snapshot => false,
    }, {
        insta::assert_snapshot!(name, &value);
    });
}

#[test]
fn every_verdict_is_the_declared_one() {
    let rows = decided();
    let wrong: Vec<String> = rows
        .iter()
        .filter(|r| !r.as_expected())
        .map(|r| {
            format!(
                "{}: decided {} (declared {}); correction {:?}",
                r.claim.id,
                r.outcome.verdict(),
                r.claim.expect,
                r.correction.as_ref().map(|o| o.verdict())
            )
        })
        .collect();
    assert!(
        wrong.is_empty(),
        "unexpected verdicts:\n{}",
        wrong.join("\n")
    );
}

#[test]
fn the_paper_claims_of_sections_3_to_5_are_all_present() {
    let files = corpus();
    let ids: Vec<&str> = files
        .iter()
        .flat_map(|f| &f.claims)
        .map(|c| c.id.as_str())
        .collect();
    for id in [
        "eq25",
        "eq26",
        "odd-averages",
        "eq27",
        "eq28",
        "eq30",
        "eq31",
        "eq32",
        "eq33",
        "eq35",
        "eq36",
        "eq37",
        "eq38",
        "eq39",
        "eq7",
        "eq8",
        "eq9",
        "eq13",
        "eq14",
        "eq16",
        "eq17",
        "eq18",
        "eq19",
        "eq20",
        "eq21",
        "eq22",
        "eq23",
        "eq24",
        "eq41",
        "eq42",
        "eq43",
        "eq44",
        "eq46",
        "eq47",
        "eq49",
        "fig3-mohr-circle",
        "eq50",
        "fig4-not-circle",
        "sec5-mv-equals-f2",
        "sec5-f2-dominates-f1",
        "convex-F1",
        "convex-F2",
        "grad-F1",
        "grad-F1star",
        "grad-F2",
        "grad-FMV",
        "grad-T2-3d",
        "grad-Mc2-3d",
    ] {
        assert!(ids.contains(&id), "claim {id} is missing");
    }
}

#[test]
fn every_non_holding_verdict_carries_evidence_and_a_reason() {
    for r in decided() {
        if r.outcome.verdict() != Verdict::Holds {
            assert!(r.claim.reason.is_some(), "{}: no reason", r.claim.id);
            let cx = r.outcome.counterexample.as_ref().expect("a counterexample");
            assert!(
                cx.ill_formed.is_some() || !cx.difference.is_empty() || cx.lhs_value.is_some(),
                "{}: empty counterexample",
                r.claim.id
            );
            if r.outcome.verdict() == Verdict::Conditional {
                // Sampled strategies state the domain in their numeric evidence, the
                // exact ones in their finding ("holds on …" for a rational function).
                let numeric = r.outcome.numeric.as_ref().and_then(|n| n.domain.as_ref());
                let symbolic = r
                    .outcome
                    .finding
                    .as_ref()
                    .map(cosserat_check::report::words::finding)
                    .filter(|d| d.contains("holds for") || d.contains("holds on"));
                assert!(
                    numeric.is_some() || symbolic.is_some(),
                    "{}: a conditional verdict states its domain",
                    r.claim.id
                );
            }
            if !cx.difference.is_empty() {
                // A counterexample from a difference polynomial also names a point.
                assert!(
                    cx.lhs_value.is_some() && cx.rhs_value.is_some(),
                    "{}: no values at a point",
                    r.claim.id
                );
            }
        } else {
            assert!(
                r.outcome.checks > 0,
                "{}: holds without a single check",
                r.claim.id
            );
        }
    }
}

#[test]
fn exact_verdicts_agree_with_the_independent_float_route() {
    let mut compared = 0;
    for r in decided() {
        let mut pairs = vec![(&r.claim.check, &r.outcome)];
        if let (Some(c), Some(o)) = (&r.claim.correction, &r.correction) {
            pairs.push((&c.check, o));
        }
        for (check, outcome) in pairs {
            if !matches!(
                check.strategy,
                Strategy::Exact { .. } | Strategy::Proportional { .. }
            ) {
                continue;
            }
            assert_eq!(
                outcome.method == Method::IndexCheck,
                check.chains.iter().flatten().any(|s| s.node.is_err())
            );
            if let Some(v) = float::decide(&r.claim.decls, check, 5, 2024)
                .unwrap_or_else(|e| panic!("{}: {e}", r.claim.id))
            {
                assert_eq!(
                    v,
                    outcome.verdict(),
                    "{}: exact and float routes disagree",
                    r.claim.id
                );
                compared += 1;
            }
        }
    }
    assert!(compared >= 15, "only {compared} statements cross-checked");
}

#[test]
fn derivation_table_markdown() {
    snapshot("derivation_table_markdown", &{
        let rows = report::refs(decided());
        report::markdown::render(&rows, &report::paper_of(&rows, &[]))
    });
}

#[test]
fn derivation_table_json() {
    let rows = report::refs(decided());
    let json = report::json::render(&rows, &report::paper_of(&rows, &[]));
    let v: serde_json::Value = serde_json::from_str(&json).expect("valid JSON");
    for key in ["paper", "claims", "summary"] {
        assert!(v.get(key).is_some(), "missing {key}");
    }
    for c in v["claims"].as_array().unwrap() {
        for key in [
            "id",
            "section",
            "statement",
            "verdict",
            "method",
            "expected",
            "checks",
            "counterexample",
            "correction",
        ] {
            assert!(c.get(key).is_some(), "claim {} lacks {key}", c["id"]);
        }
    }
    snapshot("derivation_table_json", &json);
}

#[test]
fn output_is_deterministic() {
    // A second, independent run gives byte-identical output.
    let files = corpus();
    let render = |rows: &[Decided<'_>]| {
        let rows = report::refs(rows);
        report::json::render(&rows, &report::paper_of(&rows, &[]))
    };
    let again = render(&decide_all(&files, None).unwrap());
    assert_eq!(render(decided()), again);
}

#[test]
fn the_readme_excerpt_matches_the_table() {
    let readme = cosserat_check::cli::GUIDE.join("\n");
    let rows = report::refs(decided());
    let table = report::markdown::render(&rows, &report::paper_of(&rows, &[]));
    let rows: Vec<&str> = readme
        .lines()
        .filter(|l| l.starts_with("| eq") && l[4..].starts_with(|c: char| c.is_ascii_digit()))
        .collect();
    assert!(!rows.is_empty(), "the guide shows no table rows");
    for row in rows {
        assert!(
            table.lines().any(|l| l == row),
            "guide row is out of date:\n{row}"
        );
    }
}

/// The compact excerpt in the guide is the compact table's own lines (no terminal
/// width, no colour).
#[test]
fn the_compact_excerpt_in_the_guide_matches_the_table() {
    let guide = cosserat_check::cli::GUIDE.join("\n");
    let rows = report::refs(decided());
    let table = report::compact::render(
        &rows,
        &report::paper_of(&rows, &[]),
        (false, None),
        "",
        false,
    );
    let excerpt: Vec<&str> = guide
        .lines()
        .filter(|l| l.starts_with("eq") || l.starts_with("sec5-"))
        .filter(|l| {
            l.contains("  holds  ") || l.contains("  FAILS  ") || l.contains("  conditional  ")
        })
        .collect();
    assert!(excerpt.len() >= 4, "the guide shows no compact rows");
    for row in excerpt {
        assert!(
            table.lines().any(|l| l.trim_end() == row.trim_end()),
            "guide row is out of date:\n{row}"
        );
    }
}

/// Gradient claims whose function and closed forms are polynomials are also proved
/// exactly: the exact derivative of the function's canonical expansion equals the
/// closed form's expansion in every component (an independent route to num-dual).
#[test]
fn polynomial_gradients_agree_with_exact_derivatives() {
    use cosserat_check::algebra::assignments;
    use cosserat_check::eval::exact::env::ExactEnv;
    let mut proved = Vec::new();
    for r in decided() {
        let claim = r.claim;
        let Strategy::Gradient {
            function,
            closed_forms,
            ..
        } = &claim.check.strategy
        else {
            continue;
        };
        let mut env =
            ExactEnv::new(&claim.decls, &claim.check.defs, &claim.check.assumptions).unwrap();
        let Ok(f) = env.eval(&function.node, &function.origin) else {
            continue; // not a polynomial (square roots): num-dual and central differences only
        };
        let f = f.tensor.into_scalar().unwrap();
        let f = f.as_poly().expect("no division by a sum");
        for (symbol, closed) in closed_forms {
            let cf = env
                .eval(&closed.node, &closed.origin)
                .expect("a polynomial closed form");
            let rank = claim.decls.symbols[symbol];
            for idx in assignments(claim.decls.dim, rank) {
                let name = format!(
                    "{symbol}_{}",
                    idx.iter().map(|i| (i + 1).to_string()).collect::<String>()
                );
                let derivative = match env.vars.lookup(&name) {
                    Some(v) => f.derivative(v),
                    None => Default::default(),
                };
                // Closed forms carry the indices i, j in order (labels are sorted).
                assert_eq!(
                    Some(&derivative),
                    cf.tensor.get(&idx).as_poly(),
                    "{}: ∂/∂{name}",
                    claim.id
                );
            }
        }
        proved.push(claim.id.clone());
    }
    assert_eq!(
        proved,
        ["grad-T2-3d", "grad-Mc2-3d"],
        "the polynomial gradient claims"
    );
}
