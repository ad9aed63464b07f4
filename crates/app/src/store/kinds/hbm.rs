//! The harmonic-balance branch of the frequency response
//! ([`JobKind::HarmonicBalance`]): one continuation on one worker, its
//! progress in per cent; the current state's last complete branch fades
//! under the new one while it computes.

use super::{FeedCx, Kind, Pool, StartCx, StatusKey};
use crate::store::status::{Dirty, JobStatus};
use crate::store::{Computation, Fed};
use figures::protocol::{FromWorker, JobKind, JobSpec, Target};
use figures::views::fr::HbmStore;

pub(super) struct HarmonicBalance;

impl Computation {
    /// The status of the harmonic-balance branch's job.
    pub fn hbm_status(&self) -> &JobStatus {
        self.status(JobKind::HarmonicBalance)
    }
}

impl Kind for HarmonicBalance {
    fn kind(&self) -> JobKind {
        JobKind::HarmonicBalance
    }

    fn shards(&self, _cx: &StartCx) -> Option<u32> {
        Some(1)
    }

    fn status_key(&self) -> StatusKey {
        StatusKey::Top("fr")
    }

    fn total(&self, _cx: &StartCx) -> usize {
        100
    }

    fn begin(&self, c: &mut Computation, _total: usize, cx: &StartCx) {
        // Keep the last complete branch (not a half-computed one) to fade
        // under the new one while it computes.
        if cx.main && c.hbm.is_complete() {
            c.hbm_previous = Some(std::mem::take(&mut c.hbm));
        }
        c.hbm = HbmStore::new(cx.view().harmonics);
    }

    fn spec(&self, cx: &StartCx, _chains: u32, _shard: u32) -> JobSpec {
        let v = cx.view();
        JobSpec::HarmonicBalance {
            omega_from: v.omega_from,
            omega_to: v.omega_to,
            points: v.fr_points,
            harmonics: v.harmonics,
            stability: true,
        }
    }

    /// The current state's branch on the last worker, A's beside it, the
    /// members' spread from there.
    fn worker(&self, target: Target, _shard: (u32, u32), pool: Pool) -> usize {
        match target {
            Target::Main => pool.hbm_worker(),
            Target::A => pool.pinned_hbm_worker(),
            Target::Member(m) => (pool.hbm_worker() + m as usize) % pool.size,
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
        let FromWorker::HbmPoints {
            id,
            points,
            progress,
            finished,
            error,
            notes,
        } = msg
        else {
            return false;
        };
        if !self.answers(c, *id) {
            return false;
        }
        c.hbm
            .add(points.clone(), *progress, *finished, error.clone());
        if !notes.is_empty() {
            c.hbm.notes = notes.clone();
        }
        let done = (100.0 * c.hbm.progress).floor() as usize;
        let has_points = !c.hbm.points.is_empty();
        let at = c.hbm.points.last().map_or(cx.omega_from, |p| p.omega);
        if c.hbm.is_complete() {
            c.hbm_previous = None;
        }
        let st = c.status_mut(JobKind::HarmonicBalance);
        st.done = done;
        if has_points {
            st.first_data_ms.get_or_insert(cx.now_ms);
        }
        if *finished {
            st.finished_ms = Some(cx.now_ms);
        }
        if let Some(e) = error {
            let msg = format!(
                "The frequency response stops at Ω {}: {e} The branch shown is partial.",
                figures::words::short(at)
            );
            st.error = Some(msg.clone());
            st.issued.push(msg.clone());
            fed.issues.push(msg);
        }
        dirty.data(JobKind::HarmonicBalance);
        true
    }
}
