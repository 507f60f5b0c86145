//! `draft`: a derivation file written from a paper's LaTeX (or Markdown with `$$…$$`
//! displays), which `verify` accepts unchanged.
//!
//! One claim per numbered displayed equation ([`displays`]), with id `eqN` by the number
//! LaTeX would print and `printed` as in the source (alignment marks removed), decided
//! on its reading (no `sides`). Declarations come from the printed symbols
//! ([`symbols`]); a symbol seen for the first time alone on the left of an equation is
//! a definition (its body is the equation's next member, read through the draft's
//! notation), and the claim that states it is a use of every later claim that reads
//! it. So is a symbol an equation of the text introduces (`$t_i = \sigma_{ki} n_k$`),
//! and the new term of a decomposition the text announces (`stated_definitions`). A
//! symbol with a label, an accent or primes gets a notation entry with a readable name.
//! What the loader refuses is learned round by round (`Rounds`): a definition of the
//! text is dropped; a subscript a definition's right side has no index for, on a symbol
//! the paper also prints bare, is read as stray; a chain whose members carry different
//! free indices is checked as printed (`verbatim`).
//!
//! An equation the draft cannot read, or whose claim the loader refuses, is kept in the
//! file as a commented claim, and listed in `to_complete` with its line in the source,
//! the reason and the edit that would let it be read (`verify` lists them): nothing is
//! dropped silently. The draft is deterministic: the same source and
//! options give the same bytes.

mod analogy;
mod displays;
mod reading;
mod symbols;
mod symmetry;

use super::notation::{self, Notation};
use super::TieKind;
use crate::lang::latex::{self, MathKind, ReadOptions};
use crate::lang::{Decls, DefSig};
use reading::{defined_symbol, no_label, Equation, Stated, Variant};
use std::collections::{BTreeMap, BTreeSet};
pub use symbols::RESERVED;
use symbols::{Key, Stems, Symbol};

/// What the command line sets.
#[derive(Clone, Debug, Default)]
pub struct Options {
    /// The index range 1..=d; without it, a sentence of the source such as "indices
    /// ranging from 1 to 3" sets it, else 3.
    pub dimension: Option<usize>,
    /// The unit normal that `\langle … \rangle` averages over; without it, the one the
    /// text names ("Let $n$ be the unit normal").
    pub normal: Option<String>,
}

/// A draft: the file's text and what it says about the source.
#[derive(Clone, Debug)]
pub struct Draft {
    pub toml: String,
    /// Numbered equations found.
    pub equations: usize,
    /// Of them, claims in the file (the rest are to complete).
    pub claims: usize,
    /// Displays without a number (not drafted).
    pub unnumbered: usize,
}

/// The largest source a draft reads, in bytes: its file stays well within a derivation
/// file's limit.
pub const MAX_SOURCE_BYTES: usize = 1 << 20;

/// The most equations one draft takes.
pub const MAX_EQUATIONS: usize = 500;

/// Drafts a derivation file from `source` (named `label` in the file's header); the
/// claims `refused` names (id → why) are left to complete, and those `numeric` names are
/// decided by sampling.
///
/// A character no derivation file may hold (a control character, a bidirectional
/// control that reorders what a reader sees, a noncharacter) is written U+FFFD, and the
/// file's header says where each was: the equation that held one is read as it then
/// stands, or left to complete.
pub fn draft(
    label: &str,
    source: &str,
    options: &Options,
    refused_numeric: (&BTreeMap<String, String>, &BTreeSet<String>),
) -> Draft {
    use crate::derivation::control::{describe, forbidden};
    if !source.chars().any(forbidden) {
        return draft_clean(label, source, options, refused_numeric);
    }
    // Where each was (the first few, and how many in all).
    const LISTED: usize = 20;
    let found: Vec<(usize, usize, char)> = source
        .lines()
        .enumerate()
        .flat_map(|(n, line)| {
            line.chars()
                .enumerate()
                .filter(|(_, c)| forbidden(*c))
                .map(move |(col, c)| (n + 1, col + 1, c))
        })
        .collect();
    let mut notes = String::new();
    for (line, col, c) in found.iter().take(LISTED) {
        notes.push_str(&format!(
            "# The paper's line {line}, column {col}: {}, written U+FFFD here.\n",
            describe(*c)
        ));
    }
    if found.len() > LISTED {
        notes.push_str(&format!(
            "# … and {} more such characters, each written U+FFFD.\n",
            found.len() - LISTED
        ));
    }
    let clean: String = source
        .chars()
        .map(|c| if forbidden(c) { '\u{FFFD}' } else { c })
        .collect();
    let mut d = draft_clean(label, &clean, options, refused_numeric);
    let at = d.toml.find('\n').map_or(0, |k| k + 1);
    d.toml.insert_str(at, &notes);
    d
}

fn draft_clean(
    label: &str,
    source: &str,
    options: &Options,
    (refused, numeric): (&BTreeMap<String, String>, &BTreeSet<String>),
) -> Draft {
    // A Markdown rendering (`.md`) hides HTML comments and code; LaTeX its comments,
    // `\iffalse` and what follows `\end{document}`.
    // Standard input has no extension: `$$` displays and no `\begin{document}` are taken
    // for Markdown.
    let markdown = label.ends_with(".md")
        || label.ends_with(".markdown")
        || (!label.contains('.') && source.contains("$$") && !source.contains("\\begin{document}"));
    let (mut found, unnumbered_displays) = displays::numbered(source, markdown);
    // Past the most a draft takes, equations are counted in the header, not drafted.
    let beyond = found.len().saturating_sub(MAX_EQUATIONS);
    found.truncate(MAX_EQUATIONS);
    let unnumbered = (unnumbered_displays.len(), beyond);
    let dimension = options
        .dimension
        .or_else(|| dimension_in(source, markdown))
        .unwrap_or(3);
    let stated = options
        .normal
        .is_none()
        .then(|| normal_in(source, markdown))
        .flatten();
    let normal = options.normal.as_deref().or(stated.as_deref());
    let live = displays::live(source, markdown);
    let lines: Vec<&str> = live.lines().collect();
    let mut prose = displays::inline_formulas(source, markdown);
    // A display without a number is an equation of the text too: it may tie symbols.
    prose.extend(unnumbered_displays.iter().map(|d| {
        let words = displays::lead_in(&lines, d.line);
        displays::Inline {
            line: d.line,
            body: d.latex.clone(),
            at: words.len(),
            words,
        }
    }));
    // The clause of a numbered equation the reader cannot read, `(\mathbf{K}_2 -
    // \mathbf{K}_1)_i = 2\ell_i \quad\text{with}\quad \ell_i = R_g n_i`, still states a
    // definition, as a sentence would ("with $\ell_i = R_g n_i$"); the equation itself
    // is left to complete.
    prose.extend(found.iter().filter_map(|d| {
        let clause = with_clause(&d.latex)?;
        latex::read(&d.latex, &ReadOptions::default())
            .is_err()
            .then(|| displays::Inline {
                line: d.line,
                body: clause.to_owned(),
                words: "with".to_owned(),
                at: "with".len(),
            })
    }));
    // What the text's own equations say, read in the first round.
    let mut said = None;
    let mut seen_ids = BTreeSet::new();
    // The line where the numbered display before each ends (0 for the first).
    let mut previous_end = 0usize;
    let mut equations: Vec<Equation> = found
        .into_iter()
        .map(|d| {
            let since = std::mem::replace(&mut previous_end, d.end);
            let mut id = format!(
                "eq{}",
                d.number
                    .chars()
                    .map(|c| if c.is_ascii_alphanumeric() { c } else { '-' })
                    .collect::<String>()
            );
            let mut unread = (!seen_ids.insert(id.clone())).then(|| {
                id = format!("{id}-line{}", d.line);
                format!("the number ({}) occurs twice", d.number)
            });
            if let Some(why) = refused.get(&id) {
                unread.get_or_insert_with(|| why.clone());
            }
            Equation {
                numeric: numeric.contains(&id),
                id,
                number: d.number,
                line: d.line,
                latex: d.latex,
                unread,
                edit: None,
                lead_in: displays::lead_in(&lines, d.line),
                before: lines
                    .get(since.min(d.line.saturating_sub(1))..d.line.saturating_sub(1))
                    .map(|l| l.join(" "))
                    .unwrap_or_default(),
                lead_out: displays::lead_out(&lines, d.end),
                reads: BTreeSet::new(),
                names: BTreeSet::new(),
                defines: Vec::new(),
                stray: BTreeSet::new(),
                verbatim: false,
                introduces: BTreeSet::new(),
                differentiated: BTreeSet::new(),
                linear: (Vec::new(), String::new()),
            }
        })
        .collect();
    // Refused claims move to "To complete", and the file is written again, until the
    // loader accepts it (each round moves at least one claim).
    // The reasons for ties (`tied`) are found only for a file the loader accepts
    // without them: finding them in every round would cost rounds × formulas.
    let mut rounds = Rounds::default();
    for text in equations
        .iter()
        .map(|e| e.latex.as_str())
        .chain(prose.iter().map(|f| f.body.as_str()))
    {
        for part in latex::read(text, &ReadOptions::default())
            .iter()
            .flat_map(|r| &r.parts)
        {
            for m in &part.members {
                symbols::vector_letters(m, &mut rounds.vectors);
            }
        }
    }
    let (headings, enclosed) = symmetry::sections(&lines, markdown);
    let sentences = displays::sentences(source, markdown);
    rounds.symmetric = symmetry::read(&sentences, &headings, &enclosed);
    rounds.text = Text {
        headings,
        sentences: sentences.into_iter().map(|s| (s.line, s.words)).collect(),
    };
    rounds.incompressible = lines.iter().enumerate().find_map(|(k, l)| {
        tie_word(l)
            .filter(|w| tie_kind(w) == TieKind::Divergence)
            .map(|w| (k + 1, w))
    });
    rounds.vectors.extend(normal.and_then(|n| {
        let mut c = n.chars();
        c.next().filter(|_| c.next().is_none())
    }));
    let mut refusal = None;
    for _ in 0..=2 * (equations.len() + prose.len()) + 2 {
        let Some(toml) = write(
            label,
            &mut equations,
            (dimension, normal),
            unnumbered,
            (&prose, None),
            &mut rounds,
        ) else {
            continue;
        };
        let toml = match super::load::load_str("draft.toml", &toml) {
            Ok(_) => write(
                label,
                &mut equations,
                (dimension, normal),
                unnumbered,
                (&prose, Some(&mut said)),
                &mut rounds,
            )
            .unwrap_or(toml),
            Err(_) => toml,
        };
        match super::load::load_str("draft.toml", &toml) {
            Ok(_) => {
                let claims = equations.iter().filter(|e| e.unread.is_none()).count();
                return Draft {
                    toml,
                    equations: equations.len(),
                    claims,
                    unnumbered: unnumbered.0,
                };
            }
            Err(e) => {
                if !refuse_claims(&toml, &e, &mut equations, &mut rounds) {
                    refusal = first_message(&e);
                    break;
                }
            }
        }
    }
    // Nothing the loader refused could be traced to one claim: every claim is left to
    // complete, which the loader always accepts, with the loader's reason.
    let why = match refusal {
        Some(m) => format!("the drafted file was refused as a whole: {m}"),
        None => "the drafted file was refused as a whole".to_owned(),
    };
    for e in &mut equations {
        e.unread.get_or_insert_with(|| why.clone());
    }
    let toml = write(
        label,
        &mut equations,
        (dimension, normal),
        unnumbered,
        (&prose, Some(&mut said)),
        &mut Rounds {
            refused_text: prose.iter().map(|f| f.line).collect(),
            stray: BTreeSet::new(),
            vectors: rounds.vectors,
            incompressible: rounds.incompressible,
            symmetric: rounds.symmetric,
            text: rounds.text,
        },
    )
    .expect("with every claim to complete, nothing is read");
    Draft {
        toml,
        equations: equations.len(),
        claims: 0,
        unnumbered: unnumbered.0,
    }
}

/// The degree of `m` in the atoms `is_symbol` accepts, when it is at most 1 (a linear
/// body, `v_{j,i} - e_{ijk} w_k`), else `None`.
fn degree(m: &latex::Math, is_symbol: &dyn Fn(&latex::Math) -> bool) -> Option<u8> {
    let constant = |x: &latex::Math| (degree(x, is_symbol)? == 0).then_some(0);
    match &m.kind {
        MathKind::Number(_) => Some(0),
        MathKind::Atom(_) => Some(u8::from(is_symbol(m))),
        MathKind::Sum(terms) => terms
            .iter()
            .try_fold(0, |d, (_, t)| Some(d.max(degree(t, is_symbol)?))),
        MathKind::Product(fs) => fs
            .iter()
            .try_fold(0, |d: u8, f| d.checked_add(degree(f, is_symbol)?))
            .filter(|&d| d <= 1),
        MathKind::Quotient(a, b) => {
            constant(b)?;
            degree(a, is_symbol)
        }
        MathKind::Average(a) => degree(a, is_symbol),
        MathKind::Power(a, b) => {
            constant(a)?;
            constant(b)
        }
        MathKind::Sqrt(a) | MathKind::Abs(a) | MathKind::Apply(_, a) => constant(a),
        // A derivative of a linear body is linear, but a label would have to commute
        // with it through the position: no labelled variant takes such a definition.
        MathKind::Partial { .. }
        | MathKind::Comma { .. }
        | MathKind::Matrix(_)
        | MathKind::Tuple(_) => None,
    }
}

/// Whether every term of `m` is of degree 1 in the atoms `is_symbol` accepts: linear and
/// homogeneous (`v_{j,i} - e_{ijk} w_k`, not `\delta_{ij} + u_{i,j}`, whose first-order
/// term in an expansion has no δ).
fn homogeneous(m: &latex::Math, is_symbol: &dyn Fn(&latex::Math) -> bool) -> bool {
    match &m.kind {
        MathKind::Atom(_) => is_symbol(m),
        MathKind::Sum(terms) => terms.iter().all(|(_, t)| homogeneous(t, is_symbol)),
        MathKind::Product(fs) => {
            let (one, rest): (Vec<&latex::Math>, Vec<&latex::Math>) =
                fs.iter().partition(|f| homogeneous(f, is_symbol));
            one.len() == 1 && rest.iter().all(|f| degree(f, is_symbol) == Some(0))
        }
        MathKind::Quotient(a, b) => homogeneous(a, is_symbol) && degree(b, is_symbol) == Some(0),
        MathKind::Average(a) => homogeneous(a, is_symbol),
        _ => false,
    }
}

/// Words of a sentence that linearises fields about a point ("linearise these fields
/// around the contact point"): a Taylor expansion cut after its first derivatives.
fn linearises(words: &str) -> bool {
    let words = words.to_lowercase();
    let tokens: Vec<&str> = words
        .split(|c: char| !c.is_alphanumeric() && c != '-')
        .filter(|w| !w.is_empty())
        .collect();
    // "linearise", "linearized", "linearisation"; not "nonlinearity", not "do not
    // linearise".
    let Some(at) = tokens
        .iter()
        .position(|w| w.starts_with("linearis") || w.starts_with("lineariz"))
    else {
        return false;
    };
    let negated = tokens[..at]
        .iter()
        .any(|w| matches!(*w, "not" | "no" | "without" | "never" | "nor" | "cannot"));
    !negated
        && tokens[at..]
            .iter()
            .any(|w| matches!(*w, "around" | "about"))
}

/// The fields the text linearises, in each equation that reads one (`Equation::linear`):
/// in the equations a sentence that linearises about a point leads into (that one, and
/// the displays right after it with no text between), each field written, in a
/// definition there, both with its value and with its first derivatives: a Taylor
/// expansion cut after them (`w_i^{(1)} = w_i^c - \ell_m w_{i,m}^c`). Not a defined
/// field, nor one whose second derivatives the paper writes, itself or through a
/// definition it differentiates (`L_{ij} = v_{i,j}` and `L_{ij,j}`). A strain linearised
/// about the reference configuration (`\varepsilon_{ij} = \frac12 (u_{i,j} + u_{j,i})`)
/// writes no value of its field, and linearised equations of motion define nothing:
/// neither makes a field linear. Each exact claim from the first of those equations on
/// that reads one, through definitions, assumes its second derivatives vanish.
fn linearised_fields(
    equations: &mut [Equation],
    symbols: &BTreeMap<Key, Symbol>,
    chosen: &BTreeMap<Key, (usize, BTreeSet<Key>)>,
    (normal, tensors): (Option<&str>, &Stems),
) {
    let mut fields: BTreeSet<Key> = BTreeSet::new();
    // The number of the equation the current sentence leads into, and of the first
    // that linearises a field.
    let (mut leads, mut number) = (String::new(), String::new());
    let mut first = None;
    let mut group = false;
    for (q, eq) in equations.iter().enumerate() {
        if linearises(&eq.lead_in) {
            group = true;
            leads.clone_from(&eq.number);
        } else if !eq.lead_in.trim().is_empty() {
            group = false;
        }
        if !group || eq.unread.is_some() {
            continue;
        }
        let Ok(printed) = latex::read(&eq.latex, &ReadOptions::default()) else {
            continue;
        };
        for part in &printed.parts {
            let members: Vec<&latex::Math> = part.members.iter().collect();
            let found = symbols::occurrences(&members, normal, tensors);
            let defines = members.first().and_then(|m| {
                let (k, _) = defined_symbol(m, found.first(), tensors)?;
                chosen.get(&k).filter(|(by, _)| *by == q)
            });
            if defines.is_none() {
                continue;
            }
            let valued: BTreeSet<&Key> = found
                .iter()
                .filter(|(_, s)| s.order == 0)
                .map(|(k, _)| k)
                .collect();
            for (k, s) in &found {
                let once = symbols.get(k).is_some_and(|all| all.order == 1);
                if s.order == 1 && once && valued.contains(k) && !chosen.contains_key(k) {
                    fields.insert(k.clone());
                    if first.is_none() {
                        first = Some(q);
                        number.clone_from(&leads);
                    }
                }
            }
        }
    }
    // A definition that reads the field and is differentiated in the paper writes a
    // second derivative of it.
    // (Each such definition's reach found once: a paper has at most 500 equations.)
    let differentiated: BTreeSet<&Key> = chosen
        .keys()
        .filter(|d| symbols.get(*d).is_some_and(|s| s.order > 0))
        .flat_map(|d| through(d, chosen))
        .collect();
    fields.retain(|f| !differentiated.contains(f));
    let Some(first) = first.filter(|_| !fields.is_empty()) else {
        return;
    };
    for eq in equations.iter_mut().skip(first) {
        if eq.unread.is_some() || eq.numeric {
            continue;
        }
        let seen: BTreeSet<&Key> = eq.reads.iter().flat_map(|k| through(k, chosen)).collect();
        let read: Vec<Key> = fields
            .iter()
            .filter(|f| seen.contains(f))
            .cloned()
            .collect();
        eq.linear = (read, number.clone());
    }
}

