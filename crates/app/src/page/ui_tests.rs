//! The page core's tests of what it decides for the web layer: a touch's
//! gesture (tap, scrub, swipe, cancel), the built elements and their
//! accessible names, the actions' writes (tour, controls, family, exports),
//! the animation under reduced motion, and a view drawn on SVG.

use super::dom::{built, Action, TourMove, WIRING};
use super::*;
use figures::plots::PlotFrame;
use glam::DVec2;

fn page(link: &str) -> Page {
    let (ctl, _) = Controller::new(link, 0.0);
    Page::new(ctl, true)
}

/// A frame mapping pixels 100 ..= 500 to Omega 0.5 ..= 1.5.
fn frame() -> PlotFrame {
    PlotFrame {
        top_left: DVec2::new(100.0, 20.0),
        bottom_right: DVec2::new(500.0, 380.0),
        x_range: (0.5, 1.5),
        y_range: (-1.0, 1.0),
    }
}

fn touch(phase: Phase, x: f64, y: f64) -> PointerIn {
    PointerIn::new(phase, x, (x, y), "touch")
}

fn picked(p: &mut Page) -> f64 {
    p.apply_pending(1.0);
    p.ctl().settings().view.omega
}

#[test]
fn a_vertical_swipe_scrolls_and_never_selects() {
    let mut p = page("omega=0.84");
    p.set_frame(ViewId::Fr, Some(frame()));
    assert!(!p.pointer(ViewId::Fr, touch(Phase::Down, 300.0, 200.0)));
    // Down the page, a little sideways: a swipe.
    assert!(!p.pointer(ViewId::Fr, touch(Phase::Move, 303.0, 185.0)));
    assert!(!p.pointer(ViewId::Fr, touch(Phase::Move, 340.0, 60.0)));
    assert!(!p.pointer(ViewId::Fr, touch(Phase::Up, 340.0, 60.0)));
    assert_eq!(picked(&mut p), 0.84);
    assert_eq!(
        (p.telemetry.gestures_ended, p.telemetry.last_gesture),
        (1, "scroll")
    );
    // The browser took the touch to scroll: a cancel, then nothing.
    p.pointer(ViewId::Fr, touch(Phase::Down, 300.0, 200.0));
    assert!(!p.pointer(ViewId::Fr, touch(Phase::Cancel, 300.0, 200.0)));
    assert!(!p.pointer(ViewId::Fr, touch(Phase::Up, 300.0, 200.0)));
    assert_eq!(picked(&mut p), 0.84);
    assert_eq!(
        (p.telemetry.gestures_ended, p.telemetry.last_gesture),
        (2, "cancel")
    );
}

#[test]
fn a_tap_selects_where_it_lifts_and_a_drag_along_the_axis_scrubs() {
    let mut p = page("omega=0.84");
    p.set_frame(ViewId::Fr, Some(frame()));
    // A tap with a tremble under the slop.
    p.pointer(ViewId::Fr, touch(Phase::Down, 300.0, 200.0));
    assert!(!p.pointer(ViewId::Fr, touch(Phase::Move, 304.0, 203.0)));
    assert!(p.pointer(ViewId::Fr, touch(Phase::Up, 304.0, 203.0)));
    assert!((picked(&mut p) - 1.01).abs() < 1e-9);
    // A drag along the axis selects at every move once past the slop.
    p.pointer(ViewId::Fr, touch(Phase::Down, 100.0, 200.0));
    assert!(p.pointer(ViewId::Fr, touch(Phase::Move, 140.0, 205.0)));
    assert!((picked(&mut p) - 0.6).abs() < 1e-9);
    assert!(p.pointer(ViewId::Fr, touch(Phase::Move, 180.0, 260.0)));
    assert!((picked(&mut p) - 0.7).abs() < 1e-9);
    assert!(!p.pointer(ViewId::Fr, touch(Phase::Up, 180.0, 260.0)));
    // On a phone the selection offers the jump to the motion.
    let (d, _) = p.begin_frame(5.0);
    p.end_frame(&d);
    assert!(p.notices.see_orbit);
    // A mouse selects at its press.
    let mouse = PointerIn::new(Phase::Down, 500.0, (500.0, 0.0), "mouse");
    assert!(p.pointer(ViewId::Fr, mouse));
    assert_eq!(picked(&mut p), 1.5);
}

