//! The kernel's checker on statements written by hand, true and false side by side:
//! every fact it accepts must hold and every false one must be refused. These are
//! the tests a broken kernel fails (a flipped sign in the coefficient test, an
//! off-by-one in a Sturm count, a wrapped exponent).

use cosserat_check::kernel::check::{check, Conclusion, Evaluation, Fact};
use cosserat_check::kernel::statement::{Claim, Context, End, Equation, Interval, Sign, Statement};
use cosserat_check::kernel::term::{Leaf, Slot, Term};
use cosserat_check::kernel::Rational;

fn q(n: i64, d: i64) -> Rational {
    Rational::ratio(n, d).unwrap()
}

fn num(n: i64) -> Term {
    Term::int(n)
}

fn frac(n: i64, d: i64) -> Term {
    Term::Const {
        value: q(n, d),
        free: Vec::new(),
    }
}

fn leaf(of: Leaf, slots: &str) -> Term {
    Term::Leaf {
        of,
        slots: slots
            .chars()
            .map(|c| match c.to_digit(10) {
                Some(d) => Slot::Fixed(d as usize - 1),
                None => Slot::Letter(c),
            })
            .collect(),
    }
}

fn sym(name: &str, slots: &str) -> Term {
    leaf(Leaf::Symbol(name.to_owned()), slots)
}

fn prod(fs: Vec<Term>) -> Term {
    Term::Product(fs)
}

fn sum(ts: Vec<Term>) -> Term {
    Term::Sum(ts)
}

fn neg(t: Term) -> Term {
    Term::Neg(Box::new(t))
}

fn context(symbols: &[(&str, usize)]) -> Context {
    Context {
        dim: 3,
        normal: Some("n".to_owned()),
        symbols: symbols.iter().map(|&(s, r)| (s.to_owned(), r)).collect(),
        ..Context::default()
    }
}

fn equal(ctx: &Context, left: Term, right: Term) -> Statement {
    Statement {
        context: ctx.clone(),
        claim: Claim::Equal {
            chains: vec![vec![left, right]],
        },
    }
}

fn holds(st: Statement, fact: Fact) -> bool {
    check(st, fact).is_ok_and(|p| p.conclusion() == Conclusion::Holds)
}

fn fails(st: Statement, fact: Fact) -> bool {
    check(st, fact).is_ok_and(|p| p.conclusion() == Conclusion::Fails)
}

fn identity() -> Fact {
    Fact::Identity { roots: Vec::new() }
}

#[test]
fn identities_hold_and_their_twins_are_refused() {
    let ctx = context(&[("a", 1), ("b", 1)]);
    let ab = prod(vec![sym("a", "i"), sym("b", "i")]);
    let ba = prod(vec![sym("b", "j"), sym("a", "j")]);
    assert!(holds(equal(&ctx, ab.clone(), ba), identity()));
    let aa = prod(vec![sym("a", "j"), sym("a", "j")]);
    assert!(!holds(equal(&ctx, ab.clone(), aa), identity()));
    // ε_ijk ε_imn = δ_jm δ_kn − δ_jn δ_km, and with the sign of one term flipped.
    let ee = prod(vec![leaf(Leaf::Eps, "ijk"), leaf(Leaf::Eps, "imn")]);
    let dd = |a: &str, b: &str| prod(vec![leaf(Leaf::Delta, a), leaf(Leaf::Delta, b)]);
    let right = sum(vec![dd("jm", "kn"), neg(dd("jn", "km"))]);
    let flipped = sum(vec![dd("jm", "kn"), dd("jn", "km")]);
    assert!(holds(equal(&ctx, ee.clone(), right), identity()));
    assert!(!holds(equal(&ctx, ee, flipped), identity()));
    // ⟨n_i n_j⟩ = δ_ij / 3, not δ_ij / 2; n·n = 1 only modulo the sphere.
    let avg = Term::Avg(Box::new(prod(vec![
        leaf(Leaf::Normal, "i"),
        leaf(Leaf::Normal, "j"),
    ])));
    let third = prod(vec![frac(1, 3), leaf(Leaf::Delta, "ij")]);
    let half = prod(vec![frac(1, 2), leaf(Leaf::Delta, "ij")]);
    assert!(holds(equal(&ctx, avg.clone(), third), identity()));
    assert!(!holds(equal(&ctx, avg, half), identity()));
    let nn = prod(vec![leaf(Leaf::Normal, "k"), leaf(Leaf::Normal, "k")]);
    assert!(holds(equal(&ctx, nn.clone(), num(1)), identity()));
    assert!(!holds(equal(&ctx, nn, num(2)), identity()));
    // A quotient: (x² − y²)/(x − y) = x + y wherever x ≠ y, not x − y.
    let xy = context(&[("x", 0), ("y", 0)]);
    let (x, y) = (sym("x", ""), sym("y", ""));
    let ratio = Term::Div(
        Box::new(sum(vec![
            Term::Pow(Box::new(x.clone()), 2),
            neg(Term::Pow(Box::new(y.clone()), 2)),
        ])),
        Box::new(sum(vec![x.clone(), neg(y.clone())])),
    );
    assert!(holds(
        equal(&xy, ratio.clone(), sum(vec![x.clone(), y.clone()])),
        identity()
    ));
    assert!(!holds(equal(&xy, ratio, sum(vec![x, neg(y)])), identity()));
}

