//! `gearshock lyapunov`: a negative exponent on a stable orbit.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use test_support::cli::{json, words};

#[test]
fn lyapunov_is_negative_on_a_stable_orbit() {
    let v = json(&words("lyapunov --model gear-pair --set backlash_um=0 --omega-from 0.8 --omega-to 1.2 --points 2 --periods 100"));
    let pts = v["points"].as_array().unwrap();
    assert_eq!(pts.len(), 2);
    for p in pts {
        assert!(p["exponent_per_period"].as_f64().unwrap() < 0.0);
        assert!(p["exponent_per_s"].as_f64().unwrap() < 0.0);
    }
}
