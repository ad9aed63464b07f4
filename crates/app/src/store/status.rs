//! What the page knows about its jobs between frames: each job's progress
//! and timing ([`JobStatus`]) and whose data changed ([`Dirty`]). The
//! controller writes both; the redraw scheduler and the captions read them.

use figures::protocol::{JobId, KindSet};

/// Jobs shorter than this show no progress indicator (ms).
pub const PROGRESS_AFTER_MS: f64 = 200.0;

/// Progress and timing of the current job of one kind.
#[derive(Debug, Clone, PartialEq, Default, serde::Serialize)]
pub struct JobStatus {
    /// Current job id (0: none yet).
    pub id: JobId,
    /// When it was started (ms, the page's clock).
    pub started_ms: f64,
    /// When its messages were posted: at its start, or, for a job held at
    /// the page's start (`Controller::hold_off_screen`), at its release;
    /// `None` while it is held. What "from job start" counts from.
    pub posted_ms: Option<f64>,
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
    /// The messages this job added to the page's (its failure, a partial
    /// branch): taken back when the job is replaced, so the messages
    /// speak of the state on screen.
    #[serde(skip)]
    pub issued: Vec<String>,
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
            posted_ms: Some(now_ms),
            total,
            ..JobStatus::default()
        }
    }
}

/// What changed since the last frame: whose data (a set of job kinds;
/// each view redraws when a kind it shows is in it, see
/// `views::ViewSpec::shows`), the controls, the link and the messages.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Dirty {
    /// The kinds whose data (or whose views' axes) changed.
    pub jobs: KindSet,
    /// Control values (after a link, preset or reset).
    pub controls: bool,
    /// The URL.
    pub url: bool,
    /// The messages area.
    pub messages: bool,
}

impl Dirty {
    /// Everything: a new page state (a link, a preset, a reset).
    pub fn all() -> Self {
        Dirty {
            jobs: KindSet::ALL,
            controls: true,
            url: true,
            messages: true,
        }
    }

    /// Marks `kinds`' data as changed.
    pub fn data(&mut self, kinds: impl Into<KindSet>) {
        self.jobs = self.jobs.with(kinds.into());
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

    /// The map's caption status: the cells computed while it runs.
    pub fn map_caption_suffix(&self) -> String {
        if self.running() {
            format!(" (computing {}/{} cells)", self.done, self.total)
        } else {
            String::new()
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
