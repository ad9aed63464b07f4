//! The harmonic-balance engine against independent answers: the exact linear
//! receptance, the classical one-harmonic Duffing results, the time
//! integration of the same model (agreement, stability and jumps), its own
//! convergence in H, and the seed's describing function against AFT.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use solver::hbm::{
    Bifurcation, BranchPoint, FrfContinuation, FrfSpec, HbmModel, Method, PieceEnd, StepControl,
};
use solver::modal::linear_receptance;
use solver::steady::{steady_state, Model, SteadyOptions, SteadyState};
use solver::sweep::Direction;
use test_support::models::model;

fn branch(c: &mut FrfContinuation) -> Vec<BranchPoint> {
    let mut out = Vec::new();
    while !c.is_finished() {
        out.extend(c.advance(64).expect("continuation"));
    }
    out
}

/// The first point of a continuation: the periodic solution at `omega`.
fn solve_at(m: &Model, omega: f64, h: usize, method: Method, grid: Option<usize>) -> BranchPoint {
    let mut spec = FrfSpec::new(omega, omega + 0.01, 10);
    spec.harmonics = h;
    spec.method = method;
    spec.grid = grid;
    let mut c = FrfContinuation::new(m, spec).expect("spec");
    c.advance(1).expect("Newton").remove(0)
}

fn time_integration(m: &Model, omega: f64) -> SteadyState {
    let mut o = SteadyOptions::new(omega);
    o.transient_periods = 800;
    o.record_periods = 30;
    steady_state(m, &o, None).expect("time integration")
}

#[test]
fn linear_limit_equals_the_exact_receptance_for_h1_and_h5() {
    let m = model(&["backlash_um=0", "stiffness_variation=0"]);
    for h in [1, 5] {
        let mut spec = FrfSpec::new(0.1, 2.0, 120);
        spec.harmonics = h;
        let mut c = FrfContinuation::new(&m, spec).expect("spec");
        let pts = branch(&mut c);
        assert!(pts.len() >= 120, "H = {h}: only {} points", pts.len());
        let mut worst: f64 = 0.0;
        for p in &pts {
            let exact = linear_receptance(&m.system, p.omega * m.system.omega_ref_rad_s).unwrap();
            for (mesh, x) in p.meshes.iter().zip(&exact) {
                worst = worst.max((mesh.delta_amplitude_m - x.norm()).abs() / x.norm());
                // A linear orbit has no higher harmonics.
                for a in &mesh.harmonics_m[2..] {
                    assert!(*a <= 1e-9 * x.norm(), "H = {h}: harmonic {a}");
                }
            }
            assert_eq!(p.stable, Some(true), "a damped linear system is stable");
            assert!(p.bifurcation.is_none());
        }
        assert!(worst < 1e-8, "H = {h}: worst relative error {worst:e}");
    }
}

/// One-harmonic Duffing: `((1 - W^2 + 3/4 alpha a^2)^2 + (2 zeta W)^2) a^2 = F^2`.
/// As a cubic in `u = a^2` it has three real roots between the two folds,
/// so the folds are the zeros of its discriminant.
fn duffing_discriminant(omega: f64, zeta: f64, alpha: f64, force: f64) -> f64 {
    let c = 1.0 - omega * omega;
    let d = 4.0 * zeta * zeta * omega * omega;
    let (a3, a2, a1, a0) = (
        0.5625 * alpha * alpha,
        1.5 * alpha * c,
        c * c + d,
        -force * force,
    );
    18.0 * a3 * a2 * a1 * a0 - 4.0 * a2.powi(3) * a0 + a2 * a2 * a1 * a1
        - 4.0 * a3 * a1.powi(3)
        - 27.0 * a3 * a3 * a0 * a0
}

fn bisect(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    let fa = f(a);
    for _ in 0..100 {
        let mid = 0.5 * (a + b);
        if (f(mid) > 0.0) == (fa > 0.0) {
            a = mid;
        } else {
            b = mid;
        }
    }
    0.5 * (a + b)
}

