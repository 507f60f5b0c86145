//! Canonical forms in symbolic indices: sums of products of δ, ε, declared tensors and
//! the unit normal, with the free indices left as letters and every value of them
//! covered at once.
//!
//! The component route ([`super::einsum`]) proves an identity of rank r by comparing
//! d^r components, each a polynomial: 6,561 at rank 8 in 3D, 59,049 at rank 10. Here
//! each side is reduced once, whatever its rank, the way FORM's `dd_` and Cadabra's
//! canonicalisation work:
//!
//! - an isotropic moment becomes its δ pairings (eq. (26) and its higher-rank
//!   analogues): ⟨n_{a1} … n_{a2k}⟩ = Σ_pairings Π δ / (d (d+2) … (d+2k−2)), and 0 at
//!   odd order;
//! - δ is contracted (δ_ab X_b = X_a, δ_aa = d), a pair of ε becomes the determinant
//!   of δ's, and n_a n_a = 1 for the unit normal;
//! - a term vanishes when it is antisymmetric in a pair of summed indices that the rest
//!   of the term is symmetric in (ε_ijk n_j n_k), when an antisymmetric tensor or ε
//!   repeats an index, or when a traceless tensor is traced;
//! - the summed indices are renamed canonically and the factors sorted.
//!
//! Every rewrite is an identity of tensors, true for every value of the indices, so two
//! sides with the same canonical form are equal in every component: that is what
//! [`Canonical`] certifies. The converse does not hold, and nothing is concluded from
//! different forms: δ products are linearly dependent once the rank exceeds 2d (the
//! 105 pairings of rank 8 span a smaller space in 3D), a declared tensor may obey
//! relations the assumptions state but this form does not use, and the renaming of
//! summed indices is canonical only among at most [`MAX_ORDERINGS`] orderings of equal
//! factors. The caller then compares components.

use crate::kernel::Rational;
use num_traits::{One, Zero};
use std::collections::{BTreeMap, BTreeSet};

/// An index label. The caller numbers free indices and summed ones as it likes, below
/// [`FIRST_CANONICAL`]; the canonical form renames summed indices from there on.
pub type Label = u32;

/// The first label of a canonically renamed summed index.
pub const FIRST_CANONICAL: Label = 1 << 31;

/// The orderings of equal-shaped factors tried for a canonical naming of the summed
/// indices; beyond it one ordering is used (a form that may miss an equality).
pub const MAX_ORDERINGS: usize = 720;

/// How many terms a reduction may produce in all before it gives up.
pub const TERM_BUDGET: usize = 400_000;

/// How many term evaluations [`first_difference`] may make.
pub const EVALUATION_BUDGET: usize = 20_000_000;

/// One factor of a term.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Factor {
    /// δ_ab.
    Delta(Label, Label),
    /// ε_{a…} with d slots.
    Eps(Vec<Label>),
    /// A declared symbol (a scalar when `slots` is empty) or the unit normal, by the
    /// caller's number for it.
    Symbol { id: u32, slots: Vec<Label> },
}

impl Factor {
    /// The slots of ε or a symbol (δ has two labels, not a slice).
    fn slots(&self) -> &[Label] {
        match self {
            Factor::Delta(..) => &[],
            Factor::Eps(s) | Factor::Symbol { slots: s, .. } => s,
        }
    }
}

/// One term: a rational coefficient times a product of factors.
#[derive(Clone, Debug, PartialEq)]
pub struct Term {
    pub coeff: Rational,
    pub factors: Vec<Factor>,
}

/// A sum of terms. Within a term every label occurs once (a free index) or twice (a
/// summed one); the caller keeps summed labels of different factors apart.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Sum {
    pub terms: Vec<Term>,
}

impl Sum {
    /// The constant `q`.
    pub fn constant(q: Rational) -> Sum {
        let terms = if q.is_zero() {
            Vec::new()
        } else {
            vec![Term {
                coeff: q,
                factors: Vec::new(),
            }]
        };
        Sum { terms }
    }

    /// One factor with coefficient 1.
    pub fn factor(f: Factor) -> Sum {
        Sum {
            terms: vec![Term {
                coeff: Rational::one(),
                factors: vec![f],
            }],
        }
    }

    /// `q · self`.
    pub fn scale(mut self, q: &Rational) -> Sum {
        if q.is_zero() {
            return Sum::default();
        }
        for t in &mut self.terms {
            t.coeff = &t.coeff * q;
        }
        self
    }

    /// `self + other`.
    pub fn plus(mut self, other: Sum) -> Sum {
        self.terms.extend(other.terms);
        self
    }

    /// The value when every term is a constant (no factor), e.g. a divisor.
    pub fn as_constant(&self) -> Option<Rational> {
        self.terms.iter().try_fold(Rational::zero(), |acc, t| {
            t.factors.is_empty().then(|| &acc + &t.coeff)
        })
    }
}

