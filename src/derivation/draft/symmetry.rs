//! A symmetry the text states of a tensor: "The stress $\sigma_{ij}$ is symmetric.",
//! "Let $S_{ij}$ be a symmetric tensor.", "The spin $W_{ij}$ is skew-symmetric.", or
//! "The strain tensor is symmetric." where the paper writes the same noun phrase right
//! before one symbol ("small strain $\varepsilon_{ij}$").
//!
//! The draft writes such a symmetry as an assumption of the claims of its section
//! (`symmetric(sigma)`, `antisymmetric(W)`), so that a claim true only for a symmetric
//! stress holds, and one false even for it fails, where before either was undecided
//! ("σ being symmetric would remove the difference"). Read wrongly, it would make a false
//! claim hold; two adversaries broke looser versions 45 ways. So a sentence states a
//! symmetry only in a few fixed shapes, whole:
//!
//! - `[prefix] [the] [nouns] $X$ is symmetric [tail].`, `[prefix] the nouns is
//!   symmetric [tail].`, `Let $X$ be a symmetric nouns [tail].`, `Let $X$ denote the
//!   nouns, which is symmetric [tail].`; the prefix one of "let", "here", "note that",
//!   "recall that", "by the balance of angular momentum"; the tail nothing, the same
//!   symmetry in components (`, $\sigma_{12} = \sigma_{21}$`) or "by the balance of
//!   angular momentum", then perhaps a description after a comma ("describing the
//!   anisotropy", "with traction $t_i = \sigma_{ji} n_j$", "and we use this
//!   throughout") with no word of place ("for", "away", …) or symmetry, whose formulas
//!   are symbols or define other symbols; the formula one symbol with two index letters
//!   or none. Anything else in the sentence ("about the axis", "in the absence of
//!   couple stresses", "for $\ell = 0$", "(see Fig. 2)", a question) makes it state
//!   nothing, and so does a formula alone (`$\sigma_{12} = \sigma_{21}$` is one pair of
//!   components).
//! - The sentence and each of the two after it that speaks of it ("this", "it", a
//!   symmetry word) neither deny nor contrast ("not", "isn't", "no longer", "differs",
//!   "but", "only", …); it stands outside every environment (a lemma, a quotation).
//! - No sentence of the paper speaks of a symmetry with a denial or a restriction ("σ is
//!   not symmetric", "non-symmetric", "symmetric only in …"), and no word names a medium
//!   with couple stresses ("couple", "polar", "Cosserat"): either tells symmetric and
//!   other stresses apart in ways a few shapes cannot follow, and no symmetry is read.
//! - A noun phrase names the one symbol the paper writes right after the same phrase,
//!   up to an article, "tensor" or "field", a plural and the adjectives of a small
//!   strain ("small", "infinitesimal", "linear"): "the stress" is neither "the Cauchy
//!   stress" nor "the couple stress".
//! - It holds for the claims of its own section (from the heading before it to the
//!   next, however LaTeX or Markdown spells the heading).
//!
//! [`symmetric_tensors`] settles which declared symbol each statement names.

use super::displays::Sentence;
use super::symbols::{self, Key, Stems, Symbol};
use crate::lang::latex::{self, MathKind, ReadOptions};
use std::collections::{BTreeMap, BTreeSet};

/// Which symmetry.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Kind {
    Symmetric,
    Antisymmetric,
}

impl Kind {
    /// The file's assumption for the symbol `name`.
    pub fn assumption(self, name: &str) -> String {
        match self {
            Kind::Symmetric => format!("symmetric({name})"),
            Kind::Antisymmetric => format!("antisymmetric({name})"),
        }
    }

    pub fn word(self) -> &'static str {
        match self {
            Kind::Symmetric => "symmetric",
            Kind::Antisymmetric => "antisymmetric",
        }
    }
}

/// What a sentence says is symmetric: a formula (one symbol), or a noun phrase the
/// paper writes elsewhere right before a formula.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Subject {
    Formula(String),
    Noun(Vec<String>),
}

/// A symmetry the text states: its line, its subject, which symmetry, the sentence,
/// and the lines of its section (the claims it holds for).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Symmetry {
    pub line: usize,
    pub subject: Subject,
    pub kind: Kind,
    pub quote: String,
    pub section: std::ops::Range<usize>,
}

/// What the text's sentences say: the symmetries they state, and the noun phrase the
/// paper writes right before each formula.
#[derive(Clone, Debug, Default)]
pub struct Statements {
    pub symmetries: Vec<Symmetry>,
    pub nouns: Vec<(Vec<String>, String)>,
}

/// Words that deny.
const DENIALS: &[&str] = &[
    "not",
    "no",
    "nor",
    "neither",
    "never",
    "cannot",
    "non",
    "need",
    "needs",
    "none",
    "nothing",
    "lacks",
    "lack",
    "fails",
    "fail",
    "lose",
    "loses",
    "lost",
    "isn",
    "aren",
    "wasn",
    "weren",
    "doesn",
    "don",
    "won",
    "nt",
    "longer",
    "drop",
    "drops",
    "relax",
    "relaxed",
    "relaxes",
    "leave",
    "aside",
    "violate",
    "violated",
    "violates",
    "break",
    "broken",
    "breaks",
    "absent",
    "cease",
    "ceases",
    "ceased",
    "false",
    "wrong",
    "incorrect",
    "disappear",
    "disappears",
    "refute",
    "refutes",
    "refuted",
    "unequal",
    "differ",
    "differs",
    "different",
    "nonzero",
    "imagine",
    "pretend",
];

