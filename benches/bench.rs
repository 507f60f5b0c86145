//! `cargo bench`: medians of repeated wall-clock timings, printed as a Markdown table.
//!
//! What is measured (release build): the whole-paper check (and its exact claims
//! alone), isotropic moment identities (each with a refuted mutant) of rank 2 to 10 in 2D
//! and 3D, the scaling of an exact proof with polynomial degree, the exact moments up to
//! order 12, the num-dual gradient claim of F2, the symbolic A² derivation, and the
//! whole paper in a fresh process (the user's view, when the release binary exists).
//! `-- --each` times every claim of the paper, slowest first (the profile by claim);
//! `-- --task NAME REPS` prints each repetition of one task for benches/peers.py.
//! The targets are in benches/README.md; this prints what the machine does, it asserts nothing.
//! `-- --claim ID` and `-- --derive-a2` print one median for benches/sympy_compare.py.

use cosserat_check::algebra::gcd;
use cosserat_check::check::decide_claim;
use cosserat_check::check::probe::Probe;
use cosserat_check::cli::decide_all;
use cosserat_check::derivation::{load_dir, load_str, DerivationFile, Strategy};
use cosserat_check::kernel::{monomial_moment, Poly};
use std::hint::black_box;
use std::path::Path;
use std::time::Instant;

/// The binary's allocator (see src/main.rs), so that in-process rows time what a run does.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn median_ms(reps: usize, mut f: impl FnMut()) -> f64 {
    let mut times: Vec<f64> = (0..reps)
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[reps / 2]
}

fn corpus() -> Vec<DerivationFile> {
    load_dir(&Path::new(env!("CARGO_MANIFEST_DIR")).join("derivations")).expect("derivations load")
}

#[path = "../tests/support/pairings.rs"]
mod pairings;
use pairings::delta_products;

/// An isotropic-moment identity of even rank `rank` in dimension `dim` and a wrong
/// version of it, as a file. Past rank 8 the right side is a sum of definitions of 35
/// pairings each (a side holds at most 1000 tokens).
fn moment_identity(dim: usize, rank: usize) -> String {
    let letters: Vec<char> = "ijklmpqrst".chars().take(rank).collect();
    let free: String = letters.iter().collect();
    let ns: Vec<String> = letters.iter().map(|c| format!("n_{c}")).collect();
    let terms: Vec<String> = delta_products(&letters);
    let denom: usize = (0..rank / 2).map(|m| dim + 2 * m).product();
    let claim = |id: &str, expect: &str, terms: &[String]| {
        format!(
            "[[claim]]\nid = \"{id}\"\nprinted = '{id}'\nexpect = \"{expect}\"\nsides = [\"avg({})\", \"1/{denom} ({})\"]\n",
            ns.join(" "),
            terms.join(" + ")
        )
    };
    // The identity, and the same with its last pairing dropped (refuted), as the peers
    // in benches/peers.py do it; at rank 2, its one pairing doubled.
    let (mut terms, mut defs) = (terms, String::new());
    if rank > 8 {
        let last = terms.pop().expect("pairings");
        let mut parts: Vec<String> = terms
            .chunks(35)
            .enumerate()
            .map(|(k, c)| format!("\"P{k}_{free} = {}\"", c.join(" + ")))
            .collect();
        parts.push(format!("\"L_{free} = {last}\""));
        defs = format!("define = [{}]\n", parts.join(", "));
        terms = (0..parts.len() - 1)
            .map(|k| format!("P{k}_{free}"))
            .collect();
        terms.push(format!("L_{free}"));
    }
    let wrong = match &terms[..] {
        [one] => vec![format!("2 {one}")],
        all => all[..all.len() - 1].to_vec(),
    };
    format!(
        "section = \"b\"\ntitle = \"b\"\ndimension = {dim}\nnormal = \"n\"\n{defs}{}{}reason = \"one pairing dropped\"\n",
        claim("m", "holds", &terms),
        claim("wrong", "fails", &wrong)
    )
}

/// ⟨(a·n)^(2k)⟩ = (2k−1)!! / (3·5·…·(2k+1)) (a·a)^k in 3D: degree 2k in a and in n.
fn degree_identity(k: usize) -> String {
    let num: usize = (1..2 * k).step_by(2).product();
    let den: usize = (0..k).map(|m| 3 + 2 * m).product();
    format!(
        "section = \"b\"\ntitle = \"b\"\ndimension = 3\nnormal = \"n\"\ntensors = [\"a_i\"]\n[[claim]]\nid = \"d\"\nprinted = 'd'\nexpect = \"holds\"\nsides = [\"avg((a_i n_i)^{})\", \"{num}/{den} (a_j a_j)^{k}\"]\n",
        2 * k
    )
}

