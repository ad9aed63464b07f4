//! The page's built elements as data: the controls, the export bars, the
//! claims' rows, the option lists and every listener, as [`Node`] trees
//! and [`Action`]s that the web layer turns into elements and events with
//! one builder. What a control, a button or a row says and does is decided
//! (and tested) here; the web layer only creates what it is given.

use super::present::PresentMove;
use super::tefile::{DROP, HARMONICS, INPUT, KIND, NOTE, PLOT};
use crate::claims::{claims, heading};
use crate::controller::Format;
use figures::controls::{controls, Group, Widget};
use figures::family_spec::FAMILY_KEYS;
use figures::presets::{preset, PRESETS};
use figures::views::{ViewId, PAGE};
use solver::params::TE_HARMONICS;

/// What a user's event on an element asks of the page.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Action {
    /// A control's new value (a number field or a drop-down) for its key.
    Set(&'static str),
    /// A slider moved: its key's value, mirrored into the number field.
    Slide(&'static str),
    /// The preset drop-down: the value is the preset's id.
    Preset,
    /// A claim's button: load this preset.
    LoadPreset(&'static str),
    /// Back to the defaults.
    Reset,
    /// Pin the current state as A.
    PinA,
    /// End the A/B comparison.
    ClearA,
    /// Copy the link (the web layer's clipboard).
    CopyLink,
    /// Dismiss the messages.
    ClearMessages,
    /// A view as a PNG image at twice its size (the web layer rasterizes).
    Png(ViewId),
    /// A view as an SVG picture.
    Svg(ViewId),
    /// A view's data as CSV or JSON.
    Data(ViewId, Format),
    /// A view's data in the command-line tool's format.
    Cli(ViewId),
    /// The parameters as JSON for the command-line tool.
    Params,
    /// A tour button: start, back, next or skip.
    Tour(TourMove),
    /// The family's key chosen (the value: the key).
    FamilyKey,
    /// The family's values typed (the value: the text).
    FamilyValues,
    /// Show the family typed; also Enter in its field.
    FamilyApply,
    /// Back to one value.
    FamilyClear,
    /// Play or pause the gear set.
    AnimPlay,
    /// Step the gear set by samples (pauses).
    AnimStep(i64),
    /// The animation's speed (the value: mesh periods per second).
    AnimSpeed,
    /// The "see the motion" jump after a selection on a phone.
    SeeOrbit,
    /// The gear set in motion as an animated GIF (the web layer draws
    /// the frames).
    AnimGif,
    /// Present mode: open a part, move, leave.
    Present(super::present::PresentMove),
    /// Step the selected Ω by this many keyboard steps (present mode's
    /// buttons, for a screen without keys).
    OmegaStep(i8),
}

/// A tour button's move.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TourMove {
    /// To the first step.
    Start,
    /// One step back.
    Back,
    /// One step on (past the last: the tour ends).
    Next,
    /// End the tour.
    Skip,
    /// Scroll to the control the step's action uses (a phone's drawer
    /// opened first).
    ToControl,
    /// Scroll back to the step's target.
    ToTarget,
}

/// An element to create: tag, attributes, text, children and listeners.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Node {
    /// The tag.
    pub tag: &'static str,
    /// Attributes, in order (`id`, `class`, `value`, `aria-label`, ...).
    pub attrs: Vec<(&'static str, String)>,
    /// Its text, set as text (never markup).
    pub text: Option<String>,
    /// Its children, in order.
    pub children: Vec<Node>,
    /// The events it listens to (`input`, `change`, `click`) and what each asks.
    pub on: Vec<(&'static str, Action)>,
}

impl Node {
    /// An element `tag`.
    pub fn new(tag: &'static str) -> Self {
        Node {
            tag,
            ..Node::default()
        }
    }

    /// With attribute `name` set to `value`.
    pub fn attr(mut self, name: &'static str, value: impl Into<String>) -> Self {
        self.attrs.push((name, value.into()));
        self
    }

    /// With its text.
    pub fn text(mut self, text: impl Into<String>) -> Self {
        self.text = Some(text.into());
        self
    }

    /// With a child.
    pub fn child(mut self, node: Node) -> Self {
        self.children.push(node);
        self
    }

    /// With children.
    pub fn children(mut self, nodes: impl IntoIterator<Item = Node>) -> Self {
        self.children.extend(nodes);
        self
    }

    /// Listening to `event`.
    pub fn on(mut self, event: &'static str, action: Action) -> Self {
        self.on.push((event, action));
        self
    }

    /// Its attribute `name`, if set.
    pub fn get(&self, name: &str) -> Option<&str> {
        self.attrs
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, v)| v.as_str())
    }

    /// This node and every node below it, depth first.
    pub fn walk(&self) -> Vec<&Node> {
        let mut all = vec![self];
        for c in &self.children {
            all.extend(c.walk());
        }
        all
    }
}

