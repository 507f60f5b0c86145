//! Definitions the text gives by analogy: "Similarly, … the couple-stress vector $m_i =
//! \mu_{ki} n_k$ can be decomposed into a normal component $m^{(n)}$ and a tangential
//! component $m_i^{(t)}$", after the stress vector $t_i = \sigma_{ki} n_k$ was decomposed
//! into $t^{(n)} = t_i n_i$ (30) and $t_i^{(t)} = t_i - t^{(n)} n_i$ (31). The paper writes
//! no equation for $m^{(n)}$: it says the decomposition is the same. Read so, $m^{(n)} =
//! m_i n_i$ and $m_i^{(t)} = m_i - m^{(n)} n_i$, and the invariants (35) and (36) that
//! read them can be checked.
//!
//! The reading is taken only where everything agrees, since a wrong analogy would make a
//! wrong verdict: the two unlabelled symbols are defined by the same formula up to a
//! renaming of symbols (`t_i = \sigma_{ki} n_k` and `m_i = \mu_{ki} n_k`), the labelled
//! one carries the same label as the defined one, which reads only its unlabelled symbol,
//! the normal and other such labels, the text names the labelled symbol in a formula
//! with the words that lead into the defined one ("a normal component $m^{(n)}$", as
//! "into a normal component" leads into (30)) wherever it names it, with no contrast
//! after ("rather", "but", …), no formula of the text states it or restates the defined
//! one, and a word between the two says the analogy ("similarly", "likewise", …).

use super::displays;
use super::reading::{defined_symbol, no_label, Equation, Stated, Variant};
use super::symbols::{self, fields, label, Key, Stems, Symbol};
use crate::lang::latex::{self, Math, MathKind, ReadOptions};
use std::collections::{BTreeMap, BTreeSet};

/// Words after a formula that may give it another meaning than the analogy's.
const CONTRASTS: [&str; 10] = [
    "rather", "instead", "but", "however", "although", "whereas", "unlike", "not", "except",
    "differs",
];

/// Words that say a construction is repeated for other symbols.
const CUES: [&str; 9] = [
    "similarly",
    "likewise",
    "analogously",
    "by analogy",
    "in analogy",
    "in the same way",
    "in the same manner",
    "in the same fashion",
    "correspondingly",
];

/// A key's symbol without its label and rank: accent, base, primes, suffix.
fn stem(k: &Key) -> Option<[&str; 4]> {
    let [accent, base, _, primes, suffix, _] = fields(k)?;
    Some([accent, base, primes, suffix])
}

/// The key of `stem`'s symbol with `label`, of `rank` index slots.
fn key_of(stem: [&str; 4], label: &str, rank: &str) -> Key {
    let [accent, base, primes, suffix] = stem;
    [accent, base, label, primes, suffix, rank].join("|")
}

/// The cue word of a text, if it says an analogy.
fn cue(text: &str) -> Option<&'static str> {
    let words: String = text
        .to_lowercase()
        .chars()
        .map(|c| if c.is_alphanumeric() { c } else { ' ' })
        .collect();
    let words = format!(
        " {} ",
        words.split_whitespace().collect::<Vec<_>>().join(" ")
    );
    CUES.into_iter().find(|c| words.contains(&format!(" {c} ")))
}

/// The name the text gives what follows `words`: their last two words after the last
/// formula, lowercase ("into a normal component", "a shear (i.e. tangential)
/// component": `normal component`, `tangential component`).
fn naming(words: &str) -> Option<[String; 2]> {
    // After the last display the words hold, up to the one they lead into, after the
    // last formula.
    let after = ["\\end{", "$$", "\\]"]
        .iter()
        .filter_map(|c| {
            let at = words.rfind(c)? + c.len();
            Some(match *c {
                "\\end{" => words[at..].find('}').map_or(at, |k| at + k + 1),
                _ => at,
            })
        })
        .max()
        .unwrap_or(0);
    let words = &words[after..];
    let display = ["\\begin{", "$$", "\\["]
        .iter()
        .filter_map(|o| words.find(o))
        .min()
        .unwrap_or(words.len());
    let words = &words[..display];
    let text = words.rsplit('$').next().unwrap_or(words);
    let mut last = text
        .split(|c: char| !c.is_alphabetic())
        .filter(|w| !w.is_empty())
        .rev()
        .map(str::to_lowercase);
    let (b, a) = (last.next()?, last.next()?);
    Some([a, b])
}

