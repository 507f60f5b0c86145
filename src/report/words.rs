//! Findings in words: the only place where what a decision recorded
//! (`decide::Finding`) becomes a sentence.

use crate::decide::finding::{Finding, Point, Rejection, Unresolved};
use crate::decide::Measure;
use crate::digits;

/// A finding as one clause of the evidence.
pub fn finding(f: &Finding) -> String {
    match f {
        Finding::NothingCompared => "no component was compared, so nothing was proved".into(),
        Finding::ResourceLimit { what, at, help } if at.is_empty() => {
            format!("undecided (resource limit): {what}; {help}")
        }
        Finding::ResourceLimit { what, at, help } => format!(
            "undecided (resource limit): {what} (at {at}); {help}"
        ),
        Finding::Uncertified { what, at, help } => {
            format!("undecided: {what} (at {at}); {help}")
        }
        // An overflow is no gap in the domain: the value exists, f64 cannot hold it.
        Finding::Undefined {
            what,
            at,
            point,
            overflow: true,
        } => format!(
            "undecided: the sides overflow floating point on a set of positive measure: {what} \
             (at {at}) at {} and at every state tried near it; restrict `ranges` or `given`, \
             or decide it exactly",
            self::point(point)
        ),
        Finding::Undefined {
            what, at, point, ..
        } => format!(
            "undecided: the sides are undefined on a set of positive measure, not only at \
             isolated points: {what} (at {at}) at {} and at every state tried near it; restrict \
             `ranges` or `given`, or exclude the set with `singular`",
            self::point(point)
        ),
        Finding::Inconclusive { why } => format!("undecided: {why}"),
        Finding::KernelRefused { why } => format!(
            "undecided: the search's result was not accepted by the kernel's check ({why})"
        ),
        Finding::InternalError { message, at } => format!(
            "undecided (internal error): the checker failed while deciding this claim ({message}, \
             at {at}); this is a defect of the checker, not of the derivation: please report it"
        ),
        Finding::TimeLimit { seconds } => format!(
            "undecided (time limit): the decision did not finish within {} s (raise it with \
             `--time-limit SECONDS`; a sampled claim can also lower `samples`)",
            digits::significant(*seconds, 6)
        ),
        Finding::Unconfirmed { difference, why } => format!(
            "undecided: the sides differ as polynomials ({difference}), but the counterexample was \
             not confirmed by a second evaluation: {}",
            rejection(why)
        ),
        Finding::Witness {
            state,
            points,
            determinant,
        } => {
            let state: Vec<String> = state.iter().map(|(k, v)| format!("{k}={v}")).collect();
            let points: Vec<String> = points.iter().map(|(a, b)| format!("({a}, {b})")).collect();
            format!(
                "witness: at {} (other variables 0) and n = ((1−u²), 2u)/(1+u²) for u = 0, 1/2, 2, −1/3, \
                 the points (x, y) = {} lie on no common circle or line: det[x²+y², x, y, 1] = {determinant}",
                state.join(", "),
                points.join(", ")
            )
        }
        Finding::OnCircle {
            center,
            radius_squared,
        } => format!(
            "the locus is a circle: at every state where these are defined and the radius is \
             not 0, every point (x, y) lies on the circle with centre {center} and radius² \
             {radius_squared}, and covers it (a polynomial in the normal at constant distance \
             from the centre runs over the whole circle; checked as an identity in the state \
             and the normal)"
        ),
        Finding::NowhereDefined { radicands, tries } => format!(
            "undecided: the sides are identical modulo the squares of their roots, but at none \
             of {tries} points tried is every radicand positive ({}): the sides may be defined \
             nowhere, and the identity would hold only vacuously",
            radicands.join(", ")
        ),
        Finding::NoPointUnderHypotheses {
            difference,
            hypotheses,
        } => format!(
            "undecided: the sides differ by {difference}, but no exact point where the \
             hypotheses hold ({hypotheses}) and the sides differ was found (they may hold \
             nowhere); this is not a counterexample"
        ),
        Finding::OneSided {
            chain,
            equality,
            left,
            right,
        } => {
            // As the paper prints it, then the file's name (which an edit names).
            let names = |names: &[crate::decide::finding::DraftedSymbol]| {
                let shown: Vec<String> = names
                    .iter()
                    .map(|s| {
                        let name = crate::decide::drafted::shown(&s.name, s.printed.as_deref());
                        match &s.tied {
                            Some(why) => format!("{name} (which the paper may tie: {why})"),
                            None => name,
                        }
                    })
                    .collect();
                match shown.as_slice() {
                    [] => String::new(),
                    [one] => one.clone(),
                    [init @ .., last] => format!("{} and {last}", init.join(", ")),
                }
            };
            let reads = match (left.is_empty(), right.is_empty()) {
                (false, false) => format!(
                    "the left side reads {}; the right side reads {}; neither is read by the other side",
                    names(left),
                    names(right)
                ),
                (false, true) => format!(
                    "the left side reads {}, which the right side does not",
                    names(left)
                ),
                _ => format!(
                    "the right side reads {}, which the left side does not",
                    names(right)
                ),
            };
            format!(
                "undecided (as drafted): {reads}. Equality {equality} of chain {chain} fails as \
                 read, but the draft took every symbol as independent, and the paper may tie \
                 these, in its text or in an equation left to complete: state the tie (a \
                 definition, or `assume`), or delete `drafted = true` once the file's \
                 declarations are checked, to decide it strictly. This is not a counterexample"
            )
        }
        Finding::Tie {
            chain,
            equality,
            tie,
        } => format!(
            "undecided (as drafted): equality {equality} of chain {chain} fails as read, but \
             {tie} would remove the difference, and the paper may state such a tie in words \
             (the draft took every symbol it does not define as independent): state it (a \
             definition, or `assume`), or delete `drafted = true` once the file's \
             declarations are checked, to decide it strictly. This is not a counterexample"
        ),
        Finding::NoConstrainedPoint { difference, tries } => format!(
            "undecided: the sides differ modulo the constraints and the squares of the roots \
             by {difference}, but no exact point where they hold, every root is rational and \
             the sides differ was found in {tries} tries (there may be no real one); this is \
             not a counterexample"
        ),
        Finding::NoWitness { attempts } => format!(
            "undecided: no witness among {attempts} rational states (every four points tried were \
             concyclic); this is not a counterexample"
        ),
        Finding::Unresolved { why, at } => unresolved(why, at),
        Finding::UnresolvedInsideDomain { domain, why, at } => format!(
            "it fails outside the declared domain {domain}; inside, {}",
            unresolved(why, at)
        ),
        Finding::InsideDomain { domain } => {
            format!("the counterexample lies inside the declared domain {domain}")
        }
        Finding::AlsoInsideDomain { domain } => {
            format!("it also fails inside the declared domain {domain}")
        }
        Finding::HoldsOnDomain { samples, domain } => format!(
            "holds on {samples} samples with {domain}; the counterexample lies outside that domain"
        ),
        Finding::DerivativesNotSampled => "not decided: the statement differentiates fields, and only the exact strategy does so (a sample is a point, not a field); write it as a polynomial identity with strategy = \"exact\"".to_owned(),
        Finding::ThroughAdaptiveAverage => {
            "the function averages an argument that is not a polynomial in n (adaptive \
             quadrature); derivatives through it are not checked"
                .into()
        }
        Finding::ClosedFormUndefined { message } => format!(
            "the closed form is undefined at a sample where the derivative exists ({message})"
        ),
        Finding::DerivativeDoesNotExist {
            message,
            component,
            num_dual,
            central,
        } => format!(
            "undecided: the closed form is undefined at a sample ({message}), and ∂/∂{component} does \
             not exist there (num-dual {}, central difference {}); declare the \
             singular set with `singular = …` to exclude such states",
            value(*num_dual),
            value(*central)
        ),
        Finding::DerivativeRoutesDisagree {
            component,
            num_dual,
            central,
            closed,
            at,
        } => format!(
            "undecided: at a sample, ∂/∂{component} is {} by num-dual, {} by \
             central differences and {} by the closed form; the two derivative routes do not \
             agree there, so no verdict is given (point: {})",
            value(*num_dual),
            value(*central),
            value(*closed),
            point(at)
        ),
        Finding::ClosedFormDisagrees => {
            "num-dual and the closed form disagree; central differences agree with num-dual".into()
        }
        Finding::GradientAgrees {
            variables,
            tied,
            convention,
        } => {
            let convention = convention
                .map(|c| {
                    format!(
                        "; tied components ({}), convention: {}",
                        tied.join(", "),
                        c.describe()
                    )
                })
                .unwrap_or_default();
            format!(
                "∂/∂{} by num-dual = closed form = central differences{convention}",
                variables.join(", ")
            )
        }
        Finding::HessianNotFinite { at } => format!(
            "undecided: the Hessian is not finite at a sample (the function is not twice \
             differentiable there; declare `singular = …` to exclude such states); point: {}",
            point(at)
        ),
        Finding::SecondDifferenceDisagrees {
            eigenvalue,
            curvature,
            at,
        } => format!(
            "undecided: num-dual gives the Hessian an eigenvalue {} at a sample, but the \
             second difference of the function along its eigenvector is {}; the two \
             routes do not agree, so no verdict is given (point: {})",
            value(*eigenvalue),
            value(*curvature),
            point(at)
        ),
        Finding::NegativeEigenvalue { curvature } => format!(
            "the Hessian has a negative eigenvalue; the second difference along its eigenvector is \
             {}",
            value(*curvature)
        ),
        Finding::ConvexAgrees { variables } => {
            format!("Hessian in {variables} variables positive semidefinite at every sample")
        }
        Finding::RationalFunction(e) => rational_evidence(e),
    }
}

