//! A parameter family on the page: member 0 is the current state itself;
//! members 1, 2, ... run their own harmonic-balance branch, bifurcation
//! sweep and selected-Omega steady state in the workers, beside the current
//! state's jobs, and arrive progressively like them.

use super::*;
use crate::controller::jobs::{bif_job, bif_total, hbm_job};
use crate::family::FamilySpec;
use crate::views::bif::BifView;
use crate::views::family::{panel_titles, Panel};

/// One family member besides the current state, and its three results.
#[derive(Debug, Clone)]
pub struct Member {
    /// Its value of the family's key.
    pub value: f64,
    /// Its parameters (the current state's with the key set), or why they
    /// cannot be built.
    pub params: Result<solver::params::ModelParams, String>,
    /// Its harmonic-balance branch.
    pub hbm: HbmStore,
    /// Its bifurcation points.
    pub bif: BifStore,
    /// Its selected-Omega steady state.
    pub omega: Option<OmegaResult>,
    /// Branch job.
    pub fr_status: JobStatus,
    /// Bifurcation job.
    pub bif_status: JobStatus,
    /// Selected-Omega job.
    pub omega_status: JobStatus,
}

/// The family shown: its spec and members 1, 2, ... (member 0 is the
/// current state).
#[derive(Debug, Clone)]
pub struct Family {
    /// Key and values.
    pub spec: FamilySpec,
    /// Members 1.. in the order of the values.
    pub members: Vec<Member>,
}

impl Controller {
    /// Shows a family (replacing any other): the current state takes the
    /// first value, the others compute in the workers. Nothing changes if
    /// the family cannot be built.
    pub fn set_family(&mut self, spec: FamilySpec, now_ms: f64) -> Result<Vec<Effect>, String> {
        let first = spec.member_params(&self.settings.params, 0)?;
        Model::new(&first).map_err(|e| e.to_string())?;
        let mut fx = self.cancel_members(None);
        let changed = first != self.settings.params;
        self.family = Some(Family {
            members: Vec::new(),
            spec,
        });
        if changed {
            self.settings.params = first;
            self.rebuild_model();
            self.dirty.controls = true;
            fx.extend(self.restart(ALL, now_ms));
        } else {
            fx.extend(self.restart_members(ALL, now_ms));
        }
        self.dirty.fr = true;
        self.dirty.bif = true;
        self.dirty.omega = true;
        self.dirty.url = true;
        Ok(fx)
    }

    /// Parses and shows a family typed on the page ("0, 20, 30"); a bad
    /// one is refused with a message and the last good state kept.
    pub fn set_family_text(
        &mut self,
        key: &str,
        values: &str,
        now_ms: f64,
    ) -> Result<Vec<Effect>, String> {
        let spec = crate::family::parse_parts(key, values, &self.settings.params)?;
        self.set_family(spec, now_ms)
    }

    /// Ends the family: the current state alone again.
    pub fn clear_family(&mut self) -> Vec<Effect> {
        if self.family.take().is_none() {
            return Vec::new();
        }
        self.dirty.fr = true;
        self.dirty.bif = true;
        self.dirty.omega = true;
        self.dirty.url = true;
        self.cancel_members(None)
    }

    pub(super) fn cancel_members(&mut self, kind: Option<JobKind>) -> Vec<Effect> {
        (0..self.workers())
            .flat_map(|w| self.post(w, &ToWorker::CancelMembers { kind }))
            .collect()
    }

