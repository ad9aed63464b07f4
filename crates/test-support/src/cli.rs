//! Running the `gearshock` binary in a test: its output, its JSON, its
//! refusals, and scratch folders and files.

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

/// The `gearshock` binary Cargo built beside the running test
/// (`target/<profile>/gearshock`; the test is in `target/<profile>/deps/`).
pub fn bin() -> PathBuf {
    let test = std::env::current_exe().expect("the test's path");
    let profile = test
        .parent()
        .and_then(Path::parent)
        .expect("target/<profile>/deps");
    profile.join(format!("gearshock{}", std::env::consts::EXE_SUFFIX))
}

/// A command running `gearshock` with `args`.
pub fn command(args: &[&str]) -> Command {
    let mut c = Command::new(bin());
    c.args(args);
    c
}

/// Runs `gearshock` with `args` and collects its output.
pub fn gearshock(args: &[&str]) -> Output {
    command(args).output().expect("run gearshock")
}

/// Runs and expects success; returns stdout.
pub fn ok(args: &[&str]) -> Vec<u8> {
    let out = gearshock(args);
    assert!(
        out.status.success(),
        "{args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out.stdout
}

/// Runs and expects success with one JSON document on stdout.
pub fn json(args: &[&str]) -> Value {
    serde_json::from_slice(&ok(args)).expect("JSON on stdout")
}

/// Runs and expects success with JSON lines on stdout, every line one value.
pub fn json_lines(args: &[&str]) -> Vec<Value> {
    String::from_utf8_lossy(&ok(args))
        .lines()
        .map(|l| serde_json::from_str(l).expect("one JSON value per line"))
        .collect()
}

/// Runs and expects exit 2 with one line on stderr containing every needle,
/// no panic and nothing on stdout; returns the line.
pub fn refused(args: &[&str], needles: &[&str]) -> String {
    let out = gearshock(args);
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
    for n in needles {
        assert!(err.contains(n), "{args:?}: `{n}` not in {err}");
    }
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    assert!(out.stdout.is_empty(), "{args:?}: no partial output");
    err
}

/// Runs with stdout on `/dev/full`, where every write fails with "No space
/// left on device".
pub fn to_full_disk(args: &[&str]) -> Output {
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .expect("/dev/full");
    command(args)
        .stdout(Stdio::from(full))
        .output()
        .expect("run gearshock")
}

/// An empty scratch folder for this test process, named `name`.
pub fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("gearshock-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("dir");
    dir
}

/// Writes `v` as `dir/name`; returns the path as text (for an argument).
pub fn write_json(dir: &Path, name: &str, v: &Value) -> String {
    let file = dir.join(name);
    std::fs::write(&file, v.to_string()).expect("write");
    file.to_str().expect("path").to_string()
}

/// Files as (name, bytes).
pub type Files = Vec<(String, Vec<u8>)>;

/// Every file of a folder: (name, bytes), sorted by name.
pub fn files(d: &Path) -> Files {
    let mut v: Files = std::fs::read_dir(d)
        .expect("read dir")
        .map(|e| {
            let e = e.expect("entry");
            (
                e.file_name().to_string_lossy().into_owned(),
                std::fs::read(e.path()).unwrap_or_default(),
            )
        })
        .collect();
    v.sort();
    v
}

/// The words of a command line written as one string:
/// `json(&words("map --model gear-pair --omega-points 2"))`.
pub fn words(line: &str) -> Vec<&str> {
    line.split_whitespace().collect()
}
