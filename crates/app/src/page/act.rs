//! What the page does on a user's [`Action`] (a button, a drop-down, a
//! field), and what the controls, the tour's panel and the family bar
//! show after a change, decided here rather than in the web layer's
//! listeners: as [`Write`]s and [`Effect`]s the native tests read.

use super::dom::{Action, TourMove};
use super::{Page, Write};
use crate::controller::Effect;
use crate::tour::{counter, in_speed, TOUR};
use figures::controls::{
    controls, field_text, label_for, model_subtitle, shown_for, Target, Widget,
};

/// What a user's event carries: the element's value (a field's text, a
/// drop-down's choice) and, for a key press, the key.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct EventIn {
    /// The element's `value`, if it has one.
    pub value: String,
    /// The key pressed (`keydown` only).
    pub key: Option<String>,
}

/// What an action asks of the web layer.
#[derive(Debug, Default)]
pub struct Acted {
    /// Messages to post, files to offer.
    pub effects: Vec<Effect>,
    /// Changes to the document.
    pub writes: Vec<Write>,
    /// Whether a frame is needed.
    pub frame: bool,
}

/// Why a view's PNG could not be made.
#[derive(Debug, Clone, PartialEq)]
pub enum PngFailure {
    /// The view has no picture to make (the reason).
    Picture(String),
    /// The browser gave no image element.
    NoImage,
    /// The picture could not be stored as a file for the image to load.
    NotStored,
    /// The image did not load the picture.
    NotLoaded,
    /// The browser could not encode the canvas as a PNG.
    NotEncoded,
}

impl Page {
    /// Does `action` at `now_ms` with the event `ev`. The copy to the
    /// clipboard and the PNG's rasterizing are the web layer's own (they
    /// wait for the browser); they ask nothing here.
    pub fn act(&mut self, action: Action, ev: &EventIn, now_ms: f64) -> Acted {
        let mut out = Acted {
            frame: true,
            ..Acted::default()
        };
        let ctl = &mut self.ctl;
        let fx = match action {
            Action::Slide(key) => {
                out.writes.push(Write::Value {
                    id: format!("num-{key}"),
                    value: ev.value.clone(),
                });
                self.input(key, &ev.value, now_ms);
                Vec::new()
            }
            Action::Set(key) => {
                self.input(key, &ev.value, now_ms);
                Vec::new()
            }
            Action::Preset if ev.value.is_empty() => Vec::new(),
            Action::Preset => ctl.apply_preset(&ev.value, now_ms),
            Action::LoadPreset(id) => ctl.apply_preset(id, now_ms),
            Action::Reset => ctl.load_query("", now_ms),
            Action::PinA => ctl.pin_a(now_ms),
            Action::ClearA => ctl.clear_a(now_ms),
            Action::ClearMessages => {
                ctl.clear_issues();
                Vec::new()
            }
            Action::Svg(v) => {
                let r = self.ctl.export_svg(v).map(|e| vec![e]);
                self.offer(r)
            }
            Action::Data(v, fmt) => {
                let r = self.ctl.export(v, fmt).map(|e| vec![e]);
                self.offer(r)
            }
            Action::Cli(v) => {
                let r = self.ctl.export_cli(v, now_ms);
                self.offer(r)
            }
            Action::Params => vec![ctl.export_params()],
            Action::Tour(TourMove::ToControl) => {
                out.writes.extend(self.tour_to_control());
                out.frame = false;
                Vec::new()
            }
            Action::Tour(TourMove::ToTarget) => {
                if let Some(s) = ctl.tour() {
                    out.writes.push(at_control(false));
                    out.writes.push(Write::Scroll(TOUR[s].target.into()));
                    out.writes.extend(self.place_tour_card(true));
                }
                out.frame = false;
                Vec::new()
            }
            Action::Tour(m) => {
                out.writes.push(at_control(false));
                let now = ctl.tour();
                let step = match m {
                    TourMove::Start => Some(0),
                    TourMove::Back => now.map(|s| s.saturating_sub(1)),
                    TourMove::Next => now.map(|s| s + 1).filter(|&s| s < TOUR.len()),
                    TourMove::Skip | TourMove::ToControl | TourMove::ToTarget => None,
                };
                let fx = ctl.tour_go(step, now_ms);
                self.notices.tour_copied = false;
                out.writes.extend(self.tour_writes(true));
                fx
            }
            Action::FamilyKey => {
                self.family_bar.key = ev.value.clone();
                out.frame = false;
                Vec::new()
            }
            Action::FamilyValues => {
                self.family_bar.values = ev.value.clone();
                out.frame = false;
                Vec::new()
            }
            Action::FamilyApply if ev.key.as_ref().is_some_and(|k| k != "Enter") => {
                out.frame = false;
                Vec::new()
            }
            Action::FamilyApply => {
                let (key, values) = (self.family_bar.key.clone(), self.family_bar.values.clone());
                let r = self.ctl.set_family_text(&key, &values, now_ms);
                let error = r
                    .as_ref()
                    .err()
                    .map(ToString::to_string)
                    .unwrap_or_default();
                out.writes.push(Write::text("family-error", error));
                r.unwrap_or_default()
            }
            Action::FamilyClear => {
                out.writes.push(Write::text("family-error", ""));
                ctl.clear_family(now_ms)
            }
            Action::AnimPlay => {
                self.anim_play();
                Vec::new()
            }
            Action::AnimStep(n) => {
                self.anim_step(n);
                Vec::new()
            }
            Action::AnimSpeed => {
                self.anim_speed(&ev.value);
                Vec::new()
            }
            Action::SeeOrbit => {
                self.notices.see_orbit = false;
                out.writes.push(Write::Hidden {
                    id: "see-orbit".into(),
                    hidden: true,
                });
                out.writes.push(Write::Scroll("view-phase".into()));
                Vec::new()
            }
            // The web layer draws and encodes the GIF (Page::gif_plan).
            Action::AnimGif => {
                out.frame = false;
                Vec::new()
            }
            Action::Present(m) => {
                out.writes.extend(self.present_move(m));
                Vec::new()
            }
            Action::OmegaStep(n) => {
                let key = if n < 0 { "ArrowLeft" } else { "ArrowRight" };
                for _ in 0..n.unsigned_abs() {
                    self.key(key, false);
                }
                Vec::new()
            }
            Action::CopyLink => {
                self.notices.tour_copied = true;
                out.writes.extend(self.tour_writes(false));
                out.frame = false;
                Vec::new()
            }
            Action::Png(_) => {
                out.frame = false;
                Vec::new()
            }
        };
        out.effects = fx;
        out
    }

