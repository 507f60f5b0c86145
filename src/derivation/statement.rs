//! What a check says, in the kernel's terms: its context (declarations, definitions,
//! assumptions, the box of parameter values) and its claim, for the kernel to check a
//! fact against ([`crate::kernel::check`]).
//!
//! The reading is one-to-one: each checked node becomes the term of the same shape,
//! each assumption the equation or substitution it is. Which assumptions are solved
//! as one linear system and in which order the substitutions apply is taken from the
//! untrusted solver ([`super::parametrisation::Parametrisation`]); the kernel verifies that the
//! equations are linear and that no substitution reads a later one.

use super::parametrisation::Parametrisation;
use crate::derivation::{AssumptionKind, Check, ParamBox, Side};
use crate::kernel::statement::{Claim, Context, Definition, Equation, Statement, Substitution};
use crate::kernel::term::{Leaf, MatOp, MatRead, Order, Term};
use crate::lang::check::Target;
use crate::lang::matrix::{MatrixOp, MatrixRead};
use crate::lang::parser::{ExprKind, Func, Wrt};
use crate::lang::{parse_expr, Decls, Diagnostic, Expr, Node, NodeKind};

/// The term a checked node reads as.
pub fn term(node: &Node) -> Term {
    let b = |n: &Node| Box::new(term(n));
    let opaque = |what: &str| Term::Opaque {
        what: what.to_owned(),
        free: node.free_letters(),
    };
    match &node.kind {
        NodeKind::Const(q) => Term::Const {
            value: q.clone(),
            free: node.free_letters(),
        },
        NodeKind::Leaf { target, slots } => {
            let of = match target {
                Target::Symbol(s) => Leaf::Symbol(s.clone()),
                Target::Def(d) => Leaf::Def(d.clone()),
                Target::Delta => Leaf::Delta,
                Target::Eps => Leaf::Eps,
                Target::Normal => Leaf::Normal,
                Target::Pi => return opaque("π is not rational"),
            };
            Term::Leaf {
                of,
                slots: slots.clone(),
            }
        }
        NodeKind::Sum(ts) => Term::Sum(ts.iter().map(term).collect()),
        NodeKind::Product(fs) => Term::Product(fs.iter().map(term).collect()),
        NodeKind::Div(a, d) => Term::Div(b(a), b(d)),
        NodeKind::Neg(a) => Term::Neg(b(a)),
        NodeKind::Pow(a, k) => Term::Pow(b(a), *k),
        NodeKind::Apply(Func::Sqrt, a) => Term::Sqrt(b(a)),
        NodeKind::Apply(f, _) => opaque(&format!("{}(…) has no exact polynomial value", f.name())),
        NodeKind::Apply2(f, _, _) => {
            opaque(&format!("{}(…, …) has no exact polynomial value", f.name()))
        }
        NodeKind::Avg(a) => Term::Avg(b(a)),
        NodeKind::MaxN(_) => opaque("maxn(…) is a maximum over orientations"),
        NodeKind::Deriv(a, slot) => Term::Deriv(b(a), *slot),
        NodeKind::Wrt {
            op,
            body,
            symbol,
            slots,
        } => match op {
            Wrt::Grad => Term::Grad {
                body: b(body),
                symbol: symbol.clone(),
                slots: slots.clone(),
            },
            Wrt::Variation => Term::Variation {
                body: b(body),
                field: symbol.clone(),
                slots: slots.clone(),
            },
        },
        NodeKind::Matrix { rows, cols, op } => {
            let bb = |n: &Node| Box::new(term(n));
            let order = |o: &crate::lang::matrix::Order| Order {
                positions: o.positions.clone(),
                slots: o.slots.clone(),
            };
            let op = match op {
                MatrixOp::Literal(es) => MatOp::Literal(es.iter().map(term).collect()),
                MatrixOp::Def(d) => MatOp::Def(d.clone()),
                MatrixOp::Identity => MatOp::Identity,
                MatrixOp::Sum(ms) => MatOp::Sum(ms.iter().map(term).collect()),
                MatrixOp::Scale(s, m) => MatOp::Scale(bb(s), bb(m)),
                MatrixOp::Product(x, y) => MatOp::Product(bb(x), bb(y)),
                MatrixOp::Transpose(x) => MatOp::Transpose(bb(x)),
                MatrixOp::Inverse(x) => MatOp::Inverse(bb(x)),
                MatrixOp::Adjugate(x) => MatOp::Adjugate(bb(x)),
                MatrixOp::Solve(x, y) => MatOp::Solve(bb(x), bb(y)),
                MatrixOp::View { tensor, rows, cols } => MatOp::View {
                    tensor: bb(tensor),
                    rows: order(rows),
                    cols: cols.as_deref().map(order),
                },
            };
            Term::Mat {
                rows: *rows,
                cols: *cols,
                op,
            }
        }
        NodeKind::Read(read, m) => {
            let order = |o: &crate::lang::matrix::Order| Order {
                positions: o.positions.clone(),
                slots: o.slots.clone(),
            };
            let read = match read {
                MatrixRead::Det => MatRead::Det,
                MatrixRead::Trace => MatRead::Trace,
                MatrixRead::Entry(i, j) => MatRead::Entry(*i, *j),
                MatrixRead::Tensor { rows, cols } => MatRead::Tensor {
                    rows: order(rows),
                    cols: cols.as_deref().map(order),
                },
            };
            Term::Read(read, b(m))
        }
    }
}