#[test]
fn duffing_peak_and_folds_match_the_closed_form() {
    let (zeta, alpha, force) = (0.05, 0.1, 0.3);
    // Closed form. Peak: 1 - W^2 + 3/4 alpha a^2 = 0 (the backbone) and a = F / (2 zeta W).
    let mut a_peak: f64 = force / (2.0 * zeta);
    for _ in 0..200 {
        let w = (1.0 + 0.75 * alpha * a_peak * a_peak).sqrt();
        a_peak = force / (2.0 * zeta * w);
    }
    let w_peak = (1.0 + 0.75 * alpha * a_peak * a_peak).sqrt();
    let disc = |w: f64| duffing_discriminant(w, zeta, alpha, force);
    let grid: Vec<f64> = (0..=2000).map(|i| 0.5 + 1.5 * i as f64 / 2000.0).collect();
    let folds: Vec<f64> = grid
        .windows(2)
        .filter(|w| disc(w[0]).signum() != disc(w[1]).signum())
        .map(|w| bisect(disc, w[0], w[1]))
        .collect();
    assert_eq!(folds.len(), 2, "closed form folds {folds:?}");

    let mut spec = FrfSpec::new(0.5, 2.0, 300);
    spec.harmonics = 1;
    let mut c = FrfContinuation::for_model(HbmModel::duffing(zeta, alpha, force), spec).unwrap();
    let pts = branch(&mut c);
    let amp = |p: &BranchPoint| p.meshes[0].delta_amplitude_m * 1e6; // unit model: "um" = 1
    let top = pts.iter().max_by(|a, b| amp(a).total_cmp(&amp(b))).unwrap();
    assert!(
        (amp(top) - a_peak).abs() < 2e-3 * a_peak,
        "peak {} vs {a_peak}",
        amp(top)
    );
    assert!(
        (top.omega - w_peak).abs() < 5e-3,
        "peak at {} vs {w_peak}",
        top.omega
    );
    // Every point lies on the closed-form curve.
    for p in &pts {
        let a = amp(p);
        let w = p.omega;
        let lhs = ((1.0 - w * w + 0.75 * alpha * a * a).powi(2) + (2.0 * zeta * w).powi(2)) * a * a;
        assert!(
            (lhs - force * force).abs() < 1e-6,
            "off the curve at {w}: {lhs}"
        );
    }
    let found = fold_omegas(&pts);
    assert_eq!(found.len(), 2, "folds found {found:?}");
    // The upper fold is met first on the way up; each is located on the
    // branch (regula falsi on the tangent's Omega component), so it equals
    // the closed form's up to the bisection's and the corrector's tolerance.
    assert!((found[0] - folds[1]).abs() < 1e-6, "{found:?} vs {folds:?}");
    assert!((found[1] - folds[0]).abs() < 1e-6, "{found:?} vs {folds:?}");
    // Between the folds the middle branch is unstable (a real multiplier > 1).
    let between: Vec<&BranchPoint> = pts
        .iter()
        .skip_while(|p| p.bifurcation != Some(Bifurcation::Fold))
        .skip(1)
        .take_while(|p| p.bifurcation != Some(Bifurcation::Fold))
        .collect();
    // Stability comes from the monodromy matrix of the one-harmonic orbit,
    // which is not an exact solution of the ODE, so its multiplier crosses
    // +1 slightly inside the balance's fold (measured: 0.002 in Omega).
    assert!(between.len() > 4);
    let inner: Vec<&&BranchPoint> = between
        .iter()
        .filter(|p| p.omega > folds[0] + 0.004 && p.omega < folds[1] - 0.004)
        .collect();
    assert!(inner.len() > 4);
    assert!(
        inner.iter().all(|p| p.stable == Some(false)),
        "{:?}",
        between
            .iter()
            .map(|p| (p.omega, p.stable))
            .collect::<Vec<_>>()
    );
    assert!(pts.first().unwrap().stable == Some(true) && pts.last().unwrap().stable == Some(true));
}