#[test]
fn every_button_names_its_visible_text_and_every_control_is_labelled() {
    let all = built();
    let nodes: Vec<&Node> = all
        .iter()
        .flat_map(|(_, n)| n)
        .flat_map(|n| n.walk())
        .collect();
    let buttons: Vec<&&Node> = nodes.iter().filter(|n| n.tag == "button").collect();
    // Five views' four exports, the CLI's two, the parameters, the claims.
    assert!(buttons.len() > 40, "{}", buttons.len());
    for b in buttons {
        let text = b.text.as_deref().unwrap_or("");
        assert!(!text.is_empty());
        if let Some(name) = b.get("aria-label") {
            assert!(name.starts_with(text), "{name} does not contain {text}");
        }
        assert_eq!(b.on.len(), 1, "{text} does nothing");
    }
    for label in nodes.iter().filter(|n| n.tag == "label") {
        let id = label.get("for").unwrap_or("");
        assert!(
            nodes.iter().any(|n| n.get("id") == Some(id)),
            "a label for {id}, which is not built"
        );
    }
    // Every view has every export, each once.
    for v in ViewId::ALL {
        let bar = &all
            .iter()
            .find(|(id, _)| *id == format!("exports-{}", v.key()))
            .expect("a bar")
            .1;
        assert!(bar.iter().any(|b| b.on == vec![("click", Action::Png(v))]));
        assert!(bar.iter().any(|b| b.on == vec![("click", Action::Svg(v))]));
    }
    // The fixed elements' ids are unique listeners.
    for (i, (id, ev, _)) in WIRING.iter().enumerate() {
        assert!(!WIRING[..i].iter().any(|(j, e, _)| j == id && e == ev));
    }
}

#[test]
fn a_slider_mirrors_its_field_and_a_reset_rewrites_every_control() {
    let mut p = page("");
    let ev = EventIn {
        value: "73".into(),
        key: None,
    };
    let out = p.act(Action::Slide("backlash_um"), &ev, 1.0);
    assert!(out.writes.contains(&Write::Value {
        id: "num-backlash_um".into(),
        value: "73".into()
    }));
    p.apply_pending(2.0);
    let w = p.control_writes();
    assert!(w.contains(&Write::Value {
        id: "slider-backlash_um".into(),
        value: "73".into()
    }));
    p.act(Action::Reset, &EventIn::default(), 3.0);
    assert!(p.control_writes().contains(&Write::Value {
        id: "num-backlash_um".into(),
        value: "100".into()
    }));
}

#[test]
fn the_tour_buttons_step_and_highlight_one_target() {
    let mut p = page("");
    let out = p.act(Action::Tour(TourMove::Start), &EventIn::default(), 1.0);
    let on: Vec<&Write> = out
        .writes
        .iter()
        .filter(|w| matches!(w, Write::Class { on: true, .. }))
        .collect();
    assert_eq!(on.len(), 1);
    assert!(out
        .writes
        .contains(&Write::Scroll(crate::tour::TOUR[0].target.into())));
    p.act(Action::Tour(TourMove::Next), &EventIn::default(), 2.0);
    assert_eq!(p.ctl().tour(), Some(1));
    let out = p.act(Action::Tour(TourMove::Skip), &EventIn::default(), 3.0);
    assert!(out.writes.contains(&Write::Hidden {
        id: "tour".into(),
        hidden: true
    }));
}

#[test]
fn a_bad_family_is_refused_in_its_bar_and_an_export_not_ready_says_why() {
    let mut p = page("");
    let ev = |v: &str| EventIn {
        value: v.into(),
        key: None,
    };
    p.act(Action::FamilyKey, &ev("backlash_um"), 1.0);
    p.act(Action::FamilyValues, &ev("10"), 1.0);
    let out = p.act(Action::FamilyApply, &EventIn::default(), 2.0);
    assert!(out.writes.iter().any(
        |w| matches!(w, Write::Text { id, text } if id == "family-error" && text.contains("2 to 6"))
    ));
    // A key other than Enter in the field does not apply it.
    let typing = EventIn {
        value: String::new(),
        key: Some("a".into()),
    };
    assert!(p.act(Action::FamilyApply, &typing, 3.0).writes.is_empty());
    // The motion has not arrived: the CLI JSON says so in the messages.
    let out = p.act(Action::Cli(ViewId::Phase), &EventIn::default(), 4.0);
    assert!(out.effects.is_empty());
    assert!(p.ctl().issues.iter().any(|i| i.contains("still computing")));
}

