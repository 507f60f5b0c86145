//! The transcription check: does a claim's `sides` (or `chains`, or the function and
//! closed forms of a gradient claim) say what its printed LaTeX says?
//!
//! The printed statement, read and translated through the notation table
//! ([`crate::derivation::notation`]), is compared with the sides as written by the same
//! engine that decides claims: member by member, each pair an identity in the claim's
//! context (definitions and assumptions), exactly where the expressions are
//! polynomial or rational, on seeded samples otherwise. Every chain of the sides must
//! be a printed chain; a printed chain that no chain of the sides transcribes must hold
//! in the claim's context as an identity (a definition printed beside the statement,
//! `with T^2 = ⟨…⟩`), or the claim `differs`.

// The comparison's steps return the claim's final status as their error (built once per
// claim, on the way out), so its size costs nothing.
#![allow(clippy::result_large_err)]

use super::dispatch::decide;
use crate::algebra::sign::Sign;
use crate::decide::{Outcome, Strength};
use crate::derivation::edit::Incomparable;
use crate::derivation::notation::{ReadMember, ReadPart};
use crate::derivation::{
    Check, Relation, Sampling, ScalarClaim, Side, Strategy, Transcript, Verdict,
};
use crate::lang::latex::Rel;
use crate::lang::rename::same_up_to_summed_letters;
use crate::lang::{Decls, Span};

/// The transcription status of one statement.
#[derive(Clone, Debug, PartialEq)]
pub enum Status {
    /// The sides say what the printed statement says: every member pair decided equal.
    MachineRead {
        /// `proof` when every pair was decided exactly, `sampled` otherwise.
        strength: Agreement,
        /// Printed chains that the sides do not transcribe but that hold in the claim's
        /// context (definitions printed beside the statement).
        context: Vec<String>,
        /// Printed symbols defined by the statement (`defines`).
        defines: Vec<String>,
        /// Set when `differs_from_printed` is declared although the sides agree: a
        /// stale declaration.
        stale: Option<String>,
        /// The claim has no `sides`: it is decided on the reading itself.
        from_reading: bool,
    },
    /// The sides and the printed statement part somewhere.
    Differs {
        /// Where in the LaTeX (byte span of the printed statement).
        span: Span,
        /// The printed piece there.
        printed: String,
        /// Its reading in the language.
        reading: String,
        /// The side as written it was compared with (empty when there is none).
        side: String,
        why: Why,
        /// With several chains on either side: the sides' chain that no printed chain
        /// transcribes (the rest describes the nearest printed one).
        unmatched: Option<String>,
        /// The claim's declared reason (`differs_from_printed`), if any.
        declared: Option<String>,
    },
    /// Not machine-read.
    Hand { reason: Hand },
}

/// Why a printed statement is not machine-read.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Hand {
    /// A sentence of the paper's prose.
    Prose,
    /// The reader or the notation table refused it, at this span.
    Unread { span: Span, message: String },
    /// The claim kind is not an equation chain (convexity, a limit, monotonicity, a
    /// witness), so there are no sides to compare.
    Kind(&'static str),
    /// Whether a printed member equals its side could not be decided (a resource
    /// limit, an inconclusive sample), at this span of the LaTeX.
    Undecided { span: Span, side: String },
    /// The reading is not an expression the language accepts (at this span).
    Untranslatable { span: Span, message: String },
    /// The checker panicked while comparing: its defect, with the message and where.
    InternalError { message: String, at: String },
}

/// Why a printed piece and a side differ.
#[derive(Clone, Debug, PartialEq)]
pub enum Why {
    /// The two are not equal: a counterexample (exact or sampled).
    Value(Strength),
    /// Neither equal nor different could be decided.
    Undecided,
    FreeIndices {
        printed: Vec<char>,
        side: Vec<char>,
    },
    /// The printed member is ill-formed in its indices, the side is not.
    IllFormed(String),
    /// The reading is not an expression the language accepts (a syntax or name error):
    /// a limit of the translation, not a difference.
    Untranslatable(String),
    /// Shapes (a matrix against a scalar) differ.
    Shape(String),
    /// No printed chain has this many members.
    Members {
        side: usize,
    },
    /// The relations differ (`=` printed, `≤` checked).
    Relation {
        printed: String,
        side: String,
    },
    /// This printed chain is not transcribed by the sides, and does not hold in the
    /// claim's context.
    Untranscribed(Option<Strength>),
    /// A closed form of a gradient claim whose derivative the printed statement does
    /// not name.
    NoDerivative(String),
    /// A printed condition (an inequality after "for", "if", …) that is none of the
    /// claim's hypotheses (`given`, `domain`).
    Condition,
}

