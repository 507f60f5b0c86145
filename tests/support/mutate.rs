//! Mutants of an expression's text: the evidence that a strategy refutes wrong
//! statements. Each mutant is one small, typical slip — a changed coefficient, two
//! indices swapped, a flipped sign, a dropped term — made on the source text through
//! the parser's spans, so it goes through exactly the same reader and checker as the
//! original.

use crate::derivation::{Check, Side};
use crate::lang::parser::{Expr, ExprKind, Func, Func2, IndexTok, MatFunc, Wrt};
use crate::lang::{
    parse_expr, Decls, DefSig, ErrorKind, LangError, Node, Origin, Scope, SourceFile,
};
use std::fmt;

/// The kind of slip a mutant makes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum MutantKind {
    /// A numeric constant q becomes q + 1, or a term (or a whole side) is doubled.
    Coefficient,
    /// Two index letters of one name trade places (`sigma_ki` → `sigma_ik`).
    SwapIndices,
    /// One term of a sum (or the whole expression) changes sign.
    FlipSign,
    /// One term of a sum is replaced by zero (kept as `0 (term)` so the indices
    /// still line up and the mutant is well-formed).
    DropTerm,
    /// A function is replaced by a neighbour: sqrt, abs, avg and maxn by the identity,
    /// cos ↔ sin, tan → sin; for matrices inv ↔ adj, det → trace, and a transpose
    /// dropped.
    Function,
}

impl fmt::Display for MutantKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            MutantKind::Coefficient => "changed coefficient",
            MutantKind::SwapIndices => "swapped indices",
            MutantKind::FlipSign => "flipped sign",
            MutantKind::DropTerm => "dropped term",
            MutantKind::Function => "replaced function",
        })
    }
}

/// One mutant of a text.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Mutant {
    pub kind: MutantKind,
    pub text: String,
    /// What changed, e.g. "`sigma_ki` → `sigma_ik`".
    pub what: String,
}

/// Every mutant of `src` (none when it does not parse). Swaps inside `delta` are not
/// generated: δ is symmetric, so they are equivalent mutants by construction.
pub fn mutants(src: &str) -> Vec<Mutant> {
    let Ok(e) = parse_expr(src) else {
        return Vec::new();
    };
    let mut edits = Vec::new();
    collect(src, &e, &mut edits);
    edits.push((
        MutantKind::FlipSign,
        0..src.len(),
        format!("-({})", src.trim()),
    ));
    edits.push((
        MutantKind::Coefficient,
        0..src.len(),
        format!("2 ({})", src.trim()),
    ));
    let mut out: Vec<Mutant> = edits
        .into_iter()
        .map(|(kind, range, replacement)| {
            let mut text = src.to_owned();
            let before = src[range.clone()].trim().to_owned();
            text.replace_range(range, &replacement);
            Mutant {
                kind,
                what: format!("`{before}` → `{}`", replacement.trim()),
                text,
            }
        })
        .collect();
    out.sort_by(|a, b| a.kind.cmp(&b.kind).then(a.text.cmp(&b.text)));
    out.dedup_by(|a, b| a.text == b.text);
    out
}

type Edit = (MutantKind, std::ops::Range<usize>, String);

fn collect(src: &str, e: &Expr, out: &mut Vec<Edit>) {
    let range = e.span.start..e.span.end;
    match &e.kind {
        ExprKind::Number(q) => {
            let bumped = q + &1i64.into();
            out.push((MutantKind::Coefficient, range, format!("({bumped})")));
        }
        ExprKind::Name { base, indices, .. } => {
            if base == "delta" {
                return;
            }
            swaps(src, indices, out);
        }
        ExprKind::Deriv { inner, indices, .. } => {
            // `sigma_ij,j` → `sigma_ji,j`, `sigma_ij,i`: the field's indices and the
            // derivative's trade places as one list.
            match &inner.kind {
                ExprKind::Name { indices: own, .. } => {
                    let all: Vec<IndexTok> = own.iter().chain(indices).copied().collect();
                    swaps(src, &all, out);
                }
                _ => {
                    swaps(src, indices, out);
                    collect(src, inner, out);
                }
            }
        }
        ExprKind::Add(..) | ExprKind::Sub(..) => {
            let mut terms = Vec::new();
            flatten(e, &mut terms);
            for t in &terms {
                let r = t.span.start..t.span.end;
                let text = &src[r.clone()];
                out.push((MutantKind::FlipSign, r.clone(), format!("(-({text}))")));
                out.push((MutantKind::DropTerm, r.clone(), format!("0 ({text})")));
                out.push((MutantKind::Coefficient, r, format!("2 ({text})")));
            }
            for t in terms {
                collect_inner(src, t, out);
            }
        }
        _ => collect_inner(src, e, out),
    }
}

