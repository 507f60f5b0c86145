//! Small files a hostile author could write against the kernel's promises: no integer
//! wraps into a proof, no rank allocates before it is bounded, no count wraps past a
//! cap, and a displacement potential is read, not a crash.

use crate::common;

use common::{error_of, outcomes_of};
use cosserat_check::decide::Strength;
use cosserat_check::derivation::{load_str, Verdict};

const HEAD: &str = "paper = \"hostile\"\nsection = \"h\"\ntitle = \"h\"\ndimension = 3\n";

fn claim(id: &str, expect: &str, sides: &str) -> String {
    let reason = if expect == "holds" {
        String::new()
    } else {
        "reason = \"false\"\n".to_owned()
    };
    format!("[[claim]]\nid = \"{id}\"\nprinted = 'x'\nexpect = \"{expect}\"\n{reason}sides = {sides}\n\n")
}

/// a0 = x^64, a1 = a0^64, then squarings: a21 = x^(2^32), whose exponent wrapped to 0
/// in an unchecked `i32` and made `a21 = 1` a proved identity; a29 = x^(2^40) is the
/// largest power the kernel represents, a30 lies beyond it.
fn powers() -> String {
    let mut defs = vec!["\"a0 = x^64\"".to_owned(), "\"a1 = a0^64\"".to_owned()];
    for k in 1..30 {
        defs.push(format!("\"a{} = a{k} a{k}\"", k + 1));
    }
    format!(
        "{HEAD}scalars = [\"x\"]\ndefine = [{}]\n\n",
        defs.join(", ")
    )
}

#[test]
fn a_power_whose_exponent_would_wrap_is_decided_exactly_or_not_at_all() {
    let text = powers()
        + &claim("wrap", "fails", "[\"a21\", \"1\"]")
        + &claim("wrap-inverse", "fails", "[\"a20\", \"1/a20\"]")
        + &claim("true-but-huge", "holds", "[\"a21\", \"a20 a20\"]")
        + &claim("largest", "fails", "[\"a29\", \"1\"]")
        + &claim("beyond", "fails", "[\"a30\", \"1\"]");
    let got: Vec<(Verdict, Strength)> = outcomes_of(&text)
        .iter()
        .map(|o| (o.verdict(), o.strength()))
        .collect();
    let (fails, holds) = (
        (Verdict::Fails, Strength::Proof),
        (Verdict::Holds, Strength::Proof),
    );
    assert_eq!(&got[..4], &[fails, fails, holds, fails]);
    // Beyond the bound: no verdict at all, never a wrapped one.
    assert_eq!(got[4].0, Verdict::Undecided, "{got:?}");
}

#[test]
fn a_declared_rank_beyond_the_bound_is_a_located_error() {
    let text = format!(
        "{HEAD}tensors = [\"T_abcdefghijklmnopqrst\"]\n\n{}",
        claim(
            "r",
            "holds",
            "[\"T_abcdefghijklmnopqrst\", \"T_abcdefghijklmnopqrst\"]"
        )
    );
    let e = load_str("f.toml", &text).unwrap_err().to_string();
    assert!(e.contains("f.toml:5:12"), "{e}");
    assert!(e.contains("`T` has rank 20"), "{e}");
    // Rank 10 is the largest in 3D, and is accepted.
    let ok = format!(
        "{HEAD}tensors = [\"T_abcdefghij\"]\n\n{}",
        claim("r", "holds", "[\"T_abcdefghij\", \"T_abcdefghij\"]")
    );
    assert!(load_str("f.toml", &ok).is_ok());
}

#[test]
fn intermediates_beyond_the_bound_are_located_errors() {
    // Eleven free indices in 3D: 177,147 components.
    let free = format!(
        "{HEAD}tensors = [\"a_i\"]\n\n{}",
        claim(
            "free",
            "holds",
            "[\"a_i a_j a_k a_l a_m a_n a_p a_q a_r a_s a_t\", \"a_i a_j a_k a_l a_m a_n a_p a_q a_r a_s a_t\"]"
        )
    );
    let e = error_of(&free);
    assert!(e.contains("11 free indices"), "{e}");
    assert!(e.contains("f.toml:"), "{e}");
    // Thirteen letters in one product (a scalar in the end): 3^13 index values.
    let letters = "a_i a_i b_j b_j c_k c_k d_l d_l e_m e_m f_n f_n g_p g_p h_q h_q A_rs A_rs B_tu B_tu C_vw C_vw D_x D_x";
    let wide = format!(
        "{HEAD}tensors = [\"a_i\", \"b_i\", \"c_i\", \"d_i\", \"e_i\", \"f_i\", \"g_i\", \"h_i\", \"A_ij\", \"B_ij\", \"C_ij\", \"D_i\"]\n\n{}",
        claim("wide", "holds", &format!("[\"{letters}\", \"{letters}\"]"))
    );
    let e = error_of(&wide);
    assert!(e.contains("index letters"), "{e}");
}

