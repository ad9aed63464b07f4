//! Present mode: one part of the page (a view, or the gear set in motion)
//! fills the screen for a projector, with its title, the selected Ω and a
//! one-line caption from the summary, and keyboard control (Escape
//! leaves; n, p, Page Down, Page Up and the up and down arrows move
//! through the parts in page order; the left and right arrows step Ω).
//!
//! The plot is redrawn for the screen, not scaled up: the web layer
//! measures the stage (CSS pixels and the device's pixel ratio) and draws
//! on a canvas of the stage's device pixels, through a transform of
//! [`PresentSize::scale`], a plot of [`PresentSize::drawing`] pixels. That
//! drawing is at most [`PRESENT_DRAWING_WIDTH`] wide, so on a 1920-pixel
//! projector the plots' 13-pixel words show about 28 pixels high, and the
//! lines and text stay sharp. The mode is in the link (`present=fr`), so
//! a lecturer can open straight into it.

use super::{Page, Write};
use figures::views::{ViewId, PAGE};

/// The link's key of present mode; its value is a part's key (`fr`, `anim`).
pub const PRESENT_KEY: &str = "present";

/// The widest drawing of a presented plot (its pixels before the
/// screen's scale): wider stages scale it up, so the words grow with the
/// screen (about 20 pixels on a 1366-pixel screen, 28 on a 1920-pixel one).
pub const PRESENT_DRAWING_WIDTH: f64 = 900.0;

/// The narrowest drawing of a presented plot: a phone's stage (about 360
/// CSS pixels) shows a drawing of this width, as the page's phone plots do
/// ([`super::PHONE_PLOT_WIDTH`]).
pub const PRESENT_MIN_WIDTH: f64 = 480.0;

/// The narrowest drawing of the presented gear set: its key and its two
/// lines of words are laid out on one line each for the page's canvas of
/// this width, so a phone shows them whole, smaller.
pub const PRESENT_ANIM_MIN_WIDTH: f64 = 760.0;

/// The lowest drawing of a presented plot: a lower stage (a phone held
/// sideways) shows a drawing this high, scaled down.
pub const PRESENT_MIN_HEIGHT: f64 = 260.0;

/// A presented plot's sizes on its stage.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PresentSize {
    /// The drawing's size (the plot's pixels).
    pub drawing: (u32, u32),
    /// The canvas's size (device pixels).
    pub canvas: (u32, u32),
    /// Canvas pixels per drawing pixel.
    pub scale: f64,
}

impl PresentSize {
    /// The sizes for a stage of `css` CSS pixels on a screen of `dpr`
    /// device pixels per CSS pixel, for a drawing at least `min_width`
    /// wide ([`PRESENT_MIN_WIDTH`] for the plots); `None` for an empty
    /// stage.
    pub fn for_stage(css: (f64, f64), dpr: f64, min_width: f64) -> Option<Self> {
        let dpr = if dpr.is_finite() && dpr > 0.0 {
            dpr
        } else {
            1.0
        };
        if !(css.0 >= 1.0 && css.1 >= 1.0 && css.0.is_finite() && css.1.is_finite()) {
            return None;
        }
        // CSS pixels per drawing pixel: the wider of the width's and the
        // height's needs, so the drawing is neither too wide nor too low.
        let wide = min_width.max(PRESENT_DRAWING_WIDTH);
        let k = (css.0 / css.0.clamp(min_width, wide)).min(css.1 / PRESENT_MIN_HEIGHT);
        let drawing = ((css.0 / k).round() as u32, (css.1 / k).round() as u32);
        let canvas = ((css.0 * dpr).round() as u32, (css.1 * dpr).round() as u32);
        Some(PresentSize {
            drawing,
            canvas,
            scale: f64::from(canvas.0) / f64::from(drawing.0.max(1)),
        })
    }
}

/// Present mode's state.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Present {
    /// The part shown, by its place in [`PAGE`] (`None`: not presenting).
    shown: Option<usize>,
    /// The stage's sizes, as last measured.
    size: Option<PresentSize>,
    /// How many times a part was drawn on the stage (the tests wait for it).
    draws: u32,
}

/// A move in present mode.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PresentMove {
    /// Present the part with this key.
    Open(&'static str),
    /// The next part in page order (after the last: the first).
    Next,
    /// The previous part (before the first: the last).
    Back,
    /// Leave present mode.
    Leave,
}

