//! An identity between tensors that no permutation of some of their free letters
//! changes is checked at one component per orbit: the rank-10 isotropic moment
//! `⟨n_i n_j … n_t⟩ = (1/10395) Σ δ…δ` has 59,049 components and 66 orbits.
//!
//! Three facts make this sound, each checked here rather than believed:
//! - a side with its definitions written out ([`written_out`]) has the value of the side: a
//!   definition's formal letters become the slots it is used with and its summed
//!   letters become letters the statement uses nowhere;
//! - the canonical form ([`canonical`]) only flattens sums, and products that sum no
//!   letter of their own (two factors may each sum the same letter), sorts the parts of
//!   both and sorts δ's two slots, none of which changes a value;
//! - when exchanging the free letters `a` and `b` leaves a side's canonical form as it
//!   was, its component at any index value equals its component at that value with the
//!   values of `a` and `b` exchanged. Exchanges of neighbouring letters of a block
//!   generate every permutation of the block, so every component equals the one whose
//!   values are sorted within each block.
//!
//! Only sides made of constants, symbols, δ, ε, the normal, sums, products, negations,
//! powers, averages and quotients by a constant are taken; a statement with
//! assumptions, hypotheses or square roots is compared component by component, and so
//! is one whose written-out sides would cost more than every definition in full. Where
//! anything here does not apply, the checker compares every component, as before.

use super::eval::Env;
use super::statement::{Context, Definition};
use super::term::{Leaf, Ranks, Slot, Term};
use std::collections::BTreeSet;

/// The fewest components an equality must have for its orbits to be compared instead:
/// below, every component is (729 is a rank-6 tensor in 3D). The most is what any value
/// may have ([`super::eval::MAX_COMPONENTS`]).
pub const ORBITS_FROM: usize = 729;

/// The most nodes a side may have once its definitions are written out.
const INLINED_NODES: usize = 200_000;

/// The blocks of free letters no permutation of which changes either side, and the
/// index values to compare: one per orbit, sorted within each block.
pub struct Orbits {
    /// The sides with their definitions written out.
    pub sides: [Term; 2],
    /// The free letters, sorted.
    pub letters: Vec<char>,
    /// Blocks of two or more letters (consecutive in `letters`).
    pub blocks: Vec<Vec<char>>,
    /// One index value (0-based, in the order of `letters`) per orbit.
    pub representatives: Vec<Vec<usize>>,
}

/// Both sides of `left = right` with their definitions written out, when the
/// statement is in the class above: each then has the value of its side, component by
/// component, and no divisor that could make another component undefined. `None` too
/// where evaluating them at one index value would cost more than evaluating the sides
/// and the definitions they read in full (definitions that read others twice, written
/// out, double at each level).
pub fn written_out(env: &Env<'_>, left: &Term, right: &Term) -> Option<[Term; 2]> {
    let (sides, nodes, full) = write_out(env, left, right)?;
    (nodes <= full).then_some(sides)
}

/// The sides written out, their nodes, and about the work of evaluating the sides and
/// the definitions they read in full: each one's nodes times its components.
fn write_out(env: &Env<'_>, left: &Term, right: &Term) -> Option<([Term; 2], usize, usize)> {
    let ctx = env.context();
    if !(ctx.equations.is_empty() && ctx.substitutions.is_empty() && ctx.hypotheses.is_empty()) {
        return None;
    }
    let mut inliner = Inliner::new(ctx, env, [left, right]);
    let sides = [inliner.inline(left)?, inliner.inline(right)?];
    let mut full = 0usize;
    for (side, original) in sides.iter().zip([left, right]) {
        let free = original.letters(env).ok()?.free;
        if side.letters(env).ok()?.free != free {
            return None;
        }
        full = full.saturating_add(cost(env, original, free.len()));
    }
    for name in inliner.written.keys() {
        let def = inliner.definition(name)?;
        full = full.saturating_add(cost(env, &def.body, def.formal.len()));
    }
    Some((sides, inliner.nodes, full))
}

/// A term's nodes times its components.
fn cost(env: &Env<'_>, t: &Term, rank: usize) -> usize {
    let components = u32::try_from(rank)
        .ok()
        .and_then(|r| env.ctx_dim().checked_pow(r))
        .unwrap_or(usize::MAX);
    nodes(t).saturating_mul(components)
}

fn nodes(t: &Term) -> usize {
    super::term::children(t)
        .into_iter()
        .map(nodes)
        .fold(1, usize::saturating_add)
}

