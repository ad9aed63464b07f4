//! What a shooting branch will cost, in integration steps (a step that
//! carries the monodromy's `n` tangent vectors counting `1 + n`, as
//! [`super::ShootFrfStats::work_steps`] counts them), before it starts.
//!
//! The branch takes some `points / 1.5` steps where it is flat (a step
//! moves Omega by up to 1.5 nominal steps) and `points / 2` more per
//! resonance in the range ([`Model::resonances`], a superharmonic one
//! counting half); with branch switching,
//! the period-doubled branches (of twice the period) add a fifth of that
//! per resonance. A point costs some `6 + n / 2` integrations of its
//! period carrying the tangents' work (the corrector's plain iterations,
//! the monodromy and `dG/dOmega` at the solved point, the extremes, the
//! full Newton steps where the chord gives up, more often with more
//! tangents). A period's steps at the shooting tolerances come from a pilot: ten
//! periods integrated from rest at four values of Omega across the range,
//! so that the estimate knows the model's stiffness and how hard its
//! motion is to follow (over Omega 0.4-1.3 the pilot takes 100 steps a
//! period on the compound set, 60 on the gear pair).
//!
//! Measured (`stats.work_steps`) over eleven ranges of both models, with
//! and without resonances and period doublings, the estimate was 0.27 to
//! 2.8 times the work: a narrow range around a resonance (the compound
//! set's Omega 0.9-1.0) grows more doubled pieces than it counts.
//! `crates/solver/tests/budgets.rs` checks it on three of them.

use super::ShootFrfSpec;
use crate::error::Result;
use crate::shooting::Reduced;
use crate::steady::{steady_state, SteadyOptions};
use crate::Model;

/// Periods each pilot run integrates.
const PILOT_PERIODS: u32 = 10;
/// Values of Omega the pilot samples.
const PILOT_OMEGAS: u32 = 4;
/// Branch points per nominal point where the branch is flat (a step
/// moves Omega by up to 1.5 nominal steps), and more per resonance.
const FLAT: f64 = 0.67;
/// See [`FLAT`].
const PER_RESONANCE: f64 = 0.5;
/// Integrations of its period, with the tangents' work, per branch point,
/// besides half the tangents' number (more tangents, more failed chord
/// corrections redone by full Newton).
const PER_POINT: f64 = 6.0;

/// A shooting branch's estimated work, from its pilot.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShootEstimate {
    /// Integration steps per branch point (with the tangents' work).
    pub steps_per_point: f64,
    /// Branch points per nominal point (`ShootFrfSpec::points`).
    pub points_per_nominal: f64,
    /// Steps the pilot took.
    pub pilot_steps: u64,
}

impl ShootEstimate {
    /// The estimated work at `points` nominal points.
    pub fn work(&self, points: u32) -> f64 {
        f64::from(points) * self.points_per_nominal * self.steps_per_point
    }
}

impl ShootFrfSpec {
    /// The estimated work of the branch on `model` (see the module's doc).
    pub fn estimate(&self, model: &Model) -> Result<ShootEstimate> {
        self.validate()?;
        let mut pilot = 0u64;
        let mut per_period = 0.0;
        for k in 0..PILOT_OMEGAS {
            let omega = self.omega_from
                + (self.omega_to - self.omega_from) * (f64::from(k) + 0.5)
                    / f64::from(PILOT_OMEGAS);
            let mut o = SteadyOptions::new(omega);
            o.transient_periods = PILOT_PERIODS - 1;
            o.record_periods = 1;
            o.early_settle = false;
            o.samples_per_period = 0;
            o.shooting = false;
            o.rtol = self.shooting.rtol;
            o.atol_m = self.shooting.atol_m;
            let run = steady_state(model, &o, None)?;
            let steps = run.stats.integrator.steps;
            pilot += steps;
            per_period += steps as f64 / f64::from(PILOT_PERIODS) / f64::from(PILOT_OMEGAS);
        }
        let dim = Reduced::new(model, self.omega_from).dim() as f64;
        // The superharmonic resonances, driven by the stiffness's and the
        // impacts' harmonics alone, count half.
        let (primary, superharmonic) = model.resonances(3, self.omega_from, self.omega_to);
        let r = primary as f64 + 0.5 * superharmonic as f64;
        // Period doublings happen near resonances: a doubled branch of
        // twice the period for every five of them.
        let doubled = if self.switch_branches { 0.2 * r } else { 0.0 };
        let period = f64::from(self.period) * (1.0 + 2.0 * doubled) / (1.0 + doubled);
        let per_point = PER_POINT + 0.5 * dim;
        Ok(ShootEstimate {
            steps_per_point: per_point * (1.0 + dim) * period * per_period,
            points_per_nominal: (FLAT + PER_RESONANCE * r) * (1.0 + doubled),
            pilot_steps: pilot,
        })
    }
}