/// The view of the page part with key `key` (`None` for the gear set).
fn view_of(key: &str) -> Option<ViewId> {
    ViewId::ALL.into_iter().find(|v| v.key() == key)
}

/// Splits `present=` off a link's query: the part it names, the query
/// without it, and what is wrong with its value, if anything.
pub fn split_present(query: &str) -> (Option<usize>, String, Option<String>) {
    let q = query.strip_prefix('?').unwrap_or(query);
    let mut shown = None;
    let mut issue = None;
    let rest: Vec<&str> = q
        .split('&')
        .filter(|part| match part.strip_prefix("present=") {
            Some(key) => {
                shown = PAGE.iter().position(|p| p.key == key);
                issue = shown.is_none().then(|| {
                    let keys: Vec<&str> = PAGE.iter().map(|p| p.key).collect();
                    format!(
                        "present = {} names no view: allowed {}; the page opened as usual",
                        solver::keys::truncate(key, 40),
                        keys.join(", ")
                    )
                });
                false
            }
            None => true,
        })
        .collect();
    (shown, rest.join("&"), issue)
}

/// The first sentence of `text` (a caption of one line): up to the first
/// full stop followed by a space and a capital letter.
pub fn first_sentence(text: &str) -> &str {
    let b = text.as_bytes();
    for (i, w) in b.windows(3).enumerate() {
        if w[0] == b'.' && w[1] == b' ' && w[2].is_ascii_uppercase() {
            return &text[..=i];
        }
    }
    text
}

impl Page {
    /// Starts in present mode on part `shown` (from the link).
    pub(super) fn present_from_link(&mut self, shown: Option<usize>) {
        self.present.shown = shown;
    }

    /// Whether the page is in present mode.
    pub fn presenting(&self) -> bool {
        self.present.shown.is_some()
    }

    /// The presented view (`None` when the gear set or nothing is presented).
    pub fn presented_view(&self) -> Option<ViewId> {
        self.present_key().and_then(view_of)
    }

    /// Whether the gear set in motion is presented.
    pub fn presenting_anim(&self) -> bool {
        self.present_key() == Some("anim")
    }

