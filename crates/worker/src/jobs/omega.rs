//! The selected-Omega job: one steady state with every mesh's history,
//! turned into the data of the phase portrait, Poincaré section, time
//! history, spectrum and gear-set animation ([`OmegaResult`]); also the
//! page's bounded preview run ([`omega_result`] with a start state).

use super::{excitation_at, failed, Job, SLICE_STEPS};
use figures::protocol::{
    history_start, um, AnimHistory, ForceByOrder, FromWorker, JobId, KindSharing, MeshSummary,
    OmegaResult, OmegaSpec, RunOptions,
};
use figures::settings::Settings;
use solver::model::Model;
use solver::params::ModelParams;
use solver::steady::{spectrum, steady_state, SteadyOptions, SteadyRun, SteadyState};

/// Samples per mesh period of the selected-Omega history.
pub const SAMPLES_PER_PERIOD: u32 = 64;
/// Highest mesh order of the spectrum.
pub const MAX_ORDER: f64 = 8.0;

/// The selected-Omega run of `settings` on its `model` with periods `run`:
/// the one spec the worker's job, the page's preview (with
/// [`PREVIEW_RUN`]) and the CLI's figures run.
pub fn selected_spec(settings: &Settings, model: &Model, run: RunOptions) -> OmegaSpec {
    OmegaSpec {
        omega: settings.view.omega,
        mesh: settings.mesh_index(model),
        run,
        samples_per_period: SAMPLES_PER_PERIOD,
        max_order: MAX_ORDER,
    }
}

/// An Omega job waiting for its one step (also the page's preview run).
pub struct OmegaJob {
    /// Job id.
    pub id: JobId,
    /// The model.
    pub model: Model,
    /// What to run.
    pub spec: OmegaSpec,
}

/// Periods of the page's preview run: continued from the last result's end
/// state under the new settings, so the selected-Omega views follow a
/// slider within a frame while the full steady state computes.
pub const PREVIEW_RUN: RunOptions = RunOptions {
    transient_periods: 20,
    record_periods: 10,
};

/// The preview's step budget per period: it bounds the main thread's time
/// (about 10 ms in the browser); a run that needs more steps shows no
/// preview and waits for the worker.
pub const PREVIEW_STEPS_PER_PERIOD: u64 = 300;

/// Why the selected-Omega run has no result.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum OmegaError {
    /// The plotted mesh is not one of the model's.
    #[error("mesh {0} does not exist in this model")]
    NoMesh(usize),
    /// The steady state failed.
    #[error("Omega = {omega}: {source}")]
    Solver {
        /// The Omega of the run.
        omega: f64,
        /// The solver's reason.
        source: solver::SolverError,
    },
    /// The run kept no history of the plotted mesh.
    #[error("the run kept no history of the plotted mesh")]
    NoHistory,
}

impl OmegaJob {
    /// Why this job has no result, in plain words with what to try.
    fn failure_words(&self, e: &OmegaError) -> String {
        let at = figures::words::short(self.spec.omega);
        match e {
            OmegaError::Solver { source, .. } => format!(
                "The steady state at Ω {at} could not be found: {}",
                figures::failure::explain(
                    source,
                    figures::failure::Task::SteadyState,
                    figures::failure::is_loaded(&self.model)
                )
            ),
            other => format!("The steady state at Ω {at} could not be computed: {other}."),
        }
    }
}

impl OmegaError {
    fn solver(job: &OmegaJob) -> impl FnOnce(solver::SolverError) -> Self + '_ {
        move |source| OmegaError::Solver {
            omega: job.spec.omega,
            source,
        }
    }
}

/// An Omega job in the worker: its steady state in slices of
/// [`SLICE_STEPS`] integrator steps, then the result.
pub(crate) struct OmegaRun {
    job: OmegaJob,
    /// The steady state in progress; `Err` holds a failure to report at
    /// the next step (bad options or mesh), `None` once finished.
    run: Option<Result<SteadyRun, OmegaError>>,
    /// The parameters the model was built from: the CLI JSON gains ISO
    /// 6336-1's K_v from them, as `gearshock simulate` prints it.
    params: ModelParams,
}

