//! Periodic branches by shooting continuation against harmonic balance on
//! the single gear pair (the Kahraman–Singh form): the same folds, and
//! period doublings where an independent shooting run finds a multiplier
//! at -1.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use solver::bifurcation::Bifurcation;
use solver::hbm::{FrfContinuation, FrfSpec};
use solver::keys;
use solver::orbits::{ShootFrfSpec, ShootPoint, ShootingContinuation};
use solver::params::ModelParams;
use solver::shooting::{shoot, ShootOptions, ShootOutcome};
use solver::Model;

fn gear_pair() -> Model {
    let mut p = ModelParams::default();
    keys::set_assignment(&mut p, "model=gear-pair").unwrap();
    Model::new(&p).unwrap()
}

fn shooting_branch(m: &Model) -> Vec<ShootPoint> {
    let mut c = ShootingContinuation::new(m, ShootFrfSpec::new(0.3, 1.5, 200)).unwrap();
    let mut pts = vec![c.first_point().unwrap()];
    while !c.is_finished() {
        pts.extend(c.advance(16).unwrap());
    }
    pts
}

#[test]
fn shooting_folds_agree_with_harmonic_balance_and_doublings_sit_at_minus_one() {
    let m = gear_pair();
    let mut spec = FrfSpec::new(0.3, 1.5, 200);
    spec.harmonics = 9;
    let mut hbm = FrfContinuation::new(&m, spec).unwrap();
    let mut hbm_folds = Vec::new();
    while !hbm.is_finished() {
        for p in hbm.advance(32).unwrap() {
            if p.bifurcation == Some(Bifurcation::Fold) {
                hbm_folds.push(p.omega);
            }
        }
    }
    assert!(hbm_folds.len() >= 2, "{hbm_folds:?}");
    let pts = shooting_branch(&m);
    let of = |b: Bifurcation, period: u32| -> Vec<f64> {
        pts.iter()
            .filter(|p| p.period == period && p.point.bifurcation == Some(b))
            .map(|p| p.point.omega)
            .collect()
    };
    let folds = of(Bifurcation::Fold, 1);
    assert_eq!(folds.len(), hbm_folds.len(), "{folds:?} vs {hbm_folds:?}");
    for f in &hbm_folds {
        let nearest = folds
            .iter()
            .map(|g| (g - f).abs())
            .fold(f64::INFINITY, f64::min);
        assert!(nearest <= 1e-4, "HBM fold {f}: shooting {folds:?}");
    }
    // Each located period doubling: a fresh shooting run at its Omega,
    // from its orbit, finds a real multiplier within 1e-4 of -1.
    let pds: Vec<&ShootPoint> = pts
        .iter()
        .filter(|p| p.period == 1 && p.point.bifurcation == Some(Bifurcation::PeriodDoubling))
        .collect();
    assert!(!pds.is_empty());
    let mut opts = ShootOptions::new(1);
    opts.rtol = 1e-11;
    for p in pds {
        let red = solver::shooting::Reduced::new(&m, p.point.omega);
        let start = red.to_state(&p.point.coefficients, (0.0, 0.0));
        let ShootOutcome::Converged(o) = shoot(&m, p.point.omega, &start, &opts).unwrap() else {
            panic!("no orbit at the period doubling {}", p.point.omega);
        };
        let nearest = o
            .multipliers
            .unwrap()
            .values
            .iter()
            .map(|v| (v - nalgebra::Complex::new(-1.0, 0.0)).norm())
            .fold(f64::INFINITY, f64::min);
        assert!(
            nearest <= 1e-4,
            "Omega {}: nearest multiplier {nearest:e} from -1",
            p.point.omega
        );
    }
    // The period-doubled branches are followed.
    assert!(pts.iter().any(|p| p.period == 2));
}

/// The mesh-space distance (µm) between two full states at `omega`.
fn distance_um(m: &Model, omega: f64, a: &[f64], b: &[f64]) -> f64 {
    let red = solver::shooting::Reduced::new(m, omega);
    let (za, _) = red.from_state(a);
    let (zb, _) = red.from_state(b);
    let d: Vec<f64> = za.iter().zip(&zb).map(|(x, y)| x - y).collect();
    red.mesh_norm_um(&d)
}

