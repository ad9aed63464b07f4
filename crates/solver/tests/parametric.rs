//! Parametric instability of the engaged system against the Mathieu
//! equation's known growth rates, the exact decay of a constant-stiffness
//! oscillator, and time integration of the compound set.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use solver::parametric::Parametric;
use solver::steady::{steady_state, Model, SteadyOptions};
use solver::SolverError;
use std::f64::consts::PI;
use test_support::models::model;

fn gear_pair(variation: f64, zeta: f64) -> Model {
    model(&[
        "model=gear-pair",
        "backlash_um=50",
        &format!("stiffness_variation={variation}"),
        &format!("damping_ratio={zeta}"),
    ])
}

/// The gear pair with all teeth engaged is `x'' + 2 z x' + (1 + v cos(Omega
/// t)) x = f` in units of its natural frequency. At the principal resonance
/// `Omega = 2` averaging gives the growth rate `v / 4 - z` per unit time
/// (error O(v^2)), so per mesh period (`pi`) `ln rho = pi (v / 4 - z)`.
#[test]
fn principal_resonance_grows_at_the_mathieu_rate() {
    for (v, z) in [(0.1, 0.0), (0.1, 0.01), (0.2, 0.02)] {
        let s = Parametric::new(&gear_pair(v, z)).unwrap().at(2.0).unwrap();
        let want = PI * (v / 4.0 - z);
        let got = s.growth_per_period();
        assert!(
            (got - want).abs() < 0.05 * want + 0.2 * v * v,
            "v = {v}, z = {z}: ln rho = {got}, Mathieu {want}"
        );
        assert!(s.unstable());
    }
    // Past the damping threshold z = v / 4 it is stable.
    assert!(!Parametric::new(&gear_pair(0.2, 0.06))
        .unwrap()
        .at(2.0)
        .unwrap()
        .unstable());
}

/// Without stiffness variation the engaged system is a damped oscillator
/// with constant coefficients: every multiplier has modulus `exp(-z T)` with
/// `T = 2 pi / Omega` exactly, whatever Omega (here to the RK4 monodromy's
/// 1e-4).
#[test]
fn constant_stiffness_decays_at_the_damping_rate() {
    let p = Parametric::new(&gear_pair(0.0, 0.03)).unwrap();
    for omega in [0.3, 1.0, 2.0, 3.7] {
        let s = p.at(omega).unwrap();
        let want = (-0.03 * 2.0 * PI / omega).exp();
        assert!(
            (s.growth_per_period() / want.ln() - 1.0).abs() < 1e-4,
            "Omega {omega}: rho {} against {want}",
            s.spectral_radius
        );
    }
}

/// The compound set without backlash is exactly its engaged system: the
/// steady state grows without bound where the spectral radius exceeds 1
/// (the deflection leaves its bound, or the periodic response's
/// multiplier equals that radius) and stays bounded where it is below.
#[test]
fn compound_set_time_integration_agrees_with_the_multipliers() {
    let m = model(&["backlash_um=0"]);
    let p = Parametric::new(&m).unwrap();
    for omega in [1.1, 1.3] {
        let s = p.at(omega).unwrap();
        let mut opts = SteadyOptions::new(omega);
        opts.early_settle = false;
        let run = steady_state(&m, &opts, None);
        match run {
            Err(SolverError::Diverged { .. }) => assert!(
                s.spectral_radius > 1.0,
                "Omega {omega}: diverged with rho {}",
                s.spectral_radius
            ),
            // Shooting's periodic response, unstable: its multiplier is
            // the engaged system's spectral radius (the same linear map).
            Err(SolverError::ParametricallyUnstable { modulus, .. }) => assert!(
                s.spectral_radius > 1.0 && (modulus / s.spectral_radius - 1.0).abs() < 1e-3,
                "Omega {omega}: multiplier {modulus} against rho {}",
                s.spectral_radius
            ),
            Ok(_) => assert!(
                s.spectral_radius < 1.0,
                "Omega {omega}: bounded with rho {}",
                s.spectral_radius
            ),
            Err(e) => panic!("Omega {omega}: {e}"),
        }
    }
    assert!(
        p.at(1.1).unwrap().unstable(),
        "the test needs an unstable case"
    );
    assert!(!p.at(1.3).unwrap().unstable(), "and a stable one");
}

#[test]
fn omega_out_of_range_is_refused() {
    let p = Parametric::new(&model(&[])).unwrap();
    for bad in [0.0, -1.0, f64::NAN, 25.0] {
        assert!(matches!(p.at(bad), Err(SolverError::BadOption { .. })));
    }
}

/// The first Mathieu tongue of `x'' + (1 + v cos(Omega t)) x = 0`: with
/// `tau = Omega t / 2` it reads `x'' + (delta + 2 eps cos 2 tau) x = 0`,
/// `delta = 4 / Omega^2`, `eps = 2 v / Omega^2`, unstable for
/// `1 - eps < delta < 1 + eps` (to O(eps^2)), so between
/// `Omega = sqrt(4 - 2 v)` and `sqrt(4 + 2 v)`: the one band of the scan.
#[test]
fn the_unstable_band_is_the_first_mathieu_tongue() {
    let v = 0.1;
    let p = Parametric::new(&gear_pair(v, 0.0)).unwrap();
    let bands = p.unstable_bands((1.7, 2.3), 121).unwrap();
    assert_eq!(bands.len(), 1, "{bands:?}");
    let (lo, hi) = bands[0];
    let (want_lo, want_hi) = ((4.0 - 2.0 * v).sqrt(), (4.0 + 2.0 * v).sqrt());
    assert!((lo - want_lo).abs() < 0.01, "{lo} vs {want_lo}");
    assert!((hi - want_hi).abs() < 0.01, "{hi} vs {want_hi}");
}

/// Band edges interpolate `ln rho` linearly between the straddling samples;
/// a band open at either end of the scan runs to that end.
#[test]
fn band_edges_interpolate_the_growth() {
    use solver::parametric::unstable_bands;
    let pts = [(1.0, -1.0), (2.0, 1.0), (3.0, 3.0), (4.0, -1.0), (5.0, 2.0)];
    assert_eq!(
        unstable_bands(&pts, 5.5),
        vec![(1.5, 3.75), (4.0 + 1.0 / 3.0, 5.5)]
    );
    assert_eq!(
        unstable_bands(&[(1.0, 0.5), (2.0, -0.5)], 2.0),
        vec![(1.0, 1.5)]
    );
    assert!(unstable_bands(&[(1.0, -0.5), (2.0, -0.5)], 2.0).is_empty());
}