#[test]
fn a_refutation_needs_an_exact_point_that_satisfies_everything() {
    let mut ctx = context(&[("a", 1), ("t", 0)]);
    let st = |ctx: &Context| equal(ctx, sym("a", "1"), sym("a", "2"));
    let at = |point: &[(&str, Rational)], index: Vec<usize>| Fact::Refutation {
        at: Evaluation {
            chain: 0,
            equality: 0,
            at: index,
            point: point
                .iter()
                .map(|(n, v)| ((*n).to_owned(), v.clone()))
                .collect(),
        },
        roots: Vec::new(),
    };
    let full = |a1: i64, a2: i64| [("a_1", q(a1, 1)), ("a_2", q(a2, 1)), ("a_3", q(0, 1))];
    assert!(fails(st(&ctx), at(&full(1, 0), vec![])));
    assert!(!fails(st(&ctx), at(&full(1, 1), vec![])), "equal there");
    assert!(
        !fails(st(&ctx), at(&[("a_1", q(1, 1))], vec![])),
        "a variable left out"
    );
    // An assumption a_1 = a_2 makes every point where they differ inadmissible.
    ctx.equations.push(Equation::Component {
        symbol: "a".to_owned(),
        index: vec![0],
        value: sym("a", "2"),
    });
    assert!(
        !fails(st(&ctx), at(&full(1, 0), vec![])),
        "the point breaks an assumption"
    );
    // A box: t > 0 refuses a point at t = −1.
    let mut boxed = context(&[("t", 0)]);
    boxed.given = vec![(
        "t".to_owned(),
        Interval {
            lo: End::Open(q(0, 1)),
            hi: End::Unbounded,
        },
    )];
    let st = equal(&boxed, sym("t", ""), num(2));
    assert!(fails(st.clone(), at(&[("t", q(1, 1))], vec![])));
    assert!(
        !fails(st, at(&[("t", q(-1, 1))], vec![])),
        "outside the box"
    );
    // The normal must be a unit vector at the point.
    let ctx = context(&[]);
    let st = equal(&ctx, leaf(Leaf::Normal, "1"), num(0));
    let n = |a: Rational, b: Rational, c: Rational| [("n_1", a), ("n_2", b), ("n_3", c)];
    assert!(fails(st.clone(), at(&n(q(3, 5), q(4, 5), q(0, 1)), vec![])));
    assert!(
        !fails(st, at(&n(q(1, 1), q(1, 1), q(0, 1)), vec![])),
        "off the sphere"
    );
}

fn sign(ctx: &Context, f: Term, s: Sign) -> Statement {
    Statement {
        context: ctx.clone(),
        claim: Claim::Sign {
            left: f,
            right: num(0),
            sign: s,
        },
    }
}

fn coefficients() -> Fact {
    Fact::SignByCoefficients {
        reduced: None,
        function: None,
        roots: Vec::new(),
    }
}

#[test]
fn coefficient_signs_certify_only_true_signs() {
    let mut ctx = context(&[("x", 0), ("y", 0)]);
    let (x, y) = (sym("x", ""), sym("y", ""));
    let sq = |t: &Term| Term::Pow(Box::new(t.clone()), 2);
    assert!(holds(
        sign(&ctx, sum(vec![sq(&x), sq(&y)]), Sign::NonNegative),
        coefficients()
    ));
    assert!(
        !holds(
            sign(&ctx, sum(vec![sq(&x), sq(&y)]), Sign::Positive),
            coefficients()
        ),
        "0 at the origin"
    );
    assert!(!holds(
        sign(
            &ctx,
            sum(vec![x.clone(), neg(y.clone())]),
            Sign::NonNegative
        ),
        coefficients()
    ));
    assert!(!holds(
        sign(&ctx, neg(sq(&x)), Sign::NonNegative),
        coefficients()
    ));
    let positive = Interval {
        lo: End::Open(q(0, 1)),
        hi: End::Unbounded,
    };
    ctx.given = vec![
        ("x".to_owned(), positive.clone()),
        ("y".to_owned(), positive),
    ];
    assert!(holds(
        sign(&ctx, prod(vec![x.clone(), y.clone()]), Sign::Positive),
        coefficients()
    ));
    assert!(!holds(
        sign(&ctx, prod(vec![x, neg(y)]), Sign::Positive),
        coefficients()
    ));
}

fn on_interval(cuts: &[Rational]) -> Fact {
    Fact::SignOnInterval {
        variable: "x".to_owned(),
        cuts: cuts.to_vec(),
        reduced: None,
        function: None,
        roots: Vec::new(),
    }
}

#[test]
fn sturm_counts_certify_only_true_signs_and_root_lists() {
    let mut ctx = context(&[("x", 0)]);
    let x = sym("x", "");
    // x² − 2 > 0 on (2, ∞), not on (1, ∞) where √2 lies, whatever cuts are offered.
    let f = sum(vec![Term::Pow(Box::new(x.clone()), 2), num(-2)]);
    ctx.given = vec![(
        "x".to_owned(),
        Interval {
            lo: End::Open(q(2, 1)),
            hi: End::Unbounded,
        },
    )];
    assert!(holds(
        sign(&ctx, f.clone(), Sign::Positive),
        on_interval(&[])
    ));
    ctx.given = vec![(
        "x".to_owned(),
        Interval {
            lo: End::Open(q(1, 1)),
            hi: End::Unbounded,
        },
    )];
    for cuts in [
        vec![],
        vec![q(3, 2)],
        vec![q(5, 4), q(3, 2)],
        vec![q(7, 5), q(3, 2)],
    ] {
        assert!(
            !holds(sign(&ctx, f.clone(), Sign::Positive), on_interval(&cuts)),
            "{cuts:?}"
        );
        assert!(
            !holds(sign(&ctx, f.clone(), Sign::NonNegative), on_interval(&cuts)),
            "{cuts:?}"
        );
    }
    // (x − 1)² ≥ 0 everywhere, with the double root as a cut; not > 0.
    ctx.given = Vec::new();
    let g = Term::Pow(Box::new(sum(vec![x.clone(), num(-1)])), 2);
    assert!(holds(
        sign(&ctx, g.clone(), Sign::NonNegative),
        on_interval(&[q(1, 1)])
    ));
    assert!(!holds(
        sign(&ctx, g, Sign::Positive),
        on_interval(&[q(1, 1)])
    ));
    // Roots: x² − x has exactly 0 and 1; x² − 2 has two (irrational) zeros, not none.
    let counted = |f: Term, listed: Vec<Term>, count: Option<usize>| Statement {
        context: ctx.clone(),
        claim: Claim::Roots {
            function: f,
            variable: "x".to_owned(),
            roots: listed,
            count,
        },
    };
    let roots = |f: Term, listed: Vec<Term>| counted(f, listed, None);
    let h = sum(vec![Term::Pow(Box::new(x.clone()), 2), neg(x.clone())]);
    let none = Fact::Roots { roots: Vec::new() };
    assert!(holds(roots(h.clone(), vec![num(0), num(1)]), none.clone()));
    assert!(fails(roots(h.clone(), vec![num(0)]), none.clone()));
    assert!(fails(roots(h, vec![num(0), num(1), num(2)]), none.clone()));
    assert!(fails(roots(f.clone(), vec![]), none.clone()));
    // A count: the kernel counts the zeros itself, rational or not, and a count with
    // roots listed as well is refused (no statement says both).
    assert!(holds(counted(f.clone(), vec![], Some(2)), none.clone()));
    for wrong in [0, 1, 3] {
        assert!(fails(counted(f.clone(), vec![], Some(wrong)), none.clone()));
    }
    assert!(check(counted(f, vec![num(0)], Some(1)), none).is_err());
}