/// A claim's transcription.
#[derive(Clone, Debug, PartialEq)]
pub struct Transcription {
    pub status: Status,
}

impl Transcription {
    /// "machine-read", "differs" or "hand".
    pub fn label(&self) -> &'static str {
        match &self.status {
            Status::MachineRead { .. } => "machine-read",
            Status::Differs { .. } => "differs",
            Status::Hand { .. } => "hand",
        }
    }

    /// A `differs` is expected only where the claim declares why; a declaration is
    /// expected only where the sides differ.
    pub fn as_expected(&self) -> bool {
        match &self.status {
            Status::MachineRead { stale, .. } => stale.is_none(),
            Status::Differs { declared, .. } => declared.is_some(),
            Status::Hand { .. } => true,
        }
    }
}

/// Compares a statement's printed LaTeX with its check.
/// [`transcribe`], with a panic caught as the transcription's internal error (the
/// claim's verdict stands; the run ends with exit status 3).
pub fn transcribe_isolated(
    id: &str,
    decls: &Decls,
    check: &Check,
    transcript: &Transcript,
) -> Transcription {
    let compare = || {
        super::isolate::transcription_test_hook(id);
        transcribe(decls, check, transcript)
    };
    use super::isolate::Unwound;
    super::isolate::caught(compare).unwrap_or_else(|unwound| {
        let (message, at) = match unwound {
            // Reading a printed statement is not a decision: a limit there is the
            // checker's to raise, reported like a defect.
            Unwound::Limit(e) => (e.to_string(), "a polynomial operation".to_owned()),
            Unwound::Panic(message, at) => (message, at),
        };
        Transcription {
            status: Status::Hand {
                reason: Hand::InternalError { message, at },
            },
        }
    })
}

impl Transcription {
    /// Whether the checker failed on this transcription (a caught panic).
    pub fn is_internal_error(&self) -> bool {
        matches!(
            self.status,
            Status::Hand {
                reason: Hand::InternalError { .. }
            }
        )
    }
}

pub fn transcribe(decls: &Decls, check: &Check, transcript: &Transcript) -> Transcription {
    let status = match &transcript.reading {
        _ if transcript.prose => Status::Hand {
            reason: Hand::Prose,
        },
        Err(u) => Status::Hand {
            reason: Hand::Unread {
                span: u.span,
                message: u.message.clone(),
            },
        },
        Ok(reading) => Comparer {
            decls,
            check,
            chains: transcript.written.len(),
            memo: Default::default(),
        }
        .compare(&reading.parts, transcript),
    };
    // A comparison that could not be decided, or a reading the language refuses, is no
    // evidence of a difference.
    let status = match status {
        Status::Differs {
            span,
            side,
            why: Why::Undecided,
            ..
        } => Status::Hand {
            reason: Hand::Undecided { span, side },
        },
        Status::Differs {
            span,
            why: Why::Untranslatable(message),
            ..
        } => Status::Hand {
            reason: Hand::Untranslatable { span, message },
        },
        s => s,
    };
    let mut status = status;
    if let Some(d) = &transcript.declared {
        match &mut status {
            Status::Differs { declared, .. } => *declared = Some(d.clone()),
            Status::MachineRead { stale, .. } => *stale = Some(d.clone()),
            Status::Hand { .. } => {}
        }
    }
    Transcription { status }
}

/// The outcome of comparing one printed member with one side.
#[derive(Clone)]
enum Same {
    Yes(Agreement),
    No(Why),
}

/// How a printed member was found to say what its side says: the same expression as
/// written (reflexivity: textual, not a proof of anything), equal by the exact route
/// (a kernel proof), or on seeded samples.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Agreement {
    Textual,
    Exact,
    Sampled,
}