    /// Restarts the members' jobs of the kinds `what` names (a member
    /// computes the branch, the sweep and the selected Omega).
    pub(super) fn restart_members(&mut self, what: Restart, now_ms: f64) -> Vec<Effect> {
        let Some(mut family) = self.family.take() else {
            return Vec::new();
        };
        let mut fx = Vec::new();
        // The current state's value follows the key's control.
        if let Some(keys::Value::Num(x)) = keys::get(&self.settings.params, family.spec.key.key) {
            if let Some(v0) = family.spec.values.first_mut() {
                *v0 = x;
            }
        }
        let n = family.spec.values.len().saturating_sub(1);
        if family.members.len() != n || what == ALL {
            family.members = (1..=n)
                .map(|i| Member {
                    value: family.spec.values[i],
                    params: family.spec.member_params(&self.settings.params, i),
                    hbm: HbmStore::default(),
                    bif: BifStore::default(),
                    omega: None,
                    fr_status: JobStatus::default(),
                    bif_status: JobStatus::default(),
                    omega_status: JobStatus::default(),
                })
                .collect();
        } else {
            for (i, m) in family.members.iter_mut().enumerate() {
                m.params = family.spec.member_params(&self.settings.params, i + 1);
            }
        }
        let v = self.settings.view.clone();
        let pool = self.workers();
        let hbm_worker = self.hbm_worker();
        let kinds = [
            (what.fr, JobKind::Hbm),
            (what.bif, JobKind::Bif),
            (what.omega, JobKind::Omega),
        ];
        for (_, kind) in kinds.iter().filter(|(on, _)| *on) {
            fx.extend(self.cancel_members(Some(*kind)));
        }
        let main_error = self.model.as_ref().err().cloned();
        for (i, m) in family.members.iter_mut().enumerate() {
            let member = (i + 1) as u32;
            let built = match (&main_error, &m.params) {
                (Some(e), _) | (_, Err(e)) => Err(e.clone()),
                (None, Ok(p)) => Model::new(p).map_err(|e| e.to_string()),
            };
            let built = match built {
                Ok(b) => b,
                Err(e) => {
                    for st in [&mut m.fr_status, &mut m.bif_status, &mut m.omega_status] {
                        *st = JobStatus {
                            error: Some(e.clone()),
                            ..JobStatus::default()
                        };
                    }
                    continue;
                }
            };
            let Ok(p) = &m.params else { continue };
            let params = keys::to_json(p);
            for (on, kind) in kinds {
                if !on {
                    continue;
                }
                self.next_id += 1;
                let id = self.next_id;
                let (job, total, workers): (Vec<JobSpec>, usize, Vec<usize>) = match kind {
                    JobKind::Hbm => {
                        m.hbm = HbmStore::new(id, v.harmonics);
                        (vec![hbm_job(&v)], 100, vec![(hbm_worker + i + 1) % pool])
                    }
                    JobKind::Bif => {
                        let total = bif_total(&v);
                        m.bif = BifStore::new(id, total);
                        // As many chains as the current state's sweep, dealt
                        // round robin: the same results on any pool.
                        let chains = super::chain_count(v.bif_points);
                        let jobs = (0..chains)
                            .map(|shard| bif_job(&v, chains, shard))
                            .collect();
                        (
                            jobs,
                            total,
                            (0..chains as usize).map(|c| c % pool).collect(),
                        )
                    }
                    _ => {
                        m.omega = None;
                        (vec![self.omega_job(&built)], 1, vec![(i + 1) % pool])
                    }
                };
                let st = match kind {
                    JobKind::Hbm => &mut m.fr_status,
                    JobKind::Bif => &mut m.bif_status,
                    _ => &mut m.omega_status,
                };
                *st = JobStatus::start(id, now_ms, total);
                for (job, w) in job.into_iter().zip(workers) {
                    let msg = ToWorker::RunMember {
                        member,
                        id,
                        params: params.clone(),
                        job,
                    };
                    fx.extend(self.post(w, &msg));
                }
            }
        }
        self.family = Some(family);
        fx
    }

    /// Feeds the members' stores with replies to their jobs.
    pub(super) fn family_message(&mut self, msg: &FromWorker, now_ms: f64) {
        let Some(f) = self.family.as_mut() else {
            return;
        };
        for m in &mut f.members {
            let side = super::replies::Side {
                hbm: (&mut m.hbm, &mut m.fr_status),
                bif: (&mut m.bif, &mut m.bif_status),
                omega: Some((&mut m.omega, &mut m.omega_status)),
            };
            side.feed(msg, now_ms, &mut self.dirty);
        }
    }

