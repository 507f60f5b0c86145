//! The random states of the sampled strategies: drawing them (ranges, assumptions,
//! hypotheses, singular sets), evaluating expressions at them (compiled tapes, the
//! interpreter as fallback), and describing them in counterexamples.

use super::finding::SampledState;
use super::random::Rng;
use crate::algebra::{assignments, Tensor};
use crate::derivation::parametrisation::{product_value, Parametrisation};
use crate::derivation::{Check, Constraint, Expression, Reads, Relation, Sampling};
use crate::digits::{self, significant};
use crate::eval::quadrature::{Level, Quadrature};
use crate::eval::real::{Labeled, RealEnv, RealError};
use crate::eval::state::State;
use crate::eval::tape::Tape;
use crate::lang::{Decls, Diagnostic, Node};
use crate::tolerance::{RANGE_TOL, SINGULAR_EPS, TOL};
use num_dual::DualNum;
use rustc_hash::FxHashMap as HashMap;
use std::cell::{Cell, RefCell};
use std::collections::{BTreeMap, BTreeSet};
use std::rc::Rc;

/// Draws allowed per accepted sample before the hypotheses are judged too narrow.
const MAX_DRAWS_PER_SAMPLE: usize = 100;

/// Halvings that find how far a draw may be scaled toward the origin before a
/// constraint's even power loses its root (to 2^-40 of the draw).
const BISECTIONS: usize = 40;

pub(crate) fn located(e: &Expression, r: RealError) -> Diagnostic {
    e.origin.diagnostic(r.span, r.message)
}

pub(crate) struct Sampler<'a> {
    pub(crate) decls: &'a Decls,
    pub(crate) check: &'a Check,
    pub(crate) sampling: &'a Sampling,
    /// Compiled tapes of the expressions evaluated at every sample, keyed by node
    /// address (`None`: not compilable, the interpreter is used).
    pub(crate) tapes: RefCell<HashMap<usize, Option<Rc<Tape>>>>,
    pub(crate) rng: Rng,
    /// Where errors about the sampling as a whole point (the statement's first
    /// expression).
    pub(crate) anchor: &'a Expression,
    /// The claim's assumptions, solved once.
    pub(crate) parametrisation: Parametrisation,
    /// What the adaptive averages of the last evaluations reported, at the accuracy
    /// the decision is made at and at the coarser one it is compared with.
    pub(crate) fine: Quadrature,
    pub(crate) coarse: Quadrature,
    pub(crate) arbiter: Quadrature,
    /// The first states drawn, with the values of `recording`'s expressions, kept for
    /// `explain` (nothing is kept unless [`Sampler::record`] asked for it).
    recording: Option<(usize, Vec<Expression>, &'a Sink)>,
    /// What the statement reads: a described state shows only these symbols.
    reads: Reads,
    /// Samples drawn so far (for progress).
    drawn: usize,
    /// States whose floating-point violation lay within the sides' interval
    /// enclosures (see [`crate::eval::interval`]).
    pub(crate) within_rounding: Cell<usize>,
}

/// Where a sampled decision keeps the states it drew, for `explain`.
pub type Sink = RefCell<Vec<SampledState>>;

/// How many drawn states a recorded decision keeps.
pub const RECORDED_STATES: usize = 3;

impl<'a> Sampler<'a> {
    pub(crate) fn new(
        decls: &'a Decls,
        check: &'a Check,
        sampling: &'a Sampling,
        anchor: &'a Expression,
    ) -> Result<Self, Diagnostic> {
        Ok(Sampler {
            decls,
            check,
            sampling,
            tapes: RefCell::new(HashMap::default()),
            rng: Rng::new(sampling.seed),
            anchor,
            parametrisation: Parametrisation::new(decls, &check.defs, &check.assumptions)?,
            fine: Quadrature::new(Level::Fine),
            coarse: Quadrature::new(Level::Coarse),
            arbiter: Quadrature::new(Level::Arbiter),
            recording: None,
            reads: check.reads(),
            drawn: 0,
            within_rounding: Cell::new(0),
        })
    }

