//! Name resolution and index validation: turns a parsed [`Expr`] into a checked
//! [`Node`] whose free indices are known, or explains precisely what is wrong.
//!
//! Rules (Einstein summation, as in the paper's Section 2):
//! - in a product, each index letter occurs once (free) or twice (summed), never more;
//! - a letter summed inside a factor (a parenthesised sum, an `avg`, a definition) may
//!   not appear again elsewhere in the same product;
//! - all terms of a sum have the same free indices;
//! - divisors, powers and `sqrt` take scalars (no free index);
//! - a name carries exactly as many indices as its rank; fixed indices run 1..=d;
//!   `eps` has rank d.

use super::diag::Span;
use super::parser::{ErrorKind, Expr, ExprKind, Func, Func2, IndexTok, LangError, Wrt};
use crate::algebra::tensor::{
    assignment_count_saturating as assignment_count, MAX_ASSIGNMENTS, MAX_COMPONENTS,
};
use crate::kernel::Rational;
use std::collections::BTreeMap;

/// The names declared by a derivation file.
#[derive(Clone, Debug, Default)]
pub struct Decls {
    /// Dimension d of the index range 1..=d (2 or 3).
    pub dim: usize,
    /// The name of the unit contact normal averaged over by `avg(…)`, if any.
    pub normal: Option<String>,
    /// The normal lies in the 1-2 plane (n_3 = 0) and is uniform on its unit circle:
    /// plane problems with a 3D index range (Section 4).
    pub normal_in_plane: bool,
    /// Declared symbols and their ranks (0 for scalars such as `R_g`). Fields and the
    /// position are symbols too: at one point, a field is a tensor like any other.
    pub symbols: BTreeMap<String, usize>,
    /// The fields (symbols that vary with the position), each with the coordinates it
    /// depends on: `deps[k]` for x_{k+1}.
    pub fields: BTreeMap<String, Vec<bool>>,
    /// The name of the position vector x_i, if the file declares one.
    pub position: Option<String>,
    /// The position orders of the matrix views (`voigt` → (1,1), (2,2), (1,2), (2,1)),
    /// components 0-based.
    pub orders: BTreeMap<String, Vec<Vec<usize>>>,
}

impl Decls {
    /// Whether `name` is a field or the position: something a derivative can act on.
    pub fn varies(&self, name: &str) -> bool {
        self.fields.contains_key(name) || self.position.as_deref() == Some(name)
    }
}

/// A definition visible in a scope: its name and formal index letters.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DefSig {
    pub name: String,
    pub formal: Vec<char>,
    /// The shape of a matrix definition (its `formal` is then empty).
    pub shape: Option<(usize, usize)>,
}

/// What a name refers to.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Target {
    Symbol(String),
    Def(String),
    Delta,
    Eps,
    Normal,
    /// π: a real constant, not a rational (exact mode refuses it).
    Pi,
}

/// One index slot of a leaf (the kernel's contraction reads the same slots).
pub use crate::algebra::einsum::Slot;

