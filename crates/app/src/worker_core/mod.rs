//! The Web Worker's job runner, as plain Rust: no browser types, so it is
//! tested natively.
//!
//! The worker's thin shell (`web.rs`) feeds every incoming message to
//! [`WorkerCore::handle`] and, while [`WorkerCore::has_work`], calls
//! [`WorkerCore::step`] in a loop for a few milliseconds, posts the replies,
//! and yields to the event loop so that newer jobs and cancels arrive. One
//! step is one bounded chunk of one job ([`crate::jobs::Job::step`]).
//!
//! The selected-Omega job is served first, so the views at the selected
//! Omega update even while a long sweep runs; then the harmonic-balance
//! branch of the frequency response (the view a slider drag watches, and the
//! quickest sweep); the time-integration overlay grid and the bifurcation
//! sweep then take turns, one slice each; the Lyapunov curve and
//! then the impact-regime map run when those are idle.

use crate::jobs::bif::{BandsCache, BifJob, BifSpec};
use crate::jobs::hbm::HbmJob;
use crate::jobs::map::MapJob;
use crate::jobs::omega::{OmegaJob, OmegaRun};
use crate::jobs::{failed, Job};
use crate::protocol::{encode, FromWorker, JobId, JobKind, JobSpec, ToWorker};
use serde_json::{Map, Value};
use solver::keys;
use solver::map::MapSpec;
use solver::params::ModelParams;
use solver::steady::Model;

/// The kinds in the order the runner serves them after the selected-Omega
/// job and the harmonic-balance branch: the overlay and the bifurcation
/// sweep take turns (so both diagrams fill in together and show their
/// first points early), then the Lyapunov curve, then the map (the slower,
/// secondary views must not delay the main diagrams).
const TAKING_TURNS: [JobKind; 2] = [JobKind::Fr, JobKind::Bif];
const WHEN_IDLE: [JobKind; 2] = [JobKind::Lyap, JobKind::Map];

/// The worker's state: at most one job of each kind, which may hold
/// several shards (chains) of that job: the page spreads a fixed number of
/// chains over however many workers it runs.
#[derive(Default)]
pub struct WorkerCore {
    /// The running shards of each kind's job (all of one id), by [`kind_slot`].
    jobs: [Vec<Box<dyn Job>>; 6],
    /// The next shard to step of each kind (its shards take turns).
    next_shard: [usize; 6],
    /// The finished shards of the last bifurcation sweep (kept for its export).
    finished: Vec<Box<dyn Job>>,
    turn: usize,
    /// The jobs of the pinned state A of an A/B comparison.
    pinned: Option<Box<WorkerCore>>,
    pinned_turn: bool,
    /// The jobs of a parameter family's members 1, 2, ... (index = member - 1).
    members: Vec<WorkerCore>,
    /// Which of the main state (0) and the members (1..) steps next.
    member_turn: usize,
    /// The last parametric-instability bands and their inputs.
    bands: BandsCache,
}

/// The slot of a kind in [`WorkerCore::jobs`].
fn kind_slot(kind: JobKind) -> usize {
    match kind {
        JobKind::Omega => 0,
        JobKind::Hbm => 1,
        JobKind::Fr => 2,
        JobKind::Bif => 3,
        JobKind::Map => 4,
        JobKind::Lyap => 5,
    }
}

fn model_from(params: &Map<String, Value>) -> solver::Result<(ModelParams, Model)> {
    let p = keys::from_json(params)?;
    let model = Model::new(&p)?;
    Ok((p, model))
}

impl WorkerCore {
    /// A worker with no jobs.
    pub fn new() -> Self {
        Self::default()
    }

    /// Whether a job waits for [`Self::step`].
    pub fn has_work(&self) -> bool {
        self.has_own_work()
            || self.pinned.as_ref().is_some_and(|p| p.has_work())
            || self.members.iter().any(WorkerCore::has_work)
    }

    fn has_own_work(&self) -> bool {
        self.jobs.iter().any(|shards| !shards.is_empty())
    }

