//! Exact evaluation of checked expressions to tensors of canonical polynomials.
//!
//! Every symbol component becomes a polynomial variable (`sigma_12`, `n_3`, `R_g`),
//! definitions are evaluated once and cached, assumptions rewrite the symbols'
//! component tensors before anything else is evaluated, and `avg(…)` applies the exact
//! isotropic moments to the normal's monomials. The tree is walked by the one walk all
//! routes share (`walk.rs`), in canonical polynomials under a work budget.
//!
//! A value is a [`Quotient`]: a polynomial, or one over a product of divisors when the
//! statement divides by a sum (`E / (2*(1 + nu))`, `1 / det(A)`). Divisors with the
//! normal or a field in them are refused: the reduction on the unit sphere and the
//! derivatives of fields assume a polynomial denominator free of them.

use crate::algebra::certificate::Certificate;
use crate::algebra::einsum::{einsum, einsum_closing, Arithmetic};
use crate::algebra::quotient::Quotients;
use crate::algebra::sign::Interval;
use crate::algebra::{assignments, Quotient, Tensor};
use crate::derivation::parametrisation::{product_value, Component, Parametrisation};
use crate::derivation::{Assumption, Definition, ParamBox};
pub use crate::eval::labeled::Labeled;
use crate::eval::walk::{self, Ring};
pub use crate::kernel::eval::jet_name;
pub use crate::kernel::term::component_name;
use crate::kernel::{Poly, PolyError, Var, VarTable};
use crate::lang::{Decls, Diagnostic, Node, Origin};
use num_traits::{One, Zero};
use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};

/// Largest number of terms one component may reach before evaluation stops: keeps a
/// hostile input (a product of hundreds of sums) from running for hours.
pub const MAX_TERMS: usize = 50_000;

/// Largest number of term-by-term products one evaluation environment (one claim's
/// statement) may spend in all: well under a second of work. The paper's largest exact
/// claim needs a few thousand; a fuzzed file raising σ_kk to the 64th power spent
/// seconds across its claims before this budget.
pub const MAX_WORK: usize = 1_000_000;

/// Largest size, in bits, of a coefficient a power may produce (a fuzzed input raised
/// 31^-64 to the 4096th power and took minutes).
pub const MAX_COEFFICIENT_BITS: u64 = 100_000;

/// Largest number of terms of an exact square root: the long division that finds it
/// costs a pass over the remainder per term, so this bounds it well under a second.
pub const MAX_ROOT_TERMS: usize = 2_000;

/// Largest exponent a power may produce.
pub const MAX_EXPONENT: i64 = 10_000;

/// What a polynomial variable stands for where a derivative acts on it: a coordinate
/// of the position, or one derivative of a field component at the point (a jet
/// variable). Jet variables of different orders are independent: at one point, a
/// smooth field's value and its derivatives can take any values, so two expressions
/// in them agree for every field exactly when their canonical polynomials agree.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Varying {
    /// Coordinate k (0-based) of the position.
    Coordinate(usize),
    /// Component `idx` of `field`, differentiated by the coordinates `orders`
    /// (0-based, sorted: mixed partials commute).
    Jet {
        field: String,
        idx: Vec<usize>,
        orders: Vec<usize>,
    },
}

/// A differential hypothesis solved for its highest derivative: ∂^orders field_idx =
/// value, and so for every derivative of it (`differential.rs` solves and applies it).
#[derive(Clone, Debug)]
pub(crate) struct DerivativeRule {
    pub(crate) field: String,
    pub(crate) idx: Vec<usize>,
    pub(crate) orders: Vec<usize>,
    pub(crate) value: Poly,
}

