//! The periodic orbits' branches by shooting ([`JobKind::Orbits`]): one
//! continuation on the first worker (beside the boundaries on the last),
//! drawn on the bifurcation diagram; off unless the view asks for them.

use super::{FeedCx, Kind, StartCx, StatusKey};
use crate::store::status::Dirty;
use crate::store::{Computation, Fed};
use figures::protocol::{FromWorker, JobKind, JobSpec};
use figures::views::orbits::OrbitStore;

pub(super) struct Orbits;

impl Kind for Orbits {
    fn kind(&self) -> JobKind {
        JobKind::Orbits
    }

    fn shards(&self, cx: &StartCx) -> Option<u32> {
        cx.view().branches.then_some(1)
    }

    fn status_key(&self) -> StatusKey {
        StatusKey::Job("bif_branches")
    }

    fn total(&self, _cx: &StartCx) -> usize {
        worker::jobs::orbits::MAX_ORBIT_POINTS
    }

    fn begin(&self, c: &mut Computation, _total: usize, _cx: &StartCx) {
        c.orbits = OrbitStore::default();
    }

    fn clear(&self, c: &mut Computation) {
        c.orbits = OrbitStore::default();
    }

    fn spec(&self, cx: &StartCx, _chains: u32, _shard: u32) -> JobSpec {
        let v = cx.view();
        JobSpec::Orbits {
            omega_from: v.omega_from,
            omega_to: v.omega_to,
            points: v.bif_points,
        }
    }

    fn feed(
        &self,
        c: &mut Computation,
        msg: &FromWorker,
        cx: &FeedCx,
        dirty: &mut Dirty,
        fed: &mut Fed,
    ) -> bool {
        let FromWorker::OrbitPoints {
            id,
            points,
            finished,
            error,
        } = msg
        else {
            return false;
        };
        if !self.answers(c, *id) {
            return false;
        }
        c.orbits.points.extend(points.iter().cloned());
        c.orbits.finished = *finished;
        let done = c.orbits.points.len();
        let st = c.status_mut(JobKind::Orbits);
        st.record(done, cx.now_ms);
        if *finished {
            st.finished_ms = Some(cx.now_ms);
        }
        if let Some(e) = error {
            let msg = format!("The shooting branches stop: {e} The branches drawn are partial.");
            st.issued.push(msg.clone());
            c.orbits.error = Some(msg.clone());
            fed.issues.push(msg);
        }
        dirty.data(JobKind::Orbits);
        true
    }
}