/// Words that name media whose stress need not be symmetric (couple stresses act in
/// them): a paper that uses one tells symmetric and other stresses apart in ways a few
/// shapes of sentence cannot follow, and no symmetry is read in it.
const POLAR: &[&str] = &[
    "couple",
    "couples",
    "polar",
    "micropolar",
    "micro-polar",
    "cosserat",
    "micromorphic",
    "strain-gradient",
];

/// Words that qualify, beside the [`RESTRICTIONS`]: a statement with one of them, or
/// followed by one that speaks of it, states nothing.
const QUALIFIERS: &[&str] = &[
    "while",
    "otherwise",
    "if",
    "when",
    "whenever",
    "provided",
    "suppose",
    "supposing",
    "were",
    "would",
    "could",
    "might",
    "may",
    "classical",
    "limit",
    "special",
    "case",
    "approximately",
    "nearly",
    "almost",
    "up",
    "apart",
];

/// Words that restrict a symmetry wherever it is spoken of ("symmetric only in …", "but
/// not …"): a sentence with one of them withdraws every reading.
const RESTRICTIONS: &[&str] = &[
    "but",
    "however",
    "although",
    "though",
    "whereas",
    "unlike",
    "except",
    "only",
    "rather",
    "instead",
    "contrary",
    "differently",
    "unless",
    "iff",
];

/// Prefixes a statement may open with.
const PREFIXES: &[&[&str]] = &[
    &["let"],
    &["now", "let"],
    &["here"],
    &["note", "that"],
    &["recall", "that"],
    &["we", "note", "that"],
    &["by", "the", "balance", "of", "angular", "momentum"],
];

/// Words that end no noun phrase: the grammar around it.
const GRAMMAR: &[&str] = &[
    "the",
    "a",
    "an",
    "of",
    "by",
    "to",
    "from",
    "on",
    "onto",
    "into",
    "at",
    "in",
    "over",
    "under",
    "about",
    "through",
    "between",
    "and",
    "or",
    "with",
    "without",
    "for",
    "is",
    "are",
    "be",
    "being",
    "was",
    "were",
    "which",
    "that",
    "this",
    "these",
    "its",
    "their",
    "whose",
    "let",
    "here",
    "we",
    "denote",
    "denotes",
    "denoted",
    "as",
    "symmetric",
    "skew-symmetric",
    "antisymmetric",
    "anti-symmetric",
    "product",
    "part",
    "parts",
    "derivative",
    "gradient",
    "rate",
    "inverse",
    "transpose",
    "sum",
    "difference",
    "square",
    "trace",
    "consider",
    "under",
    "write",
    "take",
];

/// Words a noun phrase may carry that name no other tensor.
const ADJECTIVES: &[&str] = &[
    "small",
    "infinitesimal",
    "linear",
    "linearised",
    "linearized",
];

/// Nouns that name a kind, not a quantity.
const KINDS: &[&str] = &["tensor", "field", "matrix"];

#[derive(Clone, Debug, PartialEq, Eq)]
enum Token {
    Word(String),
    /// The k-th formula of the sentence.
    Formula(usize),
    /// `,`, `;`, `:`, `(`, `)`, `?`, `!`, `.` inside the sentence.
    Mark(char),
}

/// The sentence's words (lowercase; an apostrophe splits `isn't` into `isn`, `t`),
/// formulas and marks, in order, and whether it ends as a statement (`.` or `;`).
fn tokens(s: &Sentence) -> (Vec<Token>, bool) {
    let mut out = Vec::new();
    let mut word = String::new();
    let flush = |word: &mut String, out: &mut Vec<Token>, at: usize| {
        let w = word.trim_end_matches('-');
        if !w.is_empty() {
            let start = at - word.len();
            // A formula stands as ` x ` at its offset: its `x` is the formula.
            match s.formulas.iter().position(|(f, _)| *f + 1 == start) {
                Some(k) if w == "x" => out.push(Token::Formula(k)),
                _ => out.push(Token::Word(w.to_lowercase())),
            }
        }
        word.clear();
    };
    let body = s.words.trim_end();
    let (body, statement) = match body.strip_suffix(['.', ';']) {
        Some(b) => (b, true),
        None => (body, false),
    };
    for (at, c) in body.char_indices() {
        if c.is_alphanumeric() || (c == '-' && !word.is_empty()) {
            word.push(c);
            continue;
        }
        flush(&mut word, &mut out, at);
        if !c.is_whitespace() && !matches!(c, '{' | '}' | '~' | '-' | '\\') {
            out.push(Token::Mark(c));
        }
    }
    flush(&mut word, &mut out, body.len());
    // "skew symmetric", "anti symmetric", "skew\-symmetric", "skew--symmetric": one word.
    let mut merged: Vec<Token> = Vec::with_capacity(out.len());
    for t in out {
        let t = match t {
            Token::Word(w) if w.contains("--") => {
                let mut w = w;
                while w.contains("--") {
                    w = w.replace("--", "-");
                }
                Token::Word(w)
            }
            t => t,
        };
        if let (Some(Token::Word(prefix)), Token::Word(w)) = (merged.last(), &t) {
            if matches!(prefix.as_str(), "skew" | "anti")
                && w.trim_start_matches('-') == "symmetric"
            {
                let joined = format!("{prefix}-symmetric");
                merged.pop();
                merged.push(Token::Word(joined));
                continue;
            }
        }
        merged.push(t);
    }
    (merged, statement)
}