/// Max and min of x = delta - e of every mesh: HBM against time integration,
/// relative to the peak-to-peak.
fn discrepancy(p: &BranchPoint, ti: &SteadyState) -> f64 {
    p.meshes
        .iter()
        .zip(&ti.meshes)
        .map(|(h, t)| {
            let pp = t.rel_max_m - t.rel_min_m;
            ((h.rel_max_m - t.rel_max_m).abs()).max((h.rel_min_m - t.rel_min_m).abs()) / pp
        })
        .fold(0.0, f64::max)
}

/// Harmonic balance with `harmonics` and time integration at `omega`: both
/// period 1, the balance stable, and their extremes within 1 % of the
/// peak-to-peak. Returns both for the caller's further checks.
fn agree_within_a_percent(m: &Model, omega: f64, harmonics: usize) -> (BranchPoint, SteadyState) {
    let p = solve_at(m, omega, harmonics, Method::Aft, None);
    let ti = time_integration(m, omega);
    assert_eq!(ti.period, Some(1), "Omega {omega}");
    assert_eq!(p.stable, Some(true), "Omega {omega}");
    let d = discrepancy(&p, &ti);
    assert!(
        d < 0.01,
        "Omega {omega}: {:.3} % of the peak-to-peak",
        100.0 * d
    );
    (p, ti)
}

#[test]
fn gear_pair_hbm_agrees_with_time_integration_where_it_is_period_one_and_stable() {
    // The pair's default: TE 20 um, backlash 100 um; Omega 0.65 and 0.7 and
    // 1.9 lose contact once per period (single-sided impacts).
    let m = model(&["model=gear-pair"]);
    let mut impacts = 0;
    for omega in [0.35, 0.45, 0.65, 0.7, 1.9] {
        let (p, ti) = agree_within_a_percent(&m, omega, 15);
        assert_eq!(p.meshes[0].impact, ti.meshes[0].impact, "Omega {omega}");
        if p.meshes[0].impact != solver::steady::Impact::None {
            impacts += 1;
        }
    }
    assert!(impacts >= 3);
}

#[test]
fn ravigneaux_hbm_agrees_with_time_integration_on_every_mesh() {
    let m = model(&[]);
    let mut impacts = 0;
    for omega in [0.15, 0.3, 0.45] {
        let (p, ti) = agree_within_a_percent(&m, omega, 9);
        for (h, t) in p.meshes.iter().zip(&ti.meshes) {
            assert_eq!(h.impact, t.impact, "Omega {omega}");
        }
        if p.meshes
            .iter()
            .any(|m| m.impact != solver::steady::Impact::None)
        {
            impacts += 1;
        }
    }
    // Some meshes lose contact (single-sided impacts) at 0.3 and 0.45.
    assert!(impacts >= 2);
}

#[test]
fn time_integration_does_not_settle_on_an_unstable_branch() {
    // Gear pair at Omega 0.8 (period-1 branch past a period doubling) and the
    // Ravigneaux set at 0.8 (past a Neimark–Sacker point).
    for (m, omega) in [(model(&["model=gear-pair"]), 0.8), (model(&[]), 0.8)] {
        let p = solve_at(&m, omega, 9, Method::Aft, None);
        assert_eq!(p.stable, Some(false), "Omega {omega}");
        let ti = time_integration(&m, omega);
        let d = discrepancy(&p, &ti);
        assert!(
            ti.period != Some(1) || d > 0.05,
            "Omega {omega}: TI period {:?}, discrepancy {d}",
            ti.period
        );
    }
}

/// Up and down time-integration sweeps, each point starting from the last
/// one's end state; returns (omega, rel_min of the first mesh).
fn ti_sweep(m: &Model, omegas: &[f64]) -> Vec<(f64, f64)> {
    let mut state: Option<Vec<f64>> = None;
    omegas
        .iter()
        .map(|&omega| {
            let mut o = SteadyOptions::new(omega);
            o.transient_periods = 300;
            o.record_periods = 20;
            let s = steady_state(m, &o, state.as_deref()).expect("TI");
            state = Some(s.end_state.clone());
            (omega, s.meshes[0].rel_min_m)
        })
        .collect()
}

