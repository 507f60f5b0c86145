//! Evaluation at a state (issue 13, item 5): `grad(F, sigma_ij)` differentiates with
//! every component independent and only then applies the assumptions (the state);
//! square roots are exact where the state makes the radicand the square of a rational
//! function whose sign the kernel certifies on the box of `given`, and sampled with
//! num-dual numbers under `strategy = "numeric"`. Every claim that holds has a wrong
//! twin that must come out `fails`, confirmed by the interpreter.

use cosserat_check::decide::Strength;
use cosserat_check::derivation::Verdict;

use crate::common;

#[test]
fn gradients_at_states_and_their_twins_are_decided_as_declared() {
    common::assert_as_declared("tests/soundness/states.toml", 18, |rows| {
        for r in rows {
            let (o, id) = (&r.outcome, r.claim.id.as_str());
            match o.verdict() {
                Verdict::Holds if id == "drucker-prager-general" => {
                    assert_eq!(
                        o.strength(),
                        Strength::Sampled,
                        "no square at a general state"
                    );
                }
                Verdict::Holds => assert_eq!(o.strength(), Strength::Proof, "{id}"),
                Verdict::Fails => {
                    if o.numeric.is_none() {
                        let cx = o.counterexample.as_ref().expect(id);
                        assert!(
                            cx.reverified.is_some(),
                            "{id}: confirmed by the interpreter"
                        );
                    }
                }
                v => panic!("{id}: {v:?}"),
            }
        }
        let evidence = |id: &str| common::evidence_of(rows, id);
        // The root and the box its sign was certified on are part of the proof.
        let e = evidence("mises-uniaxial");
        assert!(e.contains("sqrt(Y^2) = Y on 0 < Y"), "{e}");
        assert!(evidence("mises-compression").contains("sqrt(Y^2) = -Y on Y < 0"));
        // A counterexample lies inside the box.
        assert!(evidence("mises-compression-wrong").contains("values at Y=-"));
    });
}

/// Second derivatives (`grad` inside `grad`): exact where the values are rational
/// functions or certified roots, sampled with nested num-dual numbers otherwise; each
/// wrong twin fails with a counterexample the interpreter confirms.
#[test]
fn second_derivatives_and_their_twins_are_decided_as_declared() {
    common::assert_as_declared("tests/soundness/second-derivatives.toml", 23, |rows| {
        for r in rows {
            let (o, id) = (&r.outcome, r.claim.id.as_str());
            let sampled = r.claim.id.contains("sampled");
            match o.verdict() {
                Verdict::Holds if sampled => assert_eq!(o.strength(), Strength::Sampled, "{id}"),
                Verdict::Holds => assert_eq!(o.strength(), Strength::Proof, "{id}"),
                Verdict::Fails => {
                    let cx = o.counterexample.as_ref().expect(id);
                    assert!(cx.reverified.is_some(), "{id}: confirmed by a second route");
                    if !sampled {
                        assert_eq!(o.strength(), Strength::Proof, "{id}");
                    }
                }
                v => panic!("{id}: {v:?}"),
            }
        }
        let evidence = |id: &str| common::evidence_of(rows, id);
        // The fourth-order Hessian is compared in all 3^4 components.
        assert!(evidence("j2-hessian").contains("81 component checks"));
        // The root taken inside two derivatives is certified on the box.
        assert!(evidence("mises-hessian-uniaxial").contains("sqrt(Y^2) = Y on 0 < Y"));
    });
}

/// A third derivative is refused where it is written and where a definition hides
/// one of its levels.
#[test]
fn a_third_derivative_is_a_located_refusal() {
    let hidden = common::one_claim(
        "dimension = 2\ntensors = [\"a_i\"]\ndefine = [\"F = (a_i a_i)^2\", \"G_ij = grad(grad(F, a_i), a_j)\"]",
        "sides = [\"grad(G_ij, a_k)\", \"0\"]",
    );
    let e = common::error_of(&hidden);
    assert!(
        e.contains("a third derivative inside grad(…) is not supported"),
        "{e}"
    );
    assert!(e.contains("f.toml:"), "located: {e}");
}