fn word(t: Option<&Token>) -> Option<&str> {
    match t {
        Some(Token::Word(w)) => Some(w),
        _ => None,
    }
}

/// The symmetry a word names, if it names one on its own.
fn kind_of(w: &str) -> Option<Kind> {
    match w {
        "symmetric" => Some(Kind::Symmetric),
        "skew-symmetric" | "antisymmetric" | "anti-symmetric" | "skew" => Some(Kind::Antisymmetric),
        _ => None,
    }
}

/// A noun phrase, normalised: no article, kind or adjective, each noun singular.
fn phrase(words: &[&str]) -> Vec<String> {
    words
        .iter()
        .filter(|w| !KINDS.contains(&singular(w).as_str()) && !ADJECTIVES.contains(w))
        .map(|w| singular(w))
        .collect()
}

fn singular(w: &str) -> String {
    match w.strip_suffix('s') {
        Some(stem) if !stem.ends_with('s') && stem.len() > 2 => stem.to_owned(),
        _ => w.to_owned(),
    }
}

fn is_noun(t: &Token) -> bool {
    word(Some(t)).is_some_and(|w| {
        !GRAMMAR.contains(&w)
            && !DENIALS.contains(&w)
            && !RESTRICTIONS.contains(&w)
            && !QUALIFIERS.contains(&w)
            && w.chars().all(|c| c.is_alphabetic() || c == '-')
    })
}

/// The symmetries `sentences` state ([`Symmetry`]), each held for its section
/// (`headings`: the lines where sections start, sorted), outside the environments of
/// `enclosed` (by lines, sorted, not overlapping), and the noun phrases before formulas.
pub fn read(
    sentences: &[Sentence],
    headings: &[usize],
    enclosed: &[std::ops::Range<usize>],
) -> Statements {
    let mut said = Statements::default();
    let read: Vec<(Vec<Token>, bool)> = sentences.iter().map(tokens).collect();
    let speaks = |t: &[Token]| {
        t.iter()
            .any(|t| word(Some(t)).is_some_and(|w| w.contains("symmetr") || w == "skew"))
    };
    // A denial, or for a statement's own sentences any contrast or qualification too.
    let denies = |t: &[Token], also: &[&str]| {
        t.iter().any(|t| {
            word(Some(t)).is_some_and(|w| {
                DENIALS.contains(&w)
                    || also.contains(&w)
                    || w == "t"
                    || ["asym", "unsym", "un-sym", "nonsym", "non-sym", "dissym"]
                        .iter()
                        .any(|n| w.starts_with(n))
            })
        })
    };
    let polar = read
        .iter()
        .flat_map(|(t, _)| t)
        .any(|t| word(Some(t)).is_some_and(|w| POLAR.contains(&w)));
    if polar {
        return said;
    }
    for (s, (t, _)) in sentences.iter().zip(&read) {
        for (k, tok) in t.iter().enumerate() {
            if let Token::Formula(f) = tok {
                let start = t[..k]
                    .iter()
                    .rposition(|t| !is_noun(t))
                    .map_or(0, |j| j + 1);
                let words: Vec<&str> = t[start..k].iter().filter_map(|t| word(Some(t))).collect();
                said.nouns.push((phrase(&words), s.formulas[*f].1.clone()));
            }
        }
        let transposes = s.formulas.iter().any(|(_, b)| transposed(b).is_some());
        if (speaks(t) || transposes) && denies(t, RESTRICTIONS) {
            // One denial or contrast of a symmetry anywhere: nothing is read.
            said.symmetries.clear();
            return said;
        }
    }
    let mut stated_at: Vec<(usize, Symmetry)> = Vec::new();
    for (n, (s, (t, statement))) in sentences.iter().zip(&read).enumerate() {
        // The sentence, and each of the two after it that speaks of it or of a symmetry
        // ("this is no longer true", "it holds only for …"), neither denies nor
        // contrasts.
        let speaks_of_it = |t: &[Token]| {
            speaks(t)
                || t.iter().any(|t| {
                    matches!(
                        word(Some(t)),
                        Some("this" | "it" | "that" | "these" | "those" | "such" | "which" | "so")
                    )
                })
        };
        let withdrawn = read[n..].iter().take(3).enumerate().any(|(k, (t, _))| {
            (k == 0 || speaks_of_it(t)) && (denies(t, RESTRICTIONS) || denies(t, QUALIFIERS))
        });
        if !statement || withdrawn || inside(enclosed, s.line) {
            continue;
        }
        let Some((subject, kind)) = stated(t, s) else {
            continue;
        };
        stated_at.push((
            n,
            Symmetry {
                line: s.line,
                subject,
                kind,
                quote: restored(s),
                section: section(headings, s.line),
            },
        ));
    }
    // A sentence that gives a tensor stated symmetric a skew part ("once the grains
    // rotate, the stress $\sigma_{ij}$ acquires a skew part"): the statement was of one
    // state of it only.
    let skewed = |t: &[Token]| {
        t.iter()
            .any(|t| word(Some(t)).is_some_and(|w| SKEW.iter().any(|p| w.starts_with(p))))
    };
    stated_at.retain(|(at, sym)| {
        sym.kind != Kind::Symmetric
            || !sentences
                .iter()
                .zip(&read)
                .enumerate()
                .any(|(n, (s, (t, _)))| {
                    let names = match &sym.subject {
                        Subject::Formula(x) => atom(x).is_some_and(|base| {
                            s.formulas.iter().any(|(_, f)| f.contains(base.as_str()))
                        }),
                        Subject::Noun(noun) => noun.last().is_some_and(|head| {
                            t.iter().any(|t| word(Some(t)) == Some(head.as_str()))
                        }),
                    };
                    n != *at && skewed(t) && names
                })
    });
    said.symmetries
        .extend(stated_at.into_iter().map(|(_, sym)| sym));
    said
}

