//! Assumptions are one exact linear system over the components: the verdict does not
//! depend on the order they are written in, contradictions are input errors naming the
//! assumptions that clash, and rank-4 symmetries are expressible (issue: order-free
//! assumptions). The derivation files under `tests/soundness/` hold the true verdicts.

use cosserat_check::check::decide_claim;
use cosserat_check::derivation::parametrisation::{Constrained, Parametrisation};
use cosserat_check::derivation::{load_files, load_str};
use std::path::PathBuf;

fn soundness_file(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/soundness")
        .join(name)
}

#[test]
fn every_claim_gets_its_true_verdict_whatever_the_order_of_its_assumptions() {
    let files = load_files(&[soundness_file("assumption-order.toml")]).unwrap();
    let mut decided = 0;
    for claim in files.iter().flat_map(|f| &f.claims) {
        let d = decide_claim(claim).unwrap_or_else(|e| panic!("{}: {e}", claim.id));
        assert_eq!(d.outcome.verdict(), claim.expect, "{}", claim.id);
        decided += 1;
    }
    assert_eq!(decided, 13);
}

const HEADER: &str = "section = \"t\"\ntitle = \"t\"\ndimension = 3\ntensors = [\"eta_ij\", \"C_ijkl\"]\nscalars = [\"S\", \"V\", \"T\"]\n";

fn error_of(claim: &str) -> String {
    let text =
        format!("{HEADER}\n[[claim]]\nid = \"x\"\nprinted = 'x'\nexpect = \"holds\"\n{claim}\n");
    let file = load_str("t.toml", &text).unwrap();
    decide_claim(&file.claims[0]).unwrap_err().to_string()
}

#[test]
fn contradictory_assumptions_are_an_input_error_naming_both() {
    let err =
        error_of("assume = [\"eta_11 = 5\", \"antisymmetric(eta)\"]\nsides = [\"eta_11\", \"5\"]");
    assert!(
        err.contains("contradict each other")
            && err.contains("`eta_11 = 5`")
            && err.contains("`antisymmetric(eta)`"),
        "{err}"
    );
    // The contradiction is found through a chain of symmetries too.
    let err = error_of(
        "assume = [\"C_ijkl = C_jikl\", \"C_ijkl = C_klij\", \"C_1211 = 1\", \"C_1121 = 2\"]\nsides = [\"C_1111\", \"C_1111\"]",
    );
    assert!(err.contains("contradict each other"), "{err}");
    assert!(
        err.contains("`C_1211 = 1`") && err.contains("`C_1121 = 2`"),
        "{err}"
    );
}

#[test]
fn consistent_redundant_assumptions_are_accepted() {
    let text = format!(
        "{HEADER}\n[[claim]]\nid = \"x\"\nprinted = 'x'\nexpect = \"holds\"\nassume = [\"symmetric(eta)\", \"eta_12 = 3\", \"eta_21 = 3\"]\nsides = [\"eta_21\", \"3\"]\n"
    );
    let file = load_str("t.toml", &text).unwrap();
    assert!(decide_claim(&file.claims[0]).is_ok());
}

#[test]
fn substitutions_in_a_cycle_or_twice_are_refused() {
    let err = error_of("assume = [\"S = V T / T^2 + T\", \"T = S^2\"]\nsides = [\"S\", \"S\"]");
    assert!(err.contains("cycle"), "{err}");
    let err = error_of("assume = [\"S = V^2\", \"S = 1/V\"]\nsides = [\"S\", \"S\"]");
    assert!(err.contains("already replaced"), "{err}");
}