fn differs() -> Fact {
    Fact::Differs {
        at: Evaluation {
            chain: 0,
            equality: 0,
            at: Vec::new(),
            point: Vec::new(),
        },
        roots: Vec::new(),
    }
}

#[test]
fn an_exponent_beyond_the_bound_is_a_limit_never_a_wrap() {
    // x^(2^13), squared 27 times: x^(2^40) is the largest exponent, one more square
    // would be 2^41. `a = 1` must never hold, x^(2^40) = x^(2^40) still does, and
    // x^(2^40) = 1 fails as functions (no value of it can be computed at x = 2).
    let ctx = context(&[("x", 0)]);
    let mut t = Term::Pow(Box::new(sym("x", "")), 1 << 13);
    for _ in 0..27 {
        t = Term::Pow(Box::new(t), 2);
    }
    assert!(holds(equal(&ctx, t.clone(), t.clone()), identity()));
    assert!(fails(equal(&ctx, t.clone(), num(1)), differs()));
    let beyond = Term::Pow(Box::new(t), 2);
    assert!(!holds(equal(&ctx, beyond.clone(), num(1)), identity()));
    assert!(!fails(equal(&ctx, beyond.clone(), num(1)), differs()));
    let e = check(equal(&ctx, beyond, num(1)), identity())
        .unwrap_err()
        .to_string();
    assert!(e.contains("bound"), "{e}");
}

#[test]
fn sides_differ_as_functions_only_on_an_open_box_of_free_variables() {
    let x = || sym("x", "");
    let ctx = context(&[("x", 0), ("a", 1)]);
    assert!(fails(equal(&ctx, x(), num(1)), differs()));
    assert!(
        !fails(equal(&ctx, x(), x()), differs()),
        "the same function"
    );
    // n·n − 1 is zero wherever the normal is a unit vector.
    let nn = prod(vec![leaf(Leaf::Normal, "i"), leaf(Leaf::Normal, "i")]);
    assert!(!fails(equal(&ctx, nn.clone(), num(1)), differs()));
    // A divisor that vanishes on the whole sphere leaves nothing to compare.
    let over = |d: Term| Term::Div(Box::new(num(1)), Box::new(d));
    let empty = sum(vec![nn, num(-1)]);
    assert!(!fails(equal(&ctx, over(empty), x()), differs()));
    assert!(fails(equal(&ctx, over(x()), x()), differs()));
    // A box of one point, or bounds on an eliminated variable, may hold the sides
    // equal: the kernel refuses to reason as functions there.
    let mut point = ctx.clone();
    point.given = vec![(
        "x".to_owned(),
        Interval {
            lo: End::Closed(q(1, 1)),
            hi: End::Closed(q(1, 1)),
        },
    )];
    assert!(!fails(equal(&point, x(), num(1)), differs()));
    let mut eliminated = ctx.clone();
    eliminated.equations.push(Equation::Component {
        symbol: "a".to_owned(),
        index: vec![0],
        value: num(5),
    });
    // a_1 = 5 and 0 < a_1 < 2: no state at all, so nothing fails.
    eliminated.given = vec![(
        "a_1".to_owned(),
        Interval {
            lo: End::Open(q(0, 1)),
            hi: End::Open(q(2, 1)),
        },
    )];
    assert!(!fails(equal(&eliminated, sym("a", "2"), num(1)), differs()));
    // A point must not be named: that is a refutation's business.
    let named = Fact::Differs {
        at: Evaluation {
            chain: 0,
            equality: 0,
            at: Vec::new(),
            point: vec![("x".to_owned(), q(2, 1))],
        },
        roots: Vec::new(),
    };
    assert!(!fails(equal(&ctx, x(), num(1)), named));
}

#[test]
fn a_fact_for_another_claim_or_another_kind_is_refused() {
    let ctx = context(&[("x", 0)]);
    let st = equal(&ctx, sym("x", ""), sym("x", ""));
    assert!(check(st.clone(), coefficients()).is_err());
    assert!(
        check(st, Fact::IllFormed { chain: 0, side: 0 }).is_err(),
        "well-formed"
    );
    // An index three times in one product is ill-formed, and the kernel says so.
    let bad = prod(vec![
        sym("x", ""),
        leaf(Leaf::Delta, "ii"),
        leaf(Leaf::Normal, "i"),
    ]);
    let st = equal(&context(&[("x", 0)]), bad, num(0));
    assert!(fails(st, Fact::IllFormed { chain: 0, side: 0 }));
}

/// `t^2 = a_i a_i` (a vector of length |t|): what the kernel proves modulo it, and the
/// facts it refuses under it.
fn on_a_sphere_of_radius_t() -> Context {
    let mut ctx = context(&[("a", 1), ("t", 0)]);
    ctx.equations.push(Equation::Constraint {
        left: Term::Pow(Box::new(sym("t", "")), 2),
        right: prod(vec![sym("a", "i"), sym("a", "i")]),
    });
    ctx
}

#[test]
fn an_identity_under_a_polynomial_constraint_holds_modulo_it_only() {
    let ctx = on_a_sphere_of_radius_t();
    let t = sym("t", "");
    let aa = prod(vec![sym("a", "i"), sym("a", "i")]);
    let t4 = Term::Pow(Box::new(t.clone()), 4);
    // (a·a)² = t⁴ and t³ = t a·a hold; a·a = t, t² = 2 a·a and t = 1 do not.
    assert!(holds(
        equal(&ctx, Term::Pow(Box::new(aa.clone()), 2), t4.clone()),
        identity()
    ));
    let t3 = Term::Pow(Box::new(t.clone()), 3);
    assert!(holds(
        equal(&ctx, t3, prod(vec![t.clone(), aa.clone()])),
        identity()
    ));
    assert!(!holds(equal(&ctx, aa.clone(), t.clone()), identity()));
    assert!(!holds(
        equal(
            &ctx,
            Term::Pow(Box::new(t.clone()), 2),
            prod(vec![num(2), aa.clone()])
        ),
        identity()
    ));
    assert!(!holds(equal(&ctx, t.clone(), num(1)), identity()));
    // Without the constraint the first identity is false.
    let free = context(&[("a", 1), ("t", 0)]);
    assert!(!holds(
        equal(&free, Term::Pow(Box::new(aa), 2), t4),
        identity()
    ));
    // A divisor the constraint makes zero everywhere: nothing is proved.
    let vanishing = Term::Div(
        Box::new(num(1)),
        Box::new(sum(vec![
            Term::Pow(Box::new(t.clone()), 2),
            neg(prod(vec![sym("a", "i"), sym("a", "i")])),
        ])),
    );
    assert!(!holds(
        equal(&ctx, vanishing.clone(), vanishing),
        identity()
    ));
}

