//! A view's drawing in the page core, on any plotters backend: its size on
//! this screen, its plot or the message why there is none, its note, its
//! text alternative and the frame its clicks map through. The web layer
//! hands it a canvas's drawing area and rasterizes the overlay it returns
//! (the bifurcation dots, the map's cells, as scene [`Item`]s) with the
//! canvas's own calls; the native tests hand it an SVG one. Also the
//! animation-frame requests.

use super::{Page, Write};
use crate::controller::{Drawn, SvgError};
use crate::scene::{Item, SubPath};
use figures::plots;
use figures::views::fr::FrView;
use figures::views::ViewId;
use glam::DVec2;
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
    /// alternative to write after the frame's drawing, and the overlay the
    /// caller's canvas fills itself ([`overlay`]).
    pub fn draw_view<DB: DrawingBackend>(
        &mut self,
        view: ViewId,
        root: &DrawingArea<DB, Shift>,
        fr: Option<&FrView>,
    ) -> (Vec<Write>, Vec<Item>) {
        let (writes, d) = self.draw_view_data(view, root, fr);
        if let (ViewId::Map, Some(o)) = (view, &d.map) {
            // Every kind's line over its halo: half the lines are the curves'.
            self.telemetry.map_drawn = serde_json::json!({
                "curve_paths": o.curves.iter().skip(o.curves.len() / 2).map(|l| l.paths.len()).sum::<usize>(),
                "marks": o.marks.len(),
                "cusps": o.cusps.len(),
                "picked": o.picked.is_some(),
            });
        }
        (writes, overlay(&d))
    }

    fn draw_view_data<DB: DrawingBackend>(
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
                if view == ViewId::Time
                    || (view == ViewId::Lyap && !self.ctl.settings().view.lyap_on())
                {
                    self.set_frame(view, None);
                }
                plots::draw_message(root, view.spec().title, &message)
                    .map(|()| None)
                    .map_err(SvgError::from)
            }
            None => self
                .ctl
                .plot(view, root, &suffix, fr, self.part_now(view))
                .map(Some),
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
        !std::mem::replace(&mut self.turn.requested, true)
    }

    /// The end of a frame: whether views still wait, so that the web layer
    /// requests the next frame at once (then marked pending).
    pub fn next_frame(&mut self) -> bool {
        self.turn.requested = self.wants_frame();
        self.turn.requested
    }

    /// The schematic of the model shown, its plotted mesh highlighted.
    pub(super) fn schematic_writes(&mut self) -> Vec<Write> {
        let pair = self.ctl.settings().params.kind() == solver::ModelKind::GearPair;
        let style = |show: bool| if show { "" } else { "display:none" }.to_string();
        let mut w = vec![
            Write::Attr {
                id: "schem-ravigneaux".into(),
                name: "style",
                value: style(!pair),
            },
            Write::Attr {
                id: "schem-pair".into(),
                name: "style",
                value: style(pair),
            },
        ];
        let now = self.ctl.highlighted_mesh();
        let before = std::mem::replace(&mut self.schematic.mesh, now.clone());
        if before != now {
            for (name, on) in [(before, false), (now, true)] {
                w.push(Write::Class {
                    id: format!("mesh-{name}"),
                    class: "selected",
                    on,
                });
            }
        }
        w
    }

    /// Every plot canvas's drawing size at start: on a narrow screen fewer,
    /// larger pixels ([`screen_size`](super::screen_size)); the gear set
    /// keeps its drawing.
    pub fn fit_writes(&self) -> Vec<Write> {
        let mut w = Vec::new();
        for view in ViewId::ALL {
            let base = crate::controller::view_size(view);
            let (cw, ch) = super::screen_size(
                base,
                view == ViewId::Fr,
                (self.screen.narrow, self.screen.wide),
            );
            let mut ids = vec![format!("canvas-{}", view.key())];
            if view == ViewId::Time {
                ids.push("canvas-time-cursor".into());
            }
            for id in ids {
                w.push(Write::Attr {
                    id: id.clone(),
                    name: "width",
                    value: cw.to_string(),
                });
                w.push(Write::Attr {
                    id,
                    name: "height",
                    value: ch.to_string(),
                });
            }
        }
        w
    }

    /// The phone's "see the motion" jump, offered after an Omega was
    /// picked on a narrow screen.
    pub(super) fn see_orbit_writes(&self) -> Vec<Write> {
        let omega = self.ctl.settings().view.omega;
        let at = match self.ctl.speed_axis().rpm_scale() {
            Some(s) => format!("{} rpm", figures::speed::grouped_fine(s.rpm(omega))),
            None => format!("Ω = {omega:.2}"),
        };
        vec![
            Write::text("see-orbit", format!("See the motion at {at} ↓")),
            Write::Hidden {
                id: "see-orbit".into(),
                hidden: !self.notices.see_orbit,
            },
        ]
    }
}

