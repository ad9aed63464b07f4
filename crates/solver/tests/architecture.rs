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

#[test]
fn the_solver_source_uses_no_clock_thread_or_io() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut checked = 0;
    for entry in std::fs::read_dir(&src).expect("src") {
        let path = entry.expect("entry").path();
        if path.extension().and_then(|e| e.to_str()) != Some("rs") {
            continue;
        }
        let text = std::fs::read_to_string(&path).expect("read");
        assert!(
            text.starts_with("//!"),
            "{} must start with a //! doc",
            path.display()
        );
        for bad in FORBIDDEN_SOURCE {
            assert!(!text.contains(bad), "{} uses {bad}", path.display());
        }
        checked += 1;
    }
    assert!(checked >= 10, "checked {checked} files");
}