/// Why a reduction gave up. Neither says anything about the statement.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Refused {
    /// More than [`TERM_BUDGET`] terms.
    TooLarge,
    /// A label occurs more than twice in a term, or ε has the wrong number of slots.
    Malformed,
}

/// What the reduction knows about the declared symbols.
#[derive(Clone, Debug, Default)]
pub struct Properties {
    /// The unit normal's number: n_a n_a = 1, and [`Algebra::average`] averages it.
    pub normal: Option<u32>,
    /// Rank-2 symbols with X_ab = X_ba.
    pub symmetric: BTreeSet<u32>,
    /// Rank-2 symbols with X_ab = −X_ba.
    pub antisymmetric: BTreeSet<u32>,
    /// Rank-2 symbols with X_aa = 0.
    pub traceless: BTreeSet<u32>,
}

/// The reduction in dimension `dim`, with a budget of terms.
pub struct Algebra {
    dim: usize,
    props: Properties,
    spent: usize,
    /// Whether the current reduction used n_a n_a = 1.
    unit_normal: bool,
}

/// A reduced sum in canonical form: two are equal exactly when their terms are, and
/// then the sums they came from are equal for every value of the free indices. Only
/// [`Algebra::canonical`] makes one.
#[derive(Clone, Debug)]
pub struct Canonical {
    terms: BTreeMap<Vec<Factor>, Rational>,
    /// Whether n_a n_a = 1 was used outside an average.
    unit_normal: bool,
}

/// Two forms are equal when their terms are, however they were reached.
impl PartialEq for Canonical {
    fn eq(&self, other: &Self) -> bool {
        self.terms == other.terms
    }
}

impl Eq for Canonical {}

impl Canonical {
    /// How many distinct terms the form has.
    pub fn len(&self) -> usize {
        self.terms.len()
    }

    pub fn is_empty(&self) -> bool {
        self.terms.is_empty()
    }

    /// Whether the reduction used n_a n_a = 1 (outside an average).
    pub fn used_unit_normal(&self) -> bool {
        self.unit_normal
    }

    /// The terms, in canonical order.
    pub fn terms(&self) -> impl Iterator<Item = (&[Factor], &Rational)> {
        self.terms.iter().map(|(f, c)| (f.as_slice(), c))
    }
}

/// A term made only of δ's and ε's over free labels, with each slot's position in the
/// list of free labels: its value at index values is a product of 0s and ±1s.
type ConstantTerm = (Vec<(bool, Vec<usize>)>, Rational);

/// One term as a constant term, or `None` when it has a symbol or a summed index (its
/// value is not a number).
fn constant_term(factors: &[Factor], c: Rational, labels: &[Label]) -> Option<ConstantTerm> {
    let position = |l: &Label| labels.iter().position(|m| m == l);
    let mut slots = Vec::with_capacity(factors.len());
    for f in factors {
        slots.push(match f {
            Factor::Delta(x, y) => (false, vec![position(x)?, position(y)?]),
            Factor::Eps(s) => (true, s.iter().map(position).collect::<Option<_>>()?),
            Factor::Symbol { .. } => return None,
        });
    }
    Some((slots, c))
}

/// Every term of `form` as a constant term, or `None`.
fn constant_terms(form: &Canonical, labels: &[Label]) -> Option<Vec<ConstantTerm>> {
    form.terms
        .iter()
        .map(|(f, c)| constant_term(f, c.clone(), labels))
        .collect()
}

/// `a − b` as constant terms, or `None` when a term of the difference is not constant.
fn constant_difference(
    a: &Canonical,
    b: &Canonical,
    labels: &[Label],
) -> Option<Vec<ConstantTerm>> {
    let mut out = Vec::new();
    for (f, c) in &a.terms {
        let d = match b.terms.get(f) {
            Some(e) => c - e,
            None => c.clone(),
        };
        if !d.is_zero() {
            out.push(constant_term(f, d, labels)?);
        }
    }
    for (f, c) in &b.terms {
        if !a.terms.contains_key(f) {
            out.push(constant_term(f, -c, labels)?);
        }
    }
    Some(out)
}

/// The value of constant terms at the index values `x` (by position).
fn constant_value(terms: &[ConstantTerm], x: &[usize]) -> Rational {
    let mut value = Rational::zero();
    'terms: for (factors, c) in terms {
        let mut sign = 1i8;
        for (eps, slots) in factors {
            if *eps {
                let v: Vec<usize> = slots.iter().map(|&k| x[k]).collect();
                sign *= super::tensor::permutation_sign(&v);
            } else if x[slots[0]] != x[slots[1]] {
                sign = 0;
            }
            if sign == 0 {
                continue 'terms;
            }
        }
        value = if sign > 0 { &value + c } else { &value - c };
    }
    value
}

