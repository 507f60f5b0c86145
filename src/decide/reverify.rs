//! Every counterexample is re-verified before a `fails` is printed, by a second
//! evaluation of both sides at the reported point that does not share the method of
//! the one that found it.
//!
//! - A counterexample of the **exact** strategy (canonical polynomials evaluated at a
//!   rational point) is evaluated again by the floating-point interpreter on the
//!   expression tree (`real`: no canonical forms, averages by quadrature), and both
//!   sides must agree with the exact values.
//! - A counterexample of the **numeric** strategy (found in `f64` on the compiled tape)
//!   is evaluated again **exactly** where the sides, the hypotheses and the singular set
//!   are polynomial: at the rational point the sample's `f64` values denote (every
//!   `f64` is a rational), with the normal moved onto the unit sphere by an exact
//!   rational parametrisation. Confirmed there, the `fails` is proved. Where the sides
//!   are not polynomial, the tree-walking interpreter evaluates them again instead of
//!   the tape (strength `sampled`).
//!
//!   Both evaluations round alike, so where the sides have interval enclosures
//!   ([`crate::eval::interval`]) the violation counts only if the enclosures exclude the
//!   relation.
//!
//! A counterexample that the second evaluation does not confirm is never printed: the
//! claim is `undecided`, with the reason.

use super::enclosures::Enclosures;
use super::finding::Rejection;
use super::outcome::{Counterexample, Reverified};
use super::sampler::{relation_holds, Sampler};
use crate::algebra::{Quotient, Tensor};
use crate::derivation::Definition;
use crate::derivation::{Check, Constraint, Expression, Relation};
use crate::eval::exact::env::{component_name, ExactEnv, Labeled};
use crate::eval::real::RealError;
use crate::eval::real::{component_pairs, RealEnv};
use crate::eval::state::State;
use crate::eval::taylor::TaylorFields;
use crate::kernel::{Rational, Var};
use crate::lang::Diagnostic;
use crate::lang::{Decls, Node, NodeKind, Slot, Target};
use crate::tolerance::REVERIFY_AGREEMENT;
use rustc_hash::FxHashMap as HashMap;
use std::cell::RefCell;
use std::collections::BTreeMap;

/// The exact strategy's counterexample at `point` (values of the variables the sides
/// use, and the whole normal), with exact side values `lhs`, `rhs`, confirmed by the `f64`
/// interpreter. `Err` says why it is not confirmed.
pub(crate) fn exact_counterexample(
    decls: &Decls,
    check: &Check,
    env: &ExactEnv<'_>,
    point: &BTreeMap<Var, Rational>,
    (lhs, rhs): (&Rational, &Rational),
    cx: &Counterexample,
) -> Result<Reverified, Rejection> {
    // Variables the point leaves out do not occur in the sides; any value will do as
    // long as the assumptions can be evaluated there (`S = 3 V / (2 R_g)` cannot at
    // R_g = 0), so a few are tried.
    let mut last = NoValue::NotScalar;
    // Derivatives of fields are taken by central differences (see `taylor`), to the
    // stencil's accuracy rather than to rounding.
    let (agreement, how) = if check.reads().differentiates {
        (
            crate::tolerance::TAYLOR_AGREEMENT,
            Reverified::TaylorDifferences,
        )
    } else {
        (REVERIFY_AGREEMENT, Reverified::FloatingPoint)
    };
    for absent in [0.0, 1.0, 0.577_215_664_901_532_9] {
        match float_values(decls, check, env, point, absent, cx) {
            Ok((lf, rf)) => return confirm(lf, rf, lhs, rhs, agreement, how),
            Err(why) => last = why,
        }
    }
    Err(Rejection::CannotEvaluate {
        message: last.to_string(),
    })
}

/// Whether the interpreter's values agree with the exact ones.
fn confirm(
    lf: f64,
    rf: f64,
    lhs: &Rational,
    rhs: &Rational,
    agreement: f64,
    how: Reverified,
) -> Result<Reverified, Rejection> {
    let agrees = |f: f64, q: &Rational| {
        let e = q.to_f64();
        f.is_finite() && (f - e).abs() <= agreement * (1.0 + e.abs())
    };
    if agrees(lf, lhs) && agrees(rf, rhs) {
        Ok(how)
    } else {
        Err(Rejection::InterpreterDisagrees {
            lhs: lf,
            rhs: rf,
            exact_lhs: lhs.to_string(),
            exact_rhs: rhs.to_string(),
        })
    }
}