/// A checked expression node. `free` is sorted by letter and gives, for each free
/// index, where it occurs; `bound` lists letters summed anywhere inside the node.
#[derive(Clone, Debug, PartialEq)]
pub struct Node {
    pub kind: NodeKind,
    pub free: Vec<(char, Span)>,
    pub bound: Vec<char>,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub enum NodeKind {
    Const(Rational),
    Leaf {
        target: Target,
        slots: Vec<Slot>,
    },
    Sum(Vec<Node>),
    /// Indices that occur in two factors are summed over.
    Product(Vec<Node>),
    Div(Box<Node>, Box<Node>),
    Neg(Box<Node>),
    Pow(Box<Node>, u32),
    /// A function of two scalars (`atan2`, `min`, `max`, a real power).
    Apply2(Func2, Box<Node>, Box<Node>),
    /// A scalar function (`sqrt`, `abs`, `cos`, `sin`, `tan`, `exp`, `log`, `atan`,
    /// `asin`, `acos`) of a scalar.
    Apply(Func, Box<Node>),
    Avg(Box<Node>),
    /// The maximum over the orientation of the normal of a scalar.
    MaxN(Box<Node>),
    /// The derivative of a node with respect to one coordinate of the position, the
    /// coordinate given by the slot: `u_j,i` is `Deriv(u_j, i)`; `u_j,ik` nests two.
    Deriv(Box<Node>, Slot),
    /// A derivative of `body` with respect to every component of the declared
    /// `symbol`, one component per slot of the symbol (they follow `body`'s):
    /// - [`Wrt::Variation`], `variation(P, v_j)`: the variational (Euler–Lagrange)
    ///   derivative of the density `P` with respect to the field `v`,
    ///   Σ_α (−1)^|α| D_α (∂P/∂v_j,α) over the field's derivatives v_j,α that `P`
    ///   reads. Convention: δ∫P dV = ∫ variation(P, v_j) δv_j dV + boundary terms, so
    ///   for P = σ_ij v_j,i it is −σ_ij,i.
    /// - [`Wrt::Grad`], `grad(F, sigma_ij)`: ∂F/∂σ_ij with every component of σ an
    ///   independent variable and every other symbol held fixed, evaluated at the
    ///   state the assumptions give (the assumptions apply after differentiating).
    Wrt {
        op: Wrt,
        body: Box<Node>,
        symbol: String,
        slots: Vec<Slot>,
    },
    /// A matrix (see [`super::matrix`]): no free index, `rows × cols` entries.
    Matrix {
        rows: usize,
        cols: usize,
        op: MatrixOp,
    },
    /// A scalar or a tensor read off a matrix: det, trace, an entry, the index view.
    Read(MatrixRead, Box<Node>),
}

/// A declared position order bound to index slots: `voigt_ij` is the order `voigt`
/// with its positions' components read into the slots i and j.
#[derive(Clone, Debug, PartialEq)]
pub struct Order {
    pub name: String,
    /// The positions, each one component per slot (0-based).
    pub positions: Vec<Vec<usize>>,
    pub slots: Vec<Slot>,
}

impl Order {
    /// The position whose components are `values`, if the order has it.
    pub fn position_of(&self, values: &[usize]) -> Option<usize> {
        self.positions.iter().position(|p| p == values)
    }
}

/// A matrix-valued node's operation (the node is [`NodeKind::Matrix`]).
#[derive(Clone, Debug, PartialEq)]
pub enum MatrixOp {
    /// The entries row by row, each a scalar node.
    Literal(Vec<Node>),
    /// A matrix definition.
    Def(String),
    Identity,
    /// Matrices of one shape.
    Sum(Vec<Node>),
    /// A scalar times a matrix.
    Scale(Box<Node>, Box<Node>),
    Product(Box<Node>, Box<Node>),
    Transpose(Box<Node>),
    Inverse(Box<Node>),
    Adjugate(Box<Node>),
    /// `solve(A, b)`.
    Solve(Box<Node>, Box<Node>),
    /// The matrix (or, without `cols`, column) view of a tensor: entry (a, b) is the
    /// component at the rows' position a and the columns' position b.
    View {
        tensor: Box<Node>,
        rows: Box<Order>,
        cols: Option<Box<Order>>,
    },
}

/// What is read off a matrix (the node is [`NodeKind::Read`]).
#[derive(Clone, Debug, PartialEq)]
pub enum MatrixRead {
    Det,
    Trace,
    /// One entry, 0-based.
    Entry(usize, usize),
    /// The index view: the tensor whose component at the rows' position a (and the
    /// columns' position b) is the entry (a, b), and zero at positions the orders
    /// leave out.
    Tensor {
        rows: Box<Order>,
        cols: Option<Box<Order>>,
    },
}

impl Node {
    /// Whether the node is the literal `0`, which stands for a zero tensor of any
    /// rank (`avg(n_i n_j n_k) = 0`).
    pub fn is_literal_zero(&self) -> bool {
        matches!(&self.kind, NodeKind::Const(q) if q.is_zero())
    }

    /// The literal `0` standing for a zero tensor with the free indices `letters`
    /// (sorted), where a context expects them: a definition `z_ij = 0`, a closed-form
    /// gradient `mu = "0"`. Every route evaluates a constant with free indices as that
    /// constant in every component.
    pub fn zero_with_free(&self, letters: &[char]) -> Node {
        debug_assert!(self.is_literal_zero());
        Node {
            kind: NodeKind::Const(Rational::int(0)),
            free: letters.iter().map(|&c| (c, self.span)).collect(),
            bound: Vec::new(),
            span: self.span,
        }
    }

    /// Whether two sides of an equation carry the same free indices (the literal `0`
    /// matches any): the one rule every reader of sides applies.
    pub fn matches_free_indices(&self, other: &Node) -> bool {
        self.is_literal_zero()
            || other.is_literal_zero()
            || self.free_letters() == other.free_letters()
    }

    /// The definition the node refers to directly: a tensor's (`t_i`) or a matrix's.
    pub fn definition(&self) -> Option<&str> {
        match &self.kind {
            NodeKind::Leaf {
                target: Target::Def(name),
                ..
            }
            | NodeKind::Matrix {
                op: MatrixOp::Def(name),
                ..
            } => Some(name),
            _ => None,
        }
    }

    /// The node with its free letters fixed at the 0-based values `at` (a letter `at`
    /// leaves out stays free): one component of it, to evaluate without the others.
    /// A letter is replaced only where it is free, so a letter summed inside a
    /// divisor or a function is untouched. `None` for a derivative, a variation or
    /// gradient, or a matrix, whose fixed forms are not built.
    pub fn at_indices(&self, at: &[(char, usize)]) -> Option<Node> {
        let here: Vec<(char, usize)> = at
            .iter()
            .copied()
            .filter(|(c, _)| self.free.iter().any(|(d, _)| d == c))
            .collect();
        if here.is_empty() {
            return Some(self.clone());
        }
        let fix = |n: &Node| n.at_indices(&here).map(Box::new);
        let kind = match &self.kind {
            NodeKind::Const(q) => NodeKind::Const(q.clone()),
            NodeKind::Leaf { target, slots } => NodeKind::Leaf {
                target: target.clone(),
                slots: slots
                    .iter()
                    .map(|s| match s {
                        Slot::Letter(c) => here
                            .iter()
                            .find(|(d, _)| d == c)
                            .map_or(*s, |&(_, v)| Slot::Fixed(v)),
                        Slot::Fixed(_) => *s,
                    })
                    .collect(),
            },
            NodeKind::Sum(xs) => NodeKind::Sum(
                xs.iter()
                    .map(|x| x.at_indices(&here))
                    .collect::<Option<_>>()?,
            ),
            NodeKind::Product(xs) => NodeKind::Product(
                xs.iter()
                    .map(|x| x.at_indices(&here))
                    .collect::<Option<_>>()?,
            ),
            NodeKind::Div(a, b) => NodeKind::Div(fix(a)?, b.clone()),
            NodeKind::Neg(a) => NodeKind::Neg(fix(a)?),
            NodeKind::Avg(a) => NodeKind::Avg(fix(a)?),
            _ => return None,
        };
        Some(Node {
            kind,
            free: self
                .free
                .iter()
                .copied()
                .filter(|(c, _)| !here.iter().any(|(d, _)| d == c))
                .collect(),
            bound: self.bound.clone(),
            span: self.span,
        })
    }