/// The interval where a sweep jumps most.
fn jump(sweep: &[(f64, f64)]) -> (f64, f64) {
    let w = sweep
        .windows(2)
        .max_by(|a, b| (a[1].1 - a[0].1).abs().total_cmp(&(b[1].1 - b[0].1).abs()))
        .unwrap();
    (w[0].0.min(w[1].0), w[0].0.max(w[1].0))
}

/// The Omegas of a branch's folds, in branch order.
fn fold_omegas(pts: &[BranchPoint]) -> Vec<f64> {
    pts.iter()
        .filter(|p| p.bifurcation == Some(Bifurcation::Fold))
        .map(|p| p.omega)
        .collect()
}

#[test]
fn continuation_passes_the_folds_where_the_sweeps_jump() {
    let m = model(&["model=gear-pair"]);
    let mut spec = FrfSpec::new(0.4, 0.7, 200);
    spec.harmonics = 7;
    let mut c = FrfContinuation::new(&m, spec).unwrap();
    let pts = branch(&mut c);
    // The branch turns back: Omega is not monotonic along it.
    let folds = fold_omegas(&pts);
    assert!(folds.len() >= 2, "folds {folds:?}");
    let upper = folds.iter().copied().fold(f64::MIN, f64::max);
    let lower = folds.iter().copied().fold(f64::MAX, f64::min);
    assert!(upper - lower > 0.05, "hysteresis band {lower}..{upper}");
    let up: Vec<f64> = (0..=30).map(|i| 0.4 + 0.01 * i as f64).collect();
    let down: Vec<f64> = up.iter().rev().copied().collect();
    let (a, b) = jump(&ti_sweep(&m, &up));
    assert!(
        a <= upper && upper <= b,
        "up sweep jumps in {a}..{b}, upper fold {upper}"
    );
    let (a, b) = jump(&ti_sweep(&m, &down));
    assert!(
        a <= lower && lower <= b,
        "down sweep jumps in {a}..{b}, lower fold {lower}"
    );
    assert!(c.stats.points as usize == pts.len());
}

#[test]
fn convergence_in_the_number_of_harmonics() {
    // Single-sided impacts at Omega 0.7: the error against H = 21 shrinks as
    // H grows (measured: 5.1e-2, 7.7e-4, 1.6e-4, 2.7e-5 of the peak-to-peak
    // for H = 1, 3, 7, 11: fast at first, then algebraic, as the force's
    // kinks at the contact switches limit the Fourier series' decay).
    let m = model(&["model=gear-pair"]);
    let reference = solve_at(&m, 0.7, 21, Method::Aft, None);
    let r = &reference.meshes[0];
    let pp = r.rel_max_m - r.rel_min_m;
    let errors: Vec<f64> = [1, 3, 7, 11]
        .iter()
        .map(|&h| {
            let p = solve_at(&m, 0.7, h, Method::Aft, None);
            let x = &p.meshes[0];
            ((x.rel_max_m - r.rel_max_m).abs()).max((x.rel_min_m - r.rel_min_m).abs()) / pp
        })
        .collect();
    eprintln!("H = 1, 3, 7, 11 against H = 21: {errors:?}");
    for w in errors.windows(2) {
        assert!(w[1] < w[0], "errors {errors:?}");
    }
    assert!(errors[3] < 1e-4, "errors {errors:?}");
    assert!(errors[0] > 100.0 * errors[3], "errors {errors:?}");
}

