//! The redraw scheduler: which views to draw in this animation frame, as a
//! pure type fed with the page's clock (`now_ms`), so it is tested natively.
//!
//! A change marks views as needed ([`Redraw::mark`]); each frame the page
//! walks [`figures::views::DRAW_ORDER`] and asks [`Redraw::decide`] per view: draw it, skip
//! it for now (a running sweep's view is redrawn at most every
//! [`RUNNING_REDRAW_MS`], though a new job's start and its first points show
//! at once), or stop (the frame's budget [`FRAME_BUDGET_MS`] is spent; the
//! rest waits for the next frame). It also keeps the per-view counters the
//! tests' status reports.

use crate::store::status::{Dirty, JobStatus};
use figures::views::{ViewId, VIEWS};

/// Main-thread time after which a frame starts no further view (ms): a
/// full refresh spreads over a few frames instead of blocking one. (Drawing
/// the frequency response and the phase portrait in one frame regardless
/// was tried: with both workers busy such frames reached 100 ms.)
pub const FRAME_BUDGET_MS: f64 = 8.0;
/// While a sweep is still running its view is redrawn at most this often (ms).
pub const RUNNING_REDRAW_MS: f64 = 250.0;

const N: usize = VIEWS.len();

/// What to do with a view in this frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Decision {
    /// Draw it now.
    Draw,
    /// Not now (not needed, or throttled while its job runs).
    Skip,
    /// The frame's budget is spent: draw nothing more in this frame.
    Stop,
}

/// Which views need drawing, and what the drawing took.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Redraw {
    need: [bool; N],
    /// Draws per view.
    pub draws: [u32; N],
    /// When each view was last drawn (ms).
    pub last_draw_ms: [f64; N],
    /// The longest draw per view (ms).
    pub max_draw_ms: [f64; N],
    /// When each view was first drawn (ms, 0 before).
    pub first_draw_ms: [f64; N],
    /// Draws per progressive view while its job ran with some of its
    /// points in: the partial pictures a user saw.
    pub partial_draws: [u32; N],
    /// The next part of a view drawn in parts, one a frame (0: it starts
    /// over, clearing its canvas).
    part: [usize; N],
}

impl Redraw {
    /// Marks the views that show a kind whose data `dirty` says changed.
    pub fn mark(&mut self, dirty: &Dirty) {
        for spec in VIEWS {
            if !spec.shows.and(dirty.jobs).is_empty() {
                self.mark_view(spec.id);
            }
        }
    }

    /// Marks `view` for drawing from its first part (its data changed, or
    /// its canvas changed size: present mode).
    pub fn mark_view(&mut self, view: ViewId) {
        self.need[view.slot()] = true;
        self.part[view.slot()] = 0;
    }

    /// The part of `view` to draw next, when it draws in parts.
    pub fn part(&self, view: ViewId) -> usize {
        self.part[view.slot()]
    }

    /// Whether a view still waits for a frame.
    pub fn pending(&self) -> bool {
        self.need.iter().any(|&n| n)
    }

    /// Whether `view` waits to be drawn.
    pub fn needs(&self, view: ViewId) -> bool {
        self.need[view.slot()]
    }

    /// Whether to draw `view` at `now_ms` in a frame that started at
    /// `frame_ms`; `status` is the view's job when it streams points. A
    /// [`Decision::Draw`] clears the need: call [`Self::drawn`] after.
    pub fn decide(
        &mut self,
        view: ViewId,
        frame_ms: f64,
        now_ms: f64,
        status: Option<&JobStatus>,
    ) -> Decision {
        let k = view.slot();
        if !self.need[k] {
            return Decision::Skip;
        }
        if now_ms - frame_ms > FRAME_BUDGET_MS {
            return Decision::Stop;
        }
        let status = status.filter(|_| view.spec().progressive);
        let running = status.is_some_and(JobStatus::running);
        // Progressive views: throttle redraws while points stream in, but
        // show a new job's start (the new settings) and its first points
        // at once.
        let last = self.last_draw_ms[k];
        let fresh = status
            .is_some_and(|s| s.started_ms > last || s.first_data_ms.is_some_and(|t| t > last));
        if running && !fresh && self.draws[k] > 0 && now_ms - last < RUNNING_REDRAW_MS {
            return Decision::Skip;
        }
        self.need[k] = false;
        if running && status.is_some_and(|s| s.done > 0) {
            self.partial_draws[k] += 1;
        }
        Decision::Draw
    }

    /// Records that `view`, drawn in `parts` (1: whole), had its next part
    /// drawn from `start_ms` to `end_ms`: the view waits for the next
    /// frame until its last part is drawn, and only then counts as drawn.
    pub fn drawn(&mut self, view: ViewId, start_ms: f64, end_ms: f64, parts: usize) {
        let k = view.slot();
        self.max_draw_ms[k] = self.max_draw_ms[k].max(end_ms - start_ms);
        self.part[k] += 1;
        if self.part[k] < parts {
            self.need[k] = true;
            return;
        }
        self.part[k] = 0;
        self.draws[k] += 1;
        self.last_draw_ms[k] = end_ms;
        if self.first_draw_ms[k] == 0.0 {
            self.first_draw_ms[k] = end_ms;
        }
    }
}