/// The exact evaluation environment of one claim.
pub struct ExactEnv<'a> {
    pub(crate) decls: &'a Decls,
    pub(crate) defs: &'a [Definition],
    pub vars: VarTable,
    /// The variables a derivative acts on (see [`Varying`]).
    pub(crate) varying: HashMap<Var, Varying>,
    pub(crate) normal: Vec<Var>,
    pub(crate) symbols: HashMap<String, Tensor<Quotient>>,
    pub(crate) cache: HashMap<String, Tensor<Quotient>>,
    /// Term products still allowed (see [`MAX_WORK`]).
    pub(crate) work_left: usize,
    /// Every symbol an assumption mentions (on either side): such a field cannot be
    /// varied component by component.
    pub(crate) assumed: HashSet<String>,
    pub(crate) parametrisation: Option<Parametrisation>,
    /// The claim's box of parameter values (`given`): the sign of a square root is
    /// certified on it.
    pub(crate) domain: Vec<(Var, Interval)>,
    /// The square roots taken exactly, each with the kernel's certificate.
    pub(crate) roots: Vec<Certificate>,
    /// Their values, offered to the kernel when it re-checks a proof.
    root_values: Vec<Quotient>,
    /// Definitions with their derivatives by symbols (`grad`), by (the symbols of each
    /// level, name).
    pub(crate) jet_cache: HashMap<(String, String), Tensor<super::jet::Jet>>,
    /// The claim's box by name, while [`ExactEnv::on`] evaluates the substitutions.
    pending: Vec<(String, Interval)>,
    /// The polynomial constraints, each solved for a power of a variable of its own,
    /// then the square roots taken as variables of their own.
    rules: Vec<crate::kernel::rules::Rule>,
    /// Whether a square root of a polynomial that is no square becomes a variable of
    /// its own (see [`ExactEnv::allow_algebraic_roots`]).
    algebraic_roots: bool,
    /// The differential hypotheses, each solved for its highest derivative.
    pub(crate) derivative_rules: Vec<DerivativeRule>,
    /// The derivatives of fields those rules determine, by variable.
    pub(crate) derivative_values: HashMap<Var, Poly>,
}

pub(crate) fn poly_error(origin: &Origin, node: &Node, e: PolyError) -> Diagnostic {
    let help = match e {
        PolyError::DivisionByZero => "the divisor is identically zero",
        PolyError::DivisionBySum => {
            "exact mode divides only by a single term such as 3, V or 2*R_g"
        }
        PolyError::NegativeNormalPower => "keep components of the normal out of divisors",
        PolyError::TooLarge | PolyError::TooManyProducts => {
            "split the statement with definitions, or decide it numerically"
        }
        PolyError::ExponentTooLarge => "exponents up to 2^40 are supported exactly",
    };
    origin.diagnostic(node.span, e.to_string()).with_help(help)
}

impl<'a> ExactEnv<'a> {
    /// Builds the environment: the assumptions solved as one system
    /// ([`Parametrisation`]), every constrained component replaced by its value in the
    /// free ones, then the substitutions in dependency order.
    pub fn new(
        decls: &'a Decls,
        defs: &'a [Definition],
        assumptions: &[Assumption],
    ) -> Result<Self, Diagnostic> {
        Ok(Self::on(decls, defs, assumptions, None)?)
    }

    /// [`ExactEnv::new`] on the claim's box (`given`): the square roots of the
    /// substitutions, and of the definitions they read, take their sign there. A
    /// substitution whose value costs more than the limits allow, or needs a root the
    /// box does not certify, is a refusal of that kind, not an input error.
    pub fn on(
        decls: &'a Decls,
        defs: &'a [Definition],
        assumptions: &[Assumption],
        domain: Option<&ParamBox>,
    ) -> Result<Self, Refusal> {
        let parametrisation =
            Parametrisation::new(decls, defs, assumptions).map_err(Refusal::Input)?;
        let mut env = ExactEnv {
            defs,
            ..ExactEnv::unconstrained(decls)
        };
        // Variables are numbered in order of first use, and witnesses and counterexample
        // points list them in that order: the symbols of the assumptions come first, in
        // the order they are written.
        for (k, a) in assumptions.iter().enumerate() {
            if parametrisation.substitutions().contains(&k) {
                continue;
            }
            match a.kind.symbol() {
                Some(s) => {
                    env.symbol(s);
                }
                None => {
                    for s in &a.reads {
                        env.symbol(s);
                    }
                }
            }
        }
        for d in parametrisation.dependents() {
            let (symbol, idx) = d.component;
            let value = env.dependent_value(&d);
            let mut t = env.symbol(symbol);
            *t.get_mut(idx) = Quotient::from(value);
            env.symbols.insert(symbol.clone(), t);
        }
        for s in parametrisation.solved() {
            let value = s.value.iter().fold(Poly::zero(), |acc, (p, q)| {
                let x = product_value(p, Poly::one(), |(s, i)| env.component(s, i));
                &acc + &(&x * &Poly::constant(q.clone()))
            });
            let var = env.component_var(&s.component.0, &s.component.1);
            env.rules.push(crate::kernel::rules::Rule {
                var,
                power: s.power,
                value,
                nonnegative: false,
            });
        }
        // While the substitutions are evaluated, the box is read by name, so that the
        // variables keep the order in which they are first used.
        env.pending = domain.map(|d| d.bounds.clone()).unwrap_or_default();
        for sub in parametrisation.substituted(assumptions) {
            let value = env.eval(sub.body, &sub.assumption.origin)?;
            let t = to_formal_order(&value, sub.formal);
            env.symbols.insert(sub.symbol.to_owned(), t);
        }
        env.differential(assumptions)?;
        env.pending.clear();
        if let Some(domain) = domain {
            env.set_domain(domain);
        }
        env.assumed = assumptions.iter().flat_map(Assumption::symbols).collect();
        env.parametrisation = Some(parametrisation);
        Ok(env)
    }

