//! `gearshock simulate`: one steady state, reported per mesh in SI units.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use test_support::cli::{gearshock, json, refused, words};

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

/// `kv_iso6336`: ISO 6336-1's K_v (method B) beside the nonlinear dynamic
/// factor. The gear pair's defaults are the worked input of
/// `solver::iso6336`'s hand calculation (30/45 teeth, m 4 mm, 500 N m,
/// face width 50 mm, grade 6): K_v 1.3284 at N 0.5 (subcritical) and
/// 2.2214 at N 1 (main resonance). Its reduced mass is the model's
/// equivalent mass, so N is Omega.
#[test]
fn simulate_reports_iso_kv_beside_the_dynamic_factor() {
    for (omega, kv, range) in [
        (0.5, 1.3284, "subcritical"),
        (1.0, 2.2214, "main resonance"),
    ] {
        let v = json(&[
            "simulate",
            "--model",
            "gear-pair",
            "--omega",
            &omega.to_string(),
            "--transient-periods",
            "20",
            "--record-periods",
            "5",
        ]);
        let got = v["kv_iso6336"].as_f64().expect("kv");
        assert!((got - kv).abs() < 1e-4, "Omega {omega}: {got}");
        assert!(v["dynamic_factor"].is_number());
        let m = &v["iso6336"]["meshes"]["pg"];
        assert_eq!(m["range"], range);
        let n = m["resonance_ratio"].as_f64().expect("N");
        assert!((n - omega).abs() < 1e-9, "N {n}");
        assert_eq!(v["all_meshes"]["pg"]["kv_iso6336"], v["kv_iso6336"]);
        assert_eq!(v["iso6336"]["inputs"]["accuracy_grade"], 6.0);
        assert_eq!(v["iso6336"]["inputs"]["face_width_mm"], 50.0);
    }
    // Every mesh of the compound set is rated; the inputs are echoed.
    let v = json(&words(
        "simulate --omega 0.5 --transient-periods 20 --record-periods 5 --accuracy-grade 8 --face-width-mm 40",
    ));
    let meshes = v["iso6336"]["meshes"].as_object().expect("meshes");
    assert_eq!(meshes.len(), 12);
    for (name, m) in v["all_meshes"].as_object().expect("all") {
        assert!(m["kv_iso6336"].as_f64().expect("kv") > 1.0, "{name}");
        assert_eq!(m["kv_iso6336"], meshes[name]["kv"], "{name}");
    }
    assert_eq!(v["iso6336"]["inputs"]["accuracy_grade"], 8.0);
    // 1e9 N/m over 40 mm: c_gamma_alpha 25 N/(mm um).
    let c = meshes["s1a1"]["mesh_stiffness_n_mm_um"]
        .as_f64()
        .expect("c");
    assert!((c - 25.0).abs() < 1e-9, "{c}");
    refused(
        &words("simulate --omega 0.5 --accuracy-grade 12"),
        &["accuracy grade = 12", "1 ..= 11"],
    );
    refused(
        &words("simulate --omega 0.5 --face-width-mm -3"),
        &["face width (mm) = -3"],
    );
}
