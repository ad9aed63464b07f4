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

/// `bench --branches-only --quick`: both branch figures with their medians
/// and what the run computed (the gear pair's whole branch: its 993 points
/// end near Omega 1.5, the range's end).
#[test]
fn bench_branches_reports_both_figures() {
    let v = json(&["bench", "--branches-only", "--quick", "--repeats", "1"]);
    let b = &v["shooting_branches"];
    let page = &b["compound_page_300_points"];
    assert!(page["median_s"].as_f64().expect("s") > 0.0);
    assert_eq!(page["last_run"]["points"].as_u64(), Some(20));
    let pair = &b["gear_pair_whole_branch"]["last_run"];
    assert!(pair["points"].as_u64().expect("points") > 100, "{pair}");
    let reach = pair["omega_reached"].as_f64().expect("omega");
    assert!(reach > 1.49 && reach <= 1.5, "{pair}");
}
