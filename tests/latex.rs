//! The LaTeX table and errata compile with pdflatex in a plain `article` (portrait, the
//! default margins) with no overfull box: statements are scaled to their column when
//! wider, long evidence sits in a second table, and sums break at their signs. Skipped,
//! saying so, when pdflatex is not installed, unless `COSSERAT_REQUIRE_TOOLS` is set
//! (`.ci/run` installs it and sets it).

use std::path::Path;
use std::process::Command;

fn compile(args: &[&str], name: &str) {
    if Command::new("pdflatex").arg("--version").output().is_err() {
        crate::common::tool_missing("pdflatex (apt-get install texlive-latex-base)");
        return;
    }
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/latex-test");
    std::fs::create_dir_all(&dir).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_cosserat-check"))
        .args(args)
        .args(["--format", "latex", "--standalone"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0));
    std::fs::write(dir.join(format!("{name}.tex")), &out.stdout).unwrap();
    // Twice, so that longtable settles its column widths.
    for _ in 0..2 {
        Command::new("pdflatex")
            .args([
                "-interaction=nonstopmode",
                "-halt-on-error",
                &format!("{name}.tex"),
            ])
            .current_dir(&dir)
            .output()
            .unwrap();
    }
    let log = std::fs::read_to_string(dir.join(format!("{name}.log"))).unwrap();
    let errors: Vec<&str> = log.lines().filter(|l| l.starts_with("! ")).collect();
    assert!(errors.is_empty(), "{name}: {errors:?}");
    let overfull: Vec<&str> = log.lines().filter(|l| l.starts_with("Overfull")).collect();
    assert!(overfull.is_empty(), "{name}: {overfull:#?}");
    assert!(dir.join(format!("{name}.pdf")).is_file());
    // What a reader sees names no macro, except one the report quotes on purpose as
    // code (`\texttt{\textbackslash overline}` in a reading's reason): every other
    // command was typeset, none printed.
    let Some(txt) = pdf_text(&dir, name) else {
        return;
    };
    let quoted = quoted_macros(&String::from_utf8_lossy(&out.stdout));
    let leaked: Vec<String> = macro_names(&txt)
        .into_iter()
        .filter(|m| !quoted.contains(m))
        .collect();
    assert!(
        leaked.is_empty(),
        "{name}: macro names in the text: {leaked:?}"
    );
}

/// The text of `dir/name.pdf` as a reader sees it (`pdftotext`), or `None`, said, when
/// the tool is missing.
fn pdf_text(dir: &Path, name: &str) -> Option<String> {
    if Command::new("pdftotext").arg("-v").output().is_err() {
        crate::common::tool_missing("pdftotext (apt-get install poppler-utils)");
        return None;
    }
    let txt = Command::new("pdftotext")
        .args([&format!("{name}.pdf"), "-"])
        .current_dir(dir)
        .output()
        .unwrap();
    Some(String::from_utf8_lossy(&txt.stdout).into_owned())
}

/// The names after a backslash in `text` (`\overline` gives `overline`).
fn macro_names(text: &str) -> Vec<String> {
    text.split('\\')
        .skip(1)
        .map(|rest| {
            rest.chars()
                .take_while(char::is_ascii_alphabetic)
                .collect::<String>()
        })
        .filter(|n| !n.is_empty())
        .collect()
}

/// The macro names a `.tex` source quotes as code: `\textbackslash NAME` inside
/// `\texttt{…}`.
fn quoted_macros(tex: &str) -> Vec<String> {
    let mut out = Vec::new();
    for part in tex.split("\\texttt{").skip(1) {
        let mut depth = 1;
        let end = part
            .char_indices()
            .find(|&(_, c)| {
                depth += match c {
                    '{' => 1,
                    '}' => -1,
                    _ => 0,
                };
                depth == 0
            })
            .map_or(part.len(), |(i, _)| i);
        for q in part[..end].split("\\textbackslash").skip(1) {
            let q = q.trim_start_matches("{}").trim_start();
            let n: String = q.chars().take_while(char::is_ascii_alphabetic).collect();
            if !n.is_empty() {
                out.push(n);
            }
        }
    }
    out
}

#[test]
fn the_table_fits_a_portrait_page() {
    compile(&["check"], "table");
}

#[test]
fn the_errata_fit_a_portrait_page() {
    compile(&["errata"], "errata");
}

/// A report made from `tests/hostile/report.toml`, whose statements, notes, reasons
/// and titles carry TeX that reads a file (`\input{/etc/passwd}`), writes one
/// (`\openout`), and closes the table and the document early. Compiled with a default
/// pdflatex, it must neither read nor write a file other than its own, and the PDF must
/// show every claim and the summary (checked with `pdftotext` when it is installed).
#[test]
fn a_hostile_report_reads_and_writes_nothing_and_shows_every_claim() {
    if Command::new("pdflatex").arg("--version").output().is_err() {
        crate::common::tool_missing("pdflatex (apt-get install texlive-latex-base)");
        return;
    }
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/latex-hostile");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/hostile/report.toml"),
    )
    .unwrap()
    .replace("PORT", "9");
    std::fs::write(dir.join("report.toml"), text).unwrap();
    for (name, command) in [("table", "verify"), ("errata", "errata")] {
        let mut args = vec![command, "report.toml", "--format", "latex", "--standalone"];
        if command == "errata" {
            args = vec![command, "--dir", ".", "--format", "latex", "--standalone"];
        }
        let out = Command::new(env!("CARGO_BIN_EXE_cosserat-check"))
            .args(&args)
            .current_dir(&dir)
            .output()
            .unwrap();
        assert!(out.status.code().is_some_and(|c| c <= 1), "{out:?}");
        std::fs::write(dir.join(format!("{name}.tex")), &out.stdout).unwrap();
        let compiled = Command::new("pdflatex")
            .args([
                "-interaction=nonstopmode",
                "-recorder",
                &format!("{name}.tex"),
            ])
            .current_dir(&dir)
            .output()
            .unwrap();
        // -recorder lists every file TeX opened: only its own and TeX Live's.
        let fls = std::fs::read_to_string(dir.join(format!("{name}.fls"))).unwrap();
        for line in fls.lines() {
            let path = line.split_once(' ').map_or("", |(_, p)| p);
            // TeX Live's own files, and its font cache (~/.texlive*/texmf-var).
            let own = path.starts_with("/usr/") || path.contains("/texmf");
            let here = !path.starts_with('/') || path.starts_with(dir.to_str().unwrap());
            assert!(own || here, "{name}: TeX opened {line}");
            assert!(
                !path.contains("passwd") && !path.contains("pwned"),
                "{name}: {line}"
            );
        }
        assert!(!dir.join("pwned.txt").exists() && !dir.join("pwned.tex").exists());
        assert!(
            dir.join(format!("{name}.pdf")).is_file(),
            "{name}: {}",
            String::from_utf8_lossy(&compiled.stdout)
        );
        let Some(txt) = pdf_text(&dir, name) else {
            continue;
        };
        assert!(
            !txt.contains("root:"),
            "{name}: the password file is in the PDF"
        );
        let ids: &[&str] = if name == "table" {
            &["op", "tex", "href", "quotes"]
        } else {
            &["op", "tex", "quotes"]
        };
        for id in ids {
            assert!(txt.contains(id), "{name}: claim {id} is missing:\n{txt}");
        }
        if name == "table" {
            assert!(
                txt.contains("3 fail"),
                "{name}: the summary is missing:\n{txt}"
            );
        }
    }
}