impl Agreement {
    /// The weaker of two agreements.
    fn weaker(self, other: Agreement) -> Agreement {
        self.max(other)
    }
}

/// At most this many comparisons are decided for one statement; beyond, the
/// transcription is read by hand (a statement with thousands of chains).
const MAX_COMPARISONS: usize = 400;

struct Comparer<'a> {
    decls: &'a Decls,
    check: &'a Check,
    /// How many chains the sides have.
    chains: usize,
    /// Comparisons already decided, by (printed, side).
    memo: std::cell::RefCell<std::collections::HashMap<(String, String), Same>>,
}

/// One printed chain: a route of a part.
struct Printed<'p> {
    part: &'p ReadPart,
    members: &'p [ReadMember],
}

impl Comparer<'_> {
    fn compare(&self, parts: &[ReadPart], transcript: &Transcript) -> Status {
        let printed: Vec<Printed> = parts
            .iter()
            .flat_map(|part| {
                part.routes.iter().map(move |r| Printed {
                    part,
                    members: r.as_slice(),
                })
            })
            .collect();
        let defines: Vec<String> = parts.iter().filter_map(|p| p.defines.clone()).collect();
        let mut used = vec![false; printed.len()];
        let mut strength = Agreement::Textual;
        let kind = match &self.check.strategy {
            Strategy::Gradient {
                function,
                closed_forms,
                ..
            } => {
                for (symbol, closed) in closed_forms {
                    match self.gradient(&printed, &mut used, &function.text, symbol, &closed.text) {
                        Ok(s) => strength = strength.weaker(s),
                        Err(status) => return status,
                    }
                }
                None
            }
            Strategy::Convex { .. } => Some("convexity"),
            Strategy::NotCircle { .. } => Some("a witness that a locus is not a circle"),
            Strategy::Scalar { claim, .. } => match &**claim {
                ScalarClaim::Sign(_) => None,
                ScalarClaim::SignExactly(..) => Some("a sign on exactly a set"),
                ScalarClaim::Monotone { .. } => Some("monotonicity"),
                ScalarClaim::Limit { .. } => Some("a limit"),
                ScalarClaim::Roots { .. } => Some("the roots of a function"),
                ScalarClaim::Stationary(_) => Some("a stationary point"),
            },
            _ => None,
        };
        if let Some(kind) = kind {
            return Status::Hand {
                reason: Hand::Kind(kind),
            };
        }
        if !matches!(self.check.strategy, Strategy::Gradient { .. }) {
            for chain in &transcript.written {
                match self.chain(&printed, &mut used, chain) {
                    Ok(s) => strength = strength.weaker(s),
                    Err(status) => return status,
                }
            }
        }
        // A printed condition that is an inequality is one of the claim's hypotheses.
        for (k, p) in printed.iter().enumerate() {
            if used[k] || !p.part.condition || p.part.relations.iter().all(|r| *r == Rel::Eq) {
                continue;
            }
            // A comparison that could not be decided is no evidence of a difference.
            let mut undecided = false;
            let found = transcript.conditions.iter().find_map(|c| {
                let (members, relations) = split_relations(c)?;
                let forwards = relations == p.part.relations;
                let flipped: Vec<Rel> = relations.iter().rev().map(|r| flip(*r)).collect();
                let backwards = flipped == p.part.relations;
                let order: Vec<&String> = if forwards {
                    members.iter().collect()
                } else if backwards {
                    members.iter().rev().collect()
                } else {
                    return None;
                };
                if order.len() != p.members.len() {
                    return None;
                }
                let mut strength = Agreement::Textual;
                for (m, side) in p.members.iter().zip(order) {
                    match self.same(&m.text, side) {
                        Same::Yes(s) => strength = strength.weaker(s),
                        Same::No(why) => {
                            undecided |= inconclusive(&why);
                            return None;
                        }
                    }
                }
                Some(strength)
            });
            match found {
                Some(s) => {
                    strength = strength.weaker(s);
                    used[k] = true;
                }
                None => {
                    return Status::Differs {
                        span: p.part.span,
                        printed: p.part.latex.clone(),
                        reading: String::new(),
                        side: transcript.conditions.join(", "),
                        why: if undecided {
                            Why::Undecided
                        } else {
                            Why::Condition
                        },
                        unmatched: None,
                        declared: None,
                    }
                }
            }
        }
        // Printed chains that no chain of the sides transcribes must hold in context.
        let mut context = Vec::new();
        for (k, p) in printed.iter().enumerate() {
            if used[k] {
                continue;
            }
            let mut held = p.members.len() >= 2 && p.part.relations.iter().all(|r| *r == Rel::Eq);
            let mut why = None;
            if held {
                for pair in p.members.windows(2) {
                    match self.same(&pair[0].text, &pair[1].text) {
                        Same::Yes(s) => strength = strength.weaker(s),
                        Same::No(w) if inconclusive(&w) => {
                            return Status::Differs {
                                span: p.part.span,
                                printed: p.part.latex.clone(),
                                reading: chain_text(p),
                                side: String::new(),
                                why: w,
                                unmatched: None,
                                declared: None,
                            }
                        }
                        Same::No(w) => {
                            why = match w {
                                Why::Value(s) => Some(s),
                                _ => None,
                            };
                            held = false;
                            break;
                        }
                    }
                }
            }
            if !held {
                return Status::Differs {
                    span: p.part.span,
                    printed: p.part.latex.clone(),
                    reading: chain_text(p),
                    side: String::new(),
                    why: Why::Untranscribed(why),
                    unmatched: None,
                    declared: None,
                };
            }
            if !context.contains(&p.part.latex) {
                context.push(p.part.latex.clone());
            }
        }
        Status::MachineRead {
            strength,
            context,
            defines,
            stale: None,
            from_reading: transcript.from_reading,
        }
    }

    /// Finds the printed chain that `chain` (as written) transcribes.
    fn chain(
        &self,
        printed: &[Printed],
        used: &mut [bool],
        chain: &[String],
    ) -> Result<Agreement, Status> {
        // A proportionality [X, L] states that X = 0 is the printed law `L = 0` (a
        // balance law and the variation it comes from): the printed L is the right side.
        if let (Strategy::Proportional { .. }, [_, law]) = (&self.check.strategy, chain) {
            for (k, p) in printed.iter().enumerate() {
                let zero = p.members.len() == 2
                    && p.part.relations == [Rel::Eq]
                    && p.members[1].text == "0";
                if !used[k] && zero {
                    match self.same(&p.members[0].text, law) {
                        Same::Yes(s) => {
                            used[k] = true;
                            return Ok(s);
                        }
                        Same::No(why) => return Err(self.differs(p.part, &p.members[0], law, why)),
                    }
                }
            }
        }
        let mut best: Option<(usize, Status)> = None;
        for (k, p) in printed.iter().enumerate() {
            // A condition is a hypothesis, not what the sides conclude.
            if used[k] || p.part.condition || p.members.len() != chain.len() {
                continue;
            }
            if let Err(status) = self.relations(p) {
                best.get_or_insert((0, status));
                continue;
            }
            // A chain of equalities reads the same backwards: `A^2 = X` is `X = A2`.
            let equalities = p.part.relations.iter().all(|r| *r == Rel::Eq);
            let backwards = equalities
                && p.members.len() > 1
                && !matches!(self.same(&p.members[0].text, &chain[0]), Same::Yes(_))
                && matches!(
                    self.same(&p.members[0].text, &chain[chain.len() - 1]),
                    Same::Yes(_)
                );
            let members: Vec<&ReadMember> = if backwards {
                p.members.iter().rev().collect()
            } else {
                p.members.iter().collect()
            };
            let mut strength = Agreement::Textual;
            let mut agreed = 0;
            let mut failure = None;
            for (m, side) in members.into_iter().zip(chain) {
                match self.same(&m.text, side) {
                    Same::Yes(s) => {
                        strength = strength.weaker(s);
                        agreed += 1;
                    }
                    Same::No(why) => {
                        failure = Some(self.differs(p.part, m, side, why));
                        break;
                    }
                }
            }
            match failure {
                None => {
                    used[k] = true;
                    return Ok(strength);
                }
                Some(status) => {
                    if best.as_ref().is_none_or(|(a, _)| agreed > *a) {
                        best = Some((agreed, status));
                    }
                }
            }
        }
        if printed.len() > 1 || self.chains > 1 {
            if let Some((_, Status::Differs { unmatched, .. })) = &mut best {
                *unmatched = Some(chain.join(" = "));
            }
        }
        let best = best.map(|(_, s)| s);
        Err(best.unwrap_or_else(|| {
            let part = printed.first().map(|p| p.part);
            Status::Differs {
                span: part.map_or(Span::default(), |p| p.span),
                printed: part.map_or(String::new(), |p| p.latex.clone()),
                reading: String::new(),
                side: chain.join(" = "),
                why: Why::Members { side: chain.len() },
                unmatched: None,
                declared: None,
            }
        }))
    }

    /// The printed relations against the claim's.
    fn relations(&self, p: &Printed) -> Result<(), Status> {
        let want: Option<Rel> = match &self.check.strategy {
            Strategy::Numeric { relation, .. } => Some(match relation {
                Relation::Eq => Rel::Eq,
                Relation::Le => Rel::Le,
                Relation::Ge => Rel::Ge,
            }),
            Strategy::Scalar { claim, .. } => match &**claim {
                ScalarClaim::Sign(s) => Some(match s {
                    Sign::Positive => Rel::Gt,
                    Sign::NonNegative => Rel::Ge,
                    Sign::Negative => Rel::Lt,
                    Sign::NonPositive => Rel::Le,
                }),
                _ => None,
            },
            _ => Some(Rel::Eq),
        };
        match (want, p.part.relations.iter().find(|r| Some(**r) != want)) {
            (Some(w), Some(r)) => Err(Status::Differs {
                span: p.part.span,
                printed: p.part.latex.clone(),
                reading: String::new(),
                side: String::new(),
                why: Why::Relation {
                    printed: r.symbol().to_owned(),
                    side: w.symbol().to_owned(),
                },
                unmatched: None,
                declared: None,
            }),
            _ => Ok(()),
        }
    }

    /// A differing member, located at its first term that no term of the side equals.
    fn differs(&self, part: &ReadPart, m: &ReadMember, side: &str, why: Why) -> Status {
        let mut at = (m.span, m.text.clone());
        if m.terms.len() > 1 && m.terms.len() <= 8 {
            let side_terms = terms_of(side);
            if side_terms.len() <= 8 {
                if let Some((span, text)) = m.terms.iter().find(|(_, t)| {
                    !side_terms
                        .iter()
                        .any(|s| matches!(self.same(t, s), Same::Yes(_)))
                }) {
                    at = (*span, text.clone());
                }
            }
        }
        Status::Differs {
            span: at.0,
            printed: String::new(),
            reading: at.1,
            side: side.to_owned(),
            why,
            unmatched: None,
            declared: None,
        }
        .located(part)
    }

    /// The derivative of a gradient claim's function by `symbol`, and its closed form.
    fn gradient(
        &self,
        printed: &[Printed],
        used: &mut [bool],
        function: &str,
        symbol: &str,
        closed: &str,
    ) -> Result<Agreement, Status> {
        for (k, p) in printed.iter().enumerate() {
            let Some((f, x)) = p.members.first().and_then(|m| m.partial.as_ref()) else {
                continue;
            };
            if used[k] || x != symbol {
                continue;
            }
            let mut strength = match self.same(f, function) {
                Same::Yes(s) => s,
                Same::No(why) => return Err(self.differs(p.part, &p.members[0], function, why)),
            };
            if let Some(value) = p.members.get(1) {
                match self.same(&value.text, closed) {
                    Same::Yes(s) => strength = strength.weaker(s),
                    Same::No(why) => return Err(self.differs(p.part, value, closed, why)),
                }
            }
            used[k] = true;
            return Ok(strength);
        }
        let part = printed.first().map(|p| p.part);
        Err(Status::Differs {
            span: part.map_or(Span::default(), |p| p.span),
            printed: part.map_or(String::new(), |p| p.latex.clone()),
            reading: String::new(),
            side: closed.to_owned(),
            why: Why::NoDerivative(symbol.to_owned()),
            unmatched: None,
            declared: None,
        })
    }

    /// Whether a printed member (in the language) equals a side as written, in the
    /// claim's context: exactly first, on samples where the exact route does not apply.
    fn same(&self, printed: &str, side: &str) -> Same {
        let key = (printed.to_owned(), side.to_owned());
        if let Some(s) = self.memo.borrow().get(&key) {
            return s.clone();
        }
        // The same tree is the same expression (reflexivity): no evaluation needed.
        let s = if identical(printed, side) || same_tree(printed, side) {
            Same::Yes(Agreement::Textual)
        } else if self.memo.borrow().len() >= MAX_COMPARISONS {
            Same::No(Why::Undecided)
        } else {
            self.decide_same(printed, side)
        };
        self.memo.borrow_mut().insert(key, s.clone());
        s
    }

    fn decide_same(&self, printed: &str, side: &str) -> Same {
        let domain = self
            .check
            .strategy
            .exact_domain()
            .cloned()
            .unwrap_or_default();
        let hypotheses = match &self.check.strategy {
            Strategy::Exact { hypotheses, .. } => hypotheses.clone(),
            _ => Vec::new(),
        };
        let exact = Strategy::Exact { domain, hypotheses };
        let c = match self.check.comparing(self.decls, printed, side, exact) {
            Ok(c) => c,
            Err(Incomparable::FreeIndices { left, right }) => {
                return Same::No(Why::FreeIndices {
                    printed: left,
                    side: right,
                })
            }
            Err(Incomparable::Shape(m)) => return Same::No(Why::Shape(m)),
            Err(Incomparable::Left(e)) | Err(Incomparable::Right(e)) if self.check.verbatim => {
                return if same_up_to_grouping(printed, side) {
                    Same::Yes(Agreement::Textual)
                } else {
                    Same::No(Why::IllFormed(e.message))
                };
            }
            Err(Incomparable::Left(e)) if e.kind != crate::lang::ErrorKind::Index => {
                return Same::No(Why::Untranslatable(e.message))
            }
            Err(Incomparable::Left(e)) | Err(Incomparable::Right(e)) => {
                return Same::No(Why::IllFormed(e.message))
            }
        };
        // The same expression up to the letters of summed indices: no evaluation needed.
        if let [chain] = c.chains.as_slice() {
            if let [Side { node: Ok(l), .. }, Side { node: Ok(r), .. }] = chain.as_slice() {
                if same_up_to_summed_letters(l, r) {
                    return Same::Yes(Agreement::Textual);
                }
            }
        }
        // Not decided exactly for a reason other than a size (no rational point of a
        // square root taken as a variable of its own, a construct the exact route does
        // not take, such as maxn after such a root): sampled instead, as where the
        // exact route refuses the statement outright.
        let sample = |o: &Outcome| {
            use crate::decide::finding::Finding;
            o.verdict() == Verdict::Undecided
                && !matches!(
                    o.finding,
                    Some(Finding::ResourceLimit { .. } | Finding::TimeLimit { .. })
                )
        };
        match decide(self.decls, &c) {
            Ok(o) if !sample(&o) => verdict_of(&o),
            _ => {
                let sampled = Strategy::Numeric {
                    sampling: self.sampling(),
                    relation: Relation::Eq,
                    domain: Vec::new(),
                };
                let c = Check {
                    strategy: sampled,
                    ..c
                };
                match decide(self.decls, &c) {
                    Ok(o) => verdict_of(&o),
                    Err(_) => Same::No(Why::Undecided),
                }
            }
        }
    }

    /// The claim's own sampling, or the default one.
    fn sampling(&self) -> Sampling {
        match &self.check.strategy {
            Strategy::Numeric { sampling, .. }
            | Strategy::Gradient { sampling, .. }
            | Strategy::Convex { sampling, .. } => sampling.clone(),
            _ => Sampling {
                samples: crate::derivation::DEFAULT_SAMPLES,
                seed: 1,
                ranges: Default::default(),
                given: Vec::new(),
                singular: None,
            },
        }
    }
}

