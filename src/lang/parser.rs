//! Lexer and parser of the index-notation expression language.
//!
//! Grammar (juxtaposition is multiplication, as on paper):
//!
//! ```text
//! expr   := term (('+' | '-') term)*
//! term   := unary (('*' | '/') unary | unary)*      -- `a b` means `a * b`
//! unary  := '-' unary | power
//! power  := post ('^' integer | '^T')?                  -- A^T is the transpose
//! post   := atom ('[' integer (',' integer)? ']')?     -- A[1,2], v[3]: no space before '['
//! atom   := number | name derivs? | func '(' expr ')' | '(' expr ')'
//!         | 'd(' expr ')/d' position '_' index+       -- d(u_i u_i)/dx_j
//!         | '[' expr (',' expr)* ']'                   -- a column vector
//!         | '[' row (',' row)* ']'                     -- a matrix, row := '[' expr (',' expr)* ']'
//!         | mfunc '(' expr (',' expr)* ')'             -- det(A), solve(A, b), matrix(D_ijkl, v_ij, v_kl)
//! derivs := ',' index+                                -- u_j,i  sigma_ij,j  theta_,kk
//! func   := 'sqrt' | 'abs' | 'cos' | 'sin' | 'tan' | 'exp' | 'log' | 'atan' | 'asin'
//!         | 'acos' | 'avg' | 'maxn'
//! mfunc  := 'det' | 'trace' | 'inv' | 'adj' | 'transpose' | 'solve' | 'identity'
//!         | 'matrix' | 'vector' | 'tensor'
//! name   := letter alnum* ('_' alnum+)*             -- sigma_ki, n_k, R_g, sigma_el_ij
//! number := digits ('.' digits)? (('e' | 'E') ('+' | '-')? digits)?   -- 2.5e-3
//! ```
//!
//! A name's suffix after its last `_` is its index list (one character per slot, a
//! digit being a fixed component 1..=d), and what comes before is the name
//! (`sigma_el_ij`), unless the whole token is a declared scalar such as `R_g`; that is
//! resolved later, in [`super::check`], where the declarations are known (and where a
//! spelling that could be read both ways is refused when it is declared).

use super::diag::Span;
use crate::kernel::Rational;

/// An index slot as written: a letter (free or summed) or a digit (a fixed component).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct IndexTok {
    pub ch: char,
    pub span: Span,
}

/// The functions of the language. `avg` and `maxn` act on the contact normal; the
/// others are ordinary scalar functions (exact mode accepts only `sqrt` of a square).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Func {
    Sqrt,
    Abs,
    Cos,
    Sin,
    Tan,
    Exp,
    /// The natural logarithm.
    Log,
    Atan,
    Asin,
    Acos,
    /// The average over the contact normal.
    Avg,
    /// The maximum over the orientation of the contact normal.
    MaxN,
}

impl Func {
    /// The function called `name`, if any.
    pub fn from_name(name: &str) -> Option<Func> {
        Some(match name {
            "sqrt" => Func::Sqrt,
            "abs" => Func::Abs,
            "cos" => Func::Cos,
            "sin" => Func::Sin,
            "tan" => Func::Tan,
            "exp" => Func::Exp,
            "log" => Func::Log,
            "atan" => Func::Atan,
            "asin" => Func::Asin,
            "acos" => Func::Acos,
            "avg" => Func::Avg,
            "maxn" => Func::MaxN,
            _ => return None,
        })
    }

    pub fn name(self) -> &'static str {
        match self {
            Func::Sqrt => "sqrt",
            Func::Abs => "abs",
            Func::Cos => "cos",
            Func::Sin => "sin",
            Func::Tan => "tan",
            Func::Exp => "exp",
            Func::Log => "log",
            Func::Atan => "atan",
            Func::Asin => "asin",
            Func::Acos => "acos",
            Func::Avg => "avg",
            Func::MaxN => "maxn",
        }
    }
}

/// The functions of two scalars: `atan2(y, x)`, `min(a, b)`, `max(a, b)`, and the real
/// power `x^(p/q)` (written with `^`, any exponent that is not a whole number).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Func2 {
    Atan2,
    Min,
    Max,
    /// `x^y` for x > 0 (and x = 0 with y > 0).
    Pow,
}

impl Func2 {
    pub fn from_name(name: &str) -> Option<Func2> {
        Some(match name {
            "atan2" => Func2::Atan2,
            "min" => Func2::Min,
            "max" => Func2::Max,
            _ => return None,
        })
    }

    pub fn name(self) -> &'static str {
        match self {
            Func2::Atan2 => "atan2",
            Func2::Min => "min",
            Func2::Max => "max",
            Func2::Pow => "^",
        }
    }
}

/// The functions of the matrix language (see [`super::check`] for their types).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MatFunc {
    Det,
    Trace,
    Inv,
    /// The adjugate (transposed cofactor matrix).
    Adj,
    Transpose,
    /// `solve(A, b)`: x with A x = b.
    Solve,
    /// `identity(n)`: the n×n identity.
    Identity,
    /// `matrix(T_ijkl, o_ij, o_kl)`: the matrix view of a tensor in declared orders.
    Matrix,
    /// `vector(t_ij, o_ij)`: the column-vector view of a tensor.
    Vector,
    /// `tensor(M, o_ij, o_kl)` or `tensor(v, o_ij)`: the index view of a matrix.
    Tensor,
}

impl MatFunc {
    pub fn from_name(name: &str) -> Option<MatFunc> {
        Some(match name {
            "det" => MatFunc::Det,
            "trace" => MatFunc::Trace,
            "inv" => MatFunc::Inv,
            "adj" => MatFunc::Adj,
            "transpose" => MatFunc::Transpose,
            "solve" => MatFunc::Solve,
            "identity" => MatFunc::Identity,
            "matrix" => MatFunc::Matrix,
            "vector" => MatFunc::Vector,
            "tensor" => MatFunc::Tensor,
            _ => return None,
        })
    }

