//! The plots drawn to SVG natively: labels, units, legends, ranges.

use super::fr::{compact_key, fr_key};
use super::*;
use crate::protocol::OmegaResult;
use crate::views::fr::FrView;
use crate::views::fr::{FrBranch, FrCurvePoint, FrMarker, FrMarkerKind, FrSource};
use crate::views::multiples::Panel;

fn svg<F: FnOnce(&DrawingArea<SVGBackend, Shift>) -> Res<()>>(f: F) -> String {
    svg_sized((WIDTH, HEIGHT), f)
}

pub(super) fn svg_sized<F: FnOnce(&DrawingArea<SVGBackend, Shift>) -> Res<()>>(
    size: (u32, u32),
    f: F,
) -> String {
    let mut s = String::new();
    {
        let root = SVGBackend::with_string(&mut s, size).into_drawing_area();
        f(&root).unwrap();
    }
    s
}

pub(super) fn result() -> OmegaResult {
    crate::views::test_support::omega_result()
}

#[test]
fn a_failed_point_is_counted_and_its_reason_named() {
    let failed = vec![
        (
            1.1,
            "the response grows without bound: mesh rb1 deflected 5e-3 m".to_string(),
        ),
        (1.2, "step size fell to 1e-17 s at t = 0.1 s".to_string()),
    ];
    assert_eq!(
        failed_label(&failed),
        "2 point(s) failed, not plotted, first at Ω = 1.100: the response grows without bound"
    );
    assert_eq!(failed_label(&[]), "0 point(s) failed, not plotted");
}

#[test]
fn frame_maps_pixels_to_omega_and_back() {
    let f = PlotFrame {
        top_left: DVec2::new(60.0, 30.0),
        bottom_right: DVec2::new(760.0, 360.0),
        x_range: (0.1, 2.0),
        y_range: (-100.0, 100.0),
    };
    let p = f.to_px(1.05, 0.0);
    assert!((f.x_at(p.x).unwrap() - 1.05).abs() < 1e-12);
    assert_eq!(f.x_at(0.0), None);
    assert_eq!(f.x_at(f64::NAN), None);
    assert_eq!(f.x_at(55.0), Some(0.1));
}

#[test]
fn ranges_never_magnify_noise() {
    let (lo, hi) = padded_range([5.0, 5.0 + 1e-9].into_iter(), &[], 20.0);
    assert!(hi - lo >= 20.0);
    assert_eq!(padded_range(std::iter::empty(), &[], 1.0), (-1.0, 1.0));
}

/// An A/B comparison's frequency response: two branches, a marker, an
/// overlay point, a natural frequency and a solver failure.
fn ab_fr() -> FrView {
    let point = |k: u32| FrCurvePoint {
        omega: 0.1 + 0.2 * f64::from(k),
        max_um: 120.0 + f64::from(k),
        min_um: 90.0 - f64::from(k),
        stable: Some(k <= 6),
        regime: Some(Regime::NoImpact),
        period: Some(1),
        bifurcation: (k == 7).then_some(FrMarkerKind::Fold),
        piece: 0,
    };
    let source = FrSource::Hbm { harmonics: 5 };
    FrView {
        method: source.label(),
        source,
        mesh_label: "s1a1".into(),
        backlash_um: vec![150.0],
        pinned_backlash_um: vec![100.0],
        branches: vec![
            FrBranch {
                label: "A: backlash_um=100".into(),
                points: (0..10).map(point).collect(),
                faded: false,
                pinned: true,
                member: None,
            },
            FrBranch {
                label: "B: backlash_um=150; HBM, H = 5".into(),
                points: (0..10).map(point).collect(),
                faded: false,
                pinned: false,
                member: None,
            },
        ],
        markers: vec![FrMarker {
            omega: 1.5,
            value_um: 127.0,
            kind: FrMarkerKind::Fold,
        }],
        overlay: vec![point(2)],
        overlay_source: Some(FrSource::TimeIntegration {
            transient_periods: 300,
            record_periods: 30,
        }),
        discrepancy: crate::views::fr::Discrepancy {
            max_um: Some(1.5),
            compared: 1,
            off_branch: 2,
        },
        natural: vec![NaturalFreq {
            omega: 0.5,
            frequency_hz: 3000.0,
            kind: "rotational".into(),
            multiplicity: 1,
        }],
        omega_from: 0.1,
        omega_to: 2.0,
        selected_omega: 0.84,
        selected_motion: None,
        branch_error: Some((1.9, "no convergence at Omega = 1.9".into())),
        failed: vec![],
        done: 10,
        progress: 0.95,
        finished: true,
        branch_notes: Vec::new(),
        whole_clearance: true,
        speed: Default::default(),
    }
}

