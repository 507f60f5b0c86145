//! A symmetry the text states of a tensor: "the stress $\sigma_{ij}$ is symmetric",
//! "let $S_{ij}$ be a symmetric tensor", "$\varepsilon_{ij} = \varepsilon_{ji}$", or "the
//! strain tensor is symmetric" where a formula elsewhere names the strain
//! ("small strain $\varepsilon_{ij}$").
//!
//! The draft writes such a symmetry as an assumption of the file (`symmetric(sigma)`),
//! so that a claim true only for a symmetric stress holds, and one false for it too
//! fails, where before either was undecided ("σ being symmetric would remove the
//! difference"). Read wrongly, it would make a false claim hold, so the reading is
//! narrow:
//!
//! - the sentence neither qualifies nor contrasts ("if", "unless", "only", "but",
//!   "as in", "in the classical case", "its symmetric part", …): such a sentence states
//!   nothing;
//! - a sentence anywhere in the text that denies a symmetry ("is not symmetric",
//!   "neither … nor … is symmetric", "need not be", "non-symmetric", "asymmetric")
//!   withdraws every symmetry reading of the paper: the text then tells symmetric and
//!   non-symmetric tensors apart in ways words alone cannot settle;
//! - the symbol is the formula next to the word (`$X$ is symmetric`, `a symmetric
//!   stress $X$`), with only plain words between, and is not the object of a
//!   preposition (`the square of $A$ is symmetric` says nothing of A); or, for a
//!   sentence without a formula ("The stress is symmetric"), the one symbol of rank 2
//!   that the paper writes right after that noun, wherever it does.
//!
//! Which symbol a formula names, and whether the draft declares it as a tensor of rank 2
//! it does not define, is for the draft to settle (`mod.rs`).

use super::displays::Sentence;
use crate::lang::latex::{self, MathKind, ReadOptions};

/// What a sentence says is symmetric: the formula next to the word, or a noun the paper
/// writes elsewhere before a formula.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Subject {
    Formula(String),
    Noun(String),
}

/// A symmetry the text states, with its line and the words that state it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Symmetry {
    pub line: usize,
    pub subject: Subject,
    pub quote: String,
}

/// What the text's sentences say: the symmetries they state, or none at all when one
/// denies a symmetry; and each noun the paper writes right before a formula.
#[derive(Clone, Debug, Default)]
pub struct Said {
    pub symmetries: Vec<Symmetry>,
    /// (noun, formula) for each formula right after a word (`strain
    /// $\varepsilon_{ij}$`).
    pub nouns: Vec<(String, String)>,
}

/// Words that deny: a sentence with one of them and "symmetric" withdraws every reading.
const DENIALS: &[&str] = &[
    "not", "no", "nor", "neither", "never", "cannot", "non", "need", "needs", "none", "nothing",
    "lacks", "lack", "fails", "lose", "loses", "lost",
];

/// Words that qualify or contrast: a sentence with one of them states nothing.
const QUALIFIERS: &[&str] = &[
    "if",
    "unless",
    "when",
    "whenever",
    "were",
    "would",
    "could",
    "should",
    "might",
    "may",
    "suppose",
    "supposing",
    "assume",
    "assuming",
    "assumed",
    "provided",
    "only",
    "except",
    "but",
    "however",
    "although",
    "though",
    "whereas",
    "while",
    "unlike",
    "like",
    "as",
    "than",
    "contrary",
    "classical",
    "case",
    "cases",
    "limit",
    "general",
    "generally",
    "special",
    "part",
    "parts",
    "whether",
    "either",
    "or",
    "else",
    "otherwise",
    "instead",
    "rather",
    "until",
    "once",
    "become",
    "becomes",
    "made",
    "approximately",
    "nearly",
    "almost",
];

/// Words that make a formula the object of another word: `the square of $A$`, `$A$
/// and $B$`, `the product with $A$`.
const PREPOSITIONS: &[&str] = &[
    "of", "by", "to", "from", "on", "onto", "into", "times", "at", "in", "over", "under", "about",
    "through", "between", "and", "with", "for", "plus", "minus", "per",
];

/// Words that, between a formula and "symmetric", speak of something else than the
/// formula: `$A$'s square is symmetric`, `$\sigma$ times $n$`.
const OTHER_THING: &[&str] = &[
    "product",
    "derivative",
    "derivatives",
    "gradient",
    "rate",
    "inverse",
    "transpose",
    "sum",
    "difference",
    "square",
    "power",
    "trace",
    "its",
    "their",
    "whose",
    "s",
];

/// Nouns a subject phrase may end on that name no quantity (`the strain tensor`).
const KINDS: &[&str] = &["tensor", "tensors", "field", "fields", "matrix"];