    /// An environment with no definitions and no assumptions: every component of every
    /// symbol is its own variable.
    pub fn unconstrained(decls: &'a Decls) -> Self {
        let mut vars = VarTable::new();
        let free_components = if decls.normal_in_plane { 2 } else { decls.dim };
        let normal = match &decls.normal {
            Some(n) => (1..=free_components)
                .map(|k| vars.intern(&format!("{n}_{k}")))
                .collect(),
            None => Vec::new(),
        };
        ExactEnv {
            decls,
            defs: &[],
            vars,
            varying: HashMap::default(),
            normal,
            symbols: HashMap::default(),
            cache: HashMap::default(),
            work_left: MAX_WORK,
            assumed: HashSet::default(),
            parametrisation: None,
            domain: Vec::new(),
            roots: Vec::new(),
            root_values: Vec::new(),
            jet_cache: HashMap::default(),
            pending: Vec::new(),
            rules: Vec::new(),
            algebraic_roots: false,
            derivative_rules: Vec::new(),
            derivative_values: HashMap::default(),
        }
    }

    /// Bounds the declared scalars by the claim's box (`given`), on which the sign of
    /// every square root is certified.
    pub fn set_domain(&mut self, domain: &ParamBox) {
        self.domain = domain
            .bounds
            .iter()
            .map(|(name, i)| (self.component_var(name, &[]), i.clone()))
            .collect();
    }