    /// An error once the claim's time limit has passed (`watch`): the decision stops,
    /// and `check::decide` makes the claim undecided.
    pub(crate) fn time_left(&self) -> Result<(), Diagnostic> {
        super::watch::check().map_err(|_| {
            self.error(
                "the per-claim time limit has passed".into(),
                "raise --time-limit",
            )
        })
    }

    pub(crate) fn error(&self, message: String, help: &str) -> Diagnostic {
        self.anchor
            .origin
            .diagnostic(self.anchor.node.span, message)
            .with_help(help)
    }

    pub(crate) fn env<T: DualNum<Primitive = f64>>(
        &self,
        symbols: HashMap<String, Tensor<T>>,
    ) -> RealEnv<'a, T> {
        RealEnv::new(self.decls, &self.check.defs, symbols)
    }

    pub(crate) fn tape(&self, node: &Node) -> Option<Rc<Tape>> {
        self.tapes
            .borrow_mut()
            .entry(node as *const Node as usize)
            .or_insert_with(|| {
                Tape::compile(self.decls, &self.check.defs, node)
                    .ok()
                    .map(Rc::new)
            })
            .clone()
    }

    /// `node` at the given symbol values and normal: by its compiled tape, or by the
    /// interpreter when it has none; adaptive averages at the fine accuracy.
    pub(crate) fn eval<T: DualNum<Primitive = f64>>(
        &self,
        symbols: &HashMap<String, Tensor<T>>,
        node: &Node,
        n: &[f64],
    ) -> Result<Labeled<T>, RealError> {
        self.eval_at(symbols, node, n, Level::Fine)
    }

    /// As [`Sampler::eval`], adaptive averages at the given level and reported to its
    /// record ([`Sampler::fine`], [`Sampler::coarse`] or [`Sampler::arbiter`]).
    pub(crate) fn eval_at<T: DualNum<Primitive = f64>>(
        &self,
        symbols: &HashMap<String, Tensor<T>>,
        node: &Node,
        n: &[f64],
        level: Level,
    ) -> Result<Labeled<T>, RealError> {
        let quad = match level {
            Level::Fine => &self.fine,
            Level::Coarse => &self.coarse,
            Level::Arbiter => &self.arbiter,
        };
        match self.tape(node) {
            Some(tape) => {
                let inputs: Vec<T> = tape.gather(
                    |s| symbols.get(s),
                    |x: Option<&T>| x.map_or_else(|| T::from(f64::NAN), T::clone),
                );
                tape.eval(&inputs, n, quad)
            }
            None => {
                let mut env = self.env(symbols.clone());
                env.quadrature = Quadrature::new(level);
                let value = env.eval(node, n);
                quad.absorb(&env.quadrature);
                value
            }
        }
    }

    /// The expression evaluated by the interpreter, never the tape (the second
    /// evaluation of a counterexample, `reverify`), adaptive averages at the fine level.
    pub(crate) fn interpret(
        &self,
        symbols: &HashMap<String, Tensor<f64>>,
        node: &Node,
        n: &[f64],
    ) -> Result<Labeled<f64>, RealError> {
        let mut env = self.env(symbols.clone());
        env.quadrature = Quadrature::new(Level::Fine);
        env.eval(node, n)
    }

    /// The range of every component of `symbol`.
    pub(crate) fn range(&self, symbol: &str) -> (f64, f64) {
        self.sampling
            .ranges
            .get(symbol)
            .copied()
            .unwrap_or((-1.0, 1.0))
    }

    /// Whether every component of a symbol with a declared range that the assumptions
    /// compute from others (`s` in `C_11 = t^2`, `C_11 = s`) lies in it, as the drawn
    /// ones do: a range says where the symbol's values lie, so a state that puts a
    /// computed component outside it is no state of the claim. (A component fixed to a
    /// constant is the assumption's business, not the range's.)
    pub(crate) fn in_ranges(&self, state: &State) -> bool {
        use crate::derivation::parametrisation::Constrained;
        let d = self.decls.dim;
        // A polynomial constraint whose root does not exist at the drawn values (an
        // even power of a negative number) leaves no state.
        if !self.parametrisation.solved().is_empty() {
            let value = |(s, idx): &(String, Vec<usize>)| {
                state.symbols.get(s).map_or(f64::NAN, |t| *t.get(idx))
            };
            if self.parametrisation.residual(value) > TOL {
                return false;
            }
        }
        self.sampling.ranges.iter().all(|(name, &(lo, hi))| {
            let Some(t) = state.symbols.get(name) else {
                return true;
            };
            let slack = |b: f64| RANGE_TOL * (1.0 + b.abs());
            assignments(d, t.rank()).all(|idx| {
                let x = *t.get(&idx);
                self.parametrisation.constrained(name, &idx) != Constrained::Dependent
                    || (lo - slack(lo) <= x && x <= hi + slack(hi))
            })
        })
    }

    pub(crate) fn draw(&mut self) -> Result<State, Diagnostic> {
        let d = self.decls.dim;
        let mut symbols = HashMap::default();
        for (name, &rank) in &self.decls.symbols {
            let (lo, hi) = self.range(name);
            let rng = &mut self.rng;
            symbols.insert(
                name.clone(),
                Tensor::from_fn(d, rank, |_| lo + (hi - lo) * (rng.uniform() + 1.0) / 2.0),
            );
        }
        self.toward_constraints(&mut symbols);
        let n = self.rng.unit_normal(self.decls);
        self.complete(symbols, n)
    }

    /// Draws that a polynomial constraint's even power cannot meet (`N_33² = 1 − …`
    /// negative) moved toward the origin: the components its value reads are scaled by
    /// a random fraction of the largest factor, found by bisection, at which the value is
    /// still ≥ 0. Only free components move, so the draw stays a draw of them.
    fn toward_constraints(&mut self, symbols: &mut HashMap<String, Tensor<f64>>) {
        for s in self.parametrisation.solved() {
            if s.power % 2 == 1 {
                continue;
            }
            let read: BTreeSet<&(String, Vec<usize>)> = s
                .value
                .iter()
                .flat_map(|(p, _)| p.iter().map(|(c, _)| c))
                .collect();
            let original: Vec<f64> = read
                .iter()
                .map(|(n, i)| symbols.get(n).map_or(f64::NAN, |t| *t.get(i)))
                .collect();
            let value_at = |lambda: f64| {
                let at = |c: &(String, Vec<usize>)| {
                    read.iter().position(|r| *r == c).map_or_else(
                        || symbols.get(&c.0).map_or(f64::NAN, |t| *t.get(&c.1)),
                        |k| lambda * original[k],
                    )
                };
                s.value.iter().fold(0.0, |acc, (p, q)| {
                    acc + q.to_f64() * product_value(p, 1.0, at)
                })
            };
            let origin = value_at(0.0);
            if value_at(1.0) >= 0.0 || origin.is_nan() || origin < 0.0 {
                continue;
            }
            let (mut inside, mut outside) = (0.0, 1.0);
            for _ in 0..BISECTIONS {
                let mid = 0.5 * (inside + outside);
                if value_at(mid) >= 0.0 {
                    inside = mid;
                } else {
                    outside = mid;
                }
            }
            let lambda = inside * (self.rng.uniform() + 1.0) / 2.0;
            for (k, (n, i)) in read.iter().enumerate() {
                if let Some(t) = symbols.get_mut(n) {
                    *t.get_mut(i) = lambda * original[k];
                }
            }
        }
    }

    /// A state from values of the symbols (only the free components matter) and a
    /// normal: the constrained components and substitutions set by the assumptions.
    pub(crate) fn complete(
        &self,
        symbols: HashMap<String, Tensor<f64>>,
        n: Vec<f64>,
    ) -> Result<State, Diagnostic> {
        let mut env = self.env(symbols);
        env.assume(&self.parametrisation, &self.check.assumptions, &n)
            .map_err(|e| {
                self.error(
                    format!(
                        "an assumption cannot be evaluated at a random state: {}",
                        e.message
                    ),
                    "check the assumptions of this claim",
                )
            })?;
        Ok(State {
            symbols: env.symbols,
            n,
        })
    }

    /// Checks that a state satisfies every assumption before it is reported: the
    /// assumed equations (not the solution that produced the state) and every
    /// substitution. A violation is a bug in the checker, never a verdict.
    pub(crate) fn verify_state(&self, state: &State) -> Result<(), Diagnostic> {
        let p = &self.parametrisation;
        let value = |(s, idx): &(String, Vec<usize>)| {
            state.symbols.get(s).map_or(f64::NAN, |t| *t.get(idx))
        };
        let mut ok = p.residual(value) <= TOL;
        for sub in p.substituted(&self.check.assumptions) {
            let (symbol, formal) = (sub.symbol, sub.formal);
            let Ok(Labeled {
                labels: ls,
                tensor: t,
            }) = self.eval(&state.symbols, sub.body, &state.n)
            else {
                ok = false;
                continue;
            };
            let perm: Vec<usize> = formal
                .iter()
                .map(|c| ls.iter().position(|x| x == c).unwrap_or(0))
                .collect();
            let expected = t.permuted(&perm);
            let actual = &state.symbols[symbol];
            ok &= assignments(self.decls.dim, formal.len())
                .all(|idx| relation_holds(Relation::Eq, *actual.get(&idx), *expected.get(&idx)).0);
        }
        if ok {
            Ok(())
        } else {
            Err(self.error(
                "internal error: a sampled state violates the assumptions; no verdict is given"
                    .into(),
                "please report this with the derivation file",
            ))
        }
    }

    pub(crate) fn scalar(&self, state: &State, e: &Expression) -> Result<f64, Diagnostic> {
        let v = self
            .eval(&state.symbols, &e.node, &state.n)
            .map_err(|r| located(e, r))?;
        Ok(v.tensor.into_scalar().unwrap_or(f64::NAN))
    }

    /// Whether the state satisfies every constraint. A constraint evaluated through
    /// adaptive averages must hold with the averages' error bound to spare, so that
    /// their error cannot put a state inside a hypothesis it violates.
    pub(crate) fn satisfies(&self, state: &State, cs: &[Constraint]) -> Result<bool, Diagnostic> {
        Ok(self.slack(state, cs)?.is_some())
    }

    /// How far inside the hypotheses `cs` the state is: the smallest relative spare of
    /// any (infinite when there are none), or `None` when one is violated (as
    /// [`Sampler::satisfies`] judges).
    pub(crate) fn slack(
        &self,
        state: &State,
        cs: &[Constraint],
    ) -> Result<Option<f64>, Diagnostic> {
        let mut least = f64::INFINITY;
        for c in cs {
            self.fine.reset();
            let (l, r) = (self.scalar(state, &c.lhs)?, self.scalar(state, &c.rhs)?);
            let (ok, residual) = relation_holds(c.relation, l, r);
            let spare = self.adaptive_error(l, r);
            if !ok || residual + spare > TOL {
                return Ok(None);
            }
            least = least.min(-(residual + spare));
        }
        Ok(Some(least))
    }

    /// Whether the state lies on the singular set (within the error bound of any
    /// adaptive average the singular expression takes).
    pub(crate) fn singular(&self, state: &State) -> Result<bool, Diagnostic> {
        match &self.sampling.singular {
            None => Ok(false),
            Some(e) => {
                self.fine.reset();
                let v = self.scalar(state, e)?;
                Ok(v.abs() < SINGULAR_EPS + self.adaptive_error(v, 0.0))
            }
        }
    }

    /// The relative error bound, on the scale of `l` and `r`, of the adaptive averages
    /// taken since [`Sampler::fine`] was reset (0 when there were none).
    fn adaptive_error(&self, l: f64, r: f64) -> f64 {
        if self.fine.used() {
            self.fine.worst_error() / (1.0 + l.abs() + r.abs())
        } else {
            0.0
        }
    }

    /// The next state satisfying the hypotheses (and `extra`), or an error when they
    /// reject almost every draw. `excluded` counts singular states skipped.
    /// Keeps the first [`RECORDED_STATES`] states drawn, with the values of `exprs`
    /// there, in `sink` (when there is one).
    pub(crate) fn record(&mut self, sink: Option<&'a Sink>, exprs: Vec<Expression>) {
        self.recording = sink.map(|s| (RECORDED_STATES, exprs, s));
    }

    fn keep(&mut self, state: &State) {
        let Some((k, exprs, sink)) = &self.recording else {
            return;
        };
        if sink.borrow().len() >= *k {
            return;
        }
        let values = exprs
            .iter()
            .map(|e| {
                let v = self.scalar(state, e).ok().filter(|v| !v.is_nan());
                (e.text.trim().to_owned(), v)
            })
            .collect();
        sink.borrow_mut().push(SampledState {
            point: self.describe(state),
            values,
        });
    }

    pub(crate) fn next(
        &mut self,
        extra: &[Constraint],
        excluded: &mut usize,
    ) -> Result<State, Diagnostic> {
        self.time_left()?;
        self.drawn += 1;
        super::watch::progress("samples", self.drawn, self.sampling.samples);
        for _ in 0..MAX_DRAWS_PER_SAMPLE {
            let s = self.draw()?;
            if !self.in_ranges(&s)
                || !self.satisfies(&s, &self.sampling.given)?
                || !self.satisfies(&s, extra)?
            {
                continue;
            }
            if self.singular(&s)? {
                *excluded += 1;
                continue;
            }
            self.keep(&s);
            return Ok(s);
        }
        Err(self.error(
            format!("the hypotheses accept fewer than 1 in {MAX_DRAWS_PER_SAMPLE} random states"),
            "widen `ranges` or relax `given`/`domain`",
        ))
    }
}

