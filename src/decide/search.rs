//! Adversarial search: after the random samples of a sampled claim, local searches for
//! the worst violation.
//!
//! A statement that is false only on a thin set of states (an inequality whose constant
//! is rounded past the sharp bound, an equality that fails in a corner or a small ball,
//! a statement false only near the boundary of a hypothesis) is rarely hit by uniform
//! samples. So no sampled `holds` is given before a pattern search (compass search:
//! derivative-free, so it also climbs through `abs`, `max` and `sqrt`) has tried to
//! make the margin of the statement positive, starting from the worst random samples,
//! the centre of the sampled ranges and corners of the box. The search moves only the
//! free components (the assumptions fix the others) and the orientation of the normal,
//! stays inside the ranges, and never leaves the hypotheses or enters the singular set.

use super::sampler::Sampler;
use crate::algebra::assignments;
use crate::derivation::Constraint;
use crate::eval::state::State;
use crate::lang::Diagnostic;
use crate::tolerance::{FIRST_STEP, LAST_STEP, NEARBY_STEP};
use rustc_hash::FxHashMap as HashMap;
use std::collections::BTreeSet;
use std::f64::consts::PI;

/// Random samples the search starts from (the worst ones).
pub const WORST_STARTS: usize = 3;
/// Random corners of the box the search starts from, besides the two extreme ones.
pub const RANDOM_CORNERS: usize = 4;
/// Evaluations of the whole search per random sample: the search costs this many times
/// the random sampling.
pub const EVALUATIONS_PER_SAMPLE: usize = 3;
/// Starts on the boundary of the hypotheses (when there are any), the random draws
/// tried for a state outside them, and the bisection steps towards the boundary.
const BOUNDARY_STARTS: usize = 3;
const BOUNDARY_DRAWS: usize = 16;
const BISECTIONS: usize = 40;

/// The margin of a statement at a state (positive: violated), or `None` when the state
/// violates it outright.
pub(crate) type Margin<'m> =
    dyn FnMut(&Sampler<'_>, &State) -> Result<Option<f64>, Diagnostic> + 'm;

/// What the search did and found.
#[derive(Clone, Debug)]
pub struct SearchResult {
    /// Starting points searched from.
    pub starts: usize,
    /// Evaluations of the statement.
    pub evaluations: usize,
    /// The largest margin found (positive: violated), and where.
    pub worst: f64,
    pub worst_state: Option<State>,
    /// The first violating state found, if any.
    pub violation: Option<State>,
}

/// One coordinate of the search: a free component of a symbol, or an angle of the
/// normal.
enum Coordinate {
    Component {
        symbol: String,
        index: Vec<usize>,
        lo: f64,
        hi: f64,
    },
    /// The azimuth of the normal (periodic).
    Azimuth,
    /// The polar angle of a 3D normal, in [0, π].
    Polar,
}

impl Coordinate {
    fn bounds(&self) -> (f64, f64) {
        match self {
            Coordinate::Component { lo, hi, .. } => (*lo, *hi),
            Coordinate::Azimuth => (-PI, PI),
            Coordinate::Polar => (0.0, PI),
        }
    }
}

/// The coordinates that matter to the statement: free components of the symbols the
/// statement's expressions read (all symbols when some expression is interpreted),
/// and the normal's angles when the file declares a normal.
fn coordinates(
    sampler: &Sampler<'_>,
    relevant: &Option<BTreeSet<(String, Vec<usize>)>>,
) -> Vec<Coordinate> {
    use crate::derivation::parametrisation::Constrained;
    let p = &sampler.parametrisation;
    let substituted: BTreeSet<&str> = p
        .substitutions()
        .iter()
        .filter_map(|&k| sampler.check.assumptions[k].kind.symbol())
        .collect();
    let mut out = Vec::new();
    for (name, &rank) in &sampler.decls.symbols {
        if substituted.contains(name.as_str()) {
            continue;
        }
        let (lo, hi) = sampler.range(name);
        for index in assignments(sampler.decls.dim, rank) {
            if p.constrained(name, &index) != Constrained::Free {
                continue;
            }
            // A free component matters if the statement reads it, or reads a component
            // the assumptions compute from it.
            let key = (name.clone(), index.clone());
            let read = |c: &(String, Vec<usize>)| relevant.as_ref().is_none_or(|r| r.contains(c));
            if !read(&key) && !p.dependents_on(&key).any(read) {
                continue;
            }
            out.push(Coordinate::Component {
                symbol: name.clone(),
                index,
                lo,
                hi,
            });
        }
    }
    if sampler.decls.normal.is_some() {
        out.push(Coordinate::Azimuth);
        if sampler.decls.dim == 3 && !sampler.decls.normal_in_plane {
            out.push(Coordinate::Polar);
        }
    }
    out
}

fn to_vec(coords: &[Coordinate], state: &State) -> Vec<f64> {
    let n = &state.n;
    coords
        .iter()
        .map(|c| match c {
            Coordinate::Component { symbol, index, .. } => *state.symbols[symbol].get(index),
            Coordinate::Azimuth => n[1].atan2(n[0]),
            Coordinate::Polar => n[2].clamp(-1.0, 1.0).acos(),
        })
        .collect()
}

fn to_state(
    sampler: &Sampler<'_>,
    coords: &[Coordinate],
    template: &State,
    x: &[f64],
) -> Result<State, Diagnostic> {
    let mut symbols = template.symbols.clone();
    let mut n = template.n.clone();
    let (mut azimuth, mut polar) = (None, None);
    for (c, &v) in coords.iter().zip(x) {
        match c {
            Coordinate::Component { symbol, index, .. } => {
                if let Some(t) = symbols.get_mut(symbol) {
                    *t.get_mut(index) = v;
                }
            }
            Coordinate::Azimuth => azimuth = Some(v),
            Coordinate::Polar => polar = Some(v),
        }
    }
    if let Some(phi) = azimuth {
        let s = polar.map_or(1.0, f64::sin);
        n[0] = s * phi.cos();
        n[1] = s * phi.sin();
        if let Some(theta) = polar {
            n[2] = theta.cos();
        }
    }
    sampler.complete(symbols, n)
}

/// What the search maximises at a state: the margin, and on a tie the slack of the
/// hypotheses, so that a step that moves away from a hypothesis' boundary without
/// changing the margin is taken. Violations that fill a thin region along a boundary
/// (an implication "F ≤ 0 ⇒ …" broken only where F is close to its bound) are reached
/// by such steps alternating with steps that raise the margin up to the boundary.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Value {
    margin: f64,
    slack: f64,
}

