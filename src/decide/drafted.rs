//! A drafted file's failures (`drafted = true`, written by `cosserat-check draft`).
//!
//! A draft guesses its declarations from the printed symbols, and takes every symbol it
//! does not define as independent. The paper may tie some of them in its text ("the
//! forces on the two faces are equal and opposite", "s is deviatoric", "with $W =
//! \frac12 e_{ij}e_{ij}$") or in an equation the draft could not read. A failure that
//! such a tie would remove is reported as undecided, naming the tie, never as an error
//! of the paper:
//!
//! - the two sides read different symbols ("P = ⟨t⟩" relates `P` to `t` whatever the
//!   paper means), one of which the file's `tied` lists for any tie;
//! - the difference of the sides is linear in a component of such a symbol, beside
//!   other terms: a relation that gives that component in the others removes it
//!   (`W − ½ e·e`);
//! - the difference vanishes when a tensor of rank 2 is symmetric, or when a vector is
//!   of unit length (ties named whether or not `tied` lists the symbol: they relate no
//!   two symbols, and papers often leave them unsaid);
//! - the difference vanishes, and is linear, in the trace of a tensor or the divergence
//!   of a field that `tied` lists (for a trace, or any tie); for a field the text calls
//!   incompressible (`tie = "divergence"`), at any power (`(u_k,k)²`).
//!
//! `tied` holds the reasons `draft` found in the paper's text, each with its line (and,
//! for one claim, the symbols its equation is the first to write, its `introduces`): a
//! failure whose tie the text gives no reason for stands. So does a difference no tie
//! explains: a constant such as (26)'s −4/5, a wrong coefficient of a square (`(½ − ⅓)
//! s_ij s_ij`), a factor that is a special value of a parameter rather than a relation
//! (`μ`, `2μ n_i n_k`).
//!
//! The symbols a side reads are those its exact value depends on (a symbol that
//! cancels, like the pressure in the tangential traction, is not read), or, where the
//! side has no exact value (a cosine, a root), those it names, through definitions.

use super::finding::{DraftedSymbol, Finding};
use super::Outcome;
use crate::algebra::{assignments, Quotient};
use crate::derivation::notation::Notation;
use crate::derivation::{reachable, Check, Side};
use crate::derivation::{TieKind, TiedSymbol};
use crate::eval::exact::env::{component_name, jet_name};
use crate::eval::exact::env::{ExactEnv, Varying};
use crate::eval::labeled::Labeled;
use crate::kernel::poly::{Monomial, Poly};
use crate::kernel::Var;
use crate::lang::{Decls, NodeKind, Target};
use num_traits::Zero;
use std::collections::{BTreeMap, BTreeSet, HashMap};

