//! The matrix language: literals, products, transposes, determinants, inverses,
//! adjugates, linear solves, and the two views between index notation and matrices in
//! a declared position order, typed here so that a shape error is found where it is
//! written.
//!
//! Rules:
//! - a matrix has no free index; it meets index notation only through the views
//!   `matrix(D_ijkl, voigt_ij, voigt_kl)`, `vector(sigma_ij, voigt_ij)` and
//!   `tensor(M, voigt_ij, voigt_kl)`, whose orders are declared at the top of the file
//!   (`orders = { voigt = ["11", "22", "12", "21"] }`). Components the order leaves out
//!   are zero in the tensor view;
//! - sums take matrices of one shape; a product multiplies its matrices in the order
//!   written, scaled by its scalar factors; a matrix is divided only by a scalar;
//! - a 1×1 result is the scalar it holds (`q^T D q`), so that it can be added to and
//!   divided by like any scalar;
//! - `inv(A)` and `solve(A, b)` are adj(A)/det(A): evaluation refuses a determinant
//!   that is identically zero (a singular system), and otherwise the result holds where
//!   det(A) ≠ 0, as any other division.

use super::check::{letters, Node, NodeKind, Scope, Slot};
pub use super::check::{MatrixOp, MatrixRead, Order};
use super::diag::Span;
use super::parser::{ErrorKind, Expr, ExprKind, LangError, MatFunc};
use crate::algebra::matrix::MAX_SIDE;
use crate::kernel::Rational;

impl Node {
    /// The shape of a matrix-valued node; `None` for a tensor or scalar.
    pub fn shape(&self) -> Option<(usize, usize)> {
        match &self.kind {
            NodeKind::Matrix { rows, cols, .. } => Some((*rows, *cols)),
            _ => None,
        }
    }
}

/// "a 4×4 matrix", "a 4-vector", "a row of 4".
pub fn shape_words((rows, cols): (usize, usize)) -> String {
    match (rows, cols) {
        (r, 1) => format!("a column vector of {r}"),
        (1, c) => format!("a row of {c}"),
        (r, c) => format!("a {r}×{c} matrix"),
    }
}

/// A matrix node of the given shape, or the scalar it holds when it is 1×1.
fn matrix(rows: usize, cols: usize, op: MatrixOp, bound: Vec<char>, span: Span) -> Node {
    let node = Node {
        kind: NodeKind::Matrix { rows, cols, op },
        free: Vec::new(),
        bound: bound.clone(),
        span,
    };
    if (rows, cols) == (1, 1) {
        Node {
            kind: NodeKind::Read(MatrixRead::Entry(0, 0), Box::new(node)),
            free: Vec::new(),
            bound,
            span,
        }
    } else {
        node
    }
}

fn bound_of(nodes: &[&Node]) -> Vec<char> {
    let mut out: Vec<char> = nodes.iter().flat_map(|n| n.bound.iter().copied()).collect();
    out.sort_unstable();
    out.dedup();
    out
}

fn error(span: Span, message: impl Into<String>) -> LangError {
    LangError::new(ErrorKind::Index, span, message)
}

fn too_large(span: Span, side: usize) -> Result<(), LangError> {
    if side > MAX_SIDE {
        return Err(LangError::new(
            ErrorKind::Syntax,
            span,
            format!("a matrix side of {side} is more than the {MAX_SIDE} the checker accepts"),
        )
        .help("split the system into blocks"));
    }
    Ok(())
}

