//! The Web Worker's job runner, as plain Rust: no browser types, so it is
//! tested natively, and the command line's `figure` runs its jobs too.
//!
//! Architecture invariant: this crate imports the solver, `report` and the
//! shared `figures` (the messages and results it speaks), never the page.
//!
//! The page's worker shell (`crates/app/src/web/worker.rs`) feeds every
//! incoming message to [`WorkerCore::handle`] and, while
//! [`WorkerCore::has_work`], calls [`WorkerCore::step`] in a loop for a
//! few milliseconds, posts the replies, and yields to the event loop so
//! that newer jobs and cancels arrive. One step is one bounded chunk of one
//! job ([`jobs::Job::step`]).
//!
//! The worker keeps one [`runner::Runner`] per computation (the current
//! state, the pinned A, each family member: a [`Target`]). The
//! selected-Omega jobs are served first, so the views at the selected
//! Omega update even while a long sweep runs; then the computations take
//! turns, and within one the harmonic-balance branch of the frequency
//! response comes first (the view a slider drag watches, and the quickest
//! sweep); the time-integration overlay and the bifurcation sweep then take
//! turns, one slice each; the Lyapunov curve, then the impact-regime map,
//! then the shooting branches run when those are idle.

use figures::protocol::{encode, FromWorker, JobId, KindSet, Target, ToWorker};
use jobs::bif::SharedBands;
use jobs::{failed, Job};
use runner::Runner;
use serde_json::Value;

pub mod jobs;
mod runner;
pub mod slicer;

/// The worker's state: a list of computations (the current state's, the
/// pinned A's, each family member's), each with at most one job of each
/// kind, which may hold several shards (chains) of that job: the page
/// spreads a fixed number of chains over however many workers it runs.
#[derive(Default)]
pub struct WorkerCore {
    /// The computations, by target, in the order they first had a job.
    computations: Vec<(Target, Runner)>,
    /// Which computation takes the next turn (after every selected-Omega run).
    turn: usize,
    /// The last parametric-instability bands and their inputs.
    bands: SharedBands,
}

impl WorkerCore {
    /// A worker with no jobs.
    pub fn new() -> Self {
        Self::default()
    }

    /// Whether a job waits for [`Self::step`].
    pub fn has_work(&self) -> bool {
        self.computations.iter().any(|(_, r)| r.has_work())
    }

    fn runner(&mut self, target: Target) -> Option<&mut Runner> {
        self.computations
            .iter_mut()
            .find(|(t, _)| *t == target)
            .map(|(_, r)| r)
    }

    /// Handles one message from the page (JSON text).
    pub fn handle(&mut self, text: &str) -> Vec<FromWorker> {
        let msg: ToWorker = match serde_json::from_str(text) {
            Ok(m) => m,
            Err(e) => return vec![failed(0, format!("unreadable message: {e}"))],
        };
        match msg {
            ToWorker::Run {
                target,
                id,
                params,
                job,
            } => {
                if let Target::Member(m) = target {
                    if m == 0 || m as usize > figures::family_spec::MAX_MEMBERS {
                        return vec![failed(id, format!("no family member {m}"))];
                    }
                }
                if self.runner(target).is_none() {
                    // The current state's computation first: its
                    // selected-Omega run is served before the others'.
                    let at = if target == Target::Main {
                        0
                    } else {
                        self.computations.len()
                    };
                    self.computations.insert(at, (target, Runner::default()));
                }
                let bands = &self.bands;
                match self.computations.iter_mut().find(|(t, _)| *t == target) {
                    Some((_, r)) => r.start(id, &params, job, bands),
                    None => Vec::new(),
                }
            }
            ToWorker::Cancel { target, kind } => {
                if let Some(r) = self.runner(target) {
                    r.cancel(kind);
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
            .computations
            .iter()
            .flat_map(|(_, r)| r.finished(id))
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

    /// Does one bounded chunk of the most urgent job: any computation's
    /// selected-Omega run first (the current state's, then the members':
    /// the panels of a figure), then the computations take turns, one
    /// chunk each.
    pub fn step(&mut self) -> Vec<FromWorker> {
        if let Some(out) = self
            .computations
            .iter_mut()
            .find_map(|(_, r)| KindSet::SELECTED.iter().find_map(|k| r.step_kind(k)))
        {
            return out;
        }
        let n = self.computations.len();
        for k in 0..n {
            let i = (self.turn + k) % n;
            if self.computations[i].1.has_work() {
                self.turn = (i + 1) % n;
                return self.computations[i].1.step();
            }
        }
        Vec::new()
    }
}

/// The message a worker posts first.
pub fn ready_message() -> String {
    encode(&FromWorker::Ready)
}

#[cfg(test)]
mod tests;
