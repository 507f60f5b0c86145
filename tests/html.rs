//! The HTML report: one self-contained page. Without a browser the page's structure is
//! checked; with headless Chromium (Debian's `chromium`, or `$CHROMIUM`) the page is
//! loaded for real: it must render its statements as MathML with no raw LaTeX showing,
//! draw one graph node per claim, and scroll to the claim when a node is clicked. A
//! screenshot is left in `target/html-report.png` to look at.

use cosserat_check::cli::decide_all;
use cosserat_check::derivation::{load_dir, DerivationFile};
use cosserat_check::report;
use std::path::{Path, PathBuf};
use std::process::Command;

fn page() -> (String, usize, usize) {
    let files: Vec<DerivationFile> =
        load_dir(&Path::new(env!("CARGO_MANIFEST_DIR")).join("derivations")).unwrap();
    let rows = decide_all(&files, None).unwrap();
    let refs: Vec<_> = rows.iter().collect();
    let edges = rows.iter().map(|r| r.claim.uses.len()).sum::<usize>();
    (
        report::html::render(&refs, &report::paper_of(&refs, &[])),
        rows.len(),
        edges,
    )
}

#[test]
fn the_page_is_self_contained_with_a_node_per_claim_and_mathml() {
    let (html, claims, edges) = page();
    assert_eq!(html.matches("<a class=\"node").count(), claims);
    assert_eq!(html.matches("<article class=\"claim").count(), claims);
    assert_eq!(html.matches("<path class=\"edge").count(), edges);
    assert!(html.matches("<math").count() >= claims / 2);
    // Every printed statement and correction is rendered, none shown as source.
    assert!(!html.contains("class=\"source\""));
    // Nothing is fetched: the only URL is the SVG namespace.
    for needle in ["src=", "href=\"http", "url(http", "@import", "<link"] {
        assert!(
            !html.contains(needle),
            "the page fetches something: {needle}"
        );
    }
    assert!(html.contains("eq23") && html.contains("inherited from eq21"));
}

/// Headless Chromium, if installed.
fn browser() -> Option<PathBuf> {
    let candidates = std::env::var_os("CHROMIUM")
        .map(PathBuf::from)
        .into_iter()
        .chain(
            [
                "/usr/bin/chromium",
                "/usr/bin/chromium-browser",
                "/usr/bin/google-chrome",
            ]
            .map(PathBuf::from),
        );
    candidates.into_iter().find(|p| p.is_file())
}

fn chromium(browser: &Path, profile: &Path, args: &[&str]) -> std::process::Output {
    Command::new(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .args(args)
        .output()
        .expect("the browser starts")
}

#[test]
fn in_a_real_browser_the_page_renders_mathml_and_a_click_scrolls_to_the_claim() {
    let Some(browser) = browser() else {
        eprintln!(
            "skipped: no Chromium found (/usr/bin/chromium, or set CHROMIUM); \
             `apt-get install chromium` runs this test (.ci/run installs it)"
        );
        return;
    };
    let (html, claims, _) = page();
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/html-test");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("report.html");
    std::fs::write(&file, &html).unwrap();
    let url = format!("file://{}", file.display());
    let dom = chromium(
        &browser,
        &dir.join("profile"),
        &[
            "--virtual-time-budget=30000",
            "--dump-dom",
            &format!("{url}?selftest"),
        ],
    );
    let dom = String::from_utf8_lossy(&dom.stdout);
    let start = dom.find("<pre id=\"selftest\">").unwrap_or_else(|| {
        panic!(
            "the page's self-test did not finish:\n{}",
            &dom[..dom.len().min(500)]
        )
    });
    let json = &dom[start + "<pre id=\"selftest\">".len()..];
    let json = &json[..json.find("</pre>").unwrap()];
    let result: serde_json::Value = serde_json::from_str(&json.replace("&quot;", "\"")).unwrap();
    assert_eq!(result["nodes"], claims, "{result}");
    assert_eq!(result["claims"], claims, "{result}");
    assert!(
        result["math"].as_u64().unwrap() >= claims as u64 / 2,
        "{result}"
    );
    assert_eq!(result["unrendered"], 0, "{result}");
    assert_eq!(
        result["raw_latex_outside_code"],
        serde_json::json!([]),
        "{result}"
    );
    assert_eq!(result["clicks"], claims, "{result}");
    assert_eq!(
        result["scrolled"], claims,
        "clicks that did not scroll to the claim: {result}"
    );
    assert_eq!(result["focused"], claims, "{result}");
    let shot = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/html-report.png");
    let _ = std::fs::remove_file(&shot);
    chromium(
        &browser,
        &dir.join("profile"),
        &[
            "--window-size=1280,1800",
            &format!("--screenshot={}", shot.display()),
            &url,
        ],
    );
    assert!(shot.is_file(), "no screenshot");
}