    /// The definition `name` in scope (the innermost of that name).
    pub(crate) fn definition(&self, name: &str) -> Option<&'a Definition> {
        self.defs.iter().rev().find(|d| d.sig.name == name)
    }

    /// The box of [`ExactEnv::set_domain`], by variable.
    pub fn domain(&self) -> &[(Var, Interval)] {
        &self.domain
    }

    /// The square roots taken so far, by variable names, for the kernel.
    pub fn root_data(&self) -> Vec<crate::kernel::statement::FracData> {
        self.root_values
            .iter()
            .map(|q| q.data(&self.vars))
            .collect()
    }

    /// The certificates of the square roots taken so far.
    pub fn root_certificates(&self) -> &[Certificate] {
        &self.roots
    }

    /// The normal's component variables (empty when the file declares no normal).
    pub fn normal_vars(&self) -> &[Var] {
        &self.normal
    }

    /// The polynomial constraints, solved for powers, and the square roots taken as
    /// variables (see [`crate::kernel::rules`]).
    pub fn rules(&self) -> &[crate::kernel::rules::Rule] {
        &self.rules
    }

    /// From now on, √x of a polynomial x that is no square (and reads neither the
    /// normal nor a field) is a variable r of its own with r² = x and r ≥ 0, as the
    /// kernel reads it where it checks an identity or a refutation: an identity then
    /// holds modulo r² = x (on both branches), and a refutation needs a point where x is
    /// a rational square. Only a caller that compares modulo [`ExactEnv::rules`] may
    /// allow it.
    pub fn allow_algebraic_roots(&mut self) {
        self.algebraic_roots = true;
    }

    /// The solved assumptions (`None` for an unconstrained environment).
    pub fn parametrisation(&self) -> Option<&Parametrisation> {
        self.parametrisation.as_ref()
    }

    /// A component the linear assumptions determine, as a polynomial in the variables
    /// of the free ones (and of the products of parameters).
    pub(crate) fn dependent_value(
        &mut self,
        d: &crate::derivation::parametrisation::Dependent<'_>,
    ) -> Poly {
        let linear = d.terms.iter().map(|(c, q)| (vec![((*c).clone(), 1)], *q));
        let products = d.products.iter().map(|(p, q)| ((*p).clone(), *q));
        linear
            .chain(products)
            .fold(Poly::constant(d.constant.clone()), |acc, (p, q)| {
                let x = product_value(&p, Poly::one(), |(s, i)| self.component(s, i));
                &acc + &(&x * &Poly::constant(q.clone()))
            })
    }

    /// The variable of one component before any assumption, as a polynomial.
    pub fn component(&mut self, symbol: &str, idx: &[usize]) -> Poly {
        Poly::var(self.component_var(symbol, idx))
    }

    /// The variable of one component, registered as varying when the symbol is a
    /// field or the position.
    pub(crate) fn component_var(&mut self, symbol: &str, idx: &[usize]) -> Var {
        let v = self.vars.intern(&component_name(symbol, idx));
        if self.decls.fields.contains_key(symbol) {
            self.varying.entry(v).or_insert_with(|| Varying::Jet {
                field: symbol.to_owned(),
                idx: idx.to_vec(),
                orders: Vec::new(),
            });
        } else if self.decls.position.as_deref() == Some(symbol) {
            self.varying.insert(v, Varying::Coordinate(idx[0]));
        }
        v
    }

    /// What the variables a derivative acts on stand for.
    pub fn varying(&self) -> &HashMap<Var, Varying> {
        &self.varying
    }

    /// ∂v/∂x_k for one variable: 1 or 0 for a coordinate, the next jet variable (or its
    /// value by a differential hypothesis) for a field that depends on x_k, and `None`
    /// (zero) for everything else.
    pub(crate) fn derivative_of_var(&mut self, v: Var, k: usize) -> Result<Option<Poly>, Failure> {
        match self.varying.get(&v) {
            None => Ok(None),
            Some(Varying::Coordinate(j)) => Ok((*j == k).then(Poly::one)),
            Some(Varying::Jet { field, idx, orders }) => {
                if !self.decls.fields.get(field).is_some_and(|deps| deps[k]) {
                    return Ok(None);
                }
                let mut orders = orders.clone();
                orders.push(k);
                orders.sort_unstable();
                let (field, idx) = (field.clone(), idx.clone());
                self.derivative(&field, &idx, orders).map(Some)
            }
        }
    }

    /// The variables of the parameters met so far: the declared scalars that are not
    /// fields (a proportionality's factor may depend on them).
    pub fn parameter_vars(&self) -> Vec<Var> {
        (0..self.vars.len() as Var)
            .filter(|&v| {
                let name = self.vars.name(v);
                self.decls.symbols.get(name) == Some(&0)
                    && !self.decls.varies(name)
                    && !self.normal.contains(&v)
            })
            .collect()
    }

    /// Every component of every declared symbol, by its variable.
    pub fn component_vars(&mut self) -> HashMap<Var, Component> {
        let mut out = HashMap::default();
        let symbols: Vec<(String, usize)> = self
            .decls
            .symbols
            .iter()
            .map(|(k, &r)| (k.clone(), r))
            .collect();
        for (name, rank) in symbols {
            for idx in assignments(self.decls.dim, rank) {
                let v = self.component_var(&name, &idx);
                out.insert(v, (name.clone(), idx));
            }
        }
        out
    }

    /// Whether `v` is a component of a declared symbol that an assumption may relate:
    /// not the normal, not a coordinate of the position (an independent variable of
    /// every derivative), and not a derivative of a field (`phi_,i` in a potential
    /// `u_i = phi_,i`).
    pub(crate) fn is_component(&self, v: &Var) -> bool {
        !self.normal.contains(v)
            && match self.varying.get(v) {
                Some(Varying::Coordinate(_)) => false,
                Some(Varying::Jet { orders, .. }) => orders.is_empty(),
                None => true,
            }
    }

    /// Whether `q` is affine in the components with rational coefficients: no products,
    /// powers or divisions of variables, and no normal.
    pub fn is_affine(&self, q: &Quotient) -> bool {
        q.factors().is_empty()
            && q.numerator().terms().all(|(m, _)| match m.factors() {
                [] => true,
                [(v, 1)] => self.is_component(v),
                _ => false,
            })
    }

    /// Whether `q` is a polynomial in the components with rational coefficients: no
    /// division by a sum or by a variable, no normal, no derivative of a field.
    pub fn is_polynomial(&self, q: &Quotient) -> bool {
        q.factors().is_empty()
            && q.numerator().terms().all(|(m, _)| {
                m.factors()
                    .iter()
                    .all(|(v, e)| *e > 0 && self.is_component(v))
            })
    }

    /// The component tensor of a declared symbol (fresh variables on first use).
    pub(crate) fn symbol(&mut self, name: &str) -> Tensor<Quotient> {
        if let Some(t) = self.symbols.get(name) {
            return t.clone();
        }
        let rank = self.decls.symbols.get(name).copied().unwrap_or(0);
        let t = Tensor::from_fn(self.decls.dim, rank, |idx| {
            Quotient::from(self.component(name, idx))
        });
        self.symbols.insert(name.to_owned(), t.clone());
        t
    }

    /// Evaluates a checked node; `origin` locates errors in its text. Refuses (with a
    /// located error) any component that grows past [`MAX_TERMS`] terms, and an
    /// expansion that takes more than [`MAX_WORK`] term products in all.
    pub fn eval(&mut self, node: &Node, origin: &Origin) -> Result<Labeled<Quotient>, Refusal> {
        let mut ring = ExactRing { env: self, origin };
        match walk::walk(&mut ring, node, &()) {
            Ok(tensor) => Ok(Labeled {
                labels: node.free_letters(),
                tensor,
            }),
            Err(Failure::Located(d)) => Err(Refusal::Input(d)),
            Err(Failure::Limit(d)) => Err(Refusal::Limit(d)),
            Err(Failure::Uncertified(d)) => Err(Refusal::Uncertified(d)),
            Err(Failure::OverBudget) => Err(Refusal::Limit(too_much(origin, node))),
        }
    }
}