/// Beginnings of words that give a tensor a skew part.
const SKEW: &[&str] = &[
    "skew", "asym", "unsym", "nonsym", "non-sym", "antisym", "anti-sym",
];

/// Whether a sentence hedges what it says: a denial, a restriction or a qualifier
/// ("not", "isn't", "only", "if", "would", "classical"). The readings of a posited law
/// and of a vector's components refuse such a sentence, as this one does.
pub fn hedged(words: &str) -> bool {
    words
        .to_lowercase()
        .split(|c: char| !c.is_alphanumeric() && c != '-')
        .any(|w| {
            DENIALS.contains(&w) || RESTRICTIONS.contains(&w) || QUALIFIERS.contains(&w) || w == "t"
        })
}

/// The lines of the section `line` is in: from the heading before it (or the start) to
/// the next (or the end), given the headings' lines in order.
pub fn section(headings: &[usize], line: usize) -> std::ops::Range<usize> {
    let k = headings.partition_point(|&h| h <= line);
    let from = k.checked_sub(1).map_or(0, |j| headings[j]);
    from..headings.get(k).copied().unwrap_or(usize::MAX)
}

/// Whether `line` lies in one of `ranges` (sorted, not overlapping).
fn inside(ranges: &[std::ops::Range<usize>], line: usize) -> bool {
    let k = ranges.partition_point(|r| r.end <= line);
    ranges.get(k).is_some_and(|r| r.contains(&line))
}

/// The subject and symmetry of a sentence in one of the fixed shapes, if it is one.
fn stated(t: &[Token], s: &Sentence) -> Option<(Subject, Kind)> {
    let words_at = |k: usize, w: &[&str]| {
        w.iter()
            .enumerate()
            .all(|(j, w)| word(t.get(k + j)) == Some(*w))
    };
    let after_prefix = PREFIXES
        .iter()
        .filter(|p| words_at(0, p))
        .map(|p| p.len())
        .max()
        .unwrap_or(0);
    let body = &t[after_prefix..];
    let formula = |k: usize| match body.get(k) {
        Some(Token::Formula(f)) => Some(&s.formulas[*f].1),
        _ => None,
    };
    let at = body
        .iter()
        .position(|t| word(Some(t)).and_then(kind_of).is_some())?;
    let kind = word(body.get(at)).and_then(kind_of)?;
    let (head, tail) = (&body[..at], &body[at + 1..]);
    let is_be = |k: usize| matches!(word(head.get(k)), Some("is" | "are"));
    let let_x = (after_prefix > 0 && word(t.get(after_prefix - 1)) == Some("let"))
        .then(|| formula(0).filter(|f| one_symbol(f)))
        .flatten();
    // `Let $X$ be a symmetric nouns [tail]`.
    if let Some(x) = let_x.filter(|_| at == 3 && word(head.get(1)) == Some("be")) {
        let nouns = tail.iter().take_while(|t| is_noun(t)).count();
        let article = matches!(word(head.get(2)), Some("a" | "an"));
        return (article && nouns > 0 && tail_is(&tail[nouns..], s, kind))
            .then(|| (Subject::Formula(x.clone()), kind));
    }
    // `[the] [nouns] $X$ is a symmetric nouns [tail]`.
    if at >= 3 && matches!(word(head.get(at - 1)), Some("a" | "an")) && is_be(at - 2) {
        let nouns = tail.iter().take_while(|t| is_noun(t)).count();
        let Some((Token::Formula(f), before)) = head[..at - 2].split_last() else {
            return None;
        };
        let x = &s.formulas[*f].1;
        let plain = before.iter().enumerate().all(|(k, t)| {
            is_noun(t) || (k == 0 && matches!(word(Some(t)), Some("the" | "a" | "an")))
        });
        return (plain && nouns > 0 && one_symbol(x) && tail_is(&tail[nouns..], s, kind))
            .then(|| (Subject::Formula(x.clone()), kind));
    }
    if !tail_is(tail, s, kind) || at < 2 || !is_be(at - 1) {
        return None;
    }
    let before = &head[..at - 1];
    // `Let $X$ denote the nouns, which is symmetric [tail]`.
    if let Some(x) = let_x {
        let n = before.len();
        let denotes = n >= 6
            && matches!(word(before.get(1)), Some("denote" | "denotes"))
            && word(before.get(2)) == Some("the")
            && before[3..n - 2].iter().all(is_noun)
            && before[n - 2] == Token::Mark(',')
            && word(before.get(n - 1)) == Some("which");
        return denotes.then(|| (Subject::Formula(x.clone()), kind));
    }
    // `[the] [nouns] $X$ is symmetric [tail]`.
    if let Some((Token::Formula(f), nouns)) = before.split_last() {
        let x = &s.formulas[*f].1;
        let plain = nouns.iter().enumerate().all(|(k, t)| {
            is_noun(t) || (k == 0 && matches!(word(Some(t)), Some("the" | "a" | "an")))
        });
        return (plain && one_symbol(x)).then(|| (Subject::Formula(x.clone()), kind));
    }
    // `the nouns is symmetric[, $X_{12} = X_{21}$]`: the formula of the tail, or a noun
    // phrase the paper writes before a formula.
    if word(before.first()) == Some("the") && before.len() >= 2 && before[1..].iter().all(is_noun) {
        if let [Token::Mark(','), Token::Formula(f), ..] = tail {
            return Some((Subject::Formula(s.formulas[*f].1.clone()), kind));
        }
        let words: Vec<&str> = before[1..].iter().filter_map(|t| word(Some(t))).collect();
        let noun = phrase(&words);
        return (!noun.is_empty()).then_some((Subject::Noun(noun), kind));
    }
    None
}

