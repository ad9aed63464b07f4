//! The page's controller: settings, jobs and worker replies, as a plain
//! state machine that the web layer drives and the native tests exercise.
//!
//! Every user action returns the messages to post to the workers; the
//! controller queues messages for a worker until it has said "ready".
//! Jobs are restarted by what a change affects: a model parameter restarts
//! everything, the frequency range the sweeps, the harmonics only the
//! harmonic-balance branch, the selected Omega or plotted mesh only the
//! selected-Omega job. The harmonic-balance branch of view 1 runs on the last
//! worker (worker 0 serves the selected-Omega job first). The web layer redraws the views
//! whose `dirty` flag is set, once per animation frame.

use crate::link;
use crate::maps::{LyapStore, MapGrid, MapStore, MapView};
use crate::presets;
use crate::protocol::{
    encode, FromWorker, JobId, JobKind, JobSpec, OmegaResult, RunOptions, ToWorker,
};
use crate::settings::{mesh_names, view_key, MeshSel, Settings};
use crate::views::{
    fr_view, natural_in_range, BifStore, BifView, FrSource, FrStore, FrView, HbmStore, ViewContext,
};
use crate::worker_core;
use solver::keys;
use solver::steady::Model;

/// Number of Web Workers the page runs.
pub const WORKERS: usize = 2;
/// Samples per mesh period of the selected-Omega history.
pub const SAMPLES_PER_PERIOD: u32 = 64;
/// Highest mesh order of the spectrum.
pub const MAX_ORDER: f64 = 8.0;
/// The worker that runs the harmonic-balance branch.
pub const HBM_WORKER: usize = WORKERS - 1;
/// How a failure of the harmonic-balance branch starts in the messages (a
/// new branch clears the old branch's failure).
const HBM_FAILURE: &str = "Frequency response: the harmonic-balance solver failed";
/// Jobs shorter than this show no progress indicator (ms).
pub const PROGRESS_AFTER_MS: f64 = 200.0;

/// Something the web layer must do.
#[derive(Debug, Clone, PartialEq)]
pub enum Effect {
    /// Post a message to a worker.
    Post {
        /// Worker index.
        worker: usize,
        /// JSON text.
        text: String,
    },
    /// Offer a file for download.
    Download {
        /// File name.
        name: String,
        /// MIME type.
        mime: String,
        /// Contents.
        text: String,
    },
}

/// The pinned state A of an A/B comparison and its two sweeps (the
/// frequency response and the bifurcation diagram), which are drawn under
/// the current state B's.
#[derive(Debug, Clone)]
pub struct Pinned {
    /// A's settings.
    pub settings: Settings,
    /// A's harmonic-balance branch.
    pub hbm: HbmStore,
    /// A's bifurcation points.
    pub bif: BifStore,
    /// A's branch job.
    pub fr_status: JobStatus,
    /// A's bifurcation job.
    pub bif_status: JobStatus,
}

/// Every mesh's backlash (um) of a state's model (empty if it cannot be built).
fn pinned_backlash(s: &Settings) -> Vec<f64> {
    match solver::system::MeshSystem::build(&s.params) {
        Ok(sys) => sys
            .meshes
            .iter()
            .map(|m| (m.backlash_m * 1e12).round() / 1e6)
            .collect(),
        Err(_) => Vec::new(),
    }
}

/// Steady states in a bifurcation sweep of view settings `v` (both
/// directions count twice).
fn bif_total(v: &crate::settings::ViewOptions) -> usize {
    let per_dir = if v.bif_dir == solver::sweep::Directions::Both {
        2
    } else {
        1
    };
    v.bif_points as usize * per_dir
}

/// Progress and timing of the current job of one kind.
#[derive(Debug, Clone, PartialEq, Default, serde::Serialize)]
pub struct JobStatus {
    /// Current job id (0: none yet).
    pub id: JobId,
    /// When it was started (ms, the page's clock).
    pub started_ms: f64,
    /// When its first data arrived.
    pub first_data_ms: Option<f64>,
    /// When it finished.
    pub finished_ms: Option<f64>,
    /// Units done.
    pub done: usize,
    /// Units in all.
    pub total: usize,
    /// Why it failed, if it did.
    pub error: Option<String>,
    /// When the page's own preview of this job's result was shown (the
    /// selected-Omega job only).
    pub preview_ms: Option<f64>,
}

impl JobStatus {
    /// Whether it is still running.
    pub fn running(&self) -> bool {
        self.id != 0 && self.finished_ms.is_none() && self.error.is_none()
    }

    /// Progress to show at time `now_ms` (`None` for quick or finished jobs).
    pub fn progress(&self, now_ms: f64) -> Option<(usize, usize)> {
        (self.running() && now_ms - self.started_ms > PROGRESS_AFTER_MS)
            .then_some((self.done, self.total))
    }

    fn start(id: JobId, now_ms: f64, total: usize) -> Self {
        JobStatus {
            id,
            started_ms: now_ms,
            total,
            ..JobStatus::default()
        }
    }
}

/// Which views need drawing.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Dirty {
    /// Frequency response.
    pub fr: bool,
    /// Bifurcation diagram.
    pub bif: bool,
    /// Views 3–6 and the summary.
    pub omega: bool,
    /// Control values (after a link, preset or reset).
    pub controls: bool,
    /// The URL.
    pub url: bool,
    /// The messages area.
    pub messages: bool,
    /// The impact-regime map.
    pub map: bool,
    /// The Lyapunov curve.
    pub lyap: bool,
}

#[derive(Debug, Clone, Default)]
struct WorkerSlot {
    ready: bool,
    queue: Vec<String>,
}

/// A bifurcation export being assembled from the shards.
#[derive(Debug, Clone, PartialEq)]
struct PendingExport {
    id: JobId,
    mesh: Option<usize>,
}

/// The page's state.
pub struct Controller {
    /// What a link restores.
    pub settings: Settings,
    /// The model built from the parameters, or why it cannot be.
    pub model: Result<Model, String>,
    /// Messages for the user (link problems, rejected input, job failures).
    pub issues: Vec<String>,
    /// The note of the preset last loaded.
    pub preset_note: Option<String>,
    /// The harmonic-balance branch of the current job (view 1).
    pub hbm: HbmStore,
    /// The last complete branch, shown faded while a new one computes.
    pub hbm_previous: Option<HbmStore>,
    /// Time-integration overlay points of the current job (id 0: overlay off).
    pub fr: FrStore,
    /// Bifurcation points of the current job.
    pub bif: BifStore,
    /// The latest selected-Omega result (possibly from an older job while a new one runs).
    pub omega: Option<OmegaResult>,
    /// Status of the harmonic-balance branch (view 1); `done` and `total`
    /// are per cent of the Omega range.
    pub fr_status: JobStatus,
    /// Status of the time-integration overlay grid.
    pub ti_status: JobStatus,
    /// Bifurcation job status.
    pub bif_status: JobStatus,
    /// Selected-Omega job status.
    pub omega_status: JobStatus,
    /// The impact-regime map's cells.
    pub map: MapStore,
    /// Map job status.
    pub map_status: JobStatus,
    /// The Lyapunov curve's points.
    pub lyap: LyapStore,
    /// Lyapunov job status.
    pub lyap_status: JobStatus,
    /// The pinned state A of an A/B comparison.
    pub pinned: Option<Pinned>,
    /// Views to redraw.
    pub dirty: Dirty,
    workers: [WorkerSlot; WORKERS],
    next_id: JobId,
    export: Option<PendingExport>,
    /// The parametric-instability bands of the bifurcation sweep's range,
    /// from its shard-0 worker (kept until a newer job's arrive).
    bands: Vec<(f64, f64)>,
}

/// What a change restarts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Restart {
    /// The harmonic-balance branch.
    fr: bool,
    /// The time-integration overlay.
    ti: bool,
    bif: bool,
    omega: bool,
    /// The map (only if what it depends on changed).
    map: bool,
    lyap: bool,
}

const ALL: Restart = Restart {
    fr: true,
    ti: true,
    bif: true,
    omega: true,
    map: true,
    lyap: true,
};

const NONE: Restart = Restart {
    fr: false,
    ti: false,
    bif: false,
    omega: false,
    map: false,
    lyap: false,
};

