//! Floquet multipliers where the physics fixes them, whatever method gives
//! them: the steady-state pipeline's, a fixed-Omega shooting solve's and
//! the harmonic balance's against the engaged system's spectral radius
//! (`gearshock instability`), and each monodromy's determinant against
//! Liouville's formula.
//!
//! Where no mesh changes contact over an orbit (no backlash, or every mesh
//! in drive-flank contact throughout), the orbit's variational equation is
//! the engaged linear system's `M Y'' + C Y' + K(t) Y = 0`, whatever the
//! orbit: its largest multiplier is that system's spectral radius. And the
//! mesh damping acts in and out of contact, so for any orbit
//! `det Phi = exp(-n T tr(M^-1 C))` (the rigid-body mode, which the reduced
//! monodromy leaves out, has no damping and contributes a factor 1).

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use solver::hbm::{BranchPoint, FrfContinuation, FrfSpec, Method};
use solver::parametric::Parametric;
use solver::shooting::{shoot, Orbit, ShootOptions, ShootOutcome};
use solver::steady::{steady_state, Impact, Model, Motion, SteadyOptions, SteadyState};
use test_support::models::model;

/// The models of the agreement test: both models linear (no backlash,
/// Fig. 2's TE on every mesh for the compound set), and the compound set
/// at its defaults, where only the orbits without contact change count.
fn cases() -> Vec<(&'static str, Model, Vec<f64>)> {
    let grid: Vec<f64> = (0..16).map(|i| 0.15 + 0.115 * f64::from(i)).collect();
    vec![
        (
            "compound set, Fig. 2 (no backlash, TE 5 µm on all meshes)",
            model(&["backlash_um=0", "te_meshes=all", "te_um=5"]),
            grid.clone(),
        ),
        (
            "gear pair, no backlash",
            model(&["model=gear-pair", "backlash_um=0"]),
            grid,
        ),
        (
            "compound set, defaults",
            model(&[]),
            vec![
                0.08, 0.1, 0.12, 0.15, 0.18, 0.2, 0.25, 0.3, 0.32, 0.35, 0.38, 0.4,
            ],
        ),
    ]
}

/// Whether no mesh of `ss` changes contact: no backlash, or every mesh in
/// drive-flank contact throughout.
fn engaged_throughout(m: &Model, ss: &SteadyState) -> bool {
    m.system.meshes.iter().all(|mesh| mesh.backlash_m == 0.0)
        || ss.meshes.iter().all(|ms| ms.impact == Impact::None)
}

fn exact_multiplier(ss: &SteadyState) -> Option<(u32, f64)> {
    match ss.motion {
        Motion::PeriodicExact {
            period,
            max_multiplier_modulus,
            ..
        } => Some((period, max_multiplier_modulus)),
        _ => None,
    }
}

fn converged(out: ShootOutcome) -> Orbit {
    match out {
        ShootOutcome::Converged(o) => *o,
        ShootOutcome::Failed(f) => panic!("shooting failed: {f:?}"),
    }
}

/// The harmonic balance's periodic solution at `omega` (exact integration
/// between the contact switches, 7 harmonics).
fn hbm_at(m: &Model, omega: f64) -> BranchPoint {
    let mut spec = FrfSpec::new(omega, omega + 0.01, 10);
    spec.harmonics = 7;
    spec.method = Method::Exact;
    let mut c = FrfContinuation::new(m, spec).expect("spec");
    c.advance(1).expect("Newton").remove(0)
}

fn spectral_radius(values: &[nalgebra::Complex<f64>]) -> f64 {
    values.iter().map(|v| v.norm()).fold(0.0, f64::max)
}

