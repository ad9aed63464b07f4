//! The page core: everything the page decides between the browser's events
//! and its paint, as a plain type the native tests drive. The web layer
//! (`web.rs`, `web/`) hands it events (a slider's input, a click's pixel, a
//! key, a worker's message, an animation frame) and paints what it lists
//! ([`Write`]s, the views [`Page::draw_frame`] says to draw).
//!
//! Rules it keeps: input only queues work, applied once per animation
//! frame ([`Page::apply_pending`]), so a fast drag costs one job restart
//! and one redraw per frame; every message for the user goes through
//! [`Controller::issue`]; what to redraw and when comes from
//! [`redraw::Redraw`] and [`redraw::FrameTurn`].

mod act;
pub mod anim;
pub mod boot;
pub mod dom;
mod frame;
pub mod gesture;
pub mod gif;
mod paint;
pub mod present;
pub mod redraw;
pub mod tefile;
mod texts;

use crate::controller::{Controller, Effect};
use crate::store::status::Dirty;
use figures::plots::{self, PlotFrame};
use figures::protocol::KindSet;
use figures::views::{ViewId, DRAW_ORDER, VIEWS};
use redraw::{Decision, FrameTurn, Redraw};

pub use act::{Acted, EventIn, PngFailure};
pub use anim::AnimDraw;
pub use dom::{Action, Node};
pub use gesture::{Phase, PointerIn};

/// One change to the page's document, for the web layer to make.
#[derive(Debug, Clone, PartialEq)]
pub enum Write {
    /// An element's text.
    Text {
        /// The element's id.
        id: String,
        /// Its text.
        text: String,
    },
    /// An element's attribute.
    Attr {
        /// The element's id.
        id: String,
        /// The attribute.
        name: &'static str,
        /// Its value.
        value: String,
    },
    /// Whether an element is hidden.
    Hidden {
        /// The element's id.
        id: String,
        /// Hidden or shown.
        hidden: bool,
    },
    /// A class of an element switched on or off.
    Class {
        /// The element's id.
        id: String,
        /// The class.
        class: &'static str,
        /// On or off.
        on: bool,
    },
    /// A field's or a drop-down's value.
    Value {
        /// The element's id.
        id: String,
        /// Its value.
        value: String,
    },
    /// A drop-down's options (value, text), replaced if they differ.
    Options {
        /// The drop-down's id.
        id: String,
        /// Its options.
        options: Vec<(String, String)>,
    },
    /// A boolean attribute (`disabled`) set or removed.
    Flag {
        /// The element's id.
        id: String,
        /// The attribute.
        name: &'static str,
        /// Set or removed.
        on: bool,
    },
    /// An element scrolled into view.
    Scroll(String),
    /// A card (the tour's) placed beside what it points at, never over
    /// it, and for a new step scrolled on until both show
    /// ([`crate::tour::placement`], from what the window says).
    PlaceCard {
        /// The card's id.
        id: String,
        /// The ids of what it must leave in view, its target first.
        keep_clear: Vec<String>,
        /// The ids of what it had better leave in view too, where the
        /// screen has room.
        prefer_clear: Vec<String>,
        /// Docked at the screen's foot (a phone's): placed by the style
        /// sheet, its target scrolled above it.
        docked: bool,
        /// A new step (its target just scrolled to): scroll on if needed.
        new_step: bool,
    },
    /// The page's address (the query, without `?`).
    Url(String),
    /// An element given the keyboard's focus.
    Focus(String),
}

impl Write {
    fn text(id: &str, text: impl Into<String>) -> Self {
        Write::Text {
            id: id.to_string(),
            text: text.into(),
        }
    }

    /// The id of the element it changes (none for the address).
    pub fn id(&self) -> Option<&str> {
        match self {
            Write::Text { id, .. }
            | Write::Attr { id, .. }
            | Write::Hidden { id, .. }
            | Write::Class { id, .. }
            | Write::Value { id, .. }
            | Write::Options { id, .. }
            | Write::Flag { id, .. }
            | Write::Scroll(id)
            | Write::Focus(id)
            | Write::PlaceCard { id, .. } => Some(id),
            Write::Url(_) => None,
        }
    }
}

