//! Architecture invariant: the solver depends on nothing web, clock, thread
//! or I/O related, so it builds unchanged for native and wasm32 targets.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::path::Path;

const FORBIDDEN_CRATES: &[&str] = &[
    "wasm-bindgen",
    "web-sys",
    "js-sys",
    "gloo",
    "tokio",
    "rayon",
    "crossbeam",
    "chrono",
    "time",
    "instant",
    "web-time",
    "getrandom",
    "plotters",
    "glam",
    "clap",
];

const FORBIDDEN_SOURCE: &[&str] = &[
    "std::time",
    "std::thread",
    "std::fs",
    "std::io",
    "std::net",
    "std::process",
    "std::env",
    "Instant::",
    "SystemTime",
    "println!",
    "eprintln!",
    "print!(",
    "dbg!",
];

#[test]
fn the_solver_has_no_platform_dependencies() {
    let manifest = include_str!("../Cargo.toml");
    let deps = manifest
        .split("[dependencies]")
        .nth(1)
        .and_then(|s| s.split("\n[").next())
        .expect("a [dependencies] table");
    for line in deps.lines().filter(|l| !l.trim().is_empty()) {
        let name = line.split(['.', '=', ' ']).next().unwrap_or("").trim();
        assert!(
            !FORBIDDEN_CRATES.contains(&name),
            "the solver must not depend on {name}"
        );
    }
}

/// Every source file below `src/`, recursively (`hbm/` included).
fn source_files(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("src") {
        let path = entry.expect("entry").path();
        if path.is_dir() {
            source_files(&path, out);
        } else if path.extension().and_then(|e| e.to_str()) == Some("rs") {
            out.push(path);
        }
    }
}

#[test]
fn the_solver_source_uses_no_clock_thread_or_io() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    source_files(&src, &mut files);
    for path in &files {
        let text = std::fs::read_to_string(path).expect("read");
        assert!(
            text.starts_with("//!"),
            "{} must start with a //! doc",
            path.display()
        );
        for bad in FORBIDDEN_SOURCE {
            assert!(!text.contains(bad), "{} uses {bad}", path.display());
        }
    }
    assert!(files.len() >= 20, "checked {} files", files.len());
    let hbm = src.join("hbm").join("stability.rs");
    assert!(files.contains(&hbm), "the walk reaches src/hbm/");
}

use test_support::modgraph;

/// Architecture invariant: no import cycle in the solver, between its
/// top-level modules or between any two of its files (see
/// `test_support::modgraph` for how the graph is read).
#[test]
fn the_solver_has_no_import_cycle() {
    let g = modgraph::read(&Path::new(env!("CARGO_MANIFEST_DIR")).join("src"));
    // The reader sees the edges it must: dependencies known from the code.
    for (a, b) in [
        ("hbm::stability", "hbm::harmonic"),
        ("hbm::assembly", "hbm::harmonic"),
        ("parametric", "hbm::stability"),
        ("steady", "ode"),
    ] {
        assert!(
            g.edges.contains(&(a.into(), b.into())),
            "{a} -> {b} not seen"
        );
    }
    for depth in [1, 2, 99] {
        assert_eq!(modgraph::cycle(&g, depth), None, "at depth {depth}");
    }
}

/// The cycle finder finds cycles: through `use` groups, `super::` paths and
/// inline paths, and at file level inside one top-level module.
#[test]
fn the_cycle_finder_finds_cycles() {
    let g = modgraph::from_files(&[
        ("lib.rs", "//! root\npub mod a;\npub mod b;\npub mod c;"),
        ("a.rs", "use crate::{b::{self, X}, other};"),
        ("b.rs", "fn f() { crate::c::g(); }"),
        (
            "c.rs",
            "// use crate::a;\nfn g() {}\n#[cfg(test)]\nmod tests { use crate::a::Y; }",
        ),
    ]);
    assert_eq!(
        modgraph::cycle(&g, 1),
        None,
        "comments and tests are not edges"
    );
    let g = modgraph::from_files(&[
        ("a.rs", "use crate::{b::{self, X}, other};"),
        ("b.rs", "fn f() { crate::c::g(); }"),
        ("c.rs", "use crate::a::Y;"),
    ]);
    assert_eq!(
        modgraph::cycle(&g, 1),
        Some(vec!["a".into(), "b".into(), "c".into(), "a".into()])
    );
    let g = modgraph::from_files(&[
        ("h/mod.rs", "pub mod p; pub mod q; pub use p::X;"),
        ("h/p.rs", "use super::q::Y; use super::*;"),
        ("h/q.rs", "fn f() { super::p::x() }"),
    ]);
    assert_eq!(modgraph::cycle(&g, 1), None);
    assert!(modgraph::cycle(&g, 2).is_some(), "h::p <-> h::q");
}

/// Architecture invariant: no solver source file is over 800 lines, so
/// each holds one concept a reader can take in (`hbm/continuation/`,
/// `steady/`, `keys/` are split by concept).
#[test]
fn no_solver_source_file_is_over_800_lines() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    source_files(&src, &mut files);
    for path in &files {
        let lines = std::fs::read_to_string(path).expect("read").lines().count();
        let rel = path.strip_prefix(&src).expect("below src");
        assert!(lines <= 800, "{}: {lines} lines", rel.display());
    }
}

/// Architecture invariant: eigenvalues come from a bounded iteration.
/// nalgebra's `Matrix::complex_eigenvalues` sweeps without limit and hung a
/// boundary trace on a matrix that stagnated; only `dense.rs` calls it, on
/// a Schur form computed with a bound (`dense::eigenvalues_with`), and
/// the rest of the solver goes through that.
#[test]
fn eigenvalues_come_from_a_bounded_schur_form() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    source_files(&src, &mut files);
    let mut seen = 0;
    for path in &files {
        let text = std::fs::read_to_string(path).expect("read");
        let code = text.split("#[cfg(test)]").next().unwrap_or("");
        for line in code.lines().filter(|l| l.contains("complex_eigenvalues()")) {
            seen += 1;
            assert!(
                path.ends_with("dense.rs") && line.contains("schur.complex_eigenvalues()"),
                "{}: eigenvalues outside dense::eigenvalues_with: {line}",
                path.display()
            );
        }
    }
    assert_eq!(
        seen, 1,
        "the scan reads the sources and finds dense.rs's one call"
    );
}