/// `outcome` unchanged, unless it is a failure of a drafted check that a tie between
/// the draft's independent symbols could remove: then undecided, naming the tie.
pub fn judged(decls: &Decls, check: &Check, outcome: Outcome) -> Outcome {
    let Some(drafted) = &check.drafted else {
        return outcome;
    };
    let (table, tied) = (&*drafted.notation, &*drafted.tied);
    if outcome.verdict() != crate::derivation::Verdict::Fails {
        return outcome;
    }
    let Some(cx) = &outcome.counterexample else {
        return outcome;
    };
    // A statement ill-formed as printed fails by its indices, whatever its symbols.
    if cx.ill_formed.is_some() {
        return outcome;
    }
    let (chain, equality) = (cx.chain, cx.equality);
    let sides = check
        .chains
        .get(chain.wrapping_sub(1))
        .and_then(|c| Some((c.get(equality.wrapping_sub(1))?, c.get(equality)?)));
    let Some((left, right)) = sides else {
        return outcome;
    };
    let (Ok(l_node), Ok(r_node)) = (&left.node, &right.node) else {
        return outcome;
    };
    let named = (named(check, l_node), named(check, r_node));
    // Past the claim's time limit the analysis stops, and nothing is said of the paper.
    let analysed = crate::kernel::interrupt::stoppable(|| {
        let mut exact = Exact::of(decls, check, (left, right));
        let (l, r) = match &exact {
            Some(e) => (e.reads(&e.left), e.reads(&e.right)),
            None => named.clone(),
        };
        // Only a symbol the paper's text may tie to others (`tied`, for any tie or a law,
        // not a trace only) explains sides that read different symbols.
        let any_tie = |n: &String| tied.get(n).is_some_and(|t| t.kind >= TieKind::Law);
        if l != r && l.symmetric_difference(&r).any(any_tie) {
            let shown = |only: BTreeSet<&String>| {
                only.into_iter()
                    .map(|s| DraftedSymbol {
                        name: s.clone(),
                        printed: table.printed_symbol(s).map(str::to_owned),
                        tied: tied.get(s).map(|t| t.why.clone()),
                    })
                    .collect()
            };
            Some(Finding::OneSided {
                chain,
                equality,
                left: shown(l.difference(&r).collect()),
                right: shown(r.difference(&l).collect()),
            })
        } else {
            // The same symbols, or none the text ties to others: a tie of one symbol
            // (a relation, a symmetry, a unit length, a zero trace) may still remove it.
            exact
                .as_mut()
                .and_then(|e| e.tie(decls, &cx.indices, (table, tied)))
                .map(|tie| Finding::Tie {
                    chain,
                    equality,
                    tie,
                })
        }
    });
    let finding = match analysed {
        Ok(finding) => finding,
        Err(_) => Some(Finding::TimeLimit {
            seconds: super::watch::expired().map_or(0.0, |l| l.as_secs_f64()),
        }),
    };
    let Some(finding) = finding else {
        return outcome;
    };
    let mut undecided = Outcome::undecided(outcome.method, outcome.checks).with_finding(finding);
    // What the decision evaluated stays, for `explain`.
    undecided.record = outcome.record;
    undecided
}

/// The symbols `node` names, directly or through the definitions it uses.
fn named(check: &Check, node: &crate::lang::Node) -> BTreeSet<String> {
    let (nodes, _) = reachable(vec![node], &check.defs);
    nodes
        .iter()
        .filter_map(|n| match &n.kind {
            NodeKind::Leaf {
                target: Target::Symbol(s),
                ..
            } => Some(s.clone()),
            _ => None,
        })
        .collect()
}

/// Both sides' exact values, in one environment.
struct Exact<'a> {
    env: ExactEnv<'a>,
    left: Labeled<Quotient>,
    right: Labeled<Quotient>,
    /// Each component of a symbol the sides or the assumptions name: its symbol and
    /// indices (0-based).
    components: HashMap<Var, (String, Vec<usize>)>,
}

impl<'a> Exact<'a> {
    fn of(decls: &'a Decls, check: &'a Check, (left, right): (&Side, &Side)) -> Option<Self> {
        let (Ok(l), Ok(r)) = (&left.node, &right.node) else {
            return None;
        };
        let mut env = ExactEnv::on(
            decls,
            &check.defs,
            &check.assumptions,
            check.strategy.exact_domain(),
        )
        .ok()?;
        // As the identity was decided: a square root of a polynomial that is no square
        // is a variable of its own, compared modulo its square.
        if matches!(check.strategy, crate::derivation::Strategy::Exact { .. }) {
            env.allow_algebraic_roots();
        }
        let left_value = env.eval(l, &left.origin).ok()?;
        let right_value = env.eval(r, &right.origin).ok()?;
        // The symbols the sides name, and those the assumptions compute them from
        // (`S = 3 V / (2 R_g)` makes `V` read where `S` is).
        let mut names = named(check, l);
        names.extend(named(check, r));
        names.extend(check.reads().symbols);
        let mut components = HashMap::new();
        for name in names {
            let Some(&rank) = decls.symbols.get(&name) else {
                continue;
            };
            for idx in assignments(decls.dim, rank) {
                components.insert(env.component_var(&name, &idx), (name.clone(), idx));
            }
        }
        Some(Exact {
            env,
            left: left_value,
            right: right_value,
            components,
        })
    }

