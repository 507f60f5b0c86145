//! Expressions compiled once per claim to a flat tape of scalar operations, evaluated
//! at every sample: the sampled strategies' hot path.
//!
//! [`RealEnv`](super::real::RealEnv) interprets the expression tree at every sample and
//! every quadrature node, allocating tensors as it goes; for a gradient in eighteen
//! variables through a sphere quadrature that was seconds per claim. Here the same
//! semantics — contraction over summed letters, memoised definitions, `avg` as a sum
//! over the nodes of a rule exact for the argument's degree in n, `maxn` as a grid with
//! golden-section refinement — are unrolled into straight-line code over component
//! values: constants are folded (δ, ε and structural zeros vanish), repeated
//! subexpressions are shared, and evaluation is one pass over a `Vec` generic over the
//! scalar (`f64` or num-dual numbers).
//!
//! Contraction is the one [`einsum`](crate::algebra::einsum) over op ids, the same code the interpreter runs
//! over numbers; `tests/tape.rs` holds the tape to the interpreter on every sampled claim
//! of the paper, so the compiler's folding, sharing and unrolling are checked against
//! plain evaluation. Errors keep the interpreter's messages and spans (division by
//! zero, square root of a negative number).

use super::labeled::Labeled;
use super::quadrature::Quadrature;
use super::real::{RealError, MAXN_GRID};
use super::walk::{self, Derivative, DynCalculus, Normals, Ring};
use crate::algebra::einsum::Arithmetic;
use crate::algebra::{assignments, Tensor};
use crate::derivation::Definition;
use crate::kernel::Rational;
use crate::lang::parser::{Func, Func2};
use crate::lang::{Decls, Node, Span};
use num_dual::DualNum;
use rustc_hash::FxHashMap as HashMap;

/// One scalar operation; operands are indices of earlier operations.
#[derive(Clone, Debug, PartialEq)]
enum Op {
    /// Component `k` of the inputs (every symbol component, in [`Tape::inputs`] order).
    Input(usize),
    /// Component `k` of the sample's normal.
    Normal(usize),
    /// The normal at angle θ inside a `maxn` (component `k` of (cos θ, sin θ, 0)).
    Angle(usize),
    Const(f64),
    Add(usize, usize),
    Mul(usize, usize),
    Neg(usize),
    Div(usize, usize, Span),
    Powi(usize, i32),
    /// A scalar function ([`super::real::elementary`]); the span locates its domain
    /// errors.
    Apply(Func, usize, Span),
    /// A function of two numbers ([`super::real::elementary2`]).
    Apply2(Func2, usize, usize, Span),
    /// max over θ of the sub-tape's output (index into [`Tape::maxn`]).
    MaxN(usize, Span),
    /// Component `c` (in [`assignments`] order) of the adaptive average of the
    /// sub-tape `k` of [`Tape::avgs`] (an argument that is not a polynomial in n).
    Avg(usize, usize),
}

/// A hashable key for sharing equal operations.
#[derive(Clone, PartialEq, Eq, Hash)]
enum Key {
    Input(usize),
    Normal(usize),
    Angle(usize),
    Const(u64),
    Bin(u8, usize, usize),
    Un(u8, usize, i32),
}

/// A compiled expression: its free-index labels, the op index of each component.
#[derive(Clone, Debug)]
pub struct Tape {
    ops: Vec<Op>,
    /// Symbol components in input order: (symbol, component index).
    pub inputs: Vec<(String, Vec<usize>)>,
    /// The runs of [`Tape::inputs`] that belong to one symbol, as ranges, each with
    /// whether it lists every component in storage order: each symbol is looked up
    /// once per sample, not compared with every input's name.
    runs: Vec<(std::ops::Range<usize>, bool)>,
    labels: Vec<char>,
    outputs: Tensor<usize>,
    /// Sub-tapes of `maxn` arguments: their `Angle` ops stand for the normal.
    maxn: Vec<Tape>,
    /// Sub-tapes of `avg` arguments that are not polynomials in n, averaged by
    /// adaptive quadrature: their `Angle` ops stand for the normal.
    avgs: Vec<Tape>,
    /// Whether the normal lies in the 1-2 plane (averages are then over the circle).
    in_plane: bool,
    /// The ops that depend on the angle (`Angle`, and through operands; nested `maxn`
    /// and `avg` conservatively), in order: a sub-tape evaluated over many angles or
    /// points of a rule computes the others once ([`Tape::max_over_angle`],
    /// [`Tape::average`]).
    varying: Vec<usize>,
    /// The maximisers found by [`Tape::max_over_angle`], by the bits of the values the
    /// angle does not change: a search revisits states (a step clamped to the box, a
    /// start that is also a sample), and one maximisation costs hundreds of angles.
    maxima: Maxima,
}

/// A memo of `maxn` maximisers: a pure function's results, so sharing it between
/// clones and threads changes no value.
#[derive(Clone, Debug, Default)]
struct Maxima(std::sync::Arc<std::sync::Mutex<MaximaByKey>>);

/// Maximisers (θ, value) by the bits of a `maxn` argument's angle-invariant values.
type MaximaByKey = HashMap<Vec<u64>, (f64, f64)>;

/// The most a tape's memo of maximisers holds, in key words (8 MB): each key has one
/// word per op of the sub-tape, so a large sub-tape remembers fewer states.
const MAXIMA_WORDS: usize = 1 << 20;

impl Maxima {
    fn get(&self, key: &[u64]) -> Option<(f64, f64)> {
        self.0
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .get(key)
            .copied()
    }

    fn insert(&self, key: Vec<u64>, best: (f64, f64)) {
        let mut memo = self.0.lock().unwrap_or_else(|e| e.into_inner());
        if (memo.len() + 1) * key.len() <= MAXIMA_WORDS {
            memo.insert(key, best);
        }
    }
}

