//! Which crate may import which: the workspace's layers, read from every
//! crate's `Cargo.toml` (its dependencies, target-specific ones included;
//! tests' dev-dependencies aside) and from the sentence of its README that
//! says what it may import. The solver is the centre, the figures the
//! page and the command line share sit on it, the worker on the figures,
//! and the page (`app`) on all three; nothing imports the page.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// Every crate of the workspace and the workspace crates it may import.
const LAYERS: [(&str, &[&str]); 9] = [
    ("solver", &[]),
    ("report", &["solver"]),
    ("figures", &["solver"]),
    ("worker", &["solver", "report", "figures"]),
    ("app", &["solver", "figures", "worker"]),
    ("cli", &["solver", "report", "figures", "worker"]),
    ("fuzz", &["solver", "report", "figures"]),
    ("wasm-bench", &["solver"]),
    ("test-support", &["solver"]),
];

fn crates() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The names of the workspace's crates: the folders under `crates/`.
fn workspace() -> BTreeSet<String> {
    std::fs::read_dir(crates())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.join("Cargo.toml").exists())
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect()
}

/// The workspace crates a manifest depends on outside its tests.
fn imports(manifest: &str, workspace: &BTreeSet<String>) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    let mut in_deps = false;
    for line in manifest.lines() {
        let t = line.trim();
        if t.starts_with('[') {
            in_deps = t.ends_with("dependencies]") && !t.ends_with("dev-dependencies]");
            continue;
        }
        if !in_deps || t.is_empty() || t.starts_with('#') {
            continue;
        }
        let name = t.split(['.', '=', ' ']).next().unwrap_or("").trim();
        if workspace.contains(name) {
            out.insert(name.to_string());
        }
    }
    out
}

/// Architecture invariant: each crate imports only the crates of its
/// layer; the command line does not import the page, the figures import
/// neither the worker nor the page, and every crate has a layer.
#[test]
fn every_crate_imports_only_its_layers() {
    let ws = workspace();
    let named: BTreeSet<String> = LAYERS.iter().map(|(c, _)| c.to_string()).collect();
    assert_eq!(ws, named, "every crate under crates/ has a row in LAYERS");
    for (krate, allowed) in LAYERS {
        let manifest = std::fs::read_to_string(crates().join(krate).join("Cargo.toml")).unwrap();
        let allowed: BTreeSet<String> = allowed.iter().map(|s| s.to_string()).collect();
        let got = imports(&manifest, &ws);
        assert!(
            got.is_subset(&allowed),
            "{krate} imports {:?}, beyond its layers {allowed:?}",
            got.difference(&allowed).collect::<Vec<_>>()
        );
    }
    // The rule the split was made for, said once more by name.
    let cli = std::fs::read_to_string(crates().join("cli/Cargo.toml")).unwrap();
    assert!(
        !imports(&cli, &ws).contains("app"),
        "the CLI imports the page"
    );
}

/// Every crate has a README whose paragraph says what it owns and, in a
/// sentence starting "It may import", the workspace crates it may import
/// (up to the first `.`, `;` or `(`, after which it may say what it must
/// not): exactly its row of [`LAYERS`].
#[test]
fn every_crate_readme_says_what_it_may_import() {
    let ws = workspace();
    for (krate, allowed) in LAYERS {
        let path = crates().join(krate).join("README.md");
        let text = std::fs::read_to_string(&path)
            .unwrap_or_else(|_| panic!("crates/{krate}/README.md is missing"))
            .split_whitespace()
            .collect::<Vec<_>>()
            .join(" ");
        let start = text
            .find("It may import")
            .unwrap_or_else(|| panic!("crates/{krate}/README.md: no \"It may import\""));
        let end = text[start..].find(['.', ';', '(']).unwrap();
        let sentence = &text[start..start + end];
        let said: BTreeSet<String> = sentence
            .split(|c: char| !(c.is_alphanumeric() || c == '-'))
            .filter(|w| ws.contains(*w))
            .map(str::to_string)
            .collect();
        let allowed: BTreeSet<String> = allowed.iter().map(|s| s.to_string()).collect();
        assert_eq!(said, allowed, "crates/{krate}/README.md: {sentence}");
    }
}
