//! What the browser reports, decided natively: the page's start from what
//! the window says (link, cores, width, motion preference), its workers'
//! failures, the Copy link's outcome, and a canvas event's pixel. The web
//! layer reads these facts from the browser and passes them in as they
//! are (absent or nonsense included); every decision on them is here.

use super::{Page, PngFailure, Write};
use crate::controller::{pool_size, Controller, Effect};
use figures::plots;
use figures::views::ViewId;

/// A view's PNG as the browser makes it: its SVG picture rasterized at
/// `size` (twice the drawing's) and offered as the file `name`.
#[derive(Debug, Clone, PartialEq)]
pub struct Png {
    /// The view's SVG picture (the same drawing as its canvas).
    pub svg: String,
    /// The file's name.
    pub name: String,
    /// The PNG's pixels, twice the drawing's in each direction.
    pub size: (u32, u32),
}

/// What the window says at the page's start.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Browser {
    /// The link's query (`?` and after, or empty).
    pub query: String,
    /// The page's clock (ms).
    pub now_ms: f64,
    /// How many Web Workers `index.html`'s script started (0 where it
    /// started none): the page runs exactly these ([`pool_size_of`]).
    pub early_workers: usize,
    /// `navigator.hardwareConcurrency`, where it is a number.
    pub cores: Option<f64>,
    /// `window.gearshockWorkers` (the benchmark's override), where it is a
    /// number.
    pub forced_workers: Option<f64>,
    /// `window.innerWidth` (CSS pixels), where it is a number.
    pub width: Option<f64>,
    /// The media query `prefers-reduced-motion: reduce` matches.
    pub reduced_motion: bool,
}

/// The page's workers: exactly those `index.html`'s inline script started
/// before the page's WebAssembly loaded (the script decides their count;
/// the page adopts them), or, where it started none (it did not run, or
/// the browser refused a worker), [`worker_count`]'s.
pub fn pool_size_of(b: &Browser) -> usize {
    if b.early_workers > 0 {
        b.early_workers
    } else {
        worker_count(b.cores, b.forced_workers)
    }
}

/// The workers to start where `index.html`'s script started none
/// ([`pool_size_of`]), by the script's rule: the benchmark's count where
/// it set a whole number of at least 1, else one per logical core but one
/// (the page's) within the pool's bounds ([`pool_size`]).
pub fn worker_count(cores: Option<f64>, forced: Option<f64>) -> usize {
    let whole = |n: f64| n.is_finite() && n >= 1.0;
    forced
        .filter(|&n| whole(n))
        .map(|n| n as usize)
        .unwrap_or_else(|| pool_size(cores.filter(|&c| whole(c)).map(|c| c as u32)))
}

/// A mouse event's offset (CSS pixels from the canvas's corner) in the
/// canvas's drawing pixels, for a canvas shown `css` CSS pixels large and
/// drawn `px` pixels large.
pub fn drawing_px(offset: (f64, f64), css: (f64, f64), px: (u32, u32)) -> (f64, f64) {
    (
        offset.0 * f64::from(px.0) / css.0.max(1.0),
        offset.1 * f64::from(px.1) / css.1.max(1.0),
    )
}

/// The pointer events an Omega axis listens to, with their phases.
pub const POINTER_EVENTS: [(&str, super::Phase); 4] = [
    ("pointerdown", super::Phase::Down),
    ("pointermove", super::Phase::Move),
    ("pointerup", super::Phase::Up),
    ("pointercancel", super::Phase::Cancel),
];

impl Page {
    /// The page for what the window says, and the controller's first
    /// effects (the workers' first jobs).
    pub fn boot(b: &Browser) -> (Page, Vec<Effect>) {
        let workers = pool_size_of(b);
        let (shown, query, issue) = super::present::split_present(&b.query);
        let (mut ctl, effects) = Controller::with_workers(&query, b.now_ms, workers);
        ctl.hold_off_screen();
        if let Some(issue) = issue {
            ctl.issue(issue);
        }
        let narrow = b.width.is_some_and(|w| w < f64::from(plots::NARROW));
        let mut page = Page::new(ctl, narrow);
        page.set_wide(b.width.is_some_and(|w| w >= super::WIDE_SCREEN));
        if b.reduced_motion {
            page.prefer_still();
        }
        page.present_from_link(shown);
        (page, effects)
    }

    /// The page's first writes once its elements are built: the canvases'
    /// sizes for this screen, then the tour's state from the link.
    pub fn first_writes(&self) -> Vec<Write> {
        let mut w = self.fit_writes();
        w.extend(self.tour_writes(true));
        w
    }

    /// The first writes that need the state's texts: present mode's
    /// stage, when the link opens in it.
    pub fn first_present_writes(&mut self) -> Vec<Write> {
        if self.presenting() {
            self.present_writes()
        } else {
            Vec::new()
        }
    }

    /// Worker `w`'s message `text`, handled at `clock()`; the time it took
    /// is kept for the status.
    pub fn worker_said(&mut self, w: usize, text: &str, clock: impl Fn() -> f64) -> Vec<Effect> {
        let t = clock();
        let fx = self.worker_message(w, text, t);
        self.message_took(clock() - t);
        fx
    }

    /// View `v`'s PNG, or why its picture cannot be made.
    pub fn png(&self, v: ViewId) -> Result<Png, PngFailure> {
        let svg = self
            .ctl
            .plot_svg(v)
            .map_err(|e| PngFailure::Picture(e.to_string()))?;
        let (w, h) = self.ctl.canvas_size(v);
        let name = self.ctl.file_name(v, None, "png");
        Ok(Png {
            svg,
            name,
            size: (2 * w, 2 * h),
        })
    }

