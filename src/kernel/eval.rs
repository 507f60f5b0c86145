//! The kernel's evaluator: a [`Term`] in its [`Context`] to a tensor of fractions,
//! one per value of its free letters.
//!
//! It is written for being read rather than for speed: dense tensors, a contraction
//! that visits the values of a product's letters in order (skipping those where a
//! factor is 0), no cancellation. Every component of a symbol is a polynomial variable
//! (`sigma_12`, `n_3`, `R_g`); the linear assumptions are solved once by Gaussian
//! elimination and the substitutions applied in order; a definition is evaluated once;
//! `avg` applies the exact moments of the normal; a derivative along the position is
//! the chain rule on jet variables (`u_2,13` is ∂²u_2/∂x_1∂x_3); `grad` differentiates
//! the term ([`super::differentiate`]) and evaluates the derivative at the state; a
//! square root is a root the caller offers, accepted only when its square is the
//! radicand and its sign is certified on the box. A hostile term stops at the work
//! budget, never runs without bound.

use super::differentiate::{differentiate, Definitions};
use super::frac::Frac;
use super::poly::{Poly, Var, VarTable};
use super::rational::Rational;
use super::rules::Rule;
use super::statement::{Context, Definition, Equation, FracData, PolyData};
pub use super::term::{children, component_name, EvalError};
use super::term::{Leaf, Letters, Ranks, Slot, Term};
use num_traits::{One, Zero};
use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::rc::Rc;

/// Term products one statement may spend in all.
pub const WORK: usize = 50_000_000;

/// Most terms one reduction by the polynomial constraints may replace.
pub const RULE_STEPS: usize = 1_000_000;

/// The deepest [`Env::eval`] may recurse, through terms and the definitions they read:
/// more than any file the loader accepts, few enough for the evaluating thread's stack
/// (`crate::parallel::STACK`, about 13 KB a level).
pub const MAX_DEPTH: usize = 20_000;

/// The most components a symbol, definition or intermediate value may have (3^10).
pub const MAX_COMPONENTS: usize = 59_049;

type R<T> = Result<T, EvalError>;

/// A value: a tensor over its sorted free letters, its components row-major.
#[derive(Clone, Debug, PartialEq)]
pub struct Value {
    pub letters: Vec<char>,
    pub comps: Vec<Frac>,
}

impl Value {
    fn scalar(f: Frac) -> Value {
        Value {
            letters: Vec::new(),
            comps: vec![f],
        }
    }

    pub fn comps(&self) -> &[Frac] {
        &self.comps
    }

    pub fn letters(&self) -> &[char] {
        &self.letters
    }
}

/// One axis of a factor in a contraction: the position of its letter among the
/// contraction's letters, or a fixed index value.
#[derive(Clone, Copy, Debug)]
enum Axis {
    Letter(usize),
    Fixed(usize),
}

/// A contraction under way ([`Env::contract`]): each factor's components, axes and
/// how many letters must have values before it is known; the letters' values so far,
/// and where the result's letters are among them; the result's components.
struct Walk<'f> {
    factors: Vec<(&'f [Frac], Vec<Axis>, usize)>,
    values: Vec<usize>,
    out: Vec<usize>,
    comps: Vec<Frac>,
}

impl<'f> Walk<'f> {
    /// Factor `k`'s component at the letters' values so far.
    fn component(&self, k: usize, d: usize) -> R<&'f Frac> {
        let (t, axes, _) = &self.factors[k];
        let offset = axes.iter().fold(0, |acc, a| {
            acc * d
                + match *a {
                    Axis::Letter(p) => self.values[p],
                    Axis::Fixed(value) => value,
                }
        });
        t.get(offset)
            .ok_or_else(|| EvalError::IllFormed("a slot count that is not the rank".into()))
    }
}

/// No two names of a context give one variable: a declared scalar `a_1` and the
/// first component of a vector `a` (or of the normal, the position, a field's
/// derivative `theta_,2`) would be read as one unknown.
fn distinct_names(ctx: &Context) -> R<()> {
    let indexed: Vec<&str> = ctx
        .symbols
        .iter()
        .filter(|(name, &rank)| rank > 0 || ctx.fields.contains_key(*name))
        .map(|(name, _)| name.as_str())
        .chain(ctx.normal.as_deref())
        .collect();
    let names = ctx
        .symbols
        .keys()
        .map(String::as_str)
        .chain(ctx.normal.as_deref());
    for name in names {
        for prefix in &indexed {
            let generated = name
                .strip_prefix(prefix)
                .and_then(|rest| rest.strip_prefix('_'))
                .is_some_and(|rest| {
                    !rest.is_empty() && rest.chars().all(|c| c.is_ascii_digit() || c == ',')
                });
            if generated {
                return Err(EvalError::IllFormed(format!(
                    "`{name}` is also the name of a component of `{prefix}`"
                )));
            }
        }
    }
    Ok(())
}

/// The variable name of a field component's derivative: `u_2,13` is ∂²u_2/∂x_1∂x_3,
/// `theta_,2` is ∂θ/∂x_2 (the component's own name when `orders` is empty).
pub fn jet_name(field: &str, idx: &[usize], orders: &[usize]) -> String {
    let mut name = component_name(field, idx);
    if !orders.is_empty() {
        name.push_str(if idx.is_empty() { "_," } else { "," });
        name.extend(orders.iter().map(|k| char::from(b'1' + *k as u8)));
    }
    name
}

/// Every assignment of `rank` indices in `0..dim`, row-major.
pub fn assignments(dim: usize, rank: usize) -> Vec<Vec<usize>> {
    let mut out = vec![Vec::new()];
    for _ in 0..rank {
        out = out
            .into_iter()
            .flat_map(|p| {
                (0..dim).map(move |k| {
                    let mut q = p.clone();
                    q.push(k);
                    q
                })
            })
            .collect();
    }
    out
}

fn count(dim: usize, rank: usize) -> R<usize> {
    u32::try_from(rank)
        .ok()
        .and_then(|r| dim.checked_pow(r))
        .filter(|&n| n <= MAX_COMPONENTS)
        .ok_or(EvalError::Limit)
}

/// The sign of a permutation of distinct values (0 when two repeat).
fn permutation_sign(p: &[usize]) -> i64 {
    let mut sign = 1;
    for a in 0..p.len() {
        for b in a + 1..p.len() {
            if p[a] == p[b] {
                return 0;
            }
            if p[a] > p[b] {
                sign = -sign;
            }
        }
    }
    sign
}

/// What a variable a derivative acts on stands for.
#[derive(Clone, Debug)]
enum Varying {
    Coordinate(usize),
    Jet {
        field: String,
        idx: Vec<usize>,
        orders: Vec<usize>,
    },
}

/// A linear differential hypothesis solved for its highest derivative:
/// ∂^orders field_idx = value. Every derivative of it holds too, so ∂^β field_idx for
/// β ⊇ orders is ∂^(β − orders) value.
#[derive(Clone, Debug)]
struct JetRule {
    field: String,
    idx: Vec<usize>,
    orders: Vec<usize>,
    value: Poly,
}

/// The rank of a derivative among the unknowns of the differential hypotheses: by
/// order, then field and component, then the coordinates, the highest first. It is a
/// term order: two derivatives compare the same after both are differentiated once
/// more, so every derivative of a rule keeps the rule's leading derivative.
pub fn jet_rank(
    field: &str,
    idx: &[usize],
    orders: &[usize],
    dim: usize,
) -> (usize, String, Vec<usize>, Vec<usize>) {
    let mut counts = vec![0; dim];
    for &k in orders {
        if let Some(c) = counts.get_mut(k) {
            *c += 1;
        }
    }
    counts.reverse();
    (orders.len(), field.to_owned(), idx.to_vec(), counts)
}

/// The coordinates of `orders` beyond those of `base` (both sorted), when `orders`
/// holds every coordinate of `base` as often.
fn beyond(orders: &[usize], base: &[usize]) -> Option<Vec<usize>> {
    let mut rest = orders.to_vec();
    for k in base {
        let at = rest.iter().position(|x| x == k)?;
        rest.remove(at);
    }
    Some(rest)
}

/// A square root the kernel accepted: √radicand = root on the box `on`, the root's
/// sign certified by coefficients.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RootTaken {
    pub radicand: String,
    pub root: String,
    pub on: String,
    pub sign: super::sign::ByCoefficients,
}