impl Scope<'_> {
    /// Refuses a matrix where a scalar or tensor is expected.
    pub(super) fn not_matrix(&self, node: &Node, what: &str) -> Result<(), LangError> {
        match node.shape() {
            Some(shape) => Err(error(
                node.span,
                format!("{what} takes a scalar or a tensor, but this is {}", shape_words(shape)),
            )
            .help("read a scalar off a matrix with det(…), trace(…) or A[i,j], or a tensor with tensor(…)")),
            None => Ok(()),
        }
    }

    /// A reference to a matrix definition.
    pub(super) fn matrix_def(&self, name: &str, shape: (usize, usize), span: Span) -> Node {
        matrix(
            shape.0,
            shape.1,
            MatrixOp::Def(name.to_owned()),
            Vec::new(),
            span,
        )
    }

    /// `[a, b]` or `[[a, b], [c, d]]`: entries must be scalars.
    pub(super) fn literal(&self, rows: &[Vec<Expr>], span: Span) -> Result<Node, LangError> {
        let (r, c) = (rows.len(), rows.first().map_or(0, Vec::len));
        too_large(span, r.max(c))?;
        let mut entries = Vec::with_capacity(r * c);
        for e in rows.iter().flatten() {
            let n = self.check(e)?;
            self.not_matrix(&n, "an entry of a matrix")?;
            if let Some(&(ch, at)) = n.free.first() {
                return Err(error(
                    at,
                    format!(
                        "an entry of a matrix is a scalar, but this has free index {}",
                        letters(&n.free_letters())
                    ),
                )
                .help(format!(
                    "fix `{ch}` to a component, or use vector(…) for the view of a tensor"
                )));
            }
            entries.push(n);
        }
        let bound = bound_of(&entries.iter().collect::<Vec<_>>());
        Ok(matrix(r, c, MatrixOp::Literal(entries), bound, span))
    }

    /// `A[i,j]` or `v[i]`.
    pub(super) fn entry(
        &self,
        inner: &Expr,
        at: &[(usize, Span)],
        span: Span,
    ) -> Result<Node, LangError> {
        let m = self.check(inner)?;
        let Some((rows, cols)) = m.shape() else {
            return Err(
                error(inner.span, "only a matrix or a vector has entries A[i,j]")
                    .help("index a tensor with subscripts, as in sigma_12"),
            );
        };
        let (i, j) = match at {
            [(i, _)] if cols == 1 => (*i, 1),
            [(j, _)] if rows == 1 => (1, *j),
            [(i, _), (j, _)] => (*i, *j),
            _ => {
                return Err(error(
                    span,
                    format!(
                        "{} needs two entry numbers, A[i,j]",
                        shape_words((rows, cols))
                    ),
                ))
            }
        };
        let span_k = at[at.len() - 1].1;
        if i > rows || j > cols {
            return Err(LangError::new(
                ErrorKind::Dimension,
                if i > rows { at[0].1 } else { span_k },
                format!("entry ({i}, {j}) is outside {}", shape_words((rows, cols))),
            )
            .help(format!(
                "rows run from 1 to {rows}, columns from 1 to {cols}"
            )));
        }
        Ok(Node {
            free: Vec::new(),
            bound: m.bound.clone(),
            span,
            kind: NodeKind::Read(MatrixRead::Entry(i - 1, j - 1), Box::new(m)),
        })
    }

    /// A sum whose terms include a matrix: every term a matrix of the first's shape.
    pub(super) fn matrix_sum(&self, terms: Vec<Node>, span: Span) -> Result<Node, LangError> {
        let shape = terms
            .iter()
            .find_map(Node::shape)
            .expect("called with a matrix term");
        for t in &terms {
            if t.shape() != Some(shape) {
                let what = t
                    .shape()
                    .map_or_else(|| "a scalar or tensor".to_owned(), shape_words);
                return Err(error(
                    t.span,
                    format!("this term is {what}, the others {}", shape_words(shape)),
                )
                .help("every term of a sum of matrices has the same shape"));
            }
        }
        let bound = bound_of(&terms.iter().collect::<Vec<_>>());
        Ok(matrix(shape.0, shape.1, MatrixOp::Sum(terms), bound, span))
    }

    /// `-A`.
    pub(super) fn matrix_neg(&self, m: Node, span: Span) -> Node {
        let minus = Node {
            kind: NodeKind::Const(Rational::int(-1)),
            free: Vec::new(),
            bound: Vec::new(),
            span,
        };
        scale(minus, m, span)
    }

    /// A product whose factors include a matrix: the scalars scale, the matrices
    /// multiply in the order written.
    pub(super) fn matrix_product(&self, factors: Vec<Node>, span: Span) -> Result<Node, LangError> {
        let mut scalars = Vec::new();
        let mut acc: Option<Node> = None;
        for f in factors {
            if f.shape().is_none() {
                if let Some(&(c, at)) = f.free.first() {
                    return Err(error(
                        at,
                        format!("a tensor with free index {c} multiplies a matrix"),
                    )
                    .help("turn the tensor into a matrix with matrix(…) or vector(…) first"));
                }
                scalars.push(f);
                continue;
            }
            match acc.take() {
                None => acc = Some(f),
                // A row times a column is the scalar it holds: it scales the rest.
                Some(a) => match multiply(a, f)? {
                    m if m.shape().is_some() => acc = Some(m),
                    s => scalars.push(s),
                },
            }
        }
        let Some(m) = acc else {
            let bound = bound_of(&scalars.iter().collect::<Vec<_>>());
            return Ok(Node {
                kind: NodeKind::Product(scalars),
                free: Vec::new(),
                bound,
                span,
            });
        };
        Ok(match scalars.len() {
            0 => m,
            1 => scale(scalars.pop().expect("one scalar"), m, span),
            _ => {
                let bound = bound_of(&scalars.iter().collect::<Vec<_>>());
                let product = Node {
                    kind: NodeKind::Product(scalars),
                    free: Vec::new(),
                    bound,
                    span,
                };
                scale(product, m, span)
            }
        })
    }

    /// `A / s`.
    pub(super) fn matrix_divide(&self, m: Node, den: Node, span: Span) -> Result<Node, LangError> {
        if let Some(shape) = den.shape() {
            return Err(error(
                den.span,
                format!(
                    "a divisor must be a scalar, but this is {}",
                    shape_words(shape)
                ),
            )
            .help("multiply by inv(A), or write solve(A, b)"));
        }
        let one = Node {
            kind: NodeKind::Const(Rational::int(1)),
            free: Vec::new(),
            bound: Vec::new(),
            span: den.span,
        };
        let bound = den.bound.clone();
        let factor = Node {
            kind: NodeKind::Div(Box::new(one), Box::new(den)),
            free: Vec::new(),
            bound,
            span,
        };
        Ok(scale(factor, m, span))
    }

    /// `A^k` of a square matrix: k − 1 products (the identity for k = 0).
    pub(super) fn matrix_power(&self, m: Node, k: u32, span: Span) -> Result<Node, LangError> {
        let (rows, cols) = m.shape().expect("called with a matrix");
        if rows != cols {
            return Err(error(
                m.span,
                format!(
                    "a power of {} (only a square matrix has powers)",
                    shape_words((rows, cols))
                ),
            ));
        }
        if k == 0 {
            return Ok(matrix(rows, rows, MatrixOp::Identity, Vec::new(), span));
        }
        let mut acc = m.clone();
        for _ in 1..k {
            acc = multiply(acc, m.clone())?;
        }
        acc.span = span;
        Ok(acc)
    }

    /// `det(A)`, `inv(A)`, `solve(A, b)`, `matrix(T_ijkl, o_ij, o_kl)`, ….
    pub(super) fn mat_call(
        &self,
        f: MatFunc,
        args: &[Expr],
        span: Span,
    ) -> Result<Node, LangError> {
        match f {
            MatFunc::Identity => {
                let n = match &args[0].kind {
                    ExprKind::Number(q) if q.is_integer() && !q.is_negative() && !q.is_zero() => {
                        q.to_string().parse::<usize>().unwrap_or(usize::MAX)
                    }
                    _ => {
                        return Err(LangError::new(
                            ErrorKind::Syntax,
                            args[0].span,
                            "identity(n) takes a whole number n ≥ 1",
                        ))
                    }
                };
                too_large(args[0].span, n)?;
                Ok(matrix(n, n, MatrixOp::Identity, Vec::new(), span))
            }
            MatFunc::Matrix | MatFunc::Vector => {
                let t = self.check(&args[0])?;
                self.not_matrix(&t, f.name())?;
                let rows = self.order(&args[1], false)?;
                let cols = match args.get(2) {
                    Some(a) => Some(self.order(a, false)?),
                    None => None,
                };
                let mut want: Vec<char> = rows
                    .slots
                    .iter()
                    .chain(cols.iter().flat_map(|o| o.slots.iter()))
                    .filter_map(|s| match s {
                        Slot::Letter(c) => Some(*c),
                        Slot::Fixed(_) => None,
                    })
                    .collect();
                let n = want.len();
                want.sort_unstable();
                want.dedup();
                if want.len() != n || want != t.free_letters() {
                    return Err(error(
                        args[0].span,
                        format!(
                            "the orders bind the indices {}, and the tensor has free indices {}",
                            letters(&want),
                            letters(&t.free_letters())
                        ),
                    )
                    .help(format!(
                        "write {}: each free index bound once by an order",
                        f.usage()
                    )));
                }
                let r = rows.positions.len();
                let c = cols.as_ref().map_or(1, |o| o.positions.len());
                let bound = t.bound.clone();
                let op = MatrixOp::View {
                    tensor: Box::new(t),
                    rows: Box::new(rows),
                    cols: cols.map(Box::new),
                };
                Ok(matrix(r, c, op, bound, span))
            }
            MatFunc::Tensor => {
                let m = self.check(&args[0])?;
                let Some((r, c)) = m.shape() else {
                    return Err(error(args[0].span, "tensor(…) takes a matrix or a vector")
                        .help(format!("write {}", f.usage())));
                };
                let rows = self.order(&args[1], true)?;
                let cols = match args.get(2) {
                    Some(a) => Some(self.order(a, true)?),
                    None => None,
                };
                let want = (
                    rows.positions.len(),
                    cols.as_ref().map_or(1, |o| o.positions.len()),
                );
                if want != (r, c) {
                    return Err(LangError::new(
                        ErrorKind::Dimension,
                        args[0].span,
                        format!(
                            "the orders give {}, and this is {}",
                            shape_words(want),
                            shape_words((r, c))
                        ),
                    ));
                }
                let mut counts: std::collections::BTreeMap<char, Vec<Span>> = Default::default();
                for (o, a) in std::iter::once((&rows, &args[1])).chain(cols.iter().zip(&args[2..]))
                {
                    for s in &o.slots {
                        if let Slot::Letter(ch) = s {
                            counts.entry(*ch).or_default().push(a.span);
                        }
                    }
                }
                if let Some((ch, spans)) = counts.iter().find(|(_, s)| s.len() > 1) {
                    return Err(error(
                        spans[1],
                        format!("index `{ch}` is bound twice by the orders of tensor(…)"),
                    )
                    .help("each order binds its own index letters"));
                }
                let free = counts.into_iter().map(|(ch, s)| (ch, s[0])).collect();
                let bound = m.bound.clone();
                Ok(Node {
                    kind: NodeKind::Read(
                        MatrixRead::Tensor {
                            rows: Box::new(rows),
                            cols: cols.map(Box::new),
                        },
                        Box::new(m),
                    ),
                    free,
                    bound,
                    span,
                })
            }
            _ => {
                let ms = args
                    .iter()
                    .map(|a| self.check(a))
                    .collect::<Result<Vec<_>, _>>()?;
                let mut shapes = Vec::with_capacity(ms.len());
                for m in &ms {
                    // A 1×1 matrix is its scalar: det, inv and transpose of a scalar
                    // are still meant as of a 1×1 matrix.
                    let shape =
                        match m.shape() {
                            Some(s) => s,
                            None if m.free.is_empty() => (1, 1),
                            None => return Err(error(
                                m.span,
                                format!("{}(…) takes a matrix, but this is a tensor", f.name()),
                            )
                            .help(
                                "turn the tensor into a matrix with matrix(…) or vector(…) first",
                            )),
                        };
                    shapes.push(shape);
                }
                self.square_op(f, ms, &shapes, span)
            }
        }
    }

    fn square_op(
        &self,
        f: MatFunc,
        mut ms: Vec<Node>,
        shapes: &[(usize, usize)],
        span: Span,
    ) -> Result<Node, LangError> {
        let (r, c) = shapes[0];
        let bound = bound_of(&ms.iter().collect::<Vec<_>>());
        if f == MatFunc::Transpose {
            let a = as_matrix(ms.remove(0), (r, c));
            return Ok(matrix(c, r, MatrixOp::Transpose(Box::new(a)), bound, span));
        }
        if r != c {
            return Err(error(
                ms[0].span,
                format!(
                    "{}(…) needs a square matrix, but this is {}",
                    f.name(),
                    shape_words((r, c))
                ),
            ));
        }
        let a = as_matrix(ms.remove(0), (r, c));
        let read = |read: MatrixRead, a: Node| Node {
            kind: NodeKind::Read(read, Box::new(a)),
            free: Vec::new(),
            bound: bound.clone(),
            span,
        };
        Ok(match f {
            MatFunc::Det => read(MatrixRead::Det, a),
            MatFunc::Trace => read(MatrixRead::Trace, a),
            MatFunc::Inv => matrix(r, r, MatrixOp::Inverse(Box::new(a)), bound, span),
            MatFunc::Adj => matrix(r, r, MatrixOp::Adjugate(Box::new(a)), bound, span),
            MatFunc::Solve => {
                let (br, bc) = shapes[1];
                if br != r {
                    return Err(error(
                        ms[0].span,
                        format!(
                            "solve(A, b) with A {} and b {}: b needs {r} rows",
                            shape_words((r, r)),
                            shape_words((br, bc))
                        ),
                    ));
                }
                let b = as_matrix(ms.remove(0), (br, bc));
                matrix(
                    r,
                    bc,
                    MatrixOp::Solve(Box::new(a), Box::new(b)),
                    bound,
                    span,
                )
            }
            _ => unreachable!("the views and the identity are handled by the caller"),
        })
    }

    /// `voigt_ij`: a declared order and the slots it binds (digits only in the tensor
    /// view, where they fix a component).
    fn order(&self, e: &Expr, digits: bool) -> Result<Order, LangError> {
        let ExprKind::Name { base, indices, .. } = &e.kind else {
            return Err(LangError::new(
                ErrorKind::Syntax,
                e.span,
                "an order is written with the indices it binds, as in voigt_ij",
            ));
        };
        let Some(positions) = self.decls.orders.get(base) else {
            let known: Vec<&str> = self.decls.orders.keys().map(String::as_str).collect();
            return Err(LangError::new(
                ErrorKind::Name,
                e.span,
                format!("`{base}` is not a declared order"),
            )
            .help(if known.is_empty() {
                "declare it at the top of the file: orders = { voigt = [\"11\", \"22\", \"12\", \"21\"] }".to_owned()
            } else {
                format!("declared orders: {}", known.join(", "))
            }));
        };
        let width = positions.first().map_or(0, Vec::len);
        if indices.len() != width {
            return Err(error(
                e.span,
                format!(
                    "the positions of `{base}` have {width} component{}, so it binds {width} ind{}",
                    if width == 1 { "" } else { "s" },
                    if width == 1 { "ex" } else { "ices" }
                ),
            ));
        }
        let mut slots = Vec::with_capacity(width);
        for t in indices {
            match t.ch.to_digit(10) {
                Some(_) if !digits => {
                    return Err(error(
                        t.span,
                        "a matrix view binds index letters, not fixed components",
                    ))
                }
                Some(k) if (1..=self.decls.dim as u32).contains(&k) => {
                    slots.push(Slot::Fixed(k as usize - 1))
                }
                Some(k) => {
                    return Err(LangError::new(
                        ErrorKind::Dimension,
                        t.span,
                        format!("fixed index {k} is outside 1..={}", self.decls.dim),
                    ))
                }
                None => {
                    if slots.contains(&Slot::Letter(t.ch)) {
                        return Err(error(
                            t.span,
                            format!("index `{}` is bound twice by one order", t.ch),
                        ));
                    }
                    slots.push(Slot::Letter(t.ch));
                }
            }
        }
        Ok(Order {
            name: base.clone(),
            positions: positions.clone(),
            slots,
        })
    }
}

