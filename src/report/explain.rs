//! `cosserat-check explain ID`: how one claim was decided, in enough detail for a
//! reviewer to audit the verdict by hand — the setting, the definitions and
//! assumptions it uses, each side's canonical expansion (exact) or the first sampled
//! states (numeric), and the full evidence.

use super::evidence;
use crate::derivation::{Check, Claim, Strategy};
use crate::kernel::assignments;
use crate::lang::Decls;
use crate::strategy::eval::ExactEnv;
use crate::strategy::numeric::trace;
use crate::strategy::{Decided, Outcome};
use std::fmt::Write as _;

/// Terms shown per canonical polynomial, components shown per side.
const TERMS: usize = 24;
const COMPONENTS: usize = 27;
/// Sampled states shown for numeric strategies.
const STATES: usize = 3;

fn setting(decls: &Decls) -> String {
    let mut s = format!("dimension {}", decls.dim);
    if let Some(n) = &decls.normal {
        let where_ = if decls.normal_in_plane {
            "in the 1-2 plane, uniform on the unit circle"
        } else if decls.dim == 2 {
            "uniform on the unit circle"
        } else {
            "uniform on the unit sphere"
        };
        let _ = write!(s, "; normal {n} (unit, {where_})");
    }
    let symbols: Vec<String> = decls
        .symbols
        .iter()
        .map(|(k, r)| {
            if *r == 0 {
                k.clone()
            } else {
                format!("{k} (rank {r})")
            }
        })
        .collect();
    let _ = write!(s, "; symbols: {}", symbols.join(", "));
    s
}

fn check_section(out: &mut String, claim: &Claim, check: &Check, outcome: &Outcome) {
    let deps = check.dependencies();
    if !deps.is_empty() {
        let _ = writeln!(out, "Definitions used:");
        for k in deps {
            let _ = writeln!(out, "    {}", check.defs[k].text.trim());
        }
    }
    if !check.assumptions.is_empty() {
        let texts: Vec<String> = check.assumptions.iter().map(|a| a.text.clone()).collect();
        let _ = writeln!(out, "Assumptions: {}", texts.join("; "));
    }
    match &check.strategy {
        Strategy::Exact => exact_section(out, claim, check),
        Strategy::Numeric { sampling, .. }
        | Strategy::Gradient { sampling, .. }
        | Strategy::Convex { sampling, .. } => {
            let ranges: Vec<String> = sampling
                .ranges
                .iter()
                .map(|(k, (a, b))| format!("{k} in [{a}, {b}]"))
                .collect();
            let _ = writeln!(
                out,
                "Sampling: {} states, seed {}; components in [-1, 1]{}{}",
                sampling.samples,
                sampling.seed,
                if ranges.is_empty() {
                    String::new()
                } else {
                    format!(" except {}", ranges.join(", "))
                },
                if sampling.given.is_empty() {
                    String::new()
                } else {
                    format!(
                        "; given {}",
                        sampling
                            .given
                            .iter()
                            .map(|g| g.text.clone())
                            .collect::<Vec<_>>()
                            .join(", ")
                    )
                }
            );
            match trace(&claim.decls, check, STATES) {
                Ok(lines) => {
                    let _ = writeln!(out, "First {STATES} sampled states:");
                    for l in lines {
                        let _ = writeln!(out, "    {l}");
                    }
                }
                Err(d) => {
                    let _ = writeln!(out, "(the states cannot be shown: {})", d.message);
                }
            }
        }
        Strategy::NotCircle { x, y } => {
            let _ = writeln!(out, "Locus: x = {}, y = {}", x.text, y.text);
        }
        Strategy::Appendix { step, .. } => {
            let _ = writeln!(
                out,
                "Appendix step `{}`: derived with exact rational functions (src/model), cross-checked in f64",
                step.name()
            );
        }
    }
    let _ = writeln!(
        out,
        "Verdict: {} ({})",
        outcome.verdict_text(),
        outcome.method.as_str()
    );
    if let Some(c) = outcome.certificate() {
        let _ = writeln!(
            out,
            "Certificate (verified by the kernel): {}",
            super::certificate_words(c)
        );
    }
    let _ = writeln!(out, "Evidence: {}", evidence(outcome));
    if let Some(cx) = &outcome.counterexample {
        let json = serde_json::to_string_pretty(cx).unwrap_or_default();
        let _ = writeln!(out, "Counterexample:\n{json}");
    }
}

fn exact_section(out: &mut String, claim: &Claim, check: &Check) {
    let mut env = match ExactEnv::new(&claim.decls, &check.defs, &check.assumptions) {
        Ok(env) => env,
        Err(d) => {
            let _ = writeln!(out, "(cannot expand: {})", d.message);
            return;
        }
    };
    for (ci, chain) in check.chains.iter().enumerate() {
        for (si, side) in chain.iter().enumerate() {
            let _ = writeln!(
                out,
                "Chain {}, side {}: {}",
                ci + 1,
                si + 1,
                side.text.trim()
            );
            let node = match &side.node {
                Ok(n) => n,
                Err(e) => {
                    let _ = writeln!(out, "    ill-formed as printed: {}", e.message);
                    continue;
                }
            };
            match env.eval(node, &side.origin) {
                Ok(v) => {
                    for (k, idx) in assignments(claim.decls.dim, v.labels.len()).enumerate() {
                        if k == COMPONENTS {
                            let _ = writeln!(out, "    … (more components)");
                            break;
                        }
                        let at: Vec<String> = v
                            .labels
                            .iter()
                            .zip(&idx)
                            .map(|(c, i)| format!("{c}={}", i + 1))
                            .collect();
                        let label = if at.is_empty() {
                            String::new()
                        } else {
                            format!("[{}] ", at.join(", "))
                        };
                        let _ = writeln!(
                            out,
                            "    {label}= {}",
                            v.tensor.get(&idx).display_truncated(&env.vars, TERMS)
                        );
                    }
                }
                Err(d) => {
                    let _ = writeln!(out, "    (cannot expand: {})", d.message);
                }
            }
        }
    }
}

/// Renders the explanation of one decided claim.
pub fn render(r: &Decided<'_>) -> String {
    let c = r.claim;
    let mut out = format!("# {} (Section {})\n\n", c.id, c.section);
    let _ = writeln!(out, "As printed: {}", c.statement);
    let _ = writeln!(
        out,
        "Declared: {}; decided: {} ({})",
        c.expect,
        r.outcome.verdict(),
        r.outcome.method.as_str()
    );
    if let Some(reason) = &c.reason {
        let _ = writeln!(out, "Why: {reason}");
    }
    if let Some(note) = &c.note {
        let _ = writeln!(out, "Note: {note}");
    }
    let _ = writeln!(out, "Setting: {}\n", setting(&c.decls));
    check_section(&mut out, c, &c.check, &r.outcome);
    if let (Some(k), Some(o)) = (&c.correction, &r.correction) {
        let _ = writeln!(out, "\n## Correction\n\n{}\nWhy: {}", k.statement, k.reason);
        let _ = writeln!(out, "Declared: {}", k.expect);
        check_section(&mut out, c, &k.check, o);
    }
    out
}
