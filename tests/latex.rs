//! The LaTeX table and errata compile with pdflatex in a plain `article` (portrait, the
//! default margins) with no overfull box: statements are scaled to their column when
//! wider, long evidence sits in a second table, and sums break at their signs. Skipped,
//! saying so, when pdflatex is not installed (`.ci/run` installs it).

use std::path::Path;
use std::process::Command;

fn compile(args: &[&str], name: &str) {
    if Command::new("pdflatex").arg("--version").output().is_err() {
        eprintln!("skipped: pdflatex is not installed (apt-get install texlive-latex-base)");
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
}

#[test]
fn the_table_fits_a_portrait_page() {
    compile(&["check"], "table");
}

#[test]
fn the_errata_fit_a_portrait_page() {
    compile(&["errata"], "errata");
}