/// Why an exact evaluation gave no value: the input cannot be evaluated exactly (a
/// function with no polynomial value: the file should say `strategy = "numeric"`), or
/// it can, but past a resource limit ([`MAX_WORK`], [`MAX_TERMS`], the size of a
/// power), or the kernel cannot certify a value it needs (the sign of a square root on
/// the claim's box); the last two make the claim undecided rather than the file
/// malformed.
#[derive(Clone, Debug)]
pub enum Refusal {
    Input(Diagnostic),
    Limit(Diagnostic),
    Uncertified(Diagnostic),
}

impl Refusal {
    pub fn diagnostic(&self) -> &Diagnostic {
        match self {
            Refusal::Input(d) | Refusal::Limit(d) | Refusal::Uncertified(d) => d,
        }
    }
}

/// Where a caller cannot decide anything without the value, both are errors.
impl From<Refusal> for Diagnostic {
    fn from(r: Refusal) -> Self {
        match r {
            Refusal::Input(d) | Refusal::Limit(d) | Refusal::Uncertified(d) => d,
        }
    }
}

/// Why an exact evaluation stopped: the work budget ran out in a contraction (located
/// by the walk at the contraction's node), a located resource limit, or a located
/// input error.
pub(crate) enum Failure {
    /// A value the kernel could not certify (see [`Refusal::Uncertified`]).
    Uncertified(Diagnostic),
    OverBudget,
    Limit(Diagnostic),
    Located(Diagnostic),
}

/// The exact environment as the walk's ring, with the origin that locates errors in
/// the text being evaluated (a definition's body has its own).
pub(crate) struct ExactRing<'e, 'a> {
    pub(crate) env: &'e mut ExactEnv<'a>,
    pub(crate) origin: &'e Origin,
}

