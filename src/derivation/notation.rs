//! The notation table of a derivation file, and the translation of a printed statement
//! ([`crate::lang::latex`]) into the index-notation language through it.
//!
//! A table maps printed symbols to the language: `'\sigma_{ij}^{(1)}' = "sig1_ij"`,
//! `'T^2' = "avg(tt_k tt_k)"`. The index letters of a key are pattern variables:
//! `\sigma_{ki}^{(1)}` becomes `sig1_ki`, and `\sigma_{21}^{(1)}` becomes `sig1_21`.
//! Index letters of a value that are not pattern variables are summed inside it and are
//! renamed apart from the statement's. A value may be a list of readings (routes) of
//! the same symbol; the statement is then read once per reading. A key `'^{n}'` with
//! value `"power"` declares the superscript n a power; every other superscript that is
//! not a number is a label. The claim's table (`[claim.notation]`) comes before the
//! file's.
//!
//! Without an entry, a symbol is read as written: Greek letters by their names
//! (`\sigma_{ki}` → `sigma_ki`, `\ell_m` → `ell_m`), `\delta_{ij}` → `delta_ij`,
//! `e_{ijk}` and `\varepsilon_{ijk}` → `eps_ijk`, a subscript that completes a declared
//! scalar's name (`R_g`, `f_r`) as that name, and a comma in a subscript as a
//! derivative (`v_{i,m}` → `v_i,m`). A label, an accent or a prime without an entry is
//! refused, as is a symbol that is neither declared nor defined.

use crate::lang::latex::{self, Atom, LatexError, Math, MathKind, Part, Printed, ReadOptions};
use crate::lang::parser::{ExprKind, IndexTok};
use crate::lang::{parse_expr, Decls, DefSig, Expr, Span};
use std::collections::{BTreeMap, BTreeSet};

/// One entry: a printed symbol and its readings in the language.
#[derive(Clone, Debug)]
pub struct Entry {
    pattern: Math,
    /// The key as written, for reading the table backwards ([`Notation::printed`]).
    key: String,
    pub values: Vec<String>,
    /// The letters of the key's subscript that are pattern variables.
    vars: BTreeSet<char>,
}

/// A notation table: the claim's entries first, then the file's.
#[derive(Clone, Debug, Default)]
pub struct Notation {
    pub entries: Vec<Entry>,
    pub options: ReadOptions,
    /// `'\langle\rangle' = "macaulay"`: angle brackets are the Macaulay bracket
    /// ⟨x⟩ = max(x, 0), not the average over the normal.
    pub macaulay: bool,
}

/// Why an entry of a table is malformed.
#[derive(Debug, thiserror::Error)]
#[error("{message}")]
pub struct EntryError {
    pub message: String,
}

impl Notation {
    /// Adds `key = values` (the superscript declarations `'^{n}' = "power"` included).
    pub fn add(&mut self, key: &str, values: Vec<String>) -> Result<(), EntryError> {
        if key.split_whitespace().collect::<String>() == "\\langle\\rangle" {
            return match values.as_slice() {
                [v] if v == "macaulay" => {
                    self.macaulay = true;
                    Ok(())
                }
                [v] if v == "average" => Ok(()),
                _ => Err(EntryError {
                    message: format!("the key `{key}` takes \"average\" or \"macaulay\""),
                }),
            };
        }
        if let Some(sup) = key.strip_prefix('^') {
            let sup: String = sup
                .trim_matches(|c| c == '{' || c == '}')
                .chars()
                .filter(|c| !c.is_whitespace())
                .collect();
            return match values.as_slice() {
                [v] if v == "power" => {
                    self.options.powers.push(sup);
                    Ok(())
                }
                [v] if v == "label" => Ok(()),
                _ => Err(EntryError {
                    message: format!("the superscript key `{key}` takes \"power\" or \"label\""),
                }),
            };
        }
        let pattern = latex::read_symbol(key, &self.options).map_err(|e| EntryError {
            message: format!("the key `{key}` is not a printed symbol: {}", e.message),
        })?;
        let atom = match &pattern.kind {
            MathKind::Atom(a) => a,
            MathKind::Power(base, _) => match &base.kind {
                MathKind::Atom(a) => a,
                _ => {
                    return Err(EntryError {
                        message: format!("the key `{key}` is not a symbol or a power of one"),
                    })
                }
            },
            _ => {
                return Err(EntryError {
                    message: format!("the key `{key}` is not a symbol or a power of one"),
                })
            }
        };
        let letters = pattern_letters(atom);
        if values.is_empty() {
            return Err(EntryError {
                message: format!("the key `{key}` has no reading"),
            });
        }
        // A letter of the key's subscript is a pattern variable when the readings use it
        // as an index (`\sigma_{ij}^{(1)}` → sig1_ij), and part of the name otherwise
        // (`F_{MV}` → FMV); every reading must agree.
        let mut vars: Option<BTreeSet<char>> = None;
        for v in &values {
            let e = parse_expr(v).map_err(|e| EntryError {
                message: format!(
                    "the reading `{v}` of `{key}` is not an expression: {}",
                    e.message
                ),
            })?;
            let mut toks = Vec::new();
            index_tokens(&e, &|_| false, &mut toks);
            let used: BTreeSet<char> = toks
                .iter()
                .map(|t| t.ch)
                .filter(|c| letters.contains(c))
                .collect();
            match &vars {
                Some(before) if *before != used => {
                    return Err(EntryError {
                        message: format!("the readings of `{key}` use different indices of it"),
                    })
                }
                _ => vars = Some(used),
            }
        }
        self.entries.push(Entry {
            pattern,
            key: key.to_owned(),
            values,
            vars: vars.unwrap_or_default(),
        });
        Ok(())
    }

