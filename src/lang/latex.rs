//! The reader of printed LaTeX: turns the statement of a claim, as the paper prints it,
//! into a tree that the checker's notation table (`derivation::notation`) translates into the index-notation
//! language, so that the transcription in `sides` can be checked against what is
//! printed.
//!
//! The reader knows the subset of LaTeX that equations of continuum mechanics use:
//! symbols with sub- and superscripts (a superscript is a power when it is a number,
//! otherwise a label such as `(1)`, `c` or `(ep)`; a file's notation table can declare
//! other superscripts powers), accents (`\dot`, `\mathbf`), primes, `\frac`, `\sqrt`,
//! `\langle … \rangle`, `|…|`, brackets with `\left`/`\right`, implicit products, `/`,
//! `\partial` fractions, comma derivatives in subscripts, elementary functions,
//! `pmatrix`, tuples, and chains of `=`, `<`, `≤`, `>`, `≥` separated by commas,
//! `\quad`, `\;`, `\text{…}` and `\Rightarrow`.
//!
//! Everything else is refused with its position in the LaTeX: the reader never skips
//! or guesses. Two readings are fixed conventions, stated here and in the guide (docs/src/reading.md):
//! `a b/c d` is `(a b)/(c d)` (a slash divides the whole product on its left by the
//! whole product on its right, as in `2R_g S/3V`), and a symbol written against a
//! parenthesised single symbol or list, `w(y)`, `\theta(x_1, x_2)`, is refused as a possible
//! function application.

use super::diag::Span;

/// A Greek letter named by its LaTeX command without the backslash (`sigma` → σ).
pub fn greek_letter(name: &str) -> Option<char> {
    const TABLE: [(&str, char); 32] = [
        ("alpha", 'α'),
        ("beta", 'β'),
        ("gamma", 'γ'),
        ("delta", 'δ'),
        ("epsilon", 'ε'),
        ("varepsilon", 'ε'),
        ("zeta", 'ζ'),
        ("eta", 'η'),
        ("theta", 'θ'),
        ("vartheta", 'θ'),
        ("kappa", 'κ'),
        ("lambda", 'λ'),
        ("mu", 'μ'),
        ("nu", 'ν'),
        ("xi", 'ξ'),
        ("pi", 'π'),
        ("rho", 'ρ'),
        ("sigma", 'σ'),
        ("tau", 'τ'),
        ("phi", 'φ'),
        ("varphi", 'φ'),
        ("chi", 'χ'),
        ("psi", 'ψ'),
        ("omega", 'ω'),
        ("Gamma", 'Γ'),
        ("Delta", 'Δ'),
        ("Theta", 'Θ'),
        ("Lambda", 'Λ'),
        ("Sigma", 'Σ'),
        ("Phi", 'Φ'),
        ("Psi", 'Ψ'),
        ("Omega", 'Ω'),
    ];
    TABLE.iter().find(|(n, _)| *n == name).map(|(_, c)| *c)
}

/// A printed statement: equations (or bare expressions) and the words between them.
#[derive(Clone, Debug, PartialEq)]
pub struct Printed {
    pub parts: Vec<Part>,
    /// Words after the last part (`\text{ at incipient failure}`).
    pub trailing: Option<String>,
}

/// One chain `a = b < c` of a printed statement, or a bare expression (`∂F/∂σ_ij`).
#[derive(Clone, Debug, PartialEq)]
pub struct Part {
    pub members: Vec<Math>,
    /// Between consecutive members; one fewer than the members.
    pub relations: Vec<Rel>,
    /// What stands before the part: nothing, a comma or space, words, or ⇒.
    pub before: Connective,
    pub span: Span,
}

/// What separates two parts of a statement.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Connective {
    First,
    /// A comma, `\quad` or `\;`.
    Comma,
    /// `\text{…}` with its words.
    Words(String),
    /// `\Rightarrow` or `\implies`.
    Implies,
}

/// A relation between consecutive members of a chain.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rel {
    Eq,
    Lt,
    Le,
    Gt,
    Ge,
}

impl Rel {
    pub fn symbol(self) -> &'static str {
        match self {
            Rel::Eq => "=",
            Rel::Lt => "<",
            Rel::Le => "≤",
            Rel::Gt => ">",
            Rel::Ge => "≥",
        }
    }
}

/// An expression of a printed statement, with its span in the LaTeX.
#[derive(Clone, Debug, PartialEq)]
pub struct Math {
    pub kind: MathKind,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub enum MathKind {
    /// Digits, possibly with a decimal point.
    Number(String),
    Atom(Atom),
    /// Terms with their signs (`true` = subtracted).
    Sum(Vec<(bool, Math)>),
    Product(Vec<Math>),
    Quotient(Box<Math>, Box<Math>),
    Power(Box<Math>, Box<Math>),
    Sqrt(Box<Math>),
    /// `\langle … \rangle`.
    Average(Box<Math>),
    /// `|…|`.
    Abs(Box<Math>),
    /// `\cos x`, `\det(…)`: the function's name without the backslash.
    Apply(String, Box<Math>),
    /// `\partial F / \partial x` or `\frac{\partial F}{\partial x}`.
    Partial {
        of: Box<Math>,
        by: Box<Math>,
    },
    /// `(\sigma_{ij} v_j)_{,i}`: the derivative of a bracketed expression along the
    /// position, once per index after the comma (`ij` for a second derivative).
    Comma {
        of: Box<Math>,
        indices: String,
    },
    /// `\begin{pmatrix} … \end{pmatrix}`: rows of cells.
    Matrix(Vec<Vec<Math>>),
    /// `(a, b, c)`.
    Tuple(Vec<Math>),
}

/// A printed symbol: `\dot\sigma_{ij}^{(1)}`, `v_2'`, `\mathbf{D}^{(el)}`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Atom {
    /// A letter or a command with its backslash: `v`, `\sigma`.
    pub base: String,
    /// `\dot`, `\mathbf`, … with the backslash.
    pub accent: Option<String>,
    pub sub: Option<Script>,
    /// A superscript that is a label, not a power (`(1)`, `c`, `(ep)`).
    pub sup: Option<Script>,
    pub primes: usize,
}

