//! The compiled tape (`eval::tape`) against the interpreter (`eval::real`) on
//! every expression the sampled strategies evaluate in the paper: the sides of numeric
//! claims, the functions of gradient and convexity claims and their closed forms, the
//! hypotheses, domains and singular sets. Values in `f64` and first derivatives with
//! num-dual must agree at random states; a tape that folded a constant wrongly, shared
//! two different subexpressions or contracted the wrong slot would show here.

use cosserat_check::algebra::Tensor;
use cosserat_check::decide::random::Rng;
use cosserat_check::derivation::parametrisation::Parametrisation;
use cosserat_check::derivation::{load_dir, Claim, Strategy};
use cosserat_check::eval::quadrature::{Level, Quadrature};
use cosserat_check::eval::real::RealEnv;
use cosserat_check::eval::tape::Tape;
use cosserat_check::lang::Node;
use num_dual::Dual64;
use std::collections::HashMap;
use std::path::Path;

/// The accuracy the decisions evaluate adaptive averages at.
fn fine() -> Quadrature {
    Quadrature::new(Level::Fine)
}

fn expressions(claim: &Claim) -> Vec<&Node> {
    let check = &claim.check;
    let mut out: Vec<&Node> = check
        .chains
        .iter()
        .flatten()
        .filter_map(|s| s.node.as_ref().ok())
        .collect();
    out.extend(check.strategy.expressions().into_iter().map(|e| &e.node));
    out
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-10 * (1.0 + a.abs() + b.abs()) || (a.is_nan() && b.is_nan())
}

#[test]
fn the_tape_agrees_with_the_interpreter_on_every_sampled_expression() {
    let files = load_dir(&Path::new(env!("CARGO_MANIFEST_DIR")).join("derivations")).unwrap();
    let mut compared = 0;
    let mut declined = 0;
    let mut rng = Rng::new(4242);
    for claim in files.iter().flat_map(|f| &f.claims) {
        if matches!(
            claim.check.strategy,
            Strategy::Exact { .. } | Strategy::Proportional { .. } | Strategy::NotCircle { .. }
        ) {
            continue;
        }
        let decls = &claim.decls;
        let defs = &claim.check.defs;
        for node in expressions(claim) {
            let tape = match Tape::compile(decls, defs, node) {
                Ok(t) => t,
                // The tape declines grad(…) by design (the interpreter runs it, one
                // num-dual pass per gradient); every other construct must compile.
                Err(e) if e.0.contains("grad(…)") => {
                    declined += 1;
                    continue;
                }
                Err(e) => panic!("{}: not compiled: {e:?}", claim.id),
            };
            for _ in 0..5 {
                // A random state after the claim's assumptions, as the sampler draws it.
                let mut symbols: HashMap<String, Tensor<f64>> = HashMap::new();
                for (name, &rank) in &decls.symbols {
                    symbols.insert(
                        name.clone(),
                        Tensor::from_fn(decls.dim, rank, |_| 0.1 + 0.9 * rng.uniform().abs()),
                    );
                }
                let n = rng.unit_normal(decls);
                let mut env = RealEnv::new(decls, defs, symbols);
                let p = Parametrisation::new(decls, &claim.check.defs, &claim.check.assumptions)
                    .unwrap();
                env.assume(&p, &claim.check.assumptions, &n).unwrap();
                let symbols = env.symbols.clone();
                let inputs: Vec<f64> = tape
                    .inputs
                    .iter()
                    .map(|(s, idx)| *symbols[s].get(idx))
                    .collect();
                let by_tree = env.eval(node, &n);
                let by_tape = tape.eval(&inputs, &n, &fine());
                match (by_tree, by_tape) {
                    (Ok(a), Ok(b)) => {
                        assert_eq!(a.labels, b.labels, "{}: labels", claim.id);
                        for (x, y) in a.tensor.components().iter().zip(b.tensor.components()) {
                            assert!(close(*x, *y), "{}: interpreter {x}, tape {y}", claim.id);
                        }
                    }
                    (Err(a), Err(b)) => assert_eq!(a, b, "{}: different errors", claim.id),
                    (a, b) => panic!("{}: interpreter {a:?}, tape {b:?}", claim.id),
                }
                // First derivatives along the first input, with num-dual.
                let dual_symbols: HashMap<String, Tensor<Dual64>> = symbols
                    .iter()
                    .map(|(k, t)| (k.clone(), t.map(|&v| Dual64::from_re(v))))
                    .collect();
                let mut dual_inputs: Vec<Dual64> =
                    inputs.iter().map(|&v| Dual64::from_re(v)).collect();
                let mut seeded = dual_symbols.clone();
                if let Some((s, idx)) = tape.inputs.first() {
                    dual_inputs[0] = Dual64::new(inputs[0], 1.0);
                    *seeded.get_mut(s).unwrap().get_mut(idx) = Dual64::new(inputs[0], 1.0);
                }
                let tree = RealEnv::new(decls, defs, seeded).eval(node, &n);
                let taped = tape.eval(&dual_inputs, &n, &fine());
                if let (Ok(a), Ok(b)) = (tree, taped) {
                    for (x, y) in a.tensor.components().iter().zip(b.tensor.components()) {
                        assert!(
                            close(x.eps, y.eps),
                            "{}: derivative {} vs {}",
                            claim.id,
                            x.eps,
                            y.eps
                        );
                    }
                }
                compared += 1;
            }
        }
    }
    assert!(compared > 100, "only {compared} comparisons");
    // The Appendix's scalar claims read Q = grad(F₂, σ): declined, and only those.
    assert!(
        declined < compared / 4,
        "{declined} declined against {compared}"
    );
}