/// Whether what follows the symmetry word is an allowed tail: nothing, `, $X_{12} =
/// X_{21}$` (the same symmetry), or "by the balance of angular momentum" with or
/// without it.
fn tail_is(tail: &[Token], s: &Sentence, kind: Kind) -> bool {
    let balance = ["by", "the", "balance", "of", "angular", "momentum"];
    let rest = if tail.len() >= balance.len()
        && balance
            .iter()
            .zip(tail)
            .all(|(w, t)| word(Some(t)) == Some(*w))
    {
        &tail[balance.len()..]
    } else {
        tail
    };
    match rest {
        [] => true,
        [Token::Mark(','), Token::Formula(f)] => transposed(&s.formulas[*f].1) == Some(kind),
        [Token::Mark(','), Token::Formula(f), Token::Mark(','), described @ ..] => {
            transposed(&s.formulas[*f].1) == Some(kind) && describes(described, s)
        }
        [Token::Mark(','), described @ ..] => describes(described, s),
        _ => false,
    }
}

/// How a tail may go on to describe the tensor, after a comma: a participle or "with"
/// ("describing the contact-force anisotropy", "with traction $t_i = \sigma_{ji} n_j$"),
/// or "and we use this throughout".
const DESCRIPTIONS: &[&[&str]] = &[
    &["describing"],
    &["representing"],
    &["denoting"],
    &["measuring"],
    &["with"],
    &["and", "we", "use", "this", "throughout"],
];

/// Words that would say where, when or for what a described symmetry holds ("for
/// $x_3 > 0$", "away from the wall", "with the exception of").
const PLACES: &[&str] = &[
    "for",
    "at",
    "near",
    "away",
    "outside",
    "inside",
    "within",
    "until",
    "after",
    "before",
    "about",
    "along",
    "across",
    "beyond",
    "under",
    "below",
    "above",
    "exception",
    "apart",
    "besides",
    "save",
];

/// Whether the rest of a tail only describes the tensor: it opens with one of
/// [`DESCRIPTIONS`], has no word of [`PLACES`] nor of a symmetry, no mark but commas,
/// and each of its formulas is one symbol (`$n_i$`) or defines another from a right side
/// that does not read it (`$t_i = \sigma_{ji} n_j$`): never a second statement of the
/// tensor (`$\sigma_{12} = 2\sigma_{21}$`).
fn describes(t: &[Token], s: &Sentence) -> bool {
    // The sentence's first formula, when it is one symbol: the tensor stated symmetric,
    // which a description may not define (`, with $\sigma_{ij} = \tau_{ij} - \tau_{ji}$`).
    let subject = s.formulas.first().and_then(|(_, f)| atom(f));
    let Some(opening) = DESCRIPTIONS.iter().find(|d| {
        d.len() <= t.len() && d.iter().zip(t).all(|(w, tok)| word(Some(tok)) == Some(*w))
    }) else {
        return false;
    };
    t[opening.len()..].iter().all(|tok| match tok {
        Token::Word(w) => !PLACES.contains(&w.as_str()) && !w.contains("symmetr"),
        Token::Mark(c) => *c == ',',
        Token::Formula(f) => {
            let body = &s.formulas[*f].1;
            atom(body).is_some() || defines_another(body, subject.as_deref())
        }
    })
}

