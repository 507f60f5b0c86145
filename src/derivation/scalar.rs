//! Reading the scalar claim kinds (`strategy = "sign" | "monotone" | "limit" |
//! "roots" | "stationary"`): the parameter box of `given`, the variable of `in`, where
//! it tends to, the stated limit, roots and stationary point; and the parts that a sign
//! on exactly a set and a stationary point are decided in.

use super::load::Loader;
use super::model::{
    Definition, Expression, Extremum, LimitValue, ParamBox, ScalarClaim, Stationary, Strategy,
};
use super::raw::{RawClaim, S};
use super::spec::DEFAULT_SAMPLES;
use crate::algebra::limit::{Approach, Side};
use crate::algebra::sign::{End, Interval, Sign};
use crate::kernel::Rational;
use crate::lang::{Decls, DefSig, Diagnostic};

/// The comparison operators of a bound, longest first so that `<=` is not read as `<`.
const OPERATORS: [&str; 6] = ["<=", ">=", "≤", "≥", "<", ">"];

/// The largest root count a claim may state (more than any degree the kernel expands).
const MAX_ROOT_COUNT: usize = 100_000;

impl Loader {
    /// The strategy of a scalar claim of kind `name`.
    pub(super) fn scalar_strategy(
        &self,
        name: &str,
        c: &RawClaim,
        decls: &Decls,
        defs: &[Definition],
    ) -> Result<Strategy, Diagnostic> {
        let sigs: Vec<DefSig> = defs.iter().map(|d| d.sig.clone()).collect();
        let anchor = c.strategy.as_ref().unwrap_or(&c.id);
        let need = |field: &Option<S>, what: &str, example: &str| -> Result<S, Diagnostic> {
            field.clone().ok_or_else(|| {
                self.diag(
                    anchor.span(),
                    format!("strategy = \"{name}\" needs `{what}`"),
                )
                .with_help(format!("e.g. {example}"))
            })
        };
        if !c.ranges.is_empty() || c.singular.is_some() || !c.domain.is_empty() {
            return Err(self
                .diag(anchor.span(), format!("strategy = \"{name}\" takes its parameter box from `given`; `ranges`, `singular` and `domain` belong to the sampled strategies"))
                .with_help("given = [\"f_r > 0\", \"0 < nu < 1/2\"]"));
        }
        let scalar = |s: &S| self.scalar_expression(s, decls, &sigs);
        let variable = |c: &RawClaim| -> Result<String, Diagnostic> {
            let v = need(&c.variable, "in", "in = \"f_r\", the parameter")?;
            self.parameter(&v, decls)
        };
        let function = || scalar(&need(&c.function, "function", "function = \"A2\"")?);
        let claim = match name {
            "sign" => {
                let r = need(&c.relation, "relation", "relation = \">\"")?;
                let want = match r.get_ref().as_str() {
                    ">" => Sign::Positive,
                    ">=" | "≥" => Sign::NonNegative,
                    "<" => Sign::Negative,
                    "<=" | "≤" => Sign::NonPositive,
                    other => {
                        return Err(self
                            .diag(r.span(), format!("unknown relation `{other}` for a sign claim"))
                            .with_help("relation is one of \">\", \">=\", \"<\", \"<=\": left − right has that sign"))
                    }
                };
                match &c.exactly_when {
                    Some(when) => {
                        let set = self.param_box(when.get_ref(), decls)?;
                        if set.bounds.is_empty() {
                            return Err(self
                                .diag(when.span(), "`exactly_when` needs at least one bound")
                                .with_help("exactly_when = [\"-1 < nu < 1/2\"]: the sign holds there and nowhere else in the domain"));
                        }
                        ScalarClaim::SignExactly(want, set)
                    }
                    None => ScalarClaim::Sign(want),
                }
            }
            "monotone" => {
                let d = need(&c.direction, "direction", "direction = \"increasing\"")?;
                let increasing = match d.get_ref().as_str() {
                    "increasing" => true,
                    "decreasing" => false,
                    other => {
                        return Err(self
                            .diag(d.span(), format!("unknown direction `{other}`"))
                            .with_help("direction is \"increasing\" or \"decreasing\""))
                    }
                };
                ScalarClaim::Monotone {
                    function: function()?,
                    variable: variable(c)?,
                    increasing,
                }
            }
            "limit" => {
                let to = need(&c.tends_to, "tends_to", "tends_to = \"0+\"")?;
                let value = need(&c.limit, "limit", "limit = \"0\" or \"+infinity\"")?;
                ScalarClaim::Limit {
                    function: function()?,
                    variable: variable(c)?,
                    to: self.approach(&to)?,
                    value: match value.get_ref().trim() {
                        "infinity" => LimitValue::Unsigned,
                        "+infinity" => LimitValue::Signed(true),
                        "-infinity" => LimitValue::Signed(false),
                        _ => LimitValue::Finite(scalar(&value)?),
                    },
                }
            }
            "roots" => {
                let (roots, count) = match (&c.roots, &c.count) {
                    (Some(roots), None) => (roots.iter().map(scalar).collect::<Result<_, _>>()?, None),
                    (None, Some(n)) => match usize::try_from(*n.get_ref()) {
                        Ok(k) if k <= MAX_ROOT_COUNT => (Vec::new(), Some(k)),
                        _ => {
                            return Err(self
                                .diag(n.span(), format!("count must be between 0 and {MAX_ROOT_COUNT}"))
                                .with_help("count = 1: the domain holds exactly one real root"))
                        }
                    },
                    (Some(_), Some(n)) => {
                        return Err(self
                            .diag(n.span(), "a roots claim lists its `roots` or gives their `count`, not both")
                            .with_help("roots = [\"1\", \"-3\"] when every root is rational; count = 2 otherwise"))
                    }
                    (None, None) => {
                        return Err(self
                            .diag(anchor.span(), "strategy = \"roots\" needs `roots` or `count`")
                            .with_help("roots = [\"1/2\", \"-3\"]: every real root in the domain (roots = [] for none); count = 1: exactly one, rational or not"))
                    }
                };
                ScalarClaim::Roots {
                    function: function()?,
                    variable: variable(c)?,
                    roots,
                    count,
                }
            }
            "stationary" => {
                let function = function()?;
                let variable = variable(c)?;
                let at_text = need(&c.at, "at", "at = \"a / 2\", the stationary point")?;
                let at = scalar(&at_text)?;
                let k = need(&c.kind, "kind", "kind = \"local-maximum\"")?;
                let kind = match k.get_ref().as_str() {
                    "stationary" => Extremum::Stationary,
                    "local-maximum" => Extremum::LocalMaximum,
                    "local-minimum" => Extremum::LocalMinimum,
                    other => {
                        return Err(self
                            .diag(k.span(), format!("unknown kind `{other}`"))
                            .with_help("kind is \"stationary\" (the derivative vanishes), \"local-maximum\" or \"local-minimum\" (and the second derivative is < 0 or > 0 there)"))
                    }
                };
                // The derivatives, read as the file would write them.
                let f = need(&c.function, "function", "")?;
                let derivative = |text: String| scalar(&toml::Spanned::new(f.span(), text));
                let first = derivative(format!("grad({}, {variable})", f.get_ref()))?;
                let second = derivative(format!(
                    "grad(grad({}, {variable}), {variable})",
                    f.get_ref()
                ))?;
                let point = self.assumption(
                    &toml::Spanned::new(
                        at_text.span(),
                        format!("{variable} = {}", at_text.get_ref()),
                    ),
                    decls,
                    defs,
                )?;
                if point.reads.contains(&variable) {
                    return Err(self
                        .diag(at_text.span(), format!("the point reads `{variable}` itself"))
                        .with_help(format!("at is an expression in the other parameters, the value of `{variable}` at the stationary point")));
                }
                let domain = self.param_box(&c.given, decls)?;
                let interval = domain.interval(&variable);
                let mut ends = Vec::new();
                for (lower, end) in [(true, &interval.lo), (false, &interval.hi)] {
                    let (closed, value) = match end {
                        End::Unbounded => continue,
                        End::Open(x) => (false, x),
                        End::Closed(x) => (true, x),
                    };
                    let value = scalar(&toml::Spanned::new(at_text.span(), value.to_string()))?;
                    ends.push((lower, closed, value));
                }
                ScalarClaim::Stationary(Box::new(Stationary {
                    function,
                    variable,
                    at,
                    kind,
                    first,
                    second,
                    point,
                    ends,
                }))
            }
            _ => unreachable!("called for the scalar kinds only"),
        };
        for (at, key) in [
            (c.variable.as_ref().map(|s| s.span()), "in"),
            (c.direction.as_ref().map(|s| s.span()), "direction"),
            (c.tends_to.as_ref().map(|s| s.span()), "tends_to"),
            (c.limit.as_ref().map(|s| s.span()), "limit"),
            (c.roots.as_ref().map(|_| anchor.span()), "roots"),
            (c.count.as_ref().map(|s| s.span()), "count"),
            (c.exactly_when.as_ref().map(|s| s.span()), "exactly_when"),
            (c.at.as_ref().map(|s| s.span()), "at"),
            (c.kind.as_ref().map(|s| s.span()), "kind"),
        ] {
            let used = match key {
                "in" => claim.function().is_some(),
                "at" | "kind" => matches!(claim, ScalarClaim::Stationary(_)),
                "direction" => matches!(claim, ScalarClaim::Monotone { .. }),
                "roots" | "count" => matches!(claim, ScalarClaim::Roots { .. }),
                "exactly_when" => matches!(claim, ScalarClaim::SignExactly(..)),
                _ => matches!(claim, ScalarClaim::Limit { .. }),
            };
            if let (Some(at), false) = (at, used) {
                return Err(self
                    .diag(
                        at,
                        format!("`{key}` does not apply to strategy = \"{name}\""),
                    )
                    .with_help(
                        "see `cosserat-check guide`, section \"Claims about rational functions\"",
                    ));
            }
        }
        if let (Some(f), ScalarClaim::Sign(_) | ScalarClaim::SignExactly(..)) =
            (&c.function, &claim)
        {
            return Err(self
                .diag(
                    f.span(),
                    "a sign claim compares its `sides`; `function` does not apply",
                )
                .with_help("sides = [\"A2\", \"0\"] with relation = \">\""));
        }
        let samples = match &c.samples {
            None => DEFAULT_SAMPLES,
            Some(n) if (50..=1_000_000).contains(n.get_ref()) => *n.get_ref() as usize,
            Some(n) => {
                return Err(self
                    .diag(n.span(), "samples must be between 50 and 1000000")
                    .with_help("samples are drawn only when no exact route applies"))
            }
        };
        let seed = match &c.seed {
            None => 1,
            Some(s) if *s.get_ref() >= 0 => *s.get_ref() as u64,
            Some(s) => return Err(self.diag(s.span(), "seed must be a non-negative integer")),
        };
        Ok(Strategy::Scalar {
            claim: Box::new(claim),
            domain: self.param_box(&c.given, decls)?,
            samples,
            seed,
        })
    }

