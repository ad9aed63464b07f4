//! What the page knows about its jobs and views between frames: each
//! job's progress and timing ([`JobStatus`]) and which views' data changed
//! ([`Dirty`]). The controller writes both; the redraw scheduler and the
//! captions read them.

use crate::protocol::JobId;

/// Jobs shorter than this show no progress indicator (ms).
pub const PROGRESS_AFTER_MS: f64 = 200.0;

/// Progress and timing of the current job of one kind.
#[derive(Debug, Clone, PartialEq, Default, serde::Serialize)]
pub struct JobStatus {
    /// Current job id (0: none yet).
    pub id: JobId,
    /// When it was started (ms, the page's clock).
    pub started_ms: f64,
    /// When its first data arrived.
    pub first_data_ms: Option<f64>,
    /// When it finished.
    pub finished_ms: Option<f64>,
    /// Units done.
    pub done: usize,
    /// Units in all.
    pub total: usize,
    /// Why it failed, if it did.
    pub error: Option<String>,
    /// When the page's own preview of this job's result was shown (the
    /// selected-Omega job only).
    pub preview_ms: Option<f64>,
}

impl JobStatus {
    /// Whether it is still running.
    pub fn running(&self) -> bool {
        self.id != 0 && self.finished_ms.is_none() && self.error.is_none()
    }

    /// Progress to show at time `now_ms` (`None` for quick or finished jobs).
    pub fn progress(&self, now_ms: f64) -> Option<(usize, usize)> {
        (self.running() && now_ms - self.started_ms > PROGRESS_AFTER_MS)
            .then_some((self.done, self.total))
    }

    pub(crate) fn start(id: JobId, now_ms: f64, total: usize) -> Self {
        JobStatus {
            id,
            started_ms: now_ms,
            total,
            ..JobStatus::default()
        }
    }
}

/// Which views need drawing.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Dirty {
    /// Frequency response.
    pub fr: bool,
    /// Bifurcation diagram.
    pub bif: bool,
    /// Views 3–6 and the summary.
    pub omega: bool,
    /// Control values (after a link, preset or reset).
    pub controls: bool,
    /// The URL.
    pub url: bool,
    /// The messages area.
    pub messages: bool,
    /// The impact-regime map.
    pub map: bool,
    /// The Lyapunov curve.
    pub lyap: bool,
}

impl Dirty {
    /// Everything: a new page state (a link, a preset, a reset).
    pub fn all() -> Self {
        Dirty {
            fr: true,
            bif: true,
            omega: true,
            controls: true,
            url: true,
            messages: true,
            map: true,
            lyap: true,
        }
    }
}

impl JobStatus {
    /// Records `done` units at `now_ms`: the first data's time, and the
    /// finish once every unit is done.
    pub fn record(&mut self, done: usize, now_ms: f64) {
        self.done = done;
        self.first_data_ms.get_or_insert(now_ms);
        if done >= self.total {
            self.finished_ms = Some(now_ms);
        }
    }

    /// The caption's status: failed, or computing with its count.
    pub fn caption_suffix(&self) -> String {
        if self.error.is_some() {
            " (failed)".into()
        } else if self.running() {
            format!(" (computing {}/{})", self.done, self.total)
        } else {
            String::new()
        }
    }
}