#[test]
fn every_plot_draws_labels_units_and_legends() {
    let fr = ab_fr();
    let mut frame = None;
    let s = svg(|root| {
        frame = Some(draw_fr(root, &fr, "")?);
        Ok(())
    });
    assert!(s.contains("µm") && s.contains("Ω"), "{s}");
    // A comparison's key holds more than the drawn key's eight entries:
    // what gives way is counted and is in the full key.
    for text in [
        "dashed: unstable (a small disturbance grows)",
        "6 more in the full key under the plot",
        "time integration: the actual response (1 points; within 1.5 µm of the stable curve)",
        "Solver failure after Ω = 1.9000",
        "(partial)",
        "max x (A: backlash_um=100)",
        "max x (B: backlash_um=150; HBM, H = 5)",
    ] {
        assert!(s.contains(text), "{text} missing");
    }
    let f = frame.unwrap();
    assert!(f.bottom_right.x > f.top_left.x);
    let r = result();
    for s in [
        svg(|root| draw_phase(root, &r, "")),
        svg(|root| draw_poincare(root, &r, "")),
        svg(|root| draw_time(root, &r, "").map(|_| ())),
        svg(|root| draw_spectrum(root, &r, "")),
    ] {
        assert!(s.contains("µm") && s.contains("s1a1"), "{s}");
    }
    let s = svg(|root| draw_message(root, "Bifurcation diagram", "waiting for the workers"));
    assert!(s.contains("waiting"));
}

#[test]
fn wrap_breaks_at_spaces() {
    assert_eq!(wrap("aa bb cc", 5), vec!["aa bb", "cc"]);
}

fn hex(c: RGBColor) -> String {
    format!("#{:02X}{:02X}{:02X}", c.0, c.1, c.2)
}

#[test]
fn a_family_overlays_one_colour_per_value_named_in_words() {
    let curve = |a: f64| -> Vec<FrCurvePoint> {
        (0..10)
            .map(|k| FrCurvePoint {
                omega: 0.2 + 0.1 * f64::from(k),
                max_um: a,
                min_um: -a,
                stable: Some(true),
                regime: Some(Regime::NoImpact),
                period: Some(1),
                bifurcation: None,
                piece: 0,
            })
            .collect()
    };
    let fr = fr_view(
        200.0,
        [0.0, 20.0, 30.0]
            .iter()
            .enumerate()
            .map(|(m, te)| FrBranch {
                label: format!("TE {te} µm"),
                points: curve(40.0 + te),
                faded: false,
                pinned: false,
                member: Some(m),
            })
            .collect(),
    );
    let s = svg(|root| draw_fr(root, &fr, "").map(|_| ()));
    for (m, text) in ["TE 0 µm", "TE 20 µm", "TE 30 µm"].iter().enumerate() {
        assert!(s.contains(text), "{text} missing from the legend: {s}");
        assert!(
            s.contains(&hex(family_color(m))),
            "member {m}'s colour missing"
        );
    }
    // Words only: one legend entry per value, no "max x (...)" pairs.
    assert!(!s.contains("max x (TE"), "{s}");
    assert!(s.contains("max and min x per value"));
    // No regime strip under a family, so no key for one.
    assert!(!s.contains("regime strip"), "{s}");
}