/// The evidence of a claim about a rational function.
fn rational_evidence(e: &crate::decide::finding::RationalEvidence) -> String {
    let mut parts = vec![format!("decided {} on {}", e.decided, e.domain)];
    if let Some(l) = &e.limit {
        parts.push(format!("the limit is {l}"));
    }
    if !e.points.is_empty() {
        parts.push(e.points.join(", "));
    }
    if let Some(h) = &e.holds_on {
        parts.push(format!("holds on {h}"));
    }
    if let Some(s) = &e.sampled {
        parts.push(format!(
            "sampled: {} exact samples (seed {}{}), {} search evaluations; the smallest margin {} at {}",
            s.samples,
            s.seed,
            if s.excluded > 0 {
                format!(", {} undefined and excluded", s.excluded)
            } else {
                String::new()
            },
            s.search_evaluations,
            s.smallest_margin,
            point(&s.at)
        ));
    }
    parts.join("; ")
}

/// Why a state was not judged, and where.
fn unresolved(why: &Unresolved, at: &Point) -> String {
    match why {
        Unresolved::QuadratureError {
            error,
            limit,
            budget,
        } => {
            let budget = budget
                .map(|b| format!(" (an average stopped at its budget of {b} integrand evaluations)"))
                .unwrap_or_default();
            format!(
                "the error estimate {error:.1e} (relative) exceeds {limit:e}{budget} at {}: the \
                 averages by adaptive quadrature cannot decide it",
                point(at)
            )
        }
        Unresolved::WithinError {
            chain,
            residual,
            clear,
            error,
        } => format!(
            "the sides of chain {chain} differ by {residual:.2e} (relative), within {clear} times the \
             error estimate {error:.1e} at {}: the averages by adaptive quadrature cannot decide it",
            point(at)
        ),
        Unresolved::WithinRounding { random, samples } => format!(
            "at {random} of {samples} random samples (the first at {}) the floating-point \
             values violate the relation but the sides' interval enclosures admit it: \
             floating point cannot tell there (rounding, as where a side cancels or swamps \
             another), and no violation was confirmed anywhere; the exact strategy may \
             decide it",
            point(at)
        ),
        Unresolved::NotConfirmed(r) => format!(
            "a floating-point violation at {} was not confirmed by a second evaluation: {}",
            point(at),
            rejection(r)
        ),
    }
}

