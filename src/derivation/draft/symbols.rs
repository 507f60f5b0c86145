//! What the printed symbols of a paper are: from every occurrence, the declarations a
//! draft needs (tensors with their index slots, scalars, fields where a comma
//! derivative appears) and, for a symbol with a label, an accent or primes, a readable
//! name for its notation entry (`v_i^{(2,1)c}` → `v21c`, `\dot{\Gamma}` → `Gammadot`).
//!
//! Conventions of the draft, stated in the file it writes:
//! - a subscript of two or more characters, or of one letter that occurs more than once
//!   in the equation's subscripts, holds index slots (`\sigma_{ij}`, `n_i` in
//!   `\ell_i = R_g n_i`); digits are components (`\sigma_{12}`);
//! - a one-letter subscript that occurs once completes a scalar's name (`R_g`, `f_r`),
//!   unless it is one of i, j, k, l, m on a symbol written with index slots elsewhere
//!   (`t_k` where the paper has `t_i`); so does a subscript of one Greek letter
//!   (`\mu_\tau`), since the language's indices are Latin letters;
//! - a subscript found stray ([`Stems::stray`]) is read as the bare scalar;
//! - a subscript of the letters of the paper's vectors (`n` where it has `n_i`) labels,
//!   unless the equation indexes with them elsewhere (`\sigma_n + \tau_n`,
//!   `\sigma_{nn}`, but `\delta_{nm} a_n`); so does an upright one (`\sigma_{\mathrm{I}}`,
//!   `\tau_{\max}`, `\tau_{\rm max}`);
//! - δ_{ij}, e_{ijk} and ε_{ijk} are Kronecker's and Levi-Civita's symbols.

use crate::lang::latex::{roman_label, Atom, Math, MathKind};
use std::collections::{BTreeMap, BTreeSet};

/// One printed symbol, as a draft declares it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Symbol {
    /// The name in the language (`sigma`, `v21c`, `R_g`).
    pub name: String,
    /// Index slots (0 for a scalar).
    pub rank: usize,
    /// A comma derivative of it occurs: a field of the position.
    pub field: bool,
    /// The highest order of its comma derivatives (2 for `u_{i,jk}`), 0 for none.
    pub order: usize,
    /// The printed symbol as a notation key, with its first occurrence's index letters.
    pub key: (String, Vec<char>),
    /// Whether it needs a notation entry: it cannot be read as written (a label, an
    /// accent, primes, or a name the draft had to change).
    pub entry: bool,
    /// A component of a vector the paper declares (`u_1` beside `u_i`): read as written,
    /// never declared.
    pub component: bool,
    /// This occurrence is the base of a square (`T` in `T^2`).
    pub squared: bool,
    /// Why this occurrence is read as a symbol the paper may not mean: a superscript
    /// that looks like an exponent (`x^{\,2}`, `e^{x}`, `\pi^{2}`) is read as a label.
    pub doubt: Option<String>,
    /// Its comma derivatives as printed (`w_{i,m}^{c}`), each a notation key with its
    /// reading (`wc_i,m`), for a symbol that needs an entry.
    pub derivatives: BTreeSet<(String, String)>,
    /// This occurrence carries a stray subscript ([`Stems::stray`]).
    pub stray: bool,
    /// This occurrence is inside a bracket a comma differentiates (`(\sigma_{ij}
    /// v_j)_{,i}`): it varies with the position only if it is a field.
    pub differentiated: bool,
    /// For a scalar, the printed forms it is read from (`t^{(n)}`, and `t_{i}^{(n)}` with
    /// a stray subscript), each a notation key.
    pub printed: BTreeSet<String>,
}