/// The labelled variants that take their unlabelled symbol's definition: the same
/// definition of the same-labelled symbols (eq. (2) at the centre of grain (1):
/// `K_{ij}^{(1)} = w_{j,i}^{(1)}`). Only for a tensor whose definition is linear and
/// homogeneous in what it reads (`linear`): a label that marks where a quantity is
/// evaluated, or a term of an expansion, commutes with it (`\frac12 e_{ij} e_{ij}` and
/// `\delta_{ij} + u_{i,j}` have no such variant). Not for a superscript that may be an
/// operation (`A^{-T}`, `A^{T}`), nor a label the paper also writes on the normal (its own
/// normal, which the definition does not rename), nor a symbol an equation states
/// something of on its left (`stated_of`: `2 K_{ij}^{(1)} = …`), nor one an equation left
/// to complete may define. A variant a field is differentiated in needs that variant to
/// be a field or defined.
#[allow(clippy::type_complexity)]
fn labelled_variants(
    symbols: &BTreeMap<Key, Symbol>,
    chosen: &BTreeMap<Key, (usize, BTreeSet<Key>)>,
    (linear, stated_of, parts): (&BTreeSet<(usize, Key)>, &BTreeSet<Key>, &[BTreeSet<Key>]),
    blocked: &BTreeMap<Key, usize>,
    normal: Option<&str>,
) -> Vec<Variant> {
    use symbols::with_label;
    let label_of = |key: &Key| symbols::label(key).to_owned();
    let mut out = Vec::new();
    for (key, s) in symbols {
        let label = label_of(key);
        if label.is_empty()
            || s.rank == 0
            || no_label(symbols, normal, &label)
            || chosen.contains_key(key)
            || blocked.contains_key(key)
            || stated_of.contains(key)
        {
            continue;
        }
        let Some(of) = with_label(key, "") else {
            continue;
        };
        let Some((q, body)) = chosen.get(&of) else {
            continue;
        };
        if body.is_empty() || !linear.contains(&(*q, of.clone())) {
            continue;
        }
        let renamed: Option<Vec<(Key, Key)>> = body
            .iter()
            .map(|y| {
                if !label_of(y).is_empty() {
                    return None;
                }
                let labelled = with_label(y, &label)?;
                let (from, to) = (symbols.get(y)?, symbols.get(&labelled)?);
                let differentiable = !from.field || to.field || chosen.contains_key(&labelled);
                (differentiable && labelled != *key).then_some((y.clone(), labelled))
            })
            .collect();
        // A label that extends one with a definition of its own (`K^{(1)c}` beside `K^{(1)}
        // = …`): which definition it takes is not clear.
        let chained = symbols.keys().any(|k| {
            let other = label_of(k);
            !other.is_empty()
                && other != label
                && label.contains(other.as_str())
                && chosen.contains_key(k)
                && with_label(k, "").as_ref() == Some(&of)
        });
        // A part that relates the variant to its would-be body alone (`w_{j,i}^{(1)} +
        // w_{i,j}^{(1)} = 2 K_{ij}^{(1)}`) states what the paper takes it to be.
        let stated = |renamed: &[(Key, Key)]| {
            parts.iter().any(|p| {
                p.contains(key)
                    && p.iter()
                        .all(|k| k == key || renamed.iter().any(|(_, to)| to == k))
            })
        };
        if let Some(renamed) = renamed.filter(|r| !chained && !stated(r)) {
            out.push(Variant {
                key: key.clone(),
                of,
                how: format!("with the label {label}"),
                renamed,
            });
        }
    }
    out
}

/// A variant's definition, `head = body`, from its unlabelled symbol's
/// (`K_ij = w_j,i` → `K1_ij = d(w1_j)/dx_i`): each symbol renamed, and a comma
/// derivative of one that is defined, not a field, written `d(…)/dx_i`.
fn relabelled(
    text: &str,
    v: &Variant,
    symbols: &BTreeMap<Key, Symbol>,
    defined: &BTreeMap<Key, (usize, BTreeSet<Key>)>,
    position: Option<&str>,
) -> Option<String> {
    use crate::lang::parser::parse_expr;
    let (head, body) = text.split_once(" = ")?;
    let head = format!(
        "{}{}",
        symbols.get(&v.key)?.name,
        head.strip_prefix(symbols.get(&v.of)?.name.as_str())?
    );
    // Language name → (its variant's name, whether that variant is defined).
    let names: BTreeMap<&str, (&str, bool)> = v
        .renamed
        .iter()
        .filter_map(|(from, to)| {
            let (a, b) = (symbols.get(from)?, symbols.get(to)?);
            Some((a.name.as_str(), (b.name.as_str(), defined.contains_key(to))))
        })
        .collect();
    let expr = parse_expr(body).ok()?;
    let mut edits: Vec<(usize, usize, String)> = Vec::new();
    relabel_walk(&expr, (&names, position), &mut edits)?;
    let mut body = body.to_owned();
    edits.sort_by_key(|(start, _, _)| std::cmp::Reverse(*start));
    for (start, end, to) in edits {
        body.get(start..end)?;
        body.replace_range(start..end, &to);
    }
    Some(format!("{head} = {body}"))
}

/// The edits (byte range, new text) that rename the symbols of `e` ([`relabelled`]);
/// `None` where a defined variant is differentiated and the file has no position.
fn relabel_walk(
    e: &crate::lang::parser::Expr,
    (names, position): (&BTreeMap<&str, (&str, bool)>, Option<&str>),
    edits: &mut Vec<(usize, usize, String)>,
) -> Option<()> {
    use crate::lang::parser::{ExprKind, IndexTok};
    let slots = |indices: &[IndexTok]| -> String { indices.iter().map(|t| t.ch).collect() };
    let renamed = |kind: &ExprKind| -> Option<(String, bool)> {
        let ExprKind::Name {
            full,
            base,
            indices,
        } = kind
        else {
            return None;
        };
        if let Some((to, def)) = names.get(full.as_str()) {
            return Some(((*to).to_owned(), *def));
        }
        let (to, def) = names.get(base.as_str()).filter(|_| !indices.is_empty())?;
        Some((format!("{to}_{}", slots(indices)), *def))
    };
    let mut go = |x: &crate::lang::parser::Expr| relabel_walk(x, (names, position), edits);
    match &e.kind {
        ExprKind::Name { .. } => {
            if let Some((to, _)) = renamed(&e.kind) {
                edits.push((e.span.start, e.span.end, to));
            }
        }
        ExprKind::Deriv {
            inner,
            indices,
            wrt: None,
        } => match renamed(&inner.kind) {
            Some((to, true)) => {
                let by = format!("d{}_{}", position?, slots(indices));
                edits.push((e.span.start, e.span.end, format!("d({to})/{by}")));
            }
            _ => go(inner)?,
        },
        ExprKind::Number(_) => {}
        ExprKind::Neg(a)
        | ExprKind::Pow(a, _)
        | ExprKind::Call(_, a)
        | ExprKind::Entry(a, _)
        | ExprKind::Deriv { inner: a, .. } => go(a)?,
        ExprKind::Add(a, b)
        | ExprKind::Sub(a, b)
        | ExprKind::Mul(a, b)
        | ExprKind::Div(a, b)
        | ExprKind::Call2(_, a, b)
        | ExprKind::Wrt {
            body: a, symbol: b, ..
        } => {
            go(a)?;
            go(b)?;
        }
        ExprKind::Matrix(rows) => rows.iter().flatten().try_for_each(go)?,
        ExprKind::MatCall(_, args) => args.iter().try_for_each(go)?,
    }
    Some(())
}

/// The number of dimensions a sentence turns to ("The invariants presented in Section
/// 3.4 assume a different form in two dimensions", "in plane strain", "In three
/// dimensions, … is instead"), if it names one. An alternative form alone ("which can be
/// written in a different form") names none: it restates the same quantity, a claim to
/// check; a sentence that names both contrasts them, and turns to neither; a number
/// named in a comparison or a negation ("as in three dimensions", "unlike plane
/// stress", "we do not consider plane strain") is no turn.
fn dimension_named(words: &str) -> Option<usize> {
    let words = format!(" {} ", words.to_lowercase().replace(['\n', '\t'], " "));
    const TWO: [&str; 13] = [
        "two dimensions",
        "two-dimensional",
        "two spatial dimensions",
        "two space dimensions",
        " 2d ",
        " 2-d ",
        "in the plane",
        "planar problem",
        "planar case",
        "plane problem",
        "plane strain",
        "plane stress",
        "plane case",
    ];
    const THREE: [&str; 7] = [
        "three dimensions",
        "three-dimensional",
        "three spatial dimensions",
        "three space dimensions",
        " 3d ",
        " 3-d ",
        "in space",
    ];
    // A comparison or a negation names a number without turning to it ("as in three
    // dimensions", "unlike the familiar plane stress solutions", "we do not consider
    // plane strain"): the three words before the phrase say so.
    const ASIDE: [&str; 15] = [
        "as",
        "like",
        "unlike",
        "than",
        "compared",
        "comparison",
        "contrary",
        "opposed",
        "versus",
        "vs",
        "not",
        "no",
        "nor",
        "without",
        "except",
    ];
    let turns = |phrase: &str| {
        words.match_indices(phrase).any(|(at, _)| {
            let before: Vec<&str> = words[..at]
                .split(|c: char| !c.is_alphanumeric())
                .filter(|w| !w.is_empty())
                .collect();
            !before.iter().rev().take(3).any(|w| ASIDE.contains(w))
        })
    };
    // Both named ("Unlike the two-dimensional case of [4], we work in space"): a
    // contrast, no turn.
    match (TWO.iter().any(|w| turns(w)), THREE.iter().any(|w| turns(w))) {
        (true, false) => Some(2),
        (false, true) => Some(3),
        _ => None,
    }
}

/// What `k` reads, through the definitions `chosen` (itself included).
fn through<'a>(k: &'a Key, chosen: &'a BTreeMap<Key, (usize, BTreeSet<Key>)>) -> BTreeSet<&'a Key> {
    let mut seen: BTreeSet<&Key> = BTreeSet::new();
    let mut stack: Vec<&Key> = vec![k];
    while let Some(k) = stack.pop() {
        if seen.insert(k) {
            stack.extend(chosen.get(k).into_iter().flat_map(|(_, body)| body));
        }
    }
    seen
}

/// Leaves to complete each equation after a sentence that turns to a number of
/// dimensions ([`dimension_named`]; the latest such sentence before it) that could be
/// read wrongly in the draft's `dimension`:
/// - after one that names another number than the draft's (the text before the
///   equation, headings included), every equation: the file has one dimension, and
///   `\delta_{kk} = 2` is true in the plane;
/// - after one that names the draft's own (the sentence that leads into the equation),
///   an equation that reads a symbol an equation before the sentence defines, directly
///   or through definitions (`2p = \sigma_{11} + \sigma_{22}` after `p =
///   \frac13\sigma_{kk}`), read with the earlier definition.
///
/// An equation that only defines new symbols (`F^* = q + r\cos\phi + p\sin\phi`)
/// states nothing to check, and stays. Whether any was left.
fn restated_in_another_form(
    equations: &mut [Equation],
    chosen: &BTreeMap<Key, (usize, BTreeSet<Key>)>,
    variants: &BTreeSet<&Key>,
    dimension: usize,
) -> bool {
    let mut scope: Option<(usize, usize)> = None;
    let mut left = false;
    for q in 0..equations.len() {
        let named = dimension_named(&equations[q].before).filter(|&d| d != dimension);
        let own = dimension_named(&equations[q].lead_in).filter(|&d| d == dimension);
        if let Some(d) = named.or(own) {
            scope = Some((q, d));
        }
        let Some((from, turned)) = scope else {
            continue;
        };
        let other = turned != dimension;
        if equations[q].unread.is_some() {
            continue;
        }
        // Reading `T` (or `T^2`) reads what defines `T^2`.
        let squares: Vec<Key> = equations[q]
            .reads
            .iter()
            .map(|k| format!("{k}^2"))
            .collect();
        let older = equations[q]
            .reads
            .iter()
            .chain(&squares)
            .flat_map(|k| through(k, chosen))
            .find_map(|k| chosen.get(k).map(|(by, _)| *by).filter(|by| *by < from));
        if older.is_none() && !other {
            continue;
        }
        // Each part `X = …`, X defined here.
        // (A labelled variant is counted with no equation: it takes its definition.)
        let defines_here = chosen
            .iter()
            .filter(|(k, (by, _))| *by == q && !variants.contains(k))
            .count();
        let pure = latex::read(&equations[q].latex, &ReadOptions::default()).is_ok_and(|p| {
            p.parts.len() == defines_here && p.parts.iter().all(|part| part.members.len() == 2)
        });
        if pure {
            continue;
        }
        let (line, number) = (equations[from].line, comment(&equations[from].number));
        let word = |d: usize| if d == 2 { "two" } else { "three" };
        let mut why = format!(
            "the text before equation ({number}), line {line}, turns to {} dimensions",
            word(turned)
        );
        if other {
            why.push_str(&format!(", while the draft has {}", word(dimension)));
        }
        if let Some(by) = older {
            why.push_str(&format!(
                ", and this equation reads what {} defines before it",
                equations[by].id
            ));
        }
        let eq = &mut equations[q];
        eq.unread = Some(why);
        eq.edit = Some(format!(
            "draft the text from line {line} on by itself (with `--dimension`), or give this claim its own definitions"
        ));
        left = true;
    }
    left
}

/// The clause after the last `\text{with}` of a display (`\ell_i = R_g n_i`), when it is
/// one equation that reads on its own, `X_i = …`, of a symbol with index slots the rest
/// of the display writes (`2\ell_i`): it says what that symbol is. A clause of a symbol
/// the rest does not write, or of a scalar (`(\sigma(r) n)_i = 0 \quad\text{with}\quad r
/// = c + h`), may say where the equation holds, and defines nothing.
fn with_clause(latex: &str) -> Option<&str> {
    let word = "\\text{with}";
    let start = latex.rfind(word)?;
    let mut tail = latex[start + word.len()..].trim_start();
    while let Some(rest) = ["\\quad", "\\qquad", "\\;", ","]
        .iter()
        .find_map(|s| tail.strip_prefix(s))
    {
        tail = rest.trim_start();
    }
    let tail = tail.trim_end().trim_end_matches(['.', ',']).trim_end();
    let read = latex::read(tail, &ReadOptions::default()).ok()?;
    let [part] = &read.parts[..] else { return None };
    let MathKind::Atom(defined) = &part.members.first()?.kind else {
        return None;
    };
    // A scalar may be where the equation is evaluated (`\sigma(r) n = 0 \quad\text{with}
    // \quad r = c + h`); a clause defines a symbol with index slots only.
    if !defined
        .sub
        .as_ref()
        .is_some_and(|s| s.text.chars().any(|c| c.is_ascii_alphabetic()))
    {
        return None;
    }
    let head = &latex[..start];
    // A command (`\ell`) starts a token whatever precedes it (`2\ell_i`).
    let written = match defined.base.strip_prefix('\\') {
        Some(_) => head.match_indices(defined.base.as_str()).any(|(at, b)| {
            !head[at + b.len()..]
                .chars()
                .next()
                .is_some_and(|c| c.is_ascii_alphabetic())
        }),
        None => mentions(head, &defined.base),
    };
    (part.relations[..] == [latex::Rel::Eq] && written).then_some(tail)
}

/// The first message of a loader's refusal.
fn first_message(e: &super::LoadError) -> Option<String> {
    match e {
        super::LoadError::Invalid(ds) => ds.first().map(|d| d.message.clone()),
        _ => None,
    }
}

/// Marks the claims the loader's diagnostics point into as to complete; `false` when
/// none of them is a claim's.
fn refuse_claims(
    toml: &str,
    e: &super::LoadError,
    equations: &mut [Equation],
    rounds: &mut Rounds,
) -> bool {
    let super::LoadError::Invalid(ds) = e else {
        return false;
    };
    let owners = line_owners(toml);
    let mut moved = false;
    for d in ds {
        let text_line = owners
            .get(&d.line)
            .and_then(|o| o.strip_prefix("the text, line "))
            .and_then(|l| l.parse().ok());
        if let Some(line) = text_line {
            moved |= rounds.refused_text.insert(line);
            continue;
        }
        let Some(id) = owners.get(&d.line) else {
            // A declaration the loader refuses (`'c_abcdefghijk'`): the claims that read
            // the symbol it declares.
            let Some(names) = declared_at(toml, d.line, d.col) else {
                continue;
            };
            for eq in equations.iter_mut().filter(|q| q.unread.is_none()) {
                if names.iter().any(|n| eq.names.contains(n)) {
                    eq.unread = Some(d.message.clone());
                    eq.edit.clone_from(&d.help);
                    moved = true;
                }
            }
            continue;
        };
        // A definition whose left side carries indices its right side lacks
        // (`t_i^{(n)} = t_i n_i`): once, its subscript is read as stray.
        let stray_index = d.message.contains(super::load::DEFINED_WITH_INDICES)
            && d.message.ends_with("free indices none");
        if let Some(eq) = equations
            .iter_mut()
            .find(|q| &q.id == id && q.unread.is_none())
        {
            let stems: Vec<String> = eq
                .defines
                .iter()
                .filter_map(|(k, _)| symbols::tensor_stem(k))
                .collect();
            // A chain whose members carry different free indices as printed
            // (`t_i = … = \sigma_{ki} n_k (\delta_{il} - n_i n_l)`): once, it is checked as
            // printed, for every value of each.
            // Only where an index is certain: with single-letter subscripts alone
            // (`\sigma_n + \tau_n = R`) the letter may label, and the equation is left
            // to complete rather than accused.
            let different = d.message.starts_with(super::load::DIFFERENT_FREE_INDICES);
            if different && !eq.verbatim && indexed(&eq.latex) {
                eq.verbatim = true;
                moved = true;
                continue;
            }
            if different && !eq.verbatim {
                eq.unread = Some(format!(
                    "{}; every subscript is one letter, which may label (the normal stress σ_n) rather than index",
                    d.message
                ));
                eq.edit = Some("declare each labelled symbol as a scalar with a notation entry (`'\\sigma_{n}' = 'sigma_n'`), or write its indices".to_owned());
                moved = true;
                continue;
            }
            if stray_index && !stems.is_empty() {
                let before = rounds.stray.len();
                rounds.stray.extend(stems);
                if rounds.stray.len() > before {
                    moved = true;
                    continue;
                }
            }
            eq.unread = Some(d.message.clone());
            eq.edit.clone_from(&d.help);
            moved = true;
        }
    }
    moved
}

/// The names the quoted declaration at `line`:`col` (1-based) of a drafted file may
/// declare: `'c_abcd'` declares `c`, `'R_g'` itself.
fn declared_at(toml: &str, line: usize, col: usize) -> Option<Vec<String>> {
    let text = toml.lines().nth(line.checked_sub(1)?)?;
    let chars: Vec<char> = text.chars().collect();
    let at = col.checked_sub(1)?.min(chars.len().checked_sub(1)?);
    let start = chars[..=at].iter().rposition(|&c| c == '\'')?;
    let end = start + 1 + chars[start + 1..].iter().position(|&c| c == '\'')?;
    let token: String = chars[start + 1..end].iter().collect();
    let stem = token.split('_').next().unwrap_or("").to_owned();
    Some(vec![token, stem])
}

/// The claim line `line` of a drafted file belongs to: its `[[claim]]` table, or a
/// definition it states.
pub fn owner(toml: &str, line: usize) -> Option<String> {
    line_owners(toml).remove(&line)
}

/// Which claim each line of a drafted file belongs to: its `[[claim]]` table, and the
/// definitions it states (marked `# from eqN`).
fn line_owners(toml: &str) -> BTreeMap<usize, String> {
    let mut out = BTreeMap::new();
    let mut current: Option<String> = None;
    for (k, line) in toml.lines().enumerate() {
        let n = k + 1;
        if line.starts_with("[[claim]]") {
            current = None;
        }
        if let Some(id) = line
            .strip_prefix("id = \"")
            .and_then(|r| r.strip_suffix('"'))
        {
            current = Some(id.to_owned());
            // The table's first line belongs to it too.
            out.insert(n - 1, id.to_owned());
        }
        // A definition's line (`  'X = …',  # from eqN`); a printed string that says
        // "# from" is not one.
        let definition = line.starts_with("  ") && !line.starts_with("  #");
        if let Some(id) = line
            .rsplit_once("# from ")
            .filter(|_| definition)
            .map(|(_, id)| id.trim())
        {
            out.insert(n, id.to_owned());
        } else if let Some(id) = &current {
            out.insert(n, id.clone());
        }
    }
    out
}

