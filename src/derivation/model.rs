//! The checked, in-memory form of derivation files: claims whose expressions have
//! already passed name resolution and index validation.

use crate::lang::{Decls, DefSig, LangError, Node, Origin, Span};
use serde::Serialize;
use std::fmt;
use std::sync::Arc;

/// A verdict, as in the guide's table.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Verdict {
    /// Proved (method `exact`) or verified on seeded samples (method `numeric`).
    Holds,
    /// A counterexample exists.
    Fails,
    /// Holds on a stated domain and fails outside it.
    Conditional,
}

impl Verdict {
    pub fn parse(s: &str) -> Option<Self> {
        match s {
            "holds" => Some(Verdict::Holds),
            "fails" => Some(Verdict::Fails),
            "conditional" => Some(Verdict::Conditional),
            _ => None,
        }
    }

    pub fn as_str(self) -> &'static str {
        match self {
            Verdict::Holds => "holds",
            Verdict::Fails => "fails",
            Verdict::Conditional => "conditional",
        }
    }
}

impl fmt::Display for Verdict {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// A named definition such as `t_i = sigma_ki n_k`.
#[derive(Clone, Debug)]
pub struct Definition {
    pub sig: DefSig,
    pub body: Node,
    pub origin: Origin,
    /// The definition as written.
    pub text: String,
}

/// A constraint on a declared symbol, applied before anything is evaluated.
#[derive(Clone, Debug)]
pub enum Assumption {
    /// The rank-2 symbol's trace vanishes: its last diagonal component is replaced by
    /// minus the others.
    Traceless { symbol: String },
    /// `X_ji = X_ij` for a rank-2 symbol.
    Symmetric { symbol: String },
    /// `X_ji = −X_ij` (and `X_ii = 0`) for a rank-2 symbol.
    Antisymmetric { symbol: String },
    /// One component of a symbol is fixed, e.g. `sigma_13 = 0` for plane problems.
    Component {
        symbol: String,
        /// 0-based component indices.
        index: Vec<usize>,
        body: Node,
        origin: Origin,
    },
    /// The symbol is replaced by an expression, e.g. `S = 3*V/(2*R_g)` for the paper's
    /// `2 R_g S = 3 V`.
    Equals {
        symbol: String,
        formal: Vec<char>,
        body: Node,
        origin: Origin,
    },
}

/// One side of an equation chain.
#[derive(Clone, Debug)]
pub struct Side {
    /// The side as written in the derivation file.
    pub text: String,
    pub origin: Origin,
    /// The checked expression; an index error is kept (not raised) only for a
    /// printed statement transcribed verbatim, where it is a finding about the paper.
    pub node: Result<Node, LangError>,
}

impl Side {
    /// The whole side's span in its own text.
    pub fn span(&self) -> Span {
        Span::new(0, self.text.len())
    }
}

/// Everything needed to decide one statement: definitions, assumptions and one or
/// more chains `a = b = c` whose consecutive members must be equal.
#[derive(Clone, Debug)]
pub struct Check {
    pub defs: Vec<Definition>,
    pub assumptions: Vec<Assumption>,
    pub chains: Vec<Vec<Side>>,
    /// The sides transcribe a printed statement index for index, so ill-formed
    /// indices are a verdict rather than an input error.
    pub verbatim: bool,
}

/// A corrected statement that the paper evidently intended.
#[derive(Clone, Debug)]
pub struct Correction {
    pub statement: String,
    pub reason: String,
    pub expect: Verdict,
    pub check: Check,
}

/// One checkable statement of the paper.
#[derive(Clone, Debug)]
pub struct Claim {
    pub id: String,
    pub section: String,
    /// The statement as printed (LaTeX, verbatim, typos included).
    pub statement: String,
    /// The statement is a sentence of the paper's prose rather than a formula.
    pub prose: bool,
    pub expect: Verdict,
    /// Why the expected verdict is not `holds` (required then).
    pub reason: Option<String>,
    /// Conventions, readings and second routes behind the verdict.
    pub note: Option<String>,
    /// The file's declarations (dimension, normal, symbols).
    pub decls: Arc<Decls>,
    pub check: Check,
    pub correction: Option<Correction>,
}

/// A whole derivation file, checked.
#[derive(Clone, Debug)]
pub struct DerivationFile {
    pub path: String,
    pub section: String,
    pub title: String,
    pub claims: Vec<Claim>,
}