/// What the paper's equations, all together, say of the stems of its symbols
/// ([`tensor_stem`]).
#[derive(Clone, Debug, Default)]
pub struct Stems {
    /// Stems of symbols that carry index slots somewhere.
    pub tensors: BTreeSet<String>,
    /// Stems whose subscript is stray (`t_i^{(n)} = t_i n_i`, where the paper prints
    /// `t^{(n)}` elsewhere): read as the bare scalar.
    pub stray: BTreeSet<String>,
    /// The letters that name vectors in the paper ([`vector_letters`]): a lone subscript
    /// of one of them is a label (`\sigma_n + \tau_n`, the normal and shear stresses
    /// where the paper has `n_i`), never an index shared by two symbols.
    pub vectors: BTreeSet<char>,
}

/// Whether a subscript is two or more of the paper's vector letters and nothing else
/// (`nn`, `nt`).
fn vector_letters_only(sub: &str, tensors: &Stems) -> bool {
    sub.chars().count() > 1 && sub.chars().all(|c| tensors.vectors.contains(&c))
}

/// The letters that name vectors in `m`: a plain Latin letter with a subscript of one
/// index letter or digit (`n` in `n_i`, `n_1`).
pub fn vector_letters(m: &Math, out: &mut BTreeSet<char>) {
    let mut atoms = Vec::new();
    atoms_of(m, (false, false), &mut atoms, &mut Vec::new());
    for Occurrence { atom: a, .. } in atoms {
        let mut base = a.base.chars();
        let (Some(letter), None) = (base.next(), base.next()) else {
            continue;
        };
        let one = a.sub.as_ref().is_some_and(|s| {
            let t = s.text.trim();
            t.len() == 1 && t.chars().all(|c| c.is_ascii_alphanumeric())
        });
        let plain = a.accent.is_none() && a.sup.is_none() && a.primes == 0;
        if letter.is_ascii_alphabetic() && one && plain {
            out.insert(letter);
        }
    }
}

/// The identity of a printed symbol: everything but its index letters.
pub type Key = String;

/// A key's fields: accent, base, label (the superscript), primes, suffix, rank.
pub fn fields(k: &Key) -> Option<[&str; 6]> {
    let f: Vec<&str> = k.split('|').collect();
    f.try_into().ok()
}

/// A key's label (`(1)`, `c`), empty for none.
pub fn label(k: &Key) -> &str {
    fields(k).map_or("", |f| f[2])
}

/// The key of the same symbol with another label.
pub fn with_label(k: &Key, label: &str) -> Option<Key> {
    let mut f = fields(k)?;
    f[2] = label;
    Some(f.join("|"))
}

/// The part of a key that names a printed symbol whatever its subscript (accent, base,
/// label, primes), when the key is of a symbol with index slots.
pub fn tensor_stem(key: &Key) -> Option<String> {
    let fields: Vec<&str> = key.split('|').collect();
    let [accent, base, sup, primes, suffix, rank] = fields[..] else {
        return None;
    };
    (suffix.is_empty() && rank != "0").then(|| format!("{accent}|{base}|{sup}|{primes}"))
}