/// The symbol an equation the reader cannot read may define: its text before the first
/// `=` outside braces, when that reads as one symbol alone (or its square).
fn left_symbol(latex_text: &str, normal: Option<&str>, tensors: &Stems) -> Option<Key> {
    let mut depth = 0i32;
    let at = latex_text.char_indices().find_map(|(i, c)| {
        match c {
            '{' => depth += 1,
            '}' => depth -= 1,
            '=' if depth == 0 => return Some(i),
            _ => {}
        }
        None
    })?;
    let left = latex::read(&latex_text[..at], &ReadOptions::default()).ok()?;
    let [part] = &left.parts[..] else { return None };
    let [first] = &part.members[..] else {
        return None;
    };
    let found = symbols::occurrences(&[first], normal, tensors);
    if found.len() != 1 {
        return None;
    }
    defined_symbol(first, found.first(), tensors).map(|(k, _)| k)
}

/// The index letters of a defined symbol as its defining member writes them.
fn formal_of(member: &latex::Math, rank: usize) -> Vec<char> {
    let atom = match &member.kind {
        MathKind::Atom(a) => Some(a),
        MathKind::Power(b, _) => match &b.kind {
            MathKind::Atom(a) => Some(a),
            _ => None,
        },
        _ => None,
    };
    if rank == 0 {
        return Vec::new();
    }
    atom.and_then(|a| a.sub.as_ref())
        .map(|t| t.text.chars().filter(char::is_ascii_alphabetic).collect())
        .unwrap_or_default()
}

/// Whether `latex` has the printed symbol `symbol` as a token of its own (`a` in
/// `a = b`, not in `\frac` or `ab`).
fn mentions(latex: &str, symbol: &str) -> bool {
    let word = |c: Option<char>| c.is_some_and(|c| c.is_ascii_alphanumeric() || c == '\\');
    !symbol.is_empty()
        && latex.match_indices(symbol).any(|(at, _)| {
            !word(latex[..at].chars().next_back())
                && !word(latex[at + symbol.len()..].chars().next())
        })
}

/// Whether `body` reads `key`, directly or through the definitions `chosen`.
fn leads_to(
    body: &BTreeSet<Key>,
    key: &Key,
    chosen: &BTreeMap<Key, (usize, BTreeSet<Key>)>,
) -> bool {
    let mut stack: Vec<&Key> = body.iter().collect();
    let mut visited: BTreeSet<&Key> = BTreeSet::new();
    while let Some(k) = stack.pop() {
        if k == key {
            return true;
        }
        if visited.insert(k) {
            if let Some((_, b)) = chosen.get(k) {
                stack.extend(b.iter());
            }
        }
    }
    false
}

/// "Let $n$ be the unit normal", "the unit normal vector $\mathbf{n}$": the letter of the
/// unit normal the source's text names beside the words "unit normal" (or "unit vector",
/// for the letter n), if it names one and only one. Read as a plain vector, n·n = 1 is lost, and
/// true equations that need it would fail.
fn normal_in(source: &str, markdown: bool) -> Option<String> {
    let text = displays::live(source, markdown);
    // The words in any case; the formulas as written (`N` is not `n`). An ASCII
    // lowercase keeps every byte offset.
    let lower = text.to_ascii_lowercase();
    let mut found = BTreeSet::new();
    for phrase in ["unit normal", "unit vector"] {
        for (at, _) in lower.match_indices(phrase) {
            // Whole words only: not "non-unit normal", "community", "normalisation",
            // "unit vectors" (a count of them).
            let prior = lower[..at].chars().next_back();
            let next = lower[at + phrase.len()..].chars().next();
            if prior.is_some_and(|c| c.is_alphanumeric() || c == '-')
                || next.is_some_and(char::is_alphanumeric)
            {
                continue;
            }
            // The inline formula just after the words.
            let before = text[..at].trim_end();
            let after = text[at + phrase.len()..].trim_start();
            let after = after
                .get(..6)
                .filter(|w| w.eq_ignore_ascii_case("vector"))
                .map_or(after, |_| &after[6..])
                .trim_start();
            let candidates = [
                after
                    .strip_prefix('$')
                    .and_then(|a| a.find('$').map(|k| &a[..k])),
                after
                    .strip_prefix("\\(")
                    .and_then(|a| a.find("\\)").map(|k| &a[..k])),
            ];
            // "The unit vector e_i along axis i" names no normal: a unit vector is one
            // only when it is written n.
            let takes = |letter: &String| phrase == "unit normal" || letter == "n";
            for formula in candidates.into_iter().flatten() {
                if let Some(letter) = vector_letter(formula).filter(takes) {
                    found.insert(letter);
                }
            }
            // "Let $n$ be the unit normal", "where $n$ is a unit vector": the formula
            // before the verb.
            let lead = VERBS.iter().find_map(|verb| {
                let k = before.len().checked_sub(verb.len())?;
                let w = before.get(k..)?;
                let word_start = before[..k].ends_with(char::is_whitespace);
                (w.eq_ignore_ascii_case(verb) && word_start).then_some(k)
            });
            if let Some(b) = lead
                .map(|k| before[..k].trim_end())
                .and_then(|b| b.strip_suffix('$'))
            {
                if let Some(letter) = b
                    .rfind('$')
                    .and_then(|k| vector_letter(&b[k + 1..]))
                    .filter(takes)
                {
                    found.insert(letter);
                }
            }
        }
    }
    // "with $n_k n_k = 1$", "$|\mathbf{n}| = 1$": a vector of unit length, written n.
    for f in displays::inline_formulas(source, markdown) {
        if let Some(letter) = unit_length(&f.body).filter(|l| l == "n") {
            found.insert(letter);
        }
    }
    match found.len() {
        1 => found.into_iter().next(),
        _ => None,
    }
}

/// The words between a vector and "unit normal" or "unit vector" that say it is one.
const VERBS: [&str; 8] = [
    "be the",
    "is the",
    "be a",
    "is a",
    "denotes the",
    "denotes a",
    "denote the",
    "denote a",
];

/// The letter of a vector an inline formula says is of unit length: `n_k n_k = 1`,
/// `|n| = 1`, `\|\mathbf{n}\| = 1`, `n \cdot n = 1`.
fn unit_length(formula: &str) -> Option<String> {
    let f: String = formula.chars().filter(|c| !c.is_whitespace()).collect();
    let (left, right) = f.split_once('=')?;
    if right != "1" {
        return None;
    }
    let norm = ["\\|", "|", "\\lVert", "\\lvert", "\\left|", "\\left\\|"]
        .iter()
        .find_map(|open| {
            let inner = left.strip_prefix(open)?;
            ["\\|", "|", "\\rVert", "\\rvert", "\\right|", "\\right\\|"]
                .iter()
                .find_map(|close| inner.strip_suffix(close))
        });
    if let Some(v) = norm {
        return vector_letter(v);
    }
    if let Some((a, b)) = left.split_once("\\cdot") {
        return (a == b).then(|| vector_letter(a)).flatten();
    }
    // x_k x_k, x_{k}x_{k}: one letter with one index, twice.
    let half = left.len() / 2;
    let (a, b) = (left.get(..half)?, left.get(half..)?);
    let indexed = a.contains('_');
    (a == b && indexed)
        .then(|| vector_letter_any_index(a))
        .flatten()
}

/// `n_q` or `n_{q}` for any one index letter q: the vector's letter.
fn vector_letter_any_index(f: &str) -> Option<String> {
    let (v, index) = f.split_once('_')?;
    let index = index.trim_start_matches('{').trim_end_matches('}');
    let one = index.len() == 1 && index.chars().all(|c| c.is_ascii_lowercase());
    one.then(|| vector_letter(v)).flatten()
}

/// `n`, `n_i`, `n_{i}`, `\mathbf{n}`, `\boldsymbol{n}`, `\bm{n}`: the one Latin letter of a
/// vector written alone.
fn vector_letter(formula: &str) -> Option<String> {
    let mut f = formula.trim();
    for font in ["\\mathbf{", "\\boldsymbol{", "\\bm{", "\\vec{"] {
        if let Some(inner) = f.strip_prefix(font).and_then(|r| r.strip_suffix('}')) {
            f = inner.trim();
        }
    }
    let f = f
        .strip_suffix("_i")
        .or_else(|| f.strip_suffix("_{i}"))
        .or_else(|| f.strip_suffix("_k"))
        .or_else(|| f.strip_suffix("_{k}"))
        .unwrap_or(f);
    let mut chars = f.chars();
    match (chars.next(), chars.next()) {
        (Some(c), None) if c.is_ascii_lowercase() => Some(c.to_string()),
        _ => None,
    }
}

/// "indices ranging from 1 to 3", "i = 1, 2, 3", "i, j = 1, 2": the index range the
/// source's text states (comments and other dead text left out), if it states one and
/// only one.
fn dimension_in(source: &str, markdown: bool) -> Option<usize> {
    let lower = displays::live(source, markdown).to_lowercase();
    let mut found = BTreeSet::new();
    // Sentence by sentence: words name a range only in a sentence about indices ("the
    // load steps run from 1 to 2" is not one); `i = 1, 2, 3` is one wherever it stands.
    for sentence in lower.split(['.', ';']) {
        let about_indices = sentence.contains("ind") || sentence.contains("subscript");
        let mut phrases = vec!["= 1, 2, ", "= 1,2,"];
        if about_indices {
            phrases.extend(["from 1 to ", "values 1, 2, ", "values 1,2,"]);
        }
        for phrase in phrases {
            for (at, _) in sentence.match_indices(phrase) {
                match sentence[at + phrase.len()..].chars().next() {
                    Some('2') if phrase.starts_with("from") => {
                        found.insert(2);
                    }
                    Some('3') => {
                        found.insert(3);
                    }
                    _ => {}
                }
            }
        }
        for phrase in ["= 1, 2$", "= 1,2$", "= 1, 2 ", "= 1,2 "] {
            if sentence.contains(phrase) || sentence.trim_end().ends_with(phrase.trim_end()) {
                found.insert(2);
            }
        }
        // "indices range over 1 and 2", "take the values 1, 2": two values, not three.
        if about_indices {
            for phrase in ["1 and 2", "1, 2", "1,2"] {
                for (at, _) in sentence.match_indices(phrase) {
                    let next = sentence[at + phrase.len()..].trim_start_matches([',', ' ']);
                    let third = ["3", "and 3", "or 3"].iter().any(|t| next.starts_with(t));
                    let before = sentence[..at].trim_end();
                    if !third && !before.ends_with("from") && !before.ends_with('=') {
                        found.insert(2);
                    }
                }
            }
        }
        // Another range named in a sentence about indices makes the text ambiguous
        // ("Latin indices take the values 1, 2, 3; Greek ones range from 1 to 2"): no
        // dimension is read then.
        if about_indices
            && ["1, 2, 3", "1,2,3", "1, 2 and 3"]
                .iter()
                .any(|p| sentence.contains(p))
        {
            found.insert(3);
        }
    }
    match found.len() {
        1 => found.into_iter().next(),
        _ => None,
    }
}

