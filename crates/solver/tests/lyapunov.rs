//! The largest Lyapunov exponent of the Poincaré map against known values:
//! the decay rate of a linear damped system (exactly `-zeta omega_n T` for
//! the gear pair, the slowest modal decay for the compound set), a negative
//! exponent on a stable period-1 orbit and a positive one where the time
//! integration finds no period.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use solver::lyapunov::{largest_exponent, LyapunovOptions};
use solver::steady::{steady_state, SteadyOptions};
use std::f64::consts::PI;
use test_support::models::model;

#[test]
fn linear_gear_pair_exponent_is_the_damped_decay_rate() {
    // m x'' + c x' + k x: the separation decays as exp(-zeta omega_n t), so
    // the map's exponent per period is -zeta omega_n T.
    let m = model(&[
        "model=gear-pair",
        "backlash_um=0",
        "stiffness_variation=0",
        "damping_ratio=0.05",
    ]);
    let mesh = &m.system.meshes[0];
    let (k, c, me) = (
        mesh.stiffness_mean_n_m,
        mesh.damping_n_s_m,
        mesh.equivalent_mass_kg,
    );
    let zeta_wn = c / (2.0 * me);
    let wn = (k / me).sqrt();
    assert!((zeta_wn / wn - 0.05).abs() < 1e-12);
    for omega in [0.7, 1.0, 1.6] {
        let mut o = LyapunovOptions::new(omega);
        o.transient_periods = 50;
        o.periods = 400;
        let l = largest_exponent(&m, &o, None).unwrap();
        let t = 2.0 * PI / (omega * m.system.omega_ref_rad_s);
        let exact = -zeta_wn * t;
        // The metric's anisotropy adds a bounded term that averages out as 1/periods.
        assert!(
            (l.per_period - exact).abs() < 0.01 * exact.abs(),
            "Omega {omega}: {} vs {exact}",
            l.per_period
        );
        assert!((l.per_s + zeta_wn).abs() < 0.01 * zeta_wn);
    }
}

#[test]
fn linear_compound_set_exponent_is_the_slowest_modal_decay() {
    let m = model(&["backlash_um=0", "stiffness_variation=0"]);
    let slowest = m.modes.slowest_decay_rate(m.system.omega_ref_rad_s);
    let omega = 0.8;
    let mut o = LyapunovOptions::new(omega);
    o.transient_periods = 20;
    // The slowest mode must dominate the separation: many periods.
    o.periods = 3000;
    let l = largest_exponent(&m, &o, None).unwrap();
    assert!(
        (l.per_s + slowest).abs() < 0.05 * slowest,
        "{} 1/s vs the slowest modal decay {slowest} 1/s",
        l.per_s
    );
}

#[test]
fn stable_periodic_orbit_is_negative_and_chaos_is_positive() {
    let m = model(&[]);
    // Omega 0.3: period 1 (checked against HBM in hbm.rs); Omega 1.3: no period.
    let periodic = largest_exponent(&m, &LyapunovOptions::new(0.3), None).unwrap();
    assert!(periodic.per_period < -1e-3, "{}", periodic.per_period);
    let mut so = SteadyOptions::new(1.3);
    so.transient_periods = 300;
    so.record_periods = 100;
    assert_eq!(steady_state(&m, &so, None).unwrap().period, None);
    let chaotic = largest_exponent(&m, &LyapunovOptions::new(1.3), None).unwrap();
    assert!(chaotic.per_period > 0.01, "{}", chaotic.per_period);
}

#[test]
fn bad_options_name_the_option() {
    let m = model(&[]);
    let mut o = LyapunovOptions::new(0.5);
    o.periods = 0;
    let e = largest_exponent(&m, &o, None).unwrap_err().to_string();
    assert!(e.contains("periods"), "{e}");
    let mut o = LyapunovOptions::new(f64::NAN);
    o.periods = 10;
    let e = largest_exponent(&m, &o, None).unwrap_err().to_string();
    assert!(e.contains("omega"), "{e}");
}
