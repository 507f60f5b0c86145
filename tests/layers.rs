//! The one-way structure of `src/`: no file imports, directly or through others, a file
//! that imports it back; the top-level folders depend only downwards, in the order data
//! flows (kernel, algebra, lang, derivation, eval, decide, check, report, then the
//! command line); and the trusted kernel, a crate of its own in `src/kernel`, names
//! nothing outside itself (the compiler holds it to that too). The algebra and the
//! language are crates of their own as well (`src/algebra`, `src/lang`).
//!
//! An import is any path that starts with `crate::`, `super::` or `self::` outside
//! comments and test modules (a `use`, a call, a type), and in a `mod.rs` a path that
//! starts with the name of one of its own child modules. Each resolves to the longest
//! module it names.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

type Module = Vec<String>;

/// The folders of `src/` that are crates of their own (`src/kernel/Cargo.toml`, …).
const CRATES: &[&str] = &["kernel", "algebra", "lang"];

/// The top-level modules in the order data flows: a module may use only modules of its
/// own rank or lower.
const RANKS: &[(&str, usize)] = &[
    ("digits", 0),
    ("parallel", 0),
    ("tolerance", 0),
    ("kernel", 1),
    ("algebra", 2),
    ("lang", 3),
    ("derivation", 4),
    ("eval", 5),
    ("decide", 6),
    ("check", 7),
    ("report", 8),
    ("corpus", 9),
    ("recheck", 9),
    ("cli", 10),
];

fn files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

fn module_of(src: &Path, file: &Path) -> Module {
    let rel = file.strip_prefix(src).unwrap().with_extension("");
    let mut parts: Module = rel
        .iter()
        .map(|p| p.to_string_lossy().into_owned())
        .collect();
    if matches!(
        parts.last().map(String::as_str),
        Some("mod" | "lib" | "main")
    ) {
        parts.pop();
    }
    parts
}

/// The text of a file without comments, `#[cfg(test)]` module declarations and the test
/// module at its end.
fn code(text: &str) -> String {
    let mut out = String::new();
    let mut lines = text.lines().peekable();
    while let Some(line) = lines.next() {
        if line.trim() == "#[cfg(test)]" {
            let next = lines.peek().map_or("", |l| l.trim());
            let declares = next.starts_with("mod ") || next.starts_with("pub(crate) mod ");
            if declares && next.ends_with('{') {
                break;
            }
            if declares {
                lines.next();
                continue;
            }
        }
        out.push_str(line.split("//").next().unwrap_or(""));
        out.push('\n');
    }
    out
}

/// Every path in `code` that starts with one of `roots` at an identifier boundary: its
/// segments, one list per item of a trailing `{…}` group.
fn paths(code: &str, roots: &[&str]) -> Vec<Vec<String>> {
    let ident = |c: char| c.is_alphanumeric() || c == '_';
    let bytes: Vec<char> = code.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        let boundary = i == 0 || !(ident(bytes[i - 1]) || bytes[i - 1] == ':');
        let root = roots.iter().find(|r| {
            let r: Vec<char> = format!("{r}::").chars().collect();
            bytes[i..].starts_with(&r)
        });
        let (true, Some(root)) = (boundary, root) else {
            i += 1;
            continue;
        };
        let mut segments = vec![root.to_string()];
        i += root.chars().count() + 2;
        loop {
            if bytes.get(i) == Some(&'{') {
                // One path per item of the group (its first segment is enough); a
                // nested group belongs to the item it follows.
                let mut depth = 0;
                let mut close = i;
                let mut items = vec![String::new()];
                for (k, &c) in bytes.iter().enumerate().skip(i + 1) {
                    match c {
                        '{' => depth += 1,
                        '}' if depth == 0 => {
                            close = k;
                            break;
                        }
                        '}' => depth -= 1,
                        ',' if depth == 0 => items.push(String::new()),
                        _ => items.last_mut().unwrap().push(c),
                    }
                }
                for item in &items {
                    let first = item.trim().split("::").next().unwrap_or("");
                    let first = first.split_whitespace().next().unwrap_or("");
                    if !first.is_empty() && first != "self" {
                        let mut p = segments.clone();
                        p.push(first.to_owned());
                        out.push(p);
                    }
                }
                i = close;
                break;
            }
            let start = i;
            while i < bytes.len() && ident(bytes[i]) {
                i += 1;
            }
            if i > start {
                segments.push(bytes[start..i].iter().collect());
            }
            if i > start && bytes[i..].starts_with(&[':', ':']) {
                i += 2;
                continue;
            }
            out.push(segments);
            break;
        }
    }
    out
}