    pub fn name(self) -> &'static str {
        match self {
            MatFunc::Det => "det",
            MatFunc::Trace => "trace",
            MatFunc::Inv => "inv",
            MatFunc::Adj => "adj",
            MatFunc::Transpose => "transpose",
            MatFunc::Solve => "solve",
            MatFunc::Identity => "identity",
            MatFunc::Matrix => "matrix",
            MatFunc::Vector => "vector",
            MatFunc::Tensor => "tensor",
        }
    }

    /// The numbers of arguments accepted.
    pub fn arity(self) -> std::ops::RangeInclusive<usize> {
        match self {
            MatFunc::Solve | MatFunc::Vector => 2..=2,
            MatFunc::Matrix => 3..=3,
            MatFunc::Tensor => 2..=3,
            _ => 1..=1,
        }
    }

    /// How the call is written, for messages.
    pub fn usage(self) -> &'static str {
        match self {
            MatFunc::Solve => "solve(A, b)",
            MatFunc::Identity => "identity(4)",
            MatFunc::Matrix => "matrix(D_ijkl, voigt_ij, voigt_kl)",
            MatFunc::Vector => "vector(sigma_ij, voigt_ij)",
            MatFunc::Tensor => "tensor(M, voigt_ij, voigt_kl) or tensor(v, voigt_ij)",
            MatFunc::Det => "det(A)",
            MatFunc::Trace => "trace(A)",
            MatFunc::Inv => "inv(A)",
            MatFunc::Adj => "adj(A)",
            MatFunc::Transpose => "transpose(A) or A^T",
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub enum ExprKind {
    Number(Rational),
    /// `full` is the whole token (`R_g`, `sigma_el_ij`), `base` the part before the
    /// last `_` (`R`, `sigma_el`), and `indices` the characters after it.
    Name {
        full: String,
        base: String,
        indices: Vec<IndexTok>,
    },
    Neg(Box<Expr>),
    Add(Box<Expr>, Box<Expr>),
    Sub(Box<Expr>, Box<Expr>),
    Mul(Box<Expr>, Box<Expr>),
    Div(Box<Expr>, Box<Expr>),
    Pow(Box<Expr>, u32),
    Call(Func, Box<Expr>),
    Call2(Func2, Box<Expr>, Box<Expr>),
    /// Derivatives with respect to the position, one per index, in order: `u_j,i`
    /// (`wrt` is `None`) or `d(expr)/dx_i` (`wrt` is the position's name as written,
    /// checked against the declared one).
    Deriv {
        inner: Box<Expr>,
        indices: Vec<IndexTok>,
        wrt: Option<(String, Span)>,
    },
    /// `variation(P, v_j)` or `grad(F, sigma_ij)`: a derivative with respect to a
    /// declared symbol named with its own index letters (see [`Wrt`]).
    Wrt {
        op: Wrt,
        body: Box<Expr>,
        symbol: Box<Expr>,
    },
    /// A matrix literal, row by row; `[a, b, c]` is a column (three rows of one).
    Matrix(Vec<Vec<Expr>>),
    /// `A[i,j]` or `v[i]`: one entry, 1-based as written.
    Entry(Box<Expr>, Vec<(usize, Span)>),
    MatCall(MatFunc, Vec<Expr>),
}

/// The derivatives taken with respect to a declared symbol rather than a coordinate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Wrt {
    /// `variation(P, v_j)`: the variational (Euler–Lagrange) derivative of a density
    /// with respect to a field.
    Variation,
    /// `grad(F, sigma_ij)`: the partial derivatives of an expression with respect to
    /// the components of a symbol that is not a field, at the state the assumptions
    /// give.
    Grad,
}

impl Wrt {
    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "variation" => Some(Wrt::Variation),
            "grad" => Some(Wrt::Grad),
            _ => None,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Wrt::Variation => "variation",
            Wrt::Grad => "grad",
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct Expr {
    pub kind: ExprKind,
    pub span: Span,
}

impl Expr {
    /// Whether two expressions are the same tree, wherever each was written (spans
    /// aside). Brackets the parser drops (`(1 / 3) x` and `1/3 x`) leave no trace;
    /// nothing is reordered or regrouped, so equal trees evaluate alike in any context:
    /// the same expression, by reflexivity.
    pub fn same_tree(&self, other: &Expr) -> bool {
        use ExprKind as K;
        fn letters(a: &[IndexTok], b: &[IndexTok]) -> bool {
            a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.ch == y.ch)
        }
        fn all(a: &[Expr], b: &[Expr]) -> bool {
            a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.same_tree(y))
        }
        match (&self.kind, &other.kind) {
            (K::Number(a), K::Number(b)) => a == b,
            // `base` and `indices` are read off `full`.
            (K::Name { full: a, .. }, K::Name { full: b, .. }) => a == b,
            (K::Neg(a), K::Neg(b)) => a.same_tree(b),
            (K::Add(a, b), K::Add(c, d))
            | (K::Sub(a, b), K::Sub(c, d))
            | (K::Mul(a, b), K::Mul(c, d))
            | (K::Div(a, b), K::Div(c, d)) => a.same_tree(c) && b.same_tree(d),
            (K::Pow(a, n), K::Pow(b, m)) => n == m && a.same_tree(b),
            (K::Call(f, a), K::Call(g, b)) => f == g && a.same_tree(b),
            (K::Call2(f, a, b), K::Call2(g, c, d)) => f == g && a.same_tree(c) && b.same_tree(d),
            (
                K::Deriv {
                    inner: a,
                    indices: i,
                    wrt: v,
                },
                K::Deriv {
                    inner: b,
                    indices: j,
                    wrt: w,
                },
            ) => {
                letters(i, j)
                    && v.as_ref().map(|v| &v.0) == w.as_ref().map(|w| &w.0)
                    && a.same_tree(b)
            }
            (
                K::Wrt {
                    op: p,
                    body: a,
                    symbol: s,
                },
                K::Wrt {
                    op: q,
                    body: b,
                    symbol: t,
                },
            ) => p == q && a.same_tree(b) && s.same_tree(t),
            (K::Matrix(r), K::Matrix(s)) => {
                r.len() == s.len() && r.iter().zip(s).all(|(x, y)| all(x, y))
            }
            (K::Entry(a, i), K::Entry(b, j)) => {
                i.len() == j.len() && i.iter().zip(j).all(|(x, y)| x.0 == y.0) && a.same_tree(b)
            }
            (K::MatCall(f, a), K::MatCall(g, b)) => f == g && all(a, b),
            _ => false,
        }
    }
}

/// What kind of mistake a language error is: a printed statement transcribed verbatim
/// may be ill-formed in its indices (that is a finding about the paper), but never in
/// its syntax or names (that is a mistake in the derivation file).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ErrorKind {
    Syntax,
    Name,
    Index,
    Dimension,
}

/// An error inside one expression's text.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{message}")]
pub struct LangError {
    pub kind: ErrorKind,
    pub span: Span,
    pub message: String,
    pub help: Option<String>,
    /// The name that was not found, for a caller that knows more about it (a
    /// definition further down the file).
    pub unknown: Option<String>,
}

