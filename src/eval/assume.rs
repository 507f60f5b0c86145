//! Assumptions as one exact affine system over the components, solved once.
//!
//! Every component-level assumption is an affine equation with rational coefficients:
//! `symmetric(X)`, `antisymmetric(X)`, `traceless(X)`, a fixed component `sigma_13 = 0`,
//! and any `X_ij… = expression` whose right side is affine in components, such as the
//! minor and major symmetries `C_ijkl = C_jikl`, `C_ijkl = C_klij`. They are collected
//! into one system and solved exactly over ℚ by the kernel ([`crate::algebra::linear`]),
//! so the result does not depend on the order in which they are written, and a
//! contradiction is an input error that names the assumptions that clash.
//!
//! Which components are eliminated is fixed by a rule, not by the order of writing:
//! first the components an assumption sets explicitly (its left side), then the others;
//! within each group, a symbol's components from the highest index down. So `symmetric`
//! eliminates the lower triangle, `traceless` the last diagonal component, and
//! `sigma_13 = 0` the component it names.
//!
//! A component assumption may be polynomial in other symbols, as long as it is affine in
//! the components it constrains (`u_2 = z^2`, `D_12 = t D_11`): every symbol that occurs in
//! a product or a power of any equation is a **parameter** of the system, and each product
//! of parameters is a column of its own, ordered after the components, so the solution
//! gives each eliminated component as an affine function of the free components with a
//! polynomial in the parameters as its constant term. A combination of the equations
//! that constrains the parameters alone is an input error; so is a parameter that is a
//! field (its value would have to be differentiated through the product).
//!
//! An `X = expression` whose right side is not affine (`S = 3 V / (2 R_g)`) substitutes
//! the whole symbol after the system is solved; substitutions are evaluated in the order
//! of their dependencies, and a cycle is an input error.

use super::exact::env::ExactEnv;
use crate::algebra::assignments;
use crate::algebra::linear::{self, AffineEquation};
use crate::derivation::parametrisation::{
    single, Component, Parametrisation, Polynomial, Product, Solved,
};
use crate::derivation::{Assumption, AssumptionKind, Definition};
use crate::kernel::eval::{substitute, RULE_STEPS};
use crate::kernel::rules::{self, Rule};
use crate::kernel::term::component_name;
use crate::kernel::{Poly, Rational, Var};
use crate::lang::{Decls, Diagnostic};
use num_traits::Zero;
use rustc_hash::FxHashMap as HashMap;
use std::cmp::Reverse;
use std::collections::{BTreeMap, BTreeSet};

/// Largest number of component equations one claim may assume (a rank-4 tensor in 3D
/// with minor and major symmetries needs a few hundred).
pub const MAX_EQUATIONS: usize = 20_000;

/// How an assumption enters: equations in the system, polynomial constraints solved
/// after it, a substitution, or a differential hypothesis (solved by the evaluation
/// environment after all of these: `eval::exact::differential`).
enum Role {
    Linear(Vec<Poly>),
    Polynomial(Vec<Poly>),
    Substitution,
    Differential,
}

