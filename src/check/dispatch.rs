//! Dispatch: each check to its strategy, under the claim's time limit and in
//! isolation from panics.

use super::isolate;
use crate::decide::{
    drafted, finding, identity, numeric, sampler, scalar, watch, witness, Method, Outcome,
};
use crate::lang::Diagnostic;

/// Decides one check with its strategy.
pub fn decide(
    decls: &crate::lang::Decls,
    check: &crate::derivation::Check,
) -> Result<Outcome, Diagnostic> {
    decide_keeping(decls, check, false)
}

pub(crate) fn decide_keeping(
    decls: &crate::lang::Decls,
    check: &crate::derivation::Check,
    keep: bool,
) -> Result<Outcome, Diagnostic> {
    isolate::isolated(method_of(check), &check.location(), || {
        decide_unisolated(decls, check, keep)
    })
}

/// The method a check's strategy decides with.
pub(crate) fn method_of(check: &crate::derivation::Check) -> Method {
    use crate::derivation::Strategy;
    match &check.strategy {
        Strategy::Numeric { .. } => Method::Numeric,
        Strategy::Gradient { .. } => Method::Gradient,
        Strategy::Convex { .. } => Method::Convex,
        Strategy::Exact { .. } | Strategy::Proportional { .. } => Method::Exact,
        Strategy::NotCircle { .. } => Method::Witness,
        Strategy::Scalar { .. } => Method::RationalFunction,
    }
}

/// A differential hypothesis (`phi_,kk = 0`) is supported in an identity decided
/// exactly. A constraint between expressions (`s_ij s_ij = 2 tau^2`) is supported where its
/// meaning is settled: in an identity decided exactly or by sampling, and never under a
/// derivative by a symbol it reads (whose components it ties, in no stated way).
fn constraints_supported(check: &crate::derivation::Check) -> Result<(), Diagnostic> {
    use crate::derivation::{AssumptionKind, Strategy};
    use crate::lang::parser::Wrt;
    use crate::lang::NodeKind;
    if let Some(a) = check
        .assumptions
        .iter()
        .find(|a| matches!(a.kind, AssumptionKind::Differential { .. }))
    {
        if !matches!(check.strategy, Strategy::Exact { .. }) {
            return Err(a
                .diagnostic("a differential hypothesis applies to identities (sides or chains) decided exactly")
                .with_help("drop the strategy: a sample is a point, not a field"));
        }
    }
    let Some(a) = check
        .assumptions
        .iter()
        .find(|a| matches!(a.kind, AssumptionKind::Constraint { .. }))
    else {
        return Ok(());
    };
    if !matches!(
        check.strategy,
        Strategy::Exact { .. } | Strategy::Numeric { .. }
    ) {
        return Err(a
            .diagnostic("a constraint between expressions applies to identities (sides or chains) decided exactly or numerically")
            .with_help("drop the strategy, or write strategy = \"numeric\""));
    }
    let (nodes, _) = check.reachable();
    // The symbols a constraint reads, and every symbol another assumption relates to
    // one of them (`x = w` with `x^3 = y` ties w too).
    let mut tied: std::collections::BTreeSet<&str> = check
        .assumptions
        .iter()
        .filter(|a| matches!(a.kind, AssumptionKind::Constraint { .. }))
        .flat_map(|a| a.reads.iter().map(String::as_str))
        .collect();
    loop {
        let before = tied.len();
        for a in &check.assumptions {
            let symbols: Vec<&str> = a
                .kind
                .symbol()
                .into_iter()
                .chain(a.reads.iter().map(String::as_str))
                .collect();
            if symbols.iter().any(|s| tied.contains(s)) {
                tied.extend(symbols);
            }
        }
        if tied.len() == before {
            break;
        }
    }
    for n in nodes {
        if let NodeKind::Wrt { symbol, op, .. } = &n.kind {
            if tied.contains(symbol.as_str()) {
                let what = if *op == Wrt::Variation {
                    "a variation"
                } else {
                    "a derivative"
                };
                return Err(a
                    .diagnostic(format!("{what} by `{symbol}`, whose components this constraint ties together, has no stated meaning"))
                    .with_help("differentiate in a claim without the constraint, or by a symbol it does not read"));
            }
        }
    }
    Ok(())
}