/// `maxn` is not differentiated: its maximising angle is found to about 1e-8 and moves
/// with the variable, so a derivative through it is refused (`grad`), or left
/// undecided (the `gradient` strategy), never a verdict.
#[test]
fn a_derivative_through_maxn_is_never_a_verdict() {
    let header = "dimension = 2\nnormal = \"n\"\nscalars = [\"x\", \"y\"]";
    for sides in [
        "sides = [\"grad(maxn(x n_1 + y n_2), x)\", \"x / sqrt(x^2 + y^2)\"]",
        "sides = [\"grad(grad(maxn(x n_1 + y n_2), x), x)\", \"0\"]",
    ] {
        let text = common::one_claim(
            header,
            &format!("strategy = \"numeric\"\nranges = {{ x = [0.5, 1], y = [0.5, 1] }}\n{sides}"),
        );
        let e = common::error_of(&text);
        assert!(e.contains("maxn(…) is not differentiated"), "{e}");
    }
    let text = common::one_claim(
        header,
        "strategy = \"gradient\"\nranges = { x = [0.5, 1], y = [0.5, 1] }\n\
         function = \"maxn(x n_1 + y n_2)\"\n\
         gradient = { x = \"x / sqrt(x^2 + y^2)\", y = \"y / sqrt(x^2 + y^2)\" }",
    );
    let file = cosserat_check::derivation::load_str("f.toml", &text).unwrap();
    let outcome = cosserat_check::check::decide_claim(&file.claims[0])
        .unwrap()
        .outcome;
    assert_eq!(outcome.verdict(), Verdict::Undecided);
}

/// The radial-return example: the consistent tangent and the fourth-order Hessian it
/// holds are proved at an exact state and sampled at random strains; the continuum
/// tangent, planted in its place, fails.
#[test]
fn the_radial_return_example_is_decided_as_declared() {
    common::assert_as_declared("derivations/examples/radial-return.toml", 8, |rows| {
        for r in rows {
            let numeric = r.claim.id.contains("general");
            let want = if numeric {
                Strength::Sampled
            } else {
                Strength::Proof
            };
            assert_eq!(r.outcome.strength(), want, "{}", r.claim.id);
        }
    });
}

#[test]
fn the_worked_example_is_decided_as_declared() {
    common::assert_as_declared("derivations/examples/states.toml", 7, |_| {});
}

const HEADER: &str = "dimension = 2\nscalars = [\"x\", \"y\"]\ntensors = [\"s_ij\"]\nposition = \"p\"\nfields = [\"u_i\"]";

fn file(body: &str) -> String {
    format!("section = \"t\"\ntitle = \"t\"\n{HEADER}\n{body}\n")
}

fn claim(rest: &str) -> String {
    common::one_claim(HEADER, rest)
}