impl LangError {
    pub fn new(kind: ErrorKind, span: Span, message: impl Into<String>) -> Self {
        LangError {
            kind,
            span,
            message: message.into(),
            help: None,
            unknown: None,
        }
    }

    pub fn help(mut self, help: impl Into<String>) -> Self {
        self.help = Some(help.into());
        self
    }
}

#[derive(Clone, Debug, PartialEq)]
enum Tok {
    Num(Rational),
    Name {
        full: String,
        base: String,
        indices: Vec<IndexTok>,
        /// The indices after a comma: `u_j,i` has derivative index `i`.
        derivs: Vec<IndexTok>,
        /// Where the name itself ends (before the comma).
        name_end: usize,
    },
    Op(char),
    End,
}

/// Longest exponent accepted by `^`; larger powers are almost certainly a typo and
/// would only make the expansion explode.
const MAX_POWER: u32 = 64;

fn lex(src: &str) -> Result<Vec<(Tok, Span)>, LangError> {
    let bytes = src.as_bytes();
    let mut out = Vec::new();
    let mut k = 0;
    while k < src.len() {
        let c = src[k..].chars().next().expect("k is a char boundary");
        let start = k;
        if c.is_whitespace() {
            k += c.len_utf8();
        } else if c.is_ascii_digit() || c == '.' {
            while k < src.len() && (bytes[k].is_ascii_digit() || bytes[k] == b'.') {
                k += 1;
            }
            // Scientific notation: `e` or `E`, an optional sign, and digits (`1e-3`).
            if k < src.len() && matches!(bytes[k], b'e' | b'E') {
                let sign = usize::from(matches!(bytes.get(k + 1), Some(b'+' | b'-')));
                if bytes.get(k + 1 + sign).is_some_and(u8::is_ascii_digit) {
                    k += 1 + sign;
                    while k < src.len() && bytes[k].is_ascii_digit() {
                        k += 1;
                    }
                }
            }
            let text = &src[start..k];
            let value = parse_decimal(text).ok_or_else(|| {
                LangError::new(
                    ErrorKind::Syntax,
                    Span::new(start, k),
                    format!("`{text}` is not a number"),
                )
                .help("write integers or decimals such as 3, 0.25 or 2.5e-3 (exponents up to ±300); fractions as 1/3")
            })?;
            out.push((Tok::Num(value), Span::new(start, k)));
        } else if c.is_ascii_alphabetic() {
            while k < src.len() && bytes[k].is_ascii_alphanumeric() {
                k += 1;
            }
            // Segments `_alnum+`: the last is the index list, the ones before it belong
            // to the name (`sigma_el_ij` is `sigma_el` with indices i, j).
            let mut base_end = k;
            let mut indices = Vec::new();
            while k + 1 < src.len() && bytes[k] == b'_' && bytes[k + 1].is_ascii_alphanumeric() {
                // The previous segment, if any, ends here and joins the name.
                base_end = if indices.is_empty() { base_end } else { k };
                indices.clear();
                k += 1;
                while k < src.len() && bytes[k].is_ascii_alphanumeric() {
                    indices.push(IndexTok {
                        ch: bytes[k] as char,
                        span: Span::new(k, k + 1),
                    });
                    k += 1;
                }
            }
            // `theta_,i`, `phi_el_,i`: a scalar's derivative has an empty index list;
            // every segment then belongs to the name.
            let bare_comma = bytes.get(k) == Some(&b'_') && bytes.get(k + 1) == Some(&b',');
            if bare_comma {
                base_end = k;
                indices.clear();
            }
            let base = src[start..base_end].to_owned();
            if bare_comma {
                k += 1;
            } else if k < src.len() && bytes[k] == b'_' {
                return Err(LangError::new(
                    ErrorKind::Syntax,
                    Span::new(k, k + 1),
                    "`_` must be followed by indices",
                )
                .help("write indices right after the underscore, as in sigma_ki"));
            }
            let name_end = k;
            let full = src[start..k].trim_end_matches('_').to_owned();
            let mut derivs = Vec::new();
            if bare_comma || !indices.is_empty() {
                // A comma right after an indexed name, followed by index characters
                // and no further `_` or `(`, starts derivative indices (`u_j,i`);
                // otherwise it separates arguments (`min(u_1,v_2)`).
                let mut end = k + 1;
                while end < src.len() && bytes[end].is_ascii_alphanumeric() {
                    end += 1;
                }
                let is_derivative = bytes.get(k) == Some(&b',')
                    && end > k + 1
                    && !matches!(bytes.get(end), Some(b'_' | b'('));
                if is_derivative {
                    derivs = (k + 1..end)
                        .map(|j| IndexTok {
                            ch: bytes[j] as char,
                            span: Span::new(j, j + 1),
                        })
                        .collect();
                    k = end;
                } else if bare_comma {
                    return Err(LangError::new(
                        ErrorKind::Syntax,
                        Span::new(start, k + 1),
                        "`_,` must be followed by derivative indices",
                    )
                    .help("write a scalar field's derivative as theta_,i"));
                }
            }
            out.push((
                Tok::Name {
                    full,
                    base,
                    indices,
                    derivs,
                    name_end,
                },
                Span::new(start, k),
            ));
        } else if "+-*/^(),[]".contains(c) {
            k += 1;
            out.push((Tok::Op(c), Span::new(start, k)));
        } else {
            let end = k + c.len_utf8();
            return Err(LangError::new(
                ErrorKind::Syntax,
                Span::new(start, end),
                format!("unexpected character `{c}`"),
            )
            .help("expressions use names with index suffixes, numbers, + - * / ^, parentheses, sqrt(…) and avg(…)"));
        }
    }
    out.push((Tok::End, Span::new(src.len(), src.len())));
    Ok(out)
}

/// Longest expression accepted, in tokens. Trees are recursive, so an unbounded
/// operand chain could exhaust the stack; paper expressions have a few dozen tokens.
pub const MAX_TOKENS: usize = 1000;

/// Parses one expression; the whole text must be consumed.
pub fn parse_expr(src: &str) -> Result<Expr, LangError> {
    let toks = lex(src)?;
    if toks.len() > MAX_TOKENS {
        return Err(LangError::new(
            ErrorKind::Syntax,
            toks[MAX_TOKENS].1,
            format!("expression longer than {MAX_TOKENS} tokens"),
        )
        .help("split it into named definitions"));
    }
    let mut p = Parser {
        toks,
        pos: 0,
        depth: 0,
    };
    let e = p.expr()?;
    match p.peek() {
        Tok::End => Ok(e),
        Tok::Op(')') => Err(LangError::new(ErrorKind::Syntax, p.span(), "unmatched `)`")),
        _ => Err(
            LangError::new(ErrorKind::Syntax, p.span(), "unexpected token")
                .help("an operator may be missing here"),
        ),
    }
}