/// Who draws in an animation frame: the views or the gear set, not both.
/// Each has a requestAnimationFrame callback, and the callbacks of one
/// frame run in one main-thread task, followed by the browser's commit of
/// every canvas they changed: a view (up to 30 ms with both workers busy)
/// and the gear set (usually 1 ms, at times 20-50 ms) in one frame made
/// tasks of 100-166 ms. The views go first: the gear set gives a frame up
/// to views waiting to draw, once, and draws in the next; the views wait a
/// frame when the gear set drew in this one. Frames are named by their
/// time stamp (the one every callback of a frame receives).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct FrameTurn {
    /// Whether an animation frame is requested for the views.
    pub requested: bool,
    views_ts: f64,
    anim_ts: f64,
    yielded: bool,
}

impl FrameTurn {
    /// Whether the gear set draws in frame `ts` (and if so, notes it):
    /// not in a frame the views drew in, and not when `views_waiting`
    /// (a frame is requested for views that need drawing), once.
    pub fn anim_draws(&mut self, ts: f64, views_waiting: bool) -> bool {
        if self.views_ts == ts {
            return false;
        }
        if views_waiting && !self.yielded {
            self.yielded = true;
            return false;
        }
        self.yielded = false;
        self.anim_ts = ts;
        true
    }

    /// Whether the views may draw in frame `ts`: not when the gear set drew in it.
    pub fn views_draw(&self, ts: f64) -> bool {
        self.anim_ts != ts
    }

    /// Notes that views drew in frame `ts`.
    pub fn views_drew(&mut self, ts: f64) {
        self.views_ts = ts;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use figures::protocol::KindSet;
    use figures::views::DRAW_ORDER;

    /// The views drawn in one frame if each takes `draw_ms`:
    /// [`Redraw::decide`] over
    /// [`DRAW_ORDER`] from `frame_ms`, with `status` per view.
    fn plan<'a>(
        r: &mut Redraw,
        frame_ms: f64,
        draw_ms: f64,
        status: impl Fn(ViewId) -> Option<&'a JobStatus>,
    ) -> Vec<ViewId> {
        let mut now = frame_ms;
        let mut out = Vec::new();
        for v in DRAW_ORDER {
            match r.decide(v, frame_ms, now, status(v)) {
                Decision::Stop => break,
                Decision::Skip => {}
                Decision::Draw => {
                    r.drawn(v, now, now + draw_ms, 1);
                    now += draw_ms;
                    out.push(v);
                }
            }
        }
        out
    }

    fn all() -> Dirty {
        Dirty {
            jobs: KindSet::ALL,
            ..Dirty::default()
        }
    }

    /// A view drawn in parts (a family's six phase portraits) waits for
    /// another frame after each part, counts as drawn once, after its last
    /// part, and starts over from its first when its data change on the
    /// way.
    #[test]
    fn a_view_in_parts_draws_a_part_a_frame_and_counts_once() {
        let mut r = Redraw::default();
        let phase = Dirty {
            jobs: ViewId::Phase.spec().shows,
            ..Dirty::default()
        };
        let k = ViewId::Phase.slot();
        let draw_parts = |r: &mut Redraw, count: usize, parts: usize| {
            for _ in 0..count {
                assert!(r.decide(ViewId::Phase, 0.0, 0.0, None) == Decision::Draw);
                let part = r.part(ViewId::Phase);
                r.drawn(ViewId::Phase, 0.0, 1.0, parts);
                assert!(part < parts);
            }
        };
        r.mark(&phase);
        draw_parts(&mut r, 2, 6);
        assert_eq!((r.part(ViewId::Phase), r.draws[k]), (2, 0));
        assert!(r.needs(ViewId::Phase));
        // New data after two of six parts: from the first part again.
        r.mark(&phase);
        assert_eq!(r.part(ViewId::Phase), 0);
        draw_parts(&mut r, 6, 6);
        assert_eq!((r.part(ViewId::Phase), r.draws[k]), (0, 1));
        assert!(!r.needs(ViewId::Phase));
        // Whole (one part): counted at once, as before.
        r.mark(&phase);
        draw_parts(&mut r, 1, 1);
        assert_eq!((r.part(ViewId::Phase), r.draws[k]), (0, 2));
        assert!(!r.needs(ViewId::Phase));
    }

