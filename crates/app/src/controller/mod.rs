//! The page's controller: settings, jobs and worker replies, as a plain
//! state machine that the web layer drives and the native tests exercise.
//!
//! Every user action returns the messages to post to the workers; the
//! controller queues messages for a worker until it has said "ready".
//! Jobs are restarted by what a change affects: a model parameter restarts
//! everything, the frequency range the sweeps, the harmonics only the
//! harmonic-balance branch, the selected Omega or plotted mesh only the
//! selected-Omega job. The harmonic-balance branch of view 1 runs on the last
//! worker (worker 0 serves the selected-Omega job first).
//!
//! The page runs a pool of workers sized to the machine ([`pool_size`]).
//! Sweeps along continuation chains use a number of chains fixed by their
//! point count alone ([`chain_count`]), dealt round robin over the pool, so
//! their results are the same bits on any machine; map rows are
//! independent and shared by every worker. The web layer redraws the views
//! whose `dirty` flag is set, once per animation frame.

use crate::link;
use crate::presets;
use crate::protocol::{
    encode, FromWorker, JobId, JobKind, JobSpec, OmegaResult, RunOptions, ToWorker,
};
use crate::settings::{mesh_names, view_key, MeshSel, Settings};
use crate::status::{Dirty, JobStatus};
use crate::views::bif::{BifStore, BifView};
use crate::views::fr::{fr_view, FrBranch, FrSource, FrStore, FrView, HbmStore};
use crate::views::lyap::LyapStore;
use crate::views::map::{MapGrid, MapStore, MapView};
use crate::views::{distinct, natural_in_range, ViewContext};
use solver::keys;
use solver::steady::Model;

/// The fewest Web Workers the page runs (also the pool of [`Controller::new`]).
pub const MIN_WORKERS: usize = 2;
/// The most Web Workers the page runs.
pub const MAX_WORKERS: usize = 8;
/// A continuation chain's fewest grid points (see [`chain_count`]).
pub const MIN_CHAIN_POINTS: u32 = 50;

/// The worker pool for a machine with `hardware_concurrency` logical cores
/// (`navigator.hardwareConcurrency`; `None` or 0 when the browser does not
/// say): one core left to the page's main thread, at least
/// [`MIN_WORKERS`] and at most [`MAX_WORKERS`] workers.
pub fn pool_size(hardware_concurrency: Option<u32>) -> usize {
    let cores = hardware_concurrency.unwrap_or(0) as usize;
    cores.saturating_sub(1).clamp(MIN_WORKERS, MAX_WORKERS)
}

/// Interleaved continuation chains of a sweep of `points` grid points:
/// one per [`MIN_CHAIN_POINTS`] points, at least 2 and at most
/// [`MAX_WORKERS`] (never more than the points). It depends on the points
/// only, never on the pool, so that each chain continues from the same
/// states and a sweep gives the same bits on any machine.
pub fn chain_count(points: u32) -> u32 {
    (points / MIN_CHAIN_POINTS)
        .clamp(2, MAX_WORKERS as u32)
        .min(points)
        .max(1)
}
/// Samples per mesh period of the selected-Omega history.
pub const SAMPLES_PER_PERIOD: u32 = 64;
/// Highest mesh order of the spectrum.
pub const MAX_ORDER: f64 = 8.0;
/// How a failure of the harmonic-balance branch starts in the messages (a
/// new branch clears the old branch's failure).
const HBM_FAILURE: &str = "Frequency response: the harmonic-balance solver failed";
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
    /// The other workers' shards received so far (one JSON text each).
    collected: Vec<String>,
    /// How many shards the other workers hold.
    expected: usize,
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
    /// The parameter family shown, if any (member 0 is the current state).
    pub family: Option<Family>,
    /// The meshes of the frequency response's side-by-side panels (the
    /// paper's Figs. 2 and 3), if shown.
    pub panels: Option<Vec<String>>,
    /// Views to redraw.
    pub dirty: Dirty,
    workers: Vec<WorkerSlot>,
    next_id: JobId,
    export: Option<PendingExport>,
    /// The parametric-instability bands of the bifurcation sweep's range,
    /// from its shard-0 worker (kept until a newer job's arrive).
    bands: Vec<(f64, f64)>,
    /// The "Start here" tour's step (0-based), if it is running.
    pub tour: Option<usize>,
}

impl Controller {
    /// Starts from a link's query string with [`MIN_WORKERS`] workers (all
    /// jobs queued until the workers are ready).
    pub fn new(query: &str, now_ms: f64) -> (Self, Vec<Effect>) {
        Self::with_workers(query, now_ms, MIN_WORKERS)
    }

