//! A parameter family on the page: member 0 is the current state itself;
//! members 1, 2, ... run their own harmonic-balance branch, bifurcation
//! sweep and selected-Omega steady state in the workers, beside the current
//! state's jobs, and arrive progressively like them.

use super::*;
use figures::family_spec::FamilySpec;
use figures::views::bif::BifView;
use figures::views::multiples::{panel_titles, Panel};

/// One family member besides the current state, and its results (its
/// branch, its sweep, its selected-Omega run).
#[derive(Debug, Clone)]
pub struct Member {
    /// Its value of the family's key.
    pub value: f64,
    /// Its parameters (the current state's with the key set), or why they
    /// cannot be built.
    pub params: Result<solver::params::ModelParams, solver::SolverError>,
    /// Its results.
    pub comp: Computation,
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
    pub fn set_family(&mut self, spec: FamilySpec, now_ms: f64) -> Result<Vec<Effect>, InputError> {
        let first = spec.member_params(&self.settings.params, 0)?;
        Model::new(&first)?;
        let mut fx = self.cancel_members(now_ms);
        let changed = first != self.settings.params;
        self.family = Some(Family {
            members: Vec::new(),
            spec,
        });
        if changed {
            self.settings.params = first;
            self.rebuild_model();
            self.dirty.controls = true;
            fx.extend(self.restart(KindSet::ALL, now_ms));
        } else {
            fx.extend(self.restart_members(KindSet::ALL, now_ms));
        }
        self.dirty.data(KindSet::MEMBER);
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
    ) -> Result<Vec<Effect>, InputError> {
        let spec = figures::family_spec::parse_parts(key, values, &self.settings.params)?;
        self.set_family(spec, now_ms)
    }

    /// Ends the family at `now_ms`: the current state alone again.
    pub fn clear_family(&mut self, now_ms: f64) -> Vec<Effect> {
        if self.family.is_none() {
            return Vec::new();
        }
        let fx = self.cancel_members(now_ms);
        self.family = None;
        self.dirty.data(KindSet::MEMBER);
        self.dirty.url = true;
        fx
    }

    /// Cancels every job of the members shown, at `now_ms`.
    pub(super) fn cancel_members(&mut self, now_ms: f64) -> Vec<Effect> {
        let n = self.family.as_ref().map_or(0, |f| f.members.len());
        (1..=n as u32)
            .flat_map(|m| self.cancel(Target::Member(m), None, now_ms))
            .collect()
    }

    /// Restarts the members' jobs of the kinds `what` names (a member
    /// computes the branch, the sweep and the selected Omega).
    pub(super) fn restart_members(&mut self, what: KindSet, now_ms: f64) -> Vec<Effect> {
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
        let rebuild = family.members.len() != n || what == KindSet::ALL;
        self.family = Some(family);
        let kinds = what.and(KindSet::MEMBER);
        // The members' running jobs of those kinds (all of them, if the
        // members change) are dropped first.
        if rebuild {
            fx.extend(self.cancel_members(now_ms));
        } else {
            for m in 1..=n as u32 {
                for kind in kinds.iter() {
                    fx.extend(self.cancel(Target::Member(m), Some(kind), now_ms));
                }
            }
        }
        let params = &self.settings.params;
        if let Some(f) = &mut self.family {
            if rebuild {
                f.members = (1..=n)
                    .map(|i| Member {
                        value: f.spec.values[i],
                        params: f.spec.member_params(params, i),
                        comp: Computation::default(),
                    })
                    .collect();
            } else {
                for (i, m) in f.members.iter_mut().enumerate() {
                    m.params = f.spec.member_params(params, i + 1);
                }
            }
        }
        for m in 1..=n as u32 {
            fx.extend(self.start(Target::Member(m), kinds, now_ms));
        }
        fx
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
            data: match (
                &self.main.bif_status().error,
                self.main.bif.samples.is_empty(),
            ) {
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
            let c = &m.comp;
            let data = match (&c.bif_status().error, c.bif.samples.is_empty()) {
                (Some(e), true) => Err(e.clone()),
                _ => Ok(c.bif.view(mesh, &backlash, &ctx)),
            };
            out.push(Panel { title, data });
        }
        out
    }

    /// The selected-Omega small multiples (phase portraits or Poincaré
    /// sections), one per member, borrowing each member's result: the
    /// page draws them and the status reads their titles at every
    /// animation frame, and a result of 1000 recorded periods is
    /// megabytes (cloning six of them was most of a family's redraw).
    pub fn omega_panels(&self, offset: usize) -> Vec<Panel<&OmegaResult>> {
        let Some(f) = &self.family else {
            return Vec::new();
        };
        let titles = self.panel_titles(offset);
        let waiting = || {
            Err(figures::views::omega::computing_message(
                self.settings.view.omega,
            ))
        };
        let comps = std::iter::once(&self.main).chain(f.members.iter().map(|m| &m.comp));
        comps
            .zip(titles)
            .map(|(c, title)| Panel {
                title,
                data: match (&c.omega, &c.omega_status().error) {
                    (_, Some(e)) => Err(format!("Not computed: {e}")),
                    (Some(r), None) => Ok(r),
                    (None, None) => waiting(),
                },
            })
            .collect()
    }

    /// Whether a family member's job of `kind` (its branch, sweep or
    /// selected-Omega run) is still computing.
    pub fn members_running(&self, kind: JobKind) -> bool {
        self.family
            .as_ref()
            .is_some_and(|f| f.members.iter().any(|m| m.comp.status(kind).running()))
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
                let c = &m.comp;
                let mut member = serde_json::json!({
                    "value": m.value,
                    "fr_branch_points": c.hbm.points.len(),
                    "bif_points": c.bif.samples.len(),
                    "period": c.omega.as_ref().map(|r| r.period),
                    "motion": c.omega.as_ref().map(|r| figures::story::motion_tag(r.motion)),
                });
                crate::store::kinds::put_statuses(&mut member, c, KindSet::MEMBER, None);
                member
            })
            .collect();
        // The phase portraits' panel titles as drawn (a member still
        // computing shows its bare title).
        let titles: Vec<String> = self
            .omega_panels(0)
            .iter()
            .map(|p| match &p.data {
                Ok(r) => figures::plots::multiples::phase_panel_title(&p.title, r),
                Err(_) => p.title.clone(),
            })
            .collect();
        serde_json::json!({
            "omega_titles": titles,
            "key": f.spec.key.key,
            "values": f.spec.values,
            "labels": (0..f.spec.values.len()).map(|i| f.spec.label(i)).collect::<Vec<_>>(),
            "members": members,
        })
    }
}