/// A fraction in words, at most eight terms of its numerator.
pub fn show(f: &Frac, names: &VarTable) -> String {
    let num = f.numerator().display_truncated(names, 8);
    if f.denominator().is_empty() {
        return num;
    }
    let den: Vec<String> = f
        .denominator()
        .iter()
        .map(|(g, k)| {
            let g = g.display_truncated(names, 8);
            if *k == 1 {
                format!("({g})")
            } else {
                format!("({g})^{k}")
            }
        })
        .collect();
    format!("({num}) / {}", den.join(" "))
}

/// Whether `v` is a component of a declared symbol that an assumption may eliminate:
/// not the normal, not a coordinate of the position (the independent variable of every
/// derivative), not a derivative of a field.
fn is_free_component(env: &Env<'_>, v: Var) -> bool {
    !env.normal.contains(&v)
        && !matches!(env.varying.get(&v), Some(Varying::Coordinate(_)))
        && !matches!(env.varying.get(&v), Some(Varying::Jet { orders, .. }) if !orders.is_empty())
}

/// One statement's evaluation environment.
pub struct Env<'c> {
    ctx: &'c Context,
    pub vars: VarTable,
    normal: Vec<Var>,
    varying: HashMap<Var, Varying>,
    /// The components of each symbol read so far, shared by every reading.
    symbols: HashMap<String, Rc<[Frac]>>,
    /// Those of δ, ε and the normal (in this order), once read.
    constants: [Option<Rc<[Frac]>>; 3],
    cache: HashMap<String, Value>,
    /// Definitions made by `grad`: the derivatives of definitions, by name.
    derived: HashMap<String, Definition>,
    /// The statement's definitions by name (the last of a name counts).
    defined: HashMap<&'c str, &'c Definition>,
    active: Vec<String>,
    /// Symbols some assumption mentions: a field among them cannot be varied.
    assumed: BTreeSet<String>,
    /// Square roots offered: accepted only after the kernel checks them.
    roots: Vec<Frac>,
    /// The eliminated components, each with its value in the free ones.
    pivots: BTreeMap<Var, Poly>,
    /// The polynomial constraints, each solved for a power of a variable of its own,
    /// then the square roots taken as variables of their own.
    pub rules: Vec<Rule>,
    /// Whether a square root of a polynomial that is no square becomes a variable of
    /// its own (`r² = radicand`, `r ≥ 0`): only where the facts checked reduce by the
    /// rules (an identity, a refutation at a point).
    pub algebraic_roots: bool,
    /// The square roots accepted, as the evidence states them.
    pub roots_taken: Vec<RootTaken>,
    /// Square roots accepted so far, by radicand.
    certified: Vec<(Frac, Frac)>,
    /// The differential hypotheses, each solved for its highest derivative.
    jet_rules: Vec<JetRule>,
    /// The derivatives the rules determine, by variable, reduced.
    jet_values: HashMap<Var, Poly>,
    work: usize,
    /// How deeply [`Env::eval`] is recursing now.
    depth: usize,
}

impl Ranks for Env<'_> {
    fn dim(&self) -> usize {
        self.ctx.dim
    }
    fn symbol_rank(&self, name: &str) -> Option<usize> {
        self.ctx.symbols.get(name).copied()
    }
    fn def_rank(&self, name: &str) -> Option<usize> {
        self.definition(name).map(|d| d.formal.len())
    }
}

impl<'c> Env<'c> {
    /// The environment of `ctx` with the offered square roots: the assumptions solved
    /// and substituted.
    pub fn new(ctx: &'c Context, roots: &[FracData]) -> R<Self> {
        if !(ctx.dim == 2 || ctx.dim == 3)
            || (ctx.in_plane && (ctx.dim != 3 || ctx.normal.is_none()))
        {
            return Err(EvalError::IllFormed(
                "the dimension is 2 or 3; a normal in a plane needs 3".into(),
            ));
        }
        for &rank in ctx.symbols.values() {
            count(ctx.dim, rank)?;
        }
        let mut env = Env {
            ctx,
            vars: VarTable::new(),
            normal: Vec::new(),
            varying: HashMap::new(),
            symbols: HashMap::new(),
            constants: Default::default(),
            cache: HashMap::new(),
            derived: HashMap::new(),
            defined: ctx
                .definitions
                .iter()
                .map(|d| (d.name.as_str(), d))
                .collect(),
            active: Vec::new(),
            assumed: BTreeSet::new(),
            roots: Vec::new(),
            pivots: BTreeMap::new(),
            rules: Vec::new(),
            algebraic_roots: false,
            certified: Vec::new(),
            roots_taken: Vec::new(),
            jet_rules: Vec::new(),
            jet_values: HashMap::new(),
            work: WORK,
            depth: 0,
        };
        for r in roots {
            let mut f = Frac::from(env.poly_of(&r.num)?);
            for (d, k) in &r.den {
                let d = Frac::from(env.poly_of(d)?);
                let d = env.pow(&d, *k)?;
                f = f.div(&d)?;
            }
            env.roots.push(f);
        }
        if let Some(n) = &ctx.normal {
            let free = if ctx.in_plane { 2 } else { ctx.dim };
            env.normal = (0..free)
                .map(|k| env.vars.intern(&component_name(n, &[k])))
                .collect();
        }
        distinct_names(ctx)?;
        if let Some(d) = ctx.definitions.iter().find(|d| d.name.contains('∂')) {
            return Err(EvalError::IllFormed(format!(
                "`{}`: a definition's name with ∂ is reserved for derivatives",
                d.name
            )));
        }
        env.solve_equations()?;
        // A bounded variable stays free: its interval would otherwise bound a
        // combination of the others, which no check below reads.
        for (name, _) in &ctx.given {
            if env.substituted_or_eliminated(name) {
                return Err(EvalError::Unsupported(format!(
                    "`{name}` is bounded by the box and fixed by an assumption"
                )));
            }
        }
        for s in &ctx.substitutions {
            let value = env.eval(&s.value)?;
            let mut mentioned = BTreeSet::new();
            env.mentions(&s.value, &mut mentioned)?;
            let later = ctx
                .substitutions
                .iter()
                .skip_while(|t| !std::ptr::eq(*t, s));
            if later.clone().any(|t| mentioned.contains(&t.symbol)) {
                return Err(EvalError::IllFormed(format!(
                    "the substitution of `{}` refers to itself or to a later one",
                    s.symbol
                )));
            }
            env.assumed.extend(mentioned);
            env.assumed.insert(s.symbol.clone());
            let t = env.in_order(value, &s.formal)?;
            if t.len() != count(ctx.dim, env.rank(&s.symbol)?)? {
                return Err(EvalError::IllFormed(format!(
                    "`{}` is substituted with the wrong rank",
                    s.symbol
                )));
            }
            env.symbols.insert(s.symbol.clone(), t.into());
            // Definitions read so far may have read the symbol before it was replaced.
            env.cache.clear();
            env.certified.clear();
        }
        env.differential()?;
        // A field on some coordinates only keeps that restriction only while no
        // assumption replaces, eliminates or ties it.
        if let Some(field) = env
            .assumed
            .iter()
            .find(|s| ctx.fields.get(*s).is_some_and(|deps| deps.contains(&false)))
        {
            return Err(EvalError::IllFormed(format!(
                "`{field}` depends on some coordinates only, and an assumption mentions it"
            )));
        }
        Ok(env)
    }

    fn definition(&self, name: &str) -> Option<&Definition> {
        self.derived
            .get(name)
            .or_else(|| self.defined.get(name).copied())
    }

    fn rank(&self, symbol: &str) -> R<usize> {
        self.ctx
            .symbols
            .get(symbol)
            .copied()
            .ok_or_else(|| EvalError::IllFormed(format!("`{symbol}` is not a declared symbol")))
    }

    /// The variable of one component, registered as varying for a field or the position.
    pub fn component_var(&mut self, symbol: &str, idx: &[usize]) -> Var {
        let v = self.vars.intern(&component_name(symbol, idx));
        if self.ctx.fields.contains_key(symbol) {
            self.varying.entry(v).or_insert_with(|| Varying::Jet {
                field: symbol.to_owned(),
                idx: idx.to_vec(),
                orders: Vec::new(),
            });
        } else if self.ctx.position.as_deref() == Some(symbol) {
            self.varying.insert(v, Varying::Coordinate(idx[0]));
        }
        v
    }

    /// A symbol's components, after the assumptions: each eliminated component is its
    /// value in the free ones.
    fn symbol(&mut self, name: &str) -> R<Vec<Frac>> {
        let rank = self.rank(name)?;
        let mut t = Vec::new();
        for idx in assignments(self.ctx.dim, rank) {
            let v = self.component_var(name, &idx);
            let p = self.pivots.get(&v).cloned().unwrap_or_else(|| Poly::var(v));
            t.push(Frac::from(p));
        }
        Ok(t)
    }

