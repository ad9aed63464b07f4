//! The Web Worker's job runner, as plain Rust: no browser types, so it is
//! tested natively.
//!
//! The worker's thin shell (`web.rs`) feeds every incoming message to
//! [`WorkerCore::handle`] and, while [`WorkerCore::has_work`], calls
//! [`WorkerCore::step`] in a loop for a few milliseconds, posts the replies,
//! and yields to the event loop so that newer jobs and cancels arrive. One
//! step computes one steady state, or [`HBM_CHUNK`] points of the
//! harmonic-balance branch: the bounded chunk of work.
//!
//! The selected-Omega job is served first, so the views at the selected
//! Omega update even while a long sweep runs; then the harmonic-balance
//! branch of the frequency response (the view a slider drag watches, and the
//! quickest sweep); the time-integration overlay grid and the bifurcation
//! sweep then take turns, one steady state each; the Lyapunov curve and
//! then the impact-regime map run when those are idle.

use crate::protocol::{
    encode, BifMesh, BifSample, FrSample, FromWorker, HbmMesh, HbmSample, JobId, JobKind, JobSpec,
    LyapSample, MapSample, MeshExtremes, MeshSummary, OmegaResult, Regime, RunOptions, ToWorker,
};
use serde_json::{Map, Value};
use solver::hbm::{BranchPoint, FrfContinuation, FrfSpec};
use solver::keys;
use solver::lyapunov::{largest_exponent, LyapunovOptions};
use solver::map::{MapSpec, RegimeMap};
use solver::params::ModelParams;
use solver::report;
use solver::steady::{spectrum, steady_state, Model, SteadyOptions, SteadyState};
use solver::sweep::{canonical_order, BifurcationSweep, Directions, SweepPoint, SweepSpec};

/// An Omega job waiting for its one step (also the page's preview run).
pub struct OmegaJob {
    /// Job id.
    pub id: JobId,
    /// The model.
    pub model: Model,
    /// Dimensionless frequency.
    pub omega: f64,
    /// Mesh to plot, `None` for the worst.
    pub mesh: Option<usize>,
    /// Transient and recorded periods.
    pub run: RunOptions,
    /// History samples per mesh period.
    pub samples_per_period: u32,
    /// Highest spectrum order.
    pub max_order: f64,
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

/// Points of the harmonic-balance branch computed per step: a few
/// milliseconds each, so a newer job or a cancel waits at most a few tens of
/// milliseconds.
pub const HBM_CHUNK: usize = 8;

/// A harmonic-balance branch in progress.
struct HbmJob {
    id: JobId,
    cont: FrfContinuation,
}

/// A time-integration overlay grid in progress: one continuation chain.
struct FrJob {
    id: JobId,
    model: Model,
    omegas: Vec<(u32, f64)>,
    next: usize,
    run: RunOptions,
    state: Option<Vec<f64>>,
}

/// A bifurcation shard in progress (or finished, kept for export).
struct BifJob {
    id: JobId,
    params: ModelParams,
    sweep: BifurcationSweep,
    points: Vec<SweepPoint>,
}

/// A share of an impact-regime map in progress.
struct MapJob {
    id: JobId,
    map: RegimeMap,
}

/// A chain of the Lyapunov curve in progress.
struct LyapJob {
    id: JobId,
    model: Model,
    omegas: Vec<(u32, f64)>,
    next: usize,
    transient_periods: u32,
    periods: u32,
    state: Option<Vec<f64>>,
}

/// The worker's state: at most one job of each kind.
#[derive(Default)]
pub struct WorkerCore {
    omega: Option<OmegaJob>,
    hbm: Option<HbmJob>,
    fr: Option<FrJob>,
    bif: Option<BifJob>,
    finished_bif: Option<BifJob>,
    map: Option<MapJob>,
    lyap: Option<LyapJob>,
    turn: usize,
    /// The jobs of the pinned state A of an A/B comparison.
    pinned: Option<Box<WorkerCore>>,
    pinned_turn: bool,
    /// The last parametric-instability bands and what they depend on (the
    /// parameters without backlash and TE, the Omega range): a backlash or
    /// TE drag restarts the sweep but not the scan.
    bands: Option<BandsCache>,
}

/// Parametric-instability bands and their inputs.
#[derive(Debug, Clone, PartialEq)]
struct BandsCache {
    params: ModelParams,
    range: (f64, f64),
    bands: Vec<(f64, f64)>,
}

/// Omega samples of the parametric-instability scan over the sweep's range
/// (a band narrower than the spacing can slip between them).
pub const BAND_SAMPLES: u32 = 300;

/// The Omega intervals of `range` where the engaged system's Floquet
/// spectral radius exceeds 1, from `samples` equally spaced Omegas, their
/// edges interpolated linearly in `ln rho`; empty if the scan fails.
pub fn unstable_bands(model: &Model, range: (f64, f64), samples: u32) -> Vec<(f64, f64)> {
    let Ok(engaged) = solver::parametric::Parametric::new(model) else {
        return Vec::new();
    };
    let n = samples.max(2);
    let mut growth = Vec::with_capacity(n as usize);
    for i in 0..n {
        let omega = range.0 + (range.1 - range.0) * f64::from(i) / f64::from(n - 1);
        match engaged.at(omega.max(0.01)) {
            Ok(s) => growth.push((omega, s.growth_per_period())),
            Err(_) => return Vec::new(),
        }
    }
    let edge = |(o0, g0): (f64, f64), (o1, g1): (f64, f64)| o0 + (o1 - o0) * g0 / (g0 - g1);
    let mut bands = Vec::new();
    let mut start = growth.first().filter(|g| g.1 > 0.0).map(|g| g.0);
    for w in growth.windows(2) {
        let (a, b) = (w[0], w[1]);
        match (a.1 > 0.0, b.1 > 0.0) {
            (false, true) => start = Some(edge(a, b)),
            (true, false) => {
                if let Some(s0) = start.take() {
                    bands.push((s0, edge(a, b)));
                }
            }
            _ => {}
        }
    }
    if let Some(s0) = start {
        bands.push((s0, range.1));
    }
    bands
}

fn failed(id: JobId, message: impl Into<String>) -> FromWorker {
    FromWorker::Failed {
        id,
        message: message.into(),
    }
}

fn model_from(params: &Map<String, Value>) -> Result<(ModelParams, Model), String> {
    let p = keys::from_json(params).map_err(|e| e.to_string())?;
    let model = Model::new(&p).map_err(|e| e.to_string())?;
    Ok((p, model))
}

/// Rounds to 1e-6 um: plenty for plots, and it keeps messages short.
fn round_um(x: f64) -> f64 {
    (x * 1e6).round() / 1e6
}

impl WorkerCore {
    /// A worker with no jobs.
    pub fn new() -> Self {
        Self::default()
    }

