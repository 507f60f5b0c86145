//! The algebra's own certificates: what the search checks, in its own fast
//! arithmetic, before it asks the kernel for a proof. A certificate here decides
//! which fact to hand the kernel (`kernel::check`), never a verdict: the kernel
//! re-runs every fact against the claim's statement, and only its proof makes a
//! verdict of strength `proof`.

use super::indexed::{first_difference, Canonical, Label};
use super::limit::{self, Approach, Expansion, Limit};
use super::linear::determinant;
use super::quotient::{cleared_difference, over, Quotient};
use super::ratfunc::RatFunc;
use super::sign::{self, Interval, Sign, Violation};
use crate::kernel::poly::{Poly, PolyError, Var, VarTable};
use crate::kernel::Rational;
use serde::Serialize;

/// One fact the algebra verified.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Fact {
    /// Both sides reduced to the same canonical form in symbolic indices (δ
    /// contracted, ε pairs and isotropic moments as δ's, summed indices renamed):
    /// equal for every value of the free indices `free` at once.
    /// When the forms differ only by δ's and ε's, `evaluated` counts the index values
    /// at which their difference was evaluated exactly and found 0 (δ products are
    /// linearly dependent at high rank); 0 when the forms are identical.
    IndexIdentity {
        free: String,
        terms: usize,
        modulo_unit_normal: bool,
        evaluated: usize,
    },
    /// Four rational points lie on no common circle or line:
    /// det[x²+y², x, y, 1] ≠ 0.
    NotConcyclic { determinant: String },
    /// A rational function of one variable has the stated sign on an interval wherever
    /// it is defined: the real roots of numerator · denominator isolated (Sturm), the
    /// sign exact at a rational point of each piece between them and at closed ends.
    SignOnInterval {
        interval: String,
        relation: String,
        pieces: usize,
        /// Poles inside the interval, where the function is undefined.
        poles: usize,
    },
    /// A rational function of several variables has the stated sign on a box: after
    /// moving every variable onto t ≥ 0, numerator and denominator have coefficients
    /// of one sign (one case per sign of each unbounded variable).
    CoefficientSigns { substitution: String, cases: usize },
    /// The real roots of a rational function of one variable on an interval are
    /// exactly the listed rationals (Sturm isolation of every root).
    Roots {
        interval: String,
        roots: Vec<String>,
    },
    /// √radicand = root: root·root equals the radicand (denominators cleared,
    /// canonical polynomials), and root ≥ 0 on the box by the coefficient signs
    /// that follow ([`Fact::CoefficientSigns`]), or root is a nonnegative rational.
    SquareRoot {
        radicand: String,
        root: String,
        /// The box the sign was certified on (`given`), in words.
        on: String,
    },
    /// The limit of a rational function, from the lowest orders of numerator and
    /// denominator, wherever the listed polynomials are nonzero.
    Limit {
        variable: String,
        to: String,
        value: String,
        #[serde(skip_serializing_if = "Vec::is_empty")]
        nonzero: Vec<String>,
    },
}

/// Facts verified by the kernel; a conjunction when there are several.
///
/// Outside this module a certificate cannot be written down, only obtained from the
/// functions that verify it:
///
/// ```compile_fail
/// use cosserat_algebra::certificate::{Certificate, Fact};
/// let forged = Certificate { facts: vec![Fact::RationalFunctionIdentity] };
/// ```
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Certificate {
    facts: Vec<Fact>,
}

impl Certificate {
    /// What the kernel verified.
    pub fn facts(&self) -> &[Fact] {
        &self.facts
    }

    /// The conjunction of two certificates.
    pub fn and(mut self, other: Certificate) -> Certificate {
        self.facts.extend(other.facts);
        self
    }

    fn of(fact: Fact) -> Self {
        Certificate { facts: vec![fact] }
    }

    /// `a = b` as canonical forms in symbolic indices ([`super::indexed`]), or forms
    /// that differ by δ's and ε's alone with the difference 0 at every value of the
    /// free indices `free` (their labels are `labels`).
    pub fn index_identity(
        a: &Canonical,
        b: &Canonical,
        (free, labels): (&str, &[Label]),
        dim: usize,
    ) -> Option<Self> {
        let evaluated = if a == b {
            0
        } else {
            match first_difference(a, b, labels, dim)? {
                Some(_) => return None,
                None => dim.checked_pow(labels.len() as u32)?,
            }
        };
        Some(Self::of(Fact::IndexIdentity {
            free: free.to_owned(),
            terms: a.len(),
            modulo_unit_normal: a.used_unit_normal() || b.used_unit_normal(),
            evaluated,
        }))
    }