fn rgb(c: plotters::style::RGBColor) -> String {
    format!("rgb({},{},{})", c.0, c.1, c.2)
}

/// What a canvas fills faster with its own calls than plotters draws it:
/// the bifurcation dots (a filled square per upward point, an open one per
/// downward), the map's cells (one path per colour), its period dots and
/// its cursor lines.
pub(super) fn overlay(d: &Drawn) -> Vec<Item> {
    let mut items = Vec::new();
    for g in &d.dots {
        let half = if g.filled { 1.25 } else { 2.5 };
        let parts =
            g.px.iter()
                .map(|&(x, y)| SubPath::Rect {
                    at: DVec2::new(f64::from(x) - half, f64::from(y) - half),
                    size: DVec2::splat(2.0 * half),
                })
                .collect();
        let c = rgb(g.color);
        let (fill, stroke) = if g.filled {
            (Some(c), None)
        } else {
            (None, Some((c, 1.0)))
        };
        items.push(Item::Shape {
            parts,
            fill,
            even_odd: false,
            stroke,
        });
    }
    let (Some(f), Some(o)) = (d.frame, &d.map) else {
        return items;
    };
    let shape = |parts, fill: Option<&str>, stroke: Option<&str>| Item::Shape {
        parts,
        fill: fill.map(String::from),
        even_odd: false,
        stroke: stroke.map(|c| (c.to_string(), 1.0)),
    };
    for (c, rects) in &o.cells {
        let parts = rects
            .iter()
            .map(|r| SubPath::Rect {
                at: DVec2::new(r[0], r[1]),
                size: DVec2::new(r[2], r[3]),
            })
            .collect();
        items.push(shape(parts, Some(&rgb(*c)), None));
    }
    let dots = o.dots.iter().map(|d| SubPath::Circle {
        c: DVec2::new(d[0], d[1]),
        r: o.dot_radius,
    });
    items.push(shape(dots.collect(), Some("#000"), None));
    let (t, b) = (f.top_left, f.bottom_right);
    let lines = [
        o.cursor
            .0
            .map(|x| vec![DVec2::new(x, t.y), DVec2::new(x, b.y)]),
        o.cursor
            .1
            .map(|y| vec![DVec2::new(t.x, y), DVec2::new(b.x, y)]),
    ];
    let lines = lines.into_iter().flatten().map(SubPath::Polyline).collect();
    items.push(shape(lines, None, Some("rgba(0,0,0,0.7)")));
    // The traced boundaries over the cells (a clicked one's glow under
    // them), then the marks, the cusps and the clicked point's ring.
    for l in o.picked.iter().map(|(l, _)| l).chain(&o.curves) {
        let parts = l
            .paths
            .iter()
            .map(|p| SubPath::Polyline(p.iter().map(|q| DVec2::new(q[0], q[1])).collect()))
            .collect();
        items.push(Item::Shape {
            parts,
            fill: None,
            even_odd: false,
            stroke: Some((rgb(l.color), l.width)),
        });
    }
    if !o.marks.is_empty() {
        let parts = o
            .marks
            .iter()
            .map(|r| SubPath::Rect {
                at: DVec2::new(r[0], r[1]),
                size: DVec2::new(r[2], r[3]),
            })
            .collect();
        items.push(Item::Shape {
            parts,
            fill: None,
            even_odd: false,
            stroke: Some((rgb(plots::boundaries::MARK), 2.0)),
        });
    }
    if !o.cusps.is_empty() {
        let parts = o
            .cusps
            .iter()
            .map(|c| SubPath::Circle {
                c: DVec2::new(c[0], c[1]),
                r: 5.0,
            })
            .collect();
        items.push(Item::Shape {
            parts,
            fill: Some("#fff".into()),
            even_odd: false,
            stroke: Some(("#000".into(), 2.0)),
        });
    }
    if let Some((_, at)) = &o.picked {
        items.push(Item::Shape {
            parts: vec![SubPath::Circle {
                c: DVec2::new(at[0], at[1]),
                r: 8.0,
            }],
            fill: None,
            even_odd: false,
            stroke: Some((rgb(plots::boundaries::PICKED), 3.0)),
        });
    }
    items
}