#[test]
fn malformed_gradients_are_located_errors() {
    let cases = [
        (claim("sides = [\"grad(u_k u_k, u_i)\", \"2 u_i\"]"), "`u` varies with position, so grad(…) does not apply to it"),
        (claim("sides = [\"grad(s_kk, s_1i)\", \"0\"]"), "grad(…) takes the symbol with index letters, one per slot"),
        (claim("sides = [\"grad(s_ij, s_ij)\", \"0\"]"), "index `i` of the symbol differentiated by is also an index of the expression"),
        (claim("sides = [\"grad(s_kk, delta_ij)\", \"0\"]"), "`delta_ij` is not a declared symbol"),
        (claim("sides = [\"grad(s_mn s_mn, s_ii)\", \"0\"]"), "index `i` repeats in the symbol of grad(…)"),
        (claim("sides = [\"grad(grad(s_mn s_mn, s_ij), s_ii)\", \"0\"]"), "index `i` repeats in the symbol of grad(…)"),
        (claim("sides = [\"grad(grad(grad(x^3, x), x), x)\", \"6\"]"), "a third derivative (a gradient inside two) inside grad(…) is not supported"),
        (claim("sides = [\"grad(variation(u_i u_i, u_j), x)\", \"0\"]"), "a variation or gradient inside grad(…) is not supported"),
        (claim("sides = [\"grad(x, 2)\", \"0\"]"), "the second argument of grad(…) is a declared symbol with its indices"),
        (claim("sides = [\"grad([[x, y], [y, x]], x)\", \"0\"]"), "grad(…) takes a scalar or a tensor, but this is a 2×2 matrix"),
        (claim("sides = [\"grad(sqrt(2 x^2), x)\", \"0\"]"), "sqrt(…) of this expression has no exact value"),
        // √((s_12 − s_21)²) = |s_12 − s_21| has no derivative where s_12 = s_21, though
        // the first partials of its radicand vanish there: an error, never 0.
        (claim("assume = [\"s_ij = x delta_ij\"]\ngiven = [\"x > 0\"]\nsides = [\"grad(sqrt((s_12 - s_21)^2), s_ij)\", \"0\"]"), "its radicand is 0 at the state"),
        (claim("samples = 60\nsides = [\"x\", \"x\"]"), "`samples` belongs to the sampled strategies"),
        (claim("strategy = \"proportional\"\ngiven = [\"x > y\"]\nsides = [\"x\", \"x\"]"), "cannot read `x > y` as a bound"),
        (claim("strategy = \"gradient\"\nfunction = \"grad(x^2 s_kk, x)\"\ngradient = { s = \"2 x delta_ij\" }"), "differentiates this function, which takes grad(…) or variation(…) itself"),
        (file("define = [\"g = grad(x^3, x)\"]\n[[claim]]\nid = \"c\"\nprinted = 'x'\nexpect = \"holds\"\nstrategy = \"convex\"\nfunction = \"g\"\nwrt = [\"s\"]"), "differentiates this function, which takes grad(…) or variation(…) itself"),
    ];
    common::assert_located_errors(&cases);
}

/// With the set where it does not exist excluded, the same gradient holds; without,
/// the worst-case search reaches √ at 0 and steps off it (a set of measure zero),
/// never calling it a counterexample to a true statement.
#[test]
fn a_gradient_holds_off_the_set_where_it_does_not_exist() {
    let text = claim("strategy = \"numeric\"\nsingular = \"x^2 + y^2\"\nsides = [\"grad(sqrt(x^2 + y^2), x)^2 + grad(sqrt(x^2 + y^2), y)^2\", \"1\"]");
    let outcomes = common::outcomes_of(&text);
    assert_eq!(outcomes[0].verdict(), Verdict::Holds);
    assert_eq!(outcomes[0].strength(), Strength::Sampled);
    let stepped = common::outcomes_of(&text.replace("singular = \"x^2 + y^2\"\n", ""));
    assert_eq!(stepped[0].verdict(), Verdict::Holds);
    let ev = cosserat_check::report::evidence(&stepped[0]);
    assert!(ev.contains("stepped off"), "{ev}");
}