    /// An empty table that reads keys as `file` does, for a claim's own entries.
    pub fn within(file: &Notation) -> Notation {
        Notation {
            entries: Vec::new(),
            options: file.options.clone(),
            macaulay: file.macaulay,
        }
    }

    /// These entries before the file's.
    pub fn then(mut self, file: &Notation) -> Notation {
        self.entries.extend(file.entries.iter().cloned());
        self.macaulay |= file.macaulay;
        self
    }

    /// The printed symbol of a variable of the language, read backwards through the
    /// table: the key of the first entry whose one reading is the variable's name with
    /// the key's pattern variables as its indices, those letters replaced by the
    /// variable's index values (`'\Gamma_{mi}^{(1)}' = "G1_mi"` gives `G1_21` ↦
    /// `\Gamma_{21}^{(1)}`; `'\bar\tau' = "tb"` gives `tb` ↦ `\bar\tau`). None for a
    /// variable no entry names alone (an entry whose reading is an expression).
    pub fn printed(&self, variable: &str) -> Option<String> {
        self.entries.iter().find_map(|e| {
            let [value] = e.values.as_slice() else {
                return None;
            };
            if e.vars.is_empty() {
                return (value == variable && is_name(value)).then(|| e.key.clone());
            }
            let (base, letters) = value.rsplit_once('_')?;
            let (vbase, digits) = variable.rsplit_once('_')?;
            let letters: Vec<char> = letters.chars().collect();
            let distinct: BTreeSet<char> = letters.iter().copied().collect();
            let fits = base == vbase
                && is_name(base)
                && distinct == e.vars
                && distinct.len() == letters.len()
                && digits.chars().count() == letters.len()
                && digits.chars().all(|c| c.is_ascii_digit());
            if !fits {
                return None;
            }
            let map: Vec<(char, char)> = letters.into_iter().zip(digits.chars()).collect();
            with_indices(&e.key, &map)
        })
    }
    /// The printed symbol of a symbol of the language (no index values): the key as
    /// written of the first entry whose one reading is the name alone, or the name with
    /// the key's pattern variables as its indices (`'f_{i}^{(1,2)c}' = "f12c_i"` gives
    /// `f12c` ↦ `f_{i}^{(1,2)c}`). None for a symbol no entry names alone.
    pub fn printed_symbol(&self, symbol: &str) -> Option<&str> {
        self.entries.iter().find_map(|e| {
            let [value] = e.values.as_slice() else {
                return None;
            };
            let fits = if e.vars.is_empty() {
                value == symbol
            } else {
                value.rsplit_once('_').is_some_and(|(base, letters)| {
                    let distinct: BTreeSet<char> = letters.chars().collect();
                    base == symbol
                        && distinct == e.vars
                        && distinct.len() == letters.chars().count()
                })
            };
            (fits && is_name(symbol)).then_some(e.key.as_str())
        })
    }
}