    /// Every symbol `t` reads, through the definitions it reads.
    pub(super) fn mentions<'t>(&'t self, t: &'t Term, out: &mut BTreeSet<String>) -> R<()> {
        let mut stack: Vec<&Term> = vec![t];
        let mut seen: BTreeSet<&str> = BTreeSet::new();
        while let Some(t) = stack.pop() {
            match t {
                Term::Leaf {
                    of: Leaf::Symbol(s),
                    ..
                } => {
                    out.insert(s.clone());
                }
                Term::Leaf {
                    of: Leaf::Def(d), ..
                } if seen.insert(d) => {
                    if let Some(def) = self.definition(d) {
                        stack.push(&def.body);
                    }
                }
                Term::Grad { symbol, .. } | Term::Variation { field: symbol, .. } => {
                    out.insert(symbol.clone());
                }
                _ => {}
            }
            stack.extend(children(t));
        }
        Ok(())
    }

    /// The linear assumptions as one system over the components, solved by Gauss–Jordan
    /// elimination over ℚ (constant terms may be polynomials in the other variables);
    /// each pivot component is replaced by its value in the free ones.
    fn solve_equations(&mut self) -> R<()> {
        let d = self.ctx.dim;
        let mut rows: Vec<Poly> = Vec::new();
        let equations = self.ctx.equations.clone();
        // The components an equation sets explicitly (its left side) are eliminated
        // first: then a parameter such as Y in `sigma_11 = Y` stays free, with the box
        // it is given on.
        let mut explicit: BTreeSet<Var> = BTreeSet::new();
        // The polynomial constraints, solved after the linear equations.
        let mut polynomial: Vec<Poly> = Vec::new();
        for e in &equations {
            let symbol = match e {
                Equation::Symmetric(s) | Equation::Antisymmetric(s) | Equation::Traceless(s) => s,
                Equation::Component { symbol, .. } | Equation::Equals { symbol, .. } => symbol,
                Equation::Constraint { left, right } => {
                    for g in self.constraint_rows(left, right)? {
                        let affine = g.terms().all(|(m, _)| match m.factors() {
                            [] => true,
                            [(v, 1)] => is_free_component(self, *v),
                            _ => false,
                        });
                        if affine {
                            rows.push(g);
                        } else {
                            polynomial.push(g);
                        }
                    }
                    continue;
                }
                // Solved after the substitutions (`Env::differential`).
                Equation::Differential { .. } => continue,
            };
            if self.ctx.position.as_deref() == Some(symbol.as_str()) {
                return Err(EvalError::IllFormed(
                    "an assumption constrains the position, whose coordinates are independent"
                        .into(),
                ));
            }
            self.assumed.insert(symbol.clone());
            let rank = self.rank(symbol)?;
            let var = |env: &mut Self, idx: &[usize]| Poly::var(env.component_var(symbol, idx));
            match e {
                Equation::Symmetric(_) | Equation::Antisymmetric(_) | Equation::Traceless(_)
                    if rank != 2 =>
                {
                    return Err(EvalError::IllFormed(format!("`{symbol}` is not of rank 2")))
                }
                Equation::Traceless(_) => {
                    let trace = (0..d).fold(Poly::zero(), |acc, k| &acc + &var(self, &[k, k]));
                    rows.push(trace);
                }
                Equation::Symmetric(_) | Equation::Antisymmetric(_) => {
                    let anti = matches!(e, Equation::Antisymmetric(_));
                    for i in 0..d {
                        for j in i..d {
                            if i == j && !anti {
                                continue;
                            }
                            let (x, y) = (var(self, &[i, j]), var(self, &[j, i]));
                            rows.push(if anti { &x + &y } else { &x - &y });
                        }
                    }
                }
                Equation::Component { index, value, .. } => {
                    if index.len() != rank || index.iter().any(|&k| k >= d) {
                        return Err(EvalError::IllFormed(format!(
                            "a component of `{symbol}` out of range"
                        )));
                    }
                    let v = self.affine(value)?;
                    explicit.insert(self.component_var(symbol, index));
                    rows.push(&var(self, index) - &v[0]);
                }
                Equation::Equals { formal, value, .. } => {
                    let values = self.affine(value)?;
                    let letters = Term::letters(value, self)?.free;
                    let mut sorted = formal.clone();
                    sorted.sort_unstable();
                    if sorted != letters || formal.len() != rank {
                        return Err(EvalError::IllFormed(format!(
                            "the indices of `{symbol}` and its value differ"
                        )));
                    }
                    for idx in assignments(d, rank) {
                        let at = position_of(&letters, formal, &idx, d);
                        explicit.insert(self.component_var(symbol, &idx));
                        rows.push(&var(self, &idx) - &values[at]);
                    }
                }
                Equation::Constraint { .. } | Equation::Differential { .. } => {}
            }
        }
        self.mentions_of_equations(&equations)?;
        let is_component = is_free_component;
        let mut values: BTreeMap<Var, Poly> = BTreeMap::new();
        for row in rows {
            // Reduce by the pivots found so far.
            let row = substitute(&row, &values)?;
            // The pivot: a component that occurs in the row once, alone and to the
            // power 1 (so that row = 0 says exactly pivot = the rest, whatever the rest
            // is: a polynomial in other components); an explicit component first,
            // then by name, the highest index first (a symmetric tensor keeps its
            // upper triangle).
            let occurrences = |v: Var| row.terms().filter(|(m, _)| m.exponent(v) != 0).count();
            let pivot = row
                .terms()
                .filter_map(|(m, c)| match m.factors() {
                    [(v, 1)] if is_component(self, *v) && occurrences(*v) == 1 => {
                        Some((*v, c.clone()))
                    }
                    _ => None,
                })
                .min_by_key(|(v, _)| {
                    let name = self.vars.name(*v).to_owned();
                    (!explicit.contains(v), std::cmp::Reverse(name))
                });
            let Some((v, c)) = pivot else {
                if row.is_zero() {
                    continue;
                }
                return Err(EvalError::IllFormed(
                    "the assumptions contradict each other, or constrain no component linearly"
                        .into(),
                ));
            };
            let scale = Poly::constant(-&c.recip().ok_or(EvalError::DivisionByZero)?);
            let rest = &row - &Poly::term(super::poly::Monomial::var(v, 1), c.clone());
            let value = rest.checked_mul(&scale).map_err(|_| EvalError::Limit)?;
            for w in values.values_mut() {
                *w = substitute(w, &BTreeMap::from([(v, value.clone())]))?;
            }
            values.insert(v, value);
        }
        // Each polynomial constraint, with the pivots substituted and reduced by the
        // rules so far, is solved for a power of a variable of its own: a scalar
        // first, then by name from the highest index down (as the search does).
        for g in polynomial {
            let g = substitute(&g, &values)?;
            let g =
                super::rules::reduce(&g, &self.rules, RULE_STEPS).map_err(|_| EvalError::Limit)?;
            if g.is_zero() {
                continue;
            }
            let ctx = self.ctx;
            let names = &self.vars;
            let rule = Rule::solve(
                &g,
                &self.rules,
                |v| is_component(self, v) && !values.contains_key(&v),
                |v, d| {
                    let name = names.name(v);
                    (
                        d,
                        ctx.symbols.get(name) != Some(&0),
                        std::cmp::Reverse(name.to_owned()),
                    )
                },
            )
            .ok_or_else(|| {
                EvalError::IllFormed(
                    "a polynomial constraint is not solved for a power of a variable of its own"
                        .into(),
                )
            })?;
            self.rules.push(rule);
        }
        self.pivots = values;
        // Symbols read while the equations were formed are read again with the pivots.
        self.symbols.clear();
        self.cache.clear();
        Ok(())
    }

    fn mentions_of_equations(&mut self, equations: &[Equation]) -> R<()> {
        let mut mentioned = BTreeSet::new();
        for e in equations {
            match e {
                Equation::Component { value, .. } | Equation::Equals { value, .. } => {
                    self.mentions(value, &mut mentioned)?;
                }
                Equation::Constraint { left, right } | Equation::Differential { left, right } => {
                    self.mentions(left, &mut mentioned)?;
                    self.mentions(right, &mut mentioned)?;
                }
                _ => {}
            }
        }
        self.assumed.extend(mentioned);
        Ok(())
    }

    /// `left − right` for every value of their free letters, as polynomials in the
    /// components with every symbol unconstrained.
    fn constraint_rows(&mut self, left: &Term, right: &Term) -> R<Vec<Poly>> {
        let letters = Term::letters(left, self)?.free;
        if Term::letters(right, self)?.free != letters {
            return Err(EvalError::IllFormed(
                "the sides of a constraint have different free indices".into(),
            ));
        }
        let (l, r) = (self.eval(left)?, self.eval(right)?);
        let (l, r) = (self.in_order(l, &letters)?, self.in_order(r, &letters)?);
        self.cache.clear();
        l.iter()
            .zip(&r)
            .map(|(a, b)| {
                let d = a.sub(b)?;
                if d.denominator().is_empty() && d.conditions().is_empty() {
                    Ok(d.numerator().clone())
                } else {
                    Err(EvalError::IllFormed("a constraint divides by a sum".into()))
                }
            })
            .collect()
    }

    /// The components of `value` with every symbol unconstrained: polynomials, for an
    /// equation (the elimination checks that they are affine).
    fn affine(&mut self, value: &Term) -> R<Vec<Poly>> {
        let v = self.eval(value)?;
        self.cache.clear();
        v.comps()
            .iter()
            .map(|f| {
                if f.denominator().is_empty() && f.conditions().is_empty() {
                    Ok(f.numerator().clone())
                } else {
                    Err(EvalError::IllFormed(
                        "an assumption divides by a sum".into(),
                    ))
                }
            })
            .collect()
    }

    /// Spends `cost` of the statement's work, which is also what a stop condition
    /// counts ([`super::interrupt::tick_by`]): a product of large coefficients is long
    /// in limbs, not in terms.
    fn charge(&mut self, cost: usize) -> R<()> {
        self.work = self.work.checked_sub(cost).ok_or(EvalError::Limit)?;
        super::interrupt::tick_by(cost);
        Ok(())
    }

    /// A product, charged in products of 64-bit limbs: the terms of one numerator
    /// times the other's, times the limbs of their largest coefficients.
    fn mul(&mut self, a: &Frac, b: &Frac) -> R<Frac> {
        let size = |f: &Frac| {
            let limbs = f
                .numerator()
                .terms()
                .map(|(_, c)| c.bits())
                .max()
                .unwrap_or(0)
                / 64
                + 1;
            usize::try_from(limbs)
                .unwrap_or(usize::MAX)
                .saturating_mul(f.numerator().num_terms())
        };
        self.charge(size(a).saturating_mul(size(b)).max(1))?;
        Ok(a.mul(b)?)
    }

    /// `x^k` by squaring, each product charged as it is formed.
    fn pow(&mut self, x: &Frac, k: u32) -> R<Frac> {
        let (mut base, mut k, mut acc) = (x.clone(), k, Frac::one());
        while k > 0 {
            if k & 1 == 1 {
                acc = self.mul(&acc, &base)?;
            }
            k >>= 1;
            if k > 0 {
                base = self.mul(&base, &base)?;
            }
        }
        Ok(acc)
    }

    fn add(&mut self, a: &Frac, b: &Frac) -> R<Frac> {
        if !a.denominator().is_empty() || !b.denominator().is_empty() {
            self.charge(a.numerator().num_terms() + b.numerator().num_terms())?;
        }
        Ok(a.add(b)?)
    }

    fn div(&mut self, a: &Frac, b: &Frac) -> R<Frac> {
        self.charge(a.numerator().num_terms().max(1))?;
        Ok(a.div(b)?)
    }

    /// The value of `t`.
    pub fn eval(&mut self, t: &Term) -> R<Value> {
        if self.depth >= MAX_DEPTH {
            return Err(EvalError::Limit);
        }
        let letters = t.letters(self)?;
        self.depth += 1;
        let value = self.eval_checked(t, &letters);
        self.depth -= 1;
        let value = value?;
        if value.comps().len() > MAX_COMPONENTS {
            return Err(EvalError::Limit);
        }
        Ok(value)
    }

    fn scalar_of(&mut self, t: &Term) -> R<Frac> {
        match self.eval(t)? {
            Value { letters, mut comps } if letters.is_empty() => Ok(comps.remove(0)),
            _ => Err(EvalError::IllFormed("a scalar was expected".into())),
        }
    }

    fn eval_checked(&mut self, t: &Term, l: &Letters) -> R<Value> {
        let d = self.ctx.dim;
        let tensor = |letters: Vec<char>, comps: Vec<Frac>| Value { letters, comps };
        Ok(match t {
            Term::Const { value, .. } => tensor(
                l.free.clone(),
                vec![Frac::constant(value.clone()); count(d, l.free.len())?],
            ),
            Term::Leaf { of, slots } => {
                let base = self.leaf(of)?;
                self.contract(&[(&base, slots.clone())], &l.free, None)?
            }
            Term::Sum(terms) => {
                let mut acc = self.eval(&terms[0])?;
                for term in &terms[1..] {
                    // A product adds its terms into the sum as it forms them, in the
                    // same order: the same sum, without a tensor of its own.
                    if let Term::Product(fs) = term {
                        if term.letters(self)?.free == acc.letters {
                            acc = self.product(fs, &l.free, Some(acc.comps))?;
                            continue;
                        }
                    }
                    let v = self.eval(term)?;
                    for (x, y) in acc.comps.iter_mut().zip(&v.comps) {
                        // x + 0 is x itself, divisors and conditions alike.
                        if !(y.is_zero() && y.denominator().is_empty() && y.conditions().is_empty())
                        {
                            *x = self.add(x, y)?;
                        }
                    }
                }
                acc
            }
            Term::Product(fs) => self.product(fs, &l.free, None)?,
            Term::Neg(a) => self.map(a, |_, f| Ok(f.neg()))?,
            // A divisor written as a product of scalars or a power is divided by one
            // factor at a time, so that the factors stay apart (and are named apart
            // where the statement is claimed to hold).
            Term::Div(a, b) => {
                // The numerator first: variables are numbered in the order they are
                // met, and the evidence writes polynomials in that order.
                let numerator = self.eval(a)?;
                // A product of scalars divides one factor at a time; a product that
                // contracts an index between its factors (`v_k v_k`) is one divisor.
                let scalars = |fs: &[Term]| {
                    fs.iter()
                        .all(|f| f.letters(&*self).is_ok_and(|l| l.free.is_empty()))
                };
                let parts: Vec<(&Term, u32)> = match &**b {
                    Term::Product(fs) if scalars(fs) => fs.iter().map(|f| (f, 1)).collect(),
                    Term::Pow(base, k) => vec![(&**base, *k)],
                    other => vec![(other, 1)],
                };
                let mut dens = Vec::with_capacity(parts.len());
                for (part, k) in parts {
                    let den = self.scalar_of(part)?;
                    for _ in 0..k.min(64) {
                        dens.push(den.clone());
                    }
                    if k > 64 {
                        dens.push(self.pow(&den, k - 64)?);
                    }
                }
                self.map_value(numerator, |env, f| {
                    let mut out = f.clone();
                    for den in &dens {
                        out = env.div(&out, den)?;
                    }
                    Ok(out)
                })?
            }
            Term::Pow(a, k) => {
                let x = self.scalar_of(a)?;
                Value::scalar(self.pow(&x, *k)?)
            }
            Term::Sqrt(a) => {
                let x = self.scalar_of(a)?;
                Value::scalar(self.square_root(&x)?)
            }
            Term::Avg(a) => {
                let normal = self.normal.clone();
                if normal.is_empty() {
                    return Err(EvalError::IllFormed("an average without a normal".into()));
                }
                self.map(a, |env, f| {
                    if normal.iter().any(|&v| f.divides_by(v)) {
                        return Err(EvalError::Unsupported(
                            "a divisor with the normal in an average".into(),
                        ));
                    }
                    env.charge(f.numerator().num_terms())?;
                    Ok(f.map_numerator(|p| Ok(p.average_over_normal(&normal)?))?)
                })?
            }
            Term::Deriv(a, slot) => {
                let v = self.eval(a)?;
                let mut comps = Vec::with_capacity(v.comps().len() * d);
                for f in v.comps() {
                    for k in 0..d {
                        comps.push(self.total_derivative(f, k)?);
                    }
                }
                let mut slots: Vec<Slot> = v.letters().iter().map(|&c| Slot::Letter(c)).collect();
                slots.push(*slot);
                self.contract(&[(&comps, slots)], &l.free, None)?
            }
            Term::Grad {
                body,
                symbol,
                slots,
            } => {
                let rank = self.rank(symbol)?;
                let mut parts = Vec::new();
                let mut letters = Vec::new();
                for c in assignments(d, rank) {
                    let derivative = differentiate(body, symbol, &c, self)?;
                    let v = self.eval(&derivative)?;
                    letters = v.letters().to_vec();
                    parts.push(v.comps().to_vec());
                }
                // Body components first, then the symbol's.
                let n = parts.first().map_or(0, Vec::len);
                let comps: Vec<Frac> = (0..n)
                    .flat_map(|i| parts.iter().map(move |p| p[i].clone()))
                    .collect();
                let mut all: Vec<Slot> = letters.iter().map(|&c| Slot::Letter(c)).collect();
                all.extend(slots);
                self.contract(&[(&comps, all)], &l.free, None)?
            }
            Term::Variation { body, field, slots } => {
                self.variation(body, field, slots, &l.free)?
            }
            Term::Opaque { what, .. } => return Err(EvalError::Unsupported(what.clone())),
        })
    }

    /// `f` applied to every component of `a`'s value.
    fn map(&mut self, a: &Term, f: impl FnMut(&mut Self, &Frac) -> R<Frac>) -> R<Value> {
        let v = self.eval(a)?;
        self.map_value(v, f)
    }

    /// `f` applied to every component of a value.
    fn map_value(&mut self, v: Value, mut f: impl FnMut(&mut Self, &Frac) -> R<Frac>) -> R<Value> {
        let comps = v.comps.iter().map(|x| f(self, x)).collect::<R<_>>()?;
        Ok(Value {
            letters: v.letters,
            comps,
        })
    }

    /// A leaf's components in slot order; those of δ, ε, the normal and the symbols
    /// are formed once.
    fn leaf(&mut self, of: &Leaf) -> R<Rc<[Frac]>> {
        let constant = match of {
            Leaf::Def(name) => return Ok(self.def_value(name)?.comps.into()),
            Leaf::Symbol(s) => match self.symbols.get(s) {
                Some(t) => return Ok(Rc::clone(t)),
                None => None,
            },
            Leaf::Delta => Some(0),
            Leaf::Eps => Some(1),
            Leaf::Normal => Some(2),
        };
        if let Some(t) = constant.and_then(|k| self.constants[k].as_ref()) {
            return Ok(Rc::clone(t));
        }
        let t: Rc<[Frac]> = self.leaf_components(of)?.into();
        match (constant, of) {
            (Some(k), _) => self.constants[k] = Some(Rc::clone(&t)),
            (None, Leaf::Symbol(s)) => {
                self.symbols.insert(s.clone(), Rc::clone(&t));
            }
            (None, _) => {}
        }
        Ok(t)
    }

    /// A leaf's components, formed anew.
    fn leaf_components(&mut self, of: &Leaf) -> R<Vec<Frac>> {
        let d = self.ctx.dim;
        Ok(match of {
            Leaf::Delta => assignments(d, 2)
                .iter()
                .map(|i| Frac::constant(Rational::int(i64::from(i[0] == i[1]))))
                .collect(),
            Leaf::Eps => assignments(d, d)
                .iter()
                .map(|i| Frac::constant(Rational::int(permutation_sign(i))))
                .collect(),
            Leaf::Normal => {
                if self.ctx.normal.is_none() {
                    return Err(EvalError::IllFormed("no normal is declared".into()));
                }
                (0..d)
                    .map(|k| {
                        Frac::from(
                            self.normal
                                .get(k)
                                .map_or_else(Poly::zero, |&v| Poly::var(v)),
                        )
                    })
                    .collect()
            }
            Leaf::Symbol(s) => self.symbol(s)?,
            Leaf::Def(name) => self.def_value(name)?.comps,
        })
    }

    /// A definition's value: a tensor in its formal order.
    fn def_value(&mut self, name: &str) -> R<Value> {
        if let Some(v) = self.cache.get(name) {
            return Ok(v.clone());
        }
        let def = self
            .definition(name)
            .cloned()
            .ok_or_else(|| EvalError::IllFormed(format!("`{name}` is not defined")))?;
        if self.active.iter().any(|a| a == name) {
            return Err(EvalError::IllFormed(format!(
                "`{name}` is defined through itself"
            )));
        }
        self.active.push(name.to_owned());
        let v = self.eval(&def.body);
        self.active.pop();
        let v = v?;
        let comps = self.in_order(v, &def.formal).map_err(|_| {
            EvalError::IllFormed(format!("the indices of `{name}` and its body differ"))
        })?;
        // A definition is undefined wherever one of its components is.
        let v = Value {
            letters: def.formal.clone(),
            comps: with_all_conditions(comps),
        };
        self.cache.insert(name.to_owned(), v.clone());
        Ok(v)
    }

    /// A tensor value's components reordered from sorted letters into `formal` order.
    fn in_order(&self, v: Value, formal: &[char]) -> R<Vec<Frac>> {
        let Value { letters, comps } = v;
        let d = self.ctx.dim;
        let mut sorted = formal.to_vec();
        sorted.sort_unstable();
        if sorted != letters {
            return Err(EvalError::IllFormed("indices differ".into()));
        }
        if formal == letters {
            return Ok(comps);
        }
        Ok(assignments(d, formal.len())
            .iter()
            .map(|idx| comps[position_of(&letters, formal, idx, d)].clone())
            .collect())
    }

    /// The product of the terms `fs` over the letters `out`, its terms added to the
    /// components `into` when given (else to zeros).
    fn product<'t>(&mut self, fs: &'t [Term], out: &[char], into: Option<Vec<Frac>>) -> R<Value> {
        // Leaves at fixed values only: one component of each, multiplied from left to
        // right and added as the walk below would add them.
        let d = self.ctx.dim;
        let fixed = |f: &'t Term| match f {
            Term::Leaf { of, slots } => slots
                .iter()
                .try_fold(0usize, |acc, s| match s {
                    Slot::Fixed(v) => acc.checked_mul(d)?.checked_add(*v),
                    Slot::Letter(_) => None,
                })
                .map(|offset| (of, offset)),
            _ => None,
        };
        if out.is_empty() {
            if let Some(leaves) = fs.iter().map(fixed).collect::<Option<Vec<_>>>() {
                let mut comps = into.unwrap_or_else(|| vec![Frac::default()]);
                let mut p = Frac::one();
                for (of, offset) in leaves {
                    let base = self.leaf(of)?;
                    let x = base.get(offset).ok_or_else(|| {
                        EvalError::IllFormed("a slot count that is not the rank".into())
                    })?;
                    if x.is_zero() && x.conditions().is_empty() {
                        return Ok(Value {
                            letters: Vec::new(),
                            comps,
                        });
                    }
                    p = self.mul(&p, x)?;
                }
                let [sum] = &mut comps[..] else {
                    return Err(EvalError::IllFormed("a sum of different ranks".into()));
                };
                *sum = self.add(sum, &p)?;
                return Ok(Value {
                    letters: Vec::new(),
                    comps,
                });
            }
        }
        let mut values = Vec::with_capacity(fs.len());
        for f in fs {
            values.push(self.eval(f)?);
        }
        let factors: Vec<(&[Frac], Vec<Slot>)> = values
            .iter()
            .map(|v| {
                (
                    v.comps(),
                    v.letters().iter().map(|&c| Slot::Letter(c)).collect(),
                )
            })
            .collect();
        self.contract(&factors, out, into)
    }

    /// Σ over the summed letters of Π factors (each a tensor with its axes' slots), for
    /// every value of `out`. The letters take their values in a fixed order, each
    /// factor's letters together, factor after factor (the last fastest), so that each
    /// component adds its terms in one fixed order, each term the product of the
    /// factors from left to right. The values are walked as a tree: a factor is read
    /// once its letters have values, a factor that is 0 there cuts off every term below
    /// (each would be 0: `\delta_{it}\delta_{jk}…` is cut at `t ≠ i`, not after every
    /// other letter), and the product of the leading factors known so far is formed once
    /// for all the terms that share it. Where a term lands is its values of `out`, in
    /// the order of `out`, whatever the walk's order. The terms are added to the
    /// components `into` when given, else to zeros.
    fn contract(
        &mut self,
        factors: &[(&[Frac], Vec<Slot>)],
        out: &[char],
        into: Option<Vec<Frac>>,
    ) -> R<Value> {
        let d = self.ctx.dim;
        // A result letter no factor carries (none in a well-formed product) first, then
        // each factor's letters in the order of the factors.
        let mut all: Vec<char> = out
            .iter()
            .copied()
            .filter(|c| {
                !factors
                    .iter()
                    .any(|(_, slots)| slots.contains(&Slot::Letter(*c)))
            })
            .collect();
        for (_, slots) in factors {
            for s in slots {
                if let Slot::Letter(c) = s {
                    if !all.contains(c) {
                        all.push(*c);
                    }
                }
            }
        }
        count(d, all.len()).map_err(|_| EvalError::Limit)?;
        let out_at: Vec<usize> = out
            .iter()
            .map(|c| all.iter().position(|x| x == c))
            .collect::<Option<_>>()
            .ok_or_else(|| EvalError::IllFormed("a result letter no factor carries".into()))?;
        let factors = factors
            .iter()
            .map(|(t, slots)| {
                let axes: Vec<Axis> = slots
                    .iter()
                    .map(|s| match *s {
                        Slot::Letter(c) => {
                            Axis::Letter(all.iter().position(|x| *x == c).unwrap_or(0))
                        }
                        Slot::Fixed(k) => Axis::Fixed(k),
                    })
                    .collect();
                let known = axes
                    .iter()
                    .filter_map(|a| match a {
                        Axis::Letter(p) => Some(p + 1),
                        Axis::Fixed(_) => None,
                    })
                    .max()
                    .unwrap_or(0);
                (*t, axes, known)
            })
            .collect();
        let mut walk = Walk {
            factors,
            values: vec![0; all.len()],
            out: out_at,
            comps: match into {
                Some(comps) if comps.len() == count(d, out.len())? => comps,
                Some(_) => return Err(EvalError::IllFormed("a sum of different ranks".into())),
                None => std::iter::repeat_with(Frac::default)
                    .take(count(d, out.len())?)
                    .collect(),
            },
        };
        self.visit(&mut walk, 0, &mut vec![Frac::one()])?;
        Ok(Value {
            letters: out.to_vec(),
            comps: walk.comps,
        })
    }

    /// The walk of [`Env::contract`] once `level` letters have values: `products[k]`
    /// is the product of the first `k` factors, as far as they are known.
    fn visit(&mut self, w: &mut Walk<'_>, level: usize, products: &mut Vec<Frac>) -> R<()> {
        let d = self.ctx.dim;
        for k in 0..w.factors.len() {
            if w.factors[k].2 == level {
                let x = w.component(k, d)?;
                if x.is_zero() && x.conditions().is_empty() {
                    return Ok(());
                }
            }
        }
        let entry = products.len();
        while w
            .factors
            .get(products.len() - 1)
            .is_some_and(|f| f.2 <= level)
        {
            let x = w.component(products.len() - 1, d)?;
            let p = self.mul(&products[products.len() - 1], x)?;
            products.push(p);
        }
        if level == w.values.len() {
            let at = w.out.iter().fold(0, |acc, &p| acc * d + w.values[p]);
            w.comps[at] = self.add(&w.comps[at], &products[products.len() - 1])?;
        } else {
            for v in 0..d {
                w.values[level] = v;
                self.visit(w, level + 1, products)?;
            }
        }
        products.truncate(entry);
        Ok(())
    }

    /// D_k f = Σ_v ∂f/∂v · ∂v/∂x_k over the variables of the numerator; no divisor may
    /// vary with the position.
    fn total_derivative(&mut self, f: &Frac, k: usize) -> R<Frac> {
        let varying: Vec<Var> = self.varying.keys().copied().collect();
        if varying.iter().any(|&v| f.divides_by(v)) {
            return Err(EvalError::Unsupported(
                "a divisor that varies with the position".into(),
            ));
        }
        let p = f.numerator();
        let mut acc = Poly::zero();
        for x in p.variables() {
            let dx = match self.varying.get(&x).cloned() {
                Some(Varying::Coordinate(j)) if j == k => Poly::one(),
                Some(Varying::Jet {
                    field,
                    idx,
                    mut orders,
                }) if self
                    .ctx
                    .fields
                    .get(&field)
                    .is_some_and(|deps| deps.get(k) == Some(&true)) =>
                {
                    orders.push(k);
                    orders.sort_unstable();
                    self.jet(&field, &idx, orders)?
                }
                _ => continue,
            };
            let term = p.derivative(x);
            self.charge(term.num_terms().saturating_mul(dx.num_terms()))?;
            acc += &term.checked_mul(&dx).map_err(|_| EvalError::Limit)?;
        }
        Ok(f.map_numerator(|_| Ok(acc))?)
    }

    /// ∂^orders field_idx: its variable, or its value when a differential hypothesis
    /// determines it.
    fn jet(&mut self, field: &str, idx: &[usize], orders: Vec<usize>) -> R<Poly> {
        let w = self.vars.intern(&jet_name(field, idx, &orders));
        if let Some(p) = self.jet_values.get(&w) {
            return Ok(p.clone());
        }
        let rule = self
            .jet_rules
            .iter()
            .position(|r| r.field == field && r.idx == idx && beyond(&orders, &r.orders).is_some());
        self.varying.insert(
            w,
            Varying::Jet {
                field: field.to_owned(),
                idx: idx.to_vec(),
                orders: orders.clone(),
            },
        );
        let Some(r) = rule else {
            return Ok(Poly::var(w));
        };
        let p = self.by_rule(r, &orders)?;
        self.jet_values.insert(w, p.clone());
        Ok(p)
    }

    /// ∂^orders field_idx by rule `r` (whose derivative it must be): the rule's value
    /// differentiated by the coordinates beyond the rule's, every derivative in it
    /// reduced. Each step goes to derivatives of lower [`jet_rank`], so it ends.
    fn by_rule(&mut self, r: usize, orders: &[usize]) -> R<Poly> {
        if self.depth >= MAX_DEPTH {
            return Err(EvalError::Limit);
        }
        let rule = &self.jet_rules[r];
        let rest = beyond(orders, &rule.orders)
            .ok_or_else(|| EvalError::IllFormed("a derivative no rule determines".into()))?;
        let mut p = rule.value.clone();
        self.depth += 1;
        let mut reduced = Ok(());
        for k in rest {
            match self.total_derivative(&Frac::from(p.clone()), k) {
                Ok(f) => p = f.numerator().clone(),
                Err(e) => {
                    reduced = Err(e);
                    break;
                }
            }
        }
        let p = reduced.and_then(|()| self.reduce_jets(&p));
        self.depth -= 1;
        p
    }

    /// `p` with every derivative that a differential hypothesis determines replaced by
    /// its value.
    fn reduce_jets(&mut self, p: &Poly) -> R<Poly> {
        let mut values = BTreeMap::new();
        for x in p.variables() {
            let Some(Varying::Jet { field, idx, orders }) = self.varying.get(&x).cloned() else {
                continue;
            };
            let ruled = self
                .jet_rules
                .iter()
                .any(|r| r.field == field && r.idx == idx && beyond(&orders, &r.orders).is_some());
            if ruled {
                values.insert(x, self.jet(&field, &idx, orders)?);
            }
        }
        substitute(p, &values)
    }

    /// The differential hypotheses (`phi_,kk = 0`), after every other assumption: each
    /// component of each, reduced by the rules before it, is solved for its derivative
    /// of highest [`jet_rank`], which must occur once, alone, with a rational
    /// coefficient. Each must be linear in the fields with coefficients constant in
    /// position, and the rules must be in involution (any two that determine
    /// derivatives of one component agree on their common derivative): then the
    /// derivatives no rule determines are independent at a point, as a refutation needs
    /// (Riquier's and Janet's normal form of a passive linear system).
    fn differential(&mut self) -> R<()> {
        let ctx = self.ctx;
        let hypotheses: Vec<(&Term, &Term)> = ctx
            .equations
            .iter()
            .filter_map(|e| match e {
                Equation::Differential { left, right } => Some((left, right)),
                _ => None,
            })
            .collect();
        for (left, right) in hypotheses {
            for row in self.constraint_rows(left, right)? {
                let row = self.reduce_jets(&row)?;
                if row.is_zero() {
                    continue;
                }
                self.linear_in_fields(&row)?;
                let leading = row
                    .variables()
                    .into_iter()
                    .filter_map(|v| match self.varying.get(&v) {
                        Some(Varying::Jet { field, idx, orders }) if !orders.is_empty() => {
                            Some((jet_rank(field, idx, orders, ctx.dim), v))
                        }
                        _ => None,
                    })
                    .max();
                let Some((_, v)) = leading else {
                    return Err(EvalError::IllFormed(
                        "a differential hypothesis reads no derivative of a field".into(),
                    ));
                };
                let terms: Vec<_> = row.terms().filter(|(m, _)| m.exponent(v) != 0).collect();
                let c = match terms.as_slice() {
                    [(m, c)] if m.factors() == [(v, 1)] => (*c).clone(),
                    _ => {
                        return Err(EvalError::IllFormed(
                            "the highest derivative of a differential hypothesis must occur once, with a rational coefficient".into(),
                        ))
                    }
                };
                let scale = Poly::constant(-&c.recip().ok_or(EvalError::DivisionByZero)?);
                let rest = &row - &Poly::term(super::poly::Monomial::var(v, 1), c);
                let value = rest.checked_mul(&scale).map_err(|_| EvalError::Limit)?;
                let Some(Varying::Jet { field, idx, orders }) = self.varying.get(&v).cloned()
                else {
                    return Err(EvalError::IllFormed("a derivative without a field".into()));
                };
                self.jet_rules.push(JetRule {
                    field,
                    idx,
                    orders,
                    value,
                });
                self.jet_values.clear();
                self.cache.clear();
            }
        }
        for a in 0..self.jet_rules.len() {
            for b in a + 1..self.jet_rules.len() {
                let (x, y) = (&self.jet_rules[a], &self.jet_rules[b]);
                if (&x.field, &x.idx) != (&y.field, &y.idx) {
                    continue;
                }
                // The least derivative of both: each coordinate as often as in either.
                let often = |o: &[usize], k: usize| o.iter().filter(|&&c| c == k).count();
                let common: Vec<usize> = (0..self.ctx.dim)
                    .flat_map(|k| vec![k; often(&x.orders, k).max(often(&y.orders, k))])
                    .collect();
                if self.by_rule(a, &common)? != self.by_rule(b, &common)? {
                    let x = &self.jet_rules[a];
                    return Err(EvalError::IllFormed(format!(
                        "the differential hypotheses are not in involution: they give `{}` two different values",
                        jet_name(&x.field, &x.idx, &common)
                    )));
                }
            }
        }
        self.cache.clear();
        Ok(())
    }

    /// Refuses a row that is not linear in the fields' components and derivatives, or
    /// whose coefficients vary with position (a term without a field may: a source).
    fn linear_in_fields(&self, row: &Poly) -> R<()> {
        for (m, _) in row.terms() {
            let is = |v: &Var, jet: bool| match self.varying.get(v) {
                Some(Varying::Jet { .. }) => jet,
                Some(Varying::Coordinate(_)) => !jet,
                None => false,
            };
            let jets: Vec<_> = m.factors().iter().filter(|(v, _)| is(v, true)).collect();
            let positional = m.factors().iter().any(|(v, _)| is(v, false));
            let normal = m.factors().iter().any(|(v, _)| self.normal.contains(v));
            let linear = match jets.as_slice() {
                [] => true,
                [(_, 1)] => !positional,
                _ => false,
            };
            if !linear || normal {
                return Err(EvalError::IllFormed(
                    "a differential hypothesis must be linear in the fields, with coefficients constant in position".into(),
                ));
            }
        }
        Ok(())
    }

    /// The Euler operator: Σ_α (−1)^|α| D_α (∂P/∂v_j,α) over the jet variables of the
    /// field that P reads, for every component of P and of the field.
    fn variation(&mut self, body: &Term, field: &str, slots: &[Slot], out: &[char]) -> R<Value> {
        if self.assumed.contains(field) || !self.ctx.fields.contains_key(field) {
            return Err(EvalError::Unsupported(format!(
                "`{field}` is not a free field to vary"
            )));
        }
        let d = self.ctx.dim;
        let v = self.eval(body)?;
        let field_comps = assignments(d, self.rank(field)?);
        let mut comps = Vec::new();
        for f in v.comps() {
            if !f.denominator().is_empty() {
                return Err(EvalError::Unsupported("a density with a divisor".into()));
            }
            let p = f.numerator();
            for idx in &field_comps {
                let mut acc = Frac::default();
                for x in p.variables() {
                    let Some(Varying::Jet {
                        field: g,
                        idx: i,
                        orders,
                    }) = self.varying.get(&x).cloned()
                    else {
                        continue;
                    };
                    if g != field || i != *idx {
                        continue;
                    }
                    let mut term = Frac::from(p.derivative(x));
                    for &k in &orders {
                        term = self.total_derivative(&term, k)?;
                    }
                    if orders.len() % 2 == 1 {
                        term = term.neg();
                    }
                    acc = self.add(&acc, &term)?;
                }
                comps.push(acc);
            }
        }
        let mut all: Vec<Slot> = v.letters().iter().map(|&c| Slot::Letter(c)).collect();
        all.extend(slots);
        self.contract(&[(&comps, all)], out, None)
    }

    /// √x: a nonnegative rational, or an offered root r with r² = x exactly (cleared)
    /// and r ≥ 0 on the box by coefficient signs.
    fn square_root(&mut self, x: &Frac) -> R<Frac> {
        // √0 = 0 wherever x is defined (its divisors are among its conditions).
        if x.numerator().is_zero() {
            return Ok(Frac::default().with_conditions_of(x));
        }
        if x.denominator().is_empty() {
            if let Some(q) = x.numerator().as_constant() {
                let r = q
                    .sqrt_exact()
                    .ok_or_else(|| EvalError::Unsupported(format!("sqrt({q}) is irrational")))?;
                return Ok(Frac::constant(r).with_conditions_of(x));
            }
        }
        if let Some((_, r)) = self.certified.iter().find(|(y, _)| y == x) {
            return Ok(r.clone());
        }
        let box_ = self.given_box();
        for r in self.roots.clone() {
            let square = self.mul(&r, &r)?;
            if !square.cleared_difference(x)?.is_zero() {
                continue;
            }
            let sign = match r
                .denominator()
                .is_empty()
                .then(|| r.numerator().as_constant())
                .flatten()
            {
                Some(c) if !c.is_negative() => Some(super::sign::ByCoefficients {
                    substitution: String::new(),
                    cases: 0,
                }),
                Some(_) => None,
                None => super::sign::by_coefficients(
                    &r,
                    &box_,
                    super::statement::Sign::NonNegative,
                    &self.vars,
                ),
            };
            if let Some(how) = sign {
                let on: Vec<String> = box_
                    .iter()
                    .map(|(v, i)| i.describe(self.vars.name(*v)))
                    .collect();
                self.roots_taken.push(RootTaken {
                    radicand: show(&x.tidied(), &self.vars),
                    root: show(&r, &self.vars),
                    on: if on.is_empty() {
                        "every real value".to_owned()
                    } else {
                        on.join(", ")
                    },
                    sign: how,
                });
                let r = r.with_conditions_of(x);
                self.certified.push((x.clone(), r.clone()));
                return Ok(r);
            }
        }
        if self.algebraic_roots {
            if let Some(r) = self.algebraic_root(x)? {
                return Ok(r);
            }
        }
        Err(EvalError::Unsupported(
            "a square root whose value and sign on the box are not certified".into(),
        ))
    }

    /// √x as a variable r with the rule r² = x, r ≥ 0, for a polynomial x that is not
    /// constant, has no negative power and reads no component of the normal and no
    /// derivative of a field; `None` for any other x.
    fn algebraic_root(&mut self, x: &Frac) -> R<Option<Frac>> {
        let p = x.numerator();
        let plain = x.denominator().is_empty()
            && x.conditions().is_empty()
            && p.as_constant().is_none()
            && p.terms().all(|(m, _)| {
                m.factors().iter().all(|&(v, e)| {
                    e > 0 && !self.normal.contains(&v) && !self.varying.contains_key(&v)
                })
            });
        if !plain {
            return Ok(None);
        }
        let radicand =
            super::rules::reduce(p, &self.rules, RULE_STEPS).map_err(|_| EvalError::Limit)?;
        // Reduced by the constraints to a constant: its root is rational, or refused.
        if let Some(c) = radicand.as_constant() {
            return Ok(c
                .sqrt_exact()
                .map(|r| Frac::constant(r).with_conditions_of(x)));
        }
        let rule = Rule::square_root(radicand, &mut self.vars);
        let r = Frac::from(Poly::var(rule.var));
        if !self.rules.iter().any(|s| s.var == rule.var) {
            self.rules.push(rule);
        }
        Ok(Some(r))
    }

    /// The box `given` over the variables it names.
    pub fn given_box(&mut self) -> Vec<(Var, super::statement::Interval)> {
        let given = self.ctx.given.clone();
        given
            .into_iter()
            .map(|(name, i)| (self.vars.intern(&name), i))
            .collect()
    }

    /// The normal's variables.
    pub fn normal_vars(&self) -> &[Var] {
        &self.normal
    }
}

