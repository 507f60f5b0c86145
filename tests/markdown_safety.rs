//! A hostile file's text never becomes Markdown markup: its table and errata are parsed
//! by a CommonMark parser (pulldown-cmark, with GFM tables and strikethrough, with and
//! without mathematics), and no link, image or HTML appears, every row keeps its seven
//! cells, and with mathematics no emphasis or strikethrough either. (Bare addresses, which pulldown-cmark does not
//! link, are unit-tested in `report::markdown`.)

use pulldown_cmark::{Event, Options, Parser as Markdown, Tag};

/// Every text field of a file, written to break out: escapes undone by a backslash, a
/// backtick escaped so as to move a code span, dollars that pandoc would not pair,
/// links and images inside statements, pipes.
const HOSTILE: &str = r#"paper = 'P \*e\* \[l\](javascript:1) `x` | y'
section = 's \_u\_ \`*a*` [s](javascript:2)'
title = "t"
dimension = 2
scalars = ["x"]

[[claim]]
id = "wrong"
printed = '[a](javascript:3) = x \`[b](javascript:4)` \| \$ *c* ~~d~~ + 1'
expect = "fails"
reason = 'R \*emph\* \[click\](javascript:alert(1)) \`![i](https://e.example/p.png) *b* ` price $5 *bold* and $6 | <b>x</b>'
note = 'N ![img](https://e.example/n.png) _n_ \`[n](javascript:5)`'
sides = ["x", "x + 1"]

[claim.correction]
printed = 'x + 1 = x + 1 [c](javascript:6)'
reason = 'C \`*corr* [c](javascript:alert(1)) ` ~~s~~'
expect = "holds"
sides = ["x + 1", "x + 1"]

[[claim]]
id = "prose"
prose = true
printed = 'Prose \`_u_ ~~s~~ [p](javascript:7)` and $[m](javascript:8)$ and $5 *i* $6'
expect = "holds"
sides = ["x", "x"]
"#;

/// The Markdown of `verify` (the table) or `errata` on the hostile file.
fn markdown(errata: bool) -> String {
    let dir = std::env::temp_dir().join(format!("cosserat-check-md-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("hostile.toml");
    std::fs::write(&file, HOSTILE).unwrap();
    let (dir, file) = (dir.to_str().unwrap(), file.to_str().unwrap());
    let args = if errata {
        vec!["errata", "--format", "markdown", "--dir", dir]
    } else {
        vec!["verify", "--format", "markdown", file]
    };
    crate::common::run_cli(&args, false).1
}

/// The markup a parse of `text` finds that a file could have put there: links, images
/// and HTML, rows of other than seven cells (a pipe that splits a cell is unit-tested:
/// GFM drops a row's excess cells), and, where the parser reads the
/// mathematics as such (`math`), emphasis and strikethrough. (Without mathematics a
/// viewer shows a statement's LaTeX as text, in which `_` and `*` may look like
/// emphasis: nothing there is active.)
fn markup(text: &str, math: bool) -> Vec<String> {
    let mut options = Options::ENABLE_TABLES | Options::ENABLE_STRIKETHROUGH;
    if math {
        options |= Options::ENABLE_MATH;
    }
    let mut found = Vec::new();
    let mut cells = 0;
    for event in Markdown::new_ext(text, options) {
        match event {
            Event::Start(Tag::Link { dest_url, .. }) => found.push(format!("link {dest_url}")),
            Event::Start(Tag::Image { dest_url, .. }) => found.push(format!("image {dest_url}")),
            Event::Start(Tag::Emphasis) if math => found.push("emphasis".into()),
            Event::Start(Tag::Strikethrough) if math => found.push("strikethrough".into()),
            Event::Html(h) | Event::InlineHtml(h) => found.push(format!("html {h}")),
            Event::Start(Tag::TableRow | Tag::TableHead) => cells = 0,
            Event::Start(Tag::TableCell) => cells += 1,
            Event::End(pulldown_cmark::TagEnd::TableRow | pulldown_cmark::TagEnd::TableHead)
                if cells != 7 =>
            {
                found.push(format!("a row of {cells} cells"))
            }
            _ => {}
        }
    }
    found
}

#[test]
fn a_hostile_files_text_is_no_markup_in_the_table_or_the_errata() {
    // The parse finds what it is looking for, so that a pass means something.
    assert_eq!(markup("[a](javascript:1) <b>x</b>", false).len(), 3);
    assert_eq!(markup("*a* ~~b~~ $x$", true).len(), 2);
    for errata in [false, true] {
        let text = markdown(errata);
        assert!(text.contains("wrong"), "{text}");
        for math in [false, true] {
            assert_eq!(markup(&text, math), Vec::<String>::new(), "{text}");
        }
    }
}
