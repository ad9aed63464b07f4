//! Caps on the work and memory of one command (one shard of a sharded
//! run), checked before any work: each option has its own range, and these
//! bound their product, so no combination runs for days or fills memory
//! before writing anything.
//!
//! Work is counted in integration steps, not mesh periods: the adaptive
//! Dormand–Prince step is held below its stability limit by the stiffest
//! mode, so a period costs about [`ACCURACY_STEPS`] steps at ordinary
//! settings plus `2 pi Omega_top / (STABILITY_LIMIT Omega)`, where
//! `Omega_top` is the highest natural frequency of the modal analysis (a
//! 1e12 N/m planet-planet stiffness raises it from 1.5 to 35, and a period
//! at Omega 0.1 from 67 to 880 steps, both measured).

use crate::failure::{usage, Failure};
use solver::steady::Model;
use std::f64::consts::PI;

/// Most integration steps one command may take: about 10^8 mesh periods
/// of the default model (some hours on one core at about 1 us a step;
/// split larger runs with `--shard`).
pub const MAX_STEPS: f64 = 4e9;
/// Most Poincaré samples (points x directions x meshes x recorded
/// periods) one bifurcation command keeps for its output (some hundred
/// MB once written as JSON).
pub const MAX_SAMPLES: u64 = 2_000_000;
/// Most `--points x (2 --harmonics + 1)^3` of one frequency response: a
/// Newton step solves a dense system of (2 H + 1) unknowns per
/// coordinate, so its work grows like the cube; this allows every point
/// count up to H = 27 and some hours at H = 40.
pub const MAX_FRF_WORK: u64 = 2_000_000_000;
/// Most work units one boundary trace may take, as its estimate before it
/// starts gives them (`BoundarySpec::estimated_work`, in the units of
/// `solver::hbm::HbmCost`, about a microsecond of one core each): about an
/// hour. The estimate knows the model: its unknowns, channels and
/// resonances in the range (the compound set's default trace, 50 million
/// units measured, 42 s; the gear pair's, 0.8 million, 0.6 s).
pub const MAX_BOUNDARY_WORK: f64 = 3.6e9;

/// Steps a mesh period takes for accuracy alone, whatever the stiffness
/// (measured on the default model: 18 to 67 between Omega 2 and 0.1).
const ACCURACY_STEPS: f64 = 25.0;
/// The step times the highest natural frequency (rad) that the step-size
/// control keeps below on a stiff model (measured: 2.5).
const STABILITY_LIMIT: f64 = 2.5;

/// What a mesh period costs on one model: its highest natural frequency.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepCost {
    /// Highest dimensionless natural frequency of the mean-stiffness modes.
    omega_top: f64,
}

impl StepCost {
    /// The cost on `model`, from its modes.
    pub fn of(model: &Model) -> Self {
        let omega_top = model
            .modes
            .modes
            .iter()
            .map(|m| m.omega)
            .filter(|w| w.is_finite())
            .fold(0.0, f64::max);
        StepCost { omega_top }
    }

    /// The dearer of two costs (a sweep over a key that changes the modes).
    pub fn max(self, other: StepCost) -> StepCost {
        StepCost {
            omega_top: self.omega_top.max(other.omega_top),
        }
    }

    /// Estimated integration steps of one mesh period at `omega`.
    pub fn per_period(&self, omega: f64) -> f64 {
        let stiff = 2.0 * PI * self.omega_top / (STABILITY_LIMIT * omega.abs().max(1e-6));
        ACCURACY_STEPS + stiff
    }

    /// The mean of [`StepCost::per_period`] over `n` evenly spaced values
    /// of Omega from `from` to `to`.
    pub fn mean_per_period(&self, from: f64, to: f64, n: u32) -> f64 {
        if n <= 1 {
            return self.per_period(from);
        }
        let step = (to - from) / f64::from(n - 1);
        (0..n)
            .map(|i| self.per_period(from + step * f64::from(i)))
            .sum::<f64>()
            / f64::from(n)
    }
}

/// The largest value in `lo ..= hi` whose work `work(value)` is at most
/// `max` (the work grows with the value), or `None` if `lo`'s is over.
pub fn largest_within(
    lo: u32,
    hi: u32,
    max: f64,
    work: impl Fn(u32) -> Result<f64, Failure>,
) -> Result<Option<u32>, Failure> {
    if work(lo)? > max {
        return Ok(None);
    }
    if work(hi)? <= max {
        return Ok(Some(hi));
    }
    // `ok` fits, `over` does not.
    let (mut ok, mut over) = (lo, hi);
    while over - ok > 1 {
        let mid = ok + (over - ok) / 2;
        if work(mid)? <= max {
            ok = mid;
        } else {
            over = mid;
        }
    }
    Ok(Some(ok))
}

/// Checks `periods` mesh periods (the product `formula` of the options) at
/// `steps_per_period` each against [`MAX_STEPS`]; `fix` says what to
/// change (fewer of what, or how to split the run). The refusal is one line of at most 200 characters.
pub fn check_work(
    periods: u64,
    steps_per_period: f64,
    formula: &str,
    fix: &str,
) -> Result<(), Failure> {
    let steps = periods as f64 * steps_per_period;
    let per = steps_per_period.round();
    if steps > MAX_STEPS {
        return Err(usage(format!(
            "{formula} = {steps:.1e} integration steps ({per:.0} a period) over the \
             {MAX_STEPS:.0e} limit: {fix}"
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use solver::params::ModelParams;

    fn cost(planet_planet_stiffness_n_m: f64) -> StepCost {
        let mut params = ModelParams::default();
        solver::keys::set(
            &mut params,
            "stiffness_ab_n_m",
            solver::keys::Value::Num(planet_planet_stiffness_n_m),
        )
        .expect("stiffness in range");
        StepCost::of(&Model::new(&params).expect("model"))
    }

    #[test]
    fn a_stiffer_model_costs_more_per_period_and_in_proportion_to_its_top_frequency() {
        let base = cost(1e9);
        let stiff = cost(1e12);
        // The stiffest mode scales like sqrt(k): 1000 times the stiffness
        // raises it by at most sqrt(1000) = 31.6 times.
        let ratio = stiff.omega_top / base.omega_top;
        assert!(ratio > 5.0 && ratio <= 1000f64.sqrt() * 1.001, "{ratio}");
        assert!(stiff.per_period(0.1) > 10.0 * base.per_period(0.1));
        // Slower meshing means more steps per period, never fewer.
        assert!(base.per_period(0.1) > base.per_period(1.0));
        let mean = base.mean_per_period(0.1, 1.0, 10);
        assert!(mean > base.per_period(1.0) && mean < base.per_period(0.1));
    }
}
