//! Mutation tests: the exact strategy refutes wrong statements.
//!
//! For every statement that is expected to hold (each `holds` claim, and each
//! correction that holds), every side and every definition the statement depends on
//! is mutated — each coefficient changed, each pair of indices of a name swapped, each
//! term's sign flipped, each term dropped — and the mutant is decided by the same
//! strategy. A mutant must be refuted (`fails`) or rejected as ill-formed by the
//! validator; a survivor must be listed in `EQUIVALENT` with the reason it is
//! equivalent to the original, and every listed survivor must still survive (so the
//! list cannot go stale). The per-kind report is snapshot-tested.

use cosserat_check::derivation::{load_dir, Check, Verdict};
use cosserat_check::lang::Decls;
use cosserat_check::mutate::{mutants, MutantKind};
use cosserat_check::strategy::exact;
use std::collections::BTreeMap;
use std::path::Path;

/// Surviving mutants that are equivalent to the original: (statement, place, mutant
/// text, why it is equivalent).
const EQUIVALENT: &[(&str, &str, &str, &str)] = &[];

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
}

fn fate(decls: &Decls, mutated: Result<Check, impl std::fmt::Debug>) -> Fate {
    match mutated {
        Err(_) => Fate::Rejected,
        Ok(check) => match exact::decide(decls, &check) {
            Err(_) => Fate::Rejected,
            Ok(o) if o.verdict == Verdict::Fails => Fate::Killed,
            Ok(_) => Fate::Survived,
        },
    }
}

#[test]
fn every_mutant_of_every_proved_statement_is_refuted() {
    let files = load_dir(&Path::new(env!("CARGO_MANIFEST_DIR")).join("derivations")).expect("derivations load");
    let mut per_kind: BTreeMap<MutantKind, Tally> = BTreeMap::new();
    let mut per_claim: Vec<String> = Vec::new();
    let mut survivors: Vec<(String, String, String)> = Vec::new();
    for claim in files.iter().flat_map(|f| &f.claims) {
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
                }
            };
            for (ci, chain) in check.chains.iter().enumerate() {
                for (si, side) in chain.iter().enumerate() {
                    for m in mutants(&side.text) {
                        let f = fate(&claim.decls, check.with_side(&claim.decls, ci, si, &m.text));
                        record(m.kind, format!("chain {} side {}", ci + 1, si + 1), m.text, f);
                    }
                }
            }
            for d in check.dependencies() {
                let def = &check.defs[d];
                let body = def.text.split_once('=').map_or("", |(_, b)| b);
                for m in mutants(body) {
                    let f = fate(&claim.decls, check.with_definition_body(&claim.decls, d, &m.text));
                    record(m.kind, format!("definition {}", def.sig.name), m.text.trim().to_owned(), f);
                }
            }
            let summary: Vec<String> = kinds
                .iter()
                .map(|(k, (killed, survived))| format!("{k}: {killed} refuted, {survived} equivalent"))
                .collect();
            per_claim.push(format!("{name}: {}", summary.join("; ")));
        }
    }

    let mut report = String::from("kind | refuted | rejected as ill-formed | equivalent (listed) | kill rate of non-equivalent\n");
    for (kind, t) in &per_kind {
        let non_equivalent = t.killed + t.rejected;
        report.push_str(&format!(
            "{kind} | {} | {} | {} | {:.1}%\n",
            t.killed,
            t.rejected,
            t.equivalent,
            100.0 * (t.killed + t.rejected) as f64 / non_equivalent.max(1) as f64
        ));
    }
    report.push('\n');
    for line in &per_claim {
        report.push_str(line);
        report.push('\n');
    }
    println!("{report}");

    let listed: Vec<(String, String, String)> = EQUIVALENT
        .iter()
        .map(|(a, b, c, _)| (a.to_string(), b.to_string(), c.to_string()))
        .collect();
    let unexplained: Vec<_> = survivors.iter().filter(|s| !listed.contains(s)).collect();
    assert!(unexplained.is_empty(), "surviving mutants not shown to be equivalent:\n{unexplained:#?}");
    let stale: Vec<_> = listed.iter().filter(|s| !survivors.contains(s)).collect();
    assert!(stale.is_empty(), "listed as equivalent but no longer surviving:\n{stale:#?}");

    insta::with_settings!({
        snapshot_path => concat!(env!("CARGO_MANIFEST_DIR"), "/snapshots"),
        prepend_module_to_snapshot => false,
    }, {
        insta::assert_snapshot!("mutation_report", report);
    });
}
