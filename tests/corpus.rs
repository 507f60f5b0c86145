//! The corpus embedded in the binary is the one in `derivations/`: every file, in name
//! order, byte for byte, so that an installed binary checks the same paper.

use cosserat_check::corpus;
use std::path::Path;

#[test]
fn the_embedded_corpus_is_the_derivations_directory() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("derivations");
    let mut on_disk: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.is_file() && p.extension().is_some_and(|x| x == "toml"))
        .map(|p| format!("derivations/{}", p.file_name().unwrap().to_str().unwrap()))
        .collect();
    on_disk.sort();
    let embedded: Vec<String> = corpus::FILES.iter().map(|(n, _)| (*n).to_owned()).collect();
    assert_eq!(
        embedded, on_disk,
        "src/corpus.rs lists every derivation file"
    );
    for (name, text) in corpus::FILES {
        let disk =
            std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join(name)).unwrap();
        assert_eq!(*text, disk, "{name}");
    }
}

#[test]
fn the_embedded_corpus_reads_like_the_files() {
    let embedded = corpus::load().unwrap();
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("derivations");
    let files = cosserat_check::derivation::load_dir(&dir).unwrap();
    let ids = |f: &[cosserat_check::derivation::DerivationFile]| -> Vec<String> {
        f.iter()
            .flat_map(|f| f.claims.iter().map(|c| c.id.clone()))
            .collect()
    };
    assert_eq!(ids(&embedded), ids(&files));
    assert_eq!(ids(&embedded).len(), 75);
}

/// Run from a directory with no `derivations/`, the binary checks the embedded paper.
#[test]
fn the_binary_checks_the_paper_without_the_source_tree() {
    let dir = std::env::temp_dir().join(format!("cosserat-check-elsewhere-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_cosserat-check"))
        .args(["--format", "csv"])
        .current_dir(&dir)
        .output()
        .unwrap();
    std::fs::remove_dir_all(&dir).ok();
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let table = String::from_utf8(out.stdout).unwrap();
    assert_eq!(table.lines().count(), 76, "a header and 75 claims");
    assert!(
        table.contains("\n\"eq54\",\"6\","),
        "the Appendix's claims are there"
    );
}