    /// The free index letters, sorted.
    pub fn free_letters(&self) -> Vec<char> {
        self.free.iter().map(|&(c, _)| c).collect()
    }

    /// The node's direct operands, in order.
    pub fn children(&self) -> Vec<&Node> {
        match &self.kind {
            NodeKind::Const(_) | NodeKind::Leaf { .. } => Vec::new(),
            NodeKind::Sum(xs) | NodeKind::Product(xs) => xs.iter().collect(),
            NodeKind::Div(a, b) | NodeKind::Apply2(_, a, b) => vec![a, b],
            NodeKind::Neg(a)
            | NodeKind::Pow(a, _)
            | NodeKind::Apply(_, a)
            | NodeKind::Avg(a)
            | NodeKind::MaxN(a)
            | NodeKind::Deriv(a, _)
            | NodeKind::Wrt { body: a, .. }
            | NodeKind::Read(_, a) => vec![a],
            NodeKind::Matrix { op, .. } => match op {
                MatrixOp::Literal(xs) | MatrixOp::Sum(xs) => xs.iter().collect(),
                MatrixOp::Def(_) | MatrixOp::Identity => Vec::new(),
                MatrixOp::Scale(a, b) | MatrixOp::Product(a, b) | MatrixOp::Solve(a, b) => {
                    vec![a, b]
                }
                MatrixOp::Transpose(a)
                | MatrixOp::Inverse(a)
                | MatrixOp::Adjugate(a)
                | MatrixOp::View { tensor: a, .. } => vec![a],
            },
        }
    }