/// Why an expression was not compiled (the caller falls back to the interpreter).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("not compiled: {0}")]
pub struct Unsupported(pub String);

struct Compiler<'a> {
    decls: &'a Decls,
    defs: &'a [Definition],
    ops: Vec<Op>,
    /// Common subexpressions: looked up once per op pushed, so hashed by FxHash (the
    /// lookup order and the ops pushed do not depend on the hasher).
    shared: HashMap<Key, usize>,
    symbols: HashMap<String, Tensor<usize>>,
    inputs: Vec<(String, Vec<usize>)>,
    memo: HashMap<(String, Vec<usize>), Tensor<usize>>,
    degrees: HashMap<String, Option<usize>>,
    maxn: Vec<Tape>,
    avgs: Vec<Tape>,
    /// Ops created so far; compilation stops beyond this (a hostile input).
    budget: usize,
}

/// Largest number of operations a tape may hold.
pub const MAX_OPS: usize = 2_000_000;

impl Tape {
    /// Compiles `node` over the given symbols (every component of each becomes an
    /// input, in `decls.symbols` order) and definitions.
    pub fn compile(decls: &Decls, defs: &[Definition], node: &Node) -> Result<Tape, Unsupported> {
        let mut c = Compiler::new(decls, defs, MAX_OPS);
        let mut names: Vec<(&String, &usize)> = decls.symbols.iter().collect();
        names.sort();
        for (name, &rank) in names {
            let t = Tensor::from_fn(decls.dim, rank, |idx| {
                let k = c.inputs.len();
                c.inputs.push((name.clone(), idx.to_vec()));
                c.push(Op::Input(k))
            });
            c.symbols.insert(name.clone(), t);
        }
        let n: Vec<usize> = (0..decls.dim).map(|k| c.push(Op::Normal(k))).collect();
        let outputs = c.eval(node, &n)?;
        Ok(Tape {
            ops: c.ops,
            runs: symbol_runs(&c.inputs, decls.dim),
            inputs: c.inputs,
            labels: node.free_letters(),
            outputs,
            maxn: c.maxn,
            avgs: c.avgs,
            in_plane: decls.normal_in_plane,
            varying: Vec::new(),
            maxima: Maxima::default(),
        })
    }

    pub fn len(&self) -> usize {
        self.ops.len()
    }

    /// The values of [`Tape::inputs`] from a map of symbol values: `value` of each
    /// component (`None` when the symbol has no value). Each symbol is looked up once;
    /// a run of inputs that lists every component in storage order reads the value's
    /// components as they are stored.
    pub fn gather<'s, U: 's, T>(
        &self,
        symbol: impl Fn(&str) -> Option<&'s Tensor<U>>,
        value: impl Fn(Option<&U>) -> T,
    ) -> Vec<T> {
        let mut out = Vec::with_capacity(self.inputs.len());
        for (run, whole) in &self.runs {
            let inputs = &self.inputs[run.clone()];
            let t = symbol(&inputs[0].0);
            match t {
                Some(t)
                    if *whole
                        && t.rank() == inputs[0].1.len()
                        && t.components().len() == run.len() =>
                {
                    out.extend(t.components().iter().map(|x| value(Some(x))));
                }
                _ => out.extend(inputs.iter().map(|(_, idx)| value(t.map(|t| t.get(idx))))),
            }
        }
        out
    }

    /// The entries of [`Tape::inputs`] the result depends on: every symbol component
    /// is an input, but folding (δ, ε, a factor 0) leaves many unread.
    pub fn inputs_read(&self) -> Vec<&(String, Vec<usize>)> {
        let mut read = vec![false; self.inputs.len()];
        self.mark_read(&mut read);
        self.inputs
            .iter()
            .zip(read)
            .filter_map(|(input, r)| r.then_some(input))
            .collect()
    }

    /// Marks the inputs reachable from the outputs, through operands and sub-tapes
    /// (which share this tape's input order).
    fn mark_read(&self, read: &mut [bool]) {
        let mut live = vec![false; self.ops.len()];
        for &k in self.outputs.components() {
            live[k] = true;
        }
        for k in (0..self.ops.len()).rev() {
            if !live[k] {
                continue;
            }
            match self.ops[k] {
                Op::Input(i) => read[i] = true,
                Op::Normal(_) | Op::Angle(_) | Op::Const(_) => {}
                Op::Add(a, b) | Op::Mul(a, b) | Op::Div(a, b, _) | Op::Apply2(_, a, b, _) => {
                    live[a] = true;
                    live[b] = true;
                }
                Op::Neg(a) | Op::Powi(a, _) | Op::Apply(_, a, _) => live[a] = true,
                Op::MaxN(t, _) => self.maxn[t].mark_read(read),
                Op::Avg(t, _) => self.avgs[t].mark_read(read),
            }
        }
    }

    pub fn is_empty(&self) -> bool {
        self.ops.is_empty()
    }

    /// The labelled result at `inputs` (one value per entry of [`Tape::inputs`]) and
    /// the sample's normal `n`; adaptive averages are taken at the accuracy of `quad`
    /// and reported to it.
    pub fn eval<T: DualNum<Primitive = f64>>(
        &self,
        inputs: &[T],
        n: &[f64],
        quad: &Quadrature,
    ) -> Result<Labeled<T>, RealError> {
        let vals = self.run(inputs, n, &[], quad)?;
        Ok(Labeled::new(
            self.labels.clone(),
            self.outputs.map(|&k| vals[k].clone()),
        ))
    }

    fn run<T: DualNum<Primitive = f64>>(
        &self,
        inputs: &[T],
        n: &[f64],
        angle: &[f64],
        quad: &Quadrature,
    ) -> Result<Vec<T>, RealError> {
        let mut v: Vec<T> = vec![T::zero(); self.ops.len()];
        self.fill(&mut v, 0..self.ops.len(), inputs, n, angle, quad)?;
        Ok(v)
    }

