//! Reading a claim's decision procedure (`strategy = …` and its fields) into a
//! [`Strategy`], with every expression checked against the claim's scope.

use super::load::Loader;
use super::model::{
    Constraint, Definition, Expression, GradientConvention, Relation, Sampling, Strategy,
};
use super::raw::{RawClaim, S};
use super::spans::sub_origin;
use crate::lang::check::letters;
use crate::lang::{parse_expr, Decls, DefSig, Diagnostic, NodeKind, Scope, Span};
use std::collections::BTreeMap;

/// Default and smallest sample counts. Fewer than 50 random states would let a
/// statement that fails on a small part of the domain pass too easily.
pub const DEFAULT_SAMPLES: usize = 200;
pub const MIN_SAMPLES: usize = 50;

const STRATEGIES: &str =
    "exact, proportional, numeric, gradient, convex, not-circle, sign, monotone, limit, roots or stationary";

impl Loader {
    /// The strategy of a claim; `defs` are the claim's visible definitions.
    pub(super) fn strategy(
        &self,
        c: &RawClaim,
        decls: &Decls,
        defs: &[Definition],
    ) -> Result<Strategy, Diagnostic> {
        let sigs: Vec<DefSig> = defs.iter().map(|d| d.sig.clone()).collect();
        let name = c
            .strategy
            .as_ref()
            .map_or("exact", |s| s.get_ref().as_str());
        let anchor = c.strategy.as_ref().unwrap_or(&c.id);
        let need = |field: &Option<S>, what: &str| -> Result<S, Diagnostic> {
            field.clone().ok_or_else(|| {
                self.diag(
                    anchor.span(),
                    format!("strategy = \"{name}\" needs `{what}`"),
                )
                .with_help("see `cosserat-check guide`, section \"Derivation files\"")
            })
        };
        let scalar = |s: &S| self.expression(s, decls, &sigs, &[]);
        if let (Some(text), false) = (&c.relation, matches!(name, "numeric" | "sign")) {
            return Err(self
                .diag(
                    text.span(),
                    "`relation` applies to strategy = \"numeric\" or \"sign\" only",
                )
                .with_help(
                    "exact and proportional claims compare their sides as equations; remove it, or use strategy = \"numeric\"",
                ));
        }
        let scalar_only = [
            c.variable.as_ref().map(|s| ("in", s.span())),
            c.direction.as_ref().map(|s| ("direction", s.span())),
            c.tends_to.as_ref().map(|s| ("tends_to", s.span())),
            c.limit.as_ref().map(|s| ("limit", s.span())),
            c.count.as_ref().map(|s| ("count", s.span())),
            c.exactly_when.as_ref().map(|s| ("exactly_when", s.span())),
            c.roots.as_ref().map(|_| ("roots", anchor.span())),
            c.at.as_ref().map(|s| ("at", s.span())),
            c.kind.as_ref().map(|s| ("kind", s.span())),
        ];
        let scalar_kind = matches!(name, "sign" | "monotone" | "limit" | "roots" | "stationary");
        if let (Some((field, at)), false) = (scalar_only.into_iter().flatten().next(), scalar_kind)
        {
            return Err(self
                .diag(at, format!("`{field}` does not apply to strategy = \"{name}\""))
                .with_help("it belongs to the claims about rational functions (strategy = \"sign\", \"monotone\", \"limit\", \"roots\" or \"stationary\")"));
        }
        if let (Some(text), false) = (&c.convention, name == "gradient") {
            return Err(self
                .diag(
                    text.span(),
                    "`convention` applies to strategy = \"gradient\" only",
                )
                .with_help("remove it, or use strategy = \"gradient\""));
        }
        Ok(match name {
            "exact" | "proportional" => {
                let sampled = [
                    c.samples.as_ref().map(|_| "samples"),
                    c.seed.as_ref().map(|_| "seed"),
                    (!c.ranges.is_empty()).then_some("ranges"),
                    c.singular.as_ref().map(|_| "singular"),
                    (!c.domain.is_empty()).then_some("domain"),
                ];
                if let Some(field) = sampled.into_iter().flatten().next() {
                    return Err(self
                        .diag(anchor.span(), format!("`{field}` belongs to the sampled strategies; strategy = \"{name}\" decides exactly"))
                        .with_help("remove it, or bound the parameters of an exact claim with given = [\"f_r > 0\"]"));
                }
                // An entry that bounds no declared scalar by rationals is a hypothesis
                // of an identity (`J2 > 0`); elsewhere it is refused as a bound.
                let mut bounds = Vec::new();
                let mut hypotheses = Vec::new();
                for g in &c.given {
                    if name == "exact" && self.param_box(std::slice::from_ref(g), decls).is_err() {
                        if let Ok(h) = self.hypotheses(g, decls, &sigs) {
                            use super::reads::varies_with;
                            if h.iter()
                                .flat_map(|h| [&h.left, &h.right])
                                .any(|n| varies_with(n, defs, decls).is_some())
                            {
                                return Err(self
                                    .diag(g.span(), "a hypothesis bounds a quantity of one state, but it varies with the normal or with position")
                                    .with_help("bound a quantity that reads neither the normal (outside avg) nor a field"));
                            }
                            hypotheses.extend(h);
                            continue;
                        }
                    }
                    bounds.push(g.clone());
                }
                let domain = self.param_box(&bounds, decls)?;
                if name == "exact" {
                    Strategy::Exact { domain, hypotheses }
                } else {
                    Strategy::Proportional { domain }
                }
            }
            "numeric" => {
                let relation = match &c.relation {
                    None => Relation::Eq,
                    Some(r) => Relation::parse(r.get_ref()).ok_or_else(|| {
                        self.diag(r.span(), format!("unknown relation `{}`", r.get_ref()))
                            .with_help("relation is one of \"==\", \"<=\", \">=\"")
                    })?,
                };
                let domain = c
                    .domain
                    .iter()
                    .map(|d| self.constraint(d, decls, &sigs))
                    .collect::<Result<_, _>>()?;
                Strategy::Numeric {
                    sampling: self.sampling(c, decls, &sigs)?,
                    relation,
                    domain,
                }
            }
            "gradient" => {
                let function = scalar(&need(&c.function, "function")?)?;
                differentiable_once(&function, defs, name)?;
                if c.gradient.is_empty() {
                    return Err(self
                        .diag(
                            anchor.span(),
                            "strategy = \"gradient\" needs a `gradient` table",
                        )
                        .with_help("gradient = { sigma = \"closed form of ∂F/∂sigma_ij\" }"));
                }
                let mut closed_forms = Vec::new();
                for (symbol, text) in &c.gradient {
                    let Some(&rank) = decls.symbols.get(symbol) else {
                        return Err(
                            self.diag(text.span(), format!("`{symbol}` is not a declared symbol"))
                        );
                    };
                    let want: Vec<char> = "ijklmn".chars().take(rank).collect();
                    closed_forms
                        .push((symbol.clone(), self.expression(text, decls, &sigs, &want)?));
                }
                let convention = match &c.convention {
                    None => None,
                    Some(text) => {
                        Some(GradientConvention::parse(text.get_ref()).ok_or_else(|| {
                            self.diag(
                                text.span(),
                                format!("unknown gradient convention `{}`", text.get_ref()),
                            )
                            .with_help("convention = \"independent\" or \"symmetrised\"")
                        })?)
                    }
                };
                Strategy::Gradient {
                    sampling: self.sampling(c, decls, &sigs)?,
                    function,
                    closed_forms,
                    convention,
                }
            }
            "convex" => {
                let function = scalar(&need(&c.function, "function")?)?;
                differentiable_once(&function, defs, name)?;
                let mut wrt = Vec::new();
                for w in &c.wrt {
                    if !decls.symbols.contains_key(w.get_ref()) {
                        return Err(self.diag(
                            w.span(),
                            format!("`{}` is not a declared symbol", w.get_ref()),
                        ));
                    }
                    wrt.push(w.get_ref().clone());
                }
                if wrt.is_empty() {
                    return Err(self.diag(
                        anchor.span(),
                        "strategy = \"convex\" needs `wrt`, the symbols to vary",
                    ));
                }
                Strategy::Convex {
                    sampling: self.sampling(c, decls, &sigs)?,
                    function,
                    wrt,
                }
            }
            "sign" | "monotone" | "limit" | "roots" | "stationary" => {
                self.scalar_strategy(name, c, decls, defs)?
            }
            "not-circle" => {
                // The claim is about a generic state: a box or sampling would be ignored.
                let ignored = [
                    (!c.given.is_empty()).then_some("given"),
                    (!c.domain.is_empty()).then_some("domain"),
                    (!c.ranges.is_empty()).then_some("ranges"),
                    c.samples.as_ref().map(|_| "samples"),
                    c.seed.as_ref().map(|_| "seed"),
                    c.singular.as_ref().map(|_| "singular"),
                    c.relation.as_ref().map(|_| "relation"),
                ];
                if let Some(field) = ignored.into_iter().flatten().next() {
                    return Err(self
                        .diag(anchor.span(), format!("`{field}` does not apply to strategy = \"not-circle\", a claim about the locus at a generic state"))
                        .with_help("remove it; fix parameters with assume = [\"a = 1\"] instead"));
                }
                Strategy::NotCircle {
                    x: scalar(&need(&c.x, "x")?)?,
                    y: scalar(&need(&c.y, "y")?)?,
                }
            }
            other => {
                return Err(self
                    .diag(anchor.span(), format!("unknown strategy `{other}`"))
                    .with_help(format!("strategy is one of {STRATEGIES}")))
            }
        })
    }