impl Parametrisation {
    /// Solves the assumptions of one claim.
    pub fn new(
        decls: &Decls,
        defs: &[Definition],
        assumptions: &[Assumption],
    ) -> Result<Self, Diagnostic> {
        // Definitions read by an assumption are read with every component free, as if
        // written out in it.
        let mut env = ExactEnv::unconstrained(decls);
        env.defs = defs;
        // Which component each variable is: needed only to read equations.
        let components = if assumptions.is_empty() {
            HashMap::default()
        } else {
            env.component_vars()
        };
        let mut roles = Vec::with_capacity(assumptions.len());
        for a in assumptions {
            roles.push(role(&mut env, decls, a)?);
        }
        let var_symbol = |v: &Var| components.get(v).map(|(s, _)| s.as_str());
        let symbols_of = |polys: &[Poly]| -> BTreeSet<String> {
            polys
                .iter()
                .flat_map(|p| p.terms().flat_map(|(m, _)| m.factors().to_vec()))
                .filter_map(|(v, _)| var_symbol(&v).map(str::to_owned))
                .collect()
        };
        // Substituted symbols; an affine `X = …` that refers to one becomes a
        // substitution too (it is evaluated after the one it refers to).
        let mut substituted: BTreeSet<String> = BTreeSet::new();
        loop {
            let mut changed = false;
            for (a, r) in assumptions.iter().zip(roles.iter_mut()) {
                let demote = match (&*r, a.kind.symbol()) {
                    (Role::Substitution, Some(symbol)) => {
                        changed |= substituted.insert(symbol.to_owned());
                        false
                    }
                    (Role::Linear(polys), _) => {
                        matches!(a.kind, AssumptionKind::Equals { .. })
                            && !symbols_of(polys).is_disjoint(&substituted)
                    }
                    _ => false,
                };
                if demote {
                    *r = Role::Substitution;
                    changed = true;
                }
            }
            if !changed {
                break;
            }
        }
        let substitutions = substitution_order(assumptions, &roles)?;
        for (a, r) in assumptions.iter().zip(&roles) {
            let Role::Polynomial(polys) = r else { continue };
            if let Some(s) = symbols_of(polys).intersection(&substituted).next() {
                return Err(a
                    .diagnostic(format!(
                        "`{s}` is replaced by a substitution, so it cannot also be constrained"
                    ))
                    .with_help("constrain the symbols of the substitution's right side instead"));
            }
        }
        // The unknowns: every component in an equation, explicit left sides first; a
        // component in a product or a power is a parameter.
        let mut explicit: BTreeSet<&Component> = BTreeSet::new();
        let mut all: BTreeSet<&Component> = BTreeSet::new();
        let mut parameters: BTreeSet<&Component> = BTreeSet::new();
        for (a, r) in assumptions.iter().zip(&roles) {
            let Role::Linear(polys) = r else { continue };
            for p in polys {
                for (m, _) in p.terms() {
                    let product = !matches!(m.factors(), [(_, 1)]);
                    for (v, _) in m.factors() {
                        let c = &components[v];
                        if substituted.contains(&c.0) {
                            return Err(a.diagnostic(
                                format!("`{}` is replaced by a substitution, so its components cannot also be constrained", c.0),
                            ).with_help("constrain the symbols of the substitution's right side instead"));
                        }
                        if product {
                            if decls.varies(&c.0) {
                                return Err(a.diagnostic(format!(
                                    "`{}` is a field, and occurs in a product or a power here",
                                    c.0
                                ))
                                .with_help("a component assumption may be polynomial only in symbols that are not fields; relate whole fields with X = expression"));
                            }
                            parameters.insert(c);
                        }
                        all.insert(c);
                    }
                }
            }
        }
        // Marked after every unknown is known, so that the choice does not depend on the
        // order of the assumptions.
        for (a, r) in assumptions.iter().zip(&roles) {
            if !matches!(r, Role::Linear(_)) {
                continue;
            }
            match &a.kind {
                AssumptionKind::Component { symbol, index, .. } => {
                    explicit.extend(all.get(&(symbol.clone(), index.clone())));
                }
                AssumptionKind::Equals { symbol, .. } => {
                    explicit.extend(all.iter().filter(|c| &c.0 == symbol));
                }
                _ => {}
            }
        }
        let mut unknowns: Vec<&Component> = all
            .iter()
            .copied()
            .filter(|c| !parameters.contains(c))
            .collect();
        unknowns.sort_by_key(|c| (!explicit.contains(c), c.0.clone(), Reverse(c.1.clone())));
        let mut columns: Vec<Product> = unknowns.iter().map(|&c| vec![(c.clone(), 1)]).collect();
        let unknown_count = columns.len();
        // The products of parameters, in a fixed order after the unknowns.
        let product_of = |m: &crate::kernel::Monomial| -> Product {
            m.factors()
                .iter()
                .map(|(v, e)| (components[v].clone(), u32::try_from(*e).unwrap_or(0)))
                .collect()
        };
        let mut products: BTreeSet<Product> = BTreeSet::new();
        for r in &roles {
            let Role::Linear(polys) = r else { continue };
            for (m, _) in polys.iter().flat_map(Poly::terms) {
                let p = product_of(m);
                if !p.is_empty() && single(&p).is_none_or(|c| parameters.contains(c)) {
                    products.insert(p);
                }
            }
        }
        columns.extend(products);
        let column_of: HashMap<&Product, usize> =
            columns.iter().enumerate().map(|(k, c)| (c, k)).collect();
        let mut equations = Vec::new();
        for (k, r) in roles.iter().enumerate() {
            let Role::Linear(polys) = r else { continue };
            for p in polys {
                let mut eq = AffineEquation {
                    coeffs: Default::default(),
                    constant: Rational::int(0),
                    source: k,
                };
                for (m, q) in p.terms() {
                    match m.factors() {
                        [] => eq.constant = q.clone(),
                        _ => {
                            eq.coeffs.insert(column_of[&product_of(m)], q.clone());
                        }
                    }
                }
                equations.push(eq);
            }
        }
        if equations.len() > MAX_EQUATIONS {
            let a = &assumptions[equations[MAX_EQUATIONS].source];
            return Err(a
                .diagnostic(format!(
                    "the assumptions give more than {MAX_EQUATIONS} component equations"
                ))
                .with_help("constrain fewer or smaller tensors"));
        }
        let solution = linear::solve(columns.len(), &equations)
            .map_err(|clash| contradiction(assumptions, &clash.sources))?;
        // A pivot among the products: the equations relate the parameters alone.
        if let Some(k) = (unknown_count..columns.len()).find(|&k| !solution.is_free(k)) {
            // The assumptions that read a parameter of that product.
            let shares = |c: &Product| {
                c.iter()
                    .any(|(f, _)| columns[k].iter().any(|(g, _)| f == g))
            };
            let mut sources: Vec<usize> = equations
                .iter()
                .filter(|e| e.coeffs.keys().any(|c| shares(&columns[*c])))
                .map(|e| e.source)
                .collect();
            sources.dedup();
            let names: Vec<String> = columns[k]
                .iter()
                .map(|((s, i), _)| format!("`{}`", component_name(s, i)))
                .collect();
            let written: Vec<String> = sources
                .iter()
                .map(|&j| format!("`{}`", assumptions[j].text))
                .collect();
            return Err(assumptions[sources[0]]
                .diagnostic(format!(
                    "the assumptions {} constrain the parameters {} (each occurs in a product or a power), not only components",
                    written.join(", "),
                    names.join(", ")
                ))
                .with_help("fix or relate parameters by whole-symbol equations (t = …), not through components"));
        }
        let mut p = Parametrisation {
            columns,
            solution,
            equations,
            substitutions,
            solved: Vec::new(),
            constraints: Vec::new(),
        };
        p.solve_constraints(&mut env, &components, assumptions, &roles)?;
        Ok(p)
    }

