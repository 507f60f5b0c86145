//! The transcription check (issue 15): the reader of printed LaTeX on each construct and
//! each refusal, the notation table, the statuses, and the paper: which claims are
//! machine-read, and that a mutated side makes a machine-read claim `differs`.

use crate::support::mutate::mutants;
use cosserat_check::check::transcription::{transcribe, Hand, Status, Why};
use cosserat_check::check::{decide, Decided};
use cosserat_check::cli::decide_all;
use cosserat_check::derivation::{load_dir, load_str, Strategy, Transcript, Verdict};
use cosserat_check::lang::latex::{read, Connective, MathKind, ReadOptions, Rel};
use std::path::Path;

fn parts(src: &str) -> Vec<(Vec<String>, Vec<Rel>)> {
    read(src, &ReadOptions::default())
        .unwrap_or_else(|e| panic!("{src}: {}", e.message))
        .parts
        .iter()
        .map(|p| {
            let shapes = p.members.iter().map(|m| format!("{:?}", m.kind)).collect();
            (shapes, p.relations.clone())
        })
        .collect()
}

/// The column (1-based) and message of a refusal.
fn refusal(src: &str) -> (usize, String) {
    let e = read(src, &ReadOptions::default()).expect_err(src);
    (e.column(src), e.message)
}

#[test]
fn the_reader_reads_each_construct() {
    let one = |src: &str| {
        let p =
            read(src, &ReadOptions::default()).unwrap_or_else(|e| panic!("{src}: {}", e.message));
        assert_eq!(p.parts.len(), 1, "{src}");
        p.parts[0].members[0].kind.clone()
    };
    // Sub- and superscripts: a number is a power, anything else a label.
    let MathKind::Atom(a) = one(r"\sigma_{ij}^{(1)}") else {
        panic!()
    };
    assert_eq!(
        (
            a.base.as_str(),
            a.sub.unwrap().text.as_str(),
            a.sup.unwrap().text.as_str()
        ),
        (r"\sigma", "ij", "(1)")
    );
    let MathKind::Atom(a) = one(r"D^{(ep)}_{ijkl}") else {
        panic!()
    };
    assert_eq!(
        (a.sub.unwrap().text, a.sup.unwrap().text),
        ("ijkl".to_owned(), "(ep)".to_owned())
    );
    assert!(matches!(one("x^2"), MathKind::Power(..)));
    assert!(matches!(one("(M^c)^2"), MathKind::Power(..)));
    let MathKind::Atom(a) = one(r"\dot\sigma_{ij}") else {
        panic!()
    };
    assert_eq!(a.accent.as_deref(), Some(r"\dot"));
    let MathKind::Atom(a) = one("v_2''") else {
        panic!()
    };
    assert_eq!(a.primes, 2);
    let MathKind::Atom(a) = one("w_{i,m}^c") else {
        panic!()
    };
    assert_eq!(a.sub.unwrap().text, "i,m");
    let MathKind::Atom(a) = one(r"\mu_\tau") else {
        panic!()
    };
    assert_eq!(a.sub.unwrap().text, r"\tau");
    // Fractions, roots, averages, bars, brackets, functions.
    assert!(matches!(one(r"\frac{1}{3}"), MathKind::Quotient(..)));
    assert!(matches!(one(r"\tfrac12"), MathKind::Quotient(..)));
    assert!(matches!(one(r"\sqrt{q^2 + 2r^2}"), MathKind::Sqrt(_)));
    assert!(matches!(
        one(r"\langle n_i n_j \rangle"),
        MathKind::Average(_)
    ));
    assert!(matches!(one("|a_1 n_2|"), MathKind::Abs(_)));
    assert!(matches!(one(r"\left( a + b \right)"), MathKind::Sum(_)));
    assert!(matches!(one(r"\cos \phi"), MathKind::Apply(..)));
    assert!(matches!(
        one(r"\begin{pmatrix} a & b \\ c & d \end{pmatrix}"),
        MathKind::Matrix(_)
    ));
    assert!(matches!(one("(0, v_2', -w_3)"), MathKind::Tuple(_)));
    // Both forms of a partial derivative.
    assert!(matches!(
        one(r"\partial T^2 / \partial \sigma_{ij}"),
        MathKind::Partial { .. }
    ));
    assert!(matches!(
        one(r"\frac{\partial F_2}{\partial \mu_{i3}}"),
        MathKind::Partial { .. }
    ));
    // Implicit products, and the slash convention: 2R_g S/3V is (2 R_g S)/(3 V).
    let MathKind::Quotient(num, den) = one("2R_g S/3V") else {
        panic!()
    };
    assert!(
        matches!((&num.kind, &den.kind), (MathKind::Product(n), MathKind::Product(d)) if n.len() == 3 && d.len() == 2)
    );
    // Chains, separators and words.
    let p = parts(r"a = b \le c");
    assert_eq!(p[0].1, vec![Rel::Eq, Rel::Le]);
    let printed = read(
        r"a = b, \quad c = d \text{ with } e = f \Rightarrow g > h \text{ at incipient failure}",
        &ReadOptions::default(),
    )
    .unwrap();
    let before: Vec<&Connective> = printed.parts.iter().map(|p| &p.before).collect();
    assert_eq!(
        before,
        [
            &Connective::First,
            &Connective::Comma,
            &Connective::Words("with".into()),
            &Connective::Implies
        ]
    );
    assert_eq!(printed.trailing.as_deref(), Some("at incipient failure"));
    // Spacing commands are ignored.
    assert_eq!(parts(r"a\,b = c\!d")[0].0.len(), 2);
}

