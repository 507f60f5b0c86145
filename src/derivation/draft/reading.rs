//! What the draft reads of each numbered equation, and the definitions it takes other
//! than alone on an equation's left: the types its readings share (the equations, a
//! definition the text states, a labelled variant or an analogy), and the reading of a
//! defined symbol.

use super::symbols::{self, Key, Stems, Symbol};
use crate::lang::latex::{self, MathKind};
use std::collections::{BTreeMap, BTreeSet};

/// One numbered equation on its way into the file.
pub(super) struct Equation {
    pub(super) id: String,
    pub(super) number: String,
    pub(super) line: usize,
    pub(super) latex: String,
    /// Why it is not a claim, if it is not.
    pub(super) unread: Option<String>,
    /// The one edit that would let it be read, where the reason says one.
    pub(super) edit: Option<String>,
    /// Decided by sampling (its exact decision asked for it).
    pub(super) numeric: bool,
    /// The sentence of the text that leads into it (`displays::lead_in`), and the one
    /// that follows it (`displays::lead_out`: "where n is the unit normal").
    pub(super) lead_in: String,
    /// All the text since the numbered display before it (headings included).
    pub(super) before: String,
    pub(super) lead_out: String,
    /// The symbols it reads (identities).
    pub(super) reads: BTreeSet<Key>,
    /// Their names in the file.
    pub(super) names: BTreeSet<String>,
    /// The symbols it defines: (identity, index letters, the definition's text).
    pub(super) defines: Vec<(Key, String)>,
    /// The printed symbols it reads with a stray subscript (`t_{i}^{(n)}`).
    pub(super) stray: BTreeSet<String>,
    /// Its members carry different free indices as printed: it is checked as printed,
    /// for every value of each (`verbatim`).
    pub(super) verbatim: bool,
    /// The names of the declared symbols it is the first to write (`introduces`).
    pub(super) introduces: BTreeSet<String>,
    /// The symbols it reads inside a bracket a comma differentiates (`(\sigma_{ij}
    /// v_j)_{,i}`).
    pub(super) differentiated: BTreeSet<Key>,
    /// The fields the text linearises that it reads, through definitions, with the
    /// number of the equation the sentence that says so leads into
    /// (`linearised_fields`).
    pub(super) linear: (Vec<Key>, String),
}

/// A labelled symbol that no equation defines, read where its unlabelled symbol is
/// defined linearly (`K_{mi}^{(1)}` beside `K_{ij} = w_{j,i}`), and whose every
/// symbol of that definition the paper also writes with the same label (`w_i^{(1)}`).
pub(super) struct Variant {
    pub(super) key: Key,
    /// The unlabelled symbol, whose definition it takes.
    pub(super) of: Key,
    /// How it takes that definition, for the file's comment ("with the label (1)").
    pub(super) how: String,
    /// Each symbol of that definition, with its labelled variant.
    pub(super) renamed: Vec<(Key, Key)>,
}

/// Whether a superscript is no label of place or order: one that may be an operation (a
/// transpose or an inverse, `A^{-T}`, `A^{T}`, a sign or a conjugate), or one the paper
/// also writes on the normal (`n_i^{(1)}`: each labelled world has its own normal, which
/// a definition reading δ, ε and n does not rename).
pub(super) fn no_label(symbols: &BTreeMap<Key, Symbol>, normal: Option<&str>, label: &str) -> bool {
    let operation =
        label.contains(['-', '+', '*', '\\']) || matches!(label.trim(), "T" | "t" | "H");
    operation
        || symbols.keys().any(|k| {
            let f: Vec<&str> = k.split('|').collect();
            f.len() == 6 && Some(f[1]) == normal && f[2] == label
        })
}

/// The symbol a chain's first member defines, if it is one symbol (or the square of
/// one without a label, which becomes a symbol of its own, `T^2` → `T2`): its identity,
/// and the new symbol of a square. `symbol` is the chain's first symbol as read in the
/// whole chain (whose letters decide what is an index).
pub(super) fn defined_symbol(
    first: &latex::Math,
    symbol: Option<&(Key, Symbol)>,
    tensors: &Stems,
) -> Option<(Key, Option<Symbol>)> {
    let (key, s) = symbol?;
    // A component (`\sigma_{21} = \tau`), a trace (`s_{kk} = 0`) or a derivative
    // (`u_{i,j} = …`) defines no symbol.
    let letters: BTreeSet<&char> = s.key.1.iter().collect();
    let part = s.key.1.iter().any(char::is_ascii_digit) || letters.len() < s.key.1.len();
    if s.field || (s.rank > 0 && part) {
        return None;
    }
    // The chain's first symbol must be the first member's own (a constant such as π is
    // no symbol, and the first symbol is then a later member's).
    let own = symbols::occurrences(&[first], None, tensors);
    if own.first().map(|(_, o)| &o.key.0) != Some(&s.key.0) {
        return None;
    }
    match &first.kind {
        MathKind::Atom(_) => Some((key.clone(), None)),
        MathKind::Power(base, exponent)
            if matches!(&exponent.kind, MathKind::Number(n) if n == "2")
                && matches!(&base.kind, MathKind::Atom(a) if a.sup.is_none()) =>
        {
            let (printed, letters) = s.key.clone();
            let square = Symbol {
                name: format!("{}2", s.name.split('_').next().unwrap_or(&s.name)),
                rank: s.rank,
                field: false,
                order: 0,
                key: (format!("{printed}^2"), letters),
                entry: true,
                component: false,
                squared: false,
                doubt: None,
                derivatives: BTreeSet::new(),
                stray: false,
                printed: BTreeSet::new(),
                differentiated: false,
            };
            Some((format!("{key}^2"), Some(square)))
        }
        _ => None,
    }
}

/// A definition stated other than alone on the left of a numbered equation.
pub(super) struct Stated {
    /// The text's line, for one a sentence states; `None` for a decomposition that a
    /// numbered equation states.
    pub(super) line: Option<usize>,
    /// The definition as LaTeX, `X = …`.
    pub(super) latex: String,
    /// A decomposition's left side, which it defines instead of being defined by it.
    pub(super) instead_of: Option<Key>,
    /// Stated by a law the paper posits, solved for its source term (`posited_laws`).
    pub(super) law: bool,
}
