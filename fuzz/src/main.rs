//! A mutational fuzzer for cosserat-check's input side: the derivation-file reader, the
//! expression parser, the index validator, the exact decision (the strategies that
//! run in bounded time per input), and `draft`, whose file must always load. No nightly toolchain or sanitizer runtime is needed.
//!
//! Usage: `cargo run --release -- SECONDS [SEED]` from `fuzz/`. Seeds are every derivation
//! file of the repository (the paper, the examples, the bad-input corpus). Each input is
//! a seed mutated by byte edits, token insertions from a dictionary of the language, and
//! splices of two seeds. A panic is a crash (written to `crashes/`), an input that takes
//! more than `SLOW` seconds is a hang candidate (written to `slow/`). The run prints its
//! statistics and exits 1 when it found anything.

use cosserat_check::check::decide;
use cosserat_check::check::probe::curve_values;
use cosserat_check::check::transcription::transcribe;
use cosserat_check::decide::finding::Finding;
use cosserat_check::decide::random::Rng;
use cosserat_check::derivation::{draft, load_str, Strategy};
use cosserat_check::eval::quadrature::{Level, Quadrature};
use cosserat_check::eval::tape::Tape;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

const SLOW: Duration = Duration::from_secs(5);

const DICTIONARY: &[&str] = &[
    "\\frac{",
    "}{",
    "\\langle ",
    " \\rangle",
    "^{(1)}",
    "_{ij}",
    "_{i,m}",
    "\\sqrt{",
    "\\partial ",
    "\\left(",
    "\\right)",
    "\\text{ with }",
    "\\text{ for }",
    "\\quad",
    "\\Rightarrow",
    "\\dot",
    "\\begin{pmatrix}",
    " & ",
    "\\\\",
    "\\end{pmatrix}",
    "|",
    "\\le",
    "[notation]\n",
    "'\\sigma_{ij}^{(1)}' = \"sigma_ij\"\n",
    "'T^2' = \"avg(n_k n_k)\"\n",
    "'^{n}' = \"power\"\n",
    "'\\langle \\rangle' = \"macaulay\"\n",
    "defines = ['",
    "differs_from_printed = \"x\"\n",
    "notation = { ",
    "(",
    ")",
    "_",
    "_ij",
    "_k",
    "_1",
    "^",
    "^64",
    "^0",
    "+",
    "-",
    "*",
    "/",
    "/0",
    "/(1 + ",
    "sigma_el_ij",
    "_el",
    "_,",
    "/(x - x)",
    " (1 - 2 nu)",
    ")^3",
    " ",
    "\n",
    "\"",
    "'",
    "[",
    "]",
    "=",
    "==",
    "<=",
    "avg(",
    "maxn(",
    ",",
    "pi",
    "exp(",
    "log(",
    "acos(",
    "atan2(",
    "max(",
    "min(",
    "^(1/3)",
    "^(-2)",
    "^0.5",
    "1e-3",
    "1e300",
    "2.5E+",
    "sqrt(",
    "abs(",
    "cos(",
    "eps_ijk",
    "delta_ij",
    "n_i",
    "sigma_kk",
    "0",
    "1/3",
    "0.5",
    "99999999999999999999",
    "[[claim]]\n",
    "sides = [",
    "chains = [[",
    "strategy = \"numeric\"\n",
    "strategy = \"gradient\"\n",
    "strategy = \"roots\"\n",
    "[[figure]]\nid = \"f\"\ntitle = \"t\"\nx = \"x = 0 .. 1 : 0.25\"\ncurves = [{ y = \"x\", label = \"l\" }]\n",
    "x = \"x = 0 .. 1\"\n",
    "set = [\"x = 1\"]\n",
    "strategy = \"monotone\"\n",
    "solve(",
    "dsigma_21",
    "dmu_23",
    "verbatim = true\n",
    "convention = \"symmetrised\"\n",
    "convention = \"independent\"\n",
    "symmetric(sigma)",
    "traceless(sigma)",
    "strategy = \"convex\"\n",
    "wrt = [\"sigma\"]\n",
    "assume = [\"",
    "define = [\"",
    "expect = \"fails\"\n",
    "dimension = 2\n",
    "normal_in_plane = true\n",
    "\u{3c3}",
    "\u{0}",
    "\\u0041",
    "\\",
    "#",
    "'''",
    ",i",
    ",jk",
    "_,k",
    "u_i,j",
    "d(",
    ")/dx_i",
    ")/dx_ij",
    "(x_2)",
    "(x_1, x_2)",
    "position = \"x\"\n",
    "fields = [\"u_i\", \"w_i(x_2)\", \"theta\"]\n",
    "x_k x_k",
    "variation(",
    ", u_j)",
    ", theta)",
    "strategy = \"proportional\"\n",
    "variation(sigma_ij u_j,i, u_k)",
    "variation(u_i,jj u_i,kk, u_m)",
    "strategy = \"sign\"\nrelation = \">\"\n",
    "strategy = \"monotone\"\nfunction = \"x/(1 + x^2)\"\nin = \"x\"\ndirection = \"increasing\"\n",
    "strategy = \"limit\"\nfunction = \"1/x\"\nin = \"x\"\ntends_to = \"0+\"\nlimit = \"+infinity\"\n",
    "strategy = \"roots\"\nfunction = \"x^3 - 7 x + 6\"\nin = \"x\"\nroots = [\"1\"]\n",
    "given = [\"0 < x <= 1/2\"]\n",
    "strategy = \"not-circle\"\nx = \"sigma_ij n_i n_j\"\ny = \"sigma_12 (n_1 n_1 - n_2 n_2) + (sigma_22 - sigma_11) n_1 n_2\"\n",
    "strategy = \"not-circle\"\nx = \"x n_1 + 1\"\ny = \"x n_2\"\n",
    "strategy = \"not-circle\"\nx = \"n_1 n_1\"\ny = \"n_1 n_2\"\n",
    "tends_to = \"-infinity\"\n",
    "relation = \"<=\"\n",
    "[[a, b], [c, d]]",
    "[x, y]",
    "[1, 0, 1, 1]",
    "A[1,2]",
    "v[2]",
    "^T",
    "det(",
    "trace(",
    "inv(",
    "adj(",
    "transpose(",
    "solve(",
    "identity(4)",
    "identity(13)",
    "matrix(C_ijkl, voigt_ij, voigt_kl)",
    "vector(sigma_ij, voigt_ij)",
    "tensor(D, voigt_ij, voigt_kl)",
    "orders = { voigt = [\"11\", \"22\", \"12\", \"21\"], plane = [\"1\", \"2\"] }\n",
    "define = [\"A = [[1, 2], [3, 4]]\", \"v = [1, 2]\"]\n",
    "inv([[1, 2], [2, 4]])",
    "grad(",
    "grad(F2, sigma_ij)",
    "grad(sqrt(J2), sigma_kl)",
    "grad(x^2 / (1 + x), x)",
    "grad(grad(x^3, x), x)",
    "grad(det(A), x)",
    ", sigma_kl)",
    "sqrt(tau^2)",
    "given = [\"tau > 0\", \"s < 0\"]\n",
    "given = [\"x >= 0\"]\n",
    "assume = [\"sigma_ij = s delta_ij - f_r s (delta_i1 delta_j2 + delta_i2 delta_j1)\"]\n",
    "$$",
    " \\quad (1)$$\n",
    "\\begin{equation}",
    "\\end{equation}",
    "\\begin{align}",
    "\\end{align}",
    "\\tag{",
    "\\nonumber",
    " &= ",
    "\\[",
    "\\]",
    "%",
    "\\sin 2\\theta",
    "\\cos^2",
    "_{\\mathrm{I}}",
    "_{\\max}",
    "_n",
    "where $p = ",
    "$ is the ",
    " = 0",
    "\\det(",
    "incompressible",
    "deviatoric ",
    ", tie = 'divergence'",
    ", tie = 'law'",
    "_{nn}",
    " = -b_i",
    "\\sin k\\theta",
    " \\quad \\text{with} \\quad ",
    "We linearise the field around the point ",
    "assume a different form in two dimensions ",
    "^{(1)}",
    "_{i,m}^c",
    " = 0\"]",
    ")_{,i}",
    "Similarly, the vector $m_i = \\mu_{ki} n_k$ has a normal component $m^{(n)}$ ",
    "In two dimensions, ",
    "The stress $\\sigma_{ij}$ is symmetric. ",
    "The strain tensor is skew symmetric; ",
    "Let $S$ be a symmetric tensor, $S_{12} = S_{21}$. ",
    "\\section{Cosserat} ",
    "Equilibrium requires \\begin{equation}\\sigma_{ij,j} + b_i = 0\\end{equation} ",
    "The normal is $n_1 = \\cos\\theta$ and $n_2 = \\sin\\theta$. ",
    ", describing the anisotropy",
    ", with traction $t_i = \\sigma_{ji} n_j$",
    "\\begin{equation*} I_1 = \\sigma_{kk}, \\qquad I_2 = \\sigma_{ij}\\sigma_{ji} \\end{equation*} ",
];

