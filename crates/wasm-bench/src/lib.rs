//! The workloads of `gearshock bench`, callable from JavaScript.
//!
//! `scripts/bench-wasm.mjs` builds this crate for `wasm32-unknown-unknown`,
//! binds it for node with wasm-bindgen, times each workload there (the
//! solver has no clock; timing is the caller's) and compares the medians
//! with the native `gearshock bench`. The workloads are the same code and
//! inputs in both: the default model's HBM frequency response over Omega
//! 0.1..2, one steady-state run at Omega 0.5, a bifurcation sweep and a
//! regime map.

use solver::hbm::{FrfContinuation, FrfSpec};
use solver::map::{MapSpec, RegimeMap};
use solver::params::ModelParams;
use solver::steady::{steady_state, Model, SteadyOptions};
use solver::sweep::{BifurcationSweep, SweepSpec};

/// The frequency response of the default model over Omega 0.1 ..= 2 with
/// `points` nominal points and `harmonics` harmonics; returns the number of
/// branch points, or -1 on a solver failure.
pub fn frf_branch_points(harmonics: u32, points: u32, stability: bool) -> i32 {
    let run = || -> solver::Result<usize> {
        let model = Model::new(&ModelParams::default())?;
        let mut spec = FrfSpec::new(0.1, 2.0, points);
        spec.harmonics = harmonics as usize;
        spec.stability = stability;
        let mut c = FrfContinuation::new(&model, spec)?;
        let mut n = 0;
        while !c.is_finished() {
            n += c.advance(64)?.len();
        }
        Ok(n)
    };
    run().map_or(-1, |n| i32::try_from(n).unwrap_or(i32::MAX))
}

/// One steady state of the default model at `omega` with the given periods;
/// returns the transient periods run, or -1 on a solver failure.
pub fn simulate_periods(omega: f64, transient: u32, record: u32) -> i32 {
    let run = || -> solver::Result<u32> {
        let model = Model::new(&ModelParams::default())?;
        let mut o = SteadyOptions::new(omega);
        o.transient_periods = transient;
        o.record_periods = record;
        o.history_meshes = vec![0];
        Ok(steady_state(&model, &o, None)?.stats.transient_periods_run)
    };
    run().map_or(-1, |n| i32::try_from(n).unwrap_or(i32::MAX))
}

/// A single-chain bifurcation sweep of the default model over Omega
/// 0.05 ..= 2 with `points` points of 300 + 100 periods, as `gearshock
/// bench` runs it; returns the number of points that failed (-1 if the
/// sweep could not start).
pub fn sweep_failures(points: u32) -> i32 {
    let run = || -> solver::Result<i32> {
        let model = Model::new(&ModelParams::default())?;
        let spec = SweepSpec::new(0.05, 2.0, points);
        let mut sweep = BifurcationSweep::new(model, spec)?;
        let pts = sweep.advance(points as usize);
        Ok(pts.iter().filter(|p| p.error.is_some()).count() as i32)
    };
    run().unwrap_or(-1)
}

/// A regime map of the default model over Omega 0.1 ..= 2 (`columns`
/// points) and backlash 10 ..= 200 um (`rows` points), 300 + 100 periods
/// per cell, as `gearshock bench` runs it; returns the number of failed
/// cells (-1 if the map could not start).
pub fn map_failures(columns: u32, rows: u32) -> i32 {
    let spec = MapSpec::new((0.1, 2.0, columns), "backlash_um", (10.0, 200.0, rows));
    match RegimeMap::new(&ModelParams::default(), spec) {
        Ok(mut map) => {
            let mut failed = 0;
            while !map.is_finished() {
                failed += map.advance(64).iter().filter(|c| c.error.is_some()).count();
            }
            i32::try_from(failed).unwrap_or(i32::MAX)
        }
        Err(_) => -1,
    }
}

#[cfg(target_arch = "wasm32")]
mod exports {
    //! The wasm-bindgen exports (wasm32 only).
    use wasm_bindgen::prelude::wasm_bindgen;

    /// See [`crate::frf_branch_points`].
    #[wasm_bindgen]
    pub fn frf(harmonics: u32, points: u32, stability: bool) -> i32 {
        crate::frf_branch_points(harmonics, points, stability)
    }

    /// See [`crate::sweep_failures`].
    #[wasm_bindgen]
    pub fn sweep(points: u32) -> i32 {
        crate::sweep_failures(points)
    }

    /// See [`crate::map_failures`].
    #[wasm_bindgen]
    pub fn map(columns: u32, rows: u32) -> i32 {
        crate::map_failures(columns, rows)
    }

    /// See [`crate::simulate_periods`].
    #[wasm_bindgen]
    pub fn simulate(omega: f64, transient: u32, record: u32) -> i32 {
        crate::simulate_periods(omega, transient, record)
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn workloads_run_natively() {
        assert!(super::frf_branch_points(1, 20, false) > 20);
        assert_eq!(super::simulate_periods(0.5, 5, 2), 5);
        assert_eq!(super::sweep_failures(2), 0);
        assert_eq!(super::map_failures(2, 1), 0);
    }
}