/// Terms per factor and variables in the term-product comparison.
const TIGHT_TERMS: usize = 40;
const TIGHT_VARS: usize = 12;

/// A polynomial of the tight loop: packed monomials and integer numerators over 6.
type Packed = Vec<(u64, i64)>;

/// A deterministic stream from the checker's one generator: each call gives a number
/// below `m`.
fn stream(seed: u64) -> impl FnMut(u64) -> u64 {
    let mut rng = cosserat_check::decide::random::Rng::new(seed);
    move |m| rng.below(m as usize) as u64
}

/// `GCD_PAIRS` pairs `(g·a, g·b)` with a common factor `g`: random polynomials in
/// three variables, four terms each with exponents 0..=3 and small integer
/// coefficients, plus a constant term (so that no monomial content hides the work).
/// Each is returned with `g`, which must divide the gcd found.
fn gcd_pairs() -> Vec<(Poly, Poly, Poly)> {
    use cosserat_check::kernel::rational::Rational;
    use cosserat_check::kernel::Monomial;
    let mut next = stream(0x2545_f491_4f6c_dd1d);
    let mut random = || {
        (0..4).fold(Poly::constant(Rational::int(3)), |p, _| {
            let factors: Vec<(u32, i64)> = (0..3)
                .map(|v| (v, next(4) as i64))
                .filter(|&(_, e)| e > 0)
                .collect();
            let c = next(9) as i64 - 4;
            &p + &Poly::term(
                Monomial::from_factors(factors),
                Rational::int(if c == 0 { 5 } else { c }),
            )
        })
    };
    (0..GCD_PAIRS)
        .map(|_| {
            let (g, a, b) = (random(), random(), random());
            (&g * &a, &g * &b, g)
        })
        .collect()
}

const GCD_PAIRS: usize = 10;

/// The operands of the tight-loop comparison: two polynomials as the kernel holds
/// them, and the same two packed.
fn product_operands() -> (Poly, Poly, Packed, Packed) {
    use cosserat_check::kernel::rational::Rational;
    use cosserat_check::kernel::Monomial;
    use std::collections::HashMap;
    let mut next = stream(0x9e37_79b9_7f4a_7c15);
    // Two polynomials of TIGHT_TERMS terms, exponents 0..=3, coefficients k/6 (the
    // paper's denominators are small).
    let mut factor = || -> Vec<([u32; TIGHT_VARS], i64)> {
        (0..TIGHT_TERMS)
            .map(|_| {
                let mut e = [0u32; TIGHT_VARS];
                for x in e.iter_mut() {
                    *x = if next(3) == 0 { next(4) as u32 } else { 0 };
                }
                (e, next(19) as i64 - 9)
            })
            .collect()
    };
    let (a, b) = (factor(), factor());
    let poly = |terms: &[([u32; TIGHT_VARS], i64)]| {
        let mut p = Poly::default();
        for (e, c) in terms {
            let factors: Vec<(u32, i64)> = (0..TIGHT_VARS as u32)
                .zip(e.iter().map(|&x| x as i64))
                .filter(|&(_, x)| x != 0)
                .collect();
            p = &p
                + &Poly::term(
                    Monomial::from_factors(factors),
                    Rational::ratio(*c, 6).expect("6 ≠ 0"),
                );
        }
        p
    };
    let (pa, pb) = (poly(&a), poly(&b));
    let packed = |terms: &[([u32; TIGHT_VARS], i64)]| -> Vec<(u64, i64)> {
        // Equal monomials merged, as in a canonical polynomial.
        let mut merged: HashMap<u64, i64> = HashMap::new();
        for (e, c) in terms {
            *merged.entry(pack(e)).or_default() += c;
        }
        merged.into_iter().filter(|&(_, c)| c != 0).collect()
    };
    let (qa, qb) = (packed(&a), packed(&b));
    (pa, pb, qa, qb)
}

/// A monomial's exponents packed 5 bits each into one word (the tight loop's monomial).
fn pack(e: &[u32; TIGHT_VARS]) -> u64 {
    e.iter().fold(0u64, |acc, &x| (acc << 5) | u64::from(x))
}