    /// Handles one message from the page (JSON text).
    pub fn handle(&mut self, text: &str) -> Vec<FromWorker> {
        let msg: ToWorker = match serde_json::from_str(text) {
            Ok(m) => m,
            Err(e) => return vec![failed(0, format!("unreadable message: {e}"))],
        };
        match msg {
            ToWorker::Run { id, params, job } => self.start(id, &params, job),
            ToWorker::Cancel { kind } => {
                self.jobs[kind_slot(kind)].clear();
                Vec::new()
            }
            ToWorker::RunPinned { id, params, job } => self
                .pinned
                .get_or_insert_with(Box::default)
                .start(id, &params, job),
            ToWorker::CancelPinned { kind } => {
                if let Some(p) = self.pinned.as_mut() {
                    p.jobs[kind_slot(kind)].clear();
                }
                Vec::new()
            }
            ToWorker::RunMember {
                member,
                id,
                params,
                job,
            } => {
                let Some(i) = (member as usize)
                    .checked_sub(1)
                    .filter(|i| *i < crate::family::MAX_MEMBERS)
                else {
                    return vec![failed(id, format!("no family member {member}"))];
                };
                if self.members.len() <= i {
                    self.members.resize_with(i + 1, WorkerCore::default);
                }
                self.members[i].start(id, &params, job)
            }
            ToWorker::CancelMembers { kind } => {
                for m in &mut self.members {
                    match kind {
                        Some(k) => m.jobs[kind_slot(k)].clear(),
                        None => m.jobs = Default::default(),
                    }
                }
                Vec::new()
            }
            ToWorker::ExportBif { id, mesh, other } => vec![self.export_bif(id, mesh, &other)],
        }
    }

    /// The finished bifurcation shards of job `id` as CLI JSON. Without
    /// `other` (every worker but the first): this worker's shards, one
    /// shard's JSON or, for several, a JSON array of them. With `other` (the
    /// first worker, given the others' shards): every shard merged into the
    /// sweep's JSON.
    fn export_bif(&self, id: JobId, mesh: Option<usize>, other: &[String]) -> FromWorker {
        let mine: Vec<&dyn Job> = self
            .finished
            .iter()
            .filter(|j| j.id() == id)
            .map(|j| &**j)
            .collect();
        let Some((first, rest)) = mine.split_first() else {
            return failed(id, "the bifurcation sweep has not finished yet");
        };
        let mut texts = Vec::new();
        for j in rest {
            match j.export(mesh, &[]) {
                Some(FromWorker::Export { text, .. }) => texts.push(text),
                Some(reply) => return reply,
                None => return failed(id, "the bifurcation sweep has not finished yet"),
            }
        }
        if other.is_empty() && !texts.is_empty() {
            let Some(FromWorker::Export { text, .. }) = first.export(mesh, &[]) else {
                return failed(id, "the bifurcation sweep has not finished yet");
            };
            let values: Result<Vec<Value>, _> = std::iter::once(&text)
                .chain(&texts)
                .map(|t| serde_json::from_str::<Value>(t))
                .collect();
            let values = match values {
                Ok(v) => v,
                Err(e) => return failed(id, format!("cannot read a shard: {e}")),
            };
            let chains = values[0]["spec"]["chains"].as_u64();
            if chains != Some(values.len() as u64) {
                // Several shards here, to be merged by the first worker.
                return FromWorker::Export {
                    id,
                    text: Value::Array(values).to_string(),
                };
            }
            // A pool of one: every chain is here; merge them.
        }
        texts.extend(other.iter().cloned());
        first
            .export(mesh, &texts)
            .unwrap_or_else(|| failed(id, "the bifurcation sweep has not finished yet"))
    }

    fn start(&mut self, id: JobId, params: &Map<String, Value>, job: JobSpec) -> Vec<FromWorker> {
        // A new job replaces the old one of its kind, even if it fails; a
        // further shard of the running job joins it.
        let slot = kind_slot(job.kind());
        if self.jobs[slot].iter().any(|j| j.id() != id) {
            self.jobs[slot].clear();
        }
        let (params, model) = match model_from(params) {
            Ok(x) => x,
            Err(e) => return vec![failed(id, e.to_string())],
        };
        match self.new_job(id, params, model, job) {
            Ok((job, out)) => {
                self.jobs[slot].push(job);
                out
            }
            Err(reply) => vec![reply],
        }
    }

