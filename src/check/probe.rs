//! One expression evaluated in the context of a derivation file, outside any claim: what
//! `plot` draws and what the cross-checks in `tests/` compare with an independent route.
//!
//! The expression is read as the side of a claim appended to the file, with the
//! file's declarations, definitions and assumptions plus the probe's own, so it means
//! exactly what it would mean in a claim: the same states, the same square-root signs
//! on the same box (`given`), the same arithmetic.

use crate::algebra::RatFunc;
use crate::derivation::{load_str, Check, Curve, DerivationFile, Grid, LoadError};
use crate::eval::exact::env::ExactEnv;
use crate::kernel::{Rational, Var, VarTable};
use crate::lang::{Decls, Diagnostic};
use std::collections::BTreeMap;
use std::sync::Arc;

/// The id of the claim a probe appends; a file that uses it cannot be probed.
const PROBE_ID: &str = "cosserat-check-probe";

/// A scalar expression read in a file's context.
pub struct Probe {
    decls: Arc<Decls>,
    check: Check,
}

/// A TOML basic string holding `s`.
fn toml_string(s: &str) -> String {
    toml::Value::String(s.to_owned()).to_string()
}

fn toml_list(items: &[String]) -> String {
    let items: Vec<String> = items.iter().map(|s| toml_string(s)).collect();
    format!("[{}]", items.join(", "))
}

impl Probe {
    /// `expression` in the context of the file `text` (named `label` in errors), with
    /// the extra assumptions `assume` (e.g. `"u = 1"`) and the box `given` (e.g.
    /// `"sig < 0"`). Errors point into the file, or into the probe's own text.
    pub fn new(
        label: &str,
        text: &str,
        expression: &str,
        assume: &[String],
        given: &[String],
    ) -> Result<Self, LoadError> {
        Probe::of_each(label, text, &[expression], assume, given)
    }

    /// Several expressions in one context, as [`Probe::new`]: [`Probe::exact_each`]
    /// derives the definitions they share once (D^(ep) for the four A² of the
    /// Appendix), as a derivation by hand would. [`Probe::exact`] and [`Probe::at`]
    /// read the first.
    pub fn of_each(
        label: &str,
        text: &str,
        expressions: &[&str],
        assume: &[String],
        given: &[String],
    ) -> Result<Self, LoadError> {
        let chains: Vec<String> = expressions
            .iter()
            .map(|e| format!("[{}, \"0\"]", toml_string(e)))
            .collect();
        let claim = format!(
            "\n\n[[claim]]\nid = {}\nprinted = 'probe'\nexpect = \"holds\"\nassume = {}\ngiven = {}\nchains = [{}]\n",
            toml_string(PROBE_ID),
            toml_list(assume),
            toml_list(given),
            chains.join(", "),
        );
        let file: DerivationFile = load_str(label, &format!("{text}{claim}"))?;
        let claim = file
            .claims
            .into_iter()
            .find(|c| c.id == PROBE_ID)
            .expect("the appended claim is loaded");
        Ok(Probe {
            decls: claim.decls,
            check: claim.check,
        })
    }

    fn node(&self) -> &crate::derivation::Side {
        &self.check.chains[0][0]
    }