#[test]
fn a_component_assumption_must_be_a_polynomial() {
    let err =
        error_of("assume = [\"eta_11 = 1 / (1 + eta_22)\"]\nsides = [\"eta_11\", \"eta_11\"]");
    assert!(err.contains("polynomial"), "{err}");
    // A product of other components is a polynomial: they become parameters.
    let text = format!("{HEADER}\n[[claim]]\nid = \"x\"\nprinted = 'x'\nexpect = \"holds\"\nassume = [\"eta_11 = eta_22 eta_33\"]\nsides = [\"eta_11\", \"eta_22 eta_33\"]\n");
    let file = load_str("t.toml", &text).unwrap();
    let claim = &file.claims[0];
    let p =
        Parametrisation::new(&claim.decls, &claim.check.defs, &claim.check.assumptions).unwrap();
    assert_eq!(p.constrained("eta", &[0, 0]), Constrained::Dependent);
    assert_eq!(p.constrained("eta", &[1, 1]), Constrained::Free);
    assert_eq!(decide_claim(claim).unwrap().outcome.verdict(), claim.expect);
}

#[test]
fn elasticity_tensor_symmetries_leave_21_and_6_independent_components() {
    for (dim, free) in [(3, 21), (2, 6)] {
        let text = format!(
            "section = \"t\"\ntitle = \"t\"\ndimension = {dim}\ntensors = [\"C_ijkl\"]\n[[claim]]\nid = \"x\"\nprinted = 'x'\nexpect = \"holds\"\nassume = [\"C_ijkl = C_jikl\", \"C_ijkl = C_ijlk\", \"C_ijkl = C_klij\"]\nsides = [\"C_ijkl\", \"C_ijkl\"]\n"
        );
        let file = load_str("t.toml", &text).unwrap();
        let claim = &file.claims[0];
        let p = Parametrisation::new(&claim.decls, &claim.check.defs, &claim.check.assumptions)
            .unwrap();
        let components = cosserat_check::algebra::assignments(dim, 4)
            .filter(|idx| p.constrained("C", idx) == Constrained::Free)
            .count();
        assert_eq!(components, free, "dimension {dim}");
    }
}

#[test]
fn the_parametrisation_itself_does_not_depend_on_the_order() {
    let assumptions = [
        "\"C_ijkl = C_klij\"",
        "\"C_1111 = 2\"",
        "\"C_ijkl = C_jikl\"",
        "\"C_1122 = C_2211\"",
    ];
    let mut seen = None;
    for perm in itertools::Itertools::permutations(0..4, 4) {
        let list: Vec<&str> = perm.iter().map(|&k| assumptions[k]).collect();
        let text = format!(
            "section = \"t\"\ntitle = \"t\"\ndimension = 2\ntensors = [\"C_ijkl\"]\n[[claim]]\nid = \"x\"\nprinted = 'x'\nexpect = \"holds\"\nassume = [{}]\nsides = [\"C_ijkl\", \"C_ijkl\"]\n",
            list.join(", ")
        );
        let file = load_str("t.toml", &text).unwrap();
        let claim = &file.claims[0];
        let p = Parametrisation::new(&claim.decls, &claim.check.defs, &claim.check.assumptions)
            .unwrap();
        let shown = format!("{:?}", p.dependents().collect::<Vec<_>>());
        match &seen {
            None => seen = Some(shown),
            Some(first) => assert_eq!(&shown, first, "{list:?}"),
        }
    }
}

/// Assumptions that read definitions (`tests/soundness/assumptions-with-definitions.toml`):
/// each true claim is proved (or sampled, under `strategy = "numeric"`) and its wrong
/// twin fails; a substitution that reads a definition waits for the substitutions the
/// definition depends on, whatever the order written.
#[test]
fn assumptions_that_read_definitions_and_their_twins_are_decided_as_declared() {
    use cosserat_check::decide::Strength;
    let files = load_files(&[soundness_file("assumptions-with-definitions.toml")]).unwrap();
    let mut decided = 0;
    for claim in files.iter().flat_map(|f| &f.claims) {
        let d = decide_claim(claim).unwrap_or_else(|e| panic!("{}: {e}", claim.id));
        assert_eq!(d.outcome.verdict(), claim.expect, "{}", claim.id);
        if !claim.id.contains("sampled") {
            assert_eq!(d.outcome.strength(), Strength::Proof, "{}", claim.id);
        }
        decided += 1;
    }
    assert_eq!(decided, 10);
}

