//! A view's drawing in the page core, on any plotters backend: its size on
//! this screen, its plot or the message why there is none, its note, its
//! text alternative and the frame its clicks map through. The web layer
//! hands it a canvas's drawing area and fills what [`Drawn`] returns (the
//! bifurcation dots, the map's cells) with the canvas's own calls; the
//! native tests hand it an SVG one. Also the animation-frame requests.

use super::{Page, Write};
use crate::controller::{Drawn, SvgError};
use crate::plots;
use crate::views::fr::FrView;
use crate::views::ViewId;
use plotters::coord::Shift;
use plotters::prelude::{DrawingArea, DrawingBackend};

impl Page {
    /// What `view` needs before its canvas is sized: the frequency
    /// response's view model (built once for its size, note and plot), and
    /// its drawing size on this screen.
    pub fn prepare(&self, view: ViewId) -> (Option<FrView>, (u32, u32)) {
        let fr = (view == ViewId::Fr).then(|| self.ctl.fr_view());
        let size = self.canvas_size(view, fr.as_ref());
        (fr, size)
    }

    /// Draws `view` on `root` (or why it has nothing to draw); a plotting
    /// failure joins the messages. Returns the note and the text
    /// alternative to write after the frame's drawing, and what the
    /// caller's backend fills itself.
    pub fn draw_view<DB: DrawingBackend>(
        &mut self,
        view: ViewId,
        root: &DrawingArea<DB, Shift>,
        fr: Option<&FrView>,
    ) -> (Vec<Write>, Drawn) {
        let mut writes: Vec<Write> = self.note(view, fr).into_iter().collect();
        let suffix = self.caption_suffix(view, fr);
        let r = match self.ctl.placeholder(view) {
            Some(message) => {
                // No plot, no frame to map clicks with (the Lyapunov curve
                // drops its frame only when switched off).
                if view == ViewId::Time || (view == ViewId::Lyap && self.ctl.main().lyap.id == 0) {
                    self.set_frame(view, None);
                }
                plots::draw_message(root, view.spec().title, &message)
                    .map(|()| None)
                    .map_err(SvgError::from)
            }
            None => self.ctl.draw_view(view, root, &suffix, fr).map(Some),
        };
        if view == ViewId::Time {
            self.anim_touch();
        }
        writes.push(Write::Attr {
            id: format!("canvas-{}", view.key()),
            name: "aria-label",
            value: self.ctl.canvas_label(view),
        });
        match r {
            Ok(Some(d)) => {
                self.set_frame(view, d.frame);
                (writes, d)
            }
            Ok(None) => (writes, Drawn::default()),
            Err(e) => {
                if view == ViewId::Time {
                    self.set_frame(view, None);
                }
                self.issue(e.to_string());
                (writes, Drawn::default())
            }
        }
    }

    /// Whether to request an animation frame now: none is pending (marks
    /// one pending).
    pub fn request_frame(&mut self) -> bool {
        !std::mem::replace(&mut self.frame_requested, true)
    }

    /// The end of a frame: whether views still wait, so that the web layer
    /// requests the next frame at once (then marked pending).
    pub fn next_frame(&mut self) -> bool {
        self.frame_requested = self.wants_frame();
        self.frame_requested
    }

    /// The phone's "see the motion" jump, offered after an Omega was
    /// picked on a narrow screen.
    pub(super) fn see_orbit_writes(&self) -> Vec<Write> {
        let omega = self.ctl.settings().view.omega;
        vec![
            Write::text("see-orbit", format!("See the motion at Ω = {omega:.2} ↓")),
            Write::Hidden {
                id: "see-orbit".into(),
                hidden: !self.see_orbit,
            },
        ]
    }
}