#[test]
fn small_multiples_draw_every_panel_with_its_title() {
    let mut other = result();
    other.x_um.iter_mut().for_each(|x| *x -= 400.0);
    other.period = None;
    other.motion = crate::protocol::Motion::NotPeriodic;
    let first = result();
    let panels = vec![
        Panel {
            title: "(a) TE 0 µm".into(),
            data: Ok(&first),
        },
        Panel {
            title: "(b) TE 20 µm".into(),
            data: Ok(&other),
        },
        Panel {
            title: "(c) TE 30 µm".into(),
            data: Err("Computing the steady state…".into()),
        },
    ];
    // The shared range holds both orbits (110 ± 30 and -290 ± 30 µm).
    let (x, _) = multiples::phase_ranges(&panels);
    assert!(x.0 < -320.0 && x.1 > 140.0, "{x:?}");
    for poincare in [false, true] {
        let s = svg(|root| multiples::draw_phase_panels(root, &panels, poincare, "", None));
        for text in [
            "(a) TE 0 µm: period 1 (exact)",
            "(b) TE 20 µm: not periodic",
            "(c) TE 30 µm",
            "Computing",
        ] {
            assert!(s.contains(text), "{text} missing");
        }
        assert!(s.contains("x axis per panel"));
        // Each panel's x axis fits its own orbit: 0 µm, between the two
        // orbits, is on no panel's axis (a shared one would hold it).
        assert!(!s.contains(">0<"), "a shared x axis");
    }
}

/// The axes fit the data unless the whole clearance is asked for: then
/// both ±b and zero are in range, and the plots differ.
#[test]
fn axes_fit_the_data_or_show_the_whole_clearance() {
    assert!(contact_levels(&[100.0], &[50.0], false).is_empty());
    let whole = contact_levels(&[100.0], &[50.0], true);
    for v in [100.0, -100.0, 50.0, -50.0, 0.0] {
        assert!(whole.contains(&v), "{v}");
    }
    let r = result();
    let fit = svg(|root| draw_phase_with(root, &r, "", false));
    let all = svg(|root| draw_phase_with(root, &r, "", true));
    assert_ne!(fit, all);
    assert_eq!(all, svg(|root| draw_phase(root, &r, "")));
}

/// The texts of an SVG drawn by plotters: anchor (x, y) and words.
fn texts(s: &str) -> Vec<(f64, f64, String)> {
    let attr = |tag: &str, name: &str| -> Option<f64> {
        let at = tag.find(&format!(" {name}=\""))? + name.len() + 3;
        let end = tag[at..].find('"')? + at;
        tag[at..end].parse().ok()
    };
    s.split("<text")
        .skip(1)
        .filter_map(|part| {
            let (tag, rest) = part.split_once('>')?;
            let words = rest.split("</text>").next()?;
            let words = words
                .trim()
                .replace("&lt;", "<")
                .replace("&gt;", ">")
                .replace("&amp;", "&");
            Some((attr(tag, "x")?, attr(tag, "y")?, words))
        })
        .collect()
}

/// Checks a plot's layout: every key entry (words in `key`) is drawn under
/// the x axis's description, which is under the plotting area; with the
/// frame known, no words at all are drawn inside the plotting area (no
/// legend over the data), and the caption is above it.
fn assert_key_outside(name: &str, s: &str, key: &[&str], x_desc: &str, frame: Option<PlotFrame>) {
    let t = texts(s);
    let find = |w: &str| {
        t.iter()
            .find(|(_, _, words)| words.contains(w))
            .unwrap_or_else(|| panic!("{name}: \"{w}\" not drawn: {t:?}"))
            .clone()
    };
    let desc_y = find(x_desc).1;
    for k in key {
        let (_, y, _) = find(k);
        assert!(
            y > desc_y,
            "{name}: key entry \"{k}\" at y = {y}, above the x axis description at {desc_y}"
        );
    }
    if let Some(f) = frame {
        let inside = |x: f64, y: f64| {
            x > f.top_left.x && x < f.bottom_right.x && y > f.top_left.y && y < f.bottom_right.y
        };
        let over: Vec<_> = t.iter().filter(|(x, y, _)| inside(*x, *y)).collect();
        assert!(over.is_empty(), "{name}: words over the data: {over:?}");
        for k in key {
            assert!(
                find(k).1 > f.bottom_right.y,
                "{name}: \"{k}\" not under the plotting area"
            );
        }
        // The caption (the first text) is above the plotting area.
        assert!(t[0].1 < f.top_left.y, "{name}: caption at {}", t[0].1);
    }
}

/// A plot drawn to SVG at `size`, with the frame its drawing returns.
fn framed<F: FnOnce(&DrawingArea<SVGBackend, Shift>) -> Res<PlotFrame>>(
    size: (u32, u32),
    f: F,
) -> (String, Option<PlotFrame>) {
    let mut frame = None;
    let s = svg_sized(size, |root| {
        frame = Some(f(root)?);
        Ok(())
    });
    (s, frame)
}