#[test]
fn seed_describing_function_equals_aft_at_one_harmonic() {
    // Same approximation; the AFT quadrature of the kinked force converges
    // as the grid grows (a 4096-point grid reaches about 1e-7 of the amplitude).
    let m = model(&["model=gear-pair"]);
    for omega in [0.35, 0.7, 1.2, 1.9] {
        let df = solve_at(&m, omega, 1, Method::DescribingFunction, None);
        let aft = solve_at(&m, omega, 1, Method::Aft, Some(4096));
        for (a, b) in df.coefficients.iter().zip(&aft.coefficients) {
            let scale = 1.0 + df.coefficients.iter().fold(0.0f64, |s, v| s.max(v.abs()));
            assert!((a - b).abs() < 1e-5 * scale, "Omega {omega}: {a} vs {b}");
        }
    }
}

#[test]
fn bad_options_are_rejected_with_the_option_named() {
    let m = model(&[]);
    let mut spec = FrfSpec::new(0.5, 0.4, 100);
    let e = FrfContinuation::new(&m, spec.clone())
        .unwrap_err()
        .to_string();
    assert!(e.contains("omega-to"), "{e}");
    spec.omega_to = 1.0;
    spec.harmonics = 0;
    let e = FrfContinuation::new(&m, spec.clone())
        .unwrap_err()
        .to_string();
    assert!(e.contains("harmonics"), "{e}");
    spec.harmonics = 3;
    spec.method = Method::DescribingFunction;
    let e = FrfContinuation::new(&m, spec.clone())
        .unwrap_err()
        .to_string();
    assert!(e.contains("describing-function"), "{e}");
    spec.method = Method::Aft;
    spec.omega_from = f64::NAN;
    let e = FrfContinuation::new(&m, spec).unwrap_err().to_string();
    assert!(e.contains("omega-from"), "{e}");
}

#[test]
fn downward_continuation_retraces_the_upward_branch() {
    let m = model(&["model=gear-pair"]);
    let run = |direction| {
        let mut spec = FrfSpec::new(1.2, 1.9, 100);
        spec.harmonics = 5;
        spec.direction = direction;
        let mut c = FrfContinuation::new(&m, spec).unwrap();
        branch(&mut c)
    };
    let up = run(Direction::Up);
    let down = run(Direction::Down);
    assert!((up[0].omega - 1.2).abs() < 1e-12 && (down[0].omega - 1.9).abs() < 1e-12);
    assert!((up.last().unwrap().omega - 1.9).abs() < 1e-9);
    assert!((down.last().unwrap().omega - 1.2).abs() < 1e-9);
    // The same solution at both ends.
    let a = &up.last().unwrap().meshes[0];
    let b = &down[0].meshes[0];
    assert!((a.rel_max_m - b.rel_max_m).abs() < 1e-9 && (a.rel_min_m - b.rel_min_m).abs() < 1e-9);
}

#[test]
fn continuation_crosses_the_first_modes_resonance_zone() {
    // Near Omega 0.21 the branch of the compound set is nearly vertical (the
    // first mode's damping ratio is 0.0024) and contact is lost; a coarse AFT
    // grid stalls Newton there (H = 3 and H = 5, TE 20 and 30 um).
    for (te, h) in [("te_um=20", 3), ("te_um=30", 5)] {
        let m = model(&[te]);
        let mut spec = FrfSpec::new(0.1, 0.5, 60);
        spec.harmonics = h;
        spec.stability = false;
        let mut c = FrfContinuation::new(&m, spec).unwrap();
        let pts = branch(&mut c);
        let last = pts.last().unwrap().omega;
        assert!((last - 0.5).abs() < 1e-9, "{te}, H = {h}: ended at {last}");
    }
}

#[test]
fn exact_integration_agrees_with_fine_aft_on_both_models() {
    // Two different evaluations of the same balance: closed-form integrals
    // between the contact switches, and quadrature on a fine grid.
    for (m, omega) in [
        (model(&["model=gear-pair"]), 0.7),
        (model(&["model=gear-pair"]), 1.9),
        (model(&[]), 0.3),
        (model(&["backlash_um=50"]), 0.45),
    ] {
        let e = solve_at(&m, omega, 7, Method::Exact, None);
        let a = solve_at(&m, omega, 7, Method::Aft, Some(1 << 12));
        let scale = e.coefficients.iter().fold(0.0f64, |s, v| s.max(v.abs()));
        for (x, y) in e.coefficients.iter().zip(&a.coefficients) {
            assert!((x - y).abs() < 1e-5 * scale, "Omega {omega}: {x} vs {y}");
        }
        assert_eq!(e.stable, a.stable);
    }
}