/// Whether `l rel r` holds within tolerance, and the relative residual (for `=`, the
/// relative difference; for inequalities, the relative violation, ≤ 0 when satisfied).
pub(crate) fn relation_holds(rel: Relation, l: f64, r: f64) -> (bool, f64) {
    if !l.is_finite() || !r.is_finite() {
        return (false, f64::INFINITY);
    }
    let residual = rel.violation(l, r) / (1.0 + l.abs() + r.abs());
    (residual <= TOL, residual)
}

impl Sampler<'_> {
    /// The state as a counterexample shows it: the nonzero components of the symbols
    /// the statement reads (never every declared symbol), and the normal when it
    /// reads the normal, to [`digits::POINT`] significant digits.
    pub(crate) fn describe(&self, state: &State) -> BTreeMap<String, String> {
        let mut out = BTreeMap::new();
        for (name, t) in &state.symbols {
            if !self.reads.symbols.contains(name) {
                continue;
            }
            let rank = t.rank();
            for idx in assignments(self.decls.dim, rank) {
                let v = *t.get(&idx);
                if v != 0.0 {
                    let key = if rank == 0 {
                        name.clone()
                    } else {
                        format!(
                            "{name}_{}",
                            idx.iter().map(|i| (i + 1).to_string()).collect::<String>()
                        )
                    };
                    out.insert(key, significant(v, digits::POINT));
                }
            }
        }
        if self.decls.normal.is_some() && self.reads.normal {
            let n: Vec<String> = state
                .n
                .iter()
                .map(|&x| significant(x, digits::POINT))
                .collect();
            out.insert("n".into(), format!("({})", n.join(", ")));
        }
        out
    }
}
