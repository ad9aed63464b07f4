//! The page core's tests: queued input applied once per frame, the
//! keyboard's Omega step, refused values, the frame's redraw decisions and
//! writes, the progress texts, and the preview marker the browser tests
//! wait for.

use super::*;
use crate::controller::Effect;
use figures::protocol::{encode, JobKind, JobSpec, ToWorker};
use worker::WorkerCore;

/// A page on `link` whose two workers said "ready"; the messages posted.
fn page(link: &str) -> (Page, Vec<Effect>) {
    let (ctl, _) = Controller::new(link, 0.0);
    let mut p = Page::new(ctl, false);
    let mut fx = p.worker_message(0, r#"{"type":"ready"}"#, 1.0);
    fx.extend(p.worker_message(1, r#"{"type":"ready"}"#, 1.0));
    (p, fx)
}

/// The jobs posted, by kind.
fn posted(fx: &[Effect], kind: JobKind) -> usize {
    fx.iter()
        .filter(|e| match e {
            Effect::Post { text, .. } => matches!(
                serde_json::from_str::<ToWorker>(text),
                Ok(ToWorker::Run { job, .. }) if job.kind() == kind
            ),
            Effect::Download { .. } => false,
        })
        .count()
}

/// Runs the selected-Omega jobs among `fx` on a worker and feeds the replies.
fn run_omega(p: &mut Page, fx: &[Effect], now_ms: f64) {
    for e in fx {
        let Effect::Post { worker, text } = e else {
            continue;
        };
        if !matches!(
            serde_json::from_str::<ToWorker>(text),
            Ok(ToWorker::Run {
                job: JobSpec::Omega(_),
                ..
            })
        ) {
            continue;
        }
        let mut core = WorkerCore::new();
        core.handle(text);
        while core.has_work() {
            for reply in core.step() {
                p.worker_message(*worker, &encode(&reply), now_ms);
            }
        }
    }
}

#[test]
fn a_drag_costs_one_restart_per_frame_and_the_latest_value_wins() {
    let (mut p, _) = page("bif_points=8");
    for v in ["110", "120", "130"] {
        p.input("backlash_um", v, 5.0);
    }
    let (fx, marks) = p.apply_pending(6.0);
    assert_eq!(posted(&fx, JobKind::HarmonicBalance), 1);
    assert!(
        p.ctl().query().contains("backlash_um=130"),
        "{}",
        p.ctl().query()
    );
    assert_eq!(
        marks,
        vec![Write::Class {
            id: "control-backlash_um".into(),
            class: "invalid",
            on: false
        }]
    );
    // Nothing queued: the next frame posts nothing.
    assert!(p.apply_pending(7.0).0.is_empty());
}

#[test]
fn a_refused_value_marks_its_control_and_replaces_its_earlier_message() {
    let (mut p, _) = page("");
    p.input("backlash_um", "5000", 1.0);
    let (_, marks) = p.apply_pending(2.0);
    assert!(matches!(&marks[..], [Write::Class { on: true, .. }]));
    p.input("backlash_um", "9000", 3.0);
    p.apply_pending(4.0);
    let about: Vec<&String> = p
        .ctl()
        .issues
        .iter()
        .filter(|i| i.contains("9000") || i.contains("5000"))
        .collect();
    assert_eq!(about.len(), 1, "{:?}", p.ctl().issues);
    assert!(about[0].contains("9000"));
    // The frame shows the message box with it.
    let (d, _) = p.begin_frame(10.0);
    let w = p.end_frame(&d);
    assert!(w.contains(&Write::Hidden {
        id: "messages".into(),
        hidden: false
    }));
}

/// An empty TE is refused (its field keeps the TE in force, red border,
/// message); a valid backlash then moves the state on: the TE's message
/// and red border go with the state they spoke of.
#[test]
fn a_refusal_goes_once_the_state_moves_on() {
    let (mut p, _) = page("");
    p.input("te_um", "", 1.0);
    let (_, marks) = p.apply_pending(2.0);
    assert!(matches!(&marks[..], [Write::Class { on: true, .. }]));
    let (d, _) = p.begin_frame(3.0);
    let w = p.end_frame(&d);
    assert!(!p.ctl().issues.is_empty());
    assert!(w.contains(&Write::Hidden {
        id: "messages".into(),
        hidden: false
    }));
    // A refusal alone changes no state: the next frame keeps it.
    let (d, _) = p.begin_frame(4.0);
    p.end_frame(&d);
    assert_eq!(p.ctl().issues.len(), 1, "{:?}", p.ctl().issues);
    p.input("backlash_um", "80", 5.0);
    p.apply_pending(6.0);
    let (d, _) = p.begin_frame(7.0);
    let w = p.end_frame(&d);
    assert!(p.ctl().issues.is_empty(), "{:?}", p.ctl().issues);
    assert!(w.contains(&Write::Class {
        id: "control-te_um".into(),
        class: "invalid",
        on: false
    }));
    assert!(w.contains(&Write::Hidden {
        id: "messages".into(),
        hidden: true
    }));
    // The TE field shows the TE in force.
    assert!(w.contains(&Write::Value {
        id: "num-te_um".into(),
        value: figures::controls::field_text(20.0)
    }));
}

#[test]
fn the_arrows_step_the_selected_omega_within_the_range() {
    let (mut p, _) = page("omega_from=0.5&omega_to=1.5&omega=1.0");
    assert!(!p.key("a", false), "other keys are not taken");
    assert!(p.key("ArrowRight", false));
    p.apply_pending(1.0);
    assert!((p.ctl().settings().view.omega - 1.01).abs() < 1e-12);
    // Two presses in one frame add up; Shift steps a tenth of the range.
    p.key("ArrowLeft", true);
    p.key("ArrowDown", false);
    p.apply_pending(2.0);
    assert!((p.ctl().settings().view.omega - 0.90).abs() < 1e-9);
    // The range's end holds.
    for _ in 0..20 {
        p.key("ArrowUp", true);
    }
    p.apply_pending(3.0);
    assert_eq!(p.ctl().settings().view.omega, 1.5);
}

#[test]
fn a_frame_draws_the_changed_views_in_order_and_writes_the_texts() {
    let (mut p, _) = page("bif_points=8");
    let (d, order) = p.begin_frame(16.0);
    assert_eq!(order, DRAW_ORDER.as_slice());
    let mut drawn = Vec::new();
    for &v in order {
        match p.decide(v, 16.0, 16.0) {
            Decision::Stop => break,
            Decision::Skip => continue,
            Decision::Draw => drawn.push(v),
        }
        p.drawn(v, (16.0, 17.0), 16.0);
    }
    assert_eq!(drawn, DRAW_ORDER.to_vec(), "a new page draws every view");
    assert!(!p.wants_frame());
    let w = p.end_frame(&d);
    assert!(w
        .iter()
        .any(|w| matches!(w, Write::Url(q) if q.contains("bif_points=8"))));
    assert!(w.contains(&Write::Text {
        id: "summary".into(),
        text: "Computing the motion at the selected speed…".into()
    }));
    // The gear set waits for a frame the views drew in.
    assert!(!p.anim_draws(16.0, false));
    assert!(p.anim_draws(32.0, false));
    // Nothing changed: the next frame draws nothing and keeps the link.
    let (d, order) = p.begin_frame(32.0);
    assert!(order.is_empty(), "the gear set drew in that frame");
    assert!(!p.end_frame(&d).iter().any(|w| matches!(w, Write::Url(_))));
}

#[test]
fn progress_shows_after_a_while_with_the_status_line() {
    let (mut p, _) = page("");
    let hidden = |hidden: bool| Write::Hidden {
        id: "progress-bif".into(),
        hidden,
    };
    let early = p.progress(100.0);
    assert!(early.contains(&hidden(true)));
    assert!(early.contains(&Write::text("status", "")));
    let later = p.progress(1000.0);
    assert!(later.contains(&hidden(false)));
    assert!(later.contains(&Write::Attr {
        id: "progress-bif-bar".into(),
        name: "style",
        value: "width:0.0%".into()
    }));
    assert!(later.contains(&Write::text("progress-bif-label", "computing 0/200 points")));
    assert!(later.contains(&Write::text("status", texts::COMPUTING)));
    // The Copy link's confirmation shows for two seconds, then goes.
    let shown = p.confirm("Link copied.", 1000.0, 5.0);
    assert!(shown.contains(&Write::Hidden {
        id: "copy-done".into(),
        hidden: false
    }));
    let gone = Write::Hidden {
        id: "copy-done".into(),
        hidden: true,
    };
    assert!(!p.progress(2990.0).contains(&gone));
    assert!(p.progress(3000.0).contains(&gone));
    assert!(!p.progress(3100.0).contains(&gone), "once");
}

#[test]
fn a_preview_drawn_leaves_its_marker_in_the_status() {
    let (mut p, fx) = page("transient_periods=40&record_periods=10&bif_points=4");
    run_omega(&mut p, &fx, 5.0);
    assert!(p.status(6.0)["preview_drawn"].is_null());
    p.input("backlash_um", "150", 10.0);
    let (fx, _) = p.apply_pending(11.0);
    p.begin_frame(16.0);
    while p.decide(ViewId::Phase, 16.0, 16.0) == Decision::Skip {
        p.begin_frame(16.0);
    }
    p.drawn(ViewId::Phase, (16.0, 18.0), 16.0);
    // The full run replaces the preview; the marker stays.
    run_omega(&mut p, &fx, 30.0);
    let s = p.status(31.0);
    assert_eq!(s["preview_drawn"]["ms"], 18.0);
    let summary = s["preview_drawn"]["summary"].as_str().unwrap();
    assert!(summary.starts_with("Preview ("), "{summary}");
    assert_eq!(s["omega_result"]["preview"], false);
    assert!(s["omega_job"]["finished_ms"].as_f64().unwrap() > 18.0);
}

#[test]
fn a_plot_failure_and_a_map_click_outside_speak_through_the_messages() {
    let (mut p, _) = page("");
    p.plot_failed("the plot failed".into());
    p.plot_failed("the plot failed".into());
    assert_eq!(p.ctl().issues, vec!["the plot failed".to_string()]);
    // No map drawn yet: a click there does nothing.
    assert!(p.map_click(10.0, 10.0, 1.0).is_empty());
}

/// The summary compares the selected Omega's state with the frequency
/// response's branch there, and either job may end last: the branch's end
/// alone (no new state) rewrites it, so its sentence is never left out.
#[test]
fn the_branch_ending_after_the_state_rewrites_the_summary() {
    let (mut p, _) = page("");
    let d = Dirty {
        jobs: KindSet::of(&[JobKind::HarmonicBalance]),
        controls: false,
        url: false,
        messages: false,
    };
    let w = p.end_frame(&d);
    assert!(
        w.iter()
            .any(|w| matches!(w, Write::Text { id, .. } if id == "summary")),
        "{w:?}"
    );
    // A job the summary does not read leaves it alone.
    let d = Dirty {
        jobs: KindSet::of(&[JobKind::Bif]),
        ..d
    };
    assert!(!p
        .end_frame(&d)
        .iter()
        .any(|w| matches!(w, Write::Text { id, .. } if id == "summary")));
}
