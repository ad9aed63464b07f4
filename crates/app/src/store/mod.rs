//! What the page holds of its computations: one [`Computation`] (every
//! job kind's data store and status) for the current state, one for the
//! pinned state A, one per family member; and one [`Computation::feed`]
//! by which every worker reply reaches its store.
//!
//! Architecture invariant: a reply reaches a store only through
//! [`Computation::feed`], and only the store whose current job id it
//! carries (ids are unique across all computations).

pub mod status;

use figures::protocol::{FromWorker, JobKind, OmegaResult};
use figures::views::bif::BifStore;
use figures::views::boundaries::BoundaryStore;
use figures::views::fr::{FrStore, HbmStore};
use figures::views::lyap::LyapStore;
use figures::views::map::MapStore;
use figures::views::orbits::OrbitStore;
use status::{Dirty, JobStatus};

/// One state's results: a store and a status per job kind. The pinned A
/// computes the harmonic balance and the sweep, a family member also the
/// selected Omega; the other stores then stay empty.
#[derive(Debug, Clone, Default)]
pub struct Computation {
    /// The harmonic-balance branch ([`JobKind::HarmonicBalance`]).
    pub hbm: HbmStore,
    /// The last complete branch, shown faded while a new one computes.
    pub hbm_previous: Option<HbmStore>,
    /// The time-integration overlay's points ([`JobKind::Overlay`]; id 0: off).
    pub overlay: FrStore,
    /// The bifurcation sweep's points ([`JobKind::Bif`]).
    pub bif: BifStore,
    /// The parametric-instability bands of the sweep's range, from its
    /// shard-0 worker (kept until a newer sweep's arrive).
    pub bands: Vec<(f64, f64)>,
    /// The latest selected-Omega result ([`JobKind::Omega`]; possibly an
    /// older job's while a new one runs).
    pub omega: Option<OmegaResult>,
    /// The impact-regime map's cells ([`JobKind::Map`]).
    pub map: MapStore,
    /// The Lyapunov curve's points ([`JobKind::Lyap`]).
    pub lyap: LyapStore,
    /// The shooting branches' points ([`JobKind::Orbits`]; id 0: off).
    pub orbits: OrbitStore,
    /// The map's traced boundaries ([`JobKind::Boundaries`]; id 0: off).
    pub boundaries: BoundaryStore,
    /// Each kind's job status, by [`JobKind::slot`].
    status: [JobStatus; JobKind::COUNT],
}

/// What a reply did that the controller acts on beyond the stores.
#[derive(Debug, Default, PartialEq)]
pub struct Fed {
    /// Messages for the user.
    pub issues: Vec<String>,
    /// Whether it answered one of this computation's jobs.
    pub matched: bool,
}

impl Computation {
    /// The status of the job of `kind`.
    pub fn status(&self, kind: JobKind) -> &JobStatus {
        &self.status[kind.slot()]
    }

    /// The status of the job of `kind`, to change.
    pub fn status_mut(&mut self, kind: JobKind) -> &mut JobStatus {
        &mut self.status[kind.slot()]
    }

    /// Whether any job of `kinds` is running.
    pub fn running(&self, kinds: &[JobKind]) -> bool {
        kinds.iter().any(|k| self.status(*k).running())
    }

    /// Every job failing with `e` (a model that cannot be built).
    pub fn fail_all(&mut self, kinds: &[JobKind], e: &str) {
        for k in kinds {
            *self.status_mut(*k) = JobStatus {
                error: Some(e.to_string()),
                ..JobStatus::default()
            };
        }
    }

