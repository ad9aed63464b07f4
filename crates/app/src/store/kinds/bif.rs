//! The bifurcation sweep ([`JobKind::Bif`]): steady states along
//! interleaved chains, in one or both directions, with the parametric
//! instability bands of its range; without an overlay job of its own the
//! frequency response shows its points as dots.

use super::{chain_count, FeedCx, Kind, StartCx, StatusKey};
use crate::store::status::{Dirty, JobStatus};
use crate::store::{Computation, Fed};
use figures::protocol::{FromWorker, JobKind, JobSpec, KindSet};
use figures::settings::ViewOptions;
use figures::views::bif::BifStore;

pub(super) struct Bif;

/// Steady states in a bifurcation sweep of view settings `v` (both
/// directions count twice).
fn bif_total(v: &ViewOptions) -> usize {
    let per_dir = if v.bif_dir == solver::sweep::Directions::Both {
        2
    } else {
        1
    };
    v.bif_points as usize * per_dir
}

impl Computation {
    /// The status of the bifurcation sweep's job.
    pub fn bif_status(&self) -> &JobStatus {
        self.status(JobKind::Bif)
    }
}

impl Kind for Bif {
    fn kind(&self) -> JobKind {
        JobKind::Bif
    }

    fn shards(&self, cx: &StartCx) -> Option<u32> {
        Some(chain_count(cx.view().bif_points))
    }

    fn status_key(&self) -> StatusKey {
        StatusKey::Top("bif")
    }

    fn total(&self, cx: &StartCx) -> usize {
        bif_total(cx.view())
    }

    fn begin(&self, c: &mut Computation, total: usize, _cx: &StartCx) {
        c.bif = BifStore::new(total);
    }

    fn spec(&self, cx: &StartCx, chains: u32, shard: u32) -> JobSpec {
        let v = cx.view();
        JobSpec::Bif {
            omega_from: v.omega_from,
            omega_to: v.omega_to,
            points: v.bif_points,
            directions: v.bif_dir.name().to_string(),
            chains,
            shard,
            run: cx.run(v.record_periods),
        }
    }

    /// The sweep's steady states are also the frequency response's dots.
    fn also_shown_as(&self) -> KindSet {
        JobKind::Overlay.set()
    }

    fn feed(
        &self,
        c: &mut Computation,
        msg: &FromWorker,
        cx: &FeedCx,
        dirty: &mut Dirty,
        fed: &mut Fed,
    ) -> bool {
        match msg {
            FromWorker::Bands { id, bands, error } if self.answers(c, *id) => {
                if *bands != c.bands {
                    c.bands = bands.clone();
                    dirty.data(JobKind::Bif);
                }
                if let Some(e) = error {
                    let msg = format!("Parametric-instability bands not computed: {e}");
                    c.status_mut(JobKind::Bif).issued.push(msg.clone());
                    fed.issues.push(msg);
                }
                true
            }
            FromWorker::BifPoints { id, points } if self.answers(c, *id) => {
                let before = c.bif.samples.len();
                c.bif.samples.extend(points.iter().cloned());
                let after = c.bif.samples.len();
                c.status_mut(JobKind::Bif).record(after, cx.now_ms);
                dirty.data(JobKind::Bif);
                // Without its own overlay job the frequency response shows
                // these as its dots: redrawn at each tenth of the sweep and
                // at its end, not per point (a frequency-response draw costs
                // more than a sweep point's message).
                let tenth = (c.bif.total / 10).max(1);
                let batch = before / tenth != after / tenth || after >= c.bif.total;
                if c.status(JobKind::Overlay).id == 0 && batch {
                    dirty.data(self.also_shown_as());
                }
                true
            }
            _ => false,
        }
    }
}
