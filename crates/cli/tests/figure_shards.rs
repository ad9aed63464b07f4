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
    // Forged shards (data-driven): each change to shard 1 is refused,
    // naming the file, and nothing is written.
    let good: Value = serde_json::from_slice(&std::fs::read(&shards[1]).unwrap()).unwrap();
    assert_eq!(good["figure_shard"]["members"], serde_json::json!([1]));
    let history = good["members"][0]["orbit"]["x_um"]
        .as_array()
        .unwrap()
        .len();
    // 4 recorded periods of 64 samples each.
    assert_eq!(history, 4 * 64);
    let forgeries: &[(&str, Value, &str)] = &[
        // The members the figure's definition gives shard 1/2 are [1].
        (
            "/figure_shard/members",
            serde_json::json!([2]),
            "differs from the figure's definition",
        ),
        // File text is never passed through: a shard holds no files.
        (
            "/files",
            serde_json::json!([{ "name": "../fig5b.svg", "text": "<svg><script>alert(1)</script></svg>" }]),
            "field files is not one a figure shard holds",
        ),
        (
            "/members/0/orbit/mesh_name",
            "<script>".into(),
            "orbit.mesh_name = \"<script>\" is out of range",
        ),
        (
            "/members/0/orbit/x_um",
            Value::Array(vec![0.5.into(); 3_000_000]),
            "orbit.x_um (3000000 entries) is out of range: allowed an array of exactly 256 numbers",
        ),
        (
            "/members/0/orbit/poincare_x_um",
            serde_json::json!([1.0]),
            "orbit.poincare_x_um (1 entries)",
        ),
        (
            "/members/0/orbit/period",
            serde_json::json!(1e300),
            "orbit.period = 1e+300 is out of range",
        ),
        (
            "/members/0/orbit/omega",
            serde_json::json!(0.9),
            "orbit.omega = 0.9 is out of range",
        ),
        ("/members/0/orbit/regime", "<script>".into(), "orbit.regime"),
        ("/members/0/orbit/extra", Value::Null, "field orbit.extra"),
        (
            "/members/0/member",
            serde_json::json!(2),
            "in the order of figure_shard.members",
        ),
        (
            "/figure_shard/options/points",
            serde_json::json!(1_000_000),
            "computed with other options",
        ),
    ];
    for (k, (pointer, value, words)) in forgeries.iter().enumerate() {
        let mut forged = good.clone();
        match forged.pointer_mut(pointer) {
            Some(slot) => *slot = value.clone(),
            None => {
                let (parent, key) = pointer.rsplit_once('/').unwrap();
                forged
                    .pointer_mut(parent)
                    .and_then(Value::as_object_mut)
                    .unwrap()
                    .insert(key.into(), value.clone());
            }
        }
        let bad = shards[0].with_file_name(format!("forged{k}.json"));
        std::fs::write(&bad, forged.to_string()).unwrap();
        let name = format!("forged{k}.json");
        refused(&["merge", "--out", o, s0, bad.to_str().unwrap()], words);
        refused(&["merge", "--out", o, s0, bad.to_str().unwrap()], &name);
    }
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
    let (whole, merged, shards) = both("fig4", 3, &opts);
    assert_eq!(whole.len(), 9);
    assert!(
        whole == merged,
        "the merged files differ from the unsharded run's"
    );
    // Forged sweeps are refused, naming the file and the field.
    let out = dir("fig4-refused");
    let good: Value = serde_json::from_slice(&std::fs::read(&shards[2]).unwrap()).unwrap();
    let forgeries: &[(&str, Value, &str)] = &[
        (
            "/members/0/sweep/points/0/stats/steps",
            serde_json::json!(1.5),
            "stats.steps = 1.5 is out of range",
        ),
        (
            "/members/0/sweep/points/0/poincare_delta_m",
            serde_json::json!([]),
            "poincare_delta_m has 0 entries: allowed exactly 4",
        ),
        (
            "/members/0/sweep/spec/record_periods",
            serde_json::json!(5),
            "sweep.spec = ",
        ),
        (
            "/members/0/sweep/stats/steps",
            serde_json::json!(1),
            "its stats are not the totals of its points",
        ),
        (
            "/members/0/sweep/points/0/impact",
            "<script>".into(),
            "impact = \"<script>\" is out of range",
        ),
    ];
    for (k, (pointer, value, words)) in forgeries.iter().enumerate() {
        let mut forged = good.clone();
        *forged.pointer_mut(pointer).unwrap() = value.clone();
        let bad = shards[2].with_file_name(format!("forged{k}.json"));
        std::fs::write(&bad, forged.to_string()).unwrap();
        let mut args = vec!["merge", "--out", out.to_str().unwrap()];
        args.extend(shards[..2].iter().map(|p| p.to_str().unwrap()));
        args.push(bad.to_str().unwrap());
        let r = gearshock(&args);
        let err = String::from_utf8_lossy(&r.stderr);
        assert_eq!(r.status.code(), Some(2), "{pointer}: {err}");
        assert!(err.contains(words), "{pointer}: `{words}` not in {err}");
        assert!(err.contains(&format!("forged{k}.json")), "{err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    }
    assert!(files(&out).is_empty(), "a refused merge wrote files");
}