/// Why the floating-point interpreter gave no value to confirm with.
#[derive(Clone, Debug, thiserror::Error)]
pub enum NoValue {
    /// A side of the statement could not be read.
    #[error("{}", .0.message)]
    Side(Diagnostic),
    #[error("{}", .0.message)]
    Eval(RealError),
    #[error("the assumptions cannot be evaluated there: {}", .0.message)]
    Assumptions(RealError),
    #[error("not a scalar")]
    NotScalar,
    #[error("the counterexample's indices are not among the components")]
    Indices,
}

/// Both sides of the counterexample's equality by the interpreter at `point`, the
/// variables it leaves out set to `absent`.
fn float_values(
    decls: &Decls,
    check: &Check,
    env: &ExactEnv<'_>,
    point: &BTreeMap<Var, Rational>,
    absent: f64,
    cx: &Counterexample,
) -> Result<(f64, f64), NoValue> {
    let (real, n) = interpreter_at(decls, check, env, point, absent)?;
    let chain = &check.chains[cx.chain - 1];
    // Only the counterexample's component is evaluated where the side allows it.
    let at: Vec<(char, usize)> = cx
        .indices
        .iter()
        .filter_map(|(c, &v)| Some((c.chars().next()?, v.checked_sub(1)?)))
        .collect();
    let side = |k: usize| -> Result<crate::eval::real::Labeled<f64>, NoValue> {
        let node = chain[k]
            .node
            .as_ref()
            .map_err(|e| NoValue::Side(chain[k].origin.diagnostic(e.span, e.message.clone())))?;
        match node.at_indices(&at) {
            Some(fixed) => {
                let mut budget = INLINED_NODES;
                match inline_fixed(&fixed, real.defs, &mut budget) {
                    Some(inlined) => real.eval(&inlined, &n),
                    None => real.eval(&fixed, &n),
                }
            }
            None => real.eval(node, &n),
        }
        .map_err(NoValue::Eval)
    };
    let (l, r) = (side(cx.equality - 1)?, side(cx.equality)?);
    pick(decls.dim, &l, &r, cx)
}

/// The most nodes [`inline_fixed`] writes for one side; past it the side is evaluated
/// as written.
const INLINED_NODES: usize = 100_000;

/// `node` with each definition that it reads at fixed index values only (every slot
/// fixed) replaced by the definition's body at those values, where that body is made of
/// constants, symbols, δ, ε, the normal, sums, products, negations, powers and
/// definitions alone: the interpreter then forms the one component with the
/// operations, in the order, that give it in the definition's whole tensor, and no
/// other (with no division and no function, every component is defined wherever this
/// one is). The node is walked through sums, products, negations, powers, quotients and
/// averages; `None` past `budget` nodes (a definition read many times is written
/// anew each time).
fn inline_fixed(node: &Node, defs: &[Definition], budget: &mut usize) -> Option<Node> {
    *budget = budget.checked_sub(1)?;
    let each = |xs: &[Node], budget: &mut usize| -> Option<Vec<Node>> {
        xs.iter().map(|x| inline_fixed(x, defs, budget)).collect()
    };
    let kind = match &node.kind {
        NodeKind::Leaf {
            target: Target::Def(name),
            slots,
        } => match inlined_definition(name, slots, defs, budget)? {
            Some(body) => return Some(body),
            None => node.kind.clone(),
        },
        NodeKind::Sum(xs) => NodeKind::Sum(each(xs, budget)?),
        NodeKind::Product(xs) => NodeKind::Product(each(xs, budget)?),
        NodeKind::Neg(a) => NodeKind::Neg(Box::new(inline_fixed(a, defs, budget)?)),
        NodeKind::Pow(a, k) => NodeKind::Pow(Box::new(inline_fixed(a, defs, budget)?), *k),
        NodeKind::Avg(a) => NodeKind::Avg(Box::new(inline_fixed(a, defs, budget)?)),
        NodeKind::Div(a, b) => NodeKind::Div(
            Box::new(inline_fixed(a, defs, budget)?),
            Box::new(inline_fixed(b, defs, budget)?),
        ),
        other => other.clone(),
    };
    Some(Node {
        kind,
        free: node.free.clone(),
        bound: node.bound.clone(),
        span: node.span,
    })
}

