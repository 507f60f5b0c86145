//! What every scalar decision works with: the claim's exact environment and box, the
//! exact value of its function, and the few helpers the sign, monotonicity, limit and
//! roots decisions share.

use crate::algebra::certificate::Certificate;
use crate::algebra::sign::{Interval, Real, Sign};
use crate::algebra::{Quotient, RatFunc};
use crate::decide::finding::{Finding, RationalEvidence};
use crate::decide::outcome::{Method, Outcome};
use crate::derivation::{Check, Expression, ParamBox};
use crate::eval::exact::env::ExactEnv;
use crate::kernel::check::Fact;
use crate::kernel::{Poly, Rational, Var};
use crate::lang::{Decls, Diagnostic};
use crate::tolerance::SCALAR_AGREEMENT;
use num_traits::One;
use std::collections::BTreeMap;

/// Why a decision stopped early: bad input (exit 2), or an outcome already reached
/// (undecided at a resource limit).
pub(super) enum Stop {
    Input(Diagnostic),
    Outcome(Box<Outcome>),
}

impl From<Diagnostic> for Stop {
    fn from(d: Diagnostic) -> Self {
        Stop::Input(d)
    }
}

/// What every scalar decision works with.
pub(super) struct Context<'a> {
    pub(super) env: ExactEnv<'a>,
    pub(super) decls: &'a Decls,
    pub(super) check: &'a Check,
    pub(super) domain: &'a ParamBox,
    pub(super) samples: usize,
    pub(super) seed: u64,
}

/// An expression evaluated exactly: the reduced rational function, and every divisor
/// the expression was divided by on its way (cancelled or not), where it is undefined.
pub(super) struct Exact {
    pub(super) f: RatFunc,
    pub(super) conditions: Vec<Poly>,
}

impl Exact {
    /// Numerator and denominator of `f`, both multiplied by every divisor: their
    /// common roots are where the expression is undefined.
    pub(super) fn cleared(&self) -> (Poly, Poly) {
        let c = self.conditions.iter().fold(Poly::one(), |acc, p| &acc * p);
        (self.f.numerator() * &c, self.f.denominator() * &c)
    }

    /// The exact value at a point; `None` where the expression is undefined.
    pub(super) fn eval(&self, point: &BTreeMap<Var, Rational>) -> Option<Rational> {
        let at = |v: Var| point.get(&v).cloned().unwrap_or_else(|| Rational::int(0));
        for c in &self.conditions {
            if c.eval(&at)?.is_zero() {
                return None;
            }
        }
        self.f.eval(&at)
    }

    /// Every variable of the function and of its divisors, sorted.
    pub(super) fn variables(&self) -> Vec<Var> {
        let mut vars = variables(&self.f);
        vars.extend(self.conditions.iter().flat_map(Poly::variables));
        vars.sort_unstable();
        vars.dedup();
        vars
    }

    /// `self − other`, undefined where either is.
    pub(super) fn minus(&self, other: &Exact) -> Exact {
        Exact {
            f: &self.f - &other.f,
            conditions: self
                .conditions
                .iter()
                .chain(&other.conditions)
                .cloned()
                .collect(),
        }
    }
}

