//! Shooting against independent facts: the closed-form linear response,
//! the closed-form multipliers of a damped oscillator, finite differences
//! of the map, and a long run.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use super::variational::MapRun;
use super::*;
use crate::keys;
use crate::modal::linear_receptance;
use crate::params::ModelParams;
use crate::steady::{steady_state, SteadyOptions};
use nalgebra::Complex;

pub(crate) fn model(sets: &[&str]) -> Model {
    let mut p = ModelParams::default();
    for s in sets {
        keys::set_assignment(&mut p, s).unwrap();
    }
    Model::new(&p).unwrap()
}

fn converged(out: ShootOutcome) -> Orbit {
    match out {
        ShootOutcome::Converged(o) => *o,
        ShootOutcome::Failed(f) => panic!("shooting failed: {f:?}"),
    }
}

/// Each mesh's deflection and rate of full state `y` at phase 0.
fn mesh_state(model: &Model, y: &[f64]) -> Vec<(f64, f64)> {
    let n = model.system.dof();
    model
        .system
        .meshes
        .iter()
        .map(|m| (m.dot(&y[..n]), m.dot(&y[n..])))
        .collect()
}

/// With no backlash and a constant stiffness the compound set is linear and
/// time-invariant: its periodic response is the closed form
/// `delta_j = static_j + Re(A_j e^{i omega t})`, and Newton reaches it in
/// one step from the static equilibrium.
#[test]
fn linear_orbit_is_the_closed_form_after_one_newton_step() {
    let m = model(&[
        "backlash_um=0",
        "stiffness_variation=0",
        "te_meshes=all",
        "te_um=5",
    ]);
    // The integrator 10 times tighter than the default: the orbit's error
    // is the map's integration error amplified by 1 / |1 - mu| (the slow
    // first mode's multiplier is near 1), and 1e-8 is asked of it.
    let mut opts = ShootOptions::new(1);
    opts.rtol = 1e-12;
    opts.atol_m = 1e-15;
    for omega in [0.5, 0.84, 1.3] {
        let orbit = converged(shoot(&m, omega, &m.static_state(), &opts).unwrap());
        assert_eq!(orbit.iterations, 1, "Omega {omega}");
        let w = omega * m.system.omega_ref_rad_s;
        let amp = linear_receptance(&m.system, w).unwrap();
        let got = mesh_state(&m, &orbit.start_state);
        let scale = m
            .statics
            .mesh_deflection_m
            .iter()
            .zip(&amp)
            .map(|(s, a)| s.abs() + a.norm())
            .fold(0.0, f64::max);
        for (j, ((d, v), a)) in got.iter().zip(&amp).enumerate() {
            let d_exact = m.statics.mesh_deflection_m[j] + a.re;
            let v_exact = (Complex::new(0.0, w) * a).re;
            assert!(
                (d - d_exact).abs() <= 1e-8 * scale,
                "Omega {omega} mesh {j}: {d:e} vs {d_exact:e}"
            );
            assert!(
                (v - v_exact).abs() <= 1e-8 * scale * w,
                "Omega {omega} mesh {j}: rate {v:e} vs {v_exact:e}"
            );
        }
        assert!(orbit.is_stable());
    }
}

/// A single gear pair without backlash or stiffness fluctuation is a damped
/// linear oscillator in its relative coordinate: its two multipliers over a
/// period T are `exp((-zeta w_n +- i w_d) T)`.
#[test]
fn oscillator_multipliers_are_the_closed_form() {
    for zeta in [0.02_f64, 0.1] {
        let m = model(&[
            "model=gear-pair",
            "backlash_um=0",
            "stiffness_variation=0",
            &format!("damping_ratio={zeta}"),
        ]);
        let wn = m.system.omega_ref_rad_s;
        for omega in [0.7, 1.9] {
            let orbit =
                converged(shoot(&m, omega, &m.static_state(), &ShootOptions::new(1)).unwrap());
            let t = 2.0 * std::f64::consts::PI / (omega * wn);
            let wd = wn * (1.0 - zeta * zeta).sqrt();
            let exact = Complex::new(-zeta * wn * t, wd * t).exp();
            let mults = orbit.multipliers.unwrap().values;
            assert_eq!(mults.len(), 2);
            for mu in &mults {
                let target = if mu.im * exact.im >= 0.0 {
                    exact
                } else {
                    exact.conj()
                };
                assert!(
                    (mu - target).norm() <= 1e-7 * target.norm(),
                    "zeta {zeta}, Omega {omega}: {mu} vs {target}"
                );
            }
        }
    }
}

