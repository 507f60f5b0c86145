//! One expression evaluated in the context of a derivation file, outside any claim: what
//! `plot` draws and what the cross-checks in `tests/` compare with an independent route.
//!
//! The expression is read as the side of a claim appended to the file, with the
//! file's declarations, definitions and assumptions plus the probe's own, so it means
//! exactly what it would mean in a claim: the same states, the same square-root signs
//! on the same box (`given`), the same arithmetic.

use super::eval::ExactEnv;
use crate::derivation::{load_str, Check, DerivationFile, LoadError};
use crate::kernel::{Quotient, RatFunc, Rational, Var, VarTable};
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
        let claim = format!(
            "\n\n[[claim]]\nid = {}\nprinted = 'probe'\nexpect = \"holds\"\nassume = {}\ngiven = {}\nsides = [{}, \"0\"]\n",
            toml_string(PROBE_ID),
            toml_list(assume),
            toml_list(given),
            toml_string(expression),
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
        let mut env = ExactEnv::new(&self.decls, &self.check.defs, &self.check.assumptions)?;
        if let Some(domain) = self.check.strategy.exact_domain() {
            env.set_domain(domain);
        }
        Ok(env)
    }

    /// The expression as a reduced rational function of the parameters it still
    /// depends on, with their names.
    pub fn exact(&self) -> Result<(RatFunc, VarTable), Diagnostic> {
        let side = self.node();
        let node = side
            .node
            .as_ref()
            .map_err(|e| side.origin.diagnostic(e.span, e.message.clone()))?;
        let mut env = self.env()?;
        let value = env.eval(node, &side.origin).map_err(Diagnostic::from)?;
        let q: Quotient = value.at(&[]).clone();
        Ok((Quotient::to_ratfunc(&q), env.vars.clone()))
    }

    /// The expression in floating point at the parameter values `at` (by name), by
    /// the interpreter: num-dual gradients, `f64` matrices and square roots, so a
    /// second route to [`Probe::exact`]. Parameters it does not name are 0.
    pub fn at(&self, at: &[(&str, f64)]) -> Result<f64, String> {
        let side = self.node();
        let node = side.node.as_ref().map_err(|e| e.message.clone())?;
        let mut env = self.env().map_err(|d| d.to_string())?;
        let mut point: BTreeMap<Var, Rational> = BTreeMap::new();
        for (name, x) in at {
            let v = env.vars.intern(name);
            let q = Rational::from_f64_exact(*x)
                .ok_or_else(|| format!("{name} = {x} is not finite"))?;
            point.insert(v, q);
        }
        super::reverify::interpret_scalar(&self.decls, &self.check, &env, &point, node)
    }
}
