//! What a check says, in the kernel's terms: its context (declarations, definitions,
//! assumptions, the box of parameter values) and its claim, for the kernel to check a
//! fact against ([`crate::kernel::check`]).
//!
//! The reading is one-to-one: each checked node becomes the term of the same shape
//! (matrices written out in their entries, [`super::lowering`]), each assumption the
//! equation or substitution it is. Which assumptions are solved
//! as one linear system and in which order the substitutions apply is taken from the
//! untrusted solver ([`super::parametrisation::Parametrisation`]); the kernel verifies that the
//! equations are linear and that no substitution reads a later one.

use super::lowering::Lowering;
use super::parametrisation::Parametrisation;
use crate::derivation::{AssumptionKind, Check, ParamBox, Side};
use crate::kernel::statement::{Claim, Context, Equation, LimitValue, Statement, Substitution};
use crate::kernel::term::{Leaf, Term};
use crate::lang::parser::{ExprKind, Func};
use crate::lang::{parse_expr, Decls, Diagnostic, Expr, Node};

/// The sides of a chain as terms; the literal 0 takes the free indices of the other
/// sides (it stands for the zero tensor of their rank).
fn chain_terms(
    chain: &[Side],
    decls: &Decls,
    defs: &[super::Definition],
    l: &mut Lowering,
) -> Vec<Term> {
    let free = chain
        .iter()
        .filter_map(|s| s.node.as_ref().ok())
        .find(|n| !n.is_literal_zero())
        .map(Node::free_letters)
        .unwrap_or_default();
    chain
        .iter()
        .map(|s| match &s.node {
            Ok(n) if n.is_literal_zero() => Term::Const {
                value: crate::kernel::Rational::int(0),
                free: free.clone(),
            },
            Ok(n) => l.term(n),
            Err(_) => printed(&s.text, decls, defs).unwrap_or_else(|| Term::Opaque {
                what: "an ill-formed side outside the reading of index structure".to_owned(),
                free: Vec::new(),
            }),
        })
        .collect()
}

/// The index structure of a side the language refused (ill-formed as printed):
/// names with their index slots, sums, products, quotients, powers, read from the
/// text without the checks that refused it, so that the kernel can confirm what is
/// wrong. `None` for any other construct.
fn printed(text: &str, decls: &Decls, defs: &[super::Definition]) -> Option<Term> {
    fn go(e: &Expr, decls: &Decls, defs: &[super::Definition]) -> Option<Term> {
        let b = |x: &Expr| go(x, decls, defs).map(Box::new);
        Some(match &e.kind {
            ExprKind::Number(q) => Term::Const {
                value: q.clone(),
                free: Vec::new(),
            },
            ExprKind::Name {
                full,
                base,
                indices,
            } => {
                let def = |n: &str| defs.iter().rev().find(|d| d.sig.name == n);
                if decls.symbols.get(full.as_str()) == Some(&0) {
                    return Some(Term::Leaf {
                        of: Leaf::Symbol(full.clone()),
                        slots: Vec::new(),
                    });
                }
                if def(full).is_some_and(|d| d.sig.formal.is_empty() && d.sig.shape.is_none()) {
                    return Some(Term::Leaf {
                        of: Leaf::Def(full.clone()),
                        slots: Vec::new(),
                    });
                }
                let of = match base.as_str() {
                    "delta" => Leaf::Delta,
                    "eps" => Leaf::Eps,
                    n if decls.normal.as_deref() == Some(n) => Leaf::Normal,
                    n if decls.symbols.contains_key(n) => Leaf::Symbol(n.to_owned()),
                    n if def(n).is_some() => Leaf::Def(n.to_owned()),
                    _ => return None,
                };
                let slots = indices
                    .iter()
                    .map(|t| match t.ch.to_digit(10) {
                        Some(d) if d >= 1 => Some(crate::kernel::term::Slot::Fixed(d as usize - 1)),
                        Some(_) => None,
                        None => Some(crate::kernel::term::Slot::Letter(t.ch)),
                    })
                    .collect::<Option<Vec<_>>>()?;
                Term::Leaf { of, slots }
            }
            ExprKind::Neg(a) => Term::Neg(b(a)?),
            ExprKind::Add(x, y) => Term::Sum(vec![go(x, decls, defs)?, go(y, decls, defs)?]),
            ExprKind::Sub(x, y) => Term::Sum(vec![go(x, decls, defs)?, Term::Neg(b(y)?)]),
            ExprKind::Mul(x, y) => {
                // Products are flattened, so that a letter's occurrences are counted
                // across all the factors at once.
                let mut fs = Vec::new();
                for f in [go(x, decls, defs)?, go(y, decls, defs)?] {
                    match f {
                        Term::Product(inner) => fs.extend(inner),
                        other => fs.push(other),
                    }
                }
                Term::Product(fs)
            }
            ExprKind::Div(x, y) => Term::Div(b(x)?, b(y)?),
            ExprKind::Pow(x, k) => Term::Pow(b(x)?, *k),
            ExprKind::Call(Func::Sqrt, a) => Term::Sqrt(b(a)?),
            // A function of scalars is a scalar: what is inside does not reach the
            // index structure around it.
            ExprKind::Call(f, _) => Term::Opaque {
                what: format!("{}(…)", f.name()),
                free: Vec::new(),
            },
            ExprKind::Call2(f, _, _) => Term::Opaque {
                what: format!("{}(…, …)", f.name()),
                free: Vec::new(),
            },
            _ => return None,
        })
    }
    go(&parse_expr(text).ok()?, decls, defs)
}