/// The position of component `idx` (values in `formal` order) among the components
/// of a tensor over the sorted `letters`.
fn position_of(letters: &[char], formal: &[char], idx: &[usize], d: usize) -> usize {
    letters.iter().fold(0, |acc, c| {
        acc * d + formal.iter().position(|f| f == c).map_or(0, |k| idx[k])
    })
}

/// Every component carries every component's conditions.
fn with_all_conditions(comps: Vec<Frac>) -> Vec<Frac> {
    let mut all = Frac::one();
    for c in &comps {
        all = all.with_conditions_of(c);
    }
    comps
        .into_iter()
        .map(|c| c.with_conditions_of(&all))
        .collect()
}

/// `p` with the variables of `values` replaced by their polynomials.
pub fn substitute(p: &Poly, values: &BTreeMap<Var, Poly>) -> R<Poly> {
    if values.is_empty() || !p.variables().iter().any(|v| values.contains_key(v)) {
        return Ok(p.clone());
    }
    let mut out = Poly::zero();
    for (m, c) in p.terms() {
        let mut t = Poly::constant(c.clone());
        for &(v, e) in m.factors() {
            let factor = match values.get(&v) {
                Some(x) if e >= 0 => x
                    .checked_pow_wide(e.unsigned_abs())
                    .map_err(|_| EvalError::Limit)?,
                Some(_) => {
                    return Err(EvalError::Unsupported(
                        "a negative power of a constrained component".into(),
                    ))
                }
                None => Poly::term(super::poly::Monomial::var(v, e), Rational::one()),
            };
            t = t.checked_mul(&factor).map_err(|_| EvalError::Limit)?;
        }
        out += &t;
    }
    Ok(out)
}