fn seeds(root: &Path) -> Vec<Vec<u8>> {
    let mut out = Vec::new();
    for dir in [
        "derivations",
        "derivations/examples",
        "tests/bad",
        "tests/soundness",
        "tests/papers",
        "tests/draft",
        "tests/draft/attacks",
    ] {
        if let Ok(entries) = std::fs::read_dir(root.join(dir)) {
            let mut paths: Vec<PathBuf> =
                entries.filter_map(Result::ok).map(|e| e.path()).collect();
            paths.sort();
            for p in paths {
                if p.extension().is_some_and(|x| x == "toml" || x == "tex") {
                    if let Ok(b) = std::fs::read(&p) {
                        // A paper's draft is a seed too: a drafted file (`drafted`,
                        // `to_complete`) as `verify` reads it.
                        if p.extension().is_some_and(|x| x == "tex") {
                            let text = String::from_utf8_lossy(&b).into_owned();
                            let none = (&Default::default(), &Default::default());
                            let d =
                                draft::draft("seed.tex", &text, &draft::Options::default(), none);
                            out.push(d.toml.into_bytes());
                        }
                        out.push(b);
                    }
                }
            }
        }
    }
    out
}

fn mutate(rng: &mut Rng, seeds: &[Vec<u8>]) -> Vec<u8> {
    let mut data = seeds[rng.below(seeds.len())].clone();
    for _ in 0..1 + rng.below(8) {
        let at = rng.below(data.len() + 1);
        match rng.below(6) {
            0 if !data.is_empty() => {
                let k = rng.below(data.len());
                data[k] = rng.next_u64() as u8;
            }
            1 if !data.is_empty() => {
                let len = 1 + rng.below(16.min(data.len()));
                let start = rng.below(data.len() - len + 1);
                data.drain(start..start + len);
            }
            2 | 3 => {
                let tok = DICTIONARY[rng.below(DICTIONARY.len())].as_bytes();
                data.splice(at..at, tok.iter().copied());
            }
            4 => {
                let other = &seeds[rng.below(seeds.len())];
                if !other.is_empty() {
                    let a = rng.below(other.len());
                    let b = a + rng.below(other.len() - a + 1).min(400);
                    data.splice(at..at, other[a..b].iter().copied());
                }
            }
            _ if !data.is_empty() => {
                // Duplicate a slice (repetition finds depth and size limits).
                let a = rng.below(data.len());
                let b = (a + rng.below(64)).min(data.len());
                let piece: Vec<u8> = data[a..b].repeat(1 + rng.below(8));
                data.splice(at.min(data.len())..at.min(data.len()), piece);
            }
            _ => {}
        }
    }
    data
}

