//! The excitation's waveforms against closed forms: the rectangular and
//! trapezoid stiffness's Fourier coefficients, a linear gear pair driven by
//! a two-harmonic transmission error against its exact receptance at both
//! orders (harmonic balance, time integration and shooting), the balance's
//! refusal of fewer harmonics than the excitation has, the equations of
//! motion against the series written out, and the rectangular
//! stiffness's resonance at twice the mesh frequency, which the seed's
//! cosine does not have.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use nalgebra::Complex;
use solver::hbm::{BranchPoint, FrfContinuation, FrfSpec, Method};
use solver::keys;
use solver::params::ModelParams;
use solver::steady::{steady_state, Model, SteadyOptions};
use std::f64::consts::PI;

fn pair(assignments: &[&str]) -> Model {
    let mut p = ModelParams::default();
    keys::set_assignment(&mut p, "model=gear-pair").expect("model");
    for a in assignments {
        keys::set_assignment(&mut p, a).expect(a);
    }
    Model::new(&p).expect("model")
}

/// The relative stiffness series `[a_1, a_2, ...]` the solver sees.
fn series(m: &Model) -> Vec<f64> {
    let mesh = &m.system.meshes[0];
    let mut s = vec![mesh.stiffness_variation];
    s.extend(&mesh.stiffness_harmonics);
    s
}

#[test]
fn the_rectangular_stiffness_is_its_fourier_series() {
    // Contact ratio 1.6: double contact for d = 0.6 of each mesh period,
    // centred on theta = 0; w = 2 (1 - d) there and -2 d elsewhere, so
    // a_n = (1/pi) int_{-pi d}^{pi d} 2 cos(n t) dt = 4 sin(n pi d) / (n pi).
    let (v, d) = (0.3, 0.6);
    let m = pair(&[
        "stiffness_wave=rectangular",
        "contact_ratio=1.6",
        "stiffness_variation=0.3",
        "stiffness_harmonics=9",
    ]);
    let a = series(&m);
    assert_eq!(a.len(), 9);
    for (i, an) in a.iter().enumerate() {
        let n = (i + 1) as f64;
        let want = v * 4.0 * (n * PI * d).sin() / (n * PI);
        assert!((an - want).abs() < 1e-15, "a_{n}: {an} vs {want}");
    }
    // Half the peak-to-peak over the mean is v: the levels 1 + 2 v (1 - d)
    // and 1 - 2 v d, whose time mean is 1.
    let (hi, lo) = (1.0 + 2.0 * v * (1.0 - d), 1.0 - 2.0 * v * d);
    assert!(((hi - lo) / 2.0 - v).abs() < 1e-15);
    assert!((d * hi + (1.0 - d) * lo - 1.0).abs() < 1e-15);
    // The mean stiffness, and so the natural frequency, is the cosine's.
    let cosine = pair(&["stiffness_variation=0.3"]);
    assert_eq!(m.system.omega_ref_rad_s, cosine.system.omega_ref_rad_s);
    assert_eq!(series(&cosine), vec![0.3]);
}

#[test]
fn the_trapezoid_stiffness_is_its_fourier_series() {
    // Ramps r = 0.1 mesh periods wide, centred on the rectangle's switches:
    // the rectangle convolved with a box of width r, each coefficient
    // multiplied by sin(n pi r) / (n pi r).
    let (v, d, r) = (0.25, 0.45, 0.1);
    let m = pair(&[
        "stiffness_wave=trapezoid",
        "contact_ratio=1.45",
        "stiffness_ramp=0.1",
        "stiffness_variation=0.25",
        "stiffness_harmonics=7",
    ]);
    let a = series(&m);
    for (i, an) in a.iter().enumerate() {
        let n = (i + 1) as f64;
        let want = v * 4.0 * (n * PI * d).sin() / (n * PI) * (n * PI * r).sin() / (n * PI * r);
        assert!((an - want).abs() < 1e-15, "a_{n}: {an} vs {want}");
    }
    // The same coefficients by quadrature of the trapezoid itself: flat
    // 2 (1 - d) for |t| < pi (d - r), flat -2 d beyond pi (d + r), linear between.
    let shape = |t: f64| {
        let x = t.abs() / PI;
        if x < d - r {
            2.0 * (1.0 - d)
        } else if x > d + r {
            -2.0 * d
        } else {
            2.0 * (1.0 - d) - 2.0 * (x - (d - r)) / (2.0 * r)
        }
    };
    let samples = 100_000;
    for (i, an) in a.iter().enumerate() {
        let n = (i + 1) as f64;
        let q: f64 = (0..samples)
            .map(|j| {
                let t = -PI + 2.0 * PI * (j as f64 + 0.5) / samples as f64;
                v * shape(t) * (n * t).cos()
            })
            .sum::<f64>()
            * 2.0
            / samples as f64;
        assert!((an - q).abs() < 1e-7, "a_{n}: {an} vs quadrature {q}");
    }
}