/// The orbits of `left = right`, or `None` (compare every component): the equality
/// has fewer than 729 or more than 59,049 components, the sides are outside the class
/// above or their free letters differ, no two letters are exchangeable, or the orbits
/// would cost more than every component.
pub fn orbits(env: &Env<'_>, left: &Term, right: &Term) -> Option<Orbits> {
    let letters = left.letters(env).ok()?.free;
    if right.letters(env).ok()?.free != letters {
        return None;
    }
    let dim = env.ctx_dim();
    // No more components than a value may have: the orbits stand for them all.
    let components = dim.checked_pow(u32::try_from(letters.len()).ok()?)?;
    if !(ORBITS_FROM..=super::eval::MAX_COMPONENTS).contains(&components) {
        return None;
    }
    let (sides, nodes, full) = write_out(env, left, right)?;
    // At the fewest orbits (every letter in one block), is it still cheaper?
    let n = letters.len();
    let fewest = (1..dim).fold(1usize, |c, k| c.saturating_mul(n + k) / k);
    if fewest.saturating_mul(nodes) > full {
        return None;
    }
    let canonical_sides = [canonical(sides[0].clone()), canonical(sides[1].clone())];
    // Neighbouring letters that both sides let exchange, joined into blocks.
    let mut blocks: Vec<Vec<char>> = Vec::new();
    let mut run = vec![letters[0]];
    for pair in letters.windows(2) {
        let exchangeable = sides
            .iter()
            .zip(&canonical_sides)
            .all(|(side, form)| canonical(exchanged(side, pair[0], pair[1])) == *form);
        if !exchangeable {
            blocks.push(std::mem::take(&mut run));
        }
        run.push(pair[1]);
    }
    blocks.push(run);
    blocks.retain(|b| b.len() > 1);
    if blocks.is_empty() {
        return None;
    }
    let representatives = sorted_within(dim, &letters, &blocks);
    // Each orbit's component evaluates the written-out sides once.
    if representatives.len().saturating_mul(nodes) > full {
        return None;
    }
    Some(Orbits {
        sides,
        letters,
        blocks,
        representatives,
    })
}

/// Every index value of `letters` in `0..dim` whose values do not decrease along each
/// block, row-major.
fn sorted_within(dim: usize, letters: &[char], blocks: &[Vec<char>]) -> Vec<Vec<usize>> {
    // The letter before each one in its block, if any.
    let before: Vec<Option<usize>> = letters
        .iter()
        .enumerate()
        .map(|(k, c)| {
            let in_block = blocks.iter().any(|b| b.contains(c) && b[0] != *c);
            in_block.then(|| k - 1)
        })
        .collect();
    let mut out = vec![Vec::new()];
    for prev in before {
        out = out
            .into_iter()
            .flat_map(|p: Vec<usize>| {
                let from = prev.map_or(0, |k| p[k]);
                (from..dim).map(move |v| {
                    let mut q = p.clone();
                    q.push(v);
                    q
                })
            })
            .collect();
    }
    out
}

/// Writes definitions out, with summed letters the statement uses nowhere.
struct Inliner<'c> {
    ctx: &'c Context,
    ranks: &'c dyn Ranks,
    used: BTreeSet<char>,
    next: u32,
    nodes: usize,
    active: Vec<&'c str>,
    /// Each definition written out once (its summed letters as in its body) and its
    /// nodes.
    written: std::collections::HashMap<&'c str, (Term, usize)>,
}

impl<'c> Inliner<'c> {
    fn new(ctx: &'c Context, ranks: &'c dyn Ranks, sides: [&Term; 2]) -> Self {
        let mut used = BTreeSet::new();
        for t in sides
            .into_iter()
            .chain(ctx.definitions.iter().map(|d| &d.body))
        {
            letters_in(t, &mut used);
        }
        used.extend(
            ctx.definitions
                .iter()
                .flat_map(|d| d.formal.iter().copied()),
        );
        Inliner {
            ctx,
            ranks,
            used,
            // The private-use area: no reader writes these letters, and any the
            // statement does use are skipped.
            next: 0xE000,
            nodes: 0,
            active: Vec::new(),
            written: std::collections::HashMap::new(),
        }
    }

    /// A letter the statement and every earlier inlining leave unused.
    fn fresh(&mut self) -> Option<char> {
        loop {
            let c = char::from_u32(self.next)?;
            self.next = self.next.checked_add(1).filter(|&n| n <= 0xF8FF)?;
            if self.used.insert(c) {
                return Some(c);
            }
        }
    }