/// The pipeline's largest multiplier of a period-1 orbit without contact
/// change equals the engaged system's spectral radius to 1e-6, on both
/// models at ten Omegas or more each (Fig. 2's linear case among them);
/// shooting at fixed Omega and the harmonic balance agree with it to 1e-4.
#[test]
fn every_method_gives_the_engaged_spectral_radius_where_no_mesh_changes_contact() {
    for (name, m, omegas) in cases() {
        let engaged = Parametric::new(&m).unwrap();
        let linear = m.system.meshes.iter().all(|mesh| mesh.backlash_m == 0.0);
        let mut checked = 0;
        for &omega in &omegas {
            let rho = engaged.at(omega).unwrap().spectral_radius;
            if rho >= 1.0 {
                // Parametrically unstable: no steady state to compare.
                continue;
            }
            let ss = steady_state(&m, &SteadyOptions::new(omega), None).unwrap();
            if !engaged_throughout(&m, &ss) {
                continue;
            }
            let Some((period, mu)) = exact_multiplier(&ss) else {
                panic!("{name}, Omega {omega}: {:?}, not an exact orbit", ss.motion);
            };
            assert_eq!(period, 1, "{name}, Omega {omega}");
            assert!(
                (mu - rho).abs() <= 1e-6,
                "{name}, Omega {omega}: the pipeline's multiplier {mu} against the engaged system's {rho}"
            );
            let orbit = converged(shoot(&m, omega, &ss.end_state, &ShootOptions::new(1)).unwrap());
            let shot = orbit.max_multiplier_modulus();
            assert!(
                (shot - rho).abs() <= 1e-4,
                "{name}, Omega {omega}: shooting's multiplier {shot} against {rho}"
            );
            let p = hbm_at(&m, omega);
            if p.stable.is_some() && (linear || p.meshes.iter().all(|bm| bm.impact == Impact::None))
            {
                let h = spectral_radius(&p.multipliers);
                assert!(
                    (h - rho).abs() <= 1e-4,
                    "{name}, Omega {omega}: the harmonic balance's multiplier {h} against {rho}"
                );
            }
            checked += 1;
        }
        let least = if linear { 10 } else { 3 };
        assert!(
            checked >= least,
            "{name}: {checked} Omegas without contact change, {least} or more wanted"
        );
    }
}

/// `det Phi = exp(-n T tr(M^-1 C))` for the orbits shooting finds, with
/// contact changes or without (the gear pair's period-1, -2 and -8 orbits
/// with single-sided impacts): the determinant needs no other method. The
/// determinant is the product of every multiplier, the small ones too, so
/// the tangents are integrated to the orbit's own relative accuracy
/// (`tangent_atol_scale`); at rtol 1e-13 the error is some 1e-9 and falls
/// tenfold per decade of the tolerance: an integration error, not a
/// structural one (a rigid-body mode coupled into the reduced monodromy,
/// say, would not shrink).
#[test]
fn the_monodromy_obeys_liouvilles_formula() {
    let cases: [(&[&str], f64); 6] = [
        (&["backlash_um=0", "te_meshes=all", "te_um=5"], 0.84),
        (&[], 0.35),
        (&[], 0.27),
        (&["model=gear-pair"], 0.5),
        (&["model=gear-pair"], 0.84),
        (&["model=gear-pair"], 1.0),
    ];
    for (sets, omega) in cases {
        let m = model(sets);
        let c = m.system.damping_matrix();
        let m_inv = m.system.mass.clone().try_inverse().unwrap();
        let trace = (m_inv * c).trace();
        let ss = steady_state(&m, &SteadyOptions::new(omega), None).unwrap();
        let (period, _) = exact_multiplier(&ss).unwrap();
        let mut opts = ShootOptions::new(period);
        (opts.rtol, opts.atol_m, opts.tangent_atol_scale) = (1e-12, 1e-16, 1e-2);
        let orbit = match shoot(&m, omega, &ss.end_state, &opts).unwrap() {
            ShootOutcome::Converged(o) => *o,
            ShootOutcome::Failed(f) => panic!("{sets:?} at Omega {omega}: {f:?}"),
        };
        let period_s = 2.0 * std::f64::consts::PI / (omega * m.system.omega_ref_rad_s);
        let expected = (-f64::from(orbit.period) * period_s * trace).exp();
        let det = orbit.monodromy.determinant();
        assert!(
            ((det - expected) / expected).abs() <= 1e-8,
            "{sets:?} at Omega {omega}: det {det:e} against Liouville's {expected:e}"
        );
    }
}