/// Every symbol occurrence of one equation: (identity, the symbol), built-ins left out.
/// `tensors` holds the stems ([`tensor_stem`]) of symbols that carry index slots
/// elsewhere in the paper: a one-letter subscript on one of them is an index too.
pub fn occurrences(members: &[&Math], normal: Option<&str>, tensors: &Stems) -> Vec<(Key, Symbol)> {
    // A subscript letter is an index where two symbols share it (`n_i` in
    // `\ell_i = R_g n_i`) or one side repeats it (`u_i u_i`).
    let mut indices: BTreeSet<char> = BTreeSet::new();
    let mut bases: BTreeMap<char, BTreeSet<String>> = BTreeMap::new();
    // Letters met in a subscript of more than one character (`\delta_{nm}`): indices
    // whatever they name elsewhere.
    let mut in_longer: BTreeSet<char> = BTreeSet::new();
    // Letters of subscripts made only of the paper's vector letters (`\sigma_{nn}`, the
    // normal stress), and letters of every other subscript: the first label unless
    // the equation also has them in the second.
    let (mut of_vectors, mut elsewhere): (BTreeSet<char>, BTreeSet<char>) = Default::default();
    let mut atoms = Vec::new();
    for m in members {
        let mut own = Vec::new();
        let mut commas = Vec::new();
        atoms_of(m, (false, false), &mut own, &mut commas);
        let mut in_member: BTreeMap<char, usize> = BTreeMap::new();
        // A letter after a comma (`(\sigma_{ij} v_j)_{,i}`) is an index.
        for c in commas {
            in_longer.insert(c);
            *in_member.entry(c).or_default() += 1;
        }
        for Occurrence { atom: a, .. } in &own {
            if let Some(sub) = a
                .sub
                .as_ref()
                .filter(|s| greek_subscript(&s.text).is_none() && upright(&s.text).is_none())
            {
                if vector_letters_only(&sub.text, tensors) {
                    of_vectors.extend(sub.text.chars());
                    continue;
                }
                elsewhere.extend(sub.text.chars().filter(char::is_ascii_alphabetic));
                let letters = sub.text.chars().filter(char::is_ascii_alphanumeric);
                if letters.count() > 1 {
                    in_longer.extend(sub.text.chars().filter(char::is_ascii_alphabetic));
                }
                for c in sub.text.chars().filter(char::is_ascii_alphabetic) {
                    bases.entry(c).or_default().insert(a.base.clone());
                    *in_member.entry(c).or_default() += 1;
                }
            }
        }
        indices.extend(
            in_member
                .into_iter()
                .filter(|&(_, n)| n > 1)
                .map(|(c, _)| c),
        );
        atoms.extend(own);
    }
    indices.extend(
        bases
            .into_iter()
            .filter(|(_, b)| b.len() > 1)
            .map(|(c, _)| c),
    );
    // A vector's letter met only alone in subscripts labels (`\sigma_n`), and so does
    // one met only in subscripts of vector letters (`\sigma_{nn}`); met elsewhere too
    // (`\sigma_{mn} n_m n_n`), it indexes.
    let shared: Vec<char> = of_vectors.intersection(&elsewhere).copied().collect();
    in_longer.extend(shared.iter().copied());
    indices.extend(shared);
    indices.retain(|c| in_longer.contains(c) || !tensors.vectors.contains(c));
    atoms
        .into_iter()
        .filter_map(|o| {
            let (k, mut s) = symbol(o.atom, &indices, normal, tensors)?;
            s.squared = o.squared;
            s.differentiated = o.differentiated;
            Some((k, s))
        })
        .collect()
}

/// Whether `m` differentiates the normal inside a bracket (`(\sigma_{ij} n_j)_{,i}`):
/// whether the normal is a field of the position or a constant, the reader does not
/// guess.
pub fn differentiates_normal(m: &Math, normal: Option<&str>) -> bool {
    let mut atoms = Vec::new();
    atoms_of(m, (false, false), &mut atoms, &mut Vec::new());
    atoms
        .iter()
        .any(|o| o.differentiated && Some(o.atom.base.trim_start_matches('\\')) == normal)
}

/// An atom of a formula, with where it stands.
struct Occurrence<'m> {
    atom: &'m Atom,
    /// The base of a square.
    squared: bool,
    /// Inside a bracket a comma differentiates (`(\sigma_{ij} v_j)_{,i}`).
    differentiated: bool,
}

