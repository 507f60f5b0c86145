//! The words for a transcription status: whether the sides say what the printed
//! statement says, and where they part.

use crate::check::transcription::{Agreement, Hand, Status, Transcription, Why};
use crate::decide::Strength;
use crate::lang::Span;

/// The status with its detail, in one sentence or two: "machine-read (proof)",
/// "differs at column 31 `\frac{1}{3}`: …", "hand: prose".
pub fn describe(t: &Transcription, printed: &str) -> String {
    match &t.status {
        Status::MachineRead {
            strength,
            context,
            defines,
            stale,
            from_reading,
        } => {
            let mut out = if *from_reading {
                "machine-read (no sides: decided on the reading itself)".to_owned()
            } else {
                format!(
                    "machine-read ({})",
                    match strength {
                        Agreement::Textual =>
                            "every member the same expression as its side, as written",
                        Agreement::Exact => "every member decided equal exactly",
                        Agreement::Sampled => "sampled: some members compared on seeded samples",
                    }
                )
            };
            if !defines.is_empty() {
                let defines: Vec<String> = defines.iter().map(|d| format!("`{d}`")).collect();
                out.push_str(&format!("; defines {}", defines.join(", ")));
            }
            if !context.is_empty() {
                out.push_str(&format!(
                    "; printed beside it and holding in the claim's context: {}",
                    context
                        .iter()
                        .map(|c| format!("`{c}`"))
                        .collect::<Vec<_>>()
                        .join("; ")
                ));
            }
            if let Some(d) = stale {
                out.push_str(&format!(
                    "; but the claim declares a difference that is not there (\"{d}\")"
                ));
            }
            out
        }
        Status::Differs {
            span,
            printed: piece,
            reading,
            side,
            why,
            unmatched,
            declared,
        } => {
            let mut out = match unmatched {
                Some(chain) => format!(
                    "differs: the sides' chain `{chain}` transcribes no printed chain; the nearest differs at column {}",
                    column(printed, *span)
                ),
                None => format!("differs at column {}", column(printed, *span)),
            };
            if !piece.is_empty() {
                out.push_str(&format!(" `{piece}`"));
            }
            if !reading.is_empty() {
                out.push_str(&format!(" (read as `{reading}`)"));
            }
            out.push_str(": ");
            out.push_str(&why_words(why, side));
            if let Some(d) = declared {
                out.push_str(&format!(". Declared: {d}"));
            }
            out
        }
        Status::Hand { reason } => format!("hand: {}", hand_words(reason, printed)),
    }
}

/// Why a statement is read by hand, in words.
pub fn hand_words(reason: &Hand, printed: &str) -> String {
    match reason {
        Hand::Prose => "a sentence of prose".to_owned(),
        Hand::Unread { span, message } => {
            format!(
                "outside the subset at column {}: {message}",
                column(printed, *span)
            )
        }
        Hand::Kind(kind) => format!("{kind} is not an equation chain to compare"),
        Hand::Undecided { span, side } => format!(
            "whether the printed member at column {} equals the side `{side}` could not be decided",
            column(printed, *span)
        ),
        Hand::Untranslatable { span, message } => format!(
            "the reading at column {} is not an expression of the language: {message}",
            column(printed, *span)
        ),
        Hand::InternalError { message, at } => format!(
            "internal error of the checker while comparing ({message}, at {at}); please report it"
        ),
    }
}

fn why_words(why: &Why, side: &str) -> String {
    let against = if side.is_empty() {
        String::new()
    } else {
        format!(" the side `{side}`")
    };
    match why {
        Why::Value(Strength::Proof) => format!("not equal to{against} (exact counterexample)"),
        Why::Value(Strength::Sampled) => format!("not equal to{against} (on a seeded sample)"),
        Why::Undecided => format!("equality with{against} could not be decided"),
        Why::FreeIndices { printed, side: s } => format!(
            "free indices {} printed, {} in{against}",
            letters(printed),
            letters(s)
        ),
        Why::IllFormed(m) => format!("ill-formed where{against} is not: {m}"),
        Why::Shape(m) => format!("{m} (against{against})"),
        Why::Members { side: n } => {
            format!("no printed chain has the {n} members of{against}")
        }
        Why::Relation { printed, side: s } => {
            format!("the printed relation is {printed}, the claim checks {s}")
        }
        Why::Untranscribed(Some(_)) => {
            "no chain of the sides transcribes this, and it is false in the claim's context"
                .to_owned()
        }
        Why::Untranscribed(None) => {
            "no chain of the sides transcribes this, and it does not hold in the claim's context"
                .to_owned()
        }
        Why::Untranslatable(m) => format!("the reading is not an expression of the language: {m}"),
        Why::Condition => format!(
            "a printed condition that is none of the claim's hypotheses ({})",
            if side.is_empty() { "it has none" } else { side }
        ),
        Why::NoDerivative(symbol) => {
            format!("the printed statement names no derivative by {symbol} for the closed form `{side}`")
        }
    }
}

fn letters(ls: &[char]) -> String {
    if ls.is_empty() {
        "none".to_owned()
    } else {
        ls.iter().collect()
    }
}

/// The 1-based column (in characters) of a span in the printed statement.
fn column(printed: &str, span: Span) -> usize {
    crate::lang::latex::column(printed, span.start)
}