/// Where two canonical forms made only of δ and ε differ: the first index values (in
/// the lexicographic order of [`super::assignments`] over `labels`) where their values
/// differ, with both values. `Some(None)`: they agree at every index value (δ products
/// are linearly dependent at high rank, so different forms can be equal tensors).
/// `None`: a term has a symbol or a summed index.
/// The first of `Some(Some(…))` is the ordinal of the index values in that order.
/// Beyond [`EVALUATION_BUDGET`] term evaluations: `None`.
#[allow(clippy::type_complexity)]
pub fn first_difference(
    a: &Canonical,
    b: &Canonical,
    labels: &[Label],
    dim: usize,
) -> Option<Option<(usize, Vec<usize>, Rational, Rational)>> {
    let difference = constant_difference(a, b, labels)?;
    // Charged as the values are visited: a difference at the first index values (a
    // wrong constant) is found at once, whatever the rank.
    let mut spent = 0usize;
    for (ordinal, x) in super::tensor::assignments(dim, labels.len()).enumerate() {
        spent = spent.saturating_add(difference.len().max(1));
        if spent > EVALUATION_BUDGET {
            return None;
        }
        if !constant_value(&difference, &x).is_zero() {
            // Terms the forms share may still have symbols: then the sides' values are
            // not numbers, and nothing is returned.
            let (l, r) = (constant_terms(a, labels)?, constant_terms(b, labels)?);
            return Some(Some((
                ordinal,
                x.clone(),
                constant_value(&l, &x),
                constant_value(&r, &x),
            )));
        }
    }
    Some(None)
}

impl Algebra {
    pub fn new(dim: usize, props: Properties) -> Self {
        Algebra {
            dim,
            props,
            spent: 0,
            unit_normal: false,
        }
    }

    fn spend(&mut self, terms: usize) -> Result<(), Refused> {
        self.spent += terms;
        if self.spent > TERM_BUDGET {
            Err(Refused::TooLarge)
        } else {
            Ok(())
        }
    }

    /// `a · b`, term by term. The caller keeps the summed labels of `a` and `b` apart.
    pub fn product(&mut self, a: &Sum, b: &Sum) -> Result<Sum, Refused> {
        self.spend(a.terms.len() * b.terms.len())?;
        let mut terms = Vec::with_capacity(a.terms.len() * b.terms.len());
        for x in &a.terms {
            for y in &b.terms {
                let mut factors = Vec::with_capacity(x.factors.len() + y.factors.len());
                factors.extend(x.factors.iter().cloned());
                factors.extend(y.factors.iter().cloned());
                terms.push(Term {
                    coeff: &x.coeff * &y.coeff,
                    factors,
                });
            }
        }
        Ok(Sum { terms })
    }

    /// The average over the unit normal n uniform on the unit sphere: in each term the
    /// normal's factors n_{a1} … n_{am} become 0 for odd m, else
    /// Σ_pairings Π δ / (d (d+2) … (d+m−2)) (the isotropic moments, eqs. (25)–(26), as
    /// `moments.rs` derives them). Terms without n are unchanged.
    pub fn average(&mut self, s: Sum) -> Result<Sum, Refused> {
        let Some(normal) = self.props.normal else {
            return Ok(s);
        };
        let mut out = Vec::new();
        for t in s.terms {
            let (ns, rest): (Vec<Factor>, Vec<Factor>) = t
                .factors
                .into_iter()
                .partition(|f| matches!(f, Factor::Symbol { id, .. } if *id == normal));
            let mut labels = Vec::with_capacity(ns.len());
            for f in &ns {
                match f.slots() {
                    [a] => labels.push(*a),
                    _ => return Err(Refused::Malformed),
                }
            }
            if labels.len() % 2 == 1 {
                continue;
            }
            let m = labels.len() as i64;
            let denom = (0..m / 2).fold(Rational::one(), |acc, j| {
                &acc * &Rational::int(self.dim as i64 + 2 * j)
            });
            let coeff = t
                .coeff
                .checked_div(&denom)
                .expect("a product of positive integers is nonzero");
            let count = pairing_count(labels.len());
            self.spend(count)?;
            for_each_pairing(&labels, &mut Vec::new(), &mut |pairs| {
                let mut factors = rest.clone();
                factors.extend(pairs.iter().map(|&(a, b)| Factor::Delta(a, b)));
                out.push(Term {
                    coeff: coeff.clone(),
                    factors,
                });
            });
        }
        Ok(Sum { terms: out })
    }

    /// The canonical form of `s`: every term reduced, its summed indices renamed, equal
    /// terms collected.
    pub fn canonical(&mut self, s: Sum) -> Result<Canonical, Refused> {
        let mut terms: BTreeMap<Vec<Factor>, Rational> = BTreeMap::new();
        self.unit_normal = false;
        let mut work = s.terms;
        while let Some(t) = work.pop() {
            let Some(t) = self.reduce(t, &mut work)? else {
                continue;
            };
            // The orderings tried count against the budget like terms.
            let (named, tried) = self.canonical_term(&t.factors);
            self.spend(tried)?;
            let Some((factors, sign)) = named else {
                continue;
            };
            let c = if sign < 0 { -&t.coeff } else { t.coeff };
            let entry = terms.entry(factors).or_insert_with(Rational::zero);
            *entry = &*entry + &c;
        }
        terms.retain(|_, c| !c.is_zero());
        Ok(Canonical {
            terms,
            unit_normal: self.unit_normal,
        })
    }