/// A printed chain in the language, with its relations.
fn chain_text(p: &Printed) -> String {
    let mut out = p.members[0].text.clone();
    for (m, r) in p.members[1..].iter().zip(&p.part.relations) {
        out.push_str(&format!(" {} {}", r.symbol(), m.text));
    }
    out
}

/// The members and relations of a hypothesis as written: `0 < nu < 1/2`, `p <= 0`.
fn split_relations(text: &str) -> Option<(Vec<String>, Vec<Rel>)> {
    let mut members = Vec::new();
    let mut relations = Vec::new();
    let mut rest = text;
    loop {
        let next = ["<=", ">=", "==", "<", ">", "="]
            .iter()
            .filter_map(|op| rest.find(op).map(|k| (k, *op)))
            .min_by_key(|(k, op)| (*k, std::cmp::Reverse(op.len())));
        let Some((k, op)) = next else {
            members.push(rest.trim().to_owned());
            break;
        };
        members.push(rest[..k].trim().to_owned());
        relations.push(match op {
            "<=" => Rel::Le,
            ">=" => Rel::Ge,
            "<" => Rel::Lt,
            ">" => Rel::Gt,
            _ => Rel::Eq,
        });
        rest = &rest[k + op.len()..];
    }
    (!relations.is_empty()).then_some((members, relations))
}