    /// Four rational points on no common circle or line.
    pub fn not_concyclic(points: &[(Rational, Rational); 4]) -> Option<Self> {
        let rows = points
            .iter()
            .map(|(a, b)| vec![&(a * a) + &(b * b), a.clone(), b.clone(), Rational::int(1)])
            .collect();
        let det = determinant(rows);
        (!det.is_zero()).then(|| {
            Self::of(Fact::NotConcyclic {
                determinant: det.to_string(),
            })
        })
    }

    /// `num / den` (polynomials in `v` alone, not necessarily coprime: a common factor
    /// is a point where the expression is undefined) satisfies `want` on `interval`
    /// wherever it is defined. `Err` carries where it does not (`None`: `f` is not a function
    /// of `v` alone, or the interval is empty).
    pub fn sign_on_interval(
        (num, den): (&Poly, &Poly),
        v: Var,
        interval: &Interval,
        want: Sign,
        names: &VarTable,
    ) -> Result<Self, Option<Box<Violation>>> {
        let chart = sign::chart_of((num, den), v, interval).ok_or(None)?;
        match chart.violation(want) {
            Some(v) => Err(Some(Box::new(v))),
            None => Ok(Self::of(Fact::SignOnInterval {
                interval: interval.describe(names.name(v)),
                relation: want.relation().to_owned(),
                pieces: chart.pieces.len(),
                poles: chart.poles(),
            })),
        }
    }

    /// The zeros of `num / den` (polynomials in `v` alone; common roots are undefined
    /// points, not zeros) on `interval` are exactly `roots`. `Err` carries the zeros
    /// found, or `None` when there is no sign chart to read them from (`num / den` is
    /// not a function of `v` alone, the interval is empty, or the roots could not be
    /// isolated).
    pub fn roots_exactly(
        (num, den): (&Poly, &Poly),
        v: Var,
        interval: &Interval,
        roots: &[Rational],
        names: &VarTable,
    ) -> Result<Self, Option<Vec<sign::Real>>> {
        let chart = sign::chart_of((num, den), v, interval).ok_or(None)?;
        let zeros = chart.zeros();
        let mut stated: Vec<&Rational> = roots.iter().collect();
        stated.sort();
        stated.dedup();
        let exact = zeros.len() == stated.len()
            && zeros
                .iter()
                .zip(&stated)
                .all(|(z, r)| *z == sign::Real::Exact((*r).clone()));
        if !exact {
            return Err(Some(zeros));
        }
        Ok(Self::of(Fact::Roots {
            interval: interval.describe(names.name(v)),
            roots: stated.iter().map(ToString::to_string).collect(),
        }))
    }

    /// `f` satisfies `want` on the box `domain` (an interval per variable; variables
    /// of `f` not listed range over the real line), certified when every variable can
    /// be moved onto t ≥ 0 so that numerator and denominator have coefficients of one
    /// sign. `None`: no such certificate (which says nothing about the claim).
    pub fn sign_by_coefficients(
        f: &RatFunc,
        domain: &[(Var, Interval)],
        want: Sign,
        names: &VarTable,
    ) -> Option<Self> {
        let (cases, substitution) = sign::orthant_cases(f, domain, names)?;
        let count = cases.len();
        for (g, closed) in cases {
            let n = sign::coefficient_sign(g.numerator(), &closed)?;
            let d = sign::coefficient_sign(g.denominator(), &closed)?;
            // The denominator's zeros are poles; only its sign matters.
            let value = n.sign * d.sign;
            let admitted = if want.admits(0) {
                want.admits(value)
            } else {
                want.admits(value) && n.nonzero_on_closed
            };
            if !admitted {
                return None;
            }
        }
        Some(Self::of(Fact::CoefficientSigns {
            substitution,
            cases: count,
        }))
    }