/// The modules each module's code names.
fn imports(src: &Path) -> BTreeMap<Module, BTreeSet<Module>> {
    let mut all = Vec::new();
    files(src, &mut all);
    let modules: BTreeMap<Module, String> = all
        .iter()
        .map(|f| {
            (
                module_of(src, f),
                code(&std::fs::read_to_string(f).unwrap()),
            )
        })
        .collect();
    let longest = |path: &[String]| -> Option<Module> {
        (0..=path.len())
            .rev()
            .map(|k| path[..k].to_vec())
            .find(|m| modules.contains_key(m))
    };
    let mut graph = BTreeMap::new();
    for (m, text) in &modules {
        let mut deps = BTreeSet::new();
        for path in paths(text, &["crate", "super", "self"]) {
            let (mut base, rest): (Module, &[String]) = match path[0].as_str() {
                // The kernel, the algebra and the language are crates of their own:
                // there `crate::` is the crate, except the names they give the crates
                // below them (`crate::kernel`, `crate::algebra`).
                "crate"
                    if m.first().is_some_and(|f| CRATES.contains(&f.as_str()))
                        && path
                            .get(1)
                            .is_none_or(|p| !CRATES.contains(&p.as_str()) || p == &m[0]) =>
                {
                    (vec![m[0].clone()], &path[1..])
                }
                "crate" => (Vec::new(), &path[1..]),
                "self" => (m.clone(), &path[1..]),
                _ => {
                    let ups = path.iter().take_while(|s| *s == "super").count();
                    let keep = m.len().saturating_sub(ups);
                    (m[..keep].to_vec(), &path[ups..])
                }
            };
            base.extend(rest.iter().cloned());
            deps.extend(longest(&base));
        }
        let children: Vec<&Module> = modules
            .keys()
            .filter(|c| c.len() == m.len() + 1 && c.starts_with(m))
            .collect();
        for child in children {
            let name = child.last().unwrap();
            if paths(text, &[name]).iter().any(|p| p.len() > 1) {
                deps.insert(child.clone());
            }
        }
        deps.remove(m);
        graph.insert(m.clone(), deps);
    }
    graph
}

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

fn name(m: &Module) -> String {
    if m.is_empty() {
        "crate".to_owned()
    } else {
        m.join("/")
    }
}

/// Every import circle, as its modules in order.
fn circles(graph: &BTreeMap<Module, BTreeSet<Module>>) -> Vec<String> {
    // Depth-first search; a module met again while on the stack closes a circle.
    fn visit<'g>(
        m: &'g Module,
        graph: &'g BTreeMap<Module, BTreeSet<Module>>,
        stack: &mut Vec<&'g Module>,
        done: &mut BTreeSet<&'g Module>,
        circles: &mut Vec<String>,
    ) {
        if done.contains(m) {
            return;
        }
        if let Some(k) = stack.iter().position(|s| *s == m) {
            let circle: Vec<String> = stack[k..].iter().map(|s| name(s)).collect();
            circles.push(format!("{} → {}", circle.join(" → "), name(m)));
            return;
        }
        stack.push(m);
        for d in graph[m].iter().filter(|d| graph.contains_key(*d)) {
            visit(d, graph, stack, done, circles);
        }
        stack.pop();
        done.insert(m);
    }
    let mut circles = Vec::new();
    let mut done = BTreeSet::new();
    for m in graph.keys() {
        visit(m, graph, &mut Vec::new(), &mut done, &mut circles);
    }
    circles
}