#[test]
fn sequential_phasing_branch_crosses_the_range_and_turning_back_is_reported() {
    // Five planet pairs with sequential phasing (no symmetric reduction):
    // the exact method follows the branch across the first mode's zone.
    let m = model(&["planets=5", "phasing=sequential"]);
    let mut spec = FrfSpec::new(0.1, 0.5, 100);
    spec.stability = false;
    let mut c = FrfContinuation::new(&m, spec).unwrap();
    let pts = branch(&mut c);
    assert!((pts.last().unwrap().omega - 0.5).abs() < 1e-9);
    assert!(!c.left_at_start());
    // The gear pair from inside its hysteresis band (0.49..0.60): the
    // branch found at 0.55 ends at the upper fold, turns back and leaves
    // the range through 0.55, which the continuation reports, and restarts
    // from 0.7 downward to cover the rest of the range.
    let m = model(&["model=gear-pair"]);
    let mut spec = FrfSpec::new(0.55, 0.7, 100);
    spec.harmonics = 7;
    spec.stability = false;
    let mut c = FrfContinuation::new(&m, spec).unwrap();
    let pts = branch(&mut c);
    let first: Vec<&BranchPoint> = pts.iter().filter(|p| p.piece == 0).collect();
    assert!(first.last().unwrap().omega < 0.55);
    let folds: Vec<f64> = first
        .iter()
        .filter(|p| p.bifurcation == Some(Bifurcation::Fold))
        .map(|p| p.omega)
        .collect();
    assert_eq!(folds.len(), 1);
    assert!((0.59..0.62).contains(&folds[0]), "{folds:?}");
    let r = c.restarts();
    assert_eq!(r.len(), 1, "{r:?}");
    assert_eq!(r[0].reason, PieceEnd::TurnedBack);
    assert!((r[0].start_omega - 0.7).abs() < 1e-12 && r[0].direction == Direction::Down);
    assert!(c.notes()[0].contains("turned back"), "{:?}", c.notes());
    // The second piece starts at 0.7 and reaches below the upper fold.
    let second: Vec<&BranchPoint> = pts.iter().filter(|p| p.piece == 1).collect();
    assert!((second[0].omega - 0.7).abs() < 1e-12);
    assert!(second.last().unwrap().omega < folds[0]);
    assert!(!c.left_at_start());
}

#[test]
fn geometric_step_control_halves_the_points_and_keeps_the_folds() {
    // The gear pair's hysteresis band at H = 7: the step control on the
    // predictor-corrector distance and the tangent's turn against the
    // control on the corrector's iterations, on the same branch. The
    // iterations control locates a fold only to within its step and needs
    // 200 nominal points; the geometry control locates folds on the
    // branch, and its `points` only caps the Omega step (at 0.006 here).
    let m = model(&["model=gear-pair"]);
    let run = |control, points| {
        let mut spec = FrfSpec::new(0.4, 0.7, points);
        spec.harmonics = 7;
        spec.step_control = control;
        let mut c = FrfContinuation::new(&m, spec).unwrap();
        let pts = branch(&mut c);
        let folds = fold_omegas(&pts);
        (pts, folds)
    };
    let (new, new_folds) = run(StepControl::Geometry, 50);
    let (old, old_folds) = run(StepControl::Iterations, 200);
    eprintln!(
        "points {} (before {}), folds {new_folds:?} (before {old_folds:?})",
        new.len(),
        old.len()
    );
    assert_eq!(new_folds.len(), 2);
    assert_eq!(old_folds.len(), 2);
    for (a, b) in new_folds.iter().zip(&old_folds) {
        assert!((a - b).abs() < 1e-4, "fold {a} vs {b} before");
    }
    assert!(2 * new.len() <= old.len(), "{} vs {}", new.len(), old.len());
    // A located fold is a turning point: both neighbours lie on the same
    // side of it in Omega.
    for (i, p) in new.iter().enumerate() {
        if p.bifurcation == Some(Bifurcation::Fold) {
            let (a, b) = (new[i - 1].omega - p.omega, new[i + 1].omega - p.omega);
            assert!(a * b > 0.0, "fold at {} not a turning point", p.omega);
        }
    }
}

