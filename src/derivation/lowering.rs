//! Checked nodes in the kernel's terms. The reading is one-to-one for index notation:
//! each node becomes the term of the same shape. The kernel has no matrices, so that
//! what it trusts stays small: each matrix a statement reads becomes scalar
//! definitions of its entries here, and the statement the kernel checks (and a JSON
//! report records) is written in sums, products and quotients of those entries.
//!
//! - A matrix definition `A` gives the definitions `A[1,2]` (1-based; `b[2]` for a
//!   column); an intermediate result that is read more than once, such as a factor of
//!   a product, gives `matrix 3[1,2]`. No file can write a name with a bracket or a
//!   space, so these never clash with the file's own.
//! - `A B` is Σ_k A[i,k] B[k,j]; sums, scalings, transposes and `identity(n)` go entry
//!   by entry.
//! - det A is expanded along the rows over the sets of columns used so far (Laplace),
//!   each minor of two or more rows a definition `det 4{1,3}` of the minors before it;
//!   adj(A)_ij = (−1)^(i+j) det(A without row j and column i), read off the same
//!   expansion without row j (`det 5 without row 2{1,3}`), so that an n×n adjugate
//!   takes about n·2ⁿ definitions; inv(A) = (1 / det A) adj(A) and solve(A, b) =
//!   (1 / det A) adj(A) b, so that both hold where det A ≠ 0, as any other division.
//! - `matrix(T_ijkl, voigt_ij, voigt_kl)` reads the tensor at fixed indices: entry
//!   (a, b) is `T` with its letters set to the positions a and b (through a definition
//!   of the tensor when it is not a single name).
//! - `tensor(M, r_i, r_j)` is Σ_ab M[a,b] δ_{i r_a} δ_{j r_b}: zero at the positions
//!   the orders leave out.
//!
//! A matrix that would need more than [`BUDGET`] definitions is opaque: a statement
//! that reads it is undecided, never proved.

use crate::kernel::statement::Definition;
use crate::kernel::term::{Leaf, Slot, Term};
use crate::kernel::Rational;
use crate::lang::check::Target;
use crate::lang::matrix::{MatrixOp, MatrixRead, Order};
use crate::lang::parser::{Func, Wrt};
use crate::lang::{Node, NodeKind};

/// The most definitions the matrices of one statement may add (a 12×12 inverse needs
/// about 27,000).
pub const BUDGET: usize = 100_000;

/// A matrix's entries, row by row, each a scalar term.
struct Grid {
    rows: usize,
    cols: usize,
    entries: Vec<Term>,
}

/// More definitions than [`BUDGET`].
struct TooLarge;

/// The definitions made so far for one statement.
#[derive(Default)]
pub struct Lowering {
    defs: Vec<Definition>,
    made: usize,
    /// The file's definitions by name, each lowered when a term first reads it.
    offered: std::collections::HashMap<String, (Vec<char>, Node)>,
}

/// The name of a matrix definition's entry k (0-based, row by row).
fn entry_name(name: &str, cols: usize, k: usize) -> String {
    if cols == 1 {
        format!("{name}[{}]", k + 1)
    } else {
        format!("{name}[{},{}]", k / cols + 1, k % cols + 1)
    }
}

fn def_leaf(name: String) -> Term {
    Term::Leaf {
        of: Leaf::Def(name),
        slots: Vec::new(),
    }
}

fn constant(n: i64) -> Term {
    Term::int(n)
}

/// A term that costs nothing to repeat: a constant or a leaf without letters.
fn atomic(t: &Term) -> bool {
    match t {
        Term::Const { free, .. } => free.is_empty(),
        Term::Leaf { slots, .. } => slots.iter().all(|s| matches!(s, Slot::Fixed(_))),
        _ => false,
    }
}

fn is_zero(t: &Term) -> bool {
    matches!(t, Term::Const { value, .. } if value == &Rational::int(0))
}