impl Value {
    fn better_than(&self, other: &Value) -> bool {
        self.margin > other.margin || (self.margin == other.margin && self.slack > other.slack)
    }
}

/// States tried near a state where the sides are undefined, and how far each
/// coordinate moves (a fraction of its range).
const NEARBY: usize = 3;

/// Up to [`NEARBY`] states near `state`: every free coordinate moved by a random
/// fraction of [`NEARBY_STEP`] of its range (a range of one value stays put), inside the
/// hypotheses and off the singular set. Sides undefined at `state` but defined at one
/// of them are undefined there only on a set of measure zero (a zero of a divisor).
pub(crate) fn nearby(
    sampler: &mut Sampler<'_>,
    state: &State,
    extra: &[Constraint],
) -> Result<Vec<State>, Diagnostic> {
    let coords = coordinates(sampler, &None);
    let x = to_vec(&coords, state);
    let mut out = Vec::new();
    for _ in 0..NEARBY {
        let y: Vec<f64> = coords
            .iter()
            .zip(&x)
            .map(|(c, &v)| {
                let (lo, hi) = c.bounds();
                (v + NEARBY_STEP * (hi - lo) * sampler.rng.uniform()).clamp(lo, hi)
            })
            .collect();
        let s = to_state(sampler, &coords, state, &y)?;
        if sampler.in_ranges(&s)
            && sampler.satisfies(&s, &sampler.sampling.given)?
            && sampler.satisfies(&s, extra)?
            && !sampler.singular(&s)?
        {
            out.push(s);
        }
    }
    Ok(out)
}

