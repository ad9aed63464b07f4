//! Starting the page's jobs: which change restarts what, and the job
//! messages posted to the workers (a kind's shards spread over them).

use super::*;

/// Steady states in a bifurcation sweep of view settings `v` (both
/// directions count twice).
pub(super) fn bif_total(v: &crate::settings::ViewOptions) -> usize {
    let per_dir = if v.bif_dir == solver::sweep::Directions::Both {
        2
    } else {
        1
    };
    v.bif_points as usize * per_dir
}

/// What a change restarts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Restart {
    /// The harmonic-balance branch.
    pub(super) fr: bool,
    /// The time-integration overlay.
    pub(super) ti: bool,
    pub(super) bif: bool,
    pub(super) omega: bool,
    /// The map (only if what it depends on changed).
    pub(super) map: bool,
    pub(super) lyap: bool,
}

impl Restart {
    /// The kinds to restart, in the order they start (the selected Omega
    /// first: its worker serves it first).
    fn kinds(self) -> impl Iterator<Item = JobKind> {
        let on = [self.omega, self.fr, self.ti, self.bif, self.map, self.lyap];
        JobKind::ALL
            .into_iter()
            .zip(on)
            .filter(|(_, on)| *on)
            .map(|(k, _)| k)
    }
}

/// A job's parameters as the worker messages carry them.
pub(super) type Params = serde_json::Map<String, serde_json::Value>;

pub(super) const ALL: Restart = Restart {
    fr: true,
    ti: true,
    bif: true,
    omega: true,
    map: true,
    lyap: true,
};

pub(super) const NONE: Restart = Restart {
    fr: false,
    ti: false,
    bif: false,
    omega: false,
    map: false,
    lyap: false,
};

/// The harmonic-balance job of a view's settings (the current state's and
/// the pinned A state's alike).
pub(super) fn hbm_job(v: &crate::settings::ViewOptions) -> JobSpec {
    JobSpec::Hbm {
        omega_from: v.omega_from,
        omega_to: v.omega_to,
        points: v.fr_points,
        harmonics: v.harmonics,
        stability: true,
    }
}

/// Chain `shard` of the `chains` of a bifurcation sweep of view settings
/// `v` (the current state's, A's and a family member's alike).
pub(super) fn bif_job(v: &crate::settings::ViewOptions, chains: u32, shard: u32) -> JobSpec {
    JobSpec::Bif {
        omega_from: v.omega_from,
        omega_to: v.omega_to,
        points: v.bif_points,
        directions: v.bif_dir.name().to_string(),
        chains,
        shard,
        run: RunOptions {
            transient_periods: v.transient_periods,
            record_periods: v.record_periods,
        },
    }
}

impl Controller {
    /// The selected-Omega job of the current settings on `model` (the
    /// current state's and a family member's alike).
    pub(super) fn omega_job(&self, model: &Model) -> JobSpec {
        let v = &self.settings.view;
        JobSpec::Omega {
            omega: v.omega,
            mesh: self.settings.mesh_index(model),
            run: self.run_options(v.record_periods),
            samples_per_period: SAMPLES_PER_PERIOD,
            max_order: MAX_ORDER,
        }
    }

