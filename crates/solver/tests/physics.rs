//! Physics invariants of the compound planetary model, each derived
//! independently of the code under test: kinematics from tooth counts,
//! equilibrium by hand, symmetry of the planets, energy conservation and
//! the closed-form linear response.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use solver::dynamics::MeshOde;
use solver::keys::{self, Value};
use solver::modal::{self, ModeKind};
use solver::ode::{Dopri5, Ode, Tolerances};
use solver::params::ModelParams;
use solver::steady::{steady_state, Model, SteadyOptions};
use solver::system::{dead_zone, MeshSystem};
use std::f64::consts::PI;

fn params(assignments: &[&str]) -> ModelParams {
    let mut p = ModelParams::default();
    for a in assignments {
        keys::set_assignment(&mut p, a).expect(a);
    }
    p
}

fn model(assignments: &[&str]) -> Model {
    Model::new(&params(assignments)).expect("model")
}

#[test]
fn rigid_body_mode_has_the_tooth_count_speed_ratios() {
    let m = model(&[]);
    // The eigen-solver's zero-frequency mode, not the kinematic one.
    let rigid: Vec<_> = m
        .modes
        .modes
        .iter()
        .filter(|x| x.kind == ModeKind::RigidBody)
        .collect();
    assert_eq!(rigid.len(), 1);
    let phi = &rigid[0].shape;
    let c = phi[2];
    // omega_s1/omega_c = 1 - z_r/z_s1 = -4/3, omega_s2/omega_c = 1 + z_r/z_s2 = 2.75.
    assert!(
        (phi[0] / c + 4.0 / 3.0).abs() < 1e-9,
        "s1/c = {}",
        phi[0] / c
    );
    assert!((phi[1] / c - 2.75).abs() < 1e-9, "s2/c = {}", phi[1] / c);
    assert!(phi[3].abs() < 1e-9 * c.abs(), "the ring is held");
    // Planets relative to the carrier: z_r/z_a = 4 and -z_r/z_b = -14/3.
    for n in 0..3 {
        assert!((phi[4 + n] / c - 4.0).abs() < 1e-9);
        assert!((phi[7 + n] / c + 14.0 / 3.0).abs() < 1e-9);
    }
    assert_eq!(
        m.modes.modes[0].frequency_hz, 0.0,
        "rigid mode reported as 0 Hz"
    );
    // No mesh deflection depends on the kinematic rigid mode.
    for mesh in &m.system.meshes {
        assert!(
            mesh.dot(&m.system.rigid_mode).abs() < 1e-12,
            "{}",
            mesh.name
        );
    }
}

#[test]
fn balancing_torque_is_969_697_n_m() {
    let m = model(&[]);
    assert!((m.system.balancing_torque_nm - 969.697).abs() < 1e-3);
    // Independently: 2000 * (84/36 - 1) / (1 + 84/48).
    let expected = 2000.0 * (84.0 / 36.0 - 1.0) / (1.0 + 84.0 / 48.0);
    assert!((m.system.balancing_torque_nm - expected).abs() < 1e-9);
    // A visibly unbalanced torque is refused with the balancing value named.
    let err = Model::new(&params(&["torque_s2_nm=900"])).expect_err("unbalanced");
    assert!(err.to_string().contains("969.697"), "{err}");
    // The seed's printed value is accepted (round-off, projected out).
    Model::new(&params(&["torque_s2_nm=969.69"])).expect("seed value accepted");
}

#[test]
fn reference_scales_match_model_md() {
    let m = model(&[]);
    let s1a1 = &m.system.meshes[0];
    assert!((s1a1.equivalent_mass_kg - 0.8616).abs() < 1e-4);
    assert!((m.system.omega_ref_rad_s - 34_068.0).abs() < 1.0);
    assert!((m.system.mesh_freq_hz(1.0) - 5_422.0).abs() < 1.0);
}