/// A root whose sign the box does not fix is never guessed. In an identity it is a
/// variable of its own, r² = x², and the claim √(x²) = x is refuted on the branch
/// r ≥ 0, at x < 0; with the box x > 0 the root is x and the claim is proved. Where no
/// rule is checked (a sign claim), the root of unknown sign leaves the claim
/// undecided, with the reason.
#[test]
fn a_root_of_unknown_sign_is_never_guessed() {
    let text = claim("expect = \"fails\"\nreason = \"sqrt(x^2) = |x|\"\nsides = [\"sqrt(x^2)\", \"x\"]\n[[claim]]\nid = \"d\"\nprinted = 'x'\nexpect = \"holds\"\ngiven = [\"x > 0\"]\nsides = [\"sqrt(x^2)\", \"x\"]\n[[claim]]\nid = \"e\"\nprinted = 'x'\nstrategy = \"sign\"\nsides = [\"sqrt(x^2) - x\", \"0\"]\nrelation = \">=\"").replacen("expect = \"holds\"\n", "", 1);
    let outcomes = common::outcomes_of(&text);
    assert_eq!(outcomes[0].verdict(), Verdict::Fails);
    assert_eq!(outcomes[0].strength(), Strength::Proof);
    let cx = outcomes[0].counterexample.as_ref().expect("a point");
    assert!(cx.point["x"].starts_with('-'), "{:?}", cx.point);
    assert_eq!(outcomes[1].verdict(), Verdict::Holds);
    assert_eq!(outcomes[1].strength(), Strength::Proof);
    assert_ne!(outcomes[2].verdict(), Verdict::Fails);
    let e = cosserat_check::report::evidence(&outcomes[2]);
    assert!(e.contains("not certified"), "{e}");
}

/// The exact route and num-dual numbers agree on a gradient at random states: a
/// rational function of the components, differentiated both ways.
#[test]
fn exact_and_dual_gradients_agree() {
    let text = file("[[claim]]\nid = \"c\"\nprinted = 'x'\nexpect = \"holds\"\nsides = [\"grad((s_ij s_ji)^2 / (1 + x^2) - s_12 s_21 s_11 / y, s_kl)\", \"4 s_ij s_ji s_lk / (1 + x^2) - (delta_k1 delta_l2 s_21 s_11 + delta_k2 delta_l1 s_12 s_11 + delta_k1 delta_l1 s_12 s_21) / y\"]\n[[claim]]\nid = \"d\"\nprinted = 'x'\nexpect = \"holds\"\nstrategy = \"numeric\"\nranges = { y = [0.5, 1.0] }\nsides = [\"grad((s_ij s_ji)^2 / (1 + x^2) - s_12 s_21 s_11 / y, s_kl)\", \"4 s_ij s_ji s_lk / (1 + x^2) - (delta_k1 delta_l2 s_21 s_11 + delta_k2 delta_l1 s_12 s_11 + delta_k1 delta_l1 s_12 s_21) / y\"]");
    let f = cosserat_check::derivation::load_str("f.toml", &text).expect("loads");
    let rows = cosserat_check::cli::decide_all(std::slice::from_ref(&f), None).unwrap();
    for r in &rows {
        assert_eq!(
            r.outcome.verdict(),
            Verdict::Holds,
            "{}",
            cosserat_check::report::evidence(&r.outcome)
        );
    }
    assert_eq!(rows[0].outcome.strength(), Strength::Proof);
    assert_eq!(rows[1].outcome.strength(), Strength::Sampled);
}

/// A parameter that only fixes the sign of a square root (y in √(y²)/y = −1 on y < 0)
/// is not a variable of the function, yet the interpreter that confirms a
/// counterexample reads it: it must come from the box, and the point shows it.
#[test]
fn a_counterexample_takes_unread_parameters_from_the_box() {
    let text = claim("expect = \"fails\"\nreason = \"x − 1 ≤ 0 fails for x > 1\"\nstrategy = \"sign\"\ngiven = [\"y < 0\"]\nsides = [\"x + sqrt(y^2) / y\", \"0\"]\nrelation = \"<=\"").replacen("expect = \"holds\"\n", "", 1);
    let outcomes = common::outcomes_of(&text);
    let o = &outcomes[0];
    assert_eq!(
        o.verdict(),
        Verdict::Fails,
        "{}",
        cosserat_check::report::evidence(o)
    );
    let cx = o.counterexample.as_ref().expect("a counterexample");
    assert!(
        cx.point.get("y").is_some_and(|y| y.starts_with('-')),
        "{:?}",
        cx.point
    );
}
