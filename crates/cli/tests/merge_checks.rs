//! `gearshock merge` is exact and checks what it copies.
//!
//! - Exact: 2, 3 and 7 shards of a sweep and of a map, merged, are the
//!   unsharded run's output byte for byte (`--chains n` for a sweep, which
//!   `--shard i/n` implies): numbers pass through unchanged.
//! - Checked: forged shards (counters that are not whole numbers,
//!   Poincaré arrays of the wrong length, a model or shard that is not the
//!   run's, fields gearshock never writes, a cell's fields that disagree) are refused with exit 2 and one
//!   line naming the file, the field and the allowed range.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use serde_json::{json, Value};
use std::path::{Path, PathBuf};
use test_support::cli::{ok, refused, words};

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("gearshock-merge-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("dir");
    d
}

/// Runs `base` with `--shard i/n` for every i, each output written as
/// printed into `d`; returns the files.
fn shards(d: &Path, base: &[&str], n: usize) -> Vec<String> {
    (0..n)
        .map(|i| {
            let s = format!("{i}/{n}");
            let mut args = base.to_vec();
            args.extend(["--shard", &s]);
            let f = d.join(format!("s{i}.json"));
            std::fs::write(&f, ok(&args)).expect("write");
            f.to_str().expect("path").to_string()
        })
        .collect()
}

fn merged(files: &[String]) -> Vec<u8> {
    let mut args = vec!["merge"];
    // Reversed: the order of the files does not matter.
    args.extend(files.iter().rev().map(String::as_str));
    ok(&args)
}

const SWEEP: &str = "bifurcation --omega-from 0.4 --omega-to 1.4 --points 14 --direction both \
     --transient-periods 30 --record-periods 6";

const MAP: &str = "map --model gear-pair --omega-from 0.4 --omega-to 1.6 --omega-points 3 \
     --key te_um --value-from 1 --value-to 40 --value-points 7 \
     --transient-periods 40 --record-periods 8";

/// A tiny sweep (3 points, up only) forged by the tests below.
const TINY_SWEEP: &str = "bifurcation --omega-from 0.5 --omega-to 0.7 --points 3 \
     --transient-periods 5 --record-periods 3";