    /// A scalar expression with no free index.
    fn scalar_expression(
        &self,
        s: &S,
        decls: &Decls,
        sigs: &[DefSig],
    ) -> Result<Expression, Diagnostic> {
        self.expression(s, decls, sigs, &[])
    }

    /// A declared scalar (rank 0, not a field).
    fn parameter(&self, s: &S, decls: &Decls) -> Result<String, Diagnostic> {
        let name = s.get_ref().trim();
        match decls.symbols.get(name) {
            Some(0) if !decls.fields.contains_key(name) => Ok(name.to_owned()),
            Some(_) => Err(self
                .diag(s.span(), format!("`{name}` is not a scalar parameter"))
                .with_help("scalar claims are about declared scalars: scalars = [\"f_r\"]")),
            None => Err(self
                .diag(s.span(), format!("`{name}` is not a declared scalar"))
                .with_help("declare it: scalars = [\"…\"]")),
        }
    }

    /// `0`, `0+`, `1/2-`, `infinity`, `-infinity`.
    fn approach(&self, s: &S) -> Result<Approach, Diagnostic> {
        let text = s.get_ref().trim();
        let bad = || {
            self.diag(s.span(), format!("cannot read `{text}` as where the parameter tends"))
                .with_help("tends_to is a rational with an optional side (\"0\", \"0+\", \"1/2-\"), \"infinity\" or \"-infinity\"")
        };
        Ok(match text {
            "infinity" | "+infinity" => Approach::PlusInfinity,
            "-infinity" => Approach::MinusInfinity,
            _ => {
                let (number, side) = if let Some(n) = text.strip_suffix('+') {
                    (n, Side::Above)
                } else if let Some(n) = text.strip_suffix('-') {
                    (n, Side::Below)
                } else {
                    (text, Side::Both)
                };
                Approach::At(rational(number).ok_or_else(bad)?, side)
            }
        })
    }

