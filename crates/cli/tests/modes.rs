//! `gearshock modes`: the static equilibrium, mesh forces and natural modes.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use test_support::cli::{gearshock, json};

#[test]
fn modes_reports_frequencies_forces_and_the_balancing_torque() {
    let v = json(&["modes"]);
    let f = v["natural_frequencies_hz"].as_array().expect("array");
    assert_eq!(f.len(), 10);
    assert_eq!(f[0], 0.0);
    assert!(f.windows(2).all(|w| w[0].as_f64() <= w[1].as_f64()));
    assert!((v["balancing_torque_s2_nm"].as_f64().expect("number") - 969.697).abs() < 1e-3);
    assert!((v["static_mesh_force_n"]["s1a1"].as_f64().expect("force") - 9853.5).abs() < 0.1);
    assert_eq!(v["modes"][0]["kind"], "rigid-body");
    assert!((v["omega_ref_rad_s"].as_f64().expect("omega_ref") - 34068.0).abs() < 1.0);
    let csv = gearshock(&["modes", "--format", "csv"]);
    assert!(String::from_utf8_lossy(&csv.stdout).starts_with("frequency_hz,omega,kind"));
}
