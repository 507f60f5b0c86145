//! The pairings of a list of index letters: the δ products of an isotropic moment
//! (3 for four letters, 15 for six, 945 for ten), for the moment tests and the bench.

/// Every way to split `ls` into pairs, each pairing in the order the letters come.
pub fn pairings(ls: &[char]) -> Vec<Vec<(char, char)>> {
    if ls.is_empty() {
        return vec![vec![]];
    }
    let mut out = Vec::new();
    for k in 1..ls.len() {
        let rest: Vec<char> = (ls[1..].iter().enumerate())
            .filter(|(j, _)| j + 1 != k)
            .map(|(_, c)| *c)
            .collect();
        for mut p in pairings(&rest) {
            p.insert(0, (ls[0], ls[k]));
            out.push(p);
        }
    }
    out
}

/// Each pairing of `letters` as a product of δ's in the file language
/// (`delta_ij delta_kl`), in the order of [`pairings`].
pub fn delta_products(letters: &[char]) -> Vec<String> {
    pairings(letters)
        .iter()
        .map(|p| {
            p.iter()
                .map(|(a, b)| format!("delta_{a}{b}"))
                .collect::<Vec<_>>()
                .join(" ")
        })
        .collect()
}