#[test]
fn a_refutation_under_a_polynomial_constraint_needs_a_point_on_it() {
    let ctx = on_a_sphere_of_radius_t();
    // a_1 = t is false: at a = (3, 4, 0), t = 5 the sides differ.
    let st = equal(&ctx, sym("a", "1"), sym("t", ""));
    let at = |t: i64, a: [i64; 3]| Fact::Refutation {
        at: Evaluation {
            chain: 0,
            equality: 0,
            at: Vec::new(),
            point: vec![
                ("a_1".to_owned(), q(a[0], 1)),
                ("a_2".to_owned(), q(a[1], 1)),
                ("a_3".to_owned(), q(a[2], 1)),
                ("t".to_owned(), q(t, 1)),
            ],
        },
        roots: Vec::new(),
    };
    assert!(fails(st.clone(), at(5, [3, 4, 0])));
    assert!(fails(st.clone(), at(-5, [3, 4, 0])), "either root");
    assert!(!fails(st.clone(), at(6, [3, 4, 0])), "off the constraint");
    assert!(!fails(st.clone(), at(3, [3, 0, 0])), "equal there");
    // A difference as functions proves nothing under a constraint (x² = −1 − y² has
    // no real point at all).
    assert!(!fails(st, differs()));
}

#[test]
fn a_square_root_of_a_polynomial_is_a_variable_only_where_a_rule_is_checked() {
    let ctx = context(&[("x", 0), ("y", 0)]);
    let (x, y) = (sym("x", ""), sym("y", ""));
    let radicand = sum(vec![
        Term::Pow(Box::new(x.clone()), 2),
        Term::Pow(Box::new(y.clone()), 2),
    ]);
    let root = Term::Sqrt(Box::new(radicand.clone()));
    // √(x² + y²)² = x² + y² holds modulo the square; √ = x + y does not.
    assert!(holds(
        equal(&ctx, Term::Pow(Box::new(root.clone()), 2), radicand.clone()),
        identity()
    ));
    assert!(!holds(
        equal(&ctx, root.clone(), sum(vec![x.clone(), y.clone()])),
        identity()
    ));
    // √(x² + y²) = −√(x² + y²): refuted only on the branch ≥ 0.
    let st = equal(&ctx, root.clone(), neg(root.clone()));
    let name = "√(x^2 + y^2)";
    let at = |r: i64| Fact::Refutation {
        at: Evaluation {
            chain: 0,
            equality: 0,
            at: Vec::new(),
            point: vec![
                ("x".to_owned(), q(3, 1)),
                ("y".to_owned(), q(4, 1)),
                (name.to_owned(), q(r, 1)),
            ],
        },
        roots: Vec::new(),
    };
    assert!(fails(st.clone(), at(5)));
    assert!(!fails(st.clone(), at(-5)), "the other branch");
    assert!(!fails(st, at(6)), "not the root");
    // A proportionality evaluates no such root: refused, not proved.
    let prop = Statement {
        context: ctx.clone(),
        claim: Claim::Proportional {
            chains: vec![vec![Term::Pow(Box::new(root), 2), radicand]],
        },
    };
    let factor = Fact::Proportional {
        factors: vec![cosserat_check::kernel::check::Factor::Constant(q(1, 1))],
        roots: Vec::new(),
    };
    assert!(!holds(prop, factor));
}

#[test]
fn roots_of_parameters_are_proved_only_when_they_divide_the_numerator_and_nothing_else_vanishes() {
    let mut ctx = context(&[("h", 0), ("a", 0), ("b", 0)]);
    let (h, a, b) = (sym("h", ""), sym("a", ""), sym("b", ""));
    let roots = |ctx: &Context, f: &Term, listed: Vec<Term>| Statement {
        context: ctx.clone(),
        claim: Claim::Roots {
            function: f.clone(),
            variable: "h".to_owned(),
            roots: listed,
            count: None,
        },
    };
    let by = |m: Vec<u32>| Fact::RootsOfParameters {
        multiplicities: m,
        roots: Vec::new(),
    };
    let div = |x: &Term, y: &Term| Term::Div(Box::new(x.clone()), Box::new(y.clone()));
    let square = |x: Term| Term::Pow(Box::new(x), 2);
    // a h − b = 0 exactly at h = b/a, for a > 0; with a free, a = 0 breaks it.
    let f = sum(vec![prod(vec![a.clone(), h.clone()]), neg(b.clone())]);
    let positive = (
        "a".to_owned(),
        Interval {
            lo: End::Open(q(0, 1)),
            hi: End::Unbounded,
        },
    );
    ctx.given = vec![positive.clone()];
    assert!(holds(roots(&ctx, &f, vec![div(&b, &a)]), by(vec![1])));
    assert!(check(roots(&ctx, &f, vec![div(&a, &b)]), by(vec![1])).is_err());
    assert!(check(roots(&ctx, &f, vec![div(&b, &a)]), by(vec![2])).is_err());
    assert!(check(roots(&ctx, &f, vec![div(&b, &a)]), by(vec![])).is_err());
    let free = context(&[("h", 0), ("a", 0), ("b", 0)]);
    assert!(check(roots(&free, &f, vec![div(&b, &a)]), by(vec![1])).is_err());
    // h² + 1 has no real root: 0 twice would leave h⁻² in the quotient.
    let g = sum(vec![square(h.clone()), num(1)]);
    assert!(holds(roots(&free, &g, vec![]), by(vec![])));
    for m in [1, 2] {
        assert!(check(roots(&free, &g, vec![num(0)]), by(vec![m])).is_err());
    }
    // a h² + 1 with a > 0 has none either; (h − a)² listed once leaves h − a, of
    // both signs; (h − a)/(h − b) has no zero where b = a.
    let g = sum(vec![prod(vec![a.clone(), square(h.clone())]), num(1)]);
    assert!(holds(roots(&ctx, &g, vec![]), by(vec![])));
    assert!(check(roots(&ctx, &g, vec![num(0)]), by(vec![2])).is_err());
    let shifted = sum(vec![h.clone(), neg(a.clone())]);
    let twice = square(shifted.clone());
    assert!(holds(roots(&free, &twice, vec![a.clone()]), by(vec![2])));
    assert!(check(roots(&free, &twice, vec![a.clone()]), by(vec![1])).is_err());
    let pole = div(&shifted, &sum(vec![h.clone(), neg(b.clone())]));
    assert!(check(roots(&free, &pole, vec![a.clone()]), by(vec![1])).is_err());
    // A refutation at a point of the parameters, only where the zeros differ.
    let at = |point: &[(&str, i64)]| Fact::RootsAt {
        point: point
            .iter()
            .map(|(n, x)| ((*n).to_owned(), q(*x, 1)))
            .collect(),
        roots: Vec::new(),
    };
    let wrong = roots(&ctx, &f, vec![div(&a, &b)]);
    assert!(fails(wrong.clone(), at(&[("a", 2), ("b", 1)])));
    assert!(check(wrong.clone(), at(&[("a", 1), ("b", 1)])).is_err());
    assert!(
        check(wrong.clone(), at(&[("a", -1), ("b", 1)])).is_err(),
        "outside the box"
    );
    assert!(
        check(wrong.clone(), at(&[("a", 2)])).is_err(),
        "b left free"
    );
    assert!(check(wrong, at(&[("a", 2), ("b", 1), ("h", 0)])).is_err());
    assert!(fails(
        roots(&free, &pole, vec![a.clone()]),
        at(&[("a", 1), ("b", 1)])
    ));
    assert!(check(roots(&free, &pole, vec![a]), at(&[("a", 1), ("b", 2)])).is_err());
}