    /// Whether a job waits for [`Self::step`].
    pub fn has_work(&self) -> bool {
        self.has_own_work() || self.pinned.as_ref().is_some_and(|p| p.has_work())
    }

    fn has_own_work(&self) -> bool {
        self.omega.is_some()
            || self.hbm.is_some()
            || self.fr.is_some()
            || self.bif.is_some()
            || self.map.is_some()
            || self.lyap.is_some()
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
                self.drop_job(kind);
                Vec::new()
            }
            ToWorker::RunPinned { id, params, job } => self
                .pinned
                .get_or_insert_with(Box::default)
                .start(id, &params, job),
            ToWorker::CancelPinned { kind } => {
                if let Some(p) = self.pinned.as_mut() {
                    p.drop_job(kind);
                }
                Vec::new()
            }
            ToWorker::ExportBif { id, mesh, other } => vec![self.export_bif(id, mesh, &other)],
        }
    }

    /// The instability bands of `model` over `range`, from the cache when
    /// only the backlash or the TE changed.
    fn bands_for(
        &mut self,
        params: &ModelParams,
        model: &Model,
        range: (f64, f64),
    ) -> Vec<(f64, f64)> {
        let mut key = params.clone();
        let _ = keys::set(&mut key, "backlash_um", keys::Value::Num(0.0));
        let _ = keys::set(&mut key, "te_um", keys::Value::Num(0.0));
        if let Some(c) = &self.bands {
            if c.params == key && c.range == range {
                return c.bands.clone();
            }
        }
        let bands = unstable_bands(model, range, BAND_SAMPLES);
        self.bands = Some(BandsCache {
            params: key,
            range,
            bands: bands.clone(),
        });
        bands
    }

    fn drop_job(&mut self, kind: JobKind) {
        match kind {
            JobKind::Omega => self.omega = None,
            JobKind::Hbm => self.hbm = None,
            JobKind::Fr => self.fr = None,
            JobKind::Bif => self.bif = None,
            JobKind::Map => self.map = None,
            JobKind::Lyap => self.lyap = None,
        }
    }

    fn start(&mut self, id: JobId, params: &Map<String, Value>, job: JobSpec) -> Vec<FromWorker> {
        // A new job replaces the old one of its kind, even if it fails.
        self.drop_job(job.kind());
        let (params, model) = match model_from(params) {
            Ok(x) => x,
            Err(e) => return vec![failed(id, e)],
        };
        match job {
            JobSpec::Omega {
                omega,
                mesh,
                run,
                samples_per_period,
                max_order,
            } => {
                self.omega = Some(OmegaJob {
                    id,
                    model,
                    omega,
                    mesh,
                    run,
                    samples_per_period,
                    max_order,
                });
                Vec::new()
            }
            JobSpec::Hbm {
                omega_from,
                omega_to,
                points,
                harmonics,
                stability,
            } => {
                let mut spec = FrfSpec::new(omega_from, omega_to, points);
                spec.harmonics = harmonics as usize;
                spec.direction = solver::sweep::Direction::Up;
                spec.stability = stability;
                match FrfContinuation::new(&model, spec) {
                    Ok(cont) => {
                        self.hbm = Some(HbmJob { id, cont });
                        vec![FromWorker::Progress {
                            id,
                            done: 0,
                            total: 100,
                        }]
                    }
                    Err(e) => vec![failed(id, e.to_string())],
                }
            }
            JobSpec::Fr {
                omega_from,
                omega_to,
                points,
                chains,
                shard,
                run,
            } => {
                let mut spec = SweepSpec::new(omega_from, omega_to, points);
                spec.chains = chains;
                spec.shard = Some(shard);
                spec.steady.transient_periods = run.transient_periods;
                spec.steady.record_periods = run.record_periods;
                if let Err(e) = spec.validate(model.system.meshes.len()) {
                    return vec![failed(id, e.to_string())];
                }
                let omegas: Vec<(u32, f64)> = (shard..points)
                    .step_by(chains.max(1) as usize)
                    .map(|i| (i, spec.omega(i)))
                    .collect();
                let total = omegas.len();
                self.fr = Some(FrJob {
                    id,
                    model,
                    omegas,
                    next: 0,
                    run,
                    state: None,
                });
                vec![FromWorker::Progress { id, done: 0, total }]
            }
            JobSpec::Bif {
                omega_from,
                omega_to,
                points,
                directions,
                chains,
                shard,
                run,
            } => {
                let mut spec = SweepSpec::new(omega_from, omega_to, points);
                spec.chains = chains;
                spec.shard = Some(shard);
                spec.directions = match Directions::from_name(&directions) {
                    Some(d) => d,
                    None => return vec![failed(id, "directions: allowed up, down, both")],
                };
                spec.steady.transient_periods = run.transient_periods;
                spec.steady.record_periods = run.record_periods;
                spec.meshes = (0..model.system.meshes.len()).collect();
                // Shard 0 also sends the instability bands of the range.
                let bands = (shard == 0).then(|| FromWorker::Bands {
                    id,
                    bands: self.bands_for(&params, &model, (omega_from, omega_to)),
                });
                match BifurcationSweep::new(model, spec) {
                    Ok(sweep) => {
                        let total = sweep.total();
                        self.bif = Some(BifJob {
                            id,
                            params,
                            sweep,
                            points: Vec::new(),
                        });
                        bands
                            .into_iter()
                            .chain([FromWorker::Progress { id, done: 0, total }])
                            .collect()
                    }
                    Err(e) => vec![failed(id, e.to_string())],
                }
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
                match RegimeMap::new(&params, spec) {
                    Ok(map) => {
                        let total = map.total();
                        self.map = Some(MapJob { id, map });
                        vec![FromWorker::Progress { id, done: 0, total }]
                    }
                    Err(e) => vec![failed(id, e.to_string())],
                }
            }
            JobSpec::Lyap {
                omega_from,
                omega_to,
                points,
                chains,
                shard,
                transient_periods,
                periods,
            } => {
                if points < 2
                    || omega_to.partial_cmp(&omega_from) != Some(std::cmp::Ordering::Greater)
                {
                    return vec![failed(
                        id,
                        "Lyapunov: at least 2 points over an increasing Omega range",
                    )];
                }
                let step = (omega_to - omega_from) / f64::from(points - 1);
                let omegas: Vec<(u32, f64)> = (shard..points)
                    .step_by(chains.max(1) as usize)
                    .map(|i| (i, omega_from + step * f64::from(i)))
                    .collect();
                let total = omegas.len();
                self.lyap = Some(LyapJob {
                    id,
                    model,
                    omegas,
                    next: 0,
                    transient_periods,
                    periods,
                    state: None,
                });
                vec![FromWorker::Progress { id, done: 0, total }]
            }
        }
    }

    /// Does one bounded chunk of the most urgent job.
    pub fn step(&mut self) -> Vec<FromWorker> {
        if let Some(job) = self.omega.take() {
            return vec![run_omega(&job), FromWorker::Done { id: job.id }];
        }
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
        if let Some(job) = self.hbm.as_mut() {
            let msg = hbm_chunk(job);
            if matches!(msg, FromWorker::HbmPoints { finished: true, .. }) {
                self.hbm = None;
            }
            return vec![msg];
        }
        // The frequency-response overlay and the bifurcation sweep take
        // turns, one bounded chunk each, so both diagrams fill in together
        // and show their first points early; the Lyapunov curve and then the
        // regime map use the workers once those are idle (they are the
        // slower, secondary views and must not delay the main diagrams).
        for k in 0..2 {
            let kind = (self.turn + k) % 2;
            let out = match kind {
                0 => self.fr_step(),
                _ => self.bif_step(),
            };
            if let Some(out) = out {
                self.turn = (kind + 1) % 2;
                return out;
            }
        }
        if let Some(out) = self.lyap_step() {
            return out;
        }
        self.map_step().unwrap_or_default()
    }

    fn fr_step(&mut self) -> Option<Vec<FromWorker>> {
        let job = self.fr.as_mut()?;
        let mut out = Vec::new();
        if let Some(&(index, omega)) = job.omegas.get(job.next) {
            job.next += 1;
            let sample = fr_point(job, index, omega);
            out.push(FromWorker::FrPoints {
                id: job.id,
                points: vec![sample],
            });
            out.push(FromWorker::Progress {
                id: job.id,
                done: job.next,
                total: job.omegas.len(),
            });
        }
        if job.next >= job.omegas.len() {
            out.push(FromWorker::Done { id: job.id });
            self.fr = None;
        }
        Some(out)
    }

    fn bif_step(&mut self) -> Option<Vec<FromWorker>> {
        let job = self.bif.as_mut()?;
        let mut out = Vec::new();
        let pts = job.sweep.advance(1);
        let samples: Vec<BifSample> = pts.iter().map(|p| bif_sample(&job.sweep, p)).collect();
        job.points.extend(pts);
        if !samples.is_empty() {
            out.push(FromWorker::BifPoints {
                id: job.id,
                points: samples,
            });
        }
        out.push(FromWorker::Progress {
            id: job.id,
            done: job.sweep.done(),
            total: job.sweep.total(),
        });
        if job.sweep.is_finished() {
            out.push(FromWorker::Done { id: job.id });
            self.finished_bif = self.bif.take();
        }
        Some(out)
    }

    fn map_step(&mut self) -> Option<Vec<FromWorker>> {
        let job = self.map.as_mut()?;
        let mut out = Vec::new();
        let cells: Vec<MapSample> = job
            .map
            .advance(1)
            .into_iter()
            .map(|c| MapSample {
                row: c.row,
                column: c.column,
                omega: c.omega,
                value: c.value,
                regime: c.impact.into(),
                period: c.period,
                error: c.error,
            })
            .collect();
        if !cells.is_empty() {
            out.push(FromWorker::MapCells { id: job.id, cells });
        }
        if job.map.is_finished() {
            out.push(FromWorker::Done { id: job.id });
            self.map = None;
        }
        Some(out)
    }

    fn lyap_step(&mut self) -> Option<Vec<FromWorker>> {
        let job = self.lyap.as_mut()?;
        let mut out = Vec::new();
        if let Some(&(index, omega)) = job.omegas.get(job.next) {
            job.next += 1;
            let mut opts = LyapunovOptions::new(omega);
            opts.transient_periods = job.transient_periods;
            opts.periods = job.periods;
            let sample = match largest_exponent(&job.model, &opts, job.state.as_deref()) {
                Ok(l) => {
                    job.state = Some(l.end_state);
                    LyapSample {
                        index,
                        omega,
                        per_period: Some(l.per_period),
                        per_s: Some(l.per_s),
                        error: None,
                    }
                }
                Err(e) => {
                    // The chain restarts from the static equilibrium.
                    job.state = None;
                    LyapSample {
                        index,
                        omega,
                        per_period: None,
                        per_s: None,
                        error: Some(e.to_string()),
                    }
                }
            };
            out.push(FromWorker::LyapPoints {
                id: job.id,
                points: vec![sample],
            });
        }
        if job.next >= job.omegas.len() {
            out.push(FromWorker::Done { id: job.id });
            self.lyap = None;
        }
        Some(out)
    }

    fn export_bif(&self, id: JobId, mesh: Option<usize>, other: &[String]) -> FromWorker {
        let Some(job) = self.finished_bif.as_ref().filter(|j| j.id == id) else {
            return failed(id, "the bifurcation sweep has not finished yet");
        };
        let mut spec = job.sweep.spec().clone();
        let model = job.sweep.model();
        let mut points = job.points.clone();
        if let Some(j) = mesh {
            if j >= model.system.meshes.len() {
                return failed(id, format!("no mesh {j}"));
            }
            spec.meshes = vec![j];
            for p in &mut points {
                p.meshes.retain(|m| m.mesh == j);
            }
        }
        canonical_order(&mut points);
        let mine = report::sweep_json(model, &job.params, &spec, &points);
        if other.is_empty() {
            return FromWorker::Export {
                id,
                text: mine.to_string(),
            };
        }
        let mut shards = vec![mine];
        for text in other {
            match serde_json::from_str::<Value>(text) {
                Ok(v) => shards.push(v),
                Err(e) => return failed(id, format!("cannot read the other shard: {e}")),
            }
        }
        match report::merge_shards(&shards) {
            Ok(v) => FromWorker::Export {
                id,
                text: v.to_string(),
            },
            Err(e) => failed(id, e.to_string()),
        }
    }
}