    /// Feeds `msg` to the store whose job it answers (ids 0 and other
    /// computations' are ignored), at `now_ms`, and marks the kinds whose
    /// data changed in `dirty`. `omega_from` is where the branch starts
    /// (named when it fails before its first point).
    pub fn feed(
        &mut self,
        msg: &FromWorker,
        now_ms: f64,
        omega_from: f64,
        dirty: &mut Dirty,
    ) -> Fed {
        let mut fed = Fed::default();
        let ours = |id: u64, mine: u64| id == mine && id != 0;
        match msg {
            FromWorker::HbmPoints {
                id,
                points,
                progress,
                finished,
                error,
                notes,
            } if ours(*id, self.hbm.id) => {
                self.hbm
                    .add(points.clone(), *progress, *finished, error.clone());
                if !notes.is_empty() {
                    self.hbm.notes = notes.clone();
                }
                let st = &mut self.status[JobKind::HarmonicBalance.slot()];
                st.done = (100.0 * self.hbm.progress).floor() as usize;
                if !self.hbm.points.is_empty() {
                    st.first_data_ms.get_or_insert(now_ms);
                }
                if *finished {
                    st.finished_ms = Some(now_ms);
                }
                if self.hbm.is_complete() {
                    self.hbm_previous = None;
                }
                if let Some(e) = error {
                    let at = self.hbm.points.last().map_or(omega_from, |p| p.omega);
                    let msg = format!(
                        "The frequency response stops at Ω {}: {e} The branch shown is partial.",
                        figures::words::short(at)
                    );
                    st.error = Some(msg.clone());
                    st.issued.push(msg.clone());
                    fed.issues.push(msg);
                }
                dirty.data(JobKind::HarmonicBalance);
                fed.matched = true;
            }
            FromWorker::OverlayPoints { id, points } if ours(*id, self.overlay.id) => {
                self.overlay.add(points.clone());
                let done = self.overlay.done();
                self.status_mut(JobKind::Overlay).record(done, now_ms);
                dirty.data(JobKind::Overlay);
                fed.matched = true;
            }
            FromWorker::Bands { id, bands, error } if ours(*id, self.bif.id) => {
                if *bands != self.bands {
                    self.bands = bands.clone();
                    dirty.data(JobKind::Bif);
                }
                if let Some(e) = error {
                    let msg = format!("Parametric-instability bands not computed: {e}");
                    self.status_mut(JobKind::Bif).issued.push(msg.clone());
                    fed.issues.push(msg);
                }
                fed.matched = true;
            }
            FromWorker::BifPoints { id, points } if ours(*id, self.bif.id) => {
                let before = self.bif.samples.len();
                self.bif.samples.extend(points.iter().cloned());
                let after = self.bif.samples.len();
                self.status_mut(JobKind::Bif).record(after, now_ms);
                dirty.data(JobKind::Bif);
                // Without its own overlay job the frequency response shows
                // these as its dots: redrawn at each tenth of the sweep and
                // at its end, not per point (a frequency-response draw costs
                // more than a sweep point's message).
                let tenth = (self.bif.total / 10).max(1);
                let batch = before / tenth != after / tenth || after >= self.bif.total;
                if self.overlay.id == 0 && batch {
                    dirty.data(JobKind::Overlay);
                }
                fed.matched = true;
            }
            FromWorker::MapCells { id, cells } if ours(*id, self.map.id) => {
                self.map.add(cells.clone());
                let done = self.map.done;
                self.status_mut(JobKind::Map).record(done, now_ms);
                dirty.data(JobKind::Map);
                fed.matched = true;
            }
            FromWorker::LyapPoints { id, points } if ours(*id, self.lyap.id) => {
                self.lyap.points.extend(points.iter().cloned());
                let done = self.lyap.points.len();
                self.status_mut(JobKind::Lyap).record(done, now_ms);
                dirty.data(JobKind::Lyap);
                fed.matched = true;
            }
            FromWorker::OrbitPoints {
                id,
                points,
                finished,
                error,
            } if ours(*id, self.orbits.id) => {
                self.orbits.points.extend(points.iter().cloned());
                self.orbits.finished = *finished;
                let done = self.orbits.points.len();
                let st = self.status_mut(JobKind::Orbits);
                st.record(done, now_ms);
                if *finished {
                    st.finished_ms = Some(now_ms);
                }
                if let Some(e) = error {
                    let msg =
                        format!("The shooting branches stop: {e} The branches drawn are partial.");
                    st.issued.push(msg.clone());
                    self.orbits.error = Some(msg.clone());
                    fed.issues.push(msg);
                }
                dirty.data(JobKind::Orbits);
                fed.matched = true;
            }
            FromWorker::BoundaryCurves {
                id,
                curves,
                cusps,
                notes,
                permille,
                finished,
            } if ours(*id, self.boundaries.id) => {
                let b = &mut self.boundaries;
                b.curves.extend(curves.iter().cloned());
                b.cusps.clone_from(cusps);
                b.notes.extend(notes.iter().cloned());
                b.finished = *finished;
                let st = self.status_mut(JobKind::Boundaries);
                st.record(*permille, now_ms);
                if *finished {
                    st.finished_ms = Some(now_ms);
                }
                dirty.data(JobKind::Boundaries);
                fed.matched = true;
            }
            FromWorker::Omega { id, result } if ours(*id, self.status(JobKind::Omega).id) => {
                self.omega = Some((**result).clone());
                let st = self.status_mut(JobKind::Omega);
                st.done = 1;
                st.first_data_ms = Some(now_ms);
                st.finished_ms = Some(now_ms);
                dirty.data(JobKind::Omega);
                fed.matched = true;
            }
            FromWorker::Failed { id, message } if *id != 0 => {
                for kind in JobKind::ALL {
                    let st = self.status_mut(kind);
                    if st.id == *id {
                        st.error = Some(message.clone());
                        st.issued.push(message.clone());
                        dirty.data(kind);
                        fed.matched = true;
                    }
                }
            }
            // Progress and Done of current jobs are implied by the data;
            // stale replies are dropped.
            _ => {}
        }
        fed
    }
}

#[cfg(test)]
mod tests;