/// A scalar standing for a 1×1 matrix becomes one again, for a matrix operation.
fn as_matrix(node: Node, shape: (usize, usize)) -> Node {
    if node.shape().is_some() {
        return node;
    }
    if let NodeKind::Read(MatrixRead::Entry(0, 0), inner) = &node.kind {
        if inner.shape() == Some((1, 1)) {
            return (**inner).clone();
        }
    }
    let span = node.span;
    let bound = node.bound.clone();
    Node {
        kind: NodeKind::Matrix {
            rows: shape.0,
            cols: shape.1,
            op: MatrixOp::Literal(vec![node]),
        },
        free: Vec::new(),
        bound,
        span,
    }
}

fn scale(s: Node, m: Node, span: Span) -> Node {
    let (r, c) = m.shape().expect("a matrix is scaled");
    let bound = bound_of(&[&s, &m]);
    matrix(r, c, MatrixOp::Scale(Box::new(s), Box::new(m)), bound, span)
}

fn multiply(a: Node, b: Node) -> Result<Node, LangError> {
    let ((ar, ac), (br, bc)) = (a.shape().expect("matrix"), b.shape().expect("matrix"));
    if ac != br {
        return Err(LangError::new(
            ErrorKind::Dimension,
            b.span,
            format!(
                "{} times {}: the columns of the first ({ac}) must match the rows of the second ({br})",
                shape_words((ar, ac)),
                shape_words((br, bc))
            ),
        )
        .help("transpose one factor with A^T, or reorder the product"));
    }
    let span = a.span.to(b.span);
    let bound = bound_of(&[&a, &b]);
    Ok(matrix(
        ar,
        bc,
        MatrixOp::Product(Box::new(a), Box::new(b)),
        bound,
        span,
    ))
}