impl Context<'_> {
    /// The outcome of the kernel's check of `fact` about this claim on the box `domain`
    /// (the claim's own when `None`): the proof's verdict, or `undecided` with the
    /// kernel's reason for refusing what the search found.
    pub(super) fn by_kernel(&self, fact: Fact, domain: Option<&ParamBox>) -> Outcome {
        let statement = match crate::derivation::statement::scalar(
            self.decls,
            self.check,
            domain.unwrap_or(self.domain),
        ) {
            Ok(s) => s,
            Err(d) => {
                return Outcome::undecided(Method::RationalFunction, 0)
                    .with_finding(Finding::KernelRefused { why: d.message })
            }
        };
        match crate::kernel::check::check(statement, fact) {
            Ok(proof) => Outcome::proved(Method::RationalFunction, 1, proof),
            Err(why) => Outcome::undecided(Method::RationalFunction, 0).with_finding(
                Finding::KernelRefused {
                    why: why.to_string(),
                },
            ),
        }
    }

    /// A point for the kernel: every variable of the environment by name, the box's
    /// parameters inside it (see [`Context::complete`]), the others 0.
    pub(super) fn full_point(&self, point: &BTreeMap<Var, Rational>) -> Vec<(String, Rational)> {
        crate::decide::identity::full_point(&self.env, &self.complete(point))
    }

    /// A rational function in lowest terms by names, for the kernel to check against
    /// its own value.
    pub(super) fn reduced(&self, e: &Exact) -> crate::kernel::check::Reduced {
        use crate::kernel::statement::poly_data;
        (
            poly_data(e.f.numerator(), &self.env.vars),
            poly_data(e.f.denominator(), &self.env.vars),
        )
    }

    /// The square roots the evaluation took, for the kernel.
    pub(super) fn roots(&self) -> Vec<crate::kernel::statement::FracData> {
        self.env.root_data()
    }

    /// `e` evaluated exactly (a scalar, checked by the loader).
    pub(super) fn exact(&mut self, e: &Expression) -> Result<Exact, Stop> {
        let labeled = match self.env.eval(&e.node, &e.origin) {
            Ok(v) => v,
            Err(r) => {
                return Err(match Finding::of_refusal(&r) {
                    Some(f) => Stop::Outcome(Box::new(
                        Outcome::undecided(Method::RationalFunction, 0).with_finding(f),
                    )),
                    None => Stop::Input(r.into()),
                })
            }
        };
        let quotient = labeled.at(&[]).clone();
        let normal = self.env.normal_vars();
        if quotient.variables().iter().any(|v| normal.contains(v)) {
            return Err(Stop::Input(
                e.origin
                    .diagnostic(
                        e.node.span,
                        "a claim about a rational function of parameters cannot depend on the unit normal",
                    )
                    .with_help("average over the normal first, or use strategy = \"numeric\""),
            ));
        }
        // A divisor of one sign on the whole box never makes the expression undefined
        // there; dropping it keeps a function of one parameter univariate when a
        // square root divided by another (bounded) parameter.
        let names = &self.env.vars;
        let conditions = quotient
            .conditions()
            .iter()
            .filter(|c| {
                let f = RatFunc::from_poly(c);
                let on = self.box_on(&c.variables());
                ![Sign::Positive, Sign::Negative]
                    .into_iter()
                    .any(|s| Certificate::sign_by_coefficients(&f, &on, s, names).is_some())
            })
            .cloned()
            .collect();
        Ok(Exact {
            f: Quotient::to_ratfunc(&quotient),
            conditions,
        })
    }

    /// The variable of a declared scalar parameter (`None`: the function does not use it).
    pub(super) fn var(&self, name: &str) -> Option<Var> {
        self.env.vars.lookup(name)
    }

    pub(super) fn name(&self, v: Var) -> String {
        self.env.vars.name(v).to_owned()
    }

    /// The interval of a variable in the box (the real line when not bounded).
    pub(super) fn interval(&self, v: Var) -> Interval {
        self.domain.interval(self.env.vars.name(v))
    }

    /// The box on `vars`.
    pub(super) fn box_on(&self, vars: &[Var]) -> Vec<(Var, Interval)> {
        vars.iter().map(|&v| (v, self.interval(v))).collect()
    }

    /// A point as the reports show it.
    pub(super) fn shown(&self, point: &BTreeMap<Var, Rational>) -> BTreeMap<String, String> {
        self.complete(point)
            .iter()
            .map(|(&v, x)| (self.name(v), readable(x)))
            .collect()
    }

    /// The evidence skeleton: what was decided, on which box.
    pub(super) fn evidence(&self, decided: &RatFunc) -> RationalEvidence {
        RationalEvidence {
            decided: decided.display(&self.env.vars),
            domain: self.domain.describe(),
            points: Vec::new(),
            holds_on: None,
            limit: None,
            sampled: None,
        }
    }

    /// `e` by the floating-point interpreter at `point`.
    pub(super) fn interpret(
        &self,
        e: &Expression,
        point: &BTreeMap<Var, Rational>,
    ) -> Result<f64, crate::decide::reverify::NoValue> {
        let point = self.complete(point);
        crate::decide::reverify::interpret_scalar(
            self.decls, self.check, &self.env, &point, &e.node,
        )
    }

    /// `point` with every parameter of the box that it leaves out set inside the box:
    /// a parameter the function does not read can still decide the sign of a square
    /// root on the way (σ in √(f_r² σ²)), so the interpreter that confirms the point,
    /// and the reader, must take it from the box.
    /// `p` = c · q(v), with c free of `v` and of one strict sign on the box (μ in
    /// μ (x² − 1), with μ > 0; a nonzero constant): q, and whether c is negative.
    /// Such a factor changes neither the roots in `v` nor, up to its sign, the sign of
    /// `p`; the kernel divides it out again in its own one-variable reduction.
    pub(super) fn in_one_variable(&self, p: &Poly, v: Var) -> Option<(Poly, bool)> {
        let (content, rest) = crate::algebra::sturm::content_in(p, v)?;
        let bx = self.box_on(&content.variables());
        let c = RatFunc::from_poly(&content);
        [Sign::Positive, Sign::Negative]
            .into_iter()
            .find(|&s| Certificate::sign_by_coefficients(&c, &bx, s, &self.env.vars).is_some())
            .map(|s| (rest, s == Sign::Negative))
    }

    /// A rational function's numerator and denominator, each in `v` alone once a factor
    /// of one strict sign is divided out ([`Context::in_one_variable`]), the
    /// numerator carrying both factors' signs; `None` when another parameter occurs
    /// otherwise.
    pub(super) fn cleared_in(&self, (num, den): (Poly, Poly), v: Var) -> Option<(Poly, Poly)> {
        let (n, n_negative) = self.in_one_variable(&num, v)?;
        let (d, d_negative) = self.in_one_variable(&den, v)?;
        Some(if n_negative != d_negative {
            (-&n, d)
        } else {
            (n, d)
        })
    }

    pub(super) fn complete(&self, point: &BTreeMap<Var, Rational>) -> BTreeMap<Var, Rational> {
        let mut point = point.clone();
        for (name, i) in &self.domain.bounds {
            if let Some(v) = self.env.vars.lookup(name) {
                point
                    .entry(v)
                    .or_insert_with(|| crate::algebra::sign::inner_point(i));
            }
        }
        point
    }
}