/// Folds located to 1e-6 in Omega, period doublings to 1e-4, checked by
/// brackets that do not use the continuation: 1e-6 on the branch's side of
/// a fold, Newton from the fold's orbit finds a period-1 orbit next to it,
/// and 1e-6 beyond it finds none nearby (a fold has orbits on one side
/// only); 1e-4 either side of a period doubling, fresh shooting runs find
/// the real multiplier on either side of -1.
#[test]
fn folds_are_located_to_1e_6_and_period_doublings_to_1e_4() {
    let m = gear_pair();
    let pts = shooting_branch(&m);
    let mut opts = ShootOptions::new(1);
    opts.rtol = 1e-11;
    opts.max_iterations = 30;
    let mut folds = 0;
    for (i, p) in pts.iter().enumerate() {
        if p.period != 1 || p.point.bifurcation != Some(Bifurcation::Fold) {
            continue;
        }
        folds += 1;
        let w = p.point.omega;
        let before = pts[..i].iter().rev().find(|q| q.period == 1).unwrap();
        let inside = (before.point.omega - w).signum();
        let state = |q: &ShootPoint| {
            solver::shooting::Reduced::new(&m, q.point.omega)
                .to_state(&q.point.coefficients, (0.0, 0.0))
        };
        let fold_state = state(p);
        let starts = [state(before), fold_state.clone()];
        let span_um = (p.point.meshes[0].delta_max_m - p.point.meshes[0].delta_min_m) * 1e6;
        // The smallest distance (over the two starts) from the fold's orbit
        // of an orbit that Newton finds at `omega`, as a part of the span.
        let nearest = |omega: f64| -> Option<f64> {
            starts
                .iter()
                .filter_map(|s| match shoot(&m, omega, s, &opts).unwrap() {
                    ShootOutcome::Converged(o) => {
                        Some(distance_um(&m, omega, &o.start_state, &fold_state) / span_um)
                    }
                    ShootOutcome::Failed(_) => None,
                })
                .reduce(f64::min)
        };
        let d_in = nearest(w + inside * 1e-6);
        assert!(
            d_in.is_some_and(|d| d < 0.05),
            "fold {w}: 1e-6 inside, {d_in:?}"
        );
        let d_out = nearest(w - inside * 1e-6);
        assert!(
            d_out.is_none_or(|d| d > 0.05),
            "fold {w}: an orbit 1e-6 beyond it ({d_out:?})"
        );
    }
    assert_eq!(folds, 2);
    let mut doublings = 0;
    for p in pts
        .iter()
        .filter(|p| p.period == 1 && p.point.bifurcation == Some(Bifurcation::PeriodDoubling))
    {
        doublings += 1;
        let w = p.point.omega;
        let red = solver::shooting::Reduced::new(&m, w);
        let start = red.to_state(&p.point.coefficients, (0.0, 0.0));
        let most_negative = |omega: f64| -> f64 {
            let ShootOutcome::Converged(o) = shoot(&m, omega, &start, &opts).unwrap() else {
                panic!("no orbit at Omega {omega}");
            };
            o.multipliers
                .unwrap()
                .values
                .iter()
                .filter(|v| v.im.abs() < 1e-9)
                .map(|v| v.re)
                .fold(f64::INFINITY, f64::min)
        };
        let (lo, hi) = (most_negative(w - 1e-4), most_negative(w + 1e-4));
        assert!(
            (lo + 1.0) * (hi + 1.0) < 0.0,
            "period doubling {w}: multipliers {lo} and {hi} at +-1e-4"
        );
    }
    assert!(doublings >= 2);
}

/// The branch computed in slices of a few hundred integrator steps (each
/// call returning whatever points it finished) is the branch computed in
/// one go, bit for bit: a paused step is taken up again, not restarted
/// differently; and the slices really are short (most calls finish no
/// point).
#[test]
fn a_sliced_continuation_gives_the_same_points() {
    let m = gear_pair();
    let whole = shooting_branch(&m);
    let mut c = ShootingContinuation::new(&m, ShootFrfSpec::new(0.3, 1.5, 200)).unwrap();
    let mut sliced = vec![c.first_point().unwrap()];
    let (mut calls, mut empty) = (0, 0);
    while !c.is_finished() {
        let got = c.advance_within(1, 400).unwrap();
        calls += 1;
        empty += usize::from(got.is_empty());
        sliced.extend(got);
        assert!(calls < 1_000_000, "no progress");
    }
    assert_eq!(sliced, whole);
    assert!(empty > 2 * whole.len(), "{empty} empty calls of {calls}");
}