/// A side as a term (a side of a matrix chain already reads its entry); `None` for
/// an ill-formed side.
pub fn side(s: &Side) -> Option<Term> {
    s.node.as_ref().ok().map(term)
}

/// The sides of a chain as terms; the literal 0 takes the free indices of the other
/// sides (it stands for the zero tensor of their rank).
fn chain_terms(chain: &[Side], decls: &Decls, defs: &[super::Definition]) -> Vec<Term> {
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
            Ok(n) => term(n),
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
/// assumptions as equations and substitutions, and the box `domain`.
pub fn context(
    decls: &Decls,
    check: &Check,
    domain: Option<&ParamBox>,
) -> Result<Context, Diagnostic> {
    let parametrisation = Parametrisation::new(decls, &check.defs, &check.assumptions)?;
    let substituted = parametrisation.substitutions();
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
                value: term(body),
            },
            AssumptionKind::Equals {
                symbol,
                formal,
                body,
            } => Equation::Equals {
                symbol: symbol.clone(),
                formal: formal.clone(),
                value: term(body),
            },
            AssumptionKind::Constraint { left, right } => Equation::Constraint {
                left: term(left),
                right: term(right),
            },
        });
    }
    let substitutions = substituted
        .iter()
        .filter_map(|&k| match &check.assumptions[k].kind {
            AssumptionKind::Equals {
                symbol,
                formal,
                body,
            } => Some(Substitution {
                symbol: symbol.clone(),
                formal: formal.clone(),
                value: term(body),
            }),
            _ => None,
        })
        .collect();
    Ok(Context {
        dim: decls.dim,
        normal: decls.normal.clone(),
        in_plane: decls.normal_in_plane,
        symbols: decls.symbols.clone(),
        fields: decls.fields.clone(),
        position: decls.position.clone(),
        definitions: check
            .defs
            .iter()
            .map(|d| Definition {
                name: d.sig.name.clone(),
                formal: d.sig.formal.clone(),
                shape: d.sig.shape,
                body: term(&d.body),
            })
            .collect(),
        equations,
        substitutions,
        given: domain.map(|d| d.bounds.clone()).unwrap_or_default(),
    })
}

/// The statement that the sides of every chain of `check` are equal (or, for a
/// proportionality, proportional). Ill-formed sides read as opaque terms.
pub fn equalities(decls: &Decls, check: &Check) -> Result<Statement, Diagnostic> {
    let chains: Vec<Vec<Term>> = check
        .chains
        .iter()
        .map(|c| chain_terms(c, decls, &check.defs))
        .collect();
    let proportional = matches!(check.strategy, super::Strategy::Proportional { .. });
    let mut context = context(decls, check, check.strategy.exact_domain())?;
    keep_read(&mut context, chains.iter().flatten());
    Ok(Statement {
        context,
        claim: if proportional {
            Claim::Proportional { chains }
        } else {
            Claim::Equal { chains }
        },
    })
}