/// [`decide_keeping`] without the panic isolation.
pub(crate) fn decide_unisolated(
    decls: &crate::lang::Decls,
    check: &crate::derivation::Check,
    keep: bool,
) -> Result<Outcome, Diagnostic> {
    use crate::derivation::Strategy;
    let sink = sampler::Sink::default();
    let states = keep.then_some(&sink);
    let method = method_of(check);
    constraints_supported(check)?;
    if method != Method::Exact && check.reads().differentiates {
        return Ok(
            Outcome::undecided(method, 0).with_finding(finding::Finding::DerivativesNotSampled)
        );
    }
    // A computation stopped at the time limit unwinds to here (`interrupt::tick`);
    // the watch has expired then, so the match below makes it undecided.
    let decided = crate::kernel::interrupt::stoppable(|| match &check.strategy {
        Strategy::Exact { .. } | Strategy::Proportional { .. } => {
            identity::decide(decls, check, keep)
        }
        Strategy::Numeric { .. } => numeric::decide_numeric(decls, check, states),
        Strategy::Gradient { .. } => numeric::decide_gradient(decls, check, states),
        Strategy::Convex { .. } => numeric::decide_convex(decls, check, states),
        Strategy::NotCircle { .. } => witness::decide_not_circle(decls, check),
        Strategy::Scalar { .. } => scalar::decide(decls, check),
    })
    .unwrap_or_else(|_| {
        Ok(
            Outcome::undecided(method, 0).with_finding(finding::Finding::TimeLimit {
                seconds: watch::expired().map_or(0.0, |l| l.as_secs_f64()),
            }),
        )
    });
    // A decision that outlived the time limit is undecided: it was stopped
    // (`watch::check`), whatever error the stop surfaced as, or the kernel gave up a
    // step and returned a meaningless value (`kernel::interrupt`). One that finished
    // in time stands.
    let mut outcome = match (decided, watch::expired()) {
        (Ok(o), None) => o,
        (_, Some(limit)) => {
            Outcome::undecided(method, 0).with_finding(finding::Finding::TimeLimit {
                seconds: limit.as_secs_f64(),
            })
        }
        (Err(e), None) => return Err(e),
    };
    if keep {
        outcome.record.get_or_insert_with(Default::default).states = sink.into_inner();
    }
    let judged = drafted::judged(decls, check, outcome);
    Ok(past_a_tie(decls, check, judged))
}

/// The rest of `check` after equality `equality` of chain `chain` (both 1-based): the
/// members of that chain from the equality's right side on, and the chains after it
/// (`None` when nothing is left). A claim asserts each of its equalities, so a
/// refutation of the rest refutes it: the rest is weaker.
pub(crate) fn rest_of(
    check: &crate::derivation::Check,
    chain: usize,
    equality: usize,
) -> Option<crate::derivation::Check> {
    let sides = check.chains.get(chain.checked_sub(1)?)?;
    let mut chains = Vec::new();
    if sides.len() > equality + 1 {
        chains.push(sides[equality..].to_vec());
    }
    chains.extend(check.chains[chain..].iter().cloned());
    (!chains.is_empty()).then(|| crate::derivation::Check {
        chains,
        ..check.clone()
    })
}