impl<'c> Env<'c> {
    /// The kernel's polynomial of a hint, its variables interned by name.
    pub(super) fn poly_of(&mut self, p: &PolyData) -> R<Poly> {
        let mut terms = Vec::with_capacity(p.len());
        for (factors, c) in p {
            let factors: Vec<(Var, super::poly::Exp)> = factors
                .iter()
                .map(|(n, e)| (self.vars.intern(n), *e))
                .collect();
            let m = super::poly::Monomial::checked_from_factors(factors).ok_or(EvalError::Limit)?;
            terms.push((m, c.clone()));
        }
        Ok(Poly::from_terms(terms))
    }

    /// The dimension.
    /// Whether the variable of that name is fixed by an assumption: eliminated by an
    /// equation, or a component of a substituted symbol.
    pub(super) fn substituted_or_eliminated(&self, name: &str) -> bool {
        let substituted = self.ctx.substitutions.iter().any(|s| {
            name == s.symbol
                || name
                    .strip_prefix(s.symbol.as_str())
                    .is_some_and(|rest| rest.starts_with('_'))
        });
        let eliminated = self
            .vars
            .lookup(name)
            .is_some_and(|v| self.pivots.contains_key(&v));
        substituted || eliminated
    }

    /// The variable a scalar claim is about: free, not the normal's, not fixed by an
    /// assumption.
    pub fn free_variable(&mut self, name: &str) -> R<Var> {
        let v = self.vars.intern(name);
        if self.substituted_or_eliminated(name) || self.normal.contains(&v) {
            return Err(EvalError::Unsupported(format!(
                "the claim's variable `{name}` is not a free variable"
            )));
        }
        Ok(v)
    }