    /// A full refresh draws the slider's views first and spreads over
    /// frames once a frame's budget is spent.
    #[test]
    fn a_full_refresh_spreads_over_frames_in_draw_order() {
        let mut r = Redraw::default();
        r.mark(&all());
        // 3 ms per view: views start at 0, 3, 6, 9 ms; the fourth starts
        // after the 8 ms budget, so three per frame.
        let first = plan(&mut r, 100.0, 3.0, |_| None);
        assert_eq!(first, vec![ViewId::Fr, ViewId::Phase, ViewId::Bif]);
        let second = plan(&mut r, 200.0, 3.0, |_| None);
        assert_eq!(
            second,
            vec![ViewId::Poincare, ViewId::Time, ViewId::Spectrum]
        );
        let third = plan(&mut r, 300.0, 3.0, |_| None);
        assert_eq!(third, vec![ViewId::Lyap, ViewId::Map, ViewId::Campbell]);
        let fourth = plan(&mut r, 400.0, 3.0, |_| None);
        assert_eq!(fourth, vec![ViewId::Dynamic, ViewId::Orders]);
        assert!(!r.pending());
        assert_eq!(r.draws, [1; 11]);
        assert_eq!(r.first_draw_ms[ViewId::Fr.slot()], 103.0);
        assert_eq!(r.max_draw_ms[ViewId::Map.slot()], 3.0);
        // Nothing marked: nothing drawn.
        assert!(plan(&mut r, 500.0, 3.0, |_| None).is_empty());
    }

    /// A running sweep's view is redrawn at most every RUNNING_REDRAW_MS,
    /// but a new job's start and its first data show at once; a view whose
    /// job does not stream (the selected-Omega views) is never throttled.
    #[test]
    fn running_sweeps_are_throttled_but_fresh_data_is_not() {
        let mut r = Redraw::default();
        let mut st = JobStatus {
            id: 4,
            started_ms: 0.0,
            total: 10,
            ..JobStatus::default()
        };
        let bif = Dirty {
            jobs: ViewId::Bif.spec().shows.with(KindSet::SELECTED),
            ..Dirty::default()
        };
        r.mark(&bif);
        let status = |s: &JobStatus| s.clone();
        let s0 = status(&st);
        let drawn = plan(&mut r, 10.0, 1.0, |v| (v == ViewId::Bif).then_some(&s0));
        assert!(drawn.contains(&ViewId::Bif) && drawn.contains(&ViewId::Phase));
        // 100 ms later, more points, same job: throttled, still needed.
        r.mark(&bif);
        let drawn = plan(&mut r, 112.0, 1.0, |v| (v == ViewId::Bif).then_some(&s0));
        assert!(!drawn.contains(&ViewId::Bif) && drawn.contains(&ViewId::Phase));
        assert!(r.needs(ViewId::Bif));
        // The first data arrive: drawn at once.
        st.first_data_ms = Some(115.0);
        st.done = 3;
        let s1 = status(&st);
        let drawn = plan(&mut r, 120.0, 1.0, |v| (v == ViewId::Bif).then_some(&s1));
        assert_eq!(drawn, vec![ViewId::Bif]);
        // More points within 250 ms: throttled; after 250 ms: drawn.
        r.mark(&bif);
        assert!(
            !plan(&mut r, 200.0, 1.0, |v| (v == ViewId::Bif).then_some(&s1)).contains(&ViewId::Bif)
        );
        assert!(
            plan(&mut r, 380.0, 1.0, |v| (v == ViewId::Bif).then_some(&s1)).contains(&ViewId::Bif)
        );
        // A finished job is not throttled.
        st.finished_ms = Some(390.0);
        let s2 = status(&st);
        r.mark(&bif);
        assert!(
            plan(&mut r, 400.0, 1.0, |v| (v == ViewId::Bif).then_some(&s2)).contains(&ViewId::Bif)
        );
        // Partial pictures: the two drawn with points in while it ran (not
        // the empty start, not the finished diagram).
        assert_eq!(r.partial_draws[ViewId::Bif.slot()], 2);
        assert_eq!(r.draws[ViewId::Bif.slot()], 4);
    }

    /// One drawer per frame, whichever callback runs first, and neither
    /// starves: with views waiting in every frame the gear set still draws
    /// every other frame.
    #[test]
    fn a_frame_draws_the_views_or_the_gear_set() {
        // The views' callback first: they draw, the gear set waits.
        let mut t = FrameTurn::default();
        assert!(t.views_draw(16.0));
        t.views_drew(16.0);
        assert!(!t.anim_draws(16.0, false));
        assert!(t.anim_draws(33.0, false));
        // The gear set first, nothing waiting: it draws, the views wait.
        assert!(!t.views_draw(33.0));
        assert!(t.views_draw(50.0));
        // Views waiting: the gear set yields once, then draws.
        let mut t = FrameTurn::default();
        let mut anim = 0;
        let mut views = 0;
        for k in 1..=10 {
            let ts = 16.0 * f64::from(k);
            if t.anim_draws(ts, true) {
                anim += 1;
            }
            if t.views_draw(ts) {
                t.views_drew(ts);
                views += 1;
            }
        }
        assert_eq!((anim, views), (5, 5));
    }
}