#[test]
fn the_reader_refuses_what_is_outside_the_subset_where_it_stands() {
    for (src, col, words) in [
        (r"\lim_{x \to 0} f = 1", 1, r"`\lim`"),
        (r"\sum_i a_i = 0", 1, r"`\sum`"),
        (r"\overline{AM} = r", 1, r"`\overline`"),
        (r"x = \pm y", 5, r"\pm"),
        (r"a \neq b", 3, r"`\neq`"),
        (r"\frac{d}{d x} y = 0", 1, "ordinary derivative"),
        (r"h(\theta = 0) = 1", 10, "relation inside brackets"),
        (r"x = \text{const}", 5, "expected an expression"),
        ("a/b/c = d", 1, "two ways"),
        ("w_3(y) = 0", 1, "function application"),
        (
            r"\theta = \theta(x_1, x_2)",
            10,
            "function application f(x, y)",
        ),
        (r"\frac{1}{2 = x", 9, "never closed"),
        ("", 1, "empty"),
        ("a = b;", 6, "unexpected `;`"),
        (r"\sqrt[3]{x} = y", 1, "square roots"),
        (r"a = b,", 6, "ends with a separator"),
    ] {
        let (c, m) = refusal(src);
        assert!(m.contains(words), "{src}: {m}");
        assert_eq!(c, col, "{src}: {m}");
    }
    // Deep nesting is refused, not a stack overflow; a statement with a multi-byte space
    // before the error still gets its column.
    let deep = format!("{}x{} = 1", "(".repeat(10_000), ")".repeat(10_000));
    assert!(refusal(&deep).1.contains("nested more than 64 deep"));
    assert_eq!(
        refusal("a = b,\u{3000}"),
        (8, "the statement ends with a separator".to_owned())
    );
}

const FILE: &str = r#"section = "t"
title = "t"
dimension = 3
normal = "n"
tensors = ["sigma_ij", "mu_ij"]
scalars = ["R_g", "x"]
define = ["s_ij = sigma_ij - sigma_kk / 3 delta_ij", "t_i = sigma_ki n_k", "tt_i = t_i - t_j n_j n_i"]

[notation]
'\sigma_{ij}^{(1)}' = "sigma_ij"
't_i^{(t)}' = "tt_i"
'T^2' = "avg(tt_k tt_k)"
'S' = ["s_kk", "0"]
"#;

fn file(claims: &str) -> cosserat_check::derivation::DerivationFile {
    load_str("f.toml", &format!("{FILE}\n{claims}")).unwrap_or_else(|e| panic!("{e}"))
}

fn statuses(claims: &str) -> Vec<(String, Status, bool)> {
    let f = file(claims);
    decide_all(std::slice::from_ref(&f), None)
        .unwrap()
        .into_iter()
        .map(|r: Decided<'_>| {
            (
                r.claim.id.clone(),
                r.transcription.status.clone(),
                r.as_expected(),
            )
        })
        .collect()
}

