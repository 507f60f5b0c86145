//! The statements the kernel checks: expressions in index notation and the context
//! that gives their symbols meaning, as plain data that a report keeps and `recheck`
//! reads back.
//!
//! A [`Term`] is index notation after names are resolved: constants, declared
//! symbols, definitions, δ, ε and the normal with their index slots, sums, products (a
//! letter twice in a product is summed), quotients, powers, square roots, averages
//! over the normal, derivatives along the position, `grad` and `variation`. There are
//! no matrices: the reader of a file writes a matrix out in definitions of its
//! entries, and the statement records them. The kernel computes which letters are free itself
//! ([`Term::letters`]) and refuses an ill-formed term; nothing the reader of the file
//! computed about indices is believed.

use super::rational::Rational;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// One index slot: a letter (free or summed) or a fixed component, 0-based (written
/// `"i"` or `0` in a report).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Slot {
    Letter(char),
    Fixed(usize),
}

/// What a leaf names.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Leaf {
    /// A declared symbol (tensor, scalar, field or the position).
    Symbol(String),
    /// A definition of the statement.
    Def(String),
    Delta,
    Eps,
    /// The unit normal.
    Normal,
}

/// An expression. Its order is structural: it sorts the parts of a canonical form
/// ([`super::symmetry::canonical`]).
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Term {
    /// A constant in every component of the free letters `free` (the literal 0 of a
    /// tensor equation has some; every other constant none).
    Const {
        value: Rational,
        free: Vec<char>,
    },
    Leaf {
        of: Leaf,
        slots: Vec<Slot>,
    },
    Sum(Vec<Term>),
    Product(Vec<Term>),
    Neg(Box<Term>),
    Div(Box<Term>, Box<Term>),
    Pow(Box<Term>, u32),
    Sqrt(Box<Term>),
    Avg(Box<Term>),
    /// ∂/∂x along the slot's coordinate.
    Deriv(Box<Term>, Slot),
    /// ∂body/∂symbol for every component of the symbol, at the state.
    Grad {
        body: Box<Term>,
        symbol: String,
        slots: Vec<Slot>,
    },
    /// The variational derivative of a density with respect to every component of a
    /// field.
    Variation {
        body: Box<Term>,
        field: String,
        slots: Vec<Slot>,
    },
    /// A construct the kernel does not evaluate (a transcendental function, π, a
    /// maximum over orientations), with its free letters: a statement that reads it
    /// cannot be proved.
    Opaque {
        what: String,
        free: Vec<char>,
    },
}

/// The free letters of a term (sorted) and the letters summed inside it.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Letters {
    pub free: Vec<char>,
    pub summed: Vec<char>,
}

/// The most letters one term may carry, free and summed (a hostile term cannot make
/// the kernel visit more index values than a product of 12 letters in 3D).
pub const MAX_LETTERS: usize = 12;

/// What the kernel knows of the symbols: their ranks, and the dimension.
pub trait Ranks {
    fn dim(&self) -> usize;
    /// The rank of a declared symbol, `None` if undeclared.
    fn symbol_rank(&self, name: &str) -> Option<usize>;
    /// The formal letters' count of a definition, `None` for an unknown one.
    fn def_rank(&self, name: &str) -> Option<usize>;
}

/// Letters once free, twice summed; a third occurrence, or a letter summed inside one
/// part and used again in another, is ill-formed.
fn tally(parts: &[Letters], extra: &[char]) -> Result<Letters, EvalError> {
    let mut seen: BTreeMap<char, usize> = BTreeMap::new();
    for c in parts.iter().flat_map(|p| &p.free).chain(extra) {
        *seen.entry(*c).or_default() += 1;
    }
    let mut out = Letters::default();
    for (&c, &n) in &seen {
        match n {
            1 => out.free.push(c),
            2 => out.summed.push(c),
            n => {
                return Err(EvalError::IllFormed(format!(
                    "index `{c}` occurs {n} times in one product"
                )))
            }
        }
    }
    // The contraction here visits every value of these letters (those summed inside
    // a factor are that factor's own).
    if out.free.len() + out.summed.len() > MAX_LETTERS {
        return Err(EvalError::Limit);
    }
    for (k, p) in parts.iter().enumerate() {
        for c in &p.summed {
            // Summed inside two factors is two separate sums; free in another factor
            // is ambiguous, and refused as the language refuses it.
            let again = parts
                .iter()
                .enumerate()
                .any(|(j, q)| j != k && q.free.contains(c))
                || extra.contains(c);
            if again {
                return Err(EvalError::IllFormed(format!(
                    "index `{c}` is summed inside one factor and used again in another"
                )));
            }
        }
        out.summed.extend(&p.summed);
    }
    Ok(out)
}