/// `a < b` read backwards is `b > a`.
fn flip(r: Rel) -> Rel {
    match r {
        Rel::Lt => Rel::Gt,
        Rel::Gt => Rel::Lt,
        Rel::Le => Rel::Ge,
        Rel::Ge => Rel::Le,
        Rel::Eq => Rel::Eq,
    }
}

/// Whether a failed comparison says nothing about a difference: it could not be
/// decided, or the reading is not an expression of the language. The status is then
/// `hand`, never `differs`.
fn inconclusive(why: &Why) -> bool {
    matches!(why, Why::Undecided | Why::Untranslatable(_))
}

fn verdict_of(o: &Outcome) -> Same {
    match o.verdict() {
        Verdict::Holds => Same::Yes(match o.strength() {
            Strength::Proof => Agreement::Exact,
            Strength::Sampled => Agreement::Sampled,
        }),
        Verdict::Fails => Same::No(Why::Value(o.strength())),
        Verdict::Conditional | Verdict::Undecided => Same::No(Why::Undecided),
    }
}

impl Status {
    /// Fills in the printed piece of a `Differs` from its part.
    fn located(mut self, part: &ReadPart) -> Status {
        if let Status::Differs { span, printed, .. } = &mut self {
            let rel = span.start.saturating_sub(part.span.start);
            *printed = part
                .latex
                .get(rel..rel + (span.end - span.start))
                .map_or_else(|| part.latex.clone(), |s| s.trim().to_owned());
        }
        self
    }
}

