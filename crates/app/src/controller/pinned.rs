//! The pinned state A of an A/B comparison: pinning, clearing, its two
//! sweeps and their replies.

use super::*;
use crate::controller::jobs::{bif_total, hbm_job};

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
pub(super) fn pinned_backlash(s: &Settings) -> Vec<f64> {
    match solver::system::MeshSystem::build(&s.params) {
        Ok(sys) => sys
            .meshes
            .iter()
            .map(|m| (m.backlash_m * 1e12).round() / 1e6)
            .collect(),
        Err(_) => Vec::new(),
    }
}

impl Controller {
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

    pub(super) fn cancel_pinned(&mut self) -> Vec<Effect> {
        let running = self
            .pinned
            .as_ref()
            .is_some_and(|p| p.fr_status.running() || p.bif_status.running());
        let mut fx = Vec::new();
        if running {
            for kind in [JobKind::Hbm, JobKind::Bif] {
                for w in 0..self.workers.len() {
                    fx.extend(self.post(w, &ToWorker::CancelPinned { kind }));
                }
            }
        }
        fx
    }

    /// Starts A's branch and bifurcation sweep (a link that carries A).
    pub(super) fn start_pinned(&mut self, a: Settings, now_ms: f64) -> Vec<Effect> {
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
        let msg = ToWorker::RunPinned {
            id,
            params: params.clone(),
            job: hbm_job(v),
        };
        fx.extend(self.post(self.pinned_hbm_worker(), &msg));
        self.next_id += 1;
        let id = self.next_id;
        let total = bif_total(v);
        pinned.bif = BifStore::new(id, total);
        pinned.bif_status = JobStatus::start(id, now_ms, total);
        fx.extend(self.post_bif(id, &params, v, true));
        self.pinned = Some(pinned);
        fx
    }

    /// Feeds A's stores with replies to A's jobs (ids that are A's).
    pub(super) fn pinned_message(&mut self, msg: &FromWorker, now_ms: f64) {
        let Some(p) = self.pinned.as_mut() else {
            return;
        };
        let side = super::replies::Side {
            hbm: (&mut p.hbm, &mut p.fr_status),
            bif: (&mut p.bif, &mut p.bif_status),
            omega: None,
        };
        side.feed(msg, now_ms, &mut self.dirty);
    }
}