/// The text of a sub- or superscript, without braces or spaces.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Script {
    pub text: String,
    pub span: Span,
}

/// Why a printed statement could not be read, and where.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{message}")]
pub struct LatexError {
    pub span: Span,
    pub message: String,
}

impl LatexError {
    /// "column N" (1-based, in characters) of the error in `src`.
    pub fn column(&self, src: &str) -> usize {
        column(src, self.span.start)
    }
}

/// The 1-based column, in characters, of a byte offset in `src` (an offset inside a
/// character counts as that character).
pub fn column(src: &str, offset: usize) -> usize {
    src.char_indices().take_while(|(k, _)| *k < offset).count() + 1
}

/// How superscripts are told apart: numbers are powers; these too.
#[derive(Clone, Debug, Default)]
pub struct ReadOptions {
    /// Superscripts (without braces) that are powers although they are not numbers.
    pub powers: Vec<String>,
}

/// Reads a printed statement.
pub fn read(src: &str, options: &ReadOptions) -> Result<Printed, LatexError> {
    let mut r = Reader {
        src,
        pos: 0,
        nesting: 0,
        depth: 0,
        abs: 0,
        options,
    };
    r.statement()
}

/// Reads one symbol, as the key of a notation table: `\sigma_{ij}^{(1)}`, `T^2`.
pub fn read_symbol(src: &str, options: &ReadOptions) -> Result<Math, LatexError> {
    let p = read(src, options)?;
    match (&p.parts[..], &p.trailing) {
        ([part], None) if part.members.len() == 1 => Ok(part.members[0].clone()),
        _ => Err(LatexError {
            span: Span::new(0, src.len()),
            message: "a notation key is one printed symbol".to_owned(),
        }),
    }
}

pub const GREEK: &[&str] = &[
    "alpha",
    "beta",
    "gamma",
    "delta",
    "epsilon",
    "varepsilon",
    "zeta",
    "eta",
    "theta",
    "vartheta",
    "iota",
    "kappa",
    "lambda",
    "mu",
    "nu",
    "xi",
    "pi",
    "rho",
    "sigma",
    "tau",
    "upsilon",
    "phi",
    "varphi",
    "chi",
    "psi",
    "omega",
    "Gamma",
    "Delta",
    "Theta",
    "Lambda",
    "Xi",
    "Pi",
    "Sigma",
    "Upsilon",
    "Phi",
    "Psi",
    "Omega",
    "ell",
];
/// The letters of an upright label that makes up a whole script (`\mathrm{eq}`,
/// `\text{I}`, `\textrm{II}`, `\rm{el}`): letters and digits only.
pub fn roman_label(script: &str) -> Option<&str> {
    let inner = ["\\mathrm{", "\\text{", "\\textrm{", "\\rm{"]
        .iter()
        .find_map(|open| script.strip_prefix(open))?
        .strip_suffix('}')?;
    (!inner.is_empty() && inner.chars().all(|c| c.is_ascii_alphanumeric())).then_some(inner)
}

pub const FUNCTIONS: &[&str] = &[
    "cos", "sin", "tan", "exp", "ln", "log", "arctan", "arcsin", "arccos", "det",
];
pub const ACCENTS: &[&str] = &[
    "dot",
    "ddot",
    "bar",
    "hat",
    "tilde",
    "mathbf",
    "boldsymbol",
    "vec",
];
/// Commands that only space.
const SPACES: &[&str] = &[",", "!", " ", ":", ">"];
/// Size prefixes of delimiters.
pub const SIZES: &[&str] = &[
    "left", "right", "big", "Big", "bigl", "bigr", "Bigl", "Bigr",
];

/// Brackets, fractions and roots nest at most this deep (the reader recurses).
const MAX_NESTING: usize = 64;

struct Reader<'a> {
    src: &'a str,
    pos: usize,
    /// How deep the reader has recursed into nested constructs.
    nesting: usize,
    /// Bracket depth: at depth 0, commas and `\quad` separate parts.
    depth: usize,
    /// Open `|…|` bars.
    abs: usize,
    options: &'a ReadOptions,
}

type R<T> = Result<T, LatexError>;

impl<'a> Reader<'a> {
    fn err<T>(&self, start: usize, end: usize, message: impl Into<String>) -> R<T> {
        Err(LatexError {
            span: Span::new(start, end.max(start)),
            message: message.into(),
        })
    }

