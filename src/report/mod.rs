//! Reports: the derivation table in Markdown and JSON. Rendering only; every verdict
//! has been decided before anything here runs.

pub mod json;
pub mod markdown;

use crate::strategy::{Counterexample, Decided, Outcome};
use serde::Serialize;

/// The paper this corpus checks.
pub const PAPER: &str =
    "Papanicolopoulos & Veveakis, Sliding and rolling dissipation in Cosserat plasticity";

/// Verdict counts over a table.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Summary {
    pub holds: usize,
    pub fails: usize,
    pub conditional: usize,
    /// Claims whose verdict (or whose correction's verdict) differs from the one the
    /// derivation file declares.
    pub unexpected: usize,
}

impl Summary {
    pub fn of(rows: &[Decided<'_>]) -> Self {
        let mut s = Summary::default();
        for r in rows {
            match r.outcome.verdict {
                crate::derivation::Verdict::Holds => s.holds += 1,
                crate::derivation::Verdict::Fails => s.fails += 1,
                crate::derivation::Verdict::Conditional => s.conditional += 1,
            }
            if !r.as_expected() {
                s.unexpected += 1;
            }
        }
        s
    }
}

/// One line of evidence for an outcome, in plain text with inline code.
pub fn evidence(o: &Outcome) -> String {
    let mut parts = Vec::new();
    if let Some(n) = &o.numeric {
        let mut line = format!(
            "{} samples (seed {}), {} {:.1e}, tolerance {}",
            n.samples, n.seed, n.residual, n.largest_residual, n.tolerance
        );
        if let Some(x) = &n.exclusion {
            line.push_str(&format!("; excluded {} samples with {x}", n.excluded));
        }
        parts.push(line);
    }
    if let Some(d) = &o.detail {
        parts.push(d.clone());
    }
    match &o.counterexample {
        None if o.numeric.is_none() && o.detail.is_none() => {
            let unit = if o.used_unit_normal {
                ", using n·n = 1"
            } else {
                ""
            };
            parts.push(format!(
                "{} component check{}, every difference identically 0{unit}",
                o.checks,
                if o.checks == 1 { "" } else { "s" }
            ));
        }
        None => {}
        Some(cx) => parts.push(counterexample_text(cx)),
    }
    parts.join("; ")
}

fn counterexample_text(cx: &Counterexample) -> String {
    let mut parts = Vec::new();
    if let Some(m) = &cx.ill_formed {
        parts.push(format!("ill-formed: {m}"));
    }
    if cx.difference.is_empty() && cx.lhs_value.is_some() {
        // A numeric counterexample: a sample where the relation fails.
        let at = if cx.indices.is_empty() {
            String::new()
        } else {
            let idx: Vec<String> = cx.indices.iter().map(|(c, v)| format!("{c}={v}")).collect();
            format!(" at {}", idx.join(", "))
        };
        let pts: Vec<String> = cx.point.iter().map(|(k, v)| format!("{k}={v}")).collect();
        parts.push(format!(
            "counterexample to `{}` vs `{}`{at}: left {}, right {} at {}",
            cx.lhs,
            cx.rhs,
            cx.lhs_value.as_deref().unwrap_or("?"),
            cx.rhs_value.as_deref().unwrap_or("?"),
            pts.join(", ")
        ));
    }
    if !cx.difference.is_empty() {
        let at = if cx.indices.is_empty() {
            String::new()
        } else {
            let idx: Vec<String> = cx.indices.iter().map(|(c, v)| format!("{c}={v}")).collect();
            format!(" at {}", idx.join(", "))
        };
        let modulo = if cx.reduced_on_sphere {
            " (mod n·n = 1)"
        } else {
            ""
        };
        let chain = if cx.chain > 1 {
            format!("chain {}, ", cx.chain)
        } else {
            String::new()
        };
        parts.push(format!(
            "{chain}equality {} (`{}` = `{}`){at}: left − right = `{}`{modulo}",
            cx.equality, cx.lhs, cx.rhs, cx.difference
        ));
        if let (Some(l), Some(r)) = (&cx.lhs_value, &cx.rhs_value) {
            let shown: Vec<String> = cx
                .point
                .iter()
                .filter(|(_, v)| v.as_str() != "0")
                .map(|(k, v)| format!("{k}={v}"))
                .collect();
            let zeros = cx.point.len() - shown.len();
            let where_ = match (shown.len(), zeros) {
                (0, 0) => String::new(),
                (0, _) => " with every variable 0".to_owned(),
                (1..=8, 0) => format!(" at {}", shown.join(", ")),
                (1..=8, _) => format!(" at {}, other variables 0", shown.join(", ")),
                _ => format!(
                    " at a rational point of {} variables (see JSON)",
                    cx.point.len()
                ),
            };
            parts.push(format!("values{where_}: left {l}, right {r}"));
        }
    }
    parts.join("; ")
}