    /// Each polynomial constraint, with the solution of the linear system substituted
    /// and reduced by those solved before it, solved for a power of a variable of its
    /// own ([`crate::kernel::rules`], the rule the kernel applies too): a scalar first,
    /// then by name from the highest index down.
    fn solve_constraints(
        &mut self,
        env: &mut ExactEnv<'_>,
        components: &HashMap<Var, Component>,
        assumptions: &[Assumption],
        roles: &[Role],
    ) -> Result<(), Diagnostic> {
        let mut values: BTreeMap<Var, Poly> = BTreeMap::new();
        for d in self.dependents() {
            let value = env.dependent_value(&d);
            let (s, i) = d.component;
            values.insert(env.component_var(s, i), value);
        }
        // Exponents are positive and bounded by the exact evaluation's limit; one that
        // did not fit would be an error, never a silent 0.
        let as_polynomial = |p: &Poly, a: &Assumption| -> Result<Polynomial, Diagnostic> {
            p.terms()
                .map(|(m, q)| {
                    let product = m
                        .factors()
                        .iter()
                        .map(|(v, e)| Some((components[v].clone(), u32::try_from(*e).ok()?)))
                        .collect::<Option<Product>>()
                        .ok_or_else(|| {
                            a.diagnostic("an exponent of this constraint is out of range")
                        })?;
                    Ok((product, q.clone()))
                })
                .collect()
        };
        let mut rules: Vec<Rule> = Vec::new();
        for (a, r) in assumptions.iter().zip(roles) {
            let Role::Polynomial(polys) = r else { continue };
            for g in polys {
                self.constraints.push(as_polynomial(g, a)?);
                let reduced = substitute(g, &values)
                    .ok()
                    .and_then(|g| rules::reduce(&g, &rules, RULE_STEPS).ok())
                    .ok_or_else(|| {
                        a.diagnostic("this constraint is too large to solve exactly")
                            .with_help("constrain fewer or smaller tensors")
                    })?;
                if reduced.is_zero() {
                    continue;
                }
                let decls = env.decls;
                let names = &env.vars;
                let rule = Rule::solve(
                    &reduced,
                    &rules,
                    |v| components.contains_key(&v) && !values.contains_key(&v),
                    |v, d| {
                        let name = names.name(v);
                        (d, decls.symbols.get(name) != Some(&0), Reverse(name.to_owned()))
                    },
                )
                .ok_or_else(|| {
                    a.diagnostic(
                        "this constraint cannot be solved for a power of one variable: no component or scalar occurs in it once, alone, as a power of its own that no other constraint reads",
                    )
                    .with_help("write it so that one symbol occurs only as a pure power (tau^2 = s_ij s_ij / 2, N_ij N_ij = 1); two constraints cannot be solved for, or read, the same variable")
                })?;
                self.solved.push(Solved {
                    component: components[&rule.var].clone(),
                    power: rule.power,
                    value: as_polynomial(&rule.value, a)?,
                });
                rules.push(rule);
            }
        }
        Ok(())
    }
}

