//! The time-integration overlay of the frequency response (view 1): one
//! continuation chain of steady states over its share of the Omega grid.

use super::{failed, round_um, Job};
use crate::protocol::{FrSample, FromWorker, JobId, MeshExtremes, RunOptions};
use solver::steady::{steady_state, Model, SteadyOptions};
use solver::sweep::SweepSpec;

/// A time-integration overlay grid in progress: one continuation chain.
pub(crate) struct FrJob {
    id: JobId,
    model: Model,
    omegas: Vec<(u32, f64)>,
    next: usize,
    run: RunOptions,
    state: Option<Vec<f64>>,
}

impl FrJob {
    /// Starts chain `shard` of `chains` over `points` Omegas of the range.
    pub(crate) fn start(
        id: JobId,
        model: Model,
        (omega_from, omega_to, points): (f64, f64, u32),
        (chains, shard): (u32, u32),
        run: RunOptions,
    ) -> Result<(Self, Vec<FromWorker>), FromWorker> {
        let mut spec = SweepSpec::new(omega_from, omega_to, points);
        spec.chains = chains;
        spec.shard = Some(shard);
        spec.steady.transient_periods = run.transient_periods;
        spec.steady.record_periods = run.record_periods;
        if let Err(e) = spec.validate(model.system.meshes.len()) {
            return Err(failed(id, e.to_string()));
        }
        let omegas: Vec<(u32, f64)> = (shard..points)
            .step_by(chains.max(1) as usize)
            .map(|i| (i, spec.omega(i)))
            .collect();
        let total = omegas.len();
        let job = FrJob {
            id,
            model,
            omegas,
            next: 0,
            run,
            state: None,
        };
        Ok((job, vec![FromWorker::Progress { id, done: 0, total }]))
    }
}

impl Job for FrJob {
    fn id(&self) -> JobId {
        self.id
    }

    fn step(&mut self) -> Vec<FromWorker> {
        let mut out = Vec::new();
        if let Some(&(index, omega)) = self.omegas.get(self.next) {
            self.next += 1;
            let sample = fr_point(self, index, omega);
            out.push(FromWorker::FrPoints {
                id: self.id,
                points: vec![sample],
            });
            out.push(FromWorker::Progress {
                id: self.id,
                done: self.next,
                total: self.omegas.len(),
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

fn fr_point(job: &mut FrJob, index: u32, omega: f64) -> FrSample {
    let mut opts = SteadyOptions::new(omega);
    opts.transient_periods = job.run.transient_periods;
    opts.record_periods = job.run.record_periods;
    opts.samples_per_period = 0;
    match steady_state(&job.model, &opts, job.state.as_deref()) {
        Ok(ss) => {
            job.state = Some(ss.end_state.clone());
            FrSample {
                index,
                omega,
                meshes: ss
                    .meshes
                    .iter()
                    .map(|m| MeshExtremes {
                        rel_min_um: round_um(m.rel_min_m * 1e6),
                        rel_max_um: round_um(m.rel_max_m * 1e6),
                        regime: m.impact.into(),
                        dynamic_factor: m.dynamic_factor,
                    })
                    .collect(),
                period: ss.period,
                error: None,
            }
        }
        Err(e) => {
            // The chain restarts from the static equilibrium, like the solver's sweeps.
            job.state = None;
            FrSample {
                index,
                omega,
                meshes: Vec::new(),
                period: None,
                error: Some(e.to_string()),
            }
        }
    }
}
