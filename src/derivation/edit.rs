//! A check's context applied to new text: the equation `left = right` between a
//! printed statement's reading and a side as written, re-checked by the same validator
//! as the claim. The original claim is never modified.

use super::model::{Check, Side};
use crate::lang::Node;
use crate::lang::{parse_expr, Decls, DefSig, LangError, Origin, Scope, SourceFile};

fn parse_checked(decls: &Decls, sigs: &[DefSig], text: &str) -> Result<(Node, Origin), LangError> {
    let origin = Origin::whole(SourceFile::new("<edited>", text));
    let e = parse_expr(text)?;
    let node = Scope { decls, defs: sigs }.check(&e)?;
    Ok((node, origin))
}

/// Why two texts could not be compared as the sides of one equation.
#[derive(Clone, Debug)]
pub enum Incomparable {
    /// The left text (the reading of a printed member) is ill-formed.
    Left(LangError),
    /// The right text (a side as written) is ill-formed.
    Right(LangError),
    /// The two carry different free indices.
    FreeIndices { left: Vec<char>, right: Vec<char> },
    /// A matrix against a scalar, or matrices of different shapes.
    Shape(String),
}

impl Check {
    /// The equation `left = right` in this check's context (its definitions and
    /// assumptions), decided by `strategy`: how a printed statement's reading is
    /// compared with a side as written. Matrices are compared entry by entry.
    pub fn comparing(
        &self,
        decls: &Decls,
        left: &str,
        right: &str,
        strategy: super::Strategy,
    ) -> Result<Check, Incomparable> {
        let sigs: Vec<DefSig> = self.defs.iter().map(|d| d.sig.clone()).collect();
        let (l, l_origin) = parse_checked(decls, &sigs, left).map_err(Incomparable::Left)?;
        let (r, r_origin) = parse_checked(decls, &sigs, right).map_err(Incomparable::Right)?;
        let l = if l.is_literal_zero() {
            l.zero_with_free(&r.free_letters())
        } else {
            l
        };
        if !l.matches_free_indices(&r) {
            return Err(Incomparable::FreeIndices {
                left: l.free_letters(),
                right: r.free_letters(),
            });
        }
        let side = |text: &str, origin: Origin, node: Node| Side {
            text: text.to_owned(),
            origin,
            node: Ok(node),
            entry: None,
        };
        let mut defs = self.defs.clone();
        let chains = super::load::entrywise(
            vec![vec![side(left, l_origin, l), side(right, r_origin, r)]],
            &mut defs,
        )
        .map_err(|d| Incomparable::Shape(d.message))?;
        Ok(Check {
            defs,
            assumptions: self.assumptions.clone(),
            chains,
            verbatim: false,
            // Two readings compared: whether they differ is the question, whatever a
            // draft guessed.
            drafted: None,
            strategy,
        })
    }
}