/// The variables of a rational function, sorted.
pub(super) fn variables(f: &RatFunc) -> Vec<Var> {
    let mut vars = f.numerator().variables();
    vars.extend(f.denominator().variables());
    vars.sort_unstable();
    vars.dedup();
    vars
}

pub(super) fn agrees(float: f64, exact: &Rational) -> bool {
    let e = exact.to_f64();
    float.is_finite() && (float - e).abs() <= SCALAR_AGREEMENT * (1.0 + e.abs())
}

/// A rational as the reports show it: exact when short, else to ten digits.
pub(super) fn readable(x: &Rational) -> String {
    if x.bits() <= 48 {
        x.to_string()
    } else {
        format!("≈ {}", crate::digits::significant(x.to_f64(), 10))
    }
}

/// A real number as evidence writes it: exactly when rational, `≈ x` to ten
/// significant digits when an isolated irrational root.
pub(super) fn shown_real(x: &Real) -> String {
    match x {
        Real::Exact(q) => q.to_string(),
        Real::Isolated { .. } => format!("≈ {}", crate::digits::significant(x.approx(), 10)),
    }
}

/// "name = x" for an exact number, "name ≈ x" for an isolated irrational one.
pub(super) fn equated(x: &Real, name: &str) -> String {
    let equals = if matches!(x, Real::Exact(_)) {
        "= "
    } else {
        ""
    };
    format!("{name} {equals}{}", shown_real(x))
}