    /// Applies the rewrites to one term until none applies. `None`: the term is 0.
    /// A pair of ε splits the term: the pieces go to `work` and `None` is returned.
    fn reduce(&mut self, mut t: Term, work: &mut Vec<Term>) -> Result<Option<Term>, Refused> {
        loop {
            if t.coeff.is_zero() {
                return Ok(None);
            }
            let counts = label_counts(&t.factors)?;
            let summed = |a: &Label| counts.summed(*a);
            // δ_aa = d; δ_ab with a summed: the other occurrence of a becomes b.
            if let Some(k) = t
                .factors
                .iter()
                .position(|f| matches!(f, Factor::Delta(a, b) if a == b || summed(a) || summed(b)))
            {
                let Factor::Delta(a, b) = t.factors.swap_remove(k) else {
                    unreachable!("found above")
                };
                if a == b {
                    t.coeff = &t.coeff * &Rational::int(self.dim as i64);
                } else {
                    let (from, to) = if summed(&a) { (a, b) } else { (b, a) };
                    rename(&mut t.factors, from, to);
                }
                continue;
            }
            // ε_{a…} ε_{b…} = det[δ_{a_i b_j}].
            let eps: Vec<usize> = (0..t.factors.len())
                .filter(|&k| matches!(t.factors[k], Factor::Eps(_)))
                .collect();
            if let [i, j, ..] = eps[..] {
                let (Factor::Eps(x), Factor::Eps(y)) = (t.factors[i].clone(), t.factors[j].clone())
                else {
                    unreachable!("found above")
                };
                if x.len() != self.dim || y.len() != self.dim {
                    return Err(Refused::Malformed);
                }
                let rest: Vec<Factor> = t
                    .factors
                    .iter()
                    .enumerate()
                    .filter(|&(k, _)| k != i && k != j)
                    .map(|(_, f)| f.clone())
                    .collect();
                let perms = permutations(self.dim);
                self.spend(perms.len())?;
                for (p, sign) in perms {
                    let mut factors = rest.clone();
                    factors.extend(x.iter().zip(&p).map(|(&a, &k)| Factor::Delta(a, y[k])));
                    let coeff = if sign < 0 { -&t.coeff } else { t.coeff.clone() };
                    work.push(Term { coeff, factors });
                }
                return Ok(None);
            }
            // n_a n_a = 1 for the unit normal.
            if let Some(normal) = self.props.normal {
                let ns: Vec<usize> = (0..t.factors.len())
                    .filter(|&k| matches!(&t.factors[k], Factor::Symbol { id, slots } if *id == normal && slots.len() == 1))
                    .collect();
                let pair = ns.iter().enumerate().find_map(|(u, &i)| {
                    ns[u + 1..]
                        .iter()
                        .find(|&&j| t.factors[i].slots() == t.factors[j].slots())
                        .map(|&j| (i, j))
                });
                if let Some((i, j)) = pair {
                    t.factors.remove(j);
                    t.factors.remove(i);
                    self.unit_normal = true;
                    continue;
                }
            }
            if self.vanishes(&t.factors, &counts) {
                return Ok(None);
            }
            return Ok(Some(t));
        }
    }

    /// Whether a reduced term is 0 by a symmetry: ε or an antisymmetric tensor with a
    /// repeated index, a traceless tensor traced, or ε contracted on a pair of summed
    /// indices that the rest of the term is symmetric in.
    fn vanishes(&self, factors: &[Factor], counts: &LabelCounts) -> bool {
        for (k, f) in factors.iter().enumerate() {
            match f {
                Factor::Eps(s) => {
                    for a in 0..s.len() {
                        for b in a + 1..s.len() {
                            if s[a] == s[b] {
                                return true;
                            }
                            let both_summed = counts.summed(s[a]) && counts.summed(s[b]);
                            if both_summed && self.symmetric_in(factors, k, s[a], s[b]) {
                                return true;
                            }
                        }
                    }
                }
                Factor::Symbol { id, slots }
                    if slots.len() == 2
                        && slots[0] == slots[1]
                        && (self.props.antisymmetric.contains(id)
                            || self.props.traceless.contains(id)) =>
                {
                    return true;
                }
                _ => {}
            }
        }
        false
    }

    /// Whether the factors other than `skip` are unchanged, as a multiset, by swapping
    /// the labels `a` and `b`.
    fn symmetric_in(&self, factors: &[Factor], skip: usize, a: Label, b: Label) -> bool {
        let mut before: Vec<Factor> = Vec::with_capacity(factors.len());
        let mut after: Vec<Factor> = Vec::with_capacity(factors.len());
        for (k, f) in factors.iter().enumerate() {
            if k == skip {
                continue;
            }
            let mut g = f.clone();
            rename_in(&mut g, |l| {
                if l == a {
                    b
                } else if l == b {
                    a
                } else {
                    l
                }
            });
            // Only a symmetric slot order is forgotten; ε and antisymmetric tensors
            // keep theirs (a sign would be lost).
            before.push(self.unordered(f.clone()));
            after.push(self.unordered(g));
        }
        before.sort();
        after.sort();
        before == after
    }