/// The harmonic-balance job of a view's settings (the current state's and
/// the pinned A state's alike).
fn hbm_job(v: &crate::settings::ViewOptions) -> JobSpec {
    JobSpec::Hbm {
        omega_from: v.omega_from,
        omega_to: v.omega_to,
        points: v.fr_points,
        harmonics: v.harmonics,
        stability: true,
    }
}

impl Controller {
    /// Starts from a link's query string (all jobs queued until the workers are ready).
    pub fn new(query: &str, now_ms: f64) -> (Self, Vec<Effect>) {
        let decoded = link::decode(query);
        let pinned = decoded.pinned;
        let mut c = Controller {
            model: Err("not built yet".into()),
            settings: decoded.settings,
            issues: decoded.issues,
            preset_note: None,
            hbm: HbmStore::default(),
            hbm_previous: None,
            fr: FrStore::default(),
            bif: BifStore::default(),
            omega: None,
            fr_status: JobStatus::default(),
            ti_status: JobStatus::default(),
            bif_status: JobStatus::default(),
            omega_status: JobStatus::default(),
            map: MapStore::default(),
            map_status: JobStatus::default(),
            lyap: LyapStore::default(),
            lyap_status: JobStatus::default(),
            pinned: None,
            dirty: Dirty::default(),
            workers: Default::default(),
            next_id: 0,
            export: None,
            bands: Vec::new(),
        };
        c.rebuild_model();
        let mut fx = c.restart(ALL, now_ms);
        if let Some(a) = pinned {
            fx.extend(c.start_pinned(a, now_ms));
        }
        c.dirty = Dirty {
            fr: true,
            bif: true,
            omega: true,
            controls: true,
            url: true,
            messages: true,
            map: true,
            lyap: true,
        };
        (c, fx)
    }

    fn rebuild_model(&mut self) {
        self.model = Model::new(&self.settings.params).map_err(|e| e.to_string());
    }

    /// The current link query (without `?`), with the pinned state A if any.
    pub fn query(&self) -> String {
        link::encode_ab(&self.settings, self.pinned.as_ref().map(|p| &p.settings))
    }

    /// "Pin as A": keeps the current state and its results as A; later
    /// changes draw as B over it. Results still computing are computed again
    /// for A (B's next change would cancel them).
    pub fn pin_a(&mut self, now_ms: f64) -> Vec<Effect> {
        let mut fx = self.cancel_pinned();
        let complete = self.hbm.finished && self.bif_status.finished_ms.is_some();
        if complete {
            self.pinned = Some(Pinned {
                settings: self.settings.clone(),
                hbm: self.hbm.clone(),
                bif: self.bif.clone(),
                fr_status: self.fr_status.clone(),
                bif_status: self.bif_status.clone(),
            });
        } else {
            fx.extend(self.start_pinned(self.settings.clone(), now_ms));
        }
        self.dirty.fr = true;
        self.dirty.bif = true;
        self.dirty.url = true;
        fx
    }

    /// "Clear A": ends the comparison.
    pub fn clear_a(&mut self) -> Vec<Effect> {
        let fx = self.cancel_pinned();
        self.pinned = None;
        self.dirty.fr = true;
        self.dirty.bif = true;
        self.dirty.url = true;
        fx
    }

    fn cancel_pinned(&mut self) -> Vec<Effect> {
        let running = self
            .pinned
            .as_ref()
            .is_some_and(|p| p.fr_status.running() || p.bif_status.running());
        let mut fx = Vec::new();
        if running {
            for kind in [JobKind::Hbm, JobKind::Bif] {
                for w in 0..WORKERS {
                    fx.extend(self.post(w, &ToWorker::CancelPinned { kind }));
                }
            }
        }
        fx
    }

    /// Starts A's branch and bifurcation sweep (a link that carries A).
    fn start_pinned(&mut self, a: Settings, now_ms: f64) -> Vec<Effect> {
        let mut fx = Vec::new();
        let mut pinned = Pinned {
            settings: a.clone(),
            hbm: HbmStore::default(),
            bif: BifStore::default(),
            fr_status: JobStatus::default(),
            bif_status: JobStatus::default(),
        };
        if let Err(e) = Model::new(&a.params) {
            pinned.fr_status.error = Some(e.to_string());
            pinned.bif_status.error = Some(e.to_string());
            self.pinned = Some(pinned);
            return fx;
        }
        let params = keys::to_json(&a.params);
        let v = &a.view;
        self.next_id += 1;
        let id = self.next_id;
        pinned.hbm = HbmStore::new(id, v.harmonics);
        pinned.fr_status = JobStatus::start(id, now_ms, 100);
        let job = hbm_job(v);
        fx.extend(self.post(
            HBM_WORKER,
            &ToWorker::RunPinned {
                id,
                params: params.clone(),
                job,
            },
        ));
        self.next_id += 1;
        let id = self.next_id;
        let total = bif_total(v);
        pinned.bif = BifStore::new(id, total);
        pinned.bif_status = JobStatus::start(id, now_ms, total);
        let chains = (WORKERS as u32).min(v.bif_points);
        for w in 0..chains {
            let job = JobSpec::Bif {
                omega_from: v.omega_from,
                omega_to: v.omega_to,
                points: v.bif_points,
                directions: v.bif_dir.name().to_string(),
                chains,
                shard: w,
                run: RunOptions {
                    transient_periods: v.transient_periods,
                    record_periods: v.record_periods,
                },
            };
            fx.extend(self.post(
                w as usize,
                &ToWorker::RunPinned {
                    id,
                    params: params.clone(),
                    job,
                },
            ));
        }
        self.pinned = Some(pinned);
        fx
    }

    /// Feeds A's stores with replies to A's jobs (ids that are A's).
    fn pinned_message(&mut self, msg: &FromWorker, now_ms: f64) {
        let Some(p) = self.pinned.as_mut() else {
            return;
        };
        match msg {
            FromWorker::HbmPoints {
                id,
                points,
                progress,
                finished,
                error,
            } if *id == p.hbm.id && *id != 0 => {
                p.hbm
                    .add(points.clone(), *progress, *finished, error.clone());
                if *finished {
                    p.fr_status.finished_ms = Some(now_ms);
                }
                if error.is_some() {
                    p.fr_status.error = error.clone();
                }
                self.dirty.fr = true;
            }
            FromWorker::BifPoints { id, points } if *id == p.bif.id && *id != 0 => {
                p.bif.samples.extend(points.iter().cloned());
                p.bif_status.done = p.bif.samples.len();
                if p.bif_status.done >= p.bif_status.total {
                    p.bif_status.finished_ms = Some(now_ms);
                }
                self.dirty.bif = true;
            }
            FromWorker::Failed { id, message } => {
                for st in [&mut p.fr_status, &mut p.bif_status] {
                    if st.id == *id && *id != 0 {
                        st.error = Some(message.clone());
                    }
                }
            }
            _ => {}
        }
    }

    /// The mesh names of the current model.
    pub fn mesh_names(&self) -> Vec<String> {
        mesh_names(&self.settings.params)
    }

    fn post(&mut self, worker: usize, msg: &ToWorker) -> Vec<Effect> {
        let text = encode(msg);
        match self.workers.get_mut(worker) {
            Some(slot) if slot.ready => vec![Effect::Post { worker, text }],
            Some(slot) => {
                slot.queue.push(text);
                Vec::new()
            }
            None => Vec::new(),
        }
    }

    fn run_options(&self, record: u32) -> RunOptions {
        RunOptions {
            transient_periods: self.settings.view.transient_periods,
            record_periods: record,
        }
    }

    /// Shows a preview of the selected-Omega views at once: a short bounded
    /// run ([`worker_core::PREVIEW_RUN`]) continued from the last result's
    /// end state under the new settings. The worker's full steady state
    /// replaces it; without a previous state, or if the run fails or
    /// exceeds its step budget, the views keep the last result until then.
    fn preview_omega(&mut self, model: &Model, id: JobId, now_ms: f64) {
        let Some(start) = self
            .omega
            .as_ref()
            .map(|r| r.end_state.clone())
            .filter(|y| y.len() == 2 * model.system.dof())
        else {
            return;
        };
        let v = &self.settings.view;
        let job = worker_core::OmegaJob {
            id,
            model: model.clone(),
            omega: v.omega,
            mesh: self.settings.mesh_index(model),
            run: worker_core::PREVIEW_RUN,
            samples_per_period: SAMPLES_PER_PERIOD,
            max_order: MAX_ORDER,
        };
        if let Ok(r) = worker_core::omega_result(&job, Some(&start)) {
            self.omega = Some(r);
            self.omega_status.preview_ms = Some(now_ms);
        }
    }