/// The time of one term product (multiply two terms and add the result into the sum)
/// in the kernel's `Poly` and in a tight loop written for the purpose, in nanoseconds,
/// on the same two polynomials: the distance of the exact kernel from the limit that
/// issue 18 names (11–40 ns per product all-in). The tight loop packs a monomial's
/// exponents (at most 15 each, 5 bits per variable) into one u64, so that a monomial
/// product is one addition, and keeps integer numerators over one common denominator,
/// so that a coefficient product is one multiplication. Both results are compared, so
/// the estimate does the same work.
fn term_products() -> (f64, f64) {
    use cosserat_check::kernel::rational::Rational;
    let (pa, pb, qa, qb) = product_operands();
    let products = (pa.num_terms() * pb.num_terms()) as f64;
    let reps = 200;
    let ours = median_ms(9, || {
        for _ in 0..reps {
            black_box(&pa * &pb);
        }
    });
    let tight_product = || {
        let mut sum: rustc_hash::FxHashMap<u64, i64> = rustc_hash::FxHashMap::default();
        for &(ma, ca) in &qa {
            for &(mb, cb) in &qb {
                *sum.entry(ma + mb).or_default() += ca * cb;
            }
        }
        sum.retain(|_, c| *c != 0);
        sum
    };
    let tight = median_ms(9, || {
        for _ in 0..reps {
            black_box(tight_product());
        }
    });
    // The same polynomial: as many terms, each coefficient over 36.
    let check = tight_product();
    let product = &pa * &pb;
    assert_eq!(
        check.len(),
        product.num_terms(),
        "the tight loop computes the same product"
    );
    for (m, c) in product.terms() {
        let mut e = [0u32; TIGHT_VARS];
        for &(v, x) in m.factors() {
            e[v as usize] = x as u32;
        }
        let n = check.get(&pack(&e)).copied().unwrap_or(0);
        assert_eq!(
            *c,
            Rational::ratio(n, 36).expect("36 ≠ 0"),
            "coefficient of {m:?}"
        );
    }
    let per = |ms: f64| ms * 1e6 / (reps as f64 * products);
    (per(ours), per(tight))
}

fn decide_text(text: &str) {
    let file = load_str("bench.toml", text).expect("valid");
    for c in &file.claims {
        black_box(decide_claim(c).expect("decides"));
    }
}