/// An `<option>`.
pub fn option(value: &str, text: &str) -> Node {
    Node::new("option").attr("value", value).text(text)
}

/// A button whose accessible name starts with its visible text (`text`)
/// and goes on with what it does (`does`, also its tooltip).
pub fn button(text: &str, does: &str, action: Action) -> Node {
    Node::new("button")
        .attr("type", "button")
        .attr("title", does)
        .attr("aria-label", format!("{text}: {does}"))
        .text(text)
        .on("click", action)
}

/// The settings panel: one fieldset per group (the per-mesh-kind group
/// folded in a `<details>`), each control a labelled slider and number
/// field, or a drop-down.
pub fn control_panel() -> Vec<Node> {
    Group::ALL
        .into_iter()
        .map(|group| {
            let rows = controls()
                .into_iter()
                .filter(|c| c.group == group)
                .map(|c| {
                    let key = c.key;
                    let tooltip = figures::words::tooltip(key, c.description);
                    let applies = match c.applies {
                        solver::keys::Applies::Both => "both",
                        solver::keys::Applies::Ravigneaux => "ravigneaux",
                        solver::keys::Applies::GearPair => "gear-pair",
                    };
                    let div = Node::new("div")
                        .attr("class", "control")
                        .attr("id", format!("control-{key}"))
                        .attr("title", tooltip)
                        .attr("data-applies", applies);
                    let label = Node::new("label")
                        .attr("id", format!("label-{key}"))
                        .text(c.label.clone());
                    match &c.widget {
                        Widget::Slider {
                            min,
                            max,
                            step,
                            field_min,
                            field_max,
                        } => div
                            .child(label.attr("for", format!("num-{key}")))
                            .child(
                                Node::new("input")
                                    .attr("type", "range")
                                    .attr("id", format!("slider-{key}"))
                                    .attr("min", min.to_string())
                                    .attr("max", max.to_string())
                                    .attr("step", step.to_string())
                                    .attr("aria-label", format!("{} slider", c.label))
                                    .on("input", Action::Slide(key)),
                            )
                            .child(
                                Node::new("input")
                                    .attr("type", "number")
                                    .attr("id", format!("num-{key}"))
                                    .attr("min", field_min.to_string())
                                    .attr("max", field_max.to_string())
                                    .attr("step", "any")
                                    .on("change", Action::Set(key)),
                            )
                            .child(Node::new("span").attr("class", "unit").text(c.unit.clone()))
                            .children(key.starts_with("contact_ratio").then(|| {
                                Node::new("p")
                                    .attr("class", "hint")
                                    .attr("id", format!("hint-{key}"))
                            })),
                        Widget::Select(options) => {
                            div.child(label.attr("for", format!("sel-{key}"))).child(
                                Node::new("select")
                                    .attr("id", format!("sel-{key}"))
                                    .children(options.iter().map(|(v, t)| option(v, t)))
                                    .on("change", Action::Set(key)),
                            )
                        }
                    }
                });
            if group == Group::Advanced {
                Node::new("details")
                    .attr("class", "advanced")
                    .child(Node::new("summary").text(group.title()))
                    .child(Node::new("fieldset").children(rows))
                    .child(te_file_panel())
            } else {
                Node::new("fieldset")
                    .child(Node::new("legend").text(group.title()))
                    .children(rows)
            }
        })
        .collect()
}