/// The value of an expression made of numbers only (`1/3`, `-2`), if it is one.
fn constant(e: &Expr) -> Option<Rational> {
    Some(match &e.kind {
        ExprKind::Number(q) => q.clone(),
        ExprKind::Neg(a) => -constant(a)?,
        ExprKind::Add(a, b) => &constant(a)? + &constant(b)?,
        ExprKind::Sub(a, b) => &constant(a)? - &constant(b)?,
        ExprKind::Mul(a, b) => &constant(a)? * &constant(b)?,
        ExprKind::Div(a, b) => constant(a)?.checked_div(&constant(b)?)?,
        _ => return None,
    })
}

/// Nesting deeper than this is refused rather than risking the stack.
const MAX_DEPTH: usize = 200;

struct Parser {
    toks: Vec<(Tok, Span)>,
    pos: usize,
    depth: usize,
}

impl Parser {
    fn peek(&self) -> &Tok {
        &self.toks[self.pos].0
    }

    fn span(&self) -> Span {
        self.toks[self.pos].1
    }

    fn bump(&mut self) -> (Tok, Span) {
        let t = self.toks[self.pos].clone();
        if self.pos + 1 < self.toks.len() {
            self.pos += 1;
        }
        t
    }

    fn enter(&mut self) -> Result<(), LangError> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err(LangError::new(
                ErrorKind::Syntax,
                self.span(),
                format!("expression nested more than {MAX_DEPTH} levels deep"),
            ));
        }
        Ok(())
    }

    fn expr(&mut self) -> Result<Expr, LangError> {
        self.enter()?;
        let mut lhs = self.term()?;
        while let Tok::Op(c @ ('+' | '-')) = *self.peek() {
            self.bump();
            let rhs = self.term()?;
            let span = lhs.span.to(rhs.span);
            let (l, r) = (Box::new(lhs), Box::new(rhs));
            let kind = if c == '+' {
                ExprKind::Add(l, r)
            } else {
                ExprKind::Sub(l, r)
            };
            lhs = Expr { kind, span };
        }
        self.depth -= 1;
        Ok(lhs)
    }

    fn starts_atom(&self) -> bool {
        matches!(
            self.peek(),
            Tok::Num(_) | Tok::Name { .. } | Tok::Op('(') | Tok::Op('[')
        )
    }

    fn term(&mut self) -> Result<Expr, LangError> {
        let mut lhs = self.unary()?;
        loop {
            let div = match self.peek() {
                Tok::Op('*') => false,
                Tok::Op('/') => true,
                _ if self.starts_atom() => {
                    let rhs = self.unary()?;
                    lhs = binary(lhs, rhs, ExprKind::Mul);
                    continue;
                }
                _ => break,
            };
            self.bump();
            let rhs = self.unary()?;
            lhs = binary(lhs, rhs, if div { ExprKind::Div } else { ExprKind::Mul });
        }
        Ok(lhs)
    }

    fn unary(&mut self) -> Result<Expr, LangError> {
        if let Tok::Op('-') = self.peek() {
            let (_, span) = self.bump();
            self.enter()?;
            let inner = self.unary()?;
            self.depth -= 1;
            let span = span.to(inner.span);
            return Ok(Expr {
                kind: ExprKind::Neg(Box::new(inner)),
                span,
            });
        }
        self.power()
    }

    fn power(&mut self) -> Result<Expr, LangError> {
        let base = self.postfix()?;
        if let Tok::Op('^') = self.peek() {
            let (_, caret) = self.bump();
            // `A^T`: the transpose.
            if matches!(self.peek(), Tok::Name { full, derivs, .. } if full == "T" && derivs.is_empty())
            {
                let (_, t) = self.bump();
                let span = base.span.to(t);
                return Ok(Expr {
                    kind: ExprKind::MatCall(MatFunc::Transpose, vec![base]),
                    span,
                });
            }
            // `x^(e)`: a parenthesised exponent; a whole number is an ordinary power,
            // a negative whole number a division, anything else a real power.
            if let Tok::Op('(') = self.peek() {
                let exponent = self.parenthesised()?;
                let span = base.span.to(exponent.span);
                let whole = constant(&exponent).and_then(|q| {
                    q.is_integer()
                        .then(|| q.to_string().parse::<i64>().ok())
                        .flatten()
                });
                let kind = match whole {
                    Some(k) if (0..=i64::from(MAX_POWER)).contains(&k) => {
                        ExprKind::Pow(Box::new(base), k as u32)
                    }
                    Some(k) if (-i64::from(MAX_POWER)..0).contains(&k) => {
                        let one = Expr {
                            kind: ExprKind::Number(Rational::int(1)),
                            span,
                        };
                        let pow = Expr {
                            kind: ExprKind::Pow(Box::new(base), k.unsigned_abs() as u32),
                            span,
                        };
                        ExprKind::Div(Box::new(one), Box::new(pow))
                    }
                    Some(_) => {
                        return Err(LangError::new(
                            ErrorKind::Syntax,
                            exponent.span,
                            "this whole exponent is too large",
                        )
                        .help(format!(
                            "whole exponents run from -{MAX_POWER} to {MAX_POWER}"
                        )))
                    }
                    None => ExprKind::Call2(Func2::Pow, Box::new(base), Box::new(exponent)),
                };
                return Ok(Expr { kind, span });
            }
            let (tok, span) = self.bump();
            let exp = match tok {
                Tok::Num(q) if q.is_integer() && !q.is_negative() => q
                    .to_string()
                    .parse::<u32>()
                    .ok()
                    .filter(|&e| e <= MAX_POWER),
                Tok::Num(q) if !q.is_integer() => {
                    // `x^0.5`: a real power.
                    let span = base.span.to(span);
                    let exponent = Expr {
                        kind: ExprKind::Number(q),
                        span,
                    };
                    return Ok(Expr {
                        kind: ExprKind::Call2(Func2::Pow, Box::new(base), Box::new(exponent)),
                        span,
                    });
                }
                _ => None,
            };
            let Some(exp) = exp else {
                return Err(LangError::new(
                    ErrorKind::Syntax,
                    if span.end > span.start { span } else { caret },
                    "`^` must be followed by a number or a parenthesised exponent",
                )
                .help(format!(
                    "write x^2 (whole exponents from 0 to {MAX_POWER}), x^(-1), x^(1/3), x^0.5, or A^T for a transpose"
                )));
            };
            let span = base.span.to(span);
            return Ok(Expr {
                kind: ExprKind::Pow(Box::new(base), exp),
                span,
            });
        }
        Ok(base)
    }

    fn atom(&mut self) -> Result<Expr, LangError> {
        let (tok, span) = self.bump();
        match tok {
            Tok::Num(q) => Ok(Expr {
                kind: ExprKind::Number(q),
                span,
            }),
            Tok::Name {
                full,
                base,
                indices,
                derivs,
                name_end,
            } => {
                if !derivs.is_empty() {
                    let inner = Expr {
                        kind: ExprKind::Name {
                            full,
                            base,
                            indices,
                        },
                        span: Span::new(span.start, name_end),
                    };
                    return Ok(Expr {
                        kind: ExprKind::Deriv {
                            inner: Box::new(inner),
                            indices: derivs,
                            wrt: None,
                        },
                        span,
                    });
                }
                if full == "d" && indices.is_empty() {
                    if let Some(e) = self.derivative_quotient(span)? {
                        return Ok(e);
                    }
                }
                if let Some(func) = Func2::from_name(&full) {
                    let (a, b, span) = self.two_arguments(&full, span)?;
                    return Ok(Expr {
                        kind: ExprKind::Call2(func, Box::new(a), Box::new(b)),
                        span,
                    });
                }
                if let Some(func) = MatFunc::from_name(&full) {
                    let usage = format!("write {}", func.usage());
                    let (args, span) = self.arguments(&full, span, &usage)?;
                    if !func.arity().contains(&args.len()) {
                        return Err(LangError::new(
                            ErrorKind::Syntax,
                            span,
                            format!(
                                "{full}(…) takes {} argument{}, not {}",
                                arity_words(func),
                                if *func.arity().end() == 1 { "" } else { "s" },
                                args.len()
                            ),
                        )
                        .help(format!("write {}", func.usage())));
                    }
                    return Ok(Expr {
                        kind: ExprKind::MatCall(func, args),
                        span,
                    });
                }
                if let Some(op) = Wrt::from_name(&full) {
                    let (body, symbol, span) = self.two_arguments(&full, span)?;
                    return Ok(Expr {
                        kind: ExprKind::Wrt {
                            op,
                            body: Box::new(body),
                            symbol: Box::new(symbol),
                        },
                        span,
                    });
                }
                let func = Func::from_name(&full);
                if let Some(func) = func {
                    if *self.peek() != Tok::Op('(') {
                        return Err(LangError::new(
                            ErrorKind::Syntax,
                            span,
                            format!("`{full}` must be followed by `(`"),
                        )
                        .help(format!("write {full}(…)")));
                    }
                    let arg = self.parenthesised()?;
                    let span = span.to(arg.span);
                    return Ok(Expr {
                        kind: ExprKind::Call(func, Box::new(arg)),
                        span,
                    });
                }
                Ok(Expr {
                    kind: ExprKind::Name {
                        full,
                        base,
                        indices,
                    },
                    span,
                })
            }
            Tok::Op('(') => {
                self.pos -= 1;
                self.parenthesised()
            }
            Tok::Op('[') => self.literal(span),
            Tok::End => Err(
                LangError::new(ErrorKind::Syntax, span, "expression ends too early")
                    .help("an operand is missing at the end"),
            ),
            Tok::Op(c) => Err(LangError::new(
                ErrorKind::Syntax,
                span,
                format!("expected an operand, found `{c}`"),
            )),
        }
    }

    /// After a name `d`: `d(expr)/dx_i…` as a derivative, when the tokens have that
    /// shape (`None` leaves them alone: `d (a + b)` is a product).
    fn derivative_quotient(&mut self, d: Span) -> Result<Option<Expr>, LangError> {
        if *self.peek() != Tok::Op('(') {
            return Ok(None);
        }
        let mut depth = 0usize;
        let mut close = None;
        for (j, (t, _)) in self.toks.iter().enumerate().skip(self.pos) {
            match t {
                Tok::Op('(') => depth += 1,
                Tok::Op(')') => {
                    depth -= 1;
                    if depth == 0 {
                        close = Some(j);
                        break;
                    }
                }
                Tok::End => break,
                _ => {}
            }
        }
        let Some(close) = close else {
            return Ok(None);
        };
        let wrt = match (self.toks.get(close + 1), self.toks.get(close + 2)) {
            (
                Some((Tok::Op('/'), _)),
                Some((
                    Tok::Name {
                        base,
                        indices,
                        derivs,
                        ..
                    },
                    span,
                )),
            ) if base.len() > 1
                && base.starts_with('d')
                && !indices.is_empty()
                && derivs.is_empty() =>
            {
                (base[1..].to_owned(), *span, indices.clone())
            }
            _ => return Ok(None),
        };
        self.enter()?;
        let inner = self.parenthesised()?;
        self.depth -= 1;
        self.bump(); // `/`
        self.bump(); // `dx_i`
        let (name, wrt_span, indices) = wrt;
        Ok(Some(Expr {
            kind: ExprKind::Deriv {
                inner: Box::new(inner),
                indices,
                wrt: Some((name, Span::new(wrt_span.start + 1, wrt_span.end))),
            },
            span: d.to(wrt_span),
        }))
    }

    /// `name(a, b)` after the name: both arguments and the span up to `)`.
    fn two_arguments(&mut self, full: &str, span: Span) -> Result<(Expr, Expr, Span), LangError> {
        let usage = format!("write {full}(a, b)");
        let (mut args, span) = self.arguments(full, span, &usage)?;
        if args.len() != 2 {
            return Err(LangError::new(
                ErrorKind::Syntax,
                span,
                format!("{full}(…) takes two arguments separated by `,`"),
            )
            .help(usage));
        }
        let b = args.pop().expect("two arguments");
        let a = args.pop().expect("two arguments");
        Ok((a, b, span))
    }
    /// An atom and the entry picked from it, `A[2,3]` or `v[2]`: the `[` must touch
    /// what precedes it (`A [1, 2]` is A times a column vector).
    fn postfix(&mut self) -> Result<Expr, LangError> {
        let atom = self.atom()?;
        if !(*self.peek() == Tok::Op('[') && self.span().start == atom.span.end) {
            return Ok(atom);
        }
        let (_, open) = self.bump();
        let mut at = Vec::new();
        loop {
            match self.bump() {
                (Tok::Num(q), span) if q.is_integer() && !q.is_negative() && !q.is_zero() => {
                    let k = q.to_string().parse::<usize>().unwrap_or(usize::MAX);
                    at.push((k, span));
                }
                (_, span) => {
                    return Err(LangError::new(
                        ErrorKind::Syntax,
                        span,
                        "an entry is picked with whole numbers from 1, as in A[2,3] or v[2]",
                    ))
                }
            }
            match self.bump() {
                (Tok::Op(','), _) if at.len() < 2 => {}
                (Tok::Op(']'), close) => {
                    let span = atom.span.to(close);
                    return Ok(Expr {
                        kind: ExprKind::Entry(Box::new(atom), at),
                        span,
                    });
                }
                _ => {
                    return Err(LangError::new(
                        ErrorKind::Syntax,
                        open,
                        "this `[` is not closed after one or two entry numbers",
                    )
                    .help("write A[2,3] for a matrix entry or v[2] for a vector's"))
                }
            }
        }
    }

    /// After `[`: a column vector `[a, b]`, or a matrix `[[a, b], [c, d]]` whose rows
    /// are all bracketed and of one length.
    fn literal(&mut self, open: Span) -> Result<Expr, LangError> {
        self.enter()?;
        let nested = *self.peek() == Tok::Op('[');
        let mut rows: Vec<Vec<Expr>> = Vec::new();
        let close = loop {
            if nested {
                let (t, row_open) = self.bump();
                if t != Tok::Op('[') {
                    return Err(LangError::new(
                        ErrorKind::Syntax,
                        row_open,
                        "every row of a matrix is written in brackets",
                    )
                    .help("write [[a, b], [c, d]]"));
                }
                let (row, _) = self.elements(row_open)?;
                if let Some(first) = rows.first() {
                    if first.len() != row.len() {
                        return Err(LangError::new(
                            ErrorKind::Syntax,
                            row_open,
                            format!(
                                "this row has {} entries, the first row {}",
                                row.len(),
                                first.len()
                            ),
                        )
                        .help("every row of a matrix has the same number of entries"));
                    }
                }
                rows.push(row);
                match self.bump() {
                    (Tok::Op(','), _) => {}
                    (Tok::Op(']'), close) => break close,
                    (_, span) => {
                        return Err(LangError::new(
                            ErrorKind::Syntax,
                            span,
                            "expected `,` or `]` after a row of a matrix",
                        ))
                    }
                }
            } else {
                let (column, close) = self.elements(open)?;
                rows = column.into_iter().map(|e| vec![e]).collect();
                break close;
            }
        };
        self.depth -= 1;
        Ok(Expr {
            kind: ExprKind::Matrix(rows),
            span: open.to(close),
        })
    }

    /// `a, b, …]` after a `[`: the expressions and the span of `]`.
    fn elements(&mut self, open: Span) -> Result<(Vec<Expr>, Span), LangError> {
        let mut out = Vec::new();
        loop {
            if *self.peek() == Tok::Op('[') {
                return Err(LangError::new(
                    ErrorKind::Syntax,
                    self.span(),
                    "brackets nest two deep at most: a matrix's rows hold expressions",
                ));
            }
            out.push(self.expr()?);
            match self.bump() {
                (Tok::Op(','), _) => {}
                (Tok::Op(']'), close) => return Ok((out, close)),
                (_, span) => {
                    return Err(
                        LangError::new(ErrorKind::Syntax, open, "this `[` is never closed")
                            .help(format!("add `]` (at column {} or earlier)", span.start + 1)),
                    )
                }
            }
        }
    }

    /// `name(a, b, …)` after the name: the arguments and the span up to `)`.
    fn arguments(
        &mut self,
        full: &str,
        span: Span,
        usage: &str,
    ) -> Result<(Vec<Expr>, Span), LangError> {
        if *self.peek() != Tok::Op('(') {
            return Err(LangError::new(
                ErrorKind::Syntax,
                span,
                format!("`{full}` must be followed by `(`"),
            )
            .help(usage.to_owned()));
        }
        let (_, open) = self.bump();
        self.enter()?;
        let mut args = Vec::new();
        loop {
            args.push(self.expr()?);
            match self.bump() {
                (Tok::Op(','), _) => {}
                (Tok::Op(')'), close) => {
                    self.depth -= 1;
                    return Ok((args, span.to(close)));
                }
                _ => {
                    return Err(LangError::new(
                        ErrorKind::Syntax,
                        open,
                        format!("`(` of {full}(…) is never closed"),
                    )
                    .help(format!(
                        "separate the arguments with `,` and close with `)`: {usage}"
                    )))
                }
            }
        }
    }

    /// `( expr )`, returning the inner expression with the parentheses' span.
    fn parenthesised(&mut self) -> Result<Expr, LangError> {
        let (_, open) = self.bump();
        let mut inner = self.expr()?;
        match self.bump() {
            (Tok::Op(')'), close) => {
                inner.span = open.to(close);
                Ok(inner)
            }
            (_, span) => Err(
                LangError::new(ErrorKind::Syntax, open, "this `(` is never closed")
                    .help(format!("add `)` (at column {} or earlier)", span.start + 1)),
            ),
        }
    }
}