/// Writes the file for the equations as they stand, reading each one (which sets what
/// it reads and defines, or why it is to complete); `None` when a definition could not
/// be read, which changes what the others read: write again.
fn write(
    label: &str,
    equations: &mut [Equation],
    (dimension, normal): (usize, Option<&str>),
    unnumbered: (usize, usize),
    (prose, said): (&[displays::Inline], Option<&mut Option<Vec<Said>>>),
    rounds: &mut Rounds,
) -> Option<String> {
    let Rounds {
        refused_text,
        stray,
        vectors,
        incompressible,
        symmetric,
        text,
    } = rounds;
    // Pass 1: the symbols each equation reads, and the candidates for definitions: a
    // chain `X = …` (or `X^2 = …`) with X alone on the left and nowhere else in it.
    let mut symbols: BTreeMap<Key, Symbol> = BTreeMap::new();
    let mut order: Vec<Key> = Vec::new();
    let mut candidates: Vec<Candidate> = Vec::new();
    // Numbered definitions whose body is linear in the symbols it reads (`K_{ij} =
    // w_{j,i}`), by equation and symbol: a labelled variant follows them
    // ([`labelled_variants`]).
    let mut linear: BTreeSet<(usize, Key)> = BTreeSet::new();
    // Symbols some equation states something of on its left, not alone (`2
    // K_{ij}^{(1)} = …`): what the paper says of them, which a labelled variant's
    // definition would override.
    let mut on_the_left: BTreeSet<Key> = BTreeSet::new();
    // The symbols of each part of each equation read.
    let mut part_reads: Vec<BTreeSet<Key>> = Vec::new();
    // Equations left to complete that the reader cannot read: what they define is
    // unknown, so a symbol they mention is defined by no later equation.
    let mut opaque: Vec<(usize, String)> = Vec::new();
    let options = ReadOptions::default();
    // Pass 0: the symbols that carry index slots anywhere (read or left to complete),
    // and those printed bare somewhere, which a stray subscript may stand for.
    let mut bare: BTreeSet<String> = BTreeSet::new();
    let tensor_stems: BTreeSet<String> = equations
        .iter()
        .filter_map(|eq| latex::read(&eq.latex, &options).ok())
        .flat_map(|p| {
            p.parts
                .iter()
                .flat_map(|part| {
                    let members: Vec<&latex::Math> = part.members.iter().collect();
                    let first = Stems {
                        vectors: vectors.clone(),
                        ..Stems::default()
                    };
                    symbols::occurrences(&members, normal, &first)
                })
                .filter(|(_, s)| !s.component)
                .inspect(|(k, _)| {
                    if let Some(stem) = k.strip_suffix("||0") {
                        bare.insert(stem.to_owned());
                    }
                })
                .filter_map(|(k, _)| symbols::tensor_stem(&k))
                .collect::<Vec<_>>()
        })
        .collect();
    let tensors = Stems {
        tensors: tensor_stems,
        stray: stray.intersection(&bare).cloned().collect(),
        vectors: vectors.clone(),
    };
    // Symbols that an equation left to complete has alone on a left side: it may define
    // them, so no later equation does. Symbols met other than squared (`T`, not `T^2`):
    // their squares are no symbols of their own.
    let mut blocked: BTreeMap<Key, usize> = BTreeMap::new();
    // An equation the reader cannot read may define its lone left side.
    let block_left = |blocked: &mut BTreeMap<Key, usize>, q: usize, text: &str| {
        if let Some(k) = left_symbol(text, normal, &tensors) {
            blocked.entry(k).or_insert(q);
        }
    };
    // Symbols a sentence of the text sets equal to something (`$J_2 = …$`) before an
    // equation that would define them: the text's own meaning may differ from the
    // equation's, which is then a claim about them, not their definition.
    // (A second name for the symbol, `$f_i^{(2,1)c} = f_i^c$`, says nothing of its value.)
    // (The same equation said in a sentence first, `$A_{ik} = C_{ijkl} n_j n_l$`, is no
    // other meaning: the display still defines it.)
    let spaceless = |t: &str| t.chars().filter(|c| !c.is_whitespace()).collect::<String>();
    let mut in_prose: BTreeMap<Key, (usize, BTreeSet<String>)> = BTreeMap::new();
    let equalities = prose.iter().filter(|f| f.body.contains('='));
    for (line, text) in equalities.map(|f| (&f.line, &f.body)) {
        let alias = text.split_once('=').is_some_and(|(_, right)| {
            latex::read(right, &options).is_ok_and(|r| {
                matches!(&r.parts[..], [part] if matches!(&part.members[..], [m] if second_name(m)))
            })
        });
        if alias {
            continue;
        }
        if let Some(k) = left_symbol(text, normal, &tensors) {
            let said = in_prose.entry(k).or_insert((*line, BTreeSet::new()));
            said.1.insert(spaceless(text));
        }
    }
    let mut plain: BTreeSet<Key> = BTreeSet::new();
    // The symbols each equation left to complete mentions: it may tie them.
    let mut open: BTreeMap<Key, usize> = BTreeMap::new();
    for (q, eq) in equations.iter_mut().enumerate() {
        eq.reads.clear();
        eq.defines.clear();
        eq.stray.clear();
        eq.introduces.clear();
        eq.differentiated.clear();
        if eq.unread.is_some() {
            if let Ok(p) = latex::read(&eq.latex, &options) {
                for part in &p.parts {
                    let members: Vec<&latex::Math> = part.members.iter().collect();
                    let found = symbols::occurrences(&members, normal, &tensors);
                    for (k, _) in &found {
                        open.entry(k.clone()).or_insert(q);
                    }
                    plain.extend(
                        found
                            .iter()
                            .filter(|(_, s)| !s.squared)
                            .map(|(k, _)| k.clone()),
                    );
                    if let Some(first) = members.first() {
                        if let Some((k, _)) = defined_symbol(first, found.first(), &tensors) {
                            blocked.entry(k).or_insert(q);
                        }
                    }
                }
            } else {
                opaque.push((q, eq.latex.clone()));
                block_left(&mut blocked, q, &eq.latex);
            }
            continue;
        }
        let printed = match latex::read(&eq.latex, &options) {
            Ok(p) => p,
            Err(e) => {
                opaque.push((q, eq.latex.clone()));
                block_left(&mut blocked, q, &eq.latex);
                let col = latex::column(&eq.latex, e.span.start);
                eq.unread = Some(format!("cannot read column {col}: {}", e.message));
                continue;
            }
        };
        // `(\sigma_{ij} n_j)_{,i}`: the normal differentiated, a field or a constant?
        let normal_varies = printed.parts.iter().any(|part| {
            part.members
                .iter()
                .any(|m| symbols::differentiates_normal(m, normal))
        });
        if normal_varies {
            eq.unread = Some(
                "the normal is differentiated inside a bracket with a comma: a field of the position or a constant?"
                    .to_owned(),
            );
            eq.edit = Some("expand the derivative, writing the normal's own derivative".to_owned());
            continue;
        }
        let doubt = printed.parts.iter().find_map(|part| {
            let members: Vec<&latex::Math> = part.members.iter().collect();
            symbols::occurrences(&members, normal, &tensors)
                .into_iter()
                .find_map(|(_, s)| s.doubt)
        });
        if let Some(why) = doubt {
            eq.unread = Some(why);
            opaque.push((q, eq.latex.clone()));
            block_left(&mut blocked, q, &eq.latex);
            continue;
        }
        for part in &printed.parts {
            let members: Vec<&latex::Math> = part.members.iter().collect();
            let found = symbols::occurrences(&members, normal, &tensors);
            for (key, s) in found.iter().cloned() {
                eq.reads.insert(key.clone());
                if s.differentiated {
                    eq.differentiated.insert(key.clone());
                }
                if !s.squared {
                    plain.insert(key.clone());
                }
                let entry = symbols.entry(key.clone()).or_insert_with(|| {
                    order.push(key.clone());
                    s.clone()
                });
                entry.field |= s.field;
                entry.order = entry.order.max(s.order);
                entry.derivatives.extend(s.derivatives.iter().cloned());
                entry.printed.extend(s.printed.iter().cloned());
                entry.entry |= s.entry;
                if s.stray {
                    eq.stray.insert(s.key.0.clone());
                }
            }
            part_reads.push(found.iter().map(|(k, _)| k.clone()).collect());
            if members.len() > 1 {
                on_the_left.extend(
                    symbols::occurrences(&members[..1], normal, &tensors)
                        .into_iter()
                        .map(|(k, _)| k),
                );
            }
            if part.relations.first() != Some(&latex::Rel::Eq) || members.len() < 2 {
                continue;
            }
            let Some((key, square)) = defined_symbol(members[0], found.first(), &tensors) else {
                continue;
            };
            let body: BTreeSet<Key> = symbols::occurrences(&members[1..], normal, &tensors)
                .into_iter()
                .map(|(k, _)| k)
                .collect();
            if body.contains(&key) {
                continue;
            }
            if let Some(s) = square {
                symbols.entry(key.clone()).or_insert_with(|| {
                    order.push(key.clone());
                    s
                });
            }
            let text = eq
                .latex
                .get(members[0].span.start..members[0].span.end)
                .unwrap_or("")
                .trim()
                .to_owned();
            let is_symbol =
                |m: &latex::Math| !symbols::occurrences(&[m], normal, &tensors).is_empty();
            // A body that reads the normal is not taken over by a label: a labelled
            // world may have a normal of its own, under any letter.
            let reads_normal = normal.is_some_and(|n| {
                eq.latex
                    .get(members[1].span.start..members[1].span.end)
                    .is_none_or(|body| mentions(body, n))
            });
            if members.len() == 2 && !reads_normal && homogeneous(members[1], &is_symbol) {
                linear.insert((q, key.clone()));
            }
            candidates.push(Candidate {
                q,
                key,
                body,
                text,
                stated: None,
            });
        }
    }
    // Symbols a numbered equation has alone on its left: defined there, not by the text.
    let numbered: BTreeSet<Key> = candidates.iter().map(|c| c.key.clone()).collect();
    candidates.extend(stated_definitions(
        equations,
        (prose, &*refused_text, text),
        (&symbols, &open, &in_prose, &numbered),
        (normal, &tensors),
    ));
    candidates.extend(components_stated(
        equations,
        (prose, &*refused_text, text),
        (&symbols, &open, &numbered),
        (dimension, normal, &tensors),
    ));
    // A decomposition `A = B + C` of a symbol read before defines B, not A.
    let instead: BTreeSet<(usize, Key)> = candidates
        .iter()
        .filter_map(|c| Some((c.q, c.stated.as_ref()?.instead_of.clone()?)))
        .collect();
    // (The square of such a symbol too: "$\sigma_e^2 = …$, with $\sigma_e = \sqrt{3J_2}$".)
    candidates.retain(|c| {
        let of = c.key.strip_suffix("^2").unwrap_or(&c.key).to_owned();
        c.stated.is_some() || !instead.contains(&(c.q, of))
    });
    // A definition the text states comes before the equation that follows it.
    candidates.sort_by_key(|c| (c.q, c.stated.as_ref().is_none_or(|s| s.line.is_none())));
    // The first candidate of each symbol defines it, unless its body leads back to it
    // through the definitions chosen before.
    let mut chosen: BTreeMap<Key, (usize, BTreeSet<Key>)> = BTreeMap::new();
    let mut stated: BTreeMap<Key, Stated> = BTreeMap::new();
    // Symbols whose square an equation states alone on its left (`T^2 = …` where the
    // paper writes `T` too): the first such equation of each.
    let mut squares: BTreeMap<Key, usize> = BTreeMap::new();
    // Symbols some equation (or sentence) may define: the square of one of them is its
    // square, never a symbol of its own.
    let candidate_keys: BTreeSet<Key> = candidates.iter().map(|c| c.key.clone()).collect();
    for Candidate {
        q,
        key,
        body,
        text,
        stated: by,
    } in candidates
    {
        let before = |k: &str| {
            blocked.get(k).is_some_and(|&b| b < q)
                || opaque
                    .iter()
                    .any(|(o, latex)| *o < q && mentions(latex, &text))
        };
        let base = key.strip_suffix("^2");
        // `T^2 = \langle … \rangle` beside `\sqrt{2}T`, where no equation defines T:
        // the square is defined, T stays a symbol of its own, tied by that equation.
        let plain_base = base.is_some_and(|b| plain.contains(b) || before(b));
        let square_of_plain =
            base.is_some_and(|b| before(b) || (plain.contains(b) && candidate_keys.contains(b)));
        // Said of the symbol, or of its base for a square (`$q = \sqrt{3J_2}$` before
        // `q^2 = …`).
        let said_before = by.is_none()
            && [Some(key.as_str()), base].into_iter().flatten().any(|k| {
                in_prose.get(k).is_some_and(|(line, texts)| {
                    *line < equations[q].line && !texts.contains(&spaceless(&equations[q].latex))
                })
            });
        if let Some(b) = base.filter(|_| plain_base && by.is_none()) {
            squares.entry(b.to_owned()).or_insert(q);
        }
        if chosen.contains_key(&key)
            || before(&key)
            || said_before
            || square_of_plain
            || leads_to(&body, &key, &chosen)
        {
            continue;
        }
        if let Some(by) = by {
            stated.insert(key.clone(), by);
        }
        chosen.insert(key, (q, body));
    }
    let variants = labelled_variants(
        &symbols,
        &chosen,
        (&linear, &on_the_left, &part_reads),
        &blocked,
        normal,
    );
    for v in &variants {
        let body = v.renamed.iter().map(|(_, to)| to.clone()).collect();
        chosen.insert(v.key.clone(), (chosen[&v.of].0, body));
    }
    let mut variants = variants;
    let analogies = {
        let excluded = |k: &Key| blocked.contains_key(k);
        let said = |k: &Key| in_prose.contains_key(k);
        let context = analogy::Context {
            equations,
            prose,
            refused: refused_text,
            excluded: &excluded,
            said: &said,
            normal,
            tensors: &tensors,
        };
        analogy::by_analogy(&context, &mut symbols, &mut order, &mut chosen, &mut stated)
    };
    for v in analogies {
        let body = v.renamed.iter().map(|(_, to)| to.clone()).collect();
        chosen.insert(v.key.clone(), (chosen[&v.of].0, body));
        variants.push(v);
    }
    linearised_fields(equations, &symbols, &chosen, (normal, &tensors));
    // A square that defines nothing is its base times itself (`x^2` after `x = 1`),
    // not a symbol of its own that no equation ties to its base.
    symbols.retain(|k, _| !k.ends_with("^2") || chosen.contains_key(k));
    order.retain(|k| symbols.contains_key(k));
    let mut defined: BTreeMap<Key, String> = BTreeMap::new();
    for (key, (q, _)) in &chosen {
        if let Some(line) = stated.get(key).and_then(|s| s.line) {
            defined.insert(key.clone(), format!("the text, line {line}"));
            continue;
        }
        let eq = &mut equations[*q];
        eq.defines.push((key.clone(), String::new()));
        defined.insert(key.clone(), eq.id.clone());
    }
    // A symbol that an equation left to complete may define, and that no equation
    // read defines, is unknown after that equation: so is every definition stated
    // after it whose body reads one. An equation further on that reads an unknown is
    // left to complete as well, or its verdict would be about an independent symbol
    // that the paper ties down where it was not read.
    let mut unknown: BTreeMap<Key, usize> = blocked
        .iter()
        .filter(|(k, _)| !defined.contains_key(*k))
        .map(|(k, &q)| (k.clone(), q))
        .collect();
    loop {
        let before = unknown.len();
        for (k, (q, body)) in &chosen {
            let root = body
                .iter()
                .filter_map(|b| unknown.get(b))
                .find(|&&b| b < *q);
            if let Some(&b) = root {
                unknown.entry(k.clone()).or_insert(b);
            }
        }
        if unknown.len() == before {
            break;
        }
    }
    let ids: Vec<String> = equations.iter().map(|e| e.id.clone()).collect();
    let variant_keys: BTreeSet<&Key> = variants.iter().map(|v| &v.key).collect();
    let mut left = restated_in_another_form(equations, &chosen, &variant_keys, dimension);
    // `(E u_{i,j})_{,j}` where the paper never writes a derivative of E: a field, or a
    // constant whose derivative is 0? The reader does not guess.
    for eq in equations.iter_mut().filter(|e| e.unread.is_none()) {
        let constant = eq
            .differentiated
            .iter()
            .filter(|k| !chosen.contains_key(*k))
            .find_map(|k| symbols.get(k).filter(|s| !s.field));
        if let Some(s) = constant {
            eq.unread = Some(format!(
                "`{}` is differentiated inside a bracket with a comma, and the paper writes no derivative of it elsewhere: a field or a constant?",
                s.key.0
            ));
            eq.edit = Some(
                "declare it among the fields (`fields`) if it varies with the position, or expand the derivative".to_owned(),
            );
            left = true;
        }
    }
    for (q, eq) in equations.iter_mut().enumerate() {
        if eq.unread.is_some() {
            continue;
        }
        // Reading `T` (or `T^2`) reads what defines `T^2`.
        let first = eq.reads.iter().find_map(|k| {
            [k.clone(), format!("{k}^2")]
                .into_iter()
                .find_map(|key| unknown.get_key_value(&key).filter(|(_, &b)| b < q))
                .map(|(key, &b)| (key.clone(), b))
        });
        if let Some((k, b)) = first {
            // A square that defines nothing is no symbol: it is printed as its base's.
            let printed = symbols.get(&k).map_or_else(
                || {
                    k.strip_suffix("^2")
                        .and_then(|b| symbols.get(b))
                        .map_or_else(|| k.clone(), |s| format!("{}^2", s.key.0))
                },
                |s| s.key.0.clone(),
            );
            eq.unread = Some(format!(
                "it reads `{printed}`, which {} may define, and that is still to complete",
                ids[b]
            ));
            eq.edit = Some(format!(
                "complete {} first (or define `{printed}` yourself)",
                ids[b]
            ));
            left = true;
        }
    }
    if left {
        return None;
    }
    let defined_keys: BTreeSet<Key> = defined.keys().cloned().collect();
    symbols::unique_names(&mut symbols, &order, &defined_keys);
    let tied = match said {
        Some(cache) => {
            let said = cache.get_or_insert_with(|| said_in_text(prose, normal, &tensors));
            // A definition of the text is an equation of the file, not a reason.
            let text_lines: BTreeSet<usize> = stated.values().filter_map(|s| s.line).collect();
            let said: Vec<&Said> = said
                .iter()
                .filter(|f| !text_lines.contains(&f.line))
                .collect();
            let by_law: BTreeSet<&Key> = stated
                .iter()
                .filter(|(_, s)| s.law)
                .map(|(k, _)| k)
                .collect();
            let defined_atom = |m: &latex::Math| {
                symbols::occurrences(&[m], normal, &tensors)
                    .first()
                    .is_some_and(|(k, _)| chosen.contains_key(k))
            };
            let mut tied = tied(
                (equations, &symbols, &chosen, &squares),
                (&open, &opaque),
                (&said, &by_law, &defined_atom),
            );
            // A trace speaks of a tensor of rank 2, a divergence of a vector field: on
            // any other symbol such a reason ties nothing.
            tied.retain(|name, (_, _, kind)| {
                *kind >= TieKind::Law
                    || symbols.values().any(|s| {
                        s.name == *name && ((s.rank == 2 && !s.field) || (s.rank == 1 && s.field))
                    })
            });
            // "Throughout, the material is incompressible": every vector field's
            // divergence, wherever the words stand.
            if let Some((line, word)) = incompressible {
                for (k, s) in &symbols {
                    if !s.field || s.rank != 1 || s.component || defined.contains_key(k) {
                        continue;
                    }
                    let said = (
                        Some(*line),
                        format!("the text says \"{word}\""),
                        TieKind::Divergence,
                    );
                    let entry = tied.entry(s.name.clone()).or_insert_with(|| said.clone());
                    if entry.2 < TieKind::Divergence {
                        *entry = said;
                    }
                }
            }
            first_written(equations, (&symbols, &defined), (&open, prose));
            tied
        }
        None => BTreeMap::new(),
    };
    for eq in equations.iter_mut() {
        eq.names = eq
            .reads
            .iter()
            .filter_map(|k| symbols.get(k))
            .map(|s| s.name.clone())
            .collect();
    }
    let letters = |rank: usize| -> String { "ijklpqrsabcdefgh".chars().take(rank).collect() };
    let with_slots = |s: &Symbol| {
        if s.rank == 0 {
            s.name.clone()
        } else {
            format!("{}_{}", s.name, letters(s.rank))
        }
    };
    let any_field = symbols.values().any(|s| s.field);
    let position = any_field.then(|| {
        ["x", "X", "y"]
            .into_iter()
            .find(|p| symbols.values().all(|s| s.name != *p))
            .unwrap_or("xpos")
            .to_owned()
    });
    // The declarations and the notation the reading needs.
    let mut decls = Decls {
        dim: dimension,
        normal: normal.map(str::to_owned),
        normal_in_plane: false,
        symbols: BTreeMap::new(),
        fields: BTreeMap::new(),
        position: position.clone(),
        orders: BTreeMap::new(),
    };
    let mut table = Notation::default();
    let mut entries: Vec<(String, String)> = Vec::new();
    // One entry per printed key (a TOML table has each key once): the table takes
    // `\sigma_{n}` with `n` an index and as a label as two patterns, but the second
    // reading gets no entry, and the equations that read it are left to complete.
    let mut keys: BTreeSet<String> = BTreeSet::new();
    let mut add = |table: &mut Notation, key: &String, value: String| {
        if !keys.contains(key) && table.add(key, vec![value.clone()]).is_ok() {
            keys.insert(key.clone());
            entries.push((key.clone(), value));
        }
    };
    for k in &order {
        let s = &symbols[k];
        if s.component {
            continue;
        }
        if !defined.contains_key(k) {
            decls.symbols.insert(s.name.clone(), s.rank);
            if s.field {
                decls.fields.insert(s.name.clone(), vec![true; dimension]);
            }
        }
        if s.entry {
            let (key, key_letters) = &s.key;
            let value = if key_letters.is_empty() {
                s.name.clone()
            } else {
                format!("{}_{}", s.name, key_letters.iter().collect::<String>())
            };
            add(&mut table, key, value);
            // A scalar printed with a stray subscript too (`t_{i}^{(n)}` beside `t^{(n)}`).
            for other in s.printed.iter().filter(|p| *p != key && s.rank == 0) {
                add(&mut table, other, s.name.clone());
            }
            for (key, value) in &s.derivatives {
                // The derivative's reading names the symbol by its final name.
                let value = match value.split_once('_') {
                    Some((_, rest)) => format!("{}_{rest}", s.name),
                    None => value.clone(),
                };
                add(&mut table, key, value);
            }
        }
    }
    if let Some(p) = &position {
        decls.symbols.insert(p.clone(), 1);
    }
    // Pass 2: each definition's body, read through that notation, every definition's
    // signature known (a body may use a definition stated further on).
    let defining = |eq: &Equation| -> Vec<(Key, latex::Math)> {
        let Ok(printed) = latex::read(&eq.latex, &options) else {
            return Vec::new();
        };
        printed
            .parts
            .iter()
            .filter_map(|part| {
                let members: Vec<&latex::Math> = part.members.iter().collect();
                let found = symbols::occurrences(&members, normal, &tensors);
                let first = part.members.first()?;
                let (k, _) = defined_symbol(first, found.first(), &tensors)?;
                eq.defines
                    .iter()
                    .any(|(d, _)| *d == k)
                    .then(|| (k, first.clone()))
            })
            .collect()
    };
    let mut sigs: Vec<DefSig> = Vec::new();
    for eq in equations.iter().filter(|e| e.unread.is_none()) {
        for (key, member) in defining(eq) {
            let Some(s) = symbols.get(&key) else { continue };
            if sigs.iter().any(|g| g.name == s.name) {
                continue;
            }
            sigs.push(DefSig {
                name: s.name.clone(),
                formal: formal_of(&member, s.rank),
                shape: None,
            });
        }
    }
    // A stated definition, `X = …` alone: its defining member.
    let stated_member = |st: &Stated| {
        latex::read(&st.latex, &options)
            .ok()
            .and_then(|p| p.parts.first()?.members.first().cloned())
    };
    for (key, st) in &stated {
        let (Some(s), Some(member)) = (symbols.get(key), stated_member(st)) else {
            continue;
        };
        if !sigs.iter().any(|g| g.name == s.name) {
            sigs.push(DefSig {
                name: s.name.clone(),
                formal: formal_of(&member, s.rank),
                shape: None,
            });
        }
    }
    let mut texts: BTreeMap<Key, (String, String)> = BTreeMap::new();
    for eq in equations.iter_mut() {
        if eq.unread.is_some() || eq.defines.is_empty() {
            continue;
        }
        let members = defining(eq);
        let patterns: Vec<latex::Math> = members.iter().map(|(_, m)| m.clone()).collect();
        let reading = match notation::read(&eq.latex, &table, &patterns, &decls, &sigs) {
            Ok(r) => r,
            Err(u) => {
                let col = latex::column(&eq.latex, u.span.start);
                eq.unread = Some(format!("cannot read column {col}: {}", u.message));
                return None;
            }
        };
        // Each defining chain, read from its body on, in the order of `members`.
        let bodies: Vec<String> = reading
            .parts
            .iter()
            .filter(|p| p.defines.is_some())
            .filter_map(|p| p.routes.first()?.first().map(|m| m.text.clone()))
            .collect();
        if bodies.len() != members.len() {
            eq.unread = Some("a definition of this equation cannot be read".to_owned());
            return None;
        }
        for ((key, member), body) in members.iter().zip(bodies) {
            let Some(s) = symbols.get(key) else { continue };
            let formal: String = formal_of(member, s.rank).into_iter().collect();
            let head = if formal.is_empty() {
                s.name.clone()
            } else {
                format!("{}_{formal}", s.name)
            };
            texts.insert(key.clone(), (format!("{head} = {body}"), eq.id.clone()));
        }
    }
    for (key, st) in &stated {
        let (Some(s), Some((q, _))) = (symbols.get(key), chosen.get(key)) else {
            continue;
        };
        let origin = match st.line {
            Some(line) => format!("the text, line {line}"),
            None => equations[*q].id.clone(),
        };
        let body = stated_member(st).and_then(|member| {
            let reading = notation::read(
                &st.latex,
                &table,
                std::slice::from_ref(&member),
                &decls,
                &sigs,
            )
            .ok()?;
            let body = reading
                .parts
                .iter()
                .find(|p| p.defines.is_some())?
                .routes
                .first()?
                .first()?
                .text
                .clone();
            Some((member, body))
        });
        let Some((member, body)) = body else {
            // Not read: the text's definition is dropped, a decomposition's equation is
            // left to complete; the file is written again.
            match st.line {
                Some(line) => {
                    refused_text.insert(line);
                }
                None => {
                    equations[*q].unread = Some(format!(
                        "the definition it states of `{}` cannot be read",
                        s.key.0
                    ));
                }
            }
            return None;
        };
        let formal: String = formal_of(&member, s.rank).into_iter().collect();
        let head = if formal.is_empty() {
            s.name.clone()
        } else {
            format!("{}_{formal}", s.name)
        };
        texts.insert(key.clone(), (format!("{head} = {body}"), origin));
    }
    // Each labelled variant, from its unlabelled symbol's definition.
    for v in &variants {
        let Some((text, origin)) = texts.get(&v.of).cloned() else {
            continue;
        };
        let Some(text) = relabelled(&text, v, &symbols, &chosen, position.as_deref()) else {
            continue;
        };
        let origin = format!("{origin}, {}", comment(&v.how));
        texts.insert(v.key.clone(), (text, origin));
    }
    // In an order where each definition uses only those above it.
    let mut define_lines: Vec<(String, String)> = Vec::new();
    let mut placed: BTreeSet<Key> = BTreeSet::new();
    fn place(
        key: &Key,
        chosen: &BTreeMap<Key, (usize, BTreeSet<Key>)>,
        texts: &BTreeMap<Key, (String, String)>,
        placed: &mut BTreeSet<Key>,
        out: &mut Vec<(String, String)>,
    ) {
        if !placed.insert(key.clone()) {
            return;
        }
        if let Some((_, body)) = chosen.get(key) {
            for k in body {
                place(k, chosen, texts, placed, out);
            }
        }
        if let Some(t) = texts.get(key) {
            out.push(t.clone());
        }
    }
    for key in texts.keys() {
        place(key, &chosen, &texts, &mut placed, &mut define_lines);
    }
    let symmetric = symmetry::symmetric_tensors(symmetric, &symbols, &defined, (normal, &tensors));
    Some(render(Render {
        label,
        equations,
        symmetric: &symmetric,
        symbols: &symbols,
        order: &order,
        defined: &defined,
        entries: &entries,
        define_lines: &define_lines,
        dimension,
        normal,
        position: position.as_deref(),
        unnumbered,
        with_slots: &with_slots,
        tied: &tied,
    }))
}