/// A failed evaluation of the map (here within the first points of the
/// compound set's default branch at 10 nominal points, whose long steps
/// predict far out of range) is replayed as the same failure: before, it
/// was integrated anew in every slice and the evaluation after it never
/// got past its first slice, so the page's branches hung at 36 points.
/// The first 40 points, sliced as the page's worker slices them, equal the
/// one-shot run's.
#[test]
fn a_sliced_continuation_gets_past_a_failed_evaluation() {
    let m = Model::new(&ModelParams::default()).unwrap();
    let spec = || ShootFrfSpec::new(0.1, 2.0, 10);
    let mut c = ShootingContinuation::new(&m, spec()).unwrap();
    let mut whole = vec![c.first_point().unwrap()];
    while !c.is_finished() && whole.len() < 40 {
        whole.extend(c.advance(1).unwrap());
    }
    assert!(whole.len() >= 40, "{} points", whole.len());
    // The path does meet a failure, so the replay of one is what is tested.
    let failed = c.stats.failed_evaluations;
    assert!(failed >= 1, "{:?}", c.stats);
    let mut c = ShootingContinuation::new(&m, spec()).unwrap();
    let mut sliced = vec![c.first_point().unwrap()];
    let mut calls = 0;
    while !c.is_finished() && sliced.len() < 40 {
        sliced.extend(c.advance_within(1, 3000).unwrap());
        calls += 1;
        assert!(calls < 20_000, "no progress after {} points", sliced.len());
    }
    assert_eq!(sliced[..40], whole[..40]);
    assert_eq!(c.stats.failed_evaluations, failed, "{:?}", c.stats);
}

/// On the compound set's default branch, at the command line's default
/// resolution (400 nominal points) the branch passes the resonances' first four folds
/// the harmonic balance finds, in its order, each within 2e-3 in Omega (H
/// = 7 against the exact orbits): the corrector's path once retraced
/// itself at the third (Omega 0.2167) and went back to the start. At the
/// page's resolution (100) its first 300 points (the page's cap) reach
/// past Omega 0.5.
#[test]
fn the_compound_sets_branch_follows_the_harmonic_balances_folds() {
    let m = Model::new(&ModelParams::default()).unwrap();
    let mut spec = FrfSpec::new(0.1, 0.6, 200);
    spec.harmonics = 7;
    let mut hbm = FrfContinuation::new(&m, spec).unwrap();
    let mut hbm_folds = Vec::new();
    while !hbm.is_finished() && hbm_folds.len() < 4 {
        for p in hbm.advance(32).unwrap() {
            if p.bifurcation == Some(Bifurcation::Fold) {
                hbm_folds.push(p.omega);
            }
        }
    }
    hbm_folds.truncate(4);
    assert_eq!(hbm_folds.len(), 4, "{hbm_folds:?}");
    let fold = |p: &ShootPoint| p.period == 1 && p.point.bifurcation == Some(Bifurcation::Fold);
    // The points up to the first `folds` folds, at most `cap` of them.
    let first = |points: u32, folds: usize, cap: usize| {
        let mut c = ShootingContinuation::new(&m, ShootFrfSpec::new(0.1, 2.0, points)).unwrap();
        let mut pts = vec![c.first_point().unwrap()];
        while !c.is_finished() && pts.len() < cap && pts.iter().filter(|p| fold(p)).count() < folds
        {
            pts.extend(c.advance(1).unwrap());
        }
        pts
    };
    let folds: Vec<f64> = first(400, 4, 5_000)
        .iter()
        .filter(|p| fold(p))
        .map(|p| p.point.omega)
        .take(4)
        .collect();
    assert_eq!(folds.len(), 4, "{folds:?} vs {hbm_folds:?}");
    for (f, h) in folds.iter().zip(&hbm_folds) {
        assert!((f - h).abs() <= 2e-3, "{folds:?} vs {hbm_folds:?}");
    }
    let reach = first(100, usize::MAX, 300)
        .iter()
        .map(|p| p.point.omega)
        .fold(0.0, f64::max);
    assert!(reach > 0.5, "the first 300 points end at Omega {reach}");
}