/// The keyboard's step of the selected Omega: the arrows move it by this
/// share of the range (with Shift, [`OMEGA_STEP_SHIFT`]).
pub const OMEGA_STEP: f64 = 0.01;
/// The keyboard's step of the selected Omega with Shift.
pub const OMEGA_STEP_SHIFT: f64 = 0.1;

/// The page's state besides the controller's: queued input, the redraw
/// schedule, the plots' frames, and the figures the tests read.
pub struct Page {
    ctl: Controller,
    input: PendingInput,
    redraw: Redraw,
    turn: FrameTurn,
    /// Each view's plot frame as last drawn (views with pixel-to-data
    /// mappings), by [`ViewId::slot`].
    frames: [Option<PlotFrame>; VIEWS.len()],
    /// The link last written to the address bar.
    last_query: String,
    screen: Screen,
    /// What a pressed pointer on an Omega axis is doing.
    gesture: gesture::Gesture,
    notices: Notices,
    telemetry: Telemetry,
    /// The gear set's animation.
    anim: anim::Anim,
    family_bar: FamilyBar,
    schematic: SchematicShown,
    /// Each control's refusal shown in the messages, until a newer value
    /// of its key or any change of the state ([`Refusal`]).
    refused: Vec<Refusal>,
    /// Present mode: one part of the page on the whole screen.
    present: present::Present,
    /// The last TE file fitted ([`tefile`]).
    te: Option<figures::te_fit::TeFitView>,
}

/// Input waiting for the next frame.
#[derive(Debug, Default)]
struct PendingInput {
    /// Slider and field values (the latest per key).
    values: Vec<(String, String)>,
    /// An Omega picked on a plot.
    omega: Option<f64>,
}

/// The screen's size class.
#[derive(Debug, Default)]
struct Screen {
    /// A phone: plots draw on fewer, larger pixels.
    narrow: bool,
    /// Wide ([`WIDE_SCREEN`]): the frequency response spans the views'
    /// columns, drawn [`WIDE_FR_WIDTH`] wide.
    wide: bool,
}

/// Short-lived notices the page offers.
#[derive(Debug, Default)]
struct Notices {
    /// When the Copy link's confirmation goes (ms).
    toast_until: Option<f64>,
    /// Whether the phone's "see the motion" jump is offered.
    see_orbit: bool,
    /// Whether the link was copied during the tour's current step.
    tour_copied: bool,
}

/// What the page reports for the tests and the benchmark to read: nothing
/// here changes what is drawn.
#[derive(Debug)]
struct Telemetry {
    /// Each view's canvas size and the boxes of the text last drawn on it
    /// (the tests check that none overlap or leave the canvas).
    text_boxes: [((u32, u32), Vec<figures::plots::TextBox>); VIEWS.len()],
    /// What the map's last drawing put over its cells.
    map_drawn: serde_json::Value,
    /// How many gestures on an Omega axis ended, and how the last did.
    gestures_ended: u32,
    last_gesture: &'static str,
    /// When the last input arrived (ms).
    last_input_ms: f64,
    /// The longest handling of one worker message (ms).
    max_message_ms: f64,
    /// The longest animation frame's work (ms).
    max_frame_ms: f64,
    /// When a preview of the selected-Omega views was last drawn (ms) and
    /// the summary it showed: the tests wait for this marker.
    preview_drawn: Option<(f64, String)>,
}

impl Default for Telemetry {
    fn default() -> Self {
        Telemetry {
            text_boxes: std::array::from_fn(|_| ((0, 0), Vec::new())),
            map_drawn: serde_json::Value::Null,
            gestures_ended: 0,
            last_gesture: "",
            last_input_ms: 0.0,
            max_message_ms: 0.0,
            max_frame_ms: 0.0,
            preview_drawn: None,
        }
    }
}

/// The family bar's fields as chosen and typed, and the family they last
/// showed.
#[derive(Debug)]
struct FamilyBar {
    key: String,
    values: String,
    /// The shown family's link code.
    shown: String,
}

/// The mesh the schematic last highlighted and the drop-downs' options
/// last written: the plotted mesh's and the speed axes' (which name the
/// input member). A drop-down is rebuilt only when they change.
#[derive(Debug, Default)]
struct SchematicShown {
    mesh: String,
    options: Vec<(String, String)>,
    axis_options: Vec<(String, String)>,
}

