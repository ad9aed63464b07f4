//! The workers' replies: a worker's readiness, then every reply fed to
//! every computation ([`Computation::feed`]: only the one whose job id it
//! carries takes it), failures into the messages, export shards to the
//! export being assembled; the jobs held at the page's start posted once
//! the first screen's have ended.

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
        let mut fx = match msg {
            FromWorker::Ready => {
                let Some(slot) = self.workers.get_mut(worker) else {
                    return Vec::new();
                };
                slot.ready = true;
                std::mem::take(&mut slot.queue)
                    .into_iter()
                    .map(|out| Effect::Post {
                        worker,
                        text: out.text,
                    })
                    .collect()
            }
            FromWorker::Export { id, text } => self.export_reply(worker, id, text, now_ms),
            msg => {
                let current = self.feed(&msg, now_ms);
                if let FromWorker::Failed { id, message } = msg {
                    let export = self.export.as_ref().is_some_and(|e| e.id == id);
                    if export {
                        self.export = None;
                    }
                    // A replaced job's failure speaks of a state gone by.
                    if current || export || id == 0 {
                        self.issue(message);
                    }
                }
                Vec::new()
            }
        };
        fx.extend(self.release_if_first_screen_ended(now_ms));
        fx
    }

    /// Feeds a reply to every computation; the current state's messages
    /// (a failed branch, bands not computed) join the page's. Whether a
    /// computation's current job took it.
    fn feed(&mut self, msg: &FromWorker, now_ms: f64) -> bool {
        let omega_from = self.settings.view.omega_from;
        for target in self.targets() {
            let mut dirty = self.dirty;
            let Some(c) = self.computation_mut(target) else {
                continue;
            };
            let fed = c.feed(msg, now_ms, omega_from, &mut dirty);
            self.dirty = dirty;
            if target == Target::Main {
                for issue in fed.issues {
                    self.issue(issue);
                }
            }
            if fed.matched {
                return true;
            }
        }
        false
    }
}
