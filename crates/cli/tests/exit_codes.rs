//! The table of exit codes in docs/cli.md holds: each row's example, run as
//! written (through `sh`, for its redirection), exits with the row's code,
//! and an I/O failure never exits 1.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::process::Command;
use test_support::cli::bin;

/// The rows of docs/cli.md's exit-code table: (code, example command).
fn table() -> Vec<(i32, String)> {
    let doc = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/cli.md"))
        .expect("docs/cli.md");
    doc.lines()
        .skip_while(|l| !l.starts_with("| Code | Meaning | Example |"))
        .skip(2)
        .take_while(|l| l.starts_with('|'))
        .map(|l| {
            let cells: Vec<&str> = l.split('|').map(str::trim).collect();
            let code = cells[1].parse().expect("a code");
            let example = cells[3].trim_matches('`').to_string();
            (code, example)
        })
        .collect()
}

fn sh(command: &str, env: &[(&str, &str)]) -> (Option<i32>, String) {
    let bin_dir = bin().parent().expect("dir").to_path_buf();
    let path = format!(
        "{}:{}",
        bin_dir.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let mut c = Command::new("sh");
    c.arg("-c").arg(command).env("PATH", path);
    for (k, v) in env {
        c.env(k, v);
    }
    let out = c.output().expect("sh");
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).to_string(),
    )
}

#[test]
fn every_row_of_the_exit_code_table_is_the_code_of_its_example() {
    let rows = table();
    let codes: Vec<i32> = rows.iter().map(|r| r.0).collect();
    assert_eq!(codes, [0, 1, 2, 3], "the table: {rows:?}");
    for (code, example) in &rows {
        assert!(example.starts_with("gearshock "), "{example}");
        let (got, err) = sh(example, &[]);
        assert_eq!(got, Some(*code), "{example}: {err}");
        assert!(!err.contains("panicked"), "{example}: {err}");
    }
}

#[test]
fn io_failures_exit_3_never_1() {
    let d = std::env::temp_dir().join(format!("gearshock-exit-{}", std::process::id()));
    std::fs::create_dir_all(&d).expect("dir");
    // Two shards of a tiny sweep, merged with TMPDIR where nothing can be
    // written: merge's temporary file fails, named.
    let base = "gearshock bifurcation --model gear-pair --omega-from 0.5 --omega-to 0.6 \
                --points 2 --transient-periods 5 --record-periods 2";
    for i in 0..2 {
        let f = d.join(format!("s{i}.json"));
        let (code, err) = sh(&format!("{base} --shard {i}/2 > {}", f.display()), &[]);
        assert_eq!(code, Some(0), "{err}");
    }
    let merge = format!(
        "gearshock merge {} {}",
        d.join("s0.json").display(),
        d.join("s1.json").display()
    );
    let (code, err) = sh(&merge, &[("TMPDIR", "/nonexistent/folder")]);
    assert_eq!(code, Some(3), "{err}");
    assert!(
        err.contains("cannot write the merge's temporary file"),
        "{err}"
    );
    for command in [
        format!("{merge} > /dev/full"),
        format!("{base} > /dev/full"),
        "gearshock modes > /dev/full".to_string(),
        "gearshock keys > /dev/full".to_string(),
    ] {
        let (code, err) = sh(&command, &[]);
        assert_eq!(code, Some(3), "{command}: {err}");
        assert!(err.contains("No space left on device"), "{command}: {err}");
    }
    let _ = std::fs::remove_dir_all(&d);
}
