//! The evidence of an outcome in words, assembled from [`super::words`] (where what a
//! decision recorded becomes a sentence).

use super::words;
use crate::decide::{Counterexample, Outcome};
use crate::kernel::check::Checked;

/// One line of evidence for an outcome, in plain text with inline code.
pub fn evidence(o: &Outcome) -> String {
    let mut parts = Vec::new();
    if let Some(n) = &o.numeric {
        let within = n
            .domain
            .as_ref()
            .map(|d| format!(" with {d}"))
            .unwrap_or_default();
        let mut line = format!(
            "{} samples{within} (seed {}): {}, tolerance {}",
            n.samples,
            n.seed,
            words::measure(n.residual, n.largest_residual, false),
            n.tolerance
        );
        if let Some(x) = &n.exclusion {
            line.push_str(&format!("; excluded {} samples with {x}", n.excluded));
        }
        if n.undefined > 0 {
            line.push_str(&format!(
                "; stepped off {} state{} where a side is undefined but defined next to it",
                n.undefined,
                if n.undefined == 1 { "" } else { "s" }
            ));
        }
        if n.rounding > 0 {
            line.push_str(&format!(
                "; {} state{} where floating point cannot tell whether the relation holds \
                 (the sides' interval enclosures admit it), excluded",
                n.rounding,
                if n.rounding == 1 { "" } else { "s" }
            ));
        }
        if let Some(s) = &n.search {
            let at: Vec<String> = s.at.iter().map(|(k, v)| format!("{k}={v}")).collect();
            line.push_str(&format!(
                "; search for the worst case: {} evaluations from {} starts, {} at {}",
                s.evaluations,
                s.starts,
                words::measure(n.residual, s.worst_margin, true),
                at.join(", ")
            ));
        }
        parts.push(line);
    }
    if let Some(f) = &o.finding {
        parts.push(words::finding(f));
        // A rational-function claim's proof that it holds: the kernel's facts, in
        // words (a refutation's evidence is its counterexample).
        if let (crate::decide::finding::Finding::RationalFunction(_), Some(w), false) = (
            f,
            proof_words(o),
            o.verdict() == crate::derivation::Verdict::Fails,
        ) {
            parts.push(format!("proof: {w}"));
        }
    }
    match &o.counterexample {
        None if o.numeric.is_none() && o.finding.is_none() => {
            let unit = if o.used_unit_normal {
                ", using n·n = 1"
            } else {
                ""
            };
            parts.push(format!(
                "{} component check{}{}, every difference identically 0{unit}{}{}{}",
                o.checks,
                if o.checks == 1 { "" } else { "s" },
                factor(o),
                constraints(o),
                domain(o),
                roots(o)
            ));
        }
        None => {}
        Some(cx) => parts.push(counterexample_text(cx)),
    }
    parts.join("; ")
}

/// What the kernel checked behind an outcome's proofs, item by item: for a
/// conditional, the proof that it holds on its domain (its counterexample outside is
/// stated as a counterexample); for a sign on exactly a set, every part's.
fn checked(o: &Outcome) -> impl Iterator<Item = &Checked> {
    let parts = if o.verdict() == crate::derivation::Verdict::Conditional {
        1
    } else {
        usize::MAX
    };
    o.proofs().iter().take(parts).flat_map(|p| p.summary())
}

/// The rules an exact proof reduced by: the polynomial constraints solved for a power,
/// the squares of the roots taken as variables.
fn constraints(o: &Outcome) -> String {
    checked(o)
        .filter_map(|c| match c {
            Checked::Constraints { rules, .. } => Some(format!(" modulo {}", rules.join(", "))),
            _ => None,
        })
        .collect()
}