    /// Evaluates the ops `which` (increasing) into `v`, whose entries for every other
    /// op they read are already computed.
    fn fill<T: DualNum<Primitive = f64>>(
        &self,
        v: &mut [T],
        which: impl IntoIterator<Item = usize>,
        inputs: &[T],
        n: &[f64],
        angle: &[f64],
        quad: &Quadrature,
    ) -> Result<(), RealError> {
        let mut averages: Vec<Option<Vec<T>>> = vec![None; self.avgs.len()];
        for k in which {
            let x = match self.ops[k] {
                Op::Input(k) => inputs[k].clone(),
                Op::Normal(k) => T::from(n[k]),
                Op::Angle(k) => T::from(angle[k]),
                Op::Const(c) => T::from(c),
                Op::Add(a, b) => v[a].clone() + &v[b],
                Op::Mul(a, b) => v[a].clone() * &v[b],
                Op::Neg(a) => -v[a].clone(),
                Op::Div(a, b, span) => {
                    if v[b].re() == 0.0 {
                        return Err(super::real::undefined(span, "division by zero"));
                    }
                    v[a].clone() / &v[b]
                }
                Op::Powi(a, k) => v[a].powi(k),
                Op::Apply(f, a, span) => super::real::elementary(f, v[a].clone())
                    .map_err(|e| super::real::undefined(span, e.to_string()))?,
                Op::Apply2(f, a, b, span) => {
                    super::real::elementary2(f, v[a].clone(), v[b].clone())
                        .map_err(|e| super::real::undefined(span, e.to_string()))?
                }
                Op::MaxN(k, span) => self.maxn[k].max_over_angle(inputs, n, span, quad)?,
                Op::Avg(k, c) => {
                    if averages[k].is_none() {
                        averages[k] = Some(self.avgs[k].average(inputs, n, quad)?);
                    }
                    averages[k].as_ref().expect("computed above")[c].clone()
                }
            };
            v[k] = x;
        }
        Ok(())
    }

    /// The adaptive average over the normal of this `avg` sub-tape's outputs, in
    /// [`assignments`] order.
    ///
    /// The ops that do not depend on the normal (the inputs, and what is formed from
    /// them alone) are evaluated once, and only the others at each point of the rule,
    /// into one buffer: the same operations on the same values as a whole run per
    /// point. Where one of them fails, every point runs the whole tape instead, so that
    /// the error reported is the one the first point's run gives (a varying op before
    /// the failing one may fail first).
    fn average<T: DualNum<Primitive = f64>>(
        &self,
        inputs: &[T],
        n: &[f64],
        quad: &Quadrature,
    ) -> Result<Vec<T>, RealError> {
        let free = self.free_normal_dim(n.len());
        let outputs = |vals: &[T]| -> Vec<T> {
            let components = self.outputs.components();
            components.iter().map(|&k| vals[k].clone()).collect()
        };
        let mut vals = vec![T::zero(); self.ops.len()];
        if self
            .fill(&mut vals, self.invariant(), inputs, n, &[], quad)
            .is_err()
        {
            return quad.average(free, n.len(), &mut |point| {
                Ok(outputs(&self.run(inputs, n, point, quad)?))
            });
        }
        quad.average(free, n.len(), &mut |point| {
            self.fill(
                &mut vals,
                self.varying.iter().copied(),
                inputs,
                n,
                point,
                quad,
            )?;
            Ok(outputs(&vals))
        })
    }

    /// The ops that are not [`Tape::varying`]: those of a `maxn` or `avg` sub-tape that
    /// the angle or the point of the rule does not change, in increasing order.
    fn invariant(&self) -> Vec<usize> {
        let mut varies = vec![false; self.ops.len()];
        for &k in &self.varying {
            varies[k] = true;
        }
        (0..self.ops.len()).filter(|&k| !varies[k]).collect()
    }

    /// The dimension the normal ranges over: 2 for an in-plane normal (recorded at
    /// compilation), else the space's.
    fn free_normal_dim(&self, dim: usize) -> usize {
        if self.in_plane {
            2
        } else {
            dim
        }
    }

    /// The scalar output at angle θ.
    fn at_angle<T: DualNum<Primitive = f64>>(
        &self,
        inputs: &[T],
        n: &[f64],
        theta: f64,
        quad: &Quadrature,
    ) -> Result<T, RealError> {
        let v = self.run(inputs, n, &angle_normal(theta), quad)?;
        Ok(v[*self.outputs.get(&[])].clone())
    }

    /// max over θ, as in `RealEnv::max_over_angle`: the grid, golden-section refinement
    /// of every local maximum in `f64`, then the value at the maximiser (refused for
    /// dual numbers, as there).
    ///
    /// The ops that do not depend on θ are evaluated once; the others over all the
    /// grid's angles at once, and over every refined maximum at once (the golden
    /// sections run in lockstep). Each angle sees the same operations in the same order
    /// as a whole run, so the values are identical; where any evaluation fails, the
    /// angles are evaluated one by one instead, so that the error reported is the one
    /// the first failing angle gives.
    fn max_over_angle<T: DualNum<Primitive = f64>>(
        &self,
        inputs: &[T],
        n: &[f64],
        span: Span,
        quad: &Quadrature,
    ) -> Result<T, RealError> {
        if T::NDERIV > 0 {
            return Err(super::real::maxn_not_differentiated(span));
        }
        let re: Vec<f64> = inputs.iter().map(|x| x.re()).collect();
        let mut fixed = vec![0.0; self.ops.len()];
        self.fill(&mut fixed, self.invariant(), &re, n, &[], quad)?;
        // The maximiser depends only on the ops the angle does not change (the inputs
        // and the normal reach the varying ops through them).
        let key: Vec<u64> = fixed.iter().map(|v| v.to_bits()).collect();
        let best = match self.maxima.get(&key) {
            Some(best) => best,
            None => {
                let lanes = Lanes::new(self, &fixed, n.len());
                match lanes.and_then(|l| l.maximise()) {
                    Some(best) => {
                        self.maxima.insert(key, best);
                        best
                    }
                    None => self.maximise_one_by_one(&fixed, &re, n, span, quad)?,
                }
            }
        };
        self.at_angle(inputs, n, best.0, quad)
    }

