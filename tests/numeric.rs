//! Evidence that the numeric strategies refute wrong statements: a wrong gradient, a
//! wrong circle radius, a false inequality, a false maximum, a non-convex function, a
//! genuine circle offered as "not a circle", and a statement undefined on its samples.

use cosserat_check::check::decide_claim;
use cosserat_check::decide::Method;
use cosserat_check::derivation::{load_str, Verdict};

/// A plane problem as in derivations/4.2-yield-surfaces.toml.
const HEADER: &str = r#"
section = "t"
title = "numeric strategies"
dimension = 3
normal = "n"
normal_in_plane = true
tensors = ["sigma_ij", "mu_ij"]
scalars = ["R_g", "f_s", "f_r", "phi"]
assume = [
  "sigma_13 = 0", "sigma_23 = 0", "sigma_31 = 0", "sigma_32 = 0", "sigma_33 = 0",
  "mu_11 = 0", "mu_12 = 0", "mu_21 = 0", "mu_22 = 0", "mu_31 = 0", "mu_32 = 0", "mu_33 = 0",
]
define = [
  "p = (sigma_11 + sigma_22) / 2",
  "Pi_ij = delta_ij - delta_i3 delta_j3",
  "s_ij = sigma_ij - p Pi_ij",
  "t_i = sigma_ki n_k",
  "tn = t_i n_i",
  "tau = t_i eps_i3k n_k",
  "q2 = 1/4 (s_11 - s_22)^2 + 1/4 (s_12 + s_21)^2",
  "r2 = 1/4 (s_12 - s_21)^2",
  "M2 = 1/2 (mu_13^2 + mu_23^2)",
  "F1 = sqrt(q2 + 2 r2) + f_s p",
  "F1star = sqrt(q2) + sqrt(r2) cos(phi) + p sin(phi)",
  "F2 = sqrt(2 M2 / R_g^2 + q2 + 2 r2) + f_r p",
]
"#;

/// Decides the single claim `body` (a `[[claim]]` table without its header line).
fn decide(body: &str) -> (Verdict, Method, String) {
    let text = format!("{HEADER}\n[[claim]]\nid = \"x\"\nprinted = 'x'\n{body}");
    let file = load_str("test.toml", &text).unwrap_or_else(|e| panic!("{e}"));
    let d = decide_claim(&file.claims[0]).unwrap_or_else(|e| panic!("{e}"));
    let text = cosserat_check::report::evidence(&d.outcome);
    (d.outcome.verdict(), d.outcome.method, text)
}

#[test]
fn a_correct_gradient_holds_and_a_wrong_one_fails() {
    let right = r#"expect = "holds"
strategy = "gradient"
ranges = { f_s = [0.0, 2.0] }
singular = "q2 + 2 r2"
function = "F1"
gradient = { sigma = "(3 s_ij - s_ji) / (4 sqrt(q2 + 2 r2)) + f_s / 2 Pi_ij" }"#;
    assert_eq!(decide(right).0, Verdict::Holds);
    for wrong in [
        "(2 s_ij - s_ji) / (4 sqrt(q2 + 2 r2)) + f_s / 2 Pi_ij",
        "(3 s_ji - s_ij) / (4 sqrt(q2 + 2 r2)) + f_s / 2 Pi_ij",
        "(3 s_ij - s_ji) / (4 sqrt(q2 + 2 r2))",
        "(3 s_ij - s_ji) / (4 sqrt(q2 + 2 r2)) - f_s / 2 Pi_ij",
    ] {
        let (v, m, ev) = decide(&right.replace(
            "(3 s_ij - s_ji) / (4 sqrt(q2 + 2 r2)) + f_s / 2 Pi_ij",
            wrong,
        ));
        assert_eq!((v, m), (Verdict::Fails, Method::Gradient), "{wrong}: {ev}");
        assert!(ev.contains("num-dual and the closed form disagree"), "{ev}");
    }
}

