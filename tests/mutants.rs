//! Mutation tests: the exact strategy refutes wrong statements.
//!
//! For every statement that is expected to hold (each `holds` claim, and each
//! correction that holds), every side and every definition the statement depends on
//! is mutated — each coefficient changed, each pair of indices of a name swapped, each
//! term's sign flipped, each term dropped — and the mutant is decided by the same
//! strategy. A mutant must be refuted (`fails`) or rejected as ill-formed by the
//! validator, or be equivalent: a surviving mutant counts as equivalent only when the
//! independent floating-point route (`strategy::float`: random values, quadrature
//! averages, no polynomial code) also finds the mutated statement true. Every mutant
//! decided by both routes must get the same verdict from both. The report — kill
//! rates per kind and the full list of equivalent mutants — is snapshot-tested, so a
//! new survivor shows up as a diff to review.

use cosserat_check::derivation::{load_dir, Check, Strategy, Verdict};
use cosserat_check::lang::Decls;
use cosserat_check::mutate::{mutants, MutantKind};
use cosserat_check::strategy::{exact, float};
use std::collections::BTreeMap;
use std::path::Path;

/// Random points per mutant for the float route (see `float::decide`).
const FLOAT_SAMPLES: usize = 2;

#[derive(Default)]
struct Tally {
    killed: usize,
    rejected: usize,
    equivalent: usize,
}

enum Fate {
    Killed,
    Rejected,
    Survived,
    /// The exact and float routes disagree: a bug in one of them.
    Disagreement(String),
}

fn fate(decls: &Decls, mutated: Result<Check, impl std::fmt::Debug>) -> Fate {
    let Ok(check) = mutated else {
        return Fate::Rejected;
    };
    let Ok(exact) = exact::decide(decls, &check) else {
        return Fate::Rejected;
    };
    match float::decide(decls, &check, FLOAT_SAMPLES, 7) {
        Ok(Some(v)) if v != exact.verdict => {
            return Fate::Disagreement(format!("exact {}, float {v}", exact.verdict));
        }
        Err(e) => return Fate::Disagreement(format!("exact {}, float error {e}", exact.verdict)),
        _ => {}
    }
    if exact.verdict == Verdict::Fails {
        Fate::Killed
    } else {
        Fate::Survived
    }
}

#[test]
fn every_mutant_of_every_proved_statement_is_refuted() {
    let files = load_dir(&Path::new(env!("CARGO_MANIFEST_DIR")).join("derivations"))
        .expect("derivations load");
    let mut per_kind: BTreeMap<MutantKind, Tally> = BTreeMap::new();
    let mut per_claim: Vec<String> = Vec::new();
    let mut survivors: Vec<(String, String, String)> = Vec::new();
    let mut disagreements: Vec<String> = Vec::new();
    for claim in files.iter().flat_map(|f| &f.claims) {
        // The sweep covers the exact strategy; numeric strategies have their own
        // refutation tests (tests/numeric.rs).
        if !matches!(claim.check.strategy, Strategy::Exact) {
            continue;
        }
        let mut statements: Vec<(String, &Check)> = Vec::new();
        if claim.expect == Verdict::Holds {
            statements.push((claim.id.clone(), &claim.check));
        }
        if let Some(c) = claim.correction.iter().find(|c| c.expect == Verdict::Holds) {
            statements.push((format!("{} (correction)", claim.id), &c.check));
        }
        for (name, check) in statements {
            let mut kinds: BTreeMap<MutantKind, (usize, usize)> = BTreeMap::new();
            let mut record = |kind: MutantKind, place: String, text: String, f: Fate| {
                let entry = per_kind.entry(kind).or_default();
                let k = kinds.entry(kind).or_default();
                match f {
                    Fate::Killed => {
                        entry.killed += 1;
                        k.0 += 1;
                    }
                    Fate::Rejected => entry.rejected += 1,
                    Fate::Survived => {
                        entry.equivalent += 1;
                        k.1 += 1;
                        survivors.push((name.clone(), place, text));
                    }
                    Fate::Disagreement(why) => {
                        disagreements.push(format!("{name}, {place}: `{text}`: {why}"))
                    }
                }
            };
            for (ci, chain) in check.chains.iter().enumerate() {
                for (si, side) in chain.iter().enumerate() {
                    for m in mutants(&side.text) {
                        let f = fate(&claim.decls, check.with_side(&claim.decls, ci, si, &m.text));
                        record(
                            m.kind,
                            format!("chain {} side {}", ci + 1, si + 1),
                            m.text,
                            f,
                        );
                    }
                }
            }
            for d in check.dependencies() {
                let def = &check.defs[d];
                let body = def.text.split_once('=').map_or("", |(_, b)| b);
                for m in mutants(body) {
                    let f = fate(
                        &claim.decls,
                        check.with_definition_body(&claim.decls, d, &m.text),
                    );
                    record(
                        m.kind,
                        format!("definition {}", def.sig.name),
                        m.text.trim().to_owned(),
                        f,
                    );
                }
            }
            let summary: Vec<String> = kinds
                .iter()
                .map(|(k, (killed, survived))| {
                    format!("{k}: {killed} refuted, {survived} equivalent")
                })
                .collect();
            per_claim.push(format!("{name}: {}", summary.join("; ")));
        }
    }

    let mut report = String::from(
        "kind | mutants | refuted | rejected as ill-formed | equivalent (still true)\n",
    );
    for (kind, t) in &per_kind {
        report.push_str(&format!(
            "{kind} | {} | {} | {} | {}\n",
            t.killed + t.rejected + t.equivalent,
            t.killed,
            t.rejected,
            t.equivalent
        ));
    }
    report.push('\n');
    for line in &per_claim {
        report.push_str(line);
        report.push('\n');
    }
    println!("{report}");

    report.push_str("\nEquivalent mutants (the mutated statement is still true; confirmed by the float route):\n");
    for (name, place, text) in &survivors {
        report.push_str(&format!("{name}, {place}: {text}\n"));
    }
    assert!(
        disagreements.is_empty(),
        "exact and float routes disagree:\n{}",
        disagreements.join("\n")
    );
    for kind in [
        MutantKind::Coefficient,
        MutantKind::SwapIndices,
        MutantKind::FlipSign,
        MutantKind::DropTerm,
    ] {
        assert!(
            per_kind.get(&kind).is_some_and(|t| t.killed > 0),
            "no {kind} mutant was refuted"
        );
    }

    insta::with_settings!({
        snapshot_path => concat!(env!("CARGO_MANIFEST_DIR"), "/snapshots"),
        prepend_module_to_snapshot => false,
    }, {
        insta::assert_snapshot!("mutation_report", report);
    });
}