/// A period-1 orbit shot for as period 3 (as the pipeline does when its
/// loose test reads 3 off a transient) is reported as period 1 with its
/// own multipliers, not their cubes.
#[test]
fn an_orbit_shot_at_a_multiple_of_its_period_has_its_own_multipliers() {
    let m = model(&[]);
    let omega = 0.35;
    let ss = steady_state(&m, &SteadyOptions::new(omega), None).unwrap();
    let once = converged(shoot(&m, omega, &ss.end_state, &ShootOptions::new(1)).unwrap());
    for n in [2, 3, 6] {
        let orbit = converged(shoot(&m, omega, &ss.end_state, &ShootOptions::new(n)).unwrap());
        assert_eq!(orbit.period, 1, "shot for period {n}");
        let (a, b) = (
            orbit.max_multiplier_modulus(),
            once.max_multiplier_modulus(),
        );
        assert!(
            (a - b).abs() <= 1e-7,
            "shot for period {n}: {a} against {b}"
        );
    }
}

/// The orbits' multipliers converge at RK4's fourth order in the step:
/// on the compound set's impacting harmonic-balance orbits (where the
/// contact switches cut the period into pieces), the largest modulus at
/// 8, 16 and 32 steps a period of the fastest mode against 256. Halving
/// the step divides the error by at least 2^3.5 (more where the leading
/// term happens to be small), by 2^4 within half an order on the orbit
/// with the largest error, and at the default 16 steps the error stays
/// within the 1e-3 that docs/model.md states for the benchmark sweep
/// (`gearshock bench --multipliers`: 5.1e-4 at most).
#[test]
fn orbit_multipliers_converge_at_rk4s_fourth_order() {
    use solver::hbm::stability::{floquet_with_steps, ORBIT_STEPS_PER_FASTEST};
    let m = model(&[]);
    // (error at 8, at 16, at 32 steps) of each impacting orbit.
    let mut errors = Vec::new();
    for omega in [0.21, 0.22, 0.3, 0.4, 0.45] {
        let mut spec = FrfSpec::new(omega, omega + 0.01, 10);
        spec.harmonics = 7;
        let mut c = FrfContinuation::new(&m, spec).expect("spec");
        let p = c.advance(1).expect("Newton").remove(0);
        let impacting = p
            .meshes
            .iter()
            .any(|ms| matches!(ms.impact, Impact::SingleSided | Impact::DoubleSided));
        if !impacting {
            continue;
        }
        let radius = |steps: f64| {
            floquet_with_steps(c.assembly(), &p.coefficients, p.omega, steps)
                .expect("multipliers")
                .spectral_radius()
        };
        let reference = radius(256.0);
        let err = |steps| (radius(steps) - reference).abs();
        let e = (err(8.0), err(ORBIT_STEPS_PER_FASTEST), err(32.0));
        assert!(
            e.1 <= 1e-3,
            "Omega {omega}: 16 steps {:e} from the reference",
            e.1
        );
        // Below 1e-8 the reference's own error and rounding take over.
        for (coarse, fine) in [(e.0, e.1), (e.1, e.2)] {
            let order = (coarse / fine).log2();
            assert!(
                coarse < 1e-8 || order >= 3.5,
                "Omega {omega}: observed order {order:.2} ({coarse:e} -> {fine:e})"
            );
        }
        errors.push(e);
    }
    assert!(errors.len() >= 3, "only {} impacting orbits", errors.len());
    let worst = errors
        .iter()
        .copied()
        .fold((0.0, 1.0, 1.0), |a, b| if b.0 > a.0 { b } else { a });
    for (coarse, fine) in [(worst.0, worst.1), (worst.1, worst.2)] {
        let order = (coarse / fine).log2();
        assert!(
            (3.5..=4.5).contains(&order),
            "the largest error's observed order {order:.2} ({coarse:e} -> {fine:e})"
        );
    }
}