/// The base of a formula that is one printed symbol (`n_i`, `\sigma_{ij}`), nothing
/// else.
fn atom(body: &str) -> Option<String> {
    let read = latex::read(body, &ReadOptions::default()).ok()?;
    match &read.parts[..] {
        [p] if p.relations.is_empty() => match &p.members[..] {
            [m] => match &m.kind {
                MathKind::Atom(a) => Some(a.base.clone()),
                _ => None,
            },
            _ => None,
        },
        _ => None,
    }
}

/// Whether a formula is `Y = …` with `Y` one printed symbol ([`atom`]), not `subject`,
/// that its right side does not read.
fn defines_another(body: &str, subject: Option<&str>) -> bool {
    let Ok(read) = latex::read(body, &ReadOptions::default()) else {
        return false;
    };
    let [part] = &read.parts[..] else {
        return false;
    };
    let [left, right] = &part.members[..] else {
        return false;
    };
    let (Some(l), Some(r)) = (
        body.get(left.span.start..left.span.end),
        body.get(right.span.start..right.span.end),
    ) else {
        return false;
    };
    let MathKind::Atom(a) = &left.kind else {
        return false;
    };
    part.relations == [latex::Rel::Eq]
        && atom(l).is_some()
        && Some(a.base.as_str()) != subject
        && !r.contains(a.base.as_str())
}

/// Whether a formula is one symbol, with two distinct index letters or none (`\sigma`,
/// `\sigma_{ij}`; not a component, `\sigma_{12}`), no accent or primes.
fn one_symbol(body: &str) -> bool {
    let Ok(read) = latex::read(body, &ReadOptions::default()) else {
        return false;
    };
    match &read.parts[..] {
        [p] if p.relations.is_empty() => match &p.members[..] {
            [m] => matches!(&m.kind, MathKind::Atom(a) if a.accent.is_none() && a.primes == 0
                && a.sub.as_ref().is_none_or(|s| two_letters(&s.text).is_some_and(|l| l.iter().all(char::is_ascii_lowercase)))),
            _ => false,
        },
        _ => false,
    }
}

fn two_letters(s: &str) -> Option<[char; 2]> {
    let c: Vec<char> = s.chars().collect();
    match c[..] {
        [i, j]
            if i != j
                && (i.is_ascii_lowercase() || i.is_ascii_digit())
                && (j.is_ascii_lowercase() || j.is_ascii_digit()) =>
        {
            Some([i, j])
        }
        _ => None,
    }
}

/// The symmetry a formula states: `X_{ij} = X_{ji}` (or `X_{12} = X_{21}`), `X_{ij} =
/// -X_{ji}`; one symbol with its two indices swapped.
pub fn transposed(body: &str) -> Option<Kind> {
    let read = latex::read(body, &ReadOptions::default()).ok()?;
    let [part] = &read.parts[..] else {
        return None;
    };
    let [a, b] = &part.members[..] else {
        return None;
    };
    if part.relations != [latex::Rel::Eq] {
        return None;
    }
    let (b, kind) = match &b.kind {
        MathKind::Sum(terms) => match &terms[..] {
            [(true, inner)] => (inner, Kind::Antisymmetric),
            _ => return None,
        },
        _ => (b, Kind::Symmetric),
    };
    let (MathKind::Atom(a), MathKind::Atom(b)) = (&a.kind, &b.kind) else {
        return None;
    };
    let [i, j] = two_letters(&a.sub.as_ref()?.text)?;
    let other = two_letters(&b.sub.as_ref()?.text)?;
    let label = |x: &latex::Atom| x.sup.as_ref().map(|s| s.text.clone());
    (a.base == b.base
        && a.accent == b.accent
        && label(a) == label(b)
        && a.primes == b.primes
        && other == [j, i])
    .then_some(kind)
}

