//! Every write is checked: a failed write to stdout or a file is
//! an error naming it with exit code 3, a reader that goes away stops the
//! work quietly, and `figure --out` is checked before any work and leaves
//! no empty or cut file behind.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::io::Read;
use std::process::Stdio;
use test_support::cli::{command, files, ok, refused, temp_dir, to_full_disk, words};

const FULL: &str = "gearshock: cannot write stdout: No space left on device";

/// A short steady run for the sweeps.
const SHORT: [&str; 4] = ["--transient-periods", "5", "--record-periods", "2"];

fn with(args: &[&str], more: &[&str]) -> Vec<String> {
    args.iter().chain(more).map(|s| s.to_string()).collect()
}

/// One run of every subcommand (and of help), small; the sweeps' shards
/// for merge are written into `dir`.
fn every_subcommand(dir: &std::path::Path) -> Vec<Vec<String>> {
    let shard = |i: &str| {
        let path = dir.join(format!("b{}.json", i.replace('/', "-")));
        let args = with(
            &["bifurcation", "--omega-from", "0.4", "--omega-to", "0.6"],
            &["--points", "4", "--shard", i],
        );
        let args: Vec<&str> = args.iter().map(String::as_str).chain(SHORT).collect();
        std::fs::write(&path, ok(&args)).unwrap();
        path.to_str().unwrap().to_string()
    };
    let (s0, s1) = (shard("0/2"), shard("1/2"));
    let sweep = ["--omega-from", "0.4", "--omega-to", "0.6"];
    let cases: Vec<Vec<String>> = vec![
        with(&["params"], &[]),
        with(&["params", "--format", "csv"], &[]),
        with(&["keys"], &[]),
        with(&["keys", "--markdown"], &[]),
        with(&["modes"], &[]),
        with(&["campbell"], &[]),
        with(&["campbell", "--format", "csv"], &[]),
        with(&["simulate", "--omega", "0.5"], &SHORT),
        with(&["simulate", "--omega", "0.5", "--format", "csv"], &SHORT),
        with(
            &["bifurcation", "--points", "3"],
            &[&sweep[..], &SHORT].concat(),
        ),
        with(
            &["bifurcation", "--points", "3", "--format", "jsonl"],
            &[&sweep[..], &SHORT].concat(),
        ),
        with(
            &["frf", "--points", "10", "--harmonics", "1"],
            &[&sweep[..], &["--method", "describing-function"]].concat(),
        ),
        with(
            &["map", "--omega-points", "2", "--value-from", "40"],
            &[
                &sweep[..],
                &["--value-to", "60", "--value-points", "2"],
                &SHORT,
            ]
            .concat(),
        ),
        with(
            &["boundaries", "--model", "gear-pair", "--key", "te_um"],
            &[
                "--value-from",
                "1",
                "--value-to",
                "20",
                "--omega-from",
                "0.4",
                "--omega-to",
                "0.6",
                "--levels",
                "2",
                "--points",
                "10",
                "--harmonics",
                "3",
            ],
        ),
        with(
            &["lyapunov", "--points", "2", "--transient-periods", "5"],
            &[&sweep[..], &["--periods", "5"]].concat(),
        ),
        with(&["instability", "--points", "5", "--format", "csv"], &sweep),
        with(
            &["instability", "--points", "5", "--format", "jsonl"],
            &sweep,
        ),
        with(&["merge", &s0, &s1], &[]),
        with(&["presets"], &[]),
        with(
            &["frf", "--model", "gear-pair", "--method", "shooting"],
            &["--omega-from", "0.4", "--omega-to", "0.6", "--points", "10"],
        ),
        with(&["figure", "fig5", "--shard", "0/3"], &SHORT),
        with(&["--help"], &[]),
    ];
    cases
}