#[test]
fn a_one_point_interval_counts_its_point_once_and_has_no_open_piece() {
    let mut ctx = context(&[("x", 0)]);
    ctx.given = vec![(
        "x".to_owned(),
        Interval {
            lo: End::Closed(q(1, 1)),
            hi: End::Closed(q(1, 1)),
        },
    )];
    let x = sym("x", "");
    let f = sum(vec![x.clone(), num(-1)]);
    let counted = |count: usize| Statement {
        context: ctx.clone(),
        claim: Claim::Roots {
            function: f.clone(),
            variable: "x".to_owned(),
            roots: Vec::new(),
            count: Some(count),
        },
    };
    let none = Fact::Roots { roots: Vec::new() };
    assert!(holds(counted(1), none.clone()));
    assert!(fails(counted(2), none));
    // 1/(x − 1) > 0 on the one point x = 1, where it is undefined: no piece to sample.
    let pole = Term::Div(Box::new(num(1)), Box::new(f));
    let on_interval = Fact::SignOnInterval {
        variable: "x".to_owned(),
        cuts: Vec::new(),
        reduced: None,
        function: None,
        roots: Vec::new(),
    };
    assert!(holds(sign(&ctx, pole, Sign::Positive), on_interval));
}

/// ∂ by the coordinates `slots` (letters, or digits 1..3) of `t`, innermost first.
fn deriv(t: Term, slots: &str) -> Term {
    slots.chars().fold(t, |acc, c| {
        let slot = match c.to_digit(10) {
            Some(d) => Slot::Fixed(d as usize - 1),
            None => Slot::Letter(c),
        };
        Term::Deriv(Box::new(acc), slot)
    })
}

fn with_fields(hypotheses: Vec<(Term, Term)>) -> Context {
    let mut ctx = context(&[("phi", 0), ("psi", 0), ("x", 1)]);
    ctx.position = Some("x".to_owned());
    ctx.fields = ["phi", "psi"]
        .iter()
        .map(|f| (f.to_string(), vec![true; 3]))
        .collect();
    ctx.equations = hypotheses
        .into_iter()
        .map(|(left, right)| Equation::Differential { left, right })
        .collect();
    ctx
}

fn refuted_at(point: &[(&str, i64)]) -> Fact {
    Fact::Refutation {
        at: Evaluation {
            chain: 0,
            equality: 0,
            at: Vec::new(),
            point: point
                .iter()
                .map(|&(v, x)| (v.to_owned(), q(x, 1)))
                .collect(),
        },
        roots: Vec::new(),
    }
}

#[test]
fn a_differential_hypothesis_holds_with_every_derivative_and_leaves_the_rest_free() {
    let phi = || sym("phi", "");
    let harmonic = with_fields(vec![(deriv(phi(), "kk"), num(0))]);
    let laplacian = |extra: &str| {
        sum(["11", "22", "33"]
            .iter()
            .map(|d| deriv(phi(), &format!("{d}{extra}")))
            .collect())
    };
    // ∇²φ = 0 and its derivatives, to the fourth order.
    for extra in ["", "1", "23", "3311"] {
        let st = equal(&harmonic, laplacian(extra), num(0));
        assert!(holds(st.clone(), identity()), "{extra}");
        // A point that breaks the hypothesis does not refute a consequence of it.
        let jet = |d: &str| {
            format!("phi_,{}", {
                let mut s: Vec<char> = format!("{d}{extra}").chars().collect();
                s.sort_unstable();
                s.into_iter().collect::<String>()
            })
        };
        assert!(!fails(st, refuted_at(&[(&jet("11"), 1)])), "{extra}");
    }
    // φ_,11 is free: refuted where it is 1 (φ = (x_1² − x_3²)/2 is harmonic).
    let st = equal(&harmonic, deriv(phi(), "11"), num(0));
    assert!(fails(st.clone(), refuted_at(&[("phi_,11", 1)])));
    assert!(!holds(st, identity()));
    // ψ is not assumed harmonic.
    let psi = sum(["11", "22", "33"]
        .iter()
        .map(|d| deriv(sym("psi", ""), d))
        .collect());
    assert!(!holds(equal(&harmonic, psi, num(0)), identity()));
}