/// A name of the language with no indices: a letter, then letters and digits.
fn is_name(s: &str) -> bool {
    s.starts_with(|c: char| c.is_ascii_alphabetic())
        && s.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// `key` with the letters of its subscript (the first `_` outside braces, a group of
/// letters and commas or one letter) replaced by `map`; None where the subscript holds
/// anything else.
fn with_indices(key: &str, map: &[(char, char)]) -> Option<String> {
    let chars: Vec<char> = key.chars().collect();
    let mut depth = 0usize;
    let at = chars.iter().enumerate().find_map(|(k, &c)| {
        match c {
            '{' => depth += 1,
            '}' => depth = depth.saturating_sub(1),
            '_' if depth == 0 => return Some(k),
            _ => {}
        }
        None
    })?;
    let (start, end) = if chars.get(at + 1) == Some(&'{') {
        let close = chars[at + 2..].iter().position(|&c| c == '}')? + at + 2;
        (at + 2, close)
    } else {
        (at + 1, at + 2)
    };
    let group = chars.get(start..end)?;
    if !group
        .iter()
        .all(|c| c.is_ascii_alphabetic() || *c == ',' || *c == ' ')
    {
        return None;
    }
    let mut out: String = chars[..start].iter().collect();
    for c in group {
        out.push(map.iter().find(|(l, _)| l == c).map_or(*c, |(_, d)| *d));
    }
    out.extend(&chars[end..]);
    Some(out)
}

/// The letters of a key's subscript: its pattern variables.
fn pattern_letters(a: &Atom) -> Vec<char> {
    a.sub
        .as_ref()
        .filter(|s| is_slots(&s.text))
        .map(|s| s.text.chars().filter(char::is_ascii_alphabetic).collect())
        .unwrap_or_default()
}

/// A subscript of index slots (letters, digits, a comma before derivatives), not a
/// name part such as `\tau`.
fn is_slots(text: &str) -> bool {
    !text.contains('\\')
}

/// Every index token of an expression (names and derivatives), except the suffixes of
/// names that `whole` says are scalars (`R_g`).
fn index_tokens(e: &Expr, whole: &dyn Fn(&str) -> bool, out: &mut Vec<IndexTok>) {
    let go = |x: &Expr, out: &mut Vec<IndexTok>| index_tokens(x, whole, out);
    match &e.kind {
        ExprKind::Number(_) => {}
        ExprKind::Name { indices, full, .. } => {
            if !whole(full) {
                out.extend(indices.iter().copied())
            }
        }
        ExprKind::Neg(a) | ExprKind::Pow(a, _) | ExprKind::Call(_, a) => go(a, out),
        ExprKind::Add(a, b)
        | ExprKind::Sub(a, b)
        | ExprKind::Mul(a, b)
        | ExprKind::Div(a, b)
        | ExprKind::Call2(_, a, b) => {
            go(a, out);
            go(b, out);
        }
        ExprKind::Deriv { inner, indices, .. } => {
            go(inner, out);
            out.extend(indices.iter().copied());
        }
        ExprKind::Wrt { body, symbol, .. } => {
            go(body, out);
            go(symbol, out);
        }
        ExprKind::Matrix(rows) => rows.iter().flatten().for_each(|x| go(x, out)),
        ExprKind::Entry(a, _) => go(a, out),
        ExprKind::MatCall(_, args) => args.iter().for_each(|x| go(x, out)),
    }
}

/// A printed statement in the language: its parts, each read once per combination of
/// the readings of its symbols.
#[derive(Clone, Debug)]
pub struct Reading {
    pub parts: Vec<ReadPart>,
}

#[derive(Clone, Debug)]
pub struct ReadPart {
    /// The part as printed.
    pub latex: String,
    pub span: Span,
    pub relations: Vec<latex::Rel>,
    pub before: latex::Connective,
    /// One chain of members per combination of readings.
    pub routes: Vec<Vec<ReadMember>>,
    /// The printed symbol this chain defines (its dropped first member).
    pub defines: Option<String>,
    /// The chain is a condition (after "if", "for", "when", …): a hypothesis of the
    /// statement, not its conclusion.
    pub condition: bool,
}

/// Words that introduce a condition rather than a conclusion.
const CONDITION_WORDS: &[&str] = &[
    "if", "for", "when", "whenever", "provided", "on", "at", "where",
];

/// One member of a chain, in the language, with its top-level terms for locating a
/// difference.
#[derive(Clone, Debug)]
pub struct ReadMember {
    pub span: Span,
    pub text: String,
    /// (span in the LaTeX, the term with its sign in the language).
    pub terms: Vec<(Span, String)>,
    /// The member is a bare `∂F/∂x`: (F, the symbol's name) in the language.
    pub partial: Option<(String, String)>,
}

/// Why a printed statement is not read: a refusal of the reader or of the translation,
/// located in the LaTeX.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Unread {
    pub span: Span,
    pub message: String,
}