/// The atoms of `m`, in reading order (`squared` and `inside` say so of `m` itself),
/// and the letters after the comma of each bracket it differentiates (`i` in
/// `(\sigma_{ij} v_j)_{,i}`).
fn atoms_of<'m>(
    m: &'m Math,
    (squared, inside): (bool, bool),
    out: &mut Vec<Occurrence<'m>>,
    commas: &mut Vec<char>,
) {
    let mut go = |x: &'m Math| atoms_of(x, (false, inside), out, commas);
    match &m.kind {
        MathKind::Comma { of, indices } => {
            commas.extend(indices.chars().filter(char::is_ascii_alphabetic));
            atoms_of(of, (false, true), out, commas);
        }
        MathKind::Number(_) => {}
        MathKind::Atom(atom) => out.push(Occurrence {
            atom,
            squared,
            differentiated: inside,
        }),
        MathKind::Sum(terms) => terms.iter().for_each(|(_, t)| go(t)),
        MathKind::Product(fs) | MathKind::Tuple(fs) => fs.iter().for_each(go),
        MathKind::Power(a, b) => {
            let square = matches!(&b.kind, MathKind::Number(n) if n == "2");
            atoms_of(a, (square, inside), out, commas);
            atoms_of(b, (false, inside), out, commas);
        }
        MathKind::Quotient(a, b) => {
            go(a);
            go(b);
        }
        MathKind::Partial { of, by } => {
            go(of);
            go(by);
        }
        MathKind::Sqrt(a) | MathKind::Average(a) | MathKind::Abs(a) | MathKind::Apply(_, a) => {
            go(a)
        }
        MathKind::Matrix(rows) => rows.iter().flatten().for_each(go),
    }
}

/// The symbol an atom is, or `None` for δ, ε and the normal.
fn symbol(
    a: &Atom,
    indices: &BTreeSet<char>,
    normal: Option<&str>,
    tensors: &Stems,
) -> Option<(Key, Symbol)> {
    let base = a.base.trim_start_matches('\\');
    let sub = a.sub.as_ref().map(|s| s.text.as_str()).unwrap_or("");
    let (slots, derivative) = match sub.split_once(',') {
        Some((s, d)) => (s, !d.is_empty()),
        None => (sub, false),
    };
    let plain = a.accent.is_none() && a.sup.is_none() && a.primes == 0;
    let slot_count = slots.chars().filter(|c| c.is_ascii_alphanumeric()).count();
    if plain
        && ((base == "delta" && slot_count == 2)
            || (matches!(base, "e" | "varepsilon" | "epsilon") && slot_count == 3)
            || (base == "pi" && sub.is_empty())
            || normal == Some(base))
    {
        return None;
    }
    // A label that may be an exponent: spacing or commands in it, digits only, or on
    // e or π (the exponential, a power of π).
    let doubt = a.sup.as_ref().and_then(|sup| {
        let t = sup.text.as_str();
        let exponent_like = t.contains('\\')
            || t.contains(char::is_whitespace)
            || t.contains('~')
            || t.chars().all(|c| c.is_ascii_digit() || c == '.' || c == ',')
            || (matches!(base, "e" | "pi") && sub.is_empty());
        exponent_like.then(|| {
            format!(
                "the superscript `{t}` of `{}` reads as a label, not an exponent; write a power as `^{{2}}`, the exponential as `\\exp(…)`, or add a notation entry",
                a.base
            )
        })
    });
    // A one-letter subscript met once completes the name (R_g), and so does one digit
    // (J_2: a component `u_1` where the paper has a vector `u`, see `unique_names`);
    // any other subscript holds index slots.
    // A subscript of one Greek letter (`\mu_\tau`) names: the language's indices are
    // Latin letters, so it never holds a slot.
    let greek = greek_subscript(slots).is_some() && !derivative;
    // An upright subscript (`\sigma_{\mathrm{I}}`, `\sigma_{\text{eq}}`, `\tau_{\max}`)
    // names too.
    let roman = upright(slots).filter(|_| !derivative);
    let one_letter = slots.len() == 1 && slots.chars().all(|c| c.is_ascii_alphanumeric());
    let stem = format!(
        "{}|{}|{}|{}",
        a.accent.as_deref().unwrap_or(""),
        a.base,
        a.sup.as_ref().map(|s| s.text.as_str()).unwrap_or(""),
        a.primes
    );
    // `t_k^{(t)}` where the paper writes `t_i^{(t)}` with an index elsewhere: one of the
    // usual index letters on a symbol with slots is an index (`f_s` beside `f_i` stays
    // a name: s, r, g, p, n, t label as often as they index).
    let of_a_tensor = slots.chars().all(|c| "ijklm".contains(c)) && tensors.tensors.contains(&stem);
    let stray = !slots.is_empty()
        && !derivative
        && slots.chars().all(|c| c.is_ascii_lowercase())
        && tensors.stray.contains(&stem);
    // `\sigma_{nn}`: a subscript of vector letters that index nothing here.
    let of_vectors = !derivative
        && vector_letters_only(slots, tensors)
        && !slots.chars().any(|c| indices.contains(&c));
    let suffix = !stray
        && (greek
            || roman.is_some()
            || of_vectors
            || (one_letter
                && !derivative
                && !of_a_tensor
                && !slots.chars().any(|c| indices.contains(&c))));
    let mut name = String::from(base);
    if let Some(acc) = &a.accent {
        name.push_str(match acc.trim_start_matches('\\') {
            "dot" => "dot",
            "ddot" => "ddot",
            "hat" | "widehat" => "hat",
            "bar" | "overline" => "bar",
            "tilde" | "widetilde" => "tilde",
            "vec" => "vec",
            _ => "bf",
        });
    }
    if let Some(sup) = &a.sup {
        name.extend(sup.text.chars().filter(char::is_ascii_alphanumeric));
    }
    name.push_str(&"p".repeat(a.primes));
    let (rank, key_letters) = if suffix {
        let label = roman.unwrap_or_else(|| slots.trim().trim_start_matches('\\'));
        name = format!("{name}_{label}");
        (0, Vec::new())
    } else if stray {
        (0, Vec::new())
    } else {
        (
            slot_count,
            slots.chars().filter(char::is_ascii_alphanumeric).collect(),
        )
    };
    // Symbols of one name with different numbers of slots are different symbols.
    let identity = format!("{stem}|{}|{rank}", if suffix { slots } else { "" });
    let key = (printed_key(a, suffix.then_some(slots)), key_letters.clone());
    let printed = if rank == 0 {
        BTreeSet::from([key.0.clone()])
    } else {
        BTreeSet::new()
    };
    let mut derivatives = BTreeSet::new();
    if derivative && !plain {
        let whole = sub.replace(' ', "");
        let mut k = printed_key(a, None);
        k = k.replacen(&format!("_{{{}}}", slots), &format!("_{{{whole}}}"), 1);
        let (own, by): (String, String) = match whole.split_once(',') {
            Some((s, d)) => (s.to_owned(), d.to_owned()),
            None => (whole.clone(), String::new()),
        };
        derivatives.insert((k, format!("{name}_{own},{by}")));
    }
    Some((
        identity,
        Symbol {
            name,
            rank,
            field: derivative,
            order: sub.split_once(',').map_or(0, |(_, d)| {
                d.chars().filter(char::is_ascii_alphanumeric).count()
            }),
            key,
            entry: !plain || stray || roman.is_some(),
            component: false,
            squared: false,
            doubt,
            derivatives,
            stray,
            printed,
            differentiated: false,
        },
    ))
}

