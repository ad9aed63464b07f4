//! The impact-regime map ([`JobKind::Map`]): its rows shared among the
//! workers no long job holds; it restarts only when what it depends on
//! changed (a click on a cell sets the key its rows vary, which does not).

use super::{FeedCx, Kind, Pool, StartCx, StatusKey};
use crate::store::status::{Dirty, JobStatus};
use crate::store::{Computation, Fed};
use figures::protocol::{FromWorker, JobKind, JobSpec, RunOptions, Target};
use figures::views::map::MapStore;

pub(super) struct Map;

/// The map's cells times their periods (transient and recorded) up to
/// which its rows leave the long jobs' workers: the default map (640 cells
/// of 350 periods, 224 000) takes about as long as the compound set's 300
/// branch points (natively 3.9 s of CPU against 2.7 to 4.6 s), so both end
/// together; a larger map would wait on fewer workers after the branches
/// end, and shares every worker.
const BESIDE_LONG_PERIODS: f64 = 250_000.0;

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

    /// One share of the rows per worker no long job holds
    /// ([`Pool::free_workers`]) for a map up to [`BESIDE_LONG_PERIODS`];
    /// one per worker for a larger one.
    fn shards(&self, cx: &StartCx) -> Option<u32> {
        let v = cx.view();
        let periods =
            cx.grid.cells() as f64 * f64::from(v.map_transient_periods + v.map_record_periods);
        let workers = if periods <= BESIDE_LONG_PERIODS {
            cx.pool.free_workers().len()
        } else {
            cx.pool.size
        };
        Some(u32::try_from(workers).unwrap_or(1).min(v.map_value_points))
    }

    /// As many shares as free workers: on those; more: round robin.
    fn worker(&self, _target: Target, (shard, chains): (u32, u32), pool: Pool) -> usize {
        let free = pool.free_workers();
        if chains as usize <= free.len() {
            free.get(shard as usize % free.len().max(1))
                .copied()
                .unwrap_or(0)
        } else {
            pool.shard_worker(shard)
        }
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