/// What one round of writing the file learns for the next: definitions of the text the
/// loader refuses (by line), and stems read with a stray subscript; and what every
/// round reads alike, found once: the letters of the paper's vectors
/// ([`Stems::vectors`]).
#[derive(Default)]
struct Rounds {
    refused_text: BTreeSet<usize>,
    stray: BTreeSet<String>,
    vectors: BTreeSet<char>,
    /// The first line of the text, and its word, that calls the body incompressible or
    /// its motion isochoric.
    incompressible: Option<(usize, String)>,
    /// The symmetries the text states ([`symmetry`]).
    symmetric: symmetry::Statements,
    /// The text's sections and sentences, for the readings of laws and components.
    text: Text,
}

/// The paper's text as the readings of a posited law and of a vector's components look
/// at it: the line each section begins at, and each sentence's line and words.
#[derive(Default)]
struct Text {
    headings: Vec<usize>,
    sentences: Vec<(usize, String)>,
}

impl Text {
    /// The lines of the section `line` is in, from its heading to the next.
    fn section(&self, line: usize) -> std::ops::Range<usize> {
        symmetry::section(&self.headings, line)
    }
}

/// A symbol's definition on its way into the file.
struct Candidate {
    /// The numbered equation that states it, or for the text's, the number of
    /// equations before it.
    q: usize,
    key: Key,
    /// The symbols its body reads.
    body: BTreeSet<Key>,
    /// The defined symbol as printed.
    text: String,
    /// Where it is stated, if not alone on the left of equation `q`.
    stated: Option<Stated>,
}

/// Sets each claim's `introduces`: the declared symbols it is the first to write, before
/// any other equation (read or left to complete) and any formula of the text names them.
/// Such an equation may be what defines them (`\sigma_{ij} = s_{ij} + p\delta_{ij}` with
/// no word of a decomposition), so a failure they could explain is undecided there.
fn first_written(
    equations: &mut [Equation],
    (symbols, defined): (&BTreeMap<Key, Symbol>, &BTreeMap<Key, String>),
    (open, prose): (&BTreeMap<Key, usize>, &[displays::Inline]),
) {
    let mut out: Vec<(usize, String)> = Vec::new();
    for (k, q) in first_readers(equations, open) {
        let Some(s) = symbols
            .get(k)
            .filter(|s| !s.component && !defined.contains_key(k))
        else {
            continue;
        };
        let line = equations[q].line;
        let base = k.split('|').nth(1).unwrap_or("");
        let said = prose
            .iter()
            .any(|f| f.line <= line && mentions(&f.body, base));
        // An equation left to complete writes it first: no claim introduces it.
        if equations[q].unread.is_none() && !said {
            out.push((q, s.name.clone()));
        }
    }
    for (q, name) in out {
        equations[q].introduces.insert(name);
    }
}

/// The first equation (its index) that reads each symbol, read or left to complete
/// (`open`: what the equations left to complete mention).
fn first_readers<'e>(
    equations: &'e [Equation],
    open: &'e BTreeMap<Key, usize>,
) -> BTreeMap<&'e Key, usize> {
    let mut first: BTreeMap<&Key, usize> = open.iter().map(|(k, &q)| (k, q)).collect();
    for (q, eq) in equations.iter().enumerate() {
        for k in &eq.reads {
            let at = first.entry(k).or_insert(q);
            *at = (*at).min(q);
        }
    }
    first
}

/// "… their equal and opposite reactions $f_i^{(1,2)c}$ …": a symbol whose label is a
/// pair `(a,b)`, named after the word "opposite" in its sentence, is minus the one the
/// paper labels `(b,a)` (action and reaction), when the equations read both and read it
/// only after the sentence.
fn reaction(
    f: &displays::Inline,
    equations: &[Equation],
    (symbols, first_line): (&BTreeMap<Key, Symbol>, &BTreeMap<&Key, usize>),
    (normal, tensors): (Option<&str>, &Stems),
) -> Option<Candidate> {
    let before = f.words.get(..f.at)?.to_lowercase();
    if !before.contains("opposite") {
        return None;
    }
    let read = latex::read(&f.body, &ReadOptions::default()).ok()?;
    let [part] = &read.parts[..] else { return None };
    let [m] = &part.members[..] else { return None };
    let MathKind::Atom(a) = &m.kind else {
        return None;
    };
    // The label's pair, `(1,2)` in `(1,2)c`, and the body with it reversed.
    let sup = a.sup.as_ref()?.text.as_str();
    let open = sup.find('(')?;
    let close = open + sup[open..].find(')')?;
    let (x, y) = sup[open + 1..close].split_once(',')?;
    let (x, y) = (x.trim(), y.trim());
    if x.is_empty() || y.is_empty() || x == y {
        return None;
    }
    let reversed_sup = format!("{}({y},{x}){}", &sup[..open], &sup[close + 1..]);
    let body = f.body.trim();
    let at = body.find(sup)?;
    let reversed = format!("{}{reversed_sup}{}", &body[..at], &body[at + sup.len()..]);
    let key_of = |text: &str| -> Option<Key> {
        let r = latex::read(text, &ReadOptions::default()).ok()?;
        let m = r.parts.first()?.members.first()?;
        symbols::occurrences(&[m], normal, tensors)
            .into_iter()
            .next()
            .map(|(k, _)| k)
    };
    let (key, other) = (key_of(body)?, key_of(&reversed)?);
    let introduced = first_line.get(&key).is_some_and(|&l| l > f.line);
    if key == other || !introduced || !symbols.contains_key(&other) {
        return None;
    }
    Some(Candidate {
        q: equations.iter().filter(|e| e.line < f.line).count(),
        key,
        body: BTreeSet::from([other]),
        text: body.to_owned(),
        stated: Some(Stated {
            line: Some(f.line),
            latex: format!("{body} = -{reversed}"),
            instead_of: None,
            law: false,
        }),
    })
}

/// Words that give a formula of the text to someone else's convention ("in the older
/// literature $\dot{\kappa}_{ij} = w_{i,j}$").
const OTHERS: [&str; 8] = [
    "literature",
    "older",
    "convention",
    "traditionally",
    "elsewhere",
    "authors",
    "author",
    "others",
];

/// Words that make a formula of the text a condition or another model's, not the
/// paper's own value ("if", "in the case", "for instance", "unlike").
const CONDITION: [&str; 16] = [
    "if",
    "when",
    "whenever",
    "under",
    "assuming",
    "assume",
    "suppose",
    "case",
    "state",
    "example",
    "instance",
    "earlier",
    "classical",
    "rather",
    "instead",
    "unlike",
];

/// Whether the words before a formula of the text, in its sentence, introduce it as the
/// value of what they name ("the stress vector", "the equivalent stress is", "where"),
/// rather than as a condition or another model's ("In a hydrostatic state,", "Earlier
/// models took … as", "Rather than").
fn names_its_value(before: &str) -> bool {
    // A last word that leaves the formula's role open (besides the condition words).
    const STOP: [&str; 16] = [
        "as", "than", "of", "in", "on", "for", "at", "to", "from", "that", "and", "or", "not",
        "nor", "like", "unless",
    ];
    // A formula set off by a comma ("the invariants of the stress, $I_1 = …$") is named
    // by the clause before the comma.
    let clause = before
        .trim_end()
        .trim_end_matches([',', ':'])
        .rsplit(|c: char| ",;:.!?()".contains(c))
        .next()
        .unwrap_or("")
        .to_lowercase();
    let words: Vec<&str> = clause
        .split(|c: char| !c.is_alphanumeric() && c != '-')
        .filter(|w| !w.is_empty())
        .collect();
    words.last().is_some_and(|w| !STOP.contains(w)) && !words.iter().any(|w| CONDITION.contains(w))
}

/// Words of the sentence before a decomposition ("We decompose the stress into a
/// spherical and a deviatoric part").
const DECOMPOSITION_WORDS: [&str; 4] = ["decompos", "split", " part", "sum of"];

/// Definitions the paper states other than alone on the left of a numbered equation:
/// - an equation of the text that introduces a symbol the numbered equations read only
///   after it ("the stress vector $t_i = \sigma_{ki} n_k$"), from symbols they read,
///   where the words before it name its value ([`names_its_value`]) and no numbered
///   equation has the symbol alone on its left. Its right side must read a symbol, and
///   not be one alone ([`second_name`]): `$f_i^{(2,1)c} = f_i^c$` gives a second name,
///   `$x = 0$` a condition;
/// - a reaction ([`reaction`]): minus its action;
/// - a decomposition (`\sigma_{ij} = s_{ij} + p \delta_{ij}`), where the sentence before
///   it says so ([`DECOMPOSITION_WORDS`]): an equation `A = B` whose right side is a sum
///   with one added term that is a symbol met there first and once; it defines that
///   symbol as the rest moved over (`s_{ij} = \sigma_{ij} - (p \delta_{ij})`), and `A`
///   is not defined by it, even where met there first; not when a numbered equation has
///   that symbol alone on its left (the sum is then a claim, which may be wrong).
#[allow(clippy::type_complexity)]
fn stated_definitions(
    equations: &[Equation],
    (prose, refused, text): (&[displays::Inline], &BTreeSet<usize>, &Text),
    (symbols, open, in_prose, numbered): (
        &BTreeMap<Key, Symbol>,
        &BTreeMap<Key, usize>,
        &BTreeMap<Key, (usize, BTreeSet<String>)>,
        &BTreeSet<Key>,
    ),
    (normal, tensors): (Option<&str>, &Stems),
) -> Vec<Candidate> {
    let options = ReadOptions::default();
    // The line each symbol is first read at, by an equation read or left to complete.
    let first_line: BTreeMap<&Key, usize> = first_readers(equations, open)
        .into_iter()
        .map(|(k, q)| (k, equations[q].line))
        .collect();
    let keys = |members: &[&latex::Math]| -> Vec<Key> {
        symbols::occurrences(members, normal, tensors)
            .into_iter()
            .map(|(k, _)| k)
            .collect()
    };
    fn span<'t>(text: &'t str, m: &latex::Math) -> Option<&'t str> {
        text.get(m.span.start..m.span.end).map(str::trim)
    }
    let mut out = Vec::new();
    for f in prose {
        if refused.contains(&f.line) {
            continue;
        }
        let reacts = reaction(f, equations, (symbols, &first_line), (normal, tensors));
        if let Some(c) = reacts.filter(|c| !numbered.contains(&c.key)) {
            out.push(c);
            continue;
        }
        if !f.body.contains('=') {
            continue;
        }
        let Ok(read) = latex::read(&f.body, &options) else {
            continue;
        };
        // Each part of a formula that defines several (`I_1 = \sigma_{kk}, \quad I_2 =
        // …`), with its own text.
        for part in &read.parts {
            let [m0, m1] = &part.members[..] else {
                continue;
            };
            if part.relations[..] != [latex::Rel::Eq]
                || !matches!(m0.kind, MathKind::Atom(_))
                || second_name(m1)
            {
                continue;
            }
            let Some(own) = f.body.get(m0.span.start..m1.span.end) else {
                continue;
            };
            let found = symbols::occurrences(&[m0, m1], normal, tensors);
            let Some((key, None)) = defined_symbol(m0, found.first(), tensors) else {
                continue;
            };
            let body: BTreeSet<Key> = keys(&[m1]).into_iter().collect();
            let well_formed = !body.is_empty()
                && !body.contains(&key)
                && body.iter().all(|k| symbols.contains_key(k));
            // "… = K\varepsilon_{kk}, where $p = \sigma_{kk}/3$ is the mean stress": the
            // clause that continues the first equation to read the symbol defines it there,
            // instead of that equation (then a claim about it).
            let clause = equations.iter().position(|e| {
                e.unread.is_none()
                    && e.reads.contains(&key)
                    && first_line.get(&key) == Some(&e.line)
                    && defines_in_clause(&e.lead_out, &f.body)
            });
            if let (Some(q), true) = (clause, well_formed) {
                let Some(text) = span(&f.body, m0) else {
                    continue;
                };
                out.push(Candidate {
                    q,
                    key: key.clone(),
                    body,
                    text: text.to_owned(),
                    stated: Some(Stated {
                        line: Some(f.line),
                        latex: own.to_owned(),
                        instead_of: Some(key),
                        law: false,
                    }),
                });
                continue;
            }
            let introduced = first_line.get(&key).is_some_and(|&l| l > f.line);
            // A sentence that contrasts before the formula ("Unlike Smith's convention,
            // where $\dot{\kappa}_{ij} = w_{i,j}$ …, we use …"), or a symbol the text
            // sets equal to two things, is no definition.
            let hedged = f.words[..f.at.min(f.words.len())]
                .to_lowercase()
                .split(|c: char| !c.is_alphanumeric())
                .any(|w| CONDITION.contains(&w) || OTHERS.contains(&w));
            let twice = in_prose.get(&key).is_some_and(|(_, texts)| texts.len() > 1);
            if body.is_empty()
                || body.contains(&key)
                || !introduced
                || hedged
                || twice
                || numbered.contains(&key)
                || !names_its_value(&f.words[..f.at.min(f.words.len())])
                || !body.iter().all(|k| symbols.contains_key(k))
            {
                continue;
            }
            let Some(text) = span(&f.body, m0) else {
                continue;
            };
            out.push(Candidate {
                q: equations.iter().filter(|e| e.line < f.line).count(),
                key,
                body,
                text: text.to_owned(),
                stated: Some(Stated {
                    line: Some(f.line),
                    latex: own.to_owned(),
                    instead_of: None,
                    law: false,
                }),
            });
        }
    }
    out.extend(posited_laws(
        equations,
        (prose, text),
        (symbols, in_prose, numbered, &first_line),
        (normal, tensors),
    ));
    for (q, eq) in equations.iter().enumerate() {
        // Only where its sentence says so: a new symbol added to a known one is
        // otherwise as likely an error as a definition.
        let lead_in = eq.lead_in.to_lowercase();
        if eq.unread.is_some() || !DECOMPOSITION_WORDS.iter().any(|w| lead_in.contains(w)) {
            continue;
        }
        let Ok(printed) = latex::read(&eq.latex, &options) else {
            continue;
        };
        for part in &printed.parts {
            let [m0, m1] = &part.members[..] else {
                continue;
            };
            let MathKind::Sum(terms) = &m1.kind else {
                continue;
            };
            if part.relations[..] != [latex::Rel::Eq] || terms.len() < 2 {
                continue;
            }
            let found = keys(&[m0, m1]);
            let known = |k: &Key| first_line.get(k).is_some_and(|&l| l < eq.line);
            // The one added term that is a symbol met here first, once.
            let new: Vec<(usize, Key)> = terms
                .iter()
                .enumerate()
                .filter(|(_, (minus, t))| !minus && matches!(t.kind, MathKind::Atom(_)))
                .filter_map(|(n, (_, t))| Some((n, keys(&[m0, t]).pop()?)))
                .filter(|(_, k)| {
                    found.iter().filter(|f| *f == k).count() == 1
                        && !known(k)
                        && !in_prose.contains_key(k)
                        && !numbered.contains(k)
                        && symbols.contains_key(k)
                })
                .collect();
            let [(at, key)] = &new[..] else { continue };
            let Some(rest) = signed_rest(&eq.latex, terms, *at) else {
                continue;
            };
            let (Some(text), Some(left)) = (span(&eq.latex, &terms[*at].1), span(&eq.latex, m0))
            else {
                continue;
            };
            out.push(Candidate {
                q,
                key: key.clone(),
                body: found.iter().filter(|k| *k != key).cloned().collect(),
                text: text.to_owned(),
                stated: Some(Stated {
                    line: None,
                    latex: format!("{text} = {left} - ({rest})"),
                    instead_of: keys(&[m0]).pop(),
                    law: false,
                }),
            });
        }
    }
    out
}

/// The vectors whose every component one sentence of the text gives ("$n_1 =
/// \cos\theta$ and $n_2 = \sin\theta$"), in the paper's number of dimensions: each
/// defined as the sum of its components along the axes (`n_i = \cos\theta \delta_{i1} +
/// \sin\theta \delta_{i2}`). Only a vector the numbered equations read first after that
/// sentence, which none of them defines, whose components read neither it nor another
/// of its components, at least one of them a symbol; each component given once, in
/// one sentence with no word of a condition or a denial ([`CONDITION`]: "if $n_1 = 0$",
/// "unlike").
#[allow(clippy::type_complexity)]
fn components_stated(
    equations: &[Equation],
    (prose, refused, text): (&[displays::Inline], &BTreeSet<usize>, &Text),
    (symbols, open, numbered): (
        &BTreeMap<Key, Symbol>,
        &BTreeMap<Key, usize>,
        &BTreeSet<Key>,
    ),
    (dimension, normal, tensors): (usize, Option<&str>, &Stems),
) -> Vec<Candidate> {
    const DENIAL: [&str; 6] = ["not", "no", "never", "nor", "neither", "except"];
    let options = ReadOptions::default();
    let first_line: BTreeMap<&Key, usize> = first_readers(equations, open)
        .into_iter()
        .map(|(k, q)| (k, equations[q].line))
        .collect();
    // Per vector: its components' bodies (by digit) and what they read, with the
    // sentence and line of each.
    struct Given<'p> {
        bodies: BTreeMap<usize, String>,
        reads: BTreeSet<Key>,
        sentences: Vec<&'p str>,
        formulas: Vec<&'p str>,
        line: usize,
        twice: bool,
    }
    let mut given: BTreeMap<Key, Given> = BTreeMap::new();
    for f in prose.iter().filter(|f| !refused.contains(&f.line)) {
        let Ok(read) = latex::read(&f.body, &options) else {
            continue;
        };
        let before = f.words.get(..f.at).unwrap_or("");
        let sentence = before
            .rsplit(|c: char| ".!?".contains(c))
            .next()
            .unwrap_or("")
            .to_lowercase();
        let words: Vec<&str> = sentence
            .split(|c: char| !c.is_alphanumeric())
            .filter(|w| !w.is_empty())
            .collect();
        if symmetry::hedged(&f.words)
            || words
                .iter()
                .any(|w| CONDITION.contains(w) || DENIAL.contains(w))
        {
            continue;
        }
        for part in &read.parts {
            let [m0, m1] = &part.members[..] else {
                continue;
            };
            if part.relations[..] != [latex::Rel::Eq] || !matches!(m0.kind, MathKind::Atom(_)) {
                continue;
            }
            let left = symbols::occurrences(&[m0], normal, tensors);
            let [(component, _)] = &left[..] else {
                continue;
            };
            let Some(vector) = symbols::vector_of(component, symbols) else {
                continue;
            };
            let Some(digit) = component
                .split('|')
                .nth(4)
                .and_then(|d| d.parse::<usize>().ok())
            else {
                continue;
            };
            let Some(body) = f.body.get(m1.span.start..m1.span.end).map(str::trim) else {
                continue;
            };
            let reads: BTreeSet<Key> = symbols::occurrences(&[m1], normal, tensors)
                .into_iter()
                .map(|(k, _)| k)
                .collect();
            let g = given.entry(vector).or_insert_with(|| Given {
                bodies: BTreeMap::new(),
                reads: BTreeSet::new(),
                sentences: Vec::new(),
                formulas: Vec::new(),
                line: f.line,
                twice: false,
            });
            g.twice |= g.bodies.insert(digit, body.to_owned()).is_some();
            g.reads.extend(reads);
            g.formulas.push(f.body.as_str());
            if !g.sentences.contains(&f.words.as_str()) {
                g.sentences.push(f.words.as_str());
            }
        }
    }
    let mut out = Vec::new();
    for (vector, g) in given {
        let Some(s) = symbols.get(&vector) else {
            continue;
        };
        let complete = g.bodies.keys().copied().eq(1..=dimension);
        let own =
            |k: &Key| *k == vector || symbols::vector_of(k, symbols).as_ref() == Some(&vector);
        let [index] = s.key.1[..] else { continue };
        if !complete
            || g.twice
            || g.sentences.len() != 1
            || numbered.contains(&vector)
            || first_line.get(&vector).is_none_or(|&l| l <= g.line)
            || g.reads.is_empty()
            || g.reads.iter().any(own)
            || !g.reads.iter().all(|k| symbols.contains_key(k))
        {
            continue;
        }
        // The words the sentence describes the vector with ("unit normal", "angle"): a
        // later sentence with one of them may describe it again ("the angle is measured
        // from the vertical", "now let the unit normal be arbitrary").
        let sentence = g
            .sentences
            .first()
            .map_or(String::new(), |w| w.to_lowercase());
        let nouns: Vec<&str> = sentence
            .split(|c: char| !c.is_alphanumeric())
            .filter(|w| VECTOR_NOUNS.contains(w))
            .collect();
        let described_again = text.sentences.iter().any(|(line, words)| {
            *line > g.line
                && words
                    .to_lowercase()
                    .split(|c: char| !c.is_alphanumeric())
                    .any(|w| nouns.contains(&w))
        });
        // A formula of the text after them that writes the vector ("the sign of $n_i$ is
        // reversed"), or a sentence that turns it ("on the opposite face it is
        // reversed"), may change it.
        let written_again = || {
            prose.iter().any(|f| {
                f.line >= g.line
                    && !g.formulas.contains(&f.body.as_str())
                    && latex::read(&f.body, &options).is_ok_and(|r| {
                        r.parts.iter().any(|p| {
                            let members: Vec<&latex::Math> = p.members.iter().collect();
                            symbols::occurrences(&members, normal, tensors)
                                .iter()
                                .any(|(k, _)| own(k))
                        })
                    })
            })
        };
        let turned = || {
            text.sentences.iter().any(|(line, words)| {
                let lower = words.to_lowercase();
                *line >= g.line && REVISIONS.iter().any(|w| lower.contains(w))
            })
        };
        let section = text.section(g.line);
        let scoped = equations
            .iter()
            .filter(|e| e.reads.contains(&vector))
            .all(|e| section.contains(&e.line));
        if described_again || written_again() || turned() || !scoped {
            continue;
        }
        let sum: Vec<String> = g
            .bodies
            .iter()
            .map(|(d, body)| format!("\\left({body}\\right) \\delta_{{{index}{d}}}"))
            .collect();
        out.push(Candidate {
            q: equations.iter().filter(|e| e.line < g.line).count(),
            key: vector.clone(),
            body: g.reads,
            text: s.key.0.clone(),
            stated: Some(Stated {
                line: Some(g.line),
                latex: format!("{} = {}", s.key.0, sum.join(" + ")),
                instead_of: None,
                law: false,
            }),
        });
    }
    out
}