    /// √radicand = root on the box `domain` (variables not listed range over the real
    /// line): root·root is the radicand wherever both are defined, and root ≥ 0 on the
    /// box, certified by coefficient signs ([`Certificate::sign_by_coefficients`]).
    /// `None`: not verified, which says nothing about the radicand.
    pub fn square_root(
        radicand: &Quotient,
        root: &Quotient,
        domain: &[(Var, Interval)],
        names: &VarTable,
    ) -> Option<Self> {
        use super::einsum::Arithmetic;
        let mut work = super::quotient::CLEARING_WORK;
        let square = super::quotient::Quotients {
            work_left: &mut work,
        }
        .mul(root.clone(), root)
        .ok()?;
        let (difference, _) = cleared_difference(&square, radicand)?;
        if !difference.is_zero() {
            return None;
        }
        let sign = match root.as_constant() {
            Some(c) if !c.is_negative() => None,
            Some(_) => return None,
            None => Some(Self::sign_by_coefficients(
                &root.to_ratfunc(),
                domain,
                Sign::NonNegative,
                names,
            )?),
        };
        let on: Vec<String> = domain
            .iter()
            .map(|(v, i)| i.describe(names.name(*v)))
            .collect();
        let fact = Self::of(Fact::SquareRoot {
            radicand: radicand.display_truncated(names, 8),
            root: root.display_truncated(names, 8),
            on: if on.is_empty() {
                "every real value".to_owned()
            } else {
                on.join(", ")
            },
        });
        Some(match sign {
            Some(s) => fact.and(s),
            None => fact,
        })
    }

    /// `lim f = claimed` as `v` tends to `to`, wherever the expansion's conditions
    /// hold. `Err` carries the expansion when the limit differs (or is infinite).
    pub fn limit(
        f: &RatFunc,
        v: Var,
        to: &Approach,
        claimed: &RatFunc,
        names: &VarTable,
    ) -> Result<Self, Option<Expansion>> {
        let e = limit::expand(f, v, to).ok_or(None)?;
        match &e.limit {
            Limit::Finite(value) if value == claimed => Ok(Self::of(Fact::Limit {
                variable: names.name(v).to_owned(),
                to: to.to_string(),
                value: value.display(names),
                nonzero: e.nonzero.iter().map(|p| p.display(names)).collect(),
            })),
            _ => Err(Some(e)),
        }
    }

    /// `|f| → ∞` as `v` tends to `to`, with the sign of the returned rational function
    /// (the caller decides that sign), wherever the expansion's conditions hold.
    pub fn diverges(
        f: &RatFunc,
        v: Var,
        to: &Approach,
        names: &VarTable,
    ) -> Result<(Self, Option<RatFunc>), Option<Expansion>> {
        let e = limit::expand(f, v, to).ok_or(None)?;
        let sign_of = match &e.limit {
            Limit::Infinite { sign_of } => Some(sign_of.clone()),
            Limit::InfiniteBothSigns => None,
            Limit::Finite(_) => return Err(Some(e)),
        };
        let value = match &sign_of {
            Some(s) => format!("∞ with the sign of {}", s.display(names)),
            None => "∞ in absolute value, with opposite signs on the two sides".to_owned(),
        };
        Ok((
            Self::of(Fact::Limit {
                variable: names.name(v).to_owned(),
                to: to.to_string(),
                value,
                nonzero: e.nonzero.iter().map(|p| p.display(names)).collect(),
            }),
            sign_of,
        ))
    }
}

/// The difference of two sides that are not identical: `numerator / Π factor^k`, the
/// numerator reduced modulo n·n = 1.
#[derive(Clone, Debug, PartialEq)]
pub struct Difference {
    pub numerator: Poly,
    pub denominator: Vec<(Poly, u32)>,
}

impl Difference {
    /// Plain text, at most `max_terms` terms of the numerator.
    pub fn display(&self, names: &VarTable, max_terms: usize) -> String {
        over(&self.numerator, &self.denominator, names, max_terms)
    }
}

