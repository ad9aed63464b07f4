//! Models and run options as the solver's tests write them: a model from
//! key assignments (`"model=gear-pair"`, `"backlash_um=50"`, checked as the
//! CLI's `--set` checks them), and a steady-state run at fixed lengths and
//! tight tolerances (no early settling), the set-up of every comparison
//! with a closed form or a reference integration.

use solver::keys;
use solver::params::ModelParams;
use solver::steady::{Model, SteadyOptions};

/// The default parameters with `assignments` applied.
pub fn params(assignments: &[&str]) -> ModelParams {
    let mut p = ModelParams::default();
    for a in assignments {
        keys::set_assignment(&mut p, a).expect(a);
    }
    p
}

/// The model of the default parameters with `assignments` applied.
pub fn model(assignments: &[&str]) -> Model {
    Model::new(&params(assignments)).expect("model")
}

/// A steady-state run at `omega` of exactly `transient` then `record`
/// mesh periods (no early settling), at relative tolerance `rtol` and
/// absolute tolerance `atol_m`.
pub fn strict_run(
    omega: f64,
    (transient, record): (u32, u32),
    (rtol, atol_m): (f64, f64),
) -> SteadyOptions {
    let mut o = SteadyOptions::new(omega);
    o.transient_periods = transient;
    o.record_periods = record;
    o.early_settle = false;
    o.rtol = rtol;
    o.atol_m = atol_m;
    o
}

/// Drives a run in slices of at most `slice` integrator steps until it
/// ends: `advance(slice)` takes one slice and returns the result once
/// there is one, and the steps that slice took (checked against `slice`).
/// Returns the result and the number of pauses.
pub fn in_slices<T>(slice: u64, mut advance: impl FnMut(u64) -> (Option<T>, u64)) -> (T, u64) {
    let mut pauses = 0;
    loop {
        let (out, took) = advance(slice);
        assert!(
            took <= slice,
            "a slice took {took} steps, more than {slice}"
        );
        if let Some(x) = out {
            return (x, pauses);
        }
        pauses += 1;
        assert!(pauses < 10_000_000, "the run never ends");
    }
}
