//! The regime map's traced boundaries ([`JobKind::Boundaries`]): one
//! trace on the last worker, its progress in per mille; off unless the
//! view asks for them, and restarted only when what the curves depend on
//! changed.

use super::{FeedCx, Kind, Pool, StartCx, StatusKey};
use crate::store::status::{Dirty, JobStatus};
use crate::store::{Computation, Fed};
use figures::protocol::{FromWorker, JobKind, JobSpec, Target};
use figures::views::boundaries::{BoundaryStore, BOUNDARY_LEVELS, BOUNDARY_POINTS};

pub(super) struct Boundaries;

impl Computation {
    /// The status of the map's boundaries's job.
    pub fn boundaries_status(&self) -> &JobStatus {
        self.status(JobKind::Boundaries)
    }
}

impl Kind for Boundaries {
    fn kind(&self) -> JobKind {
        JobKind::Boundaries
    }

    fn shards(&self, cx: &StartCx) -> Option<u32> {
        cx.view().boundaries.then_some(1)
    }

    /// A click on the map sets the key the curves vary: they stand.
    fn unchanged(&self, cx: &StartCx, main: &Computation) -> bool {
        cx.view().boundaries
            && cx.boundaries_signature == main.boundaries.signature
            && main.status(JobKind::Boundaries).error.is_none()
    }

    /// Per mille.
    fn status_key(&self) -> StatusKey {
        StatusKey::Job("map_boundaries")
    }

    fn total(&self, _cx: &StartCx) -> usize {
        1000
    }

    fn begin(&self, c: &mut Computation, _total: usize, cx: &StartCx) {
        c.boundaries = BoundaryStore::new(cx.boundaries_signature.clone());
    }

    fn clear(&self, c: &mut Computation) {
        c.boundaries = BoundaryStore::default();
    }

    fn spec(&self, cx: &StartCx, _chains: u32, _shard: u32) -> JobSpec {
        let g = &cx.grid;
        JobSpec::Boundaries {
            key: g.key.clone(),
            omega_from: g.omega_from,
            omega_to: g.omega_to,
            value_from: g.value_from,
            value_to: g.value_to,
            levels: BOUNDARY_LEVELS,
            points: BOUNDARY_POINTS,
            harmonics: cx.view().harmonics as usize,
            contact_mesh: cx.mesh,
        }
    }

    /// The last worker: the two long jobs, the trace and the shooting
    /// branches (on the first), run side by side on a pool of two or more.
    /// On one worker the trace, served after the branches, waited for all
    /// of them: with the compound set's default map the page's trace had
    /// not begun after 13 minutes, while alone it takes about a minute.
    fn worker(&self, _target: Target, _shard: (u32, u32), pool: Pool) -> usize {
        pool.size - 1
    }

    fn feed(
        &self,
        c: &mut Computation,
        msg: &FromWorker,
        cx: &FeedCx,
        dirty: &mut Dirty,
        _fed: &mut Fed,
    ) -> bool {
        let FromWorker::BoundaryCurves {
            id,
            curves,
            cusps,
            notes,
            permille,
            finished,
        } = msg
        else {
            return false;
        };
        if !self.answers(c, *id) {
            return false;
        }
        let b = &mut c.boundaries;
        b.curves.extend(curves.iter().cloned());
        b.cusps.clone_from(cusps);
        b.notes.extend(notes.iter().cloned());
        b.finished = *finished;
        let st = c.status_mut(JobKind::Boundaries);
        st.record(*permille, cx.now_ms);
        if *finished {
            st.finished_ms = Some(cx.now_ms);
        }
        dirty.data(JobKind::Boundaries);
        true
    }
}