#[derive(Clone, Debug, PartialEq, Eq)]
enum Token {
    Word(String),
    /// The k-th formula of the sentence.
    Formula(usize),
    /// `,`, `;`, `:`.
    Mark(char),
}

/// The sentence's words, lowercase, its formulas and clause marks, in order.
fn tokens(s: &Sentence) -> Vec<Token> {
    let mut out = Vec::new();
    let mut word = String::new();
    let flush = |word: &mut String, out: &mut Vec<Token>, at: usize| {
        if word.is_empty() {
            return;
        }
        let start = at - word.len();
        // A formula stands as ` x ` at its offset: its `x` is the formula.
        match s.formulas.iter().position(|(f, _)| *f + 1 == start) {
            Some(k) if word == "x" => out.push(Token::Formula(k)),
            _ => out.push(Token::Word(word.to_ascii_lowercase())),
        }
        word.clear();
    };
    for (at, c) in s.words.char_indices() {
        if c.is_alphanumeric() || (c == '-' && !word.is_empty()) {
            word.push(c);
            continue;
        }
        flush(&mut word, &mut out, at);
        if matches!(c, ',' | ';' | ':') {
            out.push(Token::Mark(c));
        }
    }
    flush(&mut word, &mut out, s.words.len());
    out
}

fn is(t: Option<&Token>, set: &[&str]) -> bool {
    matches!(t, Some(Token::Word(w)) if set.contains(&w.as_str()))
}