#[test]
fn a_displacement_potential_is_substituted() {
    let head = format!(
        "{HEAD}position = \"x\"\nfields = [\"u_i\", \"phi\"]\nassume = [\"u_i = phi_,i\"]\n\n"
    );
    let text = head.clone()
        + &claim("curl-free", "holds", "[\"u_i,j - u_j,i\", \"0\"]")
        + &claim("divergence", "holds", "[\"u_k,k\", \"phi_,kk\"]")
        + &claim("not-symmetric-zero", "fails", "[\"u_i,j + u_j,i\", \"0\"]");
    let verdicts: Vec<Verdict> = outcomes_of(&text).iter().map(|o| o.verdict()).collect();
    assert_eq!(verdicts, [Verdict::Holds, Verdict::Holds, Verdict::Fails]);
    // One component set to a derivative is not a polynomial in components: a located
    // error, not a crash.
    let component = format!(
        "{HEAD}position = \"x\"\nfields = [\"u_i\", \"phi\"]\nassume = [\"u_1 = phi_,1\"]\n\n{}",
        claim("c", "holds", "[\"u_1\", \"phi_,1\"]")
    );
    let e = error_of(&component);
    assert!(e.contains("f.toml:"), "{e}");
    assert!(e.contains("polynomial in the components"), "{e}");
}

#[test]
fn a_count_of_readings_that_would_wrap_is_refused_like_any_over_the_cap() {
    // 64 symbols with two readings each: 2^64 combinations, which wrapped to 0 (and
    // other products to 1) in an unchecked product.
    let mut notation = String::from("[notation]\n");
    let mut printed = Vec::new();
    for k in 0..64 {
        notation.push_str(&format!("'Q^{{({k})}}' = [\"x\", \"y\"]\n"));
        printed.push(format!("Q^{{({k})}}"));
    }
    let text = format!(
        "{HEAD}scalars = [\"x\", \"y\"]\n\n[[claim]]\nid = \"many\"\nprinted = '{} = 0'\nexpect = \"fails\"\nreason = \"false\"\nsides = [\"x\", \"0\"]\n\n{notation}",
        printed.join(" + ")
    );
    let file = load_str("f.toml", &text).unwrap();
    let rows = cosserat_check::cli::decide_all(std::slice::from_ref(&file), None).unwrap();
    let t = &rows[0].transcription;
    assert_eq!(t.label(), "hand", "{t:?}");
    let shown = format!("{t:?}");
    assert!(shown.contains("more than 2^64 combinations"), "{shown}");
}

fn limit(id: &str, function: &str, to: &str, value: &str, given: &str) -> String {
    format!(
        "[[claim]]\nid = \"{id}\"\nprinted = 'x'\nexpect = \"holds\"\nstrategy = \"limit\"\n\
         function = \"{function}\"\nin = \"x\"\ntends_to = \"{to}\"\nlimit = \"{value}\"\n{given}\n"
    )
}

/// A limit read off the lowest orders holds only where their coefficients do not
/// vanish: with a parameter `a` that can be 0 in the box, each of these statements is
/// false at a = 0 (or about no point at all), so none may be proved.
#[test]
fn a_limit_whose_leading_coefficient_can_vanish_is_never_proved() {
    let text = format!("{HEAD}scalars = [\"x\", \"a\"]\n\n")
        // At a = 0 the function is 1: not infinite.
        + &limit("infinite", "(a x + x^2)/x^2", "0", "infinity", "given = [\"-1 <= a <= 1\"]")
        // At a = 0 it is 1/x: not 0.
        + &limit("zero", "x^2/(a x + x^3)", "0", "0", "given = [\"0 <= a <= 1\"]")
        + &limit("zero-at-a-point", "x^2/(a x + x^3)", "0", "0", "given = [\"0 <= a <= 0\"]")
        // Undefined for every x when a = 0.
        + &limit("nowhere", "(a x + x^2)/(a x)", "0", "1", "given = [\"0 <= a <= 0\"]")
        // Controls: a coefficient of one sign on the box, and a divisor a that only
        // removes the points a = 0, where the function is undefined for every x.
        + &limit("one-sign", "(a x + x^2)/x^2", "0", "infinity", "given = [\"1 <= a <= 2\"]")
        + &limit("divisor-free-of-x", "(a x + x^2)/(a x)", "0", "1", "given = [\"-1 <= a <= 1\"]");
    let got: Vec<(Verdict, Strength)> = outcomes_of(&text)
        .iter()
        .map(|o| (o.verdict(), o.strength()))
        .collect();
    for (k, id) in ["infinite", "zero", "zero-at-a-point", "nowhere"]
        .iter()
        .enumerate()
    {
        assert_ne!(got[k].0, Verdict::Holds, "{id}: {got:?}");
    }
    let proved = (Verdict::Holds, Strength::Proof);
    assert_eq!(&got[4..], &[proved, proved], "{got:?}");
}

