//! `gearshock figure ID --shard i/n` and `gearshock merge --out DIR`: the
//! heavy figures split by member and joined again give the unsharded
//! run's files byte for byte, and merge refuses foreign, mismatched,
//! incomplete or tampered shards with exit 2.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use serde_json::Value;
use std::path::PathBuf;
use test_support::cli::{files, gearshock, ok, temp_dir, words, Files};

/// A fresh scratch folder of this file's tests.
fn dir(name: &str) -> PathBuf {
    temp_dir(&format!("shards-{name}"))
}

/// Runs figure `id` unsharded into one directory and in `n` shards merged
/// into another; returns both file lists, both reports and the shard files.
fn both(id: &str, n: usize, opts: &[&str]) -> (Files, Files, Vec<PathBuf>) {
    let whole = dir(&format!("{id}-whole"));
    let merged = dir(&format!("{id}-merged"));
    let work = dir(&format!("{id}-work"));
    let mut args = vec!["figure", id, "--out", whole.to_str().unwrap()];
    args.extend(opts);
    let report: Value = serde_json::from_slice(&ok(&args)).unwrap();
    let mut shard_files = Vec::new();
    for i in 0..n {
        let s = format!("{i}/{n}");
        let mut args = vec!["figure", id, "--shard", &s];
        args.extend(opts);
        let path = work.join(format!("s{i}.json"));
        std::fs::write(&path, ok(&args)).unwrap();
        shard_files.push(path);
    }
    let mut args = vec!["merge", "--out", merged.to_str().unwrap()];
    let names: Vec<String> = shard_files
        .iter()
        .map(|p| p.to_str().unwrap().to_string())
        .collect();
    // Given in reverse order: the order of the files does not matter.
    args.extend(names.iter().rev().map(String::as_str));
    let again: Value = serde_json::from_slice(&ok(&args)).unwrap();
    assert_eq!(
        report["panels"], again["panels"],
        "{id}: the reports' panels"
    );
    assert_eq!(report["id"], again["id"]);
    (files(&whole), files(&merged), shard_files)
}

#[test]
fn a_sharded_orbit_figure_merged_is_byte_identical_to_the_unsharded_run() {
    let opts = ["--transient-periods", "20", "--record-periods", "4"];
    let (whole, merged, shards) = both("fig5", 2, &opts);
    // Three phase portraits and three Poincaré sections, three files each.
    assert_eq!(whole.len(), 18);
    assert!(
        whole == merged,
        "the merged files differ from the unsharded run's"
    );

    // Refusals, exit 2, one line naming the problem.
    let out = dir("fig5-refused");
    let o = out.to_str().unwrap();
    let s0 = shards[0].to_str().unwrap();
    let s1 = shards[1].to_str().unwrap();
    let refused = |args: &[&str], words: &str| {
        let r = gearshock(args);
        assert_eq!(r.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&r.stderr);
        assert!(err.contains(words), "{args:?}: {err}");
    };
    refused(&["merge", "--out", o, s0], "split into 2 shards; 1 files");
    refused(&["merge", "--out", o, s0, s0], "given twice");
    refused(&["merge", s0, s1], "need --out DIR");
    // Another figure's shard.
    let foreign = shards[0].with_file_name("fig6.json");
    std::fs::write(
        &foreign,
        ok(&words(
            "figure fig9 --shard 1/2 --transient-periods 20 --record-periods 4",
        )),
    )
    .unwrap();
    refused(
        &["merge", "--out", o, s0, foreign.to_str().unwrap()],
        "of figure fig9 (not fig5)",
    );
    // Other options.
    let other = shards[0].with_file_name("other.json");
    std::fs::write(
        &other,
        ok(&words(
            "figure fig5 --shard 1/2 --transient-periods 20 --record-periods 5",
        )),
    )
    .unwrap();
    refused(
        &["merge", "--out", o, s0, other.to_str().unwrap()],
        "computed with other options",
    );
    // A tampered file name cannot write outside the directory.
    let mut tampered: Value = serde_json::from_slice(&std::fs::read(&shards[1]).unwrap()).unwrap();
    assert_eq!(tampered["files"][0]["name"], "fig5b.svg");
    tampered["files"][0]["name"] = "../fig5b.svg".into();
    let bad = shards[0].with_file_name("bad.json");
    std::fs::write(&bad, tampered.to_string()).unwrap();
    refused(
        &["merge", "--out", o, s0, bad.to_str().unwrap()],
        "is not one of shard 1/2's panels",
    );
    assert!(!out.parent().unwrap().join("fig5b.svg").exists());
    // Nothing was written by a refused merge.
    assert!(files(&out).is_empty());
    // Bad shard options, before any work.
    refused(&["figure", "fig5", "--shard", "3/4"], "at most 3 shards");
    refused(&["figure", "fig2", "--shard", "0/2"], "not sharded");
    refused(
        &["figure", "fig5", "--shard", "0/2", "--out", o],
        "give --out to `gearshock merge",
    );
    refused(&["figure", "fig5"], "--out DIR is required");
}

#[test]
fn a_sharded_bifurcation_figure_merged_is_byte_identical_to_the_unsharded_run() {
    let opts = words("--points 3 --transient-periods 20 --record-periods 4");
    let (whole, merged, _) = both("fig4", 3, &opts);
    assert_eq!(whole.len(), 9);
    assert!(
        whole == merged,
        "the merged files differ from the unsharded run's"
    );
}
