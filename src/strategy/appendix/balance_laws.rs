//! `balance-v1`, `balance-v2`, `balance-w3`: the printed balance laws (58)–(60) against
//! the Euler–Lagrange equations of the virtual power.

use super::*;

/// The printed law (`sides[0] − sides[1]` of the first chain) as a polynomial whose
/// variables are named like the derived law's (`sigma_12`, `dmu_23`, …).
pub(super) fn printed_law(
    origin: &Origin,
    decls: &Decls,
    check: &Check,
) -> Result<(Poly, VarTable, String), Diagnostic> {
    let chain =
        check
            .chains
            .first()
            .filter(|c| c.len() == 2)
            .ok_or_else(|| {
                origin
            .diagnostic(Span::new(0, 0), "a balance step needs sides = [\"printed law\", \"0\"]")
            .with_help("the left side is the printed equation's left-hand side, e.g. \"dsigma_21\"")
            })?;
    let mut env = ExactEnv::new(decls, &check.defs, &check.assumptions)?;
    let mut value = |k: usize| -> Result<Poly, Diagnostic> {
        let side = &chain[k];
        let node = side
            .node
            .as_ref()
            .map_err(|e| side.origin.diagnostic(e.span, e.message.clone()))?;
        let l = env.eval(node, &side.origin)?;
        l.tensor
            .into_scalar()
            .and_then(|q| q.as_poly().cloned())
            .ok_or_else(|| {
                side.origin.diagnostic(
                    Span::new(0, side.text.len()),
                    "a balance law is a scalar polynomial equation",
                )
            })
    };
    let law = &value(0)? - &value(1)?;
    let text = format!("{} = {}", chain[0].text, chain[1].text);
    Ok((law, env.vars.clone(), text))
}

pub(super) fn translate(p: &Poly, from: &VarTable, to: &mut VarTable) -> Poly {
    let mut out = Poly::default();
    for (m, c) in p.terms() {
        let factors = m
            .factors()
            .iter()
            .map(|&(v, e)| (to.intern(from.name(v)), e))
            .collect();
        out.add_term(crate::kernel::Monomial::from_factors(factors), c.clone());
    }
    out
}

pub(super) fn balance_law(
    v: Velocity,
    origin: &Origin,
    decls: &Decls,
    check: &Check,
) -> Result<Outcome, Diagnostic> {
    let (printed, mut names, text) = printed_law(origin, decls, check)?;
    let mut own = VarTable::new();
    let derived = balance::balance_law(v, 1, &mut own);
    let derived = translate(&derived, &own, &mut names);
    let mut own_flipped = VarTable::new();
    let flipped = balance::balance_law(v, -1, &mut own_flipped);
    let flipped = translate(&flipped, &own_flipped, &mut names);
    let derived_text = derived.display(&names);
    let base = format!(
        "Euler–Lagrange equation of the virtual power (3) for {} with Γ_ij = v_j,i − e_ijk w_k, K_ij = w_j,i (2), fields of x_2 \
         only: {derived_text} = 0 (d-prefixed variables are ∂/∂x_2; rates implied)",
        v.name()
    );
    // A point where the two laws differ: the first variable of the difference set to
    // 1, every other one 0.
    let diff = &printed - &derived;
    let first = diff
        .terms()
        .next()
        .and_then(|(m, _)| m.factors().first().map(|&(v, _)| v));
    let at_point: BTreeMap<String, Rational> = first
        .map(|v| (names.name(v).to_owned(), Rational::int(1)))
        .into_iter()
        .collect();
    let value = |v| {
        if Some(v) == first {
            Rational::int(1)
        } else {
            Rational::int(0)
        }
    };
    match Certificate::proportional(&printed, &derived) {
        Some((certificate, lambda)) => Ok(Outcome::proved(Method::Symbolic, 1, certificate)
            .with_finding(Finding::Appendix {
                text: format!("{base}; the printed law is {lambda} times it"),
            })),
        None => {
            let flip = if Certificate::proportional(&printed, &flipped).is_some() {
                format!(
                    "; the printed law follows from the opposite rotation sign Γ_ij = v_j,i + e_ijk w_k ({} = 0)",
                    flipped.display(&names)
                )
            } else {
                String::new()
            };
            Ok(Outcome::fails(Method::Symbolic, Strength::Proof, 1)
                .with_finding(Finding::Appendix {
                    text: format!("{base}{flip}"),
                })
                .with_counterexample(Counterexample {
                    chain: 1,
                    equality: 1,
                    lhs: text,
                    rhs: format!("{derived_text} = 0"),
                    difference: (&printed - &derived).display(&names),
                    point: at_point
                        .iter()
                        .map(|(k, v)| (k.clone(), v.to_string()))
                        .collect(),
                    lhs_value: printed.eval(&value).map(|v| v.to_string()),
                    rhs_value: derived.eval(&value).map(|v| v.to_string()),
                    ..Counterexample::default()
                }))
        }
    }
}