/// Why a second evaluation did not confirm a counterexample.
pub fn rejection(r: &Rejection) -> String {
    match r {
        Rejection::Rounding { lhs, rhs } => format!(
            "the floating-point violation is rounding: exactly, left {lhs} and right {rhs} satisfy \
             the relation at the point"
        ),
        Rejection::HypothesisFails { hypothesis } => format!(
            "at the exact point the hypothesis `{hypothesis}` does not hold; the floating-point \
             violation lies on its boundary"
        ),
        Rejection::OnSingularSet => "the exact point lies on the singular set".into(),
        Rejection::Pole { what } => format!("{what} has a pole at the exact point"),
        Rejection::InterpreterDisagrees {
            lhs,
            rhs,
            exact_lhs,
            exact_rhs,
        } => format!(
            "the interpreter gives left {lhs:e}, right {rhs:e} at the point, against the exact \
             {exact_lhs}, {exact_rhs}"
        ),
        Rejection::InterpreterSatisfied { lhs, rhs, residual } => format!(
            "the interpreter does not confirm it: left {lhs:e}, right {rhs:e} (relative residual \
             {residual:.1e})"
        ),
        Rejection::CannotEvaluate { message } => {
            format!("the interpreter cannot evaluate the sides at the point: {message}")
        }
        Rejection::WithinRounding { lhs, rhs } => format!(
            "the violation is within rounding: in interval arithmetic the left side lies in \
             [{:e}, {:e}] and the right in [{:e}, {:e}], which admit the relation",
            lhs.0, lhs.1, rhs.0, rhs.1
        ),
    }
}

