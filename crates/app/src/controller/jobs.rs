//! Starting the page's jobs: one path for every [`Target`] (the current
//! state, the pinned A, a family member) and every [`JobKind`]: a kind's
//! store started in the target's [`Computation`], its job's shards posted
//! to the workers.

use super::*;
use crate::store::kinds::{self, Pool, StartCx};
use solver::SolverError;
use worker::jobs::omega::{selected_spec, OmegaJob, PREVIEW_RUN};

/// A job's parameters as the worker messages carry them.
pub(super) type Params = serde_json::Map<String, serde_json::Value>;

/// What a target computes with: its settings (a member's are the current
/// view with its own parameters) and its model.
pub(super) struct Inputs {
    pub(super) settings: Settings,
    pub(super) model: Model,
    pub(super) params: Params,
}

/// A message on its way to a worker, with the job it runs noted when it
/// is made: the page's start sorts the queued messages by it and dates
/// the jobs it releases, without decoding the JSON again.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Outgoing {
    /// The message's JSON text.
    pub(super) text: String,
    /// The job it runs, if it runs one (not a cancel or an export).
    pub(super) run: Option<RunOf>,
}

/// The job a [`ToWorker::Run`] message runs (one of its shards).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct RunOf {
    pub(super) target: Target,
    pub(super) kind: JobKind,
    pub(super) id: JobId,
}

impl Outgoing {
    pub(super) fn of(msg: &ToWorker) -> Self {
        let run = match msg {
            ToWorker::Run {
                target, id, job, ..
            } => Some(RunOf {
                target: *target,
                kind: job.kind(),
                id: *id,
            }),
            _ => None,
        };
        Outgoing {
            text: encode(msg),
            run,
        }
    }

    /// Whether it runs a job off the first screen ([`KindSet::FIRST_SCREEN`]):
    /// one the page's start holds.
    pub(super) fn off_screen(&self) -> bool {
        self.run
            .is_some_and(|r| !KindSet::FIRST_SCREEN.contains(r.kind))
    }
}

impl Controller {
    /// Posts `msg` to `worker` at `now_ms`, or queues it until the worker
    /// is ready; at the page's start, holds it if it runs a job off the
    /// first screen ([`Self::hold_off_screen`]).
    pub(super) fn post(&mut self, worker: usize, msg: &ToWorker, now_ms: f64) -> Vec<Effect> {
        let out = Outgoing::of(msg);
        let mut fx = Vec::new();
        if self.held.is_some() {
            if out.off_screen() {
                self.date_post(out.run, None);
                if let Some(held) = &mut self.held {
                    held.push((worker, out));
                }
                return fx;
            }
            // A cancel or an export speaks of the jobs held: they go first.
            if out.run.is_none() {
                fx = self.release(now_ms);
            }
        }
        fx.extend(self.post_out(worker, out));
        fx
    }

    /// Holds back the jobs off the first screen ([`KindSet::FIRST_SCREEN`])
    /// until the first screen's jobs have ended: at the page's start, before
    /// a worker is ready, so that the frequency response and the selected
    /// Omega have the cores to themselves (on two cores the first worker
    /// would otherwise run the bifurcation sweep beside the branch). The
    /// jobs queued so far and those started meanwhile wait, in order; a
    /// cancel or an export posts them first. A held job is not yet posted
    /// ([`JobStatus::posted_ms`]): its release dates it.
    pub fn hold_off_screen(&mut self) {
        let mut held = self.held.take().unwrap_or_default();
        for (worker, slot) in self.workers.iter_mut().enumerate() {
            let (hold, keep): (Vec<Outgoing>, Vec<Outgoing>) = std::mem::take(&mut slot.queue)
                .into_iter()
                .partition(Outgoing::off_screen);
            slot.queue = keep;
            held.extend(hold.into_iter().map(|out| (worker, out)));
        }
        let runs: Vec<Option<RunOf>> = held.iter().map(|(_, out)| out.run).collect();
        for run in runs {
            self.date_post(run, None);
        }
        self.held = Some(held);
    }

    /// Posts the messages held back at the page's start ([`Self::hold_off_screen`]),
    /// in their order, at `now_ms` (their jobs' post time), and holds no more.
    pub(super) fn release(&mut self, now_ms: f64) -> Vec<Effect> {
        let held = self.held.take().unwrap_or_default();
        let mut fx = Vec::new();
        for (worker, out) in held {
            self.date_post(out.run, Some(now_ms));
            fx.extend(self.post_out(worker, out));
        }
        fx
    }