/// Recurses into the children of a node that is not itself a sum.
fn collect_inner(src: &str, e: &Expr, out: &mut Vec<Edit>) {
    match &e.kind {
        ExprKind::Number(_)
        | ExprKind::Name { .. }
        | ExprKind::Add(..)
        | ExprKind::Sub(..)
        | ExprKind::Deriv { .. } => collect(src, e, out),
        ExprKind::Call(func, a) => {
            let name = func.name();
            let at = e.span.start..e.span.start + name.len();
            let neighbours: &[&str] = match func {
                Func::Sqrt | Func::Abs | Func::Avg | Func::MaxN => &[""],
                Func::Cos => &["sin"],
                Func::Sin => &["cos"],
                Func::Tan => &["sin"],
                Func::Exp => &["log", ""],
                Func::Log => &["exp", ""],
                Func::Atan => &["tan", ""],
                Func::Asin => &["acos"],
                Func::Acos => &["asin"],
            };
            for n in neighbours {
                out.push((MutantKind::Function, at.clone(), (*n).to_owned()));
            }
            collect(src, a, out);
        }
        ExprKind::Call2(func, a, b) => {
            // min ↔ max; atan2's arguments are mutated as any operands.
            let name = func.name();
            let at = e.span.start..e.span.start + name.len();
            match func {
                Func2::Min => out.push((MutantKind::Function, at, "max".to_owned())),
                Func2::Max => out.push((MutantKind::Function, at, "min".to_owned())),
                Func2::Atan2 | Func2::Pow => {}
            }
            collect(src, a, out);
            collect(src, b, out);
        }
        ExprKind::Neg(a) | ExprKind::Pow(a, _) => collect(src, a, out),
        // The varied field is named, not computed: only the density is mutated. The
        // symbol of a gradient has its letters swapped too, `grad(F, sigma_ji)`: the
        // transposed gradient.
        ExprKind::Wrt { op, body, symbol } => {
            if let (Wrt::Grad, ExprKind::Name { indices, .. }) = (op, &symbol.kind) {
                swaps(src, indices, out);
            }
            collect(src, body, out)
        }
        ExprKind::Mul(a, b) | ExprKind::Div(a, b) => {
            collect(src, a, out);
            collect(src, b, out);
        }
        // Two different neighbouring entries of a row (or a column vector) trade places.
        ExprKind::Matrix(rows) => {
            let lines: Vec<Vec<&Expr>> = if rows.iter().all(|r| r.len() == 1) {
                vec![rows.iter().map(|r| &r[0]).collect()]
            } else {
                rows.iter().map(|r| r.iter().collect()).collect()
            };
            for line in &lines {
                for pair in line.windows(2) {
                    let (x, y) = (pair[0], pair[1]);
                    let (tx, ty) = (
                        &src[x.span.start..x.span.end],
                        &src[y.span.start..y.span.end],
                    );
                    if tx != ty {
                        let middle = &src[x.span.end..y.span.start];
                        out.push((
                            MutantKind::SwapIndices,
                            x.span.start..y.span.end,
                            format!("{ty}{middle}{tx}"),
                        ));
                    }
                }
            }
            for entry in rows.iter().flatten() {
                collect(src, entry, out);
            }
        }
        ExprKind::Entry(inner, at) => {
            if let [(i, si), (j, sj)] = at[..] {
                if i != j {
                    out.push((
                        MutantKind::SwapIndices,
                        si.start..sj.end,
                        format!("{j},{i}"),
                    ));
                }
            }
            collect(src, inner, out);
        }
        ExprKind::MatCall(func, args) => {
            let name = func.name();
            let at = e.span.start..e.span.start + name.len();
            let written_as_call = src[e.span.start..].starts_with(name);
            match func {
                MatFunc::Inv if written_as_call => {
                    out.push((MutantKind::Function, at, "adj".to_owned()))
                }
                MatFunc::Adj if written_as_call => {
                    out.push((MutantKind::Function, at, "inv".to_owned()))
                }
                MatFunc::Det if written_as_call => {
                    out.push((MutantKind::Function, at, "trace".to_owned()))
                }
                MatFunc::Transpose => {
                    let inner = &args[0];
                    let text = &src[inner.span.start..inner.span.end];
                    let range = e.span.start..e.span.end;
                    out.push((MutantKind::Function, range, format!("({text})")));
                }
                _ => {}
            }
            for a in args {
                collect(src, a, out);
            }
        }
    }
}

