//! The largest Lyapunov exponent over Omega (under view 2): one chain of
//! Benettin runs over its share of the Omega grid, each continued from the
//! previous end state.

use super::{failed, Job};
use crate::protocol::{FromWorker, JobId, LyapSample};
use solver::lyapunov::{largest_exponent, LyapunovOptions};
use solver::steady::Model;

/// A chain of the Lyapunov curve in progress.
pub(crate) struct LyapJob {
    id: JobId,
    model: Model,
    omegas: Vec<(u32, f64)>,
    next: usize,
    transient_periods: u32,
    periods: u32,
    state: Option<Vec<f64>>,
}

impl LyapJob {
    /// Starts chain `shard` of `chains` over `points` Omegas of the range.
    pub(crate) fn start(
        id: JobId,
        model: Model,
        (omega_from, omega_to, points): (f64, f64, u32),
        (chains, shard): (u32, u32),
        (transient_periods, periods): (u32, u32),
    ) -> Result<(Self, Vec<FromWorker>), FromWorker> {
        if points < 2 || omega_to.partial_cmp(&omega_from) != Some(std::cmp::Ordering::Greater) {
            return Err(failed(
                id,
                "Lyapunov: at least 2 points over an increasing Omega range",
            ));
        }
        let step = (omega_to - omega_from) / f64::from(points - 1);
        let omegas: Vec<(u32, f64)> = (shard..points)
            .step_by(chains.max(1) as usize)
            .map(|i| (i, omega_from + step * f64::from(i)))
            .collect();
        let total = omegas.len();
        let job = LyapJob {
            id,
            model,
            omegas,
            next: 0,
            transient_periods,
            periods,
            state: None,
        };
        Ok((job, vec![FromWorker::Progress { id, done: 0, total }]))
    }
}

impl Job for LyapJob {
    fn id(&self) -> JobId {
        self.id
    }

    fn step(&mut self) -> Vec<FromWorker> {
        let mut out = Vec::new();
        if let Some(&(index, omega)) = self.omegas.get(self.next) {
            self.next += 1;
            let mut opts = LyapunovOptions::new(omega);
            opts.transient_periods = self.transient_periods;
            opts.periods = self.periods;
            let sample = match largest_exponent(&self.model, &opts, self.state.as_deref()) {
                Ok(l) => {
                    self.state = Some(l.end_state);
                    LyapSample {
                        index,
                        omega,
                        per_period: Some(l.per_period),
                        per_s: Some(l.per_s),
                        error: None,
                    }
                }
                Err(e) => {
                    // The chain restarts from the static equilibrium.
                    self.state = None;
                    LyapSample {
                        index,
                        omega,
                        per_period: None,
                        per_s: None,
                        error: Some(e.to_string()),
                    }
                }
            };
            out.push(FromWorker::LyapPoints {
                id: self.id,
                points: vec![sample],
            });
        }
        if self.finished() {
            out.push(FromWorker::Done { id: self.id });
        }
        out
    }

    fn finished(&self) -> bool {
        self.next >= self.omegas.len()
    }

    fn progress(&self) -> (usize, usize) {
        (self.next, self.omegas.len())
    }
}