    /// The grid and the golden sections one angle at a time (the reference order).
    fn maximise_one_by_one(
        &self,
        fixed: &[f64],
        re: &[f64],
        n: &[f64],
        span: Span,
        quad: &Quadrature,
    ) -> Result<(f64, f64), RealError> {
        let out = *self.outputs.get(&[]);
        let buffer = std::cell::RefCell::new(fixed.to_vec());
        let f = |theta: f64| -> Result<f64, RealError> {
            let mut v = buffer.borrow_mut();
            let angle = angle_normal(theta);
            self.fill(&mut v, self.varying.iter().copied(), re, n, &angle, quad)?;
            Ok(v[out])
        };
        let h = grid_step();
        let mut grid = Vec::with_capacity(MAXN_GRID);
        for k in 0..MAXN_GRID {
            let v = f(k as f64 * h)?;
            if !v.is_finite() {
                return Err(super::real::undefined(
                    span,
                    "maxn(…): the argument is not finite",
                ));
            }
            grid.push(v);
        }
        let mut best = (0.0, f64::NEG_INFINITY);
        for k in local_maxima(&grid) {
            let (theta, v) = super::real::golden_max(&f, k as f64 * h, h)?;
            if v > best.1 {
                best = (theta, v);
            }
        }
        Ok(best)
    }
}

/// The spacing of the `maxn` grid over [0, 2π).
fn grid_step() -> f64 {
    2.0 * std::f64::consts::PI / MAXN_GRID as f64
}

/// The normals at the `maxn` grid's angles, computed once per process.
fn grid_normals() -> &'static [[f64; 3]] {
    static GRID: std::sync::OnceLock<Vec<[f64; 3]>> = std::sync::OnceLock::new();
    GRID.get_or_init(|| {
        (0..MAXN_GRID)
            .map(|k| angle_normal(k as f64 * grid_step()))
            .collect()
    })
}

/// The grid points that are not below either neighbour (the grid is periodic).
fn local_maxima(grid: &[f64]) -> impl Iterator<Item = usize> + '_ {
    let m = grid.len();
    (0..m).filter(move |&k| grid[k] >= grid[(k + m - 1) % m] && grid[k] >= grid[(k + 1) % m])
}

/// A `maxn` sub-tape evaluated at many angles at once: the values of its varying ops,
/// one row of lanes per op, so that each op is dispatched once per batch of angles
/// rather than once per angle. Only for sub-tapes without nested `maxn` or `avg`.
///
/// The rows, the normals and the outputs live in buffers kept across batches (the
/// golden sections ask for a few angles some fifty times per maximum), so that a batch
/// allocates nothing.
struct Lanes {
    /// The varying ops, in order, with their operands resolved.
    ops: Vec<LaneOp>,
    /// Where the output is.
    output: Arg,
    /// The varying ops' values, one row of `width` lanes per op.
    vals: Vec<f64>,
    /// The normals of the current batch.
    angles: Vec<[f64; 3]>,
    /// The output of the current batch.
    out: Vec<f64>,
}

/// An operand of a lane operation, resolved once per maximisation: the row of a varying
/// op, or the value of an op the angle does not change (the same for every lane).
#[derive(Clone, Copy)]
enum Arg {
    Row(usize),
    Fixed(f64),
}

/// A varying op of the sub-tape, its operands resolved ([`Arg`]).
#[derive(Clone, Copy)]
enum LaneOp {
    Angle(usize),
    Add(Arg, Arg),
    Mul(Arg, Arg),
    Neg(Arg),
    Powi(Arg, i32),
    Div(Arg, Arg),
    Apply(Func, Arg),
    Apply2(Func2, Arg, Arg),
}

/// An operand of a lane operation: a row of lanes, or one value for every lane.
#[derive(Clone, Copy)]
enum Operand<'a> {
    Row(&'a [f64]),
    Fixed(f64),
}

impl Operand<'_> {
    fn at(self, lane: usize) -> f64 {
        match self {
            Operand::Row(x) => x[lane],
            Operand::Fixed(x) => x,
        }
    }
}

impl Lanes {
    fn new(tape: &Tape, fixed: &[f64], dim: usize) -> Option<Self> {
        if dim > 3
            || tape
                .varying
                .iter()
                .any(|&k| matches!(tape.ops[k], Op::MaxN(..) | Op::Avg(..)))
        {
            return None;
        }
        let mut row = vec![usize::MAX; tape.ops.len()];
        for (r, &k) in tape.varying.iter().enumerate() {
            row[k] = r;
        }
        let arg = |op: usize| match row[op] {
            usize::MAX => Arg::Fixed(fixed[op]),
            r => Arg::Row(r),
        };
        let ops = tape
            .varying
            .iter()
            .map(|&k| match tape.ops[k] {
                Op::Angle(c) => LaneOp::Angle(c),
                Op::Add(a, b) => LaneOp::Add(arg(a), arg(b)),
                Op::Mul(a, b) => LaneOp::Mul(arg(a), arg(b)),
                Op::Neg(a) => LaneOp::Neg(arg(a)),
                Op::Powi(a, e) => LaneOp::Powi(arg(a), e),
                Op::Div(a, b, _) => LaneOp::Div(arg(a), arg(b)),
                Op::Apply(f, a, _) => LaneOp::Apply(f, arg(a)),
                Op::Apply2(f, a, b, _) => LaneOp::Apply2(f, arg(a), arg(b)),
                Op::Input(_) | Op::Normal(_) | Op::Const(_) | Op::MaxN(..) | Op::Avg(..) => {
                    unreachable!("not varying, or refused above")
                }
            })
            .collect();
        Some(Lanes {
            ops,
            output: arg(*tape.outputs.get(&[])),
            vals: Vec::new(),
            angles: Vec::new(),
            out: Vec::new(),
        })
    }