/// The vector of `symbols` whose component `key` is (`n_1` where the paper writes
/// `n_i`): the same printed symbol, with one index slot for the one digit of its
/// subscript.
pub fn vector_of(key: &Key, symbols: &BTreeMap<Key, Symbol>) -> Option<Key> {
    let fields: Vec<&str> = key.split('|').collect();
    let [accent, base, sup, primes, suffix, "0"] = fields[..] else {
        return None;
    };
    let digit = suffix.len() == 1 && suffix.bytes().all(|b| b.is_ascii_digit());
    let vector = format!("{accent}|{base}|{sup}|{primes}||1");
    (digit && symbols.contains_key(&vector)).then_some(vector)
}

/// The name an upright subscript gives (`\mathrm{eq}` → `eq`, `\max` → `max`): a
/// roman label, or one command that is no Greek letter.
fn upright(sub: &str) -> Option<&str> {
    let sub = sub.trim();
    roman_label(sub).or_else(|| {
        let name = sub.strip_prefix('\\')?;
        let word = !name.is_empty() && name.chars().all(|c| c.is_ascii_alphabetic());
        // `{\rm max}`, its space gone from the script: the label after `\rm`.
        let name = name
            .strip_prefix("rm")
            .filter(|r| !r.is_empty())
            .unwrap_or(name);
        (word && crate::lang::latex::greek_letter(name).is_none()).then_some(name)
    })
}