#[test]
fn differential_hypotheses_outside_the_checked_class_are_refused() {
    let phi = || sym("phi", "");
    let psi = || sym("psi", "");
    let claim = |ctx: &Context| equal(ctx, deriv(phi(), "12"), num(0));
    // φ_,1 = ψ and φ_,2 = 0 give φ_,12 both ψ_,2 and 0: not in involution, so the
    // derivatives left free are not independent.
    let open = with_fields(vec![
        (deriv(phi(), "1"), psi()),
        (deriv(phi(), "2"), num(0)),
    ]);
    assert!(check(claim(&open), identity()).is_err());
    assert!(check(claim(&open), refuted_at(&[("psi_,2", 1)])).is_err());
    // With ψ_,2 = 0 they are, and φ_,12 = 0 follows.
    let closed = with_fields(vec![
        (deriv(phi(), "1"), psi()),
        (deriv(phi(), "2"), num(0)),
        (deriv(psi(), "2"), num(0)),
    ]);
    assert!(holds(claim(&closed), identity()));
    // Nonlinear, or with a coefficient that varies with position: refused.
    let nonlinear = with_fields(vec![(deriv(phi(), "kk"), prod(vec![phi(), phi()]))]);
    assert!(check(claim(&nonlinear), identity()).is_err());
    let varying = with_fields(vec![(
        prod(vec![sym("x", "1"), deriv(phi(), "kk")]),
        num(0),
    )]);
    assert!(check(claim(&varying), identity()).is_err());
    // Its highest derivative twice: 2 φ_,11 − φ_,11 is fine, φ_,11 φ_,11 is not.
    let square = with_fields(vec![(
        prod(vec![deriv(phi(), "11"), deriv(phi(), "11")]),
        num(0),
    )]);
    assert!(check(claim(&square), identity()).is_err());
}

#[test]
fn a_refutation_under_hypotheses_needs_a_point_where_they_hold() {
    use cosserat_check::kernel::statement::Hypothesis;
    let mut ctx = context(&[("a", 0), ("b", 0)]);
    // a > 1 and b ≥ a.
    ctx.hypotheses = vec![
        Hypothesis {
            left: sym("a", ""),
            right: num(1),
            sign: Sign::Positive,
        },
        Hypothesis {
            left: sym("b", ""),
            right: sym("a", ""),
            sign: Sign::NonNegative,
        },
    ];
    let st = equal(&ctx, sym("a", ""), num(0));
    let at = |a: i64, b: i64| refuted_at(&[("a", a), ("b", b)]);
    assert!(fails(st.clone(), at(2, 2)));
    assert!(!fails(st.clone(), at(1, 1)), "a > 1 is strict");
    assert!(!fails(st.clone(), at(3, 2)), "b < a there");
    assert!(!fails(st.clone(), at(-1, 5)), "a < 1 there");
    // Hypotheses may hold nowhere (a > 1 and a < 0): only a point refutes.
    assert!(!fails(st, differs()));
    // An identity proved for every state holds where they do.
    let square = equal(
        &ctx,
        prod(vec![sym("a", ""), sym("a", "")]),
        Term::Pow(Box::new(sym("a", "")), 2),
    );
    assert!(holds(square, identity()));
}

#[test]
fn a_square_root_in_a_hypothesis_is_held_to_its_square_at_the_point() {
    use cosserat_check::kernel::statement::Hypothesis;
    let mut ctx = context(&[("x", 0)]);
    // √x > 1, so x > 1.
    ctx.hypotheses = vec![Hypothesis {
        left: Term::Sqrt(Box::new(sym("x", ""))),
        right: num(1),
        sign: Sign::Positive,
    }];
    let st = equal(&ctx, sym("x", ""), num(0));
    let at = |x: Rational, root: Rational| Fact::Refutation {
        at: Evaluation {
            chain: 0,
            equality: 0,
            at: Vec::new(),
            point: vec![("x".to_owned(), x), ("√(x)".to_owned(), root)],
        },
        roots: Vec::new(),
    };
    assert!(fails(st.clone(), at(q(4, 1), q(2, 1))));
    assert!(!fails(st.clone(), at(q(1, 4), q(1, 2))), "√x = 1/2 there");
    assert!(
        !fails(st.clone(), at(q(1, 4), q(5, 1))),
        "a root that is not √x"
    );
    assert!(!fails(st, at(q(4, 1), q(-2, 1))), "the negative root");
}

/// A refutation's sides are evaluated at its index values only: each term with its
/// free letters fixed must give the component the whole tensor has there, including
/// where a letter free in a numerator is summed in its divisor, a constant carries
/// free letters, a slot is fixed and `grad` adds letters of its own.
#[test]
fn a_term_at_fixed_index_values_is_that_component_of_the_whole() {
    let ctx = context(&[("a", 1), ("T", 2), ("s", 0)]);
    let grad = Term::Grad {
        body: Box::new(prod(vec![sym("T", "kl"), sym("T", "kl"), sym("a", "c")])),
        symbol: "T".to_owned(),
        slots: vec![Slot::Letter('i'), Slot::Letter('j')],
    };
    let terms = vec![
        Term::Div(
            Box::new(prod(vec![sym("T", "ic"), sym("a", "i")])),
            Box::new(sum(vec![prod(vec![sym("a", "c"), sym("a", "c")]), num(1)])),
        ),
        sum(vec![
            prod(vec![sym("T", "ij"), sym("a", "j")]),
            prod(vec![leaf(Leaf::Eps, "ijk"), sym("a", "j"), sym("T", "k1")]),
            neg(prod(vec![
                leaf(Leaf::Delta, "ij"),
                sym("a", "j"),
                sym("s", ""),
            ])),
        ]),
        Term::Avg(Box::new(prod(vec![
            leaf(Leaf::Normal, "i"),
            leaf(Leaf::Normal, "j"),
            leaf(Leaf::Normal, "k"),
            leaf(Leaf::Normal, "k"),
            sym("T", "ij"),
            sym("a", "m"),
        ]))),
        sum(vec![
            Term::Const {
                value: q(2, 3),
                free: vec!['i', 'j'],
            },
            sym("T", "ji"),
        ]),
        prod(vec![sym("T", "2j"), sym("a", "i")]),
        grad,
    ];
    components_agree(&ctx, &terms, |t, at, env| t.at_indices(at, env).unwrap());
}

/// Each term, rewritten by `fixed` at each index value of its free letters, has there
/// the component the whole term has.
fn components_agree(
    ctx: &Context,
    terms: &[Term],
    fixed: impl Fn(&Term, &[(char, usize)], &cosserat_check::kernel::eval::Env) -> Term,
) {
    use cosserat_check::kernel::eval::{assignments, Env};
    for t in terms {
        let mut env = Env::new(ctx, &[]).unwrap();
        let whole = env.eval(t).unwrap();
        let letters = whole.letters().to_vec();
        assert!(!letters.is_empty());
        for (k, values) in assignments(3, letters.len()).iter().enumerate() {
            let at: Vec<(char, usize)> = letters
                .iter()
                .copied()
                .zip(values.iter().copied())
                .collect();
            let one = fixed(t, &at, &env);
            let value = env.eval(&one).unwrap();
            assert!(value.letters().is_empty(), "{one:?} keeps a letter");
            assert_eq!(value.comps(), &whole.comps()[k..=k], "{t:?} at {at:?}");
        }
    }
}

