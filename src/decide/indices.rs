//! The exact strategy's route through symbolic indices: both sides of each equality are
//! read into the (untrusted) index algebra ([`crate::algebra::indexed`]) and reduced to
//! canonical forms. Equal forms prove the equality for every value of the free indices
//! without expanding a component; anything else (a construct outside the algebra,
//! the term budget, forms that differ) proves nothing, and the component route decides.
//!
//! The algebra covers rational constants, declared symbols with index slots, δ, ε,
//! the unit normal and its average `avg`, sums, products, constant divisors, integer
//! powers of scalars and index definitions (inlined, their summed letters renamed
//! apart). A fixed component (`sigma_13`), a function, a derivative, `maxn`, a matrix
//! or a normal confined to a plane is outside it.

use crate::algebra::certificate::Certificate;
use crate::algebra::einsum::Slot;
use crate::algebra::indexed::{
    first_difference, Algebra, Canonical, Factor, Label, Properties, Sum,
};
use crate::derivation::{AssumptionKind, Check, Definition, Side};
use crate::kernel::Rational;
use crate::lang::check::{Decls, Target};
use crate::lang::{Node, NodeKind};
use std::collections::BTreeMap;

/// Summed letters get labels from here up; a free letter's label is its code point.
const FIRST_SUMMED: Label = 1 << 24;

/// Deepest nesting of definitions followed.
const MAX_DEPTH: usize = 64;

/// Highest power of a scalar that is multiplied out.
const MAX_POWER: u32 = 32;

/// What the symbolic route found.
pub enum Symbolic {
    /// Every equality proved.
    // What the symbolic route found; its own tests read it (the kernel re-checks the
    // identity component by component).
    #[cfg_attr(not(test), allow(dead_code))]
    Proved(Certificate),
    /// The first equality whose sides differ, made only of δ's and ε's: the first
    /// index values where they differ (in the component route's order) and both values.
    Differs(Difference),
    /// Nothing decided: the component route decides.
    Open,
}

/// A constant difference between two sides, found by evaluating their canonical forms.
pub struct Difference {
    /// 0-based chain and equality (between sides `equality` and `equality + 1`).
    pub chain: usize,
    pub equality: usize,
    /// The index values, 0-based, by letter.
    pub at: Vec<(char, usize)>,
    pub lhs: Rational,
    pub rhs: Rational,
    /// Components the component route would have compared up to this one, included.
    pub components: usize,
}

/// Decides every equality of `check` by canonical forms in symbolic indices, as far as
/// it can. Without `read_eps`, a side with ε leaves it open: below a few hundred
/// components, contracting ε pairs in the algebra costs more than the component route.
pub fn decide(decls: &Decls, check: &Check, read_eps: bool) -> Symbolic {
    // A polynomial constraint or a differential hypothesis has no form in symbolic
    // indices; hypotheses on derived quantities restrict where a counterexample may lie.
    let constrained = check.constrained();
    if decls.normal_in_plane || constrained {
        return Symbolic::Open;
    }
    let mut reader = Reader::new(decls, check, read_eps);
    let mut certificate: Option<Certificate> = None;
    let mut components = 0usize;
    for (ci, chain) in check.chains.iter().enumerate() {
        let Some((forms, letters)) = reader.chain(chain) else {
            return Symbolic::Open;
        };
        let labels: Vec<Label> = letters.iter().map(|&c| c as Label).collect();
        let free: String = letters.iter().collect();
        let per_pair = decls.dim.saturating_pow(letters.len() as u32);
        for (k, pair) in forms.windows(2).enumerate() {
            if let Some(c) =
                Certificate::index_identity(&pair[0], &pair[1], (&free, &labels), decls.dim)
            {
                certificate = Some(match certificate {
                    None => c,
                    Some(acc) => acc.and(c),
                });
                components = components.saturating_add(per_pair);
                continue;
            }
            return match first_difference(&pair[0], &pair[1], &labels, decls.dim) {
                Some(Some((ordinal, x, lhs, rhs))) => Symbolic::Differs(Difference {
                    chain: ci,
                    equality: k,
                    at: letters.iter().copied().zip(x).collect(),
                    lhs,
                    rhs,
                    components: components.saturating_add(ordinal + 1),
                }),
                _ => Symbolic::Open,
            };
        }
    }
    certificate.map_or(Symbolic::Open, Symbolic::Proved)
}

impl Reader<'_> {
    /// The canonical forms of a chain's sides and their free letters (sorted), or
    /// `None` when a side is outside the algebra or the sides' letters differ.
    fn chain(&mut self, chain: &[Side]) -> Option<(Vec<Canonical>, Vec<char>)> {
        let mut forms: Vec<Canonical> = Vec::with_capacity(chain.len());
        let mut free: Option<Vec<char>> = None;
        for side in chain {
            let node = side.node.as_ref().ok()?;
            if side.entry.is_some() {
                return None;
            }
            if !node.is_literal_zero() {
                let letters = node.free_letters();
                if free.get_or_insert_with(|| letters.clone()) != &letters {
                    return None;
                }
            }
            let map: Vec<(char, Label)> = node.free.iter().map(|&(c, _)| (c, c as Label)).collect();
            let sum = self.sum(node, &map, 0)?;
            forms.push(self.algebra.canonical(sum).ok()?);
        }
        Some((forms, free.unwrap_or_default()))
    }
}

/// Reads checked nodes into the index algebra.
struct Reader<'a> {
    decls: &'a Decls,
    defs: &'a [Definition],
    algebra: Algebra,
    /// Symbol numbers, shared by every side so that their forms compare.
    ids: BTreeMap<String, u32>,
    next: Label,
    /// Whether ε is read (else a side with ε is outside the algebra).
    read_eps: bool,
}