/// The sentence as printed, its formulas back in place of their ` x `, on one line.
fn restored(s: &Sentence) -> String {
    let mut out = String::new();
    let mut from = 0;
    for (at, body) in &s.formulas {
        let Some(before) = s.words.get(from..*at) else {
            break;
        };
        out.push_str(before);
        out.push_str(&format!(" ${body}$ "));
        from = at + 3;
    }
    out.push_str(s.words.get(from..).unwrap_or(""));
    out.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// Where each section of the text starts (its heading's line: a LaTeX sectioning
/// command anywhere in a line, a Markdown `#` heading, quoted or not, a line underlined
/// with `===` or `---`, an HTML `<h1>` to `<h6>`), and the lines of each environment
/// other than the document and the displays (a lemma, a quote, a figure): a symmetry
/// the text states holds in its section, and one stated inside an environment is not
/// read at all.
pub fn sections(lines: &[&str], markdown: bool) -> (Vec<usize>, Vec<std::ops::Range<usize>>) {
    const COMMANDS: [&str; 9] = [
        "\\part",
        "\\chapter",
        "\\section",
        "\\subsection",
        "\\subsubsection",
        "\\paragraph",
        "\\appendix",
        "\\addsec",
        "\\frametitle",
    ];
    let mut headings = Vec::new();
    for (k, l) in lines.iter().enumerate() {
        let t = l.trim_start().trim_start_matches('>').trim_start();
        let underline = |c: char| t.len() >= 3 && t.trim_end().chars().all(|x| x == c);
        // The command itself, not a longer one (`\\part`, not `\\partial`).
        let command = |h: &str| {
            l.match_indices(h).any(|(at, _)| {
                !l[at + h.len()..]
                    .chars()
                    .next()
                    .is_some_and(|c| c.is_ascii_alphabetic())
            })
        };
        let heading = COMMANDS.iter().any(|h| command(h))
            || (markdown && (t.starts_with('#') || l.to_ascii_lowercase().contains("<h")));
        if heading {
            headings.push(k + 1);
        } else if markdown && k > 0 && (underline('=') || underline('-')) {
            headings.push(k);
        }
    }
    // Environments by their lines, nested ones included.
    let mut enclosed = Vec::new();
    let mut open: Vec<(String, usize)> = Vec::new();
    let displays = [
        "document", "equation", "align", "gather", "multline", "eqnarray", "flalign", "alignat",
        "split", "aligned",
    ];
    for (k, l) in lines.iter().enumerate() {
        let mut marks: Vec<usize> = l
            .match_indices("\\begin{")
            .chain(l.match_indices("\\end{"))
            .map(|(at, _)| at)
            .collect();
        marks.sort_unstable();
        for at in marks {
            let rest = &l[at..];
            let begin = rest.starts_with("\\begin{");
            let name = rest[rest.find('{').map_or(0, |b| b + 1)..]
                .split('}')
                .next()
                .unwrap_or("")
                .trim_end_matches('*')
                .to_owned();
            if displays.contains(&name.as_str()) {
                continue;
            }
            if begin {
                open.push((name, k + 1));
            } else if let Some(back) = open.iter().rev().take(64).position(|(n, _)| *n == name) {
                // Environments nest: the one it closes is near the top (a stray `\end`
                // deeper down closes nothing).
                let (_, from) = open.remove(open.len() - 1 - back);
                enclosed.push(from..k + 2);
            }
        }
    }
    // One never closed runs to the end. The ranges, sorted and merged, do not overlap.
    enclosed.extend(open.into_iter().map(|(_, from)| from..usize::MAX));
    enclosed.sort_unstable_by_key(|r| (r.start, r.end));
    let mut merged: Vec<std::ops::Range<usize>> = Vec::with_capacity(enclosed.len());
    for r in enclosed {
        match merged.last_mut() {
            Some(last) if r.start <= last.end => last.end = last.end.max(r.end),
            _ => merged.push(r),
        }
    }
    headings.sort_unstable();
    headings.dedup();
    (headings, merged)
}

/// A symmetry the text states of a symbol the file declares .
pub struct SymmetryOf {
    pub name: String,
    /// The symbol as printed.
    pub printed: String,
    pub kind: Kind,
    pub line: usize,
    pub quote: String,
    /// The lines of its section: the claims it holds for.
    pub section: std::ops::Range<usize>,
}

/// The symmetries the text states of symbols of rank 2 the file declares (one it
/// defines is symmetric or not by its definition): named by the formula in the
/// sentence, or by the noun phrase the paper writes right before one symbol and no
/// other. A symbol said to be both symmetric and antisymmetric in one section is
/// neither.
pub fn symmetric_tensors(
    said: &Statements,
    symbols: &BTreeMap<Key, Symbol>,
    defined: &BTreeMap<Key, String>,
    (normal, tensors): (Option<&str>, &Stems),
) -> Vec<SymmetryOf> {
    let options = ReadOptions::default();
    let unranked = |k: &Key| symbols::fields(k).map(|f| f[..5].join("|"));
    // The declared symbols of rank 2, by their identity without the rank.
    let mut by_identity: BTreeMap<String, Vec<(&Key, &Symbol)>> = BTreeMap::new();
    for (k, s) in symbols.iter().filter(|(_, s)| s.rank == 2 && !s.component) {
        if let Some(u) = unranked(k) {
            by_identity.entry(u).or_default().push((k, s));
        }
    }
    // The printed symbol a formula begins with, without its rank; each formula read
    // once.
    let mut first: BTreeMap<String, Option<String>> = BTreeMap::new();
    let mut first_symbol = |body: &str| -> Option<String> {
        if let Some(known) = first.get(body) {
            return known.clone();
        }
        let found = (|| {
            let read = latex::read(body, &options).ok()?;
            let member = read.parts.first()?.members.first()?;
            let (key, _) = symbols::occurrences(&[member], normal, tensors)
                .into_iter()
                .next()?;
            unranked(&key)
        })();
        first.insert(body.to_owned(), found.clone());
        found
    };
    // The one declared symbol of rank 2 with that identity, if the file does not define
    // it.
    let named = |key: &Option<String>| -> Option<&Symbol> {
        match by_identity.get(key.as_ref()?)?.as_slice() {
            [(k, s)] if !defined.contains_key(*k) => Some(*s),
            _ => None,
        }
    };
    // Every formula the paper writes right after a noun phrase, declared or not: the
    // phrase names a symbol when they are all one symbol.
    let mut after: BTreeMap<&[String], BTreeSet<Option<String>>> = BTreeMap::new();
    for (noun, body) in &said.nouns {
        let key = first_symbol(body);
        after.entry(noun.as_slice()).or_default().insert(key);
    }
    // One statement per symbol, section and kind; a symbol said to be both symmetric
    // and antisymmetric in a section is neither there (sections do not overlap: each
    // runs from one heading to the next).
    let mut found: BTreeMap<(String, usize), BTreeMap<Kind, SymmetryOf>> = BTreeMap::new();
    for st in &said.symmetries {
        let key = match &st.subject {
            Subject::Formula(body) => first_symbol(body),
            Subject::Noun(noun) => match after.get(noun.as_slice()) {
                Some(keys) if keys.len() == 1 => keys.first().cloned().flatten(),
                _ => None,
            },
        };
        let Some(s) = named(&key) else {
            continue;
        };
        found
            .entry((s.name.clone(), st.section.start))
            .or_default()
            .entry(st.kind)
            .or_insert_with(|| SymmetryOf {
                name: s.name.clone(),
                // As printed, with the index letters `ij` (`\sigma_{ij}`, not the
                // `\sigma_{kk}` of its first occurrence).
                printed: match &s.key.1[..] {
                    [a, b] => s.key.0.replacen(&format!("_{{{a}{b}}}"), "_{ij}", 1),
                    _ => s.key.0.clone(),
                },
                kind: st.kind,
                line: st.line,
                quote: st.quote.clone(),
                section: st.section.clone(),
            });
    }
    found
        .into_values()
        .filter(|kinds| kinds.len() == 1)
        .flat_map(BTreeMap::into_values)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn said(text: &str) -> Vec<(Subject, Kind)> {
        read(&super::super::displays::sentences(text, false), &[], &[])
            .symmetries
            .into_iter()
            .map(|s| (s.subject, s.kind))
            .collect()
    }

    fn formula(f: &str) -> (Subject, Kind) {
        (Subject::Formula(f.to_owned()), Kind::Symmetric)
    }

    #[test]
    fn a_symmetry_is_read_in_a_few_whole_shapes() {
        assert_eq!(
            said("The stress $\\sigma_{ij}$ is symmetric."),
            [formula("\\sigma_{ij}")]
        );
        assert_eq!(
            said("Let $\\sigma_{ij}$ denote the Cauchy stress tensor, which is symmetric by the balance of angular momentum, $\\sigma_{ij}=\\sigma_{ji}$."),
            [formula("\\sigma_{ij}")]
        );
        assert_eq!(said("Let $S$ be a symmetric tensor."), [formula("S")]);
        assert_eq!(
            said("The strain tensor is symmetric."),
            [(Subject::Noun(vec!["strain".into()]), Kind::Symmetric)]
        );
        // A formula alone states no symmetry: `$\sigma_{12} = \sigma_{21}$` is one pair.
        assert_eq!(said("Here $e_{ij} = e_{ji}$."), []);
        for skew in ["skew-symmetric", "skew", "a skew tensor"] {
            assert_eq!(
                said(&format!("The spin $W_{{ij}}$ is {skew}.")),
                [(Subject::Formula("W_{ij}".into()), Kind::Antisymmetric)]
            );
        }
        // A later sentence that gives a symmetric tensor a skew part withdraws it.
        assert_eq!(
            said("Let $\\sigma_{ij}$ be a symmetric stress. Once the grains rotate, $\\sigma_{ij}$ acquires a skew part."),
            []
        );
        assert_eq!(
            said("The spin $W$ is skew symmetric. The spin $V$ is skew\\-symmetric."),
            [
                (Subject::Formula("W".into()), Kind::Antisymmetric),
                (Subject::Formula("V".into()), Kind::Antisymmetric),
            ]
        );
    }

    #[test]
    fn anything_else_states_nothing() {
        for text in [
            "If $\\sigma$ is symmetric, the power simplifies.",
            "The square of $A$ is symmetric.",
            "The product $\\sigma_{ik}\\sigma_{jk}$ is symmetric.",
            "The stress field $\\sigma_{ij}$ is symmetric about the $x_1$ axis.",
            "In the classical continuum $\\sigma$ is symmetric.",
            "The stress $\\sigma$ is symmetric in the absence of couple stresses.",
            "The stress $\\sigma$ is symmetric (see Fig. 2) only in Boltzmann media.",
            "Is the stress $\\sigma_{ij}$ symmetric?",
            "The strain $\\epsilon_{ij}$, differently from the stress $\\sigma_{ij}$, is symmetric.",
            "The component $\\sigma_{12}$ is symmetric.",
            "$\\sigma_{ij} = \\sigma_{ji}$ for $i, j \\le 2$.",
            "The stress $\\sigma_{ij}$ is symmetric. In a Cosserat continuum this is no longer true.",
        ] {
            assert_eq!(said(text), [], "{text}");
        }
        // One denial of a symmetry anywhere withdraws every reading.
        for denial in [
            "The couple stress $\\mu$ is not symmetric.",
            "Neither $\\sigma$ nor $\\mu$ is symmetric.",
            "The couple stress isn't symmetric.",
            "It is an asymmetric stress.",
            "The tensor $A$ is non-{}symmetric.",
        ] {
            let text = format!("The stress $\\sigma$ is symmetric.\n\n{denial}");
            assert_eq!(said(&text), [], "{text}");
        }
    }
}
