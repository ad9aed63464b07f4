//! Jobs that walk a chain of Omega grid points, each continued from the
//! previous point's end state: the time-integration overlay and the
//! Lyapunov curve. One [`ChainJob`] runs the chain; its kind
//! ([`ChainKind`]) computes one point as a run paused and resumed every
//! [`SLICE_STEPS`] integrator steps, so a newer job waits at most one slice.

use super::{Job, SLICE_STEPS};
use figures::protocol::{FromWorker, JobId};
use solver::model::Model;

/// A chain's share of an Omega grid: every `chains`-th of `points` grid
/// points from `shard`, computed in order (each continued from the last).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Chain {
    omegas: Vec<(u32, f64)>,
    next: usize,
}

impl Chain {
    /// Chain `shard` of `chains` over grid points `0..points` at `omega(i)`.
    pub(crate) fn new(
        points: u32,
        (chains, shard): (u32, u32),
        omega: impl Fn(u32) -> f64,
    ) -> Self {
        let omegas = (shard..points)
            .step_by(chains.max(1) as usize)
            .map(|i| (i, omega(i)))
            .collect();
        Chain { omegas, next: 0 }
    }

    /// The next grid point `(index, omega)`, if any is left.
    pub(crate) fn peek(&self) -> Option<(u32, f64)> {
        self.omegas.get(self.next).copied()
    }

    /// Marks the next grid point done.
    pub(crate) fn advance(&mut self) {
        self.next = (self.next + 1).min(self.omegas.len());
    }

    /// Whether every point is done.
    pub(crate) fn finished(&self) -> bool {
        self.next >= self.omegas.len()
    }

    /// Points done and in all.
    pub(crate) fn progress(&self) -> (usize, usize) {
        (self.next, self.omegas.len())
    }
}

/// What one kind of chain computes at a grid point.
pub(crate) trait ChainKind {
    /// One point's data.
    type Sample;
    /// One point's computation in progress (paused between slices).
    type Run;
    /// Whether each point is followed by a progress message.
    const PROGRESS: bool;
    /// Starts grid point `at` (index, omega), continued from `from` (the
    /// previous point's end state; the static state if `None`).
    fn start(
        &self,
        model: &Model,
        from: Option<&[f64]>,
        at: (u32, f64),
    ) -> solver::Result<Self::Run>;
    /// Continues `run` for at most `max_steps` integrator steps: the
    /// point's sample and end state once it is complete, `None` if paused.
    fn advance(
        &self,
        model: &Model,
        run: &mut Self::Run,
        at: (u32, f64),
        max_steps: u64,
    ) -> solver::Result<Option<(Self::Sample, Vec<f64>)>>;
    /// The sample of a point whose computation failed, saying why.
    fn failed(at: (u32, f64), error: String) -> Self::Sample;
    /// The message that carries samples.
    fn message(id: JobId, points: Vec<Self::Sample>) -> FromWorker;
}

/// A chain of one kind in progress.
pub(crate) struct ChainJob<K: ChainKind> {
    id: JobId,
    model: Model,
    chain: Chain,
    state: Option<Vec<f64>>,
    /// The point in progress, paused between slices.
    pending: Option<K::Run>,
    kind: K,
}

impl<K: ChainKind> ChainJob<K> {
    /// Starts `chain` of `kind` on `model`, with its first message.
    pub(crate) fn start(id: JobId, model: Model, chain: Chain, kind: K) -> (Self, Vec<FromWorker>) {
        let job = ChainJob {
            id,
            model,
            chain,
            state: None,
            pending: None,
            kind,
        };
        let out = vec![job.progress_message()];
        (job, out)
    }

    /// A slice of the point `at`: its result once complete, `None` if paused.
    fn slice(&mut self, at: (u32, f64)) -> Option<solver::Result<(K::Sample, Vec<f64>)>> {
        let run = match self.pending.as_mut() {
            Some(run) => run,
            None => match self.kind.start(&self.model, self.state.as_deref(), at) {
                Ok(run) => self.pending.insert(run),
                Err(e) => return Some(Err(e)),
            },
        };
        let out = self
            .kind
            .advance(&self.model, run, at, SLICE_STEPS)
            .transpose()?;
        self.pending = None;
        Some(out)
    }
}

impl<K: ChainKind> Job for ChainJob<K> {
    fn id(&self) -> JobId {
        self.id
    }

    fn step(&mut self) -> Vec<FromWorker> {
        let mut out = Vec::new();
        if let Some(at) = self.chain.peek() {
            let Some(result) = self.slice(at) else {
                // Paused inside the point: nothing to say yet.
                return out;
            };
            self.chain.advance();
            let sample = match result {
                Ok((sample, end)) => {
                    self.state = Some(end);
                    sample
                }
                Err(e) => {
                    // The chain restarts from the static equilibrium, like
                    // the solver's sweeps.
                    self.state = None;
                    K::failed(at, e.to_string())
                }
            };
            out.push(K::message(self.id, vec![sample]));
            if K::PROGRESS {
                out.push(self.progress_message());
            }
        }
        if self.finished() {
            out.push(FromWorker::Done { id: self.id });
        }
        out
    }

    fn finished(&self) -> bool {
        self.chain.finished()
    }

    fn progress(&self) -> (usize, usize) {
        self.chain.progress()
    }
}