/// A value a control refused: its message and red border last while the
/// state they speak of does. The field already shows the value in force,
/// so once the state moves on (another setting, a preset, a click on a
/// plot) the refusal is old news and both go.
#[derive(Debug, Clone, PartialEq)]
struct Refusal {
    /// The control's key.
    key: String,
    /// The message it added.
    message: String,
    /// The state (its link) when the value was refused.
    state: String,
}

impl Page {
    /// A page around `ctl`; `narrow`: a phone's screen.
    pub fn new(ctl: Controller, narrow: bool) -> Self {
        Page {
            ctl,
            input: PendingInput::default(),
            redraw: Redraw::default(),
            turn: FrameTurn::default(),
            frames: [None; VIEWS.len()],
            last_query: String::new(),
            screen: Screen {
                narrow,
                wide: false,
            },
            gesture: gesture::Gesture::Idle,
            notices: Notices::default(),
            telemetry: Telemetry::default(),
            anim: anim::Anim::default(),
            family_bar: FamilyBar {
                key: figures::family_spec::FAMILY_KEYS
                    .first()
                    .map_or_else(String::new, |k| k.key.to_string()),
                values: String::new(),
                shown: String::new(),
            },
            schematic: SchematicShown::default(),
            refused: Vec::new(),
            present: present::Present::default(),
            te: None,
        }
    }

    /// The controller.
    pub fn ctl(&self) -> &Controller {
        &self.ctl
    }

    /// The controller, to act on (buttons, presets, exports).
    pub fn ctl_mut(&mut self) -> &mut Controller {
        &mut self.ctl
    }

    /// A message for the user.
    pub fn issue(&mut self, message: String) {
        self.ctl.issue(message);
    }

    /// Whether the screen is narrow.
    pub fn narrow(&self) -> bool {
        self.screen.narrow
    }

    /// Whether the screen is wide.
    pub fn wide(&self) -> bool {
        self.screen.wide
    }

    /// Draws for a wide screen (`wide`) or not.
    pub fn set_wide(&mut self, wide: bool) {
        self.screen.wide = wide;
    }

    // ------------------------------------------------------------ input

    /// A control's new text (a slider moved, a field changed), applied at
    /// the next frame; only a key's latest value is kept.
    pub fn input(&mut self, key: &str, value: &str, now_ms: f64) {
        self.telemetry.last_input_ms = now_ms;
        self.input.values.retain(|(k, _)| k != key);
        self.input.values.push((key.to_string(), value.to_string()));
    }

    /// A key pressed on an Omega axis: the arrows move the selected Omega
    /// by [`OMEGA_STEP`] of the range ([`OMEGA_STEP_SHIFT`] with Shift),
    /// within the range. Whether the key was taken.
    pub fn key(&mut self, key: &str, shift: bool) -> bool {
        let dir = match key {
            "ArrowLeft" | "ArrowDown" => -1.0,
            "ArrowRight" | "ArrowUp" => 1.0,
            _ => return false,
        };
        let v = &self.ctl.settings().view;
        let share = if shift { OMEGA_STEP_SHIFT } else { OMEGA_STEP };
        let from = self.input.omega.unwrap_or(v.omega);
        let step = (v.omega_to - v.omega_from) * share;
        self.input.omega = Some((from + dir * step).clamp(v.omega_from, v.omega_to));
        true
    }

    /// A click at pixel `(x, y)` of `view`: on the map, that cell's value
    /// and Omega; on the time history, the animation's instant.
    pub fn click(&mut self, view: ViewId, x: f64, y: f64, now_ms: f64) -> Vec<Effect> {
        match view {
            ViewId::Map => self.map_click(x, y, now_ms),
            ViewId::Time => {
                self.anim_seek(x, y);
                Vec::new()
            }
            ViewId::Campbell => {
                let frame = self.frames[ViewId::Campbell.slot()];
                let picked = frame.and_then(|f| {
                    let v = self.ctl.campbell_view().ok()?;
                    figures::plots::campbell::pick(&v, &f, x, y).map(|c| c.omega)
                });
                self.input.omega = picked.or(self.input.omega);
                Vec::new()
            }
            _ => Vec::new(),
        }
    }