    /// A checked expression whose free indices must be exactly `free` (letters).
    pub(super) fn expression(
        &self,
        s: &S,
        decls: &Decls,
        sigs: &[DefSig],
        free: &[char],
    ) -> Result<Expression, Diagnostic> {
        let origin = self.origin(s);
        let e = parse_expr(s.get_ref()).map_err(|e| self.lang(&origin, e))?;
        let node = Scope { decls, defs: sigs }
            .check(&e)
            .map_err(|e| self.lang(&origin, e))?;
        super::load::no_matrix(&origin, &node, "this field")?;
        let node = if node.is_literal_zero() {
            node.zero_with_free(free)
        } else {
            node
        };
        if node.free_letters() != free {
            return Err(origin
                .diagnostic(
                    Span::new(0, s.get_ref().len()),
                    format!(
                        "this expression has free indices {}, but {} are expected here",
                        letters(&node.free_letters()),
                        letters(free)
                    ),
                )
                .with_help("functions are scalars; a closed-form gradient carries the indices i, j, … of its symbol"));
        }
        Ok(Expression {
            text: s.get_ref().clone(),
            origin,
            node,
        })
    }

    /// `J2 > 0`, `a <= b`, `0 < J2 < k^2`: comparisons of scalar expressions of one
    /// state (not the normal, not varying with position), each a hypothesis.
    fn hypotheses(
        &self,
        s: &S,
        decls: &Decls,
        sigs: &[DefSig],
    ) -> Result<Vec<super::model::Hypothesis>, Diagnostic> {
        use crate::kernel::statement::Sign;
        const COMPARISONS: [&str; 6] = ["<=", ">=", "≤", "≥", "<", ">"];
        let origin = self.origin(s);
        let text = s.get_ref();
        let mut cuts: Vec<(usize, &str)> = Vec::new();
        let mut at = 0;
        while let Some((k, op)) = COMPARISONS
            .iter()
            .filter_map(|op| text[at..].find(op).map(|k| (at + k, *op)))
            .min_by_key(|(k, op)| (*k, std::cmp::Reverse(op.len())))
        {
            cuts.push((k, op));
            at = k + op.len();
        }
        let upper = |op: &str| matches!(op, "<" | "<=" | "≤");
        if cuts.is_empty() || cuts.len() > 2 || cuts.iter().any(|c| upper(c.1) != upper(cuts[0].1))
        {
            return Err(origin.diagnostic(
                Span::new(0, text.len()),
                "a hypothesis is one or two comparisons in one direction",
            ));
        }
        let mut sides = Vec::new();
        let mut start = 0;
        for (k, op) in cuts
            .iter()
            .copied()
            .chain(std::iter::once((text.len(), "")))
        {
            let sub = sub_origin(&origin, start..k);
            sides.push(self.compared(&sub, &text[start..k], (decls, sigs), "a hypothesis")?);
            start = k + op.len();
        }
        Ok(cuts
            .iter()
            .zip(sides.windows(2))
            .map(|(&(_, op), pair)| super::model::Hypothesis {
                text: text.trim().to_owned(),
                origin: origin.clone(),
                left: pair[0].clone(),
                right: pair[1].clone(),
                sign: match op {
                    "<" => Sign::Negative,
                    ">" => Sign::Positive,
                    "<=" | "≤" => Sign::NonPositive,
                    _ => Sign::NonNegative,
                },
            })
            .collect())
    }

