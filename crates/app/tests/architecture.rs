//! The architecture of the page's crates, checked on their source: the
//! shared figures (`crates/figures`), the worker (`crates/worker`) and the
//! page (`crates/app`). No import cycle inside any of them, the browser
//! touched only by the page's `web` boundary, a `//!` doc on every file,
//! the size limit that keeps each file readable, and ARCHITECTURE.md's maps
//! of the three naming real files. Which crate may import which is checked
//! for the whole workspace by `test-support`'s `layers` test.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use test_support::modgraph;

use std::path::{Path, PathBuf};

/// The page's crates: (name, the heading of its section in
/// ARCHITECTURE.md, its folder).
const CRATES: [(&str, &str, &str); 3] = [
    ("figures", "## The figures", "../figures"),
    ("worker", "## The worker", "../worker"),
    ("app", "## The app", "."),
];

fn dir(krate: &str) -> PathBuf {
    let (_, _, rel) = CRATES.iter().find(|(n, _, _)| *n == krate).unwrap();
    Path::new(env!("CARGO_MANIFEST_DIR")).join(rel)
}

fn src(krate: &str) -> PathBuf {
    dir(krate).join("src")
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

/// Every source file of a crate: (path relative to its `src`, text).
fn sources(krate: &str) -> Vec<(String, String)> {
    let mut paths = Vec::new();
    files(&src(krate), &mut paths);
    paths
        .into_iter()
        .map(|p| {
            let rel = p
                .strip_prefix(src(krate))
                .unwrap()
                .to_string_lossy()
                .replace('\\', "/");
            (rel, std::fs::read_to_string(&p).unwrap())
        })
        .collect()
}

/// Architecture invariant: no import cycle between the top-level modules
/// of the figures, the worker or the app (such as `plots -> views ->
/// story -> plots`), nor between any two of their files.
#[test]
fn no_page_crate_has_an_import_cycle() {
    let seen = [
        ("figures", "plots", "views"),
        ("figures", "views", "protocol"),
        ("figures", "link", "settings"),
        ("worker", "runner", "jobs"),
        ("app", "controller", "store"),
        ("app", "page", "controller"),
        ("app", "web", "page"),
    ];
    for (krate, _, _) in CRATES {
        let g = modgraph::read(&src(krate));
        for (_, a, b) in seen.iter().filter(|(k, _, _)| *k == krate) {
            assert!(
                g.edges
                    .iter()
                    .any(|(x, y)| x.starts_with(a) && y.starts_with(b)),
                "{krate}: {a} -> {b} not seen"
            );
        }
        for depth in [1, 2, 99] {
            assert_eq!(modgraph::cycle(&g, depth), None, "{krate} at depth {depth}");
        }
    }
}

/// Architecture invariant: only the page's `web` boundary (`crates/app`'s
/// web.rs and web/) touches `web_sys`, `wasm_bindgen` and `js_sys`; every
/// file of the three crates says what it is.
#[test]
fn only_the_web_boundary_touches_the_browser() {
    for (krate, _, _) in CRATES {
        let all = sources(krate);
        assert!(all.len() > 10, "{krate}: {} files", all.len());
        for (rel, text) in &all {
            assert!(
                text.starts_with("//!"),
                "{krate}: {rel} must start with a //! doc"
            );
            let web = krate == "app" && (rel == "web.rs" || rel.starts_with("web/"));
            let code = text.lines().filter(|l| !l.trim_start().starts_with("//"));
            for line in code.filter(|_| !web) {
                for name in ["web_sys", "wasm_bindgen", "js_sys"] {
                    assert!(!line.contains(name), "{krate}: {rel} uses {name}: {line}");
                }
            }
        }
    }
}

/// Architecture invariant: no file of the figures, the worker or the app
/// over 800 lines.
#[test]
fn no_file_is_too_long() {
    for (krate, _, _) in CRATES {
        for (rel, text) in sources(krate) {
            let n = text.lines().count();
            assert!(n <= 800, "{krate}: {rel}: {n} lines (at most 800)");
        }
    }
}

/// ARCHITECTURE.md's sections on the figures, the worker and the app stay
/// true: every file and folder a section's code map names exists in its
/// crate (its invariants and their tests are checked with the rest of the
/// file by `test-support`).
#[test]
fn the_crate_maps_name_real_files() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let doc = std::fs::read_to_string(root.join("../../ARCHITECTURE.md")).unwrap();
    let mut named = 0;
    for (krate, heading, _) in CRATES {
        let start = doc
            .find(&format!("{heading}\n"))
            .unwrap_or_else(|| panic!("a section {heading}"));
        let end = doc[start + 3..]
            .find("\n## ")
            .map_or(doc.len(), |i| start + 3 + i);
        let section = &doc[start..end];
        let mut all = Vec::new();
        files(&src(krate), &mut all);
        if dir(krate).join("tests").exists() {
            files(&dir(krate).join("tests"), &mut all);
        }
        // Files and folders: words ending in `.rs` or `/` in the code map.
        let words = section
            .split(|c: char| c.is_whitespace() || c == '(' || c == ')' || c == ',' || c == '`');
        for w in words {
            let w = w.trim_end_matches(['.', ':', ';']);
            let is_path = (w.ends_with(".rs") || (w.ends_with('/') && w.len() > 1))
                && w.chars()
                    .all(|c| c.is_ascii_alphanumeric() || "_/.".contains(c));
            if !is_path || w.starts_with("crates/") {
                continue;
            }
            let here = src(krate).join(w);
            // A file (or a folder) in one of the crate's rooms.
            let in_a_room = all.iter().any(|p| {
                let p = p.to_string_lossy();
                p.ends_with(&format!("/{w}")) || (w.ends_with('/') && p.contains(&format!("/{w}")))
            });
            assert!(
                here.exists() || in_a_room,
                "ARCHITECTURE.md's {heading} names {w}, which is not in {krate}"
            );
            named += 1;
        }
    }
    assert!(named > 30, "only {named} files named");
}

/// Architecture invariant: a job kind lives in one place. Its name
/// (`JobKind::X`) appears, outside tests, only in the kinds' table
/// (`protocol/kinds.rs`), the views' table (`views/table.rs`) and its own
/// page-side module (`store/kinds/`), with at most one other file for a
/// kind whose data another kind's view shows: at most 4 files per kind.
#[test]
fn a_job_kind_is_named_in_at_most_four_files() {
    let kinds = [
        "Omega",
        "HarmonicBalance",
        "Overlay",
        "Bif",
        "Map",
        "Lyap",
        "Orbits",
        "Boundaries",
    ];
    let mut all = Vec::new();
    for (krate, _, _) in CRATES {
        for (rel, text) in sources(krate) {
            let test_file = rel.ends_with("tests.rs") || rel.contains("tests/");
            if !test_file {
                all.push((format!("{krate}/{rel}"), text));
            }
        }
    }
    for kind in kinds {
        let pattern = format!("JobKind::{kind}");
        let naming: Vec<&str> = all
            .iter()
            .filter(|(_, text)| {
                text.match_indices(&pattern).any(|(i, _)| {
                    let next = text[i + pattern.len()..].chars().next();
                    !next.is_some_and(|c| c.is_alphanumeric() || c == '_')
                })
            })
            .map(|(name, _)| name.as_str())
            .collect();
        assert!(
            naming.len() <= 4,
            "JobKind::{kind} is named in {} files: {naming:?}",
            naming.len()
        );
    }
}
