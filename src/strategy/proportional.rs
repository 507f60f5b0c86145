//! `strategy = "proportional"`: the two sides agree up to one nonzero constant factor,
//! `left = λ · right` in every component (a balance law derived in another sign or
//! scale convention than the printed one).
//!
//! The factor is fixed where the right side is first nonzero: at the first component
//! that is not identically zero, a rational point where it is nonzero gives
//! λ = left/right. Any factor that works must equal that ratio there, so the kernel
//! then compares `left` with `λ · right` in every component ([`Identities::proportional`]).
//! A difference refutes every factor at once: the reference point fixes λ, the
//! difference's point shows that λ does not work. Both points are re-evaluated by the
//! interpreter before a `fails` is printed.

use super::eval::{ExactEnv, Labeled};
use super::exact::{point_where_differ, shown_point};
use super::FactorWitness;
use crate::algebra::certificate::Identities;
use crate::algebra::{assignments, Quotient};
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
}

impl Reference {
    /// The factor left/right at the reference (nonzero right side by construction).
    pub fn factor(&self) -> Rational {
        self.lhs
            .checked_div(&self.rhs)
            .expect("the reference point has a nonzero right side")
    }

    /// The reference as the report shows it.
    pub fn witness(&self, env: &ExactEnv<'_>, l: &Quotient, r: &Quotient) -> FactorWitness {
        FactorWitness {
            factor: self.factor().to_string(),
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

/// The reference of a pair of sides: the first component (in index order) whose right
/// side is not identically zero (modulo n·n = 1), at a point where it is nonzero.
/// `Ok(None)` when the right side is zero in every component: then the sides are
/// proportional exactly when the left side is zero too, a plain identity. `Err` says
/// why no reference was found, which leaves the claim undecided.
pub fn reference(
    env: &ExactEnv<'_>,
    dim: usize,
    (l, r): (&Labeled, &Labeled),
    labels: &[char],
) -> Result<Option<Reference>, String> {
    let normal = env.normal_vars();
    let zero = Quotient::default();
    for a in assignments(dim, labels.len()) {
        let assignment: Vec<(char, usize)> = labels.iter().copied().zip(a).collect();
        let rp = r.at(&assignment);
        let zero_there = Identities::new(normal)
            .compare(rp, &zero)
            .map_err(|e: PolyError| e.to_string())?
            .is_none();
        if zero_there {
            continue;
        }
        // Nonzero as a function, so a point where it is nonzero exists; the search
        // tries a fixed number of candidates and may miss it.
        let missed = || {
            "no rational point found where the right side is nonzero and the left side defined, to fix the factor".to_owned()
        };
        let (point, rhs, _) =
            point_where_differ(normal, rp, &zero, env.domain()).ok_or_else(missed)?;
        let at = |v: Var| point.get(&v).cloned().unwrap_or_else(|| Rational::int(0));
        let lhs = l.at(&assignment).eval(&at).ok_or_else(missed)?;
        return Ok(Some(Reference {
            assignment,
            point,
            lhs,
            rhs,
        }));
    }
    Ok(None)
}