    fn restart(&mut self, what: Restart, now_ms: f64) -> Vec<Effect> {
        let mut fx = Vec::new();
        let model = match &self.model {
            Ok(m) => m.clone(),
            Err(e) => {
                // No jobs on an invalid model: say why on every view.
                let e = e.clone();
                for (flag, st) in [
                    (what.fr, &mut self.fr_status),
                    (what.ti, &mut self.ti_status),
                    (what.bif, &mut self.bif_status),
                    (what.omega, &mut self.omega_status),
                    (what.map, &mut self.map_status),
                    (what.lyap, &mut self.lyap_status),
                ] {
                    if flag {
                        st.error = Some(e.clone());
                    }
                }
                for kind in JobKind::ALL {
                    for w in 0..WORKERS {
                        fx.extend(self.post(w, &ToWorker::Cancel { kind }));
                    }
                }
                self.map.signature.clear();
                self.dirty.fr = true;
                self.dirty.bif = true;
                self.dirty.omega = true;
                self.dirty.map = true;
                self.dirty.lyap = true;
                return fx;
            }
        };
        let params = keys::to_json(&self.settings.params);
        let v = self.settings.view.clone();
        if what.omega {
            self.next_id += 1;
            let id = self.next_id;
            self.omega_status = JobStatus::start(id, now_ms, 1);
            let job = JobSpec::Omega {
                omega: v.omega,
                mesh: self.settings.mesh_index(&model),
                run: self.run_options(v.record_periods),
                samples_per_period: SAMPLES_PER_PERIOD,
                max_order: MAX_ORDER,
            };
            fx.extend(self.post(
                0,
                &ToWorker::Run {
                    id,
                    params: params.clone(),
                    job,
                },
            ));
            self.preview_omega(&model, id, now_ms);
            self.dirty.omega = true;
        }
        if what.fr {
            self.next_id += 1;
            let id = self.next_id;
            // Keep the last complete branch (not a half-computed one) to fade
            // under the new one while it computes.
            if self.hbm.is_complete() {
                self.hbm_previous = Some(std::mem::take(&mut self.hbm));
            }
            self.hbm = HbmStore::new(id, v.harmonics);
            let before = self.issues.len();
            self.issues.retain(|i| !i.starts_with(HBM_FAILURE));
            self.dirty.messages |= self.issues.len() != before;
            self.fr_status = JobStatus::start(id, now_ms, 100);
            let job = hbm_job(&v);
            fx.extend(self.post(
                HBM_WORKER,
                &ToWorker::Run {
                    id,
                    params: params.clone(),
                    job,
                },
            ));
            self.dirty.fr = true;
        }
        if what.ti && v.fr_ti_points == 0 {
            // Overlay off: drop a running overlay job, if there was one.
            if self.fr.id != 0 {
                for w in 0..WORKERS {
                    fx.extend(self.post(w, &ToWorker::Cancel { kind: JobKind::Fr }));
                }
            }
            self.fr = FrStore::default();
            self.ti_status = JobStatus::default();
            self.dirty.fr = true;
        } else if what.ti {
            self.next_id += 1;
            let id = self.next_id;
            let n = v.fr_ti_points;
            self.fr = FrStore::new(id, n, v.transient_periods, v.fr_record_periods);
            self.ti_status = JobStatus::start(id, now_ms, n as usize);
            let chains = (WORKERS as u32).min(n);
            for w in 0..chains {
                let job = JobSpec::Fr {
                    omega_from: v.omega_from,
                    omega_to: v.omega_to,
                    points: n,
                    chains,
                    shard: w,
                    run: self.run_options(v.fr_record_periods),
                };
                fx.extend(self.post(
                    w as usize,
                    &ToWorker::Run {
                        id,
                        params: params.clone(),
                        job,
                    },
                ));
            }
            self.dirty.fr = true;
        }
        if what.bif {
            self.next_id += 1;
            let id = self.next_id;
            let total = bif_total(&v);
            self.bif = BifStore::new(id, total);
            self.bif_status = JobStatus::start(id, now_ms, total);
            self.export = None;
            let chains = (WORKERS as u32).min(v.bif_points);
            for w in 0..chains {
                let job = JobSpec::Bif {
                    omega_from: v.omega_from,
                    omega_to: v.omega_to,
                    points: v.bif_points,
                    directions: v.bif_dir.name().to_string(),
                    chains,
                    shard: w,
                    run: self.run_options(v.record_periods),
                };
                fx.extend(self.post(
                    w as usize,
                    &ToWorker::Run {
                        id,
                        params: params.clone(),
                        job,
                    },
                ));
            }
            self.dirty.bif = true;
        }
        if what.map {
            fx.extend(self.restart_map(&model, &params, now_ms));
        }
        if what.lyap {
            fx.extend(self.restart_lyap(&params, now_ms));
        }
        self.dirty.url = true;
        fx
    }

    /// The map's grid from the view options.
    pub fn map_grid(&self) -> MapGrid {
        let v = &self.settings.view;
        MapGrid {
            key: v.map_key.clone(),
            omega_from: v.omega_from,
            omega_to: v.omega_to,
            omega_points: v.map_omega_points,
            value_from: v.map_from,
            value_to: v.map_to,
            value_points: v.map_value_points,
        }
    }

    /// Everything the map depends on, as text: its grid, periods and mesh,
    /// and the parameters with the rows' key neutralised (the rows set it),
    /// so a click on a cell, which sets that key, does not restart the map.
    fn map_signature(
        &self,
        model: &Model,
        params: &serde_json::Map<String, serde_json::Value>,
    ) -> String {
        let v = &self.settings.view;
        let mut p = self.settings.params.clone();
        let neutral = keys::set(&mut p, &v.map_key, keys::Value::Num(0.0)).is_ok();
        let params_text = if neutral {
            serde_json::Value::Object(keys::to_json(&p)).to_string()
        } else {
            serde_json::Value::Object(params.clone()).to_string()
        };
        format!(
            "{:?}|{}|{}|{:?}|{params_text}",
            self.map_grid(),
            v.map_transient_periods,
            v.map_record_periods,
            self.settings.mesh_index(model),
        )
    }

    fn restart_map(
        &mut self,
        model: &Model,
        params: &serde_json::Map<String, serde_json::Value>,
        now_ms: f64,
    ) -> Vec<Effect> {
        let signature = self.map_signature(model, params);
        if signature == self.map.signature && self.map_status.error.is_none() {
            return Vec::new();
        }
        let mut fx = Vec::new();
        self.next_id += 1;
        let id = self.next_id;
        let grid = self.map_grid();
        let v = self.settings.view.clone();
        self.map_status = JobStatus::start(id, now_ms, grid.cells());
        let shards = (WORKERS as u32).min(grid.value_points);
        for w in 0..shards {
            let job = JobSpec::Map {
                key: grid.key.clone(),
                omega_from: grid.omega_from,
                omega_to: grid.omega_to,
                omega_points: grid.omega_points,
                value_from: grid.value_from,
                value_to: grid.value_to,
                value_points: grid.value_points,
                mesh: self.settings.mesh_index(model),
                shards,
                shard: w,
                run: RunOptions {
                    transient_periods: v.map_transient_periods,
                    record_periods: v.map_record_periods,
                },
            };
            fx.extend(self.post(
                w as usize,
                &ToWorker::Run {
                    id,
                    params: params.clone(),
                    job,
                },
            ));
        }
        self.map = MapStore::new(id, grid, signature);
        self.dirty.map = true;
        fx
    }

