//! `gearshock sharing`: the planets' load sharing over speed, in-phase
//! against sequential phasing, and the mesh force by order `simulate`
//! prints, against facts derived here.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use serde_json::Value;
use test_support::cli::{gearshock, json};

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap()
}

/// In-phase planets on equal meshes move alike: at every speed each kind's
/// planets reach the same peak force and the factor is 1 to 1e-12. Five
/// sequential planets (36, 48, 84 teeth: no k z / 5 whole below k = 5)
/// stagger their mesh cycles and share unequally; a factor is never below
/// 1, being the largest over the mean.
#[test]
fn in_phase_planets_share_exactly_and_sequential_ones_do_not() {
    let v = json(&[
        "sharing",
        "--omega-from",
        "0.3",
        "--omega-to",
        "0.5",
        "--points",
        "3",
        "--record-periods",
        "20",
        "--set",
        "planets=5",
    ]);
    assert_eq!(v["planets"], 5);
    let inphase = v["phasings"]["in-phase"]["points"].as_array().unwrap();
    let seq = v["phasings"]["sequential"]["points"].as_array().unwrap();
    assert_eq!((inphase.len(), seq.len()), (3, 3));
    for p in inphase {
        let kinds = p["kinds"].as_object().unwrap();
        assert_eq!(kinds.len(), 4, "{p}");
        for (kind, k) in kinds {
            assert!((f(&k["factor"]) - 1.0).abs() <= 1e-12, "{kind} {p}");
            let peaks: Vec<f64> = k["peak_force_n"]
                .as_array()
                .unwrap()
                .iter()
                .map(f)
                .collect();
            assert_eq!(peaks.len(), 5);
            let mean = peaks.iter().sum::<f64>() / 5.0;
            assert!(
                peaks.iter().all(|x| (x - mean).abs() <= 1e-12 * mean),
                "{kind} {p}"
            );
        }
    }
    let mut worst: f64 = 1.0;
    for p in seq {
        for (_, k) in p["kinds"].as_object().unwrap() {
            let peaks: Vec<f64> = k["peak_force_n"]
                .as_array()
                .unwrap()
                .iter()
                .map(f)
                .collect();
            let mean = peaks.iter().sum::<f64>() / peaks.len() as f64;
            let largest = peaks.iter().copied().fold(0.0, f64::max);
            assert!((f(&k["factor"]) - largest / mean).abs() <= 1e-12);
            worst = worst.max(largest / mean);
        }
    }
    assert!(worst > 1.01, "{worst}");
    // The speed in rpm is Omega's: 63 mesh cycles per input turn.
    let scale = f(&inphase[1]["input_speed_rpm"]) / f(&inphase[1]["omega"]);
    assert!((f(&inphase[2]["input_speed_rpm"]) - 0.5 * scale).abs() <= 1e-9 * scale);
}

/// The gear pair has nothing to share: refused by name.
#[test]
fn the_gear_pair_is_refused() {
    let out = gearshock(&[
        "sharing",
        "--model",
        "gear-pair",
        "--omega-from",
        "0.3",
        "--omega-to",
        "0.5",
    ]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("gear pair") && err.contains("ravigneaux"),
        "{err}"
    );
}

/// `simulate` prints the force by order: its peaks are the spectrum's
/// lines named as orders, and the sum over the planets of the mesh's kind
/// is in phase three times one planet's force.
#[test]
fn simulate_prints_the_mesh_force_by_order() {
    let v = json(&["simulate", "--omega", "0.35", "--record-periods", "20"]);
    let fo = &v["force_by_order"];
    assert_eq!(fo["mesh"], "s1a1");
    assert_eq!(fo["record_periods"], 20);
    let order: Vec<f64> = fo["order"].as_array().unwrap().iter().map(f).collect();
    let amp: Vec<f64> = fo["amplitude_n"]
        .as_array()
        .unwrap()
        .iter()
        .map(f)
        .collect();
    // Bin k is order k / 20.
    for (k, o) in order.iter().enumerate() {
        assert!((o - k as f64 / 20.0).abs() <= 1e-12);
    }
    let peaks = fo["peaks"].as_array().unwrap();
    let labels: Vec<&str> = peaks.iter().map(|p| p["label"].as_str().unwrap()).collect();
    assert_eq!(labels[..2], ["1×", "2×"], "{fo}");
    for p in peaks {
        let k = (f(&p["order"]) * 20.0).round() as usize;
        assert_eq!(f(&p["amplitude_n"]), amp[k]);
        assert_eq!(p["whole"], k.is_multiple_of(20));
    }
    let sum = &fo["planet_sum"];
    assert_eq!(sum["kind"], "s1a");
    assert_eq!(sum["meshes"].as_array().unwrap().len(), 3);
    assert!(sum["cancelled_orders"].as_array().unwrap().is_empty());
    let total: Vec<f64> = sum["amplitude_n"]
        .as_array()
        .unwrap()
        .iter()
        .map(f)
        .collect();
    let largest = amp.iter().skip(1).copied().fold(0.0, f64::max);
    for (s, a) in total.iter().zip(&amp) {
        assert!((s - 3.0 * a).abs() <= 1e-6 * largest, "{s} against 3 x {a}");
    }
}
