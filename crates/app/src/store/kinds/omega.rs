//! The selected Omega's steady state ([`JobKind::Omega`]): one shard; the
//! current state keeps its last result on screen until the new one (or
//! its preview) arrives.

use super::{FeedCx, Kind, Pool, StartCx, StatusKey};
use crate::store::status::{Dirty, JobStatus};
use crate::store::{Computation, Fed};
use figures::protocol::{FromWorker, JobKind, JobSpec, Target};
use worker::jobs::omega::selected_spec;

pub(super) struct Omega;

impl Computation {
    /// The status of the selected Omega's steady state's job.
    pub fn omega_status(&self) -> &JobStatus {
        self.status(JobKind::Omega)
    }
}

impl Kind for Omega {
    fn kind(&self) -> JobKind {
        JobKind::Omega
    }

    fn shards(&self, _cx: &StartCx) -> Option<u32> {
        Some(1)
    }

    fn status_key(&self) -> StatusKey {
        StatusKey::Top("omega_job")
    }

    fn total(&self, _cx: &StartCx) -> usize {
        1
    }

    fn begin(&self, c: &mut Computation, _total: usize, cx: &StartCx) {
        // A member's panel waits for its own result.
        if !cx.main {
            c.omega = None;
        }
    }

    fn spec(&self, cx: &StartCx, _chains: u32, _shard: u32) -> JobSpec {
        JobSpec::Omega(selected_spec(
            cx.settings,
            cx.model,
            cx.run(cx.view().record_periods),
        ))
    }

    fn worker(&self, target: Target, (shard, _): (u32, u32), pool: Pool) -> usize {
        match target {
            Target::Member(m) => m as usize % pool.size,
            _ => pool.shard_worker(shard),
        }
    }

    fn previews(&self) -> bool {
        true
    }

    fn feed(
        &self,
        c: &mut Computation,
        msg: &FromWorker,
        cx: &FeedCx,
        dirty: &mut Dirty,
        _fed: &mut Fed,
    ) -> bool {
        let FromWorker::Omega { id, result } = msg else {
            return false;
        };
        if !self.answers(c, *id) {
            return false;
        }
        c.omega = Some((**result).clone());
        let st = c.status_mut(JobKind::Omega);
        st.done = 1;
        st.first_data_ms = Some(cx.now_ms);
        st.finished_ms = Some(cx.now_ms);
        dirty.data(JobKind::Omega);
        true
    }
}