fn slot_letters(slots: &[Slot], dim: usize) -> Result<Vec<char>, EvalError> {
    let mut out = Vec::new();
    for s in slots {
        match s {
            Slot::Letter(c) => out.push(*c),
            Slot::Fixed(k) if *k >= dim => {
                return Err(EvalError::IllFormed(format!(
                    "fixed index {} is out of range 1..{dim}",
                    k + 1
                )))
            }
            Slot::Fixed(_) => {}
        }
    }
    Ok(out)
}

fn scalar(t: &Term, r: &dyn Ranks, what: &str) -> Result<Letters, EvalError> {
    let l = t.letters(r)?;
    if !l.free.is_empty() {
        return Err(EvalError::IllFormed(format!("{what} must be a scalar")));
    }
    Ok(l)
}

impl Term {
    pub fn int(n: i64) -> Term {
        Term::Const {
            value: Rational::int(n),
            free: Vec::new(),
        }
    }

    /// The term's free letters (sorted) and summed ones, or why it is ill-formed: an
    /// index three times in a product, terms of a sum with different free indices, a
    /// slot count that is not the rank, a fixed index out of range, a non-scalar where
    /// a scalar belongs.
    pub fn letters(&self, r: &dyn Ranks) -> Result<Letters, EvalError> {
        let dim = r.dim();
        Ok(match self {
            Term::Const { free, .. } | Term::Opaque { free, .. } => {
                let mut f = free.clone();
                f.sort_unstable();
                f.dedup();
                Letters {
                    free: f,
                    summed: Vec::new(),
                }
            }
            Term::Leaf { of, slots } => {
                let rank = match of {
                    Leaf::Symbol(s) => r.symbol_rank(s).ok_or_else(|| {
                        EvalError::IllFormed(format!("`{s}` is not a declared symbol"))
                    })?,
                    Leaf::Def(d) => r.def_rank(d).ok_or_else(|| {
                        EvalError::IllFormed(format!("`{d}` is not a definition of the statement"))
                    })?,
                    Leaf::Delta => 2,
                    Leaf::Eps => dim,
                    Leaf::Normal => 1,
                };
                if slots.len() != rank {
                    return Err(EvalError::IllFormed(format!(
                        "{} indices where the rank is {rank}",
                        slots.len()
                    )));
                }
                let own = Letters {
                    free: slot_letters(slots, dim)?,
                    summed: Vec::new(),
                };
                tally(&[own], &[])?
            }
            Term::Sum(terms) => {
                let first = terms
                    .first()
                    .ok_or_else(|| EvalError::IllFormed("an empty sum".to_owned()))?
                    .letters(r)?;
                let mut summed = first.summed.clone();
                for t in &terms[1..] {
                    let l = t.letters(r)?;
                    if l.free != first.free {
                        return Err(EvalError::IllFormed(format!(
                            "terms of a sum have different free indices: {:?} and {:?}",
                            first.free, l.free
                        )));
                    }
                    summed.extend(l.summed);
                }
                Letters {
                    free: first.free,
                    summed,
                }
            }
            Term::Product(fs) => {
                let parts = fs
                    .iter()
                    .map(|f| f.letters(r))
                    .collect::<Result<Vec<_>, _>>()?;
                tally(&parts, &[])?
            }
            Term::Neg(a) | Term::Avg(a) => a.letters(r)?,
            Term::Div(a, b) => {
                let mut l = a.letters(r)?;
                l.summed.extend(scalar(b, r, "a divisor")?.summed);
                l
            }
            Term::Pow(a, _) => scalar(a, r, "the base of a power")?,
            Term::Sqrt(a) => scalar(a, r, "the argument of sqrt")?,
            Term::Deriv(a, s) => {
                let inner = a.letters(r)?;
                tally(&[inner], &slot_letters(std::slice::from_ref(s), dim)?)?
            }
            Term::Grad {
                body,
                symbol: name,
                slots,
            }
            | Term::Variation {
                body,
                field: name,
                slots,
            } => {
                let rank = r.symbol_rank(name).ok_or_else(|| {
                    EvalError::IllFormed(format!("`{name}` is not a declared symbol"))
                })?;
                if slots.len() != rank {
                    return Err(EvalError::IllFormed(format!(
                        "{} indices where the rank is {rank}",
                        slots.len()
                    )));
                }
                let inner = body.letters(r)?;
                tally(&[inner], &slot_letters(slots, dim)?)?
            }
        })
    }
}