/// Searches for the state of largest `margin` (positive: the statement is violated),
/// starting from `worst` (the worst random samples) and from the centre and corners of
/// the sampled box, within `budget` evaluations in all. `margin` answers `None` when the
/// state violates the statement outright (the search stops there). `relevant` lists the
/// components the statement reads (`None`: all).
pub(crate) fn worst_case(
    sampler: &mut Sampler<'_>,
    worst: &[State],
    extra: &[Constraint],
    relevant: Option<BTreeSet<(String, Vec<usize>)>>,
    budget: usize,
    margin: &mut Margin<'_>,
) -> Result<SearchResult, Diagnostic> {
    let coords = coordinates(sampler, &relevant);
    let mut result = SearchResult {
        starts: 0,
        evaluations: 0,
        worst: f64::NEG_INFINITY,
        worst_state: None,
        violation: None,
    };
    let Some(template) = worst.first().cloned() else {
        return Ok(result);
    };
    // Starting points: the worst samples, the centre of the box, its two extreme
    // corners and random corners (the normal as in the worst sample).
    let mut starts: Vec<Vec<f64>> = worst.iter().map(|s| to_vec(&coords, s)).collect();
    let base = to_vec(&coords, &template);
    let corner = |pick: &mut dyn FnMut(usize) -> Option<bool>| -> Vec<f64> {
        coords
            .iter()
            .enumerate()
            .map(|(k, c)| match (c, pick(k)) {
                (Coordinate::Component { lo, hi, .. }, Some(high)) => {
                    if high {
                        *hi
                    } else {
                        *lo
                    }
                }
                (Coordinate::Component { lo, hi, .. }, None) => (lo + hi) / 2.0,
                _ => base[k],
            })
            .collect()
    };
    starts.push(corner(&mut |_| None));
    starts.push(corner(&mut |_| Some(false)));
    starts.push(corner(&mut |_| Some(true)));
    for _ in 0..RANDOM_CORNERS {
        let rng = &mut sampler.rng;
        starts.push(corner(&mut |_| Some(rng.uniform() >= 0.0)));
    }
    // Points on the boundary of the hypotheses, by bisection between a worst sample and
    // a random state outside them: a violation that fills a thin region along a
    // boundary is reached from there (see [`Value`]).
    let given = &sampler.sampling.given;
    if !given.is_empty() || !extra.is_empty() {
        for b in 0..BOUNDARY_STARTS {
            let mut outside = None;
            for _ in 0..BOUNDARY_DRAWS {
                let s = sampler.draw()?;
                if !(sampler.satisfies(&s, given)? && sampler.satisfies(&s, extra)?) {
                    outside = Some(to_vec(&coords, &s));
                    break;
                }
            }
            let Some(mut out) = outside else { break };
            let mut inside = to_vec(&coords, &worst[b % worst.len()]);
            for _ in 0..BISECTIONS {
                let mid: Vec<f64> = inside
                    .iter()
                    .zip(&out)
                    .map(|(a, c)| 0.5 * (a + c))
                    .collect();
                let state = to_state(sampler, &coords, &template, &mid)?;
                if sampler.satisfies(&state, given)? && sampler.satisfies(&state, extra)? {
                    inside = mid;
                } else {
                    out = mid;
                }
            }
            starts.push(inside);
        }
    }
    let per_start = budget / starts.len().max(1);
    let sampler = &*sampler;
    // The points visited, by the bits of their coordinates: a pattern search steps back
    // to the point it came from after every improvement. A revisit counts as an
    // evaluation, as it did when it was computed again; its margin is the one already
    // found (the margin is a function of the state, and what it records — quadrature
    // accuracy — is a maximum), and it cannot raise the worst margin found so far.
    let mut seen: HashMap<Vec<u64>, Option<Value>> = HashMap::default();
    // A state inside the hypotheses and off the singular set, with its margin and the
    // hypotheses' slack; `None` for a point the search may not visit.
    let mut visit = |x: &[f64], result: &mut SearchResult| -> Result<Option<Value>, Diagnostic> {
        sampler.time_left()?;
        super::watch::progress("search", result.evaluations, budget);
        let key: Vec<u64> = x.iter().map(|v| v.to_bits()).collect();
        if let Some(&known) = seen.get(&key) {
            if known.is_some() {
                result.evaluations += 1;
            }
            return Ok(known);
        }
        let state = to_state(sampler, &coords, &template, x)?;
        let slack = match (
            sampler.slack(&state, &sampler.sampling.given)?,
            sampler.slack(&state, extra)?,
        ) {
            (Some(a), Some(b)) if sampler.in_ranges(&state) && !sampler.singular(&state)? => {
                a.min(b)
            }
            _ => {
                seen.insert(key, None);
                return Ok(None);
            }
        };
        result.evaluations += 1;
        let m = margin(sampler, &state)?;
        let value = m.unwrap_or(f64::INFINITY);
        if value > result.worst || result.worst_state.is_none() {
            result.worst = value;
            result.worst_state = Some(state.clone());
        }
        let value = Value {
            margin: value,
            slack,
        };
        match m {
            // The search stops here: never revisited.
            None => result.violation = Some(state),
            Some(_) => {
                seen.insert(key, Some(value));
            }
        }
        Ok(Some(value))
    };
    for start in starts {
        let spent = result.evaluations;
        let Some(mut f) = visit(&start, &mut result)? else {
            continue;
        };
        result.starts += 1;
        let mut x = start;
        let mut step = FIRST_STEP;
        while result.violation.is_none()
            && result.evaluations - spent < per_start
            && step > LAST_STEP
        {
            let mut improved = false;
            for k in 0..coords.len() {
                if result.evaluations - spent >= per_start {
                    break;
                }
                let (lo, hi) = coords[k].bounds();
                for sign in [1.0, -1.0] {
                    let mut y = x.clone();
                    y[k] = (x[k] + sign * step * (hi - lo)).clamp(lo, hi);
                    if y[k] == x[k] {
                        continue;
                    }
                    if let Some(fy) = visit(&y, &mut result)? {
                        if fy.better_than(&f) {
                            (x, f, improved) = (y, fy, true);
                            break;
                        }
                    }
                    if result.violation.is_some() {
                        return Ok(result);
                    }
                }
            }
            if !improved {
                step /= 2.0;
            }
        }
        if result.violation.is_some() {
            break;
        }
    }
    Ok(result)
}

/// The components read by the claim's expressions through their compiled tapes, or
/// `None` when some expression is interpreted (then every component counts).
pub(crate) fn components_read<'n>(
    sampler: &Sampler<'_>,
    nodes: impl IntoIterator<Item = &'n crate::lang::Node>,
) -> Option<BTreeSet<(String, Vec<usize>)>> {
    let mut out = BTreeSet::new();
    for node in nodes {
        out.extend(sampler.tape(node)?.inputs_read().into_iter().cloned());
    }
    // Substitutions read their own right sides.
    for sub in sampler
        .parametrisation
        .substituted(&sampler.check.assumptions)
    {
        out.extend(sampler.tape(sub.body)?.inputs_read().into_iter().cloned());
    }
    Some(out)
}
