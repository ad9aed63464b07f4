//! The control panel as data: which keys get a control, in which group, with
//! what slider range, step, unit and tooltip. The web layer builds the DOM
//! from [`controls`]; ranges of the number fields are the keys' full ranges
//! (from `solver::keys::KEYS` and [`crate::settings::VIEW_KEYS`]), the sliders
//! cover the useful part.

use crate::settings::{view_key, ViewType};
use solver::keys::{self, Applies, KeyType};
use solver::params::ModelKind;

/// Where a control's value lives.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// A model parameter (`solver::keys`).
    Param,
    /// A view option (`crate::settings`).
    View,
}

/// Panel groups, in display order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Group {
    /// Model choice.
    Model,
    /// Backlash and transmission error: the main sliders.
    Excitation,
    /// Stiffness, damping, load, planets.
    Mesh,
    /// Per-mesh-kind backlash and TE.
    Advanced,
    /// Frequency range, grids, periods, harmonics, plotted mesh.
    Analysis,
    /// The impact-regime map and the Lyapunov curve.
    Maps,
}

impl Group {
    /// Heading.
    pub fn title(self) -> &'static str {
        match self {
            Group::Model => "Model",
            Group::Excitation => "Backlash and transmission error",
            Group::Mesh => "Meshes, load and planets",
            Group::Advanced => "Advanced: per mesh kind",
            Group::Analysis => "Analysis and views",
            Group::Maps => "Regime map and Lyapunov exponent",
        }
    }

    /// All groups in order.
    pub const ALL: [Group; 6] = [
        Group::Model,
        Group::Excitation,
        Group::Mesh,
        Group::Advanced,
        Group::Analysis,
        Group::Maps,
    ];
}

/// How a control takes its value.
#[derive(Debug, Clone, PartialEq)]
pub enum Widget {
    /// Slider plus number field.
    Slider {
        /// Slider minimum.
        min: f64,
        /// Slider maximum.
        max: f64,
        /// Step of slider and field.
        step: f64,
        /// Number field minimum (the key's full range).
        field_min: f64,
        /// Number field maximum.
        field_max: f64,
    },
    /// A drop-down of words: (value, label).
    Select(Vec<(String, String)>),
}

/// One control.
#[derive(Debug, Clone, PartialEq)]
pub struct Control {
    /// The key it sets.
    pub key: &'static str,
    /// Where the key lives.
    pub target: Target,
    /// Label text.
    pub label: String,
    /// Unit as shown (`µm`, `N m`, empty if none).
    pub unit: String,
    /// The key's description (as the command line gives it); the page's
    /// tooltip says it in plain words (`words::tooltip`).
    pub description: &'static str,
    /// Group.
    pub group: Group,
    /// Widget.
    pub widget: Widget,
    /// Models it applies to.
    pub applies: Applies,
}

fn unit_text(u: &str) -> String {
    match u {
        "-" => String::new(),
        "um" => "µm".into(),
        other => other.into(),
    }
}

fn param(key: &'static str, label: &str, group: Group, slider: (f64, f64, f64)) -> Option<Control> {
    let spec = keys::spec(key)?;
    let (field_min, field_max) = match spec.ty {
        KeyType::Float { min, max } | KeyType::FloatOrAuto { min, max } => (min, max),
        KeyType::Int { min, max } => (min as f64, max as f64),
        KeyType::Choice(words) => {
            return Some(Control {
                key,
                target: Target::Param,
                label: label.into(),
                unit: String::new(),
                description: spec.description,
                group,
                widget: Widget::Select(
                    words
                        .iter()
                        .map(|w| (w.to_string(), w.to_string()))
                        .collect(),
                ),
                applies: spec.applies,
            })
        }
    };
    Some(Control {
        key,
        target: Target::Param,
        label: label.into(),
        unit: unit_text(spec.unit),
        description: spec.description,
        group,
        widget: Widget::Slider {
            min: slider.0,
            max: slider.1,
            step: slider.2,
            field_min,
            field_max,
        },
        applies: spec.applies,
    })
}

