//! The pinned state A of an A/B comparison: pinning and clearing it. Its
//! jobs (the harmonic-balance branch and the sweep) start and are fed like
//! every computation's ([`Target::A`]).

use super::*;

/// The pinned state A of an A/B comparison and its two sweeps (the
/// frequency response and the bifurcation diagram), which are drawn under
/// the current state B's.
#[derive(Debug, Clone)]
pub struct Pinned {
    /// A's settings.
    pub settings: Settings,
    /// A's results.
    pub comp: Computation,
}

/// Every mesh's backlash (µm) of a state's model (empty if it cannot be built).
pub(super) fn pinned_backlash(s: &Settings) -> Vec<f64> {
    match solver::system::MeshSystem::build(&s.params) {
        Ok(sys) => sys.meshes.iter().map(|m| um(m.backlash_m)).collect(),
        Err(_) => Vec::new(),
    }
}

impl Controller {
    /// "Pin as A": keeps the current state and its results as A; later
    /// changes draw as B over it. Results still computing are computed again
    /// for A (B's next change would cancel them).
    pub fn pin_a(&mut self, now_ms: f64) -> Vec<Effect> {
        let mut fx = self.cancel_pinned(now_ms);
        let complete = (KindSet::PINNED.iter()).all(|k| self.main.status(k).finished_ms.is_some());
        if complete {
            let mut comp = Computation::default();
            comp.hbm = self.main.hbm.clone();
            comp.bif = self.main.bif.clone();
            for kind in KindSet::PINNED.iter() {
                *comp.status_mut(kind) = self.main.status(kind).clone();
            }
            self.pinned = Some(Pinned {
                settings: self.settings.clone(),
                comp,
            });
        } else {
            fx.extend(self.start_pinned(self.settings.clone(), now_ms));
        }
        self.dirty.data(KindSet::PINNED);
        self.dirty.url = true;
        fx
    }

    /// "Clear A": ends the comparison (at `now_ms`).
    pub fn clear_a(&mut self, now_ms: f64) -> Vec<Effect> {
        let fx = self.cancel_pinned(now_ms);
        self.pinned = None;
        self.dirty.data(KindSet::PINNED);
        self.dirty.url = true;
        fx
    }

    fn cancel_pinned(&mut self, now_ms: f64) -> Vec<Effect> {
        let running = self
            .pinned
            .as_ref()
            .is_some_and(|p| p.comp.running(KindSet::PINNED));
        if running {
            self.cancel(Target::A, None, now_ms)
        } else {
            Vec::new()
        }
    }

    /// Starts A's branch and bifurcation sweep (a link that carries A).
    pub(super) fn start_pinned(&mut self, a: Settings, now_ms: f64) -> Vec<Effect> {
        self.pinned = Some(Pinned {
            settings: a,
            comp: Computation::default(),
        });
        self.start(Target::A, KindSet::PINNED, now_ms)
    }
}
