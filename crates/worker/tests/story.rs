//! The story told of a steady state the worker computes: the Fig. 2
//! preset's linear case, run as the page runs it, and every sentence the
//! page shows about it (the classification's own tests, on synthetic
//! results, are in `figures::story`).

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use figures::protocol::{Motion, OmegaResult, RunOptions};
use figures::views::bif::{BifPoint, BifStore};
use figures::views::ViewContext;
use worker::jobs::omega::{omega_result, selected_spec, OmegaJob};

/// Every text the page shows about one steady state: the expert summary,
/// the student summary, the selected-Omega views' text alternative, the
/// Poincaré key, a family panel's title and the bifurcation diagram's
/// text alternative.
fn texts(r: &OmegaResult) -> Vec<String> {
    let ctx = ViewContext {
        omega_from: 0.1,
        omega_to: 2.0,
        selected_omega: 0.5,
        mesh_label: "s1a1".into(),
        natural: vec![],
        speed: Default::default(),
    };
    let mut bif = BifStore::new(1).view(Some(0), &[r.backlash_um], &ctx);
    bif.points.push(BifPoint {
        omega: r.omega,
        x_um: 1.0,
        regime: r.regime,
        up: true,
    });
    bif.motions.push((r.omega, true, r.motion));
    vec![
        figures::views::omega::summary_line(r, &[]),
        figures::views::omega::student_summary(r),
        figures::views::labels::omega_label("Phase portrait", r),
        figures::plots::poincare_key(r),
        format!("TE 5 µm: {}", figures::story::motion_tag_short(r.motion)),
        figures::views::labels::bif_label(&bif),
    ]
}

/// A linear case: the Fig. 2 preset's first member (no backlash,
/// TE 5 µm on every mesh, the page's Ω 0.84 and periods) is linear, so its
/// steady state is period 1, found exactly; the summary says so and says
/// nothing of impacts.
#[test]
fn the_fig2_preset_at_the_page_defaults_is_period_1_exact() {
    let preset = figures::presets::preset("fig2").expect("the Fig. 2 preset");
    let d = figures::link::decode(&preset.query());
    let model = solver::model::Model::new(&d.settings.params).expect("model");
    let v = &d.settings.view;
    let run = RunOptions {
        transient_periods: v.transient_periods,
        record_periods: v.record_periods,
    };
    let spec = selected_spec(&d.settings, &model, run);
    let job = OmegaJob { id: 1, model, spec };
    let r = omega_result(&job, None).expect("the steady state");
    assert_eq!(r.backlash_um, 0.0);
    assert!(
        matches!(r.motion, Motion::PeriodicExact { period: 1, .. }),
        "{:?}",
        r.motion
    );
    // The Poincaré samples of an exact period-1 orbit coincide.
    let spread = r
        .poincare_x_um
        .iter()
        .fold(0.0_f64, |m, x| m.max((x - r.poincare_x_um[0]).abs()));
    assert!(spread < 1e-3, "Poincaré samples spread over {spread} µm");
    for t in texts(&r) {
        assert!(t.contains("period 1"), "{t}");
    }
    let s = figures::views::omega::student_summary(&r);
    assert!(
        s.contains("no backlash") && s.contains("repeats exactly every mesh period"),
        "{s}"
    );
}
