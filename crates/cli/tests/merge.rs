//! `gearshock merge`: forged shards refused before anything is sized, and
//! every input file read through a size limit.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use serde_json::{json, Value};
use std::process::Command;
use test_support::cli::{bin, json, refused, temp_dir, write_json};

/// Two real shards of a tiny sweep (3 points, up and down).
fn tiny_sweep_shards() -> Vec<Value> {
    (0..2)
        .map(|i| {
            shard(
                "bifurcation",
                "--omega-from 0.5 --omega-to 0.7 --points 3 --direction both",
                i,
            )
        })
        .collect()
}

/// Shard `i` of 2 of a short gear-pair run of `command` on `grid` (its
/// flags, separated by spaces), as JSON.
fn shard(command: &str, grid: &str, i: u32) -> Value {
    let shard = format!("{i}/2");
    let mut args = vec![command, "--model", "gear-pair"];
    args.extend(grid.split_whitespace());
    args.extend(["--transient-periods", "5", "--record-periods", "2"]);
    args.extend(["--shard", &shard]);
    json(&args)
}

#[test]
fn merge_refuses_forged_shards_before_sizing_anything() {
    let dir = temp_dir("forged");
    let good = tiny_sweep_shards();
    let merge = |shards: &[Value], needles: &[&str]| {
        let files: Vec<String> = shards
            .iter()
            .enumerate()
            .map(|(i, v)| write_json(&dir, &format!("s{i}.json"), v))
            .collect();
        let mut args = vec!["merge"];
        args.extend(files.iter().map(String::as_str));
        refused(&args, needles)
    };
    // The genuine shards merge.
    let files: Vec<String> = good
        .iter()
        .enumerate()
        .map(|(i, v)| write_json(&dir, &format!("g{i}.json"), v))
        .collect();
    let merged = json(&["merge", &files[0], &files[1]]);
    assert_eq!(merged["points"].as_array().expect("points").len(), 6);

    // A forged shard count sized memory: capacity overflow (exit 101) or abort (134).
    for (chains, needle) in [
        (json!(u64::MAX), "out of range"),
        (json!(1_000_000_000_000u64), "out of range"),
        // The shards still say i/2: not shards of 3.
        (json!(3), "spec.shard = \"0/2\" is out of range"),
    ] {
        let mut forged = good.clone();
        for v in &mut forged {
            v["spec"]["chains"] = chains.clone();
        }
        merge(&forged, &["chains", needle]);
    }
    // Each shard set forged from the genuine one by `edit`.
    let forge = |base: &[Value], edit: &dyn Fn(&mut [Value]), needles: &[&str]| {
        let mut forged = base.to_vec();
        edit(&mut forged);
        merge(&forged, needles);
    };
    let every = |key: &'static str, field: &'static str, value: Value| {
        move |f: &mut [Value]| f.iter_mut().for_each(|v| v[key][field] = value.clone())
    };
    forge(
        &good,
        &every("spec", "points", json!(u64::MAX)),
        &["points", "out of range"],
    );
    // A foreign point (omega 999) was copied into the output.
    let first = |f: &mut [Value], key: &str, value: Value| f[0]["points"][0][key] = value;
    forge(
        &good,
        &|f| first(f, "omega", json!(999.0)),
        &["omega 999", "not on the sweep's grid"],
    );
    forge(
        &good,
        &|f| first(f, "index", json!(1)),
        &["index 1", "not on the sweep's grid"],
    );
    let twice = |f: &mut [Value]| {
        let extra = f[0]["points"][0].clone();
        f[0]["points"].as_array_mut().expect("points").push(extra);
    };
    forge(&good, &twice, &["given twice"]);
    let missing = |f: &mut [Value]| drop(f[1]["points"].as_array_mut().expect("points").pop());
    forge(&good, &missing, &["missing"]);
    // A forged parameter set would be copied into the output.
    forge(
        &good,
        &every("params", "backlash_um", json!(-5)),
        &["params", "backlash_um"],
    );
    // Step counts that wrapped when summed.
    let wrapped = |f: &mut [Value]| f[0]["points"][0]["stats"]["steps"] = json!(u64::MAX);
    forge(&good, &wrapped, &["stats.steps", "out of range"]);

    // Maps: forged shard count and a cell off the grid.
    let map_shard = |i: u32| {
        let grid = "--omega-from 0.5 --omega-to 0.6 --omega-points 2";
        shard(
            "map",
            &format!("{grid} --value-from 50 --value-to 60 --value-points 2"),
            i,
        )
    };
    let maps = vec![map_shard(0), map_shard(1)];
    forge(
        &maps,
        &every("spec", "shards", json!(4_000_000_000u64)),
        &["shards", "out of range"],
    );
    let cell = |f: &mut [Value], key: &str, value: Value| f[1]["cells"][0][key] = value;
    forge(
        &maps,
        &|f| cell(f, "row", json!(999)),
        &["row 999", "not on the map's grid"],
    );
    forge(
        &maps,
        &|f| cell(f, "value", json!(1e300)),
        &["not on the map's grid"],
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn input_files_are_read_through_a_size_limit() {
    // `--params /dev/zero` read until memory ran out.
    refused(&["params", "--params", "/dev/zero"], &["/dev/zero"]);
    let dir = temp_dir("big");
    let big = dir.join("big.json");
    let mut text = " ".repeat(2 << 20);
    text.push_str("{}");
    std::fs::write(&big, &text).expect("write");
    let big = big.to_str().expect("path");
    refused(
        &["params", "--params", big],
        &["--params", "larger than", "1 MiB"],
    );
    // A pipe (no size to look at first) is cut at the limit too.
    let mut child = Command::new(bin())
        .args(["params", "--params", "/dev/stdin"])
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("spawn");
    let mut stdin = child.stdin.take().expect("stdin");
    let writer = std::thread::spawn(move || {
        use std::io::Write;
        // The reader stops early: a broken pipe here is expected.
        let _ = stdin.write_all(text.as_bytes());
    });
    let out = child.wait_with_output().expect("wait");
    let _ = writer.join();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("larger than"), "{err}");
    refused(&["merge", "/dev/zero"], &["merge", "/dev/zero"]);
    let _ = std::fs::remove_dir_all(&dir);
}