/// No legend covers the data: each plot's key sits under its chart, at the
/// canvas sizes of the page (760 x 400, the Lyapunov view 760 x 300), for
/// an A/B comparison, a family, the orbit views and the Lyapunov view.
#[test]
fn every_key_is_under_its_chart_never_over_the_data() {
    let mut fr = ab_fr();
    for whole in [true, false] {
        fr.whole_clearance = whole;
        let (s, frame) = framed((WIDTH, HEIGHT), |root| draw_fr(root, &fr, ""));
        let key = [
            "max x (A: backlash_um=100)",
            "min x (B: backlash_um=150; HBM, H = 5)",
            "dashed: unstable (a small disturbance grows)",
            "more in the full key under the plot",
            "solver failure: branch ends",
            "Solver failure after Ω = 1.9000",
        ];
        assert_key_outside(
            "frequency response A/B",
            &s,
            &key,
            "dimensionless mesh frequency",
            frame,
        );
        // On a phone's canvas (480 x 640): more rows, still under the chart,
        // and every line of the key within the canvas's width.
        let (s, frame) = framed((480, 640), |root| draw_fr(root, &fr, ""));
        let phone = "frequency response A/B, phone";
        assert_key_outside(phone, &s, &key, "dimensionless mesh frequency", frame);
        let t = texts(&s);
        let desc = t.iter().find(|t| t.2.contains("dimensionless")).unwrap().1;
        for (x, y, words) in t.into_iter().filter(|t| t.1 > desc) {
            // 13-pixel sans-serif: about 6.5 pixels a character on average.
            let right = x + 6.5 * words.chars().count() as f64;
            assert!(
                right <= 480.0,
                "{phone}: \"{words}\" at ({x}, {y}) ends at {right}"
            );
        }
    }
    // A family: one entry per member.
    let mut family = ab_fr();
    family.branch_error = None;
    for (m, b) in family.branches.iter_mut().enumerate() {
        b.pinned = false;
        b.member = Some(m);
        b.label = format!("TE {} µm", 10 * m);
    }
    let (s, frame) = framed((WIDTH, HEIGHT), |root| draw_fr(root, &family, ""));
    assert_key_outside(
        "family",
        &s,
        &["TE 0 µm", "TE 10 µm"],
        "dimensionless mesh frequency",
        frame,
    );
    // No regime strip under a family (even with dots), so no key for one.
    assert!(!family.overlay.is_empty() && !s.contains("regime strip"));

    let bp = |k: u32, up: bool| crate::views::bif::BifPoint {
        omega: 0.1 + 0.1 * f64::from(k),
        x_um: 100.0 + 10.0 * f64::from(k % 7),
        regime: if k.is_multiple_of(2) {
            Regime::SingleSided
        } else {
            Regime::DoubleSided
        },
        up,
    };
    let bif = crate::views::bif::BifView {
        mesh_label: "s1a1".into(),
        backlash_um: vec![100.0],
        points: (0..19).map(|k| bp(k, k % 3 != 0)).collect(),
        omega_from: 0.1,
        omega_to: 2.0,
        selected_omega: 0.84,
        failed: vec![(1.5, "the response grows without bound: x".into())],
        unstable_bands: vec![(0.4, 0.5)],
        pinned: (0..19).map(|k| bp(k, true)).collect(),
        pinned_backlash_um: vec![60.0],
        ab_labels: Some(("backlash 60 µm".into(), "backlash 100 µm".into())),
        branches: Vec::new(),
        branch_markers: Vec::new(),
        motions: Vec::new(),
        done: 19,
        total: 19,
        whole_clearance: true,
        speed: Default::default(),
    };
    let natural = [NaturalFreq {
        omega: 0.5,
        frequency_hz: 3000.0,
        kind: "rotational".into(),
        multiplicity: 1,
    }];
    let (s, frame) = framed((WIDTH, HEIGHT), |root| {
        Ok(draw_bif(root, &bif, &natural, "")?.0)
    });
    let key = [
        "A (pinned): backlash 60 µm",
        "B (current, regime colours): backlash 100 µm",
        "double-sided",
        "downward sweep",
        "parametrically unstable",
        "natural frequencies",
        "1 point(s) failed",
    ];
    assert_key_outside(
        "bifurcation A/B",
        &s,
        &key,
        "dimensionless mesh frequency",
        frame,
    );

    let lyap = crate::views::lyap::LyapStore {
        linear: false,
        points: [(0.5, -0.4), (1.0, 0.1), (1.5, 0.001)]
            .iter()
            .enumerate()
            .map(|(index, &(omega, l))| crate::protocol::LyapSample {
                index: index as u32,
                omega,
                per_period: Some(l),
                per_s: Some(l * 100.0),
                error: None,
            })
            .collect(),
        total: 3,
        periods: 100,
    };
    let (s, frame) = framed((WIDTH, 300), |root| {
        maps::draw_lyap(
            root,
            &lyap,
            (0.1, 2.0),
            &natural,
            0.84,
            &Default::default(),
            "",
        )
    });
    let key = ["λ = 0", "λ < 0: periodic", "λ > 0: chaotic", "selected Ω"];
    assert_key_outside("Lyapunov", &s, &key, "dimensionless mesh frequency", frame);

    let r = result();
    let phase = svg(|root| draw_phase_with(root, &r, "", false));
    assert_key_outside(
        "phase portrait",
        &phase,
        &["orbit over 20", "Poincaré points"],
        "x = δ − e (µm)",
        None,
    );
    let poincare = svg(|root| draw_poincare(root, &r, ""));
    assert_key_outside(
        "Poincaré section",
        &poincare,
        &["20 Poincaré points: period 1 (exact)", "±b contact"],
        "sampled once",
        None,
    );
    let (time, frame) = framed((WIDTH, HEIGHT), |root| draw_time(root, &r, ""));
    assert_key_outside(
        "time history",
        &time,
        &["x(t)", "±b contact"],
        "mesh periods since",
        frame,
    );
    let spectrum = svg(|root| draw_spectrum(root, &r, ""));
    assert_key_outside(
        "spectrum",
        &spectrum,
        &["amplitude (mean x"],
        "mesh orders",
        None,
    );
}

