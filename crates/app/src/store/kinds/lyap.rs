//! The largest Lyapunov exponent over Omega ([`JobKind::Lyap`]): points
//! along interleaved chains, off below two points.

use super::{chain_count, FeedCx, Kind, StartCx, StatusKey};
use crate::store::status::{Dirty, JobStatus};
use crate::store::{Computation, Fed};
use figures::protocol::{FromWorker, JobKind, JobSpec};
use figures::views::lyap::LyapStore;

pub(super) struct Lyap;

impl Computation {
    /// The status of the Lyapunov curve's job.
    pub fn lyap_status(&self) -> &JobStatus {
        self.status(JobKind::Lyap)
    }
}

impl Kind for Lyap {
    fn kind(&self) -> JobKind {
        JobKind::Lyap
    }

    fn shards(&self, cx: &StartCx) -> Option<u32> {
        let v = cx.view();
        v.lyap_on().then(|| chain_count(v.lyap_points))
    }

    fn status_key(&self) -> StatusKey {
        StatusKey::Top("lyap")
    }

    fn total(&self, cx: &StartCx) -> usize {
        cx.view().lyap_points as usize
    }

    fn begin(&self, c: &mut Computation, total: usize, cx: &StartCx) {
        c.lyap = LyapStore::new(total, cx.view().lyap_periods);
        c.lyap.linear = cx.model.is_linear();
    }

    fn clear(&self, c: &mut Computation) {
        c.lyap = LyapStore::default();
    }

    fn spec(&self, cx: &StartCx, chains: u32, shard: u32) -> JobSpec {
        let v = cx.view();
        JobSpec::Lyap {
            omega_from: v.omega_from,
            omega_to: v.omega_to,
            points: v.lyap_points,
            chains,
            shard,
            transient_periods: v.lyap_transient_periods,
            periods: v.lyap_periods,
        }
    }

    fn feed(
        &self,
        c: &mut Computation,
        msg: &FromWorker,
        cx: &FeedCx,
        dirty: &mut Dirty,
        _fed: &mut Fed,
    ) -> bool {
        let FromWorker::LyapPoints { id, points } = msg else {
            return false;
        };
        if !self.answers(c, *id) {
            return false;
        }
        c.lyap.points.extend(points.iter().cloned());
        let done = c.lyap.points.len();
        c.status_mut(JobKind::Lyap).record(done, cx.now_ms);
        dirty.data(JobKind::Lyap);
        true
    }
}