/// Whether `a` and `b` are one formula up to a renaming of symbols, one to one (the
/// normal, δ and ε never renamed): `t_i = \sigma_{ki} n_k` and `m_i = \mu_{ki} n_k`.
fn congruent(a: &Math, b: &Math, map: &mut BTreeMap<String, String>, fixed: &[&str]) -> bool {
    let same = |x: &[Math], y: &[Math], map: &mut BTreeMap<String, String>| {
        x.len() == y.len() && x.iter().zip(y).all(|(p, q)| congruent(p, q, map, fixed))
    };
    match (&a.kind, &b.kind) {
        (MathKind::Number(x), MathKind::Number(y)) => x == y,
        (MathKind::Atom(x), MathKind::Atom(y)) => {
            let script = |s: &Option<latex::Script>| s.as_ref().map(|s| s.text.clone());
            if x.accent != y.accent
                || script(&x.sub) != script(&y.sub)
                || script(&x.sup) != script(&y.sup)
                || x.primes != y.primes
            {
                return false;
            }
            if x.base != y.base
                && (fixed.contains(&x.base.as_str()) || fixed.contains(&y.base.as_str()))
            {
                return false;
            }
            match map.get(&x.base) {
                Some(to) => *to == y.base,
                None => {
                    if map.values().any(|to| *to == y.base) {
                        return false;
                    }
                    map.insert(x.base.clone(), y.base.clone());
                    true
                }
            }
        }
        (MathKind::Sum(x), MathKind::Sum(y)) => {
            x.len() == y.len()
                && x.iter()
                    .zip(y)
                    .all(|((s, p), (t, q))| s == t && congruent(p, q, map, fixed))
        }
        (MathKind::Product(x), MathKind::Product(y)) | (MathKind::Tuple(x), MathKind::Tuple(y)) => {
            same(x, y, map)
        }
        (MathKind::Quotient(p, q), MathKind::Quotient(r, s))
        | (MathKind::Power(p, q), MathKind::Power(r, s))
        | (MathKind::Partial { of: p, by: q }, MathKind::Partial { of: r, by: s }) => {
            congruent(p, r, map, fixed) && congruent(q, s, map, fixed)
        }
        (MathKind::Sqrt(p), MathKind::Sqrt(q))
        | (MathKind::Average(p), MathKind::Average(q))
        | (MathKind::Abs(p), MathKind::Abs(q)) => congruent(p, q, map, fixed),
        (MathKind::Apply(f, p), MathKind::Apply(g, q))
        | (MathKind::Comma { indices: f, of: p }, MathKind::Comma { indices: g, of: q }) => {
            f == g && congruent(p, q, map, fixed)
        }
        (MathKind::Matrix(x), MathKind::Matrix(y)) => {
            x.len() == y.len() && x.iter().zip(y).all(|(r, s)| same(r, s, map))
        }
        _ => false,
    }
}

/// The definition of `key` that `text` states in one of its parts, `X = …`, as its two
/// members, with the symbol as the draft reads it there.
fn definition_in(
    key: &Key,
    text: &str,
    (normal, tensors): (Option<&str>, &Stems),
) -> Option<(Math, Math, Symbol)> {
    let read = latex::read(text, &ReadOptions::default()).ok()?;
    read.parts.iter().find_map(|part| {
        let [m0, m1, ..] = &part.members[..] else {
            return None;
        };
        if part.relations.first() != Some(&latex::Rel::Eq) || !matches!(m0.kind, MathKind::Atom(_))
        {
            return None;
        }
        let members: Vec<&Math> = part.members.iter().collect();
        let found = symbols::occurrences(&members, normal, tensors);
        let (k, square) = defined_symbol(m0, found.first(), tensors)?;
        let (_, symbol) = found.into_iter().find(|(f, _)| *f == k)?;
        (k == *key && square.is_none()).then(|| (m0.clone(), m1.clone(), symbol))
    })
}

/// The definition of a chosen symbol: the text's sentence, or the part of equation `q`.
fn definition(
    key: &Key,
    q: usize,
    (equations, stated): (&[Equation], &BTreeMap<Key, Stated>),
    context: (Option<&str>, &Stems),
) -> Option<(Math, Math, Symbol)> {
    let text = match stated.get(key) {
        Some(st) if st.instead_of.is_none() => st.latex.as_str(),
        Some(_) => return None,
        None => equations.get(q)?.latex.as_str(),
    };
    definition_in(key, text, context)
}

/// A formula of the text: its line, the symbols it names, the name the words before it
/// give ([`naming`]) and whether the words after it take a contrast ([`CONTRASTS`]).
type Mention = (usize, BTreeSet<Key>, Option<[String; 2]>, bool);

/// What the draft needs to read the text's analogies.
pub(super) struct Context<'a> {
    pub equations: &'a [Equation],
    pub prose: &'a [displays::Inline],
    /// Lines of the text whose definitions were refused.
    pub refused: &'a BTreeSet<usize>,
    /// Symbols that must not be defined so: those an equation left to complete may
    /// define.
    pub excluded: &'a dyn Fn(&Key) -> bool,
    /// Symbols a formula of the text states (`$m^{(n)} = m_i m_i$`): no analogy says
    /// what they are.
    pub said: &'a dyn Fn(&Key) -> bool,
    pub normal: Option<&'a str>,
    pub tensors: &'a Stems,
}

