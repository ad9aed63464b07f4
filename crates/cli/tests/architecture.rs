//! The CLI's rooms, checked on its source (see ARCHITECTURE.md): every
//! write goes through `output`, one module per subcommand, one sweep loop,
//! no file over 800 lines.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::path::{Path, PathBuf};
use test_support::cli::{ok, words};

/// Every source file below `src/`: (path relative to `src/`, text).
fn sources() -> Vec<(String, String)> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut stack = vec![src.clone()];
    let mut out = Vec::new();
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path: PathBuf = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                let rel = path.strip_prefix(&src).unwrap();
                let rel = rel.to_string_lossy().replace('\\', "/");
                out.push((rel, std::fs::read_to_string(&path).unwrap()));
            }
        }
    }
    out.sort();
    assert!(out.len() > 10, "the walk finds the sources");
    out
}

/// The code of a file: comments cut from each line.
fn code(text: &str) -> String {
    text.lines()
        .map(|l| l.split("//").next().unwrap_or(""))
        .collect::<Vec<_>>()
        .join("\n")
}

/// Architecture invariant: every byte the CLI prints or saves goes through
/// `output` (progress lines on stderr through `progress`).
#[test]
fn only_output_writes() {
    let writers = words("print!( println!( eprint!( eprintln!( io::stdout( io::stderr( fs::write( File::create( OpenOptions");
    for (file, text) in sources() {
        let allowed: &[&str] = match file.as_str() {
            "output.rs" => &writers,
            "progress.rs" => &["io::stderr("],
            _ => &[],
        };
        for w in writers.iter().filter(|w| !allowed.contains(w)) {
            assert!(!code(&text).contains(w), "{file} writes with {w}");
        }
    }
}

/// Architecture invariant: one module per subcommand, and one sweep loop
/// (`sweep::run`) for every sweep.
#[test]
fn one_module_per_subcommand_and_one_sweep_loop() {
    let help = String::from_utf8(ok(&["--help"])).unwrap();
    let listed: Vec<String> = help
        .lines()
        .skip_while(|l| !l.starts_with("Commands:"))
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .filter_map(|l| l.split_whitespace().next())
        .filter(|name| *name != "help")
        .map(str::to_string)
        .collect();
    assert!(listed.len() >= 12, "{help}");
    let sources = sources();
    let mut modules: Vec<String> = sources
        .iter()
        .filter_map(|(f, _)| f.strip_prefix("commands/")?.strip_suffix(".rs"))
        // A subcommand's own submodules (commands/figure/shard.rs) are its.
        .filter(|m| *m != "mod" && !m.contains('/'))
        .map(str::to_string)
        .collect();
    modules.sort();
    let mut expected = listed.clone();
    expected.sort();
    assert_eq!(modules, expected, "commands/NAME.rs per subcommand");
    for (file, text) in &sources {
        let text = code(text);
        let sweep = [
            "bifurcation",
            "frf",
            "map",
            "lyapunov",
            "instability",
            "boundaries",
        ]
        .iter()
        .any(|s| *file == format!("commands/{s}.rs"));
        if sweep {
            assert!(text.contains("sweep::run("), "{file} runs its own loop");
        }
        // Only the sweep loop and the figure command (panels, not a
        // sweep of the CLI's) show progress.
        let figure = *file == "commands/figure.rs" || file.starts_with("commands/figure/");
        if file != "sweep.rs" && !figure && file != "progress.rs" {
            assert!(!text.contains("Progress::new("), "{file} has its own loop");
        }
    }
}

/// Architecture invariant: no CLI source file is over 800 lines.
#[test]
fn no_cli_source_file_is_over_800_lines() {
    for (file, text) in sources() {
        let n = text.lines().count();
        assert!(n <= 800, "{file}: {n} lines");
    }
}
