//! Starting the page's jobs: one path for every [`Target`] (the current
//! state, the pinned A, a family member) and every [`JobKind`]: a kind's
//! store started in the target's [`Computation`], its job's shards posted
//! to the workers.

use super::*;
use figures::views::boundaries::{BoundaryStore, BOUNDARY_LEVELS, BOUNDARY_POINTS};
use worker::jobs::omega::{selected_spec, OmegaJob, PREVIEW_RUN};

/// A job's parameters as the worker messages carry them.
pub(super) type Params = serde_json::Map<String, serde_json::Value>;

/// The kinds the pinned A computes (drawn under the current state's).
pub(super) const PINNED_KINDS: KindSet = KindSet::of(&[JobKind::HarmonicBalance, JobKind::Bif]);
/// The kinds a family member computes (its curve, its panel, its orbit).
pub(super) const MEMBER_KINDS: KindSet =
    KindSet::of(&[JobKind::Omega, JobKind::HarmonicBalance, JobKind::Bif]);

/// Steady states in a bifurcation sweep of view settings `v` (both
/// directions count twice).
pub(super) fn bif_total(v: &figures::settings::ViewOptions) -> usize {
    let per_dir = if v.bif_dir == solver::sweep::Directions::Both {
        2
    } else {
        1
    };
    v.bif_points as usize * per_dir
}

/// What a target computes with: its settings (a member's are the current
/// view with its own parameters) and its model.
pub(super) struct Inputs {
    pub(super) settings: Settings,
    pub(super) model: Model,
    pub(super) params: Params,
}

impl Controller {
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

    /// The worker that runs the current state's harmonic-balance branch: the last.
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

    /// The worker of `target`'s job of `kind`, shard `shard`: the
    /// selected-Omega runs and the branches spread over the pool by target,
    /// the chains round robin. The map's boundaries go to the last worker,
    /// the shooting branches (one job, shard 0) to the first: the two long
    /// jobs run side by side on a pool of two or more. On one worker the
    /// boundaries, served after the branches, waited for all of them: with
    /// the compound set's default map the page's trace had not begun after
    /// 13 minutes, while alone it takes about a minute.
    fn worker_of(&self, target: Target, kind: JobKind, shard: u32) -> usize {
        let pool = self.workers.len();
        match (kind, target) {
            (JobKind::Boundaries, _) => pool - 1,
            (JobKind::HarmonicBalance, Target::Main) => self.hbm_worker(),
            (JobKind::HarmonicBalance, Target::A) => self.pinned_hbm_worker(),
            (JobKind::HarmonicBalance, Target::Member(m)) => {
                (self.hbm_worker() + m as usize) % pool
            }
            (JobKind::Omega, Target::Member(m)) => m as usize % pool,
            _ => self.shard_worker(shard),
        }
    }

    /// How many of `chains` chains worker `worker` holds.
    pub(super) fn chains_on(&self, worker: usize, chains: u32) -> usize {
        (0..chains)
            .filter(|&c| self.shard_worker(c) == worker)
            .count()
    }

    /// The next job id (unique across every computation).
    pub(super) fn next_job(&mut self) -> JobId {
        self.next_id += 1;
        self.next_id
    }

    /// The computation of `target`, if it exists.
    pub(super) fn computation_mut(&mut self, target: Target) -> Option<&mut Computation> {
        match target {
            Target::Main => Some(&mut self.main),
            Target::A => self.pinned.as_mut().map(|p| &mut p.comp),
            Target::Member(m) => self
                .family
                .as_mut()
                .and_then(|f| f.members.get_mut((m as usize).checked_sub(1)?))
                .map(|m| &mut m.comp),
        }
    }

    /// The computation of `target`, if it exists.
    pub fn computation(&self, target: Target) -> Option<&Computation> {
        match target {
            Target::Main => Some(&self.main),
            Target::A => self.pinned.as_ref().map(|p| &p.comp),
            Target::Member(m) => self
                .family
                .as_ref()
                .and_then(|f| f.members.get((m as usize).checked_sub(1)?))
                .map(|m| &m.comp),
        }
    }

    /// Every computation and its target: the current state, A, the members.
    pub(super) fn targets(&self) -> Vec<Target> {
        let mut t = vec![Target::Main];
        if self.pinned.is_some() {
            t.push(Target::A);
        }
        if let Some(f) = &self.family {
            t.extend((1..=f.members.len() as u32).map(Target::Member));
        }
        t
    }

    /// Cancels `target`'s jobs of `kind` (`None`: all) on every worker.
    pub(super) fn cancel(&mut self, target: Target, kind: Option<JobKind>) -> Vec<Effect> {
        (0..self.workers.len())
            .flat_map(|w| self.post(w, &ToWorker::Cancel { target, kind }))
            .collect()
    }