    /// The browser could not start a Web Worker: said in the messages.
    pub fn worker_missing(&mut self) {
        self.issue("could not start a Web Worker; the views cannot be computed".into());
    }

    /// Web Worker `w` failed to load or crashed (at `now_ms`): said in the
    /// messages, and the jobs held for the first screen are posted (the
    /// messages to post).
    pub fn worker_failed(&mut self, w: usize, now_ms: f64) -> Vec<Effect> {
        self.issue(format!("Web Worker {w} failed to load or crashed"));
        self.ctl.stop_holding(now_ms)
    }

    /// The clipboard took the link (`copied`) or refused it: the
    /// confirmation next to the button (the status line is rewritten every
    /// frame), at `now_ms`, stamped `stamp` for the tests.
    pub fn link_copied(&mut self, copied: bool, now_ms: f64, stamp: f64) -> Vec<Write> {
        let text = if copied {
            "Link copied to the clipboard."
        } else {
            "Could not copy; the link is in the address bar."
        };
        self.confirm(text, now_ms, stamp)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::controller::{MAX_WORKERS, MIN_WORKERS};

    #[test]
    fn the_worker_count_follows_the_cores_within_bounds_unless_the_benchmark_sets_it() {
        // One core is the page's; the pool stays within its bounds.
        assert_eq!(worker_count(Some(4.0), None), 3);
        assert_eq!(worker_count(Some(1.0), None), MIN_WORKERS);
        assert_eq!(worker_count(Some(64.0), None), MAX_WORKERS);
        // An absent or nonsense core count: the smallest pool.
        for c in [None, Some(f64::NAN), Some(0.0), Some(-3.0)] {
            assert_eq!(worker_count(c, None), MIN_WORKERS, "{c:?}");
        }
        // The benchmark's whole number wins, even past the bounds; nonsense
        // is ignored.
        assert_eq!(worker_count(Some(4.0), Some(1.0)), 1);
        assert_eq!(worker_count(Some(4.0), Some(12.0)), 12);
        assert_eq!(worker_count(Some(4.0), Some(0.0)), 3);
        assert_eq!(worker_count(Some(4.0), Some(f64::INFINITY)), 3);
    }

    #[test]
    fn the_page_runs_exactly_the_workers_the_inline_script_started() {
        // The script's count wins over the cores and the benchmark's,
        // which it has applied already.
        let b = |early_workers, forced| Browser {
            early_workers,
            cores: Some(4.0),
            forced_workers: forced,
            ..Browser::default()
        };
        assert_eq!(pool_size_of(&b(5, None)), 5);
        assert_eq!(pool_size_of(&b(1, Some(1.0))), 1);
        assert_eq!(Page::boot(&b(5, None)).0.ctl().workers(), 5);
        // None started: 4 cores give 3, or the benchmark's 1.
        assert_eq!(pool_size_of(&b(0, None)), 3);
        assert_eq!(pool_size_of(&b(0, Some(1.0))), 1);
    }

    #[test]
    fn a_canvas_shown_at_half_size_doubles_the_offsets() {
        assert_eq!(
            drawing_px((10.0, 20.0), (380.0, 200.0), (760, 400)),
            (20.0, 40.0)
        );
        // A canvas not laid out (0 CSS pixels) does not divide by zero.
        let (x, y) = drawing_px((3.0, 4.0), (0.0, 0.0), (760, 400));
        assert!(x.is_finite() && y.is_finite());
    }

    #[test]
    fn the_window_decides_the_pool_the_screen_and_the_motion() {
        let b = Browser {
            query: "omega=0.9".into(),
            cores: Some(4.0),
            width: Some(390.0),
            reduced_motion: true,
            ..Browser::default()
        };
        let (p, fx) = Page::boot(&b);
        assert_eq!(p.ctl().workers(), 3);
        assert!(p.narrow(), "390 CSS pixels is a phone");
        assert_eq!(p.ctl().settings().view.omega, 0.9);
        assert!(fx.is_empty(), "no job before a worker is ready: {fx:?}");
        let wide = Browser {
            width: Some(1280.0),
            ..b.clone()
        };
        assert!(!Page::boot(&wide).0.narrow());
        assert!(!Page::boot(&wide).0.wide(), "1280 CSS pixels: one column");
        let full_hd = Browser {
            width: Some(1920.0),
            ..b.clone()
        };
        assert!(Page::boot(&full_hd).0.wide());
        // An unknown width is not a phone.
        let unknown = Browser { width: None, ..b };
        assert!(!Page::boot(&unknown).0.narrow());
    }

    #[test]
    fn worker_failures_and_the_copy_outcome_are_said_to_the_user() {
        let (mut p, _) = Page::boot(&Browser::default());
        p.worker_missing();
        p.worker_failed(2, 1.0);
        let issues = &p.ctl().issues;
        assert!(issues
            .iter()
            .any(|i| i.contains("could not start a Web Worker")));
        assert!(issues.iter().any(|i| i.contains("Web Worker 2 failed")));
        let png = p.png(ViewId::Bif).unwrap();
        assert_eq!(png.name, "gearshock-bif-s1a1.png");
        assert_eq!(png.size, (2 * plots::WIDTH, 2 * plots::HEIGHT));
        assert!(png.svg.starts_with("<svg"), "{}", &png.svg[..40]);
        p.png_failed(PngFailure::NotLoaded);
        let said = "The PNG image could not be made: the picture did not load";
        assert!(p.ctl().issues.iter().any(|i| i.contains(said)));
        let ok = p.link_copied(true, 10.0, 1.0);
        assert!(ok.contains(&Write::text("copy-done", "Link copied to the clipboard.")));
        let no = p.link_copied(false, 20.0, 2.0);
        assert!(no
            .iter()
            .any(|w| matches!(w, Write::Text { text, .. } if text.starts_with("Could not copy"))));
    }
}