    /// An export's files, or its reason in the messages.
    fn offer<E: std::fmt::Display>(&mut self, r: Result<Vec<Effect>, E>) -> Vec<Effect> {
        r.unwrap_or_else(|e| {
            self.ctl.issue(e.to_string());
            Vec::new()
        })
    }

    /// A PNG export could not be made: said in the messages.
    pub fn png_failed(&mut self, why: PngFailure) {
        let why = match why {
            PngFailure::Picture(e) => e,
            PngFailure::NoImage => "no image element".into(),
            PngFailure::NotStored => "the picture could not be stored".into(),
            PngFailure::NotLoaded => "the picture did not load".into(),
            PngFailure::NotEncoded => "the browser could not encode it".into(),
        };
        self.ctl
            .issue(format!("The PNG image could not be made: {why}"));
    }

    /// Every control's value, visibility and options as the state has them
    /// (after a link, a preset, a reset, a tour step or a refused value).
    pub fn control_writes(&mut self) -> Vec<Write> {
        let params = &self.ctl.settings().params;
        let model = params.kind();
        let mut w = Vec::new();
        // The mesh list depends on the model.
        let names = self.ctl.mesh_names();
        let mut options: Vec<(String, String)> =
            names.iter().map(|n| (n.clone(), n.clone())).collect();
        options.push(("worst".into(), "worst mesh at each speed".into()));
        if options != self.schematic.options {
            self.schematic.options = options.clone();
            w.push(Write::Options {
                id: "sel-mesh".into(),
                options,
            });
        }
        let axis_options = self.ctl.axis_options();
        if axis_options != self.schematic.axis_options {
            self.schematic.axis_options = axis_options.clone();
            w.push(Write::Options {
                id: "sel-axis".into(),
                options: axis_options,
            });
        }
        w.push(Write::text("model-subtitle", model_subtitle(model)));
        for c in controls() {
            w.push(Write::Hidden {
                id: format!("control-{}", c.key),
                hidden: !shown_for(&c, model) || self.ctl.control_unused(c.key),
            });
            let label = self.ctl.speed_label(c.key);
            w.push(Write::text(
                &format!("label-{}", c.key),
                label.unwrap_or_else(|| label_for(&c, model)),
            ));
            if let Some(Widget::Slider {
                min,
                max,
                step,
                field_min,
                field_max,
            }) = self.ctl.speed_widget(c.key, &c.widget)
            {
                for (id, name, x) in [
                    ("slider", "min", min),
                    ("slider", "max", max),
                    ("slider", "step", step),
                    ("num", "min", field_min),
                    ("num", "max", field_max),
                ] {
                    w.push(Write::Attr {
                        id: format!("{id}-{}", c.key),
                        name,
                        value: x.to_string(),
                    });
                }
            }
            let hint = self.ctl.contact_ratio_hint(c.key);
            if let Some(words) = self.ctl.contact_ratio_words(c.key) {
                w.push(Write::text(&format!("hint-{}", c.key), words));
            }
            let text = match c.target {
                Target::Param => match solver::keys::get(params, c.key) {
                    Some(solver::keys::Value::Num(x)) => field_text(x),
                    // An automatic value: the field empty, its placeholder
                    // the value computed.
                    Some(solver::keys::Value::Text(_)) if hint.is_some() => String::new(),
                    Some(solver::keys::Value::Text(t)) => t,
                    None => continue,
                },
                Target::View => match self
                    .ctl
                    .speed_field_text(c.key)
                    .or_else(|| self.ctl.settings().view.get(c.key))
                {
                    Some(t) => t,
                    None => continue,
                },
            };
            match c.widget {
                Widget::Slider { .. } => {
                    let mixed = if text.is_empty() { "mixed" } else { "" };
                    w.push(Write::Attr {
                        id: format!("num-{}", c.key),
                        name: "placeholder",
                        value: hint.unwrap_or_else(|| mixed.into()),
                    });
                    if !text.is_empty() {
                        w.push(Write::Value {
                            id: format!("slider-{}", c.key),
                            value: text.clone(),
                        });
                    }
                    w.push(Write::Value {
                        id: format!("num-{}", c.key),
                        value: text,
                    });
                }
                Widget::Select(_) => w.push(Write::Value {
                    id: format!("sel-{}", c.key),
                    value: text,
                }),
            }
        }
        w
    }

