//! The one path by which the workers' replies reach a computation beside
//! the current state's — the pinned state A's or a family member's: its
//! branch, its sweep and (a member's) its selected-Ω run, by job id.

use super::*;

/// The stores and statuses of one side computation.
pub(super) struct Side<'a> {
    /// Its harmonic-balance branch and that job's status.
    pub(super) hbm: (&'a mut HbmStore, &'a mut JobStatus),
    /// Its bifurcation points and that job's status.
    pub(super) bif: (&'a mut BifStore, &'a mut JobStatus),
    /// Its selected-Ω result and that job's status, if it has one (A has none).
    pub(super) omega: Option<(&'a mut Option<OmegaResult>, &'a mut JobStatus)>,
}

impl Side<'_> {
    /// Feeds `msg` to the store whose job it answers (ids 0 and others'
    /// are ignored) and marks the views it changes in `dirty`.
    pub(super) fn feed(self, msg: &FromWorker, now_ms: f64, dirty: &mut Dirty) {
        let (hbm, fr_status) = self.hbm;
        let (bif, bif_status) = self.bif;
        match msg {
            FromWorker::HbmPoints {
                id,
                points,
                progress,
                finished,
                error,
                ..
            } if *id == hbm.id && *id != 0 => {
                hbm.add(points.clone(), *progress, *finished, error.clone());
                fr_status.done = (100.0 * hbm.progress).floor() as usize;
                if *finished {
                    fr_status.finished_ms = Some(now_ms);
                }
                if error.is_some() {
                    fr_status.error = error.clone();
                }
                dirty.fr = true;
            }
            FromWorker::BifPoints { id, points } if *id == bif.id && *id != 0 => {
                bif.samples.extend(points.iter().cloned());
                bif_status.record(bif.samples.len(), now_ms);
                dirty.bif = true;
            }
            FromWorker::Omega { id, result } => {
                if let Some((omega, st)) = self.omega.filter(|(_, st)| st.id == *id && *id != 0) {
                    *omega = Some((**result).clone());
                    st.done = 1;
                    st.first_data_ms = Some(now_ms);
                    st.finished_ms = Some(now_ms);
                    dirty.omega = true;
                }
            }
            FromWorker::Failed { id, message } if *id != 0 => {
                let omega_status = self.omega.map(|(_, st)| st);
                for st in [Some(fr_status), Some(bif_status), omega_status]
                    .into_iter()
                    .flatten()
                {
                    if st.id == *id {
                        st.error = Some(message.clone());
                        dirty.fr = true;
                        dirty.bif = true;
                        dirty.omega = true;
                    }
                }
            }
            _ => {}
        }
    }
}