    /// The output at each angle of `thetas`, or `None` when any evaluation fails (a
    /// domain error, a division by zero) or gives a value that is not finite.
    fn at(&mut self, thetas: &[f64]) -> Option<&[f64]> {
        let mut angles = std::mem::take(&mut self.angles);
        angles.clear();
        angles.extend(thetas.iter().map(|&t| angle_normal(t)));
        let ok = self.fill(&angles);
        self.angles = angles;
        ok.then_some(&self.out[..])
    }

    /// The output at each of the grid's normals, as [`Lanes::at`].
    fn at_grid(&mut self) -> Option<&[f64]> {
        self.fill(grid_normals()).then_some(&self.out[..])
    }

    /// Evaluates the varying ops at `angles` into `self.out`; false when any evaluation
    /// fails or gives a value that is not finite.
    fn fill(&mut self, angles: &[[f64; 3]]) -> bool {
        let w = angles.len();
        // Every row is written in full before it is read, so stale lanes never leak.
        self.vals.resize(self.ops.len() * w, 0.0);
        for (r, op) in self.ops.iter().enumerate() {
            let (done, rest) = self.vals.split_at_mut(r * w);
            let out = &mut rest[..w];
            let operand = |a: Arg| match a {
                Arg::Fixed(x) => Operand::Fixed(x),
                Arg::Row(s) => Operand::Row(&done[s * w..(s + 1) * w]),
            };
            macro_rules! binary {
                ($a:expr, $b:expr, $f:expr) => {
                    match (operand($a), operand($b)) {
                        (Operand::Row(x), Operand::Row(y)) => out
                            .iter_mut()
                            .zip(x.iter().zip(y))
                            .for_each(|(o, (&x, &y))| *o = $f(x, y)),
                        (Operand::Row(x), Operand::Fixed(y)) => {
                            out.iter_mut().zip(x).for_each(|(o, &x)| *o = $f(x, y))
                        }
                        (Operand::Fixed(x), Operand::Row(y)) => {
                            out.iter_mut().zip(y).for_each(|(o, &y)| *o = $f(x, y))
                        }
                        (Operand::Fixed(x), Operand::Fixed(y)) => out.fill($f(x, y)),
                    }
                };
            }
            match *op {
                LaneOp::Angle(c) => out.iter_mut().zip(angles).for_each(|(o, a)| *o = a[c]),
                LaneOp::Add(a, b) => binary!(a, b, |x: f64, y: f64| x + y),
                LaneOp::Mul(a, b) => binary!(a, b, |x: f64, y: f64| x * y),
                LaneOp::Neg(a) => binary!(a, a, |x: f64, _: f64| -x),
                LaneOp::Powi(a, e) => binary!(a, a, |x: f64, _: f64| x.powi(e)),
                LaneOp::Div(a, b) => {
                    let (x, y) = (operand(a), operand(b));
                    for (l, o) in out.iter_mut().enumerate() {
                        let d = y.at(l);
                        if d == 0.0 {
                            return false;
                        }
                        *o = x.at(l) / d;
                    }
                }
                // `abs` is defined everywhere: one pass without the per-lane dispatch.
                LaneOp::Apply(Func::Abs, a) => binary!(a, a, |x: f64, _: f64| x.abs()),
                LaneOp::Apply(f, a) => {
                    let x = operand(a);
                    for (l, o) in out.iter_mut().enumerate() {
                        match super::real::elementary(f, x.at(l)) {
                            Ok(v) => *o = v,
                            Err(_) => return false,
                        }
                    }
                }
                LaneOp::Apply2(f, a, b) => {
                    let (x, y) = (operand(a), operand(b));
                    for (l, o) in out.iter_mut().enumerate() {
                        match super::real::elementary2(f, x.at(l), y.at(l)) {
                            Ok(v) => *o = v,
                            Err(_) => return false,
                        }
                    }
                }
            }
        }
        self.out.clear();
        match self.output {
            Arg::Fixed(x) => self.out.resize(w, x),
            Arg::Row(s) => self.out.extend_from_slice(&self.vals[s * w..(s + 1) * w]),
        }
        self.out.iter().all(|v| v.is_finite())
    }