/// The context of a check: declarations, its definitions in scope order, its
/// assumptions as equations and substitutions, and the box `domain`. The definitions
/// the matrices need are added by [`finish`], once the claim's terms are read too.
fn context(
    decls: &Decls,
    check: &Check,
    domain: Option<&ParamBox>,
    l: &mut Lowering,
) -> Result<Context, Diagnostic> {
    let parametrisation = Parametrisation::new(decls, &check.defs, &check.assumptions)?;
    let substituted = parametrisation.substitutions();
    for d in &check.defs {
        l.offer(&d.sig.name, &d.sig.formal, &d.body);
    }
    let mut equations = Vec::new();
    for (k, a) in check.assumptions.iter().enumerate() {
        if substituted.contains(&k) {
            continue;
        }
        equations.push(match &a.kind {
            AssumptionKind::Traceless { symbol } => Equation::Traceless(symbol.clone()),
            AssumptionKind::Symmetric { symbol } => Equation::Symmetric(symbol.clone()),
            AssumptionKind::Antisymmetric { symbol } => Equation::Antisymmetric(symbol.clone()),
            AssumptionKind::Component {
                symbol,
                index,
                body,
            } => Equation::Component {
                symbol: symbol.clone(),
                index: index.clone(),
                value: l.term(body),
            },
            AssumptionKind::Equals {
                symbol,
                formal,
                body,
            } => Equation::Equals {
                symbol: symbol.clone(),
                formal: formal.clone(),
                value: l.term(body),
            },
            AssumptionKind::Constraint { left, right } => Equation::Constraint {
                left: l.term(left),
                right: l.term(right),
            },
            AssumptionKind::Differential { left, right } => Equation::Differential {
                left: l.term(left),
                right: l.term(right),
            },
        });
    }
    let mut substitutions = Vec::new();
    for &k in substituted {
        if let AssumptionKind::Equals {
            symbol,
            formal,
            body,
        } = &check.assumptions[k].kind
        {
            substitutions.push(Substitution {
                symbol: symbol.clone(),
                formal: formal.clone(),
                value: l.term(body),
            });
        }
    }
    Ok(Context {
        dim: decls.dim,
        normal: decls.normal.clone(),
        in_plane: decls.normal_in_plane,
        symbols: decls.symbols.clone(),
        fields: decls.fields.clone(),
        position: decls.position.clone(),
        definitions: Vec::new(),
        equations,
        substitutions,
        given: domain.map(|d| d.bounds.clone()).unwrap_or_default(),
        hypotheses: match &check.strategy {
            super::Strategy::Exact { hypotheses, .. } => hypotheses
                .iter()
                .map(|h| crate::kernel::statement::Hypothesis {
                    left: l.term(&h.left),
                    right: l.term(&h.right),
                    sign: h.sign,
                })
                .collect(),
            _ => Vec::new(),
        },
    })
}

