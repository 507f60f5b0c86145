//! What a statement reads: the definitions it depends on (mutation testing edits
//! them) and the symbols whose values decide it (a counterexample shows those, and
//! only those).

use super::model::{AssumptionKind, Check, Definition};
use crate::lang::parser::Wrt;
use crate::lang::{Decls, Node, NodeKind, Target};
use std::collections::BTreeSet;

/// Every node reachable from `roots`, through the bodies of the definitions (in
/// `defs`, the innermost of a name) they use, directly or through other definitions;
/// and the names of those definitions.
pub fn reachable<'a>(
    roots: Vec<&'a Node>,
    defs: &'a [Definition],
) -> (Vec<&'a Node>, BTreeSet<&'a str>) {
    let mut names = BTreeSet::new();
    let mut stack = roots;
    let mut seen = Vec::new();
    while let Some(n) = stack.pop() {
        seen.push(n);
        if let Some(name) = n.definition() {
            if names.insert(name) {
                if let Some(d) = defs.iter().rev().find(|d| d.sig.name == name) {
                    stack.push(&d.body);
                }
            }
        }
        stack.extend(n.children());
    }
    (seen, names)
}

/// What an expression varies with besides the state's symbols.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Varies {
    Normal,
    /// A field or the position.
    Position,
}

/// What makes `node` vary outside `avg` and `maxn`, through the definitions it reads
/// (in `defs`, the innermost of a name): the normal (when it varies with both), or a
/// field or the position.
pub fn varies_with(node: &Node, defs: &[Definition], decls: &Decls) -> Option<Varies> {
    fn walk<'a>(
        node: &'a Node,
        defs: &'a [Definition],
        decls: &Decls,
        seen: &mut BTreeSet<&'a str>,
    ) -> Option<Varies> {
        match &node.kind {
            NodeKind::Avg(_) | NodeKind::MaxN(_) => return None,
            NodeKind::Leaf {
                target: Target::Normal,
                ..
            } => return Some(Varies::Normal),
            NodeKind::Leaf {
                target: Target::Symbol(s),
                ..
            } if decls.varies(s) => return Some(Varies::Position),
            _ => {}
        }
        let mut found = None;
        if let Some(name) = node.definition() {
            if seen.insert(name) {
                if let Some(d) = defs.iter().rev().find(|d| d.sig.name == name) {
                    found = walk(&d.body, defs, decls, seen);
                }
            }
        }
        for c in node.children() {
            if found == Some(Varies::Normal) {
                break;
            }
            found = walk(c, defs, decls, seen).or(found);
        }
        found
    }
    walk(node, defs, decls, &mut BTreeSet::new())
}

/// Whether `node` differentiates by the position (`phi_,kk`, `d(…)/dx_i`), through
/// the definitions it reads (in `defs`, the innermost of a name).
pub fn differentiates_fields(node: &Node, defs: &[Definition]) -> bool {
    reachable(vec![node], defs)
        .0
        .iter()
        .any(|n| matches!(n.kind, NodeKind::Deriv(..)))
}

/// The highest order of derivative by the position that `node` takes of anything,
/// through the definitions it reads (`d(d(phi psi)/dx_k)/dx_k` is 2).
fn derivative_order(node: &Node, defs: &[Definition]) -> usize {
    fn walk<'a>(
        node: &'a Node,
        defs: &'a [Definition],
        known: &mut std::collections::BTreeMap<&'a str, usize>,
    ) -> usize {
        let own = match &node.kind {
            NodeKind::Deriv(inner, _) => return 1 + walk(inner, defs, known),
            _ => node.definition().map_or(0, |name| {
                if let Some(&k) = known.get(name) {
                    return k;
                }
                // A name is read before its value is known only through a cycle, which
                // the loader refuses; 0 stops the walk there.
                known.insert(name, 0);
                let k = defs
                    .iter()
                    .rev()
                    .find(|d| d.sig.name == name)
                    .map_or(0, |d| walk(&d.body, defs, known));
                known.insert(name, k);
                k
            }),
        };
        node.children()
            .into_iter()
            .map(|c| walk(c, defs, known))
            .fold(own, usize::max)
    }
    walk(node, defs, &mut std::collections::BTreeMap::new())
}