#[test]
fn a_tape_reports_the_interpreters_errors() {
    // Division by zero and the square root of a negative number, located as before.
    let text = "section = \"t\"\ntitle = \"t\"\ndimension = 2\ntensors = [\"a_i\"]\n\
                [[claim]]\nid = \"c\"\nprinted = 'x'\nexpect = \"holds\"\nstrategy = \"numeric\"\n\
                sides = [\"sqrt(a_1) / (a_2 - a_2)\", \"1\"]\n";
    let file = cosserat_check::derivation::load_str("t.toml", text).unwrap();
    let claim = &file.claims[0];
    let node = claim.check.chains[0][0].node.as_ref().unwrap();
    let tape = Tape::compile(&claim.decls, &claim.check.defs, node).unwrap();
    let env = RealEnv::new(
        &claim.decls,
        &claim.check.defs,
        HashMap::from([("a".to_owned(), Tensor::from_fn(2, 1, |i| [4.0, 1.0][i[0]]))]),
    );
    let inputs = [4.0, 1.0];
    assert_eq!(
        tape.eval(&inputs, &[1.0, 0.0], &fine()).unwrap_err(),
        env.eval(node, &[1.0, 0.0]).unwrap_err()
    );
    let negative = [-4.0, 1.0];
    let err = tape.eval(&negative, &[1.0, 0.0], &fine()).unwrap_err();
    assert!(
        err.message.contains("sqrt(…) of a negative number (-4)"),
        "{}",
        err.message
    );
    let env = RealEnv::new(
        &claim.decls,
        &claim.check.defs,
        HashMap::from([("a".to_owned(), Tensor::from_fn(2, 1, |i| [-4.0, 1.0][i[0]]))]),
    );
    assert_eq!(err, env.eval(node, &[1.0, 0.0]).unwrap_err());
}