    /// Posts the job of each of `chains` shards (`job(shard)`) of `target`.
    fn post_shards(
        &mut self,
        (target, id, params): (Target, JobId, &Params),
        chains: u32,
        job: impl Fn(u32) -> JobSpec,
    ) -> Vec<Effect> {
        let mut fx = Vec::new();
        for shard in 0..chains {
            let job = job(shard);
            let worker = self.worker_of(target, job.kind(), shard);
            let msg = ToWorker::Run {
                target,
                id,
                params: params.clone(),
                job,
            };
            fx.extend(self.post(worker, &msg));
        }
        fx
    }

    /// The inputs of `target`'s jobs, or why it has none (its model
    /// cannot be built).
    pub(super) fn inputs(&self, target: Target) -> Result<Inputs, String> {
        let settings = match target {
            Target::Main => {
                let model = self.model.clone()?;
                let params = keys::to_json(&self.settings.params);
                return Ok(Inputs {
                    settings: self.settings.clone(),
                    model,
                    params,
                });
            }
            Target::A => self.pinned.as_ref().map(|p| p.settings.clone()),
            Target::Member(m) => {
                let member = self
                    .family
                    .as_ref()
                    .and_then(|f| f.members.get((m as usize).checked_sub(1)?));
                match member.map(|m| m.params.clone()) {
                    Some(Ok(params)) => Some(Settings {
                        params,
                        view: self.settings.view.clone(),
                    }),
                    Some(Err(e)) => return Err(e),
                    None => None,
                }
            }
        }
        .ok_or_else(|| "no such computation".to_string())?;
        let model = Model::new(&settings.params).map_err(|e| e.to_string())?;
        let params = keys::to_json(&settings.params);
        Ok(Inputs {
            settings,
            model,
            params,
        })
    }

    /// Restarts `target`'s jobs of `kinds`: each kind's store and status
    /// started afresh and its shards posted; a target whose model cannot
    /// be built says why on every one of those kinds.
    pub(super) fn start(&mut self, target: Target, kinds: KindSet, now_ms: f64) -> Vec<Effect> {
        let input = match self.inputs(target) {
            Ok(i) => i,
            Err(e) => {
                let kinds: Vec<JobKind> = kinds.iter().collect();
                if let Some(c) = self.computation_mut(target) {
                    c.fail_all(&kinds, &e);
                }
                return Vec::new();
            }
        };
        let mut fx = Vec::new();
        for kind in kinds.iter() {
            fx.extend(self.start_kind(target, kind, &input, now_ms));
        }
        fx
    }

