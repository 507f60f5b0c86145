//! The derivation table as one self-contained HTML page, to read offline or attach to a
//! review: printed statements as MathML (generated here, by `pulldown-latex`), verdict and
//! strength as text and colour, counterexamples and corrections, the transcription
//! status per section, and the `uses` graph as inline SVG with a legend. Clicking a node
//! jumps to its claim and focuses the graph on the claim's ancestors and descendants.
//! No request leaves the page: no fonts, scripts or styles are fetched.

use super::evidence::evidence;
use super::graph;
use super::layout::{layered, users, Layout};
use super::mathml::Unrendered;
use super::summary::Summary;
use crate::check::Decided;
use crate::decide::Strength;
use crate::derivation::Verdict;
use std::fmt::Write as _;

/// Escapes text for HTML element content and attribute values.
pub fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            _ => out.push(c),
        }
    }
    out
}

/// Escaped text whose `inline code` spans become `<code>`, or MathML when they quote
/// printed LaTeX (a backslash or a brace: the expression language has neither).
fn text(s: &str) -> String {
    spans(s, &escape)
}

/// An author's prose (a note, a reason): as [`text`], with the author's TeX-style
/// scripts outside code set as `<sup>`/`<sub>` ([`super::scripts`]).
fn authored(s: &str) -> String {
    spans(s, &|t| {
        super::scripts::render(t, &escape, ("<sup>", "</sup>"), ("<sub>", "</sub>"))
    })
}

fn spans(s: &str, plain: &dyn Fn(&str) -> String) -> String {
    let mut out = String::new();
    for (k, part) in s.split('`').enumerate() {
        if k % 2 == 1 {
            let latex = part.contains(['\\', '{']);
            match latex.then(|| mathml(part, false)) {
                Some(Ok(m)) => out.push_str(&m),
                _ => {
                    let _ = write!(out, "<code>{}</code>", escape(part));
                }
            }
        } else {
            out.push_str(&plain(part));
        }
    }
    out
}

/// LaTeX as MathML, or why it cannot be rendered (a construct `pulldown-latex` lacks).
///
/// The converter's output is re-emitted through an allowlist ([`super::mathml`]): text
/// the converter copies unescaped (`\operatorname{<script>…}`) stays text.
pub fn mathml(latex: &str, display: bool) -> Result<String, Unrendered> {
    use pulldown_latex::config::DisplayMode;
    use pulldown_latex::{push_mathml, Parser, RenderConfig, Storage};
    super::mathml::within_bounds(latex)?;
    let storage = Storage::new();
    let events: Vec<_> = Parser::new(latex, &storage).collect();
    if let Some(Err(e)) = events.iter().find(|e| e.is_err()) {
        return Err(Unrendered::Converter(e.to_string()));
    }
    let config = RenderConfig {
        display_mode: if display {
            DisplayMode::Block
        } else {
            DisplayMode::Inline
        },
        ..RenderConfig::default()
    };
    let mut out = String::new();
    push_mathml(&mut out, events.into_iter(), config)
        .map_err(|e| Unrendered::Converter(e.to_string()))?;
    Ok(super::mathml::sanitized(&out))
}

/// A formula as MathML; LaTeX the renderer cannot read is shown as source, saying so.
fn formula(latex: &str, display: bool) -> String {
    match mathml(latex, display) {
        Ok(m) => m,
        Err(why) => format!(
            "<code class=\"source\">{}</code> <span class=\"note\">(shown as LaTeX source: {})</span>",
            escape(latex),
            escape(&why.to_string())
        ),
    }
}

/// Prose with `$…$` mathematics.
fn prose(s: &str) -> String {
    let mut out = String::new();
    for (k, part) in s.split('$').enumerate() {
        if k % 2 == 1 {
            out.push_str(&formula(part, false));
        } else {
            out.push_str(&escape(part));
        }
    }
    out
}

