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

/// For every claim of the paper, how many claims it rests on (transitively through
/// `uses`) and how many rest on it.
fn closures() -> Vec<(String, usize, usize)> {
    let files: Vec<DerivationFile> =
        load_dir(&Path::new(env!("CARGO_MANIFEST_DIR")).join("derivations")).unwrap();
    let claims: Vec<_> = files.iter().flat_map(|f| f.claims.iter()).collect();
    let ids: Vec<&str> = claims.iter().map(|c| c.id.as_str()).collect();
    let uses: Vec<Vec<usize>> = claims
        .iter()
        .map(|c| {
            c.uses
                .iter()
                .filter_map(|u| ids.iter().position(|i| *i == u.id))
                .collect()
        })
        .collect();
    let reach = |start: usize, next: &dyn Fn(usize) -> Vec<usize>| {
        let mut seen = std::collections::BTreeSet::new();
        let mut stack = next(start);
        while let Some(j) = stack.pop() {
            if seen.insert(j) {
                stack.extend(next(j));
            }
        }
        seen.remove(&start);
        seen.len()
    };
    let up = |k: usize| uses[k].clone();
    let down = |k: usize| {
        (0..claims.len())
            .filter(|&j| uses[j].contains(&k))
            .collect()
    };
    (0..claims.len())
        .map(|k| (ids[k].to_owned(), reach(k, &up), reach(k, &down)))
        .collect()
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

/// Chromium's output, each run killed after 45 s (a page that waits on the network
/// would otherwise hold the test forever; these pages finish in a few seconds). One
/// browser runs at a time: two started together on a loaded machine have left one
/// with no output at all. Headless Chromium also hangs now and then with
/// `--virtual-time-budget` and prints nothing: a run that printed nothing is the
/// browser's failure, not the page's, and is run again, up to three times in all.
fn chromium(browser: &Path, profile: &Path, args: &[&str]) -> std::process::Output {
    static ONE_AT_A_TIME: std::sync::Mutex<()> = std::sync::Mutex::new(());
    let _turn = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let screenshot = args.iter().any(|a| a.starts_with("--screenshot"));
    // A fresh profile for every run: a killed browser may leave its lock behind.
    let run = |attempt: usize| {
        let profile = profile.with_extension(attempt.to_string());
        let _ = std::fs::remove_dir_all(&profile);
        chromium_once(browser, &profile, args)
    };
    let mut out = run(0);
    for attempt in 1..3 {
        if !out.stdout.is_empty() || screenshot {
            break;
        }
        out = run(attempt);
    }
    out
}

fn chromium_once(browser: &Path, profile: &Path, args: &[&str]) -> std::process::Output {
    let mut child = Command::new(browser)
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
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::null())
        .spawn()
        .expect("the browser starts");
    let stdout = child.stdout.take().expect("piped");
    let reader = std::thread::spawn(move || {
        let mut out = Vec::new();
        let _ = std::io::Read::read_to_end(&mut { stdout }, &mut out);
        out
    });
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(45);
    while child.try_wait().ok().flatten().is_none() && std::time::Instant::now() < deadline {
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    let _ = child.kill();
    let status = child.wait().expect("the browser is waited for");
    std::process::Output {
        status,
        stdout: reader.join().unwrap_or_default(),
        stderr: Vec::new(),
    }
}

#[test]
fn in_a_real_browser_the_page_renders_mathml_and_a_click_scrolls_to_the_claim() {
    let Some(browser) = browser() else {
        crate::common::tool_missing(
            "Chromium (/usr/bin/chromium, or set CHROMIUM; `apt-get install chromium`)",
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
        result["overflowing"],
        serde_json::json!([]),
        "cards whose content sticks out: {result}"
    );
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
    // The focus counts every claim a claim rests on and every one resting on it, as
    // the page's script follows the direct `uses` it carries.
    for (id, u, d) in closures() {
        let note = result["notes"][id.as_str()].as_str().unwrap_or_default();
        let want = format!("{u} claim(s) it rests on and {d} that rest on it");
        assert!(note.contains(&want), "{id}: {note} (want {want})");
    }
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

/// The tags of `html` (`<name …>`), for checking what markup a page carries.
fn tags(html: &str) -> Vec<&str> {
    html.match_indices('<')
        .filter_map(|(k, _)| {
            let rest = &html[k + 1..];
            rest.starts_with(|c: char| c.is_ascii_alphabetic())
                .then(|| &rest[..rest.find('>').unwrap_or(rest.len())])
        })
        .collect()
}

/// A page made from `tests/hostile/report.toml`, whose every text field carries
/// markup: a script, an image with an error handler, a style hiding failures, an
/// iframe and images fetching from `port`.
fn hostile_page(port: u16) -> String {
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/hostile/report.toml"),
    )
    .unwrap()
    .replace("PORT", &port.to_string());
    let file = cosserat_check::derivation::load_str("report.toml", &text).unwrap();
    let rows = decide_all(std::slice::from_ref(&file), None).unwrap();
    let refs: Vec<_> = rows.iter().collect();
    report::html::render(&refs, &report::paper_of(&refs, &[]))
}

#[test]
fn markup_from_a_hostile_file_stays_text() {
    let html = hostile_page(9);
    let tags = tags(&html);
    let named = |name: &str| {
        tags.iter()
            .filter(|t| t.split([' ', '/']).next() == Some(name))
            .count()
    };
    // The page's own style and script, and nothing else of the kind.
    assert_eq!((named("script"), named("style")), (1, 1));
    for name in [
        "img",
        "iframe",
        "svg onload",
        "link",
        "object",
        "embed",
        "base",
    ] {
        assert_eq!(named(name), 0, "{name}");
    }
    let handlers: Vec<&&str> = tags
        .iter()
        .filter(|t| t.split_whitespace().skip(1).any(|a| a.starts_with("on")))
        .collect();
    assert!(handlers.is_empty(), "{handlers:?}");
    assert!(!html.contains("href=\"javascript"));
    // Shown as text instead.
    assert!(
        html.contains("&lt;img src=x onerror="),
        "the payload is shown"
    );
    assert!(html.contains("Content-Security-Policy"));
}

#[test]
fn in_a_real_browser_a_hostile_page_runs_nothing_fetches_nothing_and_shows_every_failure() {
    let Some(browser) = browser() else {
        crate::common::tool_missing("Chromium (see the test above)");
        return;
    };
    // A server that answers every request at once (so that a page that does make one
    // finishes loading) and remembers that it came.
    let listener = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let port = listener.local_addr().unwrap().port();
    let requested = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
    let seen = requested.clone();
    std::thread::spawn(move || {
        for stream in listener.incoming() {
            seen.store(true, std::sync::atomic::Ordering::SeqCst);
            if let Ok(mut s) = stream {
                use std::io::Write;
                let _ = s.write_all(b"HTTP/1.0 204 No Content\r\n\r\n");
            }
        }
    });
    let html = hostile_page(port);
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/html-hostile");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("report.html");
    std::fs::write(&file, &html).unwrap();
    let dom = chromium(
        &browser,
        &dir.join("profile"),
        &[
            "--virtual-time-budget=10000",
            "--dump-dom",
            &format!("file://{}?selftest", file.display()),
        ],
    );
    let dom = String::from_utf8_lossy(&dom.stdout);
    let start = dom
        .find("<pre id=\"selftest\">")
        .unwrap_or_else(|| panic!("the page's own script did not run:\n{dom}"));
    let json = &dom[start + "<pre id=\"selftest\">".len()..];
    let json = &json[..json.find("</pre>").unwrap()];
    let result: serde_json::Value = serde_json::from_str(&json.replace("&quot;", "\"")).unwrap();
    assert_eq!(result["pwned"], 0, "an author's script ran: {result}");
    assert_eq!(result["failing"], 3, "{result}");
    assert_eq!(
        result["failing_visible"], 3,
        "a failure is hidden: {result}"
    );
    assert!(
        !requested.load(std::sync::atomic::Ordering::SeqCst),
        "the page made a request"
    );
}

/// A `uses` chain of 2,000 claims: the page carries each claim's direct neighbours
/// only, so it grows linearly (it listed every ancestor of every node, quadratic).
#[test]
fn a_long_uses_chain_makes_a_page_linear_in_its_length() {
    let n = 2_000;
    let mut text =
        String::from("section = \"c\"\ntitle = \"chain\"\ndimension = 2\nscalars = [\"x\"]\n");
    for k in 0..n {
        let uses = if k > 0 {
            format!("uses = [\"c{}\"]\n", k - 1)
        } else {
            String::new()
        };
        text.push_str(&format!(
            "[[claim]]\nid = \"c{k}\"\nprinted = 'x = x'\n{uses}expect = \"holds\"\nsides = [\"x\", \"x\"]\n"
        ));
    }
    let file = cosserat_check::derivation::load_str("chain.toml", &text).unwrap();
    let rows = decide_all(std::slice::from_ref(&file), None).unwrap();
    let refs: Vec<_> = rows.iter().collect();
    let html = report::html::render(&refs, "chain");
    assert!(
        html.len() < 1_500 * n,
        "{} bytes for {n} claims",
        html.len()
    );
}