use crate::support::pairings::pairings;

fn deltas(p: &[(char, char)]) -> Term {
    prod(
        p.iter()
            .map(|&(a, b)| leaf(Leaf::Delta, &format!("{a}{b}")))
            .collect(),
    )
}

/// `Σ c_p P_p` over pairings with nonzero coefficients, in the given order.
fn combination(ps: &[Vec<(char, char)>], cs: &[i64], order: &[usize]) -> Term {
    let terms: Vec<Term> = order
        .iter()
        .filter(|&&k| cs[k] != 0)
        .map(|&k| prod(vec![num(cs[k]), deltas(&ps[k])]))
        .collect();
    if terms.is_empty() {
        Term::Const {
            value: q(0, 1),
            free: "ijklmp".chars().collect(),
        }
    } else {
        sum(terms)
    }
}

/// The blocks a proof compared orbits of, if it did.
fn orbit_blocks(st: Statement) -> Option<Vec<String>> {
    use cosserat_check::kernel::check::Checked;
    let proof = check(st, identity()).ok()?;
    proof.summary().iter().find_map(|c| match c {
        Checked::PolynomialIdentity {
            orbits: Some(o), ..
        } => Some(o.blocks.clone()),
        _ => None,
    })
}

/// An identity compared at one component per orbit must hold at every component: the
/// kernel's verdict on sums of δ pairings (rank 6, 729 components) is the verdict of
/// comparing every component, including for sides that agree at every index value
/// sorted along the letters and differ elsewhere (`+ P − P'` with two pairings that
/// only sorted values with four equal letters tell apart).
#[test]
fn orbits_decide_as_every_component_would() {
    use cosserat_check::kernel::eval::Env;
    let letters: Vec<char> = "ijklmp".chars().collect();
    let ps = pairings(&letters);
    assert_eq!(ps.len(), 15);
    let ctx = context(&[]);
    let index = |p: &[(char, char)]| ps.iter().position(|x| x == p).unwrap();
    // (ik)(jl)(mp) and (il)(jk)(mp): equal at every sorted index value.
    let p1 = index(&[('i', 'k'), ('j', 'l'), ('m', 'p')]);
    let p2 = index(&[('i', 'l'), ('j', 'k'), ('m', 'p')]);
    let (mut proved, mut orbits, mut refused) = (0, 0, 0);
    for seed in 1..=20u64 {
        let mut rng = cosserat_check::decide::random::Rng::new(seed);
        let symmetric = seed % 2 == 0;
        let cs: Vec<i64> = if symmetric {
            vec![rng.small(); 15]
        } else {
            (0..15).map(|_| rng.small()).collect()
        };
        let mut order: Vec<usize> = (0..15).collect();
        for k in (1..15).rev() {
            order.swap(k, rng.below(k + 1));
        }
        let left = combination(&ps, &cs, &(0..15).collect::<Vec<_>>());
        let mut twisted = cs.clone();
        match seed % 4 {
            // The same sum in another order.
            0 | 1 => {}
            // Equal at every sorted index value, different elsewhere.
            2 => {
                twisted[p1] += 1;
                twisted[p2] -= 1;
            }
            // One coefficient changed.
            _ => twisted[(seed as usize) % 15] += 1,
        }
        let right = combination(&ps, &twisted, &order);
        let truth = {
            let mut env = Env::new(&ctx, &[]).unwrap();
            env.eval(&left).unwrap().comps() == env.eval(&right).unwrap().comps()
        };
        let st = equal(&ctx, left, right);
        assert_eq!(holds(st.clone(), identity()), truth, "seed {seed}");
        if truth {
            proved += 1;
            if let Some(blocks) = orbit_blocks(st) {
                orbits += 1;
                assert!(symmetric, "seed {seed}: orbits of an unsymmetric sum");
                assert_eq!(blocks, ["ijklmp"]);
            }
        } else {
            refused += 1;
        }
    }
    assert_eq!((proved, orbits, refused), (10, 5, 10));
}

/// The isotropic moment of rank 6 with its right side split into definitions (one
/// in letters of its own) is proved at its 28 orbits; an ε, which a swap of its letters changes, and a tensor of fixed δ's that
/// agrees with ε ε at every sorted index value are compared component by component.
#[test]
fn a_side_is_symmetric_only_as_written_out_and_exchanged() {
    use cosserat_check::kernel::check::Checked;
    use cosserat_check::kernel::statement::Definition;
    let letters: Vec<char> = "ijklmp".chars().collect();
    let ps = pairings(&letters);
    let mut ctx = context(&[]);
    // P0: the first 7 pairings; P1: the other 8, written in the letters a…f.
    let first = sum(ps[..7].iter().map(|p| deltas(p)).collect());
    let rename = |c: char| {
        "abcdef"
            .chars()
            .nth(letters.iter().position(|&x| x == c).unwrap())
            .unwrap()
    };
    let rest: Vec<Term> = ps[7..]
        .iter()
        .map(|p| {
            deltas(
                &p.iter()
                    .map(|&(a, b)| (rename(a), rename(b)))
                    .collect::<Vec<_>>(),
            )
        })
        .collect();
    ctx.definitions = vec![
        Definition {
            name: "P0".into(),
            formal: letters.clone(),
            body: first,
        },
        Definition {
            name: "P1".into(),
            formal: "abcdef".chars().collect(),
            body: sum(rest),
        },
    ];
    let n6 = Term::Avg(Box::new(prod(
        letters
            .iter()
            .map(|c| leaf(Leaf::Normal, &c.to_string()))
            .collect(),
    )));
    let right = prod(vec![
        frac(1, 105),
        sum(vec![
            leaf(Leaf::Def("P0".into()), "ijklmp"),
            leaf(Leaf::Def("P1".into()), "ijklmp"),
        ]),
    ]);
    let st = equal(&ctx, n6.clone(), right.clone());
    let proof = check(st, identity()).unwrap();
    assert_eq!(proof.conclusion(), Conclusion::Holds);
    assert!(matches!(
        proof.summary(),
        [Checked::PolynomialIdentity { components: 28, orbits: Some(o), .. }, ..]
            if o.of == 729 && o.blocks == ["ijklmp"]
    ));
    // With 1/104 it is refused.
    let wrong = prod(vec![
        frac(1, 104),
        sum(vec![
            leaf(Leaf::Def("P0".into()), "ijklmp"),
            leaf(Leaf::Def("P1".into()), "ijklmp"),
        ]),
    ]);
    assert!(!holds(equal(&ctx, n6, wrong), identity()));
    // ε_ijk ε_lmp and δ_i1 δ_j2 δ_k3 δ_l1 δ_m2 δ_p3 agree wherever i ≤ j ≤ k and
    // l ≤ m ≤ p, and differ at i = 2, j = 1.
    let ee = prod(vec![leaf(Leaf::Eps, "ijk"), leaf(Leaf::Eps, "lmp")]);
    let fixed = prod(
        ["i1", "j2", "k3", "l1", "m2", "p3"]
            .iter()
            .map(|s| leaf(Leaf::Delta, s))
            .collect(),
    );
    let st = equal(&context(&[]), ee.clone(), fixed);
    assert!(!holds(st, identity()));
    assert!(holds(equal(&context(&[]), ee.clone(), ee), identity()));
}

