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

/// `maxn(…)` where its argument carries derivatives: by the envelope theorem a first
/// derivative at the maximising angle is right only to the angle's accuracy (about
/// 1e-8), and a second derivative misses the angle's own motion, so none is taken.
pub(crate) fn maxn_not_differentiated(span: Span) -> RealError {
    RealError {
        span,
        message:
            "maxn(…) is not differentiated: its maximising angle moves with what is differentiated"
                .into(),
        pointwise: false,
    }
}