/// What a sampled decision measured, with its extreme over the samples (`worst`
/// false) or the worst value the search for the worst case found (`worst` true).
pub fn measure(m: Measure, v: f64, worst: bool) -> String {
    // No comparison was made (every state was excluded, or undefined).
    if v.is_infinite() && v < 0.0 {
        return if worst {
            "no state compared".to_owned()
        } else {
            "no sample compared".to_owned()
        };
    }
    match (m, worst) {
        (Measure::RelativeDifference, false) => {
            format!("the sides differ by at most {v:.1e} (relative)")
        }
        (Measure::RelativeDifference, true) => format!("largest relative difference {v:.1e}"),
        (Measure::RelativeViolation, false) if v <= 0.0 => format!(
            "the inequality held at every sample, by a relative margin of at least {:.1e}",
            v.abs()
        ),
        (Measure::RelativeViolation, true) if v <= 0.0 => {
            format!("smallest relative margin {:.1e} (held)", v.abs())
        }
        (Measure::RelativeViolation, _) => format!("largest relative violation {v:.1e}"),
        (Measure::DifferenceFromClosedForm, false) => {
            format!("the closed form is off by at most {v:.1e} (relative)")
        }
        (Measure::DifferenceFromClosedForm, true) => {
            format!("largest relative difference from the closed form {v:.1e}")
        }
        (Measure::RelativeEigenvalue, false) => {
            format!("Hessian eigenvalues ≥ {v:.1e} (relative to 1 + max |λ|)")
        }
        (Measure::RelativeEigenvalue, true) => {
            format!("smallest Hessian eigenvalue {v:.1e} (relative to 1 + max |λ|)")
        }
    }
}

/// A value compared in a verdict, to [`digits::VALUE`] significant digits.
fn value(x: f64) -> String {
    digits::significant(x, digits::VALUE)
}

/// A point as `name = value, …`.
pub fn point(at: &Point) -> String {
    if at.is_empty() {
        return "(no parameter)".to_owned();
    }
    at.iter()
        .map(|(k, v)| format!("{k} = {v}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Text for a terminal: every control character but the line end (an escape sequence
/// could clear the screen, retitle the window or draw a fake verdict) and every
/// bidirectional control (which reorders what follows it on the line, so that a
/// verdict could read as another) and line separator shown as `\u{…}`, so that what a file or a file
/// name holds is seen, never obeyed.
pub fn inert(s: &str) -> String {
    let bidi = |c: char| matches!(c, '\u{200e}' | '\u{200f}' | '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}' | '\u{61c}' | '\u{2028}' | '\u{2029}');
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        if (c.is_control() && c != '\n') || bidi(c) {
            out.push_str(&format!("\\u{{{:x}}}", u32::from(c)));
        } else {
            out.push(c);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn control_and_bidirectional_characters_are_shown_never_obeyed() {
        assert_eq!(inert("a\u{1b}[31mb"), "a\\u{1b}[31mb");
        assert_eq!(inert("x\u{202e}y\u{2066}z"), "x\\u{202e}y\\u{2066}z");
        assert_eq!(inert("line\nnext σ"), "line\nnext σ");
    }

    #[test]
    fn a_satisfied_inequality_is_said_as_a_margin_not_a_negative_violation() {
        let held = measure(Measure::RelativeViolation, -8.6e-4, false);
        assert_eq!(
            held,
            "the inequality held at every sample, by a relative margin of at least 8.6e-4"
        );
        assert_eq!(
            measure(Measure::RelativeViolation, 0.0, true),
            "smallest relative margin 0.0e0 (held)"
        );
        // Nothing compared is said so, never as a margin of −∞.
        let none = measure(Measure::RelativeDifference, f64::NEG_INFINITY, false);
        assert_eq!(none, "no sample compared");
        assert_eq!(
            measure(Measure::RelativeViolation, 0.25, false),
            "largest relative violation 2.5e-1"
        );
        assert!(!held.contains("-8.6") && !held.contains("≤ 0"));
    }
}