    /// The job of a spec, and its first messages.
    fn new_job(
        &mut self,
        id: JobId,
        params: ModelParams,
        model: Model,
        job: JobSpec,
    ) -> Result<(Box<dyn Job>, Vec<FromWorker>), FromWorker> {
        fn boxed<J: Job + 'static>(
            r: Result<(J, Vec<FromWorker>), FromWorker>,
        ) -> Result<(Box<dyn Job>, Vec<FromWorker>), FromWorker> {
            r.map(|(j, out)| (Box::new(j) as Box<dyn Job>, out))
        }
        match job {
            JobSpec::Omega {
                omega,
                mesh,
                run,
                samples_per_period,
                max_order,
            } => {
                let job = OmegaJob {
                    id,
                    model,
                    omega,
                    mesh,
                    run,
                    samples_per_period,
                    max_order,
                };
                Ok((Box::new(OmegaRun::start(job)), Vec::new()))
            }
            JobSpec::Hbm {
                omega_from,
                omega_to,
                points,
                harmonics,
                stability,
            } => boxed(HbmJob::start(
                id,
                &model,
                (omega_from, omega_to, points),
                harmonics,
                stability,
            )),
            JobSpec::Fr {
                omega_from,
                omega_to,
                points,
                chains,
                shard,
                run,
            } => boxed(crate::jobs::overlay::start(
                id,
                model,
                (omega_from, omega_to, points),
                (chains, shard),
                run,
            )),
            JobSpec::Bif {
                omega_from,
                omega_to,
                points,
                directions,
                chains,
                shard,
                run,
            } => {
                let spec = BifSpec {
                    grid: (omega_from, omega_to, points),
                    directions: &directions,
                    chains: (chains, shard),
                    run,
                };
                boxed(BifJob::start(id, params, model, spec, &mut self.bands))
            }
            JobSpec::Map {
                key,
                omega_from,
                omega_to,
                omega_points,
                value_from,
                value_to,
                value_points,
                mesh,
                shards,
                shard,
                run,
            } => {
                let mut spec = MapSpec::new(
                    (omega_from, omega_to, omega_points),
                    &key,
                    (value_from, value_to, value_points),
                );
                spec.steady.transient_periods = run.transient_periods;
                spec.steady.record_periods = run.record_periods;
                spec.mesh = mesh;
                spec.shard = Some((shard, shards));
                boxed(MapJob::start(id, &params, spec))
            }
            JobSpec::Lyap {
                omega_from,
                omega_to,
                points,
                chains,
                shard,
                transient_periods,
                periods,
            } => boxed(crate::jobs::lyap::start(
                id,
                model,
                (omega_from, omega_to, points),
                (chains, shard),
                (transient_periods, periods),
            )),
        }
    }

    /// One step of the job of `kind`, if there is one (its shards take
    /// turns); a finished shard is dropped (a bifurcation shard is kept for
    /// its export).
    fn step_kind(&mut self, kind: JobKind) -> Option<Vec<FromWorker>> {
        let k = kind_slot(kind);
        let shards = &mut self.jobs[k];
        if shards.is_empty() {
            return None;
        }
        let i = self.next_shard[k] % shards.len();
        let out = shards[i].step();
        if shards[i].finished() {
            let job = shards.remove(i);
            self.next_shard[k] = i;
            if kind == JobKind::Bif {
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

    /// Does one bounded chunk of the most urgent job.
    pub fn step(&mut self) -> Vec<FromWorker> {
        if let Some(out) = self.step_kind(JobKind::Omega) {
            return out;
        }
        // The members' selected-Omega runs next (the panels of a figure),
        // then the main state and each member take turns, one chunk each.
        if let Some(out) = self
            .members
            .iter_mut()
            .find_map(|m| m.step_kind(JobKind::Omega))
        {
            return out;
        }
        let n = self.members.len() + 1;
        for k in 0..n {
            let turn = (self.member_turn + k) % n;
            if turn == 0 {
                if self.has_own_work() || self.pinned.as_ref().is_some_and(|p| p.has_work()) {
                    self.member_turn = 1 % n;
                    return self.step_main();
                }
            } else if self.members[turn - 1].has_work() {
                self.member_turn = (turn + 1) % n;
                return self.members[turn - 1].step();
            }
        }
        Vec::new()
    }

    /// One chunk of the main state's (or the pinned state's) jobs.
    fn step_main(&mut self) -> Vec<FromWorker> {
        // The pinned state's jobs take every other chunk.
        self.pinned_turn = !self.pinned_turn;
        if let Some(p) = self
            .pinned
            .as_mut()
            .filter(|p| p.has_work())
            .filter(|_| self.pinned_turn)
        {
            return p.step();
        }
        if !self.has_own_work() {
            if let Some(p) = self.pinned.as_mut() {
                return p.step();
            }
        }
        if let Some(out) = self.step_kind(JobKind::Hbm) {
            return out;
        }
        for k in 0..TAKING_TURNS.len() {
            let i = (self.turn + k) % TAKING_TURNS.len();
            if let Some(out) = self.step_kind(TAKING_TURNS[i]) {
                self.turn = (i + 1) % TAKING_TURNS.len();
                return out;
            }
        }
        WHEN_IDLE
            .iter()
            .find_map(|&kind| self.step_kind(kind))
            .unwrap_or_default()
    }
}

/// The message a worker posts first.
pub fn ready_message() -> String {
    encode(&FromWorker::Ready)
}

#[cfg(test)]
mod tests;
