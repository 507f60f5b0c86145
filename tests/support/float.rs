//! An independent floating-point route for cross-checking exact verdicts, as a test
//! oracle (`tests/claims.rs`, `tests/mutants.rs`, `tests/balance.rs`).
//!
//! It evaluates with the library's real ring (floating point, no polynomial, no moment
//! formula) and shares the parser, the validator, the walk and the solved assumptions
//! with the exact strategy. Symbols get seeded random values in [−1, 1], the normal is
//! a random unit vector, and `avg(…)` re-evaluates its argument at the nodes of a
//! quadrature rule exact for polynomials of degree ≤ 15 in n. A disagreement between
//! this route and the exact one is a bug in one of them, and the test suite fails on it.

use cosserat_check::algebra::sign::{End, Interval};
use cosserat_check::algebra::Tensor;
use cosserat_check::decide::random::Rng;
use cosserat_check::derivation::parametrisation::Parametrisation;
use cosserat_check::derivation::{AssumptionKind, Check, Strategy, Verdict};
use cosserat_check::eval::real::{component_pairs, RealEnv};
use cosserat_check::eval::taylor::TaylorFields;
use cosserat_check::lang::parser::Wrt;
use cosserat_check::lang::{Decls, Node, NodeKind, Target};
use cosserat_check::tolerance::{TAYLOR_AGREEMENT, TAYLOR_STEP, TOL};

/// Degree of the random polynomial fields: derivatives up to this order are random,
/// higher ones zero (a statement with fifth derivatives is not distinguished from one
/// without them).
pub const FIELD_DEGREE: u32 = 4;

/// The float route's verdict on a check: `holds` when every equality agrees within
/// [`TOL`] (with field derivatives, [`taylor_agreement`]) at `samples` seeded random
/// points, else `fails`. `Ok(None)` when the check
/// has an ill-formed (verbatim) side or averages an argument that is not a polynomial
/// in n, which this route does not judge.
pub fn decide(
    decls: &Decls,
    check: &Check,
    samples: usize,
    seed: u64,
) -> Result<Option<Verdict>, String> {
    if check.chains.iter().flatten().any(|s| s.node.is_err()) {
        return Ok(None);
    }
    // Random polynomial fields do not satisfy a differential hypothesis (phi_,kk = 0):
    // this route does not judge such a check.
    if check
        .assumptions
        .iter()
        .any(|a| matches!(a.kind, AssumptionKind::Differential { .. }))
    {
        return Ok(None);
    }
    let d = decls.dim;
    let parametrisation =
        Parametrisation::new(decls, &check.defs, &check.assumptions).map_err(|e| e.message)?;
    let mut rng = Rng::new(seed);
    // Derivatives of fields: random polynomial fields, differentiated by central
    // differences, to the stencil's accuracy.
    let differentiates = check.reads().differentiates;
    let tol = if differentiates {
        taylor_agreement(check)
    } else {
        TOL
    };
    let proportional = matches!(check.strategy, Strategy::Proportional { .. });
    let domain = check.strategy.exact_domain();
    let mut factor: Option<f64> = None;
    // A draw where a polynomial constraint's even power has no real root is no state:
    // drawn again, a bounded number of times.
    let (mut kept, mut drawn) = (0, 0);
    while kept < samples {
        drawn += 1;
        if drawn > 50 * samples {
            return Ok(None);
        }
        let mut symbols: Vec<(String, Tensor<f64>)> = Vec::new();
        for (name, &rank) in &decls.symbols {
            let mut t = Tensor::from_fn(d, rank, |_| rng.uniform());
            // A scalar the claim bounds (`given`) is drawn inside its interval.
            if let Some(i) = domain.map(|b| b.interval(name)) {
                if rank == 0 {
                    *t.get_mut(&[]) = inside(&i, *t.get(&[]));
                }
            }
            symbols.push((name.clone(), t));
        }
        let mut env = RealEnv::new(decls, &check.defs, symbols);
        if differentiates {
            let fields = TaylorFields::random(decls, FIELD_DEGREE, &mut || rng.uniform());
            env = env.with_fields(fields);
        }
        let n = rng.unit_normal(decls);
        env.assume(&parametrisation, &check.assumptions, &n)
            .map_err(|e| e.message)?;
        let value =
            |(s, idx): &(String, Vec<usize>)| env.symbols.get(s).map_or(f64::NAN, |t| *t.get(idx));
        if !parametrisation.solved().is_empty() && parametrisation.residual(value) > TOL {
            continue;
        }
        // Sides undefined at this draw only (a square root of a negative number, which
        // the exact route takes as a variable of its own): another draw.
        let evaluated: Result<Vec<Vec<_>>, _> = check
            .chains
            .iter()
            .map(|chain| {
                chain
                    .iter()
                    .map(|s| env.eval(s.node.as_ref().expect("checked above"), &n))
                    .collect::<Result<Vec<_>, _>>()
            })
            .collect();
        let evaluated = match evaluated {
            Ok(v) => v,
            Err(e) if e.pointwise => continue,
            Err(e) => return Err(e.message),
        };
        kept += 1;
        for values in evaluated {
            if env.quadrature.used() {
                // Adaptive averages carry an error this route does not account for.
                return Ok(None);
            }
            for w in values.windows(2) {
                let (_, pairs) = component_pairs(d, &w[0], &w[1]);
                // A proportionality takes its factor from the pair with the largest
                // right side of the first sample where one is clearly nonzero (above
                // 100 tolerances, so that rounding noise never sets it), and holds it
                // fixed after that; until then the sides are compared as equal.
                if proportional && factor.is_none() {
                    let largest = pairs
                        .iter()
                        .max_by(|a, b| a.2.abs().total_cmp(&b.2.abs()))
                        .filter(|p| p.2.abs() > 100.0 * tol);
                    if let Some((_, l, r)) = largest {
                        let f = l / r;
                        if !f.is_finite() || f.abs() <= tol {
                            return Ok(Some(Verdict::Fails));
                        }
                        factor = Some(f);
                    }
                }
                let scale = factor.unwrap_or(1.0);
                for (_, l, r) in pairs {
                    if !l.is_finite() || !r.is_finite() {
                        return Ok(Some(Verdict::Fails));
                    }
                    let r = scale * r;
                    if (l - r).abs() > tol * (1.0 + l.abs() + r.abs()) {
                        return Ok(Some(Verdict::Fails));
                    }
                }
            }
        }
    }
    Ok(Some(Verdict::Holds))
}

