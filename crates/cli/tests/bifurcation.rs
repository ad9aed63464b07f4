//! `gearshock bifurcation`: shards merged equal the unsharded run, progress
//! lines on request, and JSON lines streamed point by point with the same results.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use serde_json::{json, Value};
use test_support::cli::{gearshock, json, json_lines, words};

#[test]
fn sharded_sweep_merged_equals_the_unsharded_run() {
    let base = words("bifurcation --omega-from 0.4 --omega-to 1.4 --points 7 --direction both --transient-periods 30 --record-periods 6");
    let mut whole_args = base.to_vec();
    whole_args.extend(["--chains", "2"]);
    let whole = json(&whole_args);
    assert_eq!(whole["points"].as_array().expect("points").len(), 14);
    let dir = std::env::temp_dir().join(format!("gearshock-shards-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    let mut files = Vec::new();
    for i in 0..2 {
        let mut args = base.to_vec();
        let shard = format!("{i}/2");
        args.extend(["--shard", &shard]);
        let v = json(&args);
        let file = dir.join(format!("shard{i}.json"));
        std::fs::write(&file, v.to_string()).expect("write");
        files.push(file.to_str().expect("path").to_string());
    }
    let mut merge_args = vec!["merge"];
    merge_args.extend(files.iter().map(String::as_str));
    let merged = json(&merge_args);
    assert_eq!(merged, whole);
    // A missing shard is refused.
    let out = gearshock(&["merge", &files[0]]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("shard 1/2 is missing"));
}

#[test]
fn progress_lines_go_to_stderr_on_request_even_when_it_is_not_a_terminal() {
    let args = words("bifurcation --model gear-pair --omega-from 0.5 --omega-to 0.7 --points 3 --transient-periods 5 --record-periods 2");
    let quiet = gearshock(&args);
    assert!(quiet.status.success());
    assert!(
        quiet.stderr.is_empty(),
        "no bar when stderr is not a terminal"
    );
    let mut with = args.to_vec();
    with.push("--progress");
    let out = gearshock(&with);
    assert!(out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(
        lines.len(),
        4,
        "a line at the start, then one per point here: {err}"
    );
    assert_eq!(lines[0], "gearshock: progress 0/3 points (0 %)");
    assert_eq!(lines[3], "gearshock: progress 3/3 points (100 %)");
    // The result is unchanged.
    let a: Value = serde_json::from_slice(&quiet.stdout).expect("json");
    let b: Value = serde_json::from_slice(&out.stdout).expect("json");
    assert_eq!(a, b);
}

#[test]
fn jsonl_streams_each_point_as_computed_with_the_same_results() {
    let sweep = words("bifurcation --model gear-pair --omega-from 0.5 --omega-to 0.7 --points 3 --direction both --transient-periods 5 --record-periods 2");
    let whole = json(&sweep);
    let mut args = sweep.to_vec();
    args.extend(["--format", "jsonl"]);
    let lines = json_lines(&args);
    assert_eq!(lines.len(), 1 + 6 + 1);
    assert_eq!(lines[0]["spec"], whole["spec"]);
    assert_eq!(lines[0]["params"], whole["params"]);
    assert_eq!(lines[7], json!({"complete": true, "points": 6}));
    let key = |p: &Value| (p["direction"].to_string(), p["index"].as_u64());
    let mut streamed: Vec<Value> = lines[1..7].to_vec();
    let mut written: Vec<Value> = whole["points"].as_array().expect("points").clone();
    streamed.sort_by_key(key);
    written.sort_by_key(key);
    assert_eq!(streamed, written);

    let lyap = words("lyapunov --model gear-pair --omega-from 0.5 --omega-to 0.6 --points 2 --transient-periods 10 --periods 10");
    let whole = json(&lyap);
    let mut args = lyap.to_vec();
    args.extend(["--format", "jsonl"]);
    let lines = json_lines(&args);
    assert_eq!(lines[0]["spec"], whole["spec"]);
    assert_eq!(lines[1..3], whole["points"].as_array().expect("points")[..]);
    assert_eq!(lines[3], json!({"complete": true, "points": 2}));

    let inst = words("instability --model gear-pair --omega-from 0.5 --omega-to 2 --points 3");
    let whole = json(&inst);
    let mut args = inst.to_vec();
    args.extend(["--format", "jsonl"]);
    let lines = json_lines(&args);
    assert_eq!(lines[1..4], whole["points"].as_array().expect("points")[..]);
    assert_eq!(lines[4], json!({"complete": true, "points": 3}));

    let map = words("map --model gear-pair --omega-from 0.5 --omega-to 0.6 --omega-points 2 --value-from 50 --value-to 60 --value-points 2 --transient-periods 5 --record-periods 2");
    let whole = json(&map);
    let mut args = map.to_vec();
    args.extend(["--format", "jsonl"]);
    let lines = json_lines(&args);
    assert_eq!(lines[0]["spec"], whole["spec"]);
    assert_eq!(lines[1..5], whole["cells"].as_array().expect("cells")[..]);
    assert_eq!(lines[5], json!({"complete": true, "cells": 4}));

    // Other commands write their one document on one line.
    let lines = json_lines(&["params", "--format", "jsonl"]);
    assert_eq!(lines, vec![json(&["params"])]);
}

/// A sweep whose shooting once went round for ever (a shot for period 4
/// landed on a period-1 orbit, whose doubling led back to 2, then 4)
/// ends. Run as a child with a generous bound (it takes well under a
/// second in release), so that a return of the loop fails the test
/// instead of hanging the suite.
#[test]
fn a_shooting_chain_that_lands_on_a_shorter_orbit_ends() {
    let args = words("bifurcation --omega-from 0.05 --omega-to 2 --points 20 --chains 4 --direction up --transient-periods 20 --record-periods 5 --shard 0/4");
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_gearshock"))
        .args(&args)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .expect("spawn");
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(600);
    loop {
        if let Some(status) = child.try_wait().expect("wait") {
            assert!(status.success(), "{status}");
            return;
        }
        if std::time::Instant::now() > deadline {
            child.kill().ok();
            panic!("the sweep did not end within 600 s");
        }
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
}
