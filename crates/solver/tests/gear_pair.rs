//! The single gear pair (Kahraman & Singh, 1990): its linear limit against
//! the closed-form one-degree-of-freedom receptance and its impact regimes.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use nalgebra::Complex;
use solver::keys;
use solver::params::ModelParams;
use solver::steady::{steady_state, Impact, Model, SteadyOptions};
use test_support::models::strict_run;

fn pair(assignments: &[&str]) -> Model {
    let mut p = ModelParams::default();
    keys::set_assignment(&mut p, "model=gear-pair").expect("model");
    for a in assignments {
        keys::set_assignment(&mut p, a).expect(a);
    }
    Model::new(&p).expect("model")
}

#[test]
fn linear_limit_is_the_single_degree_of_freedom_receptance() {
    let m = pair(&["backlash_um=0", "stiffness_variation=0", "te_um=20"]);
    let mesh = &m.system.meshes[0];
    let (k, c, me) = (
        mesh.stiffness_mean_n_m,
        mesh.damping_n_s_m,
        mesh.equivalent_mass_kg,
    );
    for omega in [0.3, 0.8, 1.0, 1.2, 2.5] {
        let w = omega * m.system.omega_ref_rad_s;
        // m x'' + c (x' - e') + k (x - e) = F, e = E sin(wt): |x_hat| = |k + i w c| E / |k - w^2 m + i w c|.
        let amp =
            Complex::new(k, w * c).norm() * 20e-6 / Complex::new(k - w * w * me, w * c).norm();
        let opts = strict_run(omega, (600, 10), (1e-10, 1e-15));
        let ss = steady_state(&m, &opts, None).expect("run");
        let r = &ss.meshes[0];
        let half_pp = 0.5 * (r.delta_max_m - r.delta_min_m);
        assert!(
            (half_pp - amp).abs() < 1e-6 * amp,
            "Omega {omega}: {half_pp} vs {amp}"
        );
        assert_eq!(ss.period, Some(1));
        // omega_ref of the pair is its own natural frequency: resonance at Omega = 1.
        assert!((m.system.omega_ref_rad_s - (k / me).sqrt()).abs() < 1e-9 * (k / me).sqrt());
    }
}

#[test]
fn impacts_go_from_none_to_single_to_double_sided_as_te_grows() {
    // Near resonance (Omega = 0.9), as in Kahraman & Singh's Fig. 7 sequence.
    let expected = [
        (0.5, Impact::None),
        (3.0, Impact::SingleSided),
        (10.0, Impact::SingleSided),
        (40.0, Impact::DoubleSided),
    ];
    for (te, impact) in expected {
        let m = pair(&[&format!("te_um={te}")]);
        let ss = steady_state(&m, &SteadyOptions::new(0.9), None).expect("run");
        let r = &ss.meshes[0];
        assert_eq!(
            r.impact,
            impact,
            "TE {te} um: x in [{}, {}] um",
            r.rel_min_m * 1e6,
            r.rel_max_m * 1e6
        );
        // The classification agrees with the relative displacement's range.
        let b = m.system.meshes[0].backlash_m;
        match impact {
            Impact::None => assert!(r.rel_min_m > b),
            Impact::SingleSided => assert!(r.rel_min_m <= b && r.rel_min_m >= -b),
            Impact::DoubleSided => assert!(r.rel_min_m < -b),
            Impact::NoContact | Impact::NoGap => unreachable!(),
        }
    }
}

#[test]
fn teeth_that_separate_carry_no_stiffness_force() {
    // Single-sided impacts: while apart, the force is the damper's alone, so
    // its minimum is far below the static load and may be negative.
    let m = pair(&["te_um=10"]);
    let ss = steady_state(&m, &SteadyOptions::new(0.9), None).expect("run");
    let r = &ss.meshes[0];
    assert_eq!(r.impact, Impact::SingleSided);
    assert!(r.contact_fraction[1] > 0.0 && r.contact_fraction[2] == 0.0);
    assert!(r.force_min_n < 0.2 * r.static_force_n);
    assert!(r.dynamic_factor.expect("loaded") > 1.5);
}

/// The principal parametric resonance of the Mathieu equation
/// `x'' + 2 z x' + (1 + v cos(Omega t)) x = f(t)` at `Omega = 2`: to first
/// order in `v` the motion grows without bound when `v / 4 > z` (growth rate
/// `v / 4 - z` per unit of dimensionless time) and stays bounded otherwise.
/// Without backlash the gear pair is exactly that equation, so the steady
/// state reports the growth (`ParametricallyUnstable` or `Diverged`) on one
/// side of the boundary and a
/// bounded period-1 response on the other, never a "response" of metres.
#[test]
fn principal_parametric_resonance_is_reported_as_unbounded_growth() {
    let run = |zeta: f64| {
        let m = pair(&[
            "backlash_um=0",
            "te_um=0",
            "stiffness_variation=0.3",
            &format!("damping_ratio={zeta}"),
        ]);
        let mut opts = SteadyOptions::new(2.0);
        opts.early_settle = false;
        steady_state(&m, &opts, None)
    };
    // v / 4 = 0.075 against z = 0.05: growth e^(0.025 pi) = 1.08 per
    // period to first order, some 1e13 over the 400 periods. The run says
    // so from the periodic response's multiplier (the system is linear), or
    // from the deflection leaving its bound.
    match run(0.05) {
        Err(solver::error::SolverError::ParametricallyUnstable { modulus, .. }) => {
            let first_order = (0.025 * std::f64::consts::PI).exp();
            assert!(
                (modulus - first_order).abs() < 0.05,
                "{modulus} vs {first_order}"
            );
        }
        Err(solver::error::SolverError::Diverged {
            delta_m, bound_m, ..
        }) => {
            assert!(delta_m.abs() > bound_m, "{delta_m} {bound_m}");
        }
        other => panic!("expected unbounded growth, got {other:?}"),
    }
    // z = 0.1: outside the tongue, a bounded period-1 response near the
    // static deflection.
    let ss = run(0.1).expect("bounded");
    assert_eq!(ss.period, Some(1));
    let mesh = &ss.meshes[0];
    assert!(mesh.delta_max_m < 3.0 * mesh.delta_mean_m, "{mesh:?}");
}
