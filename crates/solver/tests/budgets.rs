//! The work estimates the CLI's budgets check before a long computation
//! starts, against the work the computation then counts, on both models:
//! a boundary trace (work units, `BoundaryStats::work`), a shooting branch
//! (integration steps with the tangents' work, `ShootFrfStats::work_steps`)
//! and a regime map (integration steps of its cells, `RegimeMap::steps`).
//! Counted work, not time, so that a busy machine does not move them.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use solver::boundaries::{BoundarySpec, BoundaryTrace};
use solver::keys;
use solver::map::{MapSpec, RegimeMap};
use solver::orbits::{ShootFrfSpec, ShootingContinuation};
use solver::params::ModelParams;
use solver::steady::Model;

fn params(model: &str) -> ModelParams {
    let mut p = ModelParams::default();
    keys::set_assignment(&mut p, &format!("model={model}")).unwrap();
    p
}

/// Asserts that `estimate` is within a factor of 3 of `measured`.
fn within_3(what: &str, estimate: f64, measured: f64) {
    let ratio = estimate / measured;
    assert!(
        (1.0 / 3.0..=3.0).contains(&ratio),
        "{what}: estimated {estimate:.3e}, measured {measured:.3e} (ratio {ratio:.2})"
    );
}

#[test]
fn a_boundary_traces_estimate_is_within_3_of_its_work_on_both_models() {
    let cases = [
        // The gear pair's TE box: 7 curves.
        ("gear-pair", "te_um", (0.2, 40.0), (0.4, 1.3), 20, 7),
        // The compound set over the same Omega: 11 resonances, 20 curves.
        ("ravigneaux", "te_um", (0.0, 40.0), (0.4, 1.3), 10, 3),
        // Its backlash over Omega 0.5-1: 16 curves, no period doubling.
        ("ravigneaux", "backlash_um", (0.0, 200.0), (0.5, 1.0), 10, 3),
    ];
    for (model, key, values, omegas, points, harmonics) in cases {
        let mut spec = BoundarySpec::new(key, values, omegas);
        spec.levels = 2;
        spec.points = points;
        spec.harmonics = harmonics;
        let mut t = BoundaryTrace::new(&params(model), spec).unwrap();
        while !t.is_finished() {
            t.advance(64).unwrap();
        }
        within_3(
            &format!("{model} {key}: {} curves", t.curves().len()),
            t.estimated_work(),
            t.stats.work() as f64,
        );
    }
}

#[test]
fn a_shooting_branchs_estimate_is_within_3_of_its_work_on_both_models() {
    let cases = [
        // Through the primary resonance's fold and a doubled branch.
        ("gear-pair", (0.4, 1.3), 20),
        // No resonance.
        ("gear-pair", (1.3, 2.0), 20),
        // Two resonances, three pieces (two doubled).
        ("ravigneaux", (1.3, 2.0), 10),
    ];
    for (name, (from, to), points) in cases {
        let model = Model::new(&params(name)).unwrap();
        let spec = ShootFrfSpec::new(from, to, points);
        let estimate = spec.estimate(&model).unwrap();
        let mut c = ShootingContinuation::new(&model, spec).unwrap();
        c.first_point().unwrap();
        while !c.is_finished() {
            c.advance(16).unwrap();
        }
        within_3(
            &format!("{name} Omega {from}-{to}: {} points", c.stats.points),
            estimate.work(points),
            c.stats.work_steps as f64,
        );
    }
}

#[test]
fn a_maps_estimate_is_within_3_of_its_steps_on_both_models() {
    let cases = [
        ("gear-pair", "te_um", (0.4, 1.3, 8), (1.0, 40.0, 3)),
        ("gear-pair", "backlash_um", (0.3, 2.0, 10), (0.0, 200.0, 3)),
        // 39 cells of 60 not periodic.
        (
            "ravigneaux",
            "backlash_um",
            (0.1, 2.0, 12),
            (10.0, 200.0, 5),
        ),
    ];
    for (name, key, omegas, values) in cases {
        let mut spec = MapSpec::new(omegas, key, values);
        spec.steady.transient_periods = 300;
        spec.steady.record_periods = 100;
        let mut map = RegimeMap::new(&params(name), spec).unwrap();
        let (estimate, _) = map.estimated_steps(None).unwrap();
        while !map.is_finished() {
            map.advance(16);
        }
        within_3(&format!("{name} {key} map"), estimate, map.steps() as f64);
    }
}