impl From<LatexError> for Unread {
    fn from(e: LatexError) -> Self {
        Unread {
            span: e.span,
            message: e.message,
        }
    }
}

/// At most this many readings of one part (routes multiply).
const MAX_ROUTES: usize = 16;

/// Reads `printed` and translates it through `notation`. A chain whose first member is
/// one of the symbols in `defines` starts with the definition of that symbol: the member
/// is dropped, and recorded.
pub fn read(
    printed: &str,
    notation: &Notation,
    defines: &[Math],
    decls: &Decls,
    sigs: &[DefSig],
) -> Result<Reading, Unread> {
    let statement: Printed = latex::read(printed, &notation.options)?;
    let mut parts = Vec::new();
    let mut condition = false;
    for part in &statement.parts {
        condition = match &part.before {
            latex::Connective::Words(w) => {
                let first = w.split_whitespace().next().unwrap_or("");
                CONDITION_WORDS.contains(&first)
            }
            latex::Connective::Comma => condition,
            latex::Connective::First | latex::Connective::Implies => false,
        };
        let bare =
            part.members.len() == 1 && !matches!(part.members[0].kind, MathKind::Partial { .. });
        if bare {
            return Err(Unread {
                span: part.span,
                message: "a bare expression is not a statement (a list such as `x, y \\ge 0` is outside the subset)".to_owned(),
            });
        }
        let mut part = part.clone();
        let mut defined = None;
        if part.members.len() >= 2 && part.relations[0] == latex::Rel::Eq {
            let any_letter: BTreeSet<char> = ('a'..='z').chain('A'..='Z').collect();
            if defines
                .iter()
                .any(|d| matches(d, &any_letter, &part.members[0]).is_some())
            {
                let first = part.members.remove(0);
                part.relations.remove(0);
                defined = Some(printed[first.span.start..first.span.end].trim().to_owned());
            }
        }
        let mut read = read_part(printed, &part, notation, decls, sigs)?;
        read.defines = defined;
        read.condition = condition;
        // In `H ⇒ C` the chains before the arrow, back to the last words, are the
        // hypotheses.
        if part.before == latex::Connective::Implies {
            for earlier in parts.iter_mut().rev() {
                let earlier: &mut ReadPart = earlier;
                earlier.condition = true;
                if !matches!(earlier.before, latex::Connective::Comma) {
                    break;
                }
            }
        }
        parts.push(read);
    }
    Ok(Reading { parts })
}

/// Reads a `defines` entry: one printed symbol.
pub fn defined_symbol(key: &str, notation: &Notation) -> Result<Math, EntryError> {
    latex::read_symbol(key, &notation.options).map_err(|e| EntryError {
        message: format!("`{key}` is not a printed symbol: {}", e.message),
    })
}

fn read_part(
    printed: &str,
    part: &Part,
    notation: &Notation,
    decls: &Decls,
    sigs: &[DefSig],
) -> Result<ReadPart, Unread> {
    let mut letters = BTreeSet::new();
    for m in &part.members {
        printed_letters(m, &mut letters);
    }
    // First pass: which entries with several readings the part uses.
    let mut t = Translator {
        decls,
        sigs,
        notation,
        choice: BTreeMap::new(),
        multi: BTreeSet::new(),
        taken: letters.clone(),
    };
    let first: Vec<ReadMember> = part
        .members
        .iter()
        .map(|m| t.member(m))
        .collect::<Result<_, _>>()?;
    let multi: Vec<usize> = t.multi.iter().copied().collect();
    let mut routes = vec![first];
    if !multi.is_empty() {
        routes.clear();
        let counts: Vec<usize> = multi
            .iter()
            .map(|&e| notation.entries[e].values.len())
            .collect();
        // Checked: a wrapped product once let a crafted table past the cap.
        let total = counts
            .iter()
            .try_fold(1usize, |acc, &n| acc.checked_mul(n))
            .filter(|&t| t <= MAX_ROUTES)
            .ok_or_else(|| Unread {
                span: part.span,
                message: format!(
                    "{} combinations of readings; at most {MAX_ROUTES}",
                    counts
                        .iter()
                        .try_fold(1usize, |acc, &n| acc.checked_mul(n))
                        .map_or_else(|| "more than 2^64".to_owned(), |t| t.to_string())
                ),
            })?;
        for k in 0..total {
            let mut rest = k;
            t.choice.clear();
            // Each reading renames apart from the statement alone.
            t.taken = letters.clone();
            for (&e, &n) in multi.iter().zip(&counts) {
                t.choice.insert(e, rest % n);
                rest /= n;
            }
            let route = part
                .members
                .iter()
                .map(|m| t.member(m))
                .collect::<Result<_, _>>()?;
            routes.push(route);
        }
    }
    Ok(ReadPart {
        latex: printed[part.span.start..part.span.end].trim().to_owned(),
        span: part.span,
        relations: part.relations.clone(),
        before: part.before.clone(),
        routes,
        defines: None,
        condition: false,
    })
}