impl ExactRing<'_, '_> {
    pub(crate) fn error(&self, node: &Node, message: impl Into<String>, help: &str) -> Failure {
        Failure::Located(
            self.origin
                .diagnostic(node.span, message)
                .with_help(help.to_owned()),
        )
    }

    /// D_k p: Σ_v ∂p/∂v · ∂v/∂x_k over the variables of p, charged to the budget.
    pub(crate) fn total_derivative(&mut self, p: &Poly, k: usize) -> Result<Poly, Failure> {
        self.env.differentiate(p, k)
    }

    /// A resource limit reached at `node`.
    pub(crate) fn limit(&self, node: &Node, message: impl Into<String>, help: &str) -> Failure {
        Failure::Limit(
            self.origin
                .diagnostic(node.span, message)
                .with_help(help.to_owned()),
        )
    }
}

impl ExactRing<'_, '_> {
    /// The rank of a declared symbol.
    pub(crate) fn rank_of(&self, symbol: &str) -> usize {
        self.env.decls.symbols.get(symbol).copied().unwrap_or(0)
    }

    /// The average of one component over the normal: it acts on the numerator, since
    /// no divisor contains the normal.
    pub(crate) fn averaged(&self, q: &Quotient, node: &Node) -> Result<Quotient, Failure> {
        q.numerator()
            .average_over_normal(&self.env.normal)
            .map(|p| q.with_numerator(p))
            .map_err(|e| Failure::Located(poly_error(self.origin, node, e)))
    }

