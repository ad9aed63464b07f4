//! The animated gear set's picture at one instant, as a scene: shapes
//! (polygons, circles, lines with their paint) and text, in canvas pixels,
//! in drawing order. `web/anim.rs` only rasterizes it (and the plots'
//! overlays made of the same items); everything it shows is computed here
//! and tested natively.

use crate::gearset::{
    gauge_factor, sample_at, tooth_outline, view_transform, AnimClock, BodyKind, Contact, GearSet,
};
use figures::protocol::OmegaResult;
use glam::DVec2;

/// One piece of a path.
#[derive(Debug, Clone, PartialEq)]
pub enum SubPath {
    /// A closed polygon.
    Polygon(Vec<DVec2>),
    /// An open polyline.
    Polyline(Vec<DVec2>),
    /// A full circle.
    Circle {
        /// Centre (px).
        c: DVec2,
        /// Radius (px).
        r: f64,
    },
    /// An axis-aligned rectangle.
    Rect {
        /// Top-left corner (px).
        at: DVec2,
        /// Width and height (px).
        size: DVec2,
    },
}

/// Something drawn.
#[derive(Debug, Clone, PartialEq)]
pub enum Item {
    /// The whole canvas filled with a colour.
    Clear(String),
    /// The whole canvas made transparent (an overlay's canvas).
    Erase,
    /// A path, filled and/or stroked.
    Shape {
        /// Its pieces (all one path: filled together, stroked together).
        parts: Vec<SubPath>,
        /// Fill colour (CSS).
        fill: Option<String>,
        /// Fill by the even-odd rule (the ring's annulus) instead of non-zero.
        even_odd: bool,
        /// Stroke colour (CSS) and width (px).
        stroke: Option<(String, f64)>,
    },
    /// A line of text (12 px sans-serif) with its left baseline at `at`.
    Text {
        /// Where (px).
        at: DVec2,
        /// What.
        text: String,
        /// Colour (CSS).
        color: String,
    },
    /// The colour key: a dot and a label per entry, laid out left to right
    /// from `at` by the labels' measured widths.
    Key {
        /// The first label's baseline (px).
        at: DVec2,
        /// Dot colour and label per entry.
        entries: Vec<(String, String)>,
    },
}

/// A mesh gauge as drawn, for the tests' status.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Marker {
    /// Mesh index.
    pub mesh: usize,
    /// Mesh name.
    pub name: String,
    /// The pitch point (px).
    pub px: [f64; 2],
    /// `x = delta - e` (µm).
    pub x_um: f64,
    /// Backlash (µm).
    pub b_um: f64,
    /// Contact state.
    pub state: Contact,
}

/// The gear set at one instant.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// What to draw, in order.
    pub items: Vec<Item>,
    /// The mesh gauges.
    pub markers: Vec<Marker>,
    /// The animation's sample shown.
    pub sample: usize,
    /// Time in mesh periods since the recording began (the time view's axis).
    pub t_periods: f64,
    /// The gauges' exaggeration.
    pub factor: f64,
}

/// Height of the key and clock band under the gear set (px).
const KEY_H: f64 = 62.0;
const INK: &str = "#1d232b";

fn css((r, g, b): (u8, u8, u8)) -> String {
    format!("rgb({r},{g},{b})")
}

fn stroke(color: &str, width: f64, parts: Vec<SubPath>) -> Item {
    Item::Shape {
        parts,
        fill: None,
        even_odd: false,
        stroke: Some((color.into(), width)),
    }
}

fn dot(c: DVec2, r: f64, color: String) -> Item {
    Item::Shape {
        parts: vec![SubPath::Circle { c, r }],
        fill: Some(color),
        even_odd: false,
        stroke: None,
    }
}

/// The colour key laid out (an [`Item::Key`]): per entry a dot of radius
/// 6 and its label 16 px right of the dot's left edge, the next entry 18 px
/// after the label; `width` is a label's measured width (px).
pub fn key_items(
    at: DVec2,
    entries: &[(String, String)],
    width: impl Fn(&str) -> f64,
) -> Vec<Item> {
    let mut x = at.x;
    let mut items = Vec::new();
    for (color, label) in entries {
        items.push(dot(DVec2::new(x + 6.0, at.y - 4.0), 6.0, color.clone()));
        items.push(Item::Text {
            at: DVec2::new(x + 16.0, at.y),
            text: label.clone(),
            color: "#1d232b".into(),
        });
        x += 16.0 + width(label) + 18.0;
    }
    items
}

