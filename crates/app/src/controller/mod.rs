//! The page's controller: settings, jobs and worker replies, as a plain
//! state machine that the web layer drives and the native tests exercise.
//!
//! Every user action returns the messages to post to the workers; the
//! controller queues messages for a worker until it has said "ready",
//! and at the page's start holds the jobs off the first screen until the
//! first screen's have ended ([`Controller::hold_off_screen`]).
//! Jobs are restarted by what a change affects: a model parameter restarts
//! everything, a view option the kinds its row of
//! [`figures::settings::VIEW_KEYS`] names. The current state, the pinned A
//! and each family member are each one [`Computation`], addressed by a
//! [`Target`]; every reply goes to [`Computation::feed`]. The
//! harmonic-balance branch of `ViewId::Fr` runs on the last worker (worker
//! 0 serves the selected-Omega job first).
//!
//! The page runs a pool of workers sized to the machine ([`pool_size`]).
//! Sweeps along continuation chains use a number of chains fixed by their
//! point count alone ([`chain_count`]), dealt round robin over the pool, so
//! their results are the same bits on any machine; map rows are
//! independent and shared by every worker. The page core redraws the views
//! whose data changed ([`Dirty`]), once per animation frame.

use crate::store::kinds::{self, chain_count};
use crate::store::status::{Dirty, JobStatus};
use crate::store::Computation;
pub use error::InputError;
use figures::link;
use figures::presets;
use figures::protocol::{
    encode, um, FromWorker, JobId, JobKind, JobSpec, KindSet, OmegaResult, Target, ToWorker,
};
use figures::settings::{mesh_names, view_key, MeshSel, Settings};
use figures::views::bif::BifView;
use figures::views::fr::{fr_view, FrBranch, FrSource, FrStore, FrView};
use figures::views::map::{MapGrid, MapView};
use figures::views::{distinct, natural_in_range, ViewContext};
use solver::keys;
use solver::model::Model;

/// The fewest Web Workers the page runs (also the pool of [`Controller::new`]).
pub const MIN_WORKERS: usize = 2;
/// The most Web Workers the page runs: as many as a sweep's chains.
pub const MAX_WORKERS: usize = crate::store::kinds::MAX_CHAINS as usize;