/// The page's Content-Security-Policy: nothing is fetched, nothing is submitted, and
/// only the page's own style and script run (named by their SHA-256), so that markup
/// which got past every escape would still do nothing.
fn policy() -> String {
    format!(
        "default-src 'none'; style-src '{}'; script-src '{}'; img-src data:; \
         base-uri 'none'; form-action 'none'",
        sha256_source(STYLE),
        sha256_source(SCRIPT)
    )
}

/// A CSP hash source: `sha256-` and the base64 of the text's SHA-256.
fn sha256_source(text: &str) -> String {
    use sha2::{Digest, Sha256};
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let digest = Sha256::digest(text.as_bytes());
    let mut out = String::from("sha256-");
    for chunk in digest.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let n = u32::from(b[0]) << 16 | u32::from(b[1]) << 8 | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(char::from(ALPHABET[(n >> (18 - 6 * k) & 63) as usize]));
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// `verdict`, its CSS class and the glyph that says it without colour.
fn verdict_of(r: &Decided<'_>) -> (&'static str, &'static str) {
    match (r.outcome.verdict(), r.outcome.strength()) {
        (Verdict::Holds, Strength::Proof) => ("holds", "✓"),
        (Verdict::Holds, Strength::Sampled) => ("holds", "≈"),
        (Verdict::Fails, _) => ("fails", "✗"),
        (Verdict::Conditional, _) => ("conditional", "◐"),
        (Verdict::Undecided, _) => ("undecided", "?"),
    }
}

/// The graph's node label: the id, the verdict glyph, and `root` or `inherited` for a
/// failure; a long id is broken after the hyphen nearest its middle, so that a column
/// stays narrow.
fn node_label(r: &Decided<'_>) -> String {
    let (_, glyph) = verdict_of(r);
    let origin = match &r.attribution {
        Some(a) if a.is_root() => " root",
        Some(a) if !a.inherited_from().is_empty() => " inherited",
        Some(_) => " origin?",
        None => "",
    };
    let id = &r.claim.id;
    let middle = id.chars().count() / 2;
    let cut = id
        .char_indices()
        .filter(|&(_, c)| c == '-')
        .map(|(i, _)| i + 1)
        .min_by_key(|&i| id[..i].chars().count().abs_diff(middle));
    match cut {
        Some(i) if id.chars().count() > LONG_ID => {
            format!("{}\n{} {glyph}{origin}", &id[..i], &id[i..])
        }
        _ => format!("{id} {glyph}{origin}"),
    }
}

/// Ids longer than this take two lines in the graph.
const LONG_ID: usize = 16;

/// Renders the page.
pub fn render(rows: &[&Decided<'_>], paper: &str) -> String {
    let summary = Summary::of(rows);
    let mut out = String::new();
    let _ = write!(
        out,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta http-equiv=\"Content-Security-Policy\" content=\"{}\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <title>Derivation table: {}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n",
        policy(),
        escape(paper)
    );
    let _ = write!(
        out,
        "<header>\n<h1>Derivation table</h1>\n<p class=\"paper\">{}</p>\n<p>{}</p>\n",
        escape(paper),
        escape(&summary.sentence(rows.len()))
    );
    let origin = summary.origin_sentence();
    if !origin.is_empty() {
        let _ = writeln!(out, "<p>{}</p>", escape(&origin));
    }
    let _ = writeln!(
        out,
        "<p>{}</p>\n</header>",
        escape(&summary.transcription_sentence())
    );
    let graph = Graph::of(rows);
    graph_section(&mut out, rows, &graph);
    for (s, members) in &graph.sections {
        let here: Vec<&Decided<'_>> = members.iter().map(|&k| rows[k]).collect();
        let part = Summary::of(&here);
        let _ = writeln!(
            out,
            "<section id=\"section-{}\">\n<h2>Section {}</h2>\n<p class=\"section-summary\">{} {}</p>",
            escape(s),
            escape(s),
            escape(&part.sentence(here.len())),
            escape(&part.transcription_sentence())
        );
        for &k in members {
            let users: Vec<&str> = graph.used_by[k]
                .iter()
                .map(|&j| rows[j].claim.id.as_str())
                .collect();
            claim(&mut out, rows[k], &users);
        }
        out.push_str("</section>\n");
    }
    let _ = write!(out, "<script>{SCRIPT}</script>\n</body>\n</html>\n");
    out
}

/// One claim: statement, verdict, evidence, correction, origin, and its edges.
fn claim(out: &mut String, r: &Decided<'_>, used_by: &[&str]) {
    let c = r.claim;
    let (class, glyph) = verdict_of(r);
    let origin = match &r.attribution {
        Some(a) if a.is_root() => " root".to_owned(),
        Some(a) if !a.inherited_from().is_empty() => " inherited".to_owned(),
        _ => String::new(),
    };
    let _ = write!(
        out,
        "<article class=\"claim {class}{origin}\" id=\"claim-{id}\">\n<h3><a href=\"#claim-{id}\">{id}</a> \
         <span class=\"badge {class}\">{glyph} {}</span>",
        escape(&super::row::verdict_label(r)),
        id = escape(&c.id)
    );
    if let Some(a) = &r.attribution {
        let _ = write!(
            out,
            " <span class=\"origin\">{}</span>",
            match a.label() {
                "root" => "root error",
                "inherited" => "inherited failure",
                _ => "origin undetermined",
            }
        );
    }
    out.push_str("</h3>\n<div class=\"statement\">");
    if c.prose && !super::row::prose_is_formula(&c.statement) {
        let _ = write!(out, "“{}”", prose(&c.statement));
    } else {
        out.push_str(&formula(&c.statement, true));
    }
    out.push_str("</div>\n<dl>\n");
    let mut item = |term: &str, body: String| {
        let _ = writeln!(out, "<dt>{term}</dt><dd>{body}</dd>");
    };
    item(
        "Decided",
        format!(
            "{} ({}), method {}",
            escape(r.outcome.verdict().as_str()),
            match r.outcome.strength() {
                Strength::Proof => "proof: a kernel certificate",
                Strength::Sampled => "sampled evidence, not a proof",
            },
            escape(r.outcome.method.as_str())
        ),
    );
    item(
        "Read",
        format!(
            "{}{}",
            if r.transcription.as_expected() {
                ""
            } else {
                "✗ not declared: "
            },
            text(&super::transcription::describe(
                &r.transcription,
                &c.statement
            ))
        ),
    );
    let printed = super::row::printed_point(r, &|s| formula(s, false))
        .map(|p| format!(" ({p})"))
        .unwrap_or_default();
    item(
        "Evidence",
        format!("{}{printed}", text(&evidence(&r.outcome))),
    );
    if let Some(reason) = &c.reason {
        item("Why", authored(reason));
    }
    if let Some(a) = &r.attribution {
        item("Origin", text(&graph::attribution(a)));
    }
    if let (Some(k), Some(o)) = (&c.correction, &r.correction) {
        item(
            "Correction",
            format!(
                "<div class=\"statement\">{}</div>{} <span class=\"badge {}\">{}</span> ({}; {})",
                formula(&k.statement, true),
                authored(&k.reason),
                if o.verdict() == Verdict::Holds {
                    "holds"
                } else {
                    "fails"
                },
                escape(&o.verdict_text()),
                escape(o.method.as_str()),
                text(&evidence(o))
            ),
        );
    }
    let link = |id: &str| format!("<a href=\"#claim-{0}\">{0}</a>", escape(id));
    if !c.uses.is_empty() {
        let links: Vec<String> = c.uses.iter().map(|u| link(&u.id)).collect();
        item("Uses", links.join(", "));
    }
    let users: Vec<String> = used_by.iter().map(|u| link(u)).collect();
    if !users.is_empty() {
        item("Used by", users.join(", "));
    }
    if let Some(note) = &c.note {
        item("Note", authored(note));
    }
    let _ = write!(
        out,
        "</dl>\n<button type=\"button\" class=\"focus\" data-id=\"{}\">Focus the graph on this claim</button>\n</article>\n",
        escape(&c.id)
    );
}

/// The legend and the graph of `uses` as inline SVG, one band per section in the order
/// of the rows: a band lays out its section's claims, and each claim of another section
/// that one of them uses appears there once more, as a dashed copy that links to it.
/// Every edge is drawn inside one band, so the drawing grows with the number of
/// sections, not with the length of the longest chain of the whole paper.
/// The `uses` between the rows (by index), read both ways, and the rows of each
/// section in the order sections first appear: found once for the graph and the cards.
struct Graph<'r> {
    uses: Vec<Vec<usize>>,
    used_by: Vec<Vec<usize>>,
    sections: Vec<(&'r str, Vec<usize>)>,
}

impl<'r> Graph<'r> {
    fn of(rows: &[&'r Decided<'_>]) -> Graph<'r> {
        let by_id: std::collections::HashMap<&str, usize> = rows
            .iter()
            .enumerate()
            .map(|(k, r)| (r.claim.id.as_str(), k))
            .collect();
        let uses: Vec<Vec<usize>> = rows
            .iter()
            .map(|r| {
                r.claim
                    .uses
                    .iter()
                    .filter_map(|u| by_id.get(u.id.as_str()).copied())
                    .collect()
            })
            .collect();
        let mut sections: Vec<(&'r str, Vec<usize>)> = Vec::new();
        let mut section_of: std::collections::HashMap<&str, usize> =
            std::collections::HashMap::new();
        for (k, r) in rows.iter().enumerate() {
            let at = *section_of
                .entry(r.claim.section.as_str())
                .or_insert_with(|| {
                    sections.push((r.claim.section.as_str(), Vec::new()));
                    sections.len() - 1
                });
            sections[at].1.push(k);
        }
        Graph {
            used_by: users(&uses),
            uses,
            sections,
        }
    }
}

fn graph_section(out: &mut String, rows: &[&Decided<'_>], graph: &Graph<'_>) {
    let Graph {
        uses,
        used_by,
        sections,
    } = graph;
    let mut body = String::new();
    let (mut width, mut top) = (0.0f64, 0.0f64);
    for (s, members) in sections {
        let s: &str = s;
        // The band's nodes: its claims, then the claims of other sections they use.
        let mut nodes = members.clone();
        let mut place: std::collections::HashMap<usize, usize> =
            members.iter().enumerate().map(|(i, &k)| (k, i)).collect();
        for &k in members {
            for &u in &uses[k] {
                if let std::collections::hash_map::Entry::Vacant(e) = place.entry(u) {
                    e.insert(nodes.len());
                    nodes.push(u);
                }
            }
        }
        let local = |k: usize| place.get(&k).copied();
        let band_uses: Vec<Vec<usize>> = nodes
            .iter()
            .map(|&k| {
                if rows[k].claim.section == s {
                    uses[k].iter().filter_map(|&u| local(u)).collect()
                } else {
                    Vec::new()
                }
            })
            .collect();
        let labels: Vec<String> = nodes
            .iter()
            .map(|&k| match rows[k].claim.section.as_str() {
                other if other != s => format!("{} (§{})", node_label(rows[k]), short(other)),
                _ => node_label(rows[k]),
            })
            .collect();
        let Layout {
            places,
            routes,
            width: w,
            height: h,
        } = layered(&labels, &band_uses);
        let _ = writeln!(
            body,
            "<g class=\"band\" transform=\"translate(0,{top:.0})\"><text class=\"band-title\" x=\"8\" y=\"16\">§{}</text>",
            escape(s)
        );
        let offset = BAND_TITLE;
        for route in &routes {
            let (from, to) = (rows[nodes[route.from]], rows[nodes[route.to]]);
            let inherited = to
                .attribution
                .as_ref()
                .is_some_and(|a| a.inherited_from().contains(&from.claim.id));
            let mut d = String::new();
            for (i, &(x, y)) in route.points.iter().enumerate() {
                let y = y + offset;
                if i == 0 {
                    let _ = write!(d, "M{x:.1},{y:.1}");
                } else if i % 2 == 1 {
                    // Across the gap between two columns: a curve, level at both ends.
                    let (px, py) = route.points[i - 1];
                    let bend = (x - px) / 2.0;
                    let _ = write!(
                        d,
                        " C{:.1},{:.1} {:.1},{y:.1} {x:.1},{y:.1}",
                        px + bend,
                        py + offset,
                        x - bend
                    );
                } else {
                    let _ = write!(d, " L{x:.1},{y:.1}");
                }
            }
            let _ = writeln!(
                body,
                "<path class=\"edge{}\" data-from=\"{}\" data-to=\"{}\" d=\"{d}\" marker-end=\"url(#arrow)\"/>",
                if inherited { " inherited" } else { "" },
                escape(&from.claim.id),
                escape(&to.claim.id),
            );
        }
        for (local_k, &k) in nodes.iter().enumerate() {
            let r = rows[k];
            let p = places[local_k];
            let (class, _) = verdict_of(r);
            let root = r.attribution.as_ref().is_some_and(|a| a.is_root());
            let copy = r.claim.section != s;
            // The direct neighbours only (the page's script follows them to the whole
            // ancestry), so that the page grows with the edges, not with their closure.
            let ids = |set: &[usize]| {
                set.iter()
                    .map(|&j| escape(&rows[j].claim.id))
                    .collect::<Vec<_>>()
                    .join(" ")
            };
            let title = format!(
                "{}{}: {}{}",
                r.claim.id,
                if copy {
                    format!(" (§{}, used here)", short(&r.claim.section))
                } else {
                    String::new()
                },
                r.outcome.verdict_text(),
                r.attribution
                    .as_ref()
                    .map(|a| format!("; {}", graph::attribution(a)))
                    .unwrap_or_default()
            );
            let neighbours = if copy {
                String::new()
            } else {
                format!(
                    " data-up=\"{}\" data-down=\"{}\"",
                    ids(&uses[k]),
                    ids(&used_by[k])
                )
            };
            let _ = writeln!(
                body,
                "<a class=\"{} {class}{}\" href=\"#claim-{id}\" data-id=\"{id}\"{neighbours}><title>{}</title><rect x=\"{:.1}\" y=\"{:.1}\" width=\"{:.1}\" height=\"{:.1}\" rx=\"{}\"/>{}</a>",
                if copy { "copy" } else { "node" },
                if root { " root" } else { "" },
                escape(&title),
                p.x - p.width / 2.0,
                p.y - p.height / 2.0 + offset,
                p.width,
                p.height,
                if r.claim.prose { p.height / 2.0 } else { 2.0 },
                label_text(p.x, p.y + offset, &labels[local_k]),
                id = escape(&r.claim.id),
            );
        }
        let _ = writeln!(
            body,
            "<line class=\"band-rule\" x1=\"0\" y1=\"{:.0}\" x2=\"100%\" y2=\"{:.0}\"/></g>",
            h + offset,
            h + offset
        );
        width = width.max(w);
        top += h + offset;
    }
    out.push_str(LEGEND);
    let _ = write!(
        out,
        "<div class=\"graph-box\"><svg id=\"graph\" xmlns=\"http://www.w3.org/2000/svg\" width=\"{width:.0}\" height=\"{top:.0}\" viewBox=\"0 0 {width:.0} {top:.0}\" role=\"img\" aria-label=\"The claims and the claims each uses, section by section\">\n<defs><marker id=\"arrow\" viewBox=\"0 0 8 8\" refX=\"8\" refY=\"4\" markerWidth=\"6\" markerHeight=\"6\" orient=\"auto\"><path d=\"M0,0 L8,4 L0,8 z\" fill=\"#667\"/></marker></defs>\n{body}"
    );
    out.push_str("</svg></div>\n<p id=\"focus-note\" class=\"note\">Click a claim to jump to it and to focus the graph on what it uses and what uses it.</p>\n");
}

/// A section's name as a copy of one of its claims shows it: at most 12 characters, so
/// that a long name is not repeated in full once per claim that uses the claim.
fn short(section: &str) -> String {
    if section.chars().count() <= 12 {
        section.to_owned()
    } else {
        let head: String = section.chars().take(11).collect();
        format!("{head}…")
    }
}

/// A node's label as SVG text centred at (x, y), one `tspan` per line.
fn label_text(x: f64, y: f64, label: &str) -> String {
    let lines: Vec<&str> = label.lines().collect();
    let first = y + 4.0 - 7.0 * (lines.len().max(1) - 1) as f64;
    let mut out = format!("<text x=\"{x:.1}\" y=\"{first:.1}\">");
    for (i, line) in lines.iter().enumerate() {
        if i == 0 {
            out.push_str(&escape(line));
        } else {
            let _ = write!(
                out,
                "<tspan x=\"{x:.1}\" dy=\"14\">{}</tspan>",
                escape(line)
            );
        }
    }
    out.push_str("</text>");
    out
}

/// The height of a band's title, above its drawing (pixels).
const BAND_TITLE: f64 = 22.0;

const LEGEND: &str = r#"<section id="graph-section">
<h2>Derivation graph</h2>
<p>An arrow runs from a claim to each claim derived from it (<code>uses</code>), section by section: a dashed box is a claim of another section that this section uses.</p>
<ul class="legend">
<li><svg width="44" height="18"><rect x="1" y="1" width="42" height="16" rx="2" class="key"/></svg> a printed formula</li>
<li><svg width="44" height="18"><rect x="1" y="1" width="42" height="16" rx="8" class="key"/></svg> a sentence of prose</li>
<li><span class="swatch holds">✓</span> holds, proved by the kernel; <span class="swatch holds">≈</span> holds on sampled evidence (not a proof)</li>
<li><span class="swatch fails">✗</span> fails: a counterexample</li>
<li><span class="swatch conditional">◐</span> conditional: holds on a stated domain only</li>
<li><span class="swatch undecided">?</span> undecided: the checker could not decide, and says why</li>
<li><span class="swatch fails root-key">root</span> a root error (thick border): still fails with every failing claim it uses corrected</li>
<li><span class="swatch fails">inherited</span> fails only because a claim it uses fails: holds once that claim is corrected (red dashed arrow)</li>
</ul>
<p><button type="button" id="clear-focus">Show the whole graph</button></p>
"#;

const STYLE: &str = r#"
body { font-family: system-ui, sans-serif; margin: 0 auto; max-width: 72rem; padding: 1rem 1.5rem 100vh; line-height: 1.45; color: #1b1b1f; }
h1 { margin-bottom: 0.2rem; } .paper { font-style: italic; margin-top: 0; }
code { font-size: 0.9em; background: #f3f3f6; padding: 0 0.2em; border-radius: 3px; overflow-wrap: anywhere; }
.note { color: #555; font-size: 0.9em; }
.graph-box { overflow-x: auto; border: 1px solid #ccd; border-radius: 6px; background: #fcfcfe; width: calc(100vw - 2rem); max-width: fit-content; margin-left: 50%; transform: translateX(-50%); }
#graph text { font: 12px ui-monospace, monospace; text-anchor: middle; fill: #1b1b1f; pointer-events: none; }
#graph .node rect, #graph .copy rect { stroke: #556; stroke-width: 1; cursor: pointer; }
#graph .copy rect { stroke-dasharray: 4 2; }
#graph .band-title { font: 600 13px system-ui, sans-serif; text-anchor: start; }
#graph .band-rule { stroke: #dde; stroke-width: 1; }
#graph .holds rect, .swatch.holds { fill: #d9f2dd; background: #d9f2dd; }
#graph .fails rect, .swatch.fails { fill: #f9d6d9; background: #f9d6d9; }
#graph .conditional rect, .swatch.conditional { fill: #fdf0c4; background: #fdf0c4; }
#graph .undecided rect, .swatch.undecided { fill: #e3e3e8; background: #e3e3e8; }
#graph .root rect { stroke: #a3000f; stroke-width: 3; }
#graph .edge { fill: none; stroke: #99a; stroke-width: 1; }
#graph .edge.inherited { stroke: #c0001a; stroke-width: 2; stroke-dasharray: 5 3; }
#graph.focused .node:not(.kept), #graph.focused .copy:not(.kept) { opacity: 0.15; } #graph.focused .edge:not(.kept) { opacity: 0.08; }
#graph .current rect { stroke: #0b57d0; stroke-width: 3; }
.legend { list-style: none; padding: 0; display: grid; grid-template-columns: repeat(auto-fill, minmax(22rem, 1fr)); gap: 0.2rem 1rem; }
.legend svg { vertical-align: middle; } .legend .key { fill: #fff; stroke: #556; }
.swatch { display: inline-block; min-width: 1.4em; text-align: center; border: 1px solid #556; border-radius: 3px; padding: 0 0.25em; }
.swatch.root-key { border: 3px solid #a3000f; }
article.claim { border: 1px solid #ccd; border-left: 6px solid #7a7; border-radius: 6px; padding: 0.4rem 1rem; margin: 0.8rem 0; }
article.claim.fails { border-left-color: #c0001a; } article.claim.conditional { border-left-color: #c9a300; }
article.claim.undecided { border-left-color: #889; } article.claim.root { border-left-width: 12px; }
article.claim:target { box-shadow: 0 0 0 3px #0b57d0; }
h3 { margin: 0.3rem 0; font-size: 1.05rem; } h3 a { color: inherit; }
.badge { font-size: 0.85rem; font-weight: 600; padding: 0.05rem 0.45rem; border-radius: 4px; border: 1px solid #556; }
.badge.holds { background: #d9f2dd; } .badge.fails { background: #f9d6d9; color: #7a0010; }
.badge.conditional { background: #fdf0c4; } .badge.undecided { background: #e3e3e8; }
.origin { font-size: 0.85rem; font-weight: 600; color: #7a0010; }
.statement { overflow-x: auto; margin: 0.4rem 0; } .statement math[display="block"] { margin: 0.3rem 0; }
dl { display: grid; grid-template-columns: 7rem minmax(0, 1fr); gap: 0.15rem 0.8rem; margin: 0.4rem 0; }
dt { font-weight: 600; color: #444; } dd { margin: 0; min-width: 0; overflow-wrap: anywhere; }
button { font: inherit; font-size: 0.85rem; cursor: pointer; }
math { font-size: 1.1em; }
"#;

const SCRIPT: &str = r#"
(function () {
  const svg = document.getElementById('graph');
  const note = document.getElementById('focus-note');
  function ids(s) { return s ? s.split(' ') : []; }
  // Every claim reachable from `id` along `key` ('up': what it uses; 'down': what uses it).
  function closure(byId, id, key) {
    const seen = new Set(), stack = [id];
    while (stack.length) {
      const node = byId.get(stack.pop());
      if (!node) continue;
      for (const next of ids(node.dataset[key])) {
        if (!seen.has(next)) { seen.add(next); stack.push(next); }
      }
    }
    seen.delete(id);
    return [...seen];
  }
  function focus(id) {
    const nodes = [...svg.querySelectorAll('.node')];
    const byId = new Map(nodes.map(n => [n.dataset.id, n]));
    const node = byId.get(id);
    if (!node) return;
    const up = closure(byId, id, 'up'), down = closure(byId, id, 'down');
    const keep = new Set([id, ...up, ...down]);
    svg.classList.add('focused');
    svg.querySelectorAll('.node, .copy').forEach(n => {
      n.classList.toggle('kept', keep.has(n.dataset.id));
      n.classList.toggle('current', n.dataset.id === id);
    });
    svg.querySelectorAll('.edge').forEach(e => e.classList.toggle('kept', keep.has(e.dataset.from) && keep.has(e.dataset.to)));
    note.textContent = 'Focus: ' + id + ', ' + up.length + ' claim(s) it rests on and ' + down.length + ' that rest on it.';
  }
  function clear() {
    svg.classList.remove('focused');
    svg.querySelectorAll('.current').forEach(n => n.classList.remove('current'));
    note.textContent = 'The whole graph.';
  }
  svg.addEventListener('click', ev => {
    const a = ev.target.closest('.node, .copy');
    if (a) focus(a.dataset.id);
  });
  document.querySelectorAll('button.focus').forEach(b => b.addEventListener('click', () => {
    focus(b.dataset.id);
    svg.scrollIntoView();
  }));
  document.getElementById('clear-focus').addEventListener('click', clear);
  // `?selftest`: click every node and record whether its claim scrolled to the top
  // (the browser test reads the result from the page).
  async function selftest() {
    const out = { nodes: 0, claims: 0, math: 0, overflowing: [], unrendered: 0, raw_latex: [], raw_latex_outside_code: [], clicks: 0, scrolled: 0, focused: 0, failures: [], notes: {}, failing: 0, failing_visible: 0, pwned: window.__pwned || 0 };
    const failing = [...document.querySelectorAll('article.claim.fails')];
    out.failing = failing.length;
    out.failing_visible = failing.filter(a => {
      const s = getComputedStyle(a);
      return a.getBoundingClientRect().height > 0 && s.display !== 'none' && s.visibility === 'visible' && s.opacity !== '0';
    }).length;
    const nodes = [...svg.querySelectorAll('a.node')];
    out.nodes = nodes.length;
    out.claims = document.querySelectorAll('article.claim').length;
    out.math = document.querySelectorAll('math').length;
    // Cards whose content sticks out of them (a wide statement scrolls inside its own box).
    out.overflowing = [...document.querySelectorAll('article.claim')].filter(a => a.scrollWidth > a.clientWidth + 1).map(a => a.id);
    out.unrendered = document.querySelectorAll('code.source').length;
    out.raw_latex = (document.body.innerText.match(/\\[a-zA-Z]+/g) || []).slice(0, 10);
    const plain = document.body.cloneNode(true);
    plain.querySelectorAll('code').forEach(c => c.remove());
    out.raw_latex_outside_code = (plain.textContent.match(/\\[a-zA-Z]+/g) || []).slice(0, 10);
    for (const a of nodes) {
      window.scrollTo(0, 0);
      a.dispatchEvent(new MouseEvent('click', { bubbles: true, cancelable: true, view: window }));
      await new Promise(r => setTimeout(r, 0));
      const target = document.getElementById('claim-' + a.dataset.id);
      const top = target ? target.getBoundingClientRect().top : null;
      out.clicks++;
      if (target && Math.abs(top) < 2 && window.scrollY > 0) out.scrolled++;
      else out.failures.push(a.dataset.id + ' top=' + top);
      if (svg.classList.contains('focused') && a.classList.contains('current')) out.focused++;
      out.notes[a.dataset.id] = note.textContent;
    }
    clear();
    window.scrollTo(0, 0);
    const pre = document.createElement('pre');
    pre.id = 'selftest';
    pre.textContent = JSON.stringify(out);
    document.body.appendChild(pre);
  }
  if (location.search.indexOf('selftest') >= 0) selftest();
})();
"#;