    /// The grid, then every local maximum refined by golden sections in lockstep (each
    /// lane follows exactly the steps of [`super::real::golden_max`]): the best angle
    /// and value, or `None` when an evaluation fails.
    fn maximise(mut self) -> Option<(f64, f64)> {
        let h = grid_step();
        let grid = self.at_grid()?;
        let centres: Vec<f64> = local_maxima(grid).map(|k| k as f64 * h).collect();
        let g = (5f64.sqrt() - 1.0) / 2.0;
        struct Section {
            lo: f64,
            hi: f64,
            x1: f64,
            x2: f64,
            f1: f64,
            f2: f64,
        }
        let mut sections: Vec<Section> = centres
            .iter()
            .map(|&c| {
                let (lo, hi) = (c - h, c + h);
                Section {
                    lo,
                    hi,
                    x1: hi - g * (hi - lo),
                    x2: lo + g * (hi - lo),
                    f1: 0.0,
                    f2: 0.0,
                }
            })
            .collect();
        let firsts: Vec<f64> = sections.iter().flat_map(|s| [s.x1, s.x2]).collect();
        let values = self.at(&firsts)?;
        for (s, v) in sections.iter_mut().zip(values.chunks(2)) {
            (s.f1, s.f2) = (v[0], v[1]);
        }
        // The sections still wider than the tolerance, each with the end it asks for: at
        // x2 (the low bit set) or at x1.
        let mut asking: Vec<usize> = Vec::with_capacity(sections.len());
        let mut next = Vec::with_capacity(sections.len());
        loop {
            asking.clear();
            next.clear();
            // Each active section moves one end in and asks for one new value.
            for (k, s) in sections.iter_mut().enumerate() {
                // `!(… > …)` rather than `<=`: golden_max's loop test, for every width.
                #[allow(clippy::neg_cmp_op_on_partial_ord)]
                if !(s.hi - s.lo > 1e-12) {
                    continue;
                }
                let upper = s.f1 < s.f2;
                if upper {
                    s.lo = s.x1;
                    s.x1 = s.x2;
                    s.f1 = s.f2;
                    s.x2 = s.lo + g * (s.hi - s.lo);
                    next.push(s.x2);
                } else {
                    s.hi = s.x2;
                    s.x2 = s.x1;
                    s.f2 = s.f1;
                    s.x1 = s.hi - g * (s.hi - s.lo);
                    next.push(s.x1);
                }
                asking.push(k << 1 | usize::from(upper));
            }
            if asking.is_empty() {
                break;
            }
            let values = self.at(&next)?;
            for (&a, &v) in asking.iter().zip(values) {
                let s = &mut sections[a >> 1];
                if a & 1 == 1 {
                    s.f2 = v;
                } else {
                    s.f1 = v;
                }
            }
        }
        let ends: Vec<f64> = sections
            .iter()
            .zip(&centres)
            .flat_map(|(s, &c)| [(s.lo + s.hi) / 2.0, c])
            .collect();
        let values = self.at(&ends)?;
        let mut best = (0.0, f64::NEG_INFINITY);
        for (pair, v) in ends.chunks(2).zip(values.chunks(2)) {
            let (theta, value) = if v[0] >= v[1] {
                (pair[0], v[0])
            } else {
                (pair[1], v[1])
            };
            if value > best.1 {
                best = (theta, value);
            }
        }
        Some(best)
    }
}

/// The normal (cos θ, sin θ, 0) of a `maxn` (its first `dim` components are read).
fn angle_normal(theta: f64) -> [f64; 3] {
    let (s, c) = theta.sin_cos();
    [c, s, 0.0]
}

/// The ops that depend on an `Angle` op (through their operands), and every `maxn` and
/// `avg` (their sub-tapes are evaluated afresh), in increasing order.
fn varying(ops: &[Op]) -> Vec<usize> {
    let mut depends = vec![false; ops.len()];
    for (k, op) in ops.iter().enumerate() {
        depends[k] = match *op {
            Op::Angle(_) | Op::MaxN(..) | Op::Avg(..) => true,
            Op::Input(_) | Op::Normal(_) | Op::Const(_) => false,
            Op::Add(a, b) | Op::Mul(a, b) | Op::Div(a, b, _) | Op::Apply2(_, a, b, _) => {
                depends[a] || depends[b]
            }
            Op::Neg(a) | Op::Powi(a, _) | Op::Apply(_, a, _) => depends[a],
        };
    }
    (0..ops.len()).filter(|&k| depends[k]).collect()
}

impl<'a> Compiler<'a> {
    /// An empty compiler allowed `budget` more operations.
    fn new(decls: &'a Decls, defs: &'a [Definition], budget: usize) -> Self {
        Compiler {
            decls,
            defs,
            ops: Vec::new(),
            shared: HashMap::default(),
            symbols: HashMap::default(),
            inputs: Vec::new(),
            memo: HashMap::default(),
            degrees: HashMap::default(),
            maxn: Vec::new(),
            avgs: Vec::new(),
            budget,
        }
    }

    fn push(&mut self, op: Op) -> usize {
        let key = match &op {
            Op::Input(k) => Some(Key::Input(*k)),
            Op::Normal(k) => Some(Key::Normal(*k)),
            Op::Angle(k) => Some(Key::Angle(*k)),
            Op::Const(c) => Some(Key::Const(c.to_bits())),
            Op::Add(a, b) => Some(Key::Bin(0, *a.min(b), *a.max(b))),
            Op::Mul(a, b) => Some(Key::Bin(1, *a.min(b), *a.max(b))),
            Op::Div(a, b, _) => Some(Key::Bin(2, *a, *b)),
            Op::Neg(a) => Some(Key::Un(0, *a, 0)),
            Op::Powi(a, k) => Some(Key::Un(1, *a, *k)),
            Op::Apply(f, a, _) => Some(Key::Un(2 + *f as u8, *a, 0)),
            Op::Apply2(f, a, b, _) => Some(Key::Bin(3 + *f as u8, *a, *b)),
            Op::MaxN(..) | Op::Avg(..) => None,
        };
        if let Some(k) = &key {
            if let Some(&id) = self.shared.get(k) {
                return id;
            }
        }
        self.budget = self.budget.saturating_sub(1);
        let id = self.ops.len();
        self.ops.push(op);
        if let Some(k) = key {
            self.shared.insert(k, id);
        }
        id
    }

    fn folded(&self, id: usize) -> Option<f64> {
        match self.ops[id] {
            Op::Const(c) => Some(c),
            _ => None,
        }
    }

    fn c(&mut self, x: f64) -> usize {
        self.push(Op::Const(x))
    }

    fn add(&mut self, a: usize, b: usize) -> usize {
        match (self.folded(a), self.folded(b)) {
            (Some(x), Some(y)) => self.c(x + y),
            (Some(0.0), _) => b,
            (_, Some(0.0)) => a,
            _ => self.push(Op::Add(a, b)),
        }
    }