/// The Greek letter a subscript is, alone (`\tau`, `{\tau}`), or `None`.
fn greek_subscript(sub: &str) -> Option<char> {
    let name = sub.trim().strip_prefix('\\')?;
    crate::lang::latex::greek_letter(name)
}

/// The printed symbol without its derivative letters, as a notation key:
/// `\dot{\Gamma}_{ij}^{(1)}'`.
fn printed_key(a: &Atom, suffix: Option<&str>) -> String {
    let mut s = match &a.accent {
        Some(acc) => format!("{acc}{{{}}}", a.base),
        None => a.base.clone(),
    };
    let slots = a
        .sub
        .as_ref()
        .map(|sub| sub.text.split(',').next().unwrap_or("").to_owned())
        .filter(|t| !t.is_empty());
    if let Some(t) = suffix.map(str::to_owned).or(slots) {
        s.push_str(&format!("_{{{t}}}"));
    }
    if let Some(sup) = &a.sup {
        s.push_str(&format!("^{{{}}}", sup.text));
    }
    s.push_str(&"'".repeat(a.primes));
    s
}

/// Names the language reserves: built-in symbols and functions.
pub const RESERVED: &[&str] = &[
    "delta",
    "eps",
    "avg",
    "maxn",
    "sqrt",
    "abs",
    "exp",
    "log",
    "sin",
    "cos",
    "tan",
    "atan2",
    "min",
    "max",
    "grad",
    "variation",
    "det",
    "trace",
    "inv",
    "adj",
    "solve",
    "transpose",
    "identity",
    "vector",
    "tensor",
    "pi",
    "d",
];

/// Makes every symbol's name unique and unreserved: a second symbol that would take a
/// name gets a number after it. A `defined` symbol's name has no `_` (a definition's
/// subscript is its index letters): `J_2 = …` defines `J2`, read through an entry.
pub fn unique_names(symbols: &mut BTreeMap<Key, Symbol>, order: &[Key], defined: &BTreeSet<Key>) {
    let mut taken: BTreeSet<String> = RESERVED.iter().map(|s| (*s).to_owned()).collect();
    // `R_g` is read as `R` with index g where a tensor `R` is declared: such a scalar
    // takes the name `Rg`, through a notation entry.
    let tensors: BTreeSet<String> = symbols
        .values()
        .filter(|s| s.rank > 0)
        .map(|s| s.name.clone())
        .collect();
    let vectors: BTreeSet<String> = symbols
        .values()
        .filter(|s| s.rank == 1)
        .map(|s| s.name.clone())
        .collect();
    for (k, s) in symbols.iter_mut() {
        if let Some((stem, sub)) = s.name.split_once('_') {
            let digits = sub.chars().all(|c| c.is_ascii_digit());
            if s.rank == 0 && digits && vectors.contains(stem) && !s.entry {
                s.component = true;
            } else if s.rank == 0 && (digits || tensors.contains(stem) || defined.contains(k)) {
                // A scalar's name never ends in `_` and digits (that spells a
                // component): `h_2` is `h2`.
                s.name = format!("{stem}{sub}");
                s.entry = true;
            }
        }
    }
    for k in order {
        let Some(s) = symbols.get_mut(k) else {
            continue;
        };
        let mut name = s.name.clone();
        let mut n = 2;
        while taken.contains(&name) {
            // Before a name's subscript: `R_g` becomes `R2_g`, never `R_g2`.
            name = match s.name.split_once('_') {
                Some((stem, sub)) => format!("{stem}{n}_{sub}"),
                None => format!("{}{n}", s.name),
            };
            n += 1;
        }
        taken.insert(name.clone());
        // A renamed symbol (`d` is reserved: `d2`) is read through an entry.
        s.entry |= name != s.name;
        s.name = name;
    }
}
