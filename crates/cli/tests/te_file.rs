//! `--te-file`: a table of TE fitted to the model's harmonics. A file of
//! a known three-harmonic TE gives back the run with the same harmonics
//! given as keys, to the last printed digit; bad files are refused with
//! the line and the reason, and nothing is computed.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use test_support::cli::{gearshock, ok, refused, temp_dir};

fn data(name: &str) -> String {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data");
    root.join(name).to_str().expect("path").to_string()
}

/// The keys of the file's curve, written in its comment.
const KEYS: [&str; 6] = [
    "te_mean_um=2",
    "te_um=12",
    "te_cos_um=-3",
    "te_cos2_um=2.5",
    "te_sin2_um=1.25",
    "te_sin3_um=-0.8",
];

fn with(base: &[&str], extra: &[String]) -> Vec<String> {
    base.iter()
        .map(|s| s.to_string())
        .chain(extra.iter().cloned())
        .collect()
}

#[test]
fn a_three_harmonic_file_reproduces_the_run_with_its_keys() {
    let base = [
        "simulate",
        "--model",
        "gear-pair",
        "--omega",
        "0.62",
        "--transient-periods",
        "60",
        "--record-periods",
        "5",
    ];
    let by_keys: Vec<String> = KEYS
        .iter()
        .flat_map(|k| ["--set".to_string(), k.to_string()])
        .collect();
    let by_file = vec![
        "--te-file".to_string(),
        format!("pair={}", data("te_three_harmonics.csv")),
    ];
    let a = with(&base, &by_keys);
    let b = with(&base, &by_file);
    let a: Vec<&str> = a.iter().map(String::as_str).collect();
    let b: Vec<&str> = b.iter().map(String::as_str).collect();
    let (ka, kb) = (ok(&a), ok(&b));
    assert!(!ka.is_empty());
    assert_eq!(String::from_utf8_lossy(&ka), String::from_utf8_lossy(&kb));
    // The fit is said, with its residual.
    let out = gearshock(&b);
    let note = String::from_utf8_lossy(&out.stderr);
    assert!(
        note.contains("fitted to 360 points") && note.contains("RMS residual"),
        "{note}"
    );
    // The parameters the file set are the keys'.
    let params: Vec<&str> = ["params", "--model", "gear-pair"].into();
    let mut p = params.clone();
    p.extend(&b[9..]);
    let mut q = params.clone();
    q.extend(&a[9..]);
    assert_eq!(ok(&p), ok(&q));
}

#[test]
fn bad_files_are_refused_with_the_line_and_the_reason() {
    let dir = temp_dir("te-file");
    let cases: [(&str, &str, &str); 6] = [
        ("empty.csv", "", "empty"),
        (
            "word.csv",
            "fraction,te_um\n0,1\n0.5,x1\n",
            "line 3: the TE `x1` is not a number",
        ),
        (
            "one.csv",
            "fraction,te_um\n0,1\n0.5\n",
            "line 3: one column",
        ),
        (
            "back.csv",
            "fraction,te_um\n0,1\n0.5,1\n0.25,1\n",
            "line 4: the abscissa 0.25 does not increase",
        ),
        (
            "nan.csv",
            "fraction,te_um\n0,1\n0.5,NaN\n",
            "line 3: the TE is NaN",
        ),
        (
            "few.csv",
            "fraction,te_um\n0,1\n0.5,1\n",
            "2 points cannot fit",
        ),
    ];
    for (name, text, want) in cases {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        let arg = format!("pair={}", path.display());
        refused(
            &[
                "simulate",
                "--model",
                "gear-pair",
                "--omega",
                "0.5",
                "--te-file",
                &arg,
            ],
            &[want],
        );
    }
    // Over 10 MiB: refused before reading.
    let big = dir.join("big.csv");
    let f = std::fs::File::create(&big).unwrap();
    f.set_len((10 << 20) + 1).unwrap();
    let arg = format!("pair={}", big.display());
    refused(
        &["params", "--model", "gear-pair", "--te-file", &arg],
        &["larger than the 10 MiB"],
    );
    // A kind the model does not have.
    let arg = format!("s1a={}", data("te_three_harmonics.csv"));
    refused(
        &["params", "--model", "gear-pair", "--te-file", &arg],
        &["KIND one of pair"],
    );
}