/// Component-by-component comparison of canonical polynomials, certified only when
/// every comparison made was an identity. Quotients are compared with their
/// denominators cleared: `a/A = b/B` wherever A, B ≠ 0 exactly when the numerator of
/// `a/A − b/B` over the least common multiple is the zero polynomial, and the
/// certificate lists the factors that must not vanish.
///
/// ```
/// use cosserat_algebra::certificate::Identities;
/// use cosserat_kernel::{Poly, Rational, VarTable};
/// use cosserat_algebra::Quotient;
/// let mut names = VarTable::new();
/// let x = Quotient::from(Poly::var(names.intern("x")));
/// let two_x = Quotient::from(&Poly::constant(Rational::int(2)) * x.numerator());
/// let mut check = Identities::new(&[]);
/// assert_eq!(check.compare(&two_x, &two_x.clone()), Ok(None));
/// let one = Quotient::from(Poly::constant(Rational::int(1)));
/// assert!(check.compare(&x, &one).unwrap().is_some(), "a difference");
/// assert_eq!(check.components(), 2);
/// ```
#[derive(Debug)]
pub struct Identities<'n> {
    normal: &'n [Var],
    components: usize,
    modulo_unit_normal: usize,
    /// Compare `lhs` with `factor · rhs` (a proportionality with this nonzero factor,
    /// a constant or a rational function of the parameters).
    factor: Option<RatFunc>,
    /// The polynomial constraints, solved for powers: differences are reduced by them.
    rules: Vec<crate::kernel::rules::Rule>,
}

/// `q · f` for a nonzero rational function `f`: the numerator times f's numerator,
/// divided by f's denominator (which joins the conditions where it is not constant).
pub fn scaled_by(q: &Quotient, f: &RatFunc) -> Quotient {
    let scaled = q.with_numerator(q.numerator() * f.numerator());
    match f.denominator().as_constant() {
        Some(c) if c.is_one() => scaled,
        _ => scaled
            .divide(&Quotient::from(f.denominator().clone()))
            .expect("the denominator of a rational function is nonzero"),
    }
}

impl<'n> Identities<'n> {
    /// A comparison modulo n·n = 1 for the given normal's variables (none: plain
    /// polynomial identity).
    pub fn new(normal: &'n [Var]) -> Self {
        Identities {
            normal,
            components: 0,
            modulo_unit_normal: 0,
            factor: None,
            rules: Vec::new(),
        }
    }

    /// The same comparison modulo polynomial constraints, solved for powers
    /// ([`crate::kernel::rules`]).
    pub fn with_rules(mut self, rules: &[crate::kernel::rules::Rule]) -> Self {
        self.set_rules(rules);
        self
    }

    /// The rules to reduce by from now on (square roots taken as variables join them
    /// while the sides are evaluated).
    pub fn set_rules(&mut self, rules: &[crate::kernel::rules::Rule]) {
        if self.rules.len() != rules.len() {
            self.rules = rules.to_vec();
        }
    }

    /// A comparison of `lhs` with `factor · rhs`. Which factor to try is the caller's
    /// guess (a zero factor finds where the left side is not zero); the kernel verifies
    /// the identities it implies, and that the factor is nonzero.
    pub fn proportional(normal: &'n [Var], factor: &RatFunc) -> Self {
        Identities {
            factor: Some(factor.clone()),
            ..Identities::new(normal)
        }
    }

    /// Compares one component: `None` when the sides are identical (modulo n·n = 1)
    /// wherever their denominators are nonzero, else their difference: its numerator
    /// over the common denominator, reduced. A denominator must not contain the normal.
    pub fn compare(
        &mut self,
        lhs: &Quotient,
        rhs: &Quotient,
    ) -> Result<Option<Difference>, PolyError> {
        let scaled;
        let rhs = match &self.factor {
            Some(f) => {
                scaled = scaled_by(rhs, f);
                &scaled
            }
            None => rhs,
        };
        let (raw, factors) = cleared_difference(lhs, rhs).ok_or(PolyError::TooLarge)?;
        if factors
            .iter()
            .flat_map(|(f, _)| f.terms())
            .any(|(m, _)| self.normal.iter().any(|&v| m.exponent(v) != 0))
        {
            return Err(PolyError::NegativeNormalPower);
        }
        let on_sphere = raw.reduce_on_sphere(self.normal)?;
        let diff =
            crate::kernel::rules::reduce(&on_sphere, &self.rules, crate::kernel::eval::RULE_STEPS)?;
        self.components += 1;
        if diff.is_zero() {
            self.modulo_unit_normal += usize::from(raw != on_sphere);
            Ok(None)
        } else {
            Ok(Some(Difference {
                numerator: diff,
                denominator: factors,
            }))
        }
    }

    /// Whether some identity needed n·n = 1.
    pub fn used_unit_normal(&self) -> bool {
        self.modulo_unit_normal > 0
    }