/// The body of definition `name` at the fixed values of `slots`, inlined in turn, when
/// it has slots, every one fixed, and the body is a polynomial (see [`inline_fixed`]);
/// `Some(None)` where it is not; `None` past `budget`.
fn inlined_definition(
    name: &str,
    slots: &[Slot],
    defs: &[Definition],
    budget: &mut usize,
) -> Option<Option<Node>> {
    let values: Option<Vec<usize>> = slots
        .iter()
        .map(|s| match s {
            Slot::Fixed(v) => Some(*v),
            Slot::Letter(_) => None,
        })
        .collect();
    let def = defs.iter().rev().find(|d| d.sig.name == name);
    let (Some(values), Some(def)) = (values.filter(|v| !v.is_empty()), def) else {
        return Some(None);
    };
    if def.sig.formal.len() != values.len() {
        return Some(None);
    }
    let at: Vec<(char, usize)> = def.sig.formal.iter().copied().zip(values).collect();
    let Some(body) = def.body.at_indices(&at).filter(polynomial) else {
        return Some(None);
    };
    inline_fixed(&body, defs, budget).map(Some)
}

/// Whether `node` is made of constants, symbols, δ, ε, the normal, definitions, sums,
/// products, negations and powers alone.
fn polynomial(node: &Node) -> bool {
    match &node.kind {
        NodeKind::Const(_) => true,
        NodeKind::Leaf { target, .. } => !matches!(target, Target::Pi),
        NodeKind::Sum(xs) | NodeKind::Product(xs) => xs.iter().all(polynomial),
        NodeKind::Neg(a) | NodeKind::Pow(a, _) => polynomial(a),
        _ => false,
    }
}

/// A scalar expression by the interpreter at `point` (the variables it leaves out set
/// to 0, 1 or Euler's constant, the first at which the assumptions can be evaluated).
pub(crate) fn interpret_scalar(
    decls: &Decls,
    check: &Check,
    env: &ExactEnv<'_>,
    point: &BTreeMap<Var, Rational>,
    node: &crate::lang::Node,
) -> Result<f64, NoValue> {
    let mut last = NoValue::NotScalar;
    for absent in [0.0, 1.0, 0.577_215_664_901_532_9] {
        match interpret_with(decls, check, env, point, node, absent) {
            Ok(v) => return Ok(v),
            Err(why) => last = why,
        }
    }
    Err(last)
}

/// A scalar expression by the interpreter at `point`, the variables it leaves out set
/// to `absent` (NaN for a value that must not depend on one: a plot).
pub(crate) fn interpret_with(
    decls: &Decls,
    check: &Check,
    env: &ExactEnv<'_>,
    point: &BTreeMap<Var, Rational>,
    node: &crate::lang::Node,
    absent: f64,
) -> Result<f64, NoValue> {
    let (real, n) = interpreter_at(decls, check, env, point, absent)?;
    let v = real.eval(node, &n).map_err(NoValue::Eval)?;
    v.tensor.into_scalar().ok_or(NoValue::NotScalar)
}

/// The interpreter's environment at `point`, the variables it leaves out set to
/// `absent`, with the normal it evaluates at.
fn interpreter_at<'c>(
    decls: &'c Decls,
    check: &'c Check,
    env: &ExactEnv<'_>,
    point: &BTreeMap<Var, Rational>,
    absent: f64,
) -> Result<(RealEnv<'c, f64>, Vec<f64>), NoValue> {
    let value = |name: &str| {
        env.vars
            .lookup(name)
            .and_then(|v| point.get(&v))
            .map_or(absent, Rational::to_f64)
    };
    let d = decls.dim;
    let symbols: HashMap<String, Tensor<f64>> = decls
        .symbols
        .iter()
        .map(|(name, &rank)| {
            let t = Tensor::from_fn(d, rank, |idx| value(&component_name(name, idx)));
            (name.clone(), t)
        })
        .collect();
    let normal = env.normal_vars();
    let mut n: Vec<f64> = normal
        .iter()
        .map(|&v| point.get(&v).map_or(f64::NAN, Rational::to_f64))
        .collect();
    if n.iter().any(|x| x.is_nan()) {
        // The sides do not depend on the normal: any unit vector will do.
        n = vec![0.0; normal.len()];
        if let Some(first) = n.first_mut() {
            *first = 1.0;
        }
    }
    n.resize(d, 0.0);
    let mut real = RealEnv::new(decls, &check.defs, symbols);
    // Fields are functions of the position only where the statement differentiates
    // them; elsewhere they are values at the point, like any symbol.
    if check.reads().differentiates {
        real = real.with_fields(taylor_fields(decls, env, point, absent));
    }
    if let Some(p) = env.parametrisation() {
        real.assume(p, &check.assumptions, &n)
            .map_err(NoValue::Assumptions)?;
    }
    Ok((real, n))
}