#[test]
fn a_maxn_tape_agrees_with_the_interpreter_in_values_and_errors() {
    // maxn evaluates its argument over all grid angles at once and refines the local
    // maxima in lockstep; the values must be those of the interpreter's angle-by-angle
    // search, bit for bit, and an argument that fails at some angles (a square root of
    // a negative number, a division by zero) must report the error the first failing
    // angle gives. Each point is visited again in reverse order: the tape then answers
    // from its memo of maximisers, which must give the same bits at every state (a
    // memo keyed on too little would return another state's maximiser).
    let sides = [
        "maxn(abs(a_i n_i) + b_i n_i)",
        "maxn((a_i n_i)^2 - b_1 n_2 + c)",
        "maxn(sqrt(a_i n_i) + c)",
        "maxn(c / (a_i n_i))",
        "maxn(c)",
        "maxn(c a_i n_i)",
    ];
    let body: String = sides
        .iter()
        .enumerate()
        .map(|(k, s)| {
            format!(
                "[[claim]]\nid = \"c{k}\"\nprinted = 'x'\nexpect = \"holds\"\nstrategy = \"numeric\"\nsides = [\"{s}\", \"1\"]\n"
            )
        })
        .collect();
    let text = format!(
        "section = \"t\"\ntitle = \"t\"\ndimension = 2\nnormal = \"n\"\ntensors = [\"a_i\", \"b_i\"]\nscalars = [\"c\"]\n{body}"
    );
    let file = cosserat_check::derivation::load_str("t.toml", &text).unwrap();
    let mut rng = Rng::new(7);
    let mut errors = 0;
    for claim in &file.claims {
        let node = claim.check.chains[0][0].node.as_ref().unwrap();
        let tape = Tape::compile(&claim.decls, &claim.check.defs, node).unwrap();
        // Pairs of points differ only in the sign of c, which moves the maximiser of
        // c / (a_i n_i) and of c a_i n_i.
        let points: Vec<([f64; 2], [f64; 2], f64)> = (0..20)
            .flat_map(|pair| {
                let a = [rng.uniform(), rng.uniform()];
                // Some points put a on an axis, so that a_i n_i is exactly 0 at grid angles.
                let a = if pair % 3 == 0 { [a[0], 0.0] } else { a };
                let (b, c) = ([rng.uniform(), rng.uniform()], rng.uniform());
                [(a, b, c), (a, b, -c)]
            })
            .collect();
        for &(a, b, c) in points.iter().chain(points.iter().rev()) {
            let values: HashMap<String, Tensor<f64>> = HashMap::from([
                ("a".to_owned(), Tensor::from_fn(2, 1, |i| a[i[0]])),
                ("b".to_owned(), Tensor::from_fn(2, 1, |i| b[i[0]])),
                ("c".to_owned(), Tensor::from_fn(2, 0, |_| c)),
            ]);
            let inputs = tape.gather(|s| values.get(s), |x: Option<&f64>| *x.unwrap());
            let env = RealEnv::new(&claim.decls, &claim.check.defs, values.clone());
            let n = [1.0, 0.0];
            match (tape.eval(&inputs, &n, &fine()), env.eval(node, &n)) {
                (Ok(t), Ok(r)) => {
                    let (t, r) = (*t.tensor.get(&[]), *r.tensor.get(&[]));
                    assert_eq!(t.to_bits(), r.to_bits(), "{}: {t} vs {r}", claim.id);
                }
                (Err(t), Err(r)) => {
                    assert_eq!(t, r, "{}", claim.id);
                    errors += 1;
                }
                (t, r) => panic!("{}: tape {t:?}, interpreter {r:?}", claim.id),
            }
        }
    }
    assert!(
        errors > 0,
        "no argument failed: the error path was not exercised"
    );
}

#[test]
fn an_average_reports_the_error_its_first_point_gives() {
    // The ops of an average that do not depend on the normal are evaluated once, before
    // the others; the error reported must still be the one a whole run of the first
    // point gives: here the square root (which depends on the normal) fails before the
    // division by c − c (which does not) is reached; without the square root, the
    // division's error. A value that does not fail is the interpreter's.
    let text = "section = \"t\"\ntitle = \"t\"\ndimension = 3\nnormal = \"n\"\nscalars = [\"c\"]\n\
                [[claim]]\nid = \"c\"\nprinted = 'x'\nexpect = \"holds\"\nstrategy = \"numeric\"\n\
                sides = [\"avg(sqrt(n_1 - 2) + 1 / (c - c))\", \"avg(sqrt(c n_1^2 + 1) + c^2)\"]\n\
                [[claim]]\nid = \"d\"\nprinted = 'x'\nexpect = \"holds\"\nstrategy = \"numeric\"\n\
                sides = [\"avg(sqrt(n_1^2 + 1) + 1 / (c - c))\", \"1\"]\n";
    let file = cosserat_check::derivation::load_str("t.toml", text).unwrap();
    let claim = &file.claims[0];
    let env = RealEnv::new(
        &claim.decls,
        &claim.check.defs,
        HashMap::from([("c".to_owned(), Tensor::from_fn(3, 0, |_| 0.5))]),
    );
    let n = [0.0, 0.0, 1.0];
    let [failing, fine_side] = [0, 1].map(|k| {
        let node = claim.check.chains[0][k].node.as_ref().unwrap();
        (
            Tape::compile(&claim.decls, &claim.check.defs, node).unwrap(),
            node,
        )
    });
    let err = failing.0.eval(&[0.5], &n, &fine()).unwrap_err();
    assert!(
        err.message.contains("sqrt(…) of a negative number"),
        "{}",
        err.message
    );
    assert_eq!(err, env.eval(failing.1, &n).unwrap_err());
    let claim = &file.claims[1];
    let node = claim.check.chains[0][0].node.as_ref().unwrap();
    let tape = Tape::compile(&claim.decls, &claim.check.defs, node).unwrap();
    let err = tape.eval(&[0.5], &n, &fine()).unwrap_err();
    assert!(err.message.contains("division by zero"), "{}", err.message);
    assert_eq!(err, env.eval(node, &n).unwrap_err());
    let by_tape = fine_side.0.eval(&[0.5], &n, &fine()).unwrap().tensor;
    let by_tree = env.eval(fine_side.1, &n).unwrap().tensor;
    let (x, y) = (*by_tape.get(&[]), *by_tree.get(&[]));
    assert!(close(x, y), "tape {x}, interpreter {y}");
}