    fn restart_lyap(
        &mut self,
        params: &serde_json::Map<String, serde_json::Value>,
        now_ms: f64,
    ) -> Vec<Effect> {
        let v = self.settings.view.clone();
        let mut fx = Vec::new();
        self.dirty.lyap = true;
        if v.lyap_points < 2 {
            // The curve is off: drop a running job, if there was one.
            if self.lyap.id != 0 {
                for w in 0..WORKERS {
                    fx.extend(self.post(
                        w,
                        &ToWorker::Cancel {
                            kind: JobKind::Lyap,
                        },
                    ));
                }
            }
            self.lyap = LyapStore::default();
            self.lyap_status = JobStatus::default();
            return fx;
        }
        self.next_id += 1;
        let id = self.next_id;
        let n = v.lyap_points;
        self.lyap = LyapStore::new(id, n as usize, v.lyap_periods);
        self.lyap_status = JobStatus::start(id, now_ms, n as usize);
        let chains = (WORKERS as u32).min(n);
        for w in 0..chains {
            let job = JobSpec::Lyap {
                omega_from: v.omega_from,
                omega_to: v.omega_to,
                points: n,
                chains,
                shard: w,
                transient_periods: v.lyap_transient_periods,
                periods: v.lyap_periods,
            };
            fx.extend(self.post(
                w as usize,
                &ToWorker::Run {
                    id,
                    params: params.clone(),
                    job,
                },
            ));
        }
        fx
    }

    /// Handles a message from worker `worker`.
    pub fn worker_message(&mut self, worker: usize, text: &str, now_ms: f64) -> Vec<Effect> {
        let msg: FromWorker = match serde_json::from_str(text) {
            Ok(m) => m,
            Err(e) => {
                self.issue(format!("unreadable worker message: {e}"));
                return Vec::new();
            }
        };
        self.pinned_message(&msg, now_ms);
        match msg {
            FromWorker::Ready => {
                let Some(slot) = self.workers.get_mut(worker) else {
                    return Vec::new();
                };
                slot.ready = true;
                std::mem::take(&mut slot.queue)
                    .into_iter()
                    .map(|text| Effect::Post { worker, text })
                    .collect()
            }
            FromWorker::HbmPoints {
                id,
                points,
                progress,
                finished,
                error,
            } if id == self.hbm.id && id != 0 => {
                let failure = error.clone();
                self.hbm.add(points, progress, finished, error);
                let st = &mut self.fr_status;
                st.done = (100.0 * self.hbm.progress).floor() as usize;
                if !self.hbm.points.is_empty() {
                    st.first_data_ms.get_or_insert(now_ms);
                }
                if finished {
                    st.finished_ms = Some(now_ms);
                }
                if self.hbm.is_complete() {
                    self.hbm_previous = None;
                }
                if let Some(e) = failure {
                    let at = self
                        .hbm
                        .points
                        .last()
                        .map_or(self.settings.view.omega_from, |p| p.omega);
                    let msg = format!(
                        "{HBM_FAILURE} after Omega = {at:.4} ({e}); the branch shown is partial"
                    );
                    self.fr_status.error = Some(msg.clone());
                    self.issue(msg);
                }
                self.dirty.fr = true;
                Vec::new()
            }
            FromWorker::FrPoints { id, points } if id == self.fr.id && id != 0 => {
                self.fr.add(points);
                self.ti_status.done = self.fr.done();
                self.ti_status.first_data_ms.get_or_insert(now_ms);
                if self.ti_status.done >= self.ti_status.total {
                    self.ti_status.finished_ms = Some(now_ms);
                }
                self.dirty.fr = true;
                Vec::new()
            }
            FromWorker::Bands { id, bands } if id == self.bif.id => {
                if bands != self.bands {
                    self.bands = bands;
                    self.dirty.bif = true;
                }
                Vec::new()
            }
            FromWorker::BifPoints { id, points } if id == self.bif.id => {
                self.bif.samples.extend(points);
                self.bif_status.done = self.bif.samples.len();
                self.bif_status.first_data_ms.get_or_insert(now_ms);
                if self.bif_status.done >= self.bif_status.total {
                    self.bif_status.finished_ms = Some(now_ms);
                }
                self.dirty.bif = true;
                Vec::new()
            }
            FromWorker::MapCells { id, cells } if id == self.map.id && id != 0 => {
                self.map.add(cells);
                self.map_status.done = self.map.done;
                self.map_status.first_data_ms.get_or_insert(now_ms);
                if self.map.done >= self.map_status.total {
                    self.map_status.finished_ms = Some(now_ms);
                }
                self.dirty.map = true;
                Vec::new()
            }
            FromWorker::LyapPoints { id, points } if id == self.lyap.id && id != 0 => {
                self.lyap.points.extend(points);
                self.lyap_status.done = self.lyap.points.len();
                self.lyap_status.first_data_ms.get_or_insert(now_ms);
                if self.lyap_status.done >= self.lyap_status.total {
                    self.lyap_status.finished_ms = Some(now_ms);
                }
                self.dirty.lyap = true;
                Vec::new()
            }
            FromWorker::Omega { id, result } if id == self.omega_status.id => {
                self.omega = Some(*result);
                self.omega_status.done = 1;
                self.omega_status.first_data_ms = Some(now_ms);
                self.omega_status.finished_ms = Some(now_ms);
                self.dirty.omega = true;
                Vec::new()
            }
            FromWorker::Failed { id, message } => {
                for st in [
                    &mut self.fr_status,
                    &mut self.ti_status,
                    &mut self.bif_status,
                    &mut self.omega_status,
                    &mut self.map_status,
                    &mut self.lyap_status,
                ] {
                    if st.id == id && id != 0 {
                        st.error = Some(message.clone());
                    }
                }
                self.dirty.fr = true;
                self.dirty.bif = true;
                self.dirty.omega = true;
                self.dirty.map = true;
                self.dirty.lyap = true;
                if self.export.as_ref().is_some_and(|e| e.id == id) {
                    self.export = None;
                }
                self.issue(message);
                Vec::new()
            }
            FromWorker::Export { id, text } => self.export_reply(worker, id, text),
            // Progress and Done of current jobs are implied by the data; stale replies are dropped.
            _ => Vec::new(),
        }
    }

    fn issue(&mut self, message: String) {
        if !self.issues.contains(&message) {
            self.issues.push(message);
            if self.issues.len() > 12 {
                self.issues.remove(0);
            }
        }
        self.dirty.messages = true;
    }

    /// Clears the messages.
    pub fn clear_issues(&mut self) {
        self.issues.clear();
        self.dirty.messages = true;
    }

    /// Sets a control's key from its text. Out-of-range or impossible values
    /// are refused with a message naming the key and its allowed range.
    pub fn set_key(&mut self, key: &str, text: &str, now_ms: f64) -> Result<Vec<Effect>, String> {
        if view_key(key).is_some() {
            let before = self.settings.view.clone();
            let meshes = self.mesh_names();
            self.settings.view.set(key, text, &meshes)?;
            if key == "map_key" && self.settings.view.map_key != before.map_key {
                // A new axis gets that key's own default range.
                let (lo, hi) = crate::settings::map_default_range(&self.settings.view.map_key);
                self.settings.view.map_from = lo;
                self.settings.view.map_to = hi;
                self.dirty.controls = true;
            }
            if let Some(msg) = self.settings.view.check_range() {
                self.settings.view = before;
                return Err(msg);
            }
            let what = match key {
                "omega" => Restart {
                    omega: true,
                    ..NONE
                },
                "mesh" => Restart {
                    omega: true,
                    map: true,
                    ..NONE
                },
                "omega_from" | "omega_to" => ALL,
                "transient_periods" => Restart {
                    fr: false,
                    map: false,
                    lyap: false,
                    ..ALL
                },
                "map_key"
                | "map_from"
                | "map_to"
                | "map_omega_points"
                | "map_value_points"
                | "map_transient_periods"
                | "map_record_periods" => Restart { map: true, ..NONE },
                "lyap_points" | "lyap_transient_periods" | "lyap_periods" => {
                    Restart { lyap: true, ..NONE }
                }
                "fr_points" | "harmonics" => Restart { fr: true, ..NONE },
                "fr_ti_points" | "fr_record_periods" => Restart { ti: true, ..NONE },
                "bif_points" | "bif_dir" => Restart { bif: true, ..NONE },
                "record_periods" => Restart {
                    bif: true,
                    omega: true,
                    ..NONE
                },
                _ => NONE,
            };
            // The views share the mesh and range: redraw them even without new data.
            self.dirty.fr = true;
            self.dirty.bif = true;
            self.dirty.map = true;
            self.dirty.lyap = true;
            self.dirty.url = true;
            return Ok(self.restart(what, now_ms));
        }
        let value = keys::parse_value(key, text).map_err(|e| e.to_string())?;
        let mut params = self.settings.params.clone();
        keys::set(&mut params, key, value).map_err(|e| e.to_string())?;
        if params == self.settings.params {
            return Ok(Vec::new());
        }
        let model = Model::new(&params).map_err(|e| e.to_string())?;
        let model_changed = params.kind() != self.settings.params.kind();
        self.settings.params = params;
        self.model = Ok(model);
        if model_changed {
            // A new model: its own default mesh, and fresh controls.
            if let Some(first) = self.mesh_names().first() {
                self.settings.view.mesh = MeshSel::Named(first.clone());
            }
            self.dirty.controls = true;
        }
        self.preset_note = None;
        Ok(self.restart(ALL, now_ms))
    }

