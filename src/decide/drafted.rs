//! A drafted file's failures (`drafted = true`, written by `cosserat-check draft`).
//!
//! A draft guesses its declarations from the printed symbols, and takes every symbol as
//! independent. The paper may tie some of them in its text ("the forces on the two
//! faces are equal and opposite") or in an equation the draft could not read. A failure
//! whose two sides read different symbols may be nothing but such a tie: "P = ⟨t⟩"
//! relates `P` to `t` whatever the paper means. It is reported as undecided, naming the
//! symbols, never as an error of the paper. A failure whose sides read the same symbols
//! (a wrong coefficient, a sign, a swapped index, a constant such as (26)'s −4/5) is
//! one no tie between them explains away, and stands.
//!
//! The symbols a side reads are those its exact value depends on (a symbol that
//! cancels, like the pressure in the tangential traction, is not read), or, where the
//! side has no exact value (a cosine, a root), those it names, through definitions.

use super::finding::Finding;
use super::Outcome;
use crate::algebra::assignments;
use crate::derivation::{reachable, Check, Side};
use crate::eval::exact::env::{ExactEnv, Varying};
use crate::kernel::Var;
use crate::lang::{Decls, NodeKind, Target};
use std::collections::{BTreeSet, HashMap};

/// `outcome` unchanged, unless it is a failure of a drafted check whose failing
/// equality has sides that read different symbols: then undecided, with those symbols.
pub fn judged(decls: &Decls, check: &Check, outcome: Outcome) -> Outcome {
    if !check.drafted || outcome.verdict() != crate::derivation::Verdict::Fails {
        return outcome;
    }
    let Some(cx) = &outcome.counterexample else {
        return outcome;
    };
    // A statement ill-formed as printed fails by its indices, whatever its symbols.
    if cx.ill_formed.is_some() {
        return outcome;
    }
    let (chain, equality) = (cx.chain, cx.equality);
    let sides = check
        .chains
        .get(chain.wrapping_sub(1))
        .and_then(|c| Some((c.get(equality.wrapping_sub(1))?, c.get(equality)?)));
    let Some((left, right)) = sides else {
        return outcome;
    };
    let (Some(l), Some(r)) = (read(decls, check, left), read(decls, check, right)) else {
        return outcome;
    };
    if l == r {
        return outcome;
    }
    let mut undecided =
        Outcome::undecided(outcome.method, outcome.checks).with_finding(Finding::OneSided {
            chain,
            equality,
            left: l.difference(&r).cloned().collect(),
            right: r.difference(&l).cloned().collect(),
        });
    // What the decision evaluated stays, for `explain`.
    undecided.record = outcome.record;
    undecided
}

/// The declared symbols `side` reads: exactly, where it has an exact value; else by
/// name, through the definitions it uses.
fn read(decls: &Decls, check: &Check, side: &Side) -> Option<BTreeSet<String>> {
    let node = side.node.as_ref().ok()?;
    let named = named(check, node);
    Some(read_exactly(decls, check, side, &named).unwrap_or(named))
}

/// The symbols `node` names, directly or through the definitions it uses.
fn named(check: &Check, node: &crate::lang::Node) -> BTreeSet<String> {
    let (nodes, _) = reachable(vec![node], &check.defs);
    nodes
        .iter()
        .filter_map(|n| match &n.kind {
            NodeKind::Leaf {
                target: Target::Symbol(s),
                ..
            } => Some(s.clone()),
            _ => None,
        })
        .collect()
}

/// Those of the symbols `named` that the exact value of `side` depends on, over all its
/// components; `None` when it has no exact value, or the claim's time limit stops the
/// evaluation. (Only the named symbols' components are looked up: the evaluation built
/// them already.)
fn read_exactly(
    decls: &Decls,
    check: &Check,
    side: &Side,
    named: &BTreeSet<String>,
) -> Option<BTreeSet<String>> {
    let node = side.node.as_ref().ok()?;
    crate::kernel::interrupt::stoppable(|| {
        let mut env = ExactEnv::on(
            decls,
            &check.defs,
            &check.assumptions,
            check.strategy.exact_domain(),
        )
        .ok()?;
        let value = env.eval(node, &side.origin).ok()?;
        let mut symbol_of: HashMap<Var, &str> = HashMap::new();
        for name in named {
            let rank = *decls.symbols.get(name)?;
            for idx in assignments(decls.dim, rank) {
                symbol_of.insert(env.component_var(name, &idx), name);
            }
        }
        let mut out = BTreeSet::new();
        for q in value.tensor.components() {
            for v in q.variables() {
                if let Some(name) = symbol_of.get(&v) {
                    out.insert((*name).to_owned());
                } else if let Some(Varying::Jet { field, .. }) = env.varying().get(&v) {
                    out.insert(field.clone());
                }
            }
        }
        Some(out)
    })
    .ok()
    .flatten()
}