/// The agreement of central differences nested as deeply as `check` nests them.
/// [`TAYLOR_AGREEMENT`] covers three levels; each further level multiplies the
/// rounding by about 1.5/h (see [`TAYLOR_STEP`]).
fn taylor_agreement(check: &Check) -> f64 {
    let defs = |name: &str| {
        check
            .defs
            .iter()
            .find(|d| d.sig.name == name)
            .map(|d| &d.body)
    };
    let depth = check
        .chains
        .iter()
        .flatten()
        .filter_map(|s| s.node.as_ref().ok());
    let depth = depth.map(|n| nesting(n, &defs)).max().unwrap_or(0);
    let levels = i32::try_from(depth.saturating_sub(3)).unwrap_or(i32::MAX);
    TAYLOR_AGREEMENT * (1.5 / TAYLOR_STEP).powi(levels)
}

/// How many central differences `node` nests: one per comma derivative, and for a
/// variation, the derivatives of its Euler–Lagrange terms on top of its body's.
fn nesting<'a>(node: &'a Node, defs: &dyn Fn(&str) -> Option<&'a Node>) -> usize {
    let inner = |n: &'a Node| nesting(n, defs);
    match &node.kind {
        NodeKind::Deriv(a, _) => 1 + inner(a),
        NodeKind::Wrt {
            op: Wrt::Variation,
            body,
            ..
        } => 2 * inner(body),
        NodeKind::Leaf {
            target: Target::Def(name),
            ..
        } => defs(name).map_or(0, inner),
        _ => node.children().into_iter().map(inner).max().unwrap_or(0),
    }
}

/// A value of the interval for a uniform draw `u` in [−1, 1], off its ends.
fn inside(i: &Interval, u: f64) -> f64 {
    let unit = 0.05 + 0.9 * (u + 1.0) / 2.0;
    let end = |e: &End| match e {
        End::Unbounded => None,
        End::Open(x) | End::Closed(x) => Some(x.to_f64()),
    };
    match (end(&i.lo), end(&i.hi)) {
        (None, None) => u,
        (Some(a), None) => a + 2.0 * unit,
        (None, Some(b)) => b - 2.0 * unit,
        (Some(a), Some(b)) => a + (b - a) * unit,
    }
}