/// The top-level terms of an expression as written, with their signs.
fn terms_of(text: &str) -> Vec<String> {
    use crate::lang::parser::ExprKind;
    fn go(text: &str, e: &crate::lang::Expr, negated: bool, out: &mut Vec<String>) {
        match &e.kind {
            ExprKind::Add(a, b) => {
                go(text, a, negated, out);
                go(text, b, negated, out);
            }
            ExprKind::Sub(a, b) => {
                go(text, a, negated, out);
                go(text, b, !negated, out);
            }
            _ => {
                let t = &text[e.span.start..e.span.end];
                out.push(if negated {
                    format!("-({t})")
                } else {
                    t.to_owned()
                });
            }
        }
    }
    let mut out = Vec::new();
    if let Ok(e) = crate::lang::parse_expr(text) {
        go(text, &e, false, &mut out);
    }
    out
}

/// The same text, up to runs of spaces: the same expression (reflexivity). Spaces are
/// kept where they separate (`a b` is not the name `ab`).
fn identical(a: &str, b: &str) -> bool {
    a.split_whitespace().eq(b.split_whitespace())
}

/// Two texts that parse to the same tree (brackets the parser drops aside): the same
/// expression, by reflexivity, in any context (see [`crate::lang::Expr::same_tree`]).
fn same_tree(a: &str, b: &str) -> bool {
    match (crate::lang::parse_expr(a), crate::lang::parse_expr(b)) {
        (Ok(x), Ok(y)) => x.same_tree(&y),
        _ => false,
    }
}