    /// The symbols `side`'s value depends on, over all its components (and the fields
    /// whose derivatives it reads).
    fn reads(&self, side: &Labeled<Quotient>) -> BTreeSet<String> {
        let mut out = BTreeSet::new();
        // What the value depends on: its numerator and denominator, not the divisors
        // it cancelled (kept as conditions of where it is defined).
        let depends = |q: &Quotient| {
            let mut vars = q.numerator().variables();
            vars.extend(q.factors().iter().flat_map(|(f, _)| f.variables()));
            vars
        };
        // A root, or a variable a constraint solves for, reads what its rule reads.
        let rules = self.env.rules();
        let through_rules = |vars: Vec<Var>| {
            let mut out = BTreeSet::new();
            let mut stack = vars;
            while let Some(v) = stack.pop() {
                if !out.insert(v) {
                    continue;
                }
                for r in rules.iter().filter(|r| r.var == v) {
                    stack.extend(r.value.variables());
                }
            }
            out
        };
        for q in side.tensor.components() {
            for v in through_rules(depends(q)) {
                if let Some((name, _)) = self.components.get(&v) {
                    out.insert(name.clone());
                } else if let Some(Varying::Jet { field, .. }) = self.env.varying().get(&v) {
                    out.insert(field.clone());
                }
            }
        }
        out
    }