/// The monodromy of the variational equations is the derivative of the map:
/// central finite differences of `P^2` agree with it, with backlash and
/// double-sided impacts on the way.
#[test]
fn monodromy_matches_finite_differences_of_the_map() {
    for (sets, omega) in [
        (vec!["model=gear-pair", "backlash_um=20", "te_um=30"], 1.1),
        (vec!["te_um=40", "backlash_um=40"], 1.3),
    ] {
        let m = model(&sets);
        let mut so = SteadyOptions::new(omega);
        so.transient_periods = 40;
        so.record_periods = 1;
        so.early_settle = false;
        let y0 = steady_state(&m, &so, None).unwrap().end_state;
        let red = Reduced::new(&m, omega);
        let ode = crate::dynamics::MeshOde::new(&m.system, red.omega_rad_s);
        let tol = crate::dynamics::tolerances(&m.system, omega, 1e-12, 1e-16, red.period_s, 1e-14);
        let (z0, rigid) = red.from_state(&y0);
        let eval = |z: &[f64], mono: bool| {
            let mut run = MapRun::new(&red, &ode, &tol, z, rigid, 2, mono, 1.0, 1.0, u64::MAX);
            let mut taken = 0;
            run.advance(&red, u64::MAX, &mut taken).unwrap().unwrap()
        };
        let mono = eval(&z0, true).monodromy.unwrap();
        let h = 1e-4;
        let mut worst: f64 = 0.0;
        for c in 0..red.dim() {
            let mut zp = z0.clone();
            let mut zm = z0.clone();
            zp[c] += h;
            zm[c] -= h;
            let (p, q) = (eval(&zp, false).z, eval(&zm, false).z);
            for r in 0..red.dim() {
                let fd = (p[r] - q[r]) / (2.0 * h);
                worst = worst.max((fd - mono[(r, c)]).abs());
            }
        }
        let scale = mono.amax();
        assert!(
            worst <= 1e-5 * scale,
            "{sets:?}: worst difference {worst:e} of {scale:e}"
        );
    }
}

/// Fig. 2's settings (no backlash, 5 µm TE on every mesh, Omega 0.84) are a
/// linear periodic system: shooting finds the period-1 orbit in one step,
/// stable, with the slow first mode (damping ratio 0.0024) showing as a
/// multiplier just inside the unit circle; a plain run started on the
/// orbit stays on it.
#[test]
fn fig2_settings_give_a_stable_period_one_orbit_in_one_step() {
    let m = model(&["backlash_um=0", "te_meshes=all", "te_um=5"]);
    let omega = 0.84;
    let orbit = converged(shoot(&m, omega, &m.static_state(), &ShootOptions::new(1)).unwrap());
    assert_eq!(orbit.iterations, 1);
    assert!(orbit.is_stable());
    let rho = orbit.max_multiplier_modulus();
    assert!(rho > 0.9 && rho < 1.0, "largest multiplier {rho}");
    let mut so = SteadyOptions::new(omega);
    so.transient_periods = 0;
    so.record_periods = 20;
    so.rtol = 1e-12;
    so.atol_m = 1e-15;
    let ss = steady_state(&m, &so, Some(&orbit.start_state)).unwrap();
    let start = mesh_state(&m, &orbit.start_state);
    for (j, ms) in ss.meshes.iter().enumerate() {
        let scale = ms.delta_max_m.abs().max(ms.delta_min_m.abs());
        for d in &ms.poincare_delta_m {
            assert!(
                (d - start[j].0).abs() <= 1e-8 * scale,
                "mesh {j}: {d:e} vs {:e}",
                start[j].0
            );
        }
    }
}

/// With a time-varying stiffness and no backlash the gear pair is linear
/// and periodic; a long run from the static state (3000 periods, the
/// transient dead by a factor below 1e-15) ends on the shooting orbit.
#[test]
fn linear_time_varying_orbit_equals_a_long_run() {
    let m = model(&[
        "model=gear-pair",
        "backlash_um=0",
        "stiffness_variation=0.3",
    ]);
    let omega = 1.5;
    let orbit = converged(shoot(&m, omega, &m.static_state(), &ShootOptions::new(1)).unwrap());
    assert_eq!(orbit.iterations, 1);
    let mut so = SteadyOptions::new(omega);
    so.transient_periods = 3000;
    so.early_settle = false;
    so.record_periods = 1;
    so.rtol = 1e-11;
    so.atol_m = 1e-15;
    let ss = steady_state(&m, &so, None).unwrap();
    let (a, b) = (
        mesh_state(&m, &orbit.start_state),
        mesh_state(&m, &ss.end_state),
    );
    let w = omega * m.system.omega_ref_rad_s;
    let scale = a[0].0.abs().max(a[0].1.abs() / w);
    assert!((a[0].0 - b[0].0).abs() <= 1e-8 * scale, "{a:?} vs {b:?}");
    assert!(
        (a[0].1 - b[0].1).abs() / w <= 1e-8 * scale,
        "{a:?} vs {b:?}"
    );
}