    /// A key on the Campbell diagram: the arrows select the next or the
    /// previous critical speed. Returns whether the key was used.
    pub fn campbell_key(&mut self, key: &str) -> bool {
        let dir = match key {
            "ArrowLeft" | "ArrowDown" => -1.0,
            "ArrowRight" | "ArrowUp" => 1.0,
            _ => return false,
        };
        let from = self.input.omega.unwrap_or(self.ctl.settings().view.omega);
        if let Some(omega) = self.ctl.campbell_step(from, dir) {
            self.input.omega = Some(omega);
        }
        true
    }

    /// A click at pixel `(x, y)` of the map: that cell's value and Omega.
    pub fn map_click(&mut self, x: f64, y: f64, now_ms: f64) -> Vec<Effect> {
        let frame = self.frames[ViewId::Map.slot()];
        let Some((f, at)) = frame.and_then(|f| f.point_at(x, y).map(|at| (f, at))) else {
            return Vec::new();
        };
        // Near a traced boundary, the click picks the boundary's point.
        let px = (
            (f.bottom_right.x - f.top_left.x) / (f.x_range.1 - f.x_range.0),
            (f.bottom_right.y - f.top_left.y) / (f.y_range.1 - f.y_range.0),
        );
        if let Some(r) = self.ctl.pick_map_boundary((at.x, at.y), px, now_ms) {
            return r.unwrap_or_else(|e| {
                self.issue(e.to_string());
                Vec::new()
            });
        }
        self.ctl.clear_picked_boundary();
        match self.ctl.pick_map_point(at.x, at.y, now_ms) {
            Ok(fx) => fx,
            Err(e) => {
                self.issue(e.to_string());
                Vec::new()
            }
        }
    }

    /// Worker `worker`'s message: hands it to the controller, which feeds
    /// the computation whose job it answers.
    pub fn worker_message(&mut self, worker: usize, text: &str, now_ms: f64) -> Vec<Effect> {
        self.ctl.worker_message(worker, text, now_ms)
    }

    /// Records how long a worker message's handling took.
    pub fn message_took(&mut self, ms: f64) {
        self.telemetry.max_message_ms = self.telemetry.max_message_ms.max(ms);
    }

    // ------------------------------------------------------------ frames

    /// Applies the queued input at `now_ms`: each control's value (a
    /// refused one marks its control invalid and says why), then a picked
    /// Omega. Returns the messages to post and the controls to mark.
    pub fn apply_pending(&mut self, now_ms: f64) -> (Vec<Effect>, Vec<Write>) {
        self.turn.requested = false;
        let mut fx = Vec::new();
        let mut writes = Vec::new();
        for (key, value) in std::mem::take(&mut self.input.values) {
            // The key's earlier refusal gives way to this value's outcome.
            if let Some(i) = self.refused.iter().position(|r| r.key == key) {
                let old = self.refused.remove(i);
                self.ctl.withdraw(&old.message);
            }
            let ok = match self.ctl.set_control(&key, &value, now_ms) {
                Ok(more) => {
                    fx.extend(more);
                    true
                }
                Err(e) => {
                    let msg = e.to_string();
                    self.refused.push(Refusal {
                        key: key.clone(),
                        message: msg.clone(),
                        state: self.ctl.query(),
                    });
                    self.ctl.issue(msg);
                    self.ctl.touch(true);
                    false
                }
            };
            writes.push(Write::Class {
                id: format!("control-{key}"),
                class: "invalid",
                on: !ok,
            });
        }
        if let Some(o) = self.input.omega.take() {
            fx.extend(self.ctl.select_omega(o, now_ms));
            writes.extend(self.see_orbit_writes());
        }
        (fx, writes)
    }

    /// Starts drawing frame `ts`: what changed since the last frame (the
    /// views marked for redrawing), and the views to consider in this
    /// frame, in draw order (none when the gear set drew in it).
    pub fn begin_frame(&mut self, ts: f64) -> (Dirty, &'static [ViewId]) {
        let d = self.ctl.take_dirty();
        self.redraw.mark(&d);
        let order = if self.turn.views_draw(ts) {
            DRAW_ORDER.as_slice()
        } else {
            &[]
        };
        (d, order)
    }