/// The fields as Taylor polynomials with the point's jet values (`RealEnv::assume`
/// ties the components that assumptions tie to others). A derivative that a
/// differential hypothesis determines takes its value there, so the polynomials
/// satisfy the hypotheses to the orders the statement reads.
fn taylor_fields(
    decls: &Decls,
    env: &ExactEnv<'_>,
    point: &BTreeMap<Var, Rational>,
    absent: f64,
) -> TaylorFields {
    let free = |v: Var| match point.get(&v) {
        Some(q) => q.to_f64(),
        None if env.is_field_value(v) => absent,
        None => 0.0,
    };
    let at = |v: Var| match env.determined_derivative(v) {
        Some(p) => Some(
            p.terms()
                .map(|(m, c)| {
                    m.factors().iter().fold(c.to_f64(), |acc, &(x, e)| {
                        acc * free(x).powi(i32::try_from(e).unwrap_or(i32::MAX))
                    })
                })
                .sum(),
        ),
        None => point.get(&v).map(Rational::to_f64),
    };
    TaylorFields::new(decls.dim, env.varying(), &env.vars, &at, absent)
}

/// The counterexample's component of both sides.
fn pick(
    dim: usize,
    l: &crate::eval::real::Labeled<f64>,
    r: &crate::eval::real::Labeled<f64>,
    cx: &Counterexample,
) -> Result<(f64, f64), NoValue> {
    let (labels, pairs) = component_pairs(dim, l, r);
    let wanted: Vec<usize> = labels
        .iter()
        .map(|c| cx.indices.get(&c.to_string()).map_or(0, |v| v - 1))
        .collect();
    pairs
        .into_iter()
        .find(|(a, _, _)| *a == wanted)
        .map(|(_, lf, rf)| (lf, rf))
        .ok_or(NoValue::Indices)
}

/// The numeric strategy's counterexample at `state`, confirmed exactly where the
/// statement is polynomial, else by the interpreter. `Err` says why it is not
/// confirmed.
pub(crate) fn numeric_counterexample(
    sampler: &Sampler<'_>,
    state: &State,
    relation: Relation,
    cx: &mut Counterexample,
) -> Result<Reverified, Rejection> {
    match exactly(sampler, state, relation, cx) {
        // The values shown are the exact ones (the sample's may be rounding).
        Some(Ok((l, r))) => {
            let shown = |q: &Rational| crate::digits::significant(q.to_f64(), crate::digits::VALUE);
            cx.lhs_value = Some(shown(&l));
            cx.rhs_value = Some(shown(&r));
            Ok(Reverified::Exact)
        }
        Some(Err(why)) => Err(why),
        None => by_interpreter(sampler, state, relation, cx),
    }
}