    fn definition(&self, name: &str) -> Option<&'c Definition> {
        // As the evaluator reads them: the last definition of a name.
        self.ctx.definitions.iter().rev().find(|d| d.name == name)
    }

    fn inline(&mut self, t: &Term) -> Option<Term> {
        self.nodes += 1;
        if self.nodes > INLINED_NODES {
            return None;
        }
        let all = |ts: &[Term], me: &mut Self| -> Option<Vec<Term>> {
            ts.iter().map(|t| me.inline(t)).collect()
        };
        Some(match t {
            Term::Const { .. } => t.clone(),
            Term::Leaf {
                of: Leaf::Def(name),
                slots,
            } => {
                let def = self.definition(name)?;
                if def.formal.len() != slots.len() {
                    return None;
                }
                let (mut body, size) = match self.written.get(def.name.as_str()) {
                    Some(done) => done.clone(),
                    None => {
                        if self.active.contains(&def.name.as_str()) {
                            return None;
                        }
                        let before = self.nodes;
                        self.active.push(&def.name);
                        let body = self.inline(&def.body);
                        self.active.pop();
                        let body = body?;
                        // The body's free letters are its formal letters, each once
                        // (the evaluator refuses a definition where they differ);
                        // every other letter is summed inside it and is renamed to a
                        // fresh one at each use.
                        let mut formal = def.formal.clone();
                        formal.sort_unstable();
                        formal.dedup();
                        if formal.len() != def.formal.len()
                            || body.letters(self.ranks).ok()?.free != formal
                        {
                            return None;
                        }
                        let done = (body, self.nodes - before);
                        self.written.insert(&def.name, done.clone());
                        // Counted once more below, as every later use is.
                        self.nodes = before;
                        done
                    }
                };
                self.nodes = self.nodes.saturating_add(size);
                if self.nodes > INLINED_NODES {
                    return None;
                }
                let mut inner = BTreeSet::new();
                letters_in(&body, &mut inner);
                let mut map: Vec<(char, Slot)> = def
                    .formal
                    .iter()
                    .copied()
                    .zip(slots.iter().copied())
                    .collect();
                for c in inner {
                    if !def.formal.contains(&c) {
                        let f = self.fresh()?;
                        map.push((c, Slot::Letter(f)));
                    }
                }
                rename(&mut body, &map)?;
                body
            }
            Term::Leaf { .. } => t.clone(),
            Term::Sum(ts) => Term::Sum(all(ts, self)?),
            Term::Product(fs) => Term::Product(all(fs, self)?),
            Term::Neg(a) => Term::Neg(Box::new(self.inline(a)?)),
            Term::Avg(a) => Term::Avg(Box::new(self.inline(a)?)),
            Term::Pow(a, k) => Term::Pow(Box::new(self.inline(a)?), *k),
            Term::Div(a, b) if is_nonzero_constant(b) => {
                Term::Div(Box::new(self.inline(a)?), b.clone())
            }
            _ => return None,
        })
    }
}

fn is_nonzero_constant(t: &Term) -> bool {
    matches!(t, Term::Const { value, free } if free.is_empty() && !value.is_zero())
}

/// Whether no letter occurs twice among the terms.
fn writes_each_letter_once(ts: &[Term]) -> bool {
    let mut seen = BTreeSet::new();
    let mut once = true;
    for t in ts {
        each_letter(t, &mut |c| once &= seen.insert(c));
    }
    once
}

/// Calls `f` on every occurrence of a letter in a term.
fn each_letter(t: &Term, f: &mut dyn FnMut(char)) {
    let slots = |slots: &[Slot], f: &mut dyn FnMut(char)| {
        for s in slots {
            if let Slot::Letter(c) = s {
                f(*c);
            }
        }
    };
    match t {
        Term::Const { free, .. } | Term::Opaque { free, .. } => free.iter().for_each(|&c| f(c)),
        Term::Leaf { slots: s, .. } => slots(s, f),
        Term::Deriv(_, s) => slots(std::slice::from_ref(s), f),
        Term::Grad { slots: s, .. } | Term::Variation { slots: s, .. } => slots(s, f),
        _ => {}
    }
    for c in super::term::children(t) {
        each_letter(c, f);
    }
}

/// Every letter a term writes, free or summed.
fn letters_in(t: &Term, out: &mut BTreeSet<char>) {
    each_letter(t, &mut |c| {
        out.insert(c);
    });
}

/// Every occurrence of a letter of `map` replaced by its slot, all at once. `None`
/// where a letter of a constant would become a fixed value (not in the class above).
fn rename(t: &mut Term, map: &[(char, Slot)]) -> Option<()> {
    let slot = |s: &mut Slot| {
        if let Slot::Letter(c) = *s {
            if let Some((_, to)) = map.iter().find(|(from, _)| *from == c) {
                *s = *to;
            }
        }
    };
    match t {
        Term::Const { free, .. } => {
            for c in free.iter_mut() {
                match map.iter().find(|(from, _)| from == c) {
                    Some((_, Slot::Letter(to))) => *c = *to,
                    Some((_, Slot::Fixed(_))) => return None,
                    None => {}
                }
            }
        }
        Term::Leaf { slots, .. } => slots.iter_mut().for_each(slot),
        Term::Sum(ts) | Term::Product(ts) => {
            for t in ts {
                rename(t, map)?;
            }
        }
        Term::Neg(a) | Term::Avg(a) | Term::Pow(a, _) | Term::Div(a, _) => rename(a, map)?,
        // Not in the class: `inline` has refused them already.
        _ => return None,
    }
    Some(())
}