impl<'a> Reader<'a> {
    fn new(decls: &'a Decls, check: &'a Check, read_eps: bool) -> Self {
        let mut ids = BTreeMap::new();
        let mut props = Properties::default();
        if let Some(n) = &decls.normal {
            props.normal = Some(intern(&mut ids, n));
        }
        for a in &check.assumptions {
            let Some(symbol) = a.kind.symbol() else {
                continue;
            };
            if decls.symbols.get(symbol) != Some(&2) {
                continue;
            }
            let id = intern(&mut ids, symbol);
            match a.kind {
                AssumptionKind::Symmetric { .. } => props.symmetric.insert(id),
                AssumptionKind::Antisymmetric { .. } => props.antisymmetric.insert(id),
                AssumptionKind::Traceless { .. } => props.traceless.insert(id),
                _ => false,
            };
        }
        Reader {
            decls,
            defs: &check.defs,
            algebra: Algebra::new(decls.dim, props),
            ids,
            next: FIRST_SUMMED,
            read_eps,
        }
    }

    fn fresh(&mut self) -> Label {
        self.next += 1;
        self.next
    }

    /// `node` as a sum, its free letters labelled by `map`.
    fn sum(&mut self, node: &Node, map: &[(char, Label)], depth: usize) -> Option<Sum> {
        if depth > MAX_DEPTH {
            return None;
        }
        Some(match &node.kind {
            NodeKind::Const(q) => {
                if !node.free.is_empty() && !q.is_zero() {
                    return None;
                }
                Sum::constant(q.clone())
            }
            NodeKind::Leaf { target, slots } => {
                // A letter repeated within the leaf (sigma_kk) is summed here.
                let mut local: Vec<(char, Label)> = Vec::new();
                let mut labels = Vec::with_capacity(slots.len());
                for s in slots {
                    let Slot::Letter(c) = *s else { return None };
                    let label = match lookup(map, c).or_else(|| lookup(&local, c)) {
                        Some(l) => l,
                        None => {
                            let l = self.fresh();
                            local.push((c, l));
                            l
                        }
                    };
                    labels.push(label);
                }
                match target {
                    Target::Delta => match labels[..] {
                        [a, b] => Sum::factor(Factor::Delta(a, b)),
                        _ => return None,
                    },
                    Target::Eps if self.read_eps => Sum::factor(Factor::Eps(labels)),
                    Target::Eps => return None,
                    Target::Normal => {
                        let id = intern(&mut self.ids, self.decls.normal.as_deref()?);
                        Sum::factor(Factor::Symbol { id, slots: labels })
                    }
                    Target::Symbol(s) => {
                        let id = intern(&mut self.ids, s);
                        Sum::factor(Factor::Symbol { id, slots: labels })
                    }
                    Target::Def(name) => {
                        let def = self.defs.iter().find(|d| &d.sig.name == name)?;
                        if def.sig.shape.is_some() || def.sig.formal.len() != labels.len() {
                            return None;
                        }
                        let inner: Vec<(char, Label)> =
                            def.sig.formal.iter().copied().zip(labels).collect();
                        let body = &def.body;
                        self.sum(body, &inner, depth + 1)?
                    }
                    Target::Pi => return None,
                }
            }
            NodeKind::Sum(terms) => {
                let mut acc = Sum::default();
                for t in terms {
                    acc = acc.plus(self.sum(t, map, depth + 1)?);
                }
                acc
            }
            NodeKind::Product(factors) => {
                // Letters free in two factors are summed by this product.
                let mut inner: Vec<(char, Label)> = map.to_vec();
                let mut seen: Vec<char> = Vec::new();
                for f in factors {
                    for &(c, _) in &f.free {
                        if seen.contains(&c) {
                            if lookup(&inner[map.len()..], c).is_none() {
                                let l = self.fresh();
                                inner.push((c, l));
                            }
                        } else {
                            seen.push(c);
                        }
                    }
                }
                let mut acc = Sum::constant(Rational::int(1));
                for f in factors {
                    let s = self.sum(f, &inner, depth + 1)?;
                    acc = self.algebra.product(&acc, &s).ok()?;
                }
                acc
            }
            NodeKind::Div(a, b) => {
                let divisor = self.sum(b, map, depth + 1)?.as_constant()?;
                let inverse = divisor.recip()?;
                self.sum(a, map, depth + 1)?.scale(&inverse)
            }
            NodeKind::Neg(a) => self.sum(a, map, depth + 1)?.scale(&Rational::int(-1)),
            NodeKind::Pow(a, k) => {
                if *k > MAX_POWER || !a.free.is_empty() {
                    return None;
                }
                let mut acc = Sum::constant(Rational::int(1));
                // Each copy is read again, so its summed letters get their own labels.
                for _ in 0..*k {
                    let s = self.sum(a, map, depth + 1)?;
                    acc = self.algebra.product(&acc, &s).ok()?;
                }
                acc
            }
            NodeKind::Avg(a) => {
                let s = self.sum(a, map, depth + 1)?;
                self.algebra.average(s).ok()?
            }
            _ => return None,
        })
    }
}

fn lookup(map: &[(char, Label)], c: char) -> Option<Label> {
    map.iter().rev().find(|&&(d, _)| d == c).map(|&(_, l)| l)
}

fn intern(ids: &mut BTreeMap<String, u32>, name: &str) -> u32 {
    let next = ids.len() as u32;
    *ids.entry(name.to_owned()).or_insert(next)
}