    /// The statement's context.
    pub fn context(&self) -> &'c Context {
        self.ctx
    }

    pub fn ctx_dim(&self) -> usize {
        self.ctx.dim
    }

    /// The components the linear assumptions eliminated, with their values.
    pub fn eliminated(&self) -> Vec<(Var, Poly)> {
        self.pivots.iter().map(|(v, p)| (*v, p.clone())).collect()
    }
}

impl Definitions for Env<'_> {
    fn mentions(&self, t: &Term, out: &mut BTreeSet<String>) -> R<()> {
        Env::mentions(self, t, out)
    }

    fn derive(&mut self, def: Definition) {
        self.derived.insert(def.name.clone(), def);
    }

    fn has_derived(&self, name: &str) -> bool {
        self.derived.contains_key(name)
    }

    fn definition_of(&self, name: &str) -> Option<Definition> {
        self.definition(name).cloned()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The contraction as defined: every value of every letter in order (those of
    /// `out` first, the last fastest), the product of the factors from left to right up
    /// to the first that is 0 without conditions (then no term), each term added.
    fn by_definition(
        env: &mut Env<'_>,
        factors: &[(&[Frac], Vec<Slot>)],
        out: &[char],
    ) -> Vec<Frac> {
        let d = env.ctx.dim;
        let mut all: Vec<char> = out.to_vec();
        for s in factors.iter().flat_map(|(_, slots)| slots) {
            if let Slot::Letter(c) = s {
                if !all.contains(c) {
                    all.push(*c);
                }
            }
        }
        let mut comps = vec![Frac::default(); d.pow(out.len() as u32)];
        for values in assignments(d, all.len()) {
            let mut product = Frac::one();
            let mut zero = false;
            for (t, slots) in factors {
                let offset = slots.iter().fold(0, |acc, s| {
                    acc * d
                        + match s {
                            Slot::Letter(c) => values[all.iter().position(|x| x == c).unwrap()],
                            Slot::Fixed(k) => *k,
                        }
                });
                let x = &t[offset];
                if x.is_zero() && x.conditions().is_empty() {
                    zero = true;
                    break;
                }
                product = env.mul(&product, x).unwrap();
            }
            if !zero {
                let at = values[..out.len()].iter().fold(0, |acc, &v| acc * d + v);
                comps[at] = env.add(&comps[at], &product).unwrap();
            }
        }
        comps
    }

    /// A pseudo-random generator for the cases (SplitMix64).
    struct Cases(u64);

    impl Cases {
        fn below(&mut self, n: usize) -> usize {
            self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = self.0;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            ((z ^ (z >> 31)) % n as u64) as usize
        }
    }

    /// A component: mostly 0 (with or without a condition), else a constant, a
    /// variable, or a fraction over one of two divisors.
    fn fraction(env: &mut Env<'_>, cases: &mut Cases) -> Frac {
        let (x, y) = (
            Poly::var(env.vars.intern("x")),
            Poly::var(env.vars.intern("y")),
        );
        let over = |p: &Poly| Frac::one().div(&Frac::from(p.clone())).unwrap();
        let first = over(&(&x + &Poly::one()));
        let second = over(&(&(&x + &y) + &Poly::one()));
        match cases.below(9) {
            0..=3 => Frac::default(),
            4 => Frac::default().with_conditions_of(&second),
            5 => Frac::constant(Rational::int(cases.below(5) as i64 - 2)),
            6 => Frac::from(if cases.below(2) == 0 { x } else { y }),
            7 => first,
            _ => second.mul(&Frac::from(y)).unwrap(),
        }
    }

    #[test]
    fn the_walk_gives_the_definition_s_components_in_its_order() {
        let ctx = Context {
            dim: 3,
            ..Context::default()
        };
        let mut env = Env::new(&ctx, &[]).unwrap();
        let mut cases = Cases(7);
        for _ in 0..400 {
            // Up to four factors of rank 0 to 3 over the letters a–e (each at most twice),
            // now and then a fixed slot.
            let mut uses = [0usize; 5];
            let mut factors: Vec<(Vec<Frac>, Vec<Slot>)> = Vec::new();
            for _ in 0..1 + cases.below(4) {
                let mut slots = Vec::new();
                for _ in 0..cases.below(4) {
                    let k = cases.below(5);
                    if cases.below(6) == 0 || uses[k] == 2 {
                        slots.push(Slot::Fixed(cases.below(3)));
                    } else {
                        uses[k] += 1;
                        slots.push(Slot::Letter(char::from(b'a' + k as u8)));
                    }
                }
                let comps = (0..3usize.pow(slots.len() as u32))
                    .map(|_| fraction(&mut env, &mut cases))
                    .collect();
                factors.push((comps, slots));
            }
            let out: Vec<char> = (0..5)
                .filter(|&k| uses[k] == 1)
                .map(|k| char::from(b'a' + k as u8))
                .collect();
            let refs: Vec<(&[Frac], Vec<Slot>)> = factors
                .iter()
                .map(|(c, s)| (c.as_slice(), s.clone()))
                .collect();
            let expected = by_definition(&mut env, &refs, &out);
            assert_eq!(env.contract(&refs, &out, None).unwrap().comps, expected);
            // Added into a sum: as the sum and the product's own value added.
            let sum: Vec<Frac> = (0..expected.len())
                .map(|_| fraction(&mut env, &mut cases))
                .collect();
            let added: Vec<Frac> = sum
                .iter()
                .zip(&expected)
                .map(|(a, b)| a.add(b).unwrap())
                .collect();
            assert_eq!(env.contract(&refs, &out, Some(sum)).unwrap().comps, added);
        }
    }
}
