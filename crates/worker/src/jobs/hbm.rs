//! The harmonic-balance branch of the frequency response (`ViewId::Fr`): a
//! pseudo-arclength continuation streamed in chunks of [`HBM_CHUNK`] points.

use super::{failed, Job};
use figures::failure::{explain, is_loaded, Task};
use figures::protocol::um;
use figures::protocol::{FromWorker, HbmMesh, HbmSample, JobId};
use solver::hbm::{BranchPoint, FrfContinuation, FrfSpec};
use solver::model::Model;

/// Points of the harmonic-balance branch computed per step: a few
/// milliseconds each, so a newer job or a cancel waits at most a few tens of
/// milliseconds.
pub const HBM_CHUNK: usize = 8;

/// A harmonic-balance branch in progress.
pub(crate) struct HbmJob {
    id: JobId,
    cont: FrfContinuation,
    /// Whether a load presses the teeth together (the failures' advice).
    loaded: bool,
    finished: bool,
    /// Points the continuation returned beyond a chunk (a restart's piece
    /// arrives whole), sent with the next chunks.
    pending: std::collections::VecDeque<HbmSample>,
}

impl HbmJob {
    /// Starts the branch over `omega_from ..= omega_to` with `points`
    /// nominal points and `harmonics` harmonics (upward, with stability if asked).
    pub(crate) fn start(
        id: JobId,
        model: &Model,
        (omega_from, omega_to, points): (f64, f64, u32),
        harmonics: u32,
        stability: bool,
    ) -> Result<(Self, Vec<FromWorker>), FromWorker> {
        let mut spec = FrfSpec::new(omega_from, omega_to, points);
        spec.harmonics = harmonics as usize;
        spec.direction = solver::sweep::Direction::Up;
        spec.stability = stability;
        match FrfContinuation::new(model, spec) {
            Ok(cont) => Ok((
                HbmJob {
                    id,
                    cont,
                    loaded: is_loaded(model),
                    finished: false,
                    pending: std::collections::VecDeque::new(),
                },
                vec![FromWorker::Progress {
                    id,
                    done: 0,
                    total: 100,
                }],
            )),
            Err(e) => Err(failed(
                id,
                format!(
                    "The frequency response could not be started: {}",
                    explain(&e, Task::HarmonicBalance, is_loaded(model))
                ),
            )),
        }
    }
}

impl Job for HbmJob {
    fn id(&self) -> JobId {
        self.id
    }

    fn step(&mut self) -> Vec<FromWorker> {
        let msg = hbm_chunk(self);
        self.finished = matches!(msg, FromWorker::HbmPoints { finished: true, .. });
        vec![msg]
    }

    fn finished(&self) -> bool {
        self.finished
    }

    fn progress(&self) -> (usize, usize) {
        ((100.0 * self.cont.progress()).floor() as usize, 100)
    }
}

/// Advances the branch by up to [`HBM_CHUNK`] points, one at a time so that
/// a failure keeps every point before it; points beyond the chunk (a
/// restart's piece) wait for the next chunks.
fn hbm_chunk(job: &mut HbmJob) -> FromWorker {
    let mut error = None;
    while job.pending.len() < HBM_CHUNK && !job.cont.is_finished() {
        match job.cont.advance(1) {
            Ok(pts) => job.pending.extend(pts.iter().map(hbm_sample)),
            Err(e) => {
                error = Some(explain(&e, Task::HarmonicBalance, job.loaded));
                break;
            }
        }
    }
    let n = if error.is_some() {
        job.pending.len()
    } else {
        job.pending.len().min(HBM_CHUNK)
    };
    let points: Vec<HbmSample> = job.pending.drain(..n).collect();
    let finished = error.is_some() || (job.cont.is_finished() && job.pending.is_empty());
    FromWorker::HbmPoints {
        id: job.id,
        points,
        progress: job.cont.progress(),
        finished,
        error,
        notes: if finished {
            job.cont.notes()
        } else {
            Vec::new()
        },
    }
}

/// A branch point as the page's message carries it (µm, rounded as the
/// page shows them); the command line's figures use it too.
pub fn hbm_sample(p: &BranchPoint) -> HbmSample {
    HbmSample {
        omega: p.omega,
        meshes: p
            .meshes
            .iter()
            .map(|m| HbmMesh {
                rel_min_um: um(m.rel_min_m),
                rel_max_um: um(m.rel_max_m),
                regime: m.impact.into(),
            })
            .collect(),
        stable: p.stable,
        bifurcation: p.bifurcation.map(Into::into),
        piece: p.piece,
    }
}
