//! Claims about scalar rational functions of parameters: `sign`, `monotone`, `limit`,
//! `roots` and `stationary` (see [`ScalarClaim`]).
//!
//! Every expression is evaluated exactly to a reduced rational function of the
//! parameters it uses. With one parameter, it is decided completely: Sturm sequences
//! give the sign chart (`algebra::sign`), lowest orders give limits (`algebra::limit`),
//! and the kernel checks each as a fact (`kernel::scalar`). With several, a certificate is tried first (coefficients of one
//! sign after moving every parameter onto t ≥ 0); without one, the function is
//! evaluated exactly at seeded rational points of the box and an adversarial search
//! looks for the smallest margin, so that a `holds` is labelled sampled and a `fails`
//! carries an exact counterexample. Every counterexample is re-evaluated by the
//! floating-point interpreter on the expression tree before it is printed.

mod context;
mod exactly;
mod limit;
mod monotone;
mod parts;
mod roots;
mod sample;
mod sign;
mod stationary;

use super::outcome::Outcome;
use crate::derivation::{Check, ScalarClaim, Strategy};
use crate::eval::exact::env::ExactEnv;
use crate::lang::{Decls, Diagnostic};
use context::{Context, Stop};

/// Decides a `strategy = "sign" | "monotone" | "limit" | "roots"` check.
pub fn decide(decls: &Decls, check: &Check) -> Result<Outcome, Diagnostic> {
    let Strategy::Scalar {
        claim,
        domain,
        samples,
        seed,
    } = &check.strategy
    else {
        unreachable!("dispatched on the strategy")
    };
    match &**claim {
        ScalarClaim::SignExactly(..) => return exactly::decide(check, |part| decide(decls, part)),
        ScalarClaim::Stationary(_) => return stationary::decide(check, |part| decide(decls, part)),
        _ => {}
    }
    // Square roots take their sign on the claim's box.
    let env = ExactEnv::on(decls, &check.defs, &check.assumptions, Some(domain))?;
    let mut cx = Context {
        env,
        decls,
        check,
        domain,
        samples: *samples,
        seed: *seed,
    };
    let decided = match &**claim {
        ScalarClaim::Sign(want) => sign::decide(&mut cx, *want),
        ScalarClaim::SignExactly(..) | ScalarClaim::Stationary(_) => {
            unreachable!("decided part by part")
        }
        ScalarClaim::Monotone {
            function,
            variable,
            increasing,
        } => monotone::decide(&mut cx, function, variable, *increasing),
        ScalarClaim::Limit {
            function,
            variable,
            to,
            value,
        } => limit::decide(&mut cx, function, variable, to, value),
        ScalarClaim::Roots {
            function,
            variable,
            roots,
            count,
        } => match count {
            Some(n) => roots::count(&mut cx, function, variable, *n),
            None => roots::decide(&mut cx, function, variable, roots),
        },
    };
    match decided {
        Ok(o) => Ok(o),
        Err(Stop::Outcome(o)) => Ok(*o),
        Err(Stop::Input(d)) => Err(d),
    }
}
