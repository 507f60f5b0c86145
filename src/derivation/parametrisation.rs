//! The solution of a claim's assumptions ([`crate::eval::assume`] solves them): which
//! components are free, every other component as an affine function of the free ones,
//! then the whole-symbol substitutions in order; and what the routes read off it.

use crate::algebra::linear::{Affine, AffineEquation, Solution};
use crate::derivation::{Assumption, AssumptionKind};
use crate::kernel::Rational;

/// A component of a declared symbol: its name and 0-based indices.
pub type Component = (String, Vec<usize>);

/// A product of components with exponents: a column of the system. A component is the
/// product of itself alone, to the power 1; a product of parameters is one column.
pub type Product = Vec<(Component, u32)>;

/// A polynomial in components: its terms, each a product with a coefficient (the empty
/// product is the constant term).
pub type Polynomial = Vec<(Product, Rational)>;

/// A polynomial constraint solved for a power of one component:
/// `component^power = value`, the value a polynomial in components that are free
/// (neither solved for by a constraint nor determined by the linear system).
#[derive(Clone, Debug)]
pub struct Solved {
    pub component: Component,
    pub power: u32,
    pub value: Polynomial,
}

/// The value of a product at a state, from the value of each component.
pub fn product_value<T: Clone + std::ops::Mul<Output = T>>(
    product: &Product,
    one: T,
    mut value: impl FnMut(&Component) -> T,
) -> T {
    product.iter().fold(one, |acc, (c, e)| {
        let x = value(c);
        (0..*e).fold(acc, |acc, _| acc * x.clone())
    })
}

/// A whole-symbol substitution `X_ij… = expression` (see [`Parametrisation::substituted`]).
pub struct Substitution<'a> {
    pub assumption: &'a Assumption,
    pub symbol: &'a str,
    pub formal: &'a [char],
    pub body: &'a crate::lang::Node,
}

/// A component the assumptions determine: `constant + Σ coefficient · (free component)
/// + Σ coefficient · (product of parameters)`.
#[derive(Debug)]
pub struct Dependent<'a> {
    pub component: &'a Component,
    pub terms: Vec<(&'a Component, &'a Rational)>,
    pub products: Vec<(&'a Product, &'a Rational)>,
    pub constant: &'a Rational,
}

/// The solution of a claim's assumptions: which components are free, and every other
/// component as an affine function of the free ones; then the substitutions, in order.
#[derive(Debug)]
pub struct Parametrisation {
    pub(crate) columns: Vec<Product>,
    pub(crate) solution: Solution,
    /// The equations as assumed (before solving), for re-checking states.
    pub(crate) equations: Vec<AffineEquation>,
    /// Indices into the assumptions of the whole-symbol substitutions, each after the
    /// substitutions its right side refers to.
    pub(crate) substitutions: Vec<usize>,
    /// The polynomial constraints, solved in order (see [`Solved`]).
    pub(crate) solved: Vec<Solved>,
    /// The polynomial constraints as assumed (every term on one side), for re-checking
    /// states.
    pub(crate) constraints: Vec<Polynomial>,
}

/// How a component is constrained.
#[derive(Clone, Debug, PartialEq)]
pub enum Constrained {
    /// Not constrained, or a free parameter of the solution.
    Free,
    /// Set to a constant.
    Fixed(Rational),
    /// An affine function of free components (and of products of parameters), or a
    /// root of a polynomial constraint ([`Solved`]).
    Dependent,
}

/// The component a column is, when it is one component to the power 1.
pub(crate) fn single(p: &Product) -> Option<&Component> {
    match p.as_slice() {
        [(c, 1)] => Some(c),
        _ => None,
    }
}