/// Polynomial constraints (`tests/soundness/polynomial-constraints.toml`): each true
/// claim is proved by reduction modulo the constraints (or sampled on the constraint
/// set), and its wrong twin fails at an exact point of that set, which the kernel
/// checks against every constraint (or at a sampled one).
#[test]
fn polynomial_constraints_and_their_twins_are_decided_as_declared() {
    use cosserat_check::decide::Strength;
    let files = load_files(&[soundness_file("polynomial-constraints.toml")]).unwrap();
    let mut decided = 0;
    for claim in files.iter().flat_map(|f| &f.claims) {
        let d = decide_claim(claim).unwrap_or_else(|e| panic!("{}: {e}", claim.id));
        assert_eq!(d.outcome.verdict(), claim.expect, "{}", claim.id);
        let want = if claim.id.contains("sampled") {
            Strength::Sampled
        } else {
            Strength::Proof
        };
        assert_eq!(d.outcome.strength(), want, "{}", claim.id);
        decided += 1;
    }
    assert_eq!(decided, 20);
}

/// Square roots of polynomials that are no squares (`tests/soundness/square-roots.toml`):
/// proved modulo their squares, refuted at exact points where every root is rational
/// and ≥ 0, and undecided (never a verdict) where no such point exists.
#[test]
fn square_roots_as_variables_and_their_twins_are_decided_as_declared() {
    use cosserat_check::decide::Strength;
    use cosserat_check::derivation::Verdict;
    let files = load_files(&[soundness_file("square-roots.toml")]).unwrap();
    let mut decided = 0;
    for claim in files.iter().flat_map(|f| &f.claims) {
        let d = decide_claim(claim).unwrap_or_else(|e| panic!("{}: {e}", claim.id));
        assert_eq!(d.outcome.verdict(), claim.expect, "{}", claim.id);
        if claim.expect != Verdict::Undecided {
            assert_eq!(d.outcome.strength(), Strength::Proof, "{}", claim.id);
        }
        decided += 1;
    }
    assert_eq!(decided, 13);
}

/// What an adversary found with square roots, each now right: a point must make every
/// side of every chain defined (x + √(x²) is 0 on a half-line), nested roots keep
/// short names (a name once doubled at every level), a high power of a root is reduced
/// by powers of its radicand, and the origin is tried first.
#[test]
fn square_roots_under_attack() {
    use cosserat_check::derivation::Verdict;
    let decide = |claim: &str| {
        let text = format!("{HEADER}\n[[claim]]\nid = \"x\"\nprinted = 'x'\n{claim}\n");
        let file = load_str("t.toml", &text).unwrap();
        decide_claim(&file.claims[0]).unwrap().outcome
    };
    for sides in [
        "sides = [\"sqrt(S^2)\", \"S\", \"2 S^2/(S + sqrt(S^2))\"]",
        "chains = [[\"sqrt(S^2)\", \"S\"], [\"sqrt(S)\", \"sqrt(S)\"]]",
    ] {
        let o = decide(sides);
        assert_ne!(o.verdict(), Verdict::Fails, "{sides}: {o:?}");
    }
    let mut nested = "S^2 + 1".to_owned();
    for _ in 0..10 {
        nested = format!("sqrt({nested})^3 + 1");
    }
    let o = decide(&format!("sides = [\"{nested}\", \"0\"]"));
    assert_ne!(o.verdict(), Verdict::Holds);
    let o = decide("sides = [\"sqrt(S^2 + 1)^40\", \"(S^2 + 1)^20\"]");
    assert_eq!(o.verdict(), Verdict::Holds, "{o:?}");
    let o = decide("sides = [\"sqrt(T S^2 + 1)\", \"0\"]");
    assert_eq!(o.verdict(), Verdict::Fails, "{o:?}");
}

