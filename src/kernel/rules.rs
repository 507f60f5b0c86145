//! Polynomial constraints, each solved for a power of a variable of its own: the
//! rewrite rules `v^d → value` that reduce a claim's difference.
//!
//! A constraint g = 0 in which a variable v occurs in one term only, as c·v^d with a
//! constant c, says v^d = −(g − c·v^d)/c. Rewriting a monomial divisible by v^d
//! subtracts a multiple of g, so a difference that reduces to 0 vanishes wherever every
//! constraint holds: the reduction is sound whatever the rules are. It is complete as
//! well when no rule's variable occurs in any rule but its own (which [`Rule::solve`]
//! demands): the leading monomials v^d are then pairwise coprime in an elimination
//! order, so the constraints form a Gröbner basis, and a polynomial in their ideal is
//! the only kind that reduces to 0.

use super::poly::{Monomial, Poly, PolyError, Var, VarTable};
use super::rational::Rational;

/// `var^power = value`: a constraint solved for a power of one variable, or the
/// square root of `value` (`nonnegative`: a point must take the root ≥ 0). An identity
/// proved modulo `r² = x` holds on both branches, so the root's sign matters only to a
/// refutation.
#[derive(Clone, Debug, PartialEq)]
pub struct Rule {
    pub var: Var,
    pub power: u32,
    pub value: Poly,
    pub nonnegative: bool,
}

impl Rule {
    /// `g = 0` solved for a power of the candidate that comes first by `key`, among
    /// those that occur in `g` once, alone, as c·v^d with a rational c. `None` when
    /// there is none, when `g` has a negative power, or when the rules would not stay
    /// triangular: `g` reads a variable of an earlier rule, or the candidate occurs in
    /// an earlier rule.
    pub fn solve<K: Ord>(
        g: &Poly,
        earlier: &[Rule],
        candidate: impl Fn(Var) -> bool,
        key: impl Fn(Var, u32) -> K,
    ) -> Option<Rule> {
        let reads = |p: &Poly, v: Var| p.terms().any(|(m, _)| m.exponent(v) != 0);
        if g.terms()
            .any(|(m, _)| m.factors().iter().any(|&(_, e)| e < 0))
            || earlier.iter().any(|r| reads(g, r.var))
        {
            return None;
        }
        let occurrences = |v: Var| g.terms().filter(|(m, _)| m.exponent(v) != 0).count();
        let (var, power, c) = g
            .terms()
            .filter_map(|(m, c)| match m.factors() {
                [(v, d)] => Some((*v, u32::try_from(*d).ok()?, c.clone())),
                _ => None,
            })
            .filter(|&(v, _, _)| {
                candidate(v)
                    && occurrences(v) == 1
                    && !earlier.iter().any(|r| r.var == v || reads(&r.value, v))
            })
            .min_by_key(|&(v, d, _)| key(v, d))?;
        let term = Poly::term(Monomial::var(var, i64::from(power)), c.clone());
        let scale = Poly::constant(-&c.recip()?);
        let value = (g - &term).checked_mul(&scale).ok()?;
        Some(Rule {
            var,
            power,
            value,
            nonnegative: false,
        })
    }

    /// The square root of a polynomial `radicand` (no negative power, reduced by the
    /// earlier rules) as a variable of its own, named by [`root_name`].
    pub fn square_root(radicand: Poly, names: &mut VarTable) -> Rule {
        let var = names.intern(&root_name(&radicand, names));
        Rule {
            var,
            power: 2,
            value: radicand,
            nonnegative: true,
        }
    }

    /// Whether the rule holds at a point (variables it leaves out are 0).
    pub fn holds_at(&self, value: &dyn Fn(Var) -> Rational) -> bool {
        let x = value(self.var);
        let power = x.pow(i64::from(self.power));
        power.is_some() && power == self.value.eval(value) && !(self.nonnegative && x.is_negative())
    }
}