#[test]
fn reduced_motion_starts_the_animation_paused() {
    let mut p = page("");
    assert!(p.anim.clock.playing);
    p.prefer_still();
    assert!(!p.anim.clock.playing);
    // Before any motion the first tick draws the message, once.
    assert_eq!(p.anim_tick(0.0), AnimDraw::Placeholder);
    assert_eq!(p.anim_tick(16.0), AnimDraw::Nothing);
    p.act(Action::AnimPlay, &EventIn::default(), 20.0);
    assert!(p.anim.clock.playing);
}

#[test]
fn a_view_draws_on_svg_with_its_text_alternative_and_frame() {
    let mut p = page("");
    for v in [ViewId::Fr, ViewId::Map, ViewId::Lyap, ViewId::Bif] {
        let (fr, size) = p.prepare(v);
        let mut s = String::new();
        let writes = {
            let root = plotters::prelude::SVGBackend::with_string(&mut s, size);
            let root = plotters::prelude::IntoDrawingArea::into_drawing_area(root);
            p.draw_view(v, &root, fr.as_ref()).0
        };
        assert!(s.contains(v.spec().title), "{}", v.key());
        assert!(writes.iter().any(|w| matches!(w,
            Write::Attr { id, name: "aria-label", .. } if *id == format!("canvas-{}", v.key()))));
    }
    // The frequency response and the map map clicks as soon as they draw.
    assert!(p.frame(ViewId::Fr).is_some() && p.frame(ViewId::Map).is_some());
}

/// The PNG export rasterizes the SVG picture: a file with anything after
/// its end does not load (the regime map's cells and cursor were drawn
/// after plotters had closed it).
#[test]
fn every_views_svg_is_one_closed_picture() {
    let p = page("");
    for v in ViewId::ALL {
        let Ok(svg) = p.ctl().plot_svg(v) else {
            continue;
        };
        assert_eq!(svg.matches("</svg>").count(), 1, "{}", v.key());
        assert!(svg.trim_end().ends_with("</svg>"), "{}", v.key());
    }
    let map = p.ctl().plot_svg(ViewId::Map).expect("the map draws");
    // Its cursor lines are inside.
    assert!(map.contains("<polyline") || map.contains("<path"), "{map}");
}

#[test]
fn a_tour_steps_action_shows_done_once_the_student_does_it() {
    let mut p = page("");
    p.act(Action::Tour(TourMove::Start), &EventIn::default(), 1.0);
    p.act(Action::Tour(TourMove::Next), &EventIn::default(), 2.0);
    p.apply_pending(3.0);
    // Step 2 sets the backlash to 150 µm and asks for 50 µm: not done yet.
    assert_eq!(p.tour_done(), Some(false));
    let hidden = |w: &[Write], h: bool| {
        w.contains(&Write::Hidden {
            id: "tour-done".into(),
            hidden: h,
        })
    };
    assert!(hidden(&p.tour_writes(false), true));
    let ev = EventIn {
        value: "50".into(),
        key: None,
    };
    p.act(Action::Slide("backlash_um"), &ev, 4.0);
    p.apply_pending(5.0);
    assert_eq!(p.tour_done(), Some(true));
    let w = p.tour_writes(false);
    assert!(hidden(&w, false));
    assert!(w.contains(&Write::Class {
        id: "tour-next".into(),
        class: "ready",
        on: true
    }));
    assert_eq!(p.status(6.0)["tour"]["done"], serde_json::json!(true));
    // A new step starts not done; the last one is done by copying the link.
    for t in 7..10 {
        p.act(
            Action::Tour(TourMove::Next),
            &EventIn::default(),
            f64::from(t),
        );
    }
    assert_eq!(p.tour_done(), Some(false));
    p.act(Action::CopyLink, &EventIn::default(), 11.0);
    assert_eq!(p.tour_done(), Some(true));
}