    fn rest(&self) -> &'a str {
        &self.src[self.pos..]
    }

    fn peek(&self) -> Option<char> {
        self.rest().chars().next()
    }

    /// The command at the position (`\frac` → "frac", `\,` → ","), if any.
    fn command(&self) -> Option<&'a str> {
        let rest = self.rest().strip_prefix('\\')?;
        let letters = rest
            .char_indices()
            .find(|(_, c)| !c.is_ascii_alphabetic())
            .map_or(rest.len(), |(k, _)| k);
        if letters > 0 {
            Some(&rest[..letters])
        } else {
            rest.chars().next().map(|c| &rest[..c.len_utf8()])
        }
    }

    fn eat_command(&mut self, name: &str) -> bool {
        if self.command() == Some(name) {
            self.pos += 1 + name.len();
            true
        } else {
            false
        }
    }

    /// Skips whitespace and thin spaces; inside brackets also `\quad` and `\;`.
    fn skip(&mut self) {
        loop {
            let before = self.pos;
            while self.peek().is_some_and(char::is_whitespace) {
                self.pos += self.peek().map_or(0, char::len_utf8);
            }
            if let Some(c) = self.command() {
                let wide = matches!(c, "quad" | "qquad" | ";");
                if SPACES.contains(&c) || (wide && self.depth > 0) {
                    self.pos += 1 + c.len();
                }
            }
            if self.pos == before {
                return;
            }
        }
    }

    fn at_end(&mut self) -> bool {
        self.skip();
        self.pos >= self.src.len()
    }

    fn statement(&mut self) -> R<Printed> {
        let mut parts = Vec::new();
        let mut before = Connective::First;
        loop {
            if self.at_end() {
                if parts.is_empty() {
                    return self.err(0, self.src.len(), "the statement is empty");
                }
                return match before {
                    Connective::Words(w) => Ok(Printed {
                        parts,
                        trailing: Some(w),
                    }),
                    _ => self.err(
                        self.pos.saturating_sub(1),
                        self.pos,
                        "the statement ends with a separator",
                    ),
                };
            }
            let start = self.pos;
            let part = self.chain()?;
            parts.push(Part {
                span: Span::new(start, self.pos),
                before: std::mem::replace(&mut before, Connective::First),
                ..part
            });
            before = self.separator()?;
            if before == Connective::First {
                if self.at_end() {
                    return Ok(Printed {
                        parts,
                        trailing: None,
                    });
                }
                let c = self.pos;
                return self.err(c, c + 1, self.unexpected());
            }
        }
    }

    /// The separators after a part, merged: `,\quad\text{with}\quad` is "with".
    fn separator(&mut self) -> R<Connective> {
        let mut out = Connective::First;
        loop {
            self.skip();
            if self.peek() == Some(',') {
                self.pos += 1;
                if out == Connective::First {
                    out = Connective::Comma;
                }
            } else if self.eat_command("quad") || self.eat_command("qquad") || self.eat_command(";")
            {
                if out == Connective::First {
                    out = Connective::Comma;
                }
            } else if self.eat_command("Rightarrow") || self.eat_command("implies") {
                out = Connective::Implies;
            } else if self.command() == Some("text") {
                let words = self.text()?;
                out = Connective::Words(words);
            } else {
                return Ok(out);
            }
        }
    }

    /// `\text{…}`: its words, trimmed.
    fn text(&mut self) -> R<String> {
        let start = self.pos;
        self.eat_command("text");
        self.skip();
        let inner = self.braced_raw(start)?;
        Ok(inner.split_whitespace().collect::<Vec<_>>().join(" "))
    }

    /// The raw text of a `{…}` group (nested braces kept), after which the position is.
    fn braced_raw(&mut self, start: usize) -> R<&'a str> {
        if self.peek() != Some('{') {
            return self.err(start, self.pos + 1, "expected `{` here");
        }
        let open = self.pos;
        let mut level = 0usize;
        for (k, c) in self.rest().char_indices() {
            match c {
                '{' => level += 1,
                '}' => {
                    level -= 1;
                    if level == 0 {
                        let inner = &self.src[open + 1..open + k];
                        self.pos = open + k + 1;
                        return Ok(inner);
                    }
                }
                _ => {}
            }
        }
        self.err(open, self.src.len(), "this `{` is never closed")
    }

    fn unexpected(&self) -> String {
        match self.command() {
            Some(c) => format!("`\\{c}` is outside the LaTeX subset the reader knows"),
            None => match self.peek() {
                Some(c) => format!("unexpected `{c}`"),
                None => "unexpected end of the statement".to_owned(),
            },
        }
    }

    fn chain(&mut self) -> R<Part> {
        let mut members = vec![self.expr()?];
        let mut relations = Vec::new();
        while let Some(rel) = self.relation()? {
            relations.push(rel);
            members.push(self.expr()?);
        }
        Ok(Part {
            members,
            relations,
            before: Connective::First,
            span: Span::default(),
        })
    }

    fn relation(&mut self) -> R<Option<Rel>> {
        self.skip();
        let start = self.pos;
        let rel = match self.peek() {
            Some('=') => Rel::Eq,
            Some('<') => Rel::Lt,
            Some('>') => Rel::Gt,
            _ => {
                let rel = match self.command() {
                    Some("leq" | "le" | "leqslant") => Rel::Le,
                    Some("geq" | "ge" | "geqslant") => Rel::Ge,
                    Some("lt") => Rel::Lt,
                    Some("gt") => Rel::Gt,
                    Some(
                        c @ ("neq" | "ne" | "approx" | "sim" | "equiv" | "to" | "rightarrow"
                        | "propto" | "simeq" | "cong"),
                    ) => {
                        return self.err(
                            start,
                            start + 1 + c.len(),
                            format!("the relation `\\{c}` is outside the subset (=, <, ≤, >, ≥)"),
                        )
                    }
                    _ => return Ok(None),
                };
                let name = self.command().unwrap_or_default();
                self.pos += 1 + name.len();
                return Ok(Some(rel));
            }
        };
        self.pos += 1;
        Ok(Some(rel))
    }

    /// Whether the position ends an expression.
    fn ends_expr(&mut self) -> bool {
        self.skip();
        match self.peek() {
            None => true,
            Some('=' | '<' | '>' | ',' | ')' | ']' | '}' | '&') => true,
            Some('|') => self.abs > 0,
            Some('\\') => matches!(
                self.command(),
                Some(
                    "right"
                        | "rangle"
                        | "quad"
                        | "qquad"
                        | ";"
                        | "text"
                        | "Rightarrow"
                        | "implies"
                        | "leq"
                        | "le"
                        | "geq"
                        | "ge"
                        | "lt"
                        | "gt"
                        | "neq"
                        | "ne"
                        | "approx"
                        | "to"
                        | "rightarrow"
                        | "\\"
                        | "end"
                        | "sim"
                        | "equiv"
                        | "propto"
                )
            ),
            _ => false,
        }
    }

    fn expr(&mut self) -> R<Math> {
        self.skip();
        let start = self.pos;
        let mut terms = Vec::new();
        let mut negated = false;
        if self.peek() == Some('-') {
            self.pos += 1;
            negated = true;
        } else if self.peek() == Some('+') {
            self.pos += 1;
        }
        loop {
            if self.command() == Some("pm") || self.command() == Some("mp") {
                return self.err(
                    self.pos,
                    self.pos + 3,
                    "`\\pm` stands for two statements; write each",
                );
            }
            terms.push((negated, self.term()?));
            self.skip();
            match self.peek() {
                Some('+') => negated = false,
                Some('-') => negated = true,
                _ => break,
            }
            self.pos += 1;
        }
        let span = Span::new(start, self.pos);
        if terms.len() == 1 && !terms[0].0 {
            return Ok(terms.pop().expect("one term").1);
        }
        Ok(Math {
            kind: MathKind::Sum(terms),
            span,
        })
    }

    /// A product, or a product divided by a product (`2R_g S/3V` is (2R_g S)/(3V)), or
    /// a `\partial` fraction.
    fn term(&mut self) -> R<Math> {
        self.skip();
        let start = self.pos;
        if self.eat_command("partial") {
            let of = self.product()?;
            self.skip();
            if self.peek() != Some('/') {
                return self.err(start, self.pos, "a `\\partial` outside a fraction ∂F/∂x");
            }
            self.pos += 1;
            self.skip();
            let at = self.pos;
            if !self.eat_command("partial") {
                return self.err(at, at + 1, "expected `\\partial` after `/`");
            }
            let by = self.factor()?;
            return Ok(Math {
                kind: MathKind::Partial {
                    of: Box::new(of),
                    by: Box::new(by),
                },
                span: Span::new(start, self.pos),
            });
        }
        let num = self.product()?;
        self.skip();
        if self.peek() != Some('/') {
            return Ok(num);
        }
        self.pos += 1;
        let den = self.product()?;
        self.skip();
        if self.peek() == Some('/') {
            return self.err(
                start,
                self.pos + 1,
                "`a/b/c` can be read two ways; write \\frac or brackets",
            );
        }
        Ok(Math {
            kind: MathKind::Quotient(Box::new(num), Box::new(den)),
            span: Span::new(start, self.pos),
        })
    }

    /// Whether another factor of a product follows (no operator, no end of the
    /// expression, no `\cdot`).
    fn continues_product(&mut self) -> bool {
        !self.ends_expr()
            && !matches!(self.peek(), Some('+' | '-' | '/'))
            && !matches!(self.command(), Some("cdot" | "partial"))
    }

    fn product(&mut self) -> R<Math> {
        self.skip();
        let start = self.pos;
        let mut factors = Vec::new();
        loop {
            if self.ends_expr() || matches!(self.peek(), Some('+' | '-' | '/')) {
                break;
            }
            if self.eat_command("cdot") {
                continue;
            }
            if self.command() == Some("partial") {
                return self.err(
                    self.pos,
                    self.pos + 8,
                    "a `\\partial` fraction inside a product; bracket it or use \\frac",
                );
            }
            let f = self.factor()?;
            // `w(y)`, `\theta(x_1, x_2)`: a symbol against a bracketed single symbol or
            // list may be a function's arguments rather than a product.
            if let (Some(prev), MathKind::Atom(_) | MathKind::Tuple(_)) = (factors.last(), &f.kind)
            {
                let prev: &Math = prev;
                let bracketed = self.src[f.span.start..].starts_with('(');
                if bracketed
                    && prev.span.end == f.span.start
                    && matches!(prev.kind, MathKind::Atom(_))
                {
                    return self.err(
                        prev.span.start,
                        f.span.end,
                        if matches!(f.kind, MathKind::Tuple(_)) {
                            "a symbol followed by a bracketed list reads as a function application f(x, y); the reader does not guess"
                        } else {
                            "a symbol followed by a bracketed symbol reads as a function application f(x); the reader does not guess"
                        },
                    );
                }
            }
            factors.push(f);
        }
        if factors.is_empty() {
            let at = self.pos;
            return self.err(
                at,
                at + 1,
                format!("expected an expression: {}", self.unexpected()),
            );
        }
        if factors.len() == 1 {
            return Ok(factors.pop().expect("one factor"));
        }
        Ok(Math {
            kind: MathKind::Product(factors),
            span: Span::new(start, self.pos),
        })
    }

    /// A primary with its scripts and primes.
    fn factor(&mut self) -> R<Math> {
        self.skip();
        let start = self.pos;
        if self.nesting >= MAX_NESTING {
            return self.err(
                start,
                start + 1,
                format!("nested more than {MAX_NESTING} deep"),
            );
        }
        self.nesting += 1;
        let m = self.primary();
        self.nesting -= 1;
        let mut m = m?;
        loop {
            match self.peek() {
                Some('_') | Some('^') => {
                    let is_sub = self.peek() == Some('_');
                    let at = self.pos;
                    self.pos += 1;
                    self.skip();
                    let script = self.script()?;
                    let MathKind::Atom(atom) = &mut m.kind else {
                        // `(\sigma_{ij} v_j)_{,i}`: a comma derivative, the one subscript
                        // a bracket may carry (a component, `(\sigma n)_i`, would need a
                        // product the reader does not guess).
                        let comma = script.text.strip_prefix(',').filter(|d| {
                            !d.is_empty() && d.chars().all(|c| c.is_ascii_alphanumeric())
                        });
                        if let (true, Some(d)) = (is_sub, comma) {
                            m = Math {
                                kind: MathKind::Comma {
                                    of: Box::new(m),
                                    indices: d.to_owned(),
                                },
                                span: Span::new(start, self.pos),
                            };
                            continue;
                        }
                        if is_sub {
                            return self.err(at, self.pos, "a subscript on a bracketed expression");
                        }
                        m = self.power(m, script, start)?;
                        continue;
                    };
                    if is_sub {
                        // `(u_k)_{,j}`, a bracketed symbol differentiated: `u_{k,j}`.
                        let derivative = script.text.starts_with(',')
                            && script.text[1..].chars().all(|c| c.is_ascii_alphanumeric())
                            && script.text.len() > 1;
                        match &mut atom.sub {
                            Some(sub) if derivative => {
                                let more = if sub.text.contains(',') {
                                    &script.text[1..]
                                } else {
                                    &script.text
                                };
                                sub.text.push_str(more);
                                sub.span = Span::new(sub.span.start, script.span.end);
                            }
                            Some(_) => return self.err(at, self.pos, "a second subscript"),
                            None => atom.sub = Some(script),
                        }
                    } else if self.is_power(&script.text) {
                        m = self.power(m, script, start)?;
                    } else {
                        if atom.sup.is_some() {
                            return self.err(at, self.pos, "a second superscript label");
                        }
                        atom.sup = Some(script);
                    }
                    m.span = Span::new(start, self.pos);
                }
                Some('\'') => {
                    self.pos += 1;
                    match &mut m.kind {
                        MathKind::Atom(atom) => atom.primes += 1,
                        _ => {
                            return self.err(
                                self.pos - 1,
                                self.pos,
                                "a prime on a bracketed expression",
                            )
                        }
                    }
                    m.span = Span::new(start, self.pos);
                }
                _ => return Ok(m),
            }
        }
    }

    fn is_power(&self, text: &str) -> bool {
        let t = text.strip_prefix('-').unwrap_or(text);
        (!t.is_empty()
            && t.chars()
                .all(|c| c.is_ascii_digit() || c == '/' || c == '.'))
            || self.options.powers.iter().any(|p| p == text)
    }

    fn power(&self, base: Math, script: Script, start: usize) -> R<Math> {
        if !self.is_power(&script.text) {
            return self.err(
                script.span.start,
                script.span.end,
                format!("the superscript `{}` on a bracketed expression is neither a number nor a declared power", script.text),
            );
        }
        let exponent = Math {
            kind: MathKind::Number(script.text.clone()),
            span: script.span,
        };
        Ok(Math {
            kind: MathKind::Power(Box::new(base), Box::new(exponent)),
            span: Span::new(start, script.span.end),
        })
    }

    /// The text of a script: `{…}` or one character or command.
    fn script(&mut self) -> R<Script> {
        let start = self.pos;
        let raw = if self.peek() == Some('{') {
            self.braced_raw(start)?
        } else if let Some(c) = self.command() {
            self.pos += 1 + c.len();
            &self.src[start..self.pos]
        } else {
            match self.peek() {
                Some(c) if c.is_ascii_alphanumeric() || c == '*' => {
                    self.pos += 1;
                    &self.src[start..self.pos]
                }
                _ => return self.err(start, start + 1, "expected a sub- or superscript"),
            }
        };
        let text: String = raw.chars().filter(|c| !c.is_whitespace()).collect();
        if text.is_empty() {
            return self.err(start, self.pos, "an empty script");
        }
        // An upright name (`\sigma_{\mathrm{eq}}`, `\sigma_{\text{I}}`) is a label, kept as
        // printed: its braces are the only ones a script may hold.
        let checked = match roman_label(&text) {
            Some(_) => String::new(),
            None => text.clone(),
        };
        if let Some(k) =
            checked.find(|c: char| !(c.is_ascii_alphanumeric() || "(),*-/.\\".contains(c)))
        {
            let bad = checked[k..].chars().next().unwrap_or(' ');
            return self.err(
                start,
                self.pos,
                format!("`{bad}` in a script is outside the subset (letters, digits, commands, commas, brackets, *)"),
            );
        }
        Ok(Script {
            text,
            span: Span::new(start, self.pos),
        })
    }

    fn atom(&self, base: &str, start: usize) -> Math {
        Math {
            kind: MathKind::Atom(Atom {
                base: base.to_owned(),
                accent: None,
                sub: None,
                sup: None,
                primes: 0,
            }),
            span: Span::new(start, self.pos),
        }
    }

    fn primary(&mut self) -> R<Math> {
        self.skip();
        let start = self.pos;
        let Some(c) = self.peek() else {
            return self.err(start, start, "unexpected end of the statement");
        };
        if c.is_ascii_digit() {
            let len = self
                .rest()
                .char_indices()
                .find(|(_, c)| !(c.is_ascii_digit() || *c == '.'))
                .map_or(self.rest().len(), |(k, _)| k);
            let digits = self.rest()[..len].trim_end_matches('.');
            self.pos += digits.len();
            return Ok(Math {
                kind: MathKind::Number(digits.to_owned()),
                span: Span::new(start, self.pos),
            });
        }
        if c.is_ascii_alphabetic() {
            self.pos += 1;
            return Ok(self.atom(&c.to_string(), start));
        }
        match c {
            '(' | '[' => return self.bracketed(start),
            '{' => {
                self.pos += 1;
                let inner = self.group_rest(start)?;
                return Ok(Math {
                    span: Span::new(start, self.pos),
                    ..inner
                });
            }
            '|' => {
                self.pos += 1;
                self.abs += 1;
                self.depth += 1;
                let inner = self.expr()?;
                self.depth -= 1;
                self.abs -= 1;
                self.skip();
                if self.peek() != Some('|') {
                    return self.err(start, self.pos, "this `|` is never closed");
                }
                self.pos += 1;
                return Ok(Math {
                    kind: MathKind::Abs(Box::new(inner)),
                    span: Span::new(start, self.pos),
                });
            }
            '\\' => {}
            _ => return self.err(start, start + c.len_utf8(), self.unexpected()),
        }
        let name = self.command().unwrap_or_default();
        if SIZES.contains(&name) {
            self.pos += 1 + name.len();
            self.skip();
            return match self.peek() {
                Some('(' | '[') => self.bracketed(start),
                Some('|') => self.primary().map(|m| Math {
                    span: Span::new(start, m.span.end),
                    ..m
                }),
                _ if self.command() == Some("langle") => self.primary(),
                _ => self.err(start, self.pos + 1, "a size command must precede a bracket"),
            };
        }
        if GREEK.contains(&name) {
            self.pos += 1 + name.len();
            return Ok(self.atom(&format!("\\{name}"), start));
        }
        match name {
            "frac" | "tfrac" | "dfrac" => self.fraction(start, name),
            "sqrt" => {
                self.pos += 5;
                self.skip();
                if self.peek() == Some('[') {
                    return self.err(start, self.pos + 1, "only square roots are in the subset");
                }
                let inner = self.argument()?;
                Ok(Math {
                    kind: MathKind::Sqrt(Box::new(inner)),
                    span: Span::new(start, self.pos),
                })
            }
            "langle" => {
                self.pos += 7;
                self.depth += 1;
                let inner = self.expr()?;
                self.depth -= 1;
                self.skip();
                self.eat_command("right");
                if !self.eat_command("rangle") {
                    return self.err(
                        start,
                        self.pos,
                        "this `\\langle` is never closed by `\\rangle`",
                    );
                }
                Ok(Math {
                    kind: MathKind::Average(Box::new(inner)),
                    span: Span::new(start, self.pos),
                })
            }
            "begin" => self.matrix(start),
            _ if ACCENTS.contains(&name) => {
                self.pos += 1 + name.len();
                self.skip();
                let inner = self.argument()?;
                match inner.kind {
                    MathKind::Atom(mut a)
                        if a.accent.is_none() && a.sub.is_none() && a.sup.is_none() =>
                    {
                        a.accent = Some(format!("\\{name}"));
                        Ok(Math {
                            kind: MathKind::Atom(a),
                            span: Span::new(start, self.pos),
                        })
                    }
                    _ => self.err(
                        start,
                        self.pos,
                        format!("`\\{name}` on more than one symbol"),
                    ),
                }
            }
            _ if FUNCTIONS.contains(&name) => {
                self.pos += 1 + name.len();
                self.skip();
                if self.peek() == Some('_') {
                    return self.err(start, self.pos + 1, format!("a subscript on `\\{name}`"));
                }
                // `\cos^2\theta`: a whole power of the value, as tables of identities
                // print it (`\cos^{-1}` would be the inverse function: not read).
                let power = if self.peek() == Some('^') {
                    self.pos += 1;
                    self.skip();
                    let script = self.script()?;
                    let t = script.text.trim();
                    let whole =
                        !t.is_empty() && t.len() <= 3 && t.bytes().all(|b| b.is_ascii_digit());
                    if !whole {
                        return self.err(
                            start,
                            self.pos,
                            format!(
                                "a script on `\\{name}` other than a whole power (`\\{name}^2 x`)"
                            ),
                        );
                    }
                    Some(script)
                } else {
                    None
                };
                self.skip();
                let bracketed =
                    matches!(self.peek(), Some('(' | '{' | '[')) || self.command() == Some("left");
                let mut arg = self.factor()?;
                // A bare argument followed by more factors (`\sin k\theta`, `\sin\omega
                // t`) could be the argument or a factor beside the function: not guessed.
                // `\sin 2\theta` is sin(2θ), as every table of identities prints it; a
                // function after the argument (`\sin\theta\cos\theta`) ends it.
                // A space after the argument (`\det A \, A^{-1}`, `\sin\theta\,d\theta`)
                // ends it, as authors set it.
                let ambiguous = |r: &mut Self| {
                    let rest = r.src[r.pos..].trim_start();
                    let spaced = ["\\,", "\\;", "\\:", "\\ ", "~", "\\quad", "\\qquad"]
                        .iter()
                        .any(|s| rest.starts_with(s));
                    !spaced
                        && r.continues_product()
                        && !r.command().is_some_and(|c| FUNCTIONS.contains(&c))
                };
                let two_ways = format!(
                    "the argument of `\\{name}` can be read two ways; bracket it, `\\{name}(…)`"
                );
                if !bracketed && ambiguous(self) {
                    if !matches!(arg.kind, MathKind::Number(_)) {
                        return self.err(start, self.pos, two_ways);
                    }
                    let next = self.factor()?;
                    if ambiguous(self) {
                        return self.err(start, self.pos, two_ways);
                    }
                    let span = Span::new(arg.span.start, next.span.end);
                    arg = Math {
                        kind: MathKind::Product(vec![arg, next]),
                        span,
                    };
                }
                let applied = Math {
                    kind: MathKind::Apply(name.to_owned(), Box::new(arg)),
                    span: Span::new(start, self.pos),
                };
                match power {
                    Some(script) => {
                        let exponent = Math {
                            kind: MathKind::Number(script.text.trim().to_owned()),
                            span: script.span,
                        };
                        Ok(Math {
                            kind: MathKind::Power(Box::new(applied), Box::new(exponent)),
                            span: Span::new(start, self.pos),
                        })
                    }
                    None => Ok(applied),
                }
            }
            _ => self.err(start, start + 1 + name.len(), self.unexpected()),
        }
    }

    /// One argument of a command: `{…}`, or a single character or command.
    fn argument(&mut self) -> R<Math> {
        self.skip();
        let start = self.pos;
        if self.peek() == Some('{') {
            return self.primary();
        }
        if let Some(c) = self.peek().filter(char::is_ascii_digit) {
            self.pos += 1;
            return Ok(Math {
                kind: MathKind::Number(c.to_string()),
                span: Span::new(start, self.pos),
            });
        }
        self.primary()
    }

    fn fraction(&mut self, start: usize, name: &str) -> R<Math> {
        self.pos += 1 + name.len();
        self.skip();
        let num_start = self.pos;
        let num_partial = self.src[num_start..]
            .trim_start_matches('{')
            .trim_start()
            .starts_with("\\partial");
        let (num, den) = if num_partial {
            let of = self.partial_argument()?;
            self.skip();
            let by = self.partial_argument()?;
            return Ok(Math {
                kind: MathKind::Partial {
                    of: Box::new(of),
                    by: Box::new(by),
                },
                span: Span::new(start, self.pos),
            });
        } else {
            (self.argument()?, self.argument()?)
        };
        let plain_d =
            |m: &Math| matches!(&m.kind, MathKind::Atom(a) if a.base == "d" && a.sub.is_none());
        let leading_d = |m: &Math| match &m.kind {
            MathKind::Product(f) => plain_d(&f[0]),
            _ => plain_d(m),
        };
        if leading_d(&num) && leading_d(&den) {
            return self.err(
                start,
                self.pos,
                "an ordinary derivative d/dx is outside the subset",
            );
        }
        Ok(Math {
            kind: MathKind::Quotient(Box::new(num), Box::new(den)),
            span: Span::new(start, self.pos),
        })
    }

    /// `{\partial X}` of a `\frac`: X.
    fn partial_argument(&mut self) -> R<Math> {
        let start = self.pos;
        if self.peek() != Some('{') {
            return self.err(start, start + 1, "expected `{` here");
        }
        self.pos += 1;
        self.skip();
        if !self.eat_command("partial") {
            return self.err(
                start,
                self.pos + 1,
                "both parts of a \\partial fraction start with \\partial",
            );
        }
        self.group_rest(start)
    }

    /// The rest of a `{…}` group opened at `start`: an expression and the `}`.
    fn group_rest(&mut self, start: usize) -> R<Math> {
        self.depth += 1;
        let inner = self.expr()?;
        self.depth -= 1;
        self.skip();
        if self.peek() != Some('}') {
            return self.err(start, self.pos + 1, "this `{` is never closed");
        }
        self.pos += 1;
        Ok(inner)
    }

    /// `( … )`, `[ … ]` (with `\left`/`\right`): an expression or a tuple.
    fn bracketed(&mut self, start: usize) -> R<Math> {
        let open = self.peek().unwrap_or('(');
        let close = if open == '(' { ')' } else { ']' };
        self.pos += 1;
        self.depth += 1;
        let mut items = vec![self.expr()?];
        loop {
            self.skip();
            if self.peek() == Some(',') {
                self.pos += 1;
                items.push(self.expr()?);
                continue;
            }
            self.eat_command("right");
            self.skip();
            if self.peek() == Some(close) {
                self.pos += 1;
                break;
            }
            let at = self.pos;
            let what = match self.relation() {
                Ok(Some(_)) => {
                    "a relation inside brackets (a condition) is outside the subset".to_owned()
                }
                _ => format!("this `{open}` is never closed: {}", self.unexpected()),
            };
            return self.err(at, at + 1, what);
        }
        self.depth -= 1;
        let span = Span::new(start, self.pos);
        if items.len() == 1 {
            let inner = items.pop().expect("one item");
            return Ok(Math { span, ..inner });
        }
        Ok(Math {
            kind: MathKind::Tuple(items),
            span,
        })
    }

    fn matrix(&mut self, start: usize) -> R<Math> {
        self.eat_command("begin");
        let env = self.braced_raw(start)?;
        if !matches!(env, "pmatrix" | "bmatrix") {
            return self.err(
                start,
                self.pos,
                format!("the environment `{env}` is outside the subset (pmatrix, bmatrix)"),
            );
        }
        self.depth += 1;
        let mut rows = vec![Vec::new()];
        loop {
            let cell = self.expr()?;
            rows.last_mut().expect("a row").push(cell);
            self.skip();
            if self.peek() == Some('&') {
                self.pos += 1;
            } else if self.eat_command("\\") {
                rows.push(Vec::new());
            } else if self.eat_command("end") {
                let at = self.pos;
                if self.braced_raw(at)? != env {
                    return self.err(at, self.pos, format!("`\\end` does not close `{env}`"));
                }
                break;
            } else {
                let at = self.pos;
                return self.err(at, at + 1, format!("in a matrix: {}", self.unexpected()));
            }
        }
        self.depth -= 1;
        if rows.iter().any(|r| r.len() != rows[0].len()) {
            return self.err(
                start,
                self.pos,
                "the rows of this matrix have different lengths",
            );
        }
        Ok(Math {
            kind: MathKind::Matrix(rows),
            span: Span::new(start, self.pos),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The only member of a statement without a relation.
    fn one(src: &str) -> Result<Math, LatexError> {
        let p = read(src, &ReadOptions::default())?;
        Ok(p.parts[0].members[0].clone())
    }

    /// The shape of a reading, in words: `sin(2 theta)`, `pow(cos(theta), 2)`.
    fn shape(m: &Math) -> String {
        match &m.kind {
            MathKind::Number(n) => n.clone(),
            MathKind::Atom(a) => a.base.trim_start_matches('\\').to_owned(),
            MathKind::Product(fs) => fs.iter().map(shape).collect::<Vec<_>>().join(" "),
            MathKind::Apply(f, x) => format!("{f}({})", shape(x)),
            MathKind::Power(b, e) => format!("pow({}, {})", shape(b), shape(e)),
            _ => "?".to_owned(),
        }
    }

    /// A comma on a bracket differentiates it (`(\sigma_{ij} v_j)_{,i}`), and on a
    /// bracketed symbol extends its subscript (`(u_k)_{,j}` is `u_{k,j}`); a component
    /// of a bracket (`(\sigma n)_i`) or a second plain subscript is refused.
    #[test]
    fn a_comma_on_a_bracket_is_a_derivative() {
        let m = one("(\\sigma_{ij} v_j)_{,ik}").unwrap();
        let MathKind::Comma { of, indices } = &m.kind else {
            panic!("{m:?}");
        };
        assert_eq!((shape(of).as_str(), indices.as_str()), ("sigma v", "ik"));
        for (src, sub) in [
            ("(u_k)_{,j}", "k,j"),
            ("(u_{k,i})_{,j}", "k,ij"),
            ("(u)_{,1}", ",1"),
        ] {
            let m = one(src).unwrap_or_else(|e| panic!("{src}: {}", e.message));
            let MathKind::Atom(a) = &m.kind else {
                panic!("{src}: {m:?}");
            };
            assert_eq!(a.sub.as_ref().map(|s| s.text.as_str()), Some(sub), "{src}");
        }
        for (src, why) in [
            ("(\\sigma n)_i", "a subscript on a bracketed expression"),
            ("(a + b)_{,}", "a subscript on a bracketed expression"),
            ("(u_k)_j", "a second subscript"),
            ("(u_k)_{,j+1}", "outside the subset"),
        ] {
            let e = one(src).expect_err(src);
            assert!(e.message.contains(why), "{src}: {}", e.message);
        }
    }

    /// `\sin 2\theta` is sin(2θ), as every table of identities prints it, and
    /// `\cos^2\theta` the square of cos θ; a third factor, or a script that is no whole
    /// power, is not guessed.
    #[test]
    fn a_function_of_a_multiple_and_a_power_of_a_function_read_as_printed() {
        for (src, want) in [
            ("\\sin 2\\theta", "sin(2 theta)"),
            ("\\cos 2 \\theta", "cos(2 theta)"),
            ("\\sin\\theta\\cos\\theta", "sin(theta) cos(theta)"),
            ("2\\sin\\theta", "2 sin(theta)"),
            ("\\cos^2\\theta", "pow(cos(theta), 2)"),
            ("\\sin^{2} 2\\theta", "pow(sin(2 theta), 2)"),
            ("\\sin 2", "sin(2)"),
            ("\\sin 2\\theta\\cos\\theta", "sin(2 theta) cos(theta)"),
            ("\\sin(\\theta) x", "sin(theta) x"),
            ("x\\sin\\theta", "x sin(theta)"),
            ("\\cos\\theta\\,\\sigma_{11}", "cos(theta) sigma"),
            ("\\det A \\, B", "det(A) B"),
            ("\\sin 2\\theta\\, x", "sin(2 theta) x"),
        ] {
            let m = one(src).unwrap_or_else(|e| panic!("{src}: {}", e.message));
            assert_eq!(shape(&m), want, "{src}");
        }
        for (src, why) in [
            ("\\sin 2\\theta x", "can be read two ways"),
            ("\\sin k\\theta", "can be read two ways"),
            ("\\sin\\omega t", "can be read two ways"),
            ("\\cos kx", "can be read two ways"),
            ("\\cos^{-1} x", "other than a whole power"),
            ("\\cos^n x", "other than a whole power"),
            ("\\cos_k x", "a subscript on"),
        ] {
            let e = one(src).expect_err(src);
            assert!(e.message.contains(why), "{src}: {}", e.message);
        }
        // A sum after the multiple ends the argument.
        let p = read("\\sin 2\\theta + x", &ReadOptions::default()).unwrap();
        assert!(matches!(p.parts[0].members[0].kind, MathKind::Sum(_)));
    }

    /// An upright subscript is a label, kept as printed; other braces in a script are
    /// not read.
    #[test]
    fn an_upright_subscript_is_a_label() {
        for (src, label) in [
            ("\\sigma_{\\mathrm{I}}", "\\mathrm{I}"),
            ("\\sigma_{\\text{eq}}", "\\text{eq}"),
            ("\\tau_{\\max}", "\\max"),
        ] {
            let m = one(src).unwrap_or_else(|e| panic!("{src}: {}", e.message));
            let MathKind::Atom(a) = &m.kind else {
                panic!("{src}")
            };
            assert_eq!(a.sub.as_ref().map(|s| s.text.as_str()), Some(label));
        }
        assert_eq!(roman_label("\\mathrm{II}"), Some("II"));
        assert_eq!(roman_label("\\mathrm{I}x"), None);
        assert_eq!(roman_label("\\mathrm{}"), None);
        assert!(one("\\sigma_{\\mathrm{I}{x}}").is_err());
        assert!(one("\\sigma_{\\hat{x}}").is_err());
    }
}