#[test]
fn a_ramp_wider_than_a_flat_or_a_contact_ratio_out_of_range_is_refused() {
    let mut p = ModelParams::default();
    keys::set_assignment(&mut p, "model=gear-pair").unwrap();
    for a in [
        "stiffness_wave=trapezoid",
        "contact_ratio=1.05",
        "stiffness_ramp=0.2",
    ] {
        keys::set_assignment(&mut p, a).unwrap();
    }
    let e = Model::new(&p).unwrap_err().to_string();
    assert!(e.contains("ramp 0.2") && e.contains("0.050"), "{e}");
    assert!(keys::set_assignment(&mut p, "contact_ratio=3.5").is_err());
}

/// `x_n = (k + i n w c) / (k - (n w)^2 m + i n w c) E_n`: the receptance of
/// `m x'' + c (x' - e') + k (x - e) = F` at harmonic `n` of a TE `e`.
fn receptance(m: &Model, omega: f64, n: f64) -> Complex<f64> {
    let mesh = &m.system.meshes[0];
    let (k, c, me) = (
        mesh.stiffness_mean_n_m,
        mesh.damping_n_s_m,
        mesh.equivalent_mass_kg,
    );
    let w = n * omega * m.system.omega_ref_rad_s;
    Complex::new(k, w * c) / Complex::new(k - w * w * me, w * c)
}

#[test]
fn a_linear_pair_with_two_te_harmonics_has_its_exact_receptance_at_both_orders() {
    // e = 20 sin(theta) + 8 cos(2 theta) - 5 sin(2 theta) um, no backlash
    // (always in contact), constant stiffness: linear.
    let m = pair(&[
        "backlash_um=0",
        "stiffness_variation=0",
        "te_um=20",
        "te_cos2_um=8",
        "te_sin2_um=-5",
    ]);
    let e1 = Complex::new(0.0, -20e-6); // 20 sin = Re(-20 i e^{i theta})
    let e2 = Complex::new(8e-6, 5e-6); // 8 cos - 5 sin = Re((8 + 5 i) e^{2 i theta})
    for omega in [0.3, 0.45, 0.5, 0.8, 1.2] {
        let x1 = receptance(&m, omega, 1.0) * e1;
        let x2 = receptance(&m, omega, 2.0) * e2;
        // Harmonic balance: the amplitude of each harmonic.
        let mut spec = FrfSpec::new(omega, omega + 0.01, 10);
        spec.harmonics = 3;
        let mut c = FrfContinuation::new(&m, spec).expect("spec");
        let p: BranchPoint = c.advance(1).expect("Newton").remove(0);
        let h = &p.meshes[0].harmonics_m;
        for (got, want) in [(h[1], x1.norm()), (h[2], x2.norm())] {
            assert!(
                (got - want).abs() < 1e-8 * want,
                "Omega {omega}: HBM {got} vs {want}"
            );
        }
        assert!(h[3] < 1e-9 * x1.norm(), "no third harmonic: {}", h[3]);
        // The solver's own linear response at each order is the same receptance.
        let w = omega * m.system.omega_ref_rad_s;
        for (n, want) in [(1, x1), (2, x2)] {
            let q = solver::modal::linear_response_harmonic(&m.system, w, n).unwrap();
            let got = m.system.meshes[0].dot(&[q[0].re, q[1].re])
                + Complex::<f64>::i() * m.system.meshes[0].dot(&[q[0].im, q[1].im]);
            assert!((got - want).norm() < 1e-9 * want.norm(), "order {n}");
        }
        // Time integration: the extremes of mean + Re(x1 e^{i t} + x2 e^{2 i t}).
        let mean = m.statics.mesh_deflection_m[0];
        let (lo, hi) = (0..20_000)
            .map(|i| {
                let t = 2.0 * PI * i as f64 / 20_000.0;
                let z = Complex::from_polar(1.0, t);
                mean + (x1 * z + x2 * z * z).re
            })
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
                (lo.min(x), hi.max(x))
            });
        let opts = test_support::models::strict_run(omega, (600, 10), (1e-10, 1e-15));
        let ss = steady_state(&m, &opts, None).expect("run");
        let r = &ss.meshes[0];
        let pp = hi - lo;
        for (got, want) in [(r.delta_max_m, hi), (r.delta_min_m, lo)] {
            assert!(
                (got - want).abs() < 1e-5 * pp,
                "Omega {omega}: time integration {got} vs {want}"
            );
        }
    }
}