#[test]
fn a_wrong_circle_radius_or_centre_fails() {
    let circle = r#"expect = "holds"
sides = ["(tn - p)^2 + (tau - (sigma_12 - sigma_21) / 2)^2", "q2"]"#;
    assert_eq!(decide(circle).0, Verdict::Holds);
    assert_eq!(
        decide(&circle.replace("\"q2\"", "\"2 q2\"")).0,
        Verdict::Fails
    );
    assert_eq!(
        decide(&circle.replace("(tn - p)", "(tn + p)")).0,
        Verdict::Fails
    );
    assert_eq!(
        decide(&circle.replace("(sigma_12 - sigma_21) / 2", "(sigma_12 + sigma_21) / 2")).0,
        Verdict::Fails
    );
}

#[test]
fn a_false_inequality_fails_and_a_partial_one_is_conditional() {
    let base = r#"expect = "holds"
strategy = "numeric"
relation = ">="
ranges = { R_g = [0.1, 2.0], f_r = [0.0, 2.0], f_s = [0.0, 2.0] }
given = ["f_r <= f_s"]
sides = ["F2", "F1"]"#;
    // Without a domain: fails (tension counterexample).
    let (v, _, ev) = decide(base);
    assert_eq!(v, Verdict::Fails, "{ev}");
    // With the right domain: conditional, the counterexample outside it.
    let (v, _, ev) = decide(&format!("{base}\ndomain = [\"p <= 0\"]"));
    assert_eq!(v, Verdict::Conditional, "{ev}");
    // With a wrong domain (tension): it also fails inside, so fails.
    let (v, _, ev) = decide(&format!("{base}\ndomain = [\"p >= 0\"]"));
    assert_eq!(v, Verdict::Fails, "{ev}");
    assert!(ev.contains("inside the declared domain"), "{ev}");
    // The reversed inequality is false too.
    let (v, _, _) = decide(
        &base
            .replace("\">=\"", "\"<=\"")
            .replace("given = [\"f_r <= f_s\"]", "given = [\"f_r >= f_s\"]"),
    );
    assert_eq!(v, Verdict::Fails);
}

#[test]
fn a_false_maximum_fails() {
    let max = r#"expect = "holds"
strategy = "numeric"
samples = 50
ranges = { phi = [0.05, 1.5] }
sides = ["maxn(abs(tau) cos(phi) + tn sin(phi))", "F1star"]"#;
    assert_eq!(decide(max).0, Verdict::Holds);
    assert_eq!(
        decide(&max.replace("\"F1star\"", "\"F1star + 1/1000\"")).0,
        Verdict::Fails
    );
    assert_eq!(decide(&max.replace("abs(tau)", "tau")).0, Verdict::Fails);
    assert_eq!(
        decide(&max.replace("cos(phi) + tn", "cos(phi) - tn")).0,
        Verdict::Fails
    );
}

#[test]
fn a_non_convex_function_fails() {
    let convex = r#"expect = "holds"
strategy = "convex"
ranges = { f_s = [0.0, 2.0] }
singular = "q2 + 2 r2"
function = "F1"
wrt = ["sigma"]"#;
    assert_eq!(decide(convex).0, Verdict::Holds);
    let (v, m, _) = decide(&convex.replace("function = \"F1\"", "function = \"-F1\""));
    assert_eq!((v, m), (Verdict::Fails, Method::Convex));
    let (v, _, ev) =
        decide(&convex.replace("function = \"F1\"", "function = \"sqrt(sqrt(q2 + 2 r2))\""));
    assert_eq!(v, Verdict::Fails);
    assert!(ev.contains("second difference"), "{ev}");
    // At the apex the Hessian does not exist: no verdict, and the reason.
    let apex = convex
        .replace(
            "ranges = { f_s = [0.0, 2.0] }",
            "ranges = { sigma = [0.0, 0.0] }",
        )
        .replace("singular = \"q2 + 2 r2\"\n", "");
    let (v, _, ev) = decide(&apex);
    assert_eq!(v, Verdict::Undecided, "{ev}");
    assert!(ev.contains("not finite"), "{ev}");
}