fn reading(claims: &str) -> Vec<Vec<String>> {
    let f = file(claims);
    let r = f.claims[0]
        .transcript
        .reading
        .as_ref()
        .unwrap_or_else(|u| panic!("{}", u.message));
    r.parts
        .iter()
        .flat_map(|p| {
            p.routes
                .iter()
                .map(|route| route.iter().map(|m| m.text.clone()).collect())
        })
        .collect()
}

#[test]
fn the_notation_table_binds_pattern_variables_and_renames_summed_indices_apart() {
    let got = reading(
        r#"[[claim]]
id = "c"
printed = 'T^2 t_k^{(t)} = \sigma_{ki}^{(1)} \sigma_{21}^{(1)} R_g^2 \langle n_k \rangle'
expect = "holds"
sides = ["0", "0"]
"#,
    );
    // T^2's own k is renamed apart from the statement's k; i, 2, 1 are bound.
    assert_eq!(got[0][0], "avg(tt_a tt_a) tt_k");
    assert_eq!(got[0][1], "sigma_ki sigma_21 R_g^2 avg(n_k)");
    // Several readings of one symbol: the chain is read once per reading.
    let got = reading(
        r#"[[claim]]
id = "c"
printed = 'S = 0'
expect = "holds"
sides = ["0", "0"]
"#,
    );
    assert_eq!(
        got,
        vec![
            vec!["s_aa".to_owned(), "0".to_owned()],
            vec!["0".to_owned(), "0".to_owned()]
        ]
    );
}

#[test]
fn a_symbol_without_a_reading_is_refused_with_its_column() {
    let f = file(
        r#"[[claim]]
id = "c"
printed = 'x = \sigma_{ij}^{(2)} + y'
expect = "holds"
sides = ["x", "x"]
"#,
    );
    let u = f.claims[0].transcript.reading.as_ref().unwrap_err();
    assert!(u.message.contains("label"), "{}", u.message);
    assert_eq!(u.span.start, 4);
}

#[test]
fn statuses_machine_read_differs_declared_stale_hand_and_conditions() {
    let got = statuses(
        r#"[[claim]]
id = "read"
printed = 'T^2 = \langle t_k^{(t)} t_k^{(t)} \rangle'
expect = "holds"
sides = ["avg(tt_k tt_k)", "avg(tt_k tt_k)"]

[[claim]]
id = "coefficient"
printed = '\langle n_i n_j \rangle = \frac{1}{3} \delta_{ij}'
expect = "holds"
sides = ["avg(n_i n_j)", "1/3 delta_ij"]

[[claim]]
id = "changed-coefficient"
printed = '\langle n_i n_j \rangle = x \delta_{ij} + \frac{1}{5} \delta_{ij}'
expect = "holds"
sides = ["avg(n_i n_j)", "x delta_ij + 1/3 delta_ij"]

[[claim]]
id = "declared"
printed = '\langle n_i n_j \rangle = \frac{1}{5} \delta_{ij}'
expect = "holds"
differs_from_printed = "a test"
sides = ["avg(n_i n_j)", "1/3 delta_ij"]

[[claim]]
id = "stale"
printed = '\langle n_i n_j \rangle = \frac{1}{3} \delta_{ij}'
expect = "holds"
differs_from_printed = "a test"
sides = ["avg(n_i n_j)", "1/3 delta_ij"]

[[claim]]
id = "prose"
printed = 'the average is isotropic'
prose = true
expect = "holds"
sides = ["avg(n_i n_j)", "1/3 delta_ij"]

[[claim]]
id = "swapped"
printed = '\sigma_{ji}^{(1)} n_j = t_i'
expect = "fails"
reason = "a test"
sides = ["sigma_ij n_j", "t_i"]

[[claim]]
id = "condition"
printed = 'x^2 > 0 \text{ for } x > 0'
strategy = "sign"
relation = ">"
given = ["x > 0"]
expect = "holds"
sides = ["x^2", "0"]

[[claim]]
id = "missing-condition"
printed = 'x^2 > 0 \text{ for } x < 0'
strategy = "sign"
relation = ">"
given = ["x > 0"]
expect = "holds"
sides = ["x^2", "0"]
"#,
    );
    let status = |id: &str| got.iter().find(|(i, _, _)| i == id).unwrap();
    assert!(matches!(status("read").1, Status::MachineRead { .. }) && status("read").2);
    assert!(matches!(
        status("coefficient").1,
        Status::MachineRead { .. }
    ));
    // A changed coefficient: differs at the term 1/5 δ_ij, not as expected.
    match &status("changed-coefficient").1 {
        Status::Differs {
            span,
            why: Why::Value(_),
            ..
        } => {
            assert_eq!(
                span.start,
                r"\langle n_i n_j \rangle = x \delta_{ij} + ".len()
            )
        }
        other => panic!("{other:?}"),
    }
    assert!(!status("changed-coefficient").2);
    assert!(
        matches!(
            status("declared").1,
            Status::Differs {
                declared: Some(_),
                ..
            }
        ) && status("declared").2
    );
    assert!(
        matches!(
            status("stale").1,
            Status::MachineRead { stale: Some(_), .. }
        ) && !status("stale").2
    );
    assert!(matches!(
        status("prose").1,
        Status::Hand {
            reason: Hand::Prose
        }
    ));
    assert!(matches!(status("swapped").1, Status::Differs { .. }));
    assert!(
        matches!(status("condition").1, Status::MachineRead { .. }),
        "{:?}",
        status("condition").1
    );
    assert!(matches!(
        status("missing-condition").1,
        Status::Differs {
            why: Why::Condition,
            ..
        }
    ));
}