    fn mul(&mut self, a: usize, b: usize) -> usize {
        match (self.folded(a), self.folded(b)) {
            (Some(x), Some(y)) => self.c(x * y),
            // A structural zero (from δ, ε or a literal) annihilates the other factor;
            // the interpreter would give NaN only if that factor were infinite or NaN.
            (Some(0.0), _) | (_, Some(0.0)) => self.c(0.0),
            (Some(1.0), _) => b,
            (_, Some(1.0)) => a,
            _ => self.push(Op::Mul(a, b)),
        }
    }

    fn neg(&mut self, a: usize) -> usize {
        match self.folded(a) {
            Some(x) => self.c(-x),
            None => self.push(Op::Neg(a)),
        }
    }

    fn def(&self, name: &str) -> Option<&Definition> {
        self.defs.iter().rev().find(|x| x.sig.name == name)
    }

    /// The degree in n of `node` (see [`walk::normal_degree`]).
    fn normal_degree(&mut self, node: &Node) -> Option<usize> {
        walk::normal_degree(node, self.defs, &mut self.degrees)
    }

    /// The tensor of op ids of `node` (slots in the order of its free letters), with the
    /// normal `n` given as op ids.
    fn eval(&mut self, node: &Node, n: &[usize]) -> Result<Tensor<usize>, Unsupported> {
        walk::walk(self, node, n)
    }

    /// The argument of a `maxn` or an adaptive `avg` as a sub-tape over the same
    /// inputs whose normal is the `Angle` ops: it is evaluated many times per sample.
    fn sub_tape(&mut self, a: &Node) -> Result<Tape, Unsupported> {
        let d = self.decls.dim;
        let mut sub = Compiler::new(self.decls, self.defs, self.budget);
        for (k, (name, idx)) in self.inputs.iter().enumerate() {
            let id = sub.push(Op::Input(k));
            sub.inputs.push((name.clone(), idx.clone()));
            let rank = idx.len();
            sub.symbols
                .entry(name.clone())
                .or_insert_with(|| Tensor::from_fn(d, rank, |_| 0));
            *sub.symbols.get_mut(name).expect("inserted").get_mut(idx) = id;
        }
        let angle: Vec<usize> = (0..d).map(|k| sub.push(Op::Angle(k))).collect();
        let outputs = sub.eval(a, &angle)?;
        self.budget = sub.budget;
        Ok(Tape {
            varying: varying(&sub.ops),
            maxima: Maxima::default(),
            ops: sub.ops,
            runs: symbol_runs(&sub.inputs, d),
            inputs: sub.inputs,
            labels: a.free_letters(),
            outputs,
            maxn: sub.maxn,
            avgs: sub.avgs,
            in_plane: self.decls.normal_in_plane,
        })
    }
}

/// The ranges of `inputs` whose entries name the same symbol, in order, each with
/// whether its indices are every assignment of dimension `dim` in storage order.
fn symbol_runs(inputs: &[(String, Vec<usize>)], dim: usize) -> Vec<(std::ops::Range<usize>, bool)> {
    let mut runs: Vec<std::ops::Range<usize>> = Vec::new();
    for (k, (name, _)) in inputs.iter().enumerate() {
        match runs.last_mut() {
            Some(run) if inputs[run.start].0 == *name => run.end = k + 1,
            _ => runs.push(k..k + 1),
        }
    }
    runs.into_iter()
        .map(|run| {
            let listed = inputs[run.clone()].iter().map(|(_, idx)| idx.clone());
            let whole = assignments(dim, inputs[run.start].1.len()).eq(listed);
            (run, whole)
        })
        .collect()
}

/// The tape compiler as an arithmetic: the kernel's contraction emits its operations
/// (constants folded as `add` and `mul` fold them).
impl Arithmetic for Compiler<'_> {
    type Value = usize;
    type Error = Unsupported;
    fn zero(&mut self) -> usize {
        self.c(0.0)
    }

    fn one(&mut self) -> usize {
        self.c(1.0)
    }

    fn mul(&mut self, a: usize, b: &usize) -> Result<usize, Unsupported> {
        Ok(Compiler::mul(self, a, *b))
    }

    fn add(&mut self, a: usize, b: usize) -> Result<usize, Unsupported> {
        Ok(Compiler::add(self, a, b))
    }
}

