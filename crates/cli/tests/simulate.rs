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

/// `load_sharing`: in-phase planets on equal meshes share every kind's
/// load exactly (factor 1 to round-off, every planet's peak the same);
/// five sequential planets do not; the gear pair has nothing to share.
#[test]
fn load_sharing_is_one_for_in_phase_planets_and_above_for_sequential() {
    let v = json(&["simulate", "--omega", "0.35", "--set", "planets=4"]);
    let s = v["load_sharing"].as_object().expect("object");
    assert_eq!(s.len(), 4, "{s:?}");
    for (kind, k) in s {
        let f = k["factor"].as_f64().expect("factor");
        assert!((f - 1.0).abs() <= 1e-9, "{kind}: {f}");
        assert_eq!(
            k["peak_force_n"].as_array().expect("peaks").len(),
            4,
            "{kind}"
        );
    }
    let v = json(&[
        "simulate",
        "--omega",
        "0.35",
        "--set",
        "planets=5",
        "--set",
        "phasing=sequential",
    ]);
    let worst = v["load_sharing"]
        .as_object()
        .expect("object")
        .values()
        .map(|k| k["factor"].as_f64().expect("factor"))
        .fold(1.0, f64::max);
    assert!(worst > 1.001, "{}", v["load_sharing"]);
    let v = json(&["simulate", "--model", "gear-pair", "--omega", "0.5"]);
    assert_eq!(v["load_sharing"], serde_json::json!({}));
}