/// The symmetries `sentences` state, and the nouns before formulas.
pub fn read(sentences: &[Sentence]) -> Said {
    let mut said = Said::default();
    let mut denied = false;
    for s in sentences {
        let tokens = tokens(s);
        for (k, t) in tokens.iter().enumerate() {
            if let (Token::Formula(f), Some(Token::Word(w))) =
                (t, k.checked_sub(1).map(|j| &tokens[j]))
            {
                said.nouns.push((w.clone(), s.formulas[*f].1.clone()));
            }
        }
        let words = || {
            tokens.iter().filter_map(|t| match t {
                Token::Word(w) => Some(w.as_str()),
                _ => None,
            })
        };
        let negative = words().any(|w| {
            w.contains("symmetr")
                && !matches!(
                    w,
                    "symmetric"
                        | "symmetry"
                        | "symmetries"
                        | "symmetrical"
                        | "symmetrically"
                        | "skew-symmetric"
                        | "antisymmetric"
                        | "anti-symmetric"
                        | "symmetrised"
                        | "symmetrized"
                )
        });
        let positive = words().any(|w| w == "symmetric");
        let transposes: Vec<&String> = s
            .formulas
            .iter()
            .map(|(_, body)| body)
            .filter(|body| transposed(body))
            .collect();
        let stated = positive || !transposes.is_empty();
        if negative || (stated && words().any(|w| DENIALS.contains(&w))) {
            denied = true;
            continue;
        }
        if words().any(|w| QUALIFIERS.contains(&w) || DENIALS.contains(&w)) {
            continue;
        }
        let quote = restored(s);
        let mut push = |subject| {
            said.symmetries.push(Symmetry {
                line: s.line,
                subject,
                quote: quote.clone(),
            })
        };
        for body in transposes {
            push(Subject::Formula(body.clone()));
        }
        for p in (0..tokens.len()).filter(|&p| tokens[p] == Token::Word("symmetric".into())) {
            if let Some(subject) = subject(&tokens, p, s) {
                push(subject);
            }
        }
    }
    if denied {
        said.symmetries.clear();
    }
    said
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

/// Whether `body` states a symmetry: `X_{ij} = X_{ji}`, one symbol with its two index
/// letters swapped.
fn transposed(body: &str) -> bool {
    let Ok(read) = latex::read(body, &ReadOptions::default()) else {
        return false;
    };
    let [part] = &read.parts[..] else {
        return false;
    };
    let (MathKind::Atom(a), MathKind::Atom(b)) = (match &part.members[..] {
        [a, b] if part.relations == [latex::Rel::Eq] => (&a.kind, &b.kind),
        _ => return false,
    }) else {
        return false;
    };
    let letters = |x: &latex::Atom| -> Option<[char; 2]> {
        let s: Vec<char> = x.sub.as_ref()?.text.chars().collect();
        match s[..] {
            [i, j] if i != j && i.is_ascii_lowercase() && j.is_ascii_lowercase() => Some([i, j]),
            _ => None,
        }
    };
    let (Some([i, j]), Some(other)) = (letters(a), letters(b)) else {
        return false;
    };
    let label = |x: &latex::Atom| x.sup.as_ref().map(|s| s.text.clone());
    a.base == b.base
        && a.accent == b.accent
        && label(a) == label(b)
        && a.primes == b.primes
        && other == [j, i]
}

/// What the word "symmetric" at `p` is said of.
fn subject(tokens: &[Token], p: usize, s: &Sentence) -> Option<Subject> {
    let plain = |t: &Token| match t {
        Token::Word(w) => !OTHER_THING.contains(&w.as_str()) && !PREPOSITIONS.contains(&w.as_str()),
        Token::Mark(c) => *c == ',',
        Token::Formula(_) => false,
    };
    // `$X$ (…) is symmetric`: the nearest formula before, plain words between.
    let back = (0..p)
        .rev()
        .take_while(|&j| plain(&tokens[j]) || matches!(tokens[j], Token::Formula(_)));
    if let Some(j) = back
        .clone()
        .find(|&j| matches!(tokens[j], Token::Formula(_)))
    {
        let Token::Formula(f) = tokens[j] else {
            return None;
        };
        let between = p - j - 1;
        if between <= 8 && !is(j.checked_sub(1).map(|i| &tokens[i]), PREPOSITIONS) {
            return Some(Subject::Formula(s.formulas[f].1.clone()));
        }
        return None;
    }
    // `a symmetric stress $X$`: a formula within four plain words after.
    if is(
        p.checked_sub(1).map(|i| &tokens[i]),
        &["a", "an", "the", "is", "be", "being"],
    ) {
        for t in tokens.iter().skip(p + 1).take(5) {
            match t {
                Token::Formula(f) => return Some(Subject::Formula(s.formulas[*f].1.clone())),
                t if plain(t) => {}
                _ => break,
            }
        }
    }
    // `the (Cauchy) stress (tensor) is symmetric`: a noun the paper writes before a
    // formula elsewhere.
    if !is(p.checked_sub(1).map(|i| &tokens[i]), &["is", "are"]) {
        return None;
    }
    let start = p.checked_sub(5).unwrap_or(0);
    let phrase = &tokens[start..p - 1];
    let the = phrase.iter().rposition(|t| is(Some(t), &["the"]))?;
    let nouns: Vec<&str> = phrase[the + 1..]
        .iter()
        .map(|t| match t {
            Token::Word(w)
                if !PREPOSITIONS.contains(&w.as_str()) && !OTHER_THING.contains(&w.as_str()) =>
            {
                Some(w.as_str())
            }
            _ => None,
        })
        .collect::<Option<_>>()?;
    let noun = nouns.iter().rev().find(|w| !KINDS.contains(w))?;
    Some(Subject::Noun((*noun).to_owned()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn said(text: &str) -> Vec<Subject> {
        read(&super::super::displays::sentences(text, false))
            .symmetries
            .into_iter()
            .map(|s| s.subject)
            .collect()
    }

    fn formula(f: &str) -> Subject {
        Subject::Formula(f.to_owned())
    }

    #[test]
    fn a_symmetry_is_read_next_to_its_word() {
        assert_eq!(
            said("The stress $\\sigma_{ij}$ is symmetric."),
            [formula("\\sigma_{ij}")]
        );
        assert_eq!(
            said("Let $\\sigma_{ij}$ denote the Cauchy stress tensor, which is symmetric by the balance of angular momentum."),
            [formula("\\sigma_{ij}")]
        );
        assert_eq!(said("Let $S$ be a symmetric tensor."), [formula("S")]);
        assert_eq!(
            said("Let $\\sigma$ be a symmetric stress, with traction $t$ on it."),
            [formula("\\sigma")]
        );
        assert_eq!(
            said("The strain tensor is symmetric."),
            [Subject::Noun("strain".into())]
        );
        assert_eq!(
            said("By the balance of angular momentum the Cauchy stress is symmetric."),
            [Subject::Noun("stress".into())]
        );
        assert_eq!(
            said("Here $e_{ij} = e_{ji}$."),
            [formula("e_{ij} = e_{ji}")]
        );
    }

    #[test]
    fn a_qualified_or_denied_symmetry_is_not_read() {
        for text in [
            "If $\\sigma$ is symmetric, the power simplifies.",
            "The square of $A$ is symmetric.",
            "The product of $A$ and $B$ is symmetric.",
            "In the classical continuum $\\sigma$ is symmetric.",
            "Its symmetric part is the strain $\\varepsilon$.",
            "The stress $\\sigma$ is symmetric only for a simple material.",
            "As in elasticity, $\\sigma$ is symmetric.",
        ] {
            assert_eq!(said(text), [], "{text}");
        }
        // One denial anywhere withdraws every reading.
        for denial in [
            "The couple stress $\\mu$ is not symmetric.",
            "Neither $\\sigma$ nor $\\mu$ is symmetric.",
            "The stress need not be symmetric.",
            "It is an asymmetric stress.",
            "The tensor $A$ is non-symmetric.",
        ] {
            let text = format!("The stress $\\sigma$ is symmetric. {denial}");
            assert_eq!(said(&text), [], "{text}");
        }
    }
}