/// The symbols a statement reads, and whether it reads the normal.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Reads {
    pub symbols: BTreeSet<String>,
    pub normal: bool,
    /// Whether it differentiates with respect to the position.
    pub differentiates: bool,
}

impl Check {
    /// Every node the statement evaluates: its sides, its strategy's expressions
    /// (function, closed forms, hypotheses, domain, singular set) and the bodies of
    /// the definitions they use, directly or through other definitions. The second
    /// value names those definitions.
    pub(crate) fn reachable(&self) -> (Vec<&Node>, BTreeSet<&str>) {
        let mut roots: Vec<&Node> = self
            .chains
            .iter()
            .flatten()
            .filter_map(|s| s.node.as_ref().ok())
            .collect();
        roots.extend(self.strategy.expressions().into_iter().map(|e| &e.node));
        reachable(roots, &self.defs)
    }

    /// The highest order of derivative by the position its sides take.
    pub(crate) fn derivative_order(&self) -> usize {
        self.chains
            .iter()
            .flatten()
            .filter_map(|s| s.node.as_ref().ok())
            .map(|n| derivative_order(n, &self.defs))
            .max()
            .unwrap_or(0)
    }

    /// The names of the definitions the statement depends on: those its expressions
    /// and its assumptions read, directly or through other definitions.
    pub fn definitions_read(&self) -> BTreeSet<&str> {
        let roots: Vec<&Node> = self
            .assumptions
            .iter()
            .flat_map(|a| a.kind.bodies())
            .collect();
        let (_, mut names) = self.reachable();
        names.extend(reachable(roots, &self.defs).1);
        names
    }

    /// Indices (into `defs`) of the definitions the statement depends on (see
    /// [`Check::definitions_read`]), in definition order.
    pub fn dependencies(&self) -> Vec<usize> {
        let names = self.definitions_read();
        (0..self.defs.len())
            .filter(|&k| names.contains(self.defs[k].sig.name.as_str()))
            .collect()
    }

    /// The symbols whose values decide the statement: those it reads, and those the
    /// assumptions compute them from (`S = 3 V / (2 R_g)` makes `V` and `R_g` read
    /// when `S` is), and whether it reads the normal.
    pub fn reads(&self) -> Reads {
        let (nodes, _) = self.reachable();
        let mut out = Reads::default();
        for n in &nodes {
            match &n.kind {
                NodeKind::Leaf {
                    target: Target::Symbol(s),
                    ..
                } => {
                    out.symbols.insert(s.clone());
                }
                NodeKind::Leaf {
                    target: Target::Normal,
                    ..
                } => out.normal = true,
                NodeKind::Deriv(..)
                | NodeKind::Wrt {
                    op: Wrt::Variation, ..
                } => out.differentiates = true,
                _ => {}
            }
        }
        // Assumptions tie symbols together; follow them to a fixed point.
        loop {
            let before = out.symbols.len();
            for a in &self.assumptions {
                // A constraint ties every symbol it reads to every other.
                let tied = match (&a.kind, a.kind.symbol()) {
                    (AssumptionKind::Component { .. } | AssumptionKind::Equals { .. }, Some(s)) => {
                        out.symbols.contains(s)
                    }
                    (
                        AssumptionKind::Constraint { .. } | AssumptionKind::Differential { .. },
                        _,
                    ) => a.reads.iter().any(|s| out.symbols.contains(s)),
                    _ => false,
                };
                if tied {
                    out.symbols.extend(a.reads.iter().cloned());
                }
            }
            if out.symbols.len() == before {
                return out;
            }
        }
    }
}
