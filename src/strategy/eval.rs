//! Exact evaluation of checked expressions to tensors of canonical polynomials.
//!
//! Every symbol component becomes a polynomial variable (`sigma_12`, `n_3`, `R_g`),
//! definitions are evaluated once and cached, assumptions rewrite the symbols'
//! component tensors before anything else is evaluated, and `avg(…)` applies the exact
//! isotropic moments to the normal's monomials.

use super::assume::{Component, Parametrisation};
use crate::derivation::{Assumption, AssumptionKind, Definition};
use crate::kernel::einsum::{einsum as kernel_einsum, Polynomials, Slot};
use crate::kernel::{assignments, Poly, PolyError, Tensor, Var, VarTable};
use crate::lang::parser::Func;
use crate::lang::{Decls, Diagnostic, Node, NodeKind, Origin, Target};
use num_traits::Zero;
use std::collections::HashMap;

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

/// Largest exponent a power may produce.
pub const MAX_EXPONENT: i64 = 10_000;

/// A tensor whose slots are labelled by index letters, sorted.
#[derive(Clone, Debug, PartialEq)]
pub struct Labeled {
    pub labels: Vec<char>,
    pub tensor: Tensor<Poly>,
}

impl Labeled {
    /// The component for the given values of (a superset of) its labels.
    pub fn at(&self, assignment: &[(char, usize)]) -> &Poly {
        let idx: Vec<usize> = self
            .labels
            .iter()
            .map(|c| {
                assignment
                    .iter()
                    .find(|(d, _)| d == c)
                    .map_or(0, |&(_, v)| v)
            })
            .collect();
        self.tensor.get(&idx)
    }
}

/// The exact evaluation environment of one claim.
pub struct ExactEnv<'a> {
    decls: &'a Decls,
    defs: &'a [Definition],
    pub vars: VarTable,
    normal: Vec<Var>,
    symbols: HashMap<String, Tensor<Poly>>,
    cache: HashMap<String, Tensor<Poly>>,
    /// Term products still allowed (see [`MAX_WORK`]).
    work_left: usize,
    parametrisation: Option<Parametrisation>,
}

/// The variable name of a component: `sigma_12`, or the symbol's own name for a scalar.
pub fn component_name(symbol: &str, idx: &[usize]) -> String {
    if idx.is_empty() {
        symbol.to_owned()
    } else {
        let digits: String = idx.iter().map(|i| (i + 1).to_string()).collect();
        format!("{symbol}_{digits}")
    }
}

