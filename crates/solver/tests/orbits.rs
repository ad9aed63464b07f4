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