#[test]
fn planet_modes_have_multiplicity_n_minus_1() {
    for n in 3..=6u32 {
        let m = model(&[&format!("planets={n}")]);
        let modes = &m.modes.modes;
        assert_eq!(modes.len(), 4 + 2 * n as usize);
        let rotational: Vec<_> = modes
            .iter()
            .filter(|x| x.kind == ModeKind::Rotational)
            .collect();
        let planet: Vec<_> = modes
            .iter()
            .filter(|x| x.kind == ModeKind::Planet)
            .collect();
        // Rotational: s1, s2, c, r and one shape per planet kind, less the rigid mode.
        assert_eq!(rotational.len(), 5, "N = {n}");
        assert!(rotational.iter().all(|x| x.multiplicity == 1), "N = {n}");
        // Planet modes: two distinct frequencies, each N - 1 times.
        assert_eq!(planet.len(), 2 * (n as usize - 1), "N = {n}");
        for p in &planet {
            assert_eq!(
                p.multiplicity,
                n as usize - 1,
                "N = {n}, f = {}",
                p.frequency_hz
            );
            // Central members stand still in a planet mode.
            assert!(p.shape[..4].iter().all(|v| v.abs() < 1e-8), "N = {n}");
        }
    }
}

#[test]
fn static_mesh_forces_balance_the_loads() {
    let m = model(&[]);
    let sys = &m.system;
    // By hand: the sun torques are shared by N = 3 planets; the a-b mesh carries
    // the s1-a force through planet a; the carrier balances the ring force.
    let (rho_s1, rho_s2, rho_r) = (
        sys.meshes[0].w[0].1,
        sys.meshes[3].w[0].1,
        sys.meshes[9].w[0].1,
    );
    let f_s1a = 2000.0 / (3.0 * rho_s1);
    let f_s2b = sys.balancing_torque_nm / (3.0 * rho_s2);
    let f_rb = (2000.0 + sys.balancing_torque_nm) / (3.0 * rho_r);
    for (j, mesh) in sys.meshes.iter().enumerate() {
        let expected = match &mesh.name[..2] {
            "s1" | "a1" | "a2" | "a3" => f_s1a,
            "s2" => f_s2b,
            _ => f_rb,
        };
        let f = m.statics.mesh_force_n[j];
        assert!(
            (f - expected).abs() < 1e-6 * expected,
            "{}: {f} vs {expected}",
            mesh.name
        );
        assert_eq!(m.statics.contact[j].name(), "drive");
    }
    // Generalized equilibrium: sum_j w_j F_j + K_sup q = tau.
    let mut residual = sys.load_nm.clone();
    for (j, mesh) in sys.meshes.iter().enumerate() {
        for &(i, wi) in &mesh.w {
            residual[i] -= wi * m.statics.mesh_force_n[j];
        }
    }
    let ring = sys.support.vals[0] * m.statics.q[3];
    residual[3] -= ring;
    assert!(residual.iter().all(|r| r.abs() < 1e-6), "{residual:?}");
}

/// Total mechanical energy of a conservative system (xi = 0, v = 0, no TE).
fn energy(sys: &MeshSystem, y: &[f64]) -> f64 {
    let n = sys.dof();
    let (q, v) = y.split_at(n);
    let mut e = 0.0;
    for i in 0..n {
        for k in 0..n {
            e += 0.5 * v[i] * sys.mass[(i, k)] * v[k];
        }
        e -= sys.load_nm[i] * q[i];
    }
    for mesh in &sys.meshes {
        let x = mesh.dot(q) - mesh.te_mean_m;
        let g = dead_zone(x, mesh.backlash_m);
        e += 0.5 * mesh.stiffness_mean_n_m * g * g;
    }
    e + 0.5 * sys.support.vals[0] * q[3] * q[3]
}