/// The sum of `terms` (0 when there are none, the term itself when there is one).
fn sum(mut terms: Vec<Term>) -> Term {
    terms.retain(|t| !is_zero(t));
    match terms.len() {
        0 => constant(0),
        1 => terms.remove(0),
        _ => Term::Sum(terms),
    }
}

impl Lowering {
    fn charge(&mut self) -> Result<(), TooLarge> {
        self.made += 1;
        if self.made > BUDGET {
            return Err(TooLarge);
        }
        Ok(())
    }

    /// A definition of `body` with the given name, as a leaf to read it by.
    fn define(&mut self, name: String, formal: Vec<char>, body: Term) -> Result<(), TooLarge> {
        self.charge()?;
        self.defs.push(Definition { name, formal, body });
        Ok(())
    }

    /// `t`, or a definition of it when it is not atomic.
    fn shared(&mut self, t: Term) -> Result<Term, TooLarge> {
        if atomic(&t) {
            return Ok(t);
        }
        let name = format!("matrix {}", self.made + 1);
        self.define(name.clone(), Vec::new(), t)?;
        Ok(def_leaf(name))
    }

    /// The grid with every entry atomic: what a product or a determinant repeats.
    fn materialised(&mut self, g: Grid) -> Result<Grid, TooLarge> {
        if g.entries.iter().all(atomic) {
            return Ok(g);
        }
        let name = format!("matrix {}", self.made + 1);
        let mut entries = Vec::with_capacity(g.entries.len());
        for (k, e) in g.entries.into_iter().enumerate() {
            if atomic(&e) {
                entries.push(e);
            } else {
                let entry = entry_name(&name, g.cols, k);
                self.define(entry.clone(), Vec::new(), e)?;
                entries.push(def_leaf(entry));
            }
        }
        Ok(Grid { entries, ..g })
    }

    /// A file's definition, lowered (by [`Lowering::finish`]) only if the statement
    /// reads it.
    pub fn offer(&mut self, name: &str, formal: &[char], body: &Node) {
        self.offered
            .insert(name.to_owned(), (formal.to_vec(), body.clone()));
    }