/// Reads and decides one input; numeric strategies are not decided (they are bounded
/// by their sample counts and exercised by the test suite), but every expression they
/// would evaluate is compiled to a tape and run once.
fn exercise(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    // A draft of any text loads (the promise of `draft`; its claims' decisions are the
    // command line's loop).
    let options = draft::Options {
        dimension: None,
        normal: Some("n".to_owned()),
    };
    let none = (&Default::default(), &Default::default());
    let d = draft::draft("fuzz.tex", text, &options, none);
    if let Err(e) = load_str("draft.toml", &d.toml) {
        panic!("a draft does not load: {e}");
    }
    let Ok(file) = load_str("fuzz.toml", text) else {
        return;
    };
    // Figures: every curve on a grid small enough to stay fast (at most 10,000 points
    // are allowed, each one interpreter run).
    for figure in file.figures.iter().filter(|f| f.x.values.len() <= 200) {
        for curve in &figure.curves {
            let _ = curve_values(curve, &figure.x);
        }
    }
    for claim in &file.claims {
        if matches!(
            claim.check.strategy,
            Strategy::Exact { .. } | Strategy::Proportional { .. } | Strategy::NotCircle { .. }
        ) {
            // A decision isolates its own panics as an internal error: the fuzzer
            // turns that back into a crash, so that none is hidden.
            if let Ok(o) = decide(&claim.decls, &claim.check) {
                if let Some(Finding::InternalError { message, at }) = &o.finding {
                    panic!("internal error: {message} at {at}");
                }
                // Every proof the decision made is checked again from its statement.
                for p in o.proofs() {
                    let again = cosserat_check::kernel::check::check(
                        p.statement().clone(),
                        p.fact().clone(),
                    );
                    assert!(again.is_ok(), "a proof the kernel does not accept again");
                }
            }
            let _ = transcribe(&claim.decls, &claim.check, &claim.transcript);
            continue;
        }
        let nodes = claim
            .check
            .chains
            .iter()
            .flatten()
            .filter_map(|s| s.node.as_ref().ok())
            .chain(
                claim
                    .check
                    .strategy
                    .expressions()
                    .into_iter()
                    .map(|e| &e.node),
            );
        for node in nodes {
            if let Ok(tape) = Tape::compile(&claim.decls, &claim.check.defs, node) {
                let inputs = vec![0.5; tape.inputs.len()];
                let mut n = vec![0.0; claim.decls.dim];
                n[0] = 1.0;
                let _ = tape.eval(&inputs, &n, &Quadrature::new(Level::Fine));
            }
        }
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let seconds: u64 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(60);
    let seed: u64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(1);
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let seeds = seeds(&root);
    assert!(!seeds.is_empty(), "no seed files found");
    std::panic::set_hook(Box::new(|_| {}));
    let here = Path::new(env!("CARGO_MANIFEST_DIR"));
    let (crashes, slow) = (here.join("crashes"), here.join("slow"));
    let mut rng = Rng::new(seed);
    let started = Instant::now();
    let (mut runs, mut loaded, mut found) = (0u64, 0u64, 0u64);
    let mut last_report = Instant::now();
    while started.elapsed() < Duration::from_secs(seconds) {
        let input = mutate(&mut rng, &seeds);
        let t = Instant::now();
        let outcome = catch_unwind(AssertUnwindSafe(|| exercise(&input)));
        let took = t.elapsed();
        runs += 1;
        if std::str::from_utf8(&input)
            .ok()
            .and_then(|s| load_str("f", s).ok())
            .is_some()
        {
            loaded += 1;
        }
        let bucket = if outcome.is_err() {
            Some(&crashes)
        } else if took > SLOW {
            Some(&slow)
        } else {
            None
        };
        if let Some(dir) = bucket {
            found += 1;
            let _ = std::fs::create_dir_all(dir);
            let _ = std::fs::write(dir.join(format!("{seed}-{runs}.toml")), &input);
            eprintln!(
                "finding {} after {runs} runs ({:.1} s): {}",
                found,
                took.as_secs_f64(),
                dir.display()
            );
        }
        if last_report.elapsed() > Duration::from_secs(60) {
            eprintln!(
                "{:>6.0} s: {runs} inputs, {loaded} valid files, {found} findings",
                started.elapsed().as_secs_f64()
            );
            last_report = Instant::now();
        }
    }
    println!(
        "fuzzed {runs} inputs in {:.0} s ({loaded} valid derivation files), {found} findings",
        started.elapsed().as_secs_f64()
    );
    std::process::exit(i32::from(found > 0));
}
