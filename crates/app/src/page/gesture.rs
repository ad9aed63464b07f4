//! A pointer's gesture on an Omega axis (the frequency response, the
//! bifurcation diagram, the Lyapunov curve): a tap selects where it
//! lifts, a drag along the axis scrubs, and a swipe across it scrolls the
//! page and never selects. Until the pointer has moved [`SLOP_PX`] CSS
//! pixels the gesture is undecided; its first clear direction decides it.
//! A `pointercancel` (the browser took the touch to scroll) ends it with
//! no selection. A mouse's press selects at once.

use super::Page;
use figures::views::ViewId;

/// How far (CSS pixels) a finger moves before its gesture is a drag or a
/// swipe rather than a tap.
pub const SLOP_PX: f64 = 10.0;

/// One pointer event on an Omega axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointerIn {
    /// Down, move, up or cancel.
    pub phase: Phase,
    /// The x in the canvas's drawing pixels (mapped to Omega).
    pub x_px: f64,
    /// The position in CSS pixels (for the movement threshold).
    pub at: (f64, f64),
    /// A mouse (else a finger or a pen).
    pub mouse: bool,
}

impl PointerIn {
    /// A pointer event as the browser gives it, `kind` its pointer type
    /// (`mouse`, `touch` or `pen`).
    pub fn new(phase: Phase, x_px: f64, at: (f64, f64), kind: &str) -> Self {
        Self {
            phase,
            x_px,
            at,
            mouse: kind == "mouse",
        }
    }
}

/// A pointer event's kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phase {
    /// `pointerdown`.
    Down,
    /// `pointermove`.
    Move,
    /// `pointerup`.
    Up,
    /// `pointercancel`.
    Cancel,
}

/// What a pressed pointer is doing.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(super) enum Gesture {
    /// Nothing pressed.
    #[default]
    Idle,
    /// Pressed at `at` (CSS px) on `view`, not yet moved past the slop.
    Undecided { view: ViewId, at: (f64, f64) },
    /// Dragging along the axis of `view`: every move selects.
    Scrub(ViewId),
    /// Swiping across: the page scrolls, nothing is selected.
    Scroll,
}

impl Page {
    /// A pointer event on `view`'s canvas: whether it selected an Omega
    /// (then a frame is needed).
    pub fn pointer(&mut self, view: ViewId, e: PointerIn) -> bool {
        let before = self.gesture;
        let select = match (before, e.phase) {
            (_, Phase::Cancel) => {
                self.gesture = Gesture::Idle;
                false
            }
            (_, Phase::Down) if e.mouse => {
                self.gesture = Gesture::Scrub(view);
                true
            }
            (_, Phase::Down) => {
                self.gesture = Gesture::Undecided { view, at: e.at };
                false
            }
            (Gesture::Undecided { view: v, at }, Phase::Move) if v == view => {
                let (dx, dy) = ((e.at.0 - at.0).abs(), (e.at.1 - at.1).abs());
                if dx.max(dy) < SLOP_PX {
                    false
                } else if dx > dy {
                    self.gesture = Gesture::Scrub(view);
                    true
                } else {
                    self.gesture = Gesture::Scroll;
                    false
                }
            }
            (Gesture::Scrub(v), Phase::Move) => v == view,
            // A tap: it selects where it lifts.
            (Gesture::Undecided { view: v, .. }, Phase::Up) => {
                self.gesture = Gesture::Idle;
                v == view
            }
            (_, Phase::Up) => {
                self.gesture = Gesture::Idle;
                false
            }
            (_, Phase::Move) => false,
        };
        // A gesture ends (or is decided a swipe): the tests wait for it.
        let ended = match (before, self.gesture, e.phase) {
            (b, _, Phase::Cancel) if b != Gesture::Idle => Some("cancel"),
            (Gesture::Undecided { .. }, Gesture::Scroll, _) => Some("scroll"),
            (Gesture::Undecided { .. }, _, Phase::Up) => Some("tap"),
            (Gesture::Scrub(_), _, Phase::Up) => Some("scrub"),
            _ => None,
        };
        if let Some(kind) = ended {
            self.telemetry.gestures_ended += 1;
            self.telemetry.last_gesture = kind;
        }
        if !select {
            return false;
        }
        let omega = self.frames[view.slot()].and_then(|f| f.x_at(e.x_px));
        self.input.omega = omega.or(self.input.omega);
        if omega.is_some() && self.screen.narrow {
            self.notices.see_orbit = true;
        }
        omega.is_some()
    }
}
