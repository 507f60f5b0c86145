//! An evaluation error of the real route, located in the expression's text.

use crate::lang::{Node, Span};

/// An evaluation error located in the expression's text.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{message}")]
pub struct RealError {
    pub span: Span,
    pub message: String,
    /// The expression has no value at this state only (a divisor zero, a function
    /// outside its domain, a derivative that does not exist): a sampled claim steps off
    /// such a state. Otherwise the expression cannot be evaluated at all.
    pub pointwise: bool,
}

pub(super) fn err(node: &Node, message: impl Into<String>) -> RealError {
    RealError {
        span: node.span,
        message: message.into(),
        pointwise: false,
    }
}

/// The expression at `node` has no value at this state (see [`RealError::pointwise`]).
pub(crate) fn undefined(span: Span, message: impl Into<String>) -> RealError {
    RealError {
        span,
        message: message.into(),
        pointwise: true,
    }
}