    /// δ and symmetric tensors with their two slots in increasing order.
    fn unordered(&self, f: Factor) -> Factor {
        match f {
            Factor::Delta(a, b) if a > b => Factor::Delta(b, a),
            Factor::Symbol { id, mut slots }
                if slots.len() == 2
                    && slots[0] > slots[1]
                    && self.props.symmetric.contains(&id) =>
            {
                slots.swap(0, 1);
                Factor::Symbol { id, slots }
            }
            f => f,
        }
    }

    /// The canonical naming of a reduced term's summed labels and the order of its
    /// factors, with the sign that sorting ε and antisymmetric slots gave. `None`: the
    /// term equals its own negative, so it is 0.
    /// The second value is the number of orderings tried.
    fn canonical_term(&self, factors: &[Factor]) -> (Option<(Vec<Factor>, i8)>, usize) {
        let counts = label_counts(factors).expect("reduced terms are well formed");
        let is_summed = |l: Label| counts.summed(l);
        // The shape of a factor forgets the names of its summed labels.
        let shape = |f: &Factor| {
            let mut g = f.clone();
            rename_in(&mut g, |l| if is_summed(l) { Label::MAX } else { l });
            self.normalised(g).0
        };
        let mut order: Vec<(Factor, &Factor)> = factors.iter().map(|f| (shape(f), f)).collect();
        order.sort_by(|x, y| x.0.cmp(&y.0));
        // Runs of equal shape: their orderings are the candidates.
        let mut groups: Vec<std::ops::Range<usize>> = Vec::new();
        let mut start = 0;
        for k in 1..=order.len() {
            if k == order.len() || order[k].0 != order[start].0 {
                groups.push(start..k);
                start = k;
            }
        }
        let orderings = groups
            .iter()
            .try_fold(1usize, |acc, g| acc.checked_mul(factorial(g.len())?))
            .filter(|&n| n <= MAX_ORDERINGS);
        let base: Vec<&Factor> = order.iter().map(|(_, f)| *f).collect();
        let mut best: Option<(Vec<Factor>, i8)> = None;
        let mut opposite = false;
        let mut consider = |candidate: (Vec<Factor>, i8)| match &best {
            Some((b, s)) if *b == candidate.0 => {
                if *s != candidate.1 {
                    opposite = true;
                }
            }
            Some((b, _)) if *b < candidate.0 => {}
            _ => {
                best = Some(candidate);
                opposite = false;
            }
        };
        match orderings {
            Some(n) if n > 1 => {
                let mut perm: Vec<&Factor> = base.clone();
                for_each_ordering(&groups, &mut perm, 0, &base, &mut |p| {
                    consider(self.named(p, &is_summed))
                });
            }
            _ => consider(self.named(&base, &is_summed)),
        }
        let (factors, sign) = best.expect("one candidate at least");
        let tried = orderings.unwrap_or(1);
        ((!opposite).then_some((factors, sign)), tried)
    }

    /// The term with its summed labels renamed in order of first appearance in
    /// `factors`, each factor's slots normalised, and the factors sorted.
    fn named(&self, factors: &[&Factor], is_summed: &dyn Fn(Label) -> bool) -> (Vec<Factor>, i8) {
        let mut names: BTreeMap<Label, Label> = BTreeMap::new();
        let mut sign = 1i8;
        let mut out: Vec<Factor> = factors
            .iter()
            .map(|f| {
                let mut g = (*f).clone();
                rename_in(&mut g, |l| {
                    if is_summed(l) {
                        let next = FIRST_CANONICAL + names.len() as Label;
                        *names.entry(l).or_insert(next)
                    } else {
                        l
                    }
                });
                let (g, s) = self.normalised(g);
                sign *= s;
                g
            })
            .collect();
        out.sort();
        (out, sign)
    }

    /// A factor with its slots in the order its symmetry allows, and the sign of the
    /// reordering (ε and antisymmetric tensors).
    fn normalised(&self, f: Factor) -> (Factor, i8) {
        match f {
            Factor::Eps(mut s) => {
                let sign = sort_with_sign(&mut s);
                (Factor::Eps(s), sign)
            }
            Factor::Symbol { id, mut slots }
                if slots.len() == 2 && self.props.antisymmetric.contains(&id) =>
            {
                let sign = sort_with_sign(&mut slots);
                (Factor::Symbol { id, slots }, sign)
            }
            f => (self.unordered(f), 1),
        }
    }
}

/// How often each label occurs in a term, by label (sorted, for a binary search).
struct LabelCounts(Vec<(Label, u8)>);