impl Parametrisation {
    /// Every component the assumptions determine, with its value.
    pub fn dependents(&self) -> impl Iterator<Item = Dependent<'_>> {
        self.columns.iter().enumerate().filter_map(|(k, c)| {
            let a: &Affine = self.solution.dependent(k)?;
            let (mut terms, mut products) = (Vec::new(), Vec::new());
            for (f, q) in &a.terms {
                let column = &self.columns[*f];
                match single(column) {
                    Some(c) => terms.push((c, q)),
                    None => products.push((column, q)),
                }
            }
            Some(Dependent {
                component: single(c).expect("a pivot is a component"),
                terms,
                products,
                constant: &a.constant,
            })
        })
    }

    /// Indices into the assumptions of the substitutions, in the order to apply them.
    pub fn substitutions(&self) -> &[usize] {
        &self.substitutions
    }

    /// The whole-symbol substitutions among `assumptions` (those this was solved from),
    /// in the order of their dependencies.
    pub fn substituted<'s>(
        &'s self,
        assumptions: &'s [Assumption],
    ) -> impl Iterator<Item = Substitution<'s>> + 's {
        self.substitutions.iter().filter_map(move |&k| {
            let assumption = &assumptions[k];
            match &assumption.kind {
                AssumptionKind::Equals {
                    symbol,
                    formal,
                    body,
                } => Some(Substitution {
                    assumption,
                    symbol,
                    formal,
                    body,
                }),
                _ => None,
            }
        })
    }

    /// The polynomial constraints, each solved for a power of a component of its own,
    /// in the order to evaluate them.
    pub fn solved(&self) -> &[Solved] {
        &self.solved
    }

    /// How the assumptions constrain one component (substitutions aside).
    pub fn constrained(&self, symbol: &str, index: &[usize]) -> Constrained {
        if self
            .solved
            .iter()
            .any(|s| s.component.0 == symbol && s.component.1 == index)
        {
            return Constrained::Dependent;
        }
        let Some(k) = self
            .columns
            .iter()
            .position(|c| single(c).is_some_and(|(s, i)| s == symbol && i == index))
        else {
            return Constrained::Free;
        };
        match self.solution.dependent(k) {
            None => Constrained::Free,
            Some(a) if a.terms.is_empty() => Constrained::Fixed(a.constant.clone()),
            Some(_) => Constrained::Dependent,
        }
    }

    /// The dependent components whose value involves the free component `c`.
    pub fn dependents_on<'a>(&'a self, c: &'a Component) -> impl Iterator<Item = &'a Component> {
        self.dependents()
            .filter(move |d| {
                d.terms.iter().any(|(f, _)| *f == c)
                    || d.products
                        .iter()
                        .any(|(p, _)| p.iter().any(|(f, _)| f == c))
            })
            .map(|d| d.component)
    }

    /// The largest relative residual of the assumed equations at a state (0 when every
    /// one holds exactly): a state that violates them is never reported.
    pub fn residual(&self, value: impl Fn(&Component) -> f64) -> f64 {
        let constraints = self.constraints.iter().map(|p| {
            let (mut sum, mut scale) = (0.0, 0.0);
            for (product, q) in p {
                let term = q.to_f64() * product_value(product, 1.0, &value);
                sum += term;
                scale += term.abs();
            }
            sum.abs() / (1.0 + scale)
        });
        self.equations
            .iter()
            .map(|e| {
                let mut sum = e.constant.to_f64();
                let mut scale = sum.abs();
                for (c, q) in &e.coeffs {
                    let term = q.to_f64() * product_value(&self.columns[*c], 1.0, &value);
                    sum += term;
                    scale += term.abs();
                }
                sum.abs() / (1.0 + scale)
            })
            .chain(constraints)
            // A NaN (a root of a negative number) is no state: it fails the bound.
            .fold(
                0.0,
                |a: f64, b| if b.is_nan() { f64::INFINITY } else { a.max(b) },
            )
    }

    /// Whether every assumed equation holds exactly when the free components take the
    /// given values and the others the values the solution gives them: the solution is
    /// re-checked against the equations as assumed, not trusted.
    pub fn holds_exactly(&self, free: impl Fn(&Component) -> Rational) -> bool {
        let values = self
            .solution
            .complete(|k| product_value(&self.columns[k], Rational::int(1), &free));
        let linear = self.equations.iter().all(|e| {
            e.coeffs
                .iter()
                .fold(e.constant.clone(), |acc, (c, q)| &acc + &(q * &values[*c]))
                .is_zero()
        });
        // The constraints, at every component's value: a column's from the solution.
        let value = |c: &Component| match self.columns.iter().position(|p| single(p) == Some(c)) {
            Some(k) => values[k].clone(),
            None => free(c),
        };
        linear
            && self.constraints.iter().all(|p| {
                p.iter()
                    .fold(Rational::int(0), |acc, (product, q)| {
                        &acc + &(q * &product_value(product, Rational::int(1), &value))
                    })
                    .is_zero()
            })
    }
}