/// The plotting area's height of the frequency response drawn at `size`.
fn fr_plot_height(v: &FrView, size: (u32, u32)) -> f64 {
    let mut frame = None;
    svg_sized(size, |root| {
        frame = Some(draw_fr(root, v, "")?);
        Ok(())
    });
    let f = frame.unwrap();
    f.bottom_right.y - f.top_left.y
}

/// A comparison's key never squeezes its plot: the canvas grows where the
/// key would (the drawn key is at most eight entries, so it rarely does),
/// and the plot keeps the height of a single branch's; a single branch's
/// key keeps the ordinary height.
#[test]
fn a_long_key_never_squeezes_the_frequency_response() {
    let mut one = ab_fr();
    one.branches.truncate(1);
    one.branches[0].pinned = false;
    one.pinned_backlash_um.clear();
    one.branch_error = None;
    assert_eq!(fr_height(&one, (WIDTH, HEIGHT)), HEIGHT);
    let single = fr_plot_height(&one, (WIDTH, HEIGHT));
    let ab = ab_fr();
    let h = fr_height(&ab, (WIDTH, HEIGHT));
    assert!(h >= HEIGHT, "{h}");
    let kept = fr_plot_height(&ab, (WIDTH, h));
    assert!(kept >= single - 10.0, "{kept} vs {single}");
}

/// The key drawn under the frequency response has at most
/// [`KEY_MAX`] entries however much the plot holds (two branches, every
/// regime, every bifurcation kind, dots, a failure); the full key under
/// the plot keeps every entry and explains each bifurcation kind drawn.
#[test]
fn the_drawn_key_is_short_and_the_full_key_complete() {
    let mut fr = ab_fr();
    for (k, p) in fr.branches[1].points.iter_mut().enumerate() {
        p.regime = Some(Regime::ALL[k % Regime::ALL.len()]);
    }
    fr.markers = FrMarkerKind::ALL
        .iter()
        .enumerate()
        .map(|(k, &kind)| FrMarker {
            omega: 0.3 + 0.3 * k as f64,
            value_um: 100.0,
            kind,
        })
        .collect();
    let full = fr_key(&fr, (0.0, 200.0));
    assert!(
        full.len() > KEY_MAX,
        "the case needs a long key: {}",
        full.len()
    );
    let drawn = compact_key(full.clone());
    assert!(drawn.len() <= KEY_MAX, "{} entries", drawn.len());
    // The branches and the dots stay in the drawn key.
    for (icon, text) in &full {
        if matches!(icon, KeyIcon::Overlay) || text.contains("HBM") {
            assert!(drawn.iter().any(|d| &d.1 == text), "{text} dropped");
        }
    }
    let lines = fr_full_key(&fr);
    assert_eq!(lines.len(), full.len());
    for kind in FrMarkerKind::ALL {
        assert!(lines.iter().any(|l| l.contains(kind.explain())), "{kind:?}");
    }
    assert!(
        lines
            .iter()
            .any(|l| l
                .contains("period doubling: the motion starts repeating every two mesh periods"))
    );
    // A short key is drawn as it is.
    let short: KeyItems = full.into_iter().take(KEY_MAX).collect();
    let texts = |k: &KeyItems| k.iter().map(|i| i.1.clone()).collect::<Vec<_>>();
    assert_eq!(texts(&compact_key(short.clone())), texts(&short));
}