    fn env(&self) -> Result<ExactEnv<'_>, Diagnostic> {
        Ok(ExactEnv::on(
            &self.decls,
            &self.check.defs,
            &self.check.assumptions,
            self.check.strategy.exact_domain(),
        )?)
    }

    /// The (first) expression as a reduced rational function of the parameters it
    /// still depends on, with their names.
    pub fn exact(&self) -> Result<(RatFunc, VarTable), Diagnostic> {
        let mut env = self.env()?;
        let f = exact_side(&mut env, self.node())?;
        Ok((f, env.vars.clone()))
    }

    /// Every expression as a reduced rational function, in order, evaluated in one
    /// environment: a definition they share is derived once. The names are those of
    /// the whole evaluation (numbered by first use across the expressions, so a
    /// result may print its terms in another order than [`Probe::exact`] alone).
    pub fn exact_each(&self) -> Result<(Vec<RatFunc>, VarTable), Diagnostic> {
        let mut env = self.env()?;
        let each = self
            .check
            .chains
            .iter()
            .map(|chain| exact_side(&mut env, &chain[0]))
            .collect::<Result<_, _>>()?;
        Ok((each, env.vars.clone()))
    }

    /// The expression in floating point at the parameter values `at` (by name), by
    /// the interpreter: num-dual gradients, `f64` matrices and square roots, so a
    /// second route to [`Probe::exact`]. Parameters it does not name are 0.
    pub fn at(&self, at: &[(&str, f64)]) -> Result<f64, ProbeError> {
        let side = self.node();
        let node = side
            .node
            .as_ref()
            .map_err(|e| ProbeError::Side(side.origin.diagnostic(e.span, e.message.clone())))?;
        let mut env = self.env()?;
        let mut point: BTreeMap<Var, Rational> = BTreeMap::new();
        for (name, x) in at {
            let v = env.vars.intern(name);
            let q = crate::algebra::rational::from_f64_exact(*x).ok_or_else(|| {
                ProbeError::NotFinite {
                    name: (*name).to_owned(),
                    value: *x,
                }
            })?;
            point.insert(v, q);
        }
        Ok(crate::decide::reverify::interpret_scalar(
            &self.decls,
            &self.check,
            &env,
            &point,
            node,
        )?)
    }
}

/// A scalar side as a reduced rational function in `env`.
fn exact_side(
    env: &mut ExactEnv<'_>,
    side: &crate::derivation::Side,
) -> Result<RatFunc, Diagnostic> {
    let node = side
        .node
        .as_ref()
        .map_err(|e| side.origin.diagnostic(e.span, e.message.clone()))?;
    let value = env.eval(node, &side.origin).map_err(Diagnostic::from)?;
    Ok(value.at(&[]).to_ratfunc())
}

/// Why a probe or a curve has no value.
#[derive(Debug, thiserror::Error)]
pub enum ProbeError {
    /// The file the expression is read in is malformed.
    #[error("{0}")]
    Input(#[from] Diagnostic),
    /// The expression is malformed.
    #[error("{}", .0.message)]
    Side(Diagnostic),
    #[error("{0}")]
    NoValue(#[from] crate::decide::reverify::NoValue),
    #[error("{name} = {value} is not finite")]
    NotFinite { name: String, value: f64 },
    #[error("`{curve}` is not a number at {grid} = {value}: it reads a parameter that is neither {grid} nor fixed; give it with --set NAME=VALUE")]
    Unfixed {
        curve: String,
        grid: String,
        value: String,
    },
}

/// A curve's values on its grid: `None` where the curve is undefined (a square root of
/// a negative number, a pole), with the first reason. An error when a value depends on
/// a parameter that is neither the grid's nor fixed by an assumption.
pub fn curve_values(
    curve: &Curve,
    grid: &Grid,
) -> Result<(Vec<Option<f64>>, Option<String>), ProbeError> {
    let mut env = ExactEnv::on(
        &curve.decls,
        &curve.check.defs,
        &curve.check.assumptions,
        curve.check.strategy.exact_domain(),
    )
    .map_err(Diagnostic::from)?;
    let side = &curve.check.chains[0][0];
    let node = side
        .node
        .as_ref()
        .map_err(|e| ProbeError::Side(side.origin.diagnostic(e.span, e.message.clone())))?;
    let x = env.vars.intern(&grid.name);
    let mut first_gap = None;
    let mut values = Vec::with_capacity(grid.values.len());
    for value in &grid.values {
        let point = BTreeMap::from([(x, value.clone())]);
        match crate::decide::reverify::interpret_with(
            &curve.decls,
            &curve.check,
            &env,
            &point,
            node,
            f64::NAN,
        ) {
            Ok(y) if y.is_finite() => values.push(Some(y)),
            Ok(_) => {
                return Err(ProbeError::Unfixed {
                    curve: curve.text.clone(),
                    grid: grid.name.clone(),
                    value: value.to_string(),
                })
            }
            Err(why) => {
                first_gap.get_or_insert_with(|| format!("{} = {value}: {why}", grid.name));
                values.push(None);
            }
        }
    }
    Ok((values, first_gap))
}