/// Every import against the order of [`RANKS`], and every import of the kernel's that
/// leaves it.
fn against_order(graph: &BTreeMap<Module, BTreeSet<Module>>) -> Vec<String> {
    let rank = |m: &Module| {
        let top = m.first().map(String::as_str).unwrap_or("");
        RANKS.iter().find(|(n, _)| *n == top).map(|(_, r)| *r)
    };
    let mut out = Vec::new();
    for (m, deps) in graph {
        let Some(r) = rank(m) else { continue };
        for d in deps {
            match rank(d) {
                Some(s) if s > r => out.push(format!("{} → {}", name(m), name(d))),
                None if !d.is_empty() => out.push(format!("{} has no rank", name(d))),
                _ => {}
            }
            if m[0] == "kernel" && d.first().map(String::as_str) != Some("kernel") {
                out.push(format!("{} → {} (outside the kernel)", name(m), name(d)));
            }
        }
    }
    out
}

#[test]
fn no_file_imports_a_file_that_imports_it_back() {
    let graph = imports(&src());
    assert!(graph.len() > 100, "only {} modules read", graph.len());
    let circles = circles(&graph);
    assert!(
        circles.is_empty(),
        "import circles:\n{}",
        circles.join("\n")
    );
}

#[test]
fn folders_depend_only_downwards_and_the_kernel_on_nothing_else() {
    let wrong = against_order(&imports(&src()));
    assert!(
        wrong.is_empty(),
        "imports against the order:\n{}",
        wrong.join("\n")
    );
}

/// The checks above can fail: in a small tree written for the purpose, a circle through
/// a `{…}` group and a call, and a kernel file that calls into `report` (the same call
/// in a comment does not count), are found; `crate::` in the kernel names the kernel.
#[test]
fn a_circle_and_an_upward_import_are_found() {
    let dir = std::env::temp_dir().join(format!("cc-layers-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("kernel")).unwrap();
    let write = |path: &str, text: &str| std::fs::write(dir.join(path), text).unwrap();
    write("lib.rs", "pub mod kernel;\npub mod report;\n");
    write(
        "kernel/mod.rs",
        "pub mod a;\npub mod b;\npub mod c;\npub mod d;\npub mod e;\npub use c::{k};\n",
    );
    write("kernel/a.rs", "use super::b::{f, G};\n");
    write(
        "kernel/b.rs",
        "use super::{a::{g, h}, d};\npub fn f() { super::a::g(); }\n",
    );
    write("kernel/d.rs", "pub fn e() {}\n");
    write("kernel/e.rs", "pub fn f() { crate::d::e(); }\n");
    write(
        "kernel/c.rs",
        "use super::{a};\n// super::super::report::h();\npub fn k() { super::super::report::h(); }\n",
    );
    write(
        "report.rs",
        "pub fn h() {}\n#[cfg(test)]\nmod tests {\n    use crate::kernel::c;\n}\n",
    );
    let graph = imports(&dir);
    std::fs::remove_dir_all(&dir).unwrap();
    let m = |s: &str| s.split('/').map(str::to_owned).collect::<Module>();
    // A group right after the root names its items, not the root's module.
    assert!(graph[&m("kernel")].contains(&m("kernel/c")));
    assert!(graph[&m("kernel/c")].contains(&m("kernel/a")));
    assert!(!graph[&m("kernel/c")].contains(&m("kernel")));
    // In the kernel, a crate of its own, `crate::` is the kernel.
    assert!(graph[&m("kernel/e")].contains(&m("kernel/d")));
    // A nested group belongs to its item.
    assert!(graph[&m("kernel/b")].contains(&m("kernel/d")));
    assert!(!graph[&m("kernel/b")].contains(&m("kernel")));
    assert_eq!(circles(&graph), ["kernel/a → kernel/b → kernel/a"]);
    assert_eq!(
        against_order(&graph),
        [
            "kernel/c → report",
            "kernel/c → report (outside the kernel)"
        ],
        "report → kernel/c is in a test module, kernel/c → report against the order"
    );
}

#[test]
fn the_folders_read_as_crates_are_the_crates() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut crates: Vec<String> = std::fs::read_dir(&src)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.join("Cargo.toml").is_file())
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    crates.sort();
    let mut expected: Vec<&str> = CRATES.to_vec();
    expected.sort();
    assert_eq!(crates, expected);
}