    /// Sets when the job `run` names was posted (`None`: not yet, it is
    /// held), if it is still its kind's current job.
    fn date_post(&mut self, run: Option<RunOf>, posted_ms: Option<f64>) {
        let Some(run) = run else {
            return;
        };
        if let Some(c) = self.computation_mut(run.target) {
            let status = c.status_mut(run.kind);
            if status.id == run.id {
                status.posted_ms = posted_ms;
            }
        }
    }

    /// A worker failed to load or crashed (at `now_ms`): the jobs held at
    /// the page's start ([`Self::hold_off_screen`]) go out now, so that the
    /// other workers' jobs do not wait for a first screen that may never end.
    pub fn stop_holding(&mut self, now_ms: f64) -> Vec<Effect> {
        self.release(now_ms)
    }

    /// Releases the held messages (at `now_ms`) once none of the current
    /// state's first-screen jobs runs.
    pub(super) fn release_if_first_screen_ended(&mut self, now_ms: f64) -> Vec<Effect> {
        let running = |c: &Self| {
            KindSet::FIRST_SCREEN
                .iter()
                .any(|k| c.main.status(k).running())
        };
        if self.held.is_some() && !running(self) {
            self.release(now_ms)
        } else {
            Vec::new()
        }
    }

    /// Posts `out` to `worker`, or queues it until the worker is ready.
    fn post_out(&mut self, worker: usize, out: Outgoing) -> Vec<Effect> {
        match self.workers.get_mut(worker) {
            Some(slot) if slot.ready => vec![Effect::Post {
                worker,
                text: out.text,
            }],
            Some(slot) => {
                slot.queue.push(out);
                Vec::new()
            }
            None => Vec::new(),
        }
    }

    /// Workers in the pool.
    pub fn workers(&self) -> usize {
        self.workers.len()
    }

    /// The pool's placement rules.
    pub(super) fn pool(&self) -> Pool {
        Pool {
            size: self.workers.len(),
            long: KindSet::NONE,
        }
    }

    /// The worker that runs the current state's harmonic-balance branch: the last.
    pub fn hbm_worker(&self) -> usize {
        self.pool().hbm_worker()
    }

    /// The worker that runs A's harmonic-balance branch: the one before the
    /// last when the pool has more than two (so both branches compute at
    /// once), else the last.
    pub fn pinned_hbm_worker(&self) -> usize {
        self.pool().pinned_hbm_worker()
    }

    /// The worker of chain (or share) `shard`: chains are dealt round robin.
    pub fn shard_worker(&self, shard: u32) -> usize {
        self.pool().shard_worker(shard)
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

    /// Cancels `target`'s jobs of `kind` (`None`: all) on every worker, at `now_ms`.
    pub(super) fn cancel(
        &mut self,
        target: Target,
        kind: Option<JobKind>,
        now_ms: f64,
    ) -> Vec<Effect> {
        (0..self.workers.len())
            .flat_map(|w| self.post(w, &ToWorker::Cancel { target, kind }, now_ms))
            .collect()
    }

    /// Posts the job of each of `chains` shards (`job(shard)`) of `target`.
    fn post_shards(
        &mut self,
        (target, id, params): (Target, JobId, &Params),
        (chains, pool): (u32, Pool),
        job: impl Fn(u32) -> JobSpec,
        now_ms: f64,
    ) -> Vec<Effect> {
        let mut fx = Vec::new();
        for shard in 0..chains {
            let job = job(shard);
            let worker = kinds::of(job.kind()).worker(target, (shard, chains), pool);
            let msg = ToWorker::Run {
                target,
                id,
                params: params.clone(),
                job,
            };
            fx.extend(self.post(worker, &msg, now_ms));
        }
        fx
    }

    /// The inputs of `target`'s jobs, or why it has none (its model
    /// cannot be built); `None` if there is no such target.
    pub(super) fn inputs(&self, target: Target) -> Option<Result<Inputs, SolverError>> {
        let settings = match target {
            Target::Main => {
                let model = match self.model.clone() {
                    Ok(m) => m,
                    Err(e) => return Some(Err(e)),
                };
                let params = keys::to_json(&self.settings.params);
                return Some(Ok(Inputs {
                    settings: self.settings.clone(),
                    model,
                    params,
                }));
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
                    Some(Err(e)) => return Some(Err(e)),
                    None => None,
                }
            }
        }?;
        Some(Model::new(&settings.params).map(|model| Inputs {
            params: keys::to_json(&settings.params),
            settings,
            model,
        }))
    }