/// Every swap of two different index letters of one list: the text from the first to
/// the second, with its two ends exchanged (what lies between, a comma included, stays).
fn swaps(src: &str, indices: &[IndexTok], out: &mut Vec<Edit>) {
    for a in 0..indices.len() {
        for b in a + 1..indices.len() {
            let (x, y) = (indices[a], indices[b]);
            if x.ch == y.ch {
                continue;
            }
            let (lo, hi) = (x.span.start, y.span.end);
            let middle = &src[x.span.end..y.span.start];
            out.push((
                MutantKind::SwapIndices,
                lo..hi,
                format!("{}{middle}{}", y.ch, x.ch),
            ));
        }
    }
}

fn flatten<'e>(e: &'e Expr, out: &mut Vec<&'e Expr>) {
    match &e.kind {
        ExprKind::Add(a, b) | ExprKind::Sub(a, b) => {
            flatten(a, out);
            flatten(b, out);
        }
        _ => out.push(e),
    }
}

/// Edited copies of a checked statement, the mutants' carriers: one side or one
/// definition body replaced by new text, re-checked by the same validator as the
/// original. The original claim is never modified.
pub trait Edited: Sized {
    /// A copy with side `side` of chain `chain` replaced by `text`. The new side must
    /// be well-formed and keep the free indices of the side it replaces (unless one of
    /// them is the literal 0).
    fn with_side(
        &self,
        decls: &Decls,
        chain: usize,
        side: usize,
        text: &str,
    ) -> Result<Self, LangError>;
}

/// `text` read and checked in the context of `decls` and the definitions `sigs`.
pub fn parse_checked(
    decls: &Decls,
    sigs: &[DefSig],
    text: &str,
) -> Result<(Node, Origin), LangError> {
    let origin = Origin::whole(SourceFile::new("<edited>", text));
    let e = parse_expr(text)?;
    let node = Scope { decls, defs: sigs }.check(&e)?;
    Ok((node, origin))
}

impl Edited for Check {
    fn with_side(
        &self,
        decls: &Decls,
        chain: usize,
        side: usize,
        text: &str,
    ) -> Result<Check, LangError> {
        let sigs: Vec<DefSig> = self.defs.iter().map(|d| d.sig.clone()).collect();
        let (node, origin) = parse_checked(decls, &sigs, text)?;
        let old = &self.chains[chain][side];
        if let Ok(old_node) = &old.node {
            if old_node.shape() != node.shape()
                || (!self.verbatim && !old_node.matches_free_indices(&node))
            {
                return Err(LangError::new(
                    ErrorKind::Index,
                    node.span,
                    "free indices changed",
                ));
            }
        }
        let mut out = self.clone();
        out.chains[chain][side] = Side {
            text: text.to_owned(),
            origin,
            node: Ok(node),
            entry: old.entry,
        };
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_kind_is_generated() {
        let ms = mutants("1/3 delta_ij - sigma_ki n_k");
        let texts: Vec<&str> = ms.iter().map(|m| m.text.as_str()).collect();
        assert!(
            texts.contains(&"(2)/3 delta_ij - sigma_ki n_k"),
            "{texts:?}"
        );
        assert!(texts.contains(&"1/3 delta_ij - sigma_ik n_k"), "{texts:?}");
        assert!(
            texts.contains(&"1/3 delta_ij - 0 (sigma_ki n_k)"),
            "{texts:?}"
        );
        assert!(
            texts.contains(&"(-(1/3 delta_ij)) - sigma_ki n_k"),
            "{texts:?}"
        );
        assert!(!texts.iter().any(|t| t.contains("delta_ji")));
    }

    #[test]
    fn functions_are_replaced_by_neighbours() {
        let ms = mutants("sqrt(x) + cos(y)");
        let texts: Vec<&str> = ms
            .iter()
            .filter(|m| m.kind == MutantKind::Function)
            .map(|m| m.text.as_str())
            .collect();
        assert_eq!(texts, vec!["(x) + cos(y)", "sqrt(x) + sin(y)"]);
    }

    #[test]
    fn matrix_slips_are_generated() {
        let texts =
            |src: &str| -> Vec<String> { mutants(src).into_iter().map(|m| m.text).collect() };
        let t = texts("[[a, b], [c, d]]");
        assert!(t.contains(&"[[b, a], [c, d]]".to_owned()), "{t:?}");
        assert!(t.contains(&"[[a, b], [d, c]]".to_owned()), "{t:?}");
        let t = texts("inv(A) q^T + A[1,2]");
        assert!(t.contains(&"adj(A) q^T + A[1,2]".to_owned()), "{t:?}");
        assert!(t.contains(&"inv(A) (q) + A[1,2]".to_owned()), "{t:?}");
        assert!(t.contains(&"inv(A) q^T + A[2,1]".to_owned()), "{t:?}");
        assert!(texts("det(A)").contains(&"trace(A)".to_owned()));
    }
}