fn view(key: &'static str, label: &str, slider: (f64, f64, f64)) -> Option<Control> {
    view_in(Group::Analysis, key, label, slider)
}

fn view_in(
    group: Group,
    key: &'static str,
    label: &str,
    slider: (f64, f64, f64),
) -> Option<Control> {
    let spec = view_key(key)?;
    let (field_min, field_max) = match spec.ty {
        ViewType::Float { min, max } => (min, max),
        ViewType::Int { min, max } => (f64::from(min), f64::from(max)),
        ViewType::Choice(words) => {
            return Some(Control {
                key,
                target: Target::View,
                label: label.into(),
                unit: String::new(),
                description: spec.description,
                group,
                widget: Widget::Select(
                    words
                        .iter()
                        .map(|w| {
                            let text = match *w {
                                "backlash_um" => "backlash b (µm)",
                                "te_um" => "TE amplitude (µm)",
                                "fit" => "fit the data",
                                "whole" => "show the whole clearance ±b",
                                "omega" => "Ω (dimensionless)",
                                "rpm" => "input speed, rpm",
                                "on" if key == "boundaries" => "traced and drawn over the map",
                                "on" => "shown: stable solid, unstable thin",
                                "off" => "hidden",
                                other => other,
                            };
                            (w.to_string(), text.to_string())
                        })
                        .collect(),
                ),
                applies: Applies::Both,
            })
        }
        ViewType::Mesh => {
            return Some(Control {
                key,
                target: Target::View,
                label: label.into(),
                unit: String::new(),
                description: spec.description,
                group,
                // Filled with the model's meshes by the page.
                widget: Widget::Select(Vec::new()),
                applies: Applies::Both,
            });
        }
    };
    Some(Control {
        key,
        target: Target::View,
        label: label.into(),
        unit: unit_text(spec.unit),
        description: spec.description,
        group,
        widget: Widget::Slider {
            min: slider.0,
            max: slider.1,
            step: slider.2,
            field_min,
            field_max,
        },
        applies: Applies::Both,
    })
}