    /// Restarts `target`'s jobs of `kinds`: each kind's store and status
    /// started afresh and its shards posted; a target whose model cannot
    /// be built says why on every one of those kinds.
    pub(super) fn start(&mut self, target: Target, kinds: KindSet, now_ms: f64) -> Vec<Effect> {
        let input = match self.inputs(target) {
            Some(Ok(i)) => i,
            Some(Err(e)) => {
                if let Some(c) = self.computation_mut(target) {
                    c.fail_all(kinds, &e.to_string());
                }
                return Vec::new();
            }
            None => return Vec::new(),
        };
        let long = self.long_beside(target, kinds, &input);
        let mut fx = Vec::new();
        for kind in kinds.iter() {
            fx.extend(self.start_kind(target, kind, (&input, long), now_ms));
        }
        fx
    }

    /// The current state's long jobs ([`KindSet::LONG`]) that run beside
    /// `target`'s jobs of `kinds` started from `input`: those the current
    /// state restarts and has switched on, and those running and not
    /// restarted.
    fn long_beside(&self, target: Target, kinds: KindSet, input: &Inputs) -> KindSet {
        let cx = self.start_cx(target, input, KindSet::NONE);
        let mut long = KindSet::NONE;
        for kind in KindSet::LONG.iter() {
            let on = if target == Target::Main && kinds.contains(kind) {
                kinds::of(kind).shards(&cx).is_some()
            } else {
                self.main.status(kind).running()
            };
            if on {
                long.insert(kind);
            }
        }
        long
    }

    /// What `target`'s jobs start with from `input`, `long` running beside.
    fn start_cx<'a>(&self, target: Target, input: &'a Inputs, long: KindSet) -> StartCx<'a> {
        StartCx {
            settings: &input.settings,
            model: &input.model,
            main: target == Target::Main,
            grid: self.map_grid(),
            mesh: input.settings.mesh_index(&input.model),
            map_signature: self.map_signature(&input.model, &input.params),
            boundaries_signature: self.boundaries_signature(&input.model, &input.params),
            pool: Pool {
                long,
                ..self.pool()
            },
        }
    }

    /// Starts `target`'s job of `kind` with `input`: the kind's shards
    /// and store come from its module ([`kinds::of`]).
    fn start_kind(
        &mut self,
        target: Target,
        kind: JobKind,
        (input, long): (&Inputs, KindSet),
        now_ms: f64,
    ) -> Vec<Effect> {
        let main = target == Target::Main;
        let k = kinds::of(kind);
        let cx = self.start_cx(target, input, long);
        if k.unchanged(&cx, &self.main) {
            return Vec::new();
        }
        let Some(chains) = k.shards(&cx) else {
            return self.switch_off(target, kind, now_ms);
        };
        let total = k.total(&cx);
        let id = self.next_job();
        let Some(c) = self.computation_mut(target) else {
            return Vec::new();
        };
        let replaced = c.status(kind).id;
        let issued = std::mem::take(&mut c.status_mut(kind).issued);
        *c.status_mut(kind) = JobStatus::start(id, now_ms, total);
        k.begin(c, total, &cx);
        // A pending export of the replaced job speaks of the state before.
        if main && self.export.as_ref().is_some_and(|e| e.id == replaced) {
            self.export = None;
        }
        // The replaced job's messages spoke of the state before.
        for message in &issued {
            self.withdraw(message);
        }
        if main {
            self.dirty.data(kind);
            self.dirty.data(k.also_shown_as());
        }
        let fx = self.post_shards(
            (target, id, &input.params),
            (chains, cx.pool),
            |shard| k.spec(&cx, chains, shard),
            now_ms,
        );
        if main && k.previews() {
            self.preview_omega(&input.model, kind, id, now_ms);
        }
        fx
    }

    /// A kind switched off (no overlay, no Lyapunov curve): its store and
    /// status cleared, its running job dropped (at `now_ms`).
    fn switch_off(&mut self, target: Target, kind: JobKind, now_ms: f64) -> Vec<Effect> {
        let Some(c) = self.computation_mut(target) else {
            return Vec::new();
        };
        let running = c.status(kind).id != 0;
        let issued = std::mem::take(&mut c.status_mut(kind).issued);
        *c.status_mut(kind) = JobStatus::default();
        kinds::of(kind).clear(c);
        for message in &issued {
            self.withdraw(message);
        }
        self.dirty.data(kind);
        if running {
            self.cancel(target, Some(kind), now_ms)
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
            let e = e.to_string();
            self.main.fail_all(kinds, &e);
            for kind in JobKind::ALL {
                fx.extend(self.cancel(Target::Main, Some(kind), now_ms));
            }
            self.main.map.signature.clear();
            fx.extend(self.cancel_members(now_ms));
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
    fn preview_omega(&mut self, model: &Model, kind: JobKind, id: JobId, now_ms: f64) {
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
            self.main.status_mut(kind).preview_ms = Some(now_ms);
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