fn main() {
    // `cargo bench --bench bench -- --claim ID`: the median time to decide one claim of
    // the paper (and its correction), in process, in milliseconds (used by
    // benches/sympy_compare.py).
    let args: Vec<String> = std::env::args().collect();
    if let Some(k) = args.iter().position(|a| a == "--claim") {
        let id = args.get(k + 1).expect("--claim ID");
        let files = corpus();
        let claim = files
            .iter()
            .flat_map(|f| &f.claims)
            .find(|c| &c.id == id)
            .expect("a known claim id");
        let t = median_ms(15, || {
            black_box(decide_claim(claim).unwrap());
        });
        println!("{t:.3}");
        return;
    }
    // `-- --task NAME REPS`: each repetition's time in milliseconds, one per line, for
    // benches/peers.py (NAME: a claim id, decided with its correction; `rank6`, `rank8`
    // or `rank10`, the isotropic moment identity of that rank in 3D and its mutant read and decided; `a2`,
    // Q, D^(ep) and the four A² of the Appendix file derived together, as the peers do it
    // (`a2-apart`: each A² derived from scratch); `gcd`, the gcds of [`GCD_PAIRS`] pairs with a
    // known common factor ([`gcd_pairs`]); `products`, 200 products of the tight-loop
    // comparison's two polynomials, for profiling the kernel).
    if let Some(k) = args.iter().position(|a| a == "--task") {
        let name = args.get(k + 1).expect("--task NAME REPS");
        let reps: usize = args
            .get(k + 2)
            .and_then(|r| r.parse().ok())
            .expect("--task NAME REPS");
        let files = corpus();
        let mut run: Box<dyn FnMut()> = match name.as_str() {
            "products" => {
                let (pa, pb, _, _) = product_operands();
                Box::new(move || {
                    for _ in 0..200 {
                        black_box(&pa * &pb);
                    }
                })
            }
            "gcd" => {
                let pairs = gcd_pairs();
                Box::new(move || {
                    for (a, b, g) in &pairs {
                        let d = gcd::gcd(a, b);
                        assert!(
                            gcd::divide_exact(&d, g).is_some(),
                            "g divides gcd(g·a, g·b)"
                        );
                    }
                })
            }
            "a2" => {
                let probe = a2_probe();
                Box::new(move || {
                    black_box(probe.exact_each().unwrap());
                })
            }
            "a2-apart" => {
                let probes = a2_probes();
                Box::new(move || {
                    for p in &probes {
                        black_box(p.exact().unwrap());
                    }
                })
            }
            rank if rank.starts_with("rank") => {
                let text = moment_identity(3, rank[4..].parse().expect("rankN"));
                Box::new(move || decide_text(&text))
            }
            id => {
                let claim = files
                    .iter()
                    .flat_map(|f| &f.claims)
                    .find(|c| c.id == id)
                    .expect("a known claim id");
                Box::new(move || {
                    black_box(decide_claim(claim).unwrap());
                })
            }
        };
        for _ in 0..reps {
            let t = Instant::now();
            run();
            println!("{:.4}", t.elapsed().as_secs_f64() * 1e3);
        }
        return;
    }
    // `-- --each`: every claim's median time (with its correction), slowest first: the
    // profile of the whole paper by claim.
    if args.iter().any(|a| a == "--each") {
        let files = corpus();
        let mut times: Vec<(f64, &str)> = files
            .iter()
            .flat_map(|f| &f.claims)
            .map(|c| {
                let t = median_ms(5, || {
                    black_box(decide_claim(c).unwrap());
                });
                (t, c.id.as_str())
            })
            .collect();
        times.sort_by(|a, b| b.0.total_cmp(&a.0));
        let total: f64 = times.iter().map(|t| t.0).sum();
        println!("| claim | median |\n|---|---|");
        for (t, id) in &times {
            println!("| {id} | {t:.2} ms |");
        }
        println!(
            "| all {} claims, one after another | {total:.1} ms |",
            times.len()
        );
        return;
    }
    // `-- --derive-a2`: the median time of the A² derivation of the Appendix file
    // (used by benches/sympy_compare.py).
    if args.iter().any(|a| a == "--derive-a2") {
        let t = median_ms(15, || {
            black_box(derive_a2());
        });
        println!("{t:.3}");
        return;
    }
    let mut rows: Vec<(String, String)> = Vec::new();
    let files = corpus();
    let whole = median_ms(3, || {
        black_box(decide_all(&corpus(), None).unwrap());
    });
    rows.push((
        "whole paper: read + decide every claim".into(),
        format!("{whole:.1} ms"),
    ));
    let read = median_ms(5, || {
        black_box(corpus());
    });
    rows.push((
        "read and validate the derivation files (no deciding)".into(),
        format!("{read:.1} ms"),
    ));
    let exact_only: Vec<_> = files
        .iter()
        .flat_map(|f| &f.claims)
        .filter(|c| matches!(c.check.strategy, Strategy::Exact { .. }))
        .collect();
    let exact = median_ms(9, || {
        for c in &exact_only {
            black_box(decide_claim(c).unwrap());
        }
    });
    rows.push((
        format!("the {} exact claims (decide only)", exact_only.len()),
        format!("{exact:.1} ms"),
    ));
    for c in files
        .iter()
        .flat_map(|f| &f.claims)
        .filter(|c| !matches!(c.check.strategy, Strategy::Exact { .. }))
    {
        let t = median_ms(3, || {
            black_box(decide_claim(c).unwrap());
        });
        let strategy = match &c.check.strategy {
            Strategy::Numeric { .. } => "numeric",
            Strategy::Gradient { .. } => "gradient",
            Strategy::Convex { .. } => "convex",
            Strategy::NotCircle { .. } => "witness",
            Strategy::Scalar { .. } => "rational-function",
            Strategy::Exact { .. } => "exact",
            Strategy::Proportional { .. } => "proportional",
        };
        rows.push((format!("claim {} ({strategy})", c.id), format!("{t:.1} ms")));
    }
    for dim in [2, 3] {
        for rank in [2, 4, 6, 8, 10] {
            let text = moment_identity(dim, rank);
            let t = median_ms(9, || decide_text(&text));
            rows.push((
                format!("exact: isotropic moment identity and a refuted mutant (one pairing dropped), rank {rank}, {dim}D, read and decided"),
                format!("{t:.2} ms"),
            ));
        }
    }
    for k in 1..=4 {
        let text = degree_identity(k);
        let t = median_ms(5, || decide_text(&text));
        rows.push((
            format!(
                "exact: ⟨(a·n)^{}⟩ identity, degree {} in n and a",
                2 * k,
                2 * k
            ),
            format!("{t:.2} ms"),
        ));
    }
    let (ours, tight) = term_products();
    rows.push((
        format!("exact kernel: one term product, `Poly × Poly` ({TIGHT_TERMS}×{TIGHT_TERMS} terms, {TIGHT_VARS} variables, rational coefficients)"),
        format!("{ours:.1} ns"),
    ));
    rows.push((
        format!("tight-loop estimate of the same products (exponents packed in one u64, integer coefficients over a common denominator, FxHash accumulation): {:.1}× faster", ours / tight),
        format!("{tight:.1} ns"),
    ));
    let moments = median_ms(9, || {
        for total in 0..=12u32 {
            for a in 0..=total {
                for b in 0..=total - a {
                    black_box(monomial_moment(3, &[a, b, total - a - b]));
                }
            }
        }
    });
    rows.push((
        "exact moments: every 3D monomial of order ≤ 12 (455)".into(),
        format!("{moments:.2} ms"),
    ));
    if let Some(g) = files
        .iter()
        .flat_map(|f| &f.claims)
        .find(|c| c.id == "grad-F2")
    {
        let samples = match &g.check.strategy {
            Strategy::Gradient { sampling, .. } => sampling.samples,
            _ => 1,
        };
        let t = median_ms(5, || {
            black_box(decide_claim(g).unwrap());
        });
        rows.push((
            "num-dual gradient of F2 (per sample: gradient, closed form, a central difference along a mixed direction)"
                .into(),
            format!("{:.0} samples/s", samples as f64 / (t / 1e3)),
        ));
    }
    let derive = median_ms(9, || {
        black_box(derive_a2());
    });
    rows.push((
        "A² derivation of derivations/A-3-shear-band.toml (Q by grad, D^(ep), A² in four variants, exact rational functions)".into(),
        format!("{derive:.2} ms"),
    ));
    // The user's view: a fresh process reading and deciding the whole paper (the
    // in-process medians above reuse the Appendix derivation computed on first use).
    let exe = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/release/cosserat-check");
    if exe.exists() {
        let t = median_ms(3, || {
            let out = std::process::Command::new(&exe)
                .arg("check")
                .current_dir(env!("CARGO_MANIFEST_DIR"))
                .output()
                .expect("the binary runs");
            black_box(out);
        });
        rows.push((
            "whole paper, fresh process (target/release/cosserat-check check)".into(),
            format!("{t:.1} ms"),
        ));
    }
    println!("| benchmark | median |\n|---|---|");
    for (k, v) in rows {
        println!("| {k} | {v} |");
    }
}