/// Two texts that parse to the same expression up to the order of terms and the
/// grouping of products and quotients (`a ((b c) / d)` is `a b c / d`; the factors keep
/// their order, as a product of matrices must): how a printed statement that is
/// ill-formed in its indices (so that it cannot be evaluated) is compared with a side
/// transcribed verbatim.
fn same_up_to_grouping(a: &str, b: &str) -> bool {
    match (crate::lang::parse_expr(a), crate::lang::parse_expr(b)) {
        (Ok(x), Ok(y)) => matches!((canonical(&x), canonical(&y)), (Some(p), Some(q)) if p == q),
        _ => false,
    }
}

/// The expression as sorted sums of flattened products (factors in order), as text;
/// `None` for constructs a verbatim statement does not use (never called equal).
fn canonical(e: &crate::lang::Expr) -> Option<String> {
    use crate::lang::parser::ExprKind as K;
    fn terms(e: &crate::lang::Expr, negated: bool, out: &mut Vec<String>) -> Option<()> {
        match &e.kind {
            K::Add(a, b) => {
                terms(a, negated, out)?;
                terms(b, negated, out)
            }
            K::Sub(a, b) => {
                terms(a, negated, out)?;
                terms(b, !negated, out)
            }
            K::Neg(a) => terms(a, !negated, out),
            _ => {
                let t = product(e)?;
                out.push(if negated { format!("-{t}") } else { t });
                Some(())
            }
        }
    }
    fn factors(e: &crate::lang::Expr, out: &mut Vec<String>) -> Option<()> {
        match &e.kind {
            K::Mul(a, b) => {
                factors(a, out)?;
                factors(b, out)
            }
            K::Div(a, b) => {
                factors(a, out)?;
                out.push(format!("/{}", canonical(b)?));
                Some(())
            }
            K::Number(q) => {
                out.push(q.to_string());
                Some(())
            }
            K::Name { full, .. } => {
                out.push(full.clone());
                Some(())
            }
            K::Pow(a, n) => {
                out.push(format!("{}^{n}", canonical(a)?));
                Some(())
            }
            K::Call(f, a) => {
                out.push(format!("{}({})", f.name(), canonical(a)?));
                Some(())
            }
            K::Call2(f, a, b) => {
                out.push(format!(
                    "{}({}, {})",
                    f.name(),
                    canonical(a)?,
                    canonical(b)?
                ));
                Some(())
            }
            _ => {
                let c = canonical(e)?;
                out.push(format!("({c})"));
                Some(())
            }
        }
    }
    fn product(e: &crate::lang::Expr) -> Option<String> {
        let mut fs = Vec::new();
        factors(e, &mut fs)?;
        fs.retain(|f| f != "1");
        Some(fs.join(" "))
    }
    match &e.kind {
        K::Add(..) | K::Sub(..) | K::Neg(..) => {
            let mut ts = Vec::new();
            terms(e, false, &mut ts)?;
            ts.sort();
            Some(format!("[{}]", ts.join(" + ")))
        }
        K::Mul(..)
        | K::Div(..)
        | K::Number(_)
        | K::Name { .. }
        | K::Pow(..)
        | K::Call(..)
        | K::Call2(..) => product(e),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The verbatim comparison regroups products and reorders terms, never factors (a
    /// product of matrices does not commute).
    #[test]
    fn verbatim_texts_are_the_same_up_to_grouping_only() {
        for (a, b) in [
            (
                "M_ij - c ((M_ij F_k) / (F_i F_i + h))",
                "M_ij - c M_ij F_k / (F_i F_i + h)",
            ),
            ("a_i a_i a_i + b", "b + a_i a_i a_i"),
            ("1 x_i x_i x_i", "x_i x_i x_i"),
        ] {
            assert!(same_up_to_grouping(a, b), "{a} | {b}");
        }
        for (a, b) in [
            ("A B", "B A"),
            ("a_i b_i b_i", "b_i a_i b_i"),
            ("a / b c", "a c / b"),
            ("a - b", "b - a"),
            ("a_i a_i a_i", "a_i a_i a_j"),
        ] {
            assert!(!same_up_to_grouping(a, b), "{a} | {b}");
        }
    }
}