    /// The box of `given`: each entry bounds one declared scalar by rationals
    /// (`f_r > 0`, `0 < nu < 1/2`, `K >= 1`); several entries on one scalar intersect.
    pub(super) fn param_box(&self, given: &[S], decls: &Decls) -> Result<ParamBox, Diagnostic> {
        let mut out = ParamBox::default();
        for g in given {
            let text = g.get_ref();
            let bad = |why: &str| {
                self.diag(g.span(), format!("cannot read `{text}` as a bound: {why}"))
                    .with_help("write \"x > 0\", \"x <= 1/2\" or \"0 < x < 1\" with a declared scalar and rational bounds")
            };
            let mut parts: Vec<&str> = Vec::new();
            let mut ops: Vec<&str> = Vec::new();
            let mut rest = text.as_str();
            while let Some((k, op)) = OPERATORS
                .iter()
                .filter_map(|op| rest.find(op).map(|k| (k, *op)))
                .min_by_key(|(k, op)| (*k, std::cmp::Reverse(op.len())))
            {
                parts.push(&rest[..k]);
                ops.push(op);
                rest = &rest[k + op.len()..];
            }
            parts.push(rest);
            let parts: Vec<&str> = parts.iter().map(|p| p.trim()).collect();
            let upper = |op: &str| matches!(op, "<" | "<=" | "≤");
            let strict = |op: &str| matches!(op, "<" | ">");
            let end = |x: Rational, op: &str| {
                if strict(op) {
                    End::Open(x)
                } else {
                    End::Closed(x)
                }
            };
            // Read as `lo op symbol op hi` in increasing order.
            let (symbol, interval) = match (parts.as_slice(), ops.as_slice()) {
                ([a, b], [op]) => match (rational(a), rational(b)) {
                    (None, Some(x)) if upper(op) => (*a, (End::Unbounded, end(x, op))),
                    (None, Some(x)) => (*a, (end(x, op), End::Unbounded)),
                    (Some(x), None) if upper(op) => (*b, (end(x, op), End::Unbounded)),
                    (Some(x), None) => (*b, (End::Unbounded, end(x, op))),
                    _ => return Err(bad("one side is a scalar, the other a rational")),
                },
                ([a, b, c], [o1, o2]) if upper(o1) == upper(o2) => {
                    let (Some(x), Some(y)) = (rational(a), rational(c)) else {
                        return Err(bad("the outer parts are rationals"));
                    };
                    if upper(o1) {
                        (*b, (end(x, o1), end(y, o2)))
                    } else {
                        (*b, (end(y, o2), end(x, o1)))
                    }
                }
                _ => return Err(bad("one or two comparisons, in one direction")),
            };
            let name = self
                .parameter(&toml::Spanned::new(g.span(), symbol.to_owned()), decls)
                .map_err(|d| {
                    d.with_help(
                        "`given` of a proportionality or of a claim about a rational function bounds declared \
                         scalars (`given = [\"f_r > 0\"]`); a bound on a definition or on any other \
                         expression is a hypothesis of an exact identity or of strategy = \"numeric\"",
                    )
                })?;
            let new = Interval {
                lo: interval.0,
                hi: interval.1,
            };
            let merged = match out.bounds.iter().position(|(s, _)| *s == name) {
                Some(k) => {
                    let (_, old) = out.bounds.remove(k);
                    intersect(&old, &new)
                }
                None => new,
            };
            if merged.is_empty() {
                return Err(bad(
                    "no value satisfies it (with the other bounds on the same scalar)",
                ));
            }
            out.bounds.push((name, merged));
        }
        Ok(out)
    }
}