/// The TE file's part of the Advanced group.
pub fn te_file_panel() -> Node {
    let (w, h) = figures::plots::te_fit::SIZE;
    let harmonics = (1..=TE_HARMONICS).rev().map(|n| {
        let words = if n == 1 {
            "1 harmonic".to_string()
        } else {
            format!("{n} harmonics")
        };
        option(&n.to_string(), &words)
    });
    Node::new("div")
        .attr("class", "te-file")
        .attr("id", DROP)
        .child(
            Node::new("p")
                .attr("class", "te-file-title")
                .text("Transmission error from a file"),
        )
        .child(Node::new("p").text(
            "A table of TE over one or more mesh periods, fitted to the harmonics of the \
             mesh frequency: a CSV file whose heading row names its two columns with their \
             units, Fraction (of a mesh period), Roll angle (deg) or Time (s), then TE (µm), \
             TE (nm), TE (mm) or TE (m). Drop the file here or choose it.",
        ))
        .child(
            Node::new("div")
                .attr("class", "control")
                .child(Node::new("label").attr("for", KIND).text("Mesh kind"))
                .child(Node::new("select").attr("id", KIND)),
        )
        .child(
            Node::new("div")
                .attr("class", "control")
                .child(
                    Node::new("label")
                        .attr("for", HARMONICS)
                        .text("Harmonics fitted"),
                )
                .child(
                    Node::new("select")
                        .attr("id", HARMONICS)
                        .children(harmonics),
                ),
        )
        .child(
            Node::new("div")
                .attr("class", "control")
                .child(Node::new("label").attr("for", INPUT).text("TE file"))
                .child(
                    Node::new("input")
                        .attr("type", "file")
                        .attr("id", INPUT)
                        .attr("accept", ".csv,.txt,.tsv,text/csv,text/plain"),
                ),
        )
        .child(
            Node::new("canvas")
                .attr("id", PLOT)
                .attr("width", w.to_string())
                .attr("height", h.to_string())
                .attr("role", "img")
                .attr("aria-label", "The TE file's points beside the fitted curve")
                .attr("hidden", ""),
        )
        .child(
            Node::new("p")
                .attr("id", NOTE)
                .attr("class", "note")
                .attr("aria-live", "polite"),
        )
}

/// A view's export bar: PNG, SVG, CSV, JSON and, for the views that have
/// one, the command-line tool's JSON.
pub fn export_bar(v: ViewId) -> Vec<Node> {
    let mut bar = vec![
        button(
            "PNG",
            &v.export_name("a PNG image at twice the size"),
            Action::Png(v),
        ),
        button("SVG", &v.export_name("an SVG picture"), Action::Svg(v)),
    ];
    for fmt in Format::ALL {
        bar.push(button(
            fmt.label(),
            &v.export_name(fmt.label()),
            Action::Data(v, fmt),
        ));
    }
    if v.cli_export_title().is_some() {
        bar.push(button(
            "CLI JSON",
            &v.export_name("JSON for the command-line tool"),
            Action::Cli(v),
        ));
    }
    bar
}

/// The button that presents a part of the page on the whole screen.
pub fn present_button(key: &'static str, title: &str) -> Node {
    let n = figures::views::part_number(key).unwrap_or(0);
    button(
        "Present",
        &format!(
            "Show view {n}, {title}, alone on the whole screen for a projector; Escape leaves"
        ),
        Action::Present(PresentMove::Open(key)),
    )
    .attr("id", format!("present-{key}"))
    .attr("class", "present-open")
}

/// The claims' rows: heading, what the paper says, the verdict, the
/// evidence, a button loading the figure's preset, the command.
pub fn claim_rows() -> Vec<Node> {
    claims()
        .iter()
        .map(|c| {
            let texts = [
                heading(c),
                c.says.clone(),
                c.verdict.clone(),
                c.evidence.clone(),
            ];
            let figure = c.figure.as_deref().and_then(preset).map(|f| {
                let short = f.title.split(':').next().unwrap_or(f.id);
                Node::new("button")
                    .attr("type", "button")
                    .attr("title", format!("Load the preset: {}", f.title))
                    .text(short)
                    .on("click", Action::LoadPreset(f.id))
            });
            let mut command = Node::new("td").child(Node::new("code").text(&c.command));
            if !c.with.is_empty() {
                command = command.child(Node::new("div").text(&c.with));
            }
            Node::new("tr")
                .attr("id", format!("claim-{}", c.id))
                .children(texts.into_iter().map(|t| Node::new("td").text(t)))
                .child(Node::new("td").children(figure))
                .child(command)
        })
        .collect()
}

