//! The regime map's boundaries (`solver::boundaries`): the folds, period
//! doublings and contact changes of the harmonic-balance branch traced as
//! curves in Omega and the map's key, a few points per step; each curve is
//! posted as soon as it is finished, so the map shows them one by one.

use super::Job;
use figures::protocol::{BoundaryCurve, FromWorker, JobId};
use solver::boundaries::{BoundarySpec, BoundaryTrace};
use solver::params::ModelParams;

/// Branch or curve points per step: on the gear pair a few ms in the
/// browser, on the compound set a few tens.
pub const BOUNDARY_CHUNK: usize = 2;

/// A boundary trace in progress.
pub(crate) struct BoundariesJob {
    id: JobId,
    trace: BoundaryTrace,
    sent_curves: usize,
    sent_notes: usize,
    finished: bool,
}

impl BoundariesJob {
    /// Starts the trace of `spec` on `params`.
    pub(crate) fn start(
        id: JobId,
        params: &ModelParams,
        spec: BoundarySpec,
    ) -> Result<(Self, Vec<FromWorker>), FromWorker> {
        match BoundaryTrace::new(params, spec) {
            Ok(trace) => {
                let job = BoundariesJob {
                    id,
                    trace,
                    sent_curves: 0,
                    sent_notes: 0,
                    finished: false,
                };
                let out = vec![job.progress_message()];
                Ok((job, out))
            }
            Err(e) => Err(super::failed(id, format!("boundaries: {e}"))),
        }
    }
}

impl Job for BoundariesJob {
    fn id(&self) -> JobId {
        self.id
    }

    fn step(&mut self) -> Vec<FromWorker> {
        if let Err(e) = self.trace.advance(BOUNDARY_CHUNK) {
            self.finished = true;
            return vec![super::failed(self.id, format!("boundaries: {e}"))];
        }
        self.finished = self.trace.is_finished();
        let curves = &self.trace.curves()[self.sent_curves..];
        let notes = &self.trace.notes()[self.sent_notes..];
        if curves.is_empty() && notes.is_empty() && !self.finished {
            return vec![self.progress_message()];
        }
        let msg = FromWorker::BoundaryCurves {
            id: self.id,
            curves: curves.iter().map(BoundaryCurve::from).collect(),
            cusps: self
                .trace
                .cusps()
                .iter()
                .map(|c| (c.omega, c.value))
                .collect(),
            notes: notes.to_vec(),
            permille: self.progress().0,
            finished: self.finished,
        };
        self.sent_curves = self.trace.curves().len();
        self.sent_notes = self.trace.notes().len();
        vec![msg]
    }

    fn finished(&self) -> bool {
        self.finished
    }

    fn progress(&self) -> (usize, usize) {
        let done = if self.finished {
            1000
        } else {
            (1000.0 * self.trace.progress()).floor() as usize
        };
        (done.min(1000), 1000)
    }
}