#[test]
fn a_full_disk_is_an_error_naming_stdout_with_exit_3_for_every_subcommand() {
    let dir = temp_dir("full");
    for case in &every_subcommand(&dir) {
        let args: Vec<&str> = case.iter().map(String::as_str).collect();
        let out = to_full_disk(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(3), "{args:?}: {err}");
        assert_eq!(err.lines().last(), Some(FULL), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
    }
}

#[test]
fn a_closed_stdout_is_an_error_with_exit_3_for_every_subcommand_before_any_work() {
    let dir = temp_dir("closed");
    for case in &every_subcommand(&dir) {
        // `>&-` through the shell: the program starts with descriptor 1 closed.
        let line = format!(
            "exec '{}' {} >&-",
            test_support::cli::bin().display(),
            case.join(" ")
        );
        let out = std::process::Command::new("sh")
            .arg("-c")
            .arg(&line)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(3), "{line}: {err}");
        assert_eq!(
            err.trim_end(),
            "gearshock: cannot write stdout: it is closed",
            "{line}: no work, one line"
        );
    }
    // A redirection to /dev/null is the user's choice, not a closed stdout.
    let out = std::process::Command::new("sh")
        .arg("-c")
        .arg(format!(
            "exec '{}' params > /dev/null",
            test_support::cli::bin().display()
        ))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0));
}

/// A streamed sweep of 20 000 points (minutes of work), its reader gone.
fn long_stream() -> std::process::Command {
    let mut c = command(&words("bifurcation --omega-from 0.4 --omega-to 0.6 --points 20000 --transient-periods 100 --record-periods 10 --format jsonl --progress"));
    c.stdout(Stdio::piped()).stderr(Stdio::piped());
    c
}

/// The progress lines' counts of points done (`gearshock: progress 37/200 points`).
fn progress_counts(err: &str) -> Vec<u64> {
    err.lines()
        .filter_map(|l| l.strip_prefix("gearshock: progress "))
        .map(|l| l.split('/').next().unwrap().parse().unwrap())
        .collect()
}

#[test]
fn a_reader_that_goes_away_stops_the_sweep_quietly_with_exit_3() {
    // Closed before the first line: not one point is computed (a computed
    // point prints a progress line).
    // The pipe's reading end is closed before the program starts, so no
    // scheduling lets it write first.
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let out = long_stream().stdout(writer).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(3), "{err}");
    assert!(progress_counts(&err).is_empty(), "no point computed: {err}");
    assert!(err.is_empty(), "quiet: {err}");

    // `| head -c 100`: the stream stops at the next line, far from the end.
    let mut child = long_stream().spawn().unwrap();
    let mut first = [0u8; 100];
    child
        .stdout
        .as_mut()
        .unwrap()
        .read_exact(&mut first)
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(3), "{err}");
    assert!(first.starts_with(b"{\"model\""), "the header came first");
    let done = progress_counts(&err).last().copied().unwrap_or(0);
    assert!(done < 20_000, "stopped at {done} of 20000 points");
    assert!(
        err.lines().all(|l| l.starts_with("gearshock: progress ")),
        "no message for a closed pipe: {err}"
    );
}

#[test]
fn figure_out_is_checked_before_any_work_and_written_whole_or_not_at_all() {
    let dir = temp_dir("figure-out");
    let file = dir.join("a-file");
    std::fs::write(&file, "not a folder").unwrap();
    // Before the work (the default periods take minutes): a folder that
    // cannot be made is refused at once, naming --out.
    let under = file.join("sub");
    refused(
        &["figure", "fig5", "--out", under.to_str().unwrap()],
        &["--out", "a-file/sub", "Not a directory"],
    );
    refused(
        &["figure", "fig5", "--out", file.to_str().unwrap()],
        &["--out", "a-file", "exists"],
    );
    assert!(!under.exists());

    // A file that cannot be written (its name taken by a folder): exit 3
    // naming it, and no empty, cut or temporary file left.
    let out = dir.join("out");
    std::fs::create_dir_all(out.join("fig5b.svg")).unwrap();
    let mut args = vec!["figure", "fig5", "--out", out.to_str().unwrap()];
    args.extend(SHORT);
    let o = command(&args).output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(3), "{err}");
    assert!(
        err.contains("cannot write ") && err.contains("fig5b.svg"),
        "{err}"
    );
    for (name, bytes) in files(&out) {
        assert!(!name.starts_with('.'), "temporary file {name} left");
        if name != "fig5b.svg" {
            assert!(!bytes.is_empty(), "{name} left empty");
        }
    }

    // The same run into a free folder writes every file, none empty.
    let free = dir.join("free");
    let mut args = vec!["figure", "fig5", "--out", free.to_str().unwrap()];
    args.extend(SHORT);
    ok(&args);
    let written = files(&free);
    assert_eq!(written.len(), 18, "6 panels x svg, json, csv");
    assert!(written
        .iter()
        .all(|(n, b)| !n.starts_with('.') && !b.is_empty()));
}
