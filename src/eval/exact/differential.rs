//! Differential hypotheses (`phi_,kk = 0`, `u_k,k = 0`) in the exact search: each is
//! solved for its highest derivative, and every derivative of a field that a rule or
//! one of its derivatives determines is replaced by its value as it is formed, so two
//! sides that agree for every field satisfying the hypotheses have one canonical form.
//!
//! The kernel solves them again by its own code (`kernel::eval`) and checks that the
//! rules are in involution; this side only has to find the same canonical forms, and a
//! mistake here makes a claim undecided, never wrong. Both rank derivatives by
//! [`jet_rank`], so that they choose the same leading derivative.

use super::env::{DerivativeRule, ExactEnv, Failure, Refusal, Varying};
use crate::algebra::assignments;
use crate::algebra::einsum::{Arithmetic, Polynomials};
use crate::derivation::{Assumption, AssumptionKind};
use crate::kernel::eval::{jet_name, jet_rank, substitute};
use crate::kernel::{Poly, Var};
use crate::lang::{Diagnostic, Node};
use itertools::Itertools;
use num_traits::Zero;
use std::collections::BTreeMap;

/// The highest order of derivative [`ExactEnv::complete_derivatives`] forms: far
/// above any statement a person writes, and at most a few hundred per component.
const MAX_COMPLETED_ORDER: usize = 12;

impl DerivativeRule {
    /// The coordinates by which ∂^orders field_idx is a derivative of this rule's
    /// leading derivative, if it is one.
    fn extra(&self, field: &str, idx: &[usize], orders: &[usize]) -> Option<Vec<usize>> {
        if self.field != field || self.idx != idx {
            return None;
        }
        let mut rest = orders.to_vec();
        for k in &self.orders {
            let at = rest.iter().position(|x| x == k)?;
            rest.remove(at);
        }
        Some(rest)
    }
}