/// Every index letter the statement uses, so that a reading's own summed letters are
/// renamed apart from them.
fn printed_letters(m: &Math, out: &mut BTreeSet<char>) {
    match &m.kind {
        MathKind::Atom(a) => out.extend(pattern_letters(a)),
        MathKind::Number(_) => {}
        MathKind::Sum(ts) => ts.iter().for_each(|(_, t)| printed_letters(t, out)),
        MathKind::Product(fs) | MathKind::Tuple(fs) => {
            fs.iter().for_each(|f| printed_letters(f, out))
        }
        MathKind::Quotient(a, b) | MathKind::Power(a, b) => {
            printed_letters(a, out);
            printed_letters(b, out);
        }
        MathKind::Partial { of, by } => {
            printed_letters(of, out);
            printed_letters(by, out);
        }
        MathKind::Comma { of, indices } => {
            printed_letters(of, out);
            out.extend(indices.chars().filter(char::is_ascii_alphabetic));
        }
        MathKind::Sqrt(a) | MathKind::Average(a) | MathKind::Abs(a) | MathKind::Apply(_, a) => {
            printed_letters(a, out)
        }
        MathKind::Matrix(rows) => rows.iter().flatten().for_each(|c| printed_letters(c, out)),
    }
}

struct Translator<'a> {
    decls: &'a Decls,
    sigs: &'a [DefSig],
    notation: &'a Notation,
    /// The reading chosen for each entry with several.
    choice: BTreeMap<usize, usize>,
    /// Entries with several readings met so far.
    multi: BTreeSet<usize>,
    /// Index letters in use.
    taken: BTreeSet<char>,
}

type T<X> = Result<X, Unread>;

fn refuse<X>(span: Span, message: impl Into<String>) -> T<X> {
    Err(Unread {
        span,
        message: message.into(),
    })
}

/// Operator precedence of a translated piece: 0 sum, 1 product, 2 power, 3 atom.
struct Piece {
    text: String,
    prec: u8,
}

impl Piece {
    fn atom(text: String) -> Self {
        Piece { text, prec: 3 }
    }
    fn at_least(&self, prec: u8) -> String {
        if self.prec >= prec {
            self.text.clone()
        } else {
            format!("({})", self.text)
        }
    }
}