#[test]
fn a_bad_notation_entry_is_a_located_input_error() {
    let text = format!("{FILE}'\\frac{{a}}{{b}}' = \"x\"\n");
    let e = load_str("f.toml", &text).expect_err("refused").to_string();
    assert!(e.contains("f.toml:14:17"), "{e}");
    assert!(e.contains("is not a symbol or a power of one"), "{e}");
}

fn paper() -> Vec<cosserat_check::derivation::DerivationFile> {
    load_dir(&Path::new(env!("CARGO_MANIFEST_DIR")).join("derivations")).unwrap()
}

/// The paper's formula claims that are not machine-read are exactly those the README
/// lists, with the status it gives; every other formula claim is machine-read.
#[test]
fn the_paper_is_machine_read_except_where_the_readme_says_why() {
    let files = paper();
    let rows = decide_all(&files, None).unwrap();
    let readme = cosserat_check::cli::GUIDE.join("\n");
    let listed: Vec<(String, String)> = readme
        .lines()
        .filter(|l| l.starts_with("| `"))
        .filter_map(|l| {
            let cells: Vec<&str> = l.split(" | ").collect();
            let id = cells[0].trim_start_matches("| `").trim_end_matches('`');
            let status = cells.get(1)?.split_whitespace().next()?;
            rows.iter()
                .any(|r| r.claim.id == id)
                .then(|| (id.to_owned(), status.to_owned()))
        })
        .collect();
    let mut machine = 0;
    let mut formulas = 0;
    for r in &rows {
        assert!(
            r.as_expected(),
            "{}: {:?}",
            r.claim.id,
            r.transcription.status
        );
        if r.claim.prose {
            continue;
        }
        formulas += 1;
        let label = r.transcription.label();
        match listed.iter().find(|(id, _)| *id == r.claim.id) {
            Some((_, status)) => assert_eq!(label, status, "{}", r.claim.id),
            None => {
                assert_eq!(
                    label, "machine-read",
                    "{}: {:?}",
                    r.claim.id, r.transcription.status
                );
                machine += 1;
            }
        }
    }
    assert_eq!(listed.len() + machine, formulas);
    assert!(machine >= 43, "{machine} of {formulas}");
    assert!(readme.contains(&format!(
        "{machine} of its {formulas} formula claims are `machine-read`"
    )));
}