    /// The family bar's fields after a change: the family shown, written
    /// when the family changed, not while it is typed.
    pub fn family_writes(&mut self) -> Vec<Write> {
        let Some(f) = self.ctl.family() else {
            // No family (another preset, a reset, a link without one): the
            // bar is emptied once, so it never shows a family not drawn.
            if self.family_bar.shown.is_empty() {
                return Vec::new();
            }
            self.family_bar.shown.clear();
            self.family_bar.values.clear();
            return vec![Write::Value {
                id: "family-values".into(),
                value: String::new(),
            }];
        };
        let code = f.spec.encode();
        if code == self.family_bar.shown {
            return Vec::new();
        }
        let values: Vec<String> = f
            .spec
            .values
            .iter()
            .map(|x| figures::settings::fmt_exact(*x))
            .collect();
        self.family_bar.key = f.spec.key.key.to_string();
        self.family_bar.values = values.join(", ");
        self.family_bar.shown = code;
        vec![
            Write::Value {
                id: "family-key".into(),
                value: self.family_bar.key.clone(),
            },
            Write::Value {
                id: "family-values".into(),
                value: self.family_bar.values.clone(),
            },
        ]
    }

    /// The tour's panel for the current step (or hidden), its target
    /// highlighted and, if `scroll`, scrolled to.
    pub fn tour_writes(&self, scroll: bool) -> Vec<Write> {
        let step = self.ctl.tour();
        let mut w: Vec<Write> = TOUR
            .iter()
            .enumerate()
            .map(|(i, s)| Write::Class {
                id: s.target.into(),
                class: "tour-target",
                on: step == Some(i),
            })
            .collect();
        w.push(Write::Hidden {
            id: "tour".into(),
            hidden: step.is_none(),
        });
        let Some(step) = step else {
            return w;
        };
        let s = &TOUR[step];
        let axis = self.ctl.speed_axis();
        let last = step + 1 == TOUR.len();
        let done = self.tour_done() == Some(true);
        w.extend([
            Write::Attr {
                id: "tour".into(),
                name: "data-step",
                value: (step + 1).to_string(),
            },
            Write::text("tour-count", counter(step)),
            Write::text("tour-title", s.title),
            // The speeds in the unit the reader chose for the axes.
            Write::text("tour-text", in_speed(s.text, &axis)),
            Write::text("tour-action", in_speed(s.action, &axis)),
            Write::text("tour-done", format!("✓ Done: {}", in_speed(s.done, &axis))),
            Write::Hidden {
                id: "tour-done".into(),
                hidden: !done,
            },
            Write::Class {
                id: "tour-next".into(),
                class: "ready",
                on: done,
            },
            Write::Attr {
                id: "tour".into(),
                name: "data-done",
                value: done.to_string(),
            },
            Write::text("tour-next", if last { "Finish" } else { "Next" }),
            Write::Flag {
                id: "tour-back".into(),
                name: "disabled",
                on: step == 0,
            },
        ]);
        // A phone's settings drawer starts closed, far above the plots:
        // the card says where the control is and jumps there and back.
        let jump = self.screen.narrow.then_some(s.control).flatten();
        for id in ["tour-control", "tour-plot"] {
            w.push(Write::Hidden {
                id: id.into(),
                hidden: jump.is_none(),
            });
        }
        if let Some(key) = jump {
            w.push(Write::text(
                "tour-control",
                format!("Show “{}” ↑", self.control_label(key)),
            ));
            let back = if s.target == "schematic" {
                "Back to the gear set ↓"
            } else {
                "Back to the plot ↓"
            };
            w.push(Write::text("tour-plot", back));
        }
        if scroll {
            if jump.is_some() {
                w.push(Write::Flag {
                    id: "drawer".into(),
                    name: "open",
                    on: true,
                });
            }
            w.push(Write::Scroll(s.target.into()));
            w.extend(self.place_tour_card(true));
        }
        w
    }

