//! The worker's jobs, one module per kind, behind one trait.
//!
//! Each kind's module turns its [`figures::protocol::JobSpec`] into a job
//! (`start`), and the job computes one bounded chunk per [`Job::step`]
//! (a slice of a steady state or of a Lyapunov run, or a few
//! harmonic-balance points), posting its data and progress as
//! [`FromWorker`] messages. Cancelling a job is dropping it; the runner
//! ([`crate::WorkerCore`]) keeps at most one job of each kind per
//! computation and loops over the kinds in its priority order. [`start`]
//! is the one place that maps a spec to its kind's job.
//!
//! Architecture invariant: a job's step is bounded: [`SLICE_STEPS`]
//! integrator steps of the point in progress (the selected-Omega run, a
//! bifurcation point, an overlay point, a Lyapunov point, a map cell; the
//! run pauses and resumes without changing a bit), [`hbm::HBM_CHUNK`]
//! branch points, [`SLICE_STEPS`] steps' work of a shooting branch
//! step ([`orbits`]: a step carrying the monodromy's tangents counts one
//! per vector; the branch step pauses and is taken up again, bit for bit),
//! or [`boundaries::BOUNDARY_CHUNK`] boundary points.
//! A newer job, a cancel or an export request waits at most one step.

pub mod bif;
pub mod boundaries;
pub mod chain;
pub mod hbm;
pub mod lyap;
pub mod map;
pub mod omega;
pub mod orbits;
pub mod overlay;

use bif::{BifJob, BifSpec, SharedBands};
use figures::protocol::{FromWorker, JobId, JobSpec};
use hbm::HbmJob;
use map::MapJob;
use omega::{OmegaJob, OmegaRun};
use solver::map::MapSpec;
use solver::model::Model;
use solver::params::ModelParams;

/// Integrator steps per step of a sliced run (the selected-Omega run, a
/// bifurcation, overlay or Lyapunov point, a map cell): a few ms in the
/// browser, so a newer job or a cancel waits at most that long, however
/// long the point's run is.
pub const SLICE_STEPS: u64 = 3000;

/// A job of one kind in progress in a worker.
pub trait Job {
    /// The job's id (the page's, so replies to an old job are recognised).
    fn id(&self) -> JobId;
    /// Computes one bounded chunk and returns the messages to post.
    fn step(&mut self) -> Vec<FromWorker>;
    /// Whether every chunk has been computed (the runner then drops it).
    fn finished(&self) -> bool;
    /// Units done and in all (steady states, cells, per cent of the range).
    fn progress(&self) -> (usize, usize);
    /// The progress as the message the page reads.
    fn progress_message(&self) -> FromWorker {
        let (done, total) = self.progress();
        FromWorker::Progress {
            id: self.id(),
            done,
            total,
        }
    }
    /// The finished job's data as the CLI's JSON (`other`: the other
    /// shards' JSON to merge), for kinds that export from the worker.
    fn export(&self, _mesh: Option<usize>, _other: &[String]) -> Option<FromWorker> {
        None
    }
    /// Whether the finished shards are kept for [`Job::export`].
    fn exports(&self) -> bool {
        false
    }
}

/// The message of a job that failed.
pub fn failed(id: JobId, message: impl Into<String>) -> FromWorker {
    FromWorker::Failed {
        id,
        message: message.into(),
    }
}

/// A started job: the job and its first messages, or the failure to post.
pub(crate) type Started = Result<(Box<dyn Job>, Vec<FromWorker>), FromWorker>;

fn boxed<J: Job + 'static>(r: Result<(J, Vec<FromWorker>), FromWorker>) -> Started {
    r.map(|(j, out)| (Box::new(j) as Box<dyn Job>, out))
}

/// The job of `spec` (id `id`, on `model` built from `params`), and its
/// first messages; `bands` caches the bifurcation sweep's
/// parametric-instability bands.
pub(crate) fn start(
    id: JobId,
    params: ModelParams,
    model: Model,
    spec: JobSpec,
    bands: &SharedBands,
) -> Started {
    match spec {
        JobSpec::Omega(spec) => {
            let job = OmegaJob { id, model, spec };
            Ok((Box::new(OmegaRun::start(job, params)), Vec::new()))
        }
        JobSpec::HarmonicBalance {
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
        JobSpec::Overlay {
            omega_from,
            omega_to,
            points,
            chains,
            shard,
            run,
        } => boxed(overlay::start(
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
            boxed(BifJob::start(id, params, model, spec, bands))
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
        } => boxed(lyap::start(
            id,
            model,
            (omega_from, omega_to, points),
            (chains, shard),
            (transient_periods, periods),
        )),
        JobSpec::Orbits {
            omega_from,
            omega_to,
            points,
        } => boxed(orbits::OrbitsJob::start(
            id,
            model,
            (omega_from, omega_to, points),
        )),
        JobSpec::Boundaries {
            key,
            omega_from,
            omega_to,
            value_from,
            value_to,
            levels,
            points,
            harmonics,
            contact_mesh,
        } => {
            let mut spec = solver::boundaries::BoundarySpec::new(
                &key,
                (value_from, value_to),
                (omega_from, omega_to),
            );
            spec.levels = levels;
            spec.points = points;
            spec.harmonics = harmonics;
            spec.contact_mesh = contact_mesh;
            boxed(boundaries::BoundariesJob::start(id, &params, spec))
        }
    }
}

/// TE and its rate of mesh `j` at phase 0 of the excitation (the Poincaré phase).
pub(crate) fn excitation_at(model: &Model, j: usize, omega_rad_s: f64, t_s: f64) -> (f64, f64) {
    let (s, c) = (omega_rad_s * t_s).sin_cos();
    let (_, e, de) = model.system.meshes[j].excitation(omega_rad_s, c, s);
    (e, de)
}