#[test]
fn merged_sweep_shards_are_the_run_with_as_many_chains_byte_for_byte() {
    let d = dir("sweep");
    for n in [2usize, 3, 7] {
        let chains = n.to_string();
        let mut whole = words(SWEEP);
        whole.extend(["--chains", &chains]);
        let whole = ok(&whole);
        let files = shards(&d, &words(SWEEP), n);
        let merged = merged(&files);
        // Non-trivial: the merged text holds long floats (17 digits), the
        // kind a read without round trip altered in the last place.
        let text = String::from_utf8_lossy(&whole);
        assert!(
            text.split(|c: char| !c.is_ascii_digit())
                .any(|digits| digits.len() >= 16),
            "no long float in the run's output"
        );
        assert!(
            whole == merged,
            "{n} shards merged differ from --chains {n}"
        );
    }
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn merged_map_shards_are_the_unsharded_map_byte_for_byte() {
    let d = dir("map");
    let whole = ok(&words(MAP));
    for n in [2usize, 3, 7] {
        let files = shards(&d, &words(MAP), n);
        assert!(whole == merged(&files), "{n} map shards merged differ");
    }
    let _ = std::fs::remove_dir_all(&d);
}

/// One forgery: a change made to shard 0 (a JSON pointer and its new
/// value), and words the refusal must hold.
type Forgery = (&'static str, Value, &'static [&'static str]);

/// Sets the field at `pointer` (a JSON pointer), adding it to its object
/// if it is not there.
fn set(v: &mut Value, pointer: &str, value: Value) {
    if let Some(slot) = v.pointer_mut(pointer) {
        *slot = value;
        return;
    }
    let (parent, key) = pointer.rsplit_once('/').expect("a pointer");
    v.pointer_mut(parent)
        .and_then(Value::as_object_mut)
        .unwrap_or_else(|| panic!("{parent} is not an object of the shard"))
        .insert(key.to_string(), value);
}

/// Each forgery applied to genuine shards `good` and merged: refused,
/// naming the forged file.
fn all_refused(d: &Path, good: &[Value], forgeries: &[Forgery]) {
    for (k, (pointer, value, needles)) in forgeries.iter().enumerate() {
        let mut forged = good.to_vec();
        set(&mut forged[0], pointer, value.clone());
        let files: Vec<String> = forged
            .iter()
            .enumerate()
            .map(|(i, v)| {
                let f = d.join(format!("forged{k}-{i}.json"));
                std::fs::write(&f, v.to_string()).expect("write");
                f.to_str().expect("path").to_string()
            })
            .collect();
        let mut args = vec!["merge"];
        args.extend(files.iter().map(String::as_str));
        let mut words = needles.to_vec();
        // The forged file is named.
        let name = format!("forged{k}-0.json");
        words.push(&name);
        refused(&args, &words);
    }
}

fn read(files: &[String]) -> Vec<Value> {
    files
        .iter()
        .map(|f| serde_json::from_slice(&std::fs::read(f).expect("read")).expect("JSON"))
        .collect()
}

#[test]
fn forged_sweep_shards_are_refused_naming_file_field_value_and_range() {
    let d = dir("forged-sweep");
    let good = read(&shards(&d, &words(TINY_SWEEP), 2));
    // The genuine shards merge, and their arrays are record_periods long.
    assert_eq!(
        good[0]["points"][0]["poincare_delta_m"]
            .as_array()
            .unwrap()
            .len(),
        3
    );
    let long = Value::Array(vec![json!(1e-6); 1_000_000]);
    let forgeries: &[Forgery] = &[
        // Work counters: whole numbers up to 2^53 only.
        (
            "/points/0/stats/steps",
            json!(1e300),
            &[
                "stats.steps = 1e+300",
                "out of range",
                "0 ..= 9007199254740992",
            ],
        ),
        (
            "/points/0/stats/steps",
            json!(1e20),
            &["stats.steps = 1e+20"],
        ),
        ("/points/0/stats/steps", json!(1.5), &["stats.steps = 1.5"]),
        (
            "/points/0/stats/steps",
            json!("7"),
            &["stats.steps = \"7\""],
        ),
        (
            "/points/0/stats/steps",
            Value::Null,
            &["stats.steps = null"],
        ),
        (
            "/points/0/stats/settled",
            json!(1),
            &["stats.settled = 1", "true or false"],
        ),
        // At most the 5 transient periods and the record periods of the
        // two Lyapunov probes a run may hand back to its transient
        // (5 + 2 x 3).
        (
            "/points/0/stats/transient_periods_run",
            json!(12),
            &["stats.transient_periods_run = 12", "0 ..= 11"],
        ),
        // Poincaré arrays: exactly record_periods entries.
        (
            "/points/0/poincare_delta_m",
            json!([1e-6]),
            &["poincare_delta_m has 1 entries", "exactly 3"],
        ),
        (
            "/points/0/poincare_velocity_m_s",
            long,
            &["poincare_velocity_m_s has 1000000 entries", "exactly 3"],
        ),
        (
            "/points/0/poincare_delta_m/1",
            json!("<script>"),
            &["poincare_delta_m", "numbers"],
        ),
        // Names gearshock writes, nothing else.
        (
            "/points/0/impact",
            json!("<script>alert(1)</script>"),
            &["impact", "none, single-sided"],
        ),
        (
            "/points/0/worst_mesh",
            json!("s9a9"),
            &["worst_mesh = \"s9a9\""],
        ),
        ("/points/0/period", json!(0), &["period = 0", "1 ..= 3"]),
        (
            "/points/0/extra",
            json!(1),
            &["field extra is not one gearshock writes"],
        ),
        // The run: its model, its shard.
        (
            "/model",
            json!("gear-pair"),
            &["model = \"gear-pair\"", "ravigneaux"],
        ),
        (
            "/spec/shard",
            json!("0/1000000000"),
            &["spec.shard = \"0/1000000000\"", "i/2", "0 ..= 1"],
        ),
        ("/spec/shard", json!("00/2"), &["spec.shard = \"00/2\""]),
        (
            "/spec/record_periods",
            json!(0),
            &["spec.record_periods = 0", "1 ..= 100000"],
        ),
    ];
    all_refused(&d, &good, forgeries);
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_model_differing_between_shards_is_refused() {
    let d = dir("model");
    let mut good = read(&shards(&d, &words(TINY_SWEEP), 2));
    // Shard 1 claims another model (its params unchanged).
    good[1]["model"] = json!("gear-pair");
    let files: Vec<String> = good
        .iter()
        .enumerate()
        .map(|(i, v)| {
            let f = d.join(format!("m{i}.json"));
            std::fs::write(&f, v.to_string()).expect("write");
            f.to_str().expect("path").to_string()
        })
        .collect();
    refused(
        &["merge", &files[0], &files[1]],
        &["m1.json", "model = \"gear-pair\"", "differs"],
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn forged_map_shards_are_refused_naming_file_field_value_and_range() {
    let d = dir("forged-map");
    let base = words(
        "map --model gear-pair --omega-from 0.5 --omega-to 0.6 --omega-points 2 \
         --value-from 50 --value-to 60 --value-points 2 --transient-periods 5 --record-periods 2",
    );
    let good = read(&shards(&d, &base, 2));
    let forgeries: &[Forgery] = &[
        (
            "/cells/0/impact",
            json!("<script>"),
            &["impact = \"<script>\"", "none, single-sided"],
        ),
        ("/cells/0/period", json!(1.5), &["period = 1.5", "1 ..= 2"]),
        (
            "/cells/0/error",
            json!(7),
            &["impact", "null in a failed cell"],
        ),
        ("/cells/0/extra", json!(null), &["field extra"]),
        // A cell's fields agree: cell 0 is periodic-exact, cell 1 not
        // periodic; an exact orbit's multipliers are those of a stable one.
        (
            "/cells/0/max_multiplier_modulus",
            json!(5),
            &[
                "max_multiplier_modulus = 5",
                "a stable orbit",
                "periodic-exact",
            ],
        ),
        (
            "/cells/0/exact",
            json!(false),
            &["exact = false", "true with motion \"periodic-exact\""],
        ),
        (
            "/cells/0/motion",
            json!("not-periodic"),
            &["exact = true", "false with motion \"not-periodic\""],
        ),
        (
            "/cells/0/period",
            Value::Null,
            &["period = null", "a whole number with a periodic motion"],
        ),
        (
            "/cells/1/max_multiplier_modulus",
            json!(0.5),
            &[
                "max_multiplier_modulus = 0.5",
                "null with motion \"not-periodic\"",
            ],
        ),
        (
            "/spec/shard",
            json!("0/1000000000"),
            &["spec.shard = \"0/1000000000\"", "i/2"],
        ),
        (
            "/model",
            json!("ravigneaux"),
            &["model = \"ravigneaux\"", "allowed gear-pair"],
        ),
    ];
    all_refused(&d, &good, forgeries);
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_key_given_twice_in_a_streamed_shard_is_refused_naming_it() {
    // serde_json would keep the last of the two silently; the shard reader
    // streams points one at a time and still refuses, at the top level and
    // inside a point.
    let d = dir("twice");
    let files = shards(&d, &words(TINY_SWEEP), 2);
    let text = std::fs::read_to_string(&files[1]).expect("read");
    let in_point = text.replacen("\"omega\":", "\"omega\":0.61,\"omega\":", 1);
    assert_ne!(in_point, text, "the shard has an omega field to double");
    let at_top = text.replacen('{', "{\"model\":\"ravigneaux\",", 1);
    for (name, forged) in [("p.json", in_point), ("t.json", at_top)] {
        let f = d.join(name);
        std::fs::write(&f, forged).expect("write");
        refused(
            &["merge", &files[0], f.to_str().expect("path")],
            &[name, "given twice"],
        );
    }
    let _ = std::fs::remove_dir_all(&d);
}