/// Every machine-read claim of the paper turns `differs` when one of its sides is
/// mutated (a changed coefficient, swapped indices, a flipped sign, a dropped term),
/// unless the engine proves the mutant equal to the original side (an equivalent
/// mutant, such as two summed indices swapped).
#[test]
fn mutated_sides_of_the_paper_make_its_transcriptions_differ() {
    let files = paper();
    let mut refuted = 0;
    let mut equivalent = 0;
    let mut kinds = std::collections::BTreeSet::new();
    for claim in files.iter().flat_map(|f| &f.claims) {
        let t = transcribe(&claim.decls, &claim.check, &claim.transcript);
        if !matches!(t.status, Status::MachineRead { .. }) {
            continue;
        }
        let mut claim_refuted = 0;
        for (ci, chain) in claim.transcript.written.iter().enumerate() {
            for (si, side) in chain.iter().enumerate() {
                for m in mutants(side).into_iter().take(6) {
                    let exact = Strategy::Exact {
                        domain: Default::default(),
                        hypotheses: Vec::new(),
                    };
                    let same = claim
                        .check
                        .comparing(&claim.decls, side, &m.text, exact)
                        .ok()
                        .and_then(|c| decide(&claim.decls, &c).ok())
                        .is_some_and(|o| o.verdict() == cosserat_check::derivation::Verdict::Holds);
                    let mut written = claim.transcript.written.clone();
                    written[ci][si] = m.text.clone();
                    let mutated = Transcript {
                        written,
                        ..claim.transcript.clone()
                    };
                    let status = transcribe(&claim.decls, &claim.check, &mutated).status;
                    if same {
                        equivalent += 1;
                        continue;
                    }
                    assert!(
                        !matches!(status, Status::MachineRead { .. }),
                        "{}: the mutant `{}` ({}) still reads as the printed statement",
                        claim.id,
                        m.text,
                        m.kind
                    );
                    refuted += 1;
                    claim_refuted += 1;
                    kinds.insert(m.kind);
                }
            }
        }
        if !claim.transcript.written.is_empty() {
            assert!(claim_refuted > 0, "{}: no mutant refuted", claim.id);
        }
    }
    eprintln!("{refuted} mutants refuted, {equivalent} equivalent");
    assert!(kinds.len() >= 4, "kinds refuted: {kinds:?}");
    assert!(refuted >= 200, "{refuted} refuted, {equivalent} equivalent");
}

/// Without `sides`, a readable printed statement is decided on the reading itself: the
/// identity holds, its wrong twin fails, and the status says there was nothing to compare.
#[test]
fn a_claim_without_sides_is_decided_on_its_reading() {
    let f = file(
        r#"[[claim]]
id = "isotropic"
printed = '\langle n_i n_j \rangle = \frac{1}{3} \delta_{ij}'
expect = "holds"

[[claim]]
id = "isotropic-wrong"
printed = '\langle n_i n_j n_k n_l \rangle = \frac{1}{3} (\delta_{ij} \delta_{kl} + \delta_{ik} \delta_{jl} + \delta_{il} \delta_{jk})'
expect = "fails"
reason = "The factor is 1/15."
"#,
    );
    let rows = decide_all(std::slice::from_ref(&f), None).unwrap();
    for r in &rows {
        assert!(r.as_expected(), "{}", r.claim.id);
        assert!(matches!(
            r.transcription.status,
            Status::MachineRead {
                from_reading: true,
                ..
            }
        ));
    }
    assert_eq!(
        rows[0].outcome.verdict(),
        cosserat_check::derivation::Verdict::Holds
    );
    let cx = rows[1]
        .outcome
        .counterexample
        .as_ref()
        .expect("a counterexample");
    assert_eq!(cx.lhs_value.as_deref(), Some("1/5"));
}

/// A correction without `sides` is decided on its reading too, with the claim's
/// `defines`: the wrong printed step fails, the corrected one holds, and a wrong
/// correction fails as well (it is checked, not believed).
#[test]
fn a_correction_without_sides_is_decided_on_its_reading() {
    let claim = |corrected: &str, expect: &str| {
        format!(
            r#"[[claim]]
id = "trace"
printed = 'P = \sigma_{{kk}} = 2 \sigma_{{11}}'
defines = ['P']
expect = "fails"
reason = "a typo: the trace has three terms"
[claim.correction]
printed = '{corrected}'
reason = "the trace"
expect = "{expect}"
"#
        )
    };
    for (corrected, verdict) in [
        (
            r"P = \sigma_{kk} = \sigma_{11} + \sigma_{22} + \sigma_{33}",
            Verdict::Holds,
        ),
        (
            r"P = \sigma_{kk} = \sigma_{11} + \sigma_{22}",
            Verdict::Fails,
        ),
    ] {
        let expect = if verdict == Verdict::Holds {
            "holds"
        } else {
            "fails"
        };
        let f = file(&claim(corrected, expect));
        let rows = decide_all(std::slice::from_ref(&f), None).unwrap();
        assert_eq!(rows[0].outcome.verdict(), Verdict::Fails);
        let c = rows[0]
            .correction
            .as_ref()
            .expect("the correction is decided");
        assert_eq!(c.verdict(), verdict, "{corrected}");
        let words = cosserat_check::report::evidence(c);
        let want = if verdict == Verdict::Holds {
            "every difference identically 0"
        } else {
            "left − right = `sigma_33`"
        };
        assert!(words.contains(want), "{words}");
    }
}