/// The worker pool for a machine with `hardware_concurrency` logical cores
/// (`navigator.hardwareConcurrency`; `None` or 0 when the browser does not
/// say): one core left to the page's main thread, at least
/// [`MIN_WORKERS`] and at most [`MAX_WORKERS`] workers.
pub fn pool_size(hardware_concurrency: Option<u32>) -> usize {
    let cores = hardware_concurrency.unwrap_or(0) as usize;
    cores.saturating_sub(1).clamp(MIN_WORKERS, MAX_WORKERS)
}

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
    queue: Vec<jobs::Outgoing>,
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
    settings: Settings,
    /// The model built from the parameters, or why it cannot be.
    model: Result<Model, solver::SolverError>,
    /// Messages for the user (link problems, rejected input, job failures).
    pub issues: Vec<String>,
    /// The note of the preset last loaded.
    preset_note: Option<String>,
    /// The current state's results.
    main: Computation,
    /// The pinned state A of an A/B comparison.
    pinned: Option<Pinned>,
    /// The parameter family shown, if any (member 0 is the current state).
    family: Option<Family>,
    /// The meshes of the frequency response's side-by-side panels (the
    /// paper's Figs. 2 and 3), if shown.
    panels: Option<Vec<String>>,
    /// What changed since the page last drew.
    dirty: Dirty,
    workers: Vec<WorkerSlot>,
    /// At the page's start ([`Controller::hold_off_screen`]), the messages
    /// of the jobs off the first screen ([`KindSet::FIRST_SCREEN`]), held
    /// back with their workers until the first screen's jobs have ended;
    /// `None` when nothing is held.
    held: Option<Vec<(usize, jobs::Outgoing)>>,
    next_id: JobId,
    export: Option<PendingExport>,
    /// The "Start here" tour's step (0-based), if it is running.
    tour: Option<usize>,
    /// The boundary last clicked on the map: what it marks, in a sentence,
    /// and where.
    picked_boundary: Option<boundaries::PickedMark>,
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
        let tour_issue = crate::tour::tour_issue(query);
        let (tour, query) = crate::tour::split_tour(query);
        let mut decoded = link::decode(&query);
        decoded.issues.extend(tour_issue);
        let pinned = decoded.pinned;
        let family = decoded.family.map(|spec| Family {
            spec,
            members: Vec::new(),
        });
        let mut c = Controller {
            model: Model::new(&decoded.settings.params),
            settings: decoded.settings,
            issues: decoded.issues,
            preset_note: None,
            main: Computation::default(),
            pinned: None,
            family,
            panels: decoded.panels,
            dirty: Dirty::default(),
            workers: vec![WorkerSlot::default(); workers],
            held: None,
            next_id: 0,
            export: None,
            tour,
            picked_boundary: None,
        };
        let mut fx = c.restart(KindSet::ALL, now_ms);
        if let Some(a) = pinned {
            fx.extend(c.start_pinned(a, now_ms));
        }
        c.dirty = Dirty::all();
        (c, fx)
    }

    fn rebuild_model(&mut self) {
        self.model = Model::new(&self.settings.params);
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
                if self.setting_text(k).as_deref() == Some(*v) {
                    continue;
                }
                match self.set_key(k, v, now_ms) {
                    Ok(more) => fx.extend(more),
                    Err(e) => self.issue(e.to_string()),
                }
                self.dirty.controls = true;
            }
        }
        fx
    }

    /// A setting's value as the link writes it (a view option or a
    /// parameter), if `key` names one.
    pub fn setting_text(&self, key: &str) -> Option<String> {
        self.settings
            .view
            .get(key)
            .or_else(|| keys::get(&self.settings.params, key).map(|x| link::value_text(&x)))
    }

    /// The warning when the state leaves the model's validity (teeth that
    /// deflect by millimetres: [`crate::validity`]), if it does.
    pub fn validity_warning(&self) -> Option<String> {
        let model = self.model.as_ref().ok()?;
        let peak = self
            .main
            .omega
            .as_ref()
            .map(|r| (r.omega, crate::validity::peak_deflection_um(&r.anim)));
        crate::validity::warning(crate::validity::static_deflection_um(model), peak)
    }

    /// The mesh names of the current model.
    pub fn mesh_names(&self) -> Vec<String> {
        mesh_names(&self.settings.params)
    }

    /// Adds a message for the user (once; the last 12 are kept).
    pub fn issue(&mut self, message: String) {
        if !self.issues.contains(&message) {
            self.issues.push(message);
            if self.issues.len() > 12 {
                self.issues.remove(0);
            }
        }
        self.dirty.messages = true;
    }

    /// Takes back a message (a refused value the user has since changed).
    pub fn withdraw(&mut self, message: &str) {
        let before = self.issues.len();
        self.issues.retain(|i| i != message);
        self.dirty.messages |= self.issues.len() != before;
    }

    /// Clears the messages.
    pub fn clear_issues(&mut self) {
        self.issues.clear();
        self.dirty.messages = true;
    }

    /// Sets a control's key from its text. Out-of-range or impossible values
    /// are refused with a message naming the key and its allowed range.
    pub fn set_key(
        &mut self,
        key: &str,
        text: &str,
        now_ms: f64,
    ) -> Result<Vec<Effect>, InputError> {
        if let Some(row) = view_key(key) {
            let before = self.settings.view.clone();
            let meshes = self.mesh_names();
            self.settings
                .view
                .set(key, text, &meshes)
                .map_err(|_| InputError::refused(key, text))?;
            if key == "map_key" && self.settings.view.map_key != before.map_key {
                // A new axis gets that key's own default range.
                let (lo, hi) = figures::settings::map_default_range(&self.settings.view.map_key);
                self.settings.view.map_from = lo;
                self.settings.view.map_to = hi;
                self.dirty.controls = true;
            }
            if let Some(msg) = self.settings.view.check_range() {
                self.settings.view = before;
                return Err(InputError::RangeReset(msg));
            }
            if key == "mesh" && self.panels.take().is_some() {
                // Choosing a mesh shows that mesh alone.
                self.dirty.url = true;
            }
            // The sweeps' views share the mesh and the range: they are
            // redrawn even without new data; the axes of x are every view's.
            self.dirty.data(KindSet::ALL.without(KindSet::SELECTED));
            if key == "clearance" || key == "axis" {
                self.dirty.data(KindSet::SELECTED);
                self.dirty.controls |= key == "axis";
            }
            self.dirty.url = true;
            return Ok(self.restart(row.restarts, now_ms));
        }
        // The message in a sentence with the allowed range ("Backlash b must be
        // between 0 and 1000 µm"), not the CLI's key syntax.
        let plain = |_| InputError::refused(key, text);
        let value = keys::parse_value(key, text).map_err(plain)?;
        let mut params = self.settings.params.clone();
        keys::set(&mut params, key, value).map_err(plain)?;
        if params == self.settings.params {
            return Ok(Vec::new());
        }
        let model = Model::new(&params)?;
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
        // Every control shows the state after the change: a shortcut
        // (backlash on all meshes) sets the per-mesh-kind fields, and a
        // per-kind value makes the shortcut's field read "mixed".
        self.dirty.controls = true;
        self.preset_note = None;
        Ok(self.restart(KindSet::ALL, now_ms))
    }

    /// Moves the selected Omega (clicks and drags on the Omega axes).
    pub fn select_omega(&mut self, omega: f64, now_ms: f64) -> Vec<Effect> {
        let omega = self.rounded_selection(omega);
        let text = figures::settings::fmt_exact(omega);
        match self.set_key("omega", &text, now_ms) {
            Ok(fx) => {
                self.dirty.controls = true;
                fx
            }
            Err(e) => {
                self.issue(e.to_string());
                Vec::new()
            }
        }
    }

    /// Replaces the whole state by a link's (or preset's) query.
    pub fn load_query(&mut self, query: &str, now_ms: f64) -> Vec<Effect> {
        let tour_issue = crate::tour::tour_issue(query);
        let (tour, query) = crate::tour::split_tour(query);
        self.tour = tour;
        let d = link::decode(&query);
        self.settings = d.settings;
        self.issues = d.issues;
        self.issues.extend(tour_issue);
        self.preset_note = None;
        self.rebuild_model();
        self.main.hbm_previous = None;
        let mut fx = self.clear_a(now_ms);
        fx.extend(self.clear_family(now_ms));
        self.family = d.family.map(|spec| Family {
            spec,
            members: Vec::new(),
        });
        self.panels = d.panels;
        if let Some(a) = d.pinned {
            fx.extend(self.start_pinned(a, now_ms));
        }
        self.dirty = Dirty::all();
        fx.extend(self.restart(KindSet::ALL, now_ms));
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
    ) -> Result<Vec<Effect>, InputError> {
        let grid = self
            .main
            .map
            .grid
            .clone()
            .unwrap_or_else(|| self.map_grid());
        let (row, column) = grid.cell_at(omega, value).ok_or(InputError::OutsideMap)?;
        let v = (grid.value(row) * 1e3).round() / 1e3;
        let mut fx = self.set_key(&grid.key, &figures::settings::fmt_exact(v), now_ms)?;
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
        let (boundaries, disagree, _) = self.map_boundaries();
        let picked = self.picked_boundary.as_ref().map(|p| (p.curve, p.at));
        MapView {
            store: &self.main.map,
            mesh_label: match &self.settings.view.mesh {
                MeshSel::Named(n) => format!("mesh {n}"),
                MeshSel::Worst => "worst mesh".into(),
            },
            selected: (self.settings.view.omega, value),
            boundaries,
            cusps: self.main.boundaries.cusps.clone(),
            disagree,
            picked,
            speed: self.speed_axis(),
        }
    }

    /// The boundaries the map shows, and the cells that disagree with
    /// them with how many cells were judged.
    fn map_boundaries(
        &self,
    ) -> (
        Vec<&figures::protocol::BoundaryCurve>,
        Vec<(u32, u32)>,
        usize,
    ) {
        let mesh = self
            .model
            .as_ref()
            .ok()
            .and_then(|m| self.settings.mesh_index(m));
        let shown = self.main.boundaries.shown(mesh);
        let (disagree, judged) = match &self.main.map.grid {
            Some(g) if !shown.is_empty() => {
                figures::views::boundaries::disagreements(g, &self.main.map, &shown)
            }
            _ => (Vec::new(), 0),
        };
        (shown, disagree, judged)
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
                .map(|x| figures::settings::fmt_exact(*x))
                .collect();
            query.push_str(&format!("&family={}:{}", f.key, v.join(",")));
        }
        if let Some(m) = p.meshes.filter(|m| m.len() > 1) {
            query.push_str(&format!("&{}={}", figures::panels::PANELS_KEY, m.join(",")));
        }
        // The speed axes are how the reader reads, not the figure: kept.
        let axis = self.settings.view.axis;
        let fx = self.load_query(&query, now_ms);
        self.settings.view.axis = axis;
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
                MeshSel::Worst => "worst mesh".into(),
            },
            natural: self
                .model
                .as_ref()
                .map(|m| natural_in_range(m, v.omega_from, v.omega_to))
                .unwrap_or_default(),
            speed: self.speed_axis(),
        }
    }

    fn mesh_and_backlash(&self) -> (Option<usize>, Vec<f64>) {
        match &self.model {
            Ok(m) => (
                self.settings.mesh_index(m),
                m.system.meshes.iter().map(|x| um(x.backlash_m)).collect(),
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
        let main = &self.main;
        let previous = main.hbm_previous.as_ref().filter(|_| !main.hbm.finished);
        // The time-integration dots: the overlay job's when it is on, else
        // the bifurcation sweep's steady states (the same computation, free).
        let swept;
        let overlay = if self.settings.view.overlay_on() {
            Some(&main.overlay)
        } else {
            let v = &self.settings.view;
            swept = FrStore::from_sweep(&main.bif.samples, v.transient_periods, v.record_periods);
            Some(&swept).filter(|s| !s.points.is_empty())
        };
        let previous = previous.filter(|_| self.family.is_none());
        let mut v = fr_view(&main.hbm, previous, overlay, mesh, &b, &ctx);
        v.whole_clearance = self.settings.view.whole_clearance;
        v.selected_motion = main
            .omega
            .as_ref()
            .filter(|r| !r.preview && (r.omega - ctx.selected_omega).abs() < 1e-12)
            .map(|r| r.motion);
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
                let partial = if main.hbm.error.is_some() {
                    "; partial"
                } else {
                    ""
                };
                br.label = format!("{}{partial}", f.spec.label(0));
                br.member = Some(0);
            }
            for (i, m) in f.members.iter().enumerate() {
                let partial = if m.comp.hbm.error.is_some() {
                    "; partial"
                } else {
                    ""
                };
                // Each member's bifurcations sit on its own curve.
                let (points, markers) = m.comp.hbm.curve(mesh);
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
            let partial = if p.comp.hbm.error.is_some() {
                "; partial"
            } else {
                ""
            };
            v.pinned_backlash_um = distinct(&pinned_backlash(&p.settings), mesh);
            v.branches.insert(
                0,
                FrBranch {
                    label: format!("A: {ta}{partial}"),
                    points: p.comp.hbm.curve(mesh).0,
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

    /// The bifurcation view.
    pub fn bif_view(&self) -> BifView {
        let (mesh, b) = self.mesh_and_backlash();
        let ctx = self.view_context();
        let mut v = self.main.bif.view(mesh, &b, &ctx);
        v.whole_clearance = self.settings.view.whole_clearance;
        v.unstable_bands = self.instability_bands();
        // The shooting branches, on a named mesh (a "worst" diagram takes
        // each point's own mesh; a branch has no one mesh to follow).
        if let Some(j) = mesh {
            v.branches = self.main.orbits.lines(j);
            v.branch_markers = self.main.orbits.markers(j);
        }
        if let Some(p) = &self.pinned {
            v.pinned = p.comp.bif.view(mesh, &b, &ctx).points;
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
        self.main.bands.clone()
    }

    /// Everything the tests and the benchmark read.
    pub fn status(&self, now_ms: f64) -> serde_json::Value {
        let fr = self.fr_view();
        let main = &self.main;
        // What the bifurcation diagram draws of the shooting branches.
        let bif_branches = {
            let v = self.bif_view();
            let periods: std::collections::BTreeSet<u32> =
                v.branches.iter().map(|l| l.period).collect();
            serde_json::json!({
                "points": main.orbits.points.len(),
                "stable_lines": v.branches.iter().filter(|l| l.stable).count(),
                "unstable_lines": v.branches.iter().filter(|l| !l.stable).count(),
                "periods": periods,
                "markers": v.branch_markers.iter().map(|m| m.kind.label()).collect::<Vec<_>>(),
            })
        };
        let mut out = serde_json::json!({
            "query": self.query(),
            "issues": self.issues,
            "omega": self.settings.view.omega,
            "fr_method": self.fr_method(),
            "fr_branch_points": main.hbm.points.len(),
            "fr_partial": main.hbm.error,
            "fr_discrepancy": fr.discrepancy,
            // The frequency response's time-integration dots and the
            // sentence under it where the branch is unstable.
            "fr_dots": fr.overlay.len(),
            "fr_sentence": figures::views::unstable::unstable_sentence(&fr),
            "bif_bands": self.instability_bands(),
            "map_grid": main.map.grid,
            "map_counts": main.map.counts(),
            "lyap_points": main.lyap.curve().len(),
            "pinned": self.pinned.as_ref().map(|p| {
                let mut a = serde_json::json!({
                    "query": link::encode(&p.settings),
                    "fr_branch_points": p.comp.hbm.points.len(),
                    "bif_points": p.comp.bif.samples.len(),
                });
                kinds::put_statuses(&mut a, &p.comp, KindSet::PINNED, None);
                a
            }),
            "ab_labels": self.ab_labels(),
            "family": self.family_status(),
            "fr_panels": self.panels,
            "fr_first_mode_peaks": self.first_mode_peaks(&fr),
            "workers_ready": self.workers.iter().filter(|w| w.ready).count(),
            "workers": self.workers.len(),
            "omega_result": main.omega.as_ref().map(|r| serde_json::json!({
                "omega": r.omega, "mesh": r.mesh_name, "impact": r.regime.solver_name(),
                "period": r.period, "preview": r.preview,
                "motion": figures::story::motion_tag(r.motion),
            })),
        });
        if let Some(o) = out.as_object_mut() {
            o.insert("bif_branches".into(), bif_branches);
            o.insert("map_boundaries".into(), self.boundaries_status());
        }
        kinds::put_statuses(&mut out, main, KindSet::ALL, Some(now_ms));
        out
    }

    /// What a link restores.
    pub fn settings(&self) -> &Settings {
        &self.settings
    }

    /// The model of the current parameters, or why it cannot be built.
    pub fn model(&self) -> Result<&Model, &solver::SolverError> {
        self.model.as_ref()
    }

    /// The current state's results.
    pub fn main(&self) -> &Computation {
        &self.main
    }

    /// The pinned state A, if comparing.
    pub fn pinned(&self) -> Option<&Pinned> {
        self.pinned.as_ref()
    }

    /// The family shown, if any.
    pub fn family(&self) -> Option<&Family> {
        self.family.as_ref()
    }

    /// The frequency response's mesh panels, if shown.
    pub fn panels(&self) -> Option<&[String]> {
        self.panels.as_deref()
    }

    /// The note of the preset last loaded.
    pub fn preset_note(&self) -> Option<&str> {
        self.preset_note.as_deref()
    }

    /// The tour's step (0-based), if it is running.
    pub fn tour(&self) -> Option<usize> {
        self.tour
    }

    /// What changed since the last call: the page draws it.
    pub fn take_dirty(&mut self) -> Dirty {
        std::mem::take(&mut self.dirty)
    }

    /// Whether the messages changed since the last call.
    pub fn take_messages_dirty(&mut self) -> bool {
        std::mem::take(&mut self.dirty.messages)
    }

    /// Marks the messages and the controls to be shown again (the page's
    /// own change to them, e.g. a refused value).
    pub fn touch(&mut self, controls: bool) {
        self.dirty.messages = true;
        self.dirty.controls |= controls;
    }
}

mod boundaries;
pub(crate) mod campbell;
mod dynamic;
mod error;
mod excitation;
mod export;
mod orders;
mod speed;
mod text;
pub use export::{ExportError, Format};
mod members;
pub use members::{Family, Member};
mod jobs;
mod panels;
use pinned::pinned_backlash;
mod messages;
mod pinned;
pub use export::{view_size, Drawn, SvgError};

pub use pinned::Pinned;

#[cfg(test)]
mod members_tests;
#[cfg(test)]
mod tests;
