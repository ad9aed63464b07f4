//! Every output format of every command writes its data: each command that
//! takes `--format` is run on a small case in JSON, JSON lines and CSV, and
//! its stdout must be non-empty and parse (one JSON document; one JSON
//! value a line; a CSV header and at least one row, every row as many
//! fields as the header).

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use test_support::cli::{gearshock, words};

/// A short steady run for the sweeps.
const SHORT: &str = "--transient-periods 5 --record-periods 2";

/// One small case of each command (and of each frequency-response method).
fn cases() -> Vec<String> {
    let range = "--omega-from 0.5 --omega-to 0.6";
    vec![
        "params --model gear-pair".into(),
        "modes --model gear-pair".into(),
        "modes --model ravigneaux".into(),
        format!("simulate --model gear-pair --omega 0.8 {SHORT}"),
        format!("bifurcation --model gear-pair {range} --points 2 {SHORT}"),
        "frf --model gear-pair --omega-from 0.4 --omega-to 1.3 --points 20 --harmonics 3".into(),
        "frf --model gear-pair --omega-from 0.4 --omega-to 1.3 --points 20 --harmonics 3 --method aft"
            .into(),
        "frf --model gear-pair --omega-from 0.4 --omega-to 1.3 --points 20 --harmonics 1 \
         --method describing-function"
            .into(),
        "frf --model gear-pair --method shooting --omega-from 0.4 --omega-to 1.3 --points 50".into(),
        "frf --model gear-pair --method shooting --omega-from 0.4 --omega-to 1.3 --points 10 \
         --mesh all --direction down --no-switch"
            .into(),
        format!(
            "map --model gear-pair {range} --omega-points 2 --key te_um --value-from 10 \
             --value-to 20 --value-points 2 {SHORT}"
        ),
        "boundaries --model gear-pair --key te_um --value-from 1 --value-to 20 \
         --omega-from 0.4 --omega-to 0.6 --levels 2 --points 10 --harmonics 3"
            .into(),
        format!("lyapunov --model gear-pair {range} --points 2 --transient-periods 5 --periods 5"),
        format!("instability --model gear-pair {range} --points 3"),
    ]
}

/// Checks that `text` is a CSV table: a header and rows of as many fields.
fn check_csv(case: &str, text: &str) {
    let mut lines = text.lines();
    let header = lines.next().unwrap_or_else(|| panic!("{case}: no header"));
    let fields = header.split(',').count();
    assert!(fields >= 2, "{case}: header {header}");
    assert!(
        header
            .split(',')
            .all(|f| !f.is_empty() && f.parse::<f64>().is_err()),
        "{case}: the first line is a header of names: {header}"
    );
    let rows: Vec<&str> = lines.collect();
    assert!(!rows.is_empty(), "{case}: a header and no row");
    for r in &rows {
        assert_eq!(
            r.split(',').count(),
            fields,
            "{case}: row {r} against {header}"
        );
    }
}

#[test]
fn every_format_of_every_command_writes_data_that_parses() {
    for case in cases() {
        for format in ["json", "jsonl", "csv"] {
            let line = format!("{case} --format {format}");
            let out = gearshock(&words(&line));
            let err = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(0), "{line}: {err}");
            let text = String::from_utf8(out.stdout).expect("UTF-8");
            assert!(!text.trim().is_empty(), "{line}: nothing written");
            match format {
                "json" => {
                    let v: serde_json::Value =
                        serde_json::from_str(&text).unwrap_or_else(|e| panic!("{line}: {e}"));
                    assert!(v.is_object(), "{line}");
                }
                "jsonl" => {
                    for l in text.lines() {
                        let v: serde_json::Value =
                            serde_json::from_str(l).unwrap_or_else(|e| panic!("{line}: {e}: {l}"));
                        assert!(v.is_object(), "{line}: {l}");
                    }
                }
                _ => check_csv(&line, &text),
            }
        }
    }
}