    /// Starts `target`'s job of `kind` with `input`.
    fn start_kind(
        &mut self,
        target: Target,
        kind: JobKind,
        input: &Inputs,
        now_ms: f64,
    ) -> Vec<Effect> {
        let v = &input.settings.view;
        let main = target == Target::Main;
        // Everything the map depends on (it restarts only if that changed).
        let map_signature = match kind {
            JobKind::Map => self.map_signature(&input.model, &input.params),
            JobKind::Boundaries => self.boundaries_signature(&input.model, &input.params),
            _ => String::new(),
        };
        // The units of the job's progress, and its shards: `None` for a
        // kind switched off (its running job dropped).
        let shards = match kind {
            JobKind::Omega | JobKind::HarmonicBalance => Some(1),
            JobKind::Overlay => (v.fr_ti_points > 0).then(|| chain_count(v.fr_ti_points)),
            JobKind::Bif => Some(chain_count(v.bif_points)),
            JobKind::Map => {
                let st = self.main.status(JobKind::Map);
                if map_signature == self.main.map.signature && st.error.is_none() {
                    // What the map depends on did not change.
                    return Vec::new();
                }
                Some((self.workers.len() as u32).min(v.map_value_points))
            }
            JobKind::Lyap => (v.lyap_points >= 2).then(|| chain_count(v.lyap_points)),
            // One continuation, on one worker.
            JobKind::Orbits => v.branches.then_some(1),
            JobKind::Boundaries => {
                let st = self.main.status(JobKind::Boundaries);
                if v.boundaries
                    && map_signature == self.main.boundaries.signature
                    && st.error.is_none()
                {
                    // What the curves depend on did not change (a click
                    // on the map sets the key they vary).
                    return Vec::new();
                }
                v.boundaries.then_some(1)
            }
        };
        let Some(chains) = shards else {
            return self.switch_off(target, kind);
        };
        let total = match kind {
            JobKind::Omega => 1,
            JobKind::HarmonicBalance => 100,
            JobKind::Overlay => v.fr_ti_points as usize,
            JobKind::Bif => bif_total(v),
            JobKind::Map => self.map_grid().cells(),
            JobKind::Lyap => v.lyap_points as usize,
            JobKind::Orbits => worker::jobs::orbits::MAX_ORBIT_POINTS,
            // Per mille.
            JobKind::Boundaries => 1000,
        };
        let id = self.next_job();
        let grid = self.map_grid();
        let linear = input.model.is_linear();
        let Some(c) = self.computation_mut(target) else {
            return Vec::new();
        };
        let issued = std::mem::take(&mut c.status_mut(kind).issued);
        *c.status_mut(kind) = JobStatus::start(id, now_ms, total);
        match kind {
            // The current state keeps its last result on screen until the
            // new one (or its preview) arrives; a member's panel waits.
            JobKind::Omega if !main => c.omega = None,
            JobKind::Omega => {}
            JobKind::HarmonicBalance => {
                // Keep the last complete branch (not a half-computed one)
                // to fade under the new one while it computes.
                if main && c.hbm.is_complete() {
                    c.hbm_previous = Some(std::mem::take(&mut c.hbm));
                }
                c.hbm = HbmStore::new(id, v.harmonics);
            }
            JobKind::Overlay => {
                c.overlay =
                    FrStore::new(id, v.fr_ti_points, v.transient_periods, v.fr_record_periods)
            }
            JobKind::Bif => c.bif = BifStore::new(id, total),
            JobKind::Map => c.map = MapStore::new(id, grid.clone(), map_signature),
            JobKind::Lyap => {
                c.lyap = LyapStore::new(id, total, v.lyap_periods);
                c.lyap.linear = linear;
            }
            JobKind::Orbits => c.orbits = OrbitStore::new(id),
            JobKind::Boundaries => c.boundaries = BoundaryStore::new(id, map_signature),
        }
        // The replaced job's messages spoke of the state before.
        for message in &issued {
            self.withdraw(message);
        }
        if main {
            self.dirty.data(kind);
            if kind == JobKind::Bif {
                self.export = None;
                // The sweep's steady states are also the frequency response's dots.
                self.dirty.data(JobKind::Overlay);
            }
        }
        let run = |record_periods| RunOptions {
            transient_periods: v.transient_periods,
            record_periods,
        };
        let mesh = input.settings.mesh_index(&input.model);
        let fx = self.post_shards((target, id, &input.params), chains, |shard| match kind {
            JobKind::Omega => JobSpec::Omega(selected_spec(
                &input.settings,
                &input.model,
                run(v.record_periods),
            )),
            JobKind::HarmonicBalance => JobSpec::HarmonicBalance {
                omega_from: v.omega_from,
                omega_to: v.omega_to,
                points: v.fr_points,
                harmonics: v.harmonics,
                stability: true,
            },
            JobKind::Overlay => JobSpec::Overlay {
                omega_from: v.omega_from,
                omega_to: v.omega_to,
                points: v.fr_ti_points,
                chains,
                shard,
                run: run(v.fr_record_periods),
            },
            JobKind::Bif => JobSpec::Bif {
                omega_from: v.omega_from,
                omega_to: v.omega_to,
                points: v.bif_points,
                directions: v.bif_dir.name().to_string(),
                chains,
                shard,
                run: run(v.record_periods),
            },
            JobKind::Map => JobSpec::Map {
                key: grid.key.clone(),
                omega_from: grid.omega_from,
                omega_to: grid.omega_to,
                omega_points: grid.omega_points,
                value_from: grid.value_from,
                value_to: grid.value_to,
                value_points: grid.value_points,
                mesh,
                shards: chains,
                shard,
                run: RunOptions {
                    transient_periods: v.map_transient_periods,
                    record_periods: v.map_record_periods,
                },
            },
            JobKind::Lyap => JobSpec::Lyap {
                omega_from: v.omega_from,
                omega_to: v.omega_to,
                points: v.lyap_points,
                chains,
                shard,
                transient_periods: v.lyap_transient_periods,
                periods: v.lyap_periods,
            },
            JobKind::Orbits => JobSpec::Orbits {
                omega_from: v.omega_from,
                omega_to: v.omega_to,
                points: v.bif_points,
            },
            JobKind::Boundaries => JobSpec::Boundaries {
                key: grid.key.clone(),
                omega_from: grid.omega_from,
                omega_to: grid.omega_to,
                value_from: grid.value_from,
                value_to: grid.value_to,
                levels: BOUNDARY_LEVELS,
                points: BOUNDARY_POINTS,
                harmonics: v.harmonics as usize,
                contact_mesh: mesh,
            },
        });
        if main && kind == JobKind::Omega {
            self.preview_omega(&input.model, id, now_ms);
        }
        fx
    }