fn hbm_branch(m: &Model, from: f64, to: f64) -> Vec<BranchPoint> {
    let mut spec = FrfSpec::new(from, to, 160);
    spec.harmonics = 7;
    spec.method = Method::Exact;
    spec.stability = false;
    let mut c = FrfContinuation::new(m, spec).expect("spec");
    let mut out = Vec::new();
    while !c.is_finished() {
        out.extend(c.advance(64).expect("continuation"));
    }
    out
}

/// The branch's highest peak-to-peak: its Omega, the peak-to-peak, and the
/// amplitudes of the first and second harmonics there.
fn peak(points: &[BranchPoint]) -> (f64, f64, [f64; 2]) {
    points
        .iter()
        .map(|p| {
            let mm = &p.meshes[0];
            let h = [mm.harmonics_m[1], mm.harmonics_m[2]];
            (p.omega, mm.delta_max_m - mm.delta_min_m, h)
        })
        .fold((0.0, 0.0, [0.0; 2]), |a, b| if b.1 > a.1 { b } else { a })
}

#[test]
fn a_rectangular_stiffness_resonates_at_twice_the_mesh_order_and_the_cosine_does_not() {
    // The pair's natural frequency is Omega = 1; at Omega = 1/2 the mesh
    // frequency's second harmonic meets it. The rectangle (contact ratio
    // 1.6, v 0.3) has a second harmonic 4 v sin(1.2 pi) / (2 pi) = -0.112;
    // the cosine has none, only the parametric coupling of its first.
    // No TE: the stiffness's ripple under the static load is the only
    // excitation; damping 0.1 keeps the branch free of folds.
    let base = ["te_um=0", "stiffness_variation=0.3", "damping_ratio=0.1"];
    let rect = pair(
        &[
            &base[..],
            &["stiffness_wave=rectangular", "contact_ratio=1.6"],
        ]
        .concat(),
    );
    let cosine = pair(&base);
    let (w_rect, pp_rect, [h1, h2]) = peak(&hbm_branch(&rect, 0.38, 0.62));
    let (_, pp_cos, _) = peak(&hbm_branch(&cosine, 0.38, 0.62));
    assert!(
        h2 > h1,
        "the second harmonic is the larger there: {h2} vs {h1}"
    );
    let quiet = |m: &Model| {
        let pts = hbm_branch(m, 0.32, 0.34);
        pts.iter()
            .map(|p| p.meshes[0].delta_max_m - p.meshes[0].delta_min_m)
            .fold(0.0, f64::max)
    };
    assert!(
        (w_rect - 0.5).abs() < 0.05,
        "the peak sits near Omega 0.5: {w_rect}"
    );
    assert!(
        pp_rect > 1.8 * quiet(&rect),
        "a resonance: {pp_rect} against {} off it",
        quiet(&rect)
    );
    assert!(
        pp_rect > 2.0 * pp_cos,
        "the cosine has no such peak: {pp_rect} vs {pp_cos}"
    );
    // Harmonic balance and time integration agree at the peak to 1 % of
    // its peak-to-peak.
    let mut o = SteadyOptions::new(w_rect);
    o.transient_periods = 1500;
    o.record_periods = 20;
    let ss = steady_state(&rect, &o, None).expect("time integration");
    let r = &ss.meshes[0];
    let pp_ti = r.delta_max_m - r.delta_min_m;
    assert!(
        (pp_ti - pp_rect).abs() < 0.01 * pp_rect,
        "peak-to-peak at Omega {w_rect}: HBM {pp_rect} vs time integration {pp_ti}"
    );
    println!(
        "rectangular peak at Omega {w_rect:.4}: HBM {:.4} um, time integration {:.4} um \
         (difference {:.3} %); cosine peak {:.4} um",
        pp_rect * 1e6,
        pp_ti * 1e6,
        100.0 * (pp_ti - pp_rect).abs() / pp_rect,
        pp_cos * 1e6
    );
}