impl OmegaRun {
    /// Starts `job` on the model built from `params` (no integration yet).
    pub(crate) fn start(job: OmegaJob, params: ModelParams) -> Self {
        let run = omega_options(&job, false).and_then(|opts| {
            SteadyRun::new(&job.model, &opts, None).map_err(OmegaError::solver(&job))
        });
        OmegaRun {
            job,
            run: Some(run),
            params,
        }
    }
}

/// `result`'s CLI JSON with ISO 6336-1's K_v added at `inputs`, as
/// `gearshock simulate` adds it (`report::add_iso6336`): the worker's
/// full run adds it at the standard's defaults, the page's export again
/// at the page's grade and face width (the K_v it had is replaced); the
/// page's preview has no CLI JSON.
pub fn with_iso6336(
    result: &mut OmegaResult,
    params: &ModelParams,
    model: &Model,
    inputs: &solver::iso6336::IsoInputs,
) {
    let Ok(mut v) = serde_json::from_str::<serde_json::Value>(&result.cli_json) else {
        return;
    };
    report::add_iso6336(
        &mut v,
        params,
        model,
        result.mesh,
        result.mesh_freq_hz,
        inputs,
    );
    result.cli_json = v.to_string();
}

impl Job for OmegaRun {
    fn id(&self) -> JobId {
        self.job.id
    }

    fn step(&mut self) -> Vec<FromWorker> {
        let id = self.job.id;
        let result = match self.run.as_mut() {
            None => return Vec::new(),
            Some(Err(e)) => Err(e.clone()),
            Some(Ok(run)) => match run.advance(&self.job.model, SLICE_STEPS) {
                Ok(None) => return Vec::new(),
                Ok(Some(ss)) => omega_result_of(&self.job, ss, false).map(|mut r| {
                    let inputs = solver::iso6336::IsoInputs::default();
                    with_iso6336(&mut r, &self.params, &self.job.model, &inputs);
                    r
                }),
                Err(e) => Err(OmegaError::solver(&self.job)(e)),
            },
        };
        self.run = None;
        let msg = match result {
            Ok(result) => FromWorker::Omega {
                id,
                result: Box::new(result),
            },
            Err(e) => failed(id, self.job.failure_words(&e)),
        };
        vec![msg, FromWorker::Done { id }]
    }

    fn finished(&self) -> bool {
        self.run.is_none()
    }

    fn progress(&self) -> (usize, usize) {
        (usize::from(self.run.is_none()), 1)
    }
}

/// The steady-state options of `job` (`preview`: the page's bounded run).
fn omega_options(job: &OmegaJob, preview: bool) -> Result<SteadyOptions, OmegaError> {
    let n_mesh = job.model.system.meshes.len();
    let spec = &job.spec;
    if let Some(j) = spec.mesh.filter(|&j| j >= n_mesh) {
        return Err(OmegaError::NoMesh(j));
    }
    let mut opts = SteadyOptions::new(spec.omega);
    opts.transient_periods = spec.run.transient_periods;
    opts.record_periods = spec.run.record_periods;
    opts.samples_per_period = spec.samples_per_period.clamp(8, 256);
    if preview {
        // Integration only: with shooting's Newton steps on the
        // variational equations the preview took about 36 ms of the main
        // thread a slider change, 20 without (a sampling profile of the
        // page); the worker's full run finds the exact orbit.
        opts.max_steps_per_period = PREVIEW_STEPS_PER_PERIOD;
        opts.shooting = false;
    }
    // Every mesh's history: the animated gear set colours every mesh.
    opts.history_meshes = (0..n_mesh).collect();
    Ok(opts)
}

/// The selected-Omega views' data. With `preview_from` (a previous result's
/// end state) it is the page's bounded preview run: it starts there, keeps
/// to [`PREVIEW_STEPS_PER_PERIOD`], and carries no CLI JSON (the full run,
/// from the static state as `gearshock simulate` starts, replaces it).
pub fn omega_result(
    job: &OmegaJob,
    preview_from: Option<&[f64]>,
) -> Result<OmegaResult, OmegaError> {
    let opts = omega_options(job, preview_from.is_some())?;
    let ss = steady_state(&job.model, &opts, preview_from).map_err(OmegaError::solver(job))?;
    omega_result_of(job, ss, preview_from.is_some())
}