fn arity_words(f: MatFunc) -> String {
    let r = f.arity();
    if r.start() == r.end() {
        r.start().to_string()
    } else {
        format!("{} or {}", r.start(), r.end())
    }
}

fn binary(l: Expr, r: Expr, f: fn(Box<Expr>, Box<Expr>) -> ExprKind) -> Expr {
    let span = l.span.to(r.span);
    Expr {
        kind: f(Box::new(l), Box::new(r)),
        span,
    }
}

/// The largest power of ten a decimal literal may carry (`1e300`): enough for any
/// physical constant, small enough that no literal makes a huge integer.
pub const MAX_DECIMAL_EXPONENT: i64 = 300;

/// A decimal literal such as `12`, `0.25`, `3.` or `2.5e-3`, exactly; `None` for
/// anything else and for exponents beyond ±[`MAX_DECIMAL_EXPONENT`].
pub fn parse_decimal(text: &str) -> Option<Rational> {
    use num_bigint::BigInt;
    // Scientific notation: a mantissa times an exact power of ten (`1e-3` is 1/1000).
    if let Some((mantissa, exponent)) = text.split_once(['e', 'E']) {
        let m = parse_decimal(mantissa)?;
        let digits = exponent.strip_prefix(['+', '-']).unwrap_or(exponent);
        if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
            return None;
        }
        let e: i64 = exponent.parse().ok()?;
        if e.abs() > MAX_DECIMAL_EXPONENT {
            return None;
        }
        let power = num_traits::pow(BigInt::from(10), e.unsigned_abs() as usize);
        let power = Rational::from_big(power, BigInt::from(1))?;
        return if e < 0 {
            m.checked_div(&power)
        } else {
            Some(&m * &power)
        };
    }
    let (int_part, frac_part) = text.split_once('.').unwrap_or((text, ""));
    let all_digits = |s: &str| s.bytes().all(|b| b.is_ascii_digit());
    if int_part.is_empty() && frac_part.is_empty()
        || !all_digits(int_part)
        || !all_digits(frac_part)
    {
        return None;
    }
    let numer: BigInt = format!("{int_part}{frac_part}").parse().ok()?;
    Rational::from_big(numer, num_traits::pow(BigInt::from(10), frac_part.len()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shape(e: &Expr) -> String {
        match &e.kind {
            ExprKind::Number(q) => q.to_string(),
            ExprKind::Name { full, .. } => full.clone(),
            ExprKind::Neg(a) => format!("(-{})", shape(a)),
            ExprKind::Add(a, b) => format!("({} + {})", shape(a), shape(b)),
            ExprKind::Sub(a, b) => format!("({} - {})", shape(a), shape(b)),
            ExprKind::Mul(a, b) => format!("({} {})", shape(a), shape(b)),
            ExprKind::Div(a, b) => format!("({} / {})", shape(a), shape(b)),
            ExprKind::Pow(a, k) => format!("{}^{k}", shape(a)),
            ExprKind::Call(f, a) => format!("{f:?}{}", shape(a)),
            ExprKind::Call2(f, a, b) => format!("{f:?}({}, {})", shape(a), shape(b)),
            ExprKind::Deriv {
                inner,
                indices,
                wrt,
            } => format!(
                "D[{}{}]({})",
                wrt.as_ref().map_or(String::new(), |w| format!("{}:", w.0)),
                indices.iter().map(|t| t.ch).collect::<String>(),
                shape(inner)
            ),
            ExprKind::Wrt { op, body, symbol } => {
                format!("{op:?}({}, {})", shape(body), shape(symbol))
            }
            ExprKind::Matrix(rows) => format!(
                "[{}]",
                rows.iter()
                    .map(|r| r.iter().map(shape).collect::<Vec<_>>().join(", "))
                    .collect::<Vec<_>>()
                    .join("; ")
            ),
            ExprKind::Entry(a, at) => format!(
                "{}[{}]",
                shape(a),
                at.iter()
                    .map(|(k, _)| k.to_string())
                    .collect::<Vec<_>>()
                    .join(",")
            ),
            ExprKind::MatCall(f, args) => format!(
                "{}({})",
                f.name(),
                args.iter().map(shape).collect::<Vec<_>>().join(", ")
            ),
        }
    }

    #[test]
    fn decimal_literals_parse_exactly() {
        let q = |n, d| Rational::ratio(n, d);
        assert_eq!(parse_decimal("0.25"), q(1, 4));
        assert_eq!(parse_decimal("12"), q(12, 1));
        assert_eq!(parse_decimal("3."), q(3, 1));
        assert_eq!(parse_decimal("."), None);
        assert_eq!(parse_decimal("1.2.3"), None);
        assert_eq!(parse_decimal("1e-3"), q(1, 1000));
        assert_eq!(parse_decimal("2.5E+2"), q(250, 1));
        assert_eq!(parse_decimal("25e-1"), q(5, 2));
        assert_eq!(parse_decimal("1e"), None);
        assert_eq!(parse_decimal("1e+"), None);
        assert_eq!(parse_decimal("e3"), None);
        assert_eq!(parse_decimal("1e400"), None);
    }

    #[test]
    fn same_tree_ignores_where_and_dropped_brackets_but_nothing_else() {
        let same = |a: &str, b: &str| parse_expr(a).unwrap().same_tree(&parse_expr(b).unwrap());
        for (a, b) in [
            ("(1 / 3) (delta_ij + n_i n_j)", "1/3 (delta_ij + n_i n_j)"),
            ("((2 R_g S) / V) n_k", "2 R_g S / V n_k"),
            ("(sqrt(2) / R_g) sqrt(M)", "sqrt(2) / R_g sqrt(M)"),
            ("u_j,i + d(mu_23)/dx_2", "u_j,i  +  d(mu_23)/dx_2"),
            (
                "grad(F, sigma_ij) + det([[a, b], [c, d]]) A[1,2]",
                "grad(F,sigma_ij)+det([[a,b],[c,d]]) A[1,2]",
            ),
        ] {
            assert!(same(a, b), "{a} | {b}");
        }
        // Each pair differs in one place: an order, a grouping, a letter, a number, a
        // function, an operation, a derivative's form, a matrix entry.
        for (a, b) in [
            ("a b", "b a"),
            ("a + b", "b + a"),
            ("a (b c)", "(a b) c"),
            ("a - (b - c)", "a - b - c"),
            ("sigma_ij", "sigma_ji"),
            ("u_j,i", "u_j,k"),
            ("d(mu_23)/dx_2", "mu_23,2"),
            ("x^2", "x^3"),
            ("1/3 x", "1/15 x"),
            ("sqrt(a)", "abs(a)"),
            ("max(a, b)", "min(a, b)"),
            ("a / b", "a b"),
            ("-a", "a"),
            ("grad(F, sigma_ij)", "grad(F, mu_ij)"),
            ("grad(F, sigma_ij)", "variation(F, sigma_ij)"),
            ("[[a, b], [c, d]]", "[[a, b], [c, e]]"),
            ("[[a, b], [c, d]]", "[[a, b, c, d]]"),
            ("A[1,2]", "A[2,1]"),
            ("det(A)", "trace(A)"),
            ("solve(A, b)", "solve(A, c)"),
        ] {
            assert!(!same(a, b), "{a} | {b}");
            assert!(!same(b, a), "{b} | {a}");
        }
    }

    #[test]
    fn matrices_vectors_entries_and_transposes() {
        let e = parse_expr("[[a, b], [c, d]] [x, y]").unwrap();
        assert_eq!(shape(&e), "([a, b; c, d] [x; y])");
        let e = parse_expr("A[1,2] + v[3] - q^T D q").unwrap();
        assert_eq!(shape(&e), "((A[1,2] + v[3]) - ((transpose(q) D) q))");
        let e = parse_expr("(A B)[2,1]").unwrap();
        assert_eq!(shape(&e), "(A B)[2,1]");
        let e = parse_expr("solve(A, b) + matrix(D_ijkl, v_ij, v_kl)").unwrap();
        assert_eq!(shape(&e), "(solve(A, b) + matrix(D_ijkl, v_ij, v_kl))");
        for (bad, want) in [
            ("[[a, b], [c]]", "this row has 1 entries, the first row 2"),
            (
                "[[a, b], c]",
                "every row of a matrix is written in brackets",
            ),
            ("[a, b", "this `[` is never closed"),
            ("A[0,1]", "an entry is picked with whole numbers from 1"),
            (
                "A[1,2,3]",
                "this `[` is not closed after one or two entry numbers",
            ),
            ("det(A, B)", "det(…) takes 1 argument, not 2"),
            ("solve(A)", "solve(…) takes 2 arguments, not 1"),
            ("[[[a]]]", "brackets nest two deep at most"),
        ] {
            let e = parse_expr(bad).unwrap_err();
            assert!(e.message.contains(want), "{bad}: {}", e.message);
        }
    }

    #[test]
    fn precedence_and_juxtaposition() {
        let e = parse_expr("sigma_ki n_k (delta_il - n_i n_l)").unwrap();
        assert_eq!(shape(&e), "((sigma_ki n_k) (delta_il - (n_i n_l)))");
        let e = parse_expr("1/3 delta_ij + 2R_g^2 x").unwrap();
        assert_eq!(shape(&e), "(((1 / 3) delta_ij) + ((2 R_g^2) x))");
        let e = parse_expr("3*V/(2*R_g)").unwrap();
        assert_eq!(shape(&e), "((3 V) / (2 R_g))");
        let e = parse_expr("-a - -b").unwrap();
        assert_eq!(shape(&e), "((-a) - (-b))");
        let e = parse_expr("avg(n_i n_j) - sqrt(4)").unwrap();
        assert_eq!(shape(&e), "(Avg(n_i n_j) - Sqrt4)");
    }

    #[test]
    fn scientific_notation_is_one_number() {
        let e = parse_expr("2.5e-3 x + 1E2 - 3e_ijk").unwrap();
        assert_eq!(shape(&e), "(((1/400 x) + 100) - (3 e_ijk))");
        let e = parse_expr("2eps_ijk").unwrap();
        assert_eq!(shape(&e), "(2 eps_ijk)");
        assert!(parse_expr("1e999").is_err());
    }

    #[test]
    fn two_argument_functions_and_real_powers() {
        let e = parse_expr("max(a, b^2) + atan2(y, x) min(1, 2)").unwrap();
        assert_eq!(shape(&e), "(Max(a, b^2) + (Atan2(y, x) Min(1, 2)))");
        let e = parse_expr("x^(1/3) + x^0.5 + x^(-2) + x^(4/2)").unwrap();
        assert_eq!(
            shape(&e),
            "(((Pow(x, (1 / 3)) + Pow(x, 1/2)) + (1 / x^2)) + x^2)"
        );
        assert!(parse_expr("max(a)").is_err());
        assert!(parse_expr("max(a, b, c)").is_err());
        assert!(parse_expr("x^y").is_err());
        assert!(parse_expr("x^(65)").is_err());
        assert!(parse_expr("x^(-130/2)").is_err());
        assert!(parse_expr("x^(64) x^(-64)").is_ok());
    }

    #[test]
    fn derivatives_by_comma_and_by_quotient() {
        let e = parse_expr("sigma_ij,j + u_j,ik - theta_,k n_k").unwrap();
        assert_eq!(
            shape(&e),
            "((D[j](sigma_ij) + D[ik](u_j)) - (D[k](theta) n_k))"
        );
        let e = parse_expr("d(u_i u_i)/dx_j + d (a + b) - d(a)/b").unwrap();
        assert_eq!(
            shape(&e),
            "((D[x:j]((u_i u_i)) + (d (a + b))) - ((d a) / b))"
        );
        // A comma followed by a name with `_` or a call separates arguments.
        let e = parse_expr("min(u_1,v_2) + max(u_1,sqrt(2))").unwrap();
        assert_eq!(shape(&e), "(Min(u_1, v_2) + Max(u_1, Sqrt2))");
        let e = parse_expr("min(u_1, v)").unwrap();
        assert_eq!(shape(&e), "Min(u_1, v)");
        assert!(parse_expr("theta_, i").is_err());
        let e = parse_expr("d(d(w)/dx_1)/dx_12").unwrap();
        assert_eq!(shape(&e), "D[x:12](D[x:1](w))");
    }

    #[test]
    fn names_split_into_base_and_indices() {
        let e = parse_expr("sigma_k1").unwrap();
        let ExprKind::Name { base, indices, .. } = e.kind else {
            panic!()
        };
        assert_eq!(base, "sigma");
        assert_eq!(indices.iter().map(|t| t.ch).collect::<String>(), "k1");
        assert_eq!(indices[1].span, Span::new(7, 8));
    }

    #[test]
    fn spans_point_at_tokens() {
        let err = parse_expr("a + * b").unwrap_err();
        assert_eq!(err.span, Span::new(4, 5));
        assert_eq!(err.kind, ErrorKind::Syntax);
        let err = parse_expr("(a + b").unwrap_err();
        assert_eq!(err.span, Span::new(0, 1));
        assert_eq!(parse_expr("a)").unwrap_err().message, "unmatched `)`");
        assert_eq!(parse_expr("a # b").unwrap_err().span, Span::new(2, 3));
        assert_eq!(parse_expr("x^y").unwrap_err().span, Span::new(2, 3));
        assert_eq!(parse_expr("sigma_ ").unwrap_err().span, Span::new(5, 6));
        assert!(parse_expr("").is_err());
        assert!(parse_expr("1.2.3").is_err());
        assert!(parse_expr("avg n").is_err());
    }

    #[test]
    fn deep_nesting_is_an_error_not_a_crash() {
        let deep = "(".repeat(5000) + "a" + &")".repeat(5000);
        assert!(parse_expr(&deep).is_err());
        let negs = "-".repeat(5000) + "a";
        assert!(parse_expr(&negs).is_err());
        let long = vec!["a"; 3000].join(" + ");
        assert!(parse_expr(&long)
            .unwrap_err()
            .message
            .contains("longer than"));
    }

    #[test]
    fn non_ascii_input_is_rejected_cleanly() {
        let err = parse_expr("σ_ij").unwrap_err();
        assert_eq!(err.span, Span::new(0, 2));
    }
}