/// Paused and resumed at every step, an attempt computes the same bits.
#[test]
fn slices_compute_the_same_orbit() {
    let m = model(&["model=gear-pair", "backlash_um=20", "te_um=30"]);
    let opts = ShootOptions::new(1);
    let one = shoot(&m, 0.6, &m.static_state(), &opts).unwrap();
    let mut run = ShootRun::new(&m, 0.6, &m.static_state(), &opts).unwrap();
    let sliced = loop {
        if let Some(out) = run.advance(7).unwrap() {
            break out;
        }
    };
    assert_eq!(one, sliced);
}

/// A period beyond the largest is refused, naming the allowed range.
#[test]
fn a_period_above_the_maximum_is_refused() {
    let m = model(&["model=gear-pair"]);
    let e = ShootRun::new(
        &m,
        1.0,
        &m.static_state(),
        &ShootOptions::new(MAX_SHOOT_PERIOD + 1),
    )
    .unwrap_err();
    assert!(
        e.to_string().contains(&format!("1 ..= {MAX_SHOOT_PERIOD}")),
        "{e}"
    );
}

/// Broyden's updates change the path, not the destination: on a gear pair
/// with backlash and impacts, the attempt with the updated Newton matrix
/// (and a looser integration of the matrix that only steers it) ends on the
/// orbit plain Newton finds, with the multipliers of the monodromy
/// integrated at that orbit.
#[test]
fn broyden_updates_find_the_plain_newton_orbit() {
    let m = model(&["model=gear-pair", "backlash_um=20", "te_um=30"]);
    for (omega, period) in [(0.6, 1), (1.1, 1), (1.1, 2)] {
        let mut so = SteadyOptions::new(omega);
        so.transient_periods = 60;
        so.record_periods = 1;
        so.early_settle = false;
        so.shooting = false;
        let start = steady_state(&m, &so, None).unwrap().end_state;
        let mut plain = ShootOptions::new(period);
        plain.broyden = false;
        let mut updated = ShootOptions::new(period);
        updated.jacobian_tol = Some((1e-7, 1e-10));
        let a = converged(shoot(&m, omega, &start, &plain).unwrap());
        let b = converged(shoot(&m, omega, &start, &updated).unwrap());
        // Both see the same period (the period-2 attempt at 1.1 lands on
        // the period-1 orbit, which both report as such).
        assert_eq!(a.period, b.period, "Omega {omega} period {period}");
        let red = Reduced::new(&m, omega);
        let diff: Vec<f64> = a.z.iter().zip(&b.z).map(|(x, y)| x - y).collect();
        let size = red.mesh_norm_um(&a.z);
        assert!(
            red.mesh_norm_um(&diff) <= 1e-7 * size,
            "Omega {omega} period {period}: orbits {:?} and {:?}",
            a.z,
            b.z
        );
        // The monodromy at b's orbit, integrated here at the same tolerances.
        let ode = crate::dynamics::MeshOde::new(&m.system, red.omega_rad_s);
        let tol = crate::dynamics::tolerances(
            &m.system,
            omega,
            updated.rtol,
            updated.atol_m,
            red.period_s,
            1e-14,
        );
        let (z, rigid) = red.from_state(&b.start_state);
        let mut run = MapRun::new(
            &red,
            &ode,
            &tol,
            &z,
            rigid,
            b.period,
            true,
            1.0,
            1.0,
            u64::MAX,
        );
        let mut taken = 0;
        let mono = run.advance(&red, u64::MAX, &mut taken).unwrap().unwrap();
        let mono = mono.monodromy.unwrap();
        assert!(
            (&mono - &b.monodromy).amax() <= 1e-9 * mono.amax(),
            "Omega {omega} period {period}: monodromy not the orbit's"
        );
        let (ma, mb) = (
            a.multipliers.clone().unwrap(),
            b.multipliers.clone().unwrap(),
        );
        assert!(
            (ma.max_modulus() - mb.max_modulus()).abs() <= 1e-6,
            "Omega {omega} period {period}: {} vs {}",
            ma.max_modulus(),
            mb.max_modulus()
        );
        assert_eq!(a.is_stable(), b.is_stable());
    }
}
