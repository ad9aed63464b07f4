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

    pub(super) fn restart(&mut self, what: Restart, now_ms: f64) -> Vec<Effect> {
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

    pub(super) fn restart_lyap(
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
}