/// The tape compiler as the walk's ring: each node becomes operations on op ids.
impl Ring for Compiler<'_> {
    type Normal = [usize];

    fn dim(&self) -> usize {
        self.decls.dim
    }

    fn constant(&mut self, q: &Rational) -> usize {
        self.c(q.to_f64())
    }

    fn neg(&mut self, x: usize) -> usize {
        Compiler::neg(self, x)
    }

    fn symbol(&mut self, name: &str, _node: &Node) -> Result<Tensor<usize>, Unsupported> {
        self.symbols
            .get(name)
            .cloned()
            .ok_or_else(|| Unsupported(format!("no value for symbol {name}")))
    }

    fn definition(
        &mut self,
        name: &str,
        _node: &Node,
        n: &[usize],
    ) -> Result<Tensor<usize>, Unsupported> {
        let def = self
            .def(name)
            .cloned()
            .ok_or_else(|| Unsupported(format!("definition {name} not in scope")))?;
        let key_n = if self.normal_degree(&def.body) == Some(0) {
            Vec::new()
        } else {
            n.to_vec()
        };
        let key = (name.to_owned(), key_n);
        if let Some(t) = self.memo.get(&key) {
            return Ok(t.clone());
        }
        let t = walk::in_formal_order(self, &def.body, &def.sig.formal, n)?;
        self.memo.insert(key, t.clone());
        Ok(t)
    }

    fn divide(&mut self, x: usize, den: &usize, divisor: &Node) -> Result<usize, Unsupported> {
        Ok(match (self.folded(x), self.folded(*den)) {
            (Some(p), Some(q)) if q != 0.0 => self.c(p / q),
            _ => self.push(Op::Div(x, *den, divisor.span)),
        })
    }

    fn power(&mut self, x: usize, k: u32, _node: &Node) -> Result<usize, Unsupported> {
        Ok(match self.folded(x) {
            Some(c) => self.c(c.powi(k as i32)),
            None => self.push(Op::Powi(x, k as i32)),
        })
    }

    fn apply(&mut self, f: Func, x: usize, node: &Node) -> Result<usize, Unsupported> {
        debug_assert!(!matches!(f, Func::Avg | Func::MaxN), "their own node kinds");
        Ok(self.push(Op::Apply(f, x, node.span)))
    }

    fn apply2(&mut self, f: Func2, x: usize, y: usize, node: &Node) -> Result<usize, Unsupported> {
        Ok(self.push(Op::Apply2(f, x, y, node.span)))
    }

    fn pi(&mut self, _node: &Node) -> Result<usize, Unsupported> {
        Ok(self.c(std::f64::consts::PI))
    }

    fn enter(&mut self, _node: &Node) -> Result<(), Unsupported> {
        if self.budget == 0 {
            return Err(Unsupported("the tape grew beyond its size limit".into()));
        }
        Ok(())
    }

    fn not_scalar(&mut self, _node: &Node) -> Unsupported {
        Unsupported("expected a scalar".into())
    }

    /// A determinant that folded to the constant 0: singular at every point.
    fn vanishes(&self, det: &usize) -> bool {
        self.folded(*det) == Some(0.0)
    }

    fn singular(&mut self, _node: &Node) -> Unsupported {
        Unsupported("a singular matrix".into())
    }

    /// The tape takes no derivatives: the interpreter takes gradients with dual numbers.
    fn calculus(
        &mut self,
        what: Derivative,
        _node: &Node,
    ) -> Result<&mut DynCalculus<'_, Self>, Unsupported> {
        Err(Unsupported(what.to_string()))
    }
}

impl Normals for Compiler<'_> {
    fn normal(&mut self, n: &[usize]) -> Tensor<usize> {
        Tensor::from_fn(self.decls.dim, 1, |i| n[i[0]])
    }

    fn average(
        &mut self,
        a: &Node,
        _node: &Node,
        _n: &[usize],
    ) -> Result<Tensor<usize>, Unsupported> {
        let d = self.decls.dim;
        let Some(degree) = self.normal_degree(a) else {
            // Not a polynomial in n: an adaptive average of a sub-tape.
            let sub = self.sub_tape(a)?;
            self.avgs.push(sub);
            let k = self.avgs.len() - 1;
            let rank = self.avgs[k].outputs.rank();
            let mut c = 0;
            return Ok(Tensor::from_fn(d, rank, |_| {
                c += 1;
                self.push(Op::Avg(k, c - 1))
            }));
        };
        let rule = super::quadrature::rule_for(self.decls, degree.clamp(1, 40));
        let mut acc: Option<Tensor<usize>> = None;
        for (point, w) in rule {
            let pn: Vec<usize> = point.iter().map(|&x| self.c(x)).collect();
            let t = self.eval(a, &pn)?;
            let wid = self.c(w);
            let t = t.try_map(|&x| Ok::<_, Unsupported>(Compiler::mul(self, x, wid)))?;
            acc = Some(match acc {
                None => t,
                Some(s) => {
                    let mut out = s.clone();
                    for idx in assignments(d, s.rank()) {
                        *out.get_mut(&idx) = Compiler::add(self, *s.get(&idx), *t.get(&idx));
                    }
                    out
                }
            });
        }
        acc.ok_or_else(|| Unsupported("empty quadrature rule".into()))
    }

    fn maximum(&mut self, a: &Node, node: &Node) -> Result<usize, Unsupported> {
        if self.decls.dim == 3 && !self.decls.normal_in_plane {
            return Err(Unsupported("maxn needs an in-plane normal".into()));
        }
        let sub = self.sub_tape(a)?;
        if sub.outputs.rank() != 0 {
            return Err(Unsupported("maxn of a tensor".into()));
        }
        self.maxn.push(sub);
        let k = self.maxn.len() - 1;
        Ok(self.push(Op::MaxN(k, node.span)))
    }
}

#[cfg(test)]
mod tests {
    use super::symbol_runs;

    fn inputs(list: &[(&str, &[usize])]) -> Vec<(String, Vec<usize>)> {
        list.iter()
            .map(|(s, idx)| ((*s).to_owned(), idx.to_vec()))
            .collect()
    }

    /// A run is read in storage order only when it lists every component in that
    /// order: a partial or reordered run (as a sub-tape may list them) is looked up
    /// component by component.
    #[test]
    fn runs_are_whole_only_in_storage_order() {
        let whole = inputs(&[
            ("a", &[]),
            ("s", &[0, 0]),
            ("s", &[0, 1]),
            ("s", &[1, 0]),
            ("s", &[1, 1]),
            ("v", &[0]),
            ("v", &[1]),
        ]);
        assert_eq!(
            symbol_runs(&whole, 2),
            vec![(0..1, true), (1..5, true), (5..7, true)]
        );
        let reordered = inputs(&[
            ("s", &[0, 1]),
            ("s", &[0, 0]),
            ("s", &[1, 0]),
            ("s", &[1, 1]),
        ]);
        assert_eq!(symbol_runs(&reordered, 2), vec![(0..4, false)]);
        let partial = inputs(&[("s", &[0, 0]), ("s", &[0, 1]), ("v", &[1]), ("s", &[1, 0])]);
        assert_eq!(
            symbol_runs(&partial, 2),
            vec![(0..2, false), (2..3, false), (3..4, false)]
        );
    }
}
