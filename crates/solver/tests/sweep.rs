//! Bifurcation sweeps: bounded work per call, continuation, and shards that
//! reproduce an unsharded run bit for bit.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use solver::params::ModelParams;
use solver::steady::Model;
use solver::sweep::{canonical_order, BifurcationSweep, Directions, SweepPoint, SweepSpec};

fn spec(chains: u32, shard: Option<u32>) -> SweepSpec {
    let mut s = SweepSpec::new(0.3, 1.6, 9);
    s.directions = Directions::Both;
    s.steady.transient_periods = 40;
    s.steady.record_periods = 8;
    s.chains = chains;
    s.shard = shard;
    s
}

fn run(spec: SweepSpec) -> Vec<SweepPoint> {
    let model = Model::new(&ModelParams::default()).expect("model");
    let mut sweep = BifurcationSweep::new(model, spec).expect("sweep");
    let mut out = Vec::new();
    let mut calls = 0;
    while !sweep.is_finished() {
        let batch = sweep.advance(2);
        assert!(batch.len() <= 2, "bounded work per call");
        out.extend(batch);
        calls += 1;
    }
    assert_eq!(sweep.done(), sweep.total());
    assert!(calls >= sweep.total() / 2);
    out
}

#[test]
fn shards_merged_equal_the_unsharded_run() {
    let mut whole = run(spec(3, None));
    let mut merged: Vec<SweepPoint> = (0..3).flat_map(|i| run(spec(3, Some(i)))).collect();
    canonical_order(&mut whole);
    canonical_order(&mut merged);
    assert_eq!(whole.len(), 18, "9 points up and 9 down");
    assert_eq!(whole, merged);
}

#[test]
fn canonical_order_is_up_ascending_then_down_descending() {
    let mut pts = run(spec(1, None));
    canonical_order(&mut pts);
    let omegas: Vec<f64> = pts.iter().map(|p| p.omega).collect();
    assert!(omegas[..9].windows(2).all(|w| w[0] < w[1]));
    assert!(omegas[9..].windows(2).all(|w| w[0] > w[1]));
    assert!(pts.iter().all(|p| p.error.is_none()));
}

#[test]
fn bad_specs_are_refused_with_the_option_named() {
    let model = Model::new(&ModelParams::default()).expect("model");
    let cases = [
        (SweepSpec::new(0.5, 0.2, 10), "omega-to"),
        (SweepSpec::new(0.0, 1.0, 10), "omega-from"),
        (SweepSpec::new(0.2, 1.0, 0), "points"),
        (SweepSpec::new(0.2, 1.0, 10_000_000), "points"),
        (spec(3, Some(3)), "shard"),
        (spec(20, None), "chains"),
    ];
    for (s, option) in cases {
        let e = BifurcationSweep::new(model.clone(), s)
            .expect_err(option)
            .to_string();
        assert!(e.contains(option), "{e}");
    }
}

#[test]
fn a_sweep_advanced_in_step_slices_gives_the_same_points() {
    // The page's worker advances a sweep a slice of integrator steps at a
    // time (`advance_steps`), pausing inside a steady state; every point,
    // and each chain's end state carried to its next point, must be the
    // bits of the point-by-point sweep.
    let model = Model::new(&solver::params::ModelParams::default()).expect("model");
    let mut spec = SweepSpec::new(0.7, 1.3, 6);
    spec.directions = Directions::Both;
    spec.chains = 2;
    spec.steady.transient_periods = 60;
    spec.steady.record_periods = 10;
    let mut whole = BifurcationSweep::new(model.clone(), spec.clone()).expect("sweep");
    let want = whole.advance(usize::MAX);
    assert_eq!(want.len(), 12);
    let mut sliced = BifurcationSweep::new(model, spec).expect("sweep");
    let mut got = Vec::new();
    let mut pauses = 0;
    while !sliced.is_finished() {
        match sliced.advance_steps(97) {
            Some(p) => got.push(p),
            None => pauses += 1,
        }
        assert!(pauses < 1_000_000, "the sweep never ends");
    }
    assert!(pauses > 12, "the slices never paused inside a steady state");
    assert_eq!(sliced.advance_steps(97), None);
    assert_eq!(got, want);
}