impl Term {
    /// The term at fixed values of some of its free letters: each free occurrence of a
    /// letter of `at` becomes a fixed slot (a constant's free letter is dropped). A
    /// letter summed inside a subterm belongs to that subterm, and stays.
    pub fn at_indices(&self, at: &[(char, usize)], r: &dyn Ranks) -> Result<Term, EvalError> {
        let mut t = self.clone();
        t.fix_letters(at, r)?;
        Ok(t)
    }

    fn fix_letters(&mut self, at: &[(char, usize)], r: &dyn Ranks) -> Result<(), EvalError> {
        let free = self.letters(r)?.free;
        let here: Vec<(char, usize)> = at
            .iter()
            .copied()
            .filter(|(c, _)| free.contains(c))
            .collect();
        let fix = |s: &mut Slot| {
            if let Some(&(_, v)) = here.iter().find(|(c, _)| *s == Slot::Letter(*c)) {
                *s = Slot::Fixed(v);
            }
        };
        match self {
            _ if here.is_empty() => {}
            Term::Const { free, .. } | Term::Opaque { free, .. } => {
                free.retain(|c| !here.iter().any(|(d, _)| d == c))
            }
            Term::Leaf { slots, .. } => slots.iter_mut().for_each(fix),
            Term::Sum(ts) | Term::Product(ts) => {
                for t in ts {
                    t.fix_letters(&here, r)?;
                }
            }
            // A divisor, a base and a radicand are scalars: no free letter.
            Term::Neg(a) | Term::Avg(a) | Term::Div(a, _) => a.fix_letters(&here, r)?,
            Term::Pow(..) | Term::Sqrt(_) => {}
            Term::Deriv(a, s) => {
                fix(s);
                a.fix_letters(&here, r)?;
            }
            Term::Grad { body, slots, .. } | Term::Variation { body, slots, .. } => {
                slots.iter_mut().for_each(fix);
                body.fix_letters(&here, r)?;
            }
        }
        Ok(())
    }
}

/// Why the kernel has no value for a term.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum EvalError {
    #[error("ill-formed: {0}")]
    IllFormed(String),
    #[error("not evaluable exactly: {0}")]
    Unsupported(String),
    #[error("division by zero")]
    DivisionByZero,
    #[error("the kernel's work or size bound")]
    Limit,
}

impl From<super::frac::FracError> for EvalError {
    fn from(e: super::frac::FracError) -> Self {
        match e {
            super::frac::FracError::DivisionByZero => EvalError::DivisionByZero,
            super::frac::FracError::TooLarge => EvalError::Limit,
        }
    }
}

/// The variable name of a component: `sigma_12`, or the symbol's own name for a scalar.
pub fn component_name(symbol: &str, idx: &[usize]) -> String {
    if idx.is_empty() {
        return symbol.to_owned();
    }
    let digits: String = idx.iter().map(|i| (i + 1).to_string()).collect();
    format!("{symbol}_{digits}")
}

/// The direct subterms of a term.
pub fn children(t: &Term) -> Vec<&Term> {
    match t {
        Term::Const { .. } | Term::Leaf { .. } | Term::Opaque { .. } => Vec::new(),
        Term::Sum(ts) | Term::Product(ts) => ts.iter().collect(),
        Term::Neg(a) | Term::Pow(a, _) | Term::Sqrt(a) | Term::Avg(a) | Term::Deriv(a, _) => {
            vec![a]
        }
        Term::Div(a, b) => vec![a, b],
        Term::Grad { body, .. } | Term::Variation { body, .. } => vec![body],
    }
}
