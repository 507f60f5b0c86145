//! The paper's derivation files, embedded in the binary: the default run checks the
//! paper from an installed binary, with no source tree (`tests/corpus.rs` holds this
//! list to `derivations/*.toml`). A `./derivations` directory, when there is one,
//! is read instead, so that an edited file is checked as edited.

/// (path as the reports name it, text), in name order.
pub const FILES: &[(&str, &str)] = &[
    (
        "derivations/3.1-grain-contact.toml",
        include_str!("../derivations/3.1-grain-contact.toml"),
    ),
    (
        "derivations/3.2-1-embedment-at-the-contact.toml",
        include_str!("../derivations/3.2-1-embedment-at-the-contact.toml"),
    ),
    (
        "derivations/3.2-2-embedment-at-the-centre.toml",
        include_str!("../derivations/3.2-2-embedment-at-the-centre.toml"),
    ),
    (
        "derivations/3.3-fabric-averaging.toml",
        include_str!("../derivations/3.3-fabric-averaging.toml"),
    ),
    (
        "derivations/3.4-invariants.toml",
        include_str!("../derivations/3.4-invariants.toml"),
    ),
    (
        "derivations/4.1-two-dimensional-invariants.toml",
        include_str!("../derivations/4.1-two-dimensional-invariants.toml"),
    ),
    (
        "derivations/4.2-yield-surfaces.toml",
        include_str!("../derivations/4.2-yield-surfaces.toml"),
    ),
    (
        "derivations/6-simple-shear.toml",
        include_str!("../derivations/6-simple-shear.toml"),
    ),
    (
        "derivations/A-1-elastoplastic-tangent.toml",
        include_str!("../derivations/A-1-elastoplastic-tangent.toml"),
    ),
    (
        "derivations/A-2-bifurcation.toml",
        include_str!("../derivations/A-2-bifurcation.toml"),
    ),
    (
        "derivations/A-3-shear-band.toml",
        include_str!("../derivations/A-3-shear-band.toml"),
    ),
];

/// The examples of the guide (`derivations/examples/*.toml`, and the LaTeX that `draft`
/// is shown on), embedded so that `cosserat-check examples --out DIR` can write them
/// from an installed binary.
pub const EXAMPLES: &[(&str, &str)] = &[
    (
        "derivations/examples/stress-invariants.tex",
        include_str!("../derivations/examples/stress-invariants.tex"),
    ),
    (
        "derivations/examples/balance.toml",
        include_str!("../derivations/examples/balance.toml"),
    ),
    (
        "derivations/examples/fields.toml",
        include_str!("../derivations/examples/fields.toml"),
    ),
    (
        "derivations/examples/inverse.toml",
        include_str!("../derivations/examples/inverse.toml"),
    ),
    (
        "derivations/examples/matrices.toml",
        include_str!("../derivations/examples/matrices.toml"),
    ),
    (
        "derivations/examples/moduli.toml",
        include_str!("../derivations/examples/moduli.toml"),
    ),
    (
        "derivations/examples/rational-functions.toml",
        include_str!("../derivations/examples/rational-functions.toml"),
    ),
    (
        "derivations/examples/radial-return.toml",
        include_str!("../derivations/examples/radial-return.toml"),
    ),
    (
        "derivations/examples/rudnicki-rice.toml",
        include_str!("../derivations/examples/rudnicki-rice.toml"),
    ),
    (
        "derivations/examples/states.toml",
        include_str!("../derivations/examples/states.toml"),
    ),
    (
        "derivations/examples/textbook.toml",
        include_str!("../derivations/examples/textbook.toml"),
    ),
];

/// The embedded corpus, read and checked like files on disk.
pub fn load() -> Result<Vec<crate::derivation::DerivationFile>, crate::derivation::LoadError> {
    crate::derivation::load_texts(FILES)
}