/// Each tour step's card is placed clear of its target's picture (a
/// view's canvas, not its section, whose text runs below the plot) and of
/// the control it names (docked at a phone's foot here). A new step
/// places it after scrolling to the target; every frame of the tour places it again, as its plot grows;
/// with the tour over, nothing is placed.
#[test]
fn the_tour_card_leaves_each_steps_picture_and_control_in_view_each_frame() {
    let html = include_str!("../../../../index.html");
    let mut p = page("");
    let mut out = p.act(Action::Tour(TourMove::Start), &EventIn::default(), 1.0);
    for (i, s) in crate::tour::TOUR.iter().enumerate() {
        let at = out
            .writes
            .iter()
            .position(|w| w == &Write::Scroll(s.target.into()));
        let Some(Write::PlaceCard {
            id,
            keep_clear,
            prefer_clear,
            docked: true,
            new_step: true,
        }) = at.and_then(|at| out.writes.get(at + 1))
        else {
            panic!(
                "step {i}: no card placed after the scroll: {:?}",
                out.writes
            );
        };
        assert_eq!(id, "tour");
        assert!(html.contains(&format!("id=\"{id}\"")));
        let first = keep_clear.first().cloned().unwrap_or_default();
        let canvas = s.target.starts_with("view-");
        assert_eq!(first.starts_with("canvas-"), canvas, "{first}");
        if canvas {
            assert!(first.ends_with(s.target.trim_start_matches("view-")));
        }
        if let Some(c) = s.control {
            assert!(
                keep_clear.contains(&format!("control-{c}")),
                "{keep_clear:?}"
            );
        }
        assert_eq!(prefer_clear.first(), Some(&s.target.to_string()));
        assert!(html.contains("id=\"views\""));
        let frame = p.draw_frame(16.0 * (i + 1) as f64, || 0.0, |_, _| Vec::new());
        assert_eq!(
            frame.last(),
            Some(&Write::PlaceCard {
                id: id.clone(),
                keep_clear: keep_clear.clone(),
                prefer_clear: prefer_clear.clone(),
                docked: true,
                new_step: false
            })
        );
        out = p.act(Action::Tour(TourMove::Next), &EventIn::default(), 2.0);
    }
    assert_eq!(p.ctl().tour(), None);
    let frame = p.draw_frame(1000.0, || 0.0, |_, _| Vec::new());
    assert!(!frame.iter().any(|w| matches!(w, Write::PlaceCard { .. })));
}

/// A preset without a family empties the family bar's values: the bar
/// never shows a family the plots do not draw.
#[test]
fn a_preset_without_a_family_empties_the_family_bar() {
    let mut p = page("");
    let ev = |v: &str| EventIn {
        value: v.into(),
        key: None,
    };
    let values = |p: &mut Page, preset: &str, at: f64| {
        p.act(Action::Preset, &ev(preset), at);
        let d = p.ctl.take_dirty();
        p.end_frame(&d).into_iter().find_map(|w| match w {
            Write::Value { id, value } if id == "family-values" => Some(value),
            _ => None,
        })
    };
    assert_eq!(
        values(&mut p, "fig2", 1.0).as_deref(),
        Some("5, 10, 15, 20, 25, 30")
    );
    assert_eq!(values(&mut p, "pair", 2.0).as_deref(), Some(""));
    assert!(p.ctl().family().is_none());
    // Once emptied, the bar is left alone.
    assert_eq!(values(&mut p, "table1", 3.0), None);
}

/// On a phone the settings drawer starts closed, far above the plots: a
/// step whose action uses a control opens the drawer, the card is docked
/// at the screen's foot and offers a jump to the control and back.
#[test]
fn on_a_phone_the_tour_opens_the_drawer_and_jumps_to_the_control() {
    let (ctl, _) = Controller::new("", 0.0);
    let mut p = Page::new(ctl, true);
    let out = p.act(Action::Tour(TourMove::Start), &EventIn::default(), 1.0);
    let open = Write::Flag {
        id: "drawer".into(),
        name: "open",
        on: true,
    };
    assert!(out.writes.contains(&open), "{:?}", out.writes);
    assert!(out.writes.contains(&Write::Hidden {
        id: "tour-control".into(),
        hidden: false
    }));
    assert!(out
        .writes
        .contains(&Write::text("tour-control", "Show “Mesh to plot” ↑")));
    assert!(out.writes.iter().any(|w| matches!(
        w,
        Write::PlaceCard {
            docked: true,
            new_step: true,
            ..
        }
    )));
    let jump = p.act(Action::Tour(TourMove::ToControl), &EventIn::default(), 2.0);
    // The card is marked at the control, so that a layout shift under it
    // does not scroll the control away; back at the target, unmarked.
    let at = |on: bool| Write::Flag {
        id: "tour".into(),
        name: "data-at-control",
        on,
    };
    assert_eq!(
        jump.writes,
        vec![open, at(true), Write::Scroll("control-mesh".into())]
    );
    let back = p.act(Action::Tour(TourMove::ToTarget), &EventIn::default(), 3.0);
    assert_eq!(
        back.writes[..2],
        [at(false), Write::Scroll("schematic".into())]
    );
    // Step 3 uses no control: no jump offered.
    for t in [4.0, 5.0] {
        p.act(Action::Tour(TourMove::Next), &EventIn::default(), t);
    }
    assert!(p.tour_writes(false).contains(&Write::Hidden {
        id: "tour-control".into(),
        hidden: true
    }));
}