fn poly_error(origin: &Origin, node: &Node, e: PolyError) -> Diagnostic {
    let help = match e {
        PolyError::DivisionByZero => "the divisor is identically zero",
        PolyError::DivisionBySum => {
            "exact mode divides only by a single term such as 3, V or 2*R_g"
        }
        PolyError::NegativeNormalPower => "keep components of the normal out of divisors",
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
        let parametrisation = Parametrisation::new(decls, assumptions)?;
        let mut env = ExactEnv {
            defs,
            ..ExactEnv::unconstrained(decls)
        };
        // Variables are numbered in order of first use, and witnesses and counterexample
        // points list them in that order: the symbols of the assumptions come first, in
        // the order they are written.
        for (k, a) in assumptions.iter().enumerate() {
            if !parametrisation.substitutions().contains(&k) {
                env.symbol(a.kind.symbol());
            }
        }
        for ((symbol, idx), terms, constant) in parametrisation.dependents() {
            let value = terms
                .iter()
                .fold(Poly::constant(constant.clone()), |acc, ((s, i), q)| {
                    &acc + &(&env.component(s, i) * &Poly::constant((*q).clone()))
                });
            let mut t = env.symbol(symbol);
            *t.get_mut(idx) = value;
            env.symbols.insert(symbol.clone(), t);
        }
        for &k in parametrisation.substitutions() {
            let a = &assumptions[k];
            let AssumptionKind::Equals {
                symbol,
                formal,
                body,
            } = &a.kind
            else {
                unreachable!("substitutions are equations")
            };
            let value = env.eval(body, &a.origin)?;
            let t = to_formal_order(&value, formal);
            env.symbols.insert(symbol.clone(), t);
        }
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
            normal,
            symbols: HashMap::new(),
            cache: HashMap::new(),
            work_left: MAX_WORK,
            parametrisation: None,
        }
    }

    /// The normal's component variables (empty when the file declares no normal).
    pub fn normal_vars(&self) -> &[Var] {
        &self.normal
    }

    /// The solved assumptions (`None` for an unconstrained environment).
    pub fn parametrisation(&self) -> Option<&Parametrisation> {
        self.parametrisation.as_ref()
    }

    /// The variable of one component before any assumption, as a polynomial.
    pub fn component(&mut self, symbol: &str, idx: &[usize]) -> Poly {
        let name = component_name(symbol, idx);
        Poly::var(self.vars.intern(&name))
    }

    /// Every component of every declared symbol, by its variable.
    pub fn component_vars(&mut self) -> HashMap<Var, Component> {
        let mut out = HashMap::new();
        for (name, &rank) in &self.decls.symbols {
            for idx in assignments(self.decls.dim, rank) {
                let v = self.vars.intern(&component_name(name, &idx));
                out.insert(v, (name.clone(), idx));
            }
        }
        out
    }

    /// Whether `p` is affine in the components with rational coefficients: no products,
    /// powers or divisions of variables, and no normal.
    pub fn is_affine(&self, p: &Poly) -> bool {
        p.terms().all(|(m, _)| match m.factors() {
            [] => true,
            [(v, 1)] => !self.normal.contains(v),
            _ => false,
        })
    }

    /// The component tensor of a declared symbol (fresh variables on first use).
    fn symbol(&mut self, name: &str) -> Tensor<Poly> {
        if let Some(t) = self.symbols.get(name) {
            return t.clone();
        }
        let rank = self.decls.symbols.get(name).copied().unwrap_or(0);
        let vars = &mut self.vars;
        let t = Tensor::from_fn(self.decls.dim, rank, |idx| {
            Poly::var(vars.intern(&component_name(name, idx)))
        });
        self.symbols.insert(name.to_owned(), t.clone());
        t
    }

    fn base(&mut self, target: &Target, origin: &Origin) -> Result<Tensor<Poly>, Diagnostic> {
        let d = self.decls.dim;
        Ok(match target {
            Target::Delta => Tensor::delta(d),
            Target::Eps => Tensor::levi_civita(d),
            // An in-plane normal has no third component: n_3 = 0.
            Target::Normal => Tensor::from_fn(d, 1, |i| {
                self.normal
                    .get(i[0])
                    .map_or_else(Poly::zero, |&v| Poly::var(v))
            }),
            Target::Symbol(name) => self.symbol(name),
            Target::Def(name) => {
                if let Some(t) = self.cache.get(name) {
                    return Ok(t.clone());
                }
                let Some(def) = self.defs.iter().rev().find(|d| &d.sig.name == name) else {
                    return Err(origin.diagnostic(
                        Default::default(),
                        format!("internal: definition `{name}` is not in scope"),
                    ));
                };
                let value = self.eval(&def.body, &def.origin)?;
                let t = to_formal_order(&value, &def.sig.formal);
                self.cache.insert(name.clone(), t.clone());
                t
            }
        })
    }

    /// Evaluates a checked node; `origin` locates errors in its text. Refuses (with a
    /// located error) any component that grows past [`MAX_TERMS`] terms.
    pub fn eval(&mut self, node: &Node, origin: &Origin) -> Result<Labeled, Diagnostic> {
        let value = self.eval_unchecked(node, origin)?;
        if let Some(big) = value
            .tensor
            .components()
            .iter()
            .find(|p| p.num_terms() > MAX_TERMS)
        {
            return Err(origin
                .diagnostic(
                    node.span,
                    format!(
                        "this expands to {} terms, more than the limit of {MAX_TERMS}",
                        big.num_terms()
                    ),
                )
                .with_help("split the statement with definitions, or decide it numerically"));
        }
        Ok(value)
    }

    fn eval_unchecked(&mut self, node: &Node, origin: &Origin) -> Result<Labeled, Diagnostic> {
        let d = self.decls.dim;
        let labels = node.free_letters();
        let scalar = |p: Poly| Labeled {
            labels: vec![],
            tensor: Tensor::scalar(d, p),
        };
        Ok(match &node.kind {
            NodeKind::Const(q) => scalar(Poly::constant(q.clone())),
            NodeKind::Leaf { target, slots } => {
                let base = self.base(target, origin)?;
                let tensor = einsum(d, &[(&base, slots.clone())], &labels, &mut self.work_left)
                    .ok_or_else(|| too_much(origin, node))?;
                Labeled { labels, tensor }
            }
            NodeKind::Neg(a) => {
                let a = self.eval(a, origin)?;
                Labeled {
                    tensor: a.tensor.map(|p| -p),
                    labels: a.labels,
                }
            }
            NodeKind::Sum(terms) => {
                let mut acc: Option<Labeled> = None;
                for t in terms {
                    let v = self.eval(t, origin)?;
                    acc = Some(match acc {
                        None => v,
                        Some(a) => Labeled {
                            tensor: a.tensor.add(&v.tensor),
                            labels: a.labels,
                        },
                    });
                }
                acc.expect("a sum has at least one term")
            }
            NodeKind::Product(factors) => {
                let values = factors
                    .iter()
                    .map(|f| self.eval(f, origin))
                    .collect::<Result<Vec<_>, _>>()?;
                let slots: Vec<(&Tensor<Poly>, Vec<Slot>)> = values
                    .iter()
                    .map(|v| {
                        (
                            &v.tensor,
                            v.labels.iter().map(|&c| Slot::Letter(c)).collect(),
                        )
                    })
                    .collect();
                let tensor = einsum(d, &slots, &labels, &mut self.work_left)
                    .ok_or_else(|| too_much(origin, node))?;
                Labeled { labels, tensor }
            }
            NodeKind::Div(a, b) => {
                let num = self.eval(a, origin)?;
                let den = self.eval(b, origin)?;
                let den = den
                    .tensor
                    .into_scalar()
                    .expect("validated: divisors are scalars");
                let tensor = num
                    .tensor
                    .try_map(|p| p.checked_div(&den))
                    .map_err(|e| poly_error(origin, b, e))?;
                Labeled {
                    labels: num.labels,
                    tensor,
                }
            }
            NodeKind::Pow(a, k) => {
                let p = self
                    .eval(a, origin)?
                    .tensor
                    .into_scalar()
                    .expect("validated: powers of scalars");
                let max_exp = p
                    .terms()
                    .flat_map(|(m, _)| m.factors().iter().map(|&(_, e)| i64::from(e).abs()))
                    .max()
                    .unwrap_or(0);
                // Terms of p^k: at most num_terms^k, and at most the number of
                // monomials of degree ≤ k·(max exponent) in p's variables.
                let mut vars: Vec<_> = p
                    .terms()
                    .flat_map(|(m, _)| m.factors().iter().map(|&(v, _)| v))
                    .collect();
                vars.sort_unstable();
                vars.dedup();
                let degree = (max_exp * i64::from(*k)) as f64;
                let monomials =
                    (1..=vars.len()).fold(1.0, |acc, j| acc * (degree + j as f64) / j as f64);
                let terms = (p.num_terms() as f64).powi(*k as i32).min(monomials);
                // Coefficients grow too: (q)^k has about k times the bits of q.
                let max_bits = p.terms().map(|(_, c)| c.bits()).max().unwrap_or(0);
                let too_big = max_exp * i64::from(*k) > MAX_EXPONENT
                    || terms > MAX_TERMS as f64
                    || max_bits.saturating_mul(u64::from(*k)) > MAX_COEFFICIENT_BITS;
                if too_big {
                    return Err(origin
                        .diagnostic(node.span, "this power is too large to expand exactly")
                        .with_help(format!(
                            "exponents up to {MAX_EXPONENT}, expansions up to {MAX_TERMS} terms and coefficients up to {MAX_COEFFICIENT_BITS} bits are supported"
                        )));
                }
                scalar(p.pow(*k))
            }
            NodeKind::Apply(Func::Sqrt, a) => {
                let p = self
                    .eval(a, origin)?
                    .tensor
                    .into_scalar()
                    .expect("validated: sqrt of scalars");
                let root = p.as_constant().and_then(|q| q.sqrt_exact()).ok_or_else(|| {
                    origin
                        .diagnostic(node.span, "sqrt(…) of this expression has no exact polynomial value")
                        .with_help("exact mode takes square roots of squares of rationals only; use strategy = \"numeric\"")
                })?;
                scalar(Poly::constant(root))
            }
            NodeKind::Apply(func, _) => {
                return Err(origin
                    .diagnostic(
                        node.span,
                        format!("{}(…) has no exact polynomial value", func.name()),
                    )
                    .with_help("decide this claim with strategy = \"numeric\""))
            }
            NodeKind::MaxN(_) => {
                return Err(origin
                    .diagnostic(
                        node.span,
                        "maxn(…) is a maximum over orientations, not a polynomial",
                    )
                    .with_help("decide this claim with strategy = \"numeric\""))
            }
            NodeKind::Avg(a) => {
                let v = self.eval(a, origin)?;
                let normal = self.normal.clone();
                let tensor = v
                    .tensor
                    .try_map(|p| p.average_over_normal(&normal))
                    .map_err(|e| poly_error(origin, node, e))?;
                Labeled {
                    labels: v.labels,
                    tensor,
                }
            }
        })
    }
}

fn too_much(origin: &Origin, node: &Node) -> Diagnostic {
    origin
        .diagnostic(
            node.span,
            format!("expanding this statement exactly takes more than {MAX_WORK} term products"),
        )
        .with_help("split the statement with definitions, or decide it numerically")
}

/// Reorders a sorted-label tensor into a definition's formal index order.
fn to_formal_order(value: &Labeled, formal: &[char]) -> Tensor<Poly> {
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

/// The kernel's contraction in canonical polynomials, charged to `budget`; `None`
/// when the expansion would take more term products than are left.
fn einsum(
    dim: usize,
    factors: &[(&Tensor<Poly>, Vec<Slot>)],
    out: &[char],
    budget: &mut usize,
) -> Option<Tensor<Poly>> {
    let mut left = *budget;
    let t = kernel_einsum(
        &mut Polynomials {
            work_left: &mut left,
        },
        dim,
        factors,
        out,
    )
    .ok()?;
    *budget = left;
    Some(t)
}