/// A drafted chain whose first failing equality waits for a tie the paper may state
/// (`drafted::judged`) may fail further on, where no tie is in question (`P = … =
/// (\sigma_{ij} v_j)_{,i} + \sigma_{ij,i} v_j - …`, with a planted sign after an
/// equality that needs the text's `\dot{\kappa}_{ij} = w_{j,i}`): the rest of the chain
/// and the chains after it ([`rest_of`]) are decided on their own, and a failure there,
/// itself past every tie, is the claim's, at its own place in the claim.
fn past_a_tie(
    decls: &crate::lang::Decls,
    check: &crate::derivation::Check,
    outcome: Outcome,
) -> Outcome {
    use crate::derivation::{Strategy, Verdict};
    use finding::Finding;
    let waits = match &outcome.finding {
        Some(Finding::OneSided {
            chain, equality, ..
        })
        | Some(Finding::Tie {
            chain, equality, ..
        }) => Some((*chain, *equality)),
        _ => None,
    };
    let Some((chain, equality)) = waits else {
        return outcome;
    };
    if check.drafted.is_none() || !matches!(check.strategy, Strategy::Exact { .. }) {
        return outcome;
    }
    let Some(rest) = rest_of(check, chain, equality) else {
        return outcome;
    };
    let kept = check.chains[chain - 1].len() > equality + 1;
    let Ok(mut later) = decide_unisolated(decls, &rest, false) else {
        return outcome;
    };
    if later.verdict() != Verdict::Fails {
        return outcome;
    }
    if let Some(cx) = later.counterexample.as_mut() {
        (cx.chain, cx.equality) = match (kept, cx.chain) {
            (true, 1) => (chain, equality + cx.equality),
            (true, r) => (chain + r - 1, cx.equality),
            (false, r) => (chain + r, cx.equality),
        };
    }
    later.record = outcome.record;
    later
}

/// The statements a claim's proofs may be about: a `holds` proves every one of
/// `whole` (one, or each part of a claim decided in parts), and a refutation is about
/// one of them or of `weaker` (the weaker parts that tell a failure of a stationary
/// claim from a case its test does not decide).
#[derive(Clone, Debug, Default)]
pub struct ProofStatements {
    pub whole: Vec<crate::kernel::statement::Statement>,
    pub weaker: Vec<crate::kernel::statement::Statement>,
}

/// The statements a proof of `check` may be about, rebuilt from its file as a decision
/// builds them for the kernel: the equalities of an exact or proportional claim, a
/// scalar claim on its box (each part of one decided in parts), a locus; none for the
/// sampled strategies, which prove nothing. (A scalar claim's proof may also be on a
/// sub-box of its domain: the box is the one part of the statement this does not fix.)
pub fn proof_statements(
    decls: &crate::lang::Decls,
    check: &crate::derivation::Check,
) -> Result<ProofStatements, Diagnostic> {
    use crate::derivation::{statement, Strategy};
    let scalar = |part: &crate::derivation::Check| match &part.strategy {
        Strategy::Scalar { domain, .. } => statement::scalar(decls, part, domain),
        _ => unreachable!("a part is a sign claim"),
    };
    let whole = match &check.strategy {
        // A drafted claim may be refuted past an equality that waits for a tie
        // ([`past_a_tie`]): by the rest of the claim after any of its equalities.
        Strategy::Exact { .. } if check.drafted.is_some() => {
            let mut weaker = Vec::new();
            for (c, sides) in check.chains.iter().enumerate() {
                for e in 1..sides.len() {
                    if let Some(rest) = rest_of(check, c + 1, e) {
                        weaker.push(statement::equalities(decls, &rest)?);
                    }
                }
            }
            return Ok(ProofStatements {
                whole: vec![statement::equalities(decls, check)?],
                weaker,
            });
        }
        Strategy::Exact { .. } | Strategy::Proportional { .. } => {
            vec![statement::equalities(decls, check)?]
        }
        Strategy::Scalar { .. } => {
            if let Some(parts) = crate::derivation::exact_part_checks(check) {
                parts.iter().map(scalar).collect::<Result<_, _>>()?
            } else if let Some(parts) = crate::derivation::stationary_parts(check) {
                let mut out = ProofStatements::default();
                for p in &parts {
                    out.whole.push(scalar(&p.check)?);
                    if let Some((weaker, _)) = &p.weaker {
                        out.weaker.push(scalar(weaker)?);
                    }
                }
                return Ok(out);
            } else {
                vec![scalar(check)?]
            }
        }
        Strategy::NotCircle { x, y } => {
            vec![statement::not_circle(decls, check, &x.node, &y.node)?]
        }
        Strategy::Numeric { .. } | Strategy::Gradient { .. } | Strategy::Convex { .. } => {
            Vec::new()
        }
    };
    Ok(ProofStatements {
        whole,
        weaker: Vec::new(),
    })
}
