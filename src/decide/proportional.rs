//! `strategy = "proportional"`: the two sides agree up to one nonzero factor,
//! `left = λ · right` in every component (a balance law derived in another sign or
//! scale convention than the printed one, or multiplied by a modulus).
//!
//! Convention: λ is a constant or a rational function of the claim's parameters (the
//! declared scalars that are not fields), the same in every component and at every
//! state; the claim then holds where λ is defined and nonzero, and the proof names
//! λ's numerator and denominator as the polynomials that must not vanish ("where
//! G ≠ 0"). A law multiplied by a parameter is the same law where it is nonzero.
//!
//! The factor is fixed where the right side is first nonzero: at the first component
//! that is not identically zero, a rational point where it is nonzero gives
//! λ = left/right with the other variables fixed there and the parameters kept. Any
//! factor that works must equal that ratio, so the search then compares `left` with
//! `λ · right` in every component ([`Identities::proportional`]) and the kernel checks
//! the fact it hands in. A difference refutes
//! every factor at once: the reference, moved to the parameter values of the
//! difference's point, fixes λ there, and the difference's point shows that λ does not
//! work at the same parameter values. Both points are re-evaluated by the interpreter
//! before a `fails` is printed.

use super::outcome::FactorWitness;
use super::points::{point_where_differ, shown_point};
use crate::algebra::certificate::Identities;
use crate::algebra::{assignments, Quotient, RatFunc};
use crate::eval::exact::env::{ExactEnv, Labeled};
use crate::kernel::{PolyError, Rational, Var};
use std::collections::BTreeMap;

/// Where the factor was fixed: the component (index values), the point, and both
/// sides' exact values there.
#[derive(Clone, Debug)]
pub struct Reference {
    pub assignment: Vec<(char, usize)>,
    pub point: BTreeMap<Var, Rational>,
    pub lhs: Rational,
    pub rhs: Rational,
    /// λ as a function of the parameters (a constant when it reads none).
    pub function: RatFunc,
}

impl Reference {
    /// The factor left/right at the reference (nonzero right side by construction).
    pub fn factor(&self) -> Rational {
        self.lhs
            .checked_div(&self.rhs)
            .expect("the reference point has a nonzero right side")
    }

    /// Whether λ depends on parameters.
    pub fn is_function(&self) -> bool {
        self.function.as_constant().is_none()
    }

    /// The reference moved to the parameter values of `point` (the other variables
    /// kept): where λ takes its value at `point`'s parameters. `None` when the right
    /// side is zero there, or a side undefined.
    pub fn at_parameters_of(
        &self,
        env: &ExactEnv<'_>,
        point: &BTreeMap<Var, Rational>,
        (l, r): (&Labeled<Quotient>, &Labeled<Quotient>),
    ) -> Option<Reference> {
        let mut moved = self.point.clone();
        for v in env.parameter_vars() {
            moved.insert(
                v,
                point.get(&v).cloned().unwrap_or_else(|| Rational::int(0)),
            );
        }
        let at = |v: Var| moved.get(&v).cloned().unwrap_or_else(|| Rational::int(0));
        let rhs = r.at(&self.assignment).eval(&at)?;
        let lhs = l.at(&self.assignment).eval(&at)?;
        (!rhs.is_zero()).then(|| Reference {
            assignment: self.assignment.clone(),
            point: moved,
            lhs,
            rhs,
            function: self.function.clone(),
        })
    }

    /// The reference as the report shows it.
    pub fn witness(
        &self,
        env: &ExactEnv<'_>,
        l: &Quotient,
        r: &Quotient,
        of_parameters: bool,
    ) -> FactorWitness {
        let factor = if self.is_function() {
            format!(
                "{} (here {})",
                self.function.display(&env.vars),
                self.factor()
            )
        } else {
            self.factor().to_string()
        };
        FactorWitness {
            factor,
            of_parameters,
            indices: self
                .assignment
                .iter()
                .map(|&(c, v)| (c.to_string(), v + 1))
                .collect(),
            point: shown_point(&env.vars, l, r, &self.point),
            lhs_value: self.lhs.to_string(),
            rhs_value: self.rhs.to_string(),
        }
    }
}

/// Whether either side reads a parameter (a declared scalar that is not a field): only
/// then may the factor depend on parameters, and must a refutation compare two
/// evaluations at the same parameter values.
pub fn reads_parameters(
    env: &ExactEnv<'_>,
    (l, r): (&Labeled<Quotient>, &Labeled<Quotient>),
) -> bool {
    let parameters = env.parameter_vars();
    !parameters.is_empty()
        && [l, r]
            .iter()
            .flat_map(|s| s.tensor.components())
            .any(|q| q.variables().iter().any(|v| parameters.contains(v)))
}

/// Why no reference component was found: a polynomial past its limits, or no rational
/// point among the candidates tried.
#[derive(Debug, thiserror::Error)]
pub enum NoReference {
    #[error("{0}")]
    Limit(#[from] PolyError),
    #[error("no rational point found where the right side is nonzero and the left side defined, to fix the factor")]
    NoPoint,
}

/// The reference of a pair of sides: the first component (in index order) whose right
/// side is not identically zero (modulo n·n = 1), at a point where it is nonzero.
/// `Ok(None)` when the right side is zero in every component: then the sides are
/// proportional exactly when the left side is zero too, a plain identity. `Err` says
/// why no reference was found, which leaves the claim undecided.
pub fn reference(
    env: &ExactEnv<'_>,
    dim: usize,
    (l, r): (&Labeled<Quotient>, &Labeled<Quotient>),
    labels: &[char],
) -> Result<Option<Reference>, NoReference> {
    let normal = env.normal_vars();
    let zero = Quotient::default();
    for a in assignments(dim, labels.len()) {
        let assignment: Vec<(char, usize)> = labels.iter().copied().zip(a).collect();
        let rp = r.at(&assignment);
        let zero_there = Identities::new(normal).compare(rp, &zero)?.is_none();
        if zero_there {
            continue;
        }
        // Nonzero as a function, so a point where it is nonzero and the left side
        // defined exists (the left side's divisors are nonzero polynomials): the search
        // looks for one with them as conditions, among a fixed number of candidates,
        // and may miss it.
        let lp = l.at(&assignment);
        let divisors: Vec<_> = (lp.factors().iter().map(|(f, _)| f.clone()))
            .chain(lp.conditions().iter().cloned())
            .collect();
        let target = rp.clone().with_conditions(&divisors);
        let (point, rhs, _) = point_where_differ(normal, &target, &zero, (env.domain(), &[]))
            .ok_or(NoReference::NoPoint)?;
        let at = |v: Var| point.get(&v).cloned().unwrap_or_else(|| Rational::int(0));
        let lhs = lp.eval(&at).ok_or(NoReference::NoPoint)?;
        // λ with every variable but the parameters fixed at the point.
        let parameters = env.parameter_vars();
        let keep = |v: Var| (!parameters.contains(&v)).then(|| at(v));
        let function = lp
            .to_ratfunc()
            .fix(&keep)
            .zip(rp.to_ratfunc().fix(&keep))
            .and_then(|(a, b)| &a / &b)
            .ok_or(NoReference::NoPoint)?;
        return Ok(Some(Reference {
            assignment,
            point,
            lhs,
            rhs,
            function,
        }));
    }
    Ok(None)
}