/// A rational literal: `3`, `-0.25`, `1/2`, `-7/3`.
fn rational(text: &str) -> Option<Rational> {
    let t = text.trim();
    let (negative, body) = match t.strip_prefix('-') {
        Some(b) => (true, b.trim()),
        None => (false, t.strip_prefix('+').unwrap_or(t).trim()),
    };
    let value = match body.split_once('/') {
        Some((n, d)) => crate::lang::parser::parse_decimal(n.trim())?
            .checked_div(&crate::lang::parser::parse_decimal(d.trim())?)?,
        None => crate::lang::parser::parse_decimal(body)?,
    };
    Some(if negative { -value } else { value })
}

/// The intersection of two intervals.
/// The parts a sign claim that holds exactly on `set` within `domain` is decided in:
/// the sign `want` on their intersection, and the negated sign on each box of the rest
/// of the domain (for the k-th bounded scalar: the scalars before it in the set, this
/// one below or above it, the others anywhere in the domain). Empty boxes are left out;
/// together the boxes cover the domain once.
pub fn exact_parts(want: Sign, set: &ParamBox, domain: &ParamBox) -> Vec<(Sign, ParamBox)> {
    let within = |name: &str, i: &Interval| intersect(&domain.interval(name), i);
    let with = |bounds: Vec<(String, Interval)>| {
        let mut b = domain.clone();
        for (name, i) in bounds {
            match b.bounds.iter_mut().find(|(s, _)| *s == name) {
                Some(slot) => slot.1 = i,
                None => b.bounds.push((name, i)),
            }
        }
        b
    };
    let flip = |e: &End| match e {
        End::Unbounded => None,
        End::Open(x) => Some(End::Closed(x.clone())),
        End::Closed(x) => Some(End::Open(x.clone())),
    };
    let inside: Vec<(String, Interval)> = set
        .bounds
        .iter()
        .map(|(name, i)| (name.clone(), within(name, i)))
        .collect();
    let mut out = Vec::new();
    if inside.iter().all(|(_, i)| !i.is_empty()) {
        out.push((want, with(inside.clone())));
    }
    let negated = match want {
        Sign::Positive => Sign::NonPositive,
        Sign::NonNegative => Sign::Negative,
        Sign::Negative => Sign::NonNegative,
        Sign::NonPositive => Sign::Positive,
    };
    for (k, (name, i)) in set.bounds.iter().enumerate() {
        if inside[..k].iter().any(|(_, i)| i.is_empty()) {
            break;
        }
        let below = flip(&i.lo).map(|hi| Interval {
            lo: End::Unbounded,
            hi,
        });
        let above = flip(&i.hi).map(|lo| Interval {
            lo,
            hi: End::Unbounded,
        });
        for rest in [below, above].into_iter().flatten() {
            let rest = within(name, &rest);
            if !rest.is_empty() {
                let mut bounds = inside[..k].to_vec();
                bounds.push((name.clone(), rest));
                out.push((negated, with(bounds)));
            }
        }
    }
    out
}