/// The animation's speeds (mesh periods per second) and their words.
pub const ANIM_SPEEDS: [(f64, &str); 5] = [
    (0.1, "0.1 mesh periods/s"),
    (0.25, "0.25 mesh periods/s"),
    (0.5, "0.5 mesh periods/s"),
    (1.0, "1 mesh period/s"),
    (2.0, "2 mesh periods/s"),
];

/// Everything built at start: (the id of the element to fill, its new children).
pub fn built() -> Vec<(String, Vec<Node>)> {
    let presets = std::iter::once(option("", "Choose a preset…"))
        .chain(PRESETS.iter().map(|p| option(p.id, p.title)))
        .collect();
    let family = FAMILY_KEYS
        .iter()
        .map(|k| {
            let text = if k.unit.is_empty() {
                k.words.to_string()
            } else {
                format!("{} ({})", k.words, k.unit)
            };
            option(k.key, &text)
        })
        .collect();
    let speeds = ANIM_SPEEDS
        .iter()
        .map(|(v, t)| {
            let o = option(&v.to_string(), t);
            if *v == 0.5 {
                o.attr("selected", "")
            } else {
                o
            }
        })
        .collect();
    let params = button(
        "Download gearshock-params.json",
        "Download the parameters as JSON for the command-line tool",
        Action::Params,
    );
    let mut all = vec![
        ("controls".to_string(), control_panel()),
        ("preset".to_string(), presets),
        ("family-key".to_string(), family),
        ("anim-speed".to_string(), speeds),
        ("claims-rows".to_string(), claim_rows()),
        ("export-cli".to_string(), vec![params]),
    ];
    for v in ViewId::ALL {
        all.push((format!("exports-{}", v.key()), export_bar(v)));
    }
    for part in PAGE {
        all.push((
            format!("present-slot-{}", part.key),
            vec![present_button(part.key, part.title)],
        ));
    }
    all
}

/// The listeners of the page's fixed elements (those in `index.html`):
/// (element id, event, action).
pub const WIRING: [(&str, &str, Action); 28] = [
    ("preset", "change", Action::Preset),
    ("reset", "click", Action::Reset),
    ("pin-a", "click", Action::PinA),
    ("clear-a", "click", Action::ClearA),
    ("copy-link", "click", Action::CopyLink),
    ("messages", "click", Action::ClearMessages),
    ("tour-start", "click", Action::Tour(TourMove::Start)),
    ("tour-back", "click", Action::Tour(TourMove::Back)),
    ("tour-next", "click", Action::Tour(TourMove::Next)),
    ("tour-skip", "click", Action::Tour(TourMove::Skip)),
    ("tour-control", "click", Action::Tour(TourMove::ToControl)),
    ("tour-plot", "click", Action::Tour(TourMove::ToTarget)),
    ("family-key", "change", Action::FamilyKey),
    ("family-values", "input", Action::FamilyValues),
    ("family-values", "keydown", Action::FamilyApply),
    ("family-apply", "click", Action::FamilyApply),
    ("family-clear", "click", Action::FamilyClear),
    ("anim-play", "click", Action::AnimPlay),
    ("anim-back", "click", Action::AnimStep(-1)),
    ("anim-fwd", "click", Action::AnimStep(1)),
    ("anim-speed", "change", Action::AnimSpeed),
    ("anim-gif", "click", Action::AnimGif),
    ("see-orbit", "click", Action::SeeOrbit),
    (
        "present-leave",
        "click",
        Action::Present(PresentMove::Leave),
    ),
    ("present-next", "click", Action::Present(PresentMove::Next)),
    ("present-back", "click", Action::Present(PresentMove::Back)),
    ("present-omega-down", "click", Action::OmegaStep(-1)),
    ("present-omega-up", "click", Action::OmegaStep(1)),
];