/// The sides with their definitions written out have, at every index value, the
/// component the whole has there: definitions used at fixed values, with summed
/// letters of their own that the use site also writes, through another definition,
/// as a trace, and under a constant divisor, a power and an average.
#[test]
fn a_side_written_out_has_every_component_of_the_side() {
    use cosserat_check::kernel::eval::Env;
    use cosserat_check::kernel::statement::Definition;
    use cosserat_check::kernel::symmetry::{at_values, written_out};
    let mut ctx = context(&[("a", 1), ("T", 2), ("s", 0)]);
    let def = |name: &str, formal: &str, body: Term| Definition {
        name: name.into(),
        formal: formal.chars().collect(),
        body,
    };
    ctx.definitions = vec![
        // X_ij = T_ik T_jk: k is summed inside.
        def("X", "ij", prod(vec![sym("T", "ik"), sym("T", "jk")])),
        // Y_jk = X_jm a_m a_k + s δ_jk / 2, through X.
        def(
            "Y",
            "jk",
            sum(vec![
                prod(vec![
                    leaf(Leaf::Def("X".into()), "jm"),
                    sym("a", "m"),
                    sym("a", "k"),
                ]),
                Term::Div(
                    Box::new(prod(vec![sym("s", ""), leaf(Leaf::Delta, "jk")])),
                    Box::new(num(2)),
                ),
            ]),
        ),
        def(
            "N",
            "i",
            Term::Avg(Box::new(prod(vec![
                leaf(Leaf::Normal, "i"),
                leaf(Leaf::Normal, "k"),
                sym("a", "k"),
            ]))),
        ),
    ];
    let x = |slots: &str| leaf(Leaf::Def("X".into()), slots);
    let y = |slots: &str| leaf(Leaf::Def("Y".into()), slots);
    let terms = vec![
        // k is also a letter of the use site.
        prod(vec![x("ik"), sym("a", "k")]),
        sum(vec![
            y("ij"),
            x("ji"),
            neg(prod(vec![y("2j"), sym("a", "i")])),
        ]),
        prod(vec![
            x("kk"),
            leaf(Leaf::Def("N".into()), "i"),
            sym("a", "j"),
        ]),
        prod(vec![Term::Pow(Box::new(x("mm")), 2), y("i1")]),
    ];
    components_agree(&ctx, &terms, |t, at, env| {
        let [out, _] = written_out(env, t, &num(0)).expect("in the class");
        at_values(&out, at)
    });
    // Outside the class: a divisor that is not a constant, a square root.
    let env = Env::new(&ctx, &[]).unwrap();
    let div = Term::Div(Box::new(sym("a", "i")), Box::new(sym("s", "")));
    assert!(written_out(&env, &div, &sym("a", "i")).is_none());
    let root = Term::Sqrt(Box::new(sym("s", "")));
    assert!(written_out(&env, &root, &num(0)).is_none());
}

/// Two factors of a product may each sum the same letter in a scope of their own:
/// `(δ_iq δ_q2)(δ_jq δ_q1) a_k a_l a_m a_p = 0` is false (at i = 2, j = 1), and a
/// canonical form that flattened both scopes into one would find it symmetric in i and
/// j and compare only i ≤ j, where it holds (a forged report found this).
#[test]
fn products_that_sum_the_same_letter_stay_apart() {
    let ctx = context(&[("a", 1)]);
    let scope = |a: &str, b: &str| prod(vec![leaf(Leaf::Delta, a), leaf(Leaf::Delta, b)]);
    let left = prod(vec![
        scope("iq", "q2"),
        scope("jq", "q1"),
        sym("a", "k"),
        sym("a", "l"),
        sym("a", "m"),
        sym("a", "p"),
    ]);
    let zero = Term::Const {
        value: q(0, 1),
        free: "ijklmp".chars().collect(),
    };
    assert!(!holds(equal(&ctx, left.clone(), zero), identity()));
    assert!(holds(equal(&ctx, left.clone(), left), identity()));
}

/// Definitions that each read the one before twice double when written out: at 13
/// levels the written-out sides (8,192 terms) would cost more at each orbit than every
/// definition evaluated in full, and every component is compared instead.
#[test]
fn definitions_that_double_when_written_out_are_evaluated_in_full() {
    use cosserat_check::kernel::check::Checked;
    use cosserat_check::kernel::statement::Definition;
    let mut ctx = context(&[("A", 2)]);
    let swaps = ["jiklmp", "ikjlmp", "ijlkmp", "ijkmlp", "ijklpm", "ijklmp"];
    let d = |k: usize, slots: &str| leaf(Leaf::Def(format!("D{k}")), slots);
    ctx.definitions.push(Definition {
        name: "D0".into(),
        formal: "ijklmp".chars().collect(),
        body: prod(vec![sym("A", "ij"), sym("A", "kl"), sym("A", "mp")]),
    });
    for k in 1..=13 {
        ctx.definitions.push(Definition {
            name: format!("D{k}"),
            formal: "ijklmp".chars().collect(),
            body: sum(vec![d(k - 1, "ijklmp"), d(k - 1, swaps[(k - 1) % 6])]),
        });
    }
    let right = sum(vec![d(12, "ijklmp"), d(12, "jiklmp")]);
    let proof = check(equal(&ctx, d(13, "ijklmp"), right), identity()).unwrap();
    assert_eq!(proof.conclusion(), Conclusion::Holds);
    assert!(matches!(
        proof.summary(),
        [
            Checked::PolynomialIdentity {
                components: 729,
                orbits: None,
                ..
            },
            ..
        ]
    ));
}