    /// Whether to draw `view` now (`now_ms`) in a frame begun at `frame_ms`.
    pub fn decide(&mut self, view: ViewId, frame_ms: f64, now_ms: f64) -> Decision {
        let status = self.ctl.redraw_status(view).clone();
        self.redraw.decide(view, frame_ms, now_ms, Some(&status))
    }

    /// Records that `view` was drawn from `start_ms` to `end_ms` in frame `ts`.
    pub fn drawn(&mut self, view: ViewId, (start_ms, end_ms): (f64, f64), ts: f64) {
        let parts = self.parts(view);
        self.redraw.drawn(view, start_ms, end_ms, parts);
        self.turn.views_drew(ts);
        let preview = self.ctl.main().omega.as_ref().is_some_and(|r| r.preview);
        if view == ViewId::Phase && preview && self.ctl.family().is_none() {
            self.telemetry.preview_drawn = Some((end_ms, self.ctl.summary_text()));
        }
    }

    /// The parts `view` is drawn in, one an animation frame
    /// ([`crate::controller::Controller::parts`]); whole (1) on the stage
    /// of present mode.
    pub fn parts(&self, view: ViewId) -> usize {
        if self.presented_view() == Some(view) {
            1
        } else {
            self.ctl.parts(view)
        }
    }

    /// The part of `view` to draw now, if it is drawn in parts.
    pub fn part_now(&self, view: ViewId) -> Option<usize> {
        (self.parts(view) > 1).then(|| self.redraw.part(view))
    }

    /// Whether views still wait to be drawn (another frame is needed).
    pub fn wants_frame(&self) -> bool {
        self.redraw.pending()
    }

    /// Whether the gear set draws in frame `ts` (else it waits a frame).
    pub fn anim_draws(&mut self, ts: f64, views_waiting: bool) -> bool {
        self.turn.anim_draws(ts, views_waiting)
    }

    /// Records how long frame's work took.
    pub fn frame_took(&mut self, ms: f64) {
        self.telemetry.max_frame_ms = self.telemetry.max_frame_ms.max(ms);
    }

    /// The plot frame `view` was last drawn in.
    pub fn frame(&self, view: ViewId) -> Option<PlotFrame> {
        self.frames[view.slot()]
    }

    /// Records the text boxes of `view`'s last drawing on its canvas of
    /// `size` pixels; with `add`, those of a later part of it, beside the
    /// earlier parts'.
    pub fn set_text_boxes(
        &mut self,
        view: ViewId,
        size: (u32, u32),
        boxes: Vec<figures::plots::TextBox>,
        add: bool,
    ) {
        let slot = &mut self.telemetry.text_boxes[view.slot()];
        if add && slot.0 == size {
            slot.1.extend(boxes);
        } else {
            *slot = (size, boxes);
        }
    }

    /// Records the plot frame `view` was drawn in (`None`: nothing to click).
    pub fn set_frame(&mut self, view: ViewId, frame: Option<PlotFrame>) {
        self.frames[view.slot()] = frame;
    }

    /// A view's plot failed: the reason joins the messages.
    pub fn plot_failed(&mut self, reason: String) {
        self.issue(reason);
    }

    /// The writes after a frame's views: the messages, the summaries, the
    /// link, the comparison line, as `d` says they changed.
    pub fn end_frame(&mut self, d: &Dirty) -> Vec<Write> {
        let mut w = self.forget_old_refusals();
        // (A plotting failure in this frame joined the messages.)
        let again = self.ctl.take_messages_dirty();
        if d.messages || again {
            w.extend(self.messages());
        }
        if d.controls || d.jobs.intersects(KindSet::SELECTED) {
            let warning = self.ctl.validity_warning();
            w.push(Write::Hidden {
                id: "validity".into(),
                hidden: warning.is_none(),
            });
            w.push(Write::text("validity", warning.unwrap_or_default()));
            w.extend(self.speed_writes());
        }
        if d.jobs.intersects(KindSet::SUMMARY) {
            w.push(Write::text("summary", self.ctl.student_summary()));
            w.push(Write::text("summary-expert", self.ctl.summary_text()));
            w.push(Write::Attr {
                id: "canvas-anim".into(),
                name: "aria-label",
                value: self.ctl.anim_label(),
            });
        }
        if self.presenting() && (d.url || d.controls || d.jobs.intersects(KindSet::SELECTED)) {
            w.extend(self.present_writes());
        }
        if d.url || d.controls {
            let q = self.link_query();
            if q != self.last_query {
                self.last_query = q.clone();
                w.push(Write::Url(q));
            }
            w.push(Write::text("cli-command", self.ctl.cli_commands()));
            w.extend(self.comparison());
            w.extend(self.family_writes());
            w.extend(self.tour_writes(false));
        }
        if d.controls {
            w.extend(self.control_writes());
            w.push(self.te_kind_writes());
        }
        w.extend(self.schematic_writes());
        w
    }

