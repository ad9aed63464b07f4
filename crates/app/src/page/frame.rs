//! One animation frame's views: which to draw, in what order, within the
//! frame's budget, and the texts after them. The web layer gives the clock
//! and the drawing; the decisions are the redraw scheduler's
//! ([`super::redraw`]).

use super::redraw::Decision;
use super::{Page, Write};
use crate::scene::Item;
use figures::plots::Boxed;
use figures::views::fr::FrView;
use figures::views::ViewId;
use plotters::prelude::{DrawingBackend, IntoDrawingArea};
use std::cell::RefCell;
use std::rc::Rc;

impl Page {
    /// Draws frame `ts`'s views: those changed, in draw order, until the
    /// frame's budget (counted from the first `clock()` reading) is spent;
    /// `draw` draws one view and returns its writes. Returns the views'
    /// writes, then the frame's texts (messages, summaries, link): the
    /// canvases are drawn before any text is written, since plotters
    /// measures legend text in the page, which lays out the whole page
    /// again whenever text changed since the last measure. Last, in a
    /// tour, its card follows its plot, whose size changes as data arrive.
    pub fn draw_frame(
        &mut self,
        ts: f64,
        clock: impl Fn() -> f64,
        mut draw: impl FnMut(&mut Page, ViewId) -> Vec<Write>,
    ) -> Vec<Write> {
        let t0 = clock();
        let (d, order) = self.begin_frame(ts);
        let mut writes = Vec::new();
        for &v in order {
            let start = clock();
            match self.decide(v, t0, start) {
                Decision::Stop => break,
                Decision::Skip => continue,
                Decision::Draw => writes.extend(draw(self, v)),
            }
            self.drawn(v, (start, clock()), ts);
        }
        writes.extend(self.end_frame(&d));
        writes.extend(self.place_tour_card(false));
        writes
    }

    /// Draws `view` on its canvas's backend `b` ([`Page::draw_view`]),
    /// noting the box of every text drawn for the status (`text_boxes`).
    pub fn draw_on<DB: DrawingBackend>(
        &mut self,
        view: ViewId,
        b: DB,
        fr: Option<&FrView>,
    ) -> (Vec<Write>, Vec<Item>) {
        let size = b.get_size();
        let boxes = Rc::new(RefCell::new(Vec::new()));
        let root = Boxed::new(b, boxes.clone()).into_drawing_area();
        // A later part adds to the canvas, and its texts to the first's.
        let later = self.part_now(view).is_some_and(|k| k > 0);
        let drawn = self.draw_view(view, &root, fr);
        drop(root);
        self.set_text_boxes(view, size, boxes.take(), later);
        drawn
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::page::redraw::FRAME_BUDGET_MS;
    use figures::views::DRAW_ORDER;
    use std::cell::Cell;

    fn page() -> Page {
        Page::new(crate::controller::Controller::new("", 0.0).0, false)
    }

    #[test]
    fn a_frame_draws_views_until_its_budget_is_spent_then_the_rest_next_frame() {
        let mut p = page();
        // Each view's drawing takes 5 ms of the page's clock.
        let now = Cell::new(100.0);
        let mut drawn = Vec::new();
        let w = p.draw_frame(
            16.0,
            || now.get(),
            |_, v| {
                drawn.push(v);
                now.set(now.get() + 5.0);
                vec![Write::text("drew", v.key())]
            },
        );
        // Two views fit the budget (the third starts past it).
        let fit = (FRAME_BUDGET_MS / 5.0).floor() as usize + 1;
        assert_eq!(drawn, DRAW_ORDER[..fit].to_vec());
        // The views' writes come first, the frame's texts after.
        let first_text = w
            .iter()
            .position(|w| !matches!(w, Write::Text { id, .. } if id == "drew"));
        assert_eq!(first_text, Some(fit));
        assert!(w.iter().any(|w| matches!(w, Write::Url(_))));
        assert!(p.wants_frame());
        // The next frame the views draw in goes on with the rest.
        let mut more = Vec::new();
        let mut ts = 32.0;
        while p.wants_frame() && ts < 1000.0 {
            p.draw_frame(
                ts,
                || now.get(),
                |_, v| {
                    more.push(v);
                    vec![]
                },
            );
            ts += 16.0;
        }
        assert_eq!(more, DRAW_ORDER[fit..].to_vec());
    }

    #[test]
    fn a_view_drawn_on_a_backend_leaves_its_text_boxes_in_the_status() {
        let mut p = page();
        let mut svg = String::new();
        let (fr, size) = p.prepare(ViewId::Fr);
        p.draw_on(
            ViewId::Fr,
            plotters::prelude::SVGBackend::with_string(&mut svg, size),
            fr.as_ref(),
        );
        let s = p.status(0.0);
        let fr_boxes = &s["text_boxes"][ViewId::Fr.key()];
        assert_eq!(fr_boxes["size"], serde_json::json!([size.0, size.1]));
        assert!(
            !fr_boxes["boxes"].as_array().unwrap().is_empty(),
            "{fr_boxes}"
        );
    }
}
