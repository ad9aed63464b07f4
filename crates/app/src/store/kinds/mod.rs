//! Each job kind's page side in one module: how many shards its job has
//! (or whether it is switched off), its progress total, how its store
//! starts and clears, the [`JobSpec`] each shard is posted with, which
//! worker runs a shard and how the worker's replies reach its store. The
//! controller's job start and [`Computation::feed`] go through [`of`]
//! and name no kind.
//!
//! Architecture invariant: a kind's page-side behaviour lives in its own
//! module here; adding a kind means one module and one line in [`of`].

mod bif;
mod boundaries;
mod hbm;
mod lyap;
mod map;
mod omega;
mod orbits;
mod overlay;

use super::status::Dirty;
use super::{Computation, Fed};
use figures::protocol::{FromWorker, JobId, JobKind, JobSpec, KindSet, RunOptions, Target};
use figures::settings::{Settings, ViewOptions};
use figures::views::map::MapGrid;
use solver::model::Model;

/// What a job starts with: the target's settings and model, the map's
/// grid and what the map and its boundaries depend on, the pool.
pub struct StartCx<'a> {
    /// The target's settings (a member's: the current view, its parameters).
    pub settings: &'a Settings,
    /// The target's model.
    pub model: &'a Model,
    /// Whether the target is the current state.
    pub main: bool,
    /// The map's grid (the current state's view).
    pub grid: MapGrid,
    /// The plotted mesh (`None`: every mesh).
    pub mesh: Option<usize>,
    /// Everything the map depends on, as text.
    pub map_signature: String,
    /// Everything the map's boundaries depend on, as text.
    pub boundaries_signature: String,
    /// The pool (its size), with the long jobs that run beside this one.
    pub pool: Pool,
}

impl StartCx<'_> {
    /// The view options.
    pub fn view(&self) -> &ViewOptions {
        &self.settings.view
    }

    /// The periods of a steady state with `record_periods` recorded.
    pub fn run(&self, record_periods: u32) -> RunOptions {
        RunOptions {
            transient_periods: self.view().transient_periods,
            record_periods,
        }
    }
}

/// When and for what a reply is fed.
pub struct FeedCx {
    /// Now (ms).
    pub now_ms: f64,
    /// Where the frequency response starts (named when it fails before
    /// its first point).
    pub omega_from: f64,
}

/// The worker pool's placement rules.
#[derive(Debug, Clone, Copy)]
pub struct Pool {
    /// Workers in the pool (at least 1).
    pub size: usize,
    /// The long jobs ([`KindSet::LONG`]) of the current state that run, or
    /// start, beside the jobs being placed.
    pub long: KindSet,
}

impl Pool {
    /// The worker that runs the current state's harmonic-balance branch: the last.
    pub fn hbm_worker(self) -> usize {
        self.size - 1
    }

    /// The worker that runs A's harmonic-balance branch: the one before the
    /// last when the pool has more than two (so both branches compute at
    /// once), else the last.
    pub fn pinned_hbm_worker(self) -> usize {
        if self.size > 2 {
            self.size - 2
        } else {
            self.size - 1
        }
    }

    /// The worker of chain (or share) `shard`: chains are dealt round robin.
    pub fn shard_worker(self, shard: u32) -> usize {
        shard as usize % self.size
    }

    /// The workers no long job of [`Pool::long`] holds, in order. The
    /// map's rows go to these: on two cores the shooting branches of the
    /// compound set (about 4 s of a worker) and its map (about 4 s of CPU
    /// in all) then end together, where with the rows on both workers the
    /// branches began only after the first worker's rows and the other
    /// worker sat idle for the rest. When each holds one, every worker but
    /// the boundaries' (the longest job: on the compound set's default map
    /// two to three times the branches', begun only after its worker's
    /// other jobs), or every worker if that leaves none.
    pub fn free_workers(self) -> Vec<usize> {
        let alone = Pool {
            long: KindSet::NONE,
            ..self
        };
        let worker_of = |k: JobKind| of(k).worker(Target::Main, (0, 1), alone);
        let held: Vec<usize> = self.long.iter().map(worker_of).collect();
        let free: Vec<usize> = (0..self.size).filter(|w| !held.contains(w)).collect();
        if !free.is_empty() {
            return free;
        }
        let trace = self
            .long
            .contains(JobKind::Boundaries)
            .then(|| worker_of(JobKind::Boundaries));
        let rest: Vec<usize> = (0..self.size).filter(|w| Some(*w) != trace).collect();
        if rest.is_empty() {
            (0..self.size).collect()
        } else {
            rest
        }
    }
}