/// The labelled symbols the text defines by analogy ([the module](self)), each as a
/// [`Variant`] of the analogous definition; the unlabelled symbol it renames to, when
/// only a sentence of the text defines it (`$m_i = \mu_{ki} n_k$`), is added to
/// `symbols`, `chosen` and `stated`.
pub(super) fn by_analogy(
    cx: &Context<'_>,
    symbols: &mut BTreeMap<Key, Symbol>,
    order: &mut Vec<Key>,
    chosen: &mut BTreeMap<Key, (usize, BTreeSet<Key>)>,
    stated: &mut BTreeMap<Key, Stated>,
) -> Vec<Variant> {
    let Context {
        equations,
        prose,
        refused,
        excluded,
        said,
        normal,
        tensors,
    } = *cx;
    let fixed: Vec<&str> = ["\\delta", "e", "\\epsilon", "\\varepsilon"]
        .into_iter()
        .chain(normal)
        .collect();
    let first_read = |k: &Key| equations.iter().position(|e| e.reads.contains(k));
    // The cue word of the text before each equation, read once.
    let cues: Vec<Option<&str>> = equations.iter().map(|e| cue(&e.before)).collect();
    // The symbols each formula of the text names, with its line, the name the words
    // before it give, and whether the words after it in its sentence take a contrast
    // ("… $m^{(n)}$, taken along the fibre rather than the normal").
    let named: Vec<Mention> = prose
        .iter()
        .filter_map(|f| {
            let read = latex::read(&f.body, &ReadOptions::default()).ok()?;
            let keys = read
                .parts
                .iter()
                .flat_map(|part| {
                    let members: Vec<&Math> = part.members.iter().collect();
                    symbols::occurrences(&members, normal, tensors)
                })
                .map(|(k, _)| k)
                .collect();
            let after = f.words.get(f.at..).unwrap_or("").to_lowercase();
            let contrast = after
                .split(|c: char| !c.is_alphabetic())
                .any(|w| CONTRASTS.contains(&w));
            Some((
                f.line,
                keys,
                naming(f.words.get(..f.at).unwrap_or("")),
                contrast,
            ))
        })
        .collect();
    // What each labelled definition's first body reads, read once (a hostile paper may
    // label hundreds of symbols alike).
    let reads: BTreeMap<Key, Option<BTreeSet<Key>>> = chosen
        .iter()
        .filter(|(k, _)| !label(k).is_empty())
        .map(|(k, (q, _))| {
            let body =
                definition(k, *q, (equations, stated), (normal, tensors)).map(|(l, b, _)| {
                    symbols::occurrences(&[&l, &b], normal, tensors)
                        .into_iter()
                        .map(|(b, _)| b)
                        .filter(|b| b != k)
                        .collect()
                });
            (k.clone(), body)
        })
        .collect();
    let mut out = Vec::new();
    let targets: Vec<Key> = symbols.keys().cloned().collect();
    for k in targets {
        let (Some(s), Some(kstem)) = (symbols.get(&k), stem(&k)) else {
            continue;
        };
        let l = label(&k).to_owned();
        if l.is_empty()
            || no_label(symbols, normal, &l)
            || excluded(&k)
            || said(&k)
            || chosen.contains_key(&k)
        {
            continue;
        }
        let Some(at) = first_read(&k) else { continue };
        let line = equations[at].line;
        // The text names it before its first equation, or in that equation's sentence,
        // with the words it names the analogous symbol ("a normal component
        // $m^{(n)}$", as "into a normal component" leads into `t^{(n)} = t_i n_i`).
        // Every formula of the text that names it must do so, with no contrast after it
        // ("measured by $m^{(n)}$", or a later sentence that names it otherwise, may say
        // another meaning).
        let mentions: Vec<(usize, Option<&[String; 2]>, bool)> = named
            .iter()
            .filter(|(_, keys, _, _)| keys.contains(&k))
            .map(|(l, _, name, contrast)| (*l, name.as_ref(), *contrast))
            .collect();
        if !mentions.iter().any(|(l, _, _)| *l <= line) {
            continue;
        }
        // The defined symbols of the same label and rank, of another stem.
        let mut found: Vec<(Variant, Key, usize)> = Vec::new();
        for (yl, (qy, _)) in chosen.iter() {
            let Some(ystem) = stem(yl) else { continue };
            // (One the text restates, `$t^{(n)} = t_i a_i$` in a later section, is no
            // one analogue.)
            if label(yl) != l
                || ystem == kstem
                || *qy >= at
                || said(yl)
                || symbols.get(yl).map(|y| y.rank) != Some(s.rank)
            {
                continue;
            }
            // What its definition's first body reads (`t^{(n)} = t_i n_i = …`: `t_i`).
            let Some(Some(body)) = reads.get(yl) else {
                continue;
            };
            // Its unlabelled symbol, which its definition reads, once.
            let ys: Vec<&Key> = body
                .iter()
                .filter(|b| stem(b) == Some(ystem) && label(b).is_empty())
                .collect();
            let [y] = ys[..] else { continue };
            let Some(yrank) = fields(y).map(|f| f[5]) else {
                continue;
            };
            let x = key_of(kstem, "", yrank);
            // Every other symbol it reads carries its stem and a label, whose analogue
            // the paper writes.
            let mut renamed = vec![(y.clone(), x.clone())];
            let others = body.iter().filter(|b| *b != y).map(|b| {
                let f = fields(b)?;
                (stem(b)? == ystem && !f[2].is_empty()).then_some(())?;
                let to = key_of(kstem, f[2], f[5]);
                (symbols.contains_key(&to) && to != k).then_some((b.clone(), to))
            });
            let Some(others) = others.collect::<Option<Vec<_>>>() else {
                continue;
            };
            renamed.extend(others);
            found.push((
                Variant {
                    key: k.clone(),
                    of: yl.clone(),
                    how: String::new(),
                    renamed,
                },
                y.clone(),
                *qy,
            ));
        }
        // One analogue only: with two, which one the text means is not clear.
        if found.len() != 1 {
            continue;
        }
        let Some((mut v, y, qy)) = found.pop() else {
            continue;
        };
        let x = v.renamed[0].1.clone();
        // Between the analogous definition and the symbol's first equation.
        let Some(word) = cues
            .get(qy + 1..=at)
            .and_then(|c| c.iter().find_map(|w| *w))
        else {
            continue;
        };
        // The words that lead into the analogous definition: its sentence's, or its
        // equation's.
        let lead = match stated.get(&v.of).and_then(|st| st.line) {
            Some(l) => prose
                .iter()
                .find(|f| f.line == l)
                .and_then(|f| naming(f.words.get(..f.at).unwrap_or(""))),
            None => naming(&equations[qy].lead_in),
        };
        let same = |(_, name, contrast): &(usize, Option<&[String; 2]>, bool)| {
            !contrast && lead.is_some() && *name == lead.as_ref()
        };
        if !mentions.iter().all(same) {
            continue;
        }
        // The unlabelled symbol's definition: an equation's, or a sentence's before
        // the labelled symbol's first equation.
        let sentence = || {
            prose.iter().find_map(|f| {
                (f.line <= line && !refused.contains(&f.line) && f.body.contains('='))
                    .then(|| Some((f, definition_in(&x, &f.body, (normal, tensors))?)))
                    .flatten()
            })
        };
        let (xdef, from_text) = match chosen.get(&x) {
            Some((qx, _)) => (
                definition(&x, *qx, (equations, stated), (normal, tensors)),
                None,
            ),
            None if excluded(&x) || symbols.contains_key(&x) => (None, None),
            None => match sentence() {
                Some((f, def)) => (Some(def), Some(f)),
                None => (None, None),
            },
        };
        let Some(qy_def) = chosen.get(&y).map(|(q, _)| *q) else {
            continue;
        };
        let (Some((x_left, x_body, x_symbol)), Some((y_left, y_body, _))) = (
            xdef,
            definition(&y, qy_def, (equations, stated), (normal, tensors)),
        ) else {
            continue;
        };
        let mut map = BTreeMap::new();
        if !congruent(&y_left, &x_left, &mut map, &fixed)
            || !congruent(&y_body, &x_body, &mut map, &fixed)
        {
            continue;
        }
        // Every symbol of the unlabelled definition is one the draft knows.
        let x_reads: BTreeSet<Key> = symbols::occurrences(&[&x_left, &x_body], normal, tensors)
            .into_iter()
            .map(|(b, _)| b)
            .filter(|b| *b != x)
            .collect();
        if x_reads.is_empty() || x_reads.iter().any(|b| !symbols.contains_key(b)) {
            continue;
        }
        if let Some(f) = from_text {
            order.push(x.clone());
            symbols.insert(x.clone(), x_symbol);
            let q = equations.iter().filter(|e| e.line < f.line).count();
            chosen.insert(x.clone(), (q, x_reads));
            stated.insert(
                x.clone(),
                Stated {
                    line: Some(f.line),
                    latex: f.body.clone(),
                    instead_of: None,
                    law: false,
                },
            );
        }
        let printed = |key: &Key| {
            symbols
                .get(key)
                .map_or_else(String::new, |s| s.key.0.clone())
        };
        v.how = format!(
            "as {} from {}: the text says \"{word}\"",
            printed(&v.of),
            printed(&y)
        );
        out.push(v);
    }
    out
}