fn energy_drift(assignments: &[&str], rtol: f64) -> f64 {
    let m = model(assignments);
    let sys = &m.system;
    let omega = 0.7 * sys.omega_ref_rad_s;
    let mut ode = MeshOde::new(sys, omega);
    // Start off equilibrium: kick every coordinate's velocity (a vibration of
    // some ten micrometres), without a rigid-body component, which would make
    // the whole train turn away and the absolute angles grow.
    let mut y0 = m.static_state();
    let n = sys.dof();
    let mut kick: Vec<f64> = (0..n).map(|i| 2.0 * ((i as f64) * 1.7).sin()).collect();
    let u = &sys.rigid_mode;
    let mu: Vec<f64> = (0..n)
        .map(|i| (0..n).map(|k| sys.mass[(i, k)] * u[k]).sum())
        .collect();
    let along = kick.iter().zip(&mu).map(|(a, b)| a * b).sum::<f64>()
        / u.iter().zip(&mu).map(|(a, b)| a * b).sum::<f64>();
    for (k, ui) in kick.iter_mut().zip(u) {
        *k -= along * ui;
    }
    y0[n..].copy_from_slice(&kick);
    let lengths = sys.dof_length_m();
    let mut atol: Vec<f64> = lengths.iter().map(|l| rtol * 1e-5 / l).collect();
    atol.extend(
        lengths
            .iter()
            .map(|l| rtol * 1e-5 / l * sys.omega_ref_rad_s),
    );
    let period = 2.0 * PI / omega;
    let tol = Tolerances {
        rtol,
        atol,
        h_min: 1e-16,
        h_max: period,
    };
    let mut int = Dopri5::new(&mut ode, 0.0, &y0, period / 100.0, tol);
    let e0 = energy(sys, &y0);
    let scale = {
        // Kinetic energy of the kick: the natural scale of energy errors.
        let mut k = 0.0;
        for i in 0..n {
            for j in 0..n {
                k += 0.5 * y0[n + i] * sys.mass[(i, j)] * y0[n + j];
            }
        }
        k
    };
    let mut worst: f64 = 0.0;
    while int.t() < 30.0 * period {
        int.step(&mut ode, 30.0 * period).expect("step");
        worst = worst.max((energy(sys, int.y()) - e0).abs() / scale);
    }
    assert!(int.stats.steps > 100);
    let _ = ode.dim();
    worst
}

/// No damping, no excitation (constant stiffness, no TE): energy is conserved.
const UNFORCED_UNDAMPED: [&str; 3] = ["damping_ratio=0", "stiffness_variation=0", "te_um=0"];

#[test]
fn undamped_linear_motion_conserves_energy() {
    let linear = [&UNFORCED_UNDAMPED[..], &["backlash_um=0"]].concat();
    // DOPRI5 is not symplectic: the energy error grows with the steps taken,
    // a few tolerances' worth per step, here over about 750 steps.
    let loose = energy_drift(&linear, 1e-7);
    let tight = energy_drift(&linear, 1e-10);
    assert!(tight < 1e3 * 1e-10, "relative energy drift {tight}");
    assert!(loose < 1e3 * 1e-7, "relative energy drift {loose}");
    assert!(
        tight < 1e-2 * loose,
        "drift shrinks with the tolerance: {tight} vs {loose}"
    );
}

#[test]
fn undamped_motion_with_backlash_conserves_energy_across_impacts() {
    // The dead-zone force is conservative too; this checks that contact
    // switches are crossed without an energy error (event location).
    let with_backlash = [&UNFORCED_UNDAMPED[..], &["backlash_um=5"]].concat();
    let drift = energy_drift(&with_backlash, 1e-10);
    assert!(drift < 1e3 * 1e-10, "relative energy drift {drift}");
}