/// Where a kind's job status sits in the page's status JSON.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StatusKey {
    /// A top-level key, its progress beside it.
    Top(&'static str),
    /// The `job` of the object under this key.
    Job(&'static str),
}

/// One job kind's page side.
pub trait Kind: Sync {
    /// The kind.
    fn kind(&self) -> JobKind;

    /// The job's shards under `cx`; `None`: the kind is switched off (its
    /// store cleared, its running job dropped).
    fn shards(&self, cx: &StartCx) -> Option<u32>;

    /// Whether the running or finished job of the current state `main`
    /// still stands: what it depends on did not change.
    fn unchanged(&self, _cx: &StartCx, _main: &Computation) -> bool {
        false
    }

    /// The units of the job's progress.
    fn total(&self, cx: &StartCx) -> usize;

    /// Starts the kind's store in `c` for a new job of `total` units.
    fn begin(&self, c: &mut Computation, total: usize, cx: &StartCx);

    /// Clears the kind's store when it is switched off.
    fn clear(&self, _c: &mut Computation) {}

    /// The job of shard `shard` of `chains`.
    fn spec(&self, cx: &StartCx, chains: u32, shard: u32) -> JobSpec;

    /// The worker that runs `target`'s shard `shard` of `chains`: round
    /// robin unless the kind says otherwise.
    fn worker(&self, _target: Target, (shard, _chains): (u32, u32), pool: Pool) -> usize {
        pool.shard_worker(shard)
    }

    /// The other kinds whose views show this kind's data (marked changed
    /// with it).
    fn also_shown_as(&self) -> KindSet {
        KindSet::NONE
    }

    /// Where the tests and the benchmark read the job's status in the
    /// page's status JSON: a top-level key (with its progress beside it
    /// as `{key}_progress`), or the `job` of the object under that key.
    fn status_key(&self) -> StatusKey;

    /// Whether the current state's quick preview follows the job's start.
    fn previews(&self) -> bool {
        false
    }

    /// Whether a reply's `id` answers this kind's current job in `c` (a
    /// kind switched off or failed has id 0: nothing answers it).
    fn answers(&self, c: &Computation, id: JobId) -> bool {
        id != 0 && id == c.status(self.kind()).id
    }

    /// Feeds `msg` to the kind's store in `c` if it answers the kind's
    /// current job; marks the data changed in `dirty`, adds messages for
    /// the user to `fed`. Whether it did.
    fn feed(
        &self,
        c: &mut Computation,
        msg: &FromWorker,
        cx: &FeedCx,
        dirty: &mut Dirty,
        fed: &mut Fed,
    ) -> bool;
}

/// Every kind's page side, by [`JobKind::slot`]: the one table.
const KINDS: [&dyn Kind; JobKind::COUNT] = [
    &omega::Omega,
    &hbm::HarmonicBalance,
    &overlay::Overlay,
    &bif::Bif,
    &map::Map,
    &lyap::Lyap,
    &orbits::Orbits,
    &boundaries::Boundaries,
];

/// The page side of `kind`.
pub fn of(kind: JobKind) -> &'static dyn Kind {
    KINDS[kind.slot()]
}

/// Puts the job status of each of `kinds` in `c` where
/// [`Kind::status_key`] says, into the status JSON `out` (an object;
/// `Job` keys into the objects already there); with `now_ms`, each
/// top-level status's progress beside it.
pub fn put_statuses(
    out: &mut serde_json::Value,
    c: &Computation,
    kinds: KindSet,
    now_ms: Option<f64>,
) {
    let Some(o) = out.as_object_mut() else {
        return;
    };
    for kind in kinds.iter() {
        let st = c.status(kind);
        match of(kind).status_key() {
            StatusKey::Top(key) => {
                o.insert(key.into(), serde_json::json!(st));
                if let Some(now) = now_ms {
                    o.insert(
                        format!("{key}_progress"),
                        serde_json::json!(st.progress(now)),
                    );
                }
            }
            StatusKey::Job(key) => {
                if let Some(inner) = o.get_mut(key).and_then(|v| v.as_object_mut()) {
                    inner.insert("job".into(), serde_json::json!(st));
                }
            }
        }
    }
}

/// The most chains a sweep is split into (and the most workers the page runs).
pub const MAX_CHAINS: u32 = 8;
/// A continuation chain's fewest grid points (see [`chain_count`]).
pub const MIN_CHAIN_POINTS: u32 = 50;

/// Interleaved continuation chains of a sweep of `points` grid points:
/// one per [`MIN_CHAIN_POINTS`] points, at least 2 and at most
/// [`MAX_CHAINS`] (never more than the points). It depends on the points
/// only, never on the pool, so that each chain continues from the same
/// states and a sweep gives the same bits on any machine.
pub fn chain_count(points: u32) -> u32 {
    (points / MIN_CHAIN_POINTS)
        .clamp(2, MAX_CHAINS)
        .min(points)
        .max(1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_holds_each_kind_in_its_slot() {
        for kind in JobKind::ALL {
            assert_eq!(of(kind).kind(), kind);
        }
    }
}
