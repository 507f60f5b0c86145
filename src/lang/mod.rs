//! The index-notation language of the derivation files: lexer and parser
//! ([`parser`]), name resolution and index validation ([`check`]), and diagnostics
//! that point at file, line and column ([`diag`]); the matrix language is typed in
//! [`matrix`]. The reader of the printed LaTeX of statements is [`latex`].

// The kernel and the algebra under their names in the checker, so that paths read the
// same on every side.
use cosserat_algebra as algebra;
use cosserat_kernel as kernel;

pub mod check;
pub mod diag;
pub mod latex;
pub mod matrix;
pub mod parser;
pub mod rename;

pub use check::{Decls, DefSig, Node, NodeKind, Scope, Slot, Target};
pub use diag::{Diagnostic, Origin, SourceFile, Span};
pub use parser::{parse_expr, ErrorKind, Expr, LangError};