/// A variable fixed by an assumption (x = y) is not free: a limit or a monotonicity
/// in it is not refuted as if it were.
#[test]
fn a_claim_in_a_variable_an_assumption_fixes_is_not_refuted() {
    let text = format!("{HEAD}scalars = [\"x\", \"y\"]\n\n")
        + &limit("limit", "x", "0", "0", "assume = [\"x = y\"]");
    let got = outcomes_of(&text);
    assert_ne!(got[0].verdict(), Verdict::Fails, "{:?}", got[0]);
}

/// x²/x is undefined at 0: 0 is not one of its roots, and "no real root" holds.
#[test]
fn a_root_where_the_function_is_undefined_is_not_a_root() {
    let roots = |id: &str, list: &str, expect: &str| {
        format!(
            "[[claim]]\nid = \"{id}\"\nprinted = 'x'\nexpect = \"{expect}\"\nreason = \"r\"\n\
             strategy = \"roots\"\nfunction = \"x^2/x\"\nin = \"x\"\nroots = {list}\n\n"
        )
    };
    let text = format!("{HEAD}scalars = [\"x\"]\n\n")
        + &roots("zero", "[\"0\"]", "fails")
        + &roots("none", "[]", "holds");
    let got: Vec<Verdict> = outcomes_of(&text).iter().map(|o| o.verdict()).collect();
    assert_eq!(got, [Verdict::Fails, Verdict::Holds]);
}

/// Ten nested derivatives of a field: the exact route finds the sides differ, and the
/// second evaluation, by central differences, would take (4d)^10 evaluations. It is
/// refused at once (more than four nested differences), so the claim is undecided in
/// well under a second instead of running for hours.
#[test]
fn nested_derivatives_past_four_are_not_taken_by_central_differences() {
    let text = "section = \"t\"\ntitle = \"t\"\ndimension = 3\nposition = \"x\"\nfields = [\"phi\"]\n\n\
                [[claim]]\nid = \"deep\"\nprinted = 'x'\nexpect = \"fails\"\nreason = \"r\"\n\
                sides = [\"d(d(d(d(d(d(d(d(d(d(phi)/dx_1)/dx_1)/dx_1)/dx_1)/dx_1)/dx_1)/dx_1)/dx_1)/dx_1)/dx_1\", \"phi\"]\n";
    let got = outcomes_of(text);
    assert_eq!(got[0].verdict(), Verdict::Undecided, "{:?}", got[0]);
    let finding = format!("{:?}", got[0].finding);
    assert!(finding.contains("nested derivatives"), "{finding}");
}

/// A proportionality whose factor reads a parameter the box fixes: "where the factor
/// ≠ 0" could be empty (G b_i ∝ b_i on G = 0 is false), so the kernel proves nothing.
#[test]
fn a_factor_of_a_parameter_the_box_fixes_proves_nothing() {
    for (given, left) in [
        ("[\"G >= 0\", \"G <= 0\"]", "G b_i"),
        ("[\"G >= 1\", \"G <= 1\"]", "(G - 1) b_i"),
    ] {
        let text = format!(
            "{HEAD}tensors = [\"b_i\"]\nscalars = [\"G\"]\n\n[[claim]]\nid = \"pinned\"\nprinted = 'x'\nexpect = \"fails\"\nreason = \"false on the box\"\nstrategy = \"proportional\"\ngiven = {given}\nsides = [\"{left}\", \"b_i\"]\n"
        );
        let o = &outcomes_of(&text)[0];
        assert_ne!(
            o.verdict(),
            Verdict::Holds,
            "{}",
            cosserat_check::report::evidence(o)
        );
    }
}

/// The zeroth power of a quotient keeps no divisor: `(1/(1 − 2ν))^0 + 1` once left a
/// divisor of multiplicity 0 that a later product cancelled below zero (an overflow,
/// found by the fuzzer in an inverse matrix). It is 2 wherever 1 − 2ν ≠ 0.
#[test]
fn the_zeroth_power_of_a_quotient_is_one_where_it_is_defined() {
    let text = format!("{HEAD}scalars = [\"nu\"]\ndefine = [\"K = 1 / (1 - 2 nu)\"]\n\n")
        + &claim(
            "zeroth",
            "holds",
            "[\"(K^0 + 1) (1 - 2 nu)\", \"2 (1 - 2 nu)\"]",
        )
        + &claim(
            "zeroth-wrong",
            "fails",
            "[\"K^0 (1 - 2 nu)\", \"2 (1 - 2 nu)\"]",
        );
    let outcomes = outcomes_of(&text);
    assert_eq!(outcomes[0].verdict(), Verdict::Holds, "{:?}", outcomes[0]);
    assert_eq!(outcomes[0].strength(), Strength::Proof);
    assert_eq!(outcomes[1].verdict(), Verdict::Fails, "{:?}", outcomes[1]);
}
