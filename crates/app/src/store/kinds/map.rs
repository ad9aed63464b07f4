//! The impact-regime map ([`JobKind::Map`]): its rows shared among the
//! workers no long job holds; it restarts only when what it depends on changed (a click on
//! a cell sets the key its rows vary, which does not).

use super::{FeedCx, Kind, Pool, StartCx, StatusKey};
use crate::store::status::{Dirty, JobStatus};
use crate::store::{Computation, Fed};
use figures::protocol::{FromWorker, JobKind, JobSpec, RunOptions, Target};
use figures::views::map::MapStore;

pub(super) struct Map;

impl Computation {
    /// The status of the regime map's job.
    pub fn map_status(&self) -> &JobStatus {
        self.status(JobKind::Map)
    }
}

impl Kind for Map {
    fn kind(&self) -> JobKind {
        JobKind::Map
    }

    fn shards(&self, cx: &StartCx) -> Option<u32> {
        let free = u32::try_from(cx.pool.free_workers().len()).unwrap_or(1);
        Some(free.min(cx.view().map_value_points))
    }

    /// The rows go to the workers no long job holds ([`Pool::free_workers`]).
    fn worker(&self, _target: Target, shard: u32, pool: Pool) -> usize {
        let free = pool.free_workers();
        free.get(shard as usize % free.len().max(1))
            .copied()
            .unwrap_or(0)
    }

    fn unchanged(&self, cx: &StartCx, main: &Computation) -> bool {
        cx.map_signature == main.map.signature && main.status(JobKind::Map).error.is_none()
    }

    fn status_key(&self) -> StatusKey {
        StatusKey::Top("map")
    }

    fn total(&self, cx: &StartCx) -> usize {
        cx.grid.cells()
    }

    fn begin(&self, c: &mut Computation, _total: usize, cx: &StartCx) {
        c.map = MapStore::new(cx.grid.clone(), cx.map_signature.clone());
    }

    fn spec(&self, cx: &StartCx, chains: u32, shard: u32) -> JobSpec {
        let (g, v) = (&cx.grid, cx.view());
        JobSpec::Map {
            key: g.key.clone(),
            omega_from: g.omega_from,
            omega_to: g.omega_to,
            omega_points: g.omega_points,
            value_from: g.value_from,
            value_to: g.value_to,
            value_points: g.value_points,
            mesh: cx.mesh,
            shards: chains,
            shard,
            run: RunOptions {
                transient_periods: v.map_transient_periods,
                record_periods: v.map_record_periods,
            },
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
        let FromWorker::MapCells { id, cells } = msg else {
            return false;
        };
        if !self.answers(c, *id) {
            return false;
        }
        c.map.add(cells.clone());
        let done = c.map.done;
        c.status_mut(JobKind::Map).record(done, cx.now_ms);
        dirty.data(JobKind::Map);
        true
    }
}