/// The Rudnicki–Rice example: the denominator of the elastic-plastic modulus, the
/// inverse of the elastic acoustic tensor and the band at the critical hardening
/// modulus are proved at every deviatoric state of every intensity and every band
/// normal (both as polynomial constraints); the planted errors fail at exact points.
#[test]
fn the_rudnicki_rice_example_is_decided_as_declared_with_proofs() {
    use cosserat_check::decide::Strength;
    let files = load_files(&["derivations/examples/rudnicki-rice.toml"]).unwrap();
    let mut decided = 0;
    for claim in files.iter().flat_map(|f| &f.claims) {
        let d = decide_claim(claim).unwrap_or_else(|e| panic!("{}: {e}", claim.id));
        assert_eq!(d.outcome.verdict(), claim.expect, "{}", claim.id);
        assert_eq!(d.outcome.strength(), Strength::Proof, "{}", claim.id);
        decided += 1;
    }
    assert_eq!(decided, 6);
}

/// A constraint is solved for a power of a variable of its own whatever the order
/// written, and one that has none, or shares it, is a located error.
#[test]
fn constraints_are_solved_in_any_order_or_located() {
    for assume in [
        "\"s_kk = 0\", \"s_ij s_ij = 2 tau^2\"",
        "\"s_ij s_ij = 2 tau^2\", \"s_kk = 0\"",
        "\"s_ij s_ij = 2 tau^2\", \"symmetric(s)\", \"traceless(s)\"",
    ] {
        let text = format!(
            "section = \"t\"\ntitle = \"t\"\ndimension = 3\ntensors = [\"s_ij\"]\nscalars = [\"tau\"]\n\
             [[claim]]\nid = \"c\"\nprinted = 'x'\nexpect = \"holds\"\nassume = [{assume}]\n\
             sides = [\"s_ij s_ij tau^2\", \"2 tau^4\"]\n"
        );
        let files = [load_str("t.toml", &text).unwrap()];
        let d = decide_claim(&files[0].claims[0]).unwrap();
        assert_eq!(
            d.outcome.verdict(),
            cosserat_check::derivation::Verdict::Holds,
            "{assume}"
        );
    }
    // The second constraint reduced by the first says T = 0.
    let text = format!(
        "{HEADER}\n[[claim]]\nid = \"x\"\nprinted = 'x'\nexpect = \"holds\"\n\
         assume = [\"S^2 = 1\", \"S^2 = 1 + T\"]\nsides = [\"T S\", \"0\"]\n"
    );
    let file = load_str("t.toml", &text).unwrap();
    let d = decide_claim(&file.claims[0]).unwrap();
    assert_eq!(
        d.outcome.verdict(),
        cosserat_check::derivation::Verdict::Holds
    );
    // Two constraints: the first solved for T = S², the second then reads S twice.
    let e = error_of("assume = [\"S^2 = T\", \"T^2 = S\"]\nsides = [\"S\", \"S\"]");
    assert!(
        e.contains("cannot be solved for a power of one variable"),
        "{e}"
    );
    // A constraint set with no real point: a difference modulo it is no refutation.
    let text = format!(
        "{HEADER}\n[[claim]]\nid = \"x\"\nprinted = 'x'\nexpect = \"holds\"\n\
         assume = [\"S^2 + T^2 = -1\"]\nsides = [\"S\", \"0\"]\n"
    );
    let file = load_str("t.toml", &text).unwrap();
    let d = decide_claim(&file.claims[0]).unwrap();
    assert_eq!(
        d.outcome.verdict(),
        cosserat_check::derivation::Verdict::Undecided
    );
    assert!(matches!(
        d.outcome.finding,
        Some(cosserat_check::decide::finding::Finding::NoConstrainedPoint { .. })
    ));
    // A constraint with a pure power in none of its variables (a hyperbola).
    let e = error_of("assume = [\"S T = 1\"]\nsides = [\"S\", \"S\"]");
    assert!(
        e.contains("cannot be solved for a power of one variable"),
        "{e}"
    );
}