impl Translator<'_> {
    fn member(&mut self, m: &Math) -> T<ReadMember> {
        let piece = self.math(m)?;
        let terms = match &m.kind {
            MathKind::Sum(ts) => ts
                .iter()
                .map(|(neg, t)| {
                    let p = self.math(t)?;
                    let sign = if *neg { "- " } else { "" };
                    Ok((t.span, format!("{sign}{}", p.at_least(1))))
                })
                .collect::<T<Vec<_>>>()?,
            _ => vec![(m.span, piece.text.clone())],
        };
        let partial = match &m.kind {
            MathKind::Partial { of, by } => {
                let f = self.math(of)?.text;
                let x = self.math(by)?.text;
                let symbol = parse_expr(&x)
                    .ok()
                    .and_then(|e| match e.kind {
                        ExprKind::Name { base, full, .. } => {
                            Some(if self.decls.symbols.contains_key(&full) {
                                full
                            } else {
                                base
                            })
                        }
                        _ => None,
                    })
                    .unwrap_or(x);
                Some((f, symbol))
            }
            _ => None,
        };
        Ok(ReadMember {
            span: m.span,
            text: piece.text,
            terms,
            partial,
        })
    }

    fn math(&mut self, m: &Math) -> T<Piece> {
        Ok(match &m.kind {
            MathKind::Number(n) => Piece::atom(n.clone()),
            MathKind::Atom(a) => self.symbol(m, a)?,
            MathKind::Sum(ts) => {
                let mut text = String::new();
                for (k, (neg, t)) in ts.iter().enumerate() {
                    let p = self.math(t)?.at_least(1);
                    match (k, neg) {
                        (0, false) => text.push_str(&p),
                        (0, true) => text.push_str(&format!("-{p}")),
                        (_, false) => text.push_str(&format!(" + {p}")),
                        (_, true) => text.push_str(&format!(" - {p}")),
                    }
                }
                Piece { text, prec: 0 }
            }
            MathKind::Product(fs) => {
                let parts = fs
                    .iter()
                    .map(|f| Ok(self.math(f)?.at_least(2)))
                    .collect::<T<Vec<_>>>()?;
                Piece {
                    text: parts.join(" "),
                    prec: 1,
                }
            }
            MathKind::Quotient(a, b) => {
                let a = self.math(a)?.at_least(2);
                let b = self.math(b)?.at_least(2);
                Piece {
                    text: format!("{a} / {b}"),
                    prec: 1,
                }
            }
            MathKind::Power(base, e) => {
                if let Some(p) = self.entry(m)? {
                    return Ok(p);
                }
                let b = self.math(base)?.at_least(3);
                let MathKind::Number(e) = &e.kind else {
                    return refuse(e.span, "an exponent that is not a number");
                };
                let e = if e.chars().all(|c| c.is_ascii_digit()) {
                    e.clone()
                } else {
                    format!("({e})")
                };
                Piece {
                    text: format!("{b}^{e}"),
                    prec: 2,
                }
            }
            MathKind::Sqrt(a) => Piece::atom(format!("sqrt({})", self.math(a)?.text)),
            MathKind::Average(a) if self.notation.macaulay => {
                Piece::atom(format!("max({}, 0)", self.math(a)?.text))
            }
            MathKind::Average(a) => Piece::atom(format!("avg({})", self.math(a)?.text)),
            MathKind::Abs(a) => Piece::atom(format!("abs({})", self.math(a)?.text)),
            MathKind::Apply(f, a) => {
                let name = match f.as_str() {
                    "ln" | "log" => "log",
                    "arctan" => "atan",
                    "arcsin" => "asin",
                    "arccos" => "acos",
                    other => other,
                };
                Piece::atom(format!("{name}({})", self.math(a)?.text))
            }
            MathKind::Partial { of, by } => self.partial(of, by)?,
            MathKind::Comma { of, indices } => {
                let Some(x) = self.decls.position.as_deref() else {
                    return refuse(
                        m.span,
                        "a comma derivative of a bracketed expression needs the position (`position = \"x\"`)",
                    );
                };
                Piece::atom(format!("d({})/d{x}_{indices}", self.math(of)?.text))
            }
            MathKind::Matrix(rows) => {
                let rows = rows
                    .iter()
                    .map(|r| {
                        let cells = r
                            .iter()
                            .map(|c| Ok(self.math(c)?.text))
                            .collect::<T<Vec<_>>>()?;
                        Ok(format!("[{}]", cells.join(", ")))
                    })
                    .collect::<T<Vec<_>>>()?;
                Piece::atom(format!("[{}]", rows.join(", ")))
            }
            MathKind::Tuple(items) => {
                let cells = items
                    .iter()
                    .map(|c| Ok(self.math(c)?.text))
                    .collect::<T<Vec<_>>>()?;
                Piece::atom(format!("[{}]", cells.join(", ")))
            }
        })
    }

    /// `∂F/∂x`: a derivative by a coordinate of the position (`d(F)/dx_2`), or by a
    /// declared tensor (`grad(F, sigma_ij)`).
    fn partial(&mut self, of: &Math, by: &Math) -> T<Piece> {
        let f = self.math(of)?.text;
        let x = self.math(by)?.text;
        let e = parse_expr(&x).map_err(|e| Unread {
            span: by.span,
            message: e.message,
        })?;
        match &e.kind {
            ExprKind::Name { base, indices, .. }
                if self.decls.position.as_deref() == Some(base.as_str()) && indices.len() == 1 =>
            {
                Ok(Piece::atom(format!("d({f})/d{x}")))
            }
            ExprKind::Name { .. } => Ok(Piece::atom(format!("grad({f}, {x})"))),
            _ => refuse(by.span, "a derivative by something that is not a symbol"),
        }
    }

    /// The notation entry for a printed symbol (or a power of one), if any.
    fn entry(&mut self, m: &Math) -> T<Option<Piece>> {
        for (k, entry) in self.notation.entries.iter().enumerate() {
            let Some(binding) = matches(&entry.pattern, &entry.vars, m) else {
                continue;
            };
            let value = if entry.values.len() > 1 {
                self.multi.insert(k);
                &entry.values[self.choice.get(&k).copied().unwrap_or(0)]
            } else {
                &entry.values[0]
            };
            let text = self.instantiate(value, &binding, m.span)?;
            let prec = match parse_expr(&text).map(|e| e.kind) {
                Ok(ExprKind::Add(..) | ExprKind::Sub(..) | ExprKind::Neg(..)) => 0,
                Ok(ExprKind::Mul(..) | ExprKind::Div(..)) => 1,
                Ok(ExprKind::Pow(..) | ExprKind::Call2(..)) => 2,
                _ => 3,
            };
            return Ok(Some(Piece { text, prec }));
        }
        Ok(None)
    }

    /// A reading with its pattern variables bound and its own summed letters renamed
    /// apart from the statement's.
    fn instantiate(&mut self, value: &str, binding: &BTreeMap<char, char>, at: Span) -> T<String> {
        let e = parse_expr(value).map_err(|e| Unread {
            span: at,
            message: e.message,
        })?;
        let mut toks = Vec::new();
        index_tokens(&e, &|full| self.is_scalar(full), &mut toks);
        toks.sort_by_key(|t| t.span.start);
        let mut own: BTreeMap<char, char> = BTreeMap::new();
        let mut out = String::new();
        let mut last = 0;
        for t in toks {
            let to = if let Some(&c) = binding.get(&t.ch) {
                c
            } else if t.ch.is_ascii_alphabetic() {
                match own.get(&t.ch) {
                    Some(&c) => c,
                    None => {
                        let Some(fresh) = ('a'..='z').find(|c| !self.taken.contains(c)) else {
                            return refuse(at, "no index letter is left to rename a summed index");
                        };
                        self.taken.insert(fresh);
                        own.insert(t.ch, fresh);
                        fresh
                    }
                }
            } else {
                t.ch
            };
            out.push_str(&value[last..t.span.start]);
            out.push(to);
            last = t.span.end;
        }
        out.push_str(&value[last..]);
        Ok(out)
    }

    fn symbol(&mut self, m: &Math, a: &Atom) -> T<Piece> {
        if let Some(p) = self.entry(m)? {
            return Ok(p);
        }
        let shown = |a: &Atom| {
            let mut s = String::new();
            if let Some(acc) = &a.accent {
                s.push_str(&format!("{acc}{{{}}}", a.base));
            } else {
                s.push_str(&a.base);
            }
            if let Some(sub) = &a.sub {
                s.push_str(&format!("_{{{}}}", sub.text));
            }
            if let Some(sup) = &a.sup {
                s.push_str(&format!("^{{{}}}", sup.text));
            }
            s.push_str(&"'".repeat(a.primes));
            s
        };
        if let Some(acc) = &a.accent {
            return refuse(
                m.span,
                format!(
                    "the accent `{acc}` of `{}` has no entry in the notation table",
                    shown(a)
                ),
            );
        }
        if let Some(sup) = &a.sup {
            return refuse(
                m.span,
                format!("the superscript `{}` of `{}` is a label, and the notation table has no entry for the symbol", sup.text, shown(a)),
            );
        }
        if a.primes > 0 {
            return refuse(
                m.span,
                format!(
                    "the prime of `{}` has no entry in the notation table",
                    shown(a)
                ),
            );
        }
        let name = a.base.trim_start_matches('\\');
        // The permutation symbol, e_{ijk} or \varepsilon_{ijk}, unless the file declares
        // a symbol of that name and rank.
        let slots = a.sub.as_ref().map_or(0, |s| s.text.chars().count());
        let permutation = slots == self.decls.dim
            && matches!(name, "varepsilon" | "epsilon" | "e")
            && self.decls.symbols.get(name) != Some(&slots)
            && !self
                .sigs
                .iter()
                .any(|s| s.name == name && s.formal.len() == slots);
        let name = if permutation { "eps" } else { name };
        let Some(sub) = &a.sub else {
            if self.is_scalar(name) {
                return Ok(Piece::atom(name.to_owned()));
            }
            return refuse(
                m.span,
                format!(
                    "`{}` is neither declared nor in the notation table",
                    shown(a)
                ),
            );
        };
        let joined = format!("{name}_{}", sub.text);
        if self.is_scalar(&joined) {
            return Ok(Piece::atom(joined));
        }
        let (indices, derivs) = match sub.text.split_once(',') {
            Some((i, d)) => (i, Some(d)),
            None => (sub.text.as_str(), None),
        };
        let slots_ok = |s: &str| !s.is_empty() && s.chars().all(|c| c.is_ascii_alphanumeric());
        // A scalar field's derivative has no index slots before the comma (`\phi_{,jk}`).
        let scalar_field = indices.is_empty()
            && derivs.is_some()
            && self.decls.fields.contains_key(name)
            && self.decls.symbols.get(name) == Some(&0);
        if !(slots_ok(indices) || scalar_field) || derivs.is_some_and(|d| !slots_ok(d)) {
            return refuse(
                sub.span,
                format!(
                    "the subscript `{}` is neither indices nor part of a declared name",
                    sub.text
                ),
            );
        }
        let known = matches!(name, "delta" | "eps")
            || scalar_field
            || self.decls.normal.as_deref() == Some(name)
            || self.decls.symbols.get(name).is_some_and(|&r| r > 0)
            || self
                .sigs
                .iter()
                .any(|s| s.name == name && !s.formal.is_empty());
        if !known {
            return refuse(
                m.span,
                format!(
                    "`{}` is neither declared nor in the notation table",
                    shown(a)
                ),
            );
        }
        Ok(Piece::atom(match derivs {
            Some(d) => format!("{name}_{indices},{d}"),
            None => joined,
        }))
    }

    fn is_scalar(&self, name: &str) -> bool {
        self.decls.symbols.get(name) == Some(&0)
            || self
                .sigs
                .iter()
                .any(|s| s.name == name && s.formal.is_empty())
            || name == "pi"
    }
}