/// Every control of the panel, in display order.
pub fn controls() -> Vec<Control> {
    use Group::*;
    let mut c: Vec<Option<Control>> = vec![
        param("model", "Model", Model, (0.0, 0.0, 0.0)),
        param(
            "backlash_um",
            "Backlash b (all meshes)",
            Excitation,
            (0.0, 300.0, 1.0),
        ),
        param(
            "te_um",
            "TE amplitude (s1a meshes)",
            Excitation,
            (0.0, 100.0, 0.5),
        ),
        param(
            "stiffness_variation",
            "Stiffness variation v",
            Mesh,
            (0.0, 0.9, 0.01),
        ),
        param("damping_ratio", "Damping ratio ξ", Mesh, (0.0, 0.3, 0.005)),
        param(
            "torque_s1_nm",
            "Input torque on s1",
            Mesh,
            (0.0, 5000.0, 10.0),
        ),
        param(
            "torque_pinion_nm",
            "Torque on the pinion",
            Mesh,
            (0.0, 2000.0, 10.0),
        ),
        param("planets", "Planet pairs N", Mesh, (3.0, 6.0, 1.0)),
        param("phasing", "Mesh phasing", Mesh, (0.0, 0.0, 0.0)),
    ];
    for kind in ["s1a", "s2b", "ab", "rb"] {
        let b: &'static str = match kind {
            "s1a" => "backlash_s1a_um",
            "s2b" => "backlash_s2b_um",
            "ab" => "backlash_ab_um",
            _ => "backlash_rb_um",
        };
        c.push(param(
            b,
            &format!("Backlash, {kind} meshes"),
            Advanced,
            (0.0, 300.0, 1.0),
        ));
    }
    for (key, label) in [
        ("te_sin_s1a_um", "TE sine, s1a meshes"),
        ("te_sin_s2b_um", "TE sine, s2b meshes"),
        ("te_sin_ab_um", "TE sine, ab meshes"),
        ("te_sin_rb_um", "TE sine, rb meshes"),
        ("te_cos_s1a_um", "TE cosine, s1a meshes"),
        ("te_cos_s2b_um", "TE cosine, s2b meshes"),
        ("te_cos_ab_um", "TE cosine, ab meshes"),
        ("te_cos_rb_um", "TE cosine, rb meshes"),
    ] {
        c.push(param(key, label, Advanced, (-100.0, 100.0, 0.5)));
    }
    // The excitation's waveforms (docs/excitation.md).
    for (key, label) in [
        ("stiffness_wave", "Stiffness waveform"),
        ("stiffness_wave_s1a", "Stiffness waveform, s1a meshes"),
        ("stiffness_wave_s2b", "Stiffness waveform, s2b meshes"),
        ("stiffness_wave_ab", "Stiffness waveform, ab meshes"),
        ("stiffness_wave_rb", "Stiffness waveform, rb meshes"),
    ] {
        c.push(param(key, label, Advanced, (0.0, 0.0, 0.0)));
    }
    // The contact ratio the rectangle and the trapezoid read: empty for
    // the teeth's (the page's placeholder says it), or given.
    for (key, label) in [
        (
            "contact_ratio",
            "Contact ratio (rectangular and trapezoid stiffness)",
        ),
        ("contact_ratio_s1a", "Contact ratio, s1a meshes"),
        ("contact_ratio_s2b", "Contact ratio, s2b meshes"),
        ("contact_ratio_ab", "Contact ratio, ab meshes"),
        ("contact_ratio_rb", "Contact ratio, rb meshes"),
    ] {
        c.push(param(key, label, Advanced, (1.0, 2.95, 0.01)));
    }
    c.push(param(
        "stiffness_ramp",
        "Trapezoid ramp (share of a mesh period)",
        Advanced,
        (0.0, 0.5, 0.01),
    ));
    c.push(param(
        "stiffness_harmonics",
        "Stiffness harmonics kept",
        Advanced,
        (1.0, 15.0, 1.0),
    ));
    for (key, label) in [
        ("te_cos2_um", "TE second harmonic, cosine"),
        ("te_sin2_um", "TE second harmonic, sine"),
        ("te_cos3_um", "TE third harmonic, cosine"),
        ("te_sin3_um", "TE third harmonic, sine"),
        ("te_cos2_s1a_um", "TE second harmonic, cosine, s1a meshes"),
        ("te_sin2_s1a_um", "TE second harmonic, sine, s1a meshes"),
        ("te_cos3_s1a_um", "TE third harmonic, cosine, s1a meshes"),
        ("te_sin3_s1a_um", "TE third harmonic, sine, s1a meshes"),
    ] {
        c.push(param(key, label, Advanced, (-50.0, 50.0, 0.5)));
    }
    c.extend([
        view("mesh", "Mesh to plot", (0.0, 0.0, 0.0)),
        view("omega", "Selected Ω", (0.01, 3.0, 0.001)),
        view("omega_from", "Frequency range: from Ω", (0.01, 3.0, 0.01)),
        view("omega_to", "Frequency range: to Ω", (0.01, 3.0, 0.01)),
        view("harmonics", "Harmonics in the balance", (1.0, 15.0, 1.0)),
        view(
            "fr_points",
            "Points along the curve (about)",
            (2.0, 400.0, 1.0),
        ),
        view(
            "fr_ti_points",
            "Own time-integration dots (0 = the bifurcation sweep's)",
            (0.0, 60.0, 1.0),
        ),
        view(
            "fr_record_periods",
            "Periods recorded per dot",
            (1.0, 100.0, 1.0),
        ),
        view("bif_points", "Bifurcation points", (2.0, 400.0, 1.0)),
        view("bif_dir", "Bifurcation sweep", (0.0, 0.0, 0.0)),
        view("clearance", "Axes of x", (0.0, 0.0, 0.0)),
        view("axis", "Speed axes", (0.0, 0.0, 0.0)),
        view(
            "accuracy_grade",
            "Accuracy grade for Kv (ISO 1328-1)",
            (1.0, 11.0, 1.0),
        ),
        view("face_width_mm", "Face width for Kv", (5.0, 200.0, 1.0)),
        view(
            "branches",
            "Branches of repeating motion (found by shooting)",
            (0.0, 0.0, 0.0),
        ),
        view(
            "transient_periods",
            "Periods to settle (at most)",
            (0.0, 1000.0, 10.0),
        ),
        view("record_periods", "Recorded periods", (1.0, 400.0, 1.0)),
        view_in(Maps, "map_key", "Map: vertical axis", (0.0, 0.0, 0.0)),
        view_in(
            Maps,
            "boundaries",
            "Map: boundaries traced as curves",
            (0.0, 0.0, 0.0),
        ),
        view_in(Maps, "map_from", "Map: from", (0.0, 300.0, 1.0)),
        view_in(Maps, "map_to", "Map: to", (0.0, 300.0, 1.0)),
        view_in(
            Maps,
            "map_omega_points",
            "Map: speed columns",
            (2.0, 200.0, 1.0),
        ),
        view_in(Maps, "map_value_points", "Map: rows", (1.0, 100.0, 1.0)),
        view_in(
            Maps,
            "map_transient_periods",
            "Map: transient periods per cell (max)",
            (0.0, 1000.0, 10.0),
        ),
        view_in(
            Maps,
            "map_record_periods",
            "Map: recorded periods per cell",
            (1.0, 400.0, 1.0),
        ),
        view_in(
            Maps,
            "lyap_points",
            "Lyapunov: speed points (0 = off)",
            (0.0, 200.0, 1.0),
        ),
        view_in(
            Maps,
            "lyap_transient_periods",
            "Lyapunov: transient periods",
            (0.0, 1000.0, 10.0),
        ),
        view_in(
            Maps,
            "lyap_periods",
            "Lyapunov: averaged periods",
            (10.0, 1000.0, 10.0),
        ),
    ]);
    c.into_iter().flatten().collect()
}