    /// How many components were compared.
    pub fn components(&self) -> usize {
        self.components
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::VarTable;

    fn q(n: i64, d: i64) -> Rational {
        Rational::ratio(n, d).unwrap()
    }

    #[test]
    fn identities_modulo_the_unit_normal() {
        let mut names = VarTable::new();
        let n1 = names.intern("n_1");
        let n2 = names.intern("n_2");
        let (a, b) = (Poly::var(n1), Poly::var(n2));
        let one = Quotient::from(Poly::constant(Rational::int(1)));
        let square = Quotient::from(&(&a * &a) + &(&b * &b));
        let mut plain = Identities::new(&[]);
        assert!(plain.compare(&square, &one).unwrap().is_some());
        let normal = [n1, n2];
        let mut on_sphere = Identities::new(&normal);
        assert_eq!(on_sphere.compare(&square, &one), Ok(None));
        assert!(on_sphere.used_unit_normal());
        assert_eq!(on_sphere.components(), 1);
        // A denominator with the normal in it is refused: the reduction on the sphere
        // would not be canonical for the quotient.
        let over = one
            .divide(&Quotient::from(&a + &one.numerator().clone()))
            .unwrap();
        assert_eq!(
            Identities::new(&normal).compare(&over, &one),
            Err(PolyError::NegativeNormalPower)
        );
    }

    #[test]
    fn quotients_are_compared_with_denominators_cleared() {
        let mut names = VarTable::new();
        let l = Poly::var(names.intern("lambda"));
        let g = Poly::var(names.intern("G"));
        let c = |k: i64| Poly::constant(Rational::int(k));
        // E = G (3λ + 2G)/(λ + G) and ν = λ / (2(λ + G)) give E / (2(1 + ν)) = G.
        let lg = Quotient::from(&l + &g);
        let e = Quotient::from(&g * &(&(&c(3) * &l) + &(&c(2) * &g)))
            .divide(&lg)
            .unwrap();
        let nu = Quotient::from(l.clone())
            .divide(&Quotient::from(&c(2) * &(&l + &g)))
            .unwrap();
        let mut work = 10_000;
        let mut ring = crate::quotient::Quotients {
            work_left: &mut work,
        };
        use crate::einsum::Arithmetic;
        let one_plus_nu = ring.add(Quotient::from(c(1)), nu).unwrap();
        let two = Quotient::from(c(2));
        let g_again = e.divide(&ring.mul(two, &one_plus_nu).unwrap()).unwrap();
        let mut check = Identities::new(&[]);
        assert_eq!(
            check.compare(&g_again, &Quotient::from(g.clone())),
            Ok(None)
        );
        // G again, with every divisor on the way kept as a condition: both cancelled.
        assert_eq!(g_again.as_poly(), Some(&g));
        let shown: Vec<String> = g_again
            .conditions()
            .iter()
            .map(|c| c.display(&names))
            .collect();
        assert_eq!(shown.len(), 2, "{shown:?}");
        // A wrong Poisson ratio: λ/(λ + G) makes the difference nonzero.
        let wrong = Quotient::from(l.clone()).divide(&lg).unwrap();
        let mut check = Identities::new(&[]);
        let diff = check.compare(&wrong, &nu_of(&l, &g)).unwrap().unwrap();
        assert!(!diff.numerator.is_zero());
        assert_eq!(diff.denominator.len(), 1, "over lambda + G alone");
    }

    fn nu_of(l: &Poly, g: &Poly) -> Quotient {
        Quotient::from(l.clone())
            .divide(&Quotient::from(
                &Poly::constant(Rational::int(2)) * &(l + g),
            ))
            .unwrap()
    }

    #[test]
    fn four_points_on_a_circle_are_not_a_witness() {
        // Four points of the unit circle are concyclic; move one off it.
        let on = |n: i64, d: i64| {
            let u = q(n, d);
            let s = &(&u * &u) + &q(1, 1);
            (
                (&q(1, 1) - &(&u * &u)).checked_div(&s).unwrap(),
                (&q(2, 1) * &u).checked_div(&s).unwrap(),
            )
        };
        let mut pts = [on(0, 1), on(1, 2), on(2, 1), on(-1, 3)];
        assert!(Certificate::not_concyclic(&pts).is_none());
        pts[3] = (q(2, 1), q(0, 1));
        assert!(Certificate::not_concyclic(&pts).is_some());
    }
}