/// TE and its rate of mesh `j` at phase 0 of the excitation (the Poincaré phase).
fn excitation_at(model: &Model, j: usize, omega_rad_s: f64, t_s: f64) -> (f64, f64) {
    let (s, c) = (omega_rad_s * t_s).sin_cos();
    let (_, e, de) = model.system.meshes[j].excitation(omega_rad_s, c, s);
    (e, de)
}

/// Advances the branch by up to [`HBM_CHUNK`] points, one at a time so that
/// a failure keeps every point before it.
fn hbm_chunk(job: &mut HbmJob) -> FromWorker {
    let mut points = Vec::new();
    let mut error = None;
    for _ in 0..HBM_CHUNK {
        if job.cont.is_finished() {
            break;
        }
        match job.cont.advance(1) {
            Ok(pts) => points.extend(pts.iter().map(hbm_sample)),
            Err(e) => {
                error = Some(e.to_string());
                break;
            }
        }
    }
    FromWorker::HbmPoints {
        id: job.id,
        points,
        progress: job.cont.progress(),
        finished: error.is_some() || job.cont.is_finished(),
        error,
    }
}

fn hbm_sample(p: &BranchPoint) -> HbmSample {
    HbmSample {
        omega: p.omega,
        meshes: p
            .meshes
            .iter()
            .map(|m| HbmMesh {
                rel_min_um: round_um(m.rel_min_m * 1e6),
                rel_max_um: round_um(m.rel_max_m * 1e6),
                regime: m.impact.into(),
            })
            .collect(),
        stable: p.stable,
        bifurcation: p.bifurcation.map(Into::into),
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

fn bif_sample(sweep: &BifurcationSweep, p: &SweepPoint) -> BifSample {
    let model = sweep.model();
    let omega_rad_s = p.omega * model.system.omega_ref_rad_s;
    BifSample {
        index: p.index,
        omega: p.omega,
        up: p.direction == solver::sweep::Direction::Up,
        meshes: p
            .meshes
            .iter()
            .map(|m| {
                let (e0, _) = excitation_at(model, m.mesh, omega_rad_s, 0.0);
                BifMesh {
                    x_um: m
                        .poincare_delta_m
                        .iter()
                        .map(|d| round_um((d - e0) * 1e6))
                        .collect(),
                    regime: m.impact.into(),
                }
            })
            .collect(),
        worst_mesh: p.worst_mesh,
        period: p.period,
        error: p.error.clone(),
    }
}

/// The mesh with the largest dynamic factor (as the solver's sweeps define "worst").
pub fn worst_mesh(ss: &SteadyState) -> usize {
    ss.meshes
        .iter()
        .enumerate()
        .max_by(|a, b| {
            let da = a.1.dynamic_factor.unwrap_or(0.0);
            let db = b.1.dynamic_factor.unwrap_or(0.0);
            da.total_cmp(&db)
        })
        .map_or(0, |(j, _)| j)
}

fn run_omega(job: &OmegaJob) -> FromWorker {
    match omega_result(job, None) {
        Ok(result) => FromWorker::Omega {
            id: job.id,
            result: Box::new(result),
        },
        Err(e) => failed(job.id, e),
    }
}

/// The selected-Omega views' data. With `preview_from` (a previous result's
/// end state) it is the page's bounded preview run: it starts there, keeps
/// to [`PREVIEW_STEPS_PER_PERIOD`], and carries no CLI JSON (the full run,
/// from the static state as `gearshock simulate` starts, replaces it).
pub fn omega_result(job: &OmegaJob, preview_from: Option<&[f64]>) -> Result<OmegaResult, String> {
    let model = &job.model;
    let n_mesh = model.system.meshes.len();
    if let Some(j) = job.mesh.filter(|&j| j >= n_mesh) {
        return Err(format!("mesh {j} does not exist in this model"));
    }
    let mut opts = SteadyOptions::new(job.omega);
    opts.transient_periods = job.run.transient_periods;
    opts.record_periods = job.run.record_periods;
    opts.samples_per_period = job.samples_per_period.clamp(8, 256);
    if preview_from.is_some() {
        opts.max_steps_per_period = PREVIEW_STEPS_PER_PERIOD;
    }
    // Every mesh's history: the animated gear set colours every mesh.
    opts.history_meshes = (0..n_mesh).collect();
    let ss = steady_state(model, &opts, preview_from)
        .map_err(|e| format!("Omega = {}: {e}", job.omega))?;
    let j = job.mesh.unwrap_or_else(|| worst_mesh(&ss));
    let Some(h) = ss.histories.iter().find(|h| h.mesh == j) else {
        return Err("the run kept no history of the plotted mesh".into());
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
    let spec = spectrum(
        &h.rel_m,
        opts.samples_per_period,
        opts.record_periods,
        job.max_order,
    );
    let cli_json = match preview_from {
        Some(_) => String::new(),
        None => report::simulate_json(model, &ss, j, job.max_order).to_string(),
    };
    let start =
        crate::plots::history_start(h.rel_m.len(), opts.samples_per_period, opts.record_periods);
    let mut anim_x = vec![Vec::new(); n_mesh];
    for hist in &ss.histories {
        if let Some(slot) = anim_x.get_mut(hist.mesh) {
            *slot = hist.rel_m[start.min(hist.rel_m.len())..]
                .iter()
                .map(|x| (x * 1e9).round() / 1e3)
                .collect();
        }
    }
    let anim = crate::protocol::AnimHistory {
        start_sample: start as u32,
        x_um: anim_x,
        backlash_um: model
            .system
            .meshes
            .iter()
            .map(|m| round_um(m.backlash_m * 1e6))
            .collect(),
    };
    let result = OmegaResult {
        omega: ss.omega,
        mesh: j,
        mesh_name: model.system.meshes[j].name.clone(),
        backlash_um: round_um(model.system.meshes[j].backlash_m * 1e6),
        regime: m.impact.into(),
        period: ss.period,
        dynamic_factor: m.dynamic_factor,
        mesh_freq_hz: ss.mesh_freq_hz,
        transient_periods_run: ss.stats.transient_periods_run,
        settled: ss.stats.settled,
        samples_per_period: opts.samples_per_period,
        record_periods: opts.record_periods,
        x_um: h.rel_m.iter().map(|x| round_um(x * 1e6)).collect(),
        xdot_m_s: xdot_m_s.iter().map(|v| (v * 1e9).round() / 1e9).collect(),
        poincare_x_um: m
            .poincare_delta_m
            .iter()
            .map(|d| round_um((d - e0) * 1e6))
            .collect(),
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
        steps: ss.stats.integrator.steps,
        cli_json,
        preview: preview_from.is_some(),
        end_state: ss.end_state,
    };
    Ok(result)
}

/// The message a worker posts first.
pub fn ready_message() -> String {
    encode(&FromWorker::Ready)
}

/// Which regime the worst meshes of a sample show, for colouring: the most severe.
pub fn severity(r: Regime) -> u8 {
    match r {
        Regime::NoContact => 0,
        Regime::NoImpact => 1,
        Regime::SingleSided => 2,
        Regime::DoubleSided => 3,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::protocol::encode;

    fn params(p: &ModelParams) -> Map<String, Value> {
        keys::to_json(p)
    }

    fn run_msg(id: JobId, p: &ModelParams, job: JobSpec) -> String {
        encode(&ToWorker::Run {
            id,
            params: params(p),
            job,
        })
    }

    fn quick() -> RunOptions {
        RunOptions {
            transient_periods: 20,
            record_periods: 8,
        }
    }

    fn drain(core: &mut WorkerCore) -> Vec<FromWorker> {
        let mut out = Vec::new();
        let mut guard = 0;
        while core.has_work() && guard < 10_000 {
            out.extend(core.step());
            guard += 1;
        }
        out
    }

    #[test]
    fn map_and_lyapunov_jobs_share_the_worker_and_cover_their_shares() {
        let mut core = WorkerCore::new();
        let p = ModelParams::defaults(solver::ModelKind::GearPair);
        core.handle(&run_msg(
            3,
            &p,
            JobSpec::Map {
                key: "backlash_um".into(),
                omega_from: 0.5,
                omega_to: 1.5,
                omega_points: 3,
                value_from: 0.0,
                value_to: 100.0,
                value_points: 3,
                mesh: None,
                shards: 2,
                shard: 1,
                run: quick(),
            },
        ));
        core.handle(&run_msg(
            4,
            &p,
            JobSpec::Lyap {
                omega_from: 0.5,
                omega_to: 1.5,
                points: 3,
                chains: 1,
                shard: 0,
                transient_periods: 20,
                periods: 20,
            },
        ));
        let out = drain(&mut core);
        let cells: Vec<(u32, u32)> = out
            .iter()
            .flat_map(|m| match m {
                FromWorker::MapCells { id: 3, cells } => {
                    cells.iter().map(|c| (c.row, c.column)).collect()
                }
                _ => Vec::new(),
            })
            .collect();
        // Shard 1 of 2 over 3 rows is row 1 only.
        assert_eq!(cells, vec![(1, 0), (1, 1), (1, 2)]);
        let lyap: Vec<f64> = out
            .iter()
            .flat_map(|m| match m {
                FromWorker::LyapPoints { id: 4, points } => {
                    points.iter().filter_map(|p| p.per_period).collect()
                }
                _ => Vec::new(),
            })
            .collect();
        assert_eq!(lyap.len(), 3);
        assert!(lyap.iter().all(|l| l.is_finite()));
        assert!(out.iter().any(|m| matches!(m, FromWorker::Done { id: 3 })));
        assert!(out.iter().any(|m| matches!(m, FromWorker::Done { id: 4 })));
    }

    #[test]
    fn a_pinned_job_runs_beside_the_current_job_of_its_kind() {
        let mut core = WorkerCore::new();
        let p = ModelParams::defaults(solver::ModelKind::GearPair);
        let job = |shard| JobSpec::Fr {
            omega_from: 0.5,
            omega_to: 1.0,
            points: 2,
            chains: 1,
            shard,
            run: quick(),
        };
        core.handle(&run_msg(1, &p, job(0)));
        core.handle(&encode(&ToWorker::RunPinned {
            id: 2,
            params: params(&p),
            job: job(0),
        }));
        let out = drain(&mut core);
        for id in [1, 2] {
            assert!(
                out.iter()
                    .any(|m| matches!(m, FromWorker::Done { id: i } if *i == id)),
                "job {id} did not finish"
            );
        }
        // Cancelling A's job leaves B's alone.
        core.handle(&run_msg(3, &p, job(0)));
        core.handle(&encode(&ToWorker::RunPinned {
            id: 4,
            params: params(&p),
            job: job(0),
        }));
        core.handle(&encode(&ToWorker::CancelPinned { kind: JobKind::Fr }));
        let out = drain(&mut core);
        assert!(out.iter().any(|m| matches!(m, FromWorker::Done { id: 3 })));
        assert!(!out
            .iter()
            .any(|m| matches!(m, FromWorker::FrPoints { id: 4, .. })));
    }

    #[test]
    fn omega_job_returns_history_poincare_and_cli_json() {
        let mut core = WorkerCore::new();
        let p = ModelParams::defaults(solver::ModelKind::GearPair);
        let out = core.handle(&run_msg(
            7,
            &p,
            JobSpec::Omega {
                omega: 0.8,
                mesh: None,
                run: quick(),
                samples_per_period: 32,
                max_order: 4.0,
            },
        ));
        assert!(out.is_empty());
        let out = drain(&mut core);
        let FromWorker::Omega { id, result } = &out[0] else {
            panic!("expected an Omega result, got {out:?}");
        };
        assert_eq!(*id, 7);
        assert_eq!(result.mesh_name, "pg");
        assert_eq!(result.x_um.len(), result.xdot_m_s.len());
        assert_eq!(result.poincare_x_um.len(), 8);
        assert!(!result.spectrum_order.is_empty());
        let cli: Value = serde_json::from_str(&result.cli_json).unwrap();
        assert_eq!(cli["mesh"], "pg");
        assert_eq!(out[1], FromWorker::Done { id: 7 });
        // The animation's window is the time history's: the last 8 recorded
        // periods here, and the plotted mesh's samples are the same numbers.
        let a = &result.anim;
        assert_eq!(a.x_um.len(), 1);
        assert_eq!(a.start_sample as usize, result.x_um.len() - 8 * 32);
        assert_eq!(a.x_um[0].len(), 8 * 32);
        for (k, x) in a.x_um[0].iter().enumerate() {
            assert!((x - result.x_um[a.start_sample as usize + k]).abs() < 1e-3);
        }
        assert_eq!(a.backlash_um.len(), 1);
    }

    #[test]
    fn sharded_fr_grid_covers_every_point_once() {
        let p = ModelParams::defaults(solver::ModelKind::GearPair);
        let mut seen = Vec::new();
        for shard in 0..2 {
            let mut core = WorkerCore::new();
            let out = core.handle(&run_msg(
                1,
                &p,
                JobSpec::Fr {
                    omega_from: 0.5,
                    omega_to: 1.5,
                    points: 5,
                    chains: 2,
                    shard,
                    run: quick(),
                },
            ));
            assert!(
                matches!(out[0], FromWorker::Progress { total, .. } if total == if shard == 0 { 3 } else { 2 })
            );
            for m in drain(&mut core) {
                if let FromWorker::FrPoints { points, .. } = m {
                    for s in points {
                        assert_eq!(s.meshes.len(), 1);
                        assert!(s.meshes[0].rel_max_um >= s.meshes[0].rel_min_um);
                        seen.push(s.index);
                    }
                }
            }
        }
        seen.sort_unstable();
        assert_eq!(seen, vec![0, 1, 2, 3, 4]);
    }

    /// Shard 0 of a sweep sends the instability bands first: for the
    /// default model over 0.1..2 the band 0.99-1.22 that `gearshock
    /// instability` finds holds Omega 1.1 (where the set without backlash
    /// diverges) and not 1.3; a backlash change sends the same bands (from
    /// the cache); shard 1 sends none.
    #[test]
    fn the_first_shard_of_a_sweep_sends_the_instability_bands() {
        let bif = |id, shard, p: &ModelParams| {
            run_msg(
                id,
                p,
                JobSpec::Bif {
                    omega_from: 0.1,
                    omega_to: 2.0,
                    points: 4,
                    directions: "up".into(),
                    chains: 2,
                    shard,
                    run: quick(),
                },
            )
        };
        let mut p = ModelParams::default();
        let mut core = WorkerCore::new();
        let out = core.handle(&bif(1, 0, &p));
        let Some(FromWorker::Bands { id: 1, bands }) = out.first() else {
            panic!("{out:?}");
        };
        let inside = |o: f64| bands.iter().any(|&(a, b)| a <= o && o <= b);
        assert!(inside(1.1) && !inside(1.3), "{bands:?}");
        let main = bands
            .iter()
            .find(|&&(a, b)| a <= 1.1 && 1.1 <= b)
            .copied()
            .unwrap();
        assert!(
            (main.0 - 0.99).abs() < 0.01 && (main.1 - 1.22).abs() < 0.01,
            "{main:?}"
        );
        keys::set_assignment(&mut p, "backlash_um=10").unwrap();
        let again = core.handle(&bif(2, 0, &p));
        assert!(matches!(again.first(), Some(FromWorker::Bands { id: 2, bands: b }) if b == bands));
        let other = WorkerCore::new().handle(&bif(3, 1, &p));
        assert!(!other.iter().any(|m| matches!(m, FromWorker::Bands { .. })));
    }

    #[test]
    fn hbm_job_streams_the_branch_in_chunks_and_a_newer_job_replaces_it() {
        let p = ModelParams::defaults(solver::ModelKind::GearPair);
        let hbm = |id, harmonics| {
            run_msg(
                id,
                &p,
                JobSpec::Hbm {
                    omega_from: 0.3,
                    omega_to: 1.8,
                    points: 60,
                    harmonics,
                    stability: true,
                },
            )
        };
        let mut core = WorkerCore::new();
        let out = core.handle(&hbm(1, 3));
        assert!(matches!(out[0], FromWorker::Progress { id: 1, .. }));
        let out = core.step();
        assert!(
            matches!(&out[..], [FromWorker::HbmPoints { id: 1, points, finished: false, error: None, .. }] if !points.is_empty() && points.len() <= HBM_CHUNK)
        );
        core.handle(&hbm(2, 3));
        let out = drain(&mut core);
        let mut omegas = Vec::new();
        let mut last = None;
        for m in &out {
            let FromWorker::HbmPoints {
                id,
                points,
                progress,
                finished,
                error,
            } = m
            else {
                panic!("unexpected {m:?}");
            };
            assert_eq!(*id, 2);
            assert!(points.len() <= HBM_CHUNK);
            for s in points {
                assert_eq!(s.meshes.len(), 1);
                assert!(s.meshes[0].rel_max_um >= s.meshes[0].rel_min_um);
                assert!(s.stable.is_some());
                omegas.push(s.omega);
            }
            last = Some((*progress, *finished, error.clone()));
        }
        assert_eq!(last, Some((1.0, true, None)));
        assert!(omegas[0] == 0.3 && omegas.len() > 30, "{omegas:?}");
        assert!(!core.has_work());
        // A cancel drops a running branch.
        core.handle(&hbm(3, 3));
        core.handle(&encode(&ToWorker::Cancel { kind: JobKind::Hbm }));
        assert!(!core.has_work());
        // Out-of-range harmonics fail cleanly.
        let out = core.handle(&hbm(4, 99));
        assert!(
            matches!(&out[0], FromWorker::Failed { id: 4, message } if message.contains("harmonics"))
        );
    }

    #[test]
    fn newer_job_replaces_older_and_bad_params_fail_cleanly() {
        let mut core = WorkerCore::new();
        let p = ModelParams::defaults(solver::ModelKind::GearPair);
        let bif = |id| {
            run_msg(
                id,
                &p,
                JobSpec::Bif {
                    omega_from: 0.5,
                    omega_to: 1.5,
                    points: 4,
                    directions: "both".into(),
                    chains: 2,
                    shard: 1,
                    run: quick(),
                },
            )
        };
        core.handle(&bif(1));
        core.step();
        core.handle(&bif(2));
        let out = drain(&mut core);
        assert!(out.iter().all(|m| match m {
            FromWorker::BifPoints { id, .. }
            | FromWorker::Progress { id, .. }
            | FromWorker::Done { id } => *id == 2,
            _ => false,
        }));
        // Shard 1 of 2 chains over 4 points: indices 1 and 3, up and down.
        let n: usize = out
            .iter()
            .map(|m| match m {
                FromWorker::BifPoints { points, .. } => points.len(),
                _ => 0,
            })
            .sum();
        assert_eq!(n, 4);

        let mut bad = params(&p);
        bad.insert("backlash_um".into(), Value::from(-5));
        let msg = encode(&ToWorker::Run {
            id: 9,
            params: bad,
            job: JobSpec::Omega {
                omega: 1.0,
                mesh: Some(0),
                run: quick(),
                samples_per_period: 16,
                max_order: 4.0,
            },
        });
        let out = core.handle(&msg);
        assert!(
            matches!(&out[0], FromWorker::Failed { id: 9, message } if message.contains("backlash_um"))
        );
        assert!(matches!(
            core.handle("{not json")[0],
            FromWorker::Failed { id: 0, .. }
        ));
    }

    #[test]
    fn exported_shards_merge_into_the_cli_format() {
        let p = ModelParams::defaults(solver::ModelKind::GearPair);
        let mut cores = [WorkerCore::new(), WorkerCore::new()];
        for (w, core) in cores.iter_mut().enumerate() {
            core.handle(&run_msg(
                5,
                &p,
                JobSpec::Bif {
                    omega_from: 0.6,
                    omega_to: 1.2,
                    points: 4,
                    directions: "up".into(),
                    chains: 2,
                    shard: w as u32,
                    run: quick(),
                },
            ));
            drain(core);
        }
        let FromWorker::Export { text: shard1, .. } =
            cores[1].handle(&encode(&ToWorker::ExportBif {
                id: 5,
                mesh: Some(0),
                other: vec![],
            }))[0]
                .clone()
        else {
            panic!("no export");
        };
        let FromWorker::Export { text, .. } = cores[0].handle(&encode(&ToWorker::ExportBif {
            id: 5,
            mesh: Some(0),
            other: vec![shard1],
        }))[0]
            .clone()
        else {
            panic!("no merged export");
        };
        let v: Value = serde_json::from_str(&text).unwrap();
        assert_eq!(v["spec"]["chains"], 2);
        assert_eq!(v["spec"]["shard"], Value::Null);
        let idx: Vec<i64> = v["points"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| p["index"].as_i64().unwrap())
            .collect();
        assert_eq!(idx, vec![0, 1, 2, 3]);
        // An export of an unknown or unfinished sweep is an error, not a panic.
        assert!(matches!(
            cores[0].handle(&encode(&ToWorker::ExportBif {
                id: 99,
                mesh: None,
                other: vec![]
            }))[0],
            FromWorker::Failed { .. }
        ));
    }
}
