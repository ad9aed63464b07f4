//! The animated gear set's state in the page core: its slow-motion clock,
//! whether it is on screen, what each tick of its own animation-frame loop
//! draws (the scene, the "no motion yet" message or nothing), the time
//! history's cursor, and what the last frame showed for the tests' status.
//! The web layer rasterizes the [`Scene`] and strokes the cursor.

use super::{Page, Write};
use crate::gearset::{AnimClock, GearSet};
use crate::scene::{anim_note, gear_scene, Item, Scene, SubPath};
use figures::views::ViewId;
use glam::DVec2;
use plotters::coord::Shift;
use plotters::prelude::{DrawingArea, DrawingBackend};

/// The gear set's animation.
#[derive(Debug, Default)]
pub struct Anim {
    /// The slow-motion clock.
    pub clock: AnimClock,
    last_ts: Option<f64>,
    frames: u32,
    /// Something changed that the canvas does not show yet.
    dirty: bool,
    /// Whether the canvas holds the "no motion yet" frame.
    placeholder: bool,
    /// Whether the gear set's canvas and the time history's cursor canvas
    /// are scrolled out of view: then the clock runs on but nothing is
    /// drawn, which spares the main thread two canvas updates per frame
    /// while workers load the cores.
    offscreen: [bool; 2],
    /// The drawing model and the parameters it was built from.
    pub(super) set: Option<(solver::params::ModelParams, GearSet)>,
    /// What the last frame showed (for the tests' status).
    pub(super) info: serde_json::Value,
    /// The last GIF made (for the tests' status).
    pub(super) gif: serde_json::Value,
}

/// What one tick of the animation's loop draws.
#[derive(Debug, Clone, PartialEq)]
pub enum AnimDraw {
    /// Nothing new.
    Nothing,
    /// The "no motion yet" frame.
    Placeholder,
    /// The gear set and the time history's cursor.
    Scene,
}

/// The canvases the animation draws on, by [`Page::anim_visible`]'s slot.
pub const ANIM_CANVASES: [&str; 2] = ["canvas-anim", "canvas-time-cursor"];

impl Page {
    /// The animation's window length in samples (0 before any motion).
    pub fn anim_len(&self) -> usize {
        self.ctl
            .main()
            .omega
            .as_ref()
            .and_then(|r| r.anim.x_um.first())
            .map_or(0, Vec::len)
    }

    /// Marks the gear set for drawing (a new state, or its view redrawn).
    pub fn anim_touch(&mut self) {
        self.anim.dirty = true;
    }

    /// The browser asks for reduced motion: the animation starts paused.
    pub fn prefer_still(&mut self) {
        self.anim.clock.playing = false;
        self.anim.dirty = true;
    }

    /// Play or pause.
    pub fn anim_play(&mut self) {
        self.anim.clock.playing = !self.anim.clock.playing;
        self.anim.dirty = true;
    }

    /// Steps by `samples` (pauses).
    pub fn anim_step(&mut self, samples: i64) {
        let len = self.anim_len();
        self.anim.clock.step(samples, len);
        self.anim.dirty = true;
    }

    /// The speed from its drop-down's text (mesh periods per second).
    pub fn anim_speed(&mut self, text: &str) {
        if let Some(v) = text.parse::<f64>().ok().filter(|v| *v > 0.0) {
            self.anim.clock.periods_per_s = v;
            self.anim.dirty = true;
        }
    }

    /// A click at pixel `(x, y)` of the time history: the animation moves
    /// to that instant.
    pub fn anim_seek(&mut self, x: f64, y: f64) {
        let len = self.anim_len();
        let (Some(f), Some(r)) = (self.frame(ViewId::Time), self.ctl.main().omega.as_ref()) else {
            return;
        };
        let Some(q) = f.point_at(x, y) else { return };
        let window = (r.anim.start_sample, r.samples_per_period);
        self.anim.clock.seek(q.x, window, len);
        self.anim.dirty = true;
    }

    /// Whether the canvas [`ANIM_CANVASES`]`[slot]` is on screen.
    pub fn anim_visible(&mut self, id: &str, visible: bool) {
        if let Some(slot) = ANIM_CANVASES.iter().position(|c| *c == id) {
            self.anim.offscreen[slot] = !visible;
            self.anim.dirty = true;
        }
    }