/// The terms of a sum but the one at `at`, as printed, each with its sign (`a - b + c`
/// without `b` is `a + c`); `None` when a term's text cannot be cut out.
fn signed_rest(latex_text: &str, terms: &[(bool, latex::Math)], at: usize) -> Option<String> {
    let rest = terms
        .iter()
        .enumerate()
        .filter(|(n, _)| *n != at)
        .map(|(n, (minus, t))| {
            let sign = match (minus, n == 0 || (at == 0 && n == 1)) {
                (true, _) => "- ",
                (false, true) => "",
                (false, false) => "+ ",
            };
            let text = latex_text.get(t.span.start..t.span.end)?.trim();
            Some(format!("{sign}{text}"))
        })
        .collect::<Option<Vec<String>>>()?;
    Some(rest.join(" "))
}

/// Words that describe a vector whose components the text gives ("the unit normal at
/// the angle $\theta$").
const VECTOR_NOUNS: [&str; 7] = [
    "normal",
    "tangent",
    "direction",
    "vector",
    "angle",
    "orientation",
    "unit",
];

/// Words that say a vector is turned or replaced ("reversed", "the opposite face",
/// "rotated").
const REVISIONS: [&str; 9] = [
    "revers",
    "flip",
    "opposite",
    "rotat",
    "turn",
    "instead",
    "otherwise",
    "replac",
    "negat",
];

/// Words of the sentence before a law the paper posits ("equilibrium requires", "the
/// balance of linear momentum reads").
const LAW_WORDS: [&str; 7] = [
    "equilibri",
    "balance",
    "conservation",
    "of motion",
    "momentum",
    "governing",
    "field equation",
];

/// Words that, beside a law word, say a law is neglected, violated or approximate.
const LAW_HEDGES: [&str; 5] = ["neglect", "ignor", "violat", "approximat", "break"];

/// Words of a sentence that derive its equation rather than posit it ("inserting this
/// in equilibrium gives Navier's equations").
const DERIVED_WORDS: [&str; 23] = [
    "give",
    "yield",
    "therefore",
    "hence",
    "thus",
    "substitut",
    "insert",
    "obtain",
    "lead",
    "become",
    "reduce",
    "combin",
    "follow",
    "so that",
    "find",
    "we get",
    "result",
    "deduce",
    "rewrit",
    "taking",
    "in terms of",
    "express",
    "navier",
];

/// The definitions that laws the paper posits state: a numbered equation of the form of
/// a law ([`law_form`]: equilibrium, `\sigma_{ij,j} + b_i = 0` or `\sigma_{ij,j} =
/// -b_i`), whose sentence says it is one ([`LAW_WORDS`], and none of [`DERIVED_WORDS`]),
/// and that has one source term, a bare symbol (no derivative, no coefficient) met there
/// first and once, which no numbered equation and no formula of the text defines. It
/// defines that symbol as what the law leaves it (`b_i = -(\sigma_{ij,j})`): every later
/// equation that reads it is then checked on the law's solutions, which is what the
/// paper asserts of it (Navier's equations), and a wrong one fails. A source term the
/// text writes elsewhere (`$b_i = \rho g_i$`) or an equation before mentions is no new
/// symbol, and neither is one a formula of the text relates to anything (`$\sigma_{ij,j}
/// + b_i = 0$` said before in words): the law then ties it ([`tied`]).
#[allow(clippy::type_complexity)]
fn posited_laws(
    equations: &[Equation],
    (prose, text): (&[displays::Inline], &Text),
    (symbols, in_prose, numbered, first_line): (
        &BTreeMap<Key, Symbol>,
        &BTreeMap<Key, (usize, BTreeSet<String>)>,
        &BTreeSet<Key>,
        &BTreeMap<&Key, usize>,
    ),
    (normal, tensors): (Option<&str>, &Stems),
) -> Vec<Candidate> {
    let options = ReadOptions::default();
    let keys = |members: &[&latex::Math]| -> Vec<Key> {
        symbols::occurrences(members, normal, tensors)
            .into_iter()
            .map(|(k, _)| k)
            .collect()
    };
    let derivative = |m: &latex::Math| match &m.kind {
        MathKind::Atom(a) => a.sub.as_ref().is_some_and(|s| s.text.contains(',')),
        _ => true,
    };
    // The symbols a formula of the text relates to others.
    let related: BTreeSet<Key> = prose
        .iter()
        .filter(|f| f.body.contains('='))
        .filter_map(|f| latex::read(&f.body, &options).ok())
        .flat_map(|r| {
            r.parts
                .iter()
                .flat_map(|p| keys(&p.members.iter().collect::<Vec<_>>()))
                .collect::<Vec<_>>()
        })
        .collect();
    // A sentence anywhere that speaks of a law and hedges ("this balance is violated
    // in the boundary layer", "the balance of momentum is not the equilibrium
    // condition"): the paper tells laws apart in ways no reading follows.
    let hedges = |words: &str| {
        let lower = words.to_lowercase();
        symmetry::hedged(&lower) || LAW_HEDGES.iter().any(|w| lower.contains(w))
    };
    if text.sentences.iter().any(|(_, words)| {
        LAW_WORDS.iter().any(|w| words.to_lowercase().contains(w)) && hedges(words)
    }) {
        return Vec::new();
    }
    // Every equation read once, for the rivals of each law.
    let parsed: Vec<Option<latex::Printed>> = equations
        .iter()
        .map(|e| latex::read(&e.latex, &options).ok())
        .collect();
    let mut out = Vec::new();
    for (q, eq) in equations.iter().enumerate() {
        let lead_in = eq.lead_in.to_lowercase();
        if eq.unread.is_some()
            || !law_form(&eq.latex, &|_| false)
            || !LAW_WORDS.iter().any(|w| lead_in.contains(w))
            || DERIVED_WORDS.iter().any(|w| lead_in.contains(w))
            || hedges(&lead_in)
        {
            continue;
        }
        let Ok(printed) = latex::read(&eq.latex, &options) else {
            continue;
        };
        let [part] = &printed.parts[..] else { continue };
        let [m0, m1] = &part.members[..] else {
            continue;
        };
        if part.relations[..] != [latex::Rel::Eq] {
            continue;
        }
        let found = keys(&[m0, m1]);
        // A bare symbol met here first and once, which nothing else defines.
        let new = |t: &latex::Math| -> Option<Key> {
            if !matches!(t.kind, MathKind::Atom(_)) || derivative(t) {
                return None;
            }
            let k = keys(&[t]).pop()?;
            let fresh = found.iter().filter(|f| **f == k).count() == 1
                && first_line.get(&k) == Some(&eq.line)
                && !in_prose.contains_key(&k)
                && !related.contains(&k)
                && !numbered.contains(&k)
                && symbols.contains_key(&k);
            fresh.then_some(k)
        };
        let span = |m: &latex::Math| eq.latex.get(m.span.start..m.span.end).map(str::trim);
        let terms = |m: &latex::Math| -> Vec<(bool, latex::Math)> {
            match &m.kind {
                MathKind::Sum(terms) => terms.clone(),
                _ => vec![(false, m.clone())],
            }
        };
        let zero = |m: &latex::Math| matches!(&m.kind, MathKind::Number(n) if n == "0");
        // `… + X = 0` (either way round): X is minus the rest of the sum; `A = X` (or
        // `A = -X`): X is A (or minus A).
        let (sum, other) = if zero(m1) {
            (terms(m0), None)
        } else if zero(m0) {
            (terms(m1), None)
        } else {
            match (terms(m1).as_slice(), terms(m0).as_slice()) {
                ([(minus, t)], _) if new(t).is_some() => (vec![(!minus, t.clone())], Some(m0)),
                (_, [(minus, t)]) if new(t).is_some() => (vec![(!minus, t.clone())], Some(m1)),
                _ => continue,
            }
        };
        let fresh: Vec<(usize, Key)> = sum
            .iter()
            .enumerate()
            .filter_map(|(n, (_, t))| Some((n, new(t)?)))
            .collect();
        let [(at, key)] = &fresh[..] else { continue };
        // The rest is one derivative of one symbol (`\sigma_{ij,j}`): a balance as the
        // paper posits it, not a form derived from it (`\mu u_{i,jj} + … + b_i = 0`),
        // which may be wrong.
        let one_derivative = |m: &latex::Math| match &m.kind {
            MathKind::Atom(_) => derivative(m),
            MathKind::Sum(terms) => {
                matches!(&terms[..], [(_, t)] if matches!(t.kind, MathKind::Atom(_)) && derivative(t))
            }
            _ => false,
        };
        let rest_is_one = match other {
            Some(m) => one_derivative(m),
            None => {
                sum.len() == 2
                    && sum
                        .iter()
                        .enumerate()
                        .all(|(n, (_, t))| n == *at || one_derivative(t))
            }
        };
        // Every equation that reads the source is in the law's section: another section
        // may treat another problem (with inertia, without the body force).
        let section = text.section(eq.line);
        let scoped = equations
            .iter()
            .filter(|e| {
                e.reads.contains(key)
                    || (e.unread.is_some()
                        && span(&sum[*at].1).is_some_and(|t| e.latex.contains(t)))
            })
            .all(|e| section.contains(&e.line));
        // Another equation that reads the source and sets it against a term of no
        // derivative and without it (`\sigma_{ij,j} + b_i = \rho\ddot{u}_i` under rapid
        // loading): the paper posits another law for the same source.
        let rival = equations
            .iter()
            .zip(&parsed)
            .enumerate()
            .any(|(r, (e, read))| {
                let Some(read) = read.as_ref().filter(|_| r != q && e.reads.contains(key)) else {
                    return false;
                };
                read.parts.iter().any(|part| match &part.members[..] {
                    [a, b] if !zero(a) && !zero(b) => [a, b].iter().any(|m| {
                        let text = e.latex.get(m.span.start..m.span.end).unwrap_or(",");
                        !text.contains(',') && !keys(&[m]).contains(key)
                    }),
                    _ => false,
                })
            });
        if !rest_is_one || !scoped || rival {
            continue;
        }
        let (minus, source) = &sum[*at];
        let rest = match other {
            Some(m) => span(m).map(str::to_owned),
            None => signed_rest(&eq.latex, &sum, *at),
        };
        let (Some(rest), Some(text)) = (rest.filter(|r| !r.is_empty()), span(source)) else {
            continue;
        };
        // `X + R = 0` gives `X = -(R)`; `-X + R = 0` gives `X = (R)`; for `A = X` the
        // source was moved over with its sign flipped, so the same rule holds.
        let sign = if *minus { "" } else { "-" };
        out.push(Candidate {
            q,
            key: key.clone(),
            body: found.iter().filter(|k| *k != key).cloned().collect(),
            text: text.to_owned(),
            stated: Some(Stated {
                line: None,
                latex: format!("{text} = {sign}({rest})"),
                instead_of: None,
                law: true,
            }),
        });
    }
    out
}

/// Words of a sentence that say its symbols are tied to others: "equal and opposite",
/// "deviatoric", "orthogonal", … (a whole word or the start of one). "Symmetric" and
/// "unit vector" are not among them: those ties are named without a reason
/// (`decide::drafted`), and a symmetry or a unit length relates no two symbols.
const TIE_WORDS: [&str; 10] = [
    "opposite",
    "reaction",
    "deviator",
    "traceless",
    "trace-free",
    "orthogonal",
    "perpendicular",
    "incompressib",
    "isochoric",
    "constrain",
];

/// The tie words that speak of a trace only (a deviator, an incompressible body): they
/// make a symbol's trace, or a field's divergence, zero, and no other tie.
const TRACE_WORDS: [&str; 5] = [
    "deviator",
    "traceless",
    "trace-free",
    "incompressib",
    "isochoric",
];

/// The ties a tie word allows: a zero divergence outright for an incompressible body, a
/// zero trace for a deviator, any tie else.
fn tie_kind(word: &str) -> TieKind {
    let starts = |stems: &[&str]| stems.iter().any(|w| word.starts_with(w));
    if starts(&["incompressib", "isochoric"]) {
        TieKind::Divergence
    } else if starts(&TRACE_WORDS) {
        TieKind::Trace
    } else {
        TieKind::Any
    }
}

/// The tie word of `words`, if any: the first word (lowercase) that starts with one of
/// [`TIE_WORDS`].
fn tie_word(words: &str) -> Option<String> {
    let lower = words.to_lowercase();
    lower
        .split(|c: char| !(c.is_alphanumeric() || c == '-'))
        .find(|t| !t.is_empty() && TIE_WORDS.iter().any(|w| t.starts_with(w)))
        .map(str::to_owned)
}

/// What an equation of the paper's text (inline, or a display without a number) says,
/// read once for every round of the draft.
struct Said {
    line: usize,
    /// The tie word of its sentence.
    word: Option<String>,
    /// It states an antisymmetry of one tensor (`$W_{ij} = -W_{ji}$`, "the skew stress
    /// $\tau_{ij}$"), or a symmetry word stands beside a tensor of three or more
    /// indices: a tie of that tensor, if declared, and of nothing it is defined from.
    symmetry: bool,
    /// Every symbol it names.
    found: Vec<Key>,
    /// Each equality: its left side when that is one symbol, and the right side's
    /// symbols.
    parts: Vec<(Option<Key>, Vec<Key>)>,
    /// It is an equality (a condition such as `\mu > 0` is not).
    relation: bool,
    /// It writes a trace (`\varepsilon_{kk}`, `u_{k,k}`).
    trace: bool,
    /// It reads the normal (`$n_1 = \cos\theta$`).
    normal: bool,
    /// The words after it, up to the next formula, call it constant ("let the modulus
    /// $E$ be a constant", "$E$ is uniform").
    constant: bool,
    /// It is one plain symbol (no script, accent or prime) in a sentence that names the
    /// normal by a formula ("the unit normal $n_i$ … at angle $\theta$").
    beside_normal: bool,
}

/// What each equation of the text says ([`Said`]); a formula the reader cannot read, or
/// with neither an equality nor a tie word, says nothing.
fn said_in_text(prose: &[displays::Inline], normal: Option<&str>, tensors: &Stems) -> Vec<Said> {
    let options = ReadOptions::default();
    let keys = |members: &[&latex::Math]| -> Vec<Key> {
        symbols::occurrences(members, normal, tensors)
            .into_iter()
            .map(|(k, _)| k)
            .collect()
    };
    // Whether a formula reads the normal (`$n_i$`, `$n_1 = \cos\theta$`).
    let reads_normal = |read: &latex::Printed| {
        let mut letters = BTreeSet::new();
        for part in &read.parts {
            for m in &part.members {
                symbols::vector_letters(m, &mut letters);
            }
        }
        normal.is_some_and(|n| n.chars().count() == 1 && n.chars().all(|c| letters.contains(&c)))
    };
    // The sentences that name the normal by a formula.
    let of_normal: BTreeSet<&str> = prose
        .iter()
        .filter(|f| normal.is_some_and(|n| f.body.contains(n)))
        .filter(|f| latex::read(&f.body, &options).is_ok_and(|r| reads_normal(&r)))
        .map(|f| f.words.as_str())
        .collect();
    prose
        .iter()
        .filter_map(|f| {
            // A symmetry of a tensor the text writes as a formula (`$W_{ij} = -W_{ji}$`),
            // or names beside a tensor of three or more indices ("$C_{ijkl}$ with the
            // major and minor symmetries"), ties it: a difference it removes is
            // undecided (the statements `symmetry` reads assume rank-2 symmetries).
            let lower = f.words.to_lowercase();
            let parsed = latex::read(&f.body, &options);
            let of_many_indices = parsed.as_ref().is_ok_and(|r| {
                matches!(&r.parts[..], [p] if matches!(&p.members[..], [m] if matches!(&m.kind,
                    MathKind::Atom(a) if a.sub.as_ref().is_some_and(|s| s.text.chars().filter(char::is_ascii_lowercase).count() >= 3))))
            });
            // "the skew stress $\tau_{ij}$": an adjective of antisymmetry right before it.
            let before = f.words.get(..f.at).unwrap_or("").to_lowercase();
            let skew_adjective = before
                .split(|c: char| !c.is_alphanumeric() && c != '-')
                .filter(|w| !w.is_empty())
                .rev()
                .take(2)
                .any(|w| w.starts_with("skew") || w.starts_with("antisym"));
            let symmetry = symmetry::transposed(&f.body) == Some(symmetry::Kind::Antisymmetric)
                || ((lower.contains("symmetr") || lower.contains("skew")) && of_many_indices)
                || skew_adjective;
            let word = tie_word(&f.words);
            let beside_normal = of_normal.contains(f.words.as_str());
            let after = f.words.get(f.at + 3..).unwrap_or("").to_lowercase();
            let clause = after.split(" x ").next().unwrap_or("");
            let constant = clause
                .split(|c: char| !c.is_alphabetic())
                .any(|w| matches!(w, "constant" | "constants" | "uniform"));
            if word.is_none() && !f.body.contains('=') && !beside_normal && !constant && !symmetry {
                return None;
            }
            let read = parsed.ok()?;
            let found = read
                .parts
                .iter()
                .flat_map(|part| keys(&part.members.iter().collect::<Vec<_>>()))
                .collect();
            let parts = read
                .parts
                .iter()
                .filter(|p| p.relations.first() == Some(&latex::Rel::Eq))
                .map(|p| {
                    let left = p
                        .members
                        .first()
                        .filter(|m| matches!(m.kind, MathKind::Atom(_)))
                        .and_then(|m| keys(&[m]).into_iter().next());
                    (left, keys(&p.members.iter().skip(1).collect::<Vec<_>>()))
                })
                .collect();
            Some(Said {
                line: f.line,
                word,
                symmetry,
                found,
                parts,
                relation: read
                    .parts
                    .iter()
                    .any(|p| p.relations.contains(&latex::Rel::Eq)),
                trace: repeated_index(&f.body),
                normal: reads_normal(&read),
                constant,
                beside_normal: beside_normal
                    && matches!(&read.parts[..], [p] if matches!(&p.members[..], [m] if matches!(&m.kind,
                        MathKind::Atom(a) if a.sub.is_none() && a.sup.is_none() && a.accent.is_none() && a.primes == 0))),
            })
        })
        .collect()
}