    /// The declared symbols the node refers to directly (not through definitions).
    pub fn symbols(&self) -> std::collections::BTreeSet<&str> {
        let mut out = std::collections::BTreeSet::new();
        let mut stack = vec![self];
        while let Some(node) = stack.pop() {
            if let NodeKind::Leaf {
                target: Target::Symbol(s),
                ..
            } = &node.kind
            {
                out.insert(s.as_str());
            }
            stack.extend(node.children());
        }
        out
    }
}

/// How deeply gradients nest in `node` (0: none), and how many variations it holds (not
/// looking into definitions).
fn nested_wrt(node: &Node) -> (usize, usize) {
    let (mut depth, mut variations) = (0, 0);
    for child in node.children() {
        let (d, v) = nested_wrt(child);
        depth = depth.max(d);
        variations += v;
    }
    match &node.kind {
        NodeKind::Wrt { op: Wrt::Grad, .. } => (depth + 1, variations),
        NodeKind::Wrt { .. } => (depth, variations + 1),
        _ => (depth, variations),
    }
}

/// Formats a list of index letters for messages: `i, l` or `none`.
pub fn letters(ls: &[char]) -> String {
    if ls.is_empty() {
        "none".into()
    } else {
        ls.iter()
            .map(char::to_string)
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// Names that cannot be declared: built-ins and functions.
pub const RESERVED: [&str; 27] = [
    "delta",
    "eps",
    "pi",
    "sqrt",
    "abs",
    "cos",
    "sin",
    "tan",
    "exp",
    "log",
    "atan",
    "asin",
    "acos",
    "avg",
    "maxn",
    "variation",
    "grad",
    "det",
    "trace",
    "inv",
    "adj",
    "transpose",
    "solve",
    "identity",
    "matrix",
    "vector",
    "tensor",
];

/// Resolves and validates expressions against declarations and visible definitions.
pub struct Scope<'a> {
    pub decls: &'a Decls,
    pub defs: &'a [DefSig],
}

impl Scope<'_> {
    /// The checked node of `e`, whose components and whose products' index values stay
    /// within the kernel's bounds ([`MAX_COMPONENTS`], [`MAX_ASSIGNMENTS`]), checked
    /// before anything is evaluated or allocated.
    pub fn check(&self, e: &Expr) -> Result<Node, LangError> {
        let node = self.check_node(e)?;
        let components = assignment_count(self.decls.dim, node.free.len());
        if components > MAX_COMPONENTS {
            return Err(LangError::new(
                ErrorKind::Index,
                e.span,
                format!(
                    "this expression has {} free indices, {components} components in {}D; at most {MAX_COMPONENTS} are supported",
                    node.free.len(),
                    self.decls.dim
                ),
            )
            .help("split the statement into smaller tensors"));
        }
        Ok(node)
    }

    fn check_node(&self, e: &Expr) -> Result<Node, LangError> {
        match &e.kind {
            ExprKind::Number(q) => Ok(leafless(NodeKind::Const(q.clone()), e.span)),
            ExprKind::Name {
                full,
                base,
                indices,
            } => self.name(full, base, indices, e.span),
            ExprKind::Neg(a) => {
                let a = self.check(a)?;
                if a.shape().is_some() {
                    return Ok(self.matrix_neg(a, e.span));
                }
                Ok(wrap(a, e.span, |a| NodeKind::Neg(Box::new(a))))
            }
            ExprKind::Matrix(rows) => self.literal(rows, e.span),
            ExprKind::Entry(inner, at) => self.entry(inner, at, e.span),
            ExprKind::MatCall(f, args) => self.mat_call(*f, args, e.span),
            ExprKind::Add(..) | ExprKind::Sub(..) => self.sum(e),
            ExprKind::Mul(..) => self.product(e),
            ExprKind::Div(a, b) => {
                let num = self.check(a)?;
                let den = self.check(b)?;
                if num.shape().is_some() {
                    return self.matrix_divide(num, den, e.span);
                }
                self.not_matrix(&den, "a divisor")?;
                if let Some(&(c, span)) = den.free.first() {
                    return Err(LangError::new(
                        ErrorKind::Index,
                        span,
                        format!(
                            "a divisor must be a scalar, but this one has free index {}",
                            letters(&den.free_letters())
                        ),
                    )
                    .help(format!(
                        "sum over `{c}` inside the divisor, or multiply instead"
                    )));
                }
                reject_reuse(&[&num, &den])?;
                let mut bound = num.bound.clone();
                bound.extend(&den.bound);
                Ok(Node {
                    free: num.free.clone(),
                    bound,
                    span: e.span,
                    kind: NodeKind::Div(Box::new(num), Box::new(den)),
                })
            }
            ExprKind::Pow(a, k) => {
                let checked = self.check(a)?;
                if checked.shape().is_some() {
                    return self.matrix_power(checked, *k, e.span);
                }
                let a = self.scalar_arg(a, "a power")?;
                let k = *k;
                Ok(wrap(a, e.span, |a| NodeKind::Pow(Box::new(a), k)))
            }
            ExprKind::Call(func @ (Func::Avg | Func::MaxN), a) => {
                if self.decls.normal.is_none() {
                    return Err(LangError::new(
                        ErrorKind::Name,
                        e.span,
                        format!(
                            "{}(…) needs a contact normal, and this file declares none",
                            func.name()
                        ),
                    )
                    .help("add `normal = \"n\"` at the top of the file"));
                }
                if *func == Func::Avg {
                    let a = self.check(a)?;
                    self.not_matrix(&a, "avg(…)")?;
                    return Ok(wrap(a, e.span, |a| NodeKind::Avg(Box::new(a))));
                }
                let a = self.scalar_arg(a, "maxn")?;
                Ok(wrap(a, e.span, |a| NodeKind::MaxN(Box::new(a))))
            }
            ExprKind::Call(func, a) => {
                let a = self.scalar_arg(a, func.name())?;
                let func = *func;
                Ok(wrap(a, e.span, |a| NodeKind::Apply(func, Box::new(a))))
            }
            ExprKind::Deriv {
                inner,
                indices,
                wrt,
            } => self.derivative(inner, indices, wrt.as_ref(), e.span),
            ExprKind::Wrt { op, body, symbol } => self.wrt(*op, body, symbol, e.span),
            ExprKind::Call2(func, a, b) => {
                let what = match func {
                    Func2::Pow => "a real power",
                    f => f.name(),
                };
                let (a, b) = (self.scalar_arg(a, what)?, self.scalar_arg(b, what)?);
                let mut bound = a.bound.clone();
                bound.extend(&b.bound);
                Ok(Node {
                    free: Vec::new(),
                    bound,
                    span: e.span,
                    kind: NodeKind::Apply2(*func, Box::new(a), Box::new(b)),
                })
            }
        }
    }

    /// `u_j,i…` or `d(expr)/dx_i…`: one [`NodeKind::Deriv`] per index, innermost
    /// first, so that `u_i,i` is a divergence and `u_i,jj` a Laplacian.
    fn derivative(
        &self,
        inner: &Expr,
        indices: &[IndexTok],
        wrt: Option<&(String, Span)>,
        span: Span,
    ) -> Result<Node, LangError> {
        let position = self.decls.position.as_deref();
        if let Some((name, at)) = wrt {
            if position != Some(name.as_str()) {
                let help = match position {
                    Some(p) => format!("the position is `{p}`: write d(…)/d{p}_i"),
                    None => {
                        "declare the position at the top of the file: position = \"x\"".to_owned()
                    }
                };
                return Err(LangError::new(
                    ErrorKind::Name,
                    *at,
                    format!("`{name}` is not the declared position"),
                )
                .help(help));
            }
        }
        let mut node = self.check(inner)?;
        self.not_matrix(&node, "a derivative")?;
        if wrt.is_none() {
            // A comma on a name that cannot vary is a slip, not a zero.
            let varies = match &node.kind {
                NodeKind::Leaf {
                    target: Target::Symbol(s),
                    ..
                } => self.decls.varies(s),
                NodeKind::Leaf {
                    target: Target::Def(_),
                    ..
                } => true,
                _ => false,
            };
            if !varies {
                let ExprKind::Name { base, full, .. } = &inner.kind else {
                    unreachable!("the comma form follows a name")
                };
                let name = if self.decls.symbols.contains_key(full) {
                    full
                } else {
                    base
                };
                return Err(LangError::new(
                    ErrorKind::Name,
                    inner.span,
                    format!("`{name}` is not a field, so its derivative is zero"),
                )
                .help(format!(
                    "declare it in `fields` (e.g. fields = [\"{}\"]) if it varies with the position",
                    inner_text(inner)
                )));
            }
        }
        let dim = self.decls.dim;
        for t in indices {
            let slot = match t.ch.to_digit(10) {
                Some(k) if (1..=dim as u32).contains(&k) => Slot::Fixed(k as usize - 1),
                Some(k) => {
                    return Err(LangError::new(
                        ErrorKind::Dimension,
                        t.span,
                        format!("coordinate {k} is outside 1..={dim} in {dim}D"),
                    )
                    .help(format!("coordinates run from 1 to {dim}")))
                }
                None => Slot::Letter(t.ch),
            };
            if node.bound.contains(&t.ch) {
                return Err(LangError::new(
                    ErrorKind::Index,
                    t.span,
                    format!(
                        "index `{}` is summed inside what is differentiated and used again here",
                        t.ch
                    ),
                )
                .help(format!("rename the summed `{}` inside", t.ch)));
            }
            let mut occurrences = node.free.clone();
            if let Slot::Letter(c) = slot {
                occurrences.push((c, t.span));
            }
            let (free, mut bound) = tally(occurrences)?;
            bound.extend(&node.bound);
            node = Node {
                kind: NodeKind::Deriv(Box::new(node), slot),
                free,
                bound,
                span,
            };
        }
        Ok(node)
    }

    /// `variation(P, v_j)` or `grad(F, sigma_ij)`: the body and a symbol written with
    /// its own index letters, which become free indices of the result (the symbol's
    /// slots follow the body's). A variation takes a field; a gradient takes a
    /// declared symbol that does not vary with position. See [`NodeKind::Wrt`].
    fn wrt(&self, op: Wrt, body: &Expr, symbol: &Expr, span: Span) -> Result<Node, LangError> {
        let name = op.name();
        let body = self.check(body)?;
        self.not_matrix(&body, &format!("{name}(…)"))?;
        // A gradient may hold one gradient (second derivatives); nothing else nests.
        let (gradients, variations) = nested_wrt(&body);
        if variations > 0 || (op == Wrt::Variation && gradients > 0) || gradients > 1 {
            let what = if variations > 0 || op == Wrt::Variation {
                "a variation or gradient"
            } else {
                "a third derivative (a gradient inside two)"
            };
            return Err(LangError::new(
                ErrorKind::Syntax,
                body.span,
                format!("{what} inside {name}(…) is not supported"),
            )
            .help(match op {
                Wrt::Variation => {
                    "name the inner one with a definition and vary that definition's density"
                }
                Wrt::Grad => {
                    "grad(…) nests once, for second derivatives: grad(grad(F, a_ij), b_kl)"
                }
            }));
        }
        let example = match op {
            Wrt::Variation => "a field with its indices, such as v_j",
            Wrt::Grad => "a declared symbol with its indices, such as sigma_ij",
        };
        let ExprKind::Name {
            full,
            base,
            indices,
        } = &symbol.kind
        else {
            return Err(LangError::new(
                ErrorKind::Syntax,
                symbol.span,
                format!("the second argument of {name}(…) is {example}"),
            ));
        };
        let symbol_node = self.name(full, base, indices, symbol.span)?;
        let (target, slots) = match &symbol_node.kind {
            NodeKind::Leaf {
                target: Target::Symbol(s),
                slots,
            } => (s.clone(), slots.clone()),
            _ => (String::new(), Vec::new()),
        };
        if target.is_empty() || (op == Wrt::Variation && !self.decls.fields.contains_key(&target)) {
            let what = match op {
                Wrt::Variation => "field",
                Wrt::Grad => "symbol",
            };
            return Err(LangError::new(
                ErrorKind::Name,
                symbol.span,
                format!("`{}` is not a declared {what}", inner_text(symbol)),
            )
            .help(match op {
                Wrt::Variation => {
                    "vary a field declared in `fields`, e.g. fields = [\"v_i\"]".to_owned()
                }
                Wrt::Grad => format!("the second argument of {name}(…) is {example}"),
            }));
        }
        let varies = self.decls.varies(&target);
        match op {
            Wrt::Grad if varies => {
                return Err(LangError::new(
                    ErrorKind::Name,
                    symbol.span,
                    format!("`{target}` varies with position, so grad(…) does not apply to it"),
                )
                .help("differentiate along the position with a comma (u_j,i), or vary a field with variation(…)"))
            }
            _ => {}
        }
        if op == Wrt::Grad && slots.iter().any(|s| matches!(s, Slot::Fixed(_))) {
            return Err(LangError::new(
                ErrorKind::Index,
                symbol.span,
                "grad(…) takes the symbol with index letters, one per slot",
            )
            .help("write grad(F, sigma_ij) and pick a component of the result, e.g. with a definition Q_ij = grad(F, sigma_ij), then Q_12"));
        }
        if let Some(&c) = symbol_node.bound.first() {
            // `sigma_ii` would be a trace, not a symbol to differentiate by.
            return Err(LangError::new(
                ErrorKind::Index,
                symbol.span,
                format!("index `{c}` repeats in the symbol of {name}(…): it takes one letter per slot, each once"),
            )
            .help(format!("write {name}(…, sigma_ij) with distinct letters and contract the result afterwards")));
        }
        let mut occurrences = body.free.clone();
        for &(c, s) in &symbol_node.free {
            if body.bound.contains(&c) || occurrences.iter().any(|&(d, _)| d == c) {
                let what = match op {
                    Wrt::Variation => "of the varied field is also an index of the density",
                    Wrt::Grad => {
                        "of the symbol differentiated by is also an index of the expression"
                    }
                };
                return Err(
                    LangError::new(ErrorKind::Index, s, format!("index `{c}` {what}"))
                        .help("give the symbol index letters the first argument does not use"),
                );
            }
            occurrences.push((c, s));
        }
        let (free, mut bound) = tally(occurrences)?;
        bound.extend(&body.bound);
        bound.extend(&symbol_node.bound);
        Ok(Node {
            kind: NodeKind::Wrt {
                op,
                body: Box::new(body),
                symbol: target,
                slots,
            },
            free,
            bound,
            span,
        })
    }

    fn scalar_arg(&self, a: &Expr, what: &str) -> Result<Node, LangError> {
        let a = self.check(a)?;
        self.not_matrix(&a, what)?;
        if let Some(&(c, span)) = a.free.first() {
            return Err(LangError::new(
                ErrorKind::Index,
                span,
                format!(
                    "{what} takes a scalar, but this has free index {}",
                    letters(&a.free_letters())
                ),
            )
            .help(format!(
                "contract `{c}` first, e.g. x_{c} x_{c} instead of x_{c}^2"
            )));
        }
        Ok(a)
    }

    fn name(
        &self,
        full: &str,
        base: &str,
        indices: &[IndexTok],
        span: Span,
    ) -> Result<Node, LangError> {
        let dim = self.decls.dim;
        let def = |n: &str| self.defs.iter().rev().find(|d| d.name == n);
        if let Some(shape) = def(full).and_then(|d| d.shape) {
            return Ok(self.matrix_def(full, shape, span));
        }
        // A whole token such as `R_g` may itself be a scalar's name.
        if !indices.is_empty() {
            if self.decls.symbols.get(full) == Some(&0) {
                return Ok(leaf(Target::Symbol(full.into()), vec![], vec![], span));
            }
            if def(full).is_some_and(|d| d.formal.is_empty()) {
                return Ok(leaf(Target::Def(full.into()), vec![], vec![], span));
            }
        }
        if let Some((rows, cols)) = def(base).and_then(|d| d.shape) {
            return Err(LangError::new(
                ErrorKind::Index,
                span,
                format!("`{base}` is a {rows}×{cols} matrix and takes no index letters"),
            )
            .help(format!(
                "read an entry as {base}[1,2], or use it whole ({base}^T, det({base}), {base} b)"
            )));
        }
        let (target, rank) = match base {
            "delta" => (Target::Delta, 2),
            "pi" => (Target::Pi, 0),
            "eps" => (Target::Eps, dim),
            _ if self.decls.normal.as_deref() == Some(base) => (Target::Normal, 1),
            _ => {
                if let Some(d) = def(base) {
                    (Target::Def(base.into()), d.formal.len())
                } else if let Some(&r) = self.decls.symbols.get(base) {
                    (Target::Symbol(base.into()), r)
                } else {
                    return Err(self.unknown(base, span));
                }
            }
        };
        if indices.len() != rank {
            let what = match &target {
                Target::Eps => format!("eps has {rank} indices in {dim}D"),
                _ if rank == 0 => format!("`{base}` is a scalar and takes no indices"),
                _ => format!(
                    "`{base}` has rank {rank} but is written with {} ind{}",
                    indices.len(),
                    if indices.len() == 1 { "ex" } else { "ices" }
                ),
            };
            let kind = if matches!(target, Target::Eps) {
                ErrorKind::Dimension
            } else {
                ErrorKind::Index
            };
            return Err(LangError::new(kind, span, what).help(format!(
                "write {base}{}{}",
                if rank == 0 { "" } else { "_" },
                &"ijklmnpqrs"[..rank.min(10)]
            )));
        }
        let mut slots = Vec::with_capacity(rank);
        let mut occurrences = Vec::with_capacity(rank);
        for t in indices {
            if let Some(d) = t.ch.to_digit(10) {
                let d = d as usize;
                if d == 0 || d > dim {
                    return Err(LangError::new(
                        ErrorKind::Dimension,
                        t.span,
                        format!("fixed index {d} is outside 1..={dim} in {dim}D"),
                    )
                    .help(format!("components run from 1 to {dim}")));
                }
                slots.push(Slot::Fixed(d - 1));
            } else {
                slots.push(Slot::Letter(t.ch));
                occurrences.push((t.ch, t.span));
            }
        }
        let (free, bound) = tally(occurrences)?;
        Ok(leaf(target, slots, free, span).with_bound(bound))
    }

    fn unknown(&self, base: &str, span: Span) -> LangError {
        let mut known: Vec<String> = self.decls.symbols.keys().cloned().collect();
        known.extend(self.defs.iter().map(|d| d.name.clone()));
        known.extend(self.decls.normal.iter().cloned());
        known.sort();
        known.dedup();
        let close = known
            .iter()
            .filter(|k| {
                k.eq_ignore_ascii_case(base) || k.starts_with(base) || base.starts_with(k.as_str())
            })
            .cloned()
            .collect::<Vec<_>>();
        let help = if close.is_empty() {
            format!(
                "declare it in `tensors`/`scalars`, or define it in `define`; known names: {}",
                known.join(", ")
            )
        } else {
            format!("did you mean {}?", close.join(" or "))
        };
        let mut e =
            LangError::new(ErrorKind::Name, span, format!("unknown name `{base}`")).help(help);
        e.unknown = Some(base.to_owned());
        e
    }

    fn sum(&self, e: &Expr) -> Result<Node, LangError> {
        let mut terms = Vec::new();
        flatten_sum(e, false, &mut terms);
        let mut nodes: Vec<Node> = Vec::with_capacity(terms.len());
        for (neg, t) in terms {
            let n = self.check(t)?;
            // The literal 0 is a zero of any rank: as a term it adds nothing.
            if n.is_literal_zero() {
                continue;
            }
            if n.shape().is_some() {
                nodes.push(if neg { self.matrix_neg(n, t.span) } else { n });
                continue;
            }
            if nodes.first().is_some_and(|f| f.shape().is_some()) {
                // A scalar among matrices: refused with the shapes by `matrix_sum`.
                nodes.push(n);
                continue;
            }
            if let Some(first) = nodes.first() {
                if first.free_letters() != n.free_letters() {
                    return Err(LangError::new(
                        ErrorKind::Index,
                        n.span,
                        format!(
                            "free indices differ between terms: {} here, {} in the first term",
                            letters(&n.free_letters()),
                            letters(&first.free_letters())
                        ),
                    )
                    .help("every term of a sum must have the same free indices"));
                }
            }
            nodes.push(if neg {
                let span = n.span;
                wrap(n, span, |n| NodeKind::Neg(Box::new(n)))
            } else {
                n
            });
        }
        let Some(first) = nodes.first() else {
            return Ok(leafless(NodeKind::Const(Rational::int(0)), e.span));
        };
        if nodes.iter().any(|n| n.shape().is_some()) {
            return self.matrix_sum(nodes, e.span);
        }
        let free = first.free.clone();
        let bound = nodes.iter().flat_map(|n| n.bound.iter().copied()).collect();
        Ok(Node {
            kind: NodeKind::Sum(nodes),
            free,
            bound,
            span: e.span,
        })
    }

    fn product(&self, e: &Expr) -> Result<Node, LangError> {
        let mut factors = Vec::new();
        flatten_product(e, &mut factors);
        let nodes = factors
            .into_iter()
            .map(|f| self.check(f))
            .collect::<Result<Vec<_>, _>>()?;
        if nodes.iter().any(|n| n.shape().is_some()) {
            return self.matrix_product(nodes, e.span);
        }
        let occurrences = nodes.iter().flat_map(|n| n.free.iter().copied()).collect();
        reject_reuse(&nodes.iter().collect::<Vec<_>>())?;
        let (free, mut bound) = tally(occurrences)?;
        // The contraction visits every value of every letter of the product.
        let values = assignment_count(self.decls.dim, free.len() + bound.len());
        if values > MAX_ASSIGNMENTS {
            return Err(LangError::new(
                ErrorKind::Index,
                e.span,
                format!(
                    "this product has {} index letters, {values} index values to visit in {}D; at most {MAX_ASSIGNMENTS} are supported",
                    free.len() + bound.len(),
                    self.decls.dim
                ),
            )
            .help("contract in steps, through definitions of smaller tensors"));
        }
        bound.extend(nodes.iter().flat_map(|n| n.bound.iter().copied()));
        Ok(Node {
            kind: NodeKind::Product(nodes),
            free,
            bound,
            span: e.span,
        })
    }
}

/// Free indices with where they occur, and summed letters.
type Tally = (Vec<(char, Span)>, Vec<char>);

/// Splits index occurrences into free (once) and summed (twice); a third occurrence is
/// an error pointing at it.
///
/// `occurrences` are the index letters with where they occur, in reading order; the
/// result lists letters in alphabetical order (a stable sort keeps each letter's
/// occurrences in reading order, so the third one is the one reported).
fn tally(mut occurrences: Vec<(char, Span)>) -> Result<Tally, LangError> {
    occurrences.sort_by_key(|&(c, _)| c);
    let mut free = Vec::new();
    let mut bound = Vec::new();
    for group in occurrences.chunk_by(|a, b| a.0 == b.0) {
        let c = group[0].0;
        match group.len() {
            1 => free.push((c, group[0].1)),
            2 => bound.push(c),
            n => {
                return Err(LangError::new(
                    ErrorKind::Index,
                    group[2].1,
                    format!("index `{c}` occurs {n} times in one product"),
                )
                .help("an index may occur once (free) or twice (summed); rename one summed pair"))
            }
        }
    }
    Ok((free, bound))
}

/// A letter summed inside one factor must not occur in another factor.
fn reject_reuse(nodes: &[&Node]) -> Result<(), LangError> {
    for (a, na) in nodes.iter().enumerate() {
        for &c in &na.bound {
            for (b, nb) in nodes.iter().enumerate() {
                if a == b {
                    continue;
                }
                if let Some(&(_, span)) = nb.free.iter().find(|(d, _)| *d == c) {
                    return Err(LangError::new(
                        ErrorKind::Index,
                        span,
                        format!("index `{c}` is summed inside another factor of this product and used again here"),
                    )
                    .help(format!("rename the summed `{c}` inside the other factor")));
                }
            }
        }
    }
    Ok(())
}

/// A name as declared in `fields`: `u_j` for `u_j,i`.
fn inner_text(e: &Expr) -> String {
    match &e.kind {
        ExprKind::Name { base, indices, .. } if !indices.is_empty() => {
            format!(
                "{base}_{}",
                indices.iter().map(|t| t.ch).collect::<String>()
            )
        }
        ExprKind::Name { full, .. } => full.clone(),
        _ => String::new(),
    }
}

fn flatten_sum<'e>(e: &'e Expr, neg: bool, out: &mut Vec<(bool, &'e Expr)>) {
    match &e.kind {
        ExprKind::Add(a, b) => {
            flatten_sum(a, neg, out);
            flatten_sum(b, neg, out);
        }
        ExprKind::Sub(a, b) => {
            flatten_sum(a, neg, out);
            flatten_sum(b, !neg, out);
        }
        _ => out.push((neg, e)),
    }
}

fn flatten_product<'e>(e: &'e Expr, out: &mut Vec<&'e Expr>) {
    match &e.kind {
        ExprKind::Mul(a, b) => {
            flatten_product(a, out);
            flatten_product(b, out);
        }
        _ => out.push(e),
    }
}