/// The side at the index values `at` of its free letters: in the class above a free
/// letter occurs nowhere summed, so each occurrence becomes its value. A product with
/// a δ at two different values is 0 and is left out of its sum.
pub fn at_values(t: &Term, at: &[(char, usize)]) -> Term {
    let value = |c: char| at.iter().find(|(d, _)| *d == c).map(|&(_, v)| v);
    let zero = || Term::Const {
        value: super::rational::Rational::int(0),
        free: Vec::new(),
    };
    match t {
        Term::Const { value: v, free } => Term::Const {
            value: v.clone(),
            free: free
                .iter()
                .copied()
                .filter(|c| value(*c).is_none())
                .collect(),
        },
        Term::Leaf { of, slots } => Term::Leaf {
            of: of.clone(),
            slots: slots
                .iter()
                .map(|s| match s {
                    Slot::Letter(c) => value(*c).map_or(*s, Slot::Fixed),
                    Slot::Fixed(_) => *s,
                })
                .collect(),
        },
        Term::Product(fs) => {
            let fixed = |s: &Slot| match s {
                Slot::Letter(c) => value(*c),
                Slot::Fixed(v) => Some(*v),
            };
            let vanishes = fs.iter().any(|f| {
                matches!(f, Term::Leaf { of: Leaf::Delta, slots }
                    if matches!(slots[..], [ref a, ref b] if fixed(a).zip(fixed(b)).is_some_and(|(a, b)| a != b)))
            });
            // Only where no letter is left: a tensor's 0 would need its letters.
            if vanishes && fs.iter().all(|f| only_fixed(f, at)) {
                return zero();
            }
            Term::Product(fs.iter().map(|f| at_values(f, at)).collect())
        }
        Term::Sum(ts) => {
            let mut kept: Vec<Term> = ts
                .iter()
                .map(|t| at_values(t, at))
                .filter(|t| !matches!(t, Term::Const { value, free } if value.is_zero() && free.is_empty()))
                .collect();
            match kept.len() {
                0 => zero(),
                1 => kept.remove(0),
                _ => Term::Sum(kept),
            }
        }
        Term::Neg(a) => Term::Neg(Box::new(at_values(a, at))),
        Term::Avg(a) => Term::Avg(Box::new(at_values(a, at))),
        Term::Div(a, b) => Term::Div(Box::new(at_values(a, at)), b.clone()),
        // A power's base is a scalar: no free letter.
        other => other.clone(),
    }
}

/// Whether every letter a term writes is one of `at`'s.
fn only_fixed(t: &Term, at: &[(char, usize)]) -> bool {
    let mut known = true;
    each_letter(t, &mut |c| known &= at.iter().any(|(d, _)| *d == c));
    known
}

/// The term with the letters `a` and `b` exchanged.
fn exchanged(t: &Term, a: char, b: char) -> Term {
    let mut t = t.clone();
    // Never `None`: a and b stay letters.
    let _ = rename(&mut t, &[(a, Slot::Letter(b)), (b, Slot::Letter(a))]);
    t
}

/// The term with sums and products flattened (a product only where it sums no letter)
/// and their parts sorted, and δ's two slots sorted: the same value, written one way.
pub fn canonical(t: Term) -> Term {
    match t {
        Term::Sum(ts) => {
            let mut out = Vec::with_capacity(ts.len());
            for t in ts {
                match canonical(t) {
                    Term::Sum(inner) => out.extend(inner),
                    other => out.push(other),
                }
            }
            out.sort_unstable();
            Term::Sum(out)
        }
        Term::Product(fs) => {
            let mut out = Vec::with_capacity(fs.len());
            for f in fs {
                match canonical(f) {
                    // A product that sums a letter is a scope of its own: two such
                    // factors may sum the same letter, and flattened they would share it.
                    Term::Product(inner) if writes_each_letter_once(&inner) => out.extend(inner),
                    other => out.push(other),
                }
            }
            out.sort_unstable();
            Term::Product(out)
        }
        Term::Leaf {
            of: Leaf::Delta,
            mut slots,
        } => {
            slots.sort_unstable();
            Term::Leaf {
                of: Leaf::Delta,
                slots,
            }
        }
        Term::Const { value, mut free } => {
            free.sort_unstable();
            Term::Const { value, free }
        }
        Term::Neg(a) => Term::Neg(Box::new(canonical(*a))),
        Term::Avg(a) => Term::Avg(Box::new(canonical(*a))),
        Term::Pow(a, k) => Term::Pow(Box::new(canonical(*a)), k),
        Term::Div(a, b) => Term::Div(Box::new(canonical(*a)), b),
        other => other,
    }
}