/// What an adversary found under constraints, each now right: a rounded root is no
/// exact point (sampling cannot tell, never `fails`); a derivative by a symbol tied to
/// a constraint through a linear assumption is refused; a definition only a constraint
/// reads is in the kernel's statement; a first power solved before a square is set
/// again after the square moves its variables; a counterexample shows every coordinate.
#[test]
fn constraints_under_attack() {
    use cosserat_check::derivation::Verdict;
    let decide = |claim: &str| {
        let text = format!(
            "{HEADER}\ndefine = [\"Q = eta_ij eta_ij / 2\"]\n[[claim]]\nid = \"x\"\nprinted = 'x'\n{claim}\n"
        );
        let file = load_str("t.toml", &text).unwrap();
        decide_claim(&file.claims[0]).unwrap().outcome
    };
    let o = decide(
        "strategy = \"numeric\"\nranges = { S = [-10000, 10000] }\n\
         assume = [\"T^2 = S^2 + 1\"]\nsides = [\"T^2 - S^2\", \"1\"]",
    );
    assert_ne!(o.verdict(), Verdict::Fails, "{o:?}");
    let e = error_of("assume = [\"S = V\", \"S^3 = T\"]\nsides = [\"grad(T, V)\", \"3 V^2\"]");
    assert!(e.contains("a derivative by `V`"), "{e}");
    let o = decide("assume = [\"2 Q = 2 T^2\"]\nsides = [\"eta_ij eta_ij\", \"2 T^2\"]");
    assert_eq!(o.verdict(), Verdict::Holds, "{o:?}");
    let o = decide("assume = [\"S^2 = T + 1\", \"V^2 = T\"]\nsides = [\"S^2 + V^2\", \"1\"]");
    assert_eq!(o.verdict(), Verdict::Fails, "{o:?}");
    let cx = o.counterexample.expect("a counterexample");
    for name in ["S", "T", "V"] {
        assert!(cx.point.contains_key(name), "{name} in {:?}", cx.point);
    }
}

/// A definition that an assumption reads is in the assumption's scope: a cycle through
/// it is located, and a file-wide assumption does not see a claim's definitions.
#[test]
fn definitions_in_assumptions_are_scoped_and_never_cycle() {
    let cycle =
        error_of("define = [\"D = S^2 + 1\"]\nassume = [\"S = D\"]\nsides = [\"S\", \"1\"]");
    assert!(
        cycle.contains("substitutions refer to each other in a cycle: S → S"),
        "{cycle}"
    );
    let text = "section = \"t\"\ntitle = \"t\"\ndimension = 2\nscalars = [\"a\", \"b\"]\n\
                assume = [\"a = mine\"]\n[[claim]]\nid = \"c\"\nprinted = 'x'\n\
                expect = \"holds\"\ndefine = [\"mine = b\"]\nsides = [\"a\", \"b\"]\n";
    let e = load_str("t.toml", text).unwrap_err().to_string();
    assert!(e.contains("unknown name `mine`"), "{e}");
}

/// An assumption gives a symbol one value per state: a right side that varies with the
/// normal (outside `avg`) or, for a symbol that is not a field, with position is a
/// located error, also through a definition. (Read at one normal, `avg(S)` with
/// `S = sigma_ij n_i n_j` came out equal to S, and a false claim held as sampled.)
#[test]
fn an_assumption_never_varies_with_the_normal_or_the_position() {
    let normal = "section = \"t\"\ntitle = \"t\"\ndimension = 3\nnormal = \"n\"\n\
                  tensors = [\"sigma_ij\"]\nscalars = [\"S\"]\ndefine = [\"tnn = sigma_ij n_i n_j\"]\n\
                  [[claim]]\nid = \"c\"\nprinted = 'x'\nexpect = \"holds\"\nstrategy = \"numeric\"\n\
                  assume = [\"S = tnn\"]\nsides = [\"avg(S)\", \"S\"]\n";
    let e = load_str("t.toml", normal).unwrap_err().to_string();
    assert!(
        e.contains("gives `S` one value per state, but this right side varies with the normal"),
        "{e}"
    );
    assert!(e.contains("t.toml:13:13"), "{e}");
    let averaged = normal.replace("S = tnn", "S = avg(tnn)");
    assert!(load_str("t.toml", &averaged).is_ok());
    let position = "section = \"t\"\ntitle = \"t\"\ndimension = 3\nposition = \"x\"\n\
                    fields = [\"v_i\"]\nscalars = [\"S\"]\ndefine = [\"Dq = v_k,k v_m,m\"]\n\
                    [[claim]]\nid = \"c\"\nprinted = 'x'\nexpect = \"holds\"\n\
                    assume = [\"S = Dq\"]\nsides = [\"d(S)/dx_1\", \"0\"]\n";
    let e = load_str("t.toml", position).unwrap_err().to_string();
    assert!(
        e.contains("`S` does not vary with position, but this right side does"),
        "{e}"
    );
}