    /// Moves the selected Omega (clicks and drags on the Omega axes).
    pub fn select_omega(&mut self, omega: f64, now_ms: f64) -> Vec<Effect> {
        let omega = (omega * 1e4).round() / 1e4;
        let text = crate::settings::fmt_exact(omega);
        match self.set_key("omega", &text, now_ms) {
            Ok(fx) => {
                self.dirty.controls = true;
                fx
            }
            Err(e) => {
                self.issue(e);
                Vec::new()
            }
        }
    }

    /// Replaces the whole state by a link's (or preset's) query.
    pub fn load_query(&mut self, query: &str, now_ms: f64) -> Vec<Effect> {
        let d = link::decode(query);
        self.settings = d.settings;
        self.issues = d.issues;
        self.preset_note = None;
        self.rebuild_model();
        self.hbm_previous = None;
        let mut fx = self.clear_a();
        if let Some(a) = d.pinned {
            fx.extend(self.start_pinned(a, now_ms));
        }
        self.dirty = Dirty {
            fr: true,
            bif: true,
            omega: true,
            controls: true,
            url: true,
            messages: true,
            map: true,
            lyap: true,
        };
        fx.extend(self.restart(ALL, now_ms));
        fx
    }

    /// A click on the map at `(omega, value)`: sets the rows' key to the
    /// cell's value and the selected Omega to the cell's Omega. Values are
    /// rounded to 1e-3 um and Omega to 1e-4, as the link shows them.
    pub fn pick_map_point(
        &mut self,
        omega: f64,
        value: f64,
        now_ms: f64,
    ) -> Result<Vec<Effect>, String> {
        let grid = self.map.grid.clone().unwrap_or_else(|| self.map_grid());
        let (row, column) = grid
            .cell_at(omega, value)
            .ok_or_else(|| "the click is outside the map".to_string())?;
        let v = (grid.value(row) * 1e3).round() / 1e3;
        let mut fx = self.set_key(&grid.key, &crate::settings::fmt_exact(v), now_ms)?;
        self.dirty.controls = true;
        fx.extend(self.select_omega(grid.omega(column), now_ms));
        Ok(fx)
    }