/// The equations an assumption contributes, or that it substitutes a whole symbol.
fn role(env: &mut ExactEnv<'_>, decls: &Decls, a: &Assumption) -> Result<Role, Diagnostic> {
    let d = decls.dim;
    if let Some(symbol) = a
        .kind
        .symbol()
        .filter(|s| decls.position.as_deref() == Some(*s))
    {
        return Err(a
            .diagnostic(format!(
                "`{symbol}` is the position: its coordinates are the independent variables of every derivative"
            ))
            .with_help("constrain the fields instead (u_i = A_ij x_j), or use a scalar"));
    }
    let var = |env: &mut ExactEnv<'_>, s: &str, idx: &[usize]| env.component(s, idx);
    Ok(match &a.kind {
        AssumptionKind::Traceless { symbol } => {
            let trace = (0..d).fold(Poly::zero(), |acc, k| &acc + &var(env, symbol, &[k, k]));
            Role::Linear(vec![trace])
        }
        AssumptionKind::Symmetric { symbol } | AssumptionKind::Antisymmetric { symbol } => {
            let anti = matches!(a.kind, AssumptionKind::Antisymmetric { .. });
            let mut out = Vec::new();
            for i in 0..d {
                for j in i..d {
                    if i == j && !anti {
                        continue;
                    }
                    let (x, y) = (var(env, symbol, &[i, j]), var(env, symbol, &[j, i]));
                    out.push(if anti { &x + &y } else { &x - &y });
                }
            }
            Role::Linear(out)
        }
        AssumptionKind::Component {
            symbol,
            index,
            body,
        } => {
            let not_affine = || {
                a.origin
                    .diagnostic(body.span, "a component assumption must be a polynomial in the components, with rational coefficients")
                    .with_help("write e.g. sigma_13 = 0, sigma_22 = sigma_11 or u_2 = z^2; relate whole symbols with X = expression")
            };
            let value = env
                .eval(body, &a.origin)
                .map_err(|_| not_affine())?
                .tensor
                .into_scalar()
                .expect("validated: scalar");
            if !env.is_polynomial(&value) {
                return Err(not_affine());
            }
            Role::Linear(vec![&var(env, symbol, index) - value.numerator()])
        }
        AssumptionKind::Constraint { left, right } => {
            let not_polynomial = || {
                a.diagnostic("a constraint must be a polynomial in the components, with rational coefficients")
                    .with_help("divide by nothing but numbers; keep the normal and fields out of it")
            };
            let (l, r) = (
                env.eval(left, &a.origin).map_err(|_| not_polynomial())?,
                env.eval(right, &a.origin).map_err(|_| not_polynomial())?,
            );
            let letters = left.free_letters();
            let mut out = Vec::new();
            for idx in assignments(d, letters.len()) {
                let assignment: Vec<(char, usize)> =
                    letters.iter().copied().zip(idx.iter().copied()).collect();
                let (x, y) = (l.at(&assignment), r.at(&assignment));
                if !env.is_polynomial(x) || !env.is_polynomial(y) {
                    return Err(not_polynomial());
                }
                out.push(x.numerator() - y.numerator());
            }
            if out
                .iter()
                .all(|p| env.is_affine(&crate::algebra::Quotient::from(p.clone())))
            {
                Role::Linear(out)
            } else {
                Role::Polynomial(out)
            }
        }
        AssumptionKind::Differential { .. } => Role::Differential,
        AssumptionKind::Equals {
            symbol,
            formal,
            body,
        } => {
            let Ok(value) = env.eval(body, &a.origin) else {
                return Ok(Role::Substitution);
            };
            let rank = formal.len();
            let mut out = Vec::new();
            for idx in assignments(d, rank) {
                let assignment: Vec<(char, usize)> =
                    formal.iter().copied().zip(idx.iter().copied()).collect();
                let p = value.at(&assignment);
                if !env.is_affine(p) {
                    return Ok(Role::Substitution);
                }
                out.push(&var(env, symbol, &idx) - p.numerator());
            }
            Role::Linear(out)
        }
    })
}