#[test]
fn a_genuine_circle_refutes_not_circle_by_its_circle() {
    let not_circle = "expect = \"holds\"\nstrategy = \"not-circle\"\nx = \"tn\"\ny = \"tau\"";
    // Mohr's circle: no witness exists, and the circle itself, checked by the kernel
    // on the whole locus, refutes the claim.
    let (v, m, ev) = decide(not_circle);
    assert_eq!((v, m), (Verdict::Fails, Method::Witness), "{ev}");
    assert!(ev.contains("the locus is a circle"), "{ev}");
    // A segment is not a circle, but has no witness either: undecided, never `fails`.
    let (v, _, ev) = decide(&not_circle.replace("\"tau\"", "\"2 tn\""));
    assert_eq!(v, Verdict::Undecided, "{ev}");
    assert!(ev.contains("not a counterexample"), "{ev}");
    // Distorting the shear axis breaks the circle: a witness exists.
    let (v, _, ev) = decide(&not_circle.replace("\"tau\"", "\"2 tau\""));
    assert_eq!(v, Verdict::Holds, "{ev}");
    assert!(ev.contains("det["), "{ev}");
}

#[test]
fn nan_and_division_by_zero_never_pass() {
    let text = format!(
        "{HEADER}\n[[claim]]\nid = \"x\"\nprinted = 'x'\nexpect = \"holds\"\nstrategy = \"numeric\"\nsides = [\"sqrt(-1 - q2)\", \"0\"]\n"
    );
    // Undefined at every state (a set of positive measure): undecided, with where and
    // why, and never a pass.
    let undefined_everywhere = |text: &str, what: &str| {
        let file = load_str("t.toml", text).unwrap();
        let o = decide_claim(&file.claims[0]).unwrap().outcome;
        let ev = cosserat_check::report::evidence(&o);
        assert_eq!(o.verdict(), Verdict::Undecided, "{ev}");
        assert!(
            ev.contains("undefined on a set of positive measure")
                && ev.contains(what)
                && ev.contains("t.toml:"),
            "{ev}"
        );
    };
    undefined_everywhere(&text, "of a negative number");
    undefined_everywhere(
        &text.replace("sqrt(-1 - q2)", "1 / (p - p)"),
        "division by zero",
    );
}

/// Undefined on part of the box and false on the rest: a violation where both sides
/// are defined is a counterexample, whichever the draws meet first, for every seed.
#[test]
fn a_violation_where_defined_is_found_whatever_is_undefined_before_it() {
    for seed in 1..=20 {
        let (verdict, _, ev) = decide(&format!(
            "expect = \"holds\"\nstrategy = \"numeric\"\nseed = {seed}\nsides = [\"sqrt(f_s) + f_s\", \"f_s\"]\nranges = {{ f_s = [-1.0, 1.0] }}"
        ));
        assert_eq!(verdict, Verdict::Fails, "seed {seed}: {ev}");
    }
}

#[test]
fn too_few_samples_are_refused() {
    let text = format!(
        "{HEADER}\n[[claim]]\nid = \"x\"\nprinted = 'x'\nexpect = \"holds\"\nstrategy = \"numeric\"\nsamples = 10\nsides = [\"F1\", \"F1\"]\n"
    );
    let err = load_str("t.toml", &text).unwrap_err().to_string();
    assert!(err.contains("samples must be between 50"), "{err}");
}

#[test]
fn at_the_apex_the_gradient_does_not_exist_and_is_reported() {
    // Every sample at the apex q = r = 0 (a range of one value puts every stress
    // component at 0; the derivative is still taken in every free direction): num-dual's
    // sqrt has a NaN derivative there, and NaN never passes. Nor is it a counterexample:
    // the gradient does not exist there, so the claim is undecided, with the reason.
    let apex = r#"expect = "holds"
strategy = "gradient"
samples = 50
ranges = { sigma = [0.0, 0.0] }
function = "F1"
gradient = { sigma = "(3 s_ij - s_ji) / (4 sqrt(q2 + 2 r2)) + f_s / 2 Pi_ij" }"#;
    let (v, m, ev) = decide(apex);
    assert_eq!((v, m), (Verdict::Undecided, Method::Gradient), "{ev}");
    assert!(
        ev.contains("does not exist there") && ev.contains("singular"),
        "{ev}"
    );
    // Declaring the singular set excludes those samples; when every sample lies on it,
    // the checker says so instead of passing vacuously.
    let text = format!(
        "{HEADER}\n[[claim]]\nid = \"x\"\nprinted = 'x'\n{apex}\nsingular = \"q2 + 2 r2\"\n"
    );
    let file = load_str("t.toml", &text).unwrap();
    let err = decide_claim(&file.claims[0]).unwrap_err().to_string();
    assert!(err.contains("accept fewer than 1 in"), "{err}");
}