    /// A tie of a common kind that removes the difference of the sides at the failing
    /// component (`indices`, 1-based), described; `None` when none does (or the
    /// difference is not a polynomial).
    fn tie(
        &mut self,
        decls: &Decls,
        indices: &BTreeMap<String, usize>,
        (table, tied): (&Notation, &BTreeMap<String, TiedSymbol>),
    ) -> Option<String> {
        let at = |side: &Labeled<Quotient>| -> Option<Poly> {
            let assignment: Vec<(char, usize)> = side
                .labels
                .iter()
                .map(|&c| Some((c, indices.get(&c.to_string())?.checked_sub(1)?)))
                .collect::<Option<_>>()?;
            let q = side.at(&assignment);
            q.factors().is_empty().then(|| q.numerator().clone())
        };
        let difference = &at(&self.left)? - &at(&self.right)?;
        let normal = self.env.normal_vars();
        let difference = difference.reduce_on_sphere(normal).ok()?;
        // Modulo the constraints and the squares of the roots (`R² = …` with R a root),
        // as the failure was found.
        let rules = self.env.rules();
        let difference =
            crate::kernel::rules::reduce(&difference, rules, crate::kernel::eval::RULE_STEPS)
                .ok()?;
        if difference.is_zero() {
            return None;
        }
        // A difference that still reads a root or a solved variable is a tie's only
        // modulo rules that read the components it would substitute: no symmetry, unit
        // length or trace is claimed of it.
        let ruled: BTreeSet<Var> = rules.iter().map(|r| r.var).collect();
        let algebraic = difference.variables().iter().any(|v| ruled.contains(v));
        // A relation that gives one component in the others.
        for v in difference.variables() {
            let symbol = match (self.components.get(&v), self.env.varying().get(&v)) {
                (Some((n, _)), _) | (None, Some(Varying::Jet { field: n, .. })) => Some(n),
                _ => None,
            };
            if normal.contains(&v)
                || symbol.is_none_or(|n| tied.get(n).is_none_or(|t| t.kind != TieKind::Any))
                || self
                    .env
                    .varying()
                    .get(&v)
                    .is_some_and(|w| matches!(w, Varying::Coordinate(_)))
            {
                continue;
            }
            let linear = difference.terms().all(|(m, _)| m.exponent(v) <= 1);
            let beside = difference.terms().any(|(m, _)| m.exponent(v) == 0);
            if linear && beside {
                let name = self.env.vars.name(v);
                let why = symbol.and_then(|n| tied.get(n)).map_or(String::new(), |t| {
                    format!(" (the paper may state one: {})", t.why)
                });
                return Some(format!(
                    "a relation that gives {} in the other symbols{why}",
                    shown(name, table.printed(name).as_deref())
                ));
            }
        }
        if algebraic {
            return None;
        }
        // A symmetric tensor and a unit vector are ties narrow enough to name whether or
        // not the text gives a reason: they remove only a difference that vanishes for
        // every such tensor or vector, and papers often leave them unsaid.
        let read: BTreeSet<&str> = difference
            .variables()
            .iter()
            .filter_map(|v| self.components.get(v).map(|(n, _)| n.as_str()))
            .collect();
        let said = |name: &str| {
            tied.get(name).map_or(String::new(), |t| {
                format!(" (the paper may say so: {})", t.why)
            })
        };
        for name in read {
            let Some(&rank) = decls.symbols.get(name) else {
                continue;
            };
            let var = |idx: &[usize]| {
                self.components
                    .iter()
                    .find(|(_, (n, i))| n == name && i == idx)
                    .map(|(&v, _)| v)
            };
            if rank == 2 {
                // Antisymmetry is no common tie (it would also remove every trace): only
                // one the text gives a reason for.
                let skew = tied.get(name).is_some_and(|t| t.kind == TieKind::Any);
                let kinds: &[(i64, &str)] = if skew {
                    &[(1, "symmetric"), (-1, "antisymmetric")]
                } else {
                    &[(1, "symmetric")]
                };
                for &(sign, what) in kinds {
                    let mut map: HashMap<Var, (Option<Var>, i64)> = HashMap::new();
                    for i in 0..decls.dim {
                        for j in 0..decls.dim {
                            let Some(v) = var(&[i, j]) else { continue };
                            let image = match i.cmp(&j) {
                                std::cmp::Ordering::Greater => (var(&[j, i]), sign),
                                // An antisymmetric tensor's diagonal is zero.
                                std::cmp::Ordering::Equal if sign < 0 => (None, 0),
                                _ => (Some(v), 1),
                            };
                            map.insert(v, image);
                        }
                    }
                    if substituted(&difference, &map).is_zero() {
                        let why = said(name);
                        let name = shown(name, table.printed_symbol(name));
                        return Some(format!("{name} being {what}{why}"));
                    }
                }
            }
            if rank == 1 {
                let vars: Option<Vec<Var>> = (0..decls.dim).map(|i| var(&[i])).collect();
                if let Some(vars) = vars {
                    if difference
                        .reduce_on_sphere(&vars)
                        .is_ok_and(|p| p.is_zero())
                    {
                        let why = said(name);
                        let name = shown(name, table.printed_symbol(name));
                        return Some(format!("{name} being a unit vector{why}"));
                    }
                }
            }
        }
        self.trace_tie(decls, &difference, (table, tied))
    }