    /// The definitions the statement reads through `terms`, directly or through other
    /// definitions, with every file definition among them lowered; the others are left
    /// out (the statement is what the claim says, not the whole file).
    pub fn finish<'t>(mut self, terms: impl Iterator<Item = &'t Term>) -> Vec<Definition> {
        fn names(t: &Term, out: &mut Vec<String>) {
            if let Term::Leaf {
                of: Leaf::Def(d), ..
            } = t
            {
                out.push(d.clone());
            }
            for c in crate::kernel::eval::children(t) {
                names(c, out);
            }
        }
        let mut pending = Vec::new();
        for t in terms {
            names(t, &mut pending);
        }
        let mut index: std::collections::HashMap<String, usize> = std::collections::HashMap::new();
        let mut indexed = 0;
        let mut read = std::collections::BTreeSet::new();
        while let Some(name) = pending.pop() {
            if !read.insert(name.clone()) {
                continue;
            }
            // A file definition (`A`, or an entry `A[1,2]` of a matrix one) not yet
            // lowered is lowered now.
            let file = name.split_once('[').map_or(name.as_str(), |(base, _)| base);
            if let Some((formal, body)) = self.offered.remove(file) {
                self.definition(file, &formal, &body);
            }
            for (k, d) in self.defs.iter().enumerate().skip(indexed) {
                index.insert(d.name.clone(), k);
            }
            indexed = self.defs.len();
            if let Some(&k) = index.get(&name) {
                names(&self.defs[k].body, &mut pending);
            }
        }
        self.defs.retain(|d| read.contains(&d.name));
        self.defs
    }

    /// A file's definition in the kernel's terms: a matrix definition becomes one
    /// scalar definition per entry.
    fn definition(&mut self, name: &str, formal: &[char], body: &Node) {
        let Some((rows, cols)) = body.shape() else {
            let body = self.term(body);
            self.defs.push(Definition {
                name: name.to_owned(),
                formal: formal.to_vec(),
                body,
            });
            return;
        };
        let entries = match self.grid(body) {
            Ok(g) => g.entries,
            Err(TooLarge) => vec![too_large(Vec::new()); rows * cols],
        };
        for (k, body) in entries.into_iter().enumerate() {
            self.defs.push(Definition {
                name: entry_name(name, cols, k),
                formal: Vec::new(),
                body,
            });
        }
    }

    /// The term a checked node reads as; a matrix read (det, trace, an entry, a tensor
    /// view) is written out in its entries.
    pub fn term(&mut self, node: &Node) -> Term {
        let opaque = |what: &str| Term::Opaque {
            what: what.to_owned(),
            free: node.free_letters(),
        };
        let mut b = |n: &Node| Box::new(self.term(n));
        match &node.kind {
            NodeKind::Const(q) => Term::Const {
                value: q.clone(),
                free: node.free_letters(),
            },
            NodeKind::Leaf { target, slots } => {
                let of = match target {
                    Target::Symbol(s) => Leaf::Symbol(s.clone()),
                    Target::Def(d) => Leaf::Def(d.clone()),
                    Target::Delta => Leaf::Delta,
                    Target::Eps => Leaf::Eps,
                    Target::Normal => Leaf::Normal,
                    Target::Pi => return opaque("π is not rational"),
                };
                Term::Leaf {
                    of,
                    slots: slots.clone(),
                }
            }
            NodeKind::Sum(ts) => Term::Sum(ts.iter().map(|t| self.term(t)).collect()),
            NodeKind::Product(fs) => Term::Product(fs.iter().map(|f| self.term(f)).collect()),
            NodeKind::Div(a, d) => Term::Div(b(a), b(d)),
            NodeKind::Neg(a) => Term::Neg(b(a)),
            NodeKind::Pow(a, k) => Term::Pow(b(a), *k),
            NodeKind::Apply(Func::Sqrt, a) => Term::Sqrt(b(a)),
            NodeKind::Apply(f, _) => {
                opaque(&format!("{}(…) has no exact polynomial value", f.name()))
            }
            NodeKind::Apply2(f, _, _) => {
                opaque(&format!("{}(…, …) has no exact polynomial value", f.name()))
            }
            NodeKind::Avg(a) => Term::Avg(b(a)),
            NodeKind::MaxN(_) => opaque("maxn(…) is a maximum over orientations"),
            NodeKind::Deriv(a, slot) => Term::Deriv(b(a), *slot),
            NodeKind::Wrt {
                op,
                body,
                symbol,
                slots,
            } => match op {
                Wrt::Grad => Term::Grad {
                    body: b(body),
                    symbol: symbol.clone(),
                    slots: slots.clone(),
                },
                Wrt::Variation => Term::Variation {
                    body: b(body),
                    field: symbol.clone(),
                    slots: slots.clone(),
                },
            },
            NodeKind::Matrix { .. } | NodeKind::Read(..) => self.read(node),
        }
    }

    /// A node that reads a matrix, as a term.
    fn read(&mut self, node: &Node) -> Term {
        let free = node.free_letters();
        let NodeKind::Read(read, m) = &node.kind else {
            return Term::Opaque {
                what: "a matrix where a scalar or a tensor belongs".to_owned(),
                free,
            };
        };
        let lowered = self.grid(m).and_then(|g| match read {
            MatrixRead::Entry(i, j) => Ok(g.entries[i * g.cols + j].clone()),
            MatrixRead::Trace => Ok(sum((0..g.rows)
                .map(|k| g.entries[k * g.cols + k].clone())
                .collect())),
            MatrixRead::Det => {
                let g = self.materialised(g)?;
                self.det(&g.entries, g.rows)
            }
            MatrixRead::Tensor { rows, cols } => {
                let g = self.materialised(g)?;
                Ok(tensor_view(g, rows, cols.as_deref(), &free))
            }
        });
        lowered.unwrap_or_else(|TooLarge| too_large(free))
    }

    /// A matrix node's entries.
    fn grid(&mut self, node: &Node) -> Result<Grid, TooLarge> {
        let NodeKind::Matrix { rows, cols, op } = &node.kind else {
            // A 1×1 result is the scalar it holds.
            return Ok(Grid {
                rows: 1,
                cols: 1,
                entries: vec![self.term(node)],
            });
        };
        let (rows, cols) = (*rows, *cols);
        let entries = match op {
            MatrixOp::Literal(es) => es.iter().map(|e| self.term(e)).collect(),
            MatrixOp::Def(name) => (0..rows * cols)
                .map(|k| def_leaf(entry_name(name, cols, k)))
                .collect(),
            MatrixOp::Identity => (0..rows * cols)
                .map(|k| constant(i64::from(k / cols == k % cols)))
                .collect(),
            MatrixOp::Sum(ms) => {
                let mut grids = Vec::with_capacity(ms.len());
                for m in ms {
                    grids.push(self.grid(m)?.entries);
                }
                (0..rows * cols)
                    .map(|k| sum(grids.iter().map(|g| g[k].clone()).collect()))
                    .collect()
            }
            MatrixOp::Scale(s, m) => {
                let s = self.term(s);
                let s = self.shared(s)?;
                let m = self.grid(m)?;
                m.entries
                    .into_iter()
                    .map(|e| Term::Product(vec![s.clone(), e]))
                    .collect()
            }
            MatrixOp::Product(x, y) => {
                let a = self.grid(x)?;
                let a = self.materialised(a)?;
                let b = self.grid(y)?;
                let b = self.materialised(b)?;
                product(&a, &b)
            }
            MatrixOp::Transpose(x) => {
                let a = self.grid(x)?;
                (0..rows * cols)
                    .map(|k| a.entries[(k % cols) * a.cols + k / cols].clone())
                    .collect()
            }
            MatrixOp::Adjugate(x) => {
                let a = self.grid(x)?;
                let a = self.materialised(a)?;
                self.adjugate(&a.entries, a.rows)?.0
            }
            MatrixOp::Inverse(x) | MatrixOp::Solve(x, _) => {
                let a = self.grid(x)?;
                let a = self.materialised(a)?;
                let (entries, det) = self.adjugate(&a.entries, a.rows)?;
                let adj = Grid {
                    rows: a.rows,
                    cols: a.rows,
                    entries,
                };
                let top = match op {
                    MatrixOp::Solve(_, y) => {
                        let adj = self.materialised(adj)?;
                        let b = self.grid(y)?;
                        let b = self.materialised(b)?;
                        product(&adj, &b)
                    }
                    _ => adj.entries,
                };
                // (1 / det A) adj(A), so that the determinant's variables are met
                // first, in the order of A's entries, as the evidence writes them.
                let reciprocal = Term::Div(Box::new(constant(1)), Box::new(det));
                let reciprocal = self.shared(reciprocal)?;
                top.into_iter()
                    .map(|e| Term::Product(vec![reciprocal.clone(), e]))
                    .collect()
            }
            MatrixOp::View {
                tensor,
                rows: ro,
                cols: co,
            } => self.view(tensor, ro, co.as_deref(), rows, cols)?,
        };
        Ok(Grid {
            rows,
            cols,
            entries,
        })
    }

    /// Entry (a, b) of `matrix(T, rows, cols)`: `T` with its letters set to the
    /// positions a and b.
    fn view(
        &mut self,
        tensor: &Node,
        ro: &Order,
        co: Option<&Order>,
        rows: usize,
        cols: usize,
    ) -> Result<Vec<Term>, TooLarge> {
        let t = self.term(tensor);
        let (of, slots) = match t {
            Term::Leaf { of, slots } => (of, slots),
            body => {
                let formal = tensor.free_letters();
                let name = format!("matrix {}", self.made + 1);
                self.define(name.clone(), formal.clone(), body)?;
                let slots = formal.into_iter().map(Slot::Letter).collect();
                (Leaf::Def(name), slots)
            }
        };
        let mut out = Vec::with_capacity(rows * cols);
        for a in 0..rows {
            for b in 0..cols {
                let mut bound: Vec<(char, usize)> = Vec::new();
                let mut bind = |o: &Order, p: usize| {
                    for (s, &v) in o.slots.iter().zip(&o.positions[p]) {
                        if let Slot::Letter(c) = s {
                            bound.push((*c, v));
                        }
                    }
                };
                bind(ro, a);
                if let Some(co) = co {
                    bind(co, b);
                }
                let fixed = slots
                    .iter()
                    .map(|s| match s {
                        Slot::Letter(c) => bound
                            .iter()
                            .find(|(l, _)| l == c)
                            .map_or(*s, |&(_, v)| Slot::Fixed(v)),
                        Slot::Fixed(_) => *s,
                    })
                    .collect();
                out.push(Term::Leaf {
                    of: of.clone(),
                    slots: fixed,
                });
            }
        }
        Ok(out)
    }

    /// det by expansion along the rows over the sets of columns used so far.
    fn det(&mut self, m: &[Term], n: usize) -> Result<Term, TooLarge> {
        if n == 0 {
            return Ok(constant(1));
        }
        let minors = self.minors(m, n, None, &[])?;
        Ok(minors[(1 << n) - 1].clone())
    }

    /// The minors of the rows of `m` (without row `skip`) taken in order, by the sets
    /// of columns used so far: minor(S) is the determinant of the first |S| of those
    /// rows and the columns in S, expanded along its last row (Laplace); each of two or
    /// more rows is a definition. Without a skipped row, `shared` is empty; with one,
    /// it is the minors without a skip, which are the same for the sets of rows before
    /// the skipped one.
    fn minors(
        &mut self,
        m: &[Term],
        n: usize,
        skip: Option<usize>,
        shared: &[Term],
    ) -> Result<Vec<Term>, TooLarge> {
        let full = (1usize << n) - 1;
        let tag = self.made + 1;
        let rows = n - usize::from(skip.is_some());
        let mut minors: Vec<Term> = vec![constant(1); 1 << n];
        for set in 1..=full {
            let size = set.count_ones() as usize;
            if size > rows {
                continue;
            }
            // The row this set's last step expands along.
            let row = match skip {
                Some(j) if size > j => size,
                Some(_) => {
                    minors[set] = shared[set].clone();
                    continue;
                }
                None => size - 1,
            };
            let mut terms = Vec::new();
            // The sign of a column is the parity of the columns of the set after it.
            // The last column first: the diagonal's product leads.
            for col in (0..n).rev().filter(|c| set & (1 << c) != 0) {
                let rest = set & !(1 << col);
                let entry = m[row * n + col].clone();
                if is_zero(&entry) {
                    continue;
                }
                let p = if rest == 0 {
                    entry
                } else if is_zero(&minors[rest]) {
                    continue;
                } else {
                    Term::Product(vec![minors[rest].clone(), entry])
                };
                terms.push(if (rest >> col).count_ones() % 2 == 0 {
                    p
                } else {
                    Term::Neg(Box::new(p))
                });
            }
            let minor = sum(terms);
            minors[set] = if size == 1 || size == rows || atomic(&minor) {
                minor
            } else {
                let columns: Vec<String> = (0..n)
                    .filter(|c| set & (1 << c) != 0)
                    .map(|c| (c + 1).to_string())
                    .collect();
                let without = skip.map_or(String::new(), |j| format!(" without row {}", j + 1));
                let name = format!("det {tag}{without}{{{}}}", columns.join(","));
                self.define(name.clone(), Vec::new(), minor)?;
                def_leaf(name)
            };
        }
        Ok(minors)
    }

    /// The adjugate: entry (i, j) is (−1)^(i+j) times the minor without row j and
    /// column i, read off the minors without row j.
    /// The adjugate and the determinant, from one expansion.
    fn adjugate(&mut self, m: &[Term], n: usize) -> Result<(Vec<Term>, Term), TooLarge> {
        let full = (1usize << n) - 1;
        let shared = self.minors(m, n, None, &[])?;
        if n == 1 {
            return Ok((vec![constant(1)], shared[full].clone()));
        }
        let mut out = vec![constant(0); n * n];
        for j in 0..n {
            let minors = self.minors(m, n, Some(j), &shared)?;
            for i in 0..n {
                let minor = minors[full & !(1 << i)].clone();
                out[i * n + j] = if (i + j) % 2 == 0 || is_zero(&minor) {
                    minor
                } else {
                    Term::Neg(Box::new(minor))
                };
            }
        }
        Ok((out, shared[full].clone()))
    }
}

