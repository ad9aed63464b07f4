//! The workers' replies: each job's data into its store, its status, and
//! failures into the messages.

use super::*;

impl Controller {
    /// Handles a message from worker `worker`.
    pub fn worker_message(&mut self, worker: usize, text: &str, now_ms: f64) -> Vec<Effect> {
        let msg: FromWorker = match serde_json::from_str(text) {
            Ok(m) => m,
            Err(e) => {
                self.issue(format!("unreadable worker message: {e}"));
                return Vec::new();
            }
        };
        self.pinned_message(&msg, now_ms);
        self.family_message(&msg, now_ms);
        match msg {
            FromWorker::Ready => {
                let Some(slot) = self.workers.get_mut(worker) else {
                    return Vec::new();
                };
                slot.ready = true;
                std::mem::take(&mut slot.queue)
                    .into_iter()
                    .map(|text| Effect::Post { worker, text })
                    .collect()
            }
            FromWorker::HbmPoints {
                id,
                points,
                progress,
                finished,
                error,
                notes,
            } if id == self.hbm.id && id != 0 => {
                let failure = error.clone();
                self.hbm.add(points, progress, finished, error);
                if !notes.is_empty() {
                    self.hbm.notes = notes;
                }
                let st = &mut self.fr_status;
                st.done = (100.0 * self.hbm.progress).floor() as usize;
                if !self.hbm.points.is_empty() {
                    st.first_data_ms.get_or_insert(now_ms);
                }
                if finished {
                    st.finished_ms = Some(now_ms);
                }
                if self.hbm.is_complete() {
                    self.hbm_previous = None;
                }
                if let Some(e) = failure {
                    let at = self
                        .hbm
                        .points
                        .last()
                        .map_or(self.settings.view.omega_from, |p| p.omega);
                    let msg = format!(
                        "{HBM_FAILURE} after Omega = {at:.4} ({e}); the branch shown is partial"
                    );
                    self.fr_status.error = Some(msg.clone());
                    self.issue(msg);
                }
                self.dirty.fr = true;
                Vec::new()
            }
            FromWorker::FrPoints { id, points } if id == self.fr.id && id != 0 => {
                self.fr.add(points);
                self.ti_status.record(self.fr.done(), now_ms);
                self.dirty.fr = true;
                Vec::new()
            }
            FromWorker::Bands { id, bands, error } if id == self.bif.id => {
                if bands != self.bands {
                    self.bands = bands;
                    self.dirty.bif = true;
                }
                if let Some(e) = error {
                    self.issue(format!("Parametric-instability bands not computed: {e}"));
                }
                Vec::new()
            }
            FromWorker::BifPoints { id, points } if id == self.bif.id => {
                let before = self.bif.samples.len();
                self.bif.samples.extend(points);
                let after = self.bif.samples.len();
                self.bif_status.record(after, now_ms);
                self.dirty.bif = true;
                // Without its own overlay job the frequency response shows
                // these: redrawn at each tenth of the sweep and at its end,
                // not per point (a frequency-response draw costs more than a
                // sweep point's message).
                let tenth = (self.bif.total / 10).max(1);
                let batch = before / tenth != after / tenth || after >= self.bif.total;
                self.dirty.fr |= self.fr.id == 0 && batch;
                Vec::new()
            }
            FromWorker::MapCells { id, cells } if id == self.map.id && id != 0 => {
                self.map.add(cells);
                self.map_status.record(self.map.done, now_ms);
                self.dirty.map = true;
                Vec::new()
            }
            FromWorker::LyapPoints { id, points } if id == self.lyap.id && id != 0 => {
                self.lyap.points.extend(points);
                self.lyap_status.record(self.lyap.points.len(), now_ms);
                self.dirty.lyap = true;
                Vec::new()
            }
            FromWorker::Omega { id, result } if id == self.omega_status.id => {
                self.omega = Some(*result);
                self.omega_status.done = 1;
                self.omega_status.first_data_ms = Some(now_ms);
                self.omega_status.finished_ms = Some(now_ms);
                self.dirty.omega = true;
                Vec::new()
            }
            FromWorker::Failed { id, message } => {
                for kind in JobKind::ALL {
                    let st = self.status_mut(kind);
                    if st.id == id && id != 0 {
                        st.error = Some(message.clone());
                    }
                }
                self.dirty.fr = true;
                self.dirty.bif = true;
                self.dirty.omega = true;
                self.dirty.map = true;
                self.dirty.lyap = true;
                if self.export.as_ref().is_some_and(|e| e.id == id) {
                    self.export = None;
                }
                self.issue(message);
                Vec::new()
            }
            FromWorker::Export { id, text } => self.export_reply(worker, id, text),
            // Progress and Done of current jobs are implied by the data; stale replies are dropped.
            _ => Vec::new(),
        }
    }
}
