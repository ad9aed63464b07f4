//! `gearshock merge` streams: it holds one point at a time, never the
//! shards. Observed with a data limit (`ulimit -d`, the heap's ceiling)
//! below the size of the shards' text: a merge that held them all, even as
//! bare text, could not fit, and a streaming one does. The merged output
//! is still the in-memory merge's (`report::merge_shards`) byte for byte.
//! Likewise `bifurcation` keeps its points' numbers (8 bytes each, a
//! quarter of their text) and writes the document one point at a time: it
//! runs under a heap limit of half its output.

#![cfg(unix)]
// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use serde_json::{json, Value};
use std::process::Command;
use test_support::cli::{bin, ok, words};

/// Shards of a tiny real sweep, each point's Poincaré arrays stretched to
/// `record` entries (the spec's `record_periods` with them): merge checks
/// shapes, not physics, so these are shards it must accept, and large.
fn stretched_shards(n: usize, record: usize) -> Vec<Value> {
    let base = "bifurcation --model gear-pair --omega-from 0.5 --omega-to 0.8 --points 48 \
                --transient-periods 5 --record-periods 2";
    (0..n)
        .map(|i| {
            let shard = format!("{i}/{n}");
            let mut args = words(base);
            args.extend(["--shard", &shard]);
            let mut v: Value = serde_json::from_slice(&ok(&args)).expect("json");
            v["spec"]["record_periods"] = json!(record);
            for p in v["points"].as_array_mut().expect("points") {
                for key in [
                    "poincare_x_m",
                    "poincare_x_velocity_m_s",
                    "poincare_delta_m",
                    "poincare_velocity_m_s",
                ] {
                    let a = p[key].as_array().expect("array").clone();
                    p[key] = a.iter().cycle().take(record).cloned().collect();
                }
            }
            v
        })
        .collect()
}

#[test]
fn merge_holds_one_point_not_the_shards() {
    let d = std::env::temp_dir().join(format!("gearshock-merge-memory-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("dir");
    let shards = stretched_shards(6, 5_000);
    let mut files = Vec::new();
    let mut total = 0;
    for (i, s) in shards.iter().enumerate() {
        let f = d.join(format!("s{i}.json"));
        let text = serde_json::to_string_pretty(s).expect("text") + "\n";
        total += text.len();
        std::fs::write(&f, text).expect("write");
        files.push(f.to_str().expect("path").to_string());
    }
    // The heap's ceiling: half the shards' text.
    let limit_kib = total / 2 / 1024;
    assert!(limit_kib > 8 * 1024, "the shards are large: {total} bytes");
    let out = Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -d {limit_kib} && exec \"$0\" merge \"$@\""))
        .arg(bin())
        .args(&files)
        .env("TMPDIR", &d)
        .output()
        .expect("run");
    assert!(
        out.status.success(),
        "merge of {total} bytes under a {limit_kib} KiB heap: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let expected = serde_json::to_string_pretty(&report::merge_shards(&shards).expect("merge"))
        .expect("text")
        + "\n";
    assert!(
        out.stdout == expected.as_bytes(),
        "the streamed merge is the in-memory one byte for byte"
    );
    // The temporary file is gone.
    let left: Vec<_> = std::fs::read_dir(&d)
        .expect("dir")
        .filter_map(Result::ok)
        .filter(|e| e.file_name().to_string_lossy().starts_with(".gearshock"))
        .collect();
    assert!(left.is_empty(), "temporary files left: {left:?}");
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn bifurcation_holds_its_numbers_not_its_document() {
    let args = words(
        "bifurcation --model gear-pair --omega-from 0.5 --omega-to 1.5 --points 20 \
         --record-periods 10000 --transient-periods 0",
    );
    let whole = ok(&args);
    assert!(
        whole.len() > 16 << 20,
        "a large output: {} bytes",
        whole.len()
    );
    let limit_kib = whole.len() / 2 / 1024;
    let out = Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -d {limit_kib} && exec \"$0\" \"$@\""))
        .arg(bin())
        .args(&args)
        .output()
        .expect("run");
    assert!(
        out.status.success(),
        "{} bytes under a {limit_kib} KiB heap: {}",
        whole.len(),
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(out.stdout == whole, "the same document under the limit");
}