/// The square roots an exact proof took, with where their signs were certified.
fn roots(o: &Outcome) -> String {
    checked(o)
        .filter_map(|c| match c {
            Checked::SquareRoot {
                radicand,
                root,
                on,
                substitution,
                ..
            } => {
                let sign = if substitution.is_empty() {
                    String::new()
                } else {
                    format!(", ≥ 0 there by coefficient signs after {substitution}")
                };
                Some(format!("; sqrt({radicand}) = {root} on {on}{sign}"))
            }
            _ => None,
        })
        .collect()
}

/// For a proportionality, the factor the components were compared with.
fn factor(o: &Outcome) -> String {
    checked(o)
        .find_map(|c| match c {
            Checked::Proportional { factor, nonzero } if nonzero.is_empty() => {
                Some(format!(" of left = {factor} · right"))
            }
            Checked::Proportional { factor, nonzero } => Some(format!(
                " of left = {factor} · right where {} ≠ 0",
                nonzero.join(" ≠ 0, ")
            )),
            _ => None,
        })
        .unwrap_or_default()
}

/// Where an identity of quotients holds: every divisor nonzero (empty for
/// polynomials).
fn domain(o: &Outcome) -> String {
    let nonzero = checked(o).find_map(|c| match c {
        Checked::PolynomialIdentity { nonzero, .. } if !nonzero.is_empty() => Some(nonzero),
        _ => None,
    });
    match nonzero {
        None => String::new(),
        Some(fs) => format!(" after clearing denominators; {}", holds_where(fs)),
    }
}

/// `holds where f ≠ 0, g ≠ 0` for the factors of cleared denominators.
fn holds_where(factors: &[String]) -> String {
    let conditions: Vec<String> = factors.iter().map(|f| format!("{f} ≠ 0")).collect();
    format!("holds where {}", conditions.join(", "))
}

/// `name=value` for the coordinates of a point that are not 0.
fn nonzero_coordinates(point: &std::collections::BTreeMap<String, String>) -> Vec<String> {
    point
        .iter()
        .filter(|(_, v)| v.as_str() != "0")
        .map(|(k, v)| coordinate(k, v))
        .collect()
}

/// `x=1/2`, or `x ≈ 0.8452994616` for a value given to ten digits (an irrational root):
/// never `x=≈ …`.
fn coordinate(k: &str, v: &str) -> String {
    if v.starts_with('≈') {
        format!("{k} {v}")
    } else {
        format!("{k}={v}")
    }
}

/// ` at i=1, j=2` for index values (empty for none).
fn at_indices(indices: &std::collections::BTreeMap<String, usize>) -> String {
    if indices.is_empty() {
        return String::new();
    }
    let idx: Vec<String> = indices.iter().map(|(c, v)| format!("{c}={v}")).collect();
    format!(" at {}", idx.join(", "))
}

fn counterexample_text(cx: &Counterexample) -> String {
    let mut parts = Vec::new();
    if let Some(m) = &cx.ill_formed {
        parts.push(format!("ill-formed: {m}"));
    }
    if cx.difference.is_empty() && (cx.lhs_value.is_some() || !cx.aux.is_empty()) {
        // A sampled counterexample: a state where the relation fails, its values
        // there, then the numbers that are not coordinates of the state.
        let at = at_indices(&cx.indices);
        let values = match (&cx.lhs_value, &cx.rhs_value) {
            (Some(l), Some(r)) => format!(": left {l}, right {r}"),
            _ => String::new(),
        };
        let pts: Vec<String> = cx.point.iter().map(|(k, v)| coordinate(k, v)).collect();
        let state = if pts.is_empty() {
            "with every variable it reads 0".to_owned()
        } else {
            format!("at {}", pts.join(", "))
        };
        let aux: String = cx.aux.iter().map(|(k, v)| format!("; {k} {v}")).collect();
        parts.push(format!(
            "counterexample to `{}` vs `{}`{at}{values} {state}{aux}",
            cx.lhs, cx.rhs
        ));
    }
    if !cx.difference.is_empty() {
        let at = at_indices(&cx.indices);
        let modulo = match (cx.reduced_on_sphere, cx.reduced_by_constraints) {
            (true, true) => " (mod n·n = 1 and the constraints)",
            (true, false) => " (mod n·n = 1)",
            (false, true) => " (mod the constraints)",
            (false, false) => "",
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
            let shown = nonzero_coordinates(&cx.point);
            let zeros = cx.point.len() - shown.len();
            let where_ = match (shown.len(), zeros) {
                (0, 0) => String::new(),
                (0, _) => " with every variable 0".to_owned(),
                (_, 0) => format!(" at {}", shown.join(", ")),
                _ => format!(" at {}, other variables 0", shown.join(", ")),
            };
            parts.push(format!("values{where_}: left {l}, right {r}"));
        }
    }
    if let Some(f) = &cx.factor {
        let at = at_indices(&f.indices);
        let pts = nonzero_coordinates(&f.point);
        let point = if pts.is_empty() {
            "with every variable 0".to_owned()
        } else {
            format!("at {}, other variables 0", pts.join(", "))
        };
        let which = if f.of_parameters {
            "no factor of the parameters"
        } else {
            "no constant factor"
        };
        parts.push(format!(
            "the factor {} is fixed by left/right{at}, {point} (left {}, right {}), so {which} works",
            f.factor, f.lhs_value, f.rhs_value
        ));
    }
    parts.join("; ")
}