impl LabelCounts {
    /// Whether `l` occurs twice: a summed label.
    fn summed(&self, l: Label) -> bool {
        self.0
            .binary_search_by_key(&l, |&(k, _)| k)
            .is_ok_and(|at| self.0[at].1 == 2)
    }
}

/// How often each label occurs in a term; more than twice is malformed.
fn label_counts(factors: &[Factor]) -> Result<LabelCounts, Refused> {
    let mut labels: Vec<Label> = Vec::with_capacity(2 * factors.len());
    for f in factors {
        for_each_label(f, |l| labels.push(l));
    }
    labels.sort_unstable();
    let mut counts: Vec<(Label, u8)> = Vec::with_capacity(labels.len());
    for run in labels.chunk_by(|a, b| a == b) {
        if run.len() > 2 {
            return Err(Refused::Malformed);
        }
        counts.push((run[0], run.len() as u8));
    }
    Ok(LabelCounts(counts))
}

fn for_each_label(f: &Factor, mut g: impl FnMut(Label)) {
    match f {
        Factor::Delta(a, b) => {
            g(*a);
            g(*b);
        }
        Factor::Eps(s) | Factor::Symbol { slots: s, .. } => s.iter().for_each(|&l| g(l)),
    }
}

fn rename_in(f: &mut Factor, mut g: impl FnMut(Label) -> Label) {
    match f {
        Factor::Delta(a, b) => {
            *a = g(*a);
            *b = g(*b);
        }
        Factor::Eps(s) | Factor::Symbol { slots: s, .. } => {
            for l in s.iter_mut() {
                *l = g(*l);
            }
        }
    }
}

/// Every occurrence of `from` becomes `to`.
fn rename(factors: &mut [Factor], from: Label, to: Label) {
    for f in factors {
        rename_in(f, |l| if l == from { to } else { l });
    }
}

/// Sorts `s` and returns the sign of the permutation (0 never: equal labels are
/// caught before).
fn sort_with_sign(s: &mut [Label]) -> i8 {
    let mut sign = 1;
    for i in 1..s.len() {
        let mut j = i;
        while j > 0 && s[j - 1] > s[j] {
            s.swap(j - 1, j);
            sign = -sign;
            j -= 1;
        }
    }
    sign
}

fn factorial(n: usize) -> Option<usize> {
    (1..=n).try_fold(1usize, |acc, k| acc.checked_mul(k))
}

/// (m − 1)!!, the number of pairings of m labels (m even), saturating: a charge
/// against the budget, which a saturated count exceeds.
fn pairing_count(m: usize) -> usize {
    (1..m)
        .step_by(2)
        .try_fold(1usize, |acc, k| acc.checked_mul(k))
        .unwrap_or(usize::MAX)
}

/// Two labels paired by a δ.
type Pair = (Label, Label);

/// Calls `f` with every pairing of `labels` (an even number of them).
fn for_each_pairing(labels: &[Label], pairs: &mut Vec<Pair>, f: &mut dyn FnMut(&[Pair])) {
    let Some((&first, rest)) = labels.split_first() else {
        f(pairs);
        return;
    };
    for k in 0..rest.len() {
        let others: Vec<Label> = rest
            .iter()
            .enumerate()
            .filter(|&(j, _)| j != k)
            .map(|(_, &l)| l)
            .collect();
        pairs.push((first, rest[k]));
        for_each_pairing(&others, pairs, f);
        pairs.pop();
    }
}

/// Every permutation of 0..n with its sign.
fn permutations(n: usize) -> Vec<(Vec<usize>, i8)> {
    fn go(prefix: &mut Vec<usize>, n: usize, out: &mut Vec<(Vec<usize>, i8)>) {
        if prefix.len() == n {
            out.push((prefix.clone(), super::tensor::permutation_sign(prefix)));
            return;
        }
        for k in 0..n {
            if !prefix.contains(&k) {
                prefix.push(k);
                go(prefix, n, out);
                prefix.pop();
            }
        }
    }
    let mut out = Vec::new();
    go(&mut Vec::new(), n, &mut out);
    out
}