    /// A tick of the animation's loop at `ts`: the clock advances, and a
    /// new state (or a seek, a speed, the view scrolled in) is drawn at
    /// once, in view or not, so the canvas always holds the current state;
    /// the running animation only in view, and not in a frame the views
    /// need ([`redraw::FrameTurn`](super::redraw::FrameTurn)).
    pub fn anim_tick(&mut self, ts: f64) -> AnimDraw {
        let dt = self.anim.last_ts.map_or(0.0, |t| (ts - t) / 1000.0);
        self.anim.last_ts = Some(ts);
        let len = self.anim_len();
        let spp = self.ctl.main().omega.as_ref().map(|r| r.samples_per_period);
        let (Some(spp), true) = (spp, len > 0) else {
            // No motion yet: a drawn frame that says so, never a blank canvas.
            if self.anim.placeholder {
                return AnimDraw::Nothing;
            }
            self.anim.placeholder = true;
            return AnimDraw::Placeholder;
        };
        if self.anim.clock.pos >= len as f64 {
            self.anim.clock.pos = 0.0;
        }
        self.anim.clock.advance(dt, spp, len);
        let in_view = self.presenting_anim() || !self.anim.offscreen.iter().all(|&o| o);
        if !(self.anim.dirty || (self.anim.clock.playing && in_view)) {
            return AnimDraw::Nothing;
        }
        let views_waiting = self.turn.requested && self.wants_frame();
        if !self.turn.anim_draws(ts, views_waiting) {
            return AnimDraw::Nothing;
        }
        self.anim.dirty = false;
        AnimDraw::Scene
    }

    /// The gear set on a canvas of `size` pixels at the clock's instant,
    /// and the writes that go with it (its note, the play button's word);
    /// `None` before any motion or for a model that cannot be drawn.
    pub fn anim_scene(&mut self, size: (f64, f64)) -> Option<(Scene, Vec<Write>)> {
        self.anim_set();
        let (Some((_, set)), Some(r)) = (self.anim.set.as_ref(), self.ctl.main().omega.as_ref())
        else {
            return None;
        };
        let clock = self.anim.clock;
        let scene = gear_scene(set, r, &clock, size);
        let k = r.anim.start_sample as usize + scene.sample;
        self.anim.frames += 1;
        self.anim.info = serde_json::json!({
            "frames": self.anim.frames,
            "playing": clock.playing,
            "periods_per_s": clock.periods_per_s,
            "sample": scene.sample,
            "window_len": r.anim.x_um.first().map_or(0, Vec::len),
            "history_sample": k,
            "t_periods": scene.t_periods,
            "factor": scene.factor,
            "omega": r.omega,
            "plotted_mesh": r.mesh,
            "plotted_x_um": r.x_um.get(k),
            "markers": &scene.markers,
        });
        let writes = vec![
            Write::text("note-anim", anim_note(r, &clock)),
            Write::text("anim-play", if clock.playing { "Pause" } else { "Play" }),
        ];
        Some((scene, writes))
    }

    /// Builds the drawing model of the gear set for the current
    /// parameters, if they changed; whether there is one.
    pub(super) fn anim_set(&mut self) -> Option<()> {
        let params = self.ctl.settings().params.clone();
        if self.anim.set.as_ref().is_none_or(|(q, _)| *q != params) {
            let meshes: Vec<(solver::params::MeshKind, usize)> = match self.ctl.model() {
                Ok(m) => m.system.meshes.iter().map(|x| (x.kind, x.planet)).collect(),
                Err(_) => Vec::new(),
            };
            self.anim.set = GearSet::new(&params, &meshes).map(|g| (params, g));
        }
        self.anim.set.as_ref().map(|_| ())
    }

    /// Draws on the gear set's canvas a frame and a line saying the
    /// motion is on its way (before any motion: never a blank canvas).
    pub fn draw_anim_placeholder<DB: DrawingBackend>(&mut self, root: &DrawingArea<DB, Shift>) {
        let why = "The gear set and its meshes appear here once the motion at the selected speed is computed.";
        if let Err(e) = figures::plots::draw_message(root, "The gear set", why) {
            self.issue(e.to_string());
        }
    }

    /// The time history's cursor canvas at the clock's instant: cleared,
    /// and a red line across the plot at that time.
    pub fn time_cursor(&self) -> Vec<Item> {
        let mut items = vec![Item::Erase];
        let (Some(f), Some(r)) = (self.frame(ViewId::Time), self.ctl.main().omega.as_ref()) else {
            return items;
        };
        let t = self
            .anim
            .clock
            .time_periods((r.anim.start_sample, r.samples_per_period));
        let x = f.to_px(t, f.y_range.0).x;
        items.push(Item::Shape {
            parts: vec![SubPath::Polyline(vec![
                DVec2::new(x, f.top_left.y),
                DVec2::new(x, f.bottom_right.y),
            ])],
            fill: None,
            even_odd: false,
            stroke: Some(("rgba(220,20,60,0.9)".into(), 2.0)),
        });
        items
    }
}
