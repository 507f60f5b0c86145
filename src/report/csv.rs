//! The derivation table as CSV (RFC 4180: every field quoted, quotes doubled), one row
//! per claim, for spreadsheets and scripts; no cell starts a formula ([`neutralised`]).

use super::row::full_evidence;
use crate::check::Decided;

fn field(s: &str) -> String {
    format!("\"{}\"", neutralised(s).replace('"', "\"\""))
}

/// A text cell a spreadsheet will not run as a formula: one that starts with `=`, `+`,
/// `-`, `@` or `|` (or their full-width forms), after any white space, or with a tab or
/// a line break, gets a leading `'` (OWASP's advice against CSV injection; spreadsheets
/// skip leading spaces before a formula). Numbers the checker writes are not text
/// cells and keep their sign.
pub fn neutralised(s: &str) -> std::borrow::Cow<'_, str> {
    const STARTS: [char; 10] = ['=', '+', '-', '@', '|', '＝', '＋', '－', '＠', '｜'];
    if s.starts_with(['\t', '\r', '\n']) || s.trim_start().starts_with(STARTS) {
        format!("'{s}").into()
    } else {
        s.into()
    }
}

/// Renders the table: a header line, then one line per claim.
pub fn render(rows: &[&Decided<'_>]) -> String {
    let mut out = String::from(
        "id,section,statement,verdict,expected,method,checks,evidence,correction,correction_verdict,strength,transcription\n",
    );
    for r in rows {
        let c = r.claim;
        let (corr, corr_verdict) = match (&c.correction, &r.correction) {
            (Some(k), Some(o)) => (k.statement.as_str(), o.verdict().as_str()),
            _ => ("", ""),
        };
        let cells = [
            c.id.as_str(),
            c.section.as_str(),
            c.statement.as_str(),
            r.outcome.verdict().as_str(),
            if c.declared { c.expect.as_str() } else { "" },
            r.outcome.method.as_str(),
            &r.outcome.checks.to_string(),
            &full_evidence(r, (&|s| s.to_owned(), &|s| s.to_owned()), &|s| s.to_owned()),
            corr,
            corr_verdict,
            match r.outcome.strength() {
                crate::decide::Strength::Proof => "proof",
                crate::decide::Strength::Sampled => "sampled",
            },
            &super::row::read_label(r),
        ]
        .map(field);
        out.push_str(&cells.join(","));
        out.push('\n');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::neutralised;

    #[test]
    fn no_cell_starts_a_formula_even_after_white_space() {
        for cell in [
            "=1+1",
            " =1+1",
            " \t=HYPERLINK(\"x\")",
            "\n=1",
            "+1",
            "-1",
            "@SUM(A1)",
            "|cmd",
            "＝1+1",
            "  －1",
        ] {
            assert!(neutralised(cell).starts_with('\''), "{cell:?}");
        }
        for cell in ["x = 1", "1 = 1", "holds", "a -1", ""] {
            assert_eq!(neutralised(cell), cell);
        }
    }
}