    /// The presented part's key.
    pub fn present_key(&self) -> Option<&'static str> {
        self.present.shown.and_then(|i| PAGE.get(i)).map(|p| p.key)
    }

    /// The stage's sizes, once measured.
    pub fn present_size(&self) -> Option<PresentSize> {
        self.present.size.filter(|_| self.presenting())
    }

    /// The stage measured `css` CSS pixels at `dpr` device pixels each:
    /// the presented part is redrawn if its sizes changed.
    pub fn present_fit(&mut self, css: (f64, f64), dpr: f64) {
        let min_width = if self.presenting_anim() {
            PRESENT_ANIM_MIN_WIDTH
        } else {
            PRESENT_MIN_WIDTH
        };
        let size = PresentSize::for_stage(css, dpr, min_width);
        if size != self.present.size {
            self.present.size = size;
            self.present_touch();
        }
    }

    /// Records a drawing of the presented part on the stage.
    pub fn present_drew(&mut self) {
        self.present.draws += 1;
    }

    /// Marks the presented part for drawing.
    fn present_touch(&mut self) {
        match self.presented_view() {
            Some(v) => self.redraw.mark_view(v),
            None => self.anim_touch(),
        }
    }

    /// Does `m`: the writes that show the new state (the stage, its texts,
    /// the link) and, on entering or leaving, the element to focus (the
    /// way out; the button that opened the part).
    pub fn present_move(&mut self, m: PresentMove) -> Vec<Write> {
        let n = PAGE.len();
        let before = self.present.shown;
        self.present.shown = match (m, before) {
            (PresentMove::Open(key), _) => PAGE.iter().position(|p| p.key == key),
            (PresentMove::Next, Some(i)) => Some((i + 1) % n),
            (PresentMove::Back, Some(i)) => Some((i + n - 1) % n),
            (PresentMove::Leave, _) | (_, None) => None,
        };
        // The page's own canvas of the part left shows the page's size
        // again, and its clicks map through that drawing's frame.
        if let Some(i) = before.filter(|_| before != self.present.shown) {
            match PAGE.get(i).and_then(|p| view_of(p.key)) {
                Some(v) => self.redraw.mark_view(v),
                None => self.anim_touch(),
            }
        }
        self.present_touch();
        let focus = match (before, self.present.shown) {
            (None, Some(_)) => Some("present-leave".to_string()),
            (Some(i), None) => PAGE.get(i).map(|p| format!("present-{}", p.key)),
            _ => None,
        };
        let mut w = self.present_writes();
        w.extend(focus.map(Write::Focus));
        w
    }

    /// A key pressed in present mode: whether it was taken.
    pub fn present_keydown(&mut self, key: &str, shift: bool) -> Option<Vec<Write>> {
        if !self.presenting() {
            return None;
        }
        let m = match key {
            "Escape" => PresentMove::Leave,
            "n" | "N" | "PageDown" | "ArrowDown" | " " => PresentMove::Next,
            "p" | "P" | "PageUp" | "ArrowUp" | "Backspace" => PresentMove::Back,
            "ArrowLeft" | "ArrowRight" => {
                self.key(key, shift);
                return Some(Vec::new());
            }
            _ => return None,
        };
        Some(self.present_move(m))
    }

    /// The stage's texts and the link, as the state now is.
    pub(super) fn present_writes(&mut self) -> Vec<Write> {
        let key = self.present_key();
        let mut w = vec![Write::Hidden {
            id: "present".into(),
            hidden: key.is_none(),
        }];
        if let Some(i) = self.present.shown {
            let title = PAGE.get(i).map_or("", |p| p.title);
            w.push(Write::text("present-title", format!("{}. {title}", i + 1)));
            w.push(Write::text(
                "present-count",
                format!("view {} of {}", i + 1, PAGE.len()),
            ));
            w.push(Write::text("present-omega", self.present_omega()));
            w.push(Write::text("present-caption", self.present_caption()));
            let label = match self.presented_view() {
                Some(v) => self.ctl.canvas_label(v),
                None => self.ctl.anim_label(),
            };
            w.push(Write::Attr {
                id: "canvas-present".into(),
                name: "aria-label",
                value: label,
            });
        }
        let q = self.link_query();
        if q != self.last_query {
            self.last_query = q.clone();
            w.push(Write::Url(q));
        }
        w
    }

    /// The selected speed as the stage shows it ("Ω = 0.840", or in rpm
    /// "4 452 rpm (Ω 0.840)").
    fn present_omega(&self) -> String {
        self.ctl.speed_axis().text(self.ctl.settings().view.omega)
    }

    /// The stage's caption: the summary's first sentence.
    fn present_caption(&self) -> String {
        first_sentence(&self.ctl.student_summary()).to_string()
    }

    /// The link: the controller's, with the presented part.
    pub(super) fn link_query(&self) -> String {
        let q = self.ctl.query();
        match self.present_key() {
            Some(k) if q.is_empty() => format!("{PRESENT_KEY}={k}"),
            Some(k) => format!("{q}&{PRESENT_KEY}={k}"),
            None => q,
        }
    }

    /// Present mode's figures for the tests' status.
    pub(super) fn present_status(&self) -> serde_json::Value {
        let size = self.present_size();
        serde_json::json!({
            "shown": self.present_key(),
            "draws": self.present.draws,
            "drawing": size.map(|s| [s.drawing.0, s.drawing.1]),
            "canvas": size.map(|s| [s.canvas.0, s.canvas.1]),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::controller::Controller;

    fn page(query: &str) -> Page {
        Page::boot(&crate::page::boot::Browser {
            query: query.into(),
            ..Default::default()
        })
        .0
    }

    #[test]
    fn a_projector_stage_scales_a_drawing_of_at_most_900_pixels() {
        // 1920 x 900 CSS pixels at 1 device pixel each: the words grow
        // by 1920/900.
        let s = PresentSize::for_stage((1920.0, 900.0), 1.0, PRESENT_MIN_WIDTH).unwrap();
        assert_eq!(s.canvas, (1920, 900));
        assert_eq!(s.drawing, (900, 422));
        assert!((s.scale - 1920.0 / 900.0).abs() < 1e-12);
        // A phone: 360 CSS pixels at 3 device pixels each, a drawing of
        // 480 (as the page's phone plots), every device pixel drawn.
        let s = PresentSize::for_stage((360.0, 500.0), 3.0, PRESENT_MIN_WIDTH).unwrap();
        assert_eq!(s.canvas, (1080, 1500));
        assert_eq!(s.drawing, (480, 667));
        assert!((s.scale - 1080.0 / 480.0).abs() < 1e-12);
        // A low stage: the drawing keeps 260 pixels of height.
        let s = PresentSize::for_stage((800.0, 200.0), 1.0, PRESENT_MIN_WIDTH).unwrap();
        assert_eq!(s.drawing.1, 260);
        // The gear set on a phone: the page's 760 pixels, scaled down.
        let s = PresentSize::for_stage((380.0, 500.0), 2.0, PRESENT_ANIM_MIN_WIDTH).unwrap();
        assert_eq!(s.drawing, (760, 1000));
        assert!(PresentSize::for_stage((0.0, 500.0), 1.0, PRESENT_MIN_WIDTH).is_none());
        assert!(PresentSize::for_stage((f64::NAN, 500.0), 1.0, PRESENT_MIN_WIDTH).is_none());
    }

    #[test]
    fn the_link_opens_present_mode_and_keeps_it() {
        let p = page("backlash_um=80&present=bif");
        assert_eq!(p.present_key(), Some("bif"));
        assert_eq!(p.presented_view(), Some(ViewId::Bif));
        assert!(
            p.link_query().ends_with("&present=bif"),
            "{}",
            p.link_query()
        );
        assert!(p.ctl().issues.is_empty(), "{:?}", p.ctl().issues);
        let p = page("present=anim");
        assert!(p.presenting_anim());
        assert_eq!(p.link_query(), format!("{}&present=anim", p.ctl().query()));
        // A bad value is named with the allowed ones; the page opens as usual.
        let p = page("present=movie");
        assert!(!p.presenting());
        let said = p.ctl().issues.join(" ");
        assert!(said.contains("present = movie names no view"), "{said}");
        assert!(said.contains("fr, map, bif"), "{said}");
    }

    #[test]
    fn keys_move_through_the_views_in_page_order_and_escape_leaves() {
        let mut p = Page::new(Controller::new("", 0.0).0, false);
        assert!(p.present_keydown("n", false).is_none(), "not presenting");
        let w = p.present_move(PresentMove::Open("fr"));
        assert!(w.contains(&Write::Focus("present-leave".into())));
        assert!(w.contains(&Write::Hidden {
            id: "present".into(),
            hidden: false
        }));
        assert!(w.contains(&Write::text("present-title", "1. Frequency response")));
        assert!(w
            .iter()
            .any(|w| matches!(w, Write::Url(q) if q.ends_with("present=fr"))));
        p.present_keydown("n", false);
        assert_eq!(p.present_key(), Some("map"));
        p.present_keydown("ArrowUp", false);
        p.present_keydown("PageUp", false);
        // Wraps round to the page's last view (the mesh force by order).
        assert_eq!(
            p.present_key(),
            PAGE.last().map(|part| part.key),
            "wraps round"
        );
        assert_eq!(p.present_key(), Some("orders"));
        p.present_keydown("PageDown", false);
        assert_eq!(p.present_key(), Some("fr"));
        // The left and right arrows step Ω, as on the page's plots.
        let before = p.ctl().settings().view.omega;
        assert!(p.present_keydown("ArrowRight", false).is_some());
        p.apply_pending(0.0);
        assert!(p.ctl().settings().view.omega > before);
        assert!(p.present_keydown("x", false).is_none());
        let w = p.present_keydown("Escape", false).unwrap();
        assert!(!p.presenting());
        assert!(w.contains(&Write::Hidden {
            id: "present".into(),
            hidden: true
        }));
        assert!(w
            .iter()
            .any(|w| matches!(w, Write::Url(q) if !q.contains("present"))));
        assert!(w.contains(&Write::Focus("present-fr".into())));
        // The page's canvas is drawn again at the page's size.
        assert!(p.redraw.needs(ViewId::Fr));
    }

    #[test]
    fn the_caption_is_the_summary_s_first_sentence() {
        assert_eq!(
            first_sentence("The teeth never part at Ω = 0.84. They mesh smoothly."),
            "The teeth never part at Ω = 0.84."
        );
        assert_eq!(first_sentence("One sentence only"), "One sentence only");
    }
}