/// The product of two grids whose entries are atomic.
fn product(a: &Grid, b: &Grid) -> Vec<Term> {
    let mut out = Vec::with_capacity(a.rows * b.cols);
    for i in 0..a.rows {
        for j in 0..b.cols {
            let terms = (0..a.cols)
                .filter_map(|k| {
                    let (x, y) = (&a.entries[i * a.cols + k], &b.entries[k * b.cols + j]);
                    (!is_zero(x) && !is_zero(y)).then(|| Term::Product(vec![x.clone(), y.clone()]))
                })
                .collect();
            out.push(sum(terms));
        }
    }
    out
}

/// `tensor(M, rows, cols)` = Σ_ab M[a,b] δ_{i r_a} δ_{j r_b} over the letters of the
/// orders' slots; a fixed slot keeps only the positions with its value.
fn tensor_view(g: Grid, ro: &Order, co: Option<&Order>, free: &[char]) -> Term {
    let mut letters: Vec<char> = ro
        .slots
        .iter()
        .chain(co.iter().flat_map(|o| &o.slots))
        .filter_map(|s| match s {
            Slot::Letter(c) => Some(*c),
            Slot::Fixed(_) => None,
        })
        .collect();
    letters.sort_unstable();
    if letters.windows(2).any(|w| w[0] == w[1]) {
        return Term::Opaque {
            what: "a tensor view with a letter in two slots".to_owned(),
            free: free.to_vec(),
        };
    }
    let mut terms = Vec::new();
    for (k, e) in g.entries.into_iter().enumerate() {
        let (a, b) = (k / g.cols, k % g.cols);
        let mut factors = vec![e];
        let mut fits = true;
        let mut place = |o: &Order, p: usize| {
            for (s, &v) in o.slots.iter().zip(&o.positions[p]) {
                match s {
                    Slot::Letter(c) => factors.push(Term::Leaf {
                        of: Leaf::Delta,
                        slots: vec![Slot::Letter(*c), Slot::Fixed(v)],
                    }),
                    Slot::Fixed(f) => fits &= *f == v,
                }
            }
        };
        place(ro, a);
        if let Some(co) = co {
            place(co, b);
        }
        if fits && !is_zero(&factors[0]) {
            terms.push(Term::Product(factors));
        }
    }
    if terms.is_empty() {
        return Term::Const {
            value: Rational::int(0),
            free: free.to_vec(),
        };
    }
    sum(terms)
}

/// The term of a matrix too large to expand.
fn too_large(free: Vec<char>) -> Term {
    Term::Opaque {
        what: format!("a matrix that needs more than {BUDGET} definitions to expand"),
        free,
    }
}