/// Fill and stroke colours of a body.
fn body_paint(kind: BodyKind, name: &str) -> (&'static str, &'static str) {
    match (kind, name) {
        (BodyKind::Ring, _) => ("rgba(200,205,212,0.55)", "#6b7480"),
        (_, "s1") | (_, "pinion") => ("rgba(190,210,240,0.75)", "#3d5f8f"),
        (_, "s2") | (_, "gear") => ("rgba(215,200,235,0.55)", "#6a4f8f"),
        _ if name.starts_with('a') => ("rgba(234,241,251,0.85)", "#4b6fa5"),
        _ => ("rgba(243,238,250,0.85)", "#7d62a3"),
    }
}

/// The gear set `set` at the animation clock's instant of the result `r`,
/// on a canvas of `size` pixels.
pub fn gear_scene(set: &GearSet, r: &OmegaResult, clock: &AnimClock, size: (f64, f64)) -> Scene {
    let (w, h) = size;
    let len = r.anim.x_um.first().map_or(0, Vec::len);
    let k = clock.sample(len);
    let spp = f64::from(r.samples_per_period.max(1));
    let t_periods = (f64::from(r.anim.start_sample) + clock.pos) / spp;
    let tau = t_periods;
    let mut items = vec![Item::Clear("#ffffff".into())];
    let view = view_transform(set.extent_m, (w, h - KEY_H));
    let scale = view.matrix2.x_axis.x;
    // Bodies: the ring, the large sun, the small sun, then the planets.
    for body in &set.bodies {
        let t = view * set.body_transform(body, tau);
        let outline: Vec<DVec2> = tooth_outline(body, set.module_m)
            .iter()
            .map(|q| t.transform_point2(*q))
            .collect();
        let (fill, line) = body_paint(body.kind, &body.name);
        let c = t.transform_point2(DVec2::ZERO);
        let mut parts = vec![SubPath::Polygon(outline)];
        let ring = body.kind == BodyKind::Ring;
        if ring {
            // The ring's body: the annulus between its teeth and its rim.
            let rim = (body.pitch_radius_m + 2.2 * set.module_m) * scale;
            parts.push(SubPath::Circle { c, r: rim });
        }
        items.push(Item::Shape {
            parts,
            fill: Some(fill.into()),
            even_odd: ring,
            stroke: Some((line.into(), 1.0)),
        });
        // A radial mark so the turning shows at any tooth count.
        let m = t.transform_point2(DVec2::new(body.pitch_radius_m * 0.8, 0.0));
        items.push(stroke(line, 1.0, vec![SubPath::Polyline(vec![c, m])]));
    }
    // The carrier: pins, arms and its circle, turning with it.
    if set.carrier_radius_m > 0.0 {
        let centres: Vec<DVec2> = set
            .bodies
            .iter()
            .filter(|b| b.kind == BodyKind::Planet)
            .map(|b| (view * set.body_transform(b, tau)).transform_point2(DVec2::ZERO))
            .collect();
        for pair in centres.chunks(2) {
            items.push(stroke(
                "rgba(90,100,115,0.9)",
                2.0,
                vec![SubPath::Polyline(pair.to_vec())],
            ));
        }
        for &c in &centres {
            items.push(dot(c, 4.0, "#5a6573".into()));
        }
    }
    // Body labels.
    for body in &set.bodies {
        let t = view * set.body_transform(body, tau);
        let c = match body.kind {
            BodyKind::Planet => t.transform_point2(DVec2::ZERO),
            BodyKind::Ring => {
                view.transform_point2(DVec2::new(0.72 * set.extent_m, -0.72 * set.extent_m))
            }
            BodyKind::Sun => {
                let off = if body.name == "s2" {
                    -0.86 * body.pitch_radius_m
                } else {
                    0.0
                };
                let base = view.transform_point2(body.centre_m);
                DVec2::new(base.x, base.y - off * scale)
            }
        };
        items.push(Item::Text {
            at: DVec2::new(c.x - 6.0, c.y + 4.0),
            text: body.name.clone(),
            color: INK.into(),
        });
    }
    // Mesh gauges and contact markers.
    let x_now = sample_at(&r.anim.x_um, k);
    let x_max = r
        .anim
        .x_um
        .iter()
        .flatten()
        .fold(0.0_f64, |m, x| m.max(x.abs()));
    let factor = gauge_factor(set.module_m, &r.anim.backlash_um, x_max);
    let mut markers = Vec::new();
    for site in &set.sites {
        let (pt, tan) = set.site_at(site, tau);
        let c = view.transform_point2(pt);
        let d = view.transform_vector2(tan).normalize_or_zero();
        let (Some(&x), Some(&b)) = (x_now.get(site.mesh), r.anim.backlash_um.get(site.mesh)) else {
            continue;
        };
        if !x.is_finite() {
            continue;
        }
        let state = Contact::of(x, b);
        let to_px = |um: f64| um * 1e-6 * factor * scale;
        // Ticks at +-b.
        let n = d.perp();
        for sb in [b, -b] {
            let q = c + d * to_px(sb);
            let tick = vec![q - n * 5.0, q + n * 5.0];
            items.push(stroke("#222", 1.5, vec![SubPath::Polyline(tick)]));
        }
        let bar = vec![c, c + d * to_px(x)];
        items.push(stroke(&css(state.rgb()), 3.0, vec![SubPath::Polyline(bar)]));
        markers.push(Marker {
            mesh: site.mesh,
            name: site.name.clone(),
            px: [c.x, c.y],
            x_um: x,
            b_um: b,
            state,
        });
    }
    for m in &markers {
        items.push(dot(DVec2::from(m.px), 6.0, css(m.state.rgb())));
    }
    // The key and the clock.
    let ky = h - KEY_H + 14.0;
    items.push(Item::Key {
        at: DVec2::new(10.0, ky),
        entries: [Contact::Drive, Contact::Apart, Contact::Back]
            .iter()
            .map(|s| (css(s.rgb()), s.label().to_string()))
            .collect(),
    });
    let clock_line = format!(
        "t = {t_periods:.3} mesh periods (sample {} of the time history), Ω = {:.4}{}",
        r.anim.start_sample as usize + k,
        r.omega,
        if clock.playing { "" } else { "; paused" }
    );
    let gauge_line = format!(
        "gauges: x = δ − e along each mesh's pitch tangent, exaggerated × {factor}; black ticks at ±b"
    );
    for (dy, text) in [(18.0, clock_line), (34.0, gauge_line)] {
        items.push(Item::Text {
            at: DVec2::new(10.0, ky + dy),
            text,
            color: INK.into(),
        });
    }
    Scene {
        items,
        markers,
        sample: k,
        t_periods,
        factor,
    }
}