/// Whether `formula` stands in `clause`, the words after an equation, as a definition
/// of that equation's symbol: the clause continues the equation ("where", "with", "in
/// which"), and the formula ends the clause or is followed by words that name it ("is
/// the mean stress", "denotes").
fn defines_in_clause(clause: &str, formula: &str) -> bool {
    let lower = clause.trim_start().to_lowercase();
    if !["where ", "with ", "in which "]
        .iter()
        .any(|w| lower.starts_with(w))
    {
        return false;
    }
    let Some(at) = clause.find(&format!("${formula}$")) else {
        return false;
    };
    let after = clause[at + formula.len() + 2..].trim_start().to_lowercase();
    if after.is_empty() || after.starts_with(['.', ',', ';']) {
        return true;
    }
    let word = after
        .split(|c: char| !c.is_alphabetic())
        .next()
        .unwrap_or("");
    [
        "is",
        "are",
        "denotes",
        "denote",
        "being",
        "represents",
        "defines",
    ]
    .contains(&word)
}

/// The inline formula that follows `word` in `words` within three words ("deviatoric
/// strain $e_{ij} = …$"), without its dollars.
fn formula_after<'w>(words: &'w str, word: &str) -> Option<&'w str> {
    // ASCII case only: the offset must stay an offset of `words`.
    let at = words.to_ascii_lowercase().find(word)?;
    let mut rest = words.get(at + word.len()..)?;
    for _ in 0..4 {
        rest = rest.trim_start();
        if let Some(inner) = rest.strip_prefix('$') {
            return inner.split('$').next();
        }
        let end = rest
            .find(|c: char| !c.is_alphabetic())
            .unwrap_or(rest.len());
        if end == 0 {
            return None;
        }
        rest = &rest[end..];
    }
    None
}

/// Whether a right side is a second name for its left (`$f_i^{(2,1)c} = f_i^c$`): one
/// symbol, not differentiated. A derivative (`$\dot{\kappa}_{ij} = w_{j,i}$`) is a
/// value.
fn second_name(m: &latex::Math) -> bool {
    matches!(&m.kind, MathKind::Atom(a) if !a.sub.as_ref().is_some_and(|s| s.text.contains(',')))
}

/// Whether an equation has the form of a law (`\sigma_{ij,j} + b_i = 0`, `\sigma_{ij,j} =
/// -b_i`, `\sigma_{ij,j} = \rho a_i`): it reads a comma derivative, and one of its two
/// members is 0 or a lone symbol, negated or not, with coefficients or not, that no
/// definition gives (`P = \sigma_{ij} v_{j,i}`, with `P`
/// defined, is a claim about `P`).
fn law_form(latex_text: &str, defined: &dyn Fn(&latex::Math) -> bool) -> bool {
    let derivative = latex_text
        .split("_{")
        .skip(1)
        .any(|rest| rest.split('}').next().is_some_and(|sub| sub.contains(',')));
    // A source term: a symbol, not a derivative (`u_{i,j} = …` is no law).
    let source = |m: &latex::Math| second_name(m) && !defined(m);
    // A source with coefficients (`\rho a_i`, `\rho\,\ddot{u}_i`): symbols, none a
    // derivative, one of them a source.
    let sourced = |m: &latex::Math| match &m.kind {
        MathKind::Product(factors) => {
            factors.iter().all(second_name) && factors.iter().any(&source)
        }
        _ => source(m),
    };
    let lone = |m: &latex::Math| match &m.kind {
        MathKind::Number(n) => n == "0",
        MathKind::Sum(terms) => matches!(&terms[..], [(_, t)] if sourced(t)),
        _ => sourced(m),
    };
    derivative
        && latex::read(latex_text, &ReadOptions::default()).is_ok_and(|r| {
            matches!(&r.parts[..], [p] if p.relations[..] == [latex::Rel::Eq]
                && p.members.len() == 2
                && p.members.iter().any(lone))
        })
}

/// Whether a formula has a subscript of two or more letters, or a comma derivative
/// (`A_{ik}`, `u_{i,j}`): its letters are indices beyond doubt.
fn indexed(formula: &str) -> bool {
    formula.split('_').skip(1).any(|rest| {
        let sub = match rest.trim_start().strip_prefix('{') {
            Some(inner) => inner.split('}').next().unwrap_or(""),
            None => return false,
        };
        // Letters of a command (`\mathrm`, `\tau`) are no indices.
        let mut letters = 0;
        let mut command = false;
        for c in sub.chars() {
            command = (command && c.is_ascii_alphabetic()) || c == '\\';
            letters += usize::from(!command && c.is_ascii_alphabetic());
        }
        sub.contains(',') || letters > 1
    })
}

/// Whether a formula has a subscript that repeats an index letter (`\varepsilon_{kk}`,
/// `u_{k,k}`): a trace or a divergence.
fn repeated_index(formula: &str) -> bool {
    let mut rest = formula;
    while let Some(at) = rest.find('_') {
        rest = &rest[at + 1..];
        let sub = match rest.strip_prefix('{') {
            Some(inner) => inner.split('}').next().unwrap_or(""),
            None => rest.get(..1).unwrap_or(""),
        };
        let letters: Vec<char> = sub.chars().filter(char::is_ascii_lowercase).collect();
        let distinct: BTreeSet<char> = letters.iter().copied().collect();
        if distinct.len() < letters.len() {
            return true;
        }
    }
    false
}

/// Whether `words` name the symbol of `key` as a word of their own: its base letter
/// (`n` in "where n_i is"), a Greek base by its letter or its command (`σ`, `\sigma`).
fn names(words: &str, key: &Key) -> bool {
    let base = key.split('|').nth(1).unwrap_or("");
    let greek = base
        .strip_prefix('\\')
        .and_then(crate::lang::latex::greek_letter);
    let alone = |w: &str| {
        !w.is_empty()
            && words.match_indices(w).any(|(at, _)| {
                let before = words[..at].chars().next_back();
                let after = words[at + w.len()..].chars().next();
                !before.is_some_and(char::is_alphanumeric)
                    && !after.is_some_and(char::is_alphabetic)
            })
    };
    alone(base) || greek.is_some_and(|g| alone(&g.to_string()))
}

/// The declared symbols the paper may tie to others, by name, each with its line (if
/// one) and why: an equation left to complete mentions it; a formula of the text
/// relates it to others, or stands in a sentence that says so ("equal and opposite",
/// "symmetric", "a unit vector"); or the paper writes a labelled variant of it
/// (`f^{(1,2)}` beside `f^{(2,1)}`), which it may relate in words.
#[allow(clippy::type_complexity)]
fn tied(
    (equations, symbols, chosen, squares): (
        &[Equation],
        &BTreeMap<Key, Symbol>,
        &BTreeMap<Key, (usize, BTreeSet<Key>)>,
        &BTreeMap<Key, usize>,
    ),
    (open, opaque): (&BTreeMap<Key, usize>, &[(usize, String)]),
    (said, by_law, defined_atom): (&[&Said], &BTreeSet<&Key>, &dyn Fn(&latex::Math) -> bool),
) -> BTreeMap<String, (Option<usize>, String, TieKind)> {
    let declared = |k: &Key| {
        symbols
            .get(k)
            .filter(|s| !s.component && !chosen.contains_key(k))
    };
    // The declared symbols a symbol stands for: itself, or what its definition reads,
    // through every definition (`ε` defined from the field `u` stands for `u`).
    let through = |k: &Key| -> Vec<&Symbol> {
        let mut out = Vec::new();
        let mut stack = vec![k];
        let mut seen: BTreeSet<&Key> = BTreeSet::new();
        while let Some(k) = stack.pop() {
            if !seen.insert(k) {
                continue;
            }
            match chosen.get(k) {
                Some((_, body)) => stack.extend(body.iter()),
                None => out.extend(declared(k)),
            }
        }
        out
    };
    let mut out: BTreeMap<String, (Option<usize>, String, TieKind)> = BTreeMap::new();
    // A reason that allows more ties prevails ([`TieKind`], from the narrowest).
    let mut add = |name: &str, line: Option<usize>, why: String, kind: TieKind| {
        let entry = out
            .entry(name.to_owned())
            .or_insert((line, why.clone(), kind));
        if kind > entry.2 {
            *entry = (line, why, kind);
        }
    };
    // What the sentence that leads into an equation says of it ("The Cauchy stress is
    // symmetric,"), and the clause that continues it says of a symbol it names ("where
    // n_i is the unit vector normal to the plane", in words or formulas).
    for e in equations {
        let before = tie_word(&e.lead_in);
        let lower = e.lead_out.to_lowercase();
        let continues = ["where ", "with ", "in which ", "here "]
            .iter()
            .any(|w| lower.starts_with(w));
        let after = continues.then(|| tie_word(&e.lead_out)).flatten();
        // "Introducing the deviatoric strain $e_{ij} = …$": a word of a trace names the
        // symbol of the formula right after it, and only that one, if the file declares
        // it (a defined symbol's trace is what its definition gives).
        let named = before
            .as_ref()
            .filter(|w| tie_kind(w) == TieKind::Trace)
            .and_then(|w| formula_after(&e.lead_in, w))
            .map(|f| f.split('=').next().unwrap_or(f));
        for (k, s) in e
            .reads
            .iter()
            .flat_map(|k| through(k).into_iter().map(move |s| (k, s)))
        {
            if named.is_some_and(|left| !names(left, k) || declared(k).is_none()) {
                continue;
            }
            if let Some(w) = &before {
                add(
                    &s.name,
                    Some(e.line),
                    format!("the sentence before equation ({}) says \"{w}\"", e.number),
                    tie_kind(w),
                );
            } else if let Some(w) = after.as_ref().filter(|_| names(&e.lead_out, k)) {
                add(
                    &s.name,
                    Some(e.line),
                    format!("the sentence after equation ({}) says \"{w}\"", e.number),
                    tie_kind(w),
                );
            }
        }
    }
    for (k, &q) in open {
        let e = &equations[q];
        // An equation whose sides carry different free indices is ill-formed: it
        // states no relation, so it ties nothing.
        let ill_formed = e
            .unread
            .as_deref()
            .is_some_and(|why| why.starts_with(super::load::DIFFERENT_FREE_INDICES));
        if ill_formed {
            continue;
        }
        for s in through(k) {
            add(
                &s.name,
                Some(e.line),
                format!("equation ({}), left to complete, mentions it", e.number),
                TieKind::Any,
            );
        }
    }
    // A law the paper may posit (equilibrium: `\sigma_{ij,j} + b_i = 0`, `\sigma_{ij,j} =
    // -b_i`, `\sigma_{ij,j} = 0`): an equation that defines nothing, reads a derivative,
    // and sets an expression of two or more symbols to zero or to a lone source term.
    // Later equations may hold only where it does (Navier's equations): the fields it
    // reads, through definitions, and the symbols it is the first to write are tied to
    // it, for sides that read different symbols only (`tie = 'law'`). One of a single
    // symbol (`e_{ijk}\phi_{,jk} = 0`) relates it to no other.
    // A law that defines its source term ([`posited_laws`]) still ties the fields it
    // reads: a later equation may hold only where the source takes a value the text
    // gives in words ("from now on the body force vanishes").
    let first = first_readers(equations, open);
    for (q, e) in equations.iter().enumerate() {
        let posits = e.defines.iter().any(|(k, _)| by_law.contains(k));
        if e.unread.is_some()
            || !(posits || (e.defines.is_empty() && law_form(&e.latex, defined_atom)))
        {
            continue;
        }
        let related: BTreeSet<&str> = e
            .reads
            .iter()
            .flat_map(&through)
            .map(|s| s.name.as_str())
            .collect();
        if related.len() < 2 {
            continue;
        }
        let why = format!(
            "equation ({}) may be a law the paper posits, which later equations use",
            e.number
        );
        for k in &e.reads {
            let new = first.get(k) == Some(&q);
            for s in through(k).into_iter().filter(|s| s.field || new) {
                add(&s.name, Some(e.line), why.clone(), TieKind::Law);
            }
        }
    }
    // What the reader cannot read at all is searched for each symbol's printed base.
    for (q, latex) in opaque {
        for (k, s) in symbols {
            let base = k.split('|').nth(1).unwrap_or("");
            if declared(k).is_some() && mentions(latex, base) {
                let e = &equations[*q];
                add(
                    &s.name,
                    Some(e.line),
                    format!("equation ({}), left to complete, may mention it", e.number),
                    TieKind::Any,
                );
            }
        }
    }
    // Each symbol's keys by their identity without the rank: `$m$` names `m_i` too.
    fn unranked(k: &Key) -> &str {
        k.rsplit_once('|').map_or(k.as_str(), |(head, _)| head)
    }
    let mut by_identity: BTreeMap<&str, Vec<&Key>> = BTreeMap::new();
    for k in symbols.keys() {
        by_identity.entry(unranked(k)).or_default().push(k);
    }
    let named = |keys: &[Key]| -> Vec<&Symbol> {
        keys.iter()
            .flat_map(|k| by_identity.get(unranked(k)).into_iter().flatten())
            .flat_map(|j| through(j))
            .collect()
    };
    // The line of the first equation to read each symbol.
    let first_line: BTreeMap<&Key, usize> = first
        .iter()
        .map(|(&k, &q)| (k, equations[q].line))
        .collect();
    for f in said {
        // A component of a vector the equations write with an index (`$n_1 =
        // \cos\theta$` beside `n_i`) is that vector.
        let vector = |k: &Key| symbols::vector_of(k, symbols).unwrap_or_else(|| k.clone());
        let found: Vec<Key> = f.found.iter().map(vector).collect();
        let parts: Vec<(Option<Key>, Vec<Key>)> = f
            .parts
            .iter()
            .map(|(l, r)| (l.as_ref().map(vector), r.iter().map(vector).collect()))
            .collect();
        let f = Said {
            found,
            parts,
            word: f.word.clone(),
            ..**f
        };
        let f = &f;
        // An equation that names a symbol no numbered equation has (`$\rho c_L^2 =
        // \lambda + 2\mu$`, `$f_i^{(2,1)c} = f_i^c$`) says what that symbol is: it
        // ties nothing else.
        let new = f
            .found
            .iter()
            .any(|k| !symbols.contains_key(k) && !open.contains_key(k));
        // `$\lambda = \frac{E\nu}{(1+\nu)(1-2\nu)}$`, with E and ν defined by the
        // equations from λ and μ: a definition read backwards (the right side's
        // definitions read the left symbol), which ties nothing.
        let backwards = f.parts.iter().all(|(left, right)| {
            let mut reach: BTreeSet<&Key> = BTreeSet::new();
            let mut stack: Vec<&Key> = right.iter().collect();
            while let Some(k) = stack.pop() {
                if let Some((_, body)) = chosen.get(k).filter(|_| reach.insert(k)) {
                    stack.extend(body.iter());
                }
                reach.insert(k);
            }
            left.as_ref().is_some_and(|l| reach.contains(l))
                && !right.is_empty()
                && right.iter().all(|k| chosen.contains_key(k))
        });
        // "Let the Young modulus $E$ be a constant", of a symbol the equations
        // differentiate (`E_{,j}`): its derivatives may be 0, which a failure may need.
        if f.constant {
            for s in named(&f.found).into_iter().filter(|s| s.field) {
                let why = "its sentence calls it constant".to_owned();
                add(&s.name, Some(f.line), why, TieKind::Any);
            }
        }
        // `$n_1 = \cos\theta$`: an equation of the text that relates the normal to other
        // symbols ties them (a claim may read the normal on one side, θ on the other).
        if f.relation && f.normal {
            for s in named(&f.found) {
                let why = "an equation in the text relates it to the normal".to_owned();
                add(&s.name, Some(f.line), why, TieKind::Any);
            }
        }
        // "… the unit normal $n_i$ … at angle $\theta$": a scalar named beside the
        // normal may parametrise it.
        if f.beside_normal {
            for s in named(&f.found).into_iter().filter(|s| s.rank == 0) {
                let why = "its sentence names it beside the normal".to_owned();
                add(&s.name, Some(f.line), why, TieKind::Any);
            }
        }
        // `$W = K e$`, with K and e in no numbered equation: W alone on its left is what
        // the text says, in symbols the draft does not read, and a numbered `W = …` is
        // then a claim about it that the text may tie.
        if f.relation && new {
            for (left, _) in &f.parts {
                let Some(k) = left.as_ref().filter(|k| symbols.contains_key(*k)) else {
                    continue;
                };
                for s in through(k) {
                    let why = "an equation in the text gives it in symbols no equation writes";
                    add(&s.name, Some(f.line), why.to_owned(), TieKind::Any);
                }
            }
        }
        if f.symmetry {
            for s in f.found.iter().filter_map(&declared) {
                let why = "the text states a symmetry of it".to_owned();
                add(&s.name, Some(f.line), why, TieKind::Any);
            }
        }
        if f.relation && !new && !backwards {
            // An equation with one symbol alone on its left (`$K = \lambda +
            // \frac23\mu$`) says what that symbol is, and ties it only; `$u_{k,k} = 0$`,
            // `$t_k n_k = 0$` tie every symbol they read.
            let lone: Vec<Key> = f.parts.iter().filter_map(|(l, _)| l.clone()).collect();
            // `$\det(\sigma_{ij} - \lambda\delta_{ij}) = 0$` with σ read before and λ
            // new: it says what the new symbols are, and ties them only.
            let fresh: Vec<Key> = f
                .found
                .iter()
                .filter(|k| first_line.get(k).is_some_and(|&l| l > f.line))
                .cloned()
                .collect();
            let relates = match (lone.is_empty(), fresh.is_empty()) {
                (false, _) => &lone,
                (true, false) => &fresh,
                (true, true) => &f.found,
            };
            let names: BTreeSet<&str> = named(&f.found).iter().map(|s| s.name.as_str()).collect();
            // An equation of one symbol relates it to no other: with a trace in it
            // (`$\varepsilon_{kk} = 0$`, `$u_{k,k} = 0$`) it gives a reason for a zero
            // trace; with the symbol on both sides (`$\varepsilon_{ij} =
            // \varepsilon_{ji}$`: a symmetry, which like a unit length needs no reason),
            // none; a value (`$W = 0$`), a reason for any tie.
            let both_sides = f.parts.iter().any(|(_, right)| {
                right.iter().any(|k| {
                    f.found
                        .first()
                        .is_some_and(|first| unranked(k) == unranked(first))
                })
            });
            match (names.len() == 1, f.trace) {
                (true, false) if both_sides => {}
                (true, true) => {
                    for s in named(relates) {
                        let why = "an equation in the text sets a trace of it".to_owned();
                        add(&s.name, Some(f.line), why, TieKind::Trace);
                    }
                }
                _ => {
                    for s in named(relates) {
                        let why = "an equation in the text relates it to others".to_owned();
                        add(&s.name, Some(f.line), why, TieKind::Any);
                    }
                }
            }
        } else if let Some(w) = &f.word {
            for s in named(&f.found) {
                add(
                    &s.name,
                    Some(f.line),
                    format!("its sentence says \"{w}\""),
                    tie_kind(w),
                );
            }
        }
    }
    // A labelled variant: the same base (and name suffix), another accent, label or
    // primes.
    let parts = |k: &Key| -> Option<(String, String)> {
        let f: Vec<&str> = k.split('|').collect();
        let [accent, base, sup, primes, suffix, _rank] = f[..] else {
            return None;
        };
        Some((
            format!("{base}|{suffix}"),
            format!("{accent}|{sup}|{primes}"),
        ))
    };
    for (k, s) in symbols {
        if declared(k).is_none() {
            continue;
        }
        let Some((stem, label)) = parts(k) else {
            continue;
        };
        // A variant the draft defines from this symbol (`\sigma'_{ij} = \sigma_{ij} -
        // p\delta_{ij}`) is related to it by that definition, in the file.
        let reaches = |from: &Key, to: &Key| {
            let mut stack = vec![from];
            let mut seen: BTreeSet<&Key> = BTreeSet::new();
            while let Some(x) = stack.pop() {
                if x == to {
                    return true;
                }
                if seen.insert(x) {
                    stack.extend(chosen.get(x).into_iter().flat_map(|(_, body)| body));
                }
            }
            false
        };
        let variant = symbols.iter().find(|(j, t)| {
            !t.component
                && parts(j).is_some_and(|(st, la)| st == stem && la != label)
                && !reaches(j, k)
                && !reaches(k, j)
        });
        // Or a formula of the text writes one (`$m_i = \mu_{ki} n_k$` beside `m^{(n)}`,
        // which the text may name in words only: "its squared magnitude $m^{(n)}$").
        let in_text = || {
            said.iter().find_map(|f| {
                f.found
                    .iter()
                    .find(|j| {
                        !symbols.contains_key(*j)
                            && parts(j).is_some_and(|(st, la)| st == stem && la != label)
                    })
                    .map(|j| (f.line, j))
            })
        };
        if let Some((_, t)) = variant {
            add(
                &s.name,
                None,
                format!("the paper also writes {}", t.key.0),
                TieKind::Any,
            );
        } else if let Some((line, j)) = in_text() {
            let base = j.split('|').nth(1).unwrap_or("");
            add(
                &s.name,
                Some(line),
                format!("a formula of the text writes {base} with another label"),
                TieKind::Any,
            );
        }
        // A symbol whose square an equation states (`T^2 = \langle … \rangle`, with `T`
        // written elsewhere): that equation is a claim about it, and may be what the
        // paper means by it.
        if let Some(&q) = squares.get(k) {
            let e = &equations[q];
            add(
                &s.name,
                Some(e.line),
                format!("equation ({}) states its square", e.number),
                TieKind::Any,
            );
        }
    }
    out
}