    /// A kind switched off (no overlay, no Lyapunov curve): its store and
    /// status cleared, its running job dropped.
    fn switch_off(&mut self, target: Target, kind: JobKind) -> Vec<Effect> {
        let Some(c) = self.computation_mut(target) else {
            return Vec::new();
        };
        let running = c.status(kind).id != 0;
        let issued = std::mem::take(&mut c.status_mut(kind).issued);
        *c.status_mut(kind) = JobStatus::default();
        match kind {
            JobKind::Overlay => c.overlay = FrStore::default(),
            JobKind::Lyap => c.lyap = LyapStore::default(),
            JobKind::Orbits => c.orbits = OrbitStore::default(),
            JobKind::Boundaries => c.boundaries = BoundaryStore::default(),
            _ => {}
        }
        for message in &issued {
            self.withdraw(message);
        }
        self.dirty.data(kind);
        if running {
            self.cancel(target, Some(kind))
        } else {
            Vec::new()
        }
    }

    /// Restarts the jobs of `kinds`, kind by kind, for the current state
    /// and the family members (A keeps its own settings).
    pub(super) fn restart(&mut self, kinds: KindSet, now_ms: f64) -> Vec<Effect> {
        let mut fx = Vec::new();
        if let Err(e) = &self.model {
            // No jobs on an invalid model: say why on every view.
            let e = e.clone();
            let all: Vec<JobKind> = kinds.iter().collect();
            self.main.fail_all(&all, &e);
            for kind in JobKind::ALL {
                fx.extend(self.cancel(Target::Main, Some(kind)));
            }
            self.main.map.signature.clear();
            fx.extend(self.cancel_members());
            self.dirty.data(KindSet::ALL);
            return fx;
        }
        fx.extend(self.start(Target::Main, kinds, now_ms));
        fx.extend(self.restart_members(kinds, now_ms));
        self.dirty.url = true;
        fx
    }

    /// Shows a preview of the selected-Omega views at once: a short bounded
    /// run ([`PREVIEW_RUN`]) continued from the last result's end state
    /// under the new settings. The worker's full steady state replaces it;
    /// without a previous state, or if the run fails or exceeds its step
    /// budget, the views keep the last result until then.
    fn preview_omega(&mut self, model: &Model, id: JobId, now_ms: f64) {
        let Some(start) = self
            .main
            .omega
            .as_ref()
            .map(|r| r.end_state.clone())
            .filter(|y| y.len() == 2 * model.system.dof())
        else {
            return;
        };
        let job = OmegaJob {
            id,
            model: model.clone(),
            spec: selected_spec(&self.settings, model, PREVIEW_RUN),
        };
        if let Ok(r) = worker::jobs::omega::omega_result(&job, Some(&start)) {
            self.main.omega = Some(r);
            self.main.status_mut(JobKind::Omega).preview_ms = Some(now_ms);
        }
    }

    /// The map's grid from the view options.
    pub fn map_grid(&self) -> MapGrid {
        MapGrid::of(&self.settings.view)
    }

    /// Everything the map depends on, as text: its grid, periods and mesh,
    /// and the parameters with the rows' key neutralised (the rows set it),
    /// so a click on a cell, which sets that key, does not restart the map.
    pub(super) fn map_signature(&self, model: &Model, params: &Params) -> String {
        let v = &self.settings.view;
        let params_text = self.params_but_map_key(params);
        format!(
            "{:?}|{}|{}|{:?}|{params_text}",
            self.map_grid(),
            v.map_transient_periods,
            v.map_record_periods,
            self.settings.mesh_index(model),
        )
    }

    /// The parameters as JSON text with the map's key set to 0 (the map
    /// and its boundaries vary it themselves).
    fn params_but_map_key(&self, params: &Params) -> String {
        let mut p = self.settings.params.clone();
        let neutral = keys::set(&mut p, &self.settings.view.map_key, keys::Value::Num(0.0)).is_ok();
        if neutral {
            serde_json::Value::Object(keys::to_json(&p)).to_string()
        } else {
            serde_json::Value::Object(params.clone()).to_string()
        }
    }

    /// Everything the map's boundaries depend on (they restart only if
    /// that changed): the box, the harmonics and the parameters but the
    /// map's key.
    pub(super) fn boundaries_signature(&self, model: &Model, params: &Params) -> String {
        let g = self.map_grid();
        format!(
            "{}|{}|{}|{}|{}|{}|{:?}|{}",
            g.key,
            g.omega_from,
            g.omega_to,
            g.value_from,
            g.value_to,
            self.settings.view.harmonics,
            // The map's mesh: the job traces its contact boundaries only.
            self.settings.mesh_index(model),
            self.params_but_map_key(params)
        )
    }
}
