//! `gearshock simulate`: one steady state, reported per mesh in SI units.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use test_support::cli::{gearshock, json, words};

#[test]
fn simulate_reports_one_mesh_with_si_units() {
    let v = json(&words(
        "simulate --omega 0.5 --transient-periods 20 --record-periods 10 --mesh rb2",
    ));
    assert_eq!(v["mesh"], "rb2");
    for k in words("omega mesh_freq_hz delta_min_m delta_max_m delta_rms_m dynamic_factor") {
        assert!(v[k].is_number(), "{k}");
    }
    assert_eq!(
        v["poincare"]["delta_m"].as_array().expect("samples").len(),
        10
    );
    assert!(["none", "single-sided", "double-sided", "no-contact"]
        .contains(&v["impact"].as_str().expect("impact")));
    assert!(v["period"].is_null() || v["period"].is_u64());
    assert!((v["mesh_freq_hz"].as_f64().expect("f") - 0.5 * 5422.1).abs() < 1.0);
    assert!(
        v["spectrum"]["amplitude_m"]
            .as_array()
            .expect("spectrum")
            .len()
            > 10
    );
    let csv = gearshock(&words(
        "simulate --omega 0.5 --transient-periods 2 --record-periods 2 --format csv",
    ));
    let text = String::from_utf8_lossy(&csv.stdout);
    assert!(text.starts_with("t_s,delta_m,velocity_m_s"));
    assert_eq!(text.lines().count(), 1 + 2 * 64);
}