/// Steady response with b = 0 and v = 0 against the complex receptance.
#[test]
fn linear_steady_response_equals_the_receptance() {
    let m = model(&["backlash_um=0", "stiffness_variation=0"]);
    for omega in [0.15, 0.4, 0.85, 1.3, 1.9] {
        let mut opts = SteadyOptions::new(omega);
        // Some transients are slow: the ring's support spring is undamped, so
        // the first mode (0.23 omega_ref) has a modal damping ratio of 0.0024
        // and loses only 0.35 % / Omega of its amplitude per mesh period.
        opts.transient_periods = 4000;
        opts.record_periods = 12;
        opts.rtol = 1e-10;
        opts.atol_m = 1e-14;
        let omega_rad_s = omega * m.system.omega_ref_rad_s;
        let amp = modal::linear_receptance(&m.system, omega_rad_s).expect("receptance");
        if omega < 1.0 {
            // Once the early-settle criterion fires, the residual transient is
            // within the settle tolerance.
            let early = steady_state(&m, &opts, None).expect("steady");
            assert!(
                early.stats.settled,
                "Omega {omega} settles within 4000 periods"
            );
            let span_um = amp.iter().map(|a| 2.0 * a.norm() * 1e6).fold(0.0, f64::max);
            let tol_um = solver::steady::settle_tol_um(span_um);
            for (j, r) in early.meshes.iter().enumerate() {
                let half_pp = 0.5 * (r.delta_max_m - r.delta_min_m);
                let err_um = (half_pp - amp[j].norm()).abs() * 1e6;
                assert!(
                    err_um <= tol_um,
                    "Omega {omega}, mesh {j}: {err_um} > {tol_um} um"
                );
            }
        }
        // Started on the exact periodic solution (no transient at all), the
        // integration must follow it to the integration tolerance.
        let q_hat = modal::linear_response(&m.system, omega_rad_s).expect("response");
        let n = m.system.dof();
        let mut y0 = m.static_state();
        for i in 0..n {
            y0[i] += q_hat[i].re;
            y0[n + i] = -omega_rad_s * q_hat[i].im;
        }
        opts.early_settle = false;
        opts.transient_periods = 0;
        opts.record_periods = 4;
        let ss = steady_state(&m, &opts, Some(&y0)).expect("steady");
        assert_eq!(
            ss.period,
            Some(1),
            "a linear response is period 1 at Omega = {omega}"
        );
        for (j, mesh) in m.system.meshes.iter().enumerate() {
            let r = &ss.meshes[j];
            let half_pp = 0.5 * (r.delta_max_m - r.delta_min_m);
            let mid = 0.5 * (r.delta_max_m + r.delta_min_m);
            let exact = amp[j].norm();
            let stat = m.statics.mesh_deflection_m[j];
            assert!(
                (half_pp - exact).abs() < 1e-7 * exact + 1e-14,
                "Omega {omega} {}: amplitude {half_pp:e} vs receptance {exact:e}",
                mesh.name
            );
            assert!(
                (mid - stat).abs() < 1e-7 * exact + 1e-14,
                "mean of {}",
                mesh.name
            );
        }
    }
}

#[test]
fn in_phase_planets_respond_identically() {
    let m = model(&["backlash_um=200", "te_um=30"]);
    let mut opts = SteadyOptions::new(1.2);
    opts.transient_periods = 60;
    opts.record_periods = 10;
    opts.early_settle = false;
    let ss = steady_state(&m, &opts, None).expect("steady");
    for kind in 0..4 {
        let a = &ss.meshes[3 * kind];
        for p in 1..3 {
            let b = &ss.meshes[3 * kind + p];
            for (x, y) in a.poincare_delta_m.iter().zip(&b.poincare_delta_m) {
                assert!((x - y).abs() < 1e-9, "{x} vs {y}");
            }
        }
    }
}