    /// Refuses a value with a component past [`MAX_TERMS`] terms.
    pub(crate) fn within_limits<'q>(
        &self,
        node: &Node,
        values: impl IntoIterator<Item = &'q Quotient>,
    ) -> Result<(), Failure> {
        if let Some(big) = values
            .into_iter()
            .find(|q| q.numerator().num_terms() > MAX_TERMS)
        {
            return Err(self.limit(
                node,
                format!(
                    "this expands to {} terms, more than the limit of {MAX_TERMS}",
                    big.numerator().num_terms()
                ),
                "split the statement with definitions, or decide it numerically",
            ));
        }
        Ok(())
    }

    /// √p exactly: a nonnegative rational, or a rational function whose square is
    /// `p` and whose sign the kernel certifies on the claim's box (`given`), with
    /// the certificate kept for the proof.
    pub(crate) fn square_root(&mut self, p: &Quotient, node: &Node) -> Result<Quotient, Failure> {
        if let Some(q) = p.as_constant() {
            return q
                .sqrt_exact()
                .map(|q| Quotient::from(Poly::constant(q)).with_conditions(p.conditions()))
                .ok_or_else(|| {
                    self.error(
                        node,
                        format!("sqrt({q}) is not a rational number"),
                        "exact mode takes square roots of squares only; decide this claim with strategy = \"numeric\"",
                    )
                });
        }
        let Some(root) = p.sqrt_exact(MAX_ROOT_TERMS) else {
            if let Some(r) = self.algebraic_root(p) {
                return Ok(r);
            }
            return Err(self.error(
                node,
                "sqrt(…) of this expression has no exact value: it is not the square of a rational function here",
                "exact mode takes square roots of squares (such as sqrt(tau^2) with given = [\"tau > 0\"]) and, in an identity, of other polynomials as variables of their own, but not of a constant times a square (irrational wherever it is not 0); decide this claim with strategy = \"numeric\" to sample it",
            ));
        };
        let env = &mut *self.env;
        // A bound of the pending box on a variable not used yet bounds nothing here.
        let mut domain = env.domain.clone();
        domain.extend(
            env.pending
                .iter()
                .filter_map(|(name, i)| Some((env.vars.lookup(name)?, i.clone()))),
        );
        for candidate in [root.clone(), -root.clone()] {
            if let Some(c) = Certificate::square_root(p, &candidate, &domain, &env.vars) {
                if !env.roots.contains(&c) {
                    env.roots.push(c);
                }
                if !env.root_values.iter().any(|r| {
                    r.numerator() == candidate.numerator() && r.factors() == candidate.factors()
                }) {
                    env.root_values.push(candidate.clone());
                }
                // √X is defined only where X is (as the kernel reads it).
                return Ok(candidate.with_conditions(p.conditions()));
            }
        }
        // In an identity the root may still be a variable of its own (r² = p, r ≥ 0):
        // then the sign matters only to a refutation, which takes r ≥ 0.
        if let Some(r) = self.algebraic_root(p) {
            return Ok(r);
        }
        // The statement may well hold; without the sign it is not decided.
        let shown = root.display_truncated(&self.env.vars, 8);
        Err(Failure::Uncertified(
            self.origin
                .diagnostic(
                    node.span,
                    format!("sqrt(…) is ±({shown}) here, but the sign of {shown} on the claim's domain is not certified"),
                )
                .with_help("bound the parameters with given (such as given = [\"f_r > 0\", \"sigma < 0\"]) so that the root has one sign there"),
        ))
    }

    /// √p as a variable of its own, as the kernel takes it (`kernel::eval`): for a
    /// polynomial p, not constant, with no negative power, reading neither the normal
    /// nor a field, reduced by the rules so far; `None` otherwise, or when not allowed.
    fn algebraic_root(&mut self, p: &Quotient) -> Option<Quotient> {
        let env = &mut *self.env;
        let n = p.numerator();
        let plain = env.algebraic_roots
            && p.factors().is_empty()
            && p.conditions().is_empty()
            && n.as_constant().is_none()
            && n.terms().all(|(m, _)| {
                m.factors().iter().all(|&(v, e)| {
                    e > 0 && !env.normal.contains(&v) && !env.varying.contains_key(&v)
                })
            });
        if !plain {
            return None;
        }
        // A constant that is no square times a square (3 Y²) has an irrational root at
        // every rational point where it is not 0: no exact refutation could exist, so
        // it stays refused.
        let (_, lead) = n.leading()?;
        let unit = Quotient::from(n * &Poly::constant(lead.recip()?));
        if lead.sqrt_exact().is_none() && unit.sqrt_exact(MAX_ROOT_TERMS).is_some() {
            return None;
        }
        let radicand =
            crate::kernel::rules::reduce(n, &env.rules, crate::kernel::eval::RULE_STEPS).ok()?;
        // Reduced by the constraints to a constant: its root is rational, or refused
        // (as the kernel does).
        if let Some(c) = radicand.as_constant() {
            return c
                .sqrt_exact()
                .map(|r| Quotient::from(Poly::constant(r)).with_conditions(p.conditions()));
        }
        let rule = crate::kernel::rules::Rule::square_root(radicand, &mut env.vars);
        let r = Quotient::from(Poly::var(rule.var));
        if !env.rules.iter().any(|s| s.var == rule.var) {
            env.rules.push(rule);
        }
        Some(r)
    }

    /// `avg(product)` (eqs. (33), (36), (38)): the product evaluated as the walk does it
    /// (entered, its factors, their contraction), each product of components averaged
    /// as it is formed ([`crate::algebra::polynomial::average_of_product`], charged as the product), so that
    /// the terms whose average vanishes are never formed. That skips the product's own
    /// size limit, so it is done only where the limit cannot bite (at most
    /// [`MAX_TERMS`] term products in every component) and only for polynomials without
    /// negative powers of n; otherwise the product is formed, limited and averaged.
    pub(crate) fn average_of_product(
        &mut self,
        product: &Node,
        fs: &[Node],
        node: &Node,
    ) -> Result<Tensor<Quotient>, Failure> {
        self.enter(product)?;
        let values = walk::factor_values(self, fs, &())?;
        let factors = walk::as_factors(&values);
        let labels = product.free_letters();
        let d = self.env.decls.dim;
        let normal = self.env.normal.clone();
        let plain = |q: &Quotient| {
            q.factors().is_empty()
                && q.conditions().is_empty()
                && q.numerator().terms().all(|(m, _)| {
                    m.factors()
                        .iter()
                        .all(|(v, e)| *e >= 0 || !normal.contains(v))
                })
        };
        let fused = values
            .iter()
            .all(|v| v.tensor.components().iter().all(plain))
            && {
                let counts: Vec<Tensor<usize>> = values
                    .iter()
                    .map(|v| v.tensor.map(|q| q.numerator().num_terms()))
                    .collect();
                let count_factors: Vec<_> = counts
                    .iter()
                    .zip(&factors)
                    .map(|(c, (_, slots))| (c, slots.clone()))
                    .collect();
                let bound = einsum(&mut TermCounts, d, &count_factors, &labels)
                    .unwrap_or_else(|never| match never {});
                bound.components().iter().all(|&b| b <= MAX_TERMS)
            };
        if !fused {
            let v = walk::contract(self, &factors, &labels, product)?;
            let v = self.leave(product, v)?;
            return v.try_map(|q| self.averaged(q, node));
        }
        let (origin, at) = (self.origin, node);
        let averaged = einsum_closing(self, d, &factors, &labels, |ring, p, c| {
            let (p, c) = (p.numerator(), c.numerator());
            let cost = p.num_terms().saturating_mul(c.num_terms());
            ring.env.work_left = ring
                .env
                .work_left
                .checked_sub(cost)
                .ok_or(Failure::OverBudget)?;
            crate::algebra::polynomial::average_of_product(p, c, &normal)
                .map(Quotient::from)
                .map_err(|e| Failure::Located(poly_error(origin, at, e)))
        });
        averaged.map_err(|e| self.at(e, product))
    }
}