/// The name of the variable that stands for √radicand: the same whatever the numbering
/// of the variables (its terms written with their factors by name and sorted), so that
/// the kernel and the search name one root alike.
pub fn root_name(radicand: &Poly, names: &VarTable) -> String {
    let mut terms: Vec<(String, Rational)> = radicand
        .terms()
        .map(|(m, c)| {
            let mut factors: Vec<String> = m
                .factors()
                .iter()
                .map(|&(v, e)| match e {
                    1 => names.name(v).to_owned(),
                    _ => format!("{}^{e}", names.name(v)),
                })
                .collect();
            factors.sort();
            (factors.join("*"), c.clone())
        })
        .collect();
    terms.sort_by(|a, b| a.0.cmp(&b.0));
    let mut out = String::new();
    for (k, (factors, c)) in terms.iter().enumerate() {
        let (sign, size) = if c.is_negative() {
            ("-", -c)
        } else {
            ("+", c.clone())
        };
        match (k, sign) {
            (0, "-") => out.push('-'),
            (0, _) => {}
            _ => out.push_str(&format!(" {sign} ")),
        }
        out.push_str(&match (factors.is_empty(), size.is_one()) {
            (true, _) => size.to_string(),
            (false, true) => factors.clone(),
            (false, false) => format!("{size}*{factors}"),
        });
    }
    // A root's name is read inside the name of a root of a radicand that holds it:
    // past a length, a digest keeps every name short (and still the same for both).
    if out.chars().count() <= MAX_NAME {
        format!("√({out})")
    } else {
        let digest = out.bytes().fold(0xcbf2_9ce4_8422_2325_u64, |h, b| {
            (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
        });
        format!("√#{digest:016x}")
    }
}

/// The longest radicand written out in a root's name (see [`root_name`]).
const MAX_NAME: usize = 300;

/// `p` reduced by the rules: no monomial left that a rule's `var^power` divides. Each
/// step replaces one term; more than `steps` of them is [`PolyError::TooLarge`].
///
/// A division by a single term (`s_ij / (2 tau)`) leaves negative powers, which no
/// rule divides: `p` is first multiplied by the monomial that clears them, nonzero
/// wherever `p` is defined, so that the result is zero exactly where `p` is.
pub fn reduce(p: &Poly, rules: &[Rule], steps: usize) -> Result<Poly, PolyError> {
    if rules.is_empty() {
        return Ok(p.clone());
    }
    let mut lowest: Vec<(Var, i64)> = Vec::new();
    for (m, _) in p.terms() {
        for &(v, e) in m.factors() {
            match lowest.iter_mut().find(|(w, _)| *w == v) {
                Some((_, l)) => *l = (*l).min(e),
                None => lowest.push((v, e)),
            }
        }
    }
    let clearing = Monomial::checked_from_factors(
        lowest
            .into_iter()
            .filter(|&(_, e)| e < 0)
            .map(|(v, e)| (v, -e))
            .collect(),
    )
    .ok_or(PolyError::ExponentTooLarge)?;
    let mut p = p.checked_mul(&Poly::term(clearing, Rational::int(1)))?;
    // The clearing made every exponent ≥ 0, and the rules' values have none below 0.
    // A term with v^e, e ≥ d, becomes (the term without v^(d·⌊e/d⌋)) · value^⌊e/d⌋,
    // summed (equal monomials merged) pass by pass until no rule applies; a value's
    // powers are kept, and every term formed counts against `steps`.
    let mut left = steps;
    let mut powers: Vec<Vec<Poly>> = rules.iter().map(|r| vec![r.value.clone()]).collect();
    loop {
        let mut changed = false;
        let mut out: Vec<(Monomial, Rational)> = Vec::with_capacity(p.num_terms());
        let mut sums: Vec<Poly> = Vec::new();
        for (m, c) in p.terms() {
            let Some(k) = rules
                .iter()
                .position(|r| m.exponent(r.var) >= i64::from(r.power))
            else {
                out.push((m.clone(), c.clone()));
                continue;
            };
            changed = true;
            let (rule, e) = (&rules[k], m.exponent(rules[k].var));
            let d = i64::from(rule.power);
            let q = usize::try_from(e / d).map_err(|_| PolyError::ExponentTooLarge)?;
            while powers[k].len() < q {
                let next = powers[k]
                    .last()
                    .expect("the first power")
                    .checked_mul(&rule.value)?;
                left = left
                    .checked_sub(next.num_terms())
                    .ok_or(PolyError::TooLarge)?;
                powers[k].push(next);
            }
            let rest = m
                .checked_mul(&Monomial::var(rule.var, -(e / d) * d))
                .ok_or(PolyError::ExponentTooLarge)?;
            let term = Poly::term(rest, c.clone()).checked_mul(&powers[k][q - 1])?;
            left = left
                .checked_sub(term.num_terms())
                .ok_or(PolyError::TooLarge)?;
            sums.push(term);
        }
        if !changed {
            return Ok(p);
        }
        // All the terms at once, sorted and merged: adding the sums one by one would
        // merge the whole polynomial for each.
        for t in &sums {
            out.extend(t.terms().map(|(m, c)| (m.clone(), c.clone())));
        }
        p = Poly::from_terms(out);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::poly::VarTable;

    fn q(n: i64) -> Rational {
        Rational::int(n)
    }

    #[test]
    fn a_deviator_of_given_intensity() {
        // s1² + s2² + (s1 + s2)² = 2 t²: solved for t², the only pure power.
        let mut names = VarTable::new();
        let (s1, s2, t) = (names.intern("s1"), names.intern("s2"), names.intern("t"));
        let (a, b, c) = (Poly::var(s1), Poly::var(s2), Poly::var(t));
        let g = &(&(&(&a * &a) + &(&b * &b)) + &(&(&a + &b) * &(&a + &b)))
            - &(&(&c * &c) * &Poly::constant(q(2)));
        let rule = Rule::solve(&g, &[], |_| true, |v, d| (d, v)).unwrap();
        let rules = std::slice::from_ref(&rule);
        assert_eq!((rule.var, rule.power), (t, 2));
        // J2 − t² reduces to 0; t alone and t³ − t·J2 do not, and t³ becomes t·J2.
        let j2 = &(&g + &(&(&c * &c) * &Poly::constant(q(2))))
            * &Poly::constant(Rational::ratio(1, 2).unwrap());
        let zero = reduce(&(&j2 - &(&c * &c)), rules, 1000).unwrap();
        assert!(zero.is_zero());
        assert_eq!(reduce(&c, rules, 1000).unwrap(), c);
        let cubed = reduce(&(&(&c * &c) * &c), rules, 1000).unwrap();
        assert_eq!(cubed, (&c * &j2));
        // J2/t² − 1 (a division by a single term) is cleared, then reduced to 0.
        let over = Poly::term(Monomial::var(t, -2), q(1));
        let ratio = &(&j2 * &over) - &Poly::constant(q(1));
        assert!(reduce(&ratio, rules, 1000).unwrap().is_zero());
        // Too few steps is a limit, not a remainder.
        assert_eq!(
            reduce(&(&c * &c).pow(4), rules, 3),
            Err(PolyError::TooLarge)
        );
    }

    #[test]
    fn only_a_pure_power_of_its_own_is_solved_for() {
        let mut names = VarTable::new();
        let (x, y) = (names.intern("x"), names.intern("y"));
        let (a, b) = (Poly::var(x), Poly::var(y));
        // x·y = 1 has no pure power; x² + x·y = 1 has none either (x occurs twice).
        let one = Poly::constant(q(1));
        assert!(Rule::solve(&(&(&a * &b) - &one), &[], |_| true, |v, d| (d, v)).is_none());
        let g = &(&(&a * &a) + &(&a * &b)) - &one;
        assert!(Rule::solve(&g, &[], |_| true, |v, d| (d, v)).is_none());
        // y² = x solves for y (x occurs once too, but to the first power: preferred).
        let g = &(&b * &b) - &a;
        let r = Rule::solve(&g, &[], |_| true, |v, d| (d, v)).unwrap();
        assert_eq!((r.var, r.power), (x, 1));
        // A second rule may not read the first one's variable.
        assert!(Rule::solve(
            &(&a - &one),
            std::slice::from_ref(&r),
            |_| true,
            |v, d| (d, v)
        )
        .is_none());
        // Nor be solved for a variable the first one's value reads.
        let g2 = &(&b * &b).pow(2) - &one;
        assert!(Rule::solve(&g2, &[r], |_| true, |v, d| (d, v)).is_none());
    }

    #[test]
    fn a_rule_is_checked_at_a_point() {
        let mut names = VarTable::new();
        let (x, y) = (names.intern("x"), names.intern("y"));
        let rule = Rule {
            var: x,
            power: 2,
            value: &Poly::var(y) + &Poly::constant(q(1)),
            nonnegative: false,
        };
        let at = |x0: i64, y0: i64| move |v: Var| q(if v == x { x0 } else { y0 });
        assert!(rule.holds_at(&at(3, 8)));
        assert!(rule.holds_at(&at(-3, 8)));
        assert!(!rule.holds_at(&at(3, 7)));
        // A square root takes the branch ≥ 0 only.
        let root = Rule {
            nonnegative: true,
            ..rule
        };
        assert!(root.holds_at(&at(3, 8)));
        assert!(!root.holds_at(&at(-3, 8)));
    }

    #[test]
    fn a_root_is_named_alike_whatever_the_numbering() {
        let (mut a, mut b) = (VarTable::new(), VarTable::new());
        let (x, y) = (a.intern("x"), a.intern("y"));
        let (y2, x2) = (b.intern("y"), b.intern("x"));
        let p = &(&Poly::var(x) * &Poly::var(x)) + &(&Poly::var(y) * &Poly::constant(q(3)));
        let r = &(&Poly::var(x2) * &Poly::var(x2)) + &(&Poly::var(y2) * &Poly::constant(q(3)));
        assert_eq!(root_name(&p, &a), root_name(&r, &b));
        assert_eq!(root_name(&p, &a), "√(x^2 + 3*y)");
        let m = &Poly::constant(q(1)) - &(&Poly::var(y) * &Poly::constant(q(2)));
        assert_eq!(root_name(&m, &a), "√(1 - 2*y)");
    }
}