    /// One side of a comparison (`what`: "a constraint", "a hypothesis"): a scalar
    /// expression, not a matrix, located at `sub`.
    fn compared(
        &self,
        sub: &crate::lang::Origin,
        part: &str,
        (decls, sigs): (&Decls, &[DefSig]),
        what: &str,
    ) -> Result<crate::lang::Node, Diagnostic> {
        let e = parse_expr(part).map_err(|e| self.lang(sub, e))?;
        let node = Scope { decls, defs: sigs }
            .check(&e)
            .map_err(|e| self.lang(sub, e))?;
        super::load::no_matrix(sub, &node, what)?;
        if !node.free.is_empty() {
            return Err(sub.diagnostic(node.span, format!("{what} compares scalars")));
        }
        Ok(node)
    }

    /// `a <= b`, `a >= b` or `a == b` between scalars.
    fn constraint(&self, s: &S, decls: &Decls, sigs: &[DefSig]) -> Result<Constraint, Diagnostic> {
        let origin = self.origin(s);
        let text = s.get_ref();
        let found = ["<=", ">=", "=="]
            .iter()
            .find_map(|op| text.find(op).map(|k| (k, *op)));
        let Some((k, op)) = found else {
            return Err(origin
                .diagnostic(
                    Span::new(0, text.len()),
                    "a constraint needs `<=`, `>=` or `==`",
                )
                .with_help("e.g. \"p <= 0\" or \"f_r <= f_s\""));
        };
        let side = |range: std::ops::Range<usize>| -> Result<Expression, Diagnostic> {
            let sub = sub_origin(&origin, range.clone());
            let part = &text[range];
            let node = self.compared(&sub, part, (decls, sigs), "a constraint")?;
            Ok(Expression {
                text: part.trim().to_owned(),
                origin: sub,
                node,
            })
        };
        Ok(Constraint {
            text: text.trim().to_owned(),
            lhs: side(0..k)?,
            relation: Relation::parse(op).expect("listed above"),
            rhs: side(k + 2..text.len())?,
        })
    }