/// The frequency response's small multiples (one panel per mesh, every
/// member's curve in each) draw the ±b lines dotted and grey: no member's
/// colour, and never the dashes of an unstable branch.
#[test]
fn fr_panels_draw_their_contact_lines_dotted_and_grey() {
    let fr = |b: f64| fr_view(b, vec![]);
    let panels: Vec<Panel<FrView>> = [50.0, 100.0, 200.0]
        .iter()
        .map(|&b| Panel {
            title: format!("b {b} µm"),
            data: Ok(fr(b)),
        })
        .collect();
    let s = svg(|root| multiples::draw_fr_panels(root, &panels, "").map(|_| ()));
    for m in 0..3 {
        assert!(
            !s.contains(&hex(family_color(m))),
            "member {m}'s colour on a mesh panel without curves"
        );
    }
    assert!(s.contains(&hex(RGBColor(90, 90, 90))), "the grey ±b lines");
}

/// A finished harmonic-balance frequency response of mesh s1a1 over
/// Omega 0.1..2 with backlash `backlash_um` and these branches.
fn fr_view(backlash_um: f64, branches: Vec<FrBranch>) -> FrView {
    let source = FrSource::Hbm { harmonics: 5 };
    FrView {
        method: source.label(),
        source,
        mesh_label: "s1a1".into(),
        backlash_um: vec![backlash_um],
        pinned_backlash_um: vec![],
        branches,
        markers: vec![],
        overlay: vec![],
        overlay_source: None,
        discrepancy: crate::views::fr::Discrepancy::default(),
        natural: vec![],
        omega_from: 0.1,
        omega_to: 2.0,
        selected_omega: 0.84,
        selected_motion: None,
        branch_error: None,
        failed: vec![],
        done: 10,
        progress: 1.0,
        finished: true,
        branch_notes: Vec::new(),
        whole_clearance: true,
        speed: Default::default(),
    }
}

/// With the speed axes in rpm, the frequency response's axis names the
/// input member and its unit, its ticks are whole rpm, the key states the
/// selected speed in rpm and Ω, and the frame (what clicks map through)
/// is the same Ω as before.
#[test]
fn the_rpm_axis_relabels_the_frequency_response_and_keeps_its_frame() {
    use crate::speed::{grouped, AxisUnit, SpeedAxis};
    let m = solver::model::Model::new(&solver::params::ModelParams::default()).unwrap();
    let omega = fr_view(100.0, vec![]);
    let mut rpm = omega.clone();
    rpm.speed = SpeedAxis::new(AxisUnit::Rpm, Some(&m));
    let (a, fa) = framed((WIDTH, HEIGHT), |root| draw_fr(root, &omega, ""));
    let (b, fb) = framed((WIDTH, HEIGHT), |root| draw_fr(root, &rpm, ""));
    assert_eq!(fa, fb);
    assert!(a.contains("Ω = ω / ω_ref") && !a.contains("rpm"));
    assert!(b.contains("Sun s1 speed (rpm)") && !b.contains("ω_ref"));
    let s = rpm.speed.scale.unwrap();
    let selected = format!("selected {} rpm (Ω 0.840)", grouped(s.rpm(0.84)));
    assert!(b.contains(&selected), "no {selected}");
    // A tick at a round thousand of rpm (Ω 0.1 to 2 spans thousands).
    let thousands = (1..40)
        .filter(|k| b.lines().any(|l| l == format!("{k}\u{a0}000")))
        .count();
    assert!(thousands >= 2, "{b}");
}