/// `None` when some expression involved is not polynomial (or over the exact budget).
fn exactly(
    sampler: &Sampler<'_>,
    state: &State,
    relation: Relation,
    cx: &Counterexample,
) -> Option<Result<(Rational, Rational), Rejection>> {
    let check = sampler.check;
    let mut env = ExactEnv::new(sampler.decls, &check.defs, &check.assumptions).ok()?;
    let chain = &check.chains[cx.chain - 1];
    let mut side = |k: usize| -> Option<Labeled<Quotient>> {
        let s = &chain[k];
        env.eval(s.node.as_ref().ok()?, &s.origin).ok()
    };
    let (l, r) = (side(cx.equality - 1)?, side(cx.equality)?);
    let mut poly =
        |e: &Expression| -> Option<Labeled<Quotient>> { env.eval(&e.node, &e.origin).ok() };
    let scalar = |e: &Expression,
                  poly: &mut dyn FnMut(&Expression) -> Option<Labeled<Quotient>>| {
        poly(e).and_then(|v| v.tensor.into_scalar())
    };
    let mut hypotheses: Vec<(Relation, Quotient, Quotient)> = Vec::new();
    for Constraint {
        lhs, relation, rhs, ..
    } in &sampler.sampling.given
    {
        hypotheses.push((*relation, scalar(lhs, &mut poly)?, scalar(rhs, &mut poly)?));
    }
    let singular = match &sampler.sampling.singular {
        Some(e) => Some(scalar(e, &mut poly)?),
        None => None,
    };
    let point = exact_point(&mut env, state)?;
    let at = |v: Var| point.get(&v).cloned().unwrap_or_else(|| Rational::int(0));
    let assignment: Vec<(char, usize)> = cx
        .indices
        .iter()
        .filter_map(|(c, v)| Some((c.chars().next()?, v - 1)))
        .collect();
    let (Some(lv), Some(rv)) = (l.at(&assignment).eval(&at), r.at(&assignment).eval(&at)) else {
        return Some(Err(Rejection::Pole {
            what: "a side".into(),
        }));
    };
    for (k, (rel, a, b)) in hypotheses.iter().enumerate() {
        let (Some(a), Some(b)) = (a.eval(&at), b.eval(&at)) else {
            return Some(Err(Rejection::Pole {
                what: format!("hypothesis `{}`", sampler.sampling.given[k].text),
            }));
        };
        if !rel.holds(&a, &b) {
            return Some(Err(Rejection::HypothesisFails {
                hypothesis: sampler.sampling.given[k].text.clone(),
            }));
        }
    }
    if let Some(s) = singular {
        if s.eval(&at).is_none_or(|v| v.is_zero()) {
            return Some(Err(Rejection::OnSingularSet));
        }
    }
    Some(if relation.holds(&lv, &rv) {
        Err(Rejection::Rounding {
            lhs: lv.to_string(),
            rhs: rv.to_string(),
        })
    } else {
        Ok((lv, rv))
    })
}

/// The exact route at sampled states, built once per claim when first needed: the
/// environment and each side evaluated (`None` where not polynomial or over the
/// budget).
struct ExactSides<'a> {
    env: Option<ExactEnv<'a>>,
    sides: HashMap<(usize, usize), Option<Labeled<Quotient>>>,
}

/// [`ExactSides`] of one claim, built when first needed.
pub(crate) struct ExactCache<'a> {
    decls: &'a Decls,
    check: &'a Check,
    sides: RefCell<Option<ExactSides<'a>>>,
}

impl<'a> ExactCache<'a> {
    pub(crate) fn new(decls: &'a Decls, check: &'a Check) -> Self {
        ExactCache {
            decls,
            check,
            sides: RefCell::new(None),
        }
    }

    /// [`ExactSides::holds_at`], the sides evaluated on first use.
    pub(crate) fn holds_at(
        &self,
        state: &State,
        relation: Relation,
        at: (usize, usize),
        values: &[(char, usize)],
    ) -> Option<bool> {
        let mut sides = self.sides.borrow_mut();
        let sides = sides.get_or_insert_with(|| ExactSides {
            env: ExactEnv::new(self.decls, &self.check.defs, &self.check.assumptions).ok(),
            sides: HashMap::default(),
        });
        sides.holds_at(self.check, state, relation, at, values)
    }
}

impl<'a> ExactSides<'a> {
    /// Whether, exactly, sides `k` and `k + 1` of chain `chain` (0-based) satisfy
    /// `relation` at the rational point `state` denotes, for the index values `at`
    /// (0-based); `None` where the sides are not polynomial, or not defined there.
    fn holds_at(
        &mut self,
        check: &Check,
        state: &State,
        relation: Relation,
        (chain, k): (usize, usize),
        at: &[(char, usize)],
    ) -> Option<bool> {
        let env = self.env.as_mut()?;
        let mut side = |j: usize| -> Option<Quotient> {
            let value = self.sides.entry((chain, j)).or_insert_with(|| {
                let s = &check.chains[chain][j];
                env.eval(s.node.as_ref().ok()?, &s.origin).ok()
            });
            value.as_ref().map(|v| v.at(at).clone())
        };
        let (l, r) = (side(k)?, side(k + 1)?);
        let point = exact_point(env, state)?;
        let value = |v: Var| point.get(&v).cloned().unwrap_or_else(|| Rational::int(0));
        Some(relation.holds(&l.eval(&value)?, &r.eval(&value)?))
    }
}