    /// A zero trace of a tensor of rank 2, or a zero divergence of a vector field (and
    /// of its derivatives), that removes `difference`, for a symbol the text ties: each
    /// relation solved for its last diagonal component (`s_33 = −s_11 − s_22`,
    /// `u_3,3j = −u_1,1j − u_2,2j`) and substituted, the difference vanishes, and it is
    /// linear in those components.
    fn trace_tie(
        &mut self,
        decls: &Decls,
        difference: &Poly,
        (table, tied): (&Notation, &BTreeMap<String, TiedSymbol>),
    ) -> Option<String> {
        let last = decls.dim.checked_sub(1)?;
        let said = |t: &TiedSymbol| format!(" (the paper may say so: {})", t.why);
        // (A law explains no zero trace: a wrong coefficient of a divergence stays an
        // error.)
        for (name, t) in tied.iter().filter(|(_, t)| t.kind != TieKind::Law) {
            let mut map: BTreeMap<Var, Poly> = BTreeMap::new();
            let field = decls.fields.contains_key(name);
            match decls.symbols.get(name) {
                Some(2) if !field => {
                    let mut var = |k: usize| self.env.vars.intern(&component_name(name, &[k, k]));
                    let pivot = var(last);
                    let rest = (0..last).fold(Poly::zero(), |acc, k| &acc - &Poly::var(var(k)));
                    map.insert(pivot, rest);
                }
                Some(1) if field => {
                    // Every derivative of the last component by the last coordinate.
                    let pivots: Vec<(Var, Vec<usize>)> = difference
                        .variables()
                        .into_iter()
                        .filter_map(|v| match self.env.varying().get(&v) {
                            Some(Varying::Jet {
                                field: f,
                                idx,
                                orders,
                            }) if f == name
                                && idx.as_slice() == [last]
                                && orders.contains(&last) =>
                            {
                                let mut beta = orders.clone();
                                let at = beta.iter().position(|&o| o == last)?;
                                beta.remove(at);
                                Some((v, beta))
                            }
                            _ => None,
                        })
                        .collect();
                    for (pivot, beta) in pivots {
                        let mut rest = Poly::zero();
                        for k in 0..last {
                            let mut orders = beta.clone();
                            orders.push(k);
                            orders.sort_unstable();
                            let v = self.env.vars.intern(&jet_name(name, &[k], &orders));
                            rest = &rest - &Poly::var(v);
                        }
                        map.insert(pivot, rest);
                    }
                }
                _ => continue,
            }
            // Linear in the trace only: a wrong coefficient of a trace squared (`p²` with
            // p = σ_kk/3) is an error a zero trace would hide, not a tie. A field the
            // text calls incompressible has a zero divergence outright, at any power, and
            // so may one with a reason for any tie (which prevails over "incompressible"
            // when the text gives both).
            let outright = field && matches!(t.kind, TieKind::Divergence | TieKind::Any);
            let linear = map
                .keys()
                .all(|&v| difference.terms().all(|(m, _)| m.exponent(v) <= 1));
            if map.is_empty() || !(linear || outright) {
                continue;
            }
            let reduced = crate::kernel::eval::substitute(difference, &map).ok()?;
            if reduced.is_zero() {
                let what = if field {
                    "of zero divergence"
                } else {
                    "of zero trace"
                };
                let shown = shown(name, table.printed_symbol(name));
                return Some(format!("{shown} being {what}{}", said(t)));
            }
        }
        None
    }
}

/// A symbol or component named in words: as the paper prints it, then its name in
/// the file (which an edit names), or the file's name alone.
pub fn shown(name: &str, printed: Option<&str>) -> String {
    match printed {
        Some(p) => format!("`{p}` (`{name}` in the file)"),
        None => format!("`{name}`"),
    }
}

/// `p` with each variable of `map` replaced by its image times its sign (a sign 0, or
/// no image, makes it 0).
fn substituted(p: &Poly, map: &HashMap<Var, (Option<Var>, i64)>) -> Poly {
    Poly::from_terms(p.terms().filter_map(|(m, c)| {
        let mut factors = Vec::new();
        let mut coefficient = c.clone();
        for &(v, e) in m.factors() {
            match map.get(&v) {
                None => factors.push((v, e)),
                Some((Some(w), sign)) if *sign != 0 => {
                    factors.push((*w, e));
                    if *sign < 0 && e % 2 == 1 {
                        coefficient = -coefficient;
                    }
                }
                _ => return None,
            }
        }
        // Two factors may become one variable (σ₁₂σ₂₁ → σ₁₂²): exponents add, checked.
        let mut merged: BTreeMap<Var, crate::kernel::poly::Exp> = BTreeMap::new();
        for (v, e) in factors {
            let sum = merged.get(&v).map_or(Some(e), |&f| f.checked_add(e))?;
            merged.insert(v, sum);
        }
        Some((
            Monomial::checked_from_factors(merged.into_iter().collect())?,
            coefficient,
        ))
    }))
}