fn leafless(kind: NodeKind, span: Span) -> Node {
    Node {
        kind,
        free: vec![],
        bound: vec![],
        span,
    }
}

fn leaf(target: Target, slots: Vec<Slot>, free: Vec<(char, Span)>, span: Span) -> Node {
    Node {
        kind: NodeKind::Leaf { target, slots },
        free,
        bound: vec![],
        span,
    }
}

impl Node {
    fn with_bound(mut self, bound: Vec<char>) -> Self {
        self.bound = bound;
        self
    }
}

fn wrap(inner: Node, span: Span, f: impl FnOnce(Node) -> NodeKind) -> Node {
    let free = inner.free.clone();
    let bound = inner.bound.clone();
    Node {
        kind: f(inner),
        free,
        bound,
        span,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parser::parse_expr;

    fn decls() -> Decls {
        Decls {
            dim: 3,
            normal: Some("n".into()),
            normal_in_plane: false,
            symbols: [("sigma", 2), ("mu", 2), ("R_g", 0), ("V", 0), ("x", 1)]
                .into_iter()
                .map(|(k, v)| (k.to_string(), v))
                .collect(),
            ..Decls::default()
        }
    }

    fn check(src: &str) -> Result<Node, LangError> {
        let d = decls();
        let defs = vec![DefSig {
            name: "t".into(),
            formal: vec!['i'],
            shape: None,
        }];
        Scope {
            decls: &d,
            defs: &defs,
        }
        .check(&parse_expr(src).unwrap())
    }

    fn free(src: &str) -> String {
        check(src).unwrap().free_letters().into_iter().collect()
    }

    fn err(src: &str) -> (ErrorKind, String, Span) {
        let e = check(src).unwrap_err();
        (e.kind, e.message, e.span)
    }

    #[test]
    fn free_and_summed_indices() {
        assert_eq!(free("sigma_ki n_k"), "i");
        assert_eq!(free("sigma_ki n_k (delta_il - n_i n_l)"), "l");
        assert_eq!(free("sigma_kk"), "");
        assert_eq!(free("eps_ijk x_j n_k"), "i");
        assert_eq!(free("R_g^2 sigma_ij / V"), "ij");
        assert_eq!(free("avg(n_i n_j n_k n_l)"), "ijkl");
        assert_eq!(free("t_i t_i"), "");
        assert_eq!(free("sigma_1k n_k"), "");
    }

    #[test]
    fn an_index_three_times_is_refused_at_the_third() {
        let (kind, msg, span) = err("sigma_ki n_k n_k");
        assert_eq!(kind, ErrorKind::Index);
        assert_eq!(msg, "index `k` occurs 3 times in one product");
        assert_eq!(span, Span::new(15, 16));
    }

    #[test]
    fn mismatched_terms_are_refused() {
        let (kind, msg, span) = err("n_i + sigma_ki n_k n_l");
        assert_eq!(kind, ErrorKind::Index);
        assert!(msg.contains("i, l here, i in the first term"), "{msg}");
        assert_eq!(span, Span::new(6, 22));
    }

    #[test]
    fn scalars_only_where_scalars_belong() {
        assert_eq!(
            err("x_i / n_i").1,
            "a divisor must be a scalar, but this one has free index i"
        );
        assert!(err("x_i^2").1.contains("a power takes a scalar"));
        assert!(err("sqrt(n_i)").1.contains("sqrt takes a scalar"));
        assert!(err("n_i / (x_i x_i)")
            .1
            .contains("summed inside another factor"));
        let (_, msg, span) = err("x_j (x_j n_j + 1)");
        assert!(msg.contains("summed inside another factor"), "{msg}");
        assert_eq!(span, Span::new(2, 3));
    }

    #[test]
    fn ranks_and_dimensions() {
        assert_eq!(
            err("sigma_i").1,
            "`sigma` has rank 2 but is written with 1 index"
        );
        assert_eq!(err("eps_ij").0, ErrorKind::Dimension);
        let (kind, msg, span) = err("sigma_14");
        assert_eq!(kind, ErrorKind::Dimension);
        assert_eq!(msg, "fixed index 4 is outside 1..=3 in 3D");
        assert_eq!(span, Span::new(7, 8));
        assert_eq!(err("V_i").1, "`V` is a scalar and takes no indices");
    }

    #[test]
    fn unknown_names_get_suggestions() {
        let (kind, msg, _) = err("sigm_ij");
        assert_eq!(kind, ErrorKind::Name);
        assert_eq!(msg, "unknown name `sigm`");
        let e = check("sigm_ij").unwrap_err();
        assert_eq!(e.help.as_deref(), Some("did you mean sigma?"));
    }
}