/// The note under the animation: how slow the motion is.
pub fn anim_note(r: &OmegaResult, clock: &AnimClock) -> String {
    let slow = r.mesh_freq_hz / clock.periods_per_s;
    format!(
        "Slow motion: {} mesh periods per second of {:.0} Hz, {:.0}× slower than real time. Drawn to scale from the module and tooth counts; bodies turn with the rigid-body motion (ring held), the vibration shows in the mesh gauges.",
        clock.periods_per_s, r.mesh_freq_hz, slow
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_key_sets_each_label_after_the_previous_labels_width() {
        let entries = vec![
            ("red".to_string(), "ab".to_string()),
            ("blue".into(), "cde".into()),
        ];
        // A label 10 px a letter wide.
        let items = key_items(DVec2::new(10.0, 50.0), &entries, |t| 10.0 * t.len() as f64);
        let texts: Vec<(f64, &str)> = items
            .iter()
            .filter_map(|i| match i {
                Item::Text { at, text, .. } => Some((at.x, text.as_str())),
                _ => None,
            })
            .collect();
        // The second entry starts after dot, gap, 20 px of label and 18 px.
        assert_eq!(texts, [(26.0, "ab"), (26.0 + 16.0 + 20.0 + 18.0, "cde")]);
        let dots = items
            .iter()
            .filter(|i| matches!(i, Item::Shape { fill: Some(c), .. } if c == "blue"))
            .count();
        assert_eq!(dots, 1);
    }
    use figures::protocol::{OmegaSpec, RunOptions};
    use solver::model::Model;
    use worker::jobs::omega::{omega_result, OmegaJob};

    /// The default set and a real (short) steady state of it.
    fn fixture() -> (GearSet, OmegaResult) {
        let s = figures::link::decode("backlash_um=20").settings;
        let model = Model::new(&s.params).unwrap();
        let meshes: Vec<_> = model
            .system
            .meshes
            .iter()
            .map(|m| (m.kind, m.planet))
            .collect();
        let set = GearSet::new(&s.params, &meshes).unwrap();
        let job = OmegaJob {
            id: 1,
            model,
            spec: OmegaSpec {
                omega: 1.05,
                mesh: None,
                run: RunOptions {
                    transient_periods: 30,
                    record_periods: 8,
                },
                samples_per_period: 32,
                max_order: 8.0,
            },
        };
        (set, omega_result(&job, None).unwrap())
    }

    const SIZE: (f64, f64) = (760.0, 600.0);

    /// One outline per body with every tooth's vertices, the ring filled as
    /// an annulus; one gauge per mesh whose state is the dead zone's
    /// verdict on that mesh's x at the shown sample, drawn as a dot of that
    /// state's colour at the mesh's pitch point.
    #[test]
    fn the_scene_draws_every_body_and_every_mesh_in_its_contact_state() {
        let (set, r) = fixture();
        let clock = AnimClock {
            pos: 37.6,
            ..AnimClock::default()
        };
        let sc = gear_scene(&set, &r, &clock, SIZE);
        assert_eq!(sc.items[0], Item::Clear("#ffffff".into()));
        assert_eq!(sc.sample, 37);
        let outlines: Vec<&Item> = sc
            .items
            .iter()
            .filter(|i| matches!(i, Item::Shape { parts, .. } if matches!(parts[0], SubPath::Polygon(_))))
            .collect();
        assert_eq!(outlines.len(), set.bodies.len());
        for (item, body) in outlines.iter().zip(&set.bodies) {
            let Item::Shape {
                parts, even_odd, ..
            } = item
            else {
                unreachable!()
            };
            let SubPath::Polygon(pts) = &parts[0] else {
                unreachable!()
            };
            assert_eq!(pts.len(), tooth_outline(body, set.module_m).len());
            assert_eq!(*even_odd, body.kind == BodyKind::Ring, "{}", body.name);
        }
        assert_eq!(sc.markers.len(), set.sites.len());
        for m in &sc.markers {
            let x = r.anim.x_um[m.mesh][37];
            assert_eq!(m.x_um, x);
            assert_eq!(m.state, Contact::of(x, r.anim.backlash_um[m.mesh]));
            assert!((0.0..SIZE.0).contains(&m.px[0]) && (0.0..SIZE.1).contains(&m.px[1]));
            let want = Item::Shape {
                parts: vec![SubPath::Circle {
                    c: DVec2::from(m.px),
                    r: 6.0,
                }],
                fill: Some(css(m.state.rgb())),
                even_odd: false,
                stroke: None,
            };
            assert!(sc.items.contains(&want), "{}", m.name);
        }
        let t = (f64::from(r.anim.start_sample) + 37.6) / 32.0;
        assert!((sc.t_periods - t).abs() < 1e-12);
    }

    /// Each gauge bar runs from the pitch point by x times the stated
    /// exaggeration, at the view's scale; the ticks stand at +-b on the
    /// same line, so the bar passes a tick exactly when the teeth touch.
    #[test]
    fn gauges_are_to_the_stated_exaggeration() {
        let (set, r) = fixture();
        let clock = AnimClock::default();
        let sc = gear_scene(&set, &r, &clock, SIZE);
        let scale = view_transform(set.extent_m, (SIZE.0, SIZE.1 - KEY_H))
            .matrix2
            .x_axis
            .x;
        let bars: Vec<(DVec2, DVec2)> = sc
            .items
            .iter()
            .filter_map(|i| match i {
                Item::Shape {
                    parts,
                    stroke: Some((_, w)),
                    ..
                } if *w == 3.0 => match &parts[0] {
                    SubPath::Polyline(p) => Some((p[0], p[1])),
                    _ => None,
                },
                _ => None,
            })
            .collect();
        assert_eq!(bars.len(), sc.markers.len());
        for (m, (a, b)) in sc.markers.iter().zip(&bars) {
            let want = m.x_um.abs() * 1e-6 * sc.factor * scale;
            assert!(((*b - *a).length() - want).abs() < 1e-9, "{}", m.name);
            let beyond = (*b - *a).length() > m.b_um * 1e-6 * sc.factor * scale;
            assert_eq!(beyond, m.state != Contact::Apart, "{}", m.name);
        }
        // The clock line names Omega and whether it is paused.
        let texts: Vec<&str> = sc
            .items
            .iter()
            .filter_map(|i| match i {
                Item::Text { text, .. } => Some(text.as_str()),
                _ => None,
            })
            .collect();
        assert!(texts
            .iter()
            .any(|t| t.contains("Ω = 1.0500") && !t.contains("paused")));
        let mut paused = clock;
        paused.playing = false;
        let sc = gear_scene(&set, &r, &paused, SIZE);
        assert!(sc
            .items
            .iter()
            .any(|i| matches!(i, Item::Text { text, .. } if text.ends_with("; paused"))));
    }
}