/// Keeps only the definitions that `terms` or the assumptions read (through other
/// definitions): the statement is what the claim says, not the whole file.
fn keep_read<'t>(context: &mut Context, terms: impl Iterator<Item = &'t Term>) {
    fn names(t: &Term, out: &mut Vec<String>) {
        match t {
            Term::Leaf {
                of: Leaf::Def(d), ..
            }
            | Term::Mat {
                op: MatOp::Def(d), ..
            } => out.push(d.clone()),
            _ => {}
        }
        for c in crate::kernel::eval::children(t) {
            names(c, out);
        }
    }
    let mut pending = Vec::new();
    for t in terms {
        names(t, &mut pending);
    }
    for e in &context.equations {
        match e {
            Equation::Component { value, .. } | Equation::Equals { value, .. } => {
                names(value, &mut pending);
            }
            Equation::Constraint { left, right } => {
                names(left, &mut pending);
                names(right, &mut pending);
            }
            _ => {}
        }
    }
    for s in &context.substitutions {
        names(&s.value, &mut pending);
    }
    let mut read = std::collections::BTreeSet::new();
    while let Some(name) = pending.pop() {
        if read.insert(name.clone()) {
            for d in context.definitions.iter().filter(|d| d.name == name) {
                names(&d.body, &mut pending);
            }
        }
    }
    context.definitions.retain(|d| read.contains(&d.name));
}

/// The statement of a claim about a scalar function of parameters, on the box
/// `domain`.
pub fn scalar(decls: &Decls, check: &Check, domain: &ParamBox) -> Result<Statement, Diagnostic> {
    use crate::derivation::{LimitValue as Value, ScalarClaim, Strategy};
    use crate::kernel::statement::LimitValue;
    let Strategy::Scalar { claim, .. } = &check.strategy else {
        unreachable!("a scalar strategy")
    };
    let claim = match &**claim {
        ScalarClaim::SignExactly(..) => {
            unreachable!("decided part by part, each a sign claim (exact_part_checks)")
        }
        ScalarClaim::Sign(sign) => {
            let sides = chain_terms(&check.chains[0], decls, &check.defs);
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
            function: term(&function.node),
            variable: variable.clone(),
            increasing: *increasing,
        },
        ScalarClaim::Limit {
            function,
            variable,
            to,
            value,
        } => Claim::Limit {
            function: term(&function.node),
            variable: variable.clone(),
            to: to.clone(),
            value: match value {
                Value::Finite(e) => LimitValue::Finite(term(&e.node)),
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
            function: term(&function.node),
            variable: variable.clone(),
            roots: roots.iter().map(|r| term(&r.node)).collect(),
            count: *count,
        },
    };
    let mut context = context(decls, check, Some(domain))?;
    let mut read: Vec<&Term> = Vec::new();
    match &claim {
        Claim::Sign { left, right, .. } => read.extend([left, right]),
        Claim::Monotone { function, .. } | Claim::Roots { function, .. } => read.push(function),
        Claim::Limit {
            function, value, ..
        } => {
            read.push(function);
            if let LimitValue::Finite(v) = value {
                read.push(v);
            }
        }
        _ => {}
    }
    let extra: Vec<Term> = match &claim {
        Claim::Roots { roots, .. } => roots.clone(),
        _ => Vec::new(),
    };
    keep_read(&mut context, read.into_iter().chain(&extra));
    Ok(Statement { context, claim })
}

/// The statement that the locus (x, y) over the normal is not a circle.
pub fn not_circle(
    decls: &Decls,
    check: &Check,
    x: &Node,
    y: &Node,
) -> Result<Statement, Diagnostic> {
    let (x, y) = (term(x), term(y));
    let mut context = context(decls, check, None)?;
    keep_read(&mut context, [&x, &y].into_iter());
    Ok(Statement {
        context,
        claim: Claim::NotCircle { x, y },
    })
}