/// What the kernel checked behind an outcome's proof, in words; `None` without one.
pub fn proof_words(o: &Outcome) -> Option<String> {
    if o.proofs().is_empty() {
        return None;
    }
    let words: Vec<String> = checked(o)
        .map(|c| match c {
            Checked::PolynomialIdentity {
                components,
                modulo_unit_normal,
                nonzero,
                orbits,
            } => {
                let s = if *components == 1 { "" } else { "s" };
                let mut modulo = if *modulo_unit_normal > 0 {
                    format!(" ({modulo_unit_normal} of them modulo n·n = 1)")
                } else {
                    String::new()
                };
                if let Some(o) = orbits {
                    let blocks: Vec<String> = o.blocks.iter().map(|b| format!("`{b}`")).collect();
                    modulo.push_str(&format!(
                        ", one per orbit of the {} components under the permutations of the letters {}, which change neither side",
                        o.of,
                        blocks.join(" and ")
                    ));
                }
                if nonzero.is_empty() {
                    format!("canonical polynomials identical in {components} component{s}{modulo}")
                } else {
                    format!(
                        "numerators identical over a common denominator in {components} component{s}{modulo}; {}",
                        holds_where(nonzero)
                    )
                }
            }
            Checked::Constraints { rules, reduced } => {
                let s = if *reduced == 1 { "" } else { "s" };
                format!(
                    "{reduced} component{s} identical only after reduction by {} (constraints solved for a power, squares of roots)",
                    rules.join(", ")
                )
            }
            Checked::Proportional { factor, nonzero } if nonzero.is_empty() => {
                format!("one polynomial is {factor} times the other")
            }
            Checked::Proportional { factor, nonzero } => format!(
                "one polynomial is {factor} times the other, where {} ≠ 0",
                nonzero.join(" ≠ 0, ")
            ),
            Checked::SquareRoot { radicand, root, on, substitution, cases } => {
                let s = if *cases == 1 { "" } else { "s" };
                let sign = if substitution.is_empty() {
                    String::new()
                } else {
                    format!("; numerator and denominator have coefficients of one sign after {substitution} ({cases} case{s})")
                };
                format!("sqrt({radicand}) = {root} on {on} (its square exactly, its sign as follows){sign}")
            }
            Checked::Values { left, right } => format!("left {left}, right {right} there, exactly"),
            Checked::DifferentFunctions { terms } => format!(
                "the sides differ as functions: their difference over a common denominator is a nonzero polynomial of {terms} term{}, and the box is open",
                if *terms == 1 { "" } else { "s" }
            ),
            Checked::IllFormed { why } => format!("ill-formed in its indices: {why}"),
            Checked::CoefficientSigns { substitution, .. } if substitution.is_empty() => {
                "numerator and denominator are constants of one sign".to_owned()
            }
            Checked::CoefficientSigns { substitution, cases } => {
                let s = if *cases == 1 { "" } else { "s" };
                format!("numerator and denominator have coefficients of one sign after {substitution} ({cases} case{s})")
            }
            Checked::SignOnInterval { interval, relation, pieces, poles } => {
                let s = if *pieces == 1 { "" } else { "s" };
                let undefined = match poles {
                    0 => String::new(),
                    1 => " except at 1 pole".to_owned(),
                    n => format!(" except at {n} poles"),
                };
                if *pieces == 0 {
                    format!("{relation} for {interval}{undefined} (its one point evaluated exactly)")
                } else {
                    format!(
                        "{relation} for {interval}{undefined} (Sturm: real roots isolated, the sign exact on each of {pieces} piece{s})"
                    )
                }
            }
            Checked::ZeroBetween { variable, lo, hi } => {
                format!("a zero or pole in {lo} < {variable} < {hi} (Sturm count)")
            }
            Checked::Constant => "the function does not change with the variable".to_owned(),
            Checked::Limit { variable, to, value, nonzero } => {
                let limit = format!("the limit as {variable} → {to} is {value} (lowest orders)");
                if nonzero.is_empty() {
                    limit
                } else {
                    format!("{limit}; {}", holds_where(nonzero))
                }
            }
            Checked::Roots { interval, zeros, count: Some(n), exactly, .. } => {
                let s = if *zeros == 1 { "" } else { "s" };
                if *exactly {
                    format!("exactly {zeros} real root{s} for {interval} (Sturm count)")
                } else {
                    format!("{zeros} real root{s} for {interval}, not {n} (Sturm count)")
                }
            }
            Checked::Roots { interval, roots, zeros, exactly: false, .. } => {
                let s = if *zeros == 1 { "" } else { "s" };
                format!(
                    "the real roots for {interval} are not exactly [{}]: {zeros} zero{s} in all (Sturm counts)",
                    roots.join(", ")
                )
            }
            Checked::Roots { interval, roots, .. } => {
                if roots.is_empty() {
                    format!("no real root for {interval} (Sturm isolation)")
                } else {
                    format!("the real roots for {interval} are exactly {} (Sturm isolation)", roots.join(", "))
                }
            }
            Checked::RootsOfParameters {
                variable,
                roots,
                multiplicities,
                nonzero,
            } => {
                let factors: Vec<String> = roots
                    .iter()
                    .zip(multiplicities)
                    .map(|(r, m)| match m {
                        1 => format!("({variable} − ({r}))"),
                        m => format!("({variable} − ({r}))^{m}"),
                    })
                    .collect();
                format!(
                    "the numerator is {} times a quotient of one strict sign (exact division), \
                     and {nonzero} polynomial{} (the quotient, the parameters it or a root \
                     divides by, the roots' divisors, the function's divisors at the roots) \
                     of one strict sign on the box (coefficient signs)",
                    if factors.is_empty() { "1".to_owned() } else { factors.join(" ") },
                    if *nonzero == 1 { "" } else { "s" }
                )
            }
            Checked::RootsAt { point, roots, zeros } => {
                let s = if *zeros == 1 { "" } else { "s" };
                format!(
                    "at {}: {zeros} zero{s} (Sturm counts), not exactly [{}]",
                    point.join(", "),
                    roots.join(", ")
                )
            }
            Checked::NotConcyclic { determinant } => {
                format!("four points on no common circle or line (det = {determinant})")
            }
            Checked::OnCircle {
                center,
                radius_squared,
            } => format!(
                "the whole locus lies on the circle with centre {center} and radius² \
                 {radius_squared}, and covers it (a polynomial in the normal at constant \
                 distance from the centre), at every state where these are defined and the \
                 radius is not 0"
            ),
        })
        .collect();
    Some(words.join("; "))
}