    pub(super) fn post(&mut self, worker: usize, msg: &ToWorker) -> Vec<Effect> {
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

    /// Workers in the pool.
    pub fn workers(&self) -> usize {
        self.workers.len()
    }

    /// The worker that runs the harmonic-balance branch: the last.
    pub fn hbm_worker(&self) -> usize {
        self.workers.len() - 1
    }

    /// The worker that runs A's harmonic-balance branch: the one before the
    /// last when the pool has more than two (so both branches compute at
    /// once), else the last.
    pub fn pinned_hbm_worker(&self) -> usize {
        let n = self.workers.len();
        if n > 2 {
            n - 2
        } else {
            n - 1
        }
    }

    /// The worker of chain (or share) `shard`: chains are dealt round robin.
    pub fn shard_worker(&self, shard: u32) -> usize {
        shard as usize % self.workers.len()
    }

    /// How many of `chains` chains worker `worker` holds.
    pub(super) fn chains_on(&self, worker: usize, chains: u32) -> usize {
        (0..chains)
            .filter(|&c| self.shard_worker(c) == worker)
            .count()
    }

    pub(super) fn run_options(&self, record: u32) -> RunOptions {
        RunOptions {
            transient_periods: self.settings.view.transient_periods,
            record_periods: record,
        }
    }

    /// Shows a preview of the selected-Omega views at once: a short bounded
    /// run ([`crate::jobs::omega::PREVIEW_RUN`]) continued from the last result's
    /// end state under the new settings. The worker's full steady state
    /// replaces it; without a previous state, or if the run fails or
    /// exceeds its step budget, the views keep the last result until then.
    pub(super) fn preview_omega(&mut self, model: &Model, id: JobId, now_ms: f64) {
        let Some(start) = self
            .omega
            .as_ref()
            .map(|r| r.end_state.clone())
            .filter(|y| y.len() == 2 * model.system.dof())
        else {
            return;
        };
        let v = &self.settings.view;
        let job = crate::jobs::omega::OmegaJob {
            id,
            model: model.clone(),
            omega: v.omega,
            mesh: self.settings.mesh_index(model),
            run: crate::jobs::omega::PREVIEW_RUN,
            samples_per_period: SAMPLES_PER_PERIOD,
            max_order: MAX_ORDER,
        };
        if let Ok(r) = crate::jobs::omega::omega_result(&job, Some(&start)) {
            self.omega = Some(r);
            self.omega_status.preview_ms = Some(now_ms);
        }
    }

    /// The next job id.
    fn next_job(&mut self) -> JobId {
        self.next_id += 1;
        self.next_id
    }

    /// Posts the job of each of `chains` shards (`job(shard)`), dealt round
    /// robin over the workers, for the current state or (`pinned`) for A.
    pub(super) fn post_shards(
        &mut self,
        id: JobId,
        params: &Params,
        (chains, pinned): (u32, bool),
        job: impl Fn(u32) -> JobSpec,
    ) -> Vec<Effect> {
        let mut fx = Vec::new();
        for w in 0..chains {
            let (params, job) = (params.clone(), job(w));
            let msg = if pinned {
                ToWorker::RunPinned { id, params, job }
            } else {
                ToWorker::Run { id, params, job }
            };
            fx.extend(self.post(self.shard_worker(w), &msg));
        }
        fx
    }

    /// A new job of `kind` with `total` units: its id, its status started.
    fn begin(&mut self, kind: JobKind, total: usize, now_ms: f64) -> JobId {
        let id = self.next_job();
        *self.status_mut(kind) = JobStatus::start(id, now_ms, total);
        id
    }

    /// A kind switched off: its running job (if `running`) cancelled and
    /// its status cleared.
    fn switch_off(&mut self, kind: JobKind, running: bool) -> Vec<Effect> {
        *self.status_mut(kind) = JobStatus::default();
        if running {
            self.cancel(kind)
        } else {
            Vec::new()
        }
    }

    /// Cancels the jobs of `kind` on every worker.
    fn cancel(&mut self, kind: JobKind) -> Vec<Effect> {
        (0..self.workers.len())
            .flat_map(|w| self.post(w, &ToWorker::Cancel { kind }))
            .collect()
    }

    /// The status of the current job of `kind`.
    pub(super) fn status_mut(&mut self, kind: JobKind) -> &mut JobStatus {
        match kind {
            JobKind::Omega => &mut self.omega_status,
            JobKind::Hbm => &mut self.fr_status,
            JobKind::Fr => &mut self.ti_status,
            JobKind::Bif => &mut self.bif_status,
            JobKind::Map => &mut self.map_status,
            JobKind::Lyap => &mut self.lyap_status,
        }
    }

    /// Restarts the jobs `what` names, kind by kind.
    pub(super) fn restart(&mut self, what: Restart, now_ms: f64) -> Vec<Effect> {
        let mut fx = Vec::new();
        let model = match &self.model {
            Ok(m) => m.clone(),
            Err(e) => {
                // No jobs on an invalid model: say why on every view.
                let e = e.clone();
                for kind in what.kinds() {
                    self.status_mut(kind).error = Some(e.clone());
                }
                for kind in JobKind::ALL {
                    fx.extend(self.cancel(kind));
                }
                self.map.signature.clear();
                fx.extend(self.cancel_members(None));
                self.dirty.fr = true;
                self.dirty.bif = true;
                self.dirty.omega = true;
                self.dirty.map = true;
                self.dirty.lyap = true;
                return fx;
            }
        };
        let params = keys::to_json(&self.settings.params);
        for kind in what.kinds() {
            fx.extend(match kind {
                JobKind::Omega => self.start_omega(&model, &params, now_ms),
                JobKind::Hbm => self.start_hbm(&params, now_ms),
                JobKind::Fr => self.start_overlay(&params, now_ms),
                JobKind::Bif => self.start_bif(&params, now_ms),
                JobKind::Map => self.restart_map(&model, &params, now_ms),
                JobKind::Lyap => self.restart_lyap(&params, now_ms),
            });
        }
        fx.extend(self.restart_members(what, now_ms));
        self.dirty.url = true;
        fx
    }

    fn start_omega(&mut self, model: &Model, params: &Params, now_ms: f64) -> Vec<Effect> {
        let job = self.omega_job(model);
        let id = self.begin(JobKind::Omega, 1, now_ms);
        let fx = self.post_shards(id, params, (1, false), |_| job.clone());
        self.preview_omega(model, id, now_ms);
        self.dirty.omega = true;
        fx
    }

    fn start_hbm(&mut self, params: &Params, now_ms: f64) -> Vec<Effect> {
        let id = self.begin(JobKind::Hbm, 100, now_ms);
        // Keep the last complete branch (not a half-computed one) to fade
        // under the new one while it computes.
        if self.hbm.is_complete() {
            self.hbm_previous = Some(std::mem::take(&mut self.hbm));
        }
        self.hbm = HbmStore::new(id, self.settings.view.harmonics);
        let before = self.issues.len();
        self.issues.retain(|i| !i.starts_with(HBM_FAILURE));
        self.dirty.messages |= self.issues.len() != before;
        let job = hbm_job(&self.settings.view);
        self.dirty.fr = true;
        let msg = ToWorker::Run {
            id,
            params: params.clone(),
            job,
        };
        self.post(self.hbm_worker(), &msg)
    }

    fn start_overlay(&mut self, params: &Params, now_ms: f64) -> Vec<Effect> {
        let v = self.settings.view.clone();
        self.dirty.fr = true;
        if v.fr_ti_points == 0 {
            // Overlay off: drop a running overlay job, if there was one.
            let running = self.fr.id != 0;
            self.fr = FrStore::default();
            return self.switch_off(JobKind::Fr, running);
        }
        let n = v.fr_ti_points;
        let id = self.begin(JobKind::Fr, n as usize, now_ms);
        self.fr = FrStore::new(id, n, v.transient_periods, v.fr_record_periods);
        let chains = chain_count(n);
        let run = self.run_options(v.fr_record_periods);
        self.post_shards(id, params, (chains, false), |shard| JobSpec::Fr {
            omega_from: v.omega_from,
            omega_to: v.omega_to,
            points: n,
            chains,
            shard,
            run,
        })
    }

    fn start_bif(&mut self, params: &Params, now_ms: f64) -> Vec<Effect> {
        let v = self.settings.view.clone();
        let total = bif_total(&v);
        let id = self.begin(JobKind::Bif, total, now_ms);
        self.bif = BifStore::new(id, total);
        // The sweep's steady states are also the frequency response's dots.
        self.dirty.fr = true;
        self.export = None;
        self.dirty.bif = true;
        self.post_bif(id, params, &v, false)
    }

    /// Posts the shards of a bifurcation sweep of view settings `v`.
    pub(super) fn post_bif(
        &mut self,
        id: JobId,
        params: &Params,
        v: &crate::settings::ViewOptions,
        pinned: bool,
    ) -> Vec<Effect> {
        let chains = chain_count(v.bif_points);
        self.post_shards(id, params, (chains, pinned), |shard| {
            bif_job(v, chains, shard)
        })
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
    pub(super) fn map_signature(
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

    pub(super) fn restart_map(
        &mut self,
        model: &Model,
        params: &Params,
        now_ms: f64,
    ) -> Vec<Effect> {
        let signature = self.map_signature(model, params);
        if signature == self.map.signature && self.map_status.error.is_none() {
            return Vec::new();
        }
        let grid = self.map_grid();
        let id = self.begin(JobKind::Map, grid.cells(), now_ms);
        let v = &self.settings.view;
        let run = RunOptions {
            transient_periods: v.map_transient_periods,
            record_periods: v.map_record_periods,
        };
        // Rows are independent: every worker takes a share.
        let shards = (self.workers.len() as u32).min(grid.value_points);
        let mesh = self.settings.mesh_index(model);
        let fx = self.post_shards(id, params, (shards, false), |shard| JobSpec::Map {
            key: grid.key.clone(),
            omega_from: grid.omega_from,
            omega_to: grid.omega_to,
            omega_points: grid.omega_points,
            value_from: grid.value_from,
            value_to: grid.value_to,
            value_points: grid.value_points,
            mesh,
            shards,
            shard,
            run,
        });
        self.map = MapStore::new(id, grid, signature);
        self.dirty.map = true;
        fx
    }

    pub(super) fn restart_lyap(&mut self, params: &Params, now_ms: f64) -> Vec<Effect> {
        let v = self.settings.view.clone();
        self.dirty.lyap = true;
        if v.lyap_points < 2 {
            // The curve is off: drop a running job, if there was one.
            let running = self.lyap.id != 0;
            self.lyap = LyapStore::default();
            return self.switch_off(JobKind::Lyap, running);
        }
        let n = v.lyap_points;
        let id = self.begin(JobKind::Lyap, n as usize, now_ms);
        self.lyap = LyapStore::new(id, n as usize, v.lyap_periods);
        let chains = chain_count(n);
        self.post_shards(id, params, (chains, false), |shard| JobSpec::Lyap {
            omega_from: v.omega_from,
            omega_to: v.omega_to,
            points: n,
            chains,
            shard,
            transient_periods: v.lyap_transient_periods,
            periods: v.lyap_periods,
        })
    }
}