/// The selected-Omega views' data of `job`'s steady state `ss` (`preview`:
/// the page's bounded run, without CLI JSON).
fn omega_result_of(
    job: &OmegaJob,
    ss: SteadyState,
    preview: bool,
) -> Result<OmegaResult, OmegaError> {
    let model = &job.model;
    let n_mesh = model.system.meshes.len();
    let samples_per_period = job.spec.samples_per_period.clamp(8, 256);
    let record_periods = job.spec.run.record_periods;
    let max_order = job.spec.max_order;
    let j = job.spec.mesh.unwrap_or_else(|| ss.worst_mesh());
    let Some(h) = ss.histories.iter().find(|h| h.mesh == j) else {
        return Err(OmegaError::NoHistory);
    };
    let m = &ss.meshes[j];
    let w = ss.omega_rad_s;
    let xdot_m_s: Vec<f64> = h
        .velocity_m_s
        .iter()
        .zip(&ss.sample_times_s)
        .map(|(v, &t)| v - excitation_at(model, j, w, t).1)
        .collect();
    let (e0, de0) = excitation_at(model, j, w, 0.0);
    let spec = spectrum(&h.rel_m, samples_per_period, record_periods, max_order);
    let cli_json = if preview {
        String::new()
    } else {
        report::simulate_json(model, &ss, j, max_order).to_string()
    };
    let start = history_start(h.rel_m.len(), samples_per_period, record_periods);
    let mut anim_x = vec![Vec::new(); n_mesh];
    for hist in &ss.histories {
        if let Some(slot) = anim_x.get_mut(hist.mesh) {
            *slot = hist.rel_m[start.min(hist.rel_m.len())..]
                .iter()
                .map(|x| (x * 1e9).round() / 1e3)
                .collect();
        }
    }
    let anim = AnimHistory {
        start_sample: start as u32,
        x_um: anim_x,
        backlash_um: model
            .system
            .meshes
            .iter()
            .map(|m| um(m.backlash_m))
            .collect(),
    };
    let result = OmegaResult {
        omega: ss.omega,
        mesh: j,
        mesh_name: model.system.meshes[j].name.clone(),
        backlash_um: um(model.system.meshes[j].backlash_m),
        regime: m.impact.into(),
        period: ss.period,
        motion: ss.motion,
        dynamic_factor: m.dynamic_factor,
        mesh_freq_hz: ss.mesh_freq_hz,
        transient_periods_run: ss.stats.transient_periods_run,
        settled: ss.stats.settled,
        samples_per_period,
        record_periods,
        x_um: h.rel_m.iter().map(|x| um(*x)).collect(),
        xdot_m_s: xdot_m_s.iter().map(|v| (v * 1e9).round() / 1e9).collect(),
        poincare_x_um: m.poincare_delta_m.iter().map(|d| um(d - e0)).collect(),
        poincare_xdot_m_s: m.poincare_velocity_m_s.iter().map(|v| v - de0).collect(),
        spectrum_order: spec.order,
        spectrum_um: spec.amplitude.iter().map(|a| a * 1e6).collect(),
        all_meshes: model
            .system
            .meshes
            .iter()
            .zip(&ss.meshes)
            .map(|(d, ms)| MeshSummary {
                name: d.name.clone(),
                regime: ms.impact.into(),
                dynamic_factor: ms.dynamic_factor,
            })
            .collect(),
        anim,
        load_sharing: solver::sharing::load_sharing(&model.system, &ss.meshes)
            .into_iter()
            .map(|k| KindSharing {
                kind: k.kind.key().to_string(),
                peak_force_n: k.peak_force_n,
                factor: k.factor,
            })
            .collect(),
        force_orders: solver::orders::force_orders(&model.system, &ss, j, max_order)
            .map(|f| ForceByOrder::of(&f)),
        steps: ss.stats.integrator.steps,
        cli_json,
        preview,
        end_state: ss.end_state,
    };
    Ok(result)
}