#[test]
fn the_balance_refuses_fewer_harmonics_than_the_excitation_has() {
    let m = pair(&[
        "stiffness_wave=rectangular",
        "contact_ratio=1.6",
        "stiffness_harmonics=5",
    ]);
    let mut spec = FrfSpec::new(0.4, 0.6, 10);
    spec.harmonics = 4;
    let Err(e) = FrfContinuation::new(&m, spec.clone()) else {
        panic!("refused")
    };
    assert!(e.to_string().contains("at least 5"), "{e}");
    spec.harmonics = 5;
    assert!(FrfContinuation::new(&m, spec.clone()).is_ok());
    spec.method = Method::DescribingFunction;
    spec.harmonics = 1;
    let Err(e) = FrfContinuation::new(&m, spec.clone()) else {
        panic!("refused")
    };
    assert!(e.to_string().contains("describing function"), "{e}");
}

#[test]
fn the_equations_of_motion_see_the_series_at_every_instant() {
    // k(t) = k_m (1 + sum_n a_n cos(n w t)), e(t) = sum_n (C_n cos + S_n sin)(n w t):
    // the force at a fixed deflection, written out here, against the ODE's.
    let m = pair(&[
        "stiffness_wave=trapezoid",
        "contact_ratio=1.7",
        "stiffness_ramp=0.2",
        "stiffness_harmonics=6",
        "backlash_um=0",
        "te_um=3",
        "te_cos3_um=2",
        "te_sin5_um=-1",
        "damping_ratio=0",
    ]);
    let mesh = &m.system.meshes[0];
    let (v, d, r) = (0.2, 0.7, 0.2);
    let w = 0.8 * m.system.omega_ref_rad_s;
    let ode = solver::dynamics::MeshOde::new(&m.system, w);
    let y = [3e-5, -1e-5, 0.0, 0.0];
    let delta = mesh.dot(&y[..2]);
    for i in 0..50 {
        let t = i as f64 * 0.37 / w;
        let th = w * t;
        let k = mesh.stiffness_mean_n_m
            * (1.0
                + (1..=6)
                    .map(|n| {
                        let x = n as f64 * PI;
                        v * 4.0 * (x * d).sin() / x * (x * r).sin() / (x * r)
                            * (n as f64 * th).cos()
                    })
                    .sum::<f64>());
        let e = 3e-6 * th.sin() + 2e-6 * (3.0 * th).cos() - 1e-6 * (5.0 * th).sin();
        let want = k * (delta - e);
        let got = ode.mesh_instant(0, t, &y).force;
        assert!(
            (got - want).abs() < 1e-9 * want.abs(),
            "t {t}: {got} vs {want}"
        );
        let (ks, es, _) = mesh.excitation(w, th.cos(), th.sin());
        assert!((ks - k).abs() < 1e-9 * k && (es - e).abs() < 1e-15, "t {t}");
    }
}

#[test]
fn shooting_finds_the_two_harmonic_linear_orbit_in_one_newton_step() {
    // Linear: the orbit is the closed form at t = 0, delta = static +
    // Re(x1 + x2), delta' = Re(i w x1 + 2 i w x2), and Newton on the
    // period map (with its variational equations) reaches it at once.
    let m = pair(&[
        "backlash_um=0",
        "stiffness_variation=0",
        "te_um=20",
        "te_cos2_um=8",
        "te_sin2_um=-5",
    ]);
    let e1 = Complex::new(0.0, -20e-6);
    let e2 = Complex::new(8e-6, 5e-6);
    let mut opts = solver::shooting::ShootOptions::new(1);
    opts.rtol = 1e-12;
    opts.atol_m = 1e-15;
    for omega in [0.45, 0.8] {
        let out = solver::shooting::shoot(&m, omega, &m.static_state(), &opts).unwrap();
        let solver::shooting::ShootOutcome::Converged(orbit) = out else {
            panic!("shooting failed at Omega {omega}");
        };
        assert_eq!(orbit.iterations, 1, "Omega {omega}");
        let w = omega * m.system.omega_ref_rad_s;
        let x1 = receptance(&m, omega, 1.0) * e1;
        let x2 = receptance(&m, omega, 2.0) * e2;
        let mesh = &m.system.meshes[0];
        let y = &orbit.start_state;
        let d = mesh.dot(&y[..2]);
        let v = mesh.dot(&y[2..]);
        let d_exact = m.statics.mesh_deflection_m[0] + (x1 + x2).re;
        let v_exact = (Complex::new(0.0, w) * (x1 + 2.0 * x2)).re;
        let scale = x1.norm() + x2.norm();
        assert!(
            (d - d_exact).abs() < 1e-7 * scale,
            "Omega {omega}: {d} vs {d_exact}"
        );
        assert!(
            (v - v_exact).abs() < 1e-7 * w * scale,
            "Omega {omega}: {v} vs {v_exact}"
        );
    }
}