/// The exact point a sampled state denotes: each component's `f64` value as the
/// rational it is, the normal moved exactly onto the unit circle or sphere.
fn exact_point(env: &mut ExactEnv<'_>, state: &State) -> Option<HashMap<Var, Rational>> {
    let mut point = HashMap::default();
    for (v, (symbol, idx)) in env.component_vars() {
        let x = *state.symbols.get(&symbol)?.get(&idx);
        point.insert(v, crate::algebra::rational::from_f64_exact(x)?);
    }
    let normal = env.normal_vars().to_vec();
    if !normal.is_empty() {
        let n = on_unit_sphere(&state.n[..normal.len()])?;
        point.extend(normal.into_iter().zip(n));
    }
    // A component solved for by a polynomial constraint is a rounded root: unless the
    // rounded values satisfy every constraint exactly, the state denotes no exact point.
    let value = |v: Var| point.get(&v).cloned().unwrap_or_else(|| Rational::int(0));
    if !env.rules().iter().all(|r| r.holds_at(&value)) {
        return None;
    }
    Some(point)
}

/// A rational point of the unit circle or sphere next to `n` (a unit vector in `f64`),
/// by stereographic projection from the pole farther from `n`.
fn on_unit_sphere(n: &[f64]) -> Option<Vec<Rational>> {
    let q = |x: f64| crate::algebra::rational::from_f64_exact(x);
    let stereographic = super::points::stereographic;
    match n {
        // u = y/(1 + s x), s = ±1 the sign of x.
        [x, y] => {
            let s = if *x >= 0.0 { 1.0 } else { -1.0 };
            Some(stereographic(&[q(y / (1.0 + s * x))?], s < 0.0))
        }
        // u = x/(1 + s z), v = y/(1 + s z), s = ±1 the sign of z.
        [x, y, z] => {
            let s = if *z >= 0.0 { 1.0 } else { -1.0 };
            let (u, v) = (q(x / (1.0 + s * z))?, q(y / (1.0 + s * z))?);
            Some(stereographic(&[u, v], s < 0.0))
        }
        _ => None,
    }
}

/// The sides evaluated again by the interpreter (never the tape) at the state.
fn by_interpreter(
    sampler: &Sampler<'_>,
    state: &State,
    relation: Relation,
    cx: &Counterexample,
) -> Result<Reverified, Rejection> {
    let chain = &sampler.check.chains[cx.chain - 1];
    let cannot = |message: String| Rejection::CannotEvaluate { message };
    let side = |k: usize| {
        let node = chain[k]
            .node
            .as_ref()
            .map_err(|e| cannot(e.message.clone()))?;
        sampler
            .interpret(&state.symbols, node, &state.n)
            .map_err(|e| cannot(e.message))
    };
    let (l, r) = (side(cx.equality - 1)?, side(cx.equality)?);
    let (lf, rf) = pick(sampler.decls.dim, &l, &r, cx).map_err(|e| cannot(e.to_string()))?;
    let (ok, residual) = relation_holds(relation, lf, rf);
    if ok {
        return Err(Rejection::InterpreterSatisfied {
            lhs: lf,
            rhs: rf,
            residual,
        });
    }
    // Both evaluations round alike: the violation counts only where the sides'
    // interval enclosures exclude the relation.
    let (labels, _) = component_pairs(sampler.decls.dim, &l, &r);
    let at: Vec<(char, usize)> = labels
        .iter()
        .map(|&c| (c, cx.indices.get(&c.to_string()).map_or(0, |v| v - 1)))
        .collect();
    // An enclosure taken on the domain (a root of an argument that rounding leaves on
    // both sides of 0) can dismiss a violation but not confirm one; the interpreter's
    // confirmation stands then, as where there is no enclosure.
    match Enclosures::new(sampler, state).pair(cx.chain - 1, cx.equality - 1, &at) {
        Ok((li, ri, _)) if li.may_satisfy(relation, &ri) => Err(Rejection::WithinRounding {
            lhs: (li.lo, li.hi),
            rhs: (ri.lo, ri.hi),
        }),
        Ok((_, _, false)) => Ok(Reverified::Intervals),
        Ok((_, _, true)) | Err(_) => Ok(Reverified::Interpreter),
    }
}
