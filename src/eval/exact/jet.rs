//! The values of the exact route's `grad`: a value at the state with its partial
//! derivatives by the components of one symbol per level (nested dual numbers over
//! exact quotients). The ring that computes with them is [`super::jets`].

use crate::algebra::Quotient;

/// A value with its partial derivatives, level by level.
#[derive(Clone, Debug)]
pub enum Jet {
    /// A value whose partials at every level are 0.
    Const(Quotient),
    /// A value and its partials by each component of the symbol of `level` (in the
    /// symbol's component order; missing ones are 0). The value and the partials are
    /// jets of lower levels only.
    Var {
        level: usize,
        value: Box<Jet>,
        partials: Vec<Jet>,
    },
}

impl Default for Jet {
    fn default() -> Self {
        Jet::Const(Quotient::default())
    }
}

impl Jet {
    pub(super) fn level(&self) -> Option<usize> {
        match self {
            Jet::Const(_) => None,
            Jet::Var { level, .. } => Some(*level),
        }
    }

    /// The value and partials of the given level (a jet of a lower level is a
    /// constant there: its partials are 0).
    pub(super) fn split(self, level: usize) -> (Jet, Vec<Jet>) {
        match self {
            Jet::Var {
                level: l,
                value,
                partials,
            } if l == level => (*value, partials),
            other => (other, Vec::new()),
        }
    }

    pub(super) fn is_zero(&self) -> bool {
        match self {
            Jet::Const(q) => q.is_exact_zero(),
            Jet::Var {
                value, partials, ..
            } => value.is_zero() && partials.iter().all(Jet::is_zero),
        }
    }

    /// The value at the state, all partials dropped.
    pub(super) fn state(&self) -> &Quotient {
        match self {
            Jet::Const(q) => q,
            Jet::Var { value, .. } => value.state(),
        }
    }

    /// Every quotient in the jet: its value and all its partials.
    pub(super) fn quotients<'j>(&'j self, out: &mut Vec<&'j Quotient>) {
        match self {
            Jet::Const(q) => out.push(q),
            Jet::Var {
                value, partials, ..
            } => {
                value.quotients(out);
                partials.iter().for_each(|p| p.quotients(out));
            }
        }
    }

    /// Each quotient mapped by `f`.
    pub(super) fn try_map<E>(
        &self,
        f: &mut impl FnMut(&Quotient) -> Result<Quotient, E>,
    ) -> Result<Jet, E> {
        Ok(match self {
            Jet::Const(q) => Jet::Const(f(q)?),
            Jet::Var {
                level,
                value,
                partials,
            } => Jet::Var {
                level: *level,
                value: Box::new(value.try_map(f)?),
                partials: partials
                    .iter()
                    .map(|p| p.try_map(f))
                    .collect::<Result<_, _>>()?,
            },
        })
    }

    /// Each quotient mapped by `f`, which cannot fail.
    pub(super) fn map(&self, mut f: impl FnMut(&Quotient) -> Quotient) -> Jet {
        match self.try_map(&mut |q| Ok::<_, std::convert::Infallible>(f(q))) {
            Ok(jet) => jet,
            Err(never) => match never {},
        }
    }
}