/// Term counts: each product of components has at most the product of their counts
/// of terms, and a sum at most the sum (saturating: a bound, never an overflow).
struct TermCounts;

impl Arithmetic for TermCounts {
    type Value = usize;
    type Error = std::convert::Infallible;
    fn zero(&mut self) -> usize {
        0
    }
    fn one(&mut self) -> usize {
        1
    }
    fn is_exact_zero(&self, x: &usize) -> bool {
        *x == 0
    }
    fn mul(&mut self, a: usize, b: &usize) -> Result<usize, Self::Error> {
        Ok(a.saturating_mul(*b))
    }
    fn add(&mut self, a: usize, b: usize) -> Result<usize, Self::Error> {
        Ok(a.saturating_add(b))
    }
}

/// Quotients of canonical polynomials, products charged to the environment's work
/// budget by the kernel's [`Quotients`] arithmetic.
impl Arithmetic for ExactRing<'_, '_> {
    type Value = Quotient;
    type Error = Failure;
    fn zero(&mut self) -> Quotient {
        Quotient::default()
    }
    fn one(&mut self) -> Quotient {
        Quotient::from(Poly::one())
    }
    fn is_exact_zero(&self, x: &Quotient) -> bool {
        x.is_exact_zero()
    }
    fn mul(&mut self, a: Quotient, b: &Quotient) -> Result<Quotient, Failure> {
        let mut ring = Quotients {
            work_left: &mut self.env.work_left,
        };
        ring.mul(a, b).map_err(|_| Failure::OverBudget)
    }
    fn add(&mut self, a: Quotient, b: Quotient) -> Result<Quotient, Failure> {
        let mut ring = Quotients {
            work_left: &mut self.env.work_left,
        };
        ring.add(a, b).map_err(|_| Failure::OverBudget)
    }
    fn first(&mut self, x: &Quotient) -> Result<Quotient, Failure> {
        let mut ring = Quotients {
            work_left: &mut self.env.work_left,
        };
        ring.first(x).map_err(|_| Failure::OverBudget)
    }
}

/// Every condition (a divisor that must not vanish) of the given values, once each.
pub(crate) fn conditions_of<'q>(values: impl IntoIterator<Item = &'q Quotient>) -> Vec<Poly> {
    let mut all: Vec<Poly> = Vec::new();
    for q in values {
        for c in q.conditions() {
            if !all.contains(c) {
                all.push(c.clone());
            }
        }
    }
    all
}

pub(crate) fn too_much(origin: &Origin, node: &Node) -> Diagnostic {
    origin
        .diagnostic(
            node.span,
            format!("expanding this statement exactly takes more than {MAX_WORK} term products"),
        )
        .with_help("split the statement with definitions, or decide it numerically")
}

/// Reorders a sorted-label tensor into a definition's formal index order.
fn to_formal_order(value: &Labeled<Quotient>, formal: &[char]) -> Tensor<Quotient> {
    let perm: Vec<usize> = formal
        .iter()
        .map(|c| {
            value
                .labels
                .iter()
                .position(|d| d == c)
                .expect("validated: same letters")
        })
        .collect();
    value.tensor.permuted(&perm)
}