#[test]
fn sequential_phasing_differs_only_where_tooth_counts_require() {
    // z_s1 psi_n is a whole number of turns for N = 3 (36/3 = 12), not for N = 5.
    for (n, differs) in [(3, false), (5, true)] {
        let seq = MeshSystem::build(&params(&[&format!("planets={n}"), "phasing=sequential"]))
            .expect("build");
        let phases: Vec<f64> = seq.meshes.iter().map(|m| m.phase_rad).collect();
        let any = phases.iter().any(|&g| g.sin().abs() > 1e-9);
        assert_eq!(any, differs, "N = {n}: phases {phases:?}");
    }
    // For N = 5 the s1a phases step by 2 pi * 36 / 5 = 0.2 turn.
    let seq = MeshSystem::build(&params(&["planets=5", "phasing=sequential"])).expect("build");
    let step = seq.meshes[1].phase_rad - seq.meshes[0].phase_rad;
    assert!(
        (step.rem_euclid(2.0 * PI) - 0.4 * PI).abs() < 1e-9,
        "{step}"
    );
}

#[test]
fn validation_names_the_key_value_and_range() {
    let cases = [
        ("backlash_um=-1", "backlash_um"),
        ("damping_ratio=nan", "damping_ratio"),
        ("planets=7", "planets"),
        ("teeth_r=85", "teeth_r"),
        ("inertia_s1_kg_m2=0", "inertia_s1_kg_m2"),
        ("te_um=inf", "te_um"),
    ];
    for (a, key) in cases {
        let mut p = ModelParams::default();
        let err = keys::set_assignment(&mut p, a).and_then(|_| Model::new(&p).map(|_| ()));
        let msg = err.expect_err(a).to_string();
        assert!(msg.contains(key), "{a}: {msg}");
    }
    // Odd (teeth_r - teeth_s2) is refused with both counts named.
    let mut p = ModelParams::default();
    keys::set(&mut p, "teeth_r", Value::Num(85.0)).expect("in range");
    let msg = Model::new(&p).expect_err("odd").to_string();
    assert!(msg.contains("85") && msg.contains("48"), "{msg}");
}

/// Planet phasing: with five planets spaced evenly and sequential phasing
/// the mesh phases are `gamma_n = 2 pi n z / 5`, so order `k` survives the
/// sum over the planets only when `k z / 5` is whole; z_s1 = 36, z_s2 = 48,
/// z_r = 84 are not multiples of 5, so only k = 5 survives (Parker & Lin
/// 2004). In phase (or with three planets, where `z / 3` is whole for these
/// tooth counts) every order survives in full.
#[test]
fn sequential_phasing_of_five_planets_cancels_orders_one_to_four() {
    use solver::params::MeshKind;
    let kinds = [MeshKind::S1A, MeshKind::S2B, MeshKind::AB, MeshKind::RB];
    let m = model(&["planets=5", "phasing=sequential"]);
    for kind in kinds {
        assert_eq!(
            m.system.phasing_factors(kind, 6),
            vec![0.0, 0.0, 0.0, 0.0, 1.0, 0.0],
            "{kind:?}"
        );
    }
    for q in [
        ["planets=5", "phasing=in-phase"],
        ["planets=3", "phasing=sequential"],
    ] {
        let m = model(&q);
        for kind in kinds {
            assert_eq!(m.system.phasing_factors(kind, 6), vec![1.0; 6], "{q:?}");
        }
    }
    let pair = model(&["model=gear-pair"]);
    assert!(pair.system.phasing_factors(MeshKind::S1A, 6).is_empty());
}

/// The worst mesh of a steady state is the one with the largest dynamic
/// factor, as the sweep reports it.
#[test]
fn the_worst_mesh_has_the_largest_dynamic_factor() {
    let m = model(&["backlash_um=50"]);
    let mut o = SteadyOptions::new(1.05);
    o.transient_periods = 40;
    o.record_periods = 10;
    let ss = steady_state(&m, &o, None).unwrap();
    let j = ss.worst_mesh();
    let df = |k: usize| ss.meshes[k].dynamic_factor.unwrap_or(0.0);
    assert!(df(j) > 0.0);
    assert!((0..ss.meshes.len()).all(|k| df(k) <= df(j)));
}