/// Binds the pattern variables of `pattern` to the printed symbol `m`, if it matches.
fn matches(pattern: &Math, vars: &BTreeSet<char>, m: &Math) -> Option<BTreeMap<char, char>> {
    match (&pattern.kind, &m.kind) {
        (MathKind::Atom(p), MathKind::Atom(a)) => match_atom(p, vars, a),
        (MathKind::Power(pb, pe), MathKind::Power(b, e)) => match (&pe.kind, &e.kind) {
            (MathKind::Number(x), MathKind::Number(y)) if x == y => matches(pb, vars, b),
            _ => None,
        },
        _ => None,
    }
}

fn match_atom(p: &Atom, vars: &BTreeSet<char>, a: &Atom) -> Option<BTreeMap<char, char>> {
    if p.base != a.base
        || p.accent != a.accent
        || p.primes != a.primes
        || p.sup.as_ref().map(|s| &s.text) != a.sup.as_ref().map(|s| &s.text)
    {
        return None;
    }
    let mut binding = BTreeMap::new();
    match (&p.sub, &a.sub) {
        (None, None) => {}
        (Some(ps), Some(s)) if !is_slots(&ps.text) => {
            if ps.text != s.text {
                return None;
            }
        }
        (Some(ps), Some(s)) => {
            if ps.text.chars().count() != s.text.chars().count() {
                return None;
            }
            for (pc, c) in ps.text.chars().zip(s.text.chars()) {
                if vars.contains(&pc) {
                    if !(c.is_ascii_alphanumeric()) {
                        return None;
                    }
                    if *binding.entry(pc).or_insert(c) != c {
                        return None;
                    }
                } else if pc != c {
                    return None;
                }
            }
        }
        _ => return None,
    }
    Some(binding)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_read_backwards_names_a_variable_as_printed() {
        let mut t = Notation::default();
        let entries = [
            (r"\Gamma_{mi}^{(1)}", "G1_mi"),
            (r"w_{i,m}^c", "Dw_im"),
            (r"\bar\tau", "tb"),
            (r"P^{(n)}", "1/V f_i v21c_i"),
            (r"T^2", "avg(tt_k tt_k)"),
        ];
        for (k, v) in entries {
            t.add(k, vec![v.to_owned()]).unwrap();
        }
        assert_eq!(t.printed("G1_21").as_deref(), Some(r"\Gamma_{21}^{(1)}"));
        assert_eq!(t.printed("Dw_23").as_deref(), Some(r"w_{2,3}^c"));
        assert_eq!(t.printed("tb").as_deref(), Some(r"\bar\tau"));
        assert_eq!(t.printed_symbol("G1"), Some(r"\Gamma_{mi}^{(1)}"));
        assert_eq!(t.printed_symbol("tb"), Some(r"\bar\tau"));
        assert_eq!(t.printed_symbol("Dw"), Some(r"w_{i,m}^c"));
        for v in ["G1_mi", "tt", "P", "Dw_im"] {
            assert_eq!(t.printed_symbol(v), None, "{v}");
        }
        // Not a variable an entry names alone, or the wrong number of indices.
        for v in ["G1_2", "G1_213", "G1", "Dw_ab", "tt_1", "V", "P"] {
            assert_eq!(t.printed(v), None, "{v}");
        }
    }
}