/// Sides typeset as LaTeX, for a reader to compare with the printed statement.
#[test]
fn sides_are_typeset_as_latex() {
    use cosserat_check::report::typeset::{chain, latex};
    assert_eq!(latex("avg(n_i n_j)"), r"\langle n_{i} \, n_{j} \rangle");
    assert_eq!(latex("1/15 delta_ij"), r"\frac{1}{15} \, \delta_{ij}");
    assert_eq!(
        latex("sqrt(q2 + 2 r2)"),
        r"\sqrt{\mathrm{q2} + 2 \, \mathrm{r2}}"
    );
    assert_eq!(latex("(a - b)^2"), r"{\left( a - b \right)}^{2}");
    assert_eq!(
        latex("eps_ijk sigma_jk,i"),
        r"\varepsilon_{ijk} \, {\sigma_{jk}}_{,i}"
    );
    assert_eq!(latex("a - (b - c)"), r"a - \left( b - c \right)");
    assert_eq!(
        latex("grad(F2, sigma_ij)"),
        r"\frac{\partial \mathrm{F2}}{\partial \sigma_{ij}}"
    );
    assert_eq!(chain(&["x".into(), "R_g".into()]), "x = R_{g}");
    // An ill-formed side is still shown, as text.
    assert_eq!(latex("a +"), r"\texttt{a +}");
}

/// A gradient claim's closed forms are typeset as ∂F/∂x = G, with x's free indices.
#[test]
fn gradient_closed_forms_are_typeset() {
    let files = paper();
    let claim = files
        .iter()
        .flat_map(|f| &f.claims)
        .find(|c| c.id == "grad-F1")
        .unwrap();
    let typeset = cosserat_check::report::typeset::checked(&claim.check, &claim.transcript);
    assert!(
        typeset.contains(
            &r"\frac{\partial \left( \mathrm{F1} \right)}{\partial \mu_{ij}} = 0 \, \mu_{ij}"
                .to_owned()
        ),
        "{typeset:?}"
    );
}

/// A printed chain whose comparison passes a resource limit is read by hand: an
/// undecided comparison is no evidence that the sides differ.
#[test]
fn an_undecided_comparison_is_hand_not_differs() {
    let got = statuses(
        r#"[[claim]]
id = "beside-a-huge-power"
printed = 'x = x \text{ with } ((x/31^{64})^{64})^{64} = 1 \cdot ((x/31^{64})^{64})^{64}'
expect = "holds"
sides = ["x", "x"]
"#,
    );
    assert!(
        matches!(
            got[0].1,
            Status::Hand {
                reason: Hand::Undecided { .. }
            }
        ),
        "{:?}",
        got[0].1
    );
    assert!(got[0].2);
}

#[test]
fn a_correction_inherits_the_defines_of_its_claim() {
    let f = file(
        r#"[[claim]]
id = "defined"
printed = 'S = \sigma_{kk} - 1 = s_{kk}'
defines = ['S']
expect = "fails"
reason = "a test"
sides = ["sigma_kk - 1", "s_kk"]
correction = { printed = 'S = s_{kk} = 0', sides = ["s_kk", "0"], reason = "a test", expect = "holds" }
"#,
    );
    let rows = decide_all(std::slice::from_ref(&f), None).unwrap();
    let corrected = rows[0]
        .correction_transcription
        .as_ref()
        .expect("a correction");
    assert!(
        matches!(corrected.status, Status::MachineRead { .. }),
        "{:?}",
        corrected.status
    );
}