/// A root in a substitution whose sign the box does not fix leaves that claim
/// `undecided` with the reason, as a root in a definition does; the file's other claims
/// are decided.
#[test]
fn an_uncertified_root_in_a_substitution_is_undecided_not_an_input_error() {
    use cosserat_check::derivation::Verdict;
    let text = "section = \"t\"\ntitle = \"t\"\ndimension = 2\nscalars = [\"S\", \"T\", \"V\"]\n\
                define = [\"root = sqrt(S^2) + 1\"]\n\
                [[claim]]\nid = \"open\"\nprinted = 'x'\nexpect = \"holds\"\n\
                assume = [\"T = root\", \"S = 2 V\"]\nsides = [\"T\", \"2 V + 1\"]\n\
                [[claim]]\nid = \"boxed\"\nprinted = 'x'\nexpect = \"holds\"\ngiven = [\"V > 0\"]\n\
                assume = [\"T = root\", \"S = 2 V\"]\nsides = [\"T\", \"2 V + 1\"]\n";
    let file = load_str("t.toml", text).unwrap();
    let open = decide_claim(&file.claims[0]).unwrap().outcome;
    assert_eq!(open.verdict(), Verdict::Undecided);
    assert!(cosserat_check::report::evidence(&open).contains("is not certified"));
    let boxed = decide_claim(&file.claims[1]).unwrap().outcome;
    assert_eq!(boxed.verdict(), Verdict::Holds);
}

#[test]
fn hypotheses_on_derived_quantities_restrict_where_a_counterexample_may_lie() {
    crate::common::assert_as_declared("tests/soundness/hypotheses.toml", 9, |rows| {
        crate::common::assert_failures_confirmed(
            rows,
            4,
            cosserat_check::decide::Reverified::FloatingPoint,
        );
        // Every counterexample satisfies its claim's hypotheses, and shows the
        // variables they read.
        let between = rows
            .iter()
            .find(|r| r.claim.id == "between-two-scalars-wrong")
            .expect("listed");
        let point = &between
            .outcome
            .counterexample
            .as_ref()
            .expect("refuted")
            .point;
        assert!(
            point.contains_key("a") && point.keys().any(|k| k.starts_with("s_")),
            "{point:?}"
        );
    });
}

#[test]
fn hypotheses_outside_an_exact_identity_are_located_errors() {
    let head = "section = \"t\"\ntitle = \"t\"\ndimension = 3\nnormal = \"n\"\nposition = \"x\"\nfields = [\"u_i\"]\ntensors = [\"s_ij\"]\nscalars = [\"a\"]\ndefine = [\"J2 = 1/2 s_ij s_ij\"]\n\n[[claim]]\nid = \"c\"\nprinted = 'c'\nexpect = \"holds\"\n";
    let cases = [
        ("given = [\"s_ij n_i n_j > 0\"]\nsides = [\"a\", \"a\"]", "varies with the normal or with position"),
        ("given = [\"u_k u_k > 0\"]\nsides = [\"a\", \"a\"]", "varies with the normal or with position"),
        ("strategy = \"proportional\"\ngiven = [\"J2 > 0\"]\nsides = [\"a\", \"a\"]", "`J2` is not a declared scalar"),
        ("strategy = \"sign\"\ngiven = [\"J2 > 0\"]\nsides = [\"a^2\", \"0\"]\nrelation = \">=\"", "`J2` is not a declared scalar"),
        ("given = [\"J2 >\"]\nsides = [\"a\", \"a\"]", "cannot read `J2 >` as a bound"),
    ];
    for (claim, message) in cases {
        let e = crate::common::error_of(&format!("{head}{claim}\n"));
        assert!(e.contains("f.toml:") && e.contains(message), "{claim}: {e}");
    }
}