    /// Starts from a link's query string with a pool of `workers` workers
    /// (clamped to 1 ..= [`MAX_WORKERS`]; one worker only for the
    /// benchmark's scaling figure, the page runs [`pool_size`]).
    pub fn with_workers(query: &str, now_ms: f64, workers: usize) -> (Self, Vec<Effect>) {
        let workers = workers.clamp(1, MAX_WORKERS);
        let (tour, query) = crate::tour::split_tour(query);
        let decoded = link::decode(&query);
        let pinned = decoded.pinned;
        let family = decoded.family.map(|spec| Family {
            spec,
            members: Vec::new(),
        });
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
            family,
            panels: decoded.panels,
            dirty: Dirty::default(),
            workers: vec![WorkerSlot::default(); workers],
            next_id: 0,
            export: None,
            bands: Vec::new(),
            tour,
        };
        c.rebuild_model();
        let mut fx = c.restart(ALL, now_ms);
        if let Some(a) = pinned {
            fx.extend(c.start_pinned(a, now_ms));
        }
        c.dirty = Dirty::all();
        (c, fx)
    }

    fn rebuild_model(&mut self) {
        self.model = Model::new(&self.settings.params).map_err(|e| e.to_string());
    }

    /// The current link query (without `?`), with the pinned state A if any.
    pub fn query(&self) -> String {
        let q = link::encode_all(
            &self.settings,
            self.pinned.as_ref().map(|p| &p.settings),
            self.family.as_ref().map(|f| &f.spec),
            self.panels.as_deref(),
        );
        match self.tour {
            Some(step) => format!("{q}&tour={}", step + 1),
            None => q,
        }
    }

    /// Goes to tour step `step` (0-based; `None` ends the tour): makes the
    /// step's settings as the controls would and puts the step in the link.
    pub fn tour_go(&mut self, step: Option<usize>, now_ms: f64) -> Vec<Effect> {
        let step = step.filter(|&s| s < crate::tour::TOUR.len());
        self.tour = step;
        self.dirty.url = true;
        let mut fx = Vec::new();
        if let Some(s) = step {
            for (k, v) in crate::tour::TOUR[s].set {
                let current =
                    self.settings.view.get(k).or_else(|| {
                        keys::get(&self.settings.params, k).map(|x| link::value_text(&x))
                    });
                if current.as_deref() == Some(*v) {
                    continue;
                }
                match self.set_key(k, v, now_ms) {
                    Ok(more) => fx.extend(more),
                    Err(e) => self.issue(e),
                }
                self.dirty.controls = true;
            }
        }
        fx
    }

    /// The mesh names of the current model.
    pub fn mesh_names(&self) -> Vec<String> {
        mesh_names(&self.settings.params)
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
            self.settings
                .view
                .set(key, text, &meshes)
                .map_err(|_| crate::words::must_be(key, text))?;
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
            if key == "mesh" && self.panels.take().is_some() {
                // Choosing a mesh shows that mesh alone.
                self.dirty.url = true;
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
                // Only the axes change: every view of x is redrawn.
                "clearance" => {
                    self.dirty.omega = true;
                    NONE
                }
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
        // The message in a sentence with the allowed range ("Backlash b must be
        // between 0 and 1000 µm"), not the CLI's key syntax.
        let plain = |_| crate::words::must_be(key, text);
        let value = keys::parse_value(key, text).map_err(plain)?;
        let mut params = self.settings.params.clone();
        keys::set(&mut params, key, value).map_err(plain)?;
        if params == self.settings.params {
            return Ok(Vec::new());
        }
        let model = Model::new(&params).map_err(|e| e.to_string())?;
        let model_changed = params.kind() != self.settings.params.kind();
        self.settings.params = params;
        self.model = Ok(model);
        if model_changed {
            // A new model: its own meshes (no panels of the old one), its
            // default mesh, and fresh controls.
            self.panels = None;
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
        let (tour, query) = crate::tour::split_tour(query);
        self.tour = tour;
        let d = link::decode(&query);
        self.settings = d.settings;
        self.issues = d.issues;
        self.preset_note = None;
        self.rebuild_model();
        self.hbm_previous = None;
        let mut fx = self.clear_a();
        fx.extend(self.clear_family());
        self.family = d.family.map(|spec| Family {
            spec,
            members: Vec::new(),
        });
        self.panels = d.panels;
        if let Some(a) = d.pinned {
            fx.extend(self.start_pinned(a, now_ms));
        }
        self.dirty = Dirty::all();
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
        let mut query = p.query();
        if let Some(f) = &p.family {
            let v: Vec<String> = f
                .values
                .iter()
                .map(|x| crate::settings::fmt_exact(*x))
                .collect();
            query.push_str(&format!("&family={}:{}", f.key, v.join(",")));
        }
        if let Some(m) = p.meshes.filter(|m| m.len() > 1) {
            query.push_str(&format!("&{}={}", crate::panels::PANELS_KEY, m.join(",")));
        }
        let fx = self.load_query(&query, now_ms);
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
        let (mesh, _) = self.mesh_and_backlash();
        self.fr_view_on(mesh, None)
    }

    /// The frequency-response view of mesh `mesh` (`None`: the worst),
    /// titled `label` (default: the plotted mesh's).
    fn fr_view_on(&self, mesh: Option<usize>, label: Option<&str>) -> FrView {
        let (_, b) = self.mesh_and_backlash();
        let mut ctx = self.view_context();
        if let Some(l) = label {
            ctx.mesh_label = l.to_string();
        }
        // The previous branch is context while the new one computes, not
        // after it has ended (complete or failed).
        let previous = self.hbm_previous.as_ref().filter(|_| !self.hbm.finished);
        // The time-integration dots: the overlay job's when it is on, else
        // the bifurcation sweep's steady states (the same computation, free).
        let swept;
        let overlay = if self.fr.id != 0 {
            Some(&self.fr)
        } else {
            let v = &self.settings.view;
            swept = FrStore::from_sweep(&self.bif.samples, v.transient_periods, v.record_periods);
            Some(&swept).filter(|s| !s.points.is_empty())
        };
        let previous = previous.filter(|_| self.family.is_none());
        let mut v = fr_view(&self.hbm, previous, overlay, mesh, &b, &ctx);
        v.whole_clearance = self.settings.view.whole_clearance;
        if let Some(f) = &self.family {
            // Every member's ±b (a backlash family has one pair per value).
            let mut levels = v.backlash_um.clone();
            for m in &f.members {
                if let Ok(p) = &m.params {
                    let s = Settings {
                        params: p.clone(),
                        view: self.settings.view.clone(),
                    };
                    levels.extend(distinct(&pinned_backlash(&s), mesh));
                }
            }
            v.backlash_um = distinct(&levels, None);
            for br in v.branches.iter_mut().filter(|b| !b.faded) {
                let partial = if self.hbm.error.is_some() {
                    "; partial"
                } else {
                    ""
                };
                br.label = format!("{}{partial}", f.spec.label(0));
                br.member = Some(0);
            }
            for (i, m) in f.members.iter().enumerate() {
                let partial = if m.hbm.error.is_some() {
                    "; partial"
                } else {
                    ""
                };
                // Each member's bifurcations sit on its own curve.
                let (points, markers) = m.hbm.curve(mesh);
                v.markers.extend(markers);
                v.branches.push(FrBranch {
                    label: format!("{}{partial}", f.spec.label(i + 1)),
                    points,
                    faded: false,
                    pinned: false,
                    member: Some(i + 1),
                });
            }
        }
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
            v.pinned_backlash_um = distinct(&pinned_backlash(&p.settings), mesh);
            v.branches.insert(
                0,
                FrBranch {
                    label: format!("A: {ta}{partial}"),
                    points: p.hbm.curve(mesh).0,
                    faded: false,
                    pinned: true,
                    member: None,
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
        v.whole_clearance = self.settings.view.whole_clearance;
        v.unstable_bands = self.instability_bands();
        if let Some(p) = &self.pinned {
            v.pinned = p.bif.view(mesh, &b, &ctx).points;
            v.pinned_backlash_um = distinct(&pinned_backlash(&p.settings), mesh);
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

    /// Everything the tests and the benchmark read.
    pub fn status(&self, now_ms: f64) -> serde_json::Value {
        let fr = self.fr_view();
        serde_json::json!({
            "query": self.query(),
            "issues": self.issues,
            "omega": self.settings.view.omega,
            "fr": self.fr_status,
            "fr_method": self.fr_method(),
            "fr_branch_points": self.hbm.points.len(),
            "fr_partial": self.hbm.error,
            "fr_overlay": self.ti_status,
            "fr_discrepancy": fr.discrepancy,
            // The frequency response's time-integration dots and the
            // sentence under it where the branch is unstable.
            "fr_dots": fr.overlay.len(),
            "fr_sentence": crate::views::unstable::unstable_sentence(&fr),
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
            "family": self.family_status(),
            "fr_panels": self.panels,
            "fr_progress": self.fr_status.progress(now_ms),
            "fr_overlay_progress": self.ti_status.progress(now_ms),
            "bif_progress": self.bif_status.progress(now_ms),
            "omega_progress": self.omega_status.progress(now_ms),
            "workers_ready": self.workers.iter().filter(|w| w.ready).count(),
            "workers": self.workers.len(),
            "omega_result": self.omega.as_ref().map(|r| serde_json::json!({
                "omega": r.omega, "mesh": r.mesh_name, "impact": r.regime.solver_name(), "period": r.period,
            })),
        })
    }
}

mod export;
mod family_export;
mod text;
pub use export::{ExportError, Format};
mod family;
pub use family::{Family, Member};
mod jobs;
mod panels;
use jobs::{Restart, ALL, NONE};
use pinned::pinned_backlash;
mod messages;
mod pinned;
mod replies;
mod svg;
pub use svg::{view_size, SvgError};

pub use pinned::Pinned;

#[cfg(test)]
mod family_tests;
#[cfg(test)]
mod tests;