    /// The control the tour's step uses, scrolled to (its drawer opened).
    fn tour_to_control(&self) -> Vec<Write> {
        let Some(key) = self.ctl.tour().and_then(|s| TOUR[s].control) else {
            return Vec::new();
        };
        vec![
            Write::Flag {
                id: "drawer".into(),
                name: "open",
                on: true,
            },
            // The reader is at the control: the docked card no longer
            // scrolls with the target as the layout shifts below.
            at_control(true),
            Write::Scroll(format!("control-{key}")),
        ]
    }

    /// A control's label as the settings show it for the current model,
    /// without its parenthesis ("Backlash b").
    fn control_label(&self, key: &str) -> String {
        let model = self.ctl.settings().params.kind();
        controls().iter().find(|c| c.key == key).map_or_else(
            || key.to_string(),
            |c| {
                let label = label_for(c, model);
                label.split(" (").next().unwrap_or(&label).to_string()
            },
        )
    }

    /// Whether the tour's current step's action is done ([`crate::tour::done`]),
    /// if the tour is running.
    pub fn tour_done(&self) -> Option<bool> {
        let step = &TOUR[self.ctl.tour()?];
        Some(crate::tour::done(
            step,
            |k| self.ctl.setting_text(k),
            self.notices.tour_copied,
        ))
    }

    /// The tour's card placed beside what its step points at (a view's
    /// whole canvas: data, axes and key) and the control it names, if the
    /// tour is on, and off the plots where the screen has room; docked at
    /// the screen's foot on a phone.
    pub fn place_tour_card(&self, new_step: bool) -> Option<Write> {
        let step = &TOUR[self.ctl.tour()?];
        Some(Write::PlaceCard {
            id: "tour".into(),
            keep_clear: step.keep_clear.iter().map(|s| s.to_string()).collect(),
            // The highlighted target whole, and the plots.
            prefer_clear: vec![step.target.to_string(), "views".to_string()],
            docked: self.screen.narrow,
            new_step,
        })
    }
}

/// Marks the tour's card as showing the reader a control (`on`) or back at
/// its target: while at a control, the web layer does not scroll the
/// page with the target.
fn at_control(on: bool) -> Write {
    Write::Flag {
        id: "tour".into(),
        name: "data-at-control",
        on,
    }
}
