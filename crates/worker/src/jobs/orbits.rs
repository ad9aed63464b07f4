//! The periodic orbits' branches on the bifurcation diagram: shooting
//! continuation in Omega (`solver::orbits`), period doublings followed,
//! [`SLICE_STEPS`] integrator steps of work per step (a branch step that
//! needs more pauses and is taken up again by the next, so the job never
//! holds its worker longer than any other job's slice); each finished
//! point is posted at once, with every mesh's Poincaré samples, found by
//! integrating the converged orbit over its period.

use super::{excitation_at, failed, Job, SLICE_STEPS};
use figures::failure::{explain, is_loaded, Task};
use figures::protocol::{um, FromWorker, JobId, OrbitSample};
use solver::model::Model;
use solver::orbits::{ShootFrfSpec, ShootPoint, ShootingContinuation};
use solver::shooting::Reduced;
use solver::steady::{steady_state, SteadyOptions};

/// The most branch points one job computes: the continuation can wind
/// through folds for long on an impacting model, and the diagram needs
/// the branches near the sweep, not every turn.
pub const MAX_ORBIT_POINTS: usize = 300;

/// A shooting continuation in progress.
pub(crate) struct OrbitsJob {
    id: JobId,
    model: Model,
    cont: ShootingContinuation,
    sent: usize,
    started: bool,
    finished: bool,
}

impl OrbitsJob {
    /// Starts the continuation over `omega_from ..= omega_to` with
    /// resolution `points`, upward from the period-1 orbit at `omega_from`.
    pub(crate) fn start(
        id: JobId,
        model: Model,
        (omega_from, omega_to, points): (f64, f64, u32),
    ) -> Result<(Self, Vec<FromWorker>), FromWorker> {
        let spec = ShootFrfSpec::new(omega_from, omega_to, points);
        match ShootingContinuation::new(&model, spec) {
            Ok(cont) => Ok((
                OrbitsJob {
                    id,
                    model,
                    cont,
                    sent: 0,
                    started: false,
                    finished: false,
                },
                vec![FromWorker::Progress {
                    id,
                    done: 0,
                    total: MAX_ORBIT_POINTS,
                }],
            )),
            Err(e) => Err(failed(
                id,
                format!(
                    "The shooting branches could not be started: {}",
                    explain(&e, Task::Shooting, is_loaded(&model))
                ),
            )),
        }
    }

    /// A failure of the branch in plain words.
    fn explain(&self, e: &solver::SolverError) -> String {
        explain(e, Task::Shooting, is_loaded(&self.model))
    }

    fn reply(&mut self, points: Vec<OrbitSample>, error: Option<String>) -> Vec<FromWorker> {
        self.sent += points.len();
        self.finished = error.is_some() || self.cont.is_finished() || self.sent >= MAX_ORBIT_POINTS;
        vec![FromWorker::OrbitPoints {
            id: self.id,
            points,
            finished: self.finished,
            error,
        }]
    }
}

impl Job for OrbitsJob {
    fn id(&self) -> JobId {
        self.id
    }

    fn step(&mut self) -> Vec<FromWorker> {
        let pts = if self.started {
            self.cont.advance_within(1, SLICE_STEPS)
        } else {
            self.started = true;
            self.cont.first_point().map(|p| vec![p])
        };
        let pts = match pts {
            Ok(pts) => pts,
            Err(e) => return self.reply(Vec::new(), Some(self.explain(&e))),
        };
        if pts.is_empty() && !self.cont.is_finished() {
            // The branch step paused: nothing to post yet.
            return Vec::new();
        }
        let mut samples = Vec::with_capacity(pts.len());
        for p in &pts {
            match orbit_sample(&self.model, p) {
                Ok(s) => samples.push(s),
                Err(e) => return self.reply(samples, Some(self.explain(&e))),
            }
        }
        self.reply(samples, None)
    }

    fn finished(&self) -> bool {
        self.finished
    }

    fn progress(&self) -> (usize, usize) {
        (self.sent.min(MAX_ORBIT_POINTS), MAX_ORBIT_POINTS)
    }
}

/// A branch point as the page draws it: the orbit integrated over its
/// period from its start (phase 0 of the excitation), every mesh's x
/// sampled once per mesh period.
pub fn orbit_sample(model: &Model, p: &ShootPoint) -> solver::Result<OrbitSample> {
    let bp = &p.point;
    let red = Reduced::new(model, bp.omega);
    let start = red.to_state(&bp.coefficients, (0.0, 0.0));
    let mut opts = SteadyOptions::new(bp.omega);
    opts.transient_periods = 0;
    opts.record_periods = p.period;
    opts.early_settle = false;
    opts.samples_per_period = 0;
    opts.shooting = false;
    let ss = steady_state(model, &opts, Some(&start))?;
    let w = bp.omega * model.system.omega_ref_rad_s;
    let x_um = ss
        .meshes
        .iter()
        .enumerate()
        .map(|(j, m)| {
            let (e0, _) = excitation_at(model, j, w, 0.0);
            m.poincare_delta_m.iter().map(|d| um(d - e0)).collect()
        })
        .collect();
    Ok(OrbitSample {
        omega: bp.omega,
        period: p.period,
        stable: bp.stable,
        bifurcation: bp.bifurcation.map(Into::into),
        piece: bp.piece,
        x_um,
    })
}