    /// The panel titles of the family: "(a) TE 0 µm", ... (lettered from
    /// `offset`: the Poincaré panels are d-f).
    pub fn panel_titles(&self, offset: usize) -> Vec<String> {
        let Some(f) = &self.family else {
            return Vec::new();
        };
        let labels: Vec<String> = (0..f.spec.values.len()).map(|i| f.spec.label(i)).collect();
        panel_titles(&labels, offset)
    }

    /// The bifurcation diagram's small multiples, one per member.
    pub fn bif_panels(&self) -> Vec<Panel<BifView>> {
        let Some(f) = &self.family else {
            return Vec::new();
        };
        let titles = self.panel_titles(0);
        let (mesh, _) = self.mesh_and_backlash();
        let ctx = self.view_context();
        let mut out = vec![Panel {
            title: titles[0].clone(),
            data: match (&self.bif_status.error, self.bif.samples.is_empty()) {
                (Some(e), true) => Err(e.clone()),
                _ => Ok(self.bif_view()),
            },
        }];
        for (m, title) in f.members.iter().zip(titles.into_iter().skip(1)) {
            let backlash = m
                .params
                .as_ref()
                .map(|p| {
                    pinned_backlash(&Settings {
                        params: p.clone(),
                        view: self.settings.view.clone(),
                    })
                })
                .unwrap_or_default();
            let data = match (&m.bif_status.error, m.bif.samples.is_empty()) {
                (Some(e), true) => Err(e.clone()),
                _ => Ok(m.bif.view(mesh, &backlash, &ctx)),
            };
            out.push(Panel { title, data });
        }
        out
    }

    /// The selected-Omega small multiples (phase portraits or Poincaré
    /// sections), one per member.
    pub fn omega_panels(&self, offset: usize) -> Vec<Panel<OmegaResult>> {
        let Some(f) = &self.family else {
            return Vec::new();
        };
        let titles = self.panel_titles(offset);
        let waiting = || {
            Err(crate::views::omega::computing_message(
                self.settings.view.omega,
            ))
        };
        let mut out = vec![Panel {
            title: titles[0].clone(),
            data: match (&self.omega, &self.omega_status.error) {
                (_, Some(e)) => Err(format!("Not computed: {e}")),
                (Some(r), None) => Ok(r.clone()),
                (None, None) => waiting(),
            },
        }];
        for (m, title) in f.members.iter().zip(titles.into_iter().skip(1)) {
            let data = match (&m.omega, &m.omega_status.error) {
                (_, Some(e)) => Err(format!("Not computed: {e}")),
                (Some(r), None) => Ok(r.clone()),
                (None, None) => waiting(),
            };
            out.push(Panel { title, data });
        }
        out
    }

    /// Whether a family member's job of `kind` (its branch, sweep or
    /// selected-Omega run) is still computing.
    pub fn members_running(&self, kind: JobKind) -> bool {
        self.family.as_ref().is_some_and(|f| {
            f.members.iter().any(|m| match kind {
                JobKind::Hbm => m.fr_status.running(),
                JobKind::Bif => m.bif_status.running(),
                _ => m.omega_status.running(),
            })
        })
    }

    /// The family's part of the status the tests read.
    pub(super) fn family_status(&self) -> serde_json::Value {
        let Some(f) = &self.family else {
            return serde_json::Value::Null;
        };
        let members: Vec<serde_json::Value> = f
            .members
            .iter()
            .map(|m| {
                serde_json::json!({
                    "value": m.value,
                    "fr": m.fr_status,
                    "fr_branch_points": m.hbm.points.len(),
                    "bif": m.bif_status,
                    "bif_points": m.bif.samples.len(),
                    "omega_job": m.omega_status,
                    "period": m.omega.as_ref().map(|r| r.period),
                })
            })
            .collect();
        serde_json::json!({
            "key": f.spec.key.key,
            "values": f.spec.values,
            "labels": (0..f.spec.values.len()).map(|i| f.spec.label(i)).collect::<Vec<_>>(),
            "members": members,
        })
    }
}