    /// What the map plot draws.
    pub fn map_view(&self) -> MapView<'_> {
        let key = &self.settings.view.map_key;
        let value = match keys::get(&self.settings.params, key) {
            Some(keys::Value::Num(x)) if x.is_finite() => Some(x),
            _ => None,
        };
        MapView {
            store: &self.map,
            mesh_label: match &self.settings.view.mesh {
                MeshSel::Named(n) => format!("mesh {n}"),
                MeshSel::Worst => "most severe of all meshes".into(),
            },
            selected: (self.settings.view.omega, value),
        }
    }

    /// Loads a preset by id.
    pub fn apply_preset(&mut self, id: &str, now_ms: f64) -> Vec<Effect> {
        let Some(p) = presets::preset(id) else {
            self.issue(format!("no preset `{}`", keys::truncate(id, 30)));
            return Vec::new();
        };
        let fx = self.load_query(&p.query(), now_ms);
        self.preset_note = Some(presets::note(p));
        fx
    }

    /// What every view shares.
    pub fn view_context(&self) -> ViewContext {
        let v = &self.settings.view;
        ViewContext {
            omega_from: v.omega_from,
            omega_to: v.omega_to,
            selected_omega: v.omega,
            mesh_label: match &v.mesh {
                MeshSel::Named(n) => n.clone(),
                MeshSel::Worst => "worst (largest dynamic factor)".into(),
            },
            natural: self
                .model
                .as_ref()
                .map(|m| natural_in_range(m, v.omega_from, v.omega_to))
                .unwrap_or_default(),
        }
    }

    fn mesh_and_backlash(&self) -> (Option<usize>, Vec<f64>) {
        match &self.model {
            Ok(m) => (
                self.settings.mesh_index(m),
                m.system
                    .meshes
                    .iter()
                    .map(|x| (x.backlash_m * 1e12).round() / 1e6)
                    .collect(),
            ),
            Err(_) => (Some(0), Vec::new()),
        }
    }

    /// The frequency-response view: the harmonic-balance branch (with the
    /// previous complete branch faded while a new one computes) and the
    /// time-integration overlay if it is on.
    pub fn fr_view(&self) -> FrView {
        let (mesh, b) = self.mesh_and_backlash();
        let ctx = self.view_context();
        // The previous branch is context while the new one computes, not
        // after it has ended (complete or failed).
        let previous = self.hbm_previous.as_ref().filter(|_| !self.hbm.finished);
        let overlay = Some(&self.fr).filter(|f| f.id != 0);
        let mut v = fr_view(&self.hbm, previous, overlay, mesh, &b, &ctx);
        if let Some(p) = &self.pinned {
            let (ta, tb) = link::ab_difference(&p.settings, &self.settings, 3);
            for br in v.branches.iter_mut().filter(|b| !b.faded) {
                br.label = format!("B: {tb}; {}", br.label);
            }
            let partial = if p.hbm.error.is_some() {
                "; partial"
            } else {
                ""
            };
            v.pinned_backlash_um = crate::views::distinct(&pinned_backlash(&p.settings), mesh);
            v.branches.insert(
                0,
                crate::views::FrBranch {
                    label: format!("A: {ta}{partial}"),
                    points: p.hbm.curve(mesh).0,
                    faded: false,
                    pinned: true,
                },
            );
        }
        v
    }

    /// The legend texts of A and B (what differs), if comparing.
    pub fn ab_labels(&self) -> Option<(String, String)> {
        self.pinned
            .as_ref()
            .map(|p| link::ab_difference(&p.settings, &self.settings, 3))
    }

    /// The method of view 1 in words.
    pub fn fr_method(&self) -> String {
        FrSource::Hbm {
            harmonics: self.hbm.harmonics,
        }
        .label()
    }

    /// The bifurcation view.
    pub fn bif_view(&self) -> BifView {
        let (mesh, b) = self.mesh_and_backlash();
        let ctx = self.view_context();
        let mut v = self.bif.view(mesh, &b, &ctx);
        v.unstable_bands = self.instability_bands();
        if let Some(p) = &self.pinned {
            v.pinned = p.bif.view(mesh, &b, &ctx).points;
            v.pinned_backlash_um = crate::views::distinct(&pinned_backlash(&p.settings), mesh);
            v.ab_labels = self.ab_labels();
        }
        v
    }

    /// The Omega bands of the bifurcation sweep's range where the system
    /// with every tooth pair in contact is parametrically unstable (Floquet
    /// spectral radius above 1: motion large against the backlash grows
    /// without bound), as the sweep's worker computed them.
    pub fn instability_bands(&self) -> Vec<(f64, f64)> {
        self.bands.clone()
    }

    /// Starts assembling the bifurcation JSON in the CLI's format: the last
    /// shard exports first, then worker 0 merges the others into its own.
    pub fn request_bif_export(&mut self) -> Result<Vec<Effect>, String> {
        if self.bif_status.finished_ms.is_none() {
            return Err("the bifurcation sweep has not finished yet".into());
        }
        let (mesh, _) = self.mesh_and_backlash();
        let id = self.bif.id;
        self.export = Some(PendingExport { id, mesh });
        let chains = (WORKERS as u32).min(self.settings.view.bif_points) as usize;
        let msg = ToWorker::ExportBif {
            id,
            mesh,
            other: Vec::new(),
        };
        Ok(self.post(chains - 1, &msg))
    }

    fn export_reply(&mut self, worker: usize, id: JobId, text: String) -> Vec<Effect> {
        let Some(pending) = self.export.clone().filter(|e| e.id == id) else {
            return Vec::new();
        };
        if worker == 0 {
            self.export = None;
            return vec![Effect::Download {
                name: format!("gearshock-bifurcation-{}.json", self.mesh_file_label()),
                mime: "application/json".into(),
                text,
            }];
        }
        let msg = ToWorker::ExportBif {
            id,
            mesh: pending.mesh,
            other: vec![text],
        };
        self.post(0, &msg)
    }

    /// The plotted mesh for file names.
    pub fn mesh_file_label(&self) -> String {
        self.settings.view.mesh.text().to_string()
    }

    /// The CLI commands that reproduce the current views natively.
    pub fn cli_commands(&self) -> String {
        let v = &self.settings.view;
        let mesh = match (&self.model, &v.mesh) {
            (_, MeshSel::Named(n)) => n.clone(),
            (Ok(m), MeshSel::Worst) => self
                .omega
                .as_ref()
                .map_or_else(|| m.system.meshes[0].name.clone(), |r| r.mesh_name.clone()),
            (Err(_), MeshSel::Worst) => "s1a1".into(),
        };
        let chains = (WORKERS as u32).min(v.bif_points);
        let frf_mesh = match &v.mesh {
            MeshSel::Named(n) => n.as_str(),
            MeshSel::Worst => "all",
        };
        format!(
            "gearshock frf --params gearshock-params.json --omega-from {} --omega-to {} --points {} --harmonics {} --mesh {frf_mesh}\n\
             gearshock simulate --params gearshock-params.json --omega {} --mesh {mesh} --transient-periods {} --record-periods {}\n\
             gearshock bifurcation --params gearshock-params.json --omega-from {} --omega-to {} --points {} --direction {} --transient-periods {} --record-periods {} --mesh {} --chains {chains}",
            v.omega_from,
            v.omega_to,
            v.fr_points,
            v.harmonics,
            v.omega,
            v.transient_periods,
            v.record_periods,
            v.omega_from,
            v.omega_to,
            v.bif_points,
            v.bif_dir.name(),
            v.transient_periods,
            v.record_periods,
            match &v.mesh {
                MeshSel::Named(n) => n.as_str(),
                MeshSel::Worst => "all",
            }
        )
    }

    /// The parameters as the CLI's `--params` JSON.
    pub fn params_json(&self) -> String {
        serde_json::to_string_pretty(&keys::to_json(&self.settings.params))
            .unwrap_or_else(|_| "{}".into())
    }

    /// Everything the tests and the benchmark read (JSON).
    pub fn status_json(&self, now_ms: f64) -> String {
        let v = serde_json::json!({
            "query": self.query(),
            "issues": self.issues,
            "omega": self.settings.view.omega,
            "fr": self.fr_status,
            "fr_method": self.fr_method(),
            "fr_branch_points": self.hbm.points.len(),
            "fr_partial": self.hbm.error,
            "fr_overlay": self.ti_status,
            "fr_discrepancy": self.fr_view().discrepancy,
            "bif": self.bif_status,
            "bif_bands": self.instability_bands(),
            "omega_job": self.omega_status,
            "map": self.map_status,
            "map_grid": self.map.grid,
            "map_progress": self.map_status.progress(now_ms),
            "map_counts": self.map.counts(),
            "lyap": self.lyap_status,
            "lyap_points": self.lyap.curve().len(),
            "lyap_progress": self.lyap_status.progress(now_ms),
            "pinned": self.pinned.as_ref().map(|p| serde_json::json!({
                "query": link::encode(&p.settings),
                "fr": p.fr_status,
                "bif": p.bif_status,
                "fr_branch_points": p.hbm.points.len(),
                "bif_points": p.bif.samples.len(),
            })),
            "ab_labels": self.ab_labels(),
            "fr_progress": self.fr_status.progress(now_ms),
            "fr_overlay_progress": self.ti_status.progress(now_ms),
            "bif_progress": self.bif_status.progress(now_ms),
            "omega_progress": self.omega_status.progress(now_ms),
            "workers_ready": self.workers.iter().filter(|w| w.ready).count(),
            "omega_result": self.omega.as_ref().map(|r| serde_json::json!({
                "omega": r.omega, "mesh": r.mesh_name, "impact": r.regime.solver_name(), "period": r.period,
            })),
        });
        v.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::protocol::{FrSample, HbmMesh, HbmSample};

    fn posts(fx: &[Effect]) -> Vec<(usize, ToWorker)> {
        fx.iter()
            .filter_map(|e| match e {
                Effect::Post { worker, text } => {
                    Some((*worker, serde_json::from_str(text).unwrap()))
                }
                Effect::Download { .. } => None,
            })
            .collect()
    }

    fn ready(c: &mut Controller) -> Vec<(usize, ToWorker)> {
        let mut fx = c.worker_message(0, r#"{"type":"ready"}"#, 1.0);
        fx.extend(c.worker_message(1, r#"{"type":"ready"}"#, 1.0));
        posts(&fx)
    }

    fn hbm_points(id: JobId, omegas: &[f64], finished: bool, error: Option<&str>) -> String {
        encode(&FromWorker::HbmPoints {
            id,
            points: omegas
                .iter()
                .map(|&omega| HbmSample {
                    omega,
                    meshes: vec![HbmMesh {
                        rel_min_um: 80.0,
                        rel_max_um: 120.0,
                        regime: crate::protocol::Regime::NoImpact,
                    }],
                    stable: Some(true),
                    bifurcation: None,
                })
                .collect(),
            progress: omegas.last().map_or(0.0, |o| (o - 0.1) / 1.9),
            finished,
            error: error.map(str::to_string),
        })
    }

    /// The bands arrive from the sweep's shard-0 worker and are kept for
    /// the view; another job's bands are ignored.
    #[test]
    fn instability_bands_come_from_the_current_sweep() {
        let (mut c, _) = Controller::new("", 0.0);
        ready(&mut c);
        let id = c.bif.id;
        let msg = |id, bands: Vec<(f64, f64)>| encode(&FromWorker::Bands { id, bands });
        c.worker_message(0, &msg(id + 100, vec![(0.2, 0.3)]), 1.0);
        assert!(c.instability_bands().is_empty());
        c.dirty = Dirty::default();
        c.worker_message(0, &msg(id, vec![(0.99, 1.22)]), 2.0);
        assert_eq!(c.instability_bands(), vec![(0.99, 1.22)]);
        assert!(c.dirty.bif);
        assert_eq!(c.bif_view().unstable_bands, vec![(0.99, 1.22)]);
    }

    #[test]
    fn jobs_queue_until_ready_then_split_over_two_workers() {
        let (mut c, fx) = Controller::new("", 0.0);
        assert!(fx.is_empty(), "nothing may be posted before ready");
        let p = ready(&mut c);
        // Omega on worker 0, the HBM branch on worker 1, bifurcation shards on
        // both; no time-integration overlay by default.
        // Map rows and Lyapunov chains are shared by both workers too.
        assert_eq!(p.iter().filter(|(w, _)| *w == 0).count(), 4);
        assert_eq!(p.iter().filter(|(w, _)| *w == 1).count(), 4);
        assert!(p.iter().any(|(w, m)| *w == HBM_WORKER
            && matches!(
                m,
                ToWorker::Run {
                    job: JobSpec::Hbm {
                        harmonics: 5,
                        points: 150,
                        stability: true,
                        ..
                    },
                    ..
                }
            )));
        let shards: Vec<u32> = p
            .iter()
            .filter_map(|(_, m)| match m {
                ToWorker::Run {
                    job: JobSpec::Bif { shard, chains, .. },
                    ..
                } => {
                    assert_eq!(*chains, 2);
                    Some(*shard)
                }
                _ => None,
            })
            .collect();
        assert_eq!(shards, vec![0, 1]);
        assert_eq!(c.fr_method(), "harmonic balance, H = 5, exact");
    }

    #[test]
    fn slider_change_restarts_and_stale_replies_are_ignored() {
        let (mut c, _) = Controller::new("", 0.0);
        ready(&mut c);
        let old = c.hbm.id;
        let fx = c.set_key("backlash_um", "150", 10.0).unwrap();
        // Omega, branch, two bifurcation and two Lyapunov shards; the map over
        // backlash does not depend on the backlash, so it goes on.
        assert_eq!(posts(&fx).len(), 6);
        assert_ne!(c.hbm.id, old);
        assert!(c.query().contains("backlash_um=150"));
        c.worker_message(1, &hbm_points(old, &[0.1], false, None), 11.0);
        assert!(c.hbm.points.is_empty());
        // Out of range: refused with the key and range named; nothing restarts.
        let e = c.set_key("backlash_um", "5000", 12.0).unwrap_err();
        assert!(e.contains("backlash_um") && e.contains("1000"), "{e}");
        // The selected Omega restarts only the Omega job.
        let fx = c.select_omega(1.23456, 13.0);
        let p = posts(&fx);
        assert_eq!(p.len(), 1);
        assert!(
            matches!(&p[0].1, ToWorker::Run { job: JobSpec::Omega { omega, .. }, .. } if (*omega - 1.2346).abs() < 1e-12)
        );
        assert!(c.query().contains("omega=1.2346"));
        // The harmonics restart only the branch, on its worker.
        let p = posts(&c.set_key("harmonics", "3", 14.0).unwrap());
        assert_eq!(p.len(), 1);
        assert!(matches!(
            &p[0],
            (
                HBM_WORKER,
                ToWorker::Run {
                    job: JobSpec::Hbm { harmonics: 3, .. },
                    ..
                }
            )
        ));
        assert!(c.set_key("harmonics", "16", 15.0).is_err());
    }

    /// Runs the Omega jobs among `p` on a real worker core and feeds the
    /// replies back to the controller.
    fn run_omega_jobs(c: &mut Controller, p: &[(usize, ToWorker)], now_ms: f64) {
        for (w, m) in p {
            if matches!(
                m,
                ToWorker::Run {
                    job: JobSpec::Omega { .. },
                    ..
                }
            ) {
                let mut core = worker_core::WorkerCore::new();
                core.handle(&encode(m));
                while core.has_work() {
                    for reply in core.step() {
                        c.worker_message(*w, &encode(&reply), now_ms);
                    }
                }
            }
        }
    }

    #[test]
    fn a_slider_change_previews_the_selected_omega_from_the_last_end_state() {
        let (mut c, _) = Controller::new("transient_periods=40&record_periods=10", 0.0);
        let p = ready(&mut c);
        // No previous state: no preview, the views wait for the worker.
        assert!(c.omega.is_none() && c.omega_status.preview_ms.is_none());
        run_omega_jobs(&mut c, &p, 5.0);
        let full = c.omega.clone().expect("the worker's result");
        assert!(!full.preview && !full.cli_json.is_empty());
        assert_eq!(
            full.end_state.len(),
            2 * c.model.as_ref().unwrap().system.dof()
        );

        let p = posts(&c.set_key("backlash_um", "150", 10.0).unwrap());
        // The preview shows at once, under the new backlash, while the
        // worker's job runs; it is bounded and carries no CLI JSON.
        let pre = c.omega.clone().expect("a preview");
        assert!(pre.preview && pre.cli_json.is_empty());
        assert_eq!(c.omega_status.preview_ms, Some(10.0));
        assert!(c.omega_status.running());
        assert_eq!(pre.backlash_um, 150.0);
        assert_eq!(pre.record_periods, worker_core::PREVIEW_RUN.record_periods);
        assert!(pre.transient_periods_run <= worker_core::PREVIEW_RUN.transient_periods);
        assert!(crate::views::summary_line(&pre, &[]).starts_with("Preview ("));
        // The full run (from the static state, as the CLI starts) replaces it.
        run_omega_jobs(&mut c, &p, 20.0);
        let after = c.omega.clone().unwrap();
        assert!(!after.preview && after.backlash_um == 150.0);
        assert!(!c.omega_status.running());
        // A preview that cannot start (a model with other coordinates) is
        // skipped: the last result stays until the worker answers.
        c.omega.as_mut().unwrap().end_state.pop();
        c.set_key("backlash_um", "120", 30.0).unwrap();
        assert!(!c.omega.as_ref().unwrap().preview);
    }

    #[test]
    fn progress_shows_only_for_long_jobs() {
        let (mut c, _) = Controller::new("fr_points=4", 0.0);
        ready(&mut c);
        assert_eq!(c.fr_status.progress(100.0), None);
        assert_eq!(c.fr_status.progress(300.0), Some((0, 100)));
        let id = c.hbm.id;
        c.worker_message(1, &hbm_points(id, &[0.1, 1.05], false, None), 350.0);
        assert_eq!(c.fr_status.progress(360.0), Some((50, 100)));
        c.worker_message(1, &hbm_points(id, &[2.0], true, None), 400.0);
        assert_eq!(c.fr_status.finished_ms, Some(400.0));
        assert_eq!(c.fr_status.progress(500.0), None);
        assert!(c.hbm.is_complete());
        // The complete branch is kept, faded, while the next one computes.
        c.set_key("harmonics", "3", 600.0).unwrap();
        let v = c.fr_view();
        assert_eq!(v.branches.len(), 2);
        assert!(v.branches[0].faded && v.branches[0].points.len() == 3);
    }

    #[test]
    fn a_solver_failure_ends_the_branch_as_partial_and_is_reported() {
        let (mut c, _) = Controller::new("", 0.0);
        ready(&mut c);
        let id = c.hbm.id;
        c.worker_message(1, &hbm_points(id, &[0.1, 0.5], false, None), 10.0);
        c.worker_message(
            1,
            &hbm_points(id, &[], true, Some("Newton did not converge")),
            20.0,
        );
        assert!(!c.fr_status.running());
        let e = c.fr_status.error.clone().unwrap();
        assert!(e.contains("0.5000") && e.contains("partial"), "{e}");
        assert!(c.issues.contains(&e));
        let v = c.fr_view();
        assert_eq!(v.branches.last().unwrap().points.len(), 2);
        assert!(v.branches.last().unwrap().label.contains("partial"));
        assert_eq!(v.branch_error.as_ref().map(|b| b.0), Some(0.5));
        let s: serde_json::Value = serde_json::from_str(&c.status_json(30.0)).unwrap();
        assert_eq!(s["fr_partial"], "Newton did not converge");
        // A new branch clears the old branch's failure message.
        c.set_key("harmonics", "3", 40.0).unwrap();
        assert!(c.issues.is_empty());
    }

    #[test]
    fn the_time_integration_overlay_runs_on_both_workers_when_asked() {
        let (mut c, _) = Controller::new("fr_ti_points=4", 0.0);
        let p = ready(&mut c);
        let ti: Vec<usize> = p
            .iter()
            .filter(|(_, m)| {
                matches!(
                    m,
                    ToWorker::Run {
                        job: JobSpec::Fr { points: 4, .. },
                        ..
                    }
                )
            })
            .map(|(w, _)| *w)
            .collect();
        assert_eq!(ti, vec![0, 1]);
        let id = c.fr.id;
        let pts = (0..4)
            .map(|i| FrSample {
                index: i,
                omega: 0.1 * f64::from(i + 1),
                meshes: vec![],
                period: None,
                error: Some("x".into()),
            })
            .collect();
        c.worker_message(1, &encode(&FromWorker::FrPoints { id, points: pts }), 400.0);
        assert_eq!(c.ti_status.finished_ms, Some(400.0));
        assert_eq!(c.fr_view().failed.len(), 4);
        // Switching it off cancels it on both workers.
        let p = posts(&c.set_key("fr_ti_points", "0", 500.0).unwrap());
        assert_eq!(p.len(), 2);
        assert!(p
            .iter()
            .all(|(_, m)| matches!(m, ToWorker::Cancel { kind: JobKind::Fr })));
        assert!(c.fr_view().overlay_source.is_none());
    }

    fn map_cells(id: JobId, cells: &[(u32, u32, crate::protocol::Regime, Option<u32>)]) -> String {
        encode(&FromWorker::MapCells {
            id,
            cells: cells
                .iter()
                .map(
                    |&(row, column, regime, period)| crate::protocol::MapSample {
                        row,
                        column,
                        omega: 0.0,
                        value: 0.0,
                        regime,
                        period,
                        error: None,
                    },
                )
                .collect(),
        })
    }

    #[test]
    fn the_map_shards_rows_and_a_cell_click_sets_both_parameters() {
        use crate::protocol::Regime;
        let (mut c, _) = Controller::new(
            "map_omega_points=20&map_value_points=4&map_from=40&map_to=160",
            0.0,
        );
        let p = ready(&mut c);
        let shards: Vec<(usize, u32, u32)> = p
            .iter()
            .filter_map(|(w, m)| match m {
                ToWorker::Run {
                    job:
                        JobSpec::Map {
                            shard,
                            shards,
                            omega_points: 20,
                            value_points: 4,
                            ..
                        },
                    ..
                } => Some((*w, *shard, *shards)),
                _ => None,
            })
            .collect();
        assert_eq!(shards, vec![(0, 0, 2), (1, 1, 2)]);
        let id = c.map.id;
        c.worker_message(
            0,
            &map_cells(id, &[(0, 0, Regime::NoImpact, Some(1))]),
            10.0,
        );
        c.worker_message(
            1,
            &map_cells(id, &[(1, 0, Regime::DoubleSided, Some(2))]),
            11.0,
        );
        assert_eq!(c.map_status.done, 2);
        assert_eq!(c.map.counts().0, [1, 0, 1, 0]);
        // Row 2 is 120 um, column 10 is Omega = 0.1 + 10 * 1.9 / 19 = 1.1.
        let fx = c.pick_map_point(1.1 + 0.02, 120.0 - 5.0, 20.0).unwrap();
        assert!(c.query().contains("backlash_um=120"), "{}", c.query());
        assert_eq!(c.settings.view.omega, 1.1);
        assert!(c.query().contains("omega=1.1&"), "{}", c.query());
        // The map goes on (same signature), everything else restarts.
        assert_eq!(c.map.id, id);
        assert!(!posts(&fx).iter().any(|(_, m)| matches!(
            m,
            ToWorker::Run {
                job: JobSpec::Map { .. },
                ..
            }
        )));
        assert_eq!(c.map_status.done, 2);
        assert!(c.pick_map_point(5.0, 100.0, 21.0).is_err());
        // On the TE axis, with its own default range, a click sets te_um.
        c.set_key("map_key", "te_um", 30.0).unwrap();
        assert_eq!(
            (c.settings.view.map_from, c.settings.view.map_to),
            (0.0, 60.0)
        );
        assert_ne!(c.map.id, id);
        c.set_key("map_value_points", "7", 31.0).unwrap();
        c.pick_map_point(0.1, 30.0, 32.0).unwrap();
        assert!(c.query().contains("te_um=30"), "{}", c.query());
        assert_eq!(c.settings.view.omega, 0.1);
        // Another parameter changes the map's model: it restarts.
        let before = c.map.id;
        c.set_key("damping_ratio", "0.05", 40.0).unwrap();
        assert_ne!(c.map.id, before);
    }

    #[test]
    fn the_lyapunov_curve_collects_both_chains_and_can_be_switched_off() {
        let (mut c, _) = Controller::new("lyap_points=4", 0.0);
        let p = ready(&mut c);
        assert_eq!(
            p.iter()
                .filter(|(_, m)| matches!(
                    m,
                    ToWorker::Run {
                        job: JobSpec::Lyap {
                            points: 4,
                            chains: 2,
                            ..
                        },
                        ..
                    }
                ))
                .count(),
            2
        );
        let id = c.lyap.id;
        let pts = |idx: &[u32]| {
            encode(&FromWorker::LyapPoints {
                id,
                points: idx
                    .iter()
                    .map(|&i| crate::protocol::LyapSample {
                        index: i,
                        omega: 0.1 + f64::from(i),
                        per_period: Some(-0.1 * f64::from(i)),
                        per_s: Some(-1.0),
                        error: None,
                    })
                    .collect(),
            })
        };
        c.worker_message(1, &pts(&[1, 3]), 5.0);
        c.worker_message(0, &pts(&[0, 2]), 6.0);
        assert_eq!(c.lyap_status.finished_ms, Some(6.0));
        let curve = c.lyap.curve();
        assert_eq!(curve.len(), 4);
        assert!(curve.windows(2).all(|w| w[0].0 < w[1].0));
        let p = posts(&c.set_key("lyap_points", "0", 7.0).unwrap());
        assert!(p.iter().all(|(_, m)| matches!(
            m,
            ToWorker::Cancel {
                kind: JobKind::Lyap
            }
        )));
        assert_eq!(c.lyap.id, 0);
    }

    #[test]
    fn a_link_with_a_pinned_state_computes_both_and_pinning_keeps_a() {
        let (mut c, _) = Controller::new("backlash_um=150&a=backlash_um%3D100%26omega%3D0.5", 0.0);
        assert!(c.issues.is_empty(), "{:?}", c.issues);
        let p = ready(&mut c);
        let pinned: Vec<(usize, JobKind)> = p
            .iter()
            .filter_map(|(w, m)| match m {
                ToWorker::RunPinned { job, params, .. } => {
                    assert_eq!(params["backlash_s1a_um"].as_f64(), Some(100.0));
                    Some((*w, job.kind()))
                }
                _ => None,
            })
            .collect();
        assert_eq!(
            pinned,
            vec![
                (0, JobKind::Bif),
                (HBM_WORKER, JobKind::Hbm),
                (1, JobKind::Bif)
            ]
        );
        let a_id = c.pinned.as_ref().unwrap().hbm.id;
        c.worker_message(1, &hbm_points(a_id, &[0.1, 1.0, 2.0], true, None), 5.0);
        let a = c.pinned.as_ref().unwrap();
        assert_eq!(a.hbm.points.len(), 3);
        assert!(c.hbm.points.is_empty(), "A's points must not reach B");
        let v = c.fr_view();
        let labels: Vec<&str> = v.branches.iter().map(|b| b.label.as_str()).collect();
        assert!(
            labels[0].starts_with("A: backlash_um=100") && v.branches[0].pinned,
            "{labels:?}"
        );
        assert!(labels[1].starts_with("B: backlash_um=150"), "{labels:?}");
        assert!(
            c.query().contains("&a=model%3Dravigneaux%26omega%3D0.5%26"),
            "{}",
            c.query()
        );
        assert_eq!(link::decode(&c.query()).pinned.unwrap().view.omega, 0.5);
        // Clear A: the link loses it, and A's jobs are cancelled on every worker.
        let fx = posts(&c.clear_a());
        assert!(fx
            .iter()
            .all(|(_, m)| matches!(m, ToWorker::CancelPinned { .. })));
        assert!(c.pinned.is_none() && !c.query().contains("&a="));
    }

    #[test]
    fn pin_as_a_keeps_finished_results_while_b_changes() {
        let (mut c, _) = Controller::new("bif_points=2&bif_dir=up", 0.0);
        ready(&mut c);
        let id = c.hbm.id;
        c.worker_message(1, &hbm_points(id, &[0.1, 2.0], true, None), 5.0);
        c.bif_status.finished_ms = Some(6.0);
        let fx = c.pin_a(7.0);
        assert!(fx.is_empty(), "finished results are kept, not recomputed");
        c.set_key("backlash_um", "150", 8.0).unwrap();
        let a = c.pinned.as_ref().unwrap();
        assert_eq!(a.hbm.points.len(), 2);
        assert_eq!(
            keys::get(&a.settings.params, "backlash_um"),
            Some(keys::Value::Num(100.0))
        );
        let (ta, tb) = c.ab_labels().unwrap();
        assert_eq!(
            (ta.as_str(), tb.as_str()),
            ("backlash_um=100", "backlash_um=150")
        );
        assert!(c.bif_view().ab_labels.is_some());
    }

    #[test]
    fn presets_links_and_model_switch() {
        let (mut c, _) = Controller::new("backlash_um=oops&te_um=25", 0.0);
        assert!(c.issues.iter().any(|i| i.contains("backlash_um")));
        assert!(c.query().contains("te_um=25"));
        c.apply_preset("pair", 1.0);
        assert!(c.preset_note.is_some());
        assert_eq!(c.mesh_names(), vec!["pg".to_string()]);
        c.set_key("model", "ravigneaux", 2.0).unwrap();
        assert_eq!(c.settings.view.mesh, MeshSel::Named("s1a1".into()));
        assert!(c.set_key("nonsense", "1", 3.0).is_err());
        assert!(c.cli_commands().contains("--mesh s1a1"));
        let cli = c.cli_commands();
        assert!(
            cli.starts_with("gearshock frf --params gearshock-params.json --omega-from ")
                && cli
                    .lines()
                    .next()
                    .unwrap()
                    .ends_with("--points 150 --harmonics 5 --mesh s1a1"),
            "{cli}"
        );
        let _ = c.fr_view();
        let _ = c.bif_view();
        let s: serde_json::Value = serde_json::from_str(&c.status_json(5.0)).unwrap();
        assert!(s["query"].as_str().unwrap().starts_with("model=ravigneaux"));
    }
}