impl ExactEnv<'_> {
    /// The value of a derivative of a field that a differential hypothesis determines,
    /// in the derivatives it leaves free.
    pub fn determined_derivative(&self, v: Var) -> Option<&Poly> {
        self.derivative_values.get(&v)
    }

    /// Forms every derivative up to `order` of each field component a differential
    /// hypothesis determines, so that a counterexample's fields (`decide::reverify`)
    /// take the values the hypotheses give them, including derivatives the statement
    /// reached only through a rule's value (phi_,11 through phi_,1 = psi).
    pub(crate) fn complete_derivatives(&mut self, order: usize) -> Result<(), Failure> {
        let mut positions: Vec<(String, Vec<usize>)> = self
            .derivative_rules
            .iter()
            .map(|r| (r.field.clone(), r.idx.clone()))
            .collect();
        positions.dedup();
        for (field, idx) in positions {
            let coordinates: Vec<usize> = (0..self.decls.dim)
                .filter(|&k| self.decls.fields.get(&field).is_some_and(|deps| deps[k]))
                .collect();
            for n in 1..=order.min(MAX_COMPLETED_ORDER) {
                for orders in coordinates.iter().copied().combinations_with_replacement(n) {
                    self.derivative(&field, &idx, orders)?;
                }
            }
        }
        Ok(())
    }

    /// Whether `v` is a field's component (a derivative of order 0).
    pub fn is_field_value(&self, v: Var) -> bool {
        matches!(self.varying.get(&v), Some(Varying::Jet { orders, .. }) if orders.is_empty())
    }

    /// Solves the differential hypotheses among `assumptions`, in order, once every
    /// other assumption is in place, then checks that the rules are in involution.
    pub(crate) fn differential(&mut self, assumptions: &[Assumption]) -> Result<(), Refusal> {
        let refusal = |a: &Assumption, f: Failure| match f {
            Failure::Located(d) => Refusal::Input(d),
            Failure::Limit(d) => Refusal::Limit(d),
            Failure::Uncertified(d) => Refusal::Uncertified(d),
            Failure::OverBudget => Refusal::Limit(
                a.diagnostic("the differential hypotheses take more work than one claim may spend"),
            ),
        };
        let mut last = None;
        for a in assumptions {
            let AssumptionKind::Differential { left, right } = &a.kind else {
                continue;
            };
            self.solve_differential(a, left, right)
                .map_err(|f| refusal(a, f))?;
            last = Some(a);
        }
        match last {
            Some(a) => self.involution(a).map_err(|f| refusal(a, f)),
            None => Ok(()),
        }
    }

    /// One differential hypothesis: each component, reduced by the rules so far, solved
    /// for its derivative of highest [`jet_rank`].
    fn solve_differential(
        &mut self,
        a: &Assumption,
        left: &Node,
        right: &Node,
    ) -> Result<(), Failure> {
        let dim = self.decls.dim;
        let refuse = |message: &str| {
            Failure::Located(a.diagnostic(message.to_owned()).with_help(
                "write a linear hypothesis with constant coefficients, such as phi_,kk = 0 or u_k,k = 0",
            ))
        };
        let located = |e: Refusal| Failure::Located(Diagnostic::from(e));
        let (l, r) = (
            self.eval(left, &a.origin).map_err(located)?,
            self.eval(right, &a.origin).map_err(located)?,
        );
        let letters = left.free_letters();
        for idx in assignments(dim, letters.len()) {
            let assignment: Vec<(char, usize)> =
                letters.iter().copied().zip(idx.iter().copied()).collect();
            let (x, y) = (l.at(&assignment), r.at(&assignment));
            if !x.factors().is_empty() || !y.factors().is_empty() {
                return Err(refuse("a differential hypothesis divides by a sum"));
            }
            let row = self.reduce_derivatives(&(x.numerator() - y.numerator()))?;
            if row.is_zero() {
                continue;
            }
            if !self.linear_in_fields(&row) {
                return Err(refuse("a differential hypothesis must be linear in the fields, with coefficients constant in position"));
            }
            let leading = row
                .variables()
                .into_iter()
                .filter_map(|v| match self.varying.get(&v) {
                    Some(Varying::Jet { field, idx, orders }) if !orders.is_empty() => {
                        Some((jet_rank(field, idx, orders, dim), v))
                    }
                    _ => None,
                })
                .max();
            let Some((_, v)) = leading else {
                // Reduced by the rules before it, nothing of order 1 or more is left.
                return Err(refuse(&format!(
                    "with the differential hypotheses before it, this one says {} = 0, a relation without derivatives (or a contradiction)",
                    row.display_truncated(&self.vars, 8)
                )));
            };
            let mut with_v = row.terms().filter(|(m, _)| m.exponent(v) != 0);
            let c = match (with_v.next(), with_v.next()) {
                (Some((m, c)), None) if m.factors() == [(v, 1)] => c.clone(),
                _ => {
                    return Err(refuse(
                        "the highest derivative of a differential hypothesis must occur once, with a rational coefficient",
                    ))
                }
            };
            let Some(Varying::Jet { field, idx, orders }) = self.varying.get(&v).cloned() else {
                continue;
            };
            let Some(inverse) = c.recip() else { continue };
            let rest = &row - &(&Poly::var(v) * &Poly::constant(c));
            let value = &rest * &Poly::constant(-inverse);
            self.derivative_rules.push(DerivativeRule {
                field,
                idx,
                orders,
                value,
            });
            self.derivative_values.clear();
            self.cache.clear();
        }
        Ok(())
    }

    /// Whether the rules are in involution: two that determine derivatives of one
    /// component agree on their common derivative (else the hypotheses imply a
    /// condition that no rule states, and the derivatives left free are not
    /// independent). `a` locates the refusal.
    fn involution(&mut self, a: &Assumption) -> Result<(), Failure> {
        for i in 0..self.derivative_rules.len() {
            for j in 0..i {
                let (x, y) = (&self.derivative_rules[i], &self.derivative_rules[j]);
                if (&x.field, &x.idx) != (&y.field, &y.idx) {
                    continue;
                }
                // The least derivative of both: each coordinate as often as in either.
                let often = |o: &[usize], k: usize| o.iter().filter(|&&c| c == k).count();
                let common: Vec<usize> = (0..self.decls.dim)
                    .flat_map(|k| vec![k; often(&x.orders, k).max(often(&y.orders, k))])
                    .collect();
                let name = jet_name(&x.field, &x.idx, &common);
                let (p, q) = (self.by_rule(i, &common)?, self.by_rule(j, &common)?);
                if p != q {
                    let condition = (&p - &q).display_truncated(&self.vars, 8);
                    return Err(Failure::Located(
                        a.diagnostic(format!("the differential hypotheses are not in involution: they give `{name}` two different values, so they imply {condition} = 0"))
                            .with_help("add that condition as a hypothesis of its own (assume = [\"… = 0\"]), or drop one"),
                    ));
                }
            }
        }
        Ok(())
    }

    /// Whether every term of `row` has at most one factor that is a field or a
    /// derivative of one, to the power 1 and with no coordinate beside it.
    fn linear_in_fields(&self, row: &Poly) -> bool {
        row.terms().all(|(m, _)| {
            let jets: Vec<_> = m
                .factors()
                .iter()
                .filter(|(v, _)| matches!(self.varying.get(v), Some(Varying::Jet { .. })))
                .collect();
            let positional = m
                .factors()
                .iter()
                .any(|(v, _)| matches!(self.varying.get(v), Some(Varying::Coordinate(_))));
            match jets.as_slice() {
                [] => true,
                [(_, 1)] => !positional,
                _ => false,
            }
        })
    }

    /// ∂^orders of rule `r`'s leading derivative, by that rule alone, reduced.
    fn by_rule(&mut self, r: usize, orders: &[usize]) -> Result<Poly, Failure> {
        let rule = self.derivative_rules[r].clone();
        let extra = rule
            .extra(&rule.field, &rule.idx, orders)
            .unwrap_or_default();
        let mut p = rule.value;
        for k in extra {
            p = self.differentiate(&p, k)?;
        }
        self.reduce_derivatives(&p)
    }

    /// ∂v/∂x_k for a jet variable `(field, idx, orders)` differentiated once more by
    /// x_k: the next variable, or its value by the rules.
    pub(crate) fn derivative(
        &mut self,
        field: &str,
        idx: &[usize],
        orders: Vec<usize>,
    ) -> Result<Poly, Failure> {
        let w = self.vars.intern(&jet_name(field, idx, &orders));
        if let Some(p) = self.derivative_values.get(&w) {
            return Ok(p.clone());
        }
        self.varying.insert(
            w,
            Varying::Jet {
                field: field.to_owned(),
                idx: idx.to_vec(),
                orders: orders.clone(),
            },
        );
        let found = self
            .derivative_rules
            .iter()
            .find_map(|r| Some((r.extra(field, idx, &orders)?, r.value.clone())));
        let Some((extra, value)) = found else {
            return Ok(Poly::var(w));
        };
        let mut p = value;
        for k in extra {
            p = self.differentiate(&p, k)?;
        }
        let p = self.reduce_derivatives(&p)?;
        self.derivative_values.insert(w, p.clone());
        Ok(p)
    }

    /// D_k p: Σ_v ∂p/∂v · ∂v/∂x_k over the variables of p, charged to the budget.
    pub(crate) fn differentiate(&mut self, p: &Poly, k: usize) -> Result<Poly, Failure> {
        let mut acc = Poly::zero();
        for x in p.variables() {
            if let Some(dx) = self.derivative_of_var(x, k)? {
                let mut ring = Polynomials {
                    work_left: &mut self.work_left,
                };
                acc += &ring
                    .mul(p.derivative(x), &dx)
                    .map_err(|_| Failure::OverBudget)?;
            }
        }
        Ok(acc)
    }

    /// `p` with every derivative the rules determine replaced by its value.
    fn reduce_derivatives(&mut self, p: &Poly) -> Result<Poly, Failure> {
        let mut values: BTreeMap<Var, Poly> = BTreeMap::new();
        for x in p.variables() {
            let Some(Varying::Jet { field, idx, orders }) = self.varying.get(&x).cloned() else {
                continue;
            };
            if self
                .derivative_rules
                .iter()
                .any(|r| r.extra(&field, &idx, &orders).is_some())
            {
                values.insert(x, self.derivative(&field, &idx, orders)?);
            }
        }
        substitute(p, &values).map_err(|_| Failure::OverBudget)
    }
}