#[test]
fn advance_returns_at_most_the_points_asked_for() {
    // A located fold and the point after it come from one step: with
    // `advance(1)` the second waits for the next call, and the branch is
    // the same as in chunks of 64.
    let m = model(&["model=gear-pair"]);
    let spec = || {
        let mut s = FrfSpec::new(0.45, 0.65, 40);
        s.harmonics = 3;
        s.stability = false;
        s
    };
    let mut c = FrfContinuation::new(&m, spec()).unwrap();
    let mut one_by_one = Vec::new();
    while !c.is_finished() {
        let pts = c.advance(1).unwrap();
        assert!(pts.len() <= 1);
        one_by_one.extend(pts);
    }
    let chunked = branch(&mut FrfContinuation::new(&m, spec()).unwrap());
    assert!(
        one_by_one
            .iter()
            .filter(|p| p.bifurcation == Some(Bifurcation::Fold))
            .count()
            >= 2
    );
    assert_eq!(one_by_one, chunked);
}

#[test]
fn sampled_stability_gives_every_point_the_flags_and_labels_of_the_monodromy_at_every_point() {
    // The gear pair's band at H = 7 (two folds, an unstable middle branch)
    // and the Duffing oscillator: the monodromy on every fourth point, with
    // changes located by bisection, against the monodromy at every point.
    let m = model(&["model=gear-pair"]);
    let run = |stride| {
        let mut spec = FrfSpec::new(0.4, 0.7, 50);
        spec.harmonics = 7;
        spec.stability_stride = stride;
        let mut c = FrfContinuation::new(&m, spec).unwrap();
        let pts = branch(&mut c);
        (pts, c.stats.monodromies)
    };
    let (every, n_every) = run(1);
    let (sampled, n_sampled) = run(4);
    assert_eq!(n_every as usize, every.len());
    assert!(n_sampled < n_every, "{n_sampled} vs {n_every}");
    assert!(every.iter().any(|p| p.stable == Some(false)));
    assert_eq!(every.len(), sampled.len());
    for (a, b) in every.iter().zip(&sampled) {
        assert_eq!(a.omega, b.omega);
        assert_eq!(a.stable, b.stable, "Omega {}", a.omega);
        assert_eq!(a.bifurcation, b.bifurcation, "Omega {}", a.omega);
    }
    assert!(FrfSpec {
        stability_stride: 0,
        ..FrfSpec::new(0.4, 0.7, 50)
    }
    .validate()
    .is_err());
}

#[test]
fn sampled_stability_sees_the_one_point_window_between_period_doublings() {
    // The compound set's default branch at H = 7 (Omega 0.1 to 0.5): next
    // to Omega 0.214 the largest multiplier crosses -1 inward, a second
    // one crosses out and back one point later (spectral radius 1.0046,
    // 0.9936, 1.0074, 0.9920 at four consecutive points), a stable window
    // one point wide. Sampling every fourth point missed it (two points'
    // flags and labels differed); intervals whose ends lie within 1 % of
    // the unit circle are now split, so every flag and label agrees with
    // the monodromy at every point, at a third of the monodromies.
    let m = model(&[]);
    let run = |stride| {
        let mut spec = FrfSpec::new(0.1, 0.5, 50);
        spec.harmonics = 7;
        spec.step_control = StepControl::Geometry;
        spec.stability_stride = stride;
        let mut c = FrfContinuation::new(&m, spec).unwrap();
        let pts = branch(&mut c);
        (pts, c.stats.monodromies)
    };
    let (every, n_every) = run(1);
    let (sampled, n_sampled) = run(4);
    assert!(3 * n_sampled < 2 * n_every, "{n_sampled} vs {n_every}");
    assert_eq!(every.len(), sampled.len());
    let window = every.windows(3).any(|w| {
        w[0].stable == Some(false) && w[1].stable == Some(true) && w[2].stable == Some(false)
    });
    assert!(window, "the one-point stable window is on the branch");
    for (a, b) in every.iter().zip(&sampled) {
        assert_eq!(a.stable, b.stable, "Omega {}", a.omega);
        assert_eq!(a.bifurcation, b.bifurcation, "Omega {}", a.omega);
    }
}