/// The four A² of the Appendix file: derived, correctly signed, (61), (54).
const A2_EXPRESSIONS: [&str; 4] = ["A2", "A2c", "A2eq61", "A2eq54"];

/// The Appendix file's text, and the box every probe of it needs.
fn appendix() -> (String, [String; 2]) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("derivations/A-3-shear-band.toml");
    let text = std::fs::read_to_string(&path).expect("the Appendix file");
    (text, ["f_r > 0", "sig < 0"].map(str::to_owned))
}

/// The four A² as one probe: the file read and checked, nothing evaluated yet.
fn a2_probe() -> Probe {
    let (text, given) = appendix();
    Probe::of_each("A-3", &text, &A2_EXPRESSIONS, &["u = 1".to_owned()], &given).unwrap()
}

/// The four A² as four probes: the file read and checked, nothing evaluated yet.
fn a2_probes() -> Vec<Probe> {
    let (text, given) = appendix();
    A2_EXPRESSIONS
        .iter()
        .map(|e| Probe::new("A-3", &text, e, &["u = 1".to_owned()], &given).unwrap())
        .collect()
}

/// Q at the Appendix's state by grad(F₂, σ), D^(ep), and the four A² of the Appendix
/// file, each read and reduced from scratch.
fn derive_a2() -> Vec<String> {
    a2_probes()
        .iter()
        .map(|probe| {
            let (f, names) = probe.exact().unwrap();
            f.display(&names)
        })
        .collect()
}
