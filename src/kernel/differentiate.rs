//! `grad(F, sigma_ij)` as a term: ∂F/∂σ_c for one component c of σ, with every
//! component of σ independent and every other symbol held fixed, by the rules of
//! differentiation applied to the term. The kernel then evaluates the derivative at
//! the state like any term, so that the assumptions apply after differentiating.
//!
//! ∂σ_ab/∂σ_c = δ_{a c_1} δ_{b c_2}; sums, products, quotients, powers, square roots
//! (d√x = dx / (2√x)), averages, derivatives along the position and `grad`
//! (derivatives commute) follow their rules; a definition's derivative is a new definition, named `∂name/∂σ_c`, made
//! once. A term that does not read σ has derivative 0.

use super::rational::Rational;
use super::statement::Definition;
use super::term::{component_name, EvalError, Leaf, Ranks, Slot, Term};
use std::collections::BTreeSet;

type R<T> = Result<T, EvalError>;

/// What differentiating needs of the evaluator: the definitions a term reads, and a
/// place for the derivatives of definitions it makes.
pub trait Definitions: Ranks {
    /// Every symbol `t` reads, through the definitions it reads.
    fn mentions(&self, t: &Term, out: &mut BTreeSet<String>) -> R<()>;
    /// Registers a definition made by differentiating another; its name is new.
    fn derive(&mut self, def: Definition);
    /// Whether a derived definition of that name exists.
    fn has_derived(&self, name: &str) -> bool;
    /// The definition of that name (a derived one included).
    fn definition_of(&self, name: &str) -> Option<Definition>;
}

/// ∂t/∂(symbol at component c).
pub fn differentiate(t: &Term, symbol: &str, c: &[usize], env: &mut dyn Definitions) -> R<Term> {
    let mut reads = BTreeSet::new();
    env.mentions(t, &mut reads)?;
    if !reads.contains(symbol) {
        return zero_like(t, env);
    }
    let d = |t: &Term, env: &mut dyn Definitions| differentiate(t, symbol, c, env);
    let b = Box::new;
    Ok(match t {
        Term::Const { .. } => zero_like(t, env)?,
        Term::Opaque { what, .. } => return Err(EvalError::Unsupported(what.clone())),
        Term::Leaf {
            of: Leaf::Symbol(_),
            slots,
        } => Term::Product(
            slots
                .iter()
                .zip(c)
                .map(|(s, &k)| Term::Leaf {
                    of: Leaf::Delta,
                    slots: vec![*s, Slot::Fixed(k)],
                })
                .collect(),
        ),
        Term::Leaf {
            of: Leaf::Def(name),
            slots,
        } => Term::Leaf {
            of: Leaf::Def(derived(name, symbol, c, env)?),
            slots: slots.clone(),
        },
        Term::Leaf { .. } => zero_like(t, env)?,
        Term::Sum(ts) => Term::Sum(ts.iter().map(|x| d(x, env)).collect::<R<_>>()?),
        Term::Product(fs) => {
            let mut terms = Vec::new();
            for k in 0..fs.len() {
                let mut factors = fs.clone();
                factors[k] = d(&fs[k], env)?;
                terms.push(Term::Product(factors));
            }
            Term::Sum(terms)
        }
        Term::Neg(a) => Term::Neg(b(d(a, env)?)),
        Term::Div(num, den) => {
            let top = Term::Sum(vec![
                Term::Product(vec![d(num, env)?, (**den).clone()]),
                Term::Neg(b(Term::Product(vec![(**num).clone(), d(den, env)?]))),
            ]);
            Term::Div(b(top), b(Term::Pow(den.clone(), 2)))
        }
        Term::Pow(a, 0) => zero_like(a, env)?,
        Term::Pow(a, k) => Term::Product(vec![
            Term::Const {
                value: Rational::int(i64::from(*k)),
                free: Vec::new(),
            },
            Term::Pow(a.clone(), k - 1),
            d(a, env)?,
        ]),
        Term::Sqrt(a) => Term::Div(
            b(d(a, env)?),
            b(Term::Product(vec![Term::int(2), Term::Sqrt(a.clone())])),
        ),
        Term::Avg(a) => Term::Avg(b(d(a, env)?)),
        Term::Deriv(a, s) => Term::Deriv(b(d(a, env)?), *s),
        // Partial derivatives by symbols commute (the terms are rational functions
        // and roots, smooth where defined): ∂/∂σ_c ∂F/∂τ_k = ∂/∂τ_k ∂F/∂σ_c.
        Term::Grad {
            body,
            symbol: inner,
            slots,
        } => Term::Grad {
            body: b(d(body, env)?),
            symbol: inner.clone(),
            slots: slots.clone(),
        },
        Term::Variation { .. } => {
            return Err(EvalError::Unsupported(
                "a variational derivative inside grad(…)".into(),
            ))
        }
    })
}

/// 0 with the free letters of `t`.
fn zero_like(t: &Term, env: &dyn Definitions) -> R<Term> {
    let free = t.letters(env)?.free;
    Ok(Term::Const {
        value: Rational::int(0),
        free,
    })
}

/// The name of the derivative of definition `name`, made (once) if it is new.
fn derived(name: &str, symbol: &str, c: &[usize], env: &mut dyn Definitions) -> R<String> {
    let dname = format!("∂{name}/∂{}", component_name(symbol, c));
    if !env.has_derived(&dname) {
        let def = env
            .definition_of(name)
            .ok_or_else(|| EvalError::IllFormed(format!("`{name}` is not defined")))?;
        // Registered before its body is made, so that a definition read twice is
        // differentiated once.
        env.derive(Definition {
            name: dname.clone(),
            formal: def.formal.clone(),
            body: Term::int(0),
        });
        let body = differentiate(&def.body, symbol, c, env)?;
        env.derive(Definition {
            name: dname.clone(),
            formal: def.formal,
            body,
        });
    }
    Ok(dname)
}
