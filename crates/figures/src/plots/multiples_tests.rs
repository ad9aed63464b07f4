//! A family's small multiples drawn to SVG natively: the phase
//! portraits' budget of drawn samples and their drawing in parts.

use super::tests::{result, svg_sized};
use super::*;
use crate::protocol::OmegaResult;
use crate::views::multiples::Panel;

/// The polyline points of an SVG drawing (plotters' `<polyline points=...>`).
fn polyline_points(svg: &str) -> usize {
    svg.split("<polyline")
        .skip(1)
        .filter_map(|p| p.split("points=\"").nth(1))
        .filter_map(|p| p.split('"').next())
        .map(|p| p.split_whitespace().count())
        .sum()
}

/// A family's phase portraits share a budget of drawn samples: six orbits
/// of 1000 periods draw their last 250 periods each (the key says so);
/// a short record is drawn whole and the key says nothing of a cut.
#[test]
fn family_phase_panels_draw_the_last_periods_within_a_budget() {
    use std::f64::consts::TAU;
    // Quasi-periodic: no period retraces another's pixels.
    let long = |k: usize| {
        let mut r = result();
        let n = 64 * 1000;
        r.record_periods = 1000;
        let t = |i: usize| i as f64 / 64.0 * TAU;
        r.x_um = (0..n)
            .map(|i| 110.0 + 30.0 * t(i).sin() + 12.0 * (0.618_034 * t(i)).sin() + k as f64)
            .collect();
        r.xdot_m_s = (0..n)
            .map(|i| 0.5 * t(i).cos() + 0.2 * (0.414_214 * t(i)).cos())
            .collect();
        r
    };
    assert_eq!(
        multiples::panel_orbit_tail(&long(0), 6),
        (64_000 - 250 * 64, 250)
    );
    assert_eq!(multiples::panel_orbit_tail(&long(0), 1), (0, 1000));
    let orbits: Vec<OmegaResult> = (0..6).map(long).collect();
    let panels = titled_panels(&orbits);
    let size = multiples::family_panels_size(6);
    let s = svg_sized(size, |root| {
        multiples::draw_phase_panels(root, &panels, false, "", None)
    });
    assert!(s.contains("last 250 of 1000 recorded periods"), "key");
    let drawn = polyline_points(&s);
    assert!(
        (10_000..=multiples::PANEL_ORBIT_SAMPLES + 2_000).contains(&drawn),
        "{drawn} polyline points"
    );
    // The Poincaré sections draw every period's dot and cut nothing.
    let s = svg_sized(size, |root| {
        multiples::draw_phase_panels(root, &panels, true, "", None)
    });
    assert!(!s.contains("recorded periods"));
    let short_orbit = result();
    let short: Vec<Panel<&OmegaResult>> = (0..6)
        .map(|k| Panel {
            title: format!("({k})"),
            data: Ok(&short_orbit),
        })
        .collect();
    assert_eq!(multiples::panel_orbit_tail(&result(), 6), (0, 20));
    let s = svg_sized(size, |root| {
        multiples::draw_phase_panels(root, &short, false, "", None)
    });
    assert!(!s.contains("recorded periods"), "no cut, no words on one");
}

/// Panels "(0)", "(1)", ... of `orbits`.
fn titled_panels(orbits: &[OmegaResult]) -> Vec<Panel<&OmegaResult>> {
    orbits
        .iter()
        .enumerate()
        .map(|(k, r)| Panel {
            title: format!("({k})"),
            data: Ok(r),
        })
        .collect()
}

/// Drawn in parts, one panel a frame as the page does, the small multiples
/// are the whole drawing's elements: the first part clears the canvas and
/// draws the title and key, each later part its own panel, nothing twice.
#[test]
fn small_multiples_drawn_in_parts_are_the_whole_drawing() {
    let orbits: Vec<OmegaResult> = (0..6)
        .map(|k| {
            let mut r = result();
            r.backlash_um = 50.0 + 10.0 * k as f64;
            r
        })
        .collect();
    let mut panels = titled_panels(&orbits);
    panels[4].data = Err("computing…".into());
    let size = multiples::family_panels_size(6);
    // An SVG document's elements, one a line, without its header.
    let body = |s: &str| -> Vec<String> {
        s.lines()
            .filter(|l| !l.starts_with("<svg") && !l.starts_with("</svg"))
            .map(str::to_string)
            .collect()
    };
    for poincare in [false, true] {
        let whole = svg_sized(size, |root| {
            multiples::draw_phase_panels(root, &panels, poincare, "", None)
        });
        let mut parts = Vec::new();
        for k in 0..panels.len() {
            let s = svg_sized(size, |root| {
                multiples::draw_phase_panels(root, &panels, poincare, "", Some(k))
            });
            let lines = body(&s);
            // Only the first part clears the canvas (a white rectangle
            // over all of it) and holds the title.
            assert_eq!(
                s.contains("Phase portraits") || s.contains("Poincaré sections"),
                k == 0
            );
            assert!(!lines.is_empty(), "part {k} drew nothing");
            parts.extend(lines);
        }
        let mut whole = body(&whole);
        whole.sort();
        parts.sort();
        assert_eq!(whole, parts, "poincare {poincare}");
    }
}
