//! `cosserat-check explain ID`: how one claim was decided, in enough detail for a
//! reviewer to audit the verdict by hand — the setting, the definitions and
//! assumptions it uses, each side's canonical expansion (exact) or the first sampled
//! states (numeric), and the full evidence. It renders what the decision recorded
//! (`check::decide_claim_recorded`); nothing is computed again here.

use super::evidence::evidence;
use crate::check::Decided;
use crate::decide::finding::Record;
use crate::decide::Outcome;
use crate::derivation::{Check, Strategy};
use crate::lang::Decls;
use std::fmt::Write as _;

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
    if let Some(x) = &decls.position {
        let _ = write!(s, "; position {x}");
    }
    let rank = |k: &str, r: usize| {
        if r == 0 {
            k.to_owned()
        } else {
            format!("{k} (rank {r})")
        }
    };
    let fields: Vec<String> = decls
        .fields
        .iter()
        .map(|(k, deps)| {
            let r = decls.symbols.get(k).copied().unwrap_or(0);
            let on: Vec<String> = (1..=decls.dim)
                .filter(|j| deps[j - 1])
                .map(|j| format!("{}_{j}", decls.position.as_deref().unwrap_or("x")))
                .collect();
            if on.len() == decls.dim {
                rank(k, r)
            } else {
                format!("{} on {}", rank(k, r), on.join(", "))
            }
        })
        .collect();
    if !fields.is_empty() {
        let _ = write!(s, "; fields: {}", fields.join(", "));
    }
    let symbols: Vec<String> = decls
        .symbols
        .iter()
        .filter(|(k, _)| !decls.varies(k))
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

fn check_section(out: &mut String, check: &Check, outcome: &Outcome) {
    let deps = check.dependencies();
    if !deps.is_empty() {
        let _ = writeln!(out, "Definitions used:");
        for k in deps {
            let text = check.defs[k].text.trim();
            let typeset = match text.split_once('=') {
                // A side of a matrix chain, named by the reader (`side 1.2`): words,
                // not a product of a name and a number.
                Some((_, body)) if check.defs[k].sig.name.starts_with("side ") => format!(
                    "\\text{{{}}} = {}",
                    check.defs[k].sig.name,
                    super::typeset::latex(body.trim())
                ),
                Some((name, body)) => format!(
                    "{} = {}",
                    super::typeset::latex(name.trim()),
                    super::typeset::latex(body.trim())
                ),
                None => super::typeset::latex(text),
            };
            let _ = writeln!(out, "    {text}\n      typeset: ${typeset}$");
        }
    }
    if !check.assumptions.is_empty() {
        let texts: Vec<String> = check.assumptions.iter().map(|a| a.text.clone()).collect();
        let _ = writeln!(out, "Assumptions: {}", texts.join("; "));
    }
    if let Some(domain) = check.strategy.exact_domain() {
        if !domain.bounds.is_empty() {
            let _ = writeln!(out, "Parameter box (given): {}", domain.describe());
        }
    }
    if let Strategy::Exact { hypotheses, .. } = &check.strategy {
        if !hypotheses.is_empty() {
            // One entry may give two comparisons (`0 < J2 < 1`): each text once.
            let mut texts: Vec<&str> = hypotheses.iter().map(|h| h.text.as_str()).collect();
            texts.dedup();
            let _ = writeln!(out, "Hypotheses (given): {}", texts.join("; "));
        }
    }
    match &check.strategy {
        Strategy::Exact { .. } | Strategy::Proportional { .. } => {
            expansions(out, outcome.record.as_ref())
        }
        Strategy::Scalar {
            domain,
            samples,
            seed,
            ..
        } => {
            let _ = writeln!(
                out,
                "Parameters: {}; with several parameters and no certificate, {samples} exact samples, seed {seed}",
                domain.describe()
            );
        }
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
            states(out, outcome.record.as_ref());
        }
        Strategy::NotCircle { x, y } => {
            let _ = writeln!(out, "Locus: x = {}, y = {}", x.text, y.text);
        }
    }
    let _ = writeln!(
        out,
        "Verdict: {} ({})",
        outcome.verdict_text(),
        outcome.method.as_str()
    );
    if let Some(w) = super::evidence::proof_words(outcome) {
        let _ = writeln!(out, "Proof (checked by the kernel): {w}");
    }
    let _ = writeln!(out, "Evidence: {}", evidence(outcome));
    if let Some(cx) = &outcome.counterexample {
        let json = serde_json::to_string_pretty(cx).unwrap_or_default();
        let _ = writeln!(out, "Counterexample:\n{json}");
    }
}

