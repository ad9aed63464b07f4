//! `gearshock bench --quick`: medians reported.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use test_support::cli::json;

#[test]
fn bench_quick_reports_medians() {
    let v = json(&["bench", "--quick", "--repeats", "1"]);
    assert!(v["rhs"]["evaluations_per_s"].as_f64().expect("rate") > 0.0);
    assert!(v["simulate"]["median_ms"].as_f64().expect("ms") > 0.0);
    assert!(v["bifurcation"]["points_per_s"].as_f64().expect("pts") > 0.0);
}