/// The checks a claim with `exactly_when` is decided as: one sign claim per part of
/// [`exact_parts`], each on its own box (`None` for any other claim).
pub fn exact_part_checks(check: &super::model::Check) -> Option<Vec<super::model::Check>> {
    let Strategy::Scalar { claim, domain, .. } = &check.strategy else {
        return None;
    };
    let ScalarClaim::SignExactly(want, set) = &**claim else {
        return None;
    };
    let parts = exact_parts(*want, set, domain)
        .into_iter()
        .map(|(sign, part)| {
            let mut c = check.clone();
            c.strategy = sign_claim(check, sign, part);
            c
        });
    Some(parts.collect())
}

/// The strategy of a part of `check` (a scalar claim): the sign `sign` on `domain`,
/// with the claim's samples and seed.
fn sign_claim(check: &super::model::Check, sign: Sign, domain: ParamBox) -> Strategy {
    let (samples, seed) = match &check.strategy {
        Strategy::Scalar { samples, seed, .. } => (*samples, *seed),
        _ => (DEFAULT_SAMPLES, 1),
    };
    Strategy::Scalar {
        claim: Box::new(ScalarClaim::Sign(sign)),
        domain,
        samples,
        seed,
    }
}

/// One part of a stationary claim: a sign claim under `variable = at`.
pub struct Part {
    /// What the part says, in words.
    pub what: String,
    pub check: super::model::Check,
    /// A weaker claim that tells a failure of the part from a case the test does not
    /// decide: where the part fails and this holds, the claim is undecided, for `why`.
    pub weaker: Option<(super::model::Check, &'static str)>,
}

/// The parts a stationary claim is decided in, each a sign claim on the domain without
/// the claim's variable, under `variable = at`: the point inside the variable's
/// interval (in it, for a stationary point), the first derivative ≥ 0 and ≤ 0 there,
/// and for an extremum the second derivative's strict sign (`None` for any other
/// claim). The claim holds when every part does.
pub fn stationary_parts(check: &super::model::Check) -> Option<Vec<Part>> {
    let Strategy::Scalar { claim, domain, .. } = &check.strategy else {
        return None;
    };
    let ScalarClaim::Stationary(s) = &**claim else {
        return None;
    };
    let mut domain = domain.clone();
    domain.bounds.retain(|(name, _)| *name != s.variable);
    let side = |e: &Expression| super::model::Side {
        text: e.text.clone(),
        origin: e.origin.clone(),
        node: Ok(e.node.clone()),
        entry: None,
    };
    let zero = Expression {
        text: "0".to_owned(),
        origin: s.first.origin.clone(),
        node: crate::lang::Node {
            kind: crate::lang::NodeKind::Const(Rational::int(0)),
            free: Vec::new(),
            bound: Vec::new(),
            span: s.first.node.span,
        },
    };
    let part = |left: &Expression, right: &Expression, sign: Sign| {
        let mut c = check.clone();
        c.assumptions.push(s.point.clone());
        c.chains = vec![vec![side(left), side(right)]];
        c.strategy = sign_claim(check, sign, domain.clone());
        c
    };
    let (v, at) = (&s.variable, &s.at.text);
    let mut parts = Vec::new();
    for (lower, closed, end) in &s.ends {
        let (own, strict) = match (lower, closed) {
            (true, true) => (Sign::NonNegative, Sign::Positive),
            (true, false) => (Sign::Positive, Sign::Positive),
            (false, true) => (Sign::NonPositive, Sign::Negative),
            (false, false) => (Sign::Negative, Sign::Negative),
        };
        // `left − right` of `at` and the end, as a relation between the two.
        let relation = |sign: Sign| &sign.relation()[..sign.relation().len() - 2];
        let said = |sign: Sign, where_: &str| {
            format!(
                "the point {v} = {at} is {} {} ({where_})",
                relation(sign).trim(),
                end.text
            )
        };
        parts.push(match s.kind {
            Extremum::Stationary => Part {
                what: said(own, "in the interval"),
                check: part(&s.at, end, own),
                weaker: None,
            },
            Extremum::LocalMaximum | Extremum::LocalMinimum => Part {
                what: said(strict, "inside the interval"),
                check: part(&s.at, end, strict),
                weaker: closed.then(|| {
                    (
                        part(&s.at, end, own),
                        "the point reaches an end of the interval, where the derivative test decides nothing",
                    )
                }),
            },
        });
    }
    for sign in [Sign::NonNegative, Sign::NonPositive] {
        parts.push(Part {
            what: format!("the derivative in {v} at {v} = {at} is {}", sign.relation()),
            check: part(&s.first, &zero, sign),
            weaker: None,
        });
    }
    let second = match s.kind {
        Extremum::Stationary => None,
        Extremum::LocalMaximum => Some((Sign::Negative, Sign::NonPositive)),
        Extremum::LocalMinimum => Some((Sign::Positive, Sign::NonNegative)),
    };
    if let Some((strict, loose)) = second {
        parts.push(Part {
            what: format!("the second derivative in {v} at {v} = {at} is {}", strict.relation()),
            check: part(&s.second, &zero, strict),
            weaker: Some((
                part(&s.second, &zero, loose),
                "the second derivative vanishes there at some values of the parameters, where the second-derivative test decides nothing",
            )),
        });
    }
    Some(parts)
}

fn intersect(a: &Interval, b: &Interval) -> Interval {
    let pick = |x: &End, y: &End, lower: bool| -> End {
        let v = |e: &End| match e {
            End::Unbounded => None,
            End::Open(r) | End::Closed(r) => Some(r.clone()),
        };
        match (v(x), v(y)) {
            (None, _) => y.clone(),
            (_, None) => x.clone(),
            (Some(p), Some(q)) if p == q => {
                if matches!(x, End::Open(_)) {
                    x.clone()
                } else {
                    y.clone()
                }
            }
            (Some(p), Some(q)) => {
                if (p > q) == lower {
                    x.clone()
                } else {
                    y.clone()
                }
            }
        }
    };
    Interval {
        lo: pick(&a.lo, &b.lo, true),
        hi: pick(&a.hi, &b.hi, false),
    }
}