    /// The refusals whose state has moved on: their messages withdrawn and
    /// their controls' red borders taken off.
    fn forget_old_refusals(&mut self) -> Vec<Write> {
        if self.refused.is_empty() {
            return Vec::new();
        }
        let now = self.ctl.query();
        let (old, kept): (Vec<Refusal>, Vec<Refusal>) = std::mem::take(&mut self.refused)
            .into_iter()
            .partition(|r| r.state != now);
        self.refused = kept;
        old.into_iter()
            .map(|r| {
                self.ctl.withdraw(&r.message);
                Write::Class {
                    id: format!("control-{}", r.key),
                    class: "invalid",
                    on: false,
                }
            })
            .collect()
    }

    /// A view's drawing size on this screen (a frequency response's key
    /// may need a taller canvas: `fr_height`).
    pub fn canvas_size(&self, view: ViewId, fr: Option<&figures::views::fr::FrView>) -> (u32, u32) {
        let (w, h) = screen_size(
            self.ctl.base_canvas_size(view),
            view == ViewId::Fr,
            (self.screen.narrow, self.screen.wide),
        );
        match (fr, self.ctl.panels()) {
            (Some(fr), None) => (w, plots::fr_height(fr, (w, h))),
            _ => (w, h),
        }
    }
}

/// The plots' drawing width on a phone: with the canvas at the screen's
/// width (about 360 CSS pixels), the axes' and the key's 13-pixel words
/// read at about 10 pixels rather than the 6 of the 760-pixel drawing.
pub const PHONE_PLOT_WIDTH: u32 = 480;

/// The window width (CSS px) from which the page's views take two
/// columns beside the settings (the style sheet's `minmax(520px, 1fr)`
/// grid), so the frequency response spans both: its own row, drawn wider.
pub const WIDE_SCREEN: f64 = 1400.0;

/// The frequency response's drawing width on a wide screen: across both
/// columns of a 1920-pixel window (about 1 550 CSS pixels) its 13-pixel
/// words read at about 17 pixels, as the 760-pixel drawing's do in the
/// one column of a 1366-pixel window.
pub const WIDE_FR_WIDTH: u32 = 1160;

/// The frequency response's drawing height on a wide screen (one mesh;
/// taller if its key needs: `fr_height`).
pub const WIDE_FR_HEIGHT: u32 = 480;

/// A plot canvas's size on the screen for its drawing size `(w, h)` and
/// the screen `(narrow, wide)`: as drawn; on a narrow screen
/// [`PHONE_PLOT_WIDTH`] wide and taller for its width (the frequency
/// response of one mesh 640 pixels high); on a wide screen the frequency
/// response [`WIDE_FR_WIDTH`] wide (one mesh [`WIDE_FR_HEIGHT`] high).
pub fn screen_size((w, h): (u32, u32), fr: bool, (narrow, wide): (bool, bool)) -> (u32, u32) {
    let one = fr && h == plots::HEIGHT;
    match (narrow, wide && fr, one) {
        (true, _, true) => (PHONE_PLOT_WIDTH, 640),
        (true, _, false) => (PHONE_PLOT_WIDTH, h * 13 / 10),
        (false, true, true) => (WIDE_FR_WIDTH, WIDE_FR_HEIGHT),
        (false, true, false) => (WIDE_FR_WIDTH, h),
        (false, false, _) => (w, h),
    }
}

#[cfg(test)]
mod state_tests;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod ui_tests;