struct Render<'a> {
    label: &'a str,
    equations: &'a [Equation],
    /// The symmetries the text states, each for the claims of its section.
    symmetric: &'a [symmetry::SymmetryOf],
    symbols: &'a BTreeMap<Key, Symbol>,
    order: &'a [Key],
    defined: &'a BTreeMap<Key, String>,
    entries: &'a [(String, String)],
    define_lines: &'a [(String, String)],
    dimension: usize,
    normal: Option<&'a str>,
    position: Option<&'a str>,
    /// Displays without a number, and numbered equations past [`MAX_EQUATIONS`].
    unnumbered: (usize, usize),
    with_slots: &'a dyn Fn(&Symbol) -> String,
    /// The declared symbols the paper may tie to others: line, why, and whether only
    /// a trace.
    tied: &'a BTreeMap<String, (Option<usize>, String, TieKind)>,
}

/// The file's text.
fn render(r: Render<'_>) -> String {
    let mut out = String::new();
    let todo: Vec<&Equation> = r.equations.iter().filter(|e| e.unread.is_some()).collect();
    out.push_str(&format!(
        "# Drafted by `cosserat-check draft` from {}.\n",
        comment(r.label)
    ));
    out.push_str(&format!(
        "# {} numbered equations: {} claims, {} to complete (below); {} displays without a number not drafted.\n",
        r.equations.len(),
        r.equations.len() - todo.len(),
        todo.len(),
        r.unnumbered.0
    ));
    if r.unnumbered.1 > 0 {
        out.push_str(&format!(
            "# {} numbered equations after the first {MAX_EQUATIONS} not drafted (the most one draft takes).\n",
            r.unnumbered.1
        ));
    }
    out.push_str(
        "# Conventions of the draft: a subscript of two or more characters, or a letter that\n",
    );
    out.push_str(
        "# occurs more than once in an equation's subscripts, holds index slots; a one-letter\n",
    );
    out.push_str(
        "# subscript met once (or one Greek letter) completes a scalar's name (R_g, mu_tau); a\n",
    );
    out.push_str(
        "# symbol first seen alone on the left of an equation is defined by it, and so is one\n",
    );
    out.push_str(
        "# an equation of the text introduces, or the new term of a decomposition its sentence\n",
    );
    out.push_str(
        "# announces; an equation that reads a symbol an earlier equation left to complete may\n",
    );
    for line in [
        "# define is left to complete too, and so is one after the text turns to another",
        "# number of dimensions; a labelled symbol takes its unlabelled symbol's linear",
        "# definition on the same labels (K^{(1)} from K = w_{j,i} and w^{(1)}), and one",
        "# whose decomposition the text repeats (\"similarly\") the analogous definition; a",
        "# field the text linearises about a point has no second derivatives; a tensor the",
        "# text calls symmetric (or skew) in so many words is assumed so in the claims of",
        "# its section. Check each reading before trusting a verdict. Every declared symbol",
        "# is taken as independent, so a failure that a common tie between symbols would",
        "# remove (one side reads what the other does not, a relation, a symmetric tensor, a",
        "# unit vector) is left undecided, naming the tie; delete `drafted = true` once the",
        "# declarations are checked, to decide every claim strictly.",
    ] {
        out.push_str(line);
        out.push('\n');
    }
    out.push_str(&format!("section = \"{}\"\n", "1"));
    if !todo.is_empty() {
        out.push_str(
            "# The equations the draft could not read: each stays below as a commented claim;\n",
        );
        out.push_str(
            "# `verify` lists them, with the reason and the edit that would let each be read.\n",
        );
        out.push_str("to_complete = [\n");
        for e in &todo {
            out.push_str(&format!(
                "  {{ id = {}, line = {}, reason = {}",
                toml_string(&e.id),
                e.line,
                toml_string(&comment(e.unread.as_deref().unwrap_or("")))
            ));
            if let Some(edit) = &e.edit {
                out.push_str(&format!(", edit = {}", toml_string(&comment(edit))));
            }
            out.push_str(" },\n");
        }
        out.push_str("]\n");
    }
    if !r.tied.is_empty() {
        out.push_str(
            "# The symbols the paper may tie to others, in words or in an equation left to\n",
        );
        out.push_str(
            "# complete: a failure that only a tie of one of them would remove is undecided.\n",
        );
        out.push_str("# Delete an entry to decide such failures strictly.\n");
        out.push_str("tied = [\n");
        for (name, (line, why, kind)) in r.tied {
            out.push_str(&format!("  {{ symbol = {}", toml_string(name)));
            if let Some(l) = line {
                out.push_str(&format!(", line = {l}"));
            }
            out.push_str(&format!(", why = {}", toml_string(&comment(why))));
            out.push_str(match kind {
                TieKind::Trace => ", tie = 'trace'",
                TieKind::Divergence => ", tie = 'divergence'",
                TieKind::Law => ", tie = 'law'",
                TieKind::Any => "",
            });
            out.push_str(" },\n");
        }
        out.push_str("]\n");
    }
    out.push_str(&format!(
        "title = {}\n",
        toml_string(&format!("drafted from {}", r.label))
    ));
    out.push_str(&format!("dimension = {}\n", r.dimension));
    out.push_str("drafted = true\n");
    if let Some(n) = r.normal {
        out.push_str(&format!("normal = {}\n", toml_string(n)));
    }
    if let Some(p) = r.position {
        out.push_str(&format!("position = {}\n", toml_string(p)));
    }
    let declared: Vec<&Symbol> = r
        .order
        .iter()
        .filter(|k| !r.defined.contains_key(*k))
        .map(|k| &r.symbols[k])
        .filter(|s| !s.component)
        .collect();
    let list = |items: Vec<String>| {
        items
            .iter()
            .map(|s| toml_string(s))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let fields: Vec<String> = declared
        .iter()
        .filter(|s| s.field)
        .map(|s| (r.with_slots)(s))
        .collect();
    let tensors: Vec<String> = declared
        .iter()
        .filter(|s| !s.field && s.rank > 0)
        .map(|s| (r.with_slots)(s))
        .collect();
    let scalars: Vec<String> = declared
        .iter()
        .filter(|s| !s.field && s.rank == 0)
        .map(|s| s.name.clone())
        .collect();
    if !fields.is_empty() {
        out.push_str(&format!("fields = [{}]\n", list(fields)));
    }
    if !tensors.is_empty() {
        out.push_str(&format!("tensors = [{}]\n", list(tensors)));
    }
    if !scalars.is_empty() {
        out.push_str(&format!("scalars = [{}]\n", list(scalars)));
    }
    if !r.define_lines.is_empty() {
        out.push_str("define = [\n");
        for (text, id) in r.define_lines {
            out.push_str(&format!("  {},  # from {id}\n", toml_string(text)));
        }
        out.push_str("]\n");
    }
    if !r.entries.is_empty() {
        out.push_str("\n[notation]\n");
        for (key, value) in r.entries {
            out.push_str(&format!("{} = {}\n", toml_string(key), toml_string(value)));
        }
    }
    // Which claim defines each symbol, for `uses`.
    let mut definer: BTreeMap<&Key, &str> = BTreeMap::new();
    for e in r.equations.iter().filter(|e| e.unread.is_none()) {
        for (k, _) in &e.defines {
            definer.insert(k, &e.id);
        }
    }
    // `uses` without a cycle: an edge that would close one (a definition stated after
    // the claim that reads it, which reads back) is left out.
    let mut graph: BTreeMap<&str, BTreeSet<&str>> = BTreeMap::new();
    let reaches = |graph: &BTreeMap<&str, BTreeSet<&str>>, from: &str, to: &str| {
        let mut stack = vec![from];
        let mut seen = BTreeSet::new();
        while let Some(n) = stack.pop() {
            if n == to {
                return true;
            }
            if seen.insert(n) {
                stack.extend(graph.get(n).into_iter().flatten().copied());
            }
        }
        false
    };
    for e in r.equations {
        out.push('\n');
        let mut table = format!(
            "[[claim]]\nid = \"{}\"\nprinted = {}\n",
            e.id,
            toml_string(&e.latex)
        );
        if e.numeric {
            table.push_str("strategy = \"numeric\"\n");
        }
        if !e.introduces.is_empty() && e.unread.is_none() {
            let names: Vec<String> = e.introduces.iter().map(|n| toml_string(n)).collect();
            table.push_str(&format!("introduces = [{}]\n", names.join(", ")));
        }
        let mut notes = Vec::new();
        if e.verbatim {
            table.push_str("verbatim = true\n");
            notes.push("As printed, its members carry different free indices: it is checked for every value of each.".to_owned());
        }
        if !e.stray.is_empty() {
            let printed: Vec<&str> = e.stray.iter().map(String::as_str).collect();
            notes.push(format!(
                "Read with a stray subscript: {} carries an index that its equation does not, and is read as the scalar the paper also prints without it.",
                printed.join(", ")
            ));
        }
        let (linear, number) = &e.linear;
        let linear: Vec<&Symbol> = linear.iter().filter_map(|k| r.symbols.get(k)).collect();
        let mut hypotheses: Vec<String> = linear
            .iter()
            .map(|s| {
                let letters: Vec<char> = "ijklpqrs".chars().take(s.rank + 2).collect();
                let (own, by) = letters.split_at(s.rank);
                let own: String = own.iter().collect();
                let by: String = by.iter().collect();
                toml_string(&format!("{}_{own},{by} = 0", s.name))
            })
            .collect();
        if !linear.is_empty() {
            let names: Vec<&str> = linear.iter().map(|s| s.key.0.as_str()).collect();
            notes.push(format!(
                "The text before equation ({}) linearises {} about a point: {} second derivatives vanish.",
                comment(number),
                names.join(", "),
                if names.len() == 1 { "its" } else { "their" }
            ));
        }
        for sym in r.symmetric.iter().filter(|s| s.section.contains(&e.line)) {
            hypotheses.push(toml_string(&sym.kind.assumption(&sym.name)));
            let short: String = sym.quote.chars().take(100).collect();
            let ellipsis = if short.len() < sym.quote.len() {
                "…"
            } else {
                ""
            };
            notes.push(format!(
                "The text, line {}, calls {} {}: \"{short}{ellipsis}\"",
                sym.line,
                sym.printed,
                sym.kind.word()
            ));
        }
        if !hypotheses.is_empty() {
            table.push_str(&format!("assume = [{}]\n", hypotheses.join(", ")));
        }
        if !notes.is_empty() {
            table.push_str(&format!("note = {}\n", toml_string(&notes.join(" "))));
        }
        let mut uses: BTreeSet<&str> = BTreeSet::new();
        for target in e.reads.iter().filter_map(|k| definer.get(k).copied()) {
            if target != e.id && e.unread.is_none() && !reaches(&graph, target, &e.id) {
                graph.entry(e.id.as_str()).or_default().insert(target);
                uses.insert(target);
            }
        }
        if !uses.is_empty() {
            table.push_str(&format!(
                "uses = [{}]\n",
                uses.iter()
                    .map(|u| format!("\"{u}\""))
                    .collect::<Vec<_>>()
                    .join(", ")
            ));
        }
        if e.unread.is_some() {
            out.push_str(&format!(
                "# To complete: equation ({}), line {}.\n",
                comment(&e.number),
                e.line
            ));
            for line in table.lines() {
                out.push_str(&format!("# {line}\n"));
            }
        } else {
            out.push_str(&table);
        }
    }
    out
}

/// `text` as a TOML string: literal when it can be, else basic with escapes.
fn toml_string(text: &str) -> String {
    if !text.contains('\'') && !text.chars().any(char::is_control) {
        return format!("'{text}'");
    }
    let mut out = String::from("\"");
    for c in text.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if c.is_control() => out.push_str(&format!("\\u{:04X}", c as u32)),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// `text` on one comment line: control characters (a newline would end the comment)
/// and the bidirectional controls (which reorder what a reader sees) shown as spaces.
fn comment(text: &str) -> String {
    use crate::derivation::control::forbidden;
    text.chars()
        .map(|c| {
            if c.is_control() || forbidden(c) {
                ' '
            } else {
                c
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_trace_is_a_repeated_index_in_one_subscript() {
        for (formula, trace) in [
            ("\\varepsilon_{kk} = 0", true),
            ("u_{k,k} = 0", true),
            ("\\varepsilon_{ij} = \\varepsilon_{ji}", false),
            ("n_k n_k = 1", false),
            ("a_i", false),
        ] {
            assert_eq!(repeated_index(formula), trace, "{formula}");
        }
    }

    #[test]
    fn words_name_a_symbol_by_its_base_letter() {
        let key = |base: &str| format!("|{base}||0||1");
        assert!(names("where n_i is the unit normal", &key("n")));
        assert!(names("where σ is symmetric", &key("\\sigma")));
        assert!(names("with \\sigma_{ij} symmetric", &key("\\sigma")));
        assert!(!names("where nn is", &key("n")));
        assert!(!names("in which the normal", &key("n")));
    }

    #[test]
    fn words_that_tie_and_formulas_of_unit_length() {
        for (words, tie) in [
            (
                "their equal and opposite reactions x and x",
                Some("opposite"),
            ),
            ("the Deviatoric stress x", Some("deviatoric")),
            ("an incompressible body", Some("incompressible")),
            ("x is orthogonal to y", Some("orthogonal")),
            ("The Cauchy stress is symmetric,", None),
            ("Let x be a unit vector.", None),
            ("Let x be the strain.", None),
        ] {
            assert_eq!(tie_word(words).as_deref(), tie, "{words}");
        }
        for (formula, letter) in [
            ("n_k n_k = 1", Some("n")),
            ("n_{i}n_{i}=1", Some("n")),
            ("|\\mathbf{n}| = 1", Some("n")),
            ("\\|m\\| = 1", Some("m")),
            ("n \\cdot n = 1", Some("n")),
            ("n_k n_k = 2", None),
            ("n_k m_k = 1", None),
            ("n_k n_j = 1", None),
            ("|n| < 1", None),
        ] {
            assert_eq!(unit_length(formula).as_deref(), letter, "{formula}");
        }
    }

    /// The draft of `source` with the default options, nothing refused or sampled.
    fn plain_draft(label: &str, source: &str) -> Draft {
        draft(
            label,
            source,
            &Options::default(),
            (&BTreeMap::new(), &BTreeSet::new()),
        )
    }

    #[test]
    fn a_definition_and_an_identity_from_markdown() {
        let source = "$$P = \\sigma_{ij}\\Gamma_{ij} + \\mu_{ij}K_{ij} \\quad (3)$$\n\nText.\n\n$$P = \\Gamma_{ij}\\sigma_{ij} + K_{ij}\\mu_{ij} \\quad (4)$$\n";
        let d = plain_draft("paper.md", source);
        assert_eq!((d.equations, d.claims), (2, 2), "{}", d.toml);
        assert!(
            d.toml
                .contains("'P = sigma_ij Gamma_ij + mu_ij K_ij',  # from eq3"),
            "{}",
            d.toml
        );
        assert!(d.toml.contains("uses = [\"eq3\"]"), "{}", d.toml);
        let f = crate::derivation::load_str("d.toml", &d.toml).unwrap();
        assert_eq!(f.claims.len(), 2);
    }

    #[test]
    fn what_cannot_be_read_is_kept_to_complete() {
        let source = "$$a = \\frobnicate{b} \\quad (1)$$\n$$x' = \\text{broken (2)$$";
        let d = plain_draft("p.tex", source);
        assert_eq!(d.equations, 2);
        assert_eq!(d.claims, 0, "{}", d.toml);
        assert!(
            d.toml.contains("{ id = 'eq1', line = 1, reason = "),
            "{}",
            d.toml
        );
        assert!(d.toml.contains("# [[claim]]\n# id = \"eq1\""), "{}", d.toml);
        crate::derivation::load_str("d.toml", &d.toml).unwrap();
    }

    #[test]
    fn hostile_text_stays_inside_its_strings_and_comments() {
        let source = "$$a = b \\quad (1)$$\n$$x = '''\n[[claim]]\nid = \"evil\" \\quad (2)$$";
        let d = plain_draft("p\nwith [[claim]] newline.tex", source);
        let f = crate::derivation::load_str("d.toml", &d.toml).unwrap();
        assert!(f.claims.iter().all(|c| c.id != "evil"), "{}", d.toml);
        // The label's newline is a space in the header comment.
        assert!(d.toml.starts_with(
            "# Drafted by `cosserat-check draft` from p with [[claim]] newline.tex.\n"
        ));
    }
}