/// The substitutions, each after those whose symbols its right side refers to.
fn substitution_order(
    assumptions: &[Assumption],
    roles: &[Role],
) -> Result<Vec<usize>, Diagnostic> {
    let subs: Vec<usize> = (0..assumptions.len())
        .filter(|&k| matches!(roles[k], Role::Substitution))
        .collect();
    // A substitution is an `X = …`: it has a symbol.
    let symbol_of = |k: usize| assumptions[k].kind.symbol().unwrap_or_default();
    let of = |symbol: &str| -> Vec<usize> {
        subs.iter()
            .copied()
            .filter(|&k| symbol_of(k) == symbol)
            .collect()
    };
    for &k in &subs {
        if let [first, second, ..] = of(symbol_of(k))[..] {
            let a = &assumptions[second];
            return Err(a
                .diagnostic(format!(
                    "`{}` is already replaced by `{}`",
                    symbol_of(second),
                    assumptions[first].text
                ))
                .with_help("a symbol can be substituted once"));
        }
    }
    // Depth-first, in the order written; a node on the current path again is a cycle.
    fn visit(
        k: usize,
        assumptions: &[Assumption],
        of: &dyn Fn(&str) -> Vec<usize>,
        path: &mut Vec<usize>,
        done: &mut Vec<usize>,
    ) -> Result<(), Diagnostic> {
        if done.contains(&k) {
            return Ok(());
        }
        if let Some(at) = path.iter().position(|&p| p == k) {
            let a = &assumptions[k];
            let cycle: Vec<&str> = path[at..]
                .iter()
                .chain([&k])
                .map(|&p| assumptions[p].kind.symbol().unwrap_or_default())
                .collect();
            return Err(a
                .diagnostic(format!(
                    "substitutions refer to each other in a cycle: {}",
                    cycle.join(" → ")
                ))
                .with_help("a substituted symbol cannot depend on itself"));
        }
        path.push(k);
        for s in &assumptions[k].reads {
            for dep in of(s) {
                visit(dep, assumptions, of, path, done)?;
            }
        }
        path.pop();
        done.push(k);
        Ok(())
    }
    let mut done = Vec::new();
    for &k in &subs {
        visit(k, assumptions, &of, &mut Vec::new(), &mut done)?;
    }
    Ok(done)
}

fn contradiction(assumptions: &[Assumption], sources: &[usize]) -> Diagnostic {
    let line = |a: &Assumption| a.diagnostic("").line;
    let first = &assumptions[sources[0]];
    let names: Vec<String> = sources
        .iter()
        .map(|&k| format!("`{}` (line {})", assumptions[k].text, line(&assumptions[k])))
        .collect();
    let message = if sources.len() == 1 {
        format!("the assumption `{}` has no solution", first.text)
    } else {
        format!(
            "these assumptions contradict each other: {}",
            names.join(", ")
        )
    };
    first
        .diagnostic(message)
        .with_help("together they admit no value of the components; correct or remove one")
}