/// The statement of `claim` in `context`, with the definitions that the claim or the
/// assumptions read (through other definitions), in the kernel's terms: the
/// statement is what the claim says, not the whole file.
fn finish(mut context: Context, claim: Claim, l: Lowering) -> Statement {
    let mut read: Vec<&Term> = Vec::new();
    match &claim {
        Claim::Equal { chains } | Claim::Proportional { chains } => {
            read.extend(chains.iter().flatten())
        }
        Claim::Sign { left, right, .. } => read.extend([left, right]),
        Claim::Monotone { function, .. } => read.push(function),
        Claim::Roots {
            function, roots, ..
        } => {
            read.push(function);
            read.extend(roots);
        }
        Claim::Limit {
            function, value, ..
        } => {
            read.push(function);
            if let LimitValue::Finite(v) = value {
                read.push(v);
            }
        }
        Claim::NotCircle { x, y } => read.extend([x, y]),
    }
    for h in &context.hypotheses {
        read.extend([&h.left, &h.right]);
    }
    for e in &context.equations {
        match e {
            Equation::Component { value, .. } | Equation::Equals { value, .. } => read.push(value),
            Equation::Constraint { left, right } | Equation::Differential { left, right } => {
                read.extend([left, right])
            }
            _ => {}
        }
    }
    read.extend(context.substitutions.iter().map(|s| &s.value));
    let definitions = l.finish(read.into_iter());
    context.definitions = definitions;
    Statement { context, claim }
}

/// The statement that the sides of every chain of `check` are equal (or, for a
/// proportionality, proportional). Ill-formed sides read as opaque terms.
pub fn equalities(decls: &Decls, check: &Check) -> Result<Statement, Diagnostic> {
    let mut l = Lowering::default();
    let context = context(decls, check, check.strategy.exact_domain(), &mut l)?;
    let chains: Vec<Vec<Term>> = check
        .chains
        .iter()
        .map(|c| chain_terms(c, decls, &check.defs, &mut l))
        .collect();
    let proportional = matches!(check.strategy, super::Strategy::Proportional { .. });
    let claim = if proportional {
        Claim::Proportional { chains }
    } else {
        Claim::Equal { chains }
    };
    Ok(finish(context, claim, l))
}

/// The statement of a claim about a scalar function of parameters, on the box
/// `domain`.
pub fn scalar(decls: &Decls, check: &Check, domain: &ParamBox) -> Result<Statement, Diagnostic> {
    use crate::derivation::{LimitValue as Value, ScalarClaim, Strategy};
    let Strategy::Scalar { claim, .. } = &check.strategy else {
        unreachable!("a scalar strategy")
    };
    let mut l = Lowering::default();
    let context = context(decls, check, Some(domain), &mut l)?;
    let claim = match &**claim {
        ScalarClaim::SignExactly(..) | ScalarClaim::Stationary(_) => {
            unreachable!(
                "decided part by part, each a sign claim (exact_part_checks, stationary_parts)"
            )
        }
        ScalarClaim::Sign(sign) => {
            let sides = chain_terms(&check.chains[0], decls, &check.defs, &mut l);
            Claim::Sign {
                left: sides[0].clone(),
                right: sides[1].clone(),
                sign: *sign,
            }
        }
        ScalarClaim::Monotone {
            function,
            variable,
            increasing,
        } => Claim::Monotone {
            function: l.term(&function.node),
            variable: variable.clone(),
            increasing: *increasing,
        },
        ScalarClaim::Limit {
            function,
            variable,
            to,
            value,
        } => Claim::Limit {
            function: l.term(&function.node),
            variable: variable.clone(),
            to: to.clone(),
            value: match value {
                Value::Finite(e) => LimitValue::Finite(l.term(&e.node)),
                Value::Signed(plus) => LimitValue::Signed(*plus),
                Value::Unsigned => LimitValue::Unsigned,
            },
        },
        ScalarClaim::Roots {
            function,
            variable,
            roots,
            count,
        } => Claim::Roots {
            function: l.term(&function.node),
            variable: variable.clone(),
            roots: roots.iter().map(|r| l.term(&r.node)).collect(),
            count: *count,
        },
    };
    Ok(finish(context, claim, l))
}

/// The statement that the locus (x, y) over the normal is not a circle.
pub fn not_circle(
    decls: &Decls,
    check: &Check,
    x: &Node,
    y: &Node,
) -> Result<Statement, Diagnostic> {
    let mut l = Lowering::default();
    let context = context(decls, check, None, &mut l)?;
    let (x, y) = (l.term(x), l.term(y));
    Ok(finish(context, Claim::NotCircle { x, y }, l))
}