/// Calls `f` with every ordering of `base` that permutes only within each group.
fn for_each_ordering<'a>(
    groups: &[std::ops::Range<usize>],
    perm: &mut Vec<&'a Factor>,
    g: usize,
    base: &[&'a Factor],
    f: &mut dyn FnMut(&[&'a Factor]),
) {
    let Some(range) = groups.get(g) else {
        f(perm);
        return;
    };
    if range.len() == 1 {
        for_each_ordering(groups, perm, g + 1, base, f);
        return;
    }
    let items: Vec<&Factor> = base[range.clone()].to_vec();
    let mut idx: Vec<usize> = (0..items.len()).collect();
    loop {
        for (slot, &i) in range.clone().zip(&idx) {
            perm[slot] = items[i];
        }
        for_each_ordering(groups, perm, g + 1, base, f);
        if !next_permutation(&mut idx) {
            break;
        }
    }
}

/// The next permutation in lexicographic order; false after the last.
fn next_permutation(p: &mut [usize]) -> bool {
    let Some(i) = (1..p.len()).rev().find(|&i| p[i - 1] < p[i]) else {
        return false;
    };
    let j = (i..p.len())
        .rev()
        .find(|&j| p[j] > p[i - 1])
        .expect("p[i] qualifies");
    p.swap(i - 1, j);
    p[i..].reverse();
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    const I: Label = 1;
    const J: Label = 2;
    const K: Label = 3;
    const A: u32 = 10;
    const B: u32 = 11;
    const SIGMA: u32 = 12;
    const N: u32 = 13;

    fn sym(id: u32, slots: &[Label]) -> Factor {
        Factor::Symbol {
            id,
            slots: slots.to_vec(),
        }
    }

    fn term(c: i64, factors: Vec<Factor>) -> Sum {
        Sum {
            terms: vec![Term {
                coeff: Rational::int(c),
                factors,
            }],
        }
    }

    fn algebra(dim: usize) -> Algebra {
        let mut props = Properties {
            normal: Some(N),
            ..Properties::default()
        };
        props.symmetric.insert(SIGMA);
        Algebra::new(dim, props)
    }

    fn form(dim: usize, s: Sum) -> Canonical {
        algebra(dim).canonical(s).expect("reduces")
    }

    #[test]
    fn summed_indices_are_renamed_and_factors_sorted() {
        // a_x b_x (x summed, 100) and b_y a_y (y = 200) are one term.
        let left = term(1, vec![sym(A, &[100]), sym(B, &[100])]);
        let right = term(1, vec![sym(B, &[200]), sym(A, &[200])]);
        assert_eq!(form(3, left.clone()), form(3, right.clone()));
        // Their difference cancels to the empty form.
        let diff = left.plus(right.scale(&Rational::int(-1)));
        assert!(form(3, diff).is_empty());
    }

    #[test]
    fn delta_contracts_and_traces_to_the_dimension() {
        // δ_ix δ_xj = δ_ij; δ_xx = d.
        let chain = term(1, vec![Factor::Delta(I, 100), Factor::Delta(100, J)]);
        assert_eq!(form(3, chain), form(3, term(1, vec![Factor::Delta(I, J)])));
        for d in [2, 3] {
            let trace = term(1, vec![Factor::Delta(100, 100)]);
            assert_eq!(
                form(d, trace),
                form(d, Sum::constant(Rational::int(d as i64)))
            );
        }
    }

    #[test]
    fn eps_pairs_become_deltas_and_symmetric_contractions_vanish() {
        // ε_xyz ε_xyz = 6 in 3D, ε_xy ε_xy = 2 in 2D.
        let full = term(
            1,
            vec![
                Factor::Eps(vec![100, 101, 102]),
                Factor::Eps(vec![100, 101, 102]),
            ],
        );
        assert_eq!(form(3, full), form(3, Sum::constant(Rational::int(6))));
        let plane = term(
            1,
            vec![Factor::Eps(vec![100, 101]), Factor::Eps(vec![100, 101])],
        );
        assert_eq!(form(2, plane), form(2, Sum::constant(Rational::int(2))));
        // ε_ixy σ_xy = 0 for a symmetric σ, ε_ixy a_x a_y = 0; not for a general b_xy.
        let s = term(
            1,
            vec![Factor::Eps(vec![I, 100, 101]), sym(SIGMA, &[100, 101])],
        );
        assert!(form(3, s).is_empty());
        let aa = term(
            1,
            vec![
                Factor::Eps(vec![I, 100, 101]),
                sym(A, &[100]),
                sym(A, &[101]),
            ],
        );
        assert!(form(3, aa).is_empty());
        let b = term(1, vec![Factor::Eps(vec![I, 100, 101]), sym(B, &[100, 101])]);
        assert_eq!(form(3, b).len(), 1);
        // ε with a repeated index is 0; swapping two slots flips the sign.
        assert!(form(3, term(1, vec![Factor::Eps(vec![I, I, J])])).is_empty());
        let swapped = term(1, vec![Factor::Eps(vec![J, I, K])]);
        assert_eq!(
            form(3, swapped),
            form(3, term(-1, vec![Factor::Eps(vec![I, J, K])]))
        );
    }

    #[test]
    fn averages_are_the_pairings_over_the_moment_denominator() {
        let mut alg = algebra(3);
        let n = |l| sym(N, &[l]);
        // ⟨n_i n_j n_x n_x⟩ = ⟨n_i n_j⟩ = δ_ij / 3 (and n·n = 1 outside the average).
        let four = alg
            .average(term(1, vec![n(I), n(J), n(100), n(100)]))
            .expect("small");
        let two = alg.average(term(1, vec![n(I), n(J)])).expect("small");
        assert_eq!(
            alg.canonical(four).unwrap(),
            alg.canonical(two.clone()).unwrap()
        );
        let delta = term(1, vec![Factor::Delta(I, J)]).scale(&Rational::ratio(1, 3).unwrap());
        assert_eq!(alg.canonical(two).unwrap(), alg.canonical(delta).unwrap());
        // Odd order: 0.
        let odd = alg.average(term(1, vec![n(I), n(J), n(K)])).expect("small");
        assert!(alg.canonical(odd).unwrap().is_empty());
        let unit = alg
            .canonical(term(1, vec![n(100), n(100), sym(A, &[I])]))
            .unwrap();
        assert!(unit.used_unit_normal());
        assert_eq!(unit, form(3, term(1, vec![sym(A, &[I])])));
    }

    #[test]
    fn a_first_difference_is_where_the_component_route_finds_it() {
        // δ_ij against δ_ij + δ_ij δ_kk/3 − δ_ij: equal (δ_kk = 3).
        let labels = [I, J];
        let a = form(3, term(1, vec![Factor::Delta(I, J)]));
        let b = form(3, term(2, vec![Factor::Delta(I, J)]));
        // The first index values in lexicographic order, (1, 1), with both values.
        let Some(Some((ordinal, x, l, r))) = first_difference(&a, &b, &labels, 3) else {
            panic!("a constant difference");
        };
        assert_eq!((ordinal, x), (0, vec![0, 0]));
        assert_eq!((l, r), (Rational::int(1), Rational::int(2)));
        // ε_ijk against 0 differs first at (1, 2, 3): ordinal 5.
        let e = form(3, term(1, vec![Factor::Eps(vec![I, J, K])]));
        let zero = form(3, Sum::default());
        let Some(Some((ordinal, x, ..))) = first_difference(&e, &zero, &[I, J, K], 3) else {
            panic!("a constant difference");
        };
        assert_eq!((ordinal, x), (5, vec![0, 1, 2]));
        // A symbol makes the difference not a number.
        let s = form(3, term(1, vec![sym(A, &[I]), sym(A, &[J])]));
        assert!(first_difference(&s, &a, &labels, 3).is_none());
        // A symbolic term both share: the difference is δ_ij, but the sides' values are
        // not numbers, so no difference is reported (nor a panic).
        let shared = |c| {
            let mut t = term(1, vec![sym(A, &[I]), sym(A, &[J])]);
            t.terms.push(Term {
                coeff: Rational::int(c),
                factors: vec![Factor::Delta(I, J)],
            });
            form(3, t)
        };
        assert!(first_difference(&shared(1), &shared(2), &labels, 3).is_none());
        // Where such a difference is 0 everywhere the forms are still equal tensors.
        assert_eq!(
            first_difference(&shared(1), &shared(1), &labels, 3),
            Some(None)
        );
    }

    #[test]
    fn linearly_dependent_delta_products_are_equal_by_evaluation() {
        // With indices running over 1..1 every δ is 1, so δ_ij δ_kl = δ_ik δ_jl although
        // the forms differ (the smallest case of δ products made dependent by the
        // dimension); over 1..2 they differ.
        let (l, m) = (4, 5);
        let a = form(1, term(1, vec![Factor::Delta(I, J), Factor::Delta(l, m)]));
        let b = form(1, term(1, vec![Factor::Delta(I, l), Factor::Delta(J, m)]));
        assert_ne!(a, b);
        assert_eq!(first_difference(&a, &b, &[I, J, l, m], 1), Some(None));
        assert!(first_difference(&a, &b, &[I, J, l, m], 2)
            .unwrap()
            .is_some());
    }

    #[test]
    fn malformed_terms_and_large_products_are_refused() {
        let thrice = term(1, vec![sym(A, &[I]), sym(B, &[I]), sym(A, &[I])]);
        assert_eq!(algebra(3).canonical(thrice), Err(Refused::Malformed));
        let mut alg = algebra(3);
        let wide = Sum {
            terms: (0..700)
                .map(|k| Term {
                    coeff: Rational::int(1),
                    factors: vec![sym(A + k, &[])],
                })
                .collect(),
        };
        assert_eq!(
            alg.product(&wide, &wide).map(|_| ()),
            Err(Refused::TooLarge)
        );
    }

    #[test]
    fn permutation_helpers_count_and_sign_correctly() {
        assert_eq!(permutations(3).len(), 6);
        assert_eq!(
            permutations(3)
                .iter()
                .map(|(_, s)| i32::from(*s))
                .sum::<i32>(),
            0
        );
        let mut p = vec![0, 1, 2, 3];
        let mut n = 1;
        while next_permutation(&mut p) {
            n += 1;
        }
        assert_eq!(n, 24);
        let mut s = [3, 1, 2];
        assert_eq!(sort_with_sign(&mut s), 1);
        let mut s = [2, 1, 3];
        assert_eq!(sort_with_sign(&mut s), -1);
        assert_eq!(pairing_count(8), 105);
        let mut count = 0;
        for_each_pairing(&[1, 2, 3, 4, 5, 6], &mut Vec::new(), &mut |_| count += 1);
        assert_eq!(count, 15);
    }
}
