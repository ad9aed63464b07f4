//! The fuzz harness's figure-shard target, run on the `gearshock` binary
//! (the figure-shard merge draws every file, so it lives in the CLI):
//! forged shard sets of a real figure (members, smuggled file text, forged
//! data and options, mutated text) given to `gearshock merge --out DIR`.
//! Every run exits 0 or 2; a refusal is one line and writes nothing; an
//! accepted merge writes exactly the genuine merge's files, without a
//! script; nothing is ever written outside `--out`. GEARSHOCK_FUZZ_INPUTS
//! sets the number of inputs (default 40; each merge draws a figure).

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use serde_json::Value;
use test_support::cli::{files, gearshock, ok, temp_dir, words};

fn inputs() -> u64 {
    std::env::var("GEARSHOCK_FUZZ_INPUTS")
        .ok()
        .and_then(|v| v.parse::<u64>().ok())
        .map_or(40, |n| (n / 40).max(40))
}

#[test]
fn figure_shard_merge_survives_forged_shards() {
    let work = temp_dir("figure-fuzz");
    let base: Vec<Value> = (0..2)
        .map(|i| {
            let s = format!("{i}/2");
            let mut args = words("figure fig5 --transient-periods 20 --record-periods 4");
            args.extend(["--shard", &s]);
            serde_json::from_slice(&ok(&args)).unwrap()
        })
        .collect();
    let write = |tag: &str, shards: &[Value]| -> Vec<String> {
        shards
            .iter()
            .enumerate()
            .map(|(k, v)| {
                let f = work.join(format!("{tag}-{k}.json"));
                let text = match v {
                    Value::String(t) => t.clone(),
                    other => other.to_string(),
                };
                std::fs::write(&f, text).unwrap();
                f.to_str().unwrap().to_string()
            })
            .collect()
    };
    let merge = |out: &std::path::Path, files_: &[String]| {
        let mut args = vec!["merge", "--out", out.to_str().unwrap()];
        args.extend(files_.iter().map(String::as_str));
        gearshock(&args)
    };
    // The genuine merge: the files an accepted merge must write.
    let genuine = work.join("genuine");
    let o = merge(&genuine, &write("genuine", &base));
    assert_eq!(o.status.code(), Some(0));
    let expected: Vec<String> = files(&genuine).into_iter().map(|(n, _)| n).collect();
    assert_eq!(expected.len(), 18);
    let (mut failures, mut accepted, mut refused) = (Vec::new(), 0, 0);
    for n in 0..inputs() {
        let mut r = fuzz::Rng::new(0x5eed, n);
        let shards = fuzz::figure_shards_input(&mut r, &base);
        let tag = format!("in{n}");
        let given = write(&tag, &shards);
        let out = work.join(format!("out{n}"));
        let o = merge(&out, &given);
        let written: Vec<(String, String)> = if out.exists() {
            files(&out)
                .into_iter()
                .map(|(name, bytes)| (name, String::from_utf8_lossy(&bytes).into_owned()))
                .collect()
        } else {
            Vec::new()
        };
        let stderr = String::from_utf8_lossy(&o.stderr);
        match fuzz::check_figure_merge(o.status.code(), &stderr, &written, &expected) {
            Ok(()) if o.status.success() => accepted += 1,
            Ok(()) => refused += 1,
            Err(e) => failures.push(format!("input {n}: {e}")),
        }
        for f in &given {
            let _ = std::fs::remove_file(f);
        }
        let _ = std::fs::remove_dir_all(&out);
    }
    assert!(failures.is_empty(), "{failures:#?}");
    // The generator reaches both sides: some sets merge, most are refused.
    assert!(
        accepted >= 1 && refused >= inputs() / 2,
        "{accepted} accepted, {refused} refused"
    );
    // Nothing escaped --out (a smuggled "../escape.svg").
    let parent = work.parent().unwrap();
    assert!(!parent.join("escape.svg").exists());
    assert!(!work.join("escape.svg").exists());
    let _ = std::fs::remove_dir_all(&work);
}
