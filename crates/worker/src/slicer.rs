//! When a Web Worker yields: it computes in slices of about
//! [`SLICE_MS`], yielding to its event loop after each so that newer jobs
//! and cancels arrive, and after [`PAUSE_EVERY_MS`] of work it pauses
//! [`SLICE_PAUSE_MS`] on a timer: on two cores, two busy workers otherwise
//! leave the page's main thread too little CPU to draw within 100 ms.
//! `web/worker.rs` keeps the clock and the event loop; this decides, and
//! keeps one wake at most on its way.

/// A worker's time slice (ms) before it yields to its event loop.
pub const SLICE_MS: f64 = 25.0;
/// The pause (ms) after [`PAUSE_EVERY_MS`] of work.
pub const SLICE_PAUSE_MS: i32 = 3;
/// Work (ms) between two pauses.
pub const PAUSE_EVERY_MS: f64 = 100.0;

/// What a worker does after a slice.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Next {
    /// No work left: wait for a message.
    Idle,
    /// Go on at once after the event loop (an unclamped channel message).
    Yield,
    /// Go on after a [`SLICE_PAUSE_MS`] timer.
    Pause,
}

/// The work done since the last pause, and whether a wake (a channel
/// message or a timer) is on its way.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Slicer {
    busy_ms: f64,
    waking: bool,
}

impl Slicer {
    /// Whether a slice begun `elapsed_ms` ago is over.
    pub fn over(elapsed_ms: f64) -> bool {
        elapsed_ms > SLICE_MS
    }

    /// One slice: `step` (one step of work, its replies posted; whether
    /// work is left) until no work is left or the slice is over by
    /// `clock` (ms), then what to do next.
    pub fn slice(&mut self, clock: impl Fn() -> f64, mut step: impl FnMut() -> bool) -> Next {
        let start = clock();
        let mut has_work = step();
        while has_work && !Self::over(clock() - start) {
            has_work = step();
        }
        self.after(clock() - start, has_work)
    }

    /// A page's message was handled (`has_work`: work is waiting): the wake
    /// to arrange, if none is on its way ([`Slicer::wake`]).
    pub fn after_message(&mut self, has_work: bool) -> Option<Next> {
        self.wake(if has_work { Next::Yield } else { Next::Idle })
    }

    /// A wake arrived: one slice ([`Slicer::slice`]), then the next wake
    /// to arrange.
    pub fn woke(&mut self, clock: impl Fn() -> f64, step: impl FnMut() -> bool) -> Option<Next> {
        self.waking = false;
        let next = self.slice(clock, step);
        self.wake(next)
    }

    /// The wake to arrange for `next` (a channel message to go on at once,
    /// a timer for a pause), noted as on its way; none while one is on its
    /// way already, or when no work is left.
    fn wake(&mut self, next: Next) -> Option<Next> {
        if next == Next::Idle || self.waking {
            return None;
        }
        self.waking = true;
        Some(next)
    }

    /// After a slice of `elapsed_ms`, with work left or not.
    pub fn after(&mut self, elapsed_ms: f64, has_work: bool) -> Next {
        if !has_work {
            self.busy_ms = 0.0;
            return Next::Idle;
        }
        self.busy_ms += elapsed_ms;
        if self.busy_ms > PAUSE_EVERY_MS {
            self.busy_ms = 0.0;
            Next::Pause
        } else {
            Next::Yield
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_busy_worker_pauses_once_per_hundred_ms_of_work_and_idles_without_work() {
        let mut s = Slicer::default();
        assert!(!Slicer::over(SLICE_MS) && Slicer::over(SLICE_MS + 1.0));
        // Four slices of 26 ms: the fourth passes 100 ms and pauses.
        let next: Vec<Next> = (0..5).map(|_| s.after(26.0, true)).collect();
        use Next::*;
        assert_eq!(next, [Yield, Yield, Yield, Pause, Yield]);
        assert_eq!(s.after(10.0, false), Idle);
        // Idle resets the count.
        assert_eq!(s.after(90.0, true), Yield);
    }

    #[test]
    fn a_slice_steps_until_its_time_is_over_or_the_work_is_done() {
        use std::cell::Cell;
        let now = Cell::new(0.0);
        let (mut s, mut steps) = (Slicer::default(), 0);
        // Steps of 10 ms with work enough: past SLICE_MS after three.
        let next = s.slice(
            || now.get(),
            || {
                steps += 1;
                now.set(now.get() + 10.0);
                true
            },
        );
        assert_eq!(
            (next, steps),
            (Next::Yield, (SLICE_MS / 10.0).floor() as u32 + 1)
        );
        // The last step ends the work: idle at once.
        let mut left = 2;
        let next = s.slice(
            || now.get(),
            || {
                left -= 1;
                left > 0
            },
        );
        assert_eq!((next, left), (Next::Idle, 0));
    }

    /// Messages arriving while a wake is on its way arrange none; the wake
    /// arranges the next, a pause's timer after 100 ms of work; a slice
    /// that ends the work arranges none, and the next message wakes again.
    #[test]
    fn one_wake_at_most_is_on_its_way() {
        use std::cell::Cell;
        let now = Cell::new(0.0);
        let mut s = Slicer::default();
        assert_eq!(s.after_message(false), None);
        assert_eq!(s.after_message(true), Some(Next::Yield));
        assert_eq!(s.after_message(true), None);
        // Slices of 30 ms (three steps of 10 ms) with work left.
        let mut step = || {
            now.set(now.get() + 10.0);
            true
        };
        let wakes: Vec<_> = (0..4).map(|_| s.woke(|| now.get(), &mut step)).collect();
        use Next::*;
        assert_eq!(wakes, [Some(Yield), Some(Yield), Some(Yield), Some(Pause)]);
        assert_eq!(s.after_message(true), None);
        assert_eq!(s.woke(|| now.get(), || false), None);
        assert_eq!(s.after_message(true), Some(Yield));
    }
}