    fn sampling(
        &self,
        c: &RawClaim,
        decls: &Decls,
        sigs: &[DefSig],
    ) -> Result<Sampling, Diagnostic> {
        let samples = match &c.samples {
            None => DEFAULT_SAMPLES,
            Some(n) => {
                let v = *n.get_ref();
                if v < MIN_SAMPLES as i64 || v > 1_000_000 {
                    return Err(self
                        .diag(n.span(), format!("samples must be between {MIN_SAMPLES} and 1000000, not {v}"))
                        .with_help(format!("fewer than {MIN_SAMPLES} random states would let a statement that fails on a small part of the domain pass")));
                }
                v as usize
            }
        };
        let seed = match &c.seed {
            None => 1,
            Some(s) if *s.get_ref() >= 0 => *s.get_ref() as u64,
            Some(s) => return Err(self.diag(s.span(), "seed must be a non-negative integer")),
        };
        let mut ranges = BTreeMap::new();
        for (name, bounds) in &c.ranges {
            let ok = bounds.len() == 2
                && bounds[0].is_finite()
                && bounds[1].is_finite()
                && bounds[0] <= bounds[1];
            if !decls.symbols.contains_key(name) || !ok {
                return Err(self
                    .diag(c.id.span(), format!("bad range for `{name}`: {bounds:?}"))
                    .with_help(
                        "ranges = { name = [low, high] } with a declared symbol and low ≤ high",
                    ));
            }
            ranges.insert(name.clone(), (bounds[0], bounds[1]));
        }
        let given = c
            .given
            .iter()
            .map(|g| self.constraint(g, decls, sigs))
            .collect::<Result<_, _>>()?;
        let singular = match &c.singular {
            None => None,
            Some(s) => Some(self.expression(s, decls, sigs, &[])?),
        };
        Ok(Sampling {
            samples,
            seed,
            ranges,
            given,
            singular,
        })
    }
}

/// Refuses a `grad(…)` in a function that a gradient or convex claim differentiates
/// again, directly or through a definition: the sampled route takes a gradient with
/// dual numbers seeded from real values, a first derivative only.
fn differentiable_once(
    f: &Expression,
    defs: &[Definition],
    strategy: &str,
) -> Result<(), Diagnostic> {
    let (nodes, _) = super::reads::reachable(vec![&f.node], defs);
    if nodes.iter().any(|n| matches!(n.kind, NodeKind::Wrt { .. })) {
        return Err(f
            .origin
            .diagnostic(
                f.node.span,
                format!("strategy = \"{strategy}\" differentiates this function, which takes grad(…) or variation(…) itself"),
            )
            .with_help("grad(…) takes first derivatives only: give this strategy the function without it"));
    }
    Ok(())
}