/// A control's label for `model`: the gear pair has one mesh, so the
/// compound set's "(all meshes)" or "(s1a meshes)" is dropped there.
pub fn label_for(c: &Control, model: ModelKind) -> String {
    match (model, c.label.split_once(" (")) {
        (ModelKind::GearPair, Some((head, tail))) if tail.ends_with("meshes)") => head.to_string(),
        _ => c.label.clone(),
    }
}

/// The page's subtitle for `model`: what is being explored.
pub fn model_subtitle(model: ModelKind) -> &'static str {
    match model {
        ModelKind::Ravigneaux => "gear rattle and shock in a Ravigneaux compound planetary set",
        ModelKind::GearPair => "gear rattle and shock in a single spur gear pair",
    }
}

/// Whether a control is shown for a model.
pub fn shown_for(c: &Control, model: ModelKind) -> bool {
    c.applies.includes(model)
}

/// A number for a number field: shortest exact form, or empty for NaN
/// (a shortcut whose per-kind values differ).
pub fn field_text(x: f64) -> String {
    if x.is_finite() {
        crate::settings::fmt_exact(x)
    } else {
        String::new()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_control_names_a_real_key() {
        let all = controls();
        assert!(all.len() >= 25);
        for c in &all {
            match c.target {
                Target::Param => assert!(keys::spec(c.key).is_some(), "{}", c.key),
                Target::View => assert!(view_key(c.key).is_some(), "{}", c.key),
            }
            if let Widget::Slider {
                min,
                max,
                field_min,
                field_max,
                step,
            } = c.widget
            {
                assert!(
                    min >= field_min && max <= field_max && min < max && step > 0.0,
                    "{}",
                    c.key
                );
            }
        }
        for must in [
            "backlash_um",
            "te_um",
            "stiffness_variation",
            "damping_ratio",
            "torque_s1_nm",
            "planets",
            "phasing",
            "omega_from",
            "omega_to",
            "harmonics",
            "mesh",
            "model",
        ] {
            assert!(all.iter().any(|c| c.key == must), "{must}");
        }
        let pair: Vec<_> = all
            .iter()
            .filter(|c| shown_for(c, ModelKind::GearPair))
            .map(|c| c.key)
            .collect();
        assert!(pair.contains(&"backlash_um") && !pair.contains(&"planets"));
    }
}