#[test]
fn a_derivative_with_respect_to_tied_components_needs_a_convention() {
    // σ_22 = σ_11 ties two variables: ∂F/∂σ then has two meanings, so without
    // `convention` the checker refuses instead of answering.
    let tied = format!(
        "{HEADER}\n[[claim]]\nid = \"x\"\nprinted = 'x'\nexpect = \"holds\"\nstrategy = \"gradient\"\nassume = [\"sigma_22 = sigma_11\"]\nfunction = \"F1\"\ngradient = {{ sigma = \"(3 s_ij - s_ji) / (4 sqrt(q2 + 2 r2)) + f_s / 2 Pi_ij\" }}\n"
    );
    let file = load_str("t.toml", &tied).unwrap();
    let err = decide_claim(&file.claims[0]).unwrap_err().to_string();
    assert!(
        err.contains("sigma_11") && err.contains("sigma_22") && err.contains("two meanings"),
        "{err}"
    );
    // Symmetrised, the tied pair shares ½(∂F/∂σ_11 + ∂F/∂σ_22), which on σ_11 = σ_22 is
    // f_s/2 for both, as the closed form says.
    let (v, _, ev) = decide(&format!(
        "{}convention = \"symmetrised\"\n",
        tied.split("[[claim]]\nid = \"x\"\nprinted = 'x'\n")
            .nth(1)
            .unwrap()
    ));
    assert_eq!(v, Verdict::Holds, "{ev}");
    // With every component fixed there is nothing to differentiate: refused, not a
    // vacuous `holds`.
    let fixed = format!(
        "{HEADER}\n[[claim]]\nid = \"x\"\nprinted = 'x'\nexpect = \"holds\"\nstrategy = \"gradient\"\nassume = [\"mu_13 = 0\", \"mu_23 = 1\"]\nfunction = \"F2\"\ngradient = {{ mu = \"0 delta_ij\" }}\n"
    );
    let file = load_str("t.toml", &fixed).unwrap();
    let err = decide_claim(&file.claims[0]).unwrap_err().to_string();
    assert!(err.contains("nothing to differentiate"), "{err}");
}

#[test]
fn num_dual_at_a_kink_is_caught_by_the_directional_difference() {
    // At σ_11 = 0, |σ_11| has no derivative; num-dual's abs picks the branch by the sign
    // bit and says 1, and a closed form that says the same agrees with it. The central
    // difference along the mixed direction gives 0, so the per-component differences
    // are taken and name the component: undecided, never holds.
    let kink = r#"expect = "holds"
strategy = "gradient"
samples = 50
ranges = { sigma = [0.0, 0.0] }
function = "abs(sigma_11)"
gradient = { sigma = "delta_i1 delta_j1" }"#;
    let (v, m, ev) = decide(kink);
    assert_eq!((v, m), (Verdict::Undecided, Method::Gradient), "{ev}");
    assert!(ev.contains("∂/∂sigma_11") && ev.contains("do not"), "{ev}");
    // Away from the kink the same claim holds: the directional check passes it.
    let (v, _, ev) = decide(&kink.replace("[0.0, 0.0]", "[0.5, 1.0]"));
    assert_eq!(v, Verdict::Holds, "{ev}");
}

#[test]
fn an_overflow_is_said_as_one_not_as_a_gap_in_the_domain() {
    // exp(x)/4 = exp(x - log 4) is true everywhere; beyond x ≈ 709.8 both sides overflow
    // f64. That is no set where the sides are undefined, and never a counterexample.
    let (v, _, ev) = decide(
        "expect = \"undecided\"\nreason = \"r\"\nstrategy = \"numeric\"\nranges = { phi = [709.0, 712.0] }\nsides = [\"exp(phi)/4\", \"exp(phi - log(4))\"]",
    );
    assert_eq!(v, Verdict::Undecided, "{ev}");
    assert!(ev.contains("overflow floating point"), "{ev}");
    assert!(!ev.contains("undefined on a set"), "{ev}");
}
