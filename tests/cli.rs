//! The command line end to end: exit codes 0/1/2, formats, `--only`, and located
//! diagnostics for malformed input.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn bin() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_cosserat-check"));
    c.current_dir(env!("CARGO_MANIFEST_DIR"));
    c
}

fn run(args: &[&str]) -> Output {
    bin().args(args).output().expect("the binary runs")
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

/// A fresh directory holding one derivation file.
fn dir_with(name: &str, contents: &str) -> PathBuf {
    let dir =
        std::env::temp_dir().join(format!("cosserat-check-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("claims.toml"), contents).unwrap();
    dir
}

const HEADER: &str =
    "section = \"t\"\ntitle = \"test\"\ndimension = 3\nnormal = \"n\"\ntensors = [\"sigma_ij\"]\n";

#[test]
fn no_arguments_checks_the_paper_and_prints_markdown() {
    let out = run(&[]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    assert!(stdout.starts_with("# Derivation table"));
    assert!(stdout.contains("| eq33 | 3.4 |"));
    assert!(stdout.contains("0 unexpected."));
}

#[test]
fn json_format_and_only() {
    let out = run(&["check", "--format", "json", "--only", "eq26"]);
    assert_eq!(out.status.code(), Some(0));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let claims = v["claims"].as_array().unwrap();
    assert_eq!(claims.len(), 1);
    assert_eq!(claims[0]["verdict"], "fails");
    assert_eq!(claims[0]["correction"]["verdict"], "holds");
    assert_eq!(claims[0]["counterexample"]["lhs_value"], "1/5");
}

/// `--only` reads the claim's file and the files of the claims it uses (a failure is
/// attributed through them), not the others: an unrelated file's bad expression does
/// not stop it, while a whole run reports that file with exit 2.
#[test]
fn only_reads_the_files_the_claim_needs() {
    let dir = dir_with(
        "only",
        &format!("{HEADER}[[claim]]\nid = \"wrong\"\nprinted = 'x'\nuses = [\"base\"]\nexpect = \"fails\"\nreason = \"r\"\nsides = [\"avg(n_i n_j)\", \"1/2 delta_ij\"]\n[[claim]]\nid = \"beside\"\nprinted = 'x'\nuses = [\"other\"]\nexpect = \"holds\"\nsides = [\"1\", \"1\"]\n"),
    );
    std::fs::write(
        dir.join("base.toml"),
        format!("{HEADER}[[claim]]\nid = \"base\"\nprinted = 'x'\nexpect = \"fails\"\nreason = \"r\"\nsides = [\"1\", \"2\"]\n"),
    )
    .unwrap();
    std::fs::write(
        dir.join("other.toml"),
        format!("{HEADER}[[claim]]\nid = \"other\"\nprinted = 'x'\nexpect = \"holds\"\nsides = [\"sigma_ii_\", \"0\"]\n"),
    )
    .unwrap();
    let d = dir.to_str().unwrap();
    let whole = run(&["check", "--dir", d]);
    assert_eq!(whole.status.code(), Some(2));
    assert!(
        text(&whole.stderr).contains("other.toml"),
        "{}",
        text(&whole.stderr)
    );
    let out = run(&["check", "--dir", d, "--only", "wrong", "--format", "json"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let claims = v["claims"].as_array().unwrap();
    assert_eq!(claims.len(), 1);
    assert_eq!(claims[0]["verdict"], "fails");
    // base.toml was read: `uses = ["base"]` names a claim of the files read (without
    // it, a warning says the edge is not followed). other.toml was not, but its claim
    // `other`, which `beside` uses, is known from its outline: no warning either, as
    // in a whole run.
    assert!(text(&out.stderr).is_empty(), "{}", text(&out.stderr));
    std::fs::remove_file(dir.join("base.toml")).unwrap();
    let out = run(&["check", "--dir", d, "--only", "wrong"]);
    assert!(
        text(&out.stderr).contains("`base` is no claim of the files read"),
        "{}",
        text(&out.stderr)
    );
    // An id no file holds: every file is read, and the whole run's error is reported.
    let out = run(&["check", "--dir", d, "--only", "nowhere"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        text(&out.stderr).contains("other.toml"),
        "{}",
        text(&out.stderr)
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn unknown_id_is_an_input_error() {
    let out = run(&["check", "--only", "eq999"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("no claim has id `eq999`"));
    assert!(out.stdout.is_empty());
}

#[test]
fn an_unexpected_verdict_exits_1() {
    let dir = dir_with(
        "unexpected",
        &format!("{HEADER}[[claim]]\nid = \"wrong\"\nprinted = 'x'\nexpect = \"holds\"\nsides = [\"avg(n_i n_j)\", \"1/2 delta_ij\"]\n"),
    );
    let out = run(&["check", "--dir", dir.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let stdout = text(&out.stdout);
    assert!(stdout.contains("**fails ✗ (declared: holds)**"), "{stdout}");
    assert!(stdout.contains("1 unexpected."));
}

#[test]
fn a_claim_without_expect_is_reported_as_found_and_strict_reads_it_as_holds() {
    let claim = |id: &str, right: &str| {
        format!(
            "[[claim]]\nid = \"{id}\"\nprinted = 'x'\nsides = [\"avg(n_i n_j)\", \"{right}\"]\n"
        )
    };
    let holds = dir_with(
        "found-holds",
        &format!("{HEADER}{}", claim("right", "1/3 delta_ij")),
    );
    let file = |d: &PathBuf| d.join("claims.toml").to_str().unwrap().to_owned();
    let out = run(&["verify", &file(&holds)]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    assert!(stdout.contains("| right | t |"), "{stdout}");
    assert!(
        stdout.contains("0 unexpected (1 without a declared verdict, reported as found)."),
        "{stdout}"
    );
    let fails = dir_with(
        "found-fails",
        &format!("{HEADER}{}", claim("wrong", "1/2 delta_ij")),
    );
    let out = run(&["verify", &file(&fails)]);
    // Reported as found, never as unexpected; the exit status still says it fails.
    assert_eq!(out.status.code(), Some(1));
    let stdout = text(&out.stdout);
    assert!(stdout.contains("| **fails** |"), "{stdout}");
    assert!(!stdout.contains("✗"), "{stdout}");
    let json = text(&run(&["verify", &file(&fails), "--format", "json"]).stdout);
    let report: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert!(report["claims"][0]["expected"].is_null());
    let out = run(&["verify", "--strict", &file(&fails)]);
    assert_eq!(out.status.code(), Some(1));
    let stdout = text(&out.stdout);
    assert!(stdout.contains("**fails ✗ (declared: holds)**"), "{stdout}");
    assert!(stdout.contains("1 unexpected."), "{stdout}");
}

#[test]
fn malformed_input_exits_2_with_a_located_caret() {
    let dir = dir_with(
        "malformed",
        &format!("{HEADER}[[claim]]\nid = \"bad\"\nprinted = 'x'\nexpect = \"holds\"\nsides = [\"sigma_ki n_k n_k\", \"0\"]\n"),
    );
    let out = run(&["check", "--dir", dir.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(out.stdout.is_empty());
    let stderr = text(&out.stderr);
    let file = Path::new(&dir).join("claims.toml");
    assert!(
        stderr.contains(&format!("{}:10:26", file.display())),
        "{stderr}"
    );
    assert!(
        stderr.contains("index `k` occurs 3 times in one product"),
        "{stderr}"
    );
    assert!(
        stderr.contains(&format!("   | {}^\n", " ".repeat(25))),
        "{stderr}"
    );
}

#[test]
fn missing_directory_and_bad_flags_exit_2() {
    let out = run(&["check", "--dir", "/nonexistent/cosserat"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("cannot read /nonexistent/cosserat"));
    let out = run(&["check", "--format", "pdf"]);
    assert_eq!(out.status.code(), Some(2));
}

#[test]
fn help_documents_every_option() {
    let out = run(&["check", "--help"]);
    assert_eq!(out.status.code(), Some(0));
    let help = text(&out.stdout);
    for word in ["--format", "--only", "--dir", "markdown", "json"] {
        assert!(help.contains(word), "--help lacks {word}");
    }
    let top = text(&run(&["--help"]).stdout);
    assert!(top.contains("Exit status"));
}

#[test]
fn every_format_renders_the_full_table() {
    for (format, marker) in [
        ("markdown", "| eq33 | 3.4 |"),
        ("latex", "eq33 (\\S{}3.4) &"),
        ("html", "id=\"claim-eq33\""),
        ("json", "\"id\": \"eq33\""),
        ("csv", "\"eq33\",\"3.4\""),
    ] {
        let out = run(&["check", "--format", format]);
        assert_eq!(
            out.status.code(),
            Some(0),
            "{format}: {}",
            text(&out.stderr)
        );
        let stdout = text(&out.stdout);
        assert!(stdout.contains(marker), "{format} lacks {marker}");
        // Quiet when stderr is not a terminal.
        assert!(out.stderr.is_empty(), "{format}: {}", text(&out.stderr));
    }
    let latex = text(&run(&["check", "--format", "latex", "--standalone"]).stdout);
    assert!(latex.starts_with("\\documentclass"));
    assert!(latex.trim_end().ends_with("\\end{document}"));
    assert!(latex.is_ascii(), "LaTeX output must be ASCII for pdflatex");
    assert!(
        !latex.contains("\\textbf{?}"),
        "a character has no LaTeX transliteration"
    );
}

#[test]
fn out_writes_a_file_and_nothing_on_error() {
    let dir = std::env::temp_dir().join(format!("cosserat-check-out-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("table.csv");
    let out = run(&[
        "check",
        "--format",
        "csv",
        "--only",
        "eq25",
        "--out",
        file.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0));
    assert!(out.stdout.is_empty());
    assert!(std::fs::read_to_string(&file).unwrap().contains("\"eq25\""));
    // A failing run leaves no file behind.
    let missing = dir.join("never.csv");
    let out = run(&[
        "check",
        "--only",
        "nope",
        "--out",
        missing.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(!missing.exists());
}

#[test]
fn errata_lists_the_failing_statements_with_corrections() {
    let out = run(&["errata"]);
    assert_eq!(out.status.code(), Some(0));
    let s = text(&out.stdout);
    for id in [
        "## eq26",
        "## eq31",
        "## eq21",
        "## eq23",
        "## eq24",
        "## sec5-f2-dominates-f1",
    ] {
        assert!(s.contains(id), "errata lack {id}");
    }
    assert!(!s.contains("## eq33"), "a holding claim is not an erratum");
    assert!(s.contains("- Correction: $\\langle n_i n_j n_k n_l \\rangle = \\frac{1}{15}"));
    let latex = text(&run(&["errata", "--format", "latex"]).stdout);
    assert!(latex.contains("\\begin{itemize}") && latex.is_ascii());
}

#[test]
fn explain_shows_expansions_and_samples() {
    let out = run(&["explain", "eq33"]);
    assert_eq!(out.status.code(), Some(0));
    let s = text(&out.stdout);
    assert!(s.contains("Definitions used:"));
    assert!(s.contains("Chain 1, side 2: 4/15 s_ij s_ij - 1/15 s_ij s_ji"));
    assert!(s.contains("= 2/15*sigma_11^2"));
    let s = text(&run(&["explain", "eq47"]).stdout);
    assert!(s.contains("First 3 sampled states:"), "{s}");
    let s = text(&run(&["explain", "eq26"]).stdout);
    assert!(s.contains("## Correction") && s.contains("Counterexample:"));
    assert_eq!(run(&["explain", "nope"]).status.code(), Some(2));
}

#[test]
fn verify_checks_the_documented_example() {
    let out = run(&["verify", "derivations/examples/textbook.toml"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let s = text(&out.stdout);
    assert!(s.contains("Worked examples"));
    assert!(s.contains("| epsilon-delta | examples |"));
    assert!(s.contains("6 claims: 5 hold, 1 fail, 0 conditional; 0 unexpected."));
    // --seed and --samples reach the numeric claims and change only their evidence.
    let a = text(
        &run(&[
            "verify",
            "derivations/examples/textbook.toml",
            "--only",
            "cauchy-schwarz",
            "--seed",
            "7",
            "--samples",
            "60",
        ])
        .stdout,
    );
    assert!(a.contains("60 samples (seed 7)"), "{a}");
    let b = text(
        &run(&[
            "verify",
            "derivations/examples/textbook.toml",
            "--only",
            "cauchy-schwarz",
            "--seed",
            "7",
            "--samples",
            "60",
        ])
        .stdout,
    );
    assert_eq!(a, b, "same seed, same output");
    assert_eq!(
        run(&[
            "verify",
            "derivations/examples/textbook.toml",
            "--samples",
            "3"
        ])
        .status
        .code(),
        Some(2)
    );
    assert_eq!(run(&["verify"]).status.code(), Some(2));
}

#[test]
fn every_subcommand_has_complete_help() {
    for (cmd, words) in [
        (
            "check",
            &[
                "--format",
                "--standalone",
                "--out",
                "--only",
                "--seed",
                "--samples",
                "--dir",
            ][..],
        ),
        ("errata", &["--format", "--out", "--dir"][..]),
        ("explain", &["<ID>", "--dir", "--file"][..]),
        (
            "plot",
            &[
                "<FILE>", "--figure", "--y", "--x", "--set", "--given", "--format", "--out",
            ][..],
        ),
        (
            "verify",
            &[
                "<FILE>",
                "--format",
                "--only",
                "--seed",
                "--samples",
                "--out",
                "--color",
            ][..],
        ),
        ("examples", &["--out"][..]),
        ("completions", &["<SHELL>", "bash", "zsh", "fish"][..]),
        ("manpage", &[][..]),
        ("guide", &[][..]),
    ] {
        let out = run(&[cmd, "--help"]);
        assert_eq!(out.status.code(), Some(0));
        let help = text(&out.stdout);
        for w in words {
            assert!(help.contains(w), "`{cmd} --help` lacks {w}");
        }
    }
}

const APPENDIX: &str = "derivations/A-3-shear-band.toml";

#[test]
fn plot_draws_the_paper_figure_as_a_table_and_a_picture() {
    let csv = run(&["plot", APPENDIX, "--figure", "fig6"]);
    assert_eq!(csv.status.code(), Some(0), "{}", text(&csv.stderr));
    let table = text(&csv.stdout);
    let lines: Vec<&str> = table.lines().collect();
    assert_eq!(
        lines[0],
        "f_r,(54) as printed,\"derived, ν = 0\",\"derived, ν = 0.25\",\"derived, ν = 0.45\""
    );
    assert_eq!(lines.len(), 61, "60 grid points and a header");
    for (k, line) in lines[1..].iter().enumerate() {
        let cells: Vec<&str> = line.split(',').collect();
        assert_eq!(cells.len(), 5, "{line}");
        // The grid value as written (k/20 in its shortest decimal).
        assert_eq!(cells[0], format!("{}", (k + 1) as f64 / 20.0), "{line}");
        for c in &cells[1..] {
            let digits = c.chars().filter(char::is_ascii_digit).count();
            assert!(digits >= 8, "too few significant digits in {c}");
            assert!(c.parse::<f64>().is_ok_and(|v| v > 0.0), "{c}");
        }
    }
    // (54) at f_r = 0.05 and the derived curve at ν = 0.45 there, as the float route
    // gives them (tests/appendix.rs compares every point).
    assert!(lines[1].starts_with("0.05,15.8259162489,"), "{}", lines[1]);
    assert!(lines[1].ends_with(",66.122876145"), "{}", lines[1]);
    assert_eq!(
        run(&["plot", APPENDIX, "--figure", "fig6"]).stdout,
        csv.stdout
    );

    let dir = std::env::temp_dir().join(format!("cosserat-check-plot-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let svg_path = dir.join("fig6.svg");
    let args = ["plot", APPENDIX, "--figure", "fig6", "--format", "svg"];
    let svg = run(&[&args[..], &["--out", svg_path.to_str().unwrap()]].concat());
    assert_eq!(svg.status.code(), Some(0), "{}", text(&svg.stderr));
    assert!(svg.stdout.is_empty());
    let picture = std::fs::read_to_string(&svg_path).unwrap();
    assert!(picture.starts_with("<svg") && picture.contains("width=\"85mm\""));
    // Labels as mathematics: italic letters, subscripts, ν.
    assert!(picture.contains("<tspan font-style=\"italic\">d</tspan><tspan baseline-shift=\"sub\" font-size=\"75%\"><tspan font-style=\"italic\">B</tspan></tspan>"));
    assert!(picture.contains("<tspan font-style=\"italic\">ν</tspan> = 0.45"));
    // Each curve and its legend mark, in its own colour and dash pattern.
    for (colour, dash) in [
        ("#000000", ""),
        ("#E69F00", " stroke-dasharray=\"6 3\""),
        ("#0072B2", " stroke-dasharray=\"2 2\""),
        ("#009E73", " stroke-dasharray=\"8 3 2 3\""),
    ] {
        let marker = format!("stroke=\"{colour}\" stroke-width=\"1.2\"{dash}/>");
        assert_eq!(
            picture.matches(&marker).count(),
            2,
            "curve and legend in {colour}"
        );
    }
    // Both axes have round ends, labelled ticks and minor ticks: the x axis starts at
    // 0 (the grid at 0.05), the log y axis runs from 2 to 100 labelled 2, 5, 10, 20, 50.
    let labels: Vec<&str> = picture
        .split("text-anchor=\"middle\">")
        .skip(1)
        .map(|rest| rest.split('<').next().unwrap())
        .collect();
    assert!(labels.starts_with(&["0", "1", "2", "3"]), "{labels:?}");
    for y in ["2", "5", "10", "20", "50", "100"] {
        assert!(
            picture.contains(&format!("text-anchor=\"end\">{y}</text>")),
            "no y label {y}"
        );
    }
    assert!(
        picture.matches("stroke-width=\"0.4\"/>").count() >= 20,
        "minor ticks"
    );
    // The minimum of (54), inside the range, is marked on the curve and in the legend,
    // and the legend sits in a corner of the axes that no curve crosses.
    assert!(
        picture.contains("(54) as printed; min. ≈ 2.597 at"),
        "{picture}"
    );
    assert_eq!(picture.matches("<circle").count(), 2, "curve and legend");
    assert!(
        picture.contains("fill=\"white\" stroke=\"#999\""),
        "a legend box inside the axes"
    );
    // A linear axis when asked.
    let linear = text(&run(&[&args[..], &["--linear"]].concat()).stdout);
    assert!(linear.contains("text-anchor=\"end\">40</text>"), "{linear}");
    // Coordinates are not rounded to whole units: the curves' points carry fractions.
    let points: Vec<f64> = picture
        .split("points=\"")
        .skip(1)
        .flat_map(|rest| rest.split('"').next().unwrap().split([' ', ',']))
        .map(|c| c.parse::<f64>().unwrap())
        .collect();
    assert!(points.len() > 400, "{} coordinates", points.len());
    let fractional = points.iter().filter(|c| c.fract() != 0.0).count();
    assert!(
        fractional > points.len() / 2,
        "{fractional} of {} coordinates have a fraction",
        points.len()
    );
    assert_eq!(run(&args).stdout, picture.as_bytes());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn plot_takes_curves_from_the_command_line() {
    let out = run(&[
        "plot",
        APPENDIX,
        "--y",
        "A2eq54, 1 / A2eq54",
        "--x",
        "f_r=1..2:0.5",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    // By hand: (54) at f_r = 1 is 48/33, at 3/2 it is 198/140.5, at 2 it is 576/417.
    assert_eq!(
        text(&out.stdout),
        "f_r,A2eq54,1 / A2eq54\n1,1.45454545455,0.6875\n1.5,1.40925266904,0.709595959596\n2,1.38129496403,0.723958333333\n"
    );
}

#[test]
fn plot_refuses_bad_input_with_exit_2_and_writes_nothing() {
    let dir = std::env::temp_dir().join(format!("cosserat-check-plot-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let target = dir.join("out.svg");
    let t = target.to_str().unwrap();
    let cases: [(&[&str], &str); 8] = [
        (
            &[
                "plot", APPENDIX, "--y", "A2", "--x", "u=0..1", "--set", "u=1", "--out", t,
            ],
            "`u` is the figure's parameter; an assumption cannot fix it",
        ),
        (
            &[
                "plot",
                APPENDIX,
                "--y",
                "A2eq54",
                "--x",
                "f_r=0..1:2",
                "--out",
                t,
            ],
            "a curve needs two points",
        ),
        (
            &["plot", APPENDIX, "--figure", "fig9", "--out", t],
            "has no figure `fig9` (its figures: fig6)",
        ),
        (
            &["plot", APPENDIX, "--y", "A2", "--x", "nu=0..1", "--out", t],
            "`nu` is not a declared scalar",
        ),
        (
            &["plot", APPENDIX, "--y", "A2", "--x", "f_r=2..1", "--out", t],
            "the range is empty",
        ),
        (
            &[
                "plot", APPENDIX, "--y", "A2 +", "--x", "f_r=1..2", "--out", t,
            ],
            "with the command line:",
        ),
        // A2 reads K, G, h^C, h_2 and the state: nothing fixes them here.
        (
            &[
                "plot", APPENDIX, "--y", "A2", "--x", "f_r=1..2", "--given", "sig < 0", "--out", t,
            ],
            "neither f_r nor fixed",
        ),
        (
            &[
                "plot",
                "no-such-file.toml",
                "--y",
                "x",
                "--x",
                "x=0..1",
                "--out",
                t,
            ],
            "cannot read no-such-file.toml",
        ),
    ];
    for (args, want) in cases {
        let out = run(args);
        assert_eq!(
            out.status.code(),
            Some(2),
            "{args:?}: {}",
            text(&out.stderr)
        );
        assert!(
            text(&out.stderr).contains(want),
            "{args:?}: {}",
            text(&out.stderr)
        );
        assert!(!target.exists(), "{args:?} wrote its output");
    }
    // A point where a curve is undefined is left out, and said so.
    let out = run(&[
        "plot",
        APPENDIX,
        "--y",
        "sqrt(f_r - 1)",
        "--x",
        "f_r=0..2:1",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert_eq!(text(&out.stdout), "f_r,sqrt(f_r - 1)\n0,\n1,0\n2,1\n");
    assert!(
        text(&out.stderr).contains("is undefined at 1 of 3 points"),
        "{}",
        text(&out.stderr)
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// A user's file with one claim that holds, with or without `paper = …`.
fn user_file(paper: Option<&str>) -> String {
    let paper = paper.map_or(String::new(), |p| format!("paper = \"{p}\"\n"));
    format!(
        "{paper}section = \"t\"\ntitle = \"mine\"\ndimension = 3\nscalars = [\"x\"]\n\n[[claim]]\nid = \"sq\"\nprinted = 'x'\nexpect = \"holds\"\nsides = [\"(x + 1)^2\", \"x^2 + 2 x + 1\"]\n"
    )
}

#[test]
fn a_user_file_is_never_credited_to_the_paper() {
    let dir = dir_with("untitled", &user_file(None));
    let file = dir.join("claims.toml");
    let untitled = format!("untitled derivations: {}", file.display());
    for format in ["markdown", "latex", "json"] {
        // A LaTeX fragment names no work; the standalone document does.
        let out = run(&[
            "verify",
            file.to_str().unwrap(),
            "--format",
            format,
            "--standalone",
        ]);
        assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
        let stdout = text(&out.stdout);
        assert!(!stdout.contains("Papanicolopoulos"), "{format}: {stdout}");
        let shown = if format == "latex" {
            // LaTeX may break a line after each `/` of a path.
            untitled.replace('_', "\\_").replace('/', "/\\allowbreak{}")
        } else {
            untitled.clone()
        };
        assert!(stdout.contains(&shown), "{format}: {stdout}");
    }
    // The errata of a directory with nothing failing are credited the same way.
    let out = run(&["errata", "--dir", dir.to_str().unwrap()]);
    let stdout = text(&out.stdout);
    assert!(stdout.contains("untitled derivations:") && !stdout.contains("Papanicolopoulos"));
    // A title, when the file gives one, is used as written.
    let dir = dir_with("titled", &user_file(Some("My notes on plasticity")));
    let out = run(&["verify", dir.join("claims.toml").to_str().unwrap()]);
    assert!(text(&out.stdout).contains("\nMy notes on plasticity.\n"));
    // One claim is "1 claim".
    assert!(
        text(&out.stdout).contains("1 claim: 1 hold,"),
        "{}",
        text(&out.stdout)
    );
}

#[test]
fn out_never_overwrites_an_input_file() {
    let dir = dir_with("overwrite", &user_file(None));
    let file = dir.join("claims.toml");
    let before = std::fs::read(&file).unwrap();
    // The same file, and the same file under another spelling.
    let other = dir.join(".").join("claims.toml");
    for target in [&file, &other] {
        let out = run(&[
            "verify",
            file.to_str().unwrap(),
            "--out",
            target.to_str().unwrap(),
        ]);
        assert_eq!(out.status.code(), Some(2));
        assert!(
            text(&out.stderr).contains("is an input file"),
            "{}",
            text(&out.stderr)
        );
        assert_eq!(
            std::fs::read(&file).unwrap(),
            before,
            "the input is untouched"
        );
    }
    // Another file is written whole, and no temporary file is left beside it.
    let table = dir.join("table.md");
    let out = run(&[
        "verify",
        file.to_str().unwrap(),
        "--out",
        table.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0));
    assert!(std::fs::read_to_string(&table)
        .unwrap()
        .starts_with("# Derivation table"));
    let leftovers: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(Result::ok)
        .filter(|e| e.file_name().to_string_lossy().contains(".tmp-"))
        .collect();
    assert!(leftovers.is_empty());
}

#[test]
fn options_work_without_the_subcommand() {
    let out = run(&["--only", "eq33", "--format", "json"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["claims"][0]["id"], "eq33");
    let both = run(&["--only", "eq33", "check"]);
    assert_eq!(both.status.code(), Some(2));
}

#[test]
fn explain_reads_several_files_after_one_flag() {
    let out = run(&[
        "explain",
        "eq33",
        "--file",
        "derivations/3.3-fabric-averaging.toml",
        "derivations/3.4-invariants.toml",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert!(text(&out.stdout).starts_with("# eq33"));
}

#[test]
fn a_runaway_claim_is_undecided_at_the_time_limit() {
    // The finding says the limit stopped the decision (a timed assertion here would
    // test the machine, not the checker).
    let out = run(&[
        "--only",
        "eq47",
        "--samples",
        "1000000",
        "--time-limit",
        "0.2",
        "--format",
        "json",
    ]);
    let v = stopped_by_the_time_limit(&out);
    assert!(v["claims"][0]["detail"]
        .as_str()
        .unwrap()
        .contains("undecided (time limit)"));
    for bad in ["0", "-1", "soon", "inf"] {
        let refused = run(&["--only", "eq47", "--time-limit", bad]);
        assert_eq!(refused.status.code(), Some(2), "{bad}");
    }
}

#[test]
fn devices_fifos_directories_and_huge_files_are_refused_promptly() {
    let dir = dir_with("bounded", "");
    let fifo = dir.join("fifo.toml");
    let made = Command::new("mkfifo").arg(&fifo).status();
    let huge = dir.join("huge.toml");
    std::fs::write(&huge, "#".repeat(5 << 20)).unwrap();
    let mut cases = vec![
        ("/dev/zero".to_owned(), "not a regular file"),
        (dir.display().to_string(), "a directory"),
        (huge.display().to_string(), "4 MiB"),
    ];
    if made.is_ok_and(|s| s.success()) {
        cases.push((fifo.display().to_string(), "not a regular file"));
    }
    for (path, why) in cases {
        // Refused before it is opened (a FIFO would block in open): the message says so.
        let out = run(&["verify", &path]);
        assert_eq!(out.status.code(), Some(2), "{path}");
        let err = text(&out.stderr);
        assert!(err.contains(&path) && err.contains(why), "{path}: {err}");
        assert!(out.stdout.is_empty());
    }
    // In a directory, a FIFO named *.toml is refused too, not skipped in silence.
    if fifo.exists() {
        let out = run(&["check", "--dir", dir.to_str().unwrap()]);
        assert_eq!(out.status.code(), Some(2));
        assert!(
            text(&out.stderr).contains("fifo.toml: not a regular file"),
            "{}",
            text(&out.stderr)
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn progress_on_a_terminal_names_the_claim_and_counts_its_samples() {
    // `script` (util-linux) gives the run a terminal; without it there is nothing to show.
    let bin = env!("CARGO_BIN_EXE_cosserat-check");
    let out_file =
        std::env::temp_dir().join(format!("cosserat-progress-{}.md", std::process::id()));
    let command = format!(
        "{bin} --only eq47 --samples 1000000 --time-limit 2.5 --out {}",
        out_file.display()
    );
    let Ok(out) = Command::new("script")
        .args(["-qec", &command, "/dev/null"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
    else {
        eprintln!("note: `script` is not installed; progress on a terminal not tested");
        return;
    };
    let shown = text(&out.stdout);
    assert!(shown.contains("decided 0/1 · eq47: samples "), "{shown}");
    assert!(shown.contains("/1000000, "), "{shown}");
    assert!(shown.contains("decided 1 claim in "), "{shown}");
    let _ = std::fs::remove_file(&out_file);
}

#[test]
fn a_sampled_sign_claim_stops_at_the_time_limit() {
    // A function of several parameters with coefficients of both signs is decided by
    // exact samples; a million of them would take minutes. The sampling asks the time
    // limit between samples, so the claim is undecided (time limit), not a hang.
    let dir = dir_with(
        "sampled-limit",
        "section = \"t\"\ntitle = \"test\"\ndimension = 3\nscalars = [\"x\", \"y\", \"z\"]\n\n\
         [[claim]]\nid = \"many-samples\"\nprinted = 'q > 0'\nexpect = \"holds\"\n\
         strategy = \"sign\"\nsides = [\"(x^2 - x y + y^2)^5 + (z - x)^4 + 1\", \"0\"]\n\
         relation = \">\"\nsamples = 1000000\n",
    );
    let file = dir.join("claims.toml");
    let out = run(&[
        "verify",
        file.to_str().unwrap(),
        "--time-limit",
        "0.3",
        "--format",
        "json",
    ]);
    stopped_by_the_time_limit(&out);
}

/// The JSON table of a run whose one claim the time limit stopped (exit 1, undecided,
/// the time-limit finding), after checking that it is one.
fn stopped_by_the_time_limit(out: &Output) -> serde_json::Value {
    assert_eq!(out.status.code(), Some(1), "{}", text(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["claims"][0]["verdict"], "undecided");
    assert_eq!(v["claims"][0]["finding"]["kind"], "time-limit");
    v
}

/// Definitions chained 4,900 deep (nesting 9,800, within the loader's bound of 10,000)
/// are decided on the run's deep stack, and one more level is a located error: neither
/// overflows the stack, which would abort the process.
#[test]
fn a_deep_chain_of_definitions_is_decided_or_refused_never_a_crash() {
    let chain = |n: usize| {
        let defs: Vec<String> = std::iter::once("\"d0 = x\"".to_owned())
            .chain((1..=n).map(|k| format!("\"d{k} = -d{}\"", k - 1)))
            .collect();
        format!(
            "section = \"t\"\ntitle = \"t\"\ndimension = 2\nscalars = [\"x\"]\ndefine = [{}]\n\n\
             [[claim]]\nid = \"c\"\nprinted = 'x'\nexpect = \"holds\"\nsides = [\"d{n}\", \"x\"]\n",
            defs.join(", ")
        )
    };
    let dir = dir_with("deep-chain", &chain(4_900));
    let out = run(&[
        "verify",
        dir.join("claims.toml").to_str().unwrap(),
        "--format",
        "json",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert!(text(&out.stdout).contains("\"strength\": \"proof\""));
    let dir = dir_with("deeper-chain", &chain(5_100));
    let out = run(&["verify", dir.join("claims.toml").to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        text(&out.stderr).contains("levels deep"),
        "{}",
        text(&out.stderr)
    );
}

/// `--out` replaces only regular files (atomically, through a temporary file created
/// exclusively); a device is written into and stays a device; `-` is standard output;
/// a full disk is an error with its reason; a symbolic link keeps pointing at the
/// file, which gets the table.
#[test]
fn out_replaces_only_regular_files_and_writes_devices_in_place() {
    use std::os::unix::fs::FileTypeExt;
    let csv = |out: &str| run(&["check", "--format", "csv", "--out", out]);
    let to_null = csv("/dev/null");
    assert_eq!(to_null.status.code(), Some(0), "{}", text(&to_null.stderr));
    assert!(std::fs::metadata("/dev/null")
        .unwrap()
        .file_type()
        .is_char_device());
    if Path::new("/dev/full").exists() {
        let full = csv("/dev/full");
        assert_eq!(full.status.code(), Some(2));
        assert!(
            text(&full.stderr).contains("/dev/full"),
            "{}",
            text(&full.stderr)
        );
    }
    let dash = csv("-");
    assert!(text(&dash.stdout).starts_with("id,section,statement"));
    let dir = dir_with("out-link", "");
    std::fs::write(dir.join("t.csv"), "old").unwrap();
    std::os::unix::fs::symlink(dir.join("t.csv"), dir.join("link.csv")).unwrap();
    let linked = csv(dir.join("link.csv").to_str().unwrap());
    assert_eq!(linked.status.code(), Some(0));
    assert!(std::fs::symlink_metadata(dir.join("link.csv"))
        .unwrap()
        .file_type()
        .is_symlink());
    assert!(std::fs::read_to_string(dir.join("t.csv"))
        .unwrap()
        .starts_with("id,"));
    let leftovers: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".tmp"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
    let to_dir = csv(dir.to_str().unwrap());
    assert_eq!(to_dir.status.code(), Some(2));
}

/// The hostile file of `tests/hostile/report.toml` as CSV, Markdown and the terminal
/// view: no CSV cell starts a formula, the Markdown carries no HTML tag and no forged
/// line, and no control character reaches the terminal, even from a file name.
#[test]
fn csv_markdown_and_the_terminal_carry_nothing_from_a_hostile_file_as_markup() {
    let hostile = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/hostile/report.toml"),
    )
    .unwrap()
    .replace("PORT", "9");
    let dir = dir_with("hostile-formats", &hostile);
    let file = dir.join("claims.toml");
    let csv = text(&run(&["verify", file.to_str().unwrap(), "--format", "csv"]).stdout);
    assert!(csv.lines().count() >= 5, "{csv}");
    for line in csv.lines().skip(1) {
        for cell in line.split("\",\"") {
            let cell = cell.trim_start_matches('"');
            assert!(
                !cell
                    .trim_start()
                    .starts_with(['=', '+', '-', '@', '|', '＝', '－']),
                "a formula cell: {cell}"
            );
        }
    }
    let md = text(&run(&["verify", file.to_str().unwrap(), "--format", "markdown"]).stdout);
    assert!(!md.contains("<script") && !md.contains("<style") && !md.contains("<img"));
    // TeX a converter would pass on (pandoc's raw TeX) is escaped, in text and formulas.
    // (Code spans are verbatim to Markdown and to pandoc: only the text between them.)
    let outside_code: String = md
        .lines()
        .flat_map(|l| l.split('`').step_by(2).chain(["\n"]))
        .collect();
    for command in ["\\input", "\\openout", "\\end{document}", "\\href"] {
        for (k, _) in outside_code.match_indices(command) {
            let md = &outside_code;
            let escapes = md[..k].chars().rev().take_while(|&c| c == '\\').count();
            assert_eq!(escapes % 2, 1, "{command} reaches TeX: {md}");
        }
    }
    for line in md.lines().filter(|l| l.starts_with("| ")) {
        let pipes = line.matches('|').count() - line.matches("\\|").count();
        assert_eq!(pipes, 8, "a forged cell: {line}");
    }
    // A file name with a terminal escape, and a malformed file: the error names it inert.
    let named = dir.join("x\u{1b}]0;pwned\u{7}.toml");
    std::fs::write(&named, "section = \n").unwrap();
    let out = run(&["verify", named.to_str().unwrap(), "--format", "compact"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(!out.stderr.contains(&0x1b) && !out.stderr.contains(&0x07));
    assert!(
        text(&out.stderr).contains("\\u{1b}"),
        "{}",
        text(&out.stderr)
    );
    std::fs::write(&named, &hostile).unwrap();
    let out = run(&["verify", named.to_str().unwrap(), "--format", "compact"]);
    assert!(
        !out.stdout.contains(&0x1b) && !out.stdout.contains(&0x07),
        "{}",
        text(&out.stdout)
    );
}

/// `plot` evaluates its curves under a time limit: past it, no figure and exit 2.
#[test]
fn plot_stops_at_its_time_limit() {
    let dir = dir_with(
        "plot-limit",
        "section = \"p\"\ntitle = \"p\"\ndimension = 3\nnormal = \"n\"\nscalars = [\"t\"]\n",
    );
    let file = dir.join("claims.toml");
    let out = run(&[
        "plot",
        file.to_str().unwrap(),
        "--y",
        "avg((n_1 t + n_2)^40 (n_3 + t n_1)^40 (n_1 + n_2 t)^40)",
        "--x",
        "t=0..1:0.0002",
        "--time-limit",
        "0.1",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        text(&out.stderr).contains("not evaluated within 0.1 s"),
        "{}",
        text(&out.stderr)
    );
    assert!(out.stdout.is_empty());
}

/// `--run-limit` bounds the whole run: claims that get no time left are
/// `undecided (time limit)`, and every claim that was decided has its usual verdict.
#[test]
fn the_run_limit_leaves_claims_undecided_never_wrong() {
    let out = run(&["check", "--run-limit", "0.001", "--format", "json"]);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let claims = v["claims"].as_array().unwrap();
    assert!(claims.iter().any(|c| c["detail"]
        .as_str()
        .is_some_and(|d| d.contains("time limit"))));
    for c in claims {
        let verdict = c["verdict"].as_str().unwrap();
        assert!(
            verdict == "undecided" || verdict == c["expected"],
            "{}: {verdict}",
            c["id"]
        );
    }
}

/// An exact expansion within the term budget whose coefficients have thousands of
/// digits ((x − 1/3)^4096) is stopped by the time limit inside the polynomial product.
#[test]
fn the_time_limit_stops_a_long_polynomial_product() {
    let dir = dir_with(
        "long-product",
        "section = \"s\"\ntitle = \"s\"\ndimension = 2\nscalars = [\"x\"]\n\
         define = [\"a = (x - 1/3)^64\", \"b = a^64\", \"c = b (x - 1/7) (x^2 - 2)\"]\n\n\
         [[claim]]\nid = \"s\"\nprinted = 'x'\nexpect = \"holds\"\nstrategy = \"sign\"\n\
         sides = [\"c + 1\", \"0\"]\nrelation = \">\"\ngiven = [\"0 <= x <= 1\"]\n",
    );
    let file = dir.join("claims.toml");
    let out = run(&[
        "verify",
        file.to_str().unwrap(),
        "--time-limit",
        "0.5",
        "--format",
        "json",
    ]);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let detail = v["claims"][0]["detail"].as_str().unwrap_or_default();
    assert!(detail.contains("undecided (time limit)"), "{detail}");
}

#[test]
fn standard_input_is_read_for_a_dash() {
    let file = std::fs::read("derivations/examples/moduli.toml").unwrap();
    let mut child = bin()
        .args(["verify", "-", "--format", "json"])
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    std::io::Write::write_all(&mut child.stdin.take().unwrap(), &file).unwrap();
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert!(text(&out.stdout).contains("\"claims\""));
    // Malformed input on standard input is located in `<stdin>`.
    let mut child = bin()
        .args(["verify", "-"])
        .stdin(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    std::io::Write::write_all(&mut child.stdin.take().unwrap(), b"x = [").unwrap();
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(
        text(&out.stderr).contains("<stdin>:1:"),
        "{}",
        text(&out.stderr)
    );
}

#[test]
fn colour_follows_the_flag_no_color_and_a_dumb_terminal() {
    let esc = |args: &[&str], env: &[(&str, &str)]| {
        let mut c = bin();
        c.args(args);
        for (k, v) in env {
            c.env(k, v);
        }
        let out = c.output().unwrap();
        text(&out.stdout).contains('\u{1b}')
    };
    let compact = ["--only", "eq21", "--format", "compact"];
    assert!(
        !esc(&compact, &[]),
        "piped output is never coloured by default"
    );
    let always = ["--only", "eq21", "--format", "compact", "--color", "always"];
    assert!(esc(&always, &[]));
    let never = ["--only", "eq21", "--format", "compact", "--color", "never"];
    assert!(!esc(&never, &[]));
}

#[test]
fn examples_are_written_for_an_installed_binary_and_never_replace_a_file() {
    let dir = std::env::temp_dir().join(format!("cosserat-check-examples-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let d = dir.to_str().unwrap();
    let out = run(&["examples", "--out", d]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert!(dir.join("derivations/A-2-bifurcation.toml").is_file());
    assert!(dir.join("derivations/examples/moduli.toml").is_file());
    // The documented commands work from there.
    let checked = Command::new(env!("CARGO_BIN_EXE_cosserat-check"))
        .current_dir(&dir)
        .args(["verify", "derivations/examples/moduli.toml"])
        .output()
        .unwrap();
    assert_eq!(checked.status.code(), Some(0), "{}", text(&checked.stderr));
    // Again: nothing to write. A changed file is refused, and nothing is written.
    assert_eq!(run(&["examples", "--out", d]).status.code(), Some(0));
    let edited = dir.join("derivations/examples/moduli.toml");
    std::fs::write(&edited, "edited").unwrap();
    std::fs::remove_file(dir.join("derivations/A-2-bifurcation.toml")).unwrap();
    let out = run(&["examples", "--out", d]);
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(std::fs::read_to_string(&edited).unwrap(), "edited");
    assert!(!dir.join("derivations/A-2-bifurcation.toml").exists());
    // A symbolic link on the way would lead the files out of the directory: refused,
    // nothing written anywhere.
    let linked = dir.join("linked");
    let outside = dir.join("outside");
    std::fs::create_dir_all(&linked).unwrap();
    std::fs::create_dir_all(&outside).unwrap();
    std::os::unix::fs::symlink(&outside, linked.join("derivations")).unwrap();
    let out = run(&["examples", "--out", linked.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2), "{}", text(&out.stderr));
    assert!(
        text(&out.stderr).contains("is not a directory"),
        "{}",
        text(&out.stderr)
    );
    assert_eq!(std::fs::read_dir(&outside).unwrap().count(), 0);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn completions_a_manual_page_and_the_guide_are_installed_help() {
    for shell in ["bash", "zsh", "fish", "elvish", "powershell"] {
        let out = run(&["completions", shell]);
        assert_eq!(out.status.code(), Some(0));
        assert!(text(&out.stdout).contains("verify"), "{shell}");
    }
    let man = run(&["manpage"]);
    assert!(
        text(&man.stdout).starts_with(".ie") || text(&man.stdout).contains(".TH cosserat-check 1")
    );
    assert!(text(&man.stdout).contains("verify"));
    let guide = text(&run(&["guide"]).stdout);
    assert!(guide.contains("Derivation files"));
    // Hints point to installed help, never to a file of the source tree.
    let help = text(&run(&["--help"]).stdout);
    assert!(help.contains("cosserat-check guide") && !help.contains("docs/src"));
}

#[test]
fn a_closed_pipe_ends_the_run_quietly() {
    // The JSON report (about 440 KB) is larger than a pipe's buffer, so the write
    // meets the closed pipe whenever the reader goes away.
    let mut child = bin()
        .args(["--format", "json"])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert!(text(&out.stderr).is_empty(), "{}", text(&out.stderr));
}

#[test]
fn the_compact_table_fits_the_terminal() {
    // `script` (util-linux) gives the run a terminal, COLUMNS its width.
    let bin = env!("CARGO_BIN_EXE_cosserat-check");
    let rows_at = |columns: usize| -> Option<Vec<String>> {
        let out = Command::new("script")
            .args(["-qec", &format!("{bin} --color never"), "/dev/null"])
            .env("COLUMNS", columns.to_string())
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .output()
            .ok()?;
        let shown = text(&out.stdout).replace('\r', "");
        Some(
            shown
                .lines()
                .filter(|l| l.starts_with("eq") || l.starts_with("sec"))
                .map(str::to_owned)
                .collect(),
        )
    };
    let Some(narrow) = rows_at(140) else {
        eprintln!("note: `script` is not installed; the width of the terminal not tested");
        return;
    };
    assert!(narrow.len() > 40);
    for row in &narrow {
        assert!(row.chars().count() <= 140, "wider than the terminal: {row}");
    }
    // A wider terminal shows more of the evidence.
    let wide = rows_at(220).unwrap();
    let total = |rows: &[String]| rows.iter().map(|r| r.chars().count()).sum::<usize>();
    assert!(total(&wide) > total(&narrow));
}