/// Each side's canonical expansion, as the decision computed it.
fn expansions(out: &mut String, record: Option<&Record>) {
    let Some(record) = record else {
        let _ = writeln!(out, "(the expansions were not recorded)");
        return;
    };
    for e in &record.expansions {
        let _ = writeln!(out, "Chain {}, side {}: {}", e.chain, e.side, e.text);
        match &e.components {
            Err(why) => {
                let _ = writeln!(out, "    {why}");
            }
            Ok(components) => {
                for (at, poly) in components {
                    let at: Vec<String> = at.iter().map(|(c, i)| format!("{c}={i}")).collect();
                    let label = if at.is_empty() {
                        String::new()
                    } else {
                        format!("[{}] ", at.join(", "))
                    };
                    let _ = writeln!(out, "    {label}= {poly}");
                }
                if e.more {
                    let _ = writeln!(out, "    … (more components)");
                }
            }
        }
    }
}

/// The first states the sampled decision drew, with the values there.
fn states(out: &mut String, record: Option<&Record>) {
    let states = record.map(|r| r.states.as_slice()).unwrap_or_default();
    if states.is_empty() {
        let _ = writeln!(out, "(no sampled states were recorded)");
        return;
    }
    let _ = writeln!(out, "First {} sampled states:", states.len());
    for (j, s) in states.iter().enumerate() {
        let point: Vec<String> = s.point.iter().map(|(a, b)| format!("{a}={b}")).collect();
        let values: Vec<String> = s
            .values
            .iter()
            .map(|(e, v)| match v {
                Some(v) => format!(
                    "`{e}` = {}",
                    crate::digits::significant(*v, crate::digits::VALUE)
                ),
                None => format!("`{e}` is not a scalar here"),
            })
            .collect();
        let _ = writeln!(
            out,
            "    {}. {}; {}",
            j + 1,
            point.join(", "),
            values.join(", ")
        );
    }
}

/// Renders the explanation of one decided claim.
pub fn render(r: &Decided<'_>) -> String {
    let c = r.claim;
    let mut out = format!("# {} (Section {})\n\n", c.id, c.section);
    let _ = writeln!(out, "As printed: {}", c.statement);
    let declared = if c.declared {
        c.expect.to_string()
    } else {
        "nothing (reported as found)".to_owned()
    };
    let _ = writeln!(
        out,
        "Declared: {declared}; decided: {} ({})",
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
    reading_section(
        &mut out,
        &r.transcription,
        &c.check,
        &c.transcript,
        &c.statement,
    );
    check_section(&mut out, &c.check, &r.outcome);
    if let (Some(k), Some(o)) = (&c.correction, &r.correction) {
        let _ = writeln!(out, "\n## Correction\n\n{}\nWhy: {}", k.statement, k.reason);
        let _ = writeln!(out, "Declared: {}", k.expect);
        if let Some(t) = &r.correction_transcription {
            reading_section(&mut out, t, &k.check, &k.transcript, &k.statement);
        }
        check_section(&mut out, &k.check, o);
    }
    out
}

/// The transcription: the printed statement as the reader read it, the checked chains
/// typeset as LaTeX, and whether they say the same.
fn reading_section(
    out: &mut String,
    t: &crate::check::transcription::Transcription,
    check: &Check,
    transcript: &crate::derivation::Transcript,
    printed: &str,
) {
    let _ = writeln!(
        out,
        "Transcription: {}",
        super::transcription::describe(t, printed)
    );
    if let Ok(reading) = &transcript.reading {
        for part in &reading.parts {
            for route in &part.routes {
                let mut chain = route[0].text.clone();
                for (m, rel) in route[1..].iter().zip(&part.relations) {
                    chain.push_str(&format!(" {} {}", rel.symbol(), m.text));
                }
                let _ = writeln!(out, "  printed, read as: {chain}");
            }
        }
    }
    for typeset in super::typeset::checked(check, transcript) {
        let _ = writeln!(out, "  checked, typeset: ${typeset}$");
    }
    let _ = writeln!(out);
}
