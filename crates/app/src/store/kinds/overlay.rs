//! The time-integration overlay of the frequency response
//! ([`JobKind::Overlay`]): steady states along interleaved chains, off
//! when the view asks for no points.

use super::{chain_count, FeedCx, Kind, StartCx, StatusKey};
use crate::store::status::Dirty;
use crate::store::{Computation, Fed};
use figures::protocol::{FromWorker, JobKind, JobSpec};
use figures::views::fr::FrStore;

pub(super) struct Overlay;

impl Kind for Overlay {
    fn kind(&self) -> JobKind {
        JobKind::Overlay
    }

    fn shards(&self, cx: &StartCx) -> Option<u32> {
        let v = cx.view();
        v.overlay_on().then(|| chain_count(v.fr_ti_points))
    }

    fn status_key(&self) -> StatusKey {
        StatusKey::Top("fr_overlay")
    }

    fn total(&self, cx: &StartCx) -> usize {
        cx.view().fr_ti_points as usize
    }

    fn begin(&self, c: &mut Computation, _total: usize, cx: &StartCx) {
        let v = cx.view();
        c.overlay = FrStore::new(v.fr_ti_points, v.transient_periods, v.fr_record_periods);
    }

    fn clear(&self, c: &mut Computation) {
        c.overlay = FrStore::default();
    }

    fn spec(&self, cx: &StartCx, chains: u32, shard: u32) -> JobSpec {
        let v = cx.view();
        JobSpec::Overlay {
            omega_from: v.omega_from,
            omega_to: v.omega_to,
            points: v.fr_ti_points,
            chains,
            shard,
            run: cx.run(v.fr_record_periods),
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
        let FromWorker::OverlayPoints { id, points } = msg else {
            return false;
        };
        if !self.answers(c, *id) {
            return false;
        }
        c.overlay.add(points.clone());
        let done = c.overlay.done();
        c.status_mut(JobKind::Overlay).record(done, cx.now_ms);
        dirty.data(JobKind::Overlay);
        true
    }
}