/// The largest amplitude of mesh `j`'s x over the points of a branch in
/// `(lo, hi)`.
fn peak_in(points: &[BranchPoint], j: usize, lo: f64, hi: f64) -> f64 {
    points
        .iter()
        .filter(|p| p.omega > lo && p.omega < hi)
        .map(|p| {
            p.meshes[j]
                .delta_amplitude_m
                .max(p.meshes[j].rel_max_m - p.meshes[j].rel_min_m)
        })
        .fold(0.0, f64::max)
}

/// A resonance far narrower than the step is never stepped over: Fig. 2's
/// linear set (no backlash) has a first mode with a damping ratio of
/// 0.0024, a peak 0.001 wide in Ω at 0.231. A coarse branch (8 nominal
/// points over Ω 0.1-2, a step of 0.24) finds the same peak as a fine one
/// (2 000 points over 0.2-0.26), within 2 %, at every TE: the step control
/// follows the curve's turn, not the nominal step.
#[test]
fn a_narrow_resonance_is_never_stepped_over() {
    for te in ["te_um=5", "te_um=15", "te_um=30"] {
        let m = model(&["backlash_um=0", "te_meshes=all", te]);
        let run = |from: f64, to: f64, points: u32| {
            let mut spec = FrfSpec::new(from, to, points);
            spec.harmonics = 3;
            let mut c = FrfContinuation::new(&m, spec).expect("spec");
            branch(&mut c)
        };
        let coarse = run(0.1, 2.0, 8);
        let fine = run(0.2, 0.26, 2000);
        let (a, b) = (peak_in(&coarse, 0, 0.2, 0.26), peak_in(&fine, 0, 0.2, 0.26));
        assert!(
            b > 0.0 && (a - b).abs() <= 0.02 * b,
            "{te}: coarse {a:e}, fine {b:e}"
        );
    }
}

/// Every point of a branch solves the balance: the residual at the
/// coefficients it reports, evaluated anew, is within the corrector's
/// bound (1e-6 of the solution's scale, in micrometres), wherever its
/// stopping rule (a tiny last step, or the contraction of the last two
/// bounding the error left) accepted it. On the benchmark sweep (the
/// default compound set, Omega 0.1-0.5, H = 7), through its folds,
/// impacts and stability changes.
#[test]
fn every_branch_point_solves_the_balance_it_reports() {
    let m = model(&[]);
    let mut spec = FrfSpec::new(0.1, 0.5, 400);
    spec.harmonics = 7;
    spec.stability = false;
    let mut c = FrfContinuation::new(&m, spec).expect("spec");
    let pts = branch(&mut c);
    assert!(pts.len() > 400, "{} points", pts.len());
    let mut asm = c.assembly().clone();
    let mut r = vec![0.0; asm.n_x()];
    let mut worst: f64 = 0.0;
    for p in &pts {
        asm.evaluate(&p.coefficients, p.omega, &mut r, None);
        let scale = 1.0 + p.coefficients.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
        let res = r.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
        worst = worst.max(res / scale);
        assert!(
            res <= 1e-6 * scale,
            "Omega {}: residual {res:e} against a scale of {scale}",
            p.omega
        );
    }
    eprintln!(
        "{} points, largest residual {worst:e} of the scale",
        pts.len()
    );
}
