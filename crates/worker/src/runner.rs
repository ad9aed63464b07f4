//! One computation's jobs in a worker: at most one job of each kind, its
//! shards taking turns, served in the kinds' priority order
//! ([`JobKind::URGENT`], then [`JobKind::TAKING_TURNS`], then
//! [`JobKind::WHEN_IDLE`]).

use super::jobs::bif::SharedBands;
use super::jobs::{self, failed, Job};
use figures::protocol::{FromWorker, JobId, JobKind, JobSpec};
use serde_json::{Map, Value};
use solver::keys;
use solver::model::Model;
use solver::params::ModelParams;

/// One computation's jobs.
#[derive(Default)]
pub(super) struct Runner {
    /// The running shards of each kind's job (all of one id), by [`JobKind::slot`].
    jobs: [Vec<Box<dyn Job>>; JobKind::COUNT],
    /// The next shard to step of each kind (its shards take turns).
    next_shard: [usize; JobKind::COUNT],
    /// The finished shards of the last bifurcation sweep (kept for its export).
    finished: Vec<Box<dyn Job>>,
    /// Which of [`JobKind::TAKING_TURNS`] steps next.
    turn: usize,
}

fn model_from(params: &Map<String, Value>) -> solver::Result<(ModelParams, Model)> {
    let p = keys::from_json(params)?;
    let model = Model::new(&p)?;
    Ok((p, model))
}

impl Runner {
    /// Whether a job waits for a step.
    pub(super) fn has_work(&self) -> bool {
        self.jobs.iter().any(|shards| !shards.is_empty())
    }

    /// Drops the job of `kind` (`None`: every job).
    pub(super) fn cancel(&mut self, kind: Option<JobKind>) {
        match kind {
            Some(k) => self.jobs[k.slot()].clear(),
            None => self.jobs = Default::default(),
        }
    }

    /// The finished bifurcation shards of job `id`.
    pub(super) fn finished(&self, id: JobId) -> impl Iterator<Item = &dyn Job> {
        self.finished
            .iter()
            .filter(move |j| j.id() == id)
            .map(|j| &**j)
    }

    /// Starts job `id` of `spec`.
    pub(super) fn start(
        &mut self,
        id: JobId,
        params: &Map<String, Value>,
        spec: JobSpec,
        bands: &SharedBands,
    ) -> Vec<FromWorker> {
        // A new job replaces the old one of its kind, even if it fails; a
        // further shard of the running job joins it.
        let slot = spec.kind().slot();
        if self.jobs[slot].iter().any(|j| j.id() != id) {
            self.jobs[slot].clear();
        }
        let (params, model) = match model_from(params) {
            Ok(x) => x,
            Err(e) => return vec![failed(id, e.to_string())],
        };
        match jobs::start(id, params, model, spec, bands) {
            Ok((job, out)) => {
                self.jobs[slot].push(job);
                out
            }
            Err(reply) => vec![reply],
        }
    }

    /// One step of the job of `kind`, if there is one (its shards take
    /// turns); a finished shard is dropped (a bifurcation shard is kept for
    /// its export).
    pub(super) fn step_kind(&mut self, kind: JobKind) -> Option<Vec<FromWorker>> {
        let k = kind.slot();
        let shards = &mut self.jobs[k];
        if shards.is_empty() {
            return None;
        }
        let i = self.next_shard[k] % shards.len();
        let out = shards[i].step();
        if shards[i].finished() {
            let job = shards.remove(i);
            self.next_shard[k] = i;
            if job.exports() {
                if self.finished.iter().any(|j| j.id() != job.id()) {
                    self.finished.clear();
                }
                self.finished.push(job);
            }
        } else {
            self.next_shard[k] = i + 1;
        }
        Some(out)
    }

    /// One chunk of the most urgent job.
    pub(super) fn step(&mut self) -> Vec<FromWorker> {
        for kind in JobKind::URGENT {
            if let Some(out) = self.step_kind(kind) {
                return out;
            }
        }
        let turns = JobKind::TAKING_TURNS;
        for k in 0..turns.len() {
            let i = (self.turn + k) % turns.len();
            if let Some(out) = self.step_kind(turns[i]) {
                self.turn = (i + 1) % turns.len();
                return out;
            }
        }
        JobKind::WHEN_IDLE
            .iter()
            .find_map(|&kind| self.step_kind(kind))
            .unwrap_or_default()
    }
}
