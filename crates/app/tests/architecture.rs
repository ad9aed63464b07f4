//! The app's architecture, checked on its source: no import cycle, the
//! browser touched only by the `web` boundary, a `//!` doc on every file,
//! and the size limits that keep each module readable.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use test_support::modgraph;

use std::path::{Path, PathBuf};

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

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

fn sources() -> Vec<(String, String)> {
    let mut paths = Vec::new();
    files(&src(), &mut paths);
    paths
        .into_iter()
        .map(|p| {
            let rel = p
                .strip_prefix(src())
                .unwrap()
                .to_string_lossy()
                .replace('\\', "/");
            (rel, std::fs::read_to_string(&p).unwrap())
        })
        .collect()
}

/// Architecture invariant: no import cycle between the app's top-level
/// modules (such as `plots -> views -> worker -> plots`), nor between any
/// two of its files.
#[test]
fn the_app_has_no_import_cycle() {
    let g = modgraph::read(&src());
    for (a, b) in [
        ("plots", "views"),
        ("controller", "views"),
        ("worker", "protocol"),
        ("store", "views"),
        ("page", "controller"),
        ("web", "page"),
    ] {
        assert!(
            g.edges
                .iter()
                .any(|(x, y)| x.starts_with(a) && y.starts_with(b)),
            "{a} -> {b} not seen"
        );
    }
    for depth in [1, 2, 99] {
        assert_eq!(modgraph::cycle(&g, depth), None, "at depth {depth}");
    }
}

/// Architecture invariant: only the `web` boundary (web.rs and web/)
/// touches `web_sys` and `wasm_bindgen`; every file says what it is.
#[test]
fn only_the_web_boundary_touches_the_browser() {
    let all = sources();
    assert!(all.len() > 30, "{} files", all.len());
    for (rel, text) in &all {
        assert!(text.starts_with("//!"), "{rel} must start with a //! doc");
        let web = rel == "web.rs" || rel.starts_with("web/");
        let code = text.lines().filter(|l| !l.trim_start().starts_with("//"));
        for line in code.filter(|_| !web) {
            for name in ["web_sys", "wasm_bindgen", "js_sys"] {
                assert!(!line.contains(name), "{rel} uses {name}: {line}");
            }
        }
    }
}

/// Architecture invariant: no app file over 800 lines.
#[test]
fn no_file_is_too_long() {
    for (rel, text) in sources() {
        let n = text.lines().count();
        assert!(n <= 800, "{rel}: {n} lines (at most 800)");
    }
}

/// ARCHITECTURE.md's app section stays true: every file and folder its
/// code map names exists under `crates/app/src` (its invariants and their
/// tests are checked with the rest of the file by `test-support`).
#[test]
fn the_app_map_names_real_files() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let doc = std::fs::read_to_string(root.join("../../ARCHITECTURE.md")).unwrap();
    let start = doc.find("## The app").expect("an app section");
    let end = doc[start + 3..]
        .find("\n## ")
        .map_or(doc.len(), |i| start + 3 + i);
    let section = &doc[start..end];
    let mut all = Vec::new();
    files(&src(), &mut all);
    files(&root.join("tests"), &mut all);
    // Files and folders: words ending in `.rs` or `/` in the code map.
    let words =
        section.split(|c: char| c.is_whitespace() || c == '(' || c == ')' || c == ',' || c == '`');
    let mut named = 0;
    for w in words {
        let w = w.trim_end_matches(['.', ':', ';']);
        let is_path = (w.ends_with(".rs") || (w.ends_with('/') && w.len() > 1))
            && w.chars()
                .all(|c| c.is_ascii_alphanumeric() || "_/.".contains(c));
        if !is_path || w.starts_with("crates/") {
            continue;
        }
        let here = src().join(w);
        // A file (or a folder) in one of the rooms.
        let in_a_room = all.iter().any(|p| {
            let p = p.to_string_lossy();
            p.ends_with(&format!("/{w}")) || (w.ends_with('/') && p.contains(&format!("/{w}")))
        });
        assert!(
            here.exists() || in_a_room,
            "ARCHITECTURE.md names {w}, which does not exist"
        );
        named += 1;
    }
    assert!(named > 30, "only {named} files named");
}
