//! What the page holds of its computations: one [`Computation`] (every
//! job kind's data store and status) for the current state, one for the
//! pinned state A, one per family member; and one [`Computation::feed`]
//! by which every worker reply reaches its store.
//!
//! Each job kind's part (its store's start, its replies) lives in its
//! own module under [`kinds`].
//!
//! Architecture invariant: a reply reaches a store only through
//! [`Computation::feed`], and only the store whose current job id it
//! carries (ids are unique across all computations).

pub mod kinds;
pub mod status;

use figures::protocol::{FromWorker, JobKind, KindSet, OmegaResult};
use figures::views::bif::BifStore;
use figures::views::boundaries::BoundaryStore;
use figures::views::fr::{FrStore, HbmStore};
use figures::views::lyap::LyapStore;
use figures::views::map::MapStore;
use figures::views::orbits::OrbitStore;
use status::{Dirty, JobStatus};

/// One state's results: a store and a status per job kind. The pinned A
/// computes the harmonic balance and the sweep, a family member also the
/// selected Omega; the other stores then stay empty.
#[derive(Debug, Clone, Default)]
pub struct Computation {
    /// The harmonic-balance branch (`kinds/hbm.rs`).
    pub hbm: HbmStore,
    /// The last complete branch, shown faded while a new one computes.
    pub hbm_previous: Option<HbmStore>,
    /// The time-integration overlay's points (`kinds/overlay.rs`; empty when off).
    pub overlay: FrStore,
    /// The bifurcation sweep's points (`kinds/bif.rs`).
    pub bif: BifStore,
    /// The parametric-instability bands of the sweep's range, from its
    /// shard-0 worker (kept until a newer sweep's arrive).
    pub bands: Vec<(f64, f64)>,
    /// The latest selected-Omega result (`kinds/omega.rs`; possibly an
    /// older job's while a new one runs).
    pub omega: Option<OmegaResult>,
    /// The impact-regime map's cells (`kinds/map.rs`).
    pub map: MapStore,
    /// The Lyapunov curve's points (`kinds/lyap.rs`).
    pub lyap: LyapStore,
    /// The shooting branches' points (`kinds/orbits.rs`; empty when off).
    pub orbits: OrbitStore,
    /// The map's traced boundaries (`kinds/boundaries.rs`; empty when off).
    pub boundaries: BoundaryStore,
    /// Each kind's job status, by [`JobKind::slot`]: the one place a
    /// job's id is kept (the stores hold data only).
    status: [JobStatus; JobKind::COUNT],
}

/// What a reply did that the controller acts on beyond the stores.
#[derive(Debug, Default, PartialEq)]
pub struct Fed {
    /// Messages for the user.
    pub issues: Vec<String>,
    /// Whether it answered one of this computation's jobs.
    pub matched: bool,
}

impl Computation {
    /// The status of the job of `kind`.
    pub fn status(&self, kind: JobKind) -> &JobStatus {
        &self.status[kind.slot()]
    }

    /// The status of the job of `kind`, to change.
    pub fn status_mut(&mut self, kind: JobKind) -> &mut JobStatus {
        &mut self.status[kind.slot()]
    }

    /// Whether any job of `kinds` is running.
    pub fn running(&self, kinds: KindSet) -> bool {
        kinds.iter().any(|k| self.status(k).running())
    }

    /// Every job failing with `e` (a model that cannot be built).
    pub fn fail_all(&mut self, kinds: KindSet, e: &str) {
        for k in kinds.iter() {
            *self.status_mut(k) = JobStatus {
                error: Some(e.to_string()),
                ..JobStatus::default()
            };
        }
    }

    /// Feeds `msg` to the store whose job it answers (ids 0 and other
    /// computations' are ignored), at `now_ms`, and marks the kinds whose
    /// data changed in `dirty`. `omega_from` is where the branch starts
    /// (named when it fails before its first point). Each kind feeds its
    /// own replies ([`kinds::Kind::feed`]); a failure is any kind's.
    pub fn feed(
        &mut self,
        msg: &FromWorker,
        now_ms: f64,
        omega_from: f64,
        dirty: &mut Dirty,
    ) -> Fed {
        let mut fed = Fed::default();
        if let FromWorker::Failed { id, message } = msg {
            if *id == 0 {
                return fed;
            }
            for kind in JobKind::ALL {
                let st = self.status_mut(kind);
                if st.id == *id {
                    st.error = Some(message.clone());
                    st.issued.push(message.clone());
                    dirty.data(kind);
                    fed.matched = true;
                }
            }
            return fed;
        }
        // Progress and Done of current jobs are implied by the data;
        // stale replies are dropped.
        let cx = kinds::FeedCx { now_ms, omega_from };
        fed.matched = JobKind::ALL
            .iter()
            .any(|&k| kinds::of(k).feed(self, msg, &cx, dirty, &mut fed));
        fed
    }
}

#[cfg(test)]
mod tests;
